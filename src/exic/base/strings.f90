!> Numbers as text for messages and reports.
module exic_base_strings
   use exic_base_kinds, only: wp, i8
   implicit none
   private

   public :: itoa, rtoa, rtoa_result, to_lower, SHORT_REAL

   !> rtoa's format for a number quoted back to the user as given (8 significant digits, no
   !> exponent where none is needed): rtoa(x, SHORT_REAL)
   character(len=*), parameter :: SHORT_REAL = '(g0.8)'

   !> An integer (default or 64-bit) as text, without blanks.
   interface itoa
      module procedure itoa_default, itoa_i8
   end interface itoa

contains

   pure function itoa_default(i) result(s)
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      character(len=16) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa_default

   pure function itoa_i8(i) result(s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa_i8

   !> A real as text, without blanks, in format `fmt` (default es14.7, and es15.7e3 when the
   !> exponent needs three digits: es14.7 would drop the letter E, `1.2345678-302`).
   pure function rtoa(x, fmt) result(s)
      real(wp), intent(in) :: x
      character(len=*), intent(in), optional :: fmt
      character(len=:), allocatable :: s
      character(len=40) :: buf
      if (present(fmt)) then
         write (buf, fmt) x
      else if (abs(x) < 1.0e-98_wp .and. x /= 0.0_wp .or. abs(x) >= 1.0e99_wp) then
         write (buf, '(es15.7e3)') x
      else
         write (buf, '(es14.7)') x
      end if
      s = trim(adjustl(buf))
   end function rtoa

   !> Lower-case copy of `s` (ASCII letters only).
   pure function to_lower(s) result(t)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: t
      integer :: k, c
      t = s
      do k = 1, len(s)
         c = iachar(s(k:k))
         if (c >= iachar('A') .and. c <= iachar('Z')) t(k:k) = achar(c + 32)
      end do
   end function to_lower

   !> A computed result as text for a report: rtoa(x), or `not finite` for NaN and infinities,
   !> which are never written as results (a run that failed on them says where they appeared).
   pure function rtoa_result(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      if (x - x == 0.0_wp) then
         s = rtoa(x)
      else
         s = 'not finite'
      end if
   end function rtoa_result

end module exic_base_strings
