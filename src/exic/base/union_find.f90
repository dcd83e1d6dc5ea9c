!> Union-find on a plain array of links (disjoint sets of 1..n): `parent(i)` is i's link, a root
!> links to itself. The root of a set is always its smallest member (the larger root is linked
!> to the smaller), so that the sets and their roots do not depend on the order of the joins;
!> find halves the path as it goes (Tarjan & van Leeuwen 1984). Used by TIE (mesh/tie.f90) and
!> by the components of the contact candidates (contact/components.f90).
module exic_base_union_find
   implicit none
   private

   public :: set_root, join_sets

contains

   !> The root of i's set (its smallest member), halving the path from i.
   integer function set_root(parent, i) result(r)
      integer, intent(inout) :: parent(:)
      integer, intent(in) :: i
      r = i
      do while (parent(r) /= r)
         parent(r) = parent(parent(r))
         r = parent(r)
      end do
   end function set_root

   !> Join the sets of a and b: the larger root is linked to the smaller.
   subroutine join_sets(parent, a, b)
      integer, intent(inout) :: parent(:)
      integer, intent(in) :: a, b
      integer :: ra, rb
      ra = set_root(parent, a)
      rb = set_root(parent, b)
      if (ra < rb) then
         parent(rb) = ra
      else if (rb < ra) then
         parent(ra) = rb
      end if
   end subroutine join_sets

end module exic_base_union_find
