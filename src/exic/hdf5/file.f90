!> A small wrapper over the HDF5 Fortran API.
!>
!> `hdf5_file_t` owns one file handle. It creates groups, fixed datasets (written once, or
!> rewritten whole), extendible "series" (chunked, unlimited last dimension, grown one slab at a
!> time), virtual "series views" that show a block of every slab of a series, and attributes.
!> Every HDF5 status is checked; a failure becomes an `error_t` naming the operation, the object
!> and the file, and every handle opened on the way is closed again.
!>
!> Shapes are given in Fortran order. HDF5 stores them reversed, so a Fortran array x(2, n)
!> reads as shape (n, 2) in C, Python (h5py) and h5dump.
module exic_hdf5_file
   use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_loc, c_char
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_hdf5_types, only: DTYPE_REAL, DTYPE_INT, DTYPE_INT64, file_type, mem_type, elem_bytes, &
                                 set_zero_fill, set_unwritten_fill
   use hdf5, only: hid_t, hsize_t, h5open_f, h5eset_auto_f, h5fcreate_f, h5fopen_f, h5fclose_f, &
                   h5fflush_f, h5gcreate_f, h5gclose_f, h5screate_simple_f, h5screate_f, &
                   h5sclose_f, h5sselect_hyperslab_f, h5sget_simple_extent_ndims_f, &
                   h5sget_simple_extent_dims_f, h5dcreate_f, h5dopen_f, h5dclose_f, h5dwrite_f, &
                   h5dget_space_f, h5dset_extent_f, h5dread_f, h5lexists_f, h5pcreate_f, h5pclose_f, h5pset_chunk_f, &
                   h5pset_fill_value_f, h5pset_virtual_f, h5oopen_f, h5oclose_f, h5aexists_f, &
                   h5adelete_f, h5acreate_f, h5awrite_f, h5aclose_f, h5tcopy_f, h5tclose_f, &
                   h5tset_size_f, h5tset_strpad_f, h5kind_to_type, &
                   H5_REAL_KIND, H5_INTEGER_KIND, H5F_ACC_TRUNC_F, H5F_ACC_RDWR_F, &
                   H5F_ACC_RDONLY_F, H5F_SCOPE_GLOBAL_F, H5S_UNLIMITED_F, H5S_SCALAR_F, &
                   H5S_SELECT_SET_F, H5P_DATASET_CREATE_F, H5T_IEEE_F64LE, H5T_STD_I32LE, &
                   H5T_STD_I64LE, H5T_FORTRAN_S1, H5T_STR_NULLPAD_F, h5pset_alloc_time_f, &
                   h5pset_fill_time_f, h5pset_obj_track_times_f, h5pset_cache_f, &
                   h5pset_sieve_buf_size_f, h5ldelete_f, H5D_ALLOC_TIME_EARLY_F, &
                   H5D_FILL_TIME_NEVER_F, H5P_FILE_ACCESS_F, SIZE_T
   implicit none
   private

   public :: hdf5_file_t
   public :: DTYPE_REAL, DTYPE_INT, DTYPE_INT64   ! (of exic_hdf5_types)


   !> Chunks of a series (doc/decisions.md, "HDF5 chunks"). Made with a capacity (the field
   !> series: written in place without a chunk cache, one write per chunk a batch touches): the
   !> capacity in as few equal chunks as fit under CHUNK_BYTES_ROOM (larger ones make a cut of
   !> the series rewrite up to a whole chunk). Made without (extended and written a slab at a
   !> time through the chunk cache, which writes a changed chunk whole): about CHUNK_BYTES.
   integer, parameter :: CHUNK_BYTES = 4096, CHUNK_SLABS_MAX = 64
   integer(i8), parameter :: CHUNK_BYTES_ROOM = 256_i8*1024_i8

   !> One open HDF5 file.
   type :: hdf5_file_t
      private
      integer(hid_t) :: fid = -1
      character(len=:), allocatable :: path
   contains
      procedure :: handle => file_handle
      procedure :: resize_series => file_resize_series
      procedure :: delete => file_delete
      procedure :: create => file_create
      procedure :: open => file_open
      procedure :: is_open => file_is_open
      procedure :: name => file_name
      procedure :: create_group => file_create_group
      procedure :: create_series => file_create_series
      procedure :: series_length => file_series_length
      procedure :: create_series_view => file_create_series_view
      procedure :: exists => file_exists
      procedure :: flush => file_flush
      procedure :: close => file_close
      procedure, private :: write_real1, write_real2, write_int1, write_int2
      procedure, private :: rewrite_real1, rewrite_real2, rewrite_int1
      procedure, private :: append_real0, append_real1, append_real2, append_int1, append_int64_0
      procedure, private :: read_real, read_int, read_int64
      !> Read the whole dataset `name` into `x` (real(wp), integer or integer(i8), rank 1, as many
      !> elements as the dataset holds, in Fortran order): `call f%read(name, x, err)`.
      generic :: read => read_real, read_int, read_int64
      procedure, private :: attr_real0, attr_real1, attr_int0, attr_int1, attr_int64_0, attr_string
      !> Write a fixed dataset: `call f%write(name, x, err)`, x real(wp) or integer, rank 1 or 2.
      generic :: write => write_real1, write_real2, write_int1, write_int2
      !> Overwrite the values of an existing fixed dataset of the same shape:
      !> `call f%rewrite(name, x, err)`, x real(wp) rank 1 or 2, or integer rank 1.
      generic :: rewrite => rewrite_real1, rewrite_real2, rewrite_int1
      !> Append one slab to a series: `call f%append(name, x, err)`; x has the series' leading shape.
      generic :: append => append_real0, append_real1, append_real2, append_int1, append_int64_0
      !> Write (or replace) an attribute of the object `obj`: `call f%write_attr(obj, name, v, err)`.
      generic :: write_attr => attr_real0, attr_real1, attr_int0, attr_int1, attr_int64_0, attr_string
   end type hdf5_file_t

contains

   ! ---------------------------------------------------------------------------- files

   !> Initialise the library (idempotent) and silence its own error printing: exic reports errors.
   subroutine library_init(err)
      type(error_t), allocatable, intent(out) :: err
      integer :: st
      call h5open_f(st)
      if (st < 0) then
         call make_error(err, 'cannot initialise the HDF5 library')
         return
      end if
      call h5eset_auto_f(0, st)
      if (st < 0) call make_error(err, 'cannot switch off HDF5 error printing')
   end subroutine library_init

   !> Create (or truncate) the file `path` for writing.
   subroutine file_create(self, path, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: err
      integer :: st

      if (self%fid >= 0) then
         call make_error(err, "HDF5: cannot create '"//path//"': this handle already has '"// &
                         self%path//"' open")
         return
      end if
      call library_init(err)
      if (allocated(err)) return
      call h5fcreate_f(path, H5F_ACC_TRUNC_F, self%fid, st)
      if (st < 0) then
         self%fid = -1
         call make_error(err, "HDF5: cannot create file '"//path// &
                         "' (missing directory, no permission, or open in another program)")
         return
      end if
      self%path = path
   end subroutine file_create

   !> Open the existing file `path`, for writing when `writable`. `write_through`: no chunk
   !> cache and no sieve buffer, so that every H5Dwrite is written to the file at once, in the
   !> order of the calls, and a flush has no raw data left to write (doc/fields.md, "Kill safety").
   subroutine file_open(self, path, writable, err, write_through)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: path
      logical, intent(in) :: writable
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: write_through
      integer(hid_t) :: fapl
      integer :: st
      logical :: direct

      if (self%fid >= 0) then
         call make_error(err, "HDF5: cannot open '"//path//"': this handle already has '"// &
                         self%path//"' open")
         return
      end if
      call library_init(err)
      if (allocated(err)) return
      direct = .false.
      if (present(write_through)) direct = write_through
      fapl = -1
      st = 0
      if (direct) then
         call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, st)
         ! chunk cache of 0 bytes (chunks are written directly), no sieve buffer
         if (st >= 0) call h5pset_cache_f(fapl, 0, 1_SIZE_T, 0_SIZE_T, 1.0, st)
         if (st >= 0) call h5pset_sieve_buf_size_f(fapl, 0_SIZE_T, st)
         if (st < 0) then
            call make_error(err, "HDF5: cannot set the write-through access of file '"//path//"'")
            if (fapl >= 0) call h5pclose_f(fapl, st)
            return
         end if
      end if
      if (writable .and. direct) then
         call h5fopen_f(path, H5F_ACC_RDWR_F, self%fid, st, access_prp=fapl)
      else if (writable) then
         call h5fopen_f(path, H5F_ACC_RDWR_F, self%fid, st)
      else
         call h5fopen_f(path, H5F_ACC_RDONLY_F, self%fid, st)
      end if
      if (fapl >= 0) then
         block
            integer :: st2
            call h5pclose_f(fapl, st2)
         end block
      end if
      if (st < 0) then
         self%fid = -1
         call make_error(err, "HDF5: cannot open file '"//path//"'")
         return
      end if
      self%path = path
   end subroutine file_open

   !> True while a file is open.
   pure logical function file_is_open(self)
      class(hdf5_file_t), intent(in) :: self
      file_is_open = self%fid >= 0
   end function file_is_open

   !> The HDF5 identifier of the open file (-1 when closed), for exic_hdf5_held.
   pure integer(hid_t) function file_handle(self)
      class(hdf5_file_t), intent(in) :: self
      file_handle = self%fid
   end function file_handle

   !> The path of the open file ('' when closed).
   function file_name(self) result(path)
      class(hdf5_file_t), intent(in) :: self
      character(len=:), allocatable :: path
      if (allocated(self%path) .and. self%fid >= 0) then
         path = self%path
      else
         path = ''
      end if
   end function file_name

   !> Write everything cached to disk (data and metadata), so that the file is complete and
   !> readable as it stands even if the process dies before `close`.
   subroutine file_flush(self, err)
      class(hdf5_file_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer :: st
      if (.not. check_open(self, 'flush', err)) return
      call h5fflush_f(self%fid, H5F_SCOPE_GLOBAL_F, st)
      if (st < 0) call make_error(err, "HDF5: cannot flush file '"//self%path//"'")
   end subroutine file_flush

   !> Close the file (nothing to do when none is open). Datasets held open on it
   !> (exic_hdf5_held) must be released first: HDF5 keeps a file open while one of its
   !> objects is.
   subroutine file_close(self, err)
      class(hdf5_file_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer :: st
      if (self%fid < 0) return
      call h5fclose_f(self%fid, st)
      self%fid = -1
      if (st < 0) call make_error(err, "HDF5: cannot close file '"//self%path//"'")
   end subroutine file_close

   !> Create the group `name` (a full path such as '/mesh'; its parent must exist).
   subroutine file_create_group(self, name, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      type(error_t), allocatable, intent(out) :: err
      integer(hid_t) :: gid
      integer :: st
      if (.not. check_open(self, 'create group '//name, err)) return
      call h5gcreate_f(self%fid, name, gid, st)
      if (st < 0) then
         call fail(self, err, 'create group', name)
         return
      end if
      call h5gclose_f(gid, st)
      if (st < 0) call fail(self, err, 'close group', name)
   end subroutine file_create_group

   ! ---------------------------------------------------------------------------- fixed datasets

   !> Write the real(wp) vector `x` as the new dataset `name`.
   subroutine write_real1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine write_real1

   !> Write the real(wp) matrix `x` as the new dataset `name` (HDF5 shape reversed).
   subroutine write_real2(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine write_real2

   !> Write the integer vector `x` as the new dataset `name`.
   subroutine write_int1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end subroutine write_int1

   !> Write the integer matrix `x` as the new dataset `name` (HDF5 shape reversed).
   subroutine write_int2(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end subroutine write_int2

   !> Create the fixed dataset `name` of shape `dims` and write the data at `p` (none when empty).
   subroutine write_raw(self, name, dtype, dims, p, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: dtype
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hid_t) :: space, did
      integer :: st

      if (.not. check_open(self, 'write '//name, err)) return
      space = -1
      did = -1
      steps: block
         call h5screate_simple_f(size(dims), dims, space, st)
         if (st < 0) then
            call fail(self, err, 'create the dataspace of', name)
            exit steps
         end if
         call h5dcreate_f(self%fid, name, file_type(dtype), space, did, st)
         if (st < 0) then
            call fail(self, err, 'create dataset', name)
            exit steps
         end if
         if (product(dims) > 0) then
            call h5dwrite_f(did, mem_type(dtype), p, st)
            if (st < 0) then
               call fail(self, err, 'write dataset', name)
               exit steps
            end if
         end if
      end block steps
      call close_handles(err, self, name, dset=did, space=space)
   end subroutine write_raw

   !> Overwrite the real(wp) vector dataset `name` with `x` (same shape).
   subroutine rewrite_real1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine rewrite_real1

   !> Overwrite the real(wp) matrix dataset `name` with `x` (same shape).
   subroutine rewrite_real2(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine rewrite_real2

   !> Overwrite the integer vector dataset `name` with `x` (same shape).
   subroutine rewrite_int1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end subroutine rewrite_int1

   !> Write the data at `p` over the whole existing dataset `name`, whose shape must be `dims`.
   subroutine rewrite_raw(self, name, dtype, dims, p, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: dtype
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: have(:)
      integer(hid_t) :: did
      integer :: st

      call series_dims(self, name, did, have, err)
      if (allocated(err)) return
      steps: block
         if (size(have) /= size(dims)) then
            call fail(self, err, 'rewrite with data of another rank', name)
            exit steps
         end if
         if (any(have /= dims)) then
            call fail(self, err, 'rewrite with data of another shape', name)
            exit steps
         end if
         if (product(dims) > 0) then
            call h5dwrite_f(did, mem_type(dtype), p, st)
            if (st < 0) call fail(self, err, 'rewrite dataset', name)
         end if
      end block steps
      call close_handles(err, self, name, dset=did)
   end subroutine rewrite_raw

   ! ---------------------------------------------------------------------------- series

   !> Create the extendible dataset `name` of Fortran shape (lead..., 0), unlimited in its last
   !> dimension, in chunks of whole slabs (no compression). With `capacity`, the dataset has
   !> `capacity` slabs at once, its chunks allocated but not written (fill time "never": an
   !> unwritten slab holds no output, doc/fields.md), and no object times: writing slabs into it
   !> later changes no metadata.
   subroutine file_create_series(self, name, dtype, lead, err, capacity)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: dtype
      integer, intent(in) :: lead(:)   !< leading (fixed) dimensions, may be empty
      type(error_t), allocatable, intent(out) :: err
      integer, intent(in), optional :: capacity
      integer(hsize_t) :: dims(size(lead) + 1), maxdims(size(lead) + 1), chunk(size(lead) + 1)
      integer(hid_t) :: space, dcpl, did
      integer :: st, rank
      integer(i8) :: slab_bytes, nchunk

      if (.not. check_open(self, 'create series '//name, err)) return
      rank = size(lead) + 1
      dims(1:rank - 1) = int(lead, hsize_t)
      dims(rank) = 0
      if (present(capacity)) dims(rank) = int(max(capacity, 0), hsize_t)
      maxdims = dims
      maxdims(rank) = H5S_UNLIMITED_F
      chunk(1:rank - 1) = int(max(lead, 1), hsize_t)
      slab_bytes = product(int(max(lead, 1), i8))*elem_bytes(dtype)
      chunk(rank) = int(max(1_i8, min(int(CHUNK_SLABS_MAX, i8), CHUNK_BYTES/slab_bytes)), hsize_t)
      if (present(capacity) .and. dims(rank) > 0) then   ! nchunk equal chunks (the last may be short)
         nchunk = (int(dims(rank), i8) - 1)/max(1_i8, CHUNK_BYTES_ROOM/slab_bytes) + 1
         chunk(rank) = int((int(dims(rank), i8) - 1)/nchunk + 1, hsize_t)
      end if
      space = -1
      dcpl = -1
      did = -1
      steps: block
         call h5screate_simple_f(rank, dims, space, st, maxdims)
         if (st < 0) then
            call fail(self, err, 'create the dataspace of series', name)
            exit steps
         end if
         call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, st)
         if (st >= 0) call h5pset_chunk_f(dcpl, rank, chunk, st)
         if (st >= 0 .and. present(capacity)) then
            call h5pset_alloc_time_f(dcpl, H5D_ALLOC_TIME_EARLY_F, st)
            if (st >= 0) call h5pset_fill_time_f(dcpl, H5D_FILL_TIME_NEVER_F, st)
            if (st >= 0) call set_unwritten_fill(dcpl, dtype, st)
            if (st >= 0) call h5pset_obj_track_times_f(dcpl, .false., st)
         end if
         if (st < 0) then
            call fail(self, err, 'set the chunking of series', name)
            exit steps
         end if
         call h5dcreate_f(self%fid, name, file_type(dtype), space, did, st, dcpl_id=dcpl)
         if (st < 0) call fail(self, err, 'create series', name)
      end block steps
      call close_handles(err, self, name, dset=did, space=space, plist=dcpl)
   end subroutine file_create_series

   !> Number of slabs in the series `name` (its last dimension).
   subroutine file_series_length(self, name, n, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(out) :: n
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: dims(:)
      integer(hid_t) :: did
      n = 0
      call series_dims(self, name, did, dims, err)
      if (allocated(err)) return
      n = int(dims(size(dims)))
      call close_handles(err, self, name, dset=did)
   end subroutine file_series_length

   !> Open the dataset (or series) `name` and return its handle and current dimensions (Fortran
   !> order).
   subroutine series_dims(self, name, did, dims, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer(hid_t), intent(out) :: did
      integer(hsize_t), allocatable, intent(out) :: dims(:)
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: maxdims(:)
      integer(hid_t) :: space
      integer :: st, rank

      did = -1
      space = -1
      if (.not. check_open(self, 'open series '//name, err)) return
      steps: block
         call h5dopen_f(self%fid, name, did, st)
         if (st < 0) then
            call fail(self, err, 'open dataset', name)
            exit steps
         end if
         call h5dget_space_f(did, space, st)
         if (st >= 0) call h5sget_simple_extent_ndims_f(space, rank, st)
         if (st < 0) then
            call fail(self, err, 'get the dataspace of', name)
            exit steps
         end if
         allocate (dims(rank), maxdims(rank))
         call h5sget_simple_extent_dims_f(space, dims, maxdims, st)
         if (st < 0) call fail(self, err, 'get the dimensions of', name)
      end block steps
      call close_handles(err, self, name, space=space)
      if (allocated(err)) call close_handles(err, self, name, dset=did)
   end subroutine series_dims

   !> Append the scalar `x` to the real series `name` of shape (n).
   subroutine append_real0(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target :: x
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: slab(0)
      call append_raw(self, name, DTYPE_REAL, slab, c_loc(x), err)
   end subroutine append_real0

   !> Append the vector `x` to the real series `name` of shape (size(x), n).
   subroutine append_real1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine append_real1

   !> Append the matrix `x` to the real series `name` of shape (size(x,1), size(x,2), n).
   subroutine append_real2(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(in), target, contiguous :: x(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end subroutine append_real2

   !> Append the integer vector `x` to the integer series `name` of shape (size(x), n).
   subroutine append_int1(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end subroutine append_int1

   !> Append the integer(i8) scalar `x` to the 64-bit integer series `name` of shape (n).
   subroutine append_int64_0(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer(i8), intent(in), target :: x
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: slab(0)
      call append_raw(self, name, DTYPE_INT64, slab, c_loc(x), err)
   end subroutine append_int64_0

   !> Grow the series `name` by one slab of Fortran shape `slab` and write the data at `p` into it.
   subroutine append_raw(self, name, dtype, slab, p, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: dtype
      integer(hsize_t), intent(in) :: slab(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: dims(:), offset(:), count(:)
      integer(hid_t) :: did, fspace, mspace
      integer :: st, rank

      call series_dims(self, name, did, dims, err)
      if (allocated(err)) return
      fspace = -1
      mspace = -1
      rank = size(dims)
      steps: block
         if (rank /= size(slab) + 1) then
            call fail(self, err, 'append a slab of the wrong rank to', name)
            exit steps
         end if
         if (any(dims(1:rank - 1) /= slab)) then
            call fail(self, err, 'append a slab of the wrong shape to', name)
            exit steps
         end if
         allocate (offset(rank), count(rank))
         offset = 0
         offset(rank) = dims(rank)
         count(1:rank - 1) = slab
         count(rank) = 1
         dims(rank) = dims(rank) + 1
         call h5dset_extent_f(did, dims, st)
         if (st < 0) then
            call fail(self, err, 'extend', name)
            exit steps
         end if
         call h5dget_space_f(did, fspace, st)
         if (st >= 0) call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, offset, count, st)
         if (st >= 0) call h5screate_simple_f(rank, count, mspace, st)
         if (st < 0) then
            call fail(self, err, 'select the new slab of', name)
            exit steps
         end if
         if (product(count) > 0) then
            call h5dwrite_f(did, mem_type(dtype), p, st, mspace, fspace)
            if (st < 0) call fail(self, err, 'write the new slab of', name)
         end if
      end block steps
      call close_handles(err, self, name, dset=did, space=fspace, space2=mspace)
   end subroutine append_raw

   !> True when the link `name` (one level below an existing group, or at the root) exists.
   logical function file_exists(self, name) result(yes)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer :: st
      yes = .false.
      if (self%fid < 0) return
      call h5lexists_f(self%fid, name, yes, st)
      if (st < 0) yes = .false.
   end function file_exists

   !> Set the number of slabs of the series `name` to `n` (fewer: the slabs beyond are dropped;
   !> more: new slabs, allocated and filled at once when the series was made with a capacity).
   subroutine file_resize_series(self, name, n, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: n
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: dims(:)
      integer(hid_t) :: did
      integer :: st
      call series_dims(self, name, did, dims, err)
      if (allocated(err)) return
      if (dims(size(dims)) /= int(n, hsize_t)) then
         dims(size(dims)) = int(max(n, 0), hsize_t)
         call h5dset_extent_f(did, dims, st)
         if (st < 0) call fail(self, err, 'resize to '//itoa(n)//' slabs', name)
      end if
      call close_handles(err, self, name, dset=did)
   end subroutine file_resize_series

   !> Remove the link `name` (a dataset or group).
   subroutine file_delete(self, name, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      type(error_t), allocatable, intent(out) :: err
      integer :: st
      if (.not. check_open(self, 'delete '//name, err)) return
      call h5ldelete_f(self%fid, name, st)
      if (st < 0) call fail(self, err, 'delete', name)
   end subroutine file_delete


   !> Read the real dataset `name` whole into x (size(x) elements exactly).
   subroutine read_real(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      real(wp), intent(inout), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_REAL, int(size(x), i8), p, err)
   end subroutine read_real

   !> Read the integer dataset `name` whole into x (size(x) elements exactly).
   subroutine read_int(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(inout), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_INT, int(size(x), i8), p, err)
   end subroutine read_int

   !> Read the 64-bit integer dataset `name` whole into x (size(x) elements exactly).
   subroutine read_int64(self, name, x, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer(i8), intent(inout), target, contiguous :: x(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_INT64, int(size(x), i8), p, err)
   end subroutine read_int64

   !> Read the whole dataset `name`, which must hold n elements, into the memory at `p`.
   subroutine read_raw(self, name, dtype, n, p, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      integer, intent(in) :: dtype
      integer(i8), intent(in) :: n
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t), allocatable :: dims(:)
      integer(hid_t) :: did
      integer :: st
      type(c_ptr) :: buf
      buf = p
      call series_dims(self, name, did, dims, err)
      if (allocated(err)) return
      if (product(int(dims, i8)) /= n) then
         call fail(self, err, 'read '//itoa(n)//' values from the dataset of '// &
                   itoa(product(int(dims, i8)))//' values', name)
      else if (n > 0) then
         call h5dread_f(did, mem_type(dtype), buf, st)
         if (st < 0) call fail(self, err, 'read dataset', name)
      end if
      call close_handles(err, self, name, dset=did)
   end subroutine read_raw

   ! ---------------------------------------------------------------------------- views

   !> Create the virtual dataset `name` that shows the whole series `source` at every time,
   !> now and as the series grows: a series itself, of Fortran shape (view_lead..., unlimited),
   !> whose block (view_start, view_count) of every slab is the block (src_start, src_count) of
   !> the same slab of `source` (both in the leading dimensions, 0-based); the rest reads as 0.
   !> Created once, it costs nothing per output time (the mapping is unlimited in time).
   subroutine file_create_series_view(self, name, source, dtype, view_lead, view_start, view_count, &
                                      src_start, src_count, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: name, source
      integer, intent(in) :: dtype
      integer, intent(in) :: view_lead(:), view_start(:), view_count(:), src_start(:), src_count(:)
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: dims(size(view_lead) + 1), maxdims(size(view_lead) + 1)
      integer(hsize_t) :: start(size(view_lead) + 1), count(size(view_lead) + 1)
      integer(hid_t) :: vspace, sspace, dcpl, did
      integer :: st, rank

      if (.not. check_open(self, 'create series view '//name, err)) return
      rank = size(view_lead) + 1
      vspace = -1
      sspace = -1
      dcpl = -1
      did = -1
      steps: block
         dims(1:rank - 1) = int(view_lead, hsize_t)
         dims(rank) = 0
         maxdims = dims
         maxdims(rank) = H5S_UNLIMITED_F
         call h5screate_simple_f(rank, dims, vspace, st, maxdims)
         start(1:rank - 1) = int(view_start, hsize_t)
         count(1:rank - 1) = int(view_count, hsize_t)
         start(rank) = 0
         count(rank) = H5S_UNLIMITED_F
         if (st >= 0) call h5sselect_hyperslab_f(vspace, H5S_SELECT_SET_F, start, count, st)
         if (st < 0) then
            call fail(self, err, 'select the mapped block of series view', name)
            exit steps
         end if
         call h5dopen_f(self%fid, source, did, st)
         if (st >= 0) call h5dget_space_f(did, sspace, st)
         start(1:rank - 1) = int(src_start, hsize_t)
         count(1:rank - 1) = int(src_count, hsize_t)
         if (st >= 0) call h5sselect_hyperslab_f(sspace, H5S_SELECT_SET_F, start, count, st)
         if (st < 0) then
            call fail(self, err, 'select the source block '//source//' of series view', name)
            exit steps
         end if
         call h5dclose_f(did, st)
         did = -1
         call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, st)
         if (st >= 0) call set_zero_fill(dcpl, dtype, st)
         if (st >= 0) call h5pset_virtual_f(dcpl, vspace, '.', source, sspace, st)
         if (st < 0) then
            call fail(self, err, 'map '//source//' into series view', name)
            exit steps
         end if
         call h5dcreate_f(self%fid, name, file_type(dtype), vspace, did, st, dcpl_id=dcpl)
         if (st < 0) call fail(self, err, 'create series view', name)
      end block steps
      call close_handles(err, self, name, dset=did, space=vspace, space2=sspace, plist=dcpl)
   end subroutine file_create_series_view


   ! ---------------------------------------------------------------------------- attributes

   !> Real scalar attribute.
   subroutine attr_real0(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      real(wp), intent(in), target :: value
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_REAL), mem_type(DTYPE_REAL), dims, c_loc(value), err)
   end subroutine attr_real0

   !> Real vector attribute.
   subroutine attr_real1(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      real(wp), intent(in), target, contiguous :: value(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(value) > 0) p = c_loc(value)
      call attr_raw(self, obj, name, file_type(DTYPE_REAL), mem_type(DTYPE_REAL), &
                    int(shape(value), hsize_t), p, err)
   end subroutine attr_real1

   !> Integer scalar attribute.
   subroutine attr_int0(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      integer, intent(in), target :: value
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_INT), mem_type(DTYPE_INT), dims, c_loc(value), err)
   end subroutine attr_int0

   !> 64-bit integer scalar attribute.
   subroutine attr_int64_0(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      integer(i8), intent(in), target :: value
      type(error_t), allocatable, intent(out) :: err
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_INT64), mem_type(DTYPE_INT64), dims, c_loc(value), err)
   end subroutine attr_int64_0

   !> Integer vector attribute.
   subroutine attr_int1(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      integer, intent(in), target, contiguous :: value(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(value) > 0) p = c_loc(value)
      call attr_raw(self, obj, name, file_type(DTYPE_INT), mem_type(DTYPE_INT), &
                    int(shape(value), hsize_t), p, err)
   end subroutine attr_int1

   !> String attribute (fixed length, null padded; an empty string is stored as one null byte).
   subroutine attr_string(self, obj, name, value, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name, value
      type(error_t), allocatable, intent(out) :: err
      character(kind=c_char), allocatable, target :: buf(:)
      integer(hid_t) :: tid
      integer(hsize_t) :: dims(0)
      integer :: st, i, n

      if (.not. check_open(self, 'write attribute '//name, err)) return
      n = max(1, len(value))
      allocate (buf(n))
      buf = achar(0)
      do i = 1, len(value)
         buf(i) = value(i:i)
      end do
      call h5tcopy_f(H5T_FORTRAN_S1, tid, st)
      if (st >= 0) call h5tset_size_f(tid, int(n, kind=hsize_t), st)
      if (st >= 0) call h5tset_strpad_f(tid, H5T_STR_NULLPAD_F, st)
      if (st < 0) then
         call fail(self, err, 'make the string type of attribute '//name//' of', obj)
      else
         call attr_raw(self, obj, name, tid, tid, dims, c_loc(buf), err)
      end if
      call h5tclose_f(tid, st)
      if (st < 0 .and. .not. allocated(err)) call fail(self, err, 'close a string type of', obj)
   end subroutine attr_string

   !> Create (replacing any old one) the attribute `name` of object `obj` and write `p` into it.
   subroutine attr_raw(self, obj, name, ftype, mtype, dims, p, err)
      class(hdf5_file_t), intent(inout) :: self
      character(len=*), intent(in) :: obj, name
      integer(hid_t), intent(in) :: ftype, mtype
      integer(hsize_t), intent(in) :: dims(:)
      type(c_ptr), intent(in) :: p
      type(error_t), allocatable, intent(out) :: err
      integer(hid_t) :: oid, space, aid
      integer :: st
      logical :: exists

      if (.not. check_open(self, 'write attribute '//name, err)) return
      oid = -1
      space = -1
      aid = -1
      steps: block
         call h5oopen_f(self%fid, obj, oid, st)
         if (st < 0) then
            call fail(self, err, 'open object', obj)
            exit steps
         end if
         call h5aexists_f(oid, name, exists, st)
         if (st >= 0 .and. exists) call h5adelete_f(oid, name, st)
         if (st < 0) then
            call fail(self, err, 'replace attribute '//name//' of', obj)
            exit steps
         end if
         if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, space, st)
         else
            call h5screate_simple_f(size(dims), dims, space, st)
         end if
         if (st >= 0) call h5acreate_f(oid, name, ftype, space, aid, st)
         if (st < 0) then
            call fail(self, err, 'create attribute '//name//' of', obj)
            exit steps
         end if
         if (product(dims) > 0) then
            call h5awrite_f(aid, mtype, p, st)
            if (st < 0) call fail(self, err, 'write attribute '//name//' of', obj)
         end if
      end block steps
      call close_handles(err, self, obj, space=space, attr=aid, obj_id=oid)
   end subroutine attr_raw

   ! ---------------------------------------------------------------------------- helpers


   !> True when a file is open; otherwise set `err` saying what could not be done.
   logical function check_open(self, what, err)
      class(hdf5_file_t), intent(in) :: self
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(inout) :: err
      check_open = self%fid >= 0
      if (.not. check_open) call make_error(err, 'HDF5: cannot '//what//': no file is open')
   end function check_open

   !> Set `err` to "HDF5: cannot <what> '<obj>' in file '<path>'".
   subroutine fail(self, err, what, obj)
      class(hdf5_file_t), intent(in) :: self
      type(error_t), allocatable, intent(inout) :: err
      character(len=*), intent(in) :: what, obj
      call make_error(err, 'HDF5: cannot '//what//" '"//obj//"' in file '"//self%path//"'")
   end subroutine fail

   !> Close every handle given (those >= 0) and reset it to -1. A failing close sets `err`
   !> unless an earlier error is already there.
   subroutine close_handles(err, self, obj, dset, space, space2, plist, attr, obj_id)
      type(error_t), allocatable, intent(inout) :: err
      class(hdf5_file_t), intent(in) :: self
      character(len=*), intent(in) :: obj
      integer(hid_t), intent(inout), optional :: dset, space, space2, plist, attr, obj_id
      integer :: st, worst

      worst = 0
      if (present(dset)) then
         if (dset >= 0) call h5dclose_f(dset, st)
         if (dset >= 0) worst = min(worst, st)
         dset = -1
      end if
      if (present(space)) call close_space(space, worst)
      if (present(space2)) call close_space(space2, worst)
      if (present(plist)) then
         if (plist >= 0) call h5pclose_f(plist, st)
         if (plist >= 0) worst = min(worst, st)
         plist = -1
      end if
      if (present(attr)) then
         if (attr >= 0) call h5aclose_f(attr, st)
         if (attr >= 0) worst = min(worst, st)
         attr = -1
      end if
      if (present(obj_id)) then
         if (obj_id >= 0) call h5oclose_f(obj_id, st)
         if (obj_id >= 0) worst = min(worst, st)
         obj_id = -1
      end if
      if (worst < 0 .and. .not. allocated(err)) call fail(self, err, 'close the handles of', obj)
   end subroutine close_handles

   !> Close the dataspace `space` when open; keep the worst status in `worst`.
   subroutine close_space(space, worst)
      integer(hid_t), intent(inout) :: space
      integer, intent(inout) :: worst
      integer :: st
      if (space < 0) return
      call h5sclose_f(space, st)
      worst = min(worst, st)
      space = -1
   end subroutine close_space

end module exic_hdf5_file
