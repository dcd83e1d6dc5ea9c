!> Field output of a mesh whose node numbers have gaps (doc/fields.md, "Node numbers"): a BLOCk
!> from node 11, COORdinates 101, 103, 105, 201, 203, 205 and a free node 300 (no element uses
!> it). The files hold exactly those 22 nodes, their deck numbers as `node_id`, no point that no
!> cell uses but node 300 (meshio, the series, h5py: tools/check_xdmf.py --node-ids); and every
!> field value is, bit for bit, that of the same mesh numbered 1..22 without gaps, whose file
!> has no `node_id` (h5diff).
module test_fields_nodes
   use exic_base_strings, only: itoa
   use testing, only: suite_t, check, section, skip, have_command, have_python_modules, python_command
   use deck_runner, only: run_dir, run_deck
   implicit none
   private

   public :: run_fields_nodes_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_fields_nodes_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, gap, plain
      integer :: stage, code, i
      character(len=*), parameter :: IDS = '11-25,101,103,105,201,203,205,300'
      character(len=*), parameter :: SAME(*) = [character(len=26) :: '/mesh/coordinates', &
         '/mesh/connectivity', '/mesh/contact_edges', '/fields/displacement', '/fields/velocity', &
         '/fields/acceleration', '/fields/contact_force', '/fields/contact_active', '/fields/stress', &
         '/fields/nodal_stress', '/time']

      call section(s, 'fields_nodes: node numbers with gaps write the nodes alone, node_id their numbers')
      gap = run_dir//'/nodes_gap'
      plain = run_dir//'/nodes_plain'
      call run_deck('nodes_gap', deck([11, 101, 103, 105, 201, 203, 205, 300]), stage, msg)
      call check(s, stage == 0, 'the deck with node numbers 11-25, 101-205 (odd), 300 runs', msg)
      if (stage /= 0) return
      call run_deck('nodes_plain', deck([1, 16, 17, 18, 19, 20, 21, 22]), stage, msg)
      call check(s, stage == 0, 'the same mesh numbered 1..22 runs', msg)
      if (stage /= 0) return

      if (have_python_modules('meshio,h5py,numpy')) then
         call execute_command_line(python_command()//' tools/check_xdmf.py '//gap//'.xdmf --steps 5 --points 22 '// &
                                   '--cells 10 --node-ids '//IDS//' --free 300 > '//gap//'_check.log 2>&1', &
                                   exitstat=code)
         call check(s, code == 0, 'meshio, the series and h5py see the 22 nodes alone, node_id = '//IDS// &
                    ', only node 300 in no cell', 'see '//gap//'_check.log')
         call execute_command_line(python_command()//' tools/check_xdmf.py '//plain//'.xdmf --points 22 --cells 10 '// &
                                   '--node-ids none > '//plain//'_check.log 2>&1', exitstat=code)
         call check(s, code == 0, 'the mesh without gaps has no node_id', 'see '//plain//'_check.log')
      else
         call skip(s, 'meshio and h5py read the nodes alone', 'Python with meshio and h5py', 2)
      end if

      if (have_command('h5diff')) then
         do i = 1, size(SAME)
            ! the data, not the description attribute (which says where the indices point)
            call execute_command_line('h5diff --exclude-attribute '//trim(SAME(i))//' '//gap//'.h5 '//plain// &
                                      '.h5 '//trim(SAME(i))//' '//trim(SAME(i))//' > /dev/null 2>&1', exitstat=code)
            call check(s, code == 0, trim(SAME(i))//': the same bits as the mesh numbered without gaps')
         end do
      else
         call skip(s, 'the fields equal those of the mesh without gaps', 'h5diff', size(SAME))
      end if

      if (have_command('pvpython')) then
         call execute_command_line(merge('xvfb-run -a ', '            ', have_command('xvfb-run'))// &
                                   'pvpython tools/check_paraview.py '//gap//'_series.xdmf --steps 5 '// &
                                   '--point-value node_id,0,0,11 --point-value node_id,21,0,300 > '// &
                                   gap//'_pv.log 2>&1', exitstat=code)
         call check(s, code == 0, 'ParaView (Xdmf3) reads node_id of the first and last point', &
                    'see '//gap//'_pv.log')
      else
         call skip(s, 'ParaView reads node_id', 'pvpython (make test-viewers)')
      end if
   end subroutine run_fields_nodes_tests

   !> Two bodies: a 4 x 2 BLOCk from node n(1) (element 1..8), two elements from COORdinates
   !> n(2..7) falling on it, and a free node n(8) that no element uses.
   function deck(n) result(text)
      integer, intent(in) :: n(8)
      character(len=:), allocatable :: text
      text = 'FEAP * * node numbers with gaps'//nl//'  0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,4,2,'//itoa(n(1))//',1,1'//nl// &
             '    1,0,0'//nl//'    2,4,0'//nl//'    3,4,2'//nl//'    4,0,2'//nl//nl// &
             'COORdinates'//nl// &
             '  '//itoa(n(2))//',0,1,2.5'//nl//'  '//itoa(n(3))//',0,2,2.5'//nl//'  '//itoa(n(4))//',0,3,2.5'//nl// &
             '  '//itoa(n(5))//',0,1,3.5'//nl//'  '//itoa(n(6))//',0,2,3.5'//nl//'  '//itoa(n(7))//',0,3,3.5'//nl// &
             '  '//itoa(n(8))//',0,9,9'//nl//nl// &
             'REGIon,2'//nl//'ELEMents'//nl// &
             '  9,0,1,'//itoa(n(2))//','//itoa(n(3))//','//itoa(n(6))//','//itoa(n(5))//nl// &
             '  10,0,1,'//itoa(n(3))//','//itoa(n(4))//','//itoa(n(7))//','//itoa(n(6))//nl//nl// &
             'BOUNdary'//nl//'  '//itoa(n(1))//',1,1,1'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,2,0,-1'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,SYMMetric,1,2'//nl//'END CONTact'//nl//'END'//nl// &
             'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl//'  OUTPut,HDF5,0.1'//nl// &
             '  LOOP,,100000'//nl//'    TIME,,0.4'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'STOP'
   end function deck

end module test_fields_nodes
