!> Explicit interfaces of the legacy API's Fortran 77 entry points (api.f90), for modern
!> Fortran callers that want their calls checked. Hosts need not use it: the entry points
!> are external procedures callable with no module at all (doc/api.md).
module exic_legacy_interfaces
   implicit none
   private

   public :: exic_contact_create_mesh, exic_contact_create_segments, exic_contact_set_fixed
   public :: exic_contact_set_pair, exic_contact_set_option, exic_contact_step
   public :: exic_contact_pair_results, exic_contact_ncon, exic_contact_constraints
   public :: exic_contact_work, exic_contact_free, exic_contact_error_message
   public :: exic_contact_set_friction, exic_contact_pair_friction
   public :: exic_contact_set_face, exic_contact_step_face, exic_contact_set_face_dofs, exic_contact_face_rule

   interface
      !> See api.f90 and doc/api.md.
      subroutine exic_contact_create_mesh(nnode, x0, amass, nelem, ix, ibody, npair, ipair, ppair, ih, ierr)
         implicit none
         integer, intent(in) :: nnode, nelem, npair
         double precision, intent(in) :: x0(2, nnode), amass(nnode)
         integer, intent(in) :: ix(4, nelem), ibody(nelem), ipair(6, npair)
         double precision, intent(in) :: ppair(npair)
         integer, intent(out) :: ih, ierr
      end subroutine exic_contact_create_mesh

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_create_segments(nnode, x0, amass, nseg, iseg, nsn, isn, npair, ipair, ppair, &
                                              ih, ierr)
         implicit none
         integer, intent(in) :: nnode, nseg, nsn, npair
         double precision, intent(in) :: x0(2, nnode), amass(nnode)
         integer, intent(in) :: iseg(3, nseg), isn(2, nsn), ipair(6, npair)
         double precision, intent(in) :: ppair(npair)
         integer, intent(out) :: ih, ierr
      end subroutine exic_contact_create_segments

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_fixed(ih, nnode, ifix, ierr)
         implicit none
         integer, intent(in) :: ih, nnode
         integer, intent(in) :: ifix(2, nnode)
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_fixed

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_pair(ih, ipair, iopt, pen, ierr)
         implicit none
         integer, intent(in) :: ih, ipair
         integer, intent(in) :: iopt(4)
         double precision, intent(in) :: pen
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_pair

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_option(ih, iopt, ival, ierr)
         implicit none
         integer, intent(in) :: ih, iopt, ival
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_option

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_step(ih, nnode, x, v, a, dtprev, dt, fcon, nactive, ierr)
         implicit none
         integer, intent(in) :: ih, nnode
         double precision, intent(in) :: x(2, nnode), v(2, nnode)
         double precision, intent(inout) :: a(2, nnode)
         double precision, intent(in) :: dtprev, dt
         double precision, intent(out) :: fcon(2, nnode)
         integer, intent(out) :: nactive, ierr
      end subroutine exic_contact_step

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_face(ih, nnode, amass, nf, iface, irp, ici, val, ierr)
         implicit none
         integer, intent(in) :: ih, nnode, nf
         double precision, intent(in) :: amass(nnode)
         integer, intent(in) :: iface(nf), irp(2*nf + 1), ici(*)
         double precision, intent(in) :: val(*)
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_face

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_face_dofs(ih, nnode, amass, nf, iface, ifdof, irp, ici, val, ierr)
         implicit none
         integer, intent(in) :: ih, nnode, nf
         double precision, intent(in) :: amass(2, nnode)
         integer, intent(in) :: iface(nf), ifdof(2, nf), irp(2*nf + 1), ici(*)
         double precision, intent(in) :: val(*)
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_face_dofs

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_face_rule(ih, nnode, ifdof, ierr)
         implicit none
         integer, intent(in) :: ih, nnode
         integer, intent(out) :: ifdof(2, nnode)
         integer, intent(out) :: ierr
      end subroutine exic_contact_face_rule

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_step_face(ih, nnode, x, v, a, r, dtprev, dt, fcon, nactive, ierr)
         implicit none
         integer, intent(in) :: ih, nnode
         double precision, intent(in) :: x(2, nnode), v(2, nnode), r(2, nnode)
         double precision, intent(inout) :: a(2, nnode)
         double precision, intent(in) :: dtprev, dt
         double precision, intent(out) :: fcon(2, nnode)
         integer, intent(out) :: nactive, ierr
      end subroutine exic_contact_step_face

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_pair_results(ih, ipair, res, ierr)
         implicit none
         integer, intent(in) :: ih, ipair
         double precision, intent(out) :: res(6)
         integer, intent(out) :: ierr
      end subroutine exic_contact_pair_results

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_set_friction(ih, ipair, amus, amud, decay, ierr)
         implicit none
         integer, intent(in) :: ih, ipair
         double precision, intent(in) :: amus, amud, decay
         integer, intent(out) :: ierr
      end subroutine exic_contact_set_friction

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_pair_friction(ih, ipair, res, ierr)
         implicit none
         integer, intent(in) :: ih, ipair
         double precision, intent(out) :: res(4)
         integer, intent(out) :: ierr
      end subroutine exic_contact_pair_friction

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_ncon(ih, ncon, ierr)
         implicit none
         integer, intent(in) :: ih
         integer, intent(out) :: ncon, ierr
      end subroutine exic_contact_ncon

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_constraints(ih, mcon, ncon, icon, rcon, ierr)
         implicit none
         integer, intent(in) :: ih, mcon
         integer, intent(out) :: ncon
         integer, intent(out) :: icon(4, mcon)
         double precision, intent(out) :: rcon(6, mcon)
         integer, intent(out) :: ierr
      end subroutine exic_contact_constraints

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_work(ih, wcon, penmax, ierr)
         implicit none
         integer, intent(in) :: ih
         double precision, intent(out) :: wcon, penmax
         integer, intent(out) :: ierr
      end subroutine exic_contact_work

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_free(ih, ierr)
         implicit none
         integer, intent(in) :: ih
         integer, intent(out) :: ierr
      end subroutine exic_contact_free

      !> See api.f90 and doc/api.md.
      subroutine exic_contact_error_message(ih, msg, lmsg, ierr)
         implicit none
         integer, intent(in) :: ih
         character(len=*), intent(out) :: msg
         integer, intent(out) :: lmsg, ierr
      end subroutine exic_contact_error_message
   end interface

end module exic_legacy_interfaces
