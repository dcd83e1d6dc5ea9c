!> The BATCh interpreter (spec section 5): runs a model's solution program command by command.
!>
!> The step itself is src/exic/explicit/step.f90 (`stepper_t`), the files src/exic/output.f90
!> and src/exic/output/text/report.f90, what is done around a step (restart files, signals, the
!> penetration check) src/exic/session/run.f90; this module only decides, command by command,
!> what to call.
module exic_driver
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use exic_base_kinds, only: wp
   use exic_base_constants, only: TIME_TOL
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_signals, only: signals_install
   use exic_explicit_energy, only: model_energies
   use exic_model_model, only: model_t
   use exic_model_program, only: MAX_LOOP_DEPTH, loop_end
   use exic_output_text_report, only: report_preamble, report_summary, report_final, console_summary
   use exic_session_run, only: fields_observer, run_t, resume, save_restart, init_inside, &
                               check_inside, start, step, after_step, finish_progress, pass_messages, &
                              gather_nodes_due
   use exic_explicit_decomposition_nodes, only: decomposition_gather_nodes
   implicit none
   private

   public :: run_options_t, run_model, fields_observer

   !> How run_model ended (its `status`): the program ran to its end, or SIGINT/SIGTERM stopped
   !> it after a step with its final state and a restart file written (exit code 3 of `exic`).
   integer, parameter, public :: RUN_COMPLETE = 0, RUN_INTERRUPTED = 3

   !> How a run is made.
   type :: run_options_t
      character(len=:), allocatable :: base   !< output path without extension: dir/stem
      logical :: quiet = .false.              !< no progress line and no summary on the console
      character(len=:), allocatable :: restart !< continue from this restart file (else the deck's
                                               !< RESTart file, else none)
      logical :: signals = .false.            !< answer SIGINT, SIGTERM, SIGUSR1, SIGUSR2 (README)
      !> called after every flush of the field file (doc/fields.md, "Batches"), when associated (a
      !> library user following the run)
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_options_t

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
      logical :: ran    ! the program was interpreted (a run whose resume failed did not step)

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
         call r%out%open(opts%base, err, model_energies(model%materials))
         if (.not. allocated(err)) call report_preamble(r%out%files, model)
         if (.not. allocated(err)) call r%stp%init(model%mesh, model%materials, model%contact, err, model%loads)
         if (.not. allocated(err)) call report_summary(r%out%files, model, r%stp)
      end if
      ! the .out holds the deck and the model before the first step
      call r%out%files%flush_all()
      if (.not. allocated(err)) then
         call init_inside(r, model, err)
      end if
      ran = .false.
      if (.not. allocated(err)) then
         ! the wall time of the progress line counts from here, its ETA from the time reached
         call r%progress%begin(opts%quiet, r%stp%st%t)
         r%t_start = r%stp%st%t
         ran = .true.
         call execute(r, model, err)
      end if
      if (.not. allocated(err) .and. allocated(r%out%files%io_error)) &
         call make_error(err, r%out%files%io_error)
      ! the whole nodal state for what follows (divided among MPI ranks, doc/parallel.md; after a
      ! stepper's error it is gathered already)
      if (.not. allocated(err) .and. ran .and. r%stp%started) call decomposition_gather_nodes(r%stp%dd, r%stp%st)
      ! the restart file of the end (SAVE) or of the interruption comes before the final rows
      ! and fields: a run continued from it writes them again, as the run that went on would
      ! (an interruption wrote its restart file after its step, in after_step)
      if (.not. allocated(err) .and. ran .and. r%stp%started .and. r%pos%save_on .and. .not. r%interrupted .and. &
          r%saved_step /= r%stp%st%step) then
         r%pos%pc = size(model%program)
         call save_restart(r, model, err)
      end if
      ! the final state is always written; after a failure, its fields are (doc/fields.md)
      if (ran .and. r%stp%started .and. .not. allocated(err)) then
         call r%out%final(model, r%stp, ferr)
         if (allocated(ferr)) then
            call r%out%files%say('error: '//ferr%message)
            call move_alloc(ferr, err)
         end if
      else if (ran .and. r%stp%started) then
         call r%out%failed(r%stp, err%message, ferr)
         if (allocated(ferr)) call r%out%files%say('error: '//ferr%message)
      end if
      call pass_messages(r)
      if (ran .and. r%stp%started) call check_inside(r)
      if (ran .and. r%stp%started) call finish_progress(r)
      field_files = ''
      if (r%out%field_dt > 0.0_wp) then
         call add_existing(field_files, opts%base//'.h5')
         call add_existing(field_files, opts%base//'.xdmf')
         call add_existing(field_files, opts%base//'_series.xdmf')
      end if
      wall = wall_time() - wall_start
      call report_final(r%out%files, r%stp, err, wall, field_files, r%inside)
      call r%out%close()
      if (.not. allocated(err) .and. allocated(r%out%files%io_error)) &
         call make_error(err, r%out%files%io_error)
      if (.not. opts%quiet .and. ran .and. r%stp%started) write (output_unit, '(a)') console_summary(r%stp, wall, r%inside)
      if (present(status)) status = merge(RUN_INTERRUPTED, RUN_COMPLETE, r%interrupted .and. .not. allocated(err))
   end subroutine run_model

   !> Interpret the BATCh program.
   subroutine execute(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: pc, depth, nfields, nflushed
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
               if (.not. allocated(err)) call gather_nodes_due(r)
               if (.not. allocated(err)) call r%out%record(model, r%stp)
               nfields = r%out%fields%count()
               nflushed = r%out%fields%flushed()
               if (.not. allocated(err)) call r%out%fields_due(r%stp, err)
               if (.not. allocated(err) .and. r%out%fields%flushed() > nflushed .and. associated(r%on_fields)) &
                  call r%on_fields(r%out%fields%flushed(), r%out%fields%last_flushed_time())
               if (.not. allocated(err) .and. (r%out%fields%count() > nfields .or. &
                                               r%stp%st%step - r%inside_step >= r%inside_every)) call check_inside(r)
               if (.not. allocated(err) .and. c%v(1) > 0.0_wp) then
                  r%stp%tmax = c%v(1)
                  if (r%stp%st%t >= r%stp%tmax*(1.0_wp - TIME_TOL) .and. depth > 0) then
                     pc = loop_end(model%program, pc)   ! leave the innermost loop
                     depth = depth - 1
                  end if
               end if
            case ('form')
               call start(r, model, err)
               if (.not. allocated(err)) call step(r, err)
               if (.not. allocated(err)) then
                  r%pos%pc = pc
                  r%pos%form_pc = pc
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
               r%pos%save_t0 = r%stp%st%t
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

   !> Appends ' '//path to list when the file exists (the field files a run that stopped while
   !> creating them has not got are not reported as written).
   subroutine add_existing(list, path)
      character(len=:), allocatable, intent(inout) :: list
      character(len=*), intent(in) :: path
      logical :: there
      inquire (file=path, exist=there)
      if (there) list = list//' '//path
   end subroutine add_existing

end module exic_driver
