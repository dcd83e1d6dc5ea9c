!> Cost of the legacy API's step call against the native contact path on the same scenes.
!>
!> For each scene (a bar on a rigid wall, 30 x 6 and 120 x 24; two bars, 60 x 12 each) two
!> copies of the same explicit run (exic's stepper, fixed step 0.8 x stable, t = 0 .. 3 L/c)
!> advance in lockstep, each with its contact through a hook of the stepper: one calls
!> contact_t%correct on the stepper's arrays as the deck path does, the other forms x = x0 + u
!> itself, as a host that keeps displacements would, and hands its arrays to EXIC_CONTACT_STEP.
!> Only the contact calls are timed, step by step alternately, so that the load of a shared
!> machine falls on both alike; both copies follow the same trajectory bit for bit (checked). Per repetition the ratio API/native is
!> formed; the median ratio over the repetitions (nrep, times 3000/nodes for the smaller
!> scenes) and the fastest times are reported.
!> Build and run (doc/performance.md, section "Legacy API overhead"):
!>   fpm run exic-bench-legacy --profile release --flag "-O3 -march=native -funroll-loops -ffp-contract=off" [-- nrep]
program legacy_overhead
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_clock, only: wall_time
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_explicit_step, only: stepper_t
   use exic_contact_spec, only: contact_spec_t
   use bench_legacy_hooks, only: native_hook_t, api_hook_t
   use exic_material_material, only: MAT_RIGID
   use exic_legacy_interfaces, only: exic_contact_create_mesh, exic_contact_free
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
      'API + x = x0 + u us/step | API/native - 1 (median) | with x (median) |'
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
      real(wp), allocatable :: tn(:), ta(:), tx(:), r1(:), r2(:)
      real(wp) :: diff
      integer :: rep, nsteps, ns, m
      character(len=64) :: name

      write (name, '(a,"_",i0,"x",i0)') mode, nx, ny
      path = dir//'/'//trim(name)//'.inp'
      call write_deck(path, mode, nx, ny)
      call read_deck(path, model, err)
      if (allocated(err)) then
         print '(a)', 'error: '//err%message
         return
      end if
      ! smaller scenes get more repetitions (about the same time per scene)
      m = nrep*max(1, 3000/model%mesh%nnode)
      allocate (tn(m), ta(m), tx(m))
      do rep = 1, m
         call run_both(model, tn(rep), ta(rep), tx(rep), nsteps, diff)
      end do
      r1 = ta/tn
      r2 = (ta + tx)/tn
      ns = count_surface_nodes(model)
      print '("| ",a," | ",i0," | ",i0," | ",i0," | ",f8.3," | ",f8.3," | ",f8.3," | ",f6.1," % | ",f6.1," % |")', &
         trim(name), model%mesh%nnode, ns, nsteps, 1.0e6_wp*minval(tn)/nsteps, 1.0e6_wp*minval(ta)/nsteps, &
         1.0e6_wp*minval(ta + tx)/nsteps, 100.0_wp*(median(r1) - 1.0_wp), 100.0_wp*(median(r2) - 1.0_wp)
      if (diff /= 0.0_wp) print '(a,es10.3)', '  warning: trajectories differ by ', diff
   end subroutine scene

   !> Median of a short array.
   real(wp) function median(a) result(m)
      real(wp), intent(in) :: a(:)
      real(wp) :: b(size(a)), t
      integer :: i, j
      b = a
      do i = 2, size(b)
         t = b(i)
         j = i - 1
         do while (j >= 1)
            if (b(j) <= t) exit
            b(j + 1) = b(j)
            j = j - 1
         end do
         b(j + 1) = t
      end do
      m = 0.5_wp*(b((size(b) + 1)/2) + b(size(b)/2 + 1))
   end function median

   !> Two copies of one run in lockstep, native contact (n) and API (a); tn, ta: wall time in
   !> their contact calls; tx: in forming x = x0 + u for the API; diff: largest difference of
   !> the final displacements.
   subroutine run_both(model, tn, ta, tx, nsteps, diff)
      type(model_t), intent(in) :: model
      real(wp), intent(out) :: tn, ta, tx, diff
      integer, intent(out) :: nsteps
      type(stepper_t), target :: sn, sa
      type(native_hook_t), target :: hn
      type(api_hook_t), target :: ha
      type(error_t), allocatable :: err
      integer, allocatable :: ipair(:, :)
      real(wp) :: dts, tmax, pp(1)
      integer :: ierr, emin, e

      call sn%init(model%mesh, model%materials, contact_spec_t(), err)
      call sa%init(model%mesh, model%materials, contact_spec_t(), err)
      if (allocated(err)) error stop 'exic-bench-legacy: set-up failed'
      call sn%initial_stable_step(dts, emin)
      call sn%set_fixed_dt(0.8_wp*dts, 'bench', err)
      call sa%set_fixed_dt(0.8_wp*dts, 'bench', err)
      tmax = 3.0_wp*30.0_wp/sqrt(1.0e4_wp/0.1_wp)
      ! the native path: exic's contact of the deck
      call hn%contact%init(model%contact, sn%st%nnode, sn%st%x0, sn%x, model%mesh%nelem, model%mesh%conn, &
                           model%mesh%region, model%mesh%mat, 0.0_wp, err)
      if (allocated(err)) error stop 'exic-bench-legacy: contact init failed'
      sn%hook => hn
      ! the API path: the same pair through the legacy API
      allocate (ipair(6, 1))
      ipair(:, 1) = [1, 2, 1, 1, 1, 0]
      do e = 1, model%mesh%nelem
         if (model%mesh%region(e) == 2 .and. model%materials(model%mesh%mat(e))%kind == MAT_RIGID) ipair(6, 1) = 1
      end do
      pp = 0.0_wp
      call exic_contact_create_mesh(sa%st%nnode, model%mesh%x, sa%st%mass, model%mesh%nelem, model%mesh%conn, &
                                    model%mesh%region, 1, ipair, pp, ha%h, ierr)
      if (ierr /= 0) error stop 'exic-bench-legacy: create failed'
      allocate (ha%x(2, sa%st%nnode), source=0.0_wp)
      ha%stp => sa
      sa%hook => ha
      call sn%start(err)
      call sa%start(err)
      if (allocated(err)) error stop 'exic-bench-legacy: start failed'
      nsteps = 0
      do while (sn%st%t < tmax*(1.0_wp - 1.0e-12_wp))
         call sn%advance(err)
         call sa%advance(err)
         if (allocated(err)) error stop 'exic-bench-legacy: step failed'
         nsteps = nsteps + 1
      end do
      tn = hn%time
      ta = ha%time
      tx = ha%time_x
      diff = maxval(abs(sn%st%u - sa%st%u))
      call exic_contact_free(ha%h, ierr)
   end subroutine run_both

   !> Nodes on the free boundaries of regions 1 and 2 (the contact surfaces).
   integer function count_surface_nodes(model) result(n)
      type(model_t), intent(in) :: model
      type(stepper_t) :: stp
      type(error_t), allocatable :: err
      integer :: k
      call stp%init(model%mesh, model%materials, model%contact, err)
      n = sum([(size(stp%contact%surfaces(k)%nodes), k=1, size(stp%contact%surfaces))])
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
