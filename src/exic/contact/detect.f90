!> Narrow phase of the contact search: swept (seed section 6, eq. 6.1-6.6) and static
!> node-to-segment detection, with the corner rule and the facing test.
!>
!> Over one step tau in [0, 1] runs from t(n+1) (positions x0) to the predicted t(n+2)
!> (positions x1). Slave node s and master nodes a = m1, b = m2 move linearly (eq. 6.1):
!>   xs(tau) = xs_i + tau (xs_f - xs_i),   xa(tau), xb(tau) likewise,
!> and the master normal is interpolated linearly (eq. 6.2):
!>   n(tau) = n_i + tau (n_f - n_i),   n_i, n_f the outward unit normals at tau = 0, 1.
!>
!> Gap function (eq. 6.3), measured from master node 1 as it moves:
!>   g(tau) = (xs(tau) - xa(tau)) . n(tau).
!> With d_i = xs_i - xa_i, d_f = xs_f - xa_f, the relative motion e = d_f - d_i
!> = (xs_f - xs_i) - (xa_f - xa_i) and dn = n_f - n_i:
!>   g(tau) = (d_i + tau e) . (n_i + tau dn) = A tau^2 + B tau + C        (eq. 6.4)
!>   A = e . dn,   B = e . n_i + d_i . dn,   C = d_i . n_i.
!> The seed's eq. 6.5 as printed has e = (xs_f - xs_i) + (xa_f - xa_i); that adds the
!> master's motion instead of subtracting it and agrees only when master node 1 is fixed.
!> Scaling n(tau) by a positive factor does not move the zeros of g, so the interpolated
!> (not re-normalized) normal is fine for finding the crossing time.
!>
!> The contact point (eq. 6.6) is the projection at tau_c on the segment,
!>   alpha = (xs - xa) . (xb - xa) / |xb - xa|^2,
!> which keeps its sign (the ratio of norms in eq. 6.6 does not). A hit is accepted for
!> -tol <= alpha <= 1 + tol with tol = ALPHA_TOL + 4 eps max|x| / |xb - xa| (a share of
!> the segment length plus the rounding of the coordinates).
!>
!> The normal returned for the corrector is frozen: the unit normal of the master segment, or
!> the master node normal when the contact point is at a segment end (see detect_pairs), at
!> the positions of the time of contact x0 + tau_c (x1 - x0). The seed (section 4) freezes
!> n_f ~ n(t(n+2)) of the predicted positions; for a slave already in contact at the start of a
!> step (tau_c = 0) that normal made sliding along a segment do work, the normal of t(n+1) does
!> not (doc/contact-detection.md, "Frozen normal of a node in contact", eq. D.1-D.2). Such a
!> slave's contact point is the projection of its predicted position on the predicted segment
!> (it then ends the step on the segment). Static detection: normal at the predicted x1. The
!> returned gap is the predicted gap at t(n+2): (xs_f - (1 - alpha) xa_f - alpha xb_f) . n.
module exic_contact_detect
   use exic_base_kinds, only: wp
   use exic_contact_spec, only: DETECT_SWEPT, DETECT_STATIC
   use exic_mesh_boundary, only: segment_normal, average_normal, some_node_normals, node_normal_from
   implicit none
   private

   public :: gap_coefficients, first_crossing, swept_pair, static_pair, alpha_tolerance
   public :: detect_pairs, detect_contacts, contact_set_t, candidate_normals

   !> Accepted contact points may lie this share of the segment length beyond either end;
   !> a contact point this close to an end is taken to be at the end (master node).
   real(wp), parameter, public :: ALPHA_TOL = 1.0e-8_wp
   !> Default facing limit: a slave whose own outward normal ns gives ns . n >= FACING_LIMIT
   !> with the master normal n is not paired (0: the two must face each other).
   real(wp), parameter, public :: FACING_LIMIT = 0.0_wp
   !> A slave in contact from the start of a step (tau_c = 0) takes as contact point the
   !> projection of its predicted position on the predicted segment; for 0 < tau_c < TAU_BLEND
   !> the contact point moves linearly from that to the seed's alpha(tau_c), so that rounding of
   !> tau_c near 0 never switches between the two (doc/contact-detection.md).
   real(wp), parameter, public :: TAU_BLEND = 0.01_wp

   !> Accepted contacts of one detection pass, at most one per slave node, in slave order.
   type :: contact_set_t
      integer :: n = 0                        !< number of contacts
      integer, allocatable :: slave(:)        !< slave node number
      integer, allocatable :: master(:, :)    !< (2, n) master nodes m1, m2 of the segment
      integer, allocatable :: seg(:)          !< segment index in the master segment list
      logical, allocatable :: at_end(:)       !< contact point at a segment end (master node)
      real(wp), allocatable :: alpha(:)       !< contact point (1 - alpha) x_m1 + alpha x_m2
      real(wp), allocatable :: normal(:, :)   !< (2, n) unit normal, frozen for the corrector
      real(wp), allocatable :: tau(:)         !< time of contact in the step (1: static)
      real(wp), allocatable :: gap(:)         !< predicted gap at t(n+2) along `normal`
   end type contact_set_t

contains

   !> Coefficients of g(tau) = A tau^2 + B tau + C (eq. 6.4, corrected eq. 6.5; see the
   !> module header) and the end gap g1 = (xs_f - xa_f) . n_f evaluated directly.
   pure subroutine gap_coefficients(xs0, xs1, xa0, xa1, xb0, xb1, a, b, c, g1)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), xb0(2), xb1(2)
      real(wp), intent(out) :: a, b, c, g1
      real(wp) :: ni(2), nf(2)
      call coefficients_normals(xs0, xs1, xa0, xa1, xb0, xb1, a, b, c, g1, ni, nf)
   end subroutine gap_coefficients

   !> gap_coefficients, and the unit normals n_i, n_f of the segment at both ends of the step.
   pure subroutine coefficients_normals(xs0, xs1, xa0, xa1, xb0, xb1, a, b, c, g1, ni, nf)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), xb0(2), xb1(2)
      real(wp), intent(out) :: a, b, c, g1, ni(2), nf(2)
      ni = segment_normal(xa0, xb0)
      nf = segment_normal(xa1, xb1)
      call coefficients_given(xs0, xs1, xa0, xa1, ni, nf, a, b, c, g1)
   end subroutine coefficients_normals

   !> gap_coefficients with the segment's unit normals ni (at x0) and nf (at x1) given.
   pure subroutine coefficients_given(xs0, xs1, xa0, xa1, ni, nf, a, b, c, g1)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), ni(2), nf(2)
      real(wp), intent(out) :: a, b, c, g1
      real(wp) :: dn(2), di(2), df(2), e(2)
      dn = nf - ni
      di = xs0 - xa0
      df = xs1 - xa1
      e = df - di
      a = dot_product(e, dn)
      b = dot_product(e, ni) + dot_product(di, dn)
      c = dot_product(di, ni)
      g1 = dot_product(df, nf)
   end subroutine coefficients_given

   !> Smallest tau in [0, 1] at which g = a tau^2 + b tau + c, positive at tau = 0 (c > 0),
   !> becomes zero; g1 is g(1) evaluated directly. Uses the cancellation-free form
   !> q = -(b + sign(b) sqrt(b^2 - 4ac))/2, roots q/a and c/q, so a -> 0 needs no special
   !> case beyond a == 0 (linear). No real root (b^2 < 4ac, grazing) means no crossing. When
   !> g1 <= 0 a crossing must exist; if rounding pushes the computed root just past 1 it
   !> is taken at tau = 1.
   pure subroutine first_crossing(a, b, c, g1, hit, tau)
      real(wp), intent(in) :: a, b, c, g1
      logical, intent(out) :: hit
      real(wp), intent(out) :: tau
      real(wp) :: disc, q, r

      hit = .false.
      tau = 2.0_wp
      if (.not. (c > 0.0_wp)) return
      if (a == 0.0_wp) then
         if (b < 0.0_wp .and. c <= -b) tau = -c/b
      else
         disc = b*b - 4.0_wp*a*c
         if (disc >= 0.0_wp) then
            q = -0.5_wp*(b + sign(sqrt(disc), b))
            ! roots q/a and c/q; only those that can lie in [0, 1] are formed (no overflow)
            if (abs(q) <= abs(a)) then
               r = q/a
               if (r >= 0.0_wp) tau = min(tau, r)
            end if
            if (c <= abs(q)) then
               r = c/q
               if (r >= 0.0_wp) tau = min(tau, r)
            end if
         end if
      end if
      if (tau <= 1.0_wp) then
         hit = .true.
      else if (g1 <= 0.0_wp) then
         hit = .true.
         tau = 1.0_wp
      else
         tau = 0.0_wp
      end if
   end subroutine first_crossing

   !> Tolerance on alpha for a segment of length len with coordinates up to `scale`.
   pure real(wp) function alpha_tolerance(len, scale) result(tol)
      real(wp), intent(in) :: len, scale
      tol = ALPHA_TOL + 4.0_wp*epsilon(1.0_wp)*scale/len
   end function alpha_tolerance

   !> Projection parameter of point p on segment xa -> xb, and whether it lies within
   !> [-tol, 1 + tol] (false for a zero-length segment).
   pure subroutine project(p, xa, xb, alpha, inside)
      real(wp), intent(in) :: p(2), xa(2), xb(2)
      real(wp), intent(out) :: alpha
      logical, intent(out) :: inside
      real(wp) :: t(2), tt, tol
      t = xb - xa
      tt = dot_product(t, t)
      alpha = 0.0_wp
      inside = .false.
      if (.not. (tt > 0.0_wp)) return
      alpha = dot_product(p - xa, t)/tt
      ! within the segment: inside whatever the tolerance (tol > 0; a NaN coordinate gives a
      ! NaN alpha or tt and never reaches here)
      inside = alpha >= 0.0_wp .and. alpha <= 1.0_wp
      if (inside) return
      tol = alpha_tolerance(sqrt(tt), max(abs(p(1)), abs(p(2)), abs(xa(1)), abs(xa(2)), abs(xb(1)), abs(xb(2))))
      inside = alpha >= -tol .and. alpha <= 1.0_wp + tol
   end subroutine project

   !> Swept test of slave s against segment a -> b over the step (seed section 6).
   !>
   !> Gap positive at tau = 0: contact at the first tau in [0, 1] where g(tau) <= 0.
   !> Gap in [-depth, 0] at tau = 0 (touching, or slightly behind after an earlier step)
   !> and g(1) <= 0: contact at tau = 0. Deeper at the start, or moving out: no contact.
   !> The contact point alpha (eq. 6.6) is the projection at tau_c and must lie within
   !> [-tol, 1 + tol]. `nf`: the segment's unit normal at the end of the step (x1).
   pure subroutine swept_pair(xs0, xs1, xa0, xa1, xb0, xb1, depth, hit, tau, alpha, nf, crossed)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), xb0(2), xb1(2), depth
      logical, intent(out) :: hit
      real(wp), intent(out) :: tau, alpha
      real(wp), intent(out), optional :: nf(2)
      logical, intent(out), optional :: crossed
      real(wp) :: ni(2), nend(2)

      ni = segment_normal(xa0, xb0)
      nend = segment_normal(xa1, xb1)
      if (present(nf)) nf = nend
      call swept_given(xs0, xs1, xa0, xa1, xb0, xb1, ni, nend, depth, hit, tau, alpha, crossed)
   end subroutine swept_pair

   !> swept_pair with the segment's unit normals ni (at x0) and nf (at x1) given.
   !> `crossed` (optional): the gap condition held (a crossing at tau, or in contact from the
   !> start), whatever the projection; alpha is then the projection at tau even when it falls
   !> outside the segment (hit false), as the vertex rule of detect_pairs reads it.
   pure subroutine swept_given(xs0, xs1, xa0, xa1, xb0, xb1, ni, nf, depth, hit, tau, alpha, crossed)
      real(wp), intent(in) :: xs0(2), xs1(2), xa0(2), xa1(2), xb0(2), xb1(2), ni(2), nf(2), depth
      logical, intent(out) :: hit
      real(wp), intent(out) :: tau, alpha
      !> the gap test passed (hit false then means: the projection alpha lies off the segment)
      logical, intent(out), optional :: crossed
      real(wp) :: a, b, c, g1

      alpha = 0.0_wp
      if (present(crossed)) crossed = .false.
      call coefficients_given(xs0, xs1, xa0, xa1, ni, nf, a, b, c, g1)
      if (c > 0.0_wp) then
         call first_crossing(a, b, c, g1, hit, tau)
         if (.not. hit) return
      else
         tau = 0.0_wp
         hit = .false.
         if (c < -depth .or. g1 > 0.0_wp) return
         if (all(ni == 0.0_wp)) return
      end if
      if (present(crossed)) crossed = .true.
      call project(xs0 + tau*(xs1 - xs0), xa0 + tau*(xa1 - xa0), xb0 + tau*(xb1 - xb0), &
                   alpha, hit)
   end subroutine swept_given

   !> Static test at the end of the step only (tau = 1): gap g = (xs_f - xa_f) . n_f in
   !> [-depth, 0] and projection alpha within [-tol, 1 + tol].
   pure subroutine static_pair(xs1, xa1, xb1, depth, hit, alpha, gap)
      real(wp), intent(in) :: xs1(2), xa1(2), xb1(2), depth
      logical, intent(out) :: hit
      real(wp), intent(out) :: alpha, gap
      real(wp) :: n(2)

      hit = .false.
      alpha = 0.0_wp
      n = segment_normal(xa1, xb1)
      gap = dot_product(xs1 - xa1, n)
      if (all(n == 0.0_wp) .or. gap > 0.0_wp .or. gap < -depth) return
      call project(xs1, xa1, xb1, alpha, hit)
   end subroutine static_pair

   !> True unless the slave's outward normal ns (zero: unknown) fails to face n.
   pure logical function faces(ns, n, facing)
      real(wp), intent(in) :: ns(2), n(2), facing
      faces = .true.
      if (ns(1) == 0.0_wp .and. ns(2) == 0.0_wp) return
      faces = dot_product(ns, n) < facing
   end function faces

   !> Narrow phase over candidate pairs cand(:, 1:ncand) (slave index, segment index),
   !> sorted by slave: at most one contact per slave, written in slave order.
   !>
   !> mode is DETECT_SWEPT or DETECT_STATIC. snrm(:, s) is the outward normal of slave s
   !> on its own surface (zero to skip the facing test); a pair is kept only if
   !> snrm . n_f < facing. link(:, k) are the neighbours of segment k (segment_links;
   !> zero where none). depth bounds the penetration accepted at the start of a swept step
   !> and at the end of a static one.
   !>
   !> Choice among a slave's hits: smallest tau; then the largest predicted gap at t(n+2)
   !> (the least penetrated segment, closest-point rule); then the segment whose sorted
   !> node pair is lowest. All keys depend on geometry and node numbers only, so the choice
   !> does not depend on the order of the segment list. A contact point within ALPHA_TOL of
   !> a segment end is put at that end (alpha = 0 or 1, at_end true) and gets the master
   !> node normal: the normalized average of the segment's normal and that of its
   !> neighbour at that node, the neighbour counting only if it passes the facing test.
   !> Swept mode: a contact point just past an end at a convex corner of the master is held at
   !> that end under the conditions of past_corner.
   !> A hit at tau = 0 of a slave behind a segment's line that the side test alone paired with it
   !> is dropped where the slave lies on the face across a convex corner (beside_corner).
   !>
   !> With the slave surface's nsseg segments `sseg` and its node -> segments lists (`shead`,
   !> `ssegs`, node_segments), snrm(:, s) is formed here at x0 (some_node_normals), for the
   !> slaves that have a hit only, when their first hit needs it; without them snrm must hold
   !> every candidate slave's normal.
   !>
   !> Segment normals formed once per search (swept mode, with the lists above): `stamp` names
   !> the search; mnrm(:, k) holds the unit normals of master segment k at x0 (1:2) and x1
   !> (3:4) when mstamp(k) == stamp, snrm_seg and sstamp likewise for the slave surface's
   !> segments (another surface: the two must not be the same arrays). A segment's normals are
   !> formed here at its first use in the search, with segment_normal on the same positions, so
   !> a candidate's arithmetic is that of swept_pair and the results are the same bits.
   subroutine detect_pairs(mode, nnode, x0, x1, nslave, slaves, snrm, nseg, seg, link, &
                           ncand, cand, depth, facing, ncon, cslave, cseg, cmaster, &
                           cend, calpha, cnormal, ctau, cgap, nsseg, sseg, shead, ssegs, &
                           stamp, mnrm, mstamp, snrm_seg, sstamp, fseg, fhead, fsegs)
      integer, intent(in) :: mode, nnode, nslave, nseg, ncand
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), depth, facing
      real(wp), intent(inout) :: snrm(2, nslave)
      integer, intent(in) :: slaves(nslave), seg(2, nseg), link(2, nseg), cand(2, ncand)
      ! the slave surface's nsseg segments and lists, the segment caches (module header): sizes
      ! assumed, so that a pass hands over addresses (assumed-shape arrays cost a descriptor and
      ! a contiguity check each, about 450 instructions a pass through detect_contacts)
      integer, intent(in), optional :: nsseg
      integer, intent(in), optional :: sseg(2, *), shead(*), ssegs(*)
      integer, intent(in), optional :: stamp
      real(wp), intent(inout), optional :: mnrm(4, *), snrm_seg(4, *)
      integer, intent(inout), optional :: mstamp(*), sstamp(*)
      ! the slave surface's segments and node -> segments lists for the side test of the facing
      ! rule when the lists above are not given (every node normal formed already)
      integer, intent(in), optional :: fseg(2, *), fhead(*), fsegs(*)
      integer, intent(out) :: ncon
      integer, intent(out) :: cslave(nslave), cseg(nslave), cmaster(2, nslave)
      logical, intent(out) :: cend(nslave)
      real(wp), intent(out) :: calpha(nslave), cnormal(2, nslave), ctau(nslave), cgap(nslave)
      integer :: j, j0, s, k, node, ma, mb, best, bkey(2), key(2), q, ks
      real(wp) :: tau, alpha, gap, nf(2), btau, balpha, bgap, w
      logical :: hit, lazy, have_nrm, cached, sides, crossed, by_side

      lazy = present(nsseg) .and. present(sseg) .and. present(shead) .and. present(ssegs)
      sides = present(fseg) .and. present(fhead) .and. present(fsegs)
      cached = lazy .and. mode == DETECT_SWEPT .and. present(stamp) .and. present(mnrm) .and. &
               present(mstamp) .and. present(snrm_seg) .and. present(sstamp)

      ncon = 0
      j0 = 1
      do while (j0 <= ncand)
         s = cand(1, j0)
         node = slaves(s)
         best = 0
         btau = 0.0_wp; balpha = 0.0_wp; bgap = 0.0_wp; bkey = 0
         have_nrm = .not. lazy
         j = j0
         do while (j <= ncand)
            if (cand(1, j) /= s) exit
            k = cand(2, j)
            j = j + 1
            ma = seg(1, k); mb = seg(2, k)
            if (ma == node .or. mb == node) cycle
            if (mode == DETECT_STATIC) then
               call static_pair(x1(:, node), x1(:, ma), x1(:, mb), depth, hit, alpha, gap)
               tau = 1.0_wp
               if (.not. hit) cycle
               nf = segment_normal(x1(:, ma), x1(:, mb))
            else if (cached) then
               if (mstamp(k) /= stamp) then
                  call both_normals(nnode, x0, x1, ma, mb, mnrm(:, k))
                  mstamp(k) = stamp
               end if
               call swept_given(x0(:, node), x1(:, node), x0(:, ma), x1(:, ma), x0(:, mb), &
                                x1(:, mb), mnrm(1:2, k), mnrm(3:4, k), depth, hit, tau, alpha, crossed)
               if (.not. (hit .or. crossed)) cycle
               ! at a master node both of whose lines it crossed: paired with the node (vertex rule)
               if (.not. hit) call vertex_entry(nnode, x0, x1, node, k, nseg, seg, link, depth, tau, &
                                                alpha, hit)
               nf = mnrm(3:4, k)
            else
               ! nf: the normal of the segment at x1, as the swept test formed it
               call swept_pair(x0(:, node), x1(:, node), x0(:, ma), x1(:, ma), x0(:, mb), &
                               x1(:, mb), depth, hit, tau, alpha, nf, crossed)
               if (.not. (hit .or. crossed)) cycle
               if (.not. hit) call vertex_entry(nnode, x0, x1, node, k, nseg, seg, link, depth, tau, &
                                                alpha, hit)
            end if
            if (.not. have_nrm) then
               if (cached) then
                  do q = shead(s), shead(s + 1) - 1
                     ks = ssegs(q)
                     if (sstamp(ks) == stamp) cycle
                     call both_normals(nnode, x0, x1, sseg(1, ks), sseg(2, ks), snrm_seg(:, ks))
                     sstamp(ks) = stamp
                  end do
                  snrm(:, s) = node_normal_from(shead, ssegs, s, snrm_seg)
               else
                  call some_node_normals(nnode, x0, nsseg, sseg, nslave, shead, ssegs, 1, [s], snrm)
               end if
               have_nrm = .true.
            end if
            by_side = .not. faces(snrm(:, s), nf, facing)
            if (by_side) then
               ! the facing rule's side test (doc/contact-detection.md, "Facing test")
               if (lazy) then
                  if (.not. side_faces(nnode, x0, sseg, shead, ssegs, s, nf, facing)) cycle
               else if (sides) then
                  if (.not. side_faces(nnode, x0, fseg, fhead, fsegs, s, nf, facing)) cycle
               else
                  cycle
               end if
            end if
            ! paired with k by the side test only, behind k's line at the start, but on the face
            ! across k's end at a convex corner (doc/contact-detection.md, "A node beside a master's
            ! convex corner")
            if (by_side .and. hit .and. mode == DETECT_SWEPT .and. tau == 0.0_wp) then
               if (beside_corner(nnode, x0, nseg, seg, link, k, node, alpha, snrm(:, s), facing)) cycle
            end if
            if (.not. hit) then
               ! off the segment: caught only just past an end at a convex corner whose other face
               ! turns away from the slave ("A node at a master's convex corner")
               if (.not. past_corner(nnode, x0, x1, tau, nseg, seg, link, k, alpha, depth, &
                                     snrm(:, s), facing)) cycle
               alpha = merge(0.0_wp, 1.0_wp, alpha < 0.0_wp)
            end if
            gap = dot_product(x1(:, node) - ((1.0_wp - alpha)*x1(:, ma) + alpha*x1(:, mb)), nf)
            key = [min(ma, mb), max(ma, mb)]
            if (best /= 0) then
               if (tau > btau) cycle
               if (tau == btau) then
                  if (gap < bgap) cycle
                  if (gap == bgap) then
                     if (key(1) > bkey(1)) cycle
                     if (key(1) == bkey(1) .and. key(2) >= bkey(2)) cycle
                  end if
               end if
            end if
            best = k; btau = tau; balpha = alpha; bgap = gap; bkey = key
         end do
         j0 = j
         if (best == 0) cycle
         ncon = ncon + 1
         cslave(ncon) = node
         cseg(ncon) = best
         cmaster(:, ncon) = seg(:, best)
         ctau(ncon) = btau
         ! the normal at the time of contact tau_c (doc/contact-detection.md, "Frozen normal");
         ! a node in contact from the start: the contact point of its predicted position,
         ! blended into the seed's alpha(tau_c) over tau_c < TAU_BLEND (continuous in tau_c)
         if (mode == DETECT_SWEPT .and. btau < TAU_BLEND) then
            w = 1.0_wp - btau/TAU_BLEND
            balpha = (1.0_wp - w)*balpha + &
                     w*end_point(x1(:, node), x1(:, cmaster(1, ncon)), x1(:, cmaster(2, ncon)), balpha)
         end if
         call finish_contact(nnode, x0, x1, merge(btau, 1.0_wp, mode == DETECT_SWEPT), node, snrm(:, s), &
                             nseg, seg, link, best, balpha, facing, cend(ncon), calpha(ncon), &
                             cnormal(:, ncon), cgap(ncon))
      end do
   end subroutine detect_pairs

   !> Whether a slave whose gap test passed on segment k at tau but whose contact point alpha lies
   !> off the segment is held at the segment's end (doc/contact-detection.md, "A node at a
   !> master's convex corner"): the contact point within HOLD_PAST of k's length past an end of
   !> k, the segment
   !> across that end turning left from k (a convex corner of the master: its body on the left)
   !> and failing the facing test with the slave's normal ns (it cannot hold the slave), and ns
   !> within 30 degrees of -n_k (a smooth part of the slave's surface facing k head-on, not a
   !> corner of its own body). Positions at x0 + tau (x1 - x0).
   pure logical function past_corner(nnode, x0, x1, tau, nseg, seg, link, k, alpha, depth, ns, &
                                     facing) result(ok)
      integer, intent(in) :: nnode, nseg, k
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), tau, alpha, depth, ns(2), facing
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      !> how far past the end a slave is held, in lengths of k: a node that drifted off the
      !> corner by round-off or a micrometre (the punch's), not one sliding past it (colliding
      !> bodies, whose hold made energy)
      real(wp), parameter :: HOLD_PAST = 1.0e-2_wp
      real(wp) :: t(2), tn(2), len, turn, pa(2), pb(2)
      integer :: nbr

      ok = .false.
      if (ns(1) == 0.0_wp .and. ns(2) == 0.0_wp) return
      t = at(seg(2, k)) - at(seg(1, k))
      len = sqrt(dot_product(t, t))
      if (.not. (len > 0.0_wp)) return
      ! the slave faces segment k head-on (within 30 degrees): not a corner of its own body
      ! meeting the master's corner (two bars of equal height meeting end to end)
      if (.not. (dot_product(ns, t)**2 <= 0.25_wp*len*len .and. ns(1)*t(2) - ns(2)*t(1) < 0.0_wp)) return
      if (alpha < 0.0_wp .and. -alpha <= HOLD_PAST) then
         nbr = link(1, k)
         if (nbr <= 0) return
         pa = at(seg(1, nbr)); pb = at(seg(2, nbr))
         tn = pb - pa
         turn = tn(1)*t(2) - tn(2)*t(1)
      else if (alpha > 1.0_wp .and. alpha - 1.0_wp <= HOLD_PAST) then
         nbr = link(2, k)
         if (nbr <= 0) return
         pa = at(seg(1, nbr)); pb = at(seg(2, nbr))
         tn = pb - pa
         turn = t(1)*tn(2) - t(2)*tn(1)
      else
         return
      end if
      if (.not. (turn > 0.0_wp)) return
      ok = .not. faces(ns, segment_normal(pa, pb), facing)
   contains
      !> Position of node j at x0 + tau (x1 - x0).
      pure function at(j) result(p)
         integer, intent(in) :: j
         real(wp) :: p(2)
         p = x0(:, j) + tau*(x1(:, j) - x0(:, j))
      end function at
   end function past_corner

   !> Whether a hit of a slave on segment k at tau = 0 (a slave behind k's line at x0, g_k < 0),
   !> which k's facing test passed by the side test only, is dropped because the slave lies
   !> beside the master's convex corner at k's end v nearest its projection alpha
   !> (doc/contact-detection.md, "A node beside a master's convex corner"): k', the segment
   !> across v, turns left from k (convex at v), faces the slave's normal ns, the slave projects
   !> onto k', and it is less deep behind the line of k' than behind k's, g_k' > g_k (in front
   !> of it, or nearer it: near v the master is the intersection of the two half-planes and k'
   !> its nearest face). Positions at x0.
   pure logical function beside_corner(nnode, x0, nseg, seg, link, k, node, alpha, ns, facing) result(drop)
      integer, intent(in) :: nnode, nseg, k, node
      real(wp), intent(in) :: x0(2, nnode), alpha, ns(2), facing
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      real(wp) :: t(2), tn(2), g, gn, turn, nn(2), an
      integer :: nbr, ma, mb
      logical :: inside

      drop = .false.
      ma = seg(1, k); mb = seg(2, k)
      g = dot_product(x0(:, node) - x0(:, ma), segment_normal(x0(:, ma), x0(:, mb)))
      if (.not. (g < 0.0_wp)) return
      nbr = merge(link(1, k), link(2, k), alpha < 0.5_wp)
      if (nbr <= 0) return
      if (seg(1, nbr) == node .or. seg(2, nbr) == node) return
      t = x0(:, mb) - x0(:, ma)
      tn = x0(:, seg(2, nbr)) - x0(:, seg(1, nbr))
      if (alpha < 0.5_wp) then
         turn = tn(1)*t(2) - tn(2)*t(1)
      else
         turn = t(1)*tn(2) - t(2)*tn(1)
      end if
      if (.not. (turn > 0.0_wp)) return
      nn = segment_normal(x0(:, seg(1, nbr)), x0(:, seg(2, nbr)))
      if (.not. faces(ns, nn, facing)) return
      ! the slave projects onto k' (its nearest point on the master is on k', not past its far end)
      call project(x0(:, node), x0(:, seg(1, nbr)), x0(:, seg(2, nbr)), an, inside)
      if (.not. inside) return
      gn = dot_product(x0(:, node) - x0(:, seg(1, nbr)), nn)
      drop = gn > g
   end function beside_corner

   !> The vertex rule (doc/contact-detection.md, "Vertex rule", V.1-V.2): slave `node` crossed the
   !> line of segment k (swept test, at tau, projection alpha) but projects past its end node m;
   !> when the slave also crossed the line of the neighbour segment at m and projects past m on
   !> it, it is behind both lines next to m, inside the master at its corner m: a hit at
   !> m (alpha 0 or 1, so finish_contact gives the master node normal), at the later of the two
   !> crossing times. On return hit tells whether the rule holds; tau and alpha are then set.
   pure subroutine vertex_entry(nnode, x0, x1, node, k, nseg, seg, link, depth, tau, alpha, hit)
      integer, intent(in) :: nnode, node, k, nseg, seg(2, nseg), link(2, nseg)
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), depth
      real(wp), intent(inout) :: tau, alpha
      logical, intent(out) :: hit
      real(wp) :: taun, alphan
      integer :: nb, m, na, nbb
      logical :: crossed, inside

      hit = .false.
      if (.not. (alpha < 0.0_wp .or. alpha > 1.0_wp)) return
      if (alpha < 0.0_wp) then
         nb = link(1, k)
         m = seg(1, k)
      else
         nb = link(2, k)
         m = seg(2, k)
      end if
      if (nb <= 0) return
      na = seg(1, nb); nbb = seg(2, nb)
      if (na == node .or. nbb == node) return
      call swept_given(x0(:, node), x1(:, node), x0(:, na), x1(:, na), x0(:, nbb), x1(:, nbb), &
                       segment_normal(x0(:, na), x0(:, nbb)), segment_normal(x1(:, na), x1(:, nbb)), &
                       depth, inside, taun, alphan, crossed)
      if (.not. crossed) return
      ! past m on the neighbour too (V.2); within it, the neighbour's own test pairs the slave
      if (alpha < 0.0_wp) then
         if (.not. (alphan > 1.0_wp)) return
         alpha = 0.0_wp
      else
         if (.not. (alphan < 0.0_wp)) return
         alpha = 1.0_wp
      end if
      tau = max(tau, taun)
      hit = .true.
   end subroutine vertex_entry

   !> The side test of the facing rule (doc/contact-detection.md, "Facing test", eq. F.1): true
   !> when a segment of the slave surface at slave s (its node -> segments lists head, segs)
   !> faces the master normal n at x0, n_k . n < facing with n_k the segment's unit normal
   !> (segment_normal, as the node normal's sum forms it). A convex corner whose node normal is
   !> tilted too far from n, one face of it turned to the master, is then still paired.
   pure logical function side_faces(nnode, x0, seg, head, segs, s, n, facing) result(ok)
      integer, intent(in) :: nnode, seg(2, *), head(*), segs(*), s
      real(wp), intent(in) :: x0(2, nnode), n(2), facing
      real(wp) :: nk(2)
      integer :: q, ks
      ok = .false.
      do q = head(s), head(s + 1) - 1
         ks = segs(q)
         nk = segment_normal(x0(:, seg(1, ks)), x0(:, seg(2, ks)))
         if (nk(1) == 0.0_wp .and. nk(2) == 0.0_wp) cycle
         if (dot_product(nk, n) < facing) then
            ok = .true.
            return
         end if
      end do
   end function side_faces

   !> Unit normals of the segment ma -> mb at x0 (n(1:2)) and at x1 (n(3:4)).
   pure subroutine both_normals(nnode, x0, x1, ma, mb, n)
      integer, intent(in) :: nnode, ma, mb
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode)
      real(wp), intent(out) :: n(4)
      n(1:2) = segment_normal(x0(:, ma), x0(:, mb))
      n(3:4) = segment_normal(x1(:, ma), x1(:, mb))
   end subroutine both_normals

   !> The unit normals of the segments of candidates cand(:, 1:ncand) at x0 (mnrm(1:2, k)) and
   !> x1 (mnrm(3:4, k)) that search `stamp` has not formed yet, as detect_pairs forms them at
   !> their first use: the segment-normal cache of detect_pairs filled beforehand, so that the
   !> narrow phase of several passes can run concurrently and only read it (src/exic/contact/narrow.f90).
   pure subroutine candidate_normals(nnode, x0, x1, nseg, seg, ncand, cand, stamp, mnrm, mstamp)
      integer, intent(in) :: nnode, nseg, ncand, stamp
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode)
      integer, intent(in) :: seg(2, nseg), cand(2, ncand)
      real(wp), intent(inout) :: mnrm(4, nseg)
      integer, intent(inout) :: mstamp(nseg)
      integer :: j, k
      do j = 1, ncand
         k = cand(2, j)
         if (mstamp(k) == stamp) cycle
         call both_normals(nnode, x0, x1, seg(1, k), seg(2, k), mnrm(:, k))
         mstamp(k) = stamp
      end do
   end subroutine candidate_normals

   !> Projection of xs1 on the segment xa1-xb1, clamped to it (alpha_c for a zero-length segment).
   pure real(wp) function end_point(xs1, xa1, xb1, alpha_c) result(alpha)
      real(wp), intent(in) :: xs1(2), xa1(2), xb1(2), alpha_c
      real(wp) :: t(2), tt
      t = xb1 - xa1
      tt = dot_product(t, t)
      alpha = alpha_c
      if (tt > 0.0_wp) alpha = min(max(dot_product(xs1 - xa1, t)/tt, 0.0_wp), 1.0_wp)
   end function end_point

   !> Snap a contact point near a segment end to that end, pick the frozen normal (segment
   !> normal, or master node normal at an end) at the positions of the time of
   !> contact, x0 + tau (x1 - x0) (tau = 0: x(n+1); tau = 1, static detection: the predicted
   !> x1), and the predicted gap along it.
   pure subroutine finish_contact(nnode, x0, x1, tau, node, ns, nseg, seg, link, k, alpha_in, &
                                  facing, at_end, alpha, n, gap)
      integer, intent(in) :: nnode, node, nseg, k
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), tau, ns(2), alpha_in, facing
      integer, intent(in) :: seg(2, nseg), link(2, nseg)
      logical, intent(out) :: at_end
      real(wp), intent(out) :: alpha, n(2), gap
      real(wp) :: nb(2), navg(2)
      integer :: nbr, ma, mb

      ma = seg(1, k); mb = seg(2, k)
      alpha = alpha_in
      nbr = 0
      at_end = .false.
      if (alpha <= ALPHA_TOL) then
         at_end = .true.
         alpha = 0.0_wp
         nbr = link(1, k)
      else if (alpha >= 1.0_wp - ALPHA_TOL) then
         at_end = .true.
         alpha = 1.0_wp
         nbr = link(2, k)
      end if
      n = segment_normal(at(ma), at(mb))
      if (nbr > 0) then
         if (seg(1, nbr) /= node .and. seg(2, nbr) /= node) then
            nb = segment_normal(at(seg(1, nbr)), at(seg(2, nbr)))
            if (faces(ns, nb, facing)) then
               navg = average_normal(n, nb)
               if (any(navg /= 0.0_wp)) n = navg
            end if
         end if
      end if
      gap = dot_product(x1(:, node) - ((1.0_wp - alpha)*x1(:, ma) + alpha*x1(:, mb)), n)
   contains
      !> Position of node j at the time of contact (exactly x1 at tau = 1, x0 at tau = 0).
      pure function at(j) result(p)
         integer, intent(in) :: j
         real(wp) :: p(2)
         if (tau == 1.0_wp) then
            p = x1(:, j)
         else
            p = x0(:, j) + tau*(x1(:, j) - x0(:, j))
         end if
      end function at
   end subroutine finish_contact

   !> Narrow phase into a contact set (grown to nslave entries when needed); see
   !> detect_pairs for the arguments and the rules.
   subroutine detect_contacts(cs, mode, nnode, x0, x1, nslave, slaves, snrm, nseg, seg, &
                              link, ncand, cand, depth, facing, nsseg, sseg, shead, ssegs, &
                              stamp, mnrm, mstamp, snrm_seg, sstamp, fseg, fhead, fsegs)
      type(contact_set_t), intent(inout) :: cs
      integer, intent(in) :: mode, nnode, nslave, nseg, ncand
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), depth, facing
      real(wp), intent(inout) :: snrm(2, nslave)
      integer, intent(in) :: slaves(nslave), seg(2, nseg), link(2, nseg), cand(2, ncand)
      integer, intent(in), optional :: nsseg
      integer, intent(in), optional :: sseg(2, *), shead(*), ssegs(*)
      integer, intent(in), optional :: stamp
      real(wp), intent(inout), optional :: mnrm(4, *), snrm_seg(4, *)
      integer, intent(inout), optional :: mstamp(*), sstamp(*)
      integer, intent(in), optional :: fseg(2, *), fhead(*), fsegs(*)
      integer :: cap

      cap = 0
      if (allocated(cs%slave)) cap = size(cs%slave)
      if (cap < nslave .or. cap == 0) then
         if (allocated(cs%slave)) then
            deallocate (cs%slave, cs%master, cs%seg, cs%at_end, cs%alpha, cs%normal, &
                        cs%tau, cs%gap)
         end if
         cap = max(nslave, 1)
         allocate (cs%slave(cap), cs%master(2, cap), cs%seg(cap), cs%at_end(cap), &
                   cs%alpha(cap), cs%normal(2, cap), cs%tau(cap), cs%gap(cap))
      end if
      call detect_pairs(mode, nnode, x0, x1, nslave, slaves, snrm, nseg, seg, link, ncand, &
                        cand, depth, facing, cs%n, cs%slave, cs%seg, cs%master, cs%at_end, &
                        cs%alpha, cs%normal, cs%tau, cs%gap, nsseg, sseg, shead, ssegs, &
                        stamp, mnrm, mstamp, snrm_seg, sstamp, fseg, fhead, fsegs)
   end subroutine detect_contacts

end module exic_contact_detect
