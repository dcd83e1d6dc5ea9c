!> Tests of the assumed-strain (physical) hourglass stabilization of the one-point quadrilateral
!> (doc/hourglass.md; src/exic/element/quad4.f90, asqbi_forces): zero for affine fields,
!> objective, forces = derivative of the energy at finite strain and rotation, the stable step
!> of the element holds, the bending energy of a rectangle is the beam's, and a cantilever of
!> one-point elements under pure bending gets the exact tip displacement (the 2x2 element locks;
!> the Flanagan-Belytschko form with 0.1 is shown beside them).
module test_hourglass
   use exic_material_law, only: neohookean_law, law_make, LAW_NEOHOOKEAN
   use exic_base_kinds, only: wp
   use exic_material_material, only: lame_from_young, HOURGLASS_STIFFNESS, HOURGLASS_PHYSICAL
   use exic_element_quad4, only: q4_force_1pt, q4_force_2x2, q4_lumped_mass, q4_stable_dt
   use exic_element_q4_general, only: q4_solid_t, q4g_init, q4g_force
   use exic_material_j2_hardening, only: j2_param_t
   use testing, only: suite_t, check, check_close, section, gradient_error
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   implicit none
   private

   public :: run_hourglass_tests

   interface
      subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
         import :: wp
         integer, intent(in) :: itype, n, lda, ldb, lwork
         character(len=1), intent(in) :: jobz, uplo
         real(wp), intent(inout) :: a(lda, *), b(ldb, *)
         real(wp), intent(out) :: w(*), work(*)
         integer, intent(out) :: info
      end subroutine dsygv
      subroutine dgesv(n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: wp
         integer, intent(in) :: n, nrhs, lda, ldb
         real(wp), intent(inout) :: a(lda, *), b(ldb, *)
         integer, intent(out) :: ipiv(*), info
      end subroutine dgesv
   end interface

   real(wp), parameter :: pi = 3.14159265358979323846_wp
   !> element kinds of these tests: one point + physical control, one point + FB 0.1, 2x2
   integer, parameter :: PHYS = 1, FB = 2, FULL = 3

contains

   subroutine run_hourglass_tests(s)
      type(suite_t), intent(inout) :: s
      call test_affine(s)
      call test_objective(s)
      call test_derivative(s)
      call test_axisymmetric(s)
      call test_stable_step(s)
      call test_bending_energy(s)
      call test_cantilever(s)
      call test_barrier_energy(s)
      call test_barrier_step(s)
      call test_barrier_fold(s)
   end subroutine run_hourglass_tests

   ! ---------------------------------------------------------------- helpers

   !> Park-Miller uniform number in (0, 1).
   function rnd(seed) result(r)
      integer(int64), intent(inout) :: seed
      real(wp) :: r
      seed = modulo(16807_int64*seed, 2147483647_int64)
      r = real(seed, wp)/2147483647.0_wp
   end function rnd

   pure function rot(th) result(r)
      real(wp), intent(in) :: th
      real(wp) :: r(2, 2)
      r = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
   end function rot

   !> A distorted 3 x 3-node patch of four elements (interior node 5).
   subroutine make_patch(x0, conn)
      real(wp), allocatable, intent(out) :: x0(:, :)
      integer, allocatable, intent(out) :: conn(:, :)
      x0 = reshape([0.0_wp, 0.0_wp, 1.1_wp, 0.1_wp, 2.0_wp, 0.0_wp, &
                    -0.1_wp, 0.9_wp, 0.9_wp, 1.2_wp, 2.1_wp, 1.0_wp, &
                    0.0_wp, 2.0_wp, 1.0_wp, 2.1_wp, 1.9_wp, 1.9_wp], [2, 9])
      conn = reshape([1, 2, 5, 4, 2, 3, 6, 5, 4, 5, 8, 7, 5, 6, 9, 8], [4, 4])
   end subroutine make_patch

   !> Internal force f (zeroed first), strain energy w and hourglass energy whg of elements
   !> (x0, conn) of kind ek; jmin and the squared stable step dt2 (density rho).
   subroutine force(ek, x0, conn, u, lambda, mu, f, w, whg, jmin, dt2, rho, v)
      integer, intent(in) :: ek
      real(wp), intent(in) :: x0(:, :), u(:, :), lambda, mu
      integer, intent(in) :: conn(:, :)
      real(wp), intent(out) :: f(:, :), w, whg, jmin
      real(wp), intent(out), optional :: dt2
      real(wp), intent(in), optional :: rho
      real(wp), intent(in), optional :: v(:, :)   !< nodal velocities (the physical control's step)
      real(wp) :: d, r
      integer :: eb, em, ef
      f = 0.0_wp
      whg = 0.0_wp
      r = 1.0_wp
      if (present(rho)) r = rho
      select case (ek)
      case (PHYS)
         call q4_force_1pt(size(conn, 2), size(x0, 2), conn, x0, u, neohookean_law(lambda, mu, r), 1.0_wp, f, w, whg, &
                           jmin, eb, d, em, ef, HOURGLASS_PHYSICAL, v)
      case (FB)
         call q4_force_1pt(size(conn, 2), size(x0, 2), conn, x0, u, neohookean_law(lambda, mu, r), 0.1_wp, f, w, whg, &
                           jmin, eb, d, em, ef, HOURGLASS_STIFFNESS)
      case default
         call q4_force_2x2(size(conn, 2), size(x0, 2), conn, x0, u, neohookean_law(lambda, mu, r), f, w, jmin, eb, &
                           d, em, ef)
      end select
      if (present(dt2)) dt2 = d
   end subroutine force

   !> Tangent stiffness at u = 0 by central differences of the force, (2 nnode)^2.
   subroutine tangent(ek, x0, conn, lambda, mu, h, kmat)
      integer, intent(in) :: ek
      real(wp), intent(in) :: x0(:, :), lambda, mu, h
      integer, intent(in) :: conn(:, :)
      real(wp), intent(out) :: kmat(:, :)
      real(wp), allocatable :: u(:, :), fp(:, :), fm(:, :)
      real(wp) :: w, whg, jmin
      integer :: j, n
      n = size(x0, 2)
      allocate (u(2, n), fp(2, n), fm(2, n))
      do j = 1, 2*n
         u = 0.0_wp
         u(modulo(j - 1, 2) + 1, (j + 1)/2) = h
         call force(ek, x0, conn, u, lambda, mu, fp, w, whg, jmin)
         u(modulo(j - 1, 2) + 1, (j + 1)/2) = -h
         call force(ek, x0, conn, u, lambda, mu, fm, w, whg, jmin)
         kmat(:, j) = reshape(fp - fm, [2*n])/(2.0_wp*h)
      end do
      kmat = 0.5_wp*(kmat + transpose(kmat))
   end subroutine tangent

   ! ---------------------------------------------------------------- tests

   !> An affine finite deformation (with a rotation) of a distorted patch: no hourglass energy
   !> or force, the mean part alone (the patch test of the one-point element holds).
   subroutine test_affine(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), f0(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: fm(2, 2), lam, mu, w, w0, whg, whg0, jmin
      call section(s, 'physical hourglass control: affine fields')
      call make_patch(x0, conn)
      call lame_from_young(1.0e4_wp, 0.3_wp, lam, mu)
      fm = matmul(rot(0.7_wp), reshape([1.3_wp, -0.15_wp, 0.3_wp, 0.8_wp], [2, 2]))
      u = matmul(fm, x0) - x0 + spread([0.4_wp, -2.0_wp], 2, 9)
      allocate (f(2, 9), f0(2, 9))
      call force(PHYS, x0, conn, u, lam, mu, f, w, whg, jmin)
      call force(FB, x0, conn, u, lam, mu, f0, w0, whg0, jmin)
      ! the FB control is zero on affine fields too: both are the mean part alone
      call check(s, abs(whg) <= 1e-20_wp*w .and. abs(whg0) <= 1e-20_wp*w, 'hourglass energy zero')
      call check(s, maxval(abs(f - f0)) <= 1e-13_wp*maxval(abs(f)), &
                 'forces = the mean part alone (as with a zero hourglass stiffness)')
      call check(s, maxval(abs(f(:, 5))) <= 1e-12_wp*maxval(abs(f)), 'zero net force at the interior node')
   end subroutine test_affine

   !> A non-affine finite deformation rotated by several angles: the same energies, the forces
   !> rotated.
   subroutine test_objective(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), ud(:, :), f(:, :), fr(:, :)
      integer, allocatable :: conn(:, :)
      real(wp), parameter :: angles(4) = [90.0_wp, 180.0_wp, 37.0_wp, -123.0_wp]
      real(wp) :: lam, mu, w, whg, wr, whgr, jmin, err, ehg, r(2, 2)
      integer :: i, k
      integer(int64) :: seed
      call section(s, 'physical hourglass control: objectivity')
      call make_patch(x0, conn)
      call lame_from_young(1.0e4_wp, 0.3_wp, lam, mu)
      allocate (ud(2, 9), f(2, 9), fr(2, 9), u(2, 9))
      seed = 2024_int64
      do i = 1, 9
         ud(:, i) = 0.25_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
      end do
      call force(PHYS, x0, conn, ud, lam, mu, f, w, whg, jmin)
      call check(s, jmin > 0.3_wp .and. whg > 1e-3_wp*w, 'deformed state valid, hourglass engaged')
      err = 0.0_wp
      ehg = 0.0_wp
      do k = 1, size(angles)
         r = rot(angles(k)*pi/180.0_wp)
         u = matmul(r, x0 + ud) - x0
         call force(PHYS, x0, conn, u, lam, mu, fr, wr, whgr, jmin)
         err = max(err, abs(wr - w)/w, maxval(abs(fr - matmul(r, f)))/maxval(abs(f)))
         ehg = max(ehg, abs(whgr - whg)/whg)
      end do
      call check(s, err <= 1e-12_wp .and. ehg <= 1e-12_wp, &
                 'rotated deformed state: same strain and hourglass energy, forces rotated')
   end subroutine test_objective

   !> f = dW/du (strain + hourglass) by central differences at a finite strain with a finite
   !> rotation of 50 degrees (the rotation term of (H12) is then large), nu = 0.3 and 0.49.
   subroutine test_derivative(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: lam, mu, w, whg, jmin, h, rel, fm(2, 2)
      real(wp), parameter :: nus(2) = [0.3_wp, 0.49_wp]
      integer :: i, inu
      integer(int64) :: seed
      character(len=60) :: buf
      call make_patch(x0, conn)
      allocate (u(2, 9), f(2, 9))
      fm = matmul(rot(50.0_wp*pi/180.0_wp), reshape([1.15_wp, 0.1_wp, -0.2_wp, 0.9_wp], [2, 2]))
      seed = 31337_int64
      do i = 1, 9
         u(:, i) = matmul(fm, x0(:, i)) - x0(:, i) + 0.2_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
      end do
      h = 1e-6_wp
      do inu = 1, size(nus)
         write (buf, '(a,f4.2)') 'physical hourglass control: force = dW/du, nu = ', nus(inu)
         call section(s, trim(buf))
         call lame_from_young(1.0e4_wp, nus(inu), lam, mu)
         call force(PHYS, x0, conn, u, lam, mu, f, w, whg, jmin)
         call check(s, jmin > 0.4_wp .and. whg > 1e-3_wp*w, 'finite strain and rotation, hourglass engaged')
         rel = gradient_error(u, f, h, energy)
         write (buf, '(a,es9.2)') 'max rel. error ', rel
         call check(s, rel <= 1e-6_wp, 'f = dW/du, 18 dofs ('//trim(buf)//')')
      end do
   contains
      real(wp) function energy(g)
         real(wp), intent(in) :: g(:, :)
         real(wp) :: ft(2, 9), whgt, jt
         call force(PHYS, x0, conn, g, lam, mu, ft, energy, whgt, jt)
         energy = energy + whgt
      end function energy
   end subroutine test_derivative

   !> omega_max^2 of one element: the largest eigenvalue of K x = omega^2 M x with the lumped mass
   !> m (LAPACK dsygv; kmat is overwritten); false when dsygv fails.
   logical function omega2_max(kmat, m, om2) result(ok)
      real(wp), intent(inout) :: kmat(8, 8)
      real(wp), intent(in) :: m(4)
      real(wp), intent(out) :: om2
      real(wp) :: mmat(8, 8), ev(8), work(64)
      integer :: k, info
      mmat = 0.0_wp
      do k = 1, 8
         mmat(k, k) = m((k + 1)/2)
      end do
      call dsygv(1, 'N', 'U', 8, kmat, 8, mmat, 8, ev, work, size(work), info)
      ok = info == 0
      om2 = ev(8)
   end function omega2_max

   !> The general path (q4_general.f90) in axisymmetry: the hourglass part of the plane element
   !> times the centroid radius (doc/hourglass.md, end): f = dW/du by central differences at a
   !> finite non-affine deformation of a patch off the axis, and no hourglass energy in an
   !> affine one.
   subroutine test_axisymmetric(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: lam, mu, w, whg, wd, jmin, d2, h, rel, hist(1, 1, 1)
      type(q4_solid_t) :: o
      type(j2_param_t) :: prm
      integer :: i, eb, em, ef
      integer(int64) :: seed
      character(len=40) :: buf
      call section(s, 'physical hourglass control: axisymmetric general path')
      call make_patch(x0, conn)
      x0(1, :) = x0(1, :) + 1.0_wp
      call lame_from_young(1.0e4_wp, 0.3_wp, lam, mu)
      o = q4g_init(1, .true., .false., law_make(LAW_NEOHOOKEAN, lam, mu, 1.0_wp, prm), 1.0_wp, HOURGLASS_PHYSICAL)
      allocate (u(2, 9), f(2, 9))
      hist = 0.0_wp
      u = matmul(reshape([1.1_wp, 0.05_wp, -0.1_wp, 0.95_wp], [2, 2]), x0) - x0
      f = 0.0_wp
      call q4g_force(o, 4, 9, conn, x0, u, 1.0_wp, hist, f, w, whg, wd, jmin, eb, d2, em, ef)
      call check(s, abs(whg) <= 1e-20_wp*w, 'affine deformation: no hourglass energy')
      seed = 99_int64
      do i = 1, 9
         u(:, i) = u(:, i) + 0.15_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
      end do
      f = 0.0_wp
      call q4g_force(o, 4, 9, conn, x0, u, 1.0_wp, hist, f, w, whg, wd, jmin, eb, d2, em, ef)
      call check(s, eb == 0 .and. whg > 1e-3_wp*w, 'non-affine deformation, hourglass engaged')
      h = 1e-6_wp
      rel = gradient_error(u, f, h, energy)
      write (buf, '(a,es9.2)') 'max rel. error ', rel
      call check(s, rel <= 1e-6_wp, 'f = dW/du, 18 dofs ('//trim(buf)//')')
   contains
      real(wp) function energy(g)
         real(wp), intent(in) :: g(:, :)
         real(wp) :: ft(2, 9), whgt, wdt, jt, d2t
         integer :: ebt, emt, eft
         ft = 0.0_wp
         call q4g_force(o, 4, 9, conn, x0, g, 1.0_wp, hist, ft, energy, whgt, wdt, jt, ebt, d2t, emt, eft)
         energy = energy + whgt
      end function energy
   end subroutine test_axisymmetric

   !> The element's stable step estimate (q4_stable_dt, one point) stays below the exact limit
   !> 2/omega_max of the element with the physical control, on random convex quads, nu to 0.49.
   subroutine test_stable_step(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nquad = 200
      real(wp), parameter :: nus(4) = [0.0_wp, 0.3_wp, 0.45_wp, 0.49_wp]
      real(wp) :: xq(2, 4), kmat(8, 8), m(4), om2, dte, ratio, rmax, rmin
      real(wp) :: lam, mu, rho, arat, skew
      integer :: iq, inu, emin, efold, k, nfail
      integer(int64) :: seed
      integer :: conn(4, 1)
      character(len=100) :: buf
      call section(s, 'physical hourglass control: stable step')
      conn(:, 1) = [1, 2, 3, 4]
      rho = 1.3_wp
      rmax = 0.0_wp
      rmin = huge(1.0_wp)
      nfail = 0
      seed = 5151_int64
      do iq = 1, nquad
         do
            arat = 1.0_wp + 4.0_wp*rnd(seed)
            skew = 1.2_wp*(rnd(seed) - 0.5_wp)
            xq = reshape([0.0_wp, 0.0_wp, arat, 0.0_wp, arat + skew, 1.0_wp, skew, 1.0_wp], [2, 4])
            do k = 1, 4
               xq(:, k) = xq(:, k) + 0.6_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
            end do
            if (iq == 1) xq = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
            if (convex(xq)) exit
         end do
         xq = matmul(rot(2.0_wp*pi*rnd(seed)), xq)
         m = 0.0_wp
         call q4_lumped_mass(1, 4, conn, xq, rho, m)
         do inu = 1, size(nus)
            call lame_from_young(1.0_wp, nus(inu), lam, mu)
            call tangent(PHYS, xq, conn, lam, mu, 1e-5_wp*sqrt(minval(m)/rho), kmat)
            if (.not. omega2_max(kmat, m, om2)) then
               nfail = nfail + 1
               cycle
            end if
            call q4_stable_dt(1, 1, 4, conn, xq, xq, neohookean_law(lam, mu, rho), dte, emin, efold)
            ratio = dte/(2.0_wp/sqrt(om2))
            rmax = max(rmax, ratio)
            rmin = min(rmin, ratio)
         end do
      end do
      write (buf, '(i0,a,f6.4,a,f6.4,a)') nquad*size(nus), ' cases, estimate/exact in [', rmin, ', ', &
         rmax, ']'
      write (output_unit, '(a)') '   '//trim(buf)
      call check(s, nfail == 0, 'all eigenproblems solved')
      call check(s, rmax <= 1.0_wp, 'estimate <= 2/omega_max in every case')
   contains
      logical function convex(xc)
         real(wp), intent(in) :: xc(2, 4)
         real(wp) :: e1(2), e2(2)
         integer :: a
         convex = .true.
         do a = 1, 4
            e1 = xc(:, modulo(a, 4) + 1) - xc(:, a)
            e2 = xc(:, modulo(a - 2, 4) + 1) - xc(:, a)
            convex = convex .and. (e1(1)*e2(2) - e1(2)*e2(1)) > 0.1_wp*norm2(e1)*norm2(e2)
         end do
      end function convex
   end subroutine test_stable_step

   !> One 2a x 2b rectangle, rotated by 30 degrees, in the small pure-bending mode about its own
   !> y axis (u_x = k x y, u_y = -k (x^2 + nub y^2)/2 in its frame): the stored energy is the
   !> beam's, (2/3) E' k^2 a b^3 (doc/hourglass.md, after (H7)).
   subroutine test_bending_energy(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 4), ul(2, 4), u(2, 4), f(2, 4), r(2, 2), lam, mu, nub, ep, w, whg, jmin, &
                  a, b, k, wex
      integer :: conn(4, 1), n
      call section(s, 'physical hourglass control: bending energy of a rectangle')
      conn(:, 1) = [1, 2, 3, 4]
      a = 1.5_wp
      b = 0.4_wp
      k = 1e-7_wp
      call lame_from_young(2.0e5_wp, 0.3_wp, lam, mu)
      nub = lam/(lam + 2.0_wp*mu)
      ep = 2.0_wp*mu*(1.0_wp + nub)
      x0 = reshape([-a, -b, a, -b, a, b, -a, b], [2, 4])
      do n = 1, 4
         ul(:, n) = [k*x0(1, n)*x0(2, n), -0.5_wp*k*(x0(1, n)**2 + nub*x0(2, n)**2)]
      end do
      r = rot(pi/6.0_wp)
      x0 = matmul(r, x0) + spread([3.0_wp, 1.0_wp], 2, 4)
      u = matmul(r, ul)
      call force(PHYS, x0, conn, u, lam, mu, f, w, whg, jmin)
      wex = 2.0_wp/3.0_wp*ep*k*k*a*b**3
      call check(s, abs(w) <= 1e-9_wp*wex, 'no mean strain in the bending mode')
      call check_close(s, whg, wex, 1e-6_wp*wex, 'hourglass energy = beam bending energy (2/3) E'' k^2 a b^3')
   end subroutine test_bending_energy

   !> A cantilever L x 2c of nx x 2 rectangular elements under pure bending: left end u_x = 0
   !> (u_y = 0 at its middle node), right end the linear traction sigma_xx = E' k y (consistent
   !> nodal forces). Plane-strain beam: u_y(L, 0) = -k L^2/2, u_x(L, c) = k L c. Solved
   !> linearly (tangent at u = 0 by differences of the force kernel, LAPACK dgesv).
   subroutine test_cantilever(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nx = 8, ny = 2
      real(wp), parameter :: el = 10.0_wp, c = 0.5_wp, k = 1e-6_wp
      real(wp) :: x0(2, (nx + 1)*(ny + 1)), kmat(2*(nx + 1)*(ny + 1), 2*(nx + 1)*(ny + 1)), &
                  rhs(2*(nx + 1)*(ny + 1), 1), lam, mu, nub, ep, tip, top, tipx, topx, rel(3), y0, y1
      integer :: conn(4, nx*ny), ipiv(2*(nx + 1)*(ny + 1)), i, j, n, ek, info, nn, ntip, ntop
      logical :: fixed(2*(nx + 1)*(ny + 1))
      character(len=16), parameter :: names(3) = [character(len=16) :: 'physical', 'FB 0.1', '2x2 Gauss']
      character(len=100) :: buf
      call section(s, 'physical hourglass control: cantilever in pure bending')
      nn = (nx + 1)*(ny + 1)
      do j = 0, ny
         do i = 0, nx
            x0(:, 1 + i + (nx + 1)*j) = [el*i/nx, -c + 2.0_wp*c*j/ny]
         end do
      end do
      do j = 1, ny
         do i = 1, nx
            n = i + (nx + 1)*(j - 1)
            conn(:, i + nx*(j - 1)) = [n, n + 1, n + nx + 2, n + nx + 1]
         end do
      end do
      call lame_from_young(2.0e5_wp, 0.3_wp, lam, mu)
      nub = lam/(lam + 2.0_wp*mu)
      ep = 2.0_wp*mu*(1.0_wp + nub)
      ! consistent nodal forces of sigma_xx = E' k y on the right edge (linear over each edge)
      rhs = 0.0_wp
      do j = 1, ny
         y0 = x0(2, (nx + 1)*j)
         y1 = x0(2, (nx + 1)*(j + 1))
         n = (nx + 1)*j
         rhs(2*n - 1, 1) = rhs(2*n - 1, 1) + ep*k*(y1 - y0)*(2.0_wp*y0 + y1)/6.0_wp
         n = (nx + 1)*(j + 1)
         rhs(2*n - 1, 1) = rhs(2*n - 1, 1) + ep*k*(y1 - y0)*(y0 + 2.0_wp*y1)/6.0_wp
      end do
      fixed = .false.
      do j = 0, ny
         fixed(2*(1 + (nx + 1)*j) - 1) = .true.
      end do
      fixed(2*(1 + (nx + 1)*(ny/2))) = .true.
      ntip = (nx + 1)*(ny/2 + 1)
      ntop = nn
      tipx = -0.5_wp*k*el**2
      topx = k*el*c
      do ek = PHYS, FULL
         call tangent(ek, x0, conn, lam, mu, 1e-6_wp*c, kmat)
         do i = 1, 2*nn
            if (fixed(i)) then
               kmat(i, :) = 0.0_wp
               kmat(:, i) = 0.0_wp
               kmat(i, i) = 1.0_wp
            end if
         end do
         block
            real(wp) :: b(2*(nx + 1)*(ny + 1), 1)
            b = rhs
            call dgesv(2*nn, 1, kmat, 2*nn, ipiv, b, 2*nn, info)
            call check(s, info == 0, trim(names(ek))//': the linear system solved')
            tip = b(2*ntip, 1)
            top = b(2*ntop - 1, 1)
         end block
         rel(ek) = max(abs(tip/tipx - 1.0_wp), abs(top/topx - 1.0_wp))
         write (buf, '(a,f9.5,a,f9.5)') 'tip deflection / beam ', tip/tipx, ', top end u_x / beam ', &
            top/topx
         write (output_unit, '(a)') '   '//names(ek)//trim(buf)
      end do
      call check(s, rel(PHYS) <= 1e-6_wp, 'physical control: the beam solution to 1e-6')
      call check(s, rel(FULL) > 0.1_wp, '2x2 Gauss locks in bending (more than 10 % stiff)')
   end subroutine test_cantilever


   ! ---------------------------------------------------------------- corner barrier

   !> The unit square (nodes 1-4) with the hourglass displacement u_x = c xi eta (nodal values
   !> c h_a) plus a small y part d h_a: corners 1 and 2 get r = 1 - c (doc/hourglass.md (H13)).
   subroutine fold_state(c, d, xq, u)
      real(wp), intent(in) :: c, d
      real(wp), intent(out) :: xq(2, 4), u(2, 4)
      real(wp), parameter :: h(4) = [1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp]
      xq = reshape([-1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 1.0_wp], [2, 4])
      u(1, :) = c*h
      u(2, :) = d*h
   end subroutine fold_state

   !> Corner barrier (doc/hourglass.md section 5): below r0 it adds energy (the element's
   !> hourglass energy exceeds the quadratic control's), f = dW/du by central differences with
   !> the barrier active, the energy and forces objective, and the energy grows without bound as
   !> a corner approaches the fold.
   subroutine test_barrier_energy(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: xq(2, 4), u(2, 4), f(2, 4), g(2, 4), fr(2, 4), r(2, 2)
      real(wp) :: lam, mu, w, whg, wa, whga, jmin, h, rel, err, e1, e2, e3
      integer :: i
      integer :: conn(4, 1)
      character(len=60) :: buf
      call section(s, 'corner barrier: energy, gradient, objectivity')
      conn(:, 1) = [1, 2, 3, 4]
      call lame_from_young(1.0e4_wp, 0.3_wp, lam, mu)
      ! r = 0.6 >= r0: the quadratic control alone, W = 1/2 q.K q (H6) with q = (c, d),
      ! K = E' diag(4/3, 4/3) for the square of side 2
      call fold_state(0.4_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, f, w, whg, jmin)
      e1 = 0.5_wp*(2.0_wp*mu*(1.0_wp + lam/(lam + 2.0_wp*mu)))*(4.0_wp/3.0_wp)*0.4_wp**2
      call check_close(s, whg, e1, 1e-12_wp*e1, 'r = 0.6: the quadratic control only, W = E'' (2/3) c^2')
      ! r = 0.3: the barrier adds kappa A0/4 (ln(0.3/0.5))^2 at each of corners 1 and 2
      call fold_state(0.7_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, f, w, whg, jmin)
      e1 = 0.5_wp*(2.0_wp*mu*(1.0_wp + lam/(lam + 2.0_wp*mu)))*(4.0_wp/3.0_wp)*0.7_wp**2
      e2 = 2.0_wp*(2.0_wp*mu*(1.0_wp + lam/(lam + 2.0_wp*mu)))*(4.0_wp/4.0_wp)*log(0.3_wp/0.5_wp)**2
      call check_close(s, whg, e1 + e2, 1e-12_wp*(e1 + e2), &
            'r = 0.3: quadratic control + kappa A0/4 ln(r/r0)^2 at 2 corners')
      ! a non-symmetric near-fold state with a rotation: f = dW/du
      call fold_state(0.8_wp, 0.15_wp, xq, u)
      u(:, 3) = u(:, 3) + [0.1_wp, -0.05_wp]
      r = rot(0.6_wp)
      u = matmul(r, xq + u) - xq
      call force(PHYS, xq, conn, u, lam, mu, f, w, whg, jmin)
      h = 1e-7_wp
      rel = gradient_error(u, f, h, energy)
      write (buf, '(a,es9.2)') 'max rel. error ', rel
      call check(s, rel <= 1e-6_wp, 'barrier active: f = dW/du, 8 dofs ('//trim(buf)//')')
      ! objectivity: rotate the deformed element
      err = 0.0_wp
      do i = 1, 3
         r = rot(real(i, wp)*1.9_wp)
         g = matmul(r, xq + u) - xq
         call force(PHYS, xq, conn, g, lam, mu, fr, wa, whga, jmin)
         err = max(err, abs(whga - whg)/whg, maxval(abs(fr - matmul(r, f)))/maxval(abs(f)))
      end do
      call check(s, err <= 1e-11_wp, 'barrier active, rotated: same energy, forces rotated')
      ! without bound: r = 1e-2, 1e-4, 1e-6
      call fold_state(1.0_wp - 1e-2_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, f, w, e1, jmin)
      call fold_state(1.0_wp - 1e-4_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, f, w, e2, jmin)
      call fold_state(1.0_wp - 1e-6_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, f, w, e3, jmin)
      call check(s, e3 > e2 .and. e2 > e1 .and. e3 > 10.0_wp*mu*4.0_wp, &
                 'energy grows without bound as a corner approaches the fold')
   contains
      real(wp) function energy(g)
         real(wp), intent(in) :: g(:, :)
         real(wp) :: ft(2, 4), whgt, jt
         call force(PHYS, xq, conn, g, lam, mu, ft, energy, whgt, jt)
         energy = energy + whgt
      end function energy
   end subroutine test_barrier_energy

   !> The stable step with the barrier (H18) stays below the exact limit 2/omega_max of the
   !> element (tangent by central differences of the force at the deformed state, lumped mass)
   !> on random states with a corner at r = 0.45 ... 0.001, and shrinks toward the fold.
   subroutine test_barrier_step(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: ncase = 120
      real(wp) :: xq(2, 4), u(2, 4), ub(2, 4), fp(2, 4), fm(2, 4), kmat(8, 8), m(4), om2
      real(wp) :: lam, mu, rho, w, whg, jmin, d2, c, dx, ratio, rmax, rmin, hh, dtfar, dtnear
      integer :: ic, j, k, nfail
      integer :: conn(4, 1)
      integer(int64) :: seed
      character(len=100) :: buf
      call section(s, 'corner barrier: stable step')
      conn(:, 1) = [1, 2, 3, 4]
      rho = 1.3_wp
      seed = 777_int64
      rmax = 0.0_wp
      rmin = huge(1.0_wp)
      nfail = 0
      do ic = 1, ncase
         call lame_from_young(1.0_wp, 0.49_wp*rnd(seed), lam, mu)
         c = 1.0_wp - 0.45_wp*10.0_wp**(-3.0_wp*rnd(seed))
         call fold_state(c, 0.3_wp*(rnd(seed) - 0.5_wp), xq, u)
         do k = 1, 4
            u(:, k) = u(:, k) + 0.05_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
         end do
         m = 0.0_wp
         call q4_lumped_mass(1, 4, conn, xq, rho, m)
         call force(PHYS, xq, conn, u, lam, mu, fp, w, whg, jmin, d2, rho)
         if (jmin <= 0.0_wp .or. .not. d2 > 0.0_wp) then
            nfail = nfail + 1
            cycle
         end if
         hh = 1e-4_wp*(1.0_wp - c)
         do j = 1, 8
            ub = u
            ub(modulo(j - 1, 2) + 1, (j + 1)/2) = u(modulo(j - 1, 2) + 1, (j + 1)/2) + hh
            call force(PHYS, xq, conn, ub, lam, mu, fp, w, whg, jmin)
            ub(modulo(j - 1, 2) + 1, (j + 1)/2) = u(modulo(j - 1, 2) + 1, (j + 1)/2) - hh
            call force(PHYS, xq, conn, ub, lam, mu, fm, w, whg, jmin)
            kmat(:, j) = reshape(fp - fm, [8])/(2.0_wp*hh)
         end do
         kmat = 0.5_wp*(kmat + transpose(kmat))
         if (.not. omega2_max(kmat, m, om2)) then
            nfail = nfail + 1
            cycle
         end if
         ratio = sqrt(d2)/(2.0_wp/sqrt(om2))
         rmax = max(rmax, ratio)
         rmin = min(rmin, ratio)
      end do
      write (buf, '(i0,a,f6.4,a,f6.4,a)') ncase, ' near-fold states, estimate/exact in [', rmin, ', ', rmax, ']'
      write (output_unit, '(a)') '   '//trim(buf)
      call check(s, nfail == 0, 'all states valid, all eigenproblems solved')
      call check(s, rmax <= 1.0_wp, 'estimate <= 2/omega_max in every case')
      ! the step shrinks toward the fold: r = 0.6 (no barrier) against r = 1e-3
      call lame_from_young(1.0_wp, 0.3_wp, lam, mu)
      call fold_state(0.4_wp, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, fp, w, whg, jmin, d2, rho)
      dtfar = sqrt(d2)
      dx = 1.0_wp - 1e-3_wp
      call fold_state(dx, 0.0_wp, xq, u)
      call force(PHYS, xq, conn, u, lam, mu, fp, w, whg, jmin, d2, rho)
      dtnear = sqrt(d2)
      write (buf, '(a,es9.2)') 'step at r = 1e-3 / step at r = 0.6: ', dtnear/dtfar
      call check(s, dtnear < 0.05_wp*dtfar, trim(buf))
   end subroutine test_barrier_step

   !> A free square driven into its hourglass fold: the velocity of the mode u_x = c xi eta
   !> carries the kinetic energy the quadratic control alone stores at c = 1.5 (a fold at c = 1,
   !> where corners 1 and 2 reach r = 0). Central differences in exic's velocity form (u(n+1) =
   !> u + dt v + dt^2/2 a, v(n+1) = v + dt/2 (a + a(n+1)), the step chosen as step.f90 does) over
   !> 5 periods of the mode: at 0.9 of the element's step the corners go deep into the barrier
   !> and never fold; at 0.05 and 0.025 of it the total energy (kinetic + strain + hourglass) stays
   !> within 0.6 % and 0.15 % of the initial one and its error falls as dt^2 (the forces are the
   !> gradient of the energy; a single element's pointwise energy is that of its highest mode,
   !> which at large steps moves far from the conserved shadow energy: 31 % at 0.9 with no
   !> barrier at all, doc/hourglass.md section 6).
   subroutine test_barrier_fold(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: rmin(3), drift(3)
      logical :: done(3)
      character(len=100) :: buf
      integer :: n
      call section(s, 'corner barrier: a driven fold stays stable and conserves energy')
      call drive(0.9_wp, n, rmin(1), drift(1), done(1))
      write (buf, '(a,i0,a,f7.4,a,es9.2)') 'CFL 0.9: steps ', n, ', smallest corner ratio ', rmin(1), &
         ', energy error ', drift(1)
      write (output_unit, '(a)') '   '//trim(buf)
      call check(s, done(1) .and. rmin(1) > 0.0_wp .and. rmin(1) < 0.3_wp, &
                 'CFL 0.9: 5 periods, corners deep in the barrier (r < 0.3), never folded')
      ! with the bound of the state a step reaches (doc/hourglass.md (H20)) the step varies as
      ! corners cross r0 e^(1/4): 0.1 -> 0.05 gives 8.5e-3 -> 2.9e-3, 0.05 -> 0.025 2.9e-3 -> 5.4e-4
      call drive(0.05_wp, n, rmin(2), drift(2), done(2))
      call drive(0.025_wp, n, rmin(3), drift(3), done(3))
      write (buf, '(a,es9.2,a,es9.2,a,2f7.4)') 'energy error at CFL 0.05 ', drift(2), ', 0.025 ', drift(3), &
         '; smallest r ', rmin(2:3)
      write (output_unit, '(a)') '   '//trim(buf)
      call check(s, all(done(2:3)) .and. all(rmin(2:3) > 0.0_wp .and. rmin(2:3) < 0.3_wp), &
                 'CFL 0.05, 0.025: 5 periods, corners in the barrier, never folded')
      call check(s, drift(2) <= 6e-3_wp .and. drift(3) <= 1.5e-3_wp .and. drift(2) >= 3.0_wp*drift(3), &
                 'total energy conserved to O(dt^2)')
   contains
      subroutine drive(cfl, n, rmin, drift, done)
         real(wp), intent(in) :: cfl
         integer, intent(out) :: n
         real(wp), intent(out) :: rmin, drift
         logical, intent(out) :: done
         real(wp), parameter :: h(4) = [1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp]
         real(wp) :: xq(2, 4), u(2, 4), v(2, 4), acc(2, 4), anew(2, 4), f(2, 4), m(4), mm(2, 4)
         real(wp) :: lam, mu, rho, w, whg, jmin, d2, e0, ek, t, kq, v0, dt, tend, target
         integer :: conn(4, 1)
         conn(:, 1) = [1, 2, 3, 4]
         call lame_from_young(1.0_wp, 0.3_wp, lam, mu)
         rho = 1.0_wp
         call fold_state(0.0_wp, 0.0_wp, xq, u)
         m = 0.0_wp
         call q4_lumped_mass(1, 4, conn, xq, rho, m)
         mm = spread(m, 1, 2)
         ! W = 1/2 K c^2 with K = E' 4/3 (H6); kinetic energy of v_x = v0 h_a: 1/2 sum(m) v0^2
         kq = 2.0_wp*mu*(1.0_wp + lam/(lam + 2.0_wp*mu))*(4.0_wp/3.0_wp)
         v0 = sqrt(kq*1.5_wp**2/sum(m))
         v(1, :) = v0*h
         v(2, :) = 0.0_wp
         e0 = 0.5_wp*sum(mm*v*v)
         tend = 5.0_wp*2.0_wp*pi*sqrt(sum(m)/kq)
         call force(PHYS, xq, conn, u, lam, mu, f, w, whg, jmin, d2, rho, v)
         acc = -f/mm
         dt = cfl*sqrt(d2)
         t = 0.0_wp
         drift = 0.0_wp
         rmin = 1.0_wp
         n = 0
         done = .false.
         do while (n < 100000)
            u = u + dt*v + (0.5_wp*dt*dt)*acc
            t = t + dt
            n = n + 1
            ! the forces and the step at u(n+1) with v(n), as the stepper calls them
            call force(PHYS, xq, conn, u, lam, mu, f, w, whg, jmin, d2, rho, v)
            if (jmin <= 0.0_wp .or. .not. d2 > 0.0_wp) exit
            anew = -f/mm
            v = v + (0.5_wp*dt)*(acc + anew)
            acc = anew
            ek = 0.5_wp*sum(mm*v*v)
            drift = max(drift, abs(ek + w + whg - e0)/e0)
            rmin = min(rmin, corner_ratio(xq + u))
            if (rmin <= 0.0_wp) exit
            if (t >= tend) then
               done = .true.
               exit
            end if
            ! exic's step choice (step.f90, choose_dt): shrink at once, grow beyond 15 %
            target = cfl*sqrt(d2)
            if (dt > target .or. dt < 0.85_wp*target) dt = target
         end do
      end subroutine drive

      !> smallest corner volume ratio r_a of (H13) of the square of side 2 deformed to xc
      real(wp) function corner_ratio(xc) result(r)
         real(wp), intent(in) :: xc(2, 4)
         real(wp) :: e1(2), e2(2), sq
         integer :: a
         sq = (xc(1, 3) - xc(1, 1))*(xc(2, 4) - xc(2, 2)) - (xc(2, 3) - xc(2, 1))*(xc(1, 4) - xc(1, 2))
         r = huge(1.0_wp)
         do a = 1, 4
            e1 = xc(:, a) - xc(:, modulo(a - 2, 4) + 1)
            e2 = xc(:, modulo(a, 4) + 1) - xc(:, a)
            ! s0_a/S0 = 4/8 for the square
            r = min(r, 2.0_wp*(e1(1)*e2(2) - e1(2)*e2(1))/sq)
         end do
      end function corner_ratio
   end subroutine test_barrier_fold

end module test_hourglass
