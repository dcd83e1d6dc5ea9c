!> A minimal test harness: every check counts as one pass or one failure.
module testing
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: suite_t, check, check_close, section

   !> Running totals of one test run.
   type :: suite_t
      integer :: passed = 0
      integer :: failed = 0
      character(len=:), allocatable :: current
   end type suite_t

contains

   !> Start a named group of checks (printed as a heading).
   subroutine section(s, name)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      s%current = name
      write (output_unit, '(a)') '== '//name
      flush (output_unit)
   end subroutine section

   !> Record `ok` as one check called `name`; print failures with `detail`.
   subroutine check(s, ok, name, detail)
      type(suite_t), intent(inout) :: s
      logical, intent(in) :: ok
      character(len=*), intent(in) :: name
      character(len=*), intent(in), optional :: detail
      if (ok) then
         s%passed = s%passed + 1
         write (output_unit, '(a)') '   ok    '//name
      else
         s%failed = s%failed + 1
         if (present(detail)) then
            write (output_unit, '(a)') '   FAIL  '//name//': '//detail
         else
            write (output_unit, '(a)') '   FAIL  '//name
         end if
      end if
      flush (output_unit)
   end subroutine check

   !> Check |actual - expected| <= tol and report both values.
   subroutine check_close(s, actual, expected, tol, name)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: actual, expected, tol
      character(len=*), intent(in) :: name
      character(len=120) :: buf
      write (buf, '(a,es12.5,a,es12.5,a,es9.2,a,es9.2)') 'got ', actual, ' want ', expected, &
         ' |diff| ', abs(actual - expected), ' tol ', tol
      call check(s, abs(actual - expected) <= tol .and. actual == actual, name//'  ('//trim(buf)//')')
   end subroutine check_close

end module testing
