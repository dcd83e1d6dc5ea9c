!> Restart files (BATCh SAVE, RESTart and `exic deck.inp --restart FILE`; doc/input-language.md
!> section 5, doc/fields.md "Restart files").
!>
!> A restart file is an HDF5 file of plain datasets, one per item, named `<part>.<item>`: the
!> complete state of a run after a step, so that the run continued from it takes the same steps
!> with the same bits as the run that was never stopped. It holds
!>   - `model.*`: what identifies the deck (mesh, element sets, contact, solution program), to
!>     refuse a restart from another deck naming what differs;
!>   - `state.*`, `stepper.*`: the nodal state, dt(n), dt(n+1), the time-step control (its
!>     hysteresis), the energy accumulators and the energy guard;
!>   - `set<k>.*`: per element set, the history of its points when the set has one;
!>   - `contact.*` (`visit_contact`, the one place that knows the contact's state);
!>   - `loading.*`: loads, prescribed motion and rigid bodies;
!>   - `output.*`, `program.*`: the output schedules, the lengths of the text files and the
!>     number of field output times at the save, and the position in the BATCh program with
!>     its LOOP counters.
!>
!> Writing and reading are one traversal (`visit`) over an `archive_t` that either saves or
!> loads each item, so that the two can never disagree on an item. A file is written under a
!> temporary name, closed, then the older file is moved to `<path>.prev` and the new one
!> renamed to `<path>`: a kill at any moment leaves at least one complete restart file.
module exic_restart
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_hdf5_file, only: hdf5_file_t, DTYPE_INT64
   use exic_base_posix, only: rename_file, file_kind, FILE_REGULAR
   use exic_model_model, only: model_t
   use exic_model_program, only: MAX_LOOP_DEPTH
   use exic_output, only: output_t
   use exic_explicit_step, only: stepper_t
   use exic_explicit_state, only: plus_zero
   use exic_contact_contact, only: contact_t
   use exic_contact_pair_history, only: pair_history_t
   use exic_explicit_erosion, only: erosion_restore
   use exic_material_material, only: HOURGLASS_PHYSICAL
   implicit none
   private

   public :: run_position_t, write_restart, read_restart, peek_restart, previous_path, landing_path, code

   !> Version of the layout; a file of another version is refused.
   integer, parameter :: RESTART_FORMAT = 4

   !> Where the BATCh interpreter is, and the schedules it keeps.
   type :: run_position_t
      integer :: pc = 1                            !< next command to run
      !> the FORM of the last step (with `depth` and `remaining` as they were at it): where a
      !> changed program resumes (doc/input-language.md, "Changing the program at a restart")
      integer :: form_pc = 0
      integer :: depth = 0                         !< open LOOPs
      integer :: remaining(MAX_LOOP_DEPTH) = 0     !< passes left in each open LOOP
      integer :: print_inc = 0                     !< PRINt,ENERgy interval
      real(wp) :: save_dt = 0.0_wp                 !< SAVE interval (0: only at the end)
      real(wp) :: save_next = 0.0_wp               !< time of the next SAVE
      real(wp) :: save_t0 = 0.0_wp                 !< time of the SAVE command (its schedule's origin)
      logical :: save_on = .false.                 !< SAVE was given
   end type run_position_t

   !> Saves items into, or loads them from, an open restart file.
   type :: archive_t
      type(hdf5_file_t) :: h5
      logical :: saving = .true.
      type(error_t), allocatable :: err            !< the first failure; later items do nothing
      !> loading: the BATCh program of the run that wrote the file, (5, commands): name and
      !> option codes (`code`), v(1:3)
      real(wp), allocatable :: program(:, :)
   contains
      procedure, private :: real0, real1, real2, real3, int0, int1, int2, i80, log0
      generic :: item => real0, real1, real2, real3, int0, int1, int2, i80, log0
   end type archive_t

contains

   !> The older restart file kept beside `path`.
   function previous_path(path) result(prev)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: prev
      prev = path//'.prev'
   end function previous_path

   !> The restart file written before the steps that landed on the end time beside `path`
   !> (doc/input-language.md, "Changing the program at a restart").
   function landing_path(path) result(land)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: land
      land = path//'.land'
   end function landing_path

   !> Write the restart file `path` of the run: `model`, the stepper, the outputs (their
   !> schedules and lengths, measured by the caller before: output_t%checkpoint) and the
   !> position `pos` in the program. With `keep_previous` false the older file is replaced, not
   !> kept as `<path>.prev`.
   subroutine write_restart(path, model, stp, out, pos, err, keep_previous)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      type(output_t), intent(inout) :: out
      type(run_position_t), intent(inout) :: pos
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: keep_previous
      type(archive_t) :: ar
      type(error_t), allocatable :: err2
      character(len=:), allocatable :: tmp
      integer :: version
      logical :: keep

      tmp = path//'.tmp'
      call ar%h5%create(tmp, err)
      if (allocated(err)) return
      ar%saving = .true.
      version = RESTART_FORMAT
      call ar%item('format', version)
      call identity(ar, model, stp)
      call visit(ar, stp, out, pos)
      if (.not. allocated(ar%err)) call ar%h5%write_attr('/', 'deck', model%deck_file, ar%err)
      call ar%h5%close(err2)
      if (allocated(ar%err)) then
         call move_alloc(ar%err, err)
      else if (allocated(err2)) then
         call move_alloc(err2, err)
      end if
      if (allocated(err)) then
         err%message = "restart file '"//path//"': "//err%message
         return
      end if
      ! only a complete file takes the name; the older one stays as <path>.prev
      keep = .true.
      if (present(keep_previous)) keep = keep_previous
      if (keep .and. file_kind(path) == FILE_REGULAR) then
         call rename_file(path, previous_path(path), err)
         if (allocated(err)) return
      end if
      call rename_file(tmp, path, err)
   end subroutine write_restart

   !> Read the restart file `path` into the stepper (made by stepper_t%init from the same
   !> model), the output schedules and the program position. A file of another deck or mesh is
   !> refused with a message naming what differs. The BATCh program is not compared here:
   !> `program` returns the one of the run that wrote the file, (5, commands) as `identity`
   !> saves it, for the caller to judge its changes (src/exic/session/program_change.f90).
   subroutine read_restart(path, model, stp, out, pos, program, err)
      character(len=*), intent(in) :: path
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      type(output_t), intent(inout) :: out
      type(run_position_t), intent(inout) :: pos
      real(wp), allocatable, intent(out) :: program(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(archive_t) :: ar
      integer :: version

      call open_to_load(path, ar, err)
      if (allocated(err)) return
      version = -1
      call ar%item('format', version)
      if (.not. allocated(ar%err) .and. version /= RESTART_FORMAT) &
         call make_error(ar%err, 'layout version '//itoa(version)//', this exic reads version '// &
                         itoa(RESTART_FORMAT))
      if (.not. allocated(ar%err)) call identity(ar, model, stp)
      if (.not. allocated(ar%err)) call visit(ar, stp, out, pos)
      call close_loaded(ar, err)
      if (allocated(err)) err%message = "restart file '"//path//"': "//err%message
      if (allocated(ar%program)) call move_alloc(ar%program, program)
   end subroutine read_restart

   !> Open the restart file `path` to load items from it.
   subroutine open_to_load(path, ar, err)
      character(len=*), intent(in) :: path
      type(archive_t), intent(inout) :: ar
      type(error_t), allocatable, intent(out) :: err
      if (file_kind(path) /= FILE_REGULAR) then
         call make_error(err, "restart file '"//path//"' does not exist or is not a regular file")
         return
      end if
      call ar%h5%open(path, .false., err)
      ar%saving = .false.
   end subroutine open_to_load

   !> Close an archive loaded from; `err`: the first failure of its items, else of the closing.
   subroutine close_loaded(ar, err)
      type(archive_t), intent(inout) :: ar
      type(error_t), allocatable, intent(out) :: err
      type(error_t), allocatable :: err2
      call ar%h5%close(err2)
      if (allocated(ar%err)) then
         call move_alloc(ar%err, err)
      else if (allocated(err2)) then
         call move_alloc(err2, err)
      end if
   end subroutine close_loaded

   !> The end time whose landing shaped the last steps of the restart file `path` (stepper
   !> `landed_tmax`, -1: none) and its BATCh program (5, commands), read without the rest: to
   !> choose the file a changed program continues from (session/run.f90 `resume`).
   subroutine peek_restart(path, landed_tmax, program, err)
      character(len=*), intent(in) :: path
      real(wp), intent(out) :: landed_tmax
      real(wp), allocatable, intent(out) :: program(:, :)
      type(error_t), allocatable, intent(out) :: err
      type(archive_t) :: ar
      integer :: np
      landed_tmax = -1.0_wp
      call open_to_load(path, ar, err)
      if (allocated(err)) return
      call ar%item('stepper.landed_tmax', landed_tmax)
      np = 0
      call ar%item('model.commands', np)
      if (.not. allocated(ar%err)) then
         allocate (program(5, np))
         if (np > 0) call ar%item('model.program', program)
      end if
      call close_loaded(ar, err)
   end subroutine peek_restart

   ! ---------------------------------------------------------------------------- identity

   !> What identifies the deck: saved as it is, compared on loading (naming the first difference).
   subroutine identity(ar, model, stp)
      type(archive_t), intent(inout) :: ar
      type(model_t), intent(in) :: model
      type(stepper_t), intent(in) :: stp
      real(wp), allocatable :: sets(:, :), prog(:, :)
      integer :: k, np

      call same_int(ar, 'model.nnode', model%mesh%nnode, 'the number of nodes')
      call same_int(ar, 'model.nelem', model%mesh%nelem, 'the number of elements')
      if (allocated(ar%err)) return
      call same_reals(ar, 'model.coordinates', reshape(model%mesh%x, [2*model%mesh%nnode]), &
                      'the node coordinates', 2)
      call same_ints(ar, 'model.connectivity', reshape(model%mesh%conn, [4*model%mesh%nelem]), &
                     'the connectivity', 4)
      call same_ints(ar, 'model.region', model%mesh%region, 'the region numbers', 1)
      call same_ints(ar, 'model.material', model%mesh%mat, 'the material numbers', 1)
      call same_ints(ar, 'model.boundary', reshape(model%mesh%bc, [2*model%mesh%nnode]), &
                     'the boundary codes', 2)
      call same_int(ar, 'model.nsets', size(stp%sets), 'the number of element sets')
      if (allocated(ar%err)) return
      allocate (sets(8, size(stp%sets)))
      do k = 1, size(stp%sets)
         associate (s => stp%sets(k))
            sets(:, k) = [real(s%mat, wp), real(s%kind, wp), real(s%nq, wp), real(s%nel, wp), &
                          s%law%lambda, s%law%mu, s%rho, merge(-s%hourglass, s%hourglass, &
                          s%hgkind == HOURGLASS_PHYSICAL)]
         end associate
      end do
      call same_reals(ar, 'model.sets', reshape(sets, [size(sets)]), &
                      'the materials of the element sets (material, kind, quadrature, elements, '// &
                      'lambda, mu, rho, hourglass: the coefficient, or minus the scale of '// &
                      'HOURglass,PHYSical)', 8)
      np = -1
      ! the passes of the PAIR records (AUTOmatic's are made per step, as many as the search finds)
      if (stp%contact%active) np = stp%contact%nfixed
      call same_int(ar, 'model.contact_passes', np, 'the contact passes (CONTact block)')
      np = 0
      if (allocated(model%program)) np = size(model%program)
      allocate (prog(5, np))
      do k = 1, np
         associate (c => model%program(k))
            prog(:, k) = [real(code(c%name), wp), real(code(c%option), wp), c%v]
         end associate
      end do
      if (ar%saving) then
         call ar%item('model.commands', np)
         call ar%item('model.program', prog)
      else
         ! the program as it was, judged by the caller (changes that leave the state up to the
         ! restart point as it is are allowed)
         call ar%item('model.commands', np)
         if (allocated(ar%err)) return
         allocate (ar%program(5, np))
         if (np > 0) call ar%item('model.program', ar%program)
      end if
      call same_int(ar, 'model.requests', size_requests(model), 'the number of TPLOt requests')
   end subroutine identity

   !> The 4 characters of a command name or option as one number.
   pure integer function code(s)
      character(len=4), intent(in) :: s
      integer :: i
      code = 0
      do i = 1, 4
         code = code*128 + iachar(s(i:i))
      end do
   end function code

   pure integer function size_requests(model)
      type(model_t), intent(in) :: model
      size_requests = 0
      if (allocated(model%requests)) size_requests = size(model%requests)
   end function size_requests

   !> Save n, or load the saved value and refuse a difference.
   subroutine same_int(ar, name, n, what)
      type(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name, what
      integer, intent(in) :: n
      integer :: saved
      if (allocated(ar%err)) return
      saved = n
      call ar%item(name, saved)
      if (allocated(ar%err) .or. ar%saving) return
      if (saved /= n) call make_error(ar%err, 'it was written for another deck: '//what// &
                                      ' differs (restart file '//itoa(saved)//', deck '//itoa(n)//')')
   end subroutine same_int

   !> Save x, or load the saved values and refuse a difference, naming its first entry
   !> (entry k of `per` values is item (k - 1)/per + 1).
   subroutine same_reals(ar, name, x, what, per)
      type(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name, what
      real(wp), intent(in) :: x(:)
      integer, intent(in) :: per
      real(wp), allocatable :: saved(:)
      if (allocated(ar%err)) return
      saved = x
      call ar%item(name, saved)
      if (allocated(ar%err) .or. ar%saving) return
      call differ(ar, what, findloc(saved /= x, .true., dim=1), per)
   end subroutine same_reals

   !> Integer version of same_reals.
   subroutine same_ints(ar, name, x, what, per)
      type(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name, what
      integer, intent(in) :: x(:)
      integer, intent(in) :: per
      integer, allocatable :: saved(:)
      if (allocated(ar%err)) return
      saved = x
      call ar%item(name, saved)
      if (allocated(ar%err) .or. ar%saving) return
      call differ(ar, what, findloc(saved /= x, .true., dim=1), per)
   end subroutine same_ints

   !> The refusal of same_reals and same_ints when entry k (> 0) of the saved values differs from
   !> the deck's (entry k of `per` values is item (k - 1)/per + 1); nothing when k = 0.
   subroutine differ(ar, what, k, per)
      type(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: what
      integer, intent(in) :: k, per
      if (k == 0) return
      call make_error(ar%err, 'it was written for another deck: '//what//' differ (first at '// &
                      'number '//itoa((k - 1)/per + 1)//')')
   end subroutine differ

   ! ---------------------------------------------------------------------------- the state

   !> Every item of the state, saved or loaded.
   subroutine visit(ar, stp, out, pos)
      type(archive_t), intent(inout) :: ar
      type(stepper_t), intent(inout) :: stp
      type(output_t), intent(inout) :: out
      type(run_position_t), intent(inout) :: pos
      integer :: k

      associate (st => stp%st)
         call ar%item('state.u', st%u)
         call ar%item('state.v', st%v)
         call ar%item('state.a', st%a)
         call ar%item('state.fint', st%fint)
         call ar%item('state.fext', st%fext)
         if (.not. ar%saving) st%fext_zero = plus_zero(st%fext)
         call ar%item('state.fcon', st%fcon)
         call ar%item('state.mass', st%mass)
         call ar%item('state.minv', st%minv)
         call ar%item('state.t', st%t)
         call ar%item('state.dt_prev', st%dt_prev)
         call ar%item('state.dt', st%dt)
         call ar%item('state.step', st%step)
         call ar%item('state.kinetic', st%energy%kinetic)
         call ar%item('state.strain', st%energy%strain)
         call ar%item('state.hourglass', st%energy%hourglass)
         call ar%item('state.wext', st%energy%wext)
         call ar%item('state.wcon', st%energy%wcon)
         call ar%item('state.total0', st%energy%total0)
         call ar%item('state.wpm', st%energy%wpm)
         call ar%item('state.momentum', st%momentum)
         call ar%item('state.jmin', st%jmin)
         call ar%item('state.nactive', st%nactive)
         call ar%item('state.plastic', st%energy%plastic)
         ! the dissipations of doc/damping.md: their energy and the nodal forces of the last pass
         if (allocated(st%gdamp)) then
            call ar%item('state.damping', st%energy%damping)
            call ar%item('state.gdamp', st%gdamp)
         end if
         if (allocated(st%gbulk)) then
            call ar%item('state.bulk', st%energy%bulk)
            call ar%item('state.gbulk', st%gbulk)
         end if
         call ar%item('state.body_power', st%body_power)
         call ar%item('state.correction0', st%correction0)
         call ar%item('state.dt_residual', st%dt_residual)
         call ar%item('state.dt_booked', st%dt_booked)
         call ar%item('state.contact_residual', st%contact_residual)
      end associate
      call ar%item('stepper.started', stp%started)
      call ar%item('stepper.cfl_mode', stp%cfl_mode)
      call ar%item('stepper.cfl', stp%cfl)
      call ar%item('stepper.dt_fixed', stp%dt_fixed)
      call ar%item('stepper.dt_stable', stp%dt_stable)
      call ar%item('stepper.dt_element', stp%dt_element)
      call ar%item('stepper.dt_elements', stp%dt_elements)
      call ar%item('stepper.dt_elements_at', stp%dt_elements_at)
      call ar%item('stepper.folded', stp%folded)
      call ar%item('stepper.tmax', stp%tmax)
      call ar%item('stepper.landed_tmax', stp%landed_tmax)
      call ar%item('stepper.dt_warned', stp%dt_warned)
      call ar%item('stepper.energy_warn', stp%energy_warn)
      call ar%item('stepper.energy_stop', stp%energy_stop)
      call ar%item('stepper.energy_warned', stp%energy_warned)
      call ar%item('stepper.growth_max', stp%growth_max)
      call ar%item('stepper.growth_max_t', stp%growth_max_t)
      call ar%item('stepper.pass_limit_warnings', stp%pass_limit_warnings)
      if (allocated(stp%x)) then
         ! the work arrays of steps that are not plain: a plain run (no contact, loads or masses
         ! per dof) has none, and the deck allocates them alike when the run is continued
         call ar%item('stepper.x', stp%x)
         call ar%item('stepper.du', stp%du)
         call ar%item('stepper.a_old', stp%a_old)
         call ar%item('stepper.vt', stp%vt)
         call ar%item('stepper.fcon_old', stp%fcon_old)
      end if
      call ar%item('stepper.time_forces', stp%time_forces)
      call ar%item('stepper.time_steps', stp%time_steps)
      if (allocated(stp%st%status)) then
         ! element erosion (doc/erosion.md): the status, then the sets without the eroded elements
         call ar%item('state.status', stp%st%status)
         call ar%item('state.neroded', stp%st%neroded)
         call ar%item('state.eroded', stp%st%energy%eroded)
         call ar%item('state.eroded_momentum', stp%st%eroded_momentum)
         if (.not. ar%saving .and. .not. allocated(ar%err)) call erosion_restore(stp%ero, stp%st, stp%sets)
      end if
      do k = 1, size(stp%sets)
         ! a material with history per point keeps it in the set, hist(nvar, nq*nq, nel)
         if (allocated(stp%sets(k)%hist)) call ar%item('set'//itoa(k)//'.hist', stp%sets(k)%hist)
         call ar%item('set'//itoa(k)//'.nel', stp%sets(k)%nel)
      end do
      call visit_contact(ar, stp%contact)
      call visit_loading(ar, stp)
      call visit_output(ar, out)
      call ar%item('program.pc', pos%pc)
      call ar%item('program.form_pc', pos%form_pc)
      call ar%item('program.save_t0', pos%save_t0)
      call ar%item('program.depth', pos%depth)
      call ar%item('program.remaining', pos%remaining)
      call ar%item('program.print_inc', pos%print_inc)
      call ar%item('program.save_dt', pos%save_dt)
      call ar%item('program.save_next', pos%save_next)
      call ar%item('program.save_on', pos%save_on)
   end subroutine visit

   !> The contact's state that lasts from step to step: the pairs' accumulated work and last
   !> results, the run's statistics, the corrector's counters and the massless faces' stiffness
   !> rows. (Everything else is rebuilt at every step: candidates, normals, the corrector's
   !> factorization.) A contact law with a state of its
   !> own (friction) adds its items here.
   subroutine visit_contact(ar, c)
      type(archive_t), intent(inout) :: ar
      type(contact_t), intent(inout) :: c
      integer :: k, n
      character(len=:), allocatable :: p
      if (.not. c%active) return
      do k = 1, size(c%results)
         p = 'contact.pair'//itoa(k)//'.'
         call ar%item(p//'fnormal', c%results(k)%fnormal)
         call ar%item(p//'force', c%results(k)%force)
         call ar%item(p//'penetration', c%results(k)%penetration)
         call ar%item(p//'pmax', c%results(k)%pmax)
         call ar%item(p//'work', c%results(k)%work)
         call ar%item(p//'nactive', c%results(k)%nactive)
         if (c%friction) then
            call ar%item(p//'ftangent', c%results(k)%ftangent)
            call ar%item(p//'nstick', c%results(k)%nstick)
            call ar%item(p//'nslip', c%results(k)%nslip)
            call ar%item(p//'dissipation', c%results(k)%dissipation)
            call ar%item(p//'pending', c%results(k)%pending)
         end if
      end do
      if (c%friction) then
         ! Coulomb friction (doc/friction.md): the booking one step late and the last step's
         ! slip speeds and forces; the penalty law's tangential springs per pass
         call ar%item('contact.friction.dissipation', c%dissipation)
         call ar%item('contact.friction.pending', c%pending)
         if (allocated(c%vslip)) call ar%item('contact.friction.vslip', c%vslip)
         if (allocated(c%ffric)) call ar%item('contact.friction.ffric', c%ffric)
         if (allocated(c%xold)) call ar%item('contact.friction.xold', c%xold)
         call ar%item('contact.friction.nsweeps', c%fr%nsweeps)
         call ar%item('contact.friction.ncalls', c%fr%ncalls)
         call ar%item('contact.friction.sweep_limit_hits', c%fr%sweep_limit_hits)
         call ar%item('contact.friction.pass_limit_hits', c%fr%pass_limit_hits)
         do k = 1, size(c%passes)
            associate (h => c%passes(k)%hist)
               p = 'contact.pass'//itoa(k)//'.penalty_friction.'
               if (allocated(h%q)) then      ! penalty passes with friction only
                  call ar%item(p//'q', h%q)
                  call ar%item(p//'vslip', h%vslip)
                  call ar%item(p//'nodes', h%nodes)
                  call ar%item(p//'n', h%n)
               end if
            end associate
         end do
         call visit_pair_history(ar, c%auto_hist)
      end if
      do k = 1, c%nfixed
         ! the corners each corner pass held at the last step (contact_step, eq. K.2)
         if (.not. c%passes(k)%corners) cycle
         p = 'contact.pass'//itoa(k)//'.corners_held'
         n = size(c%passes(k)%held)
         call ar%item(p//'.n', n)
         if (.not. ar%saving) then
            deallocate (c%passes(k)%held)
            allocate (c%passes(k)%held(max(n, 0)))
         end if
         if (n > 0) call ar%item(p, c%passes(k)%held)
      end do
      call ar%item('contact.max_penetration', c%max_penetration)
      call ar%item('contact.nredundant', c%nredundant)
      call ar%item('contact.time_search', c%time_search)
      call ar%item('contact.time_corrector', c%time_corrector)
      call ar%item('contact.xp', c%xp)
      call ar%item('contact.corrector.passes', c%corr%passes)
      call ar%item('contact.corrector.nredundant', c%corr%nredundant)
      call ar%item('contact.corrector.pass_limit_hits', c%corr%pass_limit_hits)
      call ar%item('contact.corrector.nsolves', c%corr%nsolves)
      call ar%item('contact.corrector.ndense', c%corr%ndense)
      call ar%item('contact.corrector.nsparse', c%corr%nsparse)
      if (c%face%active) then
         ! massless contact faces (doc/impact.md, section 3.2): the face rows as last formed
         ! (the initial stiffness or a refreshed tangent), where they were formed, K_FF of them
         call ar%item('contact.face.val', c%face%val)
         call ar%item('contact.face.uref', c%face%uref)
         call ar%item('contact.face.nrefresh', c%face%nrefresh)
         call ar%item('contact.face.nsolves', c%face%nsolves)
         if (.not. ar%saving .and. .not. allocated(ar%err)) call c%face%refactor(ar%err)
      end if
   end subroutine visit_contact

   !> The tangential state of penalty friction under AUTOmatic, per pair of surfaces
   !> (src/exic/contact/pair_history.f90): the sizes first, then the pairs and their entries.
   subroutine visit_pair_history(ar, h)
      type(archive_t), intent(inout) :: ar
      type(pair_history_t), intent(inout) :: h
      integer :: npair, ntot
      integer, allocatable :: pairs(:, :), counts(:), nodes(:)
      real(wp), allocatable :: q(:), vslip(:)
      character(len=*), parameter :: p = 'contact.auto_penalty_friction.'
      npair = h%npair
      ntot = h%total()
      call ar%item(p//'npair', npair)
      call ar%item(p//'entries', ntot)
      if (allocated(ar%err) .or. npair == 0) return
      allocate (pairs(2, npair), counts(npair), nodes(ntot), q(ntot), vslip(ntot))
      if (ar%saving) call h%flatten(pairs, counts, nodes, q, vslip)
      call ar%item(p//'pairs', pairs)
      call ar%item(p//'counts', counts)
      if (ntot > 0) then
         call ar%item(p//'nodes', nodes)
         call ar%item(p//'q', q)
         call ar%item(p//'vslip', vslip)
      end if
      if (.not. ar%saving .and. .not. allocated(ar%err)) call h%unflatten(npair, pairs, counts, nodes, q, vslip)
   end subroutine visit_pair_history

   !> Loads, prescribed motion and rigid bodies (doc/loads.md): what changes during the run.
   subroutine visit_loading(ar, stp)
      type(archive_t), intent(inout) :: ar
      type(stepper_t), intent(inout) :: stp
      integer :: k
      character(len=:), allocatable :: p
      associate (ld => stp%ld)
         call ar%item('loading.active', ld%active)
         call ar%item('loading.track_work', ld%track_work)
         call ar%item('loading.wext_p', ld%wext_p)
         call ar%item('loading.wpm_p', ld%wpm_p)
         if (allocated(ld%pv)) call ar%item('loading.pv', ld%pv)
         if (allocated(ld%fedge)) call ar%item('loading.fedge', ld%fedge)
         if (allocated(ld%fext_old)) call ar%item('loading.fext_old', ld%fext_old)
         if (allocated(ld%favg)) call ar%item('loading.favg', ld%favg)
         if (allocated(ld%vold)) call ar%item('loading.vold', ld%vold)
         if (allocated(ld%rold)) call ar%item('loading.rold', ld%rold)
         if (allocated(ld%rb%r)) call ar%item('loading.levers', ld%rb%r)
         if (.not. allocated(ld%bodies)) return
         do k = 1, size(ld%bodies)
            p = 'loading.body'//itoa(k)//'.'
            associate (b => ld%bodies(k))
               call ar%item(p//'xc', b%xc)
               call ar%item(p//'th', b%th)
               call ar%item(p//'v', b%v)
               call ar%item(p//'om', b%om)
               call ar%item(p//'a', b%a)
               call ar%item(p//'al', b%al)
               call ar%item(p//'vn', b%vn)
               call ar%item(p//'omn', b%omn)
               call ar%item(p//'an', b%an)
               call ar%item(p//'aln', b%aln)
            end associate
         end do
      end associate
   end subroutine visit_loading

   !> The output schedules and what the files held at the save (output_t%checkpoint).
   subroutine visit_output(ar, out)
      type(archive_t), intent(inout) :: ar
      type(output_t), intent(inout) :: out
      call ar%item('output.his_inc', out%his_inc)
      call ar%item('output.last_row_step', out%last_row_step)
      call ar%item('output.field_dt', out%field_dt)
      call ar%item('output.field_next', out%field_next)
      call ar%item('output.field_last', out%field_last)
      call ar%item('output.field_t0', out%field_t0)
      call ar%item('output.field_checked', out%field_checked)
      call ar%item('output.warned_interval', out%warned_interval)
      call ar%item('output.his_bytes', out%saved_his_bytes)
      call ar%item('output.ene_bytes', out%saved_ene_bytes)
      call ar%item('output.field_times', out%saved_field_times)
   end subroutine visit_output

   ! ---------------------------------------------------------------------------- items

   subroutine real1(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      real(wp), intent(inout), contiguous :: x(:)
      if (allocated(ar%err)) return
      if (ar%saving) then
         call ar%h5%write(name, x, ar%err)
      else
         call ar%h5%read(name, x, ar%err)
      end if
   end subroutine real1

   subroutine real2(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      real(wp), intent(inout), contiguous, target :: x(:, :)
      real(wp), pointer, contiguous :: flat(:)
      flat(1:size(x)) => x
      call real1(ar, name, flat)
   end subroutine real2

   subroutine real3(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      real(wp), intent(inout), contiguous, target :: x(:, :, :)
      real(wp), pointer, contiguous :: flat(:)
      flat(1:size(x)) => x
      call real1(ar, name, flat)
   end subroutine real3

   subroutine real0(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      real(wp), intent(inout) :: x
      real(wp) :: b(1)
      b(1) = x
      call real1(ar, name, b)
      x = b(1)
   end subroutine real0

   subroutine int1(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      integer, intent(inout), contiguous :: x(:)
      if (allocated(ar%err)) return
      if (ar%saving) then
         call ar%h5%write(name, x, ar%err)
      else
         call ar%h5%read(name, x, ar%err)
      end if
   end subroutine int1

   subroutine int2(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      integer, intent(inout), contiguous, target :: x(:, :)
      integer, pointer, contiguous :: flat(:)
      flat(1:size(x)) => x
      call int1(ar, name, flat)
   end subroutine int2

   subroutine int0(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      integer, intent(inout) :: x
      integer :: b(1)
      b(1) = x
      call int1(ar, name, b)
      x = b(1)
   end subroutine int0

   subroutine log0(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      logical, intent(inout) :: x
      integer :: b
      b = merge(1, 0, x)
      call int0(ar, name, b)
      x = b /= 0
   end subroutine log0

   subroutine i80(ar, name, x)
      class(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      integer(i8), intent(inout) :: x
      integer(i8) :: b(1)
      if (allocated(ar%err)) return
      b(1) = x
      if (ar%saving) then
         call save_i8(ar, name, b)
      else
         call ar%h5%read(name, b, ar%err)
         x = b(1)
      end if
   end subroutine i80

   !> A 64-bit integer as a dataset of one value.
   subroutine save_i8(ar, name, b)
      type(archive_t), intent(inout) :: ar
      character(len=*), intent(in) :: name
      integer(i8), intent(in) :: b(1)
      call ar%h5%create_series(name, DTYPE_INT64, [integer ::], ar%err)
      if (.not. allocated(ar%err)) call ar%h5%append(name, b(1), ar%err)
   end subroutine save_i8

end module exic_restart
