!> The 4-node plane-strain quadrilateral in the total Lagrangian form: internal force (2x2
!> Gauss, or one point with Flanagan-Belytschko stiffness hourglass control) fused with the
!> stable time step, the deformation gradient and element stress for output; the row-sum lumped
!> mass and the reference-mesh check (q4_reference.f90) are made available here too.
!>
!> Plain kernels on explicit-shape arrays; every call works on `nel` elements sharing one
!> material. `conn(4, nel)` holds global node numbers counter-clockwise, `x0(2, nnode)` the
!> reference coordinates, `u(2, nnode)` the displacements, `x(2, nnode)` the current coordinates.
!> Local node a has natural coordinates (xi_a, eta_a) = (-1,-1), (1,-1), (1,1), (-1,1). Gauss
!> points of the 2x2 rule are numbered in the same order, at +-1/sqrt(3).
!>
!> Nothing is stored per element but its nodes: the reference gradients are recomputed from
!> x0 in every pass (cheaper than loading 36 stored values per element, doc/performance.md).
!> With X = sum_a N_a X_a, the derivatives in the natural frame at (xi, eta) are
!>     dX/dxi = c1(X) + c3(X) eta,   dX/deta = c2(X) + c3(X) xi,
!>     c1 = (-X1 + X2 + X3 - X4)/4,  c2 = (-X1 - X2 + X3 + X4)/4,  c3 = (X1 - X2 + X3 - X4)/4,
!> the same for u; J0 = dX/dxi, grad0 u = (du/dxi) J0^-1, and the nodal forces
!> f_a = sum_g det J0 P J0^-T grad_xi N_a (grad_xi N_a = (xi_a (1 + eta_a eta), eta_a (1 + xi_a xi))/4).
!>
!> The force kernels work on blocks of NBLOCK elements laid out as structure of arrays, so that
!> every loop runs across the block's elements (vectorized; checked with -fopt-info-vec): the
!> block's node coordinates and displacements, the deformation gradient F at every point, one
!> call of the law's block entry point on all points (src/exic/material/law.f90: plain arrays in,
!> weighted first Piola stress and energy out), then the nodal forces and the stable step. A law
!> with history (per-point arrays) gets its arrays for the block's points in that one call
!> (doc/architecture.md). Block arrays have the fixed shape (NBLOCK, 4) (element, local node or
!> Gauss point): point (k, g) is k + (g - 1) NBLOCK, the constant stride that lets the compiler
!> vectorize loops writing several columns. A last block of nb < NBLOCK elements is padded with
!> copies of its last element (every lane stays a valid element); only lanes 1..nb are used.
!> NBLOCK, the gather and the scatter-add are in q4_block.f90.
!>
!> Work arrays are written and read again between the steps of a block (the law is a call into
!> src/exic/material), so steps that can share a loop do: the plain 2x2 and one-point kernels
!> write their nodal forces directly as the (x, y) pairs the scatter adds (forces_2x2_pairs,
!> forces_1pt), and the stable step forms the current corners x0 + u in its own loop
!> (stable_block_u, stable_block_pairs) rather than in a pass that stores them; the 2x2 kinematics
!> and the plain 2x2 block's stable step read the gathered (x, y) pairs themselves (gather_pairs),
!> so that no split copy of the corners is stored and loaded again (doc/performance.md, 6.2).
module exic_element_quad4
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum
   use exic_material_law, only: law_t, law_piola, law_cauchy, law_wave_speed2
   use exic_material_material, only: HOURGLASS_PHYSICAL
   use exic_element_q4_barrier, only: corner_barrier, barrier_limit
   use exic_element_q4_reference, only: q4_check_reference, q4_lumped_mass, gq
   use exic_element_q4_block, only: NBLOCK, gather, gather_pairs, current, scatter, scatter_pairs, split_pairs
   implicit none
   private

   public :: q4_check_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, q4_stable_dt, &
             q4_deformation, q4_stress, NBLOCK
   ! the block steps for the general solid path (q4_general.f90), as wrappers: the steps stay
   ! private, so that the compiler inlines them into the block routines as before
   public :: q4b_kinematics_2x2, q4b_kinematics_1pt, q4b_positive, q4b_forces_2x2, &
             q4b_forces_1pt, q4b_asqbi_forces, q4b_check_points, q4b_stable_block, &
             q4b_block_minimum


contains

   !> Internal force with 2x2 Gauss quadrature, f_ia += sum_g det J0 P_iJ(F_g) dN_a/dX_J, and the
   !> stable step of every element from the same gathered nodes (q4_stable_dt's estimate).
   !>
   !> F = 1 + grad0 u, P = lambda ln(J) F^-T + mu (F - F^-T) (eq. 7.2, law_piola of the neo-Hookean law). f is
   !> accumulated (scatter-add, element by element in order); wint is the strain energy (summed
   !> per block with lane_sum, the blocks in order), jmin the smallest J at a Gauss point, ebad the first element with
   !> J <= 0 (its forces are meaningless); dt2min the smallest squared stable step at the
   !> geometry x0 + u, emin its first element, efold the first element folded at a corner.
   pure subroutine q4_force_2x2(nel, nnode, conn, x0, u, law, f, wint, jmin, ebad, &
                                dt2min, emin, efold)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(inout) :: f(2, nnode)
      real(wp), intent(out) :: wint, jmin, dt2min
      integer, intent(out) :: ebad, emin, efold
      integer :: e0, nb

      wint = 0.0_wp
      jmin = huge(1.0_wp)
      dt2min = huge(1.0_wp)
      ebad = 0
      emin = 0
      efold = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call block_2x2(nb, e0 - 1, nnode, conn(:, e0:e0 + nb - 1), x0, u, law, f, wint, &
                        jmin, ebad, dt2min, emin, efold)
      end do
   end subroutine q4_force_2x2

   !> One block of q4_force_2x2: elements off + 1 .. off + nb.
   pure subroutine block_2x2(nb, off, nnode, conn, x0, u, law, f, wint, jmin, ebad, &
                             dt2min, emin, efold)
      integer, intent(in) :: nb, off, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(inout) :: f(2, nnode), wint, jmin, dt2min
      integer, intent(inout) :: ebad, emin, efold
      real(wp), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac, js, wt, i11, i12, &
                                        i21, i22, p11, p12, p21, p22, wq
      real(wp) :: fp(2, NBLOCK, 4), p0(2, NBLOCK, 4), pu(2, NBLOCK, 4), dt2(NBLOCK), good(NBLOCK), &
                  we(NBLOCK)
      integer :: k

      call gather_pairs(nb, nnode, conn, x0, u, p0, pu)
      call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      call positive(4*NBLOCK, jac, js)
      ! the law at every point of the block
      call law_piola(law, 4*NBLOCK, f11, f12, f21, f22, js, wt, p11, p12, p21, p22, wq)
      call forces_2x2_pairs(p11, p12, p21, p22, i11, i12, i21, i22, fp)
      do k = 1, NBLOCK
         we(k) = ((wq(k, 1) + wq(k, 2)) + wq(k, 3)) + wq(k, 4)
      end do
      wint = wint + lane_sum(nb, we)
      call check_points(nb, 4, off, jac, jmin, ebad)
      ! the stable step at the current geometry x0 + u
      call stable_block_pairs(2, p0, pu, law, dt2, good)
      call block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      call scatter_pairs(nb, nnode, conn, fp, f)
   end subroutine block_2x2

   !> js = J where J is a positive normal number, else 1 (so that the law stays finite on an
   !> element the caller rejects: check_points rejects J < tiny, i.e. J <= 0 and the subnormal
   !> J below 2.2e-308, whose logarithm the laws' ln_normal_block does not take).
   pure subroutine positive(n, jac, js)
      integer, intent(in) :: n
      real(wp), intent(in) :: jac(n)
      real(wp), intent(out) :: js(n)
      integer :: q
      do q = 1, n
         js(q) = merge(jac(q), 1.0_wp, jac(q) >= tiny(1.0_wp))
      end do
   end subroutine positive

   !> Gradients and Jacobians at the four Gauss points of a block (point (k, g): element k,
   !> Gauss point g): F = 1 + grad0 u, J = det F, the weight det J0 and J0^-1 (i11 .. i22), from
   !> the (x, y) pairs of gather_pairs: reference corners p0(:, k, a), displacements pu(:, k, a)
   !> (the loop splits the pairs in registers, so no split array is stored and loaded again).
   !> The four reciprocals 1/det J0 of an element come from one division (of their product).
   pure subroutine kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      real(wp), intent(in), dimension(2, NBLOCK, 4) :: p0, pu
      real(wp), intent(out), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac, wt, i11, i12, i21, i22
      real(wp) :: c1x, c2x, c3x, c1y, c2y, c3y, c1u, c2u, c3u, c1v, c2v, c3v, t
      real(wp) :: x1m, x1p, x2m, x2p, y1m, y1p, y2m, y2p, u1m, u1p, u2m, u2p, v1m, v1p, v2m, v2p
      real(wp) :: d1, d2, d3, d4, d12, d34, rr
      integer :: k

      do k = 1, NBLOCK
         ! dv/dxi = c1 + c3 eta, dv/deta = c2 + c3 xi (module header)
         c1x = 0.25_wp*((p0(1, k, 2) - p0(1, k, 1)) + (p0(1, k, 3) - p0(1, k, 4)))
         c2x = 0.25_wp*((p0(1, k, 4) - p0(1, k, 1)) + (p0(1, k, 3) - p0(1, k, 2)))
         c3x = 0.25_wp*((p0(1, k, 1) - p0(1, k, 2)) + (p0(1, k, 3) - p0(1, k, 4)))
         c1y = 0.25_wp*((p0(2, k, 2) - p0(2, k, 1)) + (p0(2, k, 3) - p0(2, k, 4)))
         c2y = 0.25_wp*((p0(2, k, 4) - p0(2, k, 1)) + (p0(2, k, 3) - p0(2, k, 2)))
         c3y = 0.25_wp*((p0(2, k, 1) - p0(2, k, 2)) + (p0(2, k, 3) - p0(2, k, 4)))
         c1u = 0.25_wp*((pu(1, k, 2) - pu(1, k, 1)) + (pu(1, k, 3) - pu(1, k, 4)))
         c2u = 0.25_wp*((pu(1, k, 4) - pu(1, k, 1)) + (pu(1, k, 3) - pu(1, k, 2)))
         c3u = 0.25_wp*((pu(1, k, 1) - pu(1, k, 2)) + (pu(1, k, 3) - pu(1, k, 4)))
         c1v = 0.25_wp*((pu(2, k, 2) - pu(2, k, 1)) + (pu(2, k, 3) - pu(2, k, 4)))
         c2v = 0.25_wp*((pu(2, k, 4) - pu(2, k, 1)) + (pu(2, k, 3) - pu(2, k, 2)))
         c3v = 0.25_wp*((pu(2, k, 1) - pu(2, k, 2)) + (pu(2, k, 3) - pu(2, k, 4)))
         ! derivatives on the lines xi = -+1/sqrt(3) (m, p) and eta = -+1/sqrt(3)
         t = c3x*gq
         x1m = c1x - t
         x1p = c1x + t
         x2m = c2x - t
         x2p = c2x + t
         t = c3y*gq
         y1m = c1y - t
         y1p = c1y + t
         y2m = c2y - t
         y2p = c2y + t
         t = c3u*gq
         u1m = c1u - t
         u1p = c1u + t
         u2m = c2u - t
         u2p = c2u + t
         t = c3v*gq
         v1m = c1v - t
         v1p = c1v + t
         v2m = c2v - t
         v2p = c2v + t
         ! det J0 at the points (positive: q4_check_reference), 1/det J0 from one division
         d1 = x1m*y2m - x2m*y1m
         d2 = x1m*y2p - x2p*y1m
         d3 = x1p*y2p - x2p*y1p
         d4 = x1p*y2m - x2m*y1p
         d12 = d1*d2
         d34 = d3*d4
         rr = 1.0_wp/(d12*d34)
         ! point g at (xi, eta): dX/dxi = x1(eta), dX/deta = x2(xi), the same for Y, u, v
         call point_2x2(x1m, x2m, y1m, y2m, u1m, u2m, v1m, v2m, (d2*d34)*rr, i11(k, 1), i12(k, 1), &
                        i21(k, 1), i22(k, 1), f11(k, 1), f12(k, 1), f21(k, 1), f22(k, 1), jac(k, 1))
         call point_2x2(x1m, x2p, y1m, y2p, u1m, u2p, v1m, v2p, (d1*d34)*rr, i11(k, 2), i12(k, 2), &
                        i21(k, 2), i22(k, 2), f11(k, 2), f12(k, 2), f21(k, 2), f22(k, 2), jac(k, 2))
         call point_2x2(x1p, x2p, y1p, y2p, u1p, u2p, v1p, v2p, (d4*d12)*rr, i11(k, 3), i12(k, 3), &
                        i21(k, 3), i22(k, 3), f11(k, 3), f12(k, 3), f21(k, 3), f22(k, 3), jac(k, 3))
         call point_2x2(x1p, x2m, y1p, y2m, u1p, u2m, v1p, v2m, (d3*d12)*rr, i11(k, 4), i12(k, 4), &
                        i21(k, 4), i22(k, 4), f11(k, 4), f12(k, 4), f21(k, 4), f22(k, 4), jac(k, 4))
         wt(k, 1) = d1
         wt(k, 2) = d2
         wt(k, 3) = d3
         wt(k, 4) = d4
      end do
   end subroutine kinematics_2x2

   !> J0^-1 (i11 .. i22), F = 1 + (du/dxi) J0^-1 and J = det F at a point where
   !> J0 = [x1 x2; y1 y2] (dX/dxi, dX/deta; dY/dxi, dY/deta), du/dxi = [u1 u2; v1 v2] and
   !> r = 1/det J0.
   pure subroutine point_2x2(x1, x2, y1, y2, u1, u2, v1, v2, r, i11, i12, i21, i22, f11, f12, f21, f22, jac)
      real(wp), intent(in) :: x1, x2, y1, y2, u1, u2, v1, v2, r
      real(wp), intent(out) :: i11, i12, i21, i22, f11, f12, f21, f22, jac
      i11 = y2*r
      i12 = -(x2*r)
      i21 = -(y1*r)
      i22 = x1*r
      f11 = 1.0_wp + (u1*i11 + u2*i21)
      f12 = u1*i12 + u2*i22
      f21 = v1*i11 + v2*i21
      f22 = 1.0_wp + (v1*i12 + v2*i22)
      jac = f11*f22 - f12*f21
   end subroutine point_2x2

   !> Nodal forces of a block of 2x2 elements from the weighted stresses p (det J0 P) and J0^-1
   !> at their Gauss points: Q = p J0^-T at each point, then with S_K = sum_g Q_iK and
   !> T = sum_g (eta_g Q_i1 + xi_g Q_i2), f_ia = (xi_a S_1 + eta_a S_2 + xi_a eta_a T)/4.
   pure subroutine forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
      real(wp), intent(in), dimension(NBLOCK, 4) :: p11, p12, p21, p22, i11, i12, i21, i22
      real(wp), intent(out), dimension(NBLOCK, 4) :: fx, fy
      integer :: k
      do k = 1, NBLOCK
         call element_forces_2x2(k, p11, p12, p21, p22, i11, i12, i21, i22, fx(k, 1), fx(k, 2), &
                                 fx(k, 3), fx(k, 4), fy(k, 1), fy(k, 2), fy(k, 3), fy(k, 4))
      end do
   end subroutine forces_2x2

   !> forces_2x2 with the forces as (x, y) pairs fp(:, k, a), the layout scatter_pairs adds.
   pure subroutine forces_2x2_pairs(p11, p12, p21, p22, i11, i12, i21, i22, fp)
      real(wp), intent(in), dimension(NBLOCK, 4) :: p11, p12, p21, p22, i11, i12, i21, i22
      real(wp), intent(out) :: fp(2, NBLOCK, 4)
      integer :: k
      do k = 1, NBLOCK
         call element_forces_2x2(k, p11, p12, p21, p22, i11, i12, i21, i22, fp(1, k, 1), fp(1, k, 2), &
                                 fp(1, k, 3), fp(1, k, 4), fp(2, k, 1), fp(2, k, 2), fp(2, k, 3), fp(2, k, 4))
      end do
   end subroutine forces_2x2_pairs

   !> The nodal forces (fx1..fx4, fy1..fy4) of element k of forces_2x2.
   pure subroutine element_forces_2x2(k, p11, p12, p21, p22, i11, i12, i21, i22, fx1, fx2, fx3, fx4, &
                                      fy1, fy2, fy3, fy4)
      integer, intent(in) :: k
      real(wp), intent(in), dimension(NBLOCK, 4) :: p11, p12, p21, p22, i11, i12, i21, i22
      real(wp), intent(out) :: fx1, fx2, fx3, fx4, fy1, fy2, fy3, fy4
      real(wp) :: a(4), b(4), c(4), d(4)
      integer :: g
      do g = 1, 4
         a(g) = p11(k, g)*i11(k, g) + p12(k, g)*i12(k, g)
         b(g) = p11(k, g)*i21(k, g) + p12(k, g)*i22(k, g)
         c(g) = p21(k, g)*i11(k, g) + p22(k, g)*i12(k, g)
         d(g) = p21(k, g)*i21(k, g) + p22(k, g)*i22(k, g)
      end do
      call natural_forces(a(1), a(2), a(3), a(4), b(1), b(2), b(3), b(4), fx1, fx2, fx3, fx4)
      call natural_forces(c(1), c(2), c(3), c(4), d(1), d(2), d(3), d(4), fy1, fy2, fy3, fy4)
   end subroutine element_forces_2x2

   !> One force component at the four nodes from Q_i1 = a_g and Q_i2 = b_g at the Gauss points.
   pure subroutine natural_forces(a1, a2, a3, a4, b1, b2, b3, b4, f1, f2, f3, f4)
      real(wp), intent(in) :: a1, a2, a3, a4, b1, b2, b3, b4
      real(wp), intent(out) :: f1, f2, f3, f4
      real(wp) :: s1, s2, t
      s1 = (a1 + a2) + (a3 + a4)
      s2 = (b1 + b2) + (b3 + b4)
      ! eta_g = gq (-1, -1, 1, 1), xi_g = gq (-1, 1, 1, -1)
      t = gq*(((a3 + a4) - (a1 + a2)) + ((b2 + b3) - (b1 + b4)))
      f1 = 0.25_wp*(t - (s1 + s2))
      f2 = 0.25_wp*((s1 - s2) - t)
      f3 = 0.25_wp*((s1 + s2) + t)
      f4 = 0.25_wp*((s2 - s1) - t)
   end subroutine natural_forces

   !> Internal force with one-point (mean-strain) quadrature plus Flanagan-Belytschko
   !> hourglass control of stiffness type, fused with the stable step as in q4_force_2x2.
   !>
   !> Mean part: f_ia += P_iJ(F) b_Ja with F = 1 + sum_a u_a (x) b_a/A0 and the mean-strain
   !> vectors b_xa = 1/2 (Y_{a+1} - Y_{a-1}), b_ya = 1/2 (X_{a-1} - X_{a+1}) (the exact mean of
   !> A0 grad N_a), A0 = sum_a b_xa X_a. Hourglass part: gam_a = 1/4 (h_a - (h.X b_xa + h.Y b_ya)/A0),
   !> h = (1,-1,1,-1), q_i = sum_a gam_a u_ia, f_ia += k gam_a q_i, energy k/2 |q|^2, with
   !> k = hg (lambda + 2 mu) (b:b)/A0. For a square (b:b/A0 = 2, gam = h/4) the hourglass mode
   !> u_x = c xi eta (nodal values c h_a, q = c) stores hg (lambda + 2 mu) c^2, against
   !> 2/3 (lambda + 3 mu) c^2 in the fully integrated element, so hg is roughly the fraction of
   !> the fully integrated hourglass stiffness (0.05-0.15 usual). The force is linear in the
   !> total displacement: elastic, conservative, and zero for affine fields.
   !> With hgkind = HOURGLASS_PHYSICAL the hourglass part is the assumed-strain stabilization
   !> of doc/hourglass.md instead (asqbi_forces), hg its scale s.
   !> wint: strain energy of the mean part; whg: hourglass energy; the rest as for q4_force_2x2.
   pure subroutine q4_force_1pt(nel, nnode, conn, x0, u, law, hg, f, wint, whg, jmin, &
                                ebad, dt2min, emin, efold, hgkind, v)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(in) :: hg
      real(wp), intent(inout) :: f(2, nnode)
      real(wp), intent(out) :: wint, whg, jmin, dt2min
      integer, intent(out) :: ebad, emin, efold
      integer, intent(in), optional :: hgkind   !< HOURGLASS_STIFFNESS (default) or HOURGLASS_PHYSICAL
      !> nodal velocities: with the physical control, the step also keeps a corner from losing
      !> more than a quarter of its volume ratio in one step (doc/hourglass.md (H19))
      real(wp), intent(in), optional :: v(2, nnode)
      integer :: e0, nb
      logical :: phys

      phys = .false.
      if (present(hgkind)) phys = hgkind == HOURGLASS_PHYSICAL

      wint = 0.0_wp
      whg = 0.0_wp
      jmin = huge(1.0_wp)
      dt2min = huge(1.0_wp)
      ebad = 0
      emin = 0
      efold = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call block_1pt(nb, e0 - 1, nnode, conn(:, e0:e0 + nb - 1), x0, u, law, hg, phys, &
                        f, wint, whg, jmin, ebad, dt2min, emin, efold, v)
      end do
   end subroutine q4_force_1pt

   !> One block of q4_force_1pt: elements off + 1 .. off + nb.
   pure subroutine block_1pt(nb, off, nnode, conn, x0, u, law, hg, phys, f, wint, whg, &
                             jmin, ebad, dt2min, emin, efold, v)
      integer, intent(in) :: nb, off, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(in) :: hg
      logical, intent(in) :: phys
      real(wp), intent(inout) :: f(2, nnode), wint, whg, jmin, dt2min
      integer, intent(inout) :: ebad, emin, efold
      real(wp), intent(in), optional :: v(2, nnode)
      real(wp), dimension(NBLOCK, 4) :: xe, ye, uxe, uye, fx, fy, hx, hy
      real(wp) :: fp(2, NBLOCK, 4)
      real(wp), dimension(NBLOCK) :: f11, f12, f21, f22, jac, js, a0, r0, p11, p12, p21, p22, wq, eh, &
                                     dt2, good, ob
      integer :: a, k

      call gather(nb, nnode, conn, x0, u, xe, ye, uxe, uye)
      call kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
      call positive(NBLOCK, jac, js)
      ! the law at every centroid of the block, weighted by the reference areas
      call law_piola(law, NBLOCK, f11, f12, f21, f22, js, a0, p11, p12, p21, p22, wq)
      if (phys) then
         call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, 0.0_wp, fp, eh)
         call split_pairs(fp, fx, fy)
         call asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, law%lambda, law%mu, hg, hx, hy, eh)
         do a = 1, 4
            do k = 1, NBLOCK
               fx(k, a) = fx(k, a) + hx(k, a)
               fy(k, a) = fy(k, a) + hy(k, a)
            end do
         end do
      else
         call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, hg*(law%lambda + 2.0_wp*law%mu), fp, eh)
      end if
      wint = wint + lane_sum(nb, wq)
      call check_points(nb, 1, off, jac, jmin, ebad)
      if (phys) then
         call current(xe, ye, uxe, uye)
         ! r0 is no longer needed: reused as the weight 1 of the plane element
         r0 = 1.0_wp
         call corner_barrier(NBLOCK, xe, ye, uxe, uye, r0, law%lambda, law%mu, law%rho, fx, fy, eh, ob)
         whg = whg + lane_sum(nb, eh)
         call stable_block(1, xe, ye, uxe, uye, law, dt2, good)
         call barrier_limit(NBLOCK, nb, nnode, conn, uxe, uye, ob, dt2, v)
      else
         whg = whg + lane_sum(nb, eh)
         ! the stable step at the current geometry x0 + u
         call stable_block_u(1, xe, ye, uxe, uye, law, dt2, good)
      end if
      call block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      if (phys) then
         call scatter(nb, nnode, conn, fx, fy, f)
      else
         call scatter_pairs(nb, nnode, conn, fp, f)
      end if
   end subroutine block_1pt

   !> Mean deformation gradient of a block of one-point elements: F = 1 + sum_a u_a (x) b_a/A0,
   !> J = det F, the reference area A0 and r0 = 1/A0 (q4_force_1pt; b_3 = -b_1, b_4 = -b_2).
   pure subroutine kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(out), dimension(NBLOCK) :: f11, f12, f21, f22, jac, a0, r0
      real(wp) :: bx1, bx2, by1, by2, du1, du2, dv1, dv2
      integer :: k

      do k = 1, NBLOCK
         bx1 = 0.5_wp*(ye(k, 2) - ye(k, 4))
         bx2 = 0.5_wp*(ye(k, 3) - ye(k, 1))
         by1 = 0.5_wp*(xe(k, 4) - xe(k, 2))
         by2 = 0.5_wp*(xe(k, 1) - xe(k, 3))
         a0(k) = bx1*(xe(k, 1) - xe(k, 3)) + bx2*(xe(k, 2) - xe(k, 4))
         r0(k) = 1.0_wp/merge(a0(k), 1.0_wp, a0(k) > 0.0_wp)
         du1 = uxe(k, 1) - uxe(k, 3)
         du2 = uxe(k, 2) - uxe(k, 4)
         dv1 = uye(k, 1) - uye(k, 3)
         dv2 = uye(k, 2) - uye(k, 4)
         f11(k) = 1.0_wp + (bx1*du1 + bx2*du2)*r0(k)
         f12(k) = (by1*du1 + by2*du2)*r0(k)
         f21(k) = (bx1*dv1 + bx2*dv2)*r0(k)
         f22(k) = 1.0_wp + (by1*dv1 + by2*dv2)*r0(k)
         jac(k) = f11(k)*f22(k) - f12(k)*f21(k)
      end do
   end subroutine kinematics_1pt

   !> Mean and hourglass forces fp (as (x, y) pairs) and hourglass energies eh of a block of one-point
   !> elements from their weighted stresses p = A0 P, r0 = 1/A0 and the hourglass stiffness
   !> factor kh = hg (lambda + 2 mu) (q4_force_1pt; b_3 = -b_1, b_4 = -b_2).
   pure subroutine forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, kh, fp, eh)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(in), dimension(NBLOCK) :: r0, p11, p12, p21, p22
      real(wp), intent(in) :: kh
      real(wp), intent(out) :: fp(2, NBLOCK, 4)   !< (x, y) pairs, the layout of scatter_pairs
      real(wp), intent(out) :: eh(NBLOCK)
      real(wp) :: bx1, bx2, by1, by2, hx, hy, t1, t2, g1, g2, g3, g4, kk, qx, qy, m1, m2
      integer :: k

      do k = 1, NBLOCK
         bx1 = 0.5_wp*(ye(k, 2) - ye(k, 4))
         bx2 = 0.5_wp*(ye(k, 3) - ye(k, 1))
         by1 = 0.5_wp*(xe(k, 4) - xe(k, 2))
         by2 = 0.5_wp*(xe(k, 1) - xe(k, 3))
         hx = (xe(k, 1) - xe(k, 2)) + (xe(k, 3) - xe(k, 4))
         hy = (ye(k, 1) - ye(k, 2)) + (ye(k, 3) - ye(k, 4))
         t1 = (hx*bx1 + hy*by1)*r0(k)
         t2 = (hx*bx2 + hy*by2)*r0(k)
         g1 = 0.25_wp*(1.0_wp - t1)
         g2 = 0.25_wp*(-1.0_wp - t2)
         g3 = 0.25_wp*(1.0_wp + t1)
         g4 = 0.25_wp*(t2 - 1.0_wp)
         ! k = hg (lambda + 2 mu) b:b/A0 with b:b = 2 (bx1^2 + bx2^2 + by1^2 + by2^2)
         kk = kh*(2.0_wp*((bx1*bx1 + bx2*bx2) + (by1*by1 + by2*by2)))*r0(k)
         qx = (g1*uxe(k, 1) + g2*uxe(k, 2)) + (g3*uxe(k, 3) + g4*uxe(k, 4))
         qy = (g1*uye(k, 1) + g2*uye(k, 2)) + (g3*uye(k, 3) + g4*uye(k, 4))
         eh(k) = 0.5_wp*kk*(qx*qx + qy*qy)
         qx = kk*qx
         qy = kk*qy
         ! mean part: (p b)/A0 with p = A0 P
         m1 = (p11(k)*bx1 + p12(k)*by1)*r0(k)
         m2 = (p11(k)*bx2 + p12(k)*by2)*r0(k)
         fp(1, k, 1) = m1 + qx*g1
         fp(1, k, 2) = m2 + qx*g2
         fp(1, k, 3) = qx*g3 - m1
         fp(1, k, 4) = qx*g4 - m2
         m1 = (p21(k)*bx1 + p22(k)*by1)*r0(k)
         m2 = (p21(k)*bx2 + p22(k)*by2)*r0(k)
         fp(2, k, 1) = m1 + qy*g1
         fp(2, k, 2) = m2 + qy*g2
         fp(2, k, 3) = qy*g3 - m1
         fp(2, k, 4) = qy*g4 - m2
      end do
   end subroutine forces_1pt

   !> Hourglass forces hx, hy and energies eh of the assumed-strain (ASQBI) stabilization of a
   !> block of one-point elements in the element's turning frame (doc/hourglass.md, (H1)-(H12);
   !> Belytschko & Bindeman 1991): q = sum_a gam_a u_a (H2), q^ = R^T q with R the rotation of
   !> the mean F (H8), W = 1/2 q^.K^ q^ with K^ = s E' [H - (1 + nub) H~xy (e1 e2^T + e2 e1^T)]
   !> (H7, H9) from the reference element, and the forces the exact gradient of W (H10-H12).
   !> r0 = 1/A0; f11..f22 the mean deformation gradient; s the scale (HOURglass,PHYSical,s).
   pure subroutine asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, lambda, mu, s, hx, hy, eh)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(in), dimension(NBLOCK) :: r0, f11, f12, f21, f22
      real(wp), intent(in) :: lambda, mu, s
      real(wp), intent(out), dimension(NBLOCK, 4) :: hx, hy
      real(wp), intent(out) :: eh(NBLOCK)
      real(wp) :: ep, nub, bx1, bx2, by1, by2, hxg, hyg, t1, t2, g1, g2, g3, g4, qx, qy, c1x, c1y, &
                  c2x, c2y, hh, kxx, kyy, kxy, e1x, e1y, hxy, sn, dn, nn, cr, sr, px, py, qpx, qpy, &
                  rqx, rqy, tm
      integer :: k

      ! E' = 2 mu (1 + nub), nub = lambda/(lambda + 2 mu) (H4, H5)
      nub = lambda/(lambda + 2.0_wp*mu)
      ep = s*2.0_wp*mu*(1.0_wp + nub)
      do k = 1, NBLOCK
         bx1 = 0.5_wp*(ye(k, 2) - ye(k, 4))
         bx2 = 0.5_wp*(ye(k, 3) - ye(k, 1))
         by1 = 0.5_wp*(xe(k, 4) - xe(k, 2))
         by2 = 0.5_wp*(xe(k, 1) - xe(k, 3))
         ! gam_a (H1), as in forces_1pt
         hxg = (xe(k, 1) - xe(k, 2)) + (xe(k, 3) - xe(k, 4))
         hyg = (ye(k, 1) - ye(k, 2)) + (ye(k, 3) - ye(k, 4))
         t1 = (hxg*bx1 + hyg*by1)*r0(k)
         t2 = (hxg*bx2 + hyg*by2)*r0(k)
         g1 = 0.25_wp*(1.0_wp - t1)
         g2 = 0.25_wp*(-1.0_wp - t2)
         g3 = 0.25_wp*(1.0_wp + t1)
         g4 = 0.25_wp*(t2 - 1.0_wp)
         qx = (g1*uxe(k, 1) + g2*uxe(k, 2)) + (g3*uxe(k, 3) + g4*uxe(k, 4))
         qy = (g1*uye(k, 1) + g2*uye(k, 2)) + (g3*uye(k, 3) + g4*uye(k, 4))
         ! c1 = dX/dxi, c2 = dX/deta at the centre; H = 4/(3 det J0) (perp c1 perp c1^T +
         ! perp c2 perp c2^T) with det J0 = A0/4 (H7)
         c1x = 0.25_wp*((xe(k, 2) - xe(k, 1)) + (xe(k, 3) - xe(k, 4)))
         c1y = 0.25_wp*((ye(k, 2) - ye(k, 1)) + (ye(k, 3) - ye(k, 4)))
         c2x = 0.25_wp*((xe(k, 3) - xe(k, 2)) + (xe(k, 4) - xe(k, 1)))
         c2y = 0.25_wp*((ye(k, 3) - ye(k, 2)) + (ye(k, 4) - ye(k, 1)))
         hh = (16.0_wp/3.0_wp)*r0(k)
         kxx = hh*(c1y*c1y + c2y*c2y)
         kyy = hh*(c1x*c1x + c2x*c2x)
         kxy = -hh*(c1x*c1y + c2x*c2y)
         ! the element's frame e1 = c1/|c1|, e2 = (-e1y, e1x); H~xy = e1^T H e2 (H9)
         tm = 1.0_wp/sqrt(c1x*c1x + c1y*c1y)
         e1x = c1x*tm
         e1y = c1y*tm
         hxy = e1x*(kxy*e1x - kxx*e1y) + e1y*(kyy*e1x - kxy*e1y)
         ! K^ = E' [H - (1 + nub) H~xy (e1 e2^T + e2 e1^T)]
         tm = (1.0_wp + nub)*hxy
         kxx = ep*(kxx + tm*2.0_wp*e1x*e1y)
         kyy = ep*(kyy - tm*2.0_wp*e1y*e1x)
         kxy = ep*(kxy - tm*(e1x*e1x - e1y*e1y))
         ! R of the mean F (H8): cos = S/sqrt(S^2 + D^2), sin = D/sqrt(S^2 + D^2)
         sn = f11(k) + f22(k)
         dn = f21(k) - f12(k)
         nn = max(sn*sn + dn*dn, tiny(1.0_wp))
         tm = 1.0_wp/sqrt(nn)
         cr = sn*tm
         sr = dn*tm
         ! q^ = R^T q, Q^ = K^ q^, W = q^.Q^/2
         px = cr*qx + sr*qy
         py = cr*qy - sr*qx
         qpx = kxx*px + kxy*py
         qpy = kxy*px + kyy*py
         eh(k) = 0.5_wp*(px*qpx + py*qpy)
         rqx = cr*qpx - sr*qpy
         rqy = sr*qpx + cr*qpy
         ! m dtheta/du_a (H10, H11): tm = m/((S^2 + D^2) A0)
         tm = (qpx*py - qpy*px)*r0(k)/nn
         ! (H12), b_3 = -b_1, b_4 = -b_2
         hx(k, 1) = g1*rqx - tm*(sn*by1 + dn*bx1)
         hx(k, 2) = g2*rqx - tm*(sn*by2 + dn*bx2)
         hx(k, 3) = g3*rqx + tm*(sn*by1 + dn*bx1)
         hx(k, 4) = g4*rqx + tm*(sn*by2 + dn*bx2)
         hy(k, 1) = g1*rqy + tm*(sn*bx1 - dn*by1)
         hy(k, 2) = g2*rqy + tm*(sn*bx2 - dn*by2)
         hy(k, 3) = g3*rqy - tm*(sn*bx1 - dn*by1)
         hy(k, 4) = g4*rqy - tm*(sn*bx2 - dn*by2)
      end do
   end subroutine asqbi_forces


   !> jmin over the points jac(NBLOCK, np) of the block's nb elements; ebad (when 0) becomes the
   !> first element off + k with J <= 0 at a point (or a subnormal J > 0, below tiny = 2.2e-308:
   !> an element crushed that far is rejected as inverted, see positive).
   pure subroutine check_points(nb, np, off, jac, jmin, ebad)
      integer, intent(in) :: nb, np, off
      real(wp), intent(in) :: jac(NBLOCK, np)
      real(wp), intent(inout) :: jmin
      integer, intent(inout) :: ebad
      real(wp) :: m
      integer :: k, g
      m = huge(1.0_wp)
      do g = 1, np
         do k = 1, nb
            m = min(m, jac(k, g))
         end do
      end do
      jmin = min(jmin, m)
      if (ebad /= 0 .or. m >= tiny(1.0_wp)) return
      do k = 1, nb
         if (any(jac(k, :) < tiny(1.0_wp))) then
            ebad = off + k
            return
         end if
      end do
   end subroutine check_points

   !> Squared stable steps dt2(k) of a block with reference corners (xr, yr) and current corners
   !> (xc, yc) (q4_stable_dt), and good(k) = 1 where the element is not folded at a corner (the
   !> area positive, every corner triangle above -FLAT of it: a corner flat to round-off is a
   !> triangle, doc/decisions.md), 0 where it is. With A the area, T the smallest
   !> corner triangle and D the longest diagonal squared, phi^2 A^2 = (c0 A + c1 T) A, so
   !>     dt^2 = phi^2 A^2/(D c^2) = (c0 A + c1 T) A/(D c^2)
   !> takes one division, and phi^2 > 0 is c0 A + c1 T > 0 (A > 0). Areas are formed doubled
   !> (2 A, 2 T, 2 A0; the halving is exact and cancels: D is multiplied by 4 instead).
   pure subroutine stable_block(nq, xr, yr, xc, yc, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         xcl = xc(k, :)
         ycl = yc(k, :)
         call corner_estimate(c0, c1, xr(k, 1), xr(k, 2), xr(k, 3), xr(k, 4), yr(k, 1), yr(k, 2), &
                              yr(k, 3), yr(k, 4), xcl, ycl, good(k), ok(k), num(k), den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block

   !> stable_block from the reference corners (xr, yr) and the displacements (ux, uy) of the
   !> block: the current corners xr + ux, yr + uy (the sums of `current`) are formed in the loop
   !> instead of being stored and loaded again.
   pure subroutine stable_block_u(nq, xr, yr, ux, uy, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, ux, uy
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k, a

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         do a = 1, 4
            xcl(a) = xr(k, a) + ux(k, a)
            ycl(a) = yr(k, a) + uy(k, a)
         end do
         call corner_estimate(c0, c1, xr(k, 1), xr(k, 2), xr(k, 3), xr(k, 4), yr(k, 1), yr(k, 2), &
                              yr(k, 3), yr(k, 4), xcl, ycl, good(k), ok(k), num(k), den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block_u

   !> stable_block_u from the (x, y) pairs of gather_pairs: reference corners p0(:, k, a),
   !> displacements pu(:, k, a); the same sums and operations.
   pure subroutine stable_block_pairs(nq, p0, pu, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(2, NBLOCK, 4) :: p0, pu
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      real(wp), dimension(NBLOCK) :: num, den, jr, ok
      real(wp) :: c0, c1, xcl(4), ycl(4)
      integer :: k, a

      call taper_factors(nq, c0, c1)
      do k = 1, NBLOCK
         do a = 1, 4
            xcl(a) = p0(1, k, a) + pu(1, k, a)
            ycl(a) = p0(2, k, a) + pu(2, k, a)
         end do
         call corner_estimate(c0, c1, p0(1, k, 1), p0(1, k, 2), p0(1, k, 3), p0(1, k, 4), p0(2, k, 1), &
                              p0(2, k, 2), p0(2, k, 3), p0(2, k, 4), xcl, ycl, good(k), ok(k), num(k), &
                              den(k), jr(k))
      end do
      call stable_finish(law, num, den, jr, ok, dt2)
   end subroutine stable_block_pairs

   !> c0, c1 of phi^2 = c0 + c1 t for the rule nq (q4_stable_dt).
   pure subroutine taper_factors(nq, c0, c1)
      integer, intent(in) :: nq
      real(wp), intent(out) :: c0, c1
      real(wp), parameter :: s3 = 0.57735026918962576451_wp
      if (nq == 1) then
         c0 = 2.0_wp/3.0_wp
         c1 = 2.0_wp/3.0_wp
      else
         c0 = 1.0_wp - s3
         c1 = 2.0_wp*s3
      end if
   end subroutine taper_factors

   !> One element of stable_block: reference corners (xr1..4, yr1..4), current corners (xc, yc);
   !> good, ok (1 or 0), the numerator ph A and denominator D of dt^2 c^2 and the volume ratio jr.
   pure subroutine corner_estimate(c0, c1, xr1, xr2, xr3, xr4, yr1, yr2, yr3, yr4, xc, yc, good, ok, &
                                   num, den, jr)
      real(wp), intent(in) :: c0, c1, xr1, xr2, xr3, xr4, yr1, yr2, yr3, yr4, xc(4), yc(4)
      real(wp), intent(out) :: good, ok, num, den, jr
      !> a corner triangle within FLAT of the area is flat (three nodes on a line to round-off), not folded
      real(wp), parameter :: FLAT = 1.0e-10_wp
      real(wp) :: d1x, d1y, d2x, d2y, a2, a02, t2, pa, ph, ex(4), ey(4)
      integer :: a

      a02 = (xr3 - xr1)*(yr4 - yr2) - (yr3 - yr1)*(xr4 - xr2)
      d1x = xc(3) - xc(1)
      d1y = yc(3) - yc(1)
      d2x = xc(4) - xc(2)
      d2y = yc(4) - yc(2)
      a2 = d1x*d2y - d1y*d2x
      ! edges a -> a+1; the corner triangle (a-1, a, a+1) is e_(a-1) x e_a / 2
      do a = 1, 4
         ex(a) = xc(modulo(a, 4) + 1) - xc(a)
         ey(a) = yc(modulo(a, 4) + 1) - yc(a)
      end do
      t2 = min(min(ex(4)*ey(1) - ey(4)*ex(1), ex(1)*ey(2) - ey(1)*ex(2)), &
               min(ex(2)*ey(3) - ey(2)*ex(3), ex(3)*ey(4) - ey(3)*ex(4)))
      ! masks as reals (1 or 0), so that the callers' loops vectorize
      pa = merge(1.0_wp, 0.0_wp, a2 > 0.0_wp)
      good = pa*merge(1.0_wp, 0.0_wp, t2 > -FLAT*a2)
      ph = c0*a2 + c1*t2
      ok = pa*merge(1.0_wp, 0.0_wp, ph > 0.0_wp)
      num = ph*a2
      den = 4.0_wp*max(d1x*d1x + d1y*d1y, d2x*d2x + d2y*d2y)
      ! J = A/A0, or 1 where the estimate is 0 (a0/a0: a division under a condition would
      ! stop the vectorizer); at least tiny, the smallest normal number (nh_wave_speed2_block)
      jr = max(merge(a2, a02, ok > 0.0_wp)/a02, tiny(1.0_wp))
   end subroutine corner_estimate

   !> dt2 = num/(den c^2) where ok, else 0, with c^2 the wave speed at the volume ratio jr.
   pure subroutine stable_finish(law, num, den, jr, ok, dt2)
      type(law_t), intent(in) :: law
      real(wp), intent(in), dimension(NBLOCK) :: num, den, jr, ok
      real(wp), intent(out) :: dt2(NBLOCK)
      real(wp) :: c2(NBLOCK)
      integer :: k
      call law_wave_speed2(law, NBLOCK, jr, c2)
      do k = 1, NBLOCK
         dt2(k) = merge(num(k)/merge(den(k)*c2(k), 1.0_wp, ok(k) > 0.0_wp), 0.0_wp, ok(k) > 0.0_wp)
      end do
   end subroutine stable_finish

   !> dt2min/emin: the smallest dt2 of the block's nb elements (first element off + k on ties)
   !> if below dt2min; efold (when 0): the first folded element (good = 0, stable_block).
   !> What the scan k = 1 .. nb with `if (dt2(k) < dt2min)` gives, from the block's smallest
   !> value m (a loop that vectorizes; a NaN, never below anything in the scan, counts as huge,
   !> which is not below dt2min <= huge either) and, only when m < dt2min, the first k with
   !> dt2(k) = m, whose value is taken (the scan keeps the first of -0 and +0 it meets). Every
   !> element is good when the smallest good (0 or 1) is 1.
   pure subroutine block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      integer, intent(in) :: nb, off
      real(wp), intent(in) :: dt2(NBLOCK), good(NBLOCK)
      real(wp), intent(inout) :: dt2min
      integer, intent(inout) :: emin, efold
      real(wp) :: m, g
      integer :: k
      m = dt2min
      g = 1.0_wp
      do k = 1, nb
         m = min(m, merge(dt2(k), huge(1.0_wp), dt2(k) == dt2(k)))
         g = min(g, good(k))
      end do
      if (m < dt2min) then
         do k = 1, nb
            if (dt2(k) == m) then
               dt2min = dt2(k)
               emin = off + k
               exit
            end if
         end do
      end if
      if (efold /= 0 .or. g > 0.0_wp) return
      do k = 1, nb
         if (.not. good(k) > 0.0_wp) then
            efold = off + k
            return
         end if
      end do
   end subroutine block_minimum

   !> Smallest critical time step of the elements from the current geometry x(2, nnode) (the same
   !> estimate, to the bit, as the force kernels compute at x = x0 + u):
   !>
   !>     dt_e = phi L_e / c_e,   L_e = A/(longest diagonal) of the current quad,
   !>     c_e^2 = (lambda + 2 mu - 2 lambda ln J)/rho0 at J = A/A0
   !>
   !> (A0 the reference area; c_e: the tangent dilatational wave speed of eq. 7.2, floored at
   !> sqrt(mu/rho0)). phi corrects for taper; with t = T_min/A, T_min the smallest of the four
   !> corner triangles (a-1, a, a+1), i.e. twice the smallest corner Jacobian:
   !>   nq = 2: phi^2 = 4 min_g det J_g / A = (1 - 1/sqrt 3) + (2/sqrt 3) t  (smallest Gauss point)
   !>   nq = 1: phi^2 = 4 m_min/(rho A)     = 2/3 (1 + t)                   (lightest node)
   !> Both give phi = 1 (L/c) for every parallelogram. Against the exact limit 2/omega_max of the
   !> linearized element with lumped mass, over random convex quads (corner angles down to 1 deg,
   !> tapers beyond 10:1, nu in [0, 0.499], hourglass coefficient up to 0.25), phi L/c stayed below
   !> 0.995 of the limit; L/c alone exceeds it by up to 2% for tapers of 1.6:1 and by 45% for
   !> wedge-like quads. An element with A <= 0 or phi^2 <= 0 gives dt_e = 0.
   !> dtmin: the smallest dt_e; emin: the first element that gives it; efold: the first element
   !> folded at a corner (a corner triangle of negative area beyond round-off, i.e. det J < 0 at that node,
   !> which the Gauss points of either rule need not see), 0 if none.
   pure subroutine q4_stable_dt(nq, nel, nnode, conn, x0, x, law, dtmin, emin, efold)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), x(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      real(wp), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      real(wp) :: dt2(NBLOCK), good(NBLOCK), dt2min
      integer :: e0, nb

      dt2min = huge(1.0_wp)
      emin = 0
      efold = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call gather(nb, nnode, conn(:, e0:e0 + nb - 1), x0, x, xr, yr, xc, yc)
         call stable_block(nq, xr, yr, xc, yc, law, dt2, good)
         call block_minimum(nb, e0 - 1, dt2, good, dt2min, emin, efold)
      end do
      dtmin = sqrt(dt2min)
   end subroutine q4_stable_dt

   !> Deformation gradient fg(1:4, g, e) = (F11, F12, F21, F22) and J = fg(5, g, e) at the
   !> nq x nq points of every element, as the force kernels compute them.
   pure subroutine q4_deformation(nq, nel, nnode, conn, x0, u, fg)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(out) :: fg(5, nq*nq, nel)
      real(wp), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac
      integer :: e0, nb, k, g

      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call block_deformation(nq, nb, nnode, conn(:, e0:e0 + nb - 1), x0, u, f11, f12, f21, f22, jac)
         do k = 1, nb
            do g = 1, nq*nq
               fg(:, g, e0 + k - 1) = [f11(k, g), f12(k, g), f21(k, g), f22(k, g), jac(k, g)]
            end do
         end do
      end do
   end subroutine q4_deformation

   !> F and J at the nq x nq points of the nb elements of one block (columns 1:nq*nq), from the
   !> force kernels' gather and kinematics.
   pure subroutine block_deformation(nq, nb, nnode, conn, x0, u, f11, f12, f21, f22, jac)
      integer, intent(in) :: nq, nb, nnode
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), dimension(NBLOCK, 4), intent(out) :: f11, f12, f21, f22, jac
      real(wp), dimension(NBLOCK, 4) :: xe, ye, uxe, uye, wt, i11, i12, i21, i22
      real(wp) :: r0(NBLOCK), p0(2, NBLOCK, 4), pu(2, NBLOCK, 4)
      if (nq == 2) then
         call gather_pairs(nb, nnode, conn, x0, u, p0, pu)
         call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      else
         call gather(nb, nnode, conn, x0, u, xe, ye, uxe, uye)
         call kinematics_1pt(xe, ye, uxe, uye, f11(:, 1), f12(:, 1), f21(:, 1), f22(:, 1), jac(:, 1), &
                             wt(:, 1), r0)
      end if
   end subroutine block_deformation

   !> Element stress for output: sig(:, e) = sxx, syy, szz, sxy, pressure (-tr sigma/3),
   !> von Mises, J; the mean over the Gauss points for nq = 2, the centroid value for nq = 1.
   !> A point with J <= 0 contributes zero stress (its J is still averaged).
   pure subroutine q4_stress(nq, nel, nnode, conn, x0, u, law, sig)
      integer, intent(in) :: nq                    !< 1 or 2
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      type(law_t), intent(in) :: law
      real(wp), intent(out) :: sig(7, nel)
      real(wp), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac, sxx, syy, szz, sxy
      real(wp) :: a(NBLOCK, 5), s(4), r
      integer :: e, e0, nb, k, g, ng

      ng = nq*nq
      r = 1.0_wp/real(ng, wp)
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call block_deformation(nq, nb, nnode, conn(:, e0:e0 + nb - 1), x0, u, f11, f12, f21, f22, jac)
         ! the points' stresses as one block (a point with J <= 0 contributes zero stress), then
         ! the means over the points in the order g = 1, ..., ng from +0, as point by point
         do g = 1, ng
            call law_cauchy(law, nb, f11(:, g), f12(:, g), f21(:, g), f22(:, g), jac(:, g), &
                                 sxx(:, g), syy(:, g), szz(:, g), sxy(:, g))
         end do
         a(1:nb, :) = 0.0_wp
         do g = 1, ng
            a(1:nb, 1) = a(1:nb, 1) + r*sxx(1:nb, g)
            a(1:nb, 2) = a(1:nb, 2) + r*syy(1:nb, g)
            a(1:nb, 3) = a(1:nb, 3) + r*szz(1:nb, g)
            a(1:nb, 4) = a(1:nb, 4) + r*sxy(1:nb, g)
            a(1:nb, 5) = a(1:nb, 5) + r*jac(1:nb, g)
         end do
         do k = 1, nb
            e = e0 + k - 1
            s = a(k, 1:4)
            sig(1:4, e) = s
            sig(5, e) = -(s(1) + s(2) + s(3))/3.0_wp
            sig(6, e) = sqrt(0.5_wp*((s(1) - s(2))**2 + (s(2) - s(3))**2 + (s(3) - s(1))**2) &
                             + 3.0_wp*s(4)**2)
            sig(7, e) = a(k, 5)
         end do
      end do
   end subroutine q4_stress

   !> kinematics_2x2 for q4_general.f90 (the pairs of gather_pairs).
   pure subroutine q4b_kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      real(wp), intent(in), dimension(2, NBLOCK, 4) :: p0, pu
      real(wp), intent(out), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac, wt, i11, i12, i21, i22
      call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
   end subroutine q4b_kinematics_2x2

   !> kinematics_1pt for q4_general.f90.
   pure subroutine q4b_kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(out), dimension(NBLOCK) :: f11, f12, f21, f22, jac, a0, r0
      call kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
   end subroutine q4b_kinematics_1pt

   !> positive for q4_general.f90.
   pure subroutine q4b_positive(n, jac, js)
      integer, intent(in) :: n
      real(wp), intent(in) :: jac(n)
      real(wp), intent(out) :: js(n)
      call positive(n, jac, js)
   end subroutine q4b_positive

   !> forces_2x2 for q4_general.f90.
   pure subroutine q4b_forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
      real(wp), intent(in), dimension(NBLOCK, 4) :: p11, p12, p21, p22, i11, i12, i21, i22
      real(wp), intent(out), dimension(NBLOCK, 4) :: fx, fy
      call forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
   end subroutine q4b_forces_2x2

   !> forces_1pt for q4_general.f90, the forces split into fx, fy.
   pure subroutine q4b_forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, kh, fx, fy, eh)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(in), dimension(NBLOCK) :: r0, p11, p12, p21, p22
      real(wp), intent(in) :: kh
      real(wp), intent(out), dimension(NBLOCK, 4) :: fx, fy
      real(wp), intent(out) :: eh(NBLOCK)
      real(wp) :: fp(2, NBLOCK, 4)
      call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, kh, fp, eh)
      call split_pairs(fp, fx, fy)
   end subroutine q4b_forces_1pt

   !> asqbi_forces for q4_general.f90.
   pure subroutine q4b_asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, lambda, mu, s, hx, &
                                    hy, eh)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(in), dimension(NBLOCK) :: r0, f11, f12, f21, f22
      real(wp), intent(in) :: lambda, mu, s
      real(wp), intent(out), dimension(NBLOCK, 4) :: hx, hy
      real(wp), intent(out) :: eh(NBLOCK)
      call asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, lambda, mu, s, hx, hy, eh)
   end subroutine q4b_asqbi_forces

   !> check_points for q4_general.f90.
   pure subroutine q4b_check_points(nb, np, off, jac, jmin, ebad)
      integer, intent(in) :: nb, np, off
      real(wp), intent(in) :: jac(NBLOCK, np)
      real(wp), intent(inout) :: jmin
      integer, intent(inout) :: ebad
      call check_points(nb, np, off, jac, jmin, ebad)
   end subroutine q4b_check_points

   !> stable_block for q4_general.f90.
   pure subroutine q4b_stable_block(nq, xr, yr, xc, yc, law, dt2, good)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      type(law_t), intent(in) :: law
      real(wp), intent(out), dimension(NBLOCK) :: dt2, good
      call stable_block(nq, xr, yr, xc, yc, law, dt2, good)
   end subroutine q4b_stable_block

   !> block_minimum for q4_general.f90.
   pure subroutine q4b_block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      integer, intent(in) :: nb, off
      real(wp), intent(in) :: dt2(NBLOCK), good(NBLOCK)
      real(wp), intent(inout) :: dt2min
      integer, intent(inout) :: emin, efold
      call block_minimum(nb, off, dt2, good, dt2min, emin, efold)
   end subroutine q4b_block_minimum

end module exic_element_quad4
