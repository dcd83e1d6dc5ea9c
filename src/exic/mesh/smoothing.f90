!> Element values carried to the nodes: at each node, the average of the values of the elements
!> around it, weighted by their areas in the given configuration (the lumped L2 projection of a
!> piecewise-constant field onto bilinear shape functions when each quadrilateral gives a quarter
!> of its area to each corner). A node whose elements all have zero area gets their plain mean;
!> nodes that no element uses get 0.
module exic_mesh_smoothing
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: nodal_average, quad_area

contains

   !> node(c, n) = sum over the elements e at node n of |A_e| cell(c, e) / sum of |A_e|, with
   !> A_e the area of element e (corners conn(:, e)) at the coordinates x(2, nnode).
   pure subroutine nodal_average(ncomp, nnode, nelem, conn, x, cell, node)
      integer, intent(in) :: ncomp, nnode, nelem
      integer, intent(in) :: conn(4, nelem)
      real(wp), intent(in) :: x(2, nnode), cell(ncomp, nelem)
      real(wp), intent(out) :: node(ncomp, nnode)
      real(wp), allocatable :: weight(:)
      integer, allocatable :: count(:)
      real(wp) :: area
      integer :: e, k, n

      allocate (weight(nnode), count(nnode))
      node = 0.0_wp
      weight = 0.0_wp
      count = 0
      do e = 1, nelem
         area = abs(quad_area(x(:, conn(1, e)), x(:, conn(2, e)), x(:, conn(3, e)), x(:, conn(4, e))))
         do k = 1, 4
            n = conn(k, e)
            node(:, n) = node(:, n) + area*cell(:, e)
            weight(n) = weight(n) + area
            count(n) = count(n) + 1
         end do
      end do
      do n = 1, nnode
         if (weight(n) > 0.0_wp) node(:, n) = node(:, n)/weight(n)
      end do
      ! nodes whose elements all have zero area: the plain mean, in a second pass only when
      ! there are such nodes (or a weight that is not positive: the weighted sums are dropped)
      if (.not. any(.not. (weight > 0.0_wp) .and. count > 0)) return
      do n = 1, nnode
         if (.not. (weight(n) > 0.0_wp)) node(:, n) = 0.0_wp
      end do
      do e = 1, nelem
         do k = 1, 4
            n = conn(k, e)
            if (.not. (weight(n) > 0.0_wp)) node(:, n) = node(:, n) + cell(:, e)
         end do
      end do
      do n = 1, nnode
         if (.not. (weight(n) > 0.0_wp) .and. count(n) > 0) node(:, n) = node(:, n)/real(count(n), wp)
      end do
   end subroutine nodal_average

   !> Signed area of the quadrilateral p1 p2 p3 p4 (positive when counterclockwise).
   pure real(wp) function quad_area(p1, p2, p3, p4) result(a)
      real(wp), intent(in) :: p1(2), p2(2), p3(2), p4(2)
      a = 0.5_wp*((p3(1) - p1(1))*(p4(2) - p2(2)) - (p4(1) - p2(1))*(p3(2) - p1(2)))
   end function quad_area

end module exic_mesh_smoothing
