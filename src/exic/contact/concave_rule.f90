!> The concave rule of the swept narrow phase (doc/contact-detection.md, "A node sliding into a
!> master's concave corner", C.1-C.3). At a node m where the master surface turns concave (its
!> body the union of the half-planes behind its two segments k and k', its outside the wedge W
!> between them) a slave takes the point of W closest to its predicted position x~s:
!>   (C.1) on k', when it was in contact with k from the start and x~s projects past m on k
!>         (concave_neighbour);
!>   (C.2) on k, when it crossed k's line past m and x~s projects on k, behind it (concave_entry);
!>   (C.3) at m, along the direction from x~s to m, when x~s projects past m on both
!>         (concave_vertex_normal).
!> Clamped to m along the average of the two normals instead, the slave ended behind k' by its
!> slide past m times the sine of half the turn.
module exic_contact_concave_rule
   use exic_base_kinds, only: wp
   use exic_mesh_boundary, only: segment_normal
   implicit none
   private

   public :: concave_neighbour, concave_entry, concave_vertex_normal

   !> A turn whose sine is below this (plus the rounding of the coordinates) is straight: the
   !> share of a segment's length within which exic_contact_detect puts a contact point at the
   !> segment's end (its ALPHA_TOL).
   real(wp), parameter :: STRAIGHT = 1.0e-8_wp

contains

   !> The neighbour segment kn that slave `node` (outward normal ns; zero skips the facing test),
   !> in contact with segment k since tau (positions x0 + tau (x1 - x0)), slides onto in a
   !> concave corner of the master, and the projection alpha_c of the slave on kn at tau (not
   !> clamped); kn = 0 when the rule (C.1) does not apply. It applies when
   !>   (i)   the projection a1 of x1(node) on the segment k at x1 lies past an end m of k by more
   !>         than `tol` (a share of k's length): a1 < -tol (m = seg(1, k), kn = link(1, k)) or
   !>         a1 > 1 + tol (m = seg(2, k), kn = link(2, k));
   !>   (ii)  the master surface turns concave at m at x1 (concave_at);
   !>   (iii) kn does not hold the slave and faces it at tau: ns . n_kn < facing.
   pure subroutine concave_neighbour(nnode, x0, x1, tau, node, ns, nseg, seg, link, k, facing, &
                                     tol, kn, alpha_c)
      integer, intent(in) :: nnode, node, nseg, k
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), tau, ns(2), facing, tol
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      integer, intent(out) :: kn
      real(wp), intent(out) :: alpha_c
      real(wp) :: t(2), tn(2), tt, a1, n(2), pa(2), pb(2), ps(2)
      integer :: nb

      kn = 0
      alpha_c = 0.0_wp
      t = x1(:, seg(2, k)) - x1(:, seg(1, k))
      tt = dot_product(t, t)
      if (.not. (tt > 0.0_wp)) return
      a1 = dot_product(x1(:, node) - x1(:, seg(1, k)), t)/tt
      ! (i), and the turn of the surface at m (ii)
      if (a1 < -tol) then
         nb = link(1, k)
      else if (a1 > 1.0_wp + tol) then
         nb = link(2, k)
      else
         return
      end if
      if (nb <= 0) return
      tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
      if (.not. concave_at(t, tn, a1 < 0.0_wp, scale_of(x1, [seg(:, k), seg(:, nb)]))) return
      ! (iii)
      if (seg(1, nb) == node .or. seg(2, nb) == node) return
      pa = at(seg(1, nb)); pb = at(seg(2, nb))
      n = segment_normal(pa, pb)
      if (n(1) == 0.0_wp .and. n(2) == 0.0_wp) return
      if (.not. (ns(1) == 0.0_wp .and. ns(2) == 0.0_wp)) then
         if (.not. (dot_product(ns, n) < facing)) return
      end if
      ps = at(node)
      tn = pb - pa
      alpha_c = dot_product(ps - pa, tn)/dot_product(tn, tn)
      kn = nb
   contains
      !> Position of node j at x0 + tau (x1 - x0) (exactly x0 at tau = 0).
      pure function at(j) result(p)
         integer, intent(in) :: j
         real(wp) :: p(2)
         if (tau == 0.0_wp) then
            p = x0(:, j)
         else
            p = x0(:, j) + tau*(x1(:, j) - x0(:, j))
         end if
      end function at
   end subroutine concave_neighbour

   !> Whether slave `node`, whose gap test on segment k passed (swept test) with a contact point
   !> alpha off k (past its end m), enters k from its concave corner at m (C.2): it is caught on
   !> k at the projection of its predicted position, returned in alpha, when
   !>   (i)  the master surface turns concave at m at x1 (concave_at),
   !>   (ii) the projection a1 of x1(node) on the segment k at x1 lies within [-tol, 1 + tol]
   !>        and x1(node) is behind the line of k: (x1(node) - x1(m1)) . n_k(x1) <= 0.
   !> alpha is then a1 clamped to [0, 1].
   pure subroutine concave_entry(nnode, x1, node, nseg, seg, link, k, tol, alpha, hit)
      integer, intent(in) :: nnode, node, nseg, k
      real(wp), intent(in) :: x1(2, nnode), tol
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      real(wp), intent(inout) :: alpha
      logical, intent(out) :: hit
      real(wp) :: t(2), tn(2), tt, a1
      integer :: nb

      hit = .false.
      if (alpha < 0.0_wp) then
         nb = link(1, k)
      else if (alpha > 1.0_wp) then
         nb = link(2, k)
      else
         return
      end if
      if (nb <= 0) return
      t = x1(:, seg(2, k)) - x1(:, seg(1, k))
      tt = dot_product(t, t)
      if (.not. (tt > 0.0_wp)) return
      tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
      ! (i)
      if (.not. concave_at(t, tn, alpha < 0.0_wp, scale_of(x1, [seg(:, k), seg(:, nb)]))) return
      ! (ii)
      a1 = dot_product(x1(:, node) - x1(:, seg(1, k)), t)/tt
      if (.not. (a1 >= -tol .and. a1 <= 1.0_wp + tol)) return
      if (dot_product(x1(:, node) - x1(:, seg(1, k)), segment_normal(x1(:, seg(1, k)), x1(:, seg(2, k)))) > 0.0_wp) return
      alpha = min(max(a1, 0.0_wp), 1.0_wp)
      hit = .true.
   end subroutine concave_entry

   !> The normal of a contact of slave `node` at the end m of segment k (m = seg(1, k) when
   !> `first`, else seg(2, k); nb the neighbour of k at m) in a concave corner of the master:
   !> (C.3): when the surface turns concave at m at x1 (concave_at) and the predicted position
   !> x1(node) projects past m on both k and nb (it lies in the normal cone of the master's outside
   !> wedge at m, whose closest point to it is m), n is the unit vector from x1(node) to x1(m);
   !> otherwise n is left as it is.
   pure subroutine concave_vertex_normal(nnode, x1, node, nseg, seg, k, nb, first, n)
      integer, intent(in) :: nnode, node, nseg, k, nb
      real(wp), intent(in) :: x1(2, nnode)
      integer, intent(in) :: seg(2, nseg)
      logical, intent(in) :: first
      real(wp), intent(inout) :: n(2)
      real(wp) :: t(2), tn(2), d(2), len
      integer :: m

      t = x1(:, seg(2, k)) - x1(:, seg(1, k))
      tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
      m = merge(seg(1, k), seg(2, k), first)
      if (.not. concave_at(t, tn, first, scale_of(x1, [seg(:, k), seg(:, nb)]))) return
      d = x1(:, node) - x1(:, m)
      ! past m on both: before the start of the segment that starts at m, beyond the end of the
      ! one that ends there
      if (first) then
         if (.not. (dot_product(d, t) < 0.0_wp .and. dot_product(d, tn) > 0.0_wp)) return
      else
         if (.not. (dot_product(d, t) > 0.0_wp .and. dot_product(d, tn) < 0.0_wp)) return
      end if
      len = sqrt(d(1)*d(1) + d(2)*d(2))
      if (.not. (len > 0.0_wp)) return
      n = -d/len
   end subroutine concave_vertex_normal

   !> The largest coordinate of nodes `nodes` at x.
   pure real(wp) function scale_of(x, nodes) result(scale)
      real(wp), intent(in) :: x(:, :)
      integer, intent(in) :: nodes(:)
      integer :: j
      scale = 0.0_wp
      do j = 1, size(nodes)
         scale = max(scale, abs(x(1, nodes(j))), abs(x(2, nodes(j))))
      end do
   end function scale_of

   !> Whether the surface turns concave (right, its body on the left) at the node m shared by
   !> segment k (direction t) and its neighbour kn (direction tn): `first` when m is k's first
   !> node (kn precedes k, the turn is tn x t), else its second (kn follows, t x tn). A turn within
   !> the resolution of the coordinates is straight, not concave: sin(turn) below
   !> STRAIGHT + 4 eps scale / min(|t|, |tn|), scale the largest coordinate, the tolerance on
   !> the contact point of a segment (so a flat face whose nodes are collinear to round-off, a
   !> moving rigid body's, is not concave at some nodes and convex at others).
   pure logical function concave_at(t, tn, first, scale) result(ok)
      real(wp), intent(in) :: t(2), tn(2), scale
      logical, intent(in) :: first
      real(wp) :: turn, lt, ln
      if (first) then
         turn = tn(1)*t(2) - tn(2)*t(1)
      else
         turn = t(1)*tn(2) - t(2)*tn(1)
      end if
      lt = sqrt(dot_product(t, t))
      ln = sqrt(dot_product(tn, tn))
      ok = .false.
      if (.not. (lt > 0.0_wp .and. ln > 0.0_wp)) return
      ok = turn < -(STRAIGHT + 4.0_wp*epsilon(1.0_wp)*scale/min(lt, ln))*lt*ln
   end function concave_at

end module exic_contact_concave_rule
