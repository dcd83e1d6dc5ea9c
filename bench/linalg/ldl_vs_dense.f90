!> Dense Cholesky versus sparse LDL' on contact-chain matrices S = G^T M^-1 G (n = 1..512).
!>
!> For each n it times, as the median of `nsample` samples of enough repetitions to last
!> about 1 ms each:
!>   dense   dense_spd_t%factorize + solve (scaled copy, dpotrf, pivot check, dpotrs)
!>   full    sparse_ldl_t%analyze + factorize + solve (AMD, ldl_symbolic, ldl_numeric)
!>   reuse   sparse_ldl_t%factorize + solve with the analysis kept
!> and prints the smallest n from which each sparse variant is cheaper than dense for every
!> larger n measured. Run in release mode:
!>   fpm run --profile release --flag "-O3 -march=native" exic-bench-linalg
!> Measured on the 2-core development machine (gfortran 12, OpenBLAS as LAPACK), 8 runs:
!> with the analysis reused, sparse is cheaper at every n >= 1 (0.2-0.3 x dense for
!> n < 32, 0.005 x at n = 512); with a fresh analysis every step the crossover is n ~ 31
!> (runs gave 30, 30, 31, 31, 32, 35, 37, 77). Below it the difference is under 1 us.
program ldl_vs_dense
   use, intrinsic :: iso_fortran_env, only: int64, output_unit
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_linalg_sparse_ldl, only: sparse_ldl_t
   use exic_linalg_dense_spd, only: dense_spd_t
   implicit none

   integer, parameter :: nmax = 512, nsample = 7
   integer, allocatable :: sizes(:), ap(:), ai(:), bad(:)
   real(wp), allocatable :: ax(:), sd(:, :), b(:), x(:), times(:, :)
   type(sparse_ldl_t) :: sp
   type(dense_spd_t) :: de
   type(error_t), allocatable :: err
   integer :: t, n, k, nbad, cross_full, cross_reuse
   real(wp) :: resid

   sizes = [(k, k=1, 128), (k, k=144, nmax, 16)]
   allocate (times(3, size(sizes)), bad(nmax), b(nmax), x(nmax))
   write (output_unit, '(a)') '#     n    dense_us     full_us    reuse_us   full/dense  reuse/dense'
   do t = 1, size(sizes)
      n = sizes(t)
      call chain(n, ap, ai, ax, sd)
      call random_number(b(1:n))
      call sp%analyze(n, ap, ai, err)
      call sp%factorize(ax, nbad, bad, err)
      call sp%solve(b(1:n), x(1:n))
      resid = chain_residual(n, sd, x, b)
      if (resid > 1.0e-12_wp .or. nbad /= 0) then
         write (output_unit, '(a,i0,a,es10.3)') 'bad sparse solution at n = ', n, ': ', resid
         error stop 1
      end if
      times(1, t) = median_time(1, n)
      times(2, t) = median_time(2, n)
      times(3, t) = median_time(3, n)
      write (output_unit, '(i7,3f12.3,2f13.3)') n, 1.0e6_wp*times(:, t), &
         times(2, t)/times(1, t), times(3, t)/times(1, t)
      flush (output_unit)
   end do
   cross_full = crossover(times(2, :))
   cross_reuse = crossover(times(3, :))
   write (output_unit, '(a,i0)') '# crossover, sparse analyze+factorize+solve cheaper than dense from n = ', &
      cross_full
   write (output_unit, '(a,i0)') '# crossover, sparse factorize+solve (analysis reused) cheaper from n = ', &
      cross_reuse

contains

   !> Median over nsample samples of the time (s) of one call of variant `which` at order n.
   real(wp) function median_time(which, n) result(tmed)
      integer, intent(in) :: which, n
      real(wp) :: samples(nsample), tmp
      integer :: reps, i, j
      reps = 1
      do
         if (elapsed(which, n, reps) > 1.0e-3_wp) exit
         reps = 2*reps
      end do
      do i = 1, nsample
         samples(i) = elapsed(which, n, reps)/real(reps, wp)
      end do
      do i = 2, nsample
         tmp = samples(i)
         j = i - 1
         do while (j >= 1)
            if (samples(j) <= tmp) exit
            samples(j + 1) = samples(j)
            j = j - 1
         end do
         samples(j + 1) = tmp
      end do
      tmed = samples((nsample + 1)/2)
   end function median_time

   !> Wall time (s) of reps calls of variant `which`.
   real(wp) function elapsed(which, n, reps) result(dt)
      integer, intent(in) :: which, n, reps
      integer(int64) :: c0, c1, rate
      integer :: r
      call system_clock(c0, rate)
      do r = 1, reps
         select case (which)
         case (1)
            call de%factorize(sd, nbad, bad, err)
            call de%solve(b(1:n), x(1:n))
         case (2)
            call sp%analyze(n, ap, ai, err)
            call sp%factorize(ax, nbad, bad, err)
            call sp%solve(b(1:n), x(1:n))
         case default
            call sp%factorize(ax, nbad, bad, err)
            call sp%solve(b(1:n), x(1:n))
         end select
      end do
      call system_clock(c1)
      dt = real(c1 - c0, wp)/real(rate, wp)
   end function elapsed

   !> Smallest measured n from which tsparse < tdense for every larger measured n.
   integer function crossover(tsparse) result(nc)
      real(wp), intent(in) :: tsparse(:)
      integer :: i
      nc = -1
      do i = size(sizes), 1, -1
         if (tsparse(i) >= times(1, i)) exit
         nc = sizes(i)
      end do
   end function crossover

   !> A contact line of n node-on-segment constraints: slave c on master segment (c, c+1),
   !> normals within 0.1 rad of vertical, random masses. S is tridiagonal.
   subroutine chain(n, ap, ai, ax, sd)
      integer, intent(in) :: n
      integer, allocatable, intent(out) :: ap(:), ai(:)
      real(wp), allocatable, intent(out) :: ax(:), sd(:, :)
      real(wp) :: alpha(n), theta(n), ms(n), mm(n + 1)
      integer :: c, q, i
      call random_number(alpha)
      call random_number(theta)
      theta = 0.2_wp*(theta - 0.5_wp)
      call random_number(ms)
      call random_number(mm)
      ms = 1.0_wp/(0.5_wp + ms)
      mm = 1.0_wp/(0.5_wp + mm)
      allocate (sd(n, n), source=0.0_wp)
      do c = 1, n
         sd(c, c) = ms(c) + (1.0_wp - alpha(c))**2*mm(c) + alpha(c)**2*mm(c + 1)
         if (c < n) then
            sd(c, c + 1) = alpha(c)*(1.0_wp - alpha(c + 1))*cos(theta(c) - theta(c + 1))*mm(c + 1)
            sd(c + 1, c) = sd(c, c + 1)
         end if
      end do
      allocate (ap(n + 1), ai(3*n), ax(3*n))
      q = 0
      ap(1) = 1
      do c = 1, n
         do i = max(1, c - 1), min(n, c + 1)
            q = q + 1
            ai(q) = i
            ax(q) = sd(i, c)
         end do
         ap(c + 1) = q + 1
      end do
      ai = ai(1:q)
      ax = ax(1:q)
   end subroutine chain

   !> ||S x - b|| / ||b|| with the dense S.
   real(wp) function chain_residual(n, sd, x, b) result(r)
      integer, intent(in) :: n
      real(wp), intent(in) :: sd(:, :), x(:), b(:)
      r = norm2(matmul(sd(1:n, 1:n), x(1:n)) - b(1:n))/norm2(b(1:n))
   end function chain_residual

end program ldl_vs_dense
