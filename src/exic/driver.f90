!> The BATCh interpreter (spec section 5): runs a model's solution program command by command.
!>
!> The step itself is src/exic/explicit/step.f90 (`stepper_t`), the files src/exic/io/output.f90
!> and src/exic/io/report.f90; this module only decides, command by command, what to call.
module exic_driver
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use exic_base_kinds, only: wp, i8
   use exic_base_constants, only: TIME_TOL
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_progress, only: progress_t, clock_text
   use exic_base_strings, only: itoa, rtoa
   use exic_base_signals, only: signals_install, signals_take, SIG_BIT_INT, SIG_BIT_TERM, SIG_BIT_USR1, &
                                SIG_BIT_USR2
   use exic_io_model, only: model_t
   use exic_io_restart, only: run_position_t, write_restart, read_restart
   use exic_io_program, only: MAX_LOOP_DEPTH
   use exic_io_output, only: output_t
   use exic_io_report, only: report_preamble, report_summary, report_final, console_summary, &
                             energy_balance
   use exic_explicit_step, only: stepper_t
   use exic_contact_inside, only: inside_t
   use exic_base_constants, only: PENETRATION_WARN
   implicit none
   private

   public :: run_options_t, run_model, fields_observer

   !> How run_model ended (its `status`): the program ran to its end, or SIGINT/SIGTERM stopped
   !> it after a step with its final state and a restart file written (exit code 3 of `exic`).
   integer, parameter, public :: RUN_COMPLETE = 0, RUN_INTERRUPTED = 3
   !> Steps between two geometric penetration checks besides the field output times and the end.
   integer, parameter :: INSIDE_STEPS = 1000

   abstract interface
      !> Told after each field output time is written and flushed: how many there are and t.
      subroutine fields_observer(count, t)
         import :: wp
         integer, intent(in) :: count
         real(wp), intent(in) :: t
      end subroutine fields_observer
   end interface

   !> How a run is made.
   type :: run_options_t
      character(len=:), allocatable :: base   !< output path without extension: dir/stem
      logical :: quiet = .false.              !< no progress line and no summary on the console
      character(len=:), allocatable :: restart !< continue from this restart file (else the deck's
                                               !< RESTart file, else none)
      logical :: signals = .false.            !< answer SIGINT, SIGTERM, SIGUSR1, SIGUSR2 (README)
      !> called after every field output time, when associated (a library user following the run)
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_options_t

   !> A run: the step, its outputs and the console.
   type :: run_t
      type(stepper_t) :: stp
      type(output_t) :: out
      type(progress_t) :: progress
      type(run_position_t) :: pos              !< program position and schedules (saved in restarts)
      character(len=:), allocatable :: rst     !< <stem>.rst
      logical :: signals = .false.
      logical :: interrupted = .false.         !< SIGINT or SIGTERM came: stop after this step
      real(wp) :: wall_start = 0.0_wp
      real(wp) :: t_start = 0.0_wp             !< simulated time when this process began stepping
      integer(i8) :: saved_step = -1           !< step of the last restart file written
      type(inside_t) :: inside                 !< geometric penetration check (with contact)
      integer(i8) :: inside_step = -1          !< step of its last check
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_t

contains

   !> Run `model`'s program, or continue it from a restart file (opts%restart, or the deck's
   !> RESTart). On error, every output written so far is kept and closed. `status`: RUN_COMPLETE,
   !> or RUN_INTERRUPTED when a SIGINT or SIGTERM stopped the run (opts%signals).
   subroutine run_model(model, opts, err, status)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(error_t), allocatable, intent(out) :: err
      integer, intent(out), optional :: status
      type(run_t) :: r
      type(error_t), allocatable :: ferr
      real(wp) :: wall_start, wall
      character(len=:), allocatable :: field_files, restart

      wall_start = wall_time()
      r%wall_start = wall_start
      r%on_fields => opts%on_fields
      r%rst = opts%base//'.rst'
      restart = ''
      if (allocated(model%restart_file)) restart = model%restart_file
      if (allocated(opts%restart)) then
         if (len(opts%restart) > 0) restart = opts%restart
      end if
      if (opts%signals) then
         r%signals = signals_install()
         if (.not. r%signals) write (error_unit, '(a)') 'exic: warning: cannot install the signal handlers'
      end if
      if (len(restart) > 0) then
         call resume(r, model, opts%base, restart, err)
      else
         call r%out%open(opts%base, err)
         if (.not. allocated(err)) call report_preamble(r%out%files, model)
         if (.not. allocated(err)) call r%stp%init(model%mesh, model%materials, model%contact, err, model%loads)
         if (.not. allocated(err)) call report_summary(r%out%files, model, r%stp)
      end if
      ! the .out holds the deck and the model before the first step
      call r%out%files%flush_all()
      if (.not. allocated(err)) then
         call init_inside(r, model, err)
      end if
      if (.not. allocated(err)) then
         call r%progress%begin(opts%quiet)
         r%t_start = r%stp%st%t
         call execute(r, model, err)
      end if
      if (.not. allocated(err) .and. allocated(r%out%files%io_error)) &
         call make_error(err, r%out%files%io_error)
      ! the restart file of the end (SAVE) or of the interruption comes before the final rows
      ! and fields: a run continued from it writes them again, as the run that went on would
      ! (an interruption wrote its restart file after its step, in after_step)
      if (.not. allocated(err) .and. r%stp%started .and. r%pos%save_on .and. .not. r%interrupted .and. &
          r%saved_step /= r%stp%st%step) then
         r%pos%pc = size(model%program)
         call save_restart(r, model, err)
      end if
      ! the final state is always written; after a failure, its fields are (doc/fields.md)
      if (r%stp%started .and. .not. allocated(err)) then
         call r%out%final(model, r%stp, ferr)
         if (allocated(ferr)) then
            call r%out%files%say('error: '//ferr%message)
            call move_alloc(ferr, err)
         end if
      else if (r%stp%started) then
         call r%out%failed(r%stp, err%message, ferr)
         if (allocated(ferr)) call r%out%files%say('error: '//ferr%message)
      end if
      call pass_messages(r)
      if (r%stp%started) call check_inside(r)
      if (r%stp%started) call finish_progress(r)
      field_files = ''
      if (r%out%field_dt > 0.0_wp) field_files = ' '//opts%base//'.h5 '//opts%base//'.xdmf '// &
                                                 opts%base//'_series.xdmf'
      wall = wall_time() - wall_start
      call report_final(r%out%files, r%stp, err, wall, field_files, r%inside)
      call r%out%close()
      if (.not. allocated(err) .and. allocated(r%out%files%io_error)) &
         call make_error(err, r%out%files%io_error)
      if (.not. opts%quiet .and. r%stp%started) write (output_unit, '(a)') console_summary(r%stp, wall, r%inside)
      if (present(status)) status = merge(RUN_INTERRUPTED, RUN_COMPLETE, r%interrupted .and. .not. allocated(err))
   end subroutine run_model

   !> Set the run up from the restart file `path`: the stepper made from the model, then its
   !> state, the output schedules and the program position read; the outputs continued.
   subroutine resume(r, model, base, path, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      character(len=*), intent(in) :: base, path
      type(error_t), allocatable, intent(out) :: err
      call r%stp%init(model%mesh, model%materials, model%contact, err, model%loads)
      if (allocated(err)) return
      call read_restart(path, model, r%stp, r%out, r%pos, err)
      if (allocated(err)) return
      call r%out%resume(base, model, r%stp, err)
      if (allocated(err)) return
      r%pos%pc = r%pos%pc + 1
      call r%out%files%say('')
      call r%out%files%say('restarted from '//path//' at t = '//rtoa(r%stp%st%t)//', step '// &
                           itoa(int(r%stp%st%step)))
   end subroutine resume

   !> Write the restart file of the state now (the files flushed and measured first).
   subroutine save_restart(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      call r%out%checkpoint()
      call write_restart(r%rst, model, r%stp, r%out, r%pos, err)
      if (allocated(err)) return
      r%saved_step = r%stp%st%step
      call r%out%files%say('restart file '//r%rst//' written at t = '//rtoa(r%stp%st%t)//', step '// &
                           itoa(int(r%stp%st%step)))
   end subroutine save_restart

   !> Interpret the BATCh program.
   subroutine execute(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: pc, depth, nfields
      integer :: remaining(MAX_LOOP_DEPTH)

      pc = r%pos%pc
      depth = r%pos%depth
      remaining = r%pos%remaining
      do while (pc <= size(model%program))
         associate (c => model%program(pc))
            select case (c%name)
            case ('tran', 'prop')
               continue          ! PROPortional: the functions hold for the whole run (read with the deck)
            case ('dt')
               if (c%option == 'cfl') then
                  call r%stp%set_cfl(c%v(1), c%where, err)
               else
                  call r%stp%set_fixed_dt(c%v(1), c%where, err)
               end if
            case ('loop')
               depth = depth + 1
               remaining(depth) = nint(c%v(1))
               if (remaining(depth) <= 0) then
                  pc = c%jump
                  depth = depth - 1
               end if
            case ('next')
               remaining(depth) = remaining(depth) - 1
               if (remaining(depth) > 0) then
                  pc = c%jump
               else
                  depth = depth - 1
               end if
            case ('time')
               call start(r, model, err)
               if (.not. allocated(err)) call r%out%record(model, r%stp)
               nfields = r%out%fields%count()
               if (.not. allocated(err)) call r%out%fields_due(r%stp, err)
               if (.not. allocated(err) .and. r%out%fields%count() > nfields .and. associated(r%on_fields)) &
                  call r%on_fields(r%out%fields%count(), r%stp%st%t)
               if (.not. allocated(err) .and. (r%out%fields%count() > nfields .or. &
                                               r%stp%st%step - r%inside_step >= INSIDE_STEPS)) call check_inside(r)
               if (.not. allocated(err) .and. c%v(1) > 0.0_wp) then
                  r%stp%tmax = c%v(1)
                  if (r%stp%st%t >= r%stp%tmax*(1.0_wp - TIME_TOL) .and. depth > 0) then
                     pc = find_next(model, pc)   ! leave the innermost loop
                     depth = depth - 1
                  end if
               end if
            case ('form')
               call start(r, model, err)
               if (.not. allocated(err)) call step(r, err)
               if (.not. allocated(err)) then
                  r%pos%pc = pc
                  r%pos%depth = depth
                  r%pos%remaining = remaining
                  call after_step(r, model, err)
                  if (r%interrupted .and. .not. allocated(err)) return
               end if
            case ('tplo')
               r%out%his_inc = max(1, nint(c%v(1)))
            case ('init')
               call r%stp%set_velocity(c%given, c%data)
            case ('outp')
               call r%out%open_fields(model, r%stp, c%v(1), err)
            case ('prin')
               r%pos%print_inc = max(1, nint(c%v(1)))
            case ('save')
               r%pos%save_on = .true.
               r%pos%save_dt = c%v(1)
               r%pos%save_next = r%stp%st%t + c%v(1)
            case ('chec')
               if (c%option == 'pene') then
                  r%inside%fraction = c%v(1)
               else
                  call r%stp%set_energy_limits(c%v(1), c%v(2))
               end if
            case default
               call make_error(err, 'solution command '//trim(c%name)//' is not implemented', c%where)
            end select
         end associate
         if (allocated(err)) return
         pc = pc + 1
      end do
   end subroutine execute

   !> The geometric penetration check (src/exic/contact/inside.f90) over the regions, for the
   !> pairs of regions that the contact passes cover; nothing without contact.
   subroutine init_inside(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: k, j
      if (.not. r%stp%contact%active) return
      call r%inside%init(r%stp%st%nnode, size(model%mesh%conn, 2), model%mesh%conn, model%mesh%region, &
                         PENETRATION_WARN, err)
      if (allocated(err)) return
      associate (c => r%stp%contact)
         ! the passes of the PAIRs, and every pair of AUTOmatic surfaces (whose passes are made
         ! per step for the surfaces found near)
         do k = 1, c%nfixed
            call r%inside%allow(c%surfaces(c%passes(k)%slave)%nodes, c%surfaces(c%passes(k)%master)%nodes)
         end do
         if (c%auto_pass%auto) then
            do k = c%auto_first + 1, size(c%surfaces)
               do j = c%auto_first + 1, size(c%surfaces)
                  if (j /= k) call r%inside%allow(c%surfaces(k)%nodes, c%surfaces(j)%nodes)
               end do
            end do
         end if
      end associate
   end subroutine init_inside

   !> Check the positions now for nodes inside other bodies; warnings go to <stem>.out and the
   !> console.
   subroutine check_inside(r)
      type(run_t), intent(inout) :: r
      character(len=:), allocatable :: warn
      if (.not. r%inside%active) return
      if (r%inside_step == r%stp%st%step) return
      r%inside_step = r%stp%st%step
      call r%inside%check(r%stp%st%x0 + r%stp%st%u, r%stp%st%t, warn)
      if (len(warn) > 0) call r%stp%messages%add(warn)
      call pass_messages(r)
   end subroutine check_inside

   !> Index of the NEXT that closes the innermost loop around command `pc`.
   integer function find_next(model, pc) result(k)
      type(model_t), intent(in) :: model
      integer, intent(in) :: pc
      integer :: level
      level = 0
      do k = pc + 1, size(model%program)
         select case (model%program(k)%name)
         case ('loop')
            level = level + 1
         case ('next')
            if (level == 0) return
            level = level - 1
         end select
      end do
      k = size(model%program)
   end function find_next

   !> First use of the state: the history header, then the state at t = 0.
   subroutine start(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      if (r%stp%started) return
      call r%out%begin(model)
      call r%stp%start(err)
   end subroutine start

   !> FORM,EXPLicit: one step, then its messages, the energy line and the progress line.
   subroutine step(r, err)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: total, drift
      call r%stp%advance(err)
      call pass_messages(r)
      if (allocated(err)) return
      associate (st => r%stp%st)
         if (r%pos%print_inc > 0) then
            if (mod(st%step, int(r%pos%print_inc, i8)) == 0) then
               call r%progress%clear()
               print '(a,es12.5,a,i0,a,es12.5,a,es12.5,a,es12.5,a,es12.5)', ' t=', st%t, ' step ', st%step, &
                  ' K=', st%kinetic, ' U=', st%strain + st%hourglass, ' Wext=', st%wext, ' Wc=', st%wcon
            end if
         end if
         if (r%progress%due()) then
            call energy_balance(st, total, drift)
            call r%progress%show(st%t, r%stp%tmax, st%dt, st%step, drift)
         end if
      end associate
   end subroutine step

   !> After a step: a write failure of the text files stops the run; the SAVE interval; the
   !> signals that came during the step (once per step: the handlers only record them).
   subroutine after_step(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: bits
      logical :: due
      if (allocated(r%out%files%io_error)) then
         call make_error(err, r%out%files%io_error)
         return
      end if
      due = .false.
      if (r%pos%save_on .and. r%pos%save_dt > 0.0_wp) then
         if (r%stp%st%t >= r%pos%save_next*(1.0_wp - TIME_TOL)) then
            due = .true.
            do while (r%pos%save_next <= r%stp%st%t*(1.0_wp + TIME_TOL))
               r%pos%save_next = r%pos%save_next + r%pos%save_dt
            end do
         end if
      end if
      bits = 0
      if (r%signals) bits = signals_take()
      if (iand(bits, SIG_BIT_USR2) /= 0) call status_line(r)
      if (iand(bits, SIG_BIT_USR1) /= 0) due = .true.
      if (iand(bits, SIG_BIT_INT + SIG_BIT_TERM) /= 0) then
         r%interrupted = .true.
         due = .true.
         call r%progress%clear()
         write (error_unit, '(a)') 'exic: '//trim(merge('SIGINT ', 'SIGTERM', iand(bits, SIG_BIT_INT) /= 0))// &
            ' at t = '//rtoa(r%stp%st%t)//', step '//itoa(int(r%stp%st%step))// &
            ': writing the final state and the restart file '//r%rst
         call r%out%files%say('interrupted by a signal at t = '//rtoa(r%stp%st%t)//', step '// &
                              itoa(int(r%stp%st%step)))
      end if
      if (due) call save_restart(r, model, err)
   end subroutine after_step

   !> SIGUSR2: one line on standard error: time, step, dt, energy balance, wall time, ETA.
   subroutine status_line(r)
      type(run_t), intent(inout) :: r
      real(wp) :: total, drift, wall, eta
      character(len=:), allocatable :: eta_text
      call energy_balance(r%stp%st, total, drift)
      wall = wall_time() - r%wall_start
      eta_text = 'unknown'
      if (r%stp%tmax > r%stp%st%t .and. r%stp%st%t > r%t_start) then
         eta = wall*(r%stp%tmax - r%stp%st%t)/(r%stp%st%t - r%t_start)
         eta_text = trim(clock_text(eta))
      end if
      call r%progress%clear()
      write (error_unit, '(a)') 'exic: status: t = '//rtoa(r%stp%st%t)//' of '//rtoa(r%stp%tmax)// &
         ', step '//itoa(int(r%stp%st%step))//', dt = '//rtoa(r%stp%st%dt)//', energy balance '// &
         rtoa(total)//' (drift '//rtoa(drift)//'), wall '//trim(clock_text(wall))//', ETA '//eta_text
      flush (error_unit)
   end subroutine status_line

   !> The progress line of the state the run ended in.
   subroutine finish_progress(r)
      type(run_t), intent(inout) :: r
      real(wp) :: total, drift
      call energy_balance(r%stp%st, total, drift)
      call r%progress%finish(r%stp%st%t, r%stp%tmax, r%stp%st%dt, r%stp%st%step, drift)
   end subroutine finish_progress

   !> Move what the stepper has to report into <stem>.out, and its warnings to the console.
   subroutine pass_messages(r)
      type(run_t), intent(inout) :: r
      character(len=:), allocatable :: text
      if (r%stp%messages%count == 0) return
      text = r%stp%messages%take()
      call r%progress%clear()
      call r%out%files%say(text)
      write (error_unit, '(a)') 'exic: '//text
      flush (error_unit)
   end subroutine pass_messages

end module exic_driver
