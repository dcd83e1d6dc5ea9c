!> The layering of src/exic (doc/architecture.md): no folder uses a folder above it, no file is
!> over 800 lines. tools/check_layers.py does the reading; it must also fail on a tree that
!> breaks the rule.
module test_layers
   use testing, only: suite_t, check, section, skip, have_command, python_command
   implicit none
   private

   public :: run_layers_tests

   character(len=*), parameter :: fake = 'build/test_layers/exic'

contains

   subroutine run_layers_tests(s)
      type(suite_t), intent(inout) :: s
      integer :: code, u
      call section(s, 'layers: every use points down (tools/check_layers.py)')
      if (.not. have_command('python3')) then
         call skip(s, 'layering of src/exic', 'python3', 2)
         return
      end if
      call execute_command_line(python_command()//' tools/check_layers.py > build/test_layers.log 2>&1', &
                                exitstat=code)
      call check(s, code == 0, 'src/exic: no folder uses one above it, no file over 800 lines', &
                 'see build/test_layers.log')
      ! a tree whose base module uses input must be refused
      call execute_command_line('mkdir -p '//fake//'/base '//fake//'/input')
      open (newunit=u, file=fake//'/base/kinds.f90', status='replace', action='write')
      write (u, '(a)') 'module exic_base_kinds', '   use exic_input_deck, only: read_deck', 'end module exic_base_kinds'
      close (u)
      open (newunit=u, file=fake//'/input/deck.f90', status='replace', action='write')
      write (u, '(a)') 'module exic_input_deck', '   use exic_base_kinds', 'end module exic_input_deck'
      close (u)
      call execute_command_line(python_command()//' tools/check_layers.py --root '//fake// &
                                ' > build/test_layers_fake.log 2>&1', exitstat=code)
      call check(s, code == 1, 'a base module that uses input is refused')
   end subroutine run_layers_tests

end module test_layers
