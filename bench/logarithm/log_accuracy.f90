!> Accuracy and speed of the logarithms and cube roots a kernel can use (doc/decisions.md,
!> "Floating point"): exic's own (src/exic/base/logarithm.f90 and cube_root.f90, scalar and
!> vector give the same bits), glibc's scalar `log` and `pow(x, 1/3)`, and glibc's vector ones
!> (libmvec, which gfortran calls when it vectorizes a loop over `log` or `x**(1.0_wp/3.0_wp)`).
!> Errors in units in the last place against the exact values (quad precision) over J in
!> [0.05, 20] (log-uniform) and next to 1; times per value in a loop of 128 values near 1
!> (processor time).
!>
!> Run: fpm run exic-bench-log --profile release --flag "-O3 -march=native -funroll-loops
!>      -ffp-contract=off" [-- samples]
program log_accuracy
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln, ln_block
   use exic_base_cube_root, only: cbrt, cbrt_block
   use, intrinsic :: iso_fortran_env, only: real128
   implicit none
   integer, parameter :: LOG_FN = 1, CBRT_FN = 2, EXIC = 1, SCALAR = 2, VECTOR = 3
   character(len=*), parameter :: names(3, 2) = reshape([character(len=26) :: &
      'exic ln (block):', 'glibc log (scalar):', 'glibc libmvec log:', &
      'exic cbrt (block):', 'glibc pow x^(1/3):', 'glibc libmvec pow x^(1/3):'], [3, 2])
   integer :: n, q, nd, fn, v
   real(wp), allocatable :: x(:), y(:, :)
   real(wp) :: u, e, emax(3), xw(3), acc
   real(real128) :: t
   character(len=32) :: arg

   n = 4000000
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) n
   end if
   allocate (x(n), y(n, 3))
   do q = 1, n
      if (q <= n/2) then
         ! log-uniform over [0.05, 20]
         x(q) = 0.05_wp*400.0_wp**(real(q - 1, wp)/real(n/2 - 1, wp))
      else
         ! next to 1: 1 +- 10^(-16 u) (1 + u)/2
         u = real(q - n/2, wp)/real(n - n/2 + 1, wp)
         u = modulo(u*7919.0_wp, 1.0_wp)
         x(q) = 1.0_wp + sign(10.0_wp**(-16.0_wp*u), u - 0.5_wp)*(1.0_wp + u)*0.5_wp
      end if
   end do
   print '(a,i0,a)', 'samples ', n, ' (half log-uniform in [0.05, 20], half next to 1)'
   acc = 0.0_wp
   do fn = LOG_FN, CBRT_FN
      do v = EXIC, VECTOR
         call evaluate(fn, v, n, x, y(:, v))
      end do
      emax = 0.0_wp
      xw = 1.0_wp
      nd = 0
      do q = 1, n
         if (fn == LOG_FN) then
            if (y(q, EXIC) /= ln(x(q))) nd = nd + 1
            t = log(real(x(q), real128))
         else
            if (y(q, EXIC) /= cbrt(x(q))) nd = nd + 1
            t = real(x(q), real128)**(1.0_real128/3.0_real128)
         end if
         if (t == 0.0_real128) cycle
         u = spacing(real(t, wp))
         do v = EXIC, VECTOR
            e = real(abs(real(y(q, v), real128) - t), wp)/u
            if (e > emax(v)) then
               emax(v) = e
               xw(v) = x(q)
            end if
         end do
      end do
      do v = EXIC, VECTOR
         print '(a26,a,f7.4,a,es23.16,a,f6.2,a)', names(v, fn), ' max ', emax(v), ' ulp at ', xw(v), &
            ', ', time_ns(fn, v, acc), ' ns per value'
      end do
      print '(a,a,i0)', trim(names(EXIC, fn)), ' block /= elemental at ', nd
   end do
   print '(a,es12.5)', 'checksum ', acc

contains

   !> y = the function fn (LOG_FN, CBRT_FN) of x by the variant v (EXIC, SCALAR, VECTOR).
   subroutine evaluate(fn, v, n, x, y)
      integer, intent(in) :: fn, v, n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      select case (3*(fn - 1) + v)
      case (1)
         call ln_block(n, x, y)
      case (2)
         call scalar_log(n, x, y)
      case (3)
         call vector_log(n, x, y)
      case (4)
         call cbrt_block(n, x, y)
      case (5)
         call scalar_pow(n, x, y)
      case default
         call vector_pow(n, x, y)
      end select
   end subroutine evaluate

   !> glibc's log in a loop the compiler vectorizes (libmvec).
   subroutine vector_log(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: i
      do i = 1, n
         y(i) = log(x(i))
      end do
   end subroutine vector_log

   !> glibc's scalar log.
   subroutine scalar_log(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: i
      !GCC$ novector
      do i = 1, n
         y(i) = log(x(i))
      end do
   end subroutine scalar_log

   !> x^(1/3) by glibc's pow in a loop the compiler vectorizes (libmvec).
   subroutine vector_pow(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: i
      do i = 1, n
         y(i) = x(i)**(1.0_wp/3.0_wp)
      end do
   end subroutine vector_pow

   !> x^(1/3) by glibc's scalar pow.
   subroutine scalar_pow(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      integer :: i
      !GCC$ novector
      do i = 1, n
         y(i) = x(i)**(1.0_wp/3.0_wp)
      end do
   end subroutine scalar_pow

   !> Processor time per value (ns) of the variant v of fn over 200,000 loops of 128 values near
   !> 1 (the volume ratios of a run); acc takes a value of each loop, so that none is skipped.
   real(wp) function time_ns(fn, v, acc)
      integer, intent(in) :: fn, v
      real(wp), intent(inout) :: acc
      real(wp) :: xb(128), yb(128), p0, p1
      integer :: q, rep
      do q = 1, 128
         xb(q) = 0.9_wp + 0.2_wp*real(q, wp)/128.0_wp
      end do
      call cpu_time(p0)
      do rep = 1, 200000
         call evaluate(fn, v, 128, xb, yb)
         acc = acc + yb(rep - 128*((rep - 1)/128))
         xb(1) = xb(1) + 1.0e-17_wp
      end do
      call cpu_time(p1)
      time_ns = (p1 - p0)/(200000.0_wp*128.0_wp)*1.0e9_wp
   end function time_ns

end program log_accuracy
