!> The anti-cycling rule of the block principal pivoting that both corrector problems use (the
!> normal one in corrector.f90, the tangential one of friction in friction.f90): Júdice & Pires,
!> "A block principal pivoting algorithm for large-scale strictly monotone linear
!> complementarity problems", Computers & Operations Research 21 (1994) 587-596. Every
!> infeasible candidate is switched at once while the count of infeasible candidates keeps
!> falling; after `TRIES` passes without a new lowest count, only the infeasible candidate of
!> the largest index is switched (Murty's single pivot, which cannot cycle), until a pass beats
!> the lowest count again.
module exic_contact_pivot_rule
   implicit none
   private

   public :: pivot_rule_t

   !> Block passes allowed without a new lowest count of infeasible candidates.
   integer, parameter :: TRIES = 3

   !> The state of the rule over the passes of one solve.
   type, public :: pivot_rule_t
      integer :: best = huge(1)     !< lowest count of infeasible candidates so far
      integer :: budget = TRIES     !< block passes left before single pivots
   contains
      procedure :: block_pass
   end type pivot_rule_t

contains

   !> After a pass with `ninf` infeasible candidates: true when every infeasible candidate is to
   !> be switched, false when only the one of the largest index is.
   logical function block_pass(self, ninf)
      class(pivot_rule_t), intent(inout) :: self
      integer, intent(in) :: ninf
      if (ninf < self%best) then
         self%best = ninf
         self%budget = TRIES
      else
         self%budget = self%budget - 1
      end if
      block_pass = self%budget >= 0
   end function block_pass

end module exic_contact_pivot_rule
