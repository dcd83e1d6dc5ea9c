!> The exic test driver: runs every test module and prints 'N passed, M failed' last.
program exic_tests
   use testing, only: suite_t
   use test_deck, only: run_deck_tests
   implicit none
   type(suite_t) :: s

   ! each area adds one call here
   call run_deck_tests(s)
   print '(i0,a,i0,a)', s%passed, ' passed, ', s%failed, ' failed'
   if (s%failed > 0) error stop 1
end program exic_tests
