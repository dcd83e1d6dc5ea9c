!> The exic program on several MPI ranks (doc/parallel.md): a family of small scenes (AUTOmatic
!> contact between bodies given in any order with gravity, Coulomb friction on a rigid floor,
!> a free rigid disk striking a bar, one-point elements with no contact, bars with bulk
!> viscosity and mass damping in AUTOmatic contact, a U whose arms meet in SELF contact) run by
!> `mpirun -np P` for P = 1, 2, 3, 4 must write .his and .ene files equal byte for byte to
!> those of the same program run without mpirun (one rank); the report names the decomposition
!> (a cut that is not empty: the partition boundaries cross the bodies and their contact
!> surfaces); the decks with element history (plastic, hypoelastic) of test_mpi_family, their
!> fields and restarts across rank counts; the decks of inputs/ of test_mpi_decks, one for each
!> feature that inputs/ has; a deck with a feature not yet supported on several ranks is refused
!> with its name.
!>
!> Plain scenes (no contact, no loads: doc/parallel.md, "Divided nodes") run with the nodal
!> state divided in chunk ranges: two BLOCks of 2x2 and one-point elements with a gap in the
!> node numbers, a fixed edge and its reaction, histories every 3 steps, fields (their .h5
!> datasets equal too, h5dump with 17 digits) and a velocity set between steps; a small
!> one-point block whose nodes are all in one chunk (rank 0 owns them all); and a plain deck
!> with VISCosity BULK and DAMPing MASS, which keeps the replicated state (METIS parts).
!>
!> Skipped, with the reason, when mpirun is missing (the Makefile installs openmpi-bin).
module test_mpi
   use testing, only: suite_t, check, section, skip, have_command, file_text
   use exic_base_strings, only: itoa
   use deck_runner, only: run_dir, write_text
   use test_mpi_family, only: run_mpi_family, FAMILY_CHECKS
   use test_mpi_decks, only: run_mpi_decks, DECK_CHECKS, count_lines
   implicit none
   private

   public :: run_mpi_tests

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: MPIRUN = 'mpirun --oversubscribe --allow-run-as-root'
   character(len=*), parameter :: HEAD = 'FEAP * * mpi scene'//nl//'0 0 0 2 2 4'//nl
   !> Checks of the suite: 13 per scene, 1 of the dissipation scene's columns, 1 of the self
   !> contact's force, the family's, 1
   !> of the refusal, 2 of the failure on one rank, 3 of the .h5 files, 7 of the unstable scene,
   !> the decks of inputs/.
   integer, parameter :: NCHECKS = 8*13 + 1 + 1 + FAMILY_CHECKS + 1 + 2 + 3 + 7 + DECK_CHECKS

contains

   subroutine run_mpi_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: exic
      character(len=*), parameter :: names(8) = [character(len=12) :: 'auto', 'friction', 'free_rigid', 'one_point', &
                                                 'dissipation', 'plain_blocks', 'plain_bulk', 'self']
      integer :: k
      call section(s, 'mpi: mpirun -np 1..4 writes the serial .his and .ene byte for byte')
      exic = exic_program()
      if (len(exic) == 0) then
         call skip(s, 'decks on several ranks', 'the exic program next to the tests', NCHECKS)
         return
      end if
      if (.not. have_command('mpirun')) then
         call skip(s, 'decks on several ranks', 'mpirun (Debian openmpi-bin, which the Makefile installs)', NCHECKS)
         return
      end if
      do k = 1, size(names)
         call scene_test(s, exic, trim(names(k)))
      end do
      call unstable_test(s, exic)
      call section(s, 'mpi: plastic and hypoelastic bodies, their fields and restarts across rank counts')
      call run_mpi_family(s, exic)
      call section(s, 'mpi: decks of inputs/ (LAGRange,ENERgy, penalty, TIE, SYMMetric, driven punch, '// &
                   'gravity, plasticity, axisymmetry) on 1..4 ranks')
      call run_mpi_decks(s, exic)
      call refusal_test(s, exic)
      call rank_failure_test(s, exic)
   end subroutine run_mpi_tests

   !> The exic program built with the tests ('' when there is none).
   function exic_program() result(path)
      character(len=:), allocatable :: path
      character(len=4096) :: argv0
      logical :: exists
      call get_command_argument(0, argv0)
      path = argv0(1:index(argv0, '/', back=.true.))//'../app/exic'
      inquire (file=path, exist=exists)
      if (.not. exists) path = ''
   end function exic_program

   !> A scene of the family by name.
   function scene(name) result(deck)
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: deck
      character(len=*), parameter :: solid1 = 'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'// &
                                              nl//'    DENSity 1'//nl
      select case (name)
      case ('auto')
         ! three bodies, numbered right to left: a one-point bar (nu 0.3), a 2x2 bar (nu 0.45)
         ! moving into it, a rigid wall; AUTOmatic contact and gravity
         deck = HEAD//solid1//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl//nl// &
                'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 2000 0.45'//nl//'    DENSity 1'//nl//nl// &
                'MATErial,3'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
                'REGIon,1'//nl//block(12, 4, 1, 2.05, 0.0, 5.05, 1.0)// &
                'REGIon,2'//nl//block(10, 4, 2, 0.0, 0.0, 2.0, 1.0)// &
                'REGIon,3'//nl//block(1, 2, 3, 5.1, -1.0, 6.0, 2.0)// &
                'INITial,VELOcity'//nl//'  REGIon,2,2,0'//nl//'  REGIon,1,0.5,0'//nl//nl// &
                'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'GRAVity,0,-10'//nl//nl//'END'//nl// &
                batch('0.3')//'  disp,5,1'//nl//'  velo,60,2'//nl//nl//'STOP'
      case ('friction')
         ! a 2x2 bar sliding on a rigid floor it touches at t = 0: NTOS with Coulomb friction
         deck = HEAD//solid1//nl//'MATErial,2'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
                'REGIon,1'//nl//block(16, 3, 1, 0.0, 0.0, 4.0, 0.75)// &
                'REGIon,2'//nl//block(2, 1, 2, -1.0, -0.5, 6.0, 0.0)// &
                'INITial,VELOcity'//nl//'  REGIon,1,3,-1'//nl//nl// &
                'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
                '  PAIR,1,NTOS,1,2'//nl//'    FRICtion,COULomb,0.3'//nl//'END CONTact'//nl//nl// &
                'GRAVity,0,-10'//nl//nl//'END'//nl//batch('0.15')//'  disp,3,1'//nl//'  cont,1,1'//nl//nl//'STOP'
      case ('free_rigid')
         ! a free rigid disk (three dofs) striking a free 2x2 bar, SYMMetric pair
         deck = HEAD//solid1//nl//'MATErial,2'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl// &
                'REGIon,1'//nl//block(16, 4, 1, 0.0, 0.0, 4.0, 1.0)// &
                'SHIFt,4.52,0.8'//nl//'REGIon,2'//nl//'BLOCk'//nl//'  POLAr,2,32,0,0,2'//nl// &
                '    1,0.1,0'//nl//'    2,0.5,0'//nl//'    3,0.5,360'//nl//'    4,0.1,360'//nl//nl// &
                'INITial,VELOcity'//nl//'  REGIon,2,-2,0.5'//nl//nl// &
                'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
                '  PAIR,1,SYMMetric,1,2'//nl//'END CONTact'//nl//'END'//nl//'TIE,REGIon,2,2'//nl// &
                batch('0.08')//'  disp,10,1'//nl//'  velo,80,2'//nl//nl//'STOP'
      case ('self')
         ! a U of three blocks of one material, tied (TIE), whose arms swing toward each other
         ! and meet: PAIR,SELF on the surface of every region (the U of the contact suite, its
         ! mesh three times finer, 8 blocks of elements); nodes 224 and 309 are the arms' inner
         ! top corners
         deck = HEAD//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 100 0.3'//nl//'    DENSity 1'//nl// &
                nl//block(18, 6, 1, 0.0, 0.0, 3.0, 1.0)//block(6, 12, 1, 0.0, 1.0, 1.0, 3.0)// &
                block(6, 12, 1, 2.0, 1.0, 3.0, 3.0)//'INITial,VELOcity'//nl//'  134,1,1,0'//nl//'  224,0,1,0'//nl// &
                '  225,1,-1,0'//nl//'  315,0,-1,0'//nl//nl//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,0'//nl// &
                '  PAIR,1,SELF,1'//nl//'END CONTact'//nl//nl//'END'//nl//'TIE'//nl//batch('1.5')// &
                '  disp,224,1'//nl//'  disp,309,1'//nl//'  cont,1,1'//nl//nl//'STOP'
      case ('dissipation')
         ! the scene 'auto' with VISCosity BULK on both bars (the default and given q1 q2) and
         ! DAMPing MASS on the one-point bar until t = 0.15: the viscous forces of the blocks
         ! exchanged, the damping on every rank, their .ene columns
         deck = HEAD//solid1//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl//'    VISCosity BULK'//nl// &
                '    DAMPing MASS 2 0.15'//nl//nl// &
                'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 2000 0.45'//nl//'    DENSity 1'//nl// &
                '    VISCosity BULK 2 0.1'//nl//nl// &
                'MATErial,3'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
                'REGIon,1'//nl//block(24, 6, 1, 2.05, 0.0, 5.05, 1.0)// &
                'REGIon,2'//nl//block(20, 6, 2, 0.0, 0.0, 2.0, 1.0)// &
                'REGIon,3'//nl//block(1, 2, 3, 5.1, -1.0, 6.0, 2.0)// &
                'INITial,VELOcity'//nl//'  REGIon,2,4,0'//nl//'  REGIon,1,1,0'//nl//nl// &
                'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'GRAVity,0,-10'//nl//nl//'END'//nl// &
                batch('0.3')//'  disp,5,1'//nl//'  velo,60,2'//nl//nl//'STOP'
      case ('plain_blocks', 'plain_unstable')
         ! plain steps, the nodal state divided: a 2x2 block (nu 0.3) with its bottom edge fixed
         ! and a one-point block (nu 0.45) above it, whose nodes start at 2500 (nodes 1626-2499
         ! are used by no element): 4124 nodes, 5 chunks; initial velocities that vary linearly
         ! with the node number (every element deforms); histories every 3 steps (nodes at chunk
         ! boundaries), fields, the upper block stopped between two loops (INITial,REGIon,2,0,0);
         ! 'plain_unstable': the same with histories every step and DT,,0.0025 (2.5 x the
         ! stable step) between the loops: the energy guard warns, then stops the run (both
         ! name the element whose nodes carry the most kinetic energy: every node read)
         deck = HEAD//solid1//nl//'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 2000 0.45'//nl// &
                '    DENSity 1'//nl//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl//nl// &
                'REGIon,1'//nl//block(64, 24, 1, 0.0, 0.0, 8.0, 3.0)// &
                'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,64,24,2500,0,2'//nl//'    1,0.0,3.5'//nl// &
                '    2,8.0,3.5'//nl//'    3,8.0,6.5'//nl//'    4,0.0,6.5'//nl//nl// &
                'BOUNdary'//nl//'  1,1,1,1'//nl//'  65,0,1,1'//nl//nl// &
                'INITial,VELOcity'//nl//'  1,1,1,2'//nl//'  1625,0,-1,-2'//nl//'  2500,1,-1,0.5'//nl// &
                '  4124,0,1,-0.5'//nl//nl//'END'//nl// &
                'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,'//merge('3', '1', name == 'plain_blocks')//nl// &
                '  OUTPut,HDF5,0.004'//nl// &
                '  LOOP,,100000'//nl//'    TIME,,0.02'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
                merge('  INITial,REGIon,2,0,0', '  DT,,0.0025          ', name == 'plain_blocks')//nl// &
                '  LOOP,,100000'//nl//'    TIME,,0.04'//nl// &
                '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
                '  disp,1025,1'//nl//'  velo,1024,2'//nl//'  acce,3073,1'//nl//'  velo,4124,1'//nl// &
                '  reac,1,2'//nl//'  stre,700,1'//nl//'  stre,2300,2'//nl//nl//'STOP'
      case ('plain_bulk')
         ! the scene 'one_point' with VISCosity BULK and DAMPing MASS: plain steps whose works
         ! are sums over every node in order, so the nodal state stays replicated
         deck = HEAD//solid1//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl//'    VISCosity BULK'//nl// &
                '    DAMPing MASS 2 0.03'//nl//nl// &
                'REGIon,1'//nl//block(20, 5, 1, 0.0, 0.0, 5.0, 1.25)// &
                'INITial,VELOcity'//nl//'  REGIon,1,1,2'//nl//nl//'END'//nl//batch('0.05')// &
                '  disp,7,1'//nl//'  velo,100,2'//nl//nl//'STOP'
      case default
         ! one-point elements, no contact, no loads: the plain step
         deck = HEAD//solid1//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl//nl// &
                'REGIon,1'//nl//block(20, 5, 1, 0.0, 0.0, 5.0, 1.25)// &
                'INITial,VELOcity'//nl//'  REGIon,1,1,2'//nl//nl//'END'//nl//batch('0.05')// &
                '  disp,7,1'//nl//'  velo,100,2'//nl//nl//'STOP'
      end select
   end function scene

   !> A BLOCk of nx x ny elements of material mat on the box (x0, y0) - (x1, y1), then a blank line.
   function block(nx, ny, mat, x0, y0, x1, y1) result(text)
      integer, intent(in) :: nx, ny, mat
      real, intent(in) :: x0, y0, x1, y1
      character(len=:), allocatable :: text
      text = 'BLOCk'//nl//'  CARTesian,'//itoa(nx)//','//itoa(ny)//',0,0,'//itoa(mat)//nl// &
             '    1,'//r(x0)//','//r(y0)//nl//'    2,'//r(x1)//','//r(y0)//nl// &
             '    3,'//r(x1)//','//r(y1)//nl//'    4,'//r(x0)//','//r(y1)//nl//nl
   end function block

   !> x as deck text.
   function r(x) result(text)
      real, intent(in) :: x
      character(len=:), allocatable :: text
      character(len=32) :: buf
      write (buf, '(f0.3)') x
      text = trim(buf)
      if (text(1:1) == '.') text = '0'//text
      if (text(1:2) == '-.') text = '-0'//text(2:)
   end function r

   !> The BATCh program to t = tend, histories every step.
   function batch(tend) result(text)
      character(len=*), intent(in) :: tend
      character(len=:), allocatable :: text
      text = 'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,100000'//nl//'    TIME,,'//tend//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl
   end function batch

   !> One scene: serial, then mpirun -np 1..4; .his and .ene equal to the serial bytes.
   subroutine scene_test(s, exic, name)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, name
      character(len=:), allocatable :: dir, deck, his, ene, out
      integer :: code, np
      logical :: same
      dir = run_dir//'/mpi_'//name
      deck = dir//'.inp'
      call execute_command_line('rm -rf '//dir)
      call write_text(deck, scene(name))
      call execute_command_line(exic//' -q '//deck//' -o '//dir//'/serial > '//dir//'_serial.log 2>&1', &
                                exitstat=code)
      call check(s, code == 0, name//': the serial run succeeds', file_text(dir//'_serial.log'))
      if (code /= 0) return
      his = file_text(dir//'/serial/mpi_'//name//'.his')
      ene = file_text(dir//'/serial/mpi_'//name//'.ene')
      call check(s, count_lines(ene) > 10, name//': the serial run wrote more than 10 energy rows')
      if (name == 'dissipation') call check(s, last_value(ene, 'damping_dissipation') > 0.0 .and. &
                                            last_value(ene, 'bulk_viscosity') > 0.0, &
                                            name//': the damping and the bulk viscosity dissipate energy (.ene)')
      if (name == 'self') call check(s, column_max(his, 4) > 1.0, name//': the arms meet (the self contact force '// &
                                     'of the .his exceeds 1)')
      do np = 1, 4
         call execute_command_line(MPIRUN//' -np '//itoa(np)//' '//exic//' -q '//deck//' -o '//dir//'/np'// &
                                   itoa(np)//' > '//dir//'_np'//itoa(np)//'.log 2>&1', exitstat=code)
         call check(s, code == 0, name//': mpirun -np '//itoa(np)//' succeeds', file_text(dir//'_np'//itoa(np)//'.log'))
         if (code /= 0) cycle
         same = file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.his') == his .and. &
                file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.ene') == ene
         call check(s, same, name//': -np '//itoa(np)//': .his and .ene equal the serial files byte for byte')
         out = file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.out')
         if (np > 1 .and. (name == 'one_point' .or. name == 'plain_blocks')) then
            ! divided nodes: the one-point scene's 126 nodes are one chunk (rank 0's); the
            ! blocks' 5 chunks are shared, and few blocks are computed twice
            if (name == 'one_point') then
               call check(s, index(out, 'MPI: '//itoa(np)//' ranks; nodal state divided in chunks of 1024 nodes, '// &
                                  'chunks per rank 1 0') > 0, name//': -np '//itoa(np)// &
                          ': the report states the divided nodal state, one chunk on rank 0')
            else
               call check(s, index(out, 'MPI: '//itoa(np)//' ranks; nodal state divided in chunks of 1024 nodes') > 0 &
                          .and. number_after(out, 'chunks per rank ') < 5 .and. &
                          4*number_after(out, 'computed again by another rank ') < number_after(out, ' (of '), &
                          name//': -np '//itoa(np)//': the report states the divided nodal state, rank 0 owns '// &
                          'some of the 5 chunks, under a quarter of the blocks are computed twice')
            end if
         else if (np > 1) then
            call check(s, index(out, 'MPI: '//itoa(np)//' ranks; METIS parts of the element blocks cut ') > 0 .and. &
                       owned_by_rank0(out) < total_blocks(out), name//': -np '//itoa(np)// &
                       ': the report names the decomposition, and rank 0 owns only some of the blocks')
         end if
         if (name == 'plain_blocks' .and. np > 1) call check(s, h5_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.h5') &
                                                            == h5_text(dir//'/serial/mpi_'//name//'.h5') .and. &
                                                            len(h5_text(dir//'/serial/mpi_'//name//'.h5')) > 1000, &
                                                            name//': -np '//itoa(np)//': the .h5 datasets equal '// &
                                                            'the serial ones (h5dump, 17 digits)')
      end do
   end subroutine scene_test

   !> The scene 'plain_unstable' stops with the energy guard: on 2 and 3 ranks (divided nodes)
   !> the same exit code, .his, .ene, and the same warning and error lines in the .out (their
   !> largest contributor found from every node after the gather) as the serial run.
   subroutine unstable_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: name = 'plain_unstable'
      character(len=:), allocatable :: dir, deck, ref, out
      integer :: code, np
      dir = run_dir//'/mpi_'//name
      deck = dir//'.inp'
      call execute_command_line('rm -rf '//dir)
      call write_text(deck, scene(name))
      call execute_command_line(exic//' -q '//deck//' -o '//dir//'/serial > '//dir//'_serial.log 2>&1', &
                                exitstat=code)
      ref = file_text(dir//'/serial/mpi_'//name//'.out')
      call check(s, code == 1 .and. index(ref, 'error: the physical energy') > 0 .and. &
                 index(ref, 'warning: the physical energy') > 0 .and. index(ref, 'largest contributor: element') > 0, &
                 name//': the serial run warns, then stops with the energy guard naming an element', &
                 file_text(dir//'_serial.log'))
      do np = 2, 3
         call execute_command_line(MPIRUN//' -np '//itoa(np)//' '//exic//' -q '//deck//' -o '//dir//'/np'// &
                                   itoa(np)//' > '//dir//'_np'//itoa(np)//'.log 2>&1', exitstat=code)
         out = file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.out')
         call check(s, code /= 0 .and. index(out, 'nodal state divided') > 0, name//': -np '//itoa(np)// &
                    ': the divided run stops too', file_text(dir//'_np'//itoa(np)//'.log'))
         call check(s, file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.his') == &
                    file_text(dir//'/serial/mpi_'//name//'.his') .and. &
                    file_text(dir//'/np'//itoa(np)//'/mpi_'//name//'.ene') == &
                    file_text(dir//'/serial/mpi_'//name//'.ene'), name//': -np '//itoa(np)// &
                    ': .his and .ene equal the serial files byte for byte')
         call check(s, lines_with(out, 'warning: the physical energy') == lines_with(ref, 'warning: the physical energy') &
                    .and. lines_with(out, 'error: the physical energy') == lines_with(ref, 'error: the physical energy'), &
                    name//': -np '//itoa(np)//': the warning and the error (time, growth, element) are the serial ones')
      end do
   end subroutine unstable_test

   !> The lines of text that contain `word`, in order.
   function lines_with(text, word) result(found)
      character(len=*), intent(in) :: text, word
      character(len=:), allocatable :: found
      integer :: i, j
      found = ''
      i = 1
      do while (i <= len(text))
         j = index(text(i:), new_line('a'))
         if (j == 0) j = len(text) - i + 2
         if (index(text(i:i + j - 2), word) > 0) found = found//text(i:i + j - 2)//new_line('a')
         i = i + j
      end do
   end function lines_with

   !> Every dataset of an .h5 file as h5dump prints it with 17 significant digits, without its
   !> first line (the file's name).
   function h5_text(path) result(text)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: text
      integer :: k
      call execute_command_line('h5dump -m %.17g '//path//' > '//path//'.txt 2>&1')
      text = file_text(path//'.txt')
      k = index(text, new_line('a'))
      if (k > 0) text = text(k + 1:)
   end function h5_text

   !> O of 'rank 0 computes B blocks of N and owns O' in a report (huge when missing).
   integer function owned_by_rank0(out) result(o)
      character(len=*), intent(in) :: out
      o = number_after(out, ' and owns ')
   end function owned_by_rank0

   !> N of 'rank 0 computes B blocks of N and owns O' in a report (-1 when missing).
   integer function total_blocks(out) result(n)
      character(len=*), intent(in) :: out
      n = number_after(out, ' blocks of ')
      if (n == huge(1)) n = -1
   end function total_blocks

   !> The integer after the first `word` in text (huge when missing or unreadable).
   integer function number_after(text, word) result(n)
      character(len=*), intent(in) :: text, word
      integer :: k, ios
      n = huge(1)
      k = index(text, word)
      if (k == 0) return
      read (text(k + len(word):), *, iostat=ios) n
      if (ios /= 0) n = huge(1)
   end function number_after

   !> The value of column `col` (named in the '# ' header line) in the last row of an .ene text
   !> (-1 when missing or unreadable).
   real function last_value(ene, col) result(v)
      character(len=*), intent(in) :: ene, col
      real :: row(64)
      integer :: e, k, n, b, ios
      v = -1.0
      e = index(ene, nl)
      if (e < 3) return
      k = index(ene(1:e - 1)//' ', ' '//col//' ')
      if (k == 0) return
      n = count_words(ene(3:k)) + 1
      b = index(ene(1:len(ene) - 1), nl, back=.true.)
      if (n > size(row) .or. b <= e) return
      read (ene(b + 1:), *, iostat=ios) row(1:n)
      if (ios == 0) v = row(n)
   end function last_value

   !> The largest value of column `col` over the rows of a .his text (after its '# ' header line;
   !> -huge when no row is readable).
   real function column_max(text, col) result(v)
      character(len=*), intent(in) :: text
      integer, intent(in) :: col
      real :: row(col)
      integer :: i, j, ios
      v = -huge(1.0)
      i = index(text, nl) + 1
      do while (i > 1 .and. i <= len(text))
         j = index(text(i:), nl)
         if (j == 0) j = len(text) - i + 2
         read (text(i:i + j - 2), *, iostat=ios) row
         if (ios == 0) v = max(v, row(col))
         i = i + j
      end do
   end function column_max

   !> Words separated by blanks in text.
   pure integer function count_words(text) result(n)
      character(len=*), intent(in) :: text
      integer :: i
      n = 0
      do i = 1, len(text)
         if (text(i:i) /= ' ' .and. (i == 1 .or. text(max(i - 1, 1):max(i - 1, 1)) == ' ')) n = n + 1
      end do
   end function count_words

   !> An eroding deck (EROSion: its element sets change during the run) on 2 ranks is refused at
   !> the start naming EROSion.
   subroutine refusal_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: deck = run_dir//'/mpi_eroding.inp'
      character(len=:), allocatable :: log
      integer :: code
      call write_text(deck, HEAD//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl// &
                      '    EROSion INVErted'//nl//'    DENSity 1'//nl//nl//'REGIon,1'//nl// &
                      block(4, 2, 1, 0.0, 0.0, 2.0, 1.0)//'INITial,VELOcity'//nl//'  REGIon,1,1,0'//nl//nl// &
                      'END'//nl//batch('0.01')//nl//'STOP')
      call execute_command_line(MPIRUN//' -np 2 '//exic//' -q '//deck//' -o '//run_dir//'/mpi_eroding > '// &
                                run_dir//'/mpi_eroding.log 2>&1', exitstat=code)
      log = file_text(run_dir//'/mpi_eroding.log')
      call check(s, code /= 0 .and. index(log, 'EROSion') > 0 .and. &
                 index(log, 'not yet supported on several MPI ranks') > 0, &
                 'an eroding deck on 2 ranks is refused naming EROSion', log)
   end subroutine refusal_test

   !> An error on one rank only stops every rank: rank 0 cannot write its restart file (a folder
   !> holds the name of the file it writes first, <stem>.rst.tmp) while the other ranks write
   !> theirs in their scratch folders and step on into the next exchange. Rank 0 reports the
   !> error and stops every rank (MPI_Abort): the run ends with an error, no rank waits forever
   !> (`timeout` turns a hang into exit code 124, a failure of the check, instead of a suite
   !> that never ends).
   subroutine rank_failure_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: dir = run_dir//'/mpi_rank_failure'
      character(len=:), allocatable :: log, deck
      integer :: code
      call execute_command_line('rm -rf '//dir//'; mkdir -p '//dir//'/out/mpi_failing.rst.tmp')
      deck = scene('one_point')
      deck = deck(:index(deck, '  LOOP') - 1)//'  SAVE,,0.02'//nl//deck(index(deck, '  LOOP'):)
      call write_text(dir//'/mpi_failing.inp', deck)
      ! the deck writes its restart files on one rank (a plain step: no contact, loads or rigid
      ! bodies), and continued from the one of mid-run it gives the uninterrupted run's files
      call execute_command_line('touch '//dir//'/cont.log && '//exic//' -q '//dir//'/mpi_failing.inp -o '//dir// &
                                '/full > '//dir//'/full.log 2>&1 && cp -r '//dir//'/full '//dir//'/cont && mv '// &
                                dir//'/cont/mpi_failing.rst.prev '//dir//'/cont/mid.rst && '//exic//' -q '//dir// &
                                '/mpi_failing.inp -o '//dir//'/cont --restart '//dir//'/cont/mid.rst > '//dir// &
                                '/cont.log 2>&1 && cmp '//dir//'/full/mpi_failing.his '//dir//'/cont/mpi_failing.his && '// &
                                'cmp '//dir//'/full/mpi_failing.ene '//dir//'/cont/mpi_failing.ene', exitstat=code)
      call check(s, code == 0, 'a plain deck (no contact, loads or rigid bodies) writes its restart files '// &
                 'and is continued from mid-run to the same .his and .ene', file_text(dir//'/full.log')// &
                 file_text(dir//'/cont.log'))
      call execute_command_line('timeout 300 '//MPIRUN//' -np 3 '//exic//' -q '//dir//'/mpi_failing.inp -o '// &
                                dir//'/out > '//dir//'/run.log 2>&1', exitstat=code)
      log = file_text(dir//'/run.log')
      call check(s, code /= 0 .and. code /= 124 .and. index(log, 'exic: error: ') > 0 .and. &
                 index(log, 'mpi_failing.rst.tmp') > 0 .and. &
                 index(log, 'exic: rank ') == 0, 'an error on rank 0 alone (its restart file cannot be '// &
                 'written) stops the 3 ranks with the error, no hang (exit code '//itoa(code)//')', log)
   end subroutine rank_failure_test

end module test_mpi
