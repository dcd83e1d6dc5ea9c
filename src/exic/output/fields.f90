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
!> output times, chunks allocated early and never filled, the buffers, the count `/n_times`),
!> renamed, and opened write-through; an output time writes raw data only, through dataset
!> handles held open (exic_hdf5_held), the count last, then flushes. Growth, restart and the
!> final cut to the times written (needed only when the run did not fill its room exactly, or
!> failed) are a copy of the file changed and renamed over it.
!> Only then are the XDMF files updated: the series is appended to in place by writes each of
!> which leaves a well-formed document (exic_output_fields_xdmf), the last-state file is written to a
!> temporary name and renamed. A run killed at any moment leaves an HDF5 file whose count names
!> its complete output times and XDMF files that parse and name only those.
module exic_output_fields
   use exic_base_kinds, only: wp, i8
   use exic_base_flat, only: copy_flat, sum_flat
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   use exic_mesh_smoothing, only: nodal_average
   use exic_hdf5_file, only: hdf5_file_t, DTYPE_REAL, DTYPE_INT, DTYPE_INT64
   use exic_hdf5_held, only: hdf5_held_t
   use exic_output_fields_checks, only: check_mesh, check_names
   use exic_output_fields_nodes, only: write_node_id
   use exic_base_posix, only: rename_file, copy_file, remove_file
   use exic_base_clock, only: wall_time
   use exic_output_fields_xdmf, only: xdmf_series_t, write_whole_file, xml_escape, real_text
   use exic_output_fields_text, only: fields_text_t, NODE_VECTORS, BUFFER, series_path, xdmf_reference
   implicit none
   private

   public :: field_writer_t, STRESS_NAMES, NODE_VECTORS, series_path

   !> Names of the seven stress components (TPLOt order: 1 sxx, 2 syy, 3 szz, 4 sxy,
   !> 5 pressure, 6 von Mises, 7 J): the default element values, in `/fields/stress`.
   character(len=9), parameter :: STRESS_NAMES(7) = [character(len=9) :: 'sxx', 'syy', 'szz', &
                                                     'sxy', 'pressure', 'von_mises', 'J']
   !> Output times kept in memory before they are written (doc/fields.md, "Batches"): at most
   !> BATCH_BYTES of them, and none longer than BATCH_SECONDS of wall time.
   integer(i8), parameter :: BATCH_BYTES = 4_i8*1024*1024
   real(wp), parameter :: BATCH_SECONDS = 1.0_wp
   !> The most blank space the series XDMF file is made with (it regrows beyond).
   integer(i8), parameter :: SERIES_RESERVE_MAX = 16_i8*1024*1024

   !> Output times preallocated when the caller gives no estimate, and the most bytes a
   !> preallocation made from an estimate may take (growth takes over beyond it).
   integer, parameter :: START_CAPACITY = 16
   integer(i8), parameter :: ESTIMATE_BYTES_MAX = 256_i8*1024*1024
   !> The count of complete output times (in a finished file, the length of every series).
   character(len=*), parameter :: COUNT_NAME = '/n_times'

   !> Writer of one field output (`.h5`, `.xdmf`, `_series.xdmf`).
   type :: field_writer_t
      private
      type(hdf5_file_t) :: h5
      type(hdf5_held_t) :: held                     !< the datasets an output time writes
      type(xdmf_series_t) :: series                 !< <stem>_series.xdmf
      type(fields_text_t) :: text                   !< the XDMF text (series grid template)
      character(len=:), allocatable :: last_path    !< <stem>.xdmf
      integer :: nnode = 0, nelem = 0
      integer :: nvec = 4                           !< nodal vectors written (5: with friction_force)
      integer :: ncomp = 0                          !< element value components
      character(len=16), allocatable :: comp_names(:)
      real(wp), allocatable :: x0(:, :)             !< reference coordinates (2, nnode)
      integer, allocatable :: conn(:, :)            !< connectivity (4, nelem), 1-based
      real(wp), allocatable :: x(:, :), vec3(:, :), col_cell(:), col_node(:)
      integer :: ntime = 0                          !< output times written so far (taken)
      !> the batch: output times ntime-npend .. ntime-1 taken but not yet in the file, slot j
      !> of each array holding output time ntime-npend+j-1
      integer :: npend = 0, nbatch = 1              !< pending output times, room for them
      integer(i8) :: batch_bytes = BATCH_BYTES      !< the batch's bounds (`set_batch`)
      real(wp) :: batch_seconds = BATCH_SECONDS
      real(wp) :: wall_first = 0.0_wp               !< wall time the oldest pending one was taken
      real(wp), allocatable :: bvec(:, :, :, :)     !< (2, nnode, nbatch, nvec)
      integer, allocatable :: bact(:, :)            !< (nnode, nbatch)
      real(wp), allocatable :: bsig(:, :, :), bnod(:, :, :)   !< (ncomp, nelem | nnode, nbatch)
      real(wp), allocatable :: ben(:, :), btime(:)  !< (nbatch, nenergy), (nbatch)
      integer(i8), allocatable :: bstep(:)
      integer :: named = -1                         !< the output time <stem>.xdmf names (-1: none)
      real(wp) :: t_flushed = 0.0_wp                !< time of the last output time flushed
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
      procedure :: flushed => writer_flushed
      procedure :: last_flushed_time => writer_last_flushed_time
      procedure :: flush => writer_flush
      procedure :: flush_stale => writer_flush_stale
      procedure :: set_batch => writer_set_batch
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
   !> the file each time the room doubles). `node_id`: the deck number of each node, when the
   !> nodes written are not the numbers 1..nnode (exic_output_fields_nodes).
   subroutine writer_open(self, path_h5, path_xdmf, nnode, nelem, x0, conn, region, mat, &
                          surf_edges, err, cell_names, energy_names, friction, capacity, node_id)
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
      integer, intent(in), optional, contiguous :: node_id(:)
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
      if (present(node_id)) then
         if (size(node_id) /= nnode) then
            call make_error(err, "field output '"//path_h5//"': node_id must have nnode entries")
            return
         end if
      end if
      call prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction, present(node_id))
      if (allocated(err)) return

      self%capacity = initial_capacity(self, capacity, energy_names)
      ! made whole under a temporary name, closed and renamed: a run killed while the file is
      ! being created leaves no .h5 rather than a broken one. Every dataset the run writes
      ! exists after this, with room for `capacity` output times (doc/fields.md, "Kill safety")
      call self%h5%create(path_h5//'.tmp', err)
      if (allocated(err)) return
      call write_mesh(self%h5, x0, conn, region, mat, surf_edges, err)
      if (.not. allocated(err) .and. present(node_id)) call write_node_id(self%h5, node_id, err)
      if (.not. allocated(err)) call create_field_series(self, err)
      if (.not. allocated(err)) call create_last_buffers(self, err)
      if (.not. allocated(err) .and. present(energy_names)) &
         call create_energy_series(self, self%h5, energy_names, err)
      if (.not. allocated(err)) call self%h5%write(COUNT_NAME, [0], err)
      if (.not. allocated(err)) call close_live(self, err)
      if (.not. allocated(err)) call rename_file(path_h5//'.tmp', path_h5, err)
      if (.not. allocated(err)) call open_live(self, err)
      if (.not. allocated(err)) call self%series%create(series_path(path_xdmf), self%text%series_head(), &
                                                        self%text%series_tail(), err, series_reserve(self))
      if (.not. allocated(err)) call write_whole_file(self%last_path, self%text%last_document(-1, -1, 0.0_wp, &
                                                                                              0_i8), err)
      if (.not. allocated(err)) call allocate_batch(self)
      if (allocated(err)) then
         call self%series%abandon()
         call close_live(self, err2)
         call remove_file(path_h5//'.tmp')     ! a file that could not be made whole
      end if
   end subroutine writer_open

   !> The writer's set-up for a mesh (names, sizes, work arrays), before its files are made.
   subroutine prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction, node_id)
      type(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path_h5, path_xdmf
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in) :: x0(:, :)
      integer, intent(in) :: conn(:, :)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: friction
      logical, intent(in) :: node_id                !< the file has /mesh/node_id
      character(len=:), allocatable :: ref
      call xdmf_reference(path_h5, path_xdmf, ref, err)
      if (allocated(err)) return
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
      call self%text%init(xml_escape(ref, dash=.true.), nnode, nelem, self%nvec, self%comp_names, node_id)
      self%x0 = x0
      self%conn = conn
      if (allocated(self%x)) deallocate (self%x, self%vec3, self%col_cell, self%col_node)
      allocate (self%x(2, nnode), self%vec3(3, nnode), self%col_cell(nelem), self%col_node(nnode))
      self%ntime = 0
      self%npend = 0
      self%named = -1
      self%t_flushed = 0.0_wp
      self%batch_bytes = BATCH_BYTES
      self%batch_seconds = BATCH_SECONDS
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
   !> file is rewritten at the next output time. `node_id`: as given to `open`.
   subroutine writer_reopen(self, path_h5, path_xdmf, nnode, nelem, x0, conn, ntime, energy_names, err, &
                            cell_names, friction, capacity, node_id)
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
      integer, intent(in), optional, contiguous :: node_id(:)
      type(error_t), allocatable :: err2
      real(wp), allocatable :: times(:)
      integer(i8), allocatable :: steps(:)
      integer :: i, held

      if (present(cell_names)) then
         self%comp_names = cell_names
      else
         self%comp_names = STRESS_NAMES
      end if
      call prepare(self, path_h5, path_xdmf, nnode, nelem, x0, conn, err, friction, present(node_id))
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
      if (.not. allocated(err)) call self%series%create(series_path(path_xdmf), self%text%series_head(), &
                                                        self%text%series_tail(), err, series_reserve(self))
      do i = 1, ntime
         if (allocated(err)) exit
         self%ntime = i
         self%t_last = times(i)
         call self%series%append(self%text%series_grid(i - 1, times(i)), err)
      end do
      if (ntime > 0) self%t_flushed = self%t_last
      if (.not. allocated(err)) call allocate_batch(self)
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
      integer :: j

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
         ! the energy series are added by a copy of the file, like a growth (first output time:
         ! nothing is pending)
         self%energy_names = energy_names
         call rebuild(self, self%ntime, self%capacity, .false., err, new_energies=.true.)
         if (allocated(err)) then
            self%broken = .true.
            return
         end if
         self%nenergy = size(energy_names)
         call allocate_batch(self)
      end if
      if (self%ntime == self%capacity) then
         ! the room is full: what is pending goes in first, then the room doubles
         call writer_flush(self, err)
         if (.not. allocated(err)) call rebuild(self, self%ntime, 2*max(self%capacity, 1), .false., err)
         if (allocated(err)) then
            self%broken = .true.
            err%message = 'field output at t = '//real_text(t)//': '//err%message
            return
         end if
      end if
      ! the output time into the next slot of the batch; the nodal averages of the element values
      ! over the current configuration
      j = self%npend + 1
      call copy_flat(2*self%nnode, u, self%bvec(:, :, j, 1))
      call copy_flat(2*self%nnode, v, self%bvec(:, :, j, 2))
      call copy_flat(2*self%nnode, a, self%bvec(:, :, j, 3))
      call copy_flat(2*self%nnode, fcont, self%bvec(:, :, j, 4))
      if (self%nvec == 5) call copy_flat(2*self%nnode, ffric, self%bvec(:, :, j, 5))
      self%bact(:, j) = active
      call copy_flat(self%ncomp*self%nelem, sig, self%bsig(:, :, j))
      call sum_flat(2*self%nnode, self%x0, u, self%x)
      call nodal_average(self%ncomp, self%nnode, self%nelem, self%conn, self%x, sig, self%bnod(:, :, j))
      self%ben(j, :) = energies
      self%btime(j) = t
      self%bstep(j) = step
      self%npend = j
      self%ntime = self%ntime + 1
      self%t_last = t
      if (j == 1) self%wall_first = wall_time()
      if (j == self%nbatch) then
         call writer_flush(self, err)
      else
         call writer_flush_stale(self, err)
      end if
   end subroutine writer_write_step

   !> Write the pending output times into the .h5 (doc/fields.md, "Batches" and "Kill safety"):
   !> one H5Dwrite per series for all of them (consecutive slabs), the last-state buffers of the
   !> last two, the count `/n_times`, the flush; then the series XDMF grids and the last-state
   !> file. Nothing to do when nothing is pending.
   subroutine writer_flush(self, err)
      class(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer :: i, k0, m, kk
      logical :: same

      if (self%npend == 0) return
      if (self%broken) then
         call make_error(err, 'field output: an earlier output failed half-way; the file takes no more')
         return
      end if
      m = self%npend
      k0 = self%ntime - m
      kk = self%ntime - 1
      do i = 1, self%nvec
         if (allocated(err)) exit
         call self%held%write_slabs(self%id_vec(i), k0, self%bvec(:, :, 1:m, i), err)
      end do
      if (.not. allocated(err)) call self%held%write_slabs(self%id_active, k0, self%bact(:, 1:m), err)
      if (.not. allocated(err)) call self%held%write_slabs(self%id_stress, k0, self%bsig(:, :, 1:m), err)
      if (.not. allocated(err)) call self%held%write_slabs(self%id_nodal, k0, self%bnod(:, :, 1:m), err)
      do i = 1, self%nenergy
         if (allocated(err)) exit
         call self%held%write_slabs(self%id_energy(i), k0, self%ben(1:m, i), err)
      end do
      if (.not. allocated(err)) call self%held%write_slabs(self%id_time, k0, self%btime(1:m), err)
      if (.not. allocated(err)) call self%held%write_slabs(self%id_step, k0, self%bstep(1:m), err)
      ! the buffers end holding output kk in buffer mod(kk, 2) and kk - 1 in the other, whatever
      ! the batches were; the one <stem>.xdmf names is never written (doc/fields.md)
      same = m >= 2 .and. self%named >= 0 .and. mod(kk, 2) == mod(max(self%named, 0), 2)
      if (same) then
         if (.not. allocated(err)) call write_last_buffer(self, kk - 1, m - 1, err)
      else
         if (.not. allocated(err)) call write_last_buffer(self, kk, m, err)
      end if
      ! the count last: it says how many slabs hold a complete output time
      if (.not. allocated(err)) call self%held%write_whole(self%id_count, self%ntime, err)
      if (.not. allocated(err)) call self%h5%flush(err)
      ! only now, with the HDF5 file complete on disk, do the XDMF files name these times
      if (.not. allocated(err)) call self%series%append(series_grids(self, k0, m), err)
      if (same) then
         if (.not. allocated(err)) call name_last(self, kk - 1, m - 1, err)
         if (.not. allocated(err)) call write_last_buffer(self, kk, m, err)
         if (.not. allocated(err)) call name_last(self, kk, m, err)
      else
         if (.not. allocated(err)) call name_last(self, kk, m, err)
         if (.not. allocated(err) .and. m >= 2) call write_last_buffer(self, kk - 1, m - 1, err)
      end if
      if (allocated(err)) then
         self%broken = .true.
         err%message = 'field output at t = '//real_text(self%btime(m))//': '//err%message
         return
      end if
      self%t_flushed = self%btime(m)
      self%npend = 0
   end subroutine writer_flush

   !> Flush when the oldest pending output time was taken BATCH_SECONDS (`set_batch`) of wall
   !> time ago or more, so that a process killed loses no more than that; called at every output
   !> time and between steps.
   subroutine writer_flush_stale(self, err)
      class(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      if (self%npend == 0) return
      if (wall_time() - self%wall_first >= self%batch_seconds) call writer_flush(self, err)
   end subroutine writer_flush_stale

   !> Bounds of the batch of the open file: at most `max_bytes` of output times (at least one)
   !> and none kept longer than `max_seconds` of wall time (`open` sets BATCH_BYTES and
   !> BATCH_SECONDS). Pending output times are flushed first.
   subroutine writer_set_batch(self, max_bytes, max_seconds, err)
      class(field_writer_t), intent(inout) :: self
      integer(i8), intent(in) :: max_bytes
      real(wp), intent(in) :: max_seconds
      type(error_t), allocatable, intent(out) :: err
      call writer_flush(self, err)
      if (allocated(err)) return
      self%batch_bytes = max_bytes
      self%batch_seconds = max_seconds
      if (self%h5%is_open()) call allocate_batch(self)
   end subroutine writer_set_batch

   !> The series grids of output times k0 .. k0+m-1 as one text, as m appends would leave them
   !> (each grid once into a text of the final length: no repeated concatenation).
   function series_grids(self, k0, m) result(s)
      type(field_writer_t), intent(in) :: self
      integer, intent(in) :: k0, m
      character(len=:), allocatable :: s
      character(len=*), parameter :: SEP = '  '//achar(10)//'    '
      type :: text_t
         character(len=:), allocatable :: c
      end type text_t
      type(text_t) :: g(m)
      integer :: j, n, at
      n = 0
      do j = 1, m
         g(j)%c = self%text%series_grid(k0 + j - 1, self%btime(j))
         n = n + len(g(j)%c)
      end do
      allocate (character(len=n + (m - 1)*len(SEP)) :: s)
      at = 0
      do j = 1, m
         if (j > 1) then
            s(at + 1:at + len(SEP)) = SEP
            at = at + len(SEP)
         end if
         s(at + 1:at + len(g(j)%c)) = g(j)%c
         at = at + len(g(j)%c)
      end do
   end function series_grids

   !> <stem>.xdmf names output k, batch slot j, in its buffer mod(k, 2).
   subroutine name_last(self, k, j, err)
      type(field_writer_t), intent(inout) :: self
      integer, intent(in) :: k, j
      type(error_t), allocatable, intent(out) :: err
      call write_whole_file(self%last_path, self%text%last_document(mod(k, 2), k, self%btime(j), &
                                                                     self%bstep(j)), err)
      if (.not. allocated(err)) self%named = k
   end subroutine name_last

   !> The reserve of the series XDMF file for the output times the room holds (the grids of a
   !> run that keeps to its estimate then never make the file regrow), at most SERIES_RESERVE_MAX.
   integer(i8) function series_reserve(self) result(r)
      type(field_writer_t), intent(in) :: self
      r = int(self%capacity, i8)*(len(self%text%series_grid(self%capacity, 0.0_wp), i8) + 8_i8)
      r = min(r, SERIES_RESERVE_MAX)
   end function series_reserve

   !> The batch's arrays, room for as many output times as `batch_bytes` holds (at least one, at
   !> most the file's room).
   subroutine allocate_batch(self)
      type(field_writer_t), intent(inout) :: self
      integer(i8) :: per_time
      per_time = 8_i8*(2_i8*self%nvec*self%nnode + int(self%ncomp, i8)*(self%nelem + self%nnode) + &
                       max(self%nenergy, 0) + 2) + 4_i8*self%nnode
      ! never more than the room: a full room is flushed before it grows
      self%nbatch = int(max(1_i8, min(int(max(self%capacity, 1), i8), self%batch_bytes/per_time)))
      if (allocated(self%bvec)) deallocate (self%bvec, self%bact, self%bsig, self%bnod, self%ben, &
                                            self%btime, self%bstep)
      allocate (self%bvec(2, self%nnode, self%nbatch, self%nvec), self%bact(self%nnode, self%nbatch), &
                self%bsig(self%ncomp, self%nelem, self%nbatch), self%bnod(self%ncomp, self%nnode, self%nbatch), &
                self%ben(self%nbatch, max(self%nenergy, 0)), self%btime(self%nbatch), self%bstep(self%nbatch))
      self%npend = 0
   end subroutine allocate_batch

   !> Close the .h5 file and cut it to the output times written (a copy renamed over it, which
   !> also stores the message of `mark_failed`; not needed when the output times filled the
   !> room exactly and the run did not fail: the file is then finished as it is), then write
   !> the series file once more without its reserve (the last-state file is complete already).
   !> Every file is closed even when one step fails; the first failure is returned (the .h5 is
   !> then left as a killed run leaves it). No-op when not open.
   subroutine writer_close(self, err)
      class(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: err2
      if (.not. self%h5%is_open()) return
      call writer_flush(self, err)
      ! a room the run filled exactly is the finished file as it is: no cut, no copy
      if (.not. allocated(err) .and. (self%ntime /= self%capacity .or. allocated(self%failed))) &
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
   !> room for `capacity`; the count is set to `nkeep` (made when missing: a file from before
   !> the count was kept). `final`: the finished file instead (no room, the `failed` attribute
   !> when the run failed), not opened again. `new_energies`: also create the energy series of
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
         if (tmp%exists(COUNT_NAME(2:))) then
            call tmp%rewrite(COUNT_NAME, [nkeep], err)
         else
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

   !> The number of complete output times of the field file `path`: its count `/n_times`, or
   !> the length of `/time` in a file without the count (finished before the count was kept).
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

   !> Number of output times written (taken: some may still be pending in the batch).
   pure integer function writer_count(self)
      class(field_writer_t), intent(in) :: self
      writer_count = self%ntime
   end function writer_count

   !> Time of the last output time complete in the .h5 file (0 before the first).
   pure real(wp) function writer_last_flushed_time(self) result(t)
      class(field_writer_t), intent(in) :: self
      t = self%t_flushed
   end function writer_last_flushed_time

   !> Number of output times complete in the .h5 file and named by the XDMF files.
   pure integer function writer_flushed(self)
      class(field_writer_t), intent(in) :: self
      writer_flushed = self%ntime - self%npend
   end function writer_flushed

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

   !> Write output time k, held in slot j of the batch, into its buffer mod(k, 2): the vectors
   !> padded to 3 components, the contact flag, each element value component and its nodal
   !> average, and k itself.
   subroutine write_last_buffer(self, k, j, err)
      type(field_writer_t), intent(inout) :: self
      integer, intent(in) :: k, j
      type(error_t), allocatable, intent(out) :: err
      integer :: i, n, b

      b = mod(k, 2)
      n = self%nvec + 1
      self%vec3(3, :) = 0.0_wp
      do i = 1, self%nvec
         if (allocated(err)) return
         self%vec3(1:2, :) = self%bvec(:, :, j, i)
         call self%held%write_whole(self%id_last(i, b), self%vec3, err)
      end do
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(n, b), self%bact(:, j), err)
      do i = 1, self%ncomp
         if (allocated(err)) return
         self%col_cell = self%bsig(i, :, j)
         call self%held%write_whole(self%id_last(n + i, b), self%col_cell, err)
         self%col_node = self%bnod(i, :, j)
         if (.not. allocated(err)) call self%held%write_whole(self%id_last(n + self%ncomp + i, b), self%col_node, err)
      end do
      if (.not. allocated(err)) call self%held%write_whole(self%id_last(n + 2*self%ncomp + 1, b), k, err)
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

end module exic_output_fields
