!> The legacy API: creation of a problem from a host's connectivity or segments.
submodule(exic_legacy_problem) exic_legacy_problem_create
   implicit none

contains

   !> A problem from connectivity: ix(4, nelem) counter-clockwise nodes, ibody(nelem) >= 1.
   !> ipair(6, npair): slave body, master body, method, detection, passes, rigid master;
   !> ppair(npair): penalty stiffness (method 2). On success h > 0, else h = 0.
   module procedure problem_create_mesh
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
   end procedure problem_create_mesh

   !> A problem from segments and slave node sets. iseg(3, nseg): node 1, node 2 (body on the
   !> left of 1 -> 2), surface number >= 1; isn(2, nsn): node, surface number of a slave node
   !> set (a surface without segments). ipair as for problem_create_mesh with surface numbers.
   module procedure problem_create_segments
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
   end procedure problem_create_segments

   !> Positions, masses and pairs common to both kinds of creation.
   subroutine base_problem(p, nnode, x0, mass, npair, ipair)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: nnode, npair
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer, intent(in) :: ipair(6, npair)
      integer :: k
      p%nnode = nnode
      p%npair = npair
      p%mass = spread(mass, 1, 2)
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

end submodule exic_legacy_problem_create
