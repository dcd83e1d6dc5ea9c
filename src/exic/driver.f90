!> Runs a model's solution program (spec section 5): the explicit time loop with its outputs.
module exic_driver
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_progress, only: progress_t
   use exic_model, only: model_t
   use exic_io_program, only: REQ_DISP, REQ_VELO, REQ_ACCE, REQ_STRE, REQ_REAC, REQ_CONT, REQ_MOME
   use exic_io_history, only: history_files_t
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_solver, only: solver_init, solver_forces, solver_stable_dt, solver_energies, &
                                   element_stress, all_stresses, cd_displacement, cd_predictor, cd_velocity
   use exic_contact_contact, only: contact_t
   use exic_io_fields, only: field_writer_t
   implicit none
   private

   public :: run_options_t, run_t, run_model

   !> How a run is made.
   type :: run_options_t
      character(len=:), allocatable :: base   !< output path without extension: dir/stem
      logical :: quiet = .false.              !< no console progress lines
   end type run_options_t

   !> A run in progress: state, element sets, contact, outputs and the time-step control.
   type :: run_t
      type(state_t) :: st
      type(element_set_t), allocatable :: sets(:)
      type(contact_t) :: contact
      type(history_files_t) :: files
      type(field_writer_t) :: fields
      character(len=:), allocatable :: base    !< output path without extension
      real(wp) :: field_dt = 0.0_wp             !< OUTPut,HDF5 interval (0: no field output)
      real(wp) :: field_next = 0.0_wp           !< time of the next field output
      real(wp) :: field_last = -huge(1.0_wp)    !< time of the last field output
      type(progress_t) :: progress
      logical :: started = .false.
      logical :: cfl_mode = .true.
      real(wp) :: cfl = 0.9_wp
      real(wp) :: dt_fixed = 0.0_wp
      real(wp) :: dt_stable = 0.0_wp            !< last stable-step estimate
      integer :: dt_element = 0                 !< element that sets it
      real(wp) :: tmax = -1.0_wp                !< from the innermost TIME,,tmax seen
      integer :: his_inc = 0                    !< TPLOt interval (0: no histories)
      integer :: print_inc = 0                  !< PRINt,ENERgy interval
      integer(i8) :: last_row_step = -1
      logical :: dt_warned = .false.
      real(wp), allocatable :: values(:)        !< one history row
      integer, allocatable :: region_of_node(:) !< region of the elements that use each node
      real(wp), allocatable :: du(:, :), a_old(:, :), vt(:, :), fcon_old(:, :)   !< step work arrays
      real(wp), allocatable :: xcur(:, :)       !< current coordinates for the stable step
      real(wp) :: wall_start = 0.0_wp
      real(wp) :: time_forces = 0.0_wp          !< wall time in the element loop and stable step
      real(wp) :: time_steps = 0.0_wp           !< wall time in FORM (whole steps)
   end type run_t

contains

   !> Run `model`'s program. On error, every output written so far is kept and closed.
   subroutine run_model(model, opts, err)
      type(model_t), intent(in) :: model
      type(run_options_t), intent(in) :: opts
      type(error_t), allocatable, intent(out) :: err
      type(run_t) :: r

      r%wall_start = wall_time()
      r%base = opts%base
      call r%files%open(opts%base, err)
      if (.not. allocated(err)) call write_preamble(r, model)
      if (.not. allocated(err)) call solver_init(model, r%st, r%sets, err)
      if (.not. allocated(err)) call r%contact%init(model, r%st, err)
      if (.not. allocated(err)) then
         call write_summary(r, model)
         call r%progress%begin(opts%quiet)
         call execute(r, model, err)
      end if
      call finish(r, model, err)
   end subroutine run_model

   !> Interpret the BATCh program.
   subroutine execute(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: pc, depth
      integer :: remaining(8)
      character(len=80) :: buf

      pc = 1
      depth = 0
      do while (pc <= size(model%program))
         associate (c => model%program(pc))
            select case (c%name)
            case ('tran')
               continue
            case ('dt')
               if (c%option == 'cfl') then
                  r%cfl_mode = .true.
                  r%cfl = c%v(1)
                  if (r%cfl <= 0.0_wp) r%cfl = 0.9_wp
               else
                  r%cfl_mode = .false.
                  r%dt_fixed = c%v(1)
               end if
               if (r%started) call choose_dt(r, err, c%where)
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
               call ensure_started(r, model, err)
               if (allocated(err)) return
               call record(r, model)
               call field_output(r, err)
               if (allocated(err)) return
               if (c%v(1) > 0.0_wp) then
                  r%tmax = c%v(1)
                  if (r%st%t >= r%tmax*(1.0_wp - 1.0e-12_wp) .and. depth > 0) then
                     pc = find_next(model, pc)   ! leave the innermost loop
                     depth = depth - 1
                  end if
               end if
            case ('form')
               call ensure_started(r, model, err)
               if (.not. allocated(err)) call explicit_step(r, err)
               if (allocated(err)) return
            case ('tplo')
               r%his_inc = max(1, nint(c%v(1)))
            case ('init')
               where (spread(c%given, 1, 2)) r%st%v = c%data
               where (r%st%minv == 0.0_wp .and. .not. spread(r%st%rigid, 1, 2)) r%st%v = 0.0_wp
               if (r%started) call solver_energies(r%st)
            case ('outp')
               call open_fields(r, model, c%v(1), err)
               if (allocated(err)) return
            case ('prin')
               r%print_inc = max(1, nint(c%v(1)))
            case default
               write (buf, '(a)') 'solution command '//trim(c%name)//' is not implemented'
               call make_error(err, trim(buf), c%where)
               return
            end select
         end associate
         pc = pc + 1
      end do
   end subroutine execute

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

   !> First use of the state: forces, step size and the initial (contact-corrected) acceleration.
   subroutine ensure_started(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(out) :: err
      integer :: ebad

      if (r%started) return
      r%started = .true.
      allocate (r%du(2, r%st%nnode), r%a_old(2, r%st%nnode), r%vt(2, r%st%nnode), &
                r%fcon_old(2, r%st%nnode), r%xcur(2, r%st%nnode), source=0.0_wp)
      call history_header(r, model)
      call node_regions(r, model)
      call solver_forces(r%st, r%sets, ebad)
      if (ebad /= 0) then
         call inverted_error(r, ebad, err)
         return
      end if
      call choose_dt(r, err, 'DT')
      if (allocated(err)) return
      r%st%a = r%st%minv*(r%st%fext - r%st%fint)
      ! at t(0) the predictor velocity is the initial velocity itself and
      ! x(1) = x(0) + dt v(0) + dt^2/2 a(0): the corrector's c is dt^2/2 (dt(n) = 0)
      r%st%dt_prev = 0.0_wp
      call r%contact%correct(r%st, r%st%v, err)
      if (allocated(err)) return
      call solver_energies(r%st)
      r%st%total0 = r%st%kinetic + r%st%strain + r%st%hourglass
   end subroutine ensure_started

   !> Set dt(n+1): fixed (checked against the stable limit) or CFL x the stable limit.
   subroutine choose_dt(r, err, where)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      character(len=*), intent(in) :: where
      character(len=200) :: buf
      integer :: n
      real(wp) :: target, dtp

      call solver_stable_dt(r%st, r%sets, r%dt_stable, r%dt_element, r%xcur)
      if (r%contact%any_penalty) then
         ! a penalty spring adds its frequency to that of the elements at its nodes:
         ! omega^2 <= omega_elements^2 + omega_penalty^2, i.e. 1/dt^2 adds up
         dtp = r%contact%stable_dt(r%st)
         if (dtp < huge(1.0_wp)) then
            r%dt_stable = 1.0_wp/sqrt(1.0_wp/r%dt_stable**2 + 1.0_wp/dtp**2)
            r%dt_element = 0
         end if
      end if
      if (r%cfl_mode) then
         if (r%dt_stable >= huge(1.0_wp)) then
            call make_error(err, 'DT,CFL needs at least one deformable element to set the step', where)
            return
         end if
         ! Hysteresis: the step shrinks at once when the stable step falls below it, and grows
         ! only when it is more than 15 % below c x the stable step. A step that followed every
         ! breath of the mesh would vary in time with the motion, and such a modulated
         ! central-difference step pumps energy into the mode that modulates it.
         target = r%cfl*r%dt_stable
         if (r%st%dt <= 0.0_wp .or. r%st%dt > target .or. r%st%dt < 0.85_wp*target) r%st%dt = target
         ! land exactly on tmax with steps no larger than the stable one
         if (r%tmax > r%st%t) then
            n = ceiling((r%tmax - r%st%t)/r%st%dt*(1.0_wp - 1.0e-12_wp))
            if (n >= 1 .and. n <= 4) r%st%dt = (r%tmax - r%st%t)/real(n, wp)
         end if
      else
         if (r%dt_fixed <= 0.0_wp) then
            call make_error(err, 'DT,,dt needs a positive step', where)
            return
         end if
         r%st%dt = r%dt_fixed
         if (r%dt_fixed > r%dt_stable) then
            write (buf, '(a,es12.5,a,es12.5,a,i0,a)') 'DT = ', r%dt_fixed, &
               ' exceeds the stable limit ', r%dt_stable, ' (element ', r%dt_element, &
               '); use a smaller DT or DT,CFL,c'
            if (.not. r%started .or. r%st%step == 0) then
               call make_error(err, trim(buf), where)
            else if (.not. r%dt_warned) then
               r%dt_warned = .true.
               call r%files%say('warning: at t = '//rtoa(r%st%t)//': '//trim(buf))
            end if
         end if
      end if
   end subroutine choose_dt

   !> One explicit step (FORM,EXPLicit): update, forces, predictor, contact corrector, velocity.
   subroutine explicit_step(r, err)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      integer :: ebad
      real(wp) :: t0, t1

      t0 = wall_time()
      associate (st => r%st)
         ! x(n+1) = x(n) + dt(n) v(n) + dt(n)^2/2 a(n)
         call cd_displacement(st%nnode, st%dt, st%v, st%a, st%u, r%du, r%a_old)
         st%t = st%t + st%dt
         st%dt_prev = st%dt
         st%step = st%step + 1
         if (r%contact%active) r%fcon_old = st%fcon

         t1 = wall_time()
         call solver_forces(st, r%sets, ebad)
         if (ebad /= 0) then
            call inverted_error(r, ebad, err)
            return
         end if
         call choose_dt(r, err, 'DT')
         r%time_forces = r%time_forces + (wall_time() - t1)
         if (allocated(err)) return
         ! predictor, eq. 4.3-4.4 (v~ only when there is contact to search)
         call cd_predictor(st%nnode, st%dt_prev, st%minv, st%fext, st%fint, st%v, r%a_old, st%a, &
                           r%contact%active, r%vt)
         call r%contact%correct(st, r%vt, err)
         if (allocated(err)) return
         ! v(n+1) and the work of external and contact forces over the step (trapezoid rule)
         call cd_velocity(st%nnode, st%dt_prev, r%a_old, st%a, st%fext, r%du, r%contact%active, &
                          r%fcon_old, st%fcon, st%v, st%wext, st%wcon)
      end associate
      call solver_energies(r%st)
      r%time_steps = r%time_steps + (wall_time() - t0)
      call check_health(r, err)
      if (allocated(err)) return
      if (r%print_inc > 0) then
         if (mod(r%st%step, int(r%print_inc, i8)) == 0) call print_energy(r)
      end if
      call r%progress%update(r%st%t, r%tmax, r%st%step)
   end subroutine explicit_step

   !> OUTPut,HDF5,dt_out: open <stem>.h5 and <stem>.xdmf with the mesh.
   subroutine open_fields(r, model, dt_out, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: dt_out
      type(error_t), allocatable, intent(out) :: err
      if (r%fields%is_open()) return
      r%field_dt = dt_out
      r%field_next = r%st%t
      call r%fields%open(r%base//'.h5', r%base//'.xdmf', model%mesh%nnode, model%mesh%nelem, &
                         model%mesh%x, model%mesh%conn, model%mesh%region, model%mesh%mat, &
                         r%contact%edges(), err)
   end subroutine open_fields

   !> Write the fields when an output time is due (every dt_out, the first at once).
   subroutine field_output(r, err)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      real(wp), allocatable :: sig(:, :)
      integer, allocatable :: flag(:)
      real(wp) :: energies(5)
      character(len=16), parameter :: names(5) = [character(len=16) :: 'kinetic', 'strain', &
                                                   'external_work', 'contact_work', 'hourglass']
      if (.not. r%fields%is_open()) return
      if (r%st%t < r%field_next*(1.0_wp - 1.0e-12_wp)) return
      do while (r%field_next <= r%st%t*(1.0_wp + 1.0e-12_wp))
         r%field_next = r%field_next + r%field_dt
      end do
      allocate (sig(7, r%st%nelem), flag(r%st%nnode))
      call all_stresses(r%st, r%sets, sig)
      flag = merge(1, 0, r%st%fcon(1, :) /= 0.0_wp .or. r%st%fcon(2, :) /= 0.0_wp)
      energies = [r%st%kinetic, r%st%strain + r%st%hourglass, r%st%wext, r%st%wcon, r%st%hourglass]
      call r%fields%write_step(r%st%t, r%st%step, r%st%u, r%st%v, r%st%a, sig, r%st%fcon, flag, &
                               energies, names, err)
      r%field_last = r%st%t
   end subroutine field_output

   !> Stop on NaN or runaway energy.
   subroutine check_health(r, err)
      type(run_t), intent(inout) :: r
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: e, scale
      associate (st => r%st)
         e = st%kinetic + st%strain + st%hourglass
         scale = abs(st%total0) + abs(st%wext) + abs(st%wcon) + tiny(1.0_wp)
         if (.not. (e == e) .or. .not. (st%wext == st%wext)) then
            call make_error(err, 'NaN in the solution at t = '//rtoa(st%t)//', step '// &
                            itoa(int(st%step)))
         else if (e > 10.0_wp*scale) then
            call make_error(err, 'runaway energy at t = '//rtoa(st%t)//': kinetic + strain = '// &
                            rtoa(e)//' against '//rtoa(scale)// &
                            ' put in; the step is probably unstable')
         end if
      end associate
   end subroutine check_health

   !> The error for an element whose Jacobian is no longer positive.
   subroutine inverted_error(r, ebad, err)
      type(run_t), intent(in) :: r
      integer, intent(in) :: ebad
      type(error_t), allocatable, intent(out) :: err
      call make_error(err, 'element '//itoa(ebad)//' inverted (J <= 0) at t = '// &
                      rtoa(r%st%t)//', step '//itoa(int(r%st%step)))
   end subroutine inverted_error

   !> Region of every node (of the last element that uses it; -huge for unused nodes).
   subroutine node_regions(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer :: e
      allocate (r%region_of_node(r%st%nnode), source=-huge(1))
      do e = 1, model%mesh%nelem
         r%region_of_node(model%mesh%conn(:, e)) = model%mesh%region(e)
      end do
   end subroutine node_regions

   !> The '#' header of <stem>.his.
   subroutine history_header(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      character(len=32), allocatable :: labels(:)
      character(len=4), parameter :: names(7) = ['disp', 'velo', 'acce', 'stre', 'reac', 'cont', 'mome']
      character(len=1), parameter :: tags(7) = ['n', 'n', 'n', 'e', 'n', 'p', 'r']
      integer :: k, nreq

      nreq = 0
      if (allocated(model%requests)) nreq = size(model%requests)
      allocate (labels(nreq), r%values(nreq))
      do k = 1, nreq
         associate (q => model%requests(k))
            write (labels(k), '(a,a,a,i0,a,i0,a)') names(q%kind), '(', tags(q%kind), q%id, ',', q%comp, ')'
         end associate
      end do
      call r%files%his_header(labels)
   end subroutine history_header

   !> Write the history and energy rows of the current state when their interval is due.
   subroutine record(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      logical :: due
      due = r%his_inc > 0
      if (due) due = mod(r%st%step, int(r%his_inc, i8)) == 0
      if (r%st%step == 0) due = .true.
      if (.not. due .or. r%last_row_step == r%st%step) return
      call write_rows(r, model)
   end subroutine record

   !> History and energy rows of the current state.
   subroutine write_rows(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer :: k
      real(wp) :: sig(7), total, drift, denom

      do k = 1, size(r%values)
         associate (q => model%requests(k), st => r%st)
            select case (q%kind)
            case (REQ_DISP)
               r%values(k) = st%u(q%comp, q%id)
            case (REQ_VELO)
               r%values(k) = st%v(q%comp, q%id)
            case (REQ_ACCE)
               r%values(k) = st%a(q%comp, q%id)
            case (REQ_STRE)
               call element_stress(st, r%sets, q%id, sig)
               r%values(k) = sig(q%comp)
            case (REQ_REAC)
               ! force the support exerts on the body: M a = F + R - P with a = 0 on a fixed dof
               r%values(k) = st%fint(q%comp, q%id) - st%fext(q%comp, q%id)
            case (REQ_CONT)
               r%values(k) = r%contact%pair_value(q%id, q%comp)
            case (REQ_MOME)
               r%values(k) = region_momentum(r, q%id, q%comp)
            end select
         end associate
      end do
      associate (st => r%st)
         call r%files%his_row(st%t, r%values)
         total = st%kinetic + st%strain + st%hourglass - st%wext - st%wcon
         denom = max(abs(st%total0), st%kinetic + st%strain + st%hourglass, tiny(1.0_wp))
         drift = (total - st%total0)/denom
         call r%files%ene_row(st%t, st%step, st%dt, st%kinetic, st%strain + st%hourglass, st%wext, &
                              st%wcon, total, drift, st%momentum, st%nactive, st%hourglass)
      end associate
      r%last_row_step = r%st%step
   end subroutine write_rows

   !> Linear momentum component `comp` of the nodes of region `region` (TPLOt `mome` [ext]).
   real(wp) function region_momentum(r, region, comp) result(p)
      type(run_t), intent(in) :: r
      integer, intent(in) :: region, comp
      integer :: i
      p = 0.0_wp
      do i = 1, r%st%nnode
         if (r%region_of_node(i) == region) p = p + r%st%mass(i)*r%st%v(comp, i)
      end do
   end function region_momentum

   !> PRINt,ENERgy: a one-line energy balance on the console.
   subroutine print_energy(r)
      type(run_t), intent(in) :: r
      associate (st => r%st)
         print '(a,es12.5,a,i0,a,es12.5,a,es12.5,a,es12.5,a,es12.5)', ' t=', st%t, ' step ', st%step, &
            ' K=', st%kinetic, ' U=', st%strain + st%hourglass, ' Wext=', st%wext, ' Wc=', st%wcon
      end associate
   end subroutine print_energy

   !> The deck echo and reader warnings at the top of <stem>.out.
   subroutine write_preamble(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      call r%files%say('exic: explicit finite elements for 2-D dynamic contact')
      if (allocated(model%title)) call r%files%say('title: '//model%title)
      if (allocated(model%deck_file)) call r%files%say('deck:  '//model%deck_file)
      call r%files%say('')
      call r%files%say('---- deck ----')
      if (allocated(model%echo)) call r%files%say(model%echo)
      call r%files%say('---- end of deck ----')
      if (allocated(model%warnings)) then
         if (len(model%warnings) > 0) call r%files%say(model%warnings)
      end if
   end subroutine write_preamble

   !> Mesh, material and stable-step summary in <stem>.out.
   subroutine write_summary(r, model)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      integer :: k
      real(wp) :: dts
      integer :: e
      call r%files%say('')
      call r%files%say('nodes (highest number) '//itoa(r%st%nnode)//', active '// &
                       itoa(count(r%st%active))//', elements '//itoa(r%st%nelem))
      do k = 1, size(r%sets)
         associate (s => r%sets(k), m => model%materials(r%sets(k)%mat))
            if (s%kind == 1) then
               call r%files%say('material '//itoa(s%mat)//': solid neo-Hookean, E = '// &
                  rtoa(m%young)//', nu = '//rtoa(m%poisson)//', lambda = '// &
                  rtoa(m%lambda)//', mu = '//rtoa(m%mu)//', rho = '//rtoa(m%rho)// &
                  ', quadrature '//itoa(s%nq)//', elements '//itoa(s%nel))
            else
               call r%files%say('material '//itoa(s%mat)//': rigid, rho = '//rtoa(m%rho)// &
                                ', elements '//itoa(s%nel))
            end if
         end associate
      end do
      call solver_stable_dt(r%st, r%sets, dts, e)
      if (e > 0) call r%files%say('stable step of the initial mesh '//rtoa(dts)// &
                                  ' (element '//itoa(e)//')')
      call r%files%say('total mass '//rtoa(sum(r%st%mass)))
      call r%contact%describe(r%files)
   end subroutine write_summary

   !> Final row, energy balance and wall time; closes the files. Keeps `err` as it is.
   subroutine finish(r, model, err)
      type(run_t), intent(inout) :: r
      type(model_t), intent(in) :: model
      type(error_t), allocatable, intent(in) :: err
      real(wp) :: wall
      type(error_t), allocatable :: ferr
      if (r%started .and. .not. allocated(err)) then
         if (r%last_row_step /= r%st%step) call write_rows(r, model)
         ! the final state is always written
         if (r%fields%is_open() .and. r%st%t > r%field_last) then
            r%field_next = r%st%t
            call field_output(r, ferr)
         end if
      end if
      if (r%fields%is_open()) then
         if (.not. allocated(ferr)) call r%fields%close(ferr)
         if (allocated(ferr)) call r%files%say('error: '//ferr%message)
      end if
      wall = wall_time() - r%wall_start
      call r%files%say('')
      if (r%started) then
         associate (st => r%st)
            call r%files%say('final time '//rtoa(st%t)//' after '//itoa(int(st%step))//' steps')
            call r%files%say('energy: kinetic '//rtoa(st%kinetic)//', strain '// &
               rtoa(st%strain + st%hourglass)//', external work '//rtoa(st%wext)// &
               ', contact work '//rtoa(st%wcon)//', initial total '//rtoa(st%total0))
         end associate
      end if
      if (allocated(err)) call r%files%say('error: '//err%message)
      call r%files%say('wall time '//rtoa(wall)//' s')
      if (r%st%step > 0) then
         call r%files%say('time in steps '//rtoa(r%time_steps)//' s: elements and stable step '// &
            rtoa(r%time_forces)//' s, contact search '//rtoa(r%contact%time_search)// &
            ' s, contact corrector '//rtoa(r%contact%time_corrector)//' s')
         call r%files%say('steps per second '//rtoa(real(r%st%step, wp)/max(r%time_steps, 1.0e-9_wp))// &
            ', element-steps per second '//rtoa(real(r%st%step, wp)*r%st%nelem/max(r%time_steps, 1.0e-9_wp)))
      end if
      if (r%contact%active) then
         call r%files%say('contact: largest penetration over the run '//rtoa(r%contact%max_penetration)// &
            ', redundant constraints removed '//itoa(r%contact%nredundant)// &
            ', steps whose corrector reached its pass limit '//itoa(r%contact%corr%pass_limit_hits))
         call r%files%say('contact corrector: factorizations '//itoa(r%contact%corr%nsolves)// &
            ' (dense '//itoa(r%contact%corr%ndense)//', sparse '//itoa(r%contact%corr%nsparse)// &
            '), sparse symbolic analyses '//itoa(r%contact%corr%sparse%nanalyze))
      end if
      if (r%field_dt > 0.0_wp) then
         call r%files%say('files written: '//r%files%his_path//' '//r%files%ene_path//' '// &
                          r%files%out_path//' '//r%base//'.h5 '//r%base//'.xdmf')
      else
         call r%files%say('files written: '//r%files%his_path//' '//r%files%ene_path//' '//r%files%out_path)
      end if
      call r%files%close()
   end subroutine finish

end module exic_driver
