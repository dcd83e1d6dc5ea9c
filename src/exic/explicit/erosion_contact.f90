!> The contact surfaces after an erosion (doc/erosion.md, section 4): the surfaces built from
!> elements (AUTOmatic, SURFace REGIon, SURFace MATErial) are built again from the free edges of
!> the live elements, so that the edges an erosion exposes take part in the search of the same
!> step. SURFace FACEts and NODEs surfaces are explicit lists and stay as given. The run's contact
!> state (statistics, friction state and dissipation, pair histories, search depth) carries over.
module exic_explicit_erosion_contact
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_mesh_mesh, only: mesh_t
   use exic_contact_spec, only: contact_spec_t
   use exic_contact_contact, only: contact_t
   use exic_explicit_state, only: state_t
   implicit none
   private

   public :: erosion_contact_t, erosion_contact_init, erosion_contact_rebuild

   !> What rebuilding the surfaces needs: the CONTact block and the mesh's elements.
   type :: erosion_contact_t
      logical :: on = .false.
      type(contact_spec_t) :: spec
      integer, allocatable :: conn(:, :), region(:), mat(:)
      real(wp) :: modulus = 0.0_wp
   end type erosion_contact_t

contains

   !> Keep the CONTact block and elements of a model whose materials erode; massless contact
   !> faces (LAGRange,ENERgy) with erosion are refused (their face block is built once).
   subroutine erosion_contact_init(ec, spec, mesh, modulus, err)
      type(erosion_contact_t), intent(out) :: ec
      type(contact_spec_t), intent(in) :: spec
      type(mesh_t), intent(in) :: mesh
      real(wp), intent(in) :: modulus
      type(error_t), allocatable, intent(out) :: err
      integer :: k
      if (.not. spec%active) return
      if (allocated(spec%pairs)) then
         do k = 1, size(spec%pairs)
            if (spec%pairs(k)%energy) then
               call make_error(err, 'EROSion with LAGRange,ENERgy (massless contact faces) is not '// &
                               'supported: expected LAGRange without ENERgy, or no EROSion')
               return
            end if
         end do
      end if
      ec%on = .true.
      ec%spec = spec
      ec%conn = mesh%conn
      ec%region = mesh%region
      ec%mat = mesh%mat
      ec%modulus = modulus
   end subroutine erosion_contact_init

   !> Build the surfaces of contact c again from the live elements (st%status == 0), keeping the
   !> run's contact state.
   subroutine erosion_contact_rebuild(ec, c, st, err)
      type(erosion_contact_t), intent(in) :: ec
      type(contact_t), intent(inout) :: c
      type(state_t), intent(in) :: st
      type(error_t), allocatable, intent(out) :: err
      type(contact_t) :: fresh
      logical, allocatable :: live(:)
      integer :: k, nlive
      if (.not. ec%on) return
      live = st%status == 0
      nlive = count(live)
      ! on the reference positions: the live elements did not overlap there
      call fresh%init(ec%spec, st%nnode, st%x0, st%x0, nlive, reshape(pack(ec%conn, spread(live, 1, 4)), &
                      [4, nlive]), pack(ec%region, live), pack(ec%mat, live), ec%modulus, err)
      if (allocated(err)) then
         err%message = 'contact surfaces after an erosion: '//err%message
         return
      end if
      ! the run's state
      fresh%lref = c%lref
      fresh%depth = c%depth
      fresh%stamp = c%stamp
      fresh%nthreaded = c%nthreaded
      fresh%keep_fcon = c%keep_fcon
      fresh%fcon_clean = c%fcon_clean
      if (size(fresh%results) == size(c%results)) fresh%results = c%results
      fresh%corr = c%corr
      fresh%fr = c%fr
      fresh%auto_hist = c%auto_hist
      fresh%hwork = c%hwork
      do k = 1, min(c%nfixed, fresh%nfixed)
         fresh%passes(k)%hist = c%passes(k)%hist
      end do
      if (allocated(c%vslip)) fresh%vslip = c%vslip
      if (allocated(c%ffric)) fresh%ffric = c%ffric
      if (allocated(c%xold)) fresh%xold = c%xold
      fresh%xp = c%xp
      fresh%dissipation = c%dissipation
      fresh%pending = c%pending
      fresh%max_penetration = c%max_penetration
      fresh%time_search = c%time_search
      fresh%time_corrector = c%time_corrector
      fresh%nredundant = c%nredundant
      call move_alloc_contact(fresh, c)
   end subroutine erosion_contact_rebuild

   !> c takes fresh's contents.
   subroutine move_alloc_contact(fresh, c)
      type(contact_t), intent(inout) :: fresh
      type(contact_t), intent(inout) :: c
      c = fresh
   end subroutine move_alloc_contact

end module exic_explicit_erosion_contact
