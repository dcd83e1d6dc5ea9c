!> The Fortran 77 entry points of the legacy contact API (doc/api.md).
!>
!> External procedures outside any module, so that a fixed-form host calls them with no
!> module and links the plain symbols (gfortran: exic_contact_step_ and so on). Arguments are
!> default INTEGER and DOUBLE PRECISION, arrays have explicit shapes sized by earlier
!> arguments, IERR is last (0: success; 1 bad argument, 2 unknown handle, 3 set-up failure,
!> 4 corrector failure). After a failure EXIC_CONTACT_ERROR_MESSAGE returns the reason.
!> Each entry point only forwards to exic_legacy_problem.

!> Create a contact problem from element connectivity: one surface per body (its free
!> boundary edges), pairs IPAIR(6, NPAIR) = slave body, master body, method (1 Lagrange,
!> 2 penalty), detection (1 swept, 2 static), passes (1 one pass with its corner pass, 2 two passes), rigid
!> master (0, 1); PPAIR = penalty stiffness. Method 3: Lagrange with massless contact faces. Returns the handle IH (0 on failure).
subroutine exic_contact_create_mesh(nnode, x0, amass, nelem, ix, ibody, npair, ipair, ppair, ih, ierr)
   use exic_legacy_problem, only: problem_create_mesh
   implicit none
   integer, intent(in) :: nnode, nelem, npair
   double precision, intent(in) :: x0(2, nnode), amass(nnode)
   integer, intent(in) :: ix(4, nelem), ibody(nelem), ipair(6, npair)
   double precision, intent(in) :: ppair(npair)
   integer, intent(out) :: ih, ierr
   call problem_create_mesh('EXIC_CONTACT_CREATE_MESH', nnode, x0, amass, nelem, ix, ibody, npair, &
                            ipair, ppair, ih, ierr)
end subroutine exic_contact_create_mesh

!> Create a contact problem from segments ISEG(3, NSEG) = node 1, node 2 (body on the left),
!> surface, and slave node sets ISN(2, NSN) = node, surface; pairs name surfaces.
subroutine exic_contact_create_segments(nnode, x0, amass, nseg, iseg, nsn, isn, npair, ipair, ppair, &
                                        ih, ierr)
   use exic_legacy_problem, only: problem_create_segments
   implicit none
   integer, intent(in) :: nnode, nseg, nsn, npair
   double precision, intent(in) :: x0(2, nnode), amass(nnode)
   integer, intent(in) :: iseg(3, nseg), isn(2, nsn), ipair(6, npair)
   double precision, intent(in) :: ppair(npair)
   integer, intent(out) :: ih, ierr
   call problem_create_segments('EXIC_CONTACT_CREATE_SEGMENTS', nnode, x0, amass, nseg, iseg, &
                                nsn, isn, npair, ipair, ppair, ih, ierr)
end subroutine exic_contact_create_segments

!> Mark prescribed dofs: IFIX(2, NNODE) non-zero = the host prescribes that dof.
subroutine exic_contact_set_fixed(ih, nnode, ifix, ierr)
   use exic_legacy_problem, only: problem_set_fixed
   implicit none
   integer, intent(in) :: ih, nnode
   integer, intent(in) :: ifix(2, nnode)
   integer, intent(out) :: ierr
   call problem_set_fixed('EXIC_CONTACT_SET_FIXED', ih, nnode, ifix, ierr)
end subroutine exic_contact_set_fixed

!> New options of pair IPAIR: IOPT(4) = method, detection, passes, rigid master; PEN penalty.
subroutine exic_contact_set_pair(ih, ipair, iopt, pen, ierr)
   use exic_legacy_problem, only: problem_set_pair
   implicit none
   integer, intent(in) :: ih, ipair
   integer, intent(in) :: iopt(4)
   double precision, intent(in) :: pen
   integer, intent(out) :: ierr
   call problem_set_pair('EXIC_CONTACT_SET_PAIR', ih, ipair, iopt, pen, ierr)
end subroutine exic_contact_set_pair

!> Handle option IOPT = 1: velocity form IVAL = 1 (v~(n+1), default) or 2 (v(n+1/2)).
subroutine exic_contact_set_option(ih, iopt, ival, ierr)
   use exic_legacy_problem, only: problem_set_option
   implicit none
   integer, intent(in) :: ih, iopt, ival
   integer, intent(out) :: ierr
   call problem_set_option('EXIC_CONTACT_SET_OPTION', ih, iopt, ival, ierr)
end subroutine exic_contact_set_option

!> One step: X = x(n+1), V = predictor velocity, A = predicted (in) and corrected (out)
!> accelerations, DTPREV = dt(n) (0 at the first call), DT = dt(n+1); FCON nodal contact
!> forces, NACTIVE constraints carrying force.
subroutine exic_contact_step(ih, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
   use exic_legacy_problem, only: problem_step
   implicit none
   integer, intent(in) :: ih, nnode
   double precision, intent(in) :: x(2, nnode), v(2, nnode)
   double precision, intent(inout) :: a(2, nnode)
   double precision, intent(in) :: dtprev, dt
   double precision, intent(out) :: fcon(2, nnode)
   integer, intent(out) :: nactive, ierr
   call problem_step('EXIC_CONTACT_STEP', ih, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
end subroutine exic_contact_step

!> Massless contact faces of the method-3 pairs (doc/impact.md section 3, doc/api.md): AMASS
!> the host's lumped masses after moving the face nodes' mass (eq. I.3), IFACE(NF) the face
!> nodes, IRP(2 NF + 1), ICI, VAL the rows of the initial stiffness for the face dofs (CSR).
subroutine exic_contact_set_face(ih, nnode, amass, nf, iface, irp, ici, val, ierr)
   use exic_legacy_problem, only: problem_set_face
   implicit none
   integer, intent(in) :: ih, nnode, nf
   double precision, intent(in) :: amass(nnode)
   integer, intent(in) :: iface(nf), irp(2*nf + 1), ici(*)
   double precision, intent(in) :: val(*)
   integer, intent(out) :: ierr
   call problem_set_face('EXIC_CONTACT_SET_FACE', ih, nnode, amass, nf, iface, irp, ici, val, ierr)
end subroutine exic_contact_set_face

!> EXIC_CONTACT_SET_FACE with the massless dofs per direction (doc/impact.md eq. I.3a, I.3b):
!> AMASS(2, NNODE) the masses per dof after the transfer of eq. I.3 per direction, IFDOF(2, NF)
!> 1 where dof d of IFACE(K) is massless, 0 where it keeps its mass.
subroutine exic_contact_set_face_dofs(ih, nnode, amass, nf, iface, ifdof, irp, ici, val, ierr)
   use exic_legacy_problem, only: problem_set_face_dofs
   implicit none
   integer, intent(in) :: ih, nnode, nf
   double precision, intent(in) :: amass(2, nnode)
   integer, intent(in) :: iface(nf), ifdof(2, nf), irp(2*nf + 1), ici(*)
   double precision, intent(in) :: val(*)
   integer, intent(out) :: ierr
   call problem_set_face_dofs('EXIC_CONTACT_SET_FACE_DOFS', ih, nnode, amass, nf, iface, ifdof, irp, ici, val, ierr)
end subroutine exic_contact_set_face_dofs

!> IFDOF(2, NNODE): 1 on the dofs that the rule of decks (doc/impact.md section 3.1, eq. I.3a,
!> I.3b) makes massless on the surfaces of the method-3 pairs, at the reference positions.
subroutine exic_contact_face_rule(ih, nnode, ifdof, ierr)
   use exic_legacy_problem, only: problem_face_rule
   implicit none
   integer, intent(in) :: ih, nnode
   integer, intent(out) :: ifdof(2, nnode)
   integer, intent(out) :: ierr
   call problem_face_rule('EXIC_CONTACT_FACE_RULE', ih, nnode, ifdof, ierr)
end subroutine exic_contact_face_rule

!> EXIC_CONTACT_STEP of a handle with massless faces: R = f_ext - f_int at t(n+1) (read on the
!> face dofs); on return A holds on the face dofs the acceleration that places them (eq. I.7).
subroutine exic_contact_step_face(ih, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
   use exic_legacy_problem, only: problem_step_face
   implicit none
   integer, intent(in) :: ih, nnode
   double precision, intent(in) :: x(2, nnode), v(2, nnode), r(2, nnode)
   double precision, intent(inout) :: a(2, nnode)
   double precision, intent(in) :: dtprev, dt
   double precision, intent(out) :: fcon(2, nnode)
   integer, intent(out) :: nactive, ierr
   call problem_step_face('EXIC_CONTACT_STEP_FACE', ih, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
end subroutine exic_contact_step_face

!> RES(6) of pair IPAIR in the last step: normal force, force x, y on the slave side (normal
!> and friction), active constraints, largest penetration at t(n+1), largest multiplier.
subroutine exic_contact_pair_results(ih, ipair, res, ierr)
   use exic_legacy_problem, only: problem_pair_results
   implicit none
   integer, intent(in) :: ih, ipair
   double precision, intent(out) :: res(6)
   integer, intent(out) :: ierr
   call problem_pair_results('EXIC_CONTACT_PAIR_RESULTS', ih, ipair, res, ierr)
end subroutine exic_contact_pair_results

!> Coulomb friction of pair IPAIR (doc/friction.md): static coefficient AMUS, dynamic AMUD
!> (0 <= AMUD <= AMUS), DECAY of the coefficient with slip speed (0: AMUS at rest, AMUD when
!> sliding; else AMUD + (AMUS - AMUD) exp(-DECAY v)). AMUS = 0: frictionless.
subroutine exic_contact_set_friction(ih, ipair, amus, amud, decay, ierr)
   use exic_legacy_problem, only: problem_set_friction
   implicit none
   integer, intent(in) :: ih, ipair
   double precision, intent(in) :: amus, amud, decay
   integer, intent(out) :: ierr
   call problem_set_friction('EXIC_CONTACT_SET_FRICTION', ih, ipair, amus, amud, decay, ierr)
end subroutine exic_contact_set_friction

!> RES(4) of pair IPAIR: friction force (sum of the tangential multipliers' sizes) in the last
!> step, constraints that stick and that slip in it, frictional dissipation so far. The
!> friction forces are also in FCON and in EXIC_CONTACT_PAIR_RESULTS' force x, y.
subroutine exic_contact_pair_friction(ih, ipair, res, ierr)
   use exic_legacy_problem, only: problem_pair_friction
   implicit none
   integer, intent(in) :: ih, ipair
   double precision, intent(out) :: res(4)
   integer, intent(out) :: ierr
   call problem_pair_friction('EXIC_CONTACT_PAIR_FRICTION', ih, ipair, res, ierr)
end subroutine exic_contact_pair_friction

!> NCON: number of candidate constraints of the last step.
subroutine exic_contact_ncon(ih, ncon, ierr)
   use exic_legacy_problem, only: problem_ncon
   implicit none
   integer, intent(in) :: ih
   integer, intent(out) :: ncon, ierr
   call problem_ncon('EXIC_CONTACT_NCON', ih, ncon, ierr)
end subroutine exic_contact_ncon

!> The constraints of the last step: ICON(4, MCON) = slave, master 1, master 2, pair;
!> RCON(6, MCON) = multiplier, alpha, normal x, y, gap at t(n+1), corrected gap at t(n+2).
subroutine exic_contact_constraints(ih, mcon, ncon, icon, rcon, ierr)
   use exic_legacy_problem, only: problem_constraints
   implicit none
   integer, intent(in) :: ih, mcon
   integer, intent(out) :: ncon
   integer, intent(out) :: icon(4, mcon)
   double precision, intent(out) :: rcon(6, mcon)
   integer, intent(out) :: ierr
   call problem_constraints('EXIC_CONTACT_CONSTRAINTS', ih, mcon, ncon, icon, rcon, ierr)
end subroutine exic_contact_constraints

!> WCON: work of the contact forces since creation; PENMAX: largest penetration seen.
subroutine exic_contact_work(ih, wcon, penmax, ierr)
   use exic_legacy_problem, only: problem_work
   implicit none
   integer, intent(in) :: ih
   double precision, intent(out) :: wcon, penmax
   integer, intent(out) :: ierr
   call problem_work('EXIC_CONTACT_WORK', ih, wcon, penmax, ierr)
end subroutine exic_contact_work

!> Release handle IH.
subroutine exic_contact_free(ih, ierr)
   use exic_legacy_problem, only: problem_free
   implicit none
   integer, intent(in) :: ih
   integer, intent(out) :: ierr
   call problem_free('EXIC_CONTACT_FREE', ih, ierr)
end subroutine exic_contact_free

!> MSG: the message of the last failed call on IH (of any call when IH names no live
!> problem, e.g. IH = 0 after a failed creation); LMSG its full length; IERR = 0.
subroutine exic_contact_error_message(ih, msg, lmsg, ierr)
   use exic_legacy_problem, only: problem_message
   implicit none
   integer, intent(in) :: ih
   character(len=*), intent(out) :: msg
   integer, intent(out) :: lmsg, ierr
   call problem_message(ih, msg, lmsg)
   ierr = 0
end subroutine exic_contact_error_message
