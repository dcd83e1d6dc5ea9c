!> Records and fields of a FEAP-style deck (input language, section 1).
!>
!> A deck is read once, with every `INCLude,file` expanded in place (relative to the including
!> file, depth <= 9), into an array of records. Each record keeps its file name, line number,
!> raw text and its fields:
!>
!> - tabs and CR are blanks; `!` starts a comment (outside double quotes);
!> - a line holding nothing but blanks or a comment is a BLANK record;
!> - separators are comma, blank and `=`; a run of blanks is one separator, blanks next to a
!>   comma or `=` are absorbed, and `,,` gives an empty field;
!> - `"..."` is one text field (the quotes are removed);
!> - a line longer than 256 characters is an error.
!>
!> Keywords match on their first 4 characters, case-insensitive; shorter keywords (`END`, `DT`,
!> `TIE`) match on their own length.
module exic_input_deck_records
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow_size
   use exic_base_strings, only: itoa, to_lower
   use exic_base_posix, only: file_kind, FILE_REGULAR, FILE_DIRECTORY, FILE_MISSING
   implicit none
   private

   public :: field_t, record_t, source_t
   public :: read_source, split_fields, keyword_is, keyword_key, nearest_keyword
   public :: edit_distance, dirname

   !> Longest record accepted (characters, trailing blanks excluded).
   integer, parameter, public :: MAX_RECORD_LENGTH = 256
   !> Deepest INCLude nesting accepted.
   integer, parameter, public :: MAX_INCLUDE_DEPTH = 9

   !> One field of a record.
   type :: field_t
      character(len=:), allocatable :: s
   end type field_t

   !> One line of input after comment stripping and splitting.
   type :: record_t
      character(len=:), allocatable :: raw      !< the line as read
      character(len=:), allocatable :: text     !< comment removed, tabs and CR as blanks
      character(len=:), allocatable :: file     !< file the line came from
      integer :: line = 0                       !< line number in that file
      logical :: blank = .true.                 !< nothing but blanks or a comment
      integer :: nf = 0                         !< number of fields
      type(field_t), allocatable :: f(:)        !< the fields
   end type record_t

   !> All records of a deck, INCLude files expanded.
   type :: source_t
      integer :: n = 0
      type(record_t), allocatable :: rec(:)
   end type source_t

contains

   !> Read the deck `path` and every file it includes into `src`.
   subroutine read_source(path, src, err)
      character(len=*), intent(in) :: path
      type(source_t), intent(out) :: src
      type(error_t), allocatable, intent(out) :: err
      allocate (src%rec(256))
      src%n = 0
      call check_regular(path, err)
      if (allocated(err)) return
      call read_file(path, 0, src, err)
      if (allocated(err)) return
      src%rec = src%rec(1:src%n)
   end subroutine read_source

   !> Read one file at include depth `depth`, appending its records to `src`. `path` has been
   !> checked to be a regular file.
   recursive subroutine read_file(path, depth, src, err)
      character(len=*), intent(in) :: path
      integer, intent(in) :: depth
      type(source_t), intent(inout) :: src
      type(error_t), allocatable, intent(out) :: err
      integer :: unit, ios, lineno
      character(len=:), allocatable :: line
      character(len=512) :: msg
      type(record_t) :: rec
      logical :: eof, too_long

      open (newunit=unit, file=path, status='old', action='read', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, 'cannot open "'//path//'": '//trim(msg))
         return
      end if
      lineno = 0
      do
         msg = ''
         call get_line(unit, line, eof, too_long, ios, msg)
         if (eof) exit
         lineno = lineno + 1
         if (ios /= 0) then
            call make_error(err, 'read error: '//trim(msg)//': expected a text file', path, lineno)
            exit
         end if
         if (too_long) then
            call make_error(err, 'record longer than '//itoa(MAX_RECORD_LENGTH)//' characters: '// &
                            'expected at most '//itoa(MAX_RECORD_LENGTH)//' characters per line '// &
                            '(blanks at the end excluded)', path, lineno)
            exit
         end if
         call make_record(line, path, lineno, rec, err)
         if (allocated(err)) exit
         if (rec%nf >= 1) then
            if (keyword_is(rec%f(1)%s, 'incl')) then
               call include_file(rec, depth, src, eof, err)
               if (allocated(err) .or. eof) exit
               cycle
            end if
         end if
         call append(src, rec, err)
         if (allocated(err)) exit
      end do
      close (unit)
   end subroutine read_file

   !> Error unless `path` is a regular file (a directory, device, FIFO or socket is refused
   !> before it is opened: reading /dev/zero or a FIFO would never end).
   subroutine check_regular(path, err)
      character(len=*), intent(in) :: path
      type(error_t), allocatable, intent(out) :: err
      select case (file_kind(path))
      case (FILE_REGULAR)
         return
      case (FILE_DIRECTORY)
         call make_error(err, '"'//path//'" is a directory: expected a regular file')
      case (FILE_MISSING)
         call make_error(err, 'cannot find file "'//path//'": expected an existing file')
      case default
         call make_error(err, '"'//path//'" is not a regular file (a device, FIFO or socket): '// &
                         'expected a regular file')
      end select
   end subroutine check_regular

   !> Handle an `INCLude,file` record (`INCLude,END` sets `stop_here`).
   recursive subroutine include_file(rec, depth, src, stop_here, err)
      type(record_t), intent(in) :: rec
      integer, intent(in) :: depth
      type(source_t), intent(inout) :: src
      logical, intent(out) :: stop_here
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: name, full
      type(error_t), allocatable :: inner

      stop_here = .false.
      name = ''
      if (rec%nf >= 2) name = rec%f(2)%s
      if (len(name) == 0) then
         call make_error(err, 'INCLude: expected a file name', rec%file, rec%line)
         return
      end if
      if (to_lower(name) == 'end') then
         stop_here = depth > 0
         return
      end if
      if (depth + 1 > MAX_INCLUDE_DEPTH) then
         call make_error(err, 'INCLude nested too deeply: expected a depth of at most 9', &
                         rec%file, rec%line)
         return
      end if
      if (name(1:1) == '/') then
         full = name
      else
         full = dirname(rec%file)//name
      end if
      call check_regular(full, inner)
      if (allocated(inner)) then
         call make_error(err, 'INCLude: '//inner%message, rec%file, rec%line)
         return
      end if
      call read_file(full, depth + 1, src, inner)
      if (allocated(inner)) call move_alloc(inner, err)
   end subroutine include_file

   !> Directory part of a path, with its trailing '/', or '' when there is none.
   pure function dirname(path) result(dir)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: dir
      integer :: k
      k = index(path, '/', back=.true.)
      dir = path(1:k)
   end function dirname

   !> Append `rec` to `src`, growing the array when full (an allocation failure is an error
   !> naming the record).
   subroutine append(src, rec, err)
      type(source_t), intent(inout) :: src
      type(record_t), intent(in) :: rec
      type(error_t), allocatable, intent(out) :: err
      integer :: stat
      call grow_record(src%rec, src%n + 1, stat)
      if (stat /= 0) then
         call make_error(err, 'out of memory after '//itoa(src%n)//' records: expected a '// &
                         'smaller deck', rec%file, rec%line)
         return
      end if
      src%n = src%n + 1
      src%rec(src%n) = rec
   end subroutine append

   !> Read one line into `line`, in time linear in its length. Blanks, tabs and CR beyond
   !> MAX_RECORD_LENGTH are dropped; the first other character beyond it stops the reading at
   !> once with `too_long` (the rest of the line is never read, so /dev/zero or a huge record
   !> costs no more than 256 characters). `eof` is true when there is no line left; `ios` is a
   !> read error other than end of file or of record (0: none), with its message in `msg`.
   subroutine get_line(unit, line, eof, too_long, ios, msg)
      use, intrinsic :: iso_fortran_env, only: iostat_eor, iostat_end
      integer, intent(in) :: unit
      character(len=:), allocatable, intent(out) :: line
      logical, intent(out) :: eof, too_long
      integer, intent(out) :: ios
      character(len=*), intent(inout) :: msg
      character(len=MAX_RECORD_LENGTH) :: keep
      character(len=512) :: buf
      integer :: sz, n, k, last

      eof = .false.
      too_long = .false.
      n = 0           ! characters read so far
      last = 0        ! position of the last kept character that is not a blank, tab or CR
      do
         read (unit, '(a)', advance='no', iostat=ios, size=sz, iomsg=msg) buf
         do k = 1, sz
            n = n + 1
            if (n <= MAX_RECORD_LENGTH) then
               keep(n:n) = buf(k:k)
               if (.not. is_blank(buf(k:k))) last = n
            else if (.not. is_blank(buf(k:k))) then
               too_long = .true.
               exit
            end if
         end do
         if (too_long .or. ios == iostat_eor) then
            ios = 0
            exit
         end if
         if (ios == iostat_end) then
            ios = 0
            eof = n == 0
            exit
         end if
         if (ios /= 0) exit
      end do
      line = keep(1:min(n, MAX_RECORD_LENGTH))
      if (.not. too_long .and. n > MAX_RECORD_LENGTH) line = keep(1:last)
   end subroutine get_line

   !> A blank, tab or carriage return.
   elemental logical function is_blank(c)
      character, intent(in) :: c
      is_blank = c == ' ' .or. c == achar(9) .or. c == achar(13)
   end function is_blank

   !> Build a record from one raw line.
   subroutine make_record(line, file, lineno, rec, err)
      character(len=*), intent(in) :: line, file
      integer, intent(in) :: lineno
      type(record_t), intent(out) :: rec
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: text
      character(len=16) :: buf
      integer :: k, code
      logical :: quoted

      rec%raw = line
      rec%file = file
      rec%line = lineno
      text = line
      do k = 1, len(text)
         if (text(k:k) == achar(9) .or. text(k:k) == achar(13)) text(k:k) = ' '
         code = iachar(text(k:k))
         if ((code >= 0 .and. code < 32) .or. code == 127) then
            call make_error(err, 'control character (code '//itoa(code)// &
                            ') in column '//itoa(k)//': expected text (a binary file?)', file, lineno)
            return
         end if
      end do
      if (len_trim(text) > MAX_RECORD_LENGTH) then
         write (buf, '(i0)') len_trim(text)
         call make_error(err, 'record has '//trim(buf)// &
                         ' characters: expected at most 256 characters per line', file, lineno)
         return
      end if
      quoted = .false.
      do k = 1, len(text)
         if (text(k:k) == '"') quoted = .not. quoted
         if (text(k:k) == '!' .and. .not. quoted) then
            text = text(1:k - 1)
            exit
         end if
      end do
      rec%text = trim(text)
      rec%blank = len_trim(text) == 0
      call split_fields(rec%text, rec%f, rec%nf, quoted)
      if (quoted) call make_error(err, 'unterminated double quote: expected a closing "', &
                                  file, lineno)
   end subroutine make_record

   !> Split `text` into fields (separators: comma, blank, `=`; `,,` = empty field; "..." quoted).
   !> `bad_quote` is true when a quote is not closed.
   pure subroutine split_fields(text, f, nf, bad_quote)
      character(len=*), intent(in) :: text
      type(field_t), allocatable, intent(out) :: f(:)
      integer, intent(out) :: nf
      logical, intent(out) :: bad_quote
      integer :: p, q, n

      allocate (f(8))
      nf = 0
      bad_quote = .false.
      n = len_trim(text)
      p = skip_blanks(text, 1, n)
      if (p > n) return
      do
         if (text(p:p) == '"') then
            q = index(text(p + 1:n), '"')
            if (q == 0) then
               bad_quote = .true.
               call add_field(f, nf, text(p + 1:n))
               return
            end if
            call add_field(f, nf, text(p + 1:p + q - 1))
            p = p + q + 1
         else if (text(p:p) == ',' .or. text(p:p) == '=') then
            call add_field(f, nf, '')
         else
            q = p
            do while (q <= n)
               if (scan(text(q:q), ' ,=') > 0) exit
               q = q + 1
            end do
            call add_field(f, nf, text(p:q - 1))
            p = q
         end if
         p = skip_blanks(text, p, n)
         if (p > n) exit
         if (text(p:p) == ',' .or. text(p:p) == '=') then
            p = skip_blanks(text, p + 1, n)
            if (p > n) exit
         end if
      end do
   end subroutine split_fields

   !> First non-blank position at or after `p` (n+1 when none).
   pure function skip_blanks(text, p, n) result(q)
      character(len=*), intent(in) :: text
      integer, intent(in) :: p, n
      integer :: q
      q = p
      do while (q <= n)
         if (text(q:q) /= ' ') exit
         q = q + 1
      end do
   end function skip_blanks

   !> Append one field, growing the array when full.
   pure subroutine add_field(f, nf, s)
      type(field_t), allocatable, intent(inout) :: f(:)
      integer, intent(inout) :: nf
      character(len=*), intent(in) :: s
      call grow_field(f, nf + 1)
      nf = nf + 1
      f(nf)%s = s
   end subroutine add_field

   !> The significant part of a keyword's display form: first 4 characters, lower case.
   pure function keyword_key(display) result(key)
      character(len=*), intent(in) :: display
      character(len=4) :: key
      key = to_lower(display(1:min(4, len_trim(display))))
   end function keyword_key

   !> True when `word` is the keyword `display` (first 4 characters, case-insensitive,
   !> blank-padded, so `END` matches `end` but `en` does not).
   pure logical function keyword_is(word, display)
      character(len=*), intent(in) :: word, display
      character(len=4) :: w
      w = to_lower(word(1:min(4, len(word))))
      keyword_is = w == keyword_key(display)
   end function keyword_is

   !> The keyword of `table` nearest to `word` (edit distance on the first 4 characters).
   pure function nearest_keyword(word, table) result(best)
      character(len=*), intent(in) :: word
      character(len=*), intent(in) :: table(:)
      character(len=:), allocatable :: best
      integer :: k, d, dbest
      character(len=4) :: w
      w = to_lower(word(1:min(4, len(word))))
      dbest = huge(1)
      best = ''
      do k = 1, size(table)
         d = edit_distance(trim(w), trim(keyword_key(table(k))))
         if (d < dbest) then
            dbest = d
            best = trim(table(k))
         end if
      end do
   end function nearest_keyword

   !> Levenshtein distance between two short strings.
   pure integer function edit_distance(a, b)
      character(len=*), intent(in) :: a, b
      integer :: d(0:len(a), 0:len(b))
      integer :: i, j, cost
      do i = 0, len(a)
         d(i, 0) = i
      end do
      do j = 0, len(b)
         d(0, j) = j
      end do
      do j = 1, len(b)
         do i = 1, len(a)
            cost = merge(0, 1, a(i:i) == b(j:j))
            d(i, j) = min(d(i - 1, j) + 1, d(i, j - 1) + 1, d(i - 1, j - 1) + cost)
         end do
      end do
      edit_distance = d(len(a), len(b))
   end function edit_distance

   !> grow (exic_base_grow) for an array of field_t: at least n entries (exactly n with `exact`),
   !> the contents kept, new entries default-initialized.
   pure subroutine grow_field(a, n, exact)
      type(field_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      logical, intent(in), optional :: exact
      type(field_t), allocatable :: tmp(:)
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n, exact)))
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_field

   !> grow (exic_base_grow) for the records of a source: at least n entries, the contents kept;
   !> stat /= 0 (and `a` unchanged) when the memory for them cannot be had.
   subroutine grow_record(a, n, stat)
      type(record_t), allocatable, intent(inout) :: a(:)
      integer, intent(in) :: n
      integer, intent(out) :: stat
      type(record_t), allocatable :: tmp(:)
      stat = 0
      if (.not. allocated(a)) allocate (a(0))
      if (size(a) >= n) return
      allocate (tmp(grow_size(size(a), n)), stat=stat)
      if (stat /= 0) return
      tmp(1:size(a)) = a
      call move_alloc(tmp, a)
   end subroutine grow_record

end module exic_input_deck_records
