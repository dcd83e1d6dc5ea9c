!> The explicit-implicit contact corrector against 1-D wave theory and its own claims.
!>
!> 1-D cases use nu = 0 (lambda = 0), so plane strain is exactly 1-D, and strains below 0.1 %,
!> so the neo-Hookean bars behave as linear ones: wave speed c = sqrt(E/rho), impedance
!> Z = rho c, contact force rho c v0 H for a bar on a rigid wall. The exact answers for two
!> bars are derived by characteristics in doc/contact-verification.md.
module test_contact
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa, itoa
   use testing, only: suite_t, check, check_close, section
   use deck_runner, only: run_dir, run_deck, read_table, column, file_has
   implicit none
   private

   public :: run_contact_tests, bar_deck

   character(len=*), parameter :: nl = new_line('a')
   real(wp), parameter :: young = 1.0e4_wp, rho0 = 0.1_wp, v0 = 0.1_wp
   real(wp), parameter :: blen = 30.0_wp, bhgt = 4.0_wp

contains

   subroutine run_contact_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'contact: bar against a rigid wall, 30 x 6')
      call wall_test(s, 30, 6, 0.04_wp)
      call section(s, 'contact: bar against a rigid wall, 60 x 12')
      call wall_test(s, 60, 12, 0.025_wp)
      call section(s, 'contact: two equal bars')
      call two_bar_test(s, rho0, rho0, 'NTOS', 'two_bars')
      call section(s, 'contact: two bars of densities 0.5 and 1.0')
      call two_bar_test(s, 0.5_wp, 1.0_wp, 'NTOS', 'unlike_bars')
      call section(s, 'contact: two-pass contact of matching meshes (redundant constraints, corners)')
      call two_bar_test(s, rho0, rho0, 'SYMMetric', 'two_pass')
      call section(s, 'contact: node-on-node against node-on-segment meshes (seed 7.2, 6 x 30 and 6 x 31)')
      call mesh_pair_test(s)
      call section(s, 'contact: swept against static detection, thin target')
      call thin_target_test(s)
      call section(s, 'contact: penalty baseline')
      call penalty_test(s)
      call section(s, 'contact: bodies overlapping at the start')
      call overlap_test(s)
      call section(s, 'contact: a wall of 10 x 1505 elements beside a block (no overlap)')
      call long_wall_test(s, 'AUTOmatic', 10.0_wp, 0, 'a block beside a wall of long elements is not an overlap (AUTOmatic)')
      call long_wall_test(s, 'PAIR,1,NTOS,2,1', 10.0_wp, 0, 'nor with the block nodes against the wall (NTOS)')
      call long_wall_test(s, 'PAIR,1,NTOS,1,2', 10.0_wp, 0, 'nor with the wall nodes against the block (NTOS)')
      call long_wall_test(s, 'AUTOmatic', 7.0_wp, 2, 'the block 3 inside the wall is refused')
      call section(s, 'contact: bodies no contact pair couples (issue 32, item 8)')
      call uncoupled_test(s, '', 3, 'three blocks without CONTact passing through each other')
      call uncoupled_test(s, 'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
                          '    REGIon,2'//nl//'  PAIR,1,SYMMetric,1,2'//nl//'END CONTact'//nl//nl, 2, &
                          'the same with a pair coupling regions 1 and 2')
      call uncoupled_test(s, '', 3, 'three blocks without CONTact passing through each other and apart at the '// &
                          'end, no field output (the checks between, every hmin / (4 vmax dt) steps)', through=.true.)
      call section(s, 'contact: self contact of a U-shaped body')
      call self_contact_test(s)
   end subroutine run_contact_tests

   !> The arms of a U (three tied blocks of one region) swing toward each other: with SELF
   !> contact they meet and push apart without passing through each other.
   subroutine self_contact_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage
      deck = 'FEAP * * U-shaped body closing on itself'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 100 0.3'//nl//'    DENSity 1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,6,2,0,0,1'//nl//'    1,0,0'//nl//'    2,3,0'//nl//'    3,3,1'//nl// &
             '    4,0,1'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,2,4,0,0,1'//nl//'    1,0,1'//nl//'    2,1,1'//nl//'    3,1,3'//nl// &
             '    4,0,3'//nl//nl// &
             'BLOCk'//nl//'  CARTesian,2,4,0,0,1'//nl//'    1,2,1'//nl//'    2,3,1'//nl//'    3,3,3'//nl// &
             '    4,2,3'//nl//nl// &
             'INITial,VELOcity'//nl//'  25,1,1,0'//nl//'  36,0,1,0'//nl//'  40,1,-1,0'//nl//'  51,0,-1,0'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,0'//nl//'  PAIR,1,SELF,1'//nl//'END CONTact'//nl//nl// &
             'END'//nl//'TIE'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,100000'//nl// &
             '    TIME,,1.5'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,36,1'//nl//'  disp,49,1'//nl//'  cont,1,1'//nl//'  cont,1,5'//nl//nl//'STOP'
      call run_deck('self_u', deck, stage, msg)
      call check(s, stage == 0, 'U-shaped self-contact deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/self_u.his', names, d)
      ! node 36: top-right corner of the left arm (1, 3); node 49: top-left of the right arm (2, 3)
      call check(s, maxval(d(4, :)) > 0.0_wp, 'the arms meet (self contact carries force)')
      call check(s, maxval(d(2, :)) > 0.4_wp .and. d(2, size(d, 2)) < maxval(d(2, :)), &
                 'the left arm swings in and is pushed back', 'largest tip displacement '//rtoa(maxval(d(2, :))))
      call check(s, maxval(d(5, :)) < 1.0e-3_wp, 'residual penetration below 1e-3 of a segment', &
                 'largest '//rtoa(maxval(d(5, :))))
   end subroutine self_contact_test

   !> Two blocks that overlap by 0.05 at the start: an error naming the node and the depth.
   subroutine overlap_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      integer :: stage
      deck = 'FEAP * * overlapping blocks'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1 0.3'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,0,0,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl// &
             '    3,1,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,0,0,1'//nl//'    1,0.95,0.2'//nl//'    2,2,0.2'//nl// &
             '    3,2,1.2'//nl//'    4,0.95,1.2'//nl//nl// &
             'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  LOOP,,10'//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'STOP'
      call run_deck('overlap', deck, stage, msg)
      call check(s, stage == 2 .and. index(msg, 'overlap') > 0 .and. index(msg, 'node') > 0 .and. &
                 index(msg, '5.0000000E-02') > 0, 'overlapping bodies are refused, naming the node and the depth', msg)
   end subroutine overlap_test

   !> Issue 32, item 6: a wall of 1 x 2 elements of 10 x 1505 (3010 high) and a block of 4 x 4
   !> elements of 10 beside it, its left face at x = x0 (10: touching; 7: inside the wall by 3),
   !> moving away from the wall at 0.1 for 20 steps. Touching: it runs, and the wall's far bottom
   !> corner (node 1 at (0, 0), which the old check took for a node inside the block) moves by less
   !> than 1, a tenth of the wall's width (a false contact moves it by 50). Overlapping: refused, naming the depth 3.
   subroutine long_wall_test(s, pair, x0, want, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: pair, what
      real(wp), intent(in) :: x0
      integer, intent(in) :: want
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage
      deck = 'FEAP * * wall beside a block'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 0.3'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,1,2,1,1,1'//nl//'    1,0,0'//nl//'    2,10,0'//nl// &
             '    3,10,3010'//nl//'    4,0,3010'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,4,4,7,3,1'//nl//'    1,'//rtoa(x0)//',0'//nl// &
             '    2,'//rtoa(x0 + 40)//',0'//nl//'    3,'//rtoa(x0 + 40)//',40'//nl//'    4,'//rtoa(x0)//',40'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,2,0.1,0'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  '//pair//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,20'//nl//'    TIME,,2'//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  disp,1,1'//nl//'  disp,1,2'//nl//nl//'STOP'
      call run_deck('wall_'//itoa(want)//'_'//pair(1:4)//pair(len(pair):), deck, stage, msg)
      if (want == 2) then
         call check(s, stage == 2 .and. index(msg, 'bodies overlap at the start') > 0 .and. &
                    index(msg, '3.0000') > 0, what, msg)
         return
      end if
      call check(s, stage == 0, what, msg)
      if (stage /= 0) return
      call read_table(run_dir//'/wall_'//itoa(want)//'_'//pair(1:4)//pair(len(pair):)//'.his', names, d)
      call check(s, maxval(abs(d(2:3, :))) < 1.0_wp, 'the far corner of the wall stays (no false contact)', &
                 'largest displacement '//rtoa(maxval(abs(d(2:3, :)))))
   end subroutine long_wall_test

   !> Issue 32, item 8: blocks A (region 1, moving right), B (region 2, at rest) and C (region 3,
   !> moving left), each 1 x 1 in 4 x 4 elements, in a row 0.2 apart, B lifted by 0.5; at t = 1 A
   !> and C have passed into B and into each other. Without contact every two of them
   !> interpenetrate: one warning per pair ("regions i and j interpenetrate ...; no contact pair
   !> couples them"), `nwarn` = 3, in <stem>.out and on the console. With `cont` a SYMMetric pair
   !> couples A and B: they do not interpenetrate and are never named; the other two pairs warn
   !> (`nwarn` = 2). (The console gets the same lines through the run's messages.)
   subroutine uncoupled_test(s, cont, nwarn, what, through)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: cont, what
      integer, intent(in) :: nwarn
      !> to t = 3.5, when regions 1 and 3 have passed through the others and left them, with
      !> no field output
      logical, intent(in), optional :: through
      character(len=:), allocatable :: msg, deck, name, batch
      integer :: stage, n12, n13, n23
      batch = '  OUTPut,HDF5,0.05'//nl//'  LOOP,,100000'//nl//'    TIME,,1'//nl
      name = 'uncoupled'//itoa(nwarn)
      if (present(through)) then
         if (through) then
            batch = '  LOOP,,100000'//nl//'    TIME,,3.5'//nl
            name = name//'_through'
         end if
      end if
      deck = 'FEAP * * blocks passing through each other'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 100 0.3'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,4,4,1,1,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl// &
             '    3,1,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,4,4,26,17,1'//nl//'    1,1.2,0.5'//nl//'    2,2.2,0.5'//nl// &
             '    3,2.2,1.5'//nl//'    4,1.2,1.5'//nl//nl// &
             'REGIon,3'//nl//'BLOCk'//nl//'  CARTesian,4,4,51,33,1'//nl//'    1,2.4,0'//nl//'    2,3.4,0'//nl// &
             '    3,3.4,1'//nl//'    4,2.4,1'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,1,0'//nl//'  REGIon,3,-1,0'//nl//nl//cont// &
             'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,10'//nl//batch// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  disp,1,1'//nl//nl//'STOP'
      call run_deck(name, deck, stage, msg)
      call check(s, stage == 0, what//' runs', msg)
      if (stage /= 0) return
      n12 = lines_with(run_dir//'/'//name//'.out', 'regions 1 and 2 interpenetrate at t')
      n13 = lines_with(run_dir//'/'//name//'.out', 'regions 1 and 3 interpenetrate at t')
      n23 = lines_with(run_dir//'/'//name//'.out', 'regions 2 and 3 interpenetrate at t')
      call check(s, n12 + n13 + n23 == nwarn .and. max(n12, n13, n23) == 1 .and. &
                 (nwarn == 3 .or. n12 == 0), what//': one warning per uncoupled pair in <stem>.out', &
                 'warnings 1-2 '//itoa(n12)//', 1-3 '//itoa(n13)//', 2-3 '//itoa(n23))
   end subroutine uncoupled_test

   !> Number of lines of the file that contain `text`.
   integer function lines_with(path, text) result(n)
      character(len=*), intent(in) :: path, text
      character(len=4096) :: line
      integer :: u, ios
      n = 0
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (index(line, text) > 0) n = n + 1
      end do
      close (u)
   end function lines_with

   !> Seed example 7.2: bar 30 x 4 (30 x 6) at 50 against a free vertical bar 4 x 30 meshed
   !> 6 x 30 (node on node) or 6 x 31 (node on segment); lambda = 33333, mu = 5000, rho = 0.1.
   function seed72_deck(nv, pair_kind) result(deck)
      integer, intent(in) :: nv
      character(len=*), intent(in) :: pair_kind
      character(len=:), allocatable :: deck
      character(len=8) :: b
      write (b, '(i0)') nv
      deck = 'FEAP * * seed example 7.2, vertical bar 6 x '//trim(b)//nl//'0 0 0 2 2 4'//nl// &
             'PARAmeters'//nl//'  lam = 33333'//nl//'  mu = 5000'//nl// &
             '  young = mu*(3*lam+2*mu)/(lam+mu)'//nl//'  nu = lam/(2*(lam+mu))'//nl//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young nu'//nl//'    DENSity 0.1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,30,6,0,0,1'//nl//'    1,0,13'//nl//'    2,30,13'//nl// &
             '    3,30,17'//nl//'    4,0,17'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,6,'//trim(b)//',0,0,1'//nl//'    1,30,0'//nl// &
             '    2,34,0'//nl//'    3,34,30'//nl//'    4,30,30'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,50,0'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,'//pair_kind//',1,2'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl// &
             '    TIME,,0.12'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,124,1'//nl//'  cont,1,1'//nl//'  cont,1,6'//nl//'  cont,1,5'//nl//nl//'STOP'
   end function seed72_deck

   !> The tip displacement histories of the node-on-node and node-on-segment meshes agree
   !> within 1 % of the peak (seed section 7.2: "indistinguishable").
   subroutine mesh_pair_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: a(:, :), b(:, :)
      integer :: stage, k, j
      real(wp) :: ub, worst, peak, w, f1d
      call run_deck('seed72_30', seed72_deck(30, 'NTOS'), stage, msg)
      call check(s, stage == 0, 'seed 7.2 with a 6 x 30 vertical bar runs', msg)
      if (stage /= 0) return
      call run_deck('seed72_31', seed72_deck(31, 'NTOS'), stage, msg)
      call check(s, stage == 0, 'seed 7.2 with a 6 x 31 vertical bar runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/seed72_30.his', names, a)
      call read_table(run_dir//'/seed72_31.his', names, b)
      peak = maxval(abs(a(2, :)))
      worst = 0.0_wp
      j = 1
      do k = 1, size(a, 2)
         do while (j < size(b, 2) - 1 .and. b(1, j + 1) < a(1, k))
            j = j + 1
         end do
         if (a(1, k) > b(1, size(b, 2))) exit
         w = (a(1, k) - b(1, j))/(b(1, j + 1) - b(1, j))
         ub = (1.0_wp - w)*b(2, j) + w*b(2, j + 1)
         worst = max(worst, abs(a(2, k) - ub))
      end do
      call check(s, worst <= 0.01_wp*peak, 'tip displacement histories agree within 1 % of the peak', &
                 'largest difference '//rtoa(worst)//', peak '//rtoa(peak))
      print '(a,es10.3)', '      figures seed 7.2 vs 7.2b: largest tip displacement difference / peak ', worst/peak
      ! multipliers stay bounded (two-pass, corners of the striking bar on the face)
      f1d = 0.1_wp*sqrt((33333.0_wp + 2.0_wp*5000.0_wp)/0.1_wp)*50.0_wp*4.0_wp
      call check(s, maxval(a(4, :)) <= 10.0_wp*f1d .and. maxval(b(4, :)) <= 10.0_wp*f1d, &
                 'no multiplier above 10x the 1-D contact force (two-pass, corners)', &
                 'largest '//rtoa(max(maxval(a(4, :)), maxval(b(4, :))))//', 1-D force '//rtoa(f1d))
      call two_pass_check(s, 30, a)
      call two_pass_check(s, 31, b)
   end subroutine mesh_pair_test

   !> Two-pass (SYMMetric) contact of the same scene: every node of both faces constrained,
   !> residual penetrations at t(n+1) (the frozen normal's linearization error) below 1e-3 of
   !> a segment, and the tip history within 1 % of the one-pass run `one`.
   subroutine two_pass_check(s, nv, one)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nv
      real(wp), intent(in) :: one(:, :)
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      character(len=8) :: tag
      integer :: stage, k
      real(wp) :: worst, peak, u
      write (tag, '(a,i0)') '6x', nv
      call run_deck('seed72_sym_'//trim(tag(3:)), seed72_deck(nv, 'SYMMetric'), stage, msg)
      call check(s, stage == 0, 'two-pass seed 7.2 runs ('//trim(tag)//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/seed72_sym_'//trim(tag(3:))//'.his', names, d)
      call check(s, maxval(d(5, :)) < 1.0e-3_wp, 'two-pass residual penetration below 1e-3 of a segment ('// &
                 trim(tag)//')', 'largest '//rtoa(maxval(d(5, :))))
      peak = maxval(abs(one(2, :)))
      worst = 0.0_wp
      do k = 1, size(d, 2)
         if (d(1, k) > one(1, size(one, 2))) exit
         u = interpolate(one(1, :), one(2, :), d(1, k))
         worst = max(worst, abs(d(2, k) - u))
      end do
      call check(s, worst <= 0.01_wp*peak, 'two-pass tip history within 1 % of the one-pass one ('//trim(tag)//')', &
                 'largest difference '//rtoa(worst)//', peak '//rtoa(peak))
   end subroutine two_pass_check

   !> Linear interpolation of y(x) at xq (x increasing).
   pure real(wp) function interpolate(x, y, xq) result(yq)
      real(wp), intent(in) :: x(:), y(:), xq
      integer :: j
      yq = y(size(y))
      do j = 2, size(x)
         if (x(j) >= xq) then
            yq = y(j - 1) + (y(j) - y(j - 1))*(xq - x(j - 1))/(x(j) - x(j - 1))
            return
         end if
      end do
   end function interpolate

   !> A block at 1/4 of its wave speed against a rigid plate thinner than one step of travel (and
   !> the travel deeper than the search depth, 0.1 of the mean segment length):
   !> SWEPt detection stops it at the plate, STATic detection (documented) lets it through.
   !> `check` is a BATCh line before the loop ('' for none).
   function thin_target_deck(detection, check) result(deck)
      character(len=*), intent(in) :: detection, check
      character(len=:), allocatable :: deck
      deck = 'FEAP * * block against a thin plate'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 400 0'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,0,0,1'//nl//'    1,-0.005,0'//nl// &
             '    2,0.995,0'//nl//'    3,0.995,1'//nl//'    4,-0.005,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,1,4,0,0,2'//nl//'    1,1,-1'//nl// &
             '    2,1.005,-1'//nl//'    3,1.005,2'//nl//'    4,1,2'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,5,0'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'    DETEction,'//detection//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//check//nl//'  LOOP,,100'//nl// &
             '    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,6,1'//nl//'  cont,1,4'//nl//nl//'STOP'
   end function thin_target_deck

   subroutine thin_target_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage
      call run_deck('thin_swept', thin_target_deck('SWEPt', ''), stage, msg)
      call check(s, stage == 0, 'thin target, swept detection, runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/thin_swept.ene', names, e)
      call check(s, 5.0_wp*e(3, 2) > 0.01_wp, 'one step of travel (v dt) exceeds the plate thickness', &
                 'v dt = '//rtoa(5.0_wp*e(3, 2)))
      call read_table(run_dir//'/thin_swept.his', names, d)
      call check(s, maxval(d(2, :)) <= 0.005_wp + 1.0e-10_wp, 'swept detection stops the face at the plate', &
                 'largest face displacement '//rtoa(maxval(d(2, :)))//' (plate at 0.005)')
      ! the nodes that went through are found behind the plate and pushed out across it: the
      ! contact feeds energy, and the energy guard stops the run naming the pair
      call run_deck('thin_static', thin_target_deck('STATic', ''), stage, msg)
      call check(s, stage == 2 .and. index(msg, 'exceeds the energy put in') > 0 .and. &
                 index(msg, 'contact pair 1') > 0, 'thin target, static detection: the energy guard stops '// &
                 'the run and names contact pair 1', msg)
      call run_deck('thin_static_free', thin_target_deck('STATic', '  CHECk,ENERgy,0.01,1000'), stage, msg)
      call check(s, stage == 0, 'thin target, static detection, with the guard''s stop limit raised, runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/thin_static_free.his', names, d)
      call check(s, d(2, size(d, 2)) > 0.05_wp, &
                 'static detection misses the crossing: the block passes through (documented)', &
                 'final face displacement '//rtoa(d(2, size(d, 2))))
      call check(s, file_has(run_dir//'/thin_static_free.out', 'warning: the physical energy'), &
                 'the energy growth past the warning limit is a warning in <stem>.out')
   end subroutine thin_target_test

   !> Penalty: finite penetration that falls as k grows, and a stable step that falls as k grows.
   subroutine penalty_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, k
      real(wp) :: pen(3), dtmin(3), kk(3)
      character(len=40) :: extra
      character(len=16) :: tag
      kk = [1.0e4_wp, 1.0e5_wp, 1.0e6_wp]
      do k = 1, 3
         write (extra, '(a,es10.3)') '    PENAlty,', kk(k)
         write (tag, '(a,i0)') 'penalty_', k
         call run_deck(trim(tag), bar_deck('bar on a wall, penalty', 30, 6, 'wall', rho0, rho0, 'NTOS', &
                       2.5_wp*blen/sqrt(young/rho0), trim(extra)//nl), stage, msg)
         call check(s, stage == 0, 'penalty run k = '//rtoa(kk(k)), msg)
         if (stage /= 0) return
         call read_table(run_dir//'/'//trim(tag)//'.his', names, d)
         call read_table(run_dir//'/'//trim(tag)//'.ene', names, e)
         pen(k) = maxval(d(7, :))
         dtmin(k) = minval(e(3, 2:size(e, 2) - 5))
         print '(a,es10.3,a,es10.3,a,es10.3)', '      figures penalty k = ', kk(k), ': largest penetration ', &
            pen(k), ', smallest step ', dtmin(k)
      end do
      call check(s, all(pen > 0.0_wp), 'penalty leaves a finite penetration')
      call check(s, pen(2) < pen(1) .and. pen(3) < pen(2), 'penetration falls as k grows')
      call check(s, dtmin(2) <= dtmin(1) .and. dtmin(3) < dtmin(2), 'the stable step falls as k grows')
   end subroutine penalty_test

   !> A deck of bar 1 (region 1, material 1) from x = 0 to blen moving at +v0, and (mode) 'wall':
   !> a rigid wall at x = blen; 'bars': a second bar of density rho2 from blen to 2 blen moving at
   !> -v0; 'fixed': no second body and no contact, the tip's x-displacement fixed instead.
   function bar_deck(title, nx, ny, mode, rho1, rho2, pair_kind, tmax, extra) result(deck)
      character(len=*), intent(in) :: title, mode, pair_kind, extra
      integer, intent(in) :: nx, ny
      real(wp), intent(in) :: rho1, rho2, tmax
      character(len=:), allocatable :: deck
      character(len=400) :: b
      logical :: wall, fixed
      wall = mode == 'wall'
      fixed = mode == 'fixed'
      deck = 'FEAP * * '//title//nl//'0 0 0 2 2 4'//nl
      write (b, '(a,es23.16,a,es23.16,a,es23.16,a,es23.16)') 'PARAmeters'//nl//'  young = ', young, &
         nl//'  v0 = ', v0, nl//'  rhoa = ', rho1, nl//'  rhob = ', rho2
      deck = deck//trim(b)//nl
      write (b, '(a,es23.16,a,es23.16,a,i0,a,i0)') '  len = ', blen, nl//'  hgt = ', bhgt, &
         nl//'  nx = ', nx, nl//'  ny = ', ny
      deck = deck//trim(b)//nl//nl
      deck = deck//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young 0'//nl// &
             '    DENSity rhoa'//nl//nl
      if (wall) then
         deck = deck//'MATErial,2'//nl//'  RIGId'//nl//'    DENSity rhoa'//nl//nl
      else
         deck = deck//'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young 0'//nl// &
                '    DENSity rhob'//nl//nl
      end if
      deck = deck//'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,nx,ny,0,0,1'//nl//'    1,0,0'//nl// &
             '    2,len,0'//nl//'    3,len,hgt'//nl//'    4,0,hgt'//nl//nl
      if (fixed) then
         deck = deck//'EBOUndary'//nl//'  1,len,1,0'//nl//nl
      else if (wall) then
         deck = deck//'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,4,0,0,2'//nl//'    1,len,-hgt'//nl// &
                '    2,len+hgt,-hgt'//nl//'    3,len+hgt,2*hgt'//nl//'    4,len,2*hgt'//nl//nl
      else
         deck = deck//'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,nx,ny,0,0,2'//nl//'    1,len,0'//nl// &
                '    2,2*len,0'//nl//'    3,2*len,hgt'//nl//'    4,len,hgt'//nl//nl
      end if
      deck = deck//'INITial,VELOcity'//nl//'  REGIon,1,v0,0'//nl
      if (mode == 'bars') deck = deck//'  REGIon,2,-v0,0'//nl
      deck = deck//nl
      if (.not. fixed) deck = deck//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
                              '    REGIon,2'//nl//'  PAIR,1,'//pair_kind//',1,2'//nl//extra//'END CONTact'//nl//nl
      deck = deck//'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl
      write (b, '(a,es23.16)') '    TIME,,', tmax
      deck = deck//'  LOOP,,10000000'//nl//trim(b)//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
             'END'//nl
      ! the bar's tip: node (nx, ny/2) of the first block
      write (b, '(a,i0,a,i0,a,i0,a)') '  disp,', 1 + (ny/2)*(nx + 1) + nx, ',1'//nl//'  velo,', &
         1 + (ny/2)*(nx + 1) + nx, ',1'//nl//'  acce,', 1 + (ny/2)*(nx + 1) + nx, ',1'
      deck = deck//trim(b)//nl
      if (fixed) then
         deck = deck//'  disp,1,1'//nl//nl//'STOP'
      else
         deck = deck//'  cont,1,1'//nl//'  cont,1,4'//nl//'  cont,1,5'//nl//'  cont,1,6'//nl// &
                '  mome,1,1'//nl//'  mome,2,1'//nl//nl//'STOP'
      end if
   end function bar_deck

   !> Seed example 7.1 in 1-D form: force rho c v0 H for 2L/c, momentum reversed, no penetration,
   !> tip velocity and acceleration zero two steps after contact (seed section 5).
   subroutine wall_test(s, nx, ny, mom_tol)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nx, ny
      real(wp), intent(in) :: mom_tol
      character(len=:), allocatable :: msg, name
      character(len=64), allocatable :: names(:), enames(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, k, n, k_on, k_off, kv, ka, kf, kn, kp, kx, kk, ku, ne
      real(wp) :: c, force, fmean, impulse, duration, mass, px, loss, worst_v, worst_a, dt, pen, pmax
      character(len=8) :: tag
      real(wp) :: tmax

      write (tag, '(i0,a,i0)') nx, 'x', ny
      name = 'wall_'//trim(tag)
      c = sqrt(young/rho0)
      tmax = 3.0_wp*blen/c
      call run_deck(name, bar_deck('bar on a rigid wall', nx, ny, 'wall', rho0, rho0, 'NTOS', tmax, ''), &
                    stage, msg)
      call check(s, stage == 0, 'bar-on-wall deck runs ('//trim(tag)//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//name//'.his', names, d)
      call read_table(run_dir//'/'//name//'.ene', enames, e)
      n = size(d, 2)
      kv = 3; ka = 4; kf = 5; kn = 6; kp = 7
      force = rho0*c*v0*bhgt
      ! contact from the first row with active constraints to the last
      k_on = 0; k_off = 0
      do k = 1, n
         if (d(kn, k) > 0.0_wp) then
            if (k_on == 0) k_on = k
            k_off = k
         end if
      end do
      call check(s, k_on == 1 .and. k_off > 1 .and. k_off < n, 'contact starts at t = 0 and ends ('//trim(tag)//')')
      if (k_off <= k_on) return
      call contact_measures(d(1, :), d(kf, :), force, impulse, duration, fmean)
      call check_close(s, fmean, force, 0.03_wp*force, 'mean contact force = rho c v0 H within 3 % ('//trim(tag)//')')
      call check_close(s, duration, 2.0_wp*blen/c, 0.03_wp*2.0_wp*blen/c, &
                       'contact lasts 2L/c within 3 % ('//trim(tag)//')')
      mass = rho0*blen*bhgt
      kx = column(enames, 'momentum_x')
      px = e(kx, size(e, 2))
      call check_close(s, px, -mass*v0, mom_tol*mass*v0, 'momentum after separation = -m v0 ('//trim(tag)//')')
      kk = column(enames, 'kinetic'); ku = column(enames, 'strain')
      ne = size(e, 2)
      loss = 1.0_wp - (e(kk, ne) + e(ku, ne))/(e(kk, 1) + e(ku, 1))
      print '(a,a,es10.3,a,es10.3,a,es10.3,a,es10.3)', '      figures ', trim(tag)//': force/exact-1 ', &
         fmean/force - 1.0_wp, ', duration/exact-1 ', duration/(2.0_wp*blen/c) - 1.0_wp, &
         ', momentum/exact-1 ', px/(-mass*v0) - 1.0_wp, ', energy lost ', loss
      print '(a,es10.3)', '      expected energy loss ~ 1/(2N) = ', 0.5_wp/real(nx, wp)
      pen = maxval(d(kp, :))
      call check(s, pen < 1.0e-10_wp*blen, 'largest penetration below 1e-10 L ('//trim(tag)//')', &
                 'largest '//rtoa(pen))
      ! seed section 5: two steps after contact the tip's normal velocity and acceleration vanish
      dt = e(3, 2)
      worst_v = maxval(abs(d(kv, k_on + 2:k_off)))
      worst_a = maxval(abs(d(ka, k_on + 2:k_off)))
      call check(s, worst_v <= 1.0e-8_wp*v0, 'tip velocity zero from two steps after contact ('//trim(tag)//')', &
                 'largest |v|/v0 '//rtoa(worst_v/v0))
      call check(s, worst_a <= 1.0e-8_wp*v0/dt, 'tip acceleration zero from two steps after contact ('//trim(tag)//')', &
                 'largest |a| dt/v0 '//rtoa(worst_a*dt/v0))
      ! Lagrange contact does not cut the step: dt during contact equals dt before it
      call fixed_tip_check(s, name, nx, ny, k_off)
      pmax = maxval(d(7 + 1, :))
      call check(s, pmax <= 10.0_wp*force, 'no multiplier above 10x the exact contact force ('//trim(tag)//')', &
                 'largest '//rtoa(pmax))
   end subroutine wall_test

   !> Seed 7.1: the same bar with its tip's x-displacement fixed instead of the wall gives the
   !> same displacements and the same time steps while contact lasts (so contact neither cuts
   !> the step nor adds anything a fixed support would not).
   subroutine fixed_tip_check(s, name, nx, ny, k_off)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      integer, intent(in) :: nx, ny, k_off
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: dw(:, :), df(:, :), ew(:, :), ef(:, :)
      integer :: stage, n
      real(wp) :: diff_dt, diff_u
      call run_deck(name//'_fixed', bar_deck('bar with a fixed tip', nx, ny, 'fixed', rho0, rho0, 'NTOS', &
                    3.0_wp*blen/sqrt(young/rho0), ''), stage, msg)
      call check(s, stage == 0, 'fixed-tip deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//name//'.his', names, dw)
      call read_table(run_dir//'/'//name//'_fixed.his', names, df)
      call read_table(run_dir//'/'//name//'.ene', names, ew)
      call read_table(run_dir//'/'//name//'_fixed.ene', names, ef)
      n = min(k_off, size(df, 2))
      diff_dt = maxval(abs(ew(3, 1:n) - ef(3, 1:n)))/ef(3, 1)
      call check(s, diff_dt <= 1.0e-12_wp, 'time steps equal those of the fixed-tip run while contact lasts', &
                 'largest relative difference '//rtoa(diff_dt))
      ! x-displacement of node 1 (the free end) in both runs
      diff_u = maxval(abs(dw(2, 1:n) - df(2, 1:n)))
      call check(s, diff_u <= 1.0e-12_wp*blen, 'tip stays where a fixed support holds it', &
                 'largest difference '//rtoa(diff_u))
   end subroutine fixed_tip_check

   !> Two bars meeting at x = blen, bar 1 at +v0 with density rho1 <= rho2, bar 2 at -v0 with
   !> density rho2. Exact (doc/contact-verification.md): force 2 v0 Z1 Z2/(Z1 + Z2) H for 2L/c1
   !> (bar 1 is the faster), then p1 = m1 v0 (Z1 - 3 Z2)/(Z1 + Z2), p2 = p1(0) + p2(0) - p1.
   subroutine two_bar_test(s, rho1, rho2, kind, name)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: rho1, rho2
      character(len=*), intent(in) :: kind, name
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, k, n, k_on, k_off
      real(wp) :: c1, c2, z1, z2, force, fmean, impulse, duration, m1, p1_exact, pmax, dur

      c1 = sqrt(young/rho1)
      c2 = sqrt(young/rho2)
      z1 = rho1*c1
      z2 = rho2*c2
      force = 2.0_wp*v0*z1*z2/(z1 + z2)*bhgt
      dur = 2.0_wp*blen/max(c1, c2)
      call run_deck(name, bar_deck('two bars', 30, 6, 'bars', rho1, rho2, kind, 3.0_wp*blen/min(c1, c2), ''), &
                    stage, msg)
      call check(s, stage == 0, name//' deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//name//'.his', names, d)
      n = size(d, 2)
      k_on = 0; k_off = 0
      do k = 1, n
         if (d(6, k) > 0.0_wp) then
            if (k_on == 0) k_on = k
            k_off = k
         end if
      end do
      call check(s, k_on == 1 .and. k_off > 1 .and. k_off < n, name//': contact starts at t = 0 and ends')
      if (k_off <= k_on) return
      call contact_measures(d(1, :), d(5, :), force, impulse, duration, fmean)
      call check_close(s, fmean, force, 0.03_wp*force, name//': mean contact force within 3 % of the exact one')
      call check_close(s, duration, dur, 0.03_wp*dur, name//': bars part after 2L/c (faster bar) within 3 %')
      print '(a,a,es10.3,a,es10.3)', '      figures ', name//': force/exact-1 ', fmean/force - 1.0_wp, &
         ', duration/exact-1 ', duration/dur - 1.0_wp
      pmax = maxval(d(8, :))
      call check(s, pmax <= 10.0_wp*force, name//': no multiplier above 10x the exact contact force', &
                 'largest '//rtoa(pmax))
      m1 = rho1*blen*bhgt
      p1_exact = m1*v0*(z1 - 3.0_wp*z2)/(z1 + z2)
      call momentum_check(s, name, p1_exact, m1*v0 - rho2*blen*bhgt*v0 - p1_exact, m1*v0)
   end subroutine two_bar_test

   !> Final momentum of each bar from its nodes' velocities in the last history rows.
   subroutine momentum_check(s, name, p1_exact, p2_exact, scale)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: p1_exact, p2_exact, scale
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      call read_table(run_dir//'/'//name//'.his', names, d)
      call check_close(s, d(9, size(d, 2)), p1_exact, 0.04_wp*scale, name//': momentum of bar 1 after separation (4 %)')
      call check_close(s, d(10, size(d, 2)), p2_exact, 0.04_wp*scale, name//': momentum of bar 2 after separation (4 %)')
      print '(a,a,es10.3,a,es10.3,a)', '      figures ', name//': momentum errors (bar 1, bar 2) / (m1 v0) ', &
         (d(9, size(d, 2)) - p1_exact)/scale, ', ', (d(10, size(d, 2)) - p2_exact)/scale, ''
   end subroutine momentum_check

   !> Contact measures from a force history f(t): impulse I = sum f_k (t_(k+1) - t_(k-1))/2 (the
   !> central-difference impulse of each step's force), duration from first contact to the last
   !> crossing of half the exact force (the middle of the smeared release front), mean I/T.
   subroutine contact_measures(t, f, fexact, impulse, duration, fmean)
      real(wp), intent(in) :: t(:), f(:), fexact
      real(wp), intent(out) :: impulse, duration, fmean
      integer :: k, n
      real(wp) :: tl, tr, t_end
      n = size(t)
      impulse = 0.0_wp
      t_end = t(1)
      do k = 1, n
         tl = t(max(k - 1, 1))
         tr = t(min(k + 1, n))
         impulse = impulse + f(k)*0.5_wp*(tr - tl)
         if (k > 1) then
            if (f(k - 1) >= 0.5_wp*fexact .and. f(k) < 0.5_wp*fexact) &
               t_end = t(k - 1) + (t(k) - t(k - 1))*(f(k - 1) - 0.5_wp*fexact)/(f(k - 1) - f(k))
         end if
      end do
      duration = t_end - t(1)
      fmean = impulse/max(duration, tiny(1.0_wp))
   end subroutine contact_measures

end module test_contact
