!> The legacy API: the contact step on the host's arrays, with its argument checks.
submodule(exic_legacy_problem) exic_legacy_problem_step
   implicit none

contains

   !> One contact step: x = x(n+1), v = v~(n+1) (or v(n+1/2), option 1), a = a~(n+1) on entry
   !> and a(n+1) on exit, dtprev = dt(n) (0 at t = 0), dt = dt(n+1); fcon = nodal contact
   !> forces, nactive = constraints carrying force (eq. 4.4-4.7). The host's arrays go to
   !> contact_t%correct as they are: nothing of size nnode is copied.
   module procedure problem_step
      call step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
   end procedure problem_step

   !> The step of a handle with massless contact faces (method 3, doc/impact.md section 3): r =
   !> f_ext - f_int at t(n+1) on the face dofs (eq. I.5); a holds there on exit eq. I.7's.
   module procedure problem_step_face
      call step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr, r)
   end procedure problem_step_face

   !> Both steps; r present: the face step.
   subroutine step_common(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr, r)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      real(wp), intent(in) :: x(2, nnode), v(2, nnode)
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(in) :: dtprev, dt
      real(wp), intent(out) :: fcon(2, nnode)
      integer, intent(out) :: nactive, ierr
      real(wp), intent(in), optional :: r(2, nnode)
      type(problem_t), pointer :: p
      type(error_t), allocatable :: err
      integer :: k, i, nbad
      real(wp) :: c

      nactive = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) then
         fcon = 0.0_wp
         return
      end if
      if (.not. step_args_ok(who, h, p, nnode, x, dtprev, dt)) then
         ierr = IERR_ARGUMENT
         fcon = 0.0_wp
         return
      end if
      if (.not. face_step_ok(who, h, p, present(r))) then
         ierr = IERR_SETUP
         fcon = 0.0_wp
         return
      end if
      if (present(r)) then
         ! the residual is read on the face dofs; the host's a~ on the massless dofs means
         ! nothing (no mass): their x~(n+2) is x*, eq. I.7
         do k = 1, size(p%face)
            i = p%face(k)
            if (nonfinite(r(1, i)) + nonfinite(r(2, i)) > 0) then
               call fail(h, who//': residual R of face node '//itoa(i)//' is not finite')
               ierr = IERR_ARGUMENT
               fcon = 0.0_wp
               return
            end if
            where (p%ffree(:, k)) a(:, i) = 0.0_wp
         end do
      end if
      ! the velocities and accelerations the corrector reads: those of the surface nodes
      nbad = 0
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         nbad = nbad + nonfinite(v(1, i)) + nonfinite(v(2, i)) + nonfinite(a(1, i)) + nonfinite(a(2, i))
      end do
      if (nbad > 0) then
         call fail(h, who//': '//first_bad(p, nnode, v, a))
         ierr = IERR_ARGUMENT
         fcon = 0.0_wp
         return
      end if
      ! v(n+1/2) of the surface nodes, for the contact work (after_step)
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         if (p%velocity_form == VEL_HALF_STEP) then
            p%vhalf(:, k) = v(:, i)
         else
            p%vhalf(:, k) = v(:, i) - (0.5_wp*dtprev)*a(:, i)
         end if
      end do
      if (p%velocity_form == VEL_HALF_STEP) then
         ! v~(n+1) = v(n+1/2) + dt(n)/2 a~(n+1) (only surface nodes are read, every node with
         ! a massless face: its free solve reads the predicted motion of the nodes next to it)
         if (present(r)) then
            p%vt = v + (0.5_wp*dtprev)*a
         else
            do k = 1, size(p%snodes)
               i = p%snodes(k)
               p%vt(:, i) = v(:, i) + (0.5_wp*dtprev)*a(:, i)
            end do
         end if
         ! (r absent and p%zero unallocated without a face: fext and fint are absent)
         call p%contact%correct(nnode, x, p%vt, a, p%minv, dtprev, dt, fcon, nactive, err, fext=r, fint=p%zero)
      else
         call p%contact%correct(nnode, x, v, a, p%minv, dtprev, dt, fcon, nactive, err, fext=r, fint=p%zero)
      end if
      if (allocated(err)) then
         call fail(h, who//': '//err%message)
         ierr = IERR_SOLVE
         return
      end if
      call after_step(p, nnode, x, a, dtprev, fcon)
      c = 0.5_wp*dt*(dtprev + dt)
      p%c = c
      if (present(r)) call face_motion(p, nnode, x, v, a, dt, c)
      p%nsteps = p%nsteps + 1
      do k = 1, size(p%contact%results)
         p%max_pen = max(p%max_pen, p%contact%results(k)%penetration)
      end do
   end subroutine step_common

   !> What the queries need of the surface nodes: the contact forces (the correction of the
   !> accelerations is minv fcon) and the contact work as the driver books it (doc/impact.md,
   !> eq. I.12): on a dof with mass the two half kicks dt(n)/2 (f(n) . (v(n) + v(n+1/2))/2 +
   !> f(n+1) . (v(n+1/2) + v(n+1))/2), elsewhere 1/2 (f(n) + f(n+1)) . (x(n+1) - x(n)).
   subroutine after_step(p, nnode, x, a, dtprev, fcon)
      type(problem_t), intent(inout) :: p
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), a(2, nnode), dtprev, fcon(2, nnode)
      integer :: k, i, d
      real(wp) :: w, h, vnew
      w = 0.0_wp
      h = 0.5_wp*dtprev
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         do d = 1, 2
            vnew = p%vhalf(d, k) + h*a(d, i)
            if (p%minv(d, i) > 0.0_wp) then
               w = w + h*(p%fprev(d, k)*(p%vprev(d, k) + p%vhalf(d, k)) + fcon(d, i)*(p%vhalf(d, k) + vnew))
            else
               w = w + (p%fprev(d, k) + fcon(d, i))*(x(d, i) - p%xprev(d, k))
            end if
            p%vprev(d, k) = vnew
         end do
         p%xprev(:, k) = x(:, i)
         p%fprev(:, k) = fcon(:, i)
      end do
      if (p%nsteps > 0) p%wcon = p%wcon + 0.5_wp*w
   end subroutine after_step

   !> Step arguments: node count, time steps and finite positions.
   logical function step_args_ok(who, h, p, nnode, x, dtprev, dt) result(ok)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode
      type(problem_t), intent(in) :: p
      real(wp), intent(in) :: x(2, nnode), dtprev, dt
      integer :: i
      ok = .false.
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         return
      end if
      if (.not. (dt > 0.0_wp .and. ieee_is_finite(dt))) then
         call fail(h, who//': DT = '//rtoa(dt)//' is not a positive finite step')
         return
      end if
      if (.not. (dtprev >= 0.0_wp .and. ieee_is_finite(dtprev))) then
         call fail(h, who//': DTPREV = '//rtoa(dtprev)//' is not a finite step >= 0')
         return
      end if
      if (count_nonfinite(2*nnode, x) > 0) then
         do i = 1, nnode
            if (.not. (ieee_is_finite(x(1, i)) .and. ieee_is_finite(x(2, i)))) then
               call fail(h, who//': position of node '//itoa(i)//' is not finite')
               return
            end if
         end do
      end if
      ok = .true.
   end function step_args_ok

   !> Number of entries of vals(n) that are NaN or infinite (all exponent bits set); integer
   !> arithmetic on the bit patterns, so the loop vectorizes where a floating-point test
   !> reduction could not (its order of additions is fixed).
   pure integer function count_nonfinite(n, vals) result(nbad)
      integer, intent(in) :: n
      real(wp), intent(in) :: vals(n)
      integer :: i
      nbad = 0
      do i = 1, n
         nbad = nbad + nonfinite(vals(i))
      end do
   end function count_nonfinite

   !> 1 if val is NaN or infinite (all exponent bits set), else 0.
   elemental integer function nonfinite(val) result(bad)
      real(wp), intent(in) :: val
      integer(int64), parameter :: expo = int(z'7FF0000000000000', int64)
      bad = merge(1, 0, iand(transfer(val, 0_int64), expo) == expo)
   end function nonfinite

   !> Message naming the first surface node with a non-finite velocity or acceleration.
   function first_bad(p, nnode, v, a) result(msg)
      type(problem_t), intent(in) :: p
      integer, intent(in) :: nnode
      real(wp), intent(in) :: v(2, nnode), a(2, nnode)
      character(len=:), allocatable :: msg
      integer :: k, i
      msg = 'a velocity or acceleration is not finite'
      do k = 1, size(p%snodes)
         i = p%snodes(k)
         if (.not. all(ieee_is_finite(v(:, i)))) then
            msg = 'velocity of node '//itoa(i)//' is not finite'
            return
         else if (.not. all(ieee_is_finite(a(:, i)))) then
            msg = 'acceleration of node '//itoa(i)//' is not finite'
            return
         end if
      end do
   end function first_bad

end submodule exic_legacy_problem_step
