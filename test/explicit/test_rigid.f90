!> Rigid bodies (doc/loads.md, sections 4-5): a free rigid block's mass properties, free flight
!> under gravity with spin, a free block striking a fixed floor with one corner against the
!> exact rigid-body impulse of the corrector's impact law, and a free rigid disk striking a free
!> elastic bar with the pair's linear and angular momentum balanced to round-off.
module test_rigid
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_explicit_step, only: stepper_t
   use exic_explicit_rigid, only: RB_FREE
   use testing, only: suite_t, check, check_close, section, error_text
   use test_loads, only: setup_stepper
   implicit none
   private

   public :: run_rigid_tests

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: head = 'FEAP * * rigid bodies'//nl//'0 0 0 2 2 4'//nl

contains

   subroutine run_rigid_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'rigid: a free rigid block')
      call flight(s)
      call section(s, 'rigid: a free block strikes a fixed floor with one corner')
      call corner_impact(s)
      call section(s, 'rigid: a free rigid disk strikes a free elastic bar')
      call disk_bar(s)
      call section(s, 'rigid: a free body with a boundary code is an error')
      call held_free_body(s)
   end subroutine run_rigid_tests

   !> A square block of side 1, turned by phi about its centre c, as a BLOCk of 2 x 2 elements.
   function square(c, phi, mat, node1, elmt1) result(text)
      real(wp), intent(in) :: c(2), phi
      integer, intent(in) :: mat, node1, elmt1
      character(len=:), allocatable :: text
      real(wp), parameter :: corner(2, 4) = reshape([-0.5_wp, -0.5_wp, 0.5_wp, -0.5_wp, 0.5_wp, 0.5_wp, &
                                                     -0.5_wp, 0.5_wp], [2, 4])
      real(wp) :: p(2)
      integer :: k
      character(len=40) :: bx, by
      text = 'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,'//itoa(node1)//','//itoa(elmt1)//','//itoa(mat)//nl
      do k = 1, 4
         p = c + [cos(phi)*corner(1, k) - sin(phi)*corner(2, k), sin(phi)*corner(1, k) + cos(phi)*corner(2, k)]
         write (bx, '(es24.16)') p(1)
         write (by, '(es24.16)') p(2)
         text = text//'    '//itoa(k)//','//trim(adjustl(bx))//','//trim(adjustl(by))//nl
      end do
      text = text//nl
   end function square

   !> The free rigid block's mass, centroid and inertia are those of the square (rho a^2, c,
   !> rho a^4/6) to round-off; under GRAVity and spinning at omega with no contact its centroid
   !> falls as -g t^2/2 and it turns as omega t, keeping its spin and 1/2 m v^2 + 1/2 I omega^2 -
   !> W_ext, to round-off.
   subroutine flight(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      real(wp), parameter :: g = 9.81_wp, om = 3.0_wp, phi = 0.3_wp, c(2) = [0.4_wp, 0.7_wp]
      logical, allocatable :: given(:)
      real(wp), allocatable :: v(:, :)
      real(wp) :: ex, eth, eom, ee, e0
      integer :: k
      deck = head//'MATErial,1'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl//square(c, phi, 1, 1, 1)// &
             'GRAVity,0,-9.81'//nl//'END'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('flight', deck, model, stp, err)
      call check(s, .not. allocated(err), 'free rigid block set up', error_text(err))
      if (allocated(err)) return
      associate (b => stp%ld%bodies(1))
         call check(s, b%kind == RB_FREE, 'region 1 is a free rigid body')
         call check_close(s, b%mass, 2.0_wp, 1.0e-14_wp, 'mass = rho a^2')
         call check_close(s, b%inertia, 2.0_wp/6.0_wp, 1.0e-14_wp, 'inertia about the centroid = m a^2/6')
         call check(s, norm2(b%xc0 - c) <= 1.0e-14_wp, 'centroid at the centre', rtoa(norm2(b%xc0 - c)))
      end associate
      allocate (given(stp%st%nnode), v(2, stp%st%nnode))
      given = stp%st%active
      v(1, :) = -om*(stp%st%x0(2, :) - c(2))
      v(2, :) = om*(stp%st%x0(1, :) - c(1))
      call stp%set_velocity(given, v)
      call stp%set_fixed_dt(1.0e-3_wp, 'test', err)
      if (.not. allocated(err)) call stp%start(err)
      call check(s, .not. allocated(err), 'free rigid block starts', error_text(err))
      if (allocated(err)) return
      e0 = stp%st%energy%kinetic
      call check_close(s, e0, 0.5_wp*(2.0_wp/6.0_wp)*om**2, 1.0e-13_wp, 'initial kinetic energy 1/2 I omega^2')
      ex = 0.0_wp
      eth = 0.0_wp
      eom = 0.0_wp
      ee = 0.0_wp
      do k = 1, 500
         call stp%advance(err)
         if (allocated(err)) exit
         associate (b => stp%ld%bodies(1), st => stp%st)
            ex = max(ex, abs(b%xc(2) - c(2) + 0.5_wp*g*st%t**2), abs(b%xc(1) - c(1)))
            eth = max(eth, abs(b%th - om*st%t))
            eom = max(eom, abs(b%om - om))
            ee = max(ee, abs(st%energy%kinetic - st%energy%wext - e0))
         end associate
      end do
      call check(s, .not. allocated(err), 'free flight runs', error_text(err))
      call check(s, ex <= 1.0e-12_wp, 'centroid falls as -g t^2/2', 'largest error '//rtoa(ex))
      call check(s, eth <= 1.0e-12_wp .and. eom <= 1.0e-13_wp, 'turns at constant omega: theta = omega t', &
                 rtoa(eth)//', '//rtoa(eom))
      call check(s, ee <= 1.0e-11_wp, 'kinetic energy - external work constant', 'largest change '//rtoa(ee))
   end subroutine flight

   !> A free rigid square (side 1, rho 2, turned by 30 degrees) falling at 1 strikes a fixed rigid
   !> floor with its lowest corner. The corrector brings the corner's normal velocity to zero
   !> (doc/loads.md, section 5): with r the corner from the centroid and n = (0, 1),
   !> P = -v_n / (1/m + (r x n)^2/I), V' = V + P n/m, omega' = P (r x n)/I; within 1 %.
   subroutine corner_impact(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      real(wp), parameter :: phi = acos(-1.0_wp)/6.0_wp, m = 2.0_wp, inertia = 2.0_wp/6.0_wp
      real(wp) :: r(2), c(2), rxn, p, vy, omg, vn
      logical, allocatable :: given(:)
      real(wp), allocatable :: v(:, :)
      integer :: k
      logical :: touched
      r = [-0.5_wp*cos(phi) + 0.5_wp*sin(phi), -0.5_wp*sin(phi) - 0.5_wp*cos(phi)]
      c = [0.5_wp, 0.01_wp - r(2)]
      deck = head//'MATErial,1'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl//'MATErial,2'//nl// &
             '  RIGId'//nl//nl//square(c, phi, 1, 1, 1)//'REGIon,2'//nl//'BLOCk'//nl// &
             '  CARTesian,5,1,101,5,2'//nl//'    1,-2,-0.2'//nl//'    2,3,-0.2'//nl//'    3,3,0'//nl// &
             '    4,-2,0'//nl//nl//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
             '    REGIon,2'//nl//'  PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//'END'//nl//'BATCh'//nl//'END'// &
             nl//'STOP'
      call setup_stepper('corner', deck, model, stp, err)
      call check(s, .not. allocated(err), 'corner impact set up', error_text(err))
      if (allocated(err)) return
      allocate (given(stp%st%nnode), v(2, stp%st%nnode))
      given = .false.
      given(stp%ld%bodies(1)%nodes) = .true.
      v = 0.0_wp
      v(2, :) = -1.0_wp
      call stp%set_velocity(given, v)
      call stp%set_fixed_dt(2.0e-4_wp, 'test', err)
      if (.not. allocated(err)) call stp%start(err)
      if (allocated(err)) return
      touched = .false.
      do k = 1, 250
         call stp%advance(err)
         if (allocated(err)) exit
         if (stp%st%nactive > 0) touched = .true.
      end do
      call check(s, .not. allocated(err) .and. touched, 'the corner strikes the floor by t = 0.05', error_text(err))
      ! exact impulse (omega = 0 before impact, v_n = -1)
      rxn = r(1)
      vn = -1.0_wp
      p = -vn/(1.0_wp/m + rxn**2/inertia)
      vy = -1.0_wp + p/m
      omg = p*rxn/inertia
      associate (b => stp%ld%bodies(1))
         call check(s, abs(b%v(2) - vy) <= 0.01_wp*abs(vy), 'velocity after impact within 1 % of the exact '// &
                    'impulse answer', rtoa(b%v(2))//' against '//rtoa(vy))
         call check(s, abs(b%om - omg) <= 0.01_wp*abs(omg), 'spin after impact within 1 %', &
                    rtoa(b%om)//' against '//rtoa(omg))
         call check(s, abs(b%v(1)) <= 1.0e-12_wp, 'no sideways velocity (frictionless floor)', rtoa(b%v(1)))
         print '(a,es10.3,a,es10.3,a)', '   info  corner impact: velocity ', 100.0_wp*(b%v(2) - vy)/abs(vy), &
            ' %, spin ', 100.0_wp*(b%om - omg)/abs(omg), ' % from the exact impulse answer'
      end associate
   end subroutine corner_impact

   !> A free rigid disk (a ring of POLAr blocks, rho 2) moving at (-2, 0) strikes the end of a free
   !> elastic bar 4 x 1 at rest, above its axis (two-pass contact). Every step: the pair's linear
   !> momentum is conserved to round-off, and its angular momentum about the origin changes by
   !> exactly the moment impulse of the contact forces, sum dt/2 (tau(n) + tau(n+1)) with
   !> tau = sum x x fcon (doc/loads.md, section 4); the size of that impulse is reported against
   !> the angular momentum the disk hands over.
   subroutine disk_bar(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      logical, allocatable :: given(:)
      real(wp), allocatable :: v(:, :)
      real(wp) :: p0(2), l0, ldisk0, tau_old, tau, imp, worst_p, worst_l, imp_max, ldisk
      integer :: k, ib
      logical :: touched
      deck = head//'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'// &
             nl//nl//'MATErial,2'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl//'REGIon,1'//nl// &
             'BLOCk'//nl//'  CARTesian,16,4,1,1,1'//nl//'    1,0,0'//nl//'    2,4,0'//nl//'    3,4,1'//nl// &
             '    4,0,1'//nl//nl//'SHIFt,4.52,0.8'//nl//'REGIon,2'//nl//'BLOCk'//nl// &
             '  POLAr,2,32,201,65,2'//nl//'    1,0.1,0'//nl//'    2,0.5,0'//nl//'    3,0.5,360'//nl// &
             '    4,0.1,360'//nl//nl//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
             '    REGIon,2'//nl//'  PAIR,1,SYMMetric,1,2'//nl//'END CONTact'//nl//'END'//nl//'TIE,REGIon,2,2'// &
             nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('disk_bar', deck, model, stp, err)
      call check(s, .not. allocated(err), 'disk and bar set up', error_text(err))
      if (allocated(err)) return
      ib = stp%ld%body_index(2)
      call check(s, ib > 0, 'region 2 is a rigid body')
      if (ib == 0) return
      allocate (given(stp%st%nnode), v(2, stp%st%nnode))
      given = .false.
      given(stp%ld%bodies(ib)%nodes) = .true.
      v = 0.0_wp
      v(1, :) = -2.0_wp
      call stp%set_velocity(given, v)
      call stp%start(err)
      if (allocated(err)) return
      p0 = stp%st%momentum
      l0 = angular()
      ldisk0 = disk_angular()
      tau_old = torque()
      imp = 0.0_wp
      imp_max = 0.0_wp
      worst_p = 0.0_wp
      worst_l = 0.0_wp
      touched = .false.
      do k = 1, 300
         call stp%advance(err)
         if (allocated(err)) exit
         tau = torque()
         imp = imp + 0.5_wp*stp%st%dt_prev*(tau_old + tau)
         tau_old = tau
         imp_max = max(imp_max, abs(imp))
         worst_p = max(worst_p, norm2(stp%st%momentum - p0))
         worst_l = max(worst_l, abs(angular() - l0 - imp))
         if (stp%st%nactive > 0) touched = .true.
      end do
      call check(s, .not. allocated(err) .and. touched, 'the disk strikes the bar', error_text(err))
      ldisk = disk_angular()
      call check(s, worst_p <= 1.0e-13_wp*norm2(p0), 'linear momentum of the pair conserved to round-off', &
                 'largest change '//rtoa(worst_p)//' of '//rtoa(norm2(p0)))
      call check(s, worst_l <= 1.0e-13_wp*abs(l0), 'angular momentum: L(t) - L(0) = moment impulse of the '// &
                 'contact forces, to round-off', 'largest difference '//rtoa(worst_l)//' of '//rtoa(abs(l0)))
      call check(s, abs(ldisk - ldisk0) > 0.1_wp*abs(ldisk0), 'the disk hands over angular momentum', &
                 rtoa(ldisk0)//' -> '//rtoa(ldisk))
      print '(a,es10.3,a,es10.3,a)', '   info  disk and bar: moment impulse of the contact forces ', imp_max, &
         ' = ', 100.0_wp*imp_max/abs(ldisk - ldisk0), ' % of the angular momentum the disk hands over'
   contains
      !> Angular momentum about the origin: nodes plus the free disk.
      real(wp) function angular() result(l)
         integer :: i
         real(wp) :: x(2)
         l = 0.0_wp
         do i = 1, stp%st%nnode
            x = stp%st%x0(:, i) + stp%st%u(:, i)
            l = l + stp%st%mass(i)*(x(1)*stp%st%v(2, i) - x(2)*stp%st%v(1, i))
         end do
         l = l + disk_angular()
      end function angular
      real(wp) function disk_angular() result(l)
         associate (b => stp%ld%bodies(ib))
            l = b%mass*(b%xc(1)*b%v(2) - b%xc(2)*b%v(1)) + b%inertia*b%om
         end associate
      end function disk_angular
      !> Moment of the contact forces about the origin at x(n+1).
      real(wp) function torque() result(t)
         integer :: i
         real(wp) :: x(2)
         t = 0.0_wp
         do i = 1, stp%st%nnode
            x = stp%st%x0(:, i) + stp%st%u(:, i)
            t = t + (x(1)*stp%st%fcon(2, i) - x(2)*stp%st%fcon(1, i))
         end do
      end function torque
   end subroutine disk_bar

   !> A node of a free rigid body with a boundary code: the stepper refuses it, naming the node.
   subroutine held_free_body(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      character(len=:), allocatable :: deck
      deck = head//'MATErial,1'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl// &
             square([0.5_wp, 0.5_wp], 0.0_wp, 1, 1, 1)//'BOUNdary'//nl//'  1,0,1,1'//nl//nl// &
             'END'//nl//'BATCh'//nl//'END'//nl//'STOP'
      call setup_stepper('held', deck, model, stp, err)
      call check(s, allocated(err), 'a held free body is an error', 'no error')
      if (allocated(err)) call check(s, index(err%message, 'node 1 of the free rigid body of region 1 has '// &
                                              'a boundary code') > 0, 'the error names the node', err%message)
   end subroutine held_free_body


end module test_rigid
