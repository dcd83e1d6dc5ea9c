!> The mesh: reference coordinates, 4-node connectivity, regions, materials and nodal data.
module exic_mesh_mesh
   use exic_base_kinds, only: wp
   use exic_mesh_edge_set, only: edge_set_t
   implicit none
   private

   public :: mesh_t

   !> A 2-D mesh of 4-node quadrilaterals. Arrays are (component, entity).
   type :: mesh_t
      integer :: nnode = 0                      !< number of node slots (highest node number)
      integer :: nelem = 0                      !< number of elements
      real(wp), allocatable :: x(:, :)          !< (2, nnode) reference coordinates
      logical, allocatable :: defined(:)        !< (nnode) node was given coordinates
      integer, allocatable :: conn(:, :)        !< (4, nelem) nodes, counter-clockwise
      integer, allocatable :: mat(:)            !< (nelem) material set number
      integer, allocatable :: region(:)         !< (nelem) region (body) number
      integer, allocatable :: bc(:, :)          !< (2, nnode) non-zero: dof prescribed
      real(wp), allocatable :: force(:, :)      !< (2, nnode) constant nodal forces
      real(wp), allocatable :: disp(:, :)       !< (2, nnode) prescribed displacement values
      real(wp), allocatable :: v0(:, :)         !< (2, nnode) initial velocity
      type(edge_set_t), allocatable :: edge_sets(:)  !< named edge sets (Gmsh physical curves)
      !> GLOBal AXISymmetric: x = r, y = z, every extensive quantity per radian (doc/axisymmetry.md)
      logical :: axisymmetric = .false.
   end type mesh_t

end module exic_mesh_mesh
