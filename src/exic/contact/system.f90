!> The contact operator S = G^T M^-1 G of a step's candidates along one set of directions, and
!> its factorisation (seed eq. 4.5-4.7).
!>
!> Candidate i has nodes node(:, i) with weights w(:, i) and a unit direction dir(:, i): its
!> column of G holds w_k dir_i at the dofs of node k. The normal problem of the corrector uses
!> the frozen normals (G = G_N), the frictional corrector also the tangents (G_T, doc/friction.md
!> eq. F2): both matrices have the pattern of the node incidence of the candidates, and free
!> rigid bodies add g_i^b . M_b^-1 g_j^b for every body two candidates touch (doc/loads.md,
!> section 5), g^b the body columns of that direction (rigid_dofs_t: `sg` normal, `sgt`
!> tangent).
!>
!> Steps with up to `dense_limit` candidates keep S dense and factorise it with LAPACK
!> (dense_spd_t); larger ones keep it in compressed columns with the full pattern and use
!> SuiteSparse LDL' (sparse_ldl_t), whose symbolic analysis is reused while the pattern and the
!> order are unchanged. S is block diagonal over the connected components of the candidates
!> (candidates that share a node, a free rigid body or a massless face; exic_contact_components,
!> doc/contact-detection.md eq. D.3-D.5): when there are several and none holds more than
!> `natural_limit` candidates, the elimination takes the components one after the other, each
!> in candidate order, which factorises every block on its own without an AMD ordering: each
!> component is then assembled as a packed block of its own and factorised by
!> exic_linalg_block_ldl with the operations, and so the bits, of the sparse LDL' of all of S in
!> that order (eq. D.6; a pivoting pass refactorises only the blocks whose mask changed); with
!> one component (or a larger one) AMD orders S as a whole. A factorisation leaves out the
!> candidates a `drop` mask names (the pivoting passes of an active-set solve) and removes
!> redundant ones (dependent columns of G), which carry a zero solution. A factorisation of the
!> same assembly with the same mask as the last one is not repeated (a solve reuses it).
!>
!> Massless contact faces (`LAGRange,ENERgy`, doc/impact.md eq. I.6) add their compliance
!> (1/c) G_F,i^T K_FF^-1 G_F,j to the normal problem's S for every two candidates on the face
!> (`massless_face_t`, prepared for the step's candidates).
!>
!> `corrector_t` (the normal problem) extends this type; `friction_t` owns a second one for the
!> tangential problem.
module exic_contact_system
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow
   use exic_base_strings, only: itoa
   use exic_base_threads, only: threaded
   use exic_linalg_sparse_ldl, only: sparse_ldl_t
   use exic_linalg_dense_spd, only: dense_spd_t
   use exic_linalg_block_ldl, only: block_ldl_factor, block_ldl_solve
   use exic_contact_rigid_dofs, only: rigid_dofs_t
   use exic_contact_massless_face, only: massless_face_t
   use exic_contact_components, only: components_t
   implicit none
   private

   public :: system_t

   !> Candidates from which the blocks of S are factorised on the threads (blocks of a few
   !> candidates: about a microsecond per 10 candidates against a few for a parallel region).
   integer, parameter :: BLOCKS_MIN = 512

   !> S of the m candidates of a step (dense or in compressed columns) and its factorisation.
   type :: system_t
      integer :: dense_limit = 30            !< steps with up to this many candidates factorize S densely (measured crossover)
      integer :: natural_limit = 64          !< largest component eliminated in candidate order
      logical :: split = .true.              !< by components when they allow it (else AMD)
      logical :: by_blocks = .true.          !< components factorised as blocks of their own (else
                                             !< the sparse LDL' in their order: the same bits)
      integer :: ncomp = 0                   !< components of the last sparse step (0: not sought)
      type(components_t) :: comp             !< those components
      logical :: blocks = .false.            !< the last assembly is by components (packed blocks)
      ! S by components (eq. D.4-D.6): block c, of nb = comp%start(c+1) - comp%start(c)
      ! candidates, holds the upper triangles of its columns packed at boff(c) + 1 ...
      ! boff(c) + nb (nb + 1) / 2 of bs (values) and bnz (in the pattern), and its L by columns
      ! (rows, values) at loff(c) + 1 ... loff(c) + nb**2 of blrow, blx; the per-candidate
      ! arrays are indexed by the position in comp%list
      integer, allocatable :: boff(:), loff(:)   !< (ncomp + 1) offsets of the blocks
      real(wp), allocatable :: bs(:), blx(:)
      logical, allocatable :: bnz(:)
      integer, allocatable :: blrow(:)
      integer, allocatable :: blcnt(:)       !< (m) entries of each column of L
      real(wp), allocatable :: bd(:), bx(:)  !< (m) pivots D, solution work
      logical, allocatable :: bremoved(:)    !< (m) pivots removed (dropped or redundant)
      logical, allocatable :: bdrop(:)       !< (m) the drop mask each block was last factorised with
      logical :: bfactored = .false.         !< every block of the assembly has been factorised
      integer, allocatable :: biwork(:)      !< (3 largest block) work of the factorisation
      real(wp), allocatable :: bwork(:)      !< (largest block) work of the factorisation
      type(sparse_ldl_t) :: sparse
      type(dense_spd_t) :: dense
      integer :: nsolves = 0, ndense = 0, nsparse = 0   !< factorisations made (statistics)
      integer :: nreused = 0                 !< solves that reused the last factorisation
      integer :: nthreaded = 0               !< factorisations by blocks made on the threads
      integer, allocatable :: ap(:), ai(:)   !< S in compressed columns: (m + 1), (nnz)
      real(wp), allocatable :: ax(:)         !< (nnz) values of S in compressed columns
      real(wp), allocatable :: s(:, :)       !< (m, m) S for the dense path
      integer, allocatable :: mark(:)        !< (m) last column that touched a row (assembly)
      integer, allocatable :: pos(:)         !< (m) where that column holds the row's entry
      integer, allocatable :: bad(:)         !< (m) candidates the factorisation finds redundant
      ! the last factorisation, for reuse
      logical :: factored = .false.          !< the current assembly has been factorised
      integer :: mlast = 0, nbad_last = 0
      logical, allocatable :: drop_last(:)   !< (m) the mask it was made with
   contains
      procedure :: assemble => system_assemble
      procedure :: factor_solve => system_factor_solve
   end type system_t

contains

   !> S = G^T M^-1 G over all m candidates (nodes node(3, m), weights w(3, m), directions
   !> dir(2, m)): dense (m <= dense_limit), by components as packed blocks (eq. D.6), or in
   !> compressed columns with the full pattern. lnode(3, m): the local number (1 ... nloc) of
   !> each node of a candidate (0 where its weight is 0); nstart(nloc + 1), nlist: local node ->
   !> candidates incidence (compressed rows, candidate order), nweight: the node's weight in each
   !> candidate of nlist (the sum over its occurrences). With free rigid bodies `rb`, each column
   !> gains the coupling of the bodies its candidate touches, through the body columns `rb%sgt`
   !> when `tangent`, else `rb%sg`. With massless faces `face` (normal
   !> problem only), each column of a candidate on the face gains the face's compliance (eq. I.6).
   subroutine system_assemble(self, m, node, lnode, w, dir, nnode, minv, nloc, nstart, nlist, &
                              nweight, rb, tangent, face)
      class(system_t), intent(inout) :: self
      integer, intent(in) :: m, nnode, nloc
      integer, intent(in) :: node(3, m), lnode(3, m), nstart(nloc + 1), nlist(:)
      real(wp), intent(in) :: w(3, m), dir(2, m), minv(2, nnode), nweight(:)
      type(rigid_dofs_t), intent(in), optional :: rb
      logical, intent(in), optional :: tangent
      type(massless_face_t), intent(in), optional :: face
      integer :: j, k, nd, ln, q, i, nnz, first, cap, base, lj
      real(wp) :: v
      logical :: along_t, csc

      along_t = .false.
      if (present(tangent)) along_t = tangent
      self%factored = .false.
      self%ncomp = 0
      self%blocks = .false.
      if (m > self%dense_limit) call choose_order(self, m, lnode, nloc, nstart, nlist, rb, face)
      csc = m > self%dense_limit .and. .not. self%blocks
      base = 0
      lj = 0
      if (self%blocks) then
         call size_blocks(self)
         call block_entries(m, node, lnode, w, dir, nnode, minv, nloc, nstart, nlist, nweight, &
                            self%comp%loc, self%comp%id, self%boff, self%bs, self%bnz)
         ! free rigid bodies and massless faces: their entries by columns below
         if (.not. (present(rb) .or. present(face))) return
      end if
      if (m <= self%dense_limit) then
         if (allocated(self%s)) then
            if (size(self%s, 1) < m) deallocate (self%s)
         end if
         if (.not. allocated(self%s)) allocate (self%s(max(m, 16), max(m, 16)))
         self%s(1:m, 1:m) = 0.0_wp
      end if
      call grow(self%ap, m + 1)
      call grow(self%mark, m)
      call grow(self%pos, m)
      self%mark(1:m) = 0
      nnz = 0
      cap = 0
      if (allocated(self%ai) .and. allocated(self%ax)) cap = min(size(self%ai), size(self%ax))
      self%ap(1) = 1
      do j = 1, m
         first = nnz + 1
         ! a column holds at most m entries: room for them before it, none grown within
         if (csc .and. nnz + m > cap) then
            call grow(self%ai, nnz + m)
            call grow(self%ax, nnz + m)
            cap = min(size(self%ai), size(self%ax))
         end if
         if (self%blocks) then
            ! the node entries are in (block_entries): the bodies' and the face's after them
            lj = self%comp%loc(j)
            base = self%boff(self%comp%id(j)) + ((lj - 1)*lj)/2
         else
            do k = 1, 3
               if (w(k, j) == 0.0_wp) cycle
               nd = node(k, j)
               ln = lnode(k, j)
               ! every candidate i that shares node nd with candidate j: S(i, j) += w_kj w_i(nd) d_j M^-1 d_i
               do q = nstart(ln), nstart(ln + 1) - 1
                  i = nlist(q)
                  v = w(k, j)*nweight(q)* &
                      (dir(1, j)*minv(1, nd)*dir(1, i) + dir(2, j)*minv(2, nd)*dir(2, i))
                  call add_entry(i, v)
               end do
            end do
         end if
         if (present(rb)) then
            if (along_t) then
               call body_entries(rb%sgt)
            else
               call body_entries(rb%sg)
            end if
         end if
         if (present(face)) then
            ! every candidate i on the face when j is: S(i, j) += (1/c) G_F,i^T K_FF^-1 G_F,j (eq. I.6)
            if (face%slot(j) > 0) then
               do i = 1, m
                  v = face%coupling(i, j, node(:, i), w(:, i), dir(:, i))
                  if (v /= 0.0_wp) call add_entry(i, v)
               end do
            end if
         end if
         if (csc) call sort_column(self%ai(first:nnz), self%ax(first:nnz))
         self%ap(j + 1) = nnz + 1
      end do
   contains
      !> Every candidate i on a body b that candidate j touches: S(i, j) += g_i^b . M_b^-1 g_j^b.
      subroutine body_entries(sg)
         real(wp), intent(in) :: sg(:, :, :)
         integer :: qj, b, e
         do qj = 1, rb%nslot(j)
            b = rb%sbody(qj, j)
            do e = rb%bstart(b), rb%bstart(b + 1) - 1
               i = rb%bcand(e)
               v = dot_product(sg(:, rb%bslot(e), i), rb%minv(:, b)*sg(:, qj, j))
               call add_entry(i, v)
            end do
         end do
      end subroutine body_entries

      !> S(i, j) += v (dense), or into column j of the compressed columns.
      subroutine add_entry(i, v)
         integer, intent(in) :: i
         real(wp), intent(in) :: v
         integer :: ie
         if (m <= self%dense_limit) then
            self%s(i, j) = self%s(i, j) + v
         else if (self%blocks) then
            if (self%comp%loc(i) > lj) return
            ie = base + self%comp%loc(i)
            if (self%bnz(ie)) then
               self%bs(ie) = self%bs(ie) + v
            else
               self%bs(ie) = v
               self%bnz(ie) = .true.
            end if
         else
            if (self%mark(i) /= j) then
               self%mark(i) = j
               nnz = nnz + 1
               self%pos(i) = nnz
               self%ai(nnz) = i
               self%ax(nnz) = v
            else
               self%ax(self%pos(i)) = self%ax(self%pos(i)) + v
            end if
         end if
      end subroutine add_entry
   end subroutine system_assemble

   !> The elimination order of the sparse factorisation (eq. D.5): the components of the
   !> candidates one after the other, each in candidate order, when there are several and none
   !> holds more than natural_limit candidates; otherwise AMD's. Arguments as system_assemble.
   subroutine choose_order(self, m, lnode, nloc, nstart, nlist, rb, face)
      type(system_t), intent(inout) :: self
      integer, intent(in) :: m, nloc
      integer, intent(in) :: lnode(3, m), nstart(nloc + 1), nlist(:)
      type(rigid_dofs_t), intent(in), optional :: rb
      type(massless_face_t), intent(in), optional :: face
      integer :: b, j, first, largest
      call self%sparse%set_order(0, [integer ::])
      if (.not. self%split) return
      ! the components (eq. D.3): candidates joined through nodes, bodies and the face
      call self%comp%reset(m)
      call self%comp%join_nodes(m, lnode, nloc, nstart, nlist)
      if (present(rb)) then
         do b = 1, rb%nbody
            call self%comp%join_list(rb%bcand(rb%bstart(b):rb%bstart(b + 1) - 1))
         end do
      end if
      if (present(face)) then
         first = 0
         do j = 1, m
            if (face%slot(j) == 0) cycle
            if (first == 0) first = j
            call self%comp%join(first, j)
         end do
      end if
      call self%comp%label()
      self%ncomp = self%comp%n
      largest = 0
      do b = 1, self%comp%n
         largest = max(largest, self%comp%start(b + 1) - self%comp%start(b))
      end do
      if (self%comp%n > 1 .and. largest <= self%natural_limit) then
         if (self%by_blocks) then
            self%blocks = .true.
         else
            call self%sparse%set_order(m, self%comp%list)
         end if
      end if
   end subroutine choose_order

   !> Offsets of the blocks of the components (eq. D.4), room for their values, pattern and L,
   !> and the pattern emptied.
   subroutine size_blocks(self)
      type(system_t), intent(inout) :: self
      integer :: c, nb, total, m, largest
      m = self%comp%m
      call grow(self%boff, self%comp%n + 1)
      call grow(self%loff, self%comp%n + 1)
      self%boff(1) = 0
      self%loff(1) = 0
      largest = 0
      do c = 1, self%comp%n
         nb = self%comp%start(c + 1) - self%comp%start(c)
         self%boff(c + 1) = self%boff(c) + (nb*(nb + 1))/2
         self%loff(c + 1) = self%loff(c) + nb*nb
         largest = max(largest, nb)
      end do
      total = self%boff(self%comp%n + 1)
      call grow(self%bs, total)
      call grow(self%bnz, total)
      call grow(self%blx, self%loff(self%comp%n + 1))
      call grow(self%blrow, self%loff(self%comp%n + 1))
      call grow(self%blcnt, m)
      call grow(self%bd, m)
      call grow(self%bx, m)
      call grow(self%bremoved, m)
      call grow(self%bdrop, m)
      self%bfactored = .false.
      call grow(self%biwork, 3*largest)
      call grow(self%bwork, largest)
      self%bnz(1:total) = .false.
   end subroutine size_blocks

   !> The node terms of S (eq. D.3) in the upper triangles of the blocks (eq. D.6): for every
   !> candidate j (column loc(j) of block id(j), upper triangle packed from boff(id(j)) + 1) and
   !> every candidate i that shares a node nd with it and comes no later in the block,
   !> S(i, j) += w_kj w_i(nd) d_j M^-1 d_i, in the order and with the operations of the
   !> compressed columns (system_assemble): an entry's first term is stored, the next ones added.
   !> Arguments as system_assemble; bnz false on entry.
   pure subroutine block_entries(m, node, lnode, w, dir, nnode, minv, nloc, nstart, nlist, &
                                 nweight, loc, id, boff, bs, bnz)
      integer, intent(in) :: m, nnode, nloc
      integer, intent(in) :: node(3, m), lnode(3, m), nstart(nloc + 1), nlist(:)
      integer, intent(in) :: loc(:), id(:), boff(:)
      real(wp), intent(in) :: w(3, m), dir(2, m), minv(2, nnode), nweight(:)
      real(wp), intent(inout) :: bs(:)
      logical, intent(inout) :: bnz(:)
      integer :: j, k, nd, ln, q, i, li, base, e
      real(wp) :: wk, a1, a2
      do j = 1, m
         base = boff(id(j)) + ((loc(j) - 1)*loc(j))/2
         do k = 1, 3
            wk = w(k, j)
            if (wk == 0.0_wp) cycle
            nd = node(k, j)
            ln = lnode(k, j)
            a1 = dir(1, j)*minv(1, nd)
            a2 = dir(2, j)*minv(2, nd)
            ! the candidates at a node are of one component and listed in candidate order, in
            ! which their positions in the block ascend: those after j are below the diagonal
            do q = nstart(ln), nstart(ln + 1) - 1
               i = nlist(q)
               if (i > j) exit
               li = loc(i)
               e = base + li
               if (bnz(e)) then
                  bs(e) = bs(e) + wk*nweight(q)*(a1*dir(1, i) + a2*dir(2, i))
               else
                  bs(e) = wk*nweight(q)*(a1*dir(1, i) + a2*dir(2, i))
                  bnz(e) = .true.
               end if
            end do
         end do
      end do
   end subroutine block_entries

   !> Factorise every block of S by components (eq. D.6) without the candidates drop(1:m)
   !> names; the redundant ones are listed in self%bad(1:nbad), component by component.
   subroutine factor_blocks(self, m, drop, nbad, err)
      type(system_t), intent(inout) :: self
      integer, intent(in) :: m
      logical, intent(in) :: drop(:)
      integer, intent(out) :: nbad
      type(error_t), allocatable, intent(out) :: err
      integer :: c, p, status, bad
      integer, allocatable :: iwork(:)
      real(wp), allocatable :: y(:)
      nbad = 0
      ! the blocks are independent (eq. D.4): each one's values, mask, L and D are its own; the
      ! first failing block in component order is reported, whatever the threads did
      bad = 0
      if (threaded(m, BLOCKS_MIN) .and. self%comp%n > 1) then
         self%nthreaded = self%nthreaded + 1
         !$omp parallel default(shared) private(c, status, iwork, y)
         allocate (iwork(size(self%biwork)), y(size(self%bwork)))
         !$omp do schedule(dynamic, 16)
         do c = 1, self%comp%n
            call factor_block(self, c, drop, iwork, y, status)
            if (status /= 0) then
               !$omp critical (exic_contact_system_bad)
               if (bad == 0 .or. c < bad) bad = c
               !$omp end critical (exic_contact_system_bad)
            end if
         end do
         !$omp end do
         deallocate (iwork, y)
         !$omp end parallel
      else
         do c = 1, self%comp%n
            call factor_block(self, c, drop, self%biwork, self%bwork, status)
            if (status /= 0) then
               bad = c
               exit
            end if
         end do
      end if
      if (bad > 0) then
         self%bfactored = .false.
         call make_error(err, 'contact corrector: non-finite pivot in S (NaN or Inf), '// &
                         'component of candidate '//itoa(self%comp%list(self%comp%start(bad))))
         return
      end if
      self%bfactored = .true.
      ! the redundant ones: removed and not dropped (listed by component)
      do p = 1, m
         if (self%bremoved(p) .and. .not. self%bdrop(p)) then
            nbad = nbad + 1
            self%bad(nbad) = self%comp%list(p)
         end if
      end do
   end subroutine factor_blocks

   !> Factorise block c of S by components (factor_blocks), unless it was factorised with the
   !> same mask: a pivoting pass changes the active set of a few components only. iwork(3 nb),
   !> y(nb): work; status as block_ldl_factor.
   subroutine factor_block(self, c, drop, iwork, y, status)
      type(system_t), intent(inout) :: self
      integer, intent(in) :: c
      logical, intent(in) :: drop(:)
      integer, intent(inout), contiguous :: iwork(:)
      real(wp), intent(inout), contiguous :: y(:)
      integer, intent(out) :: status
      integer :: p0, nb, o, ol, p
      logical :: same
      status = 0
      p0 = self%comp%start(c)
      nb = self%comp%start(c + 1) - p0
      o = self%boff(c)
      ol = self%loff(c)
      same = self%bfactored
      if (same) then
         do p = p0, p0 + nb - 1
            if (self%bdrop(p) .neqv. drop(self%comp%list(p))) then
               same = .false.
               exit
            end if
         end do
      end if
      if (same) return
      do p = p0, p0 + nb - 1
         self%bdrop(p) = drop(self%comp%list(p))
         self%bremoved(p) = self%bdrop(p)
      end do
      call block_ldl_factor(nb, self%bs(o + 1:), self%bnz(o + 1:), self%sparse%tol, &
                            self%bremoved(p0:), self%blcnt(p0:), self%blrow(ol + 1:), &
                            self%blx(ol + 1:), self%bd(p0:), iwork, y, status)
   end subroutine factor_block

   !> sol = S^-1 rhs with the factors of factor_blocks (0 on the removed candidates).
   subroutine solve_blocks(self, rhs, sol)
      type(system_t), intent(inout) :: self
      real(wp), intent(in) :: rhs(:)
      real(wp), intent(inout) :: sol(:)
      integer :: c, p0, nb, o, p
      do p = 1, self%comp%m
         self%bx(p) = rhs(self%comp%list(p))
      end do
      do c = 1, self%comp%n
         p0 = self%comp%start(c)
         nb = self%comp%start(c + 1) - p0
         o = self%loff(c)
         call block_ldl_solve(nb, self%blcnt(p0:), self%blrow(o + 1:), self%blx(o + 1:), &
                              self%bd(p0:), self%bremoved(p0:), self%bx(p0:))
      end do
      do p = 1, self%comp%m
         sol(self%comp%list(p)) = self%bx(p)
      end do
   end subroutine solve_blocks

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

   !> Factorise the assembled S of the m candidates without those drop(1:m) names and solve
   !> S sol = rhs. Redundant candidates found by the factorisation join `drop` with sol = 0
   !> (nbad of them, listed in self%bad(1:nbad)). The same mask on the same assembly reuses the
   !> last factorisation.
   subroutine system_factor_solve(self, m, drop, rhs, sol, nbad, err)
      class(system_t), intent(inout) :: self
      integer, intent(in) :: m
      logical, intent(inout) :: drop(:)
      real(wp), intent(in) :: rhs(:)
      real(wp), intent(inout) :: sol(:)
      integer, intent(out) :: nbad
      type(error_t), allocatable, intent(out) :: err
      integer :: stat, k
      logical :: reuse

      reuse = self%factored .and. self%mlast == m
      if (reuse) reuse = all(drop(1:m) .eqv. self%drop_last(1:m))
      if (reuse) then
         self%nreused = self%nreused + 1
         nbad = self%nbad_last
      else
         call grow(self%bad, m)
         call grow(self%drop_last, m)
         self%drop_last(1:m) = drop(1:m)
         self%mlast = m
         self%factored = .false.
         self%nsolves = self%nsolves + 1
         if (m <= self%dense_limit) then
            self%ndense = self%ndense + 1
            call self%dense%factorize(self%s(1:m, 1:m), nbad, self%bad, err, drop(1:m))
         else if (self%blocks) then
            self%nsparse = self%nsparse + 1
            call factor_blocks(self, m, drop, nbad, err)
         else
            self%nsparse = self%nsparse + 1
            call self%sparse%refactorize(m, self%ap(1:m + 1), self%ai(1:self%ap(m + 1) - 1), &
                                         self%ax(1:self%ap(m + 1) - 1), nbad, self%bad, err, drop(1:m))
         end if
         if (allocated(err)) return
         self%factored = .true.
         self%nbad_last = nbad
      end if
      if (m <= self%dense_limit) then
         call self%dense%solve(rhs(1:m), sol(1:m), stat)
      else if (self%blocks) then
         call solve_blocks(self, rhs, sol)
         stat = 0
      else
         call self%sparse%solve(rhs(1:m), sol(1:m), stat)
      end if
      if (stat /= 0) then
         call make_error(err, 'contact corrector: the solve of S p = -g/c failed')
         return
      end if
      do k = 1, nbad
         drop(self%bad(k)) = .true.
         sol(self%bad(k)) = 0.0_wp
      end do
   end subroutine system_factor_solve

end module exic_contact_system
