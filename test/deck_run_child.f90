!> Child process of the "killed run" test in test_run_output.
!>
!> `deck_run_child DECK BASE` reads DECK and runs it quietly through the library, writing
!> BASE.his/.ene/.out (and .h5/.xdmf when the deck asks), as the exic command does. Started
!> without arguments (as `fpm test` does with every program under test/), it does nothing.
program deck_run_child
   use exic_base_error, only: error_t
   use exic_io_model, only: model_t
   use exic_io_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   implicit none
   type(model_t) :: model
   type(run_options_t) :: opts
   type(error_t), allocatable :: err
   character(len=4096) :: deck, base

   if (command_argument_count() /= 2) then
      print '(a)', 'deck_run_child: helper of the run output tests; nothing to do without arguments'
      stop
   end if
   call get_command_argument(1, deck)
   call get_command_argument(2, base)
   call read_deck(trim(deck), model, err)
   if (allocated(err)) error stop 2
   opts%base = trim(base)
   opts%quiet = .true.
   call run_model(model, opts, err)
   if (allocated(err)) error stop 1
end program deck_run_child
