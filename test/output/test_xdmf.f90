!> The XDMF series file appended in place (src/exic/output/fields/xdmf.f90) and the nodal averages of
!> element values (src/exic/mesh/smoothing.f90).
!>
!> Kill safety is checked without killing anything: the writes of one append are applied to a
!> copy of the file one after the other, each cut after every one of its bytes (a process that
!> dies in a write leaves a prefix of it), and every one of these states must parse as XML with
!> the old grids, or the old grids and the whole new one (test/xml_states.py, Python's parser).
module test_xdmf
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t
   use exic_mesh_smoothing, only: nodal_average
   use exic_output_fields_xdmf, only: xdmf_series_t, xdmf_write_t, append_writes, write_whole_file
   use testing, only: suite_t, check, check_close, section, skip, have_python_modules, python_command, &
                      file_text, error_text
   implicit none
   private

   public :: run_xdmf_tests

   character(len=*), parameter :: DIR = 'build/test_xdmf'
   character(len=*), parameter :: NL = achar(10)
   character(len=*), parameter :: HEAD = '<?xml version="1.0" ?>'//NL//'<Xdmf Version="3.0">'//NL// &
                                         '  <Domain>'//NL// &
                                         '    <Grid Name="c" GridType="Collection" CollectionType="Temporal">'//NL
   character(len=*), parameter :: TAIL = '    </Grid>'//NL//'  </Domain>'//NL//'</Xdmf>'//NL

contains

   subroutine run_xdmf_tests(s)
      type(suite_t), intent(inout) :: s
      call execute_command_line('rm -rf '//DIR//'; mkdir -p '//DIR)
      call section(s, 'xdmf: every prefix of every write of an append leaves a well-formed file')
      call torn_append_test(s)
      call section(s, 'xdmf: appending past the reserve, and the compact file at the end')
      call growth_test(s)
      call section(s, 'xdmf: a whole file that cannot be written')
      call whole_file_error_test(s)
      call section(s, 'xdmf: nodal averages of element values')
      call nodal_average_test(s)
   end subroutine run_xdmf_tests

   !> A small grid named `name`, with a time and one attribute (text without '--').
   function grid_text(name, t) result(g)
      character(len=*), intent(in) :: name, t
      character(len=:), allocatable :: g
      g = '  <Grid Name="'//name//'" GridType="Uniform">'//NL//'        <Time Value="'//t//'"/>'//NL// &
          '        <Attribute Name="sxx" AttributeType="Scalar" Center="Cell">'//NL// &
          '          <DataItem Dimensions="2" Format="XML">1.5E-001 &#45;2.0</DataItem>'//NL// &
          '        </Attribute>'//NL//'      </Grid>'
   end function grid_text

   !> Two grids appended, then the third one's writes applied to a copy with every cut.
   subroutine torn_append_test(s)
      type(suite_t), intent(inout) :: s
      type(xdmf_series_t) :: series
      type(error_t), allocatable :: err
      type(xdmf_write_t) :: w(6)
      character(len=*), parameter :: path = DIR//'/torn_series.xdmf', states = DIR//'/states'
      character(len=:), allocatable :: before, after, state, g
      integer :: j, p, nstate, code
      integer(i8) :: free

      call series%create(path, HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append(grid_text('t0', '0.0'), err)
      if (.not. allocated(err)) call series%append(grid_text('t1', '0.5'), err)
      call check(s, .not. allocated(err), 'create a series and append two grids', error_text(err))
      if (allocated(err)) return
      g = grid_text('t2', '1.0')
      free = series%next_offset()
      before = file_text(path)
      w = append_writes(free, g)
      call series%append(g, err)
      after = file_text(path)
      call check(s, .not. allocated(err), 'append the third grid', error_text(err))
      ! the writes, applied to the file as it was, give the file the append wrote
      state = before
      do j = 1, size(w)
         call apply(state, w(j)%offset, w(j)%text)
      end do
      call check(s, state == after, 'the planned writes, applied in order, give the appended file')

      call execute_command_line('rm -rf '//states//'; mkdir -p '//states)
      state = before
      nstate = 0
      do j = 1, size(w)
         do p = 0, len(w(j)%text)
            nstate = nstate + 1
            call write_state(states, nstate, cut(state, w(j)%offset, w(j)%text(1:p)))
         end do
         call apply(state, w(j)%offset, w(j)%text)
      end do
      call check(s, nstate == 3 + 3 + 1 + len(g) + 4 + 3 + 6, 'one state per cut of every write', &
                 itoa(nstate)//' states')
      if (.not. have_python_modules('xml.etree.ElementTree')) then
         call skip(s, 'every torn state parses', 'Python')
         return
      end if
      call execute_command_line(python_command()//' test/xml_states.py '//states//' 2 t2', exitstat=code)
      call check(s, code == 0, 'every one of the '//itoa(nstate)//' torn states parses, with 2 grids '// &
                 'or 3 whole ones (test/xml_states.py)', 'exit code '//itoa(code))
      call series%finish(err)
      call check(s, .not. allocated(err) .and. file_text(path) == HEAD//'    '//grid_text('t0', '0.0')// &
                 '  '//NL//'    '//grid_text('t1', '0.5')//'  '//NL//'    '//g//'  '//NL//TAIL, &
                 'finish leaves head, the three grids and tail, without the reserve', error_text(err))
   end subroutine torn_append_test

   !> 60 grids of about 2 kB go past the 64 kB reserve: every one is there, in order.
   subroutine growth_test(s)
      type(suite_t), intent(inout) :: s
      type(xdmf_series_t) :: series
      type(error_t), allocatable :: err
      character(len=*), parameter :: path = DIR//'/growth_series.xdmf'
      character(len=:), allocatable :: text, g, pad, expect
      integer :: k, at, last_at
      logical :: in_order
      integer(i8) :: size_at_30

      pad = repeat('        <Information Name="pad" Value="x"/>'//NL, 40)
      call series%create(path, HEAD, TAIL, err)
      expect = HEAD
      size_at_30 = 0
      do k = 0, 59
         if (allocated(err)) exit
         g = grid_text('g'//itoa(k), itoa(k))
         g = g(:index(g, '</Grid>') - 7)//NL//pad//'      </Grid>'
         call series%append(g, err)
         expect = expect//'    '//g//'  '//NL
         if (k == 30) inquire (file=path, size=size_at_30)
      end do
      call check(s, .not. allocated(err), 'append 60 grids of '//itoa(len(g))//' bytes', error_text(err))
      call check(s, size_at_30 > 65536_i8, 'the file outgrew its first reserve', 'size after 31 grids '// &
                 itoa(int(size_at_30)))
      text = file_text(path)
      in_order = .true.
      last_at = 0
      do k = 0, 59
         at = index(text, 'Grid Name="g'//itoa(k)//'"')
         in_order = in_order .and. at > last_at
         last_at = at
      end do
      call check(s, in_order .and. index(text, TAIL) > 0, 'every grid is in the file before the tail')
      call series%finish(err)
      call check(s, .not. allocated(err) .and. file_text(path) == expect//TAIL, &
                 'the finished file is head, the 60 grids in order and tail', error_text(err))
   end subroutine growth_test

   !> A file in a missing directory: an error naming the temporary file, nothing left behind.
   subroutine whole_file_error_test(s)
      type(suite_t), intent(inout) :: s
      type(error_t), allocatable :: err
      type(xdmf_series_t) :: series
      call write_whole_file(DIR//'/no/such/dir/run.xdmf', 'text', err)
      call check(s, has(err, DIR//'/no/such/dir/run.xdmf.tmp'), 'a missing directory is an error naming '// &
                 'the file', error_text(err))
      call series%append('  <Grid/>', err)
      call check(s, has(err, 'not open'), 'appending to a series never created is an error', error_text(err))
      call series%create(DIR//'/dash_series.xdmf', HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append('  <Grid Name="a--b"/>', err)
      call check(s, has(err, "'--'"), 'a grid containing -- is refused (it would end the comment)', error_text(err))
      call series%abandon()
      ! the test runs as one vector loop over neighbours: a pair at either end of a long grid,
      ! a grid ending in '-', and single dashes everywhere (accepted)
      call series%create(DIR//'/dash_series.xdmf', HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append('--'//repeat(' <Grid/>', 40), err)
      call check(s, has(err, "'--'"), 'a grid starting with -- is refused', error_text(err))
      call series%abandon()
      call series%create(DIR//'/dash_series.xdmf', HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append(repeat(' <Grid/>', 41)//'--', err)
      call check(s, has(err, "'--'"), 'a grid ending with -- is refused', error_text(err))
      call series%abandon()
      call series%create(DIR//'/dash_series.xdmf', HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append(repeat(' <Grid/>', 41)//'-', err)
      call check(s, has(err, "'--'"), 'a grid ending with - is refused', error_text(err))
      call series%abandon()
      call series%create(DIR//'/dash_series.xdmf', HEAD, TAIL, err)
      if (.not. allocated(err)) call series%append(repeat(' <Grid Name="a-b-c"/>-x', 17), err)
      call check(s, .not. allocated(err), 'a grid with single dashes only is taken', error_text(err))
      call series%abandon()
   end subroutine whole_file_error_test

   !> Two elements of areas 1 and 2 sharing an edge, an unused node and a flat element.
   subroutine nodal_average_test(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x(2, 9), cell(2, 3), node(2, 9)
      integer :: conn(4, 3)
      ! 4---5---------6     nodes 1-6: a unit square (1 2 5 4) and a 2 x 1 rectangle (2 3 6 5);
      ! |   |         |     node 7 unused; element 3 (7 8 9 8) has zero area
      ! 1---2---------3
      x = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 3.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 1.0_wp, &
                   3.0_wp, 1.0_wp, 5.0_wp, 5.0_wp, 6.0_wp, 5.0_wp, 7.0_wp, 5.0_wp], [2, 9])
      conn = reshape([1, 2, 5, 4, 2, 3, 6, 5, 8, 9, 9, 8], [4, 3])
      cell = reshape([1.0_wp, 10.0_wp, 4.0_wp, -20.0_wp, 7.0_wp, 8.0_wp], [2, 3])
      call nodal_average(2, 9, 3, conn, x, cell, node)
      call check_close(s, node(1, 2), (1.0_wp*1.0_wp + 2.0_wp*4.0_wp)/3.0_wp, 1.0e-15_wp, &
                       'shared node: area-weighted mean (1 x 1 + 2 x 4) / 3')
      call check_close(s, node(2, 5), (1.0_wp*10.0_wp - 2.0_wp*20.0_wp)/3.0_wp, 1.0e-14_wp, &
                       'shared node, second component')
      call check(s, node(1, 1) == 1.0_wp .and. node(1, 3) == 4.0_wp, 'a corner node takes its element''s value')
      call check(s, all(node(:, 7) == 0.0_wp), 'a node no element uses is 0')
      call check(s, all(node(:, 8) == [7.0_wp, 8.0_wp]), 'a node of zero-area elements only takes their mean')
   end subroutine nodal_average_test

   ! ---------------------------------------------------------------------------- helpers

   !> `text` with `piece` written over it at byte `offset` (0-based), growing it as a file would.
   subroutine apply(text, offset, piece)
      character(len=:), allocatable, intent(inout) :: text
      integer(i8), intent(in) :: offset
      character(len=*), intent(in) :: piece
      text = cut(text, offset, piece)
   end subroutine apply

   !> `text` with `piece` at byte `offset`; bytes beyond the old end are those of `piece` only.
   function cut(text, offset, piece) result(r)
      character(len=*), intent(in) :: text
      integer(i8), intent(in) :: offset
      character(len=*), intent(in) :: piece
      character(len=:), allocatable :: r
      integer :: o
      o = int(offset)
      if (o + len(piece) <= len(text)) then
         r = text(:o)//piece//text(o + len(piece) + 1:)
      else
         r = text(:o)//piece
      end if
   end function cut

   !> Write state number k into folder as state_NNNNNN.xml.
   subroutine write_state(folder, k, text)
      character(len=*), intent(in) :: folder, text
      integer, intent(in) :: k
      character(len=16) :: name
      integer :: u
      write (name, '(a,i6.6,a)') 'state_', k, '.xml'
      open (newunit=u, file=folder//'/'//trim(name), access='stream', form='unformatted', status='replace')
      write (u) text
      close (u)
   end subroutine write_state

   !> True when err is set and its message contains `text`.
   logical function has(err, text)
      type(error_t), allocatable, intent(in) :: err
      character(len=*), intent(in) :: text
      has = allocated(err)
      if (has) has = index(err%message, text) > 0
   end function has

end module test_xdmf
