!> Contact in the time step: surfaces, passes, search and the implicit corrector (seed 3-6).
!>
!> Each PAIR becomes one pass (SELF), two (SYMMetric: each surface's nodes against the other's
!> segments) or, for NTOS, its pass and a corner pass (the master's convex corners, turning by 30
!> degrees or more, against the slave surface's segments; doc/contact-detection.md, "Corner
!> pass of a one-pass pair"); AUTOmatic makes a surface of every region's free boundary and
!> pairs every two of them: one search over all its surfaces per step makes the passes of the
!> pairs found near (src/exic/contact/broad_all.f90), Lagrange or penalty. Per step and pass: predicted
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
!>
!> The module holds the types and the queries (stable step of penalty springs, pair values,
!> summary, edges); its submodules the rest: contact_setup.f90 (init: surfaces, passes, the
!> overlap check), contact_step.f90 (correct: the step's search, constraints, corrector and
!> penalty passes), narrow.f90 (the narrow phase, on the threads) and faces.f90 (the massless
!> faces: their nodes and dofs, the corrector's solve with them).
module exic_contact_contact
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_base_text_buffer, only: text_buffer_t
   use exic_contact_spec, only: METHOD_LAGRANGE, METHOD_PENALTY, DETECT_SWEPT, contact_spec_t
   use exic_mesh_boundary, only: node_normals, bodies_elements
   use exic_contact_broad, only: broad_t, broad_search_kept, drop_flat_fixed, keep_convex_corners
   use exic_contact_broad_all, only: broad_all_t
   use exic_contact_detect, only: contact_set_t, detect_contacts
   use exic_contact_corrector, only: constraints_t, corrector_t
   use exic_contact_friction, only: friction_t
   use exic_contact_penalty, only: penalty_history_t, smallest_mass, spring_dt, auto_spring_dt
   use exic_contact_pair_history, only: pair_history_t
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
   !> Share of the mean segment length up to which a slave node found behind a master segment at
   !> the start of a step is still caught (and pushed back by the corrector). The corrector closes
   !> each gap along a normal frozen over the step (seed section 4), so a node that slides past
   !> a master node onto a segment of another slope, or along a curved surface, ends the step
   !> behind it by the slope change times the slide: far above rounding, yet a tiny share of the
   !> segment. A node deeper than this is taken to be on the far side of the surface.
   real(wp), parameter :: DEPTH_SHARE = 0.1_wp
   !> The same share for the corner pass of an NTOS pair (a master's convex corner as a slave):
   !> a corner that slides in contact across a kink of the slave surface ends a step behind it
   !> by the slide times the kink, far below this; a corner found deeper at the start of a step
   !> entered the slave's body between its nodes before it was a corner (one-pass contact lets
   !> a master's node do so) and is left to the pass whose slaves those nodes are, not pushed
   !> out in one step (doc/contact-detection.md, "Corner pass of a one-pass pair").
   real(wp), parameter :: CORNER_DEPTH_SHARE = 0.01_wp

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
      !> corner pass of a one-pass (NTOS) pair: the master's convex corners as slaves of the slave
      !> surface's segments (keep_convex_corners; doc/contact-detection.md, "Corner pass")
      logical :: corners = .false.
      !> corner pass: the slaves it held at the last step, increasing (contact_step: a corner found
      !> behind the slave surface at the start of a step is held only when it was held before)
      integer, allocatable :: held(:)
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
      real(wp) :: depth_corner = 0.0_wp        !< the same for the corner passes (CORNER_DEPTH_SHARE x lref)
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
      !> Build surfaces and passes from the CONTact block `spec`; refuse bodies that overlap.
      !> xref(2, nnode): the positions whose segment lengths set the search depth (the reference
      !> mesh); x(2, nnode): the positions now (checked for overlap); conn(4, nelem), region(nelem),
      !> mat(nelem): the elements whose free boundaries make REGIon, MATErial and AUTOmatic surfaces;
      !> modulus: the largest constrained modulus lambda + 2 mu of the solids (PENAlty,SCALe).
      module subroutine contact_init(self, spec, nnode, xref, x, nelem, conn, region, mat, modulus, err)
         class(contact_t), intent(inout) :: self
         type(contact_spec_t), intent(in) :: spec
         integer, intent(in) :: nnode, nelem
         real(wp), intent(in) :: xref(2, nnode), x(2, nnode)
         integer, intent(in) :: conn(4, nelem), region(nelem), mat(nelem)
         real(wp), intent(in) :: modulus
         type(error_t), allocatable, intent(out) :: err
      end subroutine contact_init

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
      module subroutine contact_correct(self, nnode, x, vt, a, minv, dt_prev, dt, fcon, nactive, err, rb, fext, fint)
         class(contact_t), intent(inout) :: self
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev, dt
         real(wp), intent(inout) :: a(2, nnode)
         real(wp), intent(inout) :: fcon(2, nnode)
         integer, intent(out) :: nactive
         type(error_t), allocatable, intent(out) :: err
         type(rigid_dofs_t), intent(inout), optional :: rb
         real(wp), intent(in), optional :: fext(2, nnode), fint(2, nnode)
      end subroutine contact_correct

      !> The passes of AUTOmatic contact for this search: one search over every AUTOmatic
      !> surface (src/exic/contact/broad_all.f90) over x0 -> x1 with margin, then one pass per pair
      !> of surfaces with candidates, after the fixed passes, holding those candidates.
      module subroutine auto_passes(self, nnode, x0, x1, margin, kept)
         type(contact_t), intent(inout) :: self
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
         logical, intent(in), optional :: kept    !< answer from the kept list (the step's search)
      end subroutine auto_passes

      !> Node normals of surface sf at positions x, once per search.
      module subroutine surface_normals(self, sf, nnode, x)
         type(contact_t), intent(in) :: self
         type(surface_t), intent(inout) :: sf
         integer, intent(in) :: nnode
         real(wp), intent(in) :: x(2, nnode)
      end subroutine surface_normals

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
            if (ps%corners) call buf%add(', the convex corners of surface '//itoa(ps%slave)//' only')
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
