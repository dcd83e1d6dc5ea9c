!> Mesh-phase commands of a deck (input language, section 3) into a growable mesh builder.
!>
!> Nodes and elements are numbered by the deck; the builder grows to the highest number seen.
!> Edge (EBOUndary), physical-curve (PBOUndary) and coordinate (CBOUndary) boundary sets and the
!> region/material forms of INITial,VELOcity are kept and applied after the mesh END (see
!> exic_input_deck_finish). BLOCk and SHIFt are in exic_input_deck_block, GMSH and PBOUndary in
!> exic_input_deck_gmsh.
module exic_input_deck_mesh
   use exic_base_kinds, only: wp
   use exic_base_grow, only: grow, grow_size
   use exic_base_error, only: error_t
   use exic_base_memory, only: mesh_memory_message, MEMORY_CHECK_FROM
   use exic_mesh_mesh, only: mesh_t
   use exic_material_material, only: material_t
   use exic_input_deck_records, only: keyword_is
   use exic_input_deck_reader, only: next_in_set, reader_t, next_record, next_nonblank, back_one, nfields, &
                             field, word, has_field, real_field, int_field, fail, warn, where, &
                             unknown_keyword, itoa, looks_like_data, check_data_record
   implicit none
   private

   public :: builder_t, ebou_t, cbou_t, pbou_t, init_t, genvec_t
   !> grow (exic_base_grow) with the specifics of the builder's record lists
   public :: grow
   public :: builder_init, ensure_node, ensure_elem, gen_step, node_record
   public :: cmd_coordinates, cmd_elements, cmd_region, cmd_boundary, cmd_ebound, &
             cmd_cbound, cmd_nodal_values, cmd_global, cmd_initial, set_mode

   integer, parameter, public :: CB_NODE = 1, CB_LINE = 2
   !> Largest node or element number accepted (guards against a typo allocating huge arrays).
   integer, parameter, public :: MAX_NUMBER = 100000000
   integer, parameter, public :: INIT_NODE = 1, INIT_REGION = 2, INIT_MATERIAL = 3

   !> One EBOUndary record, applied after END.
   type :: ebou_t
      integer :: dir = 1
      real(wp) :: x = 0.0_wp
      integer :: code(2) = 0
      logical :: set = .false.            !< EBOU,SET replaces; default ADD
      integer :: rec = 0
   end type ebou_t

   !> One PBOUndary record `tag, c1, c2`: codes on every node of an edge set (physical curve),
   !> applied after the EBOUndary sets.
   type :: pbou_t
      integer :: id = 0
      integer :: code(2) = 0
      logical :: set = .false.            !< PBOU,SET replaces; default ADD (as EBOUndary)
      integer :: rec = 0
   end type pbou_t

   !> One CBOUndary NODE or LINE item, applied after the EBOUndary and PBOUndary sets.
   type :: cbou_t
      integer :: kind = CB_NODE
      real(wp) :: p(2, 2) = 0.0_wp        !< the point, or the two ends of the segment
      integer :: code(2) = 0
      logical :: set = .true.             !< CBOU default SET; CBOU,ADD combines
      real(wp) :: gap = -1.0_wp           !< GAP,value: distance tolerance (< 0: default)
      integer :: rec = 0
   end type cbou_t

   !> One initial-velocity item of the mesh phase, applied after END in input order.
   type :: init_t
      integer :: kind = INIT_NODE
      integer :: id = 0                   !< node, region or material
      real(wp) :: v(2) = 0.0_wp
      integer :: rec = 0
   end type init_t

   !> FEAP node-vector generation state (previous record's node, increment and values).
   type :: genvec_t
      integer :: l = 0, lg = 0
      real(wp) :: vl(2) = 0.0_wp
   end type genvec_t

   !> The mesh as it grows during the mesh phase.
   type :: builder_t
      type(mesh_t) :: m                         !< arrays sized to capacity; nnode/nelem = highest
      logical, allocatable :: edef(:)           !< element was defined
      integer, allocatable :: erec(:)           !< record that defined each element
      integer, allocatable :: nrec(:)           !< record that last defined each node
      integer, allocatable :: vrec(:)           !< last BOUNdary/FORCe/DISPlacement record naming
                                                !< each node (0: none), checked at END
      integer :: region = 0                     !< REGIon of the elements that follow
      integer :: block_mat = 0                  !< material of the previous BLOCk (0: none yet)
      integer :: axis_rec = 0                   !< GLOBal AXISymmetric record (0: plane strain)
      real(wp) :: origin(2) = 0.0_wp            !< SHIFt: centre of POLAr blocks
      integer :: nmat = 0
      type(material_t), allocatable :: mats(:)  !< growable, indexed by set number
      integer, allocatable :: mat_rec(:)        !< record of each MATErial command (0: none)
      integer :: nebou = 0, ncbou = 0, ninit = 0, npbou = 0
      type(ebou_t), allocatable :: ebou(:)
      type(pbou_t), allocatable :: pbou(:)
      type(cbou_t), allocatable :: cbou(:)
      type(init_t), allocatable :: init(:)
   end type builder_t

   character(len=12), parameter :: cbou_words(3) = [character(len=12) :: 'NODE', 'LINEar', 'GAP']

   interface grow
      module procedure grow_ebou, grow_pbou, grow_cbou, grow_init
   end interface grow

contains

   !> An empty builder.
   subroutine builder_init(b)
      type(builder_t), intent(out) :: b
      integer, parameter :: cap = 64
      allocate (b%m%x(2, cap), b%m%defined(cap), b%m%bc(2, cap), b%m%force(2, cap), &
                b%m%disp(2, cap), b%m%v0(2, cap), b%nrec(cap), b%vrec(cap))
      b%m%x = 0.0_wp
      b%m%defined = .false.
      b%m%bc = 0
      b%m%force = 0.0_wp
      b%m%disp = 0.0_wp
      b%m%v0 = 0.0_wp
      b%nrec = 0
      b%vrec = 0
      allocate (b%m%conn(4, cap), b%m%mat(cap), b%m%region(cap), b%edef(cap), b%erec(cap))
      b%m%conn = 0
      b%m%mat = 0
      b%m%region = 0
      b%edef = .false.
      b%erec = 0
      allocate (b%mats(8), b%mat_rec(8), b%ebou(8), b%cbou(8), b%init(8), b%pbou(8))
      b%mat_rec = 0
   end subroutine builder_init

   !> Make room for node n (and count it).
   subroutine ensure_node(b, n)
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: n
      integer :: cap, old
      old = size(b%m%defined)
      if (n > old) then
         cap = max(2*old, n)
         call grow(b%m%x, cap, 2)
         call grow(b%m%force, cap, 2)
         call grow(b%m%disp, cap, 2)
         call grow(b%m%v0, cap, 2)
         call grow(b%m%bc, cap, 2)
         call grow(b%m%defined, cap)
         call grow(b%nrec, cap)
         call grow(b%vrec, cap)
      end if
      b%m%nnode = max(b%m%nnode, n)
   end subroutine ensure_node

   !> Make room for element e (and count it).
   subroutine ensure_elem(b, e)
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: e
      integer :: cap, old
      old = size(b%edef)
      if (e > old) then
         cap = max(2*old, e)
         call grow(b%m%conn, cap, 4)
         call grow(b%m%mat, cap)
         call grow(b%m%region, cap)
         call grow(b%erec, cap)
         call grow(b%edef, cap)
      end if
      b%m%nelem = max(b%m%nelem, e)
   end subroutine ensure_elem

   !> FEAP node-vector generation (genvec): append to (nodes, vals) the nodes strictly between the
   !> previous record's node and n (when the previous record had ng /= 0), interpolated linearly,
   !> then n itself. With `codes`, generated nodes get -1 where the previous code was negative and
   !> 0 elsewhere (FEAP's BOUNdary rule).
   subroutine gen_step(g, n, ng, v, codes, nodes, vals, cnt)
      type(genvec_t), intent(inout) :: g
      integer, intent(in) :: n, ng
      real(wp), intent(in) :: v(2)
      logical, intent(in) :: codes
      integer, allocatable, intent(inout) :: nodes(:)
      real(wp), allocatable, intent(inout) :: vals(:, :)
      integer, intent(inout) :: cnt
      integer :: lg, li, l
      real(wp) :: dv(2), cur(2)
      if (g%lg /= 0 .and. g%l > 0) then
         lg = sign(g%lg, n - g%l)
         li = (abs(n - g%l + lg) - 1)/abs(lg)
         dv = (v - g%vl)/real(li, wp)
         l = g%l
         cur = g%vl
         do
            l = l + lg
            if ((n - l)*lg <= 0) exit
            if (codes) then
               cur = merge(-1.0_wp, 0.0_wp, g%vl < 0.0_wp)
            else
               cur = cur + dv
            end if
            call push(l, cur)
         end do
      end if
      call push(n, v)
      g%l = n
      g%lg = ng
      g%vl = v
   contains
      subroutine push(node, val)
         integer, intent(in) :: node
         real(wp), intent(in) :: val(2)
         call grow(nodes, max(cnt + 1, 64))
         call grow(vals, max(cnt + 1, 64), 2)
         cnt = cnt + 1
         nodes(cnt) = node
         vals(:, cnt) = val
      end subroutine push
   end subroutine gen_step

   !> Read one node-vector record `n, ng, v1, v2` (fields from `k0`) and generate.
   !> `nmax` > 0 bounds the node numbers. Integer values with `codes`.
   subroutine node_record(rd, i, k0, what, nmax, codes, g, nodes, vals, cnt, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k0, nmax
      character(len=*), intent(in) :: what
      logical, intent(in) :: codes
      type(genvec_t), intent(inout) :: g
      integer, allocatable, intent(inout) :: nodes(:)
      real(wp), allocatable, intent(inout) :: vals(:, :)
      integer, intent(inout) :: cnt
      type(error_t), allocatable, intent(out) :: err
      integer :: n, ng, k, c
      real(wp) :: v(2)
      call int_field(rd, i, k0, what, n, err)
      if (allocated(err)) return
      call int_field(rd, i, k0 + 1, what, ng, err)
      if (allocated(err)) return
      do k = 1, 2
         if (codes) then
            call int_field(rd, i, k0 + 1 + k, what, c, err)
            v(k) = real(c, wp)
         else
            call real_field(rd, i, k0 + 1 + k, what, v(k), err)
         end if
         if (allocated(err)) return
      end do
      if (n < 1 .or. n > MAX_NUMBER .or. (nmax > 0 .and. n > nmax)) then
         if (nmax > 0) then
            call fail(rd, i, what//': node '//itoa(n)//': expected a node number in 1..'// &
                      itoa(nmax), err)
         else
            call fail(rd, i, what//': node '//itoa(n)//': expected a node number in 1..'// &
                      itoa(MAX_NUMBER), err)
         end if
         return
      end if
      if (n == g%l) then
         call fail(rd, i, what//': node '//itoa(n)//' repeats the previous record: expected '// &
                   'a different node', err)
         return
      end if
      if (n > MEMORY_CHECK_FROM) call memory_check(rd, i, what, n, 0, err)
      if (allocated(err)) return
      call gen_step(g, n, ng, v, codes, nodes, vals, cnt)
   end subroutine node_record

   !> Error naming record `i` when a mesh with node numbers up to `nn` and `ne` elements would
   !> not fit in memory (exic_base_memory).
   subroutine memory_check(rd, i, what, nn, ne, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, nn, ne
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: msg
      msg = mesh_memory_message(nn, ne)
      if (len(msg) > 0) call fail(rd, i, what//': '//msg, err)
   end subroutine memory_check

   !> Read a node-vector data set (ended by a blank record) into (nodes, vals).
   subroutine node_set(rd, what, codes, nodes, vals, cnt, err, recs)
      type(reader_t), intent(inout) :: rd
      character(len=*), intent(in) :: what
      logical, intent(in) :: codes
      integer, allocatable, intent(out) :: nodes(:)
      real(wp), allocatable, intent(out) :: vals(:, :)
      integer, intent(out) :: cnt
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable, intent(out), optional :: recs(:)
      type(genvec_t) :: g
      integer :: i, old
      cnt = 0
      if (present(recs)) allocate (recs(64))
      do
         call next_in_set(rd, i)
         if (i == 0) return
         old = cnt
         call check_data_record(rd, i, what(1:index(what, ' ') - 1), err)
         if (allocated(err)) return
         call node_record(rd, i, 1, what, 0, codes, g, nodes, vals, cnt, err)
         if (allocated(err)) return
         if (present(recs)) then
            call grow(recs, cnt)
            recs(old + 1:cnt) = i
         end if
      end do
   end subroutine node_set

   !> COORdinates: `n, ng, x, y` records with FEAP generation.
   subroutine cmd_coordinates(rd, b, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: cnt, k
      integer, allocatable :: recs(:)
      call node_set(rd, 'COORdinates record n, ng, x, y', .false., nodes, vals, cnt, err, recs)
      if (allocated(err)) return
      do k = 1, cnt
         call ensure_node(b, nodes(k))
         b%m%x(:, nodes(k)) = vals(:, k)
         b%m%defined(nodes(k)) = .true.
         b%nrec(nodes(k)) = recs(k)
      end do
   end subroutine cmd_coordinates

   !> BOUNdary: `n, ng, c1, c2` (non-zero = prescribed), FEAP code generation; replaces codes.
   subroutine cmd_boundary(rd, b, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: cnt, k
      integer, allocatable :: recs(:)
      call node_set(rd, 'BOUNdary record n, ng, c1, c2', .true., nodes, vals, cnt, err, recs)
      if (allocated(err)) return
      do k = 1, cnt
         call ensure_node(b, nodes(k))
         b%vrec(nodes(k)) = recs(k)
         b%m%bc(:, nodes(k)) = merge(1, 0, vals(:, k) /= 0.0_wp)
      end do
   end subroutine cmd_boundary

   !> FORCe (`is_force`) or DISPlacement: `n, ng, v1, v2`, linear interpolation; replaces values.
   subroutine cmd_nodal_values(rd, b, is_force, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      logical, intent(in) :: is_force
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: cnt, k
      integer, allocatable :: recs(:)
      if (is_force) then
         call node_set(rd, 'FORCe record n, ng, f1, f2', .false., nodes, vals, cnt, err, recs)
      else
         call node_set(rd, 'DISPlacement record n, ng, d1, d2', .false., nodes, vals, cnt, err, recs)
      end if
      if (allocated(err)) return
      do k = 1, cnt
         call ensure_node(b, nodes(k))
         b%vrec(nodes(k)) = recs(k)
         if (is_force) then
            b%m%force(:, nodes(k)) = vals(:, k)
         else
            b%m%disp(:, nodes(k)) = vals(:, k)
         end if
      end do
   end subroutine cmd_nodal_values

   !> ELEMents: `n, ng, ma, n1, n2, n3, n4`; a gap after element m is filled by copies of m with
   !> every non-zero node increased by m's ng (0 means 1), FEAP's rule.
   subroutine cmd_elements(rd, b, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'ELEMents record n, ng, ma, n1, n2, n3, n4'
      integer :: i, n, ng, ma, nd(4), k, m, mg, mnd(4), mma, e
      m = 0
      mg = 0
      mnd = 0
      mma = 0
      do
         call next_in_set(rd, i)
         if (i == 0) return
         call check_data_record(rd, i, 'ELEMents', err)
         if (allocated(err)) return
         call int_field(rd, i, 1, what, n, err)
         if (allocated(err)) return
         call int_field(rd, i, 2, what, ng, err)
         if (allocated(err)) return
         call int_field(rd, i, 3, what, ma, err)
         if (allocated(err)) return
         do k = 1, 4
            call int_field(rd, i, 3 + k, what, nd(k), err)
            if (allocated(err)) return
         end do
         if (n > MAX_NUMBER) then
            call fail(rd, i, what//': element '//itoa(n)//': expected an element number up to '// &
                      itoa(MAX_NUMBER), err)
            return
         end if
         if (n > MEMORY_CHECK_FROM) call memory_check(rd, i, what, maxval(nd), n, err)
         if (allocated(err)) return
         if (n < 1 .or. n <= m) then
            call fail(rd, i, what//': element '//itoa(n)//': expected an element number above '// &
                      itoa(m)//' (elements in increasing order)', err)
            return
         end if
         if (ma < 1) then
            call fail(rd, i, what//': material '//itoa(ma)//': expected a material set >= 1', err)
            return
         end if
         if (any(nd < 1)) then
            call fail(rd, i, what//': element '//itoa(n)//': expected 4 node numbers >= 1', err)
            return
         end if
         if (m > 0) then
            do e = m + 1, n - 1
               where (mnd /= 0) mnd = mnd + max(mg, 1)
               call define_elem(e, mnd, mma)
               if (allocated(err)) return
            end do
         end if
         call define_elem(n, nd, ma)
         if (allocated(err)) return
         m = n
         mg = ng
         mnd = nd
         mma = ma
      end do
   contains
      subroutine define_elem(el, nodes, mat)
         integer, intent(in) :: el, nodes(4), mat
         call ensure_elem(b, el)
         if (b%edef(el)) then
            call fail(rd, i, 'ELEMents: element '//itoa(el)//' is already defined at '// &
                      where(rd, b%erec(el))//': expected each element once', err)
            return
         end if
         b%edef(el) = .true.
         b%erec(el) = i
         b%m%conn(:, el) = nodes
         b%m%mat(el) = mat
         b%m%region(el) = b%region
      end subroutine define_elem
   end subroutine cmd_elements

   !> REGIon,r: region of the elements that follow.
   subroutine cmd_region(rd, b, i, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: i
      type(error_t), allocatable, intent(out) :: err
      integer :: r
      call int_field(rd, i, 2, 'REGIon,r', r, err)
      if (allocated(err)) return
      if (r < 0) then
         call fail(rd, i, 'REGIon,r: expected a region number >= 0', err)
         return
      end if
      b%region = r
   end subroutine cmd_region

   !> EBOUndary[,SET|ADD]: `i, x_i, c1, c2`, kept for after END.
   subroutine cmd_ebound(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'EBOUndary record i, x_i, c1, c2'
      type(ebou_t) :: eb
      integer :: i
      call set_mode(rd, icmd, .false., eb%set, err)
      if (allocated(err)) return
      do
         call next_in_set(rd, i)
         if (i == 0) return
         call check_data_record(rd, i, 'EBOUndary', err)
         if (allocated(err)) return
         call int_field(rd, i, 1, what, eb%dir, err)
         if (.not. allocated(err)) call real_field(rd, i, 2, what, eb%x, err)
         if (.not. allocated(err)) call int_field(rd, i, 3, what, eb%code(1), err)
         if (.not. allocated(err)) call int_field(rd, i, 4, what, eb%code(2), err)
         if (allocated(err)) return
         if (eb%dir /= 1 .and. eb%dir /= 2) then
            call fail(rd, i, what//': i = '//itoa(eb%dir)//': expected 1 or 2', err)
            return
         end if
         eb%rec = i
         call grow(b%ebou, b%nebou + 1)
         b%nebou = b%nebou + 1
         b%ebou(b%nebou) = eb
      end do
   end subroutine cmd_ebound

   !> Option SET or ADD of EBOUndary/CBOUndary (field 2 of the command record).
   subroutine set_mode(rd, icmd, default, set, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: icmd
      logical, intent(in) :: default
      logical, intent(out) :: set
      type(error_t), allocatable, intent(out) :: err
      character(len=8), parameter :: modes(2) = [character(len=8) :: 'SET', 'ADD']
      set = default
      if (.not. has_field(rd, icmd, 2)) return
      if (keyword_is(word(rd, icmd, 2), 'set')) then
         set = .true.
      else if (keyword_is(word(rd, icmd, 2), 'add')) then
         set = .false.
      else
         call unknown_keyword(rd, icmd, 'boundary mode', field(rd, icmd, 2), modes, err)
      end if
   end subroutine set_mode

   !> CBOUndary[,SET|ADD]: `NODE, x, y, c1, c2` | `LINEar, c1, c2` + records `1, x1, y1` and
   !> `2, x2, y2` | `GAP, value`; kept for after END.
   subroutine cmd_cbound(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      type(cbou_t) :: cb
      integer :: i, k
      logical :: set
      real(wp) :: gap
      call set_mode(rd, icmd, .true., set, err)
      if (allocated(err)) return
      gap = -1.0_wp
      do
         call next_in_set(rd, i)
         if (i == 0) return
         cb = cbou_t(set=set, gap=gap, rec=i)
         if (keyword_is(word(rd, i, 1), 'node')) then
            cb%kind = CB_NODE
            call read_reals(i, 2, 'CBOUndary record NODE, x, y, c1, c2', cb%p(:, 1), err)
            if (.not. allocated(err)) call read_codes(i, 4, 'CBOUndary record NODE, x, y, c1, c2', err)
            if (allocated(err)) return
         else if (keyword_is(word(rd, i, 1), 'line')) then
            cb%kind = CB_LINE
            call read_codes(i, 2, 'CBOUndary record LINEar, c1, c2', err)
            if (allocated(err)) return
            do k = 1, 2
               call point_record(k, err)
               if (allocated(err)) return
            end do
         else if (keyword_is(word(rd, i, 1), 'gap')) then
            call real_field(rd, i, 2, 'CBOUndary record GAP, value', gap, err)
            if (allocated(err)) return
            if (gap < 0.0_wp) then
               call fail(rd, i, 'CBOUndary GAP: expected a value >= 0', err)
               return
            end if
            cycle
         else
            call check_data_record(rd, i, 'CBOUndary', err)
            if (.not. allocated(err)) call unknown_keyword(rd, i, 'CBOUndary record', &
                                                          field(rd, i, 1), cbou_words, err)
            return
         end if
         call grow(b%cbou, b%ncbou + 1)
         b%ncbou = b%ncbou + 1
         b%cbou(b%ncbou) = cb
      end do
   contains
      subroutine read_reals(ir, k0, what, v, err)
         integer, intent(in) :: ir, k0
         character(len=*), intent(in) :: what
         real(wp), intent(out) :: v(2)
         type(error_t), allocatable, intent(out) :: err
         call real_field(rd, ir, k0, what, v(1), err)
         if (.not. allocated(err)) call real_field(rd, ir, k0 + 1, what, v(2), err)
      end subroutine read_reals
      subroutine read_codes(ir, k0, what, err)
         integer, intent(in) :: ir, k0
         character(len=*), intent(in) :: what
         type(error_t), allocatable, intent(out) :: err
         call int_field(rd, ir, k0, what, cb%code(1), err)
         if (.not. allocated(err)) call int_field(rd, ir, k0 + 1, what, cb%code(2), err)
      end subroutine read_codes
      subroutine point_record(k, err)
         integer, intent(in) :: k
         type(error_t), allocatable, intent(out) :: err
         character(len=*), parameter :: what = 'CBOUndary LINEar point record k, x, y'
         integer :: ip, kk
         call next_record(rd, ip)
         if (ip == 0) then
            call fail(rd, ip, what//': expected point '//itoa(k), err)
            return
         end if
         if (rd%src%rec(ip)%blank .or. .not. looks_like_data(rd, ip)) then
            call fail(rd, ip, what//': expected point '//itoa(k)//' of the LINEar segment', err)
            return
         end if
         if (nfields(rd, ip) >= 3) then
            call int_field(rd, ip, 1, what, kk, err)
            if (allocated(err)) return
            if (kk /= k) then
               call fail(rd, ip, what//': expected point number '//itoa(k), err)
               return
            end if
            call read_reals(ip, 2, what, cb%p(:, k), err)
         else
            call read_reals(ip, 1, what, cb%p(:, k), err)
         end if
      end subroutine point_record
   end subroutine cmd_cbound

   !> GLOBal: `PLANe STRAin` (the default), `AXISymmetric` (x = r, y = z; doc/axisymmetry.md)
   !> and `FINIte` (exic is always finite-deformation) are accepted; any other option is not
   !> supported.
   subroutine cmd_global(rd, b, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      type(error_t), allocatable, intent(out) :: err
      integer :: i
      do
         call next_in_set(rd, i)
         if (i == 0) return
         if (keyword_is(word(rd, i, 1), 'plan') .and. keyword_is(word(rd, i, 2), 'stra')) then
            b%axis_rec = 0
            cycle
         end if
         if (keyword_is(word(rd, i, 1), 'axis')) then
            b%axis_rec = i
            cycle
         end if
         if (keyword_is(word(rd, i, 1), 'fini')) cycle
         call check_data_record(rd, i, 'GLOBal', err)
         if (allocated(err)) return
         call fail(rd, i, 'GLOBal option "'//trim(rd%src%rec(i)%text)//'" is not supported: '// &
                   'expected PLANe STRAin or AXISymmetric', err)
         return
      end do
   end subroutine cmd_global

   !> INITial,VELOcity (or RATE) in the mesh phase: records `REGIon, r, vx, vy`,
   !> `MATErial, m, vx, vy` or node-vector records `n, ng, vx, vy`; applied after END in order.
   subroutine cmd_initial(rd, b, icmd, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      integer, intent(in) :: icmd
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: kinds(3) = [character(len=12) :: 'REGIon', 'MATErial', &
                                                  'node n']
      type(genvec_t) :: g
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: i, cnt, k, id
      real(wp) :: v(2)
      character(len=:), allocatable :: what

      if (.not. (keyword_is(word(rd, icmd, 2), 'velo') .or. keyword_is(word(rd, icmd, 2), 'rate'))) then
         call fail(rd, icmd, 'INITial option "'//field(rd, icmd, 2)//'" is not supported in the '// &
                   'mesh: expected INITial,VELOcity', err)
         return
      end if
      do
         call next_in_set(rd, i)
         if (i == 0) return
         if (looks_like_data(rd, i)) then
            cnt = 0
            call node_record(rd, i, 1, 'INITial,VELOcity record n, ng, vx, vy', 0, .false., g, &
                             nodes, vals, cnt, err)
            if (allocated(err)) return
            do k = 1, cnt
               call push_init(init_t(INIT_NODE, nodes(k), vals(:, k), i))
            end do
            cycle
         end if
         g = genvec_t()
         if (keyword_is(word(rd, i, 1), 'regi')) then
            what = 'INITial,VELOcity record REGIon, r, vx, vy'
         else if (keyword_is(word(rd, i, 1), 'mate')) then
            what = 'INITial,VELOcity record MATErial, m, vx, vy'
         else
            call check_data_record(rd, i, 'INITial,VELOcity', err)
            if (.not. allocated(err)) call unknown_keyword(rd, i, 'INITial record', &
                                                          field(rd, i, 1), kinds, err)
            return
         end if
         call int_field(rd, i, 2, what, id, err)
         if (.not. allocated(err)) call real_field(rd, i, 3, what, v(1), err)
         if (.not. allocated(err)) call real_field(rd, i, 4, what, v(2), err)
         if (allocated(err)) return
         if (keyword_is(word(rd, i, 1), 'regi')) then
            call push_init(init_t(INIT_REGION, id, v, i))
         else
            call push_init(init_t(INIT_MATERIAL, id, v, i))
         end if
      end do
   contains
      subroutine push_init(item)
         type(init_t), intent(in) :: item
         call grow(b%init, b%ninit + 1)
         b%ninit = b%ninit + 1
         b%init(b%ninit) = item
      end subroutine push_init
   end subroutine cmd_initial

   !> grow (exic_base_grow) for an array of ebou_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_ebou(a, n, exact)
      type(ebou_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(ebou_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_ebou

   !> grow (exic_base_grow) for an array of pbou_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_pbou(a, n, exact)
      type(pbou_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(pbou_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_pbou

   !> grow (exic_base_grow) for an array of cbou_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_cbou(a, n, exact)
      type(cbou_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(cbou_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_cbou

   !> grow (exic_base_grow) for an array of init_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_init(a, n, exact)
      type(init_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(init_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_init

end module exic_input_deck_mesh
