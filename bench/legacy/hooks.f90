!> The two contact hooks of the legacy overhead benchmark (legacy_overhead.f90): exic's contact
!> and the legacy API's step call, each timed around the call alone.
module bench_legacy_hooks
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_clock, only: wall_time
   use exic_explicit_step, only: stepper_t, contact_hook_t
   use exic_explicit_central, only: positions
   use exic_contact_contact, only: contact_t
   use exic_legacy_interfaces, only: exic_contact_step
   implicit none
   private

   public :: native_hook_t, api_hook_t

   !> exic's contact, timed.
   type, extends(contact_hook_t) :: native_hook_t
      type(contact_t) :: contact
      real(wp) :: time = 0.0_wp
   contains
      procedure :: correct => native_correct
   end type native_hook_t

   !> Contact through the API, timed; the host forms x = x0 + u from its stepper's state.
   type, extends(contact_hook_t) :: api_hook_t
      integer :: h = 0
      type(stepper_t), pointer :: stp => null()
      real(wp), allocatable :: x(:, :)
      real(wp) :: time = 0.0_wp, time_x = 0.0_wp
   contains
      procedure :: correct => api_correct
   end type api_hook_t

contains

   !> The native contact call, timed.
   subroutine native_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err)
      class(native_hook_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(out) :: nactive
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: t0
      t0 = wall_time()
      call self%contact%correct(nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err)
      self%time = self%time + (wall_time() - t0)
   end subroutine native_correct

   !> The API's step call with the host's own positions, both timed.
   subroutine api_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err)
      class(api_hook_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(out) :: nactive
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: t0, t1
      integer :: ierr
      t0 = wall_time()
      call positions(nnode, self%stp%st%x0, self%stp%st%u, self%x)
      t1 = wall_time()
      call exic_contact_step(self%h, nnode, self%x, vt, a, dt_prev, dt, fcon, nactive, ierr)
      self%time = self%time + (wall_time() - t1)
      self%time_x = self%time_x + (t1 - t0)
      if (ierr /= 0) error stop 'exic-bench-legacy: step failed'
   end subroutine api_correct

end module bench_legacy_hooks
