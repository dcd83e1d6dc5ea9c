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
!>
!> This module holds the type and the interfaces; the procedures are in its submodules:
!> file_files.f90 (files, groups, closing handles, errors), file_datasets.f90 (fixed datasets,
!> series views), file_series.f90 (series, reads), file_attributes.f90.
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

   interface
      !> Initialise the library (idempotent) and silence its own error printing: exic reports errors.
      module subroutine library_init(err)
         type(error_t), allocatable, intent(out) :: err
      end subroutine library_init

      !> Create (or truncate) the file `path` for writing.
      module subroutine file_create(self, path, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: path
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_create

      !> Open the existing file `path`, for writing when `writable`. `write_through`: no chunk
      !> cache and no sieve buffer, so that every H5Dwrite is written to the file at once, in the
      !> order of the calls, and a flush has no raw data left to write (doc/fields.md, "Kill safety").
      module subroutine file_open(self, path, writable, err, write_through)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: path
         logical, intent(in) :: writable
         type(error_t), allocatable, intent(out) :: err
         logical, intent(in), optional :: write_through
      end subroutine file_open

      !> True while a file is open.
      module pure logical function file_is_open(self)
         class(hdf5_file_t), intent(in) :: self
      end function file_is_open

      !> The HDF5 identifier of the open file (-1 when closed), for exic_hdf5_held.
      module pure integer(hid_t) function file_handle(self)
         class(hdf5_file_t), intent(in) :: self
      end function file_handle

      !> The path of the open file ('' when closed).
      module function file_name(self) result(path)
         class(hdf5_file_t), intent(in) :: self
         character(len=:), allocatable :: path
      end function file_name

      !> Write everything cached to disk (data and metadata), so that the file is complete and
      !> readable as it stands even if the process dies before `close`.
      module subroutine file_flush(self, err)
         class(hdf5_file_t), intent(inout) :: self
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_flush

      !> Close the file (nothing to do when none is open). Datasets held open on it
      !> (exic_hdf5_held) must be released first: HDF5 keeps a file open while one of its
      !> objects is.
      module subroutine file_close(self, err)
         class(hdf5_file_t), intent(inout) :: self
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_close

      !> Create the group `name` (a full path such as '/mesh'; its parent must exist).
      module subroutine file_create_group(self, name, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_create_group

      !> True when a file is open; otherwise set `err` saying what could not be done.
      module logical function check_open(self, what, err)
         class(hdf5_file_t), intent(in) :: self
         character(len=*), intent(in) :: what
         type(error_t), allocatable, intent(inout) :: err
      end function check_open

      !> Set `err` to "HDF5: cannot <what> '<obj>' in file '<path>'".
      module subroutine fail(self, err, what, obj)
         class(hdf5_file_t), intent(in) :: self
         type(error_t), allocatable, intent(inout) :: err
         character(len=*), intent(in) :: what, obj
      end subroutine fail

      !> Close every handle given (those >= 0) and reset it to -1. A failing close sets `err`
      !> unless an earlier error is already there.
      module subroutine close_handles(err, self, obj, dset, space, space2, plist, attr, obj_id)
         type(error_t), allocatable, intent(inout) :: err
         class(hdf5_file_t), intent(in) :: self
         character(len=*), intent(in) :: obj
         integer(hid_t), intent(inout), optional :: dset, space, space2, plist, attr, obj_id
      end subroutine close_handles

      !> Close the dataspace `space` when open; keep the worst status in `worst`.
      module subroutine close_space(space, worst)
         integer(hid_t), intent(inout) :: space
         integer, intent(inout) :: worst
      end subroutine close_space

      !> Write the real(wp) vector `x` as the new dataset `name`.
      module subroutine write_real1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine write_real1

      !> Write the real(wp) matrix `x` as the new dataset `name` (HDF5 shape reversed).
      module subroutine write_real2(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:, :)
         type(error_t), allocatable, intent(out) :: err
      end subroutine write_real2

      !> Write the integer vector `x` as the new dataset `name`.
      module subroutine write_int1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine write_int1

      !> Write the integer matrix `x` as the new dataset `name` (HDF5 shape reversed).
      module subroutine write_int2(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in), target, contiguous :: x(:, :)
         type(error_t), allocatable, intent(out) :: err
      end subroutine write_int2

      !> Create the fixed dataset `name` of shape `dims` and write the data at `p` (none when empty).
      module subroutine write_raw(self, name, dtype, dims, p, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: dtype
         integer(hsize_t), intent(in) :: dims(:)
         type(c_ptr), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
      end subroutine write_raw

      !> Overwrite the real(wp) vector dataset `name` with `x` (same shape).
      module subroutine rewrite_real1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine rewrite_real1

      !> Overwrite the real(wp) matrix dataset `name` with `x` (same shape).
      module subroutine rewrite_real2(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:, :)
         type(error_t), allocatable, intent(out) :: err
      end subroutine rewrite_real2

      !> Overwrite the integer vector dataset `name` with `x` (same shape).
      module subroutine rewrite_int1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine rewrite_int1

      !> Write the data at `p` over the whole existing dataset `name`, whose shape must be `dims`.
      module subroutine rewrite_raw(self, name, dtype, dims, p, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: dtype
         integer(hsize_t), intent(in) :: dims(:)
         type(c_ptr), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
      end subroutine rewrite_raw

      !> Create the virtual dataset `name` that shows the whole series `source` at every time,
      !> now and as the series grows: a series itself, of Fortran shape (view_lead..., unlimited),
      !> whose block (view_start, view_count) of every slab is the block (src_start, src_count) of
      !> the same slab of `source` (both in the leading dimensions, 0-based); the rest reads as 0.
      !> Created once, it costs nothing per output time (the mapping is unlimited in time).
      module subroutine file_create_series_view(self, name, source, dtype, view_lead, view_start, view_count, &
                                         src_start, src_count, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name, source
         integer, intent(in) :: dtype
         integer, intent(in) :: view_lead(:), view_start(:), view_count(:), src_start(:), src_count(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_create_series_view

      !> Create the extendible dataset `name` of Fortran shape (lead..., 0), unlimited in its last
      !> dimension, in chunks of whole slabs (no compression). With `capacity`, the dataset has
      !> `capacity` slabs at once, its chunks allocated but not written (fill time "never": an
      !> unwritten slab holds no output, doc/fields.md), and no object times: writing slabs into it
      !> later changes no metadata.
      module subroutine file_create_series(self, name, dtype, lead, err, capacity)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: dtype
         integer, intent(in) :: lead(:)   !< leading (fixed) dimensions, may be empty
         type(error_t), allocatable, intent(out) :: err
         integer, intent(in), optional :: capacity
      end subroutine file_create_series

      !> Number of slabs in the series `name` (its last dimension).
      module subroutine file_series_length(self, name, n, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(out) :: n
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_series_length

      !> Open the dataset (or series) `name` and return its handle and current dimensions (Fortran
      !> order).
      module subroutine series_dims(self, name, did, dims, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer(hid_t), intent(out) :: did
         integer(hsize_t), allocatable, intent(out) :: dims(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine series_dims

      !> Append the scalar `x` to the real series `name` of shape (n).
      module subroutine append_real0(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target :: x
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_real0

      !> Append the vector `x` to the real series `name` of shape (size(x), n).
      module subroutine append_real1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_real1

      !> Append the matrix `x` to the real series `name` of shape (size(x,1), size(x,2), n).
      module subroutine append_real2(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(in), target, contiguous :: x(:, :)
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_real2

      !> Append the integer vector `x` to the integer series `name` of shape (size(x), n).
      module subroutine append_int1(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_int1

      !> Append the integer(i8) scalar `x` to the 64-bit integer series `name` of shape (n).
      module subroutine append_int64_0(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer(i8), intent(in), target :: x
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_int64_0

      !> Grow the series `name` by one slab of Fortran shape `slab` and write the data at `p` into it.
      module subroutine append_raw(self, name, dtype, slab, p, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: dtype
         integer(hsize_t), intent(in) :: slab(:)
         type(c_ptr), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
      end subroutine append_raw

      !> True when the link `name` (one level below an existing group, or at the root) exists.
      module logical function file_exists(self, name) result(yes)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
      end function file_exists

      !> Set the number of slabs of the series `name` to `n` (fewer: the slabs beyond are dropped;
      !> more: new slabs, allocated and filled at once when the series was made with a capacity).
      module subroutine file_resize_series(self, name, n, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: n
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_resize_series

      !> Remove the link `name` (a dataset or group).
      module subroutine file_delete(self, name, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         type(error_t), allocatable, intent(out) :: err
      end subroutine file_delete

      !> Read the real dataset `name` whole into x (size(x) elements exactly).
      module subroutine read_real(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         real(wp), intent(inout), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine read_real

      !> Read the integer dataset `name` whole into x (size(x) elements exactly).
      module subroutine read_int(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(inout), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine read_int

      !> Read the 64-bit integer dataset `name` whole into x (size(x) elements exactly).
      module subroutine read_int64(self, name, x, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer(i8), intent(inout), target, contiguous :: x(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine read_int64

      !> Read the whole dataset `name`, which must hold n elements, into the memory at `p`.
      module subroutine read_raw(self, name, dtype, n, p, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: name
         integer, intent(in) :: dtype
         integer(i8), intent(in) :: n
         type(c_ptr), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
      end subroutine read_raw

      !> Real scalar attribute.
      module subroutine attr_real0(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         real(wp), intent(in), target :: value
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_real0

      !> Real vector attribute.
      module subroutine attr_real1(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         real(wp), intent(in), target, contiguous :: value(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_real1

      !> Integer scalar attribute.
      module subroutine attr_int0(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         integer, intent(in), target :: value
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_int0

      !> 64-bit integer scalar attribute.
      module subroutine attr_int64_0(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         integer(i8), intent(in), target :: value
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_int64_0

      !> Integer vector attribute.
      module subroutine attr_int1(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         integer, intent(in), target, contiguous :: value(:)
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_int1

      !> String attribute (fixed length, null padded; an empty string is stored as one null byte).
      module subroutine attr_string(self, obj, name, value, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name, value
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_string

      !> Create (replacing any old one) the attribute `name` of object `obj` and write `p` into it.
      module subroutine attr_raw(self, obj, name, ftype, mtype, dims, p, err)
         class(hdf5_file_t), intent(inout) :: self
         character(len=*), intent(in) :: obj, name
         integer(hid_t), intent(in) :: ftype, mtype
         integer(hsize_t), intent(in) :: dims(:)
         type(c_ptr), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
      end subroutine attr_raw
   end interface

end module exic_hdf5_file
