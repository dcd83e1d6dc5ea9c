!> PENAlty under AUTOmatic contact (doc/contact-detection.md, "PENAlty under AUTOmatic"): one
!> search over all surfaces per step makes the passes of the pairs of surfaces that have
!> candidates, none for bodies apart; the stable step of the springs is the one of a pass per
!> ordered pair of surfaces, bit for bit; and with friction the run is, byte for byte, the run of
!> one NTOS PAIR per ordered pair of regions in the same order (each with its own tangential
!> state), which is what AUTOmatic asks for.
module test_contact_auto
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_strings, only: itoa, rtoa
   use exic_contact_spec, only: contact_spec_t, METHOD_PENALTY
   use exic_contact_contact, only: contact_t
   use testing, only: suite_t, check, section, file_text, error_text
   use deck_runner, only: run_dir, run_deck, read_table, column
   use scene_decks, only: sliding_blocks_deck, blocks_contact
   implicit none
   private

   public :: run_contact_auto_tests

   character(len=*), parameter :: nl = new_line('a')

contains

   subroutine run_contact_auto_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'contact_auto: PENAlty under AUTOmatic, passes only for surfaces near each other')
      call passes_test(s)
      call section(s, 'contact_auto: PENAlty and FRICtion under AUTOmatic against one NTOS PAIR per ordered pair')
      call friction_pairs_test(s)
   end subroutine run_contact_auto_tests

   !> nb x nb unit squares of one element each, 2 apart, region b for body b, with PENAlty,100
   !> under AUTOmatic. Apart, a step makes no pass at all (one per ordered pair would be
   !> nb^2 (nb^2 - 1) = 1260); with body 2 pushed 0.02 into body 1, exactly the two passes (1, 2)
   !> and (2, 1), whose forces add up to zero. The springs' stable step with one light node
   !> in body 1 and a lighter body 7 equals the formula over every ordered pair of surfaces
   !> (doc/contact-detection.md: the lightest master of each slave surface), to the bit.
   subroutine passes_test(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nb = 6, nbody = nb*nb, nnode = 4*nbody
      type(contact_spec_t) :: spec
      type(contact_t) :: c
      type(error_t), allocatable :: err
      real(wp) :: x(2, nnode), x2(2, nnode), vt(2, nnode), a(2, nnode), minv(2, nnode), fcon(2, nnode)
      integer :: conn(4, nbody), region(nbody), mat(nbody)
      integer :: b, i, j, n, nactive
      real(wp) :: dt, dt_ref, mmin, w2
      real(wp), parameter :: k = 100.0_wp
      do b = 1, nbody
         associate (x0 => 2.0_wp*real(mod(b - 1, nb), wp), y0 => 2.0_wp*real((b - 1)/nb, wp))
            x(:, 4*b - 3) = [x0, y0]
            x(:, 4*b - 2) = [x0 + 1.0_wp, y0]
            x(:, 4*b - 1) = [x0 + 1.0_wp, y0 + 1.0_wp]
            x(:, 4*b) = [x0, y0 + 1.0_wp]
         end associate
         conn(:, b) = [4*b - 3, 4*b - 2, 4*b - 1, 4*b]
         region(b) = b
      end do
      mat = 1
      spec%active = .true.
      spec%automatic = .true.
      spec%auto_options%method = METHOD_PENALTY
      spec%auto_options%penalty = k
      spec%auto_options%where = 'test'
      call c%init(spec, nnode, x, x, nbody, conn, region, mat, 1.0_wp, err)
      call check(s, .not. allocated(err), 'penalty AUTOmatic over 36 bodies sets up', error_text(err))
      if (allocated(err)) return
      vt = 0.0_wp
      a = 0.0_wp
      minv = 1.0_wp
      call c%correct(nnode, x, vt, a, minv, 0.0_wp, 1.0e-3_wp, fcon, nactive, err)
      call check(s, .not. allocated(err) .and. c%npass == 0 .and. size(c%passes) == 0 .and. nactive == 0, &
                 'bodies apart: a step makes no pass (one per ordered pair would make '// &
                 itoa(nbody*(nbody - 1))//')', 'passes '//itoa(c%npass)//' of '//itoa(size(c%passes)))
      x2 = x
      x2(1, 5:8) = x2(1, 5:8) - 1.02_wp
      call c%correct(nnode, x2, vt, a, minv, 0.0_wp, 1.0e-3_wp, fcon, nactive, err)
      n = c%npass
      call check(s, .not. allocated(err) .and. n == 2 .and. nactive > 0, &
                 'body 2 pushed into body 1: two passes with active springs', &
                 'passes '//itoa(n)//', active '//itoa(nactive))
      if (n == 2) call check(s, c%passes(1)%slave == c%auto_first + 1 .and. c%passes(1)%master == c%auto_first + 2 &
                             .and. c%passes(2)%slave == c%auto_first + 2 .and. &
                             c%passes(2)%master == c%auto_first + 1, 'the passes are (1, 2) then (2, 1)')
      call check(s, maxval(abs(fcon)) > 0.0_wp .and. &
                 all(abs(sum(fcon, dim=2)) <= 1.0e-12_wp*maxval(abs(fcon))), &
                 'the spring forces add up to zero', 'sum '//rtoa(sum(fcon(1, :)))//', '//rtoa(sum(fcon(2, :))))
      ! masses: 1 everywhere, 1/1000 at one node of body 1, 1/2 over body 7
      minv(:, 2) = 1000.0_wp
      minv(:, 25:28) = 2.0_wp
      dt = c%stable_dt(nnode, minv)
      dt_ref = huge(1.0_wp)
      do i = 1, nbody
         do j = 1, nbody
            if (i == j) cycle
            mmin = minval(1.0_wp/minv(1, 4*j - 3:4*j))
            do b = 4*i - 3, 4*i
               w2 = k*(minv(1, b) + 1.0_wp/mmin)
               dt_ref = min(dt_ref, 1.0_wp/sqrt(w2))
            end do
         end do
      end do
      call check(s, dt == dt_ref, 'the springs'' stable step is that of a pass per ordered pair, to the bit', &
                 rtoa(dt)//' against '//rtoa(dt_ref))
      call check(s, abs(dt - 1.0_wp/sqrt(k*(1000.0_wp + 2.0_wp))) <= 1.0e-15_wp, &
                 'the light node of body 1 against the lighter body 7: 1/sqrt(k (1000 + 2))', rtoa(dt))
   end subroutine passes_test

   !> The sliding blocks with PENAlty and FRICtion under AUTOmatic and with one NTOS PAIR per
   !> ordered pair of regions: the same histories and energies, byte for byte (the springs'
   !> forces in the same order, each pair's tangential state its own, the same stable step);
   !> and the scene does what it is for: the second block is pushed on, friction dissipates.
   subroutine friction_pairs_test(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, a, b
      character(len=64), allocatable :: names(:)
      real(wp), allocatable :: d(:, :), e(:, :)
      integer :: stage1, stage2, n
      call run_deck('auto_pen_fric', sliding_blocks_deck(blocks_contact(.true.)), stage1, msg)
      call check(s, stage1 == 0, 'AUTOmatic run', msg)
      call run_deck('pairs_pen_fric', sliding_blocks_deck(blocks_contact(.false.)), stage2, msg)
      call check(s, stage2 == 0, 'six NTOS PAIRs run', msg)
      if (stage1 /= 0 .or. stage2 /= 0) return
      a = file_text(run_dir//'/auto_pen_fric.his')
      b = file_text(run_dir//'/pairs_pen_fric.his')
      call check(s, len(a) > 10000 .and. a == b, 'the .his is identical')
      a = file_text(run_dir//'/auto_pen_fric.ene')
      b = file_text(run_dir//'/pairs_pen_fric.ene')
      call check(s, len(a) > 10000 .and. a == b, 'the .ene is identical')
      call read_table(run_dir//'/auto_pen_fric.his', names, d)
      call read_table(run_dir//'/auto_pen_fric.ene', names, e)
      n = size(d, 2)
      call check(s, d(5, n) > 0.05_wp, 'the second block is pushed on', 'disp,10,1 = '//rtoa(d(5, n)))
      call check(s, e(column(names, 'friction_dissipation'), size(e, 2)) > 0.0_wp .and. &
                 maxval(e(column(names, 'active'), :)) >= 3.0_wp, 'friction dissipates, springs on several pairs')
   end subroutine friction_pairs_test


end module test_contact_auto
