!> Tests of the contact geometry: free edges and surfaces, broad phase, swept and static
!> narrow phase (seed section 6).
module test_contact_geom
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t
   use exic_contact_spec, only: DETECT_SWEPT, DETECT_STATIC
   use exic_mesh_boundary, only: free_edges, surface_nodes, segment_links, locate_nodes, &
                                 segment_normal, average_normal, node_normals, node_segments, &
                                 some_node_normals
   use exic_contact_broad, only: broad_t, broad_search, broad_search_kept, broad_brute, surfaces_apart
   use exic_contact_broad_all, only: broad_all_t
   use exic_contact_detect, only: gap_coefficients, first_crossing, swept_pair, static_pair, &
                                  contact_set_t, detect_contacts, ALPHA_TOL, FACING_LIMIT
   use testing, only: suite_t, check, check_close, section
   use test_wedge, only: test_wedge_rule
   use test_corner_pass, only: test_corner_turns
   implicit none
   private

   public :: run_contact_geom_tests, block

   !> State of the test's own linear congruential generator (deterministic scenes).
   type :: lcg_t
      integer(i8) :: state = 12345_i8
   end type lcg_t

contains

   !> Run every contact geometry test.
   subroutine run_contact_geom_tests(s)
      type(suite_t), intent(inout) :: s
      call test_block_edges(s)
      call test_two_blocks_and_l(s)
      call test_normals_links(s)
      call test_fixed_segment(s)
      call test_moving_segment(s)
      call test_robustness(s)
      call test_thin_target(s)
      call test_corner(s)
      call test_facing_sides(s)
      call test_vertex_rule(s)
      call test_wedge_rule(s)
      call test_corner_turns(s)
      call test_broad_random(s)
      call test_broad_kept(s)
      call test_broad_scaling(s)
      call test_broad_all(s)
      call test_broad_all_kept(s)
   end subroutine run_contact_geom_tests

   ! ---------------------------------------------------------------- helpers

   !> Uniform block of nx x ny counter-clockwise quadrilaterals from (x0, y0), nodes
   !> numbered from off + 1 row by row.
   subroutine block(nx, ny, x0, y0, h, off, x, conn)
      integer, intent(in) :: nx, ny, off
      real(wp), intent(in) :: x0, y0, h
      real(wp), intent(inout) :: x(:, :)
      integer, intent(out) :: conn(4, nx*ny)
      integer :: i, j, e
      do j = 0, ny
         do i = 0, nx
            x(:, off + 1 + i + j*(nx + 1)) = [x0 + i*h, y0 + j*h]
         end do
      end do
      e = 0
      do j = 0, ny - 1
         do i = 0, nx - 1
            e = e + 1
            conn(:, e) = off + [1 + i + j*(nx + 1), 2 + i + j*(nx + 1), &
                                2 + i + (j + 1)*(nx + 1), 1 + i + (j + 1)*(nx + 1)]
         end do
      end do
   end subroutine block

   !> Signed area of the polygon through the edges' first nodes (chain c).
   real(wp) function chain_area(x, edges, first, last) result(area)
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: edges(:, :), first, last
      integer :: k
      area = 0.0_wp
      do k = first, last
         area = area + 0.5_wp*(x(1, edges(1, k))*x(2, edges(2, k)) - &
                               x(1, edges(2, k))*x(2, edges(1, k)))
      end do
   end function chain_area

   !> True when every chain is closed and consecutive edges join.
   logical function chains_join(edges, chain) result(ok)
      integer, intent(in) :: edges(:, :), chain(:)
      integer :: c, k
      ok = .true.
      do c = 1, size(chain) - 1
         do k = chain(c), chain(c + 1) - 2
            ok = ok .and. edges(2, k) == edges(1, k + 1)
         end do
         ok = ok .and. edges(2, chain(c + 1) - 1) == edges(1, chain(c))
      end do
   end function chains_join

   !> True when each edge has exactly one selected element holding both its nodes, and
   !> that element's centroid lies on the left of n1 -> n2 (checked independently).
   logical function body_on_left(x, conn, select, edges) result(ok)
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: conn(:, :), edges(:, :)
      logical, intent(in) :: select(:)
      integer :: k, e, nown
      real(wp) :: c(2), t(2), d(2)
      ok = .true.
      do k = 1, size(edges, 2)
         nown = 0
         do e = 1, size(conn, 2)
            if (.not. select(e)) cycle
            if (.not. (any(conn(:, e) == edges(1, k)) .and. any(conn(:, e) == edges(2, k)))) cycle
            nown = nown + 1
            c = 0.25_wp*(x(:, conn(1, e)) + x(:, conn(2, e)) + x(:, conn(3, e)) + x(:, conn(4, e)))
            t = x(:, edges(2, k)) - x(:, edges(1, k))
            d = c - x(:, edges(1, k))
            ok = ok .and. t(1)*d(2) - t(2)*d(1) > 0.0_wp
         end do
         ok = ok .and. nown == 1
      end do
   end function body_on_left

   !> Uniform random number in [lo, hi).
   real(wp) function rnd(g, lo, hi)
      type(lcg_t), intent(inout) :: g
      real(wp), intent(in) :: lo, hi
      g%state = modulo(g%state*48271_i8, 2147483647_i8)
      rnd = lo + (hi - lo)*real(g%state - 1_i8, wp)/2147483646.0_wp
   end function rnd

   !> Coefficients as printed in the seed's eq. 6.5 (master motion added, not subtracted).
   subroutine seed_coefficients(xs0, xs1, xa0, xa1, xb0, xb1, a, b, c)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), xb0(2), xb1(2)
      real(wp), intent(out) :: a, b, c
      real(wp) :: ni(2), dn(2), w(2)
      ni = segment_normal(xa0, xb0)
      dn = segment_normal(xa1, xb1) - ni
      w = -xs0 + xs1 + xa1 - xa0
      a = dot_product(dn, w)
      b = dot_product(ni, w) + dot_product(dn, xs0 - xa0)
      c = dot_product(ni, xs0 - xa0)
   end subroutine seed_coefficients

   ! ------------------------------------------------------------- boundary

   subroutine test_block_edges(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x(2, 12)
      integer :: conn(4, 6), k, nint
      integer, allocatable :: edges(:, :), chain(:), owner(:), nodes(:), expect(:)
      logical :: sel(6), sel2(6)
      type(error_t), allocatable :: err

      call section(s, 'contact geometry: free edges of a 3x2 block')
      call block(3, 2, 0.0_wp, 0.0_wp, 1.0_wp, 0, x, conn)
      sel = .true.
      call free_edges(6, conn, sel, edges, err, chain, owner)
      call check(s, .not. allocated(err), 'no error')
      call check(s, size(edges, 2) == 10, '10 free edges')
      call check(s, body_on_left(x, conn, sel, edges), 'body on the left of every edge')
      call check(s, all([(any(conn(:, owner(k)) == edges(1, k)) .and. &
                          any(conn(:, owner(k)) == edges(2, k)), k=1, size(edges, 2))]), &
                 'owner element holds each edge')
      call check(s, size(chain) == 2 .and. chains_join(edges, chain), 'one closed chain')
      call check_close(s, chain_area(x, edges, 1, 10), 6.0_wp, 1.0e-13_wp, &
                       'chain encloses the block counter-clockwise')
      call check(s, edges(1, 1) == 1, 'chain starts at the lowest node')
      call surface_nodes(size(edges, 2), edges, nodes)
      nint = 0
      allocate (expect(0))
      do k = 1, 12
         if (x(1, k) > 0.5_wp .and. x(1, k) < 2.5_wp .and. x(2, k) > 0.5_wp .and. &
             x(2, k) < 1.5_wp) then
            nint = nint + 1
         else
            expect = [expect, k]
         end if
      end do
      call check(s, nint == 2 .and. size(nodes) == 10, '10 slave nodes')
      call check(s, all(nodes == expect), 'slave nodes are the boundary nodes, sorted')
      ! a subset: the two left elements of the bottom row (1x2 strip: 6 edges)
      sel2 = .false.
      sel2(1:2) = .true.
      call free_edges(6, conn, sel2, edges, err, chain)
      call check(s, size(edges, 2) == 6 .and. body_on_left(x, conn, sel2, edges) .and. &
                 chains_join(edges, chain), 'selected subset: 6 edges, oriented, closed')
      ! a clockwise element makes a shared edge run the same way twice
      conn(:, 2) = conn([4, 3, 2, 1], 2)
      call free_edges(6, conn, sel, edges, err)
      call check(s, allocated(err), 'inconsistent orientation is an error')
   end subroutine test_block_edges

   subroutine test_two_blocks_and_l(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x(2, 16), xl(2, 9)
      integer :: conn(4, 7), connl(4, 4), c
      integer, allocatable :: edges(:, :), chain(:)
      logical :: sel(7), sell(4), ok
      type(error_t), allocatable :: err

      call section(s, 'contact geometry: two blocks, L-shaped region')
      call block(3, 2, 0.0_wp, 0.0_wp, 1.0_wp, 0, x, conn(:, 1:6))
      call block(1, 1, 5.0_wp, 0.0_wp, 1.0_wp, 12, x, conn(:, 7:7))
      sel = .true.
      call free_edges(7, conn, sel, edges, err, chain)
      call check(s, size(edges, 2) == 14 .and. size(chain) == 3, 'two blocks: 14 edges, 2 chains')
      ok = chains_join(edges, chain)
      do c = 1, 2
         ok = ok .and. (all(edges(:, chain(c):chain(c + 1) - 1) <= 12) .or. &
                        all(edges(:, chain(c):chain(c + 1) - 1) > 12))
      end do
      call check(s, ok, 'each chain closed and within one block')
      call check(s, body_on_left(x, conn, sel, edges), 'two blocks: body on the left')
      call check_close(s, chain_area(x, edges, chain(1), chain(2) - 1) + &
                       chain_area(x, edges, chain(2), chain(3) - 1), 7.0_wp, 1.0e-13_wp, &
                       'two blocks: chains enclose both areas')
      ! L: 2x2 block without its top-right element
      call block(2, 2, 0.0_wp, 0.0_wp, 1.0_wp, 0, xl, connl)
      sell = [.true., .true., .true., .false.]
      call free_edges(4, connl, sell, edges, err, chain)
      call check(s, size(edges, 2) == 8 .and. size(chain) == 2 .and. &
                 chains_join(edges, chain), 'L: 8 edges in one closed chain')
      call check(s, body_on_left(xl, connl, sell, edges), 'L: body on the left')
      call check_close(s, chain_area(xl, edges, 1, 8), 3.0_wp, 1.0e-13_wp, 'L: encloses area 3')
   end subroutine test_two_blocks_and_l

   subroutine test_normals_links(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x(2, 12), nrm(2, 10), part(2, 10), r
      integer :: conn(4, 6), k, p
      integer, allocatable :: edges(:, :), nodes(:), link(:, :), where(:, :), head(:), segs(:)
      logical :: sel(6), ok
      type(error_t), allocatable :: err

      call section(s, 'contact geometry: segment links and node normals')
      call block(3, 2, 0.0_wp, 0.0_wp, 1.0_wp, 0, x, conn)
      sel = .true.
      call free_edges(6, conn, sel, edges, err)
      call surface_nodes(10, edges, nodes)
      allocate (link(2, 10), where(2, 10))
      call segment_links(10, edges, link)
      ok = .true.
      do k = 1, 10
         ok = ok .and. link(2, k) > 0 .and. link(1, k) > 0
         if (.not. ok) exit
         ok = ok .and. edges(1, link(2, k)) == edges(2, k) .and. link(1, link(2, k)) == k
      end do
      call check(s, ok, 'links: successor starts where a segment ends, and back')
      call locate_nodes(10, edges, 10, nodes, where)
      call check(s, all(nodes(reshape(where, [20])) == reshape(edges, [20])), &
                 'locate_nodes maps segment ends to the list')
      call node_normals(12, x, 10, edges, 10, where, nrm)
      r = sqrt(0.5_wp)
      p = findloc(nodes, 1, 1)
      call check(s, maxval(abs(nrm(:, p) - [-r, -r])) < 1.0e-15_wp, 'corner node normal')
      p = findloc(nodes, 2, 1)
      call check(s, maxval(abs(nrm(:, p) - [0.0_wp, -1.0_wp])) < 1.0e-15_wp, 'edge node normal')
      p = findloc(nodes, 12, 1)
      call check(s, maxval(abs(nrm(:, p) - [r, r])) < 1.0e-15_wp, 'far corner node normal')
      call check(s, maxval(abs(segment_normal([0.0_wp, 0.0_wp], [2.0_wp, 0.0_wp]) - &
                               [0.0_wp, -1.0_wp])) == 0.0_wp, 'segment normal points right')
      ! the normals of chosen nodes only: the same bits as node_normals, the others untouched
      x(:, 6) = x(:, 6) + [0.3_wp, 0.1_wp]
      x(:, 7) = x(:, 7) + [-0.1_wp, 0.2_wp]
      call node_normals(12, x, 10, edges, 10, where, nrm)
      call node_segments(10, where, 10, head, segs)
      part = -7.0_wp
      call some_node_normals(12, x, 10, edges, 10, head, segs, 4, [2, 5, 7, 10], part)
      ok = all(part(:, [2, 5, 7, 10]) == nrm(:, [2, 5, 7, 10])) .and. &
           all(part(:, [1, 3, 4, 6, 8, 9]) == -7.0_wp)
      call check(s, ok, 'normals of chosen nodes: identical to node_normals, others untouched')
   end subroutine test_normals_links

   ! ----------------------------------------------------------- narrow phase

   subroutine test_fixed_segment(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: xa(2) = [0.0_wp, 0.0_wp], xb(2) = [2.0_wp, 0.0_wp]
      real(wp) :: tau, alpha, gap
      logical :: hit

      call section(s, 'contact geometry: swept detection, fixed segment')
      ! outward normal (0,-1): the node comes from below
      call swept_pair([0.5_wp, -1.0_wp], [0.9_wp, 0.6_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, hit, 'crossing node is caught')
      call check_close(s, tau, 0.625_wp, 1.0e-12_wp, 'crossing time')
      call check_close(s, alpha, 0.375_wp, 1.0e-12_wp, 'contact point alpha')
      call swept_pair([0.5_wp, -1.0_wp], [0.6_wp, -0.2_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, .not. hit, 'node that stays outside: no contact')
      call swept_pair([2.5_wp, -1.0_wp], [2.5_wp, 1.0_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, .not. hit, 'crossing beyond the segment end: no contact')
      call swept_pair([2.0_wp*(1.0_wp + 0.5_wp*ALPHA_TOL), -1.0_wp], &
                      [2.0_wp*(1.0_wp + 0.5_wp*ALPHA_TOL), 1.0_wp], xa, xa, xb, xb, 0.1_wp, &
                      hit, tau, alpha)
      call check(s, hit, 'crossing within the end tolerance is accepted')
      call swept_pair([2.0_wp*(1.0_wp + 2.0_wp*ALPHA_TOL), -1.0_wp], &
                      [2.0_wp*(1.0_wp + 2.0_wp*ALPHA_TOL), 1.0_wp], xa, xa, xb, xb, 0.1_wp, &
                      hit, tau, alpha)
      call check(s, .not. hit, 'crossing just past the end tolerance is rejected')
      call swept_pair([1.5_wp, -1.0_wp], [1.0_wp, 0.0_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, hit .and. tau == 1.0_wp .and. abs(alpha - 0.5_wp) < 1.0e-15_wp, &
                 'root exactly at tau = 1')
      call swept_pair([0.5_wp, 0.0_wp], [0.7_wp, 0.5_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, hit .and. tau == 0.0_wp .and. abs(alpha - 0.25_wp) < 1.0e-15_wp, &
                 'start exactly on the segment, moving in: tau = 0')
      call swept_pair([0.5_wp, 0.0_wp], [0.7_wp, -0.5_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, .not. hit, 'start on the segment, moving out: no contact')
      call swept_pair([0.5_wp, 0.05_wp], [0.5_wp, 0.2_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, hit .and. tau == 0.0_wp, 'start slightly behind (within depth): tau = 0')
      call swept_pair([0.5_wp, 0.5_wp], [0.5_wp, 0.6_wp], xa, xa, xb, xb, 0.1_wp, hit, tau, alpha)
      call check(s, .not. hit, 'start deeper than depth: no contact')
      call static_pair([0.9_wp, 0.05_wp], xa, xb, 0.1_wp, hit, alpha, gap)
      call check(s, hit .and. abs(gap + 0.05_wp) < 1.0e-15_wp .and. &
                 abs(alpha - 0.45_wp) < 1.0e-15_wp, 'static: end gap and projection')
   end subroutine test_fixed_segment

   subroutine test_moving_segment(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: tau, alpha, a, b, c, g1, sa, sb, sc, r1, r2, w(2), xs(2), t(2), d(2)
      logical :: hit

      call section(s, 'contact geometry: swept detection, moving and rotating segment')
      ! segment y = -tau translating down onto a fixed node at y = -0.5: g = 0.5 - tau
      call swept_pair([1.0_wp, -0.5_wp], [1.0_wp, -0.5_wp], [0.0_wp, 0.0_wp], [0.0_wp, -1.0_wp], &
                      [2.0_wp, 0.0_wp], [2.0_wp, -1.0_wp], 0.1_wp, hit, tau, alpha)
      call check(s, hit, 'translating segment reaches a fixed node')
      call check_close(s, tau, 0.5_wp, 1.0e-12_wp, 'translating segment: tau')
      call check_close(s, alpha, 0.5_wp, 1.0e-12_wp, 'translating segment: alpha')
      call seed_coefficients([1.0_wp, -0.5_wp], [1.0_wp, -0.5_wp], [0.0_wp, 0.0_wp], &
                             [0.0_wp, -1.0_wp], [2.0_wp, 0.0_wp], [2.0_wp, -1.0_wp], sa, sb, sc)
      call check(s, sa == 0.0_wp .and. -sc/sb < 0.0_wp, &
                 'printed eq. 6.5 puts this crossing at tau < 0 (missed)')
      ! rotation about m1 = 0: m2 from (1,0) to (0,1); g = 0.5 (tau - 0.5)(tau - 2)
      call gap_coefficients([0.75_wp, -0.5_wp], [-0.25_wp, 1.0_wp], [0.0_wp, 0.0_wp], &
                            [0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], a, b, c, g1)
      call check(s, abs(a - 0.5_wp) < 1.0e-15_wp .and. abs(b + 1.25_wp) < 1.0e-15_wp .and. &
                 abs(c - 0.5_wp) < 1.0e-15_wp .and. abs(g1 + 0.25_wp) < 1.0e-15_wp, &
                 'rotating segment: A, B, C and g(1)')
      call swept_pair([0.75_wp, -0.5_wp], [-0.25_wp, 1.0_wp], [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], &
                      [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 0.1_wp, hit, tau, alpha)
      call check_close(s, tau, 0.5_wp, 1.0e-12_wp, 'rotating segment (A /= 0): tau')
      call check_close(s, alpha, 0.5_wp, 1.0e-12_wp, 'rotating segment: alpha')
      ! the slave lies on the segment at tau_c (exact here: |m2 - m1| equal at both ends)
      xs = [0.75_wp, -0.5_wp] + tau*[-1.0_wp, 1.5_wp]
      t = [1.0_wp - tau, tau]
      call check(s, abs(t(1)*xs(2) - t(2)*xs(1)) < 1.0e-14_wp, 'rotating: slave on segment at tau_c')
      ! the same motion seen in a frame moving with w: the answer must not change
      w = [3.0_wp, -2.0_wp]
      call swept_pair([0.75_wp, -0.5_wp], [-0.25_wp, 1.0_wp] + w, [0.0_wp, 0.0_wp], w, &
                      [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp] + w, 0.1_wp, hit, tau, alpha)
      call check_close(s, tau, 0.5_wp, 1.0e-12_wp, 'rotating + translating: tau')
      call check_close(s, alpha, 0.5_wp, 1.0e-12_wp, 'rotating + translating: alpha')
      call seed_coefficients([0.75_wp, -0.5_wp], [-0.25_wp, 1.0_wp] + w, [0.0_wp, 0.0_wp], w, &
                             [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp] + w, sa, sb, sc)
      d = [sb*sb - 4.0_wp*sa*sc, 0.0_wp]
      r1 = 9.0_wp; r2 = 9.0_wp
      if (d(1) >= 0.0_wp) then
         r1 = (-sb - sqrt(d(1)))/(2.0_wp*sa)
         r2 = (-sb + sqrt(d(1)))/(2.0_wp*sa)
      end if
      call check(s, abs(r1 - 0.5_wp) > 0.1_wp .and. abs(r2 - 0.5_wp) > 0.1_wp, &
                 'printed eq. 6.5 gives a wrong crossing time for a moving master')
   end subroutine test_moving_segment

   subroutine test_robustness(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: tau, alpha, a, b, c, g1, naive, dlt, v(2)
      integer :: k
      logical :: hit

      call section(s, 'contact geometry: quadratic robustness')
      call first_crossing(0.0_wp, -1.0_wp, 0.5_wp, -0.5_wp, hit, tau)
      call check(s, hit .and. tau == 0.5_wp, 'A = 0: linear root')
      call first_crossing(1.0e-18_wp, -1.0_wp, 0.5_wp, -0.5_wp, hit, tau)
      naive = (1.0_wp - sqrt(1.0_wp - 4.0e-18_wp*0.5_wp))/2.0e-18_wp
      call check(s, hit .and. abs(tau - 0.5_wp) < 1.0e-15_wp .and. abs(naive - 0.5_wp) > 0.1_wp, &
                 'A = 1e-18: stable root (textbook formula cancels)')
      ! pure translation of the segment: dn = 0, so A = 0 exactly
      call gap_coefficients([0.3_wp, -1.0_wp], [0.7_wp, 1.0_wp], [0.0_wp, 0.0_wp], &
                            [0.1_wp, 0.2_wp], [2.0_wp, 0.0_wp], [2.1_wp, 0.2_wp], a, b, c, g1)
      call check(s, a == 0.0_wp, 'pure translation: A = 0 exactly')
      call swept_pair([0.3_wp, -1.0_wp], [0.7_wp, 1.0_wp], [0.0_wp, 0.0_wp], [0.1_wp, 0.2_wp], &
                      [2.0_wp, 0.0_wp], [2.1_wp, 0.2_wp], 0.1_wp, hit, tau, alpha)
      call check_close(s, tau, 1.0_wp/1.8_wp, 1.0e-12_wp, 'pure translation: tau')
      call check_close(s, alpha, (0.3_wp + 0.4_wp/1.8_wp - 0.1_wp/1.8_wp)/2.0_wp, 1.0e-12_wp, &
                       'pure translation: alpha')
      ! a rotation of 1e-18 rad: A of order 1e-18, answer as for the linear case
      call gap_coefficients([0.3_wp, -1.0_wp], [0.7_wp, 1.0_wp], [0.0_wp, 0.0_wp], &
                            [0.0_wp, 0.0_wp], [2.0_wp, 0.0_wp], [2.0_wp, 2.0e-18_wp], a, b, c, g1)
      call swept_pair([0.3_wp, -1.0_wp], [0.7_wp, 1.0_wp], [0.0_wp, 0.0_wp], [0.0_wp, 0.0_wp], &
                      [2.0_wp, 0.0_wp], [2.0_wp, 2.0e-18_wp], 0.1_wp, hit, tau, alpha)
      call check(s, a /= 0.0_wp .and. abs(a) < 1.0e-17_wp .and. hit .and. &
                 abs(tau - 0.5_wp) < 1.0e-12_wp, 'tiny rotation: A ~ 1e-18, tau as linear')
      ! grazing from coefficients: b^2 - 4ac = -4e-12 (miss) and +4e-12 (two close roots)
      call first_crossing(1.0_wp, -1.0_wp, 0.25_wp + 1.0e-12_wp, 0.25_wp, hit, tau)
      call check(s, .not. hit, 'grazing, discriminant slightly negative: no contact')
      c = 0.25_wp - 1.0e-12_wp
      call first_crossing(1.0_wp, -1.0_wp, c, 0.25_wp, hit, tau)
      call check(s, hit .and. abs(tau - 0.5_wp*(1.0_wp - sqrt(1.0_wp - 4.0_wp*c))) < 1.0e-15_wp &
                 .and. abs(tau - (0.5_wp - 1.0e-6_wp)) < 1.0e-10_wp, &
                 'grazing, discriminant slightly positive: first root')
      ! grazing geometry: rotating segment, g = 2 (tau - 1/2)^2 + dlt; shift v keeps A, B
      do k = -1, 1, 2
         dlt = k*1.0e-12_wp
         v = [dlt, -dlt]
         call swept_pair([0.0_wp, -0.5_wp] + v, [0.5_wp, 1.0_wp] + v, [0.0_wp, 0.0_wp], &
                         [0.0_wp, 0.0_wp], [1.0_wp, 0.0_wp], [0.0_wp, 1.0_wp], 0.1_wp, &
                         hit, tau, alpha)
         if (dlt > 0.0_wp) then
            call check(s, .not. hit, 'grazing geometry, clear by 1e-12: no contact')
         else
            call check(s, hit .and. abs(tau - (0.5_wp - sqrt(0.5e-12_wp))) < 1.0e-10_wp, &
                       'grazing geometry, touching by 1e-12: first root')
         end if
      end do
      call first_crossing(1.0_wp, -2.0_wp, 0.0_wp, -1.0_wp, hit, tau)
      call check(s, .not. hit, 'first_crossing needs a positive start gap')
   end subroutine test_robustness

   !> A thin plate (thickness 0.01) crossed entirely within one step.
   subroutine test_thin_target(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 5), x1(2, 5), snrm(2, 1)
      integer :: seg(2, 2), link(2, 2), cand(2, 2)
      type(contact_set_t) :: cs

      call section(s, 'contact geometry: fast thin target, swept vs static')
      ! nodes 1-4: plate corners; node 5: slave. top face 2 -> 1 (normal +y), bottom 3 -> 4
      x0(:, 1) = [0.0_wp, 0.01_wp]; x0(:, 2) = [2.0_wp, 0.01_wp]
      x0(:, 3) = [0.0_wp, 0.0_wp]; x0(:, 4) = [2.0_wp, 0.0_wp]
      x0(:, 5) = [1.0_wp, 1.0_wp]
      x1 = x0
      x1(:, 5) = [1.0_wp, -1.0_wp]
      seg(:, 1) = [2, 1]
      seg(:, 2) = [3, 4]
      link = 0
      cand(:, 1) = [1, 1]
      cand(:, 2) = [1, 2]
      snrm = 0.0_wp
      call detect_contacts(cs, DETECT_SWEPT, 5, x0, x1, 1, [5], snrm, 2, seg, link, 2, cand, &
                           0.005_wp, FACING_LIMIT)
      call check(s, cs%n == 1, 'swept: one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 1 .and. all(cs%master(:, 1) == [2, 1]), 'swept: front face')
         call check_close(s, cs%tau(1), 0.495_wp, 1.0e-12_wp, 'swept: tau at the front face')
         call check_close(s, cs%gap(1), -1.01_wp, 1.0e-12_wp, 'swept: predicted gap at t(n+2)')
         call check(s, maxval(abs(cs%normal(:, 1) - [0.0_wp, 1.0_wp])) == 0.0_wp, &
                    'swept: frozen normal of the front face')
      end if
      call detect_contacts(cs, DETECT_STATIC, 5, x0, x1, 1, [5], snrm, 2, seg, link, 2, cand, &
                           0.005_wp, FACING_LIMIT)
      call check(s, cs%n == 0, 'static: passed through, nothing found')
   end subroutine test_thin_target

   !> Slave landing on a master node shared by two segments; facing test at a corner.
   subroutine test_corner(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 4), x1(2, 4), snrm(2, 1), navg(2), r
      integer :: seg(2, 2), segr(2, 2), link(2, 2), linkr(2, 2), cand(2, 2)
      type(contact_set_t) :: cs, cr
      logical :: same

      call section(s, 'contact geometry: corner rule and facing test')
      ! master: 1 (1,-0.5) -> 2 (0,0) -> 3 (-2,-0.5), body below; slave 4 drops onto node 2
      x0(:, 1) = [1.0_wp, -0.5_wp]; x0(:, 2) = [0.0_wp, 0.0_wp]; x0(:, 3) = [-2.0_wp, -0.5_wp]
      x0(:, 4) = [0.0_wp, 1.0_wp]
      x1 = x0
      x1(:, 4) = [0.0_wp, -0.5_wp]
      seg(:, 1) = [1, 2]; seg(:, 2) = [2, 3]
      segr(:, 1) = seg(:, 2); segr(:, 2) = seg(:, 1)
      call segment_links(2, seg, link)
      call segment_links(2, segr, linkr)
      cand(:, 1) = [1, 1]; cand(:, 2) = [1, 2]
      snrm = 0.0_wp
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call detect_contacts(cr, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, segr, linkr, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      navg = average_normal(segment_normal(x1(:, 1), x1(:, 2)), segment_normal(x1(:, 2), x1(:, 3)))
      call check(s, cs%n == 1 .and. cr%n == 1, 'one contact in both segment orders')
      if (cs%n == 1 .and. cr%n == 1) then
         call check(s, cs%at_end(1) .and. cr%at_end(1), 'contact flagged at a segment end')
         call check(s, cs%master(nint(1.0_wp + cs%alpha(1)), 1) == 2, 'contact point is node 2')
         call check(s, maxval(abs(cs%normal(:, 1) - navg)) < 1.0e-15_wp, &
                    'averaged master node normal')
         same = all(cs%master(:, 1) == cr%master(:, 1)) .and. cs%alpha(1) == cr%alpha(1) .and. &
                all(cs%normal(:, 1) == cr%normal(:, 1)) .and. cs%tau(1) == cr%tau(1) .and. &
                cs%gap(1) == cr%gap(1)
         call check(s, same, 'identical choice when the segment order is reversed')
         call check_close(s, cs%tau(1), 2.0_wp/3.0_wp, 1.0e-12_wp, 'corner: tau')
      end if
      ! flat surface: both segments give the same tau and gap; node numbers decide
      x0(:, 1) = [1.0_wp, 0.0_wp]; x0(:, 2) = [0.0_wp, 0.0_wp]; x0(:, 3) = [-1.0_wp, 0.0_wp]
      x0(:, 4) = [0.0_wp, 1.0_wp]
      x1 = x0
      x1(:, 4) = [0.0_wp, -1.0_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call detect_contacts(cr, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, segr, linkr, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      same = cs%n == 1 .and. cr%n == 1
      if (same) same = all(cs%master(:, 1) == [1, 2]) .and. all(cr%master(:, 1) == [1, 2]) .and. &
                       cs%alpha(1) == 1.0_wp .and. cr%alpha(1) == 1.0_wp .and. &
                       all(cs%normal(:, 1) == [0.0_wp, 1.0_wp]) .and. &
                       all(cr%normal(:, 1) == [0.0_wp, 1.0_wp])
      call check(s, same, 'exact tie: lower node pair wins in both segment orders')
      ! equal-height bodies: slave corner (0.9,1) -> (1.1,1) meets master corner (1,1);
      ! master top face 1 -> 2 from (2,1) to (1,1), side face 2 -> 3 from (1,1) to (1,0)
      x0(:, 1) = [2.0_wp, 1.0_wp]; x0(:, 2) = [1.0_wp, 1.0_wp]; x0(:, 3) = [1.0_wp, 0.0_wp]
      x0(:, 4) = [0.9_wp, 1.0_wp]
      x1 = x0
      x1(:, 4) = [1.1_wp, 1.0_wp]
      r = sqrt(0.5_wp)
      snrm(:, 1) = [r, r]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1, 'corner on corner: one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 2 .and. cs%at_end(1) .and. cs%alpha(1) == 0.0_wp, &
                    'corner on corner: side face, at its end')
         call check(s, all(cs%normal(:, 1) == [-1.0_wp, 0.0_wp]), &
                    'corner on corner: top face (not faced) left out of the node normal')
         call check_close(s, cs%tau(1), 0.5_wp, 1.0e-12_wp, 'corner on corner: tau')
      end if
      snrm = 0.0_wp
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1 .and. maxval(abs(cs%normal(:, 1) - [-r, r])) < 1.0e-15_wp, &
                 'corner on corner without slave normal: averaged node normal')
      ! slave corner already past the master corner, sliding in: top face is the closest
      ! without the facing test, the side face with it
      x0(:, 4) = [1.05_wp, 1.0_wp]
      x1(:, 4) = [1.1_wp, 0.99_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1 .and. cs%seg(1) == 1 .and. .not. cs%at_end(1), &
                 'no slave normal: top face (least penetrated)')
      snrm(:, 1) = [r, r]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1 .and. cs%seg(1) == 2 .and. all(cs%normal(:, 1) == [-1.0_wp, 0.0_wp]), &
                 'slave corner normal (1,1): top face rejected, side face kept')
   end subroutine test_corner

   !> The facing rule's side test (doc/contact-detection.md, "Facing test", F.1): the convex
   !> corner of a crushed element (scene 82 of seed 20261229) crossing a wall. Master: the wall
   !> face 1 (0,0) -> 2 (0,1), normal (1,0). Slave surface: the sliver 7 (0.1,0.4) -> 5 -> 6
   !> (5e-4,0.1) -> 7, whose corner 5 (5e-4,0.5) has the segments 7 -> 5 (normal (1,1)/sqrt 2)
   !> and 5 -> 6 (normal (-1,0), lying on the wall), so its node normal (-0.38, 0.92) gives
   !> -0.38 with the wall's: not below cos(120 degrees). Node 5 moves to (-1e-3, 0.52) in the
   !> step and crosses the wall at tau = 1/3.
   subroutine test_facing_sides(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: FACING = -0.5_wp   ! the contact step's (src/exic/contact/contact.f90)
      real(wp) :: x0(2, 7), x1(2, 7), snrm(2, 1), r
      integer :: mseg(2, 1), mlink(2, 1), sseg(2, 3), cand(2, 1), head(2), segs(2)
      type(contact_set_t) :: cs

      call section(s, 'contact geometry: facing rule, side test at a convex corner')
      x0 = 0.0_wp
      x0(:, 1) = [0.0_wp, 0.0_wp]; x0(:, 2) = [0.0_wp, 1.0_wp]
      x0(:, 5) = [5.0e-4_wp, 0.5_wp]; x0(:, 6) = [5.0e-4_wp, 0.1_wp]; x0(:, 7) = [0.1_wp, 0.4_wp]
      x1 = x0
      x1(:, 5) = [-1.0e-3_wp, 0.52_wp]
      mseg(:, 1) = [1, 2]; mlink = 0
      sseg(:, 1) = [7, 5]; sseg(:, 2) = [5, 6]; sseg(:, 3) = [6, 7]
      ! slave 1 (node 5): its segments 1 and 2
      head = [1, 3]; segs = [1, 2]
      cand(:, 1) = [1, 1]
      snrm(:, 1) = average_normal(segment_normal(x0(:, 7), x0(:, 5)), segment_normal(x0(:, 5), x0(:, 6)))
      call check(s, dot_product(snrm(:, 1), [1.0_wp, 0.0_wp]) > FACING, &
                 'the corner''s node normal fails the facing limit')
      call detect_contacts(cs, DETECT_SWEPT, 7, x0, x1, 1, [5], snrm, 1, mseg, mlink, 1, cand, &
                           0.1_wp, FACING)
      call check(s, cs%n == 0, 'node normal alone: the crossing is missed')
      call detect_contacts(cs, DETECT_SWEPT, 7, x0, x1, 1, [5], snrm, 1, mseg, mlink, 1, cand, &
                           0.1_wp, FACING, fseg=sseg, fhead=head, fsegs=segs)
      call check(s, cs%n == 1, 'side test (normals given): one contact')
      if (cs%n == 1) then
         call check_close(s, cs%tau(1), 1.0_wp/3.0_wp, 1.0e-12_wp, 'side test: tau of the crossing')
         call check(s, cs%gap(1) < 0.0_wp .and. all(cs%normal(:, 1) == [1.0_wp, 0.0_wp]), &
                    'side test: the wall normal, gap closed by the corrector')
      end if
      snrm = 0.0_wp
      call detect_contacts(cs, DETECT_SWEPT, 7, x0, x1, 1, [5], snrm, 1, mseg, mlink, 1, cand, &
                           0.1_wp, FACING, 3, sseg, head, segs)
      call check(s, cs%n == 1, 'side test (normals formed in the narrow phase): one contact')
      if (cs%n == 1) call check_close(s, cs%tau(1), 1.0_wp/3.0_wp, 1.0e-12_wp, &
                                      'side test (normals formed): tau of the crossing')
      ! equal-height bodies: a block's corner 5 (1.05, 1) sliding in over the other block's top
      ! face 1 (2,1) -> 2 (1,1), normal (0,1); the corner's segments 5 -> 7 (top, normal (0,1))
      ! and 6 -> 5 (side, normal (1,0)): neither faces the top face, still rejected
      x0 = 0.0_wp
      x0(:, 1) = [2.0_wp, 1.0_wp]; x0(:, 2) = [1.0_wp, 1.0_wp]
      x0(:, 5) = [1.05_wp, 1.0_wp]; x0(:, 6) = [1.05_wp, 0.0_wp]; x0(:, 7) = [0.05_wp, 1.0_wp]
      x1 = x0
      x1(:, 5) = [1.1_wp, 0.99_wp]
      sseg(:, 1) = [5, 7]; sseg(:, 2) = [6, 5]; sseg(:, 3) = [7, 6]
      r = sqrt(0.5_wp)
      snrm(:, 1) = [r, r]
      call detect_contacts(cs, DETECT_SWEPT, 7, x0, x1, 1, [5], snrm, 1, mseg, mlink, 1, cand, &
                           0.1_wp, FACING, fseg=sseg, fhead=head, fsegs=segs)
      call check(s, cs%n == 0, 'block corner over the top face of a block of equal height: rejected')
   end subroutine test_facing_sides

   !> The vertex rule (doc/contact-detection.md, "Vertex rule", V.1-V.2). (a) The corner of a
   !> projectile in the dent it made in a plate (the erosion family's 2x2 elastic plates): the
   !> plate's surface 1 (0,1) -> 2 (0,0) -> 3 (-1,0) (body x > 0 or y < 0, a concave corner at
   !> 2); slave 4 at (1e-4, -1e-4), behind both lines, moving to (2e-4, -3e-4), projects past
   !> node 2 on both segments (alpha 1 + 1e-4 and -1e-4): paired with node 2, along the unit
   !> vector from its predicted position to node 2 (the concave rule's C.3). (b) A block's convex corner 2 (0,0) of the surface 1 (0,-1) -> 2 -> 3 (-1,0)
   !> (body x < 0 and y < 0); slave 4 passing it outside, (1e-4, 1e-4) -> (1e-4, -2e-4), crosses
   !> the top face's line past node 2 but not the side face's: no contact.
   subroutine test_vertex_rule(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 4), x1(2, 4), snrm(2, 1)
      integer :: seg(2, 2), link(2, 2), cand(2, 2)
      type(contact_set_t) :: cs

      call section(s, 'contact geometry: vertex rule at a master node')
      seg(:, 1) = [1, 2]; seg(:, 2) = [2, 3]
      call segment_links(2, seg, link)
      cand(:, 1) = [1, 1]; cand(:, 2) = [1, 2]
      snrm = 0.0_wp
      x0(:, 1) = [0.0_wp, 1.0_wp]; x0(:, 2) = [0.0_wp, 0.0_wp]; x0(:, 3) = [-1.0_wp, 0.0_wp]
      x0(:, 4) = [1.0e-4_wp, -1.0e-4_wp]
      x1 = x0
      x1(:, 4) = [2.0e-4_wp, -3.0e-4_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1, 'past node 2 on both segments, behind both lines: one contact')
      if (cs%n == 1) then
         call check(s, cs%at_end(1) .and. cs%master(nint(1.0_wp + cs%alpha(1)), 1) == 2, &
                    'the contact point is the master node 2')
         call check(s, maxval(abs(cs%normal(:, 1) - [-2.0_wp, 3.0_wp]/sqrt(13.0_wp))) < 1.0e-15_wp, &
                    'the normal from the predicted slave to node 2, in the cone of the two normals (C.3)')
         call check_close(s, cs%gap(1), -sqrt(13.0e-8_wp), 1.0e-18_wp, &
                          'predicted gap from node 2 along it: minus the distance')
         call check(s, cs%tau(1) == 0.0_wp, 'in contact from the start of the step')
      end if
      x0(:, 1) = [0.0_wp, -1.0_wp]; x0(:, 2) = [0.0_wp, 0.0_wp]; x0(:, 3) = [-1.0_wp, 0.0_wp]
      x0(:, 4) = [1.0e-4_wp, 1.0e-4_wp]
      x1 = x0
      x1(:, 4) = [1.0e-4_wp, -2.0e-4_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 0, 'a slave passing a convex corner outside it: no contact')
   end subroutine test_vertex_rule

   ! ----------------------------------------------------------- broad phase

   !> Random scene: nseg segments (length ~0.5) and nsl free slave nodes in a 10 x 10 box.
   subroutine random_scene(g, nsl, nseg, x0, x1, seg, slaves)
      type(lcg_t), intent(inout) :: g
      integer, intent(in) :: nsl, nseg
      real(wp), allocatable, intent(out) :: x0(:, :), x1(:, :)
      integer, allocatable, intent(out) :: seg(:, :), slaves(:)
      integer :: k, n
      real(wp) :: ang
      n = 2*nseg + nsl
      allocate (x0(2, n), x1(2, n), seg(2, nseg), slaves(nsl))
      do k = 1, nseg
         x0(:, 2*k - 1) = [rnd(g, 0.0_wp, 10.0_wp), rnd(g, 0.0_wp, 10.0_wp)]
         ang = rnd(g, 0.0_wp, 6.2831853_wp)
         x0(:, 2*k) = x0(:, 2*k - 1) + rnd(g, 0.1_wp, 0.8_wp)*[cos(ang), sin(ang)]
         seg(:, k) = [2*k - 1, 2*k]
      end do
      do k = 2*nseg + 1, n
         x0(:, k) = [rnd(g, 0.0_wp, 10.0_wp), rnd(g, 0.0_wp, 10.0_wp)]
      end do
      do k = 1, n
         x1(:, k) = x0(:, k) + [rnd(g, -0.3_wp, 0.3_wp), rnd(g, -0.3_wp, 0.3_wp)]
      end do
      slaves = [(2*nseg + k, k=1, nsl)]
   end subroutine random_scene

   subroutine test_broad_random(s)
      type(suite_t), intent(inout) :: s
      type(lcg_t) :: g
      type(broad_t) :: bw
      type(contact_set_t) :: c1, c2
      real(wp), allocatable :: x0(:, :), x1(:, :), snrm(:, :)
      integer, allocatable :: seg(:, :), slaves(:), cand(:, :), link(:, :)
      integer :: scene, ncand, nsl, nseg, k
      logical :: ok

      call section(s, 'contact geometry: broad phase against brute force')
      do scene = 1, 3
         nsl = 60*scene
         nseg = 150 - 40*scene
         call random_scene(g, nsl, nseg, x0, x1, seg, slaves)
         call broad_search(bw, size(x0, 2), x0, x1, nsl, slaves, nseg, seg, 0.05_wp)
         call broad_brute(size(x0, 2), x0, x1, nsl, slaves, nseg, seg, 0.05_wp, ncand, cand)
         ok = bw%ncand == ncand .and. ncand > 0
         if (ok) ok = all(bw%cand(:, 1:ncand) == cand(:, 1:ncand))
         call check(s, ok, 'random scene: same candidate list as brute force')
      end do
      ! self contact: slaves are the segment nodes themselves (chains of segments)
      do scene = 1, 2
         call random_scene(g, 0, 120, x0, x1, seg, slaves)
         seg(2, 1:119) = seg(1, 2:120)
         slaves = [(k, k=1, size(x0, 2))]
         call broad_search(bw, size(x0, 2), x0, x1, size(slaves), slaves, 120, seg, 0.02_wp)
         call broad_brute(size(x0, 2), x0, x1, size(slaves), slaves, 120, seg, 0.02_wp, ncand, cand)
         ok = bw%ncand == ncand .and. ncand > 0
         if (ok) ok = all(bw%cand(:, 1:ncand) == cand(:, 1:ncand))
         if (ok) ok = all(slaves(cand(1, 1:ncand)) /= seg(1, cand(2, 1:ncand)) .and. &
                          slaves(cand(1, 1:ncand)) /= seg(2, cand(2, 1:ncand)))
         call check(s, ok, 'self contact: same list, no node paired with its own segment')
      end do
      ! narrow phase gives the same contacts from either candidate list
      call random_scene(g, 400, 200, x0, x1, seg, slaves)
      allocate (snrm(2, 400), link(2, 200))
      snrm = 0.0_wp
      link = 0
      call broad_search(bw, size(x0, 2), x0, x1, 400, slaves, 200, seg, 0.05_wp)
      call broad_brute(size(x0, 2), x0, x1, 400, slaves, 200, seg, 0.05_wp, ncand, cand)
      call detect_contacts(c1, DETECT_SWEPT, size(x0, 2), x0, x1, 400, slaves, snrm, 200, seg, &
                           link, bw%ncand, bw%cand, 0.05_wp, FACING_LIMIT)
      call detect_contacts(c2, DETECT_SWEPT, size(x0, 2), x0, x1, 400, slaves, snrm, 200, seg, &
                           link, ncand, cand, 0.05_wp, FACING_LIMIT)
      ok = c1%n == c2%n .and. c1%n > 0
      if (ok) ok = all(c1%slave(1:c1%n) == c2%slave(1:c1%n)) .and. &
                   all(c1%seg(1:c1%n) == c2%seg(1:c1%n))
      call check(s, ok, 'random scene: same swept contacts via broad phase and brute force')
      ! whole-surface test: shift the slaves far away
      x0(1, slaves) = x0(1, slaves) + 100.0_wp
      x1(1, slaves) = x1(1, slaves) + 100.0_wp
      call broad_search(bw, size(x0, 2), x0, x1, 400, slaves, 200, seg, 0.05_wp)
      call check(s, surfaces_apart(size(x0, 2), x0, x1, 400, slaves, 200, seg, 0.05_wp) .and. &
                 bw%ncand == 0 .and. bw%ntests == 0, 'surfaces apart: skipped without tests')
   end subroutine test_broad_random

   !> The kept list (broad_search_kept) against the grid search at every step of random
   !> motions: small drifts (the list is reused) and jumps past the skin (it is built again).
   subroutine test_broad_kept(s)
      type(suite_t), intent(inout) :: s
      type(lcg_t) :: g
      type(broad_t) :: bk, bg
      real(wp), allocatable :: x0(:, :), x1(:, :), v(:, :)
      integer, allocatable :: seg(:, :), slaves(:)
      integer :: step, n, k, nsame, nfound
      logical :: same

      call section(s, 'contact geometry: kept broad-phase list')
      call random_scene(g, 200, 120, x0, x1, seg, slaves)
      n = size(x0, 2)
      allocate (v(2, n))
      do k = 1, n
         v(:, k) = [rnd(g, -1.0_wp, 1.0_wp), rnd(g, -1.0_wp, 1.0_wp)]*2.0e-3_wp
      end do
      nsame = 0
      nfound = 0
      do step = 1, 400
         x0 = x0 + v
         x1 = x0 + v*rnd(g, 0.5_wp, 1.5_wp)
         ! every 50th step one node jumps by half the scene's segment length
         if (mod(step, 50) == 0) then
            x0(:, 1 + mod(7*step, n)) = x0(:, 1 + mod(7*step, n)) + 0.25_wp
            x1(:, 1 + mod(7*step, n)) = x1(:, 1 + mod(7*step, n)) + 0.25_wp
         end if
         call broad_search(bg, n, x0, x1, 200, slaves, 120, seg, 0.05_wp)
         call broad_search_kept(bk, n, x0, x1, 200, slaves, 120, seg, 0.05_wp)
         same = bk%ncand == bg%ncand
         if (same) same = all(bk%cand(:, 1:bk%ncand) == bg%cand(:, 1:bg%ncand))
         if (same) nsame = nsame + 1
         nfound = nfound + bg%ncand
      end do
      call check(s, nsame == 400 .and. nfound > 400, &
                 'kept list: the pairs of the grid search, in its order, at each of 400 steps')
      call check(s, bk%nbuilds >= 8 .and. bk%nkept_steps >= 200, &
                 'kept list: reused between builds, built again past the skin')
   end subroutine test_broad_kept

   !> n separated (slave, segment) pairs on a row; work must grow like n, not n^2.
   subroutine test_broad_scaling(s)
      type(suite_t), intent(inout) :: s
      type(broad_t) :: bw
      integer(i8) :: tests(2)
      integer :: ncand(2), m, n, k
      real(wp), allocatable :: x0(:, :), x1(:, :)
      integer, allocatable :: seg(:, :), slaves(:)

      call section(s, 'contact geometry: broad phase work scaling')
      do m = 1, 2
         n = 100*10**(m - 1)
         if (allocated(x0)) deallocate (x0, x1, seg, slaves)
         allocate (x0(2, 3*n), x1(2, 3*n), seg(2, n), slaves(n))
         do k = 1, n
            x0(:, 3*k - 2) = [10.0_wp*k, 0.0_wp]
            x0(:, 3*k - 1) = [10.0_wp*k + 1.0_wp, 0.0_wp]
            x0(:, 3*k) = [10.0_wp*k + 0.5_wp, 0.1_wp]
            seg(:, k) = [3*k - 1, 3*k - 2]
            slaves(k) = 3*k
         end do
         x1 = x0
         x1(2, slaves) = -0.1_wp
         call broad_search(bw, 3*n, x0, x1, n, slaves, n, seg, 0.01_wp)
         tests(m) = bw%ntests
         ncand(m) = bw%ncand
      end do
      call check(s, ncand(1) == 100 .and. ncand(2) == 1000, 'one candidate per pair')
      call check(s, tests(2) <= 15_i8*tests(1), 'box tests grow linearly with the scene')
      call check(s, tests(2) <= 5_i8*1000_i8, 'box tests far below n_slave x n_segment')
   end subroutine test_broad_scaling

   !> nb closed polygons of m nodes (radius 0.5, nodes numbered body after body, bodies on a
   !> jittered grid of pitch `pitch`), moved at random by up to `move`.
   subroutine polygons(g, nb, m, pitch, move, x0, x1, seg)
      type(lcg_t), intent(inout) :: g
      integer, intent(in) :: nb, m
      real(wp), intent(in) :: pitch, move
      real(wp), allocatable, intent(out) :: x0(:, :), x1(:, :)
      integer, allocatable, intent(out) :: seg(:, :)
      integer :: b, k, nrow
      real(wp) :: c(2), ang
      allocate (x0(2, nb*m), x1(2, nb*m), seg(2, nb*m))
      nrow = max(1, int(sqrt(real(nb, wp))))
      do b = 1, nb
         c = pitch*[real(mod(b - 1, nrow), wp), real((b - 1)/nrow, wp)] + &
             [rnd(g, -0.1_wp, 0.1_wp), rnd(g, -0.1_wp, 0.1_wp)]
         do k = 1, m
            ang = 6.2831853_wp*(k - 1)/m
            x0(:, (b - 1)*m + k) = c + 0.5_wp*[cos(ang), sin(ang)]
            seg(:, (b - 1)*m + k) = [(b - 1)*m + k, (b - 1)*m + mod(k, m) + 1]
         end do
      end do
      do k = 1, nb*m
         x1(:, k) = x0(:, k) + [rnd(g, -move, move), rnd(g, -move, move)]
      end do
   end subroutine polygons

   !> The search over all surfaces gives, for every ordered pair of surfaces, exactly the
   !> candidate list of broad_brute on that pair (none: no group), in the order of the pairs.
   subroutine test_broad_all(s)
      type(suite_t), intent(inout) :: s
      type(lcg_t) :: g
      type(broad_all_t) :: ba, bb
      real(wp), allocatable :: x0(:, :), x1(:, :)
      integer, allocatable :: seg(:, :), cand(:, :)
      integer :: scene, nb, m, i, j, ncand, grp, nexp, k
      integer(i8) :: tests(2)
      logical :: ok, order

      call section(s, 'contact geometry: one broad phase over all surfaces')
      do scene = 1, 3
         nb = 9*scene
         m = 6 + 4*scene
         call polygons(g, nb, m, 1.05_wp, 0.04_wp*scene, x0, x1, seg)
         ba = broad_all_t()
         do i = 1, nb
            call ba%add_surface([((i - 1)*m + k, k=1, m)], seg(:, (i - 1)*m + 1:i*m))
         end do
         call ba%search(nb*m, x0, x1, 0.02_wp)
         ok = .true.
         nexp = 0
         grp = 0
         do i = 1, nb
            do j = 1, nb
               if (i == j) cycle
               call broad_brute(nb*m, x0, x1, m, [((i - 1)*m + k, k=1, m)], m, &
                                seg(:, (j - 1)*m + 1:j*m), 0.02_wp, ncand, cand)
               if (ncand == 0) cycle
               nexp = nexp + 1
               grp = grp + 1
               if (grp > ba%ngroup) then
                  ok = .false.
                  cycle
               end if
               if (ba%gslave(grp) /= i .or. ba%gmaster(grp) /= j .or. &
                   ba%gfirst(grp + 1) - ba%gfirst(grp) /= ncand) then
                  ok = .false.
                  cycle
               end if
               if (any(ba%gcand(:, ba%gfirst(grp):ba%gfirst(grp + 1) - 1) /= cand(:, 1:ncand))) ok = .false.
            end do
         end do
         call check(s, ok .and. ba%ngroup == nexp .and. nexp > 0, &
                    'polygon scene '//achar(48 + scene)//': every pair''s candidates as brute force, in pair order')
      end do
      ! bodies far apart: no group; the work grows like the number of bodies
      order = .true.
      do scene = 1, 2
         nb = 100*10**(scene - 1)
         call polygons(g, nb, 8, 3.0_wp, 0.1_wp, x0, x1, seg)
         bb = broad_all_t()
         do i = 1, nb
            call bb%add_surface([((i - 1)*8 + k, k=1, 8)], seg(:, (i - 1)*8 + 1:i*8))
         end do
         call bb%search(nb*8, x0, x1, 0.02_wp)
         tests(scene) = bb%ntests
         order = order .and. bb%ngroup == 0
      end do
      call check(s, order, 'bodies apart: no pair of surfaces searched')
      call check(s, tests(2) <= 15_i8*tests(1) .and. tests(2) <= 5_i8*1000_i8, &
                 'bodies apart: box tests grow like the number of bodies', &
                 'box tests '//trim(adjustl(i8str(tests(1))))//' -> '//trim(adjustl(i8str(tests(2)))))
   end subroutine test_broad_all

   !> search_kept against search over 300 steps of 25 polygons drifting into each other, with
   !> jumps past the skin: the same groups and candidates at every step.
   subroutine test_broad_all_kept(s)
      type(suite_t), intent(inout) :: s
      type(lcg_t) :: g
      type(broad_all_t) :: bk, bs
      real(wp), allocatable :: x0(:, :), x1(:, :), v(:, :)
      integer, allocatable :: seg(:, :)
      integer :: i, k, step, nsame, ngroups, n
      logical :: same

      call section(s, 'contact geometry: kept list of the search over all surfaces')
      call polygons(g, 25, 12, 1.1_wp, 0.0_wp, x0, x1, seg)
      n = size(x0, 2)
      do i = 1, 25
         call bk%add_surface([((i - 1)*12 + k, k=1, 12)], seg(:, (i - 1)*12 + 1:i*12))
         call bs%add_surface([((i - 1)*12 + k, k=1, 12)], seg(:, (i - 1)*12 + 1:i*12))
      end do
      allocate (v(2, n))
      do i = 1, 25
         ! one velocity per body: bodies drift into and past each other
         v(:, (i - 1)*12 + 1:i*12) = spread([rnd(g, -1.0_wp, 1.0_wp), rnd(g, -1.0_wp, 1.0_wp)]*1.0e-3_wp, 2, 12)
      end do
      nsame = 0
      ngroups = 0
      do step = 1, 300
         x0 = x0 + v
         x1 = x0 + v*rnd(g, 0.5_wp, 1.5_wp)
         if (mod(step, 40) == 0) then
            x0(:, 1 + mod(11*step, n)) = x0(:, 1 + mod(11*step, n)) + 0.2_wp
            x1(:, 1 + mod(11*step, n)) = x1(:, 1 + mod(11*step, n)) + 0.2_wp
         end if
         call bs%search(n, x0, x1, 0.02_wp)
         call bk%search_kept(n, x0, x1, 0.02_wp)
         same = bk%ngroup == bs%ngroup
         if (same .and. bs%ngroup > 0) then
            same = all(bk%gslave(1:bs%ngroup) == bs%gslave(1:bs%ngroup)) .and. &
                   all(bk%gmaster(1:bs%ngroup) == bs%gmaster(1:bs%ngroup)) .and. &
                   all(bk%gfirst(1:bs%ngroup + 1) == bs%gfirst(1:bs%ngroup + 1))
            if (same) same = all(bk%gcand(:, 1:bs%gfirst(bs%ngroup + 1) - 1) == &
                                 bs%gcand(:, 1:bs%gfirst(bs%ngroup + 1) - 1))
         end if
         if (same) nsame = nsame + 1
         ngroups = ngroups + bs%ngroup
      end do
      call check(s, nsame == 300 .and. ngroups > 300, &
                 'kept list: the groups and candidates of the search at each of 300 steps')
      call check(s, bk%nbuilds >= 5 .and. bk%nkept_steps >= 150, &
                 'kept list: reused between builds, built again past the skin')
      call check(s, bk%ngroups_apart > 0, &
                 'kept list: groups whose surfaces are apart skipped (the same candidates)')
      call check(s, bk%nlazy_steps > 0 .and. bk%nlazy_steps < 300, &
                 'kept list: segment boxes formed at first use in some steps, all at once in others', &
                 'steps with boxes at first use: '//i8str(bk%nlazy_steps))
   end subroutine test_broad_all_kept

   function i8str(v) result(t)
      integer(i8), intent(in) :: v
      character(len=24) :: t
      write (t, '(i0)') v
   end function i8str

end module test_contact_geom
