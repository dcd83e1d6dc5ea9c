!> Small deterministic sorting kernels (edge keys, node lists, candidate lists).
!>
!> The permutation sorts are stable merge sorts, so equal keys keep their input order and
!> results never depend on the platform; `sort_short_int` sorts a short list in place without
!> allocating (insertion sort), for per-step lists of a few entries; `search_sorted` finds a key
!> in an increasing list by bisection.
module exic_base_sort
   use exic_base_kinds, only: i8
   implicit none
   private

   public :: sort_perm_i8, sort_perm_int, sort_short_int, sorted_unique, search_sorted

   !> Position of `key` in the increasing array `keys`, or minus the position it would be
   !> inserted at (-(size(keys) + 1) past the end) when it is absent.
   interface search_sorted
      module procedure search_sorted_int, search_sorted_i8
   end interface search_sorted

contains

   !> Stable sort of `key(1:n)`: on return key(perm(1)) <= key(perm(2)) <= ...
   pure subroutine sort_perm_i8(n, key, perm)
      integer, intent(in) :: n
      integer(i8), intent(in) :: key(n)
      integer, intent(out) :: perm(n)
      integer, allocatable :: work(:)
      integer :: width, lo, mid, hi, i, j, k

      allocate (work(n))
      do i = 1, n
         perm(i) = i
      end do
      width = 1
      do while (width < n)
         lo = 1
         do while (lo <= n)
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo; j = mid + 1; k = lo
            do while (i <= mid .and. j <= hi)
               if (key(perm(j)) < key(perm(i))) then
                  work(k) = perm(j); j = j + 1
               else
                  work(k) = perm(i); i = i + 1
               end if
               k = k + 1
            end do
            do while (i <= mid)
               work(k) = perm(i); i = i + 1; k = k + 1
            end do
            do while (j <= hi)
               work(k) = perm(j); j = j + 1; k = k + 1
            end do
            lo = lo + 2*width
         end do
         perm = work
         width = 2*width
      end do
   end subroutine sort_perm_i8

   !> Stable sort of default integers `key(1:n)`, returning the permutation as above.
   pure subroutine sort_perm_int(n, key, perm)
      integer, intent(in) :: n
      integer, intent(in) :: key(n)
      integer, intent(out) :: perm(n)
      call sort_perm_i8(n, int(key, i8), perm)
   end subroutine sort_perm_int

   !> Sort `a` ascending in place (insertion sort: for short lists).
   pure subroutine sort_short_int(a)
      integer, intent(inout) :: a(:)
      integer :: i, j, v
      do i = 2, size(a)
         v = a(i)
         j = i - 1
         do while (j >= 1)
            if (a(j) <= v) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = v
      end do
   end subroutine sort_short_int

   !> The distinct values of `a`, ascending (a bitmap over minval(a)..maxval(a): for node and
   !> region numbers).
   pure function sorted_unique(a) result(u)
      integer, intent(in) :: a(:)
      integer, allocatable :: u(:)
      integer :: i, lo, hi
      logical, allocatable :: seen(:)
      lo = minval(a)
      hi = maxval(a)
      allocate (seen(lo:hi), source=.false.)
      do i = 1, size(a)
         seen(a(i)) = .true.
      end do
      u = pack([(i, i=lo, hi)], seen)
   end function sorted_unique

   pure integer function search_sorted_int(keys, key) result(pos)
      integer, intent(in) :: keys(:), key
      integer :: lo, hi, mid
      lo = 1
      hi = size(keys)
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (keys(mid) == key) then
            pos = mid
            return
         else if (keys(mid) < key) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
      pos = -lo
   end function search_sorted_int

   pure integer function search_sorted_i8(keys, key) result(pos)
      integer(i8), intent(in) :: keys(:), key
      integer :: lo, hi, mid
      lo = 1
      hi = size(keys)
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (keys(mid) == key) then
            pos = mid
            return
         else if (keys(mid) < key) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
      pos = -lo
   end function search_sorted_i8

end module exic_base_sort
