!> The decomposition (src/exic/parallel/): METIS's parts of a mesh's elements and the owners
!> of its nodes. Plain arrays, one process (no MPI needed): the partition is deterministic,
!> every element has one owner in 0 .. P - 1, the node owners follow the fixed rule, element
!> weights move the cut.
module test_parallel
   use testing, only: suite_t, check, section
   use exic_base_error, only: error_t
   use exic_base_strings, only: itoa
   use exic_parallel_partition, only: partition_elements, node_owners
   implicit none
   private

   public :: run_parallel_tests

contains

   subroutine run_parallel_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'parallel: METIS parts of a 40 x 10 mesh and the node owners')
      call grid_tests(s)
   end subroutine run_parallel_tests

   !> nx x ny quadrilaterals numbered row by row, nodes (nx + 1) x (ny + 1).
   subroutine grid(nx, ny, conn)
      integer, intent(in) :: nx, ny
      integer, allocatable, intent(out) :: conn(:, :)
      integer :: i, j, e, n1
      allocate (conn(4, nx*ny))
      e = 0
      do j = 1, ny
         do i = 1, nx
            e = e + 1
            n1 = (j - 1)*(nx + 1) + i
            conn(:, e) = [n1, n1 + 1, n1 + nx + 2, n1 + nx + 1]
         end do
      end do
   end subroutine grid

   subroutine grid_tests(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nx = 40, ny = 10, ne = nx*ny, nn = (nx + 1)*(ny + 1)
      integer, allocatable :: conn(:, :)
      integer :: w(ne), part(ne), again(ne), heavy(ne), node(nn), want(nn), cut, cut2, p, e, a, k
      integer :: load(0:3)
      type(error_t), allocatable :: err
      logical :: ok

      call grid(nx, ny, conn)
      w = 1
      call partition_elements(ne, nn, conn, w, 1, part, cut, err)
      call check(s, .not. allocated(err) .and. all(part == 0) .and. cut == 0, 'one part: every element on rank 0')
      do p = 2, 4
         call partition_elements(ne, nn, conn, w, p, part, cut, err)
         call check(s, .not. allocated(err), itoa(p)//' parts: METIS succeeds')
         if (allocated(err)) return
         call check(s, all(part >= 0 .and. part < p), itoa(p)//' parts: every element has one owner in 0 .. '// &
                    itoa(p - 1))
         ok = .true.
         do k = 0, p - 1
            ok = ok .and. count(part == k) > 0
         end do
         call check(s, ok .and. cut > 0, itoa(p)//' parts: every part holds elements and the cut is not empty ('// &
                    itoa(cut)//' edges)')
         call check(s, maxval([(count(part == k), k=0, p - 1)]) <= nint(1.05*ne/p), itoa(p)// &
                    ' parts: equal weights give parts within 5 % of ne/P')
         call partition_elements(ne, nn, conn, w, p, again, cut2, err)
         call check(s, all(again == part) .and. cut2 == cut, itoa(p)//' parts: the same parts when asked again')
         call node_owners(ne, nn, conn, part, node)
         want = huge(1)
         do e = 1, ne
            do a = 1, 4
               want(conn(a, e)) = min(want(conn(a, e)), part(e))
            end do
         end do
         call check(s, all(node == want), itoa(p)//' parts: every node owned by the smallest owner of its elements')
      end do
      ! weights: the left half 5 times as costly as the right half; 2 parts balance the weight
      heavy = 1
      do e = 1, ne
         if (mod(e - 1, nx) < nx/2) heavy(e) = 5
      end do
      call partition_elements(ne, nn, conn, heavy, 2, part, cut, err)
      load = 0
      do e = 1, ne
         load(part(e)) = load(part(e)) + heavy(e)
      end do
      call check(s, .not. allocated(err) .and. abs(load(0) - load(1)) <= nint(0.05*sum(heavy)), &
                 'weights 5:1 by halves: the 2 parts carry equal weight within 5 % ('//itoa(load(0))//' and '// &
                 itoa(load(1))//')')
      call check(s, abs(count(part == 0) - count(part == 1)) > ne/4, &
                 'weights 5:1 by halves: the element counts of the parts differ (weights honoured)')
      ! a node of no element belongs to rank 0
      call node_owners(1, 6, reshape([2, 3, 4, 5], [4, 1]), [3], want(1:6))
      call check(s, all(want(1:6) == [0, 3, 3, 3, 3, 0]), 'a node of no element is owned by rank 0')
   end subroutine grid_tests

end module test_parallel
