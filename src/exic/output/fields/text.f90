!> The XDMF text of the field output (doc/fields.md, "The XDMF files"): the head and tail of
!> `<stem>_series.xdmf`, its grid of one output time, and the whole last-state `<stem>.xdmf`.
!>
!> A grid of the series differs from one output time to the next only in the output index k
!> (the grid's name, every slab's start k and its dimension k + 1) and the time. `fields_text_t`
!> therefore builds the grid once, at `init`, with marker characters in those places, and keeps
!> it as the pieces between the markers: a grid is then the pieces with the numbers put between
!> them (`series_grid`), one pass over about 6 kB instead of some 70 concatenations of
!> allocated strings per output time (doc/performance.md, section 6.5).
module exic_output_fields_text
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   use exic_output_fields_xdmf, only: real_text, data_item, attribute
   implicit none
   private

   public :: fields_text_t, NODE_VECTORS, BUFFER, series_path, xdmf_reference

   !> Names of the nodal vector fields, datasets `/fields/<name>`; the last, the nodal friction
   !> force (doc/friction.md), only when the run has friction.
   character(len=14), parameter :: NODE_VECTORS(5) = [character(len=14) :: 'displacement', &
                                                      'velocity', 'acceleration', 'contact_force', &
                                                      'friction_force']
   !> The two last-state buffers, `/last/a` and `/last/b`.
   character(len=1), parameter :: BUFFER(0:1) = ['a', 'b']

   character(len=*), parameter :: NL = achar(10)
   !> Markers of the template: output index k, k + 1, k with six digits, the time.
   character(len=1), parameter :: MARK_K = achar(1), MARK_K1 = achar(2), MARK_SIX = achar(3), &
                                  MARK_T = achar(4)

   !> One piece of the template: text, then what follows it (0: nothing, 1..4: a marker).
   type :: piece_t
      character(len=:), allocatable :: text
      integer :: mark = 0
   end type piece_t

   !> What the XDMF text of one field file needs to know, and the series grid's template.
   type :: fields_text_t
      character(len=:), allocatable :: h5_ref       !< the .h5 file as the XDMF files name it
      integer :: nnode = 0, nelem = 0, nvec = 4, ncomp = 0
      logical :: node_id = .false.                  !< the file has /mesh/node_id (numbering gaps)
      character(len=16), allocatable :: comp_names(:)
      type(piece_t), allocatable :: pieces(:)
      integer :: fixed_len = 0                      !< characters of the pieces together
   contains
      procedure :: init => text_init
      procedure :: series_grid => text_series_grid
      procedure :: last_document => text_last_document
      procedure, nopass :: series_head, series_tail
   end type fields_text_t

contains

   !> Set up the text of a field file: the .h5 as the XDMF files name it (escaped), the mesh
   !> sizes, the number of nodal vectors, the element value names, whether the file has the
   !> nodes' deck numbers (`/mesh/node_id`); build the grid template.
   subroutine text_init(self, h5_ref, nnode, nelem, nvec, comp_names, node_id)
      class(fields_text_t), intent(inout) :: self
      character(len=*), intent(in) :: h5_ref
      integer, intent(in) :: nnode, nelem, nvec
      character(len=*), intent(in) :: comp_names(:)
      logical, intent(in) :: node_id
      character(len=:), allocatable :: grid
      integer :: i, n, start

      self%h5_ref = h5_ref
      self%nnode = nnode
      self%nelem = nelem
      self%nvec = nvec
      self%ncomp = size(comp_names)
      self%comp_names = comp_names
      self%node_id = node_id
      grid = grid_text(self, MARK_K, MARK_K1, MARK_SIX, MARK_T)
      n = 1
      do i = 1, len(grid)
         if (iachar(grid(i:i)) <= 4) n = n + 1
      end do
      if (allocated(self%pieces)) deallocate (self%pieces)
      allocate (self%pieces(n))
      n = 0
      start = 1
      do i = 1, len(grid)
         if (iachar(grid(i:i)) <= 4) then
            n = n + 1
            self%pieces(n)%text = grid(start:i - 1)
            self%pieces(n)%mark = iachar(grid(i:i))
            start = i + 1
         end if
      end do
      self%pieces(n + 1)%text = grid(start:)
      self%pieces(n + 1)%mark = 0
      self%fixed_len = len(grid) - n
   end subroutine text_init

   !> The grid of output k (0-based) at time t in the series file: the template with k, k + 1,
   !> k in six digits and the time put in. Indented for the four blanks exic_output_fields_xdmf puts
   !> before it, without a final newline.
   function text_series_grid(self, k, t) result(s)
      class(fields_text_t), intent(in) :: self
      integer, intent(in) :: k
      real(wp), intent(in) :: t
      character(len=:), allocatable :: s
      character(len=:), allocatable :: ks, k1s, sixs, ts
      integer :: i, n, at, nk, nk1, nsix, nt

      ks = itoa(k)
      k1s = itoa(k + 1)
      sixs = six_digits(k)
      ts = real_text(t)
      nk = 0
      nk1 = 0
      nsix = 0
      nt = 0
      do i = 1, size(self%pieces)
         select case (self%pieces(i)%mark)
         case (1)
            nk = nk + 1
         case (2)
            nk1 = nk1 + 1
         case (3)
            nsix = nsix + 1
         case (4)
            nt = nt + 1
         end select
      end do
      n = self%fixed_len + nk*len(ks) + nk1*len(k1s) + nsix*len(sixs) + nt*len(ts)
      allocate (character(len=n) :: s)
      at = 0
      do i = 1, size(self%pieces)
         associate (p => self%pieces(i))
            s(at + 1:at + len(p%text)) = p%text
            at = at + len(p%text)
            select case (p%mark)
            case (1)
               s(at + 1:at + len(ks)) = ks
               at = at + len(ks)
            case (2)
               s(at + 1:at + len(k1s)) = k1s
               at = at + len(k1s)
            case (3)
               s(at + 1:at + len(sixs)) = sixs
               at = at + len(sixs)
            case (4)
               s(at + 1:at + len(ts)) = ts
               at = at + len(ts)
            end select
         end associate
      end do
   end function text_series_grid

   !> The grid with the given texts for k, k + 1, the six-digit k and the time: slab k of the
   !> datasets, in Xdmf3's form "file:/dataset|start:stride:count:dims" (C order, time first).
   function grid_text(self, ks, k1s, sixs, ts) result(s)
      type(fields_text_t), intent(in) :: self
      character(len=*), intent(in) :: ks, k1s, sixs, ts
      character(len=:), allocatable :: s
      character(len=:), allocatable :: nn, ne, nc
      integer :: i

      nn = itoa(self%nnode)
      ne = itoa(self%nelem)
      nc = itoa(self%ncomp)
      s = '  <Grid Name="t'//sixs//'" GridType="Uniform">'//NL// &
          '        <Time Value="'//ts//'"/>'//NL//mesh_items(self)
      do i = 1, self%nvec
         s = s//attribute(trim(NODE_VECTORS(i)), 'Vector', 'Node', data_item(nn//' 3', 'Float', '8', &
                          slab('/xdmf/'//trim(NODE_VECTORS(i)), '0 0', '1 1', nn//' 3', nn//' 3')))
      end do
      s = s//attribute('contact_active', 'Scalar', 'Node', data_item(nn, 'Int', '4', &
                       slab('/fields/contact_active', '0', '1', nn, nn)))
      do i = 1, self%ncomp
         s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Cell', data_item(ne, 'Float', '8', &
                          slab('/fields/stress', '0 '//itoa(i - 1), '1 1', ne//' 1', ne//' '//nc)))
      end do
      do i = 1, self%ncomp
         s = s//attribute(trim(self%comp_names(i)), 'Scalar', 'Node', data_item(nn, 'Float', '8', &
                          slab('/fields/nodal_stress', '0 '//itoa(i - 1), '1 1', nn//' 1', nn//' '//nc)))
      end do
      s = s//static_attributes(self)//'      </Grid>'

   contains

      !> "file:dataset|k start:1 stride:1 count:k+1 dims": slab k of a series, C order.
      function slab(dataset, start, stride, count, dims) result(r)
         character(len=*), intent(in) :: dataset, start, stride, count, dims
         character(len=:), allocatable :: r
         r = self%h5_ref//':'//dataset//'|'//ks//' '//start//':1 '//stride//':1 '//count//':'// &
             k1s//' '//dims
      end function slab

   end function grid_text

   !> The last-state file: output k (0-based; -1 before the first: the mesh alone) at time t,
   !> solver step `step`, held in buffer b; plain datasets only, one Uniform grid, no Time element
   !> (meshio.read accepts exactly this).
   function text_last_document(self, b, k, t, step) result(s)
      class(fields_text_t), intent(in) :: self
      integer, intent(in) :: b, k
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
         name = 'exic t = '//real_text(t)//', step '//itoa(step)//', output '//itoa(k)
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
   end function text_last_document

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
      type(fields_text_t), intent(in) :: self
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

   !> Region and material of every element; the deck number of every node when the file has it.
   function static_attributes(self) result(s)
      type(fields_text_t), intent(in) :: self
      character(len=:), allocatable :: s
      character(len=:), allocatable :: f
      f = self%h5_ref//':'
      s = attribute('region', 'Scalar', 'Cell', data_item(itoa(self%nelem), 'Int', '4', f//'/mesh/region'))// &
          attribute('material', 'Scalar', 'Cell', data_item(itoa(self%nelem), 'Int', '4', f//'/mesh/material'))
      if (self%node_id) s = s//attribute('node_id', 'Scalar', 'Node', &
                                         data_item(itoa(self%nnode), 'Int', '4', f//'/mesh/node_id'))
   end function static_attributes

   !> k with six digits at least.
   function six_digits(k) result(name)
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      character(len=16) :: buf
      write (buf, '(i6.6)') k
      if (k >= 1000000) write (buf, '(i0)') k
      name = trim(buf)
   end function six_digits

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
      if (scan(ref, ':|') > 0 .or. len(ref) == 0 .or. any([(iachar(ref(i5:i5)) < 32, i5=1, len(ref))])) then
         call make_error(err, "field output: the HDF5 file name '"//ref// &
                         "' must be non-empty and contain no ':', '|' or control character")
      end if
   end subroutine xdmf_reference

end module exic_output_fields_text
