!> BLOCk (structured patches of 4-node quadrilaterals, FEAP's numbering) and SHIFt (the centre
!> of POLAr blocks) in the mesh phase of a deck.
!>
!> `SHIFt` is followed by one record `x0, y0` (FEAP); **[ext]** `SHIFt,x0,y0` on one record.
!> The origin applies to the POLAr blocks that follow. A block whose generated elements would
!> have two corners at one point (a POLAr edge at r = 0, or coincident CARTesian corners) is
!> an error that names the block edge.
module exic_input_deck_block
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_mesh_block, only: BLOCK_CARTESIAN, BLOCK_POLAR, block_coordinates, &
                              block_connectivity, collapsed_edge
   use exic_input_deck_records, only: keyword_is
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: next_in_set, reader_t, next_record, field, word, has_field, &
                             real_field, int_field, fail, where, unknown_keyword, itoa, &
                             looks_like_data, check_data_record
   use exic_input_deck_mesh, only: builder_t, ensure_node, ensure_elem, MAX_NUMBER
   use exic_base_memory, only: mesh_memory_message
   implicit none
   private

   public :: cmd_block, cmd_shift

   character(len=12), parameter :: block_types(2) = [character(len=12) :: 'CARTesian', 'POLAr']

contains

   !> SHIFt: the origin (x0, y0) of the POLAr blocks that follow, from the next record (FEAP)
   !> or **[ext]** from fields 2 and 3 of the SHIFt record itself.
   subroutine cmd_shift(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'SHIFt record x0, y0'
      integer :: i
      if (has_field(rd, icmd, 2)) then
         i = icmd
         call real_field(rd, i, 2, 'SHIFt,x0,y0', b%origin(1), err)
         if (.not. allocated(err)) call real_field(rd, i, 3, 'SHIFt,x0,y0', b%origin(2), err)
         return
      end if
      call next_record(rd, i)
      if (i == 0) then
         call fail(rd, i, 'SHIFt: expected the record x0, y0 after it', err)
         return
      end if
      if (rd%src%rec(i)%blank) then
         call fail(rd, i, 'SHIFt: expected the record x0, y0 (the centre of POLAr blocks) '// &
                   'right after it', err)
         return
      end if
      call check_data_record(rd, i, 'SHIFt', err)
      if (allocated(err)) return
      call real_field(rd, i, 1, what, b%origin(1), err)
      if (.not. allocated(err)) call real_field(rd, i, 2, what, b%origin(2), err)
   end subroutine cmd_shift

   !> BLOCk: header `CARTesian|POLAr, nr, ns, node1, elmt1, mat`, optional `QUADrilateral 4` and
   !> `MATErial m` records, master nodes `k, x, y`, blank.
   subroutine cmd_block(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'BLOCk header CARTesian|POLAr, nr, ns, node1, elmt1, mat'
      integer :: i, kind, nr, ns, node1, elmt1, mat, extra, k, e, n, j
      real(wp) :: master(2, 9)
      logical :: given(9)
      character(len=:), allocatable :: missing
      real(wp), allocatable :: xb(:, :)
      integer, allocatable :: cb(:, :)

      call next_record(rd, i)
      if (i == 0) then
         call fail(rd, i, 'BLOCk: expected the header record '//what(14:), err)
         return
      end if
      if (rd%src%rec(i)%blank .or. looks_like_data(rd, i)) then
         call fail(rd, i, 'BLOCk: expected the header record '//what(14:), err)
         return
      end if
      if (keyword_is(word(rd, i, 1), 'cart')) then
         kind = BLOCK_CARTESIAN
      else if (keyword_is(word(rd, i, 1), 'pola')) then
         kind = BLOCK_POLAR
      else if (keyword_is(word(rd, i, 1), 'cyli') .or. keyword_is(word(rd, i, 1), 'sphe')) then
         call fail(rd, i, 'BLOCk type '//field(rd, i, 1)//' is 3-D and not supported: expected '// &
                   'CARTesian or POLAr', err)
         return
      else
         call unknown_keyword(rd, i, 'BLOCk type', field(rd, i, 1), block_types, err)
         return
      end if
      call int_field(rd, i, 2, what, nr, err)
      if (.not. allocated(err)) call int_field(rd, i, 3, what, ns, err)
      if (.not. allocated(err)) call int_field(rd, i, 4, what, node1, err)
      if (.not. allocated(err)) call int_field(rd, i, 5, what, elmt1, err)
      if (.not. allocated(err)) call int_field(rd, i, 6, what, mat, err)
      if (allocated(err)) return
      do k = 7, 8
         call int_field(rd, i, k, what//', rskip, btype', extra, err)
         if (allocated(err)) return
         if (extra /= 0) then
            call fail(rd, i, 'BLOCk: rskip and btype other than 0 are not supported: expected 0', err)
            return
         end if
      end do
      if (nr < 1 .or. ns < 1) then
         call fail(rd, i, what//': expected nr >= 1 and ns >= 1', err)
         return
      end if
      if (node1 < 0 .or. mat < 0) then
         call fail(rd, i, what//': expected node1 >= 0 and mat >= 0', err)
         return
      end if
      if (real(node1, wp) + real(nr + 1, wp)*real(ns + 1, wp) > MAX_NUMBER .or. &
          real(elmt1, wp) + real(nr, wp)*real(ns, wp) > MAX_NUMBER) then
         call fail(rd, i, what//': expected node and element numbers up to '//itoa(MAX_NUMBER), err)
         return
      end if
      call master_nodes(rd, mat, master, given, err)
      if (allocated(err)) return
      if (.not. all(given(1:4))) then
         missing = ''
         do k = 1, 4
            if (.not. given(k)) missing = missing//' '//itoa(k)
         end do
         call fail(rd, icmd, 'BLOCk: missing corner master node(s)'//missing// &
                   ': expected corners 1, 2, 3 and 4', err)
         return
      end if
      if (mat == 0) mat = max(b%block_mat, 1)
      b%block_mat = mat
      if (node1 == 0) node1 = b%m%nnode + 1
      missing = mesh_memory_message(max(b%m%nnode, node1 + (nr + 1)*(ns + 1) - 1), &
                                    b%m%nelem + merge(nr*ns, 0, elmt1 >= 0))
      if (len(missing) > 0) then
         call fail(rd, i, 'BLOCk: '//missing, err)
         return
      end if
      allocate (xb(2, (nr + 1)*(ns + 1)))
      call block_coordinates(kind, nr, ns, master, given, b%origin, xb)
      call check_collapsed(err)
      if (allocated(err)) return
      call ensure_node(b, node1 + (nr + 1)*(ns + 1) - 1)
      do k = 1, size(xb, 2)
         n = node1 + k - 1
         if (b%m%defined(n) .and. b%nrec(n) /= icmd) then
            call fail(rd, icmd, 'BLOCk: node '//itoa(n)//' is already defined at '// &
                      where(rd, b%nrec(n))//': expected node1 beyond the nodes in use, or 0', err)
            return
         end if
         b%m%x(:, n) = xb(:, k)
         b%m%defined(n) = .true.
         b%nrec(n) = icmd
      end do
      if (elmt1 < 0) return
      if (elmt1 == 0) elmt1 = b%m%nelem + 1
      allocate (cb(4, nr*ns))
      call block_connectivity(nr, ns, node1, cb)
      call ensure_elem(b, elmt1 + nr*ns - 1)
      do j = 1, nr*ns
         e = elmt1 + j - 1
         if (b%edef(e)) then
            call fail(rd, icmd, 'BLOCk: element '//itoa(e)//' is already defined at '// &
                      where(rd, b%erec(e))//': expected elmt1 beyond the elements in use, or 0', err)
            return
         end if
         b%edef(e) = .true.
         b%erec(e) = icmd
         b%m%conn(:, e) = cb(:, j)
         b%m%mat(e) = mat
         b%m%region(e) = b%region
      end do
   contains
      !> Two corners of a generated element at one point: say which block edge collapsed
      !> (for POLAr, an edge at r = 0) rather than leave a degenerate element to the
      !> orientation check.
      subroutine check_collapsed(err)
         type(error_t), allocatable, intent(out) :: err
         integer :: ie, je, side, c1, corner(4)
         real(wp) :: h, tol, p(2)
         character(len=:), allocatable :: edge, hint
         h = max(maxval(xb(1, :)) - minval(xb(1, :)), maxval(xb(2, :)) - minval(xb(2, :)))
         tol = 1.0e-10_wp*max(h, tiny(1.0_wp))
         call collapsed_edge(nr, ns, xb, tol, ie, je, side)
         if (side == 0) return
         if (ie == 1 .and. side == 4) then
            edge = 'its edge 4-1 (master nodes 4 and 1, i = 0)'
         else if (ie == nr .and. side == 2) then
            edge = 'its edge 2-3 (master nodes 2 and 3, i = nr)'
         else if (je == 1 .and. side == 1) then
            edge = 'its edge 1-2 (master nodes 1 and 2, j = 0)'
         else if (je == ns .and. side == 3) then
            edge = 'its edge 3-4 (master nodes 3 and 4, j = ns)'
         else
            edge = 'the inside of the block (the map folds)'
         end if
         c1 = (je - 1)*(nr + 1) + ie
         corner = [c1, c1 + 1, c1 + nr + 2, c1 + nr + 1]
         p = xb(:, corner(side))
         if (kind == BLOCK_POLAR .and. norm2(p - b%origin) <= tol) then
            hint = ': a POLAr edge at r = 0 collapses to the centre ('//rtoa(b%origin(1), SHORT_REAL)//', '// &
                   rtoa(b%origin(2), SHORT_REAL)//') and its elements would have two corners at one point; '// &
                   'start the POLAr block at r > 0, or mesh a disk with GMSH (doc/gmsh.md) or '// &
                   'with a centre square BLOCk and a ring of CARTesian BLOCks joined by TIE '// &
                   '(as inputs/paper/common/ex75_disk.inc does)'
         else
            hint = ': expected four distinct corners and mid-side nodes that keep the map one-to-one'
         end if
         call fail(rd, icmd, 'BLOCk: element ('//itoa(ie)//', '//itoa(je)//') of the block has '// &
                   'two corners at one point near ('//rtoa(p(1), SHORT_REAL)//', '//rtoa(p(2), SHORT_REAL)//'), on '// &
                   edge//hint, err)
      end subroutine check_collapsed
   end subroutine cmd_block

   !> Master-node records of a BLOCk (and its QUADrilateral/MATErial sub-records).
   subroutine master_nodes(rd, mat, master, given, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(inout) :: mat
      real(wp), intent(out) :: master(2, 9)
      logical, intent(out) :: given(9)
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'BLOCk master node k, x, y'
      character(len=16), parameter :: subs(3) = [character(len=16) :: 'QUADrilateral', &
                                                  'MATErial', 'master node k']
      integer :: i, k, nq
      master = 0.0_wp
      given = .false.
      do
         call next_in_set(rd, i)
         if (i == 0) return
         if (.not. looks_like_data(rd, i) .and. any(given)) then
            call check_data_record(rd, i, 'BLOCk master node', err)
            if (allocated(err)) return
         end if
         if (.not. looks_like_data(rd, i)) then
            if (keyword_is(word(rd, i, 1), 'quad')) then
               call int_field(rd, i, 2, 'BLOCk QUADrilateral n', nq, err)
               if (allocated(err)) return
               if (nq /= 4 .and. nq /= 0) then
                  call fail(rd, i, 'BLOCk: QUADrilateral '//itoa(nq)//' is not supported: '// &
                            'expected 4', err)
                  return
               end if
            else if (keyword_is(word(rd, i, 1), 'mate')) then
               call int_field(rd, i, 2, 'BLOCk MATErial m', mat, err)
               if (allocated(err)) return
               if (mat < 1) then
                  call fail(rd, i, 'BLOCk MATErial m: expected m >= 1', err)
                  return
               end if
            else
               call unknown_keyword(rd, i, 'BLOCk record', field(rd, i, 1), subs, err)
               return
            end if
            cycle
         end if
         call int_field(rd, i, 1, what, k, err)
         if (allocated(err)) return
         if (k < 1 .or. k > 9) then
            call fail(rd, i, what//': k = '//itoa(k)//': expected k in 1..9', err)
            return
         end if
         if (given(k)) then
            call fail(rd, i, what//': master node '//itoa(k)//' given twice: expected it once', err)
            return
         end if
         call real_field(rd, i, 2, what, master(1, k), err)
         if (allocated(err)) return
         call real_field(rd, i, 3, what, master(2, k), err)
         if (allocated(err)) return
         given(k) = .true.
      end do
   end subroutine master_nodes

end module exic_input_deck_block
