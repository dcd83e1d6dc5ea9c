!> The central-difference kernels of one step (seed eq. 4.3-4.4) on plain arrays.
!>
!> With distinct dt(n) and dt(n+1), one step is
!>   x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)                  cd_displacement, positions
!>   M a~(n+1) = F - P(u(n+1)),  v~(n+1) = v(n) + dt(n)/2 (a(n) + a~(n+1))   cd_predictor (4.3-4.4)
!>   contact corrector: a(n+1) = a~(n+1) - M^-1 G lambda         (4.5-4.7, src/exic/contact)
!>   v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1))                       cd_velocity
!> Arrays are (component, node); every kernel is one pass without temporaries.
module exic_explicit_central
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: cd_displacement, cd_predictor, cd_velocity, positions

contains

   !> First part of a central-difference step over `n` nodes (seed eq. 4.3-4.4):
   !> du = dt v + dt^2/2 a, u = u + du, and a_old = a kept for the velocity update.
   !> One pass instead of four whole-array statements (no temporaries).
   pure subroutine cd_displacement(n, dt, v, a, u, du, a_old)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: v(2, n), a(2, n)
      real(wp), intent(inout) :: u(2, n)
      real(wp), intent(out) :: du(2, n), a_old(2, n)
      real(wp) :: h, d
      integer :: i, k
      h = 0.5_wp*dt*dt
      do i = 1, n
         do k = 1, 2
            d = dt*v(k, i) + h*a(k, i)
            du(k, i) = d
            u(k, i) = u(k, i) + d
            a_old(k, i) = a(k, i)
         end do
      end do
   end subroutine cd_displacement

   !> Predictor of eq. 4.3-4.4: a~ = M^-1 (F - P) and, when `with_vt`, v~ = v + dt/2 (a_old + a~)
   !> (only the contact search needs v~).
   pure subroutine cd_predictor(n, dt, minv, fext, fint, v, a_old, a, with_vt, vt)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: minv(2, n), fext(2, n), fint(2, n), v(2, n), a_old(2, n)
      real(wp), intent(out) :: a(2, n)
      logical, intent(in) :: with_vt
      real(wp), intent(inout) :: vt(2, n)
      real(wp) :: h
      integer :: i, k
      h = 0.5_wp*dt
      if (with_vt) then
         do i = 1, n
            do k = 1, 2
               a(k, i) = minv(k, i)*(fext(k, i) - fint(k, i))
               vt(k, i) = v(k, i) + h*(a_old(k, i) + a(k, i))
            end do
         end do
      else
         do i = 1, n
            do k = 1, 2
               a(k, i) = minv(k, i)*(fext(k, i) - fint(k, i))
            end do
         end do
      end if
   end subroutine cd_predictor

   !> Last part of a step: v = v + dt/2 (a_old + a) with the corrected a, the work of the
   !> external forces (F . du) and, when `with_contact`, of the contact forces by the
   !> trapezoid rule (1/2 (fcon_old + fcon) . du), each summed in array order.
   pure subroutine cd_velocity(n, dt, a_old, a, fext, du, with_contact, fcon_old, fcon, v, wext, wcon)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: a_old(2, n), a(2, n), fext(2, n), du(2, n)
      logical, intent(in) :: with_contact
      real(wp), intent(in) :: fcon_old(2, n), fcon(2, n)
      real(wp), intent(inout) :: v(2, n), wext, wcon
      real(wp) :: h, se, sc
      integer :: i, k
      h = 0.5_wp*dt
      se = 0.0_wp
      sc = 0.0_wp
      do i = 1, n
         do k = 1, 2
            v(k, i) = v(k, i) + h*(a_old(k, i) + a(k, i))
            se = se + fext(k, i)*du(k, i)
         end do
      end do
      wext = wext + se
      if (with_contact) then
         do i = 1, n
            do k = 1, 2
               sc = sc + (fcon_old(k, i) + fcon(k, i))*du(k, i)
            end do
         end do
         wcon = wcon + 0.5_wp*sc
      end if
   end subroutine cd_velocity

   !> x = x0 + u as a plain loop (measured several microseconds per step faster than the
   !> whole-array assignment between the components of two dummies on a 3000-node mesh).
   pure subroutine positions(nnode, x0, u, x)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(out) :: x(2, nnode)
      integer :: i
      do i = 1, nnode
         x(1, i) = x0(1, i) + u(1, i)
         x(2, i) = x0(2, i) + u(2, i)
      end do
   end subroutine positions

end module exic_explicit_central
