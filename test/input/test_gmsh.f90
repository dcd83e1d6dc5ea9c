!> Gmsh meshes (GMSH, PBOUndary, SURFace PHYSical; doc/gmsh.md) and POLAr blocks about any
!> centre: the example disk_on_block.inp read and checked against its .geo (numbering, regions,
!> edge sets and their orientation, fixed nodes); the same scene with the block written as a
!> BLOCk, and meshed from the .geo at run time, give the same histories to 1e-12; a bar made
!> of a Gmsh half and a BLOCk half joined by TIE gives the histories of the one-block bar; a
!> disk meshed at run time by Gmsh's unstructured quadrilateral mesher translates exactly;
!> every bad input is an error naming file:line and what was expected; the library is loaded at
!> run time (a library that does not load is an error, the exic program starts without it).
module test_gmsh
   use, intrinsic :: iso_c_binding, only: c_ptr, c_associated
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   use exic_mesh_edge_set, only: find_edge_set
   use exic_input_gmsh_library, only: GMSH_LIBRARIES, gmsh_library_open
   use testing, only: suite_t, check, check_close, section, skip, have_command, file_text
   use deck_runner, only: read_table, column
   implicit none
   private

   public :: run_gmsh_tests

   character(len=*), parameter :: ex = 'inputs/examples/'
   character(len=*), parameter :: tmp = 'build/test_gmsh/'
   !> From tmp back to the project's root.
   character(len=*), parameter :: up = '../../'
   character(len=*), parameter :: nl = new_line('a')
   !> A deck's head: title, control record, one solid material set per physical surface 1, 2.
   character(len=*), parameter :: head = 'FEAP * * gmsh test'//nl//'0 0 0 2 2 4'//nl// &
      'MATErial,1'//nl//' SOLId'//nl//'  ELAStic NEOHookean 1000 0.3'//nl//'  DENSity 1'//nl//nl// &
      'MATErial,2'//nl//' SOLId'//nl//'  ELAStic NEOHookean 1000 0.3'//nl//'  DENSity 1'//nl//nl
   !> The lines that head adds (the next record is on line 13).
   integer, parameter :: head_lines = 12
   character(len=*), parameter :: tail = 'END'//nl//'BATCh'//nl//'END'//nl//'STOP'

contains

   subroutine run_gmsh_tests(s)
      type(suite_t), intent(inout) :: s
      call execute_command_line('mkdir -p '//tmp)
      call section(s, 'gmsh: the example disk_on_block.inp as read')
      call example_mesh(s)
      call section(s, 'gmsh: numbering of GMSH bodies mixed with BLOCk bodies')
      call numbering(s)
      call section(s, 'gmsh: clockwise quadrilaterals are reversed')
      call clockwise_surface(s)
      call section(s, 'gmsh: same histories as the BLOCk mesh, and from the .geo at run time')
      call same_histories(s)
      call section(s, 'gmsh: a Gmsh half and a BLOCk half joined by TIE')
      call tied_bar(s)
      call section(s, 'gmsh: an unstructured disk meshed at run time translates exactly')
      call translation(s)
      call section(s, 'gmsh: bad input')
      call bad_input(s)
      call section(s, 'gmsh: the library is loaded at run time, not linked')
      call run_time_library(s)
      call section(s, 'POLAr blocks: SHIFt centre, and edges at r = 0')
      call polar_blocks(s)
   end subroutine run_gmsh_tests

   pure logical function has(str, sub)
      character(len=*), intent(in) :: str, sub
      has = index(str, sub) > 0
   end function has

   !> Write `text` to tmp//name.
   subroutine write_file(name, text)
      character(len=*), intent(in) :: name, text
      integer :: u
      open (newunit=u, file=tmp//name, status='replace', action='write')
      write (u, '(a)') text
      close (u)
   end subroutine write_file

   !> Read deck `path`; report a failure as a failed check.
   logical function load(s, path, m) result(ok)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: path
      type(model_t), intent(out) :: m
      type(error_t), allocatable :: err
      call read_deck(path, m, err)
      ok = .not. allocated(err)
      if (ok) then
         call check(s, .true., path//' reads')
      else
         call check(s, .false., path//' reads', err%message)
      end if
   end function load

   !> Read and run deck `path` quietly with outputs tmp//stem.*; .true. on success.
   logical function run(s, path, stem) result(ok)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: path, stem
      type(model_t) :: m
      type(run_options_t) :: opts
      type(error_t), allocatable :: err
      ok = load(s, path, m)
      if (.not. ok) return
      opts%base = tmp//stem
      opts%quiet = .true.
      call run_model(m, opts, err)
      ok = .not. allocated(err)
      if (allocated(err)) then
         call check(s, .false., stem//' runs', err%message)
      else
         call check(s, .true., stem//' runs')
      end if
   end function run

   !> Area of element e (shoelace).
   pure real(wp) function area(m, e)
      type(model_t), intent(in) :: m
      integer, intent(in) :: e
      real(wp) :: x(2, 4)
      x = m%mesh%x(:, m%mesh%conn(:, e))
      area = 0.5_wp*((x(1, 3) - x(1, 1))*(x(2, 4) - x(2, 2)) - (x(2, 3) - x(2, 1))*(x(1, 4) - x(1, 2)))
   end function area

   !> The example as read: Gmsh's numbering kept, physical surfaces as regions and materials,
   !> the physical curves as oriented edge sets, the bottom fixed by PBOUndary, and the contact
   !> surfaces taken from the edge sets.
   subroutine example_mesh(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      integer :: e, k, n, rim, top, bot, nfix
      logical :: ok, used(300)
      real(wp) :: a1, a2, c(2), d1(2), d2(2)
      if (.not. load(s, ex//'disk_on_block.inp', m)) return
      associate (mesh => m%mesh)
         call check(s, mesh%nelem == 256 .and. count(mesh%region == 1) == 192 .and. &
                    count(mesh%region == 2) == 64, '192 disk and 64 block quadrilaterals, as '// &
                    'disk.geo (8 x 8 + 4 x 8 x 4) and the 16 x 4 extrusion make', itoa(mesh%nelem))
         call check(s, all(mesh%mat == mesh%region), 'physical surface t: region t, material set t')
         call check(s, mesh%nnode == 294 .and. all(mesh%x(:, 1) == [0.45_wp, 1.05_wp - 0.45_wp]), &
                    'node n is Gmsh node tag n (294 tags; tag 1 is Point(2), the square''s corner)')
         a1 = 0.0_wp
         a2 = 0.0_wp
         ok = .true.
         do e = 1, mesh%nelem
            if (area(m, e) <= 0.0_wp) ok = .false.
            if (mesh%region(e) == 1) a1 = a1 + area(m, e)
            if (mesh%region(e) == 2) a2 = a2 + area(m, e)
         end do
         call check(s, ok, 'every element counter-clockwise')
         call check_close(s, a2, 4.0_wp, 1.0e-13_wp, 'block area 4 x 1')
         ! 32 chords of the unit circle: 16 sin(pi/16); Gmsh places the rim nodes to ~1e-9
         call check_close(s, a1, 16.0_wp*sin(acos(-1.0_wp)/16.0_wp), 1.0e-7_wp, &
                          'disk area: the 32-gon inscribed in the unit circle')
         rim = find_edge_set(mesh%edge_sets, 11)
         top = find_edge_set(mesh%edge_sets, 21)
         bot = find_edge_set(mesh%edge_sets, 22)
         call check(s, size(mesh%edge_sets) == 3 .and. rim > 0 .and. top > 0 .and. bot > 0, &
                    'edge sets 11, 21, 22 from the physical curves')
         if (rim == 0 .or. top == 0 .or. bot == 0) return
         call check(s, mesh%edge_sets(rim)%nedge == 32 .and. mesh%edge_sets(top)%nedge == 16 .and. &
                    mesh%edge_sets(bot)%nedge == 16, '32 rim, 16 top and 16 bottom edges')
         call check(s, mesh%edge_sets(rim)%name == 'rim' .and. mesh%edge_sets(top)%name == 'top', &
                    'the physical names are kept')
         ok = .true.
         associate (t => mesh%edge_sets(top))
            do k = 1, t%nedge
               d1 = mesh%x(:, t%edge(1, k))
               d2 = mesh%x(:, t%edge(2, k))
               ok = ok .and. d1(2) == 0.0_wp .and. d2(2) == 0.0_wp .and. d2(1) < d1(1) .and. &
                    mesh%region(t%elem(k)) == 2 .and. t%other(k) == 0
            end do
         end associate
         call check(s, ok, 'top edges run from +x to -x: the block (below) on their left')
         ok = .true.
         c = [0.0_wp, 1.05_wp]
         associate (r => mesh%edge_sets(rim))
            do k = 1, r%nedge
               d1 = mesh%x(:, r%edge(1, k)) - c
               d2 = mesh%x(:, r%edge(2, k)) - c
               ok = ok .and. d1(1)*d2(2) - d1(2)*d2(1) > 0.0_wp .and. mesh%region(r%elem(k)) == 1 &
                    .and. abs(norm2(d1) - 1.0_wp) < 1.0e-8_wp
            end do
         end associate
         call check(s, ok, 'rim edges run counter-clockwise around the disk (disk on their left)')
         used = .false.
         do e = 1, mesh%nelem
            used(mesh%conn(:, e)) = .true.
         end do
         ok = .true.
         nfix = 0
         do n = 1, mesh%nnode
            if (.not. used(n)) cycle
            if (mesh%x(2, n) == -1.0_wp) then
               ok = ok .and. all(mesh%bc(:, n) == 1)
               nfix = nfix + 1
            else
               ok = ok .and. all(mesh%bc(:, n) == 0)
            end if
         end do
         call check(s, ok .and. nfix == 17, 'PBOUndary 22 fixes the 17 bottom nodes and no other', &
                    itoa(nfix))
         call check(s, all(m%contact%surfaces(1)%facets == mesh%edge_sets(rim)%edge) .and. &
                    all(m%contact%surfaces(2)%facets == mesh%edge_sets(top)%edge), &
                    'SURFace PHYSical takes the edge set as its segments')
      end associate
   end subroutine example_mesh

   !> GMSH with explicit node1 and elmt1 (node = node1 - 1 + tag), then GMSH with the defaults
   !> (the next free numbers); the two copies' edge sets add up.
   subroutine numbering(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      integer :: k
      logical :: ok
      call write_file('numbering.inp', head//'REGIon,3'//nl//'BLOCk'//nl//' CARTesian,2,1,0,0,2'// &
                      nl//'  1,5,0'//nl//'  2,7,0'//nl//'  3,7,1'//nl//'  4,5,1'//nl//nl// &
                      'GMSH,"'//up//ex//'disk.msh",1001,3'//nl// &
                      'GMSH,'//up//ex//'disk.msh'//nl//tail)
      if (.not. load(s, tmp//'numbering.inp', m)) return
      associate (mesh => m%mesh)
         call check(s, all(mesh%x(:, 1001) == [0.45_wp, 1.05_wp - 0.45_wp]) .and. &
                    all(mesh%x(:, 1210) == [0.45_wp, 1.05_wp - 0.45_wp]), &
                    'Gmsh tag 1 is node 1001 with node1 = 1001, then node 1210 (the next free)')
         call check(s, mesh%nnode == 1209 + 209 .and. .not. any(mesh%defined(7:1000)), &
                    'nodes 7-1000 stay undefined (209 tags from 1001, 209 more from 1210)')
         call check(s, mesh%nelem == 2 + 2*192 .and. all(mesh%region(3:386) == 1) .and. &
                    all(mesh%region(1:2) == 3), 'elements 3-194 (elmt1) and 195-386 (next free) '// &
                    'are the disks''')
         ok = .true.
         do k = 3, 194
            ok = ok .and. all(mesh%conn(:, k + 192) == mesh%conn(:, k) + 209)
         end do
         call check(s, ok, 'the two copies have the same element order, nodes 209 apart')
         k = find_edge_set(mesh%edge_sets, 11)
         call check(s, k > 0, 'edge set 11 exists')
         if (k == 0) return
         call check(s, mesh%edge_sets(k)%nedge == 64, 'both copies'' rims are in edge set 11')
      end associate
   end subroutine numbering

   !> A surface whose curve loop runs clockwise: Gmsh's quadrilaterals come clockwise (negative
   !> area), exic reverses them, and the bottom curve's edges run in +x with the square above.
   subroutine clockwise_surface(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      integer :: e, k
      real(wp) :: total
      logical :: ok
      call write_file('cw.geo', 'Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; '// &
                      'Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};'//nl// &
                      'Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};'//nl// &
                      'Curve Loop(1) = {-4, -3, -2, -1}; Plane Surface(1) = {1};'//nl// &
                      'Transfinite Curve{1:4} = 3; Transfinite Surface{1}; Recombine Surface{1};'// &
                      nl//'Physical Surface(1) = {1}; Physical Curve(5) = {1};')
      call write_file('cw.inp', head//'GMSH,cw.geo'//nl//tail)
      if (.not. load(s, tmp//'cw.inp', m)) return
      total = 0.0_wp
      ok = m%mesh%nelem == 4
      do e = 1, m%mesh%nelem
         ok = ok .and. area(m, e) > 0.0_wp
         total = total + area(m, e)
      end do
      call check(s, ok, 'the 4 clockwise Gmsh quadrilaterals are made counter-clockwise')
      call check_close(s, total, 1.0_wp, 1.0e-11_wp, 'their areas sum to the unit square')
      k = find_edge_set(m%mesh%edge_sets, 5)
      ok = k > 0
      if (ok) then
         associate (es => m%mesh%edge_sets(k), x => m%mesh%x)
            ok = es%nedge == 2
            do e = 1, es%nedge
               ok = ok .and. x(1, es%edge(2, e)) > x(1, es%edge(1, e)) .and. &
                    x(2, es%edge(1, e)) == 0.0_wp .and. x(2, es%edge(2, e)) == 0.0_wp
            end do
         end associate
      end if
      call check(s, ok, 'the bottom curve''s 2 edges run in +x (the square on their left)')
   end subroutine clockwise_surface

   !> Largest |a - b| over the rows, per column, relative to the column's largest |a| or to
   !> `floor` when that is larger; a penetration column (residual gaps of about 1e-7, closed
   !> again every step) is compared with the length scale 1. The tables must have the same shape
   !> and times.
   subroutine compare_tables(s, fa, fb, tol, floor, what, pen_column)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: fa, fb, what
      real(wp), intent(in) :: tol, floor
      character(len=*), intent(in), optional :: pen_column
      character(len=64), allocatable :: na(:), nb(:)
      real(wp), allocatable :: a(:, :), b(:, :)
      real(wp) :: worst, d, scale
      integer :: k, kp
      character(len=:), allocatable :: at
      call read_table(fa, na, a)
      call read_table(fb, nb, b)
      if (any(shape(a) /= shape(b))) then
         call check(s, .false., what//': same number of rows and columns', &
                    itoa(size(a, 2))//' x '//itoa(size(a, 1))//' vs '//itoa(size(b, 2))//' x '// &
                    itoa(size(b, 1)))
         return
      end if
      kp = 0
      if (present(pen_column)) kp = column(na, pen_column)
      worst = 0.0_wp
      at = ''
      do k = 1, size(a, 1)
         scale = max(maxval(abs(a(k, :))), floor)
         ! residual penetrations (about 1e-7) against the length scale (1)
         if (k == kp .or. scale == 0.0_wp) scale = 1.0_wp
         d = maxval(abs(a(k, :) - b(k, :)))/scale
         if (d > worst) then
            worst = d
            at = trim(na(k))
         end if
      end do
      call check(s, worst <= tol .and. size(a, 2) > 10, what//' (largest difference '// &
                 rtoa(worst, '(es9.2)')//' of the column''s largest value, in '//at//')')
   end subroutine compare_tables

   !> disk_on_block.inp (all Gmsh) against disk_on_block_blocks.inp (the block as a BLOCk) and
   !> against the same deck meshing disk_on_block.geo at run time.
   subroutine same_histories(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: text
      character(len=4096) :: line
      integer :: u, ios
      if (.not. run(s, ex//'disk_on_block.inp', 'dob_gmsh')) return
      if (.not. run(s, ex//'disk_on_block_blocks.inp', 'dob_blocks')) return
      call compare_tables(s, tmp//'dob_gmsh.his', tmp//'dob_blocks.his', 1.0e-12_wp, 0.0_wp, &
                          'histories of the Gmsh block and the BLOCk agree to 1e-12', 'cont(p1,5)')
      ! energies and momenta are of order 1: momentum x (zero up to round-off) against 1
      call compare_tables(s, tmp//'dob_gmsh.ene', tmp//'dob_blocks.ene', 1.0e-12_wp, 1.0_wp, &
                          'energies and momenta agree to 1e-12')
      ! the same deck with the .geo, written under tmp with its paths made relative to it
      text = ''
      open (newunit=u, file=ex//'disk_on_block.inp', status='old', action='read')
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (trim(line) == 'GMSH,disk_on_block.msh') line = 'GMSH,'//up//ex//'disk_on_block.geo'
         if (index(line, 'INCLude,') == 1) line = 'INCLude,'//up//ex//trim(line(9:))
         text = text//trim(line)//nl
      end do
      close (u)
      call check(s, has(text, 'GMSH,'//up//ex//'disk_on_block.geo'), 'the .geo variant is made')
      call write_file('dob_geo.inp', text)
      if (run(s, tmp//'dob_geo.inp', 'dob_geo')) then
         call compare_tables(s, tmp//'dob_gmsh.his', tmp//'dob_geo.his', 1.0e-12_wp, 0.0_wp, &
                             'disk_on_block.geo meshed at run time: histories agree to 1e-12', &
                             'cont(p1,5)')
      end if
   end subroutine same_histories

   !> A bar 4 x 1 at speed 1 against a rigid wall: its left half from a .geo meshed at run time
   !> (extruded, 8 x 4), its right half a BLOCk, joined by TIE; the same bar as one BLOCk.
   subroutine tied_bar(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: common, wall, batch
      type(model_t) :: m
      integer :: used
      logical :: u(300)
      integer :: e
      call write_file('half.geo', 'Point(1) = {0, 0, 0};'//nl// &
                      'b[] = Extrude {2, 0, 0} { Point{1}; Layers{8}; };'//nl// &
                      's[] = Extrude {0, 1, 0} { Curve{b[1]}; Layers{4}; Recombine; };'//nl// &
                      'Physical Surface(1) = {s[1]};')
      wall = 'MATErial,3'//nl//' RIGId'//nl//'  DENSity 1'//nl//nl//'REGIon,3'//nl//'BLOCk'//nl// &
             ' CARTesian,1,1,0,0,3'//nl//'  1,4,-1'//nl//'  2,5,-1'//nl//'  3,5,2'//nl//'  4,4,2'// &
             nl//nl//'INITial,VELOcity'//nl//' REGIon,1,1,0'//nl//nl//'CONTact'//nl// &
             ' SURFace,1'//nl//'  REGIon,1'//nl//' SURFace,2'//nl//'  REGIon,3'//nl// &
             ' PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl//nl//'END'//nl
      batch = 'BATCh'//nl//' DT,CFL,0.9'//nl//' TPLOt,,1'//nl//' LOOP,,100000'//nl// &
              '  TIME,,0.1'//nl//'  FORM,EXPLicit'//nl//' NEXT'//nl//'END'//nl// &
              ' disp,,1,4,0.5'//nl//' velo,,1,4,0.5'//nl//' velo,,1,2,0.5'//nl// &
              ' acce,,1,2,0.5'//nl//' stre,,1,1.9,0.4'//nl//' cont,1,1'//nl//' mome,1,1'//nl// &
              nl//'STOP'
      common = 'REGIon,1'//nl//'BLOCk'//nl//' CARTesian,8,4,0,0,1'//nl//'  1,2,0'//nl//'  2,4,0'// &
               nl//'  3,4,1'//nl//'  4,2,1'//nl//nl
      call write_file('bar_tied.inp', head//'GMSH,half.geo'//nl//common//wall//'TIE,REGIon,1,1'// &
                      nl//batch)
      call write_file('bar_block.inp', head//'REGIon,1'//nl//'BLOCk'//nl// &
                      ' CARTesian,16,4,0,0,1'//nl//'  1,0,0'//nl//'  2,4,0'//nl//'  3,4,1'//nl// &
                      '  4,0,1'//nl//nl//wall//batch)
      if (.not. load(s, tmp//'bar_tied.inp', m)) return
      u = .false.
      do e = 1, m%mesh%nelem
         u(m%mesh%conn(:, e)) = .true.
      end do
      used = count(u)
      call check(s, used == 17*5 + 4, 'TIE merges the 5 shared nodes: 85 bar nodes + 4 wall nodes', &
                 itoa(used))
      if (.not. run(s, tmp//'bar_tied.inp', 'bar_tied')) return
      if (.not. run(s, tmp//'bar_block.inp', 'bar_block')) return
      call compare_tables(s, tmp//'bar_tied.his', tmp//'bar_block.his', 1.0e-12_wp, 0.0_wp, &
                          'tied Gmsh + BLOCk bar and one-BLOCk bar: histories agree to 1e-12')
   end subroutine tied_bar

   !> A disk of radius 1 meshed at run time by Gmsh's default (Frontal-Delaunay) algorithm with
   !> every triangle recombined, flying at (0.3, -0.4) with nothing to hit: every node moves v t.
   subroutine translation(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: his(:, :)
      real(wp) :: t, worst
      integer :: k, j
      call write_file('free_disk.geo', 'h = 0.25;'//nl//'Point(1) = {0, 0, 0, h};'//nl// &
                      'Point(2) = {1, 0, 0, h}; Point(3) = {0, 1, 0, h};'//nl// &
                      'Point(4) = {-1, 0, 0, h}; Point(5) = {0, -1, 0, h};'//nl// &
                      'Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5};'//nl// &
                      'Circle(4) = {5, 1, 2};'//nl//'Curve Loop(1) = {1, 2, 3, 4};'//nl// &
                      'Plane Surface(1) = {1};'//nl//'Mesh.RecombineAll = 1;'//nl// &
                      'Physical Surface(1) = {1};')
      call write_file('free_disk.inp', head//'GMSH,free_disk.geo'//nl//'INITial,VELOcity'//nl// &
                      ' MATErial,1,0.3,-0.4'//nl//nl//'END'//nl//'BATCh'//nl//' DT,CFL,0.9'//nl// &
                      ' TPLOt,,1'//nl//' LOOP,,100000'//nl//'  TIME,,0.2'//nl//'  FORM,EXPLicit'// &
                      nl//' NEXT'//nl//'END'//nl//' disp,,1,1,0'//nl//' disp,,2,1,0'//nl// &
                      ' disp,,1,0,0'//nl//' disp,,2,0,0'//nl//' disp,,1,-0.7,0.7'//nl// &
                      ' disp,,2,-0.7,0.7'//nl//nl//'STOP')
      if (.not. load(s, tmp//'free_disk.inp', m)) return
      call check(s, m%mesh%nelem > 40, 'the disk is meshed in quadrilaterals only', &
                 itoa(m%mesh%nelem)//' elements')
      if (.not. run(s, tmp//'free_disk.inp', 'free_disk')) return
      call read_table(tmp//'free_disk.his', names, his)
      worst = 0.0_wp
      do j = 1, size(his, 2)
         t = his(1, j)
         do k = 2, 6, 2
            worst = max(worst, abs(his(k, j) - 0.3_wp*t), abs(his(k + 1, j) + 0.4_wp*t))
         end do
      end do
      call check(s, worst <= 1.0e-13_wp .and. his(1, size(his, 2)) == 0.2_wp, &
                 'u = v t at three nodes until t = 0.2 (largest error '//rtoa(worst, '(es9.2)')//')')
   end subroutine translation

   !> Every bad input is an error naming file:line and what was expected.
   subroutine bad_input(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: dob = up//ex//'disk_on_block.msh'
      character(len=*), parameter :: data = up//'test/data/gmsh/'
      integer, parameter :: g = head_lines + 1
      call write_file('tri.geo', 'Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0};'// &
                      nl//'Point(4) = {0, 1, 0}; Line(1) = {1, 2}; Line(2) = {2, 3}; '// &
                      'Line(3) = {3, 4}; Line(4) = {4, 1};'//nl//'Curve Loop(1) = {1, 2, 3, 4}; '// &
                      'Plane Surface(1) = {1};'//nl//'Transfinite Curve{1:4} = 4; '// &
                      'Transfinite Surface{1};'//nl//'Physical Surface(1) = {1};')
      call write_file('inner.geo', 'Point(1) = {0, 0, 0};'//nl// &
                      'b[] = Extrude {1, 0, 0} { Point{1}; Layers{2}; };'//nl// &
                      's[] = Extrude {0, 1, 0} { Curve{b[1]}; Layers{2}; Recombine; };'//nl// &
                      't[] = Extrude {0, 1, 0} { Curve{s[0]}; Layers{2}; Recombine; };'//nl// &
                      'Physical Surface(1) = {s[1], t[1]};'//nl//'Physical Curve(7) = {s[0]};')
      call bad('g01', head//'GMSH,nothere.msh'//nl//tail, g, 'cannot find file')
      call bad('g02', head//'GMSH,'//data//'triangles.msh'//nl//tail, g, &
               '8 3-node triangles (and 0 4-node quadrilaterals)')
      call bad('g02', head//'GMSH,'//data//'triangles.msh'//nl//tail, g, 'Mesh.RecombineAll = 1')
      call bad('g03', head//'GMSH,tri.geo'//nl//tail, g, '18 3-node triangles')
      call bad('g04', head//'GMSH,'//data//'no_physical.msh'//nl//tail, g, 'no Physical Surface')
      call bad('g05', head//'GMSH,'//data//'second_order.msh'//nl//tail, g, 'Mesh.ElementOrder = 1')
      call bad('g06', head//'GMSH,'//dob//nl//'PBOUndary'//nl//' 22,1,1'//nl//' 99,1,1'//nl//nl// &
               tail, g + 3, 'PBOUndary: physical curve 99 is not in the mesh')
      call bad('g07', head//'GMSH,'//dob//nl//'CONTact'//nl//' SURFace,1'//nl//'  PHYSical,99'// &
               nl//' SURFace,2'//nl//'  REGIon,2'//nl//' PAIR,1,NTOS,1,2'//nl//'END CONTact'//nl// &
               tail, g + 3, 'physical curve 99 is not in the mesh')
      call bad('g08', head//'GMSH,inner.geo'//nl//'CONTact'//nl//' SURFace,1'//nl//'  PHYSical,7'// &
               nl//' PAIR,1,SELF,1'//nl//'END CONTact'//nl//tail, g + 3, &
               'has 2 of its 2 edges between two elements')
      call bad('g09', 'FEAP * * x'//nl//'0 0 0 2 2 4'//nl//'MATErial,1'//nl//' SOLId'//nl// &
               '  ELAStic NEOHookean 1000 0.3'//nl//'  DENSity 1'//nl//nl//'GMSH,'//dob//nl//tail, &
               8, 'Gmsh Physical Surface 2 uses material set 2, which has no MATErial set: '// &
               'expected MATErial,2')
      call bad('g10', head//'BLOCk'//nl//' CARTesian,1,1,0,0,1'//nl//'  1,5,0'//nl//'  2,6,0'// &
               nl//'  3,6,1'//nl//'  4,5,1'//nl//nl//'GMSH,'//dob//',3'//nl//tail, g + 7, &
               'node 3 (Gmsh node 1) is already defined at')
      call bad('g11', head//'GMSH'//nl//tail, g, 'expected a file name')
      call bad('g12', head//'GMSH,'//dob//',-1'//nl//tail, g, 'expected node1 >= 0')
      call bad('g13', head//'GMSH,'//dob//nl//'PBOUndary,21,1.5'//nl//tail, g + 1, &
               'PBOUndary record c, c1, c2')
      call bad('g14', head//'GMSH,'//dob//nl//'CONTact'//nl//' SURFace,1'//nl//'  PHYSical,0'// &
               nl//' PAIR,1,SELF,1'//nl//'END CONTact'//nl//tail, g + 3, 'expected a physical curve')
      call bad('g15', head//'GMSH,half.geo,0,0'//nl//'GMSH,half.geo,0,1'//nl//tail, g + 1, &
               'element 1 is already defined at')
      call write_file('line.geo', 'Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5};'//nl// &
                      'Line(1) = {1, 2};'//nl//'Physical Curve(1) = {1};')
      call bad('g16', head//'GMSH,line.geo'//nl//tail, g, 'no 4-node quadrilaterals')
   contains
      subroutine bad(tag, text, line, word)
         character(len=*), intent(in) :: tag, text, word
         integer, intent(in) :: line
         type(model_t) :: m
         type(error_t), allocatable :: err
         character(len=:), allocatable :: at
         call write_file(tag//'.inp', text)
         call read_deck(tmp//tag//'.inp', m, err)
         at = tmp//tag//'.inp:'//itoa(line)//':'
         if (.not. allocated(err)) then
            call check(s, .false., tag//': error "'//word//'"', 'no error')
            return
         end if
         call check(s, has(err%message, at) .and. has(err%message, word), &
                    tag//': '//at//' ... '//word, err%message)
      end subroutine bad
   end subroutine bad_input

   !> exic_input_gmsh_library: libraries that do not load give an error naming each with dlerror's text
   !> (the deck reader puts the GMSH record's file:line before it, as for the errors of
   !> bad_input); the first name tried is the soname a link with -lgmsh would record; the exic
   !> program needs no Gmsh library to start (none in its ldd list), and reads Gmsh meshes
   !> (the other sections of this suite).
   subroutine run_time_library(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: missing(2) = [character(len=24) :: 'libexic-no-gmsh.so.0', &
                                                   '/nonexistent/libgmsh.so']
      type(c_ptr) :: handle
      character(len=:), allocatable :: opened, soname, needed
      type(error_t), allocatable :: err
      character(len=4096) :: argv0
      character(len=:), allocatable :: exic
      logical :: exists
      integer :: code
      call gmsh_library_open(missing, handle, opened, err)
      if (.not. allocated(err)) then
         call check(s, .false., 'libraries that do not exist: an error', 'no error')
      else
         call check(s, .not. c_associated(handle) .and. has(err%message, 'the Gmsh library '// &
                    'could not be loaded') .and. has(err%message, 'libexic-no-gmsh.so.0: '// &
                    'libexic-no-gmsh.so.0: cannot open shared object file') .and. &
                    has(err%message, '/nonexistent/libgmsh.so: /nonexistent/libgmsh.so: cannot '// &
                    'open shared object file') .and. has(err%message, 'libgmsh-dev'), &
                    'libraries that do not exist: both names with dlerror''s text, and what to '// &
                    'install', err%message)
      end if
      if (.not. have_command('objdump')) then
         call skip(s, 'the first library name is the soname of libgmsh.so', 'objdump', 1)
      else
         call execute_command_line('printf %s "$(objdump -p "$(gfortran -print-file-name='// &
                                   'libgmsh.so)" | sed -n "s/^ *SONAME *//p")" > '//tmp// &
                                   'soname.txt', exitstat=code)
         soname = file_text(tmp//'soname.txt')
         call check(s, code == 0 .and. trim(GMSH_LIBRARIES(1)) == soname, 'the first library '// &
                    'name tried, '//trim(GMSH_LIBRARIES(1))//', is the SONAME of the libgmsh.so '// &
                    'the linker finds', soname)
      end if
      call get_command_argument(0, argv0)
      exic = argv0(1:index(argv0, '/', back=.true.))//'../app/exic'
      inquire (file=exic, exist=exists)
      if (.not. exists .or. .not. have_command('ldd')) then
         call skip(s, 'the exic program loads no Gmsh library at start', 'the exic program '// &
                   'next to the tests, and ldd', 1)
         return
      end if
      call execute_command_line('ldd '//exic//' > '//tmp//'ldd.txt', exitstat=code)
      needed = file_text(tmp//'ldd.txt')
      call check(s, code == 0 .and. has(needed, 'libc.so') .and. .not. has(needed, 'gmsh'), &
                 'the exic program loads no Gmsh library at start (ldd)', needed)
   end subroutine run_time_library

   !> POLAr blocks about a SHIFt centre (FEAP's record form and the one-record form), and the
   !> errors for an edge at r = 0 and for collapsed elements of other origins.
   subroutine polar_blocks(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: ring
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: n, k
      real(wp) :: worst, r, th
      integer, parameter :: g = head_lines + 1
      ring = 'BLOCk'//nl//' POLAr,4,6,0,0,1'//nl//'  1,1,0'//nl//'  2,2,0'//nl//'  3,2,90'//nl// &
             '  4,1,90'//nl//nl
      do k = 1, 2
         if (k == 1) then
            call write_file('shift.inp', head//'SHIFt'//nl//' 3,-4'//nl//nl//ring//tail)
         else
            call write_file('shift.inp', head//'SHIFt,3,-4'//nl//ring//tail)
         end if
         call read_deck(tmp//'shift.inp', m, err)
         if (allocated(err)) then
            call check(s, .false., 'POLAr ring about (3, -4) reads', err%message)
            cycle
         end if
         worst = 0.0_wp
         do n = 1, m%mesh%nnode
            ! node (i, j) = 1 + j (nr + 1) + i: r = 1 + i/4, theta = 15 j degrees
            r = 1.0_wp + real(mod(n - 1, 5), wp)/4.0_wp
            th = acos(-1.0_wp)/180.0_wp*15.0_wp*real((n - 1)/5, wp)
            worst = max(worst, norm2(m%mesh%x(:, n) - [3.0_wp + r*cos(th), -4.0_wp + r*sin(th)]))
         end do
         if (k == 1) then
            call check(s, worst <= 1.0e-14_wp, 'SHIFt + record 3,-4: nodes at (3, -4) + r (cos, sin)')
         else
            call check(s, worst <= 1.0e-14_wp, 'SHIFt,3,-4 on one record: the same nodes')
         end if
      end do
      call bad('p01', head//'SHIFt,3,-4'//nl//'BLOCk'//nl//' POLAr,4,6,0,0,1'//nl//'  1,0,0'//nl// &
               '  2,2,0'//nl//'  3,2,90'//nl//'  4,0,90'//nl//nl//tail, g + 1, &
               'edge 4-1 (master nodes 4 and 1, i = 0): a POLAr edge at r = 0 collapses to the '// &
               'centre (3.0000000, -4.0000000)')
      call bad('p02', head//'BLOCk'//nl//' CARTesian,2,2,0,0,1'//nl//'  1,0,0'//nl//'  2,1,0'//nl// &
               '  3,0.5,1'//nl//'  4,0.5,1'//nl//nl//tail, g, &
               'on its edge 3-4 (master nodes 3 and 4, j = ns): expected four distinct corners')
      call bad('p03', head//'COORdinates'//nl//' 1,0,0,0'//nl//' 2,0,1,0'//nl//' 3,0,0,1'//nl// &
               ' 4,0,0,1'//nl//nl//'ELEMents'//nl//' 1,0,1,1,2,3,4'//nl//nl//tail, g + 7, &
               'nodes 3 and 4 at (0.0000000, 1.0000000): expected four distinct corners')
      call bad('p04', head//'SHIFt'//nl//nl//tail, g + 1, 'SHIFt: expected the record x0, y0')
   contains
      subroutine bad(tag, text, line, word)
         character(len=*), intent(in) :: tag, text, word
         integer, intent(in) :: line
         character(len=:), allocatable :: at
         call write_file(tag//'.inp', text)
         call read_deck(tmp//tag//'.inp', m, err)
         at = tmp//tag//'.inp:'//itoa(line)//':'
         if (.not. allocated(err)) then
            call check(s, .false., tag//': error "'//word//'"', 'no error')
            return
         end if
         call check(s, has(err%message, at) .and. has(err%message, word), &
                    tag//': '//at//' ... '//word, err%message)
      end subroutine bad
   end subroutine polar_blocks

end module test_gmsh
