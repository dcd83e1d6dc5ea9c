!> Explicit interfaces to the LAPACK routines exic uses (double precision, default integer).
!>
!> fpm rejects implicit interfaces, so every LAPACK call goes through this module.
module exic_linalg_lapack
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: dpotrf, dpotrs, dpstrf, dsyev, dsygv

   interface

      !> Cholesky factorization of a symmetric positive definite matrix.
      subroutine dpotrf(uplo, n, a, lda, info)
         import :: wp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda
         real(wp), intent(inout) :: a(lda, *)
         integer, intent(out) :: info
      end subroutine dpotrf

      !> Solve A X = B with the Cholesky factor from dpotrf.
      subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
         import :: wp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, nrhs, lda, ldb
         real(wp), intent(in) :: a(lda, *)
         real(wp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dpotrs

      !> Cholesky factorization with complete pivoting of a positive semi-definite matrix.
      subroutine dpstrf(uplo, n, a, lda, piv, rank, tol, work, info)
         import :: wp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda
         real(wp), intent(inout) :: a(lda, *)
         integer, intent(out) :: piv(*), rank
         real(wp), intent(in) :: tol
         real(wp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dpstrf

      !> Eigenvalues (and optionally eigenvectors) of a symmetric matrix.
      subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
         import :: wp
         character(len=1), intent(in) :: jobz, uplo
         integer, intent(in) :: n, lda, lwork
         real(wp), intent(inout) :: a(lda, *)
         real(wp), intent(out) :: w(*)
         real(wp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dsyev

      !> Generalized symmetric-definite eigenproblem A x = lambda B x (itype 1..3).
      subroutine dsygv(itype, jobz, uplo, n, a, lda, b, ldb, w, work, lwork, info)
         import :: wp
         integer, intent(in) :: itype, n, lda, ldb, lwork
         character(len=1), intent(in) :: jobz, uplo
         real(wp), intent(inout) :: a(lda, *), b(ldb, *)
         real(wp), intent(out) :: w(*)
         real(wp), intent(inout) :: work(*)
         integer, intent(out) :: info
      end subroutine dsygv

   end interface

end module exic_linalg_lapack
