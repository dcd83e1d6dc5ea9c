!> TIE: merge nodes with equal coordinates (FEAP mesh manipulation after the mesh END).
!>
!> Candidate nodes are hashed into square cells of side `tol`, sorted by cell, and every node
!> is compared with the nodes of its own and the 8 neighbouring cells: O(n log n). Nodes within
!> `tol` of each other (max-norm) form one group, joined transitively; the lowest node number of
!> a group survives. Applying a tie remaps the connectivity; a merged-away node keeps its
!> coordinates and `defined` flag but no element refers to it any more: nodes not used by any
!> element are inactive everywhere in exic. Boundary codes of a group are combined (max), nodal
!> forces are summed onto the survivor, and prescribed displacements and initial velocities are
!> the survivor's own unless it has none (all zero), in which case the first non-zero one of the
!> group is taken. Edge sets (mesh%edge_sets) are remapped like the connectivity.
module exic_mesh_tie
   use exic_base_kinds, only: wp, i8
   use exic_base_sort, only: sort_perm_i8
   use exic_base_union_find, only: set_root, join_sets
   use exic_mesh_mesh, only: mesh_t
   implicit none
   private

   public :: tie_map, apply_tie

contains

   !> `map(n)` = surviving node of node n (n itself when it is not merged). Only nodes with
   !> `candidate(n)` take part.
   subroutine tie_map(nnode, x, candidate, tol, map)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode)
      logical, intent(in) :: candidate(nnode)
      real(wp), intent(in) :: tol
      integer, intent(out) :: map(nnode)
      integer, allocatable :: list(:), order(:)
      integer(i8), allocatable :: kx(:), ky(:)
      integer :: nc, k, p, q, dx, dy, lo, n
      real(wp) :: cell, x0, y0

      do n = 1, nnode
         map(n) = n
      end do
      list = pack([(n, n=1, nnode)], candidate)
      nc = size(list)
      if (nc < 2) return
      cell = tol
      if (cell <= 0.0_wp) cell = 1.0_wp
      x0 = minval(x(1, list))
      y0 = minval(x(2, list))
      allocate (kx(nc), ky(nc), order(nc))
      do k = 1, nc
         kx(k) = int(floor((x(1, list(k)) - x0)/cell), i8)
         ky(k) = int(floor((x(2, list(k)) - y0)/cell), i8)
         order(k) = k
      end do
      call sort_by_cell(nc, kx, ky, order)
      do k = 1, nc
         p = list(k)
         do dx = -1, 1
            do dy = -1, 1
               lo = lower_bound(nc, kx, ky, order, kx(k) + dx, ky(k) + dy)
               do q = lo, nc
                  if (kx(order(q)) /= kx(k) + dx .or. ky(order(q)) /= ky(k) + dy) exit
                  n = list(order(q))
                  if (n == p) cycle
                  if (abs(x(1, n) - x(1, p)) <= tol .and. abs(x(2, n) - x(2, p)) <= tol) &
                     call join_sets(map, p, n)
               end do
            end do
         end do
      end do
      do n = 1, nnode
         map(n) = set_root(map, n)
      end do
   end subroutine tie_map

   !> Sort `order` (the identity on entry) so that (kx, ky)(order(:)) is lexicographically
   !> increasing, equal cells in input order: a stable sort by ky, then a stable sort by kx.
   subroutine sort_by_cell(n, kx, ky, order)
      integer, intent(in) :: n
      integer(i8), intent(in) :: kx(n), ky(n)
      integer, intent(inout) :: order(n)
      integer :: by_y(n), by_x(n)
      call sort_perm_i8(n, ky, by_y)
      call sort_perm_i8(n, kx(by_y), by_x)
      order = by_y(by_x)
   end subroutine sort_by_cell

   !> First position q in the sorted order with (kx, ky)(order(q)) >= (cx, cy); n+1 if none.
   integer function lower_bound(n, kx, ky, order, cx, cy)
      integer, intent(in) :: n
      integer(i8), intent(in) :: kx(n), ky(n), cx, cy
      integer, intent(in) :: order(n)
      integer :: lo, hi, mid
      lo = 1
      hi = n + 1
      do while (lo < hi)
         mid = (lo + hi)/2
         if (kx(order(mid)) < cx .or. (kx(order(mid)) == cx .and. ky(order(mid)) < cy)) then
            lo = mid + 1
         else
            hi = mid
         end if
      end do
      lower_bound = lo
   end function lower_bound

   !> Apply a tie map to the mesh: remap connectivity and combine the nodal data of each group.
   subroutine apply_tie(mesh, map)
      type(mesh_t), intent(inout) :: mesh
      integer, intent(in) :: map(:)
      integer :: n, s, e, k, j
      do e = 1, mesh%nelem
         do k = 1, 4
            if (mesh%conn(k, e) >= 1) mesh%conn(k, e) = map(mesh%conn(k, e))
         end do
      end do
      if (allocated(mesh%edge_sets)) then
         do k = 1, size(mesh%edge_sets)
            do j = 1, mesh%edge_sets(k)%nedge
               mesh%edge_sets(k)%edge(:, j) = map(mesh%edge_sets(k)%edge(:, j))
            end do
         end do
      end if
      do n = 1, mesh%nnode
         s = map(n)
         if (s == n) cycle
         mesh%bc(:, s) = max(mesh%bc(:, s), mesh%bc(:, n))
         mesh%force(:, s) = mesh%force(:, s) + mesh%force(:, n)
         mesh%force(:, n) = 0.0_wp
         if (all(mesh%disp(:, s) == 0.0_wp)) mesh%disp(:, s) = mesh%disp(:, n)
         if (all(mesh%v0(:, s) == 0.0_wp)) mesh%v0(:, s) = mesh%v0(:, n)
      end do
   end subroutine apply_tie

end module exic_mesh_tie
