!> Kernels of the velocity-dependent forces of the force pass (doc/damping.md): the mass
!> damping force, the trapezoid booking of the work of a nodal force (D.5) and the damped
!> stable step (D.4). Plain arrays; the force pass (assembly.f90) calls them only for sets
!> that ask for a dissipation.
module exic_explicit_dissipation
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: mass_damping, half_work, damped_step

contains

   !> Add c m_i (v_i + dt/2 a_i) to g(:, nodes(i)) for the n nodes of a set, m_i = mass(i) the
   !> share of node nodes(i)'s lumped mass that the set gives it ((D.2): the force of the
   !> half-step velocity v(n+1/2) = v(n) + dt(n)/2 a(n)).
   pure subroutine mass_damping(n, nodes, mass, c, nnode, v, a, dt, g)
      integer, intent(in) :: n, nodes(n), nnode
      real(wp), intent(in) :: mass(n), c, v(2, nnode), a(2, nnode), dt
      real(wp), intent(inout) :: g(2, nnode)
      real(wp) :: h, cm
      integer :: i, j
      h = 0.5_wp*dt
      do i = 1, n
         j = nodes(i)
         cm = c*mass(i)
         g(1, j) = g(1, j) + cm*(v(1, j) + h*a(1, j))
         g(2, j) = g(2, j) + cm*(v(2, j) + h*a(2, j))
      end do
   end subroutine mass_damping

   !> Half the work of the nodal force g over the step just taken: 1/2 g . du with
   !> du = dt (v + dt/2 a) = u(n+1) - u(n) (D.5; the force pass books g(n) and g(n+1) each this
   !> way). Summed over the nodes in order.
   pure real(wp) function half_work(nnode, g, v, a, dt) result(w)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: g(2, nnode), v(2, nnode), a(2, nnode), dt
      real(wp) :: h
      integer :: j
      h = 0.5_wp*dt
      w = 0.0_wp
      do j = 1, nnode
         w = w + (g(1, j)*(v(1, j) + h*a(1, j)) + g(2, j)*(v(2, j) + h*a(2, j)))
      end do
      w = 0.5_wp*dt*w
   end function half_work

   !> The stable step with mass damping c of a set whose Courant step is dt0 (D.4):
   !> dt0 / (sqrt(1 + b^2) + b), b = c dt0 / 4.
   pure real(wp) function damped_step(dt0, c) result(dt)
      real(wp), intent(in) :: dt0, c
      real(wp) :: b
      b = 0.25_wp*c*dt0
      dt = dt0/(sqrt(1.0_wp + b*b) + b)
   end function damped_step

end module exic_explicit_dissipation
