!> The tangential state of penalty friction under AUTOmatic contact, kept per pair of surfaces
!> (doc/contact-detection.md, "PENAlty under AUTOmatic").
!>
!> A penalty pass with friction carries the tangential force and slip speed of its slave nodes
!> from step to step (penalty_history_t, src/exic/contact/penalty.f90). AUTOmatic contact makes
!> its passes per step, only for the pairs of surfaces (slave surface i, master surface j) that
!> have candidates, so that state cannot live in a pass: it is kept here, per pair (i, j), as the
!> list of the pass's slave nodes with a state (the pass's `nodes(1:n)`) and their force and slip
!> speed. Before the pair's pass the state is put into a clean work history of the size of the
!> mesh (`load`); after it, taken back and the work history cleaned (`store`). The pass thus sees
!> the very values a pass of its own over the whole run would hold: a pair without candidates in
!> a step keeps its state untouched, as its pass did when its search found nothing. Only pairs
!> that have had a state are held, each with its own nodes: nothing of the size of the number
!> of pairs of surfaces.
module exic_contact_pair_history
   use exic_base_kinds, only: wp, i8
   use exic_base_grow, only: grow
   use exic_base_sort, only: search_sorted
   use exic_contact_penalty, only: penalty_history_t
   implicit none
   private

   public :: pair_history_t

   !> The state of one pair: nodes(1:n) of the pass's history and their force and slip speed.
   type :: held_t
      integer :: n = 0
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: q(:), vslip(:)
   end type held_t

   !> The states of the pairs of surfaces that have one, found by (slave, master).
   type :: pair_history_t
      integer :: npair = 0
      !> (npair) the pairs as increasing keys (`pair_key`: the order of (slave, master)) and
      !> where each one's state is
      integer(i8), allocatable :: key(:)
      integer, allocatable :: at(:)
      type(held_t), allocatable :: held(:)
   contains
      procedure :: load => history_load
      procedure :: store => history_store
      procedure :: total => history_total
      procedure :: flatten => history_flatten
      procedure :: unflatten => history_unflatten
   end type pair_history_t

contains

   !> Key of pair (i, j): its order is that of (i, j), slave first (surface numbers are
   !> positive and below 2^31).
   elemental integer(i8) function pair_key(i, j) result(key)
      integer, intent(in) :: i, j
      key = shiftl(int(i, i8), 32) + int(j, i8)
   end function pair_key

   !> Position of pair (i, j) in the sorted list, or minus the position it would be inserted at.
   integer function find(self, i, j) result(pos)
      type(pair_history_t), intent(in) :: self
      integer, intent(in) :: i, j
      pos = -1
      if (self%npair > 0) pos = search_sorted(self%key(1:self%npair), pair_key(i, j))
   end function find

   !> The state of pair (i, j) into h, a history with no state (every q 0, every vslip -1, n 0).
   subroutine history_load(self, i, j, h)
      class(pair_history_t), intent(in) :: self
      integer, intent(in) :: i, j
      type(penalty_history_t), intent(inout) :: h
      integer :: pos, n
      pos = find(self, i, j)
      if (pos <= 0) return
      associate (s => self%held(self%at(pos)))
         n = s%n
         if (n == 0) return
         call grow(h%nodes, n)
         h%nodes(1:n) = s%nodes(1:n)
         h%q(s%nodes(1:n)) = s%q(1:n)
         h%vslip(s%nodes(1:n)) = s%vslip(1:n)
         h%n = n
      end associate
   end subroutine history_load

   !> The state in h becomes pair (i, j)'s; h is left without state.
   subroutine history_store(self, i, j, h)
      class(pair_history_t), intent(inout) :: self
      integer, intent(in) :: i, j
      type(penalty_history_t), intent(inout) :: h
      integer :: pos, n
      n = h%n
      pos = find(self, i, j)
      if (pos <= 0) then
         if (n == 0) return
         pos = -pos
         call insert(self, pos, i, j)
      end if
      associate (s => self%held(self%at(pos)))
         s%n = n
         if (n > 0) then
            call grow(s%nodes, n)
            call grow(s%q, n)
            call grow(s%vslip, n)
            s%nodes(1:n) = h%nodes(1:n)
            s%q(1:n) = h%q(h%nodes(1:n))
            s%vslip(1:n) = h%vslip(h%nodes(1:n))
            h%q(h%nodes(1:n)) = 0.0_wp
            h%vslip(h%nodes(1:n)) = -1.0_wp
         end if
      end associate
      h%n = 0
   end subroutine history_store

   !> A new pair (i, j) at position pos of the sorted list, its state the next free one.
   subroutine insert(self, pos, i, j)
      type(pair_history_t), intent(inout) :: self
      integer, intent(in) :: pos, i, j
      type(held_t), allocatable :: tmp(:)
      integer :: n, k
      n = self%npair + 1
      call grow(self%key, n)
      call grow(self%at, n)
      if (.not. allocated(self%held)) allocate (self%held(8))
      if (n > size(self%held)) then
         allocate (tmp(2*size(self%held)))
         do k = 1, self%npair
            call move_held(self%held(k), tmp(k))
         end do
         call move_alloc(tmp, self%held)
      end if
      self%key(pos + 1:n) = self%key(pos:n - 1)
      self%at(pos + 1:n) = self%at(pos:n - 1)
      self%key(pos) = pair_key(i, j)
      self%at(pos) = n
      self%npair = n
   end subroutine insert

   subroutine move_held(a, b)
      type(held_t), intent(inout) :: a, b
      b%n = a%n
      if (allocated(a%nodes)) call move_alloc(a%nodes, b%nodes)
      if (allocated(a%q)) call move_alloc(a%q, b%q)
      if (allocated(a%vslip)) call move_alloc(a%vslip, b%vslip)
   end subroutine move_held

   !> Entries of all states (the size of flatten's node arrays).
   integer function history_total(self) result(n)
      class(pair_history_t), intent(in) :: self
      integer :: k
      n = 0
      do k = 1, self%npair
         n = n + self%held(self%at(k))%n
      end do
   end function history_total

   !> Every pair and its state as plain arrays (for restart files): pair k is (pairs(1, k),
   !> pairs(2, k)) with counts(k) entries; nodes, q, vslip: the entries, pair after pair.
   subroutine history_flatten(self, pairs, counts, nodes, q, vslip)
      class(pair_history_t), intent(in) :: self
      integer, intent(out) :: pairs(2, self%npair), counts(self%npair), nodes(:)
      real(wp), intent(out) :: q(:), vslip(:)
      integer :: k, m, n
      m = 0
      do k = 1, self%npair
         associate (s => self%held(self%at(k)))
            n = s%n
            pairs(:, k) = [int(shiftr(self%key(k), 32)), int(iand(self%key(k), int(z'ffffffff', i8)))]
            counts(k) = n
            if (n == 0) cycle
            nodes(m + 1:m + n) = s%nodes(1:n)
            q(m + 1:m + n) = s%q(1:n)
            vslip(m + 1:m + n) = s%vslip(1:n)
            m = m + n
         end associate
      end do
   end subroutine history_flatten

   !> The inverse of flatten: the pairs (sorted, as flatten gives them) and their states.
   subroutine history_unflatten(self, npair, pairs, counts, nodes, q, vslip)
      class(pair_history_t), intent(inout) :: self
      integer, intent(in) :: npair, pairs(2, npair), counts(npair), nodes(:)
      real(wp), intent(in) :: q(:), vslip(:)
      integer :: k, m, n
      if (allocated(self%held)) deallocate (self%held, self%key, self%at)
      allocate (self%held(max(npair, 8)), self%key(npair), self%at(npair))
      self%npair = npair
      m = 0
      do k = 1, npair
         n = counts(k)
         self%key(k) = pair_key(pairs(1, k), pairs(2, k))
         self%at(k) = k
         associate (s => self%held(k))
            s%n = n
            s%nodes = nodes(m + 1:m + n)
            s%q = q(m + 1:m + n)
            s%vslip = vslip(m + 1:m + n)
         end associate
         m = m + n
      end do
   end subroutine history_unflatten

end module exic_contact_pair_history
