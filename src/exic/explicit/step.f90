!> The explicit time step: one object that owns the state, the element sets, the contact and
!> the step's work arrays, and performs the seed's sequence. Every caller steps through it: the
!> deck driver, the tests, the benchmarks, and hosts that bring their own contact through a hook.
!>
!> One `advance` (FORM,EXPLicit) is, with distinct dt(n) and dt(n+1) (doc/decisions.md):
!>   1. x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)                        (eq. 4.3-4.4)
!>   2. internal forces P(u(n+1)), strain energy                            (eq. 4.3, 7.2)
!>   3. dt(n+1) from the geometry at t(n+1) (CFL x stable estimate, or fixed)
!>   4. predictor a~ = M^-1 (F - P), v~ = v(n) + dt(n)/2 (a(n) + a~)        (eq. 4.3-4.4)
!>   5. contact corrector: a(n+1) = a~ + M^-1 G p, every active gap closed at t(n+2)  (4.5-4.7)
!>   6. v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1)); works of external and contact forces
!>   7. kinetic energy, momentum and the health check: a non-finite value stops the run naming
!>      its node and element; the energy guard warns when the physical energy exceeds the
!>      energy put in by `energy_warn` of it and stops past `energy_stop` (doc/decisions.md,
!>      "Energy guard")
!> `start` makes the state at t = 0 consistent first: forces, dt(0), a(0) with the corrector
!> acting on the initial velocity (bodies touching at t = 0 are caught at once).
!>
!> Loads that vary in time or follow the geometry, prescribed motion and rigid bodies with a
!> state (doc/loads.md) enter through `ld` (src/exic/explicit/loading.f90) at fixed points: after
!> steps 1, 2, 4, 5 and 6 and the kinetic energy of step 7; the work of the prescribed motion
!> counts as energy put in. A deck without them leaves `ld` inactive and steps exactly as before.
!>
!> The stepper writes no file: what it has to report it adds to `messages`.
module exic_explicit_step
   use exic_base_kinds, only: wp
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_base_constants, only: DEFAULT_CFL, TIME_TOL, ENERGY_WARN, ENERGY_STOP, ENERGY_FLOOR
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa, rtoa
   use exic_base_clock, only: wall_time
   use exic_base_flat, only: copy_flat
   use exic_base_messages, only: messages_t
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t, MAT_SOLID
   use exic_contact_spec, only: contact_spec_t
   use exic_contact_contact, only: contact_t
   use exic_explicit_state, only: state_t, element_set_t, plus_zero
   use exic_explicit_assembly, only: assembly_init, internal_forces, force_result_t, stable_step, kinetic_energy, &
                                     kinetic_correction, book_step_change, contact_correction, book_contact_change
   use exic_explicit_central, only: cd_displacement, cd_predictor, cd_velocity, cd_displacement_plain, &
                                    cd_update_plain, positions, positions_at, predictor_velocity_at
   use exic_explicit_loads, only: load_spec_t
   use exic_explicit_loading, only: loading_t
   use exic_explicit_face, only: face_setup, face_refresh
   use exic_explicit_decomposition, only: decomposition_t, decomposition_init, decomposition_forces, &
                                          decomposition_summary
   use exic_explicit_decomposition_nodes, only: nodes_init, nodes_displacement, nodes_update, &
                                                decomposition_gather_nodes
   use exic_explicit_erosion, only: erosion_t, erosion_init, erosion_before, erosion_after
   use exic_explicit_erosion_contact, only: erosion_contact_t, erosion_contact_init, erosion_contact_rebuild
   implicit none
   private

   public :: stepper_t, contact_hook_t, first_nonfinite

   !> The kernels of a step (advance_step): contact, loads or masses per dof; none of them; none
   !> of them with the nodes divided among MPI ranks.
   integer, parameter :: PATH_GENERAL = 1, PATH_PLAIN = 2, PATH_DIVIDED = 3

   !> Pass-limit warnings of the corrector written to the report; later ones are only counted.
   integer, parameter :: MAX_PASS_WARNINGS = 10

   !> Contact brought by a host instead of exic's own (the legacy API's hosts, in tests and
   !> benchmarks): called at step 5 with the same plain arrays as contact_t%correct.
   type, abstract :: contact_hook_t
   contains
      procedure(hook_correct), deferred :: correct
   end type contact_hook_t

   abstract interface
      !> x = x(n+1), vt = v~(n+1), a = a~(n+1) in, a(n+1) out, minv inverse mass per dof,
      !> dt_prev = dt(n), dt = dt(n+1); fcon = nodal contact forces, nactive = constraints in force.
      subroutine hook_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err)
         import :: contact_hook_t, wp, error_t
         class(contact_hook_t), intent(inout) :: self
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
         real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
         integer, intent(out) :: nactive
         type(error_t), allocatable, intent(out) :: err
      end subroutine hook_correct
   end interface

   !> A running explicit analysis.
   type :: stepper_t
      type(state_t) :: st
      type(element_set_t), allocatable :: sets(:)
      type(contact_t) :: contact                      !< exic's contact (inactive without CONTact)
      type(loading_t) :: ld                           !< loads, prescribed motion, rigid bodies
      class(contact_hook_t), pointer :: hook => null() !< a host's contact instead, when associated
      type(decomposition_t) :: dd                     !< the element pass on several MPI ranks (doc/parallel.md)
      type(messages_t) :: messages                    !< warnings for the run's report
      type(erosion_t) :: ero                          !< element erosion (doc/erosion.md)
      type(erosion_contact_t) :: eroc                 !< the contact surfaces it rebuilds
      logical :: started = .false.                    !< `start` has made the state at t = 0
      integer :: path = 0                             !< the kernels of a step (choose_path; 0: not yet)
      logical :: path_hook = .false.                  !< a host's hook was attached when it was chosen
      ! time-step control
      logical :: cfl_mode = .true.                    !< DT,CFL (else a fixed DT)
      real(wp) :: cfl = DEFAULT_CFL
      real(wp) :: dt_fixed = 0.0_wp
      real(wp) :: dt_stable = 0.0_wp                  !< last stable-step estimate
      integer :: dt_element = 0                       !< element that sets it (0: penalty or none)
      real(wp) :: dt_elements = 0.0_wp                !< the elements' estimate of the last force pass
      integer :: dt_elements_at = 0                   !< its element
      integer :: folded = 0                           !< first element folded at a corner in that pass
      real(wp) :: tmax = -1.0_wp                      !< end time to land on (TIME,,tmax; < 0: none)
      !> the end time that last shortened a step to land on it (-1: none yet): a state whose
      !> steps it shaped is not that of a run with a later end time (session/program_change.f90)
      real(wp) :: landed_tmax = -1.0_wp
      logical :: dt_warned = .false.
      ! energy guard: limits as fractions of the energy put in, and the worst growth seen
      real(wp) :: energy_warn = ENERGY_WARN
      real(wp) :: energy_stop = ENERGY_STOP
      logical :: energy_warned = .false.
      real(wp) :: growth_max = 0.0_wp                 !< largest growth / energy put in
      real(wp) :: growth_max_t = 0.0_wp               !< time of it
      !> largest (lambda + 2 mu)/rho of the solids: with the deformable mass, the round-off scale
      !> of the energy guard (energy_floor)
      real(wp) :: c2max = 0.0_wp
      !> the energy of round-off: ENERGY_FLOOR eps M c2max, M the deformable mass (doc/decisions.md,
      !> "Energy guard"); the guard measures growth against the energy put in or this, the larger
      real(wp) :: energy_floor = 0.0_wp
      integer :: pass_limit_warnings = 0              !< corrector pass-limit warnings written
      ! work arrays of a step, (2, nnode); allocated only for steps that are not plain (work_arrays)
      real(wp), allocatable :: x(:, :)                !< x(n+1) = x0 + u
      real(wp), allocatable :: du(:, :), a_old(:, :), vt(:, :), fcon_old(:, :)
      logical :: fcon_old_clean = .false.             !< fcon_old is zero everywhere
      ! wall time
      real(wp) :: time_forces = 0.0_wp                !< element loop and stable step
      real(wp) :: time_steps = 0.0_wp                 !< whole steps
   contains
      procedure :: init => stepper_init
      procedure :: start => stepper_start
      procedure :: advance => stepper_advance
      procedure :: set_cfl => stepper_set_cfl
      procedure :: set_fixed_dt => stepper_set_fixed_dt
      procedure :: set_velocity => stepper_set_velocity
      procedure :: set_energy_limits => stepper_set_energy_limits
      procedure :: initial_stable_step => stepper_initial_stable_step
      procedure :: has_contact => stepper_has_contact
   end type stepper_t

   interface
      !> Stop on a non-finite value, naming where it first appears; the energy guard
      !> (src/exic/explicit/step_health.f90).
      module subroutine check_health(self, err)
         type(stepper_t), intent(inout) :: self
         type(error_t), allocatable, intent(out) :: err
      end subroutine check_health
      !> The first node (and an element using it) whose displacement, velocity, acceleration,
      !> internal force or contact force is not finite (src/exic/explicit/step_health.f90).
      module function first_nonfinite(self) result(text)
         type(stepper_t), intent(in) :: self
         character(len=:), allocatable :: text
      end function first_nonfinite
   end interface

contains

   !> Element sets, state and contact of a mesh; `spec` inactive (the default) for no contact;
   !> `loads`: the deck's loads and prescribed motion (doc/loads.md), absent for none.
   subroutine stepper_init(self, mesh, materials, spec, err, loads)
      class(stepper_t), intent(inout) :: self
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(contact_spec_t), intent(in) :: spec
      type(error_t), allocatable, intent(out) :: err
      type(load_spec_t), intent(in), optional :: loads
      integer :: n, k, nface, ndof, nkept
      real(wp) :: modulus

      call assembly_init(mesh, materials, self%st, self%sets, err)
      if (allocated(err)) return
      call erosion_init(self%ero, self%st, self%sets, materials)
      call self%ld%init(mesh, materials, self%st, self%sets, err, loads)
      if (allocated(err)) return
      ! the nodal state is divided among the ranks when every step will be plain (no contact,
      ! loads or masses per dof) and no nodal sum runs over every node in order (the works of
      ! VISCosity BULK and DAMPing MASS): doc/parallel.md, "Divided nodes"
      call decomposition_init(self%dd, self%st, self%sets, mesh%conn, .not. (spec%active .or. self%ld%active .or. &
                              allocated(self%st%gbulk) .or. allocated(self%st%gdamp)), err)
      if (allocated(err)) return
      ! a numbering without locality (ranges of elements that reach far apart in the node
      ! numbers, as Gmsh's generation order) would have most blocks computed by several ranks:
      ! past a quarter of them, METIS parts of the blocks and the replicated nodal state instead
      if (self%dd%nodes .and. 4*self%dd%redundant > self%dd%nblock) then
         call self%messages%add('MPI: with the nodal state divided in chunk ranges, '//itoa(self%dd%redundant)// &
                                ' of the '//itoa(self%dd%nblock)//' element blocks would be computed by more '// &
                                'than one rank (the element and node numbers have little locality): the '// &
                                'nodal state stays replicated')
         call decomposition_init(self%dd, self%st, self%sets, mesh%conn, .false., err)
         if (allocated(err)) return
      end if
      if (self%dd%nodes) call nodes_init(self%dd, self%st, self%sets, err)
      if (allocated(err)) return
      if (self%dd%active) call self%messages%add(decomposition_summary(self%dd))
      n = self%st%nnode
      ! the work arrays of a step that is not plain (plain_step); contact_init reads x only when
      ! the contact is active, which such a step is
      if (spec%active .or. self%ld%active) call work_arrays(self)
      ! the contact's set-up (its start-up overlap test) sees the driven dofs at d p(0)
      if (allocated(self%x) .and. self%ld%active) call self%ld%place_initial(self%st, self%x)
      ! PENAlty,SCALe refers to the largest constrained modulus of the solids
      modulus = 0.0_wp
      do k = 1, size(materials)
         if (materials(k)%kind /= MAT_SOLID) cycle
         modulus = max(modulus, materials(k)%lambda + 2.0_wp*materials(k)%mu)
         if (materials(k)%rho > 0.0_wp) &
            self%c2max = max(self%c2max, (materials(k)%lambda + 2.0_wp*materials(k)%mu)/materials(k)%rho)
      end do
      if (allocated(self%x)) then
         call self%contact%init(spec, n, self%st%x0, self%x, mesh%nelem, mesh%conn, mesh%region, mesh%mat, &
                                modulus, err)
      else
         call self%contact%init(spec, n, self%st%x0, self%st%x0, mesh%nelem, mesh%conn, mesh%region, &
                                mesh%mat, modulus, err)
      end if
      if (allocated(err)) return
      if (self%ero%active) call erosion_contact_init(self%eroc, spec, mesh, modulus, err)
      if (allocated(err)) return
      if (self%contact%energy) then
         ! LAGRange,ENERgy: massless contact faces (doc/impact.md, section 3)
         call face_setup(self%st, self%sets, self%contact, nface, ndof, nkept, err)
         if (allocated(err)) return
         call self%messages%add('LAGRange,ENERgy: '//itoa(nface)//' massless face nodes, '//itoa(ndof)// &
                                ' massless dofs (a face that meets a deformable body along its normals '// &
                                'only), '//itoa(nkept)// &
                                ' surface nodes keep their mass (rigid, prescribed, or in elements '// &
                                'with every node on the face)')
      end if
      ! st%fcon is written by the contact only, so it need not be zeroed where it is zero
      self%contact%keep_fcon = .true.
   end subroutine stepper_init

   !> Contact acts in the step (exic's own or a host's).
   pure logical function stepper_has_contact(self) result(on)
      class(stepper_t), intent(in) :: self
      on = associated(self%hook) .or. self%contact%active
   end function stepper_has_contact

   !> The state at t = 0: forces, dt(0) and the contact-corrected a(0). Does nothing twice.
   subroutine stepper_start(self, err)
      class(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err

      if (self%started) return
      self%started = .true.
      if (self%ld%has_free .and. associated(self%hook)) then
         call make_error(err, 'free rigid bodies need exic''s own contact, not a host''s contact hook')
         return
      end if
      call self%ld%begin(self%st)
      self%st%fext_zero = plus_zero(self%st%fext)
      call choose_path(self, err)
      if (allocated(err)) return
      call forces_and_dt(self, err)
      ! divided nodes: the owners' forces to every rank, which then makes the state at t = 0 as
      ! the serial program does
      self%dd%whole = .false.
      call decomposition_gather_nodes(self%dd, self%st)
      if (allocated(err)) return
      associate (st => self%st)
         if (self%ld%active) call self%ld%forces(st, self%x, .true.)
         st%a = st%minv*(st%fext - st%fint)
         ! at t(0) the predictor velocity is the initial velocity itself and
         ! x(1) = x(0) + dt v(0) + dt^2/2 a(0): the corrector's c is dt^2/2 (dt(n) = 0)
         st%dt_prev = 0.0_wp
         if (self%ld%active) then
            self%vt = st%v
            call self%ld%predict(st, self%vt, 0.0_wp)
            st%v = self%vt
         end if
         call correct(self, st%v, err)
         if (allocated(err)) return
         if (self%ld%active) then
            call self%ld%corrected(st)
            call self%ld%finish(st, self%du, 0.0_wp, .true.)
         end if
         call kinetic_energy(st)
         if (self%ld%active) call self%ld%energy(st)
         st%energy%total0 = st%energy%physical()
         self%energy_floor = ENERGY_FLOOR*epsilon(1.0_wp)*self%c2max*sum(st%mass, mask=st%active .and. .not. st%rigid)
         ! the kinetic correction at t = 0, for the step dt(0) (doc/decisions.md, eq. E.3-E.4)
         st%dt_residual = 0.0_wp
         st%correction0 = 0.0_wp
         st%dt_booked = st%dt
         st%correction0 = kinetic_correction(st)
         ! the energy guard's contact part of the correction starts from the state before the
         ! start's corrector: its kick at t = 0 is the first capture (doc/loads.md, eq. P.5)
         st%contact_residual = 0.0_wp
      end associate
      call check_health(self, err)
   end subroutine stepper_start

   !> One explicit step (FORM,EXPLicit), steps 1-7 of the module header. With the nodal state
   !> divided among ranks, an error (which comes from the state, on every rank at the same step)
   !> returns with the whole state gathered, for the outputs of the failure.
   subroutine stepper_advance(self, err)
      class(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      call advance_step(self, err)
      if (allocated(err)) call decomposition_gather_nodes(self%dd, self%st)
   end subroutine stepper_advance

   !> stepper_advance's step: steps 1-7 of the module header, on the kernels of the path chosen
   !> once (choose_path): PATH_GENERAL (contact, loads or masses per dof: the predictor, the
   !> corrector and the velocity update apart), PATH_PLAIN (none of them: steps 4, 6 and 7's
   !> kinetic energy in one sweep over the nodes) or PATH_DIVIDED (that sweep on this rank's node
   !> chunks, doc/parallel.md "Divided nodes").
   subroutine advance_step(self, err)
      type(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: t0, t1, qnodes
      logical :: power_q

      t0 = wall_time()
      ! chosen at the start; a host's contact hook attached or removed since then changes it
      if (self%path == 0 .or. (associated(self%hook) .neqv. self%path_hook)) call choose_path(self, err)
      if (allocated(err)) return
      ! a step set between steps (BATCh DT) enters the kinetic correction (eq. E.4)
      if (guard_contact(self)) call book_contact_change(self%st)
      call book_step_change(self%st)
      ! 1. x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)
      call displacement(self)
      ! 2-3. forces and dt(n+1) at t(n+1)
      t1 = wall_time()
      call forces_and_dt(self, err)
      self%time_forces = self%time_forces + (wall_time() - t1)
      if (allocated(err)) return
      if (self%ld%active) call self%ld%forces(self%st, self%x, .false.)
      if (self%path == PATH_GENERAL) then
         ! 4. predictor, eq. 4.3-4.4
         call predict(self)
         ! 5. contact corrector, eq. 4.5-4.7
         call correct(self, self%vt, err)
         if (allocated(err)) return
         if (self%ld%active) call self%ld%corrected(self%st)
         ! 6. v(n+1) and the works of the external and contact forces
         call velocity(self)
         ! 7. kinetic energy
         call kinetic_energy(self%st)
         power_q = .false.
      else
         ! 4-6 and 7's kinetic energy in one sweep; the corrector has nothing to do
         call correct(self, self%st%v, err)
         if (allocated(err)) return
         call plain_update(self, power_q, qnodes)
      end if
      ! 7. energies of the bodies and health; dt(n+1) enters the kinetic correction (eq. E.4)
      if (self%ld%active) call self%ld%energy(self%st)
      if (guard_contact(self)) call book_contact_change(self%st)
      if (power_q) then
         call book_step_change(self%st, qnodes)
      else
         call book_step_change(self%st)
      end if
      self%time_steps = self%time_steps + (wall_time() - t0)
      call check_health(self, err)
   end subroutine advance_step

   !> The energy guard measures the contact part of the kinetic correction: loads or prescribed
   !> motion and contact (doc/loads.md, section 3, eq. P.5).
   pure logical function guard_contact(self) result(yes)
      type(stepper_t), intent(in) :: self
      yes = self%ld%active .and. self%has_contact()
   end function guard_contact

   !> The kernels of the steps to come, from what the model has (contact, loads, masses per dof,
   !> divided nodes, a host's hook): chosen at the start and when a hook is attached.
   subroutine choose_path(self, err)
      type(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      self%path_hook = associated(self%hook)
      if (.not. plain_step(self)) then
         if (self%dd%nodes) then
            call make_error(err, 'a step with contact, loads or masses per dof on several MPI ranks whose nodal '// &
                            'state is divided (a contact hook attached after the start)')
            return
         end if
         self%path = PATH_GENERAL
         call work_arrays(self)
      else if (self%dd%nodes) then
         self%path = PATH_DIVIDED
      else
         self%path = PATH_PLAIN
      end if
   end subroutine choose_path

   !> Step 1: x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n) (eq. 4.3-4.4), the clock, fcon(n) kept
   !> for the contact work of step 6, and the prescribed motion placed.
   subroutine displacement(self)
      type(stepper_t), intent(inout) :: self
      associate (st => self%st)
         select case (self%path)
         case (PATH_DIVIDED)
            call nodes_displacement(self%dd, st)
         case (PATH_PLAIN)
            call cd_displacement_plain(st%nnode, st%dt, st%v, st%a, st%u)
         case default
            call cd_displacement(st%nnode, st%dt, st%v, st%a, st%u, self%du, self%a_old)
         end select
         st%t = st%t + st%dt
         st%dt_prev = st%dt
         st%step = st%step + 1
         ! fcon_old = fcon(n): no copy while both are zero (no contact force in either step); a
         ! flat copy (an assignment of these (2, n) components loops twice, about 10 instructions a value)
         if (self%has_contact() .and. .not. (self%fcon_old_clean .and. fcon_clean(self))) &
            call copy_flat(size(st%fcon), st%fcon, self%fcon_old)
         self%fcon_old_clean = fcon_clean(self)
         if (self%ld%active) call self%ld%place(st, self%du)
      end associate
   end subroutine displacement

   !> Step 4: a~ = M^-1 (F - P), v~ = v(n) + dt(n)/2 (a(n) + a~) (eq. 4.3-4.4); v~ only when there
   !> is contact to search, and exic's own contact without loads reads it at its surface nodes only.
   subroutine predict(self)
      type(stepper_t), intent(inout) :: self
      associate (st => self%st)
         call cd_predictor(st%nnode, st%dt_prev, st%minv, st%fext, st%fint, st%v, self%a_old, st%a, &
                           self%has_contact() .and. .not. surface_only(self), self%vt)
         if (surface_only(self)) call predictor_velocity_at(st%nnode, st%dt_prev, st%v, self%a_old, st%a, &
                                                            self%contact%cnodes, self%vt)
         if (self%ld%active) call self%ld%predict(st, self%vt, 0.5_wp*st%dt_prev)
      end associate
   end subroutine predict

   !> Step 6: v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1)) and the works of the external and contact
   !> forces over the step (trapezoid rule); without a contact force at t(n) and t(n+1) the
   !> contact work's sum is +0 term by term and is skipped (the same bits).
   subroutine velocity(self)
      type(stepper_t), intent(inout) :: self
      logical :: work_con
      associate (st => self%st)
         work_con = self%has_contact() .and. .not. (self%fcon_old_clean .and. fcon_clean(self))
         if (self%ld%varying) then
            ! loads that vary in time: the trapezoid rule 1/2 (F(n) + F(n+1)) . du
            call cd_velocity(st%nnode, st%dt_prev, self%a_old, st%a, self%ld%favg, self%du, work_con, &
                             self%fcon_old, st%fcon, st%minv, st%v, st%energy%wext, st%energy%wcon)
         else
            call cd_velocity(st%nnode, st%dt_prev, self%a_old, st%a, st%fext, self%du, work_con, &
                             self%fcon_old, st%fcon, st%minv, st%v, st%energy%wext, st%energy%wcon)
         end if
         if (self%ld%active) call self%ld%finish(st, self%du, 0.5_wp*st%dt_prev, .false.)
      end associate
   end subroutine velocity

   !> Steps 4, 6 and 7's kinetic energy of a plain step in one sweep over the nodes, which forms
   !> du and reads a(n) where the other steps store them (the same operations in the same
   !> order). power_q: dt(n+1) differs from the booked step, and qnodes, Q of eq. E.3, comes from
   !> the same sweep, chunk by chunk, instead of another pass over the nodes (the same bits).
   subroutine plain_update(self, power_q, qnodes)
      type(stepper_t), intent(inout) :: self
      logical, intent(out) :: power_q
      real(wp), intent(out) :: qnodes
      associate (st => self%st)
         power_q = st%dt /= st%dt_booked
         qnodes = 0.0_wp
         if (self%path == PATH_DIVIDED) then
            ! this rank's chunks; the chunks' sums folded on every rank (the serial bits)
            call nodes_update(self%dd, st, qnodes)
         else if (power_q) then
            call cd_update_plain(st%nnode, st%dt_prev, st%minv, st%fext, st%fext_zero, st%fint, st%mass, &
                                 st%a, st%v, st%energy%wext, st%energy%kinetic, st%momentum, qnodes)
         else
            call cd_update_plain(st%nnode, st%dt_prev, st%minv, st%fext, st%fext_zero, st%fint, st%mass, &
                                 st%a, st%v, st%energy%wext, st%energy%kinetic, st%momentum)
         end if
      end associate
   end subroutine plain_update

   !> Steps 2-3 (and at t = 0): internal forces and, from the same pass over the elements, their
   !> stable step at x = x0 + u; dt(n+1); the positions x = x0 + u when contact or loads (edge
   !> loads follow the geometry) need them. An
   !> inverted element is an error naming it.
   subroutine forces_and_dt(self, err)
      type(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      type(force_result_t) :: res
      associate (st => self%st)
         if (surface_only(self)) then
            call positions_at(st%nnode, st%x0, st%u, self%contact%cnodes, self%x)
         else if (self%has_contact() .or. self%ld%active) then
            call positions(st%nnode, st%x0, st%u, self%x)
         end if
         if (self%ero%active) call erosion_before(self%ero, st, self%sets, self%messages, self%a_old)
         if (self%dd%active) then
            call decomposition_forces(self%dd, st, self%sets, res)
         else
            call internal_forces(st, self%sets, res)
         end if
         self%dt_elements = res%dt
         self%dt_elements_at = res%emin
         self%folded = res%efold
         if (res%ebad /= 0) then
            call inverted_error(st, res%ebad, err)
            return
         end if
         if (self%ero%active) call eroded(self, err)
         if (allocated(err)) return
         call choose_dt(self, err, 'DT')
      end associate
   end subroutine forces_and_dt

   !> After the force pass: the erosions it decides (doc/erosion.md (R2)); after any erosion, the
   !> contact surfaces from the live elements and the positions of their nodes.
   subroutine eroded(self, err)
      type(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      associate (st => self%st)
         call erosion_after(self%ero, st, self%sets, self%dt_elements, self%dt_elements_at, self%folded, &
                            self%messages)
         if (.not. self%ero%changed) return
         self%ero%changed = .false.
         if (.not. self%contact%active) return
         call erosion_contact_rebuild(self%eroc, self%contact, st, err)
         if (allocated(err)) return
         self%contact%keep_fcon = .true.
         call positions(st%nnode, st%x0, st%u, self%x)
      end associate
   end subroutine eroded

   !> True when a step has no contact, loads or masses per dof: it sweeps the nodes twice
   !> (cd_displacement_plain, cd_update_plain) and reads none of the work arrays x, du, a_old, v~
   !> and fcon_old.
   pure logical function plain_step(self) result(plain)
      type(stepper_t), intent(in) :: self
      plain = .not. (self%has_contact() .or. self%ld%active .or. allocated(self%st%mass_dof))
   end function plain_step

   !> Allocate the work arrays of a step that is not plain (zero, x = x0 + u) if they are not yet:
   !> at set-up with contact or loads, else at the first such step (a host's contact hook
   !> attached later). 80 bytes per node that a plain run never touches.
   subroutine work_arrays(self)
      type(stepper_t), intent(inout) :: self
      integer :: n
      if (allocated(self%x)) return
      n = self%st%nnode
      allocate (self%x(2, n), self%du(2, n), self%a_old(2, n), self%vt(2, n), self%fcon_old(2, n), &
                source=0.0_wp)
      call positions(n, self%st%x0, self%st%u, self%x)
   end subroutine work_arrays

   !> True when the step needs x and v~ at the contact surfaces' nodes only: exic's own contact
   !> (it reads no other node) and no loads, prescribed motion or rigid bodies (which read all),
   !> nor massless contact faces (their free solve reads the nodes next to them, doc/impact.md).
   pure logical function surface_only(self) result(yes)
      type(stepper_t), intent(in) :: self
      yes = self%contact%active .and. .not. associated(self%hook) .and. .not. self%ld%active .and. &
            .not. self%contact%face%active
   end function surface_only

   !> True when exic's own contact left st%fcon zero everywhere at its last call (a host's hook:
   !> never known).
   pure logical function fcon_clean(self) result(clean)
      type(stepper_t), intent(in) :: self
      clean = .not. associated(self%hook) .and. self%contact%active .and. self%contact%fcon_clean
   end function fcon_clean

   !> Step 5: the corrector of exic's contact or of the host's hook, on the positions self%x.
   subroutine correct(self, vt, err)
      type(stepper_t), intent(inout) :: self
      real(wp), intent(in) :: vt(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer :: hits, fhits
      hits = self%contact%corr%pass_limit_hits
      fhits = self%contact%fr%sweep_limit_hits + self%contact%fr%pass_limit_hits
      associate (st => self%st)
         st%nactive = 0
         ! massless contact faces: the face rows at the current strains when they moved far
         ! from those the face block was factorized at (doc/impact.md, section 3.2)
         call face_refresh(st, self%sets, self%contact, err)
         if (allocated(err)) return
         if (associated(self%hook)) then
            call self%hook%correct(st%nnode, self%x, vt, st%a, st%minv, st%dt_prev, st%dt, st%fcon, &
                                   st%nactive, err)
         else if (self%contact%active .and. self%ld%has_free) then
            call self%contact%correct(st%nnode, self%x, vt, st%a, st%minv, st%dt_prev, st%dt, st%fcon, &
                                      st%nactive, err, self%ld%rb, st%fext, st%fint)
         else if (self%contact%active) then
            call self%contact%correct(st%nnode, self%x, vt, st%a, st%minv, st%dt_prev, st%dt, st%fcon, &
                                      st%nactive, err, fext=st%fext, fint=st%fint)
         end if
         if (self%contact%corr%pass_limit_hits > hits) then
            self%pass_limit_warnings = self%pass_limit_warnings + 1
            if (self%pass_limit_warnings <= MAX_PASS_WARNINGS) &
               call self%messages%add('warning: the contact corrector reached its pass limit at step '// &
                                      itoa(int(st%step))//', t = '//rtoa(st%t)//'; the last set of '// &
                                      'compressive multipliers was kept')
            if (self%pass_limit_warnings == MAX_PASS_WARNINGS) &
               call self%messages%add('warning: further pass-limit warnings are only counted (<stem>.out, '// &
                                      'contact statistics)')
         else if (self%contact%fr%sweep_limit_hits + self%contact%fr%pass_limit_hits > fhits) then
            ! the frictional corrector did not converge (doc/friction.md, section 4)
            self%pass_limit_warnings = self%pass_limit_warnings + 1
            if (self%pass_limit_warnings <= MAX_PASS_WARNINGS) &
               call self%messages%add('warning: the frictional corrector reached its sweep or pass limit at '// &
                                      'step '//itoa(int(st%step))//', t = '//rtoa(st%t)//'; the last '// &
                                      'multipliers within the friction bounds were kept')
         end if
      end associate
   end subroutine correct

   !> DT,CFL,c: the step is c x the stable estimate from now on (c <= 0: the default).
   subroutine stepper_set_cfl(self, c, where, err)
      class(stepper_t), intent(inout) :: self
      real(wp), intent(in) :: c
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(out) :: err
      self%cfl_mode = .true.
      self%cfl = c
      if (self%cfl <= 0.0_wp) self%cfl = DEFAULT_CFL
      if (self%started) call choose_dt(self, err, where)
   end subroutine stepper_set_cfl

   !> DT,,dt: a fixed step from now on (checked against the stable estimate).
   subroutine stepper_set_fixed_dt(self, dt, where, err)
      class(stepper_t), intent(inout) :: self
      real(wp), intent(in) :: dt
      character(len=*), intent(in) :: where
      type(error_t), allocatable, intent(out) :: err
      self%cfl_mode = .false.
      self%dt_fixed = dt
      if (self%started) call choose_dt(self, err, where)
   end subroutine stepper_set_fixed_dt

   !> INITial velocities: v = data on the nodes `given`, then zero again on prescribed dofs and
   !> massless nodes (rigid bodies keep theirs).
   subroutine stepper_set_velocity(self, given, data)
      class(stepper_t), intent(inout) :: self
      logical, intent(in) :: given(:)
      real(wp), intent(in) :: data(:, :)
      call decomposition_gather_nodes(self%dd, self%st)
      associate (st => self%st)
         where (spread(given, 1, 2)) st%v = data
         where (st%minv == 0.0_wp .and. .not. spread(st%rigid, 1, 2)) st%v = 0.0_wp
         call self%ld%velocities_set(st, self%started)
         if (self%started) call kinetic_energy(st)
         if (self%started .and. self%ld%active) call self%ld%energy(st)
      end associate
   end subroutine stepper_set_velocity

   !> CHECk,ENERgy,warn,stop: the energy guard's limits (fractions of the energy put in).
   subroutine stepper_set_energy_limits(self, warn, stop)
      class(stepper_t), intent(inout) :: self
      real(wp), intent(in) :: warn, stop
      self%energy_warn = warn
      self%energy_stop = stop
   end subroutine stepper_set_energy_limits

   !> Stable step of the mesh as it is now (before `start`: the initial mesh) and its element.
   subroutine stepper_initial_stable_step(self, dtmin, emin)
      class(stepper_t), intent(inout) :: self
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin
      integer :: efold
      real(wp), allocatable :: x(:, :)
      call decomposition_gather_nodes(self%dd, self%st)
      if (allocated(self%x)) then
         call positions(self%st%nnode, self%st%x0, self%st%u, self%x)
         call stable_step(self%st, self%sets, self%x, dtmin, emin, efold)
      else
         allocate (x(2, self%st%nnode))
         call positions(self%st%nnode, self%st%x0, self%st%u, x)
         call stable_step(self%st, self%sets, x, dtmin, emin, efold)
      end if
   end subroutine stepper_initial_stable_step

   !> Set dt(n+1): fixed (checked against the stable limit) or CFL x the stable limit, from the
   !> elements' estimate of the last force pass (the current geometry).
   subroutine choose_dt(self, err, where)
      type(stepper_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in) :: where
      character(len=200) :: buf
      integer :: n
      real(wp) :: target, dtp

      associate (st => self%st)
         self%dt_stable = self%dt_elements
         self%dt_element = self%dt_elements_at
         if (self%folded /= 0) then
            call make_error(err, 'element '//itoa(self%folded)//' inverted (J <= 0 at a corner: folded) at t = '// &
                            rtoa(st%t)//', step '//itoa(int(st%step)))
            return
         end if
         if (.not. (self%dt_stable > 0.0_wp .and. ieee_is_finite(self%dt_stable)) .and. &
             self%dt_stable < huge(1.0_wp)) then
            call make_error(err, 'the stable step of element '//itoa(self%dt_element)//' is '// &
                            rtoa(self%dt_stable)//' at t = '//rtoa(st%t)//', step '//itoa(int(st%step)))
            return
         end if
         if (self%contact%any_penalty) then
            ! a penalty spring adds its frequency to that of the elements at its nodes:
            ! omega^2 <= omega_elements^2 + omega_penalty^2, i.e. 1/dt^2 adds up
            dtp = self%contact%stable_dt(st%nnode, st%minv)
            if (dtp < huge(1.0_wp)) then
               self%dt_stable = 1.0_wp/sqrt(1.0_wp/self%dt_stable**2 + 1.0_wp/dtp**2)
               self%dt_element = 0
            end if
         end if
         if (self%cfl_mode) then
            if (self%dt_stable >= huge(1.0_wp)) then
               call make_error(err, 'DT,CFL needs at least one deformable element to set the step', where)
               return
            end if
            ! Hysteresis: the step shrinks at once when the stable step falls below it, and grows
            ! only when it is more than 15 % below c x the stable step. A step that followed every
            ! breath of the mesh would vary in time with the motion, and such a modulated
            ! central-difference step pumps energy into the mode that modulates it.
            target = self%cfl*self%dt_stable
            if (st%dt <= 0.0_wp .or. st%dt > target .or. st%dt < 0.85_wp*target) st%dt = target
            ! land exactly on tmax with steps no larger than the stable one
            if (self%tmax > st%t) then
               n = ceiling((self%tmax - st%t)/st%dt*(1.0_wp - TIME_TOL))
               if (n >= 1 .and. n <= 4) then
                  if ((self%tmax - st%t)/real(n, wp) /= st%dt) self%landed_tmax = self%tmax
                  st%dt = (self%tmax - st%t)/real(n, wp)
               end if
            end if
         else
            if (self%dt_fixed <= 0.0_wp) then
               call make_error(err, 'DT,,dt needs a positive step', where)
               return
            end if
            st%dt = self%dt_fixed
            if (self%dt_fixed > self%dt_stable) then
               if (self%dt_element > 0) then
                  buf = ' (element '//itoa(self%dt_element)//')'
               else
                  buf = ' (contact penalty)'
               end if
               buf = 'DT = '//rtoa(self%dt_fixed)//' exceeds the stable limit '//rtoa(self%dt_stable)// &
                     trim(buf)//'; use a smaller DT or DT,CFL,c'
               if (.not. self%started .or. st%step == 0) then
                  call make_error(err, trim(buf), where)
               else if (.not. self%dt_warned) then
                  self%dt_warned = .true.
                  call self%messages%add('warning: at t = '//rtoa(st%t)//': '//trim(buf))
               end if
            end if
         end if
      end associate
   end subroutine choose_dt

   !> The error for an element whose Jacobian is no longer positive.
   subroutine inverted_error(st, ebad, err)
      type(state_t), intent(in) :: st
      integer, intent(in) :: ebad
      type(error_t), allocatable, intent(out) :: err
      call make_error(err, 'element '//itoa(ebad)//' inverted (J <= 0) at t = '// &
                      rtoa(st%t)//', step '//itoa(int(st%step)))
   end subroutine inverted_error

end module exic_explicit_step
