!> Cost of the legacy API's step call against the native contact path on the same scenes.
!>
!> For each scene (a bar on a rigid wall, 30 x 6 and 120 x 24; two bars, 60 x 12 each) the
!> same explicit run (exic's element loop, fixed step 0.8 x stable, t = 0 .. 3 L/c) is made
!> twice per repetition: once calling contact_t%correct on the state as the driver does, once
!> handing the host arrays to EXIC_CONTACT_STEP. Only the contact call is timed (both runs
!> follow the same trajectory bit for bit, which is checked). Repetitions alternate the two
!> paths; the fastest repetition of each is reported, in microseconds per step.
!> Build and run (doc/performance.md, section "Legacy API overhead"):
!>   fpm run exic-bench-legacy --profile release --flag "-O3 -march=native -funroll-loops" [-- nrep]
program legacy_overhead
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_clock, only: wall_time
   use exic_model, only: model_t
   use exic_io_deck, only: read_deck
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_solver, only: solver_init, solver_forces, solver_stable_dt
   use exic_contact_contact, only: contact_t
   use exic_material_material, only: MAT_RIGID
   use exic_legacy_interfaces, only: exic_contact_create_mesh, exic_contact_step, exic_contact_free
   implicit none
   character(len=*), parameter :: dir = 'build/bench_legacy'
   integer :: nrep, nargs
   character(len=32) :: arg

   nrep = 20
   nargs = command_argument_count()
   if (nargs >= 1) then
      call get_command_argument(1, arg)
      read (arg, *) nrep
   end if
   call execute_command_line('mkdir -p '//dir)
   print '(a)', '| scene | nodes | surface nodes | steps | native contact us/step | API step us/step | '// &
      'API + x = x0 + u us/step | overhead | overhead with x |'
   print '(a)', '|---|---|---|---|---|---|---|---|---|'
   call scene('wall', 30, 6, nrep)
   call scene('wall', 120, 24, nrep)
   call scene('bars', 60, 12, nrep)

contains

   !> Time both paths on one scene and print a table row.
   subroutine scene(mode, nx, ny, nrep)
      character(len=*), intent(in) :: mode
      integer, intent(in) :: nx, ny, nrep
      type(model_t) :: model
      type(error_t), allocatable :: err
      character(len=:), allocatable :: path
      real(wp) :: tn, ta, tx, best_n, best_a, best_x, diff
      real(wp), allocatable :: un(:, :), ua(:, :)
      integer :: rep, nsteps, ns
      character(len=64) :: name

      write (name, '(a,"_",i0,"x",i0)') mode, nx, ny
      path = dir//'/'//trim(name)//'.inp'
      call write_deck(path, mode, nx, ny)
      call read_deck(path, model, err)
      if (allocated(err)) then
         print '(a)', 'error: '//err%message
         return
      end if
      best_n = huge(1.0_wp)
      best_a = huge(1.0_wp)
      best_x = huge(1.0_wp)
      do rep = 1, nrep
         call run(model, .false., tn, tx, nsteps, un)
         call run(model, .true., ta, tx, nsteps, ua)
         best_n = min(best_n, tn)
         best_a = min(best_a, ta)
         best_x = min(best_x, ta + tx)
      end do
      diff = maxval(abs(un - ua))
      ns = count_surface_nodes(model)
      print '("| ",a," | ",i0," | ",i0," | ",i0," | ",f8.3," | ",f8.3," | ",f8.3," | ",f6.1," % | ",f6.1," % |")', &
         trim(name), size(un, 2), ns, nsteps, 1.0e6_wp*best_n/nsteps, 1.0e6_wp*best_a/nsteps, &
         1.0e6_wp*best_x/nsteps, 100.0_wp*(best_a/best_n - 1.0_wp), 100.0_wp*(best_x/best_n - 1.0_wp)
      if (diff /= 0.0_wp) print '(a,es10.3)', '  warning: trajectories differ by ', diff
   end subroutine scene

   !> One explicit run; tc: wall time in the contact calls; tx: in forming x = x0 + u (API).
   subroutine run(model, api, tc, tx, nsteps, ufinal)
      type(model_t), intent(in) :: model
      logical, intent(in) :: api
      real(wp), intent(out) :: tc, tx
      integer, intent(out) :: nsteps
      real(wp), allocatable, intent(out) :: ufinal(:, :)
      type(state_t) :: st
      type(element_set_t), allocatable :: sets(:)
      type(contact_t) :: contact
      type(error_t), allocatable :: err
      real(wp), allocatable :: aold(:, :), vt(:, :), x(:, :), fcon(:, :)
      integer, allocatable :: ipair(:, :)
      real(wp) :: dts, tmax, t0, pp(1)
      integer :: h, ierr, ebad, emin, nact, e

      call solver_init(model, st, sets, err)
      allocate (aold(2, st%nnode), vt(2, st%nnode), x(2, st%nnode), fcon(2, st%nnode), source=0.0_wp)
      call solver_stable_dt(st, sets, dts, emin)
      st%dt = 0.8_wp*dts
      tmax = 3.0_wp*30.0_wp/sqrt(1.0e4_wp/0.1_wp)
      h = 0
      if (api) then
         allocate (ipair(6, 1))
         ipair(:, 1) = [1, 2, 1, 1, 1, 0]
         do e = 1, model%mesh%nelem
            if (model%mesh%region(e) == 2 .and. model%materials(model%mesh%mat(e))%kind == MAT_RIGID) &
               ipair(6, 1) = 1
         end do
         pp = 0.0_wp
         call exic_contact_create_mesh(st%nnode, model%mesh%x, st%mass, model%mesh%nelem, model%mesh%conn, &
                                       model%mesh%region, 1, ipair, pp, h, ierr)
         if (ierr /= 0) error stop 'exic-bench-legacy: create failed'
      else
         call contact%init(model, st, err)
         if (allocated(err)) error stop 'exic-bench-legacy: contact init failed'
      end if
      call solver_forces(st, sets, ebad)
      st%a = st%minv*(st%fext - st%fint)
      tc = 0.0_wp
      tx = 0.0_wp
      nsteps = 0
      call contact_call(st%v)
      do while (st%t < tmax*(1.0_wp - 1.0e-12_wp))
         st%u = st%u + (st%dt*st%v + (0.5_wp*st%dt*st%dt)*st%a)
         st%t = st%t + st%dt
         st%dt_prev = st%dt
         aold = st%a
         call solver_forces(st, sets, ebad)
         st%a = st%minv*(st%fext - st%fint)
         vt = st%v + (0.5_wp*st%dt_prev)*(aold + st%a)
         call contact_call(vt)
         st%v = st%v + (0.5_wp*st%dt_prev)*(aold + st%a)
         nsteps = nsteps + 1
      end do
      ufinal = st%u
      if (api) call exic_contact_free(h, ierr)
   contains
      subroutine contact_call(v)
         real(wp), intent(in) :: v(:, :)
         real(wp) :: t1
         if (api) then
            t0 = wall_time()
            x = st%x0 + st%u
            t1 = wall_time()
            call exic_contact_step(h, st%nnode, x, v, st%a, st%dt_prev, st%dt, fcon, nact, ierr)
            tc = tc + (wall_time() - t1)
            tx = tx + (t1 - t0)
            if (ierr /= 0) error stop 'exic-bench-legacy: step failed'
         else
            t0 = wall_time()
            call contact%correct(st, v, err)
            tc = tc + (wall_time() - t0)
            if (allocated(err)) error stop 'exic-bench-legacy: correct failed'
         end if
      end subroutine contact_call
   end subroutine run

   !> Nodes on the free boundaries of regions 1 and 2 (the contact surfaces).
   integer function count_surface_nodes(model) result(n)
      type(model_t), intent(in) :: model
      type(state_t) :: st
      type(element_set_t), allocatable :: sets(:)
      type(contact_t) :: contact
      type(error_t), allocatable :: err
      integer :: k
      call solver_init(model, st, sets, err)
      call contact%init(model, st, err)
      n = sum([(size(contact%surfaces(k)%nodes), k=1, size(contact%surfaces))])
   end function count_surface_nodes

   !> A bar (region 1, nx x ny over 30 x 4) at +0.1 against a rigid wall ('wall') or a second
   !> bar at -0.1 ('bars'), contact pair 1 = surface of region 1 against that of region 2.
   subroutine write_deck(path, mode, nx, ny)
      character(len=*), intent(in) :: path, mode
      integer, intent(in) :: nx, ny
      integer :: u
      open (newunit=u, file=path, status='replace', action='write')
      write (u, '(a)') 'FEAP * * legacy API overhead', '0 0 0 2 2 4', 'PARAmeters', '  len = 30', '  hgt = 4'
      write (u, '(a,i0)') '  nx = ', nx
      write (u, '(a,i0)') '  ny = ', ny
      write (u, '(a)') '', 'MATErial,1', '  SOLId', '    ELAStic NEOHookean 1e4 0', '    DENSity 0.1', ''
      if (mode == 'wall') then
         write (u, '(a)') 'MATErial,2', '  RIGId', '    DENSity 0.1', ''
      else
         write (u, '(a)') 'MATErial,2', '  SOLId', '    ELAStic NEOHookean 1e4 0', '    DENSity 0.1', ''
      end if
      write (u, '(a)') 'REGIon,1', 'BLOCk', '  CARTesian,nx,ny,0,0,1', '    1,0,0', '    2,len,0', &
         '    3,len,hgt', '    4,0,hgt', ''
      if (mode == 'wall') then
         write (u, '(a)') 'REGIon,2', 'BLOCk', '  CARTesian,2,4,0,0,2', '    1,len,-hgt', '    2,len+hgt,-hgt', &
            '    3,len+hgt,2*hgt', '    4,len,2*hgt', ''
      else
         write (u, '(a)') 'REGIon,2', 'BLOCk', '  CARTesian,nx,ny,0,0,2', '    1,len,0', '    2,2*len,0', &
            '    3,2*len,hgt', '    4,len,hgt', ''
      end if
      write (u, '(a)') 'INITial,VELOcity', '  REGIon,1,0.1,0'
      if (mode == 'bars') write (u, '(a)') '  REGIon,2,-0.1,0'
      write (u, '(a)') '', 'CONTact', '  SURFace,1', '    REGIon,1', '  SURFace,2', '    REGIon,2', &
         '  PAIR,1,NTOS,1,2', 'END CONTact', '', 'END', 'BATCh', '  TRANsient,EXPLicit', 'END', '', 'STOP'
      close (u)
   end subroutine write_deck

end program legacy_overhead
