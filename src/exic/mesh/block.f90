!> BLOCk generation of a structured patch of 4-node quadrilaterals (FEAP numbering).
!>
!> Master nodes k = 1..9 sit at the natural coordinates (xi, eta) of a 9-node element:
!> corners 1 (-1,-1), 2 (1,-1), 3 (1,1), 4 (-1,1); mid-sides 5 (0,-1), 6 (1,0), 7 (0,1),
!> 8 (-1,0) of edges 1-2, 2-3, 3-4, 4-1; centre 9 (0,0). Generated node (i, j), i = 0..nr,
!> j = 0..ns, sits at xi = -1 + 2 i/nr, eta = -1 + 2 j/ns of the quadratic map through the
!> master nodes: the 9-node Lagrange map when node 9 is given, else the 8-node serendipity map.
!> A missing mid-side node is put at the midpoint of its edge's corners, so a block with
!> corners only is bilinear; an off-centre or off-line mid-side node grades or bends its edge.
!>
!> POLAr blocks give master nodes as (r, theta in degrees); the map interpolates (r, theta)
!> and every generated node is then converted to x = x0 + r cos(theta), y = y0 + r sin(theta),
!> as FEAP converts generated nodes, about the origin (x0, y0) of the last SHIFt command
!> (default (0, 0)). A POLAr edge of constant r is therefore an exact circular arc. An edge at
!> r = 0 collapses to the origin: `collapsed_edge` finds such edges (of any block) so that the
!> reader can say so instead of generating elements with two coincident corners.
!>
!> Numbering: node(i, j) = node1 + j (nr+1) + i; element (i, j), i = 1..nr, j = 1..ns, is
!> elmt1 + (j-1) nr + (i-1) with nodes [a, a+1, a+1+R, a+R], a = node(i-1, j-1), R = nr+1.
module exic_mesh_block
   use exic_base_kinds, only: wp
   implicit none
   private

   integer, parameter, public :: BLOCK_CARTESIAN = 1, BLOCK_POLAR = 2

   public :: block_coordinates, block_connectivity, block_shape, collapsed_edge

   real(wp), parameter :: xi_master(9) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, 1.0_wp, &
                                          0.0_wp, -1.0_wp, 0.0_wp]
   real(wp), parameter :: eta_master(9) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp, 0.0_wp, &
                                           1.0_wp, 0.0_wp, 0.0_wp]

contains

   !> Coordinates of the (nr+1)(ns+1) nodes of a block, local order i fastest.
   !> `master(:, k)` holds master node k (x, y or r, theta-degrees); `given(k)` says whether it was
   !> given. Corners 1-4 must be given. `origin` is the centre (x0, y0) of POLAr blocks.
   pure subroutine block_coordinates(kind, nr, ns, master, given, origin, x)
      integer, intent(in) :: kind, nr, ns
      real(wp), intent(in) :: master(2, 9)
      logical, intent(in) :: given(9)
      real(wp), intent(in) :: origin(2)
      real(wp), intent(out) :: x(2, (nr + 1)*(ns + 1))
      real(wp) :: m(2, 9), shp(9), xi, eta, r, t
      real(wp), parameter :: deg = acos(-1.0_wp)/180.0_wp
      integer :: i, j, k, edge(2, 4)
      logical :: lagrange

      edge = reshape([1, 2, 2, 3, 3, 4, 4, 1], [2, 4])
      m = master
      do k = 5, 8
         if (.not. given(k)) m(:, k) = 0.5_wp*(m(:, edge(1, k - 4)) + m(:, edge(2, k - 4)))
      end do
      lagrange = given(9)
      do j = 0, ns
         eta = -1.0_wp + 2.0_wp*real(j, wp)/real(ns, wp)
         do i = 0, nr
            xi = -1.0_wp + 2.0_wp*real(i, wp)/real(nr, wp)
            call block_shape(xi, eta, lagrange, shp)
            k = j*(nr + 1) + i + 1
            if (lagrange) then
               x(:, k) = matmul(m, shp)
            else
               x(:, k) = matmul(m(:, 1:8), shp(1:8))
            end if
            if (kind == BLOCK_POLAR) then
               r = x(1, k)
               t = x(2, k)*deg
               x(1, k) = origin(1) + r*cos(t)
               x(2, k) = origin(2) + r*sin(t)
            end if
         end do
      end do
   end subroutine block_coordinates

   !> Shape functions of the 9-node Lagrange (`lagrange`) or 8-node serendipity map at (xi, eta).
   !> For serendipity, shp(9) = 0.
   pure subroutine block_shape(xi, eta, lagrange, shp)
      real(wp), intent(in) :: xi, eta
      logical, intent(in) :: lagrange
      real(wp), intent(out) :: shp(9)
      real(wp) :: a, b
      integer :: k
      if (lagrange) then
         do k = 1, 9
            shp(k) = lagrange1(xi, xi_master(k))*lagrange1(eta, eta_master(k))
         end do
         return
      end if
      do k = 1, 4
         a = xi*xi_master(k)
         b = eta*eta_master(k)
         shp(k) = 0.25_wp*(1.0_wp + a)*(1.0_wp + b)*(a + b - 1.0_wp)
      end do
      do k = 5, 8
         if (xi_master(k) == 0.0_wp) then
            shp(k) = 0.5_wp*(1.0_wp - xi*xi)*(1.0_wp + eta*eta_master(k))
         else
            shp(k) = 0.5_wp*(1.0_wp + xi*xi_master(k))*(1.0_wp - eta*eta)
         end if
      end do
      shp(9) = 0.0_wp
   end subroutine block_shape

   !> 1-D quadratic Lagrange polynomial of the node at s0 in {-1, 0, 1}.
   pure real(wp) function lagrange1(s, s0)
      real(wp), intent(in) :: s, s0
      if (s0 < -0.5_wp) then
         lagrange1 = 0.5_wp*s*(s - 1.0_wp)
      else if (s0 > 0.5_wp) then
         lagrange1 = 0.5_wp*s*(s + 1.0_wp)
      else
         lagrange1 = (1.0_wp - s)*(1.0_wp + s)
      end if
   end function lagrange1

   !> Connectivity of the nr*ns elements of a block whose first node is node1
   !> (element (i, j) in column (j-1) nr + i).
   pure subroutine block_connectivity(nr, ns, node1, conn)
      integer, intent(in) :: nr, ns, node1
      integer, intent(out) :: conn(4, nr*ns)
      integer :: i, j, a, e
      do j = 1, ns
         do i = 1, nr
            e = (j - 1)*nr + i
            a = node1 + (j - 1)*(nr + 1) + (i - 1)
            conn(:, e) = [a, a + 1, a + 1 + nr + 1, a + nr + 1]
         end do
      end do
   end subroutine block_connectivity

   !> First element edge of a block whose two nodes coincide (distance <= tol): on return
   !> (i, j) is the element (1-based, i along r) and `side` its edge 1-4 (edges 1-2, 2-3, 3-4,
   !> 4-1 of the element); side = 0 when every edge has a length above tol.
   pure subroutine collapsed_edge(nr, ns, x, tol, i, j, side)
      integer, intent(in) :: nr, ns
      real(wp), intent(in) :: x(2, (nr + 1)*(ns + 1)), tol
      integer, intent(out) :: i, j, side
      integer :: c(4), k
      side = 0
      do j = 1, ns
         do i = 1, nr
            c(1) = (j - 1)*(nr + 1) + i
            c(2) = c(1) + 1
            c(3) = c(2) + nr + 1
            c(4) = c(1) + nr + 1
            do k = 1, 4
               if (norm2(x(:, c(k)) - x(:, c(mod(k, 4) + 1))) <= tol) then
                  side = k
                  return
               end if
            end do
         end do
      end do
   end subroutine collapsed_edge

end module exic_mesh_block
