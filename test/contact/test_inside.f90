!> Tests of the geometric penetration check (src/exic/contact/inside.f90): depths of nodes
!> inside another body against hand-computed values, the grid search against a brute-force
!> search over every element and boundary edge (at a vertex nearest to two edges, the
!> shorter one measures the depth), the pairs that contact does not cover, and the AUTOmatic
!> set kept per body (allow_auto) against `allow` on every ordered pair of surfaces.
module test_inside
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_mesh_boundary, only: free_edges
   use exic_contact_inside, only: inside_t, point_in_quad
   use testing, only: suite_t, check, check_close, section
   use test_contact_geom, only: block
   implicit none
   private

   public :: run_inside_tests

contains

   subroutine run_inside_tests(s)
      type(suite_t), intent(inout) :: s
      call test_two_blocks(s)
      call test_random_against_brute(s)
      call test_auto_equals_pairs(s)
   end subroutine run_inside_tests

   !> Block A (4 x 4, h = 1) and block B (3 x 3, h = 0.5) from (3.8, 1.1): A's node (4, 2) is
   !> 0.2 inside B (0.4 of B's edge), B's node (3.8, 1.1) 0.2 inside A (0.2 of A's edge).
   subroutine test_two_blocks(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x(2, 25 + 16)
      integer :: conn(4, 16 + 9), body(25)
      type(inside_t) :: ins
      type(error_t), allocatable :: err
      character(len=:), allocatable :: warn
      integer :: all_nodes(41), k
      call section(s, 'inside: two overlapping blocks')
      call block(4, 4, 0.0_wp, 0.0_wp, 1.0_wp, 0, x, conn(:, 1:16))
      call block(3, 3, 3.8_wp, 1.1_wp, 0.5_wp, 25, x, conn(:, 17:25))
      body(1:16) = 7
      body(17:25) = 9
      all_nodes = [(k, k=1, 41)]
      call ins%init(41, 25, conn, body, 1.0e-3_wp, err)
      call check(s, .not. allocated(err), 'init')
      ! no pair allowed yet: nothing checked
      call ins%check(x, 0.5_wp, warn)
      call check(s, ins%last%node == 0 .and. len(warn) == 0 .and. ins%nchecks == 0, 'no pair, no check')
      call ins%allow(all_nodes(26:41), all_nodes(1:25))     ! B's nodes against A only
      call ins%check(x, 0.5_wp, warn)
      call check(s, ins%last%node == 26 .and. ins%last%of_body == 9 .and. ins%last%in_body == 7, &
                 'B node 26 inside A')
      call check_close(s, ins%last%depth, 0.2_wp, 1.0e-12_wp, 'depth of node 26')
      call check_close(s, ins%last%edges, 0.2_wp, 1.0e-12_wp, 'depth of node 26 in A edges')
      call check(s, index(warn, 'node(s) of region 9 are inside region 7') > 0 .and. index(warn, 'node 26') > 0, &
                 'warning names the regions and node', warn)
      call ins%allow(all_nodes(1:25), all_nodes(26:41))
      call ins%check(x, 0.75_wp, warn)
      ! A's node 15 = (4, 2): 0.2 from B's left side, B's edge 0.5
      call check(s, ins%last%node == 15 .and. ins%last%of_body == 7, 'A node 15 inside B is the deepest')
      call check_close(s, ins%last%edges, 0.4_wp, 1.0e-12_wp, 'depth of node 15 in B edges')
      call check(s, index(warn, 'region 7 are inside region 9') > 0 .and. index(warn, 'region 9 are') == 0, &
                 'second check warns only for the new pair', warn)
      call check(s, index(ins%report(), 'region 9 inside region 7 past the limit at 2 of the checks') > 0 .and. &
                 index(ins%report(), 'region 7 inside region 9 past the limit at 1 of the checks') > 0, &
                 'checks past the limit counted', ins%report())
      ! moved apart: nothing inside, the worst of the run is kept
      x(1, 26:41) = x(1, 26:41) + 0.2_wp
      call ins%check(x, 1.0_wp, warn)
      call check(s, ins%last%node == 0 .and. ins%last%edges == 0.0_wp .and. len(warn) == 0, &
                 'touching bodies: nothing inside')
      call check(s, ins%worst%node == 15 .and. abs(ins%worst%t - 0.75_wp) < 1.0e-15_wp, 'worst of the run kept')
   end subroutine test_two_blocks

   !> Two jittered blocks pushed into each other at random: the deepest node and its depth equal
   !> those of a brute-force search (every boundary node against every element and every
   !> boundary edge).
   subroutine test_random_against_brute(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: NX = 12, NN = (NX + 1)**2, NE = NX*NX
      real(wp) :: x(2, 2*NN), r, best, d, len, dist
      integer :: conn(4, 2*NE), body(2*NE), nodes(2*NN), k, trial, n, e, g, bnode
      integer, allocatable :: seg(:, :)
      integer(8) :: state
      type(inside_t) :: ins
      type(error_t), allocatable :: err
      character(len=:), allocatable :: warn
      logical :: ok, inside, onb(2*NN)
      call section(s, 'inside: grid search equals brute force')
      state = 20240611_8  ! Park-Miller minimal standard generator
      ok = .true.
      nodes = [(k, k=1, 2*NN)]
      do trial = 1, 20
         call block(NX, NX, 0.0_wp, 0.0_wp, 1.0_wp/NX, 0, x, conn(:, 1:NE))
         call block(NX, NX, 0.9_wp - 0.05_wp*trial, 0.3_wp, 0.7_wp/NX, NN, x, conn(:, NE + 1:))
         do k = 1, 2*NN
            x(1, k) = x(1, k) + 0.2_wp/NX*(uniform() - 0.5_wp)
            x(2, k) = x(2, k) + 0.2_wp/NX*(uniform() - 0.5_wp)
         end do
         body(1:NE) = 1
         body(NE + 1:) = 2
         call ins%init(2*NN, 2*NE, conn, body, 1.0e-3_wp, err)
         call ins%allow(nodes, nodes)
         call ins%check(x, real(trial, wp), warn)
         ! brute force over the boundary nodes (those the check tests)
         onb = .false.
         do k = 1, 2
            call free_edges(2*NE, conn, body == k, seg, err)
            onb(seg(1, :)) = .true.
            onb(seg(2, :)) = .true.
         end do
         best = 0.0_wp
         bnode = 0
         do n = 1, 2*NN
            if (.not. onb(n)) cycle
            do e = 1, 2*NE
               if (body(e) == merge(1, 2, n <= NN)) cycle
               inside = point_in_quad(x(:, n), x(:, conn(:, e)))
               if (.not. inside) cycle
               call free_edges(2*NE, conn, body == body(e), seg, err)
               d = huge(1.0_wp)
               do g = 1, size(seg, 2)
                  call seg_dist(x(:, n), x(:, seg(1, g)), x(:, seg(2, g)), dist, len)
                  if (dist < d .or. (dist == d .and. dist/len > r)) then
                     d = dist
                     r = dist/len
                  end if
               end do
               if (r > best) then
                  best = r
                  bnode = n
               end if
               exit
            end do
         end do
         if (bnode /= ins%last%node .or. abs(best - ins%last%edges) > 1.0e-14_wp*max(best, 1.0_wp)) ok = .false.
         if (bnode == 0) ok = .false.
      end do
      call check(s, ok, '20 random overlaps: same deepest node and depth')
   contains
      real(wp) function uniform()
         state = modulo(48271_8*state, 2147483647_8)
         uniform = real(state, wp)/2147483647.0_wp
      end function uniform
      subroutine seg_dist(p, a, b, dist, len)
         real(wp), intent(in) :: p(2), a(2), b(2)
         real(wp), intent(out) :: dist, len
         real(wp) :: t
         len = norm2(b - a)
         t = dot_product(p - a, b - a)/len**2
         if (t <= 0.0_wp) then
            dist = norm2(p - a)
         else if (t >= 1.0_wp) then
            dist = norm2(p - b)
         else
            dist = norm2(p - a - t*(b - a))
         end if
      end subroutine seg_dist
   end subroutine test_random_against_brute

   !> Eight blocks of 2 x 2 elements thrown at random into a small square (they overlap), the
   !> last two sharing one surface (their nodes given together, as an AUTOmatic surface of a
   !> region whose nodes another region numbers); a seventh surface of one block's nodes only.
   !> allow_auto surface by surface must check exactly what `allow` on every ordered pair of
   !> surfaces checks: the same deepest node, warnings and report over three checks, 30 scenes.
   subroutine test_auto_equals_pairs(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: NB = 8, NPB = 9, NEB = 4
      real(wp) :: x(2, NB*NPB)
      integer :: conn(4, NB*NEB), body(NB*NEB), k, j, trial, b, first(8), last(8), nsurf
      integer(8) :: state
      type(inside_t) :: by_pairs, by_auto
      type(error_t), allocatable :: err
      character(len=:), allocatable :: w1, w2
      logical :: ok
      integer :: nwarn
      call section(s, 'inside: AUTOmatic set per body equals every pair of surfaces')
      state = 20261124_8
      ok = .true.
      nwarn = 0
      ! surfaces: blocks 1-6 one each, blocks 7 and 8 together
      nsurf = 7
      first = [(1 + (k - 1)*NPB, k=1, 8)]
      last = [(k*NPB, k=1, 8)]
      last(7) = NB*NPB
      do trial = 1, 30
         do b = 1, NB
            call block(2, 2, 3.0_wp*uniform(), 3.0_wp*uniform(), 0.5_wp, (b - 1)*NPB, x, &
                       conn(:, (b - 1)*NEB + 1:b*NEB))
            body((b - 1)*NEB + 1:b*NEB) = 10*b
         end do
         call by_pairs%init(NB*NPB, NB*NEB, conn, body, 1.0e-3_wp, err)
         call by_auto%init(NB*NPB, NB*NEB, conn, body, 1.0e-3_wp, err)
         do k = 1, nsurf
            call by_auto%allow_auto(nodes_of(k))
            do j = 1, nsurf
               if (j /= k) call by_pairs%allow(nodes_of(k), nodes_of(j))
            end do
         end do
         do k = 1, 3
            call by_pairs%check(x, real(k, wp), w1)
            call by_auto%check(x, real(k, wp), w2)
            if (w1 /= w2 .or. by_pairs%last%node /= by_auto%last%node .or. &
                by_pairs%last%edges /= by_auto%last%edges) ok = .false.
            if (len(w1) > 0) nwarn = nwarn + 1
            x(1, 1:NPB) = x(1, 1:NPB) + 0.1_wp
         end do
         ! the report without its first line (the wall time of the checks)
         if (after_first(by_pairs%report()) /= after_first(by_auto%report())) ok = .false.
      end do
      call check(s, ok, '30 scenes: same deepest nodes, warnings and reports')
      call check(s, nwarn > 0, 'the scenes overlap (warnings were given)')
   contains
      function after_first(text) result(rest)
         character(len=*), intent(in) :: text
         character(len=:), allocatable :: rest
         rest = text(index(text, new_line('a')) + 1:)
      end function after_first
      function nodes_of(k) result(nodes)
         integer, intent(in) :: k
         integer, allocatable :: nodes(:)
         integer :: i
         nodes = [(i, i=first(k), last(k))]
      end function nodes_of
      real(wp) function uniform()
         state = modulo(48271_8*state, 2147483647_8)
         uniform = real(state, wp)/2147483647.0_wp
      end function uniform
   end subroutine test_auto_equals_pairs

end module test_inside
