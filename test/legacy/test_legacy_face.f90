!> The legacy API's massless contact faces (method 3, doc/api.md; doc/impact.md section 3):
!> the refusals of EXIC_CONTACT_SET_FACE, EXIC_CONTACT_SET_FACE_DOFS and EXIC_CONTACT_FACE_RULE
!> and a face node placed on a rigid segment in one step, with both dofs massless and with the
!> normal dof only. Called by test_legacy (suite `legacy`).
module test_legacy_face
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_legacy_interfaces, only: exic_contact_create_segments, exic_contact_step, exic_contact_constraints, &
                                     exic_contact_free, exic_contact_error_message, exic_contact_set_face, &
                                     exic_contact_step_face, exic_contact_set_face_dofs, exic_contact_face_rule
   use testing, only: suite_t, check
   implicit none
   private

   public :: face_argument_tests, bad

contains

   !> Massless contact faces (method 3): a handle with a method-3 pair steps only with its face
   !> set and EXIC_CONTACT_STEP_FACE; bad face nodes, an unsymmetric or singular face block
   !> are refused with a message; with a face, the node falling on the rigid segment is placed
   !> on it by the face block in one step (gap at t(n+2) closed, no mass involved).
   subroutine face_argument_tests(s)
      type(suite_t), intent(inout) :: s
      real(wp) :: x0(2, 6), mass(6), x(2, 6), v(2, 6), a(2, 6), f(2, 6), r(2, 6), pp(1), rcon(6, 1)
      integer :: iseg(3, 1), isn(2, 1), h, ierr, nact, ncon, icon(4, 1)
      real(wp), parameter :: k = 100.0_wp
      x0 = reshape([0.0_wp, 0.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 1.0_wp, &
                    2.0_wp, -0.5_wp, -1.0_wp, -0.5_wp], [2, 6])
      mass = 1.0_wp
      pp = 0.0_wp
      iseg(:, 1) = [5, 6, 2]
      isn(:, 1) = [1, 1]
      ! node 1 over the rigid segment 5 -> 6 (0.5 below it), method 3
      call exic_contact_create_segments(6, x0, mass, 1, iseg, 1, isn, 1, [1, 2, 3, 1, 1, 1], pp, h, ierr)
      call check(s, ierr == 0 .and. h > 0, 'a pair of method 3 (massless contact faces) is accepted')
      if (ierr /= 0) return
      x = x0
      v = 0.0_wp
      v(2, 1) = -100.0_wp
      v(2, 4) = -100.0_wp
      a = 0.0_wp
      r = 0.0_wp
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 1.0e-2_wp, f, nact, ierr)
      call bad(s, ierr, h, 3, 'EXIC_CONTACT_SET_FACE', 'method 3: step before the face is set')
      call exic_contact_step_face(h, 6, x, v, a, r, 0.0_wp, 1.0e-2_wp, f, nact, ierr)
      call bad(s, ierr, h, 3, 'EXIC_CONTACT_SET_FACE', 'method 3: face step before the face is set')
      call exic_contact_set_face(h, 6, mass, 1, [2], [1, 2, 3], [3, 4], [k, k], ierr)
      call bad(s, ierr, h, 1, 'not a node of a contact surface', 'face node 2 off the contact surfaces')
      call exic_contact_set_face(h, 6, mass, 1, [5], [1, 2, 3], [9, 10], [k, k], ierr)
      call bad(s, ierr, h, 1, 'rigid', 'a rigid face node')
      call exic_contact_set_face(h, 6, mass, 1, [1], [1, 3, 4], [1, 2, 2], [k, 0.5_wp*k, k], ierr)
      call bad(s, ierr, h, 1, 'not symmetric', 'an unsymmetric face block')
      call exic_contact_set_face(h, 6, mass, 1, [1], [1, 2, 3], [1, 13], [k, k], ierr)
      call bad(s, ierr, h, 1, 'column 13', 'a column outside the dofs')
      call exic_contact_set_face(h, 6, mass, 1, [1], [1, 2, 3], [1, 2], [0.0_wp, k], ierr)
      call bad(s, ierr, h, 3, 'singular at node 1', 'a singular face block')
      ! node 1 tied to node 4 by springs k in x and y: K_FF = k I
      call exic_contact_set_face(h, 6, mass, 1, [1], [1, 3, 5], [1, 7, 2, 8], [k, -k, k, -k], ierr)
      call check(s, ierr == 0, 'a valid face is accepted', 'ierr '//itoa(ierr))
      if (ierr /= 0) return
      call exic_contact_step(h, 6, x, v, a, 0.0_wp, 1.0e-2_wp, f, nact, ierr)
      call bad(s, ierr, h, 3, 'EXIC_CONTACT_STEP_FACE', 'a handle with a face: plain step refused')
      ! node 4 falls by dt v = 1 over the step; the free solve moves the face node with it, 0.5
      ! below the segment; the face block places it on the segment (gap 0 at t(n+2)) with the
      ! static force k 0.5 of the springs
      call exic_contact_step_face(h, 6, x, v, a, r, 0.0_wp, 1.0e-2_wp, f, nact, ierr)
      call exic_contact_constraints(h, 1, ncon, icon, rcon, ierr)
      call check(s, ierr == 0 .and. nact == 1 .and. ncon == 1, 'the face step makes one constraint', &
                 'ierr '//itoa(ierr)//', active '//itoa(nact))
      if (ierr /= 0 .or. ncon /= 1) return
      call check(s, abs(rcon(6, 1)) < 1.0e-12_wp .and. abs(f(2, 1) - k*0.5_wp) < 1.0e-9_wp*k, &
                 'face step: the face node ends on the segment (gap at t(n+2) 0), held by K_FF times its '// &
                 'trial penetration', 'gap '//rtoa(rcon(6, 1))//', force '//rtoa(f(2, 1)))
      call exic_contact_free(h, ierr)
      call face_dofs_tests(s, x0, iseg, isn)
   end subroutine face_argument_tests

   !> EXIC_CONTACT_SET_FACE_DOFS (massless dofs per direction, doc/impact.md eq. I.3a, I.3b) and
   !> EXIC_CONTACT_FACE_RULE on the scene of face_argument_tests: the refusals, and node 1
   !> massless along y only (tied to node 4 by a spring k along y), falling 0.5 below the rigid
   !> segment: it is placed on the segment by the face block with the spring's static force k 0.5,
   !> and its x dof, which keeps its mass, keeps the host's predicted acceleration (the segment's
   !> normal is y: no correction along x).
   subroutine face_dofs_tests(s, x0, iseg, isn)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: x0(2, 6)
      integer, intent(in) :: iseg(3, 1), isn(2, 1)
      real(wp), parameter :: k = 100.0_wp
      real(wp) :: mass(2, 6), x(2, 6), v(2, 6), a(2, 6), f(2, 6), r(2, 6), pp(1), rcon(6, 1)
      integer :: h, ierr, nact, ncon, icon(4, 1), ifd(2, 6)
      pp = 0.0_wp
      mass = 1.0_wp
      call exic_contact_create_segments(6, x0, spread(1.0_wp, 1, 6), 1, iseg, 1, isn, 1, [1, 2, 3, 1, 1, 1], pp, h, ierr)
      if (ierr /= 0) return
      call exic_contact_face_rule(h, 5, ifd, ierr)
      call bad(s, ierr, h, 1, 'NNODE', 'face rule: NNODE differs from the handle''s')
      call exic_contact_face_rule(h, 6, ifd, ierr)
      call check(s, ierr == 0 .and. all(ifd == 0), 'face rule: a node set (no segments, no normal) gets no '// &
                 'massless dof', 'ierr '//itoa(ierr)//', massless dofs '//itoa(count(ifd == 1)))
      call exic_contact_set_face_dofs(h, 6, mass, 1, [1], reshape([0, 2], [2, 1]), [1, 1, 3], [2, 8], [k, -k], ierr)
      call bad(s, ierr, h, 1, 'IFDOF', 'a massless flag other than 0 or 1')
      call exic_contact_set_face_dofs(h, 6, mass, 1, [1], reshape([0, 0], [2, 1]), [1, 1, 3], [2, 8], [k, -k], ierr)
      call bad(s, ierr, h, 1, 'IFDOF', 'a face node without a massless dof')
      mass(1, 1) = 0.0_wp
      call exic_contact_set_face_dofs(h, 6, mass, 1, [1], reshape([0, 1], [2, 1]), [1, 1, 3], [2, 8], [k, -k], ierr)
      call bad(s, ierr, h, 1, 'along dof 1', 'no mass on the dof of a face node that keeps it')
      mass(1, 1) = 1.0_wp
      ! the row of the dof with mass (x) is empty: it is not read
      call exic_contact_set_face_dofs(h, 6, mass, 1, [1], reshape([0, 1], [2, 1]), [1, 1, 3], [2, 8], [k, -k], ierr)
      call check(s, ierr == 0, 'a face massless along y only is accepted', 'ierr '//itoa(ierr))
      if (ierr /= 0) return
      x = x0
      v = 0.0_wp
      v(2, 1) = -100.0_wp
      v(2, 4) = -100.0_wp
      a = 0.0_wp
      a(1, 1) = 7.0_wp
      r = 0.0_wp
      call exic_contact_step_face(h, 6, x, v, a, r, 0.0_wp, 1.0e-2_wp, f, nact, ierr)
      call exic_contact_constraints(h, 1, ncon, icon, rcon, ierr)
      call check(s, ierr == 0 .and. nact == 1 .and. ncon == 1, 'per direction: the face step makes one constraint', &
                 'ierr '//itoa(ierr)//', active '//itoa(nact))
      if (ierr /= 0 .or. ncon /= 1) return
      call check(s, abs(rcon(6, 1)) < 1.0e-12_wp .and. abs(f(2, 1) - k*0.5_wp) < 1.0e-9_wp*k .and. a(1, 1) == 7.0_wp, &
                 'per direction: the node ends on the segment with the spring''s force, its x dof keeps a~', &
                 'gap '//rtoa(rcon(6, 1))//', force '//rtoa(f(2, 1))//', a_x '//rtoa(a(1, 1)))
      call exic_contact_free(h, ierr)
   end subroutine face_dofs_tests

   !> One bad call: ierr /= 0 (= code when code > 0), h = 0 after a failed creation, and the
   !> message of handle `hq` names `key`.
   subroutine bad(s, ierr, hq, code, key, what)
      type(suite_t), intent(inout) :: s
      integer, intent(in) :: ierr, hq, code
      character(len=*), intent(in) :: key, what
      character(len=300) :: msg
      integer :: lmsg, ierr2
      call exic_contact_error_message(hq, msg, lmsg, ierr2)
      call check(s, ierr /= 0 .and. (code == 0 .or. ierr == code) .and. index(msg, key) > 0 .and. &
                 lmsg == len_trim(msg), 'bad argument: '//what//' -> ierr '//itoa(ierr), &
                 'message "'//msg(1:min(lmsg, 300))//'"')
   end subroutine bad

end module test_legacy_face
