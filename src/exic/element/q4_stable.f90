!> The stable time step of the 4-node quadrilateral (the estimate of q4_stable_dt, below) per
!> block of NBLOCK elements (q4_block.f90): from the reference and current corners, the corner
!> triangles that tell a folded element, and the block's smallest step. The force kernels
!> (q4_2x2.f90, q4_1pt.f90, q4_general.f90) call it once per block from their gathered corners,
!> so that the step costs no second pass over the mesh.
!>
!> Each block routine's loop and the per-element estimate it calls (corner_estimate) are in this
!> one file, so that gcc inlines the estimate into the loops, which then vectorize.
module exic_element_q4_stable
   use exic_base_kinds, only: wp
   use exic_material_law, only: law_t, law_wave_speed2
   use exic_element_q4_block, only: NBLOCK, gather
   implicit none
   private

   public :: q4_stable_dt, stable_block, stable_block_u, stable_block_pairs, block_minimum
   public :: stable_correction

   abstract interface
      !> A correction of a block's squared stable steps dt2 (the plane estimate on entry) from
      !> its reference corners (xr, yr) and current corners (xc, yc): the ring step of
      !> axisymmetric elements (q4_general.f90).
      pure subroutine stable_correction(nq, xr, yr, xc, yc, law, dt2)
         import :: wp, law_t, NBLOCK
         integer, intent(in) :: nq
         real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, xc, yc
         type(law_t), intent(in) :: law
         real(wp), intent(inout) :: dt2(NBLOCK)
      end subroutine stable_correction
   end interface

contains

   !> Smallest critical time step of the elements from the current geometry x(2, nnode) (the same
   !> estimate, to the bit, as the force kernels compute at x = x0 + u):
   !>
   !>     dt_e = phi L_e / c_e,   L_e = A/(longest diagonal) of the current quad,
   !>     c_e^2 = (lambda + 2 mu - 2 lambda ln J)/rho0 at J = A/A0
   !>
   !> (A0 the reference area; c_e: the tangent dilatational wave speed of eq. 7.2, floored at
   !> sqrt(mu/rho0)). phi corrects for taper; with t = T_min/A, T_min the smallest of the four
   !> corner triangles (a-1, a, a+1), i.e. twice the smallest corner Jacobian:
   !>   nq = 2: phi^2 = 4 min_g det J_g / A = (1 - 1/sqrt 3) + (2/sqrt 3) t  (smallest Gauss point)
   !>   nq = 1: phi^2 = 4 m_min/(rho A)     = 2/3 (1 + t)                   (lightest node)
   !> Both give phi = 1 (L/c) for every parallelogram. Against the exact limit 2/omega_max of the
   !> linearized element with lumped mass, over random convex quads (corner angles down to 1 deg,
   !> tapers beyond 10:1, nu in [0, 0.499], hourglass coefficient up to 0.25), phi L/c stayed below
   !> 0.995 of the limit; L/c alone exceeds it by up to 2% for tapers of 1.6:1 and by 45% for
   !> wedge-like quads. An element with A <= 0 or phi^2 <= 0 gives dt_e = 0.
   !> dtmin: the smallest dt_e; emin: the first element that gives it; efold: the first element
   !> folded at a corner (a corner triangle of negative area beyond round-off, i.e. det J < 0 at that node,
   !> which the Gauss points of either rule need not see), 0 if none. `correct`: a correction of
   !> each block's estimate before its minimum is taken (the ring step of axisymmetric elements,
   !> q4g_stable_dt).
   pure subroutine q4_stable_dt(nq, nel, nnode, conn, x0, x, law, dtmin, emin, efold, correct)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), x(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      procedure(stable_correction), optional :: correct
      real(wp), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      real(wp) :: dt2(NBLOCK), good(NBLOCK), dt2min
      integer :: e0, nb

      dt2min = huge(1.0_wp)
      emin = 0
      efold = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call gather(nb, nnode, conn(:, e0:e0 + nb - 1), x0, x, xr, yr, xc, yc)
         call stable_block(nq, xr, yr, xc, yc, law, dt2, good)
         if (present(correct)) call correct(nq, xr, yr, xc, yc, law, dt2)
         call block_minimum(nb, e0 - 1, dt2, good, dt2min, emin, efold)
      end do
      dtmin = sqrt(dt2min)
   end subroutine q4_stable_dt

   !> Squared stable steps dt2(k) of a block with reference corners (xr, yr) and current corners
   !> (xc, yc) (q4_stable_dt), and good(k) = 1 where the element is not folded at a corner (the
   !> area positive, every corner triangle above -FLAT of it: a corner flat to round-off is a
   !> triangle, doc/decisions.md), 0 where it is. With A the area, T the smallest
   !> corner triangle and D the longest diagonal squared, phi^2 A^2 = (c0 A + c1 T) A, so
   !>     dt^2 = phi^2 A^2/(D c^2) = (c0 A + c1 T) A/(D c^2)
   !> takes one division, and phi^2 > 0 is c0 A + c1 T > 0 (A > 0). Areas are formed doubled
   !> (2 A, 2 T, 2 A0; the halving is exact and cancels: D is multiplied by 4 instead).
   pure subroutine stable_block(nq, xr, yr, xc, yc, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         xcl = xc(k, :)
         ycl = yc(k, :)
         call corner_estimate(c0, c1, xr(k, 1), xr(k, 2), xr(k, 3), xr(k, 4), yr(k, 1), yr(k, 2), &
                              yr(k, 3), yr(k, 4), xcl, ycl, good(k), ok(k), num(k), den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block

   !> stable_block from the reference corners (xr, yr) and the displacements (ux, uy) of the
   !> block: the current corners xr + ux, yr + uy (the sums of `current`) are formed in the loop
   !> instead of being stored and loaded again.
   pure subroutine stable_block_u(nq, xr, yr, ux, uy, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, ux, uy
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k, a

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         do a = 1, 4
            xcl(a) = xr(k, a) + ux(k, a)
            ycl(a) = yr(k, a) + uy(k, a)
         end do
         call corner_estimate(c0, c1, xr(k, 1), xr(k, 2), xr(k, 3), xr(k, 4), yr(k, 1), yr(k, 2), &
                              yr(k, 3), yr(k, 4), xcl, ycl, good(k), ok(k), num(k), den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block_u

   !> stable_block_u from the (x, y) pairs of gather_pairs: reference corners p0(:, k, a),
   !> displacements pu(:, k, a); the same sums and operations.
   pure subroutine stable_block_pairs(nq, p0, pu, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(2, NBLOCK, 4) :: p0, pu
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k, a

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         do a = 1, 4
            xcl(a) = p0(1, k, a) + pu(1, k, a)
            ycl(a) = p0(2, k, a) + pu(2, k, a)
         end do
         call corner_estimate(c0, c1, p0(1, k, 1), p0(1, k, 2), p0(1, k, 3), p0(1, k, 4), p0(2, k, 1), &
                              p0(2, k, 2), p0(2, k, 3), p0(2, k, 4), xcl, ycl, good(k), ok(k), num(k), &
                              den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block_pairs

   !> c0, c1 of phi^2 = c0 + c1 t for the rule nq (q4_stable_dt).
   pure subroutine taper_factors(nq, c0, c1)
      integer, intent(in) :: nq
      real(wp), intent(out) :: c0, c1
      real(wp), parameter :: s3 = 0.57735026918962576451_wp
      if (nq == 1) then
         c0 = 2.0_wp/3.0_wp
         c1 = 2.0_wp/3.0_wp
      else
         c0 = 1.0_wp - s3
         c1 = 2.0_wp*s3
      end if
   end subroutine taper_factors

   !> One element of stable_block: reference corners (xr1..4, yr1..4), current corners (xc, yc);
   !> good, ok (1 or 0), the numerator ph A and denominator D of dt^2 c^2 and the volume ratio jr.
   pure subroutine corner_estimate(c0, c1, xr1, xr2, xr3, xr4, yr1, yr2, yr3, yr4, xc, yc, good, ok, &
                                   num, den, jr)
      real(wp), intent(in) :: c0, c1, xr1, xr2, xr3, xr4, yr1, yr2, yr3, yr4, xc(4), yc(4)
      real(wp), intent(out) :: good, ok, num, den, jr
      !> a corner triangle within FLAT of the area is flat (three nodes on a line to round-off), not folded
      real(wp), parameter :: FLAT = 1.0e-10_wp
      real(wp) :: d1x, d1y, d2x, d2y, a2, a02, t2, pa, ph, ex(4), ey(4)
      integer :: a

      a02 = (xr3 - xr1)*(yr4 - yr2) - (yr3 - yr1)*(xr4 - xr2)
      d1x = xc(3) - xc(1)
      d1y = yc(3) - yc(1)
      d2x = xc(4) - xc(2)
      d2y = yc(4) - yc(2)
      a2 = d1x*d2y - d1y*d2x
      ! edges a -> a+1; the corner triangle (a-1, a, a+1) is e_(a-1) x e_a / 2
      do a = 1, 4
         ex(a) = xc(modulo(a, 4) + 1) - xc(a)
         ey(a) = yc(modulo(a, 4) + 1) - yc(a)
      end do
      t2 = min(min(ex(4)*ey(1) - ey(4)*ex(1), ex(1)*ey(2) - ey(1)*ex(2)), &
               min(ex(2)*ey(3) - ey(2)*ex(3), ex(3)*ey(4) - ey(3)*ex(4)))
      ! masks as reals (1 or 0), so that the callers' loops vectorize
      pa = merge(1.0_wp, 0.0_wp, a2 > 0.0_wp)
      good = pa*merge(1.0_wp, 0.0_wp, t2 > -FLAT*a2)
      ph = c0*a2 + c1*t2
      ok = pa*merge(1.0_wp, 0.0_wp, ph > 0.0_wp)
      num = ph*a2
      den = 4.0_wp*max(d1x*d1x + d1y*d1y, d2x*d2x + d2y*d2y)
      ! J = A/A0, or 1 where the estimate is 0 (a0/a0: a division under a condition would
      ! stop the vectorizer); at least tiny, the smallest normal number (nh_wave_speed2_block)
      jr = max(merge(a2, a02, ok > 0.0_wp)/a02, tiny(1.0_wp))
   end subroutine corner_estimate

   !> dt2 = num/(den c^2) where ok, else 0, with c^2 the wave speed at the volume ratio jr.
   pure subroutine stable_finish(law, num, den, jr, ok, dt2)
      type(law_t), intent(in) :: law
      real(wp), intent(in), dimension(NBLOCK) :: num, den, jr, ok
      real(wp), intent(out) :: dt2(NBLOCK)
      real(wp) :: c2(NBLOCK)
      integer :: k
      call law_wave_speed2(law, NBLOCK, jr, c2)
      do k = 1, NBLOCK
         dt2(k) = merge(num(k)/merge(den(k)*c2(k), 1.0_wp, ok(k) > 0.0_wp), 0.0_wp, ok(k) > 0.0_wp)
      end do
   end subroutine stable_finish

   !> dt2min/emin: the smallest dt2 of the block's nb elements (first element off + k on ties)
   !> if below dt2min; efold (when 0): the first folded element (good = 0, stable_block).
   !> What the scan k = 1 .. nb with `if (dt2(k) < dt2min)` gives, from the block's smallest
   !> value m (a loop that vectorizes; a NaN, never below anything in the scan, counts as huge,
   !> which is not below dt2min <= huge either) and, only when m < dt2min, the first k with
   !> dt2(k) = m, whose value is taken (the scan keeps the first of -0 and +0 it meets). Every
   !> element is good when the smallest good (0 or 1) is 1.
   pure subroutine block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      integer, intent(in) :: nb, off
      real(wp), intent(in) :: dt2(NBLOCK), good(NBLOCK)
      real(wp), intent(inout) :: dt2min
      integer, intent(inout) :: emin, efold
      real(wp) :: m, g
      integer :: k
      m = dt2min
      g = 1.0_wp
      do k = 1, nb
         m = min(m, merge(dt2(k), huge(1.0_wp), dt2(k) == dt2(k)))
         g = min(g, good(k))
      end do
      if (m < dt2min) then
         do k = 1, nb
            if (dt2(k) == m) then
               dt2min = dt2(k)
               emin = off + k
               exit
            end if
         end do
      end if
      if (efold /= 0 .or. g > 0.0_wp) return
      do k = 1, nb
         if (.not. good(k) > 0.0_wp) then
            efold = off + k
            return
         end if
      end do
   end subroutine block_minimum

end module exic_element_q4_stable
