!> A small test harness: suites run by name, every check counts as one pass or one failure,
!> and a check that needs a tool this machine lacks counts as skipped.
!>
!> The driver (test/main.f90) registers every suite with `call runner%run(name, procedure)`;
!> `fpm test -- word [word ...]` runs only the suites whose name contains one of the words
!> (`fpm test -- --list` lists them). The last line is always `N passed, M failed`, the line
!> before it the number of skipped checks with the missing tools; the program stops with a
!> non-zero code on any failure.
module testing
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: suite_t, runner_t, suite_procedure, check, check_close, section, skip
   public :: have_command, have_python_modules, python_command, fpm_command, file_text
   public :: energy_of, gradient_error, error_text

   !> Running totals of one test run.
   type :: suite_t
      integer :: passed = 0
      integer :: failed = 0
      integer :: skipped = 0
      character(len=:), allocatable :: current
      character(len=:), allocatable :: missing     !< tools whose absence skipped checks
   end type suite_t

   abstract interface
      !> A suite: a procedure that runs its checks into `s`.
      subroutine suite_procedure(s)
         import :: suite_t
         type(suite_t), intent(inout) :: s
      end subroutine suite_procedure
      !> A total energy as a function of the nodal displacements (2, nnode).
      real(wp) function energy_of(u)
         import :: wp
         real(wp), intent(in) :: u(:, :)
      end function energy_of
   end interface

   !> Runs the suites the command line selects.
   type :: runner_t
      type(suite_t) :: s
      character(len=64), allocatable :: words(:)   !< selection words (none: every suite)
      logical :: list_only = .false.
      integer :: nrun = 0
   contains
      procedure :: init => runner_init
      procedure :: run => runner_run
      procedure :: finish => runner_finish
   end type runner_t

contains

   !> Read the selection words from the command line.
   subroutine runner_init(self)
      class(runner_t), intent(inout) :: self
      integer :: k, n, m
      character(len=64) :: arg
      character(len=64), allocatable :: words(:)
      n = command_argument_count()
      allocate (words(n))
      m = 0
      do k = 1, n
         call get_command_argument(k, arg)
         if (arg == '--list') then
            self%list_only = .true.
         else if (len_trim(arg) > 0) then
            m = m + 1
            words(m) = arg
         end if
      end do
      self%words = words(1:m)
      self%s%missing = ''
   end subroutine runner_init

   !> Run suite `name` when the selection asks for it.
   subroutine runner_run(self, name, suite)
      class(runner_t), intent(inout) :: self
      character(len=*), intent(in) :: name
      procedure(suite_procedure) :: suite
      integer :: k
      logical :: selected
      selected = size(self%words) == 0
      do k = 1, size(self%words)
         if (index(name, trim(self%words(k))) > 0) selected = .true.
      end do
      if (.not. selected) return
      if (self%list_only) then
         write (output_unit, '(a)') name
         return
      end if
      self%nrun = self%nrun + 1
      write (output_unit, '(a)') '#### suite '//name
      flush (output_unit)
      call suite(self%s)
   end subroutine runner_run

   !> The closing lines; stops with code 1 on any failure or when no suite was selected.
   subroutine runner_finish(self)
      class(runner_t), intent(inout) :: self
      if (self%list_only) return
      if (self%nrun == 0) then
         write (output_unit, '(a)') 'no suite matches the words given (fpm test -- --list lists them)'
         self%s%failed = self%s%failed + 1
      end if
      if (self%s%skipped > 0) write (output_unit, '(i0,a)') self%s%skipped, &
         ' skipped (missing: '//self%s%missing//')'
      write (output_unit, '(i0,a,i0,a)') self%s%passed, ' passed, ', self%s%failed, ' failed'
      flush (output_unit)
      if (self%s%failed > 0) error stop 1
   end subroutine runner_finish

   !> Start a named group of checks (printed as a heading).
   subroutine section(s, name)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      s%current = name
      write (output_unit, '(a)') '== '//name
      flush (output_unit)
   end subroutine section

   !> Record `ok` as one check called `name`; print failures with `detail`.
   subroutine check(s, ok, name, detail)
      type(suite_t), intent(inout) :: s
      logical, intent(in) :: ok
      character(len=*), intent(in) :: name
      character(len=*), intent(in), optional :: detail
      if (ok) then
         s%passed = s%passed + 1
         write (output_unit, '(a)') '   ok    '//name
      else
         s%failed = s%failed + 1
         if (present(detail)) then
            write (output_unit, '(a)') '   FAIL  '//name//': '//detail
         else
            write (output_unit, '(a)') '   FAIL  '//name
         end if
      end if
      flush (output_unit)
   end subroutine check

   !> Record `n` checks called `name` as skipped because `tool` is missing.
   subroutine skip(s, name, tool, n)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name, tool
      integer, intent(in), optional :: n
      integer :: k
      k = 1
      if (present(n)) k = n
      s%skipped = s%skipped + k
      write (output_unit, '(a)') '   SKIP  '//name//' ('//tool//' not found)'
      flush (output_unit)
      if (index(s%missing, tool) == 0) then
         if (len(s%missing) > 0) s%missing = s%missing//', '
         s%missing = s%missing//tool
      end if
   end subroutine skip

   !> Check |actual - expected| <= tol and report both values.
   subroutine check_close(s, actual, expected, tol, name)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: actual, expected, tol
      character(len=*), intent(in) :: name
      character(len=120) :: buf
      write (buf, '(a,es12.5,a,es12.5,a,es9.2,a,es9.2)') 'got ', actual, ' want ', expected, &
         ' |diff| ', abs(actual - expected), ' tol ', tol
      call check(s, abs(actual - expected) <= tol .and. actual == actual, name//'  ('//trim(buf)//')')
   end subroutine check_close

   !> A command of that name is on PATH (`name` is a fixed word of the test, never user text).
   logical function have_command(name) result(found)
      character(len=*), intent(in) :: name
      integer :: code, stat
      call execute_command_line('command -v '//name//' > /dev/null 2>&1', exitstat=code, cmdstat=stat)
      found = stat == 0 .and. code == 0
   end function have_command

   !> The Python that the tests run scripts with: the project's .venv when present, else python3.
   function python_command() result(cmd)
      character(len=:), allocatable :: cmd
      logical :: venv
      inquire (file='.venv/bin/python', exist=venv)
      if (venv) then
         cmd = '.venv/bin/python'
      else
         cmd = 'python3'
      end if
   end function python_command

   !> That Python imports every module of the comma-separated list `mods` (e.g. 'meshio,h5py').
   logical function have_python_modules(mods) result(found)
      character(len=*), intent(in) :: mods
      integer :: code, stat
      call execute_command_line(python_command()//' -c "import '//mods//'" > /dev/null 2>&1', &
                                exitstat=code, cmdstat=stat)
      found = stat == 0 .and. code == 0
   end function have_python_modules

   !> The fpm command the legacy host build uses: $EXIC_FPM, else fpm on PATH, else ''.
   function fpm_command() result(cmd)
      character(len=:), allocatable :: cmd
      integer :: l, stat
      call get_environment_variable('EXIC_FPM', length=l, status=stat)
      if (stat == 0 .and. l > 0) then
         allocate (character(len=l) :: cmd)
         call get_environment_variable('EXIC_FPM', cmd)
      else if (have_command('fpm')) then
         cmd = 'fpm'
      else
         cmd = ''
      end if
   end function fpm_command

   !> The whole content of a file ('' when it cannot be read).
   function file_text(path) result(text)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: text
      integer :: u, ios, n
      inquire (file=path, size=n)
      if (n <= 0) then
         text = ''
         return
      end if
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', &
            iostat=ios)
      if (ios /= 0) then
         text = ''
         return
      end if
      allocate (character(len=n) :: text)
      read (u, iostat=ios) text
      close (u)
   end function file_text

   !> max |fd - f| / max |f|: a force f against the central differences, step h, of the total
   !> energy at u (every dof in turn).
   real(wp) function gradient_error(u, f, h, energy) result(rel)
      real(wp), intent(in) :: u(:, :), f(:, :), h
      procedure(energy_of) :: energy
      real(wp) :: g(size(u, 1), size(u, 2)), fd(size(u, 1), size(u, 2)), ep, em
      integer :: i, j
      do j = 1, size(u, 2)
         do i = 1, size(u, 1)
            g = u
            g(i, j) = u(i, j) + h
            ep = energy(g)
            g(i, j) = u(i, j) - h
            em = energy(g)
            fd(i, j) = (ep - em)/(2.0_wp*h)
         end do
      end do
      rel = maxval(abs(fd - f))/maxval(abs(f))
   end function gradient_error

   !> The message of err, or 'no error' (the detail of a check on a call's error).
   function error_text(err) result(text)
      type(error_t), allocatable, intent(in) :: err
      character(len=:), allocatable :: text
      text = 'no error'
      if (allocated(err)) text = err%message
   end function error_text

end module testing
