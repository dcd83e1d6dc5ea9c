!> Wall-clock time in seconds.
module exic_base_clock
   use exic_base_kinds, only: wp, i8
   implicit none
   private

   public :: wall_time

contains

   !> Seconds since an arbitrary origin, from the processor's monotonic clock.
   function wall_time() result(t)
      real(wp) :: t
      integer(i8) :: count, rate
      call system_clock(count, rate)
      t = real(count, wp)/real(rate, wp)
   end function wall_time

end module exic_base_clock
