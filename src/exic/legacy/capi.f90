!> The C twins of the legacy contact API (include/exic_contact.h, doc/api.md).
!>
!> Same calls, same argument order and meaning as the Fortran 77 entry points in api.f90,
!> under the names exic_c_contact_*: input scalars by value, outputs through pointers, arrays
!> as pointers to column-major storage (x[2*(i-1)] and x[2*(i-1)+1] hold node i), node and
!> surface numbers 1-based as in Fortran. External bind(C) procedures outside any module.

!> C twin of exic_contact_create_mesh.
subroutine exic_c_contact_create_mesh(nnode, x0, amass, nelem, ix, ibody, npair, ipair, ppair, ih, ierr) &
   bind(C, name='exic_c_contact_create_mesh')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_create_mesh
   implicit none
   integer(c_int), value :: nnode, nelem, npair
   real(c_double), intent(in) :: x0(2, nnode), amass(nnode)
   integer(c_int), intent(in) :: ix(4, nelem), ibody(nelem), ipair(6, npair)
   real(c_double), intent(in) :: ppair(npair)
   integer(c_int), intent(out) :: ih, ierr
   call problem_create_mesh('exic_c_contact_create_mesh', nnode, x0, amass, nelem, ix, ibody, npair, ipair, &
                            ppair, ih, ierr)
end subroutine exic_c_contact_create_mesh

!> C twin of exic_contact_create_segments.
subroutine exic_c_contact_create_segments(nnode, x0, amass, nseg, iseg, nsn, isn, npair, ipair, ppair, &
                                          ih, ierr) bind(C, name='exic_c_contact_create_segments')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_create_segments
   implicit none
   integer(c_int), value :: nnode, nseg, nsn, npair
   real(c_double), intent(in) :: x0(2, nnode), amass(nnode)
   integer(c_int), intent(in) :: iseg(3, nseg), isn(2, nsn), ipair(6, npair)
   real(c_double), intent(in) :: ppair(npair)
   integer(c_int), intent(out) :: ih, ierr
   call problem_create_segments('exic_c_contact_create_segments', nnode, x0, amass, nseg, iseg, nsn, isn, &
                                npair, ipair, ppair, ih, ierr)
end subroutine exic_c_contact_create_segments

!> C twin of exic_contact_set_fixed.
subroutine exic_c_contact_set_fixed(ih, nnode, ifix, ierr) bind(C, name='exic_c_contact_set_fixed')
   use, intrinsic :: iso_c_binding, only: c_int
   use exic_legacy_problem, only: problem_set_fixed
   implicit none
   integer(c_int), value :: ih, nnode
   integer(c_int), intent(in) :: ifix(2, nnode)
   integer(c_int), intent(out) :: ierr
   call problem_set_fixed('exic_c_contact_set_fixed', ih, nnode, ifix, ierr)
end subroutine exic_c_contact_set_fixed

!> C twin of exic_contact_set_pair.
subroutine exic_c_contact_set_pair(ih, ipair, iopt, pen, ierr) bind(C, name='exic_c_contact_set_pair')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_set_pair
   implicit none
   integer(c_int), value :: ih, ipair
   integer(c_int), intent(in) :: iopt(4)
   real(c_double), value :: pen
   integer(c_int), intent(out) :: ierr
   call problem_set_pair('exic_c_contact_set_pair', ih, ipair, iopt, pen, ierr)
end subroutine exic_c_contact_set_pair

!> C twin of exic_contact_set_option.
subroutine exic_c_contact_set_option(ih, iopt, ival, ierr) bind(C, name='exic_c_contact_set_option')
   use, intrinsic :: iso_c_binding, only: c_int
   use exic_legacy_problem, only: problem_set_option
   implicit none
   integer(c_int), value :: ih, iopt, ival
   integer(c_int), intent(out) :: ierr
   call problem_set_option('exic_c_contact_set_option', ih, iopt, ival, ierr)
end subroutine exic_c_contact_set_option

!> C twin of exic_contact_step.
subroutine exic_c_contact_step(ih, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr) &
   bind(C, name='exic_c_contact_step')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_step
   implicit none
   integer(c_int), value :: ih, nnode
   real(c_double), intent(in) :: x(2, nnode), v(2, nnode)
   real(c_double), intent(inout) :: a(2, nnode)
   real(c_double), value :: dtprev, dt
   real(c_double), intent(out) :: fcon(2, nnode)
   integer(c_int), intent(out) :: nactive, ierr
   call problem_step('exic_c_contact_step', ih, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
end subroutine exic_c_contact_step

!> C twin of exic_contact_pair_results.
subroutine exic_c_contact_pair_results(ih, ipair, res, ierr) bind(C, name='exic_c_contact_pair_results')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_pair_results
   implicit none
   integer(c_int), value :: ih, ipair
   real(c_double), intent(out) :: res(6)
   integer(c_int), intent(out) :: ierr
   call problem_pair_results('exic_c_contact_pair_results', ih, ipair, res, ierr)
end subroutine exic_c_contact_pair_results

!> C twin of exic_contact_set_friction.
subroutine exic_c_contact_set_friction(ih, ipair, amus, amud, decay, ierr) &
   bind(C, name='exic_c_contact_set_friction')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_set_friction
   implicit none
   integer(c_int), value :: ih, ipair
   real(c_double), value :: amus, amud, decay
   integer(c_int), intent(out) :: ierr
   call problem_set_friction('exic_c_contact_set_friction', ih, ipair, amus, amud, decay, ierr)
end subroutine exic_c_contact_set_friction

!> C twin of exic_contact_pair_friction.
subroutine exic_c_contact_pair_friction(ih, ipair, res, ierr) bind(C, name='exic_c_contact_pair_friction')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_pair_friction
   implicit none
   integer(c_int), value :: ih, ipair
   real(c_double), intent(out) :: res(4)
   integer(c_int), intent(out) :: ierr
   call problem_pair_friction('exic_c_contact_pair_friction', ih, ipair, res, ierr)
end subroutine exic_c_contact_pair_friction

!> C twin of exic_contact_ncon.
subroutine exic_c_contact_ncon(ih, ncon, ierr) bind(C, name='exic_c_contact_ncon')
   use, intrinsic :: iso_c_binding, only: c_int
   use exic_legacy_problem, only: problem_ncon
   implicit none
   integer(c_int), value :: ih
   integer(c_int), intent(out) :: ncon, ierr
   call problem_ncon('exic_c_contact_ncon', ih, ncon, ierr)
end subroutine exic_c_contact_ncon

!> C twin of exic_contact_constraints.
subroutine exic_c_contact_constraints(ih, mcon, ncon, icon, rcon, ierr) bind(C, name='exic_c_contact_constraints')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_constraints
   implicit none
   integer(c_int), value :: ih, mcon
   integer(c_int), intent(out) :: ncon
   integer(c_int), intent(out) :: icon(4, mcon)
   real(c_double), intent(out) :: rcon(6, mcon)
   integer(c_int), intent(out) :: ierr
   call problem_constraints('exic_c_contact_constraints', ih, mcon, ncon, icon, rcon, ierr)
end subroutine exic_c_contact_constraints

!> C twin of exic_contact_work.
subroutine exic_c_contact_work(ih, wcon, penmax, ierr) bind(C, name='exic_c_contact_work')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_work
   implicit none
   integer(c_int), value :: ih
   real(c_double), intent(out) :: wcon, penmax
   integer(c_int), intent(out) :: ierr
   call problem_work('exic_c_contact_work', ih, wcon, penmax, ierr)
end subroutine exic_c_contact_work

!> C twin of exic_contact_free.
subroutine exic_c_contact_free(ih, ierr) bind(C, name='exic_c_contact_free')
   use, intrinsic :: iso_c_binding, only: c_int
   use exic_legacy_problem, only: problem_free
   implicit none
   integer(c_int), value :: ih
   integer(c_int), intent(out) :: ierr
   call problem_free('exic_c_contact_free', ih, ierr)
end subroutine exic_c_contact_free

!> C twin of exic_contact_error_message: msg receives at most msglen - 1 characters and a
!> terminating NUL; *lmsg is the full length of the message.
subroutine exic_c_contact_error_message(ih, msg, msglen, lmsg, ierr) bind(C, name='exic_c_contact_error_message')
   use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
   use exic_legacy_problem, only: problem_message
   implicit none
   integer(c_int), value :: ih, msglen
   character(kind=c_char), intent(out) :: msg(*)
   integer(c_int), intent(out) :: lmsg, ierr
   character(len=4096) :: buf
   integer :: k, n
   call problem_message(ih, buf, lmsg)
   ierr = 0
   if (msglen < 1) return
   n = min(msglen - 1, lmsg, len(buf))
   do k = 1, n
      msg(k) = buf(k:k)
   end do
   msg(n + 1) = c_null_char
end subroutine exic_c_contact_error_message

!> C twin of exic_contact_set_face.
subroutine exic_c_contact_set_face(ih, nnode, amass, nf, iface, irp, ici, val, ierr) &
   bind(C, name='exic_c_contact_set_face')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_set_face
   implicit none
   integer(c_int), value :: ih, nnode, nf
   real(c_double), intent(in) :: amass(nnode)
   integer(c_int), intent(in) :: iface(nf), irp(2*nf + 1), ici(*)
   real(c_double), intent(in) :: val(*)
   integer(c_int), intent(out) :: ierr
   call problem_set_face('exic_c_contact_set_face', ih, nnode, amass, nf, iface, irp, ici, val, ierr)
end subroutine exic_c_contact_set_face

!> C twin of exic_contact_set_face_dofs.
subroutine exic_c_contact_set_face_dofs(ih, nnode, amass, nf, iface, ifdof, irp, ici, val, ierr) &
   bind(C, name='exic_c_contact_set_face_dofs')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_set_face_dofs
   implicit none
   integer(c_int), value :: ih, nnode, nf
   real(c_double), intent(in) :: amass(2, nnode)
   integer(c_int), intent(in) :: iface(nf), ifdof(2, nf), irp(2*nf + 1), ici(*)
   real(c_double), intent(in) :: val(*)
   integer(c_int), intent(out) :: ierr
   call problem_set_face_dofs('exic_c_contact_set_face_dofs', ih, nnode, amass, nf, iface, ifdof, irp, ici, val, ierr)
end subroutine exic_c_contact_set_face_dofs

!> C twin of exic_contact_face_rule.
subroutine exic_c_contact_face_rule(ih, nnode, ifdof, ierr) bind(C, name='exic_c_contact_face_rule')
   use, intrinsic :: iso_c_binding, only: c_int
   use exic_legacy_problem, only: problem_face_rule
   implicit none
   integer(c_int), value :: ih, nnode
   integer(c_int), intent(out) :: ifdof(2, nnode)
   integer(c_int), intent(out) :: ierr
   call problem_face_rule('exic_c_contact_face_rule', ih, nnode, ifdof, ierr)
end subroutine exic_c_contact_face_rule

!> C twin of exic_contact_step_face.
subroutine exic_c_contact_step_face(ih, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr) &
   bind(C, name='exic_c_contact_step_face')
   use, intrinsic :: iso_c_binding, only: c_int, c_double
   use exic_legacy_problem, only: problem_step_face
   implicit none
   integer(c_int), value :: ih, nnode
   real(c_double), intent(in) :: x(2, nnode), v(2, nnode), r(2, nnode)
   real(c_double), intent(inout) :: a(2, nnode)
   real(c_double), value :: dtprev, dt
   real(c_double), intent(out) :: fcon(2, nnode)
   integer(c_int), intent(out) :: nactive, ierr
   call problem_step_face('exic_c_contact_step_face', ih, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
end subroutine exic_c_contact_step_face
