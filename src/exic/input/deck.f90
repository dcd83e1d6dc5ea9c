!> The deck reader: a FEAP-style input file into a model_t (input language, sections 1-7).
!>
!> ```
!> [PARAmeters ... blank]          parameters may also be set before the title
!> FEAP * * <title>
!> numnp numel nummat ndm ndf nen  control record (zeros = count; non-zero counts are upper bounds)
!> <mesh commands>                 see exic_input_deck_mesh, exic_input_deck_material, exic_input_deck_contact
!> END
!> [TIE ... | PARAmeters ...]
!> BATCh ... END                   see exic_input_deck_batch
!> <data for TPLOt and INITial>
!> STOP
!> ```
!> Every error is `file:line: <what was expected>`; warnings go to model%warnings (also when an
!> error is returned).
module exic_input_deck
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_grow, only: grow
   use exic_input_deck_grow, only: grow
   use exic_model_model, only: model_t
   use exic_material_material, only: material_t
   use exic_base_strings, only: to_lower
   use exic_input_deck_records, only: read_source, keyword_is
   use exic_input_deck_reader, only: reader_t, next_record, next_nonblank, word, field, int_field, fail, &
                             where, check_command, looks_like_data, read_parameters, &
                             unknown_keyword, itoa, track_fields, unused_fields, use_all
   use exic_input_deck_mesh, only: builder_t, builder_init, cmd_coordinates, cmd_elements, &
                                cmd_region, cmd_boundary, cmd_ebound, cmd_cbound, &
                                cmd_nodal_values, cmd_global, cmd_initial
   use exic_input_deck_block, only: cmd_block, cmd_shift
   use exic_input_deck_gmsh, only: cmd_gmsh, cmd_pbound
   use exic_input_deck_material, only: cmd_material
   use exic_input_deck_contact, only: cmd_contact
   use exic_input_deck_finish, only: finish_mesh, check_contact, energy_warnings, cmd_tie, physical_surfaces
   use exic_input_deck_batch, only: read_batch, read_batch_data
   use exic_input_deck_loads, only: loads_builder_t, cmd_fpro, cmd_gravity, cmd_motion, cmd_csurface, &
                                 finish_loads, check_functions
   implicit none
   private

   public :: read_deck

   character(len=16), parameter :: mesh_commands(22) = [character(len=16) :: 'PARAmeters', &
      'COORdinates', 'ELEMents', 'REGIon', 'BLOCk', 'BOUNdary', 'EBOUndary', 'CBOUndary', &
      'FORCe', 'DISPlacement', 'GLOBal', 'MATErial', 'INITial', 'CONTact', 'END', 'SHIFt', &
      'GMSH', 'PBOUndary', 'FPROportional', 'CSURface', 'GRAVity', 'MOTIon']

contains

   !> Read the deck `path` into `model`. `err` is unallocated on success.
   subroutine read_deck(path, model, err)
      character(len=*), intent(in) :: path
      type(model_t), intent(out) :: model
      type(error_t), allocatable, intent(out) :: err
      type(reader_t) :: rd
      rd%warnings = ''
      rd%deck = path
      model%deck_file = path
      model%warnings = ''
      call read_source(path, rd%src, err)
      if (allocated(err)) return
      call make_echo(rd, model)
      call track_fields(rd)
      call read_all(rd, model, err)
      ! a field no reader used is never dropped quietly (the PAIR and contact method records make
      ! it an error themselves)
      if (.not. allocated(err)) call unused_fields(rd)
      if (associated(rd%seen)) deallocate (rd%seen)
      model%warnings = rd%warnings
   end subroutine read_deck

   !> model%echo: every line read, INCLude files expanded, newline-separated.
   subroutine make_echo(rd, model)
      type(reader_t), intent(in) :: rd
      type(model_t), intent(inout) :: model
      integer :: k, n, p
      n = 0
      do k = 1, rd%src%n
         n = n + len(rd%src%rec(k)%raw) + 1
      end do
      allocate (character(len=n) :: model%echo)
      p = 0
      do k = 1, rd%src%n
         n = len(rd%src%rec(k)%raw)
         model%echo(p + 1:p + n + 1) = rd%src%rec(k)%raw//new_line('a')
         p = p + n + 1
      end do
   end subroutine make_echo

   !> The phases of a deck in order.
   subroutine read_all(rd, model, err)
      type(reader_t), intent(inout) :: rd
      type(model_t), intent(inout) :: model
      type(error_t), allocatable, intent(out) :: err
      type(builder_t) :: b
      type(loads_builder_t) :: lb
      integer :: i, iend, ictl, counts(3), n
      integer, allocatable :: map(:)

      call read_head(rd, model, ictl, counts, err)
      if (allocated(err)) return
      call builder_init(b)
      call read_mesh(rd, b, lb, model, iend, err)
      if (allocated(err)) return
      call finish_mesh(rd, b, iend, counts, ictl, model, err)
      if (allocated(err)) return
      call physical_surfaces(model%contact, model%mesh, err)
      if (allocated(err)) return
      call check_contact(model%contact, model%mesh, err)
      if (allocated(err)) return
      if (allocated(model%materials)) call energy_warnings(rd, model%contact, model%mesh, model%materials)
      map = [(n, n=1, model%mesh%nnode)]
      do
         call next_nonblank(rd, i)
         if (i == 0) then
            call fail(rd, i, 'expected BATCh after the mesh END', err)
            return
         end if
         if (keyword_is(word(rd, i, 1), 'tie')) then
            call cmd_tie(rd, i, model, map, err)
         else if (keyword_is(word(rd, i, 1), 'para')) then
            call read_parameters(rd, err)
         else if (keyword_is(word(rd, i, 1), 'batc')) then
            exit
         else
            call fail(rd, i, '"'//field(rd, i, 1)//'" after the mesh END: expected TIE, '// &
                      'PARAmeters or BATCh', err)
         end if
         if (allocated(err)) return
      end do
      call finish_loads(rd, lb, model, map, err)
      if (allocated(err)) return
      call read_batch(rd, i, model, err)
      if (allocated(err)) return
      call read_batch_data(rd, model, map, err)
      if (allocated(err)) return
      call check_functions(rd, lb, model%loads, err)
   end subroutine read_all

   !> Parameters before the title, the title record and the control record.
   subroutine read_head(rd, model, ictl, counts, err)
      type(reader_t), intent(inout) :: rd
      type(model_t), intent(inout) :: model
      integer, intent(out) :: ictl, counts(3)
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'control record numnp numel nummat ndm ndf nen'
      character(len=:), allocatable :: t
      integer :: i, k, v(6)

      ictl = 0
      counts = 0
      do
         call next_nonblank(rd, i)
         if (i == 0) then
            call fail(rd, i, 'expected a title record FEAP * * <title>', err)
            return
         end if
         if (.not. keyword_is(word(rd, i, 1), 'para')) exit
         call read_parameters(rd, err)
         if (allocated(err)) return
      end do
      call use_all(rd, i)
      t = adjustl(rd%src%rec(i)%text)
      if (len_trim(t) < 4) t = t//'    '
      if (to_lower(t(1:4)) /= 'feap') then
         call fail(rd, i, 'expected the title record FEAP * * <title> (first 4 characters "feap")', err)
         return
      end if
      k = scan(t, ' ,')
      if (k == 0) k = len(t)
      t = adjustl(t(k + 1:))
      do while (len_trim(t) > 0)
         if (scan(t(1:1), '*,') == 0) exit
         t = adjustl(t(2:))
      end do
      model%title = trim(t)
      call next_record(rd, i)
      ictl = i
      if (i == 0) then
         call fail(rd, i, 'expected the '//what//' after the title', err)
         return
      end if
      if (rd%src%rec(i)%blank .or. .not. looks_like_data(rd, i)) then
         call fail(rd, i, 'expected the '//what//' right after the title (no blank or comment '// &
                   'line between them)', err)
         return
      end if
      do k = 1, 6
         call int_field(rd, i, k, what, v(k), err)
         if (allocated(err)) return
      end do
      if (any(v < 0)) then
         call fail(rd, i, what//': expected counts >= 0', err)
      else if (v(4) /= 0 .and. v(4) /= 2) then
         call fail(rd, i, what//': ndm = '//itoa(v(4))//': expected ndm = 2', err)
      else if (v(5) /= 0 .and. v(5) /= 2) then
         call fail(rd, i, what//': ndf = '//itoa(v(5))//': expected ndf = 2', err)
      else if (v(6) /= 0 .and. v(6) /= 4) then
         call fail(rd, i, what//': nen = '//itoa(v(6))//': expected nen = 4', err)
      end if
      counts = v(1:3)
   end subroutine read_head

   !> Mesh commands up to END; `iend` is the END record.
   subroutine read_mesh(rd, b, lb, model, iend, err)
      type(reader_t), intent(inout) :: rd
      type(builder_t), intent(inout) :: b
      type(loads_builder_t), intent(inout) :: lb
      type(model_t), intent(inout) :: model
      integer, intent(out) :: iend
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: w
      integer :: i
      logical :: cut

      iend = 0
      do
         call next_nonblank(rd, i)
         if (i == 0) then
            call fail(rd, i, 'expected END to close the mesh', err)
            return
         end if
         call check_command(rd, i, cut)
         w = word(rd, i, 1)
         if (keyword_is(w, 'end')) then
            if (keyword_is(word(rd, i, 2), 'cont')) then
               call fail(rd, i, 'END CONTact without CONTact: expected CONTact before it', err)
               return
            end if
            iend = i
            return
         else if (keyword_is(w, 'para')) then
            call read_parameters(rd, err)
         else if (keyword_is(w, 'coor')) then
            call cmd_coordinates(rd, b, err)
         else if (keyword_is(w, 'elem')) then
            call cmd_elements(rd, b, err)
         else if (keyword_is(w, 'regi')) then
            call cmd_region(rd, b, i, err)
         else if (keyword_is(w, 'bloc')) then
            call cmd_block(rd, b, i, err)
         else if (keyword_is(w, 'shif')) then
            call cmd_shift(rd, b, i, err)
         else if (keyword_is(w, 'gmsh')) then
            call cmd_gmsh(rd, b, i, err)
         else if (keyword_is(w, 'pbou')) then
            call cmd_pbound(rd, b, i, err)
         else if (keyword_is(w, 'boun')) then
            call cmd_boundary(rd, b, err)
         else if (keyword_is(w, 'ebou')) then
            call cmd_ebound(rd, b, i, err)
         else if (keyword_is(w, 'cbou')) then
            call cmd_cbound(rd, b, i, err)
         else if (keyword_is(w, 'forc')) then
            call cmd_nodal_values(rd, b, .true., err)
         else if (keyword_is(w, 'disp')) then
            call cmd_nodal_values(rd, b, .false., err)
         else if (keyword_is(w, 'glob')) then
            call cmd_global(rd, b, err)
         else if (keyword_is(w, 'mate')) then
            call material(i, err)
         else if (keyword_is(w, 'init')) then
            call cmd_initial(rd, b, i, err)
         else if (keyword_is(w, 'cont')) then
            call cmd_contact(rd, i, model%contact, err)
         else if (keyword_is(w, 'fpro')) then
            call cmd_fpro(rd, lb, err)
         else if (keyword_is(w, 'csur')) then
            call cmd_csurface(rd, lb, i, err)
         else if (keyword_is(w, 'grav')) then
            call cmd_gravity(rd, lb, model%loads, i, err)
         else if (keyword_is(w, 'moti')) then
            call cmd_motion(rd, lb, i, err)
         else if (keyword_is(w, 'batc') .or. keyword_is(w, 'tie') .or. keyword_is(w, 'stop')) then
            call fail(rd, i, field(rd, i, 1)//' inside the mesh: expected END to close the mesh '// &
                      'first', err)
         else if (cut) then
            call fail(rd, i, 'record "'//trim(adjustl(rd%src%rec(i)%text))//'" where a mesh '// &
                      'command is expected: the blank record at '//where(rd, i - 1)// &
                      ' ended the data set before it (a comment-only line is a blank record)', err)
         else
            call unknown_keyword(rd, i, 'mesh command', field(rd, i, 1), mesh_commands, err)
         end if
         if (allocated(err)) return
      end do
   contains
      subroutine material(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         type(material_t) :: mat
         integer :: ma
         call cmd_material(rd, i, ma, mat, err)
         if (allocated(err)) return
         call grow(b%mats, ma)
         call grow(b%mat_rec, ma)
         if (b%mat_rec(ma) > 0) then
            call fail(rd, i, 'MATErial '//itoa(ma)//' is already defined at '// &
                      where(rd, b%mat_rec(ma))//': expected each material set once', err)
            return
         end if
         b%mats(ma) = mat
         b%mat_rec(ma) = i
         b%nmat = max(b%nmat, ma)
      end subroutine material
   end subroutine read_mesh

end module exic_input_deck
