!> Files and groups of hdf5_file_t, and the helpers that close handles and make errors (exic_hdf5_file).
submodule(exic_hdf5_file) exic_hdf5_file_files
   implicit none

contains

   !> Initialise the library (idempotent) and silence its own error printing: exic reports errors.
   module procedure library_init
      integer :: st
      call h5open_f(st)
      if (st < 0) then
         call make_error(err, 'cannot initialise the HDF5 library')
         return
      end if
      call h5eset_auto_f(0, st)
      if (st < 0) call make_error(err, 'cannot switch off HDF5 error printing')
   end procedure library_init

   !> Create (or truncate) the file `path` for writing.
   module procedure file_create
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
   end procedure file_create

   !> Open the existing file `path`, for writing when `writable`. `write_through`: no chunk
   !> cache and no sieve buffer, so that every H5Dwrite is written to the file at once, in the
   !> order of the calls, and a flush has no raw data left to write (doc/fields.md, "Kill safety").
   module procedure file_open
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
   end procedure file_open

   !> True while a file is open.
   module pure logical function file_is_open(self)
      class(hdf5_file_t), intent(in) :: self
      file_is_open = self%fid >= 0
   end function file_is_open

   !> The HDF5 identifier of the open file (-1 when closed), for exic_hdf5_held.
   module pure integer(hid_t) function file_handle(self)
      class(hdf5_file_t), intent(in) :: self
      file_handle = self%fid
   end function file_handle

   !> The path of the open file ('' when closed).
   module procedure file_name
      if (allocated(self%path) .and. self%fid >= 0) then
         path = self%path
      else
         path = ''
      end if
   end procedure file_name

   !> Write everything cached to disk (data and metadata), so that the file is complete and
   !> readable as it stands even if the process dies before `close`.
   module procedure file_flush
      integer :: st
      if (.not. check_open(self, 'flush', err)) return
      call h5fflush_f(self%fid, H5F_SCOPE_GLOBAL_F, st)
      if (st < 0) call make_error(err, "HDF5: cannot flush file '"//self%path//"'")
   end procedure file_flush

   !> Close the file (nothing to do when none is open). Datasets held open on it
   !> (exic_hdf5_held) must be released first: HDF5 keeps a file open while one of its
   !> objects is.
   module procedure file_close
      integer :: st
      if (self%fid < 0) return
      call h5fclose_f(self%fid, st)
      self%fid = -1
      if (st < 0) call make_error(err, "HDF5: cannot close file '"//self%path//"'")
   end procedure file_close

   !> Create the group `name` (a full path such as '/mesh'; its parent must exist).
   module procedure file_create_group
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
   end procedure file_create_group

   !> True when a file is open; otherwise set `err` saying what could not be done.
   module logical function check_open(self, what, err)
      class(hdf5_file_t), intent(in) :: self
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(inout) :: err
      check_open = self%fid >= 0
      if (.not. check_open) call make_error(err, 'HDF5: cannot '//what//': no file is open')
   end function check_open

   !> Set `err` to "HDF5: cannot <what> '<obj>' in file '<path>'".
   module procedure fail
      call make_error(err, 'HDF5: cannot '//what//" '"//obj//"' in file '"//self%path//"'")
   end procedure fail

   !> Close every handle given (those >= 0) and reset it to -1. A failing close sets `err`
   !> unless an earlier error is already there.
   module procedure close_handles
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
   end procedure close_handles

   !> Close the dataspace `space` when open; keep the worst status in `worst`.
   module procedure close_space
      integer :: st
      if (space < 0) return
      call h5sclose_f(space, st)
      worst = min(worst, st)
      space = -1
   end procedure close_space

end submodule exic_hdf5_file_files
