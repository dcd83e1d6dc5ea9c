!> The legacy API: results, constraints, work and messages of the last step.
submodule(exic_legacy_problem) exic_legacy_problem_queries
   implicit none

contains

   !> res(6) of pair ipair in the last step: normal force (sum of multipliers), force x, y on
   !> the slave side (normal and friction), active constraints, largest penetration at t(n+1),
   !> largest multiplier.
   module procedure problem_pair_results
      call pair_values(who, h, ipair, 0, res, ierr)
   end procedure problem_pair_results

   !> res(4) of pair ipair: friction force (sum of |q| over its constraints) in the last step,
   !> constraints that stick and that slip in it, frictional dissipation since the friction was
   !> set (doc/friction.md, section 7). The friction forces are also in the pair results' force
   !> x, y and in the nodal contact forces of the step.
   module procedure problem_pair_friction
      call pair_values(who, h, ipair, 7, res, ierr)
   end procedure problem_pair_friction

   !> res(k) = value skip + k of pair ipair's results (contact_t%pair_value), k = 1..size(res),
   !> after checking the handle and the pair number.
   subroutine pair_values(who, h, ipair, skip, res, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, ipair, skip
      real(wp), intent(out) :: res(:)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer :: k
      res = 0.0_wp
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         ierr = IERR_ARGUMENT
         return
      end if
      do k = 1, size(res)
         res(k) = p%contact%pair_value(ipair, skip + k)
      end do
   end subroutine pair_values

   !> Number of candidate (Lagrange) constraints of the last step.
   module procedure problem_ncon
      type(problem_t), pointer :: p
      ncon = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ncon = p%contact%cs%n
   end procedure problem_ncon

   !> The candidate constraints of the last step: icon(4, :) = slave, master 1, master 2, pair;
   !> rcon(6, :) = multiplier p (>= 0, compressive), alpha, normal x, y, gap at t(n+1), gap at
   !> t(n+2) after the correction (eq. 3.19 along the frozen normal). mcon >= ncon is required.
   module procedure problem_constraints
      type(problem_t), pointer :: p
      integer :: i, j, nd, s
      real(wp) :: dg
      ncon = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ncon = p%contact%cs%n
      if (mcon < ncon) then
         call fail(h, who//': MCON = '//itoa(mcon)//' is below the '//itoa(ncon)//' constraints')
         ierr = IERR_ARGUMENT
         return
      end if
      associate (cs => p%contact%cs)
         do i = 1, ncon
            icon(1:3, i) = cs%node(:, i)
            icon(4, i) = cs%pair(i)
            rcon(1, i) = cs%p(i)
            rcon(2, i) = -cs%w(3, i)
            rcon(3:4, i) = cs%nrm(:, i)
            rcon(5, i) = cs%gap_now(i)
            ! g(n+2) = g~ + c G_i^T (a - a~) with a - a~ = M^-1 fcon: the correction moves
            ! x(n+2) by c (a - a~) (eq. 4.5-4.7)
            dg = 0.0_wp
            do j = 1, 3
               nd = cs%node(j, i)
               s = p%spos(nd)
               dg = dg + cs%w(j, i)*dot_product(cs%nrm(:, i), p%minv(:, nd)*p%fprev(:, s))
            end do
            rcon(6, i) = cs%gap(i) + p%c*dg
            if (p%face_set) rcon(6, i) = rcon(6, i) + face_gap(p, i)
         end do
      end associate
   end procedure problem_constraints

   !> Work of the contact forces since creation and the largest penetration at t(n+1) seen.
   module procedure problem_work
      type(problem_t), pointer :: p
      wcon = 0.0_wp
      penmax = 0.0_wp
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      wcon = p%wcon
      penmax = p%max_pen
   end procedure problem_work

   !> Release handle h.
   module procedure problem_free
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      call registry_free(h)
   end procedure problem_free

   !> The message of the last failed call on handle h (of any call when h names no live
   !> problem), blank-padded or cut to len(msg); lmsg is its full length.
   module procedure problem_message
      character(len=:), allocatable :: m
      m = last_message(h)
      msg = m
      lmsg = len(m)
   end procedure problem_message

end submodule exic_legacy_problem_queries
