!> The 4-node plane-strain quadrilateral in the total Lagrangian form: reference gradients,
!> internal force (2x2 Gauss, or one point with Flanagan-Belytschko stiffness hourglass
!> control), row-sum lumped mass, the stable time step and element stress for output.
!>
!> Plain kernels on explicit-shape arrays; every call works on one element set of `nel`
!> elements sharing one material. `conn(4, nel)` holds global node numbers counter-clockwise,
!> `x0(2, nnode)` the reference coordinates, `u(2, nnode)` the displacements, `x(2, nnode)` the
!> current coordinates. Local node a has natural coordinates (xi_a, eta_a) = (-1,-1), (1,-1),
!> (1,1), (-1,1). Gauss points of the 2x2 rule are numbered in the same order, at +-1/sqrt(3).
!>
!> Reference data (from `q4_reference`), with nq = 2 (2x2 Gauss) or nq = 1 (one point):
!>   gdn(8, nq*nq, nel)  dN_a/dX in 1:4 and dN_a/dY in 5:8 at each integration point;
!>                        for nq = 1 the mean (Flanagan-Belytschko) gradients b_a/A0
!>   wdj(nq*nq, nel)     weight x det J0 (for nq = 1: the reference area A0);
!>                        sum(wdj(:, e)) is the reference area for either rule
!>   gam(4, nel)         hourglass shape vector, orthogonal to every affine nodal field
!>
!> Integer flags: `ebad` is the first (local) element found inverted, 0 if none.
!>
!> The force kernels work on blocks of NBLOCK elements, as DYNA codes do: first the
!> deformation gradients of every quadrature point of the block, then one call of the
!> material's kernel (src/exic/material) on all of them, then the nodal forces. A material
!> law is therefore one pure kernel on plain arrays of points, shared by both quadratures.
module exic_element_quad4
   use exic_base_kinds, only: wp
   use exic_material_neohookean, only: nh_piola, nh_cauchy, nh_wave_speed2
   implicit none
   private

   public :: q4_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, q4_stable_dt, q4_stress

   real(wp), parameter :: xin(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]   !< xi_a
   real(wp), parameter :: etn(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]   !< eta_a
   real(wp), parameter :: hgv(4) = [1.0_wp, -1.0_wp, 1.0_wp, -1.0_wp]   !< hourglass base vector h
   real(wp), parameter :: gq = 0.57735026918962576451_wp                 !< 1/sqrt(3)
   !> Elements per block of the force kernels: the block's points go to the material kernel in
   !> one call (its work arrays, 4 x NBLOCK points x 11 values, stay in the L1 cache).
   integer, parameter :: NBLOCK = 32

contains

   !> Reference shape-function gradients, integration weights and hourglass vectors.
   !>
   !> nq = 2: gradients at the 4 Gauss points and wdj = det J0 (unit weights).
   !> nq = 1: b_a / A0 with the mean-strain vectors b_xa = 1/2 (Y_{a+1} - Y_{a-1}),
   !> b_ya = 1/2 (X_{a-1} - X_{a+1}) (exact mean of grad N_a over the element), wdj = A0.
   !> gam_a = 1/4 (h_a - (h.X) b_xa/A0 - (h.Y) b_ya/A0), h = (1,-1,1,-1), for either rule.
   !> ebad: first element with det J0 <= 0 at a corner (det J0 is bilinear's linear function of
   !> xi, eta, so corners bound it everywhere, Gauss points included); 0 if none.
   pure subroutine q4_reference(nq, nel, nnode, conn, x0, gdn, wdj, gam, ebad)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode)
      real(wp), intent(out) :: gdn(8, nq*nq, nel)
      real(wp), intent(out) :: wdj(nq*nq, nel)
      real(wp), intent(out) :: gam(4, nel)
      integer, intent(out) :: ebad
      real(wp) :: xe(4), ye(4), bx(4), by(4), a0, hx, hy, dj, dnx(4), dny(4)
      integer :: e, g, a

      ebad = 0
      do e = 1, nel
         xe = x0(1, conn(:, e))
         ye = x0(2, conn(:, e))
         do a = 1, 4
            call grad_at(xe, ye, xin(a), etn(a), dnx, dny, dj)
            if (dj <= 0.0_wp .and. ebad == 0) ebad = e
         end do
         bx = 0.5_wp*[ye(2) - ye(4), ye(3) - ye(1), ye(4) - ye(2), ye(1) - ye(3)]
         by = 0.5_wp*[xe(4) - xe(2), xe(1) - xe(3), xe(2) - xe(4), xe(3) - xe(1)]
         a0 = sum(bx*xe)
         if (a0 <= 0.0_wp) then
            if (ebad == 0) ebad = e
            a0 = 1.0_wp
         end if
         hx = sum(hgv*xe)
         hy = sum(hgv*ye)
         gam(:, e) = 0.25_wp*(hgv - (hx*bx + hy*by)/a0)
         if (nq == 1) then
            gdn(1:4, 1, e) = bx/a0
            gdn(5:8, 1, e) = by/a0
            wdj(1, e) = a0
         else
            do g = 1, 4
               call grad_at(xe, ye, gq*xin(g), gq*etn(g), dnx, dny, dj)
               if (dj <= 0.0_wp) dj = 1.0_wp
               gdn(1:4, g, e) = dnx
               gdn(5:8, g, e) = dny
               wdj(g, e) = dj
            end do
         end if
      end do
   end subroutine q4_reference

   !> dN_a/dX, dN_a/dY and det J0 of the element (xe, ye) at natural point (xi, eta).
   pure subroutine grad_at(xe, ye, xi, eta, dnx, dny, dj)
      real(wp), intent(in) :: xe(4), ye(4), xi, eta
      real(wp), intent(out) :: dnx(4), dny(4), dj
      real(wp) :: dxi(4), deta(4), j11, j12, j21, j22, r
      dxi = 0.25_wp*xin*(1.0_wp + etn*eta)
      deta = 0.25_wp*etn*(1.0_wp + xin*xi)
      j11 = sum(dxi*xe)
      j12 = sum(dxi*ye)
      j21 = sum(deta*xe)
      j22 = sum(deta*ye)
      dj = j11*j22 - j12*j21
      r = 1.0_wp/merge(dj, 1.0_wp, dj /= 0.0_wp)
      dnx = (j22*dxi - j12*deta)*r
      dny = (j11*deta - j21*dxi)*r
   end subroutine grad_at

   !> Internal force with 2x2 Gauss quadrature: f_ia += sum_g wdj_g P_iJ(F_g) dN_a/dX_J.
   !>
   !> F = 1 + sum_a u_a (x) grad0 N_a, P = lambda ln(J) F^-T + mu (F - F^-T) (eq. 7.2, nh_piola).
   !> f is accumulated (scatter-add); wint is the strain energy of the set, jmin the smallest J
   !> at a Gauss point and ebad the first element with J <= 0 (its forces are meaningless).
   !> Elements go in blocks of NBLOCK: the deformation gradients of the block's points, one call
   !> of the material kernel on all of them, then the nodal forces (module header).
   subroutine q4_force_2x2(nel, nnode, conn, u, gdn, wdj, lambda, mu, f, wint, jmin, ebad)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: u(2, nnode)
      real(wp), intent(in) :: gdn(8, 4, nel)
      real(wp), intent(in) :: wdj(4, nel)
      real(wp), intent(in) :: lambda, mu
      real(wp), intent(inout) :: f(2, nnode)
      real(wp), intent(out) :: wint, jmin
      integer, intent(out) :: ebad
      real(wp) :: ux(4), uy(4), fx(4), fy(4), gx(4), gy(4), we
      real(wp), dimension(4*NBLOCK) :: f11, f12, f21, f22, js, wt, p11, p12, p21, p22, wq
      integer :: e, e0, k, nb, g, q, a

      wint = 0.0_wp
      jmin = huge(1.0_wp)
      ebad = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         ! kinematics of the block's points q = 4 (k - 1) + g
         do k = 1, nb
            e = e0 + k - 1
            call gather(nnode, u, conn(:, e), ux, uy)
            do g = 1, 4
               q = 4*(k - 1) + g
               call point_kinematics(ux, uy, gdn(1:4, g, e), gdn(5:8, g, e), e, f11(q), f12(q), f21(q), &
                                     f22(q), js(q), jmin, ebad)
               wt(q) = wdj(g, e)
            end do
         end do
         ! the law at every point of the block
         call nh_piola(4*nb, lambda, mu, f11, f12, f21, f22, js, wt, p11, p12, p21, p22, wq)
         ! nodal forces
         do k = 1, nb
            e = e0 + k - 1
            fx = 0.0_wp
            fy = 0.0_wp
            we = 0.0_wp
            do g = 1, 4
               q = 4*(k - 1) + g
               gx = gdn(1:4, g, e)
               gy = gdn(5:8, g, e)
               we = we + wq(q)
               fx = fx + p11(q)*gx + p12(q)*gy
               fy = fy + p21(q)*gx + p22(q)*gy
            end do
            wint = wint + we
            do a = 1, 4
               f(1, conn(a, e)) = f(1, conn(a, e)) + fx(a)
               f(2, conn(a, e)) = f(2, conn(a, e)) + fy(a)
            end do
         end do
      end do
   end subroutine q4_force_2x2

   !> Internal force with one-point (mean-strain) quadrature plus Flanagan-Belytschko
   !> hourglass control of stiffness type.
   !>
   !> Mean part: f_ia += A0 P_iJ(F) b_Ja/A0 with F = 1 + sum_a u_a (x) b_a/A0.
   !> Hourglass part: q_i = sum_a gam_a u_ia, f_ia += k gam_a q_i, energy k/2 |q|^2, with
   !> k = hg (lambda + 2 mu) (b:b)/A0. For a square (b:b/A0 = 2, gam = h/4) the hourglass mode
   !> u_x = c xi eta (nodal values c h_a, q = c) stores hg (lambda + 2 mu) c^2, against
   !> 2/3 (lambda + 3 mu) c^2 in the fully integrated element, so hg is roughly the fraction of
   !> the fully integrated hourglass stiffness (0.05-0.15 usual). The force is linear in the
   !> total displacement: elastic, conservative, and zero for affine fields.
   !> wint: strain energy of the mean part; whg: hourglass energy; jmin, ebad as for 2x2.
   !> Elements go in blocks of NBLOCK, as in q4_force_2x2.
   subroutine q4_force_1pt(nel, nnode, conn, u, gdn, wdj, gam, lambda, mu, hg, f, wint, whg, &
                           jmin, ebad)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: u(2, nnode)
      real(wp), intent(in) :: gdn(8, 1, nel)
      real(wp), intent(in) :: wdj(1, nel)
      real(wp), intent(in) :: gam(4, nel)
      real(wp), intent(in) :: lambda, mu, hg
      real(wp), intent(inout) :: f(2, nnode)
      real(wp), intent(out) :: wint, whg, jmin
      integer, intent(out) :: ebad
      real(wp) :: ux(4), uy(4), gx(4), gy(4), ga(4), a0, qx, qy, k, kh
      real(wp), dimension(NBLOCK) :: f11, f12, f21, f22, js, p11, p12, p21, p22, wq
      integer :: e, e0, i, nb, a

      wint = 0.0_wp
      whg = 0.0_wp
      jmin = huge(1.0_wp)
      ebad = 0
      kh = hg*(lambda + 2.0_wp*mu)
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         ! kinematics of the block's centroids
         do i = 1, nb
            e = e0 + i - 1
            call gather(nnode, u, conn(:, e), ux, uy)
            call point_kinematics(ux, uy, gdn(1:4, 1, e), gdn(5:8, 1, e), e, f11(i), f12(i), f21(i), &
                                  f22(i), js(i), jmin, ebad)
         end do
         ! the law at every centroid of the block, weighted by the reference areas
         call nh_piola(nb, lambda, mu, f11, f12, f21, f22, js, wdj(1, e0:e0 + nb - 1), p11, p12, p21, p22, wq)
         ! mean and hourglass forces
         do i = 1, nb
            e = e0 + i - 1
            call gather(nnode, u, conn(:, e), ux, uy)
            gx = gdn(1:4, 1, e)
            gy = gdn(5:8, 1, e)
            ga = gam(:, e)
            a0 = wdj(1, e)
            wint = wint + wq(i)
            ! hourglass: k = hg (lambda + 2 mu) b:b/A0 = hg (lambda + 2 mu) A0 sum(gdn**2)
            k = kh*a0*(gx(1)*gx(1) + gx(2)*gx(2) + gx(3)*gx(3) + gx(4)*gx(4) &
                       + gy(1)*gy(1) + gy(2)*gy(2) + gy(3)*gy(3) + gy(4)*gy(4))
            qx = ga(1)*ux(1) + ga(2)*ux(2) + ga(3)*ux(3) + ga(4)*ux(4)
            qy = ga(1)*uy(1) + ga(2)*uy(2) + ga(3)*uy(3) + ga(4)*uy(4)
            whg = whg + 0.5_wp*k*(qx*qx + qy*qy)
            qx = k*qx
            qy = k*qy
            do a = 1, 4
               f(1, conn(a, e)) = f(1, conn(a, e)) + (p11(i)*gx(a) + p12(i)*gy(a) + qx*ga(a))
               f(2, conn(a, e)) = f(2, conn(a, e)) + (p21(i)*gx(a) + p22(i)*gy(a) + qy*ga(a))
            end do
         end do
      end do
   end subroutine q4_force_1pt

   !> The displacements ux(4), uy(4) of the element with nodes en(4).
   pure subroutine gather(nnode, u, en, ux, uy)
      integer, intent(in) :: nnode, en(4)
      real(wp), intent(in) :: u(2, nnode)
      real(wp), intent(out) :: ux(4), uy(4)
      integer :: a
      do a = 1, 4
         ux(a) = u(1, en(a))
         uy(a) = u(2, en(a))
      end do
   end subroutine gather

   !> F = 1 + sum_a u_a (x) grad0 N_a at a point with reference gradients gx = dN/dX, gy = dN/dY;
   !> J = det F updates jmin, and ebad (when 0) becomes `e` where J <= 0; js is J, or 1 where
   !> J <= 0 (so that the law stays finite on an element the caller will reject).
   pure subroutine point_kinematics(ux, uy, gx, gy, e, f11, f12, f21, f22, js, jmin, ebad)
      real(wp), intent(in) :: ux(4), uy(4), gx(4), gy(4)
      integer, intent(in) :: e
      real(wp), intent(out) :: f11, f12, f21, f22, js
      real(wp), intent(inout) :: jmin
      integer, intent(inout) :: ebad
      real(wp) :: jg
      f11 = 1.0_wp + (ux(1)*gx(1) + ux(2)*gx(2) + ux(3)*gx(3) + ux(4)*gx(4))
      f12 = ux(1)*gy(1) + ux(2)*gy(2) + ux(3)*gy(3) + ux(4)*gy(4)
      f21 = uy(1)*gx(1) + uy(2)*gx(2) + uy(3)*gx(3) + uy(4)*gx(4)
      f22 = 1.0_wp + (uy(1)*gy(1) + uy(2)*gy(2) + uy(3)*gy(3) + uy(4)*gy(4))
      jg = f11*f22 - f12*f21
      jmin = min(jmin, jg)
      if (jg <= 0.0_wp .and. ebad == 0) ebad = e
      js = merge(jg, 1.0_wp, jg > 0.0_wp)
   end subroutine point_kinematics

   !> Row-sum lumped mass m_a = rho integral N_a dA0 (2x2 Gauss, exact for the bilinear
   !> element), accumulated into mass(nnode). The element masses sum to rho A0 exactly.
   pure subroutine q4_lumped_mass(nel, nnode, conn, x0, rho, mass)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode)
      real(wp), intent(in) :: rho
      real(wp), intent(inout) :: mass(nnode)
      real(wp) :: xe(4), ye(4), dnx(4), dny(4), dj, xi, eta, me(4)
      integer :: e, g

      do e = 1, nel
         xe = x0(1, conn(:, e))
         ye = x0(2, conn(:, e))
         me = 0.0_wp
         do g = 1, 4
            xi = gq*xin(g)
            eta = gq*etn(g)
            call grad_at(xe, ye, xi, eta, dnx, dny, dj)
            me = me + (rho*dj*0.25_wp)*(1.0_wp + xin*xi)*(1.0_wp + etn*eta)
         end do
         mass(conn(:, e)) = mass(conn(:, e)) + me
      end do
   end subroutine q4_lumped_mass

   !> Smallest critical time step of the set from the current geometry x(2, nnode).
   !>
   !>     dt_e = phi L_e / c_e,   L_e = A/(longest diagonal) of the current quad,
   !>     c_e^2 = (lambda + 2 mu - 2 lambda ln J)/rho0 at J = A/A0, A0 = sum(wdj(:, e))
   !>
   !> (c_e: the tangent dilatational wave speed of eq. 7.2, floored at sqrt(mu/rho0)).
   !> phi corrects for taper; with t = T_min/A, T_min the smallest of the four corner triangles
   !> (a-1, a, a+1), i.e. twice the smallest corner Jacobian:
   !>   nq = 2: phi^2 = 4 min_g det J_g / A = (1 - 1/sqrt 3) + (2/sqrt 3) t  (smallest Gauss point)
   !>   nq = 1: phi^2 = 4 m_min/(rho A)     = 2/3 (1 + t)                   (lightest node)
   !> Both give phi = 1 (L/c) for every parallelogram. Against the exact limit 2/omega_max of the
   !> linearized element with lumped mass, over random convex quads (corner angles down to 1 deg,
   !> tapers beyond 10:1, nu in [0, 0.499], hourglass coefficient up to 0.25), phi L/c stayed below
   !> 0.995 of the limit; L/c alone exceeds it by up to 2% for tapers of 1.6:1 and by 45% for
   !> wedge-like quads. An element with A <= 0 or phi^2 <= 0 gives dt_e = 0.
   !> dtmin: the smallest dt_e; emin: the (local) element that gives it; efold: the first (local)
   !> element folded at a corner (a corner triangle of non-positive area, i.e. det J <= 0 at that
   !> node, which the Gauss points of either rule need not see), 0 if none.
   pure subroutine q4_stable_dt(nq, nel, nnode, conn, x, wdj, lambda, mu, rho0, dtmin, emin, efold)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x(2, nnode)
      real(wp), intent(in) :: wdj(nq*nq, nel)
      real(wp), intent(in) :: lambda, mu, rho0
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      real(wp), parameter :: s3 = 0.57735026918962576451_wp
      real(wp) :: xe(4), ye(4), d1x, d1y, d2x, d2y, area, dmax2, dt2, dtmin2, tmin, phi2, c0, c1
      integer :: e

      if (nq == 1) then
         c0 = 2.0_wp/3.0_wp
         c1 = 2.0_wp/3.0_wp
      else
         c0 = 1.0_wp - s3
         c1 = 2.0_wp*s3
      end if
      dtmin2 = huge(1.0_wp)
      emin = 0
      efold = 0
      do e = 1, nel
         xe = x(1, conn(:, e))
         ye = x(2, conn(:, e))
         d1x = xe(3) - xe(1)
         d1y = ye(3) - ye(1)
         d2x = xe(4) - xe(2)
         d2y = ye(4) - ye(2)
         area = 0.5_wp*(d1x*d2y - d1y*d2x)
         ! corner triangles (a-1, a, a+1)
         tmin = min(tri(4, 1, 2), tri(1, 2, 3), tri(2, 3, 4), tri(3, 4, 1))
         if (.not. (tmin > 0.0_wp .and. area > 0.0_wp) .and. efold == 0) efold = e
         phi2 = c0 + c1*tmin/merge(area, 1.0_wp, area > 0.0_wp)
         if (area > 0.0_wp .and. phi2 > 0.0_wp) then
            dmax2 = max(d1x*d1x + d1y*d1y, d2x*d2x + d2y*d2y)
            dt2 = phi2*area*area/(dmax2*nh_wave_speed2(lambda, mu, rho0, area/sum(wdj(:, e))))
         else
            dt2 = 0.0_wp
         end if
         if (dt2 < dtmin2) then
            dtmin2 = dt2
            emin = e
         end if
      end do
      dtmin = sqrt(dtmin2)
   contains
      pure real(wp) function tri(a, b, c)
         integer, intent(in) :: a, b, c
         tri = 0.5_wp*((xe(c) - xe(b))*(ye(a) - ye(b)) - (ye(c) - ye(b))*(xe(a) - xe(b)))
      end function tri
   end subroutine q4_stable_dt

   !> Element stress for output: sig(:, e) = sxx, syy, szz, sxy, pressure (-tr sigma/3),
   !> von Mises, J; the mean over the Gauss points for nq = 2, the centroid value for nq = 1.
   !> A point with J <= 0 contributes zero stress (its J is still averaged).
   pure subroutine q4_stress(nq, nel, nnode, conn, u, gdn, lambda, mu, sig)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: u(2, nnode)
      real(wp), intent(in) :: gdn(8, nq*nq, nel)
      real(wp), intent(in) :: lambda, mu
      real(wp), intent(out) :: sig(7, nel)
      real(wp) :: ux(4), uy(4), f11, f12, f21, f22, s(4), jac, w, r
      integer :: e, g, ng

      ng = nq*nq
      r = 1.0_wp/real(ng, wp)
      do e = 1, nel
         ux = u(1, conn(:, e))
         uy = u(2, conn(:, e))
         sig(:, e) = 0.0_wp
         do g = 1, ng
            f11 = 1.0_wp + sum(ux*gdn(1:4, g, e))
            f12 = sum(ux*gdn(5:8, g, e))
            f21 = sum(uy*gdn(1:4, g, e))
            f22 = 1.0_wp + sum(uy*gdn(5:8, g, e))
            jac = f11*f22 - f12*f21
            if (jac > 0.0_wp) then
               call nh_cauchy(lambda, mu, f11, f12, f21, f22, s(1), s(2), s(3), s(4), jac, w)
               sig(1:4, e) = sig(1:4, e) + r*s
            end if
            sig(7, e) = sig(7, e) + r*jac
         end do
         s = sig(1:4, e)
         sig(5, e) = -(s(1) + s(2) + s(3))/3.0_wp
         sig(6, e) = sqrt(0.5_wp*((s(1) - s(2))**2 + (s(2) - s(3))**2 + (s(3) - s(1))**2) &
                          + 3.0_wp*s(4)**2)
      end do
   end subroutine q4_stress

end module exic_element_quad4
