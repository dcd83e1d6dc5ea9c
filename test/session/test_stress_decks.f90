!> Regression tests from the decks the stress suite saved (test/data/stress, doc/stability.md):
!> each ran to the end with a defect that is fixed now, and the test asserts the figure that
!> showed it, read from the run's <stem>.out.
!>
!> - scene 259: a block at 0.3 c against the corner of a rigid wall; a node of the block ended
!>   0.16 element edges inside the wall, reported as 0.03 over the detected pairs. Now the
!>   geometric check (src/exic/contact/inside.f90) finds no node deeper than 1e-3 edges.
!> - scene 206: disks pressed into each other while sliding; the contact corrector did
!>   positive work every step (the frozen normal of the predicted t(n+2) is not perpendicular
!>   to the segment at t(n+1), so a sliding node started every step "behind" it), and the
!>   physical energy grew by 8.8 %. Now the growth stays below the warning limit (1 %).
!> - scene 98: a light block (density 0.06) sliding over a heavy disk (23): the same cause,
!>   growth 6.2 %; now below 1 %.
!> - scene 101 of seed 20261123: a one-point block landing corner-first on a rigid block; its
!>   corner node and both neighbours lie on the rigid face, the corner's det J is 0 to round-off
!>   and the run stopped as "folded" at step 57. A flat corner is a triangle, not a fold
!>   (doc/decisions.md, "Inverted and folded elements"): it runs to the end. (Saved under its own
!>   name: a stress run of that seed replaces the scene_<seed>_*.inp files.)
!> - scene 19 of seed 20261124: a block hit corner-first by a rigid block at about 0.24 c; with
!>   HOURglass 0.1 a one-point element folded by its hourglass mode at step 55 (its corner node in
!>   contact). With HOURglass,PHYSical (the assumed-strain control, doc/hourglass.md) the run ends
!>   at its final time. The same deck with HOURglass 0.1 stopped there too (exic 0461a1e: element
!>   34 folded at step 55, no node inside the other body deeper than 3.2e-6 edges) until the
!>   concave rule of contact detection (doc/contact-detection.md, "A node sliding into a master's
!>   concave corner"), which acts in this run and changes the contact forces at the corner: it
!>   now ends at its final time too. The fold was not a penetration; what this records is that
!>   the run with the new contact forces ends, not a property of HOURglass 0.1.
!> - mutant 280 of the fuzzer's seed 20261128: a bar at rest with its massless face on a rigid wall;
!>   nothing is put in and the strain energy is round-off (terms that cancel), which the energy
!>   guard took as energy appearing from nothing and stopped on at step 1, writing a non-finite percentage in
!>   <stem>.out. The guard now measures against the round-off scale ENERGY_FLOOR eps M c^2.
!> - scene 454 of seed 20261201: a hollow POLAr ring thrown at an immovable rigid block closes
!>   on itself (AUTOmatic contact is between bodies; no self contact was asked for): by
!>   t = 0.42 25 of its boundary nodes lie inside its own elements, and the geometric check,
!>   which tested nodes against other bodies only, said nothing. It now warns that the body has
!>   passed through itself.
!> - scene 86 of seed 20261125: two one-point blocks with HOURglass,PHYSical, a corner impact;
!>   without the corner barrier (doc/hourglass.md section 5) element 106 folded at a corner at
!>   step 156 (t = 0.1708, the release build of the commit before the barrier); with it the run
!>   ends at its final time with no energy growth.
!> - plastic1pt_corner_12x8 (tools/stress/plastic_1pt.py, the family of section 1k of
!>   doc/stability/by_hand.md): a 12 x 8 one-point plastic block with HOURglass,PHYSical hits an
!>   elastic slab corner-first at CFL 0.9; crushed elements sit with a corner at the barrier's
!>   threshold r0 and enter it step by step, and the energy guard stopped the run at t = 2.63
!>   with 11 % growth (the release build of ed34b8b). With the barrier's entry bound
!>   (doc/hourglass.md (H20)) it ends at its final time and the physical energy never exceeds
!>   the energy put in.
!> - scene 82 of seed 20261229: a plastic disk between two fixed rigid walls; the convex corner
!>   node of a crushed element (node normal 67 degrees from the wall's) failed the facing test
!>   and crossed the wall, 0.42 edges deep when element 227 inverted at step 355. With the facing
!>   rule's side test (doc/contact-detection.md, "Facing test") the run ends at its final time
!>   with no node inside a wall. (Saved under its own name, as scene 101 of seed 20261123.)
!> - variant 144 of tools/stress/uncoupled_family.py --seed 7: four elastic blocks meeting at the
!>   centre; a node sliding on a face toward the master's convex corner started a step 2e-9 in
!>   front of it and 0.07 behind the side face across the corner, which won (tau_c = 0 before a
!>   crossing) and pushed it out through the side: 47 % growth, the energy guard stopped the run
!>   at t = 0.802. With the nearest-face rule (doc/contact-detection.md) it ends at its final time
!>   with no growth.
module test_stress_decks
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_strings, only: itoa, rtoa
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_driver, only: run_options_t, run_model
   use deck_runner, only: run_dir
   use testing, only: suite_t, check, section, file_text
   implicit none
   private

   public :: run_stress_decks_tests

contains

   subroutine run_stress_decks_tests(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: out
      real(wp) :: v
      call section(s, 'stress decks: scene 259, block against a rigid wall corner')
      call run_saved(s, 'scene_20240610_0259', out)
      v = number_after(line_with(out, 'largest penetration'), ' by ')
      if (index(line_with(out, 'largest penetration'), '(geometric, at') > 0) v = 0.0_wp   ! no node inside
      call check(s, v >= 0.0_wp .and. v < 1.0e-3_wp, 'deepest node inside another body < 1e-3 edges '// &
                 '(was 0.16)', line_with(out, 'largest penetration'))
      call check(s, index(out, 'warning: at t') == 0, 'no penetration warning')
      call section(s, 'stress decks: scene 206, sliding disks')
      call run_saved(s, 'scene_20240610_0206', out)
      call check_growth(s, out, 'energy growth below the warning limit of 1 % (was 8.8 %)')
      call section(s, 'stress decks: scene 98, light block over a heavy disk')
      call run_saved(s, 'scene_20240610_0098', out)
      call check_growth(s, out, 'energy growth below the warning limit of 1 % (was 6.2 %)')
      call section(s, 'stress decks: scene 101 of seed 20261123, a corner flattened on a rigid face')
      call run_saved(s, 'flat_corner_20261123_0101', out)
      call check_final_time(s, out, 12.384075_wp, 'final time 12.384 (stopped at 0.646 as folded)')
      call section(s, 'stress decks: scene 19 of seed 20261124, a one-point block under a corner impact')
      call run_saved(s, 'hourglass_20261124_0019', out)
      call check_final_time(s, out, 3.6115656_wp, 'HOURglass,PHYSical: final time 3.6116 (0461a1e stopped at '// &
                            '0.2287 with HOURglass 0.1)')
      call check_growth(s, out, 'energy growth below the warning limit of 1 %')
      call fold_with_fb(s)
      call section(s, 'stress decks: fuzzed mutant 280 of seed 20261128, a bar at rest touching a wall')
      call run_saved(s, 'rest_on_wall_20261128_0280', out)
      call check_growth(s, out, 'nothing put in, round-off energies: growth below the '// &
                        'warning limit (stopped at step 1 as "appeared with no energy put in")')
      call check(s, index(out, 'warning:') == 0 .and. index(out, 'Infinity') == 0 .and. index(out, 'NaN') == 0, &
                 'no warning and no non-finite number in <stem>.out')
      call section(s, 'stress decks: an impulsive start (velocities at 3 single nodes, nu 0.49, CFL 0.8)')
      call run_saved(s, 'impulse_12x6_nu049', out)
      call check_final_time(s, out, 0.5_wp, 'runs to its final time 0.5 (stopped at step 1, 18 % growth of '// &
                            'K + strain: the highest modes)')
      call check_growth(s, out, 'the conserved energy K + C + strain below the warning limit of 1 %')
      call check(s, index(out, 'warning:') == 0, 'no warning in <stem>.out')
      call section(s, 'stress decks: scene 86 of seed 20261125, two one-point blocks, a corner impact')
      call run_saved(s, 'barrier_20261125_0086', out)
      call check_final_time(s, out, 2.4756629_wp, 'corner barrier: final time 2.4757 (stopped at '// &
                            '0.1708, element 106 folded, without it)')
      call check_growth(s, out, 'energy growth below the warning limit of 1 %')
      call section(s, 'stress decks: a crushed one-point plastic block at CFL 0.9 (section 1k)')
      call run_saved(s, 'plastic1pt_corner_12x8', out)
      call check_final_time(s, out, 5.6_wp, 'final time 5.6 (stopped at 2.63 by the energy guard, 11 % growth)')
      v = number_after(out, 'largest growth of the physical energy over the energy put in ')
      call check(s, v >= 0.0_wp .and. v < 0.1_wp, 'physical energy never above the energy put in by '// &
                 '0.1 % (kinetic + strain + plastic work; was 11 %)', line_with(out, 'energy guard'))
      call section(s, 'stress decks: a block bouncing between frictionless rigid walls, 10^5 steps')
      call run_saved(s, 'flat_wall_bounce', out)
      call transverse_momentum(s, run_dir//'/flat_wall_bounce.his')
      call section(s, 'stress decks: scene 454 of seed 20261201, a hollow ring closing on itself')
      call run_saved(s, 'ring_self_20261201_0454', out)
      call check(s, index(out, 'node(s) of region 2 are inside other elements of region 2 (the body has '// &
                 'passed through itself') > 0, 'warned: nodes of the ring inside its own elements (not '// &
                 'warned before)', line_with(out, 'warning: at t'))
      call check(s, index(out, 'geometric penetration check: region 2 through itself past the limit at') > 0, &
                 'the summary counts the checks that found the ring through itself', &
                 line_with(out, 'through itself'))
      call check_final_time(s, out, 1.1227209_wp, 'runs to its final time 1.1227')
      call section(s, 'stress decks: scene 82 of seed 20261229, a crushed corner against a rigid wall')
      call run_saved(s, 'facing_side_20261229_0082', out)
      call check_final_time(s, out, 0.20316527_wp, 'final time 0.2032 (stopped at 0.0672, element 227 '// &
                            'inverted, a node 0.42 edges inside the wall)')
      v = number_after(line_with(out, 'largest penetration'), ' by ')
      if (index(line_with(out, 'largest penetration'), '(geometric, at') > 0) v = 0.0_wp   ! no node inside
      call check(s, v >= 0.0_wp .and. v < 1.0e-3_wp, 'deepest node inside another body < 1e-3 edges '// &
                 '(was 0.42)', line_with(out, 'largest penetration'))
      call check(s, index(out, 'warning: at t') == 0, 'no penetration warning')
      call check_growth(s, out, 'energy growth below the warning limit of 1 %')
      call section(s, 'stress decks: four blocks meeting at the centre, a node at a convex corner (uncoupled family)')
      call run_saved(s, 'nearest_face_uncoupled_7_144', out)
      call check_final_time(s, out, 2.6_wp, 'final time 2.6 (stopped at 0.802 by the energy guard, 47 % growth)')
      v = number_after(out, 'largest growth of the physical energy over the energy put in ')
      call check(s, v >= 0.0_wp .and. v < 1.0e-3_wp, 'physical energy never above the energy put in by '// &
                 '1e-3 % (was 47 %: contact work 150 in one step)', line_with(out, 'energy guard'))
      call check(s, index(out, 'warning:') == 0, 'no warning in <stem>.out (no node inside another body)')
   end subroutine run_stress_decks_tests

   !> The run's largest energy growth (<stem>.out) is below the warning limit of 1 %.
   subroutine check_growth(s, out, label)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: out, label
      real(wp) :: v
      v = number_after(out, 'largest growth of the physical energy over the energy put in ')
      call check(s, v >= 0.0_wp .and. v < 1.0_wp, label, line_with(out, 'energy guard'))
   end subroutine check_growth

   !> The run ended at the final time `t_end` (<stem>.out, to 1e-5).
   subroutine check_final_time(s, out, t_end, label)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: out, label
      real(wp), intent(in) :: t_end
      real(wp) :: v
      v = number_after(out, 'final time ')
      call check(s, abs(v - t_end) < 1.0e-5_wp, label, line_with(out, 'final time'))
   end subroutine check_final_time

   !> The largest |p_y| of the block (column 4 of the .his: t, cont, mome x, mome y, disp) over
   !> the run against p_x at t = 0: frictionless flat walls normal to x must keep it at round-off.
   subroutine transverse_momentum(s, path)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: path
      character(len=512) :: line
      real(wp) :: row(5), px0, pymax
      integer :: u, ios, n
      px0 = 0.0_wp
      pymax = -1.0_wp
      n = 0
      open (newunit=u, file=path, action='read', iostat=ios)
      if (ios == 0) then
         do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (line(1:1) == '#' .or. len_trim(line) == 0) cycle
            read (line, *, iostat=ios) row
            if (ios /= 0) exit
            n = n + 1
            if (n == 1) px0 = row(3)
            pymax = max(pymax, abs(row(4)))
         end do
         close (u)
      end if
      call check(s, n > 1000 .and. px0 > 1.0_wp .and. pymax >= 0.0_wp .and. pymax <= 1.0e-12_wp*px0, &
                 'transverse momentum at round-off (was 0.0094 of 1.83 over 10^5 steps)', &
                 'rows '//itoa(n)//', largest |p_y| / p_x(0) '//rtoa(pymax/max(px0, tiny(1.0_wp))))
   end subroutine transverse_momentum

   !> The deck of scene 19 with HOURglass 0.1 in place of HOURglass,PHYSical: on exic 0461a1e it
   !> stopped at step 55 with element 34 folded; with the concave rule of contact detection it
   !> ends at its final time without energy growth and with no node inside the other body (the
   !> geometric check's deepest node below its limit of 1e-3 element edges).
   subroutine fold_with_fb(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(run_options_t) :: opts
      type(error_t), allocatable :: err
      character(len=:), allocatable :: text
      character(len=*), parameter :: phys = 'HOURglass,PHYSical'
      integer :: u, k
      text = file_text('test/data/stress/hourglass_20261124_0019.inp')
      do
         k = index(text, phys)
         if (k == 0) exit
         text = text(:k - 1)//'HOURglass 0.1'//text(k + len(phys):)
      end do
      open (newunit=u, file=run_dir//'/hourglass_fb_0019.inp', status='replace', action='write', &
            access='stream', form='unformatted')
      write (u) text
      close (u)
      call read_deck(run_dir//'/hourglass_fb_0019.inp', m, err)
      call check(s, .not. allocated(err), 'the deck with HOURglass 0.1 reads')
      if (allocated(err)) return
      opts%base = run_dir//'/hourglass_fb_0019'
      opts%quiet = .true.
      call run_model(m, opts, err)
      if (allocated(err)) then
         call check(s, .false., 'with HOURglass 0.1 the run ends (stopped at step 55 on 0461a1e)', err%message)
         return
      end if
      text = file_text(run_dir//'/hourglass_fb_0019.out')
      call check_final_time(s, text, 3.6115656_wp, 'with HOURglass 0.1: final time 3.6116 (element 34 '// &
                            'folded at step 55 before the concave rule of contact detection)')
      call check_growth(s, text, 'with HOURglass 0.1: energy growth below the warning limit of 1 %')
      call check(s, index(text, 'warning:') == 0, 'with HOURglass 0.1: no warning (no node inside the other body)')
   end subroutine fold_with_fb

   !> Run test/data/stress/<name>.inp into run_dir and return its <stem>.out.
   subroutine run_saved(s, name, out)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: name
      character(len=:), allocatable, intent(out) :: out
      type(model_t) :: m
      type(run_options_t) :: opts
      type(error_t), allocatable :: err
      call execute_command_line('mkdir -p '//run_dir)
      out = ''
      call read_deck('test/data/stress/'//name//'.inp', m, err)
      call check(s, .not. allocated(err), name//': read')
      if (allocated(err)) return
      opts%base = run_dir//'/'//name
      opts%quiet = .true.
      call run_model(m, opts, err)
      call check(s, .not. allocated(err), name//': runs to the end')
      out = file_text(run_dir//'/'//name//'.out')
   end subroutine run_saved

   !> The number that follows the first `key` in text (-1 when absent or unreadable).
   real(wp) function number_after(text, key) result(v)
      character(len=*), intent(in) :: text, key
      integer :: k, e, ios
      v = -1.0_wp
      k = index(text, key)
      if (k == 0) return
      k = k + len(key)
      e = scan(text(k:), ' ,;)'//new_line('a'))
      if (e == 0) e = len(text) - k + 2
      read (text(k:k + e - 2), *, iostat=ios) v
      if (ios /= 0) v = -1.0_wp
   end function number_after

   !> The line of text holding `key` (for the failure detail).
   function line_with(text, key) result(line)
      character(len=*), intent(in) :: text, key
      character(len=:), allocatable :: line
      integer :: k, a, b
      line = ''
      k = index(text, key)
      if (k == 0) return
      a = index(text(:k), new_line('a'), back=.true.) + 1
      b = index(text(k:), new_line('a'))
      if (b == 0) then
         b = len(text)
      else
         b = k + b - 2
      end if
      line = text(a:b)
   end function line_with

end module test_stress_decks
