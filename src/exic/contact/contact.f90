!> Contact in the time step: surfaces, passes, search and the implicit corrector (seed 3-6).
!>
!> Each PAIR becomes one pass (NTOS, SELF) or two (SYMMetric: each surface's nodes against the
!> other's segments); AUTOmatic makes a surface of every region's free boundary and pairs every
!> two of them: one search over all its surfaces per step makes the passes of the pairs found
!> near (src/exic/contact/broad_all.f90), Lagrange or penalty. Per step and pass: predicted
!> positions x~(n+2) (eq. 4.4), the broad phase on swept boxes, swept (or static)
!> node-to-segment detection (eq. 6.1-6.6), and candidate constraints with the predicted gap
!> of eq. 3.19 at t(n+2) and a frozen normal. All Lagrange candidates of all passes are solved
!> together by the corrector (eq. 4.5-4.7), or, when a pair has Coulomb friction, by the
!> frictional corrector (doc/friction.md, eq. F6-F15); penalty passes add k x penetration
!> forces at t(n+1) instead (src/exic/contact/penalty.f90, with the regularised friction law F18).
!>
!> Everything comes in as plain arrays: the CONTact block's spec, the positions, the element
!> connectivity with region and material numbers (for REGIon/MATErial and AUTOmatic surfaces),
!> and per step the positions, velocities, accelerations and inverse masses. The deck path
!> (src/exic/explicit/step.f90) and the legacy API (src/exic/legacy) call the same two entries,
!> `init` and `correct`.
module exic_contact_contact
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_grow, only: grow
   use exic_base_sort, only: sorted_unique
   use exic_base_text_buffer, only: text_buffer_t
   use exic_contact_spec, only: SURF_REGION, SURF_MATERIAL, SURF_FACETS, SURF_NODES, PAIR_NTOS, &
                                PAIR_SYMMETRIC, PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, &
                                DETECT_SWEPT, DETECT_STATIC, pair_spec_t, contact_spec_t, spec_penalty_finite
   use exic_mesh_boundary, only: free_edges, free_edges_of, bodies_elements, &
                                 surface_nodes, segment_links, locate_nodes, node_normals, &
                                 node_segments
   use exic_contact_broad, only: broad_t, broad_search, broad_search_kept, drop_flat_fixed
   use exic_contact_broad_all, only: broad_all_t
   use exic_contact_detect, only: contact_set_t, detect_contacts
   use exic_contact_corrector, only: constraints_t, corrector_t
   use exic_contact_friction, only: friction_t, coulomb_mu
   use exic_contact_penalty, only: penalty_forces, penalty_history_t, smallest_mass, spring_dt, &
                                   auto_spring_dt
   use exic_contact_pair_history, only: pair_history_t
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_massless_face, only: massless_face_t
   use exic_contact_overlap, only: node_element_lists, inside_near
   implicit none
   private

   public :: contact_t

   !> A slave node is paired with a master segment only when its own outward normal ns and the
   !> segment's normal n face each other: ns . n < FACING = cos(120 degrees). A node at a right-
   !> angled corner meeting a face head-on gives -0.71; a face node meeting the side face of the
   !> other body's corner (deformed a little off 90 degrees) gives about 0 and is rejected, so
   !> corners of bodies of equal height do not pair with each other's side faces.
   real(wp), parameter :: FACING = -0.5_wp
   !> Share of the mean segment length up to which a slave node found behind a master segment at
   !> the start of a step is still caught (and pushed back by the corrector). The corrector closes
   !> each gap along a normal frozen over the step (seed section 4), so a node that slides past
   !> a master node onto a segment of another slope, or along a curved surface, ends the step
   !> behind it by the slope change times the slide: far above rounding, yet a tiny share of the
   !> segment. A node deeper than this is taken to be on the far side of the surface.
   real(wp), parameter :: DEPTH_SHARE = 0.1_wp

   !> A contact surface: segments (body on the left of n1 -> n2) and its nodes.
   type :: surface_t
      integer :: id = 0
      integer :: nseg = 0, nnode = 0
      integer, allocatable :: seg(:, :)        !< (2, nseg)
      integer, allocatable :: link(:, :)       !< (2, nseg) neighbouring segments
      integer, allocatable :: nodes(:)         !< (nnode) sorted
      integer, allocatable :: where(:, :)      !< (2, nseg) positions of seg nodes in `nodes`
      real(wp), allocatable :: nrm(:, :)       !< (2, nnode) node normals at t(n+1)
      integer :: nrm_stamp = -1                !< search whose positions nrm holds (all nodes)
      integer, allocatable :: nhead(:), nsegs(:) !< segments of each node (node_segments)
      real(wp), allocatable :: sn(:, :)        !< (4, nseg) segment normals at x0, x1 (detect_pairs)
      integer, allocatable :: sn_stamp(:)      !< search whose positions sn(:, k) holds
   end type surface_t

   !> One pass: the nodes of surface `slave` against the segments of surface `master`.
   type :: pass_t
      integer :: pair = 0                      !< index into pair results
      integer :: slave = 0, master = 0         !< surface indices
      integer :: method = METHOD_LAGRANGE
      logical :: energy = .false.              !< LAGRange,ENERgy: massless faces (doc/impact.md)
      integer :: detection = DETECT_SWEPT
      real(wp) :: k = 0.0_wp                   !< penalty stiffness
      logical :: friction = .false.            !< Coulomb friction with law(1) = mus > 0
      real(wp) :: law(3) = 0.0_wp              !< mus, mud, decay (doc/friction.md, eq. F12)
      type(penalty_history_t) :: hist          !< tangential state of a penalty pass with friction
      !> per hit of a penalty pass: penetration, normal force, force on the slave, tangential
      !> force and state (grown, never shrunk)
      real(wp), allocatable :: pen(:), fn(:), f(:, :), q(:)
      integer, allocatable :: state(:)
      logical :: auto = .false.                !< AUTOmatic: candidates from the search over all surfaces
      type(broad_t) :: broad
      type(contact_set_t) :: hits
   end type pass_t

   !> Results of one pair for TPLOt `cont` requests.
   type :: pair_result_t
      integer :: id = 0
      real(wp) :: fnormal = 0.0_wp, force(2) = 0.0_wp, penetration = 0.0_wp
      real(wp) :: pmax = 0.0_wp                !< largest multiplier (nodal normal force)
      !> work of the pair's multipliers over the run: sum over steps and constraints of
      !> -p g(n+1), the gap each closes by t(n+2) (positive: the pair pushed bodies apart)
      real(wp) :: work = 0.0_wp
      integer :: nactive = 0
      ! friction (doc/friction.md, section 7)
      real(wp) :: ftangent = 0.0_wp            !< friction force: sum of |q| over the pair's constraints
      integer :: nstick = 0, nslip = 0         !< constraints that stick, that slip
      real(wp) :: dissipation = 0.0_wp         !< frictional dissipation over the run (eq. F16-F17)
      real(wp) :: pending = 0.0_wp             !< Coulomb work of the last step, booked at the next
   end type pair_result_t

   !> All contact of a model. Inactive (no work at all) when the deck has no CONTact block.
   type :: contact_t
      logical :: active = .false.
      logical :: any_penalty = .false.
      type(surface_t), allocatable :: surfaces(:)
      type(pass_t), allocatable :: passes(:)
      !> passes in force: 1..nfixed those of the PAIR records, then one per pair of AUTOmatic
      !> surfaces that the search over all surfaces found near
      integer :: npass = 0, nfixed = 0
      type(pass_t) :: auto_pass                !< options of the AUTOmatic passes
      !> penalty AUTOmatic with friction: the tangential state per pair of surfaces, and the
      !> work history a pass runs on (src/exic/contact/pair_history.f90)
      type(pair_history_t) :: auto_hist
      type(penalty_history_t) :: hwork
      type(broad_all_t) :: auto                !< the AUTOmatic surfaces and their search
      integer :: auto_first = 0                !< surfaces(auto_first + r) is AUTOmatic surface r
      integer, allocatable :: cnodes(:)        !< every node of every contact surface
      integer :: stamp = 0                     !< searches made (normals are formed once per search)
      integer :: nthreaded = 0                 !< searches whose narrow phase ran on the threads
      !> the caller passes the same fcon to every call and leaves it alone in between (the
      !> stepper): fcon is then zeroed only when the last call left forces in it
      logical :: keep_fcon = .false.
      logical :: fcon_clean = .false.          !< the last call left fcon zero everywhere
      type(pair_result_t), allocatable :: results(:)
      type(constraints_t) :: cs
      type(corrector_t) :: corr
      logical :: energy = .false.              !< some pass asks for LAGRange,ENERgy
      type(massless_face_t) :: face            !< the massless faces (set up by the caller: face_nodes, face%init)
      real(wp), allocatable :: fres(:, :)      !< (2, nnode) f_ext - f_int for the face's free solve
      real(wp) :: lref = 1.0_wp                !< mean segment length
      real(wp) :: depth = 0.0_wp               !< penetration accepted at the start of a step (DEPTH_SHARE x lref)
      real(wp), allocatable :: xp(:, :)           !< (2, nnode) predicted positions x~(n+2)
      real(wp) :: max_penetration = 0.0_wp     !< largest over the run
      real(wp) :: time_search = 0.0_wp         !< wall time in search (broad + narrow phase)
      real(wp) :: time_corrector = 0.0_wp      !< wall time in the corrector (assembly + solve)
      integer :: nredundant = 0                !< redundant constraints removed over the run
      ! friction (doc/friction.md); allocated and used only when a pair has it
      logical :: friction = .false.            !< some pass has Coulomb friction
      type(friction_t) :: fr                   !< the frictional corrector's tangential problem
      real(wp), allocatable :: vslip(:)        !< (nnode) slip speed of each slave at the last step (< 0: stuck, none)
      real(wp), allocatable :: ffric(:, :)     !< (2, nnode) nodal friction forces of the last step
      real(wp), allocatable :: xold(:, :)      !< (2, nnode) positions of the last step (penalty friction)
      real(wp) :: dissipation = 0.0_wp         !< frictional dissipation booked up to t(n+1) (eq. F17)
      real(wp) :: pending = 0.0_wp             !< Coulomb work of the last step, booked at the next
   contains
      procedure :: init => contact_init
      procedure :: correct => contact_correct
      procedure :: stable_dt => contact_stable_dt
      procedure :: pair_value => contact_pair_value
      procedure :: summary => contact_summary
      procedure :: edges => contact_edges
      procedure :: face_nodes => contact_face_nodes
      procedure :: face_dofs => contact_face_dofs
   end type contact_t

   interface
      !> The narrow phase of the Lagrange passes k1 ... k2, on the threads when there is enough
      !> of it (src/exic/contact/narrow.f90).
      module subroutine narrow_passes(self, nnode, x, minv, k1, k2)
         type(contact_t), intent(inout) :: self
         integer, intent(in) :: nnode, k1, k2
         real(wp), intent(in) :: x(2, nnode), minv(2, nnode)
      end subroutine narrow_passes

      !> The corrector's solve with massless faces, detecting again on the corrected positions
      !> (src/exic/contact/faces.f90).
      module subroutine face_solve(self, nnode, x, minv, c, a, fcon, err, rb)
         type(contact_t), intent(inout) :: self
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x(2, nnode), minv(2, nnode), c
         real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
         type(error_t), allocatable, intent(out) :: err
         type(rigid_dofs_t), intent(inout), optional :: rb
      end subroutine face_solve

      !> Candidate nodes of the massless faces (src/exic/contact/faces.f90).
      module function contact_face_nodes(self, nnode) result(on)
         class(contact_t), intent(in) :: self
         integer, intent(in) :: nnode
         logical :: on(nnode)
      end function contact_face_nodes

      !> Massless dofs of the faces, eq. I.3a and I.3b (src/exic/contact/faces.f90).
      module function contact_face_dofs(self, nnode, x, rigid) result(dofs)
         class(contact_t), intent(in) :: self
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x(2, nnode)
         logical, intent(in) :: rigid(nnode)
         logical :: dofs(2, nnode)
      end function contact_face_dofs
   end interface

contains

   !> Build surfaces and passes from the CONTact block `spec`; refuse bodies that overlap.
   !> xref(2, nnode): the positions whose segment lengths set the search depth (the reference
   !> mesh); x(2, nnode): the positions now (checked for overlap); conn(4, nelem), region(nelem),
   !> mat(nelem): the elements whose free boundaries make REGIon, MATErial and AUTOmatic surfaces;
   !> modulus: the largest constrained modulus lambda + 2 mu of the solids (PENAlty,SCALe).
   subroutine contact_init(self, spec, nnode, xref, x, nelem, conn, region, mat, modulus, err)
      class(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in) :: xref(2, nnode), x(2, nnode)
      integer, intent(in) :: conn(4, nelem), region(nelem), mat(nelem)
      real(wp), intent(in) :: modulus
      type(error_t), allocatable, intent(out) :: err
      integer :: k, np, nsurf, nlen
      integer, allocatable :: head(:), list(:)
      real(wp) :: len_sum

      self%active = spec%active
      if (.not. self%active) return
      call build_surfaces(self, spec, nelem, conn, region, mat, err)
      if (allocated(err)) return
      call build_passes(self, spec, err)
      if (allocated(err)) return
      nsurf = size(self%surfaces)
      len_sum = 0.0_wp
      nlen = 0
      do k = 1, nsurf
         associate (sf => self%surfaces(k))
            len_sum = len_sum + sum(norm2(xref(:, sf%seg(2, :)) - xref(:, sf%seg(1, :)), dim=1))
            nlen = nlen + sf%nseg
         end associate
      end do
      if (nlen > 0) self%lref = len_sum/nlen
      self%depth = DEPTH_SHARE*self%lref
      self%corr%gap_tol = 1.0e-13_wp*self%lref
      allocate (self%xp(2, nnode), source=0.0_wp)
      call contact_nodes(self, nnode)
      np = size(self%passes)
      do k = 1, np
         if (self%passes(k)%method == METHOD_PENALTY) self%any_penalty = .true.
      end do
      if (self%auto_pass%auto .and. self%auto_pass%method == METHOD_PENALTY) self%any_penalty = .true.
      call penalty_stiffness(self, modulus)
      call spec_penalty_finite(spec, modulus, err)
      if (allocated(err)) return
      call friction_arrays(self, nnode, x)
      if (self%energy .and. self%friction) then
         ! the massless faces enter the normal problem only (doc/impact.md, section 3.3)
         call make_error(err, 'LAGRange,ENERgy (massless contact faces) together with Coulomb friction '// &
                         'in one model is not supported: expected friction only on LAGRange pairs of a '// &
                         'model without ENERgy')
         return
      end if
      call node_element_lists(nnode, nelem, conn, head, list)
      call check_overlap(self, nnode, x, nelem, conn, head, list, err)
   end subroutine contact_init

   !> The friction state of the passes and of the model (at init): allocated only when some
   !> pass has friction (x: the positions now).
   subroutine friction_arrays(self, nnode, x)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode)
      integer :: k
      self%friction = .false.
      do k = 1, size(self%passes)
         associate (ps => self%passes(k))
            ps%friction = ps%law(1) > 0.0_wp
            if (ps%friction) self%friction = .true.
            if (ps%friction .and. ps%method == METHOD_PENALTY .and. .not. allocated(ps%hist%q)) &
               call ps%hist%init(nnode)
         end associate
      end do
      ! the options of the AUTOmatic passes (auto_passes copies them)
      self%auto_pass%friction = self%auto_pass%auto .and. self%auto_pass%law(1) > 0.0_wp
      if (self%auto_pass%friction) self%friction = .true.
      if (self%auto_pass%friction .and. self%auto_pass%method == METHOD_PENALTY .and. &
          .not. allocated(self%hwork%q)) call self%hwork%init(nnode)
      if (.not. self%friction) return
      if (.not. allocated(self%vslip)) allocate (self%vslip(nnode), source=-1.0_wp)
      if (.not. allocated(self%ffric)) allocate (self%ffric(2, nnode), source=0.0_wp)
      if (.not. allocated(self%xold)) allocate (self%xold(2, nnode), source=x)
   end subroutine friction_arrays

   !> Surfaces of the SURFace records, plus one per region for AUTOmatic.
   subroutine build_surfaces(self, spec, nelem, conn, region, mat, err)
      type(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      integer, intent(in) :: nelem
      integer, intent(in) :: conn(4, nelem), region(nelem), mat(nelem)
      type(error_t), allocatable, intent(out) :: err
      integer :: ns, nauto, k
      integer, allocatable :: regions(:), rfirst(:), relems(:)
      logical, allocatable :: sel(:)

      ns = 0
      if (allocated(spec%surfaces)) ns = size(spec%surfaces)
      nauto = 0
      if (spec%automatic) then
         call bodies_elements(nelem, region, regions, rfirst, relems)
         nauto = size(regions)
      end if
      allocate (self%surfaces(ns + nauto))
      allocate (sel(nelem))
      do k = 1, ns
         associate (sp => spec%surfaces(k), sf => self%surfaces(k))
            sf%id = sp%id
            select case (sp%by)
            case (SURF_REGION)
               sel = region == sp%ref
               call free_edges(nelem, conn, sel, sf%seg, err)
            case (SURF_MATERIAL)
               sel = mat == sp%ref
               call free_edges(nelem, conn, sel, sf%seg, err)
            case (SURF_FACETS)
               sf%seg = sp%facets
            case (SURF_NODES)
               ! slave nodes without segments: no normals, so no facing test (see detect_pairs)
               allocate (sf%seg(2, 0))
               if (size(sp%nodes) > 0) sf%nodes = sorted_unique(sp%nodes)
            end select
            if (allocated(err)) then
               err%message = 'SURFace '//itoa(sp%id)//': '//err%message
               return
            end if
            if (size(sf%seg, 2) == 0 .and. sp%by /= SURF_NODES) then
               call make_error(err, 'SURFace '//itoa(sp%id)//' has no segments')
               return
            end if
         end associate
      end do
      do k = 1, nauto
         associate (sf => self%surfaces(ns + k))
            sf%id = -regions(k) - 1          ! automatic surface of region regions(k)
            call free_edges_of(nelem, conn, relems(rfirst(k):rfirst(k + 1) - 1), sf%seg, err)
            if (allocated(err)) return
         end associate
      end do
      do k = 1, size(self%surfaces)
         associate (sf => self%surfaces(k))
            sf%nseg = size(sf%seg, 2)
            allocate (sf%link(2, sf%nseg), sf%where(2, sf%nseg))
            call segment_links(sf%nseg, sf%seg, sf%link)
            if (.not. allocated(sf%nodes)) call surface_nodes(sf%nseg, sf%seg, sf%nodes)
            sf%nnode = size(sf%nodes)
            call locate_nodes(sf%nseg, sf%seg, sf%nnode, sf%nodes, sf%where)
            allocate (sf%nrm(2, sf%nnode), sf%sn(4, sf%nseg), sf%sn_stamp(sf%nseg))
            sf%sn_stamp = -1
            call node_segments(sf%nseg, sf%where, sf%nnode, sf%nhead, sf%nsegs)
         end associate
      end do
   end subroutine build_surfaces

   !> Passes of the PAIR records (two for SYMMetric); AUTOmatic's are made per step (auto_passes).
   subroutine build_passes(self, spec, err)
      type(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      type(error_t), allocatable, intent(out) :: err
      integer :: npair, np, k, i, j, nauto, ns, maxid, npass
      type(pass_t), allocatable :: p(:)

      npair = 0
      if (allocated(spec%pairs)) npair = size(spec%pairs)
      ns = 0
      if (allocated(spec%surfaces)) ns = size(spec%surfaces)
      nauto = size(self%surfaces) - ns
      allocate (p(2*npair + 1))
      maxid = 0
      np = 0
      allocate (self%results(npair + merge(1, 0, nauto > 0)))
      do k = 1, npair
         associate (ps => spec%pairs(k))
            self%results(k)%id = ps%id
            maxid = max(maxid, ps%id)
            i = surface_index(self, ps%slave)
            j = surface_index(self, ps%master)
            if (i == 0 .or. j == 0) then
               call make_error(err, 'PAIR '//itoa(ps%id)//' names a surface that is not defined')
               return
            end if
            if (self%surfaces(j)%nseg == 0 .or. (ps%kind /= PAIR_NTOS .and. self%surfaces(i)%nseg == 0)) then
               call make_error(err, 'PAIR '//itoa(ps%id)//': a node set can only be the slave side of a one-pass pair')
               return
            end if
            select case (ps%kind)
            case (PAIR_NTOS)
               call add_pass(p, np, k, i, j, ps)
            case (PAIR_SYMMETRIC)
               call add_pass(p, np, k, i, j, ps)
               call add_pass(p, np, k, j, i, ps)
            case (PAIR_SELF)
               call add_pass(p, np, k, i, i, ps)
            end select
         end associate
      end do
      if (nauto > 0) then
         ! AUTOmatic: one search over all its surfaces per step makes the passes of the pairs
         ! of surfaces found near (auto_passes), in the order of i, then j
         self%results(npair + 1)%id = maxid + 1
         call add_pass(p, np, npair + 1, 0, 0, spec%auto_options)
         self%auto_pass = p(np)
         self%auto_pass%auto = .true.
         self%auto_pass%energy = self%auto_pass%energy .and. self%auto_pass%method == METHOD_LAGRANGE
         if (self%auto_pass%energy) self%energy = .true.
         np = np - 1
         self%auto_first = ns
         do i = ns + 1, ns + nauto
            call self%auto%add_surface(self%surfaces(i)%nodes, self%surfaces(i)%seg)
         end do
      end if
      npass = np
      self%nfixed = npass
      self%npass = npass
      allocate (self%passes(npass))
      do k = 1, npass
         self%passes(k)%pair = p(k)%pair
         self%passes(k)%slave = p(k)%slave
         self%passes(k)%master = p(k)%master
         self%passes(k)%method = p(k)%method
         self%passes(k)%energy = p(k)%energy .and. p(k)%method == METHOD_LAGRANGE
         if (self%passes(k)%energy) self%energy = .true.
         self%passes(k)%detection = p(k)%detection
         self%passes(k)%k = p(k)%k
         self%passes(k)%law = p(k)%law
      end do
   end subroutine build_passes

   !> Append a pass with the options of `ps`.
   subroutine add_pass(p, np, pair, slave, master, ps)
      type(pass_t), intent(inout) :: p(:)
      integer, intent(inout) :: np
      integer, intent(in) :: pair, slave, master
      type(pair_spec_t), intent(in) :: ps
      np = np + 1
      p(np)%pair = pair
      p(np)%slave = slave
      p(np)%master = master
      p(np)%method = ps%method
      p(np)%energy = ps%energy
      p(np)%detection = ps%detection
      p(np)%k = ps%penalty
      if (ps%penalty_scaled) p(np)%k = -ps%penalty   ! scale factor, resolved in penalty_stiffness
      p(np)%law = [ps%mus, ps%mud, ps%decay]
   end subroutine add_pass

   !> PENAlty,SCALe,f: k = f x modulus, the largest constrained modulus lambda + 2 mu of the solids.
   subroutine penalty_stiffness(self, modulus)
      type(contact_t), intent(inout) :: self
      real(wp), intent(in) :: modulus
      integer :: k
      do k = 1, size(self%passes)
         if (self%passes(k)%k < 0.0_wp) self%passes(k)%k = -self%passes(k)%k*modulus
      end do
      if (self%auto_pass%k < 0.0_wp) self%auto_pass%k = -self%auto_pass%k*modulus
   end subroutine penalty_stiffness

   !> Index of the surface with deck id `id` (0 if none).
   integer function surface_index(self, id) result(k)
      type(contact_t), intent(in) :: self
      integer, intent(in) :: id
      do k = 1, size(self%surfaces)
         if (self%surfaces(k)%id == id) return
      end do
      k = 0
   end function surface_index

   !> Bodies that overlap at the start are an error naming the worst node, segment and depth: a
   !> node behind a segment that lies inside an element next to it (src/exic/contact/overlap.f90).
   subroutine check_overlap(self, nnode, x, nelem, conn, head, list, err)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode, nelem, conn(4, nelem), head(:), list(:)
      real(wp), intent(in) :: x(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, j, worst_node, worst_m(2)
      real(wp) :: worst
      worst = 0.0_wp
      worst_node = 0
      call auto_passes(self, nnode, x, x, 0.5_wp*self%lref)
      do k = 1, self%npass
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            call surface_normals(self, sl, nnode, x)
            if (.not. ps%auto) call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, &
                                                 0.5_wp*self%lref)
            call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                                 sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                 0.5_wp*self%lref, FACING)
            do j = 1, ps%hits%n
               if (-ps%hits%gap(j) > worst) then
                  if (.not. inside_near(ps%hits%slave(j), ps%hits%master(:, j), nnode, x, nelem, conn, &
                                        head, list)) cycle
                  worst = -ps%hits%gap(j)
                  worst_node = ps%hits%slave(j)
                  worst_m = ps%hits%master(:, j)
               end if
            end do
         end associate
      end do
      if (worst > 1.0e-8_wp*self%lref) call make_error(err, 'bodies overlap at the start: node '//itoa(worst_node)// &
                                                       ' is inside segment '//itoa(worst_m(1))//'-'// &
                                                       itoa(worst_m(2))//' by '//rtoa(worst)// &
                                                       ' (move the bodies apart or fix the mesh)')
   end subroutine check_overlap

   !> Correct the predicted accelerations so that every active gap closes at t(n+2): the one
   !> entry of the step (the deck's stepper and the legacy API's hosts call it with their own
   !> arrays). x = x(n+1), vt = v~(n+1) (eq. 4.4), a = a~(n+1) on entry and a(n+1) on exit,
   !> minv the inverse mass per dof (0: rigid, prescribed or inactive), dt_prev = dt(n) (0 at
   !> t = 0), dt = dt(n+1); fcon = nodal contact forces, nactive = constraints in force.
   !> `rb`: the free rigid bodies, three-dof bodies in the corrector (doc/loads.md, section 5);
   !> the caller moves them with the contact forces on their nodes. With friction
   !> (doc/friction.md) fcon carries the friction forces too; they are also in self%ffric.
   !> fext, fint: the external and internal forces at t(n+1), needed by massless faces
   !> (LAGRange,ENERgy, doc/impact.md eq. I.5) once `face` is set up.
   subroutine contact_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err, rb, fext, fint)
      class(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(inout) :: fcon(2, nnode)
      integer, intent(out) :: nactive
      type(error_t), allocatable, intent(out) :: err
      type(rigid_dofs_t), intent(inout), optional :: rb
      real(wp), intent(in), optional :: fext(2, nnode), fint(2, nnode)
      integer :: k, j, i, node
      real(wp) :: c, gnow, pen, t0, t1, mu
      logical :: touched

      nactive = 0
      if (.not. self%active) return
      t0 = wall_time()
      if (.not. (self%keep_fcon .and. self%fcon_clean)) fcon = 0.0_wp
      self%fcon_clean = .false.
      touched = .false.
      call predicted_positions(self, nnode, x, vt, a, dt)
      ! c = dt(n+1) (dt(n) + dt(n+1)) / 2, eq. 4.7
      c = 0.5_wp*dt*(dt_prev + dt)
      if (self%face%active) then
         ! massless faces: the free solve places them at their trial positions (eq. I.5, I.7)
         if (.not. (present(fext) .and. present(fint))) then
            call make_error(err, 'LAGRange,ENERgy needs the forces of the step (contact_t%correct: fext, fint)')
            return
         end if
         if (.not. allocated(self%fres)) allocate (self%fres(2, nnode))
         self%fres = fext - fint
         call self%face%trial(nnode, x, self%fres, c, self%xp, a, err)
         if (allocated(err)) return
      end if
      do k = 1, size(self%results)
         self%results(k)%fnormal = 0.0_wp
         self%results(k)%force = 0.0_wp
         self%results(k)%nactive = 0
         self%results(k)%penetration = 0.0_wp
         self%results(k)%pmax = 0.0_wp
      end do
      if (self%friction) call friction_begin(self)
      self%cs%friction = self%friction
      call self%cs%reserve(64)
      if (self%auto_pass%method == METHOD_PENALTY) then
         ! penalty: the springs act on the positions at t(n+1) (penalty_pass)
         call auto_passes(self, nnode, x, x, self%depth, kept=.true.)
      else
         call auto_passes(self, nnode, x, self%xp, self%depth, kept=.true.)
      end if
      ! the narrow phase of every Lagrange pass at once (src/exic/contact/narrow.f90); with
      ! penalty passes, which change node normals and forces, pass by pass in order
      if (.not. self%any_penalty) call narrow_passes(self, nnode, x, minv, 1, self%npass)
      do k = 1, self%npass
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            if (ps%method == METHOD_PENALTY) then
               call surface_normals(self, sl, nnode, x)
               call penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, dt_prev, fcon, nactive)
               if (ps%broad%ncand > 0) touched = .true.
               cycle
            end if
            if (self%any_penalty) call narrow_passes(self, nnode, x, minv, k, k)
            if (ps%broad%ncand == 0) cycle
            do j = 1, ps%hits%n
               node = ps%hits%slave(j)
               associate (m1 => ps%hits%master(1, j), m2 => ps%hits%master(2, j), &
                          al => ps%hits%alpha(j), nr => ps%hits%normal(:, j))
                  ! gap at t(n+1) along the frozen normal (eq. 3.19)
                  gnow = dot_product(x(:, node) - (1.0_wp - al)*x(:, m1) - al*x(:, m2), nr)
                  if (ps%friction) then
                     ! the step's coefficient from the slave's last state (eq. F12)
                     mu = coulomb_mu(ps%law(1), ps%law(2), ps%law(3), self%vslip(node))
                     call self%cs%add(node, m1, m2, al, nr, ps%hits%gap(j), gnow, ps%pair, mu)
                  else
                     call self%cs%add(node, m1, m2, al, nr, ps%hits%gap(j), gnow, ps%pair)
                  end if
               end associate
            end do
         end associate
      end do
      t1 = wall_time()
      self%time_search = self%time_search + (t1 - t0)
      if (self%cs%n > 0) then
         if (self%friction) then
            call self%fr%solve(self%corr, self%cs, nnode, minv, c, x, self%xp, a, fcon, self%ffric, err, rb)
         else if (self%face%active) then
            call face_solve(self, nnode, x, minv, c, a, fcon, err, rb)
         else
            call self%corr%solve(self%cs, nnode, minv, c, a, fcon, err, rb)
         end if
         self%time_corrector = self%time_corrector + (wall_time() - t1)
         if (allocated(err)) return
         self%nredundant = self%nredundant + self%corr%nredundant
         do i = 1, self%cs%n
            associate (r => self%results(self%cs%pair(i)))
               pen = max(0.0_wp, -self%cs%gap_now(i))
               r%penetration = max(r%penetration, pen)
               if (self%cs%p(i) <= 0.0_wp) cycle
               r%nactive = r%nactive + 1
               r%fnormal = r%fnormal + self%cs%p(i)
               r%pmax = max(r%pmax, self%cs%p(i))
               r%work = r%work - self%cs%p(i)*self%cs%gap_now(i)
               r%force = r%force + self%cs%p(i)*self%cs%nrm(:, i)
            end associate
         end do
         nactive = nactive + count(self%cs%p(1:self%cs%n) > 0.0_wp)
      end if
      if (self%friction) call friction_results(self, dt)
      do k = 1, size(self%results)
         self%max_penetration = max(self%max_penetration, self%results(k)%penetration)
      end do
      if (self%friction) self%xold = x
      self%fcon_clean = self%cs%n == 0 .and. .not. touched
   end subroutine contact_correct

   !> The passes of AUTOmatic contact for this search: one search over every AUTOmatic
   !> surface (src/exic/contact/broad_all.f90) over x0 -> x1 with margin, then one pass per pair
   !> of surfaces with candidates, after the fixed passes, holding those candidates.
   subroutine auto_passes(self, nnode, x0, x1, margin, kept)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      logical, intent(in), optional :: kept    !< answer from the kept list (the step's search)
      integer :: g, need
      type(pass_t), allocatable :: tmp(:)
      logical :: use_kept

      use_kept = .false.
      if (present(kept)) use_kept = kept
      self%stamp = self%stamp + 1
      self%npass = self%nfixed
      if (.not. self%auto_pass%auto) return
      if (use_kept) then
         call self%auto%search_kept(nnode, x0, x1, margin)
      else
         call self%auto%search(nnode, x0, x1, margin)
      end if
      need = self%nfixed + self%auto%ngroup
      if (need > size(self%passes)) then
         allocate (tmp(max(need, 2*size(self%passes), 8)))
         tmp(1:size(self%passes)) = self%passes
         call move_alloc(tmp, self%passes)
      end if
      do g = 1, self%auto%ngroup
         associate (ps => self%passes(self%nfixed + g))
            ! the options of auto_pass (its work arrays stay those of the slot)
            ps%pair = self%auto_pass%pair
            ps%method = self%auto_pass%method
            ps%detection = self%auto_pass%detection
            ps%k = self%auto_pass%k
            ps%law = self%auto_pass%law
            ps%friction = self%auto_pass%friction
            ps%energy = self%auto_pass%energy
            ps%auto = .true.
            ps%slave = self%auto_first + self%auto%gslave(g)
            ps%master = self%auto_first + self%auto%gmaster(g)
            call self%auto%take(g, ps%broad)
         end associate
      end do
      self%npass = need
   end subroutine auto_passes

   !> Node normals of surface sf at positions x, once per search.
   subroutine surface_normals(self, sf, nnode, x)
      type(contact_t), intent(in) :: self
      type(surface_t), intent(inout) :: sf
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode)
      if (sf%nrm_stamp == self%stamp) return
      call node_normals(nnode, x, sf%nseg, sf%seg, sf%nnode, sf%where, sf%nrm)
      sf%nrm_stamp = self%stamp
   end subroutine surface_normals

   !> Every node of every contact surface, once (cnodes).
   subroutine contact_nodes(self, nnode)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      logical, allocatable :: on(:)
      integer :: k
      allocate (on(nnode), source=.false.)
      do k = 1, size(self%surfaces)
         on(self%surfaces(k)%nodes) = .true.
      end do
      self%cnodes = pack([(k, k=1, nnode)], on)
   end subroutine contact_nodes

   !> Predicted positions x~(n+2) = x + dt vt + dt^2/2 a (eq. 4.4) of the contact nodes, the
   !> only ones the search and the corrector read; with massless faces of every node, since the
   !> face's free solve (eq. I.5) reads the predicted motion of the interior nodes next to it.
   subroutine predicted_positions(self, nnode, x, vt, a, dt)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), a(2, nnode), dt
      integer :: k, node
      real(wp) :: h
      h = 0.5_wp*dt*dt
      if (self%face%active) then
         self%xp = x + dt*vt + h*a
         return
      end if
      do k = 1, size(self%cnodes)
         node = self%cnodes(k)
         self%xp(:, node) = x(:, node) + dt*vt(:, node) + h*a(:, node)
      end do
   end subroutine predicted_positions

   !> At the start of a step with friction: the Coulomb work of the last step, whose interval
   !> has now been stepped, joins the dissipation (doc/friction.md, eq. F17); the step's
   !> friction results and forces start from zero.
   subroutine friction_begin(self)
      type(contact_t), intent(inout) :: self
      integer :: k
      self%dissipation = self%dissipation + self%pending
      self%pending = 0.0_wp
      do k = 1, size(self%results)
         associate (r => self%results(k))
            r%dissipation = r%dissipation + r%pending
            r%pending = 0.0_wp
            r%ftangent = 0.0_wp
            r%nstick = 0
            r%nslip = 0
         end associate
      end do
      self%ffric = 0.0_wp
   end subroutine friction_begin

   !> After the frictional corrector: the pairs' friction results, the Coulomb work of the step
   !> (eq. F16, booked at the next step) and each slave's slip speed for the next step's
   !> coefficient (eq. F12); dt = dt(n+1).
   subroutine friction_results(self, dt)
      type(contact_t), intent(inout) :: self
      real(wp), intent(in) :: dt
      integer :: i, node
      real(wp) :: d, tng(2)
      self%vslip = -1.0_wp
      do i = 1, self%cs%n
         node = self%cs%node(1, i)
         if (self%cs%state(i) == 0) cycle
         associate (r => self%results(self%cs%pair(i)))
            tng = [-self%cs%nrm(2, i), self%cs%nrm(1, i)]
            r%force = r%force + self%cs%q(i)*tng
            r%ftangent = r%ftangent + abs(self%cs%q(i))
            if (self%cs%state(i) == 1) then
               r%nstick = r%nstick + 1
            else
               r%nslip = r%nslip + 1
               d = self%cs%mu(i)*self%cs%p(i)*abs(self%cs%slip(i))
               r%pending = r%pending + d
               self%pending = self%pending + d
               self%vslip(node) = abs(self%cs%slip(i))/dt
            end if
         end associate
      end do
   end subroutine friction_results

   !> Penalty baseline of one pass (src/exic/contact/penalty.f90): static detection at t(n+1),
   !> forces k x penetration (plus damping) on the hits, with the regularised friction law when
   !> the pass has friction; the pair's results. An AUTOmatic pass has its candidates from the
   !> search over all surfaces (over x -> x with margin depth, as broad_search here) and its
   !> tangential state from auto_hist, kept per pair of surfaces.
   subroutine penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, dt_prev, fcon, nactive)
      type(contact_t), intent(inout) :: self
      type(pass_t), intent(inout) :: ps
      type(surface_t), intent(inout) :: sl
      type(surface_t), intent(in) :: ms
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(inout) :: nactive
      integer :: j, n
      real(wp) :: diss
      if (.not. ps%auto) call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, self%depth)
      if (ps%broad%ncand == 0) return
      call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                           sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                           self%depth, FACING)
      n = ps%hits%n
      call grow(ps%pen, n)
      call grow(ps%fn, n)
      call grow(ps%f, n, 2)
      diss = 0.0_wp
      if (ps%friction) then
         call grow(ps%q, n)
         call grow(ps%state, n)
         if (ps%auto) then
            call self%auto_hist%load(ps%slave, ps%master, self%hwork)
            call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n), &
                                self%hwork, ps%law, self%xold, dt_prev, self%ffric, ps%q(1:n), ps%state(1:n), diss)
            call self%auto_hist%store(ps%slave, ps%master, self%hwork)
         else
            call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n), &
                                ps%hist, ps%law, self%xold, dt_prev, self%ffric, ps%q(1:n), ps%state(1:n), diss)
         end if
      else
         call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n))
      end if
      associate (r => self%results(ps%pair), pen => ps%pen, fn => ps%fn, f => ps%f)
         do j = 1, n
            if (pen(j) <= 0.0_wp) cycle
            r%nactive = r%nactive + 1
            r%fnormal = r%fnormal + fn(j)
            r%pmax = max(r%pmax, fn(j))
            r%force = r%force + f(:, j)
            r%penetration = max(r%penetration, pen(j))
            nactive = nactive + 1
            if (.not. ps%friction) cycle
            r%ftangent = r%ftangent + abs(ps%q(j))
            if (ps%state(j) == 1) r%nstick = r%nstick + 1
            if (ps%state(j) == 2) r%nslip = r%nslip + 1
         end do
         ! the realised slip of [t(n), t(n+1)] is booked at once
         r%dissipation = r%dissipation + diss
         self%dissipation = self%dissipation + diss
      end associate
   end subroutine penalty_pass

   !> Critical step of the penalty springs: 1 / sqrt(k (1/m_s + 1/m_master)) over the slave
   !> nodes, m_master the smallest mass of the pass's master nodes (huge when no pass uses
   !> penalty). Lagrange contact never limits the step.
   !> The linear limit of a spring is 2/omega; half of it is taken because a spring that
   !> switches on and off within the step (impact, chatter) pumps energy at the linear limit:
   !> a bar struck at 0.9 x 2/omega gained 19 % energy, at 0.5 x 2/omega it held within 0.3 %.
   real(wp) function contact_stable_dt(self, nnode, minv) result(dt)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode)
      integer :: k
      dt = huge(1.0_wp)
      if (.not. (self%active .and. self%any_penalty)) return
      do k = 1, self%nfixed
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            if (ps%method /= METHOD_PENALTY) cycle
            call spring_dt(ps%k, nnode, minv, sl%nnode, sl%nodes, smallest_mass(nnode, minv, ms%nnode, ms%nodes), dt)
         end associate
      end do
      if (.not. (self%auto_pass%auto .and. self%auto_pass%method == METHOD_PENALTY)) return
      call auto_spring_dt(self%auto_pass%k, nnode, minv, self%auto%nsurf, self%auto%node_first, self%auto%nodes, dt)
   end function contact_stable_dt

   !> A TPLOt `cont,pair,comp` value: 1 normal force, 2-3 force x, y on the slave side (normal
   !> and friction), 4 active constraints, 5 largest penetration at t(n+1), 6 largest multiplier
   !> [ext], 7 work of the pair's multipliers over the run (pair_result_t%work) [ext]; friction
   !> (doc/friction.md, section 7) [ext]: 8 friction force sum |q|, 9 constraints that stick,
   !> 10 constraints that slip, 11 frictional dissipation over the run.
   real(wp) function contact_pair_value(self, pair, comp) result(val)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: pair, comp
      integer :: k
      real(wp) :: vals(11)
      val = 0.0_wp
      if (.not. self%active) return
      do k = 1, size(self%results)
         if (self%results(k)%id /= pair) cycle
         associate (r => self%results(k))
            vals = [r%fnormal, r%force(1), r%force(2), real(r%nactive, wp), r%penetration, r%pmax, r%work, &
                    r%ftangent, real(r%nstick, wp), real(r%nslip, wp), r%dissipation]
         end associate
         if (comp >= 1 .and. comp <= size(vals)) val = vals(comp)
         return
      end do
   end function contact_pair_value

   !> Surfaces and passes, one line each (newline separated), for <stem>.out.
   function contact_summary(self) result(text)
      class(contact_t), intent(in) :: self
      character(len=:), allocatable :: text
      type(text_buffer_t) :: buf
      integer :: k
      character(len=*), parameter :: methods(2) = ['Lagrange (implicit corrector)', 'penalty                      ']
      character(len=*), parameter :: detections(2) = ['swept ', 'static']
      character(len=1), parameter :: nl = new_line('a')
      if (.not. self%active) then
         text = 'contact: none'
         return
      end if
      do k = 1, size(self%surfaces)
         associate (sf => self%surfaces(k))
            if (sf%id >= 0) then
               call buf%add('contact surface '//itoa(sf%id)//': '//itoa(sf%nseg)//' segments, '// &
                            itoa(sf%nnode)//' nodes'//nl)
            else
               call buf%add('contact surface of region '//itoa(-sf%id - 1)//' (automatic): '// &
                            itoa(sf%nseg)//' segments, '//itoa(sf%nnode)//' nodes'//nl)
            end if
         end associate
      end do
      do k = 1, self%nfixed
         associate (ps => self%passes(k))
            call buf%add('contact pass '//itoa(k)//' of pair '//itoa(self%results(ps%pair)%id)// &
                         ': nodes of surface '//itoa(ps%slave)//' against segments of surface '// &
                         itoa(ps%master)//', '//trim(methods(ps%method))//', '//trim(detections(ps%detection)))
            if (ps%energy) call buf%add(', massless faces (ENERgy)')
            if (ps%friction) call buf%add(', Coulomb friction mus '//rtoa(ps%law(1))//' mud '// &
                                          rtoa(ps%law(2))//' decay '//rtoa(ps%law(3)))
            if (k < self%nfixed) call buf%add(nl)
         end associate
      end do
      text = buf%text()
      if (self%auto_pass%auto) then
         associate (ps => self%auto_pass)
            if (self%nfixed > 0) text = text//nl
            text = text//'contact passes of pair '//itoa(self%results(ps%pair)%id)//' (automatic): nodes of '// &
                   'each of surfaces '//itoa(self%auto_first + 1)//'-'//itoa(self%auto_first + self%auto%nsurf)// &
                   ' against segments of each other one near it (one search over all of them per step), '// &
                   trim(methods(ps%method))//', '//trim(detections(ps%detection))
            if (ps%energy) text = text//', massless faces (ENERgy)'
            if (ps%friction) text = text//', Coulomb friction mus '//rtoa(ps%law(1))//' mud '// &
                                    rtoa(ps%law(2))//' decay '//rtoa(ps%law(3))
         end associate
      end if
   end function contact_summary

   !> Every contact segment of every surface, (2, nedge); empty without contact.
   function contact_edges(self) result(e)
      class(contact_t), intent(in) :: self
      integer, allocatable :: e(:, :)
      integer :: k, n
      n = 0
      if (self%active) n = sum([(self%surfaces(k)%nseg, k=1, size(self%surfaces))])
      allocate (e(2, n))
      n = 0
      if (.not. self%active) return
      do k = 1, size(self%surfaces)
         e(:, n + 1:n + self%surfaces(k)%nseg) = self%surfaces(k)%seg
         n = n + self%surfaces(k)%nseg
      end do
   end function contact_edges

end module exic_contact_contact
