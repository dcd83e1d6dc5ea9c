!> Arrays that grow and never shrink: `call grow(a, n)` makes sure a holds at least n entries
!> (n columns for a rank-2 array), keeping its contents and zeroing the new entries (.false. for
!> logicals), doubling when it grows so that repeated small growth costs amortized O(1). Used by the per-step paths (contact search,
!> corrector, sparse factorization), which allocate nothing once their arrays are sized.
!> Arrays of a derived type grow by a specific of the same generic name `grow`, kept beside the
!> type's users (src/exic/input/deck/grow.f90) or in the module that owns the type, each sized
!> by grow_size.
module exic_base_grow
   use exic_base_kinds, only: wp, i8
   implicit none
   private

   public :: grow, grow_size

   !> Grow an allocatable array to at least n entries (or n columns), keeping its contents.
   interface grow
      module procedure grow_int, grow_i8, grow_real, grow_logical, grow_real2, grow_int2, grow_char
   end interface grow

contains

   !> New size when an array of `have` entries must hold `need`: at least double, or exactly
   !> `need` with `exact` (an array whose size is its count).
   pure integer function grow_size(have, need, exact)
      integer, intent(in) :: have, need
      logical, intent(in), optional :: exact
      grow_size = max(need, 2*have, 1)
      if (present(exact)) then
         if (exact) grow_size = need
      end if
   end function grow_size

   pure subroutine grow_int(a, n)
      integer, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer, allocatable :: tmp(:)
      if (.not. allocated(a)) then
         allocate (a(grow_size(0, n)), source=0)
      else if (size(a) < n) then
         allocate (tmp(grow_size(size(a), n)), source=0)
         tmp(1:size(a)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_int

   pure subroutine grow_i8(a, n)
      integer(i8), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer(i8), allocatable :: tmp(:)
      if (.not. allocated(a)) then
         allocate (a(grow_size(0, n)), source=0_i8)
      else if (size(a) < n) then
         allocate (tmp(grow_size(size(a), n)), source=0_i8)
         tmp(1:size(a)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_i8

   pure subroutine grow_real(a, n)
      real(wp), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      real(wp), allocatable :: tmp(:)
      if (.not. allocated(a)) then
         allocate (a(grow_size(0, n)), source=0.0_wp)
      else if (size(a) < n) then
         allocate (tmp(grow_size(size(a), n)), source=0.0_wp)
         tmp(1:size(a)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_real

   pure subroutine grow_logical(a, n)
      logical, allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, allocatable :: tmp(:)
      if (.not. allocated(a)) then
         allocate (a(grow_size(0, n)), source=.false.)
      else if (size(a) < n) then
         allocate (tmp(grow_size(size(a), n)), source=.false.)
         tmp(1:size(a)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_logical

   !> Rank 2: grows the second (entity) dimension; the first is `rows` when allocating anew.
   pure subroutine grow_real2(a, n, rows)
      real(wp), allocatable, intent(inout) :: a(:, :)
      integer, intent(in) :: n, rows
      real(wp), allocatable :: tmp(:, :)
      if (.not. allocated(a)) then
         allocate (a(rows, grow_size(0, n)), source=0.0_wp)
      else if (size(a, 2) < n) then
         allocate (tmp(size(a, 1), grow_size(size(a, 2), n)), source=0.0_wp)
         tmp(:, 1:size(a, 2)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_real2

   !> Rank 2 integer: as grow_real2.
   pure subroutine grow_int2(a, n, rows)
      integer, allocatable, intent(inout) :: a(:, :)
      integer, intent(in) :: n, rows
      integer, allocatable :: tmp(:, :)
      if (.not. allocated(a)) then
         allocate (a(rows, grow_size(0, n)), source=0)
      else if (size(a, 2) < n) then
         allocate (tmp(size(a, 1), grow_size(size(a, 2), n)), source=0)
         tmp(:, 1:size(a, 2)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_int2

   !> Character strings (of the actual's length); new entries are blank.
   pure subroutine grow_char(a, n)
      character(len=*), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      character(len=len(a)), allocatable :: tmp(:)
      if (.not. allocated(a)) then
         allocate (a(grow_size(0, n)), source=repeat(' ', len(a)))
      else if (size(a) < n) then
         allocate (tmp(grow_size(size(a), n)), source=repeat(' ', len(a)))
         tmp(1:size(a)) = a
         call move_alloc(tmp, a)
      end if
   end subroutine grow_char

end module exic_base_grow
