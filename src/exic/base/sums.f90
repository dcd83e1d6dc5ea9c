!> Sums in a fixed order that vectorize: the kernels' energies, works and momenta are summed
!> with `lane_sum` over fixed pieces (a block of elements, a chunk of nodes) and the pieces in
!> order, so that a sum is the same to the bit for every number of threads and every build
!> (doc/decisions.md, "Threads").
module exic_base_sums
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: lane_sum, ordered_sum

   !> Interleaved partial sums of lane_sum (one AVX-512 vector of reals).
   integer, parameter :: LANES = 8

contains

   !> Sum of p(1:m) in a fixed order: LANES partial sums s_l = p(l) + p(l + LANES) + ... (in
   !> that order), combined as ((s1 + s2) + (s3 + s4)) + ((s5 + s6) + (s7 + s8)). A sequential
   !> sum waits for every addition before the next (4 cycles each); these lanes go as vectors.
   pure real(wp) function lane_sum(m, p) result(total)
      integer, intent(in) :: m
      real(wp), intent(in) :: p(m)
      real(wp) :: s(LANES)
      integer :: j, l
      s = 0.0_wp
      do j = 0, m - LANES, LANES
         do l = 1, LANES
            s(l) = s(l) + p(j + l)
         end do
      end do
      do l = 1, m - LANES*(m/LANES)
         s(l) = s(l) + p(LANES*(m/LANES) + l)
      end do
      total = ((s(1) + s(2)) + (s(3) + s(4))) + ((s(5) + s(6)) + (s(7) + s(8)))
   end function lane_sum

   !> Sum of p(1:m) from the first to the last (the per-chunk sums of a pass, chunks in order).
   pure real(wp) function ordered_sum(m, p) result(total)
      integer, intent(in) :: m
      real(wp), intent(in) :: p(m)
      integer :: j
      total = 0.0_wp
      do j = 1, m
         total = total + p(j)
      end do
   end function ordered_sum

end module exic_base_sums
