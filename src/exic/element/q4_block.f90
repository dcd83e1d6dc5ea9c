!> The block layout of the quadrilateral's force kernels (quad4.f90, q4_general.f90): NBLOCK
!> elements at a time as structure of arrays (NBLOCK, 4) (element, local node), the gather of
!> node values into a block (as (x, y) pairs (2, NBLOCK, 4), or split into x and y arrays) and
!> the scatter-add of a block's nodal forces, element by element in order (so that a node's sum
!> does not depend on the block or thread that adds it), and the checks of the Jacobians at a
!> block's points (positive, check_points).
module exic_element_q4_block
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: gather, gather_pairs, current, scatter, scatter_pairs, split_pairs, positive, check_points

   !> Elements per block of the force kernels: the block's work arrays (about 90 values per
   !> element) stay in the L1 cache, and its loops run over 32 elements (4 AVX-512 vectors).
   integer, parameter, public :: NBLOCK = 32

contains

   !> The reference coordinates and displacements of nb elements, (element, local node); lanes
   !> nb + 1 .. NBLOCK repeat element nb. The pairs of gather_pairs, which a vectorized loop
   !> splits into the x and y arrays: half the scalar loads and stores of copying value by value.
   pure subroutine gather(nb, nnode, conn, x0, u, xe, ye, uxe, uye)
      integer, intent(in) :: nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(out), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), dimension(2, NBLOCK, 4) :: p0, pu
      call gather_pairs(nb, nnode, conn, x0, u, p0, pu)
      call split_pairs(p0, xe, ye)
      call split_pairs(pu, uxe, uye)
   end subroutine gather

   !> The reference coordinates p0(:, k, a) and displacements pu(:, k, a) of nb elements as
   !> (x, y) pairs, each copied with one 16-byte load and store; lanes nb + 1 .. NBLOCK repeat
   !> element nb. Kernels that read the pairs directly (their loops split them in registers)
   !> save the stores and loads of a split.
   pure subroutine gather_pairs(nb, nnode, conn, x0, u, p0, pu)
      integer, intent(in) :: nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(out), dimension(2, NBLOCK, 4) :: p0, pu
      integer :: k, a, n
      ! pairs by scalar index: faster here than the vector gather instructions (measured)
      !GCC$ novector
      do k = 1, nb
         do a = 1, 4
            n = conn(a, k)
            p0(1, k, a) = x0(1, n)
            p0(2, k, a) = x0(2, n)
            pu(1, k, a) = u(1, n)
            pu(2, k, a) = u(2, n)
         end do
      end do
      do a = 1, 4
         do k = nb + 1, NBLOCK
            p0(:, k, a) = p0(:, nb, a)
            pu(:, k, a) = pu(:, nb, a)
         end do
      end do
   end subroutine gather_pairs

   !> Current coordinates in place of the displacements: ux <- x0 + u, uy <- y0 + v (the same
   !> sums as the stepper's positions, hence the same bits).
   pure subroutine current(xe, ye, uxe, uye)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye
      real(wp), intent(inout), dimension(NBLOCK, 4) :: uxe, uye
      integer :: k, a
      do a = 1, 4
         do k = 1, NBLOCK
            uxe(k, a) = xe(k, a) + uxe(k, a)
            uye(k, a) = ye(k, a) + uye(k, a)
         end do
      end do
   end subroutine current

   !> f(:, conn(a, k)) += (fx(k, a), fy(k, a)) for the block's nb elements, in order. The forces
   !> are interleaved into (x, y) pairs first (a vectorized loop), so that each node takes one
   !> 16-byte load, addition and store: the same additions in the same order as value by value.
   pure subroutine scatter(nb, nnode, conn, fx, fy, f)
      integer, intent(in) :: nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in), dimension(NBLOCK, 4) :: fx, fy
      real(wp), intent(inout) :: f(2, nnode)
      real(wp) :: fp(2, NBLOCK, 4)
      integer :: k, a
      do a = 1, 4
         do k = 1, NBLOCK
            fp(1, k, a) = fx(k, a)
            fp(2, k, a) = fy(k, a)
         end do
      end do
      call scatter_pairs(nb, nnode, conn, fp, f)
   end subroutine scatter

   !> f(:, conn(a, k)) += fp(:, k, a) for the block's nb elements, in order (scatter).
   pure subroutine scatter_pairs(nb, nnode, conn, fp, f)
      integer, intent(in) :: nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: fp(2, NBLOCK, 4)
      real(wp), intent(inout) :: f(2, nnode)
      real(wp) :: t1, t2
      integer :: k, a, n
      !GCC$ novector
      do k = 1, nb
         do a = 1, 4
            n = conn(a, k)
            t1 = f(1, n) + fp(1, k, a)
            t2 = f(2, n) + fp(2, k, a)
            f(1, n) = t1
            f(2, n) = t2
         end do
      end do
   end subroutine scatter_pairs

   !> fx(k, a) = fp(1, k, a), fy(k, a) = fp(2, k, a).
   pure subroutine split_pairs(fp, fx, fy)
      real(wp), intent(in) :: fp(2, NBLOCK, 4)
      real(wp), intent(out), dimension(NBLOCK, 4) :: fx, fy
      integer :: k, a
      do a = 1, 4
         do k = 1, NBLOCK
            fx(k, a) = fp(1, k, a)
            fy(k, a) = fp(2, k, a)
         end do
      end do
   end subroutine split_pairs

   !> js = J where J is a positive normal number, else 1 (so that the law stays finite on an
   !> element the caller rejects: check_points rejects J < tiny, i.e. J <= 0 and the subnormal
   !> J below 2.2e-308, whose logarithm the laws' ln_normal_block does not take).
   pure subroutine positive(n, jac, js)
      integer, intent(in) :: n
      real(wp), intent(in) :: jac(n)
      real(wp), intent(out) :: js(n)
      integer :: q
      do q = 1, n
         js(q) = merge(jac(q), 1.0_wp, jac(q) >= tiny(1.0_wp))
      end do
   end subroutine positive

   !> jmin over the points jac(NBLOCK, np) of the block's nb elements; ebad (when 0) becomes the
   !> first element off + k with J <= 0 at a point (or a subnormal J > 0, below tiny = 2.2e-308:
   !> an element crushed that far is rejected as inverted, see positive).
   pure subroutine check_points(nb, np, off, jac, jmin, ebad)
      integer, intent(in) :: nb, np, off
      real(wp), intent(in) :: jac(NBLOCK, np)
      real(wp), intent(inout) :: jmin
      integer, intent(inout) :: ebad
      real(wp) :: m
      integer :: k, g
      m = huge(1.0_wp)
      do g = 1, np
         do k = 1, nb
            m = min(m, jac(k, g))
         end do
      end do
      jmin = min(jmin, m)
      if (ebad /= 0 .or. m >= tiny(1.0_wp)) return
      do k = 1, nb
         if (any(jac(k, :) < tiny(1.0_wp))) then
            ebad = off + k
            return
         end if
      end do
   end subroutine check_points

end module exic_element_q4_block
