!> The few C library (POSIX) operations exic needs, with status codes turned into errors.
!>
!> `rename` and nothing else is bound directly; the calls that need ABI-specific structures or
!> macros (stat(2) with S_ISREG and st_size, mkdir(2) and truncate(2) with errno, getrlimit(2)
!> with RLIMIT_AS) go through
!> the plain functions of `posix_c.c` next to this file. No shell is ever started.
module exic_base_posix
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_long_long, c_null_char, c_ptr, &
                                          c_size_t, c_associated, c_f_pointer
   use exic_base_kinds, only: i8
   use exic_base_error, only: error_t, make_error
   implicit none
   private

   public :: rename_file, c_string, file_kind, make_directories, address_space_limit, truncate_file, &
             file_size, exit_now, copy_file, remove_file

   !> file_kind results.
   integer, parameter, public :: FILE_MISSING = 0, FILE_REGULAR = 1, FILE_DIRECTORY = 2, &
                                 FILE_OTHER = 3

   interface
      !> size_t strlen(const char *s);
      pure function c_strlen(s) bind(C, name='strlen') result(n)
         import :: c_ptr, c_size_t
         type(c_ptr), value, intent(in) :: s
         integer(c_size_t) :: n
      end function c_strlen

      !> int rename(const char *oldpath, const char *newpath);
      function c_rename(oldpath, newpath) bind(C, name='rename') result(status)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: oldpath, newpath
         integer(c_int) :: status
      end function c_rename

      !> int exic_c_file_kind(const char *path);  (posix_c.c)
      function c_file_kind(path) bind(C, name='exic_c_file_kind') result(kind)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: path
         integer(c_int) :: kind
      end function c_file_kind

      !> int exic_c_mkdir(const char *path, char *msg, int msglen);  (posix_c.c)
      function c_mkdir(path, msg, msglen) bind(C, name='exic_c_mkdir') result(errnum)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: path
         character(kind=c_char), dimension(*), intent(inout) :: msg
         integer(c_int), value :: msglen
         integer(c_int) :: errnum
      end function c_mkdir

      !> int exic_c_address_space_limit(long long *bytes);  (posix_c.c)
      function c_address_space_limit(bytes) bind(C, name='exic_c_address_space_limit') &
         result(status)
         import :: c_int, c_long_long
         integer(c_long_long), intent(out) :: bytes
         integer(c_int) :: status
      end function c_address_space_limit

      !> int exic_c_truncate(const char *path, long long size);  (posix_c.c)
      function c_truncate(path, size) bind(C, name='exic_c_truncate') result(errnum)
         import :: c_char, c_int, c_long_long
         character(kind=c_char), dimension(*), intent(in) :: path
         integer(c_long_long), value :: size
         integer(c_int) :: errnum
      end function c_truncate

      !> long long exic_c_file_size(const char *path);  (posix_c.c)
      function c_file_size(path) bind(C, name='exic_c_file_size') result(size)
         import :: c_char, c_long_long
         character(kind=c_char), dimension(*), intent(in) :: path
         integer(c_long_long) :: size
      end function c_file_size

      !> int exic_c_copy_file(const char *from, const char *to, char *msg, int msglen);  (posix_c.c)
      function c_copy_file(from, to, msg, msglen) bind(C, name='exic_c_copy_file') result(errnum)
         import :: c_char, c_int
         character(kind=c_char), dimension(*), intent(in) :: from, to
         character(kind=c_char), dimension(*), intent(inout) :: msg
         integer(c_int), value :: msglen
         integer(c_int) :: errnum
      end function c_copy_file

      !> void exic_c_exit_now(int code);  (posix_c.c)
      subroutine c_exit_now(code) bind(C, name='exic_c_exit_now')
         import :: c_int
         integer(c_int), value :: code
      end subroutine c_exit_now
   end interface

contains

   !> End the process with exit code `code` at once: the Fortran units must be closed and the
   !> console flushed by the caller; no exit handler runs (HDF5's would retry a file whose
   !> close failed on a full disk and crash: doc/fields.md, "Write failures").
   subroutine exit_now(code)
      integer, intent(in) :: code
      call c_exit_now(int(code, c_int))
   end subroutine exit_now

   !> Cut the file `path` to `size` bytes (truncate(2)).
   subroutine truncate_file(path, size, err)
      character(len=*), intent(in) :: path
      integer(i8), intent(in) :: size
      type(error_t), allocatable, intent(out) :: err
      integer(c_int) :: e
      e = c_truncate(path//c_null_char, int(size, c_long_long))
      if (e /= 0_c_int) call make_error(err, "cannot cut '"//path//"' to the length the restart file "// &
                                        "recorded (truncate failed)")
   end subroutine truncate_file

   !> Size of the file `path` in bytes, -1 when it cannot be read (stat(2)).
   integer(i8) function file_size(path)
      character(len=*), intent(in) :: path
      file_size = int(c_file_size(path//c_null_char), i8)
   end function file_size

   !> Copy the bytes of the file `from` to `to` (created, or truncated when it exists); every
   !> read, write and close is checked.
   subroutine copy_file(from, to, err)
      character(len=*), intent(in) :: from, to
      type(error_t), allocatable, intent(out) :: err
      character(kind=c_char, len=512) :: msg
      integer :: nul
      msg = ''
      if (c_copy_file(from//c_null_char, to//c_null_char, msg, int(len(msg), c_int)) == 0_c_int) return
      nul = index(msg, c_null_char)
      if (nul == 0) nul = len_trim(msg) + 1
      call make_error(err, msg(1:nul - 1))
   end subroutine copy_file

   !> Remove the file `path` if it exists (a temporary file left by a failed copy); failures are ignored.
   subroutine remove_file(path)
      character(len=*), intent(in) :: path
      integer :: u, ios
      if (file_kind(path) == FILE_MISSING) return
      open (newunit=u, file=path, status='old', iostat=ios)
      if (ios == 0) close (u, status='delete', iostat=ios)
   end subroutine remove_file

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

   !> What `path` is (stat(2), links followed): FILE_REGULAR, FILE_DIRECTORY, FILE_OTHER
   !> (device, FIFO, socket) or FILE_MISSING (no such file, or no permission to look).
   integer function file_kind(path)
      character(len=*), intent(in) :: path
      file_kind = int(c_file_kind(path//c_null_char))
      if (file_kind < FILE_MISSING .or. file_kind > FILE_OTHER) file_kind = FILE_OTHER
   end function file_kind

   !> Create the directory `path` and any missing parents (as `mkdir -p`, with mkdir(2) and no
   !> shell). An existing directory is fine; an existing file of another kind is an error.
   subroutine make_directories(path, err)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: err
      integer :: k, n

      n = len(path)
      do while (n > 1)
         if (path(n:n) /= '/') exit
         n = n - 1
      end do
      if (n == 0) then
         call make_error(err, 'cannot create a directory with an empty name')
         return
      end if
      do k = 2, n
         if (path(k:k) == '/' .and. path(k - 1:k - 1) /= '/') then
            call make_one(path(1:k - 1), err)
            if (allocated(err)) return
         end if
      end do
      call make_one(path(1:n), err)
   end subroutine make_directories

   !> mkdir(2) of one directory whose parent exists; an existing directory is fine.
   subroutine make_one(dir, err)
      character(len=*), intent(in) :: dir
      type(error_t), allocatable, intent(out) :: err
      character(kind=c_char, len=256) :: msg
      integer(c_int) :: errnum
      integer :: kind, nul

      kind = file_kind(dir)
      if (kind == FILE_DIRECTORY) return
      if (kind /= FILE_MISSING) then
         call make_error(err, "cannot create directory '"//dir//"': a file of that name exists")
         return
      end if
      msg = ''
      errnum = c_mkdir(dir//c_null_char, msg, int(len(msg), c_int))
      if (errnum == 0_c_int) return
      if (file_kind(dir) == FILE_DIRECTORY) return     ! made meanwhile by another process
      nul = index(msg, c_null_char)
      if (nul == 0) nul = len_trim(msg) + 1
      call make_error(err, "cannot create directory '"//dir//"': "//msg(1:nul - 1))
   end subroutine make_one

   !> The soft address-space limit of this process (RLIMIT_AS, what `ulimit -v` sets) in bytes;
   !> `limited` is false when there is none or it cannot be read.
   subroutine address_space_limit(bytes, limited)
      integer(i8), intent(out) :: bytes
      logical, intent(out) :: limited
      integer(c_long_long) :: b
      bytes = -1_i8
      limited = .false.
      if (c_address_space_limit(b) /= 0_c_int) return
      if (b < 0_c_long_long) return
      bytes = int(b, i8)
      limited = .true.
   end subroutine address_space_limit

end module exic_base_posix
