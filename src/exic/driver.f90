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
   use exic_base_progress, only: progress_t
   use exic_io_model, only: model_t
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
      !> called after every field output time, when associated (a library user following the run)
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_options_t

   !> A run: the step, its outputs and the console.
   type :: run_t
      type(stepper_t) :: stp
      type(output_t) :: out
      type(progress_t) :: progress
      integer :: print_inc = 0                 !< PRINt,ENERgy interval (0: none)
      type(inside_t) :: inside                 !< geometric penetration check (with contact)
      integer(i8) :: inside_step = -1          !< step of its last check
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_t

contains

   !> Run `model`'s program. On error, every output written so far is kept and closed.
   subroutine run_model(model, opts, err)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(error_t), allocatable, intent(out) :: err
      type(run_t) :: r
      type(error_t), allocatable :: ferr
      real(wp) :: wall_start, wall
      character(len=:), allocatable :: field_files

      wall_start = wall_time()
      r%on_fields => opts%on_fields
      call r%out%open(opts%base, err)
      if (.not. allocated(err)) call report_preamble(r%out%files, model)
      if (.not. allocated(err)) call r%stp%init(model%mesh, model%materials, model%contact, err, model%loads)
      if (.not. allocated(err)) then
         call report_summary(r%out%files, model, r%stp)
         call init_inside(r, model, err)
      end if
      if (.not. allocated(err)) then
         call r%progress%begin(opts%quiet)
         call execute(r, model, err)
      end if
      ! the final state is always written; after a failure, its fields are (doc/fields.md)
      if (r%stp%started .and. .not. allocated(err)) then
         call r%out%final(model, r%stp, ferr)
         if (allocated(ferr)) call r%out%files%say('error: '//ferr%message)
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
      if (.not. opts%quiet .and. r%stp%started) write (output_unit, '(a)') console_summary(r%stp, wall, r%inside)
   end subroutine run_model

   !> Interpret the BATCh program.
   subroutine execute(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: pc, depth, nfields
      integer :: remaining(MAX_LOOP_DEPTH)

      pc = 1
      depth = 0
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
            case ('tplo')
               r%out%his_inc = max(1, nint(c%v(1)))
            case ('init')
               call r%stp%set_velocity(c%given, c%data)
            case ('outp')
               call r%out%open_fields(model, r%stp, c%v(1), err)
            case ('prin')
               r%print_inc = max(1, nint(c%v(1)))
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
      integer :: k
      if (.not. r%stp%contact%active) return
      call r%inside%init(r%stp%st%nnode, size(model%mesh%conn, 2), model%mesh%conn, model%mesh%region, &
                         PENETRATION_WARN, err)
      if (allocated(err)) return
      associate (c => r%stp%contact)
         do k = 1, size(c%passes)
            call r%inside%allow(c%surfaces(c%passes(k)%slave)%nodes, c%surfaces(c%passes(k)%master)%nodes)
         end do
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
         if (r%print_inc > 0) then
            if (mod(st%step, int(r%print_inc, i8)) == 0) then
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
