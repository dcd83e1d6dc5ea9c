!> Whole-run physics checks of the explicit solver against exact answers and conservation laws.
module test_physics
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa
   use testing, only: suite_t, check, check_close, section
   use deck_runner, only: run_dir, run_deck, read_table, column, write_text, file_has
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_assembly, only: assembly_init, internal_forces, force_result_t
   implicit none
   private

   public :: run_physics_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_physics_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'physics: 1-D wave in a bar (nu = 0)')
      call wave_test(s)
      call section(s, 'physics: energy of a spinning, stretching free block')
      call energy_test(s, 2)
      call energy_test(s, 1)
      call energy_test(s, 1, 'HOURglass,PHYSical')
      call section(s, 'physics: stable step')
      call stability_tests(s)
      call section(s, 'physics: an overflowing energy stops the run before any non-finite row')
      call overflow_test(s)
      call section(s, 'physics: element inversion stops the run')
      call inversion_test(s)
      call section(s, 'physics: objectivity under a 90-degree rigid rotation')
      call rotation_test(s, 2)
      call rotation_test(s, 1)
   end subroutine run_physics_tests

   !> A distorted block carried through a rigid rotation of 90 degrees in 2000 increments
   !> (u = (R - I) X): the strain energy and the internal forces stay at round-off at every
   !> increment (the total-Lagrangian element is objective), for both quadratures.
   subroutine rotation_test(s, nq)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      type(model_t) :: model
      type(state_t) :: st
      type(element_set_t), allocatable :: sets(:)
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      character(len=1) :: q
      integer :: k
      real(wp) :: th, c, sn, worst_w, worst_f, fscale
      type(force_result_t) :: res
      integer, parameter :: nstep = 2000

      write (q, '(i1)') nq
      deck = 'FEAP * * rigid rotation'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl// &
             '    QUADrature '//q//nl//nl// &
             'BLOCk'//nl//'  CARTesian,4,3,0,0,1'//nl//'    1,0,0'//nl//'    2,2,0.3'//nl//'    3,2.2,1.5'//nl// &
             '    4,-0.1,1.2'//nl//'    5,1.1,0.05'//nl//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call write_text(run_dir//'/rotation.inp', deck)
      call read_deck(run_dir//'/rotation.inp', model, err)
      if (.not. allocated(err)) call assembly_init(model%mesh, model%materials, st, sets, err)
      call check(s, .not. allocated(err), 'rotation block set up (quadrature '//q//')')
      if (allocated(err)) return
      worst_w = 0.0_wp
      worst_f = 0.0_wp
      ! force scale: a strain of 1 on an element edge of about 0.5
      fscale = 1000.0_wp*0.5_wp
      do k = 1, nstep
         th = 0.5_wp*acos(-1.0_wp)*real(k, wp)/real(nstep, wp)
         c = cos(th)
         sn = sin(th)
         st%u(1, :) = (c - 1.0_wp)*st%x0(1, :) - sn*st%x0(2, :)
         st%u(2, :) = sn*st%x0(1, :) + (c - 1.0_wp)*st%x0(2, :)
         call internal_forces(st, sets, res)
         worst_w = max(worst_w, abs(st%energy%strain) + abs(st%energy%hourglass))
         worst_f = max(worst_f, maxval(abs(st%fint)))
      end do
      call check(s, worst_w <= 1.0e-12_wp*1000.0_wp*3.0_wp, 'strain energy at round-off through 90 degrees'// &
                 ' (quadrature '//q//')', 'largest '//rtoa(worst_w))
      call check(s, worst_f <= 1.0e-12_wp*fscale, 'internal forces at round-off through 90 degrees'// &
                 ' (quadrature '//q//')', 'largest '//rtoa(worst_f))
   end subroutine rotation_test

   !> A bar fixed at x = L, moving at v0 toward it: a compression front of stress rho c v0 runs
   !> back and reaches the free end at t = L/c (exact 1-D wave theory; nu = 0 makes plane strain 1-D).
   subroutine wave_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, k, kv, ks, n
      real(wp), parameter :: length = 10.0_wp, young = 1000.0_wp, rho = 1.0_wp, v0 = 0.01_wp
      real(wp) :: c, h, dt, t_arrive, smean, t1, t2
      integer :: cnt

      c = sqrt(young/rho)
      h = length/100.0_wp
      dt = 0.5_wp*h/c
      deck = 'FEAP * * 1-D wave'//nl//'0 0 0 2 2 4'//nl// &
             'PARAmeters'//nl//'  len = 10'//nl//'  hgt = 0.5'//nl//'  young = 1000'//nl// &
             '  v0 = 0.01'//nl//'  cw = sqrt(young/1)'//nl//'  dt = 0.5*(len/100)/cw'//nl//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young 0'//nl// &
             '    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,100,5,0,0,1'//nl//'    1,0,0'//nl//'    2,len,0'//nl// &
             '    3,len,hgt'//nl//'    4,0,hgt'//nl//nl// &
             'EBOUndary'//nl//'  1,len,1,0'//nl//nl// &
             'INITial,VELOcity'//nl//'  MATErial,1,v0,0'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,,dt'//nl//'  TPLOt,,1'//nl// &
             '  LOOP,,100000'//nl//'    TIME,,1.6*len/cw'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
             'END'//nl//'  velo,,1,0,0'//nl//'  stre,,1,len/2,hgt/2'//nl//nl//'STOP'
      call run_deck('wave', deck, stage, msg)
      call check(s, stage == 0, 'wave deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/wave.his', names, d)
      kv = 2
      ks = 3
      n = size(d, 2)
      ! arrival: the free end's velocity crosses zero (from v0 to -v0)
      t_arrive = -1.0_wp
      do k = 2, n
         if (d(kv, k - 1) > 0.0_wp .and. d(kv, k) <= 0.0_wp) then
            t_arrive = d(1, k - 1) + (d(1, k) - d(1, k - 1))*d(kv, k - 1)/(d(kv, k - 1) - d(kv, k))
            exit
         end if
      end do
      call check(s, abs(t_arrive - length/c) <= 2.0_wp*dt, 'front reaches the free end at L/c within 2 steps', &
                 'arrival '//rtoa(t_arrive)//', L/c '//rtoa(length/c)//', dt '//rtoa(dt))
      ! stress behind the front at mid-bar, between the front's passage and the reflected unloading
      t1 = 0.5_wp*length/c + 20.0_wp*h/c
      t2 = 1.5_wp*length/c - 20.0_wp*h/c
      smean = 0.0_wp
      cnt = 0
      do k = 1, n
         if (d(1, k) >= t1 .and. d(1, k) <= t2) then
            smean = smean + d(ks, k)
            cnt = cnt + 1
         end if
      end do
      smean = smean/max(cnt, 1)
      call check_close(s, smean, -rho*c*v0, 0.01_wp*rho*c*v0, 'stress behind the front = -rho c v0 within 1 %')
   end subroutine wave_test

   !> A free block released with v = w x (x - xc) + s (x - xc): a spin plus a stretch, reaching
   !> 10 % strain. Total energy must hold within 0.5 % over 1e4 steps at CFL 0.9, with no drift.
   subroutine energy_test(s, nq, hgrec)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      character(len=*), intent(in), optional :: hgrec   !< a HOURglass record for the material
      character(len=:), allocatable :: msg, deck, init, hg, tag, stem
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, i, j, node, n, k, kd, ku, kh, nrow
      real(wp), parameter :: omega = 0.3_wp, rate = 0.12_wp
      real(wp) :: x, y, vx, vy, early, late, worst, jdev, hgmax, umax
      character(len=120) :: line
      character(len=1) :: q

      ! node-vector records: every node of the 16 x 16 block (node (i,j) = 1 + j*17 + i)
      init = ''
      do j = 0, 16
         do i = 0, 16
            node = 1 + j*17 + i
            x = real(i, wp)/16.0_wp - 0.5_wp
            y = real(j, wp)/16.0_wp - 0.5_wp
            vx = -omega*y + rate*x
            vy = omega*x + rate*y
            write (line, '(i0,a,es23.16,a,es23.16)') node, ',0,', vx, ',', vy
            init = init//'  '//trim(line)//nl
         end do
      end do
      write (q, '(i1)') nq
      hg = ''
      tag = q
      stem = 'energy_q'//q
      if (present(hgrec)) then
         hg = '    '//hgrec//nl
         tag = q//', '//hgrec
         stem = stem//'p'
      end if
      deck = 'FEAP * * spinning block'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1 0.3'//nl// &
             '    DENSity 1'//nl//'    QUADrature '//q//nl//hg//nl// &
             'BLOCk'//nl//'  CARTesian,16,16,1,1,1'//nl//'    1,-0.5,-0.5'//nl//'    2,0.5,-0.5'//nl// &
             '    3,0.5,0.5'//nl//'    4,-0.5,0.5'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl// &
             '  TPLOt,,10'//nl//'  INITial,VELOcity'//nl// &
             '  LOOP,,10000'//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
             'END'//nl//'  stre,,7,-0.45,-0.45'//nl//'  stre,,7,0,0'//nl//nl//init//nl//'STOP'
      call run_deck(stem, deck, stage, msg)
      call check(s, stage == 0, 'energy deck runs (quadrature '//tag//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//stem//'.ene', names, d)
      kd = column(names, 'drift')
      ku = column(names, 'strain')
      kh = column(names, 'hourglass')
      nrow = size(d, 2)
      worst = maxval(abs(d(kd, :)))
      call check(s, worst <= 0.005_wp, 'total energy within 0.5 % over 1e4 steps (quadrature '//tag//')', &
                 'largest drift '//rtoa(worst))
      n = nrow/10
      early = sum(d(kd, n + 1:2*n))/n
      late = sum(d(kd, nrow - n + 1:nrow))/n
      call check(s, abs(late - early) <= 1.0e-3_wp, 'no secular energy drift (quadrature '//tag//')', &
                 'mean drift early '//rtoa(early)//', late '//rtoa(late))
      call read_table(run_dir//'/'//stem//'.his', names, d)
      jdev = 0.0_wp
      do k = 2, 3
         jdev = max(jdev, maxval(abs(d(k, :) - 1.0_wp)))
      end do
      call check(s, jdev >= 0.05_wp, 'the block strains by more than 5 % in volume (quadrature '//tag//')', &
                 'largest |J - 1| '//rtoa(jdev))
      if (nq == 1) then
         call read_table(run_dir//'/'//stem//'.ene', names, d)
         ! hourglass energy at every output against the strain energy the block stores (its
         ! largest value): the strain energy itself breathes through near-zero minima
         umax = maxval(d(ku, :))
         hgmax = maxval(d(kh, :))
         call check(s, hgmax < 0.01_wp*umax, 'hourglass energy below 1 % of strain energy', &
                    'largest hourglass '//rtoa(hgmax)//', largest strain '//rtoa(umax))
      end if
   end subroutine energy_test

   !> A fixed DT above the limit is refused with the limit; CFL 0.9 on a distorted mesh is stable.
   subroutine stability_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck, coords
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, i, j, node, kd
      real(wp) :: x, y
      character(len=120) :: line

      deck = 'FEAP * * too large a step'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,10,2,0,0,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl//'    3,1,0.2'//nl// &
             '    4,0,0.2'//nl//nl//'END'//nl//'BATCh'//nl//'  DT,,0.1'//nl//'  LOOP,,10'//nl// &
             '    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'STOP'
      call run_deck('dt_too_large', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'stable limit') > 0, &
                 'a fixed DT above the stable limit is refused, naming the limit', msg)

      ! a strongly distorted 10 x 10 mesh: interior nodes moved by up to 0.35 h
      coords = ''
      do j = 0, 10
         do i = 0, 10
            node = 1 + j*11 + i
            x = real(i, wp)/10.0_wp
            y = real(j, wp)/10.0_wp
            if (i > 0 .and. i < 10 .and. j > 0 .and. j < 10) then
               x = x + 0.035_wp*sin(12.9898_wp*i + 78.233_wp*j)
               y = y + 0.035_wp*cos(39.3468_wp*i + 11.135_wp*j)
            end if
            write (line, '(i0,a,es23.16,a,es23.16)') node, ',0,', x, ',', y
            coords = coords//'  '//trim(line)//nl
         end do
      end do
      deck = 'FEAP * * distorted mesh at CFL 0.9'//nl//'0 0 0 2 2 4'//nl// &
             'COORdinates'//nl//coords//nl// &
             'ELEMents'//nl//'  1,1,1,1,2,13,12'//nl//'  10,0,1,10,11,22,21'//nl// &
             '  11,1,1,12,13,24,23'//nl//'  20,0,1,21,22,33,32'//nl// &
             '  21,1,1,23,24,35,34'//nl//'  30,0,1,32,33,44,43'//nl// &
             '  31,1,1,34,35,46,45'//nl//'  40,0,1,43,44,55,54'//nl// &
             '  41,1,1,45,46,57,56'//nl//'  50,0,1,54,55,66,65'//nl// &
             '  51,1,1,56,57,68,67'//nl//'  60,0,1,65,66,77,76'//nl// &
             '  61,1,1,67,68,79,78'//nl//'  70,0,1,76,77,88,87'//nl// &
             '  71,1,1,78,79,90,89'//nl//'  80,0,1,87,88,99,98'//nl// &
             '  81,1,1,89,90,101,100'//nl//'  90,0,1,98,99,110,109'//nl// &
             '  91,1,1,100,101,112,111'//nl//'  100,0,1,109,110,121,120'//nl//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1 0.45'//nl//'    DENSity 1'//nl//nl// &
             'INITial,VELOcity'//nl//'  1,1,0.05,0'//nl//'  121,0,-0.05,0.02'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,50'//nl//'  LOOP,,5000'//nl// &
             '    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  disp,1,1'//nl//nl//'STOP'
      call run_deck('distorted', deck, stage, msg)
      call check(s, stage == 0, 'distorted mesh runs 5000 steps at CFL 0.9', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/distorted.ene', names, d)
      kd = column(names, 'drift')
      call check(s, maxval(abs(d(kd, :))) < 0.01_wp, 'distorted mesh keeps its energy within 1 % (stable)', &
                 'largest drift '//rtoa(maxval(abs(d(kd, :)))))
   end subroutine stability_tests

   !> A bar slammed into a fixed end at twice its wave speed crushes its last element.
   subroutine inversion_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage
      deck = 'FEAP * * crush'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1 0.3'//nl//'    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,20,2,0,0,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl//'    3,1,0.1'//nl// &
             '    4,0,0.1'//nl//nl//'EBOUndary'//nl//'  1,1,1,1'//nl//nl// &
             'INITial,VELOcity'//nl//'  MATErial,1,1.2,0'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,2000'//nl// &
             '    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  disp,1,1'//nl//nl//'STOP'
      call run_deck('crush', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'element') > 0 .and. index(msg, 'inverted') > 0 &
                 .and. index(msg, 't =') > 0, 'inversion stops the run naming the element and time', msg)
      call read_table(run_dir//'/crush.his', names, d)
      call check(s, size(d, 2) >= 10 .and. all(d == d), 'histories kept up to the failing step, no NaN')
      call read_table(run_dir//'/crush.ene', names, d)
      call check(s, size(d, 2) >= 10 .and. all(d == d), 'energies kept up to the failing step, no NaN')
   end subroutine inversion_test

   !> v0 = 1e155 overflows the kinetic energy at t = 0: the run fails (exit 1) saying so, and
   !> no output file holds a non-finite number.
   subroutine overflow_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage
      deck = 'FEAP * * overflow'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1 0.3'//nl//'    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,4,2,0,0,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl//'    3,1,0.5'//nl// &
             '    4,0,0.5'//nl//nl//'INITial,VELOcity'//nl//'  MATErial,1,1e155,0'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  TPLOt,,1'//nl//'  LOOP,,10'//nl// &
             '    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  velo,1,1'//nl//nl//'STOP'
      call run_deck('overflow', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'not finite') > 0 .and. index(msg, 't = ') > 0, &
                 'an overflowing kinetic energy stops the run, saying so', msg)
      call check(s, .not. file_has(run_dir//'/overflow.ene', 'Infinity') .and. &
                 .not. file_has(run_dir//'/overflow.ene', 'NaN') .and. &
                 .not. file_has(run_dir//'/overflow.his', 'Infinity') .and. &
                 .not. file_has(run_dir//'/overflow.his', 'NaN'), 'no non-finite number in .ene or .his')
      call read_table(run_dir//'/overflow.ene', names, d)
      call check(s, all(d == d) .and. all(abs(d) <= huge(1.0_wp)), '.ene reads back finite')
   end subroutine overflow_test

end module test_physics
