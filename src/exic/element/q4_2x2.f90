!> The 2x2 Gauss kernel of the 4-node plane-strain quadrilateral (quad4.f90 describes the element
!> and its block structure): internal force f_ia += sum_g det J0 P_iJ(F_g) dN_a/dX_J fused with
!> the stable step, on blocks of NBLOCK elements (q4_block.f90).
!>
!> The block routine and every step it runs per element (kinematics, the point values, the nodal
!> forces) are in this one file, so that gcc inlines them into the block's loops (it inlines
!> within a file only); the steps run once per block (gather, scatter, the J checks, the stable
!> step) are calls into q4_block.f90 and q4_stable.f90. The 2x2 kinematics and the plain block's
!> forces read the gathered (x, y) pairs themselves (gather_pairs), so that no split copy of the
!> corners is stored and loaded again (doc/performance.md, 6.2).
module exic_element_q4_2x2
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum
   use exic_material_law, only: law_t, law_piola
   use exic_element_q4_reference, only: gq
   use exic_element_q4_block, only: NBLOCK, gather_pairs, scatter_pairs, positive, check_points
   use exic_element_q4_stable, only: stable_block_pairs, block_minimum
   implicit none
   private

   public :: q4_force_2x2
   ! the block steps for quad4.f90 and the general solid path (q4_general.f90), as wrappers:
   ! the steps stay private, so that the compiler inlines them into the block routine
   public :: q4b_kinematics_2x2, q4b_forces_2x2

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

   !> kinematics_2x2 for q4_general.f90 (the pairs of gather_pairs).
   pure subroutine q4b_kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      real(wp), intent(in), dimension(2, NBLOCK, 4) :: p0, pu
      real(wp), intent(out), dimension(NBLOCK, 4) :: f11, f12, f21, f22, jac, wt, i11, i12, i21, i22
      call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
   end subroutine q4b_kinematics_2x2

   !> forces_2x2 for q4_general.f90.
   pure subroutine q4b_forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
      real(wp), intent(in), dimension(NBLOCK, 4) :: p11, p12, p21, p22, i11, i12, i21, i22
      real(wp), intent(out), dimension(NBLOCK, 4) :: fx, fy
      call forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
   end subroutine q4b_forces_2x2

end module exic_element_q4_2x2
