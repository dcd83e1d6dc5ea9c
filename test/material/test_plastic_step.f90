!> The stable step of crushed one-point elements (doc/hourglass.md (H18)-(H20), doc/stability/by_hand.md
!> section 1k): a generator of crushed states, plastic and elastic, with either hourglass
!> control, and the worst ratio of the step exic takes from a state to the exact limit
!> 2/omega_max of the states that step can reach.
!>
!> A case: a reference rectangle (aspect 1, 2 or 4, turned by 30 degrees), crushed along its
!> long side to 0.7, 0.5 or 0.35 of its length (isochoric) and distorted by the hourglass mode
!> until its smallest corner ratio r (H13) is 0.62, 0.56, 0.52, 0.5 or 0.45, reached along a
!> straight path of 40 increments of q4g_force (the plastic history evolves along it); nu from 0
!> to 0.49. From that state A with nodal velocities v = w (L/dt0) d (d the hourglass mode that
!> closes the corner further, w = 0 .. 0.25, dt0 the step without velocities), exic's step dt
!> (the force pass's estimate with the kinematic limit (H19)) moves the element to B = A + dt v.
!> The exact limit of a state: 2/omega_max of K x = omega^2 M x with K by central differences
!> of the forces, the plastic history frozen and the yield stress out of reach (the elastic
!> unloading tangent, the stiffest the return can give), M the element's lumped mass. The ratio
!> dt / min(exact(A), exact(B)) must stay at or below 1 for w <= 0.05 (a corner's nodes moving
!> apart by up to 5 % of the element's size in a step; (H19) holds the first-order change of
!> ln r below 1/4, which faster motions exceed at second order) on every plastic state and the
!> elastic ones crushed to 0.7 with the physical control. The elastic states crushed to 0.5 and
!> 0.35 (stretches of 2 and 2.9) and the elastic states with the FB control are reported only: at
!> such elastic stretches the neo-Hookean tangent exceeds the wave speed of the estimate, which
!> depends on the volume ratio alone (q4_stable_dt; with FB at nu = 0, aspect 4 crushed to 0.7,
!> the step is 1.03 of the exact limit at rest): the elastic law's estimate, not the crushed
!> plastic element's.
module test_plastic_step
   use exic_base_kinds, only: wp
   use exic_material_material, only: lame_from_young, HOURGLASS_STIFFNESS, HOURGLASS_PHYSICAL
   use exic_material_j2_hardening, only: j2_param_t, J2_MISES
   use exic_material_law, only: law_make, LAW_J2, LAW_NEOHOOKEAN
   use exic_element_quad4, only: q4_lumped_mass
   use exic_element_q4_general, only: q4_solid_t, q4g_init, q4g_force, q4g_hist_init
   use exic_element_q4_plastic_work, only: NBOOK
   use exic_linalg_lapack, only: dsygv
   use testing, only: suite_t, check, section
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: run_plastic_step_tests

   real(wp), parameter :: YOUNG = 1.0_wp, RHO = 1.3_wp
   integer, parameter :: NPATH = 40
   !> history values per point of the plastic one-point element: J2 (5) and the booking (J31)
   integer, parameter :: NH = 5 + NBOOK
   !> the speeds w(1:NWCHECK) are asserted, the faster ones reported
   integer, parameter :: NWCHECK = 3

contains

   subroutine run_plastic_step_tests(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: aspects(3) = [1.0_wp, 2.0_wp, 4.0_wp]
      real(wp), parameter :: crush(3) = [0.7_wp, 0.5_wp, 0.35_wp]
      real(wp), parameter :: rtarget(5) = [0.62_wp, 0.56_wp, 0.52_wp, 0.5_wp, 0.45_wp]
      real(wp), parameter :: nus(4) = [0.0_wp, 0.3_wp, 0.45_wp, 0.49_wp]
      real(wp), parameter :: speeds(5) = [0.0_wp, 0.02_wp, 0.05_wp, 0.1_wp, 0.25_wp]
      character(len=*), parameter :: names(4) = [character(len=24) :: 'plastic, physical', &
                                                 'elastic, physical', 'plastic, FB 0.1', 'elastic, FB 0.1']
      real(wp) :: rmax(4), rmin(4), ratio, worst_case(4, 5), wmax(4, 5), xmax(4)
      integer :: ncase(4), nfail(4), kind, ia, ic, ir, inu, iw
      logical :: ok
      character(len=200) :: buf

      call section(s, 'crushed one-point elements: step against the exact limit (section 1k)')
      rmax = 0.0_wp
      rmin = huge(1.0_wp)
      ncase = 0
      nfail = 0
      worst_case = 0.0_wp
      wmax = 0.0_wp
      xmax = 0.0_wp
      do kind = 1, 4
         do ia = 1, size(aspects)
            do ic = 1, size(crush)
               do ir = 1, size(rtarget)
                  do inu = 1, size(nus)
                     do iw = 1, size(speeds)
                        call one_case(kind, aspects(ia), crush(ic), rtarget(ir), nus(inu), speeds(iw), &
                                      ratio, ok)
                        ncase(kind) = ncase(kind) + 1
                        if (.not. ok) then
                           nfail(kind) = nfail(kind) + 1
                           cycle
                        end if
                        wmax(kind, iw) = max(wmax(kind, iw), ratio)
                        ! elastic stretches of 2 and more: reported (the wave speed of (7.2) is
                        ! that of the volume ratio alone), not asserted
                        if (kind == 2 .or. kind == 4) then
                           if (ic > 1 .or. kind == 4) then
                              xmax(kind) = max(xmax(kind), ratio)
                              cycle
                           end if
                        end if
                        if (iw > NWCHECK) cycle
                        if (ratio > rmax(kind)) worst_case(kind, :) = [aspects(ia), crush(ic), &
                                                                        rtarget(ir), nus(inu), speeds(iw)]
                        rmax(kind) = max(rmax(kind), ratio)
                        rmin(kind) = min(rmin(kind), ratio)
                     end do
                  end do
               end do
            end do
         end do
         if (kind == 4) rmin(kind) = 0.0_wp
         write (buf, '(a,a,i0,a,f6.4,a,f6.4,a,5f6.3,a)') trim(names(kind)), ': ', ncase(kind), &
            ' cases, step/exact in [', rmin(kind), ', ', rmax(kind), '], worst at (aspect, crush, r, nu, w) = (', &
            worst_case(kind, :), ')'
         write (output_unit, '(a)') '   '//trim(buf)
         write (buf, '(a,5f7.4)') '   worst by w = 0, 0.02, 0.05, 0.1, 0.25:', wmax(kind, :)
         write (output_unit, '(a)') trim(buf)
         if (kind == 2 .or. kind == 4) then
            write (buf, '(a,f7.4)') '   not asserted (see the header), worst:', xmax(kind)
            write (output_unit, '(a)') trim(buf)
         end if
         call check(s, nfail(kind) == 0, trim(names(kind))//': every state valid, every eigenproblem solved')
         if (kind == 4) cycle
         call check(s, rmax(kind) <= 1.0_wp, trim(names(kind))//': step <= 2/omega_max of the states it '// &
                    'reaches (w <= 0.05)')
      end do
   end subroutine run_plastic_step_tests

   !> One case of the family (see the module's header); ok false when a state is not valid
   !> (an inverted element, no step) or an eigenproblem fails.
   subroutine one_case(kind, aspect, crush, rt, nu, w, ratio, ok)
      integer, intent(in) :: kind
      real(wp), intent(in) :: aspect, crush, rt, nu, w
      real(wp), intent(out) :: ratio
      logical, intent(out) :: ok
      type(q4_solid_t) :: o, oel
      type(j2_param_t) :: prm, pel
      real(wp) :: x0(2, 4), xm(2, 4), ua(2, 4), ub(2, 4), v(2, 4), d(2, 4), hist(NH, 1, 1), h0(NH, 1, 1)
      real(wp) :: m(4), lam, mu, c, fm(2, 2), rot(2, 2), dt0, dta, exa, exb, ell
      integer :: conn(4, 1), k, it
      logical :: plastic, phys
      real(wp), parameter :: hg(4) = [1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp]

      ok = .false.
      ratio = 0.0_wp
      plastic = kind == 1 .or. kind == 3
      phys = kind <= 2
      conn(:, 1) = [1, 2, 3, 4]
      call lame_from_young(YOUNG, nu, lam, mu)
      prm%law = J2_MISES
      prm%y0 = YOUNG/300.0_wp
      prm%yinf = prm%y0
      prm%hiso = 0.01_wp*YOUNG
      prm%rho = RHO
      pel = prm
      pel%y0 = huge(1.0_wp)
      pel%yinf = huge(1.0_wp)
      if (phys) then
         o = q4g_init(1, .false., .false., law_make(merge(LAW_J2, LAW_NEOHOOKEAN, plastic), lam, mu, RHO, prm), &
                        1.0_wp, HOURGLASS_PHYSICAL)
         oel = q4g_init(1, .false., .false., law_make(merge(LAW_J2, LAW_NEOHOOKEAN, plastic), lam, mu, RHO, pel), &
                        1.0_wp, HOURGLASS_PHYSICAL)
      else
         o = q4g_init(1, .false., .false., law_make(merge(LAW_J2, LAW_NEOHOOKEAN, plastic), lam, mu, RHO, prm), &
                        0.1_wp, HOURGLASS_STIFFNESS)
         oel = q4g_init(1, .false., .false., law_make(merge(LAW_J2, LAW_NEOHOOKEAN, plastic), lam, mu, RHO, pel), &
                        0.1_wp, HOURGLASS_STIFFNESS)
      end if
      ! the reference rectangle, turned by 30 degrees
      rot = reshape([cos(0.5235987755982988_wp), sin(0.5235987755982988_wp), &
                     -sin(0.5235987755982988_wp), cos(0.5235987755982988_wp)], [2, 2])
      x0 = matmul(rot, reshape([0.0_wp, 0.0_wp, aspect, 0.0_wp, aspect, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4]))
      ! crushed along the long side (isochoric), in the element's frame
      fm = matmul(rot, matmul(reshape([crush, 0.0_wp, 0.0_wp, 1.0_wp/crush], [2, 2]), transpose(rot)))
      xm = matmul(fm, x0)
      ! the hourglass mode along the crushed long side, its amplitude c found by bisection on
      ! the smallest corner ratio
      do k = 1, 4
         d(:, k) = hg(k)*rot(:, 1)*crush*aspect
      end do
      c = bisect_c(x0, xm, d, rt)
      ua = xm + c*d - x0
      ! the path, the plastic history evolving along it
      hist = 0.0_wp
      if (plastic) call q4g_hist_init(o, 1, hist)
      do it = 1, NPATH
         call forces(o, x0, conn, real(it, wp)/NPATH*ua, hist, .true.)
      end do
      h0 = hist
      m = 0.0_wp
      call q4_lumped_mass(1, 4, conn, x0, RHO, m)
      ! the step without velocities, then with v along the closing hourglass mode
      dt0 = step(o, x0, conn, ua, h0)
      if (.not. dt0 > 0.0_wp) return
      ell = sqrt(minval(m)/RHO)
      v = w*(ell/dt0)*d/sqrt(sum(d*d))
      if (ratio_of(x0, ua + 1.0e-6_wp*d) > ratio_of(x0, ua)) v = -v
      dta = step(o, x0, conn, ua, h0, v)
      if (.not. dta > 0.0_wp) return
      ub = ua + dta*v
      if (.not. (exact(oel, x0, conn, ua, h0, m, exa) .and. exact(oel, x0, conn, ub, h0, m, exb))) return
      ratio = dta/min(exa, exb)
      ok = .true.
   end subroutine one_case

   !> The amplitude c of the hourglass mode d that brings the smallest corner ratio of xm + c d
   !> (reference x0) to rt.
   real(wp) function bisect_c(x0, xm, d, rt) result(c)
      real(wp), intent(in) :: x0(2, 4), xm(2, 4), d(2, 4), rt
      real(wp) :: lo, hi
      integer :: it
      lo = 0.0_wp
      hi = 0.45_wp
      do it = 1, 60
         c = 0.5_wp*(lo + hi)
         if (ratio_of(x0, xm + c*d - x0) > rt) then
            lo = c
         else
            hi = c
         end if
      end do
   end function bisect_c

   !> The smallest corner ratio r_a (H13) of the element with reference corners x0 and
   !> displacement u.
   real(wp) function ratio_of(x0, u) result(r)
      real(wp), intent(in) :: x0(2, 4), u(2, 4)
      real(wp) :: x(2, 4)
      integer :: a, ip, ir
      x = x0 + u
      r = huge(1.0_wp)
      do a = 1, 4
         ip = modulo(a - 2, 4) + 1
         ir = modulo(a, 4) + 1
         r = min(r, (tri(x, ip, a, ir)/quad(x))/(tri(x0, ip, a, ir)/quad(x0)))
      end do
   contains
      real(wp) function tri(y, p, q, t)
         real(wp), intent(in) :: y(2, 4)
         integer, intent(in) :: p, q, t
         tri = (y(1, q) - y(1, p))*(y(2, t) - y(2, q)) - (y(2, q) - y(2, p))*(y(1, t) - y(1, q))
      end function tri
      real(wp) function quad(y)
         real(wp), intent(in) :: y(2, 4)
         quad = (y(1, 3) - y(1, 1))*(y(2, 4) - y(2, 2)) - (y(2, 3) - y(2, 1))*(y(1, 4) - y(1, 2))
      end function quad
   end function ratio_of

   !> One force pass (the history updated when keep).
   subroutine forces(o, x0, conn, u, hist, keep, f, d2, v)
      type(q4_solid_t), intent(in) :: o
      real(wp), intent(in) :: x0(2, 4), u(2, 4)
      integer, intent(in) :: conn(4, 1)
      real(wp), intent(inout) :: hist(NH, 1, 1)
      logical, intent(in) :: keep
      real(wp), intent(out), optional :: f(2, 4), d2
      real(wp), intent(in), optional :: v(2, 4)
      real(wp) :: ft(2, 4), h(NH, 1, 1), w, whg, wd, jm, dd
      integer :: eb, em, ef
      h = hist
      ft = 0.0_wp
      if (present(v)) then
         call q4g_force(o, 1, 4, conn, x0, u, 1.0_wp, h, ft, w, whg, wd, jm, eb, dd, em, ef, v)
      else
         call q4g_force(o, 1, 4, conn, x0, u, 1.0_wp, h, ft, w, whg, wd, jm, eb, dd, em, ef)
      end if
      if (keep) hist = h
      if (present(f)) f = ft
      if (present(d2)) d2 = merge(dd, 0.0_wp, eb == 0)
   end subroutine forces

   !> exic's step from the state (x0 + u, history h), with the velocities v when given.
   real(wp) function step(o, x0, conn, u, h, v) result(dt)
      type(q4_solid_t), intent(in) :: o
      real(wp), intent(in) :: x0(2, 4), u(2, 4), h(NH, 1, 1)
      integer, intent(in) :: conn(4, 1)
      real(wp), intent(in), optional :: v(2, 4)
      real(wp) :: ht(NH, 1, 1), d2
      ht = h
      call forces(o, x0, conn, u, ht, .false., d2=d2, v=v)
      dt = sqrt(d2)
   end function step

   !> The exact limit 2/omega_max of the state (x0 + u, frozen history h) under the law of oel
   !> (the elastic unloading tangent), lumped mass m; false when the state is inverted or the
   !> eigenproblem fails.
   logical function exact(oel, x0, conn, u, h, m, dtx) result(ok)
      type(q4_solid_t), intent(in) :: oel
      real(wp), intent(in) :: x0(2, 4), u(2, 4), h(NH, 1, 1), m(4)
      integer, intent(in) :: conn(4, 1)
      real(wp), intent(out) :: dtx
      real(wp) :: k(8, 8), mm(8, 8), ev(8), work(64), ub(2, 4), fp(2, 4), fm(2, 4), ht(NH, 1, 1), hh, d2
      integer :: j, info
      ok = .false.
      dtx = 0.0_wp
      ht = h
      call forces(oel, x0, conn, u, ht, .false., d2=d2)
      if (.not. d2 > 0.0_wp) return
      hh = 1.0e-7_wp*sqrt(minval(m)/RHO)
      do j = 1, 8
         ub = u
         ub(modulo(j - 1, 2) + 1, (j + 1)/2) = ub(modulo(j - 1, 2) + 1, (j + 1)/2) + hh
         call forces(oel, x0, conn, ub, ht, .false., f=fp)
         ub(modulo(j - 1, 2) + 1, (j + 1)/2) = ub(modulo(j - 1, 2) + 1, (j + 1)/2) - 2.0_wp*hh
         call forces(oel, x0, conn, ub, ht, .false., f=fm)
         k(:, j) = reshape(fp - fm, [8])/(2.0_wp*hh)
      end do
      k = 0.5_wp*(k + transpose(k))
      mm = 0.0_wp
      do j = 1, 8
         mm(j, j) = m((j + 1)/2)
      end do
      call dsygv(1, 'N', 'U', 8, k, 8, mm, 8, ev, work, size(work), info)
      if (info /= 0 .or. .not. ev(8) > 0.0_wp) return
      dtx = 2.0_wp/sqrt(ev(8))
      ok = .true.
   end function exact

end module test_plastic_step
