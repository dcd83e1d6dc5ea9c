!> A cursor over the records of a deck, with the parameter table, warnings and field access.
!>
!> Every error made here is `file:line: <what was expected>`. A data set ends at a blank
!> record (a comment-only line is one); when a record that starts like data (digit, sign or
!> `.`) is then met where a command is expected, a warning names both lines (spec section 1).
!>
!> No field is dropped quietly: `field` (and with it `word`, `has_field`, `real_field`,
!> `int_field`) records the highest field read of every record, and once the deck is read
!> `unused_fields` warns, with file:line, of every non-empty field beyond it. Records read whole
!> (the title, PARAmeter records) say so with `use_all`. Where an unused field is an error
!> (PAIR and contact method records) the parser calls `no_more_fields` itself.
module exic_input_deck_reader
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa, to_lower, SHORT_REAL
   use exic_base_error, only: error_t, make_error
   use exic_input_deck_records, only: source_t, keyword_is, nearest_keyword
   use exic_input_deck_expression, only: param_table_t, set_param, evaluate, is_valid_name
   implicit none
   private

   public :: reader_t, next_record, next_in_set, next_nonblank, back_one, nfields, field, word, has_field
   public :: real_field, int_field, fail, warn, warn_at, where, end_set, looks_like_data, check_command
   public :: read_parameters, unknown_keyword, itoa, check_data_record, is_command
   public :: no_more_fields, unused_fields, use_all, track_fields

   !> Every command keyword of the language (mesh, solution and top level), used to tell a
   !> command that was read inside a data set.
   character(len=12), parameter :: all_commands(39) = [character(len=12) :: 'PARAmeters', &
      'COORdinates', 'ELEMents', 'REGIon', 'BLOCk', 'BOUNdary', 'EBOUndary', 'CBOUndary', &
      'FORCe', 'DISPlacement', 'GLOBal', 'MATErial', 'INITial', 'CONTact', 'END', 'FEAP', 'TIE', &
      'BATCh', 'STOP', 'INCLude', 'LOOP', 'NEXT', 'TRANsient', 'TIME', 'FORM', 'TPLOt', 'OUTPut', &
      'PRINt', 'DT', 'SURFace', 'PAIR', 'SHIFt', 'GMSH', 'PBOUndary', 'FPROportional', &
      'CSURface', 'GRAVity', 'MOTIon', 'PROPortional']

   !> The deck's records and the reading state.
   type :: reader_t
      type(source_t) :: src
      integer :: pos = 0                        !< index of the record last returned
      type(param_table_t) :: params
      character(len=:), allocatable :: warnings !< newline-separated "file:line: warning: ..."
      integer :: set_end = -1                   !< index of the blank record that last ended a set
      !> highest field read of each record (see `field`); a pointer so that the readers that take
      !> the cursor intent(in) can record what they read; not associated: nothing is recorded
      integer, pointer :: seen(:) => null()
      character(len=:), allocatable :: deck     !< the deck's path (errors of an empty deck)
   end type reader_t

contains

   !> Advance to the next record; `i` = 0 at the end of input.
   subroutine next_record(rd, i)
      type(reader_t), intent(inout) :: rd
      integer, intent(out) :: i
      if (rd%pos >= rd%src%n) then
         rd%pos = rd%src%n + 1
         i = 0
      else
         rd%pos = rd%pos + 1
         i = rd%pos
      end if
   end subroutine next_record

   !> Next record of the current data set: `i` = 0 at the end of input or at the blank record
   !> that ends the set (which is recorded with end_set).
   subroutine next_in_set(rd, i)
      type(reader_t), intent(inout) :: rd
      integer, intent(out) :: i
      call next_record(rd, i)
      if (i == 0) return
      if (rd%src%rec(i)%blank) then
         call end_set(rd, i)
         i = 0
      end if
   end subroutine next_in_set

   !> Advance to the next non-blank record; `i` = 0 at the end of input.
   subroutine next_nonblank(rd, i)
      type(reader_t), intent(inout) :: rd
      integer, intent(out) :: i
      do
         call next_record(rd, i)
         if (i == 0) return
         if (.not. rd%src%rec(i)%blank) return
      end do
   end subroutine next_nonblank

   !> Step back one record, so the next call returns the current record again.
   subroutine back_one(rd)
      type(reader_t), intent(inout) :: rd
      rd%pos = min(rd%pos, rd%src%n + 1) - 1
   end subroutine back_one

   !> Number of fields of record `i`.
   pure integer function nfields(rd, i)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      nfields = rd%src%rec(i)%nf
   end function nfields

   !> Field `k` of record `i` as written ('' when absent); records that field k was read.
   function field(rd, i, k) result(s)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      character(len=:), allocatable :: s
      s = ''
      if (i < 1 .or. i > rd%src%n) return
      if (associated(rd%seen)) rd%seen(i) = max(rd%seen(i), k)
      if (k >= 1 .and. k <= rd%src%rec(i)%nf) s = rd%src%rec(i)%f(k)%s
   end function field

   !> Field `k` of record `i` in lower case ('' when absent).
   function word(rd, i, k) result(s)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      character(len=:), allocatable :: s
      s = to_lower(field(rd, i, k))
   end function word

   !> True when record `i` has a non-empty field `k`.
   logical function has_field(rd, i, k)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      has_field = len(field(rd, i, k)) > 0
   end function has_field

   !> 'file:line' of record `i` (the last record when `i` = 0).
   function where(rd, i) result(s)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      character(len=:), allocatable :: s
      integer :: j
      j = i
      if (j < 1 .or. j > rd%src%n) j = rd%src%n
      if (j < 1) then
         s = '?:0'
      else
         s = rd%src%rec(j)%file//':'//itoa(rd%src%rec(j)%line)
      end if
   end function where

   !> Make `err` = 'file:line: msg' for record `i` (`i` = 0: end of input, at the last line).
   subroutine fail(rd, i, msg, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      character(len=*), intent(in) :: msg
      type(error_t), allocatable, intent(out) :: err
      integer :: j
      j = i
      if (j < 1 .or. j > rd%src%n) j = rd%src%n
      if (j < 1) then
         if (allocated(rd%deck)) then
            call make_error(err, 'the deck is empty: '//msg, rd%deck, 1)
         else
            call make_error(err, msg)
         end if
      else if (i < 1 .or. i > rd%src%n) then
         call make_error(err, 'end of input: '//msg, rd%src%rec(j)%file, rd%src%rec(j)%line)
      else
         call make_error(err, msg, rd%src%rec(j)%file, rd%src%rec(j)%line)
      end if
   end subroutine fail

   !> Add 'file:line: warning: msg' for record `i`.
   subroutine warn(rd, i, msg)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      character(len=*), intent(in) :: msg
      call warn_at(rd, where(rd, i), msg)
   end subroutine warn

   !> Add 'loc: warning: msg' (loc: a file:line kept from an earlier record).
   subroutine warn_at(rd, loc, msg)
      type(reader_t), intent(inout) :: rd
      character(len=*), intent(in) :: loc, msg
      character(len=:), allocatable :: line
      line = loc//': warning: '//msg
      if (.not. allocated(rd%warnings)) then
         rd%warnings = line
      else if (len(rd%warnings) == 0) then
         rd%warnings = line
      else
         rd%warnings = rd%warnings//new_line('a')//line
      end if
   end subroutine warn_at

   !> Record that the blank record `i` ended a data set.
   subroutine end_set(rd, i)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      rd%set_end = i
   end subroutine end_set

   !> True when record `i` starts like data: a digit, a sign or '.'.
   pure logical function looks_like_data(rd, i)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      character(len=:), allocatable :: t
      looks_like_data = .false.
      if (i < 1 .or. i > rd%src%n) return
      t = adjustl(rd%src%rec(i)%text)
      if (len_trim(t) == 0) return
      looks_like_data = scan(t(1:1), '0123456789+-.') > 0
   end function looks_like_data

   !> Called where record `i` is read as a command: when it starts like data right after a blank
   !> record that ended a data set, warn that the set was probably cut short by a comment line.
   !> `cut` tells whether that happened (the caller's error message can then say so).
   subroutine check_command(rd, i, cut)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      logical, intent(out) :: cut
      cut = .false.
      if (i < 1) return
      if (rd%set_end == i - 1 .and. looks_like_data(rd, i)) then
         cut = .true.
         call warn(rd, i, 'record starts like data but a command is expected here: the blank '// &
                   'record at '//where(rd, i - 1)//' ended the data set before it '// &
                   '(a comment-only line is a blank record)')
      end if
   end subroutine check_command

   !> Error for an unknown keyword `w` of record `i`, naming the nearest of `table`.
   subroutine unknown_keyword(rd, i, what, w, table, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      character(len=*), intent(in) :: what, w
      character(len=*), intent(in) :: table(:)
      type(error_t), allocatable, intent(out) :: err
      call fail(rd, i, 'unknown '//what//' "'//w//'": expected a known keyword; nearest known '// &
                'keyword: '//nearest_keyword(w, table), err)
   end subroutine unknown_keyword

   !> True when `w` is a command keyword of the language.
   pure logical function is_command(w)
      character(len=*), intent(in) :: w
      integer :: k
      is_command = .false.
      do k = 1, size(all_commands)
         if (keyword_is(w, all_commands(k))) is_command = .true.
      end do
   end function is_command

   !> Record `i` is read as data of the set `setname`: when its first field is a command keyword
   !> rather than a number or expression, the set was not ended by a blank record; say so.
   subroutine check_data_record(rd, i, setname, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      character(len=*), intent(in) :: setname
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: e
      real(wp) :: v
      if (looks_like_data(rd, i)) return
      call evaluate(field(rd, i, 1), rd%params, v, e)
      if (.not. allocated(e)) return
      if (is_command(field(rd, i, 1))) call fail(rd, i, field(rd, i, 1)//' inside the '// &
         setname//' data set: expected a blank record to end the set before the next command', err)
   end subroutine check_data_record

   !> Numeric field `k` of record `i` (empty or absent: 0). `what` names the record's layout.
   subroutine real_field(rd, i, k, what, v, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      character(len=*), intent(in) :: what
      real(wp), intent(out) :: v
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: e
      call evaluate(field(rd, i, k), rd%params, v, e)
      if (allocated(e)) call fail(rd, i, what//': field '//itoa(k)//' '//e%message, err)
   end subroutine real_field

   !> Integer field `k` of record `i` (nint of its value; a non-integral value is an error).
   subroutine int_field(rd, i, k, what, n, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      character(len=*), intent(in) :: what
      integer, intent(out) :: n
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: v
      n = 0
      call real_field(rd, i, k, what, v, err)
      if (allocated(err)) return
      if (abs(v) > 2.0e9_wp) then
         call fail(rd, i, what//': field '//itoa(k)//' = '//rtoa(v, SHORT_REAL)//': expected an integer '// &
                   'of reasonable size', err)
      else if (abs(v - anint(v)) > 1.0e-9_wp*max(1.0_wp, abs(v))) then
         call fail(rd, i, what//': field '//itoa(k)//' = '//rtoa(v, SHORT_REAL)//': expected an integer', err)
      else
         n = nint(v)
      end if
   end subroutine int_field

   !> Start recording the fields read of every record (read_deck, before any record is read).
   subroutine track_fields(rd)
      type(reader_t), intent(inout) :: rd
      if (associated(rd%seen)) deallocate (rd%seen)
      allocate (rd%seen(rd%src%n), source=0)
   end subroutine track_fields

   !> Record `i` was read as a whole (its raw text), every field of it used.
   subroutine use_all(rd, i)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      if (.not. associated(rd%seen)) return
      if (i >= 1 .and. i <= rd%src%n) rd%seen(i) = huge(1)
   end subroutine use_all

   !> An error naming the first non-empty field of record `i` beyond field `k` (`what` names the
   !> record's layout): for records where an unused field must not pass (PAIR, contact methods).
   subroutine no_more_fields(rd, i, k, what, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i, k
      character(len=*), intent(in) :: what
      type(error_t), allocatable, intent(out) :: err
      integer :: j
      do j = k + 1, rd%src%rec(i)%nf
         if (len(rd%src%rec(i)%f(j)%s) == 0) cycle
         call fail(rd, i, what//': field '//itoa(j)//' "'//rd%src%rec(i)%f(j)%s//'" is not used: '// &
                   'expected at most '//itoa(k)//' fields', err)
         return
      end do
      call use_all(rd, i)
   end subroutine no_more_fields

   !> Once the deck is read: a warning with file:line for every non-empty field that no reader
   !> read (records never read field by field are skipped); stops recording.
   subroutine unused_fields(rd)
      type(reader_t), intent(inout) :: rd
      integer :: i, j
      if (.not. associated(rd%seen)) return
      do i = 1, rd%src%n
         if (rd%src%rec(i)%blank .or. rd%seen(i) == 0) cycle
         do j = min(rd%seen(i), rd%src%rec(i)%nf) + 1, rd%src%rec(i)%nf
            if (len(rd%src%rec(i)%f(j)%s) == 0) cycle
            call warn(rd, i, 'field '//itoa(j)//' "'//rd%src%rec(i)%f(j)%s//'" of this record is '// &
                      'not used (ignored)')
         end do
      end do
      deallocate (rd%seen)
   end subroutine unused_fields

   !> Read a PARAmeter data set: records `name = expression` (several per record may be separated
   !> by commas; blanks inside a record are removed, as FEAP does), ended by a blank record.
   subroutine read_parameters(rd, err)
      type(reader_t), intent(inout) :: rd
      type(error_t), allocatable, intent(out) :: err
      integer :: i
      do
         call next_in_set(rd, i)
         if (i == 0) return
         call parameter_record(rd, i, err)
         if (allocated(err)) return
      end do
   end subroutine read_parameters

   !> One PARAmeter record.
   subroutine parameter_record(rd, i, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: t, piece, name
      type(error_t), allocatable :: e
      integer :: k, p, q
      real(wp) :: v

      call use_all(rd, i)
      t = ''
      do k = 1, len(rd%src%rec(i)%text)
         if (rd%src%rec(i)%text(k:k) /= ' ') t = t//rd%src%rec(i)%text(k:k)
      end do
      p = 1
      do while (p <= len(t))
         q = index(t(p:), ',')
         if (q == 0) then
            piece = t(p:)
            p = len(t) + 1
         else
            piece = t(p:p + q - 2)
            p = p + q
         end if
         if (len(piece) == 0) cycle
         q = index(piece, '=')
         if (q == 0) then
            call check_data_record(rd, i, 'PARAmeters', err)
            if (allocated(err)) return
            call fail(rd, i, 'PARAmeter record "'//piece//'": expected name = expression', err)
            return
         end if
         name = to_lower(piece(1:q - 1))
         if (.not. is_valid_name(name)) then
            call fail(rd, i, 'PARAmeter name "'//name//'": expected a letter followed by at most'// &
                      ' 15 letters, digits or _', err)
            return
         end if
         call evaluate(piece(q + 1:), rd%params, v, e)
         if (.not. allocated(e) .and. len(piece) == q) then
            call fail(rd, i, 'PARAmeter '//name//': expected an expression after "="', err)
            return
         end if
         if (allocated(e)) then
            call fail(rd, i, 'PARAmeter '//name//': '//e%message, err)
            return
         end if
         call set_param(rd%params, name, v)
      end do
   end subroutine parameter_record

end module exic_input_deck_reader
