!> The explicit state of a problem and its element sets, and plus_zero (is a nodal array +0 everywhere).
module exic_explicit_state
   use exic_base_kinds, only: wp, i8
   use exic_element_q4_general, only: q4_solid_t
   use exic_material_material, only: HOURGLASS_STIFFNESS
   use exic_material_law, only: law_t
   use exic_explicit_energy, only: energy_t
   implicit none
   private

   public :: element_set_t, state_t, plus_zero

   !> The elements of one material set. Nothing is stored per element but its nodes: the force
   !> kernels recompute the reference gradients from the reference coordinates.
   !>
   !> Threads work on ranges of consecutive elements; the ranges are coloured so that no two
   !> ranges of one colour share a node (src/exic/explicit/assembly.f90, set_ranges). Ranges of
   !> one colour add their forces concurrently, colours follow each other in a fixed order:
   !> every node receives its contributions in the same order for every number of threads.
   type :: element_set_t
      integer :: mat = 0                        !< material set number
      integer :: kind = 0                       !< MAT_SOLID or MAT_RIGID
      integer :: nq = 2                         !< 2: 2x2 Gauss; 1: one point + hourglass
      integer :: nel = 0
      integer, allocatable :: elems(:)          !< (nel) global element numbers
      integer, allocatable :: conn(:, :)        !< (4, nel) global node numbers
      type(law_t) :: law                        !< the material law (material/law.f90)
      real(wp) :: rho = 0.0_wp, hourglass = 0.0_wp
      integer :: hgkind = HOURGLASS_STIFFNESS   !< or HOURGLASS_PHYSICAL (doc/hourglass.md)
      integer :: nrange = 0                     !< ranges of consecutive elements
      integer, allocatable :: rfirst(:)         !< (nrange + 1) first element of each range
      integer :: ncolour = 0
      integer, allocatable :: cfirst(:)         !< (ncolour + 1) first entry of each colour in cranges
      integer, allocatable :: cranges(:)        !< (nrange) the ranges by colour, ascending in each
      !> The general solid path (doc/axisymmetry.md): axisymmetric and MIXEd sets and those whose
      !> law has a history run q4_general.f90 with `solid`; the others quad4.f90's kernels.
      logical :: general = .false.
      type(q4_solid_t) :: solid
      !> (nvar, nq*nq, nel) history of a set whose law has one (law_t%nvar: J2's Cp^-1, ep[, T],
      !> material/j2.f90; the hypoelastic F, stress, energy), changed only by the force pass;
      !> (1, 1, 1) otherwise
      real(wp), allocatable :: hist(:, :, :)
      !> DAMPing MASS c [t_end] (doc/damping.md, section 2): c (0: none), t_end, the set's nodes
      !> and their shares of the lumped mass (allocated only when c > 0)
      real(wp) :: damping = 0.0_wp, damping_end = huge(1.0_wp)
      integer, allocatable :: dnodes(:)
      real(wp), allocatable :: dmass(:)
      !> VISCosity BULK q1 q2 (doc/damping.md, section 3) and the dilatational wave speed;
      !> bulk_axi: an axisymmetric set (the volume per radian, section 3.1)
      logical :: bulk = .false., bulk_axi = .false.
      real(wp) :: q1 = 0.0_wp, q2 = 0.0_wp, wave = 0.0_wp
   end type element_set_t

   !> Nodal state at time t(n+1) with v(n+1), a(n+1) once a step is complete.
   type :: state_t
      integer :: nnode = 0, nelem = 0
      real(wp), allocatable :: x0(:, :)         !< (2, nnode) reference coordinates
      real(wp), allocatable :: u(:, :)          !< (2, nnode) displacement
      real(wp), allocatable :: v(:, :)          !< (2, nnode) velocity
      real(wp), allocatable :: a(:, :)          !< (2, nnode) acceleration
      real(wp), allocatable :: fint(:, :)       !< (2, nnode) internal force P(u)
      real(wp), allocatable :: fext(:, :)       !< (2, nnode) external force F
      !> every entry of fext is +0 (plus_zero), so that a plain step need not read it
      !> (cd_update_plain). False unless shown: whoever writes fext sets it again (assembly_init,
      !> loading_init, loading_forces, stepper_start, a restart); a host that writes fext
      !> sets it to plus_zero(fext) or .false.
      logical :: fext_zero = .false.
      real(wp), allocatable :: fcon(:, :)       !< (2, nnode) contact force of the last step (-G lambda)
      real(wp), allocatable :: mass(:)          !< (nnode) lumped mass (rigid nodes included)
      real(wp), allocatable :: minv(:, :)       !< (2, nnode) inverse mass per dof; 0: prescribed or rigid
      !> (2, nnode) lumped mass per dof, allocated only where the dofs of a node differ: massless
      !> contact faces along their normals (doc/impact.md, section 3.1); mass then holds the mean
      real(wp), allocatable :: mass_dof(:, :)
      logical, allocatable :: active(:)         !< (nnode) node used by an element
      logical, allocatable :: rigid(:)          !< (nnode) node of a rigid body
      integer, allocatable :: eset(:), eloc(:)  !< (nelem) element set and position in it
      real(wp) :: t = 0.0_wp
      real(wp) :: dt_prev = 0.0_wp              !< dt(n)   = t(n+1) - t(n)
      real(wp) :: dt = 0.0_wp                   !< dt(n+1) = t(n+2) - t(n+1)
      integer(i8) :: step = 0
      !> the energies and works of the balance (explicit/energy.f90)
      type(energy_t) :: energy
      !> (2, nnode) the nodal mass-damping and bulk-viscosity forces of the last force pass (part
      !> of fint; their work is booked by the trapezoid rule, doc/damping.md (D.5)); allocated
      !> only when a set has DAMPing or VISCosity BULK
      real(wp), allocatable :: gdamp(:, :), gbulk(:, :)
      ! the kinetic correction of the energy balance (doc/decisions.md, "Energy balance", eq. E.3-E.4)
      real(wp) :: body_power = 0.0_wp           !< the free bodies' m |A|^2 + I alpha^2
      !> Q's nodal part (cd_kinetic_power) of the state now, when the nodal state is divided among
      !> MPI ranks (doc/parallel.md): the folded sums of the ranks' chunks, the bits of the pass
      !> over every node, which one rank cannot make alone
      logical :: power_known = .false.
      real(wp) :: power_nodes = 0.0_wp
      real(wp) :: correction0 = 0.0_wp          !< the correction at t = 0
      real(wp) :: dt_residual = 0.0_wp          !< its sum over the changes of the step (E.4)
      real(wp) :: dt_booked = 0.0_wp            !< the step that sum is made for
      !> the energy guard's contact part of the correction (doc/loads.md, eq. P.5): its value at t = 0
      !> with the sign changed plus its sum over the changes of the step
      real(wp) :: contact_residual = 0.0_wp
      logical :: axisymmetric = .false.         !< GLOBal AXISymmetric: quantities per radian
      logical :: has_plastic = .false.          !< a set is plastic (outputs name ep, T, Y)
      real(wp) :: momentum(2) = 0.0_wp
      real(wp) :: jmin = 1.0_wp
      integer :: nactive = 0                    !< active contact constraints
      ! element erosion (doc/erosion.md); status allocated only when a material erodes
      integer, allocatable :: status(:)         !< (nelem) 0 live, else why it was eroded
      integer :: neroded = 0                    !< elements eroded so far
      real(wp) :: eroded_momentum(2) = 0.0_wp   !< momentum of the nodes that left
   end type state_t

contains

   !> True when every entry of f is +0 (-0 is not: 0 - x and -0 - x differ for x = +0).
   pure logical function plus_zero(f) result(yes)
      real(wp), intent(in) :: f(:, :)
      integer :: i, k
      yes = .false.
      do i = 1, size(f, 2)
         do k = 1, size(f, 1)
            if (f(k, i) /= 0.0_wp .or. sign(1.0_wp, f(k, i)) < 0.0_wp) return
         end do
      end do
      yes = .true.
   end function plus_zero

end module exic_explicit_state
