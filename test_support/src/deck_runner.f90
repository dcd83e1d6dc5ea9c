!> Test helpers: write a deck, run it through the library, read its tables back.
module deck_runner
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   implicit none
   private

   public :: run_dir, write_text, run_deck, read_table, column, file_has, replace_first

   !> Where test runs write their decks and outputs.
   character(len=*), parameter :: run_dir = 'build/test_runs'

contains

   !> Write `text` (lines separated by new_line) to `path`.
   subroutine write_text(path, text)
      character(len=*), intent(in) :: path, text
      integer :: u
      call execute_command_line('mkdir -p '//run_dir)
      open (newunit=u, file=path, status='replace', action='write')
      write (u, '(a)') text
      close (u)
   end subroutine write_text

   !> Write `text` as run_dir/<name>.inp, read it and run it quietly.
   !> `stage` is 0 on success, 1 if the reader failed, 2 if the run failed; `message` the error.
   subroutine run_deck(name, text, stage, message, model)
      character(len=*), intent(in) :: name, text
      integer, intent(out) :: stage
      character(len=:), allocatable, intent(out) :: message
      type(model_t), intent(out), optional :: model
      type(model_t) :: m
      type(run_options_t) :: opts
      type(error_t), allocatable :: err

      call write_text(run_dir//'/'//name//'.inp', text)
      message = ''
      stage = 0
      call read_deck(run_dir//'/'//name//'.inp', m, err)
      if (allocated(err)) then
         stage = 1
         message = err%message
         return
      end if
      opts%base = run_dir//'/'//name
      opts%quiet = .true.
      call run_model(m, opts, err)
      if (allocated(err)) then
         stage = 2
         message = err%message
      end if
      if (present(model)) model = m
   end subroutine run_deck

   !> Read a whitespace table with a '#' header: names(ncol) and data(ncol, nrow).
   subroutine read_table(path, names, data)
      character(len=*), intent(in) :: path
      character(len=64), allocatable, intent(out) :: names(:)
      real(wp), allocatable, intent(out) :: data(:, :)
      integer :: u, ios, nrow, ncol, k, i
      character(len=4096) :: line
      character(len=64) :: words(200)

      open (newunit=u, file=path, status='old', action='read')
      read (u, '(a)') line
      line = line(2:)
      ncol = 0
      do
         line = adjustl(line)
         if (len_trim(line) == 0) exit
         k = index(trim(line), ' ')
         if (k == 0) k = len_trim(line) + 1
         ncol = ncol + 1
         words(ncol) = line(:k - 1)
         line = line(k:)
      end do
      names = words(1:ncol)
      nrow = 0
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         nrow = nrow + 1
      end do
      allocate (data(ncol, nrow))
      rewind (u)
      read (u, '(a)') line
      do i = 1, nrow
         read (u, *) data(:, i)
      end do
      close (u)
   end subroutine read_table

   !> Index of column `name` in `names` (0 if absent).
   integer function column(names, name) result(k)
      character(len=*), intent(in) :: names(:)
      character(len=*), intent(in) :: name
      do k = 1, size(names)
         if (trim(names(k)) == name) return
      end do
      k = 0
   end function column

   !> True when a line of the file contains `text`.
   logical function file_has(path, text) result(found)
      character(len=*), intent(in) :: path, text
      character(len=4096) :: line
      integer :: u, ios
      found = .false.
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (index(line, text) > 0) then
            found = .true.
            exit
         end if
      end do
      close (u)
   end function file_has

   !> `text` with its first `old` replaced by `new` (unchanged when absent): a variant of a deck.
   function replace_first(text, old, new) result(out)
      character(len=*), intent(in) :: text, old, new
      character(len=:), allocatable :: out
      integer :: k
      k = index(text, old)
      out = text
      if (k > 0) out = text(:k - 1)//new//text(k + len(old):)
   end function replace_first

end module deck_runner
