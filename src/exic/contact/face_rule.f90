!> Which nodes of a surface that meets rigid bodies only become massless faces under
!> `LAGRange,ENERgy` (doc/impact.md, section 3.1, eq. I.3b): the nodes of the segments that
!> face a segment of a rigid partner surface in the reference configuration, along the dof
!> closer to the segment's normal (as eq. I.3a).
module exic_contact_face_rule
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: facing_dofs

contains

   !> dofs(d, i) = .true., d the dof closer to n_s, for the nodes i of every segment of (nseg, seg) that faces a
   !> segment of the partner (npseg, pseg) at the positions x (eq. I.3b): outward normals n_s, n_r
   !> (the normal of a segment from a to b is (t_2, -t_1), t = x_b - x_a, as in
   !> exic_mesh_boundary) opposed within 60 degrees, n_s . n_r < -1/2 (perpendicular segments,
   !> whose product is round-off of either sign, never face), and each midpoint on or in front of the other
   !> segment's line, (x_r - x_s) . n_s >= -tol and (x_s - x_r) . n_r >= -tol, tol 1e-9 of the
   !> two segments' lengths (bodies touching at t = 0 face each other).
   pure subroutine facing_dofs(nnode, x, nseg, seg, npseg, pseg, dofs)
      integer, intent(in) :: nnode, nseg, npseg
      real(wp), intent(in) :: x(2, nnode)
      integer, intent(in) :: seg(2, nseg), pseg(2, npseg)
      logical, intent(inout) :: dofs(2, nnode)
      real(wp) :: ts(2), tr(2), xs(2), xr(2), ns(2), nr(2), tol
      integer :: s, r
      do s = 1, nseg
         ts = x(:, seg(2, s)) - x(:, seg(1, s))
         xs = 0.5_wp*(x(:, seg(1, s)) + x(:, seg(2, s)))
         ns = [ts(2), -ts(1)]/norm2(ts)
         do r = 1, npseg
            tr = x(:, pseg(2, r)) - x(:, pseg(1, r))
            xr = 0.5_wp*(x(:, pseg(1, r)) + x(:, pseg(2, r)))
            nr = [tr(2), -tr(1)]/norm2(tr)
            tol = 1.0e-9_wp*(norm2(ts) + norm2(tr))
            if (dot_product(ns, nr) < -0.5_wp .and. dot_product(xr - xs, ns) >= -tol .and. &
                dot_product(xs - xr, nr) >= -tol) then
               if (abs(ns(1)) >= abs(ns(2))) dofs(1, seg(:, s)) = .true.
               if (abs(ns(2)) >= abs(ns(1))) dofs(2, seg(:, s)) = .true.
               exit
            end if
         end do
      end do
   end subroutine facing_dofs

end module exic_contact_face_rule
