!> ParaView (pvpython, headless under xvfb-run when there is one) opens the field output by
!> relative paths from two working directories and reads known values back
!> (tools/check_paraview.py). Skipped when pvpython is missing: ParaView is not among the
!> packages `make test` installs; `make test-viewers` installs it and runs this suite.
module test_viewers
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_output_fields, only: field_writer_t
   use testing, only: suite_t, check, section, skip, have_command
   use test_fields, only: write_synthetic, synthetic_step, NNODE_T, NELEM_T
   implicit none
   private

   public :: run_viewers_tests

   character(len=*), parameter :: DIR = 'build/test_viewers'

contains

   subroutine run_viewers_tests(s)
      type(suite_t), intent(inout) :: s
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      character(len=:), allocatable :: pv, values, series_values
      real(wp) :: t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T), fcont(2, NNODE_T)
      real(wp) :: sig(7, NELEM_T), energies(2)
      integer :: active(NNODE_T), code
      integer(i8) :: step

      call section(s, 'viewers: ParaView opens the XDMF files by relative paths')
      if (.not. have_command('pvpython')) then
         call skip(s, 'ParaView reads the field output', 'pvpython (make test-viewers)', 4)
         return
      end if
      pv = 'pvpython'
      if (have_command('xvfb-run')) pv = 'xvfb-run -a pvpython'
      call execute_command_line('rm -rf '//DIR//'; mkdir -p '//DIR)
      call write_synthetic(w, DIR//'/pv', 3, err)
      if (.not. allocated(err)) call w%close(err)
      call check(s, .not. allocated(err), 'write the synthetic field output (3 times)')
      if (allocated(err)) return
      call synthetic_step(3, t, step, u, v, a, sig, fcont, active, energies)
      values = ' --cell-value von_mises,4,'//rtoa(sig(6, 5), '(es24.16)')// &
               ' --cell-value J,0,'//rtoa(sig(7, 1), '(es24.16)')// &
               ' --point-value displacement,5,0,'//rtoa(u(1, 6), '(es24.16)')// &
               ' --point-value displacement,5,2,0'// &
               ' --point-value von_mises,0,0,'//rtoa(sig(6, 1), '(es24.16)')// &
               ' --point-value contact_active,2,0,'//itoa(active(3))
      series_values = ' --steps 3'//values
      ! the series, from the project directory and from the run's own directory
      call execute_command_line(pv//' tools/check_paraview.py '//DIR//'/pv_series.xdmf'//series_values// &
                                ' > '//DIR//'/pv1.log 2>&1', exitstat=code)
      call check(s, code == 0, 'the series (3 times) from the project directory: '//DIR//'/pv_series.xdmf', &
                 'exit code '//itoa(code)//', see '//DIR//'/pv1.log')
      call execute_command_line('cd '//DIR//' && '//pv//' ../../tools/check_paraview.py ./pv_series.xdmf'// &
                                series_values//' > pv2.log 2>&1', exitstat=code)
      call check(s, code == 0, 'the series from its own directory: ./pv_series.xdmf', &
                 'exit code '//itoa(code)//', see '//DIR//'/pv2.log')
      ! the last-state file: no time, the values of the last output
      call execute_command_line('cd build && '//pv//' ../tools/check_paraview.py test_viewers/pv.xdmf --steps 0'// &
                                values//' > test_viewers/pv3.log 2>&1', exitstat=code)
      call check(s, code == 0, 'the last output alone from build/: test_viewers/pv.xdmf', &
                 'exit code '//itoa(code)//', see '//DIR//'/pv3.log')
      call execute_command_line('cd '//DIR//' && '//pv//' ../../tools/check_paraview.py pv.xdmf --reader legacy '// &
                                '--steps 0'//values//' > pv4.log 2>&1', exitstat=code)
      call check(s, code == 0, 'the last output by its bare name with ParaView''s XDMF Reader', &
                 'exit code '//itoa(code)//', see '//DIR//'/pv4.log')
   end subroutine run_viewers_tests

end module test_viewers
