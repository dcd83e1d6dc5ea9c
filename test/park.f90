!> What the child programs of the kill tests do once they have written what the test waits for:
!> tell it through a marker file, then wait to be killed (they never close their files).
module park
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private

   public :: park_until_killed

   interface
      !> unsigned int sleep(unsigned int seconds);
      function c_sleep(seconds) bind(C, name='sleep') result(left)
         import :: c_int
         integer(c_int), value :: seconds
         integer(c_int) :: left
      end function c_sleep
   end interface

contains

   !> Write `text` to the file `marker`, then sleep; stop with an error if nobody kills the
   !> process within 2 minutes.
   subroutine park_until_killed(marker, text)
      character(len=*), intent(in) :: marker, text
      integer :: u, i
      integer(c_int) :: left
      open (newunit=u, file=marker, status='replace', action='write')
      write (u, '(a)') text
      close (u)
      do i = 1, 120
         left = c_sleep(1_c_int)
      end do
      error stop 'nobody killed this child process within 2 minutes'
   end subroutine park_until_killed

end module park
