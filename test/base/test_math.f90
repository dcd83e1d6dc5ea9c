!> Tests of exic's own logarithm (src/exic/base/logarithm.f90) and cube root
!> (src/exic/base/cube_root.f90): their errors against a quad precision reference over the range
!> of volume ratios J that occur (0.05 .. 20, densely, and the hard cases next to 1 and to the
!> reduction's boundaries; for the cube root also every exponent and random bit patterns), exact
!> values, and that the block kernels (vectorized) and the elemental functions give the same
!> bits; and the flat-array kernels of src/exic/base/flat.f90.
module test_math
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln, ln_block, ln_normal_block
   use exic_base_cube_root, only: cbrt, cbrt_block
   use exic_base_flat, only: all_finite, copy_flat, sum_flat
   use, intrinsic :: iso_fortran_env, only: real128, int64
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_is_nan, ieee_positive_inf, &
                                             ieee_negative_inf, ieee_is_finite
   use testing, only: suite_t, check, section
   implicit none
   private

   public :: run_math_tests

contains

   !> Run every test of the suite.
   subroutine run_math_tests(s)
      type(suite_t), intent(inout) :: s
      call test_accuracy(s)
      call test_exact(s)
      call test_block(s)
      call test_cube_root(s)
      call test_flat(s)
   end subroutine run_math_tests

   !> Error of ln(x) in units in the last place of the exact logarithm (quad precision).
   real(wp) function ulps(x)
      real(wp), intent(in) :: x
      real(real128) :: t
      t = log(real(x, real128))
      if (t == 0.0_real128) then
         ulps = merge(0.0_wp, huge(1.0_wp), ln(x) == 0.0_wp)
      else
         ulps = real(abs(real(ln(x), real128) - t)/real(spacing(real(t, wp)), real128), wp)
      end if
   end function ulps

   !> At most one ulp (0.85 measured) over J in [0.05, 20] and near 1.
   subroutine test_accuracy(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 200000
      real(wp) :: x, worst, wnear, wbound, e
      integer :: i, k
      character(len=80) :: buf

      call section(s, 'logarithm: error against quad precision')
      worst = 0.0_wp
      do i = 0, n
         ! log-uniform over [0.05, 20], irrational spacing so every mantissa region is hit
         x = 0.05_wp*400.0_wp**(real(i, wp)/real(n, wp))
         x = x*(1.0_wp + 1.0e-7_wp*sin(real(i, wp)))
         worst = max(worst, ulps(x))
      end do
      write (buf, '(a,f6.3,a)') 'J in [0.05, 20], 200001 points: at most ', worst, ' ulp'
      call check(s, worst <= 1.0_wp, trim(buf))
      ! next to 1: 1 +- k ulp and 1 +- 2^-j (the hard cases of any logarithm)
      wnear = 0.0_wp
      do k = 1, 2000
         wnear = max(wnear, ulps(1.0_wp + real(k, wp)*epsilon(1.0_wp)), &
                     ulps(1.0_wp - real(k, wp)*0.5_wp*epsilon(1.0_wp)))
      end do
      do k = 1, 52
         wnear = max(wnear, ulps(1.0_wp + 2.0_wp**(-k)), ulps(1.0_wp - 2.0_wp**(-k)), &
                     ulps(1.0_wp + 3.0_wp*2.0_wp**(-k - 2)), ulps(1.0_wp - 3.0_wp*2.0_wp**(-k - 2)))
      end do
      write (buf, '(a,f6.3,a)') 'next to 1 (1 +- k ulp, 1 +- 2^-j): at most ', wnear, ' ulp'
      call check(s, wnear <= 1.0_wp, trim(buf))
      ! the reduction's boundaries: mantissas next to sqrt(2) and 1/sqrt(2), over many binades
      wbound = 0.0_wp
      do k = -30, 30
         do i = -50, 50
            x = sqrt(2.0_wp)*2.0_wp**k*(1.0_wp + real(i, wp)*epsilon(1.0_wp))
            e = ulps(x)
            wbound = max(wbound, e)
         end do
      end do
      write (buf, '(a,f6.3,a)') 'at the reduction boundary sqrt(2) 2^k, k = -30..30: at most ', wbound, ' ulp'
      call check(s, wbound <= 1.0_wp, trim(buf))
   end subroutine test_accuracy

   !> ln 1 = 0 exactly; powers of two; extreme and subnormal arguments; NaN.
   subroutine test_exact(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: nan, worst
      integer :: k

      call section(s, 'logarithm: exact values and the ends of the range')
      call check(s, ln(1.0_wp) == 0.0_wp, 'ln 1 = 0 exactly (a stress-free state stays stress free)')
      worst = 0.0_wp
      do k = -1000, 1000, 7
         worst = max(worst, ulps(2.0_wp**k))
      end do
      call check(s, worst <= 1.0_wp, 'powers of two 2^-1000 .. 2^1000 within 1 ulp')
      call check(s, ulps(huge(1.0_wp)) <= 1.0_wp .and. ulps(tiny(1.0_wp)) <= 1.0_wp, &
                 'largest and smallest normal numbers within 1 ulp')
      call check(s, ulps(tiny(1.0_wp)/1024.0_wp) <= 1.0_wp .and. ulps(tiny(1.0_wp)*0.7_wp) <= 1.0_wp, &
                 'subnormal numbers within 1 ulp')
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      call check(s, ieee_is_nan(ln(nan)), 'ln NaN is NaN')
   end subroutine test_exact

   !> ln_block (the vectorized loop, with its remainder) gives the bits of ln.
   subroutine test_block(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 1001
      real(wp) :: x(n), y(n)
      integer :: i, ndiff

      call section(s, 'logarithm: block kernel and elemental function')
      do i = 1, n
         x(i) = 0.05_wp + 19.95_wp*real(mod(7919*i, n), wp)/real(n, wp) + 1.0e-9_wp*real(i, wp)
      end do
      x(17) = 1.0_wp
      x(18) = tiny(1.0_wp)/8.0_wp
      call ln_block(n, x, y)
      ndiff = bits_differ(y, ln(x))
      call check(s, ndiff == 0, 'ln_block(x) = ln(x) to the bit at 1001 points (vector loop and remainder)')
      ! ln_normal_block: every positive normal number, the reduction's boundaries and the ends
      x(18) = tiny(1.0_wp)
      x(19) = huge(1.0_wp)
      x(20) = sqrt(2.0_wp)
      x(21) = nearest(sqrt(2.0_wp), -1.0_wp)
      x(22) = 0.5_wp*sqrt(2.0_wp)
      x(23) = nearest(0.5_wp*sqrt(2.0_wp), -1.0_wp)
      do i = 24, 124
         x(i) = 2.0_wp**(20*(i - 74))*(1.0_wp + 0.37_wp*real(i, wp)/124.0_wp)
      end do
      call ln_normal_block(n, x, y)
      ndiff = bits_differ(y, ln(x))
      call check(s, ndiff == 0, 'ln_normal_block(x) = ln(x) to the bit at 1001 normal numbers (tiny, huge, '// &
                 'next to sqrt(2)/2 and sqrt(2), 2^-1000 .. 2^1000)')
   end subroutine test_block

   !> Number of places where y and z differ in any bit.
   integer function bits_differ(y, z) result(nd)
      real(wp), intent(in) :: y(:), z(:)
      nd = count(transfer(y, [0_int64]) /= transfer(z, [0_int64]))
   end function bits_differ

   !> Error of cbrt(x) in units in the last place of the exact cube root (quad precision).
   real(wp) function cbrt_ulps(x)
      real(wp), intent(in) :: x
      real(real128) :: t
      t = sign(abs(real(x, real128))**(1.0_real128/3.0_real128), real(x, real128))
      cbrt_ulps = real(abs(real(cbrt(x), real128) - t)/real(spacing(real(t, wp)), real128), wp)
   end function cbrt_ulps

   !> exic's cube root (base/cube_root.f90): within 0.667 ulp (the bound of its Newton step)
   !> over the volume ratios of the mean-dilatation elements, at every exponent of the normal and
   !> subnormal numbers and at random bit patterns; exact cubes exact, the special values, and
   !> cbrt_block (the vectorized loop, with its remainder) = cbrt to the bit.
   subroutine test_cube_root(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 20001, nr = 100003
      real(wp) :: x(nr), y(nr), worst, wexp, wrand, nan, inf
      integer(int64) :: r
      character(len=120) :: buf
      integer :: i, k, ndiff, nexact

      call section(s, 'cube root: accuracy, exact values, block kernel')
      worst = 0.0_wp
      do i = 0, n - 1
         worst = max(worst, cbrt_ulps(0.05_wp + 19.95_wp*real(i, wp)/real(n - 1, wp)))
      end do
      do k = 1, 2000
         worst = max(worst, cbrt_ulps(1.0_wp + real(k, wp)*epsilon(1.0_wp)), &
                     cbrt_ulps(1.0_wp - real(k, wp)*0.5_wp*epsilon(1.0_wp)))
      end do
      write (buf, '(a,f6.3,a)') 'volume ratios 0.05 .. 20 (20,001 points) and 1 +- k ulp: at most ', &
         worst, ' ulp (bound 0.667)'
      call check(s, worst <= 0.667_wp, trim(buf))
      wexp = 0.0_wp
      do k = -1074, 1023
         ! 2^k, and 1.37 2^k and 1.999 2^k where they are representable
         wexp = max(wexp, cbrt_ulps(scale(1.0_wp, k)), cbrt_ulps(-scale(1.0_wp, k)))
         if (k > -1070) wexp = max(wexp, cbrt_ulps(1.37_wp*scale(1.0_wp, k)), &
                                   cbrt_ulps(1.999_wp*scale(1.0_wp, k)))
      end do
      wexp = max(wexp, cbrt_ulps(huge(1.0_wp)), cbrt_ulps(tiny(1.0_wp)), cbrt_ulps(nearest(tiny(1.0_wp), -1.0_wp)))
      write (buf, '(a,f6.3,a)') 'every exponent 2^-1074 .. 2^1023 (normal and subnormal, +-), huge, '// &
         'tiny: at most ', wexp, ' ulp'
      call check(s, wexp <= 0.667_wp, trim(buf))
      ! random bit patterns of every finite double (xorshift64)
      r = 88172645463325252_int64
      do i = 1, nr
         r = ieor(r, shiftl(r, 13)); r = ieor(r, shiftr(r, 7)); r = ieor(r, shiftl(r, 17))
         x(i) = transfer(iand(r, int(z'7fefffffffffffff', int64)), 1.0_wp)
         if (mod(i, 3) == 0) x(i) = -x(i)
      end do
      wrand = 0.0_wp
      do i = 1, nr
         wrand = max(wrand, cbrt_ulps(x(i)))
      end do
      write (buf, '(a,f6.3,a)') '100,003 random finite doubles of both signs: at most ', wrand, ' ulp'
      call check(s, wrand <= 0.667_wp, trim(buf))
      nexact = 0
      do k = 1, 1000
         if (cbrt(real(k, wp)**3) == real(k, wp)) nexact = nexact + 1
      end do
      do k = -340, 340
         if (cbrt(2.0_wp**(3*k)) == 2.0_wp**k) nexact = nexact + 1
      end do
      call check(s, nexact == 1000 + 681, 'k^3 -> k for k = 1..1000 and 2^(3k) -> 2^k, k = -340..340, exactly')
      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      inf = ieee_value(1.0_wp, ieee_positive_inf)
      call check(s, cbrt(1.0_wp) == 1.0_wp .and. cbrt(-8.0_wp) == -2.0_wp .and. cbrt(inf) == inf &
                 .and. cbrt(-inf) == -inf .and. ieee_is_nan(cbrt(nan)) .and. cbrt(0.0_wp) == 0.0_wp &
                 .and. transfer(cbrt(-0.0_wp), 1_int64) == transfer(-0.0_wp, 1_int64), &
                 'cbrt 1 = 1, cbrt -8 = -2, +-Inf, NaN and +-0 give themselves')
      x(1) = 1.0_wp; x(2) = 0.0_wp; x(3) = -0.0_wp; x(4) = inf; x(5) = -inf; x(6) = nan
      x(7) = tiny(1.0_wp)/3.0_wp; x(8) = huge(1.0_wp)
      call cbrt_block(nr, x, y)
      ndiff = bits_differ(y, cbrt(x))
      call check(s, ndiff == 0, 'cbrt_block(x) = cbrt(x) to the bit at 100,003 values (vector loop and '// &
                 'remainder, special values)')
   end subroutine test_cube_root

   !> base/flat.f90: all_finite agrees with ieee_is_finite on every value class at every
   !> position of arrays of 1 to 37 values (the vector loop's body, its remainder, both ends);
   !> copy_flat and sum_flat on a (2, n) array give the values of the array assignments.
   subroutine test_flat(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: v(10), x(37), a(2, 19), b(2, 19), c(2, 19)
      integer :: n, k, j, nbad
      call section(s, 'flat kernels: all_finite, copy_flat, sum_flat')
      v = [0.0_wp, -0.0_wp, huge(1.0_wp), -huge(1.0_wp), tiny(1.0_wp), 4.9406564584124654e-324_wp, &
           ieee_value(1.0_wp, ieee_quiet_nan), ieee_value(1.0_wp, ieee_positive_inf), &
           ieee_value(1.0_wp, ieee_negative_inf), 1.5_wp]
      nbad = 0
      do n = 1, size(x)
         do k = 1, n
            do j = 1, size(v)
               x(1:n) = 1.0_wp
               x(k) = v(j)
               if (all_finite(n, x) .neqv. all(ieee_is_finite(x(1:n)))) nbad = nbad + 1
            end do
         end do
      end do
      call check(s, nbad == 0, 'all_finite = all(ieee_is_finite) for NaN, +-Inf, +-huge, subnormal, +-0 '// &
                 'anywhere in 1 to 37 values')
      do k = 1, size(a, 2)
         a(:, k) = [real(k, wp)/3.0_wp, -real(k, wp)*7.0_wp]
         b(:, k) = [1.0_wp/real(k, wp), 0.1_wp*real(k, wp)]
      end do
      call copy_flat(size(a), a, c)
      call check(s, all(c == a), 'copy_flat copies a (2, n) array')
      call sum_flat(size(a), a, b, c)
      call check(s, all(c == a + b), 'sum_flat adds two (2, n) arrays as a + b does')
   end subroutine test_flat

end module test_math
