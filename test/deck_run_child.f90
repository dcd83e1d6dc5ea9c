!> Child process of the "killed run" test in test_run_output.
!>
!> `deck_run_child DECK BASE` reads DECK and runs it quietly through the library, writing
!> BASE.his/.ene/.out (and .h5/.xdmf when the deck asks), as the exic command does.
!> `deck_run_child DECK BASE N MARKER` does the same but, once N field output times are written
!> and flushed, creates the file MARKER and waits (up to 2 minutes) without closing anything,
!> so that the test can kill it at a known point. Started without arguments (as `fpm test`
!> does with every program under test/), it does nothing.
program deck_run_child
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_io_model, only: model_t
   use exic_io_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   use park, only: park_until_killed
   implicit none

   type(model_t) :: model
   type(run_options_t) :: opts
   type(error_t), allocatable :: err
   character(len=4096) :: deck, base, arg, marker
   integer :: park_after, ios

   call get_command_argument(1, deck)
   if ((command_argument_count() /= 2 .and. command_argument_count() /= 4) .or. &
       index(deck, '.inp', back=.true.) /= max(1, len_trim(deck) - 3)) then
      ! (fpm test -- words passes the suite words to every test program: they are no deck)
      print '(a)', 'deck_run_child: helper of the run output tests; nothing to do without arguments'
      stop
   end if
   call get_command_argument(1, deck)
   call get_command_argument(2, base)
   park_after = 0
   if (command_argument_count() == 4) then
      call get_command_argument(3, arg)
      read (arg, *, iostat=ios) park_after
      if (ios /= 0) error stop 'deck_run_child: N must be an integer'
      call get_command_argument(4, marker)
      opts%on_fields => park
   end if
   call read_deck(trim(deck), model, err)
   if (allocated(err)) error stop 2
   opts%base = trim(base)
   opts%quiet = .true.
   call run_model(model, opts, err)
   if (allocated(err)) error stop 1

contains

   !> After the N-th field output time: tell the test through MARKER, then wait to be killed.
   subroutine park(count, t)
      integer, intent(in) :: count
      real(wp), intent(in) :: t
      character(len=64) :: text
      if (count < park_after) return
      write (text, '(i0,1x,es24.16e3)') count, t
      call park_until_killed(trim(marker), trim(text))
   end subroutine park

end program deck_run_child
