!> The element history on several MPI ranks (doc/parallel.md, "Element history"): the history
!> of an element (a plastic or hypoelastic set's hist(nvar, nq*nq, nel)) is updated by every rank
!> that computes its block, with the same bits on each, and is stale on the other ranks. Before a
!> reader of the history (the .his stresses, the fields, the restart file) runs, the owners'
!> values are copied to every rank (one MPI_Allgatherv of values per call, never summed), so that
!> every rank holds the serial history of the elements read. One rank: nothing is done.
module exic_explicit_history_gather
   use exic_base_kinds, only: wp
   use exic_material_material, only: MAT_SOLID
   use exic_parallel_mpi, only: par_allgatherv
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_decomposition, only: decomposition_t
   implicit none
   private

   public :: decomposition_gather_history, history_stale

contains

   !> The owners' history of the elements `elems` (global numbers, any order, repeats allowed;
   !> default: every element of every set with a history) copied to every rank. Elements without
   !> a history (elastic, rigid, eroded) are passed over; when none of `elems` has one, no MPI
   !> call is made (every rank decides alike: the decomposition and the sets are the same on
   !> every rank). Collective: every rank calls it with the same `elems`.
   subroutine decomposition_gather_history(self, st, sets, elems)
      type(decomposition_t), intent(in) :: self
      type(state_t), intent(in) :: st
      type(element_set_t), intent(inout) :: sets(:)
      integer, intent(in), optional :: elems(:)
      integer :: k
      if (.not. self%active) return
      if (present(elems)) then
         call gather_list(self, st, sets, elems)
      else
         ! set by set: the buffers hold one set's history at a time
         do k = 1, size(sets)
            if (has_history(sets(k))) call gather_list(self, st, sets, sets(k)%elems)
         end do
      end if
   end subroutine decomposition_gather_history

   !> Some element history may be stale on this rank: several ranks and a set with a history
   !> (what a reader that cannot gather, after an error on one rank, must know).
   logical function history_stale(self, sets) result(stale)
      type(decomposition_t), intent(in) :: self
      type(element_set_t), intent(in) :: sets(:)
      integer :: k
      stale = .false.
      if (.not. self%active) return
      do k = 1, size(sets)
         if (has_history(sets(k))) stale = .true.
      end do
   end function history_stale

   !> A set whose elements keep a history (the general path with nvar > 0).
   pure logical function has_history(s)
      type(element_set_t), intent(in) :: s
      has_history = .false.
      if (s%kind /= MAT_SOLID .or. .not. s%general) return
      has_history = s%solid%nvar > 0 .and. allocated(s%hist)
   end function has_history

   !> History values of global element e (0 without a history).
   integer function values_of(st, sets, e) result(m)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: e
      m = 0
      if (e < 1 .or. e > st%nelem) return
      if (st%eloc(e) == 0) return
      if (.not. has_history(sets(st%eset(e)))) return
      m = size(sets(st%eset(e))%hist, 1)*size(sets(st%eset(e))%hist, 2)
   end function values_of

   !> Every rank sends the history of the elements of `elems` it owns, in the order of `elems`;
   !> the values of rank r arrive after those of ranks 0 .. r-1 and are put back in the same
   !> order (the order of `elems` among the elements rank r owns).
   subroutine gather_list(self, st, sets, elems)
      type(decomposition_t), intent(in) :: self
      type(state_t), intent(in) :: st
      type(element_set_t), intent(inout) :: sets(:)
      integer, intent(in) :: elems(:)
      integer :: counts(self%nrank), next(self%nrank), i, e, m, o, p, k, j
      real(wp), allocatable :: send(:), recv(:)
      counts = 0
      do i = 1, size(elems)
         m = values_of(st, sets, elems(i))
         if (m == 0) cycle
         o = self%elem_owner(elems(i)) + 1
         counts(o) = counts(o) + m
      end do
      if (sum(counts) == 0) return
      allocate (send(counts(self%rank + 1)), recv(sum(counts)))
      p = 0
      do i = 1, size(elems)
         e = elems(i)
         m = values_of(st, sets, e)
         if (m == 0) cycle
         if (self%elem_owner(e) /= self%rank) cycle
         k = st%eset(e)
         j = st%eloc(e)
         send(p + 1:p + m) = reshape(sets(k)%hist(:, :, j), [m])
         p = p + m
      end do
      call par_allgatherv(size(send), send, counts, recv)
      next(1) = 0
      do o = 2, self%nrank
         next(o) = next(o - 1) + counts(o - 1)
      end do
      do i = 1, size(elems)
         e = elems(i)
         m = values_of(st, sets, e)
         if (m == 0) cycle
         o = self%elem_owner(e) + 1
         k = st%eset(e)
         j = st%eloc(e)
         sets(k)%hist(:, :, j) = reshape(recv(next(o) + 1:next(o) + m), shape(sets(k)%hist(:, :, j)))
         next(o) = next(o) + m
      end do
   end subroutine gather_list

end module exic_explicit_history_gather
