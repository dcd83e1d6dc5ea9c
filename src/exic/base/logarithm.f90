!> The natural logarithm of exic's kernels: one algorithm for the scalar and the vector path, so
!> that a result never depends on whether the compiler vectorized a loop, on the loop's
!> remainder, on the machine's vector width or on the C library (doc/decisions.md, "Floating
!> point"). The material laws take ln J of a block of points with `ln_block`; single values
!> (stress output, tests) use the elemental `ln`. Both compute the same bits.
!>
!> Algorithm (fdlibm's e_log.c, Sun Microsystems 1993, without its branches): x = 2^k (1 + f)
!> with 1 + f in [sqrt(2)/2, sqrt(2)), s = f/(2 + f), z = s^2, w = z^2,
!> R = z (Lg1 + w (Lg3 + w (Lg5 + w Lg7))) + w (Lg2 + w (Lg4 + w Lg6)) (a minimax polynomial
!> for 2 atanh(s)/s - 2 - ... whose error is below 2^-58.45), and with hfsq = f^2/2
!>
!>     ln x = k ln2_hi - ((hfsq - (s (hfsq + R) + k ln2_lo)) - f)
!>
!> (fdlibm's "more accurate" form, used here for every f; ln2_hi has 32 trailing zero bits, so
!> k ln2_hi is exact). The reduction is integer arithmetic on the bits, which vectorizes.
!> Measured error against quad precision (test suite `math`): at most 0.85 ulp over
!> J in [0.05, 20] and near 1; ln 1 = 0 exactly (a stress-free state stays exactly stress free).
!> Domain: positive normal and subnormal numbers; NaN gives NaN. Zero, negative numbers and
!> infinity give meaningless finite values (the kernels never pass them: they check J > 0).
module exic_base_logarithm
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: int64
   implicit none
   private

   public :: ln, ln_block

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

   !> The algorithm of the module header. Private, so that the compiler may inline it into the
   !> loop of ln_block and vectorize it (a public procedure of position-independent code may be
   !> interposed and is not inlined).
   elemental real(wp) function log_kernel(x) result(ln)
      real(wp), intent(in) :: x
      integer(int64) :: ix, hx, i, k
      real(wp) :: y, f, s, z, w, r, hfsq, dk

      ! subnormal x: scale by 2^54 first
      y = merge(x*two54, x, x < tiny_wp)
      k = merge(-54_int64, 0_int64, x < tiny_wp)
      ix = transfer(y, ix)
      hx = shiftr(ix, 32)
      k = k + shiftr(hx, 20) - 1023_int64
      hx = iand(hx, int(z'000fffff', int64))
      ! i = 2^20 when the mantissa is at least sqrt(2): then take x/2 and k + 1
      i = iand(hx + int(z'95f64', int64), int(z'100000', int64))
      ix = ior(shiftl(ior(hx, ieor(i, int(z'3ff00000', int64))), 32), iand(ix, int(z'ffffffff', int64)))
      k = k + shiftr(i, 20)
      f = transfer(ix, f) - 1.0_wp
      s = f/(2.0_wp + f)
      dk = real(k, wp)
      z = s*s
      w = z*z
      r = z*(lg1 + w*(lg3 + w*(lg5 + w*lg7))) + w*(lg2 + w*(lg4 + w*lg6))
      hfsq = 0.5_wp*f*f
      ! + (x - x): NaN in, NaN out (the bit reduction alone would make a finite number of it);
      ! adds +0 to every other result (a merge on x == x would stop the vectorizer)
      ln = (dk*ln2_hi - ((hfsq - (s*(hfsq + r) + dk*ln2_lo)) - f)) + (x - x)
   end function log_kernel

end module exic_base_logarithm
