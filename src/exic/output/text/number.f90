!> Rows of numbers as text without Fortran's formatted-output machinery per value: reals as the
!> `1x,es24.16e3` edit descriptor writes them (NUMBER_FORMAT of exic_output_text_history, the same
!> characters), integers as `iw`. A row is assembled in a character buffer and written with one
!> `(a)` record. The real's digits come from std::to_chars in src/exic/output/text/number_cxx.cpp (the
!> same correctly rounded digits as the snprintf libgfortran uses); doc/performance.md, sections 2
!> and 6.5, give the saving.
module exic_output_text_number
   use, intrinsic :: iso_c_binding, only: c_double, c_char
   use exic_base_kinds, only: wp, i8
   implicit none
   private

   public :: put_real, put_int, REAL_WIDTH

   !> Characters of one real: a blank and 24.
   integer, parameter :: REAL_WIDTH = 25

   interface
      subroutine c_es24_16e3(x, out) bind(C, name='exic_c_es24_16e3')
         import :: c_double, c_char
         real(c_double), value :: x
         character(kind=c_char), intent(out) :: out(*)
      end subroutine c_es24_16e3
   end interface

contains

   !> Append x (finite) as `1x,es24.16e3` to line(1:n); n grows by REAL_WIDTH.
   subroutine put_real(line, n, x)
      character(len=*), intent(inout) :: line
      integer, intent(inout) :: n
      real(wp), intent(in) :: x
      call c_es24_16e3(real(x, c_double), line(n + 1:n + REAL_WIDTH))
      n = n + REAL_WIDTH
   end subroutine put_real

   !> Append k as `iw` (right-justified in w characters, asterisks when it does not fit) to
   !> line(1:n); n grows by w.
   subroutine put_int(line, n, k, w)
      character(len=*), intent(inout) :: line
      integer, intent(inout) :: n
      integer(i8), intent(in) :: k
      integer, intent(in) :: w
      character(len=24) :: d
      integer :: p
      integer(i8) :: m
      m = abs(k)
      p = len(d) + 1
      do
         p = p - 1
         d(p:p) = achar(iachar('0') + int(mod(m, 10_i8)))
         m = m/10_i8
         if (m == 0) exit
      end do
      if (k < 0) then
         p = p - 1
         d(p:p) = '-'
      end if
      if (len(d) - p + 1 > w) then
         line(n + 1:n + w) = repeat('*', w)
      else
         line(n + 1:n + w) = repeat(' ', w - (len(d) - p + 1))//d(p:)
      end if
      n = n + w
   end subroutine put_int

end module exic_output_text_number
