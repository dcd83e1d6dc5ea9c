!> The few C library (POSIX) file operations exic needs, with status codes turned into errors.
module exic_io_posix
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char
   use exic_base_error, only: error_t, make_error
   implicit none
   private

   public :: rename_file

   interface
      !> int rename(const char *oldpath, const char *newpath);
      function c_rename(oldpath, newpath) bind(C, name='rename') result(status)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: oldpath, newpath
         integer(c_int) :: status
      end function c_rename
   end interface

contains

   !> Rename `from` to `to`, replacing `to` atomically when both are on one file system.
   subroutine rename_file(from, to, err)
      character(len=*), intent(in) :: from, to
      type(error_t), allocatable, intent(out) :: err

      if (c_rename(from//c_null_char, to//c_null_char) /= 0_c_int) then
         call make_error(err, "cannot rename '"//from//"' to '"//to//"'")
      end if
   end subroutine rename_file

end module exic_io_posix
