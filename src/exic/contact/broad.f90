!> Broad phase of the contact search: candidate (slave node, master segment) pairs whose
!> swept bounding boxes overlap over the step t(n+1) -> t(n+2).
!>
!> Positions come in two arrays: x0 at t(n+1) (tau = 0) and x1, the predicted positions
!> at t(n+2) (tau = 1). With linear motion over the step (seed eq. 6.1) the path of every
!> point lies in the box of its start and end positions, so a slave can reach a segment
!> only if their swept boxes overlap; master boxes are grown by `margin` on every side.
!>
!> Search: a whole-surface test first (union boxes apart: nothing to do), then a uniform
!> bucket grid over the region where both unions overlap. The cell size is the mean swept
!> box extent (segment length plus motion plus margin) of the entities, enlarged if needed
!> so that the grid has at most about 4 x (slaves + segments) cells. Segments are binned
!> into every cell their box touches; each slave tests only the segments of the cells its
!> box touches. A pair met in several cells is reported only from the cell holding the
!> lower-left corner of the two boxes' intersection, so no marks are needed. The work
!> (counted in `ntests`) grows with the number of entities near each other, not with
!> n_slave x n_segment.
!>
!> Output: cand(1, k) = slave index (position in the slave list), cand(2, k) = segment
!> index, sorted by slave then segment. A slave node is never paired with a segment that
!> contains it. Work arrays live in `broad_t` and are only grown, never shrunk.
module exic_contact_broad
   use exic_base_kinds, only: wp, i8
   use exic_base_sort, only: sort_short_int
   use exic_base_grow, only: grow
   implicit none
   private

   public :: broad_t, broad_search, broad_search_kept, broad_brute, swept_box, surfaces_apart, &
             boxes_overlap, drop_flat_fixed, keep_convex_corners

   !> Skin of the kept list (broad_search_kept): SKIN_SHARE of the mean segment length, or
   !> SKIN_STEPS times the largest motion of one step if that is larger.
   real(wp), parameter :: SKIN_SHARE = 0.2_wp, SKIN_STEPS = 10.0_wp
   !> A node may move up to SKIN_USE x skin from its positions at the build (the rest of the
   !> skin absorbs the rounding of the box tests).
   real(wp), parameter :: SKIN_USE = 0.75_wp

   !> Turn of a surface at a node (radians) from which the node is a convex corner that the
   !> corner pass of a one-pass pair makes a slave (keep_convex_corners): 30 degrees.
   real(wp), parameter :: CORNER_TURN = 0.5235987755982988_wp

   !> Work space and result of the broad phase; reuse one per contact pair across steps.
   type :: broad_t
      integer :: ncand = 0                   !< number of candidate pairs found
      integer, allocatable :: cand(:, :)     !< (2, >= ncand): slave index, segment index
      integer(i8) :: ntests = 0              !< box tests done by the last search
      integer(i8) :: ntests_total = 0        !< box tests summed over all searches
      integer :: nx = 0, ny = 0              !< grid of the last search (0: skipped)
      real(wp), allocatable :: sbox(:, :)    !< (4, nslave) xmin, ymin, xmax, ymax
      real(wp), allocatable :: mbox(:, :)    !< (4, nseg)
      integer, allocatable :: head(:)        !< (ncell + 1) CSR pointers of the grid
      integer, allocatable :: items(:)       !< segment indices by cell
      integer, allocatable :: buf(:)         !< per-slave list of found segments
      ! kept list of broad_search_kept: the pairs within margin + 2 skin at the build
      logical :: kept = .false.              !< the kept list exists
      integer :: nkept = 0                   !< pairs in it
      integer, allocatable :: keep(:, :)     !< (2, >= nkept) slave index, segment index, sorted
      real(wp) :: skin = 0.0_wp              !< skin of the kept list
      integer :: kslave = 0, kseg = 0        !< list sizes the kept list was built for
      integer :: nwatch = 0                  !< distinct slave and segment nodes
      integer, allocatable :: watch(:)       !< (nwatch) those nodes
      real(wp), allocatable :: xw(:, :)      !< (4, nwatch) their x0, x1 at the build
      integer(i8) :: nbuilds = 0             !< builds of the kept list
      integer(i8) :: nkept_steps = 0         !< searches answered from the kept list
   end type broad_t

contains

   !> Swept box (xmin, ymin, xmax, ymax) of nodes `list(1:n)` over positions x0 and x1.
   pure function swept_box(nnode, x0, x1, n, list) result(box)
      integer, intent(in) :: nnode, n
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode)
      integer, intent(in) :: list(n)
      real(wp) :: box(4)
      integer :: k
      box(1:2) = huge(1.0_wp)
      box(3:4) = -huge(1.0_wp)
      do k = 1, n
         box(1:2) = min(box(1:2), x0(:, list(k)), x1(:, list(k)))
         box(3:4) = max(box(3:4), x0(:, list(k)), x1(:, list(k)))
      end do
   end function swept_box

   !> True when boxes a and b (xmin, ymin, xmax, ymax) overlap or touch after growing a
   !> by `margin`.
   pure logical function boxes_overlap(a, b, margin) result(ok)
      real(wp), intent(in) :: a(4), b(4), margin
      ok = a(1) - margin <= b(3) .and. b(1) <= a(3) + margin .and. &
           a(2) - margin <= b(4) .and. b(2) <= a(4) + margin
   end function boxes_overlap

   !> Whole-surface test: true when the swept box of the slave nodes and that of the
   !> master segment nodes (grown by margin) are apart, so no pair can be in contact.
   pure logical function surfaces_apart(nnode, x0, x1, nslave, slaves, nseg, seg, margin) &
      result(apart)
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      apart = .true.
      if (nslave == 0 .or. nseg == 0) return
      apart = .not. boxes_overlap(swept_box(nnode, x0, x1, 2*nseg, reshape(seg, [2*nseg])), &
                                  swept_box(nnode, x0, x1, nslave, slaves), margin)
   end function surfaces_apart

   !> Broad phase: fill bw%cand(:, 1:bw%ncand) with the (slave, segment) pairs whose swept
   !> boxes overlap (master boxes grown by margin), sorted by slave then segment.
   subroutine broad_search(bw, nnode, x0, x1, nslave, slaves, nseg, seg, margin)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      real(wp) :: ubs(4), ubm(4), dom(4), h, ext(2), hmean
      integer :: k

      bw%ncand = 0
      bw%ntests = 0
      bw%nx = 0
      bw%ny = 0
      if (nslave == 0 .or. nseg == 0) return
      call grow(bw%sbox, nslave, 4)
      call grow(bw%mbox, nseg, 4)
      hmean = 0.0_wp
      ubs(1:2) = huge(1.0_wp); ubs(3:4) = -huge(1.0_wp)
      ubm = ubs
      do k = 1, nslave
         bw%sbox(1:2, k) = min(x0(:, slaves(k)), x1(:, slaves(k)))
         bw%sbox(3:4, k) = max(x0(:, slaves(k)), x1(:, slaves(k)))
         ubs(1:2) = min(ubs(1:2), bw%sbox(1:2, k))
         ubs(3:4) = max(ubs(3:4), bw%sbox(3:4, k))
         hmean = hmean + maxval(bw%sbox(3:4, k) - bw%sbox(1:2, k))
      end do
      do k = 1, nseg
         bw%mbox(1:2, k) = min(x0(:, seg(1, k)), x1(:, seg(1, k)), &
                               x0(:, seg(2, k)), x1(:, seg(2, k))) - margin
         bw%mbox(3:4, k) = max(x0(:, seg(1, k)), x1(:, seg(1, k)), &
                               x0(:, seg(2, k)), x1(:, seg(2, k))) + margin
         ubm(1:2) = min(ubm(1:2), bw%mbox(1:2, k))
         ubm(3:4) = max(ubm(3:4), bw%mbox(3:4, k))
         hmean = hmean + maxval(bw%mbox(3:4, k) - bw%mbox(1:2, k))
      end do
      ! whole-surface test
      if (.not. boxes_overlap(ubs, ubm, 0.0_wp)) return
      dom(1:2) = max(ubs(1:2), ubm(1:2))
      dom(3:4) = min(ubs(3:4), ubm(3:4))
      ! cell size: mean extent, enlarged to keep at most ~4 (nslave + nseg) cells
      ext = dom(3:4) - dom(1:2)
      hmean = hmean/real(nslave + nseg, wp)
      h = max(hmean, sqrt(ext(1)*ext(2)/real(4*(nslave + nseg), wp)), &
              maxval(ext)/real(4*(nslave + nseg), wp))
      if (.not. (h > 0.0_wp)) h = 1.0_wp
      bw%nx = max(1, min(4*(nslave + nseg), int(ext(1)/h) + 1))
      bw%ny = max(1, min(4*(nslave + nseg), int(ext(2)/h) + 1))
      call bin_segments(bw, nseg, dom, h)
      call query_slaves(bw, nslave, slaves, nseg, seg, dom, h)
      bw%ntests_total = bw%ntests_total + bw%ntests
   end subroutine broad_search

   !> The result of broad_search (the same pairs in the same order, bit for bit) from a list
   !> kept across steps, in the manner of a Verlet list. The kept list holds the pairs whose
   !> boxes overlap with margin + 2 skin at the positions of its build; while every slave and
   !> segment node stays within SKIN_USE x skin of those positions (at both x0 and x1), every
   !> box of now lies within its box of then grown by the skin, so every pair of now is in
   !> the kept list, and testing the kept pairs with broad_search's own test and margin gives
   !> exactly broad_search's list (doc/contact-detection.md, "Kept broad-phase list"). A node
   !> moving further, or a change of the lists' sizes, builds the list again.
   subroutine broad_search_kept(bw, nnode, x0, x1, nslave, slaves, nseg, seg, margin)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      real(wp) :: sb(4), mb(4)
      integer :: k, s, m

      if (.not. kept_valid(bw, nnode, x0, x1, nslave, nseg)) then
         call build_kept(bw, nnode, x0, x1, nslave, slaves, nseg, seg, margin)
      else
         bw%nkept_steps = bw%nkept_steps + 1
      end if
      bw%ncand = 0
      bw%ntests = 0
      call grow(bw%cand, max(bw%nkept, 1), 2)
      do k = 1, bw%nkept
         s = bw%keep(1, k)
         m = bw%keep(2, k)
         sb(1:2) = min(x0(:, slaves(s)), x1(:, slaves(s)))
         sb(3:4) = max(x0(:, slaves(s)), x1(:, slaves(s)))
         mb(1:2) = min(x0(:, seg(1, m)), x1(:, seg(1, m)), x0(:, seg(2, m)), x1(:, seg(2, m))) - margin
         mb(3:4) = max(x0(:, seg(1, m)), x1(:, seg(1, m)), x0(:, seg(2, m)), x1(:, seg(2, m))) + margin
         if (.not. boxes_overlap(mb, sb, 0.0_wp)) cycle
         bw%ncand = bw%ncand + 1
         bw%cand(:, bw%ncand) = bw%keep(:, k)
      end do
      bw%ntests = bw%nkept
      bw%ntests_total = bw%ntests_total + bw%ntests
   end subroutine broad_search_kept

   !> True when the kept list of bw was built for these list sizes and no slave or segment
   !> node has moved more than SKIN_USE x skin (in x or y, at x0 or at x1) since.
   logical function kept_valid(bw, nnode, x0, x1, nslave, nseg) result(ok)
      type(broad_t), intent(in) :: bw
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode)
      real(wp) :: d
      integer :: k, n

      ok = bw%kept .and. bw%kslave == nslave .and. bw%kseg == nseg
      if (.not. ok) return
      d = 0.0_wp
      do k = 1, bw%nwatch
         n = bw%watch(k)
         d = max(d, abs(x0(1, n) - bw%xw(1, k)), abs(x0(2, n) - bw%xw(2, k)), &
                 abs(x1(1, n) - bw%xw(3, k)), abs(x1(2, n) - bw%xw(4, k)))
      end do
      ! a NaN position fails the test and builds again (broad_search then sees it)
      ok = d <= SKIN_USE*bw%skin
   end function kept_valid

   !> Build the kept list at x0, x1: broad_search with margin + 2 skin, and the positions of
   !> the distinct slave and segment nodes.
   subroutine build_kept(bw, nnode, x0, x1, nslave, slaves, nseg, seg, margin)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      real(wp) :: lsum, mv
      integer :: k, n
      logical, allocatable :: mark(:)

      if (.not. (bw%kept .and. bw%kslave == nslave .and. bw%kseg == nseg)) then
         ! the distinct nodes, in node order (once per surface pair: the lists do not change)
         allocate (mark(nnode), source=.false.)
         mark(slaves) = .true.
         mark(seg(1, 1:nseg)) = .true.
         mark(seg(2, 1:nseg)) = .true.
         n = count(mark)
         call grow(bw%watch, n)
         bw%watch(1:n) = pack([(k, k=1, nnode)], mark)
         bw%nwatch = n
         call grow(bw%xw, n, 4)
      end if
      lsum = 0.0_wp
      do k = 1, nseg
         lsum = lsum + hypot(x0(1, seg(2, k)) - x0(1, seg(1, k)), x0(2, seg(2, k)) - x0(2, seg(1, k)))
      end do
      mv = 0.0_wp
      do k = 1, bw%nwatch
         n = bw%watch(k)
         mv = max(mv, abs(x1(1, n) - x0(1, n)), abs(x1(2, n) - x0(2, n)))
         bw%xw(1:2, k) = x0(:, n)
         bw%xw(3:4, k) = x1(:, n)
      end do
      bw%skin = max(SKIN_SHARE*lsum/real(max(nseg, 1), wp), SKIN_STEPS*mv)
      call broad_search(bw, nnode, x0, x1, nslave, slaves, nseg, seg, margin + 2.0_wp*bw%skin)
      call grow(bw%keep, max(bw%ncand, 1), 2)
      bw%nkept = bw%ncand
      if (bw%ncand > 0) bw%keep(:, 1:bw%ncand) = bw%cand(:, 1:bw%ncand)
      bw%kslave = nslave
      bw%kseg = nseg
      bw%kept = .true.
      bw%nbuilds = bw%nbuilds + 1
   end subroutine build_kept

   !> Drop from bw's candidates the slaves that lie inside a straight stretch of a surface that
   !> the corrector cannot move: the slave and the far ends of its two segments have no inverse
   !> mass (rigid, fixed or prescribed: minv = 0) and the two segments continue each other
   !> (|t1 x t2| <= 1e-9 |t1| |t2|, t1 . t2 > 0) (doc/contact-detection.md, "Flat immovable
   !> faces"). head, segs: the segments of each slave (node_segments). The pairs left keep
   !> their order.
   pure subroutine drop_flat_fixed(bw, nnode, x, minv, nslave, slaves, seg, head, segs)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nnode, nslave
      real(wp), intent(in) :: x(2, nnode), minv(2, nnode)
      integer, intent(in) :: slaves(nslave), seg(:, :), head(nslave + 1), segs(:)
      integer :: k, n, s, node, far(2), j
      real(wp) :: t1(2), t2(2)
      logical :: flat

      ! most passes have no immovable slave: one quick look first
      if (.not. any_immovable(bw%ncand, bw%cand, nslave, slaves, nnode, minv)) return
      n = 0
      do k = 1, bw%ncand
         s = bw%cand(1, k)
         node = slaves(s)
         ! a movable slave (the common case) is kept at once
         flat = .false.
         if (minv(1, node) == 0.0_wp) then
            if (minv(2, node) == 0.0_wp) flat = head(s + 1) - head(s) == 2
         end if
         if (flat) then
            do j = 1, 2
               far(j) = sum(seg(:, segs(head(s) + j - 1))) - node
            end do
            flat = all(minv(:, far) == 0.0_wp)
         end if
         if (flat) then
            t1 = x(:, node) - x(:, far(1))
            t2 = x(:, far(2)) - x(:, node)
            flat = abs(t1(1)*t2(2) - t1(2)*t2(1)) <= 1.0e-9_wp*hypot(t1(1), t1(2))*hypot(t2(1), t2(2)) &
                   .and. dot_product(t1, t2) > 0.0_wp
         end if
         if (.not. flat) call keep_candidate(bw, n, k)
      end do
      bw%ncand = n
   end subroutine drop_flat_fixed

   !> Keep of bw's candidates only the slaves at which their own surface turns convex by
   !> CORNER_TURN or more: the slave has two segments, t1 into it and t2 out of it (the body on
   !> the left), t1 x t2 > 0 and the angle from t1 to t2, atan2(t1 x t2, t1 . t2), at least
   !> CORNER_TURN (doc/contact-detection.md, "Corner pass of a one-pass pair"). A node with one
   !> segment (the end of an open surface) is not kept: the body's turn there is not known. The
   !> pairs left keep their order.
   pure subroutine keep_convex_corners(bw, nnode, x, nslave, slaves, seg, head, segs)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nnode, nslave
      real(wp), intent(in) :: x(2, nnode)
      integer, intent(in) :: slaves(nslave), seg(:, :), head(nslave + 1), segs(:)
      integer :: k, n, s, last
      logical :: corner

      n = 0
      last = 0
      corner = .false.
      do k = 1, bw%ncand
         s = bw%cand(1, k)
         ! a slave's candidates come one after another: its turn is formed once for them
         if (s /= last) then
            last = s
            corner = convex_corner(nnode, x, slaves(s), seg, segs(head(s):head(s + 1) - 1))
         end if
         if (corner) call keep_candidate(bw, n, k)
      end do
      bw%ncand = n
   end subroutine keep_convex_corners

   !> True when the surface turns convex by CORNER_TURN or more at `node`, whose segments are
   !> `mine` (keep_convex_corners): two of them, one ending and one starting at the node.
   pure logical function convex_corner(nnode, x, node, seg, mine) result(corner)
      integer, intent(in) :: nnode, node, seg(:, :), mine(:)
      real(wp), intent(in) :: x(2, nnode)
      integer :: j, prev, next
      real(wp) :: t1(2), t2(2)
      corner = .false.
      if (size(mine) /= 2) return
      prev = 0
      next = 0
      do j = 1, 2
         if (seg(2, mine(j)) == node) prev = seg(1, mine(j))
         if (seg(1, mine(j)) == node) next = seg(2, mine(j))
      end do
      if (prev == 0 .or. next == 0) return
      t1 = x(:, node) - x(:, prev)
      t2 = x(:, next) - x(:, node)
      corner = atan2(t1(1)*t2(2) - t1(2)*t2(1), dot_product(t1, t2)) >= CORNER_TURN
   end function convex_corner

   !> Keep candidate k of bw as the next of the n kept so far (n < k: moved down, in order).
   pure subroutine keep_candidate(bw, n, k)
      type(broad_t), intent(inout) :: bw
      integer, intent(inout) :: n
      integer, intent(in) :: k
      n = n + 1
      if (n < k) bw%cand(:, n) = bw%cand(:, k)
   end subroutine keep_candidate

   !> True when the slave of some candidate cand(:, 1:n) has no inverse mass in either direction
   !> (drop_flat_fixed's first test).
   pure logical function any_immovable(n, cand, nslave, slaves, nnode, minv) result(any_fixed)
      integer, intent(in) :: n, cand(2, *), nslave, slaves(nslave), nnode
      real(wp), intent(in) :: minv(2, nnode)
      integer :: k, node
      any_fixed = .false.
      do k = 1, n
         node = slaves(cand(1, k))
         if (minv(1, node) == 0.0_wp .and. minv(2, node) == 0.0_wp) then
            any_fixed = .true.
            return
         end if
      end do
   end function any_immovable

   !> Cell index (0-based) of coordinate v on an axis starting at lo with n cells of size h.
   pure integer function cell_of(v, lo, h, n) result(i)
      real(wp), intent(in) :: v, lo, h
      integer, intent(in) :: n
      i = int(min(real(n - 1, wp), max(0.0_wp, (v - lo)/h)))
   end function cell_of

   !> Put each segment whose box meets the domain into every cell its box touches (CSR).
   subroutine bin_segments(bw, nseg, dom, h)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nseg
      real(wp), intent(in) :: dom(4), h
      integer :: k, ix, iy, ix0, ix1, iy0, iy1, ncell, c, pass

      ncell = bw%nx*bw%ny
      call grow(bw%head, ncell + 1)
      bw%head(1:ncell + 1) = 0
      do pass = 1, 2
         do k = 1, nseg
            if (.not. boxes_overlap(bw%mbox(:, k), dom, 0.0_wp)) cycle
            ix0 = cell_of(bw%mbox(1, k), dom(1), h, bw%nx)
            ix1 = cell_of(bw%mbox(3, k), dom(1), h, bw%nx)
            iy0 = cell_of(bw%mbox(2, k), dom(2), h, bw%ny)
            iy1 = cell_of(bw%mbox(4, k), dom(2), h, bw%ny)
            do iy = iy0, iy1
               do ix = ix0, ix1
                  c = iy*bw%nx + ix + 1
                  if (pass == 1) then
                     bw%head(c + 1) = bw%head(c + 1) + 1
                  else
                     bw%items(bw%head(c)) = k
                     bw%head(c) = bw%head(c) + 1
                  end if
               end do
            end do
         end do
         if (pass == 1) then
            ! head(c) becomes the first slot of cell c
            bw%head(1) = 1
            do c = 2, ncell + 1
               bw%head(c) = bw%head(c) + bw%head(c - 1)
            end do
            call grow(bw%items, bw%head(ncell + 1) - 1)
         end if
      end do
      ! after filling, head(c) points one past cell c: shift back
      do c = ncell + 1, 2, -1
         bw%head(c) = bw%head(c - 1)
      end do
      bw%head(1) = 1
   end subroutine bin_segments

   !> For each slave in order, test the segments of the cells its box touches.
   subroutine query_slaves(bw, nslave, slaves, nseg, seg, dom, h)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: nslave, nseg
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      real(wp), intent(in) :: dom(4), h
      integer :: s, k, ix, iy, ix0, ix1, iy0, iy1, c, p, nfound, node
      real(wp) :: rx, ry

      call grow(bw%buf, 16)
      do s = 1, nslave
         if (.not. boxes_overlap(bw%sbox(:, s), dom, 0.0_wp)) cycle
         node = slaves(s)
         ix0 = cell_of(bw%sbox(1, s), dom(1), h, bw%nx)
         ix1 = cell_of(bw%sbox(3, s), dom(1), h, bw%nx)
         iy0 = cell_of(bw%sbox(2, s), dom(2), h, bw%ny)
         iy1 = cell_of(bw%sbox(4, s), dom(2), h, bw%ny)
         nfound = 0
         do iy = iy0, iy1
            do ix = ix0, ix1
               c = iy*bw%nx + ix + 1
               do p = bw%head(c), bw%head(c + 1) - 1
                  k = bw%items(p)
                  bw%ntests = bw%ntests + 1
                  if (.not. boxes_overlap(bw%mbox(:, k), bw%sbox(:, s), 0.0_wp)) cycle
                  rx = max(bw%sbox(1, s), bw%mbox(1, k))
                  ry = max(bw%sbox(2, s), bw%mbox(2, k))
                  if (cell_of(rx, dom(1), h, bw%nx) /= ix) cycle
                  if (cell_of(ry, dom(2), h, bw%ny) /= iy) cycle
                  if (seg(1, k) == node .or. seg(2, k) == node) cycle
                  if (nfound == size(bw%buf)) call grow(bw%buf, 2*nfound)
                  nfound = nfound + 1
                  bw%buf(nfound) = k
               end do
            end do
         end do
         if (nfound == 0) cycle
         call sort_short_int(bw%buf(1:nfound))
         call append(bw, s, nfound, bw%buf)
      end do
   end subroutine query_slaves

   !> Append the pairs (s, list(1:n)) to the candidate list, growing it when full.
   subroutine append(bw, s, n, list)
      type(broad_t), intent(inout) :: bw
      integer, intent(in) :: s, n, list(:)
      integer, allocatable :: tmp(:, :)
      integer :: cap
      cap = 0
      if (allocated(bw%cand)) cap = size(bw%cand, 2)
      if (bw%ncand + n > cap) then
         allocate (tmp(2, max(2*cap, bw%ncand + n, 64)))
         if (bw%ncand > 0) tmp(:, 1:bw%ncand) = bw%cand(:, 1:bw%ncand)
         call move_alloc(tmp, bw%cand)
      end if
      bw%cand(1, bw%ncand + 1:bw%ncand + n) = s
      bw%cand(2, bw%ncand + 1:bw%ncand + n) = list(1:n)
      bw%ncand = bw%ncand + n
   end subroutine append

   !> Reference broad phase: every slave against every segment (O(n_slave x n_segment)),
   !> same box test and exclusion as broad_search; for tests and tiny surfaces.
   subroutine broad_brute(nnode, x0, x1, nslave, slaves, nseg, seg, margin, ncand, cand)
      integer, intent(in) :: nnode, nslave, nseg
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), margin
      integer, intent(in) :: slaves(nslave), seg(2, nseg)
      integer, intent(out) :: ncand
      integer, allocatable, intent(inout) :: cand(:, :)
      real(wp) :: sb(4), mb(4)
      integer :: s, k, node
      integer, allocatable :: tmp(:, :)

      ncand = 0
      if (.not. allocated(cand)) allocate (cand(2, 64))
      do s = 1, nslave
         node = slaves(s)
         sb(1:2) = min(x0(:, node), x1(:, node))
         sb(3:4) = max(x0(:, node), x1(:, node))
         do k = 1, nseg
            if (seg(1, k) == node .or. seg(2, k) == node) cycle
            mb(1:2) = min(x0(:, seg(1, k)), x1(:, seg(1, k)), x0(:, seg(2, k)), x1(:, seg(2, k)))
            mb(3:4) = max(x0(:, seg(1, k)), x1(:, seg(1, k)), x0(:, seg(2, k)), x1(:, seg(2, k)))
            if (.not. boxes_overlap(mb, sb, margin)) cycle
            if (ncand == size(cand, 2)) then
               allocate (tmp(2, 2*ncand))
               tmp(:, 1:ncand) = cand
               call move_alloc(tmp, cand)
            end if
            ncand = ncand + 1
            cand(:, ncand) = [s, k]
         end do
      end do
   end subroutine broad_brute

end module exic_contact_broad
