!> Attributes of hdf5_file_t (exic_hdf5_file).
submodule(exic_hdf5_file) exic_hdf5_file_attributes
   implicit none

contains

   !> Real scalar attribute.
   module procedure attr_real0
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_REAL), mem_type(DTYPE_REAL), dims, c_loc(value), err)
   end procedure attr_real0

   !> Real vector attribute.
   module procedure attr_real1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(value) > 0) p = c_loc(value)
      call attr_raw(self, obj, name, file_type(DTYPE_REAL), mem_type(DTYPE_REAL), &
                    int(shape(value), hsize_t), p, err)
   end procedure attr_real1

   !> Integer scalar attribute.
   module procedure attr_int0
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_INT), mem_type(DTYPE_INT), dims, c_loc(value), err)
   end procedure attr_int0

   !> 64-bit integer scalar attribute.
   module procedure attr_int64_0
      integer(hsize_t) :: dims(0)
      call attr_raw(self, obj, name, file_type(DTYPE_INT64), mem_type(DTYPE_INT64), dims, c_loc(value), err)
   end procedure attr_int64_0

   !> Integer vector attribute.
   module procedure attr_int1
      type(c_ptr) :: p
      p = c_null_ptr
      if (size(value) > 0) p = c_loc(value)
      call attr_raw(self, obj, name, file_type(DTYPE_INT), mem_type(DTYPE_INT), &
                    int(shape(value), hsize_t), p, err)
   end procedure attr_int1

   !> String attribute (fixed length, null padded; an empty string is stored as one null byte).
   module procedure attr_string
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
   end procedure attr_string

   !> Create (replacing any old one) the attribute `name` of object `obj` and write `p` into it.
   module procedure attr_raw
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
   end procedure attr_raw

end submodule exic_hdf5_file_attributes
