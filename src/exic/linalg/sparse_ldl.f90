!> Sparse LDL' factorization of the contact operator S = G^T M^-1 G (seed eq. 4.5-4.7).
!>
!> S is symmetric positive semi-definite, one row per active contact constraint, very
!> sparse (constraints couple only when they share a node). `sparse_ldl_t` orders S with
!> AMD (or eliminates in an order the caller gives with `set_order`: the contact corrector's
!> components of S one after the other), keeps the symbolic analysis while the pattern and
!> the order are unchanged, factorizes with SuiteSparse LDL and flags redundant (linearly
!> dependent) constraints from the pivots.
!>
!> Input format: compressed sparse columns, 1-based: column j holds rows ai(ap(j):ap(j+1)-1),
!> values ax(ap(j):ap(j+1)-1), ap(1) = 1. The FULL symmetric pattern must be given (both
!> triangles and the diagonal): LDL reads the upper triangle of P S P^T, which mixes the two
!> triangles of S once permuted. Rows within a column may be unsorted; duplicates are summed.
!>
!> Redundancy rule. Pivot k of the elimination (row p = P(k) of S) is rejected when
!>
!>     D(k) <= tol * S(p, p),        tol = 1e-10 by default.
!>
!> D(k)/S(p,p) is the squared sine of the angle between constraint p and the span of the
!> constraints eliminated before it, in the M^-1 inner product (it does not depend on the
!> scaling of the constraints). For an exactly dependent constraint it is round-off, a few
!> units of 1e-16 times the number of couplings, so ~1e-14 at worst; an accepted pivot
!> amplifies errors in lambda by at most S(p,p)/D(k) < 1/tol, so lambda stays accurate to
!> about eps/tol ~ 1e-6 relative even for the worst constraint kept. 1e-10 sits four orders
!> above round-off and four below anything a physical contact configuration produces.
!>
!> A rejected constraint is removed during the elimination: its column of L is zeroed and its
!> unknown is set to zero in `solve`. That is exactly the factorization of S with the row and
!> column deleted, so `solve` returns the solution of the reduced system, with lambda = 0 on
!> the removed constraints; when S lambda = r is consistent (the gaps of dependent constraints
!> are dependent too) it satisfies the removed rows as well. A zero pivot that stops
!> ldl_numeric early is handled by the same rule. The caller may also drop constraints
!> itself (e.g. tensile ones in an active-set loop) without changing the pattern.
module exic_linalg_sparse_ldl
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_base_kinds, only: wp
   use exic_base_flat, only: all_finite
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow
   use exic_linalg_suitesparse_c, only: ldl_symbolic, ldl_numeric, ldl_lsolve, ldl_dsolve, &
      ldl_ltsolve, ldl_perm, ldl_permt, amd_order, amd_defaults, amd_control_size, &
      amd_info_size, amd_ok, amd_ok_but_jumbled, amd_out_of_memory
   implicit none
   private

   public :: ldl_numeric_drop, removal_rule

   !> Sparse LDL' solver with AMD ordering, symbolic reuse and redundancy detection.
   !> All work arrays live here; they grow with n and nnz and are never shrunk.
   type, public :: sparse_ldl_t
      !> Relative pivot tolerance of the redundancy rule D(k) <= tol * S(P(k), P(k)).
      real(wp) :: tol = 1.0e-10_wp
      !> Order and number of stored entries of the analyzed pattern.
      integer :: n = 0, nnz = 0
      !> Number of symbolic analyses done so far (AMD + ldl_symbolic).
      integer :: nanalyze = 0
      !> Eliminate in the order of `set_order` instead of AMD's.
      logical :: given = .false.
      !> The analysis used the given order.
      logical, private :: analyzed_given = .false.
      !> Number of constraints removed by the last `factorize` (found redundant or dropped).
      integer :: nremoved = 0
      !> True when the last `factorize` ran the removal elimination (some pivot was rejected,
      !> ldl_numeric stopped on a zero pivot, or constraints were dropped).
      logical :: removal_pass = .false.
      logical :: analyzed = .false., factorized = .false.
      ! pattern copy (0-based), ordering and symbolic data, numeric factor, work arrays
      integer(c_int), allocatable, private :: ap(:), ai(:), perm(:), pinv(:), lp(:), parent(:)
      integer(c_int), allocatable, private :: lnz(:), flag(:), pattern(:), li(:), gperm(:)
      real(wp), allocatable, private :: lx(:), d(:), y(:), diag(:)
      logical, allocatable, private :: removed(:)
      real(c_double), private :: control(amd_control_size) = 0.0_wp, info(amd_info_size) = 0.0_wp
   contains
      procedure :: set_order => ldl_set_order
      procedure :: analyze => ldl_analyze
      procedure :: same_pattern => ldl_same_pattern
      procedure :: factorize => ldl_factorize
      procedure :: refactorize => ldl_refactorize
      procedure :: solve => ldl_solve
      procedure :: free => ldl_free
   end type sparse_ldl_t


contains

   !> Eliminate the n rows in the order order(1:n) (a permutation of 1..n: order(k) is the k-th
   !> row eliminated) from the next analysis on, instead of ordering with AMD; n = 0 returns
   !> to AMD.
   subroutine ldl_set_order(self, n, order)
      class(sparse_ldl_t), intent(inout) :: self
      integer, intent(in) :: n
      integer, intent(in) :: order(:)
      integer :: k
      self%given = n > 0
      if (.not. self%given) return
      call grow(self%gperm, n)
      do k = 1, n
         self%gperm(k) = int(order(k) - 1, c_int)
      end do
   end subroutine ldl_set_order

   !> AMD ordering (or the order of `set_order`) and symbolic analysis of the n x n pattern
   !> (ap, ai), 1-based CSC with the full symmetric pattern. Always re-analyzes; see
   !> `refactorize` for the lazy form.
   subroutine ldl_analyze(self, n, ap, ai, err)
      class(sparse_ldl_t), intent(inout) :: self
      integer, intent(in) :: n
      integer, intent(in) :: ap(:), ai(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: j, q, nnz
      integer(c_int) :: status

      self%analyzed = .false.
      self%factorized = .false.
      call check_pattern(n, ap, ai, err)
      if (allocated(err)) return
      nnz = ap(n + 1) - 1
      call grow(self%ap, n + 1)
      call grow(self%ai, nnz)
      call grow(self%lp, n + 1)
      call grow(self%perm, n)
      call grow(self%pinv, n)
      call grow(self%parent, n)
      call grow(self%lnz, n)
      call grow(self%flag, n)
      call grow(self%pattern, n)
      call grow(self%d, n)
      call grow(self%y, n)
      call grow(self%diag, n)
      call grow(self%removed, n)
      do j = 1, n + 1
         self%ap(j) = int(ap(j) - 1, c_int)
      end do
      do q = 1, nnz
         self%ai(q) = int(ai(q) - 1, c_int)
      end do
      self%n = n
      self%nnz = nnz
      self%lp(1) = 0
      self%analyzed_given = self%given
      if (n > 0 .and. self%given) then
         self%perm(1:n) = self%gperm(1:n)
      else if (n > 0) then
         call amd_defaults(self%control)
         status = amd_order(int(n, c_int), self%ap, self%ai, self%perm, self%control, self%info)
         if (status /= amd_ok .and. status /= amd_ok_but_jumbled) then
            if (status == amd_out_of_memory) then
               call make_error(err, 'sparse LDL: AMD ordering ran out of memory')
            else
               call make_error(err, 'sparse LDL: AMD rejected the pattern (invalid matrix)')
            end if
            return
         end if
      end if
      if (n > 0) call ldl_symbolic(int(n, c_int), self%ap, self%ai, self%lp, self%parent, &
                                   self%lnz, self%flag, self%perm, self%pinv)
      call grow(self%li, max(1, int(self%lp(n + 1))))
      call grow(self%lx, max(1, int(self%lp(n + 1))))
      self%nanalyze = self%nanalyze + 1
      self%analyzed = .true.
   end subroutine ldl_analyze

   !> True when (n, ap, ai) is exactly the analyzed pattern (same order, pointers, row indices)
   !> and the analysis used the ordering asked for now (AMD's, or the same given order).
   !> Costs one pass over the pattern, far less than a factorization.
   logical function ldl_same_pattern(self, n, ap, ai) result(same)
      class(sparse_ldl_t), intent(in) :: self
      integer, intent(in) :: n
      integer, intent(in) :: ap(:), ai(:)
      integer :: j, q

      same = .false.
      if (.not. self%analyzed .or. n /= self%n .or. size(ap) < n + 1) return
      if (self%given .neqv. self%analyzed_given) return
      if (self%given) then
         do j = 1, n
            if (self%gperm(j) /= self%perm(j)) return
         end do
      end if
      if (ap(n + 1) - 1 /= self%nnz .or. size(ai) < self%nnz) return
      do j = 1, n + 1
         if (ap(j) - 1 /= self%ap(j)) return
      end do
      do q = 1, self%nnz
         if (ai(q) - 1 /= self%ai(q)) return
      end do
      same = .true.
   end function ldl_same_pattern

   !> Analyze (n, ap, ai) only if it differs from the analyzed pattern, then `factorize`.
   !> The safe per-step entry point: a stale analysis is never used.
   subroutine ldl_refactorize(self, n, ap, ai, ax, nbad, bad, err, drop)
      class(sparse_ldl_t), intent(inout) :: self
      integer, intent(in) :: n
      integer, intent(in) :: ap(:), ai(:)
      real(wp), intent(in) :: ax(:)
      integer, intent(out) :: nbad
      integer, intent(out) :: bad(:)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: drop(:)

      nbad = 0
      if (.not. self%same_pattern(n, ap, ai)) then
         call self%analyze(n, ap, ai, err)
         if (allocated(err)) return
      end if
      call self%factorize(ax, nbad, bad, err, drop)
   end subroutine ldl_refactorize

   !> Numeric LDL' of the analyzed pattern with values ax (same layout as ai).
   !> Redundant constraints (rule in the module header) are removed from the factorization and
   !> their original indices returned, ascending, in bad(1:nbad); size(bad) = n always suffices.
   !> Constraints with drop(j) = .true. are removed beforehand and not reported in bad.
   subroutine ldl_factorize(self, ax, nbad, bad, err, drop)
      class(sparse_ldl_t), intent(inout) :: self
      real(wp), intent(in) :: ax(:)
      integer, intent(out) :: nbad
      integer, intent(out) :: bad(:)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: drop(:)
      integer :: n, k, j, status
      integer(c_int) :: kstop
      logical :: clean, dropping

      nbad = 0
      self%factorized = .false.
      self%removal_pass = .false.
      self%nremoved = 0
      if (.not. self%analyzed) then
         call make_error(err, 'sparse LDL: factorize called before analyze')
         return
      end if
      n = self%n
      if (size(ax) < self%nnz) then
         call make_error(err, 'sparse LDL: fewer values than entries in the analyzed pattern')
         return
      end if
      dropping = .false.
      if (present(drop)) then
         if (size(drop) < n) then
            call make_error(err, 'sparse LDL: drop mask shorter than the matrix order')
            return
         end if
         dropping = any(drop(1:n))
      end if
      if (n == 0) then
         self%factorized = .true.
         return
      end if

      clean = .false.
      if (.not. dropping) then
         ! fast path: SuiteSparse LDL, then the pivot test against the original diagonal
         call diagonal_of(n, self%ap, self%ai, ax, self%diag)
         kstop = ldl_numeric(int(n, c_int), self%ap, self%ai, ax, self%lp, self%parent, &
                             self%lnz, self%li, self%lx, self%d, self%y, self%pattern, &
                             self%flag, self%perm, self%pinv)
         clean = (kstop == n)
         if (clean) then
            do k = 1, n
               if (.not. (self%d(k) > self%tol*self%diag(self%perm(k) + 1))) then
                  clean = .false.
                  exit
               end if
            end do
         end if
         if (clean .and. .not. all_finite(n, self%d)) then
            call make_error(err, 'sparse LDL: non-finite pivot (NaN or Inf in the matrix)')
            return
         end if
         self%removed(1:n) = .false.
      end if

      if (.not. clean) then
         self%removal_pass = .true.
         ! removal path: eliminate again, deleting each rejected (or dropped) constraint
         do k = 1, n
            self%removed(k) = .false.
            if (dropping) self%removed(k) = drop(self%perm(k) + 1)
         end do
         call ldl_numeric_drop(n, self%ap, self%ai, ax, self%lp, self%parent, self%lnz, &
                               self%li, self%lx, self%d, self%y, self%pattern, self%flag, &
                               self%perm, self%pinv, self%tol, self%removed, status)
         if (status /= 0) then
            call make_error(err, 'sparse LDL: non-finite pivot (NaN or Inf in the matrix)')
            return
         end if
         do j = 1, n
            if (.not. self%removed(self%pinv(j) + 1)) cycle
            self%nremoved = self%nremoved + 1
            if (dropping) then
               if (drop(j)) cycle
            end if
            nbad = nbad + 1
            if (nbad > size(bad)) then
               call make_error(err, 'sparse LDL: bad(:) too small for the redundant constraints')
               return
            end if
            bad(nbad) = j
         end do
      end if
      self%factorized = .true.
   end subroutine ldl_factorize

   !> Solve S x = b with the last factorization (x = 0 on removed constraints).
   !> stat (optional): 0 on success, 1 if not factorized, 2 if b or x is shorter than n.
   subroutine ldl_solve(self, b, x, stat)
      class(sparse_ldl_t), intent(inout) :: self
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: x(:)
      integer, intent(out), optional :: stat
      integer :: n, k

      n = self%n
      if (present(stat)) stat = 0
      if (.not. self%factorized) then
         if (present(stat)) stat = 1
         return
      end if
      if (size(b) < n .or. size(x) < n) then
         if (present(stat)) stat = 2
         return
      end if
      if (n == 0) return
      call ldl_perm(int(n, c_int), self%y, b, self%perm)
      call ldl_lsolve(int(n, c_int), self%y, self%lp, self%li, self%lx)
      call ldl_dsolve(int(n, c_int), self%y, self%d)
      if (self%nremoved > 0) then
         do k = 1, n
            if (self%removed(k)) self%y(k) = 0.0_wp
         end do
      end if
      call ldl_ltsolve(int(n, c_int), self%y, self%lp, self%li, self%lx)
      call ldl_permt(int(n, c_int), x, self%y, self%perm)
   end subroutine ldl_solve

   !> Release every array and forget the analysis.
   subroutine ldl_free(self)
      class(sparse_ldl_t), intent(inout) :: self
      if (allocated(self%ap)) deallocate (self%ap, self%ai, self%perm, self%pinv, self%lp, &
                                          self%parent, self%lnz, self%flag, self%pattern, &
                                          self%li, self%lx, self%d, self%y, self%diag, self%removed)
      self%n = 0
      self%nnz = 0
      self%nremoved = 0
      self%analyzed = .false.
      self%factorized = .false.
   end subroutine ldl_free

   !> Up-looking LDL' of P A P^T (the algorithm of ldl_numeric, 0-based arrays) that deletes
   !> constraints on the fly: pivot k is removed when removed(k) is set on entry or when
   !> D(k) <= tol * A(P(k), P(k)). A removed pivot gets a zero column and row in L and D(k) = 1;
   !> later rows see no contribution from it, which is the elimination of A with that row and
   !> column deleted. status = 0, or 1 on a non-finite pivot.
   subroutine ldl_numeric_drop(n, ap, ai, ax, lp, parent, lnz, li, lx, d, y, pattern, flag, &
                               perm, pinv, tol, removed, status)
      integer, intent(in) :: n
      integer(c_int), intent(in) :: ap(0:n), ai(0:*), lp(0:n), parent(0:n - 1)
      integer(c_int), intent(in) :: perm(0:n - 1), pinv(0:n - 1)
      real(wp), intent(in) :: ax(0:*), tol
      integer(c_int), intent(inout) :: lnz(0:n - 1), li(0:*), pattern(0:n - 1), flag(0:n - 1)
      real(wp), intent(inout) :: lx(0:*), d(0:n - 1), y(0:n - 1)
      logical, intent(inout) :: removed(0:n - 1)
      integer, intent(out) :: status
      integer :: k, kk, q, i, top, len, t, qend
      real(wp) :: yi, lki, sdiag

      status = 0
      do k = 0, n - 1
         ! nonzero pattern of row k of L in topological order (elimination tree walk)
         y(k) = 0.0_wp
         top = n
         flag(k) = k
         lnz(k) = 0
         kk = perm(k)
         do q = ap(kk), ap(kk + 1) - 1
            i = pinv(ai(q))
            if (i > k) cycle
            y(i) = y(i) + ax(q)
            len = 0
            do while (flag(i) /= k)
               pattern(len) = i
               len = len + 1
               flag(i) = k
               i = parent(i)
            end do
            do while (len > 0)
               top = top - 1
               len = len - 1
               pattern(top) = pattern(len)
            end do
         end do
         ! numerical values of row k (sparse triangular solve)
         sdiag = y(k)
         d(k) = y(k)
         y(k) = 0.0_wp
         do t = top, n - 1
            i = pattern(t)
            yi = y(i)
            y(i) = 0.0_wp
            qend = lp(i) + lnz(i)
            do q = lp(i), qend - 1
               y(li(q)) = y(li(q)) - lx(q)*yi
            end do
            lki = 0.0_wp
            if (.not. removed(i)) lki = yi/d(i)
            d(k) = d(k) - lki*yi
            li(qend) = k
            lx(qend) = lki
            lnz(i) = lnz(i) + 1
         end do
         call removal_rule(tol, sdiag, d(k), removed(k), status)
         if (status /= 0) return
         if (removed(k)) then
            do t = top, n - 1
               i = pattern(t)
               lx(lp(i) + lnz(i) - 1) = 0.0_wp
            end do
         end if
      end do
   end subroutine ldl_numeric_drop

   ! ---------------------------------------------------------------------------------------

   !> Validate a 1-based CSC pattern of order n.
   subroutine check_pattern(n, ap, ai, err)
      integer, intent(in) :: n
      integer, intent(in) :: ap(:), ai(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: j, q
      character(len=80) :: buf

      if (n < 0 .or. size(ap) < n + 1) then
         call make_error(err, 'sparse LDL: negative order or ap shorter than n+1')
         return
      end if
      if (ap(1) /= 1) then
         call make_error(err, 'sparse LDL: ap(1) must be 1 (1-based compressed columns)')
         return
      end if
      do j = 1, n
         if (ap(j + 1) < ap(j)) then
            write (buf, '(a,i0)') 'sparse LDL: decreasing column pointer at column ', j
            call make_error(err, trim(buf))
            return
         end if
      end do
      if (size(ai) < ap(n + 1) - 1) then
         call make_error(err, 'sparse LDL: ai shorter than ap(n+1)-1')
         return
      end if
      do q = 1, ap(n + 1) - 1
         if (ai(q) < 1 .or. ai(q) > n) then
            write (buf, '(a,i0)') 'sparse LDL: row index out of range at entry ', q
            call make_error(err, trim(buf))
            return
         end if
      end do
   end subroutine check_pattern

   !> diag(j) = sum of the stored entries (j, j) (0-based pattern, 1-based values).
   subroutine diagonal_of(n, ap, ai, ax, diag)
      integer, intent(in) :: n
      integer(c_int), intent(in) :: ap(0:n), ai(0:*)
      real(wp), intent(in) :: ax(0:*)
      real(wp), intent(out) :: diag(0:n - 1)
      integer :: j, q
      do j = 0, n - 1
         diag(j) = 0.0_wp
         do q = ap(j), ap(j + 1) - 1
            if (ai(q) == j) diag(j) = diag(j) + ax(q)
         end do
      end do
   end subroutine diagonal_of

   !> The redundancy rule at pivot k of the removal elimination (ldl_numeric_drop and
   !> exic_linalg_block_ldl): a pivot not dropped on entry is removed when its D(k) <= tol * S(k, k)
   !> (sdiag); a removed pivot gets D(k) = 1. status = 1 (and nothing else done) when a pivot not
   !> dropped is not finite, else 0.
   pure subroutine removal_rule(tol, sdiag, dk, removed, status)
      real(wp), intent(in) :: tol, sdiag
      real(wp), intent(inout) :: dk
      logical, intent(inout) :: removed
      integer, intent(out) :: status
      status = 0
      if (.not. removed) then
         if (.not. ieee_is_finite(dk)) then
            status = 1
            return
         end if
         removed = (dk <= tol*sdiag)
      end if
      if (removed) dk = 1.0_wp
   end subroutine removal_rule

end module exic_linalg_sparse_ldl
