!> Coulomb friction in the implicit corrector: the frictional complementarity problem of a step
!> (doc/friction.md, eq. F6-F15).
!>
!> Each candidate i gains a tangential multiplier q_i, the force on its slave along
!> t_i = e3 x n_i (F1), with |q_i| <= mu_i p_i (F9); the slave sticks to its master point over
!> the step the corrector controls (ds_i = 0, F10) or slides with q_i = -mu_i p_i sign(ds_i)
!> (F11), ds_i = ds~_i + c [G_T^T M^-1 (G_N p + G_T q)]_i the relative tangential increment
!> from t(n+1) to t(n+2) (F6). The step is solved as a sequence of two symmetric problems
!> (F13-F14): the seed's normal problem (corrector_t, unchanged) with the gaps shifted by the
!> tangential forces, and a box-constrained tangential problem on S_TT = G_T^T M^-1 G_T with the
!> bounds mu p, solved by block principal pivoting on the box (F15); in turn until the
!> multipliers change by at most FRICTION_TOL of the largest normal one. Both problems reuse
!> the assembly and factorisation code of system_t (S_TT has the pattern of S_NN); a
!> factorisation with the free set of the previous sweep is reused.
!>
!> Free rigid bodies take part through their tangential columns (F5, rigid_dofs_t). The caller
!> (contact_t) is the only user; without friction it calls corrector_t%solve instead, so that
!> frictionless steps keep the seed's operations to the last bit.
module exic_contact_friction
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_grow, only: grow
   use exic_contact_pivot_rule, only: pivot_rule_t
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_system, only: system_t
   use exic_contact_corrector, only: constraints_t, corrector_t, apply, gap_change
   implicit none
   private

   public :: friction_t, coulomb_mu

   !> Sweeps end when no multiplier changes by more than this share of the largest normal one.
   real(wp), parameter, public :: FRICTION_TOL = 1.0e-10_wp
   !> Sweeps (normal then tangential problem) before a step is given up as not converged.
   integer, parameter, public :: FRICTION_SWEEPS = 50
   !> Mirrored pairs (section 4.1): each slave within this share of its segment of the other node.
   real(wp), parameter, public :: MIRROR_TOL = 0.05_wp

   !> The tangential problem's matrix, its work arrays and statistics (kept across steps).
   type :: friction_t
      type(system_t) :: tt                   !< S_TT of the step's candidates
      integer :: max_passes = 30             !< pivoting passes of one tangential problem
      ! statistics
      integer :: sweeps = 0                  !< sweeps of the last call
      integer :: nsweeps = 0                 !< sweeps over the run
      integer :: ncalls = 0                  !< steps solved with friction
      integer :: sweep_limit_hits = 0        !< steps that ended at FRICTION_SWEEPS
      integer :: pass_limit_hits = 0         !< tangential problems that ended at max_passes
      integer :: max_sweeps = 0              !< most sweeps of one step over the run
      integer :: max_tpasses = 0             !< most pivoting passes of one tangential problem
      integer :: nmirrors = 0                !< mirrored pairs over the run (section 4.1)
      integer :: nswaps = 0                  !< mirrored pairs whose skipped candidate took the other's place
      ! work arrays (grown, never shrunk); m candidates, nnode nodes
      real(wp), allocatable :: tng(:, :)     !< (2, m) tangents t = e3 x n
      real(wp), allocatable :: slide0(:)     !< (m) predicted slips ds~ (F6)
      real(wp), allocatable :: geff(:)       !< (m) gaps shifted by the tangential forces (F13)
      real(wp), allocatable :: b(:)          !< (m) ds~/c + S_TN p (F15)
      real(wp), allocatable :: beta(:)       !< (m) bounds mu p
      integer, allocatable :: side(:)        !< (m) 0 free (stick), +1 / -1 at the bound +beta / -beta
      real(wp), allocatable :: rhs(:), sol(:), pold(:), qold(:), qb(:), zero(:)
      logical, allocatable :: drop(:), infeasible(:)
      logical, allocatable :: skip(:)        !< (m) the candidate of a mirrored pair left out (section 4.1)
      logical, allocatable :: swapped(:)     !< (m) the pair has swapped its candidates in this step
      integer, allocatable :: partner(:)     !< (m) the other candidate of a mirrored pair, or 0
      ! slave node -> its first candidate at a segment end, valid where ostamp is this step's
      integer, allocatable :: owner(:), ostamp(:)
      integer :: ogen = 0
      real(wp), allocatable :: ft(:, :)      !< (2, nnode) G_T q
   contains
      procedure :: solve => friction_solve
   end type friction_t

contains

   !> The friction coefficient of a step (eq. F12) from the law (mus, mud, decay) and the slip
   !> speed of the previous step, vslip < 0 when the slave stuck or was not in contact: mus after
   !> a stick, mud + (mus - mud) exp(-decay vslip) after a slip (mud without decay, decay <= 0).
   pure real(wp) function coulomb_mu(mus, mud, decay, vslip) result(mu)
      real(wp), intent(in) :: mus, mud, decay, vslip
      if (vslip < 0.0_wp) then
         mu = mus
      else if (decay > 0.0_wp) then
         mu = mud + (mus - mud)*exp(-decay*vslip)
      else
         mu = mud
      end if
   end function coulomb_mu

   !> Solve the frictional problem of the candidates `cs` (cs%mu: their coefficients; eq. F12)
   !> with the normal problem of `corr`: on return cs%p, cs%q, cs%slip (ds, F6) and cs%state
   !> (1 stick, 2 slip, 0 no friction force) are set, a += M^-1 (G_N p + G_T q),
   !> fcon += G_N p + G_T q and ffric += G_T q (penalty passes may have added theirs).
   !> x = x(n+1) and xp = x~(n+2) (eq. 4.4) give the predicted slips; minv, c, rb as for
   !> corrector_t%solve.
   subroutine friction_solve(self, corr, cs, nnode, minv, c, x, xp, a, fcon, ffric, err, rb)
      class(friction_t), intent(inout) :: self
      type(corrector_t), intent(inout) :: corr
      type(constraints_t), intent(inout) :: cs
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode), c, x(2, nnode), xp(2, nnode)
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      real(wp), intent(inout) :: ffric(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      type(rigid_dofs_t), intent(inout), optional :: rb
      integer :: m, i, k
      real(wp) :: pmax, dpq

      m = cs%n
      corr%passes = 0
      corr%nredundant = 0
      self%sweeps = 0
      if (m == 0) return
      cs%p(1:m) = 0.0_wp
      cs%q(1:m) = 0.0_wp
      cs%slip(1:m) = 0.0_wp
      cs%state(1:m) = 0
      cs%active(1:m) = cs%gap(1:m) < 0.0_wp
      if (.not. any(cs%active(1:m))) return
      self%ncalls = self%ncalls + 1
      call corr%prepare(cs, nnode, minv, rb)
      call work_arrays(self, m, nnode)
      self%ft = 0.0_wp
      ! a mirrored pair is one contact point (section 4.1): one of its candidates leaves the step
      call merge_mirrors(self, cs, m)
      where (self%skip(1:m)) cs%active(1:m) = .false.
      do i = 1, m
         self%tng(:, i) = [-cs%nrm(2, i), cs%nrm(1, i)]
         self%slide0(i) = 0.0_wp
         do k = 1, 3
            if (cs%w(k, i) == 0.0_wp) cycle
            associate (nd => cs%node(k, i))
               self%slide0(i) = self%slide0(i) + cs%w(k, i)*dot_product(self%tng(:, i), xp(:, nd) - x(:, nd))
            end associate
         end do
      end do
      if (present(rb)) call rb%tangent_columns(m, cs%node(:, 1:m), cs%w(:, 1:m), self%tng(:, 1:m))
      call self%tt%assemble(m, cs%node(:, 1:m), corr%lnode(:, 1:m), cs%w(:, 1:m), self%tng(:, 1:m), &
                            nnode, minv, corr%nloc, corr%nstart, corr%nlist, corr%nweight, rb, &
                            tangent=.true.)
      self%side(1:m) = 0
      self%geff(1:m) = cs%gap(1:m)
      do k = 1, FRICTION_SWEEPS
         self%sweeps = k
         self%pold(1:m) = cs%p(1:m)
         self%qold(1:m) = cs%q(1:m)
         ! (F13) the normal problem with the gaps shifted by the tangential forces, from the last
         ! sweep's active set
         call corr%pivot(cs, nnode, minv, c, self%geff(1:m), err, rb, skip=self%skip(1:m))
         if (allocated(err)) return
         ! (F14) the tangential problem with the bounds mu p and b = ds~/c + S_TN p
         if (present(rb)) call rb%accelerations(m, cs%p(1:m))
         do i = 1, m
            self%b(i) = self%slide0(i)/c + slide_change(cs, self%tng, i, nnode, minv, corr%fwork)
            if (present(rb)) self%b(i) = self%b(i) + rb%slide_part(i)
            self%beta(i) = cs%mu(i)*cs%p(i)
         end do
         call tangential(self, cs, m, nnode, minv, c, corr%gap_tol, err, rb)
         if (allocated(err)) return
         pmax = maxval(cs%p(1:m))
         dpq = max(maxval(abs(cs%p(1:m) - self%pold(1:m))), maxval(abs(cs%q(1:m) - self%qold(1:m))))
         if ((k > 1 .and. dpq <= FRICTION_TOL*pmax) .or. pmax <= 0.0_wp) then
            ! converged; a skipped mirrored candidate whose gap the step leaves violated takes
            ! its partner's place, once per pair (section 4.1), and the sweeps go on
            if (.not. swap_mirrors(self, cs, corr, m, nnode, minv, c, rb)) exit
         end if
         if (k == FRICTION_SWEEPS) then
            self%sweep_limit_hits = self%sweep_limit_hits + 1
            exit
         end if
         ! the gaps the next normal problem sees: g~ + c S_NT q
         call apply_tangent(cs, self%tng, cs%q, nnode, self%ft)
         if (present(rb)) call rb%accelerations_nt(m, self%zero(1:m), cs%q(1:m))
         do i = 1, m
            self%geff(i) = cs%gap(i) + c*gap_change(cs, i, nnode, minv, self%ft)
            if (present(rb)) self%geff(i) = self%geff(i) + c*rb%gap_part(i)
         end do
      end do
      self%nsweeps = self%nsweeps + self%sweeps
      self%max_sweeps = max(self%max_sweeps, self%sweeps)
      ! the forces, the slips of the step (F6) and the state of each candidate
      call apply_tangent(cs, self%tng, cs%q, nnode, self%ft)
      if (present(rb)) call rb%accelerations_nt(m, cs%p(1:m), cs%q(1:m))
      do i = 1, m
         cs%slip(i) = self%slide0(i) + c*(slide_change(cs, self%tng, i, nnode, minv, corr%fwork) + &
                                          slide_change(cs, self%tng, i, nnode, minv, self%ft))
         if (present(rb)) cs%slip(i) = cs%slip(i) + c*rb%slide_part(i)
         ! a candidate at its bound slips when it moves (beyond the gap tolerance); one that the
         ! bound holds in place sticks (doc/friction.md, section 5: no dissipation)
         if (self%beta(i) > 0.0_wp) then
            cs%state(i) = 1
            if (self%side(i) /= 0 .and. abs(cs%slip(i)) > corr%gap_tol) cs%state(i) = 2
         end if
      end do
      ffric = ffric + self%ft
      a = a + minv*(corr%fwork + self%ft)
      fcon = fcon + corr%fwork + self%ft
   end subroutine friction_solve

   !> Every work array holds m candidates and nnode nodes.
   subroutine work_arrays(self, m, nnode)
      type(friction_t), intent(inout) :: self
      integer, intent(in) :: m, nnode
      call grow(self%tng, m, 2)
      call grow(self%slide0, m)
      call grow(self%geff, m)
      call grow(self%b, m)
      call grow(self%beta, m)
      call grow(self%side, m)
      call grow(self%rhs, m)
      call grow(self%sol, m)
      call grow(self%pold, m)
      call grow(self%qold, m)
      call grow(self%qb, m)
      call grow(self%zero, m)
      self%zero(1:m) = 0.0_wp
      call grow(self%drop, m)
      call grow(self%infeasible, m)
      call grow(self%skip, m)
      call grow(self%swapped, m)
      call grow(self%partner, m)
      if (allocated(self%ft)) then
         if (size(self%ft, 2) /= nnode) deallocate (self%ft)
      end if
      if (.not. allocated(self%ft)) allocate (self%ft(2, nnode))
      if (allocated(self%ostamp)) then
         if (size(self%ostamp) /= nnode) deallocate (self%ostamp, self%owner)
      end if
      if (.not. allocated(self%ostamp)) then
         allocate (self%ostamp(nnode), self%owner(nnode))
         self%ostamp = 0
         self%ogen = 0
      end if
   end subroutine work_arrays

   !> The box-constrained tangential problem (F15) by block principal pivoting: candidates with
   !> beta > 0 are free (stick: ds = 0) or at a bound (slip); the others carry q = 0. Starts from
   !> self%side (the last sweep's sets); on return cs%q and self%side.
   subroutine tangential(self, cs, m, nnode, minv, c, tol, err, rb)
      type(friction_t), intent(inout) :: self
      type(constraints_t), intent(inout) :: cs
      integer, intent(in) :: m, nnode
      real(wp), intent(in) :: minv(2, nnode), c, tol
      type(error_t), allocatable, intent(out) :: err
      type(rigid_dofs_t), intent(inout), optional :: rb
      integer :: i, pass, nfree, nbad, ninf, last
      type(pivot_rule_t) :: rule
      real(wp) :: ds

      where (.not. self%beta(1:m) > 0.0_wp) self%side(1:m) = 0
      pass = 0
      do
         pass = pass + 1
         self%max_tpasses = max(self%max_tpasses, pass)
         ! the bounded values, moved to the right-hand side: rhs = -b - S_TT q_B
         do i = 1, m
            self%qb(i) = 0.0_wp
            if (self%beta(i) > 0.0_wp) self%qb(i) = real(self%side(i), wp)*self%beta(i)
         end do
         call apply_tangent(cs, self%tng, self%qb, nnode, self%ft)
         if (present(rb)) call rb%accelerations_nt(m, self%zero(1:m), self%qb(1:m))
         nfree = 0
         do i = 1, m
            self%drop(i) = .not. (self%beta(i) > 0.0_wp .and. self%side(i) == 0)
            if (self%drop(i)) cycle
            nfree = nfree + 1
            self%rhs(i) = -self%b(i) - slide_change(cs, self%tng, i, nnode, minv, self%ft)
            if (present(rb)) self%rhs(i) = self%rhs(i) - rb%slide_part(i)
         end do
         do i = 1, m
            if (self%drop(i)) self%rhs(i) = 0.0_wp
         end do
         self%sol(1:m) = 0.0_wp
         if (nfree > 0) then
            call self%tt%factor_solve(m, self%drop, self%rhs, self%sol, nbad, err)
            if (allocated(err)) return
         end if
         do i = 1, m
            if (self%beta(i) > 0.0_wp .and. self%side(i) /= 0) then
               cs%q(i) = self%qb(i)
            else if (self%drop(i)) then
               cs%q(i) = 0.0_wp
            else
               cs%q(i) = self%sol(i)
            end if
         end do
         ! the slips of every candidate with a bound: ds/c = b + S_TT q
         call apply_tangent(cs, self%tng, cs%q, nnode, self%ft)
         if (present(rb)) call rb%accelerations_nt(m, self%zero(1:m), cs%q(1:m))
         ninf = 0
         last = 0
         do i = 1, m
            self%infeasible(i) = .false.
            if (.not. self%beta(i) > 0.0_wp) cycle
            if (self%side(i) == 0) then
               self%infeasible(i) = abs(cs%q(i)) > self%beta(i)
            else
               ds = self%b(i) + slide_change(cs, self%tng, i, nnode, minv, self%ft)
               if (present(rb)) ds = ds + rb%slide_part(i)
               ds = c*ds
               ! at +beta the slave must slide along -t (ds <= 0), at -beta along +t
               self%infeasible(i) = real(self%side(i), wp)*ds > tol
            end if
            if (self%infeasible(i)) then
               ninf = ninf + 1
               last = i
            end if
         end do
         if (ninf == 0) exit
         if (pass >= self%max_passes) then
            ! give up: keep the last multipliers within their bounds (the friction law's bound
            ! holds; the stick condition of some candidates may not)
            self%pass_limit_hits = self%pass_limit_hits + 1
            cs%q(1:m) = max(-self%beta(1:m), min(self%beta(1:m), cs%q(1:m)))
            exit
         end if
         if (rule%block_pass(ninf)) then
            do i = 1, m
               if (self%infeasible(i)) call switch(i)
            end do
         else
            call switch(last)
         end if
      end do
   contains
      !> A free candidate beyond its bound goes to it; a bounded one sliding the wrong way is freed.
      subroutine switch(i)
         integer, intent(in) :: i
         if (self%side(i) == 0) then
            self%side(i) = int(sign(1.0_wp, cs%q(i)))
         else
            self%side(i) = 0
         end if
      end subroutine switch
   end subroutine tangential

   !> Mirrored pairs (doc/friction.md, section 4.1, eq. F20): candidates i < j with friction
   !> (mu > 0) that join two nodes a and b, the slave b of i on a segment of a at weight at least
   !> 1 - MIRROR_TOL on a, the slave a of j on a segment of b at weight at least 1 - MIRROR_TOL
   !> on b, with normals that face each other (n_i . n_j < 0), as AUTOmatic's two passes find
   !> where the nodes of two bodies meet node on node. They are one contact point, whose two
   !> candidates would make the sweeps drift (eq. F19): the one with the smaller predicted gap
   !> enters the step, the other is skipped (self%skip; p = q = 0); self%partner links them.
   subroutine merge_mirrors(self, cs, m)
      type(friction_t), intent(inout) :: self
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: m
      integer :: i, j, a, b, ka

      self%skip(1:m) = .false.
      self%swapped(1:m) = .false.
      self%partner(1:m) = 0
      if (self%ogen == huge(self%ogen)) then
         self%ostamp = 0
         self%ogen = 0
      end if
      self%ogen = self%ogen + 1
      do i = 1, m
         if (near_node(i) == 0) cycle
         a = cs%node(1, i)
         if (self%ostamp(a) == self%ogen) cycle
         self%ostamp(a) = self%ogen
         self%owner(a) = i
      end do
      do j = 1, m
         ka = near_node(j)
         if (ka == 0) cycle
         b = cs%node(ka, j)
         a = cs%node(1, j)
         if (self%ostamp(b) /= self%ogen) cycle
         i = self%owner(b)
         if (i >= j .or. self%skip(i)) cycle
         ka = near_node(i)
         if (cs%node(ka, i) /= a) cycle
         if (.not. dot_product(cs%nrm(:, i), cs%nrm(:, j)) < 0.0_wp) cycle
         ! the pair is one contact point: the candidate whose predicted gap is the smaller (the
         ! constraint that binds) stays, the other leaves the step (F20)
         if (cs%gap(j) < cs%gap(i)) then
            self%skip(i) = .true.
         else
            self%skip(j) = .true.
         end if
         self%partner(i) = j
         self%partner(j) = i
         self%nmirrors = self%nmirrors + 1
      end do
   contains
      !> The index (2 or 3) in candidate k of the master node its slave landed next to, at weight
      !> at least 1 - MIRROR_TOL, when k has friction; else 0.
      integer function near_node(k)
         integer, intent(in) :: k
         near_node = 0
         if (.not. cs%mu(k) > 0.0_wp) return
         if (cs%w(2, k) <= -(1.0_wp - MIRROR_TOL)) near_node = 2
         if (cs%w(3, k) <= -(1.0_wp - MIRROR_TOL)) near_node = 3
      end function near_node
   end subroutine merge_mirrors

   !> After the sweeps converged: the corrected gap of every skipped mirrored candidate j,
   !> g~_j + c [G_N^T M^-1 (G_N p + G_T q)]_j (F7); where it is violated (below -gap_tol) and
   !> the pair has not swapped yet in this step, j takes its partner's place in the step's
   !> problem (the partner is skipped, p and q of both restart from 0). True when a pair
   !> swapped: the sweeps go on. Each pair swaps at most once a step, so this ends.
   logical function swap_mirrors(self, cs, corr, m, nnode, minv, c, rb) result(any_swap)
      type(friction_t), intent(inout) :: self
      type(constraints_t), intent(inout) :: cs
      type(corrector_t), intent(in) :: corr
      integer, intent(in) :: m, nnode
      real(wp), intent(in) :: minv(2, nnode), c
      type(rigid_dofs_t), intent(inout), optional :: rb
      integer :: j, i
      real(wp) :: g
      any_swap = .false.
      if (.not. any(self%skip(1:m))) return
      call apply_tangent(cs, self%tng, cs%q, nnode, self%ft)
      if (present(rb)) call rb%accelerations_nt(m, cs%p(1:m), cs%q(1:m))
      do j = 1, m
         if (.not. self%skip(j)) cycle
         i = self%partner(j)
         if (i == 0) cycle
         if (self%swapped(j)) cycle
         g = gap_change(cs, j, nnode, minv, corr%fwork) + gap_change(cs, j, nnode, minv, self%ft)
         if (present(rb)) g = g + rb%gap_part(j)
         if (.not. cs%gap(j) + c*g < -corr%gap_tol) cycle
         self%skip(j) = .false.
         self%skip(i) = .true.
         self%swapped(i) = .true.
         self%swapped(j) = .true.
         cs%p(i) = 0.0_wp
         cs%q(i) = 0.0_wp
         cs%active(i) = .false.
         cs%active(j) = .true.
         self%nswaps = self%nswaps + 1
         any_swap = .true.
      end do
   end function swap_mirrors

   !> f = G_T q: the nodal forces of the tangential multipliers q(m) (tng(2, m) the tangents).
   !> Only the candidates' nodes are set: f must be zero at every other node on entry (it is
   !> zeroed once per step), so that a pivoting pass costs the candidates, not the mesh.
   subroutine apply_tangent(cs, tng, q, nnode, f)
      type(constraints_t), intent(in) :: cs
      real(wp), intent(in) :: tng(:, :), q(:)
      integer, intent(in) :: nnode
      real(wp), intent(inout) :: f(2, nnode)
      integer :: i, k
      do i = 1, cs%n
         do k = 1, 3
            f(:, cs%node(k, i)) = 0.0_wp
         end do
      end do
      do i = 1, cs%n
         if (q(i) == 0.0_wp) cycle
         do k = 1, 3
            if (cs%w(k, i) == 0.0_wp) cycle
            f(:, cs%node(k, i)) = f(:, cs%node(k, i)) + q(i)*cs%w(k, i)*tng(:, i)
         end do
      end do
   end subroutine apply_tangent

   !> G_T,i^T M^-1 f for candidate i: the change of its slip per unit c.
   pure real(wp) function slide_change(cs, tng, i, nnode, minv, f) result(ds)
      type(constraints_t), intent(in) :: cs
      real(wp), intent(in) :: tng(:, :)
      integer, intent(in) :: i, nnode
      real(wp), intent(in) :: minv(2, nnode), f(2, nnode)
      integer :: k, nd
      ds = 0.0_wp
      do k = 1, 3
         if (cs%w(k, i) == 0.0_wp) cycle
         nd = cs%node(k, i)
         ds = ds + cs%w(k, i)*(tng(1, i)*minv(1, nd)*f(1, nd) + tng(2, i)*minv(2, nd)*f(2, nd))
      end do
   end function slide_change

end module exic_contact_friction
