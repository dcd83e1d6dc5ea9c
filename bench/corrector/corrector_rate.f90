!> Cost of one contact-corrector call (corrector_t%solve) against the size of the active set,
!> on the dense LAPACK path and on the sparse LDL' path, to place `dense_limit`.
!>
!> The constraint set is a contact line: n slave nodes, each on the middle of a segment of a
!> deformable master chain (slave i on master nodes n+i, n+i+1, alpha = 1/2, normal (0, 1)),
!> all violated, so that S = G^T M^-1 G is tridiagonal and every multiplier is compressive
!> (one active-set pass). One call does everything the corrector does in a step: incidence,
!> assembly, factorization, solve, the corrected-gap check and the force application. Variants:
!>   dense   dense_limit = huge: dense_spd_t (scaled copy, dpotrf, pivot check, dpotrs)
!>   reuse   dense_limit = 0: sparse_ldl_t with the symbolic analysis kept (pattern unchanged)
!>   fresh   dense_limit = 0 with the analysis forgotten before each call (pattern changed)
!> Each time is the median over `nsample` samples of enough calls to last about 2 ms (the
!> variants alternate within each sample); every
!> solution is checked (corrected gaps closed, multipliers positive). Prints one row per n and
!> the smallest n from which each sparse variant stays cheaper than dense.
!> Run: fpm run --profile release --flag "-O3 -march=native -funroll-loops -ffp-contract=off" exic-bench-corrector
program corrector_rate
   use, intrinsic :: iso_fortran_env, only: output_unit
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t
   use exic_contact_corrector, only: constraints_t, corrector_t
   implicit none

   integer, parameter :: nsample = 9, ndense_max = 512
   integer, allocatable :: sizes(:)
   real(wp), allocatable :: times(:, :)
   integer :: t, n, k, cross_reuse, cross_fresh
   character(len=16) :: arg
   real(wp) :: tmin

   tmin = 2.0e-3_wp
   if (command_argument_count() >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) tmin
   end if
   sizes = [(k, k=1, 48), 56, 64, 80, 96, 128, 160, 192, 256, 384, 512, 1024, 2048, 4096]
   allocate (times(3, size(sizes)), source=-1.0_wp)
   write (output_unit, '(a)') '#     n    dense_us    reuse_us    fresh_us  reuse/dense  fresh/dense'
   do t = 1, size(sizes)
      n = sizes(t)
      call median_times(n, n <= ndense_max, times(:, t))
      if (times(1, t) > 0.0_wp) then
         write (output_unit, '(i7,3f12.3,2f13.3)') n, 1.0e6_wp*times(:, t), times(2, t)/times(1, t), &
            times(3, t)/times(1, t)
      else
         write (output_unit, '(i7,a12,2f12.3)') n, 'nan', 1.0e6_wp*times(2:3, t)
      end if
      flush (output_unit)
   end do
   cross_reuse = crossover(times(2, :))
   cross_fresh = crossover(times(3, :))
   write (output_unit, '(a,i0)') '# crossover, sparse with the analysis reused cheaper than dense from n = ', &
      cross_reuse
   write (output_unit, '(a,i0)') '# crossover, sparse with a fresh analysis cheaper than dense from n = ', &
      cross_fresh

contains

   !> Median times (s) of one corrector call of each variant with n constraints (dense: -1
   !> when not `with_dense`). The variants alternate within every sample, so that the load of
   !> a shared machine weighs on all three alike.
   subroutine median_times(n, with_dense, tmed)
      integer, intent(in) :: n
      logical, intent(in) :: with_dense
      real(wp), intent(out) :: tmed(3)
      type(constraints_t) :: cs
      type(corrector_t) :: corr(3)
      real(wp), allocatable :: minv(:, :), a(:, :), fcon(:, :)
      real(wp) :: samples(nsample, 3), c
      integer :: reps(3), i, v, nnode, v0

      nnode = 2*n + 1
      c = 1.0e-6_wp
      call contact_line(n, cs)
      allocate (minv(2, nnode), source=1.0_wp)
      allocate (a(2, nnode), fcon(2, nnode))
      v0 = merge(1, 2, with_dense)
      tmed = -1.0_wp
      do v = v0, 3
         corr(v)%dense_limit = merge(huge(1), 0, v == 1)
         call check_solution(v, n, cs, corr(v), nnode, minv, c)
         reps(v) = 1
         do
            if (elapsed(v, cs, corr(v), nnode, minv, c, a, fcon, reps(v)) > tmin) exit
            reps(v) = 2*reps(v)
         end do
      end do
      do i = 1, nsample
         do v = v0, 3
            samples(i, v) = elapsed(v, cs, corr(v), nnode, minv, c, a, fcon, reps(v))/real(reps(v), wp)
         end do
      end do
      do v = v0, 3
         tmed(v) = median(samples(:, v))
      end do
   end subroutine median_times

   !> Median of a few values.
   real(wp) function median(x) result(m)
      real(wp), intent(in) :: x(:)
      real(wp) :: s(size(x)), tmp
      integer :: i, j
      s = x
      do i = 2, size(s)
         tmp = s(i)
         j = i - 1
         do while (j >= 1)
            if (s(j) <= tmp) exit
            s(j + 1) = s(j)
            j = j - 1
         end do
         s(j + 1) = tmp
      end do
      m = s((size(s) + 1)/2)
   end function median

   !> n slave nodes on the middles of the segments of a master chain, all violated.
   subroutine contact_line(n, cs)
      integer, intent(in) :: n
      type(constraints_t), intent(inout) :: cs
      integer :: i
      real(wp) :: g
      call cs%reserve(n)
      do i = 1, n
         g = -1.0e-3_wp*(1.0_wp + 0.5_wp*sin(real(i, wp)))
         call cs%add(i, n + i, n + i + 1, 0.5_wp, [0.0_wp, 1.0_wp], g, g, 1)
      end do
   end subroutine contact_line

   !> Wall time (s) of `reps` corrector calls.
   real(wp) function elapsed(which, cs, corr, nnode, minv, c, a, fcon, reps) result(dt)
      integer, intent(in) :: which, nnode, reps
      type(constraints_t), intent(inout) :: cs
      type(corrector_t), intent(inout) :: corr
      real(wp), intent(in) :: minv(2, nnode), c
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      type(error_t), allocatable :: err
      integer(i8) :: c0, c1, rate
      integer :: r
      a = 0.0_wp
      fcon = 0.0_wp
      call system_clock(c0, rate)
      do r = 1, reps
         if (which == 3) corr%sparse%analyzed = .false.
         call corr%solve(cs, nnode, minv, c, a, fcon, err)
         if (allocated(err)) error stop 'corrector failed'
      end do
      call system_clock(c1)
      dt = real(c1 - c0, wp)/real(rate, wp)
   end function elapsed

   !> One call from zero: every multiplier positive and every corrected gap closed.
   subroutine check_solution(which, n, cs, corr, nnode, minv, c)
      integer, intent(in) :: which, n, nnode
      type(constraints_t), intent(inout) :: cs
      type(corrector_t), intent(inout) :: corr
      real(wp), intent(in) :: minv(2, nnode), c
      type(error_t), allocatable :: err
      real(wp) :: a(2, nnode), fcon(2, nnode), g, worst
      integer :: i
      a = 0.0_wp
      fcon = 0.0_wp
      call corr%solve(cs, nnode, minv, c, a, fcon, err)
      if (allocated(err)) error stop 'corrector failed'
      worst = 0.0_wp
      do i = 1, n
         g = cs%gap(i) + c*(a(2, i) - 0.5_wp*a(2, n + i) - 0.5_wp*a(2, n + i + 1))
         worst = max(worst, abs(g)/abs(cs%gap(i)))
      end do
      if (worst > 1.0e-10_wp .or. any(cs%p(1:n) <= 0.0_wp)) then
         write (output_unit, '(a,i0,a,i0,a,es10.3)') 'bad corrector solution, variant ', which, &
            ', n = ', n, ': relative gap ', worst
         error stop 1
      end if
   end subroutine check_solution

   !> Smallest measured n from which variant times stay below the dense times (0 if never).
   integer function crossover(tv) result(nc)
      real(wp), intent(in) :: tv(:)
      integer :: t
      nc = 0
      do t = size(sizes), 1, -1
         if (times(1, t) < 0.0_wp) cycle
         if (tv(t) >= times(1, t)) exit
         nc = sizes(t)
      end do
   end function crossover

end program corrector_rate
