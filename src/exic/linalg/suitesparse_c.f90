!> Raw C interfaces to SuiteSparse LDL and AMD (the `int` variants, 0-based indices).
!>
!> Prototypes follow /usr/include/suitesparse/ldl.h and amd.h. Every integer array is
!> `int` (c_int) and every index is 0-based. Use `exic_linalg_sparse_ldl` rather than
!> calling these directly: it owns the work arrays and checks the status codes.
module exic_linalg_suitesparse_c
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   implicit none
   private

   public :: ldl_symbolic, ldl_numeric, ldl_lsolve, ldl_dsolve, ldl_ltsolve, ldl_perm, ldl_permt
   public :: amd_order, amd_defaults

   !> Size of the AMD Control array (AMD_CONTROL).
   integer, parameter, public :: amd_control_size = 5
   !> Size of the AMD Info array (AMD_INFO).
   integer, parameter, public :: amd_info_size = 20
   !> AMD return codes.
   integer(c_int), parameter, public :: amd_ok = 0_c_int, amd_out_of_memory = -1_c_int, &
      amd_invalid = -2_c_int, amd_ok_but_jumbled = 1_c_int

   interface

      !> Elimination tree, column counts and Lp of P A P^T (upper part used; P, Pinv given).
      subroutine ldl_symbolic(n, ap, ai, lp, parent, lnz, flag, p, pinv) bind(C, name='ldl_symbolic')
         import :: c_int
         integer(c_int), value :: n
         integer(c_int), intent(in) :: ap(*), ai(*), p(*)
         integer(c_int), intent(out) :: lp(*), parent(*), lnz(*), flag(*), pinv(*)
      end subroutine ldl_symbolic

      !> Numeric LDL' of P A P^T; returns n on success, else the 0-based row k with D(k) == 0.
      function ldl_numeric(n, ap, ai, ax, lp, parent, lnz, li, lx, d, y, pattern, flag, p, pinv) &
         result(k) bind(C, name='ldl_numeric')
         import :: c_int, c_double
         integer(c_int), value :: n
         integer(c_int), intent(in) :: ap(*), ai(*), lp(*), parent(*), p(*), pinv(*)
         real(c_double), intent(in) :: ax(*)
         integer(c_int), intent(inout) :: lnz(*), li(*), pattern(*), flag(*)
         real(c_double), intent(inout) :: lx(*), d(*), y(*)
         integer(c_int) :: k
      end function ldl_numeric

      !> Solve L x = b in place (unit lower L).
      subroutine ldl_lsolve(n, x, lp, li, lx) bind(C, name='ldl_lsolve')
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(inout) :: x(*)
         integer(c_int), intent(in) :: lp(*), li(*)
         real(c_double), intent(in) :: lx(*)
      end subroutine ldl_lsolve

      !> Solve D x = b in place.
      subroutine ldl_dsolve(n, x, d) bind(C, name='ldl_dsolve')
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(inout) :: x(*)
         real(c_double), intent(in) :: d(*)
      end subroutine ldl_dsolve

      !> Solve L' x = b in place.
      subroutine ldl_ltsolve(n, x, lp, li, lx) bind(C, name='ldl_ltsolve')
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(inout) :: x(*)
         integer(c_int), intent(in) :: lp(*), li(*)
         real(c_double), intent(in) :: lx(*)
      end subroutine ldl_ltsolve

      !> x(k) = b(P(k)) (0-based P).
      subroutine ldl_perm(n, x, b, p) bind(C, name='ldl_perm')
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(out) :: x(*)
         real(c_double), intent(in) :: b(*)
         integer(c_int), intent(in) :: p(*)
      end subroutine ldl_perm

      !> x(P(k)) = b(k) (0-based P).
      subroutine ldl_permt(n, x, b, p) bind(C, name='ldl_permt')
         import :: c_int, c_double
         integer(c_int), value :: n
         real(c_double), intent(out) :: x(*)
         real(c_double), intent(in) :: b(*)
         integer(c_int), intent(in) :: p(*)
      end subroutine ldl_permt

      !> Approximate minimum degree ordering of A + A^T; returns an AMD status code.
      function amd_order(n, ap, ai, p, control, info) result(status) bind(C, name='amd_order')
         import :: c_int, c_double
         integer(c_int), value :: n
         integer(c_int), intent(in) :: ap(*), ai(*)
         integer(c_int), intent(out) :: p(*)
         real(c_double), intent(in) :: control(*)
         real(c_double), intent(out) :: info(*)
         integer(c_int) :: status
      end function amd_order

      !> Default AMD control settings.
      subroutine amd_defaults(control) bind(C, name='amd_defaults')
         import :: c_double
         real(c_double), intent(out) :: control(*)
      end subroutine amd_defaults

   end interface

end module exic_linalg_suitesparse_c
