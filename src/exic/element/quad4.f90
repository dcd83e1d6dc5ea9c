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
!> The kernels live in one file per path, so that each block routine and the steps it runs per
!> element are in one file (gcc inlines within a file only): q4_2x2.f90 (2x2 Gauss), q4_1pt.f90
!> (one point with hourglass control), q4_stable.f90 (the stable step, shared by both and by the
!> general path, q4_general.f90); this module gathers them for the callers and computes the
!> deformation gradient and stress for output.
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
   use exic_material_law, only: law_t, law_cauchy
   use exic_element_q4_reference, only: q4_check_reference, q4_lumped_mass
   use exic_element_q4_block, only: NBLOCK, gather, gather_pairs
   use exic_element_q4_2x2, only: q4_force_2x2, kinematics_2x2 => q4b_kinematics_2x2
   use exic_element_q4_1pt, only: q4_force_1pt, kinematics_1pt => q4b_kinematics_1pt
   use exic_element_q4_stable, only: q4_stable_dt
   implicit none
   private

   public :: q4_check_reference, q4_force_2x2, q4_force_1pt, q4_lumped_mass, q4_stable_dt, &
             q4_deformation, q4_stress, NBLOCK

contains

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

end module exic_element_quad4
