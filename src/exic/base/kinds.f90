!> Kinds used throughout exic.
module exic_base_kinds
   use, intrinsic :: iso_fortran_env, only: real64, int32, int64
   implicit none
   private

   !> Working precision of every real in exic.
   integer, parameter, public :: wp = real64
   !> Integer kind for counters that may exceed 2**31 (step counts, byte counts).
   integer, parameter, public :: i8 = int64

end module exic_base_kinds
