!> The hypoelastic law of `ELAStic ISOTropic E nu` (doc/hypoelastic.md, section 6): one element
!> (2x2 and one point, the general path q4_general.f90 with its history) driven along uniaxial
!> strain and simple shear against the exact answers of the Jaumann rate (H10), (H11); a
!> prestressed point turned by a rigid rotation (the stress turns with it to round-off, the
!> energy stays); the plate-impact plateau against rho c_L v and the energy balance of a free
!> vibrating body, through decks.
module test_hypoelastic
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa
   use exic_material_material, only: lame_from_young
   use exic_material_law, only: law_t, law_make, law_init_history, law_piola_general, &
                                LAW_HYPOELASTIC, NVMAX
   use exic_element_q4_general, only: q4_solid_t, q4g_init, q4g_force, q4g_stress, q4g_hist_init, NSIG
   use testing, only: suite_t, check, section
   use deck_runner, only: run_dir, run_deck, read_table, column
   implicit none
   private

   public :: run_hypoelastic_tests

   character(len=*), parameter :: nl = new_line('a')
   real(wp), parameter :: E0 = 200.0_wp, NU0 = 0.3_wp

contains

   subroutine run_hypoelastic_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'hypoelastic: one element along driven paths (H10), (H11)')
      call driven(s, 2, .true.)
      call driven(s, 1, .true.)
      call driven(s, 2, .false.)
      call driven(s, 1, .false.)
      call section(s, 'hypoelastic: a prestressed point under a rigid rotation (H7), (H8)')
      call rotation(s)
      call section(s, 'hypoelastic: plate impact and a free vibrating body (decks)')
      call plate(s, 1, 0.9_wp, 0.3_wp)
      call plate(s, 2, 0.9_wp, 0.3_wp)
      call vibration(s, 2)
      call vibration(s, 1)
   end subroutine run_hypoelastic_tests

   !> One unit-square element, every node moved along uniaxial strain F = diag(1 + e, 1) to
   !> e = -0.05 (compression) or simple shear F = [1 g; 0 1] to g = 0.5, in n steps through
   !> q4g_force (which updates the history); the element stress of q4g_stress against (H10) or
   !> (H11). Uniaxial strain: the midpoint rule's sum to round-off, and ln within the sum's bound
   !> (2/3) sum u^3 (1.4e-9 of the stress here). Simple shear: first order in the step (doc/hypoelastic.md, section 2),
   !> so the error must halve with the step.
   subroutine driven(s, nq, uniaxial)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      logical, intent(in) :: uniaxial
      real(wp) :: lam, mu, err(2), sig(4), want(4), scale, sd, bound, ed, x0, x1
      character(len=:), allocatable :: what
      integer :: r, k
      call lame_from_young(E0, NU0, lam, mu)
      what = merge('uniaxial strain', 'simple shear   ', uniaxial)//merge(', 2x2      ', ', one point', nq == 2)
      do r = 1, 2
         call drive(nq, uniaxial, 200*r, sig)
         if (uniaxial) then
            want = [(lam + 2.0_wp*mu)*log(0.95_wp), lam*log(0.95_wp), lam*log(0.95_wp), 0.0_wp]
         else
            want = [mu*(1.0_wp - cos(0.5_wp)), -mu*(1.0_wp - cos(0.5_wp)), 0.0_wp, mu*sin(0.5_wp)]
         end if
         scale = maxval(abs(want))
         err(r) = maxval(abs(sig - want))/scale
      end do
      if (uniaxial) then
         ! the discrete answer: (lambda + 2 mu, lambda, lambda) sum 2 (x_k - x_(k-1))/(x_k + x_(k-1)),
         ! whose sum differs from ln x by sum 2 (u^3/3 + u^5/5 + ...), u = (x_k - x_(k-1))/(x_k + x_(k-1))
         sd = 0.0_wp
         bound = 0.0_wp
         do k = 1, 400
            x1 = 1.0_wp - 0.05_wp*real(k, wp)/400.0_wp
            x0 = 1.0_wp - 0.05_wp*real(k - 1, wp)/400.0_wp
            sd = sd + 2.0_wp*(x1 - x0)/(x1 + x0)
            bound = bound + (2.0_wp/3.0_wp)*abs((x1 - x0)/(x1 + x0))**3
         end do
         ed = maxval(abs(sig - [(lam + 2.0_wp*mu)*sd, lam*sd, lam*sd, 0.0_wp]))/scale
         bound = 1.01_wp*bound/abs(log(0.95_wp)) + 1.0e-13_wp
         call check(s, ed <= 1.0e-12_wp .and. err(2) <= bound, what// &
                    ': sxx, syy, szz = (lambda + 2 mu, lambda, lambda) ln(1 + e), to the midpoint rule''s sum', &
                    'relative error '//rtoa(err(2))//' (bound '//rtoa(bound)//'), to the discrete sum '//rtoa(ed))
      else
         call check(s, err(2) <= 2.0e-3_wp .and. err(1)/err(2) > 1.8_wp .and. err(1)/err(2) < 2.2_wp, &
                    what//': mu (1 - cos g, cos g - 1, 0, sin g), first order in the step', &
                    'relative error '//rtoa(err(1))//' (200 steps), '//rtoa(err(2))//' (400 steps)')
      end if
   end subroutine driven

   !> The element stress after n steps of the driven path (drive).
   subroutine drive(nq, uniaxial, n, sig)
      integer, intent(in) :: nq, n
      logical, intent(in) :: uniaxial
      real(wp), intent(out) :: sig(4)
      real(wp) :: x0(2, 4), u(2, 4), f(2, 4), lam, mu, w, whg, wd, jm, d2, sg(NSIG, 1), t
      real(wp), allocatable :: hist(:, :, :)
      integer :: conn(4, 1), k, eb, em, ef
      type(q4_solid_t) :: o
      call lame_from_young(E0, NU0, lam, mu)
      x0 = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp], [2, 4])
      conn(:, 1) = [1, 2, 3, 4]
      o = q4g_init(nq, .false., .false., law_make(LAW_HYPOELASTIC, lam, mu, 1.0_wp), 0.1_wp)
      allocate (hist(o%nhist, nq*nq, 1))
      call q4g_hist_init(o, 1, hist)
      do k = 1, n
         t = real(k, wp)/real(n, wp)
         u = 0.0_wp
         if (uniaxial) then
            u(1, :) = -0.05_wp*t*x0(1, :)
         else
            u(1, :) = 0.5_wp*t*x0(2, :)
         end if
         f = 0.0_wp
         call q4g_force(o, 1, 4, conn, x0, u, 1.0_wp, hist, f, w, whg, wd, jm, eb, d2, em, ef)
      end do
      call q4g_stress(o, 1, 4, conn, x0, u, hist, sg)
      sig = sg(1:4, 1)
   end subroutine drive

   !> A point prestressed by uniaxial strain F_s = diag(1.01, 0.995) in 10 steps, then turned by
   !> F = Q(theta) F_s, theta to 90 degrees in 45 steps: the stress is Q sigma_s Q^T and the
   !> energy W_s, to round-off (Hughes & Winget's update is exactly objective, (H7)).
   subroutine rotation(s)
      type(suite_t), intent(inout) :: s
      type(law_t) :: o
      real(wp) :: h(1, NVMAX), lam, mu, fs(2, 2), fk(2, 2), q(2, 2), ss(2, 2), sw(2, 2), ws, th, &
                  p(5), w(1), dw(1), ys(1), err, werr
      integer :: k
      real(wp), parameter :: PI = 3.14159265358979323846_wp
      call lame_from_young(E0, NU0, lam, mu)
      o = law_make(LAW_HYPOELASTIC, lam, mu, 1.0_wp)
      call law_init_history(o, 1, h)
      do k = 1, 10
         fs = reshape([1.0_wp + 0.001_wp*k, 0.0_wp, 0.0_wp, 1.0_wp - 0.0005_wp*k], [2, 2])
         call step(fs)
      end do
      ss = reshape([h(1, 6), h(1, 9), h(1, 9), h(1, 7)], [2, 2])
      ws = h(1, 10)
      err = 0.0_wp
      werr = 0.0_wp
      do k = 1, 45
         th = 0.5_wp*PI*real(k, wp)/45.0_wp
         q = reshape([cos(th), sin(th), -sin(th), cos(th)], [2, 2])
         fk = matmul(q, fs)
         call step(fk)
         sw = matmul(matmul(q, ss), transpose(q))
         err = max(err, abs(h(1, 6) - sw(1, 1)), abs(h(1, 7) - sw(2, 2)), abs(h(1, 9) - sw(1, 2)))
         werr = max(werr, abs(h(1, 10) - ws))
      end do
      err = err/maxval(abs(ss))
      werr = werr/ws
      call check(s, err <= 1.0e-12_wp, 'rigid rotation to 90 degrees: sigma = Q sigma_s Q^T', &
                 'relative error '//rtoa(err))
      call check(s, werr <= 1.0e-12_wp .and. ws > 0.0_wp, 'rigid rotation: the energy does not change', &
                 'relative change '//rtoa(werr))
   contains
      subroutine step(ff)
         real(wp), intent(in) :: ff(2, 2)
         call law_piola_general(o, 1, 1.0_wp, [ff(1, 1)], [ff(1, 2)], [ff(2, 1)], [ff(2, 2)], [1.0_wp], &
                                [ff(1, 1)*ff(2, 2) - ff(1, 2)*ff(2, 1)], [1.0_wp], h, p(1:1), p(2:2), &
                                p(3:3), p(4:4), p(5:5), w, dw, ys)
      end subroutine step
   end subroutine rotation

   !> The 1-D plate impact deck (uniaxial strain: uy fixed everywhere) of the family
   !> tools/stress/hypoelastic.py: a plate of length 30 on the rigid wall x = 30 (by symmetry, two
   !> equal plates striking at +-v), v/c_L = 1e-4.
   function plate_deck(nq, cfl, nu, nx, ny, hgt) result(t)
      integer, intent(in) :: nq, nx, ny
      real(wp), intent(in) :: cfl, nu, hgt
      character(len=:), allocatable :: t
      t = 'FEAP * * hypoelastic plate impact'//nl//'  0 0 0 2 2 4'//nl// &
          'PARAmeters'//nl//'  young = 1.0e4'//nl//'  nu = '//rtoa(nu)//nl//'  rho = 0.1'//nl// &
          '  cl = sqrt(young*(1-nu)/((1+nu)*(1-2*nu))/rho)'//nl//'  v0 = 1.0e-4*cl'//nl// &
          '  len = 30'//nl//'  hgt = '//rtoa(hgt)//nl//nl// &
          'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic ISOTropic young nu'//nl//'    DENSity rho'//nl// &
          '    QUADrature '//achar(iachar('0') + nq)//nl//nl// &
          'BLOCk'//nl//'  CARTesian,'//itoa_(nx)//','//itoa_(ny)//',1,1,1'//nl//'    1,0,0'//nl// &
          '    2,len,0'//nl//'    3,len,hgt'//nl//'    4,0,hgt'//nl//nl// &
          'EBOUndary'//nl//'  1 len 1 0'//nl//'  2 0 0 1'//nl//'  2 hgt 0 1'//nl//nl// &
          'INITial,VELOcity'//nl//'  MATErial,1,v0,0'//nl//nl//'END'//nl// &
          'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,'//rtoa(cfl)//nl//'  TPLOt,,1'//nl// &
          '  LOOP,,10000000'//nl//'    TIME,,1.4*len/cl'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
          'END'//nl//'  stre,,1,len/2,hgt/2'//nl//nl//'STOP'
   end function plate_deck

   !> The plate's plateau: the mean of sxx at mid-plate over the window 0.7 .. 1.3 L/c_L (after
   !> the front has passed, before the release from the free end returns) against -rho c_L v.
   subroutine plate(s, nq, cfl, nu)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      real(wp), intent(in) :: cfl, nu
      character(len=:), allocatable :: msg, name
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      real(wp) :: cl, want, mean, tc
      integer :: stage, k, n
      name = 'hypo_plate_'//achar(iachar('0') + nq)
      call run_deck(name, plate_deck(nq, cfl, nu, 60, 1, 1.0_wp), stage, msg)
      call check(s, stage == 0, 'plate impact deck runs ('//name//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//name//'.his', names, d)
      cl = sqrt(1.0e4_wp*(1.0_wp - nu)/((1.0_wp + nu)*(1.0_wp - 2.0_wp*nu))/0.1_wp)
      want = -0.1_wp*cl*1.0e-4_wp*cl
      tc = 30.0_wp/cl
      mean = 0.0_wp
      n = 0
      do k = 1, size(d, 2)
         if (d(1, k) < 0.7_wp*tc .or. d(1, k) > 1.3_wp*tc) cycle
         mean = mean + d(2, k)
         n = n + 1
      end do
      mean = mean/real(max(n, 1), wp)
      call check(s, n > 10 .and. abs(mean/want - 1.0_wp) <= 2.0e-3_wp, &
                 'plate impact, '//merge('2x2      ', 'one point', nq == 2)//', CFL '//rtoa(cfl)// &
                 ': plateau = rho c_L v to 2e-3', 'plateau/(rho c_L v) - 1 = '//rtoa(mean/want - 1.0_wp))
   end subroutine plate

   !> A free block 8 x 2 (4 x 1), nu = 0.3, with the stretching velocity v_x = v (2 x/L - 1)
   !> (zero momentum), v/c_L = 1e-3: it vibrates freely; over 3 periods of its first mode the
   !> energy drift of .ene stays below 1e-9 of the initial kinetic energy: the strain energy is the
   !> internal work of the scheme point by point (H13), so the balance closes to round-off.
   subroutine vibration(s, nq)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: nq
      character(len=:), allocatable :: msg, name, t, init
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :)
      integer :: stage, kd, kk, j
      real(wp) :: drift, ek0
      name = 'hypo_vib_'//achar(iachar('0') + nq)
      init = ''
      do j = 0, 4
         init = init//'  '//itoa_(1 + 17*j)//' 1 -v0 0'//nl//'  '//itoa_(17 + 17*j)//' 0 v0 0'//nl
      end do
      t = 'FEAP * * hypoelastic free vibration'//nl//'  0 0 0 2 2 4'//nl// &
          'PARAmeters'//nl//'  young = 1.0e4'//nl//'  rho = 0.1'//nl//'  v0 = 1.0e-3*sqrt(young/rho)'//nl//nl// &
          'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic ISOTropic young 0.3'//nl//'    DENSity rho'//nl// &
          '    QUADrature '//achar(iachar('0') + nq)//nl//nl// &
          'BLOCk'//nl//'  CARTesian,16,4,1,1,1'//nl//'    1,0,0'//nl//'    2,8,0'//nl//'    3,8,2'//nl// &
          '    4,0,2'//nl//nl//'END'//nl// &
          'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl// &
          '  INITial RATE'//nl//'  LOOP,,10000000'//nl//'    TIME,,3*2*8/sqrt(young/rho)'//nl// &
          '    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//'  disp,17,1'//nl//nl//init//nl//'STOP'
      call run_deck(name, t, stage, msg)
      call check(s, stage == 0, 'free vibration deck runs ('//name//')', msg)
      if (stage /= 0) return
      call read_table(run_dir//'/'//name//'.ene', names, d)
      kd = column(names, 'drift')
      kk = column(names, 'kinetic')
      ek0 = d(kk, 1)
      drift = maxval(abs(d(kd, :)))/ek0
      call check(s, ek0 > 0.0_wp .and. minval(d(kk, :)) < 0.5_wp*ek0 .and. drift <= 1.0e-9_wp, &
                 'free vibration, '//merge('2x2      ', 'one point', nq == 2)// &
                 ': it vibrates (kinetic energy below half its start) and the energy drift stays '// &
                 'below 1e-9 (W is the internal work, (H13))', &
                 'largest |drift|/E_k(0) = '//rtoa(drift))
   end subroutine vibration

   !> Decimal text of i.
   pure function itoa_(i) result(t)
      integer, intent(in) :: i
      character(len=:), allocatable :: t
      character(len=16) :: b
      write (b, '(i0)') i
      t = trim(b)
   end function itoa_

end module test_hypoelastic
