!> Field output of real runs: read back with h5dump against the run's own histories, and a run
!> killed with SIGTERM halfway through.
module test_run_output
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use testing, only: suite_t, check, section, skip, have_command, have_python_modules
   use deck_runner, only: run_dir, run_deck, read_table, write_text, file_has
   use test_fields, only: run_python
   implicit none
   private

   public :: run_run_output_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_run_output_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'run output: HDF5 fields of a run against its own history file')
      call readback_test(s)
      call section(s, 'run output: a run killed by SIGTERM halfway')
      call killed_run_test(s)
      call section(s, 'run output: an output interval far below the time step')
      call tiny_interval_test(s)
      call section(s, 'run output: a failed run keeps the fields of the state it stopped in')
      call failed_run_test(s)
      call section(s, 'run output: non-finite values are never written as fields')
      call nonfinite_fields_test(s)
   end subroutine run_run_output_tests

   !> A 12 x 2 bar hitting a rigid wall at a fixed step 1e-3: fields every `every` steps,
   !> histories every step.
   function bar_deck(nsteps, every) result(deck)
      integer, intent(in) :: nsteps, every
      character(len=:), allocatable :: deck
      character(len=16) :: a, b
      write (a, '(i0)') nsteps
      write (b, '(i0)') every
      deck = 'FEAP * * field output of a run'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,12,2,0,0,1'//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,1,2,0,0,2'//nl//'    1,6,-1'//nl//'    2,7,-1'//nl// &
             '    3,7,2'//nl//'    4,6,2'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,0.5,0'//nl//nl// &
             'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,,1e-3'//nl//'  TPLOt,,1'//nl//'  OUTPut,HDF5,'//trim(b)//'e-3'//nl// &
             '  LOOP,,'//trim(a)//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,13,1'//nl//'  disp,20,2'//nl//nl//'STOP'
   end function bar_deck

   !> Datasets and shapes with h5dump, and one displacement value against <stem>.his.
   subroutine readback_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, h5
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: his(:, :), times(:), one(:)
      integer :: stage, status, nt, k, row
      real(wp) :: value

      call run_deck('fields_run', bar_deck(60, 5), stage, msg)
      call check(s, stage == 0, 'deck with OUTPut,HDF5 runs', msg)
      if (stage /= 0) return
      if (.not. have_command('h5dump')) then
         call skip(s, 'the run''s .h5 read back', 'h5dump', 9)
         return
      end if
      h5 = run_dir//'/fields_run.h5'
      call execute_command_line('h5dump -H '//h5//' > '//run_dir//'/fields_run.h5dump 2>&1', exitstat=status)
      call check(s, status == 0, 'h5dump reads the run''s .h5')
      call check(s, file_has(run_dir//'/fields_run.h5dump', 'DATASET "displacement"') .and. &
                 file_has(run_dir//'/fields_run.h5dump', 'DATASET "stress"') .and. &
                 file_has(run_dir//'/fields_run.h5dump', 'DATASET "contact_force"') .and. &
                 file_has(run_dir//'/fields_run.h5dump', 'DATASET "connectivity"'), &
                 'mesh, displacement, stress and contact-force datasets are there')
      call read_h5_vector(h5, '/time', times)
      nt = size(times)
      ! 60 steps with output every 5: t = 0, 5 dt, ..., 60 dt
      call check(s, nt == 13, 'one output time every 5 steps', 'output times: '//itoa(nt))
      call check(s, file_has(run_dir//'/fields_run.h5dump', '( '//itoa(nt)//', 45, 2 )'), &
                 'displacement shape (times, 45 nodes, 2)')
      call check(s, file_has(run_dir//'/fields_run.h5dump', '( '//itoa(nt)//', 26, 7 )'), &
                 'stress shape (times, 26 elements, 7)')
      ! the x-displacement of node 13 (the struck tip) at output k against the history row at that time
      k = nt/2
      call read_h5_vector(h5, '/fields/displacement -s "'//itoa(k - 1)//',12,0" -c "1,1,1"', one)
      call check(s, size(one) == 1, 'h5dump reads one displacement value')
      if (size(one) /= 1) return
      value = one(1)
      call read_table(run_dir//'/fields_run.his', names, his)
      row = minloc(abs(his(1, :) - times(k)), dim=1)
      call check(s, abs(his(1, row) - times(k)) <= 1.0e-12_wp*max(1.0_wp, times(k)) .and. &
                 abs(value - his(2, row)) <= 1.0e-14_wp*max(abs(value), 1.0e-30_wp) + 1.0e-300_wp, &
                 'field value equals the history value at the same time', &
                 'h5 '//rtoa(value, '(es23.16)')//', his '//rtoa(his(2, row), '(es23.16)')//' at t '//rtoa(times(k), '(es23.16)'))
      ! an independent reader: meshio loads the .xdmf time series (node 13 is point 12)
      if (.not. have_python_modules('meshio,h5py')) then
         call skip(s, 'meshio reads the run''s .xdmf', 'Python with meshio and h5py')
         return
      end if
      status = run_python('tools/check_xdmf.py '//run_dir//'/fields_run.xdmf --steps '//itoa(nt)// &
                          ' --points 45 --cells 26 --point-value displacement,'//itoa(k - 1)//',12,0,'// &
                          rtoa(his(2, row), '(es23.16)')//' --tol 1e-15')
      call check(s, status == 0, 'the run''s series XDMF: times, points, cells and the same value')
      ! meshio.read of <stem>.xdmf: the last output time, against the history row of that time
      row = minloc(abs(his(1, :) - times(nt)), dim=1)
      status = run_python('tools/check_xdmf.py '//run_dir//'/fields_run.xdmf --point-value displacement,last,12,0,'// &
                          rtoa(his(2, row), '(es23.16)')//' --tol 1e-15 --convert '//run_dir//'/fields_run.vtu')
      call check(s, status == 0, 'meshio.read of the run''s .xdmf gives the last time''s displacement, '// &
                 'as in the .his; meshio convert writes it')
   end subroutine readback_test

   !> A run killed by SIGTERM after it has written 20 output times leaves a readable .h5 with
   !> exactly those 20. The child parks itself once the 20th is flushed (deck_run_child), so the
   !> kill never lands inside a write; the wait for it is bounded in seconds.
   subroutine killed_run_test(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nout = 20
      character(len=:), allocatable :: child, script, base
      real(wp), allocatable :: times(:)
      integer :: status, nflushed
      logical :: exists

      if (.not. child_found(s, child)) return
      base = run_dir//'/killed_run'
      call write_text(base//'.inp', bar_deck(20000000, 2))
      call execute_command_line('rm -f '//base//'.h5 '//base//'.xdmf '//base//'.ready '//base//'.status')
      ! start the run, wait (at most 120 s) until it has flushed at least nout output times (the
      ! first batch that reaches them; the child writes the count into .ready), then kill it
      script = child//' --child '//base//'.inp '//base//' '//itoa(nout)//' '//base//'.ready > '//base// &
               '.log 2>&1 & pid=$!; while [ ! -e '//base//'.ready ] && [ $SECONDS -lt 120 ]; do sleep 0.05; done; '// &
               'kill -TERM $pid; wait $pid; echo $? > '//base//'.status'
      call execute_command_line('bash -c '''//script//'''', exitstat=status)
      inquire (file=base//'.ready', exist=exists)
      call check(s, exists, 'the run wrote '//itoa(nout)//' output times within 120 s')
      call check(s, int(last_number(base//'.status')) == 128 + 15, 'the run was killed by SIGTERM while running')
      if (.not. have_command('h5dump')) then
         call skip(s, 'the killed run''s .h5 read back', 'h5dump', 3)
         return
      end if
      call execute_command_line('h5dump -H '//base//'.h5 > /dev/null 2>&1', exitstat=status)
      call check(s, status == 0, 'h5dump reads the killed run''s .h5')
      call read_h5_vector(base//'.h5', '/time', times)
      nflushed = first_number(base//'.ready')
      call check(s, nflushed >= nout .and. size(times) == nflushed .and. all(times(2:) > times(:size(times) - 1)), &
                 'the output times flushed before the kill (at least '//itoa(nout)//') are there', &
                 'times in file '//itoa(size(times))//', flushed '//itoa(nflushed))
      call execute_command_line('h5dump -d /fields/displacement '//base//'.h5 > /dev/null 2>&1', exitstat=status)
      call check(s, status == 0, 'the displacement field of every output time reads back')
   end subroutine killed_run_test

   !> The child program deck_run_child next to the test driver (checked: it is there).
   logical function child_found(s, child) result(exists)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable, intent(out) :: child
      character(len=4096) :: arg
      call get_command_argument(0, arg)
      child = arg(1:index(arg, '/', back=.true.))//'deck_run_child'
      inquire (file=child, exist=exists)
      call check(s, exists, 'child program found next to the test driver', child)
   end function child_found

   !> Values of a 1-D dataset, read with h5dump.
   subroutine read_h5_vector(h5, dset, v)
      character(len=*), intent(in) :: h5, dset
      real(wp), allocatable, intent(out) :: v(:)
      character(len=*), parameter :: tmp = run_dir//'/h5vector.txt'
      integer :: u, ios
      real(wp) :: x
      call execute_command_line('h5dump -d '//dset//' -y -w 0 -m "%.17g" '//h5// &
                                ' 2>/dev/null | sed -n "/DATA {/,/}/p" | tr -s ", " "\n\n" | '// &
                                'grep -E "^-?[0-9]" > '//tmp)
      allocate (v(0))
      open (newunit=u, file=tmp, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, *, iostat=ios) x
         if (ios /= 0) exit
         v = [v, x]
      end do
      close (u)
   end subroutine read_h5_vector

   !> OUTPut,HDF5,dt_out far below a step of 1e-3: fields once per step (61 output times for 60
   !> steps), a warning in <stem>.out, and no loop over the intervals each step jumps over. With
   !> 1e-308 and 1e-320 (below the spacing of the times, and so small that the number of intervals
   !> a step jumps over overflows) adding the interval no longer moves the output time: the
   !> schedule once stood still there for ever (a fuzzed deck). Each run is a child process under
   !> `timeout 120` (it takes a fraction of a second), so that such a hang fails the check
   !> instead of stopping the suite.
   subroutine tiny_interval_test(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: intervals(3) = ['1e-12 ', '1e-308', '1e-320']
      character(len=:), allocatable :: child, deck, base, dt_out
      real(wp), allocatable :: times(:)
      integer :: status, k

      if (.not. child_found(s, child)) return
      do k = 1, size(intervals)
         dt_out = trim(intervals(k))
         base = run_dir//'/tiny_interval_'//itoa(k)
         deck = bar_deck(60, 1)
         deck = deck(:index(deck, 'OUTPut,HDF5,') + 11)//dt_out//deck(index(deck, 'OUTPut,HDF5,') + 16:)
         call check(s, index(deck, 'OUTPut,HDF5,'//dt_out//nl) > 0, 'deck with OUTPut,HDF5,'//dt_out//' written')
         call write_text(base//'.inp', deck)
         call execute_command_line('rm -f '//base//'.h5 '//base//'.out')
         call execute_command_line('timeout 120 '//child//' --child '//base//'.inp '//base//' > '//base// &
                                   '.log 2>&1', exitstat=status)
         call check(s, status == 0, 'a run with OUTPut,HDF5,'//dt_out//' and a step of 1e-3 finishes', &
                    'exit status '//itoa(status)//' (124: still running after 120 s)')
         if (status /= 0) cycle
         call check(s, file_has(base//'.out', 'fields are written once per step'), &
                    'OUTPut,HDF5,'//dt_out//': the interval below the step is a warning in <stem>.out')
         if (.not. have_command('h5dump')) then
            call skip(s, 'output times read back', 'h5dump')
            cycle
         end if
         call read_h5_vector(base//'.h5', '/time', times)
         call check(s, size(times) == 61 .and. all(times(2:) > times(:size(times) - 1)), &
                    'OUTPut,HDF5,'//dt_out//': one output time per step (61 for 60 steps)', &
                    'output times '//itoa(size(times)))
      end do
   end subroutine tiny_interval_test

   !> The bar at 100 instead of 0.5 folds an element at step 8 (t = 8e-3): the fields of that
   !> state follow those of t = 0 and 5e-3, the .h5 says why, the XDMF files show it.
   subroutine failed_run_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck, base
      real(wp), allocatable :: times(:)
      integer :: stage, status
      deck = bar_deck(200, 5)
      deck = deck(:index(deck, '  REGIon,1,0.5,0') - 1)//'  REGIon,1,100,0'//deck(index(deck, '  REGIon,1,0.5,0') + 16:)
      call run_deck('failed_run', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'inverted') > 0, 'the run stops on a folded element', msg)
      if (stage /= 2) return
      base = run_dir//'/failed_run'
      call check(s, file_has(base//'.out', 'fields of the state at the failure written (t = 8.0000000E-03)'), &
                 '<stem>.out says the failing state was written')
      if (.not. have_command('h5dump')) then
         call skip(s, 'the failed run''s .h5 read back', 'h5dump', 2)
         return
      end if
      call read_h5_vector(base//'.h5', '/time', times)
      call check(s, size(times) == 3, 'output times 0, 5e-3 and the failure at 8e-3', 'times '//itoa(size(times)))
      if (size(times) == 3) call check(s, abs(times(3) - 8.0e-3_wp) < 1.0e-15_wp, 'the last output time is the failure''s', &
                                       rtoa(times(3)))
      call execute_command_line('h5dump -a /failed '//base//'.h5 > '//base//'.failed 2>&1', exitstat=status)
      call check(s, status == 0 .and. file_has(base//'.failed', 'element') .and. file_has(base//'.failed', 'inverted'), &
                 'the .h5 attribute failed holds the error')
      if (.not. have_python_modules('meshio,h5py')) then
         call skip(s, 'meshio reads the failed run', 'Python with meshio and h5py')
         return
      end if
      status = run_python('tools/check_xdmf.py '//base//'.xdmf --steps 3 --points 45 --cells 26 --time 2,8e-3')
      call check(s, status == 0, 'meshio.read shows the failing state, the series has the 3 times')
   end subroutine failed_run_test

   !> The integer that starts the first line of a file (-1 if none).
   integer function first_number(path) result(n)
      character(len=*), intent(in) :: path
      integer :: u, ios
      n = -1
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      read (u, *, iostat=ios) n
      if (ios /= 0) n = -1
      close (u)
   end function first_number

   !> A penalty of 1e300 (a fuzzed deck) with DT,CFL: the first step's contact forces overflow. The run stops
   !> naming where the values stopped being finite, and neither the output at t = 0 nor the
   !> state it stopped in is written with them: the .h5 holds no NaN or infinity. A penalty scale
   !> whose stiffness overflows outright is an error at its record.
   subroutine nonfinite_fields_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck, base
      integer :: stage, status, k
      k = index(bar_deck(200, 5), '  AUTOmatic'//nl) + len('  AUTOmatic'//nl) - 1
      deck = bar_deck(200, 5)
      deck = deck(:k)//'    PENAlty,1e300'//nl//deck(k + 1:)
      ! the stable step of the penalty is 2.5e-151: a fixed DT of 1e-3 is refused at the start
      call run_deck('penalty_dt', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'exceeds the stable limit 2.5000000E-151 (contact penalty)') > 0, &
                 'PENAlty,1e300 with DT,,1e-3: refused, the stable limit with its three-digit exponent', msg)
      ! the seed's 7.2 with PENAlty,1e300 and DT,CFL (the fuzzed deck): its bars touch at t = 0
      ! with a round-off penetration, and the first step overflows
      deck = 'FEAP * * seed 7.2 with a penalty of 1e300'//nl//'  0 0 0 2 2 4'//nl//'PARAmeters'//nl// &
             '  nsv = 30'//nl//'  cfl = 0.9'//nl//'  tend = 0.3'//nl//'  tout = 0.002'//nl// &
             'INCLude,../../inputs/paper/common/ex72_mesh.inc'//nl//'CONTact'//nl//'  SURFace,1'//nl// &
             '    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl//'  PAIR,1,NTOS,1,2'//nl// &
             '    PENAlty,1e300'//nl//'END CONTact'//nl//'INCLude,../../inputs/paper/common/ex72_batch.inc'
      call run_deck('nonfinite_fields', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'not finite') > 0 .and. index(msg, 'step 1') > 0, &
                 'PENAlty,1e300: the run stops at step 1 on a value that is not finite', msg)
      base = run_dir//'/nonfinite_fields'
      call check(s, file_has(base//'.out', 'fields of the state at the failure not written'), &
                 '<stem>.out says the failing state was not written')
      call check(s, .not. (file_has(base//'.out', 'NaN') .or. file_has(base//'.out', 'Infinity')), &
                 'no NaN or Infinity in <stem>.out')
      if (have_command('h5dump')) then
         call execute_command_line('h5dump '//base//'.h5 > '//base//'.h5dump 2>&1', exitstat=status)
         call check(s, status == 0 .and. file_has(base//'.h5dump', 'acceleration') .and. &
                    .not. (file_has(base//'.h5dump', 'nan') .or. file_has(base//'.h5dump', 'inf')), &
                    'the .h5 reads back and holds no NaN or infinity')
      else
         call skip(s, 'the .h5 holds no NaN', 'h5dump')
      end if
      deck = bar_deck(200, 5)
      deck = deck(:k)//'    PENAlty,SCALe,1e308'//nl//deck(k + 1:)
      call run_deck('penalty_overflow', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'penalty_overflow.inp:') > 0 .and. &
                 index(msg, 'not a finite stiffness') > 0, 'PENAlty,SCALe,1e308: an error naming file:line', msg)
      deck = bar_deck(200, 5)
      k = index(deck, 'DENSity 1'//nl) + len('DENSity 1') - 1
      deck = deck(:k)//'e308'//deck(k + 1:)
      call run_deck('density_overflow', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'density_overflow.inp:') > 0 .and. &
                 index(msg, 'DENSity 1.0000000E+308 gives lumped masses that are not finite') > 0, &
                 'DENSity 1e308: an error naming the MATErial record (was "total mass Infinity" and a stop '// &
                 'on the energy sums)', msg)
   end subroutine nonfinite_fields_test

   !> The last number on the lines of a file (0 if none).
   real(wp) function last_number(path) result(x)
      character(len=*), intent(in) :: path
      character(len=512) :: line
      integer :: u, ios, k
      real(wp) :: y
      x = 0.0_wp
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         do k = len_trim(line), 1, -1
            if (index(' ,:(', line(k:k)) > 0) exit
         end do
         read (line(k + 1:), *, iostat=ios) y
         if (ios == 0) x = y
      end do
      close (u)
   end function last_number

end module test_run_output
