!> Series of hdf5_file_t (extendible datasets, one slab at a time) and whole-dataset reads (exic_hdf5_file).
submodule(exic_hdf5_file) exic_hdf5_file_series
   implicit none

contains

   !> Create the extendible dataset `name` of Fortran shape (lead..., 0), unlimited in its last
   !> dimension, in chunks of whole slabs (no compression). With `capacity`, the dataset has
   !> `capacity` slabs at once, its chunks allocated but not written (fill time "never": an
   !> unwritten slab holds no output, doc/fields.md), and no object times: writing slabs into it
   !> later changes no metadata.
   module procedure file_create_series
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
   end procedure file_create_series

   !> Number of slabs in the series `name` (its last dimension).
   module procedure file_series_length
      integer(hsize_t), allocatable :: dims(:)
      integer(hid_t) :: did
      n = 0
      call series_dims(self, name, did, dims, err)
      if (allocated(err)) return
      n = int(dims(size(dims)))
      call close_handles(err, self, name, dset=did)
   end procedure file_series_length

   !> Open the dataset (or series) `name` and return its handle and current dimensions (Fortran
   !> order).
   module procedure series_dims
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
   end procedure series_dims

   !> Append the scalar `x` to the real series `name` of shape (n).
   module procedure append_real0
      integer(hsize_t) :: slab(0)
      call append_raw(self, name, DTYPE_REAL, slab, c_loc(x), err)
   end procedure append_real0

   !> Append the vector `x` to the real series `name` of shape (size(x), n).
   module procedure append_real1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure append_real1

   !> Append the matrix `x` to the real series `name` of shape (size(x,1), size(x,2), n).
   module procedure append_real2
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure append_real2

   !> Append the integer vector `x` to the integer series `name` of shape (size(x), n).
   module procedure append_int1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call append_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end procedure append_int1

   !> Append the integer(i8) scalar `x` to the 64-bit integer series `name` of shape (n).
   module procedure append_int64_0
      integer(hsize_t) :: slab(0)
      call append_raw(self, name, DTYPE_INT64, slab, c_loc(x), err)
   end procedure append_int64_0

   !> Grow the series `name` by one slab of Fortran shape `slab` and write the data at `p` into it.
   module procedure append_raw
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
   end procedure append_raw

   !> True when the link `name` (one level below an existing group, or at the root) exists.
   module logical function file_exists(self, name) result(yes)
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
   module procedure file_resize_series
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
   end procedure file_resize_series

   !> Remove the link `name` (a dataset or group).
   module procedure file_delete
      integer :: st
      if (.not. check_open(self, 'delete '//name, err)) return
      call h5ldelete_f(self%fid, name, st)
      if (st < 0) call fail(self, err, 'delete', name)
   end procedure file_delete

   !> Read the real dataset `name` whole into x (size(x) elements exactly).
   module procedure read_real
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_REAL, int(size(x), i8), p, err)
   end procedure read_real

   !> Read the integer dataset `name` whole into x (size(x) elements exactly).
   module procedure read_int
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_INT, int(size(x), i8), p, err)
   end procedure read_int

   !> Read the 64-bit integer dataset `name` whole into x (size(x) elements exactly).
   module procedure read_int64
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call read_raw(self, name, DTYPE_INT64, int(size(x), i8), p, err)
   end procedure read_int64

   !> Read the whole dataset `name`, which must hold n elements, into the memory at `p`.
   module procedure read_raw
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
   end procedure read_raw

end submodule exic_hdf5_file_series
