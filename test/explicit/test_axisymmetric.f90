!> Axisymmetric solids, plastic element sets and mean dilatation (doc/axisymmetry.md): the
!> patch test of the general element path, the reader's records and errors, a ring's breathing
!> mode, the thick-walled cylinder (elastic, against Lame) and the energy balance of a small
!> Taylor bar.
module test_axisymmetric
   use exic_material_law, only: law_make, LAW_J2, LAW_NEOHOOKEAN
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_strings, only: rtoa
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   use exic_material_j2_hardening, only: j2_param_t, J2_MISES
   use exic_material_j2, only: j2_piola
   use exic_element_q4_general, only: q4_solid_t, q4g_init, q4g_force, q4g_hist_init
   use exic_material_material, only: lame_from_young
   use testing, only: suite_t, check, check_close, section
   use deck_runner, only: run_dir, run_deck, read_table, column
   use exic_explicit_step, only: stepper_t
   use test_loads, only: setup_stepper
   implicit none
   private

   public :: run_axisymmetric_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_axisymmetric_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'axisymmetric: patch test of the general element path')
      call patch(s, 2, .false., .false., .true., '2x2')
      call patch(s, 2, .true., .false., .true., '2x2 MIXEd')
      call patch(s, 2, .false., .true., .true., '2x2 plastic')
      call patch(s, 2, .true., .true., .true., '2x2 MIXEd plastic')
      call patch(s, 1, .false., .true., .false., 'one point plastic (rectangles)')
      call patch(s, 2, .true., .true., .false., '2x2 MIXEd plastic, plane strain')
      call section(s, 'axisymmetric: deck records and errors')
      call reader_errors(s)
      call section(s, 'axisymmetric: loads per radian')
      call ring_loads(s)
      call section(s, 'axisymmetric: ring breathing mode')
      call ring(s, 2)
      call ring(s, 1)
      call section(s, 'axisymmetric: thick-walled cylinder')
      call cylinder(s)
      call section(s, 'axisymmetric: Taylor bar energy balance (5 x 50)')
      call taylor(s)
   end subroutine run_axisymmetric_tests

   !> Patch test (doc/axisymmetry.md, section 2): a mesh of 3 x 3 elements on r in [1, 2],
   !> z in [0, 1] (interior nodes moved off the grid when `distort`) under the homogeneous
   !> motion u_r = e1 R, u_z = e3 Z (uniform F, F33 = F11: uniform stress in equilibrium).
   !> The interior nodes carry no force (to round-off), and the top nodes carry the resultant
   !> P22 (r2^2 - r1^2)/2 per radian (P22 of the law at that F). Plastic: the strain is past
   !> yield, so the history of every point changes (the same at every point). In plane strain
   !> (axi false) the top resultant is P22 (r2 - r1).
   subroutine patch(s, nq, mixed, plastic, axi, what)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      logical, intent(in) :: mixed, plastic, axi
      character(len=*), intent(in) :: what
      integer, parameter :: n = 3, nn = (n + 1)*(n + 1), ne = n*n
      real(wp) :: x0(2, nn), u(2, nn), f(2, nn), w, whg, wd, jm, d2, lam, mu, ftop, want, scale
      real(wp) :: p(5), we(1), dw(1), ys(1), h(6), one(1)
      real(wp), allocatable :: hist(:, :, :)
      integer :: conn(4, ne), i, j, k, eb, em, ef
      type(j2_param_t) :: prm
      type(q4_solid_t) :: o
      real(wp), parameter :: e1 = 0.02_wp, e3 = -0.03_wp
      logical :: distort

      distort = nq == 2
      do j = 0, n
         do i = 0, n
            k = 1 + j*(n + 1) + i
            x0(:, k) = [1.0_wp + real(i, wp)/n, real(j, wp)/n]
            if (distort .and. i > 0 .and. i < n .and. j > 0 .and. j < n) &
               x0(:, k) = x0(:, k) + 0.08_wp*[real(2*i - 3, wp), real(3 - 2*j, wp) + 0.5_wp*i]
         end do
      end do
      if (.not. distort) then
         ! graded rectangles
         do k = 1, nn
            x0(1, k) = 1.0_wp + (x0(1, k) - 1.0_wp)**1.5_wp
         end do
      end if
      do j = 1, n
         do i = 1, n
            k = 1 + (j - 1)*(n + 1) + (i - 1)
            conn(:, i + (j - 1)*n) = [k, k + 1, k + n + 2, k + n + 1]
         end do
      end do
      u(1, :) = e1*x0(1, :)
      u(2, :) = e3*x0(2, :)
      call lame_from_young(200.0_wp, 0.3_wp, lam, mu)
      prm%law = J2_MISES
      prm%y0 = 0.5_wp
      prm%yinf = 0.5_wp
      prm%hiso = 5.0_wp
      o = q4g_init(nq, axi, mixed, law_make(merge(LAW_J2, LAW_NEOHOOKEAN, plastic), lam, mu, 1.0_wp, prm), 0.1_wp)
      if (plastic) then
         allocate (hist(o%nhist, nq*nq, ne))
         call q4g_hist_init(o, ne, hist)
      else
         allocate (hist(1, 1, 1), source=0.0_wp)
      end if
      f = 0.0_wp
      call q4g_force(o, ne, nn, conn, x0, u, 1.0_wp, hist, f, w, whg, wd, jm, eb, d2, em, ef)
      ! the law at the uniform F
      h = [1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp]
      one = 1.0_wp
      call j2_piola(1, lam, mu, o%law%j2, 1.0_wp, [1.0_wp + e1], [0.0_wp], [0.0_wp], [1.0_wp + e3], &
                    [merge(1.0_wp + e1, 1.0_wp, axi)], [(1.0_wp + e1)*(1.0_wp + e3)], one, h(1:1), &
                    h(2:2), h(3:3), h(4:4), h(5:5), h(6:6), p(1:1), p(2:2), p(3:3), p(4:4), p(5:5), &
                    we, dw, ys)
      scale = abs(p(4))
      w = 0.0_wp
      do j = 1, n - 1
         do i = 1, n - 1
            k = 1 + j*(n + 1) + i
            w = max(w, maxval(abs(f(:, k))))
         end do
      end do
      call check(s, w <= 1.0e-13_wp*scale .and. eb == 0, what//': no force on the interior nodes ('// &
                 rtoa(w/scale)//' of P22)')
      ftop = sum(f(2, nn - n:nn))
      if (axi) then
         want = p(4)*(2.0_wp**2 - 1.0_wp)/2.0_wp
      else
         want = p(4)
      end if
      call check_close(s, ftop, want, 1.0e-12_wp*abs(want), what//': top resultant')
      if (plastic) then
         call check(s, all(hist(5, :, :) > 0.0_wp) .and. maxval(hist(5, :, :)) - minval(hist(5, :, :)) &
                    <= 1.0e-14_wp*maxval(hist(5, :, :)) .and. wd > 0.0_wp, &
                    what//': every point yields the same, dissipation > 0')
      end if
   end subroutine patch

   !> The reader: a plastic axisymmetric deck is read; bad plastic and axisymmetric input is an
   !> error naming file:line.
   subroutine reader_errors(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg
      type(model_t) :: m
      integer :: stage
      call run_deck('axi_ok', deck('    PLAStic MISEs 400 500 10'//nl//'    PLAStic HARDening 100 0'// &
                                   nl//'    SPECific heat 385'//nl, '  AXISymmetric', '0'), stage, msg, m)
      call check(s, stage == 0, 'PLAStic MISEs, HARDening, SPECific heat and AXISymmetric read', msg)
      if (stage == 0) then
         call check(s, m%mesh%axisymmetric .and. m%materials(1)%plastic .and. &
                    m%materials(1)%j2%yinf == 500.0_wp .and. m%materials(1)%j2%hiso == 100.0_wp .and. &
                    m%materials(1)%j2%cheat == 385.0_wp, 'the values reach the model')
         call check(s, all(m%mesh%bc(1, [1, 4, 7]) /= 0), 'nodes on the axis keep r = 0 (u_r prescribed)')
      end if
      call bad(deck('    PLAStic MISEs -400'//nl, '  PLANe STRAin', '0'), 'axi_bad1.inp:7:', &
               'Y0 must be positive', 'negative yield stress')
      call bad(deck('    PLAStic MISEs 400 300 10'//nl, '  PLANe STRAin', '0'), 'axi_bad2.inp:7:', &
               'below the initial yield', 'Y0 > Yinf with beta > 0')
      call bad(deck('    PLAStic HARDening 100 50'//nl//'    PLAStic MISEs 400'//nl, '  PLANe STRAin', &
                    '0'), 'axi_bad3.inp:7:', 'kinematic hardening', 'Hkin /= 0')
      call bad(deck('    PLAStic POWEr 400 100 0.3'//nl, '  AXISymmetric', '-0.5'), 'axi_bad4.inp:', &
               'r = x = -0.5', 'a node at r < 0')
      call bad(deck('    SPECific heat 385'//nl, '  PLANe STRAin', '0'), 'axi_bad6.inp:7:', &
               'SPECific heat without a PLAStic law', 'specific heat without plasticity')
      call bad(deck('    PLAStic JOHNson-cook 400 100 0.3 0.01 1 1300 300 1'//nl, '  PLANe STRAin', &
                    '0', rigid=.true.), 'axi_bad5.inp:6:', 'PLAStic on a RIGId body', &
               'plasticity on a rigid body')
   contains
      function deck(plas, geom, x0, rigid) result(t)
         character(len=*), intent(in) :: plas, geom, x0
         logical, intent(in), optional :: rigid
         character(len=:), allocatable :: t, mat
         if (present(rigid)) then
            mat = '  RIGId'//nl//'    DENSity 1'//nl
         else
            mat = '  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl
         end if
         t = 'FEAP * * axi'//nl//'  0 0 0 2 2 4'//nl//'MATErial,1'//nl//mat//plas//nl//'GLOBal'//nl// &
             geom//nl//nl//'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,1,1,1'//nl//'    1,'//x0// &
             ',0'//nl//'    2,1,0'//nl//'    3,1,1'//nl//'    4,'//x0//',1'//nl//nl//'END'//nl// &
             'BATCh'//nl//'END'//nl//'STOP'
      end function deck
      subroutine bad(text, where, what, name)
         character(len=*), intent(in) :: text, where, what, name
         character(len=:), allocatable :: msg
         integer :: stage
         call run_deck(where(:index(where, '.') - 1), text, stage, msg)
         call check(s, stage == 1 .and. index(msg, where) > 0 .and. index(msg, what) > 0, &
                    name//' refused with file:line', msg)
      end subroutine bad
   end subroutine reader_errors

   !> Gravity and an edge pressure on an axisymmetric block r in [1, 3], z in [0, 1] (rho = 2,
   !> g = 10 downward; on the top edge p = r, linear from 1 to 3): the external forces per
   !> radian sum to -rho g int r dA = -80 (A5) and -int p r dr = -26/3 (A6, exact for a
   !> linear p), to round-off.
   subroutine ring_loads(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: text
      real(wp) :: fy, fx
      text = 'FEAP * * loads'//nl//'  0 0 0 2 2 4'//nl//'MATErial,1'//nl//'  SOLId'//nl// &
             '    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 2'//nl//nl//'GLOBal'//nl// &
             '  AXISymmetric'//nl//nl//'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,4,1,1,1,1'//nl// &
             '    1,1,0'//nl//'    2,3,0'//nl//'    3,3,1'//nl//'    4,1,1'//nl//nl//'GRAVity,0,-10'// &
             nl//'CSURface'//nl//'  NORMal'//nl//'  LINEar'//nl//'    1,1,1,1'//nl//'    2,3,1,3'//nl// &
             nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('axi_loads', text, model, stp, err)
      if (.not. allocated(err)) call stp%start(err)
      call check(s, .not. allocated(err), 'axisymmetric loads set up')
      if (allocated(err)) return
      fy = sum(stp%st%fext(2, :))
      fx = sum(stp%st%fext(1, :))
      call check_close(s, fy, -80.0_wp - 26.0_wp/3.0_wp, 1.0e-12_wp, 'gravity and pressure per radian')
      call check_close(s, fx, 0.0_wp, 1.0e-12_wp, 'no radial resultant from a pressure on a z = const edge')
   end subroutine ring_loads

   !> A thin ring (radius 10, square section 0.1 x 0.1, one element, free) given a uniform
   !> radial velocity breathes at omega = sqrt(E/rho)/R (nu = 0: the hoop stress alone; the
   !> section's finite size changes omega by order (0.1/10)^2). The period from the zero
   !> crossings of u_r over three periods, within 0.5 %.
   subroutine ring(s, nq)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      character(len=:), allocatable :: msg, text
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      real(wp) :: tz(8), period, exact
      integer :: stage, i, nz, iu
      character(len=1) :: q
      write (q, '(i1)') nq
      text = 'FEAP * * ring'//nl//'  0 0 0 2 2 4'//nl//'MATErial,1'//nl//'  SOLId'//nl// &
             '    ELAStic NEOHookean 1000 0'//nl//'    DENSity 1'//nl//'    QUADrature '//q//nl// &
             nl//'GLOBal'//nl//'  AXISymmetric'//nl//nl//'REGIon,1'//nl//'BLOCk'//nl// &
             '  CARTesian,1,1,1,1,1'//nl//'    1,9.95,0'//nl//'    2,10.05,0'//nl// &
             '    3,10.05,0.1'//nl//'    4,9.95,0.1'//nl//nl//'INITial,VELOcity'//nl// &
             '  REGIon,1,1e-3,0'//nl//nl//'END'//nl//'BATCh'//nl//'  TPLOt,,1'//nl// &
             '  LOOP,,10000000'//nl//'    TIME,,7.5'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
             'END'//nl//'  disp,1,1'//nl//'  disp,2,1'//nl//nl//'STOP'
      call run_deck('ring'//q, text, stage, msg)
      call check(s, stage == 0, 'ring deck runs (quadrature '//q//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/ring'//q//'.his', names, d)
      iu = column(names, 'disp(n1,1)')
      if (iu == 0) iu = 2
      nz = 0
      do i = 2, size(d, 2)
         if (nz < size(tz) .and. d(iu, i - 1)*d(iu, i) < 0.0_wp) then
            nz = nz + 1
            tz(nz) = d(1, i - 1) - d(iu, i - 1)*(d(1, i) - d(1, i - 1))/(d(iu, i) - d(iu, i - 1))
         end if
      end do
      exact = 2.0_wp*acos(-1.0_wp)*10.0_wp/sqrt(1000.0_wp)
      call check(s, nz >= 7, 'the ring oscillates (quadrature '//q//')')
      if (nz < 7) return
      period = (tz(7) - tz(1))/3.0_wp
      call check_close(s, period/exact, 1.0_wp, 5.0e-3_wp, 'breathing period / 2 pi R/sqrt(E/rho), '// &
                       'quadrature '//q)
   end subroutine ring

   !> Run a deck of inputs/verify into run_dir; ok when it ran.
   subroutine run_verify_deck(name, ok, msg)
      character(len=*), intent(in) :: name
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: msg
      type(model_t) :: m
      type(run_options_t) :: opts
      type(error_t), allocatable :: err
      ok = .false.
      msg = ''
      call read_deck('inputs/verify/'//name//'.inp', m, err)
      if (allocated(err)) then
         msg = err%message
         return
      end if
      call execute_command_line('mkdir -p '//run_dir)
      opts%base = run_dir//'/'//name
      opts%quiet = .true.
      call run_model(m, opts, err)
      if (allocated(err)) then
         msg = err%message
         return
      end if
      ok = .true.
   end subroutine run_verify_deck

   !> Mean of column c of the rows with t >= t0.
   real(wp) function tail_mean(d, c, t0) result(v)
      real(wp), intent(in) :: d(:, :), t0
      integer, intent(in) :: c
      v = sum(d(c, :), mask=d(1, :) >= t0)/max(1, count(d(1, :) >= t0))
   end function tail_mean

   !> inputs/verify/cylinder_elastic.inp against Lame: u_r at r = b within 1 % (mean over the
   !> last third of the run).
   subroutine cylinder(s)
      type(suite_t), intent(inout) :: s
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      character(len=:), allocatable :: msg
      real(wp) :: nu, e, p, a, b, ub
      logical :: ok
      a = 1.0_wp
      b = 2.0_wp
      call run_verify_deck('cylinder_elastic', ok, msg)
      call check(s, ok, 'elastic cylinder runs', msg)
      if (ok) then
         call read_table(run_dir//'/cylinder_elastic.his', names, d)
         nu = 0.3_wp
         e = 2.0_wp*(1.0_wp + nu)
         p = 5.0e-4_wp
         ub = (1.0_wp + nu)/e*p*a*a/(b*b - a*a)*((1.0_wp - 2.0_wp*nu)*b + b*b/b)
         call check_close(s, tail_mean(d, 2, 150.0_wp)/ub, 1.0_wp, 1.0e-2_wp, 'elastic: u(b) / Lame')
      end if
      ! the elastic-plastic cylinder (110 000 steps) runs in make verify (doc/verification.md)
   end subroutine cylinder

   !> inputs/verify/taylor_5x50.inp: kinetic + strain + plastic work + contact work is the
   !> initial kinetic energy within 1 % at every row of <stem>.ene, the rod shortens and
   !> spreads, and the stable step is the elements' at every step (contact never cuts it:
   !> dt(n+1) = 0.9 x the elements' estimate, which the .ene's dt column shows as smooth).
   subroutine taylor(s)
      type(suite_t), intent(inout) :: s
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      character(len=:), allocatable :: msg
      real(wp) :: e0, worst, bal
      integer :: i, ik, is, ic, ipl
      logical :: ok
      call run_verify_deck('taylor_5x50', ok, msg)
      call check(s, ok, 'Taylor bar 5 x 50 runs', msg)
      if (.not. ok) return
      call read_table(run_dir//'/taylor_5x50.ene', en, e)
      call read_table(run_dir//'/taylor_5x50.his', names, d)
      ik = column(en, 'kinetic')
      is = column(en, 'strain')
      ic = column(en, 'contact_work')
      ipl = column(en, 'plastic_work')
      e0 = e(ik, 1)
      worst = 0.0_wp
      do i = 1, size(e, 2)
         bal = e(ik, i) + e(is, i) + e(ipl, i) - e(ic, i)
         worst = max(worst, abs(bal - e0)/e0)
      end do
      call check(s, worst <= 1.0e-2_wp, 'energy balance within 1 % of the initial kinetic energy ('// &
                 rtoa(worst)//')')
      call check(s, e(ipl, size(e, 2)) > 0.8_wp*e0, 'most of the energy is dissipated plastically')
      call check(s, d(2, size(d, 2)) < -8.0e-3_wp .and. d(3, size(d, 2)) > 2.5e-3_wp, &
                 'the rod shortens by more than 8 mm and its foot spreads by more than 2.5 mm')
   end subroutine taylor

end module test_axisymmetric
