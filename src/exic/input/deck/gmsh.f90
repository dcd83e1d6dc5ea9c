!> **[ext]** GMSH and PBOUndary: meshes made by Gmsh in a deck's mesh phase (doc/gmsh.md).
!>
!> `GMSH,file[,node1[,elmt1]]` reads `file` (relative to the deck file holding the record, like
!> INCLude) with the Gmsh library (exic_input_gmsh); a `.geo` file is meshed in 2-D first. Its
!> 4-node quadrilaterals become elements, its physical curves edge sets:
!>
!> - node numbers: Gmsh node tag t becomes node node1 - 1 + t (node1 = 0 or absent: one above
!>   the highest node number so far, so the first mesh command keeps Gmsh's own numbers); only
!>   nodes of quadrilaterals are defined;
!> - element numbers: the quadrilaterals in increasing Gmsh element tag order take elmt1,
!>   elmt1 + 1, ... (elmt1 = 0 or absent: the next free number), because Gmsh numbers points,
!>   lines and surfaces in one sequence;
!> - physical surface t gives region t and material set t (the deck's MATErial,t);
!> - corners are made counter-clockwise (a quadrilateral of negative area is reversed);
!> - physical curve c becomes edge set c of the mesh, every line oriented with its
!>   quadrilateral on the left; GMSH commands with the same physical curve tag add to one set.
!>
!> `PBOUndary[,SET|ADD]` + records `c, c1, c2` (or one record `PBOUndary,c,c1,c2`) sets the
!> boundary codes of every node of edge set c after the mesh END (ADD by default, as EBOUndary).
module exic_input_deck_gmsh
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t
   use exic_base_sort, only: search_sorted
   use exic_mesh_edge_set, only: orient_edges, add_edges
   use exic_input_deck_records, only: keyword_is, dirname
   use exic_base_strings, only: rtoa, SHORT_REAL, to_lower
   use exic_input_deck_reader, only: reader_t, next_in_set, field, word, has_field, int_field, fail, &
                             warn, where, itoa, check_data_record
   use exic_input_gmsh, only: gmsh_mesh_t, gmsh_read
   use exic_input_deck_mesh, only: builder_t, pbou_t, grow, ensure_node, ensure_elem, set_mode, MAX_NUMBER
   use exic_base_memory, only: mesh_memory_message
   implicit none
   private

   public :: cmd_gmsh, cmd_pbound

contains

   !> GMSH,file[,node1[,elmt1]] (record `icmd`).
   subroutine cmd_gmsh(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'GMSH,file[,node1[,elmt1]]'
      type(error_t), allocatable :: gerr
      type(gmsh_mesh_t) :: gm
      character(len=:), allocatable :: name, path, tag
      integer :: node1, elmt1, k
      logical :: exists

      name = field(rd, icmd, 2)
      if (len(name) == 0) then
         call fail(rd, icmd, what//': expected a file name (a .msh file, or a .geo file to mesh)', err)
         return
      end if
      call int_field(rd, icmd, 3, what, node1, err)
      if (.not. allocated(err)) call int_field(rd, icmd, 4, what, elmt1, err)
      if (allocated(err)) return
      if (node1 < 0 .or. elmt1 < 0) then
         call fail(rd, icmd, what//': expected node1 >= 0 and elmt1 >= 0 (0: the next free number)', &
                   err)
         return
      end if
      if (name(1:1) == '/') then
         path = name
      else
         path = dirname(rd%src%rec(icmd)%file)//name
      end if
      inquire (file=path, exist=exists)
      if (.not. exists) then
         call fail(rd, icmd, 'GMSH: cannot find file "'//path//'": expected an existing .msh '// &
                   'or .geo file (the path is relative to the deck)', err)
         return
      end if
      call gmsh_read(path, is_geo(name), gm, gerr)
      call pass_warnings(gm%warnings)
      if (allocated(gerr)) then
         call fail(rd, icmd, 'GMSH '//name//': '//gerr%message, err)
         return
      end if
      if (gm%npoint_groups > 0) call warn(rd, icmd, 'GMSH '//name//': '//itoa(gm%npoint_groups)// &
                                          ' physical point group(s) are not used by exic')
      tag = 'GMSH '//name
      call add_gmsh_mesh(rd, b, icmd, tag, gm, node1, elmt1, err)
      if (allocated(err)) return
      do k = 1, size(gm%curves)
         call add_curve(rd, b, icmd, tag, gm, k, node1, elmt1, err)
         if (allocated(err)) return
      end do
   contains
      subroutine pass_warnings(text)
         character(len=*), intent(in) :: text
         integer :: p, q
         p = 1
         do while (p <= len(text))
            q = index(text(p:), new_line('a'))
            if (q == 0) then
               q = len(text) + 1
            else
               q = p + q - 1
            end if
            if (q > p) call warn(rd, icmd, 'GMSH '//name//': '//text(p:q - 1))
            p = q + 1
         end do
      end subroutine pass_warnings
   end subroutine cmd_gmsh

   !> True for a file name ending in .geo (any case).
   pure logical function is_geo(name)
      character(len=*), intent(in) :: name
      integer :: n
      n = len_trim(name)
      is_geo = .false.
      if (n >= 4) is_geo = to_lower(name(n - 3:n)) == '.geo'
   end function is_geo

   !> The nodes and quadrilaterals of a Gmsh mesh into the builder. On return node1 and elmt1
   !> are the numbers actually used.
   subroutine add_gmsh_mesh(rd, b, icmd, tag, gm, node1, elmt1, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      character(len=*), intent(in) :: tag
      type(gmsh_mesh_t), intent(in) :: gm
      integer, intent(inout) :: node1, elmt1
      type(error_t), allocatable, intent(out) :: err
      logical, allocatable :: used(:)
      integer :: q, k, j, n, e, c(4)
      integer(i8) :: maxtag
      real(wp) :: h, tol, area, xq(2, 4)
      character(len=:), allocatable :: msg

      allocate (used(gm%nnode))
      used = .false.
      do q = 1, gm%nquad
         do k = 1, 4
            j = search_sorted(gm%node_tag, gm%quad(k, q))
            if (j <= 0) then
               call fail(rd, icmd, tag//': quadrilateral '//itoa8(gm%quad_tag(q))//' uses node '// &
                         itoa8(gm%quad(k, q))//', which the file does not define', err)
               return
            end if
            used(j) = .true.
         end do
      end do
      h = max(maxval(gm%x(1, :), used) - minval(gm%x(1, :), used), &
              maxval(gm%x(2, :), used) - minval(gm%x(2, :), used))
      tol = 1.0e-9_wp*max(h, tiny(1.0_wp))
      do j = 1, gm%nnode
         if (used(j) .and. abs(gm%x(3, j)) > tol) then
            call fail(rd, icmd, tag//': node '//itoa8(gm%node_tag(j))//' has z = '// &
                      rtoa(gm%x(3, j), SHORT_REAL)//': expected a plane mesh in z = 0', err)
            return
         end if
      end do
      if (node1 == 0) node1 = b%m%nnode + 1
      maxtag = maxval(gm%node_tag, used)
      if (real(node1, wp) - 1.0_wp + real(maxtag, wp) > MAX_NUMBER .or. &
          real(elmt1, wp) + real(gm%nquad, wp) > MAX_NUMBER) then
         call fail(rd, icmd, tag//': node tags up to '//itoa8(maxtag)//' and '//itoa(gm%nquad)// &
                   ' quadrilaterals: expected node and element numbers up to '//itoa(MAX_NUMBER), err)
         return
      end if
      msg = mesh_memory_message(max(b%m%nnode, node1 - 1 + int(maxtag)), &
                                merge(b%m%nelem + gm%nquad, max(b%m%nelem, elmt1 + gm%nquad - 1), &
                                      elmt1 == 0))
      if (len(msg) > 0) then
         call fail(rd, icmd, tag//': '//msg, err)
         return
      end if
      call ensure_node(b, node1 - 1 + int(maxtag))
      do j = 1, gm%nnode
         if (.not. used(j)) cycle
         n = node1 - 1 + int(gm%node_tag(j))
         if (b%m%defined(n) .and. b%nrec(n) /= icmd) then
            call fail(rd, icmd, tag//': node '//itoa(n)//' (Gmsh node '//itoa8(gm%node_tag(j))// &
                      ') is already defined at '//where(rd, b%nrec(n))//': expected node1 '// &
                      'beyond the nodes in use, or 0', err)
            return
         end if
         b%m%x(:, n) = gm%x(1:2, j)
         b%m%defined(n) = .true.
         b%nrec(n) = icmd
      end do
      if (elmt1 == 0) elmt1 = b%m%nelem + 1
      call ensure_elem(b, elmt1 + gm%nquad - 1)
      do q = 1, gm%nquad
         e = elmt1 + q - 1
         if (b%edef(e)) then
            call fail(rd, icmd, tag//': element '//itoa(e)//' is already defined at '// &
                      where(rd, b%erec(e))//': expected elmt1 beyond the elements in use, or 0', err)
            return
         end if
         c = node1 - 1 + int(gm%quad(:, q))
         xq = b%m%x(:, c)
         area = 0.5_wp*((xq(1, 3) - xq(1, 1))*(xq(2, 4) - xq(2, 2)) - &
                        (xq(2, 3) - xq(2, 1))*(xq(1, 4) - xq(1, 2)))
         if (area < 0.0_wp) c = [c(1), c(4), c(3), c(2)]
         b%edef(e) = .true.
         b%erec(e) = icmd
         b%m%conn(:, e) = c
         b%m%mat(e) = gm%quad_phys(q)
         b%m%region(e) = gm%quad_phys(q)
      end do
   end subroutine add_gmsh_mesh

   !> Physical curve k of a Gmsh mesh into an edge set, oriented against the mesh's elements
   !> elmt1 ... elmt1 + nquad - 1.
   subroutine add_curve(rd, b, icmd, tag, gm, k, node1, elmt1, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd, k, node1, elmt1
      character(len=*), intent(in) :: tag
      type(gmsh_mesh_t), intent(in) :: gm
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: line(:, :), edge(:, :), elem(:), other(:)
      integer :: n, bad, j
      associate (cv => gm%curves(k))
         n = cv%nline
         allocate (line(2, n), edge(2, n), elem(n), other(n))
         do j = 1, n
            if (search_sorted(gm%node_tag, cv%line(1, j)) <= 0 .or. &
                search_sorted(gm%node_tag, cv%line(2, j)) <= 0) then
               call fail(rd, icmd, tag//': Physical Curve '//itoa(cv%tag)//' uses a node the '// &
                         'file does not define', err)
               return
            end if
         end do
         line = node1 - 1 + int(cv%line)
         call orient_edges(gm%nquad, b%m%conn(:, elmt1:elmt1 + gm%nquad - 1), elmt1 - 1, n, &
                           line, edge, elem, other, bad)
         if (bad /= 0) then
            call fail(rd, icmd, tag//': Physical Curve '//itoa(cv%tag)//': its mesh line from '// &
                      'Gmsh node '//itoa8(cv%line(1, bad))//' to '//itoa8(cv%line(2, bad))// &
                      ' is not an edge of a quadrilateral of the physical surfaces: expected '// &
                      'curves on the edges of the meshed surfaces', err)
            return
         end if
         call add_edges(b%m%edge_sets, cv%tag, cv%name, where(rd, icmd), edge, elem, other)
      end associate
   end subroutine add_curve

   !> A 64-bit integer as text.
   pure function itoa8(i) result(s)
      integer(i8), intent(in) :: i
      character(len=:), allocatable :: s
      character(len=24) :: buf
      write (buf, '(i0)') i
      s = trim(buf)
   end function itoa8

   !> PBOUndary[,SET|ADD] + records `c, c1, c2`, or one record PBOUndary,c,c1,c2; kept for
   !> after END (an unknown physical curve is reported there).
   subroutine cmd_pbound(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'PBOUndary record c, c1, c2'
      logical :: set
      integer :: i
      if (has_field(rd, icmd, 2) .and. .not. (keyword_is(word(rd, icmd, 2), 'set') .or. &
                                              keyword_is(word(rd, icmd, 2), 'add'))) then
         call item(icmd, 2, .false., err)
         return
      end if
      call set_mode(rd, icmd, .false., set, err)
      if (allocated(err)) return
      do
         call next_in_set(rd, i)
         if (i == 0) return
         call check_data_record(rd, i, 'PBOUndary', err)
         if (allocated(err)) return
         call item(i, 1, set, err)
         if (allocated(err)) return
      end do
   contains
      subroutine item(ir, k0, set, err)
         integer, intent(in) :: ir, k0
         logical, intent(in) :: set
         type(error_t), allocatable, intent(out) :: err
         type(pbou_t) :: p
         call int_field(rd, ir, k0, what, p%id, err)
         if (.not. allocated(err)) call int_field(rd, ir, k0 + 1, what, p%code(1), err)
         if (.not. allocated(err)) call int_field(rd, ir, k0 + 2, what, p%code(2), err)
         if (allocated(err)) return
         p%set = set
         p%rec = ir
         call grow(b%pbou, b%npbou + 1)
         b%npbou = b%npbou + 1
         b%pbou(b%npbou) = p
      end subroutine item
   end subroutine cmd_pbound

end module exic_input_deck_gmsh
