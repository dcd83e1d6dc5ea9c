!> Everything a deck defines: mesh, materials, contact, solution program and requests.
module exic_model_model
   use exic_base_kinds, only: wp
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t
   use exic_contact_spec, only: contact_spec_t
   use exic_model_program, only: command_t, request_t
   use exic_explicit_loads, only: load_spec_t
   implicit none
   private

   public :: model_t

   !> A problem as read from a deck.
   type :: model_t
      character(len=:), allocatable :: title
      character(len=:), allocatable :: deck_file       !< path of the deck as given
      type(mesh_t) :: mesh
      type(material_t), allocatable :: materials(:)    !< indexed by material set number
      type(contact_spec_t) :: contact
      type(load_spec_t) :: loads                       !< loads and prescribed motion (doc/loads.md)
      type(command_t), allocatable :: program(:)       !< BATCh commands in order
      type(request_t), allocatable :: requests(:)      !< TPLOt requests in order
      character(len=:), allocatable :: restart_file    !< BATCh RESTart,file: continue from it
      character(len=:), allocatable :: echo            !< the deck's records, for <stem>.out
      character(len=:), allocatable :: warnings        !< reader warnings, newline separated
   end type model_t

end module exic_model_model
