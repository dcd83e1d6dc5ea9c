!> Dense factorization of the contact operator S = G^T M^-1 G for small active sets
!> (seed eq. 4.5-4.7), with the redundancy rule of `exic_linalg_sparse_ldl`.
!>
!> Method. S is first scaled to unit diagonal, A = D S D with D = diag(S(j,j))^-1/2 (Jacobi
!> scaling: it makes the rule scale-free and improves the conditioning). Constraints with
!> S(j,j) <= 0 (a zero row: the constraint touches only immovable nodes) are removed at once.
!> Then:
!>  1. dpotrf (blocked Cholesky, no pivoting). If it succeeds and every pivot satisfies
!>     L(k,k)^2 > tol, which is D(k) > tol * S(k,k) of the unscaled LDL', the factor is kept.
!>  2. Otherwise the scaled matrix is factorized again with dpstrf, Cholesky with complete
!>     (diagonal) pivoting, stopping when the largest remaining Schur-complement diagonal is
!>     <= tol. The rank r and the pivot order it returns are the standard rank-revealing
!>     decision for a semi-definite matrix: the r accepted constraints each have a pivot
!>     D(k) > tol * S(k,k), and every rejected one has D <= tol * S(k,k) relative to the
!>     accepted set, i.e. exactly the sparse rule, applied in the most reliable order. The
!>     leading r x r block of the pivoted factor is the Cholesky factor of the reduced system.
!> An LDL' with Bunch-Kaufman pivoting (dsytrf) was not chosen: its 2x2 pivots mix
!> constraints and do not name the dependent one.
!>
!> `solve` returns the solution of the reduced system, zero on removed constraints.
module exic_linalg_dense_spd
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_linalg_lapack, only: dpotrf, dpotrs, dpstrf
   implicit none
   private

   !> Dense S lambda = r solver with redundancy detection; arrays grow, never shrink.
   type, public :: dense_spd_t
      !> Relative pivot tolerance: constraint k is redundant when D(k) <= tol * S(k,k).
      real(wp) :: tol = 1.0e-10_wp
      !> Order of the last factorized matrix, rank of its reduced system.
      integer :: n = 0, rank = 0
      !> Number of constraints removed by the last `factorize` (found redundant or dropped).
      integer :: nremoved = 0
      !> True when the last factorization needed the pivoted fallback (dpstrf).
      logical :: pivoted = .false.
      logical :: factorized = .false.
      real(wp), allocatable, private :: a(:, :), sc(:), work(:), rhs(:)
      integer, allocatable, private :: idx(:), kept(:), piv(:)
      logical, allocatable, private :: removed(:)
   contains
      procedure :: factorize => dense_factorize
      procedure :: solve => dense_solve
      procedure :: free => dense_free
   end type dense_spd_t

contains

   !> Factorize the symmetric n x n matrix s (lower triangle and diagonal are read).
   !> Redundant constraints are removed and their indices returned, ascending, in
   !> bad(1:nbad) (size(bad) = n always suffices). Constraints with drop(j) = .true. are
   !> removed beforehand and not reported.
   subroutine dense_factorize(self, s, nbad, bad, err, drop)
      class(dense_spd_t), intent(inout) :: self
      real(wp), intent(in) :: s(:, :)
      integer, intent(out) :: nbad
      integer, intent(out) :: bad(:)
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: drop(:)
      integer :: n, m, j, k, info
      logical :: ok

      nbad = 0
      self%factorized = .false.
      self%pivoted = .false.
      n = size(s, 1)
      if (size(s, 2) /= n) then
         call make_error(err, 'dense SPD: matrix is not square')
         return
      end if
      if (present(drop)) then
         if (size(drop) < n) then
            call make_error(err, 'dense SPD: drop mask shorter than the matrix order')
            return
         end if
      end if
      call grow_storage(self, n)
      self%n = n

      ! screening: dropped constraints, zero (or negative) diagonals
      m = 0
      do j = 1, n
         if (ieee_is_nan(s(j, j))) then
            call make_error(err, 'dense SPD: NaN on the diagonal')
            return
         end if
         self%removed(j) = .not. (s(j, j) > 0.0_wp)
         if (present(drop)) self%removed(j) = self%removed(j) .or. drop(j)
         if (self%removed(j)) cycle
         m = m + 1
         self%kept(m) = j
         self%sc(j) = 1.0_wp/sqrt(s(j, j))
      end do

      ! 1. plain Cholesky of the scaled matrix
      ok = .true.
      if (m > 0) then
         call scaled_copy(self, s, m, ok)
         if (.not. ok) then
            call make_error(err, 'dense SPD: non-finite entry (NaN or Inf in the matrix)')
            return
         end if
         call dpotrf('L', m, self%a, size(self%a, 1), info)
         ok = (info == 0)
         if (ok) then
            do k = 1, m
               if (.not. (self%a(k, k)**2 > self%tol)) ok = .false.
            end do
         end if
      end if
      if (ok) then
         self%rank = m
         self%idx(1:m) = self%kept(1:m)
      else
         ! 2. rank-revealing pivoted Cholesky of the same scaled matrix
         self%pivoted = .true.
         call scaled_copy(self, s, m, ok)
         call dpstrf('L', m, self%a, size(self%a, 1), self%piv, self%rank, self%tol, &
                     self%work, info)
         if (info < 0) then
            call make_error(err, 'dense SPD: dpstrf rejected its arguments')
            return
         end if
         do k = 1, self%rank
            self%idx(k) = self%kept(self%piv(k))
         end do
         do k = self%rank + 1, m
            self%removed(self%kept(self%piv(k))) = .true.
         end do
         if (.not. all_finite_diag(self%a, self%rank)) then
            call make_error(err, 'dense SPD: non-finite pivot (NaN or Inf in the matrix)')
            return
         end if
      end if

      self%nremoved = 0
      do j = 1, n
         if (.not. self%removed(j)) cycle
         self%nremoved = self%nremoved + 1
         if (present(drop)) then
            if (drop(j)) cycle
         end if
         nbad = nbad + 1
         if (nbad > size(bad)) then
            call make_error(err, 'dense SPD: bad(:) too small for the redundant constraints')
            return
         end if
         bad(nbad) = j
      end do
      self%factorized = .true.
   end subroutine dense_factorize

   !> Solve S x = b with the last factorization (x = 0 on removed constraints).
   !> stat (optional): 0 on success, 1 if not factorized, 2 if b or x is shorter than n,
   !> 3 if dpotrs failed.
   subroutine dense_solve(self, b, x, stat)
      class(dense_spd_t), intent(inout) :: self
      real(wp), intent(in) :: b(:)
      real(wp), intent(out) :: x(:)
      integer, intent(out), optional :: stat
      integer :: k, r, info

      if (present(stat)) stat = 0
      if (.not. self%factorized) then
         if (present(stat)) stat = 1
         return
      end if
      if (size(b) < self%n .or. size(x) < self%n) then
         if (present(stat)) stat = 2
         return
      end if
      r = self%rank
      x(1:self%n) = 0.0_wp
      if (r == 0) return
      do k = 1, r
         self%rhs(k) = b(self%idx(k))*self%sc(self%idx(k))
      end do
      call dpotrs('L', r, 1, self%a, size(self%a, 1), self%rhs, size(self%rhs), info)
      if (info /= 0) then
         if (present(stat)) stat = 3
         return
      end if
      do k = 1, r
         x(self%idx(k)) = self%rhs(k)*self%sc(self%idx(k))
      end do
   end subroutine dense_solve

   !> Release every array.
   subroutine dense_free(self)
      class(dense_spd_t), intent(inout) :: self
      if (allocated(self%a)) deallocate (self%a, self%sc, self%work, self%rhs, self%idx, &
                                         self%kept, self%piv, self%removed)
      self%n = 0
      self%rank = 0
      self%nremoved = 0
      self%factorized = .false.
   end subroutine dense_free

   ! ---------------------------------------------------------------------------------------

   !> a(1:m, 1:m) lower = D S D restricted to the kept constraints; finite = all entries finite.
   subroutine scaled_copy(self, s, m, finite)
      type(dense_spd_t), intent(inout) :: self
      real(wp), intent(in) :: s(:, :)
      integer, intent(in) :: m
      logical, intent(out) :: finite
      integer :: i, k, ik, kk
      finite = .true.
      do k = 1, m
         kk = self%kept(k)
         do i = k, m
            ik = self%kept(i)
            self%a(i, k) = self%sc(ik)*s(ik, kk)*self%sc(kk)
            if (.not. ieee_is_finite(self%a(i, k))) finite = .false.
         end do
      end do
   end subroutine scaled_copy

   !> Size every array for order n (grows only).
   subroutine grow_storage(self, n)
      type(dense_spd_t), intent(inout) :: self
      integer, intent(in) :: n
      integer :: cap
      if (allocated(self%a)) then
         if (size(self%a, 1) >= n) return
         deallocate (self%a, self%sc, self%work, self%rhs, self%idx, self%kept, self%piv, &
                     self%removed)
      end if
      cap = max(1, n)
      allocate (self%a(cap, cap), self%sc(cap), self%work(2*cap), self%rhs(cap), &
                self%idx(cap), self%kept(cap), self%piv(cap), self%removed(cap))
   end subroutine grow_storage

   !> True when the first r diagonal entries of a are finite.
   pure logical function all_finite_diag(a, r) result(ok)
      real(wp), intent(in) :: a(:, :)
      integer, intent(in) :: r
      integer :: k
      ok = .true.
      do k = 1, r
         if (.not. ieee_is_finite(a(k, k))) ok = .false.
      end do
   end function all_finite_diag

end module exic_linalg_dense_spd
