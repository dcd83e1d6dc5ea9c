!> What the child programs of the kill tests do once they have written what the test waits for:
!> tell it through a marker file, then wait to be killed (they never close their files).
module park
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private

   public :: park_until_killed, park_until_signal

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

   !> Write `text` to the file `marker`, then sleep until `pending()` is non-zero (a signal
   !> handler has recorded a signal; sleep(3) returns early when one comes); stop with an error
   !> if none comes within 2 minutes.
   subroutine park_until_signal(marker, text, pending)
      character(len=*), intent(in) :: marker, text
      interface
         integer function pending()
         end function pending
      end interface
      integer :: u, i
      integer(c_int) :: left
      open (newunit=u, file=marker, status='replace', action='write')
      write (u, '(a)') text
      close (u)
      do i = 1, 120
         if (pending() /= 0) return
         left = c_sleep(1_c_int)
      end do
      error stop 'no signal came to this child process within 2 minutes'
   end subroutine park_until_signal

end module park
