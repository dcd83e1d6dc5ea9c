!> Element erosion (doc/erosion.md), after LS-DYNA's *MAT_ADD_EROSION: under `EROSion INVErted`,
!> `EROSion STRAin e_max` and `EROSion TIMEstep dt_min` of a SOLId material, an element that would
!> invert, whose strain exceeds e_max or whose stable step falls below dt_min leaves the model.
!>
!> Masking is by compaction: an eroded element is taken out of its set's element list (nodes,
!> global numbers, history), and the set's ranges and colours are formed again, so that the force
!> kernels loop over live elements only and carry no per-element test. The status of every element
!> (st%status: 0 live, else the reason) is state: saved and loaded with a restart
!> (`erosion_restore` compacts the sets again).
!>
!> Within the step at t(n+1) (stepper_t, src/exic/explicit/step.f90):
!>  - before the force pass (`erosion_before`): INVErted, the element inverted or folded at
!>    x(n+1), or at the constant-acceleration prediction x(n+1) + dt(n) (v(n) + dt(n) a(n)) of
!>    x(n+2), doc/erosion.md (R1): it takes no part in the pass at t(n+1);
!>  - after it (`erosion_after`): STRAin and TIMEstep, from the pass's values at t(n+1); the
!>    element's forces at t(n+1) stay in that step, it takes no part from t(n+2) on, and the
!>    stable step is formed again without it (doc/erosion.md (R2)).
!> The strain (and hourglass) energy the element held at its last valid configuration and the
!> kinetic energy of the nodes that no live element holds any more are booked in st%energy%eroded
!> (doc/erosion.md (R3)-(R4)); such nodes leave the model (zero inverse mass and velocity).
module exic_explicit_erosion
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_messages, only: messages_t
   use exic_material_material, only: material_t, MAT_SOLID
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_assembly, only: set_ranges, stable_step
   use exic_element_quad4, only: q4_force_2x2, q4_force_1pt
   use exic_element_q4_general, only: q4g_force
   implicit none
   private

   public :: erosion_t, erosion_init, erosion_before, erosion_after, erosion_restore, erosion_live, element_strain
   public :: ERODED_INVERTED, ERODED_STRAIN, ERODED_TIMESTEP

   !> st%status values: why an element left the model (0: live).
   integer, parameter :: ERODED_INVERTED = 1, ERODED_STRAIN = 2, ERODED_TIMESTEP = 3
   character(len=*), parameter :: REASON(3) = [character(len=8) :: 'inverted', 'strain', 'timestep']
   !> a corner triangle within FLAT of the area is flat, not folded (quad4.f90, corner_estimate)
   real(wp), parameter :: FLAT = 1.0e-10_wp

   !> What the EROSion records of the materials ask, per element set.
   type :: erosion_t
      logical :: active = .false.              !< some set erodes
      logical, allocatable :: inverted(:)      !< (nset) EROSion INVErted
      real(wp), allocatable :: strain(:)       !< (nset) EROSion STRAin e_max (0: none)
      real(wp), allocatable :: dtmin(:)        !< (nset) EROSion TIMEstep dt_min (0: none)
      integer, allocatable :: nuse(:)          !< (nnode) live elements holding each node
      logical :: changed = .false.             !< an erosion since the contact surfaces were built
   end type erosion_t

contains

   !> The erosion of the sets from their materials; st%status allocated (all live) when one set
   !> erodes.
   subroutine erosion_init(ero, st, sets, materials)
      type(erosion_t), intent(out) :: ero
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(material_t), intent(in) :: materials(:)
      integer :: k, j
      allocate (ero%inverted(size(sets)), source=.false.)
      allocate (ero%strain(size(sets)), ero%dtmin(size(sets)), source=0.0_wp)
      do k = 1, size(sets)
         if (sets(k)%kind /= MAT_SOLID) cycle
         associate (m => materials(sets(k)%mat))
            ero%inverted(k) = m%erode_inverted
            ero%strain(k) = m%erode_strain
            ero%dtmin(k) = m%erode_dt
         end associate
      end do
      ero%active = any(ero%inverted) .or. any(ero%strain > 0.0_wp) .or. any(ero%dtmin > 0.0_wp)
      if (.not. ero%active) return
      allocate (st%status(st%nelem), source=0)
      allocate (ero%nuse(st%nnode), source=0)
      do k = 1, size(sets)
         do j = 1, sets(k)%nel
            ero%nuse(sets(k)%conn(:, j)) = ero%nuse(sets(k)%conn(:, j)) + 1
         end do
      end do
   end subroutine erosion_init

   !> True for an element that is live (always, without erosion).
   pure logical function erosion_live(st, e) result(live)
      type(state_t), intent(in) :: st
      integer, intent(in) :: e
      live = .true.
      if (allocated(st%status)) live = st%status(e) == 0
   end function erosion_live

   !> Before the force pass at t(n+1): the elements of INVErted sets inverted or folded at
   !> x(n+1) = x0 + u, or at the prediction of x(n+2) (doc/erosion.md (R1)), leave the model.
   !> v, a: v(n), a(n); st%dt_prev = dt(n).
   subroutine erosion_before(ero, st, sets, messages, a_old)
      type(erosion_t), intent(inout) :: ero
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: sets(:)
      type(messages_t), intent(inout) :: messages
      !> a(n) as the step keeps it (cd_displacement), when it keeps it: zero at nodes that leave
      real(wp), intent(inout), optional, allocatable :: a_old(:, :)
      integer :: k, j, a, n
      real(wp) :: xc(2, 4), xp(2, 4), h
      logical, allocatable :: gone(:)
      h = st%dt_prev
      do k = 1, size(sets)
         if (.not. ero%inverted(k)) cycle
         associate (s => sets(k))
            allocate (gone(s%nel), source=.false.)
            do j = 1, s%nel
               do a = 1, 4
                  n = s%conn(a, j)
                  xc(:, a) = st%x0(:, n) + st%u(:, n)
                  xp(:, a) = xc(:, a) + h*(st%v(:, n) + h*st%a(:, n))
               end do
               gone(j) = folded(xc) .or. folded(xp)
               ! its energy at x(n) and the work of its force f_e(n) over the half step the
               ! kinetic energy took it in (doc/erosion.md (R3a))
               if (gone(j)) call book_element(st, s, j, .true., ERODED_INVERTED, messages)
            end do
            if (any(gone)) call remove(ero, st, s, gone, a_old, .true.)
            deallocate (gone)
         end associate
      end do
   end subroutine erosion_before

   !> After the force pass at t(n+1): STRAin and TIMEstep (doc/erosion.md (R2)). The elements
   !> whose strain exceeds e_max leave; then, while the smallest stable step dtmin (its element
   !> emin) is below dt_min of that element's set, that element leaves and the step is formed
   !> again over the live elements (stable_step, on the positions x0 + u). Their strain and
   !> hourglass energy at t(n+1) move from st%energy%strain and st%energy%hourglass into st%energy%eroded.
   subroutine erosion_after(ero, st, sets, dtmin, emin, efold, messages)
      type(erosion_t), intent(inout) :: ero
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: sets(:)
      real(wp), intent(inout) :: dtmin
      integer, intent(inout) :: emin, efold
      type(messages_t), intent(inout) :: messages
      integer :: k, j
      logical :: again
      logical, allocatable :: gone(:)
      again = .false.
      do k = 1, size(sets)
         if (.not. ero%strain(k) > 0.0_wp) cycle
         associate (s => sets(k))
            allocate (gone(s%nel))
            do j = 1, s%nel
               gone(j) = element_strain(st, s, j) > ero%strain(k)
               if (gone(j)) call book_element(st, s, j, .false., ERODED_STRAIN, messages, .true.)
            end do
            if (any(gone)) then
               call remove(ero, st, s, gone)
               again = .true.
            end if
            deallocate (gone)
         end associate
      end do
      if (again) call restep(st, sets, dtmin, emin, efold)
      do
         if (emin == 0) exit
         k = st%eset(emin)
         if (.not. (ero%dtmin(k) > 0.0_wp .and. dtmin < ero%dtmin(k))) exit
         associate (s => sets(k))
            j = st%eloc(emin)
            allocate (gone(s%nel), source=.false.)
            gone(j) = .true.
            call book_element(st, s, j, .false., ERODED_TIMESTEP, messages, .true.)
            call remove(ero, st, s, gone)
            deallocate (gone)
         end associate
         call restep(st, sets, dtmin, emin, efold)
      end do
   end subroutine erosion_after

   !> The stable step of the live elements at x0 + u.
   subroutine restep(st, sets, dtmin, emin, efold)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      call stable_step(st, sets, st%x0 + st%u, dtmin, emin, efold)
   end subroutine restep

   !> After a restart has loaded st%status: the sets without the eroded elements, the use counts.
   subroutine erosion_restore(ero, st, sets)
      type(erosion_t), intent(inout) :: ero
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: sets(:)
      integer :: k, j
      logical, allocatable :: gone(:)
      if (.not. ero%active) return
      do k = 1, size(sets)
         associate (s => sets(k))
            gone = st%status(s%elems) /= 0
            if (any(gone)) then
               do j = 1, s%nel
                  if (gone(j)) ero%nuse(s%conn(:, j)) = ero%nuse(s%conn(:, j)) - 1
               end do
               call compact(st, s, gone)
               ero%changed = .true.
            end if
         end associate
      end do
   end subroutine erosion_restore

   !> The quadrilateral with corners x(2, 4) is inverted or folded: area not positive, or a
   !> corner triangle negative beyond round-off (the test of quad4.f90's corner_estimate).
   pure logical function folded(x)
      real(wp), intent(in) :: x(2, 4)
      real(wp) :: a2, t2, ex(4), ey(4)
      integer :: a
      a2 = (x(1, 3) - x(1, 1))*(x(2, 4) - x(2, 2)) - (x(2, 3) - x(2, 1))*(x(1, 4) - x(1, 2))
      do a = 1, 4
         ex(a) = x(1, modulo(a, 4) + 1) - x(1, a)
         ey(a) = x(2, modulo(a, 4) + 1) - x(2, a)
      end do
      t2 = min(min(ex(4)*ey(1) - ey(4)*ex(1), ex(1)*ey(2) - ey(1)*ex(2)), &
               min(ex(2)*ey(3) - ey(2)*ex(3), ex(3)*ey(4) - ey(3)*ex(4)))
      folded = .not. (a2 > 0.0_wp .and. t2 > -FLAT*a2)
   end function folded

   !> The largest equivalent plastic strain at the points of element j of a plastic set, else
   !> the largest principal logarithmic strain at its centre (doc/erosion.md (R5)).
   real(wp) function element_strain(st, s, j) result(e)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: s
      integer, intent(in) :: j
      real(wp), parameter :: dxi(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp], deta(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]
      real(wp) :: j0(2, 2), j1(2, 2), f(2, 2), c11, c12, c22, lmax, det0, r0, r1
      integer :: a, n
      if (s%general) then
         if (s%solid%plastic) then
            e = maxval(s%hist(5, :, j))
            return
         end if
      end if
      j0 = 0.0_wp
      j1 = 0.0_wp
      r0 = 0.0_wp
      r1 = 0.0_wp
      do a = 1, 4
         n = s%conn(a, j)
         j0(:, 1) = j0(:, 1) + 0.25_wp*dxi(a)*st%x0(:, n)
         j0(:, 2) = j0(:, 2) + 0.25_wp*deta(a)*st%x0(:, n)
         j1(:, 1) = j1(:, 1) + 0.25_wp*dxi(a)*(st%x0(:, n) + st%u(:, n))
         j1(:, 2) = j1(:, 2) + 0.25_wp*deta(a)*(st%x0(:, n) + st%u(:, n))
         r0 = r0 + 0.25_wp*st%x0(1, n)
         r1 = r1 + 0.25_wp*(st%x0(1, n) + st%u(1, n))
      end do
      ! F = (dx/dxi) (dX/dxi)^-1 at the centre; C = F^T F, its largest eigenvalue lambda^2
      det0 = j0(1, 1)*j0(2, 2) - j0(1, 2)*j0(2, 1)
      f(:, 1) = (j1(:, 1)*j0(2, 2) - j1(:, 2)*j0(2, 1))/det0
      f(:, 2) = (j1(:, 2)*j0(1, 1) - j1(:, 1)*j0(1, 2))/det0
      c11 = f(1, 1)**2 + f(2, 1)**2
      c22 = f(1, 2)**2 + f(2, 2)**2
      c12 = f(1, 1)*f(1, 2) + f(2, 1)*f(2, 2)
      lmax = 0.5_wp*(c11 + c22) + sqrt(0.25_wp*(c11 - c22)**2 + c12**2)
      e = 0.5_wp*log(max(lmax, tiny(1.0_wp)))
      if (st%axisymmetric .and. r0 > 0.0_wp .and. r1 > 0.0_wp) e = max(e, log(r1/r0))
   end function element_strain

   !> Book the energy of element j of set s into st%energy%eroded, mark it with `why` and write its
   !> line into the report. `back` (an element removed before the pass at t(n+1), (R1)): its
   !> strain and hourglass energy W_e(n) at u(n) = u(n+1) - du, du = dt(n) v(n) + dt(n)^2/2 a(n)
   !> (eq. 4.3), plus 1/2 f_e(n) . du, the half of the trapezoid work of its force f_e(n) that the
   !> kinetic energy of the step does not receive (doc/erosion.md (R3a)); else (R2) its energy at
   !> u(n+1). `held`: that energy is in st%energy%strain and st%energy%hourglass now (a pass at
   !> t(n+1) included the element).
   subroutine book_element(st, s, j, back, why, messages, held)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: s
      integer, intent(in) :: j, why
      logical, intent(in) :: back
      type(messages_t), intent(inout) :: messages
      logical, intent(in), optional :: held
      real(wp) :: x0(2, 4), u(2, 4), v(2, 4), du(2, 4), f(2, 4), w, whg, wd, jm, d, wdu
      real(wp), allocatable :: hist(:, :, :)
      integer :: conn(4, 1), a, n, eb, em, ef
      du = 0.0_wp
      do a = 1, 4
         n = s%conn(a, j)
         x0(:, a) = st%x0(:, n)
         u(:, a) = st%u(:, n)
         v(:, a) = st%v(:, n)
         if (back) du(:, a) = st%dt_prev*v(:, a) + 0.5_wp*st%dt_prev**2*st%a(:, n)
         u(:, a) = u(:, a) - du(:, a)
         conn(a, 1) = a
      end do
      f = 0.0_wp
      whg = 0.0_wp
      if (s%general) then
         ! the element's own history (a copy: the energy is measured, the set is not changed)
         if (s%solid%nvar > 0) then
            hist = s%hist(:, :, j:j)
         else
            allocate (hist(0, 0, 0))
         end if
         call q4g_force(s%solid, 1, 4, conn, x0, u, 0.0_wp, hist, f, w, whg, wd, jm, eb, d, em, ef, v)
      else if (s%nq == 2) then
         call q4_force_2x2(1, 4, conn, x0, u, s%law, f, w, jm, eb, d, em, ef)
      else
         call q4_force_1pt(1, 4, conn, x0, u, s%law, s%hourglass, f, w, whg, jm, eb, d, em, &
                           ef, s%hgkind, v)
      end if
      wdu = 0.5_wp*sum(f*du)
      st%energy%eroded = st%energy%eroded + w + whg + wdu
      if (present(held)) then
         if (held) then
            st%energy%strain = st%energy%strain - w
            st%energy%hourglass = st%energy%hourglass - whg
         end if
      end if
      st%status(s%elems(j)) = why
      st%neroded = st%neroded + 1
      call messages%add('erosion: element '//itoa(s%elems(j))//' at t = '//rtoa(st%t)//', step '// &
                        itoa(int(st%step))//': '//trim(REASON(why))//', energy '//rtoa(w + whg + wdu)// &
                        ' (count '//itoa(st%neroded)//')')
   end subroutine book_element

   !> Take the elements `gone` out of set s (compact); the nodes no live element holds leave
   !> the model with their kinetic energy and momentum booked (doc/erosion.md (R4)). `before`:
   !> removed before the pass at t(n+1) (R1), with the terms of (R4a): the node's part of the
   !> kinetic correction at t(n), -dt(n)^2/8 r.a (r = m a - f_con, eq. E.3), the half of the
   !> trapezoid work of its contact force f_con(n) that its kinetic energy does not receive, and
   !> less the part of 1/2 f_e(n) . du that book_element counted at it (f_e(n) there is st%fint).
   subroutine remove(ero, st, s, gone, a_old, before)
      type(erosion_t), intent(inout) :: ero
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: s
      logical, intent(in) :: gone(:)
      real(wp), intent(inout), optional, allocatable :: a_old(:, :)
      logical, intent(in), optional :: before
      integer :: j, a, n
      real(wp) :: du(2), h
      h = st%dt_prev
      do j = 1, s%nel
         if (.not. gone(j)) cycle
         do a = 1, 4
            n = s%conn(a, j)
            ero%nuse(n) = ero%nuse(n) - 1
            if (ero%nuse(n) > 0) cycle
            st%energy%eroded = st%energy%eroded + 0.5_wp*st%mass(n)*(st%v(1, n)**2 + st%v(2, n)**2)
            if (present(before)) then
               if (before) then
                  du = h*st%v(:, n) + 0.5_wp*h*h*st%a(:, n)
                  st%energy%eroded = st%energy%eroded - 0.125_wp*h*h*sum((st%mass(n)*st%a(:, n) - &
                                     st%fcon(:, n))*st%a(:, n)) + 0.5_wp*sum((st%fcon(:, n) - st%fint(:, n))*du)
               end if
            end if
            st%eroded_momentum = st%eroded_momentum + st%mass(n)*st%v(:, n)
            st%v(:, n) = 0.0_wp
            st%a(:, n) = 0.0_wp
            st%minv(:, n) = 0.0_wp
            st%active(n) = .false.
            if (present(a_old)) then
               if (allocated(a_old)) a_old(:, n) = 0.0_wp
            end if
         end do
      end do
      call compact(st, s, gone)
      ero%changed = .true.
   end subroutine remove

   !> Set s without the elements `gone`: element list, nodes and history packed, ranges and
   !> colours formed again (set_ranges), st%eloc of the live ones renumbered, 0 for the others.
   subroutine compact(st, s, gone)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: s
      logical, intent(in) :: gone(:)
      integer :: i, nkeep
      integer, allocatable :: keep(:)
      keep = pack([(i, i=1, s%nel)], .not. gone)
      nkeep = size(keep)
      st%eloc(s%elems) = 0
      s%elems = s%elems(keep)
      s%conn = s%conn(:, keep)
      if (s%general) then
         if (s%solid%plastic) s%hist = s%hist(:, :, keep)
      end if
      s%nel = nkeep
      st%eloc(s%elems) = [(i, i=1, nkeep)]
      if (allocated(s%rfirst)) deallocate (s%rfirst)
      if (allocated(s%cfirst)) deallocate (s%cfirst)
      if (allocated(s%cranges)) deallocate (s%cranges)
      call set_ranges(s, st%nnode)
   end subroutine compact

end module exic_explicit_erosion
