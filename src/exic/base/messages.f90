!> Messages a lower layer hands up to whoever writes the run's report.
!>
!> The time step (src/exic/explicit) must not write files; what it has to say (a warning that
!> the fixed step exceeds the stable estimate, ...) it adds here, and the driver moves the
!> pending lines into <stem>.out after the step. Adding costs nothing when nothing is said.
module exic_base_messages
   implicit none
   private

   public :: messages_t

   !> Pending lines of text, newline separated.
   type :: messages_t
      character(len=:), allocatable :: text
      integer :: count = 0                  !< lines pending
   contains
      procedure :: add => messages_add
      procedure :: take => messages_take
   end type messages_t

contains

   !> Append one line.
   subroutine messages_add(self, line)
      class(messages_t), intent(inout) :: self
      character(len=*), intent(in) :: line
      if (self%count == 0) then
         self%text = line
      else
         self%text = self%text//new_line('a')//line
      end if
      self%count = self%count + 1
   end subroutine messages_add

   !> The pending lines (newline separated; empty when none) and forget them.
   function messages_take(self) result(text)
      class(messages_t), intent(inout) :: self
      character(len=:), allocatable :: text
      if (self%count == 0) then
         text = ''
      else
         call move_alloc(self%text, text)
      end if
      self%count = 0
   end function messages_take

end module exic_base_messages
