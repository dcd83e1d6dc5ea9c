!> Fixed datasets of hdf5_file_t (written once or rewritten whole) and series views (exic_hdf5_file).
submodule(exic_hdf5_file) exic_hdf5_file_datasets
   implicit none

contains

   !> Write the real(wp) vector `x` as the new dataset `name`.
   module procedure write_real1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure write_real1

   !> Write the real(wp) matrix `x` as the new dataset `name` (HDF5 shape reversed).
   module procedure write_real2
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure write_real2

   !> Write the integer vector `x` as the new dataset `name`.
   module procedure write_int1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end procedure write_int1

   !> Write the integer matrix `x` as the new dataset `name` (HDF5 shape reversed).
   module procedure write_int2
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call write_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end procedure write_int2

   !> Create the fixed dataset `name` of shape `dims` and write the data at `p` (none when empty).
   module procedure write_raw
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
   end procedure write_raw

   !> Overwrite the real(wp) vector dataset `name` with `x` (same shape).
   module procedure rewrite_real1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure rewrite_real1

   !> Overwrite the real(wp) matrix dataset `name` with `x` (same shape).
   module procedure rewrite_real2
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_REAL, int(shape(x), hsize_t), p, err)
   end procedure rewrite_real2

   !> Overwrite the integer vector dataset `name` with `x` (same shape).
   module procedure rewrite_int1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(x) > 0) p = c_loc(x)
      call rewrite_raw(self, name, DTYPE_INT, int(shape(x), hsize_t), p, err)
   end procedure rewrite_int1

   !> Write the data at `p` over the whole existing dataset `name`, whose shape must be `dims`.
   module procedure rewrite_raw
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
   end procedure rewrite_raw

   !> Create the virtual dataset `name` that shows the whole series `source` at every time,
   !> now and as the series grows: a series itself, of Fortran shape (view_lead..., unlimited),
   !> whose block (view_start, view_count) of every slab is the block (src_start, src_count) of
   !> the same slab of `source` (both in the leading dimensions, 0-based); the rest reads as 0.
   !> Created once, it costs nothing per output time (the mapping is unlimited in time).
   module procedure file_create_series_view
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
   end procedure file_create_series_view

end submodule exic_hdf5_file_datasets
