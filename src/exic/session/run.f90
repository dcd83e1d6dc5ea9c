!> A run of the BATCh interpreter (src/exic/driver.f90): its state (`run_t`: the stepper, the
!> outputs, the console, the program position, restart files, signals, the geometric penetration
!> check) and what the interpreter does around a step: the first use of the state, one step with
!> its messages and progress line, the SAVE schedule and the signals after it, restart files
!> written and read, the penetration check. The interpreter decides what to call; this module
!> does it.
module exic_session_run
   use, intrinsic :: iso_fortran_env, only: error_unit
   use exic_base_kinds, only: wp, i8
   use exic_base_constants, only: TIME_TOL, PENETRATION_WARN
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_progress, only: progress_t, clock_text
   use exic_base_strings, only: itoa, rtoa
   use exic_parallel_mpi, only: par_or_bits, par_rank
   use exic_base_signals, only: signals_take, SIG_BIT_INT, SIG_BIT_TERM, SIG_BIT_USR1, SIG_BIT_USR2
   use exic_model_model, only: model_t
   use exic_restart, only: run_position_t, write_restart, read_restart, peek_restart, landing_path
   use exic_base_posix, only: file_kind, FILE_REGULAR
   use exic_output, only: output_t
   use exic_explicit_assembly, only: energy_balance
   use exic_output_text_report, only: report_preamble
   use exic_session_program_change, only: adopt_program, extends_landed_end
   use exic_explicit_step, only: stepper_t
   use exic_explicit_history_gather, only: decomposition_gather_history
   use exic_explicit_decomposition_nodes, only: decomposition_gather_nodes
   use exic_contact_inside, only: inside_t
   implicit none
   private

   public :: fields_observer, run_t, INSIDE_STEPS
   public :: resume, save_restart, init_inside, check_inside, start, step, after_step, &
             finish_progress, pass_messages, gather_nodes_due

   !> Steps between two geometric penetration checks besides the field output times and the end
   !> (at most; fewer when bodies that no contact pair couples move fast: `inside_interval`).
   integer, parameter :: INSIDE_STEPS = 1000
   !> A run that saves writes `<stem>.rst.land` after every step from which the end time is
   !> within this many steps (and one more), until a step is shortened to land on it (DT,CFL
   !> lands with at most 4; the margin covers a step that grows by 1.5 meanwhile).
   real(wp), parameter :: LAND_WINDOW = 6.0_wp

   abstract interface
      !> Told after the field file is flushed (doc/fields.md, "Batches"): how many output times
      !> it holds complete, and the time of the last of them.
      subroutine fields_observer(count, t)
         import :: wp
         integer, intent(in) :: count
         real(wp), intent(in) :: t
      end subroutine fields_observer
   end interface

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
      integer :: inside_every = INSIDE_STEPS   !< steps from one check to the next
      !> the smallest element height (area over longest side, reference mesh) when some two
      !> bodies are coupled by no contact pair (0: not needed), for `inside_interval`
      real(wp) :: inside_hmin = 0.0_wp
      integer :: inside_eroded = 0             !< eroded elements when it was built (doc/erosion.md)
      procedure(fields_observer), pointer, nopass :: on_fields => null()
   end type run_t

contains

   !> Set the run up from the restart file `path`: the stepper made from the model, then its
   !> state, the output schedules and the program position read; a changed program judged
   !> (session/program_change.f90); the outputs continued, or begun anew at the restart point in
   !> a folder that has none of them.
   subroutine resume(r, model, base, path, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      character(len=*), intent(in) :: base, path
      type(error_t), allocatable, intent(out) :: err
      real(wp), allocatable :: program(:, :)
      character(len=:), allocatable :: notes, text, from, landing
      logical :: fresh
      real(wp) :: landed
      type(error_t), allocatable :: peek_err
      ! a later end time than the one the file's last steps landed on: the file written before
      ! them, when it is there (doc/input-language.md, "Changing the program at a restart")
      from = path
      landing = ''
      call peek_restart(path, landed, program, peek_err)
      if (.not. allocated(peek_err)) then
         if (extends_landed_end(model, program, landed) .and. file_kind(landing_path(path)) == FILE_REGULAR) then
            from = landing_path(path)
            landing = 'the last steps of '//path//' were shortened to land on its end time '//rtoa(landed)// &
                      ' (DT,CFL): a later end time continues from '//from//', written before them'
         end if
      end if
      call r%stp%init(model%mesh, model%materials, model%contact, err, model%loads)
      if (allocated(err)) return
      call read_restart(from, model, r%stp, r%out, r%pos, program, err)
      if (allocated(err)) return
      call adopt_program(model, program, r%pos, r%stp, r%out, notes, err)
      if (allocated(err)) then
         err%message = "restart file '"//from//"': "//err%message
         return
      end if
      call r%out%resume(base, model, r%stp, fresh, err)
      if (allocated(err)) return
      r%pos%pc = r%pos%pc + 1
      if (fresh) then
         call report_preamble(r%out%files, model)
      else
         call r%out%files%say('')
      end if
      if (len(landing) > 0) then
         call r%out%files%say(landing)
         write (error_unit, '(a)') 'exic: '//landing
      end if
      call r%out%files%say('restarted from '//from//' at t = '//rtoa(r%stp%st%t)//', step '// &
                           itoa(int(r%stp%st%step)))
      if (fresh) then
         text = 'new output files start at the restart point (t = '//rtoa(r%stp%st%t)//', step '// &
                itoa(int(r%stp%st%step))//'): '//base//'.his, '//base//'.ene'
         if (r%out%field_dt > 0.0_wp) text = text//', '//base//'.h5'
         text = text//' hold the run from there on, not the rows and fields before it'
         call r%out%files%say(text)
         write (error_unit, '(a)') 'exic: '//text
      end if
      if (len(notes) > 0) then
         call r%out%files%say(notes)
         write (error_unit, '(a)') 'exic: '//notes
      end if
   end subroutine resume

   !> Write the restart file of the state now (the files flushed and measured first); with
   !> `landing`, the file `<stem>.rst.land` of a state before the end time's landing (not said
   !> in the .out: it is replaced until the landing begins).
   subroutine save_restart(r, model, err, landing)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: landing
      call decomposition_gather_nodes(r%stp%dd, r%stp%st)
      call r%out%checkpoint(err)
      if (allocated(err)) return
      ! several MPI ranks: the element history of every block from its owner (doc/parallel.md)
      call decomposition_gather_history(r%stp%dd, r%stp%st, r%stp%sets)
      if (present(landing)) then
         if (landing) then
            call write_restart(landing_path(r%rst), model, r%stp, r%out, r%pos, err, keep_previous=.false.)
            return
         end if
      end if
      call write_restart(r%rst, model, r%stp, r%out, r%pos, err)
      if (allocated(err)) return
      r%saved_step = r%stp%st%step
      call r%out%files%say('restart file '//r%rst//' written at t = '//rtoa(r%stp%st%t)//', step '// &
                           itoa(int(r%stp%st%step)))
   end subroutine save_restart

   !> The geometric penetration check (src/exic/contact/inside.f90) over the regions: the pairs
   !> of regions that the contact passes cover, and every other two regions, which warn once per
   !> pair when they interpenetrate (no contact pair couples them; a model without CONTact too).
   subroutine init_inside(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      if (size(model%mesh%conn, 2) == 0) return
      if (.not. r%stp%contact%active .and. all(model%mesh%region == model%mesh%region(1))) return
      call r%inside%init(r%stp%st%nnode, size(model%mesh%conn, 2), model%mesh%conn, model%mesh%region, &
                         PENETRATION_WARN, err)
      if (allocated(err)) return
      call inside_pairs(r)
      if (r%inside%uncoupled()) then
         r%inside_hmin = smallest_height(model%mesh%x, model%mesh%conn)
         ! the first check (at the first TIME) sets the interval from the speeds
         if (r%inside_hmin > 0.0_wp) r%inside_every = 1
      end if
   end subroutine init_inside

   !> The smallest element height over the mesh: area over longest side.
   pure real(wp) function smallest_height(x, conn) result(h)
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: conn(:, :)
      real(wp) :: a2, side
      integer :: e, k
      h = huge(1.0_wp)
      do e = 1, size(conn, 2)
         associate (p => x(:, conn(:, e)))
            a2 = (p(1, 3) - p(1, 1))*(p(2, 4) - p(2, 2)) - (p(1, 4) - p(1, 2))*(p(2, 3) - p(2, 1))
            side = 0.0_wp
            do k = 1, 4
               side = max(side, norm2(p(:, mod(k, 4) + 1) - p(:, k)))
            end do
         end associate
         if (side > 0.0_wp .and. a2 > 0.0_wp) h = min(h, 0.5_wp*a2/side)
      end do
      if (h == huge(1.0_wp)) h = 0.0_wp
   end function smallest_height

   !> Steps to the next penetration check when bodies no contact pair couples could pass
   !> through each other unseen between two checks: two bodies at most 2 vmax apart in speed
   !> overlap for at least hmin / (2 vmax) (each is at least hmin thick), so checks every
   !> hmin / (4 vmax dt) steps see every such overlap at least once (doc/decisions.md,
   !> "Geometric penetration check"). Between 1 and INSIDE_STEPS.
   pure integer function inside_interval(hmin, vmax, dt) result(n)
      real(wp), intent(in) :: hmin, vmax, dt
      real(wp) :: steps
      n = INSIDE_STEPS
      if (.not. (vmax*dt > 0.0_wp)) return
      steps = 0.25_wp*hmin/(vmax*dt)
      if (steps < real(INSIDE_STEPS, wp)) n = max(1, int(steps))
   end function inside_interval

   !> The pairs of regions the check covers: every two regions (all_pairs), those of the contact
   !> passes allowed to touch.
   subroutine inside_pairs(r)
      type(run_t), intent(inout) :: r
      integer :: k
      r%inside%all_pairs = .true.
      if (.not. r%stp%contact%active) return
      associate (c => r%stp%contact)
         ! the passes of the PAIRs, and every pair of AUTOmatic surfaces (whose passes are made
         ! per step for the surfaces found near), given surface by surface; not the corner pass
         ! of an NTOS pair, which holds the master's convex corners only: the master's other
         ! nodes may enter the slave's body between its nodes, as one-pass contact allows
         do k = 1, c%nfixed
            if (c%passes(k)%corners) cycle
            call r%inside%allow(c%surfaces(c%passes(k)%slave)%nodes, c%surfaces(c%passes(k)%master)%nodes)
         end do
         if (c%auto_pass%auto) then
            do k = c%auto_first + 1, size(c%surfaces)
               call r%inside%allow_auto(c%surfaces(k)%nodes)
            end do
         end if
      end associate
   end subroutine inside_pairs

   !> After erosion: the check over the live elements only (the run's results carried over).
   subroutine inside_after_erosion(r, err)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      type(inside_t) :: old
      logical, allocatable :: live(:)
      integer :: nlive
      r%inside_eroded = r%stp%st%neroded
      if (.not. r%stp%eroc%on) return
      old = r%inside
      live = r%stp%st%status == 0
      nlive = count(live)
      call r%inside%init(r%stp%st%nnode, nlive, reshape(pack(r%stp%eroc%conn, spread(live, 1, 4)), [4, nlive]), &
                         pack(r%stp%eroc%region, live), PENETRATION_WARN, err)
      if (allocated(err)) return
      call inside_pairs(r)
      r%inside%worst = old%worst
      r%inside%npast = old%npast
      r%inside%past_key = old%past_key
      r%inside%past_checks = old%past_checks
      r%inside%past_max = old%past_max
      r%inside%nchecks = old%nchecks
      r%inside%time_total = old%time_total
   end subroutine inside_after_erosion

   !> Check the positions now for nodes inside other bodies; warnings go to <stem>.out and the
   !> console.
   subroutine check_inside(r)
      type(run_t), intent(inout) :: r
      character(len=:), allocatable :: warn
      type(error_t), allocatable :: err
      if (.not. r%inside%active) return
      if (r%inside_step == r%stp%st%step) return
      if (r%stp%st%neroded /= r%inside_eroded) then
         call inside_after_erosion(r, err)
         if (allocated(err)) then
            call r%stp%messages%add('warning: the penetration check after an erosion: '//err%message)
            r%inside%active = .false.
            return
         end if
      end if
      r%inside_step = r%stp%st%step
      call r%inside%check(r%stp%st%x0 + r%stp%st%u, r%stp%st%t, warn)
      if (len(warn) > 0) call r%stp%messages%add(warn)
      call pass_messages(r)
      if (r%inside_hmin > 0.0_wp) r%inside_every = inside_interval(r%inside_hmin, &
                                                                   sqrt(maxval(sum(r%stp%st%v**2, dim=1))), r%stp%st%dt)
   end subroutine check_inside

   !> Before a TIME command's outputs: the whole nodal state on every rank when its rows, fields
   !> or penetration check are due and the state is divided among MPI ranks (doc/parallel.md).
   subroutine gather_nodes_due(r)
      type(run_t), intent(inout) :: r
      if (.not. r%stp%dd%nodes) return
      if (r%out%reads_state(r%stp) .or. (r%inside%active .and. r%stp%st%step - r%inside_step >= r%inside_every)) &
         call decomposition_gather_nodes(r%stp%dd, r%stp%st)
   end subroutine gather_nodes_due

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
               print '(a,es13.5e3,a,i0,a,es13.5e3,a,es13.5e3,a,es13.5e3,a,es13.5e3)', ' t=', st%t, ' step ', st%step, &
                  ' K=', st%energy%kinetic, ' U=', st%energy%strain + st%energy%hourglass, ' Wext=', st%energy%wext, &
                  ' Wc=', st%energy%wcon
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
      ! on several ranks every rank answers the signals that came to any of them, after the same
      ! step (a logical or of integers: exact)
      if (r%signals) bits = par_or_bits(bits)
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
      if (allocated(err) .or. r%interrupted) return
      ! DT,CFL shortens the last steps to land on the end time: a run that saves keeps the state
      ! before them too, from which a later end time continues (session/program_change.f90)
      associate (stp => r%stp)
         if (stp%cfl_mode .and. stp%tmax > stp%st%t .and. stp%landed_tmax /= stp%tmax .and. &
             stp%tmax - stp%st%t <= (LAND_WINDOW + 1.0_wp)*stp%st%dt) then
            if (any(model%program(:)%name == 'save')) call save_restart(r, model, err, landing=.true.)
         end if
      end associate
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
      ! the console is rank 0's (doc/parallel.md)
      if (par_rank() == 0) write (error_unit, '(a)') 'exic: '//text
      flush (error_unit)
   end subroutine pass_messages

end module exic_session_run
