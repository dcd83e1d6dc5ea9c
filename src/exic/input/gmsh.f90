!> Meshes read (or made) by the Gmsh library, through its C API (exic_input_gmsh_library).
!>
!> `gmsh_read` loads the library at its first call (exic_input_gmsh_library: dlopen, once per process)
!> and owns the library's whole life for one file: initialize (no configuration files, terminal
!> output off, messages to Gmsh's logger), open the file, mesh it in 2-D when asked (`.geo`
!> files), copy out what exic needs, finalize. Every status code is checked; a failure
!> becomes an error carrying Gmsh's own last message, and the library is finalized before
!> returning (a failed Gmsh call leaves it unusable until then). Gmsh's warnings are returned.
!> Arrays the library returns are copied and released with gmshFree; a failed call sets no
!> output, so nothing is released then.
!>
!> What is copied, in Gmsh's own numbering (tags): every node (x, y, z); the 4-node
!> quadrilaterals of the 2-D entities with the physical surface each belongs to; the 2-node
!> lines of every physical curve. Checked here, before any numbering is decided: no 3-node
!> triangles (counted, with the hint to recombine), no other 2-D or any 3-D element type
!> (second order elements are named), at least one quadrilateral, every 2-D entity holding
!> quadrilaterals in exactly one physical surface, physical curves of 2-node lines only.
module exic_input_gmsh
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_size_t, c_ptr, c_null_ptr, &
                                          c_null_char, c_f_pointer
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_base_sort, only: sort_perm_i8
   use exic_base_posix, only: c_string
   use exic_input_gmsh_library, only: GMSH_LIBRARIES, gmsh_library_load, gmshInitialize, gmshFinalize, &
                             gmshOpen, gmshFree, &
                             gmshOptionSetNumber, gmshModelGetEntities, &
                             gmshModelGetPhysicalGroups, gmshModelGetPhysicalName, &
                             gmshModelGetEntitiesForPhysicalGroup, &
                             gmshModelGetPhysicalGroupsForEntity, gmshModelMeshGenerate, &
                             gmshModelMeshGetNodes, gmshModelMeshGetElementTypes, &
                             gmshModelMeshGetElementsByType, gmshModelMeshGetElementProperties, &
                             gmshLoggerStart, gmshLoggerStop, gmshLoggerGet, &
                             gmshLoggerGetLastError
   implicit none
   private

   public :: gmsh_curve_t, gmsh_mesh_t, gmsh_read

   !> Gmsh element types exic looks for (MSH numbering).
   integer, parameter :: TYPE_LINE2 = 1, TYPE_TRI3 = 2, TYPE_QUAD4 = 3

   !> One physical curve: its 2-node lines, as Gmsh orients them.
   type :: gmsh_curve_t
      integer :: tag = 0
      character(len=:), allocatable :: name     !< physical name ('' when none)
      integer :: nline = 0
      integer(i8), allocatable :: line(:, :)    !< (2, nline) node tags
   end type gmsh_curve_t

   !> A 2-D quadrilateral mesh in Gmsh's numbering.
   type :: gmsh_mesh_t
      integer :: nnode = 0
      integer(i8), allocatable :: node_tag(:)   !< (nnode) increasing
      real(wp), allocatable :: x(:, :)          !< (3, nnode) coordinates
      integer :: nquad = 0
      integer(i8), allocatable :: quad_tag(:)   !< (nquad) element tags, increasing
      integer(i8), allocatable :: quad(:, :)    !< (4, nquad) node tags, as Gmsh orders them
      integer, allocatable :: quad_phys(:)      !< (nquad) physical surface tag
      type(gmsh_curve_t), allocatable :: curves(:)   !< physical curves, by increasing tag
      integer :: npoint_groups = 0              !< physical points (not used by exic)
      character(len=:), allocatable :: warnings !< Gmsh's warnings, newline separated
   end type gmsh_mesh_t

contains

   !> Read `path` with Gmsh into `gm`; with `generate`, mesh the geometry in 2-D first
   !> (gmshModelMeshGenerate(2), for `.geo` files). `err` says what went wrong, without a
   !> file:line prefix (the caller adds the deck record's).
   subroutine gmsh_read(path, generate, gm, err)
      character(len=*), intent(in) :: path
      logical, intent(in) :: generate
      type(gmsh_mesh_t), intent(out) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer(c_int) :: ierr
      logical :: logging

      gm%warnings = ''
      call gmsh_library_load(GMSH_LIBRARIES, err)
      if (allocated(err)) return
      call gmshInitialize(0_c_int, c_null_ptr, 0_c_int, ierr)
      if (ierr /= 0) then
         call make_error(err, 'the Gmsh library failed to initialize (status '// &
                         itoa(int(ierr))//')')
         return
      end if
      logging = .false.
      call gmshOptionSetNumber('General.Terminal'//c_null_char, 0.0_c_double, ierr)
      if (ierr == 0) call gmshLoggerStart(ierr)
      if (ierr /= 0) then
         call failed('setting up its logger', err)
      else
         logging = .true.
         call read_model(path, generate, gm, err)
      end if
      if (logging) then
         call collect_warnings(gm%warnings, ierr)
         if (ierr /= 0) call cleanup_failed('returning its messages')
         call gmshLoggerStop(ierr)
         if (ierr /= 0) call cleanup_failed('stopping its logger')
      end if
      call gmshFinalize(ierr)
      if (ierr /= 0) call cleanup_failed('finalizing')
   contains
      !> A failure after the model was read: reported unless an earlier error is.
      subroutine cleanup_failed(what)
         character(len=*), intent(in) :: what
         if (.not. allocated(err)) call make_error(err, 'the Gmsh library failed '//what// &
                                                   ' (status '//itoa(int(ierr))//')')
      end subroutine cleanup_failed
   end subroutine gmsh_read

   !> Open, optionally mesh, and copy the model out.
   subroutine read_model(path, generate, gm, err)
      character(len=*), intent(in) :: path
      logical, intent(in) :: generate
      type(gmsh_mesh_t), intent(inout) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer(c_int) :: ierr
      call gmshOpen(path//c_null_char, ierr)
      if (ierr /= 0) then
         call failed('reading "'//path//'"', err)
         return
      end if
      if (generate) then
         call gmshModelMeshGenerate(2_c_int, ierr)
         if (ierr /= 0) then
            call failed('meshing "'//path//'" in 2-D', err)
            return
         end if
      end if
      call check_no_volumes(err)
      if (allocated(err)) return
      call read_surfaces(gm, err)
      if (allocated(err)) return
      call read_curves(gm, err)
      if (allocated(err)) return
      call read_nodes(gm, err)
      if (allocated(err)) return
      call count_point_groups(gm, err)
   end subroutine read_model

   !> An error naming the Gmsh step and the library's last message.
   subroutine failed(what, err)
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      integer(c_int) :: ierr
      character(len=:), allocatable :: msg
      call gmshLoggerGetLastError(p, ierr)
      msg = ''
      if (ierr == 0) then
         msg = c_string(p)
         call gmshFree(p)
      end if
      if (len(msg) > 0) then
         call make_error(err, 'Gmsh failed '//what//': '//msg)
      else
         call make_error(err, 'Gmsh failed '//what)
      end if
   end subroutine failed

   !> Gmsh's warning messages, newline separated, appended to `warnings`; `ierr` is the
   !> status of gmshLoggerGet.
   subroutine collect_warnings(warnings, ierr)
      character(len=:), allocatable, intent(inout) :: warnings
      integer(c_int), intent(out) :: ierr
      type(c_ptr) :: log
      type(c_ptr), pointer :: lines(:)
      integer(c_size_t) :: n
      integer :: k
      character(len=:), allocatable :: line
      call gmshLoggerGet(log, n, ierr)
      if (ierr /= 0) return
      if (n > 0) then
         call c_f_pointer(log, lines, [n])
         do k = 1, int(n)
            line = c_string(lines(k))
            call gmshFree(lines(k))
            if (index(line, 'Warning') /= 1) cycle
            if (len(warnings) > 0) warnings = warnings//new_line('a')
            warnings = warnings//'Gmsh: '//line
         end do
      end if
      call gmshFree(log)
   end subroutine collect_warnings

   !> Copy a Gmsh int array (n values) and free it.
   subroutine take_int(p, n, a)
      type(c_ptr), intent(in) :: p
      integer(c_size_t), intent(in) :: n
      integer, allocatable, intent(out) :: a(:)
      integer(c_int), pointer :: v(:)
      allocate (a(n))
      if (n > 0) then
         call c_f_pointer(p, v, [n])
         a = int(v)
      end if
      call gmshFree(p)
   end subroutine take_int

   !> Copy a Gmsh size_t array (n values) and free it.
   subroutine take_size(p, n, a)
      type(c_ptr), intent(in) :: p
      integer(c_size_t), intent(in) :: n
      integer(i8), allocatable, intent(out) :: a(:)
      integer(c_size_t), pointer :: v(:)
      allocate (a(n))
      if (n > 0) then
         call c_f_pointer(p, v, [n])
         a = int(v, i8)
      end if
      call gmshFree(p)
   end subroutine take_size

   !> Copy a Gmsh double array (n values) and free it.
   subroutine take_double(p, n, a)
      type(c_ptr), intent(in) :: p
      integer(c_size_t), intent(in) :: n
      real(wp), allocatable, intent(out) :: a(:)
      real(c_double), pointer :: v(:)
      allocate (a(n))
      if (n > 0) then
         call c_f_pointer(p, v, [n])
         a = real(v, wp)
      end if
      call gmshFree(p)
   end subroutine take_double

   !> Tags of the entities (dim >= 0) or of the physical groups (`physical`) of dimension dim.
   subroutine tags_of(dim, physical, tags, err)
      integer, intent(in) :: dim
      logical, intent(in) :: physical
      integer, allocatable, intent(out) :: tags(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      integer(c_size_t) :: n
      integer(c_int) :: ierr
      integer, allocatable :: dimtags(:)
      if (physical) then
         call gmshModelGetPhysicalGroups(p, n, int(dim, c_int), ierr)
      else
         call gmshModelGetEntities(p, n, int(dim, c_int), ierr)
      end if
      if (ierr /= 0) then
         allocate (tags(0))
         call failed('listing the model''s entities', err)
         return
      end if
      call take_int(p, n, dimtags)
      tags = dimtags(2::2)
   end subroutine tags_of

   !> Element types present on entity (dim, tag).
   subroutine element_types(dim, tag, types, err)
      integer, intent(in) :: dim, tag
      integer, allocatable, intent(out) :: types(:)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: p
      integer(c_size_t) :: n
      integer(c_int) :: ierr
      call gmshModelMeshGetElementTypes(p, n, int(dim, c_int), int(tag, c_int), ierr)
      if (ierr /= 0) then
         call failed('listing element types', err)
         return
      end if
      call take_int(p, n, types)
   end subroutine element_types

   !> Elements of `etype` on entity `tag`: their tags and node tags (nn per element; with
   !> nn = 0 only the tags).
   subroutine elements_of(etype, tag, nn, etags, nodes, err)
      integer, intent(in) :: etype, tag, nn
      integer(i8), allocatable, intent(out) :: etags(:)
      integer(i8), allocatable, intent(out) :: nodes(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: pe, pn
      integer(c_size_t) :: ne, nnt
      integer(c_int) :: ierr
      integer(i8), allocatable :: flat(:)
      call gmshModelMeshGetElementsByType(int(etype, c_int), pe, ne, pn, nnt, int(tag, c_int), &
                                          0_c_size_t, 1_c_size_t, ierr)
      if (ierr /= 0) then
         call failed('reading elements', err)
         return
      end if
      call take_size(pe, ne, etags)
      call take_size(pn, nnt, flat)
      if (nn == 0) then
         allocate (nodes(0, size(etags)))
         return
      end if
      if (size(flat) /= nn*size(etags)) then
         call make_error(err, 'Gmsh returned '//itoa(size(flat))//' node tags for '// &
                         itoa(size(etags))//' elements of '//itoa(nn)//' nodes')
         return
      end if
      nodes = reshape(flat, [nn, size(etags)])
   end subroutine elements_of

   !> Gmsh's name of an element type (e.g. "Quadrilateral 9").
   function type_name(etype) result(name)
      integer, intent(in) :: etype
      character(len=:), allocatable :: name
      type(c_ptr) :: pname, pcoord
      integer(c_int) :: dim, order, nn, nprim, ierr
      integer(c_size_t) :: nc
      call gmshModelMeshGetElementProperties(int(etype, c_int), pname, dim, order, nn, pcoord, &
                                             nc, nprim, ierr)
      name = 'Gmsh type '//itoa(etype)
      if (ierr /= 0) return
      name = c_string(pname)//' (Gmsh type '//itoa(etype)//')'
      call gmshFree(pname)
      call gmshFree(pcoord)
   end function type_name

   !> exic is 2-D: any 3-D element is an error.
   subroutine check_no_volumes(err)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: vols(:), types(:)
      integer :: k
      call tags_of(3, .false., vols, err)
      if (allocated(err)) return
      do k = 1, size(vols)
         call element_types(3, vols(k), types, err)
         if (allocated(err)) return
         if (size(types) > 0) then
            call make_error(err, 'volume '//itoa(vols(k))//' holds 3-D elements ('// &
                            type_name(types(1))//'): expected a 2-D mesh of quadrilaterals')
            return
         end if
      end do
   end subroutine check_no_volumes

   !> The quadrilaterals of every 2-D entity, with their physical surface; the checks on
   !> element types and physical surfaces listed in the module header.
   subroutine read_surfaces(gm, err)
      type(gmsh_mesh_t), intent(inout) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: surfs(:), types(:), phys(:), nq(:), all_phys(:)
      integer(i8), allocatable :: etags(:), nodes(:, :), qtag(:), qnode(:, :)
      integer, allocatable :: qphys(:)
      integer :: k, j, ntri, nother, other_type
      type(c_ptr) :: p
      integer(c_size_t) :: np
      integer(c_int) :: ierr

      call tags_of(2, .false., surfs, err)
      if (allocated(err)) return
      call tags_of(2, .true., all_phys, err)
      if (allocated(err)) return
      ntri = 0
      nother = 0
      other_type = 0
      allocate (nq(size(surfs)), qtag(0), qnode(4, 0), qphys(0))
      nq = 0
      do k = 1, size(surfs)
         call element_types(2, surfs(k), types, err)
         if (allocated(err)) return
         do j = 1, size(types)
            select case (types(j))
            case (TYPE_QUAD4)
               call elements_of(TYPE_QUAD4, surfs(k), 4, etags, nodes, err)
               if (allocated(err)) return
               nq(k) = size(etags)
               qtag = [qtag, etags]
               qnode = reshape([reshape(qnode, [size(qnode)]), reshape(nodes, [size(nodes)])], &
                               [4, size(qtag)])
            case (TYPE_TRI3)
               call elements_of(TYPE_TRI3, surfs(k), 3, etags, nodes, err)
               if (allocated(err)) return
               ntri = ntri + size(etags)
            case default
               call elements_of(types(j), surfs(k), 0, etags, nodes, err)
               if (allocated(err)) return
               nother = nother + size(etags)
               other_type = types(j)
            end select
         end do
         if (nq(k) == 0) cycle
         call gmshModelGetPhysicalGroupsForEntity(2_c_int, int(surfs(k), c_int), p, np, ierr)
         if (ierr /= 0) then
            call failed('reading the physical groups of surface '//itoa(surfs(k)), err)
            return
         end if
         call take_int(p, np, phys)
         if (size(phys) == 0) then
            if (size(all_phys) == 0) then
               call make_error(err, 'no Physical Surface: expected every meshed surface in a '// &
                               'Physical Surface(t) (it becomes region t with material set t)')
            else
               call make_error(err, 'surface '//itoa(surfs(k))//' holds '//itoa(nq(k))// &
                               ' quadrilaterals but belongs to no Physical Surface: expected '// &
                               'every meshed surface in a Physical Surface(t) (region t, '// &
                               'material set t)')
            end if
            return
         end if
         if (size(phys) > 1) then
            call make_error(err, 'surface '//itoa(surfs(k))//' belongs to Physical Surfaces '// &
                            itoa(phys(1))//' and '//itoa(phys(2))//': expected exactly one '// &
                            '(a physical surface is a region and a material set)')
            return
         end if
         if (phys(1) < 1) then
            call make_error(err, 'Physical Surface '//itoa(phys(1))//': expected a tag >= 1 '// &
                            '(it becomes a region and a material set)')
            return
         end if
         qphys = [qphys, spread(phys(1), 1, nq(k))]
      end do
      if (ntri > 0) then
         call make_error(err, itoa(ntri)//' 3-node triangles (and '//itoa(sum(nq))// &
                         ' 4-node quadrilaterals): exic has 4-node quadrilaterals only; '// &
                         'recombine the mesh in Gmsh: Recombine Surface{...}; or '// &
                         'Mesh.RecombineAll = 1; in the .geo (with Mesh.SubdivisionAlgorithm = 1 '// &
                         'for quadrilaterals only), or Mesh > Recombine 2D in the GUI')
         return
      end if
      if (nother > 0) then
         call make_error(err, itoa(nother)//' elements of '//type_name(other_type)// &
                         ': expected first-order 4-node quadrilaterals (Mesh.ElementOrder = 1)')
         return
      end if
      if (size(qtag) == 0) then
         call make_error(err, 'no 4-node quadrilaterals: expected a 2-D quadrilateral mesh '// &
                         '(a .msh file, or a .geo file that exic meshes)')
         return
      end if
      call sort_quads(qtag, qnode, qphys, gm)
   end subroutine read_surfaces

   !> Store the quadrilaterals in increasing tag order.
   subroutine sort_quads(qtag, qnode, qphys, gm)
      integer(i8), intent(in) :: qtag(:), qnode(:, :)
      integer, intent(in) :: qphys(:)
      type(gmsh_mesh_t), intent(inout) :: gm
      integer :: perm(size(qtag))
      call sort_perm_i8(size(qtag), qtag, perm)
      gm%nquad = size(qtag)
      gm%quad_tag = qtag(perm)
      gm%quad = qnode(:, perm)
      gm%quad_phys = qphys(perm)
   end subroutine sort_quads

   !> The 2-node lines of every physical curve.
   subroutine read_curves(gm, err)
      type(gmsh_mesh_t), intent(inout) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: groups(:), ents(:), types(:)
      integer(i8), allocatable :: etags(:), nodes(:, :), lines(:, :)
      integer :: k, j, t
      type(c_ptr) :: p
      integer(c_size_t) :: n
      integer(c_int) :: ierr

      call tags_of(1, .true., groups, err)
      if (allocated(err)) return
      allocate (gm%curves(size(groups)))
      do k = 1, size(groups)
         gm%curves(k)%tag = groups(k)
         call gmshModelGetPhysicalName(1_c_int, int(groups(k), c_int), p, ierr)
         if (ierr /= 0) then
            call failed('reading the name of Physical Curve '//itoa(groups(k)), err)
            return
         end if
         gm%curves(k)%name = c_string(p)
         call gmshFree(p)
         call gmshModelGetEntitiesForPhysicalGroup(1_c_int, int(groups(k), c_int), p, n, ierr)
         if (ierr /= 0) then
            call failed('reading the curves of Physical Curve '//itoa(groups(k)), err)
            return
         end if
         call take_int(p, n, ents)
         allocate (lines(2, 0))
         do j = 1, size(ents)
            call element_types(1, ents(j), types, err)
            if (allocated(err)) return
            do t = 1, size(types)
               if (types(t) /= TYPE_LINE2) then
                  call make_error(err, 'Physical Curve '//itoa(groups(k))//' holds elements of '// &
                                  type_name(types(t))//': expected 2-node lines '// &
                                  '(first order, Mesh.ElementOrder = 1)')
                  return
               end if
               call elements_of(TYPE_LINE2, ents(j), 2, etags, nodes, err)
               if (allocated(err)) return
               lines = reshape([reshape(lines, [size(lines)]), reshape(nodes, [size(nodes)])], &
                               [2, size(lines, 2) + size(nodes, 2)])
            end do
         end do
         if (size(lines, 2) == 0) then
            call make_error(err, 'Physical Curve '//itoa(groups(k))//' has no mesh lines: '// &
                            'expected a meshed curve')
            return
         end if
         gm%curves(k)%nline = size(lines, 2)
         call move_alloc(lines, gm%curves(k)%line)
      end do
   end subroutine read_curves

   !> Every node of the model, by increasing tag.
   subroutine read_nodes(gm, err)
      type(gmsh_mesh_t), intent(inout) :: gm
      type(error_t), allocatable, intent(out) :: err
      type(c_ptr) :: pt, pc, pp
      integer(c_size_t) :: nt, nc, np
      integer(c_int) :: ierr
      integer(i8), allocatable :: tags(:)
      real(wp), allocatable :: coord(:)
      integer, allocatable :: perm(:)
      call gmshModelMeshGetNodes(pt, nt, pc, nc, pp, np, -1_c_int, -1_c_int, 0_c_int, 0_c_int, &
                                 ierr)
      if (ierr /= 0) then
         call failed('reading the nodes', err)
         return
      end if
      call gmshFree(pp)
      call take_size(pt, nt, tags)
      call take_double(pc, nc, coord)
      if (size(coord) /= 3*size(tags)) then
         call make_error(err, 'Gmsh returned '//itoa(size(coord))//' coordinates for '// &
                         itoa(size(tags))//' nodes')
         return
      end if
      allocate (perm(size(tags)))
      call sort_perm_i8(size(tags), tags, perm)
      gm%nnode = size(tags)
      gm%node_tag = tags(perm)
      gm%x = reshape(coord, [3, size(tags)])
      gm%x = gm%x(:, perm)
   end subroutine read_nodes

   !> Physical points are not used by exic; count them so that the caller can say so.
   subroutine count_point_groups(gm, err)
      type(gmsh_mesh_t), intent(inout) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: groups(:)
      call tags_of(0, .true., groups, err)
      if (allocated(err)) return
      gm%npoint_groups = size(groups)
   end subroutine count_point_groups

end module exic_input_gmsh
