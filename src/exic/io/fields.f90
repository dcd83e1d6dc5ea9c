!> Full-field output: `<stem>.h5` (HDF5) described by `<stem>.xdmf` (XDMF 3) for ParaView and meshio.
!>
!> The mesh is written once; each output time appends one slab to the extendible datasets under
!> `/fields` (Fortran shape (component, entity, time); h5py shape (time, entity, component)),
!> to `/energies/<name>`, then to `/time` and `/step`, and adds a group `/xdmf/NNNNNN` of virtual
!> datasets that show that slab as plain (entity, component) arrays (nodal vectors padded to 3
!> components, one cell scalar per stress component). The XDMF file points at those views, so
!> every XDMF reader, including those that cannot address hyperslabs, reads them directly.
!>
!> Kill safety: after every output time the HDF5 file is flushed (H5Fflush: data, metadata and
!> superblock on disk) and only then is the XDMF file rewritten, to a temporary name renamed over
!> the old one, so a run killed at any moment leaves an HDF5 file readable up to its last flushed
!> output time and an XDMF file that is complete and lists only flushed times. The default
!> (version 0) superblock has no "file open" flag, so no repair step is needed after a kill.
!> The layout is documented in doc/fields.md.
module exic_io_fields
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   use exic_io_hdf5_file, only: hdf5_file_t, DTYPE_REAL, DTYPE_INT, DTYPE_INT64
   use exic_io_posix, only: rename_file
   implicit none
   private

   public :: field_writer_t, STRESS_NAMES, NODE_VECTORS

   !> Names of the seven stress components (TPLOt order: 1 sxx, 2 syy, 3 szz, 4 sxy,
   !> 5 pressure, 6 von Mises, 7 J), as they appear in the XDMF file and in `/fields/stress`.
   character(len=9), parameter :: STRESS_NAMES(7) = [character(len=9) :: 'sxx', 'syy', 'szz', &
                                                     'sxy', 'pressure', 'von_mises', 'J']
   !> Names of the nodal vector fields, datasets `/fields/<name>`; the last, the nodal friction
   !> force (doc/friction.md), only when the run has friction (`nvec`).
   character(len=14), parameter :: NODE_VECTORS(5) = [character(len=14) :: 'displacement', &
                                                      'velocity', 'acceleration', 'contact_force', &
                                                      'friction_force']

   character(len=*), parameter :: NL = achar(10)

   !> Writer of one field output file pair (`.h5` + `.xdmf`).
   type :: field_writer_t
      private
      type(hdf5_file_t) :: h5
      character(len=:), allocatable :: xdmf_path   !< the .xdmf file
      character(len=:), allocatable :: h5_ref      !< the .h5 file as the .xdmf names it
      integer :: nnode = 0, nelem = 0
      integer :: nvec = 4                           !< nodal vectors written (5: with friction_force)
      integer :: ntime = 0                          !< output times written so far
      real(wp) :: t_last = 0.0_wp
      integer :: nenergy = -1                       !< -1 until the first write_step
      character(len=:), allocatable :: energy_names(:)
      character(len=:), allocatable :: grids        !< XDMF text of every grid written so far
      integer :: grids_len = 0
      logical :: broken = .false.                   !< an HDF5 write failed half-way
   contains
      procedure :: open => writer_open
      procedure :: write_step => writer_write_step
      procedure :: close => writer_close
      procedure :: is_open => writer_is_open
      procedure :: count => writer_count
   end type field_writer_t

contains

   !> Create `path_h5` and `path_xdmf` and write the mesh: reference coordinates x0(2, nnode),
   !> connectivity conn(4, nelem) (1-based here; stored 0-based), region and material numbers
   !> per element, and the contact edges surf_edges(2, nedge) (node pairs, 1-based; may be empty).
   !> Both files must be in one directory unless `path_h5` is absolute. `friction`: the run has
   !> friction; every output time then also holds the nodal friction force.
   subroutine writer_open(self, path_h5, path_xdmf, nnode, nelem, x0, conn, region, mat, &
                          surf_edges, err, friction)
      class(field_writer_t), intent(inout) :: self
      character(len=*), intent(in) :: path_h5, path_xdmf
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in), contiguous :: x0(:, :)
      integer, intent(in), contiguous :: conn(:, :), region(:), mat(:), surf_edges(:, :)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: friction
      type(error_t), allocatable :: err2

      if (self%h5%is_open()) then
         call make_error(err, "field output: cannot open '"//path_h5//"': the writer already has '"// &
                         self%h5%name()//"' open")
         return
      end if
      call check_mesh(nnode, nelem, x0, conn, region, mat, surf_edges, path_h5, err)
      if (allocated(err)) return
      call xdmf_reference(path_h5, path_xdmf, self%h5_ref, err)
      if (allocated(err)) return

      self%xdmf_path = path_xdmf
      self%nnode = nnode
      self%nelem = nelem
      self%nvec = 4
      if (present(friction)) then
         if (friction) self%nvec = 5
      end if
      self%ntime = 0
      self%t_last = 0.0_wp
      self%nenergy = -1
      self%grids_len = 0
      self%broken = .false.
      if (allocated(self%energy_names)) deallocate (self%energy_names)

      call self%h5%create(path_h5, err)
      if (allocated(err)) return
      call write_mesh(self%h5, x0, conn, region, mat, surf_edges, err)
      if (.not. allocated(err)) call create_field_series(self%h5, nnode, nelem, self%nvec, err)
      if (.not. allocated(err)) call self%h5%flush(err)
      if (.not. allocated(err)) call write_xdmf(self, err)
      if (allocated(err)) call self%h5%close(err2)
   end subroutine writer_open

   !> Append one output time t (solver step `step`): nodal displacement u, velocity v,
   !> acceleration a and contact force fcont, each (2, nnode); the contact flag active(nnode)
   !> (1 where a node carries an active constraint); the stress sig(7, nelem) (sxx, syy, szz,
   !> sxy, pressure, von Mises, J); and the energies with their names (the same names, in the
   !> same order, at every call); ffric(2, nnode), the nodal friction force, when the writer was
   !> opened with friction. Flushes the .h5 file, then rewrites the .xdmf file.
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
      integer :: i

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
         call create_energy_series(self, energy_names, err)
         if (allocated(err)) return
      end if

      call self%h5%append('/fields/displacement', u, err)
      if (.not. allocated(err)) call self%h5%append('/fields/velocity', v, err)
      if (.not. allocated(err)) call self%h5%append('/fields/acceleration', a, err)
      if (.not. allocated(err)) call self%h5%append('/fields/contact_force', fcont, err)
      if (.not. allocated(err) .and. self%nvec == 5) call self%h5%append('/fields/friction_force', ffric, err)
      if (.not. allocated(err)) call self%h5%append('/fields/contact_active', active, err)
      if (.not. allocated(err)) call self%h5%append('/fields/stress', sig, err)
      do i = 1, size(energies)
         if (allocated(err)) exit
         call self%h5%append('/energies/'//trim(self%energy_names(i)), energies(i), err)
      end do
      ! /time and /step last: their length is the number of complete output times
      if (.not. allocated(err)) call self%h5%append('/time', t, err)
      if (.not. allocated(err)) call self%h5%append('/step', step, err)
      if (.not. allocated(err)) call create_views(self%h5, self%ntime, self%nnode, self%nelem, self%nvec, t, step, err)
      if (.not. allocated(err)) call self%h5%flush(err)
      if (allocated(err)) then
         self%broken = .true.
         err%message = 'field output at t = '//real_text(t)//': '//err%message
         return
      end if
      self%ntime = self%ntime + 1
      self%t_last = t
      call append_text(self%grids, self%grids_len, grid_xml(self, self%ntime - 1, t))
      call write_xdmf(self, err)
   end subroutine writer_write_step

   !> Flush and close the .h5 file (the .xdmf file is already complete). No-op when not open.
   subroutine writer_close(self, err)
      class(field_writer_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: err2
      if (.not. self%h5%is_open()) return
      call self%h5%flush(err)
      call self%h5%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
   end subroutine writer_close

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

   ! ---------------------------------------------------------------------------- checks

   !> Check the shapes and index ranges of the mesh arrays.
   subroutine check_mesh(nnode, nelem, x0, conn, region, mat, surf_edges, path, err)
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in) :: x0(:, :)
      integer, intent(in) :: conn(:, :), region(:), mat(:), surf_edges(:, :)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: pre
      integer :: e

      pre = "field output '"//path//"': "
      if (nnode < 1 .or. nelem < 1) then
         call make_error(err, pre//'the mesh needs at least one node and one element')
      else if (any(shape(x0) /= [2, nnode])) then
         call make_error(err, pre//'coordinates must have shape (2, nnode)')
      else if (any(shape(conn) /= [4, nelem])) then
         call make_error(err, pre//'connectivity must have shape (4, nelem)')
      else if (size(region) /= nelem .or. size(mat) /= nelem) then
         call make_error(err, pre//'region and material must have nelem entries')
      else if (size(surf_edges, 1) /= 2) then
         call make_error(err, pre//'contact edges must have shape (2, nedge)')
      else if (any(surf_edges < 1 .or. surf_edges > nnode)) then
         call make_error(err, pre//'a contact edge names a node outside 1..nnode')
      else
         do e = 1, nelem
            if (any(conn(:, e) < 1 .or. conn(:, e) > nnode)) then
               call make_error(err, pre//'element '//itoa(e)//' names a node outside 1..nnode')
               return
            end if
         end do
      end if
   end subroutine check_mesh

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
      else if (any(shape(sig) /= [7, self%nelem])) then
         call make_error(err, pre//'stress must have shape (7, nelem)')
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
      if (.not. allocated(err)) call h5%write_attr('/', 'format_version', 1, err)
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

   !> Create the empty series /time, /step and /fields/*, and the groups /energies and /xdmf.
   subroutine create_field_series(h5, nnode, nelem, nvec, err)
      type(hdf5_file_t), intent(inout) :: h5
      integer, intent(in) :: nnode, nelem, nvec
      type(error_t), allocatable, intent(out) :: err
      integer :: i
      integer :: none(0)

      call h5%create_series('/time', DTYPE_REAL, none, err)
      if (.not. allocated(err)) call h5%create_series('/step', DTYPE_INT64, none, err)
      if (.not. allocated(err)) call h5%create_group('/fields', err)
      do i = 1, nvec
         if (allocated(err)) return
         call h5%create_series('/fields/'//trim(NODE_VECTORS(i)), DTYPE_REAL, [2, nnode], err)
         if (.not. allocated(err)) call h5%write_attr('/fields/'//trim(NODE_VECTORS(i)), 'center', &
                                                      'node', err)
      end do
      if (.not. allocated(err)) call h5%create_series('/fields/contact_active', DTYPE_INT, [nnode], err)
      if (.not. allocated(err)) call h5%write_attr('/fields/contact_active', 'center', 'node', err)
      if (.not. allocated(err)) call h5%create_series('/fields/stress', DTYPE_REAL, [7, nelem], err)
      if (.not. allocated(err)) call h5%write_attr('/fields/stress', 'center', 'cell', err)
      if (.not. allocated(err)) call h5%write_attr('/fields/stress', 'components', &
                                                   join(STRESS_NAMES), err)
      if (.not. allocated(err)) call h5%create_group('/energies', err)
      if (.not. allocated(err)) call h5%create_group('/xdmf', err)
   end subroutine create_field_series

   !> Create one series /energies/<name> per energy (at the first output time).
   subroutine create_energy_series(self, names, err)
      class(field_writer_t), intent(inout) :: self
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
         call self%h5%create_series('/energies/'//trim(names(i)), DTYPE_REAL, none, err)
         if (.not. allocated(err) .and. i == size(names)) &
            call self%h5%write_attr('/energies', 'names', join(names), err)
         if (allocated(err)) then
            self%broken = .true.
            return
         end if
      end do
      if (size(names) == 0) call self%h5%write_attr('/energies', 'names', '', err)
      if (allocated(err)) then
         self%broken = .true.
         return
      end if
      self%energy_names = names
      self%nenergy = size(names)
   end subroutine create_energy_series

   !> Create /xdmf/NNNNNN (k = output index, 0-based) holding views of slab k of every field.
   subroutine create_views(h5, k, nnode, nelem, nvec, t, step, err)
      type(hdf5_file_t), intent(inout) :: h5
      integer, intent(in) :: k, nnode, nelem, nvec
      real(wp), intent(in) :: t
      integer(i8), intent(in) :: step
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: g
      integer :: i

      g = '/xdmf/'//view_group(k)
      call h5%create_group(g, err)
      if (.not. allocated(err)) call h5%write_attr(g, 'time', t, err)
      if (.not. allocated(err)) call h5%write_attr(g, 'step', step, err)
      ! nodal vectors (2, nnode, k) -> (3, nnode), third component zero
      do i = 1, nvec
         if (allocated(err)) return
         call h5%create_view(g//'/'//trim(NODE_VECTORS(i)), '/fields/'//trim(NODE_VECTORS(i)), &
                             DTYPE_REAL, [3, nnode], [0, 0], [2, nnode], [0, 0, k], [2, nnode, 1], err)
      end do
      if (.not. allocated(err)) call h5%create_view(g//'/contact_active', '/fields/contact_active', &
                                                    DTYPE_INT, [nnode], [0], [nnode], [0, k], [nnode, 1], err)
      ! stress (7, nelem, k) -> one (7, nelem) view, read as an (nelem, 7) matrix: one view
      ! instead of seven halves the fixed cost of an output time (views are the costly part)
      if (.not. allocated(err)) call h5%create_view(g//'/stress', '/fields/stress', DTYPE_REAL, [7, nelem], &
                                                    [0, 0], [7, nelem], [0, 0, k], [7, nelem, 1], err)
   end subroutine create_views

   !> Name of the view group of output index k: six digits at least.
   function view_group(k) result(name)
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      character(len=16) :: buf
      write (buf, '(i6.6)') k
      if (k >= 1000000) write (buf, '(i0)') k
      name = trim(buf)
   end function view_group

   ! ---------------------------------------------------------------------------- XDMF

   !> How the .xdmf file names the .h5 file: its base name when both share a directory, else the
   !> absolute path. XDMF uses ':' to separate file and dataset, so the name may not contain one.
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
      if (index(ref, ':') > 0 .or. len(ref) == 0) then
         call make_error(err, "field output: the HDF5 file name '"//ref// &
                         "' must be non-empty and contain no ':'")
      end if
   end subroutine xdmf_reference

   !> XDMF text of the Uniform grid of output index k at time t.
   function grid_xml(self, k, t) result(s)
      class(field_writer_t), intent(in) :: self
      integer, intent(in) :: k
      real(wp), intent(in) :: t
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nn, ne, f, g
      integer :: i

      nn = itoa(self%nnode)
      ne = itoa(self%nelem)
      f = xml_escape(self%h5_ref)//':'
      g = f//'/xdmf/'//view_group(k)//'/'
      s = '      <Grid Name="t'//view_group(k)//'" GridType="Uniform">'//NL// &
          '        <Time Value="'//real_text(t)//'"/>'//NL// &
          '        <Topology TopologyType="Quadrilateral" NumberOfElements="'//ne//'">'//NL// &
          data_item(ne//' 4', 'Int', '4', f//'/mesh/connectivity')// &
          '        </Topology>'//NL// &
          '        <Geometry GeometryType="XY">'//NL// &
          data_item(nn//' 2', 'Float', '8', f//'/mesh/coordinates')// &
          '        </Geometry>'//NL
      do i = 1, self%nvec
         s = s//attribute(trim(NODE_VECTORS(i)), 'Vector', 'Node', &
                          data_item(nn//' 3', 'Float', '8', g//trim(NODE_VECTORS(i))))
      end do
      s = s//attribute('contact_active', 'Scalar', 'Node', &
                       data_item(nn, 'Int', '4', g//'contact_active'))
      s = s//attribute('stress', 'Matrix', 'Cell', data_item(ne//' 7', 'Float', '8', g//'stress'))
      s = s//attribute('region', 'Scalar', 'Cell', data_item(ne, 'Int', '4', f//'/mesh/region'))
      s = s//attribute('material', 'Scalar', 'Cell', data_item(ne, 'Int', '4', f//'/mesh/material'))
      s = s//'      </Grid>'//NL
   end function grid_xml

   !> One HDF DataItem line.
   function data_item(dims, number_type, precision, where) result(s)
      character(len=*), intent(in) :: dims, number_type, precision, where
      character(len=:), allocatable :: s
      s = '          <DataItem Dimensions="'//dims//'" NumberType="'//number_type// &
          '" Precision="'//precision//'" Format="HDF">'//where//'</DataItem>'//NL
   end function data_item

   !> One Attribute element around `item`.
   function attribute(name, attr_type, center, item) result(s)
      character(len=*), intent(in) :: name, attr_type, center, item
      character(len=:), allocatable :: s
      s = '        <Attribute Name="'//name//'" AttributeType="'//attr_type//'" Center="'// &
          center//'">'//NL//item//'        </Attribute>'//NL
   end function attribute

   !> Write the whole .xdmf file to '<path>.tmp', then rename it over '<path>'.
   subroutine write_xdmf(self, err)
      class(field_writer_t), intent(in) :: self
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: head = &
         '<?xml version="1.0" ?>'//NL// &
         '<Xdmf Version="3.0" xmlns:xi="http://www.w3.org/2001/XInclude">'//NL// &
         '  <Domain>'//NL// &
         '    <Grid Name="exic" GridType="Collection" CollectionType="Temporal">'//NL
      character(len=*), parameter :: tail = '    </Grid>'//NL//'  </Domain>'//NL//'</Xdmf>'//NL
      character(len=:), allocatable :: tmp
      character(len=256) :: msg
      integer :: u, ios

      tmp = self%xdmf_path//'.tmp'
      open (newunit=u, file=tmp, access='stream', form='unformatted', status='replace', &
            action='write', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, "field output: cannot write '"//tmp//"': "//trim(msg))
         return
      end if
      if (self%grids_len > 0) then
         write (u, iostat=ios, iomsg=msg) head, self%grids(1:self%grids_len), tail
      else
         write (u, iostat=ios, iomsg=msg) head, tail
      end if
      if (ios /= 0) then
         close (u, status='delete')
         call make_error(err, "field output: cannot write '"//tmp//"': "//trim(msg))
         return
      end if
      close (u, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, "field output: cannot close '"//tmp//"': "//trim(msg))
         return
      end if
      call rename_file(tmp, self%xdmf_path, err)
   end subroutine write_xdmf

   ! ---------------------------------------------------------------------------- text helpers

   !> Append `text` to buf(1:n), growing buf geometrically.
   subroutine append_text(buf, n, text)
      character(len=:), allocatable, intent(inout) :: buf
      integer, intent(inout) :: n
      character(len=*), intent(in) :: text
      character(len=:), allocatable :: tmp
      if (.not. allocated(buf)) allocate (character(len=max(4096, 2*len(text))) :: buf)
      if (n + len(text) > len(buf)) then
         allocate (character(len=max(2*len(buf), n + len(text))) :: tmp)
         tmp(1:n) = buf(1:n)
         call move_alloc(tmp, buf)
      end if
      buf(n + 1:n + len(text)) = text
      n = n + len(text)
   end subroutine append_text

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

   !> `s` with &, <, > and " replaced by XML entities.
   function xml_escape(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      integer :: i
      r = ''
      do i = 1, len(s)
         select case (s(i:i))
         case ('&')
            r = r//'&amp;'
         case ('<')
            r = r//'&lt;'
         case ('>')
            r = r//'&gt;'
         case ('"')
            r = r//'&quot;'
         case default
            r = r//s(i:i)
         end select
      end do
   end function xml_escape

   !> Real as text with 17 significant digits (round-trips exactly).
   function real_text(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es24.16e3)') x
      s = trim(adjustl(buf))
   end function real_text

end module exic_io_fields
