!> Datasets held open while a file is written: `hdf5_held_t` opens a dataset of an open
!> `hdf5_file_t` once (`hold`) and writes raw data through that handle, a slab of a series
!> (`write_slab`) or a whole fixed dataset (`write_whole`), until `release`. An output time of the
!> field writer is then only H5Dwrite calls into storage allocated when the file was made: no
!> dataset is opened, extended or closed by name, so no metadata changes (doc/fields.md, "Kill
!> safety"). Every HDF5 status is checked; a failure becomes an `error_t` naming the dataset and
!> the file.
module exic_hdf5_held
   use, intrinsic :: iso_c_binding, only: c_ptr, c_loc
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_hdf5_types, only: DTYPE_REAL, DTYPE_INT, DTYPE_INT64, mem_type
   use exic_hdf5_file, only: hdf5_file_t
   use hdf5, only: hid_t, hsize_t, h5dopen_f, h5dclose_f, h5dwrite_f, h5dget_space_f, h5sclose_f, &
                   h5screate_simple_f, h5sselect_hyperslab_f, h5sget_simple_extent_ndims_f, &
                   h5sget_simple_extent_dims_f, H5S_SELECT_SET_F
   implicit none
   private

   public :: hdf5_held_t

   !> One dataset held open.
   type :: held_t
      integer(hid_t) :: did = -1
      character(len=:), allocatable :: name
   end type held_t

   !> The datasets held open on one file.
   type :: hdf5_held_t
      private
      type(held_t), allocatable :: held(:)
      integer :: n = 0
      character(len=:), allocatable :: path
   contains
      procedure :: hold => held_hold
      procedure :: release => held_release
      procedure, private :: slab_real0, slab_real1, slab_real2, slab_int1, slab_int64_0
      procedure, private :: whole_real1, whole_real2, whole_int1, whole_int0
      procedure, private :: slabs_real1, slabs_real3, slabs_int2, slabs_int64_1
      !> Write slab k (0-based, in the last dimension) of the held series `id`:
      !> `call h%write_slab(id, k, x, err)`; x has the series' leading shape. Nothing but raw data
      !> is written: the slab must lie inside the dataset's current extent.
      generic :: write_slab => slab_real0, slab_real1, slab_real2, slab_int1, slab_int64_0
      !> Write m consecutive slabs k .. k+m-1 of the held series `id` by one H5Dwrite:
      !> `call h%write_slabs(id, k, x, err)`; x has the series' leading shape and m as its last
      !> extent (a series of scalars: x(m)). The slabs must lie inside the current extent.
      generic :: write_slabs => slabs_real1, slabs_real3, slabs_int2, slabs_int64_1
      !> Overwrite the whole held dataset `id` (same shape): `call h%write_whole(id, x, err)`.
      generic :: write_whole => whole_real1, whole_real2, whole_int1, whole_int0
   end type hdf5_held_t

contains

   !> Open the dataset `name` of the open file `f` and keep it open until `release`; `id` names
   !> it to `write_slab` and `write_whole`.
   subroutine held_hold(self, f, name, id, err)
      class(hdf5_held_t), intent(inout) :: self
      type(hdf5_file_t), intent(in) :: f
      character(len=*), intent(in) :: name
      integer, intent(out) :: id
      type(error_t), allocatable, intent(out) :: err
      type(held_t), allocatable :: grown(:)
      integer(hid_t) :: did
      integer :: st
      id = 0
      if (f%handle() < 0) then
         call make_error(err, 'HDF5: cannot open dataset '//name//': no file is open')
         return
      end if
      self%path = f%name()
      call h5dopen_f(f%handle(), name, did, st)
      if (st < 0) then
         call fail(self, err, 'open dataset', name)
         return
      end if
      if (.not. allocated(self%held)) allocate (self%held(16))
      if (self%n == size(self%held)) then
         allocate (grown(2*size(self%held)))
         grown(1:self%n) = self%held(1:self%n)
         call move_alloc(grown, self%held)
      end if
      self%n = self%n + 1
      self%held(self%n)%did = did
      self%held(self%n)%name = name
      id = self%n
   end subroutine held_hold

   !> Close every held dataset (before the file is closed).
   subroutine held_release(self, err)
      class(hdf5_held_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer :: i, st, worst
      worst = 0
      do i = 1, self%n
         call h5dclose_f(self%held(i)%did, st)
         worst = min(worst, st)
         self%held(i)%did = -1
      end do
      if (worst < 0) call make_error(err, "HDF5: cannot close the datasets held open in '"//self%path//"'")
      self%n = 0
   end subroutine held_release

   subroutine slab_real0(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      real(wp), intent(in), target :: x
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: lead(0)
      call slab_raw(self, id, k, 1, DTYPE_REAL, lead, c_loc(x), err)
   end subroutine slab_real0

   subroutine slab_real1(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      call slab_raw(self, id, k, 1, DTYPE_REAL, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine slab_real1

   subroutine slab_real2(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      real(wp), intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      call slab_raw(self, id, k, 1, DTYPE_REAL, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine slab_real2

   subroutine slab_int1(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      integer, intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      call slab_raw(self, id, k, 1, DTYPE_INT, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine slab_int1

   subroutine slab_int64_0(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      integer(i8), intent(in), target :: x
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: lead(0)
      call slab_raw(self, id, k, 1, DTYPE_INT64, lead, c_loc(x), err)
   end subroutine slab_int64_0

   subroutine slabs_real1(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: lead(0)
      call slab_raw(self, id, k, size(x), DTYPE_REAL, lead, c_loc(x), err)
   end subroutine slabs_real1

   subroutine slabs_real3(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      real(wp), intent(in), target, contiguous :: x(:, :, :)
      type(error_t), allocatable, intent(out) :: err
      call slab_raw(self, id, k, size(x, 3), DTYPE_REAL, int(shape(x(:, :, 1)), hsize_t), c_loc(x), err)
   end subroutine slabs_real3

   subroutine slabs_int2(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      integer, intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      call slab_raw(self, id, k, size(x, 2), DTYPE_INT, int(shape(x(:, 1)), hsize_t), c_loc(x), err)
   end subroutine slabs_int2

   subroutine slabs_int64_1(self, id, k, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k
      integer(i8), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: lead(0)
      call slab_raw(self, id, k, size(x), DTYPE_INT64, lead, c_loc(x), err)
   end subroutine slabs_int64_1

   !> Write the data at `p` (Fortran shape (lead, m)) into slabs k .. k+m-1 (0-based) of the held
   !> series `id`, which must have that leading shape and more than k+m-1 slabs.
   subroutine slab_raw(self, id, k, m, dtype, lead, p, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, k, m, dtype
      integer(hsize_t), intent(in) :: lead(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: dims(size(lead) + 1), offset(size(lead) + 1), count(size(lead) + 1)
      integer(hid_t) :: fspace, mspace
      integer :: st, rank

      if (.not. check_held(self, id, err)) return
      rank = size(lead) + 1
      fspace = -1
      mspace = -1
      associate (h => self%held(id))
         steps: block
            call held_dims(h%did, rank, fspace, dims, st)
            if (st < 0) then
               call fail(self, err, 'get the dimensions of', h%name)
               exit steps
            end if
            if (any(dims(1:rank - 1) /= lead)) then
               call fail(self, err, 'write a slab of the wrong shape to', h%name)
               exit steps
            end if
            if (k < 0 .or. m < 1 .or. int(k, hsize_t) + int(m, hsize_t) > dims(rank)) then
               call fail(self, err, 'write slabs '//itoa(k)//' to '//itoa(k + m - 1)//' outside the '// &
                         itoa(int(dims(rank), i8))//' slabs of', h%name)
               exit steps
            end if
            offset = 0
            offset(rank) = int(k, hsize_t)
            count(1:rank - 1) = lead
            count(rank) = int(m, hsize_t)
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, offset, count, st)
            if (st >= 0) call h5screate_simple_f(rank, count, mspace, st)
            if (st < 0) then
               call fail(self, err, 'select slab '//itoa(k)//' of', h%name)
               exit steps
            end if
            if (product(count) > 0) then
               call h5dwrite_f(h%did, mem_type(dtype), p, st, mspace, fspace)
               if (st < 0) call fail(self, err, 'write slab '//itoa(k)//' of', h%name)
            end if
         end block steps
         call close_spaces(self, err, h%name, fspace, mspace)
      end associate
   end subroutine slab_raw

   subroutine whole_real1(self, id, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      call whole_raw(self, id, DTYPE_REAL, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine whole_real1

   subroutine whole_real2(self, id, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id
      real(wp), intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      call whole_raw(self, id, DTYPE_REAL, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine whole_real2

   subroutine whole_int1(self, id, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id
      integer, intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      call whole_raw(self, id, DTYPE_INT, int(shape(x), hsize_t), c_loc(x), err)
   end subroutine whole_int1

   !> One integer into the held dataset `id` of one element.
   subroutine whole_int0(self, id, x, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id
      integer, intent(in), target :: x
      type(error_t), allocatable, intent(out) :: err
      call whole_raw(self, id, DTYPE_INT, [1_hsize_t], c_loc(x), err)
   end subroutine whole_int0

   !> Overwrite the whole held dataset `id`, whose shape must be `dims`, with the data at `p`.
   subroutine whole_raw(self, id, dtype, dims, p, err)
      class(hdf5_held_t), intent(inout) :: self
      integer, intent(in) :: id, dtype
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: have(size(dims))
      integer(hid_t) :: fspace, none
      integer :: st

      if (.not. check_held(self, id, err)) return
      fspace = -1
      none = -1
      associate (h => self%held(id))
         call held_dims(h%did, size(dims), fspace, have, st)
         if (st < 0) then
            call fail(self, err, 'get the dimensions of', h%name)
         else if (any(have /= dims)) then
            call fail(self, err, 'overwrite with data of another shape', h%name)
         else if (product(dims) > 0) then
            call h5dwrite_f(h%did, mem_type(dtype), p, st)
            if (st < 0) call fail(self, err, 'overwrite dataset', h%name)
         end if
         call close_spaces(self, err, h%name, fspace, none)
      end associate
   end subroutine whole_raw

   !> The dataspace `space` of the open dataset `did` and its dimensions (Fortran order), which
   !> must be of rank `rank`; st < 0 on failure or another rank.
   subroutine held_dims(did, rank, space, dims, st)
      integer(hid_t), intent(in) :: did
      integer, intent(in) :: rank
      integer(hid_t), intent(out) :: space
      integer(hsize_t), intent(out) :: dims(rank)
      integer, intent(out) :: st
      integer(hsize_t) :: maxdims(rank)
      integer :: have
      call h5dget_space_f(did, space, st)
      if (st >= 0) call h5sget_simple_extent_ndims_f(space, have, st)
      if (st >= 0 .and. have /= rank) st = -1
      if (st >= 0) call h5sget_simple_extent_dims_f(space, dims, maxdims, st)
   end subroutine held_dims

   !> Close the dataspaces that are open (>= 0); a failing close sets `err` unless one is set.
   subroutine close_spaces(self, err, name, s1, s2)
      class(hdf5_held_t), intent(in) :: self
      type(error_t), allocatable, intent(inout) :: err
      character(len=*), intent(in) :: name
      integer(hid_t), intent(inout) :: s1, s2
      integer :: st, worst
      worst = 0
      if (s1 >= 0) call h5sclose_f(s1, st)
      if (s1 >= 0) worst = min(worst, st)
      if (s2 >= 0) call h5sclose_f(s2, st)
      if (s2 >= 0) worst = min(worst, st)
      s1 = -1
      s2 = -1
      if (worst < 0 .and. .not. allocated(err)) call fail(self, err, 'close the dataspaces of', name)
   end subroutine close_spaces

   !> True when `id` names a held dataset; otherwise set `err`.
   logical function check_held(self, id, err)
      class(hdf5_held_t), intent(in) :: self
      integer, intent(in) :: id
      type(error_t), allocatable, intent(inout) :: err
      check_held = id >= 1 .and. id <= self%n
      if (.not. check_held) call make_error(err, 'HDF5: no held dataset '//itoa(id)//' (none open, or '// &
                                            'released)')
   end function check_held

   !> Set `err` to "HDF5: cannot <what> '<obj>' in file '<path>'".
   subroutine fail(self, err, what, obj)
      class(hdf5_held_t), intent(in) :: self
      type(error_t), allocatable, intent(inout) :: err
      character(len=*), intent(in) :: what, obj
      call make_error(err, 'HDF5: cannot '//what//" '"//obj//"' in file '"//self%path//"'")
   end subroutine fail

end module exic_hdf5_held
