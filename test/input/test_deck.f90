!> Tests of the deck reader: good decks under test/data/deck/ checked against the numbering and
!> generation rules of the input language, decks generated at run time (disk refinement), and
!> malformed decks that must give a clean `file:line: <expected ...>` error.
module test_deck
   use exic_material_law, only: LAW_HYPOELASTIC
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_material_material, only: MAT_SOLID, MAT_RIGID, HOURGLASS_STIFFNESS, HOURGLASS_PHYSICAL
   use exic_contact_spec, only: SURF_REGION, SURF_MATERIAL, SURF_FACETS, PAIR_NTOS, &
                                PAIR_SYMMETRIC, PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, &
                                DETECT_SWEPT, DETECT_STATIC
   use exic_model_program, only: REQ_DISP, REQ_VELO, REQ_STRE, REQ_REAC, REQ_CONT
   use exic_input_deck_expression, only: param_table_t, set_param, evaluate
   use exic_input_deck_records, only: record_t, split_fields, field_t
   use exic_input_deck, only: read_deck
   use testing, only: suite_t, check, check_close, section, error_text
   implicit none
   private

   public :: run_deck_tests

   character(len=*), parameter :: dir = 'test/data/deck/'
   character(len=*), parameter :: tmp = 'build/test_deck/'
   integer, parameter :: L = 300

contains

   !> Run every deck test.
   subroutine run_deck_tests(s)
      type(suite_t), intent(inout) :: s
      call execute_command_line('mkdir -p '//tmp)
      call test_fields(s)
      call test_expressions(s)
      call test_block(s)
      call test_tie(s)
      call test_generation(s)
      call test_expr_deck(s)
      call test_include(s)
      call test_comment_end(s)
      call test_initial(s)
      call test_batch(s)
      call test_bar(s)
      call test_energy_warning(s)
      call test_hourglass_records(s)
      call test_contact(s)
      call test_disk(s)
      call test_polar_ring(s)
      call test_bad_decks(s)
      call test_mutations(s)
   end subroutine run_deck_tests

   !> Read a deck of test/data/deck/ and check that it reads without error.
   subroutine load(s, name, m, ok)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      type(model_t), intent(out) :: m
      logical, intent(out) :: ok
      type(error_t), allocatable :: err
      call read_deck(dir//name, m, err)
      ok = .not. allocated(err)
      if (ok) then
         call check(s, .true., name//' reads')
      else
         call check(s, .false., name//' reads', err%message)
      end if
   end subroutine load

   pure logical function has(str, sub)
      character(len=*), intent(in) :: str, sub
      has = index(str, sub) > 0
   end function has

   !> Write lines (trimmed) to a file.
   subroutine write_lines(path, lines)
      character(len=*), intent(in) :: path
      character(len=*), intent(in) :: lines(:)
      integer :: u, k
      open (newunit=u, file=path, status='replace', action='write')
      do k = 1, size(lines)
         write (u, '(a)') trim(lines(k))
      end do
      close (u)
   end subroutine write_lines

   !> Sum of the (shoelace) areas of all elements.
   pure real(wp) function total_area(m)
      type(model_t), intent(in) :: m
      integer :: e
      real(wp) :: x(2, 4)
      total_area = 0.0_wp
      do e = 1, m%mesh%nelem
         x = m%mesh%x(:, m%mesh%conn(:, e))
         total_area = total_area + 0.5_wp*((x(1, 3) - x(1, 1))*(x(2, 4) - x(2, 2)) - &
                                           (x(2, 3) - x(2, 1))*(x(1, 4) - x(1, 2)))
      end do
   end function total_area

   !> Number of nodes used by elements.
   pure integer function active_nodes(m)
      type(model_t), intent(in) :: m
      logical :: used(m%mesh%nnode)
      integer :: e
      used = .false.
      do e = 1, m%mesh%nelem
         used(m%mesh%conn(:, e)) = .true.
      end do
      active_nodes = count(used)
   end function active_nodes

   subroutine test_fields(s)
      type(suite_t), intent(inout) :: s
      type(field_t), allocatable :: f(:)
      integer :: nf
      logical :: bad
      call section(s, 'deck: fields and separators')
      call split_fields('DT,,1e-4', f, nf, bad)
      call check(s, nf == 3 .and. f(1)%s == 'DT' .and. f(2)%s == '' .and. f(3)%s == '1e-4', &
                 'DT,,1e-4 gives DT, empty, 1e-4')
      call split_fields('  disp,,1,30,2', f, nf, bad)
      call check(s, nf == 5 .and. f(2)%s == '' .and. f(5)%s == '2', 'disp,,1,30,2 skips a field')
      call split_fields('a = 2*L   b , c', f, nf, bad)
      call check(s, nf == 4 .and. f(1)%s == 'a' .and. f(2)%s == '2*L' .and. f(3)%s == 'b' .and. &
                 f(4)%s == 'c', 'blanks next to = and , are absorbed')
      call split_fields('INCL "my file, v2.inp" x', f, nf, bad)
      call check(s, nf == 3 .and. f(2)%s == 'my file, v2.inp' .and. .not. bad, 'quoted field')
      call split_fields('2 * L', f, nf, bad)
      call check(s, nf == 3, '2 * L is three fields')
   end subroutine test_fields

   subroutine test_expressions(s)
      type(suite_t), intent(inout) :: s
      type(param_table_t) :: p
      real(wp) :: pi
      pi = acos(-1.0_wp)
      call section(s, 'deck: expressions')
      call set_param(p, 'nx', 40.0_wp)
      call set_param(p, 'Length_Of_Bar', 2.5_wp)
      call ok('1+2*3', 7.0_wp)
      call ok('(1+2)*3', 9.0_wp)
      call ok('1.0+3', 4.0_wp)
      call ok('1e+3', 1000.0_wp)
      call ok('1.5d2', 150.0_wp)
      call ok('-4.36d-05', -4.36e-5_wp)
      call ok('.5*4', 2.0_wp)
      call ok('2^3^2', 64.0_wp)
      call ok('-2^2', -4.0_wp)
      call ok('2^-1', 0.5_wp)
      call ok('8/4/2', 1.0_wp)
      call ok('1-2-3', -4.0_wp)
      call ok('--3', 3.0_wp)
      call ok('((1+2)*(3+(4-1)))', 18.0_wp)
      call ok('sqrt(16)+abs(-2)', 6.0_wp)
      call ok('4*atan(1)', pi)
      call ok('exp(log(5))', 5.0_wp)
      call ok('sin(0)+cos(0)+tan(0)', 1.0_wp)
      call ok('sind(30)+cosd(60)', 1.0_wp)
      call ok('atand(1)', 45.0_wp)
      call ok('int(2.7)', 2.0_wp)
      call ok('(nx+1)*(NX/4+1)', 451.0_wp)
      call ok('2*length_of_bar', 5.0_wp)
      call ok('', 0.0_wp)
      call bad('foo+1', 'undefined parameter "foo"')
      call bad('(1+2', 'unbalanced parentheses')
      call bad('1+2)', 'unbalanced parentheses')
      call bad('2*', 'expected a number')
      call bad('1/0', 'division by zero')
      call bad('3x', 'expected an operator')
      call bad('1e', 'exponent')
      call bad('sqrt(-1)', 'negative')
      call bad('foo(1)', 'unknown function')
      call bad('abcdefghijklmnopq', 'at most 16')
   contains
      subroutine ok(text, want)
         character(len=*), intent(in) :: text
         real(wp), intent(in) :: want
         real(wp) :: v
         type(error_t), allocatable :: err
         call evaluate(text, p, v, err)
         if (allocated(err)) then
            call check(s, .false., 'evaluate '//text, err%message)
         else
            call check_close(s, v, want, 1.0e-14_wp*max(1.0_wp, abs(want)), 'evaluate '//text)
         end if
      end subroutine ok
      subroutine bad(text, word)
         character(len=*), intent(in) :: text, word
         real(wp) :: v
         type(error_t), allocatable :: err
         call evaluate(text, p, v, err, 'deck.inp', 7)
         if (.not. allocated(err)) then
            call check(s, .false., 'evaluate '//text//' fails')
         else
            call check(s, has(err%message, 'deck.inp:7:') .and. has(err%message, word), &
                       'evaluate '//text//' fails', err%message)
         end if
      end subroutine bad
   end subroutine test_expressions

   subroutine test_block(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok, good
      integer :: i, j, n, e, a
      real(wp) :: r, t, err
      call section(s, 'deck: BLOCk numbering and shape')
      call load(s, 'block.inp', m, ok)
      if (.not. ok) return
      call check(s, m%mesh%nnode == 124 .and. m%mesh%nelem == 32, 'node and element counts', &
                 itoa(m%mesh%nnode)//' '//itoa(m%mesh%nelem))
      good = .true.
      do j = 0, 3
         do i = 0, 4
            n = 1 + j*5 + i
            good = good .and. all(abs(m%mesh%x(:, n) - [real(i, wp), real(j, wp)]) < 1.0e-14_wp)
         end do
      end do
      call check(s, good, 'A: node(i,j) = node1 + j(nr+1) + i at (i, j)')
      good = .true.
      do j = 1, 3
         do i = 1, 4
            e = 1 + (j - 1)*4 + (i - 1)
            a = 1 + (j - 1)*5 + (i - 1)
            good = good .and. all(m%mesh%conn(:, e) == [a, a + 1, a + 6, a + 5])
         end do
      end do
      call check(s, good, 'A: element (i,j) = [a, a+1, a+1+R, a+R]')
      ! B: node1 = 21, elmt1 = 13 (next free), material of the previous block
      err = 0.0_wp
      do i = 0, 4
         err = max(err, abs(m%mesh%x(1, 21 + i) - (10.0_wp + (2.0_wp*i/4.0_wp)**2)))
         err = max(err, abs(m%mesh%x(1, 21 + 2*5 + i) - (10.0_wp + i)))
      end do
      call check(s, err < 1.0e-13_wp, 'B: mid-side node 5 grades edge 1-2 as 10 + (1+xi)^2; '// &
                 'edge 3-4 stays uniform')
      call check(s, all(m%mesh%conn(:, 13) == [21, 22, 27, 26]) .and. all(m%mesh%mat(13:20) == 1), &
                 'B: automatic node1/elmt1 and material 0 = previous block')
      ! C: POLAr, node1 = 101, interpolation in (r, theta) then conversion
      err = 0.0_wp
      do j = 0, 4
         do i = 0, 2
            r = 1.0_wp + 0.5_wp*i
            t = acos(-1.0_wp)/2.0_wp*j/4.0_wp
            err = max(err, maxval(abs(m%mesh%x(:, 101 + j*3 + i) - [r*cos(t), r*sin(t)])))
         end do
      end do
      call check(s, err < 1.0e-14_wp, 'C: POLAr nodes at (r cos t, r sin t)')
      call check(s, all(m%mesh%conn(:, 21) == [101, 102, 105, 104]) .and. &
                 .not. any(m%mesh%defined(36:100)), 'C: elements follow on, nodes 36..100 unused')
      ! D: Lagrange: node 9 moves the centre node only along with the interior
      call check(s, all(abs(m%mesh%x(:, 120) - [21.5_wp, 1.0_wp]) < 1.0e-14_wp) .and. &
                 all(abs(m%mesh%x(:, 117) - [21.0_wp, 0.0_wp]) < 1.0e-14_wp), &
                 'D: centre node at master node 9, edges straight')
   end subroutine test_block

   subroutine test_tie(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: TIE')
      call load(s, 'tie_regi.inp', m, ok)
      if (ok) then
         call check(s, m%mesh%nnode == 27 .and. active_nodes(m) == 24, 'TIE,REGI,1,1 merges 3 nodes', &
                    itoa(active_nodes(m)))
         call check(s, all(m%mesh%conn(:, 5) == [3, 11, 14, 6]) .and. &
                    all(m%mesh%conn(:, 8) == [14, 15, 18, 17]) .and. &
                    all(m%mesh%conn(:, 9) == [19, 20, 23, 22]), 'connectivity remapped, region 2 untouched')
         call check(s, all(m%mesh%bc(:, 3) == [1, 1]) .and. m%mesh%defined(10), &
                    'boundary codes combined; merged node stays defined')
         call check(s, all(abs(m%mesh%force(:, 6) - [6.0_wp, 0.0_wp]) < 1.0e-14_wp) .and. &
                    all(m%mesh%force(:, 13) == 0.0_wp), 'forces summed on the survivor')
         call check(s, all(abs(m%mesh%v0(:, 9) - [0.0_wp, -3.0_wp]) < 1.0e-14_wp), &
                    'initial velocity moves to the survivor')
         call check(s, size(m%requests) == 2, 'two requests')
         if (size(m%requests) == 2) then
            call check(s, m%requests(1)%id == 3 .and. m%requests(1)%kind == REQ_DISP, &
                       'request on a merged node names its survivor')
            call check(s, m%requests(2)%id == 12 .and. m%requests(2)%by_point .and. &
                       m%requests(2)%comp == 2, 'nearest node to (3.9, 0.1) is 12')
         end if
      end if
      call load(s, 'tie_all.inp', m, ok)
      if (ok) call check(s, active_nodes(m) == 21 .and. all(m%mesh%conn(:, 9) == [12, 20, 23, 15]), &
                         'TIE merges every coincident node', itoa(active_nodes(m)))
   end subroutine test_tie

   subroutine test_generation(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok, good
      integer :: k, want(2, 10)
      call section(s, 'deck: COORdinates/ELEMents generation and nodal data')
      call load(s, 'gen.inp', m, ok)
      if (.not. ok) return
      good = m%mesh%nnode == 15
      do k = 1, 5
         good = good .and. all(abs(m%mesh%x(:, k) - [k - 1.0_wp, 0.0_wp]) < 1.0e-14_wp)
         good = good .and. all(abs(m%mesh%x(:, k + 5) - [k - 1.0_wp, 1.0_wp]) < 1.0e-14_wp)
      end do
      call check(s, good, 'COORdinates generation with ng = 1')
      call check(s, m%mesh%defined(13) .and. .not. m%mesh%defined(12) .and. &
                 .not. m%mesh%defined(14) .and. all(abs(m%mesh%x(:, 13) - [2.0_wp, 5.0_wp]) < 1.0e-14_wp), &
                 'COORdinates generation with ng = 2')
      call check(s, m%mesh%nelem == 4 .and. all(m%mesh%conn(:, 2) == [2, 3, 8, 7]) .and. &
                 all(m%mesh%conn(:, 3) == [3, 4, 9, 8]) .and. all(m%mesh%mat == 1), &
                 'ELEMents gap filled by adding ng to the nodes')
      want = reshape([1, 0, 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0, 1, 0, 0, 0, 1], [2, 10])
      good = .true.
      do k = 1, 10
         good = good .and. all(m%mesh%bc(:, k) == want(:, k))
      end do
      call check(s, good, 'BOUN generation, EBOU (ADD), then CBOU NODE and LINE (SET)')
      good = .true.
      do k = 6, 10
         good = good .and. all(abs(m%mesh%force(:, k) - [10.0_wp*(k - 5), -real(k - 6, wp)]) < 1.0e-13_wp)
      end do
      call check(s, good .and. all(m%mesh%force(:, 1:5) == 0.0_wp), 'FORCe interpolation')
      call check(s, all(abs(m%mesh%disp(:, 3) - [0.5_wp, 0.5_wp]) < 1.0e-14_wp) .and. &
                 all(m%mesh%disp(:, 2) == 0.0_wp) .and. all(m%mesh%disp(:, 5) == [1.0_wp, 0.0_wp]), &
                 'DISPlacement interpolation with ng = 2')
   end subroutine test_generation

   subroutine test_expr_deck(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: parameters and expressions in fields')
      call load(s, 'expr.inp', m, ok)
      if (.not. ok) return
      call check(s, m%mesh%nelem == 4 .and. m%mesh%nnode == 9, 'BLOCk n n with n = 2^3/4')
      call check(s, all(abs(m%mesh%x(:, 9) - [2.0_wp, 1.0_wp]) < 1.0e-14_wp), &
                 'corner at (w, h) = (length_of_bar/4, sqrt(abs(-16))/4)')
      call check_close(s, m%materials(1)%young, 300.0_wp, 1.0e-12_wp, 'E = 2*big')
      call check_close(s, m%materials(1)%poisson, 0.25_wp, 1.0e-15_wp, 'nu = -(-0.25)')
      call check_close(s, m%materials(1)%rho, 3.0_wp, 1.0e-14_wp, 'rho = exp(log(3))')
      call check_close(s, m%materials(1)%mu, 120.0_wp, 1.0e-12_wp, 'mu = E/(2(1+nu))')
      call check_close(s, m%materials(1)%lambda, 120.0_wp, 1.0e-12_wp, 'lambda = E nu/((1+nu)(1-2nu))')
      call check(s, size(m%program) == 2, 'program of two commands')
      if (size(m%program) == 2) call check_close(s, m%program(1)%v(1), 5.0_wp, 0.0_wp, &
                                                 'LOOP,,d1 with blanks removed in PARAmeters')
   end subroutine test_expr_deck

   subroutine test_include(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: INCLude')
      call load(s, 'include.inp', m, ok)
      if (.not. ok) return
      call check(s, m%mesh%nnode == 4 .and. all(m%mesh%defined) .and. &
                 all(abs(m%mesh%x(:, 3) - [1.0_wp, 1.0_wp]) < 1.0e-14_wp), &
                 'nested includes inside a data set; INCLude,END stops the file')
      call check(s, size(m%materials) == 1 .and. m%materials(1)%kind == MAT_SOLID, &
                 'quoted include file name')
      call check(s, has(m%echo, '3 0 1 1') .and. .not. has(m%echo, '5 0 9 9') .and. &
                 has(m%echo, 'FEAP * * INCLude'), 'echo holds the lines read')
   end subroutine test_include

   subroutine test_comment_end(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: a comment-only line is a blank record')
      call load(s, 'comment_end.inp', m, ok)
      if (.not. ok) return
      call check(s, m%mesh%nnode == 4 .and. m%mesh%nelem == 1 .and. len(m%warnings) == 0, &
                 'comment lines end COORdinates, ELEMents and MATErial without warnings')
   end subroutine test_comment_end

   subroutine test_initial(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok, good
      integer :: n
      call section(s, 'deck: INITial forms')
      call load(s, 'init.inp', m, ok)
      if (.not. ok) return
      good = all(abs(m%mesh%v0(:, 1) - [5.0_wp, 5.0_wp]) < 1.0e-14_wp) .and. &
             all(abs(m%mesh%v0(:, 2) - [6.0_wp, 4.0_wp]) < 1.0e-14_wp) .and. &
             all(abs(m%mesh%v0(:, 3) - [7.0_wp, 3.0_wp]) < 1.0e-14_wp)
      do n = 4, 9
         good = good .and. all(m%mesh%v0(:, n) == [1.0_wp, 0.0_wp])
      end do
      do n = 10, 18
         good = good .and. all(m%mesh%v0(:, n) == [0.0_wp, -2.0_wp])
      end do
      call check(s, good, 'mesh INITial,VELOcity: REGIon, MATErial, then node records in order')
      call check(s, m%materials(2)%kind == MAT_RIGID .and. m%materials(2)%rho == 2.0_wp, 'RIGId material')
      call check(s, size(m%program) == 4, 'four INITial commands')
      if (size(m%program) /= 4) return
      associate (c => m%program(1))
         call check(s, c%option == 'rate' .and. count(c%given) == 3 .and. c%given(2) .and. &
                    c%given(5) .and. c%given(8) .and. all(abs(c%data(:, 5) - [2.5_wp, 5.0_wp]) < 1.0e-14_wp), &
                    'INITial,RATE data after END with generation')
      end associate
      associate (c => m%program(2))
         call check(s, c%option == 'regi' .and. count(c%given) == 9 .and. all(c%given(10:18)) .and. &
                    all(c%data(:, 14) == [0.5_wp, -0.5_wp]) .and. all(c%data(:, 1) == 0.0_wp), &
                    'INITial,REGIon,2 precomputed')
      end associate
      associate (c => m%program(3))
         call check(s, c%option == 'mate' .and. count(c%given) == 9 .and. all(c%given(1:9)) .and. &
                    all(c%data(:, 9) == [3.0_wp, 4.0_wp]), 'INITial,MATErial,1 precomputed')
      end associate
      associate (c => m%program(4))
         call check(s, c%option == 'velo' .and. count(c%given) == 1 .and. c%given(18) .and. &
                    all(c%data(:, 18) == [-1.0_wp, -1.0_wp]), 'INITial,VELOcity data after END')
      end associate
   end subroutine test_initial

   subroutine test_batch(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      integer :: k
      character(len=4), parameter :: names(14) = [character(len=4) :: 'tran', 'dt', 'dt', 'dt', &
                                                  'outp', 'prin', 'loop', 'loop', 'time', 'form', &
                                                  'next', 'tplo', 'next', 'loop']
      call section(s, 'deck: BATCh program')
      call load(s, 'batch.inp', m, ok)
      if (.not. ok) return
      call check(s, size(m%program) == 15, 'fifteen commands', itoa(size(m%program)))
      if (size(m%program) /= 15) return
      call check(s, all([(m%program(k)%name == names(k), k=1, 14)]) .and. m%program(15)%name == 'next', &
                 'command names')
      call check(s, m%program(1)%option == 'cent' .and. m%program(2)%option == 'cfl' .and. &
                 m%program(2)%v(1) == 0.9_wp .and. m%program(3)%v(1) == 0.5_wp, 'TRAN,CENT; DT,CFL default 0.9')
      call check(s, m%program(4)%option == '' .and. m%program(4)%v(1) == 1.0e-4_wp .and. &
                 has(m%warnings, 'batch.inp:25: warning:'), 'DT 1e-4 accepted with a warning')
      call check(s, m%program(5)%option == 'hdf5' .and. m%program(5)%v(1) == 0.01_wp .and. &
                 m%program(6)%option == 'ener' .and. m%program(6)%v(1) == 10.0_wp, 'OUTPut and PRINt')
      call check(s, m%program(7)%jump == 13 .and. m%program(13)%jump == 7 .and. &
                 m%program(8)%jump == 11 .and. m%program(11)%jump == 8 .and. &
                 m%program(14)%jump == 15 .and. m%program(15)%jump == 14, 'LOOP/NEXT jumps')
      call check(s, m%program(7)%v(1) == 3.0_wp .and. m%program(8)%v(1) == 100.0_wp .and. &
                 m%program(9)%v(1) == 0.4_wp .and. m%program(10)%option == 'expl' .and. &
                 m%program(12)%v(1) == 5.0_wp, 'loop counts, tmax, FORM,EXPL, TPLOt inc')
      call check(s, has(m%program(9)%where, 'batch.inp:30'), 'command keeps file:line')
      call check(s, m%materials(1)%quadrature == 1 .and. m%materials(1)%hourglass == 0.05_wp, &
                 'QUADrature and HOURglass')
      call check(s, size(m%requests) == 3, 'three requests (show skipped)')
      if (size(m%requests) /= 3) return
      call check(s, m%requests(1)%id == 9 .and. m%requests(2)%kind == REQ_STRE .and. &
                 m%requests(2)%id == 4 .and. m%requests(2)%comp == 6 .and. &
                 m%requests(3)%kind == REQ_REAC .and. m%requests(3)%comp == 2, 'requests resolved')
   end subroutine test_batch

   !> LAGRange,ENERgy on a REGIon surface of a deformable body is warned about at the PAIR
   !> (doc/impact.md, section 4); on a rigid body's REGIon surface it is not.
   subroutine test_energy_warning(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer, parameter :: L = 40
      character(len=L) :: deck(33)
      call section(s, 'deck: LAGRange,ENERgy on a whole-boundary surface')
      call execute_command_line('mkdir -p '//tmp)
      deck = [character(len=L) :: 'FEAP * * two blocks', '0 0 0 2 2 4', 'MATErial,1', ' SOLId', &
              '  ELAStic NEOHookean 1e4 0', '  DENSity 0.1', '', 'MATErial,2', ' SOLId', &
              '  ELAStic NEOHookean 1e4 0', '  DENSity 0.1', '', 'REGIon,1', 'BLOCk', ' CARTesian,2,1,1,1,1', &
              '  1,0,0', '  2,2,0', '  3,2,1', '  4,0,1', '', 'REGIon,2', 'BLOCk', ' CARTesian,2,1,7,3,2', &
              '  1,2,0', '  2,4,0', '  3,4,1', '  4,2,1', '', &
              'CONTact', ' SURFace,1', '  FACEts', '   1,0,3,6', '']
      call write_lines(tmp//'ew.inp', [character(len=L) :: deck, ' SURFace,2', '  REGIon,2', &
                       ' PAIR,1,NTOS,1,2', '  LAGRange,ENERgy', 'END CONTact', '', 'END', 'BATCh', 'END', 'STOP'])
      call read_deck(tmp//'ew.inp', m, err)
      call check(s, .not. allocated(err), 'ENERgy on a REGIon surface reads', error_text(err))
      call check(s, has(m%warnings, 'ew.inp:36: warning: PAIR 1 with LAGRange,ENERgy on SURFace 2'), &
                 'warning at the PAIR names the REGIon surface', m%warnings)
      deck(9:11) = [character(len=L) :: ' RIGId', '  DENSity 0.1', '']
      call write_lines(tmp//'ew.inp', [character(len=L) :: deck, ' SURFace,2', '  REGIon,2', &
                       ' PAIR,1,NTOS,1,2', '  LAGRange,ENERgy', 'END CONTact', '', 'END', 'BATCh', 'END', 'STOP'])
      call read_deck(tmp//'ew.inp', m, err)
      call check(s, .not. allocated(err), 'ENERgy against a rigid REGIon surface reads', error_text(err))
      call check(s, .not. has(m%warnings, 'ENERgy'), 'no warning for a rigid body''s REGIon surface', &
                 m%warnings)
      ! a deformable body's REGIon surface against a rigid body: only the facing segments (eq. I.3b)
      call write_lines(tmp//'ew.inp', [character(len=L) :: deck(1:29), ' SURFace,1', '  REGIon,1', ' SURFace,2', &
                       '  REGIon,2', ' PAIR,1,NTOS,1,2', '  LAGRange,ENERgy', 'END CONTact', '', 'END', 'BATCh', 'END', &
                       'STOP'])
      call read_deck(tmp//'ew.inp', m, err)
      call check(s, .not. allocated(err) .and. .not. has(m%warnings, 'ENERgy'), 'no warning for a deformable '// &
                 'body''s REGIon surface against a rigid body (only its facing segments are massless)', m%warnings)
   end subroutine test_energy_warning

   !> HOURglass h (Flanagan-Belytschko coefficient) and HOURglass,PHYSical[,s] (doc/hourglass.md);
   !> a scale outside (0, 1] or an unknown form is an error naming file:line.
   subroutine test_hourglass_records(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer, parameter :: L = 40
      character(len=L) :: head(6), tail(13)
      call section(s, 'deck: HOURglass records')
      head = [character(len=L) :: 'FEAP * * one block', '0 0 0 2 2 4', 'MATErial,1', ' SOLId', &
              '  ELAStic NEOHookean 1e4 0.3', '  QUADrature 1']
      tail = [character(len=L) :: '  DENSity 0.1', '', 'BLOCk', ' CARTesian,2,1,1,1,1', '  1,0,0', &
              '  2,2,0', '  3,2,1', '  4,0,1', '', 'END', 'BATCh', 'END', 'STOP']
      call write_lines(tmp//'hg.inp', [character(len=L) :: head, '  HOURglass,PHYSical', tail])
      call read_deck(tmp//'hg.inp', m, err)
      call check(s, .not. allocated(err), 'HOURglass,PHYSical reads', error_text(err))
      if (allocated(err)) return
      call check(s, m%materials(1)%hourglass_kind == HOURGLASS_PHYSICAL .and. &
                 m%materials(1)%hourglass == 1.0_wp, 'HOURglass,PHYSical: scale 1')
      call write_lines(tmp//'hg.inp', [character(len=L) :: head, '  HOURglass phys 0.5', tail])
      call read_deck(tmp//'hg.inp', m, err)
      call check(s, .not. allocated(err), 'HOURglass phys 0.5 reads', error_text(err))
      if (allocated(err)) return
      call check(s, m%materials(1)%hourglass_kind == HOURGLASS_PHYSICAL .and. &
                 m%materials(1)%hourglass == 0.5_wp, 'HOURglass phys 0.5: scale 0.5')
      call write_lines(tmp//'hg.inp', [character(len=L) :: head, '  HOURglass 0.2', tail])
      call read_deck(tmp//'hg.inp', m, err)
      call check(s, .not. allocated(err), 'HOURglass 0.2 reads', error_text(err))
      if (allocated(err)) return
      call check(s, m%materials(1)%hourglass_kind == HOURGLASS_STIFFNESS .and. &
                 m%materials(1)%hourglass == 0.2_wp, 'HOURglass 0.2: the Flanagan-Belytschko coefficient')
      call write_lines(tmp//'hg.inp', [character(len=L) :: head, tail])
      call read_deck(tmp//'hg.inp', m, err)
      call check(s, .not. allocated(err) .and. m%materials(1)%hourglass_kind == HOURGLASS_STIFFNESS &
                 .and. m%materials(1)%hourglass == 0.1_wp, 'no HOURglass record: coefficient 0.1', &
                 error_text(err))
      call bad('  HOURglass,PHYSical,2', 'expected a scale s with 0 < s <= 1')
      call bad('  HOURglass,PHYSical,0', 'expected a scale s with 0 < s <= 1')
      call bad('  HOURglass,VISCous', 'HOURglass h (a coefficient) or HOURglass,PHYSical[,s]')
      call bad('  HOURglass -0.1', 'expected a coefficient >= 0')
   contains
      subroutine bad(line, want)
         character(len=*), intent(in) :: line, want
         call write_lines(tmp//'hg.inp', [character(len=L) :: head, line, tail])
         call read_deck(tmp//'hg.inp', m, err)
         call check(s, allocated(err), trim(line)//' refused')
         if (allocated(err)) call check(s, has(err%message, 'hg.inp:7:') .and. has(err%message, want), &
                                        trim(line)//': file:line and what is expected', err%message)
      end subroutine bad
   end subroutine test_hourglass_records

   subroutine test_bar(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: the reference bar deck')
      call load(s, 'bar.inp', m, ok)
      if (.not. ok) return
      call check(s, m%mesh%nnode == 205 .and. m%mesh%nelem == 160, 'bar mesh 40 x 4')
      call check(s, count(m%mesh%bc(1, :) /= 0) == 5 .and. count(m%mesh%bc(2, :) /= 0) == 41 .and. &
                 all(m%mesh%bc(1, 41:205:41) == 1), 'EBOUndary x = l and y = 0')
      call check(s, m%materials(1)%law == LAW_HYPOELASTIC .and. .not. has(m%warnings, 'ISOTropic'), &
                 'ELAStic ISOTropic is the hypoelastic law, without a warning')
      call check(s, size(m%requests) == 4, 'four requests')
      if (size(m%requests) == 4) then
         call check(s, m%requests(3)%id == 21 .and. m%requests(3)%by_point .and. &
                    m%requests(3)%kind == REQ_DISP, 'disp,,1,l/2,0 is node 21')
         call check(s, m%requests(4)%id == 20 .and. m%requests(4)%kind == REQ_STRE, &
                    'stre,,1,l/2,0.1: equidistant centroids, lowest element')
         call check(s, m%requests(2)%kind == REQ_VELO .and. m%requests(2)%id == 1, 'velo,1,1')
      end if
      call check(s, count(m%program(4)%given) == 205 .and. &
                 all(m%program(4)%data(1, :) == 5.0e3_wp), 'INITial,RATE on nodes 1..nn')
   end subroutine test_bar

   subroutine test_contact(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      logical :: ok
      call section(s, 'deck: CONTact block')
      call load(s, 'contact.inp', m, ok)
      if (.not. ok) return
      associate (c => m%contact)
         call check(s, c%active .and. c%automatic .and. size(c%surfaces) == 3 .and. size(c%pairs) == 3, &
                    'three surfaces, three pairs, AUTOmatic')
         if (size(c%surfaces) /= 3 .or. size(c%pairs) /= 3) return
         call check(s, c%surfaces(1)%by == SURF_REGION .and. c%surfaces(1)%ref == 1 .and. &
                    c%surfaces(2)%by == SURF_MATERIAL .and. c%surfaces(2)%ref == 2 .and. &
                    c%surfaces(3)%by == SURF_FACETS, 'surface descriptions')
         call check(s, size(c%surfaces(3)%facets, 2) == 3 .and. &
                    all(c%surfaces(3)%facets(:, 2) == [11, 12]), 'FACEts generation')
         call check(s, c%pairs(1)%kind == PAIR_NTOS .and. c%pairs(1)%slave == 1 .and. &
                    c%pairs(1)%master == 2 .and. c%pairs(1)%method == METHOD_PENALTY .and. &
                    c%pairs(1)%penalty == 1.0e6_wp .and. .not. c%pairs(1)%penalty_scaled .and. &
                    c%pairs(1)%detection == DETECT_STATIC, 'PAIR 1 NTOS, PENAlty k, STATic')
         call check(s, c%pairs(2)%kind == PAIR_SYMMETRIC .and. c%pairs(2)%penalty_scaled .and. &
                    c%pairs(2)%penalty == 0.2_wp .and. c%pairs(2)%detection == DETECT_SWEPT, &
                    'PAIR 2 SYMMetric, PENAlty SCALe')
         call check(s, c%pairs(3)%kind == PAIR_SELF .and. c%pairs(3)%master == 3 .and. &
                    c%pairs(3)%method == METHOD_LAGRANGE, 'PAIR 3 SELF, LAGRange')
         call check(s, c%auto_options%method == METHOD_PENALTY .and. c%auto_options%penalty_scaled &
                    .and. c%auto_options%penalty == 0.1_wp, 'AUTOmatic with PENAlty,SCALe default 0.1')
      end associate
      call check(s, size(m%requests) == 2, 'cont requests')
      if (size(m%requests) == 2) call check(s, m%requests(1)%kind == REQ_CONT .and. &
                                            m%requests(1)%id == 2 .and. m%requests(1)%comp == 4, 'cont,2,4')
   end subroutine test_contact

   !> A disk of radius 1 from a centre square and four curved blocks whose edge mid-side nodes lie
   !> on the circle, tied. On an outer edge the quadratic map through three points of a 90-degree
   !> arc (half-angle a, c = cos a, s = sin a) is radial R c + R (1-c)(1-eta^2), tangential
   !> R s eta, so r^2 = R^2 (1 - (1-c)^2 q (1-q)), q = 1 - eta^2: the nodes lie within
   !> 1 - sqrt(1 - (1-c)^2/4) = 1.08% inside the circle and exactly on it at eta = -1, 0, 1. The
   !> elements tile the polygon of the boundary nodes, whose area is exactly
   !> 2 R^2 + (16/3) R^2 s (1-c) (1 - 1/n^2) (each chord of a parabola cuts a segment (h^3/6)|B x C|);
   !> it converges at second order to 3.1046 R^2, 1.2% below pi R^2, within the radial bound.
   subroutine test_disk(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: level, n, b, j, node
      real(wp) :: c, sn, eta, q, r2, want, worst, area, alimit, prev_gap, gap, rmin
      logical :: good, inside
      call section(s, 'deck: disk from five blocks and TIE')
      c = cos(acos(-1.0_wp)/4.0_wp)
      sn = c
      alimit = 2.0_wp + 16.0_wp/3.0_wp*sn*(1.0_wp - c)
      rmin = sqrt(1.0_wp - (1.0_wp - c)**2/4.0_wp)
      prev_gap = -1.0_wp
      do level = 1, 4
         n = 2**level
         call write_lines(tmp//'disk.inp', disk_deck(n))
         call read_deck(tmp//'disk.inp', m, err)
         if (allocated(err)) then
            call check(s, .false., 'disk n = '//itoa(n)//' reads', err%message)
            return
         end if
         call check(s, active_nodes(m) == 5*(n + 1)**2 - 8*n - 4, 'n = '//itoa(n)// &
                    ': TIE leaves 5(n+1)^2 - 8n - 4 nodes', itoa(active_nodes(m)))
         worst = 0.0_wp
         inside = .true.
         do b = 1, 4
            do j = 0, n
               node = b*(n + 1)**2 + 1 + j*(n + 1) + n
               eta = -1.0_wp + 2.0_wp*j/n
               q = 1.0_wp - eta**2
               r2 = sum(m%mesh%x(:, node)**2)
               want = 1.0_wp - (1.0_wp - c)**2*q*(1.0_wp - q)
               worst = max(worst, abs(r2 - want))
               inside = inside .and. sqrt(r2) <= 1.0_wp + 1.0e-14_wp .and. sqrt(r2) >= rmin - 1.0e-14_wp
            end do
         end do
         call check(s, worst < 1.0e-14_wp, 'n = '//itoa(n)//': boundary r^2 = 1 - (1-c)^2 q(1-q)')
         call check(s, inside, 'n = '//itoa(n)//': boundary nodes within [0.9892 R, R]')
         area = total_area(m)
         want = 2.0_wp + 16.0_wp/3.0_wp*sn*(1.0_wp - c)*(1.0_wp - 1.0_wp/n**2)
         call check_close(s, area, want, 1.0e-13_wp, 'n = '//itoa(n)//': area of the tied disk')
         gap = alimit - area
         if (prev_gap > 0.0_wp) call check_close(s, gap/prev_gap, 0.25_wp, 1.0e-10_wp, &
                                                 'n = '//itoa(n)//': area error falls by 4 per halving')
         prev_gap = gap
      end do
      good = abs(alimit - acos(-1.0_wp))/acos(-1.0_wp) <= 1.0_wp - rmin**2
      call check(s, good .and. area < acos(-1.0_wp), 'area limit within the radial bound of pi R^2')
   end subroutine test_disk

   function disk_deck(n) result(lines)
      integer, intent(in) :: n
      character(len=L), allocatable :: lines(:)
      lines = [character(len=L) :: 'FEAP * * disk of radius r', '0 0 0 2 2 4', 'PARAmeters', &
               'r = 1', 'a = 0.4', 'c = r*cosd(45)', 'n = '//itoa(n), '', &
               'MATErial,1', 'SOLId', 'ELAStic NEOHookean 1 0.3', 'DENSity 1', '', &
               'BLOCk', 'CART n n 0 0 1', '1 -a -a', '2 a -a', '3 a a', '4 -a a', '', &
               'BLOCk', 'CART n n 0 0 1', '1 a -a', '2 c -c', '3 c c', '4 a a', '6 r 0', '', &
               'BLOCk', 'CART n n 0 0 1', '1 a a', '2 c c', '3 -c c', '4 -a a', '6 0 r', '', &
               'BLOCk', 'CART n n 0 0 1', '1 -a a', '2 -c c', '3 -c -c', '4 -a -a', '6 -r 0', '', &
               'BLOCk', 'CART n n 0 0 1', '1 -a -a', '2 -c -c', '3 c -c', '4 a -a', '6 0 -r', '', &
               'END', 'TIE', 'BATCh', 'END', 'STOP']
   end function disk_deck

   !> A POLAr quarter ring 1 <= r <= 2: nodes exactly on the circles; each element is the
   !> trapezoid between two rays, so the area is exactly (n/2)(4 - 1) sin(pi/(2n)) -> 3 pi/4.
   subroutine test_polar_ring(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: n, k
      real(wp) :: want, r
      logical :: good
      call section(s, 'deck: POLAr quarter ring')
      do k = 1, 3
         n = 4**k
         call write_lines(tmp//'ring.inp', [character(len=L) :: 'FEAP * * ring', '0 0 0 2 2 4', &
                          'MATE 1', 'SOLI', 'ELAS NEOH 1 0.3', 'DENS 1', '', 'BLOCk', &
                          'POLAr 2 '//itoa(n)//' 0 0 1', '1 1 0', '2 2 0', '3 2 90', '4 1 90', '', &
                          'END', 'BATCh', 'END', 'STOP'])
         call read_deck(tmp//'ring.inp', m, err)
         if (allocated(err)) then
            call check(s, .false., 'ring reads', err%message)
            return
         end if
         good = .true.
         do n = 1, m%mesh%nnode
            r = norm2(m%mesh%x(:, n))
            good = good .and. abs(r - (1.0_wp + 0.5_wp*modulo(n - 1, 3))) < 1.0e-14_wp
         end do
         n = 4**k
         call check(s, good, 'n = '//itoa(n)//': nodes on r = 1, 1.5, 2')
         want = 0.5_wp*n*3.0_wp*sin(acos(-1.0_wp)/(2.0_wp*n))
         call check_close(s, total_area(m), want, 1.0e-13_wp, 'n = '//itoa(n)//': ring area')
      end do
      n = 64
      call check_close(s, (0.75_wp*acos(-1.0_wp) - total_area(m))*n**2, acos(-1.0_wp)**3/32.0_wp, &
                       1.0e-3_wp, 'n = 64: (3 pi/4 - area) n^2 -> pi^3/32 (second order)')
   end subroutine test_polar_ring

   !> Malformed decks: each must give an error naming the file, the line and what was expected.
   subroutine test_bad_decks(s)
      type(suite_t), intent(inout) :: s
      character(len=L), allocatable :: h(:), mt(:), bl(:), en(:), bt(:)
      type(model_t) :: m
      type(error_t), allocatable :: err
      call section(s, 'deck: malformed decks')
      h = [character(len=L) :: 'FEAP * * bad deck', '0 0 0 2 2 4']
      mt = [character(len=L) :: 'MATErial,1', ' SOLId', ' ELAStic NEOHookean 100 0.3', ' DENSity 1', '']
      bl = [character(len=L) :: 'BLOCk', ' CART 2 2 0 0 1', ' 1 0 0', ' 2 1 0', ' 3 1 1', ' 4 0 1', '']
      en = [character(len=L) :: 'END', 'BATCh', ' TRAN EXPL', ' DT,,1e-4', 'END', 'STOP']
      bt = [character(len=L) :: h, mt, bl, 'END', 'BATCh']     ! next line is 17
      call bad('b01', [character(len=L) :: h, 'CORD', ' 1 0 0 0', '', mt, bl, en], 3, &
               'nearest known keyword: COORdinates')
      call bad('b02', [character(len=L) :: h, mt, 'BLOCk', ' CART 2 2 0 0 1', ' 1 0 0', ' 2 1 0', '', &
                       en], 8, 'missing corner master node(s) 3 4')
      call bad('b03', [character(len=L) :: h, mt, 'COOR', ' 1 0 0 0', ' 2 0 1 0', ' 3 0 1 1', &
                       ' 4 0 0 1', '', 'ELEM', ' 1 0 1 1 4 3 2', '', en], 15, &
               'element 1 (nodes 1 4 3 2) has non-positive area')
      call bad('b04', [character(len=L) :: h, mt, 'COOR', ' 1 0 0 0', ' 2 0 2 0', ' 3 0 0.5 0.5', &
                       ' 4 0 0 2', '', 'ELEM', ' 1 0 1 1 2 3 4', '', en], 15, 'not convex at node 3')
      call bad('b05', [character(len=L) :: h, mt, 'BLOCk', ' CART 2 2 0 0 2', ' 1 0 0', ' 2 1 0', &
                       ' 3 1 1', ' 4 0 1', '', en], 8, 'expected MATErial,2')
      call bad('b06', [character(len=L) :: h, 'MATE,1', ' SOLI', ' ELAS NEOH 100 0.5', ' DENS 1', '', &
                       bl, en], 5, 'expected -1 < nu < 0.5')
      call bad('b07', [character(len=L) :: h, 'MATE,1', ' SOLI', ' ELAS NEOH 0 0.3', ' DENS 1', '', &
                       bl, en], 5, 'expected E > 0')
      call bad('b07p', [character(len=L) :: h, 'MATE,1', ' SOLI', ' ELAS ISOT 100 0.3', ' DENS 1', &
                        ' PLAS MISE 1', '', bl, en], 7, 'expected ELAStic NEOHookean E nu with it')
      call bad('b07e', [character(len=L) :: h, 'MATE,1', ' SOLI', ' ELAS MOON 100 0.3', ' DENS 1', '', &
                        bl, en], 5, 'expected ELAStic NEOHookean E nu or ELAStic ISOTropic E nu')
      call bad('b08', [character(len=L) :: h, mt, 'COOR', ' 1 0 #5 0', '', bl, en], 9, 'expected a number')
      call bad('b09', [character(len=L) :: h, mt, 'COOR', ' 1 0 foo 0', '', bl, en], 9, &
               'undefined parameter "foo"')
      call bad('b10', [character(len=L) :: h, mt, 'COOR', ' 1 0 (1+2 0', '', bl, en], 9, &
               'unbalanced parentheses')
      call bad('b11', [character(len=L) :: bt, ' LOOP,,3', ' TIME', 'END', 'STOP'], 17, &
               'LOOP without NEXT: expected NEXT')
      call bad('b12', [character(len=L) :: bt, ' NEXT', 'END', 'STOP'], 17, 'NEXT without LOOP')
      call bad('b13', [h, mt, bl], 14, 'expected END')
      call bad('b14', [character(len=L) :: h, mt, bl, 'END'], 15, 'expected BATCh')
      call bad('b15', [character(len=L) :: bt, ' TRAN EXPL', 'END'], 18, 'expected STOP')
      call bad('b16', [character(len=L) :: h, 'INCLude nothere.inp', mt, bl, en], 3, &
               'expected an existing file')
      call write_lines(tmp//'b17_self.inp', [character(len=L) :: 'INCLude b17_self.inp'])
      call bad('b17', [character(len=L) :: h, 'INCLude b17_self.inp', mt, bl, en], 1, &
               'depth of at most 9', 'b17_self.inp')
      call bad('b18', [character(len=L) :: bt, ' TPLOt', 'END', ' disp,999,1', '', 'STOP'], 19, &
               'node 999 is unknown')
      call bad('b19', [character(len=L) :: bt, ' TPLOt', 'END', ' disp,1,3', '', 'STOP'], 19, &
               'expected dof 1 or 2')
      call bad('b20', [character(len=L) :: h, 'COOR ! '//repeat('x', 260), mt, bl, en], 3, &
               'expected at most 256 characters')
      call bad('b21', [character(len=L) :: bt, ' FROM,EXPL', 'END', 'STOP'], 17, &
               'nearest known keyword: FORM')
      call bad('b22', [character(len=L) :: bt, ' TRAN,NEWMark', 'END', 'STOP'], 17, &
               'expected TRANsient,EXPLicit')
      call bad('b23', [character(len=L) :: bt, ' DT,CFL,1.5', 'END', 'STOP'], 17, 'expected 0 < c <= 1')
      call bad('b24', [character(len=L) :: h, 'GLOBal', ' PLANe STREss', '', mt, bl, en], 4, &
               'not supported')
      call bad('b25', [character(len=L) :: h, mt, 'COOR', ' 1 0 0 0', '! a comment ends the set', &
                       ' 2 0 1 0', '', bl, en], 11, 'the blank record at')
      call check(s, has(m%warnings, 'b25.inp:11: warning: record starts like data'), &
                 'b25: warning names the record after the comment line', m%warnings)
      call bad('b26', [character(len=L) :: '0 0 0 2 2 4', mt, bl, en], 1, 'expected the title record')
      call bad('b27', [character(len=L) :: 'FEAP * * x', '', '0 0 0 2 2 4', mt, bl, en], 2, &
               'expected the control record')
      call bad('b28', [character(len=L) :: 'FEAP * * x', '0 0 0 3 2 4', mt, bl, en], 2, &
               'expected ndm = 2')
      call bad('b29', [character(len=L) :: 'FEAP * * x', '4 0 0 2 2 4', mt, bl, en], 2, &
               'expected at most numnp = 4')
      call bad('b30', [character(len=L) :: h, mt, 'COOR', ' 1 0 0 0', ' 2 0 1 0', ' 3 0 1 1', '', &
                       'ELEM', ' 1 0 1 1 2 3 99', '', en], 14, 'uses node 99')
      call bad('b31', [character(len=L) :: h, mt, bl, 'CONTact', ' SURFace,1', ' REGIon,0', &
                       ' PAIR,1,NTOS,1,2', 'END CONTact', en], 18, 'expected a defined SURFace')
      call bad('b32', [character(len=L) :: h, mt, bl, 'CONTact', ' SURFace,1', ' REGIon,5', &
                       ' PAIR,1,SELF,1', 'END CONTact', en], 16, 'region 5 has no elements')
      call bad('b33', [character(len=L) :: bt, ' INITial,REGIon,7,1,0', 'END', 'STOP'], 17, &
               'region 7 has no elements')
      call bad('b34', [character(len=L) :: h, mt, bl, 'CONTact', ' SURFace,1', ' REGIon,0'], 17, &
               'expected END CONTact')
      call bad('b35', [character(len=L) :: h, 'MATErial,1', ' ELAStic NEOHookean 100 0.3', ' DENSity 1', &
                       '', bl, en], 3, 'expected SOLId or RIGId')
      call bad('b36', [character(len=L) :: h, mt, 'COOR', ' 1 0 0 0', ' 2 0 1 0', ' 3 0 1 1', ' 4 0 0 1', &
                       '', 'ELEM', ' 2 0 1 1 2 3 4', ' 1 0 1 1 2 3 4', '', en], 16, 'increasing order')
      call bad('b37', [character(len=L) :: h, mt, 'BLOCk', ' CART 2 2 0 5 1', ' 1 0 0', ' 2 1 0', &
                       ' 3 1 1', ' 4 0 1', '', en], 15, 'element 1 is missing')
      call write_lines(tmp//'b38_part.inp', [character(len=L) :: 'MATErial,1', ' SOLId', &
                       ' ELAStic NEOHookean 100 0.7', ' DENSity 1', ''])
      call bad('b38', [character(len=L) :: h, 'INCLude b38_part.inp', bl, en], 3, &
               'expected -1 < nu < 0.5', 'b38_part.inp')
      call bad('b39', [character(len=L) :: bt, ' TPLOt', 'END', ' stre,1,11', '', 'STOP'], 19, &
               'expected 1..10')
      call bad('b40', [character(len=L) :: bt, ' TPLOt', 'END', ' cont,1,1', '', 'STOP'], 19, &
               'no CONTact block')
      call bad('b41', [character(len=L) :: h, 'INCLude "abc.inp', mt, bl, en], 3, 'expected a closing "')
      call bad('b42', [character(len=L) :: bt, ' DT,XYZ,1', 'END', 'STOP'], 17, &
               'nearest known keyword: CFL')
      call bad('b43', [character(len=L) :: h, mt, bl, 'CONTact', ' SURFace,1', ' FACEts', ' 1 0 1 99', &
                       '', ' PAIR,1,SELF,1', 'END CONTact', en], 16, 'uses node 99')
      call bad('b44', [h, mt, mt, bl, en], 8, 'MATErial 1 is already defined')
      call bad('b45', [character(len=L) :: bt, ' INITial,DISP', 'END', 'STOP'], 17, &
               'INITial,DISPlacement is not supported')
      call bad('b46', [character(len=L) :: bt, ' TPLOt', 'END', ' dips,1,1', '', 'STOP'], 19, &
               'nearest known keyword: disp')
      call bad('b47', [character(len=L) :: h, mt, bl, 'BLOCk', ' CART 1 1 1 0 1', ' 1 5 0', ' 2 6 0', &
                       ' 3 6 1', ' 4 5 1', '', en], 15, 'node 1 is already defined')
      call bad('b48', [character(len=L) :: h, mt, 'FORCe', ' 3 0 1 0', ' 3 0 2 0', '', bl, en], 10, &
               'repeats the previous record')
      call bad('b49', [character(len=L) :: h, mt, bl, 'END', 'TIE', 'STOP'], 17, &
               'expected TIE, PARAmeters or BATCh')
      call bad('b50', [character(len=L) :: h, mt, 'BLOCk', ' CART 2 2.5 0 0 1', ' 1 0 0', '', en], 9, &
               'expected an integer')
      call bad('b51', [character(len=L) :: bt, ' CHECk,ENERgy,0.2,0.1', 'END', 'STOP'], 17, &
               'expected 0 < warn <= stop')
      call bad('b52', [character(len=L) :: bt, ' CHECk,FORCe', 'END', 'STOP'], 17, &
               'nearest known keyword: ENERgy')
      call bad('b53', [character(len=L) :: bt, ' CHECk,ENERgy,0.01,0.1,7', 'END', 'STOP'], 17, &
               'is not used')
   contains
      subroutine bad(tag, lines, line, word, file)
         character(len=*), intent(in) :: tag
         character(len=*), intent(in) :: lines(:)
         integer, intent(in) :: line
         character(len=*), intent(in) :: word
         character(len=*), intent(in), optional :: file
         character(len=:), allocatable :: where, msg
         call write_lines(tmp//tag//'.inp', lines)
         call read_deck(tmp//tag//'.inp', m, err)
         where = tag//'.inp:'//itoa(line)//':'
         if (present(file)) where = file//':'//itoa(line)//':'
         if (.not. allocated(err)) then
            call check(s, .false., tag//': error returned')
            return
         end if
         msg = err%message
         call check(s, .true., tag//': error returned')
         call check(s, has(msg, where), tag//': names '//where, msg)
         call check(s, has(msg, word), tag//': says "'//word//'"', msg)
      end subroutine bad
   end subroutine test_bad_decks

   !> Every truncation, single-line deletion and single-line duplication of the good decks reads
   !> without crashing, and every error it gives names a file and a line.
   subroutine test_mutations(s)
      type(suite_t), intent(inout) :: s
      character(len=16), parameter :: decks(6) = [character(len=16) :: 'bar.inp', 'gen.inp', &
                                                  'init.inp', 'batch.inp', 'contact.inp', 'tie_regi.inp']
      character(len=L) :: lines(120)
      integer :: d, n, k, u, ios, mode, nerr
      logical :: named
      type(model_t) :: m
      type(error_t), allocatable :: err
      call section(s, 'deck: mutated decks never crash')
      call execute_command_line('cp '//dir//'tie_body.inp '//tmp)
      do d = 1, size(decks)
         open (newunit=u, file=dir//trim(decks(d)), status='old', action='read')
         n = 0
         do
            read (u, '(a)', iostat=ios) lines(n + 1)
            if (ios /= 0) exit
            n = n + 1
         end do
         close (u)
         do mode = 1, 3
            named = .true.
            nerr = 0
            do k = 1, n
               select case (mode)
               case (1)
                  call write_lines(tmp//'mut.inp', lines(1:k))
               case (2)
                  call write_lines(tmp//'mut.inp', [character(len=L) :: lines(1:k - 1), lines(k + 1:n)])
               case (3)
                  call write_lines(tmp//'mut.inp', [character(len=L) :: lines(1:k), lines(k:n)])
               end select
               call read_deck(tmp//'mut.inp', m, err)
               if (allocated(err)) then
                  nerr = nerr + 1
                  named = named .and. has_file_line(err%message)
               end if
            end do
            call check(s, named .and. nerr > 0, trim(decks(d))//': '//itoa(n)//' mutations of kind '// &
                       itoa(mode)//', '//itoa(nerr)//' errors, each with file:line')
         end do
      end do
   contains
      logical function has_file_line(msg)
         character(len=*), intent(in) :: msg
         integer :: p
         p = index(msg, '.inp:')
         has_file_line = .false.
         if (p == 0 .or. p + 5 > len(msg)) return
         has_file_line = scan(msg(p + 5:p + 5), '0123456789') == 1
      end function has_file_line
   end subroutine test_mutations

end module test_deck
