!> Free rigid bodies as three-dof bodies in the contact corrector (doc/loads.md, section 5).
!>
!> A constraint i touches body b through the nodes of i that belong to b; its column of G on the
!> body's dofs (X, Y, theta) is
!>
!>     g_i^b = sum_{k in i, k on b} w_ik (n_x, n_y, r_k x n_i),     r_k = x_k - X_b at t(n+1),
!>
!> and S = G^T M^-1 G gains g_i^b . M_b^-1 g_j^b for every body both constraints touch, with
!> M_b^-1 = diag(1/m, 1/m, 1/I) (the centroid as reference point). The corrector keeps its
!> node-wise assembly; this module gives it, per step, each candidate's body columns ("slots")
!> and the candidates of each body, and per pivoting pass the bodies' accelerations
!> M_b^-1 sum_i p_i g_i^b. Plain arrays in: the candidates' nodes, weights and normals.
!>
!> With friction (doc/friction.md, eq. F5) each candidate also has tangential body columns
!> g_T,i^b = sum w_ik (t_x, t_y, r_k x t_i) in the same slots (`tangent_columns`), the bodies'
!> accelerations count the tangential multipliers too (`accelerations_nt`), and `slide_part`
!> gives a candidate's change of slip through the bodies.
module exic_contact_rigid_dofs
   use exic_base_kinds, only: wp
   use exic_base_grow, only: grow
   implicit none
   private

   public :: rigid_dofs_t

   !> The free rigid bodies of a model as the corrector sees them.
   type :: rigid_dofs_t
      integer :: nbody = 0
      integer, allocatable :: body(:)          !< (nnode) body of each node, 0: none
      real(wp), allocatable :: r(:, :)         !< (2, nnode) lever arm x_k - X_b at t(n+1), 0 off bodies
      real(wp), allocatable :: minv(:, :)      !< (3, nbody) 1/m, 1/m, 1/I
      ! per step: the candidates' body columns
      integer, allocatable :: nslot(:)         !< (m) bodies candidate i touches (0..3)
      integer, allocatable :: sbody(:, :)      !< (3, m) those bodies
      real(wp), allocatable :: sg(:, :, :)     !< (3, 3, m) their columns g_i^b
      integer, allocatable :: bstart(:)        !< (nbody + 1) body -> candidate slots (CSR)
      integer, allocatable :: bcand(:), bslot(:) !< candidate and slot of each entry
      real(wp), allocatable :: acc(:, :)       !< (3, nbody) M_b^-1 sum_i p_i g_i^b of one pass
      real(wp), allocatable :: sgt(:, :, :)    !< (3, 3, m) the tangential columns g_T,i^b (friction)
   contains
      procedure :: init => rigid_dofs_init
      procedure :: prepare => rigid_dofs_prepare
      procedure :: accelerations => rigid_dofs_accelerations
      procedure :: gap_part => rigid_dofs_gap_part
      procedure :: tangent_columns => rigid_dofs_tangent_columns
      procedure :: accelerations_nt => rigid_dofs_accelerations_nt
      procedure :: slide_part => rigid_dofs_slide_part
   end type rigid_dofs_t

contains

   !> `nbody` bodies over `nnode` nodes; `body(nnode)` names each node's body (0: none).
   subroutine rigid_dofs_init(self, nnode, nbody, body)
      class(rigid_dofs_t), intent(inout) :: self
      integer, intent(in) :: nnode, nbody
      integer, intent(in) :: body(nnode)
      self%nbody = nbody
      self%body = body
      allocate (self%r(2, nnode), source=0.0_wp)
      allocate (self%minv(3, nbody), self%acc(3, nbody), source=0.0_wp)
      allocate (self%bstart(nbody + 1), source=1)
   end subroutine rigid_dofs_init

   !> The body columns of the m candidates (nodes node(3, m), weights w(3, m), normals nrm(2, m))
   !> and the body -> candidates incidence.
   subroutine rigid_dofs_prepare(self, m, node, w, nrm)
      class(rigid_dofs_t), intent(inout) :: self
      integer, intent(in) :: m
      integer, intent(in) :: node(3, m)
      real(wp), intent(in) :: w(3, m), nrm(2, m)
      integer :: i, k, q, b, nd, found, nent, pos
      real(wp) :: rk(2)

      call grow(self%nslot, m)
      call grow(self%sbody, m, 3)
      if (allocated(self%sg)) then
         if (size(self%sg, 3) < m) deallocate (self%sg)
      end if
      if (.not. allocated(self%sg)) allocate (self%sg(3, 3, max(m, 64)))
      nent = 0
      do i = 1, m
         self%nslot(i) = 0
         do k = 1, 3
            if (w(k, i) == 0.0_wp) cycle
            nd = node(k, i)
            b = self%body(nd)
            if (b == 0) cycle
            found = 0
            do q = 1, self%nslot(i)
               if (self%sbody(q, i) == b) found = q
            end do
            if (found == 0) then
               self%nslot(i) = self%nslot(i) + 1
               found = self%nslot(i)
               self%sbody(found, i) = b
               self%sg(:, found, i) = 0.0_wp
               nent = nent + 1
            end if
            rk = self%r(:, nd)
            self%sg(1, found, i) = self%sg(1, found, i) + w(k, i)*nrm(1, i)
            self%sg(2, found, i) = self%sg(2, found, i) + w(k, i)*nrm(2, i)
            self%sg(3, found, i) = self%sg(3, found, i) + w(k, i)*(rk(1)*nrm(2, i) - rk(2)*nrm(1, i))
         end do
      end do
      ! body -> (candidate, slot) in compressed rows, candidates in increasing order
      self%bstart = 0
      do i = 1, m
         do q = 1, self%nslot(i)
            b = self%sbody(q, i)
            self%bstart(b + 1) = self%bstart(b + 1) + 1
         end do
      end do
      self%bstart(1) = 1
      do b = 1, self%nbody
         self%bstart(b + 1) = self%bstart(b + 1) + self%bstart(b)
      end do
      call grow(self%bcand, max(nent, 1))
      call grow(self%bslot, max(nent, 1))
      do i = 1, m
         do q = 1, self%nslot(i)
            b = self%sbody(q, i)
            pos = self%bstart(b)
            self%bcand(pos) = i
            self%bslot(pos) = q
            self%bstart(b) = pos + 1
         end do
      end do
      do b = self%nbody, 1, -1
         self%bstart(b + 1) = self%bstart(b)
      end do
      self%bstart(1) = 1
   end subroutine rigid_dofs_prepare

   !> acc(:, b) = M_b^-1 sum_i p_i g_i^b: the bodies' accelerations under the multipliers p(m).
   subroutine rigid_dofs_accelerations(self, m, p)
      class(rigid_dofs_t), intent(inout) :: self
      integer, intent(in) :: m
      real(wp), intent(in) :: p(m)
      integer :: i, q, b
      self%acc = 0.0_wp
      do i = 1, m
         if (p(i) == 0.0_wp) cycle
         do q = 1, self%nslot(i)
            b = self%sbody(q, i)
            self%acc(:, b) = self%acc(:, b) + p(i)*self%sg(:, q, i)
         end do
      end do
      self%acc = self%acc*self%minv
   end subroutine rigid_dofs_accelerations

   !> sum_b g_i^b . acc(:, b): the change of candidate i's gap per unit c through the bodies.
   pure real(wp) function rigid_dofs_gap_part(self, i) result(dg)
      class(rigid_dofs_t), intent(in) :: self
      integer, intent(in) :: i
      integer :: q
      dg = 0.0_wp
      do q = 1, self%nslot(i)
         dg = dg + dot_product(self%sg(:, q, i), self%acc(:, self%sbody(q, i)))
      end do
   end function rigid_dofs_gap_part

   !> The tangential body columns g_T,i^b = sum_{k on b} w_ik (t_x, t_y, r_k x t_i) of the m
   !> candidates prepared last, in the slots of their normal columns (tng(2, m): the tangents).
   subroutine rigid_dofs_tangent_columns(self, m, node, w, tng)
      class(rigid_dofs_t), intent(inout) :: self
      integer, intent(in) :: m
      integer, intent(in) :: node(3, m)
      real(wp), intent(in) :: w(3, m), tng(2, m)
      integer :: i, k, q, nd
      real(wp) :: rk(2)
      if (allocated(self%sgt)) then
         if (size(self%sgt, 3) < m) deallocate (self%sgt)
      end if
      if (.not. allocated(self%sgt)) allocate (self%sgt(3, 3, max(m, 64)))
      do i = 1, m
         self%sgt(:, 1:self%nslot(i), i) = 0.0_wp
         do k = 1, 3
            if (w(k, i) == 0.0_wp) cycle
            nd = node(k, i)
            if (self%body(nd) == 0) cycle
            q = findloc(self%sbody(1:self%nslot(i), i), self%body(nd), 1)
            rk = self%r(:, nd)
            self%sgt(1, q, i) = self%sgt(1, q, i) + w(k, i)*tng(1, i)
            self%sgt(2, q, i) = self%sgt(2, q, i) + w(k, i)*tng(2, i)
            self%sgt(3, q, i) = self%sgt(3, q, i) + w(k, i)*(rk(1)*tng(2, i) - rk(2)*tng(1, i))
         end do
      end do
   end subroutine rigid_dofs_tangent_columns

   !> acc(:, b) = M_b^-1 sum_i (p_i g_N,i^b + q_i g_T,i^b): the bodies' accelerations under the
   !> normal and tangential multipliers p(m), q(m).
   subroutine rigid_dofs_accelerations_nt(self, m, p, q)
      class(rigid_dofs_t), intent(inout) :: self
      integer, intent(in) :: m
      real(wp), intent(in) :: p(m), q(m)
      integer :: i, j, b
      self%acc = 0.0_wp
      do i = 1, m
         do j = 1, self%nslot(i)
            b = self%sbody(j, i)
            if (p(i) /= 0.0_wp) self%acc(:, b) = self%acc(:, b) + p(i)*self%sg(:, j, i)
            if (q(i) /= 0.0_wp) self%acc(:, b) = self%acc(:, b) + q(i)*self%sgt(:, j, i)
         end do
      end do
      self%acc = self%acc*self%minv
   end subroutine rigid_dofs_accelerations_nt

   !> sum_b g_T,i^b . acc(:, b): the change of candidate i's slip per unit c through the bodies.
   pure real(wp) function rigid_dofs_slide_part(self, i) result(ds)
      class(rigid_dofs_t), intent(in) :: self
      integer, intent(in) :: i
      integer :: q
      ds = 0.0_wp
      do q = 1, self%nslot(i)
         ds = ds + dot_product(self%sgt(:, q, i), self%acc(:, self%sbody(q, i)))
      end do
   end function rigid_dofs_slide_part

end module exic_contact_rigid_dofs
