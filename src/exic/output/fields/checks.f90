!> Checks of the arguments of the field writer (exic_output_fields) that need no writer: the mesh
!> arrays and the names of element value components.
module exic_output_fields_checks
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t, make_error
   implicit none
   private

   public :: check_mesh, check_names

contains

   !> Check the shapes and index ranges of the mesh arrays.
   subroutine check_mesh(nnode, nelem, x0, conn, region, mat, surf_edges, path, err)
      integer, intent(in) :: nnode, nelem
      real(wp), intent(in) :: x0(:, :)
      integer, intent(in) :: conn(:, :), region(:), mat(:), surf_edges(:, :)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: pre
      integer :: e

      pre = "field output '"//path//"': "
      if (nnode < 1 .or. nelem < 1) then
         call make_error(err, pre//'the mesh needs at least one node and one element')
      else if (any(shape(x0) /= [2, nnode])) then
         call make_error(err, pre//'coordinates must have shape (2, nnode)')
      else if (any(shape(conn) /= [4, nelem])) then
         call make_error(err, pre//'connectivity must have shape (4, nelem)')
      else if (size(region) /= nelem .or. size(mat) /= nelem) then
         call make_error(err, pre//'region and material must have nelem entries')
      else if (size(surf_edges, 1) /= 2) then
         call make_error(err, pre//'contact edges must have shape (2, nedge)')
      else if (any(surf_edges < 1 .or. surf_edges > nnode)) then
         call make_error(err, pre//'a contact edge names a node outside 1..nnode')
      else
         do e = 1, nelem
            if (any(conn(:, e) < 1 .or. conn(:, e) > nnode)) then
               call make_error(err, pre//'element '//itoa(e)//' names a node outside 1..nnode')
               return
            end if
         end do
      end if
   end subroutine check_mesh

   !> Names of datasets and XDMF attributes: non-empty, letters, digits and '_' only, distinct.
   subroutine check_names(names, what, err)
      character(len=*), intent(in) :: names(:), what
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: allowed = 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_'
      integer :: i, j
      if (size(names) == 0) then
         call make_error(err, 'field output: no '//what//' names given')
         return
      end if
      do i = 1, size(names)
         if (len_trim(names(i)) == 0 .or. verify(trim(names(i)), allowed) /= 0 .or. len_trim(names(i)) > 16) then
            call make_error(err, "field output: "//what//" name '"//trim(names(i))// &
                            "' must be 1 to 16 letters, digits or '_'")
            return
         end if
         do j = 1, i - 1
            if (trim(names(j)) == trim(names(i))) then
               call make_error(err, "field output: "//what//" name '"//trim(names(i))//"' given twice")
               return
            end if
         end do
      end do
   end subroutine check_names

end module exic_output_fields_checks
