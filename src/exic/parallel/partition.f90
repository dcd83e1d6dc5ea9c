!> The decomposition of a mesh over P ranks (doc/parallel.md, "Partition"): every element has
!> one owner (METIS_PartMeshDual on the dual graph, elements weighted by their cost), every
!> node one owner by a fixed rule: the smallest rank that owns one of its elements (rank 0 for
!> a node of no element). Plain arrays in, the same answer on every rank.
module exic_parallel_partition
   use exic_base_error, only: error_t
   use exic_parallel_metis, only: metis_part_mesh_dual
   implicit none
   private

   public :: partition_elements, partition_mesh, node_owners

contains

   !> owner(e) in 0 .. nparts - 1 for the nelem elements conn(4, nelem): all 0 for one part,
   !> else METIS's parts of the weights weight(e) (values below 1 count as 1); cut: the shared
   !> edges between parts.
   subroutine partition_elements(nelem, nnode, conn, weight, nparts, owner, cut, err)
      integer, intent(in) :: nelem, nnode, nparts
      integer, intent(in) :: conn(4, nelem), weight(nelem)
      integer, intent(out) :: owner(nelem), cut
      type(error_t), allocatable, intent(out) :: err
      integer :: e
      call partition_mesh(nelem, nnode, [(4*e, e=0, nelem)], reshape(conn, [4*nelem]), weight, nparts, owner, &
                          cut, err)
   end subroutine partition_elements

   !> partition_elements for a mesh whose element e has the nodes eind(eptr(e) + 1 : eptr(e + 1))
   !> (eptr(1) = 0), any number each (the blocks of elements of the distributed force pass).
   subroutine partition_mesh(nelem, nnode, eptr, eind, weight, nparts, owner, cut, err)
      integer, intent(in) :: nelem, nnode, nparts
      integer, intent(in) :: eptr(nelem + 1), eind(:), weight(nelem)
      integer, intent(out) :: owner(nelem), cut
      type(error_t), allocatable, intent(out) :: err
      owner = 0
      cut = 0
      if (nparts <= 1) return
      call metis_part_mesh_dual(nelem, nnode, eptr, eind, weight, nparts, owner, cut, err)
   end subroutine partition_mesh

   !> node(n): the smallest owner of the elements that use node n (0 for a node of none).
   pure subroutine node_owners(nelem, nnode, conn, owner, node)
      integer, intent(in) :: nelem, nnode
      integer, intent(in) :: conn(4, nelem), owner(nelem)
      integer, intent(out) :: node(nnode)
      integer :: e, a
      node = huge(1)
      do e = 1, nelem
         do a = 1, 4
            node(conn(a, e)) = min(node(conn(a, e)), owner(e))
         end do
      end do
      where (node == huge(1)) node = 0
      ! (an element owner of huge(1), an element of no part, gives its nodes no owner)
   end subroutine node_owners

end module exic_parallel_partition
