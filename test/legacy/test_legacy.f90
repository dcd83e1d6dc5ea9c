!> The legacy contact API: a fixed-form Fortran 77 host and a C host built against an
!> installed exic, bad arguments, and handles used side by side.
!>
!> The hosts are built by examples/legacy_host/build.sh, which runs `fpm install` into
!> build/legacy_prefix (the fpm command is $EXIC_FPM, else fpm on PATH) and compiles
!> examples/legacy_host against that prefix only. The F77 host lhost has its own element
!> loop: with the neo-Hookean total-Lagrangian 2x2 element (the formulation exic uses) and a
!> fixed step its tip histories must equal exic's own deck run of the same scene; with its
!> small-strain element, its own CFL step and DYNA's half-step velocities every gap must
!> still close.
module test_legacy
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t, make_error
   use exic_model_model, only: model_t
   use exic_material_material, only: MAT_RIGID
   use exic_contact_spec, only: contact_spec_t
   use exic_explicit_step, only: stepper_t, contact_hook_t
   use exic_mesh_boundary, only: free_edges
   use exic_legacy_interfaces, only: exic_contact_create_mesh, exic_contact_create_segments, &
                                     exic_contact_set_fixed, exic_contact_set_pair, exic_contact_set_option, &
                                     exic_contact_step, exic_contact_pair_results, exic_contact_ncon, &
                                     exic_contact_constraints, exic_contact_work, exic_contact_free, &
                                     exic_contact_error_message, exic_contact_face_rule
   use testing, only: suite_t, check, check_close, section, skip, fpm_command, file_text
   use deck_runner, only: run_dir, run_deck, read_table, column
   use test_legacy_face, only: face_argument_tests, bad
   implicit none
   private

   public :: run_legacy_tests

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: prefix = 'build/legacy_prefix'
   character(len=*), parameter :: bindir = 'build/legacy_host'
   real(wp), parameter :: young = 1.0e4_wp, rho0 = 0.1_wp, v0 = 0.1_wp
   real(wp), parameter :: blen = 30.0_wp, bhgt = 4.0_wp
   real(wp), parameter :: dt_fixed = 1.4e-3_wp          !< 0.8 of the stable step of the 30 x 6 bars
   real(wp), parameter :: energy0 = 0.5_wp*rho0*blen*bhgt*v0**2   !< kinetic energy of bar 1

   !> The step's contact through the API: EXIC_CONTACT_STEP on handle h.
   type, extends(contact_hook_t) :: api_hook_t
      integer :: h = 0
   contains
      procedure :: correct => api_correct
   end type api_hook_t

   !> A run of exic's own step with contact through the API (a host inside the test).
   type :: api_run_t
      type(stepper_t) :: stp
      type(api_hook_t), pointer :: hook => null()
      integer :: h = 0, itip = 0, nrow = 0
      real(wp) :: tmax = 0.0_wp
      real(wp), allocatable :: rows(:, :)
      logical :: ok = .true.
   end type api_run_t

contains

   subroutine run_legacy_tests(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: wall, bars, wall_e
      logical :: built, ok1, ok2, ok3
      call section(s, 'legacy API: bad arguments')
      call bad_argument_tests(s)
      call face_argument_tests(s)
      call section(s, 'legacy API: exic deck runs of the two scenes')
      call deck_run(s, 'legacy_wall', 'wall', wall, ok1)
      call deck_run(s, 'legacy_bars', 'bars', bars, ok2)
      call deck_run(s, 'legacy_wall_energy', 'wall', wall_e, ok3, energy=.true.)
      if (.not. (ok1 .and. ok2 .and. ok3)) return
      call section(s, 'legacy API: in-process host, two handles used alternately')
      call alternate_test(s, wall, bars)
      call segments_test(s, wall)
      call section(s, 'legacy API: install and build the F77 and C hosts')
      call build_hosts(s, built)
      if (.not. built) return
      call section(s, 'legacy API: F77 host with the neo-Hookean element equals the deck run')
      call host_equal_test(s, 'legacy_wall', wall)
      call host_equal_test(s, 'legacy_bars', bars)
      call section(s, 'legacy API: F77 host with massless contact faces (method 3) equals LAGRange,ENERgy')
      call host_energy_test(s, wall_e)
      call section(s, 'legacy API: F77 host with its own linear element keeps every gap closed')
      call host_simple_test(s, 'legacy_wall', wall)
      call host_simple_test(s, 'legacy_bars', bars)
      call section(s, 'legacy API: C host')
      call c_host_test(s)
      call section(s, 'legacy API: the link lines and the F77 skeleton of doc/api.md')
      call skeleton_test(s)
      call section(s, 'legacy API: F77 host with Coulomb friction')
      call slide_test(s)
   end subroutine run_legacy_tests

   !> The F77 host examples/legacy_host/slide.f (a square of springs, mass 1, launched at 1 on a
   !> rigid floor under g = 10 with EXIC_CONTACT_SET_FRICTION mu = 0.5): its centre slides
   !> v0^2/(2 mu g) = 0.1 within 1 %, the friction force of EXIC_CONTACT_PAIR_FRICTION is mu times
   !> the normal force of EXIC_CONTACT_PAIR_RESULTS while both corners slip, and at the end both
   !> corners stick; the square still rings on its undamped springs, which may unload a corner
   !> for a moment, so the corners' motion over the last 300 steps is held to 1e-4 of the slide.
   subroutine slide_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: out
      integer :: stat, cstat, k, ios, nstick
      real(wp) :: dist, rel, creep
      call execute_command_line(bindir//'/slide > '//bindir//'/slide.txt 2>&1', exitstat=stat, cmdstat=cstat)
      out = file_text(bindir//'/slide.txt')
      call check(s, stat == 0 .and. cstat == 0, 'the F77 host with friction runs', out)
      dist = 0.0_wp
      rel = huge(1.0_wp)
      creep = huge(1.0_wp)
      nstick = 0
      k = index(out, 'DISTANCE')
      if (k > 0) out = out(k:)
      if (k > 0) read (out(9:), *, iostat=ios) dist
      k = index(out, ' FRICTION ')
      if (k > 0) read (out(k + 10:), *, iostat=ios) rel
      k = index(out, 'CREEP')
      if (k > 0) read (out(k + 5:), *, iostat=ios) creep
      k = index(out, 'STICKING')
      if (k > 0) read (out(k + 8:), *, iostat=ios) nstick
      call check(s, abs(dist - 0.1_wp) <= 1.0e-3_wp, 'F77 host: the square slides v0^2/(2 mu g) = 0.1 within 1 %', &
                 rtoa(dist))
      call check(s, rel <= 1.0e-12_wp, 'F77 host: friction force = mu N while both corners slip', rtoa(rel))
      call check(s, nstick == 2 .and. creep <= 1.0e-5_wp, 'F77 host: at the end both corners stick and stay', &
                 itoa(nstick)//' sticking, corners moved '//rtoa(creep))
   end subroutine slide_test

   ! ------------------------------------------------------------------ scenes

   !> Bar 1 (region 1, 30 x 6) at +v0 against a rigid wall (mode 'wall') or a second bar at
   !> -v0 (mode 'bars'), with a fixed step; histories of the tip (node (nx, ny/2)) and pair 1.
   function scene_deck(mode, tmax, energy) result(deck)
      character(len=*), intent(in) :: mode
      real(wp), intent(in) :: tmax
      logical, intent(in) :: energy
      character(len=:), allocatable :: deck
      character(len=400) :: b
      integer, parameter :: nx = 30, ny = 6
      integer :: tip
      tip = 1 + (ny/2)*(nx + 1) + nx
      deck = 'FEAP * * legacy API scene '//mode//nl//'0 0 0 2 2 4'//nl
      write (b, '(a,es23.16,a,es23.16,a,es23.16)') 'PARAmeters'//nl//'  young = ', young, nl//'  v0 = ', v0, &
         nl//'  rho = ', rho0
      deck = deck//trim(b)//nl
      write (b, '(a,es23.16,a,es23.16,a,i0,a,i0)') '  len = ', blen, nl//'  hgt = ', bhgt, nl//'  nx = ', nx, &
         nl//'  ny = ', ny
      deck = deck//trim(b)//nl//nl
      deck = deck//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young 0'//nl//'    DENSity rho'//nl//nl
      if (mode == 'wall') then
         deck = deck//'MATErial,2'//nl//'  RIGId'//nl//'    DENSity rho'//nl//nl
      else
         deck = deck//'MATErial,2'//nl//'  SOLId'//nl//'    ELAStic NEOHookean young 0.25'//nl// &
                '    DENSity 2*rho'//nl//nl
      end if
      deck = deck//'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,nx,ny,0,0,1'//nl//'    1,0,0'//nl// &
             '    2,len,0'//nl//'    3,len,hgt'//nl//'    4,0,hgt'//nl//nl
      if (mode == 'wall') then
         deck = deck//'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,4,0,0,2'//nl//'    1,len,-hgt'//nl// &
                '    2,len+hgt,-hgt'//nl//'    3,len+hgt,2*hgt'//nl//'    4,len,2*hgt'//nl//nl
      else
         deck = deck//'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,nx/2,ny+2,0,0,2'//nl//'    1,len,-1'//nl// &
                '    2,2*len,-1'//nl//'    3,2*len,hgt+1'//nl//'    4,len,hgt+1'//nl//nl
      end if
      deck = deck//'INITial,VELOcity'//nl//'  REGIon,1,v0,0'//nl
      if (mode == 'bars') deck = deck//'  REGIon,2,-v0,0.01'//nl
      deck = deck//nl//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
             '    REGIon,2'//nl//'  PAIR,1,NTOS,1,2'//nl
      if (energy) deck = deck//'    LAGRange,ENERgy'//nl
      deck = deck//'END CONTact'//nl//nl
      write (b, '(a,es23.16,a,es23.16)') '  DT,,', dt_fixed, nl//'  LOOP,,100000'//nl//'    TIME,,', tmax
      deck = deck//'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  TPLOt,,1'//nl//trim(b)//nl// &
             '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl
      write (b, '(a,i0,a,i0,a,i0,a)') '  disp,', tip, ',1'//nl//'  velo,', tip, ',1'//nl//'  acce,', tip, ',1'
      deck = deck//trim(b)//nl//'  cont,1,1'//nl//'  cont,1,4'//nl//'  cont,1,5'//nl//'  cont,1,6'//nl//nl//'STOP'
   end function scene_deck

   !> Run the scene's deck with exic itself; `model` is the model read.
   subroutine deck_run(s, name, mode, model, ok, energy)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, mode
      type(model_t), intent(out) :: model
      logical, intent(out) :: ok
      logical, intent(in), optional :: energy
      character(len=:), allocatable :: msg
      integer :: stage
      logical :: en
      en = .false.
      if (present(energy)) en = energy
      call run_deck(name, scene_deck(mode, 3.0_wp*blen/sqrt(young/rho0), en), stage, msg, model)
      ok = stage == 0
      call check(s, ok, name//': exic runs the deck', msg)
   end subroutine deck_run

   ! ------------------------------------------------------------------ bad arguments

   !> Every bad call returns ierr /= 0 and a message that says why; nothing crashes.
   subroutine bad_argument_tests(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 6), mass(6), x(2, 6), v(2, 6), a(2, 6), f(2, 6), pp(1), res(6), w, pen, rcon(6, 1)
      integer :: ix(4, 1), ib(1), ip(6, 1), iseg(3, 1), isn(2, 1), h, ierr, nact, ncon, icon(4, 1), ifix(2, 6)
      ! a unit square (nodes 1-4, body 1) and a rigid segment 5 -> 6 under it (segments mode)
      x0 = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                    2.0_wp, -0.5_wp, -1.0_wp, -0.5_wp], [2, 6])
      mass = 1.0_wp
      ix(:, 1) = [1, 2, 3, 4]
      ib = 1
      ip(:, 1) = [1, 2, 1, 1, 1, 1]
      pp = 0.0_wp
      iseg(:, 1) = [5, 6, 2]
      isn(:, 1) = [1, 1]

      call exic_contact_create_mesh(-4, x0, mass, 1, ix, ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'NNODE', 'negative node count')
      call exic_contact_create_mesh(6, x0, mass, -1, ix, ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'NELEM', 'negative element count')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, -2, isn, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'NSN', 'negative slave node count')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 0, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'NPAIR', 'no pairs')
      mass(3) = 0.0_wp
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [2, 1, 1, 1, 1, 1], pp, h, ierr)
      call bad(s, ierr, h, 0, 'mass of node 3', 'zero mass')
      mass(3) = -2.0_wp
      call exic_contact_create_mesh(6, x0, mass, 1, ix, ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'mass of node 3', 'negative mass')
      mass(3) = 1.0_wp
      x0(2, 4) = ieee_value(1.0_wp, ieee_quiet_nan)
      call exic_contact_create_mesh(6, x0, mass, 1, ix, ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'coordinate of node 4', 'NaN reference coordinate')
      x0(2, 4) = 1.0_wp
      call exic_contact_create_segments(6, x0, mass, 1, reshape([5, 7, 2], [3, 1]), 1, isn, 1, &
                                        [1, 2, 1, 1, 1, 1], pp, h, ierr)
      call bad(s, ierr, h, 0, 'segment 1', 'segment naming node 7 of 6')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, reshape([0, 1], [2, 1]), 1, &
                                        [1, 2, 1, 1, 1, 1], pp, h, ierr)
      call bad(s, ierr, h, 0, 'slave node entry 1', 'slave node 0')
      call exic_contact_create_mesh(6, x0, mass, 1, reshape([1, 2, 3, 9], [4, 1]), ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'element 1', 'element naming node 9 of 6')
      call exic_contact_create_mesh(6, x0, mass, 1, reshape([1, 4, 3, 2], [4, 1]), ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'clockwise', 'clockwise element')
      call exic_contact_create_mesh(6, x0, mass, 1, ix, ib, 1, ip, pp, h, ierr)
      call bad(s, ierr, h, 0, 'not defined', 'pair naming a body without elements')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [2, 1, 1, 1, 1, 1], pp, h, ierr)
      call bad(s, ierr, h, 0, 'node set', 'a node set as master')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [1, 2, 4, 1, 1, 1], pp, h, ierr)
      call bad(s, ierr, h, 0, 'out of range', 'method 4')
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [1, 2, 2, 1, 1, 1], [-1.0_wp], h, ierr)
      call bad(s, ierr, h, 0, 'penalty', 'negative penalty stiffness')

      ! a good problem: node set {1} above the rigid segment
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [1, 2, 1, 1, 1, 1], pp, h, ierr)
      call check(s, ierr == 0 .and. h > 0, 'a node set against a rigid segment is accepted')
      if (ierr /= 0) return
      x = x0
      v = 0.0_wp
      a = 0.0_wp
      call exic_contact_step(h + 1000, 6, x, v, a, 0.0_wp, 1.0e-3_wp, f, nact, ierr)
      call bad(s, ierr, h + 1000, 2, 'names no live', 'step with an unknown handle')
      call exic_contact_step(h, 5, x, v, a, 0.0_wp, 1.0e-3_wp, f, nact, ierr)
      call bad(s, ierr, h, 1, 'NNODE', 'step with another node count')
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 0.0_wp, f, nact, ierr)
      call bad(s, ierr, h, 1, 'DT', 'step with dt = 0')
      call exic_contact_step(h, 6, x, v, a, -1.0_wp, 1.0e-3_wp, f, nact, ierr)
      call bad(s, ierr, h, 1, 'DTPREV', 'step with dt(n) < 0')
      x(1, 2) = ieee_value(1.0_wp, ieee_quiet_nan)
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 1.0e-3_wp, f, nact, ierr)
      call bad(s, ierr, h, 1, 'position of node 2', 'step with a NaN position')
      x(1, 2) = 1.0_wp
      v(2, 1) = ieee_value(1.0_wp, ieee_quiet_nan)
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 1.0e-3_wp, f, nact, ierr)
      call bad(s, ierr, h, 1, 'velocity of node 1', 'step with a NaN velocity')
      v(2, 1) = -1.0_wp
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 1.0e-3_wp, f, nact, ierr)
      call check(s, ierr == 0 .and. nact == 0, 'after bad calls the handle still steps (ierr 0)')
      call exic_contact_pair_results(h, 2, res, ierr)
      call bad(s, ierr, h, 1, 'pair 2', 'results of pair 2 of 1')
      call exic_contact_constraints(h, -1, ncon, icon, rcon, ierr)
      call exic_contact_ncon(h, ncon, ierr)
      call check(s, ierr == 0, 'constraint count query', 'ierr '//itoa(ierr))
      call exic_contact_set_option(h, 7, 1, ierr)
      call bad(s, ierr, h, 1, 'unknown option', 'option 7')
      call exic_contact_set_option(h, 1, 3, ierr)
      call bad(s, ierr, h, 1, 'velocity form', 'velocity form 3')
      call exic_contact_set_pair(h, 1, [1, 1, 2, 1], 0.0_wp, ierr)
      call bad(s, ierr, h, 1, 'node set', 'two passes with a node set')
      call exic_contact_set_pair(h, 1, [2, 2, 1, 1], 1.0e3_wp, ierr)
      call check(s, ierr == 0, 'valid new pair options are accepted')
      ifix = 0
      call exic_contact_set_fixed(h, 4, ifix, ierr)
      call bad(s, ierr, h, 1, 'NNODE', 'fixities with another node count')
      call exic_contact_free(h, ierr)
      call check(s, ierr == 0, 'free a live handle')
      call exic_contact_free(h, ierr)
      call bad(s, ierr, h, 2, 'names no live', 'free the same handle twice')
      call exic_contact_work(h, w, pen, ierr)
      call bad(s, ierr, h, 2, 'names no live', 'query a freed handle')
   end subroutine bad_argument_tests

   ! ------------------------------------------------------------------ in-process host

   !> The step's contact: one EXIC_CONTACT_STEP call with the stepper's arrays.
   subroutine api_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err)
      class(api_hook_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(out) :: nactive
      type(error_t), allocatable, intent(out) :: err
      integer :: ierr
      call exic_contact_step(self%h, nnode, x, vt, a, dt_prev, dt, fcon, nactive, ierr)
      if (ierr /= 0) call make_error(err, 'EXIC_CONTACT_STEP returned ierr = '//itoa(ierr))
   end subroutine api_correct

   !> The stepper of `model` without exic's contact (the deck's is made through the API).
   subroutine api_init(r, model)
      type(api_run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable :: err
      call r%stp%init(model%mesh, model%materials, contact_spec_t(), err)
      r%ok = .not. allocated(err)
   end subroutine api_init

   !> Create the problem of `model` through the API and take the first (t = 0) step.
   subroutine api_start(r, model, tip)
      type(api_run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer, intent(in) :: tip
      integer :: ierr
      integer, allocatable :: ipair(:, :)
      real(wp), allocatable :: pp(:)
      call api_init(r, model)
      if (.not. r%ok) return
      call host_pairs(model, ipair, pp)
      call exic_contact_create_mesh(r%stp%st%nnode, model%mesh%x, r%stp%st%mass, model%mesh%nelem, &
                                    model%mesh%conn, model%mesh%region, size(ipair, 2), ipair, pp, r%h, ierr)
      r%ok = ierr == 0
      if (r%ok) call api_first_step(r, tip)
   end subroutine api_start

   !> Hook the handle into the stepper, set the deck's fixed step and make the state at t = 0.
   subroutine api_first_step(r, tip)
      type(api_run_t), intent(inout) :: r
      integer, intent(in) :: tip
      type(error_t), allocatable :: err
      allocate (r%hook)
      r%hook%h = r%h
      r%stp%hook => r%hook
      r%tmax = 3.0_wp*blen/sqrt(young/rho0)
      r%itip = tip
      allocate (r%rows(8, 1000))
      call r%stp%set_fixed_dt(dt_fixed, 'test', err)
      if (.not. allocated(err)) call r%stp%start(err)
      r%ok = .not. allocated(err)
      call api_row(r)
   end subroutine api_first_step

   !> One explicit step of the in-process host: exic's stepper with the API's contact.
   subroutine api_advance(r, done)
      type(api_run_t), intent(inout) :: r
      logical, intent(out) :: done
      type(error_t), allocatable :: err
      done = r%stp%st%t >= r%tmax*(1.0_wp - 1.0e-12_wp) .or. .not. r%ok
      if (done) return
      call r%stp%advance(err)
      r%ok = .not. allocated(err)
      call api_row(r)
   end subroutine api_advance

   !> The history row of the deck's TPLOt requests: t, tip u, v, a, pair 1 components 1, 4, 5, 6.
   subroutine api_row(r)
      type(api_run_t), intent(inout) :: r
      real(wp) :: res(6)
      real(wp), allocatable :: tmp(:, :)
      integer :: ierr
      call exic_contact_pair_results(r%h, 1, res, ierr)
      if (r%nrow == size(r%rows, 2)) then
         allocate (tmp(8, 2*r%nrow))
         tmp(:, 1:r%nrow) = r%rows
         call move_alloc(tmp, r%rows)
      end if
      r%nrow = r%nrow + 1
      associate (st => r%stp%st)
         r%rows(:, r%nrow) = [st%t, st%u(1, r%itip), st%v(1, r%itip), st%a(1, r%itip), res(1), res(4), &
                              res(5), res(6)]
      end associate
   end subroutine api_row

   !> Run to the end alone.
   subroutine api_run_alone(r, model, tip)
      type(api_run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer, intent(in) :: tip
      logical :: done
      call api_start(r, model, tip)
      do
         call api_advance(r, done)
         if (done) exit
      end do
   end subroutine api_run_alone

   !> Done-when 3: two handles stepped alternately give exactly what each gives alone; and the
   !> in-process API run equals the deck run.
   subroutine alternate_test(s, wall, bars)
      type(suite_t), intent(inout) :: s
      type(model_t), intent(in) :: wall, bars
      type(api_run_t) :: a1, b1, a2, b2
      logical :: da, db
      integer :: tip, ierr
      tip = 1 + 3*31 + 30
      call api_run_alone(a1, wall, tip)
      call api_run_alone(b1, bars, tip)
      call check(s, a1%ok .and. b1%ok, 'wall and two-bar scenes run through the API alone')
      call api_start(a2, wall, tip)
      call api_start(b2, bars, tip)
      do
         call api_advance(a2, da)
         call api_advance(b2, db)
         if (da .and. db) exit
      end do
      call check(s, a2%ok .and. b2%ok .and. a2%h /= b2%h, 'both handles step when used alternately')
      call check(s, a1%nrow == a2%nrow .and. b1%nrow == b2%nrow, 'alternate runs have as many rows as alone')
      if (a1%nrow == a2%nrow .and. b1%nrow == b2%nrow) then
         call check(s, all(a1%rows(:, 1:a1%nrow) == a2%rows(:, 1:a2%nrow)), &
                    'wall handle used alternately equals it alone (bitwise)')
         call check(s, all(b1%rows(:, 1:b1%nrow) == b2%rows(:, 1:b2%nrow)), &
                    'two-bar handle used alternately equals it alone (bitwise)')
      end if
      call compare_deck(s, 'legacy_wall', a1%rows(:, 1:a1%nrow), 'in-process API run of the wall scene')
      call compare_deck(s, 'legacy_bars', b1%rows(:, 1:b1%nrow), 'in-process API run of the two-bar scene')
      call exic_contact_free(a1%h, ierr)
      call exic_contact_free(b1%h, ierr)
      call exic_contact_free(a2%h, ierr)
      call exic_contact_free(b2%h, ierr)
   end subroutine alternate_test

   !> The wall scene made from segment lists (the free edges, as the host could give them)
   !> runs exactly as the one made from connectivity.
   subroutine segments_test(s, wall)
      type(suite_t), intent(inout) :: s
      type(model_t), intent(in) :: wall
      type(api_run_t) :: r1, r2
      type(error_t), allocatable :: err
      integer, allocatable :: e1(:, :), e2(:, :), iseg(:, :), ipair(:, :), isn(:, :)
      real(wp), allocatable :: pp(:)
      integer :: tip, ierr, ns
      logical :: done
      tip = 1 + 3*31 + 30
      call api_run_alone(r1, wall, tip)
      call free_edges(wall%mesh%nelem, wall%mesh%conn, wall%mesh%region == 1, e1, err)
      call free_edges(wall%mesh%nelem, wall%mesh%conn, wall%mesh%region == 2, e2, err)
      ns = size(e1, 2) + size(e2, 2)
      allocate (iseg(3, ns), isn(2, 0))
      iseg(1:2, 1:size(e1, 2)) = e1
      iseg(3, 1:size(e1, 2)) = 1
      iseg(1:2, size(e1, 2) + 1:) = e2
      iseg(3, size(e1, 2) + 1:) = 2
      call host_pairs(wall, ipair, pp)
      ! the in-process start, with the problem made from segments instead
      call start_from(r2, wall, tip, iseg, isn, ipair, pp)
      call check(s, r2%ok, 'wall scene from segment lists is accepted')
      if (.not. r2%ok) return
      do
         call api_advance(r2, done)
         if (done) exit
      end do
      call check(s, r1%nrow == r2%nrow .and. r2%ok, 'segment-list run has as many rows as the connectivity run')
      if (r1%nrow == r2%nrow) call check(s, all(r1%rows(:, 1:r1%nrow) == r2%rows(:, 1:r2%nrow)), &
                                         'segment-list run equals the connectivity run (bitwise)')
      call exic_contact_free(r1%h, ierr)
      call exic_contact_free(r2%h, ierr)
   end subroutine segments_test

   !> api_start with the problem made from segment lists.
   subroutine start_from(r, model, tip, iseg, isn, ipair, pp)
      type(api_run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer, intent(in) :: tip, iseg(:, :), isn(:, :), ipair(:, :)
      real(wp), intent(in) :: pp(:)
      integer :: ierr
      call api_init(r, model)
      if (.not. r%ok) return
      call exic_contact_create_segments(r%stp%st%nnode, model%mesh%x, r%stp%st%mass, size(iseg, 2), iseg, &
                                        size(isn, 2), isn, size(ipair, 2), ipair, pp, r%h, ierr)
      r%ok = ierr == 0
      if (r%ok) call api_first_step(r, tip)
   end subroutine start_from

   !> Pairs of a deck model in the API's table: slave region, master region, Lagrange, swept,
   !> one pass (NTOS) or two (SYMMetric), rigid master when the master region is rigid.
   subroutine host_pairs(model, ipair, pp)
      type(model_t), intent(in) :: model
      integer, allocatable, intent(out) :: ipair(:, :)
      real(wp), allocatable, intent(out) :: pp(:)
      integer :: k, rs, rm, e
      allocate (ipair(6, size(model%contact%pairs)), source=0)
      allocate (pp(size(model%contact%pairs)))
      pp = 0.0_wp
      do k = 1, size(model%contact%pairs)
         rs = region_of_surface(model, model%contact%pairs(k)%slave)
         rm = region_of_surface(model, model%contact%pairs(k)%master)
         ipair(:, k) = [rs, rm, model%contact%pairs(k)%method, model%contact%pairs(k)%detection, &
                        merge(1, 2, model%contact%pairs(k)%kind == 1), 0]
         ! LAGRange,ENERgy: method 3, Lagrange with massless contact faces
         if (model%contact%pairs(k)%energy) ipair(3, k) = 3
         do e = 1, model%mesh%nelem
            if (model%mesh%region(e) == rm .and. model%materials(model%mesh%mat(e))%kind == MAT_RIGID) &
               ipair(6, k) = 1
         end do
      end do
   end subroutine host_pairs

   !> Region of a SURFace,id given as REGIon,r.
   integer function region_of_surface(model, id) result(r)
      type(model_t), intent(in) :: model
      integer, intent(in) :: id
      integer :: k
      r = 0
      do k = 1, size(model%contact%surfaces)
         if (model%contact%surfaces(k)%id == id) r = model%contact%surfaces(k)%ref
      end do
   end function region_of_surface

   ! ------------------------------------------------------------------ the installed hosts

   !> Install exic into build/legacy_prefix and build lhost and chost against it.
   subroutine build_hosts(s, built)
      type(suite_t), intent(inout) :: s
      logical, intent(out) :: built
      integer :: stat, cstat
      logical :: there
      character(len=:), allocatable :: fpm
      fpm = fpm_command()
      if (len(fpm) == 0) then
         built = .false.
         call skip(s, 'install exic and build the F77 and C hosts (and their 45 checks)', 'fpm ($EXIC_FPM or on PATH)', 45)
         return
      end if
      ! an empty prefix, so the check of what is installed sees this installation only
      call execute_command_line('rm -rf '//prefix, exitstat=stat, cmdstat=cstat)
      call execute_command_line('EXIC_FPM='//fpm//' bash examples/legacy_host/build.sh '//prefix//' '//bindir// &
                                ' > build/legacy_build.log 2>&1', exitstat=stat, cmdstat=cstat)
      built = stat == 0 .and. cstat == 0
      call check(s, built, 'fpm install and the host builds succeed (log: build/legacy_build.log)')
      inquire (file=prefix//'/lib/libexic.a', exist=there)
      call check(s, there, 'libexic.a is installed under '//prefix//'/lib')
      inquire (file=prefix//'/include/exic_contact.h', exist=there)
      call check(s, there, 'the C header is installed under '//prefix//'/include')
      call execute_command_line('nm '//bindir//'/lhost | grep -q " [Tt] exic_contact_step_$"', exitstat=stat, &
                                cmdstat=cstat)
      call check(s, stat == 0 .and. cstat == 0, 'lhost links the plain F77 symbol exic_contact_step_')
      ! exactly the program, the library, its module files and the header
      call execute_command_line('test "$(ls '//prefix//'/bin)" = exic && test "$(ls '//prefix//'/lib)" = libexic.a && '// &
                                'test -z "$(ls '//prefix//'/include | grep -v -e ''^exic_.*\.mod$'' -e ''^exic_contact\.h$'')"', &
                                exitstat=stat, cmdstat=cstat)
      call check(s, stat == 0 .and. cstat == 0, 'the installation holds bin/exic, lib/libexic.a and include/exic_*.mod '// &
                 'and exic_contact.h, no benchmark program or module')
   end subroutine build_hosts

   !> The F77 skeleton shown in doc/api.md is examples/legacy_host/skeleton.f, builds with the
   !> doc's F77 link line against the installation and runs; the C link line is the header's;
   !> the doc's line for the whole library links the exic program.
   subroutine skeleton_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: doc, block, file, f77, cline, full, out
      integer :: stat, cstat
      real(wp) :: pen, vx
      integer :: ncon, ios, k
      doc = file_text('doc/api.md')
      file = file_text('examples/legacy_host/skeleton.f')
      block = between(doc, '<!-- skeleton.f: begin -->'//nl//'```fortran'//nl, '```'//nl//'<!-- skeleton.f: end -->')
      call check(s, len(file) > 0 .and. block == file, 'doc/api.md shows examples/legacy_host/skeleton.f whole')
      f77 = line_starting(doc, 'gfortran -O2 host.f ')
      cline = line_starting(doc, 'cc -O2 -I$PREFIX/include host.c ')
      full = line_starting(doc, 'mpifort -O2 -fopenmp -I$PREFIX/include prog.f90 ')
      call check(s, len(f77) > 0 .and. len(cline) > 0 .and. len(full) > 0, 'doc/api.md states the three link lines')
      call check(s, len(cline) > 0 .and. index(file_text('include/exic_contact.h'), ' * '//cline//nl) > 0, &
                 'include/exic_contact.h states the C link line of doc/api.md', cline)
      call check(s, index(f77, 'hdf5') == 0 .and. index(f77, 'gmsh') == 0 .and. index(cline, 'hdf5') == 0, &
                 'a host of the contact API links neither HDF5 nor Gmsh')
      call check(s, index(cline, 'gmsh') == 0 .and. index(full, 'gmsh') == 0, &
                 'no link line names Gmsh (GMSH loads it at run time)')
      if (len(f77) == 0) return
      f77 = replaced(replaced(f77, 'host.f', 'examples/legacy_host/skeleton.f -o '//bindir//'/skeleton_doc'), &
                     '$PREFIX', prefix)
      call execute_command_line(f77//' > '//bindir//'/skeleton_build.log 2>&1', exitstat=stat, cmdstat=cstat)
      call check(s, stat == 0 .and. cstat == 0, 'the skeleton builds with the doc''s F77 line: '//f77)
      if (stat /= 0 .or. cstat /= 0) return
      call execute_command_line(bindir//'/skeleton_doc > '//bindir//'/skeleton.txt 2>&1', exitstat=stat, cmdstat=cstat)
      out = file_text(bindir//'/skeleton.txt')
      k = index(out, 'LARGEST PENETRATION')
      pen = huge(1.0_wp)
      ncon = 0
      vx = 0.0_wp
      if (k > 0) read (out(k + 19:), *, iostat=ios) pen
      k = index(out, 'MOST CONSTRAINTS')
      if (k > 0) read (out(k + 16:), *, iostat=ios) ncon
      k = index(out, 'FINAL VX1')
      if (k > 0) read (out(k + 9:), *, iostat=ios) vx
      call check(s, stat == 0 .and. pen <= 1.0e-12_wp .and. ncon == 2 .and. vx < -0.1_wp, &
                 'the skeleton runs: the square meets the block with 2 constraints, never enters it, bounces back', &
                 'penetration '//rtoa(pen)//', constraints '//itoa(ncon)//', final vx '//rtoa(vx))
      full = replaced(replaced(full, 'prog.f90', 'app/main.f90 -o '//bindir//'/exic_linked -J '//bindir), &
                      '$PREFIX', prefix)
      call execute_command_line(full//' > '//bindir//'/exic_link.log 2>&1 && '//bindir//'/exic_linked --version > /dev/null', &
                                exitstat=stat, cmdstat=cstat)
      call check(s, stat == 0 .and. cstat == 0, 'the exic program links with the doc''s line for the whole library', full)
   end subroutine skeleton_test

   !> The text of `doc` between the end of `first` and the start of `last` ('' if either is missing).
   function between(doc, first, last) result(r)
      character(len=*), intent(in) :: doc, first, last
      character(len=:), allocatable :: r
      integer :: i, j
      r = ''
      i = index(doc, first)
      j = index(doc, last)
      if (i > 0 .and. j > i + len(first)) r = doc(i + len(first):j - 1)
   end function between

   !> The first line of `doc` that starts with `start` (without its newline; '' if none).
   function line_starting(doc, start) result(r)
      character(len=*), intent(in) :: doc, start
      character(len=:), allocatable :: r
      integer :: i, j
      r = ''
      i = index(doc, nl//start)
      if (i == 0) return
      j = index(doc(i + 1:), nl)
      if (j == 0) return
      r = doc(i + 1:i + j - 1)
   end function line_starting

   !> `text` with every `what` replaced by `by`.
   function replaced(text, what, by) result(r)
      character(len=*), intent(in) :: text, what, by
      character(len=:), allocatable :: r
      integer :: i
      r = ''
      i = 1
      do
         if (i > len(text)) exit
         if (i + len(what) - 1 <= len(text)) then
            if (text(i:i + len(what) - 1) == what) then
               r = r//by
               i = i + len(what)
               cycle
            end if
         end if
         r = r//text(i:i)
         i = i + 1
      end do
   end function replaced

   !> Write the host's input file for `model`: material kinds 1 (neo-Hookean) or 2 (linear) for
   !> solids and 0 for rigid bodies, step dt (< 0: CFL factor), velocity form ivf.
   subroutine write_host_input(path, model, solid_kind, dt, ivf)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      integer, intent(in) :: solid_kind, ivf
      real(wp), intent(in) :: dt
      integer :: u, i, e, k
      integer, allocatable :: ipair(:, :), edges(:, :)
      real(wp), allocatable :: pp(:)
      logical, allocatable :: onface(:)
      type(error_t), allocatable :: err
      call host_pairs(model, ipair, pp)
      open (newunit=u, file=path, status='replace', action='write')
      write (u, '(a)') 'exic scene for lhost'
      write (u, '(4(i0,1x))') model%mesh%nnode, model%mesh%nelem, size(model%materials), size(ipair, 2)
      do i = 1, model%mesh%nnode
         write (u, '(4es25.17,2(1x,i0))') model%mesh%x(:, i), model%mesh%v0(:, i), merge(1, 0, model%mesh%bc(:, i) /= 0)
      end do
      do e = 1, model%mesh%nelem
         write (u, '(6(i0,1x))') model%mesh%conn(:, e), model%mesh%region(e), model%mesh%mat(e)
      end do
      do k = 1, size(model%materials)
         associate (m => model%materials(k))
            write (u, '(i0,3es25.17)') merge(0, solid_kind, m%kind == MAT_RIGID), m%young, m%poisson, m%rho
         end associate
      end do
      do k = 1, size(ipair, 2)
         write (u, '(6(i0,1x),es25.17)') ipair(:, k), pp(k)
      end do
      write (u, '(2es25.17,2(1x,i0))') dt, 3.0_wp*blen/sqrt(young/rho0), 1 + 3*31 + 30, ivf
      if (any(ipair(3, :) == 3)) then
         ! the candidate face: every node of the free boundaries of the method-3 pairs' bodies
         ! (lhost drops the rigid ones)
         allocate (onface(model%mesh%nnode), source=.false.)
         do k = 1, size(ipair, 2)
            if (ipair(3, k) /= 3) cycle
            do i = 1, 2
               call free_edges(model%mesh%nelem, model%mesh%conn, model%mesh%region == ipair(i, k), edges, err)
               onface(reshape(edges, [size(edges)])) = .true.
            end do
         end do
         write (u, '(i0)') count(onface)
         write (u, '(10(i0,1x))') pack([(i, i=1, model%mesh%nnode)], onface)
      end if
      close (u)
   end subroutine write_host_input

   !> Run lhost on run_dir/<name>.dat; rows(9, n) of its table, work and penetration lines.
   subroutine run_host(name, rows, wcon, penmax, ok, energy)
      character(len=*), intent(in) :: name
      real(wp), allocatable, intent(out) :: rows(:, :)
      real(wp), intent(out) :: wcon, penmax
      logical, intent(out) :: ok
      real(wp), intent(out), optional :: energy(2)     !< final kinetic and strain energy
      integer :: stat, cstat, u, ios, n
      character(len=512) :: line
      real(wp) :: buf(9, 4000)
      call execute_command_line(bindir//'/lhost < '//run_dir//'/'//name//'.dat > '//run_dir//'/'//name//'.lh', &
                                exitstat=stat, cmdstat=cstat)
      ok = stat == 0 .and. cstat == 0
      wcon = 0.0_wp
      penmax = huge(1.0_wp)
      n = 0
      open (newunit=u, file=run_dir//'/'//name//'.lh', status='old', action='read', iostat=ios)
      if (ios /= 0) then
         ok = .false.
         allocate (rows(9, 0))
         return
      end if
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (line(1:1) == '#') then
            if (index(line, '# CONTACT WORK') == 1) read (line(15:), *) wcon
            if (index(line, '# LARGEST PENETRATION') == 1) read (line(22:), *) penmax
            if (index(line, '# KINETIC AND STRAIN ENERGY') == 1 .and. present(energy)) read (line(29:), *) energy
            if (index(line, 'ERROR') > 0) ok = .false.
            cycle
         end if
         if (n == size(buf, 2)) exit
         n = n + 1
         read (line, *) buf(:, n)
      end do
      close (u)
      rows = buf(:, 1:n)
   end subroutine run_host

   !> Done-when 1: with exic's element formulation and step the F77 host's tip and contact
   !> histories equal the deck run's to 1e-10 relative (they agree to round-off or better).
   subroutine host_equal_test(s, name, model)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      type(model_t), intent(in) :: model
      real(wp), allocatable :: rows(:, :), e(:, :)
      character(len=64), allocatable :: enames(:)
      real(wp) :: wcon, penmax, wdeck
      logical :: ok
      call write_host_input(run_dir//'/'//name//'_nh.dat', model, 1, dt_fixed, 1)
      call run_host(name//'_nh', rows, wcon, penmax, ok)
      call check(s, ok, name//': lhost (neo-Hookean, fixed step) runs')
      if (.not. ok) return
      call compare_deck(s, name, rows(1:8, :), 'F77 host')
      call read_table(run_dir//'/'//name//'.ene', enames, e)
      wdeck = e(column(enames, 'contact_work'), size(e, 2))
      ! the API sums the work over surface nodes from positions, the driver over all nodes from
      ! increments: the same terms up to rounding, compared on the scale of the initial energy
      call check_close(s, wcon, wdeck, 1.0e-10_wp*energy0, name//': contact work equals the deck''s')
      call check(s, penmax < 1.0e-10_wp*blen, name//': largest penetration below 1e-10 L', rtoa(penmax))
   end subroutine host_equal_test

   !> Method 3 (massless contact faces) through the API: lhost with the face of the bar's whole
   !> boundary (as the deck's REGIon surface), its own lumped-mass transfer (eq. I.3) and its
   !> analytic linear stiffness for the face rows reproduces exic's deck run of the same scene
   !> with LAGRange,ENERgy: every history row to 1e-10 relative (exic forms K0 by central
   !> differences of its force kernel, relative error about 1e-10, which sets only the decay of
   !> the face residual, doc/impact.md 3.2: 2.5e-11 measured), the final energy to 1e-8 of E0, contact work at
   !> round-off, every corrected gap closed. Against the default scheme's lhost run of the same
   !> scene (host_equal_test) the final energy is higher by the capture the massless face
   !> avoids, 1/(2N) = 1/60 of E0 (within 0.1 % of E0).
   subroutine host_energy_test(s, model)
      type(suite_t), intent(inout) :: s
      type(model_t), intent(in) :: model
      real(wp), allocatable :: rows(:, :), rows0(:, :), e(:, :), d(:, :)
      character(len=64), allocatable :: enames(:), names(:)
      real(wp) :: wcon, penmax, en(2), en0(2), w0, p0, edeck, worst, rel
      logical :: ok, ok0
      integer :: j
      call face_rule_test(s, model)
      call write_host_input(run_dir//'/legacy_wall_energy_nh.dat', model, 1, dt_fixed, 1)
      call run_host('legacy_wall_energy_nh', rows, wcon, penmax, ok, en)
      call check(s, ok, 'legacy_wall_energy: lhost with method 3 and its own face set-up runs')
      if (.not. ok) return
      call read_table(run_dir//'/legacy_wall_energy.his', names, d)
      call check(s, size(d, 2) == size(rows, 2), 'legacy_wall_energy: lhost has the deck''s '// &
                 itoa(size(d, 2))//' rows', 'has '//itoa(size(rows, 2)))
      if (size(d, 2) /= size(rows, 2)) return
      worst = 0.0_wp
      do j = 1, 8
         if (j == 7) then
            rel = maxval(abs(rows(j, :) - d(j, :)))/blen
         else
            rel = maxval(abs(rows(j, :) - d(j, :)))/max(maxval(abs(d(j, :))), tiny(1.0_wp))
         end if
         if (.not. (rel <= worst)) worst = rel
      end do
      call check(s, worst <= 1.0e-10_wp .and. maxval(d(6, :)) > 0.0_wp, 'legacy_wall_energy: F77 host '// &
                 'history equals the deck''s LAGRange,ENERgy run to 1e-10 relative (largest '//rtoa(worst)//')')
      call read_table(run_dir//'/legacy_wall_energy.ene', enames, e)
      edeck = e(column(enames, 'kinetic'), size(e, 2)) + e(column(enames, 'strain'), size(e, 2))
      call check_close(s, en(1) + en(2), edeck, 1.0e-8_wp*energy0, &
                       'legacy_wall_energy: final kinetic + strain energy equals the deck''s')
      call check(s, abs(wcon) < 1.0e-10_wp*energy0 .and. penmax < 1.0e-10_wp*blen .and. &
                 minval(rows(9, :)) > -1.0e-10_wp*blen, 'legacy_wall_energy: contact work, penetration and '// &
                 'corrected gaps at round-off', 'work '//rtoa(wcon/energy0)//' E0, penetration '//rtoa(penmax)// &
                 ', smallest gap '//rtoa(minval(rows(9, :))))
      call run_host('legacy_wall_nh', rows0, w0, p0, ok0, en0)
      call check(s, ok0 .and. abs((en(1) + en(2) - en0(1) - en0(2))/energy0 - 1.0_wp/60.0_wp) < 1.0e-3_wp, &
                 'legacy_wall_energy: the final energy exceeds the default scheme''s by the capture 1/(2N) of E0', &
                 'difference '//rtoa((en(1) + en(2) - en0(1) - en0(2))/energy0)//' E0, 1/60 = '// &
                 rtoa(1.0_wp/60.0_wp))
   end subroutine host_energy_test

   !> EXIC_CONTACT_FACE_RULE on the bar on a rigid wall (the bar's whole boundary the surface of
   !> a method-3 pair with a rigid master): the rule of decks (doc/impact.md eq. I.3b) makes the
   !> struck end massless along x, its ny + 1 = 7 nodes at x = L, and nothing else, as the deck's
   !> `<stem>.out` says of the same scene.
   subroutine face_rule_test(s, model)
      type(suite_t), intent(inout) :: s
      type(model_t), intent(in) :: model
      integer, allocatable :: ipair(:, :), ifd(:, :)
      real(wp), allocatable :: pp(:), mass(:)
      integer :: h, ierr, nn, k
      logical :: ok
      nn = model%mesh%nnode
      call host_pairs(model, ipair, pp)
      allocate (mass(nn), source=1.0_wp)
      call exic_contact_create_mesh(nn, model%mesh%x, mass, model%mesh%nelem, model%mesh%conn, model%mesh%region, &
                                    size(ipair, 2), ipair, pp, h, ierr)
      call check(s, ierr == 0, 'face rule: the bar on a rigid wall with method 3 is created', 'ierr '//itoa(ierr))
      if (ierr /= 0) return
      allocate (ifd(2, nn))
      call exic_contact_face_rule(h, nn, ifd, ierr)
      ok = ierr == 0 .and. count(ifd(1, :) == 1) == 7 .and. count(ifd(2, :) == 1) == 0
      if (ok) ok = all(abs(model%mesh%x(1, pack([(k, k=1, nn)], ifd(1, :) == 1)) - blen) < 1.0e-12_wp*blen)
      call check(s, ok, 'face rule: the bar''s struck end (7 nodes at x = L) massless along x, nothing else', &
                 'ierr '//itoa(ierr)//', along x '//itoa(count(ifd(1, :) == 1))//', along y '//itoa(count(ifd(2, :) == 1)))
      call exic_contact_free(h, ierr)
   end subroutine face_rule_test

   !> Compare rows(8, n) (t, tip u, v, a, pair 1 force, active, penetration, multiplier) with
   !> the deck's history: same number of rows, every column within 1e-10 of its largest value,
   !> the penetration (round-off residuals of order 1e-15 .. 1e-9) within 1e-10 of the bar's length.
   subroutine compare_deck(s, name, rows, who)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, who
      real(wp), intent(in) :: rows(:, :)
      real(wp), allocatable :: d(:, :)
      character(len=64), allocatable :: names(:)
      real(wp) :: worst, rel
      integer :: j
      call read_table(run_dir//'/'//name//'.his', names, d)
      call check(s, size(d, 1) == 8 .and. size(d, 2) == size(rows, 2), name//': '//who//' has the deck''s '// &
                 itoa(size(d, 2))//' rows', 'has '//itoa(size(rows, 2)))
      if (size(d, 1) /= 8 .or. size(d, 2) /= size(rows, 2)) return
      worst = 0.0_wp
      do j = 1, 8
         if (j == 7) then
            rel = maxval(abs(rows(j, :) - d(j, :)))/blen
         else
            rel = maxval(abs(rows(j, :) - d(j, :)))/max(maxval(abs(d(j, :))), tiny(1.0_wp))
         end if
         if (.not. (rel <= worst)) worst = rel
      end do
      call check(s, worst <= 1.0e-10_wp .and. maxval(d(6, :)) > 0.0_wp, name//': '//who// &
                 ' history equals the deck''s to 1e-10 relative (largest '//rtoa(worst)//')')
   end subroutine compare_deck

   !> Done-when 1, second half: the host's small-strain element with its own CFL step and
   !> half-step velocities; every gap closes (corrected gaps and penetrations below 1e-10 L).
   subroutine host_simple_test(s, name, model)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      type(model_t), intent(in) :: model
      real(wp), allocatable :: rows(:, :), dts(:)
      real(wp) :: wcon, penmax, e_all
      logical :: ok
      integer :: n
      call write_host_input(run_dir//'/'//name//'_lin.dat', model, 2, -0.8_wp, 2)
      call run_host(name//'_lin', rows, wcon, penmax, ok)
      n = size(rows, 2)
      call check(s, ok .and. n > 10, name//': lhost (linear element, own CFL step, half-step velocities) runs')
      if (.not. ok .or. n <= 10) return
      dts = rows(1, 2:n) - rows(1, 1:n - 1)
      call check(s, maxval(dts) > minval(dts)*(1.0_wp + 1.0e-9_wp), name//': the host''s step varies', &
                 'dt from '//rtoa(minval(dts))//' to '//rtoa(maxval(dts)))
      call check(s, count(rows(6, :) > 0.0_wp) > 10 .and. rows(6, n) == 0.0_wp, &
                 name//': contact is made and released')
      call check(s, maxval(rows(7, :)) < 1.0e-10_wp*blen .and. penmax < 1.0e-10_wp*blen, &
                 name//': largest penetration at t(n+1) below 1e-10 L', rtoa(max(maxval(rows(7, :)), penmax)))
      call check(s, minval(rows(9, :)) > -1.0e-10_wp*blen, name//': every corrected gap at t(n+2) closed', &
                 'smallest '//rtoa(minval(rows(9, :))))
      ! the contact work books the kinetic energy the corrector's capture removes (doc/impact.md,
      ! eq. I.12): negative, about 1/(2N) of the energy per struck end, never a gain
      e_all = energy0
      if (name == 'legacy_bars') e_all = 2.0_wp*energy0   ! two bars, each with energy0
      call check(s, wcon <= 0.0_wp .and. -wcon < 0.05_wp*e_all, name//': contact only removes energy, '// &
                 'less than 5 % of it (the capture of the struck columns)', rtoa(wcon/e_all))
   end subroutine host_simple_test

   !> The C host: one step, the gap closes, an unknown handle gives a message.
   subroutine c_host_test(s)
      type(suite_t), intent(inout) :: s
      integer :: stat, cstat
      call execute_command_line(bindir//'/chost > '//run_dir//'/chost.txt 2>&1', exitstat=stat, cmdstat=cstat)
      call check(s, stat == 0 .and. cstat == 0, 'chost: one step closes the gap, contact force = m a, '// &
                 'unknown handle reported; with mu = 0.5 the node slides with friction force mu N '// &
                 'against its motion, mud > mus refused; a massless face node (method 3) is placed on the '// &
                 'ground by its springs (output in '//run_dir//'/chost.txt)')
   end subroutine c_host_test

end module test_legacy
