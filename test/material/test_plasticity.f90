!> Tests of the finite-strain J2 material-point kernels (src/exic/material/j2.f90): the elastic
!> limit against the neo-Hookean kernel bit for bit, uniaxial closed forms, the discrete map
!> against an independent quad-precision implementation on every law and path, convergence to
!> the continuous model, objectivity, plastic incompressibility, consistency, the energy of the
!> return, hardening laws, heating and the parameter checks. doc/plasticity.md, section 6,
!> describes every reference.
module test_plasticity
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln
   use exic_material_material, only: lame_from_young
   use exic_material_neohookean, only: nh_piola, nh_cauchy
   use exic_material_j2_hardening, only: j2_param_t, j2_check_parameters, j2_static_yield, &
                                         j2_flow_stress, j2_has_temperature, J2_MISES, J2_POWER, &
                                         J2_JOHNSON_COOK
   use exic_material_j2, only: j2_piola, j2_cauchy, j2_init_history
   use test_plasticity_ref, only: qp, ref_t, ref_step, path_f, uniaxial_strain_pp, &
                                  uniaxial_stress_pp, ref_ode, yield_onset, PATH_SHEAR, &
                                  PATH_EXTENSION, PATH_UNIAXIAL_STRAIN
   use testing, only: suite_t, check, check_close, section
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   implicit none
   private

   public :: run_plasticity_tests

   real(wp), parameter :: E_CU = 117.0e9_wp, NU_CU = 0.35_wp   !< copper (issue 12's Taylor bar)
   real(wp), parameter :: Y_CU = 400.0e6_wp
   real(wp), parameter :: PI = 3.14159265358979323846_wp
   !> Materials of the tests: perfect plasticity, linear, saturation, power (n < 1), Johnson-Cook.
   integer, parameter :: M_PP = 1, M_LIN = 2, M_SAT = 3, M_POW = 4, M_JC = 5
   character(len=4), parameter :: MNAME(5) = ['pp  ', 'lin ', 'sat ', 'pow ', 'jc  ']
   character(len=9), parameter :: PNAME(3) = ['shear    ', 'extension', 'ustrain  ']

   !> One material point driven through the kernel (n = 1): history and last outputs.
   type :: point_t
      real(wp) :: a11(1) = 1.0_wp, a12(1) = 0.0_wp, a22(1) = 1.0_wp, a33(1) = 1.0_wp
      real(wp) :: ep(1) = 0.0_wp, temp(1) = 0.0_wp
      real(wp) :: p(5) = 0.0_wp, we = 0.0_wp, dwp = 0.0_wp, ys = 0.0_wp
   end type point_t

   real(wp) :: lam, mu   ! copper's Lame constants, set by run_plasticity_tests

contains

   !> Run every plasticity test.
   subroutine run_plasticity_tests(s)
      type(suite_t), intent(inout) :: s
      call lame_from_young(E_CU, NU_CU, lam, mu)
      call test_elastic_limit(s)
      call test_mixed_block(s)
      call test_uniaxial_closed_form(s)
      call test_discrete_reference(s)
      call test_continuous_model(s)
      call test_objectivity(s)
      call test_incompressibility(s)
      call test_energy(s)
      call test_laws(s)
      call test_parameters(s)
   end subroutine run_plasticity_tests

   ! ---------------------------------------------------------------- helpers

   !> Park-Miller uniform number in (0, 1).
   function rnd(seed) result(r)
      integer(int64), intent(inout) :: seed
      real(wp) :: r
      seed = mod(16807_int64*seed, 2147483647_int64)
      r = real(seed, wp)/2147483647.0_wp
   end function rnd

   !> The test materials (SI units, copper-like; Johnson-Cook: OFHC copper of Johnson & Cook).
   function material(kind) result(prm)
      integer, intent(in) :: kind
      type(j2_param_t) :: prm
      prm%rho = 8930.0_wp
      select case (kind)
      case (M_PP)
         prm%law = J2_MISES
         prm%y0 = Y_CU
      case (M_LIN)
         prm%law = J2_MISES
         prm%y0 = Y_CU
         prm%hiso = 100.0e6_wp
      case (M_SAT)
         prm%law = J2_MISES
         prm%y0 = Y_CU
         prm%yinf = 600.0e6_wp
         prm%beta = 10.0_wp
         prm%hiso = 50.0e6_wp
      case (M_POW)
         prm%law = J2_POWER
         prm%a = 90.0e6_wp
         prm%b = 292.0e6_wp
         prm%en = 0.31_wp
      case default
         prm%law = J2_JOHNSON_COOK
         prm%a = 90.0e6_wp
         prm%b = 292.0e6_wp
         prm%en = 0.31_wp
         prm%crate = 0.025_wp
         prm%m = 1.09_wp
         prm%tmelt = 1356.0_wp
         prm%troom = 293.0_wp
         prm%epsdot0 = 1.0_wp
         prm%cheat = 383.0_wp
      end select
   end function material

   !> A fresh point with the kernel's initial history.
   function new_point(prm) result(pt)
      type(j2_param_t), intent(in) :: prm
      type(point_t) :: pt
      call j2_init_history(1, prm, pt%a11, pt%a12, pt%a22, pt%a33, pt%ep, pt%temp)
   end function new_point

   !> One kernel step at F = f (11, 12, 21, 22, 33).
   subroutine kstep(prm, dt, f, pt)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: dt, f(5)
      type(point_t), intent(inout) :: pt
      real(wp) :: p11(1), p12(1), p21(1), p22(1), p33(1), we(1), dwp(1), ys(1)
      call j2_piola(1, lam, mu, prm, dt, f(1:1), f(2:2), f(3:3), f(4:4), f(5:5), &
                    [f(1)*f(4) - f(2)*f(3)], [1.0_wp], pt%a11, pt%a12, pt%a22, pt%a33, pt%ep, &
                    pt%temp, p11, p12, p21, p22, p33, we, dwp, ys)
      pt%p = [p11(1), p12(1), p21(1), p22(1), p33(1)]
      pt%we = we(1)
      pt%dwp = dwp(1)
      pt%ys = ys(1)
   end subroutine kstep

   !> Von Mises Kirchhoff stress q = sqrt(3/2) |dev tau| of tau = P F^T.
   pure real(wp) function mises(f, p) result(q)
      real(wp), intent(in) :: f(5), p(5)
      real(wp) :: t11, t12, t22, t33, x
      t11 = p(1)*f(1) + p(2)*f(2)
      t12 = 0.5_wp*((p(1)*f(3) + p(2)*f(4)) + (p(3)*f(1) + p(4)*f(2)))
      t22 = p(3)*f(3) + p(4)*f(4)
      t33 = p(5)*f(5)
      x = (t11 + t22 + t33)/3.0_wp
      q = sqrt(1.5_wp*((t11 - x)**2 + (t22 - x)**2 + (t33 - x)**2 + 2.0_wp*t12**2))
   end function mises

   !> b_e = F Cp^-1 F^T of a point: (b11, b12, b22, b33).
   pure function elastic_b(f, pt) result(b)
      real(wp), intent(in) :: f(5)
      type(point_t), intent(in) :: pt
      real(wp) :: b(4), g11, g12, g21, g22
      g11 = f(1)*pt%a11(1) + f(2)*pt%a12(1)
      g12 = f(1)*pt%a12(1) + f(2)*pt%a22(1)
      g21 = f(3)*pt%a11(1) + f(4)*pt%a12(1)
      g22 = f(3)*pt%a12(1) + f(4)*pt%a22(1)
      b = [g11*f(1) + g12*f(2), g11*f(3) + g12*f(4), g21*f(3) + g22*f(4), f(5)**2*pt%a33(1)]
   end function elastic_b

   !> det Cp^-1 - 1 of a point.
   pure real(wp) function det_dev(pt)
      type(point_t), intent(in) :: pt
      det_dev = (pt%a11(1)*pt%a22(1) - pt%a12(1)**2)*pt%a33(1) - 1.0_wp
   end function det_dev

   !> An integer as text.
   function its(i) result(t)
      integer, intent(in) :: i
      character(len=:), allocatable :: t
      character(len=12) :: buf
      write (buf, '(i0)') i
      t = trim(buf)
   end function its

   !> A real as text for a check's name.
   character(len=12) function fmt_e(x)
      real(wp), intent(in) :: x
      write (fmt_e, '(es12.3)') x
   end function fmt_e

   ! ---------------------------------------------------------------- elastic limit

   !> A point that never yields gives the neo-Hookean kernel's stress and energy bit for bit,
   !> with the same weights.
   subroutine test_elastic_limit(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 300
      real(wp), dimension(n) :: f11, f12, f21, f22, f33, one, wq, jac, a11, a12, a22, a33, ep, tp, &
                                p11, p12, p21, p22, p33, we, dwp, ys, q11, q12, q21, q22, w
      real(wp), dimension(n) :: sx, sy, sz, sxy, tx, ty, tz, txy
      real(wp) :: lj, fm(3, 3), fit(3, 3), pref(3, 3), wref, err, lm(2), mm(2)
      type(j2_param_t) :: prm
      integer(int64) :: seed
      integer :: i, c
      logical :: same

      call section(s, 'plasticity: elastic limit equals the neo-Hookean kernel')
      lm = [33333.0_wp, lam]
      mm = [5000.0_wp, mu]
      seed = 20240601_int64
      one = 1.0_wp
      do c = 1, 2
         prm = material(M_PP)
         prm%y0 = 1.0e30_wp
         do i = 1, n
            f11(i) = 1.0_wp + 0.6_wp*(rnd(seed) - 0.5_wp)
            f12(i) = 0.6_wp*(rnd(seed) - 0.5_wp)
            f21(i) = 0.6_wp*(rnd(seed) - 0.5_wp)
            f22(i) = 1.0_wp + 0.6_wp*(rnd(seed) - 0.5_wp)
            wq(i) = 0.5_wp + rnd(seed)
         end do
         f33 = 1.0_wp
         jac = f11*f22 - f12*f21
         call j2_init_history(n, prm, a11, a12, a22, a33, ep, tp)
         call j2_piola(n, lm(c), mm(c), prm, 0.0_wp, f11, f12, f21, f22, f33, jac, wq, a11, a12, a22, &
                       a33, ep, tp, p11, p12, p21, p22, p33, we, dwp, ys)
         call nh_piola(n, lm(c), mm(c), f11, f12, f21, f22, jac, wq, q11, q12, q21, q22, w)
         same = all(p11 == q11) .and. all(p12 == q12) .and. all(p21 == q21) .and. all(p22 == q22)
         call check(s, same, 'plane strain, 300 weighted points in 5 chunks: wt P11, P12, P21, P22 '// &
                    '== nh_piola '//merge('(seed lambda, mu) ', '(copper)          ', c == 1))
         call check(s, all(we == w), 'wt x energy == nh_piola')
         call check(s, all(a11 == 1.0_wp) .and. all(a12 == 0.0_wp) .and. all(a22 == 1.0_wp) .and. &
                    all(a33 == 1.0_wp) .and. all(ep == 0.0_wp) .and. all(dwp == 0.0_wp), &
                    'history untouched, no dissipation')
         call j2_cauchy(n, lm(c), mm(c), prm, f11, f12, f21, f22, f33, a11, a12, a22, a33, ep, tp, &
                        sx, sy, sz, sxy, ys)
         do i = 1, n
            call nh_cauchy(lm(c), mm(c), f11(i), f12(i), f21(i), f22(i), tx(i), ty(i), tz(i), txy(i), &
                           lj, wref)
         end do
         call check(s, all(sx == tx) .and. all(sy == ty) .and. all(sz == tz) .and. all(sxy == txy), &
                    'j2_cauchy == nh_cauchy')
      end do

      ! axisymmetric: F33 /= 1 against P = lambda ln J F^-T + mu (F - F^-T) in 3-D
      do i = 1, n
         f33(i) = 1.0_wp + 0.6_wp*(rnd(seed) - 0.5_wp)
      end do
      call j2_init_history(n, prm, a11, a12, a22, a33, ep, tp)
      jac = f11*f22 - f12*f21
      call j2_piola(n, lam, mu, prm, 0.0_wp, f11, f12, f21, f22, f33, jac, one, a11, a12, a22, a33, &
                    ep, tp, p11, p12, p21, p22, p33, we, dwp, ys)
      err = 0.0_wp
      do i = 1, n
         fm = reshape([f11(i), f21(i), 0.0_wp, f12(i), f22(i), 0.0_wp, 0.0_wp, 0.0_wp, f33(i)], [3, 3])
         jac(i) = (f11(i)*f22(i) - f12(i)*f21(i))*f33(i)
         fit = reshape([f22(i)*f33(i), -f12(i)*f33(i), 0.0_wp, -f21(i)*f33(i), f11(i)*f33(i), &
                        0.0_wp, 0.0_wp, 0.0_wp, f11(i)*f22(i) - f12(i)*f21(i)], [3, 3])/jac(i)
         pref = lam*log(jac(i))*fit + mu*(fm - fit)
         wref = 0.5_wp*lam*log(jac(i))**2 - mu*log(jac(i)) + 0.5_wp*mu*(sum(fm*fm) - 3.0_wp)
         err = max(err, maxval(abs([p11(i) - pref(1, 1), p12(i) - pref(1, 2), p21(i) - pref(2, 1), &
                                    p22(i) - pref(2, 2), p33(i) - pref(3, 3)]))/maxval(abs(pref)), &
                   abs(we(i) - wref)/abs(wref))
      end do
      call check(s, err <= 1.0e-14_wp, 'F33 /= 1: 3-D neo-Hookean P and W to 1e-14 (max rel '// &
                 fmt_e(err)//')')
      ! and bit for bit against the axisymmetric neo-Hookean kernel formula (J9a), weighted
      jac = f11*f22 - f12*f21
      call j2_init_history(n, prm, a11, a12, a22, a33, ep, tp)
      call j2_piola(n, lam, mu, prm, 0.0_wp, f11, f12, f21, f22, f33, jac, wq, a11, a12, a22, a33, &
                    ep, tp, p11, p12, p21, p22, p33, we, dwp, ys)
      same = .true.
      do i = 1, n
         lj = ln(jac(i)*f33(i))      ! the kernels' logarithm (base/logarithm)
         wref = (lam*lj - mu)/(jac(i)*f33(i))
         same = same .and. p11(i) == wq(i)*(mu*f11(i) + wref*(f22(i)*f33(i))) &
                .and. p12(i) == wq(i)*(mu*f12(i) - wref*(f21(i)*f33(i))) &
                .and. p21(i) == wq(i)*(mu*f21(i) - wref*(f12(i)*f33(i))) &
                .and. p22(i) == wq(i)*(mu*f22(i) + wref*(f11(i)*f33(i))) &
                .and. p33(i) == wq(i)*(mu*f33(i) + wref*jac(i)) &
                .and. we(i) == wq(i)*(lj*(0.5_wp*lam*lj - mu) + 0.5_wp*mu*((f11(i)*f11(i) &
                                      + f12(i)*f12(i) + f21(i)*f21(i) + f22(i)*f22(i) - 2.0_wp) &
                                      + (f33(i)*f33(i) - 1.0_wp)))
      end do
      call check(s, same, 'F33 /= 1, weighted: P and W == the axisymmetric neo-Hookean formula (J9a)')

   end subroutine test_elastic_limit

   !> A block where some points yield: the others stay bit-identical to nh_piola, and each
   !> yielding point gets what it gets alone (chunks do not mix points).
   subroutine test_mixed_block(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 300
      real(wp), dimension(n) :: f11, f12, f21, f22, f33, one, jac, a11, a12, a22, a33, ep, tp, &
                                p11, p12, p21, p22, p33, we, dwp, ys, q11, q12, q21, q22, w
      real(wp) :: amp
      type(j2_param_t) :: prm
      type(point_t) :: pt
      integer(int64) :: seed
      integer :: i, nel, npl
      logical :: same

      seed = 4242_int64
      one = 1.0_wp
      prm = material(M_LIN)
      f33 = 1.0_wp
      do i = 1, n
         amp = merge(0.02_wp, 0.002_wp, mod(i, 3) == 0)
         f11(i) = 1.0_wp + amp*(rnd(seed) - 0.5_wp)
         f12(i) = amp*(rnd(seed) - 0.5_wp)
         f21(i) = amp*(rnd(seed) - 0.5_wp)
         f22(i) = 1.0_wp + amp*(rnd(seed) - 0.5_wp)
      end do
      jac = f11*f22 - f12*f21
      call j2_init_history(n, prm, a11, a12, a22, a33, ep, tp)
      call j2_piola(n, lam, mu, prm, 0.0_wp, f11, f12, f21, f22, f33, jac, one, a11, a12, a22, a33, &
                    ep, tp, p11, p12, p21, p22, p33, we, dwp, ys)
      call nh_piola(n, lam, mu, f11, f12, f21, f22, jac, one, q11, q12, q21, q22, w)
      nel = 0
      npl = 0
      same = .true.
      do i = 1, n
         if (ep(i) == 0.0_wp) then
            nel = nel + 1
            same = same .and. p11(i) == q11(i) .and. p12(i) == q12(i) .and. p21(i) == q21(i) &
                   .and. p22(i) == q22(i) .and. we(i) == w(i)
         else
            npl = npl + 1
            pt = new_point(prm)
            call kstep(prm, 0.0_wp, [f11(i), f12(i), f21(i), f22(i), 1.0_wp], pt)
            same = same .and. all(pt%p == [p11(i), p12(i), p21(i), p22(i), p33(i)]) .and. &
                   pt%we == we(i) .and. pt%ep(1) == ep(i) .and. pt%a12(1) == a12(i)
         end if
      end do
      call check(s, nel > 150 .and. npl > 50 .and. same, 'mixed block ('//its(nel)// &
                 ' elastic, '//its(npl)//' yielding): elastic == nh_piola, '// &
                 'yielding == the point alone')
   end subroutine test_mixed_block

   ! ---------------------------------------------------------------- closed forms

   !> Perfect plasticity on uniaxial strain (J28) and uniaxial stress (J29), uneven steps.
   subroutine test_uniaxial_closed_form(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: lend(2) = [2.0_wp, 0.5_wp]
      integer, parameter :: n = 300
      type(j2_param_t) :: prm
      type(point_t) :: pt
      real(wp) :: t, l1, b1, b2, pex(5), aex(4), wex, ea, ep_, ew, sc, sg, jst, bz, bt, ly, lt, u
      real(wp) :: du, el
      integer(int64) :: seed
      integer :: dir, k, npl, it
      logical :: elastic_ok

      call section(s, 'plasticity: closed forms of perfect plasticity (uniaxial strain and stress)')
      prm = material(M_PP)
      seed = 77_int64
      do dir = 1, 2
         ! uniaxial strain, plane strain F = diag(l1, 1, 1)
         pt = new_point(prm)
         ea = 0.0_wp
         ep_ = 0.0_wp
         ew = 0.0_wp
         npl = 0
         do k = 1, n
            t = 1.0_wp
            if (k < n) t = ((real(k, wp) + 0.4_wp*(rnd(seed) - 0.5_wp))/real(n, wp))**1.3_wp
            l1 = 1.0_wp + (lend(dir) - 1.0_wp)*t
            call kstep(prm, 0.0_wp, [l1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp], pt)
            if (pt%ep(1) == 0.0_wp) cycle
            npl = npl + 1
            call uniaxial_strain_pp(mu, Y_CU, l1, b1, b2)
            aex = [b1/l1**2, 0.0_wp, b2, b2]
            pex = [(lam*log(l1) + mu*(b1 - 1.0_wp))/l1, 0.0_wp, 0.0_wp, &
                   lam*log(l1) + mu*(b2 - 1.0_wp), lam*log(l1) + mu*(b2 - 1.0_wp)]
            wex = 0.5_wp*lam*log(l1)**2 - mu*log(l1) + 0.5_wp*mu*(b1 + 2.0_wp*b2 - 3.0_wp)
            sc = max(maxval(abs(pex)), Y_CU)
            ea = max(ea, maxval(abs([pt%a11(1), pt%a12(1), pt%a22(1), pt%a33(1)] - aex)))
            ep_ = max(ep_, maxval(abs(pt%p - pex))/sc)
            ew = max(ew, abs(pt%we - wex)/abs(wex))
         end do
         call check(s, npl >= n - 10 .and. ea <= 1.0e-10_wp .and. ep_ <= 1.0e-10_wp .and. &
                    ew <= 1.0e-10_wp, 'uniaxial strain to stretch '//fmt_e(lend(dir))// &
                    ': Cp^-1, P, W = (J28) to 1e-10 at '//its(npl)//' plastic steps '// &
                    '(errors '//fmt_e(ea)//fmt_e(ep_)//fmt_e(ew)//')')

         ! uniaxial stress along y, F = diag(lt, l, lt), F33 = lt (the axisymmetric kernel)
         sg = merge(1.0_wp, -1.0_wp, dir == 1)
         call uniaxial_stress_pp(lam, mu, Y_CU, sg, jst, bz, bt)
         ly = sqrt(bz)
         pt = new_point(prm)
         elastic_ok = .true.
         u = 1.0_wp
         do k = 1, 10
            l1 = 1.0_wp + 0.9_wp*(ly - 1.0_wp)*real(k, wp)/10.0_wp
            do it = 1, 50   ! lateral stretch u = lt^2 with tau_rr = 0
               du = (lam*log(l1*u) + mu*(u - 1.0_wp))/(lam/u + mu)
               u = u - du
               if (abs(du) < 1.0e-16_wp) exit
            end do
            call kstep(prm, 0.0_wp, [sqrt(u), 0.0_wp, 0.0_wp, l1, sqrt(u)], pt)
            elastic_ok = elastic_ok .and. pt%ep(1) == 0.0_wp .and. abs(pt%p(1)) < 1.0e-6_wp*Y_CU
         end do
         call check(s, elastic_ok, 'uniaxial stress, elastic part: no yield, tau_rr = 0')
         ea = 0.0_wp
         ep_ = 0.0_wp
         el = 0.0_wp
         npl = 0
         do k = 1, n
            t = 1.0_wp
            if (k < n) t = ((real(k, wp) + 0.4_wp*(rnd(seed) - 0.5_wp))/real(n, wp))**1.3_wp
            l1 = ly + (lend(dir) - ly)*t
            lt = sqrt(jst/l1)
            call kstep(prm, 0.0_wp, [lt, 0.0_wp, 0.0_wp, l1, lt], pt)
            if (pt%ep(1) > 0.0_wp) npl = npl + 1
            aex = [bt/lt**2, 0.0_wp, bz/l1**2, bt/lt**2]
            pex = [0.0_wp, 0.0_wp, 0.0_wp, sg*Y_CU/l1, 0.0_wp]
            ea = max(ea, maxval(abs([pt%a11(1), pt%a12(1), pt%a22(1), pt%a33(1)] - aex)))
            ep_ = max(ep_, maxval(abs(pt%p - pex))/(Y_CU/l1))
            el = max(el, abs(mises([lt, 0.0_wp, 0.0_wp, l1, lt], pt%p) - Y_CU)/Y_CU)
         end do
         call check(s, npl == n .and. ea <= 1.0e-10_wp .and. ep_ <= 1.0e-10_wp, &
                    'uniaxial stress (F33 /= 1) to stretch '//fmt_e(lend(dir))// &
                    ': P = (0, sY/l, 0),'// &
                    ' Cp^-1 = (J29) to 1e-10 at every step (errors '//fmt_e(ea)//fmt_e(ep_)//')')
         call check(s, el <= 1.0e-12_wp, 'uniaxial stress: Kirchhoff von Mises = Y to 1e-12 ('// &
                    fmt_e(el)//')')
      end do
   end subroutine test_uniaxial_closed_form

   ! ---------------------------------------------------------------- discrete reference

   !> The kernel against the quad-precision discrete map on every law and path.
   subroutine test_discrete_reference(s)
      type(suite_t), intent(inout) :: s
      integer :: kind, path
      call section(s, 'plasticity: kernel = independent quad-precision discrete map (1e-10)')
      do kind = M_PP, M_JC
         do path = PATH_SHEAR, PATH_UNIAXIAL_STRAIN
            call compare_path(s, kind, path, 1.0_wp, 400)
         end do
      end do
      ! one large step from the virgin state (power law n < 1 starts at ep = 0)
      call compare_path(s, M_POW, PATH_SHEAR, 0.5_wp, 1)
      call compare_path(s, M_JC, PATH_EXTENSION, 0.5_wp, 1)
   end subroutine test_discrete_reference

   !> Drive kernel and reference along a path to tend in n steps (dt: a strain rate of order
   !> 1e3/s for Johnson-Cook); check agreement, consistency and D >= 0 at every step.
   subroutine compare_path(s, kind, path, tend, n)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: kind, path, n
      real(wp), intent(in) :: tend
      type(j2_param_t) :: prm
      type(point_t) :: pt
      type(ref_t) :: r
      real(wp) :: f(5), dt, ea, ee, epp, ew, ed, ey, et, ec, dmin, sc, dsum
      real(qp) :: rsum
      integer :: k, npl, nrpl
      character(len=:), allocatable :: label

      prm = material(kind)
      label = trim(MNAME(kind))//' '//trim(PNAME(path))
      if (n == 1) label = label//' (one step)'
      dt = 1.0e-3_wp*tend/real(n, wp)
      pt = new_point(prm)
      r%temp = real(pt%temp(1), qp)
      ea = 0.0_wp
      ee = 0.0_wp
      epp = 0.0_wp
      ew = 0.0_wp
      ed = 0.0_wp
      ey = 0.0_wp
      et = 0.0_wp
      ec = 0.0_wp
      dmin = 0.0_wp
      dsum = 0.0_wp
      rsum = 0.0_qp
      npl = 0
      nrpl = 0
      do k = 1, n
         call path_f(path, tend*real(k, wp)/real(n, wp), f)
         call kstep(prm, dt, f, pt)
         call ref_step(lam, mu, prm, dt, f, r)
         if (pt%dwp > 0.0_wp) then
            npl = npl + 1
            ec = max(ec, abs(mises(f, pt%p) - pt%ys)/pt%ys)
         end if
         if (r%dwp > 0.0_qp) nrpl = nrpl + 1
         dmin = min(dmin, pt%dwp)
         dsum = dsum + pt%dwp
         rsum = rsum + r%dwp
         sc = max(real(maxval(abs(r%p)), wp), real(r%ys, wp))
         ea = max(ea, maxval(abs(real([r%a11, r%a12, r%a22, r%a33], wp) &
                                 - [pt%a11(1), pt%a12(1), pt%a22(1), pt%a33(1)])))
         if (r%ep > 0.0_qp) ee = max(ee, abs(pt%ep(1) - real(r%ep, wp))/real(r%ep, wp))
         epp = max(epp, maxval(abs(real(r%p, wp) - pt%p))/sc)
         ! W is a small difference of terms of size mu |F|^2: its round-off scales with those
         ew = max(ew, abs(pt%we - real(r%we, wp))/(mu*sum(f*f)))
         ey = max(ey, abs(pt%ys - real(r%ys, wp))/real(r%ys, wp))
         if (rsum > 0.0_qp) ed = max(ed, abs(dsum - real(rsum, wp))/real(rsum, wp))
         if (kind == M_JC) et = max(et, abs(pt%temp(1) - real(r%temp, wp))/real(r%temp, wp))
      end do
      call check(s, npl == nrpl .and. npl >= n*9/10 .and. &
                 max(ea, ee, epp, ew, ed, ey, et) <= 1.0e-10_wp, &
                 label//': Cp^-1, ep, P, W, sum D, Y, T to 1e-10 ('//its(npl)// &
                 ' plastic steps; max rel '//fmt_e(max(ea, ee, epp, ew, ed, ey, et))//')', &
                 fmt_e(ea)//fmt_e(ee)//fmt_e(epp)//fmt_e(ew)//fmt_e(ed)//fmt_e(ey)//fmt_e(et))
      call check(s, ec <= 1.0e-12_wp .and. dmin >= 0.0_wp, label//': q(P) = Y to 1e-12 ('// &
                 fmt_e(ec)//'), D >= 0 at every step')
   end subroutine compare_path

   ! ---------------------------------------------------------------- continuous model

   !> First-order convergence to the continuous model integrated by RK4.
   subroutine test_continuous_model(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'plasticity: convergence to the continuous model (RK4 reference)')
      call converge_path(s, M_PP, PATH_SHEAR)
      call converge_path(s, M_LIN, PATH_SHEAR)
      call converge_path(s, M_SAT, PATH_SHEAR)
      call converge_path(s, M_LIN, PATH_EXTENSION)
   end subroutine test_continuous_model

   !> Error of a kernel state (b_e, ep) against a reference: max(mu |db|/Y0, |dep|/ep).
   pure real(wp) function state_error(y, yref) result(e)
      real(wp), intent(in) :: y(5), yref(5)
      e = max(maxval(abs(y(1:4) - yref(1:4)))*mu/Y_CU, abs(y(5) - yref(5))/yref(5))
   end function state_error

   !> Kernel on one elastic step to first yield, then nsteps equal steps to t = 1, against
   !> the RK4 solution (40 000 steps, checked against 80 000).
   subroutine converge_path(s, kind, path)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: kind, path
      type(j2_param_t) :: prm
      type(point_t) :: pt
      real(wp) :: ty, yref(5), yref2(5), f(5), yk(5, 3), err(3), eself, erich
      logical :: ok1, ok2
      integer :: i, k, nn
      character(len=:), allocatable :: label

      prm = material(kind)
      label = trim(MNAME(kind))//' '//trim(PNAME(path))
      ty = yield_onset(mu, prm%y0, path, 1.0_wp)
      call ref_ode(mu, prm, path, ty, 1.0_wp, 40000, yref, ok1)
      call ref_ode(mu, prm, path, ty, 1.0_wp, 80000, yref2, ok2)
      eself = state_error(yref, yref2)
      call check(s, ok1 .and. ok2, label//': RK4 reference loads plastically throughout')
      do i = 1, 3
         nn = 100*2**i
         pt = new_point(prm)
         call path_f(path, ty, f)
         call kstep(prm, 0.0_wp, f, pt)
         do k = 1, nn
            call path_f(path, ty + (1.0_wp - ty)*real(k, wp)/real(nn, wp), f)
            call kstep(prm, 0.0_wp, f, pt)
         end do
         yk(1:4, i) = elastic_b(f, pt)
         yk(5, i) = pt%ep(1)
         err(i) = state_error(yk(:, i), yref)
      end do
      erich = state_error(2.0_wp*yk(:, 3) - yk(:, 2), yref)
      call check(s, eself <= 1.0e-3_wp*erich, label//': RK4 at 40 000 and 80 000 steps agree to '// &
                 fmt_e(eself)//', 1000 x below the smallest difference it judges')
      call check(s, err(1)/err(2) >= 1.8_wp .and. err(1)/err(2) <= 2.2_wp .and. &
                 err(2)/err(3) >= 1.8_wp .and. err(2)/err(3) <= 2.2_wp, label// &
                 ': first order, errors at 200/400/800 steps '//fmt_e(err(1))//fmt_e(err(2))// &
                 fmt_e(err(3)))
      call check(s, erich <= 0.1_wp*err(3), label//': Richardson extrapolate 10x closer ('// &
                 fmt_e(erich)//')')
   end subroutine converge_path

   ! ---------------------------------------------------------------- objectivity

   !> A superposed rotation growing to 90 degrees leaves the rotated-back stress and the history.
   subroutine test_objectivity(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'plasticity: objectivity under a superposed rotation to 90 degrees')
      call rotated_path(s, M_PP, PATH_SHEAR)
      call rotated_path(s, M_SAT, PATH_SHEAR)
      call rotated_path(s, M_JC, PATH_EXTENSION)
   end subroutine test_objectivity

   subroutine rotated_path(s, kind, path)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: kind, path
      integer, parameter :: n = 400
      type(j2_param_t) :: prm
      type(point_t) :: pt, ptr
      real(wp) :: f(5), fr(5), pb(5), c, sn, th, eh, es, ew, ed, dt
      integer :: k

      prm = material(kind)
      pt = new_point(prm)
      ptr = new_point(prm)
      dt = 1.0e-6_wp
      eh = 0.0_wp
      es = 0.0_wp
      ew = 0.0_wp
      ed = 0.0_wp
      do k = 1, n
         call path_f(path, real(k, wp)/real(n, wp), f)
         th = 0.5_wp*PI*real(k, wp)/real(n, wp)
         c = cos(th)
         sn = sin(th)
         fr = [c*f(1) - sn*f(3), c*f(2) - sn*f(4), sn*f(1) + c*f(3), sn*f(2) + c*f(4), f(5)]
         call kstep(prm, dt, f, pt)
         call kstep(prm, dt, fr, ptr)
         pb = [c*ptr%p(1) + sn*ptr%p(3), c*ptr%p(2) + sn*ptr%p(4), -sn*ptr%p(1) + c*ptr%p(3), &
               -sn*ptr%p(2) + c*ptr%p(4), ptr%p(5)]
         eh = max(eh, maxval(abs([ptr%a11(1) - pt%a11(1), ptr%a12(1) - pt%a12(1), &
                                 ptr%a22(1) - pt%a22(1), ptr%a33(1) - pt%a33(1)])), &
                  abs(ptr%ep(1) - pt%ep(1))/max(pt%ep(1), 1.0e-3_wp), &
                  abs(ptr%temp(1) - pt%temp(1))/max(pt%temp(1), 1.0_wp))
         es = max(es, maxval(abs(pb - pt%p))/max(maxval(abs(pt%p)), pt%ys))
         ew = max(ew, abs(ptr%we - pt%we)/(mu*sum(f*f)))
         ed = max(ed, abs(ptr%dwp - pt%dwp)/max(pt%dwp, pt%ys*1.0e-6_wp))
      end do
      call check(s, pt%ep(1) > 0.1_wp .and. max(eh, es, ew, ed) <= 1.0e-12_wp, &
                 trim(MNAME(kind))//' '//trim(PNAME(path))//': history, Q^T P, W (of mu |F|^2), '// &
                 'D equal to 1e-12 at all 400 steps (max '//fmt_e(eh)//fmt_e(es)//fmt_e(ew)// &
                 fmt_e(ed)//')')
   end subroutine rotated_path

   ! ---------------------------------------------------------------- incompressibility

   !> det Cp^-1 = 1 to round-off after many plastic steps.
   subroutine test_incompressibility(s)
      type(suite_t), intent(inout) :: s
      type(j2_param_t) :: prm
      type(point_t) :: pt
      real(wp) :: f(5), dmax
      integer :: k, path, npl
      integer, parameter :: n = 2000

      call section(s, 'plasticity: plastic incompressibility det Cp^-1 = 1')
      do path = PATH_SHEAR, PATH_EXTENSION
         prm = material(merge(M_SAT, M_JC, path == PATH_SHEAR))
         pt = new_point(prm)
         dmax = 0.0_wp
         npl = 0
         do k = 1, n
            call path_f(path, 2.0_wp*real(k, wp)/real(n, wp), f)
            call kstep(prm, 1.0e-6_wp, f, pt)
            if (pt%dwp > 0.0_wp) npl = npl + 1
            dmax = max(dmax, abs(det_dev(pt)))
         end do
         call check(s, npl > n - 20 .and. dmax <= 1.0e-14_wp, trim(PNAME(path))//' to 200 %, '// &
                    its(npl)//' plastic steps: max |det Cp^-1 - 1| = '//fmt_e(dmax))
      end do
   end subroutine test_incompressibility

   ! ---------------------------------------------------------------- energy

   !> From first yield (one elastic step) to t = 1 in 200, 400, 800 equal steps: W(end) - W(yield)
   !> + sum D = integral of P:dF (trapezoid) up to an error that falls at first order (J27).
   subroutine test_energy(s)
      type(suite_t), intent(inout) :: s
      type(j2_param_t) :: prm
      type(point_t) :: pt
      real(wp) :: f(5), fo(5), po(5), work, dsum, ydep, epo, err(3), erry(3), ty, w0
      integer :: i, k, nn, kind, path

      call section(s, 'plasticity: the dissipation closes the energy balance')
      do path = PATH_SHEAR, PATH_EXTENSION
         do kind = M_LIN, M_SAT
            prm = material(kind)
            ty = yield_onset(mu, prm%y0, path, 1.0_wp)
            do i = 1, 3
               nn = 100*2**i
               pt = new_point(prm)
               call path_f(path, ty, fo)
               call kstep(prm, 0.0_wp, fo, pt)
               po = pt%p
               w0 = pt%we
               work = 0.0_wp
               dsum = 0.0_wp
               ydep = 0.0_wp
               do k = 1, nn
                  call path_f(path, ty + (1.0_wp - ty)*real(k, wp)/real(nn, wp), f)
                  epo = pt%ep(1)
                  call kstep(prm, 0.0_wp, f, pt)
                  work = work + 0.5_wp*sum((po + pt%p)*(f - fo))
                  dsum = dsum + pt%dwp
                  ydep = ydep + pt%ys*(pt%ep(1) - epo)
                  fo = f
                  po = pt%p
               end do
               err(i) = abs(work - (pt%we - w0) - dsum)/dsum
               erry(i) = abs(work - (pt%we - w0) - ydep)/ydep
            end do
            call check(s, err(1)/err(2) >= 1.8_wp .and. err(1)/err(2) <= 2.2_wp .and. &
                       err(2)/err(3) >= 1.8_wp .and. err(2)/err(3) <= 2.2_wp, &
                       trim(MNAME(kind))//' '//trim(PNAME(path))//': |work - W - sum D|/sum D at '// &
                       '200/400/800 steps '//fmt_e(err(1))//fmt_e(err(2))//fmt_e(err(3))// &
                       ' (with Y dep: '//fmt_e(erry(1))//fmt_e(erry(2))//fmt_e(erry(3))//')')
         end do
      end do
   end subroutine test_energy

   ! ---------------------------------------------------------------- laws

   subroutine test_laws(s)
      type(suite_t), intent(inout) :: s
      type(j2_param_t) :: prm
      type(point_t) :: pt
      real(wp) :: y, dy, yp, ym, ex, f(5), dt, epo, to, err, dsum, t0, ts
      integer :: k

      call section(s, 'plasticity: hardening laws, rate, thermal softening, heating')
      ! saturation
      prm = material(M_SAT)
      call check(s, j2_static_yield(prm, 0.0_wp, 0.0_wp) == Y_CU, 'MISEs: Y(0) = Y0 exactly')
      ex = Y_CU + 200.0e6_wp*(1.0_wp - exp(-3.0_wp)) + 50.0e6_wp*0.3_wp
      call check_close(s, j2_static_yield(prm, 0.3_wp, 0.0_wp), ex, 1.0e-15_wp*ex, &
                       'MISEs: Y(0.3) = Y0 + (Yinf - Y0)(1 - exp(-beta ep)) + Hiso ep')
      call slope_check(s, prm, 0.2_wp, 0.1_wp, 'MISEs')
      prm%hiso = 0.0_wp
      call check_close(s, j2_static_yield(prm, 5.0_wp, 0.0_wp), 600.0e6_wp, 1.0e-15_wp*600.0e6_wp, &
                       'MISEs saturates: Y(ep = 5) = Yinf when Hiso = 0')
      ! power law, n < 1
      prm = material(M_POW)
      call check(s, j2_static_yield(prm, 0.0_wp, 0.0_wp) == 90.0e6_wp, &
                 'POWEr: Y(0) = A exactly (n = 0.31)')
      call j2_flow_stress(prm, 0.0_wp, 1.0e-12_wp, 0.0_wp, 0.0_wp, y, dy)
      ex = 90.0e6_wp + 292.0e6_wp*1.0e-12_wp**0.31_wp
      call check(s, abs(y - ex) <= 1.0e-15_wp*ex .and. dy > 1.0e14_wp .and. dy < huge(1.0_wp), &
                 'POWEr: Y(1e-12) = A + B ep^n, slope large and finite near ep = 0')
      call slope_check(s, prm, 0.1_wp, 0.05_wp, 'POWEr')
      ! Johnson-Cook
      prm = material(M_JC)
      call check(s, j2_static_yield(prm, 0.0_wp, 250.0_wp) == 90.0e6_wp, &
                 'JOHNson: T below Troom clipped (T* = 0)')
      call check(s, j2_static_yield(prm, 0.5_wp, 1400.0_wp) == 0.0_wp, &
                 'JOHNson: T above Tmelt clipped (T* = 1, Y = 0)')
      ts = (800.0_wp - 293.0_wp)/(1356.0_wp - 293.0_wp)
      ex = (90.0e6_wp + 292.0e6_wp*0.5_wp**0.31_wp)*(1.0_wp + 0.025_wp*log(1.0e-3_wp/1.0e-6_wp)) &
           *(1.0_wp - ts**1.09_wp)
      call j2_flow_stress(prm, 0.499_wp, 1.0e-3_wp, 1.0e-6_wp, 800.0_wp, y, dy)
      call check_close(s, y, ex, 1.0e-14_wp*ex, 'JOHNson: Y(ep, rate 1e3/s, T = 800) by (J16)')
      call j2_flow_stress(prm, 0.499_wp, 1.0e-7_wp, 1.0e-6_wp, 800.0_wp, y, dy)
      call j2_flow_stress(prm, 0.499_wp + 1.0e-7_wp, 0.0_wp, 1.0e-6_wp, 800.0_wp, yp, dy)
      call check(s, y == yp, 'JOHNson: rate below epsdot0 has factor 1')
      call slope_check(s, prm, 0.3_wp, 0.01_wp, 'JOHNson')
      ! along a path: Y of every step by (J16) from the kernel's history, heating (J17)
      dt = 1.0e-6_wp
      pt = new_point(prm)
      t0 = pt%temp(1)
      err = 0.0_wp
      dsum = 0.0_wp
      do k = 1, 400
         call path_f(PATH_EXTENSION, real(k, wp)/400.0_wp, f)
         epo = pt%ep(1)
         to = pt%temp(1)
         call kstep(prm, dt, f, pt)
         dsum = dsum + pt%dwp
         if (pt%dwp > 0.0_wp) then
            ts = (to - 293.0_wp)/(1356.0_wp - 293.0_wp)
            ex = (90.0e6_wp + 292.0e6_wp*pt%ep(1)**0.31_wp)*(1.0_wp + 0.025_wp* &
                 log(max((pt%ep(1) - epo)/dt, 1.0_wp)))*(1.0_wp - ts**1.09_wp)
            err = max(err, abs(pt%ys - ex)/ex, abs(mises(f, pt%p) - ex)/ex)
         end if
      end do
      call check(s, err <= 1.0e-12_wp, 'JOHNson path: Y = (J16) with the step''s rate and T(n); '// &
                 'q(P) = Y to 1e-12 ('//fmt_e(err)//')')
      call check_close(s, pt%temp(1) - t0, 0.9_wp*dsum/(8930.0_wp*383.0_wp), &
                       1.0e-12_wp*(pt%temp(1) - t0), 'JOHNson path: T - T0 = 0.9 sum D/(rho c)')
      ! melting: the deviator vanishes
      pt = new_point(prm)
      pt%temp = 1356.0_wp
      f = [1.0_wp, 0.05_wp, 0.0_wp, 1.0_wp, 1.0_wp]
      call kstep(prm, dt, f, pt)
      call check(s, pt%ys == 0.0_wp .and. mises(f, pt%p) <= 1.0e-12_wp*mu*0.05_wp .and. &
                 pt%ep(1) > 0.0_wp, 'JOHNson at Tmelt: Y = 0, the return removes the whole deviator')
      ! heating with a law whose Y ignores T
      prm = material(M_LIN)
      prm%cheat = 383.0_wp
      call check(s, j2_has_temperature(prm) .and. .not. j2_has_temperature(material(M_LIN)) .and. &
                 j2_has_temperature(material(M_JC)), 'temperature history: JOHNson or heating only')
      pt = new_point(prm)
      t0 = pt%temp(1)
      dsum = 0.0_wp
      do k = 1, 100
         call path_f(PATH_SHEAR, real(k, wp)/100.0_wp, f)
         call kstep(prm, dt, f, pt)
         dsum = dsum + pt%dwp
      end do
      call check_close(s, pt%temp(1) - t0, 0.9_wp*dsum/(8930.0_wp*383.0_wp), &
                       1.0e-12_wp*(pt%temp(1) - t0), &
                       'MISEs with SPECific heat: T - T0 = 0.9 sum D/(rho c)')
      call j2_flow_stress(prm, 0.2_wp, 0.0_wp, 0.0_wp, 0.0_wp, y, dy)
      call j2_flow_stress(prm, 0.2_wp, 0.0_wp, 0.0_wp, 5000.0_wp, ym, dy)
      call check(s, y == ym, 'MISEs: Y independent of T')
   end subroutine test_laws

   !> dY/d(dep) of j2_flow_stress against a central difference at ep0 + dep.
   subroutine slope_check(s, prm, ep0, dep, name)
      type(suite_t), intent(inout) :: s
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep0, dep
      character(len=*), intent(in) :: name
      real(wp) :: y, dy, yp, ym, d, h
      h = 1.0e-6_wp*dep
      call j2_flow_stress(prm, ep0, dep, 1.0e-4_wp, 500.0_wp, y, dy)
      call j2_flow_stress(prm, ep0, dep + h, 1.0e-4_wp, 500.0_wp, yp, d)
      call j2_flow_stress(prm, ep0, dep - h, 1.0e-4_wp, 500.0_wp, ym, d)
      call check_close(s, dy, (yp - ym)/(2.0_wp*h), 1.0e-6_wp*abs(dy), &
                       name//': slope = central difference')
   end subroutine slope_check

   ! ---------------------------------------------------------------- parameter checks

   subroutine test_parameters(s)
      type(suite_t), intent(inout) :: s
      type(j2_param_t) :: p
      real(wp) :: zero

      call section(s, 'plasticity: parameter checks for the deck reader')
      zero = 0.0_wp
      call expect(s, material(M_PP), '', 'MISEs perfect plasticity accepted')
      call expect(s, material(M_SAT), '', 'MISEs saturation + HARDening accepted')
      call expect(s, material(M_POW), '', 'POWEr accepted')
      call expect(s, material(M_JC), '', 'JOHNson-cook with SPECific heat accepted')
      p = material(M_PP)
      p%yinf = 0.0_wp
      call expect(s, p, '', 'MISEs with beta = 0: Yinf = 0 accepted (not used)')
      p = material(M_PP)
      p%y0 = -1.0_wp
      call expect(s, p, 'Y0', 'negative Y0 refused')
      p%y0 = 0.0_wp
      call expect(s, p, 'Y0', 'zero Y0 refused')
      p%y0 = zero/zero
      call expect(s, p, 'Y0', 'NaN Y0 refused')
      p = material(M_SAT)
      p%yinf = 300.0e6_wp
      call expect(s, p, 'soften', 'Yinf < Y0 with beta > 0 refused as softening')
      p = material(M_SAT)
      p%beta = -1.0_wp
      call expect(s, p, 'beta', 'negative beta refused')
      p = material(M_LIN)
      p%hiso = -1.0e6_wp
      call expect(s, p, 'Hiso', 'negative Hiso refused')
      p = material(M_LIN)
      p%hkin = 1.0e6_wp
      call expect(s, p, 'kinematic hardening', 'Hkin /= 0 refused as not implemented')
      p = material(M_POW)
      p%hiso = 1.0e6_wp
      call expect(s, p, 'belongs to PLAStic MISEs', 'HARDening with POWEr refused')
      p%hiso = 0.0_wp
      p%en = 0.0_wp
      call expect(s, p, 'exponent n', 'POWEr n = 0 refused')
      p = material(M_POW)
      p%a = 0.0_wp
      call expect(s, p, 'A must be positive', 'POWEr A = 0 refused')
      p = material(M_POW)
      p%b = -1.0_wp
      call expect(s, p, 'B must be', 'POWEr B < 0 refused')
      p = material(M_JC)
      p%tmelt = p%troom
      call expect(s, p, 'Tmelt', 'JOHNson Tmelt <= Troom refused')
      p = material(M_JC)
      p%m = 0.0_wp
      call expect(s, p, 'thermal exponent m', 'JOHNson m = 0 refused')
      p = material(M_JC)
      p%crate = -0.1_wp
      call expect(s, p, 'rate coefficient C', 'JOHNson C < 0 refused')
      p = material(M_JC)
      p%epsdot0 = 0.0_wp
      call expect(s, p, 'epsdot0', 'JOHNson epsdot0 = 0 refused')
      p = material(M_JC)
      p%cheat = -1.0_wp
      call expect(s, p, 'SPECific heat', 'negative specific heat refused')
      p = material(M_JC)
      p%rho = 0.0_wp
      call expect(s, p, 'DENSity', 'heating without density refused')
      p = j2_param_t()
      call expect(s, p, 'PLAStic law', 'no law refused')
   end subroutine test_parameters

   !> j2_check_parameters gives '' (want = '') or a message containing want.
   subroutine expect(s, p, want, name)
      type(suite_t), intent(inout) :: s
      type(j2_param_t), intent(in) :: p
      character(len=*), intent(in) :: want, name
      character(len=:), allocatable :: msg
      call j2_check_parameters(p, msg)
      if (len(want) == 0) then
         call check(s, len(msg) == 0, name, msg)
      else
         call check(s, index(msg, want) > 0, name, 'message: "'//msg//'"')
         write (output_unit, '(a)') '         "'//msg//'"'
      end if
   end subroutine expect

end module test_plasticity
