!> Finite-strain J2 plasticity on the seed's neo-Hookean elasticity: the material-point kernels
!> (doc/plasticity.md derives every equation tagged (Jk) below).
!>
!> Multiplicative split F = Fe Fp with det Fp = 1; history per point: the inverse plastic right
!> Cauchy-Green tensor Cp^-1 (a11, a12, a22, a33), the equivalent plastic strain ep and, when
!> `j2_has_temperature`, the temperature. Elasticity is eq. 7.2 of the seed on b_e = F Cp^-1 F^T:
!>
!>     tau = lambda ln J 1 + mu (b_e - 1)                                             (J6)
!>     P = mu F Cp^-1 + c cof F,   c = (lambda ln J - mu)/J                            (J7)
!>
!> Each step: trial b_e from the stored Cp^-1 (J18), yield test q_trial <= Y (J19), radial
!> return of the Kirchhoff deviator (Simo & Hughes, Box 9.1, with b_e for bbar_e; closed form for
!> linear hardening (J22), safeguarded scalar Newton otherwise (J21, J23)), the spherical part of
!> b_e from det b_e = J^2 (J24, J25a-c), Cp^-1 = F^-1 b_e F^-T (J26), the dissipation of the
!> continuous model at the returned state (J27), adiabatic heating (J17).
!>
!> Deformation gradients are 3-D with the block form [F11 F12 0; F21 F22 0; 0 0 F33]: F33 = 1 in
!> plane strain, r/R (hoop) in axisymmetry. Arrays are of length n (points). As for the
!> neo-Hookean kernel `nh_piola`, the caller passes the in-plane j = F11 F22 - F12 F21 > 0 it has
!> computed and checked (J = j F33; F33 > 0 is the caller's too) and the weight of each point, and
!> gets stress, energy and dissipation times the weight.
module exic_material_j2
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln, ln_block
   use exic_material_j2_hardening, only: j2_param_t, j2_strain_part, j2_rate_factor, &
                                         j2_thermal_factor, j2_static_yield, j2_has_temperature, &
                                         j2_is_linear, J2_JOHNSON_COOK
   implicit none
   private

   public :: j2_piola, j2_cauchy, j2_init_history

   !> Points per chunk: the kernel's work arrays (9 x CHUNK reals) stay in the L1 cache.
   integer, parameter :: CHUNK = 64
   real(wp), parameter :: SQ32 = 1.2247448713915890491_wp   !< sqrt(3/2)
   real(wp), parameter :: EPS = epsilon(1.0_wp)
   !> Return (J23): converged when a Newton step inside the bracket is below RTOL x dep; at
   !> most MAXIT iterations (bisection alone reaches round-off in about 60).
   real(wp), parameter :: RTOL = 1.0e-8_wp
   integer, parameter :: MAXIT = 100

contains

   !> The initial history: Cp^-1 = 1, ep = 0 and, when the history has a temperature, T = Troom.
   pure subroutine j2_init_history(n, prm, a11, a12, a22, a33, ep, temp)
      integer, intent(in) :: n                                !< number of points
      type(j2_param_t), intent(in) :: prm                     !< material parameters
      real(wp), intent(out) :: a11(n), a12(n), a22(n), a33(n) !< Cp^-1
      real(wp), intent(out) :: ep(n)                          !< equivalent plastic strain
      real(wp), intent(inout) :: temp(n)                      !< temperature (set if used)
      a11 = 1.0_wp
      a12 = 0.0_wp
      a22 = 1.0_wp
      a33 = 1.0_wp
      ep = 0.0_wp
      if (j2_has_temperature(prm)) temp = prm%troom
   end subroutine j2_init_history

   !> First Piola-Kirchhoff stress, elastic energy, dissipation and yield stress at n points for
   !> the deformation gradients F(n+1), updating the history from t(n) to t(n+1).
   !>
   !> Same shape as `nh_piola`: jac is the in-plane j = F11 F22 - F12 F21 > 0 the caller computed
   !> and checked, wt the weight of each point (the quadrature weight x reference volume it
   !> stands for, x 2 pi r in axisymmetry; 1 for values per unit reference volume); stress,
   !> energy and dissipation come out times wt, the yield stress and the history do not.
   !> A point that has never yielded (Cp^-1 = 1 exactly) and stays elastic gets the neo-Hookean
   !> stress and energy of `nh_piola` to the last bit (doc/plasticity.md, section 2).
   !> temp is read and written only when `j2_has_temperature(prm)`; otherwise any array of
   !> length n may be passed. dt is the step (Johnson-Cook's rate dep/dt; dt <= 0: rate factor 1).
   !>
   !> Points go in chunks of CHUNK: (A) ln J by ln_block as in nh_piola (exic's logarithm: the
   !> same bits vectorized or not), Y(n) with its slope, scalar for exp and pow (glibc's vector
   !> functions differ from the scalar ones in the last bits); (B) the trial state of every
   !> point, without branches; (C) the return at the points that yield, gathered into a list
   !> and returned in passes over it (plastic_points), updating their history; (D) stress and
   !> energy of every point from
   !> F and the history of t(n+1), without branches (the one formula of (J7)/(J8)).
   pure subroutine j2_piola(n, lambda, mu, prm, dt, f11, f12, f21, f22, f33, jac, wt, a11, a12, &
                            a22, a33, ep, temp, p11, p12, p21, p22, p33, we, dwp, ys)
      integer, intent(in) :: n                                    !< number of points
      real(wp), intent(in) :: lambda, mu                          !< Lame constants
      type(j2_param_t), intent(in) :: prm                         !< plastic parameters
      real(wp), intent(in) :: dt                                  !< time step
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n)      !< in-plane F(n+1)
      real(wp), intent(in) :: f33(n)                              !< F33 (1, or hoop r/R)
      real(wp), intent(in) :: jac(n)                              !< j = F11 F22 - F12 F21 > 0
      real(wp), intent(in) :: wt(n)                               !< weight of each point
      real(wp), intent(inout) :: a11(n), a12(n), a22(n), a33(n)   !< Cp^-1: in t(n), out t(n+1)
      real(wp), intent(inout) :: ep(n)                            !< equivalent plastic strain
      real(wp), intent(inout) :: temp(n)                          !< temperature (see above)
      real(wp), intent(out) :: p11(n), p12(n), p21(n), p22(n)     !< wt x in-plane first Piola stress
      real(wp), intent(out) :: p33(n)                             !< wt x hoop/out-of-plane P33
      real(wp), intent(out) :: we(n)                              !< wt x elastic energy (J8)
      real(wp), intent(out) :: dwp(n)                             !< wt x dissipation of the step (J27)
      real(wp), intent(out) :: ys(n)                              !< yield stress
      real(wp), dimension(CHUNK) :: jj, lnj, hn, th, x, d11, d22, d33, d12, qtr
      real(wp) :: g11, g12, g21, g22, g33, b11, b22, b33, c, chirc
      logical :: jc, heat, linear
      integer :: q0, m, i, q, ny, iy(CHUNK)

      jc = prm%law == J2_JOHNSON_COOK
      heat = prm%cheat > 0.0_wp
      linear = j2_is_linear(prm)
      chirc = 0.0_wp
      if (heat) chirc = prm%chi/(prm%rho*prm%cheat)
      th = 1.0_wp
      do q0 = 1, n, CHUNK
         m = min(CHUNK, n - q0 + 1)
         ! (A) ln J, Y(n) (J19) and its slope H(n)
         do i = 1, m
            jj(i) = jac(q0 + i - 1)*f33(q0 + i - 1)
         end do
         call ln_block(m, jj, lnj)            ! exic's logarithm, the neo-Hookean kernels' (base/logarithm)
         if (linear) then
            do i = 1, m
               ys(q0 + i - 1) = prm%y0 + prm%hiso*ep(q0 + i - 1)      ! as j2_strain_part
               hn(i) = prm%hiso
            end do
         else
            !GCC$ novector
            do i = 1, m
               q = q0 + i - 1
               call j2_strain_part(prm, ep(q), ys(q), hn(i))
               if (jc) then
                  th(i) = j2_thermal_factor(prm, temp(q))
                  ys(q) = ys(q)*th(i)
                  hn(i) = hn(i)*th(i)
               end if
            end do
         end if
         ! (B) trial b_e = F Cp^-1 F^T, its spherical part x and deviator d (J18), q_trial (J19)
         do i = 1, m
            q = q0 + i - 1
            g11 = f11(q)*a11(q) + f12(q)*a12(q)
            g12 = f11(q)*a12(q) + f12(q)*a22(q)
            g21 = f21(q)*a11(q) + f22(q)*a12(q)
            g22 = f21(q)*a12(q) + f22(q)*a22(q)
            b11 = g11*f11(q) + g12*f12(q)
            b22 = g21*f21(q) + g22*f22(q)
            b33 = (f33(q)*a33(q))*f33(q)
            d12(i) = g11*f21(q) + g12*f22(q)
            x(i) = (b11 + b22 + b33)/3.0_wp
            d11(i) = b11 - x(i)
            d22(i) = b22 - x(i)
            d33(i) = b33 - x(i)
            qtr(i) = SQ32*mu*sqrt(d11(i)*d11(i) + d22(i)*d22(i) + d33(i)*d33(i) &
                                  + 2.0_wp*(d12(i)*d12(i)))
            dwp(q) = 0.0_wp
         end do
         ! (C) the return at the points that yield
         ny = 0
         do i = 1, m
            if (qtr(i) > ys(q0 + i - 1)) then
               ny = ny + 1
               iy(ny) = i
            end if
         end do
         if (ny > 0) call plastic_points(n, ny, iy, q0, mu, prm, linear, dt, th, hn, chirc, x, d11, &
                                         d22, d33, d12, qtr, f11, f12, f21, f22, f33, jac, a11, a12, &
                                         a22, a33, ep, temp, dwp, ys)
         ! (D) stress (J7) and energy (J8) from F and Cp^-1(n+1), times the weight; with
         ! Cp^-1 = 1 and F33 = 1 the operations of nh_piola in its order (doc/plasticity.md, (J9))
         do i = 1, m
            q = q0 + i - 1
            c = (lambda*lnj(i) - mu)/(jac(q)*f33(q))
            g11 = f11(q)*a11(q) + f12(q)*a12(q)
            g12 = f11(q)*a12(q) + f12(q)*a22(q)
            g21 = f21(q)*a11(q) + f22(q)*a12(q)
            g22 = f21(q)*a12(q) + f22(q)*a22(q)
            g33 = f33(q)*a33(q)
            p11(q) = wt(q)*(mu*g11 + c*(f22(q)*f33(q)))
            p12(q) = wt(q)*(mu*g12 - c*(f21(q)*f33(q)))
            p21(q) = wt(q)*(mu*g21 - c*(f12(q)*f33(q)))
            p22(q) = wt(q)*(mu*g22 + c*(f11(q)*f33(q)))
            p33(q) = wt(q)*(mu*g33 + c*jac(q))
            we(q) = wt(q)*(lnj(i)*(0.5_wp*lambda*lnj(i) - mu) &
                           + 0.5_wp*mu*((g11*f11(q) + g12*f12(q) + g21*f21(q) + g22*f22(q) - 2.0_wp) &
                                        + (g33*f33(q) - 1.0_wp)))
            dwp(q) = wt(q)*dwp(q)
         end do
      end do
   end subroutine j2_piola

   !> The return at the ny points iy(1:ny) of the chunk at q0 that yield: dep (J21-J23), k, the
   !> spherical part (J24, J25), the new Cp^-1 and ep (J26), dissipation (J27), heating (J17).
   !> x, d: trial spherical part and deviator; qtr: q_trial; th: thermal factor; hn: dY/dep at
   !> ep(n) (chunk values, indexed by iy); chirc = chi/(rho c); jac = F11 F22 - F12 F21 (point
   !> values, indexed by q0 + iy - 1). ys holds Y(n) on entry and the flow stress of the step on
   !> exit; dwp is the dissipation per unit reference volume (not weighted). The points go
   !> through passes that gcc vectorizes, each point's operations those of the one-point form
   !> in its order (so the same bits whether a pass is vectorized or not): (1) J2, J3 and mubar
   !> gathered; (2) dep and Y by (J22) for linear hardening, else by return_newton point by
   !> point; (3) k and the spherical part by (J25) with its residual; (4) Newton on the
   !> residual (spherical_newton) only at the points where it is not at round-off; (5) Cp^-1,
   !> ep, the dissipation and Y, then scattered.
   pure subroutine plastic_points(n, ny, iy, q0, mu, prm, linear, dt, th, hn, chirc, x, d11, d22, &
                                  d33, d12, qtr, f11, f12, f21, f22, f33, jac, a11, a12, a22, a33, &
                                  ep, temp, dwp, ys)
      integer, intent(in) :: n, ny, iy(CHUNK), q0
      real(wp), intent(in) :: mu, dt, chirc
      type(j2_param_t), intent(in) :: prm
      logical, intent(in) :: linear
      real(wp), intent(in), dimension(CHUNK) :: th, hn, x, d11, d22, d33, d12, qtr
      real(wp), intent(in), dimension(n) :: f11, f12, f21, f22, f33, jac
      real(wp), intent(inout), dimension(n) :: a11, a12, a22, a33, ep, temp, dwp, ys
      real(wp), dimension(CHUNK) :: sj2, sj3, mub, qt, yn, dep, y, k, xn, jj, ok, c11, c12, c22, &
                                    c33, dw
      real(wp) :: omk, s0, rs0, h0, del, dcp, res
      integer :: p, i, q

      ! (1) the trial values of the points that yield
      do p = 1, ny
         i = iy(p)
         ! J2 = d:d/2, J3 = det d, mubar = mu tr(b_trial)/3 (J20)
         sj2(p) = 0.5_wp*(d11(i)*d11(i) + d22(i)*d22(i) + d33(i)*d33(i) + 2.0_wp*(d12(i)*d12(i)))
         sj3(p) = d33(i)*(d11(i)*d22(i) - d12(i)*d12(i))
         mub(p) = mu*x(i)
         qt(p) = qtr(i)
         yn(p) = ys(q0 + i - 1)
      end do
      ! (2) dep and Y of the step
      if (linear) then
         do p = 1, ny
            dep(p) = (qt(p) - yn(p))/(3.0_wp*mub(p) + prm%hiso)                 ! (J22)
            y(p) = yn(p) + prm%hiso*dep(p)
         end do
      else
         do p = 1, ny
            i = iy(p)
            call return_newton(prm, ep(q0 + i - 1), dt, th(i), hn(i), qt(p), mub(p), yn(p), dep(p), y(p))
         end do
      end if
      ! (3) deviator s = k s_trial (J20), 1 - k computed directly; spherical part xn = x - delta
      ! with det(xn 1 + k d) = J^2 (J24): delta_p, the small root of h0 - s0 delta + 3 x delta^2
      ! - delta^3 = 0 (J25a), by the root of the quadratic part (stable form) and one Newton step
      ! for -delta^3 (J25b, relative error of order (delta/x)^3), less the round-off of
      ! det Cp^-1(n) (J25c); accepted (ok = 1) when det(xn 1 + k d) - J^2 is at round-off
      do p = 1, ny
         i = iy(p)
         q = q0 + i - 1
         omk = 3.0_wp*mub(p)*dep(p)/qt(p)
         k(p) = 1.0_wp - omk
         s0 = 3.0_wp*x(i)*x(i) - k(p)*k(p)*sj2(p)
         rs0 = 1.0_wp/s0
         h0 = max(omk*(x(i)*(1.0_wp + k(p))*sj2(p) - (1.0_wp + k(p) + k(p)*k(p))*sj3(p)), 0.0_wp)
         del = 2.0_wp*h0/(s0 + sqrt(max(s0*s0 - 12.0_wp*x(i)*h0, 0.0_wp)))
         del = del - del*del*del*rs0
         jj(p) = jac(q)*f33(q)
         dcp = (a11(q)*a22(q) - a12(q)*a12(q))*a33(q) - 1.0_wp
         xn(p) = x(i) - del - jj(p)*jj(p)*dcp*rs0
         res = (xn(p)*xn(p) - k(p)*k(p)*sj2(p))*xn(p) + (k(p)*k(p)*k(p)*sj3(p) - jj(p)*jj(p))
         ok(p) = merge(1.0_wp, 0.0_wp, abs(res) <= 16.0_wp*EPS*jj(p)*jj(p))
      end do
      ! (4) else Newton on that residual (large elastic strains only: delta/x is of order
      ! (Y/mu)^2 for metals)
      do p = 1, ny
         if (ok(p) == 0.0_wp) call spherical_newton(k(p), sj2(p), sj3(p), jj(p), xn(p))
      end do
      ! (5) Cp^-1 (J26), the dissipation (J27): D = -mu dgamma tr(b_e) tr(b_e^-1 n)/tr(b_e^-1)
      ! at the returned b_e = xn 1 + k d
      do p = 1, ny
         i = iy(p)
         q = q0 + i - 1
         call pull_back(f11(q), f12(q), f21(q), f22(q), f33(q), jac(q), k(p)*d11(i) + xn(p), &
                        k(p)*d12(i), k(p)*d22(i) + xn(p), k(p)*d33(i) + xn(p), c11(p), c12(p), &
                        c22(p), c33(p))
         dw(p) = y(p)*dep(p)*(3.0_wp*xn(p))*(xn(p)*sj2(p) - 1.5_wp*k(p)*sj3(p)) &
                 /(sj2(p)*(3.0_wp*xn(p)*xn(p) - k(p)*k(p)*sj2(p)))
      end do
      do p = 1, ny
         q = q0 + iy(p) - 1
         a11(q) = c11(p)
         a12(q) = c12(p)
         a22(q) = c22(p)
         a33(q) = c33(p)
         ep(q) = ep(q) + dep(p)
         dwp(q) = dw(p)
         ys(q) = y(p)
      end do
      if (chirc > 0.0_wp) then
         do p = 1, ny
            q = q0 + iy(p) - 1
            temp(q) = temp(q) + chirc*dwp(q)                       ! (J17)
         end do
      end if
   end subroutine plastic_points

   !> Newton on the residual det(xn 1 + k d) - J^2 of (J24) from xn, until it is at round-off
   !> or the step is (at most 40 steps); jj = J.
   pure subroutine spherical_newton(k, sj2, sj3, jj, xn)
      real(wp), intent(in) :: k, sj2, sj3, jj
      real(wp), intent(inout) :: xn
      real(wp) :: res, dxn
      integer :: it
      do it = 1, 40
         res = (xn*xn - k*k*sj2)*xn + (k*k*k*sj3 - jj*jj)
         if (abs(res) <= 16.0_wp*EPS*jj*jj) exit
         dxn = res/(3.0_wp*xn*xn - k*k*sj2)
         xn = xn - dxn
         if (abs(dxn) <= 2.0_wp*EPS*xn) exit
      end do
   end subroutine spherical_newton

   !> dep from (J21) by Newton, safeguarded by bisection on [0, dmax], dmax = the perfectly
   !> plastic step. Start: the step linearized at ep(n) (slope hn), a lower bound for concave
   !> laws. Converged (J23) when a Newton step inside the bracket is below RTOL x dep: the
   !> quadratic convergence puts the error after it near round-off, so that step is taken
   !> without another evaluation of the law, and y = Y + Y' x step (exact for Y = 0).
   pure subroutine return_newton(prm, ep0, dt, th, hn, qt, mub, yn, dep, y)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep0, dt, th, hn, qt, mub, yn
      real(wp), intent(out) :: dep, y
      real(wp) :: lo, hi, z, g, ys, dys, r, dr, zn, yz, hz
      integer :: it

      lo = 0.0_wp
      hi = (qt - yn)/(3.0_wp*mub)
      z = (qt - yn)/(3.0_wp*mub + hn)
      do it = 1, MAXIT
         call j2_strain_part(prm, ep0 + z, ys, dys)
         call j2_rate_factor(prm, z, dt, r, dr)
         yz = ys*r*th
         hz = (dys*r + ys*dr)*th
         g = qt - 3.0_wp*mub*z - yz
         if (g > 0.0_wp) then
            lo = z
         else
            hi = z
         end if
         zn = z + g/(3.0_wp*mub + hz)
         if (.not. (zn > lo .and. zn <= hi)) then
            zn = 0.5_wp*(lo + hi)
         else if (abs(zn - z) <= RTOL*zn) then
            dep = zn
            y = yz + hz*(zn - z)
            return
         end if
         if (zn == z) exit
         z = zn
      end do
      ! not converged by the rule above (round-off floor or MAXIT): the last iterate
      call j2_strain_part(prm, ep0 + z, ys, dys)
      call j2_rate_factor(prm, z, dt, r, dr)
      dep = z
      y = ys*r*th
   end subroutine return_newton

   !> Cp^-1 = F^-1 b_e F^-T (J26), in-plane with F^-1 = [F22 -F12; -F21 F11]/j, a33 = b33/F33^2.
   pure subroutine pull_back(f11, f12, f21, f22, f33, j2d, be11, be12, be22, be33, a11, a12, a22, &
                            a33)
      real(wp), intent(in) :: f11, f12, f21, f22, f33, j2d, be11, be12, be22, be33
      real(wp), intent(out) :: a11, a12, a22, a33
      real(wp) :: r, rj, u11, u12, u21, u22
      r = 1.0_wp/(j2d*(f33*f33))
      rj = r*(f33*f33)
      u11 = (f22*be11 - f12*be12)*rj
      u12 = (f22*be12 - f12*be22)*rj
      u21 = (f11*be12 - f21*be11)*rj
      u22 = (f11*be22 - f21*be12)*rj
      a11 = (u11*f22 - u12*f12)*rj
      a12 = (u12*f11 - u11*f21)*rj
      a22 = (u22*f11 - u21*f21)*rj
      a33 = be33*(j2d*r)
   end subroutine pull_back

   !> Cauchy stress sigma = tau/J (J6) and the static yield stress at n points from F and the
   !> history, for output; the history is not changed. With Cp^-1 = 1 and F33 = 1 the stress is
   !> that of nh_cauchy to the last bit. ep and T are history values the caller already has.
   pure subroutine j2_cauchy(n, lambda, mu, prm, f11, f12, f21, f22, f33, a11, a12, a22, a33, &
                             ep, temp, sxx, syy, szz, sxy, ys)
      integer, intent(in) :: n                                   !< number of points
      real(wp), intent(in) :: lambda, mu                         !< Lame constants
      type(j2_param_t), intent(in) :: prm                        !< plastic parameters
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n)     !< in-plane F
      real(wp), intent(in) :: f33(n)                             !< F33 (1, or hoop r/R)
      real(wp), intent(in) :: a11(n), a12(n), a22(n), a33(n)     !< Cp^-1
      real(wp), intent(in) :: ep(n)                              !< equivalent plastic strain
      real(wp), intent(in) :: temp(n)                            !< temperature (Johnson-Cook)
      real(wp), intent(out) :: sxx(n), syy(n), szz(n), sxy(n)    !< Cauchy stress (zz: hoop)
      real(wp), intent(out) :: ys(n)                             !< Y(ep, rate factor 1, T)
      real(wp) :: jac, lnj, rj, g11, g12, g21, g22, b11, b22, b12, b33, p
      logical :: jc
      integer :: q

      jc = prm%law == J2_JOHNSON_COOK
      ! exic's logarithm, as in nh_cauchy (base/logarithm: the same bits scalar and vector)
      do q = 1, n
         jac = (f11(q)*f22(q) - f12(q)*f21(q))*f33(q)
         lnj = ln(jac)
         rj = 1.0_wp/jac
         g11 = f11(q)*a11(q) + f12(q)*a12(q)
         g12 = f11(q)*a12(q) + f12(q)*a22(q)
         g21 = f21(q)*a11(q) + f22(q)*a12(q)
         g22 = f21(q)*a12(q) + f22(q)*a22(q)
         b11 = g11*f11(q) + g12*f12(q)
         b22 = g21*f21(q) + g22*f22(q)
         b12 = g11*f21(q) + g12*f22(q)
         b33 = (f33(q)*a33(q))*f33(q)
         p = lambda*lnj*rj
         sxx(q) = p + mu*rj*(b11 - 1.0_wp)
         syy(q) = p + mu*rj*(b22 - 1.0_wp)
         szz(q) = p + mu*rj*(b33 - 1.0_wp)
         sxy(q) = mu*rj*b12
         if (jc) then
            ys(q) = j2_static_yield(prm, ep(q), temp(q))
         else
            ys(q) = j2_static_yield(prm, ep(q), 0.0_wp)
         end if
      end do
   end subroutine j2_cauchy

end module exic_material_j2
