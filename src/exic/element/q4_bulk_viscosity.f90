!> The bulk viscosity of the DYNA codes for 4-node quadrilaterals (doc/damping.md, section 3):
!> the von Neumann-Richtmyer quadratic term with Landshoff's linear one,
!>
!>     q = rho l (q1 l trD^2 - q2 c trD)  for trD < 0,  q = 0 otherwise        (doc/damping.md, (Q.1))
!>
!> a pressure added to the stress of the element (sigma - q I), with trD the element's rate of
!> volume change from the half-step velocities v + dt/2 a and the current corners x0 + u:
!> trD = (dV/dt)/V, V the area (plane strain) or the volume per radian int r dA (axisymmetry,
!> (Q.3)); l = sqrt(A), rho = rho0 V0/V. Its nodal forces are -q dV/dx_a, whose power is
!> -q dV/dt (plane strain: -q A b_a, b_a the mean gradient of N_a, Flanagan & Belytschko 1981),
!> and its bound on the stable step the ratio c/(Q + sqrt(Q^2 + c^2)), Q = q1 l |trD| + q2 c
!> ((Q.2)). Plain arrays in, for any law: the caller gives rho0 and the dilatational wave speed
!> c of the material.
module exic_element_q4_bulk_viscosity
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: q4_bulk_viscosity

contains

   !> Add the viscous nodal forces of elements conn(:, 1:nel) to g(2, nnode) and lower `ratio`
   !> to the smallest step ratio of the compressing elements (unchanged when none compresses).
   !> x0, u, v, a: reference coordinates, displacement u(n+1), velocity v(n) and acceleration
   !> a(n) of the nodes; dt = dt(n), so that v + dt/2 a is the velocity of the step just taken.
   !> axi: x is the radius and V the volume per radian (forces per radian).
   pure subroutine q4_bulk_viscosity(nel, nnode, conn, x0, u, v, a, dt, rho0, c, q1, q2, axi, g, ratio)
      integer, intent(in) :: nel, nnode, conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), v(2, nnode), a(2, nnode), dt, rho0, c, q1, q2
      logical, intent(in) :: axi
      real(wp), intent(inout) :: g(2, nnode), ratio
      real(wp) :: x(4), y(4), vx(4), vy(4), bx(4), by(4), xr(4), yr(4), a2, a02, v6, v06, trd, l, q, qq, h
      integer :: e, k, n

      h = 0.5_wp*dt
      do e = 1, nel
         do k = 1, 4
            n = conn(k, e)
            x(k) = x0(1, n) + u(1, n)
            y(k) = x0(2, n) + u(2, n)
            vx(k) = v(1, n) + h*a(1, n)
            vy(k) = v(2, n) + h*a(2, n)
         end do
         ! twice the area, and 2A b_a = 2 dA/dx_a (doc/damping.md, section 3)
         a2 = (x(3) - x(1))*(y(4) - y(2)) + (x(2) - x(4))*(y(3) - y(1))
         if (.not. a2 > 0.0_wp) cycle   ! inverted: the force pass names the element
         if (axi) then
            ! 6 V and 6 dV/dx_a, V = int r dA (Q.3); rho0 V0 / V from the reference corners
            call volume6(x, y, v6, bx, by)
            if (.not. v6 > 0.0_wp) cycle
            do k = 1, 4
               xr(k) = x0(1, conn(k, e))
               yr(k) = x0(2, conn(k, e))
            end do
            call volume6(xr, yr, v06)
            trd = (bx(1)*vx(1) + bx(2)*vx(2) + bx(3)*vx(3) + bx(4)*vx(4) + &
                   by(1)*vy(1) + by(2)*vy(2) + by(3)*vy(3) + by(4)*vy(4))/v6
            if (.not. trd < 0.0_wp) cycle
            l = sqrt(0.5_wp*a2)
            q = rho0*(v06/v6)*l*(q1*l*trd*trd - q2*c*trd)
            ! P_a = -q dV/dx_a = -q/6 (6 dV/dx_a)
            do k = 1, 4
               n = conn(k, e)
               g(1, n) = g(1, n) - q*bx(k)/6.0_wp
               g(2, n) = g(2, n) - q*by(k)/6.0_wp
            end do
         else
            bx = [y(2) - y(4), y(3) - y(1), y(4) - y(2), y(1) - y(3)]
            by = [x(4) - x(2), x(1) - x(3), x(2) - x(4), x(3) - x(1)]
            ! trD = sum_a b_a . v_a = (sum_a 2A b_a . v_a) / (2A)
            trd = (bx(1)*vx(1) + bx(2)*vx(2) + bx(3)*vx(3) + bx(4)*vx(4) + &
                   by(1)*vy(1) + by(2)*vy(2) + by(3)*vy(3) + by(4)*vy(4))/a2
            if (.not. trd < 0.0_wp) cycle
            a02 = (x0(1, conn(3, e)) - x0(1, conn(1, e)))*(x0(2, conn(4, e)) - x0(2, conn(2, e))) + &
                  (x0(1, conn(2, e)) - x0(1, conn(4, e)))*(x0(2, conn(3, e)) - x0(2, conn(1, e)))
            l = sqrt(0.5_wp*a2)
            q = rho0*(a02/a2)*l*(q1*l*trd*trd - q2*c*trd)
            ! P_a = -q A b_a = -q/2 (2A b_a)
            do k = 1, 4
               n = conn(k, e)
               g(1, n) = g(1, n) - 0.5_wp*q*bx(k)
               g(2, n) = g(2, n) - 0.5_wp*q*by(k)
            end do
         end if
         qq = q1*l*abs(trd) + q2*c
         ratio = min(ratio, c/(qq + sqrt(qq*qq + c*c)))
      end do
   contains
      !> Six times the volume per radian of the quadrilateral (x radius, y axial), V = int x dA
      !> = 1/6 sum_i (x_i + x_i+1) c_i, c_i = x_i y_i+1 - x_i+1 y_i, and six times its gradient
      !> with respect to the corners (doc/damping.md, (Q.3)).
      pure subroutine volume6(x, y, v6, gx, gy)
         real(wp), intent(in) :: x(4), y(4)
         real(wp), intent(out) :: v6
         real(wp), intent(out), optional :: gx(4), gy(4)
         real(wp) :: cr(4)
         integer :: i, ip, im
         do i = 1, 4
            ip = mod(i, 4) + 1
            cr(i) = x(i)*y(ip) - x(ip)*y(i)
         end do
         v6 = (x(1) + x(2))*cr(1) + (x(2) + x(3))*cr(2) + (x(3) + x(4))*cr(3) + (x(4) + x(1))*cr(4)
         if (.not. present(gx)) return
         do i = 1, 4
            ip = mod(i, 4) + 1
            im = mod(i + 2, 4) + 1
            gx(i) = cr(i) + cr(im) + (x(i) + x(ip))*y(ip) - (x(im) + x(i))*y(im)
            gy(i) = (x(im) + x(i))*x(im) - (x(i) + x(ip))*x(ip)
         end do
      end subroutine volume6
   end subroutine q4_bulk_viscosity

end module exic_element_q4_bulk_viscosity
