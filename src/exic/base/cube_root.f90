!> The cube root of exic's kernels: one algorithm for the scalar and the vector path, so that a
!> result never depends on whether the compiler vectorized a loop, on the machine's vector width
!> or on the C library (doc/decisions.md, "Floating point"). Before it the mean-dilatation
!> elements took (Jbar/J)^(1/3) with `**(1.0_wp/3.0_wp)`: glibc's scalar `pow` in a scalar loop,
!> libmvec's `_ZGVeN8vv_pow` where gfortran vectorized the loop, two different results; and
!> 1/3 in binary is not a third, so neither was the cube root either. `cbrt_block` takes the
!> cube roots of a block of values; `cbrt` of one value. Both compute the same bits.
!>
!> Algorithm (FreeBSD's s_cbrt.c: Sun Microsystems 1993, rewritten by Bruce D. Evans 2005),
!> for a positive normal x with high word hx (sign, exponent and 20 mantissa bits):
!>
!>   1. t0 = the double with high word hx/3 + B1 and low word 0: 2^(e/3) (1 + (e mod 3 + m)/3),
!>      cbrt(x) to about 5 bits (B1 = (1023 - 1023/3 - 0.03306235651) 2^20);
!>   2. r = t0^3/x, t1 = t0 p(r), p(r) = (P0 + r (P1 + r P2)) + r^3 (P3 + r P4) the minimax
!>      polynomial |1/cbrt(r) - p(r)| < 2^-23.5 on the range of r: cbrt(x) to 23 bits;
!>   3. t = t1 rounded away from zero to 21 significant bits (so t^2 is exact);
!>   4. one Newton step in the form r = x/t^2, r = (r - t)/(2t + r), cbrt = t + t r:
!>      t^2, r - t and 2t are exact, and the error is below 0.5 + 0.5/3 + eps = 0.667 ulp.
!>
!> hx/3 is the integer quotient (hx 2863311531) / 2^33, exact for every 32-bit hx (2863311531 =
!> (2^33 + 1)/3), so no integer division (which the vector units lack) is needed. Subnormal x
!> are scaled by 2^54 first and their root by 2^-18 after; +-0, +-Inf and NaN give themselves;
!> cbrt(-x) = -cbrt(x). Measured error against quad precision (test suite `math`): at most
!> 0.667 ulp over every exponent and densely over the kernels' range of volume ratios.
module exic_base_cube_root
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private

   public :: cbrt, cbrt_block

   !> (1023 - 1023/3 - 0.03306235651) 2^20: the bias of the first estimate's high word.
   integer(int64), parameter :: b1 = 715094163_int64
   !> Multiplier of the exact division by 3 of a 32-bit integer: (2^33 + 1)/3.
   integer(int64), parameter :: third_mul = 2863311531_int64
   real(wp), parameter :: p0 = 1.87595182427177009643_wp      !< 3ffe03e6 0f61e692
   real(wp), parameter :: p1 = -1.88497979543377169875_wp     !< bffe28e0 92f02420
   real(wp), parameter :: p2 = 1.621429720105354466140_wp     !< 3ff9f160 4a49d6c2
   real(wp), parameter :: p3 = -0.758397934778766047437_wp    !< bfe844cb bee751d9
   real(wp), parameter :: p4 = 0.145996192886612446982_wp     !< 3fc2b000 d4e4edd7
   real(wp), parameter :: two54 = 1.80143985094819840000e+16_wp    !< 2^54
   real(wp), parameter :: twom18 = 3.814697265625e-06_wp           !< 2^-18 = cbrt(2^-54)
   real(wp), parameter :: tiny_wp = tiny(1.0_wp)
   real(wp), parameter :: huge_wp = huge(1.0_wp)

contains

   !> Cube root of x (module header).
   elemental real(wp) function cbrt(x)
      real(wp), intent(in) :: x
      cbrt = cbrt_kernel(x)
   end function cbrt

   !> y(q) = cbrt(x(q)) for q = 1..n, vectorized: the same operations as `cbrt`, so the same bits.
   !> y may be x.
   pure subroutine cbrt_block(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: q
      do q = 1, n
         y(q) = cbrt_kernel(x(q))
      end do
   end subroutine cbrt_block

   !> The module header's algorithm for every x: sign apart, subnormal numbers scaled, and
   !> +-0, +-Inf given back as they are (every value formed and then selected, so that the loop
   !> of cbrt_block vectorizes). NaN stays NaN through the divisions of cbrt_core. Private, so
   !> that the compiler may inline it into the loop of cbrt_block.
   elemental real(wp) function cbrt_kernel(x) result(c)
      real(wp), intent(in) :: x
      real(wp) :: a
      logical :: sub
      a = abs(x)
      sub = a < tiny_wp
      c = cbrt_core(merge(a*two54, a, sub))*merge(twom18, 1.0_wp, sub)
      c = sign(merge(a, c, a == 0.0_wp .or. a > huge_wp), x)
   end function cbrt_kernel

   !> cbrt(y) for a positive normal y, steps 1-4 of the module header.
   elemental real(wp) function cbrt_core(y) result(t)
      real(wp), intent(in) :: y
      integer(int64) :: hx, it
      real(wp) :: r, s, w
      hx = shiftr(transfer(y, hx), 32)
      t = transfer(shiftl(shiftr(hx*third_mul, 33) + b1, 32), t)
      r = (t*t)*(t/y)
      t = t*((p0 + r*(p1 + r*p2)) + ((r*r)*r)*(p3 + r*p4))
      ! rounded away from zero to 21 bits: + 2^31, then the low 30 bits cleared (-2^30 is
      ! ffffffffc0000000)
      it = iand(transfer(t, it) + int(z'80000000', int64), -1073741824_int64)
      t = transfer(it, t)
      s = t*t
      r = y/s
      w = t + t
      r = (r - t)/(w + r)
      t = t + t*r
   end function cbrt_core

end module exic_base_cube_root
