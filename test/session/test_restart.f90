!> Restart files, signals and write failures, with the exic program built next to this driver
!> and the child program deck_run_child (which parks at a known output time, so that every
!> signal lands at a known step: no sleeps, no timing).
!>
!> The reference of every continued run is the same deck run without a stop: its .his and .ene
!> must be equal byte for byte and every dataset of its .h5 equal bit for bit (h5diff without a
!> tolerance compares exactly).
module test_restart
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use testing, only: suite_t, check, section, skip, have_command, file_text
   use deck_runner, only: run_dir, write_text, replace_first
   use scene_decks, only: sliding_blocks_deck, blocks_contact
   use exic_base_progress, only: eta_seconds, eta_known
   implicit none
   private

   public :: run_restart_tests

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: dir = run_dir//'/restart'

contains

   subroutine run_restart_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: exic, child
      call section(s, 'restart: the ETA of the progress line counts from the restart point')
      ! 10 s took the run from the restart point 0.5 to 0.6 of 1.0: 0.4 is left, 40 s
      call check(s, eta_seconds(10.0_wp, 0.6_wp, 0.5_wp, 1.0_wp) - 40.0_wp <= 1.0e-12_wp .and. &
                 eta_seconds(10.0_wp, 0.6_wp, 0.5_wp, 1.0_wp) - 40.0_wp >= -1.0e-12_wp .and. &
                 .not. eta_known(10.0_wp, 0.5_wp, 0.5_wp, 1.0_wp), 'ETA = elapsed (tmax - t)/(t - t_begin), '// &
                 'unknown before the run has advanced from where it began')
      exic = sibling('../app/exic')
      child = sibling('deck_run_child')
      if (len(exic) == 0 .or. len(child) == 0 .or. .not. have_command('h5diff')) then
         call skip(s, 'restart tests', 'the exic program, deck_run_child and h5diff', 1)
         return
      end if
      call execute_command_line('rm -rf '//dir//'; mkdir -p '//dir)
      call section(s, 'restart: seed example 7.2 stopped by SIGINT halfway, continued with --restart')
      call ex72_sigint(s, exic, child)
      call section(s, 'restart: SIGUSR1 writes a restart file and the run goes on; SIGUSR2 a status line')
      call ex72_sigusr1(s, child)
      call section(s, 'restart: loads, a driven and a free rigid body, one-point quadrature')
      call continued(s, exic, 'punch', punch_deck())
      call continued(s, exic, 'free_body', free_body_deck())
      call continued(s, exic, 'one_point', one_point_deck())
      call section(s, 'restart: a plain run (no contact, loads or rigid bodies: no work arrays of the step)')
      call continued(s, exic, 'plain', plain_deck())
      call section(s, 'restart: plastic history and Coulomb friction across the restart point')
      call continued(s, exic, 'friction_plastic', friction_plastic_deck())
      ! penalty friction under AUTOmatic: the tangential state kept per pair of surfaces
      call continued(s, exic, 'penalty_auto_friction', sliding_blocks_deck(blocks_contact(.true.), &
                     '  OUTPut,HDF5,0.02'//nl//'  SAVE,,0.2'//nl))
      call section(s, 'restart: massless contact faces (LAGRange,ENERgy) pressed across the restart point')
      call continued(s, exic, 'energy_face', energy_face_deck('  RIGId'))
      call continued(s, exic, 'energy_face_dofs', energy_face_deck('  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'))
      call check(s, shell('grep -q "stiffness rows formed again at large strain [1-9]" '//dir// &
                          '/energy_face/energy_face.out') == 0, 'energy_face: the face''s stiffness '// &
                 'is formed again during the run (its state crosses the restart point)')
      call section(s, 'restart: the corners the corner pass of an NTOS pair holds, across the restart point')
      ! test/data/stress/corner_pass_punch_372.inp, the deformable punch's corners held behind the
      ! block's surface by round-off at most steps from t = 0.45 on (K.2): without the held list in
      ! the restart file the run continued from t = 0.6 differs and its drift grows to 3.5e-2
      call continued(s, exic, 'corner_pass', replace_first(file_text('test/data/stress/corner_pass_punch_372.inp'), &
                     '  TPLOt,,1'//nl, '  TPLOt,,1'//nl//'  OUTPut,HDF5,0.1'//nl//'  SAVE,,0.6'//nl))
      call section(s, 'restart: mass damping and bulk viscosity across the restart point')
      call continued(s, exic, 'dissipation', dissipation_deck())
      call section(s, 'restart: a restart file of another deck is refused')
      call mismatch(s, exic)
      call section(s, 'restart: a later end time, a changed program refused, a new output folder')
      call extended(s, exic)
      call landed(s, exic)
      call new_folder(s, exic)
      call section(s, 'restart: a write failure (file size limit) ends the run cleanly')
      call write_failure(s, exic)
   end subroutine run_restart_tests

   !> The program `name` next to this test driver ('' when missing).
   function sibling(name) result(path)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: path
      character(len=4096) :: argv0
      logical :: exists
      call get_command_argument(0, argv0)
      path = argv0(1:index(argv0, '/', back=.true.))//name
      inquire (file=path, exist=exists)
      if (.not. exists) path = ''
   end function sibling


   !> Run `command` in bash; its exit status.
   integer function shell(command) result(code)
      character(len=*), intent(in) :: command
      call execute_command_line('bash -c '''//command//'''', exitstat=code)
   end function shell

   !> The seed's example 7.2 (inputs/paper/ex72_compliant.inp: 6 x 30 bar on bar, CFL 0.9, to
   !> t = 0.3, fields every 0.002) with SAVE,,0.15, in directory `d`.
   subroutine ex72_in(d)
      character(len=*), intent(in) :: d
      integer :: code
      code = shell('mkdir -p '//d//'/common && cp inputs/paper/common/ex72_mesh.inc '//d//'/common/')
      call write_text(d//'/ex72.inp', 'FEAP * * seed 7.2 with restart files'//nl//'  0 0 0 2 2 4'//nl// &
                      'PARAmeters'//nl//'  nsv = 30'//nl//'  cfl = 0.9'//nl//'  tend = 0.3'//nl// &
                      '  tout = 0.002'//nl//nl//'INCLude,common/ex72_mesh.inc'//nl//'CONTact'//nl// &
                      '  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
                      '  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//nl//'INCLude,common/batch.inc'//nl//'STOP')
      call write_text(d//'/common/batch.inc', 'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl// &
                      '  DT,CFL,cfl'//nl//'  TPLOt,,1'//nl//'  OUTPut,HDF5,tout'//nl//'  SAVE,,0.15'//nl// &
                      '  LOOP,,10000000'//nl//'    TIME,,tend'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
                      'END'//nl//'  disp,124,1'//nl//'  velo,124,1'//nl//'  acce,124,1'//nl//'  cont,1,1'//nl// &
                      '  cont,1,4'//nl//'  cont,1,5'//nl//'  mome,1,1'//nl//'  stre,,1,29.5,0.3333'//nl// &
                      '  disp,323,1'//nl//'  acce,330,1'//nl//'  disp,217,2'//nl)
   end subroutine ex72_in

   !> Same .his and .ene bytes and .h5 datasets in two runs `a` and `b` (base paths).
   subroutine same_outputs(s, a, b, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: a, b, what
      call check(s, shell('cmp -s '//a//'.his '//b//'.his') == 0, what//': the .his is identical')
      call check(s, shell('cmp -s '//a//'.ene '//b//'.ene') == 0, what//': the .ene is identical')
      call check(s, shell('h5diff '//a//'.h5 '//b//'.h5 > '//b//'.h5diff 2>&1') == 0, &
                 what//': every dataset of the .h5 is identical (h5diff)', b//'.h5diff')
   end subroutine same_outputs

   !> The full run; a run stopped by SIGINT after the flush that reaches its 40th output time
   !> (parked there, signalled,
   !> it stops at the end of the next step: exit 3, final state in the .h5, restart written);
   !> that run continued with --restart to the end: the same outputs as the full run.
   subroutine ex72_sigint(s, exic, child)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, child
      character(len=:), allocatable :: full, half
      real(wp) :: t_park, t_last
      integer :: code, nout, nparked
      full = dir//'/full'
      half = dir//'/half'
      call ex72_in(full)
      call ex72_in(half)
      code = shell('cd '//full//' && '//abs(exic)//' -q ex72.inp > run.log 2>&1')
      call check(s, code == 0, 'the full run ends normally', full//'/run.log')
      code = shell(abs(child)//' --child '//half//'/ex72.inp '//half//'/ex72 40 '//half//'/ready signals > '// &
                   half//'/child.log 2>&1 & pid=$!; while [ ! -e '//half//'/ready ] && [ $SECONDS -lt 120 ]; '// &
                   'do sleep 0.05; done; kill -INT $pid; wait $pid; exit $?')
      call check(s, code == 3, 'SIGINT: the run stops with exit code 3', 'exit code '//itoa(code))
      t_park = number_in(half//'/ready', 2)
      nparked = nint(number_in(half//'/ready', 1))
      call h5_last_time(half//'/ex72.h5', nout, t_last)
      call check(s, nparked >= 40 .and. nout == nparked + 1 .and. t_last > t_park, 'SIGINT: the final '// &
                 'state (the step after the signal) is the last output time of the .h5, after those '// &
                 'flushed when the run parked', 'output times '//itoa(nout)//', flushed at the park '//itoa(nparked))
      call check(s, shell('test -s '//half//'/ex72.rst') == 0 .and. &
                 shell('grep -q "interrupted by a signal" '//half//'/ex72.out') == 0, &
                 'SIGINT: the restart file is written and the .out says why the run stopped')
      code = shell('cd '//half//' && '//abs(exic)//' -q ex72.inp --restart ex72.rst > run.log 2>&1')
      call check(s, code == 0, 'the run continued with --restart ends normally', half//'/run.log')
      call same_outputs(s, full//'/ex72', half//'/ex72', 'to the end against halfway + restart')
   end subroutine ex72_sigint

   !> SIGUSR1 after the flush that reaches the 20th output time: a restart file at the next step, and the run goes on
   !> to the end with the same outputs as the full run.
   subroutine ex72_sigusr1(s, child)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: child
      character(len=:), allocatable :: d
      integer :: code
      real(wp) :: t_park, t_rst
      d = dir//'/usr1'
      call ex72_in(d)
      code = shell(abs(child)//' --child '//d//'/ex72.inp '//d//'/ex72 20 '//d//'/ready signals > '// &
                   d//'/child.log 2>&1 & pid=$!; while [ ! -e '//d//'/ready ] && [ $SECONDS -lt 120 ]; '// &
                   'do sleep 0.05; done; kill -USR1 $pid; kill -USR2 $pid; wait $pid; exit $?')
      call check(s, code == 0, 'SIGUSR1: the run goes on to its end', 'exit code '//itoa(code))
      call check(s, shell('grep -q "^exic: status: t = .*, step .*, dt = .*, energy balance .*ETA" '//d// &
                          '/child.log') == 0, 'SIGUSR2: a status line (t, step, dt, energy balance, ETA)', &
                 d//'/child.log')
      ! restart files: SIGUSR1 (the step after the park), SAVE,,0.15, the end
      t_park = number_in(d//'/ready', 2)
      code = shell('grep "^restart file" '//d//'/ex72.out | head -1 | sed "s/.* at t = \([^,]*\),.*/\1/" > '// &
                   d//'/restart_t')
      t_rst = number_in(d//'/restart_t', 1)
      call check(s, shell('test "$(grep -c "^restart file" '//d//'/ex72.out)" = 3') == 0 .and. &
                 t_rst > t_park .and. t_rst < t_park + 1.0e-3_wp .and. t_park < 0.15_wp, &
                 'SIGUSR1: a restart file is written at the step after the signal (within one step, 7.2e-4, '// &
                 'of the output time the run parked at)', 'parked at t = '//rtoa(t_park)//', restart at '//rtoa(t_rst))
      call same_outputs(s, dir//'/full/ex72', d//'/ex72', 'SIGUSR1 leaves the run unchanged')
   end subroutine ex72_sigusr1

   !> `deck` (SAVE,,dt at its middle) run to the end; then continued from its middle restart
   !> file (<stem>.rst.prev) over the outputs it wrote: the outputs of the full run again.
   subroutine continued(s, exic, name, deck)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, name, deck
      character(len=:), allocatable :: d
      integer :: code
      d = dir//'/'//name
      code = shell('mkdir -p '//d//'/ref')
      call write_text(d//'/'//name//'.inp', deck)
      code = shell('cd '//d//' && '//abs(exic)//' -q '//name//'.inp > run.log 2>&1')
      call check(s, code == 0, name//': the full run ends normally', d//'/run.log')
      code = shell('cd '//d//' && cp '//name//'.his '//name//'.ene '//name//'.h5 ref/ && mv '//name// &
                   '.rst.prev middle.rst && '//abs(exic)//' -q '//name//'.inp --restart middle.rst > restart.log 2>&1')
      call check(s, code == 0, name//': the run continued from its middle ends normally', d//'/restart.log')
      call check(s, shell('grep -q "restarted from middle.rst" '//d//'/'//name//'.out') == 0, &
                 name//': the .out says where the run was continued from')
      call same_outputs(s, d//'/ref/'//name, d//'/'//name, name)
   end subroutine continued

   !> A restart file of the 7.2 deck offered to a deck with one node moved, and to one with
   !> another end time: exit 1, naming what differs.
   subroutine mismatch(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=:), allocatable :: d
      integer :: code
      d = dir//'/other'
      call ex72_in(d)
      code = shell('cd '//d//' && sed -i "s/tend = 0.3/tend = 0.31/" ex72.inp && cp ../full/ex72.rst end.rst && '// &
                   abs(exic)//' -q ex72.inp --restart end.rst > run.log 2>&1')
      call check(s, code == 1 .and. shell('grep -q "the BATCh commands differ where a restart cannot follow '// &
                                          'them: TIME at .*batch.inc:9 .*shortened to land on the end time.*'// &
                                          'rst.land" '//d//'/run.log') == 0, 'another end time from the file of '// &
                 'the end of a DT,CFL run (its last steps landed on the end time) without its .land file: '// &
                 'refused (exit 1), the TIME and the .land file named', d//'/run.log')
      code = shell('cd '//d//' && sed -i "s/tend = 0.31/tend = 0.3/" ex72.inp && '// &
                   'sed -i "s|^    1,0,-hgt/2|    1,-0.01,-hgt/2|" common/ex72_mesh.inc && '//abs(exic)// &
                   ' -q ex72.inp --restart ../full/ex72.rst > run2.log 2>&1')
      call check(s, code == 1 .and. shell('grep -q "another deck: the node coordinates differ" '//d// &
                                          '/run2.log') == 0, &
                 'a node moved: refused (exit 1), the node coordinates named', d//'/run2.log')
   end subroutine mismatch

   !> Seed 7.2 to t = 0.2 (SAVE,,0.15) continued from its restart file of t = 0.15 with the end
   !> time 0.3: the outputs of the run to 0.3 from the start (dir/full), bit for bit. From the
   !> same file, another CFL number is refused, naming the DT and its line.
   subroutine extended(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=:), allocatable :: d
      integer :: code
      d = dir//'/extended'
      call ex72_in(d)
      code = shell('cd '//d//' && sed -i "s/tend = 0.3/tend = 0.2/" ex72.inp && '//abs(exic)//' -q ex72.inp '// &
                   '> short.log 2>&1 && cp ex72.rst.prev at015.rst && mkdir -p short && cp ex72.* short/')
      call check(s, code == 0, 'the run to 0.2 ends normally', d//'/short.log')
      code = shell('cd '//d//' && sed -i "s/cfl = 0.9/cfl = 0.8/; s/tend = 0.2/tend = 0.3/" ex72.inp && '// &
                   abs(exic)//' -q ex72.inp --restart at015.rst > dt.log 2>&1')
      call check(s, code == 1 .and. shell('grep -q "DT at .*batch.inc:4 (9.0*E-01 -> 8.0*E-01): it ran '// &
                                          'before the restart point" '//d//'/dt.log') == 0 .and. &
                 shell('cmp -s '//d//'/ex72.his '//d//'/short/ex72.his') == 0 .and. &
                 shell('grep -q " wall " '//d//'/dt.log') /= 0, 'another CFL number: refused (exit 1), the DT '// &
                 'named with its line and values; the files are left as they were; no progress line', d//'/dt.log')
      code = shell('cd '//d//' && sed -i "s/cfl = 0.8/cfl = 0.9/" ex72.inp && '//abs(exic)// &
                   ' -q ex72.inp --restart at015.rst > run.log 2>&1')
      call check(s, code == 0 .and. shell('grep -q "the BATCh program differs from the restart file.s: TIME at '// &
                                          '.*batch.inc:9 (2.0*E-01 -> 3.0*E-01): end time; the run resumes after '// &
                                          'the step of FORM at .*batch.inc:10" '//d//'/ex72.out') == 0, &
                 'a later end time: the run continues, its .out says what changed and where it resumes', &
                 d//'/run.log')
      call same_outputs(s, dir//'/full/ex72', d//'/ex72', 'end time 0.2 -> 0.3 at t = 0.15')
   end subroutine extended

   !> Seed 7.2 to t = 0.2 (DT,CFL) with SAVE after the loop only: its end file (the last steps
   !> landed on 0.2) with the end time 0.3 continues from <file>.land, the step before the
   !> landing: the outputs of the run to 0.3 from the start (dir/full), bit for bit.
   subroutine landed(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=:), allocatable :: d
      integer :: code
      d = dir//'/landed'
      call ex72_in(d)
      code = shell('cd '//d//' && sed -i "/SAVE,,0.15/d; s/^  NEXT$/  NEXT\n  SAVE/" common/batch.inc && '// &
                   'sed -i "s/tend = 0.3/tend = 0.2/" ex72.inp && '//abs(exic)//' -q ex72.inp > short.log 2>&1')
      call check(s, code == 0 .and. shell('test -f '//d//'/ex72.rst.land -a ! -e '//d//'/ex72.rst.prev') == 0 .and. &
                 shell('grep -q "^  SAVE$" '//d//'/common/batch.inc') == 0, 'the run to 0.2 with SAVE at its '// &
                 'end writes <stem>.rst and <stem>.rst.land (the step before the landing on 0.2)', d//'/short.log')
      code = shell('cd '//d//' && sed -i "s/tend = 0.2/tend = 0.3/" ex72.inp && '//abs(exic)// &
                   ' -q ex72.inp --restart ex72.rst > run.log 2>&1')
      call check(s, code == 0 .and. shell('grep -q "a later end time continues from ex72.rst.land" '//d// &
                                          '/run.log') == 0, 'the end time 0.2 -> 0.3 from the end file: '// &
                 'continued from ex72.rst.land, said on the console', d//'/run.log')
      call same_outputs(s, dir//'/full/ex72', d//'/ex72', 'end file of a DT,CFL run, end time 0.2 -> 0.3')
   end subroutine landed

   !> The restart file of t = 0.15 (extended) alone in a new folder with the deck to 0.3: new
   !> .his, .ene and .h5 from the restart point, whose rows and output times are those of the
   !> run to 0.3 from the start (dir/full) from there on; a folder with the .his and no .ene is
   !> refused, naming both.
   subroutine new_folder(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=:), allocatable :: d, full
      integer :: code
      d = dir//'/new_folder'
      full = abs(dir//'/full/ex72')
      call ex72_in(d)
      code = shell('cd '//d//' && cp ../extended/at015.rst . && '//abs(exic)//' ex72.inp --restart at015.rst '// &
                   '> run.log 2>&1')
      call check(s, code == 0 .and. shell('grep -q "new output files start at the restart point (t = 1.5.*): '// &
                                          '.*ex72.his, .*ex72.ene, .*ex72.h5 hold the run from there on" '//d// &
                                          '/run.log') == 0 .and. shell('grep -q "new output files start" '//d// &
                                                                       '/ex72.out') == 0, &
                 'a new folder: the run continues, saying on the console and in the .out that new files '// &
                 'start at the restart point', d//'/run.log')
      call check(s, shell('cd '//d//' && test "$(head -1 ex72.his)" = "$(head -1 '//full//'.his)" && '// &
                          'n=$(($(wc -l < ex72.his) - 1)) && test $n -gt 10 && '// &
                          'cmp -s <(tail -n +2 ex72.his) <(tail -n $n '//full//'.his) && '// &
                          'n=$(($(wc -l < ex72.ene) - 1)) && cmp -s <(tail -n +2 ex72.ene) <(tail -n $n '// &
                          full//'.ene)') == 0, 'a new folder: the .his and .ene are the header and the last '// &
                 'rows of those of the run to 0.3 from the start, byte for byte')
      call check(s, same_tail(d//'/ex72.h5', full//'.h5', '/time') .and. &
                 same_tail(d//'/ex72.h5', full//'.h5', '/fields/displacement') .and. &
                 same_tail(d//'/ex72.h5', full//'.h5', '/fields/velocity') .and. &
                 same_tail(d//'/ex72.h5', full//'.h5', '/energies/kinetic'), 'a new folder: the .h5 holds '// &
                 'the last output times of the run to 0.3 from the start (time, displacement, velocity, '// &
                 'kinetic energy, value for value at 17 digits)')
      code = shell('cd '//d//' && mkdir -p partial && cp ex72.inp at015.rst partial/ && cp -r common partial/ && '// &
                   'cp ../extended/short/ex72.his partial/ && cd partial && '//abs(exic)// &
                   ' ex72.inp --restart at015.rst > run.log 2>&1')
      call check(s, code == 1 .and. shell('grep -q "ex72.ene, ex72.h5 missing while ex72.his present" '//d// &
                                          '/partial/run.log') == 0 .and. &
                 shell('grep -q " wall " '//d//'/partial/run.log') /= 0, 'the .his without the .ene: refused '// &
                 '(exit 1), naming the files; no progress line (its wall time was the time since boot)', &
                 d//'/partial/run.log')
   end subroutine new_folder

   !> Whether every value of dataset `name` of `short` (a .h5) equals the last ones of the same
   !> dataset of `long` (h5dump at 17 digits), and there are some.
   logical function same_tail(short, long, name) result(same)
      character(len=*), intent(in) :: short, long, name
      character(len=*), parameter :: dump = 'h5dump -d NAME -y -w 0 -m %.17g FILE 2>/dev/null | '// &
                                            'sed -n "/DATA {/,/}/p" | tr -s ", " "\n\n" | grep -E "^-?[0-9]"'
      same = shell('a=$('//fill(dump, name, short)//'); n=$(echo "$a" | wc -l); test $n -gt 2 && '// &
                   'test "$a" = "$('//fill(dump, name, long)//' | tail -n $n)"') == 0
   end function same_tail

   !> `pattern` with NAME and FILE replaced.
   function fill(pattern, name, file) result(t)
      character(len=*), intent(in) :: pattern, name, file
      character(len=:), allocatable :: t
      integer :: i
      t = pattern
      i = index(t, 'NAME')
      t = t(1:i - 1)//name//t(i + 4:)
      i = index(t, 'FILE')
      t = t(1:i - 1)//file//t(i + 4:)
   end function fill

   !> The 7.2 deck under a file size limit of 2000 kB (RLIMIT_FSIZE: writes past it fail with
   !> EFBIG, deterministically, as on a full disk): exit 1 (no signal), a message naming the file,
   !> the text outputs and the XDMF files written before intact and parseable. The field file is
   !> made with room for every output time the BATCh program will write (11.6 MB here), so a
   !> full disk would stop the deck as written before its first step; without an end time in the
   !> program (TIME alone, the LOOP bounding the run) the room is 16 output times (1.2 MB) and the
   !> failure comes mid-run, at the 17th, when the room would double to 2.4 MB.
   subroutine write_failure(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=:), allocatable :: d
      integer :: code
      d = dir//'/full_disk'
      call ex72_in(d)
      code = shell('cd '//d//' && sed -i "s/TIME,,tend/TIME/; s/LOOP,,10000000/LOOP,,2000/" common/batch.inc'// &
                   ' && ulimit -f 2000 && '//abs(exic)//' -q ex72.inp > run.log 2>&1')
      call check(s, code == 1, 'a write past the limit: exit code 1, no signal', 'exit code '//itoa(code))
      call check(s, shell('grep -q "ex72\.h5" '//d//'/run.log') == 0, 'the message names the file', &
                 d//'/run.log')
      call check(s, shell('head -c 2000 '//d//'/ex72.out | grep -q "seed 7.2 with restart files"') == 0 .and. &
                 shell('test "$(wc -l < '//d//'/ex72.his)" -gt 2') == 0, &
                 'the .out (deck echo) and the .his rows written before the failure are kept')
      call write_text(d//'/parse.py', 'import sys, xml.dom.minidom as m'//nl//'for f in sys.argv[1:]: m.parse(f)')
      call check(s, shell('python3 '//d//'/parse.py '//d//'/ex72.xdmf '//d//'/ex72_series.xdmf') == 0, &
                 'both XDMF files parse')
   end subroutine write_failure

   !> Absolute path of `p` (relative to the working directory).
   function abs(p) result(a)
      character(len=*), intent(in) :: p
      character(len=:), allocatable :: a
      character(len=4096) :: cwd
      if (p(1:1) == '/') then
         a = p
      else
         call getcwd(cwd)
         a = trim(cwd)//'/'//p
      end if
   end function abs

   !> The k-th blank-separated number of the first line of `path` (0 when unreadable).
   real(wp) function number_in(path, k) result(x)
      character(len=*), intent(in) :: path
      integer, intent(in) :: k
      real(wp) :: v(8)
      integer :: u, ios
      x = 0.0_wp
      v = 0.0_wp
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      read (u, *, iostat=ios) v(1:k)
      close (u)
      x = v(k)
   end function number_in

   !> Number of output times of a .h5 and the last one, with h5dump.
   subroutine h5_last_time(h5, n, t)
      character(len=*), intent(in) :: h5
      integer, intent(out) :: n
      real(wp), intent(out) :: t
      character(len=:), allocatable :: tmp
      integer :: u, ios
      real(wp) :: x
      tmp = h5//'.times'
      call execute_command_line('h5dump -d /time -y -w 0 -m "%.17g" '//h5// &
                                ' 2>/dev/null | sed -n "/DATA {/,/}/p" | tr -s ", " "\n\n" | '// &
                                'grep -E "^-?[0-9]" > '//tmp)
      n = 0
      t = -1.0_wp
      open (newunit=u, file=tmp, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, *, iostat=ios) x
         if (ios /= 0) exit
         n = n + 1
         t = x
      end do
      close (u)
   end subroutine h5_last_time

   ! ---------------------------------------------------------------------------- decks

   !> inputs/examples/punch.inp to t = 0.45 with SAVE,,0.3: gravity under a function, a rigid
   !> punch driven by MOTIon (it starts moving at 0.3), contact with a rigid floor.
   function punch_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * punch with restart files'//nl//'  0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1.0e4 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//nl//'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,10,5,1,1,1'//nl// &
             '    1,0,0'//nl//'    2,2,0'//nl//'    3,2,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,1,301,51,2'//nl//'    1,0.8,1'//nl//'    2,1.2,1'//nl// &
             '    3,1.2,1.2'//nl//'    4,0.8,1.2'//nl//nl//'REGIon,3'//nl//'BLOCk'//nl// &
             '  CARTesian,4,1,401,53,2'//nl//'    1,-0.5,-0.2'//nl//'    2,2.5,-0.2'//nl//'    3,2.5,0'//nl// &
             '    4,-0.5,0'//nl//nl//'GRAVity,0,-10,1'//nl//'MOTIon,REGIon,2,0,-0.2,0,2'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  SURFace,3'//nl//'    REGIon,3'//nl//'  PAIR,1,NTOS,2,1'//nl//'  PAIR,2,NTOS,1,3'//nl// &
             'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1,2'//nl//'  DT,CFL,0.9'//nl// &
             '  TPLOt,,1'//nl//'  OUTPut,HDF5,0.01'//nl//'  SAVE,,0.3'//nl//'  LOOP,,1000000'//nl// &
             '    TIME,,0.45'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '2, 0'//nl//'0, 0, 0.2, 1'//nl//nl//'2, 0'//nl//'0, 0, 0.3, 0, 0.35, 1'//nl//nl// &
             '  reac,REGIon,2,2'//nl//'  cont,1,3'//nl//'  reac,REGIon,3,2'//nl//'  rigi,2,2'//nl// &
             '  disp,56,2'//nl//nl//'STOP'
   end function punch_deck

   !> A free rigid square (RIGId,FREE) thrown at a free deformable bar,
   !> symmetric contact, to t = 1.2 with SAVE,,0.7 (after the impact began).
   function free_body_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * free rigid body with restart files'//nl//'  0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl//'REGIon,1'//nl//'BLOCk'//nl// &
             '  CARTesian,12,3,1,1,1'//nl//'    1,0,0'//nl//'    2,4,0'//nl//'    3,4,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,101,37,2'//nl//'    1,4.3,0.2'//nl//'    2,5.1,0.3'//nl// &
             '    3,5.0,1.1'//nl//'    4,4.2,1.0'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,2,-1,0.1'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,SYMMetric,1,2'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl// &
             '  TPLOt,,1'//nl//'  OUTPut,HDF5,0.05'//nl//'  SAVE,,0.7'//nl//'  LOOP,,1000000'//nl// &
             '    TIME,,1.2'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  rigi,2,1'//nl//'  rigi,2,3'//nl//'  rigi,2,6'//nl//'  disp,52,1'//nl//'  cont,1,1'//nl//nl//'STOP'
   end function free_body_deck

   !> A 12 x 2 bar with one-point quadrature and hourglass control against a rigid wall, fixed
   !> step, to 60 steps with SAVE,,0.03.
   function one_point_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * one-point quadrature with restart files'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl// &
             '    QUADrature 1'//nl//'    HOURglass 0.1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,12,2,0,0,1'//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,1,2,0,0,2'//nl//'    1,6.01,-1'//nl//'    2,7,-1'//nl// &
             '    3,7,2'//nl//'    4,6.01,2'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,1,0'//nl//nl// &
             'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,,1e-3'//nl//'  TPLOt,,1'//nl//'  OUTPut,HDF5,2e-3'//nl//'  SAVE,,0.03'//nl// &
             '  LOOP,,60'//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,13,1'//nl//'  velo,13,1'//nl//'  stre,5,1'//nl//'  cont,1,1'//nl//nl//'STOP'
   end function one_point_deck

   !> A 2x2 bar (12 x 2) held at x = 0 and moving at (0.5, 0.2) at t = 0, nothing else: every step is plain
   !> (src/exic/explicit/step.f90, plain_step), so the stepper has no work arrays to save.
   function plain_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * a plain run with restart files'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,12,2,0,0,1'//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,1'//nl//'    4,0,1'//nl//nl// &
             'EBOUndary'//nl//'  1,0,1,1'//nl//nl//'INITial,VELOcity'//nl//'  MATErial,1,0.5,0.2'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  OUTPut,HDF5,2e-3'//nl// &
             '  SAVE,,0.03'//nl//'  LOOP,,100000'//nl//'    TIME,,0.06'//nl//'    FORM,EXPLicit'//nl// &
             '  NEXT'//nl//'END'//nl//'  disp,13,1'//nl//'  velo,27,2'//nl//'  stre,5,1'//nl//nl//'STOP'
   end function plain_deck

   !> one_point_deck with DAMPing MASS 20 until 0.045 and VISCosity BULK (doc/damping.md): the
   !> damping ends and the bar is compressed after the restart point (0.03); their nodal forces
   !> and energies cross it.
   function dissipation_deck() result(deck)
      character(len=:), allocatable :: deck
      character(len=*), parameter :: hg = '    HOURglass 0.1'//nl
      integer :: k
      deck = one_point_deck()
      k = index(deck, hg) + len(hg)
      deck = deck(:k - 1)//'    DAMPing MASS 20 0.045'//nl//'    VISCosity BULK'//nl//deck(k:)
   end function dissipation_deck

   !> A bar (12 x 2, neo-Hookean) at 1 against a rigid wall 0.01 away, its struck end a
   !> massless contact face (LAGRange,ENERgy, doc/impact.md section 3): contact from t = 0.01
   !> lasts past the end (2 L/c = 0.33), so the face is pressed before and after the restart
   !> point (t = 0.03 of 0.06). wall: the wall's material records (RIGId; or a solid, which makes
   !> the struck face massless along its normal only and its lateral dofs keep their mass, with
   !> masses per dof in the state, doc/impact.md section 3.1).
   function energy_face_deck(wall) result(deck)
      character(len=*), intent(in) :: wall
      character(len=:), allocatable :: deck
      deck = 'FEAP * * bar on a wall with a massless contact face, restart files'//nl//'0 0 0 2 2 4'//nl// &
             'PARAmeters'//nl//'  nx = 12'//nl//'  ny = 2'//nl//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//wall//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,nx,ny,0,0,1'//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,1,2,0,0,2'//nl//'    1,6.01,-1'//nl//'    2,7,-1'//nl// &
             '    3,7,2'//nl//'    4,6.01,2'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,1,0'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    FACEts'//nl//'      1,nx+1,nx+1,2*(nx+1)'//nl// &
             '      ny,nx+1,ny*(nx+1),(ny+1)*(nx+1)'//nl//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'    LAGRange,ENERgy'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,,1e-3'//nl//'  TPLOt,,1'//nl//'  OUTPut,HDF5,2e-3'//nl//'  SAVE,,0.03'//nl// &
             '  LOOP,,60'//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,26,1'//nl//'  velo,26,1'//nl//'  acce,26,1'//nl//'  cont,1,1'//nl//'  cont,1,4'//nl//nl//'STOP'
   end function energy_face_deck

   !> A plastic block (J2, history per point) that lands on a rigid floor and slides on it with
   !> Coulomb friction under gravity: it yields and slides both before and after the restart
   !> point (t = 0.03 of 0.06).
   function friction_plastic_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * plastic block sliding with friction, restart files'//nl // &
             '0 0 0 2 2 4'//nl // &
             'MATErial,1'//nl // &
             '  SOLId'//nl // &
             '    ELAStic NEOHookean 1000 0.3'//nl // &
             '    DENSity 1'//nl // &
             '    PLAStic MISEs 5'//nl // &
             '    PLAStic HARDening 10 0'//nl // &
             ''//nl // &
             'MATErial,2'//nl // &
             '  RIGId'//nl // &
             '    DENSity 1'//nl // &
             ''//nl // &
             'REGIon,1'//nl // &
             'BLOCk'//nl // &
             '  CARTesian,4,2,0,0,1'//nl // &
             '    1,0,0.01'//nl // &
             '    2,2,0.01'//nl // &
             '    3,2,1.01'//nl // &
             '    4,0,1.01'//nl // &
             ''//nl // &
             'REGIon,2'//nl // &
             'BLOCk'//nl // &
             '  CARTesian,1,1,0,0,2'//nl // &
             '    1,-1,-0.5'//nl // &
             '    2,8,-0.5'//nl // &
             '    3,8,0'//nl // &
             '    4,-1,0'//nl // &
             ''//nl // &
             'INITial,VELOcity'//nl // &
             '  REGIon,1,2,-1'//nl // &
             ''//nl // &
             'GRAVity,0,-10'//nl // &
             ''//nl // &
             'CONTact'//nl // &
             '  SURFace,1'//nl // &
             '    REGIon,1'//nl // &
             '  SURFace,2'//nl // &
             '    REGIon,2'//nl // &
             '  PAIR,1,NTOS,1,2'//nl // &
             '  FRICtion,COULomb,0.3'//nl // &
             'END CONTact'//nl // &
             ''//nl // &
             'END'//nl // &
             'BATCh'//nl // &
             '  DT,,1e-3'//nl // &
             '  TPLOt,,1'//nl // &
             '  OUTPut,HDF5,2e-3'//nl // &
             '  SAVE,,0.03'//nl // &
             '  LOOP,,60'//nl // &
             '    TIME'//nl // &
             '    FORM,EXPLicit'//nl // &
             '  NEXT'//nl // &
             'END'//nl // &
             '  disp,1,1'//nl // &
             '  velo,1,1'//nl // &
             '  stre,1,8'//nl // &
             '  cont,1,8'//nl // &
             ''//nl // &
             'STOP'//nl
   end function friction_plastic_deck

end module test_restart
