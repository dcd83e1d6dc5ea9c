!> Rigid bodies with a body state (doc/loads.md, section 4): the centroid X, the rotation theta,
!> their velocities and accelerations, and the kernels that place a body's nodes, set their
!> velocities and accelerations, and gather the nodal forces on it.
!>
!> Kinds: RB_PLAIN (a RIGId region that is fixed or keeps its initial velocity; its nodes move
!> on their own, as they always did, and the body is only reported), RB_DRIVEN (MOTIon: velocity
!> and angular velocity prescribed) and RB_FREE (RIGId,FREE: three dofs moved by forces and
!> contact). Node k of a body sits at x_k = X + R(theta) s_k with s_k its reference offset.
module exic_explicit_rigid
   use exic_base_kinds, only: wp
   implicit none
   private

   integer, parameter, public :: RB_PLAIN = 0, RB_DRIVEN = 1, RB_FREE = 2

   public :: rigid_body_t, rigid_place, rigid_levers, rigid_gather, rigid_node_motion, &
             rigid_fit_velocity

   !> One rigid body: the rigid elements of one region.
   type :: rigid_body_t
      integer :: kind = RB_PLAIN
      integer :: region = 0
      integer :: motion = 0                       !< MOTIon index (RB_DRIVEN)
      integer :: nnode = 0
      integer, allocatable :: nodes(:)            !< (nnode) its nodes
      real(wp), allocatable :: s(:, :)            !< (2, nnode) reference offsets x0_k - X(0)
      real(wp) :: mass = 0.0_wp                   !< m (with the point masses of shared nodes)
      real(wp) :: inertia = 0.0_wp                !< I about the centroid
      real(wp) :: xc0(2) = 0.0_wp                 !< centroid in the reference configuration
      ! state at t(n+1) once a step is complete: centroid, rotation, velocities, accelerations
      real(wp) :: xc(2) = 0.0_wp, th = 0.0_wp
      real(wp) :: v(2) = 0.0_wp, om = 0.0_wp
      real(wp) :: a(2) = 0.0_wp, al = 0.0_wp
      ! V(n), omega(n), A(n), alpha(n) kept through a step for the velocity update
      real(wp) :: vn(2) = 0.0_wp, omn = 0.0_wp, an(2) = 0.0_wp, aln = 0.0_wp
   end type rigid_body_t

contains

   !> Step 1 for a body with a state: X(n+1) = X + dt V + dt^2/2 A, theta likewise; every node
   !> placed exactly at X + R(theta) s_k, its displacement u and increment du made consistent
   !> (du was u(n+1) - u(n) of the nodes' own update; it becomes the actual increment).
   pure subroutine rigid_place(b, dt, nnode, x0, u, du)
      type(rigid_body_t), intent(inout) :: b
      real(wp), intent(in) :: dt
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode)
      real(wp), intent(inout) :: u(2, nnode), du(2, nnode)
      real(wp) :: c, sn, unew(2)
      integer :: j, k
      b%vn = b%v
      b%omn = b%om
      b%an = b%a
      b%aln = b%al
      b%xc = b%xc + dt*b%v + (0.5_wp*dt*dt)*b%a
      b%th = b%th + dt*b%om + (0.5_wp*dt*dt)*b%al
      c = cos(b%th)
      sn = sin(b%th)
      do j = 1, b%nnode
         k = b%nodes(j)
         unew(1) = b%xc(1) + c*b%s(1, j) - sn*b%s(2, j) - x0(1, k)
         unew(2) = b%xc(2) + sn*b%s(1, j) + c*b%s(2, j) - x0(2, k)
         du(:, k) = du(:, k) + (unew - u(:, k))
         u(:, k) = unew
      end do
   end subroutine rigid_place

   !> Lever arms r_k = x_k - X of the body's nodes into r(2, nnode) (x = x0 + u).
   pure subroutine rigid_levers(b, nnode, x0, u, r)
      type(rigid_body_t), intent(in) :: b
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(inout) :: r(2, nnode)
      integer :: j, k
      do j = 1, b%nnode
         k = b%nodes(j)
         r(:, k) = x0(:, k) + u(:, k) - b%xc
      end do
   end subroutine rigid_levers

   !> Force and moment about X of the nodal forces f(2, nnode) on the body's nodes, with lever
   !> arms r(2, nnode): F = sum f_k, M = sum r_k x f_k (the generalized force T^T f).
   pure subroutine rigid_gather(b, nnode, r, f, force, moment)
      type(rigid_body_t), intent(in) :: b
      integer, intent(in) :: nnode
      real(wp), intent(in) :: r(2, nnode), f(2, nnode)
      real(wp), intent(out) :: force(2), moment
      integer :: j, k
      force = 0.0_wp
      moment = 0.0_wp
      do j = 1, b%nnode
         k = b%nodes(j)
         force = force + f(:, k)
         moment = moment + (r(1, k)*f(2, k) - r(2, k)*f(1, k))
      end do
   end subroutine rigid_gather

   !> The rigid field on the body's nodes: v_k = V + omega e3 x r_k and
   !> a_k = A + alpha e3 x r_k - omega^2 r_k (e3 x r = (-r_y, r_x)).
   pure subroutine rigid_node_motion(b, nnode, r, vel, om, acc, al, v, a)
      type(rigid_body_t), intent(in) :: b
      integer, intent(in) :: nnode
      real(wp), intent(in) :: r(2, nnode), vel(2), om, acc(2), al
      real(wp), intent(inout) :: v(2, nnode), a(2, nnode)
      integer :: j, k
      do j = 1, b%nnode
         k = b%nodes(j)
         v(1, k) = vel(1) - om*r(2, k)
         v(2, k) = vel(2) + om*r(1, k)
         a(1, k) = acc(1) - al*r(2, k) - om*om*r(1, k)
         a(2, k) = acc(2) + al*r(1, k) - om*om*r(2, k)
      end do
   end subroutine rigid_node_motion

   !> The rigid velocity nearest to the nodal velocities v(2, nnode) in the weights w(nnode)
   !> (lumped masses): V = sum w v / sum w, omega = sum w r x (v - V) / sum w |r|^2, lever arms
   !> r(2, nnode). A uniform velocity gives V = v, omega = 0; a rigid field gives itself back.
   pure subroutine rigid_fit_velocity(b, nnode, r, w, v, vel, om)
      type(rigid_body_t), intent(in) :: b
      integer, intent(in) :: nnode
      real(wp), intent(in) :: r(2, nnode), w(nnode), v(2, nnode)
      real(wp), intent(out) :: vel(2), om
      real(wp) :: wsum, num, den, d(2)
      integer :: j, k
      wsum = 0.0_wp
      vel = 0.0_wp
      do j = 1, b%nnode
         k = b%nodes(j)
         wsum = wsum + w(k)
         vel = vel + w(k)*v(:, k)
      end do
      if (wsum > 0.0_wp) then
         vel = vel/wsum
      else
         vel = v(:, b%nodes(1))
      end if
      num = 0.0_wp
      den = 0.0_wp
      do j = 1, b%nnode
         k = b%nodes(j)
         d = v(:, k) - vel
         num = num + w(k)*(r(1, k)*d(2) - r(2, k)*d(1))
         den = den + w(k)*(r(1, k)**2 + r(2, k)**2)
      end do
      om = 0.0_wp
      if (den > 0.0_wp) om = num/den
   end subroutine rigid_fit_velocity

end module exic_explicit_rigid
