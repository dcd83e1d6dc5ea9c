!> Loads and prescribed motion (doc/loads.md) against exact answers and conservation laws:
!> gravity (free fall, first contact, a block resting on a rigid floor), FEAP proportional loads
!> on a 1-D bar (ramp and hold against the dynamic and static closed forms; a prescribed end
!> displacement), edge loads (resultant on the deformed edge; a spinning ring under a follower
!> pressure), a rigid punch driven into a block, the nodal arrays kept only for decks whose
!> steps read them, and the input errors with file:line.
module test_loads
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_explicit_step, only: stepper_t
   use exic_explicit_state, only: plus_zero
   use exic_explicit_loads, only: prop_fn_t, prop_eval, prop_value, FN_TYPE1, FN_TABLE, FN_RAMP
   use testing, only: suite_t, check, check_close, section, error_text
   use deck_runner, only: run_dir, run_deck, read_table, column, write_text
   implicit none
   private

   public :: run_loads_tests, setup_stepper

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: head = 'FEAP * * loads'//nl//'0 0 0 2 2 4'//nl
   character(len=*), parameter :: solid = 'MATErial,1'//nl//'  SOLId'//nl// &
                                          '    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl
   character(len=*), parameter :: floor = 'MATErial,2'//nl//'  RIGId'//nl//nl

contains

   subroutine run_loads_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'loads: proportional functions')
      call functions(s)
      call section(s, 'loads: gravity and body forces')
      call free_fall(s, 'GRAVity,0,-9.81'//nl, 'GRAVity')
      call free_fall(s, '', 'BODY')
      call first_touch(s)
      call resting_block(s)
      call section(s, 'loads: proportional loads on a 1-D bar')
      call bar_ramp_hold(s)
      call bar_prescribed_end(s)
      call section(s, 'loads: edge loads (CSURface)')
      call edge_values(s)
      call stretched_edge(s)
      call deforming_edge(s)
      call spinning_ring(s)
      call physical_edge(s)
      call section(s, 'loads: a rigid punch driven into a block')
      call punch(s, 'MOTIon,REGIon,2,0,-vp'//nl, 'motion')
      call punch(s, 'INITial,VELOcity'//nl//'  REGIon,2,0,-vp'//nl//nl, 'initial velocity')
      call spun_body(s)
      call driven_region(s)
      call section(s, 'loads: nodal arrays only for the decks whose steps read them')
      call lean_arrays(s)
      call section(s, 'loads: a step without external force does not read fext')
      call zero_forces(s)
      call section(s, 'loads: input errors name file:line')
      call bad_input(s)
   end subroutine run_loads_tests

   !> The loading's nodal arrays exist only where a step reads them (doc/performance.md 6.2,
   !> "Bytes per element"): none for a free block; constant gravity is added to fext once and
   !> not kept (fext is the block's weight); a driven rigid body has lever arms and v(n) but no
   !> free bodies' lumped masses; a free rigid body has those too. The stepper's work arrays
   !> (x, du, a_old, v~, fcon_old) exist for the driven body, not for the free block, before or
   !> after a plain step.
   subroutine lean_arrays(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: blk, rigid
      blk = block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)
      rigid = block(2, 1, 101, 5, 2, 2, 0.0_wp, 1.0_wp, 1.0_wp, 0.5_wp)
      call setup_stepper('lean_free', head//solid//blk//batch('0.1', ''), model, stp, err)
      if (.not. ok('free block')) return
      associate (ld => stp%ld)
         call check(s, .not. (ld%active .or. allocated(ld%fnode) .or. allocated(ld%fbody) .or. &
                    allocated(ld%fgrav) .or. allocated(ld%vold) .or. allocated(ld%fpro) .or. &
                    allocated(ld%wlump) .or. allocated(ld%rb%r) .or. allocated(ld%fedge)), &
                    'free block: no nodal array of loads, v(n), dof functions or bodies')
      end associate
      call check(s, .not. work_arrays(), 'free block: no stepper work arrays (x, du, a_old, v~, fcon_old)')
      call stp%start(err)
      if (.not. ok('free block start')) return
      call stp%advance(err)
      if (.not. ok('free block step')) return
      call check(s, .not. work_arrays() .and. stp%st%step == 1, &
                 'free block: a plain step allocates no work array either')
      call setup_stepper('lean_gravity', head//solid//blk//'GRAVity,0,-10'//nl//nl// &
                         batch('0.1', ''), model, stp, err)
      if (.not. ok('constant gravity')) return
      call check(s, .not. (allocated(stp%ld%fgrav) .or. allocated(stp%ld%fbody) .or. &
                 allocated(stp%ld%fnode)) .and. abs(sum(stp%st%fext(2, :)) + 10.0_wp) <= 1.0e-13_wp, &
                 'constant gravity: in fext once (weight -10), no gravity or body arrays kept', &
                 rtoa(sum(stp%st%fext(2, :))))
      call setup_stepper('lean_driven', head//solid//floor//blk//rigid//'MOTIon,REGIon,2,0,-1'//nl// &
                         nl//batch('0.1', ''), model, stp, err)
      if (.not. ok('driven body')) return
      call check(s, allocated(stp%ld%rb%r) .and. allocated(stp%ld%vold) .and. &
                 .not. allocated(stp%ld%wlump), 'driven body: lever arms and v(n), no free masses')
      call check(s, work_arrays() .and. allocated(stp%du) .and. allocated(stp%a_old) .and. &
                 allocated(stp%vt) .and. allocated(stp%fcon_old), 'driven body: the stepper''s work arrays')
      call setup_stepper('lean_body', head//solid//'MATErial,2'//nl//'  RIGId,FREE'//nl// &
                         '    DENSity 1'//nl//nl//blk//rigid//batch('0.1', ''), model, stp, err)
      if (.not. ok('free body')) return
      call check(s, allocated(stp%ld%rb%r) .and. allocated(stp%ld%wlump) .and. stp%ld%has_free, &
                 'free body: lever arms and lumped masses')
   contains
      logical function ok(what)
         character(len=*), intent(in) :: what
         ok = .not. allocated(err)
         if (.not. ok) call check(s, .false., what//': the deck reads and sets up', err%message)
      end function ok
      !> Any of the stepper's work arrays is allocated.
      logical function work_arrays()
         work_arrays = allocated(stp%x) .or. allocated(stp%du) .or. allocated(stp%a_old) .or. &
                       allocated(stp%vt) .or. allocated(stp%fcon_old)
      end function work_arrays
   end subroutine lean_arrays

   !> fext_zero (a plain step then reads +0 from the cache instead of fext, doc/performance.md
   !> 6.2): plus_zero is true for +0 only (not -0, NaN or the smallest subnormal number); a free
   !> block has the flag, a block under constant gravity not; and a deforming free block stepped
   !> with the flag and without it (fext read) has the same bits in u, v, a, the works, the
   !> energies and the momentum after 6 steps in which dt changes.
   subroutine zero_forces(s)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: with, without
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      real(wp) :: f(2, 3), dt
      integer :: k, changes
      f = 0.0_wp
      call check(s, plus_zero(f), 'plus_zero: +0 everywhere')
      f(2, 3) = -0.0_wp
      call check(s, .not. plus_zero(f), 'plus_zero: not with a -0')
      f(2, 3) = tiny(1.0_wp)*epsilon(1.0_wp)
      call check(s, .not. plus_zero(f), 'plus_zero: not with the smallest subnormal number')
      f(2, 3) = 0.0_wp
      f(1, 2) = ieee_value(1.0_wp, ieee_quiet_nan)
      call check(s, .not. plus_zero(f), 'plus_zero: not with a NaN')
      deck = head//solid//block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
             'INITial,VELOcity'//nl//'  2,0,0.01,0.002'//nl//'  3,0,0.02,0'//nl//'  5,0,0.01,0.003'//nl// &
             '  6,0,0.02,0.001'//nl//'  8,0,0.01,-0.002'//nl//'  9,0,0.02,0'//nl//nl// &
             batch('0.1', '')
      call setup_stepper('zero_with', deck, model, with, err)
      if (.not. ok('free block')) return
      call check(s, with%st%fext_zero, 'free block: fext_zero after set-up')
      call setup_stepper('zero_without', deck, model, without, err)
      if (.not. ok('free block, second copy')) return
      call with%start(err)
      if (.not. ok('start')) return
      call without%start(err)
      if (.not. ok('start, second copy')) return
      without%st%fext_zero = .false.
      changes = 0
      do k = 1, 6
         dt = with%st%dt
         call with%advance(err)
         if (.not. ok('step')) return
         if (with%st%dt /= dt) changes = changes + 1
         call without%advance(err)
         if (.not. ok('step, second copy')) return
      end do
      call check(s, with%st%fext_zero .and. with%st%step == 6 .and. changes > 0, &
                 'free block: fext_zero after 6 plain steps, dt changed in some', itoa(changes)//' changes')
      call check(s, same(with%st%u, without%st%u) .and. same(with%st%v, without%st%v) .and. &
                 same(with%st%a, without%st%a) .and. any(with%st%a /= 0.0_wp), &
                 'u, v, a: the same bits as with fext read')
      call check(s, same(reshape([with%st%energy%wext, with%st%energy%kinetic, with%st%energy%strain, &
                                  with%st%energy%hourglass, with%st%momentum, with%st%dt_residual], [7, 1]), &
                         reshape([without%st%energy%wext, without%st%energy%kinetic, without%st%energy%strain, &
                                  without%st%energy%hourglass, without%st%momentum, without%st%dt_residual], [7, 1])), &
                 'works, energies, momentum and the kinetic correction: the same bits')
      call setup_stepper('zero_gravity', head//solid//block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
                         'GRAVity,0,-10'//nl//nl//batch('0.1', ''), model, with, err)
      if (.not. ok('constant gravity')) return
      call with%start(err)
      if (.not. ok('constant gravity start')) return
      call check(s, .not. with%st%fext_zero, 'constant gravity: no fext_zero')
   contains
      logical function ok(what)
         character(len=*), intent(in) :: what
         ok = .not. allocated(err)
         if (.not. ok) call check(s, .false., what//': the deck reads and sets up', err%message)
      end function ok
      !> a and b have the same bits (signed zeros included).
      logical function same(a, b)
         real(wp), intent(in) :: a(:, :), b(:, :)
         same = all(transfer(a, 1_i8, size(a)) == transfer(b, 1_i8, size(b)))
      end function same
   end subroutine zero_forces

   !> Write `text` as run_dir/<name>.inp, read it and set up a stepper with its loads.
   subroutine setup_stepper(name, text, model, stp, err)
      character(len=*), intent(in) :: name, text
      type(model_t), intent(out) :: model
      type(stepper_t), intent(out) :: stp
      type(error_t), allocatable, intent(out) :: err
      call write_text(run_dir//'/'//name//'.inp', text)
      call read_deck(run_dir//'/'//name//'.inp', model, err)
      if (allocated(err)) return
      call stp%init(model%mesh, model%materials, model%contact, err, model%loads)
   end subroutine setup_stepper

   !> A deck's block of nx x ny elements over [x0, x0 + w] x [y0, y0 + h], region r, material m.
   function block(nx, ny, node1, elmt1, m, r, x0, y0, w, h) result(text)
      integer, intent(in) :: nx, ny, node1, elmt1, m, r
      real(wp), intent(in) :: x0, y0, w, h
      character(len=:), allocatable :: text
      text = 'REGIon,'//itoa(r)//nl//'BLOCk'//nl//'  CARTesian,'//itoa(nx)//','//itoa(ny)//','// &
             itoa(node1)//','//itoa(elmt1)//','//itoa(m)//nl// &
             '    1,'//rtoa(x0)//','//rtoa(y0)//nl//'    2,'//rtoa(x0 + w)//','//rtoa(y0)//nl// &
             '    3,'//rtoa(x0 + w)//','//rtoa(y0 + h)//nl//'    4,'//rtoa(x0)//','//rtoa(y0 + h)//nl//nl
   end function block

   !> The batch part: TPLOt every step, run to tmax, the requests (and data) after END.
   function batch(tmax, after, cfl) result(text)
      character(len=*), intent(in) :: tmax, after
      character(len=*), intent(in), optional :: cfl
      character(len=:), allocatable :: text
      text = 'END'//nl//'BATCh'//nl
      if (present(cfl)) text = text//'  '//cfl//nl
      text = text//'  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,'//tmax//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//after//nl//'STOP'
   end function batch

   !> A block (density 2) under gravity alone, or under BODY 0 -19.62 (the same force per unit
   !> volume), falls freely: u = -g t^2/2, v = -g t, a = -g at every step to round-off (central
   !> difference integrates a constant acceleration exactly), no lateral motion, its angular
   !> momentum about the origin (mome,1,3) is -m X_c g t, and kinetic + strain - external work
   !> stays zero.
   subroutine free_fall(s, load, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: load, what
      character(len=:), allocatable :: msg, mat
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, i, kt
      real(wp), parameter :: g = 9.81_wp, tmax = 0.5_wp
      real(wp) :: eu, ev, ea, ex, et, el, t
      mat = 'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 2'//nl
      if (what == 'BODY') mat = mat//'    BODY 0 -19.62'//nl
      call run_deck('free_fall', head//mat//nl//block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
                    load//batch('0.5', '  disp,9,2'//nl//'  velo,9,2'//nl// &
                    '  acce,5,2'//nl//'  disp,1,1'//nl//'  mome,1,3'//nl), stage, msg)
      call check(s, stage == 0, what//': free fall deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/free_fall.his', names, d)
      call read_table(run_dir//'/free_fall.ene', en, e)
      kt = column(en, 'total')
      eu = 0.0_wp
      ev = 0.0_wp
      ea = 0.0_wp
      ex = 0.0_wp
      et = 0.0_wp
      el = 0.0_wp
      do i = 1, size(d, 2)
         t = d(1, i)
         eu = max(eu, abs(d(2, i) + 0.5_wp*g*t*t))
         ev = max(ev, abs(d(3, i) + g*t))
         ea = max(ea, abs(d(4, i) + g))
         ex = max(ex, abs(d(5, i)))
         el = max(el, abs(d(6, i) + 2.0_wp*0.5_wp*g*t))
         et = max(et, abs(e(kt, i)))
      end do
      call check(s, abs(d(1, size(d, 2)) - tmax) < 1.0e-12_wp, what//': free fall reaches t = 0.5')
      call check(s, eu <= 1.0e-13_wp*g*tmax**2, what//': u = -g t^2/2 at every step', 'largest error '//rtoa(eu))
      call check(s, ev <= 1.0e-13_wp*g*tmax, what//': v = -g t at every step', 'largest error '//rtoa(ev))
      call check(s, el <= 1.0e-12_wp*g*tmax, what//': angular momentum -m X_c g t (mome,1,3)', &
                 'largest error '//rtoa(el))
      ! a is formed from the element forces of the translated block, zero up to the round-off of
      ! their gradients: E |u| eps / (rho h) (E = 1000, |u| <= 1.23, rho = 2, h = 0.5)
      call check(s, ea <= 100.0_wp*epsilon(1.0_wp)*1000.0_wp*1.23_wp/(2.0_wp*0.5_wp), &
                 what//': a = -g at every step (to round-off)', 'largest error '//rtoa(ea))
      call check(s, ex <= 1.0e-15_wp, what//': no lateral motion', 'largest '//rtoa(ex))
      call check(s, et <= 1.0e-13_wp*g*tmax**2*g, what//': kinetic + strain - external work stays 0', &
                 'largest '//rtoa(et))
   end subroutine free_fall

   !> A block released at height h = 0.05 above a rigid floor (g = 10) first touches it at
   !> t = sqrt(2h/g) = 0.1 within one step; over ten contact episodes (the corrector's impacts are
   !> inelastic: the struck nodes are stopped) the balance kinetic + strain - W_ext - W_con (with
   !> the kinetic correction, doc/decisions.md "Energy balance") holds within 0.5 % of the energy
   !> put in at every row.
   subroutine first_touch(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, i, first, nb, n
      real(wp) :: tc, dt, drift
      logical :: touching
      deck = head//solid//floor//block(4, 4, 1, 1, 1, 1, 0.0_wp, 0.05_wp, 1.0_wp, 1.0_wp)// &
             block(4, 1, 101, 17, 2, 2, -0.5_wp, -0.2_wp, 2.0_wp, 0.2_wp)//'GRAVity,0,-10'//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//batch('2.0', '  cont,1,3'//nl, 'DT,CFL,0.5')
      call run_deck('first_touch', deck, stage, msg)
      call check(s, stage == 0, 'dropped block deck runs (no energy error over ten bounces)', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/first_touch.his', names, d)
      call read_table(run_dir//'/first_touch.ene', en, e)
      tc = sqrt(2.0_wp*0.05_wp/10.0_wp)
      first = 0
      nb = 0
      touching = .false.
      do i = 1, size(d, 2)
         if (d(2, i) > 0.0_wp .and. first == 0) first = i
         if (d(2, i) > 0.0_wp .and. .not. touching) nb = nb + 1
         touching = d(2, i) > 0.0_wp
      end do
      call check(s, first > 1, 'the block touches the floor')
      if (first <= 1) return
      dt = e(column(en, 'dt'), first)
      call check(s, d(1, first) <= tc .and. tc <= d(1, first) + dt, 'first contact force at the step '// &
                 'whose interval holds t = sqrt(2h/g) = 0.1', 't = '//rtoa(d(1, first))//', dt = '//rtoa(dt))
      call check(s, nb >= 10, 'ten contact episodes within t = 2', itoa(nb)//' contact episodes')
      ! the balance kinetic + strain - W_ext - W_con against the energy put in (W_ext = m g x fall)
      n = size(e, 2)
      drift = maxval(abs(e(column(en, 'total'), :) - e(column(en, 'total'), 1)))/e(column(en, 'external_work'), n)
      call check(s, drift <= 5.0e-3_wp, 'dropped block: energy balance within 0.5 % of the energy put in '// &
                 'through ten bounces', 'largest '//rtoa(drift))
      print '(a,i0,a,es10.3,a,f6.1,a)', '   info  dropped block: ', nb, ' contact episodes, balance within ', &
         100.0_wp*drift, ' % of the energy put in (largest over the run); the impacts took ', &
         -100.0_wp*e(column(en, 'contact_work'), n)/e(column(en, 'external_work'), n), ' % of it'
   end subroutine first_touch

   !> A block resting on a rigid floor under gravity ramped over 20 periods of its lowest mode
   !> (table 0, 0, T, 1) and held: the floor's reaction (reac sum over its region) averages m g
   !> within 0.1 % over the hold, equals the contact resultant, and the block stays put (its
   !> bottom on the floor, its top at the static deflection, no sideways motion).
   subroutine resting_block(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, i, n
      real(wp), parameter :: g = 10.0_wp, tr = 2.0_wp, tend = 3.5_wp
      real(wp) :: rsum, cmax, ub, utop_min, utop_max, ux, t, dtr, mg, w
      deck = head//solid//floor//block(4, 4, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
             block(4, 1, 101, 17, 2, 2, -0.5_wp, -0.2_wp, 2.0_wp, 0.2_wp)//'GRAVity,0,-10'//nl// &
             'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl//'    REGIon,2'//nl// &
             '  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl// &
             '  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,3.5'//nl//'    FORM,EXPLicit'//nl// &
             '  NEXT'//nl//'END'//nl//'2, 0'//nl//'0, 0, 2.0, 1'//nl//nl//'  reac,REGIon,2,2'//nl// &
             '  cont,1,3'//nl//'  disp,3,2'//nl//'  disp,23,2'//nl//'  disp,13,1'//nl//nl//'STOP'
      call run_deck('resting_block', deck, stage, msg)
      call check(s, stage == 0, 'resting block deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/resting_block.his', names, d)
      mg = 1.0_wp*g
      rsum = 0.0_wp
      w = 0.0_wp
      cmax = 0.0_wp
      ub = 0.0_wp
      ux = 0.0_wp
      utop_min = huge(1.0_wp)
      utop_max = -huge(1.0_wp)
      n = size(d, 2)
      do i = 2, n
         t = d(1, i)
         cmax = max(cmax, abs(d(2, i) - d(3, i)))
         ub = max(ub, abs(d(4, i)))
         ux = max(ux, abs(d(6, i)))
         if (t <= tr) cycle
         ! time average over the hold (trapezoid rule on the rows)
         dtr = t - d(1, i - 1)
         rsum = rsum + 0.5_wp*(d(2, i) + d(2, i - 1))*dtr
         w = w + dtr
         utop_min = min(utop_min, d(5, i))
         utop_max = max(utop_max, d(5, i))
      end do
      rsum = rsum/w
      call check(s, abs(rsum - mg) <= 1.0e-3_wp*mg, 'mean floor reaction over the hold = m g within 0.1 %', &
                 rtoa(rsum)//' against '//rtoa(mg))
      call check(s, cmax <= 1.0e-12_wp*mg, 'floor reaction = -contact resultant at every step', &
                 'largest difference '//rtoa(cmax))
      call check(s, ub <= 1.0e-9_wp, 'the block''s bottom stays on the floor', 'largest |u_y| '//rtoa(ub))
      call check(s, ux <= 1.0e-12_wp, 'no sideways motion of the centre line', 'largest |u_x| '//rtoa(ux))
      call check(s, utop_max < 0.0_wp .and. (utop_max - utop_min) <= 0.05_wp*abs(utop_min), 'the top stays '// &
                 'at its static deflection (oscillation below 5 % of it over the hold)', &
                 rtoa(utop_min)//' .. '//rtoa(utop_max))
   end subroutine resting_block

   !> The 1-D bar of inputs/verify (nu = 0), fixed at x = 0, the end force F ramped by a type-1
   !> function over T = 4L/c (one period of the lowest mode) and held by a type-2 table (a jump at
   !> T): during the ramp the tip follows the dynamic closed form
   !> u = F c/(E A T) int_0^t tau(s) ds (tau the triangle wave of a suddenly applied end load),
   !> after it the static F L/(E A), both within 1 %.
   subroutine bar_ramp_hold(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, i
      real(wp), parameter :: blen = 10.0_wp, hgt = 0.5_wp, young = 1000.0_wp, force = 0.5_wp
      real(wp) :: c, tr, ustat, t, u, e1, e2
      c = sqrt(young)
      tr = 4.0_wp*blen/c
      ustat = force*blen/(young*hgt)
      deck = head//'PARAmeters'//nl//'  tr = 4*10/sqrt(1000)'//nl//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0'//nl//'    DENSity 1'//nl//nl// &
             block(100, 5, 1, 1, 1, 1, 0.0_wp, 0.0_wp, blen, hgt)//'EBOUndary'//nl//'  1,0,1,0'//nl//nl// &
             'FORCe'//nl//'  101,0,0.05,0'//nl//'  202,101,0.1,0'//nl//'  505,0,0.1,0'//nl// &
             '  606,0,0.05,0'//nl//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1,2'//nl// &
             '  TPLOt,,1'//nl//'  LOOP,,1000000'//nl//'    TIME,,2*tr'//nl//'    FORM,EXPLicit'//nl// &
             '  NEXT'//nl//'END'//nl//'1, 0, 0, tr, 0, 1/tr, 0, 0'//nl//nl//'2, 0'//nl// &
             '0, 0, tr, 0, tr, 1'//nl//nl//'  disp,606,1'//nl//nl//'STOP'
      call run_deck('bar_ramp', deck, stage, msg)
      call check(s, stage == 0, 'ramped bar deck runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/bar_ramp.his', names, d)
      e1 = 0.0_wp
      e2 = 0.0_wp
      do i = 1, size(d, 2)
         t = d(1, i)
         if (t <= tr) then
            u = force*c/(young*hgt*tr)*ramp_integral(t, blen/c)
            e1 = max(e1, abs(d(2, i) - u))
         else
            e2 = max(e2, abs(d(2, i) - ustat))
         end if
      end do
      call check(s, e1 <= 0.01_wp*ustat, 'tip during the ramp against the dynamic closed form within 1 %', &
                 'largest difference '//rtoa(100.0_wp*e1/ustat)//' % of F L/(E A)')
      call check(s, e2 <= 0.01_wp*ustat, 'tip while held against the static F L/(E A) within 1 %', &
                 'largest difference '//rtoa(100.0_wp*e2/ustat)//' %')
   contains
      !> int_0^t tau(s) ds for the triangle wave tau of period 4 ta (ta = L/c), t <= 4 ta.
      pure real(wp) function ramp_integral(t, ta) result(r)
         real(wp), intent(in) :: t, ta
         if (t <= 2.0_wp*ta) then
            r = 0.5_wp*t*t
         else
            r = 2.0_wp*ta*ta + 4.0_wp*ta*(t - 2.0_wp*ta) - 0.5_wp*(t*t - 4.0_wp*ta*ta)
         end if
      end function ramp_integral
   end subroutine bar_ramp_hold

   !> The same bar with its end displaced as d sin(w t) (DISPlacement under a type-1 function):
   !> the end's displacement, velocity and acceleration are the prescribed history to round-off,
   !> and kinetic + strain - W_pm (the work of the prescribed motion) stays within 0.5 %.
   subroutine bar_prescribed_end(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, i
      real(wp), parameter :: amp = 0.01_wp, om = 5.0_wp
      real(wp) :: eu, ev, ea, t, dmax
      deck = head//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0'//nl//'    DENSity 1'// &
             nl//nl//block(100, 5, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 10.0_wp, 0.5_wp)//'EBOUndary'//nl// &
             '  1,0,1,0'//nl//'  1,10,1,0'//nl//nl//'DISPlacement'//nl//'  101,101,0.01,0'//nl// &
             '  606,0,0.01,0'//nl//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl//'  TPLOt,,1'//nl// &
             '  LOOP,,1000000'//nl//'    TIME,,1.5'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '1, 1, 0, 100, 0, 0, 1, 5'//nl//nl//'  disp,606,1'//nl//'  velo,606,1'//nl//'  acce,606,1'//nl// &
             '  disp,303,1'//nl//nl//'STOP'
      call run_deck('bar_end', deck, stage, msg)
      call check(s, stage == 0, 'bar with a prescribed end runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/bar_end.his', names, d)
      call read_table(run_dir//'/bar_end.ene', en, e)
      eu = 0.0_wp
      ev = 0.0_wp
      ea = 0.0_wp
      do i = 1, size(d, 2)
         t = d(1, i)
         eu = max(eu, abs(d(2, i) - amp*sin(om*t)))
         ev = max(ev, abs(d(3, i) - amp*om*cos(om*t)))
         ea = max(ea, abs(d(4, i) + amp*om*om*sin(om*t)))
      end do
      dmax = balance(en, e)
      call check(s, eu <= 1.0e-15_wp, 'prescribed end: u = d sin(w t) at every step', rtoa(eu))
      call check(s, ev <= 1.0e-14_wp, 'prescribed end: v = d w cos(w t) at every step', rtoa(ev))
      call check(s, ea <= 1.0e-13_wp, 'prescribed end: a = -d w^2 sin(w t) at every step', rtoa(ea))
      call check(s, maxval(abs(e(column(en, 'prescribed_work'), :))) > 0.0_wp .and. dmax <= 5.0e-3_wp, &
                 'energy balance with the work of the prescribed motion within 0.5 %', &
                 'largest drift '//rtoa(100.0_wp*dmax)//' %')
   end subroutine bar_prescribed_end

   !> Type 1 and 2 functions and the sum rule against their definitions; p' and p'' of type 1
   !> (k = 0..3) against central differences of p.
   subroutine functions(s)
      type(suite_t), intent(inout) :: s
      type(prop_fn_t) :: f(3)
      real(wp) :: p, dp, ddp, pp, pm, q, dq, ddq, h, t, worst1, worst2
      integer :: k, j
      f(1)%kind = FN_TYPE1
      f(1)%tmin = 0.5_wp
      f(1)%tmax = 3.0_wp
      f(1)%a = [0.3_wp, 0.7_wp, 1.3_wp, 2.1_wp]
      worst1 = 0.0_wp
      worst2 = 0.0_wp
      h = 1.0e-4_wp
      do k = 0, 3
         f(1)%k = k
         do j = 1, 9
            t = 0.6_wp + 0.27_wp*real(j, wp)
            call prop_eval(f(1), t, p, dp, ddp)
            call prop_eval(f(1), t + h, pp, q, ddq)
            call prop_eval(f(1), t - h, pm, q, ddq)
            worst1 = max(worst1, abs(dp - (pp - pm)/(2.0_wp*h)))
            worst2 = max(worst2, abs(ddp - (pp - 2.0_wp*p + pm)/h**2))
         end do
      end do
      ! truncation h^2 p'''/6 <= 1e-8 x 300/6 and round-off eps / h^2 x 6 = 1.3e-7: 1e-6, 1e-5
      call check(s, worst1 <= 1.0e-6_wp .and. worst2 <= 1.0e-5_wp, 'type 1: p'' and p'''' against central '// &
                 'differences (k = 0..3)', rtoa(worst1)//', '//rtoa(worst2))
      f(1)%k = 2
      call prop_eval(f(1), 1.0_wp, p, dp, ddp)
      call check_close(s, p, 0.3_wp + 0.7_wp*0.5_wp + 1.3_wp*sin(2.1_wp*0.5_wp)**2, 1.0e-15_wp, &
                       'type 1: a1 + a2 (t - tmin) + a3 sin^k(a4 (t - tmin))')
      call prop_eval(f(1), 0.49_wp, p, dp, ddp)
      call prop_eval(f(1), 3.01_wp, q, dq, ddq)
      call check(s, p == 0.0_wp .and. q == 0.0_wp .and. dp == 0.0_wp .and. dq == 0.0_wp, 'type 1: 0 outside '// &
                 '[tmin, tmax]')
      f(2)%kind = FN_TABLE
      f(2)%tab = reshape([0.0_wp, 0.0_wp, 1.0_wp, 2.0_wp, 1.0_wp, 5.0_wp, 2.0_wp, 5.0_wp], [2, 4])
      call prop_eval(f(2), 0.25_wp, p, dp, ddp)
      call check(s, p == 0.5_wp .and. dp == 2.0_wp .and. ddp == 0.0_wp, 'table: linear between points')
      call prop_eval(f(2), 1.0_wp, p, dp, ddp)
      call prop_eval(f(2), 1.0_wp + 1.0e-9_wp, q, dq, ddq)
      call check(s, p == 2.0_wp .and. abs(q - 5.0_wp) < 1.0e-12_wp, 'table: a time given twice is a jump '// &
                 '(first value at it, second after)')
      call prop_eval(f(2), -1.0_wp, p, dp, ddp)
      call prop_eval(f(2), 9.0_wp, q, dq, ddq)
      call check(s, p == 0.0_wp .and. q == 5.0_wp .and. dq == 0.0_wp, 'table: constant beyond the ends')
      f(3)%kind = FN_RAMP
      call prop_value(f, 0, 0.75_wp, p, dp, ddp)
      call check_close(s, p, (0.3_wp + 0.7_wp*0.25_wp + 1.3_wp*sin(2.1_wp*0.25_wp)**2) + 1.5_wp + 0.75_wp, &
                       1.0e-15_wp, 'function 0 is the sum of all functions')
      call prop_value(f(1:0), 0, 0.75_wp, p, dp, ddp)
      call check(s, p == 1.0_wp .and. dp == 0.0_wp, 'function 0 is 1 when there are none')
   end subroutine functions

   !> Edge loads at t = 0 on a 2 x 1 block's top: a pressure interpolated linearly from 1 at
   !> x = 0 to 3 at x = 2 adds up to its integral, -4 (downward), with the moment of its
   !> centroid (x = 7/6); a tangential traction 0.5 from point 1 (x = 2) to point 2 (x = 0) adds
   !> up to (-1, 0).
   subroutine edge_values(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      real(wp) :: fy, mz, fx
      integer :: i
      deck = head//solid//block(4, 1, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 2.0_wp, 1.0_wp)//'CSURface'//nl// &
             '  NORMal'//nl//'  LINEar'//nl//'    1,0,1,1'//nl//'    2,2,1,3'//nl//'  TANGential'//nl// &
             '  LINEar'//nl//'    1,2,1,0.5'//nl//'    2,0,1,0.5'//nl//nl//'END'//nl//'BATCh'//nl//'END'// &
             nl//'STOP'
      call setup_stepper('edge_values', deck, model, stp, err)
      if (.not. allocated(err)) call stp%start(err)
      call check(s, .not. allocated(err), 'edge values set up', error_text(err))
      if (allocated(err)) return
      fy = 0.0_wp
      mz = 0.0_wp
      fx = 0.0_wp
      do i = 1, stp%st%nnode
         fy = fy + stp%st%fext(2, i)
         fx = fx + stp%st%fext(1, i)
         mz = mz + stp%st%x0(1, i)*stp%st%fext(2, i)
      end do
      call check_close(s, fy, -4.0_wp, 1.0e-14_wp, 'linear pressure: resultant = its integral')
      call check_close(s, mz/fy, 7.0_wp/6.0_wp, 1.0e-14_wp, 'linear pressure: at its centroid')
      call check_close(s, fx, -1.0_wp, 1.0e-14_wp, 'tangential traction from point 1 to point 2')
   end subroutine edge_values

   !> A RIGId square driven by MOTIon,REGIon,1,0.5,0,2 (velocity (0.5, 0), spin 2 about its
   !> centroid): after 0.5 its centroid has moved 0.25, it has turned by 1 (rigi,1,1 and 3), and
   !> its nodes sit on the rigid placement.
   subroutine spun_body(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, n
      real(wp) :: t, xc, yc, x9, y9, c, sn
      deck = head//'MATErial,1'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)//'MOTIon,REGIon,1,0.5,0,2'//nl// &
             'END'//nl//'BATCh'//nl//'  DT,,1e-3'//nl//'  TPLOt,,1'//nl//'  LOOP,,500'//nl//'    TIME'//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  rigi,1,1'//nl//'  rigi,1,3'//nl// &
             '  rigi,1,6'//nl//'  disp,9,1'//nl//'  disp,9,2'//nl//nl//'STOP'
      call run_deck('spun', deck, stage, msg)
      call check(s, stage == 0, 'a spun rigid body runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/spun.his', names, d)
      n = size(d, 2)
      t = d(1, n)
      call check(s, abs(d(2, n) - 0.5_wp*t) <= 1.0e-12_wp .and. abs(d(3, n) - 2.0_wp*t) <= 1.0e-12_wp .and. &
                 abs(d(4, n) - 2.0_wp) <= 1.0e-12_wp, 'centroid moved v t, turned omega t at omega', &
                 'at t = '//rtoa(t)//': '//rtoa(d(2, n))//', '//rtoa(d(3, n)))
      ! node 9 = corner (1, 1): offset (0.5, 0.5) from the centroid, turned by 2 t
      c = cos(2.0_wp*t)
      sn = sin(2.0_wp*t)
      xc = 0.5_wp + 0.5_wp*t
      yc = 0.5_wp
      x9 = xc + c*0.5_wp - sn*0.5_wp
      y9 = yc + sn*0.5_wp + c*0.5_wp
      call check(s, abs(1.0_wp + d(5, n) - x9) <= 1.0e-12_wp .and. abs(1.0_wp + d(6, n) - y9) <= 1.0e-12_wp, &
                 'its corner on the rigid placement', rtoa(1.0_wp + d(5, n))//', '//rtoa(1.0_wp + d(6, n)))
   end subroutine spun_body

   !> A deformable region driven by MOTIon,REGIon,1,0.3,-0.2 (every node prescribed): it
   !> translates as (0.3, -0.2) t to round-off, and with no load the reaction sum over the
   !> region is zero.
   subroutine driven_region(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, i
      real(wp) :: eu, er, t
      call run_deck('driven_region', head//solid//block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
                    'MOTIon,REGIon,1,0.3,-0.2'//nl//batch('0.5', '  disp,9,1'//nl//'  disp,5,2'//nl// &
                    '  velo,9,2'//nl//'  reac,REGIon,1,2'//nl), stage, msg)
      call check(s, stage == 0, 'a driven deformable region runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/driven_region.his', names, d)
      eu = 0.0_wp
      er = 0.0_wp
      do i = 1, size(d, 2)
         t = d(1, i)
         eu = max(eu, abs(d(2, i) - 0.3_wp*t), abs(d(3, i) + 0.2_wp*t), abs(d(4, i) + 0.2_wp))
         er = max(er, abs(d(5, i)))
      end do
      call check(s, eu <= 1.0e-14_wp, 'driven region translates as (0.3, -0.2) t', 'largest error '//rtoa(eu))
      call check(s, er <= 1.0e-12_wp, 'its reaction sum is zero with no load', 'largest '//rtoa(er))
   end subroutine driven_region

   !> A block whose every node is prescribed (x stretched as eps X sin(w t), FPROportional
   !> giving the x dofs function 1 and the y dofs function 2 = 1): the pressure on its top edge
   !> (CSURface NORMal LINEar) has the resultant p times the deformed edge length, downward, at
   !> every step to round-off, and fext carries it.
   subroutine stretched_edge(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      integer :: k
      real(wp), parameter :: p = 3.0_wp
      real(wp) :: len, res(2), worst, worst_f, lmin, lmax
      deck = head//solid//block(2, 1, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 2.0_wp, 1.0_wp)//'BOUNdary'//nl// &
             '  1,0,1,1'//nl//'  2,0,1,1'//nl//'  3,0,1,1'//nl//'  4,0,1,1'//nl//'  5,0,1,1'//nl// &
             '  6,0,1,1'//nl//nl//'DISPlacement'//nl//'  2,0,0.1,0'//nl//'  3,0,0.2,0'//nl// &
             '  5,0,0.1,0'//nl//'  6,0,0.2,0'//nl//nl//'FPROportional'//nl//'  1,1,1,2'//nl//'  6,0,1,2'//nl// &
             nl//'CSURface'//nl//'  NORMal'//nl//'  LINEar'//nl//'    1,0,1,3'//nl//'    2,2,1,3'//nl//nl// &
             'END'//nl//'BATCh'//nl//'  PROPortional,,1,2'//nl//'END'//nl//'1, 1, 0, 100, 0, 0, 1, 20'//nl// &
             nl//'2, 0'//nl//'0, 1'//nl//nl//'STOP'
      call setup_stepper('stretched_edge', deck, model, stp, err)
      if (.not. allocated(err)) call stp%set_fixed_dt(1.0e-3_wp, 'test', err)
      if (.not. allocated(err)) call stp%start(err)
      call check(s, .not. allocated(err), 'stretched block set up', error_text(err))
      if (allocated(err)) return
      worst = 0.0_wp
      worst_f = 0.0_wp
      lmin = huge(1.0_wp)
      lmax = 0.0_wp
      do k = 1, 400
         call stp%advance(err)
         if (allocated(err)) exit
         associate (st => stp%st)
            len = (st%x0(1, 6) + st%u(1, 6)) - (st%x0(1, 4) + st%u(1, 4))
            res = sum(stp%ld%fedge, dim=2)
            worst = max(worst, abs(res(1)), abs(res(2) + p*len))
            worst_f = max(worst_f, abs(sum(st%fext(2, 4:6)) + p*len))
            lmin = min(lmin, len)
            lmax = max(lmax, len)
         end associate
      end do
      call check(s, .not. allocated(err), 'stretched block runs', error_text(err))
      call check(s, lmin < 1.85_wp .and. lmax > 2.15_wp, 'the edge length changes by +-10 %', &
                 rtoa(lmin)//' .. '//rtoa(lmax))
      call check(s, worst <= 1.0e-13_wp*p*lmax, 'edge pressure resultant = p x deformed length at every step', &
                 'largest difference '//rtoa(worst))
      print '(a,es10.3,a)', '   info  stretched edge: resultant - p x length up to ', worst/(p*lmax), ' of p L'
      call check(s, worst_f <= 1.0e-13_wp*p*lmax, 'fext of the top nodes carries it', rtoa(worst_f))
   end subroutine stretched_edge

   !> A deformable block on rollers with a pressure on its top edge (three elements along it):
   !> at every step the resultant is -p R(x_e - x_s), R(t) = (t_y, -t_x), the chord of the
   !> deformed edge chain (doc/loads.md, section 2), to round-off.
   subroutine deforming_edge(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      integer :: k
      real(wp), parameter :: p = 50.0_wp
      real(wp) :: res(2), chord(2), worst, bend, plen
      deck = head//solid//block(3, 3, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)//'EBOUndary'//nl// &
             '  2,0,0,1'//nl//'  1,0,1,0'//nl//nl//'CSURface'//nl//'  NORMal'//nl//'  LINEar'//nl// &
             '    1,0,1,50'//nl//'    2,1,1,50'//nl//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('deforming_edge', deck, model, stp, err)
      if (.not. allocated(err)) call stp%start(err)
      call check(s, .not. allocated(err), 'pressed block set up', error_text(err))
      if (allocated(err)) return
      worst = 0.0_wp
      bend = 0.0_wp
      do k = 1, 300
         call stp%advance(err)
         if (allocated(err)) exit
         associate (st => stp%st)
            chord = (st%x0(:, 13) + st%u(:, 13)) - (st%x0(:, 16) + st%u(:, 16))
            res = sum(stp%ld%fedge, dim=2)
            worst = max(worst, norm2(res + p*[chord(2), -chord(1)]))
            plen = norm2(st%x0(:, 14) + st%u(:, 14) - st%x0(:, 13) - st%u(:, 13)) + &
                   norm2(st%x0(:, 15) + st%u(:, 15) - st%x0(:, 14) - st%u(:, 14)) + &
                   norm2(st%x0(:, 16) + st%u(:, 16) - st%x0(:, 15) - st%u(:, 15))
            bend = max(bend, plen - norm2(chord))
         end associate
      end do
      call check(s, .not. allocated(err), 'pressed block runs', error_text(err))
      call check(s, worst <= 1.0e-13_wp*p, 'edge resultant = -p R(chord) of the deformed edge at every step', &
                 'largest difference '//rtoa(worst)//' (the edge bends: length - chord up to '//rtoa(bend)//')')
   end subroutine deforming_edge

   !> A ring (POLAr blocks tied) spinning at w = 2 under a follower pressure on its outer edge
   !> (CSURface LINEar through the outer nodes) that about balances the centrifugal stress:
   !> the pressure's work is W = -p (A(t) - A(0)) at every step to round-off (A the area inside the
   !> loaded loop), it does no net work over a revolution (0.1 % of the kinetic energy), and the
   !> angular momentum stays constant to round-off (a uniform pressure on a closed loop has no
   !> moment).
   subroutine spinning_ring(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck, pts
      integer, parameter :: ns = 48, nr = 2
      real(wp), parameter :: ri = 0.9_wp, ro = 1.1_wp, om = 2.0_wp
      real(wp) :: p, a0, area, worst_w, l0, lnow, worst_l, trev, kin0, wrev
      logical, allocatable :: given(:)
      real(wp), allocatable :: v(:, :)
      integer :: k, j, n, outer(ns)
      p = om*om*(ro - ri)/ro
      pts = ''
      do k = 0, ns
         pts = pts//'    '//itoa(k + 1)//', 1.1*cosd('//itoa(k)//'*7.5), 1.1*sind('//itoa(k)//'*7.5), '// &
               '2*2*(1.1-0.9)/1.1'//nl
      end do
      deck = head//solid//'BLOCk'//nl//'  POLAr,'//itoa(nr)//','//itoa(ns)//',1,1,1'//nl//'    1,'// &
             rtoa(ri)//',0'//nl//'    2,'//rtoa(ro)//',0'//nl//'    3,'//rtoa(ro)//',360'//nl//'    4,'// &
             rtoa(ri)//',360'//nl//nl//'CSURface'//nl//'  NORMal'//nl//'  LINEar'//nl//pts//nl// &
             'END'//nl//'TIE'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('ring', deck, model, stp, err)
      call check(s, .not. allocated(err), 'ring set up', error_text(err))
      if (allocated(err)) return
      call check(s, stp%ld%spec%nedge == ns, 'the pressure loads the 48 outer edges', itoa(stp%ld%spec%nedge))
      n = stp%st%nnode
      do j = 0, ns - 1
         outer(j + 1) = 1 + j*(nr + 1) + nr
      end do
      allocate (given(n), v(2, n))
      given = stp%st%active
      v(1, :) = -om*stp%st%x0(2, :)
      v(2, :) = om*stp%st%x0(1, :)
      call stp%set_velocity(given, v)
      call stp%set_cfl(0.9_wp, 'test', err)
      if (.not. allocated(err)) call stp%start(err)
      if (allocated(err)) return
      a0 = loop_area()
      l0 = ang_mom()
      kin0 = stp%st%energy%kinetic
      trev = 2.0_wp*acos(-1.0_wp)/om
      stp%tmax = trev
      worst_w = 0.0_wp
      worst_l = 0.0_wp
      do while (stp%st%t < trev*(1.0_wp - 1.0e-12_wp))
         call stp%advance(err)
         if (allocated(err)) exit
         area = loop_area()
         worst_w = max(worst_w, abs(stp%st%energy%wext + p*(area - a0)))
         lnow = ang_mom()
         worst_l = max(worst_l, abs(lnow - l0))
      end do
      call check(s, .not. allocated(err), 'ring spins one revolution', error_text(err))
      wrev = stp%st%energy%wext
      call check(s, worst_w <= 1.0e-12_wp*p*a0, 'pressure work = -p (A(t) - A(0)) at every step', &
                 'largest difference '//rtoa(worst_w))
      call check(s, abs(wrev) <= 1.0e-3_wp*kin0, 'no net work over a revolution (0.1 % of the kinetic '// &
                 'energy)', 'W = '//rtoa(wrev)//', kinetic '//rtoa(kin0))
      call check(s, worst_l <= 1.0e-12_wp*abs(l0), 'angular momentum constant to round-off', &
                 'largest change '//rtoa(worst_l)//' of '//rtoa(l0))
      print '(a,es10.3,a,es10.3,a,es10.3)', '   info  ring: net work over a revolution / kinetic energy ', &
         abs(wrev)/kin0, '; W + p dA ', worst_w/(p*a0), ' of p A; angular momentum change ', worst_l/abs(l0)
   contains
      real(wp) function loop_area() result(a)
         integer :: q, i1, i2
         real(wp) :: x1(2), x2(2)
         a = 0.0_wp
         do q = 1, ns
            i1 = outer(q)
            i2 = outer(mod(q, ns) + 1)
            x1 = stp%st%x0(:, i1) + stp%st%u(:, i1)
            x2 = stp%st%x0(:, i2) + stp%st%u(:, i2)
            a = a + 0.5_wp*(x1(1)*x2(2) - x1(2)*x2(1))
         end do
      end function loop_area
      real(wp) function ang_mom() result(l)
         integer :: i
         real(wp) :: x(2)
         l = 0.0_wp
         do i = 1, n
            x = stp%st%x0(:, i) + stp%st%u(:, i)
            l = l + stp%st%mass(i)*(x(1)*stp%st%v(2, i) - x(2)*stp%st%v(1, i))
         end do
      end function ang_mom
   end subroutine spinning_ring

   !> A unit square meshed by Gmsh (4 x 4, physical curves 5 = top, 6 = bottom) with a pressure
   !> p = 2 on curve 5 (CSURface PHYSical), ramped over 20 periods of its lowest mode and held,
   !> its bottom fixed (PBOUndary 6): the edge forces add up to p times the deformed top's chord
   !> at t = 0 and at every step, and the bottom's reaction sum (reac,PHYSical,6,2) averages p
   !> times the top's length over the hold within 0.1 %.
   subroutine physical_edge(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      real(wp) :: rsum, w, dtr, lmean
      integer :: stage, i
      call write_text(run_dir//'/phys_square.geo', 'Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; '// &
                      'Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};'//nl// &
                      'Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};'//nl// &
                      'Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};'//nl// &
                      'Transfinite Curve{1:4} = 5; Transfinite Surface{1}; Recombine Surface{1};'//nl// &
                      'Physical Surface(1) = {1}; Physical Curve(5) = {3}; Physical Curve(6) = {1};')
      deck = head//solid//'GMSH,phys_square.geo'//nl//'PBOUndary,6,1,1'//nl//'CSURface'//nl//'  NORMal'//nl// &
             '  PHYSical,5,2'//nl//nl//'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl//'  TPLOt,,1'//nl// &
             '  LOOP,,1000000'//nl//'    TIME,,3'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '2, 0'//nl//'0, 0, 2, 1'//nl//nl//'  reac,PHYSical,6,2'//nl//'  disp,,1,0,1'//nl// &
             '  disp,,1,1,1'//nl//nl//'STOP'
      call run_deck('phys_edge', deck, stage, msg)
      call check(s, stage == 0, 'pressure on a Gmsh physical curve runs', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/phys_edge.his', names, d)
      rsum = 0.0_wp
      w = 0.0_wp
      lmean = 0.0_wp
      do i = 2, size(d, 2)
         if (d(1, i) <= 2.0_wp) cycle
         dtr = d(1, i) - d(1, i - 1)
         rsum = rsum + 0.5_wp*(d(2, i) + d(2, i - 1))*dtr
         lmean = lmean + 0.5_wp*((1.0_wp + d(4, i) - d(3, i)) + (1.0_wp + d(4, i - 1) - d(3, i - 1)))*dtr
         w = w + dtr
      end do
      rsum = rsum/w
      lmean = lmean/w
      call check(s, abs(rsum - 2.0_wp*lmean) <= 1.0e-3_wp*2.0_wp*lmean, 'mean reaction over the held '// &
                 'bottom = p x the top''s length within 0.1 %', rtoa(rsum)//' against '//rtoa(2.0_wp*lmean))
   end subroutine physical_edge

   !> A rigid punch (width 0.5) driven at constant velocity 0.2 into a block (1 x 1, bottom fixed),
   !> by MOTIon or by an initial velocity, its nodes (the slaves of the pair) on the block's: the
   !> run never trips the energy guard, the reaction sum over the punch (the driving force)
   !> equals the contact resultant on it, and kinetic + strain - W_ext - W_con - W_pm stays
   !> within 0.5 % of the largest kinetic + strain energy.
   subroutine punch(s, drive, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: drive, what
      character(len=:), allocatable :: msg, deck
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, i
      real(wp) :: worst, fmax, dmax
      deck = head//'PARAmeters'//nl//'  vp = 0.2'//nl//nl//solid//floor// &
             block(8, 8, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)// &
             block(4, 2, 101, 65, 2, 2, 0.25_wp, 1.0_wp, 0.5_wp, 0.3_wp)//drive// &
             'EBOUndary'//nl//'  2,0,1,1'//nl//nl//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl// &
             '  SURFace,2'//nl//'    REGIon,2'//nl//'  PAIR,1,NTOS,2,1'//nl//'END CONTact'//nl// &
             batch('0.3', '  reac,REGIon,2,2'//nl//'  cont,1,3'//nl//'  rigi,2,2'//nl)
      call run_deck('punch', deck, stage, msg)
      call check(s, stage == 0, 'punch driven by '//what//' runs to the end with no energy error', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/punch.his', names, d)
      call read_table(run_dir//'/punch.ene', en, e)
      worst = 0.0_wp
      fmax = 0.0_wp
      do i = 1, size(d, 2)
         fmax = max(fmax, abs(d(3, i)))
         worst = max(worst, abs(abs(d(2, i)) - abs(d(3, i))))
      end do
      dmax = balance(en, e)
      call check(s, fmax > 0.0_wp .and. worst <= 1.0e-3_wp*fmax, 'punch ('//what//'): reaction sum = contact '// &
                 'resultant within 0.1 %', 'largest difference '//rtoa(worst)//' of '//rtoa(fmax))
      call check(s, abs(d(4, size(d, 2)) + 0.2_wp*d(1, size(d, 2))) <= 1.0e-12_wp, 'punch ('//what// &
                 '): it moves at constant velocity', rtoa(d(4, size(d, 2))))
      call check(s, dmax <= 5.0e-3_wp, 'punch ('//what//'): energy balance with the work of the prescribed '// &
                 'motion within 0.5 %', 'largest drift '//rtoa(100.0_wp*dmax)//' %')
   end subroutine punch

   !> Bad input of the loads: each an error naming file:line and what was expected.
   subroutine bad_input(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: base, tail
      base = head//solid//block(2, 2, 1, 1, 1, 1, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp)
      ! base has 15 lines (head 2, solid 5, block 8): the next record is line 16
      tail = 'END'//nl//'BATCh'//nl//'  PROPortional,,1'//nl//'END'//nl
      call bad('l01', base//'FPROportional'//nl//'  9,0,3,0'//nl//nl//tail//'1, 0, 0, 1, 1, 0, 0, 0'//nl// &
               nl//'STOP', 17, 'proportional function 3 is not defined')
      call bad('l02', base//tail//'2, 0'//nl//'0, 0, 1, 1'//nl//'0.5, 2'//nl//nl//'STOP', 22, &
               'expected the times in order')
      call bad('l03', base//'CSURface'//nl//'  NORMal'//nl//'  LINEar'//nl//'    1,0,1,1'//nl// &
               '    2,0.5,0.5,1'//nl//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP', 20, 'is not on a boundary')
      call bad('l04', base//'MOTIon,REGIon,7,0,1'//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP', 16, &
               'region 7 has no elements')
      call bad('l05', head//'MATErial,1'//nl//'  RIGId,FREE'//nl//nl//'END'//nl//'STOP', 4, &
               'expected DENSity rho > 0')
      call bad('l06', base//tail//'1, 0, 1, 1, 1, 0, 0, 0'//nl//nl//'STOP', 20, 'expected tmax > tmin')
      call bad('l07', base//'GRAVity,0,-1'//nl//'GRAVity,0,-2'//nl//'END'//nl//'BATCh'//nl//'END'//nl// &
               'STOP', 17, 'GRAVity is already given')
      call bad('l08', base//tail//'1, 0, 0, 1, 1, 0, 0, 0'//nl//'2, 0'//nl//'STOP', 21, &
               'expected a blank record to end it')
      call bad('l09', base//'GRAVity,0,-1,2'//nl//tail//nl//'STOP', 16, 'proportional function 2 is not defined')
      call bad('l10', base//'MOTIon,REGIon,1,1,0,0.5'//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP', 16, &
               'expected omega = 0')
      call bad('l11', base//tail//'3, 0'//nl//nl//'STOP', 20, 'expected 1')
      call bad('l12', base//'CSURface'//nl//'  LINEar'//nl//'END'//nl//'STOP', 17, 'before the load type')
   contains
      subroutine bad(tag, text, line, word)
         character(len=*), intent(in) :: tag, text, word
         integer, intent(in) :: line
         type(model_t) :: m
         type(error_t), allocatable :: err
         character(len=:), allocatable :: at
         call write_text(run_dir//'/'//tag//'.inp', text)
         call read_deck(run_dir//'/'//tag//'.inp', m, err)
         at = tag//'.inp:'//itoa(line)//':'
         if (.not. allocated(err)) then
            call check(s, .false., tag//': error "'//word//'"', 'no error')
            return
         end if
         call check(s, index(err%message, at) > 0 .and. index(err%message, word) > 0, &
                    tag//': '//at//' ... '//word, err%message)
      end subroutine bad
   end subroutine bad_input

   !> The energy balance of a run: the largest |total - total(0)| over the largest
   !> kinetic + strain energy (total = kinetic + strain - W_ext - W_con - W_pm, <stem>.ene).
   real(wp) function balance(en, e) result(r)
      character(len=*), intent(in) :: en(:)
      real(wp), intent(in) :: e(:, :)
      integer :: kt
      kt = column(en, 'total')
      r = maxval(abs(e(kt, :) - e(kt, 1)))/maxval(e(column(en, 'kinetic'), :) + e(column(en, 'strain'), :))
   end function balance

end module test_loads
