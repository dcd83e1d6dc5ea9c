!> Geometric penetration check: nodes of one body that lie inside another body's elements, or
!> inside elements of their own body.
!>
!> The contact passes measure penetration only over the node-segment pairs they detect; a node
!> that went through a surface undetected (or whose pair was lost) is invisible to them. This
!> check looks at the actual polygons: for every node on the free boundary of body A (a body
!> enters another through its boundary) it finds the elements of every
!> other body B (that contact covers) containing it, and measures how deep it is as the distance
!> to B's free boundary, in lengths of the nearest boundary edge (doc/decisions.md,
!> "Geometric penetration check"). A node inside an element of its own body A that does not
!> have it as a corner means that A has passed through itself (a hollow ring closing on itself,
!> with no self contact asked for): its depth is the distance to that element's nearest side,
!> in lengths of that side.
!>
!> Cost per check O(nnode + nelem): a uniform grid over the bounding box of the mesh (cell = the
!> mean element extent, at most about 4 nelem cells) holds the elements by the cells their boxes
!> touch; each node tests the elements of its own cell (box test, then the crossing-number test
!> on the quadrilateral). Only nodes found inside compute a depth, by a ring search over a second
!> grid holding B's boundary edges. Plain arrays in: positions, connectivity, body per element.
module exic_contact_inside
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_strings, only: itoa, rtoa
   use exic_base_clock, only: wall_time
   use exic_mesh_boundary, only: free_edges
   implicit none
   private

   public :: inside_t, point_in_quad

   !> The deepest node found by one check or over the run.
   type, public :: inside_hit_t
      real(wp) :: depth = 0.0_wp        !< distance to the other body's boundary
      real(wp) :: edges = 0.0_wp        !< depth / length of the nearest boundary edge
      integer :: node = 0
      integer :: of_body = 0, in_body = 0   !< body numbers (as given to init: regions)
      real(wp) :: t = 0.0_wp
   end type inside_hit_t

   type :: inside_t
      logical :: active = .false.
      integer :: nnode = 0, nelem = 0, nbody = 0
      integer, allocatable :: conn(:, :)        !< (4, nelem)
      integer, allocatable :: eb(:)             !< (nelem) body index 1..nbody of each element
      integer, allocatable :: ids(:)            !< (nbody) body numbers (regions)
      integer, allocatable :: nb(:)             !< (nnode) body index of each boundary node (0: not tested)
      logical, allocatable :: pairs(:, :)       !< (nbody, nbody): nodes of i checked against elements of j
      integer, allocatable :: edge(:, :)        !< (2, nedge) free boundary edges of all bodies
      integer, allocatable :: edge_body(:)      !< (nedge) body index of each edge
      real(wp) :: fraction = 1.0e-3_wp          !< warning limit, in edge lengths
      !> results
      type(inside_hit_t) :: last                !< deepest of the last check
      type(inside_hit_t) :: worst               !< deepest over the run
      integer :: nover = 0                      !< nodes past `fraction` in the last check
      integer, allocatable :: over_checks(:, :) !< (nbody, nbody) checks in which the pair had nodes past it
      integer, allocatable :: over_max(:, :)    !< (nbody, nbody) most such nodes in one check
      integer :: nchecks = 0
      real(wp) :: time_total = 0.0_wp           !< wall time of all checks
      ! work space of the grids
      integer, private :: nx = 0, ny = 0
      real(wp), private :: lo(2) = 0.0_wp, h = 1.0_wp
      integer, allocatable, private :: ehead(:), eitem(:), ghead(:), gitem(:)
      real(wp), allocatable, private :: ebox(:, :)   !< (4, nelem) element boxes: x, y low, x, y high
   contains
      procedure :: init => inside_init
      procedure :: allow => inside_allow
      procedure :: check => inside_check
      procedure :: report => inside_report
   end type inside_t

contains

   !> Bodies from `body(nelem)` (region numbers); no pair is checked until `allow` names it.
   subroutine inside_init(self, nnode, nelem, conn, body, fraction, err)
      class(inside_t), intent(inout) :: self
      integer, intent(in) :: nnode, nelem
      integer, intent(in) :: conn(4, nelem), body(nelem)
      real(wp), intent(in) :: fraction
      type(error_t), allocatable, intent(out) :: err
      integer :: e, k, j, lo_id, hi_id
      integer, allocatable :: map(:), seg(:, :)
      logical, allocatable :: seen(:), on_boundary(:)

      select type (self)
      type is (inside_t)
         self = inside_t()          ! a second init starts afresh
      end select
      if (nelem == 0) return
      self%nnode = nnode
      self%nelem = nelem
      self%conn = conn
      self%fraction = fraction
      lo_id = minval(body)
      hi_id = maxval(body)
      allocate (seen(lo_id:hi_id), source=.false.)
      seen(body) = .true.
      self%nbody = count(seen)
      allocate (self%ids(self%nbody), map(lo_id:hi_id), source=0)
      k = 0
      do j = lo_id, hi_id
         if (.not. seen(j)) cycle
         k = k + 1
         self%ids(k) = j
         map(j) = k
      end do
      self%eb = map(body)
      allocate (self%nb(nnode), source=0)
      do e = 1, nelem
         do j = 1, 4
            if (self%nb(conn(j, e)) == 0) self%nb(conn(j, e)) = self%eb(e)
         end do
      end do
      allocate (self%pairs(self%nbody, self%nbody), source=.false.)
      allocate (self%over_checks(self%nbody, self%nbody), self%over_max(self%nbody, self%nbody), source=0)
      allocate (self%edge(2, 0), self%edge_body(0))
      do k = 1, self%nbody
         call free_edges(nelem, conn, self%eb == k, seg, err)
         if (allocated(err)) return
         self%edge = reshape([self%edge, seg], [2, size(self%edge, 2) + size(seg, 2)])
         self%edge_body = [self%edge_body, spread(k, 1, size(seg, 2))]
      end do
      ! only nodes of a free boundary are tested: a body enters another through its boundary
      allocate (on_boundary(nnode), source=.false.)
      on_boundary(self%edge(1, :)) = .true.
      on_boundary(self%edge(2, :)) = .true.
      where (.not. on_boundary) self%nb = 0
      self%active = .true.
   end subroutine inside_init

   !> Check the nodes of `slave(:)`'s bodies against the elements of `master(:)`'s bodies (the
   !> nodes of a contact pass's two surfaces); nodes of the same body are never checked.
   subroutine inside_allow(self, slave, master)
      class(inside_t), intent(inout) :: self
      integer, intent(in) :: slave(:), master(:)
      logical :: bs(self%nbody), bm(self%nbody)
      integer :: ls(self%nbody), lm(self%nbody)
      integer :: i, j, ns, nm
      if (.not. self%active) return
      ! the distinct bodies of each side (a call costs its node lists and the pairs it names, not
      ! nbody^2: AUTOmatic makes one call per ordered pair of surfaces)
      bs = .false.
      bm = .false.
      call bodies_of(slave, bs, ls, ns)
      call bodies_of(master, bm, lm, nm)
      do j = 1, nm
         do i = 1, ns
            if (ls(i) /= lm(j)) self%pairs(ls(i), lm(j)) = .true.
         end do
      end do
   contains
      subroutine bodies_of(nodes, seen, list, n)
         integer, intent(in) :: nodes(:)
         logical, intent(inout) :: seen(:)
         integer, intent(out) :: list(:), n
         integer :: k, b
         n = 0
         do k = 1, size(nodes)
            b = self%nb(nodes(k))
            if (b == 0) cycle
            if (seen(b)) cycle
            seen(b) = .true.
            n = n + 1
            list(n) = b
         end do
      end subroutine bodies_of
   end subroutine inside_allow

   !> Check the positions x(2, nnode) at time t. `last` gets the deepest node, `worst` the deepest
   !> over the run; a pair of bodies with a node deeper than `fraction` edges adds one warning to
   !> `warn` the first time (node, bodies, depth, time, how many nodes), later ones are counted.
   subroutine inside_check(self, x, t, warn)
      class(inside_t), intent(inout) :: self
      real(wp), intent(in) :: x(:, :)
      real(wp), intent(in) :: t
      character(len=:), allocatable, intent(out) :: warn
      integer :: n, a, c, k, e, b, ncount(self%nbody, self%nbody), pb(self%nbody)
      integer :: ib, jb, np
      real(wp) :: d, rel, t0, q(2, 4)
      type(inside_hit_t) :: first(self%nbody, self%nbody)

      warn = ''
      self%last = inside_hit_t(t=t)
      self%nover = 0
      if (.not. (self%active .and. any(self%pairs))) return
      t0 = wall_time()
      self%nchecks = self%nchecks + 1
      call build_grids(self, x)
      ncount = 0
      do n = 1, self%nnode
         a = self%nb(n)
         if (a == 0) cycle
         if (.not. any(self%pairs(a, :))) cycle
         c = cell_of(self, x(:, n))
         np = 0
         do k = self%ehead(c), self%ehead(c + 1) - 1
            e = self%eitem(k)
            b = self%eb(e)
            ! elements of other bodies the contact covers, and of the node's own body (which it
            ! can be inside only when the body has passed through itself)
            if (b /= a .and. .not. self%pairs(a, b)) cycle
            if (any(pb(1:np) == b)) cycle
            associate (box => self%ebox(:, e))
               if (x(1, n) < box(1) .or. x(1, n) > box(3) .or. x(2, n) < box(2) .or. x(2, n) > box(4)) cycle
            end associate
            if (any(self%conn(:, e) == n)) cycle
            q(:, 1) = x(:, self%conn(1, e))
            q(:, 2) = x(:, self%conn(2, e))
            q(:, 3) = x(:, self%conn(3, e))
            q(:, 4) = x(:, self%conn(4, e))
            if (.not. point_in_quad(x(:, n), q)) cycle
            np = np + 1
            pb(np) = b
            if (b == a) then
               call side_depth(x(:, n), q, d, rel)
            else
               call boundary_depth(self, x, x(:, n), b, d, rel)
            end if
            if (rel > self%last%edges) self%last = inside_hit_t(d, rel, n, self%ids(a), self%ids(b), t)
            if (rel > self%fraction) then
               self%nover = self%nover + 1
               ncount(a, b) = ncount(a, b) + 1
               if (rel > first(a, b)%edges .or. ncount(a, b) == 1) &
                  first(a, b) = inside_hit_t(d, rel, n, self%ids(a), self%ids(b), t)
            end if
         end do
      end do
      if (self%last%edges > self%worst%edges) self%worst = self%last
      do jb = 1, self%nbody
         do ib = 1, self%nbody
            if (ncount(ib, jb) == 0) cycle
            if (self%over_checks(ib, jb) == 0) then
               if (len(warn) > 0) warn = warn//new_line('a')
               warn = warn//'warning: at t = '//rtoa(t)//' '//itoa(ncount(ib, jb))//' node(s) of region '// &
                      itoa(self%ids(ib))//' are inside '//inside_what(ib, jb)//' deeper than '// &
                      rtoa(self%fraction)//' element edges; deepest: node '//itoa(first(ib, jb)%node)// &
                      ', '//rtoa(first(ib, jb)%edges)//' edges ('//rtoa(first(ib, jb)%depth)// &
                      ') (geometric penetration check; later times are counted in <stem>.out)'
            end if
            self%over_checks(ib, jb) = self%over_checks(ib, jb) + 1
            self%over_max(ib, jb) = max(self%over_max(ib, jb), ncount(ib, jb))
         end do
      end do
      self%time_total = self%time_total + (wall_time() - t0)
   contains
      !> What the nodes of body ib are inside: body jb, or ib's own elements.
      function inside_what(ib, jb) result(what)
         integer, intent(in) :: ib, jb
         character(len=:), allocatable :: what
         if (ib == jb) then
            what = 'other elements of region '//itoa(self%ids(ib))//' (the body has passed through '// &
                   'itself; contact within one body is PAIR,id,SELF,s)'
         else
            what = 'region '//itoa(self%ids(jb))
         end if
      end function inside_what
   end subroutine inside_check

   !> Lines for <stem>.out: the deepest node over the run, the pairs of bodies past the warning
   !> limit, and the cost of the checks.
   function inside_report(self) result(text)
      class(inside_t), intent(in) :: self
      character(len=:), allocatable :: text
      integer :: ib, jb
      text = 'geometric penetration check: '//itoa(self%nchecks)//' checks, '// &
             rtoa(self%time_total/max(self%nchecks, 1))//' s each; warning limit '//rtoa(self%fraction)// &
             ' element edges'
      if (self%worst%node > 0) then
         text = text//new_line('a')//'geometric penetration check: deepest node '//itoa(self%worst%node)// &
                ' of region '//itoa(self%worst%of_body)//', '//rtoa(self%worst%edges)//' edges ('// &
                rtoa(self%worst%depth)//') inside region '//itoa(self%worst%in_body)//' at t = '// &
                rtoa(self%worst%t)
      end if
      do jb = 1, self%nbody
         do ib = 1, self%nbody
            if (self%over_checks(ib, jb) == 0) cycle
            if (ib == jb) then
               text = text//new_line('a')//'geometric penetration check: region '//itoa(self%ids(ib))// &
                      ' through itself'
            else
               text = text//new_line('a')//'geometric penetration check: region '//itoa(self%ids(ib))// &
                      ' inside region '//itoa(self%ids(jb))
            end if
            text = text//' past the limit at '//itoa(self%over_checks(ib, jb))// &
                   ' of the checks, at most '//itoa(self%over_max(ib, jb))//' nodes'
         end do
      end do
   end function inside_report

   !> Grid over the box of the used nodes: cell = mean element box extent, at most ~4 nelem
   !> cells; elements binned by the cells their boxes touch (the boxes kept in ebox for the
   !> node tests), boundary edges likewise.
   subroutine build_grids(self, x)
      type(inside_t), intent(inout) :: self
      real(wp), intent(in) :: x(:, :)
      real(wp) :: hi(2), ext, bl(2), bh(2)
      integer :: e, ncell, pass, ne
      integer, allocatable :: fill(:)

      self%lo = huge(1.0_wp)
      hi = -huge(1.0_wp)
      ext = 0.0_wp
      if (allocated(self%ebox)) then
         if (size(self%ebox, 2) /= self%nelem) deallocate (self%ebox)
      end if
      if (.not. allocated(self%ebox)) allocate (self%ebox(4, self%nelem))
      do e = 1, self%nelem
         associate (c => self%conn(:, e))
            bl(1) = min(x(1, c(1)), x(1, c(2)), x(1, c(3)), x(1, c(4)))
            bl(2) = min(x(2, c(1)), x(2, c(2)), x(2, c(3)), x(2, c(4)))
            bh(1) = max(x(1, c(1)), x(1, c(2)), x(1, c(3)), x(1, c(4)))
            bh(2) = max(x(2, c(1)), x(2, c(2)), x(2, c(3)), x(2, c(4)))
         end associate
         self%ebox(1:2, e) = bl
         self%ebox(3:4, e) = bh
         self%lo = min(self%lo, bl)
         hi = max(hi, bh)
         ext = ext + max(bh(1) - bl(1), bh(2) - bl(2))
      end do
      self%h = max(ext/self%nelem, tiny(1.0_wp))
      ! at most about 4 nelem cells
      self%h = max(self%h, sqrt((hi(1) - self%lo(1))*(hi(2) - self%lo(2))/(4.0_wp*self%nelem)))
      self%nx = max(1, min(int((hi(1) - self%lo(1))/self%h) + 1, 4*self%nelem))
      self%ny = max(1, min(int((hi(2) - self%lo(2))/self%h) + 1, 4*self%nelem))
      ncell = self%nx*self%ny
      ! elements, then edges: count, prefix sums, fill (two passes over the same loop)
      ne = size(self%edge, 2)
      if (allocated(self%ehead)) deallocate (self%ehead)
      if (allocated(self%ghead)) deallocate (self%ghead)
      allocate (self%ehead(ncell + 1), self%ghead(ncell + 1), source=0)
      if (.not. allocated(self%eitem)) allocate (self%eitem(0))
      if (.not. allocated(self%gitem)) allocate (self%gitem(0))
      do pass = 1, 2
         if (pass == 2) then
            call prefix(self%ehead)
            call prefix(self%ghead)
            if (allocated(self%eitem)) deallocate (self%eitem)
            if (allocated(self%gitem)) deallocate (self%gitem)
            allocate (self%eitem(self%ehead(ncell + 1) - 1), self%gitem(self%ghead(ncell + 1) - 1))
            fill = self%ehead(1:ncell)
         end if
         do e = 1, self%nelem
            call bin(self%ebox(1:2, e), self%ebox(3:4, e), e, self%ehead, self%eitem)
         end do
         if (pass == 2) fill = self%ghead(1:ncell)
         do e = 1, ne
            call bin(min(x(:, self%edge(1, e)), x(:, self%edge(2, e))), &
                     max(x(:, self%edge(1, e)), x(:, self%edge(2, e))), e, self%ghead, self%gitem)
         end do
      end do
   contains
      !> Pass 1: count item e in every cell its box bl-bh touches; pass 2: store it there.
      subroutine bin(bl, bh, e, head, items)
         real(wp), intent(in) :: bl(2), bh(2)
         integer, intent(in) :: e
         integer, intent(inout) :: head(:)
         integer, intent(inout) :: items(:)
         integer :: i0, i1, j0, j1, i, j, c
         call cell_range(self, bl, bh, i0, i1, j0, j1)
         do j = j0, j1
            do i = i0, i1
               c = i + (j - 1)*self%nx
               if (pass == 1) then
                  head(c + 1) = head(c + 1) + 1
               else
                  items(fill(c)) = e
                  fill(c) = fill(c) + 1
               end if
            end do
         end do
      end subroutine bin
      subroutine prefix(head)
         integer, intent(inout) :: head(:)
         integer :: k
         head(1) = 1
         do k = 2, size(head)
            head(k) = head(k) + head(k - 1)
         end do
      end subroutine prefix
   end subroutine build_grids

   !> Cell indices (clamped to the grid) of the box bl-bh.
   pure subroutine cell_range(self, bl, bh, i0, i1, j0, j1)
      type(inside_t), intent(in) :: self
      real(wp), intent(in) :: bl(2), bh(2)
      integer, intent(out) :: i0, i1, j0, j1
      i0 = cell_index((bl(1) - self%lo(1))/self%h, self%nx)
      i1 = cell_index((bh(1) - self%lo(1))/self%h, self%nx)
      j0 = cell_index((bl(2) - self%lo(2))/self%h, self%ny)
      j1 = cell_index((bh(2) - self%lo(2))/self%h, self%ny)
   end subroutine cell_range

   !> 1-based cell of coordinate s (in cells from the grid origin), clamped to 1..n.
   pure integer function cell_index(s, n) result(i)
      real(wp), intent(in) :: s
      integer, intent(in) :: n
      if (.not. (s < real(n, wp))) then
         i = n
      else if (s < 1.0_wp) then
         i = 1
      else
         i = int(s) + 1
      end if
   end function cell_index

   !> Linear cell number of point p.
   pure integer function cell_of(self, p) result(c)
      type(inside_t), intent(in) :: self
      real(wp), intent(in) :: p(2)
      c = cell_index((p(1) - self%lo(1))/self%h, self%nx) + &
          (cell_index((p(2) - self%lo(2))/self%h, self%ny) - 1)*self%nx
   end function cell_of

   !> Distance d from p to the free boundary of body b and d over the nearest edge's length: ring
   !> search over the edge grid, stopped when the rings left are farther than the best found.
   subroutine boundary_depth(self, x, p, b, d, rel)
      type(inside_t), intent(in) :: self
      real(wp), intent(in) :: x(:, :), p(2)
      integer, intent(in) :: b
      real(wp), intent(out) :: d, rel
      integer :: ci, cj, r, i, j, k, g
      real(wp) :: best, blen, dist, len
      ci = cell_index((p(1) - self%lo(1))/self%h, self%nx)
      cj = cell_index((p(2) - self%lo(2))/self%h, self%ny)
      best = huge(1.0_wp)
      blen = huge(1.0_wp)
      do r = 0, max(self%nx, self%ny)
         do j = max(cj - r, 1), min(cj + r, self%ny)
            do i = max(ci - r, 1), min(ci + r, self%nx)
               if (max(abs(i - ci), abs(j - cj)) /= r) cycle
               do k = self%ghead(i + (j - 1)*self%nx), self%ghead(i + (j - 1)*self%nx + 1) - 1
                  g = self%gitem(k)
                  if (self%edge_body(g) /= b) cycle
                  call segment_distance(p, x(:, self%edge(1, g)), x(:, self%edge(2, g)), dist, len)
                  if (dist < best .or. (dist == best .and. len < blen)) then
                     best = dist
                     blen = len
                  end if
               end do
            end do
         end do
         if (best <= r*self%h) exit
      end do
      d = best
      if (best == huge(1.0_wp)) d = 0.0_wp
      rel = 0.0_wp
      if (best < huge(1.0_wp)) rel = d/max(blen, tiny(1.0_wp))
   end subroutine boundary_depth

   !> Depth of p inside the quadrilateral q(2, 4) of its own body: the distance to the nearest of
   !> q's sides and, in lengths of that side, rel. A conforming mesh has no node inside an
   !> element that does not have it as a corner; a node on a side (a tied seam) has depth 0.
   pure subroutine side_depth(p, q, d, rel)
      real(wp), intent(in) :: p(2), q(2, 4)
      real(wp), intent(out) :: d, rel
      real(wp) :: dist, len, blen
      integer :: k
      d = huge(1.0_wp)
      blen = huge(1.0_wp)
      do k = 1, 4
         call segment_distance(p, q(:, k), q(:, mod(k, 4) + 1), dist, len)
         if (dist < d .or. (dist == d .and. len < blen)) then
            d = dist
            blen = len
         end if
      end do
      rel = d/max(blen, tiny(1.0_wp))
   end subroutine side_depth

   !> Distance from p to the segment a-b, and the segment's length. Nearest at an end, the
   !> distance is that to the end itself, so that the two edges of a vertex tie exactly (the
   !> caller then takes the shorter edge: a node's depth in edges does not depend on the order).
   pure subroutine segment_distance(p, a, b, dist, len)
      real(wp), intent(in) :: p(2), a(2), b(2)
      real(wp), intent(out) :: dist, len
      real(wp) :: ab(2), s, l2
      ab = b - a
      l2 = dot_product(ab, ab)
      len = sqrt(l2)
      s = 0.0_wp
      if (l2 > 0.0_wp) s = dot_product(p - a, ab)/l2
      if (s <= 0.0_wp) then
         dist = norm2(p - a)
      else if (s >= 1.0_wp) then
         dist = norm2(p - b)
      else
         dist = norm2(p - a - s*ab)
      end if
   end subroutine segment_distance

   !> Is p strictly inside the quadrilateral q(2, 4) (any shape, even folded: crossing number)?
   pure logical function point_in_quad(p, q) result(inside)
      real(wp), intent(in) :: p(2), q(2, 4)
      integer :: k, l
      inside = .false.
      do k = 1, 4
         l = mod(k, 4) + 1
         if ((q(2, k) > p(2)) .neqv. (q(2, l) > p(2))) then
            if (p(1) < q(1, k) + (p(2) - q(2, k))*(q(1, l) - q(1, k))/(q(2, l) - q(2, k))) &
               inside = .not. inside
         end if
      end do
   end function point_in_quad

end module exic_contact_inside
