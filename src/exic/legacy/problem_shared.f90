!> What several entry points of the legacy API share (exic_legacy_problem and its submodules):
!> rebuilding the contact object of a problem from its spec, masses, rigid masters and
!> fixities, and the checks of the host's arguments and handles, which record a failure's
!> message (exic_legacy_registry) and return false.
module exic_legacy_problem_shared
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int64
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_mesh_smoothing, only: quad_area
   use exic_base_error, only: error_t
   use exic_contact_contact, only: contact_t
   use exic_contact_spec, only: SURF_REGION, SURF_FACETS, SURF_NODES, PAIR_NTOS, PAIR_SYMMETRIC, &
                                PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, DETECT_SWEPT, DETECT_STATIC
   use exic_legacy_face, only: check_face, face_step_ok, face_motion, face_gap
   use exic_legacy_registry, only: problem_t, registry_add, registry_get, registry_free, set_error, &
                                   last_message, IERR_OK, IERR_ARGUMENT, IERR_HANDLE, IERR_SETUP, &
                                   IERR_SOLVE, VEL_FULL_STEP, VEL_HALF_STEP
   implicit none
   private

   public :: pair_table, apply_pair_options, rebuild, rigid_nodes, inverse_masses
   public :: lookup, counts_ok, nodes_ok, pairs_ok, fail

contains

   !> The pair table as in ipair(6, npair): slave, master and the current options.
   function pair_table(p) result(t)
      type(problem_t), intent(in) :: p
      integer, allocatable :: t(:, :)
      integer :: k
      allocate (t(6, p%npair))
      do k = 1, p%npair
         t(1, k) = p%spec%pairs(k)%slave
         t(2, k) = p%spec%pairs(k)%master
      end do
      t(3:6, :) = p%options
   end function pair_table

   !> Options (method, detection, passes, rigid) and penalty stiffness of pair k.
   subroutine apply_pair_options(p, k, iopt, pen)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: k, iopt(4)
      real(wp), intent(in) :: pen
      associate (ps => p%spec%pairs(k))
         ! 1 Lagrange, 2 penalty, 3 Lagrange with massless contact faces (LAGRange,ENERgy)
         ps%method = merge(METHOD_PENALTY, METHOD_LAGRANGE, iopt(1) == 2)
         ps%energy = iopt(1) == 3
         ps%detection = merge(DETECT_SWEPT, DETECT_STATIC, iopt(2) == 1)
         if (ps%slave == ps%master) then
            ps%kind = PAIR_SELF
         else
            ps%kind = merge(PAIR_NTOS, PAIR_SYMMETRIC, iopt(3) == 1)
         end if
         ps%penalty = pen
         p%options(:, k) = iopt
      end associate
   end subroutine apply_pair_options

   !> (Re)build the contact object from the spec and the masses, rigid masters and fixities.
   subroutine rebuild(who, p, ierr)
      character(len=*), intent(in) :: who
      type(problem_t), intent(inout) :: p
      integer, intent(out) :: ierr
      type(contact_t) :: fresh
      type(error_t), allocatable :: err
      logical, allocatable :: mark(:)
      real(wp), allocatable :: x(:, :)
      integer :: k, s

      call rigid_nodes(p)
      call inverse_masses(p)
      ! after steps, the segment lengths and the overlap check see the surfaces where they are now
      x = p%x0
      if (p%nsteps > 0) x(:, p%snodes) = p%xprev
      p%contact = fresh
      call p%contact%init(p%spec, p%nnode, x, x, p%nelem, p%conn, p%body, spread(1, 1, p%nelem), &
                          0.0_wp, err)
      if (allocated(err)) then
         ierr = IERR_SETUP
         call fail(0, who//': '//err%message)
         return
      end if
      allocate (mark(p%nnode), source=.false.)
      do k = 1, size(p%contact%surfaces)
         mark(p%contact%surfaces(k)%nodes) = .true.
      end do
      p%snodes = pack([(k, k=1, p%nnode)], mark)
      ! the massless faces of method-3 pairs (doc/impact.md, section 3): K_FF factorized again
      if (p%face_set) call p%contact%face%init(p%nnode, size(p%face), p%face, p%frp, p%fci, p%fval, err, &
                                               p%ffree)
      if (allocated(err)) then
         ierr = IERR_SETUP
         call fail(0, who//': '//err%message)
         return
      end if
      if (allocated(p%spos)) deallocate (p%spos)
      allocate (p%spos(p%nnode), source=0)
      do s = 1, size(p%snodes)
         p%spos(p%snodes(s)) = s
      end do
      if (.not. allocated(p%xprev)) then
         allocate (p%xprev(2, size(p%snodes)), p%fprev(2, size(p%snodes)), p%vprev(2, size(p%snodes)), &
                   p%vhalf(2, size(p%snodes)), p%xcor(2, size(p%snodes)), source=0.0_wp)
      end if
      ierr = IERR_OK
   end subroutine rebuild

   !> Nodes of rigid masters: every node of the master body's elements (connectivity), or of
   !> the master surface's segments (segment lists).
   subroutine rigid_nodes(p)
      type(problem_t), intent(inout) :: p
      integer :: k, e, j
      if (allocated(p%rigid)) deallocate (p%rigid)
      allocate (p%rigid(p%nnode), source=.false.)
      do k = 1, p%npair
         if (p%options(4, k) == 0) cycle
         associate (m => p%spec%pairs(k)%master)
            if (p%mesh_mode) then
               do e = 1, p%nelem
                  if (p%body(e) == m) p%rigid(p%conn(:, e)) = .true.
               end do
            else
               do j = 1, size(p%spec%surfaces)
                  if (p%spec%surfaces(j)%id /= m) cycle
                  if (p%spec%surfaces(j)%by == SURF_FACETS) &
                     p%rigid(reshape(p%spec%surfaces(j)%facets, [size(p%spec%surfaces(j)%facets)])) &
                     = .true.
               end do
            end if
         end associate
      end do
   end subroutine rigid_nodes

   !> minv = 1/m per dof; 0 on rigid-master nodes and on dofs the host prescribes.
   subroutine inverse_masses(p)
      type(problem_t), intent(inout) :: p
      integer :: i, k
      do i = 1, p%nnode
         p%minv(:, i) = 0.0_wp
         where (p%mass(:, i) > 0.0_wp) p%minv(:, i) = 1.0_wp/p%mass(:, i)
         if (p%rigid(i)) p%minv(:, i) = 0.0_wp
         where (p%fixed(:, i) /= 0) p%minv(:, i) = 0.0_wp
      end do
      ! the massless dofs of the face carry no mass: the face block places them (doc/impact.md,
      ! eq. I.5)
      if (p%face_set) then
         do k = 1, size(p%face)
            where (p%ffree(:, k)) p%minv(:, p%face(k)) = 0.0_wp
         end do
      end if
   end subroutine inverse_masses

   !> The live problem of h, or null with ierr = IERR_HANDLE and a message.
   function lookup(who, h, ierr) result(p)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      p => registry_get(h)
      if (associated(p)) then
         ierr = IERR_OK
      else
         ierr = IERR_HANDLE
         call fail(0, who//': handle '//itoa(h)//' names no live contact problem')
      end if
   end function lookup

   !> Node, entity and pair counts.
   logical function counts_ok(who, nnode, nent, name, npair) result(ok)
      character(len=*), intent(in) :: who, name
      integer, intent(in) :: nnode, nent, npair
      ok = .false.
      if (nnode < 1) then
         call fail(0, who//': NNODE = '//itoa(nnode)//' (must be >= 1)')
      else if (nent < 1) then
         call fail(0, who//': '//name//' = '//itoa(nent)//' (must be >= 1)')
      else if (npair < 1) then
         call fail(0, who//': NPAIR = '//itoa(npair)//' (must be >= 1)')
      else
         ok = .true.
      end if
   end function counts_ok

   !> Finite coordinates and positive finite masses.
   logical function nodes_ok(who, nnode, x0, mass) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x0(2, nnode), mass(nnode)
      integer :: i
      ok = .false.
      do i = 1, nnode
         if (.not. all(ieee_is_finite(x0(:, i)))) then
            call fail(0, who//': coordinate of node '//itoa(i)//' is not finite')
            return
         end if
         if (.not. (mass(i) > 0.0_wp .and. ieee_is_finite(mass(i)))) then
            call fail(0, who//': mass of node '//itoa(i)//' is '//rtoa(mass(i))//' (must be positive)')
            return
         end if
      end do
      ok = .true.
   end function nodes_ok

   !> Pair table: surfaces exist (has(s)), masters have segments (seg(s)), options in range.
   !> `first` is the number of the first pair in messages (default 1).
   logical function pairs_ok(who, npair, ipair, ppair, has, seg, first) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: npair
      integer, intent(in) :: ipair(6, npair)
      real(wp), intent(in) :: ppair(npair)
      logical, intent(in) :: has(:), seg(:)
      integer, intent(in), optional :: first
      integer :: k, k0
      character(len=:), allocatable :: at
      ok = .false.
      k0 = 0
      if (present(first)) k0 = first - 1
      do k = 1, npair
         at = who//': pair '//itoa(k + k0)//': '
         if (any(ipair(1:2, k) < 1 .or. ipair(1:2, k) > size(has))) then
            call fail(0, at//'slave '//itoa(ipair(1, k))//' or master '//itoa(ipair(2, k))//' is not defined')
            return
         end if
         if (.not. (has(ipair(1, k)) .and. has(ipair(2, k)))) then
            call fail(0, at//'slave '//itoa(ipair(1, k))//' or master '//itoa(ipair(2, k))//' is not defined')
            return
         end if
         if (.not. seg(ipair(2, k)) .or. (ipair(5, k) == 2 .and. .not. seg(ipair(1, k)))) then
            call fail(0, at//'a slave node set can only be the slave side of a one-pass pair')
            return
         end if
         if (ipair(3, k) < 1 .or. ipair(3, k) > 3 .or. ipair(4, k) < 1 .or. ipair(4, k) > 2 .or. &
             ipair(5, k) < 1 .or. ipair(5, k) > 2 .or. ipair(6, k) < 0 .or. ipair(6, k) > 1) then
            call fail(0, at//'method (1 to 3), detection, passes (1 or 2) or rigid flag (0 or 1) out of range')
            return
         end if
         if (ipair(3, k) == 2 .and. .not. (ppair(k) > 0.0_wp .and. ieee_is_finite(ppair(k)))) then
            call fail(0, at//'penalty stiffness '//rtoa(ppair(k))//' is not positive')
            return
         end if
      end do
      ok = .true.
   end function pairs_ok

   !> Record a failure (see set_error).
   subroutine fail(h, msg)
      integer, intent(in) :: h
      character(len=*), intent(in) :: msg
      call set_error(h, msg)
   end subroutine fail

end module exic_legacy_problem_shared
