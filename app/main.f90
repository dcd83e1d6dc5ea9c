!> The `exic` command: read a deck, run it, write <stem>.his/.ene/.out next to it or under -o DIR.
!>
!> Threads are asked for with OMP_NUM_THREADS (the results do not depend on their number); when it
!> is not set the command runs on one thread (doc/decisions.md, "Threads").
program exic_main
   use exic_base_error, only: error_t, fatal_error
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model, RUN_INTERRUPTED
   use exic_base_signals, only: ignore_file_size_signal, signals_install
   use exic_base_posix, only: make_directories, exit_now
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   !$ use omp_lib, only: omp_set_num_threads
   implicit none

   type(model_t) :: model
   type(run_options_t) :: opts
   type(error_t), allocatable :: err
   character(len=:), allocatable :: deck, outdir, arg
   integer :: i, n, nlen, status

   ! signals are recorded from here on (the run answers them after its steps, README): one that
   ! comes while the deck is read stops the run after its first step, with its files complete
   if (.not. signals_install()) write (error_unit, '(a)') 'exic: warning: cannot install the signal handlers'
   ! one thread unless OMP_NUM_THREADS asks for more: on a shared machine a thread waiting at a
   ! barrier for a preempted partner loses its time slice (doc/performance.md)
   call get_environment_variable('OMP_NUM_THREADS', length=nlen)
   !$ if (nlen == 0) call omp_set_num_threads(1)
   n = command_argument_count()
   outdir = ''
   deck = ''
   i = 1
   do while (i <= n)
      arg = argument(i)
      select case (arg)
      case ('-h', '--help')
         call usage()
         stop
      case ('--version')
         write (output_unit, '(a)') 'exic 0.1.0'
         stop
      case ('-o')
         if (i == n) call die('-o needs a directory')
         i = i + 1
         outdir = argument(i)
      case ('-q', '--quiet')
         opts%quiet = .true.
      case ('--restart')
         if (i == n) call die('--restart needs a restart file')
         i = i + 1
         opts%restart = argument(i)
      case default
         if (arg(1:1) == '-') call die('unknown option '//arg//' (see exic --help)')
         if (len(deck) > 0) call die('only one deck per run (got '//deck//' and '//arg//')')
         deck = arg
      end select
      i = i + 1
   end do
   if (len(deck) == 0) then
      call usage()
      stop 2, quiet=.true.
   end if

   call read_deck(deck, model, err)
   if (allocated(err)) call fatal_error(err, 2)
   if (allocated(model%warnings)) then
      if (len(model%warnings) > 0) write (error_unit, '(a)') model%warnings
   end if
   opts%base = output_base(deck, outdir)
   if (.not. opts%quiet) write (output_unit, '(a)') 'exic: '//deck//' -> '//opts%base//'.{his,ene,out}'
   ! SIGINT, SIGTERM, SIGUSR1, SIGUSR2 answered between steps (README); a write past the file
   ! size limit fails with EFBIG and is reported like a full disk instead of killing exic
   opts%signals = .true.
   call ignore_file_size_signal()
   call run_model(model, opts, err, status)
   if (allocated(err)) then
      ! every file of the run is closed (or its close failed and was reported): end without the
      ! library exit handlers (see exit_now)
      write (error_unit, '(a)') 'exic: error: '//err%message
      flush (error_unit)
      flush (output_unit)
      call exit_now(1)
   end if
   if (status == RUN_INTERRUPTED) then
      write (error_unit, '(a)') 'exic: interrupted; final state and restart file '//opts%base// &
         '.rst written (continue with --restart '//opts%base//'.rst)'
      stop 3, quiet=.true.
   end if
   if (.not. opts%quiet) write (output_unit, '(a)') 'exic: done'

contains

   !> Argument `k` as a string of its own length.
   function argument(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      integer :: l
      call get_command_argument(k, length=l)
      allocate (character(len=l) :: s)
      call get_command_argument(k, s)
   end function argument

   !> dir/stem of the outputs: the deck's stem, next to the deck or under `dir` (created with
   !> its parents by mkdir(2); no shell is involved).
   function output_base(path, dir) result(base)
      character(len=*), intent(in) :: path, dir
      character(len=:), allocatable :: base, stem, parent
      type(error_t), allocatable :: err
      integer :: slash, dot
      slash = index(path, '/', back=.true.)
      stem = path(slash + 1:)
      parent = path(:slash)
      dot = index(stem, '.', back=.true.)
      if (dot > 1) stem = stem(:dot - 1)
      if (len(dir) > 0) then
         call make_directories(dir, err)
         if (allocated(err)) call die('-o '//dir//': '//err%message)
         base = dir//'/'//stem
      else
         base = parent//stem
      end if
   end function output_base

   !> Print `msg` and stop with exit code 2.
   subroutine die(msg)
      character(len=*), intent(in) :: msg
      write (error_unit, '(a)') 'exic: '//msg
      stop 2, quiet=.true.
   end subroutine die

   !> The --help text.
   subroutine usage()
      write (output_unit, '(a)') &
         'usage: exic DECK [-o DIR] [-q] [--restart FILE]', &
         '', &
         'Runs the FEAP-like input deck DECK (see doc/input-language.md): explicit central-difference', &
         'dynamics of 2-D plane-strain bodies with implicit contact, and writes', &
         '  <stem>.his  time histories requested by TPLOt (a # header names the columns)', &
         '  <stem>.ene  energy balance and momentum', &
         '  <stem>.out  deck echo, mesh and material summary, stable step, energy balance, wall time', &
         '  <stem>.h5, <stem>.xdmf (last output time) and <stem>_series.xdmf (every one):', &
         '              fields, when the deck asks for OUTPut,HDF5 (doc/fields.md)', &
         'next to the deck, or under DIR with -o DIR. A progress line (percentage, time, step,', &
         'steps per second, wall time, ETA, energy drift) is shown as the run goes and a summary', &
         'at the end.', &
         '', &
         'options:', &
         '  -o DIR      write the outputs under DIR (created if missing)', &
         '  -q          no progress line and no final summary on the console', &
         '  --restart FILE  continue the run of DECK from the restart file FILE (BATCh SAVE', &
         '              writes <stem>.rst; the outputs are continued from that point)', &
         '  --version   print the version', &
         '  -h, --help  this text', &
         '', &
         'signals: SIGINT, SIGTERM  finish the step, write the final state and <stem>.rst, exit 3', &
         '         SIGUSR1          write <stem>.rst and go on', &
         '         SIGUSR2          print a status line (time, step, dt, energy balance, ETA)', &
         '', &
         'exit codes: 0 success, 1 the run failed (outputs kept up to the failure; an I/O error', &
         '            names the file), 2 bad input, 3 interrupted by SIGINT or SIGTERM'
   end subroutine usage

end program exic_main
