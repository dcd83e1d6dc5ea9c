!> The central-difference solver: set-up from a model, one explicit step, energies.
!>
!> One step follows the seed's eq. 4.3-4.4 with distinct dt(n) and dt(n+1):
!>   x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)
!>   M a~(n+1) = F - P(u(n+1))                                   (4.3)
!>   v~(n+1) = v(n) + dt(n)/2 (a(n) + a~(n+1))                    (4.4)
!>   contact corrector: a(n+1) = a~(n+1) - M^-1 G lambda          (4.5-4.7)
!>   v(n+1) = v(n) + dt(n)/2 (a(n) + a(n+1))
!> with dt(n+1) chosen from the geometry at t(n+1) before the corrector needs it.
module exic_explicit_solver
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_model, only: model_t
   use exic_material_material, only: MAT_SOLID, MAT_RIGID
   use exic_explicit_state, only: state_t, element_set_t
   use exic_element_quad4, only: q4_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, &
                                 q4_stable_dt, q4_stress
   implicit none
   private

   public :: solver_init, solver_forces, solver_stable_dt, solver_energies, element_stress, all_stresses
   public :: cd_displacement, cd_predictor, cd_velocity
   public :: STEP_OK, STEP_INVERTED

   integer, parameter :: STEP_OK = 0, STEP_INVERTED = 1

contains

   !> Build the state and element sets of `model`; the initial velocity is the mesh's v0.
   subroutine solver_init(model, st, sets, err)
      type(model_t), intent(in) :: model
      type(state_t), intent(out) :: st
      type(element_set_t), allocatable, intent(out) :: sets(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: nn, ne, im, nmat, k, e, ebad, nset, i
      integer, allocatable :: count(:)
      character(len=64) :: buf

      nn = model%mesh%nnode
      ne = model%mesh%nelem
      st%nnode = nn
      st%nelem = ne
      st%x0 = model%mesh%x
      allocate (st%u(2, nn), st%v(2, nn), st%a(2, nn), st%fint(2, nn), st%fcon(2, nn), &
                st%minv(2, nn), source=0.0_wp)
      allocate (st%mass(nn), source=0.0_wp)
      allocate (st%active(nn), st%rigid(nn), source=.false.)
      st%fext = model%mesh%force

      ! element sets, one per material in use
      nmat = size(model%materials)
      allocate (count(nmat), source=0)
      allocate (st%eset(ne), st%eloc(ne), source=0)
      do e = 1, ne
         count(model%mesh%mat(e)) = count(model%mesh%mat(e)) + 1
      end do
      nset = count_nonzero(count)
      allocate (sets(nset))
      k = 0
      do im = 1, nmat
         if (count(im) == 0) cycle
         k = k + 1
         associate (s => sets(k), m => model%materials(im))
            s%mat = im
            s%kind = m%kind
            s%nq = m%quadrature
            s%nel = count(im)
            s%lambda = m%lambda
            s%mu = m%mu
            s%rho = m%rho
            s%hourglass = m%hourglass
            allocate (s%elems(s%nel), s%conn(4, s%nel))
            s%elems = pack([(i, i=1, ne)], model%mesh%mat == im)
            s%conn = model%mesh%conn(:, s%elems)
            allocate (s%gdn(8, s%nq**2, s%nel), s%wdj(s%nq**2, s%nel), s%gamma(4, s%nel))
            call q4_reference(s%nq, s%nel, nn, s%conn, st%x0, s%gdn, s%wdj, s%gamma, ebad)
            if (ebad /= 0) then
               write (buf, '(a,i0)') 'element ', s%elems(ebad)
               call make_error(err, trim(buf)//' has a non-positive Jacobian in the reference mesh')
               return
            end if
            call q4_lumped_mass(s%nel, nn, s%conn, st%x0, s%rho, st%mass)
            st%active(reshape(s%conn, [4*s%nel])) = .true.
            st%eset(s%elems) = k
            st%eloc(s%elems) = [(i, i=1, s%nel)]
            if (s%kind == MAT_RIGID) st%rigid(reshape(s%conn, [4*s%nel])) = .true.
         end associate
      end do

      ! inverse mass per dof: zero on prescribed dofs, rigid and inactive nodes
      do i = 1, nn
         if (st%active(i) .and. .not. st%rigid(i) .and. st%mass(i) > 0.0_wp) then
            st%minv(:, i) = 1.0_wp/st%mass(i)
         end if
         where (model%mesh%bc(:, i) /= 0) st%minv(:, i) = 0.0_wp
      end do

      ! initial conditions: prescribed displacement values hold from t = 0
      where (model%mesh%bc /= 0) st%u = model%mesh%disp
      st%v = model%mesh%v0
      where (model%mesh%bc /= 0) st%v = 0.0_wp
      do i = 1, nn
         if (.not. st%active(i)) st%v(:, i) = 0.0_wp
      end do
   end subroutine solver_init

   !> Number of non-zero entries.
   pure integer function count_nonzero(a)
      integer, intent(in) :: a(:)
      count_nonzero = count(a /= 0)
   end function count_nonzero

   !> Internal forces, strain and hourglass energy at the current displacement (seed eq. 4.3 needs P(u)).
   !> `ebad` is the first (global) element with J <= 0, or 0.
   subroutine solver_forces(st, sets, ebad)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(out) :: ebad
      integer :: k, eb
      real(wp) :: w, whg, jm

      st%fint = 0.0_wp
      st%strain = 0.0_wp
      st%hourglass = 0.0_wp
      st%jmin = huge(1.0_wp)
      ebad = 0
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            if (s%nq == 2) then
               call q4_force_2x2(s%nel, st%nnode, s%conn, st%u, s%gdn, s%wdj, s%lambda, s%mu, st%fint, w, jm, eb)
               whg = 0.0_wp
            else
               call q4_force_1pt(s%nel, st%nnode, s%conn, st%u, s%gdn, s%wdj, s%gamma, s%lambda, s%mu, &
                                 s%hourglass, st%fint, w, whg, jm, eb)
            end if
            st%strain = st%strain + w
            st%hourglass = st%hourglass + whg
            st%jmin = min(st%jmin, jm)
            if (eb /= 0 .and. ebad == 0) ebad = s%elems(eb)
         end associate
      end do
   end subroutine solver_forces

   !> Smallest critical step over the deformable elements at the current geometry, and its element.
   !> `xwork` (2, nnode), when given, holds the current coordinates instead of a temporary.
   subroutine solver_stable_dt(st, sets, dtmin, emin, xwork)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin
      real(wp), intent(inout), optional, target :: xwork(:, :)
      real(wp), allocatable, target :: xtmp(:, :)
      real(wp), pointer, contiguous :: x(:, :)
      integer :: k, e, i
      real(wp) :: d

      if (present(xwork)) then
         x => xwork(:, 1:st%nnode)
      else
         allocate (xtmp(2, st%nnode))
         x => xtmp
      end if
      do i = 1, st%nnode
         x(1, i) = st%x0(1, i) + st%u(1, i)
         x(2, i) = st%x0(2, i) + st%u(2, i)
      end do
      dtmin = huge(1.0_wp)
      emin = 0
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            call q4_stable_dt(s%nq, s%nel, st%nnode, s%conn, x, s%wdj, s%lambda, s%mu, s%rho, d, e)
            if (d < dtmin) then
               dtmin = d
               emin = s%elems(e)
            end if
         end associate
      end do
   end subroutine solver_stable_dt

   !> First part of a central-difference step over `n` nodes (seed eq. 4.3-4.4):
   !> du = dt v + dt^2/2 a, u = u + du, and a_old = a kept for the velocity update.
   !> One pass instead of four whole-array statements (no temporaries).
   pure subroutine cd_displacement(n, dt, v, a, u, du, a_old)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: v(2, n), a(2, n)
      real(wp), intent(inout) :: u(2, n)
      real(wp), intent(out) :: du(2, n), a_old(2, n)
      real(wp) :: h, d
      integer :: i, k
      h = 0.5_wp*dt*dt
      do i = 1, n
         do k = 1, 2
            d = dt*v(k, i) + h*a(k, i)
            du(k, i) = d
            u(k, i) = u(k, i) + d
            a_old(k, i) = a(k, i)
         end do
      end do
   end subroutine cd_displacement

   !> Predictor of eq. 4.3-4.4: a~ = M^-1 (F - P) and, when `with_vt`, v~ = v + dt/2 (a_old + a~)
   !> (only the contact search needs v~).
   pure subroutine cd_predictor(n, dt, minv, fext, fint, v, a_old, a, with_vt, vt)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: minv(2, n), fext(2, n), fint(2, n), v(2, n), a_old(2, n)
      real(wp), intent(out) :: a(2, n)
      logical, intent(in) :: with_vt
      real(wp), intent(inout) :: vt(2, n)
      real(wp) :: h
      integer :: i, k
      h = 0.5_wp*dt
      if (with_vt) then
         do i = 1, n
            do k = 1, 2
               a(k, i) = minv(k, i)*(fext(k, i) - fint(k, i))
               vt(k, i) = v(k, i) + h*(a_old(k, i) + a(k, i))
            end do
         end do
      else
         do i = 1, n
            do k = 1, 2
               a(k, i) = minv(k, i)*(fext(k, i) - fint(k, i))
            end do
         end do
      end if
   end subroutine cd_predictor

   !> Last part of a step: v = v + dt/2 (a_old + a) with the corrected a, the work of the
   !> external forces (F . du) and, when `with_contact`, of the contact forces by the
   !> trapezoid rule (1/2 (fcon_old + fcon) . du), each summed in array order.
   pure subroutine cd_velocity(n, dt, a_old, a, fext, du, with_contact, fcon_old, fcon, v, wext, wcon)
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: a_old(2, n), a(2, n), fext(2, n), du(2, n)
      logical, intent(in) :: with_contact
      real(wp), intent(in) :: fcon_old(2, n), fcon(2, n)
      real(wp), intent(inout) :: v(2, n), wext, wcon
      real(wp) :: h, se, sc
      integer :: i, k
      h = 0.5_wp*dt
      se = 0.0_wp
      sc = 0.0_wp
      do i = 1, n
         do k = 1, 2
            v(k, i) = v(k, i) + h*(a_old(k, i) + a(k, i))
            se = se + fext(k, i)*du(k, i)
         end do
      end do
      wext = wext + se
      if (with_contact) then
         do i = 1, n
            do k = 1, 2
               sc = sc + (fcon_old(k, i) + fcon(k, i))*du(k, i)
            end do
         end do
         wcon = wcon + 0.5_wp*sc
      end if
   end subroutine cd_velocity

   !> Kinetic energy and linear momentum of every active node (rigid bodies included).
   subroutine solver_energies(st)
      type(state_t), intent(inout) :: st
      integer :: i
      real(wp) :: k, p(2)
      k = 0.0_wp
      p = 0.0_wp
      do i = 1, st%nnode
         k = k + st%mass(i)*(st%v(1, i)**2 + st%v(2, i)**2)
         p = p + st%mass(i)*st%v(:, i)
      end do
      st%kinetic = 0.5_wp*k
      st%momentum = p
   end subroutine solver_energies

   !> Stress components (sxx, syy, szz, sxy, pressure, von Mises, J) of global element `e`.
   subroutine element_stress(st, sets, e, sig)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: e
      real(wp), intent(out) :: sig(7)
      integer :: j
      real(wp) :: s1(7, 1)
      sig = 0.0_wp
      sig(7) = 1.0_wp
      j = st%eloc(e)
      associate (s => sets(st%eset(e)))
         if (s%kind /= MAT_SOLID) return
         call q4_stress(s%nq, 1, st%nnode, s%conn(:, j:j), st%u, s%gdn(:, :, j:j), s%lambda, s%mu, s1)
         sig = s1(:, 1)
      end associate
   end subroutine element_stress

   !> Stress components of every element, sig(7, nelem); rigid elements get zeros and J = 1.
   subroutine all_stresses(st, sets, sig)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), intent(out) :: sig(:, :)
      integer :: k
      real(wp), allocatable :: s1(:, :)
      sig = 0.0_wp
      sig(7, :) = 1.0_wp
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            allocate (s1(7, s%nel))
            call q4_stress(s%nq, s%nel, st%nnode, s%conn, st%u, s%gdn, s%lambda, s%mu, s1)
            sig(:, s%elems) = s1
            deallocate (s1)
         end associate
      end do
   end subroutine all_stresses

end module exic_explicit_solver
