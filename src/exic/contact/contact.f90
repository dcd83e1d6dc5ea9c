!> Contact in the time step: surfaces, passes, search and the implicit corrector (seed 3-6).
!>
!> Each PAIR becomes one pass (NTOS, SELF) or two (SYMMetric: each surface's nodes against the
!> other's segments); AUTOmatic makes a surface of every region's free boundary and a symmetric
!> pair of every two regions. Per step and pass: predicted positions x~(n+2) (eq. 4.4), the
!> broad phase on swept boxes, swept (or static) node-to-segment detection (eq. 6.1-6.6), and
!> candidate constraints with the predicted gap of eq. 3.19 at t(n+2) and a frozen normal. All
!> Lagrange candidates of all passes are solved together by the corrector (eq. 4.5-4.7);
!> penalty passes add k x penetration forces at t(n+1) instead.
!>
!> Everything comes in as plain arrays: the CONTact block's spec, the positions, the element
!> connectivity with region and material numbers (for REGIon/MATErial and AUTOmatic surfaces),
!> and per step the positions, velocities, accelerations and inverse masses. The deck path
!> (src/exic/explicit/step.f90) and the legacy API (src/exic/legacy) call the same two entries,
!> `init` and `correct`.
module exic_contact_contact
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_contact_spec, only: SURF_REGION, SURF_MATERIAL, SURF_FACETS, SURF_NODES, PAIR_NTOS, &
                                PAIR_SYMMETRIC, PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, &
                                DETECT_SWEPT, DETECT_STATIC, pair_spec_t, contact_spec_t
   use exic_mesh_boundary, only: free_edges, surface_nodes, segment_links, locate_nodes, node_normals
   use exic_contact_broad, only: broad_t, broad_search
   use exic_contact_detect, only: contact_set_t, detect_contacts
   use exic_contact_corrector, only: constraints_t, corrector_t
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_massless_face, only: massless_face_t
   implicit none
   private

   public :: contact_t

   !> A slave node is paired with a master segment only when its own outward normal ns and the
   !> segment's normal n face each other: ns . n < FACING = cos(120 degrees). A node at a right-
   !> angled corner meeting a face head-on gives -0.71; a face node meeting the side face of the
   !> other body's corner (deformed a little off 90 degrees) gives about 0 and is rejected, so
   !> corners of bodies of equal height do not pair with each other's side faces.
   real(wp), parameter :: FACING = -0.5_wp
   !> Viscous damping of penalty contact as a fraction of critical (LS-DYNA's customary 10 %).
   real(wp), parameter :: PENALTY_DAMPING = 0.1_wp
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
   end type surface_t

   !> One pass: the nodes of surface `slave` against the segments of surface `master`.
   type :: pass_t
      integer :: pair = 0                      !< index into pair results
      integer :: slave = 0, master = 0         !< surface indices
      integer :: method = METHOD_LAGRANGE
      logical :: energy = .false.              !< LAGRange,ENERgy: massless faces (doc/impact.md)
      integer :: detection = DETECT_SWEPT
      real(wp) :: k = 0.0_wp                   !< penalty stiffness
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
   end type pair_result_t

   !> All contact of a model. Inactive (no work at all) when the deck has no CONTact block.
   type :: contact_t
      logical :: active = .false.
      logical :: any_penalty = .false.
      type(surface_t), allocatable :: surfaces(:)
      type(pass_t), allocatable :: passes(:)
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
   contains
      procedure :: init => contact_init
      procedure :: correct => contact_correct
      procedure :: stable_dt => contact_stable_dt
      procedure :: pair_value => contact_pair_value
      procedure :: summary => contact_summary
      procedure :: edges => contact_edges
      procedure :: face_nodes => contact_face_nodes
   end type contact_t

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
      integer :: k, np, nsurf
      real(wp) :: len_sum
      integer :: nlen

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
      allocate (self%xp(2, nnode))
      np = size(self%passes)
      do k = 1, np
         if (self%passes(k)%method == METHOD_PENALTY) self%any_penalty = .true.
      end do
      call penalty_stiffness(self, modulus)
      call check_overlap(self, nnode, x, err)
   end subroutine contact_init

   !> Surfaces of the SURFace records, plus one per region for AUTOmatic.
   subroutine build_surfaces(self, spec, nelem, conn, region, mat, err)
      type(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      integer, intent(in) :: nelem
      integer, intent(in) :: conn(4, nelem), region(nelem), mat(nelem)
      type(error_t), allocatable, intent(out) :: err
      integer :: ns, nauto, k, r
      integer, allocatable :: regions(:)
      logical, allocatable :: sel(:)

      ns = 0
      if (allocated(spec%surfaces)) ns = size(spec%surfaces)
      nauto = 0
      if (spec%automatic) then
         regions = unique(region)
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
               if (size(sp%nodes) > 0) sf%nodes = unique(sp%nodes)
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
         r = regions(k)
         associate (sf => self%surfaces(ns + k))
            sf%id = -r - 1          ! automatic surface of region r
            sel = region == r
            call free_edges(nelem, conn, sel, sf%seg, err)
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
            allocate (sf%nrm(2, sf%nnode))
         end associate
      end do
   end subroutine build_surfaces

   !> Passes of the PAIR records (two for SYMMetric) and of AUTOmatic (two per region pair).
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
      allocate (p(2*npair + nauto*max(nauto - 1, 0)))
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
         self%results(npair + 1)%id = maxid + 1
         do i = ns + 1, ns + nauto
            do j = ns + 1, ns + nauto
               if (i /= j) call add_pass(p, np, npair + 1, i, j, spec%auto_options)
            end do
         end do
      end if
      npass = np
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
   end subroutine add_pass

   !> PENAlty,SCALe,f: k = f x modulus, the largest constrained modulus lambda + 2 mu of the solids.
   subroutine penalty_stiffness(self, modulus)
      type(contact_t), intent(inout) :: self
      real(wp), intent(in) :: modulus
      integer :: k
      do k = 1, size(self%passes)
         if (self%passes(k)%k < 0.0_wp) self%passes(k)%k = -self%passes(k)%k*modulus
      end do
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

   !> Bodies that overlap at the start are an error naming the worst node, segment and depth.
   subroutine check_overlap(self, nnode, x, err)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, j, worst_node, worst_m(2)
      real(wp) :: worst
      character(len=200) :: buf

      worst = 0.0_wp
      worst_node = 0
      do k = 1, size(self%passes)
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            call node_normals(nnode, x, sl%nseg, sl%seg, sl%nnode, sl%where, sl%nrm)
            call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, &
                              0.5_wp*self%lref)
            call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                                 sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                 0.5_wp*self%lref, FACING)
            do j = 1, ps%hits%n
               if (-ps%hits%gap(j) > worst) then
                  worst = -ps%hits%gap(j)
                  worst_node = ps%hits%slave(j)
                  worst_m = ps%hits%master(:, j)
               end if
            end do
         end associate
      end do
      if (worst > 1.0e-8_wp*self%lref) then
         write (buf, '(a,i0,a,i0,a,i0,a,es10.3)') 'bodies overlap at the start: node ', worst_node, &
            ' is inside segment ', worst_m(1), '-', worst_m(2), ' by ', worst
         call make_error(err, trim(buf)//' (move the bodies apart or fix the mesh)')
      end if
   end subroutine check_overlap

   !> Correct the predicted accelerations so that every active gap closes at t(n+2): the one
   !> entry of the step (the deck's stepper and the legacy API's hosts call it with their own
   !> arrays). x = x(n+1), vt = v~(n+1) (eq. 4.4), a = a~(n+1) on entry and a(n+1) on exit,
   !> minv the inverse mass per dof (0: rigid, prescribed or inactive), dt_prev = dt(n) (0 at
   !> t = 0), dt = dt(n+1); fcon = nodal contact forces, nactive = constraints in force.
   !> `rb`: the free rigid bodies, three-dof bodies in the corrector (doc/loads.md, section 5);
   !> the caller moves them with the contact forces on their nodes.
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
      real(wp) :: c, gnow, pen, t0, t1

      nactive = 0
      if (.not. self%active) return
      t0 = wall_time()
      fcon = 0.0_wp
      ! predicted positions at t(n+2), eq. 4.4
      self%xp = x + dt*vt + (0.5_wp*dt*dt)*a
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
      call self%cs%reserve(64)
      do k = 1, size(self%passes)
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            call node_normals(nnode, x, sl%nseg, sl%seg, sl%nnode, sl%where, sl%nrm)
            if (ps%method == METHOD_PENALTY) then
               call penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, fcon, nactive)
               cycle
            end if
            call broad_search(ps%broad, nnode, x, self%xp, sl%nnode, sl%nodes, ms%nseg, ms%seg, self%depth)
            if (ps%broad%ncand == 0) cycle
            call detect_contacts(ps%hits, ps%detection, nnode, x, self%xp, sl%nnode, sl%nodes, &
                                 sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                 self%depth, FACING)
            do j = 1, ps%hits%n
               node = ps%hits%slave(j)
               associate (m1 => ps%hits%master(1, j), m2 => ps%hits%master(2, j), &
                          al => ps%hits%alpha(j), nr => ps%hits%normal(:, j))
                  ! gap at t(n+1) along the frozen normal (eq. 3.19)
                  gnow = dot_product(x(:, node) - (1.0_wp - al)*x(:, m1) - al*x(:, m2), nr)
                  call self%cs%add(node, m1, m2, al, nr, ps%hits%gap(j), gnow, ps%pair)
               end associate
            end do
         end associate
      end do
      t1 = wall_time()
      self%time_search = self%time_search + (t1 - t0)
      if (self%cs%n > 0) then
         if (self%face%active) then
            call self%corr%solve(self%cs, nnode, minv, c, a, fcon, err, rb, self%face)
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
      do k = 1, size(self%results)
         self%max_penetration = max(self%max_penetration, self%results(k)%penetration)
      end do
   end subroutine contact_correct

   !> Penalty baseline: f = k (-g) n on the slave at t(n+1), opposite on the master nodes, plus
   !> a viscous part -c v_n with c = 2 PENALTY_DAMPING sqrt(k m) (m the pair's effective mass,
   !> v_n the relative normal velocity of the predictor), the normal force never tensile. The
   !> damping is the usual companion of explicit penalty contact: without it, the on/off
   !> switching of stiff springs within a step feeds energy into the struck nodes.
   subroutine penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, fcon, nactive)
      type(contact_t), intent(inout) :: self
      type(pass_t), intent(inout) :: ps
      type(surface_t), intent(in) :: sl, ms
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode)
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(inout) :: nactive
      integer :: j, node, m1, m2
      real(wp) :: f(2), al, pen, nr(2), vn, w, fn
      call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, self%depth)
      if (ps%broad%ncand == 0) return
      call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                           sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                           self%depth, FACING)
      do j = 1, ps%hits%n
         pen = -ps%hits%gap(j)
         if (pen <= 0.0_wp) cycle
         node = ps%hits%slave(j)
         m1 = ps%hits%master(1, j)
         m2 = ps%hits%master(2, j)
         al = ps%hits%alpha(j)
         nr = ps%hits%normal(:, j)
         vn = dot_product(vt(:, node) - (1.0_wp - al)*vt(:, m1) - al*vt(:, m2), nr)
         w = minv(1, node) + (1.0_wp - al)**2*minv(1, m1) + al**2*minv(1, m2)
         fn = ps%k*pen
         if (w > 0.0_wp) fn = fn - 2.0_wp*PENALTY_DAMPING*sqrt(ps%k/w)*vn
         fn = max(fn, 0.0_wp)
         f = fn*nr
         fcon(:, node) = fcon(:, node) + f
         fcon(:, m1) = fcon(:, m1) - (1.0_wp - al)*f
         fcon(:, m2) = fcon(:, m2) - al*f
         a(:, node) = a(:, node) + minv(:, node)*f
         a(:, m1) = a(:, m1) - minv(:, m1)*(1.0_wp - al)*f
         a(:, m2) = a(:, m2) - minv(:, m2)*al*f
         associate (r => self%results(ps%pair))
            r%nactive = r%nactive + 1
            r%fnormal = r%fnormal + fn
            r%pmax = max(r%pmax, fn)
            r%force = r%force + f
            r%penetration = max(r%penetration, pen)
         end associate
         nactive = nactive + 1
      end do
   end subroutine penalty_pass

   !> Critical step of the penalty springs: 1 / sqrt(k (1/m_s + 1/m_master)) over the slave
   !> nodes (huge when no pass uses penalty). Lagrange contact never limits the step.
   !> The linear limit of a spring is 2/omega; half of it is taken because a spring that
   !> switches on and off within the step (impact, chatter) pumps energy at the linear limit:
   !> a bar struck at 0.9 x 2/omega gained 19 % energy, at 0.5 x 2/omega it held within 0.3 %.
   real(wp) function contact_stable_dt(self, nnode, minv) result(dt)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode)
      integer :: k, j
      real(wp) :: mmin, w2
      dt = huge(1.0_wp)
      if (.not. (self%active .and. self%any_penalty)) return
      do k = 1, size(self%passes)
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            if (ps%method /= METHOD_PENALTY) cycle
            mmin = huge(1.0_wp)
            do j = 1, ms%nnode
               if (minv(1, ms%nodes(j)) > 0.0_wp) mmin = min(mmin, 1.0_wp/minv(1, ms%nodes(j)))
            end do
            do j = 1, sl%nnode
               w2 = ps%k*(minv(1, sl%nodes(j)) + merge(1.0_wp/mmin, 0.0_wp, mmin < huge(1.0_wp)))
               if (w2 > 0.0_wp) dt = min(dt, 1.0_wp/sqrt(w2))
            end do
         end associate
      end do
   end function contact_stable_dt

   !> A TPLOt `cont,pair,comp` value: 1 normal force, 2-3 force x, y on the slave side,
   !> 4 active constraints, 5 largest penetration at t(n+1), 6 largest multiplier [ext],
   !> 7 work of the pair's multipliers over the run (pair_result_t%work) [ext].
   real(wp) function contact_pair_value(self, pair, comp) result(val)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: pair, comp
      integer :: k
      val = 0.0_wp
      if (.not. self%active) return
      do k = 1, size(self%results)
         if (self%results(k)%id /= pair) cycle
         select case (comp)
         case (1)
            val = self%results(k)%fnormal
         case (2)
            val = self%results(k)%force(1)
         case (3)
            val = self%results(k)%force(2)
         case (4)
            val = real(self%results(k)%nactive, wp)
         case (5)
            val = self%results(k)%penetration
         case (6)
            val = self%results(k)%pmax
         case (7)
            val = self%results(k)%work
         end select
         return
      end do
   end function contact_pair_value

   !> Surfaces and passes, one line each (newline separated), for <stem>.out.
   function contact_summary(self) result(text)
      class(contact_t), intent(in) :: self
      character(len=:), allocatable :: text
      integer :: k
      character(len=*), parameter :: methods(2) = ['Lagrange (implicit corrector)', 'penalty                      ']
      character(len=*), parameter :: detections(2) = ['swept ', 'static']
      character(len=1), parameter :: nl = new_line('a')
      if (.not. self%active) then
         text = 'contact: none'
         return
      end if
      text = ''
      do k = 1, size(self%surfaces)
         associate (sf => self%surfaces(k))
            if (sf%id >= 0) then
               text = text//'contact surface '//itoa(sf%id)//': '//itoa(sf%nseg)//' segments, '// &
                      itoa(sf%nnode)//' nodes'//nl
            else
               text = text//'contact surface of region '//itoa(-sf%id - 1)//' (automatic): '// &
                      itoa(sf%nseg)//' segments, '//itoa(sf%nnode)//' nodes'//nl
            end if
         end associate
      end do
      do k = 1, size(self%passes)
         associate (ps => self%passes(k))
            text = text//'contact pass '//itoa(k)//' of pair '//itoa(self%results(ps%pair)%id)// &
                   ': nodes of surface '//itoa(ps%slave)//' against segments of surface '// &
                   itoa(ps%master)//', '//trim(methods(ps%method))//', '//trim(detections(ps%detection))
            if (ps%energy) text = text//', massless faces (ENERgy)'
            if (k < size(self%passes)) text = text//nl
         end associate
      end do
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

   !> Nodes of the surfaces (slave and master) of the passes that ask for LAGRange,ENERgy: the
   !> candidates for massless faces (doc/impact.md, section 3.1; the caller removes rigid and
   !> prescribed nodes and those of elements that would keep no mass).
   function contact_face_nodes(self, nnode) result(on)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: nnode
      logical :: on(nnode)
      integer :: k
      on = .false.
      if (.not. self%active) return
      do k = 1, size(self%passes)
         if (.not. self%passes(k)%energy) cycle
         on(self%surfaces(self%passes(k)%slave)%nodes) = .true.
         on(self%surfaces(self%passes(k)%master)%nodes) = .true.
      end do
   end function contact_face_nodes

   !> Sorted unique values.
   function unique(a) result(u)
      integer, intent(in) :: a(:)
      integer, allocatable :: u(:)
      integer :: i
      logical, allocatable :: seen(:)
      integer :: lo, hi
      lo = minval(a)
      hi = maxval(a)
      allocate (seen(lo:hi), source=.false.)
      do i = 1, size(a)
         seen(a(i)) = .true.
      end do
      u = pack([(i, i=lo, hi)], seen)
   end function unique

end module exic_contact_contact
