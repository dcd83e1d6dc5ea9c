!> The few C library (POSIX) operations exic needs, with status codes turned into errors.
module exic_io_posix
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_null_char, c_ptr, c_size_t, &
                                          c_associated, c_f_pointer
   use exic_base_error, only: error_t, make_error
   implicit none
   private

   public :: rename_file, c_string

   interface
      !> int rename(const char *oldpath, const char *newpath);
      function c_rename(oldpath, newpath) bind(C, name='rename') result(status)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: oldpath, newpath
         integer(c_int) :: status
      end function c_rename

      !> size_t strlen(const char *s);
      pure function c_strlen(s) bind(C, name='strlen') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: s
         integer(c_size_t) :: n
      end function c_strlen
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

   !> A copy of the null-terminated C string at `p` ('' for a null pointer).
   function c_string(p) result(s)
      type(c_ptr), intent(in) :: p
      character(len=:), allocatable :: s
      character(kind=c_char), pointer :: chars(:)
      integer :: n, k
      n = 0
      if (c_associated(p)) n = int(c_strlen(p))
      allocate (character(len=n) :: s)
      if (n == 0) return
      call c_f_pointer(p, chars, [n])
      do k = 1, n
         s(k:k) = chars(k)
      end do
   end function c_string

end module exic_io_posix
