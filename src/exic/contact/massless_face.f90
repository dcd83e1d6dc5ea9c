!> Massless contact faces of `LAGRange,ENERgy` (doc/impact.md, section 3): the compliance of
!> the face dofs in the contact corrector.
!>
!> The face dofs carry no mass (their lumped mass is moved to the other nodes of their elements
!> by the caller, eq. I.3): both dofs of a face node, or the one along its normal (`free`, eq.
!> I.3a), whose other dof keeps its mass and is an interior dof here (an identity row of K_FF,
!> decoupled, right-hand side 0). Every step they are placed by the condensed static face
!> problem (eq. I.5) with the initial stiffness's face block K_FF, factorized once (SuiteSparse
!> LDL, `sparse_ldl_t`):
!>
!>     K_FF du_F = r_F(n+1) - K_FI du_I + G_F p.
!>
!> `trial` is the free solve (p = 0): it moves the face's predicted positions and sets the face
!> accelerations of eq. I.7. In the corrector a unit multiplier j moves the face by
!> z_j = K_FF^-1 G_F,j (`prepare`: one back-substitution per candidate that touches the face),
!> so S' gains (1/c) G_F,i^T z_j (eq. I.6); `respond` forms the face motion K_FF^-1 G_F p of a
!> pass, `gap_part` its share of a gap per unit c, `accelerate` adds it to a_F (eq. I.7).
module exic_contact_massless_face
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_base_grow, only: grow
   use exic_linalg_sparse_ldl, only: sparse_ldl_t
   implicit none
   private

   public :: massless_face_t

   type :: massless_face_t
      logical :: active = .false.
      integer :: nf = 0                          !< face nodes
      integer, allocatable :: node(:)            !< (nf) global node numbers
      integer, allocatable :: fidx(:)            !< (nnode) position in `node`, 0 off the face
      !> (2, nf) the dof is massless and placed by the face problem; a face node's other dof keeps
      !> its mass (doc/impact.md, section 3.1): its row of K_FF is the identity, decoupled
      logical, allocatable :: free(:, :)
      ! rows of K0 for the face dofs (2 nf rows, dof 2 (k-1) + d of face node k), CSR over the
      ! global dofs 2 (i-1) + d of node i
      integer, allocatable :: rp(:), ci(:)
      real(wp), allocatable :: val(:)
      type(sparse_ldl_t) :: ldl                  !< K_FF
      real(wp), allocatable :: rhs(:), du(:)     !< (2 nf) work: right-hand side, solution
      ! per step: candidates touching the face and their responses
      real(wp) :: c = 0.0_wp
      integer :: nfc = 0
      integer, allocatable :: slot(:)            !< (m) column of z for a candidate, 0 if none
      real(wp), allocatable :: z(:, :)           !< (2 nf, nfc) K_FF^-1 G_F,j
      real(wp), allocatable :: dx(:)             !< (2 nf) K_FF^-1 G_F p of the current pass
      integer :: nsolves = 0                     !< back-substitutions over the run
      ! the stiffness's refresh at large strain (doc/impact.md, section 3.2): displacements
      ! at which val was last formed, and the refreshes made
      real(wp), allocatable :: uref(:, :)        !< (2, nnode)
      integer :: nrefresh = 0
   contains
      procedure :: init => face_init
      procedure :: update => face_update
      procedure :: refactor => face_refactor
      procedure :: trial => face_trial
      procedure :: prepare => face_prepare
      procedure :: coupling => face_coupling
      procedure :: respond => face_respond
      procedure :: gap_part => face_gap_part
      procedure :: accelerate => face_accelerate
   end type massless_face_t

contains

   !> Face nodes node(nf) of a mesh of nnode nodes and the rows of K0 for their dofs (rp, ci, val:
   !> CSR, row 2 (k-1) + d for dof d of face node k, columns global dofs); factorizes K_FF.
   !> dofs(2, nf): the massless dofs of each face node (default: both).
   subroutine face_init(self, nnode, nf, node, rp, ci, val, err, dofs)
      class(massless_face_t), intent(inout) :: self
      integer, intent(in) :: nnode, nf
      integer, intent(in) :: node(nf), rp(:), ci(:)
      real(wp), intent(in) :: val(:)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: dofs(2, nf)
      integer :: k, nnz
      integer, allocatable :: ap(:), ai(:)
      real(wp), allocatable :: ax(:)

      self%active = nf > 0
      self%nf = nf
      self%node = node
      allocate (self%fidx(nnode), source=0)
      do k = 1, nf
         self%fidx(node(k)) = k
      end do
      self%rp = rp
      self%ci = ci
      self%val = val
      allocate (self%free(2, nf), source=.true.)
      if (present(dofs)) self%free = dofs
      allocate (self%uref(2, nnode), source=0.0_wp)
      if (nf == 0) return
      call face_block(self, ap, ai, ax, nnz)
      call self%ldl%analyze(2*nf, ap, ai(1:nnz), err)
      if (allocated(err)) return
      call factor(self, ax(1:nnz), err)
      if (allocated(err)) return
      allocate (self%rhs(2*nf), self%du(2*nf), self%dx(2*nf))
   end subroutine face_init

   !> New values val of the face rows (the same pattern rp, ci), formed at the displacements
   !> u(2, nnode); K_FF factorized again.
   subroutine face_update(self, val, u, err)
      class(massless_face_t), intent(inout) :: self
      real(wp), intent(in) :: val(:), u(:, :)
      type(error_t), allocatable, intent(out) :: err
      if (.not. self%active) return
      self%val = val
      self%uref = u
      self%nrefresh = self%nrefresh + 1
      call self%refactor(err)
   end subroutine face_update

   !> K_FF factorized again from the face rows val as they are (after a restart loaded them).
   subroutine face_refactor(self, err)
      class(massless_face_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: ap(:), ai(:)
      real(wp), allocatable :: ax(:)
      integer :: nnz
      if (.not. self%active) return
      call face_block(self, ap, ai, ax, nnz)
      call factor(self, ax(1:nnz), err)
   end subroutine face_refactor

   !> K_FF in compressed columns (symmetric: row r of the stiffness restricted to the face
   !> columns is column r).
   subroutine face_block(self, ap, ai, ax, nnz)
      type(massless_face_t), intent(in) :: self
      integer, allocatable, intent(out) :: ap(:), ai(:)
      real(wp), allocatable, intent(out) :: ax(:)
      integer, intent(out) :: nnz
      integer :: r, q, nd, d
      allocate (ap(2*self%nf + 1), ai(size(self%ci) + 2*self%nf), ax(size(self%ci) + 2*self%nf))
      nnz = 0
      ap(1) = 1
      do r = 1, 2*self%nf
         if (.not. self%free(2 - mod(r, 2), (r + 1)/2)) then
            ! a dof with mass: identity row, decoupled (its solution is 0)
            nnz = nnz + 1
            ai(nnz) = r
            ax(nnz) = 1.0_wp
            ap(r + 1) = nnz + 1
            cycle
         end if
         do q = self%rp(r), self%rp(r + 1) - 1
            nd = (self%ci(q) + 1)/2
            d = self%ci(q) - 2*(nd - 1)
            if (self%fidx(nd) == 0) cycle
            if (.not. self%free(d, self%fidx(nd))) cycle
            nnz = nnz + 1
            ai(nnz) = 2*(self%fidx(nd) - 1) + d
            ax(nnz) = self%val(q)
         end do
         ap(r + 1) = nnz + 1
      end do
   end subroutine face_block

   !> Numeric LDL of K_FF (values ax in the analyzed pattern); a zero pivot names its node.
   subroutine factor(self, ax, err)
      type(massless_face_t), intent(inout) :: self
      real(wp), intent(in) :: ax(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: nbad
      integer :: bad(2*self%nf)
      call self%ldl%factorize(ax, nbad, bad, err)
      if (allocated(err)) return
      if (nbad > 0) call make_error(err, 'LAGRange,ENERgy: the face block of the stiffness is singular at node '// &
                                    itoa(self%node((bad(1) + 1)/2))//' (a face node not tied to the interior of '// &
                                    'its body)')
   end subroutine factor

   !> The free solve (eq. I.5 with p = 0) and eq. I.7: fres = f_ext - f_int at t(n+1), x = x(n+1),
   !> xp = predicted x~(n+2) (x* on the face, whose a~ is 0); on exit the face's xp is its trial
   !> position and a its acceleration.
   subroutine face_trial(self, nnode, x, fres, c, xp, a, err)
      class(massless_face_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), fres(2, nnode), c
      real(wp), intent(inout) :: xp(2, nnode), a(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, d, r, q, nd, dd, stat
      real(wp) :: s
      if (.not. self%active) return
      self%c = c
      do k = 1, self%nf
         do d = 1, 2
            r = 2*(k - 1) + d
            self%rhs(r) = 0.0_wp
            if (.not. self%free(d, k)) cycle
            s = fres(d, self%node(k))
            do q = self%rp(r), self%rp(r + 1) - 1
               nd = (self%ci(q) + 1)/2
               dd = self%ci(q) - 2*(nd - 1)
               if (self%fidx(nd) /= 0) then
                  if (self%free(dd, self%fidx(nd))) cycle
               end if
               s = s - self%val(q)*(xp(dd, nd) - x(dd, nd))
            end do
            self%rhs(r) = s
         end do
      end do
      call self%ldl%solve(self%rhs, self%du, stat)
      self%nsolves = self%nsolves + 1
      if (stat /= 0) then
         call make_error(err, 'LAGRange,ENERgy: the free solve of the face failed')
         return
      end if
      do k = 1, self%nf
         nd = self%node(k)
         do d = 1, 2
            if (.not. self%free(d, k)) cycle
            s = x(d, nd) + self%du(2*(k - 1) + d)
            a(d, nd) = (s - xp(d, nd))/c
            xp(d, nd) = s
         end do
      end do
   end subroutine face_trial

   !> z_j = K_FF^-1 G_F,j for every candidate j (node(3, m), weights w(3, m), normals nrm(2, m))
   !> that has a face node.
   subroutine face_prepare(self, m, node, w, nrm, err)
      class(massless_face_t), intent(inout) :: self
      integer, intent(in) :: m, node(3, m)
      real(wp), intent(in) :: w(3, m), nrm(2, m)
      type(error_t), allocatable, intent(out) :: err
      integer :: j, k, f, stat
      call grow(self%slot, m)
      self%slot(1:m) = 0
      self%nfc = 0
      if (.not. self%active) return
      do j = 1, m
         if (.not. touches(self, node(:, j), w(:, j))) cycle
         self%nfc = self%nfc + 1
         self%slot(j) = self%nfc
      end do
      if (self%nfc == 0) return
      if (allocated(self%z)) then
         if (size(self%z, 2) < self%nfc) deallocate (self%z)
      end if
      if (.not. allocated(self%z)) allocate (self%z(2*self%nf, max(self%nfc, 8)))
      do j = 1, m
         if (self%slot(j) == 0) cycle
         self%rhs = 0.0_wp
         do k = 1, 3
            if (w(k, j) == 0.0_wp) cycle
            f = self%fidx(node(k, j))
            if (f == 0) cycle
            self%rhs(2*f - 1:2*f) = self%rhs(2*f - 1:2*f) + merge(w(k, j)*nrm(:, j), 0.0_wp, self%free(:, f))
         end do
         call self%ldl%solve(self%rhs, self%z(:, self%slot(j)), stat)
         self%nsolves = self%nsolves + 1
         if (stat /= 0) then
            call make_error(err, 'LAGRange,ENERgy: a back-substitution of the face failed')
            return
         end if
      end do
   end subroutine face_prepare

   !> Candidate j has a face node with a non-zero weight.
   pure logical function touches(self, node, w)
      type(massless_face_t), intent(in) :: self
      integer, intent(in) :: node(3)
      real(wp), intent(in) :: w(3)
      integer :: k
      touches = .false.
      do k = 1, 3
         if (w(k) /= 0.0_wp .and. self%fidx(node(k)) /= 0) touches = .true.
      end do
   end function touches

   !> G_F^T v for candidate i (node, w, nrm) and a face vector v(2 nf).
   pure real(wp) function face_dot(self, node, w, nrm, v) result(s)
      type(massless_face_t), intent(in) :: self
      integer, intent(in) :: node(3)
      real(wp), intent(in) :: w(3), nrm(2), v(:)
      integer :: k, f
      s = 0.0_wp
      do k = 1, 3
         if (w(k) == 0.0_wp) cycle
         f = self%fidx(node(k))
         if (f == 0) cycle
         ! v is 0 on the dofs with mass (identity rows of K_FF with a zero right-hand side)
         s = s + w(k)*(nrm(1)*v(2*f - 1) + nrm(2)*v(2*f))
      end do
   end function face_dot

   !> (1/c) G_F,i^T K_FF^-1 G_F,j: the face's entry of S' (eq. I.6); 0 unless both touch the face.
   pure real(wp) function face_coupling(self, i, j, node_i, w_i, nrm_i) result(v)
      class(massless_face_t), intent(in) :: self
      integer, intent(in) :: i, j, node_i(3)
      real(wp), intent(in) :: w_i(3), nrm_i(2)
      v = 0.0_wp
      if (.not. self%active) return
      if (self%slot(i) == 0 .or. self%slot(j) == 0) return
      v = face_dot(self, node_i, w_i, nrm_i, self%z(:, self%slot(j)))/self%c
   end function face_coupling

   !> dx = K_FF^-1 G_F p = sum_j z_j p_j for the multipliers p(m) of a pass.
   subroutine face_respond(self, m, p)
      class(massless_face_t), intent(inout) :: self
      integer, intent(in) :: m
      real(wp), intent(in) :: p(m)
      integer :: j
      if (.not. self%active) return
      self%dx = 0.0_wp
      do j = 1, m
         if (self%slot(j) == 0 .or. p(j) == 0.0_wp) cycle
         self%dx = self%dx + p(j)*self%z(:, self%slot(j))
      end do
   end subroutine face_respond

   !> The face's change of the gap of candidate i per unit c: G_F,i^T dx / c.
   pure real(wp) function face_gap_part(self, node_i, w_i, nrm_i) result(g)
      class(massless_face_t), intent(in) :: self
      integer, intent(in) :: node_i(3)
      real(wp), intent(in) :: w_i(3), nrm_i(2)
      g = 0.0_wp
      if (.not. self%active) return
      g = face_dot(self, node_i, w_i, nrm_i, self%dx)/self%c
   end function face_gap_part

   !> a_F += dx / c: the face's share of eq. I.7.
   subroutine face_accelerate(self, nnode, a)
      class(massless_face_t), intent(in) :: self
      integer, intent(in) :: nnode
      real(wp), intent(inout) :: a(2, nnode)
      integer :: k
      if (.not. self%active) return
      do k = 1, self%nf
         where (self%free(:, k)) a(:, self%node(k)) = a(:, self%node(k)) + self%dx(2*k - 1:2*k)/self%c
      end do
   end subroutine face_accelerate

end module exic_contact_massless_face
