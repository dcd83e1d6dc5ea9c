!> The pair tests of the narrow phase: swept (seed section 6, eq. 6.1-6.6) and static
!> node-to-segment tests of one slave node against one master segment, the projection of the
!> contact point with its tolerance, and the facing test. exic_contact_detect chooses among a
!> slave's hits (doc/contact-detection.md).
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
module exic_contact_swept
   use exic_base_kinds, only: wp
   use exic_mesh_boundary, only: segment_normal
   implicit none
   private

   public :: gap_coefficients, first_crossing, alpha_tolerance, project, swept_pair, swept_given
   public :: static_pair, faces, end_point

   !> Accepted contact points may lie this share of the segment length beyond either end;
   !> a contact point this close to an end is taken to be at the end (master node).
   real(wp), parameter, public :: ALPHA_TOL = 1.0e-8_wp

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

   !> Projection of xs1 on the segment xa1-xb1, clamped to it (alpha_c for a zero-length segment).
   pure real(wp) function end_point(xs1, xa1, xb1, alpha_c) result(alpha)
      real(wp), intent(in) :: xs1(2), xa1(2), xb1(2), alpha_c
      real(wp) :: t(2), tt
      t = xb1 - xa1
      tt = dot_product(t, t)
      alpha = alpha_c
      if (tt > 0.0_wp) alpha = min(max(dot_product(xs1 - xa1, t)/tt, 0.0_wp), 1.0_wp)
   end function end_point

end module exic_contact_swept
