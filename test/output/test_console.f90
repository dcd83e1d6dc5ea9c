!> What the exic command prints: the progress line (in place on a terminal, plain lines in a
!> log, nothing with -q) and the final summary, whose figures must be those of <stem>.ene and
!> <stem>.out.
!>
!> The program is the `exic` fpm built next to this test driver (build/<profile>/app/exic). The
!> terminal is a pseudo-terminal made by `script` (util-linux), whose typescript keeps every
!> byte the program wrote, carriage returns included.
module test_console
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use testing, only: suite_t, check, section, skip, have_command, file_text
   use deck_runner, only: run_dir, write_text, read_table, column
   implicit none
   private

   public :: run_console_tests

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: CR = achar(13)

contains

   subroutine run_console_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: exic
      call section(s, 'console: the progress line and the final summary')
      exic = exic_program()
      if (len(exic) == 0) then
         call skip(s, 'the exic command prints progress and a summary', 'the exic program next to the tests', 6)
         return
      end if
      call terminal_test(s, exic)
      call log_test(s, exic)
   end subroutine run_console_tests

   !> The exic program built with the tests ('' when there is none).
   function exic_program() result(path)
      character(len=:), allocatable :: path
      character(len=4096) :: argv0
      character(len=:), allocatable :: dir
      logical :: exists
      call get_command_argument(0, argv0)
      dir = argv0(1:index(argv0, '/', back=.true.))
      path = dir//'../app/exic'
      inquire (file=path, exist=exists)
      if (.not. exists) path = ''
   end function exic_program

   !> A bar striking a rigid wall, CFL step, to t = 0.5 (about 60 steps), histories every step.
   function console_deck() result(deck)
      character(len=:), allocatable :: deck
      deck = 'FEAP * * console output'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,12,2,0,0,1'//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,1,2,0,0,2'//nl//'    1,6.01,-1'//nl//'    2,7,-1'//nl// &
             '    3,7,2'//nl//'    4,6.01,2'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,1,0'//nl//nl// &
             'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'END'//nl// &
             'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl// &
             '  LOOP,,100000'//nl//'    TIME,,0.5'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,13,1'//nl//nl//'STOP'
   end function console_deck

   !> Under a pseudo-terminal: the line is rewritten in place and the summary follows; -q
   !> prints neither.
   subroutine terminal_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: base = run_dir//'/console_tty'
      character(len=:), allocatable :: text, quiet
      integer :: code
      if (.not. have_command('script')) then
         call skip(s, 'progress line on a terminal', 'script (util-linux)', 3)
         return
      end if
      call write_text(base//'.inp', console_deck())
      call execute_command_line('script -q -e -c "'//exic//' '//base//'.inp" '//base//'.tty < /dev/null > /dev/null', &
                                exitstat=code)
      text = file_text(base//'.tty')
      call check(s, code == 0 .and. index(text, CR//' 100.0 %  t ') > 0 .and. index(text, 'ETA') > 0 .and. &
                 index(text, 'steps/s') > 0 .and. index(text, 'drift') > 0, &
                 'on a terminal the progress line is rewritten in place (carriage return) up to 100 %', &
                 'exit code '//itoa(code)//'; see '//base//'.tty')
      call check(s, index(text, CR//'     ? %') == 0 .and. index(text, '%  t  ') > 0 .and. &
                 count_text(text, ' %  t ') >= 2, 'percentage, time, and more than one update', base//'.tty')
      call check_summary(s, text, base, 'terminal')
      call execute_command_line('script -q -e -c "'//exic//' -q '//base//'.inp" '//base//'_q.tty < /dev/null > /dev/null', &
                                exitstat=code)
      quiet = file_text(base//'_q.tty')
      call check(s, code == 0 .and. index(quiet, ' %  t ') == 0 .and. index(quiet, 'steps to t') == 0 .and. &
                 index(quiet, 'energy balance') == 0, '-q: no progress line and no summary on the terminal', &
                 base//'_q.tty')
   end subroutine terminal_test

   !> Standard output into a file: whole lines without carriage returns, then the summary.
   subroutine log_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: base = run_dir//'/console_log'
      character(len=:), allocatable :: text
      integer :: code
      call write_text(base//'.inp', console_deck())
      call execute_command_line(exic//' '//base//'.inp > '//base//'.log 2>&1', exitstat=code)
      text = file_text(base//'.log')
      call check(s, code == 0 .and. index(text, CR) == 0 .and. index(text, nl//' 100.0 %  t ') > 0, &
                 'into a file: whole progress lines, no carriage return, the last one at 100 %', base//'.log')
      call check_summary(s, text, base, 'log')
   end subroutine log_test

   !> The summary in `text` against <base>.ene (last row) and <base>.out.
   subroutine check_summary(s, text, base, tag)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: text, base, tag
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: ene(:, :)
      character(len=:), allocatable :: out
      real(wp) :: last(13)
      integer :: n
      logical :: ok
      call read_table(base//'.ene', names, ene)
      out = file_text(base//'.out')
      n = size(ene, 2)
      call check(s, n > 10 .and. size(ene, 1) >= 13, tag//': the run wrote its energy rows', base//'.ene')
      if (n <= 10 .or. size(ene, 1) < 13) return
      last = ene(1:13, n)
      ok = number_before(text, ' steps to t = ') == last(column(names, 'step')) .and. &
           near(number_after(text, 'steps to t = '), last(column(names, 't'))) .and. &
           near(number_after(text, ', kinetic '), last(column(names, 'kinetic'))) .and. &
           near(number_after(text, ', strain '), last(column(names, 'strain'))) .and. &
           near(number_after(text, ', external work '), last(column(names, 'external_work'))) .and. &
           near(number_after(text, ', contact work '), last(column(names, 'contact_work'))) .and. &
           near(number_after(text, 'balance: total '), last(column(names, 'total'))) .and. &
           near(number_after(text, ', drift '), last(column(names, 'drift')))
      call check(s, ok, tag//': summary steps, time and energy balance are those of the last .ene row', &
                 'step '//rtoa(last(column(names, 'step')))//' drift '//rtoa(last(column(names, 'drift'))))
      ok = same_line_after(text, out, 'element-steps per second ') .and. &
           same_line_after(text, out, 'largest penetration over the run ') .and. &
           same_line_after(text, out, 'wall time ')
      call check(s, ok, tag//': element-steps per second, largest penetration and wall time are those '// &
                 'of the .out', base//'.out')
   end subroutine check_summary

   !> The number that follows the first `label` in `text` (huge when there is none).
   real(wp) function number_after(text, label) result(x)
      character(len=*), intent(in) :: text, label
      integer :: i, j, ios
      x = huge(1.0_wp)
      i = index(text, label)
      if (i == 0) return
      i = i + len(label)
      j = i
      do while (j <= len(text))
         if (index('0123456789+-.eE', text(j:j)) == 0) exit
         j = j + 1
      end do
      if (j == i) return
      read (text(i:j - 1), *, iostat=ios) x
      if (ios /= 0) x = huge(1.0_wp)
   end function number_after

   !> The whole number just before the first `label` in `text` (huge when there is none).
   real(wp) function number_before(text, label) result(x)
      character(len=*), intent(in) :: text, label
      integer :: i, j, ios
      x = huge(1.0_wp)
      j = index(text, label)
      if (j <= 1) return
      i = j
      do while (i > 1)
         if (index('0123456789', text(i - 1:i - 1)) == 0) exit
         i = i - 1
      end do
      if (i == j) return
      read (text(i:j - 1), *, iostat=ios) x
      if (ios /= 0) x = huge(1.0_wp)
   end function number_before

   !> Both texts have `label` followed by the same characters up to the end of the line or ','.
   logical function same_line_after(a, b, label) result(same)
      character(len=*), intent(in) :: a, b, label
      same = rest(a, label) == rest(b, label) .and. len(rest(a, label)) > 0
   end function same_line_after

   !> What follows `label` in `text` up to a comma, a blank or the end of the line.
   function rest(text, label) result(r)
      character(len=*), intent(in) :: text, label
      character(len=:), allocatable :: r
      integer :: i, j
      r = ''
      i = index(text, label)
      if (i == 0) return
      i = i + len(label)
      j = scan(text(i:), ', '//nl//CR)
      if (j == 0) then
         r = text(i:)
      else
         r = text(i:i + j - 2)
      end if
   end function rest

   !> Equal to the 8 significant digits the summary prints.
   logical function near(x, y)
      real(wp), intent(in) :: x, y
      near = abs(x - y) <= 1.0e-7_wp*max(abs(x), abs(y)) + 1.0e-300_wp
   end function near

   !> Occurrences of `piece` in `text`.
   integer function count_text(text, piece) result(n)
      character(len=*), intent(in) :: text, piece
      integer :: i, k
      n = 0
      i = 1
      do
         k = index(text(i:), piece)
         if (k == 0) exit
         n = n + 1
         i = i + k + len(piece) - 1
         if (i > len(text)) exit
      end do
   end function count_text

end module test_console
