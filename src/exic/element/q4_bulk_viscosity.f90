!> The bulk viscosity of the DYNA codes for 4-node quadrilaterals (doc/damping.md, section 3):
!> the von Neumann-Richtmyer quadratic term with Landshoff's linear one,
!>
!>     q = rho l (q1 l trD^2 - q2 c trD)  for trD < 0,  q = 0 otherwise        (doc/damping.md, (Q.1))
!>
!> a pressure added to the stress of the element (sigma - q I), with trD = div v at the element
!> centre from the half-step velocities v + dt/2 a and the current corners x0 + u, l = sqrt(A),
!> rho = rho0 A0/A; its nodal forces -q A b_a (b_a the mean gradient of N_a, Flanagan &
!> Belytschko 1981) and its bound on the stable step, the ratio c/(Q + sqrt(Q^2 + c^2)),
!> Q = q1 l |trD| + q2 c ((Q.2)). Plain arrays in, for any law: the caller gives rho0 and the
!> dilatational wave speed c of the material.
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
   pure subroutine q4_bulk_viscosity(nel, nnode, conn, x0, u, v, a, dt, rho0, c, q1, q2, g, ratio)
      integer, intent(in) :: nel, nnode, conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), v(2, nnode), a(2, nnode), dt, rho0, c, q1, q2
      real(wp), intent(inout) :: g(2, nnode), ratio
      real(wp) :: x(4), y(4), vx(4), vy(4), bx(4), by(4), a2, a02, trd, l, q, qq, h
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
         ! twice the area, and 2A b_a (doc/damping.md, section 3)
         a2 = (x(3) - x(1))*(y(4) - y(2)) + (x(2) - x(4))*(y(3) - y(1))
         if (.not. a2 > 0.0_wp) cycle   ! inverted: the force pass names the element
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
         qq = q1*l*abs(trd) + q2*c
         ratio = min(ratio, c/(qq + sqrt(qq*qq + c*c)))
      end do
   end subroutine q4_bulk_viscosity

end module exic_element_q4_bulk_viscosity
