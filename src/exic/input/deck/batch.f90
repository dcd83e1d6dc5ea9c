!> The solution program of a deck (BATCh ... END, input language section 5) and the data read
!> after its END (TPLOt requests, INITial node-vector records), in the order of the commands.
!>
!> Each command is stored as `name, option, v(1:3)` with name and option the first 4 characters
!> in lower case. Normalised forms:
!> - `tran` option `expl` or `cent`;
!> - `dt` option '' (v(1) = dt) or `cfl` (v(1) = c, 0.9 when blank); `DT dt` (a number in the
!>   option field) is read as `DT,,dt` with a warning;
!> - `loop` v(1) = n, jump = index of its `next`; `next` jump = index of its `loop`;
!> - `time` v(1) = tmax (0: none); `form` option `expl`; `tplo` v(1) = inc (>= 1);
!> - `init` option `rate`, `velo`, `regi` or `mate`: every INITial command carries
!>   data(2, nnode) and given(nnode), read after END (rate/velo) or computed (regi/mate:
!>   v(1) = r or m, v(2:3) = vx, vy; every node of those elements is given);
!> - `outp` option `hdf5`, v(1) = dt_out; `prin` option `ener`, v(1) = n;
!> - [ext] `chec` option `ener`, v(1) = warn, v(2) = stop (energy guard limits); option `pene`,
!>   v(1) = fraction (geometric penetration warning limit);
!> - `prop` v(1) = n1, v(2) = n2 (>= n1): proportional functions read after END (deck_loads);
!> - `save` v(1) = dt (0: at the end only): restart files; RESTart,file is not a command of the
!>   program but sets model%restart_file.
module exic_input_deck_batch
   use exic_base_kinds, only: wp
   use exic_base_constants, only: DEFAULT_CFL, ENERGY_WARN, ENERGY_STOP, PENETRATION_WARN
   use exic_base_error, only: error_t, make_error
   use exic_input_deck_grow, only: grow
   use exic_mesh_mesh, only: mesh_t
   use exic_model_model, only: model_t
   use exic_model_program, only: MAX_LOOP_DEPTH, command_t, request_t, REQ_DISP, REQ_VELO, REQ_ACCE, REQ_STRE, &
                              REQ_REAC, REQ_CONT, REQ_MOME, REQ_REAC_REGION, REQ_REAC_SET, REQ_RIGI
   use exic_material_material, only: MAT_RIGID
   use exic_mesh_edge_set, only: find_edge_set, edge_set_ids
   use exic_input_deck_loads, only: read_prop_data
   use exic_input_deck_records, only: keyword_is, keyword_key
   use exic_input_deck_expression, only: evaluate
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: next_in_set, reader_t, next_nonblank, field, word, has_field, &
                             real_field, int_field, fail, warn, warn_at, where, unknown_keyword, &
                             itoa, check_command, check_data_record, is_command
   use exic_input_deck_mesh, only: genvec_t, node_record
   use exic_input_deck_finish, only: used_nodes, nearest_node
   implicit none
   private

   public :: read_batch, read_batch_data

   character(len=12), parameter :: commands(15) = [character(len=12) :: 'TRANsient', 'DT', &
                                                   'LOOP', 'NEXT', 'TIME', 'FORM', 'TPLOt', &
                                                   'INITial', 'OUTPut', 'PRINt', 'CHECk', 'END', &
                                                   'PROPortional', 'SAVE', 'RESTart']
   !> Value fields (after the option) each command uses, in the order of `commands`; a value
   !> beyond them is reported by the reader as not used (INITial,RATE|VELOcity take none).
   integer, parameter :: nvalues(15) = [0, 1, 1, 0, 1, 0, 1, 3, 1, 1, 2, 0, 2, 1, 0]
   character(len=12), parameter :: requests(10) = [character(len=12) :: 'disp', 'velo', 'acce', &
                                                   'stre', 'reac', 'cont', 'mome', 'show', 'ener', &
                                                   'rigi']

contains

   !> Read the commands after the BATCh record `ib` up to END into model%program.
   subroutine read_batch(rd, ib, model, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: ib
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      type(command_t), allocatable :: prog(:)
      integer :: i, n, depth, stack(MAX_LOOP_DEPTH)
      type(command_t) :: c
      logical :: cut

      allocate (prog(16))
      n = 0
      depth = 0
      do
         call next_nonblank(rd, i)
         if (i == 0) then
            call fail(rd, i, 'BATCh opened at '//where(rd, ib)//' is not closed: expected END', err)
            return
         end if
         call check_command(rd, i, cut)
         if (keyword_is(word(rd, i, 1), 'end')) exit
         if (keyword_is(word(rd, i, 1), 'rest')) then
            ! RESTart,file: the whole run continues from that restart file (not a step of the
            ! program: the position in the program is the file's)
            if (len(field(rd, i, 2)) == 0) then
               call fail(rd, i, 'RESTart,file: expected the name of a restart file', err)
               return
            end if
            model%restart_file = field(rd, i, 2)
            cycle
         end if
         call parse_command(rd, i, model, c, err)
         if (allocated(err)) return
         call grow(prog, n + 1)
         n = n + 1
         prog(n) = c
         if (c%name == 'loop') then
            if (depth == MAX_LOOP_DEPTH) then
               call fail(rd, i, 'LOOP nested deeper than 8: expected at most 8 open LOOPs', err)
               return
            end if
            depth = depth + 1
            stack(depth) = n
         else if (c%name == 'next') then
            if (depth == 0) then
               call fail(rd, i, 'NEXT without LOOP: expected a LOOP before it', err)
               return
            end if
            prog(n)%jump = stack(depth)
            prog(stack(depth))%jump = n
            call loop_without_time(rd, prog(stack(depth):n))
            depth = depth - 1
         end if
      end do
      if (depth > 0) then
         call make_error(err, prog(stack(depth))%where//': LOOP without NEXT: expected NEXT '// &
                         'before the END at '//where(rd, i))
         return
      end if
      model%program = prog(1:n)
   end subroutine read_batch

   !> A warning for a LOOP (body(1), closed by body(size)) that steps (FORM) with no TIME anywhere
   !> in it: nothing ends it before its count, and only TIME writes history rows and fields, so
   !> it runs all its steps silently (a run of 10^7 steps that looks like a hang).
   subroutine loop_without_time(rd, body)
      type(reader_t), intent(inout) :: rd
      type(command_t), intent(in) :: body(:)
      if (.not. any(body%name == 'form') .or. any(body%name == 'time')) return
      call warn_at(rd, body(1)%where, 'LOOP,,'//itoa(nint(body(1)%v(1)))//' steps FORM with no TIME '// &
                   'in it: it runs all its steps, with no end time, and writes no history rows or '// &
                   'fields while it runs (TIME,,tmax writes them and leaves the loop at tmax)')
   end subroutine loop_without_time

   !> One solution command.
   subroutine parse_command(rd, i, model, c, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(model_t), intent(in) :: model
      type(command_t), intent(out) :: c
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: w, opt
      integer :: k, j, nv

      w = word(rd, i, 1)
      opt = word(rd, i, 2)
      c%where = where(rd, i)
      do k = 1, size(commands)
         if (keyword_is(w, commands(k))) exit
      end do
      if (k > size(commands)) then
         call unknown_keyword(rd, i, 'solution command', field(rd, i, 1), commands, err)
         return
      end if
      c%name = keyword_key(commands(k))
      c%option = opt
      nv = nvalues(k)
      if (c%name == 'init' .and. (keyword_is(opt, 'rate') .or. keyword_is(opt, 'velo'))) nv = 0
      do j = 1, nv
         call real_field(rd, i, 2 + j, trim(commands(k))//',option,v1,v2,v3', c%v(j), err)
         if (allocated(err)) return
      end do
      select case (c%name)
      case ('tran')
         if (keyword_is(opt, 'expl') .or. keyword_is(opt, 'cent')) then
            c%option = keyword_key(opt)
         else
            call fail(rd, i, 'TRANsient,'//field(rd, i, 2)//' is not supported: expected '// &
                      'TRANsient,EXPLicit or TRANsient,CENTral', err)
         end if
      case ('dt')
         call parse_dt(rd, i, c, err)
      case ('loop')
         call positive_int(rd, i, c%v(1), 'LOOP,,n', err)
      case ('next')
         continue
      case ('time')
         if (len(opt) > 0) then
            call fail(rd, i, 'TIME,'//field(rd, i, 2)//' is not supported: expected TIME or '// &
                      'TIME,,tmax', err)
         else if (c%v(1) < 0.0_wp) then
            call fail(rd, i, 'TIME,,tmax: expected tmax >= 0', err)
         end if
      case ('form')
         if (len(opt) == 0 .or. keyword_is(opt, 'expl')) then
            c%option = 'expl'
         else
            call fail(rd, i, 'FORM,'//field(rd, i, 2)//' is not supported: expected FORM,EXPLicit', err)
         end if
      case ('tplo')
         if (c%v(1) == 0.0_wp) c%v(1) = 1.0_wp
         call positive_int(rd, i, c%v(1), 'TPLOt,,inc', err)
      case ('init')
         call parse_init(rd, i, model, c, err)
      case ('outp')
         if (.not. keyword_is(opt, 'hdf5')) then
            call fail(rd, i, 'OUTPut,'//field(rd, i, 2)//' is not supported: expected '// &
                      'OUTPut,HDF5,dt_out', err)
         else if (.not. (c%v(1) > 0.0_wp)) then
            call fail(rd, i, 'OUTPut,HDF5,dt_out: expected dt_out > 0', err)
         else
            c%option = 'hdf5'
         end if
      case ('chec')
         call parse_check(rd, i, c, err)
      case ('save')
         if (len(opt) > 0) then
            call fail(rd, i, 'SAVE,'//field(rd, i, 2)//' is not supported: expected SAVE or SAVE,,dt', err)
         else if (c%v(1) < 0.0_wp) then
            call fail(rd, i, 'SAVE,,dt: expected dt >= 0 (0: only at the end)', err)
         end if
      case ('prop')
         call parse_prop(rd, i, c, err)
      case ('prin')
         if (.not. keyword_is(opt, 'ener')) then
            call fail(rd, i, 'PRINt,'//field(rd, i, 2)//' is not supported: expected PRINt,ENERgy,n', err)
         else
            c%option = 'ener'
            call positive_int(rd, i, c%v(1), 'PRINt,ENERgy,n', err)
         end if
      end select
   end subroutine parse_command

   !> [ext] CHECk,ENERgy,warn,stop: the energy guard's limits as fractions of the energy put in
   !> (blank: ENERGY_WARN, ENERGY_STOP of src/exic/base/constants.f90); 0 < warn <= stop.
   !> [ext] CHECk,PENEtration,fraction: the depth, in element edges, past which the geometric
   !> penetration check warns (blank: PENETRATION_WARN); fraction > 0.
   subroutine parse_check(rd, i, c, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      type(command_t), intent(inout) :: c
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: opts(2) = [character(len=12) :: 'ENERgy', 'PENEtration']
      if (keyword_is(c%option, 'pene')) then
         c%option = 'pene'
         if (.not. has_field(rd, i, 3)) c%v(1) = PENETRATION_WARN
         if (.not. (c%v(1) > 0.0_wp .and. c%v(1) < huge(1.0_wp))) &
            call fail(rd, i, 'CHECk,PENEtration,fraction = '//rtoa(c%v(1), SHORT_REAL)//': expected fraction > 0', err)
         if (has_field(rd, i, 4)) call fail(rd, i, 'CHECk,PENEtration,fraction takes one value; the fourth '// &
                                            'field '//field(rd, i, 4)//' is not used', err)
         return
      end if
      if (.not. keyword_is(c%option, 'ener')) then
         call unknown_keyword(rd, i, 'CHECk option', field(rd, i, 2), opts, err)
         return
      end if
      c%option = 'ener'
      if (.not. has_field(rd, i, 3)) c%v(1) = ENERGY_WARN
      if (.not. has_field(rd, i, 4)) c%v(2) = ENERGY_STOP
      if (.not. (c%v(1) > 0.0_wp .and. c%v(2) >= c%v(1) .and. c%v(2) < huge(1.0_wp))) &
         call fail(rd, i, 'CHECk,ENERgy,warn,stop = '//rtoa(c%v(1), SHORT_REAL)//', '//rtoa(c%v(2), SHORT_REAL)// &
                   ': expected 0 < warn <= stop', err)
      if (has_field(rd, i, 5)) call fail(rd, i, 'CHECk,ENERgy,warn,stop takes two values; the fifth field '// &
                                         field(rd, i, 5)//' is not used', err)
   end subroutine parse_check

   !> PROPortional,,n1[,n2]: functions n1..n2 (n2 blank or 0: n1 alone), read after END.
   subroutine parse_prop(rd, i, c, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      type(command_t), intent(inout) :: c
      type(error_t), allocatable, intent(out) :: err
      if (len_trim(c%option) > 0) then
         call fail(rd, i, 'PROPortional,'//field(rd, i, 2)//': expected PROPortional,,n1[,n2] (the '// &
                   'function numbers in fields 3 and 4, the second field empty)', err)
         return
      end if
      call positive_int(rd, i, c%v(1), 'PROPortional,,n1,n2: n1', err)
      if (allocated(err)) return
      if (c%v(2) == 0.0_wp) c%v(2) = c%v(1)
      call positive_int(rd, i, c%v(2), 'PROPortional,,n1,n2: n2', err)
      if (allocated(err)) return
      if (c%v(2) < c%v(1) .or. c%v(2) > 1000.0_wp) &
         call fail(rd, i, 'PROPortional,,n1,n2 = '//itoa(nint(c%v(1)))//', '//itoa(nint(c%v(2)))// &
                   ': expected n1 <= n2 <= 1000', err)
   end subroutine parse_prop

   !> v must be an integer >= 1.
   subroutine positive_int(rd, i, v, what, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      real(wp), intent(in) :: v
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: err
      if (v < 1.0_wp .or. v /= anint(v) .or. v > 2.0e9_wp) &
         call fail(rd, i, what//' = '//rtoa(v, SHORT_REAL)//': expected an integer >= 1', err)
   end subroutine positive_int

   !> DT,,dt | DT,CFL,c | DT dt (warning).
   subroutine parse_dt(rd, i, c, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(command_t), intent(inout) :: c
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: opts(1) = [character(len=12) :: 'CFL']
      type(error_t), allocatable :: e
      real(wp) :: v
      if (keyword_is(c%option, 'cfl')) then
         c%option = 'cfl'
         if (.not. has_field(rd, i, 3)) c%v(1) = DEFAULT_CFL
         if (.not. (c%v(1) > 0.0_wp .and. c%v(1) <= 1.0_wp)) &
            call fail(rd, i, 'DT,CFL,c: c = '//rtoa(c%v(1), SHORT_REAL)//': expected 0 < c <= 1', err)
         return
      end if
      if (len_trim(c%option) > 0) then
         call evaluate(field(rd, i, 2), rd%params, v, e)
         if (allocated(e)) then
            call unknown_keyword(rd, i, 'DT option', field(rd, i, 2), opts, err)
            return
         end if
         call warn(rd, i, 'DT '//field(rd, i, 2)//' read as DT,,'//field(rd, i, 2)// &
                   ' (a number belongs in the third field)')
         c%option = ''
         c%v(1) = v
      end if
      if (.not. (c%v(1) > 0.0_wp)) call fail(rd, i, 'DT,,dt: dt = '//rtoa(c%v(1), SHORT_REAL)// &
                                             ': expected dt > 0 (or DT,CFL,c)', err)
   end subroutine parse_dt

   !> INITial,RATE|VELOcity (data after END) or INITial,REGIon|MATErial,id,vx,vy (computed now).
   subroutine parse_init(rd, i, model, c, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      type(model_t), intent(in) :: model
      type(command_t), intent(inout) :: c
      type(error_t), allocatable, intent(out) :: err
      character(len=12), parameter :: opts(4) = [character(len=12) :: 'RATE', 'VELOcity', &
                                                 'REGIon', 'MATErial']
      integer :: e, id, nn
      logical :: hit, region
      nn = model%mesh%nnode
      allocate (c%data(2, nn), c%given(nn))
      c%data = 0.0_wp
      c%given = .false.
      if (keyword_is(c%option, 'rate') .or. keyword_is(c%option, 'velo')) then
         c%option = keyword_key(c%option)
         return
      end if
      if (.not. (keyword_is(c%option, 'regi') .or. keyword_is(c%option, 'mate'))) then
         if (keyword_is(c%option, 'disp')) then
            call fail(rd, i, 'INITial,DISPlacement is not supported: expected INITial,RATE, '// &
                      'VELOcity, REGIon or MATErial', err)
         else
            call unknown_keyword(rd, i, 'INITial option', field(rd, i, 2), opts, err)
         end if
         return
      end if
      region = keyword_is(c%option, 'regi')
      c%option = keyword_key(c%option)
      call int_field(rd, i, 3, 'INITial,'//field(rd, i, 2)//',id,vx,vy', id, err)
      if (allocated(err)) return
      hit = .false.
      do e = 1, model%mesh%nelem
         if (region .and. model%mesh%region(e) /= id) cycle
         if (.not. region .and. model%mesh%mat(e) /= id) cycle
         hit = .true.
         c%given(model%mesh%conn(:, e)) = .true.
      end do
      if (.not. hit) then
         if (region) then
            call fail(rd, i, 'INITial,REGIon: region '//itoa(id)//' has no elements: expected '// &
                      'an existing region', err)
         else
            call fail(rd, i, 'INITial,MATErial: material '//itoa(id)//' has no elements: '// &
                      'expected an existing material', err)
         end if
         return
      end if
      c%data(1, :) = merge(c%v(2), 0.0_wp, c%given)
      c%data(2, :) = merge(c%v(3), 0.0_wp, c%given)
   end subroutine parse_init

   !> Read the data sets after the BATCh END in command order, then STOP. `map` sends a node to
   !> its survivor after TIE.
   subroutine read_batch_data(rd, model, map, err)
      type(reader_t), intent(inout) :: rd
      type(model_t), intent(inout) :: model
      integer, intent(in) :: map(:)
      type(error_t), allocatable, intent(out) :: err
      type(request_t), allocatable :: req(:)
      integer :: k, nreq, i
      logical :: cut

      allocate (req(16))
      nreq = 0
      do k = 1, size(model%program)
         associate (c => model%program(k))
            if (c%name == 'tplo') then
               call read_requests(rd, model, map, req, nreq, err)
            else if (c%name == 'init' .and. (c%option == 'rate' .or. c%option == 'velo')) then
               call read_init_data(rd, model%mesh, map, c, err)
            else if (c%name == 'prop') then
               call read_prop_data(rd, model%loads, nint(c%v(1)), nint(c%v(2)), c%where, err)
            end if
         end associate
         if (allocated(err)) return
      end do
      model%requests = req(1:nreq)
      call next_nonblank(rd, i)
      if (i == 0) then
         call fail(rd, i, 'expected STOP at the end of the deck', err)
         return
      end if
      call check_command(rd, i, cut)
      if (.not. keyword_is(word(rd, i, 1), 'stop')) then
         if (cut) then
            call fail(rd, i, 'expected STOP (the blank record at '//where(rd, i - 1)// &
                      ' ended the data set before this record)', err)
         else
            call fail(rd, i, 'expected STOP after the data of the BATCh commands (one data '// &
                      'set per TPLOt and INITial,RATE|VELOcity, one per PROPortional function, '// &
                      'each ended by a blank record)', err)
         end if
      end if
   end subroutine read_batch_data

   !> INITial,RATE|VELOcity node-vector records `n, ng, vx, vy` up to a blank record.
   subroutine read_init_data(rd, mesh, map, c, err)
      type(reader_t), intent(inout) :: rd
      type(mesh_t), intent(in) :: mesh
      integer, intent(in) :: map(:)
      type(command_t), intent(inout) :: c
      type(error_t), allocatable, intent(out) :: err
      type(genvec_t) :: g
      integer, allocatable :: nodes(:)
      real(wp), allocatable :: vals(:, :)
      integer :: i, cnt, k, n
      do
         call next_in_set(rd, i)
         if (i == 0) return
         cnt = 0
         call check_data_record(rd, i, 'INITial', err)
         if (allocated(err)) return
         call node_record(rd, i, 1, 'INITial data record n, ng, vx, vy', mesh%nnode, .false., g, &
                          nodes, vals, cnt, err)
         if (allocated(err)) return
         do k = 1, cnt
            n = nodes(k)
            if (.not. mesh%defined(n)) then
               call fail(rd, i, 'INITial data: node '//itoa(n)//' has no coordinates: expected a '// &
                         'node of the mesh', err)
               return
            end if
            n = map(n)
            c%data(:, n) = vals(:, k)
            c%given(n) = .true.
         end do
      end do
   end subroutine read_init_data

   !> TPLOt request records up to a blank record, resolved against the final mesh.
   subroutine read_requests(rd, model, map, req, nreq, err)
      type(reader_t), intent(inout) :: rd
      type(model_t), intent(in) :: model
      integer, intent(in) :: map(:)
      type(request_t), allocatable, intent(inout) :: req(:)
      integer, intent(inout) :: nreq
      type(error_t), allocatable, intent(out) :: err
      type(request_t) :: r
      integer :: i
      logical :: skip
      do
         call next_in_set(rd, i)
         if (i == 0) return
         call parse_request(rd, i, model, map, r, skip, err)
         if (allocated(err)) return
         if (skip) cycle
         call grow(req, nreq + 1)
         nreq = nreq + 1
         req(nreq) = r
      end do
   end subroutine read_requests

   !> One request: `disp|velo|acce,node,dof` | `...,,dof,x,y` | `stre,elem,comp` |
   !> `stre,,comp,x,y` | `reac,node,dof` | `cont,pair,comp`; `show` (and `ener`) are skipped.
   subroutine parse_request(rd, i, model, map, r, skip, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(model_t), intent(in) :: model
      integer, intent(in) :: map(:)
      type(request_t), intent(out) :: r
      logical, intent(out) :: skip
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: w, what
      logical :: used(model%mesh%nnode)
      integer :: id, e

      skip = .false.
      w = word(rd, i, 1)
      r%where = where(rd, i)
      if (keyword_is(w, 'show')) then
         skip = .true.
         return
      else if (keyword_is(w, 'ener')) then
         call warn(rd, i, 'TPLOt request ener ignored: energies are always written to <stem>.ene')
         skip = .true.
         return
      else if (keyword_is(w, 'disp')) then
         r%kind = REQ_DISP
      else if (keyword_is(w, 'velo')) then
         r%kind = REQ_VELO
      else if (keyword_is(w, 'acce')) then
         r%kind = REQ_ACCE
      else if (keyword_is(w, 'stre')) then
         r%kind = REQ_STRE
      else if (keyword_is(w, 'reac')) then
         r%kind = REQ_REAC
      else if (keyword_is(w, 'cont')) then
         r%kind = REQ_CONT
      else if (keyword_is(w, 'mome')) then
         r%kind = REQ_MOME
      else if (keyword_is(w, 'rigi')) then
         r%kind = REQ_RIGI
      else if (is_command(w)) then
         call fail(rd, i, field(rd, i, 1)//' inside the TPLOt requests: expected a blank record '// &
                   'to end the requests', err)
         return
      else
         call unknown_keyword(rd, i, 'TPLOt request', field(rd, i, 1), requests, err)
         return
      end if
      what = 'TPLOt request '//w//',id,comp[,x,y]'
      if (r%kind == REQ_REAC .and. (keyword_is(word(rd, i, 2), 'regi') .or. keyword_is(word(rd, i, 2), 'phys'))) then
         call reaction_sum(err)
         return
      end if
      call int_field(rd, i, 2, what, id, err)
      if (.not. allocated(err)) call int_field(rd, i, 3, what, r%comp, err)
      if (allocated(err)) return
      select case (r%kind)
      case (REQ_DISP, REQ_VELO, REQ_ACCE, REQ_REAC)
         if (r%comp /= 1 .and. r%comp /= 2) then
            call fail(rd, i, what//': dof '//itoa(r%comp)//': expected dof 1 or 2', err)
            return
         end if
      case (REQ_STRE)
         if (r%comp < 1 .or. r%comp > 10) then
            call fail(rd, i, what//': component '//itoa(r%comp)//': expected 1..10 (sxx syy szz '// &
                      'sxy p mises J, and ep T Y of a PLAStic material)', err)
            return
         end if
      case (REQ_CONT)
         if (r%comp < 1 .or. r%comp > 11) then
            call fail(rd, i, what//': component '//itoa(r%comp)//': expected 1..11 (normal force, '// &
                      'force x, force y, active constraints, penetration, largest multiplier, work, '// &
                      'friction force, sticking, slipping, frictional dissipation)', err)
            return
         end if
         call check_pair(id)
         r%id = id
         return
      case (REQ_MOME)
         if (r%comp < 1 .or. r%comp > 3) then
            call fail(rd, i, what//': component '//itoa(r%comp)//': expected 1 (x), 2 (y) or 3 '// &
                      '(angular momentum about the origin)', err)
         else if (.not. any(model%mesh%region == id)) then
            call fail(rd, i, what//': region '//itoa(id)//' has no elements: expected a region number', err)
         end if
         r%id = id
         return
      case (REQ_RIGI)
         if (r%comp < 1 .or. r%comp > 6) then
            call fail(rd, i, what//': component '//itoa(r%comp)//': expected 1..6 (centroid '// &
                      'displacement x, y, rotation, centroid velocity x, y, angular velocity)', err)
         else if (.not. rigid_region(id)) then
            call fail(rd, i, what//': region '//itoa(id)//' has no rigid elements: expected the '// &
                      'region of a RIGId body', err)
         end if
         r%id = id
         return
      end select
      used = used_nodes(model%mesh)
      if (id == 0 .and. r%kind /= REQ_REAC) then
         r%by_point = .true.
         if (.not. (has_field(rd, i, 4) .and. has_field(rd, i, 5))) then
            call fail(rd, i, what//': expected x, y in fields 4 and 5 when the id field is empty', err)
            return
         end if
         call real_field(rd, i, 4, what, r%xy(1), err)
         if (.not. allocated(err)) call real_field(rd, i, 5, what, r%xy(2), err)
         if (allocated(err)) return
         if (r%kind == REQ_STRE) then
            r%id = nearest_element(model%mesh, r%xy)
         else
            r%id = nearest_node(model%mesh, used, r%xy)
         end if
         return
      end if
      if (r%kind == REQ_STRE) then
         if (id < 1 .or. id > model%mesh%nelem) then
            call fail(rd, i, what//': element '//itoa(id)//' is unknown: expected an element '// &
                      'number in 1..'//itoa(model%mesh%nelem), err)
            return
         end if
         r%id = id
         return
      end if
      e = 0
      if (id >= 1 .and. id <= model%mesh%nnode) e = map(id)
      if (e == 0) then
         call fail(rd, i, what//': node '//itoa(id)//' is unknown: expected a node of the mesh', err)
         return
      end if
      if (.not. used(e)) then
         call fail(rd, i, what//': node '//itoa(id)//' is unknown: expected a node of an element', err)
         return
      end if
      r%id = e
   contains
      !> reac,REGIon,r,dof | reac,PHYSical,c,dof: the sum over the nodes of a region or edge set.
      subroutine reaction_sum(err)
         type(error_t), allocatable, intent(out) :: err
         what = 'TPLOt request reac,'//field(rd, i, 2)//',id,dof'
         call int_field(rd, i, 3, what, id, err)
         if (.not. allocated(err)) call int_field(rd, i, 4, what, r%comp, err)
         if (allocated(err)) return
         if (r%comp /= 1 .and. r%comp /= 2) then
            call fail(rd, i, what//': dof '//itoa(r%comp)//': expected dof 1 or 2', err)
         else if (keyword_is(word(rd, i, 2), 'regi')) then
            r%kind = REQ_REAC_REGION
            if (.not. any(model%mesh%region == id)) call fail(rd, i, what//': region '//itoa(id)// &
                                                               ' has no elements: expected a region number', err)
         else
            r%kind = REQ_REAC_SET
            if (find_edge_set(model%mesh%edge_sets, id) == 0) call fail(rd, i, what// &
               ': physical curve '//itoa(id)//' is not in the mesh: expected one of the physical '// &
               'curves of the GMSH meshes (here: '//edge_set_ids(model%mesh%edge_sets)//')', err)
         end if
         r%id = id
      end subroutine reaction_sum
      !> Region `id` has rigid elements.
      logical function rigid_region(id)
         integer, intent(in) :: id
         integer :: k
         rigid_region = .false.
         do k = 1, model%mesh%nelem
            if (model%mesh%region(k) /= id) cycle
            if (model%materials(model%mesh%mat(k))%kind == MAT_RIGID) rigid_region = .true.
         end do
      end function rigid_region
      subroutine check_pair(id)
         integer, intent(in) :: id
         if (.not. model%contact%active) then
            call fail(rd, i, what//': the deck has no CONTact block: expected one for a cont request', err)
         else if (id < 1) then
            call fail(rd, i, what//': pair '//itoa(id)//': expected a pair id >= 1', err)
         else if (.not. model%contact%automatic) then
            if (.not. any(model%contact%pairs%id == id)) call fail(rd, i, what//': pair '// &
               itoa(id)//' is unknown: expected a PAIR id of the CONTact block', err)
         end if
      end subroutine check_pair
   end subroutine parse_request

   !> Element whose node-average centroid is nearest to p (lowest number on a tie).
   pure integer function nearest_element(mesh, p)
      type(mesh_t), intent(in) :: mesh
      real(wp), intent(in) :: p(2)
      real(wp) :: c(2), d, dbest
      integer :: e
      nearest_element = 0
      dbest = huge(1.0_wp)
      do e = 1, mesh%nelem
         c = 0.25_wp*sum(mesh%x(:, mesh%conn(:, e)), dim=2)
         d = (c(1) - p(1))**2 + (c(2) - p(2))**2
         if (d < dbest) then
            dbest = d
            nearest_element = e
         end if
      end do
   end function nearest_element

end module exic_input_deck_batch
