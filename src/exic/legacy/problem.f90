!> The work behind the legacy API: contact problems built from a host's plain arrays.
!>
!> A host hands over its node count, reference coordinates and lumped masses, and either its
!> element connectivity with a body number per element (each body's free boundary becomes a
!> contact surface, as REGIon surfaces do in a deck) or its own segments and slave node sets.
!> From these a contact_spec_t (as a deck's CONTact block) is built and the ordinary contact_t
!> of the deck path does the work on the host's arrays, unchanged: contact_t%init once and
!> contact_t%correct once per step (seed sections 3-6; eq. 4.4-4.7).
!>
!> Every procedure here takes explicit-shape arrays sized by earlier arguments, default
!> integers and real(wp) = double precision, and returns an integer `ierr` (codes in
!> exic_legacy_registry); a failure also stores a message retrievable with problem_message.
!> `who` is the name of the calling entry point, used in messages.
!>
!> Per step the host's arrays go to contact_t%correct as they are; the API itself touches
!> only the nodes of the contact surfaces (for its queries) and checks the positions, so its
!> cost over a native call is small (doc/performance.md, "Legacy API overhead").
!>
!> The entry points are separate module procedures, one submodule per concern:
!> problem_create.f90 (creation), problem_options.f90 (fixities, pair options, friction, massless
!> faces), problem_step.f90 (the step) and problem_queries.f90 (results, constraints, messages);
!> this module keeps their interfaces; what several of them share (rebuilding the contact
!> object, the argument checks) is in problem_shared.f90.
module exic_legacy_problem
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use, intrinsic :: iso_fortran_env, only: int64
   use exic_base_kinds, only: wp
   use exic_base_strings, only: itoa, rtoa
   use exic_mesh_smoothing, only: quad_area
   use exic_base_error, only: error_t
   use exic_contact_contact, only: contact_t
   use exic_contact_spec, only: SURF_REGION, SURF_FACETS, SURF_NODES, PAIR_NTOS, PAIR_SYMMETRIC, &
                                PAIR_SELF, METHOD_LAGRANGE, METHOD_PENALTY, DETECT_SWEPT, DETECT_STATIC
   use exic_legacy_face, only: check_face, face_step_ok, face_motion, face_gap
   use exic_legacy_registry, only: problem_t, registry_add, registry_get, registry_free, set_error, &
                                   last_message, IERR_OK, IERR_ARGUMENT, IERR_HANDLE, IERR_SETUP, &
                                   IERR_SOLVE, VEL_FULL_STEP, VEL_HALF_STEP
   use exic_legacy_problem_shared, only: pair_table, apply_pair_options, rebuild, rigid_nodes, &
                                         inverse_masses, lookup, counts_ok, nodes_ok, pairs_ok, fail
   implicit none
   private

   public :: problem_create_mesh, problem_create_segments, problem_set_fixed, problem_set_pair
   public :: problem_set_option, problem_step, problem_pair_results, problem_ncon
   public :: problem_constraints, problem_work, problem_free, problem_message
   public :: problem_set_friction, problem_pair_friction, problem_set_face, problem_step_face
   public :: problem_set_face_dofs, problem_face_rule

   !> Option codes of problem_set_option.
   integer, parameter, public :: OPT_VELOCITY_FORM = 1


   interface
      !> A problem from connectivity: ix(4, nelem) counter-clockwise nodes, ibody(nelem) >= 1.
      !> ipair(6, npair): slave body, master body, method, detection, passes, rigid master;
      !> ppair(npair): penalty stiffness (method 2). On success h > 0, else h = 0.
      module subroutine problem_create_mesh(who, nnode, x0, mass, nelem, ix, ibody, npair, ipair, &
                                            ppair, h, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: nnode, nelem, npair
         real(wp), intent(in) :: x0(2, nnode), mass(nnode)
         integer, intent(in) :: ix(4, nelem), ibody(nelem), ipair(6, npair)
         real(wp), intent(in) :: ppair(npair)
         integer, intent(out) :: h, ierr
      end subroutine problem_create_mesh

      !> A problem from segments and slave node sets. iseg(3, nseg): node 1, node 2 (body on the
      !> left of 1 -> 2), surface number >= 1; isn(2, nsn): node, surface number of a slave node
      !> set (a surface without segments). ipair as for problem_create_mesh with surface numbers.
      module subroutine problem_create_segments(who, nnode, x0, mass, nseg, iseg, nsn, isn, npair, &
                                                ipair, ppair, h, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: nnode, nseg, nsn, npair
         real(wp), intent(in) :: x0(2, nnode), mass(nnode)
         integer, intent(in) :: iseg(3, nseg), isn(2, nsn), ipair(6, npair)
         real(wp), intent(in) :: ppair(npair)
         integer, intent(out) :: h, ierr
      end subroutine problem_create_segments

      !> ifix(2, nnode): non-zero marks a dof the host prescribes (the corrector leaves it alone).
      module subroutine problem_set_fixed(who, h, nnode, ifix, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode
         integer, intent(in) :: ifix(2, nnode)
         integer, intent(out) :: ierr
      end subroutine problem_set_fixed

      !> New options iopt(4) = method, detection, passes, rigid master and penalty stiffness of
      !> pair ipair; the surfaces and passes are rebuilt at the current positions.
      module subroutine problem_set_pair(who, h, ipair, iopt, pen, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, ipair
         integer, intent(in) :: iopt(4)
         real(wp), intent(in) :: pen
         integer, intent(out) :: ierr
      end subroutine problem_set_pair

      !> Coulomb friction of pair ipair (doc/friction.md, eq. F12): static coefficient amus, dynamic
      !> amud <= amus, decay with slip speed (0: amus at rest, amud sliding); amus = 0 removes it.
      !> The contact object is rebuilt at the current positions, as for a change of pair options.
      module subroutine problem_set_friction(who, h, ipair, amus, amud, decay, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, ipair
         real(wp), intent(in) :: amus, amud, decay
         integer, intent(out) :: ierr
      end subroutine problem_set_friction

      !> Handle options: OPT_VELOCITY_FORM = 1 (v~(n+1), default) or 2 (v(n+1/2)).
      module subroutine problem_set_option(who, h, iopt, ival, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, iopt, ival
         integer, intent(out) :: ierr
      end subroutine problem_set_option

      !> The massless contact faces of method-3 pairs (doc/impact.md, section 3; doc/api.md):
      !> mass(nnode) the host's lumped masses after it moved the face nodes' mass to their
      !> elements' other nodes (eq. I.3; > 0 off the face, ignored on it), iface(nf) the face
      !> nodes (surface nodes, neither rigid nor prescribed), irp(2 nf + 1), ici, val the rows of
      !> the host's initial stiffness for the face dofs in 1-based CSR (row 2 (k-1) + d for dof d of
      !> iface(k), columns the global dofs 2 (i-1) + d). The face block must be symmetric; it is
      !> factorized (SuiteSparse LDL) when the contact object is rebuilt here.
      module subroutine problem_set_face(who, h, nnode, mass, nf, iface, irp, ici, val, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode, nf
         real(wp), intent(in) :: mass(nnode)
         integer, intent(in) :: iface(max(nf, 0)), irp(2*max(nf, 0) + 1)
         integer, intent(in) :: ici(*)
         real(wp), intent(in) :: val(*)
         integer, intent(out) :: ierr
      end subroutine problem_set_face

      !> problem_set_face with the massless dofs per direction: mass(2, nnode) per dof,
      !> ifdof(2, nf) 1 on the massless dofs of iface(k) (doc/impact.md, eq. I.3a, I.3b).
      module subroutine problem_set_face_dofs(who, h, nnode, mass, nf, iface, ifdof, irp, ici, val, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode, nf
         real(wp), intent(in) :: mass(2, nnode)
         integer, intent(in) :: iface(max(nf, 0)), ifdof(2, max(nf, 0)), irp(2*max(nf, 0) + 1)
         integer, intent(in) :: ici(*)
         real(wp), intent(in) :: val(*)
         integer, intent(out) :: ierr
      end subroutine problem_set_face_dofs

      !> ifdof(2, nnode): 1 on the dofs the deck's rule makes massless (doc/impact.md, section
      !> 3.1) at the reference positions.
      module subroutine problem_face_rule(who, h, nnode, ifdof, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode
         integer, intent(out) :: ifdof(2, nnode)
         integer, intent(out) :: ierr
      end subroutine problem_face_rule

      !> One contact step: x = x(n+1), v = v~(n+1) (or v(n+1/2), option 1), a = a~(n+1) on entry
      !> and a(n+1) on exit, dtprev = dt(n) (0 at t = 0), dt = dt(n+1); fcon = nodal contact
      !> forces, nactive = constraints carrying force (eq. 4.4-4.7). The host's arrays go to
      !> contact_t%correct as they are: nothing of size nnode is copied.
      module subroutine problem_step(who, h, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode
         real(wp), intent(in) :: x(2, nnode), v(2, nnode)
         real(wp), intent(inout) :: a(2, nnode)
         real(wp), intent(in) :: dtprev, dt
         real(wp), intent(out) :: fcon(2, nnode)
         integer, intent(out) :: nactive, ierr
      end subroutine problem_step

      !> The step of a handle with massless contact faces (method 3, doc/impact.md section 3): r =
      !> f_ext - f_int at t(n+1) on the face dofs (eq. I.5); a holds there on exit eq. I.7's.
      module subroutine problem_step_face(who, h, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, nnode
         real(wp), intent(in) :: x(2, nnode), v(2, nnode), r(2, nnode)
         real(wp), intent(inout) :: a(2, nnode)
         real(wp), intent(in) :: dtprev, dt
         real(wp), intent(out) :: fcon(2, nnode)
         integer, intent(out) :: nactive, ierr
      end subroutine problem_step_face

      !> res(6) of pair ipair in the last step: normal force (sum of multipliers), force x, y on
      !> the slave side (normal and friction), active constraints, largest penetration at t(n+1),
      !> largest multiplier.
      module subroutine problem_pair_results(who, h, ipair, res, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, ipair
         real(wp), intent(out) :: res(6)
         integer, intent(out) :: ierr
      end subroutine problem_pair_results

      !> res(4) of pair ipair: friction force (sum of |q| over its constraints) in the last step,
      !> constraints that stick and that slip in it, frictional dissipation since the friction was
      !> set (doc/friction.md, section 7). The friction forces are also in the pair results' force
      !> x, y and in the nodal contact forces of the step.
      module subroutine problem_pair_friction(who, h, ipair, res, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, ipair
         real(wp), intent(out) :: res(4)
         integer, intent(out) :: ierr
      end subroutine problem_pair_friction

      !> Number of candidate (Lagrange) constraints of the last step.
      module subroutine problem_ncon(who, h, ncon, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h
         integer, intent(out) :: ncon, ierr
      end subroutine problem_ncon

      !> The candidate constraints of the last step: icon(4, :) = slave, master 1, master 2, pair;
      !> rcon(6, :) = multiplier p (>= 0, compressive), alpha, normal x, y, gap at t(n+1), gap at
      !> t(n+2) after the correction (eq. 3.19 along the frozen normal). mcon >= ncon is required.
      module subroutine problem_constraints(who, h, mcon, ncon, icon, rcon, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h, mcon
         integer, intent(out) :: ncon
         integer, intent(out) :: icon(4, mcon)
         real(wp), intent(out) :: rcon(6, mcon)
         integer, intent(out) :: ierr
      end subroutine problem_constraints

      !> Work of the contact forces since creation and the largest penetration at t(n+1) seen.
      module subroutine problem_work(who, h, wcon, penmax, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h
         real(wp), intent(out) :: wcon, penmax
         integer, intent(out) :: ierr
      end subroutine problem_work

      !> Release handle h.
      module subroutine problem_free(who, h, ierr)
         character(len=*), intent(in) :: who
         integer, intent(in) :: h
         integer, intent(out) :: ierr
      end subroutine problem_free

      !> The message of the last failed call on handle h (of any call when h names no live
      !> problem), blank-padded or cut to len(msg); lmsg is its full length.
      module subroutine problem_message(h, msg, lmsg)
         integer, intent(in) :: h
         character(len=*), intent(out) :: msg
         integer, intent(out) :: lmsg
      end subroutine problem_message
   end interface

end module exic_legacy_problem
