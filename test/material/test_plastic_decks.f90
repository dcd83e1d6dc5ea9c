!> The [ext] hardening laws through element decks (doc/plasticity.md, section 6.6): one element
!> whose every node follows a prescribed motion (DISPlacement with FPROportional, doc/loads.md
!> section 3) along simple shear (plane strain) or isochoric extension (axisymmetric), both
!> quadratures, `PLAStic POWEr` and `PLAStic JOHNson-cook` with and without `SPECific heat`.
!> The deck's history (TPLOt stre 6..10, the nodal displacements) is compared with the closed
!> forms of the laws (J15), (J16), (J17) and with the quad-precision discrete map of
!> test_plasticity_ref driven by the same deformation gradients.
module test_plastic_decks
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa
   use exic_material_material, only: lame_from_young
   use exic_material_j2_hardening, only: j2_param_t, J2_POWER, J2_JOHNSON_COOK
   use test_plasticity_ref, only: ref_t, ref_step
   use testing, only: suite_t, check, section
   use deck_runner, only: run_dir, run_deck, read_table, column
   implicit none
   private

   public :: run_plastic_decks_tests

   character(len=*), parameter :: nl = new_line('a')
   !> Copper (the Taylor bar's elasticity) and the OFHC copper constants of Johnson & Cook (1983).
   real(wp), parameter :: E_CU = 117.0e9_wp, NU_CU = 0.35_wp, RHO_CU = 8930.0_wp
   real(wp), parameter :: JA = 90.0e6_wp, JB = 292.0e6_wp, JN = 0.31_wp, JC_C = 0.025_wp, &
                          JM = 1.09_wp, TMELT = 1356.0_wp, TROOM = 293.0_wp, EDOT0 = 1.0_wp, &
                          CHEAT = 383.0_wp
   !> The driven paths: nsteps fixed steps of dt to tend; simple shear at gdot to gamma = 1,
   !> extension to the axial stretch 2.
   integer, parameter :: NSTEPS = 400
   real(wp), parameter :: TEND = 1.0e-3_wp, DT = TEND/NSTEPS, GDOT = 1.0_wp/TEND
   !> What a test deck holds: the law and the element.
   integer, parameter :: LAW_POWER = 1, LAW_JC = 2, LAW_JC_HEAT = 3
   integer, parameter :: SHEAR = 1, EXTENSION = 2

   !> One run's history, per row: time, gamma or the two stretches, sigma_vm, J, ep, T, Y.
   type :: run_t
      logical :: ok = .false.
      real(wp), allocatable :: t(:), f(:, :), svm(:), jac(:), ep(:), temp(:), ys(:)
      real(wp) :: wp_end = 0.0_wp   !< plastic work at the end (.ene, per unit thickness/radian)
      !> the work done on the material at the end, strain energy + plastic work (.ene)
      real(wp) :: wmat = 0.0_wp
      real(wp) :: drift = huge(1.0_wp)  !< max |total(t) - total(0)| / wmat (.ene)
      real(wp) :: wp_min = 0.0_wp   !< the smallest increment of the plastic work over a row
   end type run_t

contains

   subroutine run_plastic_decks_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'plastic decks: POWEr along driven paths, against (J15)')
      call power_law(s, SHEAR, 2, .true., 'simple shear, 2x2 MIXEd')
      call power_law(s, SHEAR, 1, .false., 'simple shear, one point')
      call power_law(s, EXTENSION, 2, .true., 'axisymmetric extension, 2x2 MIXEd')
      call power_law(s, EXTENSION, 1, .false., 'axisymmetric extension, one point')
      call section(s, 'plastic decks: JOHNson-cook rate factor at a constant strain rate (J16)')
      call jc_rate(s, 2, .true., '2x2 MIXEd')
      call jc_rate(s, 1, .false., 'one point')
      call section(s, 'plastic decks: JOHNson-cook with adiabatic heating (J16), (J17)')
      call jc_heat(s, SHEAR, 2, .true., 'simple shear, 2x2 MIXEd')
      call jc_heat(s, EXTENSION, 1, .false., 'axisymmetric extension, one point')
   end subroutine run_plastic_decks_tests

   ! ---------------------------------------------------------------- decks

   !> The parameters of a law as the deck gives them (and the reference uses).
   function params(law) result(prm)
      integer, intent(in) :: law
      type(j2_param_t) :: prm
      prm%rho = RHO_CU
      prm%a = JA
      prm%b = JB
      prm%en = JN
      if (law == LAW_POWER) then
         prm%law = J2_POWER
         return
      end if
      prm%law = J2_JOHNSON_COOK
      prm%crate = JC_C
      prm%m = JM
      prm%tmelt = TMELT
      prm%troom = TROOM
      prm%epsdot0 = EDOT0
      if (law == LAW_JC_HEAT) prm%cheat = CHEAT
   end function params

   !> A one-element deck on the unit square, every dof prescribed. SHEAR (plane strain): the top
   !> nodes 3, 4 move by gamma = gdot t along x (function 1, type 1). EXTENSION (axisymmetric,
   !> x = r): the top nodes by lambda - 1 = t/tend along z (function 1), the outer nodes 2, 4 by
   !> lambda^(-1/2) - 1 along r, a table of points every tend/80 from t = -tend/80 (function 2;
   !> a table's slope at its first time would be 0, a velocity jump at t = 0): F = diag(s,
   !> lambda, s) within the chord error of the table, |J - 1| < 3e-5 (measured 2.8e-5).
   function deck(path, law, nq, mixed) result(t)
      integer, intent(in) :: path, law, nq
      logical, intent(in) :: mixed
      character(len=:), allocatable :: t, mat, geom, bc, batch, props
      integer :: k
      real(wp) :: tk
      mat = '  SOLId'//nl//'    ELAStic NEOHookean '//rtoa(E_CU)//' '//rtoa(NU_CU)//nl// &
            '    DENSity '//rtoa(RHO_CU)//nl
      if (law == LAW_POWER) then
         mat = mat//'    PLAStic POWEr '//rtoa(JA)//' '//rtoa(JB)//' '//rtoa(JN)//nl
      else
         mat = mat//'    PLAStic JOHNson-cook '//rtoa(JA)//' '//rtoa(JB)//' '//rtoa(JN)//' '// &
               rtoa(JC_C)//' '//rtoa(JM)//' '//rtoa(TMELT)//' '//rtoa(TROOM)//' '//rtoa(EDOT0)//nl
         if (law == LAW_JC_HEAT) mat = mat//'    SPECific heat '//rtoa(CHEAT)//nl
      end if
      mat = mat//'    QUADrature '//achar(iachar('0') + nq)//nl
      if (mixed) mat = mat//'    MIXEd'//nl
      bc = 'BOUNdary'//nl//'  1,0,1,1'//nl//'  2,0,1,1'//nl//'  3,0,1,1'//nl//'  4,0,1,1'//nl//nl
      props = '1, 0, 0, 1, 0, '//rtoa(GDOT)//', 0, 0'//nl//nl
      if (path == SHEAR) then
         geom = 'GLOBal'//nl//'  PLANe STRAin'//nl//nl
         bc = bc//'DISPlacement'//nl//'  3,0,1,0'//nl//'  4,0,1,0'//nl//nl// &
              'FPROportional'//nl//'  3,0,1,1'//nl//'  4,0,1,1'//nl//nl
         batch = '  PROPortional,,1'//nl
      else
         geom = 'GLOBal'//nl//'  AXISymmetric'//nl//nl
         bc = bc//'DISPlacement'//nl//'  2,0,1,0'//nl//'  3,0,0,1'//nl//'  4,0,1,1'//nl//nl// &
              'FPROportional'//nl//'  2,0,2,1'//nl//'  3,0,2,1'//nl//'  4,0,2,1'//nl//nl
         batch = '  PROPortional,,1,2'//nl
         props = props//'2, 0'//nl
         do k = -1, 80
            tk = TEND*real(k, wp)/80.0_wp
            props = props//rtoa(tk)//', '//rtoa(1.0_wp/sqrt(1.0_wp + tk/TEND) - 1.0_wp)//nl
         end do
         props = props//nl
      end if
      t = 'FEAP * * plastic deck'//nl//'  0 0 0 2 2 4'//nl//'MATErial,1'//nl//mat//nl//geom// &
          'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,1,1,1,1,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl// &
          '    3,1,1'//nl//'    4,0,1'//nl//nl//bc//'END'//nl//'BATCh'//nl//batch// &
          '  DT,,'//rtoa(DT)//nl//'  TPLOt,,1'//nl//'  LOOP,,'//'1000'//nl//'    TIME,,'//rtoa(TEND)// &
          nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//props//'  disp,4,1'//nl// &
          '  disp,4,2'//nl//'  stre,1,6'//nl//'  stre,1,7'//nl//'  stre,1,8'//nl//'  stre,1,9'//nl// &
          '  stre,1,10'//nl//nl//'STOP'
   end function deck

   !> Run a deck and read its history: F of every row from the displacements of node 4 (at
   !> X = (1, 1): SHEAR, F12 = u_x; EXTENSION, F11 = F33 = 1 + u_r, F22 = 1 + u_z).
   function run(name, path, law, nq, mixed) result(r)
      character(len=*), intent(in) :: name
      integer, intent(in) :: path, law, nq
      logical, intent(in) :: mixed
      type(run_t) :: r
      character(len=:), allocatable :: msg
      character(len=64), allocatable :: names(:), en(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage, n, i, k, itot, istr
      call run_deck(name, deck(path, law, nq, mixed), stage, msg)
      if (stage /= 0) then
         print '(a)', '   deck '//name//' failed: '//msg
         return
      end if
      call read_table(run_dir//'/'//name//'.his', names, d)
      call read_table(run_dir//'/'//name//'.ene', en, e)
      n = size(d, 2)
      allocate (r%f(5, n))
      r%t = d(1, :)
      do i = 1, n
         if (path == SHEAR) then
            r%f(:, i) = [1.0_wp, d(2, i), 0.0_wp, 1.0_wp, 1.0_wp]
         else
            r%f(:, i) = [1.0_wp + d(2, i), 0.0_wp, 0.0_wp, 1.0_wp + d(3, i), 1.0_wp + d(2, i)]
         end if
      end do
      r%svm = d(4, :)
      r%jac = d(5, :)
      r%ep = d(6, :)
      r%temp = d(7, :)
      r%ys = d(8, :)
      k = 0
      do i = 1, size(en)
         if (trim(en(i)) == 'plastic_work') k = i
      end do
      if (k > 0) r%wp_end = e(k, size(e, 2))
      if (k > 0) r%wp_min = minval(e(k, 2:) - e(k, :size(e, 2) - 1))
      itot = column(en, 'total')
      istr = column(en, 'strain')
      r%wmat = e(istr, size(e, 2)) + r%wp_end
      if (r%wmat > 0.0_wp) r%drift = maxval(abs(e(itot, :) - e(itot, 1)))/r%wmat
      r%ok = n == NSTEPS + 1 .and. k > 0 .and. abs(r%t(n) - TEND) <= 1.0e-12_wp*TEND
      if (.not. r%ok) print '(a)', '   deck '//name//': '//rtoa(real(n, wp))//' rows'
   end function run

   !> The quad-precision discrete map (test_plasticity_ref) driven by the run's F and steps:
   !> the largest relative difference of ep, q = J sigma_vm and T over the rows. This is the
   !> element path against an independent implementation of the kernel's algorithm.
   real(wp) function against_reference(r, law) result(err)
      type(run_t), intent(in) :: r
      integer, intent(in) :: law
      type(j2_param_t) :: prm
      type(ref_t) :: pt
      real(wp) :: lam, mu, q, epo
      integer :: i
      prm = params(law)
      call lame_from_young(E_CU, NU_CU, lam, mu)
      pt%temp = TROOM
      err = 0.0_wp
      do i = 2, size(r%t)
         epo = real(pt%ep, wp)
         call ref_step(lam, mu, prm, r%t(i) - r%t(i - 1), r%f(:, i), pt)
         err = max(err, abs(r%ep(i) - real(pt%ep, wp))/max(real(pt%ep, wp), 1.0e-3_wp))
         q = r%svm(i)*r%jac(i)
         if (real(pt%ep, wp) > epo) err = max(err, abs(q - real(pt%ys, wp))/JA)
         if (law == LAW_JC_HEAT) err = max(err, abs(r%temp(i) - real(pt%temp, wp))/TROOM)
      end do
   end function against_reference

   !> Y(ep) = A + B ep^n (J15).
   elemental real(wp) function power_y(ep)
      real(wp), intent(in) :: ep
      power_y = JA + JB*ep**JN
   end function power_y

   !> Thermal factor 1 - T*^m of (J16).
   elemental real(wp) function thermal(temp)
      real(wp), intent(in) :: temp
      thermal = 1.0_wp - min(max((temp - TROOM)/(TMELT - TROOM), 0.0_wp), 1.0_wp)**JM
   end function thermal

   ! ---------------------------------------------------------------- tests

   !> The energy balance of a run (doc/plasticity.md, section 5.5): every node of the element is
   !> driven, so kinetic + strain + plastic work - W_pm (`total` of <stem>.ene) is constant to
   !> the trapezoid rule's error on the elastic steps before first yield; the plastic work of
   !> (J31) takes the rest. Asserted: the largest |total(t) - total(0)| within 1e-9 of the work
   !> done on the material (strain energy + plastic work at the end; W_pm also holds the driven
   !> nodes' kinetic energy, which falls in the extension), and no step books a negative
   !> plastic work.
   subroutine balance(s, r, what)
      type(suite_t), intent(inout) :: s
      type(run_t), intent(in) :: r
      character(len=*), intent(in) :: what
      call check(s, r%wmat > 0.0_wp .and. r%drift <= 1.0e-9_wp .and. r%wp_min >= 0.0_wp, what// &
                 ': the energy balance closes (kinetic + strain + plastic work - W_pm within 1e-9 of '// &
                 'the work on the material; plastic work never decreasing)', 'strain + plastic work '// &
                 rtoa(r%wmat)//', largest drift '// &
                 rtoa(r%drift)//', smallest step of the plastic work '//rtoa(r%wp_min))
   end subroutine balance

   !> POWEr: at every plastic row the Kirchhoff von Mises stress J sigma_vm and the output yield
   !> stress (component 10) equal A + B ep^n of the row's ep, to 1e-12 of A (the return solves
   !> (J21) to round-off, section 5.2; the output is printed with 17 digits); the run follows the
   !> discrete map to 1e-10.
   subroutine power_law(s, path, nq, mixed, what)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: path, nq
      logical, intent(in) :: mixed
      character(len=*), intent(in) :: what
      type(run_t) :: r
      real(wp) :: eq, ey, eref
      integer :: i, npl
      character(len=16) :: name
      write (name, '(a,i0,i0)') 'pdeck_pow', path, nq
      r = run(trim(name), path, LAW_POWER, nq, mixed)
      call check(s, r%ok, 'POWEr deck runs ('//what//')')
      if (.not. r%ok) return
      call balance(s, r, 'POWEr '//what)
      eq = 0.0_wp
      ey = 0.0_wp
      npl = 0
      do i = 2, size(r%t)
         if (r%ep(i) <= r%ep(i - 1)) cycle
         npl = npl + 1
         eq = max(eq, abs(r%svm(i)*r%jac(i) - power_y(r%ep(i)))/JA)
         ey = max(ey, abs(r%ys(i) - power_y(r%ep(i)))/JA)
      end do
      call check(s, npl >= NSTEPS - 10 .and. r%ep(size(r%t)) > 0.3_wp, 'POWEr '//what// &
                 ': yields from the first steps on ('//rtoa(real(npl, wp))//' plastic steps, ep = '// &
                 rtoa(r%ep(size(r%t)))//')')
      call check(s, eq <= 1.0e-12_wp .and. ey <= 1.0e-12_wp, 'POWEr '//what// &
                 ': J sigma_vm and Y output = A + B ep^n at every plastic step', &
                 'largest differences '//rtoa(eq)//', '//rtoa(ey)//' of A')
      eref = against_reference(r, LAW_POWER)
      call check(s, eref <= 1.0e-10_wp, 'POWEr '//what//': ep and q = the discrete map (quad '// &
                 'precision) along the driven F to 1e-10', 'largest difference '//rtoa(eref))
   end subroutine power_law

   !> JOHNson-cook without heating, simple shear at gammadot = 1000/s: the equivalent strain rate
   !> sqrt(2/3 D:D) = gammadot/sqrt(3) is constant, and in plastic flow the plastic part of it
   !> is epdot = gammadot/(sqrt(3) (1 + H/(3 mu))), the elastic part taking qdot/(3 mu) with
   !> H = dY/dep = (1 + C ln(...)) n B ep^(n-1) the slope at the fixed rate. The rate factor
   !> q/Y_static is then 1 + C ln(epdot/epsdot0): checked to 2e-6 past ep = 0.05 (measured
   !> 1.4e-6: the discrete rate dep/dt of a step lags the rate at its end by half a step, which
   !> with d(epdot)/dt here is 4e-5 of epdot, times C). Without the elastic part (H = 0) the
   !> factor would be off by C H/(3 mu) = 1.5e-4 at ep = 0.05. At every step the factor equals
   !> 1 + C ln(dep/dt/epsdot0) of the step's own rate to 1e-12, and T stays Troom.
   subroutine jc_rate(s, nq, mixed, what)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      logical, intent(in) :: mixed
      character(len=*), intent(in) :: what
      type(run_t) :: r
      real(wp) :: fac, est, ess, eref, rate, h, ex, lam, mu
      integer :: i, nss
      character(len=16) :: name
      call lame_from_young(E_CU, NU_CU, lam, mu)
      write (name, '(a,i0)') 'pdeck_jcr', nq
      r = run(trim(name), SHEAR, LAW_JC, nq, mixed)
      call check(s, r%ok, 'JOHNson-cook deck runs ('//what//')')
      if (.not. r%ok) return
      call balance(s, r, 'JOHNson-cook '//what)
      fac = 1.0_wp + JC_C*log(GDOT/(sqrt(3.0_wp)*EDOT0))
      est = 0.0_wp
      ess = 0.0_wp
      nss = 0
      do i = 2, size(r%t)
         if (r%ep(i) <= r%ep(i - 1)) cycle
         rate = (r%ep(i) - r%ep(i - 1))/(r%t(i) - r%t(i - 1))
         est = max(est, abs(r%svm(i)*r%jac(i)/r%ys(i) - (1.0_wp + JC_C*log(max(rate/EDOT0, 1.0_wp))))/fac, &
                   abs(r%ys(i) - power_y(r%ep(i)))/JA)
         if (r%ep(i - 1) >= 0.05_wp) then
            nss = nss + 1
            h = fac*JN*JB*r%ep(i)**(JN - 1.0_wp)
            ex = 1.0_wp + JC_C*log(GDOT/(sqrt(3.0_wp)*(1.0_wp + h/(3.0_wp*mu))*EDOT0))
            ess = max(ess, abs(r%svm(i)*r%jac(i)/r%ys(i) - ex)/ex)
         end if
      end do
      call check(s, est <= 1.0e-12_wp .and. all(r%temp == TROOM), 'JOHNson '//what// &
                 ': q = (A + B ep^n)(1 + C ln(dep/dt/epsdot0)) at every step, T = Troom', &
                 'largest difference '//rtoa(est))
      call check(s, nss > NSTEPS/2 .and. ess <= 2.0e-6_wp, 'JOHNson '//what// &
                 ': rate factor = 1 + C ln(gammadot/(sqrt 3 (1 + H/(3 mu)) epsdot0)) past ep = 0.05 ('// &
                 rtoa(real(nss, wp))//' steps, largest relative difference '//rtoa(ess)//')')
      eref = against_reference(r, LAW_JC)
      call check(s, eref <= 1.0e-10_wp, 'JOHNson '//what//': ep and q = the discrete map along '// &
                 'the driven F to 1e-10', 'largest difference '//rtoa(eref))
   end subroutine jc_rate

   !> JOHNson-cook with SPECific heat: (J17) heats with the kernel's dissipation (J27), the
   !> balance books the trapezoid rule (J31) (doc/plasticity.md, section 5.5): T - Troom against
   !> 0.9 W_p/(rho c V0), W_p the plastic work of the .ene (the element is homogeneous; V0 = 1 per
   !> unit thickness, 1/2 per radian for the unit square at r in [0, 1]), within the first-order
   !> difference of the two rules, 0.9 max(dep) sum |dq| /(rho c) (for small elastic strains
   !> (J27) - (J31) = 1/2 sum dq dep, (J32)). The rise against 0.9 int q dep/(rho c) by
   !> the backward-Euler sum over the steps, sum q(n+1) dep (the return's Y dep): the dissipation
   !> (J27) is Y dep 3x (x J2 - 3/2 k J3)/(J2 (3 x^2 - k^2 J2)) for the returned deviator k d,
   !> which in axisymmetric extension (d = c diag(-1, 2, -1), c = q/(3 mu x)) is Y dep/(1 + c):
   !> with that factor to 1e-6; in simple shear J3 is small and the factor is 1 to 1e-4 (measured
   !> 3.4e-8 and 1.8e-5; the trapezoid rule would differ from the backward-Euler sum by
   !> 1/2 sum dq dep, 1e-3 here, an error of first order in the step). The yield stress at every
   !> step with the thermal factor of the temperature at the start of the step (section 4.1), to
   !> 1e-12; the thermal softening is more than 3 % at the end.
   subroutine jc_heat(s, path, nq, mixed, what)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: path, nq
      logical, intent(in) :: mixed
      character(len=*), intent(in) :: what
      type(run_t) :: r
      real(wp) :: v0, rise, wq, est, eref, rate, y, soft, lam, mu, q, tol, tv, depm, dheat, bound
      integer :: i, n
      character(len=16) :: name
      write (name, '(a,i0,i0)') 'pdeck_jch', path, nq
      r = run(trim(name), path, LAW_JC_HEAT, nq, mixed)
      call check(s, r%ok, 'JOHNson-cook deck with SPECific heat runs ('//what//')')
      if (.not. r%ok) return
      call balance(s, r, 'JOHNson-cook with SPECific heat, '//what)
      n = size(r%t)
      v0 = merge(1.0_wp, 0.5_wp, path == SHEAR)
      rise = r%temp(n) - TROOM
      ! the heating's (J27) against the balance's (J31): first order in the step, within
      ! 0.9/(rho c) max(dep) sum |dq| (1/2 sum dq dep for small elastic strains, doubled)
      tv = 0.0_wp
      depm = 0.0_wp
      do i = 2, n
         tv = tv + abs(r%svm(i)*r%jac(i) - r%svm(i - 1)*r%jac(i - 1))
         depm = max(depm, r%ep(i) - r%ep(i - 1))
      end do
      dheat = rise - 0.9_wp*r%wp_end/(RHO_CU*CHEAT*v0)
      bound = 0.9_wp*depm*tv/(RHO_CU*CHEAT)
      call check(s, abs(dheat) <= bound, 'JOHNson '//what//': T - Troom = 0.9 W_p/(rho c V0) '// &
                 'to the first-order difference of (J27) and (J31), 0.9 max(dep) sum |dq|/(rho c) (rise '// &
                 rtoa(rise)//' K, difference '//rtoa(dheat)//' K, bound '//rtoa(bound)//' K)', &
                 'W_p '//rtoa(r%wp_end))
      call lame_from_young(E_CU, NU_CU, lam, mu)
      wq = 0.0_wp
      est = 0.0_wp
      do i = 2, n
         q = r%svm(i)*r%jac(i)
         if (path == SHEAR) then
            wq = wq + q*(r%ep(i) - r%ep(i - 1))
         else
            wq = wq + q*(r%ep(i) - r%ep(i - 1))/(1.0_wp + q/(3.0_wp*mu))
         end if
         if (r%ep(i) <= r%ep(i - 1)) cycle
         rate = (r%ep(i) - r%ep(i - 1))/(r%t(i) - r%t(i - 1))
         y = power_y(r%ep(i))*(1.0_wp + JC_C*log(max(rate/EDOT0, 1.0_wp)))*thermal(r%temp(i - 1))
         est = max(est, abs(q - y)/JA, &
                   abs(r%ys(i) - power_y(r%ep(i))*thermal(r%temp(i)))/JA)
      end do
      tol = merge(1.0e-4_wp, 1.0e-6_wp, path == SHEAR)
      call check(s, abs(rise - 0.9_wp*wq/(RHO_CU*CHEAT))/rise <= tol, 'JOHNson '//what// &
                 ': T - Troom = 0.9 int q dep/(rho c) to '//rtoa(tol)//' (relative difference '// &
                 rtoa(abs(rise - 0.9_wp*wq/(RHO_CU*CHEAT))/rise)//')')
      soft = 1.0_wp - thermal(r%temp(n))
      call check(s, est <= 1.0e-12_wp .and. soft > 0.03_wp, 'JOHNson '//what// &
                 ': q = (A + B ep^n)(1 + C ln rate)(1 - T*(n)^m) at every step, softening '// &
                 rtoa(soft), 'largest difference '//rtoa(est))
      eref = against_reference(r, LAW_JC_HEAT)
      call check(s, eref <= 1.0e-10_wp, 'JOHNson '//what//': ep, q and T = the discrete map '// &
                 'along the driven F to 1e-10', 'largest difference '//rtoa(eref))
   end subroutine jc_heat

end module test_plastic_decks
