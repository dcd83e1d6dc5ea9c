!> The natural logarithm of exic's kernels: one algorithm for the scalar and the vector path, so
!> that a result never depends on whether the compiler vectorized a loop, on the loop's
!> remainder, on the machine's vector width or on the C library (doc/decisions.md, "Floating
!> point"). The material laws take ln J of a block of points with `ln_block`, or with
!> `ln_normal_block` where every J is a positive normal number (the neo-Hookean kernels); single
!> values (stress output, tests) use the elemental `ln`. All three compute the same bits.
!>
!> Algorithm (fdlibm's e_log.c, Sun Microsystems 1993, without its branches): x = 2^k (1 + f)
!> with 1 + f in [sqrt(2)/2, sqrt(2)), s = f/(2 + f), z = s^2, w = z^2,
!> R = z (Lg1 + w (Lg3 + w (Lg5 + w Lg7))) + w (Lg2 + w (Lg4 + w Lg6)) (a minimax polynomial
!> for 2 atanh(s)/s - 2 - ... whose error is below 2^-58.45), and with hfsq = f^2/2
!>
!>     ln x = k ln2_hi - ((hfsq - (s (hfsq + R) + k ln2_lo)) - f)
!>
!> (fdlibm's "more accurate" form, used here for every f; ln2_hi has 32 trailing zero bits, so
!> k ln2_hi is exact). The reduction is integer arithmetic on the bits, which vectorizes; it
!> works on all 64 bits at once (fdlibm on the high word: the same k and f).
!> Measured error against quad precision (test suite `math`): at most 0.85 ulp over
!> J in [0.05, 20] and near 1; ln 1 = 0 exactly (a stress-free state stays exactly stress free).
!> Domain: positive normal and subnormal numbers; NaN gives NaN. Zero, negative numbers and
!> infinity give meaningless finite values (the kernels never pass them: they check J > 0).
!> ln_normal_block: positive normal numbers only (J >= tiny(1.0), which the kernels check).
module exic_base_logarithm
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private

   public :: ln, ln_block, ln_normal_block

   real(wp), parameter :: ln2_hi = 6.93147180369123816490e-01_wp   !< 3fe62e42 fee00000
   real(wp), parameter :: ln2_lo = 1.90821492927058770002e-10_wp   !< 3dea39ef 35793c76
   real(wp), parameter :: two54 = 1.80143985094819840000e+16_wp    !< 2^54
   real(wp), parameter :: lg1 = 6.666666666666735130e-01_wp
   real(wp), parameter :: lg2 = 3.999999999940941908e-01_wp
   real(wp), parameter :: lg3 = 2.857142874366239149e-01_wp
   real(wp), parameter :: lg4 = 2.222219843214978396e-01_wp
   real(wp), parameter :: lg5 = 1.818357216161805012e-01_wp
   real(wp), parameter :: lg6 = 1.531383769920937332e-01_wp
   real(wp), parameter :: lg7 = 1.479819860511658591e-01_wp
   !> Smallest positive normal number.
   real(wp), parameter :: tiny_wp = tiny(1.0_wp)

contains

   !> Natural logarithm of x > 0 (module header).
   elemental real(wp) function ln(x)
      real(wp), intent(in) :: x
      ln = log_kernel(x)
   end function ln

   !> y(q) = ln(x(q)) for q = 1..n, vectorized: the same operations as `ln`, so the same bits.
   pure subroutine ln_block(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: q
      do q = 1, n
         y(q) = log_kernel(x(q))
      end do
   end subroutine ln_block

   !> y(q) = ln(x(q)) for q = 1..n where every x(q) is a positive normal number (the kernels'
   !> volume ratios after their J >= tiny check): the bits of `ln` for such x, without its
   !> handling of subnormal numbers and NaN (the vector loop: 41 instructions per 8 values against
   !> ln_block's 52). A subnormal, zero, negative, infinite or NaN x gives a meaningless finite
   !> value: callers pass none.
   pure subroutine ln_normal_block(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: q
      do q = 1, n
         y(q) = log_core(x(q), 0_int64)
      end do
   end subroutine ln_normal_block

   !> The algorithm of the module header for every x: a subnormal x is scaled by 2^54 first,
   !> and + (x - x) makes NaN of NaN (the bit reduction alone would make a finite number of it)
   !> and adds +0 to every other result (a merge on x == x would stop the vectorizer). Private,
   !> so that the compiler may inline it into the loop of ln_block and vectorize it (a public
   !> procedure of position-independent code may be interposed and is not inlined).
   elemental real(wp) function log_kernel(x) result(ln)
      real(wp), intent(in) :: x
      ln = log_core(merge(x*two54, x, x < tiny_wp), merge(-54_int64, 0_int64, x < tiny_wp)) + (x - x)
   end function log_kernel

   !> ln(2^k0 y) for a positive normal y, the algorithm of the module header. The reduction
   !> works on the 64 bits of y at once: m = its mantissa field, i = 2^52 when the mantissa is at
   !> least sqrt(2) (m + 0x95f64 2^32 carries into bit 52; fdlibm does this on the high word),
   !> then 1 + f = m with the exponent of 1 (of 1/2 when i /= 0) and k = k0 + e - 1023 + i/2^52.
   elemental real(wp) function log_core(y, k0) result(ln)
      real(wp), intent(in) :: y
      integer(int64), intent(in) :: k0
      integer(int64) :: ix, m, i, k
      real(wp) :: f, s, z, w, r, hfsq, dk

      ix = transfer(y, ix)
      m = iand(ix, int(z'000fffffffffffff', int64))
      i = iand(m + int(z'00095f6400000000', int64), int(z'0010000000000000', int64))
      k = k0 + (shiftr(ix, 52) - 1023_int64) + shiftr(i, 52)
      f = transfer(ior(m, ieor(i, int(z'3ff0000000000000', int64))), f) - 1.0_wp
      s = f/(2.0_wp + f)
      dk = real(k, wp)
      z = s*s
      w = z*z
      r = z*(lg1 + w*(lg3 + w*(lg5 + w*lg7))) + w*(lg2 + w*(lg4 + w*lg6))
      hfsq = 0.5_wp*f*f
      ln = dk*ln2_hi - ((hfsq - (s*(hfsq + r) + dk*ln2_lo)) - f)
   end function log_core

end module exic_base_logarithm
