!> Narrow phase of the contact search: swept (seed section 6, eq. 6.1-6.6) and static
!> node-to-segment detection, with the corner rule and the facing test.
!>
!> The pair tests themselves (the gap quadratic of eq. 6.1-6.6, its first crossing, the
!> projection and its tolerance, the facing test) are in exic_contact_swept.
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
   use exic_contact_concave_rule, only: concave_neighbour, concave_entry, concave_vertex_normal
   use exic_contact_swept, only: ALPHA_TOL, gap_coefficients, first_crossing, alpha_tolerance, project, &
                                 swept_pair, swept_given, static_pair, faces, end_point
   implicit none
   private

   ! the pair tests, for the callers of the narrow phase
   public :: ALPHA_TOL, gap_coefficients, first_crossing, swept_pair, static_pair, alpha_tolerance
   public :: detect_pairs, detect_contacts, contact_set_t, candidate_normals

   !> Default facing limit: a slave whose own outward normal ns gives ns . n >= FACING_LIMIT
   !> with the master normal n is not paired (0: the two must face each other).
   real(wp), parameter, public :: FACING_LIMIT = 0.0_wp
   !> A slave in contact from the start of a step (tau_c = 0) takes as contact point the
   !> projection of its predicted position on the predicted segment; for 0 < tau_c < TAU_BLEND
   !> the contact point moves linearly from that to the seed's alpha(tau_c), so that rounding of
   !> tau_c near 0 never switches between the two (doc/contact-detection.md).
   real(wp), parameter, public :: TAU_BLEND = 0.01_wp
   !> Wedge rule (doc/contact-detection.md, "A slave between two faces", W.1): a slave's other
   !> hit on a segment that shares no node with the chosen one is a second contact when the
   !> slave, moved onto the chosen segment's line along its normal, would still be behind the
   !> other segment's line by more than WEDGE_TOL of its length; MAX_HITS hits of a slave are
   !> kept for it.
   real(wp), parameter :: WEDGE_TOL = 1.0e-3_wp
   integer, parameter :: MAX_HITS = 8

   !> Accepted contacts of one detection pass, in slave order: one per slave node, two for a
   !> slave between two faces (swept mode, the wedge rule of detect_pairs).
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

   !> Narrow phase over candidate pairs cand(:, 1:ncand) (slave index, segment index),
   !> sorted by slave: one contact per slave (two under the wedge rule below), written in slave
   !> order (at most 2 nslave).
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
   !> that end under the conditions of past_corner. Wedge rule (swept mode): of the slave's other
   !> hits on segments sharing no node with the chosen one, the first by the same keys that the
   !> chosen contact would leave behind its line (W.1, WEDGE_TOL) is a second contact, written
   !> after the first.
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
      integer, intent(out) :: cslave(2*nslave), cseg(2*nslave), cmaster(2, 2*nslave)
      logical, intent(out) :: cend(2*nslave)
      real(wp), intent(out) :: calpha(2*nslave), cnormal(2, 2*nslave), ctau(2*nslave), cgap(2*nslave)
      integer :: j, j0, jend, s, k, node, ma, mb, best, bkey(2), key(2), q, ks
      real(wp) :: tau, alpha, gap, nf(2), btau, balpha, bgap, w
      logical :: hit, lazy, have_nrm, cached, sides, crossed, within, swapped
      ! the slave's hits for the wedge rule (swept mode): segment, tau, alpha, gap, key, normal
      integer :: nh, hk(MAX_HITS), hkey(2, MAX_HITS), i, i2, iw
      real(wp) :: htau(MAX_HITS), halpha(MAX_HITS), hgap(MAX_HITS), hnf(2, MAX_HITS), bnf(2)

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
         bnf = 0.0_wp
         nh = 0
         have_nrm = .not. lazy
         jend = j0
         do while (jend < ncand)
            if (cand(1, jend + 1) /= s) exit
            jend = jend + 1
         end do
         j = j0
         do while (j <= ncand)
            if (cand(1, j) /= s) exit
            k = cand(2, j)
            j = j + 1
            ma = seg(1, k); mb = seg(2, k)
            if (ma == node .or. mb == node) cycle
            within = .false.
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
               within = hit
               ! at a master node both of whose lines it crossed: paired with the node (vertex rule)
               if (.not. hit) call vertex_entry(nnode, x0, x1, node, k, nseg, seg, link, depth, tau, &
                                                alpha, hit)
               ! entering a segment from the master's concave corner at its end (concave rule)
               if (.not. hit) call concave_entry(nnode, x1, node, nseg, seg, link, k, ALPHA_TOL, alpha, hit)
               nf = mnrm(3:4, k)
            else
               ! nf: the normal of the segment at x1, as the swept test formed it
               call swept_pair(x0(:, node), x1(:, node), x0(:, ma), x1(:, ma), x0(:, mb), &
                               x1(:, mb), depth, hit, tau, alpha, nf, crossed)
               if (.not. (hit .or. crossed)) cycle
               within = hit
               if (.not. hit) call vertex_entry(nnode, x0, x1, node, k, nseg, seg, link, depth, tau, &
                                                alpha, hit)
               ! entering a segment from the master's concave corner at its end (concave rule)
               if (.not. hit) call concave_entry(nnode, x1, node, nseg, seg, link, k, ALPHA_TOL, alpha, hit)
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
            if (.not. faces(snrm(:, s), nf, facing)) then
               ! the facing rule's side test (doc/contact-detection.md, "Facing test")
               if (lazy) then
                  if (.not. side_faces(nnode, x0, sseg, shead, ssegs, s, nf, facing)) cycle
               else if (sides) then
                  if (.not. side_faces(nnode, x0, fseg, fhead, fsegs, s, nf, facing)) cycle
               else
                  cycle
               end if
            end if
            if (within .and. tau == 0.0_wp .and. mode /= DETECT_STATIC) then
               ! behind k from the start, but another candidate segment that does not hold it is
               ! nearer: k is not its nearest face ("Nearest face of a slave behind a segment")
               if (nearer_face(nnode, x0, x1, node, k, nseg, seg, link, ncand, cand, j0, jend, alpha, &
                               depth, snrm(:, s), facing)) cycle
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
            if (mode == DETECT_SWEPT) then
               ! kept for the wedge rule: the MAX_HITS first by the keys below
               if (nh < MAX_HITS) then
                  nh = nh + 1
                  iw = nh
               else
                  iw = 1
                  do i = 2, nh
                     if (before(htau(iw), hgap(iw), hkey(:, iw), htau(i), hgap(i), hkey(:, i))) iw = i
                  end do
                  if (before(htau(iw), hgap(iw), hkey(:, iw), tau, gap, key)) iw = 0
               end if
               if (iw > 0) then
                  hk(iw) = k; htau(iw) = tau; halpha(iw) = alpha; hgap(iw) = gap
                  hkey(:, iw) = key; hnf(:, iw) = nf
               end if
            end if
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
            best = k; btau = tau; balpha = alpha; bgap = gap; bkey = key; bnf = nf
         end do
         j0 = j
         if (best == 0) cycle
         ! a node in contact from the start whose predicted position lies past an end of its
         ! segment in a concave corner of the master: paired with the segment it slides onto
         ! (doc/contact-detection.md, "A node sliding into a master's concave corner")
         swapped = .false.
         if (mode == DETECT_SWEPT .and. btau < TAU_BLEND) then
            call concave_neighbour(nnode, x0, x1, btau, node, snrm(:, s), nseg, seg, link, best, &
                                   facing, ALPHA_TOL, k, alpha)
            if (k > 0) then
               best = k
               balpha = alpha
               swapped = .true.
            end if
         end if
         call emit(best, btau, balpha)
         ! a slave the concave rule moved onto the neighbour segment has its contact (C.1)
         if (swapped) cycle
         ! the wedge rule (doc/contact-detection.md, "A slave between two faces", W.1): the first
         ! by the same keys of the other hits that the chosen contact leaves behind their line is
         ! a second contact of the slave
         i2 = 0
         do i = 1, nh
            if (hk(i) == best) cycle
            ! two faces that meet at a master node: that node's own constraints (the vertex rule,
            ! the master node normal, its pass as a slave) hold the corner
            if (any(seg(:, hk(i)) == seg(1, best)) .or. any(seg(:, hk(i)) == seg(2, best))) cycle
            ! still behind the line of hk(i) once moved onto the chosen segment's line (W.1)
            if (hgap(i) - bgap*dot_product(hnf(:, i), bnf) >= -WEDGE_TOL*norm2(x1(:, seg(2, hk(i))) - &
                                                                         x1(:, seg(1, hk(i))))) cycle
            if (i2 /= 0) then
               if (.not. before(htau(i), hgap(i), hkey(:, i), htau(i2), hgap(i2), hkey(:, i2))) cycle
            end if
            i2 = i
         end do
         if (i2 /= 0) call emit(hk(i2), htau(i2), halpha(i2))
      end do
   contains
      !> Write the contact of slave s (node) with segment kk at tau tc, contact point al.
      subroutine emit(kk, tc, al_in)
         integer, intent(in) :: kk
         real(wp), intent(in) :: tc, al_in
         real(wp) :: al
         al = al_in
         ncon = ncon + 1
         cslave(ncon) = node
         cseg(ncon) = kk
         cmaster(:, ncon) = seg(:, kk)
         ctau(ncon) = tc
         ! the normal at the time of contact tau_c (doc/contact-detection.md, "Frozen normal");
         ! a node in contact from the start: the contact point of its predicted position,
         ! blended into the seed's alpha(tau_c) over tau_c < TAU_BLEND (continuous in tau_c)
         if (mode == DETECT_SWEPT .and. tc < TAU_BLEND) then
            w = 1.0_wp - tc/TAU_BLEND
            al = (1.0_wp - w)*al + &
                 w*end_point(x1(:, node), x1(:, cmaster(1, ncon)), x1(:, cmaster(2, ncon)), al)
         end if
         call finish_contact(nnode, x0, x1, merge(tc, 1.0_wp, mode == DETECT_SWEPT), node, snrm(:, s), &
                             nseg, seg, link, kk, al, facing, cend(ncon), calpha(ncon), &
                             cnormal(:, ncon), cgap(ncon))
      end subroutine emit
   end subroutine detect_pairs

   !> Whether hit 1 (tau, predicted gap, sorted node pair) comes before hit 2 by the keys of
   !> detect_pairs: the smaller tau, then the larger gap, then the lower node pair.
   pure logical function before(tau1, gap1, key1, tau2, gap2, key2)
      real(wp), intent(in) :: tau1, gap1, tau2, gap2
      integer, intent(in) :: key1(2), key2(2)
      if (tau1 /= tau2) then
         before = tau1 < tau2
      else if (gap1 /= gap2) then
         before = gap1 > gap2
      else if (key1(1) /= key2(1)) then
         before = key1(1) < key2(1)
      else
         before = key1(2) < key2(2)
      end if
   end function before

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

   !> The nearest-face rule (doc/contact-detection.md, "Nearest face of a slave behind a segment",
   !> N.1-N.3): slave `node` is behind segment k at x0 (gap c0 = (xs - xa) . n_k < 0, within
   !> depth: a contact from the start of the step, tau_c = 0) with contact point alpha on k. True
   !> when another candidate segment k2 of the slave (cand(2, j0:jend): its candidate pairs)
   !> lies nearer to it, abs(g2_0) < -c0 with g2_0 its gap at x0, faces it (ns . n2_f < facing),
   !> has its projection at x0 (within the tolerance of a hit) and does not hold it from the start
   !> itself, because the slave is
   !>   (N.2) behind k2 and leaving it (g2_0 <= 0 < g2_1, g2_1 its gap at x1), or
   !>   (N.3) in front of k2 (g2_0 > 0), k2 the neighbour of k across a convex corner of the master;
   !> k is then not the slave's nearest face and the test of k2 decides (a crossing of k2 later in
   !> the step, or no contact for a slave leaving the master through k2 or outside it). A k2 through
   !> the node of k that the contact point is snapped to is not counted when the slave lies at that
   !> node (within ALPHA_TOL of k's length across k as well): the master node normal takes both.
   pure logical function nearer_face(nnode, x0, x1, node, k, nseg, seg, link, ncand, cand, j0, jend, &
                                     alpha, depth, ns, facing) result(ok)
      integer, intent(in) :: nnode, node, k, nseg, seg(2, nseg), link(2, nseg), ncand, cand(2, ncand), j0, jend
      real(wp), intent(in) :: x0(2, nnode), x1(2, nnode), alpha, depth, ns(2), facing
      real(wp) :: nk(2), n0(2), n1(2), t(2), tn(2), c0, g0, g1, al, turn
      integer :: q, k2, pa, pb, snapped
      logical :: inside

      ok = .false.
      nk = segment_normal(x0(:, seg(1, k)), x0(:, seg(2, k)))
      c0 = dot_product(x0(:, node) - x0(:, seg(1, k)), nk)
      if (.not. (c0 < 0.0_wp .and. c0 >= -depth)) return
      ! a slave at the node of k that its contact point is snapped to (within ALPHA_TOL of k's
      ! length along k and across it) takes the master node normal of both faces already
      snapped = 0
      if (-c0 <= ALPHA_TOL*norm2(x0(:, seg(2, k)) - x0(:, seg(1, k)))) then
         if (alpha <= ALPHA_TOL) snapped = seg(1, k)
         if (alpha >= 1.0_wp - ALPHA_TOL) snapped = seg(2, k)
      end if
      do q = j0, jend
         k2 = cand(2, q)
         if (k2 == k) cycle
         pa = seg(1, k2); pb = seg(2, k2)
         if (pa == node .or. pb == node .or. pa == snapped .or. pb == snapped) cycle
         n0 = segment_normal(x0(:, pa), x0(:, pb))
         if (n0(1) == 0.0_wp .and. n0(2) == 0.0_wp) cycle
         g0 = dot_product(x0(:, node) - x0(:, pa), n0)
         if (.not. (abs(g0) < -c0)) cycle
         n1 = segment_normal(x1(:, pa), x1(:, pb))
         if (.not. faces(ns, n1, facing)) cycle
         if (g0 <= 0.0_wp) then
            ! (N.2): behind k2 too; held by it from the start (g2_1 <= 0), the hits are ranked by
            ! their predicted gaps
            g1 = dot_product(x1(:, node) - x1(:, pa), n1)
            if (.not. (g1 > 0.0_wp)) cycle
         else
            ! (N.3): in front of k2, outside the master, when k2 is k's neighbour at a convex corner
            t = x0(:, seg(2, k)) - x0(:, seg(1, k))
            tn = x0(:, pb) - x0(:, pa)
            if (k2 == link(1, k)) then
               turn = tn(1)*t(2) - tn(2)*t(1)
            else if (k2 == link(2, k)) then
               turn = t(1)*tn(2) - t(2)*tn(1)
            else
               cycle
            end if
            if (.not. (turn > 0.0_wp)) cycle
         end if
         call project(x0(:, node), x0(:, pa), x0(:, pb), al, inside)
         if (.not. inside) cycle
         ok = .true.
         return
      end do
   end function nearer_face

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
               ! in a concave corner: towards the corner from the predicted position (concave rule)
               call concave_vertex_normal(nnode, x1, node, nseg, seg, k, nbr, alpha == 0.0_wp, n)
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
      if (cap < 2*nslave .or. cap == 0) then
         if (allocated(cs%slave)) then
            deallocate (cs%slave, cs%master, cs%seg, cs%at_end, cs%alpha, cs%normal, &
                        cs%tau, cs%gap)
         end if
         cap = max(2*nslave, 1)
         allocate (cs%slave(cap), cs%master(2, cap), cs%seg(cap), cs%at_end(cap), &
                   cs%alpha(cap), cs%normal(2, cap), cs%tau(cap), cs%gap(cap))
      end if
      call detect_pairs(mode, nnode, x0, x1, nslave, slaves, snrm, nseg, seg, link, ncand, &
                        cand, depth, facing, cs%n, cs%slave, cs%seg, cs%master, cs%at_end, &
                        cs%alpha, cs%normal, cs%tau, cs%gap, nsseg, sseg, shead, ssegs, &
                        stamp, mnrm, mstamp, snrm_seg, sstamp, fseg, fhead, fsegs)
   end subroutine detect_contacts

end module exic_contact_detect
