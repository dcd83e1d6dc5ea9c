!> Kernels on whole arrays taken as flat runs of values (explicit-shape dummies of n values, so
!> one vector loop whatever the rank of the caller's array). The field writer copies an output
!> time's (2, nnode) and (ncomp, nelem) arrays into its batch with them: an assignment of a
!> (2, nnode) array loops twice over a dimension of 2 per node (about 15 instructions a value
!> in gfortran's code). `all_finite` is the check that no NaN or infinity is written as a
!> result and that the sparse LDL' pivots are finite; `ieee_is_finite` per element is a call
!> (about 27 instructions a value), this a compare and a count.
module exic_base_flat
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: all_finite, copy_flat, copy_flat_int, sum_flat

contains

   !> True when every x(1:n) is finite: |x| <= huge is false for an infinity and for NaN.
   pure logical function all_finite(n, x) result(ok)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      integer :: k, bad
      bad = 0
      do k = 1, n
         bad = bad + merge(1, 0, .not. (abs(x(k)) <= huge(1.0_wp)))
      end do
      ok = bad == 0
   end function all_finite

   !> y(1:n) = x(1:n).
   pure subroutine copy_flat(n, x, y)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n)
      real(wp), intent(out) :: y(n)
      y = x
   end subroutine copy_flat

   !> y(1:n) = x(1:n), integer values (a pass's candidate pairs, src/exic/contact/broad_all.f90).
   pure subroutine copy_flat_int(n, x, y)
      integer, intent(in) :: n
      integer, intent(in) :: x(n)
      integer, intent(out) :: y(n)
      y = x
   end subroutine copy_flat_int

   !> z(1:n) = x(1:n) + y(1:n).
   pure subroutine sum_flat(n, x, y, z)
      integer, intent(in) :: n
      real(wp), intent(in) :: x(n), y(n)
      real(wp), intent(out) :: z(n)
      z = x + y
   end subroutine sum_flat

end module exic_base_flat
