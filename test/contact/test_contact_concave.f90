!> The concave rule of the swept narrow phase (doc/contact-detection.md, "A node sliding into a
!> master's concave corner", C.1-C.3): a slave near a concave master node takes the point of the
!> master's outside wedge closest to its predicted position; convex corners are left as they were.
!>
!> The master is a valley: node 1 -> node 2 (0, 0) -> node 3, segment 1 (1 -> 2) and segment 2
!> (2 -> 3), the body below (on the left of each segment), the surface turning right at node 2;
!> its mirror is a ridge (convex). Slave node 4, its body above; every expected value is worked
!> out by hand in the comments.
module test_contact_concave
   use exic_base_kinds, only: wp
   use exic_contact_spec, only: DETECT_SWEPT
   use exic_mesh_boundary, only: segment_links
   use exic_contact_detect, only: contact_set_t, detect_contacts, FACING_LIMIT
   use testing, only: suite_t, check, check_close, section
   implicit none
   private

   public :: run_contact_concave_tests

contains

   subroutine run_contact_concave_tests(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 4), x1(2, 4), snrm(2, 1), navg(2), r
      integer :: seg(2, 2), link(2, 2), cand(2, 2)
      type(contact_set_t) :: cs

      r = sqrt(0.5_wp)
      seg(:, 1) = [1, 2]; seg(:, 2) = [2, 3]
      call segment_links(2, seg, link)
      cand(:, 1) = [1, 1]; cand(:, 2) = [1, 2]
      snrm(:, 1) = [0.0_wp, -1.0_wp]          ! the slave's body above, facing down
      x0(:, 2) = [0.0_wp, 0.0_wp]

      ! (C.1) A shallow valley as under a punch's corner, node 1 (1, 0.5) -> node 2 (0, 0) -> node 3
      ! (-1, 0): segment 1 rises at 26.6 degrees, segment 2 is flat. On segment 1 at (0.02, 0.01)
      ! (alpha 0.98, on its line), predicted at (-0.01, -0.006): in contact with segment 1 from the
      ! start, its predicted position behind segment 1 and projecting past node 2 (alpha 1.0104) and
      ! on segment 2 at 0.01. Paired with segment 2 there, with its normal (0, 1); gap -0.006.
      ! Before the rule: clamped to node 2 along the average of the two normals.
      call section(s, 'concave rule: sliding past a concave corner onto the next segment (C.1)')
      x0(:, 1) = [1.0_wp, 0.5_wp]; x0(:, 3) = [-1.0_wp, 0.0_wp]
      call slave_moves([0.02_wp, 0.01_wp], [-0.01_wp, -0.006_wp])
      call check(s, cs%n == 1, 'one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 2 .and. .not. cs%at_end(1), 'on segment 2, not at its end')
         call check_close(s, cs%alpha(1), 0.01_wp, 1.0e-12_wp, 'at the projection of the predicted position')
         call check(s, maxval(abs(cs%normal(:, 1) - [0.0_wp, 1.0_wp])) < 1.0e-15_wp, 'with segment 2''s normal')
         call check_close(s, cs%gap(1), -0.006_wp, 1.0e-15_wp, 'predicted gap along it')
         call check(s, cs%tau(1) < 1.0e-12_wp, 'in contact from the start of the step')
      end if

      ! The mirror, a ridge (convex corner) 1 (1, -0.5) -> 2 (0, 0) -> 3 (-1, 0), on segment 1 at
      ! (0.02, -0.01), predicted at (-0.01, -0.006), past node 2 (alpha 1.0056): left as before,
      ! clamped to node 2 along the average of the two normals (0.5, 1) / sqrt 1.25 and (0, 1).
      call section(s, 'concave rule: a convex corner is left as it was')
      x0(:, 1) = [1.0_wp, -0.5_wp]
      call slave_moves([0.02_wp, -0.01_wp], [-0.01_wp, -0.006_wp])
      call check(s, cs%n == 1, 'one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 1 .and. cs%at_end(1) .and. cs%alpha(1) == 1.0_wp, &
                    'on segment 1, clamped to node 2')
         navg = [0.5_wp, 1.0_wp]/sqrt(1.25_wp) + [0.0_wp, 1.0_wp]
         navg = navg/norm2(navg)
         call check(s, maxval(abs(cs%normal(:, 1) - navg)) < 1.0e-15_wp, 'the averaged normal')
      end if

      ! A concave turn of 1e-12 (node 1 at (1, 1e-12), node 3 at (-1, 0)) is straight (below 1e-8): on
      ! segment 1 at (0.02, 0), predicted at (-0.01, -0.006), past node 2, clamped to it as before.
      call section(s, 'concave rule: a turn within the resolution of the coordinates is straight')
      x0(:, 1) = [1.0_wp, 1.0e-12_wp]
      call slave_moves([0.02_wp, 0.0_wp], [-0.01_wp, -0.006_wp])
      call check(s, cs%n == 1, 'one contact')
      if (cs%n == 1) call check(s, cs%seg(1) == 1 .and. cs%at_end(1) .and. cs%alpha(1) == 1.0_wp, &
                                'on segment 1, clamped to node 2')

      ! A right-angled valley, 1 (1, 1) -> 2 (0, 0) -> 3 (-1, 1).
      x0(:, 1) = [1.0_wp, 1.0_wp]; x0(:, 3) = [-1.0_wp, 1.0_wp]

      ! (C.3) On segment 1 at (0.001, 0.001), predicted at (0.002, -0.01): past node 2 on both
      ! segments (d = (0.002, -0.01): d . t_1 = 0.008 > 0, d . t_2 = -0.012 < 0), in the normal
      ! cone of the wedge at node 2. Contact at node 2 along -d / |d| = (-0.2, 1) / sqrt(1.04),
      ! gap -|d| (the averaged normal (0, 1) left the slave 0.002 from node 2, behind segment 1).
      call section(s, 'concave rule: pressed into the corner, the normal towards the node (C.3)')
      call slave_moves([0.001_wp, 0.001_wp], [0.002_wp, -0.01_wp])
      call check(s, cs%n == 1, 'one contact')
      if (cs%n == 1) then
         call check(s, cs%at_end(1) .and. cs%master(nint(1.0_wp + cs%alpha(1)), 1) == 2, &
                    'the contact point is node 2')
         call check(s, maxval(abs(cs%normal(:, 1) - [-0.2_wp, 1.0_wp]/sqrt(1.04_wp))) < 1.0e-15_wp, &
                    'the normal from the predicted slave to node 2')
         call check_close(s, cs%gap(1), -sqrt(1.04e-4_wp), 1.0e-17_wp, 'predicted gap: minus the distance')
      end if

      ! (C.2) Behind segment 2 at (-0.003, -0.001) (by 0.004 / sqrt 2, within the depth, projecting
      ! on it at 0.001) and moving out of its line to (0.004, 0.001): segment 2 does not hold it.
      ! It crosses segment 1's line at tau 0.4, at (-0.0002, -0.0002), past node 2 (alpha 1.0002),
      ! and its predicted position projects on segment 1 at 0.9975, behind it. Caught on segment 1
      ! at 0.9975, normal (-1, 1) / sqrt 2, gap (0.0015, -0.0015) . n. Before the rule: no contact.
      call section(s, 'concave rule: entering a segment from the corner (C.2)')
      call slave_moves([-0.003_wp, -0.001_wp], [0.004_wp, 0.001_wp])
      call check(s, cs%n == 1, 'one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 1 .and. .not. cs%at_end(1), 'on segment 1, not at its end')
         call check_close(s, cs%alpha(1), 0.9975_wp, 1.0e-14_wp, 'at the projection of the predicted position')
         ! tau = -C / B with C = 0.002 / sqrt 2 formed from coordinates of size 1 (rounding 1e-16 of
         ! 1 in 1.4e-3: 1e-13 relative)
         call check_close(s, cs%tau(1), 0.4_wp, 1.0e-12_wp, 'at the time it crossed the line')
         call check(s, maxval(abs(cs%normal(:, 1) - [-r, r])) < 1.0e-15_wp, 'with segment 1''s normal')
         call check_close(s, cs%gap(1), -0.003_wp*r, 1.0e-16_wp, 'predicted gap along it')
      end if

   contains
      !> The contacts of slave node 4 moving from a to b over the step (the master's nodes at
      !> rest at x0), into cs.
      subroutine slave_moves(a, b)
         real(wp), intent(in) :: a(2), b(2)
         x0(:, 4) = a
         x1 = x0
         x1(:, 4) = b
         call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, &
                              0.1_wp, FACING_LIMIT)
      end subroutine slave_moves
   end subroutine run_contact_concave_tests

end module test_contact_concave
