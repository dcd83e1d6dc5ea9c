!> Full-field output: `<stem>.h5` (HDF5) described by two XDMF 3 files, `<stem>.xdmf` (the last
!> output time alone: meshio.read, meshio convert, ParaView) and `<stem>_series.xdmf` (every
!> output time: ParaView's Xdmf3 reader). The layout is documented in doc/fields.md.
!>
!> The mesh is written once; each output time appends one slab to the extendible datasets under
!> `/fields` (Fortran shape (component, entity, time); h5py shape (time, entity, component)):
!> the nodal vectors, the contact flag, the element values (stress components and whatever a
!> material adds, named at `open`) and their area-weighted averages at the nodes; then to
!> `/energies/<name>`, and last to `/time` and `/step`. The series XDMF file addresses slab k
!> of these datasets directly (Xdmf3's "file:/dataset|start:stride:count:dims" form); the 2-D
!> vectors are seen through virtual datasets `/xdmf/<vector>` that pad them to 3 components
!> (made once at `open`, unlimited in time: nothing per output time). The last output time is
!> also written as plain arrays into one of two buffers `/last/a`, `/last/b` (alternately, so
!> that the buffer the `<stem>.xdmf` names is never the one being written).
!>
!> Kill safety (doc/fields.md): no metadata byte of the .h5 changes while the run goes on. The
!> file is created whole under a temporary name (mesh, every series with room for the expected
!> output times, chunks allocated early and filled with NaN / -1, the buffers, the count
!> `/n_times`), renamed, and opened write-through; an output time writes raw data only, through
!> dataset handles held open (exic_io_hdf5_held), the count last, then flushes. Growth, restart
!> and the final cut to the times written are a copy of the file changed and renamed over it.
!> Only then are the XDMF files updated: the series is appended to in place by writes each of
!> which leaves a well-formed document (exic_io_xdmf), the last-state file is written to a
!> temporary name and renamed. A run killed at any moment leaves an HDF5 file whose count names
!> its complete output times and XDMF files that parse and name only those.
module exic_io_fields
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   use exic_mesh_smoothing, only: nodal_average
   use exic_io_hdf5_file, only: hdf5_file_t, DTYPE_REAL, DTYPE_INT, DTYPE_INT64
   use exic_io_hdf5_held, only: hdf5_held_t
   use exic_io_fields_checks, only: check_mesh, check_names
   use exic_io_posix, only: rename_file, copy_file, remove_file
   use exic_io_xdmf, only: xdmf_series_t, write_whole_file, xml_escape, real_text, data_item, &
                           attribute
   implicit none
   private

   public :: field_writer_t, STRESS_NAMES, NODE_VECTORS, series_path

   !> Names of the seven stress components (TPLOt order: 1 sxx, 2 syy, 3 szz, 4 sxy,
   !> 5 pressure, 6 von Mises, 7 J): the default element values, in `/fields/stress`.
   character(len=9), parameter :: STRESS_NAMES(7) = [character(len=9) :: 'sxx', 'syy', 'szz', &
                                                     'sxy', 'pressure', 'von_mises', 'J']
   !> Names of the nodal vector fields, datasets `/fields/<name>`; the last, the nodal friction
   !> force (doc/friction.md), only when the run has friction (`nvec`).
   character(len=14), parameter :: NODE_VECTORS(5) = [character(len=14) :: 'displacement', &
                                                      'velocity', 'acceleration', 'contact_force', &
                                                      'friction_force']
   !> The two last-state buffers, `/last/a` and `/last/b`.
   character(len=1), parameter :: BUFFER(0:1) = ['a', 'b']

   character(len=*), parameter :: NL = achar(10)

   !> Output times preallocated when the caller gives no estimate, and the most bytes a
   !> preallocation made from an estimate may take (growth takes over beyond it).
   integer, parameter :: START_CAPACITY = 16
   integer(i8), parameter :: ESTIMATE_BYTES_MAX = 256_i8*1024*1024
   !> The count of complete output times while the run goes on (removed at `close`).
   character(len=*), parameter :: COUNT_NAME = '/n_times'

   !> Writer of one field output (`.h5`, `.xdmf`, `_series.xdmf`).
   type :: field_writer_t
      private
      type(hdf5_file_t) :: h5
      type(hdf5_held_t) :: held                     !< the datasets an output time writes
      type(xdmf_series_t) :: series                 !< <stem>_series.xdmf
      character(len=:), allocatable :: last_path    !< <stem>.xdmf
      character(len=:), allocatable :: h5_ref       !< the .h5 file as the XDMF files name it
      integer :: nnode = 0, nelem = 0
      integer :: nvec = 4                           !< nodal vectors written (5: with friction_force)
      integer :: ncomp = 0                          !< element value components
      character(len=16), allocatable :: comp_names(:)
      real(wp), allocatable :: x0(:, :)             !< reference coordinates (2, nnode)
      integer, allocatable :: conn(:, :)            !< connectivity (4, nelem), 1-based
      real(wp), allocatable :: x(:, :), vec3(:, :), nodal(:, :), col_cell(:), col_node(:)
      integer :: ntime = 0                          !< output times written so far
      integer :: capacity = 0                       !< output times the series have room for
      character(len=:), allocatable :: path_h5
      character(len=:), allocatable :: failed       !< message of a failed run, stored at close
      !> handles of the held datasets (hdf5_file_t%hold): the count, the series, the buffers
      integer :: id_count = 0, id_active = 0, id_stress = 0, id_nodal = 0, id_time = 0, id_step = 0
      integer :: id_vec(5) = 0
      integer, allocatable :: id_energy(:)
      !> per buffer (0:1): vectors 1..nvec, contact_active, cell_<c>, node_<c>, output
      integer, allocatable :: id_last(:, :)
      real(wp) :: t_last = 0.0_wp
      integer :: nenergy = -1                       !< -1 until the first write_step
      character(len=:), allocatable :: energy_names(:)
      logical :: broken = .false.                   !< a write failed half-way
   contains
      procedure :: open => writer_open
      procedure :: reopen => writer_reopen
      procedure :: write_step => writer_write_step
      procedure :: close => writer_close
      procedure :: mark_failed => writer_mark_failed
      procedure :: is_open => writer_is_open
      procedure :: count => writer_count
   end type field_writer_t

contains

   !> Create `path_h5`, `path_xdmf` and its series file (`series_path(path_xdmf)`) and write the
   !> mesh: reference coordinates x0(2, nnode), connectivity conn(4, nelem) (1-based here; stored
   !> 0-based), region and material numbers per element, and the contact edges surf_edges(2, nedge)
   !> (node pairs, 1-based; may be empty). `cell_names` names the element values of each output
   !> time (default STRESS_NAMES; letters, digits and '_'). `energy_names`, when given, creates the
   !> energy series now instead of at the first output time (then every object of the file exists
   !> after `open`; otherwise the first output time copies the file once to add them). The files must share
   !> one directory unless `path_h5` is absolute. `friction`: the run has friction; every output
   !> time then also holds the nodal friction force. `capacity`: the number of output times the
   !> run expects (room is made for them at once; more are possible, at the cost of a copy of
   !> the file each time the room doubles).
   subroutine writer_open(self, path_h5, path_xdmf, nnode, nelem, x0, conn, region, mat, &
                          surf_edges, err, cell_names, energy_names, friction, capacity)
      class(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path_h5, path_xdmf
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in), contiguous :: x0(:, :)
      integer, intent(in), contiguous :: conn(:, :), region(:), mat(:), surf_edges(:, :)
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in), optional :: cell_names(:)
      character(len=*), intent(in), optional :: energy_names(:)
      logical, intent(in), optional :: friction
      integer, intent(in), optional :: capacity
      type(error_t), allocatable :: err2

      if (self%h5%is_open()) then
         call make_error(err, "field output: cannot open '"//path_h5//"': the writer already has '"// &
                         self%h5%name()//"' open")
         return
      end if
      call check_mesh(nnode, nelem, x0, conn, region, mat, surf_edges, path_h5, err)
      if (allocated(err)) return
      if (present(cell_names)) then
         call check_names(cell_names, 'element value', err)
         if (allocated(err)) return
         self%comp_names = cell_names
      else
         self%comp_names = STRESS_NAMES
      end if
      call prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction)
      if (allocated(err)) return

      self%capacity = initial_capacity(self, capacity, energy_names)
      ! made whole under a temporary name, closed and renamed: a run killed while the file is
      ! being created leaves no .h5 rather than a broken one. Every dataset the run writes
      ! exists after this, with room for `capacity` output times (doc/fields.md, "Kill safety")
      call self%h5%create(path_h5//'.tmp', err)
      if (allocated(err)) return
      call write_mesh(self%h5, x0, conn, region, mat, surf_edges, err)
      if (.not. allocated(err)) call create_field_series(self, err)
      if (.not. allocated(err)) call create_last_buffers(self, err)
      if (.not. allocated(err) .and. present(energy_names)) &
         call create_energy_series(self, self%h5, energy_names, err)
      if (.not. allocated(err)) call self%h5%write(COUNT_NAME, [0], err)
      if (.not. allocated(err)) call close_live(self, err)
      if (.not. allocated(err)) call rename_file(path_h5//'.tmp', path_h5, err)
      if (.not. allocated(err)) call open_live(self, err)
      if (.not. allocated(err)) call self%series%create(series_path(path_xdmf), series_head(), &
                                                        series_tail(), err)
      if (.not. allocated(err)) call write_whole_file(self%last_path, last_document(self, -1, 0.0_wp, &
                                                                                    0_i8), err)
      if (allocated(err)) then
         call self%series%abandon()
         call close_live(self, err2)
         call remove_file(path_h5//'.tmp')     ! a file that could not be made whole
      end if
   end subroutine writer_open

   !> The writer's set-up for a mesh (names, sizes, work arrays), before its files are made.
   subroutine prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction)
      type(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path_h5, path_xdmf
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in) :: x0(:, :)
      integer, intent(in) :: conn(:, :)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: friction
      character(len=:), allocatable :: ref
      call xdmf_reference(path_h5, path_xdmf, ref, err)
      if (allocated(err)) return
      self%h5_ref = xml_escape(ref, dash=.true.)
      self%last_path = path_xdmf
      self%path_h5 = path_h5
      if (allocated(self%failed)) deallocate (self%failed)
      self%nnode = nnode
      self%nelem = nelem
      self%nvec = 4
      if (present(friction)) then
         if (friction) self%nvec = 5
      end if
      self%ncomp = size(self%comp_names)
      self%x0 = x0
      self%conn = conn
      if (allocated(self%x)) deallocate (self%x, self%vec3, self%nodal, self%col_cell, self%col_node)
      allocate (self%x(2, nnode), self%vec3(3, nnode), self%nodal(self%ncomp, nnode), &
                self%col_cell(nelem), self%col_node(nnode))
      self%ntime = 0
      self%t_last = 0.0_wp
      self%nenergy = -1
      self%broken = .false.
      if (allocated(self%energy_names)) deallocate (self%energy_names)
   end subroutine prepare

   !> Continue the field output of a restarted run: take the existing `path_h5` (written by
   !> `open` for the same mesh with the same `cell_names`, `energy_names` and `friction`, finished
   !> or left by a killed run), keep its first `ntime` output times (those written before the
   !> restart point), make room for `capacity` more (default START_CAPACITY) by a copy of the
   !> file renamed over it, and write the series file anew for the times kept. The last-state
   !> file is rewritten at the next output time.
   subroutine writer_reopen(self, path_h5, path_xdmf, nnode, nelem, x0, conn, ntime, energy_names, err, &
                            cell_names, friction, capacity)
      class(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path_h5, path_xdmf
      integer, intent(in) :: nnode, nelem, ntime
      real(wp), intent(in), contiguous :: x0(:, :)
      integer, intent(in), contiguous :: conn(:, :)
      character(len=*), intent(in) :: energy_names(:)
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in), optional :: cell_names(:)
      logical, intent(in), optional :: friction
      integer, intent(in), optional :: capacity
      type(error_t), allocatable :: err2
      real(wp), allocatable :: times(:)
      integer(i8), allocatable :: steps(:)
      integer :: i, held

      if (present(cell_names)) then
         self%comp_names = cell_names
      else
         self%comp_names = STRESS_NAMES
      end if
      call prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction)
      if (allocated(err)) return
      self%energy_names = energy_names
      self%nenergy = size(energy_names)
      call complete_times(path_h5, held, err)
      if (.not. allocated(err) .and. held < ntime) &
         call make_error(err, "field output: '"//path_h5//"' holds "//itoa(held)// &
                         ' output times, fewer than the '//itoa(ntime)//' the restart file recorded')
      if (allocated(err)) then
         err%message = 'field output (restart): '//err%message
         return
      end if
      self%capacity = ntime + initial_capacity(self, capacity, energy_names)
      call rebuild(self, ntime, self%capacity, .false., err)
      if (.not. allocated(err)) then
         allocate (times(self%capacity), steps(self%capacity))
         call self%h5%read('/time', times, err)
      end if
      if (.not. allocated(err)) call self%h5%read('/step', steps, err)
      if (.not. allocated(err)) call self%series%create(series_path(path_xdmf), series_head(), &
                                                        series_tail(), err)
      do i = 1, ntime
         if (allocated(err)) exit
         self%ntime = i
         self%t_last = times(i)
         call self%series%append(series_grid(self, i - 1, times(i)), err)
      end do
      if (allocated(err)) then
         call self%series%abandon()
         call close_live(self, err2)
         err%message = 'field output (restart): '//err%message
      end if
   end subroutine writer_reopen

   !> Append one output time t (solver step `step`): nodal displacement u, velocity v,
   !> acceleration a and contact force fcont, each (2, nnode); the contact flag active(nnode)
   !> (1 where a node carries an active constraint); the element values sig(ncomp, nelem) (by
   !> default the stress: sxx, syy, szz, sxy, pressure, von Mises, J), averaged to the nodes here;
   !> and the energies with their names (the same names, in the same order, at every call);
   !> ffric(2, nnode), the nodal friction force, when the writer was opened with friction.
   !> Flushes the .h5 file, then appends to the series XDMF file and rewrites the last-state one.
   subroutine writer_write_step(self, t, step, u, v, a, sig, fcont, active, energies, &
                                energy_names, err, ffric)
      class(field_writer_t), intent(inout) :: self
      real(wp), intent(in) :: t
      integer(i8), intent(in) :: step
      real(wp), intent(in), contiguous :: u(:, :), v(:, :), a(:, :), sig(:, :), fcont(:, :)
      integer, intent(in), contiguous :: active(:)
      real(wp), intent(in) :: energies(:)
      character(len=*), intent(in) :: energy_names(:)
      type(error_t), allocatable, intent(out) :: err
      real(wp), intent(in), contiguous, optional :: ffric(:, :)
      integer :: i, b, k

      call check_step(self, t, u, v, a, sig, fcont, active, energies, energy_names, err)
      if (allocated(err)) return
      if (self%nvec == 5) then
         if (.not. present(ffric)) then
            call make_error(err, 'field output: the friction force is missing')
         else if (any(shape(ffric) /= [2, self%nnode])) then
            call make_error(err, 'field output: the friction force must be (2, nnode)')
         end if
         if (allocated(err)) return
      end if
      if (self%nenergy < 0) then
         ! the energy series are added by a copy of the file, like a growth
         self%energy_names = energy_names
         call rebuild(self, self%ntime, self%capacity, .false., err, new_energies=.true.)
         if (allocated(err)) then
            self%broken = .true.
            return
         end if
         self%nenergy = size(energy_names)
      end if
      if (self%ntime == self%capacity) then
         call rebuild(self, self%ntime, 2*max(self%capacity, 1), .false., err)
         if (allocated(err)) then
            self%broken = .true.
            err%message = 'field output at t = '//real_text(t)//': '//err%message
            return
         end if
      end if
      ! element values averaged to the nodes over the current configuration
      self%x = self%x0 + u
      call nodal_average(self%ncomp, self%nnode, self%nelem, self%conn, self%x, sig, self%nodal)

      ! raw data only, into the slab k allocated at creation, through the held handles
      k = self%ntime
      call self%held%write_slab(self%id_vec(1), k, u, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_vec(2), k, v, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_vec(3), k, a, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_vec(4), k, fcont, err)
      if (.not. allocated(err) .and. self%nvec == 5) call self%held%write_slab(self%id_vec(5), k, ffric, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_active, k, active, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_stress, k, sig, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_nodal, k, self%nodal, err)
      do i = 1, size(energies)
         if (allocated(err)) exit
         call self%held%write_slab(self%id_energy(i), k, energies(i), err)
      end do
      if (.not. allocated(err)) call self%held%write_slab(self%id_time, k, t, err)
      if (.not. allocated(err)) call self%held%write_slab(self%id_step, k, step, err)
      b = mod(self%ntime, 2)
      if (.not. allocated(err)) call write_last_buffer(self, b, u, v, a, fcont, active, sig, err)
      if (.not. allocated(err) .and. self%nvec == 5) then
         self%vec3(1:2, :) = ffric
         call self%held%write_whole(self%id_last(5, b), self%vec3, err)
      end if
      ! the count last: it says how many slabs hold a complete output time
      if (.not. allocated(err)) call self%held%write_whole(self%id_count, self%ntime + 1, err)
      if (.not. allocated(err)) call self%h5%flush(err)
      if (.not. allocated(err)) then
         self%ntime = self%ntime + 1
         self%t_last = t
         ! only now, with the HDF5 file complete on disk, do the XDMF files name this time
         call self%series%append(series_grid(self, self%ntime - 1, t), err)
         if (.not. allocated(err)) &
            call write_whole_file(self%last_path, last_document(self, b, t, step), err)
      end if
      if (allocated(err)) then
         self%broken = .true.
         err%message = 'field output at t = '//real_text(t)//': '//err%message
      end if
   end subroutine writer_write_step

   !> Close the .h5 file and cut it to the output times written (a copy renamed over it, which
   !> also drops the count `/n_times` and stores the message of `mark_failed`), then write the
   !> series file once more without its reserve (the last-state file is complete already).
   !> Every file is closed even when one step fails; the first failure is returned (the .h5 is
   !> then left as a killed run leaves it). No-op when not open.
   subroutine writer_close(self, err)
      class(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: err2
      if (.not. self%h5%is_open()) return
      call rebuild(self, self%ntime, self%ntime, .true., err)
      call close_live(self, err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      call self%series%finish(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      call self%series%abandon()
   end subroutine writer_close

   !> Record that the run failed: the root attribute `failed` of the .h5 file will hold `message`
   !> (the last output time is then the state the run stopped in). It is stored by `close`, in
   !> the copy that cuts the file to its output times: during the run no metadata changes.
   subroutine writer_mark_failed(self, message, err)
      class(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: message
      type(error_t), allocatable, intent(out) :: err
      if (.not. self%h5%is_open()) then
         call make_error(err, 'field output: cannot mark the run failed: the writer is not open')
         return
      end if
      self%failed = message
   end subroutine writer_mark_failed

   !> Room for how many output times at `open`: the caller's estimate (when given and positive),
   !> at most what ESTIMATE_BYTES_MAX holds, else START_CAPACITY.
   integer function initial_capacity(self, capacity, energy_names) result(k)
      type(field_writer_t), intent(in) :: self
      integer, intent(in), optional :: capacity
      character(len=*), intent(in), optional :: energy_names(:)
      integer(i8) :: per_time
      integer :: ne
      k = START_CAPACITY
      if (.not. present(capacity)) return
      if (capacity <= 0) return
      ne = 0
      if (present(energy_names)) ne = size(energy_names)
      per_time = 8_i8*(2_i8*self%nvec*self%nnode + int(self%ncomp, i8)*(self%nelem + self%nnode) + ne + 2) + &
                 4_i8*self%nnode
      k = int(max(1_i8, min(int(capacity, i8), ESTIMATE_BYTES_MAX/per_time)))
   end function initial_capacity

   !> Release the held datasets and close the live file (nothing to do when it is closed).
   subroutine close_live(self, err)
      type(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: err2
      call self%held%release(err)
      call self%h5%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
   end subroutine close_live

   !> Open the live file for writing, write-through, and hold every dataset an output time writes.
   subroutine open_live(self, err)
      type(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: g
      integer :: i, b, j
      call self%h5%open(self%path_h5, .true., err, write_through=.true.)
      if (allocated(err)) return
      call self%held%hold(self%h5, COUNT_NAME, self%id_count, err)
      do i = 1, self%nvec
         if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/'//trim(NODE_VECTORS(i)), self%id_vec(i), err)
      end do
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/contact_active', self%id_active, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/stress', self%id_stress, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/nodal_stress', self%id_nodal, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/time', self%id_time, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/step', self%id_step, err)
      if (allocated(self%id_energy)) deallocate (self%id_energy)
      allocate (self%id_energy(max(self%nenergy, 0)))
      do i = 1, self%nenergy
         if (.not. allocated(err)) call self%held%hold(self%h5, '/energies/'//trim(self%energy_names(i)), &
                                                     self%id_energy(i), err)
      end do
      if (allocated(self%id_last)) deallocate (self%id_last)
      allocate (self%id_last(self%nvec + 2 + 2*self%ncomp, 0:1))
      do b = 0, 1
         g = '/last/'//BUFFER(b)//'/'
            do i = 1, self%nvec
               if (.not. allocated(err)) call self%held%hold(self%h5, g//trim(NODE_VECTORS(i)), self%id_last(i, b), err)
            end do
            j = self%nvec + 1
            if (.not. allocated(err)) call self%held%hold(self%h5, g//'contact_active', self%id_last(j, b), err)
            do i = 1, self%ncomp
               if (.not. allocated(err)) call self%held%hold(self%h5, g//'cell_'//trim(self%comp_names(i)), &
                                                           self%id_last(j + i, b), err)
               if (.not. allocated(err)) call self%held%hold(self%h5, g//'node_'//trim(self%comp_names(i)), &
                                                           self%id_last(j + self%ncomp + i, b), err)
            end do
            if (.not. allocated(err)) call self%held%hold(self%h5, g//'output', self%id_last(j + 2*self%ncomp + 1, b), err)
      end do
   end subroutine open_live

   !> Change the file's metadata the only way that is safe while a run may be killed: close it,
   !> copy it to <path>.tmp, change the copy, rename the copy over it. Every series is cut to
   !> `nkeep` output times (the slabs beyond become unwritten again) and, unless `final`, given
   !> room for `capacity`; the count is set to `nkeep` (made when missing: a finished file).
   !> `final`: the finished file instead (no count, no room, the `failed` attribute when the run
   !> failed), not opened again. `new_energies`: also create the energy series of
   !> self%energy_names. Otherwise the live file is opened again and its datasets held. The file
   !> at <path> is at every moment either the old whole file or the new whole file.
   subroutine rebuild(self, nkeep, capacity, final, err, new_energies)
      type(field_writer_t), intent(inout) :: self
      integer, intent(in) :: nkeep, capacity
      logical, intent(in) :: final
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: new_energies
      type(hdf5_file_t) :: tmp
      type(error_t), allocatable :: err2
      character(len=:), allocatable :: path
      integer :: i

      path = self%path_h5//'.tmp'
      call close_live(self, err)
      if (allocated(err)) return
      call copy_file(self%path_h5, path, err)
      if (.not. allocated(err)) call tmp%open(path, .true., err)
      if (allocated(err)) then
         call remove_file(path)
         return
      end if
      if (present(new_energies)) then
         if (new_energies) call create_energy_series(self, tmp, self%energy_names, err)
      end if
      associate (names => series_names(self))
         do i = 1, size(names)
            if (allocated(err)) exit
            call tmp%resize_series(trim(names(i)), nkeep, err)
            if (.not. allocated(err) .and. .not. final) call tmp%resize_series(trim(names(i)), capacity, err)
         end do
      end associate
      if (.not. allocated(err)) then
         if (final .and. tmp%exists(COUNT_NAME(2:))) then
            call tmp%delete(COUNT_NAME, err)
         else if (.not. final .and. tmp%exists(COUNT_NAME(2:))) then
            call tmp%rewrite(COUNT_NAME, [nkeep], err)
         else if (.not. final) then
            call tmp%write(COUNT_NAME, [nkeep], err)
         end if
      end if
      if (.not. allocated(err) .and. final .and. allocated(self%failed)) &
         call tmp%write_attr('/', 'failed', self%failed, err)
      call tmp%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      if (.not. allocated(err)) call rename_file(path, self%path_h5, err)
      if (allocated(err)) then
         call remove_file(path)
      else if (.not. final) then
         self%capacity = capacity
      end if
      ! the live file again (the old one when the copy failed), unless the run is over
      if (.not. final) then
         call open_live(self, err2)
         if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      end if
   end subroutine rebuild

   !> Every series of the file: nodal vectors, contact flag, element values and their nodal
   !> averages, energies, /time and /step.
   function series_names(self) result(names)
      type(field_writer_t), intent(in) :: self
      character(len=64), allocatable :: names(:)
      integer :: i
      allocate (names(0))
      do i = 1, self%nvec
         names = [character(len=64) :: names, '/fields/'//trim(NODE_VECTORS(i))]
      end do
      names = [character(len=64) :: names, '/fields/contact_active', '/fields/stress', '/fields/nodal_stress']
      do i = 1, max(self%nenergy, 0)
         names = [character(len=64) :: names, '/energies/'//trim(self%energy_names(i))]
      end do
      names = [character(len=64) :: names, '/time', '/step']
   end function series_names

   !> The number of complete output times of the field file `path`: its count `/n_times` while a
   !> run writes it (or after a kill), else the length of `/time` (a finished file).
   subroutine complete_times(path, n, err)
      character(len=*), intent(in) :: path
      integer, intent(out) :: n
      type(error_t), allocatable, intent(out) :: err
      type(hdf5_file_t) :: f
      type(error_t), allocatable :: err2
      integer :: c(1)
      n = 0
      call f%open(path, .false., err)
      if (allocated(err)) return
      if (f%exists(COUNT_NAME(2:))) then
         call f%read(COUNT_NAME, c, err)
         n = c(1)
      else
         call f%series_length('/time', n, err)
      end if
      call f%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
   end subroutine complete_times

   !> True between a successful `open` and `close`.
   logical function writer_is_open(self)
      class(field_writer_t), intent(in) :: self
      writer_is_open = self%h5%is_open()
   end function writer_is_open

   !> Number of output times written.
   pure integer function writer_count(self)
      class(field_writer_t), intent(in) :: self
      writer_count = self%ntime
   end function writer_count

   !> The series XDMF file of the last-state file `path_xdmf`: '<stem>_series.xdmf'.
   function series_path(path_xdmf) result(path)
      character(len=*), intent(in) :: path_xdmf
      character(len=:), allocatable :: path
      integer :: n
      n = len(path_xdmf)
      if (n > 5) then
         if (path_xdmf(n - 4:) == '.xdmf') then
            path = path_xdmf(:n - 5)//'_series.xdmf'
            return
         end if
      end if
      path = path_xdmf//'_series.xdmf'
   end function series_path

   ! ---------------------------------------------------------------------------- checks


   !> Check one output time's arguments against the mesh and the earlier output times.
   subroutine check_step(self, t, u, v, a, sig, fcont, active, energies, energy_names, err)
      class(field_writer_t), intent(in) :: self
      real(wp), intent(in) :: t
      real(wp), intent(in) :: u(:, :), v(:, :), a(:, :), sig(:, :), fcont(:, :)
      integer, intent(in) :: active(:)
      real(wp), intent(in) :: energies(:)
      character(len=*), intent(in) :: energy_names(:)
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: pre
      integer :: i

      pre = 'field output at t = '//real_text(t)//': '
      if (.not. self%h5%is_open()) then
         call make_error(err, pre//'the writer is not open')
      else if (self%broken) then
         call make_error(err, pre//'an earlier output failed half-way; the file takes no more')
      else if (any(shape(u) /= [2, self%nnode]) .or. any(shape(v) /= [2, self%nnode]) .or. &
               any(shape(a) /= [2, self%nnode]) .or. any(shape(fcont) /= [2, self%nnode])) then
         call make_error(err, pre//'u, v, a and contact force must have shape (2, nnode)')
      else if (size(active) /= self%nnode) then
         call make_error(err, pre//'the contact flags must have nnode entries')
      else if (any(shape(sig) /= [self%ncomp, self%nelem])) then
         call make_error(err, pre//'element values must have shape ('//itoa(self%ncomp)//', nelem)')
      else if (.not. (abs(t) <= huge(t))) then
         call make_error(err, pre//'the time is not a finite number')
      else if (self%ntime > 0 .and. .not. (t > self%t_last)) then
         call make_error(err, pre//'output times must increase; the last one was '// &
                         real_text(self%t_last))
      else if (size(energies) /= size(energy_names)) then
         call make_error(err, pre//'energies and energy names differ in number')
      else if (self%nenergy >= 0) then
         if (size(energies) /= self%nenergy) then
            call make_error(err, pre//'the number of energies changed since the first output')
            return
         end if
         do i = 1, self%nenergy
            if (trim(energy_names(i)) /= trim(self%energy_names(i))) then
               call make_error(err, pre//"energy '"//trim(energy_names(i))// &
                               "' is not the one named at the first output ('"// &
                               trim(self%energy_names(i))//"')")
               return
            end if
         end do
      end if
   end subroutine check_step


   ! ---------------------------------------------------------------------------- HDF5 content

   !> Write the /mesh group and the file's identification attributes.
   subroutine write_mesh(h5, x0, conn, region, mat, surf_edges, err)
      type(hdf5_file_t), intent(inout) :: h5
      real(wp), intent(in), contiguous :: x0(:, :)
      integer, intent(in), contiguous :: conn(:, :), region(:), mat(:), surf_edges(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: base0(:, :)

      call h5%write_attr('/', 'format', 'exic fields', err)
      if (.not. allocated(err)) call h5%write_attr('/', 'format_version', 2, err)
      if (.not. allocated(err)) call h5%write_attr('/', 'nnode', size(x0, 2), err)
      if (.not. allocated(err)) call h5%write_attr('/', 'nelem', size(conn, 2), err)
      if (.not. allocated(err)) call h5%write_attr('/', 'units', &
                                                   'consistent units of the input deck', err)
      if (.not. allocated(err)) call h5%create_group('/mesh', err)
      if (.not. allocated(err)) call h5%write('/mesh/coordinates', x0, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/coordinates', 'description', &
                                                   'reference (initial) nodal coordinates x, y', err)
      base0 = conn - 1
      if (.not. allocated(err)) call h5%write('/mesh/connectivity', base0, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/connectivity', 'index_base', 0, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/connectivity', 'description', &
                                                   'quad nodes counterclockwise, 0-based (exic node - 1)', err)
      if (.not. allocated(err)) call h5%write('/mesh/region', region, err)
      if (.not. allocated(err)) call h5%write('/mesh/material', mat, err)
      base0 = surf_edges - 1
      if (.not. allocated(err)) call h5%write('/mesh/contact_edges', base0, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/contact_edges', 'index_base', 0, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/contact_edges', 'description', &
                                                   'node pairs of the contact surface edges, 0-based', err)
   end subroutine write_mesh

   !> Create the empty series /time, /step and /fields/*, the groups /energies and /xdmf, and the
   !> 3-component views /xdmf/<vector> of the nodal vectors (unlimited in time).
   subroutine create_field_series(self, err)
      type(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer :: i, nn, ne
      integer :: none(0)
      character(len=:), allocatable :: f

      nn = self%nnode
      ne = self%nelem
      associate (h5 => self%h5)
         call h5%create_series('/time', DTYPE_REAL, none, err, self%capacity)
         if (.not. allocated(err)) call h5%create_series('/step', DTYPE_INT64, none, err, self%capacity)
         if (.not. allocated(err)) call h5%create_group('/fields', err)
         if (.not. allocated(err)) call h5%create_group('/xdmf', err)
         do i = 1, self%nvec
            if (allocated(err)) return
            f = trim(NODE_VECTORS(i))
            call h5%create_series('/fields/'//f, DTYPE_REAL, [2, nn], err, self%capacity)
            if (.not. allocated(err)) call h5%write_attr('/fields/'//f, 'center', 'node', err)
            if (.not. allocated(err)) call h5%create_series_view('/xdmf/'//f, '/fields/'//f, DTYPE_REAL, &
                                                                  [3, nn], [0, 0], [2, nn], [0, 0], [2, nn], err)
            if (.not. allocated(err)) call h5%write_attr('/xdmf/'//f, 'description', '/fields/'//f// &
                                                         ' with a third (z) component 0, for XDMF readers', err)
         end do
         if (.not. allocated(err)) call h5%create_series('/fields/contact_active', DTYPE_INT, [nn], err, self%capacity)
         if (.not. allocated(err)) call h5%write_attr('/fields/contact_active', 'center', 'node', err)
         if (.not. allocated(err)) call h5%create_series('/fields/stress', DTYPE_REAL, [self%ncomp, ne], err, self%capacity)
         if (.not. allocated(err)) call h5%write_attr('/fields/stress', 'center', 'cell', err)
         if (.not. allocated(err)) call h5%write_attr('/fields/stress', 'components', join(self%comp_names), err)
         if (.not. allocated(err)) call h5%create_series('/fields/nodal_stress', DTYPE_REAL, [self%ncomp, nn], err, &
                                                                 self%capacity)
         if (.not. allocated(err)) call h5%write_attr('/fields/nodal_stress', 'center', 'node', err)
         if (.not. allocated(err)) call h5%write_attr('/fields/nodal_stress', 'components', &
                                                      join(self%comp_names), err)
         if (.not. allocated(err)) call h5%write_attr('/fields/nodal_stress', 'description', &
                                                      'element values averaged at the nodes, weighted by '// &
                                                      'the current element areas', err)
         if (.not. allocated(err)) call h5%create_group('/energies', err)
      end associate
   end subroutine create_field_series

   !> Create the two last-state buffers /last/a and /last/b: plain arrays of one output time.
   subroutine create_last_buffers(self, err)
      type(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      real(wp), allocatable :: zero3(:, :), zero_node(:), zero_cell(:)
      integer, allocatable :: izero(:)
      character(len=:), allocatable :: g
      integer :: b, i

      allocate (zero3(3, self%nnode), zero_node(self%nnode), zero_cell(self%nelem), source=0.0_wp)
      allocate (izero(self%nnode), source=0)
      call self%h5%create_group('/last', err)
      do b = 0, 1
         if (allocated(err)) return
         g = '/last/'//BUFFER(b)
         call self%h5%create_group(g, err)
         if (.not. allocated(err)) call self%h5%write(g//'/output', [-1], err)
         do i = 1, self%nvec
            if (.not. allocated(err)) call self%h5%write(g//'/'//trim(NODE_VECTORS(i)), zero3, err)
         end do
         if (.not. allocated(err)) call self%h5%write(g//'/contact_active', izero, err)
         do i = 1, self%ncomp
            if (.not. allocated(err)) call self%h5%write(g//'/cell_'//trim(self%comp_names(i)), zero_cell, err)
            if (.not. allocated(err)) call self%h5%write(g//'/node_'//trim(self%comp_names(i)), zero_node, err)
         end do
      end do
   end subroutine create_last_buffers

   !> Write the output time (index self%ntime) into buffer b: the vectors padded to 3 components,
   !> the contact flag, each element value component and its nodal average.
   subroutine write_last_buffer(self, b, u, v, a, fcont, active, sig, err)
      type(field_writer_t), intent(inout) :: self
      integer, intent(in) :: b
      real(wp), intent(in) :: u(:, :), v(:, :), a(:, :), fcont(:, :), sig(:, :)
      integer, intent(in), contiguous :: active(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: i, j

      j = self%nvec + 1
      self%vec3(3, :) = 0.0_wp
      self%vec3(1:2, :) = u
      call self%held%write_whole(self%id_last(1, b), self%vec3, err)
      self%vec3(1:2, :) = v
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(2, b), self%vec3, err)
      self%vec3(1:2, :) = a
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(3, b), self%vec3, err)
      self%vec3(1:2, :) = fcont
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(4, b), self%vec3, err)
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(j, b), active, err)
      do i = 1, self%ncomp
         if (allocated(err)) return
         self%col_cell = sig(i, :)
         call self%held%write_whole(self%id_last(j + i, b), self%col_cell, err)
         self%col_node = self%nodal(i, :)
         if (.not. allocated(err)) call self%held%write_whole(self%id_last(j + self%ncomp + i, b), self%col_node, err)
      end do
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(j + 2*self%ncomp + 1, b), self%ntime, err)
   end subroutine write_last_buffer

   !> Create one series /energies/<name> per energy in the file `h5` (the one being made, or a
   !> copy of the live file), with room for self%capacity output times.
   subroutine create_energy_series(self, h5, names, err)
      class(field_writer_t), intent(inout) :: self
      type(hdf5_file_t), intent(inout) :: h5
      character(len=*), intent(in) :: names(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: i, j
      integer :: none(0)

      do i = 1, size(names)
         if (len_trim(names(i)) == 0 .or. index(names(i), '/') > 0 .or. &
             adjustl(names(i)) /= names(i)) then
            call make_error(err, "field output: energy name '"//trim(names(i))// &
                            "' must be non-empty, without '/' or leading blanks")
            return
         end if
         do j = 1, i - 1
            if (trim(names(j)) == trim(names(i))) then
               call make_error(err, "field output: energy name '"//trim(names(i))//"' given twice")
               return
            end if
         end do
      end do
      do i = 1, size(names)
         call h5%create_series('/energies/'//trim(names(i)), DTYPE_REAL, none, err, self%capacity)
         if (.not. allocated(err) .and. i == size(names)) &
            call h5%write_attr('/energies', 'names', join(names), err)
         if (allocated(err)) return
      end do
      if (size(names) == 0) call h5%write_attr('/energies', 'names', '', err)
      if (allocated(err)) return
      self%energy_names = names
      self%nenergy = size(names)
   end subroutine create_energy_series

   ! ---------------------------------------------------------------------------- XDMF text

   !> The series file up to its first grid.
   function series_head() result(s)
      character(len=:), allocatable :: s
      s = '<?xml version="1.0" ?>'//NL// &
          '<!-- exic field output: every output time, for the Xdmf3 readers of ParaView. The last'//NL// &
          '     time alone, for every reader (meshio too), is in the .xdmf file without _series.'//NL// &
          '     Blank space before the closing tags is room for the next output times. -->'//NL// &
          '<Xdmf Version="3.0">'//NL// &
          '  <Domain>'//NL// &
          '    <Grid Name="exic" GridType="Collection" CollectionType="Temporal">'//NL
   end function series_head

   !> The series file after its last grid.
   function series_tail() result(s)
      character(len=:), allocatable :: s
      s = '    </Grid>'//NL//'  </Domain>'//NL//'</Xdmf>'//NL
   end function series_tail

   !> Topology and geometry (the reference mesh) of a grid.
   function mesh_items(self) result(s)
      type(field_writer_t), intent(in) :: self
      character(len=:), allocatable :: s
      character(len=:), allocatable :: f
      f = self%h5_ref//':'
      s = '        <Topology TopologyType="Quadrilateral" NumberOfElements="'//itoa(self%nelem)//'">'//NL// &
          data_item(itoa(self%nelem)//' 4', 'Int', '4', f//'/mesh/connectivity')// &
          '        </Topology>'//NL// &
          '        <Geometry GeometryType="XY">'//NL// &
          data_item(itoa(self%nnode)//' 2', 'Float', '8', f//'/mesh/coordinates')// &
          '        </Geometry>'//NL
   end function mesh_items

   !> Region and material of every element.
   function static_attributes(self) result(s)
      type(field_writer_t), intent(in) :: self
      character(len=:), allocatable :: s
      character(len=:), allocatable :: f
      f = self%h5_ref//':'
      s = attribute('region', 'Scalar', 'Cell', data_item(itoa(self%nelem), 'Int', '4', f//'/mesh/region'))// &
          attribute('material', 'Scalar', 'Cell', data_item(itoa(self%nelem), 'Int', '4', f//'/mesh/material'))
   end function static_attributes

   !> The grid of output k (0-based) at time t in the series file: slab k of the datasets, in
   !> Xdmf3's form "file:/dataset|start:stride:count:dims" (C order, time first). Indented for
   !> the four blanks exic_io_xdmf puts before it, without a final newline.
   function series_grid(self, k, t) result(s)
      type(field_writer_t), intent(in) :: self
      integer, intent(in) :: k
      real(wp), intent(in) :: t
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nn, ne, nc
      integer :: i

      nn = itoa(self%nnode)
      ne = itoa(self%nelem)
      nc = itoa(self%ncomp)
      s = '  <Grid Name="t'//six_digits(k)//'" GridType="Uniform">'//NL// &
          '        <Time Value="'//real_text(t)//'"/>'//NL//mesh_items(self)
      do i = 1, self%nvec
         s = s//attribute(trim(NODE_VECTORS(i)), 'Vector', 'Node', data_item(nn//' 3', 'Float', '8', &
                          slab(self, '/xdmf/'//trim(NODE_VECTORS(i)), k, '0 0', '1 1', nn//' 3', nn//' 3')))
      end do
      s = s//attribute('contact_active', 'Scalar', 'Node', data_item(nn, 'Int', '4', &
                       slab(self, '/fields/contact_active', k, '0', '1', nn, nn)))
      do i = 1, self%ncomp
         s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Cell', data_item(ne, 'Float', '8', &
                          slab(self, '/fields/stress', k, '0 '//itoa(i - 1), '1 1', ne//' 1', ne//' '//nc)))
      end do
      do i = 1, self%ncomp
         s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Node', data_item(nn, 'Float', '8', &
                          slab(self, '/fields/nodal_stress', k, '0 '//itoa(i - 1), '1 1', nn//' 1', nn//' '//nc)))
      end do
      s = s//static_attributes(self)//'      </Grid>'
   end function series_grid

   !> "file:dataset|k start:1 stride:1 count:k+1 dims": slab k of a series, C order.
   function slab(self, dataset, k, start, stride, count, dims) result(s)
      type(field_writer_t), intent(in) :: self
      character(len=*), intent(in) :: dataset, start, stride, count, dims
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      s = self%h5_ref//':'//dataset//'|'//itoa(k)//' '//start//':1 '//stride//':1 '//count//':'// &
          itoa(k + 1)//' '//dims
   end function slab

   !> The last-state file: output k (0-based; -1 before the first: the mesh alone) at time t,
   !> solver step `step`, held in buffer b; plain datasets only, one Uniform grid, no Time element
   !> (meshio.read accepts exactly this).
   function last_document(self, b, t, step) result(s)
      type(field_writer_t), intent(in) :: self
      integer, intent(in) :: b
      real(wp), intent(in) :: t
      integer(i8), intent(in) :: step
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nn, ne, g, name
      integer :: i

      nn = itoa(self%nnode)
      ne = itoa(self%nelem)
      if (b < 0) then
         name = 'exic mesh (no output time yet)'
      else
         name = 'exic t = '//real_text(t)//', step '//step_text(step)//', output '//itoa(self%ntime - 1)
      end if
      s = '<?xml version="1.0" ?>'//NL// &
          '<!-- exic field output: the last output time (every one: the _series.xdmf file) -->'//NL// &
          '<Xdmf Version="3.0">'//NL//'  <Domain>'//NL// &
          '    <Grid Name="'//name//'" GridType="Uniform">'//NL//mesh_items(self)
      if (b >= 0) then
         g = self%h5_ref//':/last/'//BUFFER(b)//'/'
         do i = 1, self%nvec
            s = s//attribute(trim(NODE_VECTORS(i)), 'Vector', 'Node', &
                             data_item(nn//' 3', 'Float', '8', g//trim(NODE_VECTORS(i))))
         end do
         s = s//attribute('contact_active', 'Scalar', 'Node', data_item(nn, 'Int', '4', g//'contact_active'))
         do i = 1, self%ncomp
            s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Cell', &
                             data_item(ne, 'Float', '8', g//'cell_'//trim(self%comp_names(i))))
         end do
         do i = 1, self%ncomp
            s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Node', &
                             data_item(nn, 'Float', '8', g//'node_'//trim(self%comp_names(i))))
         end do
      end if
      s = s//static_attributes(self)//'    </Grid>'//NL//'  </Domain>'//NL//'</Xdmf>'//NL
   end function last_document

   !> A 64-bit step number as text.
   function step_text(step) result(s)
      integer(i8), intent(in) :: step
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') step
      s = trim(buf)
   end function step_text

   !> k with six digits at least.
   function six_digits(k) result(name)
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      character(len=16) :: buf
      write (buf, '(i6.6)') k
      if (k >= 1000000) write (buf, '(i0)') k
      name = trim(buf)
   end function six_digits

   !> How the XDMF files name the .h5 file: its base name when both share a directory, else the
   !> absolute path. XDMF separates file and dataset by ':' and Xdmf3 a selection by '|': the name has neither.
   subroutine xdmf_reference(path_h5, path_xdmf, ref, err)
      character(len=*), intent(in) :: path_h5, path_xdmf
      character(len=:), allocatable, intent(out) :: ref
      type(error_t), allocatable, intent(out) :: err
      integer :: i5, ix

      i5 = index(path_h5, '/', back=.true.)
      ix = index(path_xdmf, '/', back=.true.)
      if (path_h5(1:i5) == path_xdmf(1:ix)) then
         ref = path_h5(i5 + 1:)
      else if (path_h5(1:1) == '/') then
         ref = path_h5
      else
         call make_error(err, "field output: '"//path_h5//"' and '"//path_xdmf// &
                         "' must be in one directory (or give the .h5 path absolute)")
         return
      end if
      if (scan(ref, ':|') > 0 .or. len(ref) == 0) then
         call make_error(err, "field output: the HDF5 file name '"//ref// &
                         "' must be non-empty and contain no ':' or '|'")
      end if
   end subroutine xdmf_reference

   !> Names joined by single blanks.
   function join(names) result(s)
      character(len=*), intent(in) :: names(:)
      character(len=:), allocatable :: s
      integer :: i
      s = ''
      do i = 1, size(names)
         if (i > 1) s = s//' '
         s = s//trim(names(i))
      end do
   end function join

end module exic_io_fields
