!> The element sets of a mesh and what the step needs of them: internal forces and strain
!> energy (seed eq. 4.3 needs P(u)), the stable step, kinetic energy and momentum, stresses.
!>
!> `assembly_init` builds the state (reference coordinates, lumped masses, inverse masses per
!> dof, initial conditions) and one element set per material in use; the loops below call the
!> element kernels of src/exic/element set by set.
!>
!> Threads (OpenMP, `OMP_NUM_THREADS`): the force pass runs the ranges of each colour of a set
!> concurrently (element_set_t); every reduction (strain and hourglass energy, jmin, the stable
!> step and its element, the first inverted and folded elements, the kinetic energy and
!> momentum) is formed per range or per fixed chunk of nodes and the partial results are
!> combined serially in index order, so that every result is the same to the bit for every
!> number of threads. Without OpenMP the same code runs serially.
module exic_explicit_assembly
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: int64
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: rtoa
   use exic_base_threads, only: threaded
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t, MAT_SOLID, MAT_RIGID, material_law
   use exic_material_law, only: law_has_history
   use exic_explicit_state, only: state_t, element_set_t, plus_zero
   use exic_explicit_central, only: cd_kinetic, cd_kinetic_power, cd_zero, cd_contact_power
   use exic_explicit_dissipation, only: mass_damping, half_work, damped_step
   use exic_element_q4_bulk_viscosity, only: q4_bulk_viscosity
   use exic_element_quad4, only: q4_check_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, &
                                 q4_stable_dt, q4_stress, NBLOCK
   use exic_element_q4_general, only: q4g_init, q4g_force, q4g_stable_dt, q4g_stress, q4g_hist_init, &
                                      NSIG
   implicit none
   private

   public :: assembly_init, internal_forces, stable_step, kinetic_energy, kinetic_correction, element_stress, &
             energy_balance, contact_correction, book_contact_change, &
             book_step_change, all_stresses, forces_open, set_damping, forces_close
   public :: set_ranges, NSIG

   !> Smallest set whose force pass runs on several threads (a parallel region costs a few
   !> microseconds; below this, or with one thread allowed, the pass runs on the calling thread
   !> without entering OpenMP (exic_base_threads), with the same results).
   integer, parameter, public :: PAR_MIN_ELEMENTS = 2048
   !> Range length: nel/64 rounded up to whole blocks, between 256 and 2048 elements (fixed by
   !> the mesh, never by the number of threads).
   integer, parameter :: RANGE_MIN = 256, RANGE_MAX = 2048, RANGES_WANTED = 64

   !> What a force pass returns besides the forces (internal_forces, set_forces).
   type, public :: force_result_t
      real(wp) :: strain = 0.0_wp        !< strain energy (without the hourglass part)
      real(wp) :: hourglass = 0.0_wp     !< hourglass energy
      real(wp) :: dissipation = 0.0_wp   !< plastic work of this pass
      real(wp) :: jmin = huge(1.0_wp)    !< smallest J
      integer :: ebad = 0                !< first element with J <= 0, or 0
      real(wp) :: dt = huge(1.0_wp)      !< the stable step (its square inside a set's pass)
      integer :: emin = 0                !< its element, 0 without deformable elements
      integer :: efold = 0               !< first element folded at a corner, or 0
   end type force_result_t

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
      st%fext_zero = plus_zero(st%fext)
      st%axisymmetric = mesh%axisymmetric

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
            s%law = material_law(m)
            s%rho = m%rho
            s%hourglass = m%hourglass
            s%hgkind = m%hourglass_kind
            allocate (s%elems(s%nel), s%conn(4, s%nel))
            s%elems = pack([(i, i=1, ne)], mesh%mat == im)
            s%conn = mesh%conn(:, s%elems)
            call q4_check_reference(s%nel, nn, s%conn, st%x0, ebad)
            if (ebad /= 0) then
               write (buf, '(a,i0)') 'element ', s%elems(ebad)
               call make_error(err, trim(buf)//' has a non-positive Jacobian in the reference mesh')
               return
            end if
            call q4_lumped_mass(s%nel, nn, s%conn, st%x0, s%rho, st%mass, mesh%axisymmetric)
            if (.not. (all(ieee_is_finite(st%mass(reshape(s%conn, [4*s%nel])))) .and. &
                       ieee_is_finite(sum(st%mass)))) then
               write (buf, '(a,i0,a)') 'MATErial ', im, ': DENSity '
               call make_error(err, trim(buf)//' '//rtoa(m%rho)//' gives lumped masses that are not finite '// &
                               '(density x element area overflows)', m%where)
               return
            end if
            call general_path(s, m, mesh%axisymmetric)
            call dissipation_init(s, m, st, mesh%axisymmetric)
            if (m%plastic .and. m%kind == MAT_SOLID) st%has_plastic = .true.
            call set_ranges(s, nn)
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

   !> The general solid path of set s (doc/axisymmetry.md) when it is axisymmetric or MIXEd or
   !> its law has a history (with that history); else the plane-strain kernels of quad4.f90.
   subroutine general_path(s, m, axi)
      type(element_set_t), intent(inout) :: s
      type(material_t), intent(in) :: m
      logical, intent(in) :: axi
      s%general = m%kind == MAT_SOLID .and. (axi .or. law_has_history(s%law) .or. &
                                             (m%mixed .and. m%quadrature == 2))
      s%solid = q4g_init(m%quadrature, axi, m%mixed, s%law, m%hourglass, m%hourglass_kind)
      if (s%solid%nvar > 0) then
         allocate (s%hist(s%solid%nhist, s%nq*s%nq, s%nel))
         call q4g_hist_init(s%solid, s%nel, s%hist)
      else
         allocate (s%hist(1, 1, 1), source=0.0_wp)
      end if
   end subroutine general_path

   !> The dissipations of set s (doc/damping.md): DAMPing MASS (the set's nodes and their shares
   !> of the lumped mass) and VISCosity BULK (plane or axisymmetric); the state's nodal force
   !> arrays of the dissipations in use.
   subroutine dissipation_init(s, m, st, axi)
      type(element_set_t), intent(inout) :: s
      type(material_t), intent(in) :: m
      type(state_t), intent(inout) :: st
      logical, intent(in) :: axi
      real(wp), allocatable :: share(:)
      integer :: i
      if (m%kind /= MAT_SOLID) return
      if (m%damping > 0.0_wp) then
         s%damping = m%damping
         s%damping_end = m%damping_end
         allocate (share(st%nnode), source=0.0_wp)
         call q4_lumped_mass(s%nel, st%nnode, s%conn, st%x0, s%rho, share, axi)
         s%dnodes = pack([(i, i=1, st%nnode)], share > 0.0_wp)
         s%dmass = share(s%dnodes)
         if (.not. allocated(st%gdamp)) allocate (st%gdamp(2, st%nnode), source=0.0_wp)
      end if
      if (m%bulk) then
         s%bulk = .true.
         s%bulk_axi = axi
         s%q1 = m%bulk_q1
         s%q2 = m%bulk_q2
         s%wave = sqrt((m%lambda + 2.0_wp*m%mu)/m%rho)
         if (.not. allocated(st%gbulk)) allocate (st%gbulk(2, st%nnode), source=0.0_wp)
      end if
   end subroutine dissipation_init

   !> Number of non-zero entries.
   pure integer function count_nonzero(a)
      integer, intent(in) :: a(:)
      count_nonzero = count(a /= 0)
   end function count_nonzero

   !> Ranges and colours of set `s` (element_set_t): ranges of consecutive elements of a length
   !> fixed by the set's size; colours by a greedy pass over the ranges in order, each range
   !> taking the lowest colour that no earlier range sharing one of its nodes has. With a banded
   !> numbering (BLOCk meshes) that is two colours, alternating. Past 62 colours (a numbering
   !> without locality) every range is a colour of its own: serial, in order.
   subroutine set_ranges(s, nnode)
      type(element_set_t), intent(inout) :: s
      integer, intent(in) :: nnode
      integer(int64), allocatable :: mask(:)
      integer(int64) :: forb
      integer, allocatable :: colour(:)
      integer :: len, r, e, a, c, i

      len = (s%nel + RANGES_WANTED - 1)/RANGES_WANTED
      len = NBLOCK*((len + NBLOCK - 1)/NBLOCK)
      len = max(RANGE_MIN, min(RANGE_MAX, len))
      s%nrange = max(1, (s%nel + len - 1)/len)
      allocate (s%rfirst(s%nrange + 1), colour(s%nrange))
      s%rfirst = [(min(1 + (r - 1)*len, s%nel + 1), r=1, s%nrange + 1)]
      allocate (mask(nnode), source=0_int64)
      s%ncolour = 0
      do r = 1, s%nrange
         forb = 0_int64
         do e = s%rfirst(r), s%rfirst(r + 1) - 1
            do a = 1, 4
               forb = ior(forb, mask(s%conn(a, e)))
            end do
         end do
         c = trailz(not(forb))
         if (c >= 62) then
            s%ncolour = 0
            exit
         end if
         colour(r) = c + 1
         s%ncolour = max(s%ncolour, c + 1)
         do e = s%rfirst(r), s%rfirst(r + 1) - 1
            do a = 1, 4
               mask(s%conn(a, e)) = ibset(mask(s%conn(a, e)), c)
            end do
         end do
      end do
      if (s%ncolour == 0) then
         s%ncolour = s%nrange
         colour = [(r, r=1, s%nrange)]
      end if
      ! the ranges by colour, ascending within each colour
      allocate (s%cfirst(s%ncolour + 1), s%cranges(s%nrange))
      s%cfirst = 0
      do r = 1, s%nrange
         s%cfirst(colour(r) + 1) = s%cfirst(colour(r) + 1) + 1
      end do
      s%cfirst(1) = 1
      do c = 1, s%ncolour
         s%cfirst(c + 1) = s%cfirst(c) + s%cfirst(c + 1)
      end do
      i = 0
      do c = 1, s%ncolour
         do r = 1, s%nrange
            if (colour(r) /= c) cycle
            i = i + 1
            s%cranges(i) = r
         end do
      end do
   end subroutine set_ranges

   !> Internal forces, strain and hourglass energy at the current displacement (seed eq. 4.3
   !> needs P(u)), and from the same pass the stable step at x = x0 + u: res%dt, its (global)
   !> element res%emin (0 when there is no deformable element) and the first (global) element
   !> folded at a corner res%efold (q4_stable_dt); res%ebad: the first (global) element with
   !> J <= 0, or 0. The energies go into st%energy (strain, hourglass) and res.
   !> Plastic sets update their history (once per call: the stepper calls this once per step)
   !> and add the step's dissipation to st%energy%plastic.
   subroutine internal_forces(st, sets, res)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: sets(:)
      type(force_result_t), intent(out) :: res
      type(force_result_t) :: r
      real(wp) :: wd, wb
      integer :: k

      call forces_open(st, wd, wb)
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            if (s%bulk) then
               call set_forces(s, st%nnode, st%x0, st%u, st%v, st%dt_prev, st%fint, r, st%a, st%gbulk)
            else
               call set_forces(s, st%nnode, st%x0, st%u, st%v, st%dt_prev, st%fint, r)
            end if
            call set_damping(s, st, r%dt)
            st%energy%plastic = st%energy%plastic + r%dissipation
            call add_result(res, global(r, s%elems, 0))
         end associate
      end do
      st%energy%strain = res%strain
      st%energy%hourglass = res%hourglass
      st%jmin = res%jmin
      call forces_close(st, wd, wb)
   end subroutine internal_forces

   !> The start of a force pass (internal_forces, and decomposition_forces on several ranks):
   !> fint zeroed; wd and wb, the first half of the trapezoid work of the mass-damping and
   !> bulk-viscosity forces of the last pass (D.5), and those forces zeroed.
   subroutine forces_open(st, wd, wb)
      type(state_t), intent(inout) :: st
      real(wp), intent(out) :: wd, wb
      wd = 0.0_wp
      wb = 0.0_wp
      call cd_zero(2*st%nnode, st%fint)
      if (allocated(st%gdamp)) then
         wd = half_work(st%nnode, st%gdamp, st%v, st%a, st%dt_prev)
         call cd_zero(2*st%nnode, st%gdamp)
      end if
      if (allocated(st%gbulk)) then
         wb = half_work(st%nnode, st%gbulk, st%v, st%a, st%dt_prev)
         call cd_zero(2*st%nnode, st%gbulk)
      end if
   end subroutine forces_open

   !> The mass damping of set s while it acts (DAMPing MASS c [t_end]): its nodal forces added to
   !> st%gdamp (D.2) and the set's stable step dt lowered to the damped one (D.4).
   subroutine set_damping(s, st, dt)
      type(element_set_t), intent(in) :: s
      type(state_t), intent(inout) :: st
      real(wp), intent(inout) :: dt
      if (s%damping > 0.0_wp .and. st%t <= s%damping_end) then
         call mass_damping(size(s%dnodes), s%dnodes, s%dmass, s%damping, st%nnode, st%v, st%a, &
                           st%dt_prev, st%gdamp)
         dt = damped_step(dt, s%damping)
      end if
   end subroutine set_damping

   !> The end of a force pass: the bulk-viscosity and mass-damping forces added to fint and their
   !> work over the step booked (wd, wb from forces_open, and the second half, D.5).
   subroutine forces_close(st, wd, wb)
      type(state_t), intent(inout) :: st
      real(wp), intent(in) :: wd, wb
      if (allocated(st%gbulk)) then
         st%fint = st%fint + st%gbulk
         st%energy%bulk = st%energy%bulk + (wb + half_work(st%nnode, st%gbulk, st%v, st%a, st%dt_prev))
      end if
      if (allocated(st%gdamp)) then
         st%fint = st%fint + st%gdamp
         st%energy%damping = st%energy%damping + (wd + half_work(st%nnode, st%gdamp, st%v, st%a, st%dt_prev))
      end if
   end subroutine forces_close

   !> Fold the result r of a range or a set into the running result `res`, in order: the sums
   !> in the order of the calls, the first element that is inverted or folded, the smallest
   !> step and its element.
   pure subroutine add_result(res, r)
      type(force_result_t), intent(inout) :: res
      type(force_result_t), intent(in) :: r
      res%strain = res%strain + r%strain
      res%dissipation = res%dissipation + r%dissipation
      res%hourglass = res%hourglass + r%hourglass
      res%jmin = min(res%jmin, r%jmin)
      if (r%ebad /= 0 .and. res%ebad == 0) res%ebad = r%ebad
      if (r%efold /= 0 .and. res%efold == 0) res%efold = r%efold
      if (r%dt < res%dt) then
         res%dt = r%dt
         res%emin = r%emin
      end if
   end subroutine add_result

   !> r with its element numbers e (local: 1 is the first element of a range or set) turned
   !> into elems(e) (a set's global numbers), or offset + e when elems is empty.
   pure function global(r, elems, offset) result(g)
      type(force_result_t), intent(in) :: r
      integer, intent(in) :: elems(:), offset
      type(force_result_t) :: g
      g = r
      if (size(elems) > 0) then
         if (r%ebad /= 0) g%ebad = elems(r%ebad)
         if (r%efold /= 0) g%efold = elems(r%efold)
         if (r%emin /= 0) g%emin = elems(r%emin)
      else
         if (r%ebad /= 0) g%ebad = offset + r%ebad
         if (r%efold /= 0) g%efold = offset + r%efold
         if (r%emin /= 0) g%emin = offset + r%emin
      end if
   end function global

   !> The force pass over one set (internal_forces): the ranges of each colour on the threads,
   !> one colour after the other; per-range results combined in range order. res%dt is the
   !> square of the set's step; its elements are local element numbers of the set.
   !> With VISCosity BULK (s%bulk), a(n) and g: the bulk viscosity's nodal forces are added to
   !> g and the set's step is lowered by its ratio (q4_bulk_viscosity).
   subroutine set_forces(s, nnode, x0, u, v, dt, f, res, a, g)
      type(element_set_t), intent(inout) :: s
      integer, intent(in) :: nnode
      !> v: the nodal velocities (the corner barrier's kinematic step limit, doc/hourglass.md (H19))
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), v(2, nnode), dt
      real(wp), intent(inout) :: f(2, nnode)
      type(force_result_t), intent(out) :: res
      real(wp), intent(in), optional :: a(2, nnode)
      real(wp), intent(inout), optional :: g(2, nnode)
      real(wp), dimension(s%nrange) :: pw, phg, pj, pd, pdw, pq
      integer, dimension(s%nrange) :: pe, pm, pf
      integer :: c, i, r, e1

      pdw = 0.0_wp
      pq = 1.0_wp
      if (threaded(s%nel, PAR_MIN_ELEMENTS)) then
         !$omp parallel default(none) private(c, i) shared(s)
         do c = 1, s%ncolour
            !$omp do schedule(dynamic)
            do i = s%cfirst(c), s%cfirst(c + 1) - 1
               call range_forces(s%cranges(i))
            end do
            !$omp end do
         end do
         !$omp end parallel
      else
         do c = 1, s%ncolour
            do i = s%cfirst(c), s%cfirst(c + 1) - 1
               call range_forces(s%cranges(i))
            end do
         end do
      end if
      do r = 1, s%nrange
         e1 = s%rfirst(r) - 1
         call add_result(res, global(force_result_t(strain=pw(r), hourglass=phg(r), dissipation=pdw(r), &
                                                    jmin=pj(r), ebad=pe(r), dt=pd(r), emin=pm(r), efold=pf(r)), &
                                     [integer ::], e1))
      end do
      res%dt = sqrt(res%dt)
      if (present(g)) res%dt = res%dt*minval(pq)
   contains
      !> The forces of range r of the set.
      subroutine range_forces(r)
         integer, intent(in) :: r
         integer :: e1, n
         e1 = s%rfirst(r)
         n = s%rfirst(r + 1) - e1
         if (s%general) then
            if (s%solid%nvar > 0) then
               call q4g_force(s%solid, n, nnode, s%conn(:, e1:e1 + n - 1), x0, u, dt, &
                              s%hist(:, :, e1:e1 + n - 1), f, pw(r), phg(r), pdw(r), pj(r), pe(r), &
                              pd(r), pm(r), pf(r), v)
            else
               call q4g_force(s%solid, n, nnode, s%conn(:, e1:e1 + n - 1), x0, u, dt, s%hist, f, &
                              pw(r), phg(r), pdw(r), pj(r), pe(r), pd(r), pm(r), pf(r), v)
            end if
         else if (s%nq == 2) then
            call q4_force_2x2(n, nnode, s%conn(:, e1:e1 + n - 1), x0, u, s%law, f, &
                              pw(r), pj(r), pe(r), pd(r), pm(r), pf(r))
            phg(r) = 0.0_wp
         else
            call q4_force_1pt(n, nnode, s%conn(:, e1:e1 + n - 1), x0, u, s%law, &
                              s%hourglass, f, pw(r), phg(r), pj(r), pe(r), pd(r), pm(r), pf(r), &
                              s%hgkind, v)
         end if
         if (present(g)) call q4_bulk_viscosity(n, nnode, s%conn(:, e1:e1 + n - 1), x0, u, v, a, dt, s%rho, &
                                                s%wave, s%q1, s%q2, s%bulk_axi, g, pq(r))
      end subroutine range_forces
   end subroutine set_forces

   !> Smallest critical step over the deformable elements at the current coordinates
   !> x(2, nnode), and its (global) element (0 when there is no deformable element); efold: the
   !> first (global) element folded at a corner (q4_stable_dt), 0 if none. The same estimate
   !> as internal_forces computes (to the bit), for a mesh before its first force pass, but for
   !> the bulk viscosity's ratio, which needs the velocities (doc/damping.md, section 3).
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
            if (s%general) then
               call q4g_stable_dt(s%solid, s%nel, st%nnode, s%conn, st%x0, x, d, e, ef)
            else
               call q4_stable_dt(s%nq, s%nel, st%nnode, s%conn, st%x0, x, s%law, d, e, ef)
            end if
            if (s%damping > 0.0_wp .and. st%t <= s%damping_end) d = damped_step(d, s%damping)
            if (ef /= 0 .and. efold == 0) efold = s%elems(ef)
            if (d < dtmin) then
               dtmin = d
               emin = s%elems(e)
            end if
         end associate
      end do
   end subroutine stable_step

   !> Kinetic energy and linear momentum of every active node (rigid bodies included), summed
   !> per fixed chunk of nodes and the chunks in order (the same bits for every number of threads).
   subroutine kinetic_energy(st)
      type(state_t), intent(inout) :: st
      if (allocated(st%mass_dof)) then
         call cd_kinetic(st%nnode, st%mass, st%v, st%energy%kinetic, st%momentum, st%mass_dof)
      else
         call cd_kinetic(st%nnode, st%mass, st%v, st%energy%kinetic, st%momentum)
      end if
   end subroutine kinetic_energy

   !> The change since t = 0 of the correction that turns the kinetic energy of integer-time
   !> velocities into the one the central-difference step conserves (doc/decisions.md, "Energy
   !> balance", eq. E.3-E.4): -dt(n+1)^2/8 Q(n) + the sum booked at the changes of the step - its
   !> value at t = 0.
   real(wp) function kinetic_correction(st) result(c)
      type(state_t), intent(in) :: st
      c = -0.125_wp*st%dt*st%dt*kinetic_power(st) + st%dt_residual - st%correction0
   end function kinetic_correction

   !> The contact part of the energy guard's kinetic correction (doc/loads.md, section 3, eq.
   !> P.5): -dt(n+1)^2/8 S(n), S = fcon . a over the free dofs with mass, plus the sum booked at
   !> the changes of the step, less its value at t = 0 (both in st%contact_residual).
   real(wp) function contact_correction(st) result(c)
      type(state_t), intent(in) :: st
      c = -0.125_wp*st%dt*st%dt*cd_contact_power(st%nnode, st%minv, st%fcon, st%a) + st%contact_residual
   end function contact_correction

   !> Before book_step_change, when the step to come differs from the one booked: the contact
   !> part of eq. E.4, (dt_new^2 - dt_old^2)/8 S(n) (doc/loads.md, eq. P.5).
   subroutine book_contact_change(st)
      type(state_t), intent(inout) :: st
      if (st%dt == st%dt_booked) return
      st%contact_residual = st%contact_residual + &
                            0.125_wp*(st%dt*st%dt - st%dt_booked*st%dt_booked)*cd_contact_power(st%nnode, st%minv, st%fcon, st%a)
   end subroutine book_contact_change

   !> The energy balance of <stem>.ene (explicit/energy.f90, energy_total): the total with the
   !> change of the kinetic correction since t = 0 (doc/decisions.md, "Energy balance", eq. E.3),
   !> its drift from the initial total relative to the largest of |initial total| and the
   !> physical energy now; `correction`, that change of the kinetic correction, for its column.
   subroutine energy_balance(st, total, drift, correction)
      type(state_t), intent(in) :: st
      real(wp), intent(out) :: total, drift
      real(wp), intent(out), optional :: correction
      real(wp) :: c
      c = kinetic_correction(st)
      call st%energy%balance(c, total, drift)
      if (present(correction)) correction = c
   end subroutine energy_balance

   !> When the step to come differs from the one the correction was booked for: the sum of
   !> eq. E.4 takes (dt_new^2 - dt_old^2)/8 Q(n) (called at t(n) with the state of t(n)).
   !> qnodes: the nodes' part of Q when the caller has formed it from this state already
   !> (cd_update_plain's power), so that no pass over the nodes forms it again.
   subroutine book_step_change(st, qnodes)
      type(state_t), intent(inout) :: st
      real(wp), intent(in), optional :: qnodes
      real(wp) :: q
      if (st%dt == st%dt_booked) return
      if (present(qnodes)) then
         q = qnodes + st%body_power
      else
         q = kinetic_power(st)
      end if
      st%dt_residual = st%dt_residual + 0.125_wp*(st%dt*st%dt - st%dt_booked*st%dt_booked)*q
      st%dt_booked = st%dt
   end subroutine book_step_change

   !> Q of eq. E.3 over the nodes and the free bodies.
   real(wp) function kinetic_power(st) result(q)
      type(state_t), intent(in) :: st
      if (st%power_known) then
         q = st%power_nodes + st%body_power
      else if (allocated(st%mass_dof)) then
         q = cd_kinetic_power(st%nnode, st%minv, st%fext, st%fint, st%a, st%mass_dof) + st%body_power
      else
         q = cd_kinetic_power(st%nnode, st%minv, st%fext, st%fint, st%a) + st%body_power
      end if
   end function kinetic_power

   !> Stress components (sxx, syy, szz, sxy, pressure, von Mises, J; ep, temperature, yield
   !> stress: zero for an elastic set) of global element `e`.
   subroutine element_stress(st, sets, e, sig)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: e
      real(wp), intent(out) :: sig(NSIG)
      integer :: j
      real(wp) :: s1(7, 1), sg(NSIG, 1)
      sig = 0.0_wp
      sig(7) = 1.0_wp
      j = st%eloc(e)
      if (j == 0) return   ! an eroded element (doc/erosion.md)
      associate (s => sets(st%eset(e)))
         if (s%kind /= MAT_SOLID) return
         if (s%general) then
            if (s%solid%nvar > 0) then
               call q4g_stress(s%solid, 1, st%nnode, s%conn(:, j:j), st%x0, st%u, s%hist(:, :, j:j), sg)
            else
               call q4g_stress(s%solid, 1, st%nnode, s%conn(:, j:j), st%x0, st%u, s%hist, sg)
            end if
            sig = sg(:, 1)
         else
            call q4_stress(s%nq, 1, st%nnode, s%conn(:, j:j), st%x0, st%u, s%law, s1)
            sig(1:7) = s1(:, 1)
         end if
      end associate
   end subroutine element_stress

   !> Stress components of every element, sig(nc, nelem) with nc = 7 or NSIG (element_stress);
   !> rigid elements get zeros and J = 1.
   subroutine all_stresses(st, sets, sig)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), intent(out) :: sig(:, :)
      integer :: k, nc
      real(wp), allocatable :: s1(:, :)
      nc = size(sig, 1)
      sig = 0.0_wp
      sig(7, :) = 1.0_wp
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            if (s%general) then
               allocate (s1(NSIG, s%nel))
               call q4g_stress(s%solid, s%nel, st%nnode, s%conn, st%x0, st%u, s%hist, s1)
            else
               allocate (s1(7, s%nel))
               call q4_stress(s%nq, s%nel, st%nnode, s%conn, st%x0, st%u, s%law, s1)
            end if
            sig(1:min(nc, size(s1, 1)), s%elems) = s1(1:min(nc, size(s1, 1)), :)
            deallocate (s1)
         end associate
      end do
   end subroutine all_stresses

end module exic_explicit_assembly
