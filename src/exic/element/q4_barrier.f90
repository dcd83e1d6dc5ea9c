!> The corner barrier of the one-point quadrilateral with the physical hourglass control
!> (doc/hourglass.md section 5, (H13)-(H19)): the energy of the corner volume ratios, its exact
!> gradient, its bound on the stable step and the kinematic step limit, on the structure-of-arrays
!> blocks of src/exic/element/q4_1pt.f90 (n lanes, (lane, local node)).
module exic_element_q4_barrier
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: corner_barrier, barrier_limit

contains

   !> Corner barrier of a block of one-point elements with the physical control (doc/hourglass.md,
   !> section 5): r_a = (s_a/S)/(s0_a/S0) (H13) from the doubled corner triangles s_a and doubled
   !> areas S of the reference (xr, yr) and current (xc, yc) corners; below r0 = 1/2 the energy
   !> w_a = kappa A0/4 (ln(r_a/r0))^2 (H14), kappa = E' = 2 mu (1 + nub), is added to eh and its
   !> exact gradient (H15) to fx, fy, both times wr (1, or R_c in axisymmetry); ob(k) returns
   !> sum_a omega_a^2/4 of the bound (H17) for the step (H18), barrier_step. A block with no
   !> corner below r0 changes nothing (ob = 0). A corner already folded (s_a <= 0 or S <= 0) is
   !> left to the fold check.
   pure subroutine corner_barrier(n, xr, yr, xc, yc, wr, lambda, mu, rho0, fx, fy, eh, ob)
      integer, intent(in) :: n   !< lanes (the force kernels' block size)
      real(wp), intent(in), dimension(n, 4) :: xr, yr, xc, yc
      real(wp), intent(in) :: wr(n), lambda, mu, rho0
      real(wp), intent(inout), dimension(n, 4) :: fx, fy
      real(wp), intent(inout) :: eh(n)
      real(wp), intent(out) :: ob(n)
      real(wp), parameter :: RB = 0.5_wp                          !< r0 of (H14)
      real(wp), parameter :: HT = 1.7320508075688772935_wp        !< |Hessian| of a doubled triangle area
      real(wp), parameter :: HQ = 2.0_wp                          !< |Hessian| of a doubled quad area
      !> beta of the kinematic limit (H19): ln r_a falls by at most beta in a step (H20)
      real(wp), parameter :: BETA = 0.25_wp
      !> exp(2 beta), and RA = r0 exp(beta): above RA no corner reaches r0 in one step (H20)
      real(wp), parameter :: EB2 = 1.6487212707001282_wp, RA = 0.64201270834387071_wp
      real(wp), dimension(n, 4) :: s0, sc, rr
      real(wp), dimension(n) :: q0, qc
      real(wp) :: kap, c, el, s, sq, gs(2, 4), gsq(2, 4), m(4), mmin, gm, sm, w
      integer :: k, a, b, ip, ir

      ! doubled corner triangles (a-1, a, a+1) and doubled areas, reference and current (H13)
      do k = 1, n
         q0(k) = (xr(k, 3) - xr(k, 1))*(yr(k, 4) - yr(k, 2)) - (yr(k, 3) - yr(k, 1))*(xr(k, 4) - xr(k, 2))
         qc(k) = (xc(k, 3) - xc(k, 1))*(yc(k, 4) - yc(k, 2)) - (yc(k, 3) - yc(k, 1))*(xc(k, 4) - xc(k, 2))
      end do
      do a = 1, 4
         ip = modulo(a - 2, 4) + 1
         ir = modulo(a, 4) + 1
         do k = 1, n
            s0(k, a) = (xr(k, a) - xr(k, ip))*(yr(k, ir) - yr(k, a)) - (yr(k, a) - yr(k, ip))*(xr(k, ir) - xr(k, a))
            sc(k, a) = (xc(k, a) - xc(k, ip))*(yc(k, ir) - yc(k, a)) - (yc(k, a) - yc(k, ip))*(xc(k, ir) - xc(k, a))
            rr(k, a) = (sc(k, a)*q0(k))/(s0(k, a)*merge(qc(k), 1.0_wp, qc(k) > 0.0_wp))
         end do
      end do
      ob = 0.0_wp
      if (minval(rr) >= RA) return

      ! kappa = E' = 2 mu (1 + nub), nub = lambda/(lambda + 2 mu) (H14)
      kap = 2.0_wp*mu*(1.0_wp + lambda/(lambda + 2.0_wp*mu))
      do k = 1, n
         if (.not. qc(k) > 0.0_wp) cycle
         ! the element's own lumped masses m_b = rho0 (S0 + s0_b)/12 (H17)
         do b = 1, 4
            m(b) = rho0*(q0(k) + s0(k, b))/12.0_wp
         end do
         mmin = minval(m)
         ! dS/dx_b (H15)
         gsq(:, 1) = [-(yc(k, 4) - yc(k, 2)), xc(k, 4) - xc(k, 2)]
         gsq(:, 3) = -gsq(:, 1)
         gsq(:, 2) = [yc(k, 3) - yc(k, 1), -(xc(k, 3) - xc(k, 1))]
         gsq(:, 4) = -gsq(:, 2)
         sq = qc(k)
         do a = 1, 4
            if (.not. (rr(k, a) < RA .and. rr(k, a) > 0.0_wp)) cycle
            ip = modulo(a - 2, 4) + 1
            ir = modulo(a, 4) + 1
            s = sc(k, a)
            ! ds/dx of the triangle (p, q, r) = (a-1, a, a+1); zero at the opposite node
            gs = 0.0_wp
            gs(:, ip) = [yc(k, a) - yc(k, ir), xc(k, ir) - xc(k, a)]
            gs(:, a) = [yc(k, ir) - yc(k, ip), xc(k, ip) - xc(k, ir)]
            gs(:, ir) = [yc(k, ip) - yc(k, a), xc(k, a) - xc(k, ip)]
            el = log(rr(k, a)/RB)
            ! w_a = kappa A0/4 L^2, grad w_a = kappa A0/2 L g, A0 = S0/2 (H14, H15); forces and
            ! energy below r0 only
            c = 0.25_wp*kap*q0(k)
            w = merge(wr(k)*c*el, 0.0_wp, el < 0.0_wp)
            gm = 0.0_wp
            sm = 0.0_wp
            do b = 1, 4
               fx(k, b) = fx(k, b) + w*(gs(1, b)/s - gsq(1, b)/sq)
               fy(k, b) = fy(k, b) + w*(gs(2, b)/s - gsq(2, b)/sq)
               gm = gm + ((gs(1, b)/s - gsq(1, b)/sq)**2 + (gs(2, b)/s - gsq(2, b)/sq)**2)/m(b)
               sm = sm + (gs(1, b)**2 + gs(2, b)**2)/m(b)
            end do
            if (el < 0.0_wp) eh(k) = eh(k) + 0.5_wp*wr(k)*c*el*el
            ! omega_a^2/4 of (H17) at the worst state the step can reach (H20): |L| + beta, the
            ! areas shrunk by exp(-beta)
            ob(k) = ob(k) + 0.25_wp*c*EB2*(gm + (BETA - el)*(sm/(s*s) + HT/(mmin*s) + HQ/(mmin*sq)))
         end do
      end do
   end subroutine corner_barrier

   !> The step of a block with the corner barrier: barrier_step with ob from corner_barrier and
   !> the kinematic limit of corner_rate from the nodal velocities v of the block's nodes, when
   !> given (the force pass), without it otherwise (the initial step).
   pure subroutine barrier_limit(n, nb, nnode, conn, xc, yc, ob, dt2, v)
      integer, intent(in) :: n, nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in), dimension(n, 4) :: xc, yc
      real(wp), intent(in) :: ob(n)
      real(wp), intent(inout) :: dt2(n)
      real(wp), intent(in), optional :: v(2, nnode)
      real(wp), dimension(n, 4) :: vx, vy
      real(wp) :: tk(n)
      tk = huge(1.0_wp)
      if (present(v)) then
         call gather_v(n, nb, nnode, conn, v, vx, vy)
         call corner_rate(n, xc, yc, vx, vy, tk)
      end if
      call barrier_step(n, dt2, ob, tk)
   end subroutine barrier_limit

   !> The step with the corner barrier (H18): dt2 <- min(dt2/(1 + dt2 ob), tk), ob = sum_a
   !> omega_a^2/4 (corner_barrier), tk the squared kinematic limit (H19) (corner_rate; huge when
   !> not known); unchanged where ob = 0 and tk >= dt2.
   pure subroutine barrier_step(n, dt2, ob, tk)
      integer, intent(in) :: n   !< lanes (the force kernels' block size)
      real(wp), intent(inout) :: dt2(n)
      real(wp), intent(in) :: ob(n), tk(n)
      integer :: k
      do k = 1, n
         dt2(k) = min(dt2(k)/(1.0_wp + dt2(k)*ob(k)), tk(k))
      end do
   end subroutine barrier_step

   !> Kinematic limit of the step (doc/hourglass.md (H19)): with the current corners (xc, yc) and
   !> nodal velocities (vx, vy), the rate at which corner a's volume ratio falls,
   !> rho_a = -d(ln r_a)/dt = dS/dt/S - ds_a/dt/s_a, and tk = (beta/max_a rho_a)^2, beta = 1/4:
   !> no corner loses more than a quarter of its volume ratio in one step (to first order). huge
   !> where no corner closes, or the element is already folded (left to the fold check).
   pure subroutine corner_rate(n, xc, yc, vx, vy, tk)
      integer, intent(in) :: n   !< lanes (the force kernels' block size)
      real(wp), intent(in), dimension(n, 4) :: xc, yc, vx, vy
      real(wp), intent(out) :: tk(n)
      real(wp), parameter :: BETA = 0.25_wp
      real(wp) :: sq, dsq, s, ds, rho, rmax
      integer :: k, a, ip, ir
      do k = 1, n
         ! S = d1 x d2 and its rate d1' x d2 + d1 x d2'
         sq = (xc(k, 3) - xc(k, 1))*(yc(k, 4) - yc(k, 2)) - (yc(k, 3) - yc(k, 1))*(xc(k, 4) - xc(k, 2))
         dsq = ((vx(k, 3) - vx(k, 1))*(yc(k, 4) - yc(k, 2)) - (vy(k, 3) - vy(k, 1))*(xc(k, 4) - xc(k, 2))) &
               + ((xc(k, 3) - xc(k, 1))*(vy(k, 4) - vy(k, 2)) - (yc(k, 3) - yc(k, 1))*(vx(k, 4) - vx(k, 2)))
         rmax = 0.0_wp
         do a = 1, 4
            ip = modulo(a - 2, 4) + 1
            ir = modulo(a, 4) + 1
            s = (xc(k, a) - xc(k, ip))*(yc(k, ir) - yc(k, a)) - (yc(k, a) - yc(k, ip))*(xc(k, ir) - xc(k, a))
            ds = ((vx(k, a) - vx(k, ip))*(yc(k, ir) - yc(k, a)) - (vy(k, a) - vy(k, ip))*(xc(k, ir) - xc(k, a))) &
                 + ((xc(k, a) - xc(k, ip))*(vy(k, ir) - vy(k, a)) - (yc(k, a) - yc(k, ip))*(vx(k, ir) - vx(k, a)))
            rho = merge(dsq/merge(sq, 1.0_wp, sq > 0.0_wp) - ds/merge(s, 1.0_wp, s > 0.0_wp), 0.0_wp, &
                        s > 0.0_wp .and. sq > 0.0_wp)
            rmax = max(rmax, rho)
         end do
         tk(k) = merge((BETA/merge(rmax, 1.0_wp, rmax > 0.0_wp))**2, huge(1.0_wp), rmax > 0.0_wp)
      end do
   end subroutine corner_rate

   !> The nodal velocities of nb elements, (element, local node); lanes nb + 1 .. n repeat
   !> element nb (as gather).
   pure subroutine gather_v(n, nb, nnode, conn, v, vx, vy)
      integer, intent(in) :: n   !< lanes (the force kernels' block size)
      integer, intent(in) :: nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: v(2, nnode)
      real(wp), intent(out), dimension(n, 4) :: vx, vy
      integer :: k, a
      do k = 1, nb
         do a = 1, 4
            vx(k, a) = v(1, conn(a, k))
            vy(k, a) = v(2, conn(a, k))
         end do
      end do
      do a = 1, 4
         do k = nb + 1, n
            vx(k, a) = vx(nb, a)
            vy(k, a) = vy(nb, a)
         end do
      end do
   end subroutine gather_v

end module exic_element_q4_barrier
