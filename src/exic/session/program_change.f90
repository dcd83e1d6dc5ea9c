!> A BATCh program changed between the run that wrote a restart file and the run continued from
!> it (doc/input-language.md, "Changing the program at a restart").
!>
!> The commands must be the same ones in the same order; their values may change when the
!> change leaves the state up to the restart point as it is: a command that has not run before
!> the restart point, and, among those that have, end times (TIME) and LOOP counts of the loops
!> still open, and the settings that only say what is written or checked (TPLOt, OUTPut,HDF5,
!> SAVE, PRINt, CHECk). Any other change is refused, naming the command (file:line) and its
!> values. An accepted change makes the continued run resume right after the step the file
!> holds (the FORM of its last step), with the open loops' counters and the output schedules
!> those of a run that had the changed program from its start, so that it writes what that run
!> writes from the restart point on.
module exic_session_program_change
   use exic_base_kinds, only: wp
   use exic_base_constants, only: TIME_TOL
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa, rtoa
   use exic_model_model, only: model_t
   use exic_model_program, only: MAX_LOOP_DEPTH, command_t, loop_end
   use exic_restart, only: run_position_t, code
   use exic_output, only: output_t
   use exic_explicit_step, only: stepper_t
   implicit none
   private

   public :: adopt_program, extends_landed_end

   !> Commands whose value only says what is written or checked: a change applies from the
   !> restart point on.
   character(len=4), parameter :: SETTINGS(5) = ['tplo', 'outp', 'save', 'prin', 'chec']
   !> Commands that may run between the last step and the end without changing the state
   !> (rows and fields they write are written once: output_t keeps track). SAVE, which wrote
   !> the file there, may too: its schedule is undone (`adopt_program`).
   character(len=4), parameter :: PURE(6) = ['loop', 'next', 'time', 'tran', 'prop', 'save']

contains

   !> Judge the program `saved` (5, commands: the restart file's, restart.f90 `identity`) against
   !> the deck's. Unchanged: nothing is done. Changed and allowed: the position `pos` is moved to
   !> the FORM of the last step with the open LOOPs' counters of the deck, and the settings that
   !> ran before the restart point take their new values (`out`, `stp`, `pos`); `notes` says
   !> what changed and where the run resumes. Otherwise `err` names every refused change.
   subroutine adopt_program(model, saved, pos, stp, out, notes, err)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: saved(:, :)
      type(run_position_t), intent(inout) :: pos
      type(stepper_t), intent(inout) :: stp
      type(output_t), intent(inout) :: out
      character(len=:), allocatable, intent(out) :: notes
      type(error_t), allocatable, intent(out) :: err
      integer :: n, k, d, depth, loops(MAX_LOOP_DEPTH), pass(MAX_LOOP_DEPTH), remaining(MAX_LOOP_DEPTH)
      logical, allocatable :: ran(:)
      logical :: saved_after
      character(len=:), allocatable :: refused, what
      real(wp) :: t

      notes = ''
      n = size(model%program)
      call same_commands(model, saved, err)
      if (allocated(err)) return
      if (all(saved(3:5, :) == program_values(model))) return
      t = stp%st%t
      depth = pos%depth
      remaining = pos%remaining
      call open_loops(model, pos%form_pc, depth, loops, err)
      if (allocated(err)) return
      do d = 1, depth
         pass(d) = nint(saved(3, loops(d))) - remaining(d) + 1
      end do
      allocate (ran(n))
      do k = 1, n
         ran(k) = has_run(model, k, pos%form_pc, depth, loops, pass)
      end do
      refused = ''
      saved_after = .false.
      if (pos%pc /= pos%form_pc) call after_last_step(model, saved, pos, t, refused, saved_after)
      if (saved_after) call undo_end_save(model, ran, pos, refused)
      do k = 1, n
         associate (c => model%program(k))
            if (all(saved(3:5, k) == c%v)) cycle
            what = upper(c%name)//' at '//where(c)//' ('//values(saved(3:5, k))//' -> '//values(c%v)//')'
            if (.not. ran(k)) then
               notes = notes//'; '//what//': not run before the restart point'
            else if (any(c%name == SETTINGS)) then
               call setting(model, k, ran, pos, stp, out, what, notes, refused)
            else if (c%name == 'time') then
               call end_time(model, k, depth, loops, pass, t, saved(3, k) == stp%landed_tmax, what, notes, &
                             refused)
            else if (c%name == 'loop') then
               d = findloc(loops(1:depth), k, dim=1)
               if (d == 0 .or. any(pass(1:max(d - 1, 0)) > 1)) then
                  refused = refused//'; '//what//': the loop ran to its end before the restart point'
               else if (nint(c%v(1)) < pass(d)) then
                  refused = refused//'; '//what//': the run was in pass '//itoa(pass(d))// &
                            ' of this loop at the restart point'
               else
                  remaining(d) = nint(c%v(1)) - pass(d) + 1
                  notes = notes//'; '//what//': pass '//itoa(pass(d))//' of '//itoa(nint(c%v(1)))// &
                          ' at the restart point'
               end if
            else
               refused = refused//'; '//what//': it ran before the restart point, so the state there '// &
                         'would not be that of the changed deck'
            end if
         end associate
      end do
      if (len(refused) > 0) then
         call make_error(err, 'the BATCh commands differ where a restart cannot follow them: '//refused(3:)// &
                         ' (a restart may change end times and LOOP counts of the loops still open, '// &
                         'TPLOt, OUTPut, SAVE, PRINt and CHECk values, and commands not run yet)')
         return
      end if
      pos%remaining = remaining
      pos%pc = pos%form_pc
      if (pos%form_pc > 0) then
         notes = 'the BATCh program differs from the restart file''s: '//notes(3:)//'; the run resumes '// &
                 'after the step of FORM at '//where(model%program(pos%form_pc))
      else
         notes = 'the BATCh program differs from the restart file''s: '//notes(3:)// &
                 '; the run resumes at the start of the program'
      end if
   end subroutine adopt_program

   !> The names and options must be those of the restart file, command by command.
   subroutine same_commands(model, saved, err)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: saved(:, :)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, n, m
      n = size(model%program)
      m = size(saved, 2)
      do k = 1, min(n, m)
         associate (c => model%program(k))
            if (nint(saved(1, k)) == code(c%name) .and. nint(saved(2, k)) == code(c%option)) cycle
            call make_error(err, 'it was written for another deck: the BATCh commands differ: command '// &
                            itoa(k)//' at '//where(c)//' is '//upper(c%name)//label(c%option)// &
                            ' in the deck, '//upper(decode(nint(saved(1, k))))//label(decode(nint(saved(2, k))))// &
                            ' in the restart file (a restart may change values, not commands)')
            return
         end associate
      end do
      if (n > m) then
         call make_error(err, 'it was written for another deck: the BATCh commands differ: the deck '// &
                         'has '//itoa(n - m)//' command(s) more, from '//upper(model%program(m + 1)%name)// &
                         ' at '//where(model%program(m + 1))//' (a restart may change values, not commands)')
      else if (m > n) then
         call make_error(err, 'it was written for another deck: the BATCh commands differ: the restart '// &
                         'file has '//itoa(m - n)//' command(s) more after the deck''s last, '// &
                         upper(decode(nint(saved(1, n + 1))))//' (a restart may change values, not commands)')
      end if
   end subroutine same_commands

   !> The LOOPs open at the FORM `form_pc` (depth of them), outermost first.
   subroutine open_loops(model, form_pc, depth, loops, err)
      type(model_t), intent(in) :: model
      integer, intent(in) :: form_pc, depth
      integer, intent(out) :: loops(MAX_LOOP_DEPTH)
      type(error_t), allocatable, intent(out) :: err
      integer :: j, d
      loops = 0
      d = depth
      do j = form_pc - 1, 1, -1
         if (d == 0) exit
         if (model%program(j)%name == 'loop' .and. model%program(j)%jump > form_pc) then
            loops(d) = j
            d = d - 1
         end if
      end do
      if (d /= 0) call make_error(err, 'the program position it holds (command '//itoa(form_pc)//', '// &
                                  itoa(depth)//' open LOOPs) does not fit the deck''s program')
   end subroutine open_loops

   !> Whether command k ran before the restart point: it stands before the FORM of the last step
   !> or at it, or after it inside an open loop that had made a pass before.
   logical function has_run(model, k, form_pc, depth, loops, pass) result(r)
      type(model_t), intent(in) :: model
      integer, intent(in) :: k, form_pc, depth, loops(:), pass(:)
      integer :: d
      r = k <= form_pc
      if (r) return
      do d = 1, depth
         if (k < model%program(loops(d))%jump .and. pass(d) > 1) r = .true.
      end do
   end function has_run

   !> A changed TPLOt, OUTPut,HDF5, SAVE, PRINt or CHECk that ran before the restart point:
   !> its value is taken from the restart point on, the schedule being the one the changed
   !> command would have made from its own time (the origin the restart file keeps). Only when
   !> it is the only command of its kind that ran (else which one holds is not known here).
   subroutine setting(model, k, ran, pos, stp, out, what, notes, refused)
      type(model_t), intent(in) :: model
      integer, intent(in) :: k
      logical, intent(in) :: ran(:)
      type(run_position_t), intent(inout) :: pos
      type(stepper_t), intent(inout) :: stp
      type(output_t), intent(inout) :: out
      character(len=*), intent(in) :: what
      character(len=:), allocatable, intent(inout) :: notes, refused
      integer :: j, nran
      real(wp) :: t, next
      associate (c => model%program(k))
         nran = 0
         do j = 1, size(model%program)
            if (ran(j) .and. model%program(j)%name == c%name .and. model%program(j)%option == c%option) &
               nran = nran + 1
         end do
         if (nran > 1) then
            refused = refused//'; '//what//': '//itoa(nran)//' '//upper(c%name)//' commands ran before '// &
                      'the restart point (a change is taken with one only)'
            return
         end if
         t = stp%st%t
         select case (c%name)
         case ('tplo')
            out%his_inc = max(1, nint(c%v(1)))
         case ('prin')
            pos%print_inc = max(1, nint(c%v(1)))
         case ('chec')
            if (c%option /= 'pene') call stp%set_energy_limits(c%v(1), c%v(2))
         case ('save')
            pos%save_dt = c%v(1)
            if (c%v(1) > 0.0_wp) then
               ! SAVE set save_next = t0 + dt; each step then passed the times reached
               ! (session/run.f90 after_step), the last at the restart point
               next = pos%save_t0 + c%v(1)
               do while (next <= t*(1.0_wp + TIME_TOL))
                  next = next + c%v(1)
               end do
               pos%save_next = next
            end if
         case ('outp')
            if (c%v(1) < stp%st%dt) then
               refused = refused//'; '//what//': an interval below the time step '//rtoa(stp%st%dt)// &
                         ' (fields once per step) cannot be taken at a restart'
               return
            end if
            ! OUTPut set field_next = t0; every TIME passed the times reached (output.f90
            ! output_fields_due), the last at field_checked
            out%field_dt = c%v(1)
            next = out%field_t0
            do while (next <= out%field_checked*(1.0_wp + TIME_TOL))
               next = next + c%v(1)
            end do
            out%field_next = next
         end select
         notes = notes//'; '//what//': taken from the restart point on'
      end associate
   end subroutine setting

   !> A changed TIME that ran before the restart point: allowed when no loop was left through it
   !> (its innermost loop is open, entered once), no step was shortened to land on its old end
   !> time (step.f90, DT,CFL: session/run.f90 `resume` then takes `<stem>.rst.land` when it is
   !> there) and the new end time is after the restart point.
   subroutine end_time(model, k, depth, loops, pass, t, landed, what, notes, refused)
      type(model_t), intent(in) :: model
      integer, intent(in) :: k, depth, loops(:), pass(:)
      real(wp), intent(in) :: t
      logical, intent(in) :: landed     !< steps before the restart point were shortened to land on it
      character(len=*), intent(in) :: what
      character(len=:), allocatable, intent(inout) :: notes, refused
      integer :: j, inner, d
      real(wp) :: tnew
      tnew = model%program(k)%v(1)
      ! the innermost LOOP around command k
      inner = 0
      do j = k - 1, 1, -1
         if (model%program(j)%name == 'loop' .and. model%program(j)%jump > k) then
            inner = j
            exit
         end if
      end do
      if (inner == 0) then
         notes = notes//'; '//what//': in no loop, the end time shown'
         return
      end if
      d = findloc(loops(1:depth), inner, dim=1)
      if (d == 0) then
         refused = refused//'; '//what//': its loop ended before the restart point'
      else if (any(pass(1:d - 1) > 1)) then
         refused = refused//'; '//what//': its loop had been run to its end before (an outer loop is '// &
                   'in a later pass)'
      else if (landed) then
         refused = refused//'; '//what//': the last steps before the restart point were shortened to '// &
                   'land on the end time (DT,CFL), so the state there is not that of a run with the '// &
                   'new end time; continue from a restart file written before them (<stem>.rst.land, '// &
                   'which a run that saves writes beside <stem>.rst; or <stem>.rst.prev of SAVE,,dt)'
      else if (.not. (t < tnew*(1.0_wp - TIME_TOL))) then
         refused = refused//'; '//what//': the end time is not after the restart point t = '//rtoa(t)
      else
         notes = notes//'; '//what//': end time'
      end if
   end subroutine end_time

   !> The file was written at the end of its run: the commands that ran after the last step
   !> (followed with the restart file's values from the FORM of that step) must not have
   !> changed the state, since a changed program resumes at that FORM. `saved_after`: a SAVE
   !> was among them.
   subroutine after_last_step(model, saved, pos, t, refused, saved_after)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: saved(:, :), t
      type(run_position_t), intent(in) :: pos
      character(len=:), allocatable, intent(inout) :: refused
      logical, intent(inout) :: saved_after
      integer :: pc, depth, remaining(MAX_LOOP_DEPTH), guard
      character(len=4) :: name
      pc = pos%form_pc + 1
      depth = pos%depth
      remaining = pos%remaining
      do guard = 1, 100000000
         if (pc > size(model%program)) return
         name = model%program(pc)%name
         if (.not. any(name == PURE)) then
            refused = refused//'; '//upper(name)//' at '//where(model%program(pc))//' ran after the last '// &
                      'step of the run that wrote the file, which ended there; continue from a restart file '// &
                      'written during the run (SAVE,,dt) to change its program'
            return
         end if
         select case (name)
         case ('save')
            saved_after = .true.
         case ('loop')
            depth = depth + 1
            remaining(depth) = nint(saved(3, pc))
            if (remaining(depth) <= 0) then
               pc = model%program(pc)%jump
               depth = depth - 1
            end if
         case ('next')
            remaining(depth) = remaining(depth) - 1
            if (remaining(depth) > 0) then
               pc = model%program(pc)%jump
            else
               depth = depth - 1
            end if
         case ('time')
            if (saved(3, pc) > 0.0_wp .and. t >= saved(3, pc)*(1.0_wp - TIME_TOL) .and. depth > 0) then
               pc = loop_end(model%program, pc)
               depth = depth - 1
            end if
         end select
         pc = pc + 1
      end do
   end subroutine after_last_step

   !> A SAVE that ran after the last step (the one that wrote a file at the end of its run) set
   !> the SAVE schedule the file holds; a run with the changed program reaches it after its
   !> later steps only. When no SAVE ran before the restart point the schedule is the one before
   !> any SAVE (none: SAVE runs again at the end); else which values held is not known here.
   subroutine undo_end_save(model, ran, pos, refused)
      type(model_t), intent(in) :: model
      logical, intent(in) :: ran(:)
      type(run_position_t), intent(inout) :: pos
      character(len=:), allocatable, intent(inout) :: refused
      integer :: k
      do k = 1, size(model%program)
         if (ran(k) .and. model%program(k)%name == 'save') then
            refused = refused//'; SAVE at '//where(model%program(k))//' ran before the last step and '// &
                      'another SAVE after it, at the end of the run that wrote the file; continue from '// &
                      'a restart file written during the run (SAVE,,dt) to change its program'
            return
         end if
      end do
      pos%save_on = .false.
      pos%save_dt = 0.0_wp
      pos%save_next = 0.0_wp
      pos%save_t0 = 0.0_wp
   end subroutine undo_end_save

   !> Whether the deck changes the end time of a TIME command whose old value `landed_tmax`
   !> shaped the last steps of the restart file (step.f90, DT,CFL): such a file cannot be
   !> extended, the one written before those steps (restart.f90 `landing_path`) can.
   logical function extends_landed_end(model, saved, landed_tmax) result(r)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: saved(:, :), landed_tmax
      integer :: k
      r = .false.
      if (landed_tmax <= 0.0_wp .or. size(saved, 2) /= size(model%program)) return
      do k = 1, size(model%program)
         associate (c => model%program(k))
            if (c%name == 'time' .and. saved(3, k) == landed_tmax .and. c%v(1) /= saved(3, k)) r = .true.
         end associate
      end do
   end function extends_landed_end

   !> v(1:3) of every command, (3, commands).
   function program_values(model) result(v)
      type(model_t), intent(in) :: model
      real(wp), allocatable :: v(:, :)
      integer :: k
      allocate (v(3, size(model%program)))
      do k = 1, size(model%program)
         v(:, k) = model%program(k)%v
      end do
   end function program_values

   !> The 4 characters `code` made one number of.
   pure function decode(n) result(s)
      integer, intent(in) :: n
      character(len=4) :: s
      integer :: i, m
      m = n
      do i = 4, 1, -1
         s(i:i) = achar(mod(m, 128))
         m = m/128
      end do
   end function decode

   !> Upper case of a command name.
   pure function upper(s) result(u)
      character(len=*), intent(in) :: s
      character(len=len_trim(s)) :: u
      integer :: i
      u = s(1:len_trim(s))
      do i = 1, len(u)
         if (u(i:i) >= 'a' .and. u(i:i) <= 'z') u(i:i) = achar(iachar(u(i:i)) - 32)
      end do
   end function upper

   !> ','//option in upper case, or nothing.
   pure function label(option) result(s)
      character(len=*), intent(in) :: option
      character(len=:), allocatable :: s
      s = ''
      if (len_trim(option) > 0) s = ','//upper(option)
   end function label

   !> The command's file:line, or its number.
   function where(c) result(s)
      type(command_t), intent(in) :: c
      character(len=:), allocatable :: s
      s = 'the program'
      if (allocated(c%where)) s = c%where
   end function where

   !> v(1:3) as text.
   function values(v) result(s)
      real(wp), intent(in) :: v(3)
      character(len=:), allocatable :: s
      s = trim(rtoa(v(1)))
      if (v(2) /= 0.0_wp .or. v(3) /= 0.0_wp) s = s//','//trim(rtoa(v(2)))
      if (v(3) /= 0.0_wp) s = s//','//trim(rtoa(v(3)))
   end function values

end module exic_session_program_change
