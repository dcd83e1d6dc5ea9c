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
!> constraints (dependent columns of G) are removed by the factorization (see
!> exic_linalg_sparse_ldl) and carry p = 0. Steps with up to `dense_limit` candidates factorize S
!> densely (LAPACK), steps with more use SuiteSparse LDL' with AMD ordering, whose symbolic
!> analysis is reused while the candidates' pattern is unchanged (across the passes of a step,
!> and across steps).
!>
!> Free rigid bodies (doc/loads.md, section 5) join as three-dof bodies when the caller passes
!> their `rigid_dofs_t`: S gains g_i^b . M_b^-1 g_j^b for every body two constraints touch, and
!> the corrected gaps of a pass count the bodies' accelerations. The caller applies the bodies'
!> share of G p (the nodal contact forces on their nodes) to the bodies.
!>
!> Massless contact faces (`LAGRange,ENERgy`, doc/impact.md) join through their compliance
!> `face`: their dofs have minv = 0, S gains (1/c) G_F^T K_FF^-1 G_F (eq. I.6), the corrected gaps
!> count the face's motion and the face's accelerations follow eq. I.7.
module exic_contact_corrector
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow
   use exic_linalg_sparse_ldl, only: sparse_ldl_t
   use exic_linalg_dense_spd, only: dense_spd_t
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_massless_face, only: massless_face_t
   implicit none
   private

   public :: constraints_t, corrector_t

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
   contains
      procedure :: reserve => constraints_reserve
      procedure :: add => constraints_add
   end type constraints_t

   !> Solver state kept across steps (factorization objects, work arrays).
   type :: corrector_t
      integer :: dense_limit = 30            !< steps with up to this many candidates factorize S densely (measured crossover)
      integer :: max_passes = 30             !< active-set passes before giving up on the step
      real(wp) :: gap_tol = 0.0_wp           !< corrected gaps above -gap_tol count as closed
      type(sparse_ldl_t) :: sparse
      type(dense_spd_t) :: dense
      ! statistics
      integer :: passes = 0                  !< passes of the last call
      integer :: nredundant = 0              !< constraints removed as redundant in the last call
      integer :: pass_limit_hits = 0         !< calls that ended at max_passes
      integer :: nsolves = 0, ndense = 0, nsparse = 0
      ! work arrays (grown, never shrunk); m is the number of candidates of the step
      integer, allocatable :: ap(:), ai(:)          !< S in compressed columns: (m + 1), (nnz)
      real(wp), allocatable :: ax(:)                !< (nnz) values of S in compressed columns
      real(wp), allocatable :: s(:, :)              !< (m, m) S for the dense path
      integer, allocatable :: mark(:)               !< (m) last column that touched a row (assembly)
      integer, allocatable :: bad(:)                !< (m) constraints the factorization finds redundant
      real(wp), allocatable :: rhs(:), sol(:)       !< (m) -g~/c and the multipliers of a pass
      real(wp), allocatable :: fwork(:, :)          !< (2, nnode) G p of the current pass
      logical, allocatable :: drop(:)               !< (m) left out of the pass's factorization
      logical, allocatable :: infeasible(:)         !< (m) candidates that switch sides
      real(wp), allocatable :: psafe(:)             !< (m) last pass's multipliers with none tensile
      integer, allocatable :: nstart(:), nlist(:)   !< node -> candidates incidence (CSR)
   contains
      procedure :: solve => corrector_solve
   end type corrector_t

contains

   !> Make room for `m` candidates and reset the count.
   subroutine constraints_reserve(self, m)
      class(constraints_t), intent(inout) :: self
      integer, intent(in) :: m
      self%n = 0
      call grow_all(self, m)
   end subroutine constraints_reserve

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
   end subroutine grow_all

   !> Append one candidate (the arrays grow, keeping their contents, when full).
   subroutine constraints_add(self, s, m1, m2, alpha, nrm, gap, gap_now, pair)
      class(constraints_t), intent(inout) :: self
      integer, intent(in) :: s, m1, m2, pair
      real(wp), intent(in) :: alpha, nrm(2), gap, gap_now
      integer :: k
      k = self%n + 1
      call grow_all(self, max(k, 64))
      self%n = k
      self%node(:, k) = [s, m1, m2]
      self%w(:, k) = [1.0_wp, -(1.0_wp - alpha), -alpha]
      self%nrm(:, k) = nrm
      self%gap(k) = gap
      self%gap_now(k) = gap_now
      self%pair(k) = pair
      self%p(k) = 0.0_wp
      self%active(k) = .false.
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
      integer :: m, nact, pass, k, i, nbad, ninf, best, budget, last
      real(wp) :: g
      logical :: have_safe

      m = cs%n
      self%passes = 0
      self%nredundant = 0
      if (m == 0) return
      cs%p(1:m) = 0.0_wp
      cs%active(1:m) = cs%gap(1:m) < 0.0_wp
      if (.not. any(cs%active(1:m))) return
      call grow(self%infeasible, m)
      call build_incidence(self, cs, nnode)
      if (allocated(self%fwork)) then
         if (size(self%fwork, 2) /= nnode) deallocate (self%fwork)
      end if
      if (.not. allocated(self%fwork)) allocate (self%fwork(2, nnode))

      ! S over every candidate, assembled once: the pivoting passes only change which
      ! constraints are dropped, so the pattern (and the sparse symbolic analysis) stays the same
      ! within the step, and across steps while the candidates do
      call grow(self%drop, m)
      call grow(self%rhs, m)
      call grow(self%sol, m)
      call grow(self%bad, m)
      self%rhs(1:m) = -cs%gap(1:m)/c
      if (present(rb)) call rb%prepare(m, cs%node(:, 1:m), cs%w(:, 1:m), cs%nrm(:, 1:m))
      if (present(face)) then
         call face%prepare(m, cs%node(:, 1:m), cs%w(:, 1:m), cs%nrm(:, 1:m), err)
         if (allocated(err)) return
      end if
      call assemble(self, cs, nnode, minv, m, rb, face)

      best = huge(1)
      budget = 3
      pass = 0
      have_safe = .false.
      call grow(self%psafe, m)
      do
         pass = pass + 1
         ! the active set F: every other candidate is dropped from the factorization
         nact = count(cs%active(1:m))
         self%drop(1:m) = .not. cs%active(1:m)
         nbad = 0
         if (nact > 0) then
            call factor_and_solve(self, m, nbad, err)
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
            else if (present(rb) .or. present(face)) then
               g = gap_change(cs, i, nnode, minv, self%fwork)
               if (present(rb)) g = g + rb%gap_part(i)
               if (present(face)) g = g + face%gap_part(cs%node(:, i), cs%w(:, i), cs%nrm(:, i))
               g = cs%gap(i) + c*g
               self%infeasible(i) = g < -self%gap_tol
            else
               g = cs%gap(i) + c*gap_change(cs, i, nnode, minv, self%fwork)
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
         if (ninf < best) then
            best = ninf
            budget = 3
         else
            budget = budget - 1
         end if
         if (budget >= 0) then
            where (self%infeasible(1:m)) cs%active(1:m) = .not. cs%active(1:m)
         else
            cs%active(last) = .not. cs%active(last)
         end if
      end do
      self%passes = pass
      do i = 1, m
         cs%active(i) = cs%p(i) > 0.0_wp
      end do
      ! a(n+1) = a~(n+1) + M^-1 G p  (eq. 4.5 with p = -lambda)
      a = a + minv*self%fwork
      if (present(face)) call face%accelerate(nnode, a)
      fcon = fcon + self%fwork
   end subroutine corrector_solve

   !> fcon = G p: the nodal contact forces.
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

   !> Node -> candidates incidence in compressed rows (nstart, nlist).
   subroutine build_incidence(self, cs, nnode)
      type(corrector_t), intent(inout) :: self
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: nnode
      integer :: i, k, nd
      call grow(self%nstart, nnode + 1)
      call grow(self%nlist, 3*cs%n)
      self%nstart(1:nnode + 1) = 0
      do i = 1, cs%n
         do k = 1, 3
            if (cs%w(k, i) == 0.0_wp) cycle
            nd = cs%node(k, i)
            self%nstart(nd + 1) = self%nstart(nd + 1) + 1
         end do
      end do
      self%nstart(1) = 1
      do nd = 1, nnode
         self%nstart(nd + 1) = self%nstart(nd + 1) + self%nstart(nd)
      end do
      ! fill, using nstart as a running pointer, then shift back
      do i = 1, cs%n
         do k = 1, 3
            if (cs%w(k, i) == 0.0_wp) cycle
            nd = cs%node(k, i)
            self%nlist(self%nstart(nd)) = i
            self%nstart(nd) = self%nstart(nd) + 1
         end do
      end do
      do nd = nnode, 1, -1
         self%nstart(nd + 1) = self%nstart(nd)
      end do
      self%nstart(1) = 1
   end subroutine build_incidence

   !> S = G^T M^-1 G over all m candidates: dense (m <= dense_limit) or in compressed columns
   !> with the full pattern (the pivoting passes drop constraints in the factorization). With
   !> free rigid bodies `rb`, each column gains the coupling of the bodies its candidate touches.
   subroutine assemble(self, cs, nnode, minv, m, rb, face)
      type(corrector_t), intent(inout) :: self
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: nnode, m
      real(wp), intent(in) :: minv(2, nnode)
      type(rigid_dofs_t), intent(in), optional :: rb
      type(massless_face_t), intent(in), optional :: face
      integer :: j, k, nd, q, i, nnz, first, l, qj, b, e
      real(wp) :: v

      if (m <= self%dense_limit) then
         if (allocated(self%s)) then
            if (size(self%s, 1) < m) deallocate (self%s)
         end if
         if (.not. allocated(self%s)) allocate (self%s(max(m, 16), max(m, 16)))
         self%s(1:m, 1:m) = 0.0_wp
      end if
      call grow(self%ap, m + 1)
      call grow(self%mark, m)
      self%mark(1:m) = 0
      nnz = 0
      self%ap(1) = 1
      do j = 1, m
         first = nnz + 1
         do k = 1, 3
            if (cs%w(k, j) == 0.0_wp) cycle
            nd = cs%node(k, j)
            ! every candidate i that shares node nd with candidate j: S(i, j) += w_kj w_i(nd) n_j M^-1 n_i
            do q = self%nstart(nd), self%nstart(nd + 1) - 1
               i = self%nlist(q)
               v = cs%w(k, j)*node_weight(cs, i, nd)* &
                   (cs%nrm(1, j)*minv(1, nd)*cs%nrm(1, i) + cs%nrm(2, j)*minv(2, nd)*cs%nrm(2, i))
               call add_entry(i, v)
            end do
         end do
         if (present(rb)) then
            ! every candidate i on a body b that candidate j touches: S(i, j) += g_i^b . M_b^-1 g_j^b
            do qj = 1, rb%nslot(j)
               b = rb%sbody(qj, j)
               do e = rb%bstart(b), rb%bstart(b + 1) - 1
                  i = rb%bcand(e)
                  v = dot_product(rb%sg(:, rb%bslot(e), i), rb%minv(:, b)*rb%sg(:, qj, j))
                  call add_entry(i, v)
               end do
            end do
         end if
         if (present(face)) then
            ! every candidate i on the face when j is: S(i, j) += (1/c) G_F,i^T K_FF^-1 G_F,j (eq. I.6)
            if (face%slot(j) > 0) then
               do i = 1, m
                  v = face%coupling(i, j, cs%node(:, i), cs%w(:, i), cs%nrm(:, i))
                  if (v /= 0.0_wp) call add_entry(i, v)
               end do
            end if
         end if
         if (m > self%dense_limit) call sort_column(self%ai(first:nnz), self%ax(first:nnz))
         self%ap(j + 1) = nnz + 1
      end do
   contains
      !> S(i, j) += v (dense), or into column j of the compressed columns.
      subroutine add_entry(i, v)
         integer, intent(in) :: i
         real(wp), intent(in) :: v
         if (m <= self%dense_limit) then
            self%s(i, j) = self%s(i, j) + v
         else
            if (self%mark(i) /= j) then
               self%mark(i) = j
               nnz = nnz + 1
               call grow(self%ai, nnz)
               call grow(self%ax, nnz)
               self%ai(nnz) = i
               self%ax(nnz) = v
            else
               do l = first, nnz
                  if (self%ai(l) == i) then
                     self%ax(l) = self%ax(l) + v
                     exit
                  end if
               end do
            end if
         end if
      end subroutine add_entry
   end subroutine assemble

   !> The weight of node `nd` in candidate `i` (sum over its occurrences).
   pure real(wp) function node_weight(cs, i, nd) result(w)
      type(constraints_t), intent(in) :: cs
      integer, intent(in) :: i, nd
      integer :: k
      w = 0.0_wp
      do k = 1, 3
         if (cs%node(k, i) == nd) w = w + cs%w(k, i)
      end do
   end function node_weight

   !> Insertion sort of one short column by row index.
   pure subroutine sort_column(ai, ax)
      integer, intent(inout) :: ai(:)
      real(wp), intent(inout) :: ax(:)
      integer :: i, j, ki
      real(wp) :: kx
      do i = 2, size(ai)
         ki = ai(i)
         kx = ax(i)
         j = i - 1
         do while (j >= 1)
            if (ai(j) <= ki) exit
            ai(j + 1) = ai(j)
            ax(j + 1) = ax(j)
            j = j - 1
         end do
         ai(j + 1) = ki
         ax(j + 1) = kx
      end do
   end subroutine sort_column

   !> Factorize the assembled S of the m candidates without the dropped ones and solve for sol.
   subroutine factor_and_solve(self, m, nbad, err)
      type(corrector_t), intent(inout) :: self
      integer, intent(in) :: m
      integer, intent(out) :: nbad
      type(error_t), allocatable, intent(out) :: err
      integer :: stat, k
      self%nsolves = self%nsolves + 1
      if (m <= self%dense_limit) then
         self%ndense = self%ndense + 1
         call self%dense%factorize(self%s(1:m, 1:m), nbad, self%bad, err, self%drop(1:m))
         if (allocated(err)) return
         call self%dense%solve(self%rhs(1:m), self%sol(1:m), stat)
      else
         self%nsparse = self%nsparse + 1
         call self%sparse%refactorize(m, self%ap(1:m + 1), self%ai(1:self%ap(m + 1) - 1), &
                                      self%ax(1:self%ap(m + 1) - 1), nbad, self%bad, err, &
                                      self%drop(1:m))
         if (allocated(err)) return
         call self%sparse%solve(self%rhs(1:m), self%sol(1:m), stat)
      end if
      if (stat /= 0) then
         call make_error(err, 'contact corrector: the solve of S p = -g/c failed')
         return
      end if
      do k = 1, nbad
         self%drop(self%bad(k)) = .true.
         self%sol(self%bad(k)) = 0.0_wp
      end do
   end subroutine factor_and_solve

end module exic_contact_corrector
