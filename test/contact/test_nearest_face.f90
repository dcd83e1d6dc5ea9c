!> The nearest-face rule of the swept narrow phase (doc/contact-detection.md, "Nearest face of a
!> slave behind a segment", N.1-N.3) on the corner of a block: master surface 1 (0,0) -> 2 (1,0)
!> (bottom face, normal (0,-1), the block above it) -> 3 (1,1) (side face, normal (1,0)), a convex
!> corner at node 2. Slave 4, the corner of another body (normal (-1,1)/sqrt 2, facing both
!> faces), slides on the bottom face towards node 2, 0.07 behind the side face's line: the
!> configuration of node 9 in variant 144 of tools/stress/uncoupled_family.py --seed 7.
module test_nearest_face
   use exic_base_kinds, only: wp
   use exic_contact_spec, only: DETECT_SWEPT
   use exic_contact_detect, only: contact_set_t, detect_contacts
   use testing, only: suite_t, check, section
   implicit none
   private

   public :: run_nearest_face_tests

contains

   subroutine run_nearest_face_tests(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: FACING = -0.5_wp   ! the contact step's (src/exic/contact/contact.f90)
      real(wp), parameter :: DEPTH = 0.1_wp
      real(wp) :: x0(2, 4), x1(2, 4), snrm(2, 1), r
      integer :: seg(2, 2), link(2, 2), cand(2, 2)
      type(contact_set_t) :: cs

      call section(s, 'contact geometry: nearest face of a slave behind a segment (N.1-N.3)')
      r = sqrt(0.5_wp)
      x0 = 0.0_wp
      x0(:, 1) = [0.0_wp, 0.0_wp]; x0(:, 2) = [1.0_wp, 0.0_wp]; x0(:, 3) = [1.0_wp, 1.0_wp]
      seg(:, 1) = [1, 2]; seg(:, 2) = [2, 3]
      link(:, 1) = [0, 2]; link(:, 2) = [1, 0]
      cand(:, 1) = [1, 1]; cand(:, 2) = [1, 2]
      snrm(:, 1) = [-r, r]
      ! (N.3) 1e-9 in front of the bottom face, crossing it early in the step: the side face, 0.07
      ! behind, must not take it at tau_c = 0 (its projection 1e-9 from node 2, snapped to it)
      x0(:, 4) = [0.93_wp, -1.0e-9_wp]
      x1 = x0
      x1(:, 4) = [0.94_wp, 5.0e-4_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, DEPTH, FACING)
      call check(s, cs%n == 1, 'in front of the bottom face: one contact')
      if (cs%n == 1) then
         call check(s, cs%seg(1) == 1 .and. .not. cs%at_end(1) .and. cs%tau(1) > 0.0_wp .and. &
                    cs%tau(1) < 1.0e-5_wp, 'held by the bottom face it crosses (tau_c 2e-6), not by the '// &
                    'side face behind which it lies 0.07 (tau_c = 0)')
         call check(s, all(cs%normal(:, 1) == [0.0_wp, -1.0_wp]) .and. cs%gap(1) > -1.0e-3_wp, &
                    'the bottom face''s normal; predicted gap -5e-4, not -0.06')
      end if
      ! (N.2) 1e-9 behind the bottom face and leaving it: no contact
      x0(:, 4) = [0.93_wp, 1.0e-9_wp]
      x1(:, 4) = [0.94_wp, -1.0e-3_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, DEPTH, FACING)
      call check(s, cs%n == 0, 'leaving the bottom face: not pushed out through the side face')
      ! a slave behind the side face by 0.03 at mid-height (the bottom face 0.5 away): kept there
      x0(:, 4) = [0.97_wp, 0.5_wp]
      x1(:, 4) = [0.965_wp, 0.5_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, DEPTH, FACING)
      call check(s, cs%n == 1, 'behind the side face, far from the corner: one contact')
      if (cs%n == 1) call check(s, cs%seg(1) == 2 .and. cs%tau(1) == 0.0_wp, &
                                'held by the side face from the start (its nearest face)')
      ! at the corner node itself (1e-12 from both lines): the master node normal, as before
      x0(:, 4) = [1.0_wp - 1.0e-12_wp, 1.0e-12_wp]
      x1(:, 4) = [1.0_wp - 1.0e-12_wp, 2.0e-12_wp]
      call detect_contacts(cs, DETECT_SWEPT, 4, x0, x1, 1, [4], snrm, 2, seg, link, 2, cand, DEPTH, FACING)
      call check(s, cs%n == 1, 'at the corner node: one contact')
      if (cs%n == 1) call check(s, cs%at_end(1) .and. abs(cs%normal(1, 1) - r) < 1.0e-12_wp .and. &
                                abs(cs%normal(2, 1) + r) < 1.0e-12_wp, &
                                'at the corner node: the master node normal (1,-1)/sqrt 2')
   end subroutine run_nearest_face_tests

end module test_nearest_face
