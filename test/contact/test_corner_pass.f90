!> The corners of the corner pass of an NTOS pair (doc/contact-detection.md, "Corner pass of a
!> one-pass pair", K.1): of a pass's candidates, keep_convex_corners keeps the slaves at which
!> their own surface turns convex by 30 degrees or more, and drops the rest in order.
module test_corner_pass
   use exic_base_kinds, only: wp
   use exic_contact_broad, only: broad_t, keep_convex_corners
   use exic_base_strings, only: itoa
   use testing, only: suite_t, check, section
   implicit none
   private

   public :: test_corner_turns

contains

   !> A chain of three nodes, the body on the left: node 1 (-1, 0) -> node 2 (0, 0) -> node 3
   !> (cos theta, sin theta), the surface turning by theta at node 2 (left, convex, for theta > 0).
   !> Candidates: every node against two segments of the other surface. Nodes 1 and 3 are ends of
   !> the chain (one segment) and are never kept; node 2 is kept for theta = 30.001, 90 and 150
   !> degrees, not for 29.999, 0 and -90 (concave).
   subroutine test_corner_turns(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: deg = acos(-1.0_wp)/180.0_wp
      real(wp) :: thetas(6)
      character(len=6), parameter :: names(6) = ['30.001', '90    ', '150   ', '29.999', '0     ', '-90   ']
      logical :: want(6)
      integer :: i
      type(broad_t) :: bw
      real(wp) :: x(2, 3)

      call section(s, 'contact geometry: convex corners of the corner pass (K.1)')
      thetas = [30.001_wp, 90.0_wp, 150.0_wp, 29.999_wp, 0.0_wp, -90.0_wp]
      want = [.true., .true., .true., .false., .false., .false.]
      do i = 1, size(thetas)
         x(:, 1) = [-1.0_wp, 0.0_wp]
         x(:, 2) = [0.0_wp, 0.0_wp]
         x(:, 3) = [cos(thetas(i)*deg), sin(thetas(i)*deg)]
         bw%ncand = 6
         bw%cand = reshape([1, 7, 1, 8, 2, 7, 2, 8, 3, 7, 3, 8], [2, 6])
         call keep_convex_corners(bw, 3, x, 3, [1, 2, 3], reshape([1, 2, 2, 3], [2, 2]), [1, 2, 4, 5], &
                                  [1, 1, 2, 2])
         if (want(i)) then
            call check(s, bw%ncand == 2 .and. all(bw%cand(:, 1:2) == reshape([2, 7, 2, 8], [2, 2])), &
                       'a turn of '//trim(names(i))//' degrees (>= 30): the node is a corner, its '// &
                       'two candidates kept in order', 'candidates left: '//itoa(bw%ncand))
         else
            call check(s, bw%ncand == 0, 'a turn of '//trim(names(i))//' degrees: no corner', &
                       'candidates left: '//itoa(bw%ncand))
         end if
      end do
   end subroutine test_corner_turns

end module test_corner_pass
