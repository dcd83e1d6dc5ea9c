!> METIS 5 (Debian's libmetis: 32-bit idx_t and real_t) as the distributed run needs it: the
!> dual graph of a mesh (elements that share an edge, ncommon = 2) cut into parts of nearly
!> equal weight by METIS_PartMeshDual (doc/parallel.md, "Partition").
!>
!> METIS is deterministic for given input and options: the seed is set explicitly
!> (METIS_OPTION_SEED = 1), so that every rank, given the same mesh, computes the same parts.
module exic_parallel_metis
   use, intrinsic :: iso_c_binding, only: c_int32_t, c_ptr, c_null_ptr
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   implicit none
   private

   public :: metis_part_mesh_dual

   !> metis.h: METIS_NOPTIONS, the option indices and the return codes
   integer, parameter :: METIS_NOPTIONS = 40
   integer, parameter :: OPTION_SEED = 8, OPTION_NUMBERING = 17
   integer(c_int32_t), parameter :: METIS_OK = 1, METIS_ERROR_INPUT = -2, METIS_ERROR_MEMORY = -3

   interface
      !> int METIS_SetDefaultOptions(idx_t *options)
      function c_set_default_options(options) bind(C, name='METIS_SetDefaultOptions') result(status)
         import :: c_int32_t
         integer(c_int32_t), intent(inout) :: options(*)
         integer(c_int32_t) :: status
      end function c_set_default_options

      !> int METIS_PartMeshDual(idx_t *ne, idx_t *nn, idx_t *eptr, idx_t *eind, idx_t *vwgt,
      !>     idx_t *vsize, idx_t *ncommon, idx_t *nparts, real_t *tpwgts, idx_t *options,
      !>     idx_t *objval, idx_t *epart, idx_t *npart)
      function c_part_mesh_dual(ne, nn, eptr, eind, vwgt, vsize, ncommon, nparts, tpwgts, options, &
                                objval, epart, npart) bind(C, name='METIS_PartMeshDual') result(status)
         import :: c_int32_t, c_ptr
         integer(c_int32_t), intent(in) :: ne, nn, ncommon, nparts
         integer(c_int32_t), intent(in) :: eptr(*), eind(*), vwgt(*)
         type(c_ptr), value :: vsize, tpwgts
         integer(c_int32_t), intent(inout) :: options(*)
         integer(c_int32_t), intent(out) :: objval, epart(*), npart(*)
         integer(c_int32_t) :: status
      end function c_part_mesh_dual
   end interface

contains

   !> part(e) in 0 .. nparts - 1 for the nelem elements of a mesh of nnode nodes, element e with
   !> the nodes eind(eptr(e) + 1 : eptr(e + 1)) (eptr(1) = 0; any number of nodes per element),
   !> weights weight(e) >= 1; nparts >= 2 and nparts <= nelem. Two elements are neighbours when
   !> they share two nodes (ncommon = 2: an edge). cut: the edges of the dual graph that the
   !> parts cut (METIS's objval).
   subroutine metis_part_mesh_dual(nelem, nnode, eptr, eind, weight, nparts, part, cut, err)
      integer, intent(in) :: nelem, nnode, nparts
      integer, intent(in) :: eptr(nelem + 1), eind(:), weight(nelem)
      integer, intent(out) :: part(nelem), cut
      type(error_t), allocatable, intent(out) :: err
      integer(c_int32_t), allocatable :: ep(:), ei(:), vwgt(:), epart(:), npart(:)
      integer(c_int32_t) :: options(METIS_NOPTIONS), objval, status

      part = 0
      cut = 0
      if (nparts < 2 .or. nparts > nelem) then
         call make_error(err, 'METIS: '//itoa(nparts)//' parts of '//itoa(nelem)//' elements')
         return
      end if
      allocate (vwgt(nelem), epart(nelem), npart(nnode))
      ep = int(eptr, c_int32_t)
      ei = int(eind(1:eptr(nelem + 1)) - 1, c_int32_t)
      vwgt = int(max(1, weight), c_int32_t)
      status = c_set_default_options(options)
      options(OPTION_SEED + 1) = 1_c_int32_t
      options(OPTION_NUMBERING + 1) = 0_c_int32_t
      status = c_part_mesh_dual(int(nelem, c_int32_t), int(nnode, c_int32_t), ep, ei, vwgt, c_null_ptr, &
                                2_c_int32_t, int(nparts, c_int32_t), c_null_ptr, options, objval, epart, npart)
      if (status /= METIS_OK) then
         call make_error(err, 'METIS_PartMeshDual failed (status '//itoa(int(status))//') on '// &
                         itoa(nelem)//' elements in '//itoa(nparts)//' parts')
         return
      end if
      part = int(epart)
      cut = int(objval)
   end subroutine metis_part_mesh_dual

end module exic_parallel_metis
