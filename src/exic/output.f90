!> What a run writes as it goes: TPLOt history rows, energy rows and HDF5/XDMF fields.
!>
!> The driver asks for a row at every TIME command (`record`: when the TPLOt interval is due)
!> and for fields when an output time is due (`fields_due`); the final state is always written
!> (`final`). Values come from the stepper's state; nothing here changes it.
module exic_output
   use, intrinsic :: iso_fortran_env, only: error_unit
   use exic_base_flat, only: all_finite
   use exic_base_kinds, only: wp, i8
   use exic_base_constants, only: TIME_TOL
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa, rtoa
   use exic_model_model, only: model_t
   use exic_model_program, only: REQ_DISP, REQ_VELO, REQ_ACCE, REQ_STRE, REQ_REAC, REQ_CONT, REQ_MOME, &
                              REQ_REAC_REGION, REQ_REAC_SET, REQ_RIGI
   use exic_mesh_edge_set, only: find_edge_set, edge_set_nodes
   use exic_output_text_history, only: history_files_t
   use exic_output_fields, only: field_writer_t, STRESS_NAMES
   use exic_output_fields_nodes, only: written_nodes, renumbered
   use exic_base_posix, only: file_kind, FILE_MISSING
   use exic_explicit_step, only: stepper_t, first_nonfinite
   use exic_explicit_assembly, only: element_stress, all_stresses, NSIG, energy_balance
   use exic_explicit_loading, only: reaction
   use exic_explicit_energy, only: energy_t, model_energies, ENERGY_NAMES, NENERGY, E_WPM, E_FRICTION, E_PLASTIC
   use exic_explicit_rigid, only: RB_PLAIN, RB_FREE
   use exic_explicit_history_gather, only: decomposition_gather_history, history_stale
   implicit none
   private

   public :: output_t

   !> The nodes a reaction-sum request adds up.
   type :: node_list_t
      integer, allocatable :: nodes(:)
   end type node_list_t

   !> The element values of the field output of a deck with a plastic set (others: the first 7,
   !> fields.f90's default).
   character(len=20), parameter :: PLASTIC_CELL_NAMES(10) = [character(len=20) :: STRESS_NAMES, &
      'plastic_strain', 'temperature', 'yield_stress']

   !> The run's output files and their schedules.
   type :: output_t
      type(history_files_t) :: files                !< <stem>.his, .ene, .out
      type(field_writer_t) :: fields                !< <stem>.h5, .xdmf
      character(len=:), allocatable :: base         !< output path without extension
      integer :: his_inc = 0                        !< TPLOt interval (0: no histories)
      integer(i8) :: last_row_step = -1
      real(wp), allocatable :: values(:)            !< one history row
      integer, allocatable :: region_of_node(:)     !< region of the elements that use each node
      type(node_list_t), allocatable :: sums(:)     !< nodes of each reaction-sum request
      real(wp) :: field_dt = 0.0_wp                 !< OUTPut,HDF5 interval (0: no field output)
      !> the node numbers the field output writes when some numbers are unused (gaps), in
      !> increasing order; unallocated: every number 1..nnode (exic_output_fields_nodes)
      integer, allocatable :: field_nodes(:)
      real(wp) :: field_next = 0.0_wp               !< time of the next field output
      real(wp) :: field_last = -huge(1.0_wp)        !< time of the last field output
      real(wp) :: field_t0 = 0.0_wp                 !< time of OUTPut,HDF5 (the schedule's origin)
      real(wp) :: field_checked = -huge(1.0_wp)     !< time of the last look at the schedule
      logical :: warned_interval = .false.          !< the interval-below-the-step warning was given
      ! what the files held at the last restart point (`checkpoint`)
      integer(i8) :: saved_his_bytes = 0, saved_ene_bytes = 0
      integer :: saved_field_times = 0
   contains
      procedure :: open => output_open
      procedure :: checkpoint => output_checkpoint
      procedure :: resume => output_resume
      procedure :: begin => output_begin
      procedure :: record => output_record
      procedure :: reads_state => output_reads_state
      procedure :: open_fields => output_open_fields
      procedure :: fields_due => output_fields_due
      procedure :: final => output_final
      procedure :: failed => output_failed
      procedure :: close => output_close
   end type output_t

contains

   !> Create <base>.his, .ene and .out; `with`: the energies of <stem>.ene (model_energies).
   subroutine output_open(self, base, err, with)
      class(output_t), intent(inout) :: self
      character(len=*), intent(in) :: base
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: with(NENERGY)
      self%base = base
      call self%files%open(base, err, with)
   end subroutine output_open

   !> Flush the files (the field output times still in memory too) and note their lengths and
   !> the number of field output times, for a restart file written now.
   subroutine output_checkpoint(self, err)
      class(output_t), intent(inout) :: self
      type(error_t), allocatable, intent(out) :: err
      call self%files%sizes(self%saved_his_bytes, self%saved_ene_bytes)
      if (self%fields%is_open()) call self%fields%flush(err)
      self%saved_field_times = self%fields%count()
   end subroutine output_checkpoint

   !> Continue the outputs of the run that wrote a restart file, whose output state (schedules,
   !> lengths, number of output times) has been read into self: the text files cut to their
   !> lengths then, the field files to their output times then, and appended to. In a folder
   !> that holds none of them (<base>.his, .ene and, with field output, .h5 all missing: the
   !> restart file was taken elsewhere), new files are made that start at the restart point
   !> (`fresh` true); some missing and some present is refused, naming them
   !> (doc/input-language.md, "Restart files").
   subroutine output_resume(self, base, model, stp, fresh, err)
      class(output_t), intent(inout) :: self
      character(len=*), intent(in) :: base
      type(model_t), intent(in) :: model
      type(stepper_t), intent(in) :: stp
      logical, intent(out) :: fresh
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: present_files, missing
      real(wp), allocatable :: x(:, :)
      integer, allocatable :: conn(:, :), edges(:, :)
      self%base = base
      self%files%with = model_energies(model%materials)
      present_files = ''
      missing = ''
      call sort_file(base//'.his', present_files, missing)
      call sort_file(base//'.ene', present_files, missing)
      if (self%field_dt > 0.0_wp) call sort_file(base//'.h5', present_files, missing)
      fresh = len(present_files) == 0
      if (.not. fresh .and. len(missing) > 0) then
         call make_error(err, 'cannot continue the outputs of the restart file: '//missing(3:)// &
                         ' missing while '//present_files(3:)//' present (all present: they are continued; '// &
                         'none: new files start at the restart point)')
         return
      end if
      if (fresh) then
         call self%files%open(base, err)
         if (allocated(err)) return
         if (self%field_dt > 0.0_wp) call create_fields(self, model, stp, err)
         if (allocated(err)) return
         call self%begin(model)
         return
      end if
      ! the .h5 first: when it cannot be continued, the text files stay as they are
      if (self%field_dt > 0.0_wp) then
         call field_mesh(self, model, stp, x, conn, edges)
         if (allocated(stp%st%status)) then
            call self%fields%reopen(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                                    model%mesh%nelem, x, conn, self%saved_field_times, &
                                    pack(ENERGY_NAMES, energy_mask(stp, self%files)), err, cell_names=status_names(stp), &
                                    friction=stp%contact%friction, &
                                    capacity=expected_field_times(model, stp%st%t, self%field_dt), &
                                    node_id=self%field_nodes)
         else if (stp%st%has_plastic) then
            call self%fields%reopen(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                                    model%mesh%nelem, x, conn, self%saved_field_times, &
                                    pack(ENERGY_NAMES, energy_mask(stp, self%files)), err, cell_names=PLASTIC_CELL_NAMES, &
                                    friction=stp%contact%friction, &
                                    capacity=expected_field_times(model, stp%st%t, self%field_dt), &
                                    node_id=self%field_nodes)
         else
            call self%fields%reopen(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                                    model%mesh%nelem, x, conn, self%saved_field_times, &
                                    pack(ENERGY_NAMES, energy_mask(stp, self%files)), err, friction=stp%contact%friction, &
                                    capacity=expected_field_times(model, stp%st%t, self%field_dt), &
                                    node_id=self%field_nodes)
         end if
         if (allocated(err)) return
      end if
      call self%files%resume(base, self%saved_his_bytes, self%saved_ene_bytes, err)
      if (allocated(err)) return
      call self%begin(model, header=.false.)
   end subroutine output_resume

   !> Add ', '//path to `there` or to `absent`, as the file exists or not.
   subroutine sort_file(path, there, absent)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(inout) :: there, absent
      if (file_kind(path) == FILE_MISSING) then
         absent = absent//', '//path
      else
         there = there//', '//path
      end if
   end subroutine sort_file

   !> At the start of the time loop: the history header (`header` false: a restarted run, whose
   !> file has it) and the region of every node.
   subroutine output_begin(self, model, header)
      class(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      logical, intent(in), optional :: header
      character(len=32), allocatable :: labels(:)
      character(len=4), parameter :: names(10) = ['disp', 'velo', 'acce', 'stre', 'reac', 'cont', 'mome', &
                                                   'reac', 'reac', 'rigi']
      character(len=1), parameter :: tags(10) = ['n', 'n', 'n', 'e', 'n', 'p', 'r', 'r', 'c', 'r']
      integer :: k, nreq, e

      nreq = 0
      if (allocated(model%requests)) nreq = size(model%requests)
      allocate (labels(nreq), self%values(nreq))
      do k = 1, nreq
         associate (q => model%requests(k))
            write (labels(k), '(a,a,a,i0,a,i0,a)') names(q%kind), '(', tags(q%kind), q%id, ',', q%comp, ')'
         end associate
      end do
      call self%files%his_header(labels, header)
      ! the region of the last element that uses each node (-huge for unused nodes)
      allocate (self%region_of_node(model%mesh%nnode), source=-huge(1))
      do e = 1, model%mesh%nelem
         self%region_of_node(model%mesh%conn(:, e)) = model%mesh%region(e)
      end do
      call sum_nodes(self, model)
   end subroutine output_begin

   !> The nodes of every reaction-sum request: of a region's elements, or of an edge set.
   subroutine sum_nodes(self, model)
      type(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      logical :: on(model%mesh%nnode)
      integer :: k, e
      allocate (self%sums(size(self%values)))
      do k = 1, size(self%values)
         associate (q => model%requests(k))
            if (q%kind == REQ_REAC_REGION) then
               on = .false.
               do e = 1, model%mesh%nelem
                  if (model%mesh%region(e) == q%id) on(model%mesh%conn(:, e)) = .true.
               end do
               self%sums(k)%nodes = pack([(e, e=1, model%mesh%nnode)], on)
            else if (q%kind == REQ_REAC_SET) then
               self%sums(k)%nodes = edge_set_nodes(model%mesh%edge_sets(find_edge_set(model%mesh%edge_sets, q%id)))
            end if
         end associate
      end do
   end subroutine sum_nodes

   !> The history and energy rows of the current state when the TPLOt interval is due (always
   !> at step 0, never twice for one step).
   subroutine output_record(self, model, stp)
      class(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      logical :: due
      due = self%his_inc > 0
      if (due) due = mod(stp%st%step, int(self%his_inc, i8)) == 0
      if (stp%st%step == 0) due = .true.
      if (.not. due .or. self%last_row_step == stp%st%step) return
      call write_rows(self, model, stp)
   end subroutine output_record

   !> The rows (output_record) or the fields (output_fields_due) of the state now are due: they
   !> read the nodal state (with the nodal state divided among MPI ranks, doc/parallel.md, it is
   !> gathered first). The same answer on every rank (steps and times only).
   logical function output_reads_state(self, stp) result(due)
      class(output_t), intent(in) :: self
      type(stepper_t), intent(in) :: stp
      due = self%his_inc > 0
      if (due) due = mod(stp%st%step, int(self%his_inc, i8)) == 0
      if (stp%st%step == 0) due = .true.
      if (self%last_row_step == stp%st%step) due = .false.
      if (self%fields%is_open()) then
         if (stp%st%t >= self%field_next*(1.0_wp - TIME_TOL)) due = .true.
      end if
   end function output_reads_state

   !> History and energy rows of the current state.
   subroutine write_rows(self, model, stp)
      type(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      integer :: k
      real(wp) :: sig(NSIG), total, drift, kc
      type(energy_t) :: en
      integer :: ids(size(self%values))

      ! several MPI ranks: the history of the elements whose stresses the row holds (doc/parallel.md)
      ids = 0
      do k = 1, size(ids)
         if (model%requests(k)%kind == REQ_STRE) ids(k) = model%requests(k)%id
      end do
      call decomposition_gather_history(stp%dd, stp%st, stp%sets, ids)
      do k = 1, size(self%values)
         associate (q => model%requests(k), st => stp%st)
            select case (q%kind)
            case (REQ_DISP)
               self%values(k) = st%u(q%comp, q%id)
            case (REQ_VELO)
               self%values(k) = st%v(q%comp, q%id)
            case (REQ_ACCE)
               self%values(k) = st%a(q%comp, q%id)
            case (REQ_STRE)
               call element_stress(st, stp%sets, q%id, sig)
               self%values(k) = sig(q%comp)
            case (REQ_REAC)
               ! force the support exerts on the body: R = M a + P - F - fcon (doc/loads.md, 3)
               self%values(k) = reaction(st, q%id, q%comp)
            case (REQ_CONT)
               self%values(k) = stp%contact%pair_value(q%id, q%comp)
            case (REQ_MOME)
               self%values(k) = region_momentum(self, stp, q%id, q%comp)
            case (REQ_REAC_REGION, REQ_REAC_SET)
               self%values(k) = reaction_sum(stp, self%sums(k)%nodes, q%comp)
            case (REQ_RIGI)
               self%values(k) = body_value(stp, q%id, q%comp)
            end select
         end associate
      end do
      associate (st => stp%st)
         call self%files%his_row(st%t, self%values)
         call energy_balance(st, total, drift, kc)
         ! the frictional dissipation as the contact has it now (also right after a restart)
         en = st%energy
         en%friction = stp%contact%dissipation
         call self%files%ene_row(st%t, st%step, st%dt, en, total, drift, st%momentum, st%nactive, kc)
      end associate
      self%last_row_step = stp%st%step
   end subroutine write_rows

   !> Linear momentum component `comp` (1, 2) or angular momentum about the origin (3) of the
   !> nodes of region `region` and of its free rigid body (TPLOt `mome` [ext]).
   real(wp) function region_momentum(self, stp, region, comp) result(p)
      type(output_t), intent(in) :: self
      type(stepper_t), intent(in) :: stp
      integer, intent(in) :: region, comp
      integer :: i, ib
      real(wp) :: x(2)
      p = 0.0_wp
      associate (st => stp%st)
         do i = 1, st%nnode
            if (self%region_of_node(i) /= region) cycle
            if (allocated(st%mass_dof)) then
               ! masses per dof (massless contact faces along their normals)
               if (comp <= 2) then
                  p = p + st%mass_dof(comp, i)*st%v(comp, i)
               else
                  x = st%x0(:, i) + st%u(:, i)
                  p = p + x(1)*st%mass_dof(2, i)*st%v(2, i) - x(2)*st%mass_dof(1, i)*st%v(1, i)
               end if
            else if (comp <= 2) then
               p = p + st%mass(i)*st%v(comp, i)
            else
               x = st%x0(:, i) + st%u(:, i)
               p = p + st%mass(i)*(x(1)*st%v(2, i) - x(2)*st%v(1, i))
            end if
         end do
      end associate
      ib = stp%ld%body_index(region)
      if (ib == 0) return
      associate (b => stp%ld%bodies(ib))
         if (b%kind /= RB_FREE) return
         if (comp <= 2) then
            p = p + b%mass*b%v(comp)
         else
            p = p + b%mass*(b%xc(1)*b%v(2) - b%xc(2)*b%v(1)) + b%inertia*b%om
         end if
      end associate
   end function region_momentum

   !> Sum of the reactions R = M a + P - F - fcon (dof `comp`) over the prescribed dofs of
   !> `nodes` (TPLOt `reac,REGIon|PHYSical` [ext]); free rigid bodies' nodes are not prescribed.
   real(wp) function reaction_sum(stp, nodes, comp) result(r)
      type(stepper_t), intent(in) :: stp
      integer, intent(in) :: nodes(:), comp
      integer :: j, i, ib
      r = 0.0_wp
      do j = 1, size(nodes)
         i = nodes(j)
         if (.not. stp%st%active(i) .or. stp%st%minv(comp, i) /= 0.0_wp) cycle
         ib = stp%ld%body_of(i)
         if (ib > 0) then
            if (stp%ld%bodies(ib)%kind == RB_FREE) cycle
         end if
         r = r + reaction(stp%st, i, comp)
      end do
   end function reaction_sum

   !> TPLOt `rigi,region,comp` [ext]: the rigid body of `region`: 1-2 centroid displacement,
   !> 3 rotation, 4-5 centroid velocity, 6 angular velocity. A plain RIGId body (fixed, or with
   !> its initial velocity) is reported from its nodes (mass-weighted; it does not rotate).
   real(wp) function body_value(stp, region, comp) result(val)
      type(stepper_t), intent(in) :: stp
      integer, intent(in) :: region, comp
      integer :: ib, j, k
      real(wp) :: w, wsum, acc(2)
      logical :: massless
      val = 0.0_wp
      ib = stp%ld%body_index(region)
      if (ib == 0) return
      associate (b => stp%ld%bodies(ib), st => stp%st)
         if (b%kind /= RB_PLAIN) then
            select case (comp)
            case (1, 2)
               val = b%xc(comp) - b%xc0(comp)
            case (3)
               val = b%th
            case (4, 5)
               val = b%v(comp - 3)
            case (6)
               val = b%om
            end select
            return
         end if
         if (comp == 3 .or. comp == 6) return
         wsum = 0.0_wp
         acc = 0.0_wp
         massless = sum(st%mass(b%nodes)) <= 0.0_wp
         do j = 1, b%nnode
            k = b%nodes(j)
            w = st%mass(k)
            if (massless) w = 1.0_wp
            wsum = wsum + w
            if (comp <= 2) then
               acc(comp) = acc(comp) + w*st%u(comp, k)
            else
               acc(comp - 3) = acc(comp - 3) + w*st%v(comp - 3, k)
            end if
         end do
         val = sum(acc)/wsum
      end associate
   end function body_value

   !> OUTPut,HDF5,dt_out: open <stem>.h5 and <stem>.xdmf with the mesh (once). The first output
   !> time is now, then every dt_out.
   subroutine output_open_fields(self, model, stp, dt_out, err)
      class(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(in) :: stp
      real(wp), intent(in) :: dt_out
      type(error_t), allocatable, intent(out) :: err
      if (self%fields%is_open()) return
      self%field_dt = dt_out
      self%field_next = stp%st%t
      self%field_t0 = stp%st%t
      call create_fields(self, model, stp, err)
   end subroutine output_open_fields

   !> Create <stem>.h5 and <stem>.xdmf with the mesh, with room for the output times of the
   !> schedule (field_dt) from now to the end of the program.
   subroutine create_fields(self, model, stp, err)
      type(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(in) :: stp
      type(error_t), allocatable, intent(out) :: err
      real(wp), allocatable :: x(:, :)
      integer, allocatable :: conn(:, :), edges(:, :)
      call field_mesh(self, model, stp, x, conn, edges)
      if (allocated(stp%st%status)) then
         ! erosion: the element status as one more element value (doc/erosion.md)
         call self%fields%open(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                               model%mesh%nelem, x, conn, model%mesh%region, &
                               model%mesh%mat, edges, err, cell_names=status_names(stp), &
                               energy_names=pack(ENERGY_NAMES, energy_mask(stp, self%files)), &
                               friction=stp%contact%friction, capacity=expected_field_times(model, stp%st%t, self%field_dt), &
                               node_id=self%field_nodes)
      else if (stp%st%has_plastic) then
         call self%fields%open(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                               model%mesh%nelem, x, conn, model%mesh%region, &
                               model%mesh%mat, edges, err, cell_names=PLASTIC_CELL_NAMES, &
                               energy_names=pack(ENERGY_NAMES, energy_mask(stp, self%files)), friction=stp%contact%friction, &
                               capacity=expected_field_times(model, stp%st%t, self%field_dt), node_id=self%field_nodes)
      else
         call self%fields%open(self%base//'.h5', self%base//'.xdmf', size(x, 2), &
                               model%mesh%nelem, x, conn, model%mesh%region, &
                               model%mesh%mat, edges, err, &
                               energy_names=pack(ENERGY_NAMES, energy_mask(stp, self%files)), friction=stp%contact%friction, &
                               capacity=expected_field_times(model, stp%st%t, self%field_dt), node_id=self%field_nodes)
      end if
   end subroutine create_fields

   !> The mesh of the field output (doc/fields.md, "Node numbers"): with unused node numbers,
   !> the nodes alone (self%field_nodes: their numbers), the connectivity and contact edges
   !> renumbered to them; otherwise the mesh as it is.
   subroutine field_mesh(self, model, stp, x, conn, edges)
      type(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(in) :: stp
      real(wp), allocatable, intent(out) :: x(:, :)
      integer, allocatable, intent(out) :: conn(:, :), edges(:, :)
      call written_nodes(model%mesh%defined, self%field_nodes)
      edges = stp%contact%edges()
      if (allocated(self%field_nodes)) then
         x = model%mesh%x(:, self%field_nodes)
         conn = renumbered(model%mesh%conn, self%field_nodes, model%mesh%nnode)
         edges = renumbered(edges, self%field_nodes, model%mesh%nnode)
      else
         x = model%mesh%x
         conn = model%mesh%conn
      end if
   end subroutine field_mesh

   !> The number of field output times a run writes from t on, every dt_out, up to the end time
   !> of its BATCh program (its largest TIME), plus the final state: the room the field file is
   !> made with (doc/fields.md, "Kill safety"). 0 when the program has no end time after t.
   integer function expected_field_times(model, t, dt_out) result(k)
      type(model_t), intent(in) :: model
      real(wp), intent(in) :: t, dt_out
      !> how near an integer (relative) the number of intervals counts as one: far above the
      !> rounding of the division and of the schedule's sums, far below a step of the schedule
      real(wp), parameter :: FIELD_TIMES_TOL = 1.0e-9_wp
      real(wp) :: t_end, n
      integer :: i
      k = 0
      t_end = t
      do i = 1, size(model%program)
         if (model%program(i)%name == 'time') t_end = max(t_end, model%program(i)%v(1))
      end do
      if (.not. (t_end > t .and. dt_out > 0.0_wp)) return
      n = (t_end - t)/dt_out
      if (.not. (n < 1.0e8_wp)) return
      ! an end time on the schedule (to rounding) is written as the last output time, the final
      ! state then coincides with it: n + 1 output times, which fill the room exactly, so that
      ! closing the file needs no cut (doc/fields.md, "Kill safety"); otherwise the final state
      ! is one more
      if (abs(n - anint(n)) <= FIELD_TIMES_TOL*max(1.0_wp, n)) then
         k = nint(n) + 1
      else
         k = int(n) + 2
      end if
   end function expected_field_times

   !> The element values of a run with erosion: those of its sets, then `status`.
   pure function status_names(stp) result(names)
      type(stepper_t), intent(in) :: stp
      character(len=20), allocatable :: names(:)
      if (stp%st%has_plastic) then
         names = [PLASTIC_CELL_NAMES, 'status              ']
      else
         names = [PLASTIC_CELL_NAMES(1:7), 'status              ']
      end if
   end function status_names

   !> Which of ENERGY_NAMES (explicit/energy.f90) the run's field output has: not the work of
   !> the prescribed motion, the frictional dissipation with friction only, the plastic work
   !> with a plastic set only, the other dissipations when <stem>.ene has them.
   pure function energy_mask(stp, files) result(mask)
      type(stepper_t), intent(in) :: stp
      type(history_files_t), intent(in) :: files
      logical :: mask(NENERGY)
      mask = files%with
      mask(E_WPM) = .false.
      mask(E_FRICTION) = stp%contact%friction
      mask(E_PLASTIC) = stp%st%has_plastic
   end function energy_mask

   !> Write the fields when an output time is due. The next output time is the first multiple
   !> of the interval after t: with an interval below the time step the fields are written once
   !> per step (the stepper's report says so once), and the schedule skips the intervals a long
   !> step jumped over at once rather than one by one.
   subroutine output_fields_due(self, stp, err)
      class(output_t), intent(inout) :: self
      type(stepper_t), intent(inout) :: stp
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: behind, next
      if (.not. self%fields%is_open()) return
      self%field_checked = stp%st%t
      ! output times kept in memory longer than the batch allows go to the file now (the rows of
      ! the text files up to them were flushed when they were taken)
      call self%fields%flush_stale(err)
      if (allocated(err)) return
      if (stp%st%t < self%field_next*(1.0_wp - TIME_TOL)) return
      if (self%field_dt < stp%st%dt_prev .and. .not. self%warned_interval) then
         self%warned_interval = .true.
         call self%files%say('warning: the OUTPut,HDF5 interval '//rtoa(self%field_dt)//' is below the '// &
                             'time step '//rtoa(stp%st%dt_prev)//': fields are written once per step')
         write (error_unit, '(a)') 'exic: warning: the OUTPut,HDF5 interval '//rtoa(self%field_dt)// &
            ' is below the time step '//rtoa(stp%st%dt_prev)//': fields are written once per step'
      end if
      behind = (stp%st%t - self%field_next)/self%field_dt
      if (behind > 64.0_wp .and. behind <= huge(behind)) &
         self%field_next = self%field_next + aint(behind - 1.0_wp)*self%field_dt
      do while (self%field_next <= stp%st%t*(1.0_wp + TIME_TOL))
         next = self%field_next + self%field_dt
         ! an interval below the spacing of the times (or so small that the skip above overflows)
         ! no longer moves the schedule: the next output is then the next step
         if (.not. (next > self%field_next .and. behind <= huge(behind))) &
            next = nearest(stp%st%t*(1.0_wp + TIME_TOL), 1.0_wp)
         self%field_next = next
      end do
      ! the rows written so far reach the disk first: after a kill the text files are never
      ! behind the .h5
      call self%files%flush_all()
      call decomposition_gather_history(stp%dd, stp%st, stp%sets)
      call write_fields(self, stp, err)
   end subroutine output_fields_due

   !> The fields of the current state; with friction also the nodal friction force and the
   !> frictional dissipation (doc/friction.md).
   subroutine write_fields(self, stp, err, nonfinite)
      type(output_t), intent(inout) :: self
      type(stepper_t), intent(in) :: stp
      type(error_t), allocatable, intent(out) :: err
      logical, intent(out), optional :: nonfinite   !< the error is a non-finite value (nothing written)
      real(wp), allocatable :: sig(:, :)
      integer, allocatable :: flag(:)
      real(wp), allocatable :: u(:, :), v(:, :), acc(:, :), fcon(:, :), ffric(:, :)
      real(wp) :: energies(NENERGY)
      integer :: nc
      associate (st => stp%st)
         nc = merge(NSIG, 7, st%has_plastic)
         if (allocated(st%status)) nc = nc + 1
         allocate (sig(nc, st%nelem), flag(st%nnode))
         call all_stresses(st, stp%sets, sig)
         ! erosion: the element status (0 live, else the reason; doc/erosion.md) as the last row
         if (allocated(st%status)) sig(nc, :) = real(st%status, wp)
         energies = st%energy%values()
         energies(E_FRICTION) = stp%contact%dissipation
         ! non-finite values are never written as results: the run stops, naming where
         if (present(nonfinite)) nonfinite = .false.
         if (.not. (all_finite(size(st%u), st%u) .and. all_finite(size(st%v), st%v) .and. &
                    all_finite(size(st%a), st%a) .and. all_finite(size(st%fcon), st%fcon) .and. &
                    all_finite(size(sig), sig) .and. all_finite(size(energies), energies))) then
            if (present(nonfinite)) nonfinite = .true.
            call make_error(err, 'a value is not finite at t = '//rtoa(st%t)//', step '//itoa(int(st%step))// &
                            ': '//first_nonfinite(stp))
            return
         end if
         flag = merge(1, 0, st%fcon(1, :) /= 0.0_wp .or. st%fcon(2, :) /= 0.0_wp)
         if (allocated(self%field_nodes)) then
            ! the nodes alone (field_mesh)
            associate (k => self%field_nodes)
               u = st%u(:, k)
               v = st%v(:, k)
               acc = st%a(:, k)
               fcon = st%fcon(:, k)
               flag = flag(k)
               if (stp%contact%friction) then
                  ffric = stp%contact%ffric(:, k)
                  call put(u, v, acc, fcon, flag, ffric)
               else
                  call put(u, v, acc, fcon, flag)
               end if
            end associate
         else if (stp%contact%friction) then
            call put(st%u, st%v, st%a, st%fcon, flag, stp%contact%ffric)
         else
            call put(st%u, st%v, st%a, st%fcon, flag)
         end if
         self%field_last = st%t
      end associate

   contains

      !> One output time of the nodal values given (every node, or the nodes of field_mesh).
      subroutine put(u, v, a, fcon, active, ffric)
         real(wp), intent(in), contiguous :: u(:, :), v(:, :), a(:, :), fcon(:, :)
         integer, intent(in), contiguous :: active(:)
         real(wp), intent(in), contiguous, optional :: ffric(:, :)
         call self%fields%write_step(stp%st%t, stp%st%step, u, v, a, sig, fcon, active, &
                                     pack(energies, energy_mask(stp, self%files)), &
                                     pack(ENERGY_NAMES, energy_mask(stp, self%files)), err, ffric)
      end subroutine put

   end subroutine write_fields

   !> The final state: its history row and fields, unless already written.
   subroutine output_final(self, model, stp, err)
      class(output_t), intent(inout) :: self
      type(model_t), intent(in) :: model
      type(stepper_t), intent(inout) :: stp
      type(error_t), allocatable, intent(out) :: err
      if (self%last_row_step /= stp%st%step) call write_rows(self, model, stp)
      call self%files%flush_all()
      if (self%fields%is_open() .and. stp%st%t > self%field_last) then
         call decomposition_gather_history(stp%dd, stp%st, stp%sets)
         call write_fields(self, stp, err)
      end if
   end subroutine output_final

   !> After a failed run: the fields of the state the stepper holds (the step it stopped in), if
   !> fields are written and that time is not in the file yet, and the failure `message` as the
   !> attribute `failed` of the .h5 file (doc/fields.md). The history files get no row.
   subroutine output_failed(self, stp, message, err)
      class(output_t), intent(inout) :: self
      type(stepper_t), intent(in) :: stp
      character(len=*), intent(in) :: message
      type(error_t), allocatable, intent(out) :: err
      logical :: nonfinite
      if (.not. self%fields%is_open()) return
      if (stp%st%t > self%field_last .and. history_stale(stp%dd, stp%sets)) then
         ! an error may have come on this rank alone: no exchange, and no stale history written
         call self%files%say('fields of the state at the failure not written (t = '//rtoa(stp%st%t)// &
                             '): on several MPI ranks the element history is not gathered after an error')
      else if (stp%st%t > self%field_last) then
         call write_fields(self, stp, err, nonfinite)
         if (nonfinite) then
            ! the failure names where the values appeared; the fields of t = field_last are the last
            deallocate (err)
            if (self%field_last > -huge(1.0_wp)) then
               call self%files%say('fields of the state at the failure not written (t = '//rtoa(stp%st%t)// &
                                   '): it holds values that are not finite; the last fields are those of t = '// &
                                   rtoa(self%field_last))
            else
               call self%files%say('fields of the state at the failure not written (t = '//rtoa(stp%st%t)// &
                                   '): it holds values that are not finite; no fields were written before')
            end if
         else
            if (allocated(err)) return
            call self%files%say('fields of the state at the failure written (t = '//rtoa(stp%st%t)//')')
         end if
      end if
      call self%fields%mark_failed(message, err)
   end subroutine output_failed

   !> Close the field files (reporting a failure in <stem>.out) and the text files.
   subroutine output_close(self)
      class(output_t), intent(inout) :: self
      type(error_t), allocatable :: err
      if (self%fields%is_open()) then
         call self%fields%close(err)
         if (allocated(err)) call self%files%say('error: '//err%message)
      end if
      call self%files%close()
   end subroutine output_close

end module exic_output
