!> Signals a run answers (README, "Signals and exit codes"): SIGINT and SIGTERM stop the run
!> after the current step with its final state and a restart file, SIGUSR1 writes a restart
!> file and the run goes on, SIGUSR2 prints a status line.
!>
!> The handlers (signals_c.c next to this file) only record that a signal came; the run asks
!> `signals_take` once per step and does the work there, outside the handler.
module exic_base_signals
   use, intrinsic :: iso_c_binding, only: c_int
   implicit none
   private

   public :: signals_install, signals_take, signals_peek, ignore_file_size_signal

   !> Bits of `signals_take`.
   integer, parameter, public :: SIG_BIT_INT = 1, SIG_BIT_TERM = 2, SIG_BIT_USR1 = 4, SIG_BIT_USR2 = 8

   interface
      function c_signals_install() bind(C, name='exic_c_signals_install') result(status)
         import :: c_int
         integer(c_int) :: status
      end function c_signals_install

      function c_signals_take() bind(C, name='exic_c_signals_take') result(bits)
         import :: c_int
         integer(c_int) :: bits
      end function c_signals_take

      function c_signals_peek() bind(C, name='exic_c_signals_peek') result(bits)
         import :: c_int
         integer(c_int) :: bits
      end function c_signals_peek

      function c_ignore_sigxfsz() bind(C, name='exic_c_ignore_sigxfsz') result(status)
         import :: c_int
         integer(c_int) :: status
      end function c_ignore_sigxfsz
   end interface

contains

   !> Install the handlers of SIGINT, SIGTERM, SIGUSR1 and SIGUSR2; false when that fails.
   logical function signals_install() result(ok)
      ok = c_signals_install() == 0_c_int
   end function signals_install

   !> The signals received since the last call (SIG_BIT_* added up), then forgotten.
   integer function signals_take() result(bits)
      bits = int(c_signals_take())
   end function signals_take

   !> The signals received and not yet taken (SIG_BIT_* added up); they stay pending.
   integer function signals_peek() result(bits)
      bits = int(c_signals_peek())
   end function signals_peek

   !> Ignore SIGXFSZ, so that a write past the file size limit fails (EFBIG) and is reported
   !> like a full disk instead of killing the process.
   subroutine ignore_file_size_signal()
      integer(c_int) :: st
      st = c_ignore_sigxfsz()
   end subroutine ignore_file_size_signal

end module exic_base_signals
