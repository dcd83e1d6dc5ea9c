!> The handles of the legacy API: a registry of contact problems and the last error messages.
!>
!> The legacy API (src/exic/legacy/api.f90, capi.f90) is called from fixed-form Fortran 77 and
!> C hosts that can hold nothing but an integer between calls. The problems therefore live here,
!> in module variables that persist between calls: this registry is the one place in exic with
!> state kept across calls (house style forbids it everywhere else). Handles are positive
!> integers, handed out in increasing order and never reused, so a stale handle of a freed
!> problem is reported as unknown instead of reaching another problem. The registry is not
!> thread safe: a host that calls the API from several threads must serialize the calls.
module exic_legacy_registry
   use exic_base_kinds, only: wp
   use exic_contact_spec, only: contact_spec_t
   use exic_contact_contact, only: contact_t
   implicit none
   private

   public :: problem_t, slot_t
   public :: registry_add, registry_get, registry_free
   public :: set_error, last_message

   !> Error codes returned in `ierr` (documented in doc/api.md).
   integer, parameter, public :: IERR_OK = 0          !< success
   integer, parameter, public :: IERR_ARGUMENT = 1    !< an argument is out of range or not finite
   integer, parameter, public :: IERR_HANDLE = 2      !< the handle names no live problem
   integer, parameter, public :: IERR_SETUP = 3       !< surfaces or pairs cannot be built
   integer, parameter, public :: IERR_SOLVE = 4       !< the contact corrector failed in a step

   !> Velocity forms accepted by the step call (option 1).
   integer, parameter, public :: VEL_FULL_STEP = 1    !< v~(n+1) = v(n) + dt(n)/2 (a(n) + a~(n+1))
   integer, parameter, public :: VEL_HALF_STEP = 2    !< v(n+1/2) = v(n) + dt(n)/2 a(n) (DYNA form)

   !> One contact problem of a host: the host's arrays the contact object is built from (the
   !> contact spec, connectivity and body numbers, reference positions), the inverse masses, the
   !> contact object, and what the API keeps for queries. Arrays indexed by `k` run over
   !> `snodes`, the nodes of all contact surfaces (the only nodes whose data the contact code
   !> reads or writes).
   type :: problem_t
      integer :: nnode = 0
      integer :: npair = 0
      logical :: mesh_mode = .true.           !< built from connectivity (else from segments)
      type(contact_spec_t) :: spec            !< surfaces and pairs, as a deck's CONTact block
      integer :: nelem = 0                    !< elements given (0 when built from segments)
      integer, allocatable :: conn(:, :)      !< (4, nelem) the host's connectivity
      integer, allocatable :: body(:)         !< (nelem) the host's body numbers
      real(wp), allocatable :: x0(:, :)       !< (2, nnode) reference coordinates
      real(wp), allocatable :: minv(:, :)     !< (2, nnode) inverse mass per dof (0: rigid or fixed)
      type(contact_t) :: contact
      real(wp), allocatable :: mass(:, :)     !< (2, nnode) lumped masses per dof as given
      integer, allocatable :: fixed(:, :)     !< (2, nnode) non-zero: dof prescribed by the host
      logical, allocatable :: rigid(:)        !< (nnode) node of a rigid master
      integer, allocatable :: options(:, :)   !< (4, npair) method, detection, passes, rigid master
      integer, allocatable :: snodes(:)       !< (ns) contact surface nodes, ascending
      integer, allocatable :: spos(:)         !< (nnode) position of a node in snodes (0: none)
      real(wp), allocatable :: vt(:, :)       !< (2, nnode) predictor velocity (half-step form)
      real(wp), allocatable :: xprev(:, :)    !< (2, ns) positions at the previous step
      real(wp), allocatable :: fprev(:, :)    !< (2, ns) contact forces of the previous step
      real(wp), allocatable :: vprev(:, :)    !< (2, ns) velocities v(n) (for the contact work)
      real(wp), allocatable :: vhalf(:, :)    !< (2, ns) v(n+1/2) of the current step
      real(wp) :: c = 0.0_wp                  !< dt(n+1) (dt(n) + dt(n+1))/2 of the last step
      real(wp) :: wcon = 0.0_wp               !< work of the contact forces since creation
      real(wp) :: max_pen = 0.0_wp            !< largest penetration at t(n+1) since creation
      integer :: nsteps = 0                   !< step calls made
      integer :: velocity_form = VEL_FULL_STEP
      ! massless contact faces (method 3, doc/impact.md section 3): the host's face nodes and
      ! the rows of its initial stiffness for their dofs (CSR, sorted), kept to set the face up
      ! again when the contact object is rebuilt
      logical :: face_set = .false.
      integer, allocatable :: face(:)         !< (nf) face nodes
      logical, allocatable :: ffree(:, :)     !< (2, nf) the massless dofs of the face nodes
      integer, allocatable :: frp(:), fci(:)  !< (2 nf + 1), (nnz) rows and global dof columns
      real(wp), allocatable :: fval(:)        !< (nnz) values
      real(wp), allocatable :: zero(:, :)     !< (2, nnode) zeros: the internal force argument
      real(wp), allocatable :: xcor(:, :)     !< (2, ns) x(n+2) - x~(n+2) after the correction
      character(len=:), allocatable :: message !< message of the last failed call on this handle
   end type problem_t

   !> A registry slot; `p` is allocated while the handle is live.
   type :: slot_t
      type(problem_t), allocatable :: p
   end type slot_t

   type(slot_t), allocatable, target :: slots(:)     !< slot h holds handle h
   integer :: nhandles = 0                            !< handles handed out so far
   character(len=:), allocatable :: last_any          !< message of the last failed call of any kind

contains

   !> Store `p` under a new handle `h` (p is moved, unallocated on return).
   subroutine registry_add(p, h)
      type(problem_t), allocatable, intent(inout) :: p
      integer, intent(out) :: h
      type(slot_t), allocatable :: tmp(:)
      integer :: k
      if (.not. allocated(slots)) allocate (slots(8))
      if (nhandles == size(slots)) then
         allocate (tmp(2*size(slots)))
         do k = 1, nhandles
            if (allocated(slots(k)%p)) call move_alloc(slots(k)%p, tmp(k)%p)
         end do
         call move_alloc(tmp, slots)
      end if
      nhandles = nhandles + 1
      h = nhandles
      call move_alloc(p, slots(h)%p)
   end subroutine registry_add

   !> Pointer to the live problem of handle `h`, or null when `h` names none.
   function registry_get(h) result(p)
      integer, intent(in) :: h
      type(problem_t), pointer :: p
      p => null()
      if (h < 1 .or. h > nhandles) return
      if (.not. allocated(slots(h)%p)) return
      p => slots(h)%p
   end function registry_get

   !> Release handle `h` (no effect if it names no live problem).
   subroutine registry_free(h)
      integer, intent(in) :: h
      if (h < 1 .or. h > nhandles) return
      if (allocated(slots(h)%p)) deallocate (slots(h)%p)
   end subroutine registry_free

   !> Record `msg` as the last error, on handle `h` as well when it is live.
   subroutine set_error(h, msg)
      integer, intent(in) :: h
      character(len=*), intent(in) :: msg
      type(problem_t), pointer :: p
      last_any = msg
      p => registry_get(h)
      if (associated(p)) p%message = msg
   end subroutine set_error

   !> The last error of handle `h`, or of any call when `h` names no live problem ('' if none).
   function last_message(h) result(msg)
      integer, intent(in) :: h
      character(len=:), allocatable :: msg
      type(problem_t), pointer :: p
      msg = ''
      p => registry_get(h)
      if (associated(p)) then
         if (allocated(p%message)) msg = p%message
      else if (allocated(last_any)) then
         msg = last_any
      end if
   end function last_message

end module exic_legacy_registry
