!> Loads, prescribed motion and rigid bodies in the time step (doc/loads.md): what the stepper
!> (src/exic/explicit/step.f90) calls at fixed points of its sequence.
!>
!>   begin      at t = 0, before the first forces: u(0) of prescribed displacements, the bodies'
!>              initial velocities
!>   place      after step 1 (t = t(n+1)): prescribed displacements, bodies placed
!>   forces     after step 2: fext(t(n+1)) on the current geometry, when loads vary
!>   predict    after step 4: prescribed v(n+1), a(n+1); free bodies' predictor (eq. 4.3-4.4)
!>   corrected  after step 5: free bodies' share of the contact forces (doc/loads.md, section 5)
!>   finish     after step 6: prescribed v, a; bodies' velocities; the work of the prescribed
!>              motion (W_pm, trapezoid rule)
!>   energy     after step 7's kinetic energy: the free bodies' kinetic energy and momentum
!>
!> `active` is false when a deck uses none of this: the stepper then calls nothing and runs
!> exactly as before (the same operations in the same order).
module exic_explicit_loading
   use exic_base_kinds, only: wp
   use exic_base_sort, only: sort_short_int
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t, MAT_SOLID, MAT_RIGID
   use exic_element_quad4, only: q4_lumped_mass
   use exic_element_q4_rigid, only: q4_mass_moments
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_explicit_state, only: state_t, element_set_t, plus_zero
   use exic_explicit_loads, only: load_spec_t, prop_value, edge_forces, FN_UNDEFINED
   use exic_explicit_rigid, only: rigid_body_t, RB_PLAIN, RB_DRIVEN, RB_FREE, rigid_place, &
                                  rigid_levers, rigid_gather, rigid_node_motion, rigid_fit_velocity
   implicit none
   private

   public :: loading_t, reaction

   !> Loads and prescribed motion of a running analysis.
   type :: loading_t
      logical :: active = .false.                !< something to do in the step
      logical :: varying = .false.               !< fext is formed at every step
      logical :: has_free = .false.              !< free rigid bodies (coupled in the corrector)
      logical :: track_work = .false.            !< W_pm is booked (a prescribed dof can move)
      type(load_spec_t) :: spec
      integer :: nfn = 0                         !< functions 1..nfn (some may be undefined)
      real(wp), allocatable :: pv(:, :)          !< (3, 0:nfn) p, p', p'' at the current time
      logical :: any_body = .false., any_grav = .false.
      ! the nodal arrays below are allocated only for decks whose steps read them
      real(wp), allocatable :: fnode(:, :)       !< (2, nnode) FORCe values (varying loads)
      real(wp), allocatable :: fbody(:, :)       !< (2, nnode) BODY forces (fn 0; varying loads)
      real(wp), allocatable :: fgrav(:, :)       !< (2, nnode) gravity (its fn; varying loads)
      real(wp), allocatable :: fedge(:, :)       !< (2, nnode) edge loads of the step
      real(wp), allocatable :: fext_old(:, :)    !< (2, nnode) fext(n)
      real(wp), allocatable :: favg(:, :)        !< (2, nnode) 1/2 (fext(n) + fext(n+1)) for the work
      real(wp), allocatable :: vold(:, :)        !< (2, nnode) v(n) in the step (varying loads, W_pm)
      !> the works of the varying loads and of the prescribed motion by the trapezoid rule of the
      !> power, dt 1/2 (F(n) + F(n+1)) . 1/2 (v(n) + v(n+1)): the energy guard's second estimate
      real(wp) :: wext_p = 0.0_wp, wpm_p = 0.0_wp
      integer, allocatable :: fpro(:, :)         !< (2, nnode) function of each dof (0: the sum;
                                                 !< varying loads, DISPlacements under functions)
      ! DISPlacement under functions
      integer :: ndisp = 0
      integer, allocatable :: dnode(:), ddof(:)
      real(wp), allocatable :: dval(:)
      ! MOTIon of deformable regions: node and motion
      integer :: nmove = 0
      integer, allocatable :: mnode(:), mmot(:)
      ! rigid bodies
      type(rigid_body_t), allocatable :: bodies(:)
      integer, allocatable :: body_of(:)         !< (nnode) body of each node, 0: none
      real(wp), allocatable :: wlump(:)          !< (nnode) lumped masses of free bodies' nodes
      type(rigid_dofs_t) :: rb                   !< free bodies for the corrector; rb%r: lever arms
                                                 !< (set up when a body is free or driven)
      ! the work of the prescribed motion: every prescribed dof and its last reaction
      integer :: npres = 0
      integer, allocatable :: pnode(:), pdof(:)
      real(wp), allocatable :: rold(:)
   contains
      procedure :: init => loading_init
      procedure :: begin => loading_begin
      procedure :: place_initial => loading_place_initial
      procedure :: place => loading_place
      procedure :: forces => loading_forces
      procedure :: predict => loading_predict
      procedure :: corrected => loading_corrected
      procedure :: finish => loading_finish
      procedure :: energy => loading_energy
      procedure :: velocities_set => loading_velocities_set
      procedure :: body_index => loading_body_index
      procedure :: work_in => loading_work_in
   end type loading_t

contains

   !> Set up from the mesh, the materials, the deck's loads (`spec`, absent: none) and the state
   !> and element sets that assembly_init made. Free bodies take over their nodes' masses.
   subroutine loading_init(self, mesh, materials, st, sets, err, spec)
      class(loading_t), intent(inout) :: self
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(error_t), allocatable, intent(out) :: err
      type(load_spec_t), intent(in), optional :: spec
      integer :: n, ndef, i, k, j
      logical :: moving

      n = st%nnode
      if (present(spec)) self%spec = spec
      self%nfn = 0
      if (allocated(self%spec%fn)) self%nfn = size(self%spec%fn)
      if (.not. allocated(self%spec%fn)) allocate (self%spec%fn(0))
      allocate (self%pv(3, 0:self%nfn), source=0.0_wp)
      self%pv(1, 0) = 1.0_wp
      allocate (self%fpro(2, n), source=0)
      if (allocated(self%spec%fpro)) self%fpro = self%spec%fpro
      ndef = count(self%spec%fn%kind /= FN_UNDEFINED)
      call body_and_gravity(self, materials, st, sets)
      self%varying = self%spec%nedge > 0 .or. (ndef > 0 .and. (any(mesh%force /= 0.0_wp) .or. &
                                                              self%any_body .or. self%any_grav))
      ! nodal arrays only where the step reads them (doc/performance.md 6.2, "Bytes per element")
      if (.not. self%varying) then
         ! constant loads: formed once (with no function every factor is 1)
         if (self%any_body) st%fext = st%fext + self%fbody
         if (self%any_grav) st%fext = st%fext + self%fgrav
         if (allocated(self%fbody)) deallocate (self%fbody)
         if (allocated(self%fgrav)) deallocate (self%fgrav)
         st%fext_zero = plus_zero(st%fext)
      else
         self%fnode = mesh%force
         allocate (self%fedge(2, n), self%fext_old(2, n), self%favg(2, n), source=0.0_wp)
      end if
      call make_bodies(self, mesh, materials, st, sets, err)
      if (allocated(err)) return
      ! MOTIon of deformable regions (the reader gave their nodes boundary codes)
      allocate (self%mnode(0), self%mmot(0))
      if (allocated(self%spec%motions)) then
         do j = 1, size(self%spec%motions)
            if (self%spec%motions(j)%rigid) cycle
            call add_motion_nodes(self, mesh, j)
         end do
      end if
      ! prescribed displacements under functions
      allocate (self%dnode(0), self%ddof(0), self%dval(0))
      if (ndef > 0) then
         do i = 1, n
            if (.not. st%active(i) .or. st%rigid(i)) cycle
            if (any(self%mnode == i)) cycle
            do k = 1, 2
               if (mesh%bc(k, i) /= 0 .and. mesh%disp(k, i) /= 0.0_wp) then
                  self%dnode = [self%dnode, i]
                  self%ddof = [self%ddof, k]
                  self%dval = [self%dval, mesh%disp(k, i)]
               end if
            end do
         end do
      end if
      self%ndisp = size(self%dnode)
      self%nmove = size(self%mnode)
      ! every prescribed dof (fixed, driven or rigid, not of a free body) for the work W_pm
      allocate (self%pnode(0), self%pdof(0))
      do i = 1, n
         if (.not. st%active(i)) cycle
         if (self%body_of(i) > 0) then
            if (self%bodies(self%body_of(i))%kind == RB_FREE) cycle
         end if
         do k = 1, 2
            if (st%minv(k, i) == 0.0_wp) then
               self%pnode = [self%pnode, i]
               self%pdof = [self%pdof, k]
            end if
         end do
      end do
      self%npres = size(self%pnode)
      allocate (self%rold(self%npres), source=0.0_wp)
      moving = self%ndisp > 0 .or. self%nmove > 0 .or. any(self%bodies%kind /= RB_PLAIN)
      self%active = self%varying .or. moving
      ! v(n) is kept when the loads vary or W_pm can be booked (loading_velocities_set: a
      ! prescribed dof that moves); the functions of the dofs when a step evaluates them
      if (self%varying .or. self%npres > 0 .or. moving) allocate (self%vold(2, n), source=0.0_wp)
      if (.not. (self%varying .or. self%ndisp > 0)) deallocate (self%fpro)
   end subroutine loading_init

   !> Nodal BODY and gravity forces of every solid and free rigid element set: b int N_a dV0 and
   !> rho g int N_a dV0 (the row-sum lumped mass with rho = 1, doc/loads.md section 2; per
   !> radian in axisymmetry, doc/axisymmetry.md (A5)).
   subroutine body_and_gravity(self, materials, st, sets)
      type(loading_t), intent(inout) :: self
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), allocatable :: vol(:)
      integer :: k
      logical :: loaded
      do k = 1, size(sets)
         associate (s => sets(k), m => materials(sets(k)%mat))
            loaded = s%kind == MAT_SOLID .or. (s%kind == MAT_RIGID .and. m%free)
            if (.not. loaded) cycle
            if (all(m%body == 0.0_wp) .and. .not. self%spec%has_gravity) cycle
            if (.not. allocated(vol)) then
               ! the arrays of a deck with body forces or gravity only
               allocate (vol(st%nnode))
               allocate (self%fbody(2, st%nnode), self%fgrav(2, st%nnode), source=0.0_wp)
            end if
            vol = 0.0_wp
            call q4_lumped_mass(s%nel, st%nnode, s%conn, st%x0, 1.0_wp, vol, st%axisymmetric)
            if (any(m%body /= 0.0_wp)) then
               self%any_body = .true.
               self%fbody(1, :) = self%fbody(1, :) + m%body(1)*vol
               self%fbody(2, :) = self%fbody(2, :) + m%body(2)*vol
            end if
            if (self%spec%has_gravity) then
               self%any_grav = .true.
               self%fgrav(1, :) = self%fgrav(1, :) + (m%rho*self%spec%gravity(1))*vol
               self%fgrav(2, :) = self%fgrav(2, :) + (m%rho*self%spec%gravity(2))*vol
            end if
         end associate
      end do
   end subroutine body_and_gravity

   !> The nodes of deformable region `spec%motions(j)%region` as MOTIon nodes.
   subroutine add_motion_nodes(self, mesh, j)
      type(loading_t), intent(inout) :: self
      type(mesh_t), intent(in) :: mesh
      integer, intent(in) :: j
      logical :: on(mesh%nnode)
      integer :: e, i
      on = .false.
      do e = 1, mesh%nelem
         if (mesh%region(e) == self%spec%motions(j)%region) on(mesh%conn(:, e)) = .true.
      end do
      do i = 1, mesh%nnode
         if (.not. on(i) .or. any(self%mnode == i)) cycle
         self%mnode = [self%mnode, i]
         self%mmot = [self%mmot, j]
      end do
   end subroutine add_motion_nodes

   !> One body per region with rigid elements: free (RIGId,FREE), driven (MOTIon) or plain, its
   !> nodes, mass, centroid and inertia (doc/loads.md, section 4). Free bodies take the lumped
   !> masses of their nodes (deformable elements' shares included, as point masses).
   subroutine make_bodies(self, mesh, materials, st, sets, err)
      type(loading_t), intent(inout) :: self
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(error_t), allocatable, intent(out) :: err
      logical :: is_rigid(mesh%nelem)
      integer, allocatable :: regions(:), free_of(:)
      integer :: e, nb, ib, nfree, i
      real(wp), allocatable :: mdef(:)

      allocate (self%body_of(st%nnode), source=0)
      do e = 1, mesh%nelem
         is_rigid(e) = materials(mesh%mat(e))%kind == MAT_RIGID
      end do
      regions = unique_regions(mesh%region, is_rigid)
      nb = size(regions)
      allocate (self%bodies(nb))
      if (nb == 0) return
      ! lumped masses of the deformable elements (point masses on nodes shared with a body)
      allocate (mdef(st%nnode), source=0.0_wp)
      do i = 1, size(sets)
         if (sets(i)%kind == MAT_SOLID) call q4_lumped_mass(sets(i)%nel, st%nnode, sets(i)%conn, &
                                                            st%x0, sets(i)%rho, mdef)
      end do
      do ib = 1, nb
         call make_body(self, mesh, materials, st, is_rigid, regions(ib), ib, mdef, err)
         if (allocated(err)) return
      end do
      nfree = count(self%bodies%kind == RB_FREE)
      self%has_free = nfree > 0
      ! lever arms (rb%r) for bodies that move, lumped masses for free ones: nothing otherwise
      if (all(self%bodies%kind == RB_PLAIN)) return
      if (self%has_free) allocate (self%wlump(st%nnode), source=0.0_wp)
      allocate (free_of(st%nnode), source=0)
      i = 0
      do ib = 1, nb
         if (self%bodies(ib)%kind /= RB_FREE) cycle
         i = i + 1
         free_of(self%bodies(ib)%nodes) = i
      end do
      call self%rb%init(st%nnode, nfree, free_of)
      i = 0
      do ib = 1, nb
         associate (b => self%bodies(ib))
            if (b%kind /= RB_FREE) cycle
            i = i + 1
            self%rb%minv(:, i) = [1.0_wp/b%mass, 1.0_wp/b%mass, 1.0_wp/b%inertia]
            ! the body owns its nodes' mass; they keep zero inverse mass (rigid)
            self%wlump(b%nodes) = st%mass(b%nodes)
            st%mass(b%nodes) = 0.0_wp
         end associate
      end do
   end subroutine make_bodies

   !> Body `ib`: the rigid elements of region `region`.
   subroutine make_body(self, mesh, materials, st, is_rigid, region, ib, mdef, err)
      type(loading_t), intent(inout) :: self
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(in) :: st
      logical, intent(in) :: is_rigid(:)
      integer, intent(in) :: region, ib
      real(wp), intent(in) :: mdef(:)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: elems(:)
      logical :: on(st%nnode)
      integer :: e, j, k, nfree

      elems = pack([(e, e=1, mesh%nelem)], is_rigid .and. mesh%region == region)
      nfree = count(materials(mesh%mat(elems))%free)
      associate (b => self%bodies(ib))
         b%region = region
         if (nfree > 0 .and. nfree < size(elems)) then
            call make_error(err, 'region '//itoa(region)//' has RIGId,FREE and fixed RIGId elements: '// &
                            'expected one kind of rigid body per region')
            return
         end if
         if (nfree > 0) b%kind = RB_FREE
         if (allocated(self%spec%motions)) then
            do j = 1, size(self%spec%motions)
               if (self%spec%motions(j)%region == region .and. self%spec%motions(j)%rigid) then
                  b%kind = RB_DRIVEN
                  b%motion = j
               end if
            end do
         end if
         on = .false.
         do j = 1, size(elems)
            on(mesh%conn(:, elems(j))) = .true.
         end do
         b%nodes = pack([(k, k=1, st%nnode)], on)
         b%nnode = size(b%nodes)
         do j = 1, b%nnode
            k = b%nodes(j)
            if (self%body_of(k) /= 0) then
               call make_error(err, 'node '//itoa(k)//' belongs to the rigid bodies of regions '// &
                               itoa(self%bodies(self%body_of(k))%region)//' and '//itoa(region)// &
                               ': expected rigid bodies that share no node')
               return
            end if
            self%body_of(k) = ib
            if (b%kind == RB_FREE .and. any(mesh%bc(:, k) /= 0)) then
               call make_error(err, 'node '//itoa(k)//' of the free rigid body of region '// &
                               itoa(region)//' has a boundary code: a free body is moved by forces '// &
                               'only (use a RIGId body with MOTIon to drive it)')
               return
            end if
         end do
         call body_moments(b, mesh, materials, st, elems, mdef, err)
      end associate
   end subroutine make_body

   !> Body b's mass, centroid and inertia from its rigid elements `elems` (2x2 Gauss) and, for a
   !> free body, the deformable lumped masses mdef at its nodes; the centroid is that of the mass
   !> (of the area for a massless body), and the reference offsets s_k of its nodes.
   subroutine body_moments(b, mesh, materials, st, elems, mdef, err)
      type(rigid_body_t), intent(inout) :: b
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(in) :: st
      integer, intent(in) :: elems(:)
      real(wp), intent(in) :: mdef(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: e, j, k
      real(wp) :: m, s(2), jj, area, sa(2), ja, xc(2), p(2)
      ! centroid: of the mass, or of the area for a massless body; then m, I about it
      p = st%x0(:, b%nodes(1))
      m = 0.0_wp
      s = 0.0_wp
      jj = 0.0_wp
      area = 0.0_wp
      sa = 0.0_wp
      ja = 0.0_wp
      do j = 1, size(elems)
         e = elems(j)
         call q4_mass_moments(1, st%nnode, mesh%conn(:, e:e), st%x0, materials(mesh%mat(e))%rho, p, m, s, jj)
         call q4_mass_moments(1, st%nnode, mesh%conn(:, e:e), st%x0, 1.0_wp, p, area, sa, ja)
      end do
      if (b%kind == RB_FREE) then
         ! point masses of deformable elements at shared nodes
         do j = 1, b%nnode
            k = b%nodes(j)
            m = m + mdef(k)
            s = s + mdef(k)*(st%x0(:, k) - p)
         end do
      end if
      if (m > 0.0_wp) then
         xc = p + s/m
      else
         xc = p + sa/area
      end if
      m = 0.0_wp
      s = 0.0_wp
      jj = 0.0_wp
      do j = 1, size(elems)
         e = elems(j)
         call q4_mass_moments(1, st%nnode, mesh%conn(:, e:e), st%x0, materials(mesh%mat(e))%rho, xc, m, s, jj)
      end do
      if (b%kind == RB_FREE) then
         do j = 1, b%nnode
            k = b%nodes(j)
            m = m + mdef(k)
            jj = jj + mdef(k)*sum((st%x0(:, k) - xc)**2)
         end do
         if (.not. (m > 0.0_wp .and. jj > 0.0_wp)) then
            call make_error(err, 'the free rigid body of region '//itoa(b%region)//' has no mass: '// &
                            'expected DENSity rho > 0')
            return
         end if
      end if
      b%mass = m
      b%inertia = jj
      b%xc0 = xc
      b%xc = xc
      allocate (b%s(2, b%nnode))
      do j = 1, b%nnode
         b%s(:, j) = st%x0(:, b%nodes(j)) - xc
      end do
   end subroutine body_moments

   !> Sorted regions of the elements marked in `mask`.
   function unique_regions(region, mask) result(u)
      integer, intent(in) :: region(:)
      logical, intent(in) :: mask(:)
      integer, allocatable :: u(:)
      integer :: e
      allocate (u(0))
      do e = 1, size(region)
         if (.not. mask(e)) cycle
         if (any(u == region(e))) cycle
         u = [u, region(e)]
      end do
      call sort_short_int(u)
   end function unique_regions

   !> Index of the body of region `region` (0: none).
   pure integer function loading_body_index(self, region) result(ib)
      class(loading_t), intent(in) :: self
      integer, intent(in) :: region
      do ib = 1, size(self%bodies)
         if (self%bodies(ib)%region == region) return
      end do
      ib = 0
   end function loading_body_index

   !> p, p', p'' of every function (and of the sum, column 0) at time t.
   subroutine evaluate(self, t)
      type(loading_t), intent(inout) :: self
      real(wp), intent(in) :: t
      integer :: j
      do j = 0, self%nfn
         if (j > 0) then
            if (self%spec%fn(j)%kind == FN_UNDEFINED) cycle
         end if
         call prop_value(self%spec%fn, j, t, self%pv(1, j), self%pv(2, j), self%pv(3, j))
      end do
   end subroutine evaluate

   !> At t = 0, before the first forces: u(0) = d p(0) on prescribed displacements; the free
   !> bodies' initial velocities fitted to their nodes' (INITial); whether W_pm is booked.
   subroutine loading_begin(self, st)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      integer :: j
      call evaluate(self, st%t)
      do j = 1, self%ndisp
         st%u(self%ddof(j), self%dnode(j)) = self%dval(j)*self%pv(1, self%fpro(self%ddof(j), self%dnode(j)))
      end do
      call self%velocities_set(st, .false.)
   end subroutine loading_begin

   !> The positions at t = 0 of the dofs that DISPlacement prescribes, x = x0 + d p(0), into x
   !> (which holds x0 + u): before `begin`, u there is still the full value d (the contact's
   !> start-up overlap test reads x at set-up, doc/loads.md section 3).
   subroutine loading_place_initial(self, st, x)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(in) :: st
      real(wp), intent(inout) :: x(:, :)
      integer :: j
      call evaluate(self, st%t)
      do j = 1, self%ndisp
         x(self%ddof(j), self%dnode(j)) = st%x0(self%ddof(j), self%dnode(j)) + &
                                          self%dval(j)*self%pv(1, self%fpro(self%ddof(j), self%dnode(j)))
      end do
   end subroutine loading_place_initial

   !> After INITial velocities: free bodies take the rigid velocity nearest to their nodes'
   !> (mass weighted) and their nodes the rigid field of it; W_pm is booked from now on when a
   !> prescribed dof can move. `started`: the run has begun (reactions are current).
   subroutine loading_velocities_set(self, st, started)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      logical, intent(in) :: started
      integer :: ib, j
      logical :: was
      do ib = 1, size(self%bodies)
         associate (b => self%bodies(ib))
            if (b%kind /= RB_FREE) cycle
            call rigid_levers(b, st%nnode, st%x0, st%u, self%rb%r)
            call rigid_fit_velocity(b, st%nnode, self%rb%r, self%wlump, st%v, b%v, b%om)
            ! V(n) of the coming step (at t = 0 the predictor starts from it)
            b%vn = b%v
            b%omn = b%om
            call rigid_node_motion(b, st%nnode, self%rb%r, b%v, b%om, b%a, b%al, st%v, st%a)
         end associate
      end do
      was = self%track_work
      self%track_work = self%ndisp > 0 .or. self%nmove > 0 .or. any(self%bodies%kind == RB_DRIVEN)
      do j = 1, self%npres
         if (st%v(self%pdof(j), self%pnode(j)) /= 0.0_wp) self%track_work = .true.
      end do
      self%active = self%active .or. self%track_work
      if (started .and. self%track_work .and. .not. was) then
         do j = 1, self%npres
            self%rold(j) = static_reaction(st, self%pnode(j), self%pdof(j))
         end do
      end if
   end subroutine loading_velocities_set

   !> After step 1 (st%t = t(n+1), st%dt_prev = dt(n)): prescribed displacements d p(t) and the
   !> bodies with a state placed; du becomes each node's actual increment.
   subroutine loading_place(self, st, du)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      real(wp), intent(inout) :: du(:, :)
      integer :: j, k, i, ib
      real(wp) :: unew
      call evaluate(self, st%t)
      do j = 1, self%ndisp
         i = self%dnode(j)
         k = self%ddof(j)
         unew = self%dval(j)*self%pv(1, self%fpro(k, i))
         du(k, i) = du(k, i) + (unew - st%u(k, i))
         st%u(k, i) = unew
      end do
      do ib = 1, size(self%bodies)
         if (self%bodies(ib)%kind == RB_PLAIN) cycle
         call rigid_place(self%bodies(ib), st%dt_prev, st%nnode, st%x0, st%u, du)
      end do
   end subroutine loading_place

   !> After step 2: fext(t(n+1)) on the current positions x when the loads vary (fext(n) kept
   !> for the work); nothing otherwise. `first`: at t = 0 (fext(n) = fext(0)).
   subroutine loading_forces(self, st, x, first)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      real(wp), intent(in) :: x(:, :)
      logical, intent(in) :: first
      integer :: i, k, g
      real(wp) :: f
      if (.not. self%varying) return
      st%fext_zero = .false.
      self%fext_old = st%fext
      if (self%spec%nedge > 0) then
         self%fedge = 0.0_wp
         call edge_forces(self%spec%nedge, st%nnode, self%spec%edge, self%spec%edge_kind, &
                          self%spec%edge_value, x, self%fedge, st%axisymmetric)
      end if
      g = self%spec%gravity_prop
      do i = 1, st%nnode
         do k = 1, 2
            f = self%fnode(k, i)*self%pv(1, self%fpro(k, i))
            if (self%any_body) f = f + self%fbody(k, i)*self%pv(1, 0)
            if (self%any_grav) f = f + self%fgrav(k, i)*self%pv(1, g)
            if (self%spec%nedge > 0) f = f + self%fedge(k, i)*self%pv(1, self%fpro(k, i))
            st%fext(k, i) = f
         end do
      end do
      if (first) self%fext_old = st%fext
      self%favg = 0.5_wp*(self%fext_old + st%fext)
   end subroutine loading_forces

   !> After step 4 (the predictor a~ = M^-1 (F - P), v~): prescribed dofs get v(n+1), a(n+1)
   !> (in vt and st%a); driven bodies their prescribed motion; free bodies
   !> A~ = F/m, alpha~ = M/I from fext - fint on their nodes, V~ = V(n) + dt(n)/2 (A(n) + A~),
   !> and their nodes the rigid field of it (doc/loads.md, section 4). h = dt(n)/2.
   subroutine loading_predict(self, st, vt, h)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      real(wp), intent(inout) :: vt(:, :)
      real(wp), intent(in) :: h
      integer :: j, i, k, ib, im
      real(wp) :: fe(2), me, fi(2), mi
      if (self%varying .or. self%track_work) self%vold = st%v
      do j = 1, self%ndisp
         i = self%dnode(j)
         k = self%ddof(j)
         vt(k, i) = self%dval(j)*self%pv(2, self%fpro(k, i))
         st%a(k, i) = self%dval(j)*self%pv(3, self%fpro(k, i))
      end do
      do j = 1, self%nmove
         i = self%mnode(j)
         associate (mo => self%spec%motions(self%mmot(j)))
            vt(:, i) = mo%v*self%pv(1, mo%prop)
            st%a(:, i) = mo%v*self%pv(2, mo%prop)
         end associate
      end do
      do ib = 1, size(self%bodies)
         associate (b => self%bodies(ib))
            if (b%kind == RB_PLAIN) cycle
            call rigid_levers(b, st%nnode, st%x0, st%u, self%rb%r)
            if (b%kind == RB_DRIVEN) then
               im = b%motion
               associate (mo => self%spec%motions(im))
                  b%v = mo%v*self%pv(1, mo%prop)
                  b%om = mo%omega*self%pv(1, mo%prop)
                  b%a = mo%v*self%pv(2, mo%prop)
                  b%al = mo%omega*self%pv(2, mo%prop)
               end associate
            else
               call rigid_gather(b, st%nnode, self%rb%r, st%fext, fe, me)
               call rigid_gather(b, st%nnode, self%rb%r, st%fint, fi, mi)
               b%a = (fe - fi)/b%mass
               b%al = (me - mi)/b%inertia
               b%v = b%vn + h*(b%an + b%a)
               b%om = b%omn + h*(b%aln + b%al)
            end if
            call rigid_node_motion(b, st%nnode, self%rb%r, b%v, b%om, b%a, b%al, vt, st%a)
         end associate
      end do
   end subroutine loading_predict

   !> After step 5: each free body takes the contact forces on its nodes,
   !> delta A = sum fcon / m, delta alpha = sum r x fcon / I (doc/loads.md, section 5).
   subroutine loading_corrected(self, st)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      integer :: ib
      real(wp) :: fc(2), mc
      if (.not. self%has_free) return
      do ib = 1, size(self%bodies)
         associate (b => self%bodies(ib))
            if (b%kind /= RB_FREE) cycle
            call rigid_gather(b, st%nnode, self%rb%r, st%fcon, fc, mc)
            b%a = b%a + fc/b%mass
            b%al = b%al + mc/b%inertia
         end associate
      end do
   end subroutine loading_corrected

   !> After step 6 (v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1)) for every node): prescribed dofs take
   !> their exact v(n+1), a(n+1); free bodies V(n+1) = V(n) + dt(n)/2 (A(n) + A(n+1)) and their
   !> nodes the rigid field. The work of the prescribed motion by the trapezoid rule,
   !> W_pm += 1/2 (R(n) + R(n+1)) . du over the prescribed dofs (doc/loads.md, section 3), and the
   !> guard's second estimates of W_ext (varying loads) and W_pm by the trapezoid rule of the power.
   !> h = dt(n)/2; `first`: at t = 0 (the reactions are only recorded).
   subroutine loading_finish(self, st, du, h, first)
      class(loading_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      real(wp), intent(in) :: du(:, :)
      real(wp), intent(in) :: h
      logical, intent(in) :: first
      integer :: j, i, k, ib
      real(wp) :: r, w, wp2, dk, m
      do j = 1, self%ndisp
         i = self%dnode(j)
         k = self%ddof(j)
         st%v(k, i) = self%dval(j)*self%pv(2, self%fpro(k, i))
         st%a(k, i) = self%dval(j)*self%pv(3, self%fpro(k, i))
      end do
      do j = 1, self%nmove
         i = self%mnode(j)
         associate (mo => self%spec%motions(self%mmot(j)))
            st%v(:, i) = mo%v*self%pv(1, mo%prop)
            st%a(:, i) = mo%v*self%pv(2, mo%prop)
         end associate
      end do
      do ib = 1, size(self%bodies)
         associate (b => self%bodies(ib))
            if (b%kind == RB_PLAIN) cycle
            if (b%kind == RB_FREE) then
               b%v = b%vn + h*(b%an + b%a)
               b%om = b%omn + h*(b%aln + b%al)
            end if
            call rigid_node_motion(b, st%nnode, self%rb%r, b%v, b%om, b%a, b%al, st%v, st%a)
         end associate
      end do
      if (self%varying .and. .not. first) then
         w = 0.0_wp
         do i = 1, st%nnode
            do k = 1, 2
               w = w + self%favg(k, i)*(self%vold(k, i) + st%v(k, i))
            end do
         end do
         self%wext_p = self%wext_p + h*w
      end if
      if (.not. self%track_work) return
      w = 0.0_wp
      wp2 = 0.0_wp
      dk = 0.0_wp
      do j = 1, self%npres
         i = self%pnode(j)
         k = self%pdof(j)
         ! the reaction without its inertia M a (eq. P.2): the inertia is booked as the change
         ! of the dof's kinetic energy, dk (eq. P.3)
         r = static_reaction(st, i, k)
         if (.not. first) then
            w = w + (self%rold(j) + r)*du(k, i)
            wp2 = wp2 + (self%rold(j) + r)*(self%vold(k, i) + st%v(k, i))
            m = dof_mass(st, i, k)
            if (m /= 0.0_wp) dk = dk + m*(st%v(k, i)**2 - self%vold(k, i)**2)
         end if
         self%rold(j) = r
      end do
      st%energy%wpm = st%energy%wpm + 0.5_wp*w
      self%wpm_p = self%wpm_p + 0.5_wp*h*wp2
      if (dk /= 0.0_wp) then
         st%energy%wpm = st%energy%wpm + 0.5_wp*dk
         self%wpm_p = self%wpm_p + 0.5_wp*dk
      end if
   end subroutine loading_finish

   !> The energy put in by the loads and the prescribed motion, W_ext + W_pm, as the larger of
   !> the booked estimate (trapezoid rule in the displacement) and the trapezoid rule of the
   !> power (doc/loads.md, section 3, "Energy guard"): the first lags half a step behind the
   !> kinetic energy of integer-time velocities (a load rising from zero would look like energy
   !> from nothing at its first steps), the second behind a suddenly applied load.
   pure real(wp) function loading_work_in(self, st) result(w)
      class(loading_t), intent(in) :: self
      type(state_t), intent(in) :: st
      real(wp) :: alt
      alt = self%wpm_p
      if (self%varying) then
         alt = alt + self%wext_p
      else
         alt = alt + st%energy%wext
      end if
      w = max(st%energy%wext + st%energy%wpm, alt)
   end function loading_work_in

   !> After the nodes' kinetic energy and momentum: add the free bodies'
   !> 1/2 m |V|^2 + 1/2 I omega^2 and m V (their nodes carry no mass), and set their part of the
   !> rate of the kinetic correction, m |A|^2 + I alpha^2 (doc/decisions.md, "Energy balance",
   !> eq. E.3: every force on a body is booked by the trapezoid rule, so r = m A).
   subroutine loading_energy(self, st)
      class(loading_t), intent(in) :: self
      type(state_t), intent(inout) :: st
      integer :: ib
      real(wp) :: s
      if (.not. self%has_free) return
      s = 0.0_wp
      do ib = 1, size(self%bodies)
         associate (b => self%bodies(ib))
            if (b%kind /= RB_FREE) cycle
            st%energy%kinetic = st%energy%kinetic + 0.5_wp*(b%mass*(b%v(1)**2 + b%v(2)**2) + b%inertia*b%om**2)
            st%momentum = st%momentum + b%mass*b%v
            s = s + b%mass*(b%a(1)**2 + b%a(2)**2) + b%inertia*b%al**2
         end associate
      end do
      st%body_power = s
   end subroutine loading_energy

   !> The lumped mass of dof k of node i.
   pure real(wp) function dof_mass(st, i, k) result(m)
      type(state_t), intent(in) :: st
      integer, intent(in) :: i, k
      if (allocated(st%mass_dof)) then
         m = st%mass_dof(k, i)
      else
         m = st%mass(i)
      end if
   end function dof_mass

   !> The reaction of dof k of node i without its inertia, R - M a = P - F - fcon (doc/loads.md,
   !> section 3, eq. P.2): the part of the reaction whose work W_pm books by the trapezoid rule.
   pure real(wp) function static_reaction(st, i, k) result(r)
      type(state_t), intent(in) :: st
      integer, intent(in) :: i, k
      r = st%fint(k, i) - st%fext(k, i)
      if (st%fcon(k, i) /= 0.0_wp) r = r - st%fcon(k, i)
   end function static_reaction

   !> The force the support (or the driver) exerts on dof k of node i (doc/loads.md, section 3):
   !> R = M a + P - F - fcon; on a fixed dof without contact the old R = P - F, to the last bit.
   pure real(wp) function reaction(st, i, k) result(r)
      type(state_t), intent(in) :: st
      integer, intent(in) :: i, k
      r = st%fint(k, i) - st%fext(k, i)
      if (st%fcon(k, i) /= 0.0_wp) r = r - st%fcon(k, i)
      if (st%a(k, i) /= 0.0_wp) then
         if (allocated(st%mass_dof)) then
            r = r + st%mass_dof(k, i)*st%a(k, i)
         else
            r = r + st%mass(i)*st%a(k, i)
         end if
      end if
   end function reaction

end module exic_explicit_loading
