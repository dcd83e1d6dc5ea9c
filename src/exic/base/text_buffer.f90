!> Text gathered piece by piece into one buffer that doubles when full: n pieces of a report
!> cost O(total length), where `text = text//piece` copies the text once per piece (a contact
!> summary of thousands of surfaces spent most of a run in such copies).
module exic_base_text_buffer
   implicit none
   private

   public :: text_buffer_t

   type :: text_buffer_t
      character(len=:), allocatable, private :: buf
      integer, private :: n = 0
   contains
      procedure :: add => text_buffer_add
      procedure :: text => text_buffer_text
   end type text_buffer_t

contains

   !> Append `piece`.
   subroutine text_buffer_add(self, piece)
      class(text_buffer_t), intent(inout) :: self
      character(len=*), intent(in) :: piece
      character(len=:), allocatable :: tmp
      if (.not. allocated(self%buf)) allocate (character(len=max(4096, len(piece))) :: self%buf)
      if (self%n + len(piece) > len(self%buf)) then
         allocate (character(len=max(2*len(self%buf), self%n + len(piece))) :: tmp)
         tmp(1:self%n) = self%buf(1:self%n)
         call move_alloc(tmp, self%buf)
      end if
      self%buf(self%n + 1:self%n + len(piece)) = piece
      self%n = self%n + len(piece)
   end subroutine text_buffer_add

   !> Everything appended so far.
   function text_buffer_text(self) result(text)
      class(text_buffer_t), intent(in) :: self
      character(len=:), allocatable :: text
      if (allocated(self%buf)) then
         text = self%buf(1:self%n)
      else
         text = ''
      end if
   end function text_buffer_text

end module exic_base_text_buffer
