!> The layout of the field file (submodule of fields.f90, doc/fields.md): the /mesh group and
!> the identification attributes, the series of /fields, /time and /step with their XDMF views,
!> the last-state buffers /last/a and /last/b, and the series of /energies.
submodule(exic_output_fields) exic_output_fields_layout
   use exic_hdf5_file, only: DTYPE_REAL, DTYPE_INT, DTYPE_INT64
   use exic_output_fields_text, only: BUFFER
   implicit none

contains

   !> The /mesh group and the file's identification attributes (interface: fields.f90).
   module procedure write_mesh
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
   end procedure write_mesh

   !> The empty series /time, /step and /fields/*, with their XDMF views (interface: fields.f90).
   module procedure create_field_series
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
   end procedure create_field_series

   !> The two last-state buffers /last/a and /last/b (interface: fields.f90).
   module procedure create_last_buffers
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
   end procedure create_last_buffers

   !> Output time k, batch slot j, into its last-state buffer mod(k, 2) (interface: fields.f90).
   module procedure write_last_buffer
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
   end procedure write_last_buffer

   !> One series /energies/<name> per energy (interface: fields.f90).
   module procedure create_energy_series
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
   end procedure create_energy_series

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

end submodule exic_output_fields_layout
