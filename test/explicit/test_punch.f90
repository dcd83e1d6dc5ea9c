!> A deformable punch resting on a block (touching at t = 0) and driven into it by DISPlacement
!> of its top nodes (doc/loads.md, section 3): the work of the prescribed motion is counted from
!> the first step, whatever the order of first touch and first motion (issue 32, item 1).
!>
!> Block 2 x 1 (8 x 4 elements, neo-Hookean E = 1e4, nu = 0.3, rho = 1), its base fixed by
!> EBOUndary; punch 0.5 x 0.2 (2 x 2 elements, E = 1e5) on its top face, the punch's face nodes
!> on the block's; NTOS punch nodes against the block. The punch's top nodes move down at
!> v = 1 (v / c = 0.009): from t = 0 (the unit ramp p = t: the velocity jumps at the start) or
!> from t0 = 0.005 (a table: at rest while touching, then the jump). Before the booking of
!> eq. P.3 and the guard of eq. P.4 (exic 1d04b3f) the first warned (9.0 % at step 1) and the
!> second stopped at the jump (4329 % at step 22: the kinetic energy the jump gives the driven
!> nodes' mass was no work).
!> Asserted: the run ends with no warning; the balance of <stem>.ene (total) stays within
!> 1e-3 of W_pm (prescribed_work at the end); with the constant velocity, W_pm equals the
!> trapezoid rule in time of the reaction (reac,REGIon,2,2 of <stem>.his) times -v to round-off.
!>
!> A rigid punch 0.075 above the block, at rest, then driven down at v / c = 0.03 (variant v128 of
!> tools/stress/punch_family.py, punch_rigid_beside_corner): a block node under the punch's
!> corner is held by the bottom face, not by the side face it lies behind (doc/contact-detection.md,
!> "A node beside a master's convex corner"); exic 0461a1e stopped at step 119 (13.8 %).
!>
!> A rigid punch driven into a plastic block (plastic_punch): its balance closes with the plastic
!> work of doc/plasticity.md (J31).
!>
!> A rigid punch touching a block at t = 0, its MOTIon velocity ramped from 0 by a table
!> (variant v341 of tools/stress/punch_family.py: AUTOmatic contact, one-point elastic block
!> 6 x 4, nu = 0, CFL 0.95): exic 1c14650 warned at step 3 (1.62 % of the energy put in, "element
!> 26"): the guard lacked the contact force's part of the kinetic correction (doc/loads.md, eq.
!> P.5). Asserted: no warning and the balance within 1e-3 of W_pm; the same deck switched to
!> DT,,0.0056 (2.5 times its stable step) after t = 0.02 must still be stopped by the guard.
module test_punch
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa, itoa
   use testing, only: suite_t, check, file_text
   use deck_runner, only: run_dir, run_deck, read_table, column, file_has
   implicit none
   private

   public :: run_punch_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_punch_tests(s)
      type(suite_t), intent(inout) :: s
      call driven_punch(s, 'punch_touch', '', 'from t = 0')
      call driven_punch(s, 'punch_late', '2, 0'//nl//'0, 0, 0.005, 0, 0.05, 0.045', 'from t0 = 0.005')
      ! d = -1.1: at x0 + d its top nodes would lie 0.1 inside the block's bottom row, within the
      ! search depth, where the start-up overlap test once saw them (doc/loads.md, section 3)
      call driven_punch(s, 'punch_far', '', 'from t = 0 at 1.1', 1.1_wp)
      call rigid_punch_corner(s)
      call rigid_punch_beside_corner(s)
      call plastic_punch(s, 'punch_plastic2', '    MIXEd', '2x2 MIXEd')
      call plastic_punch(s, 'punch_plastic1', '    QUADrature 1', 'one point')
      call ramped_rigid_punch(s, 'punch_rigid_ramp', .false.)
      call ramped_rigid_punch(s, 'punch_rigid_ramp_unstable', .true.)
      ! v1 and v48 of tools/stress/punch_family.py (rounded): the punch's corner slides into the
      ! block's concave corner (C.1) or rides on the block's node at it (C.3)
      call concave_corner_punch(s, 'punch_concave_offset', 8, 4, .true., '0.49', '0.8425', '1.3425', &
                                '46,33', '12.41', '', '0.5', '0.0145', '4e-4')
      call concave_corner_punch(s, 'punch_concave_aligned', 4, 2, .false., '0.3', '0.5', '1.5', &
                                '16,9', '3.48', '0, 0, 0.00905, 0, 0.00905, 1', '0.95', '0.0724', '4.5e-3')
      ! the corner pass of an NTOS pair (doc/contact-detection.md, "Corner pass of a one-pass pair")
      call rigid_punch_checks(s, 'corner_pass_punch_56', file_text('test/data/stress/corner_pass_punch_56.inp'), &
                              'corner pass, rigid punch (v56)')
      call corner_pass_punch(s, 'corner_pass_punch_372', 'a deformable punch''s corner (v372)')
      call corner_pass_punch(s, 'corner_pass_peak_358', 'a block''s peak inside the punch (v358, K.2)')
      ! the guard's contact part at a deformable punch's first contact (doc/loads.md, eq. P.6)
      call corner_pass_punch(s, 'guard_first_contact_272', 'a deformable punch''s first contact (v272, P.6)')
   end subroutine run_punch_tests

   !> Decks of tools/stress/punch_family.py saved in test/data/stress (their first comment lines
   !> say what each showed): the block's nodes as NTOS slaves under a deformable punch's corner
   !> (v372: exic 6847b2b stopped at step 4469, growth 46 times the energy put in), and the
   !> punch's nodes as slaves over a plastic block whose crushed peak lies inside the punch (v358:
   !> the corner pass without its rule K.2 stopped at step 134, 2.8 times the energy put in), and
   !> a deformable punch's first contact (v272: the guard with the whole C_con of doc/loads.md
   !> eq. P.5 warned at step 3870, 1.34 %; eq. P.6 takes it where it lowers the measure).
   !> Asserted: the run ends with no warning and the balance closes within 1e-3 of W_pm.
   subroutine corner_pass_punch(s, name, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, what
      character(len=:), allocatable :: msg
      integer :: stage
      real(wp) :: wpm, drift
      call run_deck(name, file_text('test/data/stress/'//name//'.inp'), stage, msg)
      call check(s, stage == 0, name//': '//what//' runs to the end', msg)
      if (stage /= 0) return
      call check(s, .not. file_has(run_dir//'/'//name//'.out', 'warning:'), name//': no warning')
      call punch_balance(name, wpm, drift)
      call check(s, wpm > 0.0_wp .and. drift <= 1.0e-3_wp, name//': the balance closes within 0.1 % of W_pm', &
                 'W_pm '//rtoa(wpm)//', largest drift '//rtoa(drift))
   end subroutine corner_pass_punch

   !> Issue 32, item 1, the punch's nodes as one-pass slaves (`PAIR,1,NTOS,punch,block`): a RIGId
   !> punch (2 x 2 elements, 0.2 high, from xa to xb) resting on a block 2 x 1 of nx x ny
   !> neo-Hookean elements (E = 1e4, nu, one point when q1) driven down at v by MOTIon (from t = 0,
   !> or at rest until a table `late` switches it on). The block's surface under the punch's
   !> corner makes a concave corner (flat under the punch, rising or falling beside it) into which
   !> the corner node, a slave, slides (doc/contact-detection.md, "A node sliding into a master's
   !> concave corner"). exic 0461a1e left the corner node 1.9e-3 (offset) and 2.8e-3 element edges
   !> (aligned) inside the block, clamped to the block's node with the averaged normal. Field
   !> output every `dt` runs the geometric penetration check at each (doc/decisions.md).
   !> Asserted: the run ends with no warning, the deepest node of the check over the run is below
   !> its warning limit of 1e-3 element edges, and the balance closes within 1e-3 of W_pm.
   subroutine concave_corner_punch(s, name, nx, ny, q1, nu, xa, xb, nodes, v, late, cfl, tend, dt)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, nu, xa, xb, nodes, v, late, cfl, tend, dt
      integer, intent(in) :: nx, ny
      logical, intent(in) :: q1
      character(len=:), allocatable :: deck, msg, out, line, motion, fn, quad, prop
      integer :: stage, at, k, ios
      real(wp) :: wpm, drift, edges
      motion = 'MOTIon,REGIon,2,0,-'//v
      fn = ''
      prop = ''
      if (len(late) > 0) then
         motion = motion//',0,1'
         fn = '2, 0'//nl//late//nl//nl
         prop = '  PROPortional,,1'//nl
      end if
      quad = ''
      if (q1) quad = '    QUADrature 1'//nl
      deck = 'FEAP * * rigid punch, its nodes as slaves'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 '//nu//nl//'    DENSity 1'//nl// &
             quad//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,'//itoa(nx)//','//itoa(ny)//',1,1,1'//nl// &
             '    1,0,0'//nl//'    2,2,0'//nl//'    3,2,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,'//nodes//',2'//nl//'    1,'//xa//',1'//nl// &
             '    2,'//xb//',1'//nl//'    3,'//xb//',1.2'//nl//'    4,'//xa//',1.2'//nl//nl// &
             'EBOUndary'//nl//'  2,0,1,1'//nl//nl//motion//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,2,1'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl// &
             prop// &
             '  OUTPut,HDF5,'//dt//nl//'  DT,CFL,'//cfl//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl// &
             '    TIME,,'//tend//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//fn// &
             '  reac,REGIon,2,2'//nl//nl//'STOP'
      call run_deck(name, deck, stage, msg)
      call check(s, stage == 0, name//': a rigid punch, its nodes as slaves, runs to the end', msg)
      if (stage /= 0) return
      out = file_text(run_dir//'/'//name//'.out')
      call check(s, index(out, 'warning:') == 0, name//': no warning (geometric penetration check)')
      ! "geometric penetration check: deepest node N of region R, X edges (...)": none when no node
      ! was inside
      edges = 0.0_wp
      at = index(out, 'geometric penetration check: deepest node')
      if (at > 0) then
         line = out(at:)
         k = index(line, new_line('a'))
         if (k > 0) line = line(:k - 1)
         line = line(index(line, ',') + 1:)
         read (line(:index(line, 'edges') - 1), *, iostat=ios) edges
         if (ios /= 0) edges = huge(1.0_wp)
      end if
      call check(s, edges < 1.0e-3_wp, name//': the punch''s corner stays outside the block (deepest node '// &
                 'of the check over the run below 1e-3 element edges)', 'deepest '//rtoa(edges)//' edges')
      call punch_balance(name, wpm, drift)
      call check(s, wpm > 0.0_wp .and. drift <= 1.0e-3_wp, name//': the balance closes within 0.1 % of '// &
                 'the work of the prescribed motion', 'W_pm '//rtoa(wpm)//', largest drift '//rtoa(drift))
   end subroutine concave_corner_punch

   !> Issue 32, item 1: a RIGId punch 0.5 wide resting on the block (touching), driven down at
   !> v = 0.1 by MOTIon,REGIon, NTOS with the BLOCK's nodes as slaves. The block's nodes under the
   !> punch's corners are held at the corners (doc/contact-detection.md, "A node at a master's
   !> convex corner"); before that rule (exic 1c14650) the run stopped at step 6 on the energy
   !> guard (growth 67 %, "largest contributor: contact pair 1"). Asserted: the run ends with no
   !> warning, the balance closes within 1e-3 of W_pm, and W_pm is the trapezoid rule of the
   !> reaction over the punch's displacement (reac,REGIon,2,2 and rigi,2,2 of <stem>.his).
   subroutine rigid_punch_corner(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: deck
      deck = 'FEAP * * rigid punch touching a block, block nodes as slaves'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,8,4,1,1,1'//nl//'    1,0,0'//nl//'    2,2,0'//nl// &
             '    3,2,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,46,33,2'//nl//'    1,0.75,1'//nl//'    2,1.25,1'//nl// &
             '    3,1.25,1.2'//nl//'    4,0.75,1.2'//nl//nl// &
             'EBOUndary'//nl//'  2,0,1,1'//nl//nl//'MOTIon,REGIon,2,0,-0.1'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl// &
             '  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,0.1'//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  reac,REGIon,2,2'//nl//'  rigi,2,2'//nl//nl//'STOP'
      call rigid_punch_checks(s, 'punch_rigid_corner', deck, 'block nodes as slaves')
   end subroutine rigid_punch_corner

   !> Variant v128 of tools/stress/punch_family.py: the rigid punch 0.075 above the block (8 x 4,
   !> nu = 0.3), at rest, then driven down at v / c = 0.03 from t0 = 0.0147 (MOTIon times a
   !> table: the velocity jumps), DT,CFL,0.7, NTOS with the block's nodes as slaves. A block node
   !> under the punch's corner, on the bottom face and 0.022 inside the side face's line (within
   !> the search depth), was caught by the side face at tau_c = 0 (its crossing of the bottom face
   !> came 1e-16 later) and pushed 0.022 sideways: exic 0461a1e warned at step 97 and stopped at
   !> step 119 (growth 13.8 % of the energy put in, "contact pair 1"). With the rule of
   !> doc/contact-detection.md, "A node beside a master's convex corner", the bottom face holds it.
   !> Asserted as for punch_rigid_corner.
   subroutine rigid_punch_beside_corner(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: deck
      deck = 'FEAP * * rigid punch apart, late, block nodes as slaves'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,8,4,1,1,1'//nl//'    1,0,0'//nl//'    2,2,0'//nl// &
             '    3,2,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,46,33,2'//nl//'    1,0.75,1.075'//nl// &
             '    2,1.25,1.075'//nl//'    3,1.25,1.2749999999999999'//nl// &
             '    4,0.75,1.2749999999999999'//nl//nl// &
             'EBOUndary'//nl//'  2,0,1,1'//nl//nl//'MOTIon,REGIon,2,0,-3.4807161066919283,0,1'//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl// &
             '  PROPortional,,1'//nl//'  DT,CFL,0.7'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl// &
             '    TIME,,0.10807761634933466'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '2, 0'//nl//'0, 0, 0.014706025550773397, 0, 0.014706025550773397, 1'//nl//nl// &
             '  reac,REGIon,2,2'//nl//'  rigi,2,2'//nl//nl//'STOP'
      call rigid_punch_checks(s, 'punch_rigid_beside_corner', deck, 'block node beside the corner')
   end subroutine rigid_punch_beside_corner

   !> Run a rigid punch's deck (`reac,REGIon,2,2` and `rigi,2,2` its two histories) and check: it
   !> ends with no warning, the balance closes within 1e-3 of W_pm, and W_pm is the trapezoid
   !> rule of the reaction over the punch's displacement.
   subroutine rigid_punch_checks(s, name, deck, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, deck, what
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: hn(:)
      real(wp), allocatable :: h(:, :)
      integer :: stage, i
      real(wp) :: wpm, drift, w
      call run_deck(name, deck, stage, msg)
      call check(s, stage == 0, 'a rigid punch driven into a block ('//what//') runs to the end', msg)
      if (stage /= 0) return
      call check(s, .not. file_has(run_dir//'/'//name//'.out', 'warning:'), &
                 'rigid punch, '//what//': no warning (energy guard)')
      call read_table(run_dir//'/'//name//'.his', hn, h)
      call punch_balance(name, wpm, drift)
      call check(s, wpm > 0.0_wp .and. drift <= 1.0e-3_wp, 'rigid punch, '//what//': the balance '// &
                 'closes within 0.1 % of W_pm', 'W_pm '//rtoa(wpm)//', largest drift '//rtoa(drift))
      w = 0.0_wp
      do i = 1, size(h, 2) - 1
         w = w + 0.5_wp*(h(2, i) + h(2, i + 1))*(h(3, i + 1) - h(3, i))
      end do
      call check(s, abs(w - wpm) <= 1.0e-6_wp*wpm, 'rigid punch, '//what//': W_pm = the integral '// &
                 'of the reaction over the punch''s displacement (.his)', 'int R du '//rtoa(w)//', W_pm '//rtoa(wpm))
   end subroutine rigid_punch_checks

   !> A rigid punch resting on a plastic block (PLAStic MISEs, yield 2e-3 E), driven into it by
   !> MOTIon at v / c = 0.01, DT,CFL,0.95, 4 x 2 elements, NTOS block nodes against the punch
   !> with friction: the worst variant of tools/stress/punch_family.py before the plastic work
   !> was booked by the trapezoid rule of the stress power (doc/plasticity.md (J31)): drift
   !> 3.2 % of W_pm with 2x2 MIXEd, 2.8 % with one point (exic 1c14650; with (J31) 5.6e-6 and
   !> 6.1e-6). Asserted: runs without a warning, the block yields, the balance (total of
   !> <stem>.ene) stays within 1e-3 of W_pm: a conservation law, the plastic work being what the
   !> forces did and the block did not store.
   subroutine plastic_punch(s, name, element, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, element, what
      character(len=:), allocatable :: deck, msg
      character(len=64), allocatable :: en(:)
      real(wp), allocatable :: e(:, :)
      integer :: stage, itot, iwpm, iwp
      real(wp) :: wpm, drift
      deck = 'FEAP * * rigid punch into a plastic block'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 0.3'//nl//'    DENSity 1'//nl// &
             '    PLAStic MISEs 20'//nl//element//nl//nl//'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,1,1,2'//nl//'    1,0.5,1'//nl//'    2,1.5,1'//nl// &
             '    3,1.5,1.2'//nl//'    4,0.5,1.2'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,4,2,10,5,1'//nl//'    1,0,0'//nl//'    2,2,0'//nl// &
             '    3,2,1'//nl//'    4,0,1'//nl//nl//'EBOUndary'//nl//'  2,0,1,1'//nl//nl// &
             'MOTIon,REGIon,1,0,-1.16'//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,2'//nl//'  SURFace,2'//nl//'    REGIon,1'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'    FRICtion,COULomb,0.3'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,CFL,0.95'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,0.0517'//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  reac,REGIon,1,2'//nl//nl//'STOP'
      call run_deck(name, deck, stage, msg)
      call check(s, stage == 0, 'a rigid punch driven into a plastic block ('//what//') runs to the end', msg)
      if (stage /= 0) return
      call check(s, .not. file_has(run_dir//'/'//name//'.out', 'warning:'), &
                 'plastic block, '//what//': no warning (energy guard)')
      call read_table(run_dir//'/'//name//'.ene', en, e)
      itot = column(en, 'total')
      iwpm = column(en, 'prescribed_work')
      iwp = column(en, 'plastic_work')
      wpm = e(iwpm, size(e, 2))
      drift = maxval(abs(e(itot, :) - e(itot, 1)))/max(wpm, tiny(1.0_wp))
      call check(s, wpm > 0.0_wp .and. e(iwp, size(e, 2)) > 0.1_wp*wpm .and. drift <= 1.0e-3_wp, &
                 'plastic block, '//what//': it yields (plastic work above 10 % of W_pm) and the balance '// &
                 'closes within 0.1 % of W_pm', 'W_pm '//rtoa(wpm)//', plastic work '// &
                 rtoa(e(iwp, size(e, 2)))//', largest drift '//rtoa(drift))
   end subroutine plastic_punch

   !> The rigid punch touching at t = 0 under a ramped MOTIon (the module header); `unstable`:
   !> the step raised to 2.5 times the stable one after t = 0.02.
   subroutine ramped_rigid_punch(s, name, unstable)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      logical, intent(in) :: unstable
      character(len=:), allocatable :: deck, msg, batch
      integer :: stage
      real(wp) :: wpm, drift
      if (unstable) then
         batch = '  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,0.02'//nl// &
                 '    FORM,EXPLicit'//nl//'  NEXT'//nl//'  DT,,0.0056'//nl//'  LOOP,,1000000'//nl// &
                 '    TIME,,0.28'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl
      else
         batch = '  DT,CFL,0.95'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,0.28'//nl// &
                 '    FORM,EXPLicit'//nl//'  NEXT'//nl
      end if
      deck = 'FEAP * * rigid punch touching, ramped MOTIon'//nl//'  0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 10000 0'//nl//'    DENSity 1'//nl// &
             '    QUADrature 1'//nl//nl//'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,1,1,2'//nl//'    1,1,1'//nl//'    2,2,1'//nl// &
             '    3,2,1.2'//nl//'    4,1,1.2'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,6,4,10,5,1'//nl//'    1,0,0'//nl//'    2,3,0'//nl// &
             '    3,3,1'//nl//'    4,0,1'//nl//nl//'EBOUndary'//nl//'  2,0,1,1'//nl//nl// &
             'MOTIon,REGIon,1,0,-0.1,0,1'//nl//'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl//batch//'END'//nl// &
             '2, 0'//nl//'0, 0, 0.07, 1'//nl//nl//'  reac,REGIon,1,2'//nl//nl//'STOP'
      call run_deck(name, deck, stage, msg)
      if (unstable) then
         call check(s, stage == 2 .and. index(msg, 'exceeds the energy put in') > 0, &
                    'a ramped rigid punch at 2.5 times the stable step is stopped by the energy guard', msg)
         return
      end if
      call check(s, stage == 0, 'a rigid punch touching a block under a ramped MOTIon runs to the end', msg)
      if (stage /= 0) return
      call check(s, .not. file_has(run_dir//'/'//name//'.out', 'warning:'), &
                 'ramped rigid punch touching: no warning (energy guard, doc/loads.md eq. P.5)')
      call punch_balance(name, wpm, drift)
      call check(s, wpm > 0.0_wp .and. drift <= 1.0e-3_wp, 'ramped rigid punch touching: the balance closes '// &
                 'within 0.1 % of the work of the prescribed motion', 'W_pm '//rtoa(wpm)//', largest drift '//rtoa(drift))
   end subroutine ramped_rigid_punch

   !> The deck with function 1 given by `fn` (blank: the unit ramp) and its checks.
   subroutine driven_punch(s, name, fn, what, speed)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, fn, what
      real(wp), intent(in), optional :: speed    !< d = -speed (1 when absent)
      character(len=:), allocatable :: deck, msg
      character(len=64), allocatable :: hn(:)
      real(wp), allocatable :: h(:, :)
      integer :: stage, i
      real(wp) :: wpm, drift, w
      real(wp) :: v
      character(len=:), allocatable :: d
      v = 1.0_wp
      if (present(speed)) v = speed
      d = '-'//rtoa(v)
      deck = 'FEAP * * driven deformable punch'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e4 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1e5 0.3'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,8,4,1,1,1'//nl//'    1,0,0'//nl//'    2,2,0'//nl// &
             '    3,2,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,46,33,2'//nl//'    1,0.75,1'//nl//'    2,1.25,1'//nl// &
             '    3,1.25,1.2'//nl//'    4,0.75,1.2'//nl//nl// &
             'EBOUndary'//nl//'  2,0,1,1'//nl//nl//'BOUNdary'//nl//'  52,1,1,1'//nl//'  54,0,1,1'//nl//nl// &
             'DISPlacement'//nl//'  52,1,0,'//d//nl//'  54,0,0,'//d//nl//nl// &
             'FPROportional'//nl//'  52,1,1,1'//nl//'  54,0,1,1'//nl//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,2,1'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl// &
             '  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,0.04'//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//fn_data(fn)//'  reac,REGIon,2,2'//nl//nl//'STOP'
      call run_deck(name, deck, stage, msg)
      call check(s, stage == 0, 'a deformable punch touching a block, driven '//what//', runs to the end', msg)
      if (stage /= 0) return
      call check(s, .not. file_has(run_dir//'/'//name//'.out', 'warning:'), &
                 'driven '//what//': no warning (energy guard)')
      call read_table(run_dir//'/'//name//'.his', hn, h)
      call punch_balance(name, wpm, drift)
      call check(s, wpm > 0.0_wp .and. drift <= 1.0e-3_wp, 'driven '//what//': the balance closes within '// &
                 '0.1 % of the work of the prescribed motion', 'W_pm '//rtoa(wpm)//', largest drift '//rtoa(drift))
      if (len(fn) > 0) return
      ! constant velocity -v: W_pm = sum 1/2 (R(n) + R(n+1)) (-v) (t(n+1) - t(n))
      w = 0.0_wp
      do i = 1, size(h, 2) - 1
         w = w - 0.5_wp*(h(2, i) + h(2, i + 1))*v*(h(1, i + 1) - h(1, i))
      end do
      call check(s, abs(w - wpm) <= 1.0e-9_wp*wpm, 'driven '//what//': W_pm = the integral of the reaction '// &
                 'times the velocity (.his)', 'int R v dt '//rtoa(w)//', W_pm '//rtoa(wpm))
   end subroutine driven_punch

   !> W_pm, the work of the prescribed motion at the end of run `name` (`prescribed_work` of its
   !> .ene), and the largest drift of its `total` from the first row over W_pm (doc/loads.md,
   !> section 3).
   subroutine punch_balance(name, wpm, drift)
      character(len=*), intent(in) :: name
      real(wp), intent(out) :: wpm, drift
      character(len=64), allocatable :: en(:)
      real(wp), allocatable :: e(:, :)
      integer :: itot
      call read_table(run_dir//'/'//name//'.ene', en, e)
      itot = column(en, 'total')
      wpm = e(column(en, 'prescribed_work'), size(e, 2))
      drift = maxval(abs(e(itot, :) - e(itot, 1)))/max(wpm, tiny(1.0_wp))
   end subroutine punch_balance

   !> The data of function 1 with its closing blank record (blank alone: the unit ramp p = t).
   function fn_data(fn) result(text)
      character(len=*), intent(in) :: fn
      character(len=:), allocatable :: text
      if (len(fn) > 0) then
         text = fn//nl//nl
      else
         text = nl
      end if
   end function fn_data

end module test_punch
