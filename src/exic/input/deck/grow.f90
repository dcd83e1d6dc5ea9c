!> Growth of the arrays of lower layers' derived types that the deck reader fills record by
!> record (materials, contact surfaces and pairs, load functions, program commands, output
!> requests): specifics of the generic `grow` of exic_base_grow, which a caller uses together
!> with that module's (the two generic interfaces merge). The types the reader owns grow in
!> their own modules (records.f90, mesh.f90, loads.f90).
module exic_input_deck_grow
   use exic_base_grow, only: grow_size
   use exic_material_material, only: material_t
   use exic_contact_spec, only: surface_spec_t, pair_spec_t
   use exic_explicit_loads, only: prop_fn_t
   use exic_model_program, only: command_t, request_t
   implicit none
   private

   public :: grow

   interface grow
      module procedure grow_material, grow_surface_spec, grow_pair_spec, grow_prop_fn, grow_command, grow_request
   end interface grow

contains

   !> grow (exic_base_grow) for an array of material_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_material(a, n, exact)
      type(material_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(material_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_material

   !> grow (exic_base_grow) for an array of surface_spec_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_surface_spec(a, n, exact)
      type(surface_spec_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(surface_spec_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_surface_spec

   !> grow (exic_base_grow) for an array of pair_spec_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_pair_spec(a, n, exact)
      type(pair_spec_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(pair_spec_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_pair_spec

   !> grow (exic_base_grow) for an array of prop_fn_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_prop_fn(a, n, exact)
      type(prop_fn_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(prop_fn_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_prop_fn

   !> grow (exic_base_grow) for an array of command_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_command(a, n, exact)
      type(command_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(command_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_command

   !> grow (exic_base_grow) for an array of request_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_request(a, n, exact)
      type(request_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(request_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_request

end module exic_input_deck_grow
