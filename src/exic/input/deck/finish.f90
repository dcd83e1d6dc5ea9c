!> What happens at the mesh END of a deck: the mesh is sized to its highest node and element
!> numbers and checked, EBOUndary, PBOUndary then CBOUndary sets and the mesh-phase initial
!> velocities are applied, contact surfaces given by PHYSical take their edge sets, and TIE
!> records merge coincident nodes.
!>
!> Checks (each error names file:line of the record that made the item): every element number
!> 1..nelem defined; every element node defined; every element's material has a MATErial set;
!> every element counter-clockwise with positive area and a positive cross product of the two
!> edges at each corner (so a clockwise, inverted or non-convex element is an error, and an
!> element with two corners at one point is named as such); regions and materials named by
!> INITial or CONTact exist; FACEts nodes are element nodes; PBOUndary and PHYSical name edge
!> sets of the mesh, and PHYSical ones lie on the boundary.
!> Tolerances scale with the mesh size h = the larger side of the bounding box of the nodes used
!> by elements: EBOUndary and CBOUndary LINEar 1e-6 h (CBOUndary GAP overrides), TIE 1e-8 h.
module exic_input_deck_finish
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_sort, only: search_sorted
   use exic_mesh_mesh, only: mesh_t
   use exic_mesh_boundary, only: bodies_elements
   use exic_mesh_tie, only: tie_map, apply_tie
   use exic_material_material, only: MAT_UNDEFINED, MAT_RIGID, material_t
   use exic_contact_spec, only: contact_spec_t, SURF_REGION, SURF_MATERIAL, SURF_FACETS
   use exic_mesh_edge_set, only: find_edge_set, edge_set_nodes, edge_set_ids
   use exic_model_model, only: model_t
   use exic_input_deck_records, only: keyword_is
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: reader_t, fail, warn, warn_at, where, itoa, word, field, int_field, &
                             unknown_keyword, has_field
   use exic_input_deck_mesh, only: builder_t, CB_NODE, CB_LINE, INIT_NODE, INIT_REGION, INIT_MATERIAL
   implicit none
   private

   public :: finish_mesh, check_contact, energy_warnings, cmd_tie, used_nodes, mesh_size, nearest_node
   public :: physical_surfaces

contains

   !> Nodes used by at least one element (the active nodes).
   function used_nodes(mesh) result(used)
      type(mesh_t), intent(in) :: mesh
      logical :: used(mesh%nnode)
      integer :: e, k
      used = .false.
      do e = 1, mesh%nelem
         do k = 1, 4
            if (mesh%conn(k, e) >= 1 .and. mesh%conn(k, e) <= mesh%nnode) used(mesh%conn(k, e)) = .true.
         end do
      end do
   end function used_nodes

   !> Larger side of the bounding box of the nodes marked in `mask` (1 when that is zero).
   pure real(wp) function mesh_size(mesh, mask)
      type(mesh_t), intent(in) :: mesh
      logical, intent(in) :: mask(:)
      real(wp) :: dx, dy
      mesh_size = 1.0_wp
      if (.not. any(mask)) return
      dx = maxval(mesh%x(1, :), mask) - minval(mesh%x(1, :), mask)
      dy = maxval(mesh%x(2, :), mask) - minval(mesh%x(2, :), mask)
      mesh_size = max(dx, dy)
      if (mesh_size <= 0.0_wp) mesh_size = 1.0_wp
   end function mesh_size

   !> The node of `mask` nearest to p (lowest number on a tie); 0 when the mask is empty.
   pure integer function nearest_node(mesh, mask, p)
      type(mesh_t), intent(in) :: mesh
      logical, intent(in) :: mask(:)
      real(wp), intent(in) :: p(2)
      real(wp) :: d, dbest
      integer :: n
      nearest_node = 0
      dbest = huge(1.0_wp)
      do n = 1, mesh%nnode
         if (.not. mask(n)) cycle
         d = (mesh%x(1, n) - p(1))**2 + (mesh%x(2, n) - p(2))**2
         if (d < dbest) then
            dbest = d
            nearest_node = n
         end if
      end do
   end function nearest_node

   !> Size the mesh, check it, and apply the deferred sets. `iend` is the END record; `counts`
   !> holds numnp, numel, nummat of the control record (0 = count) and `ictl` its record.
   subroutine finish_mesh(rd, b, iend, counts, ictl, model, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: iend, counts(3), ictl
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: nn, ne, e, k, n, m

      nn = b%m%nnode
      ne = b%m%nelem
      if (ne == 0) then
         call fail(rd, iend, 'the mesh has no elements: expected ELEMents or BLOCk before END', err)
         return
      end if
      associate (mesh => model%mesh)
         mesh%nnode = nn
         mesh%nelem = ne
         mesh%x = b%m%x(:, 1:nn)
         mesh%defined = b%m%defined(1:nn)
         mesh%bc = b%m%bc(:, 1:nn)
         mesh%force = b%m%force(:, 1:nn)
         mesh%disp = b%m%disp(:, 1:nn)
         mesh%v0 = b%m%v0(:, 1:nn)
         mesh%conn = b%m%conn(:, 1:ne)
         mesh%mat = b%m%mat(1:ne)
         mesh%region = b%m%region(1:ne)
         if (allocated(b%m%edge_sets)) mesh%edge_sets = b%m%edge_sets
      end associate
      m = 0
      do k = 1, b%nmat
         if (b%mat_rec(k) > 0) m = k
      end do
      allocate (model%materials(m))
      if (m > 0) model%materials = b%mats(1:m)
      do e = 1, ne
         if (.not. b%edef(e)) then
            call fail(rd, iend, 'element '//itoa(e)//' is missing: expected elements numbered 1..'// &
                      itoa(ne)//' without gaps', err)
            return
         end if
         do k = 1, 4
            n = model%mesh%conn(k, e)
            if (n < 1 .or. n > nn) then
               call fail(rd, b%erec(e), 'element '//itoa(e)//' uses node '//itoa(n)// &
                         ', which has no coordinates: expected a node defined by COORdinates or BLOCk', err)
               return
            end if
            if (.not. model%mesh%defined(n)) then
               call fail(rd, b%erec(e), 'element '//itoa(e)//' uses node '//itoa(n)// &
                         ', which has no coordinates: expected a node defined by COORdinates or BLOCk', err)
               return
            end if
         end do
         m = model%mesh%mat(e)
         if (m > size(model%materials)) then
            call missing_material(rd, b, e, m, model%mesh, err)
            return
         end if
         if (b%mat_rec(m) == 0 .or. model%materials(m)%kind == MAT_UNDEFINED) then
            call missing_material(rd, b, e, m, model%mesh, err)
            return
         end if
      end do
      call check_orientation(rd, b, model%mesh, err)
      if (allocated(err)) return
      call check_axisymmetric(rd, b, model, err)
      if (allocated(err)) return
      call check_nodal_records(rd, b, model%mesh, err)
      if (allocated(err)) return
      call check_counts(rd, ictl, counts, nn, ne, size(model%materials), err)
      if (allocated(err)) return
      call apply_ebound(rd, b, model%mesh)
      call apply_pbound(rd, b, model%mesh, err)
      if (allocated(err)) return
      call apply_cbound(rd, b, model%mesh)
      call apply_initial(rd, b, model%mesh, err)
   end subroutine finish_mesh

   !> GLOBal AXISymmetric: every node of an element at r = x >= 0 (error at the record that
   !> defined the first node with r < 0), and no free rigid body (its three dofs are planar).
   !> A node of a deformable element at r = 0 stays on the axis: its radial dof is prescribed
   !> (u_r = 0; doc/axisymmetry.md, section 4).
   subroutine check_axisymmetric(rd, b, model, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(in) :: b
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: e, k, n, m
      model%mesh%axisymmetric = b%axis_rec > 0
      if (b%axis_rec == 0) return
      do e = 1, model%mesh%nelem
         do k = 1, 4
            n = model%mesh%conn(k, e)
            if (model%mesh%x(1, n) < 0.0_wp) then
               call fail(rd, merge(b%nrec(n), b%axis_rec, b%nrec(n) > 0), 'node '//itoa(n)// &
                         ' (of element '//itoa(e)//') at r = x = '//rtoa(model%mesh%x(1, n), SHORT_REAL)// &
                         ' < 0 with GLOBal AXISymmetric (at '//where(rd, b%axis_rec)// &
                         '): expected every node at r >= 0 (x = r, y = z)', err)
               return
            end if
         end do
         m = model%mesh%mat(e)
         if (model%materials(m)%kind == MAT_RIGID .and. model%materials(m)%free) then
            call fail(rd, b%mat_rec(m), 'MATErial '//itoa(m)//': a free rigid body (RIGId,FREE) '// &
                      'is not supported with GLOBal AXISymmetric (at '//where(rd, b%axis_rec)// &
                      '): expected RIGId (fixed or driven) or a SOLId', err)
            return
         end if
         if (model%materials(m)%kind /= MAT_RIGID) then
            do k = 1, 4
               n = model%mesh%conn(k, e)
               if (model%mesh%x(1, n) == 0.0_wp) then
                  model%mesh%bc(1, n) = 1
                  model%mesh%disp(1, n) = 0.0_wp
               end if
            end do
         end if
      end do
   end subroutine check_axisymmetric

   !> An element's material set missing: `err` names it (for a GMSH element, the physical
   !> surface that asked for it).
   subroutine missing_material(rd, b, e, m, mesh, err)
      type(reader_t), intent(in) :: rd
      type(builder_t), intent(in) :: b
      integer, intent(in) :: e, m
      type(mesh_t), intent(in) :: mesh
      type(error_t), allocatable, intent(out) :: err
      if (keyword_is(word(rd, b%erec(e), 1), 'gmsh')) then
         call fail(rd, b%erec(e), 'element '//itoa(e)//' of Gmsh Physical Surface '// &
                   itoa(mesh%region(e))//' uses material set '//itoa(m)//', which has no '// &
                   'MATErial set: expected MATErial,'//itoa(m)//' (physical surface t takes '// &
                   'material set t)', err)
      else
         call fail(rd, b%erec(e), 'element '//itoa(e)//' uses material '//itoa(m)// &
                   ', which has no MATErial set: expected MATErial,'//itoa(m), err)
      end if
   end subroutine missing_material

   !> Every node named by a BOUNdary, FORCe or DISPlacement record exists: a node without
   !> coordinates is an error naming the record; a node used by no element (whose record has no
   !> effect) gives a warning. Checked before the EBOUndary and CBOUndary sets are applied.
   subroutine check_nodal_records(rd, b, mesh, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(in) :: mesh
      type(error_t), allocatable, intent(out) :: err
      logical :: used(mesh%nnode)
      integer :: n, last_warned
      used = used_nodes(mesh)
      last_warned = 0
      do n = 1, mesh%nnode
         if (b%vrec(n) == 0) cycle
         if (.not. mesh%defined(n)) then
            call fail(rd, b%vrec(n), 'node '//itoa(n)//' has no coordinates: expected a node '// &
                      'defined by COORdinates or BLOCk', err)
            return
         end if
         if (.not. used(n) .and. b%vrec(n) /= last_warned) then
            call warn(rd, b%vrec(n), 'node '//itoa(n)//' is used by no element: the record has '// &
                      'no effect on it')
            last_warned = b%vrec(n)
         end if
      end do
   end subroutine check_nodal_records

   !> Non-zero counts of the control record are upper bounds.
   subroutine check_counts(rd, ictl, counts, nn, ne, nm, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: ictl, counts(3), nn, ne, nm
      type(error_t), allocatable, intent(out) :: err
      if (counts(1) > 0 .and. nn > counts(1)) then
         call fail(rd, ictl, 'the mesh has '//itoa(nn)//' nodes: expected at most numnp = '// &
                   itoa(counts(1))//' (0 = count)', err)
      else if (counts(2) > 0 .and. ne > counts(2)) then
         call fail(rd, ictl, 'the mesh has '//itoa(ne)//' elements: expected at most numel = '// &
                   itoa(counts(2))//' (0 = count)', err)
      else if (counts(3) > 0 .and. nm > counts(3)) then
         call fail(rd, ictl, 'the deck has material sets up to '//itoa(nm)// &
                   ': expected at most nummat = '//itoa(counts(3))//' (0 = count)', err)
      end if
   end subroutine check_counts

   !> Every element counter-clockwise: positive area and positive corner cross products.
   subroutine check_orientation(rd, b, mesh, err)
      type(reader_t), intent(in) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(in) :: mesh
      type(error_t), allocatable, intent(out) :: err
      integer :: e, k, c(4), j
      real(wp) :: xe(2, 4), area, cross, e1(2), e2(2)
      character(len=:), allocatable :: nodes
      do e = 1, mesh%nelem
         c = mesh%conn(:, e)
         xe = mesh%x(:, c)
         area = 0.5_wp*((xe(1, 3) - xe(1, 1))*(xe(2, 4) - xe(2, 2)) - &
                        (xe(2, 3) - xe(2, 1))*(xe(1, 4) - xe(1, 2)))
         do k = 1, 4
            e1 = xe(:, modulo(k, 4) + 1) - xe(:, k)
            e2 = xe(:, modulo(k + 2, 4) + 1) - xe(:, k)
            cross = e1(1)*e2(2) - e1(2)*e2(1)
            if (cross <= 0.0_wp .or. area <= 0.0_wp) then
               nodes = itoa(c(1))//' '//itoa(c(2))//' '//itoa(c(3))//' '//itoa(c(4))
               j = collapsed_corner(xe)
               if (j > 0) then
                  call fail(rd, b%erec(e), 'element '//itoa(e)//' (nodes '//nodes// &
                            ') has two corners at one point: nodes '//itoa(c(j))//' and '// &
                            itoa(c(modulo(j, 4) + 1))//' at ('//rtoa(xe(1, j), SHORT_REAL)//', '// &
                            rtoa(xe(2, j), SHORT_REAL)//'): expected four distinct corners (a 4-node '// &
                            'element cannot be collapsed to a triangle)', err)
               else if (area <= 0.0_wp) then
                  call fail(rd, b%erec(e), 'element '//itoa(e)//' (nodes '//nodes// &
                            ') has non-positive area '//rtoa(area, SHORT_REAL)//': expected counter-clockwise'// &
                            ' nodes', err)
               else
                  call fail(rd, b%erec(e), 'element '//itoa(e)//' (nodes '//nodes// &
                            ') is clockwise or not convex at node '//itoa(c(k))// &
                            ': expected a convex counter-clockwise quadrilateral', err)
               end if
               return
            end if
         end do
      end do
   end subroutine check_orientation

   !> EBOUndary sets, in input order (ADD: > 0 fixes, < 0 releases, 0 keeps; SET: replaces).
   subroutine apply_ebound(rd, b, mesh)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(inout) :: mesh
      logical :: used(mesh%nnode)
      real(wp) :: tol
      integer :: k, n, hits
      used = used_nodes(mesh)
      tol = 1.0e-6_wp*mesh_size(mesh, used)
      do k = 1, b%nebou
         hits = 0
         do n = 1, mesh%nnode
            if (.not. mesh%defined(n)) cycle
            if (abs(mesh%x(b%ebou(k)%dir, n) - b%ebou(k)%x) > tol) cycle
            call set_codes(mesh%bc(:, n), b%ebou(k)%code, b%ebou(k)%set)
            if (used(n)) hits = hits + 1
         end do
         if (hits == 0) call warn(rd, b%ebou(k)%rec, 'EBOUndary matched no node of the mesh')
      end do
   end subroutine apply_ebound

   !> First corner j of an element whose next corner (j+1, cyclic) coincides with it (0: none).
   pure integer function collapsed_corner(xe) result(j)
      real(wp), intent(in) :: xe(2, 4)
      real(wp) :: h
      h = max(maxval(xe(1, :)) - minval(xe(1, :)), maxval(xe(2, :)) - minval(xe(2, :)))
      do j = 1, 4
         if (norm2(xe(:, j) - xe(:, modulo(j, 4) + 1)) <= 1.0e-12_wp*h) return
      end do
      j = 0
   end function collapsed_corner

   !> PBOUndary items in input order, on every node of their edge set (ADD: > 0 fixes, < 0
   !> releases, 0 keeps; SET replaces). An unknown edge set is an error.
   subroutine apply_pbound(rd, b, mesh, err)
      type(reader_t), intent(in) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(inout) :: mesh
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: nodes(:)
      integer :: k, s, j
      do k = 1, b%npbou
         s = find_edge_set(mesh%edge_sets, b%pbou(k)%id)
         if (s == 0) then
            call fail(rd, b%pbou(k)%rec, 'PBOUndary: physical curve '//itoa(b%pbou(k)%id)// &
                      ' is not in the mesh: expected one of the physical curves of the GMSH '// &
                      'meshes (here: '//edge_set_ids(mesh%edge_sets)//')', err)
            return
         end if
         nodes = edge_set_nodes(mesh%edge_sets(s))
         do j = 1, size(nodes)
            call set_codes(mesh%bc(:, nodes(j)), b%pbou(k)%code, b%pbou(k)%set)
         end do
      end do
   end subroutine apply_pbound

   !> Contact surfaces given by `PHYSical,c` take the edges of edge set c as their facets; the
   !> set must exist and lie on the boundary (each edge used by one element).
   subroutine physical_surfaces(spec, mesh, err)
      type(contact_spec_t), intent(inout) :: spec
      type(mesh_t), intent(in) :: mesh
      type(error_t), allocatable, intent(out) :: err
      integer :: k, s, inner
      if (.not. spec%active) return
      do k = 1, size(spec%surfaces)
         associate (sp => spec%surfaces(k))
            if (sp%physical == 0) cycle
            s = find_edge_set(mesh%edge_sets, sp%physical)
            if (s == 0) then
               call make_error(err, sp%physical_where//': SURFace '//itoa(sp%id)// &
                               ': physical curve '//itoa(sp%physical)//' is not in the mesh: '// &
                               'expected one of the physical curves of the GMSH meshes (here: '// &
                               edge_set_ids(mesh%edge_sets)//')')
               return
            end if
            inner = count(mesh%edge_sets(s)%other /= 0)
            if (inner > 0) then
               call make_error(err, sp%physical_where//': SURFace '//itoa(sp%id)// &
                               ': physical curve '//itoa(sp%physical)//' has '//itoa(inner)// &
                               ' of its '//itoa(mesh%edge_sets(s)%nedge)//' edges between two '// &
                               'elements: expected a curve on the boundary of a body (a contact '// &
                               'surface has its body on one side)')
               return
            end if
            sp%facets = mesh%edge_sets(s)%edge
         end associate
      end do
   end subroutine physical_surfaces

   !> CBOUndary items after the edge sets (SET replaces, ADD combines).
   subroutine apply_cbound(rd, b, mesh)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(inout) :: mesh
      logical :: used(mesh%nnode)
      real(wp) :: h, tol, d(2), t, dist, p(2), len2
      integer :: k, n, hits
      used = used_nodes(mesh)
      h = mesh_size(mesh, used)
      do k = 1, b%ncbou
         associate (cb => b%cbou(k))
            tol = 1.0e-6_wp*h
            if (cb%gap >= 0.0_wp) tol = cb%gap
            if (cb%kind == CB_NODE) then
               n = nearest_node(mesh, used, cb%p(:, 1))
               if (n == 0) cycle
               dist = norm2(mesh%x(:, n) - cb%p(:, 1))
               if (dist > 1.0e-3_wp*h) call warn(rd, cb%rec, 'CBOUndary NODE: the nearest node '// &
                                                 itoa(n)//' is '//rtoa(dist, SHORT_REAL)//' away')
               call set_codes(mesh%bc(:, n), cb%code, cb%set)
            else
               d = cb%p(:, 2) - cb%p(:, 1)
               len2 = dot_product(d, d)
               hits = 0
               do n = 1, mesh%nnode
                  if (.not. used(n)) cycle
                  t = 0.0_wp
                  if (len2 > 0.0_wp) t = dot_product(mesh%x(:, n) - cb%p(:, 1), d)/len2
                  t = min(1.0_wp, max(0.0_wp, t))
                  p = cb%p(:, 1) + t*d
                  if (norm2(mesh%x(:, n) - p) > tol) cycle
                  call set_codes(mesh%bc(:, n), cb%code, cb%set)
                  hits = hits + 1
               end do
               if (hits == 0) call warn(rd, cb%rec, 'CBOUndary LINEar matched no node of the mesh')
            end if
         end associate
      end do
   end subroutine apply_cbound

   !> Combine boundary codes: SET replaces (non-zero = 1); ADD: > 0 fixes, < 0 releases.
   pure subroutine set_codes(bc, code, set)
      integer, intent(inout) :: bc(2)
      integer, intent(in) :: code(2)
      logical, intent(in) :: set
      integer :: k
      do k = 1, 2
         if (set) then
            bc(k) = merge(1, 0, code(k) /= 0)
         else if (code(k) > 0) then
            bc(k) = 1
         else if (code(k) < 0) then
            bc(k) = 0
         end if
      end do
   end subroutine set_codes

   !> Mesh-phase INITial,VELOcity items in input order.
   subroutine apply_initial(rd, b, mesh, err)
      type(reader_t), intent(in) :: rd
      type(builder_t), intent(in) :: b
      type(mesh_t), intent(inout) :: mesh
      type(error_t), allocatable, intent(out) :: err
      integer :: k, n
      logical :: hit
      ! the elements of each region and of each material (one sort each, not a pass over every
      ! element per record: a deck may give thousands of bodies their own velocity)
      integer, allocatable :: rid(:), rfirst(:), relems(:), mid(:), mfirst(:), melems(:)
      if (b%ninit == 0) return
      if (any(b%init(1:b%ninit)%kind == INIT_REGION)) &
         call bodies_elements(mesh%nelem, mesh%region, rid, rfirst, relems)
      if (any(b%init(1:b%ninit)%kind == INIT_MATERIAL)) &
         call bodies_elements(mesh%nelem, mesh%mat, mid, mfirst, melems)
      do k = 1, b%ninit
         associate (it => b%init(k))
            select case (it%kind)
            case (INIT_NODE)
               n = it%id
               if (n > mesh%nnode) then
                  call fail(rd, it%rec, 'INITial,VELOcity: node '//itoa(n)// &
                            ' is not in the mesh: expected a node number in 1..'//itoa(mesh%nnode), err)
                  return
               end if
               if (.not. mesh%defined(n)) then
                  call fail(rd, it%rec, 'INITial,VELOcity: node '//itoa(n)// &
                            ' has no coordinates: expected a defined node', err)
                  return
               end if
               mesh%v0(:, n) = it%v
            case (INIT_REGION, INIT_MATERIAL)
               ! the record's elements in ascending order, as a pass over all of them meets them
               if (it%kind == INIT_REGION) then
                  call set_velocity(rid, rfirst, relems, it%id, it%v, hit)
               else
                  call set_velocity(mid, mfirst, melems, it%id, it%v, hit)
               end if
               if (.not. hit) then
                  if (it%kind == INIT_REGION) then
                     call fail(rd, it%rec, 'INITial,VELOcity: region '//itoa(it%id)// &
                               ' has no elements: expected an existing region', err)
                  else
                     call fail(rd, it%rec, 'INITial,VELOcity: material '//itoa(it%id)// &
                               ' has no elements: expected an existing material', err)
                  end if
                  return
               end if
            end select
         end associate
      end do
   contains
      !> Velocity v at every node of the elements of group id (ids ascending, its elements
      !> elems(first(j):first(j + 1) - 1)); hit: the group exists.
      subroutine set_velocity(ids, first, elems, id, v, hit)
         integer, intent(in) :: ids(:), first(:), elems(:), id
         real(wp), intent(in) :: v(2)
         logical, intent(out) :: hit
         integer :: m, i
         m = search_sorted(ids, id)
         hit = m > 0
         if (.not. hit) return
         do i = first(m), first(m + 1) - 1
            mesh%v0(:, mesh%conn(1, elems(i))) = v
            mesh%v0(:, mesh%conn(2, elems(i))) = v
            mesh%v0(:, mesh%conn(3, elems(i))) = v
            mesh%v0(:, mesh%conn(4, elems(i))) = v
         end do
      end subroutine set_velocity
   end subroutine apply_initial

   !> Regions and materials named by the contact surfaces exist; FACEts nodes are element nodes.
   subroutine check_contact(spec, mesh, err)
      type(contact_spec_t), intent(in) :: spec
      type(mesh_t), intent(in) :: mesh
      type(error_t), allocatable, intent(out) :: err
      logical :: used(mesh%nnode)
      integer :: k, f, j, n
      if (.not. spec%active) return
      used = used_nodes(mesh)
      do k = 1, size(spec%surfaces)
         associate (s => spec%surfaces(k))
            select case (s%by)
            case (SURF_REGION)
               if (.not. any(mesh%region == s%ref)) then
                  call make_error(err, s%where//': SURFace '//itoa(s%id)//': region '// &
                                  itoa(s%ref)//' has no elements: expected an existing region')
                  return
               end if
            case (SURF_MATERIAL)
               if (.not. any(mesh%mat == s%ref)) then
                  call make_error(err, s%where//': SURFace '//itoa(s%id)//': material '// &
                                  itoa(s%ref)//' has no elements: expected an existing material')
                  return
               end if
            case (SURF_FACETS)
               do f = 1, size(s%facets, 2)
                  do j = 1, 2
                     n = s%facets(j, f)
                     if (n > mesh%nnode) then
                        call make_error(err, s%where//': SURFace '//itoa(s%id)//': facet '// &
                                        itoa(f)//' uses node '//itoa(n)//': expected a node of the mesh')
                        return
                     end if
                     if (.not. used(n)) then
                        call make_error(err, s%where//': SURFace '//itoa(s%id)//': facet '// &
                                        itoa(f)//' uses node '//itoa(n)//': expected a node of the mesh')
                        return
                     end if
                  end do
               end do
            end select
         end associate
      end do
   end subroutine check_contact

   !> `LAGRange,ENERgy` on a whole-boundary surface (REGIon, MATErial or AUTOmatic) of a
   !> deformable body whose partner is deformable makes every boundary row of that body massless
   !> along its normals (eq. I.3a), not only the struck face: measured less accurate on equal bars
   !> and on the seed's 2-D examples (doc/impact.md, section 4). A warning at the pair names the
   !> surface. Against a rigid partner only the segments that face it are massless (eq. I.3b): no
   !> warning.
   subroutine energy_warnings(rd, spec, mesh, materials)
      type(reader_t), intent(inout) :: rd
      type(contact_spec_t), intent(in) :: spec
      type(mesh_t), intent(in) :: mesh
      type(material_t), intent(in) :: materials(:)
      character(len=*), parameter :: why = ' makes the whole boundary of its bodies a massless '// &
         'face (along its normals where it meets a deformable body, doc/impact.md section 3.1, eq. I.3a), '// &
         'not only the struck face; its energy is verified to 0.1 % with the struck faces declared '// &
         '(FACEts or PHYSical) and small strains, to 0.5 % on the seed''s examples (doc/impact.md, '// &
         'section 4)'
      integer :: k, j, id, other
      if (.not. spec%active) return
      if (spec%automatic .and. spec%auto_options%energy) &
         call warn_at(rd, spec%auto_options%where, 'AUTOmatic with LAGRange,ENERgy'//why)
      if (.not. allocated(spec%pairs)) return
      do k = 1, size(spec%pairs)
         if (.not. spec%pairs(k)%energy) cycle
         do j = 1, 2
            id = merge(spec%pairs(k)%slave, spec%pairs(k)%master, j == 1)
            other = merge(spec%pairs(k)%master, spec%pairs(k)%slave, j == 1)
            ! against a rigid partner only the segments that face it are massless (eq. I.3b)
            if (deformable_whole_boundary(id) .and. deformable_surface(other)) then
               call warn_at(rd, spec%pairs(k)%where, 'PAIR '//itoa(spec%pairs(k)%id)//' with '// &
                            'LAGRange,ENERgy on SURFace '//itoa(id)//' (REGIon or MATErial)'//why)
               exit
            end if
         end do
      end do
   contains
      !> Surface `id` is a REGIon or MATErial surface with an element of a non-rigid material.
      logical function deformable_whole_boundary(id)
         integer, intent(in) :: id
         integer :: s, e, m
         deformable_whole_boundary = .false.
         do s = 1, size(spec%surfaces)
            if (spec%surfaces(s)%id /= id) cycle
            do e = 1, mesh%nelem
               if (spec%surfaces(s)%by == SURF_REGION) then
                  if (mesh%region(e) /= spec%surfaces(s)%ref) cycle
               else if (spec%surfaces(s)%by == SURF_MATERIAL) then
                  if (mesh%mat(e) /= spec%surfaces(s)%ref) cycle
               else
                  cycle
               end if
               m = mesh%mat(e)
               if (m < 1 .or. m > size(materials)) cycle
               if (materials(m)%kind /= MAT_RIGID) deformable_whole_boundary = .true.
               if (deformable_whole_boundary) return
            end do
         end do
      end function deformable_whole_boundary

      !> Surface `id` has a node of an element of a non-rigid material.
      logical function deformable_surface(id)
         integer, intent(in) :: id
         logical :: on(mesh%nnode)
         integer :: s, e, m, a
         deformable_surface = deformable_whole_boundary(id)
         if (deformable_surface) return
         on = .false.
         do s = 1, size(spec%surfaces)
            if (spec%surfaces(s)%id /= id) cycle
            if (allocated(spec%surfaces(s)%facets)) on(pack(spec%surfaces(s)%facets, &
                                                            spec%surfaces(s)%facets >= 1 .and. &
                                                            spec%surfaces(s)%facets <= mesh%nnode)) = .true.
            if (allocated(spec%surfaces(s)%nodes)) on(pack(spec%surfaces(s)%nodes, spec%surfaces(s)%nodes >= 1 .and. &
                                                           spec%surfaces(s)%nodes <= mesh%nnode)) = .true.
         end do
         do e = 1, mesh%nelem
            m = mesh%mat(e)
            if (m < 1 .or. m > size(materials)) cycle
            if (materials(m)%kind == MAT_RIGID) cycle
            do a = 1, size(mesh%conn, 1)
               if (mesh%conn(a, e) < 1 .or. mesh%conn(a, e) > mesh%nnode) cycle
               if (on(mesh%conn(a, e))) deformable_surface = .true.
            end do
            if (deformable_surface) return
         end do
      end function deformable_surface
   end subroutine energy_warnings

   !> TIE record `i` (after END): `TIE` merges all coincident element nodes; `TIE,REGIon,r1,r2`
   !> and `TIE,MATErial,m1,m2` the nodes of elements of those regions/materials (r1 may equal
   !> r2); `TIE,NODE,n1,n2` the nodes n1..n2. `map` accumulates the merges (node -> survivor).
   subroutine cmd_tie(rd, i, model, map, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(model_t), intent(inout) :: model
      integer, intent(inout) :: map(:)
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: opts(3) = [character(len=12) :: 'REGIon', 'MATErial', 'NODE']
      logical :: used(model%mesh%nnode), cand(model%mesh%nnode)
      integer :: step(model%mesh%nnode), a, c, e, n, k, merged
      character(len=:), allocatable :: w
      real(wp) :: tol

      used = used_nodes(model%mesh)
      cand = used
      w = word(rd, i, 2)
      if (len(w) > 0) then
         call int_field(rd, i, 3, 'TIE,'//field(rd, i, 2)//',n1,n2', a, err)
         if (.not. allocated(err)) call int_field(rd, i, 4, 'TIE,'//field(rd, i, 2)//',n1,n2', c, err)
         if (allocated(err)) return
         if (.not. has_field(rd, i, 4)) c = a
         cand = .false.
         if (keyword_is(w, 'regi') .or. keyword_is(w, 'mate')) then
            do e = 1, model%mesh%nelem
               if (keyword_is(w, 'regi')) then
                  k = model%mesh%region(e)
               else
                  k = model%mesh%mat(e)
               end if
               if (k == a .or. k == c) cand(model%mesh%conn(:, e)) = .true.
            end do
         else if (keyword_is(w, 'node')) then
            do n = max(1, a), min(c, model%mesh%nnode)
               cand(n) = used(n)
            end do
         else
            call unknown_keyword(rd, i, 'TIE option', field(rd, i, 2), opts, err)
            return
         end if
      end if
      tol = 1.0e-8_wp*mesh_size(model%mesh, used)
      call tie_map(model%mesh%nnode, model%mesh%x, cand, tol, step)
      call apply_tie(model%mesh, step)
      merged = count([(step(n) /= n, n=1, model%mesh%nnode)])
      if (merged == 0) call warn(rd, i, 'TIE merged no nodes')
      do n = 1, size(map)
         map(n) = step(map(n))
      end do
      if (model%contact%active) then
         do k = 1, size(model%contact%surfaces)
            if (allocated(model%contact%surfaces(k)%facets)) then
               associate (fac => model%contact%surfaces(k)%facets)
                  fac = reshape(step(reshape(fac, [size(fac)])), shape(fac))
               end associate
            end if
         end do
      end if
   end subroutine cmd_tie

end module exic_input_deck_finish
