!> The one-point kernel of the 4-node plane-strain quadrilateral (quad4.f90 describes the element
!> and its block structure): mean-strain internal force with Flanagan-Belytschko stiffness
!> hourglass control, or the assumed-strain (ASQBI) stabilization of doc/hourglass.md, fused with
!> the stable step, on blocks of NBLOCK elements (q4_block.f90).
!>
!> The block routine and every step it runs per element (mean kinematics, mean and hourglass
!> forces) are in this one file, so that gcc inlines them into the block's loops (it inlines
!> within a file only); the steps run once per block (gather, scatter, the J checks, the stable
!> step, the corner barrier) are calls into q4_block.f90, q4_stable.f90 and q4_barrier.f90.
module exic_element_q4_1pt
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum
   use exic_material_law, only: law_t, law_piola
   use exic_material_material, only: HOURGLASS_PHYSICAL
   use exic_element_q4_barrier, only: corner_barrier, barrier_limit
   use exic_element_q4_block, only: NBLOCK, gather, current, scatter, scatter_pairs, split_pairs, &
                                    positive, check_points
   use exic_element_q4_stable, only: stable_block, stable_block_u, block_minimum
   implicit none
   private

   public :: q4_force_1pt
   ! the block steps for quad4.f90 and the general solid path (q4_general.f90), as wrappers:
   ! the steps stay private, so that the compiler inlines them into the block routine
   public :: q4b_kinematics_1pt, q4b_forces_1pt, q4b_asqbi_forces

contains

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

   !> kinematics_1pt for q4_general.f90.
   pure subroutine q4b_kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, ye, uxe, uye
      real(wp), intent(out), dimension(NBLOCK) :: f11, f12, f21, f22, jac, a0, r0
      call kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
   end subroutine q4b_kinematics_1pt

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

end module exic_element_q4_1pt
