!> Loads and prescribed motion in a deck (input language, sections 3 and 5; doc/loads.md):
!>
!> ```
!> FPROportional                     n, ng, p1, p2  (FEAP generation): function of each dof
!> GRAVity,gx,gy[,prop]              [ext] acceleration of every deformable and free rigid body
!> MOTIon,REGIon,r,vx,vy[,omega[,prop]]  [ext] a region driven at a velocity (rigid: and spin)
!> CSURface                          FEAP edge loads, data set:
!>   NORMal | TANGential               the load of the groups that follow
!>   LINEar                            then point records k, x, y, p (k = 1, 2, ...)
!>   PHYSical, c, p                    [ext] every edge of Gmsh physical curve c, uniform p
!> PROPortional,,n1[,n2]             (BATCh) functions n1..n2 read after END, each ended by a
!>                                   blank record: `1, k, tmin, tmax, a1, a2, a3, a4`, or
!>                                   `2, nn` and records of t, p pairs, or a blank record alone
!> ```
!> The mesh commands are kept in a `loads_builder_t` and resolved after the TIE records
!> (`finish_loads`: edges found on the final boundary, regions checked, FPRO mapped through
!> TIE); the function numbers they name are checked once the PROPortional data is read
!> (`check_functions`). Every error names file:line and what was expected.
module exic_input_deck_loads
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_grow, only: grow_size
   use exic_input_deck_grow, only: grow
   use exic_material_material, only: MAT_SOLID, MAT_RIGID
   use exic_mesh_boundary, only: free_edges
   use exic_mesh_edge_set, only: find_edge_set, edge_set_ids
   use exic_explicit_loads, only: load_spec_t, prop_fn_t, motion_t, FN_UNDEFINED, FN_TYPE1, &
                                  FN_TABLE, FN_RAMP, EDGE_NORMAL, EDGE_TANGENTIAL
   use exic_model_model, only: model_t
   use exic_input_deck_records, only: keyword_is
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: next_in_set, next_record, reader_t, nfields, field, word, has_field, &
                             real_field, int_field, fail, where, unknown_keyword, itoa, &
                             looks_like_data, check_data_record, end_set
   use exic_input_deck_mesh, only: genvec_t, node_record
   use exic_input_deck_finish, only: used_nodes, mesh_size
   implicit none
   private

   public :: loads_builder_t, cmd_fpro, cmd_gravity, cmd_motion, cmd_csurface, finish_loads, &
             check_functions, read_prop_data

   !> One CSURface group: its load kind and its path (LINEar points or a physical curve).
   type :: csurf_t
      integer :: kind = EDGE_NORMAL
      integer :: physical = 0                  !< PHYSical curve (0: LINEar points)
      real(wp) :: value = 0.0_wp               !< PHYSical: uniform value
      real(wp), allocatable :: pts(:, :)       !< (3, npt) x, y, value of the LINEar points
      integer, allocatable :: prec(:)          !< (npt) records of the points
      integer :: rec = 0                       !< record of LINEar / PHYSical
   end type csurf_t

   !> A reference to a proportional function, checked once the functions are read.
   type :: fn_ref_t
      integer :: id = 0
      integer :: rec = 0
      character(len=:), allocatable :: what
   end type fn_ref_t

   !> The load commands of the mesh phase, resolved after the TIE records.
   type :: loads_builder_t
      integer :: nfpro = 0
      integer, allocatable :: fnode(:), frec(:)
      real(wp), allocatable :: fval(:, :)
      integer :: grav_rec = 0
      type(csurf_t), allocatable :: csurf(:)
      type(motion_t), allocatable :: motions(:)
      integer, allocatable :: mrec(:)
      type(fn_ref_t), allocatable :: refs(:)
   end type loads_builder_t

contains

   !> FPROportional: `n, ng, p1, p2` records (FEAP generation, as FORCe: linear between records,
   !> rounded to a function number); the values replace earlier ones.
   subroutine cmd_fpro(rd, lb, err)
      type(reader_t), intent(inout) :: rd
      type(loads_builder_t), intent(inout) :: lb
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'FPROportional record n, ng, p1, p2'
      type(genvec_t) :: g
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: i, cnt, k, old, d, id, last
      if (.not. allocated(lb%fnode)) allocate (lb%fnode(0), lb%frec(0), lb%fval(2, 0))
      cnt = 0
      do
         call next_in_set(rd, i)
         if (i == 0) exit
         call check_data_record(rd, i, 'FPROportional', err)
         if (allocated(err)) return
         old = cnt
         call node_record(rd, i, 1, what, 0, .false., g, nodes, vals, cnt, err)
         if (allocated(err)) return
         if (any(vals(:, old + 1:cnt) < 0.0_wp)) then
            call fail(rd, i, what//': expected function numbers >= 0 (0: the sum of all functions)', err)
            return
         end if
         last = -1
         do k = old + 1, cnt
            lb%fnode = [lb%fnode, nodes(k)]
            lb%frec = [lb%frec, i]
            lb%fval = reshape([reshape(lb%fval, [2*size(lb%frec) - 2]), anint(vals(:, k))], &
                              [2, size(lb%frec)])
            do d = 1, 2
               id = nint(vals(d, k))
               if (id > 0 .and. id /= last) call add_ref(lb, id, i, 'FPROportional')
               if (id > 0) last = id
            end do
         end do
      end do
      lb%nfpro = size(lb%fnode)
   end subroutine cmd_fpro

   !> Remember that record `rec` names function `id`.
   subroutine add_ref(lb, id, rec, what)
      type(loads_builder_t), intent(inout) :: lb
      integer, intent(in) :: id, rec
      character(len=*), intent(in) :: what
      integer :: n
      n = 0
      if (allocated(lb%refs)) n = size(lb%refs)
      ! the size is the count
      call grow_fn_ref(lb%refs, n + 1, exact=.true.)
      lb%refs(n + 1)%id = id
      lb%refs(n + 1)%rec = rec
      lb%refs(n + 1)%what = what
   end subroutine add_ref

   !> [ext] GRAVity,gx,gy[,prop] (one record).
   subroutine cmd_gravity(rd, lb, spec, i, err)
      type(reader_t), intent(inout) :: rd
      type(loads_builder_t), intent(inout) :: lb
      type(load_spec_t), intent(inout) :: spec
      integer, intent(in) :: i
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'GRAVity,gx,gy[,prop]'
      if (lb%grav_rec > 0) then
         call fail(rd, i, 'GRAVity is already given at '//where(rd, lb%grav_rec)// &
                   ': expected one GRAVity command', err)
         return
      end if
      if (.not. (has_field(rd, i, 2) .or. has_field(rd, i, 3))) then
         call fail(rd, i, what//': expected the acceleration gx, gy on the command record', err)
         return
      end if
      call real_field(rd, i, 2, what, spec%gravity(1), err)
      if (.not. allocated(err)) call real_field(rd, i, 3, what, spec%gravity(2), err)
      if (.not. allocated(err)) call int_field(rd, i, 4, what, spec%gravity_prop, err)
      if (allocated(err)) return
      if (spec%gravity_prop < 0) then
         call fail(rd, i, what//': prop = '//itoa(spec%gravity_prop)//': expected a function '// &
                   'number >= 0 (0: the sum of all functions)', err)
         return
      end if
      if (has_field(rd, i, 5)) then
         call fail(rd, i, what//' takes three values; the fifth field '//field(rd, i, 5)// &
                   ' is not used', err)
         return
      end if
      spec%has_gravity = .true.
      lb%grav_rec = i
      if (spec%gravity_prop > 0) call add_ref(lb, spec%gravity_prop, i, 'GRAVity')
   end subroutine cmd_gravity

   !> [ext] MOTIon,REGIon,r,vx,vy[,omega[,prop]] (one record).
   subroutine cmd_motion(rd, lb, i, err)
      type(reader_t), intent(inout) :: rd
      type(loads_builder_t), intent(inout) :: lb
      integer, intent(in) :: i
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'MOTIon,REGIon,r,vx,vy[,omega[,prop]]'
      character(len=12), parameter :: opts(1) = [character(len=12) :: 'REGIon']
      type(motion_t) :: mo
      integer :: k
      if (.not. keyword_is(word(rd, i, 2), 'regi')) then
         call unknown_keyword(rd, i, 'MOTIon option', field(rd, i, 2), opts, err)
         return
      end if
      call int_field(rd, i, 3, what, mo%region, err)
      if (.not. allocated(err)) call real_field(rd, i, 4, what, mo%v(1), err)
      if (.not. allocated(err)) call real_field(rd, i, 5, what, mo%v(2), err)
      if (.not. allocated(err)) call real_field(rd, i, 6, what, mo%omega, err)
      if (.not. allocated(err)) call int_field(rd, i, 7, what, mo%prop, err)
      if (allocated(err)) return
      if (mo%prop < 0) then
         call fail(rd, i, what//': prop = '//itoa(mo%prop)//': expected a function number >= 0 '// &
                   '(0: the sum of all functions)', err)
         return
      end if
      if (.not. allocated(lb%motions)) allocate (lb%motions(0), lb%mrec(0))
      do k = 1, size(lb%motions)
         if (lb%motions(k)%region == mo%region) then
            call fail(rd, i, 'MOTIon of region '//itoa(mo%region)//' is already given at '// &
                      where(rd, lb%mrec(k))//': expected one MOTIon per region', err)
            return
         end if
      end do
      mo%where = where(rd, i)
      lb%motions = [lb%motions, mo]
      lb%mrec = [lb%mrec, i]
      if (mo%prop > 0) call add_ref(lb, mo%prop, i, 'MOTIon')
   end subroutine cmd_motion

   !> CSURface (FEAP): groups of `NORMal|TANGential`, then `LINEar` and point records
   !> `k, x, y, p`, or [ext] `PHYSical, c, p`; ended by a blank record.
   subroutine cmd_csurface(rd, lb, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(loads_builder_t), intent(inout) :: lb
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: words(5) = [character(len=12) :: 'NORMal', 'TANGential', &
                                                   'LINEar', 'PHYSical', 'point k']
      character(len=*), parameter :: pwhat = 'CSURface point record k, x, y, p'
      integer :: i, kind, k, ngroup
      type(csurf_t) :: grp
      logical :: open_line
      real(wp) :: pt(3)

      kind = 0
      ngroup = 0
      open_line = .false.
      if (.not. allocated(lb%csurf)) allocate (lb%csurf(0))
      do
         call next_in_set(rd, i)
         if (i == 0) exit
         if (looks_like_data(rd, i)) then
            if (.not. open_line) then
               call fail(rd, i, 'CSURface: a point record before LINEar: expected NORMal or '// &
                         'TANGential, then LINEar, then the points k, x, y, p', err)
               return
            end if
            call int_field(rd, i, 1, pwhat, k, err)
            if (.not. allocated(err)) call real_field(rd, i, 2, pwhat, pt(1), err)
            if (.not. allocated(err)) call real_field(rd, i, 3, pwhat, pt(2), err)
            if (.not. allocated(err)) call real_field(rd, i, 4, pwhat, pt(3), err)
            if (allocated(err)) return
            if (k /= size(grp%prec) + 1) then
               call fail(rd, i, pwhat//': point '//itoa(k)//': expected point '// &
                         itoa(size(grp%prec) + 1)//' (points numbered 1, 2, ... in order)', err)
               return
            end if
            grp%pts = reshape([reshape(grp%pts, [3*(k - 1)]), pt], [3, k])
            grp%prec = [grp%prec, i]
            cycle
         end if
         if (open_line) call close_group(err)
         if (allocated(err)) return
         if (keyword_is(word(rd, i, 1), 'norm')) then
            kind = EDGE_NORMAL
         else if (keyword_is(word(rd, i, 1), 'tang')) then
            kind = EDGE_TANGENTIAL
         else if (keyword_is(word(rd, i, 1), 'line') .or. keyword_is(word(rd, i, 1), 'phys')) then
            if (kind == 0) then
               call fail(rd, i, 'CSURface: '//field(rd, i, 1)//' before the load type: expected '// &
                         'NORMal or TANGential first', err)
               return
            end if
            grp = csurf_t(kind=kind, rec=i)
            allocate (grp%pts(3, 0), grp%prec(0))
            if (keyword_is(word(rd, i, 1), 'line')) then
               open_line = .true.
            else
               call int_field(rd, i, 2, 'CSURface record PHYSical, c, p', grp%physical, err)
               if (.not. allocated(err)) call real_field(rd, i, 3, 'CSURface record PHYSical, c, p', &
                                                         grp%value, err)
               if (allocated(err)) return
               lb%csurf = [lb%csurf, grp]
               ngroup = ngroup + 1
            end if
         else if (keyword_is(word(rd, i, 1), 'quad')) then
            call fail(rd, i, 'CSURface QUADratic is not supported: expected LINEar (or PHYSical)', err)
            return
         else
            call check_data_record(rd, i, 'CSURface', err)
            if (.not. allocated(err)) call unknown_keyword(rd, i, 'CSURface record', field(rd, i, 1), &
                                                          words, err)
            return
         end if
      end do
      if (open_line) call close_group(err)
      if (allocated(err)) return
      if (ngroup == 0) call fail(rd, icmd, 'CSURface without a load: expected NORMal or TANGential, '// &
                                 'then LINEar and two or more points k, x, y, p', err)
   contains
      subroutine close_group(err)
         type(error_t), allocatable, intent(out) :: err
         open_line = .false.
         if (size(grp%prec) < 2) then
            call fail(rd, grp%rec, 'CSURface LINEar with '//itoa(size(grp%prec))//' point(s): '// &
                      'expected two or more point records k, x, y, p', err)
            return
         end if
         lb%csurf = [lb%csurf, grp]
         ngroup = ngroup + 1
      end subroutine close_group
   end subroutine cmd_csurface

   !> After the TIE records: FPROportional through the TIE map, the CSURface edges on the
   !> boundary of the final mesh, the MOTIon regions checked and their deformable nodes given
   !> boundary codes.
   subroutine finish_loads(rd, lb, model, map, err)
      type(reader_t), intent(inout) :: rd
      type(loads_builder_t), intent(in) :: lb
      type(model_t), intent(inout) :: model
      integer, intent(in) :: map(:)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, n
      if (lb%nfpro > 0) then
         allocate (model%loads%fpro(2, model%mesh%nnode), source=0)
         do k = 1, lb%nfpro
            n = lb%fnode(k)
            if (n > model%mesh%nnode) then
               call fail(rd, lb%frec(k), 'FPROportional: node '//itoa(n)//' is not in the mesh: '// &
                         'expected a node number in 1..'//itoa(model%mesh%nnode), err)
               return
            end if
            model%loads%fpro(:, map(n)) = nint(lb%fval(:, k))
         end do
      end if
      if (allocated(lb%csurf)) then
         if (size(lb%csurf) > 0) call resolve_edges(rd, lb, model, err)
         if (allocated(err)) return
      end if
      if (allocated(lb%motions)) then
         do k = 1, size(lb%motions)
            call resolve_motion(rd, lb%motions(k), lb%mrec(k), model, err)
            if (allocated(err)) return
         end do
         model%loads%motions = lb%motions
         do k = 1, size(lb%motions)
            call resolve_motion_flag(model%loads%motions(k), model)
         end do
      end if
   end subroutine finish_loads

   !> MOTIon: the region exists; rigid (fixed RIGId) or deformable, not a free body nor both;
   !> omega only for a rigid region; a deformable region's nodes become prescribed.
   subroutine resolve_motion(rd, mo, rec, model, err)
      type(reader_t), intent(in) :: rd
      type(motion_t), intent(in) :: mo
      integer, intent(in) :: rec
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: e, nrigid, nsolid, nfree
      nrigid = 0
      nsolid = 0
      nfree = 0
      do e = 1, model%mesh%nelem
         if (model%mesh%region(e) /= mo%region) cycle
         associate (m => model%materials(model%mesh%mat(e)))
            if (m%kind == MAT_SOLID) nsolid = nsolid + 1
            if (m%kind == MAT_RIGID .and. .not. m%free) nrigid = nrigid + 1
            if (m%kind == MAT_RIGID .and. m%free) nfree = nfree + 1
         end associate
      end do
      if (nrigid + nsolid + nfree == 0) then
         call fail(rd, rec, 'MOTIon: region '//itoa(mo%region)//' has no elements: expected an '// &
                   'existing region', err)
      else if (nfree > 0) then
         call fail(rd, rec, 'MOTIon: region '//itoa(mo%region)//' is a free rigid body (RIGId,FREE): '// &
                   'expected a deformable region or a RIGId region without FREE to drive', err)
      else if (nrigid > 0 .and. nsolid > 0) then
         call fail(rd, rec, 'MOTIon: region '//itoa(mo%region)//' has rigid and deformable elements: '// &
                   'expected a region of one kind', err)
      else if (nsolid > 0 .and. mo%omega /= 0.0_wp) then
         call fail(rd, rec, 'MOTIon: region '//itoa(mo%region)//' is deformable: expected omega = 0 '// &
                   '(an angular velocity drives a rigid region about its centroid)', err)
      else if (nsolid > 0) then
         do e = 1, model%mesh%nelem
            if (model%mesh%region(e) == mo%region) model%mesh%bc(:, model%mesh%conn(:, e)) = 1
         end do
      end if
   end subroutine resolve_motion

   !> motion%rigid: the region is a (fixed) RIGId body.
   subroutine resolve_motion_flag(mo, model)
      type(motion_t), intent(inout) :: mo
      type(model_t), intent(in) :: model
      integer :: e
      mo%rigid = .false.
      do e = 1, model%mesh%nelem
         if (model%mesh%region(e) /= mo%region) cycle
         mo%rigid = model%materials(model%mesh%mat(e))%kind == MAT_RIGID
         return
      end do
   end subroutine resolve_motion_flag

   !> The CSURface groups as edges of the final mesh's boundary: LINEar, the boundary edges whose
   !> nodes and midpoint lie on the polyline through the points (within 1e-6 of the mesh size),
   !> values interpolated along it; PHYSical, the edges of the physical curve, which must lie on
   !> the boundary. Every point must lie on a boundary edge.
   subroutine resolve_edges(rd, lb, model, err)
      type(reader_t), intent(in) :: rd
      type(loads_builder_t), intent(in) :: lb
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: bnd(:, :), edge(:, :), ekind(:)
      real(wp), allocatable :: evalue(:, :)
      logical :: used(model%mesh%nnode)
      logical, allocatable :: all_elems(:)
      real(wp) :: tol
      integer :: g, before

      allocate (all_elems(model%mesh%nelem), source=.true.)
      call free_edges(model%mesh%nelem, model%mesh%conn, all_elems, bnd, err)
      if (allocated(err)) then
         call fail(rd, lb%csurf(1)%rec, 'CSURface: '//err%message, err)
         return
      end if
      used = used_nodes(model%mesh)
      tol = 1.0e-6_wp*mesh_size(model%mesh, used)
      allocate (edge(2, 0), ekind(0), evalue(2, 0))
      do g = 1, size(lb%csurf)
         before = size(ekind)
         if (lb%csurf(g)%physical > 0) then
            call physical_group(rd, lb%csurf(g), model, edge, ekind, evalue, err)
         else
            call line_group(rd, lb%csurf(g), model%mesh%x, bnd, tol, edge, ekind, evalue, err)
         end if
         if (allocated(err)) return
         if (size(ekind) == before) then
            call fail(rd, lb%csurf(g)%rec, 'CSURface: the group loads no boundary edge: expected '// &
                      'points along the boundary of the mesh', err)
            return
         end if
      end do
      model%loads%nedge = size(ekind)
      model%loads%edge = edge
      model%loads%edge_kind = ekind
      model%loads%edge_value = evalue
   end subroutine resolve_edges

   !> One PHYSical group: the edges of physical curve c with the uniform value.
   subroutine physical_group(rd, grp, model, edge, ekind, evalue, err)
      type(reader_t), intent(in) :: rd
      type(csurf_t), intent(in) :: grp
      type(model_t), intent(in) :: model
      integer, allocatable, intent(inout) :: edge(:, :), ekind(:)
      real(wp), allocatable, intent(inout) :: evalue(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer :: s, j
      s = find_edge_set(model%mesh%edge_sets, grp%physical)
      if (s == 0) then
         call fail(rd, grp%rec, 'CSURface PHYSical: physical curve '//itoa(grp%physical)//' is not '// &
                   'in the mesh: expected one of the physical curves of the GMSH meshes (here: '// &
                   edge_set_ids(model%mesh%edge_sets)//')', err)
         return
      end if
      associate (es => model%mesh%edge_sets(s))
         if (any(es%other(1:es%nedge) /= 0)) then
            call fail(rd, grp%rec, 'CSURface PHYSical: physical curve '//itoa(grp%physical)//' has '// &
                      'edges between two elements: expected a curve on the boundary', err)
            return
         end if
         do j = 1, es%nedge
            call push_edge(edge, ekind, evalue, es%edge(:, j), grp%kind, [grp%value, grp%value])
         end do
      end associate
   end subroutine physical_group

   !> One LINEar group: boundary edges on the polyline of its points.
   subroutine line_group(rd, grp, x, bnd, tol, edge, ekind, evalue, err)
      type(reader_t), intent(in) :: rd
      type(csurf_t), intent(in) :: grp
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: bnd(:, :)
      real(wp), intent(in) :: tol
      integer, allocatable, intent(inout) :: edge(:, :), ekind(:)
      real(wp), allocatable, intent(inout) :: evalue(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, e, ja, jb, jm, npt
      real(wp) :: d, dbest, ta, tb, tm, da, db, dm, va, vb, sgn, tdir(2)

      npt = size(grp%prec)
      do k = 1, npt
         dbest = huge(1.0_wp)
         do e = 1, size(bnd, 2)
            d = point_segment(grp%pts(1:2, k), x(:, bnd(1, e)), x(:, bnd(2, e)))
            dbest = min(dbest, d)
         end do
         if (dbest > tol) then
            call fail(rd, grp%prec(k), 'CSURface point '//itoa(k)//' ('//rtoa(grp%pts(1, k), SHORT_REAL)//', '// &
                      rtoa(grp%pts(2, k), SHORT_REAL)//') is not on a boundary: the nearest boundary edge is '// &
                      rtoa(dbest, SHORT_REAL)//' away: expected a point on the boundary of the mesh', err)
            return
         end if
      end do
      do e = 1, size(bnd, 2)
         call on_path(grp%pts, x(:, bnd(1, e)), ja, ta, da)
         call on_path(grp%pts, x(:, bnd(2, e)), jb, tb, db)
         call on_path(grp%pts, 0.5_wp*(x(:, bnd(1, e)) + x(:, bnd(2, e))), jm, tm, dm)
         if (da > tol .or. db > tol .or. dm > tol) cycle
         va = (1.0_wp - ta)*grp%pts(3, ja) + ta*grp%pts(3, ja + 1)
         vb = (1.0_wp - tb)*grp%pts(3, jb) + tb*grp%pts(3, jb + 1)
         sgn = 1.0_wp
         if (grp%kind == EDGE_TANGENTIAL) then
            ! positive from point 1 toward the last point along the path
            tdir = grp%pts(1:2, jm + 1) - grp%pts(1:2, jm)
            if (dot_product(x(:, bnd(2, e)) - x(:, bnd(1, e)), tdir) < 0.0_wp) sgn = -1.0_wp
         end if
         call push_edge(edge, ekind, evalue, bnd(:, e), grp%kind, sgn*[va, vb])
      end do
   end subroutine line_group

   !> Segment j of the polyline pts(1:2, :) nearest to p, the parameter t in [0, 1] of the
   !> nearest point on it and the distance d.
   pure subroutine on_path(pts, p, j, t, d)
      real(wp), intent(in) :: pts(:, :), p(2)
      integer, intent(out) :: j
      real(wp), intent(out) :: t, d
      integer :: k
      real(wp) :: tk, dk, s(2), l2
      d = huge(1.0_wp)
      j = 1
      t = 0.0_wp
      do k = 1, size(pts, 2) - 1
         s = pts(1:2, k + 1) - pts(1:2, k)
         l2 = dot_product(s, s)
         tk = 0.0_wp
         if (l2 > 0.0_wp) tk = min(1.0_wp, max(0.0_wp, dot_product(p - pts(1:2, k), s)/l2))
         dk = norm2(p - pts(1:2, k) - tk*s)
         if (dk < d) then
            d = dk
            j = k
            t = tk
         end if
      end do
   end subroutine on_path

   !> Distance from p to the segment a-b.
   pure real(wp) function point_segment(p, a, b) result(d)
      real(wp), intent(in) :: p(2), a(2), b(2)
      real(wp) :: s(2), l2, t
      s = b - a
      l2 = dot_product(s, s)
      t = 0.0_wp
      if (l2 > 0.0_wp) t = min(1.0_wp, max(0.0_wp, dot_product(p - a, s)/l2))
      d = norm2(p - a - t*s)
   end function point_segment

   !> Append one loaded edge.
   subroutine push_edge(edge, ekind, evalue, nodes, kind, val)
      integer, allocatable, intent(inout) :: edge(:, :), ekind(:)
      real(wp), allocatable, intent(inout) :: evalue(:, :)
      integer, intent(in) :: nodes(2), kind
      real(wp), intent(in) :: val(2)
      integer :: n
      n = size(ekind)
      edge = reshape([reshape(edge, [2*n]), nodes], [2, n + 1])
      evalue = reshape([reshape(evalue, [2*n]), val], [2, n + 1])
      ekind = [ekind, kind]
   end subroutine push_edge

   !> Every function a load names is defined by PROPortional.
   subroutine check_functions(rd, lb, spec, err)
      type(reader_t), intent(in) :: rd
      type(loads_builder_t), intent(in) :: lb
      type(load_spec_t), intent(inout) :: spec
      type(error_t), allocatable, intent(out) :: err
      integer :: k, nfn
      character(len=:), allocatable :: have
      if (.not. allocated(spec%fn)) allocate (spec%fn(0))
      if (.not. allocated(lb%refs)) return
      nfn = size(spec%fn)
      do k = 1, size(lb%refs)
         associate (r => lb%refs(k))
            if (r%id <= nfn) then
               if (spec%fn(r%id)%kind /= FN_UNDEFINED) cycle
            end if
            have = defined_list(spec)
            call fail(rd, r%rec, r%what//': proportional function '//itoa(r%id)//' is not defined: '// &
                      'expected a function of PROPortional,,n1,n2 (defined: '//have//')', err)
            return
         end associate
      end do
   end subroutine check_functions

   !> The defined function numbers as text ('none' when there are none).
   function defined_list(spec) result(s)
      type(load_spec_t), intent(in) :: spec
      character(len=:), allocatable :: s
      integer :: j
      s = ''
      do j = 1, size(spec%fn)
         if (spec%fn(j)%kind == FN_UNDEFINED) cycle
         if (len(s) > 0) s = s//', '
         s = s//itoa(j)
      end do
      if (len(s) == 0) s = 'none'
   end function defined_list

   !> The data of PROPortional,,n1,n2 after the BATCh END (command at `cmd`): functions n1..n2,
   !> each `1, k, tmin, tmax, a1, a2, a3, a4` or `2, nn` with records of t, p pairs (at most nn
   !> pairs per record, FEAP's layout; 0: any), or nothing (a unit ramp), each ended by a blank
   !> record.
   subroutine read_prop_data(rd, spec, n1, n2, cmd, err)
      type(reader_t), intent(inout) :: rd
      type(load_spec_t), intent(inout) :: spec
      integer, intent(in) :: n1, n2
      character(len=*), intent(in) :: cmd
      type(error_t), allocatable, intent(out) :: err
      integer :: j, i, typ

      ! the size is the number of functions (loading.f90)
      call grow(spec%fn, n2, exact=.true.)
      do j = n1, n2
         call next_record(rd, i)
         if (i == 0) then
            call fail(rd, i, 'expected the data of proportional function '//itoa(j)// &
                      ' (PROPortional at '//cmd//')', err)
            return
         end if
         if (spec%fn(j)%kind /= FN_UNDEFINED) then
            call fail(rd, i, 'proportional function '//itoa(j)//' is already defined at '// &
                      spec%fn(j)%where//': expected each function once', err)
            return
         end if
         spec%fn(j)%where = where(rd, i)
         if (rd%src%rec(i)%blank) then
            call end_set(rd, i)
            spec%fn(j)%kind = FN_RAMP
            cycle
         end if
         call check_data_record(rd, i, 'PROPortional', err)
         if (.not. allocated(err)) call int_field(rd, i, 1, 'PROPortional function record: type', typ, err)
         if (allocated(err)) return
         select case (typ)
         case (1)
            call read_type1(rd, i, j, spec%fn(j), err)
         case (2)
            call read_table(rd, i, j, spec%fn(j), err)
         case default
            call fail(rd, i, 'proportional function '//itoa(j)//': type '//itoa(typ)// &
                      ': expected 1 (a1 + a2 t + a3 sin^k(a4 t)) or 2 (a table of t, p)', err)
         end select
         if (allocated(err)) return
      end do
   end subroutine read_prop_data

   !> Type 1 `1, k, tmin, tmax, a1, a2, a3, a4`, then the blank record that ends it.
   subroutine read_type1(rd, i, j, f, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i, j
      type(prop_fn_t), intent(inout) :: f
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'PROPortional type 1 record 1, k, tmin, tmax, a1, a2, a3, a4'
      integer :: k, ib
      f%kind = FN_TYPE1
      call int_field(rd, i, 2, what, f%k, err)
      if (.not. allocated(err)) call real_field(rd, i, 3, what, f%tmin, err)
      if (.not. allocated(err)) call real_field(rd, i, 4, what, f%tmax, err)
      do k = 1, 4
         if (.not. allocated(err)) call real_field(rd, i, 4 + k, what, f%a(k), err)
      end do
      if (allocated(err)) return
      if (f%k < 0) then
         call fail(rd, i, what//': k = '//itoa(f%k)//': expected an exponent k >= 0', err)
      else if (.not. (f%tmax > f%tmin)) then
         call fail(rd, i, what//': tmin = '//rtoa(f%tmin, SHORT_REAL)//', tmax = '//rtoa(f%tmax, SHORT_REAL)// &
                   ': expected tmax > tmin', err)
      else if (has_field(rd, i, 9)) then
         call fail(rd, i, what//': the ninth field '//field(rd, i, 9)//' is not used', err)
      end if
      if (allocated(err)) return
      call next_record(rd, ib)
      if (ib == 0) return
      if (.not. rd%src%rec(ib)%blank) then
         call fail(rd, ib, 'proportional function '//itoa(j)//' (type 1, one record): expected a '// &
                   'blank record to end it', err)
         return
      end if
      call end_set(rd, ib)
   end subroutine read_type1

   !> Type 2 `2, nn`, then records of t, p pairs (non-decreasing t) up to a blank record.
   subroutine read_table(rd, i, j, f, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i, j
      type(prop_fn_t), intent(inout) :: f
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'PROPortional table record t1, p1, t2, p2, ...'
      integer :: nn, ir, nf, k, n
      real(wp) :: t, p
      real(wp), allocatable :: tab(:, :)
      f%kind = FN_TABLE
      call int_field(rd, i, 2, 'PROPortional type 2 record 2, nn', nn, err)
      if (allocated(err)) return
      if (nn < 0) then
         call fail(rd, i, 'PROPortional type 2 record 2, nn: nn = '//itoa(nn)//': expected the '// &
                   'number of pairs per record (>= 0; 0: any)', err)
         return
      end if
      allocate (tab(2, 0))
      do
         call next_in_set(rd, ir)
         if (ir == 0) exit
         call check_data_record(rd, ir, 'PROPortional table', err)
         if (allocated(err)) return
         nf = nfields(rd, ir)
         if (mod(nf, 2) /= 0) then
            call fail(rd, ir, what//': '//itoa(nf)//' values: expected pairs t, p', err)
            return
         end if
         if (nn > 0 .and. nf/2 > nn) then
            call fail(rd, ir, what//': '//itoa(nf/2)//' pairs: expected at most nn = '//itoa(nn)// &
                      ' pairs per record', err)
            return
         end if
         do k = 1, nf/2
            call real_field(rd, ir, 2*k - 1, what, t, err)
            if (.not. allocated(err)) call real_field(rd, ir, 2*k, what, p, err)
            if (allocated(err)) return
            n = size(tab, 2)
            if (n > 0) then
               if (t < tab(1, n)) then
                  call fail(rd, ir, what//': t = '//rtoa(t, SHORT_REAL)//' after t = '//rtoa(tab(1, n), SHORT_REAL)// &
                            ': expected the times in order (non-decreasing; a time given twice '// &
                            'is a jump)', err)
                  return
               end if
            end if
            tab = reshape([reshape(tab, [2*n]), t, p], [2, n + 1])
         end do
      end do
      if (size(tab, 2) == 0) then
         call fail(rd, i, 'proportional function '//itoa(j)//' (type 2): expected one or more '// &
                   'records of t, p pairs before the blank record', err)
         return
      end if
      f%tab = tab
   end subroutine read_table

   !> grow (exic_base_grow) for an array of fn_ref_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_fn_ref(a, n, exact)
      type(fn_ref_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(fn_ref_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_fn_ref

end module exic_input_deck_loads
