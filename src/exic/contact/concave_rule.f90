!> The concave-corner rule of the swept narrow phase (doc/contact-detection.md, "A node sliding
!> into a master's concave corner", eq. C.1-C.3): a slave in contact from the start of a step
!> (tau_c < TAU_BLEND of exic_contact_detect) on master segment k takes as contact point the
!> projection of its predicted position on the predicted segment. When that projection lies past
!> an end m of k where the master surface turns concave (its body the union of the two
!> half-planes at m), the predicted position lies behind the line of the neighbour k' at m as
!> well, and the slave is paired with k' instead of being clamped to m: the corrector then puts it
!> on the line of k', outside k, where clamped to m with the master node normal it ended behind
!> k' by its slide past m times the sine of half the turn.
module exic_contact_concave_rule
   use exic_base_kinds, only: wp
   use exic_mesh_boundary, only: segment_normal
   implicit none
   private

   public :: concave_neighbour, concave_entry, concave_vertex_normal

contains

   !> The neighbour segment kn that slave `node` (outward normal ns; zero skips the facing test),
   !> in contact with segment k since tau (positions x0 + tau (x1 - x0)), slides onto in a
   !> concave corner of the master, and the projection alpha_c of the slave on kn at tau (not
   !> clamped); kn = 0 when the rule does not apply. The rule applies when
   !>   (C.1) the projection a1 of x1(node) on the segment k at x1 lies past an end m of k by more
   !>         than `tol` (a share of k's length): a1 < -tol (m = seg(1, k), kn = link(1, k)) or
   !>         a1 > 1 + tol (m = seg(2, k), kn = link(2, k));
   !>   (C.2) the master surface turns concave at m at x1: kn turns right from k (the body on the
   !>         left of its segments), t_k x t_kn < 0 with t the segments' directions in their order
   !>         along the surface;
   !>   (C.3) kn does not hold the slave and faces it at tau: ns . n_kn < facing.
   pure subroutine concave_neighbour(nnode, x0, x1, tau, node, ns, nseg, seg, link, k, facing, &
                                     tol, kn, alpha_c)
      integer, intent(in) :: nnode, node, nseg, k
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), tau, ns(2), facing, tol
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      integer, intent(out) :: kn
      real(wp), intent(out) :: alpha_c
      real(wp) :: t(2), tn(2), tt, a1, turn, n(2), pa(2), pb(2), ps(2)
      integer :: nb

      kn = 0
      alpha_c = 0.0_wp
      t = x1(:, seg(2, k)) - x1(:, seg(1, k))
      tt = dot_product(t, t)
      if (.not. (tt > 0.0_wp)) return
      a1 = dot_product(x1(:, node) - x1(:, seg(1, k)), t)/tt
      ! (C.1), and the turn of the surface at m in its order along the surface (C.2)
      if (a1 < -tol) then
         nb = link(1, k)
         if (nb <= 0) return
         tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
         turn = tn(1)*t(2) - tn(2)*t(1)
      else if (a1 > 1.0_wp + tol) then
         nb = link(2, k)
         if (nb <= 0) return
         tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
         turn = t(1)*tn(2) - t(2)*tn(1)
      else
         return
      end if
      if (.not. (turn < 0.0_wp)) return
      ! (C.3)
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
   !> alpha off k (past its end m), enters k from its concave corner at
   !> m: it is caught on k at the projection of its predicted position, returned in alpha, when
   !>   (C.4) the master surface turns concave at m at x1 (as C.2),
   !>   (C.5) the projection a1 of x1(node) on the segment k at x1 lies within [-tol, 1 + tol]
   !>         and x1(node) is behind the line of k: (x1(node) - x1(m1)) . n_k(x1) <= 0.
   !> alpha is then a1 clamped to [0, 1].
   pure subroutine concave_entry(nnode, x1, node, nseg, seg, link, k, tol, alpha, hit)
      integer, intent(in) :: nnode, node, nseg, k
      real(wp), intent(in) :: x1(2, nnode), tol
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      real(wp), intent(inout) :: alpha
      logical, intent(out) :: hit
      real(wp) :: t(2), tn(2), tt, a1, turn
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
      if (alpha < 0.0_wp) then
         turn = tn(1)*t(2) - tn(2)*t(1)
      else
         turn = t(1)*tn(2) - t(2)*tn(1)
      end if
      ! (C.4)
      if (.not. (turn < 0.0_wp)) return
      ! (C.5)
      a1 = dot_product(x1(:, node) - x1(:, seg(1, k)), t)/tt
      if (.not. (a1 >= -tol .and. a1 <= 1.0_wp + tol)) return
      if (dot_product(x1(:, node) - x1(:, seg(1, k)), segment_normal(x1(:, seg(1, k)), x1(:, seg(2, k)))) > 0.0_wp) return
      alpha = min(max(a1, 0.0_wp), 1.0_wp)
      hit = .true.
   end subroutine concave_entry

   !> The normal of a contact of slave `node` at the end m of segment k (m = seg(1, k) when
   !> `first`, else seg(2, k); nb the neighbour of k at m) in a concave corner of the master:
   !> when the surface turns concave at m at x1 (as C.2) and the predicted position x1(node)
   !> projects past m on both k and nb (it lies in the normal cone of the master's outside wedge
   !> at m, whose closest point to it is m), n is the unit vector from x1(node) to x1(m) (C.6);
   !> otherwise n is left as it is.
   pure subroutine concave_vertex_normal(nnode, x1, node, nseg, seg, k, nb, first, n)
      integer, intent(in) :: nnode, node, nseg, k, nb
      real(wp), intent(in) :: x1(2, nnode)
      integer, intent(in) :: seg(2, nseg)
      logical, intent(in) :: first
      real(wp), intent(inout) :: n(2)
      real(wp) :: t(2), tn(2), d(2), turn, len
      integer :: m

      t = x1(:, seg(2, k)) - x1(:, seg(1, k))
      tn = x1(:, seg(2, nb)) - x1(:, seg(1, nb))
      if (first) then
         m = seg(1, k)
         turn = tn(1)*t(2) - tn(2)*t(1)
      else
         m = seg(2, k)
         turn = t(1)*tn(2) - t(2)*tn(1)
      end if
      if (.not. (turn < 0.0_wp)) return
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

end module exic_contact_concave_rule
