!> Child process of the "killed run" test in test_run_output.
!>
!> `deck_run_child --child DECK BASE` reads DECK and runs it quietly through the library, writing
!> BASE.his/.ene/.out (and .h5/.xdmf when the deck asks), as the exic command does.
!> `deck_run_child --child DECK BASE N MARKER` does the same but, once at least N field output times
!> are flushed into the .h5 (at the first flush that reaches N: output times are written in batches,
!> doc/fields.md), creates the file MARKER (the count flushed and the time of the last) and waits
!> (up to 2 minutes) without closing anything,
!> so that the test can kill it at a known point. `deck_run_child --child DECK BASE N MARKER
!> signals` answers signals as the exic command does and, once N field output times are flushed,
!> creates MARKER and waits until a signal comes, then goes on (the run then meets the signal at
!> the end of its next step: a known point too); exit code 3 when SIGINT or SIGTERM stopped it.
!> Without `--child` first (as `fpm test` starts
!> every program under test/, with the suite words given to it), it does nothing.
program deck_run_child
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model, RUN_INTERRUPTED
   use exic_base_signals, only: signals_peek
   use park, only: park_until_killed, park_until_signal
   implicit none

   type(model_t) :: model
   type(run_options_t) :: opts
   type(error_t), allocatable :: err
   character(len=4096) :: deck, base, arg, marker
   integer :: park_after, ios, status
   logical :: on_signal, parked = .false.

   call get_command_argument(1, arg)
   if (arg /= '--child' .or. command_argument_count() < 3 .or. command_argument_count() > 6 .or. &
       command_argument_count() == 4) then
      print '(a)', 'deck_run_child: helper of the run output tests; nothing to do without --child'
      stop
   end if
   call get_command_argument(2, deck)
   call get_command_argument(3, base)
   park_after = 0
   if (command_argument_count() >= 5) then
      call get_command_argument(4, arg)
      read (arg, *, iostat=ios) park_after
      if (ios /= 0) error stop 'deck_run_child: N must be an integer'
      call get_command_argument(5, marker)
      opts%on_fields => park
   end if
   on_signal = .false.
   if (command_argument_count() == 6) then
      call get_command_argument(6, arg)
      if (arg /= 'signals') error stop 'deck_run_child: the sixth argument can only be "signals"'
      on_signal = .true.
      opts%signals = .true.
   end if
   call read_deck(trim(deck), model, err)
   if (allocated(err)) error stop 2
   opts%base = trim(base)
   opts%quiet = .true.
   call run_model(model, opts, err, status)
   if (allocated(err)) error stop 1
   if (status == RUN_INTERRUPTED) stop 3

contains

   !> At the first flush that holds N field output times or more: tell the test through MARKER
   !> (the count and the time of the last), then wait to be killed, or for a signal.
   subroutine park(count, t)
      integer, intent(in) :: count
      real(wp), intent(in) :: t
      character(len=64) :: text
      if (count < park_after .or. parked) return
      parked = .true.
      write (text, '(i0,1x,es24.16e3)') count, t
      if (on_signal) then
         call park_until_signal(trim(marker), trim(text), signals_peek)
      else
         call park_until_killed(trim(marker), trim(text))
      end if
   end subroutine park

end program deck_run_child
