!> The plastic work of a step booked by the trapezoid rule of the stress power (doc/plasticity.md,
!> section 5.5, eq. (J31)): for an element in which some point yielded over the step,
!>
!>     D_e = sum_g [ 1/2 (wP(n) + wP(n+1)) : (F(n+1) - F(n)) - (wW(n+1) - wW(n)) ]          (J31)
!>
!> (wP the weighted first Piola stress that works on F, P* of the mean-dilatation element;
!> wW the weighted stored energy), and 0 for an element whose points all stayed elastic. Since F
!> is linear in the nodal displacements, sum_g wP : dF is the work of the element's stress forces
!> over du, so (J31) is that work by the trapezoid rule, the rule by which the balance books
!> every force (doc/decisions.md, eq. E.2), less the change of the stored energy: the balance of
!> a yielding element closes to round-off, that of an elastic one to the trapezoid rule's
!> O(du^3) error, as in an elastic set.
!>
!> The history of a plastic set carries, after the law's own values (law_t%nvar), NBOOK values
!> per point: F(n) (F11 F12 F21 F22 F33), wP(n) (P11 P12 P21 P22 P33, times the point's weight)
!> and wW(n), those of the last force pass.
module exic_element_q4_plastic_work
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum
   use exic_element_q4_block, only: NBLOCK
   implicit none
   private

   public :: NBOOK, book_init, book_block

   !> Values per point after the law's history: F (5), weighted P (5), weighted W (1).
   integer, parameter :: NBOOK = 11

contains

   !> The booking values of the reference state, F = 1, P = 0, W = 0, in hist(nvar + 1 :
   !> nvar + NBOOK, :, :).
   pure subroutine book_init(nvar, hist)
      integer, intent(in) :: nvar
      real(wp), intent(inout) :: hist(:, :, :)
      hist(nvar + 1:nvar + NBOOK, :, :) = 0.0_wp
      hist(nvar + 1, :, :) = 1.0_wp
      hist(nvar + 4, :, :) = 1.0_wp
      hist(nvar + 5, :, :) = 1.0_wp
   end subroutine book_init

   !> (J31) for the nb elements of a block with np points each (hist(:, :, h0 + k - 1) is lane
   !> k's history, its booking values after nvar): f.. the deformation gradient F(n+1) of every
   !> point (not the mean-dilatation Fbar), p.. the weighted stress that works on it, wq the
   !> weighted stored energy, yl > 0 at a point whose plastic strain grew in the step. wdis gets
   !> the block's plastic work; the booking values become those of t(n+1).
   pure subroutine book_block(np, nb, nvar, hist, h0, f11, f12, f21, f22, f33, p11, p12, p21, p22, &
                              p33, wq, yl, wdis)
      integer, intent(in) :: np, nb, nvar, h0
      real(wp), intent(inout) :: hist(:, :, :)
      real(wp), intent(in), dimension(NBLOCK, np) :: f11, f12, f21, f22, f33, p11, p12, p21, p22, &
                                                      p33, wq, yl
      real(wp), intent(inout) :: wdis
      real(wp) :: wd(NBLOCK), tr, dw, y, pw
      integer :: k, g, e, b

      wd = 0.0_wp
      b = nvar
      do k = 1, nb
         e = h0 + k - 1
         tr = 0.0_wp
         dw = 0.0_wp
         y = 0.0_wp
         do g = 1, np
            pw = (((hist(b + 6, g, e) + p11(k, g))*(f11(k, g) - hist(b + 1, g, e)) &
                   + (hist(b + 7, g, e) + p12(k, g))*(f12(k, g) - hist(b + 2, g, e))) &
                  + ((hist(b + 8, g, e) + p21(k, g))*(f21(k, g) - hist(b + 3, g, e)) &
                     + (hist(b + 9, g, e) + p22(k, g))*(f22(k, g) - hist(b + 4, g, e)))) &
                 + (hist(b + 10, g, e) + p33(k, g))*(f33(k, g) - hist(b + 5, g, e))
            tr = tr + pw
            dw = dw + (wq(k, g) - hist(b + 11, g, e))
            y = max(y, yl(k, g))
            hist(b + 1, g, e) = f11(k, g)
            hist(b + 2, g, e) = f12(k, g)
            hist(b + 3, g, e) = f21(k, g)
            hist(b + 4, g, e) = f22(k, g)
            hist(b + 5, g, e) = f33(k, g)
            hist(b + 6, g, e) = p11(k, g)
            hist(b + 7, g, e) = p12(k, g)
            hist(b + 8, g, e) = p21(k, g)
            hist(b + 9, g, e) = p22(k, g)
            hist(b + 10, g, e) = p33(k, g)
            hist(b + 11, g, e) = wq(k, g)
         end do
         if (y > 0.0_wp) wd(k) = 0.5_wp*tr - dw
      end do
      wdis = wdis + lane_sum(nb, wd)
   end subroutine book_block

end module exic_element_q4_plastic_work
