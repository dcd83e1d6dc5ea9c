!> The XDMF text files of the field output: a whole file written to a temporary name and renamed
!> into place (`write_whole_file`, the last-state `<stem>.xdmf`), and a temporal collection that
!> grows by appending in place (`xdmf_series_t`, `<stem>_series.xdmf`). The layout and the
!> kill-safety argument are in doc/fields.md ("The XDMF files", "Kill safety").
!>
!> The series file is `head`, the grids written so far, a reserve of whitespace, `tail`. A new
!> grid G goes into the reserve so that the file is a well-formed document after every single
!> write, whatever prefix of it reached the file when the process died:
!>
!>   1. '-->' after the place G will end, then '!--' and '<' before it: the reserve now holds an
!>      empty comment (text such as '-->' or '!--' is legal character data inside an element);
!>   2. G inside that comment (a partly written G is a partly filled comment);
!>   3. '<' becomes ' ' (G is live; '!--' and '-->' are plain text), then those become blanks
!>      (G ends up between four spaces and two spaces and a newline: give it without either).
!>
!> Each write reaches the file (flush) before the next starts. G may not contain '--' (the
!> callers escape '-' in file names). When the reserve is too small, the file is written anew
!> to a temporary name with a reserve at least as large as its content (so the copying is paid
!> once per doubling) and renamed over the old one. Every write, close and rename is checked.
module exic_output_fields_xdmf
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_posix, only: rename_file
   implicit none
   private

   public :: xdmf_series_t, xdmf_write_t, append_writes, write_whole_file
   public :: xml_escape, real_text, data_item, attribute

   character(len=*), parameter :: NL = achar(10)
   !> Smallest reserve of a new or regrown series file, bytes.
   integer(i8), parameter :: RESERVE_MIN = 65536_i8
   !> Length of the lines the reserve is made of (spaces and a newline).
   integer, parameter :: RESERVE_LINE = 100

   !> One write of the append protocol: `text` at byte `offset` (0-based) of the file.
   type :: xdmf_write_t
      integer(i8) :: offset = 0
      character(len=:), allocatable :: text
   end type xdmf_write_t

   !> A temporal collection appended in place.
   type :: xdmf_series_t
      private
      character(len=:), allocatable :: path
      character(len=:), allocatable :: tail
      integer :: unit = 0                  !< the file, open for writing when `opened`
      logical :: opened = .false.
      integer(i8) :: free = 0              !< offset of the first byte of the reserve (0-based)
      integer(i8) :: tail_at = 0           !< offset of the tail (end of the reserve)
   contains
      procedure :: create => series_create
      procedure :: append => series_append
      procedure :: finish => series_finish
      procedure :: abandon => series_abandon
      procedure :: is_open => series_is_open
      procedure :: next_offset => series_next_offset
   end type xdmf_series_t

contains

   ! ---------------------------------------------------------------------------- the series

   !> Create `path`: `head`, a reserve, `tail` (written to '<path>.tmp' and renamed). `reserve`:
   !> the bytes the caller expects to append (the reserve is at least RESERVE_MIN).
   subroutine series_create(self, path, head, tail, err, reserve)
      class(xdmf_series_t), intent(inout) :: self
      character(len=*), intent(in) :: path, head, tail
      type(error_t), allocatable, intent(out) :: err
      integer(i8), intent(in), optional :: reserve
      integer(i8) :: r
      r = RESERVE_MIN
      if (present(reserve)) r = max(r, reserve)
      self%path = path
      self%tail = tail
      call rebuild(self, head, '', r, err)
   end subroutine series_create

   !> Append `grid` (text without '--') before the tail, keeping the file well-formed after every
   !> write (module header).
   subroutine series_append(self, grid, err)
      class(xdmf_series_t), intent(inout) :: self
      character(len=*), intent(in) :: grid
      type(error_t), allocatable, intent(out) :: err
      integer(i8) :: g, need
      integer :: k
      character(len=:), allocatable :: old
      type(xdmf_write_t) :: plan(6)
      logical :: bad

      if (.not. self%opened) then
         call make_error(err, "XDMF: '"//path_text(self)//"' is not open")
         return
      end if
      bad = len(grid) == 0
      if (.not. bad) bad = double_dash(grid) .or. grid(len(grid):) == '-'
      if (bad) then
         call make_error(err, "XDMF: a grid for '"//self%path//"' contains '--' or ends with '-'")
         return
      end if
      g = len(grid, i8)
      need = g + 7_i8
      if (self%free + need > self%tail_at) then
         ! too little room: copy the content so far into a new file with a larger reserve
         call read_bytes(self%path, 0_i8, self%free, old, err)
         if (allocated(err)) return
         call close_unit(self, err)
         if (allocated(err)) return
         call rebuild(self, old, '    '//grid//'  '//NL, max(RESERVE_MIN, self%free + need), err)
         return
      end if
      plan = append_writes(self%free, grid)
      do k = 1, size(plan)
         call put(self, plan(k)%offset, plan(k)%text, err)
         if (allocated(err)) return
      end do
      self%free = self%free + need
   end subroutine series_append

   !> The writes that put `grid` into the reserve starting at byte `free`, in the order they must
   !> reach the file (module header): each leaves a well-formed document, whatever prefix of it
   !> was written.
   pure function append_writes(free, grid) result(w)
      integer(i8), intent(in) :: free
      character(len=*), intent(in) :: grid
      type(xdmf_write_t) :: w(6)
      integer(i8) :: g
      g = len(grid, i8)
      w(1) = xdmf_write_t(free + 4_i8 + g, '-->')    ! 1. an empty comment around the place of G
      w(2) = xdmf_write_t(free + 1_i8, '!--')
      w(3) = xdmf_write_t(free, '<')
      w(4) = xdmf_write_t(free + 4_i8, grid)         ! 2. G inside it
      w(5) = xdmf_write_t(free, '    ')              ! 3. G live, the markers blank
      w(6) = xdmf_write_t(free + 4_i8 + g, '  '//NL)
   end function append_writes

   !> Offset at which the next grid's writes start (the first byte of the reserve).
   pure integer(i8) function series_next_offset(self) result(offset)
      class(xdmf_series_t), intent(in) :: self
      offset = self%free
   end function series_next_offset

   !> Write the file once more without its reserve (temporary name, rename) and close it.
   subroutine series_finish(self, err)
      class(xdmf_series_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: content
      if (.not. self%opened) return
      call read_bytes(self%path, 0_i8, self%free, content, err)
      if (.not. allocated(err)) call close_unit(self, err)
      if (.not. allocated(err)) call write_whole_file(self%path, content//self%tail, err)
      if (allocated(err)) call close_unit(self)
   end subroutine series_finish

   !> Close the file as it stands (on an error path: it is well-formed after every write).
   subroutine series_abandon(self)
      class(xdmf_series_t), intent(inout) :: self
      call close_unit(self)
   end subroutine series_abandon

   !> True between `create` and `finish`.
   pure logical function series_is_open(self)
      class(xdmf_series_t), intent(in) :: self
      series_is_open = self%opened
   end function series_is_open

   !> Write `content`, `grid`, a reserve of `reserve` bytes and the tail to '<path>.tmp', rename
   !> it over `path` and open it for the next appends.
   subroutine rebuild(self, content, grid, reserve, err)
      type(xdmf_series_t), intent(inout) :: self
      character(len=*), intent(in) :: content, grid
      integer(i8), intent(in) :: reserve
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: text
      character(len=RESERVE_LINE) :: line
      integer(i8) :: k, at, nfull
      integer :: ios
      character(len=256) :: msg

      ! the file in one piece: content, grid, the reserve in lines of RESERVE_LINE - 1 blanks
      ! and a newline (the last line cut short), the tail
      line = repeat(' ', RESERVE_LINE - 1)//NL
      allocate (character(len=len(content, i8) + len(grid, i8) + reserve + len(self%tail, i8)) :: text)
      at = 0
      text(at + 1:at + len(content)) = content
      at = at + len(content)
      text(at + 1:at + len(grid)) = grid
      at = at + len(grid)
      nfull = reserve/RESERVE_LINE
      do k = 1, nfull
         text(at + 1:at + RESERVE_LINE) = line
         at = at + RESERVE_LINE
      end do
      text(at + 1:at + reserve - nfull*RESERVE_LINE) = ''
      at = at + reserve - nfull*RESERVE_LINE
      text(at + 1:) = self%tail
      call write_whole_file(self%path, text, err)
      if (allocated(err)) return
      self%free = len(content, i8) + len(grid, i8)
      self%tail_at = self%free + reserve
      open (newunit=self%unit, file=self%path, access='stream', form='unformatted', status='old', &
            action='write', iostat=ios, iomsg=msg)
      self%opened = ios == 0
      if (ios /= 0) call make_error(err, "XDMF: cannot open '"//self%path//"' for appending: "//trim(msg))
   end subroutine rebuild

   !> Write `text` at byte offset `offset` (0-based) of the open file and flush it to the system.
   subroutine put(self, offset, text, err)
      type(xdmf_series_t), intent(inout) :: self
      integer(i8), intent(in) :: offset
      character(len=*), intent(in) :: text
      type(error_t), allocatable, intent(out) :: err
      integer :: ios
      character(len=256) :: msg
      write (self%unit, pos=offset + 1_i8, iostat=ios, iomsg=msg) text
      if (ios == 0) flush (self%unit, iostat=ios, iomsg=msg)
      if (ios /= 0) call make_error(err, "XDMF: cannot write to '"//self%path//"': "//trim(msg))
   end subroutine put

   !> Close the file; a failing close sets `err` when present.
   subroutine close_unit(self, err)
      type(xdmf_series_t), intent(inout) :: self
      type(error_t), allocatable, intent(out), optional :: err
      integer :: ios
      character(len=256) :: msg
      if (.not. self%opened) return
      close (self%unit, iostat=ios, iomsg=msg)
      self%opened = .false.
      if (ios /= 0 .and. present(err)) &
         call make_error(err, "XDMF: cannot close '"//self%path//"': "//trim(msg))
   end subroutine close_unit

   !> The path for messages.
   function path_text(self) result(s)
      type(xdmf_series_t), intent(in) :: self
      character(len=:), allocatable :: s
      s = 'the XDMF series'
      if (allocated(self%path)) s = self%path
   end function path_text

   ! ---------------------------------------------------------------------------- whole files

   !> Write `text` to '<path>.tmp', close it, check its size and rename it over `path`, so that
   !> `path` is always either the old or the new complete file. Every step is checked; on a
   !> failure the temporary file is removed and `path` is left as it was.
   subroutine write_whole_file(path, text, err)
      character(len=*), intent(in) :: path, text
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: tmp
      character(len=256) :: msg
      integer :: u, ios
      integer(i8) :: size_on_disk

      tmp = path//'.tmp'
      open (newunit=u, file=tmp, access='stream', form='unformatted', status='replace', &
            action='write', iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call make_error(err, "cannot write '"//tmp//"': "//trim(msg))
         return
      end if
      write (u, iostat=ios, iomsg=msg) text
      if (ios /= 0) then
         close (u, status='delete', iostat=ios)
         call make_error(err, "cannot write '"//tmp//"': "//trim(msg))
         return
      end if
      close (u, iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call delete_file(tmp)
         call make_error(err, "cannot close '"//tmp//"': "//trim(msg))
         return
      end if
      inquire (file=tmp, size=size_on_disk, iostat=ios)
      if (ios /= 0 .or. size_on_disk /= len(text, i8)) then
         call delete_file(tmp)
         call make_error(err, "'"//tmp//"' is not complete after writing it (disk full?)")
         return
      end if
      call rename_file(tmp, path, err)
   end subroutine write_whole_file

   !> Remove `path` if it exists (failures are ignored: this only tidies up after an error).
   subroutine delete_file(path)
      character(len=*), intent(in) :: path
      integer :: u, ios
      open (newunit=u, file=path, status='old', iostat=ios)
      if (ios == 0) close (u, status='delete', iostat=ios)
   end subroutine delete_file

   !> Bytes [offset, offset + n) of the file `path`.
   subroutine read_bytes(path, offset, n, text, err)
      character(len=*), intent(in) :: path
      integer(i8), intent(in) :: offset, n
      character(len=:), allocatable, intent(out) :: text
      type(error_t), allocatable, intent(out) :: err
      integer :: u, ios
      character(len=256) :: msg
      allocate (character(len=n) :: text)
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', &
            iostat=ios, iomsg=msg)
      if (ios == 0 .and. n > 0) read (u, pos=offset + 1_i8, iostat=ios, iomsg=msg) text
      if (ios /= 0) call make_error(err, "XDMF: cannot read back '"//path//"': "//trim(msg))
      close (u, iostat=ios)
   end subroutine read_bytes

   ! ---------------------------------------------------------------------------- XML text

   !> One DataItem line: `dims`, number type and precision, and where the data are.
   function data_item(dims, number_type, precision, where) result(s)
      character(len=*), intent(in) :: dims, number_type, precision, where
      character(len=:), allocatable :: s
      s = '          <DataItem Dimensions="'//dims//'" NumberType="'//number_type// &
          '" Precision="'//precision//'" Format="HDF">'//where//'</DataItem>'//NL
   end function data_item

   !> One Attribute element around `item`.
   function attribute(name, attr_type, center, item) result(s)
      character(len=*), intent(in) :: name, attr_type, center, item
      character(len=:), allocatable :: s
      s = '        <Attribute Name="'//name//'" AttributeType="'//attr_type//'" Center="'// &
          center//'">'//NL//item//'        </Attribute>'//NL
   end function attribute

   !> `s` with &, <, > and " replaced by XML entities, and '-' by a character reference when
   !> `dash` is true (text that may sit inside a comment cannot contain '--').
   function xml_escape(s, dash) result(r)
      character(len=*), intent(in) :: s
      logical, intent(in), optional :: dash
      character(len=:), allocatable :: r
      integer :: i
      logical :: escape_dash
      escape_dash = .false.
      if (present(dash)) escape_dash = dash
      r = ''
      do i = 1, len(s)
         select case (s(i:i))
         case ('&')
            r = r//'&amp;'
         case ('<')
            r = r//'&lt;'
         case ('>')
            r = r//'&gt;'
         case ('"')
            r = r//'&quot;'
         case ('-')
            if (escape_dash) then
               r = r//'&#45;'
            else
               r = r//'-'
            end if
         case default
            r = r//s(i:i)
         end select
      end do
   end function xml_escape

   !> Real as text with 17 significant digits (round-trips exactly).
   function real_text(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(es24.16e3)') x
      s = trim(adjustl(buf))
   end function real_text

   !> True when s holds "--" somewhere: a count over every pair of neighbours as one vector loop
   !> (a batch's grids are hundreds of kB; `index` compares them byte by byte, about 10
   !> instructions a byte).
   pure logical function double_dash(s) result(found)
      character(len=*), intent(in) :: s
      integer(i8) :: i, n
      n = 0
      do i = 1, len(s, i8) - 1
         n = n + merge(1_i8, 0_i8, s(i:i) == '-')*merge(1_i8, 0_i8, s(i + 1:i + 1) == '-')
      end do
      found = n > 0
   end function double_dash

end module exic_output_fields_xdmf
