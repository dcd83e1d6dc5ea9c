!> The element sets of a mesh and what the step needs of them: internal forces and strain
!> energy (seed eq. 4.3 needs P(u)), the stable step, kinetic energy and momentum, stresses.
!>
!> `assembly_init` builds the state (reference coordinates, lumped masses, inverse masses per
!> dof, initial conditions) and one element set per material in use; the loops below call the
!> element kernels of src/exic/element set by set.
module exic_explicit_assembly
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t, MAT_SOLID, MAT_RIGID
   use exic_explicit_state, only: state_t, element_set_t
   use exic_element_quad4, only: q4_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, &
                                 q4_stable_dt, q4_stress
   implicit none
   private

   public :: assembly_init, internal_forces, stable_step, kinetic_energy, element_stress, all_stresses

contains

   !> Build the state and element sets of `mesh` with `materials` (indexed by material set
   !> number); the initial velocity is the mesh's v0.
   subroutine assembly_init(mesh, materials, st, sets, err)
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      type(state_t), intent(out) :: st
      type(element_set_t), allocatable, intent(out) :: sets(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: nn, ne, im, nmat, k, e, ebad, nset, i
      integer, allocatable :: count(:)
      character(len=64) :: buf

      nn = mesh%nnode
      ne = mesh%nelem
      st%nnode = nn
      st%nelem = ne
      st%x0 = mesh%x
      allocate (st%u(2, nn), st%v(2, nn), st%a(2, nn), st%fint(2, nn), st%fcon(2, nn), &
                st%minv(2, nn), source=0.0_wp)
      allocate (st%mass(nn), source=0.0_wp)
      allocate (st%active(nn), st%rigid(nn), source=.false.)
      st%fext = mesh%force

      ! element sets, one per material in use
      nmat = size(materials)
      allocate (count(nmat), source=0)
      allocate (st%eset(ne), st%eloc(ne), source=0)
      do e = 1, ne
         count(mesh%mat(e)) = count(mesh%mat(e)) + 1
      end do
      nset = count_nonzero(count)
      allocate (sets(nset))
      k = 0
      do im = 1, nmat
         if (count(im) == 0) cycle
         k = k + 1
         associate (s => sets(k), m => materials(im))
            s%mat = im
            s%kind = m%kind
            s%nq = m%quadrature
            s%nel = count(im)
            s%lambda = m%lambda
            s%mu = m%mu
            s%rho = m%rho
            s%hourglass = m%hourglass
            allocate (s%elems(s%nel), s%conn(4, s%nel))
            s%elems = pack([(i, i=1, ne)], mesh%mat == im)
            s%conn = mesh%conn(:, s%elems)
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
         where (mesh%bc(:, i) /= 0) st%minv(:, i) = 0.0_wp
      end do

      ! initial conditions: prescribed displacement values hold from t = 0
      where (mesh%bc /= 0) st%u = mesh%disp
      st%v = mesh%v0
      where (mesh%bc /= 0) st%v = 0.0_wp
      do i = 1, nn
         if (.not. st%active(i)) st%v(:, i) = 0.0_wp
      end do
   end subroutine assembly_init

   !> Number of non-zero entries.
   pure integer function count_nonzero(a)
      integer, intent(in) :: a(:)
      count_nonzero = count(a /= 0)
   end function count_nonzero

   !> Internal forces, strain and hourglass energy at the current displacement (seed eq. 4.3 needs P(u)).
   !> `ebad` is the first (global) element with J <= 0, or 0.
   subroutine internal_forces(st, sets, ebad)
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
   end subroutine internal_forces

   !> Smallest critical step over the deformable elements at the current coordinates
   !> x(2, nnode), and its (global) element (0 when there is no deformable element); efold: the
   !> first (global) element folded at a corner (q4_stable_dt), 0 if none.
   subroutine stable_step(st, sets, x, dtmin, emin, efold)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), intent(in) :: x(2, st%nnode)
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      integer :: k, e, ef
      real(wp) :: d

      dtmin = huge(1.0_wp)
      emin = 0
      efold = 0
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            call q4_stable_dt(s%nq, s%nel, st%nnode, s%conn, x, s%wdj, s%lambda, s%mu, s%rho, d, e, ef)
            if (ef /= 0 .and. efold == 0) efold = s%elems(ef)
            if (d < dtmin) then
               dtmin = d
               emin = s%elems(e)
            end if
         end associate
      end do
   end subroutine stable_step

   !> Kinetic energy and linear momentum of every active node (rigid bodies included).
   subroutine kinetic_energy(st)
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
   end subroutine kinetic_energy

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

end module exic_explicit_assembly
