!> Tests of the field output (HDF5 + XDMF): shapes and values read back by h5dump, the XDMF
!> file read by meshio, error paths, a writer killed by SIGKILL, and the metadata of a file being
!> written staying byte for byte as created.
!>
!> The data are analytic fields on a 3 x 2 quad mesh (12 nodes, 6 elements), so every value read
!> back is compared with the exact number written. The files go to build/test_fields/.
module test_fields
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_output_fields, only: field_writer_t
   use exic_base_posix, only: copy_file
   use h5dump_reader, only: h5dump
   use testing, only: suite_t, check, check_close, section, skip, have_command, have_python_modules, &
                      python_command, error_text
   implicit none
   private

   public :: run_fields_tests, synthetic_mesh, synthetic_step, write_synthetic
   public :: NNODE_T, NELEM_T, run_python

   integer, parameter :: NNODE_T = 12, NELEM_T = 6
   character(len=*), parameter :: DIR = 'build/test_fields'
   character(len=*), parameter :: ENERGY_NAMES(2) = ['kinetic', 'strain ']

contains

   ! ---------------------------------------------------------------------------- synthetic data

   !> The 3 x 2 mesh: node n at x = mod(n-1, 4), y = 0.5 (n-1)/4; element i + 3j has corners
   !> i + 4j, +1, +5, +4 (counterclockwise); region 1 below y = 0.5, 2 above; material 10 + region;
   !> contact edges along the bottom.
   subroutine synthetic_mesh(x0, conn, region, mat, edges)
      real(wp), intent(out) :: x0(2, NNODE_T)
      integer, intent(out) :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      integer :: n, i, j, e
      do n = 1, NNODE_T
         x0(:, n) = [real(mod(n - 1, 4), wp), 0.5_wp*real((n - 1)/4, wp)]
      end do
      do j = 0, 1
         do i = 1, 3
            e = i + 3*j
            n = i + 4*j
            conn(:, e) = [n, n + 1, n + 5, n + 4]
            region(e) = j + 1
            mat(e) = 10 + j + 1
         end do
      end do
      edges = reshape([1, 2, 2, 3, 3, 4], [2, 3])
   end subroutine synthetic_mesh

   !> Fields of output k (1-based) at t = k/4: u = (t x, t^2 y), v = (x, 2 t y), a = (0, 2 y),
   !> contact force (n t, -n), active = 1 when n + k is even, sig(c, e) = c + 10 e + 1000 t,
   !> energies (t^2, 3 t), step 2e9 k (beyond 32-bit integers).
   subroutine synthetic_step(k, t, step, u, v, a, sig, fcont, active, energies)
      integer, intent(in) :: k
      real(wp), intent(out) :: t
      integer(i8), intent(out) :: step
      real(wp), intent(out) :: u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T), fcont(2, NNODE_T)
      real(wp), intent(out) :: sig(7, NELEM_T), energies(2)
      integer, intent(out) :: active(NNODE_T)
      real(wp) :: x0(2, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      integer :: n, c, e

      call synthetic_mesh(x0, conn, region, mat, edges)
      t = 0.25_wp*real(k, wp)
      step = 2000000000_i8*int(k, i8)
      do n = 1, NNODE_T
         u(:, n) = [t*x0(1, n), t*t*x0(2, n)]
         v(:, n) = [x0(1, n), 2.0_wp*t*x0(2, n)]
         a(:, n) = [0.0_wp, 2.0_wp*x0(2, n)]
         fcont(:, n) = [real(n, wp)*t, -real(n, wp)]
         active(n) = merge(1, 0, mod(n + k, 2) == 0)
      end do
      do e = 1, NELEM_T
         do c = 1, 7
            sig(c, e) = real(c + 10*e, wp) + 1000.0_wp*t
         end do
      end do
      energies = [t*t, 3.0_wp*t]
   end subroutine synthetic_step

   !> Open `stem`.h5/.xdmf, write outputs 1..nsteps and flush them into the file (without
   !> closing: what a writer killed now leaves).
   subroutine write_synthetic(w, stem, nsteps, err)
      type(field_writer_t), intent(inout) :: w
      character(len=*), intent(in) :: stem
      integer, intent(in) :: nsteps
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: x0(2, NNODE_T), t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T)
      real(wp) :: fcont(2, NNODE_T), sig(7, NELEM_T), energies(2)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3), active(NNODE_T)
      integer(i8) :: step
      integer :: k

      call synthetic_mesh(x0, conn, region, mat, edges)
      call w%open(stem//'.h5', stem//'.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, edges, err)
      if (allocated(err)) return
      call write_synthetic_steps(w, 1, nsteps, err)
      if (.not. allocated(err)) call w%flush(err)
   end subroutine write_synthetic

   !> Write the synthetic outputs k1..k2 to the open writer w.
   subroutine write_synthetic_steps(w, k1, k2, err)
      type(field_writer_t), intent(inout) :: w
      integer, intent(in) :: k1, k2
      type(error_t), allocatable, intent(out) :: err
      real(wp) :: t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T)
      real(wp) :: fcont(2, NNODE_T), sig(7, NELEM_T), energies(2)
      integer :: active(NNODE_T)
      integer(i8) :: step
      integer :: k
      do k = k1, k2
         call synthetic_step(k, t, step, u, v, a, sig, fcont, active, energies)
         call w%write_step(t, step, u, v, a, sig, fcont, active, energies, ENERGY_NAMES, err)
         if (allocated(err)) return
      end do
   end subroutine write_synthetic_steps

   ! ---------------------------------------------------------------------------- the tests

   !> Run every field output test.
   subroutine run_fields_tests(s)
      type(suite_t), intent(inout) :: s
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      character(len=*), parameter :: stem = DIR//'/synthetic'

      call section(s, 'fields: write 3 output times')
      call execute_command_line('mkdir -p '//DIR)
      call write_synthetic(w, stem, 3, err)
      call check(s, .not. allocated(err), 'open and write 3 output times', error_text(err))
      call check(s, w%count() == 3 .and. w%is_open(), 'writer counts 3 output times and is open')

      call section(s, 'fields: h5dump reads the file while the writer still has it open')
      call check_h5dump_series(s, stem//'.h5', 3, 'HDF5_USE_FILE_LOCKING=FALSE ', 'live', capacity=16)

      call section(s, 'fields: bad calls are errors and leave the file alone')
      call check_step_errors(s, w)

      call w%close(err)
      call check(s, .not. allocated(err) .and. .not. w%is_open(), 'close', error_text(err))

      call section(s, 'fields: h5dump shapes and values after close')
      call check_h5dump_series(s, stem//'.h5', 3, '', 'closed')
      call check_h5dump_layout(s, stem//'.h5')

      call section(s, 'fields: meshio reads the last output, the series holds every one')
      call check_meshio(s, stem//'.xdmf', 3, 'closed')

      call section(s, 'fields: plot scripts')
      call check_plots(s, stem//'.h5')

      call section(s, 'fields: open errors')
      call check_open_errors(s)

      call section(s, 'fields: a writer killed by SIGKILL leaves readable files')
      call check_killed_writer(s)

      call section(s, 'fields: no metadata byte changes while output times are written; growth')
      call check_frozen_metadata(s)
      call check_exact_room(s)

      call section(s, 'fields: batches of output times; the files do not depend on them')
      call check_batches(s)
   end subroutine run_fields_tests

   !> Output times are kept in memory and written in batches (doc/fields.md, "Batches"): with a
   !> batch of one output time, or a time limit of 0 s, every output time is in the file when
   !> write_step returns; with a large batch none is until `flush`; a full batch is written at
   !> once. The finished files (.h5, both .xdmf) are the same bytes for batches of 1, 3, 7 and
   !> the default (room 16, 20 output times: one growth), and so is the copy of a running file
   !> after a flush at output 10.
   subroutine check_batches(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: top = DIR//'/batch'
      character(len=2), parameter :: tag(4) = ['1 ', '3 ', '7 ', '16']
      character(len=:), allocatable :: stem
      integer(i8), parameter :: huge_bytes = 2_i8**40
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      real(wp) :: x0(2, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      integer :: i, k, code, f, nb(4)
      integer(i8) :: per_time
      logical :: ok

      call execute_command_line('rm -rf '//top//'; mkdir -p '//top//'1 '//top//'3 '//top//'7 '//top//'16 '// &
                                top//'x '//top//'0')
      call synthetic_mesh(x0, conn, region, mat, edges)
      ! bytes of one output time of this mesh, as the writer counts them (2 energies)
      per_time = 8_i8*(2_i8*4*NNODE_T + 7_i8*(NELEM_T + NNODE_T) + 2 + 2) + 4_i8*NNODE_T
      do i = 1, 4
         stem = top//trim(tag(i))//'/f'
         call w%open(stem//'.h5', stem//'.xdmf', NNODE_T, NELEM_T, x0, conn, &
                     region, mat, edges, err, energy_names=ENERGY_NAMES)
         if (.not. allocated(err)) then
            select case (i)
            case (1)
               call w%set_batch(0_i8, 1.0e9_wp, err)
            case (2)
               call w%set_batch(3*per_time, 1.0e9_wp, err)
            case (3)
               call w%set_batch(7*per_time + 1, 1.0e9_wp, err)
            case (4)
               call w%set_batch(huge_bytes, 1.0e9_wp, err)   ! as large as the room
            end select
         end if
         nb = [1, 3, 7, 16]
         ok = .true.
         f = 0
         do k = 1, 20
            if (allocated(err)) exit
            call write_synthetic_steps(w, k, k, err)
            ! expected: the full room of 16 is flushed before it grows, a full batch at once
            if (k == 17) f = 16
            if (k - f == nb(i)) f = k
            ok = ok .and. w%flushed() == f
            if (k == 10 .and. .not. allocated(err)) then
               call w%flush(err)
               f = 10
               ok = ok .and. w%flushed() == 10
               if (.not. allocated(err)) call copy_file(stem//'.h5', stem//'_10.h5', err)
            end if
         end do
         ok = ok .and. w%count() == 20
         call w%close(err)
         call check(s, .not. allocated(err) .and. ok, 'batch '//trim(tag(i))//': 20 output times, in the '// &
                    'file after each full batch and after flush', error_text(err))
      end do
      if (.not. have_command('h5dump')) then
         call skip(s, 'the files of different batches compared', 'h5dump', 4)
         return
      end if
      ! h5dump of the whole file (every dataset and attribute), not its bytes: HDF5 leaves a few
      ! bytes of its metadata unset, which differ from run to run with the same data
      do i = 1, 4
         call execute_command_line('cd '//top//trim(tag(i))//' && h5dump f.h5 > f.dump 2>&1 && '// &
                                   'h5dump f_10.h5 > f_10.dump 2>&1')
      end do
      do i = 2, 4
         code = 0
         call execute_command_line('cmp -s '//top//'1/f.dump '//top//trim(tag(i))//'/f.dump && cmp -s '//top// &
                                   '1/f_10.dump '//top//trim(tag(i))//'/f_10.dump && cmp -s '//top//'1/f.xdmf '// &
                                   top//trim(tag(i))//'/f.xdmf && cmp -s '//top//'1/f_series.xdmf '//top// &
                                   trim(tag(i))//'/f_series.xdmf', exitstat=code)
         call check(s, code == 0, 'batch '//trim(tag(i))//': h5dump of the .h5 (running after 10 and closed), '// &
                    '.xdmf and _series.xdmf are those of batch 1')
      end do
      ! the check can fail: a file with other values differs
      call w%open(top//'x/f.h5', top//'x/f.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, edges, err, &
                  energy_names=ENERGY_NAMES)
      if (.not. allocated(err)) call write_synthetic_steps(w, 2, 21, err)
      if (.not. allocated(err)) call w%close(err)
      call execute_command_line('cd '//top//'x && h5dump f.h5 > f.dump 2>&1; cmp -s '//top//'1/f.dump '//top// &
                                'x/f.dump', exitstat=code)
      call check(s, .not. allocated(err) .and. code /= 0, 'the comparison sees other output times')
      ! a time limit of 0 s: every output time is flushed when it is written
      call w%open(top//'0/f.h5', top//'0/f.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, edges, err, &
                  energy_names=ENERGY_NAMES)
      if (.not. allocated(err)) call w%set_batch(huge_bytes, 0.0_wp, err)
      ok = .true.
      do k = 1, 4
         if (allocated(err)) exit
         call write_synthetic_steps(w, k, k, err)
         ok = ok .and. w%flushed() == k
      end do
      if (.not. allocated(err)) call w%close(err)
      call check(s, .not. allocated(err) .and. ok, 'a batch time limit of 0 s flushes every output time')
   end subroutine check_batches

   !> h5dump reads /time, /step and /fields/displacement of a file with `n` outputs: every value.
   subroutine check_h5dump_series(s, h5, n, env, tag, capacity)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: h5, env, tag
      integer, intent(in) :: n
      integer, intent(in), optional :: capacity   !< a file still open or killed: its room
      real(wp), allocatable :: vals(:)
      character(len=:), allocatable :: space, slots
      real(wp) :: t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T), fcont(2, NNODE_T)
      real(wp) :: sig(7, NELEM_T), energies(2), want_t(n), want_u(2, NNODE_T, n)
      real(wp) :: want_step(n), want_strain(n)
      integer :: active(NNODE_T), k, m
      integer(i8) :: step
      logical :: ok
      if (.not. have_command('h5dump')) then
         call skip(s, tag//': h5dump reads the time series', 'h5dump')
         return
      end if

      do k = 1, n
         call synthetic_step(k, t, step, u, v, a, sig, fcont, active, energies)
         want_t(k) = t
         want_step(k) = real(step, wp)
         want_u(:, :, k) = u
         want_strain(k) = energies(2)
      end do
      ! a finished file holds n slabs; one still being written (or killed) its capacity, the
      ! free slots unwritten (0: space the writer allocated and never wrote, doc/fields.md
      ! "Complete output times"); in both the count /n_times says how many are complete
      m = n
      if (present(capacity)) m = capacity
      call h5dump(env, '-d /n_times '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, [real(n, wp)]), tag//': /n_times counts '//itoa(n)// &
                 ' complete output times', list_text(vals))
      slots = itoa(m)
      call h5dump(env, '-d /time '//h5, ok, space, vals)
      call check(s, ok .and. space == '( '//slots//' ) / ( H5S_UNLIMITED )', &
                 tag//': /time has '//slots//' entries, unlimited', space)
      call check(s, prefix_then(vals, want_t), tag//': /time values', list_text(vals))
      call h5dump(env, '-d /step '//h5, ok, space, vals)
      call check(s, ok .and. prefix_then(vals, want_step), tag//': /step values (64-bit)', &
                 list_text(vals))
      call h5dump(env, '-d /fields/displacement '//h5, ok, space, vals)
      call check(s, ok .and. space == '( '//slots//', 12, 2 ) / ( H5S_UNLIMITED, 12, 2 )', &
                 tag//': /fields/displacement shape (time, node, component)', space)
      call check(s, prefix_then(vals, reshape(want_u, [2*NNODE_T*n])), &
                 tag//': every displacement value')
      call h5dump(env, '-d /energies/strain '//h5, ok, space, vals)
      call check(s, ok .and. prefix_then(vals, want_strain), tag//': /energies/strain values', &
                 list_text(vals))
   end subroutine check_h5dump_series

   !> Mesh datasets, stress layout and views of the closed 3-output file.
   subroutine check_h5dump_layout(s, h5)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: h5
      real(wp), allocatable :: vals(:)
      character(len=:), allocatable :: space
      real(wp) :: x0(2, NNODE_T), t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T)
      real(wp) :: fcont(2, NNODE_T), sig(7, NELEM_T), energies(2), want(3, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3), active(NNODE_T)
      integer(i8) :: step
      logical :: ok
      if (.not. have_command('h5dump')) then
         call skip(s, 'h5dump reads the mesh and field layout', 'h5dump')
         return
      end if

      call synthetic_mesh(x0, conn, region, mat, edges)
      call h5dump('', '-d /mesh/coordinates '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 12, 2 ) / ( 12, 2 )' .and. &
                 same(vals, reshape(x0, [2*NNODE_T])), '/mesh/coordinates (12, 2) and values', space)
      call h5dump('', '-d /mesh/connectivity '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 6, 4 ) / ( 6, 4 )' .and. &
                 same(vals, real(reshape(conn - 1, [4*NELEM_T]), wp)), &
                 '/mesh/connectivity (6, 4), 0-based', list_text(vals))
      call h5dump('', '-d /mesh/contact_edges '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 3, 2 ) / ( 3, 2 )' .and. &
                 same(vals, real(reshape(edges - 1, [6]), wp)), '/mesh/contact_edges (3, 2), 0-based', &
                 list_text(vals))
      call h5dump('', '-d /mesh/material '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, real(mat, wp)), '/mesh/material values', list_text(vals))

      ! one value: stress at output 2 (index 1), element 5 (index 4), von Mises (index 5)
      call synthetic_step(2, t, step, u, v, a, sig, fcont, active, energies)
      call h5dump('', '-d /fields/stress '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 3, 6, 7 ) / ( H5S_UNLIMITED, 6, 7 )', &
                 '/fields/stress shape (time, element, component)', space)
      call h5dump('', '-d /fields/stress -s 1,4,5 -c 1,1,1 '//h5, ok, space, vals)
      call check(s, ok .and. size(vals) == 1, 'h5dump selects one stress value')
      if (size(vals) == 1) call check_close(s, vals(1), sig(6, 5), 0.0_wp, &
                                            'von Mises of element 5 at t = 0.5 read by h5dump')
      call h5dump('', '-d /fields/contact_active '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 3, 12 ) / ( H5S_UNLIMITED, 12 )', &
                 '/fields/contact_active shape (time, node)', space)

      ! the series view of the displacement pads it with a zero z component, at every time
      call synthetic_step(3, t, step, u, v, a, sig, fcont, active, energies)
      want(1:2, :) = u
      want(3, :) = 0.0_wp
      call h5dump('', '-d /xdmf/displacement '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 3, 12, 3 ) / ( H5S_UNLIMITED, 12, 3 )', &
                 'series view /xdmf/displacement (time, node, 3), unlimited', space)
      call h5dump('', '-d /xdmf/displacement -s 2,0,0 -c 1,12,3 '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, reshape(want, [3*NNODE_T])), &
                 'slab 2 of /xdmf/displacement is u(t3) with z = 0', list_text(vals))
      ! nodal averages: every element has the same area here, so node 6 (inside; elements 1, 2,
      ! 4, 5) has the plain mean and node 1 (a corner) the value of element 1
      call h5dump('', '-d /fields/nodal_stress '//h5, ok, space, vals)
      call check(s, ok .and. space == '( 3, 12, 7 ) / ( H5S_UNLIMITED, 12, 7 )', &
                 '/fields/nodal_stress shape (time, node, component)', space)
      call h5dump('', '-d /fields/nodal_stress -s 2,5,5 -c 1,1,1 '//h5, ok, space, vals)
      call check(s, ok .and. size(vals) == 1, 'h5dump selects one nodal stress value')
      if (size(vals) == 1) call check_close(s, vals(1), 0.25_wp*(sig(6, 1) + sig(6, 2) + sig(6, 4) + &
                                                                 sig(6, 5)), 1.0e-12_wp, &
                                            'von Mises at node 6, t3: mean of its four elements')
      call h5dump('', '-d /fields/nodal_stress -s 2,0,6 -c 1,1,1 '//h5, ok, space, vals)
      if (size(vals) == 1) call check_close(s, vals(1), sig(7, 1), 0.0_wp, 'J at corner node 1, t3: element 1')
      ! the last output time (index 2) is in buffer a (outputs alternate a, b, a)
      call h5dump('', '-d /last/a/cell_von_mises '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, sig(6, :)), '/last/a/cell_von_mises is von Mises at t3', &
                 list_text(vals))
      call h5dump('', '-d /last/a/displacement '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, reshape(want, [3*NNODE_T])), '/last/a/displacement is u(t3), z = 0', &
                 list_text(vals))
      call h5dump('', '-d /last/a/output '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, [2.0_wp]), '/last/a/output names output 2', list_text(vals))
      call h5dump('', '-d /last/b/output '//h5, ok, space, vals)
      call check(s, ok .and. same(vals, [1.0_wp]), '/last/b/output names output 1', list_text(vals))
      call h5dump('', '-d /last/b/cell_von_mises '//h5, ok, space, vals)
      call synthetic_step(2, t, step, u, v, a, sig, fcont, active, energies)
      call check(s, ok .and. same(vals, sig(6, :)), '/last/b still holds t2, the output before', &
                 list_text(vals))
   end subroutine check_h5dump_layout

   !> meshio.read reads <stem>.xdmf (the last output) and the series file holds every output:
   !> counts and values through tools/check_xdmf.py; a wrong expected value makes it fail.
   subroutine check_meshio(s, xdmf, n, tag)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: xdmf, tag
      integer, intent(in) :: n
      real(wp) :: t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T), fcont(2, NNODE_T)
      real(wp) :: sig(7, NELEM_T), energies(2), t1, sig1(7, NELEM_T)
      integer :: active(NNODE_T), code
      integer(i8) :: step
      character(len=:), allocatable :: args, k
      if (.not. have_python_modules('meshio,h5py')) then
         call skip(s, tag//': meshio reads the XDMF files', 'Python with meshio and h5py', 2)
         return
      end if

      call synthetic_step(1, t1, step, u, v, a, sig1, fcont, active, energies)
      call synthetic_step(n, t, step, u, v, a, sig, fcont, active, energies)
      k = itoa(n - 1)
      args = ' --steps '//itoa(n)//' --points 12 --cells 6 --time 0,'//rtoa(t1, '(es24.16)')// &
             ' --time '//k//','//rtoa(t, '(es24.16)')// &
             ' --point-value displacement,last,5,0,'//rtoa(u(1, 6), '(es24.16)')// &
             ' --point-value displacement,last,5,1,'//rtoa(u(2, 6), '(es24.16)')// &
             ' --point-value displacement,last,5,2,0'// &
             ' --point-value contact_force,last,7,1,'//rtoa(fcont(2, 8), '(es24.16)')// &
             ' --point-value contact_active,last,2,0,'//itoa(active(3))// &
             ' --point-value von_mises,last,0,0,'//rtoa(sig(6, 1), '(es24.16)')// &
             ' --cell-value von_mises,last,4,'//rtoa(sig(6, 5), '(es24.16)')// &
             ' --cell-value J,last,0,'//rtoa(sig(7, 1), '(es24.16)')// &
             ' --cell-value sxy,'//k//',3,'//rtoa(sig(4, 4), '(es24.16)')// &
             ' --cell-value sxy,0,3,'//rtoa(sig1(4, 4), '(es24.16)')// &
             ' --cell-value material,last,4,12 --convert '//DIR//'/'//tag//'.vtu'
      code = run_python('tools/check_xdmf.py '//xdmf//args)
      call check(s, code == 0, tag//': meshio.read gets the last time, the series has '//itoa(n)// &
                 ' times; 12 points, 6 cells, values, meshio convert', 'check_xdmf.py exit code '//itoa(code))
      code = run_python('tools/check_xdmf.py '//xdmf//' --cell-value von_mises,last,4,'// &
                        rtoa(sig(6, 5) + 1.0_wp, '(es24.16)')//' > /dev/null')
      call check(s, code == 1, tag//': the check fails on a wrong value', &
                 'check_xdmf.py exit code '//itoa(code))
   end subroutine check_meshio

   !> plot_fields.py and plot_history.py run and write their PNG files; a missing input fails.
   subroutine check_plots(s, h5)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: h5
      character(len=*), parameter :: png = DIR//'/synthetic_J.png', plots = DIR//'/plots'
      character(len=*), parameter :: groups(6) = [character(len=12) :: 'displacement', 'velocity', &
                                                  'acceleration', 'contact', 'stress', 'energies']
      integer :: code, i
      logical :: exists, all_there

      if (.not. have_python_modules('matplotlib,h5py,numpy')) then
         call skip(s, 'plot_fields.py and plot_history.py', 'Python with matplotlib and h5py')
         return
      end if
      call execute_command_line('rm -rf '//png//' '//plots)
      code = run_python('tools/plot_fields.py '//h5//' -c J -t 0.3 0.7 -s 2 -o '//png// &
                        ' > /dev/null')
      inquire (file=png, exist=exists)
      call check(s, code == 0 .and. exists, 'plot_fields.py draws J at two times', &
                 'exit code '//itoa(code))
      code = run_python('tools/plot_history.py test/data/fields/sample -o '//plots//' > /dev/null')
      all_there = .true.
      do i = 1, size(groups)
         inquire (file=plots//'/sample_'//trim(groups(i))//'.png', exist=exists)
         all_there = all_there .and. exists
      end do
      call check(s, code == 0 .and. all_there, 'plot_history.py draws 5 history groups and energies', &
                 'exit code '//itoa(code))
      code = run_python('tools/plot_history.py '//DIR//'/no_such_run -o '//plots//' 2> /dev/null')
      call check(s, code == 1, 'plot_history.py fails on a missing run', 'exit code '//itoa(code))
      call execute_command_line('rm -f '//plots//'/force.png')
      code = run_python('tools/plot_history.py test/data/fields/sample --xy "disp(n31,2)" "cont(p1,1)" --negate-x -o '// &
                        plots//'/force.png > /dev/null')
      inquire (file=plots//'/force.png', exist=exists)
      call check(s, code == 0 .and. exists, 'plot_history.py --xy draws a column against another', &
                 'exit code '//itoa(code))
      code = run_python('tools/plot_history.py test/data/fields/sample --xy "disp(n99,2)" "cont(p1,1)" -o '// &
                        plots//'/none.png 2> '//DIR//'/xy.err')
      call check(s, code == 1 .and. file_has_text(DIR//'/xy.err', 'disp(n31,1)'), &
                 'plot_history.py --xy refuses a column the files lack, listing theirs', 'exit code '//itoa(code))
      code = run_python('tools/plot_fields.py '//h5//' -c plastic_strain -o '//DIR//'/none.png 2> '//DIR//'/comp.err')
      call check(s, code == 2 .and. file_has_text(DIR//'/comp.err', 'this file has sxx'), &
                 'plot_fields.py refuses a component the file lacks, listing the file''s components', &
                 'exit code '//itoa(code))
      ! the run's output times are 0.25, 0.5, 0.75: 2.0 is after the run
      call execute_command_line('rm -f '//DIR//'/late.png '//DIR//'/anim.gif')
      code = run_python('tools/plot_fields.py '//h5//' -t 0.5 2.0 -o '//DIR//'/late.png 2> '//DIR//'/late.err')
      inquire (file=DIR//'/late.png', exist=exists)
      call check(s, code == 2 .and. .not. exists .and. file_has_text(DIR//'/late.err', 'time 2 outside the run'), &
                 'plot_fields.py refuses a time after the run, saying so on stderr', 'exit code '//itoa(code))
      code = run_python('tools/plot_fields.py '//h5//' -t 2.0 --clamp --nodal -o '//DIR//'/late.png 2> '// &
                        DIR//'/late.err > /dev/null')
      inquire (file=DIR//'/late.png', exist=exists)
      call check(s, code == 0 .and. exists .and. file_has_text(DIR//'/late.err', 'warning'), &
                 'with --clamp it draws the last output time (nodal contours) and warns', 'exit code '//itoa(code))
      code = run_python('tools/animate_fields.py '//h5//' -c von_mises -o '//DIR//'/anim.gif > /dev/null && '// &
                        python_command()//' -c "from PIL import Image; import sys; '// &
                        'sys.exit(0 if Image.open('''//DIR//'/anim.gif'').n_frames == 3 else 1)"')
      call check(s, code == 0, 'animate_fields.py writes a GIF of the 3 output times', 'exit code '//itoa(code))
      code = run_python('tools/plot_summary.py test/data/fields/sample -o '//plots//'/summary.png > /dev/null')
      inquire (file=plots//'/summary.png', exist=exists)
      call check(s, code == 0 .and. exists, 'plot_summary.py draws the summary page', 'exit code '//itoa(code))
   end subroutine check_plots

   !> The file exists and contains `text`.
   logical function file_has_text(path, text) result(found)
      character(len=*), intent(in) :: path, text
      character(len=1024) :: line
      integer :: u, ios
      found = .false.
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (index(line, text) > 0) found = .true.
      end do
      close (u)
   end function file_has_text

   !> write_step errors on an open writer with 3 outputs: nothing is written.
   subroutine check_step_errors(s, w)
      type(suite_t), intent(inout) :: s
      type(field_writer_t), intent(inout) :: w
      type(field_writer_t) :: closed
      type(error_t), allocatable :: err
      real(wp) :: t, u(2, NNODE_T), v(2, NNODE_T), a(2, NNODE_T), fcont(2, NNODE_T)
      real(wp) :: sig(7, NELEM_T), energies(2), bad(2, NNODE_T - 1)
      integer :: active(NNODE_T)
      integer(i8) :: step

      call synthetic_step(4, t, step, u, v, a, sig, fcont, active, energies)
      call w%write_step(t, step, bad, v, a, sig, fcont, active, energies, ENERGY_NAMES, err)
      call check(s, allocated(err), 'u of the wrong shape is an error')
      call w%write_step(0.5_wp, step, u, v, a, sig, fcont, active, energies, ENERGY_NAMES, err)
      call check(s, has(err, 'must increase'), 'an output time not after the last is an error', &
                 error_text(err))
      call w%write_step(t, step, u, v, a, sig, fcont, active, energies, ['kinetic', 'total  '], err)
      call check(s, has(err, 'strain'), 'a changed energy name is an error naming it', error_text(err))
      call closed%write_step(t, step, u, v, a, sig, fcont, active, energies, ENERGY_NAMES, err)
      call check(s, has(err, 'not open'), 'write_step on a writer never opened is an error', &
                 error_text(err))
      call check(s, w%count() == 3, 'failed calls leave 3 output times')
   end subroutine check_step_errors

   !> open errors: missing directory, bad connectivity, files in different directories.
   subroutine check_open_errors(s)
      type(suite_t), intent(inout) :: s
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      real(wp) :: x0(2, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      character(len=*), parameter :: missing = DIR//'/no/such/dir/x'

      call synthetic_mesh(x0, conn, region, mat, edges)
      call w%open(missing//'.h5', missing//'.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, &
                  edges, err)
      call check(s, has(err, missing//'.h5') .and. .not. w%is_open(), &
                 'creating a file in a missing directory is an error naming it', error_text(err))
      conn(3, 4) = NNODE_T + 1
      call w%open(DIR//'/bad.h5', DIR//'/bad.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, &
                  edges, err)
      call check(s, has(err, 'element 4'), 'a node number out of range is an error naming the element', &
                 error_text(err))
      conn(3, 4) = 9
      call w%open(DIR//'/bad.h5', 'elsewhere/bad.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, &
                  edges, err)
      call check(s, has(err, 'one directory'), '.h5 and .xdmf in different directories is an error', &
                 error_text(err))
   end subroutine check_open_errors

   !> Run test/field_writer_child: it writes 4 outputs, then waits; kill it with SIGKILL and read
   !> what it left with h5dump (no locking override: the lock dies with the process) and meshio.
   subroutine check_killed_writer(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: stem = DIR//'/killed', marker = DIR//'/killed.ready', &
                                     status_file = DIR//'/killed.status'
      character(len=4096) :: argv0
      character(len=:), allocatable :: child, script
      logical :: exists
      integer :: status, u, ios

      call get_command_argument(0, argv0)
      child = argv0(1:index(argv0, '/', back=.true.))//'field_writer_child'
      if (index(argv0, '/') == 0) child = './field_writer_child'
      inquire (file=child, exist=exists)
      call check(s, exists, 'child program found next to the test driver', child)
      if (.not. exists) return

      script = 'rm -f '//marker//' '//status_file//' '//stem//'.h5 '//stem//'.xdmf '//stem//'_series.xdmf; '// &
               child//' --child '//stem//' 4 '//marker//' > '//DIR//'/killed.log 2>&1 & pid=$!; i=0; '// &
               'while [ ! -e '//marker//' ] && [ $i -lt 1200 ]; do sleep 0.05; i=$((i+1)); done; '// &
               'kill -KILL $pid; wait $pid 2> /dev/null; echo $? > '//status_file
      call execute_command_line(script)
      status = -1
      open (newunit=u, file=status_file, action='read', status='old', iostat=ios)
      if (ios == 0) then
         read (u, *, iostat=ios) status
         close (u)
      end if
      call check(s, status == 128 + 9, 'child was killed by SIGKILL after writing 4 outputs', &
                 'shell status '//itoa(status)//' (see '//DIR//'/killed.log)')
      call check_h5dump_series(s, stem//'.h5', 4, '', 'killed', capacity=16)
      call check_meshio(s, stem//'.xdmf', 4, 'killed')
   end subroutine check_killed_writer

   !> The design of doc/fields.md "Kill safety": copies of the file taken right after `open` and
   !> after 5 output times (the writer still open: what a SIGKILL then leaves) differ only inside
   !> the raw data of the datasets (tools/check_h5_frozen.py, which must also see the compacted
   !> file after `close` as changed: the check can fail). Then 15 more output times, beyond the
   !> room of 16 made at open: the file grows by a copy to 32 and keeps every value.
   subroutine check_frozen_metadata(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: stem = DIR//'/frozen'
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      real(wp) :: x0(2, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      integer :: code

      call execute_command_line('rm -f '//stem//'*')
      call synthetic_mesh(x0, conn, region, mat, edges)
      ! the energies named at open, as the deck driver does: every dataset exists from then on
      call w%open(stem//'.h5', stem//'.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, edges, err, &
                  energy_names=ENERGY_NAMES)
      if (.not. allocated(err)) call copy_file(stem//'.h5', stem//'_created.h5', err)
      if (.not. allocated(err)) call write_synthetic_steps(w, 1, 5, err)
      if (.not. allocated(err)) call w%flush(err)
      if (.not. allocated(err)) call copy_file(stem//'.h5', stem//'_running.h5', err)
      call check(s, .not. allocated(err), 'open, copy, write 5 output times, copy', error_text(err))
      if (allocated(err)) return
      if (have_python_modules('h5py,numpy')) then
         code = run_python('tools/check_h5_frozen.py '//stem//'_created.h5 '//stem//'_running.h5 --times 5 > '// &
                           stem//'_check.txt 2>&1')
         call check(s, code == 0, 'after 5 output times every byte outside the raw data is as created, '// &
                    'the count is 5, the free slots NaN', 'see '//stem//'_check.txt')
      else
         call skip(s, 'metadata bytes unchanged by output times', 'h5py', 1)
      end if
      call check_h5dump_series(s, stem//'_running.h5', 5, '', 'copy of a file being written', capacity=16)

      call write_synthetic_steps(w, 6, 20, err)
      if (.not. allocated(err)) call w%flush(err)
      if (.not. allocated(err)) call copy_file(stem//'.h5', stem//'_grown.h5', err)
      call check(s, .not. allocated(err) .and. w%count() == 20, '20 output times in a room of 16', error_text(err))
      call check_h5dump_series(s, stem//'_grown.h5', 20, '', 'grown', capacity=32)
      call w%close(err)
      call check(s, .not. allocated(err), 'close', error_text(err))
      call check_h5dump_series(s, stem//'.h5', 20, '', 'grown and closed')
      if (have_python_modules('h5py,numpy')) then
         code = run_python('tools/check_h5_frozen.py '//stem//'_created.h5 '//stem//'.h5 > '// &
                           stem//'_check_closed.txt 2>&1')
         call check(s, code /= 0, 'the check sees the metadata of the closed (cut) file changed')
      end if
   end subroutine check_frozen_metadata

   !> A run that fills the room made at open exactly (the common case: an end time on the
   !> output schedule, doc/fields.md "Kill safety") is finished as it stands: closing it makes no
   !> copy (a hard link taken before the close still names the closed file: the same bytes), and
   !> the file holds the 6 output times with the count 6. With room for 7 the close cuts the
   !> file by a copy renamed over it (the link keeps the old file: the check can fail).
   subroutine check_exact_room(s)
      type(suite_t), intent(inout) :: s
      type(field_writer_t) :: w
      type(error_t), allocatable :: err
      real(wp) :: x0(2, NNODE_T)
      integer :: conn(4, NELEM_T), region(NELEM_T), mat(NELEM_T), edges(2, 3)
      integer :: code, room
      character(len=:), allocatable :: tag, stem

      call synthetic_mesh(x0, conn, region, mat, edges)
      do room = 6, 7
         tag = 'room '//itoa(room)//' for 6 output times'
         stem = DIR//'/exact'//itoa(room)
         call execute_command_line('rm -f '//stem//'*')
         call w%open(stem//'.h5', stem//'.xdmf', NNODE_T, NELEM_T, x0, conn, region, mat, edges, err, &
                     energy_names=ENERGY_NAMES, capacity=room)
         if (.not. allocated(err)) call write_synthetic_steps(w, 1, 6, err)
         if (.not. allocated(err)) call w%flush(err)
         call execute_command_line('ln '//stem//'.h5 '//stem//'_link.h5', exitstat=code)
         if (.not. allocated(err)) call w%close(err)
         call check(s, .not. allocated(err) .and. code == 0, tag//': open, write, link, close', error_text(err))
         if (allocated(err)) return
         call check_h5dump_series(s, stem//'.h5', 6, '', tag//', closed')
         call execute_command_line('cmp -s '//stem//'.h5 '//stem//'_link.h5', exitstat=code)
         if (room == 6) then
            call check(s, code == 0, tag//': closed in place, no copy (the link names the closed file)')
         else
            call check(s, code /= 0, tag//': cut by a copy renamed over the file (the link keeps the old one)')
         end if
      end do
   end subroutine check_exact_room

   ! ---------------------------------------------------------------------------- helpers

   !> Run a Python script line with the tests' Python (testing's python_command); its exit code.
   integer function run_python(cmd) result(code)
      character(len=*), intent(in) :: cmd
      call execute_command_line(python_command()//' '//cmd, exitstat=code)
   end function run_python

   !> True when x begins with y and every value after is unwritten: NaN (`nan`) or -1.
   logical function prefix_then(x, y)
      real(wp), intent(in) :: x(:), y(:)
      integer :: n
      n = size(y)
      prefix_then = size(x) >= n
      if (prefix_then) prefix_then = all(x(1:n) == y)
      if (prefix_then) prefix_then = all(x(n + 1:) == 0.0_wp)
   end function prefix_then

   !> Exact equality of two vectors of the same size.
   logical function same(x, y)
      real(wp), intent(in) :: x(:), y(:)
      same = size(x) == size(y)
      if (same) same = all(x == y)
   end function same

   !> True when err is set and its message contains `text`.
   logical function has(err, text)
      type(error_t), allocatable, intent(in) :: err
      character(len=*), intent(in) :: text
      has = allocated(err)
      if (has) has = index(err%message, text) > 0
   end function has

   !> Up to 8 values as text.
   function list_text(x) result(s)
      real(wp), intent(in) :: x(:)
      character(len=:), allocatable :: s
      integer :: i
      s = 'got '//itoa(size(x))//' values:'
      do i = 1, min(size(x), 8)
         s = s//' '//rtoa(x(i), '(es24.16)')
      end do
   end function list_text

end module test_fields
