!> The run's report in <stem>.out: the deck echo before the first step, the model summary, and
!> the final state, energy balance, wall time and contact statistics at the end.
module exic_output_text_report
   use exic_material_law, only: law_name
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa, rtoa_result
   use exic_base_error, only: error_t
   use exic_material_material, only: MAT_SOLID
   use exic_model_model, only: model_t
   use exic_output_text_history, only: history_files_t
   use exic_explicit_step, only: stepper_t
   use exic_explicit_rigid, only: RB_FREE, RB_DRIVEN
   use exic_explicit_loads, only: FN_UNDEFINED
   use exic_explicit_state, only: state_t
   use exic_explicit_assembly, only: energy_balance
   use exic_explicit_decomposition_nodes, only: decomposition_timing
   use exic_explicit_energy, only: energy_t
   use exic_contact_inside, only: inside_t
   use exic_contact_friction, only: FRICTION_SWEEPS
   !$ use omp_lib, only: omp_get_max_threads
   implicit none
   private

   public :: report_preamble, report_summary, report_final, console_summary

contains

   !> Title, deck echo and reader warnings at the top of <stem>.out.
   subroutine report_preamble(files, model)
      type(history_files_t), intent(inout) :: files
      type(model_t), intent(in) :: model
      call files%say('exic: explicit finite elements for 2-D dynamic contact')
      if (allocated(model%title)) call files%say('title: '//model%title)
      if (allocated(model%deck_file)) call files%say('deck:  '//model%deck_file)
      call files%say('')
      call files%say('---- deck ----')
      if (allocated(model%echo)) call files%say(model%echo)
      call files%say('---- end of deck ----')
      if (allocated(model%warnings)) then
         if (len(model%warnings) > 0) call files%say(model%warnings)
      end if
   end subroutine report_preamble

   !> Mesh, materials, the stable step of the initial mesh and the contact surfaces.
   subroutine report_summary(files, model, stp)
      type(history_files_t), intent(inout) :: files
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      integer :: k, e, nth
      real(wp) :: dts, total
      call files%say('')
      call files%say('nodes (highest number) '//itoa(stp%st%nnode)//', active '// &
                     itoa(count(stp%st%active))//', elements '//itoa(stp%st%nelem))
      nth = 1
      !$ nth = omp_get_max_threads()
      call files%say('threads '//itoa(nth)//' (OMP_NUM_THREADS; the results do not depend on it)')
      do k = 1, size(stp%sets)
         associate (s => stp%sets(k), m => model%materials(stp%sets(k)%mat))
            if (s%kind == MAT_SOLID) then
               call files%say('material '//itoa(s%mat)//': solid '//law_name(s%law)//', E = '// &
                              rtoa(m%young)//', nu = '//rtoa(m%poisson)//', lambda = '// &
                              rtoa(m%lambda)//', mu = '//rtoa(m%mu)//', rho = '//rtoa(m%rho)// &
                              ', quadrature '//itoa(s%nq)//', elements '//itoa(s%nel)// &
                              ' (in '//itoa(s%nrange)//' ranges of '//itoa(s%ncolour)//' colours)')
            else
               call files%say('material '//itoa(s%mat)//': rigid, rho = '//rtoa(m%rho)// &
                              ', elements '//itoa(s%nel))
            end if
         end associate
      end do
      call stp%initial_stable_step(dts, e)
      if (e > 0) call files%say('stable step of the initial mesh '//rtoa(dts)//' (element '//itoa(e)//')')
      total = sum(stp%st%mass)
      do k = 1, size(stp%ld%bodies)
         if (stp%ld%bodies(k)%kind == RB_FREE) total = total + stp%ld%bodies(k)%mass
      end do
      call files%say('total mass '//rtoa_result(total))
      call loads_summary(files, stp)
      call files%say(stp%contact%summary())
   end subroutine report_summary

   !> Free and driven rigid bodies, proportional functions, gravity and edge loads.
   subroutine loads_summary(files, stp)
      type(history_files_t), intent(inout) :: files
      type(stepper_t), intent(in) :: stp
      integer :: k
      associate (ld => stp%ld)
         do k = 1, size(ld%bodies)
            associate (b => ld%bodies(k))
               if (b%kind == RB_FREE) then
                  call files%say('free rigid body of region '//itoa(b%region)//': mass '//rtoa(b%mass)// &
                                 ', centroid ('//rtoa(b%xc0(1))//', '//rtoa(b%xc0(2))//'), inertia '// &
                                 rtoa(b%inertia)//', nodes '//itoa(b%nnode))
               else if (b%kind == RB_DRIVEN) then
                  call files%say('driven rigid body of region '//itoa(b%region)//' (MOTIon): centroid ('// &
                                 rtoa(b%xc0(1))//', '//rtoa(b%xc0(2))//'), nodes '//itoa(b%nnode))
               end if
            end associate
         end do
         if (count(ld%spec%fn%kind /= FN_UNDEFINED) > 0) &
            call files%say('proportional functions: '//itoa(count(ld%spec%fn%kind /= FN_UNDEFINED)))
         if (ld%spec%has_gravity) call files%say('gravity ('//rtoa(ld%spec%gravity(1))//', '// &
                                                 rtoa(ld%spec%gravity(2))//'), function '// &
                                                 itoa(ld%spec%gravity_prop))
         if (ld%spec%nedge > 0) call files%say('edge loads (CSURface): '//itoa(ld%spec%nedge)//' edges')
      end associate
   end subroutine loads_summary

   !> Final time, energy balance, the error if the run failed, wall time per phase, contact
   !> statistics and the files written.
   subroutine report_final(files, stp, err, wall, field_files, inside)
      type(history_files_t), intent(inout) :: files
      type(stepper_t), intent(in) :: stp
      type(error_t), allocatable, intent(in) :: err
      real(wp), intent(in) :: wall                !< wall time of the whole run
      character(len=*), intent(in) :: field_files !< the .h5 and .xdmf written, or ''
      type(inside_t), intent(in) :: inside        !< the geometric penetration check
      real(wp) :: ts
      character(len=:), allocatable :: growth
      call files%say('')
      associate (st => stp%st, c => stp%contact)
         if (stp%started) then
            call files%say('final time '//rtoa(st%t)//' after '//itoa(int(st%step))//' steps')
            call files%say('energy: '//energy_text(st%energy)//', initial total '//rtoa_result(st%energy%total0))
            if (stp%growth_max >= huge(1.0_wp)/100.0_wp) then
               growth = 'all of it (energy appeared with none put in)'
            else
               growth = rtoa(100.0_wp*max(stp%growth_max, 0.0_wp))//' %'
            end if
            call files%say('energy guard: largest growth of the physical energy over the energy put in '// &
                           growth//' (at t = '//rtoa(stp%growth_max_t)// &
                           '); limits: warning '//rtoa(100.0_wp*stp%energy_warn)//' %, stop '// &
                           rtoa(100.0_wp*stp%energy_stop)//' %')
         end if
         if (allocated(err)) call files%say('error: '//err%message)
         call files%say('wall time '//rtoa(wall)//' s')
         if (st%step > 0) then
            ts = max(stp%time_steps, 1.0e-9_wp)
            call files%say('time in steps '//rtoa(stp%time_steps)//' s: elements and stable step '// &
                           rtoa(stp%time_forces)//' s, contact search '//rtoa(c%time_search)// &
                           ' s, contact corrector '//rtoa(c%time_corrector)//' s')
            call files%say('steps per second '//rtoa(real(st%step, wp)/ts)// &
                           ', element-steps per second '//rtoa(real(st%step, wp)*st%nelem/ts))
            if (len(decomposition_timing(stp%dd)) > 0) call files%say(decomposition_timing(stp%dd))
         end if
         if (c%active) then
            call files%say('contact: largest penetration over the run '//largest_penetration(stp, inside)// &
                           ', redundant constraints removed '//itoa(c%nredundant)// &
                           ', steps whose corrector reached its pass limit '//itoa(c%corr%pass_limit_hits)// &
                           ' (each kept its last compressive multipliers)')
            call files%say('contact corrector: factorizations '//itoa(c%corr%nsolves)// &
                           ' (dense '//itoa(c%corr%ndense)//', sparse '//itoa(c%corr%nsparse)// &
                           '), sparse symbolic analyses '//itoa(c%corr%sparse%nanalyze))
            ! the contact step on the threads (doc/decisions.md, "Threads")
            if (c%nthreaded + c%corr%nthreaded > 0) &
               call files%say('contact on the threads: narrow phase in '//itoa(c%nthreaded)// &
                              ' searches, blocks of S in '//itoa(c%corr%nthreaded)//' factorizations')
            ! the frictional corrector (doc/friction.md, section 4)
            if (c%friction) call files%say('friction: steps solved with friction '//itoa(c%fr%ncalls)// &
                                           ', sweeps '//itoa(c%fr%nsweeps)//' (most in a step '// &
                                           itoa(c%fr%max_sweeps)//' of '//itoa(FRICTION_SWEEPS)// &
                                           '), steps at the sweep limit '//itoa(c%fr%sweep_limit_hits)// &
                                           ', tangential problems at their pass limit '// &
                                           itoa(c%fr%pass_limit_hits)//' (most passes '// &
                                           itoa(c%fr%max_tpasses)//' of '//itoa(c%fr%max_passes)// &
                                           '), mirrored pairs '//itoa(c%fr%nmirrors)//' (swapped '// &
                                           itoa(c%fr%nswaps)//')'// &
                                           ', tangential factorizations '// &
                                           itoa(c%fr%tt%nsolves)//' (reused '//itoa(c%fr%tt%nreused)// &
                                           '), frictional dissipation '//rtoa_result(c%dissipation))
            ! the massless contact faces (doc/impact.md, section 3.2)
            if (c%face%active) call files%say('massless contact faces: back-substitutions '// &
                                              itoa(c%face%nsolves)//', stiffness rows formed again '// &
                                              'at large strain '//itoa(c%face%nrefresh)//' times')
            if (inside%active) call files%say(inside%report())
         end if
      end associate
      call files%say('files written: '//files%his_path//' '//files%ene_path//' '//files%out_path// &
                     field_files)
   end subroutine report_final

   !> The lines printed on the console at the end of a run: steps, wall time and rates (the
   !> figures of <stem>.out), the largest penetration, and the energy balance of the last
   !> <stem>.ene row.
   function console_summary(stp, wall, inside) result(text)
      type(stepper_t), intent(in) :: stp
      real(wp), intent(in) :: wall                !< wall time of the whole run
      type(inside_t), intent(in) :: inside        !< the geometric penetration check
      character(len=:), allocatable :: text
      character(len=*), parameter :: NL = achar(10)
      real(wp) :: ts, total, drift
      associate (st => stp%st, c => stp%contact)
         text = 'exic: '//itoa(int(st%step))//' steps to t = '//rtoa(st%t)//', wall time '//rtoa(wall)//' s'
         if (st%step > 0) then
            ts = max(stp%time_steps, 1.0e-9_wp)
            text = text//NL//'exic: steps per second '//rtoa(real(st%step, wp)/ts)// &
                   ', element-steps per second '//rtoa(real(st%step, wp)*st%nelem/ts)
         end if
         if (c%active) text = text//NL//'exic: largest penetration over the run '//largest_penetration(stp, inside)
         if (allocated(st%status)) text = text//NL//'exic: elements eroded '//itoa(st%neroded)//' of '// &
                                          itoa(st%nelem)//', eroded energy '//rtoa_result(st%energy%eroded)
         call energy_balance(st, total, drift)
         text = text//NL//'exic: energy: initial total '//rtoa_result(st%energy%total0)//', '// &
                energy_text(st%energy)//NL//'exic: energy balance: total '//rtoa_result(total)//', drift '// &
                rtoa_result(drift)
      end associate
   end function console_summary

   !> The energies of the final report: kinetic, strain (with the hourglass energy), external
   !> work, contact work (and the damping and bulk viscosity dissipations when not zero).
   function energy_text(en) result(text)
      type(energy_t), intent(in) :: en
      character(len=:), allocatable :: text
      text = 'kinetic '//rtoa_result(en%kinetic)//', strain '//rtoa_result(en%strain + en%hourglass)// &
             ', external work '//rtoa_result(en%wext)//', contact work '//rtoa_result(en%wcon)
      if (en%damping /= 0.0_wp) text = text//', damping dissipation '//rtoa_result(en%damping)
      if (en%bulk /= 0.0_wp) text = text//', bulk viscosity dissipation '//rtoa_result(en%bulk)
   end function energy_text

   !> The largest penetration over the run: the geometric one (the deepest node found inside
   !> another body at the checked times, with its node, regions, depth in element edges and
   !> time), then the largest gap violation of the detected contact pairs.
   function largest_penetration(stp, inside) result(text)
      type(stepper_t), intent(in) :: stp
      type(inside_t), intent(in) :: inside
      character(len=:), allocatable :: text
      associate (w => inside%worst)
         if (inside%active .and. w%node > 0) then
            text = rtoa_result(w%depth)//' (geometric: node '//itoa(w%node)//' of region '//itoa(w%of_body)// &
                   ' inside region '//itoa(w%in_body)//' by '//rtoa_result(w%edges)//' element edges at t = '// &
                   rtoa(w%t)//'; detected pairs '//rtoa_result(stp%contact%max_penetration)//')'
         else if (inside%active) then
            text = rtoa(0.0_wp)//' (geometric, at '//itoa(inside%nchecks)//' checked times; detected pairs '// &
                   rtoa_result(stp%contact%max_penetration)//')'
         else
            text = rtoa_result(stp%contact%max_penetration)//' (detected pairs)'
         end if
      end associate
   end function largest_penetration

end module exic_output_text_report
