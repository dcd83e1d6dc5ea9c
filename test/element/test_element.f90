!> Tests of the neo-Hookean law and the 4-node quadrilateral kernels: patch test under a uniform
!> finite deformation, objectivity, force = derivative of energy, lumped mass, the stable step
!> against the element's exact limit, and inversion flags.
module test_element
   use exic_material_law, only: neohookean_law
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_material_material, only: lame_from_young
   use exic_material_neohookean, only: nh_cauchy, nh_piola, nh_wave_speed2
   use exic_element_q4_stable, only: block_minimum
   use exic_element_q4_bulk_viscosity, only: q4_bulk_viscosity
   use exic_element_quad4, only: q4_check_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, &
                                 q4_stable_dt, q4_stress, q4_deformation, NBLOCK
   use testing, only: suite_t, check, check_close, section, gradient_error
   use, intrinsic :: iso_fortran_env, only: output_unit, int64
   implicit none
   private

   public :: run_element_tests

   !> Generalized symmetric-definite eigenproblem (LAPACK).
   interface
      subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
         import :: wp
         integer, intent(in) :: itype, n, lda, ldb, lwork
         character(len=1), intent(in) :: jobz, uplo
         real(wp), intent(inout) :: a(lda, *), b(ldb, *)
         real(wp), intent(out) :: w(*), work(*)
         integer, intent(out) :: info
      end subroutine dsygv
   end interface

   real(wp), parameter :: lam0 = 33333.0_wp, mu0 = 5000.0_wp   !< the seed's Lame constants
   real(wp), parameter :: hg0 = 0.1_wp
   real(wp), parameter :: pi = 3.14159265358979323846_wp

   !> One element set for one quadrature (the kernels recompute the reference data from x0).
   type :: setup_t
      integer :: nq = 2, nel = 0, nnode = 0
      integer, allocatable :: conn(:, :)
      real(wp), allocatable :: x0(:, :)
   end type setup_t

contains

   !> Run every element test.
   subroutine run_element_tests(s)
      type(suite_t), intent(inout) :: s
      call test_material(s)
      call test_patch(s)
      call test_objectivity(s)
      call test_consistency(s)
      call test_mass(s)
      call test_stable_dt(s)
      call test_fused(s)
      call test_inversion(s)
      call test_block_minimum(s)
      call test_stress_block(s)
      call test_bulk_viscosity(s)
   end subroutine run_element_tests

   !> VISCosity BULK's kernel (doc/damping.md, section 3) on one distorted quadrilateral under a
   !> uniform compression v = -alpha x, plane and axisymmetric: its forces are -q dV/dx_a (dV/dx_a
   !> by central differences of V integrated by 2x2 Gauss, independent of the kernel's closed
   !> form), q = rho l (q1 l trD^2 - q2 c trD) with trD = -2 alpha (plane) and -3 alpha (the hoop
   !> rate v_r/r adds -alpha in axisymmetry), and the step ratio c/(Q + sqrt(Q^2 + c^2)).
   subroutine test_bulk_viscosity(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: alpha = 0.01_wp, q1 = 1.5_wp, q2 = 0.06_wp, rho = 2.0_wp, c = 3.0_wp
      real(wp) :: x0(2, 4), u(2, 4), v(2, 4), a(2, 4), g(2, 4), ratio, area, vol, trd, l, q, qq, xp(2, 4), dv(2, 4)
      real(wp) :: worst
      integer :: conn(4, 1), k, i, iax
      logical :: axi
      call section(s, 'bulk viscosity kernel, plane and axisymmetric')
      conn(:, 1) = [1, 2, 3, 4]
      x0 = reshape([0.3_wp, 0.1_wp, 0.9_wp, 0.0_wp, 1.0_wp, 0.7_wp, 0.2_wp, 0.6_wp], [2, 4])
      u = 0.0_wp
      a = 0.0_wp
      v = -alpha*x0
      do iax = 0, 1
         axi = iax == 1
         g = 0.0_wp
         ratio = 1.0_wp
         call q4_bulk_viscosity(1, 4, conn, x0, u, v, a, 1.0e-3_wp, rho, c, q1, q2, axi, g, ratio)
         area = gauss_measure(x0, .false.)
         vol = gauss_measure(x0, axi)
         trd = merge(-3.0_wp, -2.0_wp, axi)*alpha
         l = sqrt(area)
         q = rho*l*(q1*l*trd*trd - q2*c*trd)
         worst = 0.0_wp
         do k = 1, 4
            do i = 1, 2
               xp = x0
               xp(i, k) = x0(i, k) + 1.0e-6_wp
               dv(i, k) = gauss_measure(xp, axi)
               xp(i, k) = x0(i, k) - 1.0e-6_wp
               dv(i, k) = (dv(i, k) - gauss_measure(xp, axi))/2.0e-6_wp
               worst = max(worst, abs(g(i, k) + q*dv(i, k)))
            end do
         end do
         call check(s, worst <= 1.0e-9_wp*q, trim(merge('axisymmetric', 'plane       ', axi))// &
                    ': forces -q dV/dx_a with q of trD = '//trim(merge('-3 alpha', '-2 alpha', axi)), &
                    'largest difference '//rtoa(worst)//' of q = '//rtoa(q))
         call check(s, abs(sum(g*v) + q*vol*trd) <= 1.0e-12_wp*abs(q*vol*trd), &
                    trim(merge('axisymmetric', 'plane       ', axi))//': their power is -q V trD')
         qq = q1*l*abs(trd) + q2*c
         call check(s, abs(ratio - c/(qq + sqrt(qq*qq + c*c))) <= 1.0e-15_wp, &
                    trim(merge('axisymmetric', 'plane       ', axi))//': step ratio c/(Q + sqrt(Q^2 + c^2))')
      end do
   contains
      !> int dA (axi false) or int r dA (axi true) over the bilinear quadrilateral x, 2x2 Gauss.
      real(wp) function gauss_measure(x, axi) result(m)
         real(wp), intent(in) :: x(2, 4)
         logical, intent(in) :: axi
         real(wp), parameter :: gp(2) = [-1.0_wp, 1.0_wp]/sqrt(3.0_wp)
         real(wp) :: xi, eta, n(4), dxi(4), deta(4), j11, j12, j21, j22
         integer :: p, r
         m = 0.0_wp
         do p = 1, 2
            do r = 1, 2
               xi = gp(p)
               eta = gp(r)
               n = 0.25_wp*[(1 - xi)*(1 - eta), (1 + xi)*(1 - eta), (1 + xi)*(1 + eta), (1 - xi)*(1 + eta)]
               dxi = 0.25_wp*[-(1 - eta), (1 - eta), (1 + eta), -(1 + eta)]
               deta = 0.25_wp*[-(1 - xi), -(1 + xi), (1 + xi), (1 - xi)]
               j11 = sum(dxi*x(1, :))
               j12 = sum(dxi*x(2, :))
               j21 = sum(deta*x(1, :))
               j22 = sum(deta*x(2, :))
               if (axi) then
                  m = m + (j11*j22 - j12*j21)*sum(n*x(1, :))
               else
                  m = m + (j11*j22 - j12*j21)
               end if
            end do
         end do
      end function gauss_measure
   end subroutine test_bulk_viscosity

   ! ---------------------------------------------------------------- helpers

   !> Park-Miller uniform number in (0, 1); deterministic on every platform.
   function rnd(seed) result(r)
      integer(int64), intent(inout) :: seed
      real(wp) :: r
      seed = mod(16807_int64*seed, 2147483647_int64)
      r = real(seed, wp)/2147483647.0_wp
   end function rnd

   !> The distorted 2x2-element patch on about [0,2]^2: 9 nodes, interior node 5 off centre.
   subroutine make_patch(x0, conn)
      real(wp), allocatable, intent(out) :: x0(:, :)
      integer, allocatable, intent(out) :: conn(:, :)
      allocate (x0(2, 9), conn(4, 4))
      x0(:, 1) = [0.0_wp, 0.0_wp]
      x0(:, 2) = [0.9_wp, 0.1_wp]
      x0(:, 3) = [2.1_wp, -0.1_wp]
      x0(:, 4) = [-0.1_wp, 1.2_wp]
      x0(:, 5) = [1.13_wp, 0.87_wp]
      x0(:, 6) = [2.0_wp, 0.9_wp]
      x0(:, 7) = [0.1_wp, 2.0_wp]
      x0(:, 8) = [1.15_wp, 2.1_wp]
      x0(:, 9) = [1.9_wp, 2.05_wp]
      conn(:, 1) = [1, 2, 5, 4]
      conn(:, 2) = [2, 3, 6, 5]
      conn(:, 3) = [4, 5, 8, 7]
      conn(:, 4) = [5, 6, 9, 8]
   end subroutine make_patch

   !> Reference data for mesh (x0, conn) and quadrature nq.
   subroutine make_setup(nq, x0, conn, st, ebad)
      integer, intent(in) :: nq
      real(wp), intent(in) :: x0(:, :)
      integer, intent(in) :: conn(:, :)
      type(setup_t), intent(out) :: st
      integer, intent(out) :: ebad
      st%nq = nq
      st%nnode = size(x0, 2)
      st%nel = size(conn, 2)
      st%x0 = x0
      st%conn = conn
      call q4_check_reference(st%nel, st%nnode, st%conn, st%x0, ebad)
   end subroutine make_setup

   !> Internal force f (zeroed first), strain energy w and hourglass energy whg of the set; the
   !> fused stable step (squared, density 1), its element and the first folded element when asked.
   subroutine eval_force(st, u, lambda, mu, hg, f, w, whg, jmin, ebad, dt2, emin, efold)
      type(setup_t), intent(in) :: st
      real(wp), intent(in) :: u(:, :), lambda, mu, hg
      real(wp), intent(out) :: f(:, :), w, whg, jmin
      integer, intent(out) :: ebad
      real(wp), intent(out), optional :: dt2
      integer, intent(out), optional :: emin, efold
      real(wp) :: d
      integer :: em, ef
      f = 0.0_wp
      whg = 0.0_wp
      if (st%nq == 2) then
         call q4_force_2x2(st%nel, st%nnode, st%conn, st%x0, u, neohookean_law(lambda, mu, 1.0_wp), f, w, &
                           jmin, ebad, d, em, ef)
      else
         call q4_force_1pt(st%nel, st%nnode, st%conn, st%x0, u, neohookean_law(lambda, mu, 1.0_wp), hg, f, w, whg, &
                           jmin, ebad, d, em, ef)
      end if
      if (present(dt2)) dt2 = d
      if (present(emin)) emin = em
      if (present(efold)) efold = ef
   end subroutine eval_force

   !> Cauchy stress of eq. 7.2 computed directly from F: (sxx, syy, szz, sxy).
   pure function exact_cauchy(lambda, mu, fm) result(sg)
      real(wp), intent(in) :: lambda, mu, fm(2, 2)
      real(wp) :: sg(4), b(2, 2), jac
      b = matmul(fm, transpose(fm))
      jac = fm(1, 1)*fm(2, 2) - fm(1, 2)*fm(2, 1)
      sg(1) = lambda*log(jac)/jac + mu/jac*(b(1, 1) - 1.0_wp)
      sg(2) = lambda*log(jac)/jac + mu/jac*(b(2, 2) - 1.0_wp)
      sg(3) = lambda*log(jac)/jac
      sg(4) = mu/jac*b(1, 2)
   end function exact_cauchy

   !> Rotation matrix by angle th.
   pure function rot(th) result(r)
      real(wp), intent(in) :: th
      real(wp) :: r(2, 2)
      r = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
   end function rot

   character(len=12) function qname(nq)
      integer, intent(in) :: nq
      qname = merge('2x2 Gauss   ', '1-pt + hg   ', nq == 2)
   end function qname

   ! ---------------------------------------------------------------- material

   !> The law itself: stress-free at F = 1, P = dW/dF, sigma = P F^T/J, linear limit.
   subroutine test_material(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: fm(2, 2), p(2, 2), sg(4), jac, w, w1(1), w2, fd(2, 2), h, eps, ref(4), err
      integer :: i, j

      call section(s, 'neo-Hookean law (eq. 7.2)')
      call nh_cauchy(lam0, mu0, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, sg(1), sg(2), sg(3), sg(4), jac, w)
      call check(s, all(sg == 0.0_wp) .and. w == 0.0_wp .and. jac == 1.0_wp, &
                 'F = 1: zero stress and energy')

      fm = reshape([1.25_wp, -0.2_wp, 0.3_wp, 0.8_wp], [2, 2])
      jac = fm(1, 1)*fm(2, 2) - fm(1, 2)*fm(2, 1)
      call nh_piola(1, lam0, mu0, fm(1, 1:1), fm(1, 2:2), fm(2, 1:1), fm(2, 2:2), [jac], [1.0_wp], &
                    p(1, 1:1), p(1, 2:2), p(2, 1:1), p(2, 2:2), w1)
      w = w1(1)
      call nh_cauchy(lam0, mu0, fm(1, 1), fm(1, 2), fm(2, 1), fm(2, 2), sg(1), sg(2), sg(3), &
                     sg(4), jac, w2)
      ref = exact_cauchy(lam0, mu0, fm)
      call check(s, maxval(abs(sg - ref)) <= 1e-12_wp*maxval(abs(ref)), &
                 'Cauchy stress equals lambda lnJ/J 1 + mu/J (b - 1)')
      ! sigma = P F^T / J
      fd = matmul(p, transpose(fm))/jac
      err = max(abs(fd(1, 1) - sg(1)), abs(fd(2, 2) - sg(2)), abs(fd(1, 2) - sg(4)), &
                abs(fd(2, 1) - sg(4)))
      call check(s, err <= 1e-12_wp*maxval(abs(sg)), 'sigma = P F^T / J')
      call check_close(s, w, w2, 1e-12_wp*abs(w), 'W from nh_piola = W from nh_cauchy')
      call check_close(s, w, 0.5_wp*lam0*log(jac)**2 + 0.5_wp*mu0*(sum(fm**2) + 1.0_wp - 3.0_wp) &
                       - mu0*log(jac), 1e-12_wp*abs(w), 'W from nh_piola = lambda/2 ln^2 J + mu/2 (I1 - 3) - mu ln J')
      ! P = dW/dF by central differences
      h = 1e-6_wp
      do j = 1, 2
         do i = 1, 2
            fd(i, j) = (wat(i, j, h) - wat(i, j, -h))/(2.0_wp*h)
         end do
      end do
      call check(s, maxval(abs(fd - p)) <= 1e-6_wp*maxval(abs(p)), 'P = dW/dF (finite differences)')
      ! small-strain limit: linear isotropic elasticity
      eps = 1e-7_wp
      fm = reshape([1.0_wp + 2.0_wp*eps, 0.5_wp*eps, 0.5_wp*eps, 1.0_wp - eps], [2, 2])
      call nh_cauchy(lam0, mu0, fm(1, 1), fm(1, 2), fm(2, 1), fm(2, 2), sg(1), sg(2), sg(3), &
                     sg(4), jac, w)
      ref = [lam0*eps + 2.0_wp*mu0*2.0_wp*eps, lam0*eps - 2.0_wp*mu0*eps, lam0*eps, mu0*eps]
      call check(s, maxval(abs(sg - ref)) <= 1e-5_wp*maxval(abs(ref)), &
                 'small strain: lambda tr(eps) 1 + 2 mu eps')
      call check_close(s, nh_wave_speed2(lam0, mu0, 2.0_wp, 1.0_wp), (lam0 + 2.0_wp*mu0)/2.0_wp, &
                       1e-12_wp*lam0, 'wave speed at J = 1: (lambda + 2 mu)/rho0')
      call check(s, nh_wave_speed2(lam0, mu0, 1.0_wp, 10.0_wp) >= mu0, &
                 'wave speed floored at large dilatation')
   contains
      real(wp) function wat(i, j, d)
         integer, intent(in) :: i, j
         real(wp), intent(in) :: d
         real(wp) :: g(2, 2)
         g = reshape([1.25_wp, -0.2_wp, 0.3_wp, 0.8_wp], [2, 2])
         g(i, j) = g(i, j) + d
         wat = nh_w(g)
      end function wat
   end subroutine test_material

   ! ---------------------------------------------------------------- patch test

   !> Uniform finite deformation of the distorted patch, both quadratures.
   subroutine test_patch(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), fb(:, :), f0(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: fm(2, 2), pm(2, 2), sref(4), sig(7, 4), w, whg, jmin, fscale, jac, fg(5, 4, 4)
      real(wp) :: nl(2), err, errf, area, wexact
      integer :: nq, ebad, e, g, k
      integer, parameter :: ring(9) = [1, 2, 3, 6, 9, 8, 7, 4, 1]
      type(setup_t) :: st
      character(len=12) :: qn

      fm = reshape([1.2_wp, -0.1_wp, 0.25_wp, 0.85_wp], [2, 2])
      call make_patch(x0, conn)
      allocate (u(2, 9), f(2, 9), fb(2, 9), f0(2, 9))
      u = matmul(fm, x0) - x0
      sref = exact_cauchy(lam0, mu0, fm)
      jac = fm(1, 1)*fm(2, 2) - fm(1, 2)*fm(2, 1)
      pm = jac*matmul(reshape([sref(1), sref(4), sref(4), sref(2)], [2, 2]), &
                      transpose(inv2(fm)))
      ! consistent nodal forces of the constant nominal traction P N on the boundary
      fb = 0.0_wp
      do k = 1, 8
         nl = [x0(2, ring(k + 1)) - x0(2, ring(k)), -(x0(1, ring(k + 1)) - x0(1, ring(k)))]
         fb(:, ring(k)) = fb(:, ring(k)) + 0.5_wp*matmul(pm, nl)
         fb(:, ring(k + 1)) = fb(:, ring(k + 1)) + 0.5_wp*matmul(pm, nl)
      end do
      area = 0.0_wp
      do k = 1, 8
         area = area + 0.5_wp*(x0(1, ring(k))*x0(2, ring(k + 1)) - x0(1, ring(k + 1))*x0(2, ring(k)))
      end do
      wexact = area*nh_w(fm)

      do nq = 2, 1, -1
         qn = qname(nq)
         call section(s, 'patch test, uniform finite deformation, '//trim(qn))
         call make_setup(nq, x0, conn, st, ebad)
         call check(s, ebad == 0, 'reference geometry accepted')
         ! F at every integration point, as the force kernels compute it
         call q4_deformation(nq, 4, 9, conn, x0, u, fg)
         err = 0.0_wp
         do e = 1, 4
            do g = 1, nq*nq
               err = max(err, abs(fg(1, g, e) - fm(1, 1)), abs(fg(2, g, e) - fm(1, 2)), &
                         abs(fg(3, g, e) - fm(2, 1)), abs(fg(4, g, e) - fm(2, 2)), abs(fg(5, g, e) - jac))
            end do
         end do
         call check(s, err <= 1e-13_wp, 'F and J exact at every integration point')
         call q4_stress(nq, 4, 9, conn, x0, u, neohookean_law(lam0, mu0, 1.0_wp), sig)
         err = 0.0_wp
         do e = 1, 4
            err = max(err, maxval(abs(sig(1:4, e) - sref)))
         end do
         call check(s, err <= 1e-10_wp*maxval(abs(sref)), 'Cauchy stress exact (eq. 7.2) in every element')
         call check(s, maxval(abs(sig(5, :) + sum(sref(1:3))/3.0_wp)) <= 1e-10_wp*maxval(abs(sref)) &
                    .and. maxval(abs(sig(7, :) - jac)) <= 1e-13_wp, 'pressure and J exact')
         call check(s, maxval(abs(sig(6, :) - vmises(sref))) <= 1e-10_wp*maxval(abs(sref)), &
                    'von Mises exact')

         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
         fscale = maxval(abs(f))
         call check(s, ebad == 0 .and. abs(jmin - jac) <= 1e-13_wp, 'jmin = det F, no flag')
         call check(s, maxval(abs(f(:, 5))) <= 1e-12_wp*fscale, 'zero net force at the interior node')
         errf = maxval(abs(f - fb))
         call check(s, errf <= 1e-12_wp*fscale, 'boundary forces = consistent forces of P N')
         call check_close(s, w, wexact, 1e-12_wp*wexact, 'strain energy = W(F) x area')
         if (nq == 1) then
            call check(s, whg <= 1e-24_wp*(lam0 + 2.0_wp*mu0)*area, 'hourglass energy zero')
            call eval_force(st, u, lam0, mu0, 0.0_wp, f0, w, whg, jmin, ebad)
            call check(s, maxval(abs(f - f0)) <= 1e-13_wp*fscale, 'hourglass force zero')
         end if
      end do
   end subroutine test_patch

   pure function inv2(a) result(b)
      real(wp), intent(in) :: a(2, 2)
      real(wp) :: b(2, 2)
      b = reshape([a(2, 2), -a(2, 1), -a(1, 2), a(1, 1)], [2, 2])/(a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1))
   end function inv2

   pure real(wp) function vmises(sg)
      real(wp), intent(in) :: sg(4)
      vmises = sqrt(0.5_wp*((sg(1) - sg(2))**2 + (sg(2) - sg(3))**2 + (sg(3) - sg(1))**2) &
                    + 3.0_wp*sg(4)**2)
   end function vmises

   ! ---------------------------------------------------------------- objectivity

   !> Rigid motions give no energy or force; rotating a deformed state rotates the forces.
   subroutine test_objectivity(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), fr(:, :), ud(:, :)
      integer, allocatable :: conn(:, :)
      real(wp), parameter :: angles(4) = [90.0_wp, 180.0_wp, 37.0_wp, -123.0_wp]
      real(wp) :: r(2, 2), w, whg, jmin, wr, whgr, tolw, tolf, wmax, fmax, err, wd, fs
      integer :: nq, k, ebad, i
      integer(int64) :: seed
      type(setup_t) :: st

      call make_patch(x0, conn)
      allocate (u(2, 9), f(2, 9), fr(2, 9), ud(2, 9))
      ! scales: energy (lambda + 2 mu) A, force (lambda + 2 mu) L with A ~ 4, L ~ 2
      tolw = 1e-14_wp*(lam0 + 2.0_wp*mu0)*4.0_wp
      tolf = 1e-13_wp*(lam0 + 2.0_wp*mu0)*2.0_wp
      seed = 12345_int64
      do i = 1, 9
         ud(1, i) = 0.3_wp*(rnd(seed) - 0.5_wp)
         ud(2, i) = 0.3_wp*(rnd(seed) - 0.5_wp)
      end do
      do nq = 2, 1, -1
         call section(s, 'objectivity, '//trim(qname(nq)))
         call make_setup(nq, x0, conn, st, ebad)
         ! rigid translation
         u(1, :) = 0.7_wp
         u(2, :) = -1.3_wp
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
         call check(s, abs(w) + whg <= tolw .and. maxval(abs(f)) <= tolf, &
                    'rigid translation: zero energy and force')
         wmax = 0.0_wp
         fmax = 0.0_wp
         do k = 1, size(angles)
            r = rot(angles(k)*pi/180.0_wp)
            u = matmul(r, x0) - x0
            call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
            wmax = max(wmax, abs(w) + whg)
            fmax = max(fmax, maxval(abs(f)))
         end do
         call check(s, wmax <= tolw, 'rigid rotations (90, 180, 37, -123 deg): zero energy')
         call check(s, fmax <= tolf, 'rigid rotations: zero internal force')
         ! a non-uniform finite deformation, then rotated
         call eval_force(st, ud, lam0, mu0, hg0, f, wd, whg, jmin, ebad)
         wd = wd + whg
         fs = maxval(abs(f))
         call check(s, jmin > 0.3_wp .and. ebad == 0 .and. wd > 0.0_wp, 'deformed state is valid')
         err = 0.0_wp
         do k = 1, size(angles)
            r = rot(angles(k)*pi/180.0_wp)
            u = matmul(r, x0 + ud) - x0
            call eval_force(st, u, lam0, mu0, hg0, fr, wr, whgr, jmin, ebad)
            err = max(err, abs(wr + whgr - wd)/wd)
            err = max(err, maxval(abs(fr - matmul(r, f)))/fs)
         end do
         call check(s, err <= 1e-12_wp, 'rotated deformed state: same W, forces rotated')
      end do
   end subroutine test_objectivity

   ! ---------------------------------------------------------------- consistency

   !> Internal force = d(total energy)/du by central differences, at a finite strain.
   subroutine test_consistency(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: w, whg, jmin, h, rel, fm(2, 2)
      integer :: nq, i, ebad
      integer(int64) :: seed
      type(setup_t) :: st
      character(len=40) :: buf

      call make_patch(x0, conn)
      allocate (u(2, 9), f(2, 9))
      fm = reshape([1.15_wp, 0.1_wp, -0.2_wp, 0.9_wp], [2, 2])
      seed = 777_int64
      do i = 1, 9
         u(:, i) = matmul(fm, x0(:, i)) - x0(:, i) + 0.2_wp*[rnd(seed) - 0.5_wp, rnd(seed) - 0.5_wp]
      end do
      h = 1e-6_wp
      do nq = 2, 1, -1
         call section(s, 'force = derivative of energy, '//trim(qname(nq)))
         call make_setup(nq, x0, conn, st, ebad)
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
         call check(s, ebad == 0 .and. jmin > 0.5_wp, 'finite strain, J > 0')
         if (nq == 1) call check(s, whg > 1e-3_wp*w, 'hourglass energy engaged')
         rel = gradient_error(u, f, h, energy)
         write (buf, '(a,es9.2)') 'max rel. error ', rel
         call check(s, rel <= 1e-6_wp, 'f = dW/du, 18 dofs ('//trim(buf)//')')
      end do
   contains
      real(wp) function energy(g)
         real(wp), intent(in) :: g(:, :)
         real(wp) :: ft(2, 9), whgt, jt
         integer :: ebt
         call eval_force(st, g, lam0, mu0, hg0, ft, energy, whgt, jt, ebt)
         energy = energy + whgt
      end function energy
   end subroutine test_consistency

   ! ---------------------------------------------------------------- mass

   !> Row-sum lumped mass: totals rho x area; a parallelogram gets equal quarters.
   subroutine test_mass(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), m(:)
      integer, allocatable :: conn(:, :)
      real(wp) :: area, rho, xq(2, 4)
      integer :: k
      integer, parameter :: ring(9) = [1, 2, 3, 6, 9, 8, 7, 4, 1]

      call section(s, 'lumped mass')
      rho = 7.8_wp
      call make_patch(x0, conn)
      allocate (m(9))
      m = 0.0_wp
      call q4_lumped_mass(4, 9, conn, x0, rho, m)
      area = 0.0_wp
      do k = 1, 8
         area = area + 0.5_wp*(x0(1, ring(k))*x0(2, ring(k + 1)) - x0(1, ring(k + 1))*x0(2, ring(k)))
      end do
      call check_close(s, sum(m), rho*area, 1e-14_wp*rho*area, 'distorted patch: sum = rho x area')
      call check(s, all(m > 0.0_wp), 'all nodal masses positive')
      ! a strongly distorted (trapezoid-like) single quad
      xq = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.2_wp, 2.2_wp, 1.0_wp, 0.4_wp, 0.7_wp], [2, 4])
      m(1:4) = 0.0_wp
      call q4_lumped_mass(1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, rho, m(1:4))
      area = 0.5_wp*((xq(1, 3) - xq(1, 1))*(xq(2, 4) - xq(2, 2)) &
                     - (xq(1, 4) - xq(1, 2))*(xq(2, 3) - xq(2, 1)))
      call check_close(s, sum(m(1:4)), rho*area, 1e-14_wp*rho*area, 'distorted quad: sum = rho x area')
      call check(s, maxval(m(1:4)) - minval(m(1:4)) > 0.1_wp*rho*area/4.0_wp, &
                 'distorted quad: unequal nodal masses')
      ! parallelogram: every node gets a quarter
      xq = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.5_wp, 2.7_wp, 2.0_wp, 0.7_wp, 1.5_wp], [2, 4])
      m(1:4) = 0.0_wp
      call q4_lumped_mass(1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, rho, m(1:4))
      area = 0.5_wp*((xq(1, 3) - xq(1, 1))*(xq(2, 4) - xq(2, 2)) &
                     - (xq(1, 4) - xq(1, 2))*(xq(2, 3) - xq(2, 1)))
      call check(s, maxval(abs(m(1:4) - 0.25_wp*rho*area)) <= 1e-14_wp*rho*area, &
                 'parallelogram: rho A / 4 at each node')
   end subroutine test_mass

   ! ---------------------------------------------------------------- stable step

   !> The estimate phi L/c never exceeds the exact limit 2/omega_max of the linearized element
   !> (generalized eigenproblem K v = omega^2 M v with the lumped mass, K by differences of the
   !> force kernel) on random convex quads, for both quadratures and nu up to 0.49.
   subroutine test_stable_dt(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nquad = 400
      real(wp), parameter :: nus(4) = [0.0_wp, 0.3_wp, 0.45_wp, 0.49_wp]
      real(wp) :: xq(2, 4), kmat(8, 8), mmat(8, 8), m(4), ev(8), work(64), dtx, dte, ratio
      real(wp) :: rmin(2), rmax(2), lambda, mu, rho, arat, skew, th, hmin, r(2, 2), pert
      integer :: nq, iq, inu, info, ebad, emin, efold, nbad(2), nfail(2), k
      integer(int64) :: seed
      type(setup_t) :: st
      character(len=100) :: buf

      call section(s, 'stable time step estimate vs exact element limit')
      rho = 1.3_wp
      rmin = huge(1.0_wp)
      rmax = 0.0_wp
      nbad = 0
      nfail = 0
      seed = 4242_int64
      do iq = 1, nquad
         ! rectangle of aspect 1..5, sheared, corners perturbed (moderately in the first half,
         ! strongly, up to wedge-like tapers, in the second), rotated; convex only
         pert = merge(0.35_wp, 1.2_wp, iq <= nquad/2)
         do
            arat = 1.0_wp + 4.0_wp*rnd(seed)
            skew = 1.2_wp*(rnd(seed) - 0.5_wp)
            xq = reshape([0.0_wp, 0.0_wp, arat, 0.0_wp, arat + skew, 1.0_wp, skew, 1.0_wp], [2, 4])
            if (iq > 3) then
               do k = 1, 4
                  xq(1, k) = xq(1, k) + pert*(rnd(seed) - 0.5_wp)
                  xq(2, k) = xq(2, k) + pert*(rnd(seed) - 0.5_wp)
               end do
            end if
            if (iq == 1) xq = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
            if (iq == 2) xq = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 3.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
            if (convex(xq)) exit
         end do
         th = 2.0_wp*pi*rnd(seed)
         r = rot(th)
         xq = matmul(r, xq) + 5.0_wp
         m = 0.0_wp
         call q4_lumped_mass(1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, rho, m)
         hmin = sqrt(minval(m)/rho)
         do inu = 1, size(nus)
            call lame_from_young(1.0_wp, nus(inu), lambda, mu)
            do nq = 2, 1, -1
               call make_setup(nq, xq, reshape([1, 2, 3, 4], [4, 1]), st, ebad)
               if (ebad /= 0) nbad(nq) = nbad(nq) + 1
               call tangent(st, lambda, mu, hmin, kmat)
               mmat = 0.0_wp
               mmat(1, 1) = m(1); mmat(2, 2) = m(1); mmat(3, 3) = m(2); mmat(4, 4) = m(2)
               mmat(5, 5) = m(3); mmat(6, 6) = m(3); mmat(7, 7) = m(4); mmat(8, 8) = m(4)
               call dsygv(1, 'N', 'U', 8, kmat, 8, mmat, 8, ev, work, size(work), info)
               if (info /= 0) then
                  nfail(nq) = nfail(nq) + 1
                  cycle
               end if
               dtx = 2.0_wp/sqrt(ev(8))
               call q4_stable_dt(nq, 1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, xq, &
                     neohookean_law(lambda, mu, rho), dte, emin, efold)
               ratio = dte/dtx
               rmin(nq) = min(rmin(nq), ratio)
               rmax(nq) = max(rmax(nq), ratio)
            end do
         end do
      end do
      do nq = 2, 1, -1
         write (buf, '(a,i0,a,f6.4,a,f6.4)') trim(qname(nq))//': ', nquad*size(nus), &
            ' cases, estimate/exact in [', rmin(nq), ', ', rmax(nq)
         write (output_unit, '(a)') '   '//trim(buf)//']'
         call check(s, nbad(nq) == 0 .and. nfail(nq) == 0, trim(qname(nq))//': all eigenproblems solved')
         call check(s, rmax(nq) <= 1.0_wp, trim(qname(nq))//': estimate <= 2/omega_max in every case')
         call check(s, rmin(nq) >= 0.45_wp, trim(qname(nq))//': estimate not needlessly small (>= 0.45)')
      end do
      call test_stable_dt_parallelogram(s, rho)
   contains
      logical function convex(xc)
         real(wp), intent(in) :: xc(2, 4)
         real(wp) :: e1(2), e2(2), ar
         integer :: a
         ar = 0.5_wp*((xc(1, 3) - xc(1, 1))*(xc(2, 4) - xc(2, 2)) &
                      - (xc(1, 4) - xc(1, 2))*(xc(2, 3) - xc(2, 1)))
         convex = ar > 0.0_wp
         do a = 1, 4
            e1 = xc(:, modulo(a, 4) + 1) - xc(:, a)
            e2 = xc(:, modulo(a - 2, 4) + 1) - xc(:, a)
            ! corner angles between ~6 and ~174 degrees
            convex = convex .and. (e1(1)*e2(2) - e1(2)*e2(1)) > 0.1_wp*norm2(e1)*norm2(e2)
         end do
      end function convex
   end subroutine test_stable_dt

   !> On parallelograms the estimate is exactly L/c, L = A/(longest diagonal), from the current
   !> geometry and the tangent wave speed at its J.
   subroutine test_stable_dt_parallelogram(s, rho)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: rho
      real(wp) :: xq(2, 4), lambda, mu, dte, dtx
      integer :: nq, ebad, emin, efold
      type(setup_t) :: st

      ! the square's a/(sqrt(2) c)
      call lame_from_young(1.0_wp, 0.3_wp, lambda, mu)
      xq = reshape([0.0_wp, 0.0_wp, 2.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, 0.0_wp, 2.0_wp], [2, 4])
      do nq = 2, 1, -1
         call make_setup(nq, xq, reshape([1, 2, 3, 4], [4, 1]), st, ebad)
         call q4_stable_dt(nq, 1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, xq, neohookean_law(lambda, mu, rho), &
                           dte, emin, efold)
         dtx = 2.0_wp/sqrt(2.0_wp)/sqrt((lambda + 2.0_wp*mu)/rho)
         call check_close(s, dte, dtx, 1e-14_wp*dtx, trim(qname(nq))//': square, a/(sqrt(2) c)')
      end do
      xq = reshape([0.0_wp, 0.0_wp, 3.0_wp, 0.5_wp, 3.8_wp, 2.5_wp, 0.8_wp, 2.0_wp], [2, 4])
      do nq = 2, 1, -1
         call make_setup(nq, xq, reshape([1, 2, 3, 4], [4, 1]), st, ebad)
         call q4_stable_dt(nq, 1, 4, reshape([1, 2, 3, 4], [4, 1]), xq, xq, neohookean_law(lambda, mu, rho), &
                           dte, emin, efold)
         ! area 3 x 2 - 0.5 x 0.8 = 5.6, longest diagonal |(3.8, 2.5)|
         dtx = 5.6_wp/norm2([3.8_wp, 2.5_wp])/sqrt((lambda + 2.0_wp*mu)/rho)
         call check_close(s, dte, dtx, 1e-13_wp*dtx, trim(qname(nq))//': parallelogram, A/(d_max c)')
      end do
      ! current geometry: a uniform dilatation J scales L by sqrt(J) and c^2 by the tangent
      xq = xq*1.1_wp
      call q4_stable_dt(st%nq, 1, 4, reshape([1, 2, 3, 4], [4, 1]), st%x0, xq, neohookean_law(lambda, mu, rho), &
                        dte, emin, efold)
      dtx = 1.1_wp*5.6_wp/norm2([3.8_wp, 2.5_wp]) &
            /sqrt((lambda + 2.0_wp*mu - 2.0_wp*lambda*log(1.21_wp))/rho)
      call check_close(s, dte, dtx, 1e-13_wp*dtx, 'dilated parallelogram: tangent wave speed at J')
   end subroutine test_stable_dt_parallelogram

   !> Tangent stiffness at u = 0 by central differences of the force kernel (symmetrized).
   subroutine tangent(st, lambda, mu, hsize, kmat)
      type(setup_t), intent(in) :: st
      real(wp), intent(in) :: lambda, mu, hsize
      real(wp), intent(out) :: kmat(8, 8)
      real(wp) :: u(2, 4), fp(2, 4), fm(2, 4), w, whg, jmin, h
      integer :: j, ebad
      h = 1e-5_wp*hsize
      do j = 1, 8
         u = 0.0_wp
         u(modulo(j - 1, 2) + 1, (j + 1)/2) = h
         call eval_force(st, u, lambda, mu, hg0, fp, w, whg, jmin, ebad)
         u(modulo(j - 1, 2) + 1, (j + 1)/2) = -h
         call eval_force(st, u, lambda, mu, hg0, fm, w, whg, jmin, ebad)
         kmat(:, j) = reshape(fp - fm, [8])/(2.0_wp*h)
      end do
      kmat = 0.5_wp*(kmat + transpose(kmat))
   end subroutine tangent

   ! ---------------------------------------------------------------- fused stable step

   !> The stable step of the force pass is q4_stable_dt's to the bit (value, element, folded
   !> element) on a distorted, deformed mesh of several blocks; the forces do not depend on how
   !> the elements are split into calls (the threads' ranges), and the energy is their sum.
   subroutine test_fused(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nx = 13, ny = 7
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), f2(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: w, whg, jmin, dt2, dtmin, w1, w2, whg1, whg2, d1, d2, j1, j2
      integer :: nq, ebad, emin, efold, em, ef, i, j, n, e, split, eb1, eb2, em1, em2, ef1, ef2
      integer(int64) :: seed
      type(setup_t) :: st

      n = (nx + 1)*(ny + 1)
      allocate (x0(2, n), u(2, n), f(2, n), f2(2, n), conn(4, nx*ny))
      seed = 99_int64
      do j = 0, ny
         do i = 0, nx
            x0(:, 1 + i + (nx + 1)*j) = [0.5_wp*i + 0.12_wp*(rnd(seed) - 0.5_wp), &
                                         0.5_wp*j + 0.12_wp*(rnd(seed) - 0.5_wp)]
            u(:, 1 + i + (nx + 1)*j) = [0.04_wp*(rnd(seed) - 0.5_wp) + 0.01_wp*j, 0.04_wp*(rnd(seed) - 0.5_wp)]
         end do
      end do
      do j = 0, ny - 1
         do i = 0, nx - 1
            e = 1 + i + nx*j
            conn(:, e) = [1 + i + (nx + 1)*j, 2 + i + (nx + 1)*j, 2 + i + (nx + 1)*(j + 1), 1 + i + (nx + 1)*(j + 1)]
         end do
      end do
      call check(s, nx*ny > 2*NBLOCK, 'test mesh spans several blocks')
      do nq = 2, 1, -1
         call section(s, 'stable step of the force pass, '//trim(qname(nq)))
         call make_setup(nq, x0, conn, st, ebad)
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad, dt2, emin, efold)
         call q4_stable_dt(nq, nx*ny, n, conn, x0, x0 + u, neohookean_law(lam0, mu0, 1.0_wp), dtmin, em, ef)
         call check(s, sqrt(dt2) == dtmin .and. emin == em .and. efold == ef .and. emin > 0, &
                    'same estimate and element as q4_stable_dt, to the bit')
         ! the same elements in two calls, split inside a block
         split = NBLOCK + 5
         f2 = 0.0_wp
         whg1 = 0.0_wp
         whg2 = 0.0_wp
         if (nq == 2) then
            call q4_force_2x2(split, n, conn(:, 1:split), x0, u, neohookean_law(lam0, mu0, 1.0_wp), &
                  f2, w1, j1, eb1, d1, em1, ef1)
            call q4_force_2x2(nx*ny - split, n, conn(:, split + 1:), x0, u, neohookean_law(lam0, &
                  mu0, 1.0_wp), f2, w2, j2, &
                              eb2, d2, em2, ef2)
         else
            call q4_force_1pt(split, n, conn(:, 1:split), x0, u, neohookean_law(lam0, mu0, 1.0_wp), &
                  hg0, f2, w1, whg1, j1, &
                              eb1, d1, em1, ef1)
            call q4_force_1pt(nx*ny - split, n, conn(:, split + 1:), x0, u, neohookean_law(lam0, &
                  mu0, 1.0_wp), hg0, f2, w2, &
                              whg2, j2, eb2, d2, em2, ef2)
         end if
         call check(s, all(f2 == f), 'forces of two calls equal those of one, to the bit')
         call check(s, abs(w1 + w2 - w) <= 1e-14_wp*w .and. abs(whg1 + whg2 - whg) <= 1e-14_wp*max(whg, tiny(1.0_wp)) &
                    .and. min(j1, j2) == jmin .and. min(d1, d2) == dt2, 'energies, jmin and dt of two calls')
      end do
   end subroutine test_fused

   ! ---------------------------------------------------------------- inversion

   !> Inverted elements are named by the force kernels, the step estimate and q4_check_reference.
   subroutine test_inversion(s)
      type(suite_t), intent(inout) :: s
      real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), xb(:, :)
      integer, allocatable :: conn(:, :)
      real(wp) :: w, whg, jmin, dtmin
      integer :: nq, ebad, emin, efold
      type(setup_t) :: st

      call make_patch(x0, conn)
      allocate (u(2, 9), f(2, 9))
      u = 0.0_wp
      ! node 7 (only in element 3) pushed through the element's other diagonal
      u(:, 7) = [1.5_wp, 0.5_wp] - x0(:, 7)
      do nq = 2, 1, -1
         call section(s, 'inversion flags, '//trim(qname(nq)))
         call make_setup(nq, x0, conn, st, ebad)
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
         call check(s, ebad == 3 .and. jmin <= 0.0_wp, 'node pushed through: ebad names element 3')
         call check(s, all(abs(f) < huge(1.0_wp)) .and. w == w, 'forces stay finite')
         call q4_stable_dt(nq, 4, 9, conn, x0, x0 + u, neohookean_law(lam0, mu0, 1.0_wp), dtmin, emin, efold)
         call check(s, emin == 3 .and. dtmin == 0.0_wp, 'stable step: zero, element 3')
         call check(s, efold == 3, 'stable step: element 3 is folded at a corner')
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad, dtmin, emin, efold)
         call check(s, emin == 3 .and. dtmin == 0.0_wp .and. efold == 3, &
                    'stable step of the force pass: zero, element 3, folded')
      end do
      ! node 9 (only in element 4) moved inside the element: a re-entrant corner whose area stays
      ! positive, so the centroid of the one-point rule does not see the fold
      u = 0.0_wp
      u(:, 9) = [1.3_wp, 1.1_wp] - x0(:, 9)
      call make_setup(1, x0, conn, st, ebad)
      call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad)
      call check(s, ebad == 0 .and. jmin > 0.0_wp, 're-entrant corner: the one-point centroid J stays positive')
      do nq = 2, 1, -1
         call make_setup(nq, x0, conn, st, ebad)
         call q4_stable_dt(nq, 4, 9, conn, x0, x0 + u, neohookean_law(lam0, mu0, 1.0_wp), dtmin, emin, efold)
         call check(s, efold == 4, trim(qname(nq))//': re-entrant corner in the current mesh flags element 4')
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad, dtmin, emin, efold)
         call check(s, efold == 4, trim(qname(nq))//': the force pass flags the re-entrant corner too')
      end do
      ! a flat corner: node 9 on the line through nodes 6 and 8 (a corner node pressed onto a flat
      ! rigid face with both neighbours, exactly or to round-off) is a triangle, not a fold; folded
      ! by 1e-6 of the edge it is a fold
      xb = x0
      xb(:, 6) = [2.0_wp, 2.0_wp]
      xb(:, 8) = [1.15_wp, 2.0_wp]
      xb(:, 9) = [1.5_wp, 2.0_wp]
      u = xb - x0
      do nq = 2, 1, -1
         call make_setup(nq, x0, conn, st, ebad)
         call q4_stable_dt(nq, 4, 9, conn, x0, xb, neohookean_law(lam0, mu0, 1.0_wp), dtmin, emin, efold)
         call check(s, efold == 0 .and. dtmin > 0.0_wp, trim(qname(nq))//': a corner flat to the bit is not folded')
         call eval_force(st, u, lam0, mu0, hg0, f, w, whg, jmin, ebad, dtmin, emin, efold)
         call check(s, efold == 0 .and. dtmin > 0.0_wp .and. ebad == 0, &
                    trim(qname(nq))//': nor in the force pass (x0 + u flat to round-off)')
         xb(2, 9) = 2.0_wp - 0.85e-6_wp
         call q4_stable_dt(nq, 4, 9, conn, x0, xb, neohookean_law(lam0, mu0, 1.0_wp), dtmin, emin, efold)
         call check(s, efold == 4, trim(qname(nq))//': the same corner folded by 1e-6 of its edge flags element 4')
         xb(2, 9) = 2.0_wp
      end do
      call section(s, 'inversion flags, reference geometry')
      ! a re-entrant (positive area) element 4: corner det J0 < 0
      xb = x0
      xb(:, 9) = [1.3_wp, 1.1_wp]
      do nq = 2, 1, -1
         call make_setup(nq, xb, conn, st, ebad)
         call check(s, ebad == 4, trim(qname(nq))//': re-entrant corner flags element 4')
      end do
      xb = x0
      xb(:, 4) = [1.6_wp, 0.3_wp]
      call make_setup(2, xb, conn, st, ebad)
      call check(s, ebad == 1, 'inverted reference element flags the first bad element (1)')
   end subroutine test_inversion

   !> Strain energy per reference volume of the law at the plane-strain F = g (from nh_piola).
   real(wp) function nh_w(g) result(w)
      real(wp), intent(in) :: g(2, 2)
      real(wp) :: p11(1), p12(1), p21(1), p22(1), w1(1)
      call nh_piola(1, lam0, mu0, g(1, 1:1), g(1, 2:2), g(2, 1:1), g(2, 2:2), [g(1, 1)*g(2, 2) - g(1, 2)*g(2, 1)], &
                    [1.0_wp], p11, p12, p21, p22, w1)
      w = w1(1)
   end function nh_w

   !> The block minimum (smallest squared stable step of a block, its first element, the first
   !> folded element) against the element-by-element scan it replaces, `if (dt2(k) < dt2min)`
   !> for k = 1 .. nb: 4000 blocks of random values with ties, +0 and -0, NaN, +Inf and huge,
   !> every nb from 1 to NBLOCK, incoming dt2min of huge, +0, a middle value or an earlier fold;
   !> dt2min compared bit for bit (the sign of a zero included), emin and efold exactly.
   subroutine test_block_minimum(s)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf
      type(suite_t), intent(inout) :: s
      real(wp) :: dt2(NBLOCK), good(NBLOCK), pool(8), d0, dm, dr
      integer(int64) :: seed
      integer :: trial, k, nb, em, er, fm, fr, bad, e0, f0
      call section(s, 'block minimum of the stable step')
      pool = [0.25_wp, 0.5_wp, 0.0_wp, -0.0_wp, ieee_value(1.0_wp, ieee_quiet_nan), &
              ieee_value(1.0_wp, ieee_positive_inf), huge(1.0_wp), 0.125_wp]
      seed = 20240611_int64
      bad = 0
      do trial = 1, 4000
         nb = 1 + mod(trial - 1, NBLOCK)
         do k = 1, NBLOCK
            if (rnd(seed) < 0.3_wp) then
               dt2(k) = pool(1 + int(8*rnd(seed)))
            else
               dt2(k) = rnd(seed)
            end if
            good(k) = merge(0.0_wp, 1.0_wp, rnd(seed) < 0.05_wp)
         end do
         select case (mod(trial, 4))
         case (0)
            d0 = huge(1.0_wp)
         case (1)
            d0 = 0.0_wp
         case (2)
            d0 = 0.3_wp
         case default
            d0 = 0.6_wp
         end select
         e0 = mod(trial, 3)
         f0 = merge(7, 0, mod(trial, 5) == 0)
         ! the scan
         dr = d0
         er = e0
         fr = f0
         do k = 1, nb
            if (dt2(k) < dr) then
               dr = dt2(k)
               er = 100 + k
            end if
         end do
         if (fr == 0) then
            do k = 1, nb
               if (.not. good(k) > 0.0_wp) then
                  fr = 100 + k
                  exit
               end if
            end do
         end if
         dm = d0
         em = e0
         fm = f0
         call block_minimum(nb, 100, dt2, good, dm, em, fm)
         if (transfer(dm, 1_int64) /= transfer(dr, 1_int64) .or. em /= er .or. fm /= fr) bad = bad + 1
      end do
      call check(s, bad == 0, 'the scan''s minimum (same bits), element and fold on 4000 blocks', &
                 'blocks that differ: '//itoa(bad))
   end subroutine test_block_minimum

   !> q4_stress (the points' stresses as vector blocks, nh_cauchy_block) gives the bits of the
   !> point-by-point form it replaced: nh_cauchy at each point of q4_deformation with J > 0, the
   !> means over the points in the order g = 1, ..., ng, from +0. 37 elements (a full block and
   !> a part of one), each on its own four nodes, displaced at random so far that some points
   !> have J <= 0 (they contribute zero stress) and some elements are inverted everywhere.
   subroutine test_stress_block(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: ne = 37
      real(wp) :: x0(2, 4*ne), u(2, 4*ne), sig(7, ne), ref(7, ne), fg(5, 4, ne), sp(4), jac, w, r
      integer :: conn(4, ne), e, a, g, nq, nneg
      integer(int64) :: seed
      real(wp), parameter :: cx(4) = [0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp], cy(4) = [0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp]
      seed = 20261124_int64
      do e = 1, ne
         do a = 1, 4
            conn(a, e) = 4*(e - 1) + a
            x0(:, conn(a, e)) = [real(e, wp) + cx(a), cy(a)]
            u(1, conn(a, e)) = 1.6_wp*(rnd(seed) - 0.5_wp)
            u(2, conn(a, e)) = 1.6_wp*(rnd(seed) - 0.5_wp)
         end do
      end do
      do nq = 1, 2
         call q4_stress(nq, ne, 4*ne, conn, x0, u, neohookean_law(lam0, mu0, 1.0_wp), sig)
         call q4_deformation(nq, ne, 4*ne, conn, x0, u, fg(:, 1:nq*nq, :))
         r = 1.0_wp/real(nq*nq, wp)
         nneg = 0
         do e = 1, ne
            ref(:, e) = 0.0_wp
            do g = 1, nq*nq
               if (fg(5, g, e) > 0.0_wp) then
                  call nh_cauchy(lam0, mu0, fg(1, g, e), fg(2, g, e), fg(3, g, e), fg(4, g, e), &
                                 sp(1), sp(2), sp(3), sp(4), jac, w)
                  ref(1:4, e) = ref(1:4, e) + r*sp
               else
                  nneg = nneg + 1
               end if
               ref(7, e) = ref(7, e) + r*fg(5, g, e)
            end do
            sp = ref(1:4, e)
            ref(5, e) = -(sp(1) + sp(2) + sp(3))/3.0_wp
            ref(6, e) = sqrt(0.5_wp*((sp(1) - sp(2))**2 + (sp(2) - sp(3))**2 + (sp(3) - sp(1))**2) &
                             + 3.0_wp*sp(4)**2)
         end do
         call check(s, nneg > 0 .and. nneg < ne*nq*nq, 'stress block test has points with J <= 0 and J > 0 ('// &
                    merge('2x2', '1pt', nq == 2)//')')
         call check(s, all(transfer(sig, 1_int64, 7*ne) == transfer(ref, 1_int64, 7*ne)), &
                    'q4_stress in vector blocks = nh_cauchy point by point, bit for bit ('// &
                    merge('2x2', '1pt', nq == 2)//')')
      end do
   end subroutine test_stress_block

end module test_element
