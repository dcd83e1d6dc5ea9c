!> The implicit contact corrector of the seed's sections 3-4 (eq. 3.19, 4.2-4.7).
!>
!> Every candidate constraint i joins a slave node s and a point (1 - alpha) m1 + alpha m2 of a
!> master segment, with a unit normal n frozen over the step (seed section 4). Its column of G
!> holds w_k n at the dofs of its nodes k = (s, m1, m2) with weights w = (1, -(1-alpha), -alpha),
!> so that the gap of eq. 3.19 is g_i = G_i^T x. With x(n+2) = x* + c a(n+1), where
!> c = dt(n+1) (dt(n) + dt(n+1)) / 2 and x* = x(n+1) + dt(n+1) (v(n) + dt(n)/2 a(n)) (eq. 4.7),
!> the correction a(n+1) = a~(n+1) + M^-1 G p changes the predicted gap g~ by c S p with
!> S = G^T M^-1 G, so closing the gaps at t(n+2) means
!>
!>     S p = -g~ / c,        p >= 0 (compressive),                        (eq. 4.5-4.7)
!>
!> p = -lambda in the seed's sign convention (its lambda is negative in compression).
!> The active set starts from the violated predicted gaps and is settled by block principal
!> pivoting (see corrector_solve): tensile multipliers leave it and candidates whose corrected
!> gap is still violated join it, for at most `max_passes` passes. S is assembled once per step
!> over every candidate; a pass only drops the constraints outside its active set. Redundant
!> constraints (dependent columns of G) are removed by the factorization and carry p = 0. The
!> assembly and the dense (LAPACK) or sparse (SuiteSparse LDL', AMD) factorisation are
!> `system_t`'s (src/exic/contact/system.f90), which this type extends.
!>
!> With friction (doc/friction.md) the step's frictional problem (src/exic/contact/friction.f90)
!> calls the same normal problem (`prepare`, then `pivot` with the gaps shifted by the
!> tangential forces) in turn with a tangential one; without friction `solve` does all of it
!> and nothing else.
!>
!> Free rigid bodies (doc/loads.md, section 5) join as three-dof bodies when the caller passes
!> their `rigid_dofs_t`: S gains g_i^b . M_b^-1 g_j^b for every body two constraints touch, and
!> the corrected gaps of a pass count the bodies' accelerations. The caller applies the bodies'
!> share of G p (the nodal contact forces on their nodes) to the bodies.
!>
!> Massless contact faces (`LAGRange,ENERgy`, doc/impact.md) join through their compliance
!> `face`: their dofs have minv = 0, S gains (1/c) G_F^T K_FF^-1 G_F (eq. I.6, in system_t's
!> assembly), the corrected gaps count the face's motion and the face's accelerations follow
!> eq. I.7. They join the normal problem only (a model with friction has no massless faces).
module exic_contact_corrector
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_grow, only: grow
   use exic_contact_pivot_rule, only: pivot_rule_t
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_system, only: system_t
   use exic_contact_massless_face, only: massless_face_t
   implicit none
   private

   public :: constraints_t, corrector_t, apply, gap_change

   !> Candidate constraints of one step, in a deterministic order.
   type :: constraints_t
      integer :: n = 0
      integer, allocatable :: node(:, :)     !< (3, n) slave, master 1, master 2
      real(wp), allocatable :: w(:, :)       !< (3, n) 1, -(1 - alpha), -alpha
      real(wp), allocatable :: nrm(:, :)     !< (2, n) frozen unit normal (master outward)
      real(wp), allocatable :: gap(:)        !< (n) predicted gap at t(n+2)
      real(wp), allocatable :: gap_now(:)    !< (n) gap at t(n+1) with the same normal
      integer, allocatable :: pair(:)        !< (n) pair index
      real(wp), allocatable :: p(:)          !< (n) multiplier, >= 0 in compression
      logical, allocatable :: active(:)      !< (n) carries force after the corrector
      ! friction (doc/friction.md): kept only when `friction` (set before the candidates are
      ! added), so that frictionless steps do no work for them
      logical :: friction = .false.
      real(wp), allocatable :: mu(:)         !< (n) friction coefficient of the step (eq. F12)
      real(wp), allocatable :: q(:)          !< (n) tangential multiplier: force on the slave along t = e3 x n
      real(wp), allocatable :: slip(:)       !< (n) relative tangential increment of the step ds (eq. F6)
      integer, allocatable :: state(:)       !< (n) 0 no friction force, 1 stick, 2 slip (after the corrector)
   contains
      procedure :: reserve => constraints_reserve
      procedure :: add => constraints_add
   end type constraints_t

   !> Solver state kept across steps (the factorisation objects of system_t, work arrays).
   type, extends(system_t) :: corrector_t
      integer :: max_passes = 30             !< active-set passes before giving up on the step
      real(wp) :: gap_tol = 0.0_wp           !< corrected gaps above -gap_tol count as closed
      ! statistics
      integer :: passes = 0                  !< passes of the last call
      integer :: nredundant = 0              !< constraints removed as redundant in the last call
      integer :: pass_limit_hits = 0         !< calls that ended at max_passes
      ! work arrays (grown, never shrunk); m is the number of candidates of the step
      real(wp), allocatable :: rhs(:), sol(:)       !< (m) -g~/c and the multipliers of a pass
      real(wp), allocatable :: fwork(:, :)          !< (2, nnode) G p of the current pass
      logical, allocatable :: drop(:)               !< (m) left out of the pass's factorization
      logical, allocatable :: infeasible(:)         !< (m) candidates that switch sides
      real(wp), allocatable :: psafe(:)             !< (m) last pass's multipliers with none tensile
      ! node -> candidates incidence (CSR) over the nodes the candidates touch, numbered 1 ...
      ! nloc in the order the candidates first touch them (`build_incidence`)
      integer :: nloc = 0                           !< nodes the candidates touch
      integer, allocatable :: lnode(:, :)           !< (3, m) local number of each candidate node (0: weight 0)
      integer, allocatable :: nstart(:), nlist(:)   !< (nloc + 1), (3 m) candidates of each local node
      real(wp), allocatable :: nweight(:)           !< weight of the node in each candidate of nlist
      integer, allocatable :: lid(:), stamp(:)      !< (nnode) local number of a node, the call that gave it
      integer :: gen = 0                            !< calls of build_incidence (the stamp of this one)
   contains
      procedure :: solve => corrector_solve
      procedure :: prepare => corrector_prepare
      procedure :: pivot => corrector_pivot
   end type corrector_t

contains

   !> Make room for `m` candidates and reset the count.
   subroutine constraints_reserve(self, m)
      class(constraints_t), intent(inout) :: self
      integer, intent(in) :: m
      self%n = 0
      call grow_all(self, m)
   end subroutine constraints_reserve

   !> Candidates every array of `cs` can hold (those of friction only when `friction`).
   pure integer function capacity(cs) result(m)
      type(constraints_t), intent(in) :: cs
      m = 0
      if (.not. allocated(cs%gap)) return
      m = size(cs%gap)
      if (.not. cs%friction) return
      m = 0
      if (allocated(cs%mu)) m = min(size(cs%gap), size(cs%mu))
   end function capacity

   !> Every array of `cs` holds at least m candidates, keeping its contents.
   subroutine grow_all(cs, m)
      type(constraints_t), intent(inout) :: cs
      integer, intent(in) :: m
      call grow(cs%node, m, 3)
      call grow(cs%w, m, 3)
      call grow(cs%nrm, m, 2)
      call grow(cs%gap, m)
      call grow(cs%gap_now, m)
      call grow(cs%pair, m)
      call grow(cs%p, m)
      call grow(cs%active, m)
      if (.not. cs%friction) return
      call grow(cs%mu, m)
      call grow(cs%q, m)
      call grow(cs%slip, m)
      call grow(cs%state, m)
   end subroutine grow_all

   !> Append one candidate (the arrays grow, keeping their contents, when full); `mu` its
   !> friction coefficient for the step (0 when absent; kept only when self%friction).
   subroutine constraints_add(self, s, m1, m2, alpha, nrm, gap, gap_now, pair, mu)
      class(constraints_t), intent(inout) :: self
      integer, intent(in) :: s, m1, m2, pair
      real(wp), intent(in) :: alpha, nrm(2), gap, gap_now
      real(wp), intent(in), optional :: mu
      integer :: k
      k = self%n + 1
      if (k > capacity(self)) call grow_all(self, max(k, 64))
      self%n = k
      self%node(1, k) = s
      self%node(2, k) = m1
      self%node(3, k) = m2
      self%w(1, k) = 1.0_wp
      self%w(2, k) = -(1.0_wp - alpha)
      self%w(3, k) = -alpha
      self%nrm(1, k) = nrm(1)
      self%nrm(2, k) = nrm(2)
      self%gap(k) = gap
      self%gap_now(k) = gap_now
      self%pair(k) = pair
      self%p(k) = 0.0_wp
      self%active(k) = .false.
      if (.not. self%friction) return
      self%mu(k) = 0.0_wp
      if (present(mu)) self%mu(k) = mu
      self%q(k) = 0.0_wp
      self%slip(k) = 0.0_wp
      self%state(k) = 0
   end subroutine constraints_add

   !> Solve for the multipliers of `cs`, add the correction M^-1 G p to `a` and G p to `fcon`.
   !> minv(2, nnode) is the inverse lumped mass per dof (0 on rigid, fixed and inactive dofs).
   !>
   !> The multipliers solve the complementarity problem p >= 0, g >= 0, p g = 0 for the
   !> corrected gaps g = g~ + c S p, by block principal pivoting (Judice and Pires): solve
   !> S p = -g~/c on the active set F; the infeasible candidates are those of F with p < 0 and
   !> those outside F with g < -gap_tol; all of them switch sides while their number falls (or
   !> for three more passes), then only the last one in candidate order (Murty's rule, finite
   !> for the positive definite S of independent constraints). Constraints the factorization
   !> finds redundant carry p = 0 and are never infeasible.
   !> `rb`: the free rigid bodies (their nodes have minv = 0), when the model has any;
   !> `face`: the massless contact faces (their nodes have minv = 0), when any pair asks for them.
   subroutine corrector_solve(self, cs, nnode, minv, c, a, fcon, err, rb, face)
      class(corrector_t), intent(inout) :: self
      type(constraints_t), intent(inout) :: cs
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode)
      real(wp), intent(in) :: c
      real(wp), intent(inout) :: a(2, nnode)
      real(wp), intent(inout) :: fcon(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      type(rigid_dofs_t), intent(inout), optional :: rb
      type(massless_face_t), intent(inout), optional :: face
      integer :: m

      m = cs%n
      self%passes = 0
      self%nredundant = 0
      if (m == 0) return
      cs%p(1:m) = 0.0_wp
      cs%active(1:m) = cs%gap(1:m) < 0.0_wp
      if (.not. any(cs%active(1:m))) return
      if (present(face)) then
         ! z_j = K_FF^-1 G_F,j of the candidates on the face (eq. I.6)
         call face%prepare(m, cs%node(:, 1:m), cs%w(:, 1:m), cs%nrm(:, 1:m), err)
         if (allocated(err)) return
      end if
      call self%prepare(cs, nnode, minv, rb, face)
      call self%pivot(cs, nnode, minv, c, cs%gap(1:m), err, rb, face)
      if (allocated(err)) return
      ! a(n+1) = a~(n+1) + M^-1 G p  (eq. 4.5 with p = -lambda)
      a = a + minv*self%fwork
      ! the face: a_F += K_FF^-1 G_F p / c (eq. I.7)
      if (present(face)) call face%accelerate(nnode, a)
      fcon = fcon + self%fwork
   end subroutine corrector_solve

   !> What every pass of a step shares: the node -> candidates incidence, the work arrays, the
   !> free bodies' columns and S = G_N^T M^-1 G_N over every candidate, assembled once: the
   !> pivoting passes only change which constraints are dropped, so the pattern (and the sparse
   !> symbolic analysis) stays the same within the step, and across steps while the candidates do.
   !> `face`: the massless faces, already prepared for these candidates (face%prepare).
   subroutine corrector_prepare(self, cs, nnode, minv, rb, face)
      class(corrector_t), intent(inout) :: self
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode)
      type(rigid_dofs_t), intent(inout), optional :: rb
      type(massless_face_t), intent(in), optional :: face
      integer :: m
      m = cs%n
      call grow(self%infeasible, m)
      call build_incidence(self, cs, nnode)
      if (allocated(self%fwork)) then
         if (size(self%fwork, 2) /= nnode) deallocate (self%fwork)
      end if
      if (.not. allocated(self%fwork)) allocate (self%fwork(2, nnode))
      call grow(self%drop, m)
      call grow(self%rhs, m)
      call grow(self%sol, m)
      call grow(self%psafe, m)
      if (present(rb)) call rb%prepare(m, cs%node(:, 1:m), cs%w(:, 1:m), cs%nrm(:, 1:m))
      call self%assemble(m, cs%node(:, 1:m), self%lnode(:, 1:m), cs%w(:, 1:m), cs%nrm(:, 1:m), &
                         nnode, minv, self%nloc, self%nstart, self%nlist, self%nweight, rb, face=face)
   end subroutine corrector_prepare

   !> The normal problem of `prepare`d candidates for the predicted gaps gap0(m) (cs%gap, or
   !> with friction the gaps shifted by the tangential forces, doc/friction.md eq. F13), from
   !> the active set cs%active: on return cs%p holds the multipliers, cs%active the candidates
   !> in force and self%fwork = G_N p (see corrector_solve for the pivoting rule); with massless
   !> faces `face` (prepared), face%dx = K_FF^-1 G_F p of the multipliers returned.
   !> `skip`: candidates left out of the problem (never active, never infeasible; p = 0), the
   !> mirrored candidates of the frictional problem (doc/friction.md, section 4.1).
   subroutine corrector_pivot(self, cs, nnode, minv, c, gap0, err, rb, face, skip)
      class(corrector_t), intent(inout) :: self
      type(constraints_t), intent(inout) :: cs
      integer, intent(in) :: nnode
      real(wp), intent(in) :: minv(2, nnode)
      real(wp), intent(in) :: c
      real(wp), intent(in) :: gap0(:)
      type(error_t), allocatable, intent(out) :: err
      type(rigid_dofs_t), intent(inout), optional :: rb
      type(massless_face_t), intent(inout), optional :: face
      logical, intent(in), optional :: skip(:)
      integer :: m, nact, pass, k, i, nbad, ninf, last
      type(pivot_rule_t) :: rule
      real(wp) :: g
      logical :: have_safe

      m = cs%n
      self%rhs(1:m) = -gap0(1:m)/c
      pass = 0
      have_safe = .false.
      do
         pass = pass + 1
         ! the active set F: every other candidate is dropped from the factorization
         nact = count(cs%active(1:m))
         self%drop(1:m) = .not. cs%active(1:m)
         nbad = 0
         if (nact > 0) then
            call self%factor_solve(m, self%drop, self%rhs, self%sol, nbad, err)
            if (allocated(err)) return
         else
            self%sol(1:m) = 0.0_wp
         end if
         self%nredundant = nbad
         ! multipliers on F (redundant ones 0) and the corrected gaps of every candidate
         cs%p(1:m) = 0.0_wp
         do k = 1, m
            if (.not. self%drop(k)) cs%p(k) = self%sol(k)
         end do
         if (all(cs%p(1:m) >= 0.0_wp)) then
            self%psafe(1:m) = cs%p(1:m)
            have_safe = .true.
         end if
         call apply(cs, nnode, self%fwork)
         if (present(rb)) call rb%accelerations(m, cs%p(1:m))
         if (present(face)) call face%respond(m, cs%p(1:m))
         ninf = 0
         last = 0
         do i = 1, m
            if (cs%active(i)) then
               self%infeasible(i) = cs%p(i) < 0.0_wp
            else if (present(skip)) then
               self%infeasible(i) = .false.
               if (.not. skip(i)) then
                  g = gap_change(cs, i, nnode, minv, self%fwork)
                  if (present(rb)) g = g + rb%gap_part(i)
                  self%infeasible(i) = gap0(i) + c*g < -self%gap_tol
               end if
            else if (present(face)) then
               ! the face's motion K_FF^-1 G_F p counts in the corrected gap (eq. I.6)
               g = gap_change(cs, i, nnode, minv, self%fwork)
               if (present(rb)) g = g + rb%gap_part(i)
               g = gap0(i) + c*(g + face%gap_part(cs%node(:, i), cs%w(:, i), cs%nrm(:, i)))
               self%infeasible(i) = g < -self%gap_tol
            else if (present(rb)) then
               g = gap0(i) + c*(gap_change(cs, i, nnode, minv, self%fwork) + rb%gap_part(i))
               self%infeasible(i) = g < -self%gap_tol
            else
               g = gap0(i) + c*gap_change(cs, i, nnode, minv, self%fwork)
               self%infeasible(i) = g < -self%gap_tol
            end if
            if (self%infeasible(i)) then
               ninf = ninf + 1
               last = i
            end if
         end do
         if (ninf == 0) exit
         if (pass >= self%max_passes) then
            ! give up on the step: keep the last pass whose multipliers were all compressive (its
            ! gaps may stay open and are closed by the next step's corrector), or no contact force
            ! at all; never a tensile multiplier, which would pull bodies together and feed them
            ! energy
            self%pass_limit_hits = self%pass_limit_hits + 1
            if (have_safe) then
               cs%p(1:m) = self%psafe(1:m)
            else
               cs%p(1:m) = 0.0_wp
            end if
            call apply(cs, nnode, self%fwork)
            if (present(face)) call face%respond(m, cs%p(1:m))
            exit
         end if
         if (rule%block_pass(ninf)) then
            where (self%infeasible(1:m)) cs%active(1:m) = .not. cs%active(1:m)
         else
            cs%active(last) = .not. cs%active(last)
         end if
      end do
      self%passes = pass
      do i = 1, m
         cs%active(i) = cs%p(i) > 0.0_wp
      end do
   end subroutine corrector_pivot

   !> fcon = G_N p: the nodal contact forces of the normal multipliers.
   subroutine apply(cs, nnode, fcon)
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: nnode
      real(wp), intent(out) :: fcon(2, nnode)
      integer :: i, k
      fcon = 0.0_wp
      do i = 1, cs%n
         if (cs%p(i) == 0.0_wp) cycle
         do k = 1, 3
            if (cs%w(k, i) == 0.0_wp) cycle
            fcon(:, cs%node(k, i)) = fcon(:, cs%node(k, i)) + cs%p(i)*cs%w(k, i)*cs%nrm(:, i)
         end do
      end do
   end subroutine apply

   !> G_i^T M^-1 f for candidate i: the change of its gap per unit c.
   pure real(wp) function gap_change(cs, i, nnode, minv, f) result(dg)
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: i, nnode
      real(wp), intent(in) :: minv(2, nnode), f(2, nnode)
      integer :: k, nd
      dg = 0.0_wp
      do k = 1, 3
         if (cs%w(k, i) == 0.0_wp) cycle
         nd = cs%node(k, i)
         dg = dg + cs%w(k, i)*(cs%nrm(1, i)*minv(1, nd)*f(1, nd) + cs%nrm(2, i)*minv(2, nd)*f(2, nd))
      end do
   end function gap_change

   !> Node -> candidates incidence in compressed rows (nstart, nlist), with the node's weight in
   !> each candidate (nweight: the sum of its weights w over the node's occurrences), over the
   !> nloc nodes the candidates touch with a nonzero weight, numbered in the order they are first
   !> touched (lnode); each node lists its candidates in candidate order. Nothing is done per node
   !> of the mesh: a node's local number is valid while its stamp is this call's.
   subroutine build_incidence(self, cs, nnode)
      type(corrector_t), intent(inout) :: self
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: nnode
      integer :: i, k, nd, kk, ln, nloc
      real(wp) :: wsum
      if (allocated(self%stamp)) then
         if (size(self%stamp) /= nnode) deallocate (self%stamp, self%lid)
      end if
      if (.not. allocated(self%stamp)) then
         allocate (self%stamp(nnode), self%lid(nnode))
         self%stamp = 0
         self%gen = 0
      end if
      if (self%gen == huge(self%gen)) then
         self%stamp = 0
         self%gen = 0
      end if
      self%gen = self%gen + 1
      call grow(self%lnode, cs%n, 3)
      call grow(self%nstart, 3*cs%n + 1)
      call grow(self%nlist, 3*cs%n)
      call grow(self%nweight, 3*cs%n)
      ! local numbers; nstart(ln + 1) counts the candidates of local node ln
      nloc = 0
      do i = 1, cs%n
         do k = 1, 3
            self%lnode(k, i) = 0
            if (cs%w(k, i) == 0.0_wp) cycle
            nd = cs%node(k, i)
            if (self%stamp(nd) /= self%gen) then
               self%stamp(nd) = self%gen
               nloc = nloc + 1
               self%lid(nd) = nloc
               self%nstart(nloc + 1) = 0
            end if
            ln = self%lid(nd)
            self%lnode(k, i) = ln
            self%nstart(ln + 1) = self%nstart(ln + 1) + 1
         end do
      end do
      self%nloc = nloc
      self%nstart(1) = 1
      do ln = 1, nloc
         self%nstart(ln + 1) = self%nstart(ln + 1) + self%nstart(ln)
      end do
      ! fill, using nstart as a running pointer, then shift back
      do i = 1, cs%n
         do k = 1, 3
            ln = self%lnode(k, i)
            if (ln == 0) cycle
            nd = cs%node(k, i)
            self%nlist(self%nstart(ln)) = i
            wsum = 0.0_wp
            do kk = 1, 3
               if (cs%node(kk, i) == nd) wsum = wsum + cs%w(kk, i)
            end do
            self%nweight(self%nstart(ln)) = wsum
            self%nstart(ln) = self%nstart(ln) + 1
         end do
      end do
      do ln = nloc, 1, -1
         self%nstart(ln + 1) = self%nstart(ln)
      end do
      self%nstart(1) = 1
   end subroutine build_incidence

end module exic_contact_corrector
