!> Start-up overlap test: whether a node that the static detection finds behind a master
!> segment lies inside the material next to that segment.
!>
!> The static detection (src/exic/contact/detect.f90, static_pair) accepts a node whose
!> projection falls within the segment and whose distance behind the segment's line is below the
!> search depth (a share of the mean segment length). Beside a very elongated element that
!> distance says nothing: a node of a block standing beside a wall of 10 x 1505 elements lies
!> "behind" the far face of the block's own neighbour, or behind the wall's far face, without
!> being inside anything. The overlap is real only when the node is inside an element next to
!> the segment: an element that has one of the segment's nodes as a corner (the element that
!> owns the segment and those around its ends), tested with the crossing-number rule
!> (point_in_quad). A segment none of whose nodes belongs to an element (a FACEts line of bare
!> nodes) keeps the distance rule.
module exic_contact_overlap
   use exic_base_kinds, only: wp
   use exic_contact_inside, only: point_in_quad
   implicit none
   private

   public :: node_element_lists, inside_near

contains

   !> The elements of each node: elements list(head(i):head(i + 1) - 1) have node i as a corner.
   pure subroutine node_element_lists(nnode, nelem, conn, head, list)
      integer, intent(in) :: nnode, nelem, conn(4, nelem)
      integer, allocatable, intent(out) :: head(:), list(:)
      integer :: e, k, i
      integer, allocatable :: fill(:)
      allocate (head(nnode + 1), source=0)
      do e = 1, nelem
         do k = 1, 4
            i = conn(k, e)
            if (i < 1 .or. i > nnode) cycle
            if (k > 1) then
               if (any(conn(1:k - 1, e) == i)) cycle    ! a collapsed corner counts once
            end if
            head(i + 1) = head(i + 1) + 1
         end do
      end do
      head(1) = 1
      do i = 1, nnode
         head(i + 1) = head(i) + head(i + 1)
      end do
      allocate (list(head(nnode + 1) - 1), fill(nnode))
      fill = head(1:nnode)
      do e = 1, nelem
         do k = 1, 4
            i = conn(k, e)
            if (i < 1 .or. i > nnode) cycle
            if (k > 1) then
               if (any(conn(1:k - 1, e) == i)) cycle
            end if
            list(fill(i)) = e
            fill(i) = fill(i) + 1
         end do
      end do
   end subroutine node_element_lists

   !> True when node `node` lies inside an element with m(1) or m(2) as a corner (not one of
   !> its own elements), or when neither m(1) nor m(2) belongs to any element.
   pure logical function inside_near(node, m, nnode, x, nelem, conn, head, list) result(inside)
      integer, intent(in) :: node, m(2), nnode, nelem, conn(4, nelem), head(nnode + 1), list(:)
      real(wp), intent(in) :: x(2, nnode)
      integer :: k, q, e
      inside = head(m(1) + 1) == head(m(1)) .and. head(m(2) + 1) == head(m(2))
      if (inside) return
      do k = 1, 2
         do q = head(m(k)), head(m(k) + 1) - 1
            e = list(q)
            if (any(conn(:, e) == node)) cycle
            if (point_in_quad(x(:, node), x(:, conn(:, e)))) then
               inside = .true.
               return
            end if
         end do
      end do
   end function inside_near

end module exic_contact_overlap
