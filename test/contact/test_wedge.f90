!> The wedge rule of the narrow phase (doc/contact-detection.md, "A slave between two faces",
!> W.1): a slave held by one segment that crosses the line of another, not a neighbour, and would
!> be left behind it by more than 1e-3 of its length gets that segment as a second contact.
module test_wedge
   use exic_base_kinds, only: wp
   use exic_contact_spec, only: DETECT_SWEPT
   use exic_mesh_boundary, only: segment_links
   use exic_contact_detect, only: detect_contacts, contact_set_t, FACING_LIMIT
   use exic_base_strings, only: rtoa
   use testing, only: suite_t, check, check_close, section
   implicit none
   private

   public :: test_wedge_rule

contains

   !> Segment 1: node 1 (1, 0) -> node 2 (-1, 0), outward normal (0, 1) (the layer the slave
   !> rests on). Segment 2: node 3 -> node 4 along x + y = c, outward normal (1, 1)/sqrt(2) (a
   !> layer folding over the slave), c from -0.1 at x0 to 0.05 at x1. Slave 5 at the origin,
   !> predicted 1e-4 lower: in contact with segment 1 from the start (tau 0, the first key) and
   !> crossing segment 2's line at tau = 0.1/0.1501 (alpha 1/2); moved onto segment 1's line it would
   !> still be 0.05/sqrt(2) behind segment 2's, so segment 2 is its second contact. With segment
   !> 2 stopping at c = 5e-4 the slave would be left 3.5e-4 behind it: one contact.
   subroutine test_wedge_rule(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 5), x1(2, 5), snrm(2, 1), r
      integer :: seg(2, 2), link(2, 2), cand(2, 2)
      type(contact_set_t) :: cs

      call section(s, 'contact geometry: wedge rule, a slave between two faces')
      r = sqrt(0.5_wp)
      seg(:, 1) = [1, 2]; seg(:, 2) = [3, 4]
      call segment_links(2, seg, link)
      cand(:, 1) = [1, 1]; cand(:, 2) = [1, 2]
      snrm = 0.0_wp
      x0(:, 1) = [1.0_wp, 0.0_wp]; x0(:, 2) = [-1.0_wp, 0.0_wp]
      x0(:, 3) = [0.4_wp, -0.5_wp]; x0(:, 4) = [-0.6_wp, 0.5_wp]
      x0(:, 5) = [0.0_wp, 0.0_wp]
      x1 = x0
      x1(:, 3) = [0.55_wp, -0.5_wp]; x1(:, 4) = [-0.45_wp, 0.5_wp]
      x1(:, 5) = [0.0_wp, -1.0e-4_wp]
      call detect_contacts(cs, DETECT_SWEPT, 5, x0, x1, 1, [5], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 2, 'held by segment 1, crossing segment 2: two contacts of the slave')
      if (cs%n == 2) then
         call check(s, all(cs%slave(1:2) == 5) .and. cs%seg(1) == 1 .and. cs%seg(2) == 2, &
                    'the first is segment 1 (tau 0), the second segment 2')
         call check(s, cs%tau(1) == 0.0_wp .and. abs(cs%tau(2) - 0.1_wp/0.1501_wp) < 1.0e-12_wp, &
                    'at tau 0 and 0.1/0.1501', 'tau '//rtoa(cs%tau(1))//', '//rtoa(cs%tau(2)))
         call check(s, maxval(abs(cs%normal(:, 2) - [r, r])) < 1.0e-15_wp, 'the second along (1, 1)/sqrt(2)')
         call check_close(s, cs%gap(2), -0.05_wp*r - 1.0e-4_wp*r, 1.0e-15_wp, &
                          'its predicted gap: the slave behind x + y = 0.05')
      end if
      ! segment 2 stopping at x + y = 5e-4: the slave crosses its line (a hit) but moved onto
      ! segment 1's line it is 3.5e-4 behind it, below WEDGE_TOL (1e-3) of its length sqrt(2)
      x1(:, 3) = [0.5005_wp, -0.5_wp]; x1(:, 4) = [-0.4995_wp, 0.5_wp]
      call detect_contacts(cs, DETECT_SWEPT, 5, x0, x1, 1, [5], snrm, 2, seg, link, 2, cand, &
                           0.1_wp, FACING_LIMIT)
      call check(s, cs%n == 1, 'left 3.5e-4 behind segment 2 (below 1e-3 of its length): one contact', &
                 'contacts: '//char(48 + min(cs%n, 9)))
      if (cs%n >= 1) call check(s, cs%seg(1) == 1, 'the contact is segment 1')
   end subroutine test_wedge_rule

end module test_wedge
