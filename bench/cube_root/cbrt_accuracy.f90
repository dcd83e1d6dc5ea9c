!> Accuracy and speed of the cube roots a kernel can use (doc/decisions.md, "Floating point"):
!> exic's own (src/exic/base/cube_root.f90, scalar and vector give the same bits), glibc's scalar
!> `pow(x, 1/3)` and glibc's vector `pow` (libmvec, which gfortran calls when it vectorizes a
!> loop over `x**(1.0_wp/3.0_wp)`: what the mean-dilatation elements used before). Errors in
!> units in the last place against the exact cube root (quad precision) over volume ratios in
!> [0.05, 20] (log-uniform) and next to 1; times per value in a loop of 128 values (processor
!> time).
!>
!> Run: fpm run exic-bench-cbrt --profile release --flag "-O3 -march=native -funroll-loops
!>      -ffp-contract=off" [-- samples]
program cbrt_accuracy
   use exic_base_kinds, only: wp
   use exic_base_cube_root, only: cbrt, cbrt_block
   use, intrinsic :: iso_fortran_env, only: real128
   implicit none
   integer :: n, q, nd, rep, k
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
         x(q) = 0.05_wp*400.0_wp**(real(q - 1, wp)/real(n/2 - 1, wp))
      else
         u = real(q - n/2, wp)/real(n - n/2 + 1, wp)
         u = modulo(u*7919.0_wp, 1.0_wp)
         x(q) = 1.0_wp + sign(10.0_wp**(-16.0_wp*u), u - 0.5_wp)*(1.0_wp + u)*0.5_wp
      end if
   end do
   call cbrt_block(n, x, yv)
   call vector_pow(n, x, ym)
   emax = 0.0_wp
   xw = 1.0_wp
   nd = 0
   do q = 1, n
      if (yv(q) /= cbrt(x(q))) nd = nd + 1
      t = real(x(q), real128)**(1.0_real128/3.0_real128)
      u = spacing(real(t, wp))
      e(1) = real(abs(real(yv(q), real128) - t), wp)/u
      e(2) = real(abs(real(x(q)**(1.0_wp/3.0_wp), real128) - t), wp)/u
      e(3) = real(abs(real(ym(q), real128) - t), wp)/u
      where (e > emax)
         emax = e
         xw = x(q)
      end where
   end do
   ! speed: 128 values near 1 (the ratios Jbar/J of a run), repeated
   do q = 1, 128
      xb(q) = 0.9_wp + 0.2_wp*real(q, wp)/128.0_wp
   end do
   acc = 0.0_wp
   do k = 1, 3
      call cpu_time(p0)
      do rep = 1, 200000
         select case (k)
         case (1)
            call cbrt_block(128, xb, yb)
         case (2)
            call scalar_pow(128, xb, yb)
         case default
            call vector_pow(128, xb, yb)
         end select
         acc = acc + yb(rep - 128*((rep - 1)/128))
         xb(1) = xb(1) + 1.0e-17_wp
      end do
      call cpu_time(p1)
      tns(k) = (p1 - p0)/(200000.0_wp*128.0_wp)*1.0e9_wp
   end do
   print '(a,i0,a)', 'samples ', n, ' (half log-uniform in [0.05, 20], half next to 1)'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'exic cbrt (block):        max ', emax(1), ' ulp at ', xw(1), ', ', &
      tns(1), ' ns per value'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'glibc pow x^(1/3):        max ', emax(2), ' ulp at ', xw(2), ', ', &
      tns(2), ' ns per value'
   print '(a,f7.4,a,es23.16,a,f6.2,a)', 'glibc libmvec pow x^(1/3): max ', emax(3), ' ulp at ', xw(3), ', ', &
      tns(3), ' ns per value'
   print '(a,i0)', 'exic cbrt: block /= elemental at ', nd
   print '(a,es12.5)', 'checksum ', acc

contains

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

end program cbrt_accuracy
