!> Whether standard output is a terminal (POSIX isatty), for the progress line.
module exic_base_terminal
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private

   public :: stdout_is_terminal

   interface
      !> int isatty(int fd): 1 for a terminal, 0 otherwise (errno ENOTTY or EBADF).
      function c_isatty(fd) bind(C, name='isatty') result(r)
         import :: c_int
         integer(c_int), value, intent(in) :: fd
         integer(c_int) :: r
      end function c_isatty
   end interface

contains

   !> True when file descriptor 1 (standard output) is a terminal. isatty's only failure
   !> (a descriptor that is not a terminal, or not open) means "no terminal" here.
   logical function stdout_is_terminal()
      stdout_is_terminal = c_isatty(1_c_int) == 1_c_int
   end function stdout_is_terminal

end module exic_base_terminal
