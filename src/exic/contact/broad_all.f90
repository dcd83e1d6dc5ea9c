!> Broad phase of AUTOmatic contact over every surface at once (doc/contact-detection.md,
!> "AUTOmatic contact in one search").
!>
!> AUTOmatic contact pairs the nodes of every surface with the segments of every other surface.
!> Instead of one broad phase per ordered pair of surfaces (N (N - 1) searches, each forming the
!> boxes of both surfaces), one search per step finds every candidate of every pair:
!>
!>  1. the swept box of each surface (its nodes over x0 -> x1), O(surface nodes);
!>  2. the pairs of surfaces whose boxes overlap (the master's grown by `margin`): the uniform
!>     bucket grid of `broad_search` run on the N surface boxes themselves (each surface one
!>     "node" and one "segment" whose boxes are the surface's box), O(N) for bodies spread out;
!>  3. one `broad_search` over the nodes and segments of the surfaces that have a near partner,
!>     all at once; pairs within one surface are dropped;
!>  4. the candidates regrouped by (slave surface, master surface), in the order of the passes
!>     that one search per pair made, each group's list sorted by slave then segment.
!>
!> The candidates of a group are exactly those of `broad_search` on that pair of surfaces: the
!> same box test on the same box values (step 2 only drops pairs of surfaces whose boxes are
!> apart, which hold no overlapping entity boxes: a segment's box lies in its surface's box
!> grown by the same margin). A step in which no two surfaces are near costs the surface
!> boxes and the search over N boxes, nothing of the size of the surfaces' product.
module exic_contact_broad_all
   use exic_base_kinds, only: wp, i8
   use exic_base_grow, only: grow
   use exic_base_flat, only: copy_flat_int
   use exic_base_sort, only: sort_perm_int
   use exic_contact_broad, only: broad_t, broad_search, boxes_overlap
   implicit none
   private

   public :: broad_all_t

   !> The surfaces of AUTOmatic contact (copies of their node and segment lists) and, after
   !> `search`, the candidates grouped by pair of surfaces.
   type :: broad_all_t
      integer :: nsurf = 0
      integer, allocatable :: node_first(:)   !< (nsurf + 1) CSR into nodes
      integer, allocatable :: nodes(:)        !< every surface's nodes, surface after surface
      integer, allocatable :: seg_first(:)    !< (nsurf + 1) CSR into seg
      integer, allocatable :: seg(:, :)       !< (2, :) every surface's segments
      integer, allocatable :: segw(:, :)      !< (2, :) their ends as indices into nodes
      ! result of the last search
      integer :: ngroup = 0                   !< pairs of surfaces with candidates
      integer, allocatable :: gslave(:), gmaster(:)  !< (ngroup) surface numbers (1..nsurf)
      integer, allocatable :: gfirst(:)       !< (ngroup + 1) CSR into gcand
      integer, allocatable :: gcand(:, :)     !< (2, :) slave index, segment index within the surfaces
      integer(i8) :: ntests = 0               !< box tests of the last search (both levels)
      ! work space
      type(broad_t) :: coarse, fine
      real(wp), allocatable :: bx0(:, :), bx1(:, :)   !< (2, 2 nsurf) box corners as positions
      integer, allocatable :: bslave(:), bseg(:, :)   !< the coarse search's "nodes" and "segments"
      integer, allocatable :: pfirst(:), partner(:)   !< surfaces whose boxes meet each one's (CSR)
      integer, allocatable :: lnodes(:), lseg(:, :)   !< nodes and segments of the near surfaces
      integer :: nl = 0, ns = 0                       !< entries of lnodes, lseg in use
      integer, allocatable :: lnode_surf(:), lnode_loc(:)    !< surface and index in it of each
      integer, allocatable :: lseg_surf(:), lseg_loc(:)      !< of lnodes, of lseg
      integer, allocatable :: count(:), slot(:), jlist(:)
      ! kept list of search_kept: the groups of the candidates within margin + 2 skin at the
      ! build, with lnodes, lseg and their surface indices of that search
      logical :: kept = .false.
      real(wp) :: skin = 0.0_wp
      integer :: nkept = 0
      integer :: nkept_nodes = 0, nkept_segs = 0   !< entries of lnodes, lseg of the kept search
      integer, allocatable :: keep(:, :)      !< (2, nkept) indices into nodes and lseg, grouped
      integer, allocatable :: ksegw(:, :)     !< (2, nkept_segs) ends of the kept lseg as indices into nodes
      real(wp), allocatable :: sbox(:, :)     !< (4, nsurf) swept box of every surface this step
      logical, allocatable :: glive(:)        !< (nkgroup) groups whose surfaces' boxes meet this step
      integer, allocatable :: mstamp(:)       !< (nkept_segs) step whose box the segment's mbox holds
      integer :: boxstamp = 0                 !< this step's stamp of mstamp
      real(wp), allocatable :: nbox(:, :)     !< (4, size(nodes)) swept box of every surface node this step
      integer, allocatable :: kloc(:, :)      !< (2, nkept) the same as indices within the surfaces
      integer :: nkgroup = 0                  !< groups of the kept list
      integer, allocatable :: kgslave(:), kgmaster(:), kgfirst(:)  !< its groups (CSR into keep)
      integer, allocatable :: gidx(:, :)      !< (2, :) regroup's placed candidates as lnodes, lseg indices
      real(wp), allocatable :: xw(:, :)       !< (4, size(nodes)) x0, x1 of every node at the build
      integer(i8) :: nbuilds = 0, nkept_steps = 0
      integer(i8) :: ngroups_apart = 0        !< kept groups skipped by the surfaces' boxes, all steps
      integer(i8) :: nlazy_steps = 0          !< steps that formed the segment boxes at first use
   contains
      procedure :: add_surface => broad_all_add_surface
      procedure :: search => broad_all_search
      procedure :: search_kept => broad_all_search_kept
      procedure :: take => broad_all_take
   end type broad_all_t

contains

   !> Append a surface: its nodes and its segments (2, nseg), numbered in the mesh.
   subroutine broad_all_add_surface(self, nodes, seg)
      class(broad_all_t), intent(inout) :: self
      integer, intent(in) :: nodes(:), seg(:, :)
      integer :: n0, s0
      if (self%nsurf == 0) then
         call grow(self%node_first, 1)
         call grow(self%seg_first, 1)
         self%node_first(1) = 1
         self%seg_first(1) = 1
      end if
      n0 = self%node_first(self%nsurf + 1) - 1
      s0 = self%seg_first(self%nsurf + 1) - 1
      self%nsurf = self%nsurf + 1
      call grow(self%node_first, self%nsurf + 1)
      call grow(self%seg_first, self%nsurf + 1)
      call grow(self%nodes, n0 + size(nodes))
      call grow(self%seg, s0 + size(seg, 2), 2)
      call grow(self%segw, s0 + size(seg, 2), 2)
      self%nodes(n0 + 1:n0 + size(nodes)) = nodes
      self%seg(:, s0 + 1:s0 + size(seg, 2)) = seg
      call locate_ends(size(nodes), nodes, size(seg, 2), seg, n0, self%segw(:, s0 + 1:s0 + size(seg, 2)))
      self%node_first(self%nsurf + 1) = n0 + size(nodes) + 1
      self%seg_first(self%nsurf + 1) = s0 + size(seg, 2) + 1
   end subroutine broad_all_add_surface

   !> Position (plus n0) in nodes(1:n) of each end of the segments seg(2, 1:m), which are all nodes of
   !> the list (by a binary search of the sorted list).
   pure subroutine locate_ends(n, nodes, m, seg, n0, where)
      integer, intent(in) :: n, nodes(n), m, seg(2, m), n0
      integer, intent(out) :: where(2, m)
      integer :: perm(n), k, j, lo, hi, mid
      call sort_perm_int(n, nodes, perm)
      do k = 1, m
         do j = 1, 2
            lo = 1
            hi = n
            do while (lo < hi)
               mid = (lo + hi)/2
               if (nodes(perm(mid)) < seg(j, k)) then
                  lo = mid + 1
               else
                  hi = mid
               end if
            end do
            where(j, k) = n0 + perm(lo)
         end do
      end do
   end subroutine locate_ends

   !> Every candidate (slave node of surface i, segment of surface j /= i) whose swept boxes
   !> overlap over x0 -> x1, the segment's box grown by margin: grouped by (i, j) in the order
   !> i, then j; within a group sorted by slave, then segment (both as indices within their
   !> surface, as `broad_search` on the pair gives them).
   subroutine broad_all_search(self, nnode, x0, x1, margin)
      class(broad_all_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer :: r, k, n, nl, ns, node, c
      real(wp) :: box(4)

      self%ngroup = 0
      self%ntests = 0
      self%kept = .false.
      self%fine%ncand = 0
      self%nl = 0
      self%ns = 0
      n = self%nsurf
      if (n < 2) return
      ! 1. the swept box of each surface, as the two positions of a "node" 2r-1 and 2r
      call grow(self%bx0, 2*n, 2)
      call grow(self%bx1, 2*n, 2)
      call grow(self%bslave, n)
      call grow(self%bseg, n, 2)
      do r = 1, n
         self%bx0(:, 2*r - 1) = huge(1.0_wp)
         self%bx1(:, 2*r - 1) = -huge(1.0_wp)
         do k = self%node_first(r), self%node_first(r + 1) - 1
            node = self%nodes(k)
            self%bx0(:, 2*r - 1) = min(self%bx0(:, 2*r - 1), x0(:, node), x1(:, node))
            self%bx1(:, 2*r - 1) = max(self%bx1(:, 2*r - 1), x0(:, node), x1(:, node))
         end do
         self%bx0(:, 2*r) = self%bx0(:, 2*r - 1)
         self%bx1(:, 2*r) = self%bx1(:, 2*r - 1)
         self%bslave(r) = 2*r - 1
         self%bseg(:, r) = [2*r - 1, 2*r]
      end do
      ! 2. pairs of surfaces whose boxes overlap (a surface's own pair is excluded: its
      ! "segment" holds its "node")
      call broad_search(self%coarse, 2*n, self%bx0, self%bx1, n, self%bslave, n, self%bseg, margin)
      self%ntests = self%coarse%ntests
      if (self%coarse%ncand == 0) return
      ! the partners of each surface, both ways (CSR)
      call grow(self%pfirst, n + 1)
      call grow(self%partner, 2*self%coarse%ncand)
      self%pfirst(1:n + 1) = 0
      do c = 1, self%coarse%ncand
         self%pfirst(self%coarse%cand(1, c) + 1) = self%pfirst(self%coarse%cand(1, c) + 1) + 1
         self%pfirst(self%coarse%cand(2, c) + 1) = self%pfirst(self%coarse%cand(2, c) + 1) + 1
      end do
      self%pfirst(1) = 1
      do r = 2, n + 1
         self%pfirst(r) = self%pfirst(r) + self%pfirst(r - 1)
      end do
      do c = 1, self%coarse%ncand
         do k = 1, 2
            r = self%coarse%cand(k, c)
            self%partner(self%pfirst(r)) = self%coarse%cand(3 - k, c)
            self%pfirst(r) = self%pfirst(r) + 1
         end do
      end do
      do r = n + 1, 2, -1
         self%pfirst(r) = self%pfirst(r - 1)
      end do
      self%pfirst(1) = 1
      ! 3. one search over the entities of the near surfaces that can reach a partner: a node
      ! whose box meets a partner's box grown by margin, a segment whose box grown by margin
      ! meets a partner's box (a candidate pair passes both tests: see the module header)
      nl = 0
      ns = 0
      do r = 1, n
         nl = nl + self%node_first(r + 1) - self%node_first(r)
         ns = ns + self%seg_first(r + 1) - self%seg_first(r)
      end do
      call grow(self%lnodes, nl)
      call grow(self%lnode_surf, nl)
      call grow(self%lnode_loc, nl)
      call grow(self%lseg, ns, 2)
      call grow(self%lseg_surf, ns)
      call grow(self%lseg_loc, ns)
      nl = 0
      ns = 0
      do r = 1, n
         if (self%pfirst(r + 1) == self%pfirst(r)) cycle
         do k = self%node_first(r), self%node_first(r + 1) - 1
            node = self%nodes(k)
            box(1:2) = min(x0(:, node), x1(:, node))
            box(3:4) = max(x0(:, node), x1(:, node))
            if (.not. reaches(self, r, box, margin)) cycle
            nl = nl + 1
            self%lnodes(nl) = node
            self%lnode_surf(nl) = r
            self%lnode_loc(nl) = k - self%node_first(r) + 1
         end do
         do k = self%seg_first(r), self%seg_first(r + 1) - 1
            box(1:2) = min(x0(:, self%seg(1, k)), x1(:, self%seg(1, k)), &
                           x0(:, self%seg(2, k)), x1(:, self%seg(2, k))) - margin
            box(3:4) = max(x0(:, self%seg(1, k)), x1(:, self%seg(1, k)), &
                           x0(:, self%seg(2, k)), x1(:, self%seg(2, k))) + margin
            if (.not. reaches(self, r, box, 0.0_wp)) cycle
            ns = ns + 1
            self%lseg(:, ns) = self%seg(:, k)
            self%lseg_surf(ns) = r
            self%lseg_loc(ns) = k - self%seg_first(r) + 1
         end do
      end do
      self%nl = nl
      self%ns = ns
      call broad_search(self%fine, nnode, x0, x1, nl, self%lnodes, ns, self%lseg, margin)
      self%ntests = self%ntests + self%fine%ntests
      call regroup(self, n)
   end subroutine broad_all_search

   !> The result of `search` (the same groups, candidates and order, bit for bit) from a list
   !> kept across steps, as `broad_search_kept` does for one pair (doc/contact-detection.md,
   !> "Kept broad-phase list"): the groups of a search with margin + 2 skin, valid while no
   !> surface node has moved more than SKIN_USE x skin from its positions at that search; each
   !> step skips the groups whose two surfaces' boxes are apart, tests the kept candidates of
   !> the others, group by group, with `search`'s own test and margin and keeps the groups left
   !> with candidates (a filter keeps the order within and between the groups, so nothing is
   !> regrouped). A candidate of now is in the kept list: its node and segment boxes lie within
   !> their boxes of then grown by the skin, so at the build they overlapped with margin + 2
   !> skin, their surfaces' boxes too, and both passed the `reaches` tests.
   subroutine broad_all_search_kept(self, nnode, x0, x1, margin)
      class(broad_all_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      ! the skin: 0.4 of the mean segment length (fewer builds for a longer list than 0.2, which
      ! PAIR lists keep; doc/contact-detection.md, "Kept broad-phase list"), or 10 steps' motion
      real(wp), parameter :: SKIN_SHARE = 0.4_wp, SKIN_STEPS = 10.0_wp, SKIN_USE = 0.75_wp
      real(wp) :: d, mv, lsum
      integer :: k, l, node, nn, nlive

      self%ngroup = 0
      self%ntests = 0
      if (self%nsurf < 2) return
      nn = self%node_first(self%nsurf + 1) - 1
      d = huge(1.0_wp)
      call grow(self%nbox, max(nn, 1), 4)
      call grow(self%sbox, self%nsurf, 4)
      if (self%kept) then
         ! the largest motion since the build and this step's boxes of every node and surface
         ! (none if the list is empty), in one pass
         call moves_and_boxes(nnode, x0, x1, self%nsurf, self%node_first, self%nodes, self%xw, &
                              self%nkept > 0, self%nbox, self%sbox, d)
      end if
      ! a NaN position fails the test and builds again
      if (.not. (d <= SKIN_USE*self%skin)) then
         lsum = 0.0_wp
         mv = 0.0_wp
         call grow(self%xw, max(nn, 1), 4)
         ! the positions of the build (the kept list's reference), then this step's node and
         ! surface boxes
         do k = 1, nn
            node = self%nodes(k)
            mv = max(mv, abs(x1(1, node) - x0(1, node)), abs(x1(2, node) - x0(2, node)))
            self%xw(1:2, k) = x0(:, node)
            self%xw(3:4, k) = x1(:, node)
         end do
         call moves_and_boxes(nnode, x0, x1, self%nsurf, self%node_first, self%nodes, self%xw, &
                              .true., self%nbox, self%sbox, d)
         do k = 1, self%seg_first(self%nsurf + 1) - 1
            lsum = lsum + hypot(x0(1, self%seg(2, k)) - x0(1, self%seg(1, k)), &
                                x0(2, self%seg(2, k)) - x0(2, self%seg(1, k)))
         end do
         self%skin = max(SKIN_SHARE*lsum/real(max(self%seg_first(self%nsurf + 1) - 1, 1), wp), &
                         SKIN_STEPS*mv)
         call broad_all_search(self, nnode, x0, x1, margin + 2.0_wp*self%skin)
         ! keep the groups of that search (pairs within one surface are already out)
         self%nkgroup = self%ngroup
         self%nkept = 0
         if (self%ngroup > 0) self%nkept = self%gfirst(self%ngroup + 1) - 1
         self%nkept_nodes = self%nl
         self%nkept_segs = self%ns
         call grow(self%keep, max(self%nkept, 1), 2)
         call grow(self%kloc, max(self%nkept, 1), 2)
         call grow(self%ksegw, max(self%nkept_segs, 1), 2)
         ! the kept nodes as indices into nodes (their boxes in nbox), the kept segments' ends
         do k = 1, self%nkept
            l = self%gidx(1, k)
            self%keep(1, k) = self%node_first(self%lnode_surf(l)) + self%lnode_loc(l) - 1
            self%keep(2, k) = self%gidx(2, k)
         end do
         do k = 1, self%nkept_segs
            self%ksegw(:, k) = self%segw(:, self%seg_first(self%lseg_surf(k)) + self%lseg_loc(k) - 1)
         end do
         call grow(self%mstamp, max(self%nkept_segs, 1))
         self%mstamp(1:self%nkept_segs) = 0
         self%boxstamp = 0
         call grow(self%kgslave, max(self%nkgroup, 1))
         call grow(self%kgmaster, max(self%nkgroup, 1))
         call grow(self%kgfirst, self%nkgroup + 1)
         if (self%nkept > 0) self%kloc(:, 1:self%nkept) = self%gcand(:, 1:self%nkept)
         self%kgfirst(1) = 1
         if (self%nkgroup > 0) then
            self%kgslave(1:self%nkgroup) = self%gslave(1:self%nkgroup)
            self%kgmaster(1:self%nkgroup) = self%gmaster(1:self%nkgroup)
            self%kgfirst(1:self%nkgroup + 1) = self%gfirst(1:self%nkgroup + 1)
         end if
         self%kept = .true.
         self%nbuilds = self%nbuilds + 1
      else
         self%nkept_steps = self%nkept_steps + 1
      end if
      ! the kept candidates that pass the search's own test at this step, group by group in
      ! their order. First the groups whose two surfaces' boxes (the slave's, the master's grown
      ! by margin) meet: a candidate's node box lies in its surface's box and its segment's box
      ! in its surface's box grown by margin (the rounding of `- margin` is monotone), so a group
      ! whose surfaces' boxes are apart holds no candidate of this step. Then the boxes of the
      ! kept segments (from those of their ends, grown by margin: the same values as
      ! broad_search forms, min and max being exact): all of them, or, when the live groups hold
      ! less than half of the kept candidates, each at its first use by one of those; and four
      ! comparisons per candidate of the live groups (boxes_overlap with 0). Filtering the
      ! grouped kept list keeps regroup's order: its groups are (slave surface, master surface)
      ! ascending, each sorted by slave then segment.
      call grow(self%gcand, max(self%nkept, 1), 2)
      call grow(self%gslave, max(self%nkgroup, 1))
      call grow(self%gmaster, max(self%nkgroup, 1))
      call grow(self%gfirst, self%nkgroup + 1)
      if (self%nkept == 0) then
         self%gfirst(1) = 1
         self%ntests = 0
         return
      end if
      call grow(self%glive, self%nkgroup)
      call live_groups(self%nkgroup, self%kgslave, self%kgmaster, self%kgfirst, self%nsurf, self%sbox, &
                       margin, self%glive, nlive)
      call grow(self%fine%mbox, max(self%nkept_segs, 1), 4)
      if (2*nlive < self%nkept) then
         self%nlazy_steps = self%nlazy_steps + 1
         if (self%boxstamp == huge(self%boxstamp)) then
            self%mstamp(1:self%nkept_segs) = 0
            self%boxstamp = 0
         end if
         self%boxstamp = self%boxstamp + 1
         call used_segment_boxes(self%nkgroup, self%kgfirst, self%glive, self%keep, self%nkept_segs, &
                                 self%ksegw, self%nbox, margin, self%boxstamp, self%mstamp, self%fine%mbox)
      else
         call segment_boxes_of(self%nkept_segs, self%ksegw, self%nbox, margin, self%fine%mbox)
      end if
      call filter_kept(self%nkgroup, self%kgslave, self%kgmaster, self%kgfirst, self%glive, self%keep, &
                       self%kloc, nn, self%nbox, self%nkept_segs, self%fine%mbox, &
                       self%ngroup, self%gslave, self%gmaster, self%gfirst, self%gcand, self%ntests)
      self%ngroups_apart = self%ngroups_apart + count(.not. self%glive(1:self%nkgroup))
   end subroutine broad_all_search_kept

   !> glive(g): the box of group g's slave surface meets that of its master surface grown by
   !> margin (the test of filter_kept on the surfaces' boxes; a NaN never makes a group apart);
   !> nlive: the kept candidates of the live groups (group g holds kgfirst(g) to kgfirst(g + 1) - 1).
   pure subroutine live_groups(nkg, kgslave, kgmaster, kgfirst, nsurf, sbox, margin, glive, nlive)
      integer, intent(in) :: nkg, kgslave(*), kgmaster(*), kgfirst(nkg + 1), nsurf
      real(wp), intent(in) :: sbox(4, nsurf), margin
      logical, intent(out) :: glive(nkg)
      integer, intent(out) :: nlive
      integer :: g, i, j
      nlive = 0
      do g = 1, nkg
         i = kgslave(g)
         j = kgmaster(g)
         glive(g) = .not. (sbox(1, j) - margin > sbox(3, i) .or. sbox(1, i) > sbox(3, j) + margin .or. &
                           sbox(2, j) - margin > sbox(4, i) .or. sbox(2, i) > sbox(4, j) + margin)
         if (glive(g)) nlive = nlive + kgfirst(g + 1) - kgfirst(g)
      end do
   end subroutine live_groups

   !> Swept boxes of segments grown by margin from the boxes nbox of their ends ends(2, 1:n):
   !> the box broad_search forms over the four end positions, min and max being exact.
   pure subroutine segment_boxes_of(n, ends, nbox, margin, box)
      integer, intent(in) :: n, ends(2, n)
      real(wp), intent(in) :: nbox(4, *), margin
      real(wp), intent(inout) :: box(4, *)
      integer :: m
      ! by scalar index: faster here than the vector gather instructions (doc/performance.md 6.4,
      ! "Gathers in the kept list"), as in the element kernels' gather_pairs
      !GCC$ novector
      do m = 1, n
         box(1:2, m) = min(nbox(1:2, ends(1, m)), nbox(1:2, ends(2, m))) - margin
         box(3:4, m) = max(nbox(3:4, ends(1, m)), nbox(3:4, ends(2, m))) + margin
      end do
   end subroutine segment_boxes_of

   !> The boxes (segment_boxes_of) of the kept segments that the candidates of the live groups
   !> use, each once: mbox(:, m) is formed when mstamp(m) /= stamp, and mstamp(m) set.
   pure subroutine used_segment_boxes(nkg, kgfirst, glive, keep, nmb, ends, nbox, margin, stamp, mstamp, mbox)
      integer, intent(in) :: nkg, kgfirst(nkg + 1), keep(2, *), nmb, ends(2, nmb), stamp
      logical, intent(in) :: glive(nkg)
      real(wp), intent(in) :: nbox(4, *), margin
      integer, intent(inout) :: mstamp(nmb)
      real(wp), intent(inout) :: mbox(4, nmb)
      integer :: g, k, m
      do g = 1, nkg
         if (.not. glive(g)) cycle
         do k = kgfirst(g), kgfirst(g + 1) - 1
            m = keep(2, k)
            if (mstamp(m) == stamp) cycle
            call segment_boxes_of(1, ends(1, m), nbox, margin, mbox(1, m))
            mstamp(m) = stamp
         end do
      end do
   end subroutine used_segment_boxes

   !> d = the largest coordinate change of a node from its positions xw(1:2, k) at x0 and
   !> xw(3:4, k) at x1 (the test of the kept list), and if `boxes` the swept boxes (xmin, ymin,
   !> xmax, ymax) of the nodes over x0 -> x1, as broad_search forms them, and those of the nsurf
   !> surfaces (nodes(node_first(r) : node_first(r + 1) - 1)). A surface's box is taken by
   !> explicit comparisons, so that a node box holding a NaN (which fails every box test) is
   !> left out and never hides the others: it holds every node box that can pass a test.
   pure subroutine moves_and_boxes(nnode, x0, x1, nsurf, node_first, nodes, xw, boxes, box, sbox, d)
      integer, intent(in) :: nnode, nsurf, node_first(nsurf + 1), nodes(*)
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), xw(4, *)
      logical, intent(in) :: boxes
      real(wp), intent(inout) :: box(4, *), sbox(4, nsurf)
      real(wp), intent(out) :: d
      real(wp) :: b(4)
      integer :: k, r, node
      d = 0.0_wp
      if (.not. boxes) then
         ! by scalar index, like segment_boxes_of
         !GCC$ novector
         do k = node_first(1), node_first(nsurf + 1) - 1
            d = max(d, moved(k))
         end do
         return
      end if
      do r = 1, nsurf
         b(1:2) = huge(1.0_wp)
         b(3:4) = -huge(1.0_wp)
         !GCC$ novector
         do k = node_first(r), node_first(r + 1) - 1
            d = max(d, moved(k))
            node = nodes(k)
            box(1:2, k) = min(x0(:, node), x1(:, node))
            box(3:4, k) = max(x0(:, node), x1(:, node))
            if (box(1, k) < b(1)) b(1) = box(1, k)
            if (box(2, k) < b(2)) b(2) = box(2, k)
            if (box(3, k) > b(3)) b(3) = box(3, k)
            if (box(4, k) > b(4)) b(4) = box(4, k)
         end do
         sbox(:, r) = b
      end do
   contains
      !> The largest change of node k's coordinates, before the one max on the chain through d
      !> (max is exact: the same d as four in a row).
      pure real(wp) function moved(k) result(dk)
         integer, intent(in) :: k
         integer :: node
         node = nodes(k)
         dk = max(abs(x0(1, node) - xw(1, k)), abs(x0(2, node) - xw(2, k)), &
                  abs(x1(1, node) - xw(3, k)), abs(x1(2, node) - xw(4, k)))
      end function moved
   end subroutine moves_and_boxes

   !> The candidates of the live kept groups (glive; keep: node and segment box indices; kloc:
   !> what a group holds) whose boxes overlap (nbox against mbox), in their order; the groups
   !> left with candidates, in their order, into (ngroup, gslave, gmaster, gfirst, gcand);
   !> ntests the candidates tested; mbox(:, m): the box of kept segment m grown by margin.
   pure subroutine filter_kept(nkg, kgslave, kgmaster, kgfirst, glive, keep, kloc, nsb, nbox, nmb, &
                               mbox, ngroup, gslave, gmaster, gfirst, gcand, ntests)
      integer, intent(in) :: nkg, kgslave(*), kgmaster(*), kgfirst(nkg + 1), keep(2, *), kloc(2, *)
      logical, intent(in) :: glive(nkg)
      integer, intent(in) :: nsb, nmb
      real(wp), intent(in) :: nbox(4, nsb), mbox(4, nmb)
      integer, intent(out) :: ngroup
      integer, intent(inout) :: gslave(*), gmaster(*), gfirst(*), gcand(2, *)
      integer(i8), intent(out) :: ntests
      integer :: g, k, l, m, nc, c0
      nc = 0
      ngroup = 0
      ntests = 0
      gfirst(1) = 1
      do g = 1, nkg
         if (.not. glive(g)) cycle
         ntests = ntests + (kgfirst(g + 1) - kgfirst(g))
         c0 = nc
         do k = kgfirst(g), kgfirst(g + 1) - 1
            l = keep(1, k)
            m = keep(2, k)
            if (mbox(1, m) <= nbox(3, l) .and. nbox(1, l) <= mbox(3, m) .and. &
                mbox(2, m) <= nbox(4, l) .and. nbox(2, l) <= mbox(4, m)) then
               nc = nc + 1
               gcand(1, nc) = kloc(1, k)
               gcand(2, nc) = kloc(2, k)
            end if
         end do
         if (nc == c0) cycle
         ngroup = ngroup + 1
         gslave(ngroup) = kgslave(g)
         gmaster(ngroup) = kgmaster(g)
         gfirst(ngroup + 1) = nc + 1
      end do
   end subroutine filter_kept

   !> True when `box` meets the box of a partner of surface r grown by `grow_by` on every side.
   pure logical function reaches(self, r, box, grow_by) result(yes)
      type(broad_all_t), intent(in) :: self
      integer, intent(in) :: r
      real(wp), intent(in) :: box(4), grow_by
      integer :: p, q
      yes = .true.
      do p = self%pfirst(r), self%pfirst(r + 1) - 1
         q = self%partner(p)
         if (self%bx0(1, 2*q) - grow_by <= box(3) .and. box(1) <= self%bx1(1, 2*q) + grow_by .and. &
             self%bx0(2, 2*q) - grow_by <= box(4) .and. box(2) <= self%bx1(2, 2*q) + grow_by) return
      end do
      yes = .false.
   end function reaches

   !> 4. The fine search's candidates (sorted by slave, then segment, both in surface order)
   !> without the pairs within one surface, regrouped by (slave surface, master surface).
   subroutine regroup(self, n)
      type(broad_all_t), intent(inout) :: self
      integer, intent(in) :: n
      integer :: c, c0, c1, i, j, nj, q, p, l, m, g, ntot, v, t

      call grow(self%count, n)
      call grow(self%slot, n)
      call grow(self%jlist, n)
      call grow(self%gcand, self%fine%ncand, 2)
      call grow(self%gidx, self%fine%ncand, 2)
      ! at most one group per candidate
      call grow(self%gslave, self%fine%ncand)
      call grow(self%gmaster, self%fine%ncand)
      call grow(self%gfirst, self%fine%ncand + 1)
      self%gfirst(1) = 1
      ntot = 0
      c0 = 1
      do while (c0 <= self%fine%ncand)
         ! the block of slave surface i: consecutive candidates (slaves are in surface order)
         i = self%lnode_surf(self%fine%cand(1, c0))
         c1 = c0
         do while (c1 < self%fine%ncand)
            if (self%lnode_surf(self%fine%cand(1, c1 + 1)) /= i) exit
            c1 = c1 + 1
         end do
         ! distinct master surfaces of the block, sorted, with their counts
         nj = 0
         do c = c0, c1
            j = self%lseg_surf(self%fine%cand(2, c))
            if (j == i) cycle
            if (nj > 0) then
               if (any(self%jlist(1:nj) == j)) then
                  self%count(j) = self%count(j) + 1
                  cycle
               end if
            end if
            nj = nj + 1
            self%jlist(nj) = j
            self%count(j) = 1
         end do
         ! insertion sort of the (few) master surfaces
         do q = 2, nj
            v = self%jlist(q)
            t = q - 1
            do while (t >= 1)
               if (self%jlist(t) <= v) exit
               self%jlist(t + 1) = self%jlist(t)
               t = t - 1
            end do
            self%jlist(t + 1) = v
         end do
         ! one group per master surface; a stable placement keeps (slave, segment) order
         p = ntot + 1
         do q = 1, nj
            j = self%jlist(q)
            self%slot(j) = p
            p = p + self%count(j)
            self%gslave(self%ngroup + q) = i
            self%gmaster(self%ngroup + q) = j
            self%gfirst(self%ngroup + q + 1) = p
         end do
         do c = c0, c1
            l = self%fine%cand(1, c)
            m = self%fine%cand(2, c)
            j = self%lseg_surf(m)
            if (j == i) cycle
            g = self%slot(j)
            self%gcand(1, g) = self%lnode_loc(l)
            self%gcand(2, g) = self%lseg_loc(m)
            self%gidx(1, g) = l
            self%gidx(2, g) = m
            self%slot(j) = g + 1
         end do
         ntot = p - 1
         self%ngroup = self%ngroup + nj
         c0 = c1 + 1
      end do
   end subroutine regroup

   !> The candidates of group g into bw (ncand, cand), as broad_search on the pair would leave them.
   subroutine broad_all_take(self, g, bw)
      class(broad_all_t), intent(in) :: self
      integer, intent(in) :: g
      type(broad_t), intent(inout) :: bw
      integer :: n, f
      f = self%gfirst(g)
      n = self%gfirst(g + 1) - f
      call grow(bw%cand, n, 2)
      ! one flat copy (element by element through the two components' descriptors it took 12
      ! instructions a candidate)
      if (n > 0) call copy_flat_int(2*n, self%gcand(1, f), bw%cand)
      bw%ncand = n
      bw%ntests = 0
   end subroutine broad_all_take

end module exic_contact_broad_all
