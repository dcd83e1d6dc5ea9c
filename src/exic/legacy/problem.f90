!> The work behind the legacy API: contact problems built from a host's plain arrays.
!>
!> A host hands over its node count, reference coordinates and lumped masses, and either its
!> element connectivity with a body number per element (each body's free boundary becomes a
!> contact surface, as REGIon surfaces do in a deck) or its own segments and slave node sets.
!> From these a contact_spec_t (as a deck's CONTact block) is built and the ordinary contact_t
!> of the deck path does the work on the host's arrays, unchanged: contact_t%init once and
!> contact_t%correct once per step (seed sections 3-6; eq. 4.4-4.7).
!>
!> Every procedure here takes explicit-shape arrays sized by earlier arguments, default
!> integers and real(wp) = double precision, and returns an integer `ierr` (codes in
!> exic_legacy_registry); a failure also stores a message retrievable with problem_message.
!> `who` is the name of the calling entry point, used in messages.
!>
!> Per step the host's arrays go to contact_t%correct as they are; the API itself touches
!> only the nodes of the contact surfaces (for its queries) and checks the positions, so its
!> cost over a native call is small (doc/performance.md, "Legacy API overhead").
module exic_legacy_problem
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int64
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_mesh_smoothing, only: quad_area
   use exic_base_error, only: error_t
   use exic_contact_contact, only: contact_t
   use exic_contact_spec, only: SURF_REGION, SURF_FACETS, SURF_NODES, PAIR_NTOS, PAIR_SYMMETRIC, &
                                PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, DETECT_SWEPT, DETECT_STATIC
   use exic_legacy_face, only: check_face, face_step_ok, face_motion, face_gap
   use exic_legacy_registry, only: problem_t, registry_add, registry_get, registry_free, set_error, &
                                   last_message, IERR_OK, IERR_ARGUMENT, IERR_HANDLE, IERR_SETUP, &
                                   IERR_SOLVE, VEL_FULL_STEP, VEL_HALF_STEP
   implicit none
   private

   public :: problem_create_mesh, problem_create_segments, problem_set_fixed, problem_set_pair
   public :: problem_set_option, problem_step, problem_pair_results, problem_ncon
   public :: problem_constraints, problem_work, problem_free, problem_message
   public :: problem_set_friction, problem_pair_friction, problem_set_face, problem_step_face

   !> Option codes of problem_set_option.
   integer, parameter, public :: OPT_VELOCITY_FORM = 1

contains

   ! ------------------------------------------------------------------ creation

   !> A problem from connectivity: ix(4, nelem) counter-clockwise nodes, ibody(nelem) >= 1.
   !> ipair(6, npair): slave body, master body, method, detection, passes, rigid master;
   !> ppair(npair): penalty stiffness (method 2). On success h > 0, else h = 0.
   subroutine problem_create_mesh(who, nnode, x0, mass, nelem, ix, ibody, npair, ipair, ppair, h, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: nnode, nelem, npair
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer, intent(in) :: ix(4, nelem), ibody(nelem), ipair(6, npair)
      real(wp), intent(in) :: ppair(npair)
      integer, intent(out) :: h, ierr
      type(problem_t), allocatable :: p
      integer :: e, k, b
      logical, allocatable :: has_body(:)

      h = 0
      ierr = IERR_ARGUMENT
      if (.not. counts_ok(who, nnode, nelem, 'NELEM', npair)) return
      if (.not. nodes_ok(who, nnode, x0, mass)) return
      do e = 1, nelem
         if (any(ix(:, e) < 1 .or. ix(:, e) > nnode)) then
            call fail(0, who//': element '//itoa(e)//' names a node outside 1..'//itoa(nnode))
            return
         end if
         if (ibody(e) < 1) then
            call fail(0, who//': body number of element '//itoa(e)//' is '//itoa(ibody(e))//' (must be >= 1)')
            return
         end if
         if (quad_area(x0(:, ix(1, e)), x0(:, ix(2, e)), x0(:, ix(3, e)), x0(:, ix(4, e))) <= 0.0_wp) then
            call fail(0, who//': element '//itoa(e)//' is clockwise or degenerate in the reference mesh')
            return
         end if
      end do
      allocate (has_body(maxval(ibody)), source=.false.)
      has_body(ibody) = .true.
      if (.not. pairs_ok(who, npair, ipair, ppair, has_body, has_body)) return
      ! a surface for every body that a pair names
      has_body = .false.
      has_body(ipair(1, :)) = .true.
      has_body(ipair(2, :)) = .true.

      allocate (p)
      call base_problem(p, nnode, x0, mass, npair, ipair)
      p%mesh_mode = .true.
      p%nelem = nelem
      p%conn = ix
      p%body = ibody
      allocate (p%spec%surfaces(count(has_body)))
      k = 0
      do b = 1, size(has_body)
         if (.not. has_body(b)) cycle
         k = k + 1
         p%spec%surfaces(k)%id = b
         p%spec%surfaces(k)%by = SURF_REGION
         p%spec%surfaces(k)%ref = b
      end do
      call finish_create(who, p, ppair, h, ierr)
   end subroutine problem_create_mesh

   !> A problem from segments and slave node sets. iseg(3, nseg): node 1, node 2 (body on the
   !> left of 1 -> 2), surface number >= 1; isn(2, nsn): node, surface number of a slave node
   !> set (a surface without segments). ipair as for problem_create_mesh with surface numbers.
   subroutine problem_create_segments(who, nnode, x0, mass, nseg, iseg, nsn, isn, npair, ipair, ppair, &
                                      h, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: nnode, nseg, nsn, npair
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer, intent(in) :: iseg(3, nseg), isn(2, nsn), ipair(6, npair)
      real(wp), intent(in) :: ppair(npair)
      integer, intent(out) :: h, ierr
      type(problem_t), allocatable :: p
      integer :: k, s, j, nsurf
      logical, allocatable :: has_seg(:), has_node(:), used(:)

      h = 0
      ierr = IERR_ARGUMENT
      if (.not. counts_ok(who, nnode, nseg, 'NSEG', npair)) return
      if (nsn < 0) then
         call fail(0, who//': NSN = '//itoa(nsn)//' is negative')
         return
      end if
      if (.not. nodes_ok(who, nnode, x0, mass)) return
      nsurf = maxval(iseg(3, :))
      if (nsn > 0) nsurf = max(nsurf, maxval(isn(2, :)))
      do k = 1, nseg
         if (any(iseg(1:2, k) < 1 .or. iseg(1:2, k) > nnode) .or. iseg(1, k) == iseg(2, k)) then
            call fail(0, who//': segment '//itoa(k)//' names a node outside 1..'//itoa(nnode)// &
                      ' or the same node twice')
            return
         end if
         if (iseg(3, k) < 1) then
            call fail(0, who//': surface number of segment '//itoa(k)//' is below 1')
            return
         end if
      end do
      do k = 1, nsn
         if (isn(1, k) < 1 .or. isn(1, k) > nnode .or. isn(2, k) < 1) then
            call fail(0, who//': slave node entry '//itoa(k)//' names a node outside 1..'//itoa(nnode)// &
                      ' or a surface number below 1')
            return
         end if
      end do
      allocate (has_seg(nsurf), has_node(nsurf), source=.false.)
      has_seg(iseg(3, :)) = .true.
      if (nsn > 0) has_node(isn(2, :)) = .true.
      if (any(has_seg .and. has_node)) then
         call fail(0, who//': surface '//itoa(findloc(has_seg .and. has_node, .true., 1))// &
                   ' has both segments and slave node entries')
         return
      end if
      if (.not. pairs_ok(who, npair, ipair, ppair, has_seg .or. has_node, has_seg)) return
      allocate (used(nsurf), source=.false.)
      used(ipair(1, :)) = .true.
      used(ipair(2, :)) = .true.

      allocate (p)
      call base_problem(p, nnode, x0, mass, npair, ipair)
      p%mesh_mode = .false.
      p%nelem = 0
      allocate (p%conn(4, 0), p%body(0))
      allocate (p%spec%surfaces(count(used)))
      k = 0
      do s = 1, nsurf
         if (.not. used(s)) cycle
         k = k + 1
         associate (sp => p%spec%surfaces(k))
            sp%id = s
            if (has_seg(s)) then
               sp%by = SURF_FACETS
               sp%facets = iseg(1:2, pack([(j, j=1, nseg)], iseg(3, :) == s))
            else
               sp%by = SURF_NODES
               sp%nodes = isn(1, pack([(j, j=1, nsn)], isn(2, :) == s))
            end if
         end associate
      end do
      call finish_create(who, p, ppair, h, ierr)
   end subroutine problem_create_segments

   !> Positions, masses and pairs common to both kinds of creation.
   subroutine base_problem(p, nnode, x0, mass, npair, ipair)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: nnode, npair
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer, intent(in) :: ipair(6, npair)
      integer :: k
      p%nnode = nnode
      p%npair = npair
      p%mass = mass
      allocate (p%fixed(2, nnode), source=0)
      p%x0 = x0
      allocate (p%minv(2, nnode), source=0.0_wp)
      p%spec%active = .true.
      allocate (p%spec%pairs(npair))
      p%options = ipair(3:6, :)
      do k = 1, npair
         p%spec%pairs(k)%id = k
         p%spec%pairs(k)%slave = ipair(1, k)
         p%spec%pairs(k)%master = ipair(2, k)
      end do
   end subroutine base_problem

   !> Apply the pair options, build the contact object and register the problem.
   subroutine finish_create(who, p, ppair, h, ierr)
      character(len=*), intent(in) :: who
      type(problem_t), allocatable, intent(inout) :: p
      real(wp), intent(in) :: ppair(:)
      integer, intent(out) :: h, ierr
      integer, allocatable :: ipair(:, :)
      integer :: k
      h = 0
      ierr = IERR_SETUP
      ipair = pair_table(p)
      do k = 1, p%npair
         call apply_pair_options(p, k, ipair(3:6, k), ppair(k))
      end do
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) return
      call registry_add(p, h)
   end subroutine finish_create

   !> The pair table as in ipair(6, npair): slave, master and the current options.
   function pair_table(p) result(t)
      type(problem_t), intent(in) :: p
      integer, allocatable :: t(:, :)
      integer :: k
      allocate (t(6, p%npair))
      do k = 1, p%npair
         t(1, k) = p%spec%pairs(k)%slave
         t(2, k) = p%spec%pairs(k)%master
      end do
      t(3:6, :) = p%options
   end function pair_table

   !> Options (method, detection, passes, rigid) and penalty stiffness of pair k.
   subroutine apply_pair_options(p, k, iopt, pen)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: k, iopt(4)
      real(wp), intent(in) :: pen
      associate (ps => p%spec%pairs(k))
         ! 1 Lagrange, 2 penalty, 3 Lagrange with massless contact faces (LAGRange,ENERgy)
         ps%method = merge(METHOD_PENALTY, METHOD_LAGRANGE, iopt(1) == 2)
         ps%energy = iopt(1) == 3
         ps%detection = merge(DETECT_SWEPT, DETECT_STATIC, iopt(2) == 1)
         if (ps%slave == ps%master) then
            ps%kind = PAIR_SELF
         else
            ps%kind = merge(PAIR_NTOS, PAIR_SYMMETRIC, iopt(3) == 1)
         end if
         ps%penalty = pen
         p%options(:, k) = iopt
      end associate
   end subroutine apply_pair_options

   !> (Re)build the contact object from the spec and the masses, rigid masters and fixities.
   subroutine rebuild(who, p, ierr)
      character(len=*), intent(in) :: who
      type(problem_t), intent(inout) :: p
      integer, intent(out) :: ierr
      type(contact_t) :: fresh
      type(error_t), allocatable :: err
      logical, allocatable :: mark(:)
      real(wp), allocatable :: x(:, :)
      integer :: k, s

      call rigid_nodes(p)
      call inverse_masses(p)
      ! after steps, the segment lengths and the overlap check see the surfaces where they are now
      x = p%x0
      if (p%nsteps > 0) x(:, p%snodes) = p%xprev
      p%contact = fresh
      call p%contact%init(p%spec, p%nnode, x, x, p%nelem, p%conn, p%body, spread(1, 1, p%nelem), &
                          0.0_wp, err)
      if (allocated(err)) then
         ierr = IERR_SETUP
         call fail(0, who//': '//err%message)
         return
      end if
      allocate (mark(p%nnode), source=.false.)
      do k = 1, size(p%contact%surfaces)
         mark(p%contact%surfaces(k)%nodes) = .true.
      end do
      p%snodes = pack([(k, k=1, p%nnode)], mark)
      ! the massless faces of method-3 pairs (doc/impact.md, section 3): K_FF factorized again
      if (p%face_set) call p%contact%face%init(p%nnode, size(p%face), p%face, p%frp, p%fci, p%fval, err)
      if (allocated(err)) then
         ierr = IERR_SETUP
         call fail(0, who//': '//err%message)
         return
      end if
      if (allocated(p%spos)) deallocate (p%spos)
      allocate (p%spos(p%nnode), source=0)
      do s = 1, size(p%snodes)
         p%spos(p%snodes(s)) = s
      end do
      if (.not. allocated(p%xprev)) then
         allocate (p%xprev(2, size(p%snodes)), p%fprev(2, size(p%snodes)), p%vprev(2, size(p%snodes)), &
                   p%vhalf(2, size(p%snodes)), p%xcor(2, size(p%snodes)), source=0.0_wp)
      end if
      ierr = IERR_OK
   end subroutine rebuild

   !> Nodes of rigid masters: every node of the master body's elements (connectivity), or of
   !> the master surface's segments (segment lists).
   subroutine rigid_nodes(p)
      type(problem_t), intent(inout) :: p
      integer :: k, e, j
      if (allocated(p%rigid)) deallocate (p%rigid)
      allocate (p%rigid(p%nnode), source=.false.)
      do k = 1, p%npair
         if (p%options(4, k) == 0) cycle
         associate (m => p%spec%pairs(k)%master)
            if (p%mesh_mode) then
               do e = 1, p%nelem
                  if (p%body(e) == m) p%rigid(p%conn(:, e)) = .true.
               end do
            else
               do j = 1, size(p%spec%surfaces)
                  if (p%spec%surfaces(j)%id /= m) cycle
                  if (p%spec%surfaces(j)%by == SURF_FACETS) &
                     p%rigid(reshape(p%spec%surfaces(j)%facets, [size(p%spec%surfaces(j)%facets)])) &
                     = .true.
               end do
            end if
         end associate
      end do
   end subroutine rigid_nodes

   !> minv = 1/m per dof; 0 on rigid-master nodes and on dofs the host prescribes.
   subroutine inverse_masses(p)
      type(problem_t), intent(inout) :: p
      integer :: i
      do i = 1, p%nnode
         p%minv(:, i) = 0.0_wp
         if (p%mass(i) > 0.0_wp) p%minv(:, i) = 1.0_wp/p%mass(i)
         if (p%rigid(i)) p%minv(:, i) = 0.0_wp
         where (p%fixed(:, i) /= 0) p%minv(:, i) = 0.0_wp
      end do
      ! massless face nodes carry no mass: the face block places them (doc/impact.md, eq. I.5)
      if (p%face_set) p%minv(:, p%face) = 0.0_wp
   end subroutine inverse_masses

   ! ------------------------------------------------------------------ options

   !> ifix(2, nnode): non-zero marks a dof the host prescribes (the corrector leaves it alone).
   subroutine problem_set_fixed(who, h, nnode, ifix, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      integer, intent(in) :: ifix(2, nnode)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         ierr = IERR_ARGUMENT
         return
      end if
      p%fixed = ifix
      call inverse_masses(p)
   end subroutine problem_set_fixed

   !> New options iopt(4) = method, detection, passes, rigid master and penalty stiffness of
   !> pair ipair; the surfaces and passes are rebuilt at the current positions.
   subroutine problem_set_pair(who, h, ipair, iopt, pen, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair
      integer, intent(in) :: iopt(4)
      real(wp), intent(in) :: pen
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer, allocatable :: t(:, :)
      logical, allocatable :: any_surf(:), seg_surf(:)
      integer :: k, n
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         return
      end if
      t = pair_table(p)
      t(3:6, ipair) = iopt
      n = maxval(t(1:2, :))
      allocate (any_surf(n), seg_surf(n), source=.false.)
      do k = 1, size(p%spec%surfaces)
         if (p%spec%surfaces(k)%id > n) cycle
         any_surf(p%spec%surfaces(k)%id) = .true.
         seg_surf(p%spec%surfaces(k)%id) = p%spec%surfaces(k)%by /= SURF_NODES
      end do
      if (.not. pairs_ok(who, 1, t(:, ipair:ipair), [pen], any_surf, seg_surf, ipair)) then
         p%message = last_message(0)
         return
      end if
      call apply_pair_options(p, ipair, iopt, pen)
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) p%message = last_message(0)
   end subroutine problem_set_pair

   !> Coulomb friction of pair ipair (doc/friction.md, eq. F12): static coefficient amus, dynamic
   !> amud <= amus, decay with slip speed (0: amus at rest, amud sliding); amus = 0 removes it.
   !> The contact object is rebuilt at the current positions, as for a change of pair options.
   subroutine problem_set_friction(who, h, ipair, amus, amud, decay, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair
      real(wp), intent(in) :: amus, amud, decay
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         return
      end if
      if (.not. (ieee_is_finite(amus) .and. ieee_is_finite(amud) .and. ieee_is_finite(decay))) then
         call fail(h, who//': the friction coefficients and the decay must be finite')
         return
      end if
      if (.not. (amus >= 0.0_wp .and. amud >= 0.0_wp .and. decay >= 0.0_wp .and. amud <= amus)) then
         call fail(h, who//': expected 0 <= AMUD <= AMUS and DECAY >= 0, got AMUS = '//rtoa(amus)// &
                   ', AMUD = '//rtoa(amud)//', DECAY = '//rtoa(decay))
         return
      end if
      p%spec%pairs(ipair)%mus = amus
      p%spec%pairs(ipair)%mud = amud
      p%spec%pairs(ipair)%decay = decay
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) p%message = last_message(0)
   end subroutine problem_set_friction

   !> Handle options: OPT_VELOCITY_FORM = 1 (v~(n+1), default) or 2 (v(n+1/2)).
   subroutine problem_set_option(who, h, iopt, ival, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, iopt, ival
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      select case (iopt)
      case (OPT_VELOCITY_FORM)
         if (ival /= VEL_FULL_STEP .and. ival /= VEL_HALF_STEP) then
            call fail(h, who//': velocity form '//itoa(ival)//' is neither 1 nor 2')
            return
         end if
         p%velocity_form = ival
         if (ival == VEL_HALF_STEP .and. .not. allocated(p%vt)) allocate (p%vt(2, p%nnode), source=0.0_wp)
      case default
         call fail(h, who//': unknown option '//itoa(iopt))
         return
      end select
      ierr = IERR_OK
   end subroutine problem_set_option

   !> The massless contact faces of method-3 pairs (doc/impact.md, section 3; doc/api.md):
   !> mass(nnode) the host's lumped masses after it moved the face nodes' mass to their
   !> elements' other nodes (eq. I.3; > 0 off the face, ignored on it), iface(nf) the face
   !> nodes (surface nodes, neither rigid nor prescribed), irp(2 nf + 1), ici, val the rows of
   !> the host's initial stiffness for the face dofs in 1-based CSR (row 2 (k-1) + d for dof d of
   !> iface(k), columns the global dofs 2 (i-1) + d). The face block must be symmetric; it is
   !> factorized (SuiteSparse LDL) when the contact object is rebuilt here.
   subroutine problem_set_face(who, h, nnode, mass, nf, iface, irp, ici, val, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode, nf
      real(wp), intent(in) :: mass(nnode)
      integer, intent(in) :: iface(max(nf, 0)), irp(2*max(nf, 0) + 1)
      integer, intent(in) :: ici(*)
      real(wp), intent(in) :: val(*)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer, allocatable :: rp(:), ci(:)
      real(wp), allocatable :: v(:), mass_old(:)
      character(len=:), allocatable :: msg
      integer :: k
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         return
      end if
      call check_face(nnode, p%spos, p%rigid, p%fixed, mass, nf, iface, irp, ici, val, rp, ci, v, msg)
      if (len(msg) > 0) then
         call fail(h, who//': '//msg)
         return
      end if
      mass_old = p%mass
      p%mass = mass
      p%mass(iface) = 0.0_wp
      p%face = iface
      p%frp = rp
      p%fci = ci
      p%fval = v
      p%face_set = .true.
      if (.not. allocated(p%zero)) allocate (p%zero(2, nnode), source=0.0_wp)
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) then
         ! a singular face block: the handle stays as it was
         p%message = last_message(0)
         p%face_set = .false.
         p%mass = mass_old
         call rebuild(who, p, k)
         ierr = IERR_SETUP
      end if
   end subroutine problem_set_face

   ! ------------------------------------------------------------------ the step

   !> One contact step: x = x(n+1), v = v~(n+1) (or v(n+1/2), option 1), a = a~(n+1) on entry
   !> and a(n+1) on exit, dtprev = dt(n) (0 at t = 0), dt = dt(n+1); fcon = nodal contact
   !> forces, nactive = constraints carrying force (eq. 4.4-4.7). The host's arrays go to
   !> contact_t%correct as they are: nothing of size nnode is copied.
   subroutine problem_step(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      real(wp), intent(in) :: x(2, nnode), v(2, nnode)
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(in) :: dtprev, dt
      real(wp), intent(out) :: fcon(2, nnode)
      integer, intent(out) :: nactive, ierr
      call step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
   end subroutine problem_step

   !> The step of a handle with massless contact faces (method 3, doc/impact.md section 3): r =
   !> f_ext - f_int at t(n+1) on the face dofs (eq. I.5); a holds there on exit eq. I.7's.
   subroutine problem_step_face(who, h, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      real(wp), intent(in) :: x(2, nnode), v(2, nnode), r(2, nnode)
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(in) :: dtprev, dt
      real(wp), intent(out) :: fcon(2, nnode)
      integer, intent(out) :: nactive, ierr
      call step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr, r)
   end subroutine problem_step_face

   !> Both steps; r present: the face step.
   subroutine step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr, r)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      real(wp), intent(in) :: x(2, nnode), v(2, nnode)
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(in) :: dtprev, dt
      real(wp), intent(out) :: fcon(2, nnode)
      integer, intent(out) :: nactive, ierr
      real(wp), intent(in), optional :: r(2, nnode)
      type(problem_t), pointer :: p
      type(error_t), allocatable :: err
      integer :: k, i, nbad
      real(wp) :: c

      nactive = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) then
         fcon = 0.0_wp
         return
      end if
      if (.not. step_args_ok(who, h, p, nnode, x, dtprev, dt)) then
         ierr = IERR_ARGUMENT
         fcon = 0.0_wp
         return
      end if
      if (.not. face_step_ok(who, h, p, present(r))) then
         ierr = IERR_SETUP
         fcon = 0.0_wp
         return
      end if
      if (present(r)) then
         ! the residual is read on the face dofs; the host's a~ there means nothing (no mass):
         ! the face's x~(n+2) is x*, eq. I.7
         do k = 1, size(p%face)
            i = p%face(k)
            if (nonfinite(r(1, i)) + nonfinite(r(2, i)) > 0) then
               call fail(h, who//': residual R of face node '//itoa(i)//' is not finite')
               ierr = IERR_ARGUMENT
               fcon = 0.0_wp
               return
            end if
            a(:, i) = 0.0_wp
         end do
      end if
      ! the velocities and accelerations the corrector reads: those of the surface nodes
      nbad = 0
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         nbad = nbad + nonfinite(v(1, i)) + nonfinite(v(2, i)) + nonfinite(a(1, i)) + nonfinite(a(2, i))
      end do
      if (nbad > 0) then
         call fail(h, who//': '//first_bad(p, nnode, v, a))
         ierr = IERR_ARGUMENT
         fcon = 0.0_wp
         return
      end if
      ! v(n+1/2) of the surface nodes, for the contact work (after_step)
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         if (p%velocity_form == VEL_HALF_STEP) then
            p%vhalf(:, k) = v(:, i)
         else
            p%vhalf(:, k) = v(:, i) - (0.5_wp*dtprev)*a(:, i)
         end if
      end do
      if (p%velocity_form == VEL_HALF_STEP) then
         ! v~(n+1) = v(n+1/2) + dt(n)/2 a~(n+1) (only surface nodes are read, every node with
         ! a massless face: its free solve reads the predicted motion of the nodes next to it)
         if (present(r)) then
            p%vt = v + (0.5_wp*dtprev)*a
         else
            do k = 1, size(p%snodes)
               i = p%snodes(k)
               p%vt(:, i) = v(:, i) + (0.5_wp*dtprev)*a(:, i)
            end do
         end if
         ! (r absent and p%zero unallocated without a face: fext and fint are absent)
         call p%contact%correct(nnode, x, p%vt, a, p%minv, dtprev, dt, fcon, nactive, err, fext=r, fint=p%zero)
      else
         call p%contact%correct(nnode, x, v, a, p%minv, dtprev, dt, fcon, nactive, err, fext=r, fint=p%zero)
      end if
      if (allocated(err)) then
         call fail(h, who//': '//err%message)
         ierr = IERR_SOLVE
         return
      end if
      call after_step(p, nnode, x, a, dtprev, fcon)
      c = 0.5_wp*dt*(dtprev + dt)
      p%c = c
      if (present(r)) call face_motion(p, nnode, x, v, a, dt, c)
      p%nsteps = p%nsteps + 1
      do k = 1, size(p%contact%results)
         p%max_pen = max(p%max_pen, p%contact%results(k)%penetration)
      end do
   end subroutine step_common

   !> What the queries need of the surface nodes: the contact forces (the correction of the
   !> accelerations is minv fcon) and the contact work as the driver books it (doc/impact.md,
   !> eq. I.12): on a dof with mass the two half kicks dt(n)/2 (f(n) . (v(n) + v(n+1/2))/2 +
   !> f(n+1) . (v(n+1/2) + v(n+1))/2), elsewhere 1/2 (f(n) + f(n+1)) . (x(n+1) - x(n)).
   subroutine after_step(p, nnode, x, a, dtprev, fcon)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), a(2, nnode), dtprev, fcon(2, nnode)
      integer :: k, i, d
      real(wp) :: w, h, vnew
      w = 0.0_wp
      h = 0.5_wp*dtprev
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         do d = 1, 2
            vnew = p%vhalf(d, k) + h*a(d, i)
            if (p%minv(d, i) > 0.0_wp) then
               w = w + h*(p%fprev(d, k)*(p%vprev(d, k) + p%vhalf(d, k)) + fcon(d, i)*(p%vhalf(d, k) + vnew))
            else
               w = w + (p%fprev(d, k) + fcon(d, i))*(x(d, i) - p%xprev(d, k))
            end if
            p%vprev(d, k) = vnew
         end do
         p%xprev(:, k) = x(:, i)
         p%fprev(:, k) = fcon(:, i)
      end do
      if (p%nsteps > 0) p%wcon = p%wcon + 0.5_wp*w
   end subroutine after_step

   !> Step arguments: node count, time steps and finite positions.
   logical function step_args_ok(who, h, p, nnode, x, dtprev, dt) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      type(problem_t), intent(in) :: p
      real(wp), intent(in) :: x(2, nnode), dtprev, dt
      integer :: i
      ok = .false.
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         return
      end if
      if (.not. (dt > 0.0_wp .and. ieee_is_finite(dt))) then
         call fail(h, who//': DT = '//rtoa(dt)//' is not a positive finite step')
         return
      end if
      if (.not. (dtprev >= 0.0_wp .and. ieee_is_finite(dtprev))) then
         call fail(h, who//': DTPREV = '//rtoa(dtprev)//' is not a finite step >= 0')
         return
      end if
      if (count_nonfinite(2*nnode, x) > 0) then
         do i = 1, nnode
            if (.not. (ieee_is_finite(x(1, i)) .and. ieee_is_finite(x(2, i)))) then
               call fail(h, who//': position of node '//itoa(i)//' is not finite')
               return
            end if
         end do
      end if
      ok = .true.
   end function step_args_ok

   !> Number of entries of vals(n) that are NaN or infinite (all exponent bits set); integer
   !> arithmetic on the bit patterns, so the loop vectorizes where a floating-point test
   !> reduction could not (its order of additions is fixed).
   pure integer function count_nonfinite(n, vals) result(nbad)
      integer, intent(in) :: n
      real(wp), intent(in) :: vals(n)
      integer :: i
      nbad = 0
      do i = 1, n
         nbad = nbad + nonfinite(vals(i))
      end do
   end function count_nonfinite

   !> 1 if val is NaN or infinite (all exponent bits set), else 0.
   elemental integer function nonfinite(val) result(bad)
      real(wp), intent(in) :: val
      integer(int64), parameter :: expo = int(z'7FF0000000000000', int64)
      bad = merge(1, 0, iand(transfer(val, 0_int64), expo) == expo)
   end function nonfinite

   !> Message naming the first surface node with a non-finite velocity or acceleration.
   function first_bad(p, nnode, v, a) result(msg)
      type(problem_t), intent(in) :: p
      integer, intent(in) :: nnode
      real(wp), intent(in) :: v(2, nnode), a(2, nnode)
      character(len=:), allocatable :: msg
      integer :: k, i
      msg = 'a velocity or acceleration is not finite'
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         if (.not. all(ieee_is_finite(v(:, i)))) then
            msg = 'velocity of node '//itoa(i)//' is not finite'
            return
         else if (.not. all(ieee_is_finite(a(:, i)))) then
            msg = 'acceleration of node '//itoa(i)//' is not finite'
            return
         end if
      end do
   end function first_bad

   ! ------------------------------------------------------------------ queries

   !> res(6) of pair ipair in the last step: normal force (sum of multipliers), force x, y on
   !> the slave side (normal and friction), active constraints, largest penetration at t(n+1),
   !> largest multiplier.
   subroutine problem_pair_results(who, h, ipair, res, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair
      real(wp), intent(out) :: res(6)
      integer, intent(out) :: ierr
      call pair_values(who, h, ipair, 0, res, ierr)
   end subroutine problem_pair_results

   !> res(4) of pair ipair: friction force (sum of |q| over its constraints) in the last step,
   !> constraints that stick and that slip in it, frictional dissipation since the friction was
   !> set (doc/friction.md, section 7). The friction forces are also in the pair results' force
   !> x, y and in the nodal contact forces of the step.
   subroutine problem_pair_friction(who, h, ipair, res, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair
      real(wp), intent(out) :: res(4)
      integer, intent(out) :: ierr
      call pair_values(who, h, ipair, 7, res, ierr)
   end subroutine problem_pair_friction

   !> res(k) = value skip + k of pair ipair's results (contact_t%pair_value), k = 1..size(res),
   !> after checking the handle and the pair number.
   subroutine pair_values(who, h, ipair, skip, res, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair, skip
      real(wp), intent(out) :: res(:)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer :: k
      res = 0.0_wp
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         ierr = IERR_ARGUMENT
         return
      end if
      do k = 1, size(res)
         res(k) = p%contact%pair_value(ipair, skip + k)
      end do
   end subroutine pair_values

   !> Number of candidate (Lagrange) constraints of the last step.
   subroutine problem_ncon(who, h, ncon, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      integer, intent(out) :: ncon, ierr
      type(problem_t), pointer :: p
      ncon = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ncon = p%contact%cs%n
   end subroutine problem_ncon

   !> The candidate constraints of the last step: icon(4, :) = slave, master 1, master 2, pair;
   !> rcon(6, :) = multiplier p (>= 0, compressive), alpha, normal x, y, gap at t(n+1), gap at
   !> t(n+2) after the correction (eq. 3.19 along the frozen normal). mcon >= ncon is required.
   subroutine problem_constraints(who, h, mcon, ncon, icon, rcon, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, mcon
      integer, intent(out) :: ncon
      integer, intent(out) :: icon(4, mcon)
      real(wp), intent(out) :: rcon(6, mcon)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer :: i, j, nd, s
      real(wp) :: dg
      ncon = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ncon = p%contact%cs%n
      if (mcon < ncon) then
         call fail(h, who//': MCON = '//itoa(mcon)//' is below the '//itoa(ncon)//' constraints')
         ierr = IERR_ARGUMENT
         return
      end if
      associate (cs => p%contact%cs)
         do i = 1, ncon
            icon(1:3, i) = cs%node(:, i)
            icon(4, i) = cs%pair(i)
            rcon(1, i) = cs%p(i)
            rcon(2, i) = -cs%w(3, i)
            rcon(3:4, i) = cs%nrm(:, i)
            rcon(5, i) = cs%gap_now(i)
            ! g(n+2) = g~ + c G_i^T (a - a~) with a - a~ = M^-1 fcon: the correction moves
            ! x(n+2) by c (a - a~) (eq. 4.5-4.7)
            dg = 0.0_wp
            do j = 1, 3
               nd = cs%node(j, i)
               s = p%spos(nd)
               dg = dg + cs%w(j, i)*dot_product(cs%nrm(:, i), p%minv(:, nd)*p%fprev(:, s))
            end do
            rcon(6, i) = cs%gap(i) + p%c*dg
            if (p%face_set) rcon(6, i) = rcon(6, i) + face_gap(p, i)
         end do
      end associate
   end subroutine problem_constraints

   !> Work of the contact forces since creation and the largest penetration at t(n+1) seen.
   subroutine problem_work(who, h, wcon, penmax, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      real(wp), intent(out) :: wcon, penmax
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      wcon = 0.0_wp
      penmax = 0.0_wp
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      wcon = p%wcon
      penmax = p%max_pen
   end subroutine problem_work

   !> Release handle h.
   subroutine problem_free(who, h, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      call registry_free(h)
   end subroutine problem_free

   !> The message of the last failed call on handle h (of any call when h names no live
   !> problem), blank-padded or cut to len(msg); lmsg is its full length.
   subroutine problem_message(h, msg, lmsg)
      integer, intent(in) :: h
      character(len=*), intent(out) :: msg
      integer, intent(out) :: lmsg
      character(len=:), allocatable :: m
      m = last_message(h)
      msg = m
      lmsg = len(m)
   end subroutine problem_message

   ! ------------------------------------------------------------------ checks

   !> The live problem of h, or null with ierr = IERR_HANDLE and a message.
   function lookup(who, h, ierr) result(p)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => registry_get(h)
      if (associated(p)) then
         ierr = IERR_OK
      else
         ierr = IERR_HANDLE
         call fail(0, who//': handle '//itoa(h)//' names no live contact problem')
      end if
   end function lookup

   !> Node, entity and pair counts.
   logical function counts_ok(who, nnode, nent, name, npair) result(ok)
      character(len=*), intent(in) :: who, name
      integer, intent(in) :: nnode, nent, npair
      ok = .false.
      if (nnode < 1) then
         call fail(0, who//': NNODE = '//itoa(nnode)//' (must be >= 1)')
      else if (nent < 1) then
         call fail(0, who//': '//name//' = '//itoa(nent)//' (must be >= 1)')
      else if (npair < 1) then
         call fail(0, who//': NPAIR = '//itoa(npair)//' (must be >= 1)')
      else
         ok = .true.
      end if
   end function counts_ok

   !> Finite coordinates and positive finite masses.
   logical function nodes_ok(who, nnode, x0, mass) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer :: i
      ok = .false.
      do i = 1, nnode
         if (.not. all(ieee_is_finite(x0(:, i)))) then
            call fail(0, who//': coordinate of node '//itoa(i)//' is not finite')
            return
         end if
         if (.not. (mass(i) > 0.0_wp .and. ieee_is_finite(mass(i)))) then
            call fail(0, who//': mass of node '//itoa(i)//' is '//rtoa(mass(i))//' (must be positive)')
            return
         end if
      end do
      ok = .true.
   end function nodes_ok

   !> Pair table: surfaces exist (has(s)), masters have segments (seg(s)), options in range.
   !> `first` is the number of the first pair in messages (default 1).
   logical function pairs_ok(who, npair, ipair, ppair, has, seg, first) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: npair
      integer, intent(in) :: ipair(6, npair)
      real(wp), intent(in) :: ppair(npair)
      logical, intent(in) :: has(:), seg(:)
      integer, intent(in), optional :: first
      integer :: k, k0
      character(len=:), allocatable :: at
      ok = .false.
      k0 = 0
      if (present(first)) k0 = first - 1
      do k = 1, npair
         at = who//': pair '//itoa(k + k0)//': '
         if (any(ipair(1:2, k) < 1 .or. ipair(1:2, k) > size(has))) then
            call fail(0, at//'slave '//itoa(ipair(1, k))//' or master '//itoa(ipair(2, k))//' is not defined')
            return
         end if
         if (.not. (has(ipair(1, k)) .and. has(ipair(2, k)))) then
            call fail(0, at//'slave '//itoa(ipair(1, k))//' or master '//itoa(ipair(2, k))//' is not defined')
            return
         end if
         if (.not. seg(ipair(2, k)) .or. (ipair(5, k) == 2 .and. .not. seg(ipair(1, k)))) then
            call fail(0, at//'a slave node set can only be the slave side of a one-pass pair')
            return
         end if
         if (ipair(3, k) < 1 .or. ipair(3, k) > 3 .or. ipair(4, k) < 1 .or. ipair(4, k) > 2 .or. &
             ipair(5, k) < 1 .or. ipair(5, k) > 2 .or. ipair(6, k) < 0 .or. ipair(6, k) > 1) then
            call fail(0, at//'method (1 to 3), detection, passes (1 or 2) or rigid flag (0 or 1) out of range')
            return
         end if
         if (ipair(3, k) == 2 .and. .not. (ppair(k) > 0.0_wp .and. ieee_is_finite(ppair(k)))) then
            call fail(0, at//'penalty stiffness '//rtoa(ppair(k))//' is not positive')
            return
         end if
      end do
      ok = .true.
   end function pairs_ok

   !> Record a failure (see set_error).
   subroutine fail(h, msg)
      integer, intent(in) :: h
      character(len=*), intent(in) :: msg
      call set_error(h, msg)
   end subroutine fail

end module exic_legacy_problem
