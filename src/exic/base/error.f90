!> The error type of set-up, input and I/O code.
!>
!> A procedure that can fail takes `type(error_t), allocatable, intent(out) :: err`;
!> it is left unallocated on success. Only `app/` and the legacy API turn an error
!> into an exit code or an `ierr`.
module exic_base_error
   implicit none
   private

   public :: error_t, make_error, fatal_error

   !> An error with a message that names where it happened (file:line, node, element, time).
   type :: error_t
      character(len=:), allocatable :: message
   end type error_t

contains

   !> Allocate `err` with `message`, prefixed by `file:line: ` when those are given.
   subroutine make_error(err, message, file, line)
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in) :: message
      character(len=*), intent(in), optional :: file
      integer, intent(in), optional :: line
      character(len=16) :: buf

      allocate (err)
      if (present(file)) then
         if (present(line)) then
            write (buf, '(i0)') line
            err%message = file//':'//trim(buf)//': '//message
         else
            err%message = file//': '//message
         end if
      else
         err%message = message
      end if
   end subroutine make_error

   !> Print `err` on standard error and stop with exit code `code` (default 1). For `app/` only.
   subroutine fatal_error(err, code)
      use, intrinsic :: iso_fortran_env, only: error_unit
      type(error_t), intent(in) :: err
      integer, intent(in), optional :: code
      write (error_unit, '(a)') 'exic: error: '//err%message
      flush (error_unit)
      if (present(code)) then
         stop code, quiet=.true.
      else
         stop 1, quiet=.true.
      end if
   end subroutine fatal_error

end module exic_base_error
