!> Checks of the massless contact faces a host hands to the legacy API (EXIC_CONTACT_SET_FACE,
!> doc/api.md; doc/impact.md, section 3): face nodes, masses off the face, and the rows of the
!> host's initial stiffness for the face dofs, returned in sorted CSR.
module exic_legacy_face
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_explicit_face, only: to_csr
   use exic_legacy_registry, only: problem_t, set_error, VEL_HALF_STEP
   implicit none
   private

   public :: check_face, face_step_ok, face_motion, face_gap

contains

   !> spos(nnode) > 0 on contact surface nodes, rigid(nnode), fixed(2, nnode) of the handle;
   !> mass(2, nnode) per dof, nf, iface, ifdof(2, nf) (1: massless dof), irp, ici, val as
   !> EXIC_CONTACT_SET_FACE_DOFS. On success msg = '' and rp, ci, v the face rows with sorted,
   !> merged columns; else msg says what is wrong. The symmetry of the face block is checked
   !> between massless dofs (the rows of dofs with mass are not read).
   subroutine check_face(nnode, spos, rigid, fixed, mass, nf, iface, ifdof, irp, ici, val, rp, ci, v, msg)
      integer, intent(in) :: nnode, nf
      integer, intent(in) :: spos(nnode), fixed(2, nnode)
      logical, intent(in) :: rigid(nnode)
      real(wp), intent(in) :: mass(2, nnode)
      integer, intent(in) :: iface(nf), ifdof(2, nf), irp(2*nf + 1), ici(*)
      real(wp), intent(in) :: val(*)
      integer, allocatable, intent(out) :: rp(:), ci(:)
      real(wp), allocatable, intent(out) :: v(:)
      character(len=:), allocatable, intent(out) :: msg
      integer, allocatable :: fidx(:), trip(:, :)
      real(wp), allocatable :: vals(:)
      integer :: k, i, r, q, nnz, nd, col, rt, qt, d
      real(wp) :: vmax, vt
      logical :: found
      msg = ''
      if (nf < 1 .or. nf > nnode) then
         msg = 'NF = '//itoa(nf)//' is outside 1..'//itoa(nnode)
         return
      end if
      allocate (fidx(nnode), source=0)
      do k = 1, nf
         i = iface(k)
         if (i < 1 .or. i > nnode) then
            msg = ('face entry '//itoa(k)//' names node '//itoa(i)//', outside 1..'//itoa(nnode))
            return
         end if
         if (fidx(i) /= 0) then
            msg = ('node '//itoa(i)//' is given twice in IFACE')
            return
         end if
         if (spos(i) == 0 .or. rigid(i) .or. any(fixed(:, i) /= 0)) then
            msg = ('face node '//itoa(i)//' is not a node of a contact surface, or is rigid or '// &
                      'prescribed (doc/impact.md, section 3.1)')
            return
         end if
         if (any(ifdof(:, k) /= 0 .and. ifdof(:, k) /= 1) .or. all(ifdof(:, k) == 0)) then
            msg = ('IFDOF(:, '//itoa(k)//') of face node '//itoa(i)//' is '//itoa(ifdof(1, k))//', '// &
                   itoa(ifdof(2, k))//' (each 0 or 1, one massless dof at least)')
            return
         end if
         fidx(i) = k
      end do
      do i = 1, nnode
         do d = 1, 2
            if (fidx(i) /= 0) then
               if (ifdof(d, fidx(i)) == 1) cycle
            end if
            if (.not. (mass(d, i) > 0.0_wp .and. ieee_is_finite(mass(d, i)))) then
               msg = ('mass of node '//itoa(i)//' along dof '//itoa(d)//' (off the face) is '//rtoa(mass(d, i))// &
                      ' (must be positive)')
               return
            end if
         end do
      end do
      if (irp(1) /= 1 .or. any(irp(2:) < irp(:2*nf))) then
         msg = ('IRP must start at 1 and never decrease')
         return
      end if
      nnz = irp(2*nf + 1) - 1
      allocate (trip(2, nnz), vals(nnz))
      do r = 1, 2*nf
         do q = irp(r), irp(r + 1) - 1
            if (ici(q) < 1 .or. ici(q) > 2*nnode .or. .not. ieee_is_finite(val(q))) then
               msg = ('entry '//itoa(q)//' of row '//itoa(r)//': column '//itoa(ici(q))// &
                         ' outside 1..'//itoa(2*nnode)//' or value not finite')
               return
            end if
            trip(:, q) = [r, ici(q)]
            vals(q) = val(q)
         end do
      end do
      ! sorted rows with merged columns; the face block K_FF must be symmetric (to 1e-10 of
      ! the largest entry: the host's element stiffness may be formed numerically)
      call to_csr(2*nf, nnz, trip, vals, rp, ci, v)
      vmax = 0.0_wp
      if (size(v) > 0) vmax = maxval(abs(v))
      do r = 1, 2*nf
         if (ifdof(2 - mod(r, 2), (r + 1)/2) /= 1) cycle
         do q = rp(r), rp(r + 1) - 1
            nd = (ci(q) + 1)/2
            if (fidx(nd) == 0) cycle
            if (ifdof(ci(q) - 2*(nd - 1), fidx(nd)) /= 1) cycle
            rt = 2*(fidx(nd) - 1) + ci(q) - 2*(nd - 1)
            col = 2*(iface((r + 1)/2) - 1) + r - 2*((r + 1)/2 - 1)
            found = .false.
            vt = 0.0_wp
            do qt = rp(rt), rp(rt + 1) - 1
               if (ci(qt) == col) then
                  found = .true.
                  vt = v(qt)
               end if
            end do
            if (.not. found .or. abs(vt - v(q)) > 1.0e-10_wp*vmax) then
               msg = ('the face block is not symmetric at the dofs '//itoa(ci(q))//' and '// &
                         itoa(col)//' (rows of face nodes '//itoa(iface((r + 1)/2))//' and '//itoa(nd)//')')
               return
            end if
         end do
      end do
   end subroutine check_face

   !> A handle with a method-3 pair steps with its face set and with EXIC_CONTACT_STEP_FACE
   !> (face = the call is the face step); a handle without a face has no face step.
   logical function face_step_ok(who, h, p, face) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h
      type(problem_t), intent(in) :: p
      logical, intent(in) :: face
      ok = .false.
      if (p%contact%energy .and. .not. p%face_set) then
         call set_error(h, who//': a pair has method 3 (massless contact faces): call EXIC_CONTACT_SET_FACE '// &
                   'and EXIC_CONTACT_STEP_FACE')
      else if (p%face_set .and. .not. face) then
         call set_error(h, who//': the handle has massless contact faces: step with EXIC_CONTACT_STEP_FACE '// &
                   '(it takes the residual R of the face)')
      else if (face .and. .not. p%face_set) then
         call set_error(h, who//': the handle has no massless contact face (EXIC_CONTACT_SET_FACE) to step')
      else
         ok = .true.
      end if
   end function face_step_ok

   !> After a face step: the face's motion by the correction, x(n+2) - x~(n+2) = x* + c a -
   !> x~(n+2) with x* = x + dt v~ (eq. I.7; a~ = 0 on the face), kept for the corrected gaps of
   !> the queries; v the step's velocities (v~(n+1), or v(n+1/2) and then v~ is p%vt), dt =
   !> dt(n+1), c of eq. 4.7.
   subroutine face_motion(p, nnode, x, v, a, dt, c)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), v(2, nnode), a(2, nnode), dt, c
      integer :: k, i
      do k = 1, size(p%face)
         i = p%face(k)
         if (p%velocity_form == VEL_HALF_STEP) then
            p%xcor(:, p%spos(i)) = x(:, i) + dt*p%vt(:, i) + c*a(:, i) - p%contact%xp(:, i)
         else
            p%xcor(:, p%spos(i)) = x(:, i) + dt*v(:, i) + c*a(:, i) - p%contact%xp(:, i)
         end if
         ! a dof with mass moves by c M^-1 G p, which the queries add themselves
         where (.not. p%ffree(:, k)) p%xcor(:, p%spos(i)) = 0.0_wp
      end do
   end subroutine face_motion

   !> The face's share of the corrected gap of constraint i at t(n+2): its massless nodes move by
   !> their static correction (eq. I.7).
   real(wp) function face_gap(p, i) result(g)
      type(problem_t), intent(in) :: p
      integer, intent(in) :: i
      integer :: j, nd
      g = 0.0_wp
      associate (cs => p%contact%cs)
         do j = 1, 3
            nd = cs%node(j, i)
            if (p%contact%face%fidx(nd) == 0) cycle
            g = g + cs%w(j, i)*dot_product(cs%nrm(:, i), p%xcor(:, p%spos(nd)))
         end do
      end associate
   end function face_gap

end module exic_legacy_face
