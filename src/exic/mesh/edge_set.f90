!> Named sets of element edges (a Gmsh physical curve, for example), kept with the mesh so
!> that boundary codes (PBOUndary), contact surfaces (SURFace + PHYSical) and edge loads can
!> select them.
!>
!> Every edge is oriented like a contact segment: the element `elem` lies on the LEFT of
!> n1 -> n2, i.e. (n1, n2) is that element's own counter-clockwise edge. `other` is the element
!> on the right (0 on the boundary of the mesh). An edge shared by two elements keeps the
!> orientation of the element on the left of the curve's own direction (as the mesh file
!> gives it).
module exic_mesh_edge_set
   use exic_base_kinds, only: i8
   use exic_base_sort, only: sort_perm_i8
   implicit none
   private

   public :: edge_set_t, orient_edges, find_edge_set, add_edges, edge_set_nodes, edge_set_ids

   !> One named set of oriented element edges.
   type :: edge_set_t
      integer :: id = 0                         !< the set's number (Gmsh physical curve tag)
      character(len=:), allocatable :: name     !< its name ('' when none)
      character(len=:), allocatable :: where    !< file:line of the command that made it
      integer :: nedge = 0
      integer, allocatable :: edge(:, :)        !< (2, nedge) nodes, element elem on the left
      integer, allocatable :: elem(:)           !< (nedge) element on the left of n1 -> n2
      integer, allocatable :: other(:)          !< (nedge) element on the right, 0 on the boundary
   end type edge_set_t

contains

   !> Orient the node pairs `line(:, k)` as edges of the elements `conn(:, 1:nelem)` (numbered
   !> elem0 + 1 ... elem0 + nelem). On return `edge`, `elem` and `other` describe every line,
   !> and `bad` = 0; when a line is not an edge of any element, `bad` is its index.
   !> Cost O((m + n) log m) for m = 4 nelem element edges and n lines.
   subroutine orient_edges(nelem, conn, elem0, nline, line, edge, elem, other, bad)
      integer, intent(in) :: nelem, elem0, nline
      integer, intent(in) :: conn(4, nelem), line(2, nline)
      integer, intent(out) :: edge(2, nline), elem(nline), other(nline), bad
      integer(i8), allocatable :: key(:)
      integer, allocatable :: perm(:)
      integer(i8) :: base, k0
      integer :: e, j, m, k, lo, hi, mid, p, a, b, left, right

      bad = 0
      base = int(max(maxval(conn), maxval(line), 1), i8) + 1_i8
      m = 4*nelem
      allocate (key(m), perm(m))
      do e = 1, nelem
         do j = 1, 4
            a = conn(j, e)
            b = conn(mod(j, 4) + 1, e)
            key(4*(e - 1) + j) = int(min(a, b), i8)*base + int(max(a, b), i8)
         end do
      end do
      call sort_perm_i8(m, key, perm)
      do k = 1, nline
         a = line(1, k)
         b = line(2, k)
         k0 = int(min(a, b), i8)*base + int(max(a, b), i8)
         lo = 1
         hi = m + 1
         do while (lo < hi)
            mid = (lo + hi)/2
            if (key(perm(mid)) < k0) then
               lo = mid + 1
            else
               hi = mid
            end if
         end do
         if (lo > m .or. a == b) then
            bad = k
            return
         end if
         if (key(perm(lo)) /= k0) then
            bad = k
            return
         end if
         left = 0
         right = 0
         do p = lo, m
            if (key(perm(p)) /= k0) exit
            e = (perm(p) - 1)/4 + 1
            j = perm(p) - 4*(e - 1)
            if (conn(j, e) == a) then
               left = e                 ! e runs a -> b counter-clockwise: it is on the left
            else
               right = e
            end if
         end do
         if (left /= 0) then
            elem(k) = left
            other(k) = right
            edge(:, k) = [a, b]
         else
            elem(k) = right
            other(k) = 0
            edge(:, k) = [b, a]
         end if
         elem(k) = elem(k) + elem0
         if (other(k) /= 0) other(k) = other(k) + elem0
      end do
   end subroutine orient_edges

   !> Index of the set with number `id` in `sets` (0 when there is none).
   pure integer function find_edge_set(sets, id) result(k)
      type(edge_set_t), allocatable, intent(in) :: sets(:)
      integer, intent(in) :: id
      if (allocated(sets)) then
         do k = 1, size(sets)
            if (sets(k)%id == id) return
         end do
      end if
      k = 0
   end function find_edge_set

   !> Add oriented edges to set `id` (created, with `name` and `where`, when new).
   subroutine add_edges(sets, id, name, where, edge, elem, other)
      type(edge_set_t), allocatable, intent(inout) :: sets(:)
      integer, intent(in) :: id
      character(len=*), intent(in) :: name, where
      integer, intent(in) :: edge(:, :), elem(:), other(:)
      type(edge_set_t), allocatable :: tmp(:)
      integer :: k, n
      if (.not. allocated(sets)) allocate (sets(0))
      k = find_edge_set(sets, id)
      if (k == 0) then
         n = size(sets)
         allocate (tmp(n + 1))
         tmp(1:n) = sets
         call move_alloc(tmp, sets)
         k = n + 1
         sets(k)%id = id
         sets(k)%name = name
         sets(k)%where = where
         allocate (sets(k)%edge(2, 0), sets(k)%elem(0), sets(k)%other(0))
      end if
      associate (s => sets(k))
         s%edge = reshape([reshape(s%edge, [2*s%nedge]), reshape(edge, [size(edge)])], &
                          [2, s%nedge + size(elem)])
         s%elem = [s%elem, elem]
         s%other = [s%other, other]
         s%nedge = s%nedge + size(elem)
      end associate
   end subroutine add_edges

   !> The distinct nodes of a set, increasing.
   function edge_set_nodes(set) result(nodes)
      type(edge_set_t), intent(in) :: set
      integer, allocatable :: nodes(:)
      integer, allocatable :: all(:), perm(:)
      integer :: k, n
      all = reshape(set%edge, [2*set%nedge])
      allocate (perm(size(all)))
      call sort_perm_i8(size(all), int(all, i8), perm)
      allocate (nodes(size(all)))
      n = 0
      do k = 1, size(all)
         if (n > 0) then
            if (nodes(n) == all(perm(k))) cycle
         end if
         n = n + 1
         nodes(n) = all(perm(k))
      end do
      nodes = nodes(1:n)
   end function edge_set_nodes

   !> The numbers of the sets, comma separated ('none' when there are none).
   function edge_set_ids(sets) result(s)
      type(edge_set_t), allocatable, intent(in) :: sets(:)
      character(len=:), allocatable :: s
      character(len=16) :: buf
      integer :: k
      s = ''
      if (allocated(sets)) then
         do k = 1, size(sets)
            write (buf, '(i0)') sets(k)%id
            if (k > 1) s = s//', '
            s = s//trim(buf)
         end do
      end if
      if (len(s) == 0) s = 'none'
   end function edge_set_ids

end module exic_mesh_edge_set
