!> LDL' with removal of one small diagonal block of the contact operator S, eliminated in its
!> natural order (doc/contact-detection.md, "Components of S", eq. D.4-D.6).
!>
!> The block is held by the upper triangles of its columns, packed (entry (i, k), i <= k, at
!> k(k-1)/2 + i), with a structural mask: an entry is in the pattern when the assembly wrote it,
!> whatever its value. The factorisation is the up-looking elimination of SuiteSparse LDL (Davis,
!> "Algorithm 849: a concise sparse Cholesky factorization package", ACM TOMS 31, 2005;
!> ldl_symbolic and ldl_numeric) with the removal rule of exic_linalg_sparse_ldl
!> (`ldl_numeric_drop`, the same `removal_rule`): the elimination tree, the pattern of each row of
!> L in the topological order of its tree walk, the columns of L in the order their entries are
!> appended, and every floating-point operation in the same order as that routine and LDL's
!> ldl_lsolve / ldl_dsolve / ldl_ltsolve. A block of a matrix whose P S P^T is block diagonal
!> (eq. D.4) therefore gets the same L, D and solution, to the bit, as the sparse factorisation of
!> the whole matrix in that order (eq. D.5), without its global index arrays, pattern checks and
!> symbolic analysis of all of S.
!>
!> Redundancy rule (as sparse_ldl): pivot k is removed when it is dropped by the caller or
!> when D(k) <= tol * S(k, k); a removed pivot gets D(k) = 1, a zero row in L, and zero
!> entries below it, and its unknown is 0 in the solve.
module exic_linalg_block_ldl
   use exic_base_kinds, only: wp
   use exic_linalg_sparse_ldl, only: removal_rule
   implicit none
   private

   public :: block_ldl_factor, block_ldl_solve

contains

   !> Factorise the nb x nb block whose columns' upper triangles s (entries S(i, k), i <= k, of
   !> column k as assembled, packed) are structural where nz is set, in natural order. On entry
   !> removed(k) marks the pivots the caller drops; on return it also marks those the rule
   !> rejected. L is returned by columns: column i holds lcnt(i) entries, rows lrow(1:lcnt(i), i)
   !> (ascending) with values lx(1:lcnt(i), i); d(nb) the pivots. iwork(3 nb), y(nb): work.
   !> status = 0, or 1 on a non-finite pivot.
   subroutine block_ldl_factor(nb, s, nz, tol, removed, lcnt, lrow, lx, d, iwork, y, status)
      integer, intent(in) :: nb
      real(wp), intent(in) :: s(*)
      logical, intent(in) :: nz(*)
      real(wp), intent(in) :: tol
      logical, intent(inout) :: removed(nb)
      integer, intent(out) :: lcnt(nb), lrow(nb, nb)
      real(wp), intent(out) :: lx(nb, nb), d(nb)
      integer, intent(out) :: iwork(nb, 3)
      real(wp), intent(out) :: y(nb)
      integer, intent(out) :: status
      integer :: k, i, ii, len, top, t, q, col
      real(wp) :: yi, lki, sdiag

      status = 0
      ! iwork: parent (elimination tree), flag, pattern
      associate (parent => iwork(:, 1), flag => iwork(:, 2), pattern => iwork(:, 3))
      ! numeric factorisation (ldl_numeric_drop, identity order), with the elimination tree of
      ! ldl_symbolic formed on the way: the tree walk of row k from an entry (i, k) visits the
      ! nodes ldl_symbolic's walk visits, and a node without a parent yet has k as its parent.
      ! Nothing is set beforehand: row k sets parent(k), lcnt(k), flag(k) and y(k) before any
      ! later row reads them, and leaves every y(i), i <= k, it touched at zero again
      do k = 1, nb
         ! pattern of row k of L in topological order: the tree walk from each entry of
         ! column k in ascending row order, each walk kept in its order, later walks first
         parent(k) = 0
         lcnt(k) = 0
         y(k) = 0.0_wp
         top = nb + 1
         flag(k) = k
         col = ((k - 1)*k)/2
         do i = 1, k
            if (.not. nz(col + i)) cycle
            y(i) = y(i) + s(col + i)
            len = 0
            ii = i
            do while (flag(ii) /= k)
               len = len + 1
               pattern(len) = ii
               flag(ii) = k
               if (parent(ii) == 0) parent(ii) = k
               ii = parent(ii)
            end do
            do while (len > 0)
               top = top - 1
               pattern(top) = pattern(len)
               len = len - 1
            end do
         end do
         ! values of row k (sparse triangular solve)
         sdiag = y(k)
         d(k) = y(k)
         y(k) = 0.0_wp
         do t = top, nb
            i = pattern(t)
            yi = y(i)
            y(i) = 0.0_wp
            do q = 1, lcnt(i)
               y(lrow(q, i)) = y(lrow(q, i)) - lx(q, i)*yi
            end do
            lki = 0.0_wp
            if (.not. removed(i)) lki = yi/d(i)
            d(k) = d(k) - lki*yi
            lcnt(i) = lcnt(i) + 1
            lrow(lcnt(i), i) = k
            lx(lcnt(i), i) = lki
         end do
         call removal_rule(tol, sdiag, d(k), removed(k), status)
         if (status /= 0) return
         if (removed(k)) then
            do t = top, nb
               i = pattern(t)
               lx(lcnt(i), i) = 0.0_wp
            end do
         end if
      end do
      end associate
   end subroutine block_ldl_factor

   !> Solve the factorised block for x (overwritten in place: b on entry), with x = 0 on the
   !> removed pivots: forward (ldl_lsolve), diagonal (ldl_dsolve), removed unknowns zeroed,
   !> backward (ldl_ltsolve).
   pure subroutine block_ldl_solve(nb, lcnt, lrow, lx, d, removed, x)
      integer, intent(in) :: nb
      integer, intent(in) :: lcnt(nb), lrow(nb, nb)
      real(wp), intent(in) :: lx(nb, nb), d(nb)
      logical, intent(in) :: removed(nb)
      real(wp), intent(inout) :: x(nb)
      integer :: j, q
      do j = 1, nb
         do q = 1, lcnt(j)
            x(lrow(q, j)) = x(lrow(q, j)) - lx(q, j)*x(j)
         end do
      end do
      do j = 1, nb
         x(j) = x(j)/d(j)
      end do
      do j = 1, nb
         if (removed(j)) x(j) = 0.0_wp
      end do
      do j = nb, 1, -1
         do q = 1, lcnt(j)
            x(j) = x(j) - lx(q, j)*x(lrow(q, j))
         end do
      end do
   end subroutine block_ldl_solve

end module exic_linalg_block_ldl
