!> The central-difference kernels of one step (seed eq. 4.3-4.4) on plain arrays.
!>
!> With distinct dt(n) and dt(n+1), one step is
!>   x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)                  cd_displacement, positions
!>   M a~(n+1) = F - P(u(n+1)),  v~(n+1) = v(n) + dt(n)/2 (a(n) + a~(n+1))   cd_predictor (4.3-4.4)
!>   contact corrector: a(n+1) = a~(n+1) - M^-1 G lambda         (4.5-4.7, src/exic/contact)
!>   v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1))                       cd_velocity
!> Arrays are (component, node); every kernel is one pass without temporaries.
!>
!> Threads (OpenMP): the nodes are cut into fixed chunks of CHUNK nodes, shared among the
!> threads; each chunk is one call of a serial kernel on plain arrays (which the compiler
!> vectorizes: inside an OpenMP region it could not tell the arrays apart). Sums (works, kinetic
!> energy, momentum) are formed per chunk, in interleaved partial sums combined in a fixed tree
!> (src/exic/base/sums.f90: vectorized, in an order fixed by the chunk alone), and the chunks' sums
!> are added in chunk order by one thread: the results are the same to the bit for every number
!> of threads (no `reduction` clause on reals, whose order would depend on the threads).
!> Meshes of fewer than PAR_MIN_NODES nodes run on one thread.
module exic_explicit_central
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum, ordered_sum
   use exic_base_threads, only: threaded
   implicit none
   private

   public :: cd_displacement, cd_predictor, cd_velocity, positions, cd_zero, cd_kinetic
   public :: cd_kinetic_power, cd_displacement_plain, cd_update_plain
   public :: cd_displacement_plain_at, cd_update_plain_chunks, cd_plain_fold
   public :: positions_at, predictor_velocity_at, cd_contact_power

   !> Nodes per chunk (fixed: the order of the additions of a sum must not depend on threads).
   integer, parameter, public :: CHUNK = 1024
   !> Smallest mesh whose nodal loops run on several threads; smaller ones, and every mesh when
   !> one thread is allowed, take each loop's serial branch, which does not enter OpenMP
   !> (exic_base_threads) and makes the same operations in the same order.
   integer, parameter, public :: PAR_MIN_NODES = 4096
   !> The external force of a chunk where it is +0 at every dof (cd_update_plain): read from
   !> the cache instead of streaming fext from memory, the same values.
   real(wp), parameter :: ZERO_FORCES(2*CHUNK) = 0.0_wp

contains

   !> First part of a central-difference step over `n` nodes (seed eq. 4.3-4.4):
   !> du = dt v + dt^2/2 a, u = u + du, and a_old = a kept for the velocity update.
   subroutine cd_displacement(n, dt, v, a, u, du, a_old)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: v(2, n), a(2, n)
      real(wp), intent(inout) :: u(2, n)
      real(wp), intent(out) :: du(2, n), a_old(2, n)
      integer :: c, i0, m
      if (.not. threaded(n, PAR_MIN_NODES)) then
         call displacement_range(2*n, dt, v, a, u, du, a_old)
         return
      end if
      !$omp parallel do default(none) shared(n, dt, v, a, u, du, a_old) &
      !$omp private(c, i0, m) schedule(dynamic)
      do c = 1, (n + CHUNK - 1)/CHUNK
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         call displacement_range(2*m, dt, v(1, i0), a(1, i0), u(1, i0), du(1, i0), a_old(1, i0))
      end do
      !$omp end parallel do
   end subroutine cd_displacement

   !> cd_displacement on m values (m/2 nodes).
   pure subroutine displacement_range(m, dt, v, a, u, du, a_old)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, v(m), a(m)
      real(wp), intent(inout) :: u(m)
      real(wp), intent(out) :: du(m), a_old(m)
      real(wp) :: h, d
      integer :: j
      h = 0.5_wp*dt*dt
      do j = 1, m
         d = dt*v(j) + h*a(j)
         du(j) = d
         u(j) = u(j) + d
         a_old(j) = a(j)
      end do
   end subroutine displacement_range

   !> Predictor of eq. 4.3-4.4: a~ = M^-1 (F - P) and, when `with_vt`, v~ = v + dt/2 (a_old + a~)
   !> (only the contact search needs v~).
   subroutine cd_predictor(n, dt, minv, fext, fint, v, a_old, a, with_vt, vt)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: minv(2, n), fext(2, n), fint(2, n), v(2, n), a_old(2, n)
      real(wp), intent(out) :: a(2, n)
      logical, intent(in) :: with_vt
      real(wp), intent(inout) :: vt(2, n)
      integer :: c, i0, m
      if (.not. threaded(n, PAR_MIN_NODES)) then
         if (with_vt) then
            call predictor_range(2*n, dt, minv, fext, fint, v, a_old, a, vt)
         else
            call acceleration_range(2*n, minv, fext, fint, a)
         end if
         return
      end if
      !$omp parallel do default(none) &
      !$omp shared(n, dt, minv, fext, fint, v, a_old, a, with_vt, vt) private(c, i0, m) schedule(dynamic)
      do c = 1, (n + CHUNK - 1)/CHUNK
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         if (with_vt) then
            call predictor_range(2*m, dt, minv(1, i0), fext(1, i0), fint(1, i0), v(1, i0), a_old(1, i0), &
                                 a(1, i0), vt(1, i0))
         else
            call acceleration_range(2*m, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0))
         end if
      end do
      !$omp end parallel do
   end subroutine cd_predictor

   !> a = M^-1 (F - P) and v~ = v + dt/2 (a_old + a) on m values.
   pure subroutine predictor_range(m, dt, minv, fext, fint, v, a_old, a, vt)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, minv(m), fext(m), fint(m), v(m), a_old(m)
      real(wp), intent(out) :: a(m), vt(m)
      real(wp) :: h
      integer :: j
      h = 0.5_wp*dt
      do j = 1, m
         a(j) = minv(j)*(fext(j) - fint(j))
         vt(j) = v(j) + h*(a_old(j) + a(j))
      end do
   end subroutine predictor_range

   !> a = M^-1 (F - P) on m values.
   pure subroutine acceleration_range(m, minv, fext, fint, a)
      integer, intent(in) :: m
      real(wp), intent(in) :: minv(m), fext(m), fint(m)
      real(wp), intent(out) :: a(m)
      integer :: j
      do j = 1, m
         a(j) = minv(j)*(fext(j) - fint(j))
      end do
   end subroutine acceleration_range

   !> Last part of a step: v = v + dt/2 (a_old + a) with the corrected a, the work of the
   !> external forces (F . du) and, when `with_contact`, of the contact forces (doc/impact.md,
   !> eq. I.12): on a dof with mass (minv > 0) the work of the velocity update's two half kicks,
   !> so that an impulsive capture is booked as the kinetic energy it removes; on a dof without (rigid, prescribed, massless face) the
   !> trapezoid rule on the displacement, 1/2 (fcon_old + fcon) . du. Each sum runs per chunk
   !> of CHUNK nodes in array order and the chunks in order.
   subroutine cd_velocity(n, dt, a_old, a, fext, du, with_contact, fcon_old, fcon, minv, v, wext, wcon)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: a_old(2, n), a(2, n), fext(2, n), du(2, n)
      logical, intent(in) :: with_contact
      real(wp), intent(in) :: fcon_old(2, n), fcon(2, n), minv(2, n)
      real(wp), intent(inout) :: v(2, n), wext, wcon
      real(wp) :: pe((n + CHUNK - 1)/CHUNK), pc((n + CHUNK - 1)/CHUNK)
      integer :: c
      if (threaded(n, PAR_MIN_NODES)) then
         !$omp parallel do default(none) shared(n) private(c) schedule(dynamic)
         do c = 1, (n + CHUNK - 1)/CHUNK
            call velocity_chunk(c)
         end do
         !$omp end parallel do
      else
         do c = 1, (n + CHUNK - 1)/CHUNK
            call velocity_chunk(c)
         end do
      end if
      wext = wext + ordered_sum(size(pe), pe)
      if (with_contact) wcon = wcon + 0.5_wp*ordered_sum(size(pc), pc)
   contains
      !> The nodes of chunk c.
      subroutine velocity_chunk(c)
         integer, intent(in) :: c
         integer :: i0, m
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         pc(c) = 0.0_wp
         if (with_contact) call work_range(2*m, dt, fcon_old(1, i0), fcon(1, i0), du(1, i0), minv(1, i0), &
                                           v(1, i0), a_old(1, i0), a(1, i0), pc(c))
         call velocity_range(2*m, dt, a_old(1, i0), a(1, i0), fext(1, i0), du(1, i0), v(1, i0), pe(c))
      end subroutine velocity_chunk
   end subroutine cd_velocity

   !> v = v + dt/2 (a_old + a) and se = sum F . du on m values.
   pure subroutine velocity_range(m, dt, a_old, a, fext, du, v, se)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, a_old(m), a(m), fext(m), du(m)
      real(wp), intent(inout) :: v(m)
      real(wp), intent(out) :: se
      real(wp) :: h, p(2*CHUNK)
      integer :: j
      h = 0.5_wp*dt
      do j = 1, m
         v(j) = v(j) + h*(a_old(j) + a(j))
         p(j) = fext(j)*du(j)
      end do
      se = lane_sum(m, p)
   end subroutine velocity_range

   !> sc = twice the work of the contact forces on m values (cd_velocity): where minv > 0 the
   !> two half kicks, dt/2 (fcon_old . (v + vh) + fcon . (vh + v_new)) with vh = v + dt/2 a_old and
   !> v_new = vh + dt/2 a; elsewhere (fcon_old + fcon) . du. Both forms are made for every
   !> value in one loop and kept by a second (merge): with a branch per value, or both forms in
   !> one loop, gcc keeps the loop scalar under -ftrapping-math (14 instructions a value); the
   !> kept form's operations are the branch's, so the same bits.
   pure subroutine work_range(m, dt, fcon_old, fcon, du, minv, v, a_old, a, sc)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, fcon_old(m), fcon(m), du(m), minv(m), v(m), a_old(m), a(m)
      real(wp), intent(out) :: sc
      real(wp) :: p(2*CHUNK), pf(2*CHUNK), h, vh
      integer :: j
      h = 0.5_wp*dt
      do j = 1, m
         vh = v(j) + h*a_old(j)
         p(j) = h*(fcon_old(j)*(v(j) + vh) + fcon(j)*(2.0_wp*vh + h*a(j)))
         pf(j) = (fcon_old(j) + fcon(j))*du(j)
      end do
      do j = 1, m
         p(j) = merge(p(j), pf(j), minv(j) > 0.0_wp)
      end do
      sc = lane_sum(m, p)
   end subroutine work_range

   !> Step 1 of a step without contact, loads or masses per dof: u = u + (dt v + dt^2/2 a), the
   !> displacement increment of cd_displacement (the same operations) without storing it or a:
   !> cd_update_plain forms both again from v(n) and a(n), which it reads anyway.
   subroutine cd_displacement_plain(n, dt, v, a, u)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: v(2, n), a(2, n)
      real(wp), intent(inout) :: u(2, n)
      integer :: c, i0, m
      if (.not. threaded(n, PAR_MIN_NODES)) then
         call displacement_plain_range(2*n, dt, v, a, u)
         return
      end if
      !$omp parallel do default(none) shared(n, dt, v, a, u) &
      !$omp private(c, i0, m) schedule(dynamic)
      do c = 1, (n + CHUNK - 1)/CHUNK
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         call displacement_plain_range(2*m, dt, v(1, i0), a(1, i0), u(1, i0))
      end do
      !$omp end parallel do
   end subroutine cd_displacement_plain

   !> cd_displacement_plain on m values.
   pure subroutine displacement_plain_range(m, dt, v, a, u)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, v(m), a(m)
      real(wp), intent(inout) :: u(m)
      real(wp) :: h
      integer :: j
      h = 0.5_wp*dt*dt
      do j = 1, m
         u(j) = u(j) + (dt*v(j) + h*a(j))
      end do
   end subroutine displacement_plain_range

   !> Steps 4, 6 and 7 of a step without contact, loads or masses per dof (after
   !> cd_displacement_plain, with its dt), in one sweep over the nodes: a(n+1) = M^-1 (F - P)
   !> (cd_predictor), v = v + dt/2 (a(n) + a(n+1)) and the work F . du of the external forces
   !> with du = dt v(n) + dt^2/2 a(n) (cd_displacement, cd_velocity), kinetic energy and momentum
   !> (cd_kinetic). a holds a(n) on entry, a(n+1) on return. The same operations in the same
   !> order as those passes, and the sums per chunk and the chunks in order as there: the same
   !> bits, with 3 of the 10 nodal arrays those passes stream (du, a_old and a's second reading)
   !> neither stored nor read. With `power` present, also Q of cd_kinetic_power at the new state
   !> (a(n+1), fint(n+1)), chunk by chunk while the chunk's arrays are in the cache: the same
   !> power_range per chunk and the same ordered_sum, so the same bits as cd_kinetic_power's pass.
   !> With `fext_zero` (fext is +0 at every dof, state_t%fext_zero) fext is not read: the
   !> kernels take ZERO_FORCES, a chunk of +0 that stays in the cache, in its place (the same
   !> values in the same operations, so the same bits: 0 - fint, 0 (dt v + dt^2/2 a) are formed
   !> as before), 16 bytes per node less from memory.
   subroutine cd_update_plain(n, dt, minv, fext, fext_zero, fint, mass, a, v, wext, kinetic, momentum, &
                              power)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in), dimension(2, n) :: minv, fext, fint
      logical, intent(in) :: fext_zero
      real(wp), intent(in) :: mass(n)
      real(wp), intent(inout) :: a(2, n), v(2, n), wext
      real(wp), intent(out) :: kinetic, momentum(2)
      real(wp), intent(out), optional :: power
      real(wp), dimension((n + CHUNK - 1)/CHUNK) :: pe, pk, px, py, pr
      integer :: c
      logical :: with_power
      with_power = present(power)
      if (threaded(n, PAR_MIN_NODES)) then
         !$omp parallel do default(none) shared(n) private(c) schedule(dynamic)
         do c = 1, (n + CHUNK - 1)/CHUNK
            call update_chunk(c)
         end do
         !$omp end parallel do
      else
         do c = 1, (n + CHUNK - 1)/CHUNK
            call update_chunk(c)
         end do
      end if
      wext = wext + ordered_sum(size(pe), pe)
      call kinetic_total((n + CHUNK - 1)/CHUNK, pk, px, py, kinetic, momentum)
      if (with_power) power = ordered_sum(size(pr), pr)
   contains
      !> The nodes of chunk c.
      subroutine update_chunk(c)
         integer, intent(in) :: c
         integer :: i0, m
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         if (fext_zero) then
            call update_plain_range(2*m, dt, minv(1, i0), ZERO_FORCES, fint(1, i0), a(1, i0), v(1, i0), pe(c))
         else
            call update_plain_range(2*m, dt, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0), v(1, i0), pe(c))
         end if
         call kinetic_range(m, mass(i0), v(1, i0), pk(c), px(c), py(c))
         if (with_power) then
            if (fext_zero) then
               call power_range(m, minv(1, i0), ZERO_FORCES, fint(1, i0), a(1, i0), pr(c))
            else
               call power_range(m, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0), pr(c))
            end if
         end if
      end subroutine update_chunk
   end subroutine cd_update_plain

   !> u = u + (dt v + dt^2/2 a) at the nodes `list` only: cd_displacement_plain's operations
   !> on those values (the nodes of a rank's elements that another rank owns, doc/parallel.md).
   pure subroutine cd_displacement_plain_at(nnode, dt, v, a, list, u)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: dt, v(2, nnode), a(2, nnode)
      integer, intent(in) :: list(:)
      real(wp), intent(inout) :: u(2, nnode)
      real(wp) :: h
      integer :: k, i
      h = 0.5_wp*dt*dt
      do k = 1, size(list)
         i = list(k)
         u(1, i) = u(1, i) + (dt*v(1, i) + h*a(1, i))
         u(2, i) = u(2, i) + (dt*v(2, i) + h*a(2, i))
      end do
   end subroutine cd_displacement_plain_at

   !> cd_update_plain on the chunks c1 .. c2 of the n nodes only (the chunks a rank owns,
   !> doc/parallel.md): the same chunk kernels, each chunk's sums left in p(:, c - c1 + 1) =
   !> (F . du, m |v|^2, m vx, m vy, Q) unfolded, Q always formed. cd_plain_fold folds the sums
   !> of every chunk in chunk order as cd_update_plain does.
   subroutine cd_update_plain_chunks(n, c1, c2, dt, minv, fext, fext_zero, fint, mass, a, v, p)
      integer, intent(in) :: n, c1, c2
      real(wp), intent(in) :: dt
      real(wp), intent(in), dimension(2, n) :: minv, fext, fint
      logical, intent(in) :: fext_zero
      real(wp), intent(in) :: mass(n)
      real(wp), intent(inout) :: a(2, n), v(2, n)
      real(wp), intent(out) :: p(5, c1:c2)
      integer :: c
      if (threaded((c2 - c1 + 1)*CHUNK, PAR_MIN_NODES)) then
         !$omp parallel do default(none) shared(c1, c2) private(c) schedule(dynamic)
         do c = c1, c2
            call part_chunk(c)
         end do
         !$omp end parallel do
      else
         do c = c1, c2
            call part_chunk(c)
         end do
      end if
   contains
      !> The nodes of chunk c (cd_update_plain's update_chunk with the power).
      subroutine part_chunk(c)
         integer, intent(in) :: c
         integer :: i0, m
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         if (fext_zero) then
            call update_plain_range(2*m, dt, minv(1, i0), ZERO_FORCES, fint(1, i0), a(1, i0), v(1, i0), p(1, c))
         else
            call update_plain_range(2*m, dt, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0), v(1, i0), p(1, c))
         end if
         call kinetic_range(m, mass(i0), v(1, i0), p(2, c), p(3, c), p(4, c))
         if (fext_zero) then
            call power_range(m, minv(1, i0), ZERO_FORCES, fint(1, i0), a(1, i0), p(5, c))
         else
            call power_range(m, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0), p(5, c))
         end if
      end subroutine part_chunk
   end subroutine cd_update_plain_chunks

   !> The sums of cd_update_plain from the chunks' sums p(5, nc) of cd_update_plain_chunks
   !> (every chunk, in order): wext += F . du, kinetic energy, momentum and Q, the same
   !> ordered_sum and kinetic_total, hence the same bits.
   pure subroutine cd_plain_fold(nc, p, wext, kinetic, momentum, power)
      integer, intent(in) :: nc
      real(wp), intent(in) :: p(5, nc)
      real(wp), intent(inout) :: wext
      real(wp), intent(out) :: kinetic, momentum(2), power
      real(wp) :: pe(nc), pk(nc), px(nc), py(nc), pr(nc)
      pe = p(1, :)
      pk = p(2, :)
      px = p(3, :)
      py = p(4, :)
      pr = p(5, :)
      wext = wext + ordered_sum(nc, pe)
      call kinetic_total(nc, pk, px, py, kinetic, momentum)
      power = ordered_sum(nc, pr)
   end subroutine cd_plain_fold

   !> cd_update_plain's velocity update on m values: displacement_range's du, acceleration_range's
   !> a and velocity_range's v and F . du, in one loop.
   pure subroutine update_plain_range(m, dt, minv, fext, fint, a, v, se)
      integer, intent(in) :: m
      real(wp), intent(in) :: dt, minv(m), fext(m), fint(m)
      real(wp), intent(inout) :: a(m), v(m)
      real(wp), intent(out) :: se
      real(wp) :: h, h2, an, p(2*CHUNK)
      integer :: j
      h = 0.5_wp*dt
      h2 = 0.5_wp*dt*dt
      do j = 1, m
         an = minv(j)*(fext(j) - fint(j))
         p(j) = fext(j)*(dt*v(j) + h2*a(j))
         v(j) = v(j) + h*(a(j) + an)
         a(j) = an
      end do
      se = lane_sum(m, p)
   end subroutine update_plain_range

   !> Kinetic energy 1/2 sum m |v|^2 and linear momentum sum m v of n nodes, summed per chunk
   !> of CHUNK nodes and the chunks in order.
   subroutine cd_kinetic(n, mass, v, kinetic, momentum, mass_dof)
      integer, intent(in) :: n
      real(wp), intent(in) :: mass(n), v(2, n)
      real(wp), intent(out) :: kinetic, momentum(2)
      real(wp), intent(in), optional :: mass_dof(2, n)
      real(wp), dimension((n + CHUNK - 1)/CHUNK) :: pk, px, py
      integer :: c
      if (threaded(n, PAR_MIN_NODES) .and. .not. present(mass_dof)) then
         !$omp parallel do default(none) shared(n) private(c) schedule(dynamic)
         do c = 1, (n + CHUNK - 1)/CHUNK
            call kinetic_chunk(c)
         end do
         !$omp end parallel do
      else
         do c = 1, (n + CHUNK - 1)/CHUNK
            call kinetic_chunk(c)
         end do
      end if
      call kinetic_total((n + CHUNK - 1)/CHUNK, pk, px, py, kinetic, momentum)
   contains
      !> The nodes of chunk c.
      subroutine kinetic_chunk(c)
         integer, intent(in) :: c
         integer :: i0, m
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         if (present(mass_dof)) then
            ! masses per dof (massless contact faces along their normals, doc/impact.md, 3.1)
            call kinetic_range_dof(m, mass_dof(1, i0), v(1, i0), pk(c), px(c), py(c))
         else
            call kinetic_range(m, mass(i0), v(1, i0), pk(c), px(c), py(c))
         end if
      end subroutine kinetic_chunk
   end subroutine cd_kinetic

   !> Kinetic energy and momentum from the sums of nc chunks (kinetic_range), added in chunk order.
   pure subroutine kinetic_total(nc, pk, px, py, kinetic, momentum)
      integer, intent(in) :: nc
      real(wp), intent(in), dimension(nc) :: pk, px, py
      real(wp), intent(out) :: kinetic, momentum(2)
      kinetic = 0.5_wp*ordered_sum(nc, pk)
      momentum = [ordered_sum(nc, px), ordered_sum(nc, py)]
   end subroutine kinetic_total

   !> sum m |v|^2 and sum m v over m nodes (lane_sum).
   pure subroutine kinetic_range(m, mass, v, k, p1, p2)
      integer, intent(in) :: m
      real(wp), intent(in) :: mass(m), v(2, m)
      real(wp), intent(out) :: k, p1, p2
      real(wp), dimension(CHUNK) :: pk, px, py
      integer :: i
      do i = 1, m
         pk(i) = mass(i)*(v(1, i)**2 + v(2, i)**2)
         px(i) = mass(i)*v(1, i)
         py(i) = mass(i)*v(2, i)
      end do
      k = lane_sum(m, pk)
      p1 = lane_sum(m, px)
      p2 = lane_sum(m, py)
   end subroutine kinetic_range

   !> kinetic_range with a mass per dof, mass(2, m).
   pure subroutine kinetic_range_dof(m, mass, v, k, p1, p2)
      integer, intent(in) :: m
      real(wp), intent(in) :: mass(2, m), v(2, m)
      real(wp), intent(out) :: k, p1, p2
      real(wp), dimension(CHUNK) :: pk, px, py
      integer :: i
      do i = 1, m
         pk(i) = mass(1, i)*v(1, i)**2 + mass(2, i)*v(2, i)**2
         px(i) = mass(1, i)*v(1, i)
         py(i) = mass(2, i)*v(2, i)
      end do
      k = lane_sum(m, pk)
      p1 = lane_sum(m, px)
      p2 = lane_sum(m, py)
   end subroutine kinetic_range_dof

   !> Q = sum_j r_j a_j over the dofs of n nodes, the rate of the correction of the kinetic
   !> energy (doc/decisions.md, "Energy balance", eq. E.3: c = -dt^2/8 Q), with r = F - P where the
   !> dof has mass and is free (minv > 0; the contact force is booked by half kicks, work_range)
   !> and r = 0 elsewhere (a prescribed dof's inertia is booked as the exact change of its kinetic
   !> energy, doc/loads.md eq. P.3; fixed and rigid dofs have a = 0). `mass_dof` present: masses
   !> per dof (the sum node by node, as before). Summed per chunk of CHUNK nodes and the chunks
   !> in order (the same bits for every number of threads).
   function cd_kinetic_power(n, minv, fext, fint, a, mass_dof) result(q)
      integer, intent(in) :: n
      real(wp), intent(in), dimension(2, n) :: minv, fext, fint, a
      real(wp), intent(in), optional :: mass_dof(2, n)
      real(wp) :: q, pr((n + CHUNK - 1)/CHUNK)
      integer :: k
      if (present(mass_dof)) then
         ! masses per dof: r = 0 on a massless dof, whatever the node's other dof holds
         q = 0.0_wp
         do k = 1, n
            q = q + sum(merge(fext(:, k) - fint(:, k), 0.0_wp, minv(:, k) > 0.0_wp)*a(:, k))
         end do
         return
      end if
      if (threaded(n, PAR_MIN_NODES)) then
         !$omp parallel do default(none) shared(n) private(k) schedule(dynamic)
         do k = 1, (n + CHUNK - 1)/CHUNK
            call power_chunk(k)
         end do
         !$omp end parallel do
      else
         do k = 1, (n + CHUNK - 1)/CHUNK
            call power_chunk(k)
         end do
      end if
      q = ordered_sum(size(pr), pr)
   contains
      !> The nodes of chunk c.
      subroutine power_chunk(c)
         integer, intent(in) :: c
         integer :: i0, m
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, n - i0 + 1)
         call power_range(m, minv(1, i0), fext(1, i0), fint(1, i0), a(1, i0), pr(c))
      end subroutine power_chunk
   end function cd_kinetic_power

   !> S = fcon . a over the free dofs with mass (minv > 0): the contact force's part of the
   !> energy guard's kinetic correction, -dt^2/8 S (doc/loads.md, section 3, eq. P.5). One serial
   !> pass in node order (the same bits for every number of threads).
   pure function cd_contact_power(n, minv, fcon, a) result(s)
      integer, intent(in) :: n
      real(wp), intent(in), dimension(2, n) :: minv, fcon, a
      real(wp) :: s
      integer :: k
      s = 0.0_wp
      do k = 1, n
         s = s + merge(fcon(1, k), 0.0_wp, minv(1, k) > 0.0_wp)*a(1, k) + &
             merge(fcon(2, k), 0.0_wp, minv(2, k) > 0.0_wp)*a(2, k)
      end do
   end function cd_contact_power

   !> Q of cd_kinetic_power over m nodes (lane_sum).
   pure subroutine power_range(m, minv, fext, fint, a, s)
      integer, intent(in) :: m
      real(wp), intent(in), dimension(2, m) :: minv, fext, fint, a
      real(wp), intent(out) :: s
      real(wp) :: p(CHUNK)
      integer :: i
      do i = 1, m
         p(i) = merge(fext(1, i) - fint(1, i), 0.0_wp, minv(1, i) > 0.0_wp)*a(1, i) + &
                merge(fext(2, i) - fint(2, i), 0.0_wp, minv(2, i) > 0.0_wp)*a(2, i)
      end do
      s = lane_sum(m, p)
   end subroutine power_range

   !> x = x0 + u over nnode nodes.
   subroutine positions(nnode, x0, u, x)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(out) :: x(2, nnode)
      integer :: c, i0, m
      if (.not. threaded(nnode, PAR_MIN_NODES)) then
         call add_range(2*nnode, x0, u, x)
         return
      end if
      !$omp parallel do default(none) shared(nnode, x0, u, x) &
      !$omp private(c, i0, m) schedule(dynamic)
      do c = 1, (nnode + CHUNK - 1)/CHUNK
         i0 = (c - 1)*CHUNK + 1
         m = min(CHUNK, nnode - i0 + 1)
         call add_range(2*m, x0(1, i0), u(1, i0), x(1, i0))
      end do
      !$omp end parallel do
   end subroutine positions

   !> x = x0 + u at the nodes `list` only (the positions the contact search reads), the same
   !> operation as `positions` there.
   pure subroutine positions_at(nnode, x0, u, list, x)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      integer, intent(in) :: list(:)
      real(wp), intent(inout) :: x(2, nnode)
      integer :: k, i
      do k = 1, size(list)
         i = list(k)
         x(1, i) = x0(1, i) + u(1, i)
         x(2, i) = x0(2, i) + u(2, i)
      end do
   end subroutine positions_at

   !> v~ = v + dt/2 (a_old + a) at the nodes `list` only, the same operation as cd_predictor's.
   pure subroutine predictor_velocity_at(nnode, dt, v, a_old, a, list, vt)
      integer, intent(in) :: nnode
      real(wp), intent(in) :: dt, v(2, nnode), a_old(2, nnode), a(2, nnode)
      integer, intent(in) :: list(:)
      real(wp), intent(inout) :: vt(2, nnode)
      real(wp) :: h
      integer :: k, i
      h = 0.5_wp*dt
      do k = 1, size(list)
         i = list(k)
         vt(1, i) = v(1, i) + h*(a_old(1, i) + a(1, i))
         vt(2, i) = v(2, i) + h*(a_old(2, i) + a(2, i))
      end do
   end subroutine predictor_velocity_at

   !> c = a + b on m values.
   pure subroutine add_range(m, a, b, c)
      integer, intent(in) :: m
      real(wp), intent(in) :: a(m), b(m)
      real(wp), intent(out) :: c(m)
      integer :: j
      do j = 1, m
         c(j) = a(j) + b(j)
      end do
   end subroutine add_range

   !> a = 0 for an array of n values (shared among the threads as the other loops).
   subroutine cd_zero(n, a)
      integer, intent(in) :: n
      real(wp), intent(out) :: a(n)
      integer :: c, i0, m
      if (.not. threaded(n, 2*PAR_MIN_NODES)) then
         a = 0.0_wp
         return
      end if
      !$omp parallel do default(none) shared(n, a) private(c, i0, m) &
      !$omp schedule(dynamic)
      do c = 1, (n + 2*CHUNK - 1)/(2*CHUNK)
         i0 = (c - 1)*2*CHUNK + 1
         m = min(2*CHUNK, n - i0 + 1)
         a(i0:i0 + m - 1) = 0.0_wp
      end do
      !$omp end parallel do
   end subroutine cd_zero

end module exic_explicit_central
