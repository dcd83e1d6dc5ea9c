!> Accuracy and speed of the logarithms a kernel can use (doc/decisions.md, "Floating point"):
!> exic's own (src/exic/base/logarithm.f90, scalar and vector give the same bits), glibc's scalar
!> `log`, and glibc's vector `log` (libmvec, which gfortran calls when it vectorizes a loop over
!> `log`). Errors in units in the last place against quad precision over J in [0.05, 20]
!> (log-uniform) and next to 1; times per logarithm in a loop of 128 values (processor time).
!>
!> Run: fpm run exic-bench-log --profile release --flag "-O3 -march=native -funroll-loops
!>      -ffp-contract=off" [-- samples]
program log_accuracy
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln, ln_block
   use, intrinsic :: iso_fortran_env, only: real128
   implicit none
   integer :: n, q, nd, rep
   real(wp), allocatable :: x(:), yv(:), ym(:)
   real(wp) :: u, e(3), emax(3), xw(3), p0, p1, xb(128), yb(128), acc, tns(3)
   real(real128) :: t
   character(len=32) :: arg

   n = 4000000
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) n
   end if
   allocate (x(n), yv(n), ym(n))
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
   call ln_block(n, x, yv)
   call vector_log(n, x, ym)
   emax = 0.0_wp
   xw = 1.0_wp
   nd = 0
   do q = 1, n
      if (yv(q) /= ln(x(q))) nd = nd + 1
      t = log(real(x(q), real128))
      if (t == 0.0_real128) cycle
      u = spacing(real(t, wp))
      e(1) = real(abs(real(yv(q), real128) - t), wp)/u
      e(2) = real(abs(real(log(x(q)), real128) - t), wp)/u
      e(3) = real(abs(real(ym(q), real128) - t), wp)/u
      where (e > emax)
         emax = e
         xw = x(q)
      end where
   end do
   ! speed: 128 values near 1 (the volume ratios of a run), repeated
   do q = 1, 128
      xb(q) = 0.9_wp + 0.2_wp*real(q, wp)/128.0_wp
   end do
   acc = 0.0_wp
   call cpu_time(p0)
   do rep = 1, 200000
      call ln_block(128, xb, yb)
      acc = acc + yb(rep - 128*((rep - 1)/128))
      xb(1) = xb(1) + 1.0e-17_wp
   end do
   call cpu_time(p1)
   tns(1) = (p1 - p0)/(200000.0_wp*128.0_wp)*1.0e9_wp
   call cpu_time(p0)
   do rep = 1, 200000
      call scalar_log(128, xb, yb)
      acc = acc + yb(rep - 128*((rep - 1)/128))
      xb(1) = xb(1) + 1.0e-17_wp
   end do
   call cpu_time(p1)
   tns(2) = (p1 - p0)/(200000.0_wp*128.0_wp)*1.0e9_wp
   call cpu_time(p0)
   do rep = 1, 200000
      call vector_log(128, xb, yb)
      acc = acc + yb(rep - 128*((rep - 1)/128))
      xb(1) = xb(1) + 1.0e-17_wp
   end do
   call cpu_time(p1)
   tns(3) = (p1 - p0)/(200000.0_wp*128.0_wp)*1.0e9_wp
   print '(a,i0,a)', 'samples ', n, ' (half log-uniform in [0.05, 20], half next to 1)'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'exic ln (block):     max ', emax(1), ' ulp at ', xw(1), ', ', tns(1), &
      ' ns per log'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'glibc log (scalar):  max ', emax(2), ' ulp at ', xw(2), ', ', tns(2), &
      ' ns per log'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'glibc libmvec log:   max ', emax(3), ' ulp at ', xw(3), ', ', tns(3), &
      ' ns per log'
   print '(a,i0)', 'exic ln: block /= elemental at ', nd
   print '(a,es12.5)', 'checksum ', acc

contains

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

end program log_accuracy
