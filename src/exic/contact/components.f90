!> Connected components of a step's contact candidates (doc/contact-detection.md, "Components
!> of S", eq. D.3-D.4).
!>
!> S = G^T M^-1 G couples two candidates only through what both touch: a node (S(i, j) sums
!> w_ki w_kj d_i . M^-1 d_j over their common nodes k), a free rigid body, or the massless
!> face of `LAGRange,ENERgy`. Candidates are joined (union-find) when they share one of those;
!> numbered by component, S is block diagonal and every block can be factorised on its own.
!> Components are numbered by their first candidate and list their members in candidate order,
!> so the split depends only on the candidates and their order.
module exic_contact_components
   use exic_base_grow, only: grow
   use exic_base_union_find, only: set_root, join_sets
   implicit none
   private

   public :: components_t

   !> The components of m candidates: component c holds list(start(c):start(c + 1) - 1).
   type :: components_t
      integer :: m = 0                       !< candidates
      integer :: n = 0                       !< components (after `label`)
      integer, allocatable :: root(:)        !< (m) union-find links; a root is its component's first candidate
      integer, allocatable :: start(:)       !< (n + 1) where each component's members begin in `list`
      integer, allocatable :: list(:)        !< (m) members, ascending within a component
      integer, allocatable :: loc(:)         !< (m) position of a candidate within its component
      integer, allocatable :: id(:)          !< (m) component of a candidate
   contains
      procedure :: reset => components_reset
      procedure :: join => components_join
      procedure :: join_nodes => components_join_nodes
      procedure :: join_list => components_join_list
      procedure :: label => components_label
   end type components_t

contains

   !> m candidates, each a component of its own.
   subroutine components_reset(self, m)
      class(components_t), intent(inout) :: self
      integer, intent(in) :: m
      integer :: i
      self%m = m
      self%n = 0
      call grow(self%root, m)
      do i = 1, m
         self%root(i) = i
      end do
   end subroutine components_reset

   !> Candidates i and j are in one component (the larger root is linked to the smaller).
   subroutine components_join(self, i, j)
      class(components_t), intent(inout) :: self
      integer, intent(in) :: i, j
      call join_sets(self%root, i, j)
   end subroutine components_join

   !> Join the candidates that share a node: candidate i with local nodes lnode(:, i) (0: a
   !> node of weight 0) joins the first candidate of each of them in the incidence
   !> nstart(nloc + 1), nlist (local node -> candidates of nonzero weight at it, compressed rows).
   subroutine components_join_nodes(self, m, lnode, nloc, nstart, nlist)
      class(components_t), intent(inout) :: self
      integer, intent(in) :: m, nloc
      integer, intent(in) :: lnode(3, m), nstart(nloc + 1), nlist(:)
      integer :: i, k
      do i = 1, m
         do k = 1, 3
            if (lnode(k, i) == 0) cycle
            call self%join(i, nlist(nstart(lnode(k, i))))
         end do
      end do
   end subroutine components_join_nodes

   !> Join every candidate of `cand` (a free rigid body's, or those on a massless face).
   subroutine components_join_list(self, cand)
      class(components_t), intent(inout) :: self
      integer, intent(in) :: cand(:)
      integer :: e
      do e = 2, size(cand)
         call self%join(cand(1), cand(e))
      end do
   end subroutine components_join_list

   !> Number the components by their first candidate and list their members in candidate order.
   subroutine components_label(self)
      class(components_t), intent(inout) :: self
      integer :: i, r, c, m
      m = self%m
      call grow(self%id, m)
      ! a root is the smallest candidate of its component, so it is labelled before every other
      ! member
      self%n = 0
      do i = 1, m
         r = set_root(self%root, i)
         if (r == i) then
            self%n = self%n + 1
            self%id(i) = self%n
         else
            self%id(i) = self%id(r)
         end if
      end do
      call grow(self%loc, m)
      call grow(self%list, m)
      call grow(self%start, self%n + 1)
      self%start(1:self%n + 1) = 0
      do i = 1, m
         c = self%id(i)
         self%start(c + 1) = self%start(c + 1) + 1
      end do
      self%start(1) = 1
      do c = 1, self%n
         self%start(c + 1) = self%start(c + 1) + self%start(c)
      end do
      ! fill in candidate order, start(c) running; then the position within the component
      do i = 1, m
         c = self%id(i)
         self%list(self%start(c)) = i
         self%start(c) = self%start(c) + 1
      end do
      do c = self%n, 1, -1
         self%start(c + 1) = self%start(c)
      end do
      self%start(1) = 1
      do c = 1, self%n
         do r = self%start(c), self%start(c + 1) - 1
            self%loc(self%list(r)) = r - self%start(c) + 1
         end do
      end do
   end subroutine components_label

end module exic_contact_components
