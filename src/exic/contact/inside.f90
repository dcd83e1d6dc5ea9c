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
!> With `all_pairs` (every run with two bodies or more, src/exic/session/run.f90) the bodies that no
!> contact pass couples are checked too: a node of one inside the other is reported once per pair
!> ("regions i and j interpenetrate at t = ...; no contact pair couples them"); such hits do not
!> enter the deepest node of the contact's report (`last`, `worst`).
!>
!> Which pairs of bodies are checked is kept per body (the AUTOmatic set) plus a sorted list of
!> the pairs PAIR passes name, and the pairs past the limit in a sorted list: memory and set-up
!> O(nbody + listed pairs), never nbody^2 (a scene of 4096 bodies needed 1 GB and 9 s before).
!>
!> Cost per check O(nnode + nelem): a uniform grid over the bounding box of the mesh (cell = the
!> mean element extent, at most about 4 nelem cells) holds the elements by the cells their boxes
!> touch; each node tests the elements of its own cell (box test, then the crossing-number test
!> on the quadrilateral). Only nodes found inside compute a depth, by a ring search over a second
!> grid holding B's boundary edges, binned at the first such node of a check. Plain arrays in:
!> positions, connectivity, body per element.
module exic_contact_inside
   use exic_base_kinds, only: wp, i8
   use exic_base_grow, only: grow
   use exic_base_sort, only: sort_perm_i8, search_sorted
   use exic_base_error, only: error_t
   use exic_base_strings, only: itoa, rtoa
   use exic_base_clock, only: wall_time
   use exic_mesh_boundary, only: free_edges_of, bodies_elements
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
      ! the pairs (i, j) whose nodes of i are checked against elements of j (see `checked`):
      logical, allocatable :: in_auto(:)        !< (nbody) the body has nodes on an AUTOmatic surface
      integer, allocatable :: only(:)           !< (nbody) that surface if it is one only, else 0
      integer :: nauto = 0                      !< AUTOmatic surfaces given to allow_auto
      integer :: nlisted = 0                    !< pairs named by allow (PAIR passes)
      integer, allocatable :: listed(:, :)      !< (2, nlisted) those pairs (i, j), i /= j
      integer(i8), allocatable :: lkey(:)       !< their keys, sorted and unique (after settle)
      logical :: settled = .false.              !< lkey and tested are up to date
      logical, allocatable :: tested(:)         !< (nbody) some pair (i, :) is checked
      logical, allocatable :: seen(:)           !< (nbody) work space of allow, all .false. between calls
      integer, allocatable :: edge(:, :)        !< (2, nedge) free boundary edges of all bodies
      integer, allocatable :: edge_body(:)      !< (nedge) body index of each edge
      real(wp) :: fraction = 1.0e-3_wp          !< warning limit, in edge lengths
      !> every two bodies are checked: those no pass couples (neither (i, j) nor (j, i) checked)
      !> warn once per pair, as "regions i and j interpenetrate ...; no contact pair couples them"
      logical :: all_pairs = .false.
      !> results
      type(inside_hit_t) :: last                !< deepest of the last check
      type(inside_hit_t) :: worst               !< deepest over the run
      integer :: nover = 0                      !< nodes past `fraction` in the last check
      integer :: npast = 0                      !< pairs that have had nodes past it
      integer(i8), allocatable :: past_key(:)   !< (npast) their keys (pair_key), ascending
      integer, allocatable :: past_checks(:)    !< (npast) checks in which the pair had nodes past it
      integer, allocatable :: past_max(:)       !< (npast) most such nodes in one check
      integer :: nchecks = 0
      real(wp) :: time_total = 0.0_wp           !< wall time of all checks
      ! work space of the grids
      integer, private :: nx = 0, ny = 0
      real(wp), private :: lo(2) = 0.0_wp, h = 1.0_wp
      integer, allocatable, private :: ehead(:), eitem(:), ghead(:), gitem(:)
      logical, private :: edges_binned = .false.   !< ghead, gitem hold this check's edge grid
      real(wp), allocatable, private :: ebox(:, :)   !< (4, nelem) element boxes: x, y low, x, y high
   contains
      procedure :: init => inside_init
      procedure :: allow => inside_allow
      procedure :: allow_auto => inside_allow_auto
      procedure :: check => inside_check
      procedure :: report => inside_report
      procedure :: uncoupled => inside_uncoupled
   end type inside_t

contains

   !> Bodies from `body(nelem)` (region numbers); no pair is checked until `allow` names it.
   subroutine inside_init(self, nnode, nelem, conn, body, fraction, err)
      class(inside_t), intent(inout) :: self
      integer, intent(in) :: nnode, nelem
      integer, intent(in) :: conn(4, nelem), body(nelem)
      real(wp), intent(in) :: fraction
      type(error_t), allocatable, intent(out) :: err
      integer :: e, k, j, ne
      integer, allocatable :: first(:), elems(:), seg(:, :)
      logical, allocatable :: on_boundary(:)

      select type (self)
      type is (inside_t)
         self = inside_t()          ! a second init starts afresh
      end select
      if (nelem == 0) return
      self%nnode = nnode
      self%nelem = nelem
      self%conn = conn
      self%fraction = fraction
      ! the bodies in ascending order of their numbers and the elements of each
      call bodies_elements(nelem, body, self%ids, first, elems)
      self%nbody = size(self%ids)
      allocate (self%eb(nelem))
      do k = 1, self%nbody
         self%eb(elems(first(k):first(k + 1) - 1)) = k
      end do
      allocate (self%nb(nnode), source=0)
      do e = 1, nelem
         do j = 1, 4
            if (self%nb(conn(j, e)) == 0) self%nb(conn(j, e)) = self%eb(e)
         end do
      end do
      allocate (self%in_auto(self%nbody), self%tested(self%nbody), self%seen(self%nbody), source=.false.)
      allocate (self%only(self%nbody), source=0)
      allocate (self%listed(2, 0), self%lkey(0), self%past_key(0), self%past_checks(0), self%past_max(0))
      ! the free boundary edges of each body, body after body
      allocate (self%edge(2, 0), self%edge_body(0))
      ne = 0
      do k = 1, self%nbody
         call free_edges_of(nelem, conn, elems(first(k):first(k + 1) - 1), seg, err)
         if (allocated(err)) return
         call grow(self%edge, ne + size(seg, 2), 2)
         call grow(self%edge_body, ne + size(seg, 2))
         self%edge(:, ne + 1:ne + size(seg, 2)) = seg
         self%edge_body(ne + 1:ne + size(seg, 2)) = k
         ne = ne + size(seg, 2)
      end do
      self%edge = self%edge(:, 1:ne)
      self%edge_body = self%edge_body(1:ne)
      ! only nodes of a free boundary are tested: a body enters another through its boundary
      allocate (on_boundary(nnode), source=.false.)
      on_boundary(self%edge(1, :)) = .true.
      on_boundary(self%edge(2, :)) = .true.
      where (.not. on_boundary) self%nb = 0
      self%settled = .true.
      self%active = .true.
   end subroutine inside_init

   !> Check the nodes of `slave(:)`'s bodies against the elements of `master(:)`'s bodies (the
   !> nodes of a contact pass's two surfaces); nodes of the same body are never checked. A call
   !> costs its node lists and the pairs it names.
   subroutine inside_allow(self, slave, master)
      class(inside_t), intent(inout) :: self
      integer, intent(in) :: slave(:), master(:)
      integer, allocatable :: ls(:), lm(:)
      integer :: i, j
      if (.not. self%active) return
      call bodies_of(self, slave, ls)
      call bodies_of(self, master, lm)
      do j = 1, size(lm)
         do i = 1, size(ls)
            if (ls(i) == lm(j)) cycle
            self%nlisted = self%nlisted + 1
            call grow(self%listed, self%nlisted, 2)
            self%listed(:, self%nlisted) = [ls(i), lm(j)]
         end do
      end do
      self%settled = .false.
   end subroutine inside_allow

   !> The nodes of one AUTOmatic surface, one call per surface: every pair of distinct bodies
   !> with nodes on two different AUTOmatic surfaces is checked (what `allow` on every ordered
   !> pair of the surfaces would name), kept per body: in_auto, and the surface when it is the
   !> body's only one. O(size(nodes)) a call, nothing per pair of surfaces.
   subroutine inside_allow_auto(self, nodes)
      class(inside_t), intent(inout) :: self
      integer, intent(in) :: nodes(:)
      integer, allocatable :: lb(:)
      integer :: i, b
      if (.not. self%active) return
      self%nauto = self%nauto + 1
      call bodies_of(self, nodes, lb)
      do i = 1, size(lb)
         b = lb(i)
         if (.not. self%in_auto(b)) then
            self%in_auto(b) = .true.
            self%only(b) = self%nauto
         else if (self%only(b) /= self%nauto) then
            self%only(b) = 0
         end if
      end do
      self%settled = .false.
   end subroutine inside_allow_auto

   !> The distinct bodies (body indices) of the tested nodes among `nodes`, in order of first
   !> appearance.
   subroutine bodies_of(self, nodes, list)
      type(inside_t), intent(inout) :: self
      integer, intent(in) :: nodes(:)
      integer, allocatable, intent(out) :: list(:)
      integer :: k, b, n
      allocate (list(min(size(nodes), self%nbody)))
      n = 0
      do k = 1, size(nodes)
         b = self%nb(nodes(k))
         if (b == 0) cycle
         if (self%seen(b)) cycle
         self%seen(b) = .true.
         n = n + 1
         list(n) = b
      end do
      list = list(1:n)
      self%seen(list) = .false.
   end subroutine bodies_of

   !> Key of the ordered pair (nodes of body i, elements of body j); ascending keys run j, then i.
   pure integer(i8) function pair_key(nbody, i, j) result(key)
      integer, intent(in) :: nbody, i, j
      key = int(j - 1, i8)*int(nbody, i8) + int(i, i8)
   end function pair_key

   !> After allow and allow_auto: the listed pairs sorted and unique, and `tested`.
   subroutine settle(self)
      type(inside_t), intent(inout) :: self
      integer(i8), allocatable :: key(:)
      integer, allocatable :: perm(:), nonly(:)
      integer :: k, n, nin
      if (allocated(self%lkey)) deallocate (self%lkey)
      allocate (key(self%nlisted), perm(self%nlisted))
      do k = 1, self%nlisted
         key(k) = pair_key(self%nbody, self%listed(1, k), self%listed(2, k))
      end do
      call sort_perm_i8(self%nlisted, key, perm)
      allocate (self%lkey(self%nlisted))
      n = 0
      do k = 1, self%nlisted
         if (n > 0) then
            if (key(perm(k)) == self%lkey(n)) cycle
         end if
         n = n + 1
         self%lkey(n) = key(perm(k))
      end do
      self%lkey = self%lkey(1:n)
      ! tested(i): a listed pair (i, :), or an AUTOmatic partner: any other body of the set when
      ! i has nodes on several surfaces, else one that is not on i's surface alone
      self%tested = .false.
      do k = 1, self%nlisted
         self%tested(self%listed(1, k)) = .true.
      end do
      nin = count(self%in_auto)
      allocate (nonly(0:self%nauto), source=0)
      do k = 1, self%nbody
         if (self%in_auto(k)) nonly(self%only(k)) = nonly(self%only(k)) + 1
      end do
      do k = 1, self%nbody
         if (.not. self%in_auto(k)) cycle
         if (self%only(k) == 0) then
            if (nin >= 2) self%tested(k) = .true.
         else
            if (nin - nonly(self%only(k)) >= 1) self%tested(k) = .true.
         end if
      end do
      self%settled = .true.
   end subroutine settle

   !> True when nodes of body i are checked against the elements of body j /= i.
   pure logical function checked(self, i, j) result(yes)
      type(inside_t), intent(in) :: self
      integer, intent(in) :: i, j
      yes = .false.
      if (i == j) return
      if (self%in_auto(i) .and. self%in_auto(j)) then
         yes = self%only(i) == 0 .or. self%only(i) /= self%only(j)
         if (yes) return
      end if
      yes = search_sorted(self%lkey, pair_key(self%nbody, i, j)) > 0
   end function checked

   !> True when two bodies exist that no contact pass couples (checked only with all_pairs); with
   !> more than UNCOUPLED_SCAN bodies assumed without looking (the scan is O(nbody^2)).
   logical function inside_uncoupled(self) result(yes)
      class(inside_t), intent(inout) :: self
      integer, parameter :: UNCOUPLED_SCAN = 512
      integer :: i, j
      yes = .false.
      if (.not. (self%active .and. self%all_pairs) .or. self%nbody < 2) return
      yes = .true.
      if (self%nbody > UNCOUPLED_SCAN) return
      if (.not. self%settled) call settle(self)
      do j = 2, self%nbody
         do i = 1, j - 1
            if (.not. (checked(self, i, j) .or. checked(self, j, i))) return
         end do
      end do
      yes = .false.
   end function inside_uncoupled

   !> Check the positions x(2, nnode) at time t. `last` gets the deepest node, `worst` the deepest
   !> over the run; a pair of bodies with a node deeper than `fraction` edges adds one warning to
   !> `warn` the first time (node, bodies, depth, time, how many nodes), later ones are counted.
   subroutine inside_check(self, x, t, warn)
      class(inside_t), intent(inout) :: self
      real(wp), intent(in), contiguous :: x(:, :)
      real(wp), intent(in) :: t
      character(len=:), allocatable, intent(out) :: warn
      integer :: n, a, c, k, e, b, pb(self%nbody), np
      real(wp) :: d, rel, t0, q(2, 4)
      logical :: free
      ! the nodes past the limit of this check: their pair's key and their hit, in node order
      integer(i8), allocatable :: hkey(:)
      type(inside_hit_t), allocatable :: hit(:)

      warn = ''
      self%last = inside_hit_t(t=t)
      self%nover = 0
      if (.not. self%active) return
      if (.not. self%settled) call settle(self)
      if (.not. (any(self%tested) .or. (self%all_pairs .and. self%nbody > 1))) return
      t0 = wall_time()
      self%nchecks = self%nchecks + 1
      call build_grids(self, x)
      allocate (hkey(16), hit(16))
      do n = 1, self%nnode
         a = self%nb(n)
         if (a == 0) cycle
         if (.not. (self%tested(a) .or. self%all_pairs)) cycle
         c = cell_of(self, x(:, n))
         np = 0
         do k = self%ehead(c), self%ehead(c + 1) - 1
            e = self%eitem(k)
            b = self%eb(e)
            ! elements of other bodies the contact covers, and of the node's own body (which it
            ! can be inside only when the body has passed through itself); with all_pairs, of
            ! bodies no contact pass couples with it (`free`)
            free = .false.
            if (b /= a) then
               if (.not. checked(self, a, b)) then
                  if (.not. self%all_pairs) cycle
                  if (checked(self, b, a)) cycle
                  free = .true.
               end if
            else if (.not. self%tested(a)) then
               cycle
            end if
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
               if (.not. self%edges_binned) call bin_edges(self, x)
               call boundary_depth(self, x, x(:, n), b, d, rel)
            end if
            if (rel > self%last%edges .and. .not. free) self%last = inside_hit_t(d, rel, n, self%ids(a), self%ids(b), t)
            if (rel > self%fraction) then
               self%nover = self%nover + 1
               if (self%nover > size(hkey)) then
                  hkey = [hkey, hkey]
                  hit = [hit, hit]
               end if
               ! a pair no pass couples: one key for both directions (min, max), marked negative
               hkey(self%nover) = pair_key(self%nbody, a, b)
               if (free) hkey(self%nover) = -pair_key(self%nbody, min(a, b), max(a, b))
               hit(self%nover) = inside_hit_t(d, rel, n, self%ids(a), self%ids(b), t)
            end if
         end do
      end do
      if (self%last%edges > self%worst%edges) self%worst = self%last
      if (self%nover > 0) call book_past(self, self%nover, hkey, hit, t, warn)
      self%time_total = self%time_total + (wall_time() - t0)
   end subroutine inside_check

   !> The nodes past the limit of one check (pair keys hkey, hits hit, in node order) booked per
   !> pair in ascending key order: the count of the pair's checks and its most nodes, and for a
   !> pair past the limit for the first time a warning naming its deepest node (the first of the
   !> deepest in node order).
   subroutine book_past(self, nh, hkey, hit, t, warn)
      type(inside_t), intent(inout) :: self
      integer, intent(in) :: nh
      integer(i8), intent(in) :: hkey(:)
      type(inside_hit_t), intent(in) :: hit(:)
      real(wp), intent(in) :: t
      character(len=:), allocatable, intent(inout) :: warn
      integer :: perm(nh), p, q, k, count, ib, jb, at
      type(inside_hit_t) :: deep
      call sort_perm_i8(nh, hkey(1:nh), perm)
      p = 1
      do while (p <= nh)
         q = p
         do while (q < nh)
            if (hkey(perm(q + 1)) /= hkey(perm(p))) exit
            q = q + 1
         end do
         count = q - p + 1
         deep = hit(perm(p))
         do k = p + 1, q
            if (hit(perm(k))%edges > deep%edges) deep = hit(perm(k))
         end do
         ! the pair's place in the sorted list of pairs past the limit
         at = search_sorted(self%past_key(1:self%npast), hkey(perm(p)))
         if (at < 0) then
            at = -at
            self%npast = self%npast + 1
            self%past_key = [self%past_key(1:at - 1), hkey(perm(p)), self%past_key(at:self%npast - 1)]
            self%past_checks = [self%past_checks(1:at - 1), 0, self%past_checks(at:self%npast - 1)]
            self%past_max = [self%past_max(1:at - 1), 0, self%past_max(at:self%npast - 1)]
            ib = int(mod(abs(hkey(perm(p))) - 1, int(self%nbody, i8))) + 1
            jb = int((abs(hkey(perm(p))) - 1)/int(self%nbody, i8)) + 1
            if (len(warn) > 0) warn = warn//new_line('a')
            if (hkey(perm(p)) < 0) then
               warn = warn//'warning: regions '//itoa(self%ids(ib))//' and '//itoa(self%ids(jb))// &
                      ' interpenetrate at t = '//rtoa(t)//'; no contact pair couples them (node '// &
                      itoa(deep%node)//' of region '//itoa(deep%of_body)//' is inside region '// &
                      itoa(deep%in_body)//' by '//rtoa(deep%depth)//', '//rtoa(deep%edges)// &
                      ' element edges; geometric penetration check, later times are counted in <stem>.out)'
            else
               warn = warn//'warning: at t = '//rtoa(t)//' '//itoa(count)//' node(s) of region '// &
                      itoa(self%ids(ib))//' are inside '//inside_what(self, ib, jb)//' deeper than '// &
                      rtoa(self%fraction)//' element edges; deepest: node '//itoa(deep%node)// &
                      ', '//rtoa(deep%edges)//' edges ('//rtoa(deep%depth)// &
                      ') (geometric penetration check; later times are counted in <stem>.out)'
            end if
         end if
         self%past_checks(at) = self%past_checks(at) + 1
         self%past_max(at) = max(self%past_max(at), count)
         p = q + 1
      end do
   end subroutine book_past

   !> What the nodes of body ib are inside: body jb, or ib's own elements.
   function inside_what(self, ib, jb) result(what)
      type(inside_t), intent(in) :: self
      integer, intent(in) :: ib, jb
      character(len=:), allocatable :: what
      if (ib == jb) then
         what = 'other elements of region '//itoa(self%ids(ib))//' (the body has passed through '// &
                'itself; contact within one body is PAIR,id,SELF,s)'
      else
         what = 'region '//itoa(self%ids(jb))
      end if
   end function inside_what

   !> Lines for <stem>.out: the deepest node over the run, the pairs of bodies past the warning
   !> limit, and the cost of the checks.
   function inside_report(self) result(text)
      class(inside_t), intent(in) :: self
      character(len=:), allocatable :: text
      integer :: ib, jb, k
      text = 'geometric penetration check: '//itoa(self%nchecks)//' checks, '// &
             rtoa(self%time_total/max(self%nchecks, 1))//' s each; warning limit '//rtoa(self%fraction)// &
             ' element edges'
      if (self%worst%node > 0) then
         text = text//new_line('a')//'geometric penetration check: deepest node '//itoa(self%worst%node)// &
                ' of region '//itoa(self%worst%of_body)//', '//rtoa(self%worst%edges)//' edges ('// &
                rtoa(self%worst%depth)//') inside region '//itoa(self%worst%in_body)//' at t = '// &
                rtoa(self%worst%t)
      end if
      do k = 1, self%npast
         ib = int(mod(abs(self%past_key(k)) - 1, int(self%nbody, i8))) + 1
         jb = int((abs(self%past_key(k)) - 1)/int(self%nbody, i8)) + 1
         if (self%past_key(k) < 0) then
            text = text//new_line('a')//'geometric penetration check: regions '//itoa(self%ids(ib))// &
                   ' and '//itoa(self%ids(jb))//' interpenetrate (no contact pair couples them)'
         else if (ib == jb) then
            text = text//new_line('a')//'geometric penetration check: region '//itoa(self%ids(ib))// &
                   ' through itself'
         else
            text = text//new_line('a')//'geometric penetration check: region '//itoa(self%ids(ib))// &
                   ' inside region '//itoa(self%ids(jb))
         end if
         text = text//' past the limit at '//itoa(self%past_checks(k))// &
                ' of the checks, at most '//itoa(self%past_max(k))//' nodes'
      end do
   end function inside_report

   !> Grid over the box of the used nodes: cell = mean element box extent, at most ~4 nelem
   !> cells; elements binned by the cells their boxes touch (the boxes kept in ebox for the
   !> node tests). The boundary edges are binned on the same grid by bin_edges, when a node
   !> inside another body first needs its depth (most checks find none).
   subroutine build_grids(self, x)
      type(inside_t), intent(inout) :: self
      real(wp), intent(in), contiguous :: x(:, :)
      real(wp) :: hi(2), ext, bl(2), bh(2)
      integer :: e
      integer, allocatable :: erng(:, :)

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
      ! the cells of every element's box once, then count, prefix sums, fill
      allocate (erng(4, self%nelem))
      do e = 1, self%nelem
         call cell_range(self, self%ebox(1:2, e), self%ebox(3:4, e), erng(1, e), erng(2, e), erng(3, e), erng(4, e))
      end do
      call bin_all(self%nx, self%nx*self%ny, erng, self%ehead, self%eitem)
      self%edges_binned = .false.
   end subroutine build_grids

   !> The boundary edges of this check's positions x binned on build_grids' grid (ghead, gitem).
   subroutine bin_edges(self, x)
      type(inside_t), intent(inout) :: self
      real(wp), intent(in), contiguous :: x(:, :)
      real(wp) :: bl(2), bh(2)
      integer :: e, ne
      integer, allocatable :: grng(:, :)
      ne = size(self%edge, 2)
      allocate (grng(4, ne))
      do e = 1, ne
         bl(1) = min(x(1, self%edge(1, e)), x(1, self%edge(2, e)))
         bl(2) = min(x(2, self%edge(1, e)), x(2, self%edge(2, e)))
         bh(1) = max(x(1, self%edge(1, e)), x(1, self%edge(2, e)))
         bh(2) = max(x(2, self%edge(1, e)), x(2, self%edge(2, e)))
         call cell_range(self, bl, bh, grng(1, e), grng(2, e), grng(3, e), grng(4, e))
      end do
      call bin_all(self%nx, self%nx*self%ny, grng, self%ghead, self%gitem)
      self%edges_binned = .true.
   end subroutine bin_edges

   !> head(1:ncell + 1) and items of a grid nx cells wide: item e in every cell of its range
   !> rng(:, e) (i0, i1, j0, j1), the items of a cell in increasing e.
   pure subroutine bin_all(nx, ncell, rng, head, items)
      integer, intent(in) :: nx, ncell, rng(:, :)
      integer, allocatable, intent(inout) :: head(:), items(:)
      integer, allocatable :: fill(:)
      integer :: e, i, j, c
      if (allocated(head)) deallocate (head)
      allocate (head(ncell + 1), source=0)
      do e = 1, size(rng, 2)
         do j = rng(3, e), rng(4, e)
            do i = rng(1, e), rng(2, e)
               c = i + (j - 1)*nx
               head(c + 1) = head(c + 1) + 1
            end do
         end do
      end do
      head(1) = 1
      do c = 2, ncell + 1
         head(c) = head(c) + head(c - 1)
      end do
      if (allocated(items)) deallocate (items)
      allocate (items(head(ncell + 1) - 1))
      fill = head(1:ncell)
      do e = 1, size(rng, 2)
         do j = rng(3, e), rng(4, e)
            do i = rng(1, e), rng(2, e)
               c = i + (j - 1)*nx
               items(fill(c)) = e
               fill(c) = fill(c) + 1
            end do
         end do
      end do
   end subroutine bin_all

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
      real(wp), intent(in), contiguous :: x(:, :)
      real(wp), intent(in) :: p(2)
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
