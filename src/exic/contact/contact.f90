!> Contact in the time step: surfaces, search and the implicit corrector (seed sections 3-6).
module exic_contact_contact
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_model, only: model_t
   use exic_explicit_state, only: state_t
   use exic_io_history, only: history_files_t
   implicit none
   private

   public :: contact_t

   !> All contact pairs of a model. Inactive (no work at all) when the deck has no CONTact block.
   type :: contact_t
      logical :: active = .false.
   contains
      procedure :: init => contact_init
      procedure :: correct => contact_correct
      procedure :: pair_value => contact_pair_value
      procedure :: describe => contact_describe
   end type contact_t

contains

   !> Build surfaces and pairs from the model's contact block.
   subroutine contact_init(self, model, st, err)
      class(contact_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(state_t), intent(in) :: st
      type(error_t), allocatable, intent(out) :: err
      self%active = model%contact%active
      if (self%active) call make_error(err, 'CONTact is not available in this build')
      if (.false.) print *, st%nnode
   end subroutine contact_init

   !> Correct the predicted accelerations st%a so that active gaps close at t(n+2).
   subroutine contact_correct(self, st, vt, err)
      class(contact_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      real(wp), intent(in) :: vt(:, :)
      type(error_t), allocatable, intent(out) :: err
      if (.not. self%active) then
         st%nactive = 0
         return
      end if
      if (.false.) print *, vt(1, 1)
   end subroutine contact_correct

   !> A TPLOt `cont,pair,comp` value.
   real(wp) function contact_pair_value(self, pair, comp) result(val)
      class(contact_t), intent(in) :: self
      integer, intent(in) :: pair, comp
      val = 0.0_wp
      if (.not. self%active .or. pair < 0 .or. comp < 0) return
   end function contact_pair_value

   !> Surfaces and pairs in <stem>.out.
   subroutine contact_describe(self, files)
      class(contact_t), intent(in) :: self
      type(history_files_t), intent(inout) :: files
      if (.not. self%active) call files%say('contact: none')
   end subroutine contact_describe

end module exic_contact_contact
