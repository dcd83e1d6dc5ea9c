!> The nodes the field output writes (doc/fields.md, "Node numbers"). A deck may leave node
!> numbers unused (BLOCk with node1 > 1, COORdinates that skip numbers, Gmsh node tags with
!> gaps): the mesh then has slots 1..nnode of which only some are nodes (`mesh_t%defined`). The
!> field output writes the nodes alone, in increasing number, with the connectivity and contact
!> edges renumbered to them and the deck numbers in `/mesh/node_id`, so that XDMF readers see no
!> point that is not a node. A mesh without unused numbers is written as it is (no `node_id`).
module exic_output_fields_nodes
   use exic_base_error, only: error_t
   use exic_hdf5_file, only: hdf5_file_t
   implicit none
   private

   public :: written_nodes, renumbered, write_node_id

contains

   !> The slots written, in increasing order, when some slot of `defined` is not a node;
   !> `keep` is left unallocated when every slot is one (the mesh is written as it is).
   pure subroutine written_nodes(defined, keep)
      logical, intent(in) :: defined(:)
      integer, allocatable, intent(out) :: keep(:)
      integer :: n
      if (all(defined)) return
      keep = pack([(n, n=1, size(defined))], defined)
   end subroutine written_nodes

   !> Node numbers `ids` (slots 1..nnode) mapped to their
   !> positions in `keep`, for the connectivity (4, nelem) and the contact edges (2, nedge).
   !> Every number of `ids` must be in `keep` (the elements' nodes are all defined: the deck
   !> reader checks it).
   pure function renumbered(ids, keep, nnode) result(r)
      integer, intent(in) :: ids(:, :), keep(:)
      integer, intent(in) :: nnode
      integer :: r(size(ids, 1), size(ids, 2))
      integer :: position(nnode), j
      position = 0
      do j = 1, size(keep)
         position(keep(j)) = j
      end do
      r = reshape(position(reshape(ids, [size(ids)])), shape(ids))
   end function renumbered

   !> `/mesh/node_id`: the deck number of each written node (as the deck gives it), and the
   !> descriptions of the connectivity and contact edges, whose indices are then rows of
   !> `/mesh/coordinates` rather than deck numbers - 1.
   subroutine write_node_id(h5, node_id, err)
      type(hdf5_file_t), intent(inout) :: h5
      integer, intent(in), contiguous :: node_id(:)
      type(error_t), allocatable, intent(out) :: err
      call h5%write('/mesh/node_id', node_id, err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/node_id', 'description', &
                                                   'deck number of each node (row) of /mesh/coordinates', err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/connectivity', 'description', &
                                                   'quad nodes counterclockwise, 0-based rows of /mesh/coordinates '// &
                                                   '(deck numbers: /mesh/node_id)', err)
      if (.not. allocated(err)) call h5%write_attr('/mesh/contact_edges', 'description', &
                                                   'node pairs of the contact surface edges, 0-based rows of '// &
                                                   '/mesh/coordinates (deck numbers: /mesh/node_id)', err)
   end subroutine write_node_id

end module exic_output_fields_nodes
