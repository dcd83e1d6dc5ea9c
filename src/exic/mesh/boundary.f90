!> Contact surfaces from a mesh: free boundary edges, slave node lists, segment
!> neighbours and normals.
!>
!> Conventions used by every contact kernel:
!> - a segment (edge) is a node pair (n1, n2) with the body on the LEFT of n1 -> n2
!>   (for counter-clockwise quadrilaterals this is the element's own edge order);
!> - its outward unit normal is N / |N| with N = (x2 - x1) x e3 = (t_y, -t_x) (seed eq. 6.2);
!> - a node normal is the normalized sum (hence average) of the unit normals of the
!>   segments meeting at the node.
!>
!> Set-up procedures (free_edges, order_chains, surface_nodes, segment_links, locate_nodes)
!> run once per surface; segment_normal, average_normal and node_normals are per-step
!> kernels and allocate nothing.
module exic_mesh_boundary
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_sort, only: sort_perm_i8, sort_perm_int
   implicit none
   private

   public :: free_edges, free_edges_of, bodies_elements, order_chains, surface_nodes, segment_links, locate_nodes
   public :: segment_normal, average_normal, node_normals, node_segments, some_node_normals, &
             node_normal_from, normal_dofs

contains

   !> Free edges of the selected elements: edges used by exactly one selected element.
   !>
   !> `edges(:, k)` is oriented with the body on its left and the list is ordered in chains
   !> that follow the boundary (see order_chains); chain c is edges(:, chain(c):chain(c+1)-1).
   !> `owner(k)` is the element that holds edge k. Degenerate edges (repeated node in a
   !> collapsed quadrilateral) are skipped. An edge shared by two selected elements in the
   !> same direction (inconsistent orientation) or by more than two elements is an error.
   !> Cost: O(nelem) for the selection, then that of free_edges_of.
   subroutine free_edges(nelem, conn, select, edges, err, chain, owner)
      integer, intent(in) :: nelem
      integer, intent(in) :: conn(4, nelem)
      logical, intent(in) :: select(nelem)
      integer, allocatable, intent(out) :: edges(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable, intent(out), optional :: chain(:)
      integer, allocatable, intent(out), optional :: owner(:)
      integer :: e
      call free_edges_of(nelem, conn, pack([(e, e=1, nelem)], select), edges, err, chain, owner)
   end subroutine free_edges

   !> free_edges of the elements elems(:) (element numbers into conn, ascending), with the same
   !> result as free_edges with those elements selected. Cost: O(m log m) for m = 4 size(elems),
   !> by sorting integer edge keys, whatever nelem and the node numbers: a mesh of many bodies
   !> forms the surface of each body from a list of its elements (bodies_elements).
   subroutine free_edges_of(nelem, conn, elems, edges, err, chain, owner)
      integer, intent(in) :: nelem
      integer, intent(in) :: conn(4, nelem)
      integer, intent(in) :: elems(:)
      integer, allocatable, intent(out) :: edges(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable, intent(out), optional :: chain(:)
      integer, allocatable, intent(out), optional :: owner(:)
      integer, allocatable :: ea(:), eb(:), eown(:), perm(:), fre(:, :), fown(:), ord(:), ch(:)
      integer(i8), allocatable :: key(:)
      integer :: e, i, j, a, b, m, nmax, p, q, nfree
      character(len=160) :: msg

      nmax = 0
      do i = 1, size(elems)
         e = elems(i)
         if (any(conn(:, e) < 1)) then
            write (msg, '(a,i0,a)') 'element ', e, ' has a node number below 1'
            call make_error(err, trim(msg))
            return
         end if
         nmax = max(nmax, maxval(conn(:, e)))
      end do
      m = 4*size(elems)
      allocate (ea(m), eb(m), eown(m), key(m))
      m = 0
      do i = 1, size(elems)
         e = elems(i)
         do j = 1, 4
            a = conn(j, e)
            b = conn(mod(j, 4) + 1, e)
            if (a == b) cycle
            m = m + 1
            ea(m) = a; eb(m) = b; eown(m) = e
            key(m) = int(min(a, b), i8)*int(nmax + 1, i8) + int(max(a, b), i8)
         end do
      end do
      allocate (perm(m), fre(2, m), fown(m))
      call sort_perm_i8(m, key(1:m), perm)
      nfree = 0
      p = 1
      do while (p <= m)
         q = p
         do while (q < m)
            if (key(perm(q + 1)) /= key(perm(p))) exit
            q = q + 1
         end do
         select case (q - p + 1)
         case (1)
            nfree = nfree + 1
            fre(:, nfree) = [ea(perm(p)), eb(perm(p))]
            fown(nfree) = eown(perm(p))
         case (2)
            if (ea(perm(p)) == ea(perm(q))) then
               write (msg, '(a,i0,a,i0,a,i0,a,i0,a)') 'edge ', ea(perm(p)), '-', eb(perm(p)), &
                  ' has the same direction in elements ', eown(perm(p)), ' and ', eown(perm(q)), &
                  ' (inconsistent element orientation)'
               call make_error(err, trim(msg))
               return
            end if
         case default
            write (msg, '(a,i0,a,i0,a,i0,a)') 'edge ', ea(perm(p)), '-', eb(perm(p)), &
               ' is shared by ', q - p + 1, ' selected elements'
            call make_error(err, trim(msg))
            return
         end select
         p = q + 1
      end do
      allocate (ord(nfree))
      call order_chains(nfree, fre(:, 1:nfree), ord, ch)
      allocate (edges(2, nfree))
      edges = fre(:, ord)
      if (present(owner)) owner = fown(ord)
      if (present(chain)) call move_alloc(ch, chain)
   end subroutine free_edges_of

   !> Order directed edges into chains that follow each other (edge k ends where k+1 starts).
   !>
   !> `edges(:, order(k))` is the k-th edge in chain order; chain c covers positions
   !> chain(c) .. chain(c+1)-1 (size(chain) = number of chains + 1). Open chains start at a
   !> node with more outgoing than incoming edges; closed loops start at the edge of lowest
   !> (start, end) node pair among those left. Where several edges leave a node, the one with
   !> the lowest end node is taken. The result depends on the edge set only.
   subroutine order_chains(nedge, edges, order, chain)
      integer, intent(in) :: nedge
      integer, intent(in) :: edges(2, nedge)
      integer, intent(out) :: order(nedge)
      integer, allocatable, intent(out) :: chain(:)
      integer, allocatable :: perm(:), first(:), nextpos(:), indeg(:), ptr(:), rk(:, :)
      logical, allocatable :: visited(:)
      integer(i8), allocatable :: key(:)
      integer :: nmax, k, p, v, nout, nchain, pass, cur

      ! the nodes ranked 1..nmax in ascending order: the walk below compares node numbers only,
      ! so it takes the same edges in the same order, with work arrays of the size of the edge
      ! set rather than of the largest node number (a mesh of many bodies orders each body's
      ! boundary on its own)
      call rank_nodes(nedge, edges, rk, nmax)
      allocate (key(nedge), perm(nedge), first(nmax + 1), indeg(nmax), visited(nedge))
      allocate (ptr(nedge + 1), nextpos(nmax + 1))
      do k = 1, nedge
         key(k) = int(rk(1, k), i8)*int(nmax + 1, i8) + int(rk(2, k), i8)
      end do
      call sort_perm_i8(nedge, key, perm)
      ! CSR of outgoing edges by start node, in sorted (start, end) order
      first = 0
      indeg = 0
      do k = 1, nedge
         first(rk(1, k)) = first(rk(1, k)) + 1
         indeg(rk(2, k)) = indeg(rk(2, k)) + 1
      end do
      p = 1
      do v = 1, nmax + 1
         k = first(v)
         first(v) = p
         p = p + k
      end do
      nextpos(:) = first
      visited = .false.
      nout = 0
      nchain = 0
      do pass = 1, 2
         do p = 1, nedge
            k = perm(p)
            if (visited(k)) cycle
            v = rk(1, k)
            if (pass == 1 .and. indeg(v) >= first(v + 1) - first(v)) cycle
            nchain = nchain + 1
            ptr(nchain) = nout + 1
            cur = k
            do
               visited(cur) = .true.
               nout = nout + 1
               order(nout) = cur
               v = rk(2, cur)
               do while (nextpos(v) < first(v + 1))
                  if (.not. visited(perm(nextpos(v)))) exit
                  nextpos(v) = nextpos(v) + 1
               end do
               if (nextpos(v) >= first(v + 1)) exit
               cur = perm(nextpos(v))
            end do
         end do
      end do
      ptr(nchain + 1) = nout + 1
      chain = ptr(1:nchain + 1)
   end subroutine order_chains

   !> rk(:, k): the rank of node edges(:, k) among the distinct end nodes of the edges, in
   !> ascending order of node number (1..nrank).
   pure subroutine rank_nodes(nedge, edges, rk, nrank)
      integer, intent(in) :: nedge, edges(2, nedge)
      integer, allocatable, intent(out) :: rk(:, :)
      integer, intent(out) :: nrank
      integer, allocatable :: ends(:), perm(:)
      integer :: k, j
      allocate (rk(2, nedge), perm(2*nedge))
      ends = reshape(edges, [2*nedge])
      call sort_perm_int(2*nedge, ends, perm)
      nrank = 0
      do k = 1, 2*nedge
         j = perm(k)
         if (k == 1) then
            nrank = 1
         else if (ends(j) /= ends(perm(k - 1))) then
            nrank = nrank + 1
         end if
         rk(mod(j - 1, 2) + 1, (j - 1)/2 + 1) = nrank
      end do
   end subroutine rank_nodes

   !> The elements of each body: elements first(b) .. first(b + 1) - 1 of elems are those with
   !> body(e) = ids(b), ascending, for the distinct values ids(:) of body(:) in ascending order.
   !> O(nelem log nelem): the per-body element lists that free_edges_of takes, without a pass
   !> over every element per body.
   subroutine bodies_elements(nelem, body, ids, first, elems)
      integer, intent(in) :: nelem, body(nelem)
      integer, allocatable, intent(out) :: ids(:), first(:), elems(:)
      integer :: k, nb
      integer, allocatable :: starts(:)
      allocate (elems(nelem), starts(nelem + 1))
      call sort_perm_int(nelem, body, elems)
      nb = 0
      do k = 1, nelem
         if (k > 1) then
            if (body(elems(k)) == body(elems(k - 1))) cycle
         end if
         nb = nb + 1
         starts(nb) = k
      end do
      ids = body(elems(starts(1:nb)))
      first = [starts(1:nb), nelem + 1]
   end subroutine bodies_elements

   !> Unique nodes of a set of edges, sorted ascending (the slave node list of a surface).
   subroutine surface_nodes(nedge, edges, nodes)
      integer, intent(in) :: nedge
      integer, intent(in) :: edges(2, nedge)
      integer, allocatable, intent(out) :: nodes(:)
      integer, allocatable :: all(:), perm(:), tmp(:)
      integer :: k, n

      all = reshape(edges, [2*nedge])
      allocate (perm(2*nedge), tmp(2*nedge))
      call sort_perm_int(2*nedge, all, perm)
      n = 0
      do k = 1, 2*nedge
         if (n > 0) then
            if (tmp(n) == all(perm(k))) cycle
         end if
         n = n + 1
         tmp(n) = all(perm(k))
      end do
      nodes = tmp(1:n)
   end subroutine surface_nodes

   !> Neighbours of each segment along its surface: link(1, k) is a segment that ends at
   !> node seg(1, k) (predecessor), link(2, k) one that starts at seg(2, k) (successor);
   !> 0 if there is none. Where several qualify, the adjacent list entry (k-1, k+1) is
   !> preferred, then the lowest index.
   subroutine segment_links(nseg, seg, link)
      integer, intent(in) :: nseg
      integer, intent(in) :: seg(2, nseg)
      integer, intent(out) :: link(2, nseg)
      integer, allocatable :: ps(:), pe(:), ks(:), ke(:)
      integer :: k

      allocate (ps(nseg), pe(nseg), ks(nseg), ke(nseg))
      ks(:) = seg(1, :)
      ke(:) = seg(2, :)
      call sort_perm_int(nseg, ks, ps)
      call sort_perm_int(nseg, ke, pe)
      ks(:) = seg(1, ps)
      ke(:) = seg(2, pe)
      do k = 1, nseg
         link(1, k) = pick(seg(1, k), ke, pe, k - 1, 2)
         link(2, k) = pick(seg(2, k), ks, ps, k + 1, 1)
      end do
   contains
      !> A segment other than k whose end `which` is `node`; prefer `pref`.
      integer function pick(node, keys, perm, pref, which) result(found)
         integer, intent(in) :: node, keys(:), perm(:), pref, which
         integer :: p
         found = 0
         if (pref >= 1 .and. pref <= nseg) then
            if (seg(which, pref) == node .and. pref /= k) then
               found = pref
               return
            end if
         end if
         p = lower_bound(keys, node)
         do while (p <= nseg)
            if (keys(p) /= node) exit
            if (perm(p) /= k .and. seg(1, perm(p)) /= seg(2, perm(p))) then
               found = perm(p)
               return
            end if
            p = p + 1
         end do
      end function pick
   end subroutine segment_links

   !> Position of each segment end in a sorted node list (0 where the node is absent).
   subroutine locate_nodes(nseg, seg, nlist, list, where)
      integer, intent(in) :: nseg, nlist
      integer, intent(in) :: seg(2, nseg), list(nlist)
      integer, intent(out) :: where(2, nseg)
      integer :: k, j, p

      do k = 1, nseg
         do j = 1, 2
            p = lower_bound(list, seg(j, k))
            where(j, k) = 0
            if (p <= nlist) then
               if (list(p) == seg(j, k)) where(j, k) = p
            end if
         end do
      end do
   end subroutine locate_nodes

   !> First position p in ascending `a` with a(p) >= v (size(a)+1 if none).
   pure integer function lower_bound(a, v) result(lo)
      integer, intent(in) :: a(:), v
      integer :: hi, mid
      lo = 1
      hi = size(a) + 1
      do while (lo < hi)
         mid = (lo + hi)/2
         if (a(mid) < v) then
            lo = mid + 1
         else
            hi = mid
         end if
      end do
   end function lower_bound

   !> Outward unit normal of segment xa -> xb (body on the left), seed eq. 6.2:
   !> n = (t_y, -t_x) / |t| with t = xb - xa; zero for a zero-length segment.
   pure function segment_normal(xa, xb) result(n)
      real(wp), intent(in) :: xa(2), xb(2)
      real(wp) :: n(2)
      real(wp) :: t(2), len
      t = xb - xa
      len = sqrt(t(1)*t(1) + t(2)*t(2))
      if (len > 0.0_wp) then
         n = [t(2), -t(1)]/len
      else
         n = 0.0_wp
      end if
   end function segment_normal

   !> Normalized average of two unit normals; zero when they cancel.
   pure function average_normal(na, nb) result(n)
      real(wp), intent(in) :: na(2), nb(2)
      real(wp) :: n(2)
      real(wp) :: len
      n = na + nb
      len = sqrt(n(1)*n(1) + n(2)*n(2))
      if (len > 1.0e-12_wp) then
         n = n/len
      else
         n = 0.0_wp
      end if
   end function average_normal

   !> Node normals of a surface at positions x: for each listed node, the normalized sum of
   !> the unit normals of the segments that meet there (the average of the two adjacent
   !> segment normals on a simple surface). `where` comes from locate_nodes. Nodes whose
   !> normals cancel get zero.
   subroutine node_normals(nnode, x, nseg, seg, nlist, where, nrm)
      integer, intent(in) :: nnode, nseg, nlist
      real(wp), intent(in) :: x(2, nnode)
      integer, intent(in) :: seg(2, nseg), where(2, nseg)
      real(wp), intent(out) :: nrm(2, nlist)
      real(wp) :: n(2)
      integer :: k, j, p

      nrm = 0.0_wp
      do k = 1, nseg
         n = segment_normal(x(:, seg(1, k)), x(:, seg(2, k)))
         do j = 1, 2
            p = where(j, k)
            if (p > 0) nrm(:, p) = nrm(:, p) + n
         end do
      end do
      ! scalar: a vectorized loop calls glibc's vector hypot (libmvec), whose results differ from
      ! the scalar hypot that some_node_normals and node_normal_from use in the last bits
      !GCC$ novector
      do p = 1, nlist
         nrm(:, p) = unit_or_zero(nrm(:, p))
      end do
   end subroutine node_normals

   !> v / |v|, or 0 when |v| <= 1e-12 (a node whose segment normals cancel has no normal).
   pure function unit_or_zero(v) result(u)
      real(wp), intent(in) :: v(2)
      real(wp) :: u(2)
      real(wp) :: len
      len = hypot(v(1), v(2))
      if (len > 1.0e-12_wp) then
         u = v/len
      else
         u = 0.0_wp
      end if
   end function unit_or_zero

   !> Segments of each node of a surface, in increasing segment order (CSR): the segments of
   !> node position p (as numbered by `where`, locate_nodes) are segs(head(p):head(p+1)-1).
   subroutine node_segments(nseg, where, nlist, head, segs)
      integer, intent(in) :: nseg, nlist
      integer, intent(in) :: where(2, nseg)
      integer, allocatable, intent(out) :: head(:), segs(:)
      integer :: k, j, p
      integer, allocatable :: fill(:)

      allocate (head(nlist + 1), source=0)
      do k = 1, nseg
         do j = 1, 2
            p = where(j, k)
            if (p > 0) head(p + 1) = head(p + 1) + 1
         end do
      end do
      head(1) = 1
      do p = 1, nlist
         head(p + 1) = head(p + 1) + head(p)
      end do
      allocate (segs(head(nlist + 1) - 1), fill(nlist))
      fill = head(1:nlist)
      do k = 1, nseg
         do j = 1, 2
            p = where(j, k)
            if (p <= 0) cycle
            segs(fill(p)) = k
            fill(p) = fill(p) + 1
         end do
      end do
   end subroutine node_segments

   !> node_normals for the node positions sel(1:nsel) only, bit for bit the same values: the
   !> segment normals are summed in increasing segment order as node_normals sums them. The
   !> other columns of nrm are left as they are.
   pure subroutine some_node_normals(nnode, x, nseg, seg, nlist, head, segs, nsel, sel, nrm)
      integer, intent(in) :: nnode, nseg, nlist, nsel
      real(wp), intent(in) :: x(2, nnode)
      integer, intent(in) :: seg(2, nseg), head(nlist + 1), segs(*), sel(nsel)
      real(wp), intent(inout) :: nrm(2, nlist)
      integer :: i, p, q, k

      do i = 1, nsel
         p = sel(i)
         nrm(:, p) = 0.0_wp
         do q = head(p), head(p + 1) - 1
            k = segs(q)
            nrm(:, p) = nrm(:, p) + segment_normal(x(:, seg(1, k)), x(:, seg(2, k)))
         end do
         nrm(:, p) = unit_or_zero(nrm(:, p))
      end do
   end subroutine some_node_normals

   !> The normal of node position p as some_node_normals forms it, from the unit normals of the
   !> surface's segments at the same positions already formed (sn(1:2, k) for segment k): the
   !> same sum in the same order, so the same bits. sn(4, *): the normals at x0 in rows 1:2 (the
   !> narrow phase's segment cache, src/exic/contact/detect.f90).
   pure function node_normal_from(head, segs, p, sn) result(n)
      integer, intent(in) :: head(*), segs(*), p
      real(wp), intent(in) :: sn(4, *)
      real(wp) :: n(2)
      integer :: q
      n = 0.0_wp
      do q = head(p), head(p + 1) - 1
         n = n + sn(1:2, segs(q))
      end do
      n = unit_or_zero(n)
   end function node_normal_from

   !> The dofs along the normals of segments seg(2, nseg) at positions x: dofs(d, i) is set for
   !> both ends i of a segment whose normal n has |n_d| >= |n_other| (a node where the surface
   !> turns gets both; doc/impact.md, eq. I.3a). Other entries are left as they are.
   pure subroutine normal_dofs(nnode, x, nseg, seg, dofs)
      integer, intent(in) :: nnode, nseg
      real(wp), intent(in) :: x(2, nnode)
      integer, intent(in) :: seg(2, nseg)
      logical, intent(inout) :: dofs(2, nnode)
      real(wp) :: t(2)
      integer :: s
      do s = 1, nseg
         ! tangent t; the normal (t2, -t1) has |n_1| = |t_2|
         t = x(:, seg(2, s)) - x(:, seg(1, s))
         if (abs(t(2)) >= abs(t(1))) dofs(1, seg(:, s)) = .true.
         if (abs(t(1)) >= abs(t(2))) dofs(2, seg(:, s)) = .true.
      end do
   end subroutine normal_dofs

end module exic_mesh_boundary
