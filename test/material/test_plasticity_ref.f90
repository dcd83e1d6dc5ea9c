!> Reference solutions for the J2 plasticity tests, computed independently of the kernels of
!> src/exic/material/j2.f90 (doc/plasticity.md, section 6):
!>
!> - `ref_step`: the discrete algorithm of doc/plasticity.md section 5 written differently, in
!>   quadruple precision: principal values of the trial b_e, the return (J21) and the
!>   spherical part (det b_e = J^2 as a product of principal values) by bisection, the
!>   dissipation from the principal values, b_e rebuilt from them;
!> - `uniaxial_strain_pp`, `uniaxial_stress_pp`: the closed forms (J28), (J29) of perfect
!>   plasticity on uniaxial paths;
!> - `ref_ode`: the continuous model (J11)-(J13) integrated by the classical Runge-Kutta method.
!>
!> The hardening laws are written out again here (`law_q`, `law_slope`) rather than taken from
!> the kernel's module.
module test_plasticity_ref
   use exic_base_kinds, only: wp
   use exic_material_j2_hardening, only: j2_param_t, J2_MISES, J2_POWER, J2_JOHNSON_COOK
   use, intrinsic :: iso_fortran_env, only: real128
   implicit none
   private

   !> Quadruple precision of the discrete reference.
   integer, parameter, public :: qp = real128

   !> Deformation paths F(t): simple shear [1 t; 0 1]; isochoric extension along y with the
   !> lateral stretch in x and in the hoop direction, diag(s, 1 + t, s) with s = (1 + t)^(-1/2)
   !> (F33 /= 1, the axisymmetric kernel); uniaxial strain diag(1 + t, 1, 1).
   integer, parameter, public :: PATH_SHEAR = 1, PATH_EXTENSION = 2, PATH_UNIAXIAL_STRAIN = 3

   public :: ref_t, ref_step, path_f, path_l, uniaxial_strain_pp, uniaxial_stress_pp
   public :: ref_ode, yield_onset, law_q

   !> One material point of the quad-precision reference: history and the outputs of its last
   !> step (P: 11, 12, 21, 22, 33).
   type :: ref_t
      real(qp) :: a11 = 1.0_qp, a12 = 0.0_qp, a22 = 1.0_qp, a33 = 1.0_qp
      real(qp) :: ep = 0.0_qp, temp = 0.0_qp
      real(qp) :: p(5) = 0.0_qp, we = 0.0_qp, dwp = 0.0_qp, ys = 0.0_qp
   end type ref_t

contains

   !> Yield stress Y(ep, dep/dt, T) of (J14)-(J16) in quadruple precision.
   pure function law_q(prm, ep, dep, dt, temp) result(y)
      type(j2_param_t), intent(in) :: prm
      real(qp), intent(in) :: ep, dep, dt, temp
      real(qp) :: y, rate, ts
      select case (prm%law)
      case (J2_MISES)
         y = prm%y0 + (prm%yinf - prm%y0)*(1.0_qp - exp(-real(prm%beta, qp)*ep)) + prm%hiso*ep
      case (J2_POWER, J2_JOHNSON_COOK)
         y = prm%a
         if (ep > 0.0_qp) y = y + prm%b*ep**real(prm%en, qp)
         if (prm%law == J2_JOHNSON_COOK) then
            rate = 1.0_qp
            if (dt > 0.0_qp) rate = max(dep/(dt*prm%epsdot0), 1.0_qp)
            ts = min(max((temp - prm%troom)/real(prm%tmelt - prm%troom, qp), 0.0_qp), 1.0_qp)
            y = y*(1.0_qp + prm%crate*log(rate))*(1.0_qp - ts**real(prm%m, qp))
         end if
      case default
         y = huge(1.0_qp)
      end select
   end function law_q

   !> Slope dY/dep of a rate-independent law (for the continuous model).
   pure real(wp) function law_slope(prm, ep) result(h)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep
      select case (prm%law)
      case (J2_MISES)
         h = prm%beta*(prm%yinf - prm%y0)*exp(-prm%beta*ep) + prm%hiso
      case (J2_POWER)
         h = prm%en*prm%b*ep**(prm%en - 1.0_wp)
      case default
         h = 0.0_wp
      end select
   end function law_slope

   !> One step of the discrete algorithm at F = f (11, 12, 21, 22, 33), in quad precision.
   pure subroutine ref_step(lam, mu, prm, dt, f, r)
      real(wp), intent(in) :: lam, mu, dt, f(5)
      type(j2_param_t), intent(in) :: prm
      type(ref_t), intent(inout) :: r
      real(qp) :: fm(2, 2), fi(2, 2), am(2, 2), bm(2, 2), tau(2, 2), f33, j, jac, lq, mq
      real(qp) :: mid, hd, rr, l(3), x, dv(3), qtr, yn, lo, hi, z, k, y, be(3), c2, s2, bmn, brd
      real(qp) :: b33, dq
      integer :: it

      lq = real(lam, qp)
      mq = real(mu, qp)
      dq = real(dt, qp)
      fm = reshape(real([f(1), f(3), f(2), f(4)], qp), [2, 2])
      f33 = real(f(5), qp)
      j = fm(1, 1)*fm(2, 2) - fm(1, 2)*fm(2, 1)
      jac = j*f33
      fi = reshape([fm(2, 2), -fm(2, 1), -fm(1, 2), fm(1, 1)], [2, 2])/j
      am = reshape([r%a11, r%a12, r%a12, r%a22], [2, 2])
      bm = matmul(matmul(fm, am), transpose(fm))
      b33 = f33*f33*r%a33
      ! principal values
      mid = 0.5_qp*(bm(1, 1) + bm(2, 2))
      hd = 0.5_qp*(bm(1, 1) - bm(2, 2))
      rr = sqrt(hd*hd + bm(1, 2)**2)
      l = [mid + rr, mid - rr, b33]
      x = sum(l)/3.0_qp
      dv = l - x
      qtr = sqrt(1.5_qp)*mq*sqrt(sum(dv*dv))
      yn = law_q(prm, r%ep, 0.0_qp, dq, r%temp)
      r%dwp = 0.0_qp
      r%ys = yn
      if (qtr > yn) then
         ! (J21) by bisection
         lo = 0.0_qp
         hi = (qtr - yn)/(3.0_qp*mq*x)
         do it = 1, 400
            z = 0.5_qp*(lo + hi)
            if (qtr - 3.0_qp*mq*x*z - law_q(prm, r%ep + z, z, dq, r%temp) > 0.0_qp) then
               lo = z
            else
               hi = z
            end if
            if (hi - lo <= 1.0e-33_qp*hi) exit
         end do
         z = 0.5_qp*(lo + hi)
         k = 1.0_qp - 3.0_qp*mq*x*z/qtr
         ! det b_e = J^2: product of the principal values, by bisection
         lo = maxval(-k*dv)
         hi = x + 1.0_qp
         do it = 1, 400
            y = 0.5_qp*(lo + hi)
            if (product(k*dv + y) > jac*jac) then
               hi = y
            else
               lo = y
            end if
            if (hi - lo <= 1.0e-33_qp*hi) exit
         end do
         y = 0.5_qp*(lo + hi)
         be = k*dv + y
         ! dissipation -mu dgamma tr(b_e) tr(b_e^-1 n)/tr(b_e^-1) in principal values (J27)
         r%dwp = -mq*sqrt(1.5_qp)*z*sum(be)*sum(dv/be)/sqrt(sum(dv*dv))/sum(1.0_qp/be)
         r%ys = law_q(prm, r%ep + z, z, dq, r%temp)
         r%ep = r%ep + z
         if (prm%cheat > 0.0_wp) r%temp = r%temp + prm%chi*r%dwp/(real(prm%rho, qp)*prm%cheat)
         ! rebuild b_e on the trial eigenvectors
         if (rr > 0.0_qp) then
            c2 = hd/rr
            s2 = bm(1, 2)/rr
         else
            c2 = 1.0_qp
            s2 = 0.0_qp
         end if
         bmn = 0.5_qp*(be(1) + be(2))
         brd = 0.5_qp*(be(1) - be(2))
         bm = reshape([bmn + brd*c2, brd*s2, brd*s2, bmn - brd*c2], [2, 2])
         b33 = be(3)
         am = matmul(matmul(fi, bm), transpose(fi))
         r%a11 = am(1, 1)
         r%a12 = 0.5_qp*(am(1, 2) + am(2, 1))
         r%a22 = am(2, 2)
         r%a33 = b33/(f33*f33)
      end if
      ! P = tau F^-T, W (J5, J6)
      tau = mq*bm
      tau(1, 1) = tau(1, 1) + lq*log(jac) - mq
      tau(2, 2) = tau(2, 2) + lq*log(jac) - mq
      tau = matmul(tau, transpose(fi))
      r%p = [tau(1, 1), tau(1, 2), tau(2, 1), tau(2, 2), (lq*log(jac) + mq*(b33 - 1.0_qp))/f33]
      r%we = 0.5_qp*lq*log(jac)**2 - mq*log(jac) + 0.5_qp*mq*(bm(1, 1) + bm(2, 2) + b33 - 3.0_qp)
   end subroutine ref_step

   !> F(t) of a path: f = (F11, F12, F21, F22, F33).
   pure subroutine path_f(path, t, f)
      integer, intent(in) :: path
      real(wp), intent(in) :: t
      real(wp), intent(out) :: f(5)
      real(wp) :: s
      select case (path)
      case (PATH_SHEAR)
         f = [1.0_wp, t, 0.0_wp, 1.0_wp, 1.0_wp]
      case (PATH_EXTENSION)
         s = 1.0_wp/sqrt(1.0_wp + t)
         f = [s, 0.0_wp, 0.0_wp, 1.0_wp + t, s]
      case default
         f = [1.0_wp + t, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp]
      end select
   end subroutine path_f

   !> Velocity gradient l = Fdot F^-1 of a path at t: (l11, l12, l21, l22, l33).
   pure subroutine path_l(path, t, l)
      integer, intent(in) :: path
      real(wp), intent(in) :: t
      real(wp), intent(out) :: l(5)
      select case (path)
      case (PATH_SHEAR)
         l = [0.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
      case (PATH_EXTENSION)
         l = [-0.5_wp, 0.0_wp, 0.0_wp, 1.0_wp, -0.5_wp]/(1.0_wp + t)
      case default
         l = [1.0_wp/(1.0_wp + t), 0.0_wp, 0.0_wp, 0.0_wp, 0.0_wp]
      end select
   end subroutine path_l

   !> Von Mises Kirchhoff stress of the purely elastic state b = F F^T at time t of a path.
   pure real(wp) function elastic_q(mu, path, t) result(q)
      real(wp), intent(in) :: mu, t
      integer, intent(in) :: path
      real(wp) :: f(5), b11, b12, b22, b33, x
      call path_f(path, t, f)
      b11 = f(1)**2 + f(2)**2
      b22 = f(3)**2 + f(4)**2
      b12 = f(1)*f(3) + f(2)*f(4)
      b33 = f(5)**2
      x = (b11 + b22 + b33)/3.0_wp
      q = sqrt(1.5_wp)*mu*sqrt((b11 - x)**2 + (b22 - x)**2 + (b33 - x)**2 + 2.0_wp*b12**2)
   end function elastic_q

   !> Time of first yield on a path (q(F F^T) = y0, by bisection on [0, tmax]).
   pure real(wp) function yield_onset(mu, y0, path, tmax) result(ty)
      real(wp), intent(in) :: mu, y0, tmax
      integer, intent(in) :: path
      real(wp) :: lo, hi
      integer :: it
      lo = 0.0_wp
      hi = tmax
      do it = 1, 200
         ty = 0.5_wp*(lo + hi)
         if (elastic_q(mu, path, ty) > y0) then
            hi = ty
         else
            lo = ty
         end if
      end do
      ty = 0.5_wp*(lo + hi)
   end function yield_onset

   !> Uniaxial strain F = diag(lam1, 1, 1), perfect plasticity after yield (J28):
   !> b_e = diag(b1, b2, b2) with b1 - b2 = s y/mu, b1 b2^2 = lam1^2 (Newton on b2).
   pure subroutine uniaxial_strain_pp(mu, y, lam1, b1, b2)
      real(wp), intent(in) :: mu, y, lam1
      real(wp), intent(out) :: b1, b2
      real(wp) :: a, db
      integer :: it
      a = sign(y/mu, lam1 - 1.0_wp)
      b2 = lam1**(2.0_wp/3.0_wp)
      do it = 1, 100
         db = ((b2 + a)*b2*b2 - lam1*lam1)/(3.0_wp*b2*b2 + 2.0_wp*a*b2)
         b2 = b2 - db
         if (abs(db) <= 1.0e-16_wp*b2) exit
      end do
      b1 = b2 + a
   end subroutine uniaxial_strain_pp

   !> Uniaxial stress, perfect plasticity after yield (J29): the constant elastic state
   !> (J, b_z, b_t) with b_z - b_t = s y/mu, b_z b_t^2 = J^2, lambda ln J + mu (b_t - 1) = 0
   !> (Newton on ln J). s = +1 in tension, -1 in compression.
   pure subroutine uniaxial_stress_pp(lam, mu, y, s, jac, bz, bt)
      real(wp), intent(in) :: lam, mu, y, s
      real(wp), intent(out) :: jac, bz, bt
      real(wp) :: lj, phi, dphi, d
      integer :: it
      lj = 0.0_wp
      do it = 1, 100
         bt = 1.0_wp - lam/mu*lj
         bz = bt + s*y/mu
         phi = bz*bt*bt - exp(2.0_wp*lj)
         dphi = -lam/mu*(bt*bt + 2.0_wp*bz*bt) - 2.0_wp*exp(2.0_wp*lj)
         d = phi/dphi
         lj = lj - d
         if (abs(d) <= 1.0e-17_wp) exit
      end do
      jac = exp(lj)
      bt = 1.0_wp - lam/mu*lj
      bz = bt + s*y/mu
   end subroutine uniaxial_stress_pp

   !> Right-hand side of the continuous model (J11)-(J13) in plastic loading:
   !> y = (b11, b12, b22, b33, ep). ok is false if the path unloads (gammadot <= 0).
   pure subroutine ode_rhs(mu, prm, path, t, y, dy, ok)
      real(wp), intent(in) :: mu, t, y(5)
      type(j2_param_t), intent(in) :: prm
      integer, intent(in) :: path
      real(wp), intent(out) :: dy(5)
      logical, intent(inout) :: ok
      real(wp) :: l(5), m11, m12, m22, m33, ie, x, n11, n12, n22, n33, nn, gd, det2, i11, i12, i22
      real(wp) :: i33, alpha
      call path_l(path, t, l)
      ! M = l b + b l^T
      m11 = 2.0_wp*(l(1)*y(1) + l(2)*y(2))
      m22 = 2.0_wp*(l(3)*y(2) + l(4)*y(3))
      m12 = l(1)*y(2) + l(2)*y(3) + y(1)*l(3) + y(2)*l(4)
      m33 = 2.0_wp*l(5)*y(4)
      ie = y(1) + y(3) + y(4)
      x = ie/3.0_wp
      n11 = y(1) - x
      n22 = y(3) - x
      n33 = y(4) - x
      n12 = y(2)
      nn = sqrt(n11*n11 + n22*n22 + n33*n33 + 2.0_wp*n12*n12)
      n11 = n11/nn
      n22 = n22/nn
      n33 = n33/nn
      n12 = n12/nn
      gd = mu*(n11*m11 + n22*m22 + n33*m33 + 2.0_wp*n12*m12) &
           /(2.0_wp/3.0_wp*(mu*ie + law_slope(prm, y(5))))
      if (.not. (gd > 0.0_wp)) ok = .false.
      det2 = y(1)*y(3) - y(2)*y(2)
      i11 = y(3)/det2
      i22 = y(1)/det2
      i12 = -y(2)/det2
      i33 = 1.0_wp/y(4)
      alpha = 2.0_wp/3.0_wp*gd*ie*(i11*n11 + i22*n22 + 2.0_wp*i12*n12 + i33*n33)/(i11 + i22 + i33)
      dy(1) = m11 - 2.0_wp/3.0_wp*gd*ie*n11 + alpha
      dy(2) = m12 - 2.0_wp/3.0_wp*gd*ie*n12
      dy(3) = m22 - 2.0_wp/3.0_wp*gd*ie*n22 + alpha
      dy(4) = m33 - 2.0_wp/3.0_wp*gd*ie*n33 + alpha
      dy(5) = sqrt(2.0_wp/3.0_wp)*gd
   end subroutine ode_rhs

   !> The continuous model from first yield at ty (b_e = F F^T, ep = 0) to tend by RK4 on nrk
   !> steps: y = (b11, b12, b22, b33, ep) of b_e at tend. ok is false if the path unloaded.
   pure subroutine ref_ode(mu, prm, path, ty, tend, nrk, y, ok)
      real(wp), intent(in) :: mu, ty, tend
      type(j2_param_t), intent(in) :: prm
      integer, intent(in) :: path, nrk
      real(wp), intent(out) :: y(5)
      logical, intent(out) :: ok
      real(wp) :: f(5), h, t, k1(5), k2(5), k3(5), k4(5)
      integer :: i
      call path_f(path, ty, f)
      y = [f(1)**2 + f(2)**2, f(1)*f(3) + f(2)*f(4), f(3)**2 + f(4)**2, f(5)**2, 0.0_wp]
      ok = .true.
      h = (tend - ty)/real(nrk, wp)
      do i = 0, nrk - 1
         t = ty + real(i, wp)*h
         call ode_rhs(mu, prm, path, t, y, k1, ok)
         call ode_rhs(mu, prm, path, t + 0.5_wp*h, y + 0.5_wp*h*k1, k2, ok)
         call ode_rhs(mu, prm, path, t + 0.5_wp*h, y + 0.5_wp*h*k2, k3, ok)
         call ode_rhs(mu, prm, path, t + h, y + h*k3, k4, ok)
         y = y + h/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
      end do
   end subroutine ref_ode

end module test_plasticity_ref
