!> Throughput of the quadrilateral force kernels: element-steps per second on a 120 x 24 mesh
!> (or nx x ny: `exic-bench-element nsteps nx ny`).
!>
!> Times q4_force_2x2, q4_force_1pt (each with the stable step fused in) and q4_stable_dt alone
!> (each step zeroes the force array first, as the explicit driver does) in 5 repetitions and
!> prints the median and range, in wall time and in processor time (the latter is what counts on
!> a shared, loaded machine).
!> `exic-bench-element bandwidth` measures the memory bandwidth instead (triad a = b + s c and
!> copy over 3 x 128 MB, best of 10, on OMP_NUM_THREADS threads): the roofline of
!> doc/performance.md.
!> `exic-bench-element plastic [nsteps]` times the general solid path instead (q4_general.f90:
!> the elastic law through it, J2 plasticity where no point yields, J2 where every point yields
!> at every step; 2x2, 2x2 MIXEd and one point) against the elastic kernels, in processor time:
!> the figures of doc/performance.md, "Plasticity".
!> Build: fpm build --profile release --flag "-O3 -march=native -funroll-loops -ffp-contract=off"
!> Run:   fpm run exic-bench-element --profile release --flag "..." [-- nsteps | bandwidth]
program element_rate
   use exic_material_law, only: neohookean_law, law_make, LAW_J2, LAW_NEOHOOKEAN
   use exic_base_kinds, only: wp, i8
   use exic_element_quad4, only: q4_check_reference, q4_force_2x2, q4_force_1pt, q4_stable_dt
   use exic_element_q4_general, only: q4_solid_t, q4g_init, q4g_force, q4g_hist_init
   use exic_material_j2_hardening, only: j2_param_t, J2_MISES
   !$ use omp_lib, only: omp_get_max_threads
   implicit none
   integer, parameter :: nrep = 5
   integer :: nx, ny, nel, nnode, nsteps, i, j, e, rep, ebad, emin, efold, step, nargs
   integer, allocatable :: conn(:, :)
   real(wp), allocatable :: x0(:, :), u(:, :), f(:, :), x(:, :)
   real(wp) :: lambda, mu, wint, whg, jmin, dtmin, chk, t(nrep, 3), tc(nrep, 3), xx, yy, p0, p1
   character(len=32) :: arg
   integer(i8) :: c0, c1, rate
   logical :: plastic_mode

   nsteps = 3000
   plastic_mode = .false.
   nargs = command_argument_count()
   if (nargs >= 1) then
      call get_command_argument(1, arg)
      if (arg == 'bandwidth') then
         call bandwidth()
         stop
      end if
      if (arg == 'plastic') then
         plastic_mode = .true.
         nsteps = 300
         if (nargs >= 2) then
            call get_command_argument(2, arg)
            read (arg, *) nsteps
         end if
         nargs = 0
      else
         read (arg, *) nsteps
      end if
   end if
   nx = 120
   ny = 24
   if (nargs >= 3) then
      call get_command_argument(2, arg)
      read (arg, *) nx
      call get_command_argument(3, arg)
      read (arg, *) ny
   end if
   lambda = 33333.0_wp
   mu = 5000.0_wp
   nel = nx*ny
   nnode = (nx + 1)*(ny + 1)
   allocate (conn(4, nel), x0(2, nnode), u(2, nnode), f(2, nnode))
   ! a 30 x 6 bar of slightly distorted squares, bent and stretched
   do j = 0, ny
      do i = 0, nx
         xx = 0.25_wp*i + 0.03_wp*sin(1.7_wp*i + 2.3_wp*j)
         yy = 0.25_wp*j + 0.03_wp*cos(2.9_wp*i - 1.1_wp*j)
         x0(:, 1 + i + (nx + 1)*j) = [xx, yy]
         u(:, 1 + i + (nx + 1)*j) = [0.01_wp*xx + 0.02_wp*yy*sin(0.1_wp*xx), 0.002_wp*xx*xx*(30.0_wp/(0.25_wp*nx))]
      end do
   end do
   do j = 0, ny - 1
      do i = 0, nx - 1
         e = 1 + i + nx*j
         conn(:, e) = [1 + i + (nx + 1)*j, 2 + i + (nx + 1)*j, 2 + i + (nx + 1)*(j + 1), &
                       1 + i + (nx + 1)*(j + 1)]
      end do
   end do
   call q4_check_reference(nel, nnode, conn, x0, ebad)
   x = x0 + u
   if (plastic_mode) then
      call plastic_rates()
      stop
   end if

   call system_clock(count_rate=rate)
   chk = 0.0_wp
   do rep = 1, nrep
      call system_clock(c0)
      call cpu_time(p0)
      do step = 1, nsteps
         f = 0.0_wp
         call q4_force_2x2(nel, nnode, conn, x0, u, neohookean_law(lambda, mu, 0.1_wp), f, wint, &
               jmin, ebad, dtmin, emin, efold)
      end do
      call system_clock(c1)
      call cpu_time(p1)
      t(rep, 1) = real(c1 - c0, wp)/real(rate, wp)
      tc(rep, 1) = p1 - p0
      chk = chk + f(1, nnode) + wint
      call system_clock(c0)
      call cpu_time(p0)
      do step = 1, nsteps
         f = 0.0_wp
         call q4_force_1pt(nel, nnode, conn, x0, u, neohookean_law(lambda, mu, 0.1_wp), 0.1_wp, f, wint, whg, &
                           jmin, ebad, dtmin, emin, efold)
      end do
      call system_clock(c1)
      call cpu_time(p1)
      t(rep, 2) = real(c1 - c0, wp)/real(rate, wp)
      tc(rep, 2) = p1 - p0
      chk = chk + f(1, nnode) + wint + whg
      call system_clock(c0)
      call cpu_time(p0)
      do step = 1, nsteps
         call q4_stable_dt(2, nel, nnode, conn, x0, x, neohookean_law(lambda, mu, 0.1_wp), dtmin, emin, efold)
         chk = chk + dtmin
      end do
      call system_clock(c1)
      call cpu_time(p1)
      t(rep, 3) = real(c1 - c0, wp)/real(rate, wp)
      tc(rep, 3) = p1 - p0
   end do
   print '(a,i0,a,i0,a,i0,a,i0,a)', 'mesh ', nx, ' x ', ny, ' (', nel, ' elements), ', nsteps, &
      ' steps, median of 5 runs'
   call report('q4_force_2x2', t(:, 1))
   call report('q4_force_1pt', t(:, 2))
   call report('q4_stable_dt', t(:, 3))
   call report('q4_force_2x2 cpu', tc(:, 1))
   call report('q4_force_1pt cpu', tc(:, 2))
   call report('q4_stable_dt cpu', tc(:, 3))
   print '(a,es12.5)', 'checksum ', chk

contains

   !> Processor time per element-step of the general path against the elastic kernels (median
   !> of nrep runs of nsteps steps each). "every point yields": Y0 = 1e-3 mu and the history
   !> restored before each step (the restore is timed alone and subtracted).
   subroutine plastic_rates()
      type(j2_param_t) :: prm
      type(q4_solid_t) :: o
      real(wp), allocatable :: h(:, :, :), h0(:, :, :), one(:, :, :)
      real(wp) :: ww, wh, wd, jm, d2, tr(nrep), tk(nrep, 12)
      integer :: eb, em, ef, c, nq, k
      character(len=40) :: names(12)
      prm%law = J2_MISES
      allocate (one(1, 1, 1), source=0.0_wp)
      k = 0
      do nq = 2, 1, -1
         do c = 1, 5
            if (nq == 1 .and. c == 5) cycle
            k = k + 1
            select case (c)
            case (1)
               o = q4g_init(nq, .false., .false., law_make(LAW_NEOHOOKEAN, lambda, mu, 0.1_wp, prm), 0.1_wp)
               names(k) = 'elastic kernel (quad4)'
            case (2)
               o = q4g_init(nq, .false., .false., law_make(LAW_NEOHOOKEAN, lambda, mu, 0.1_wp, prm), 0.1_wp)
               names(k) = 'general path, elastic'
            case (3)
               prm%y0 = 1.0e3_wp*mu
               prm%yinf = prm%y0
               o = q4g_init(nq, .false., .false., law_make(LAW_J2, lambda, mu, 0.1_wp, prm), 0.1_wp)
               names(k) = 'J2, no point yields'
            case (4, 5)
               prm%y0 = 1.0e-3_wp*mu
               prm%yinf = prm%y0
               prm%hiso = 0.1_wp*mu
               o = q4g_init(nq, .false., c == 5, law_make(LAW_J2, lambda, mu, 0.1_wp, prm), 0.1_wp)
               names(k) = 'J2, every point yields'
               if (c == 5) names(k) = 'J2 MIXEd, every point yields'
            end select
            if (nq == 1) names(k) = trim(names(k))//' (1 pt)'
            if (nq == 2) names(k) = trim(names(k))//' (2x2)'
            if (o%plastic) then
               if (allocated(h)) deallocate (h, h0)
               allocate (h(o%nvar, nq*nq, nel), h0(o%nvar, nq*nq, nel))
               call q4g_hist_init(o, nel, h0)
               h = h0
            end if
            do rep = 1, nrep
               call cpu_time(p0)
               do step = 1, nsteps
                  f = 0.0_wp
                  if (c == 1 .and. nq == 2) then
                     call q4_force_2x2(nel, nnode, conn, x0, u, neohookean_law(lambda, mu, 0.1_wp), f, wint, jmin, &
                                       ebad, dtmin, emin, efold)
                  else if (c == 1) then
                     call q4_force_1pt(nel, nnode, conn, x0, u, neohookean_law(lambda, mu, 0.1_wp), 0.1_wp, f, wint, &
                                       whg, jmin, ebad, dtmin, emin, efold)
                  else if (c == 2) then
                     call q4g_force(o, nel, nnode, conn, x0, u, 1.0e-3_wp, one, f, ww, wh, wd, jm, &
                                    eb, d2, em, ef)
                  else
                     if (c >= 4) h = h0
                     call q4g_force(o, nel, nnode, conn, x0, u, 1.0e-3_wp, h, f, ww, wh, wd, jm, eb, &
                                    d2, em, ef)
                  end if
               end do
               call cpu_time(p1)
               tk(rep, k) = p1 - p0
               chk = chk + f(1, nnode)
               if (c >= 4) then
                  call cpu_time(p0)
                  do step = 1, nsteps
                     h = h0
                     chk = chk + h(1, 1, step - nsteps*(step/nsteps) + 1)
                  end do
                  call cpu_time(p1)
                  tr(rep) = p1 - p0
               end if
            end do
            if (c >= 4) tk(:, k) = tk(:, k) - sort_median(tr)
         end do
      end do
      print '(a,i0,a,i0,a,i0,a,i0,a)', 'mesh ', nx, ' x ', ny, ' (', nel, ' elements), ', nsteps, &
         ' steps, processor time, median of 5 runs'
      do c = 1, k
         call report(trim(names(c)), tk(:, c))
      end do
      print '(a,es12.5)', 'checksum ', chk
   end subroutine plastic_rates

   real(wp) function sort_median(v) result(m)
      real(wp), intent(in) :: v(:)
      real(wp) :: s(size(v))
      integer :: a
      s = v
      do a = 1, size(s)
         s(a:) = cshift(s(a:), minloc(s(a:), 1) - 1)
      end do
      m = s((size(s) + 1)/2)
   end function sort_median

   !> Best of 10 rates of a triad and a copy over arrays of 16 M reals (128 MB each), shared
   !> among the OpenMP threads (first touch by the same threads).
   subroutine bandwidth()
      integer, parameter :: m = 16*1024*1024
      real(wp), allocatable :: a(:), b(:), c(:)
      real(wp) :: best(2), w0, w1
      integer(i8) :: r0, r1, rt
      integer :: i, it, nth
      allocate (a(m), b(m), c(m))
      !$omp parallel do schedule(static)
      do i = 1, m
         a(i) = 0.0_wp
         b(i) = 1.0_wp
         c(i) = 2.0_wp
      end do
      !$omp end parallel do
      best = huge(1.0_wp)
      call system_clock(count_rate=rt)
      do it = 1, 10
         call system_clock(r0)
         !$omp parallel do schedule(static)
         do i = 1, m
            a(i) = b(i) + 3.0_wp*c(i)
         end do
         !$omp end parallel do
         call system_clock(r1)
         w0 = real(r1 - r0, wp)/real(rt, wp)
         call system_clock(r0)
         !$omp parallel do schedule(static)
         do i = 1, m
            b(i) = a(i)
         end do
         !$omp end parallel do
         call system_clock(r1)
         w1 = real(r1 - r0, wp)/real(rt, wp)
         best = min(best, [w0, w1])
      end do
      nth = 1
      !$ nth = omp_get_max_threads()
      print '(a,i0,a,f7.2,a,f7.2,a)', 'bandwidth threads ', nth, ': triad ', 24.0_wp*m/best(1)/1e9_wp, &
         ' GB/s, copy ', 16.0_wp*m/best(2)/1e9_wp, ' GB/s'
      print '(a,es12.5)', 'checksum ', a(7) + b(9)
   end subroutine bandwidth

   subroutine report(name, times)
      character(len=*), intent(in) :: name
      real(wp), intent(in) :: times(:)
      real(wp) :: s(size(times)), r
      integer :: a, b
      s = times
      do a = 2, size(s)
         r = s(a)
         b = a - 1
         do while (b >= 1)
            if (s(b) <= r) exit
            s(b + 1) = s(b)
            b = b - 1
         end do
         s(b + 1) = r
      end do
      r = real(nel, wp)*real(nsteps, wp)
      print '(a,a,f8.3,a,f8.3,a,f8.3,a)', name, ': ', r/s((size(s) + 1)/2)/1e6_wp, &
         ' M element-steps/s (range ', r/s(size(s))/1e6_wp, ' - ', r/s(1)/1e6_wp, ')'
   end subroutine report

end program element_rate
