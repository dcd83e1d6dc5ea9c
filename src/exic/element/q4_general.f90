!> The general solid path of the 4-node element: axisymmetric solids (GLOBal AXISymmetric), sets
!> with J2 plasticity (history per Gauss point) and the mean-dilatation 2x2 element (MIXEd), in
!> the block structure of quad4.f90 (doc/axisymmetry.md derives every equation tagged (Ak)).
!>
!> The material law is the set's law_t (src/exic/material/law.f90), called once per block through
!> law_piola_general with the block's history: a law with history (J2) passes the stored one, a
!> law without the virgin state (the neo-Hookean law runs j2_piola with a yield stress never
!> reached, which gives nh_piola's stress and energy, with F33 = r/R in axisymmetry). The
!> plane-strain sets of laws without history keep the kernels of quad4.f90.
!>
!> Block steps (gather, kinematics, forces, stable step, scatter) are those of the plane kernels
!> (q4_block.f90, q4_2x2.f90, q4_1pt.f90, q4_stable.f90); this module adds
!> the hoop terms (A1)-(A5), the mean dilatation (A10)-(A12), the history copies and the ring
!> correction of the stable step (A7)-(A9).
module exic_element_q4_general
   use exic_base_kinds, only: wp
   use exic_base_sums, only: lane_sum
   use exic_base_cube_root, only: cbrt_block
   use exic_material_j2_hardening, only: j2_static_yield
   use exic_material_law, only: law_t, LAW_J2, NVMAX, law_init_history, law_piola_general, &
                                law_cauchy_general, law_wave_speed2
   use exic_material_material, only: HOURGLASS_STIFFNESS, HOURGLASS_PHYSICAL
   use exic_element_q4_block, only: NBLOCK, gather, gather_pairs, split_pairs, current, scatter
   use exic_element_q4_block, only: positive, check_points
   use exic_element_q4_2x2, only: kinematics_2x2 => q4b_kinematics_2x2, forces_2x2 => q4b_forces_2x2
   use exic_element_q4_1pt, only: kinematics_1pt => q4b_kinematics_1pt, forces_1pt => q4b_forces_1pt, &
                                  asqbi_forces => q4b_asqbi_forces
   use exic_element_q4_stable, only: q4_stable_dt, stable_block, block_minimum
   use exic_element_q4_barrier, only: corner_barrier, barrier_limit
   use exic_element_q4_plastic_work, only: NBOOK, book_init, book_block
   implicit none
   private

   public :: q4_solid_t, q4g_init, q4g_force, q4g_stable_dt, q4g_stress, q4g_hist_init
   public :: NSIG

   !> Element output rows: sxx syy szz sxy pressure mises J, ep, temperature, yield stress.
   integer, parameter :: NSIG = 10

   real(wp), parameter :: xin(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]   !< xi_a
   real(wp), parameter :: etn(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]   !< eta_a
   real(wp), parameter :: gq = 0.57735026918962576451_wp                 !< 1/sqrt(3)

   !> What a set of the general path is: quadrature, geometry, options and its law.
   type :: q4_solid_t
      integer :: nq = 2                      !< 2: 2x2 Gauss; 1: one point + hourglass
      logical :: axi = .false.               !< GLOBal AXISymmetric
      logical :: mixed = .false.             !< MIXEd: mean dilatation (2x2 only)
      logical :: plastic = .false.           !< J2 plasticity (ep, T and yield stress outputs)
      integer :: nvar = 0                    !< history values per point of the law (law_t%nvar)
      !> history values per point stored: nvar, and with plasticity the NBOOK values of the
      !> plastic work's booking after them (q4_plastic_work.f90, doc/plasticity.md (J31))
      integer :: nhist = 0
      real(wp) :: hg = 0.0_wp
      integer :: hgkind = HOURGLASS_STIFFNESS  !< or HOURGLASS_PHYSICAL (hg its scale; doc/hourglass.md)
      type(law_t) :: law                     !< the material law (material/law.f90)
   end type q4_solid_t

contains

   !> The description of a set with the law `law` (law_make).
   pure function q4g_init(nq, axi, mixed, law, hg, hgkind) result(o)
      integer, intent(in) :: nq
      logical, intent(in) :: axi, mixed
      type(law_t), intent(in) :: law
      real(wp), intent(in) :: hg
      integer, intent(in), optional :: hgkind   !< HOURGLASS_STIFFNESS (default) or HOURGLASS_PHYSICAL
      type(q4_solid_t) :: o
      if (present(hgkind)) o%hgkind = hgkind
      o%nq = nq
      o%axi = axi
      o%mixed = mixed .and. nq == 2
      o%law = law
      o%plastic = law%id == LAW_J2
      o%nvar = law%nvar
      o%nhist = law%nvar
      if (o%plastic) o%nhist = law%nvar + NBOOK
      o%hg = hg
   end function q4g_init

   !> The initial history of nel elements: hist(nhist, nq*nq, nel) (law_init_history, and the
   !> reference state of the plastic work's booking, book_init).
   pure subroutine q4g_hist_init(o, nel, hist)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nel
      real(wp), intent(out) :: hist(:, :, :)
      real(wp) :: h(1, NVMAX)
      integer :: e, g
      call law_init_history(o%law, 1, h)
      do e = 1, nel
         do g = 1, o%nq*o%nq
            hist(1:o%nvar, g, e) = h(1, 1:o%nvar)
         end do
      end do
      if (o%nhist > o%nvar) call book_init(o%nvar, hist)
   end subroutine q4g_hist_init

   !> Internal forces of nel elements (the general path of q4_force_2x2/q4_force_1pt), fused
   !> with the stable step, updating the history hist(nhist, nq*nq, nel) of a set with one (not
   !> used otherwise). dt: the step over which u changed (Johnson-Cook's rate). wint: strain
   !> energy, whg: hourglass energy, wdis: plastic work of the step by the trapezoid rule of the
   !> stress power (J31) (the history keeps what it needs: call once per step); the rest as in
   !> q4_force_2x2.
   pure subroutine q4g_force(o, nel, nnode, conn, x0, u, dt, hist, f, wint, whg, wdis, jmin, ebad, &
                             dt2min, emin, efold, v)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), dt
      real(wp), intent(inout) :: hist(:, :, :)
      real(wp), intent(inout) :: f(2, nnode)
      real(wp), intent(out) :: wint, whg, wdis, jmin, dt2min
      integer, intent(out) :: ebad, emin, efold
      !> nodal velocities: the kinematic step limit of the corner barrier (one point, physical
      !> control; doc/hourglass.md (H19))
      real(wp), intent(in), optional :: v(2, nnode)
      integer :: e0, nb, h0

      wint = 0.0_wp
      whg = 0.0_wp
      wdis = 0.0_wp
      jmin = huge(1.0_wp)
      dt2min = huge(1.0_wp)
      ebad = 0
      emin = 0
      efold = 0
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         h0 = 1
         if (o%nvar > 0) h0 = e0
         if (o%nq == 2) then
            call block_2x2(o, nb, e0 - 1, nnode, conn(:, e0:e0 + nb - 1), x0, u, dt, hist, h0, f, &
                           wint, wdis, jmin, ebad, dt2min, emin, efold)
         else
            call block_1pt(o, nb, e0 - 1, nnode, conn(:, e0:e0 + nb - 1), x0, u, dt, hist, h0, f, &
                           wint, whg, wdis, jmin, ebad, dt2min, emin, efold, v)
         end if
      end do
   end subroutine q4g_force

   !> N_a at the Gauss points of the 2x2 rule (point g at (xi_g, eta_g) = gq (xi_g, eta_g) of the
   !> node of the same number).
   pure real(wp) function shape2(a, g)
      integer, intent(in) :: a, g
      shape2 = 0.25_wp*(1.0_wp + xin(a)*gq*xin(g))*(1.0_wp + etn(a)*gq*etn(g))
   end function shape2

   !> One block of the 2x2 general path: kinematics with F33 and the ring weights (A1), (A3),
   !> mean dilatation (A10)-(A12), the law with the block's history, forces with the hoop term
   !> (A4), the stable step (A9).
   pure subroutine block_2x2(o, nb, off, nnode, conn, x0, u, dt, hist, h0, f, wint, wdis, jmin, &
                             ebad, dt2min, emin, efold)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nb, off, nnode, h0
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), dt
      real(wp), intent(inout) :: hist(:, :, :)
      real(wp), intent(inout) :: f(2, nnode), wint, wdis, jmin, dt2min
      integer, intent(inout) :: ebad, emin, efold
      real(wp), dimension(NBLOCK, 4) :: xe, ye, uxe, uye, f11, f12, f21, f22, jac, js, wt, i11, i12, &
                                        i21, i22, p11, p12, p21, p22, p33, wq, fx, fy, f33, rg, jchk, &
                                        b11, b12, b21, b22, b33, bj, al, dw, ys, yl
      real(wp), dimension(NBLOCK, 4, NVMAX) :: h
      real(wp) :: dt2(NBLOCK), good(NBLOCK), we(NBLOCK), nn(4, 4), p0(2, NBLOCK, 4), &
                  pu(2, NBLOCK, 4)
      integer :: k, g, a

      do g = 1, 4
         do a = 1, 4
            nn(a, g) = shape2(a, g)
         end do
      end do
      call gather_pairs(nb, nnode, conn, x0, u, p0, pu)
      call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
      call split_pairs(p0, xe, ye)
      call split_pairs(pu, uxe, uye)
      call hoop_2x2(o%axi, nn, xe, uxe, wt, rg, f33)
      call point_checks(4*NBLOCK, jac, f33, js, jchk)
      ! F of the law: F, or Fbar (A10)
      b11 = f11
      b12 = f12
      b21 = f21
      b22 = f22
      b33 = f33
      bj = js
      if (o%mixed) call mean_dilatation(wt, js, f33, al, b11, b12, b21, b22, b33, bj)
      call law(o, 4, nb, dt, hist, h0, h, b11, b12, b21, b22, b33, bj, wt, p11, p12, p21, p22, p33, &
               wq, dw, ys, yl)
      if (o%mixed) call mixed_stress(wt, js, f11, f12, f21, f22, f33, al, b11, b12, b21, b22, b33, &
                                     p11, p12, p21, p22, p33)
      ! the plastic work of the step (J31): the stress that works on F (p* with MIXEd) and F
      if (o%plastic) call book_block(4, nb, o%nvar, hist, h0, f11, f12, f21, f22, f33, p11, p12, &
                                     p21, p22, p33, wq, yl, wdis)
      call forces_2x2(p11, p12, p21, p22, i11, i12, i21, i22, fx, fy)
      if (o%axi) then
         ! hoop forces (A4)
         do a = 1, 4
            do k = 1, NBLOCK
               fx(k, a) = fx(k, a) + (((p33(k, 1)/rg(k, 1))*nn(a, 1) + (p33(k, 2)/rg(k, 2))*nn(a, 2)) &
                                      + ((p33(k, 3)/rg(k, 3))*nn(a, 3) + (p33(k, 4)/rg(k, 4))*nn(a, 4)))
            end do
         end do
      end if
      do k = 1, NBLOCK
         we(k) = ((wq(k, 1) + wq(k, 2)) + wq(k, 3)) + wq(k, 4)
      end do
      wint = wint + lane_sum(nb, we)
      call check_points(nb, 4, off, jchk, jmin, ebad)
      call current(xe, ye, uxe, uye)
      call stable_block(2, xe, ye, uxe, uye, o%law, dt2, good)
      if (o%axi) call ring_step(2, xe, ye, uxe, uye, o%law, dt2)
      call block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      call scatter(nb, nnode, conn, fx, fy, f)
   end subroutine block_2x2

   !> Reference radii rg, hoop stretch f33 = r/R and the ring weights wt <- wt R (A1), (A3) at the
   !> 2x2 points (x: reference radii, ux: radial displacements of the nodes); plane strain:
   !> f33 = 1, rg = 1, wt unchanged.
   pure subroutine hoop_2x2(axi, nn, xe, uxe, wt, rg, f33)
      logical, intent(in) :: axi
      real(wp), intent(in) :: nn(4, 4)
      real(wp), intent(in), dimension(NBLOCK, 4) :: xe, uxe
      real(wp), intent(inout), dimension(NBLOCK, 4) :: wt
      real(wp), intent(out), dimension(NBLOCK, 4) :: rg, f33
      real(wp) :: ur
      integer :: k, g
      if (.not. axi) then
         rg = 1.0_wp
         f33 = 1.0_wp
         return
      end if
      do g = 1, 4
         do k = 1, NBLOCK
            rg(k, g) = (nn(1, g)*xe(k, 1) + nn(2, g)*xe(k, 2)) + (nn(3, g)*xe(k, 3) + nn(4, g)*xe(k, 4))
            ur = (nn(1, g)*uxe(k, 1) + nn(2, g)*uxe(k, 2)) + (nn(3, g)*uxe(k, 3) + nn(4, g)*uxe(k, 4))
            f33(k, g) = (rg(k, g) + ur)/rg(k, g)
            wt(k, g) = wt(k, g)*rg(k, g)
         end do
      end do
   end subroutine hoop_2x2

   !> js = j where the in-plane j > 0, else 1; f33 <- 1 where f33 <= 0 (the law stays finite on
   !> an element the caller rejects); jchk = J = j F33 where both are positive, else the
   !> smaller of the two (<= 0: the point is inverted or through the axis).
   pure subroutine point_checks(n, jac, f33, js, jchk)
      integer, intent(in) :: n
      real(wp), intent(in) :: jac(n)
      real(wp), intent(inout) :: f33(n)
      real(wp), intent(out) :: js(n), jchk(n)
      integer :: q
      call positive(n, jac, js)
      do q = 1, n
         jchk(q) = merge(jac(q)*f33(q), min(jac(q), f33(q)), jac(q) > 0.0_wp .and. f33(q) > 0.0_wp)
         f33(q) = merge(f33(q), 1.0_wp, f33(q) > 0.0_wp)
      end do
   end subroutine point_checks

   !> Fbar = alpha F, alpha = (Jbar/J)^(1/3) with Jbar the weighted mean of J = j F33 over the
   !> element's four points (A10); b.. hold F on entry and Fbar on exit, bj the in-plane j of Fbar.
   !> The cube root is exic's (base/cube_root.f90): the same bits in vector and scalar loops.
   pure subroutine mean_dilatation(wt, js, f33, al, b11, b12, b21, b22, b33, bj)
      real(wp), intent(in), dimension(NBLOCK, 4) :: wt, js, f33
      real(wp), intent(out), dimension(NBLOCK, 4) :: al
      real(wp), intent(inout), dimension(NBLOCK, 4) :: b11, b12, b21, b22, b33, bj
      real(wp) :: v0, jb, ratio(NBLOCK, 4)
      integer :: k, g
      do k = 1, NBLOCK
         v0 = (wt(k, 1) + wt(k, 2)) + (wt(k, 3) + wt(k, 4))
         jb = ((wt(k, 1)*(js(k, 1)*f33(k, 1)) + wt(k, 2)*(js(k, 2)*f33(k, 2))) &
               + (wt(k, 3)*(js(k, 3)*f33(k, 3)) + wt(k, 4)*(js(k, 4)*f33(k, 4))))/v0
         do g = 1, 4
            ratio(k, g) = jb/(js(k, g)*f33(k, g))
         end do
      end do
      call cbrt_block(4*NBLOCK, ratio, al)
      do k = 1, NBLOCK
         do g = 1, 4
            b11(k, g) = al(k, g)*b11(k, g)
            b12(k, g) = al(k, g)*b12(k, g)
            b21(k, g) = al(k, g)*b21(k, g)
            b22(k, g) = al(k, g)*b22(k, g)
            b33(k, g) = al(k, g)*b33(k, g)
            bj(k, g) = (al(k, g)*al(k, g))*bj(k, g)
         end do
      end do
   end subroutine mean_dilatation

   !> The stress that works on delta F of the mean-dilatation element (A11), (A12): p holds
   !> w P(Fbar) on entry and p* on exit; f.. is F, b.. is Fbar, js the in-plane j of F.
   pure subroutine mixed_stress(wt, js, f11, f12, f21, f22, f33, al, b11, b12, b21, b22, b33, p11, &
                                p12, p21, p22, p33)
      real(wp), intent(in), dimension(NBLOCK, 4) :: wt, js, f11, f12, f21, f22, f33, al, b11, b12, &
                                                    b21, b22, b33
      real(wp), intent(inout), dimension(NBLOCK, 4) :: p11, p12, p21, p22, p33
      real(wp) :: t(4), v0, jb, pm, c, rj
      integer :: k, g
      do k = 1, NBLOCK
         v0 = (wt(k, 1) + wt(k, 2)) + (wt(k, 3) + wt(k, 4))
         jb = ((wt(k, 1)*(js(k, 1)*f33(k, 1)) + wt(k, 2)*(js(k, 2)*f33(k, 2))) &
               + (wt(k, 3)*(js(k, 3)*f33(k, 3)) + wt(k, 4)*(js(k, 4)*f33(k, 4))))/v0
         do g = 1, 4
            t(g) = (p11(k, g)*b11(k, g) + p12(k, g)*b12(k, g)) + (p21(k, g)*b21(k, g) &
                   + p22(k, g)*b22(k, g)) + p33(k, g)*b33(k, g)
         end do
         pm = ((t(1) + t(2)) + (t(3) + t(4)))/(3.0_wp*jb*v0)
         do g = 1, 4
            c = pm*wt(k, g)*(js(k, g)*f33(k, g)) - t(g)/3.0_wp
            rj = c/js(k, g)
            p11(k, g) = al(k, g)*p11(k, g) + rj*f22(k, g)
            p12(k, g) = al(k, g)*p12(k, g) - rj*f21(k, g)
            p21(k, g) = al(k, g)*p21(k, g) - rj*f12(k, g)
            p22(k, g) = al(k, g)*p22(k, g) + rj*f11(k, g)
            p33(k, g) = al(k, g)*p33(k, g) + c/f33(k, g)
         end do
      end do
   end subroutine mixed_stress

   !> The law at the np x NBLOCK points of a block (law_piola_general) with the block's history
   !> copied in from hist(:, :, h0 + k - 1) (lanes 1..nb; the padding lanes repeat lane nb) and
   !> back after the call, for a law with history; the virgin history for one without. yl: 1 at
   !> a point whose plastic strain grew (a plastic set), else 0.
   pure subroutine law(o, np, nb, dt, hist, h0, h, f11, f12, f21, f22, f33, js, wt, p11, p12, p21, &
                       p22, p33, wq, dw, ys, yl)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: np, nb, h0
      real(wp), intent(in) :: dt
      real(wp), intent(inout) :: hist(:, :, :)
      real(wp), intent(out) :: h(NBLOCK, np, NVMAX)
      real(wp), intent(in), dimension(NBLOCK, np) :: f11, f12, f21, f22, f33, js, wt
      real(wp), intent(out), dimension(NBLOCK, np) :: p11, p12, p21, p22, p33, wq, dw, ys, yl
      real(wp) :: ep0(NBLOCK, np)
      integer :: k, g, v
      if (o%nvar > 0) then
         do g = 1, np
            do v = 1, o%nvar
               do k = 1, nb
                  h(k, g, v) = hist(v, g, h0 + k - 1)
               end do
               h(nb + 1:, g, v) = h(nb, g, v)
            end do
         end do
      else
         call law_init_history(o%law, np*NBLOCK, h)
      end if
      if (o%plastic) ep0 = h(:, :, 5)
      call law_piola_general(o%law, np*NBLOCK, dt, f11, f12, f21, f22, f33, js, wt, h, p11, p12, &
                             p21, p22, p33, wq, dw, ys)
      if (o%nvar > 0) then
         do g = 1, np
            do v = 1, o%nvar
               do k = 1, nb
                  hist(v, g, h0 + k - 1) = h(k, g, v)
               end do
            end do
         end do
      end if
      yl = 0.0_wp
      if (o%plastic) yl = merge(1.0_wp, 0.0_wp, h(:, :, 5) > ep0)
   end subroutine law

   !> One block of the one-point general path: F at the centroid with F33 = r_c/R_c and the
   !> weight A0 R_c, hoop force p33/(4 R_c), hourglass forces and energy times R_c (section 3).
   pure subroutine block_1pt(o, nb, off, nnode, conn, x0, u, dt, hist, h0, f, wint, whg, wdis, jmin, &
                             ebad, dt2min, emin, efold, v)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nb, off, nnode, h0
      integer, intent(in) :: conn(4, nb)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode), dt
      real(wp), intent(inout) :: hist(:, :, :)
      real(wp), intent(inout) :: f(2, nnode), wint, whg, wdis, jmin, dt2min
      integer, intent(inout) :: ebad, emin, efold
      real(wp), dimension(NBLOCK, 4) :: xe, ye, uxe, uye, fx, fy, hx, hy
      real(wp), dimension(NBLOCK) :: f11, f12, f21, f22, jac, js, a0, r0, p11, p12, p21, p22, p33, &
                                     wq, eh, dt2, good, f33, rc, wt, jchk, dw, ys, zero, ob, yl
      real(wp), intent(in), optional :: v(2, nnode)
      real(wp) :: h(NBLOCK, 1, NVMAX), kh
      integer :: k, a

      kh = o%hg*(o%law%lambda + 2.0_wp*o%law%mu)
      call gather(nb, nnode, conn, x0, u, xe, ye, uxe, uye)
      call kinematics_1pt(xe, ye, uxe, uye, f11, f12, f21, f22, jac, a0, r0)
      if (o%axi) then
         do k = 1, NBLOCK
            rc(k) = 0.25_wp*((xe(k, 1) + xe(k, 2)) + (xe(k, 3) + xe(k, 4)))
            f33(k) = (rc(k) + 0.25_wp*((uxe(k, 1) + uxe(k, 2)) + (uxe(k, 3) + uxe(k, 4))))/rc(k)
            wt(k) = a0(k)*rc(k)
         end do
      else
         f33 = 1.0_wp
         wt = a0
      end if
      call point_checks(NBLOCK, jac, f33, js, jchk)
      call law(o, 1, nb, dt, hist, h0, h, f11, f12, f21, f22, f33, js, wt, p11, p12, p21, p22, p33, &
               wq, dw, ys, yl)
      ! the plastic work of the step (J31); the hourglass forces stay elastic and outside it
      if (o%plastic) call book_block(1, nb, o%nvar, hist, h0, f11, f12, f21, f22, f33, p11, p12, &
                                     p21, p22, p33, wq, yl, wdis)
      if (o%axi) then
         ! mean part with the ring weights, hourglass part of the plane element times R_c
         zero = 0.0_wp
         call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, 0.0_wp, fx, fy, eh)
         if (o%hgkind == HOURGLASS_PHYSICAL) then
            call asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, o%law%lambda, o%law%mu, o%hg, &
                              hx, hy, eh)
         else
            call forces_1pt(xe, ye, uxe, uye, r0, zero, zero, zero, zero, kh, hx, hy, eh)
         end if
         do a = 1, 4
            do k = 1, NBLOCK
               fx(k, a) = fx(k, a) + rc(k)*hx(k, a) + 0.25_wp*(p33(k)/rc(k))
               fy(k, a) = fy(k, a) + rc(k)*hy(k, a)
            end do
         end do
         eh = rc*eh
      else if (o%hgkind == HOURGLASS_PHYSICAL) then
         call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, 0.0_wp, fx, fy, eh)
         call asqbi_forces(xe, ye, uxe, uye, r0, f11, f12, f21, f22, o%law%lambda, o%law%mu, o%hg, hx, &
                           hy, eh)
         fx = fx + hx
         fy = fy + hy
      else
         call forces_1pt(xe, ye, uxe, uye, r0, p11, p12, p21, p22, kh, fx, fy, eh)
      end if
      wint = wint + lane_sum(nb, wq)
      call check_points(nb, 1, off, jchk, jmin, ebad)
      call current(xe, ye, uxe, uye)
      ! the corner barrier (doc/hourglass.md section 5), times R_c in axisymmetry
      if (o%hgkind == HOURGLASS_PHYSICAL) then
         if (.not. o%axi) rc = 1.0_wp
         call corner_barrier(NBLOCK, xe, ye, uxe, uye, rc, o%law%lambda, o%law%mu, o%law%rho, fx, fy, eh, ob)
      end if
      whg = whg + lane_sum(nb, eh)
      call stable_block(1, xe, ye, uxe, uye, o%law, dt2, good)
      if (o%hgkind == HOURGLASS_PHYSICAL) call barrier_limit(NBLOCK, nb, nnode, conn, uxe, uye, ob, dt2, v)
      if (o%axi) call ring_step(1, xe, ye, uxe, uye, o%law, dt2)
      call block_minimum(nb, off, dt2, good, dt2min, emin, efold)
      call scatter(nb, nnode, conn, fx, fy, f)
   end subroutine block_1pt

   !> The stable step of ring elements (A7)-(A9): dt2 holds the plane estimate dt_p^2 on entry
   !> (0: no step) and dt^2 = 1/(sqrt(R_max/rbar_min)/dt_p + omega_h/2)^2 on exit. (xr, yr):
   !> reference corners, (xc, yc): current ones.
   !> Every loop runs over the block's elements innermost, so that gcc vectorizes it; each
   !> element's operations are those of the point-by-point form, in its order (the sums over the
   !> points g = 1..4 in turn), so the same bits. min and max stand for minval and maxval of
   !> four values: the same result, for the values are positive and finite on a valid reference
   !> element (det J0 > 0, q4_check_reference; every node at r >= 0, the deck's
   !> check_axisymmetric).
   pure subroutine ring_step(nq, xr, yr, xc, yc, law, dt2)
      integer, intent(in) :: nq
      real(wp), intent(in), dimension(NBLOCK, 4) :: xr, yr, xc, yc
      type(law_t), intent(in) :: law
      real(wp), intent(inout) :: dt2(NBLOCK)
      real(wp), dimension(NBLOCK) :: jr, c2, sr, hm, c1x, c2x, c3x, c1y, c2y, c3y, rc, a0, rmax
      real(wp), dimension(NBLOCK, 4) :: d, rg, m, mp, hh
      real(wp) :: xi, eta, nn, rcur, a, dtp
      integer :: k, g, i

      do k = 1, NBLOCK
         c1x(k) = 0.25_wp*((xr(k, 2) - xr(k, 1)) + (xr(k, 3) - xr(k, 4)))
         c2x(k) = 0.25_wp*((xr(k, 4) - xr(k, 1)) + (xr(k, 3) - xr(k, 2)))
         c3x(k) = 0.25_wp*((xr(k, 1) - xr(k, 2)) + (xr(k, 3) - xr(k, 4)))
         c1y(k) = 0.25_wp*((yr(k, 2) - yr(k, 1)) + (yr(k, 3) - yr(k, 4)))
         c2y(k) = 0.25_wp*((yr(k, 4) - yr(k, 1)) + (yr(k, 3) - yr(k, 2)))
         c3y(k) = 0.25_wp*((yr(k, 1) - yr(k, 2)) + (yr(k, 3) - yr(k, 4)))
         rc(k) = 0.25_wp*((xr(k, 1) + xr(k, 2)) + (xr(k, 3) + xr(k, 4)))
         a0(k) = 0.5_wp*((xr(k, 3) - xr(k, 1))*(yr(k, 4) - yr(k, 2)) - (yr(k, 3) - yr(k, 1))*(xr(k, 4) - xr(k, 2)))
      end do
      m = 0.0_wp
      mp = 0.0_wp
      hh = 0.0_wp
      do g = 1, 4
         xi = gq*xin(g)
         eta = gq*etn(g)
         do k = 1, NBLOCK
            d(k, g) = (c1x(k) + c3x(k)*eta)*(c2y(k) + c3y(k)*xi) &
                      - (c2x(k) + c3x(k)*xi)*(c1y(k) + c3y(k)*eta)
            rg(k, g) = (((0.0_wp + shape2(1, g)*xr(k, 1)) + shape2(2, g)*xr(k, 2)) + shape2(3, g)*xr(k, 3)) &
                       + shape2(4, g)*xr(k, 4)
         end do
         do i = 1, 4
            nn = shape2(i, g)
            do k = 1, NBLOCK
               m(k, i) = m(k, i) + d(k, g)*nn*rg(k, g)
               mp(k, i) = mp(k, i) + d(k, g)*nn
            end do
            ! the one-point element takes hh from its centre below
            if (nq == 1) cycle
            do k = 1, NBLOCK
               hh(k, i) = hh(k, i) + d(k, g)*nn/rg(k, g)
            end do
         end do
      end do
      if (nq == 1) then
         do k = 1, NBLOCK
            rmax(k) = rc(k)
            hh(k, :) = a0(k)/(4.0_wp*rc(k))
         end do
      else
         do k = 1, NBLOCK
            rmax(k) = max(max(max(rg(k, 1), rg(k, 2)), rg(k, 3)), rg(k, 4))
         end do
      end if
      do k = 1, NBLOCK
         sr(k) = sqrt(rmax(k)/min(min(min(m(k, 1)/mp(k, 1), m(k, 2)/mp(k, 2)), m(k, 3)/mp(k, 3)), &
                                  m(k, 4)/mp(k, 4)))
         hm(k) = max(max(max(hh(k, 1)/m(k, 1), hh(k, 2)/m(k, 2)), hh(k, 3)/m(k, 3)), hh(k, 4)/m(k, 4))
         rcur = 0.25_wp*((xc(k, 1) + xc(k, 2)) + (xc(k, 3) + xc(k, 4)))
         a = 0.5_wp*((xc(k, 3) - xc(k, 1))*(yc(k, 4) - yc(k, 2)) - (yc(k, 3) - yc(k, 1))*(xc(k, 4) - xc(k, 2)))
         jr(k) = (a/a0(k))*(rcur/rc(k))
         jr(k) = merge(jr(k), 1.0_wp, jr(k) > 0.0_wp)
         jr(k) = max(jr(k), tiny(1.0_wp))   ! a normal number (nh_wave_speed2_block)
      end do
      call law_wave_speed2(law, NBLOCK, jr, c2)
      ! dt2 >= 0 (stable_block's estimates, barrier_limit's bounds); no step, dt2 = +0, stays +0
      ! through the formula itself (sr/0 = +Inf, 1/Inf = +0), so no selection is needed
      do k = 1, NBLOCK
         dtp = sqrt(dt2(k))
         a = 1.0_wp/(sr(k)/dtp + 0.5_wp*sqrt(c2(k)*hm(k)))
         dt2(k) = a*a
      end do
   end subroutine ring_step

   !> The stable step of nel elements at the current coordinates x: q4_stable_dt, with the ring
   !> correction (A9) of each block's estimate in axisymmetry.
   pure subroutine q4g_stable_dt(o, nel, nnode, conn, x0, x, dtmin, emin, efold)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), x(2, nnode)
      real(wp), intent(out) :: dtmin
      integer, intent(out) :: emin, efold
      if (o%axi) then
         call q4_stable_dt(o%nq, nel, nnode, conn, x0, x, o%law, dtmin, emin, efold, ring_step)
      else
         call q4_stable_dt(o%nq, nel, nnode, conn, x0, x, o%law, dtmin, emin, efold)
      end if
   end subroutine q4g_stable_dt

   !> Element outputs sig(NSIG, nel): the mean over the points of the Cauchy stress (sxx, syy,
   !> szz = hoop or out-of-plane, sxy) of j2_cauchy from F (Fbar with MIXEd) and the history,
   !> pressure, von Mises, J, and the means of ep, temperature and static yield stress
   !> (doc/axisymmetry.md, section 8). A point with J <= 0 contributes zero stress.
   pure subroutine q4g_stress(o, nel, nnode, conn, x0, u, hist, sig)
      type(q4_solid_t), intent(in) :: o
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode), u(2, nnode)
      real(wp), intent(in) :: hist(:, :, :)
      real(wp), intent(out) :: sig(NSIG, nel)
      real(wp), dimension(NBLOCK, 4) :: xe, ye, uxe, uye, f11, f12, f21, f22, jac, js, wt, i11, i12, &
                                        i21, i22, f33, rg, jchk, al, b11, b12, b21, b22, b33, bj
      real(wp), dimension(NBLOCK) :: a0, r0
      real(wp) :: h(1, NVMAX), s(4), ys(1), nn(4, 4), r, fb(5), p0(2, NBLOCK, 4), pu(2, NBLOCK, 4)
      integer :: e0, nb, k, g, ng, e, a

      do g = 1, 4
         do a = 1, 4
            nn(a, g) = shape2(a, g)
         end do
      end do
      ng = o%nq*o%nq
      r = 1.0_wp/real(ng, wp)
      do e0 = 1, nel, NBLOCK
         nb = min(NBLOCK, nel - e0 + 1)
         call gather_pairs(nb, nnode, conn(:, e0:e0 + nb - 1), x0, u, p0, pu)
         call split_pairs(p0, xe, ye)
         call split_pairs(pu, uxe, uye)
         if (o%nq == 2) then
            call kinematics_2x2(p0, pu, f11, f12, f21, f22, jac, wt, i11, i12, i21, i22)
            call hoop_2x2(o%axi, nn, xe, uxe, wt, rg, f33)
         else
            call kinematics_1pt(xe, ye, uxe, uye, f11(:, 1), f12(:, 1), f21(:, 1), f22(:, 1), &
                                jac(:, 1), a0, r0)
            do k = 1, NBLOCK
               f33(k, 1) = 1.0_wp
               if (o%axi) f33(k, 1) = 1.0_wp + sum(uxe(k, :))/sum(xe(k, :))
            end do
            wt(:, 1) = a0
         end if
         call point_checks(NBLOCK*ng, jac(:, 1:ng), f33(:, 1:ng), js(:, 1:ng), jchk(:, 1:ng))
         b11 = f11
         b12 = f12
         b21 = f21
         b22 = f22
         b33 = f33
         bj = js
         if (o%mixed) call mean_dilatation(wt, js, f33, al, b11, b12, b21, b22, b33, bj)
         do k = 1, nb
            e = e0 + k - 1
            sig(:, e) = 0.0_wp
            do g = 1, ng
               call law_init_history(o%law, 1, h)
               if (o%nvar > 0) h(1, 1:o%nvar) = hist(1:o%nvar, g, e)
               if (jchk(k, g) > 0.0_wp) then
                  fb = [b11(k, g), b12(k, g), b21(k, g), b22(k, g), b33(k, g)]
                  call law_cauchy_general(o%law, 1, fb(1:1), fb(2:2), fb(3:3), fb(4:4), fb(5:5), h, &
                                          s(1:1), s(2:2), s(3:3), s(4:4), ys)
                  sig(1:4, e) = sig(1:4, e) + r*s
               end if
               sig(7, e) = sig(7, e) + r*jchk(k, g)
               if (o%plastic) then
                  sig(8, e) = sig(8, e) + r*h(1, 5)
                  sig(9, e) = sig(9, e) + r*h(1, 6)
                  sig(10, e) = sig(10, e) + r*j2_static_yield(o%law%j2, h(1, 5), h(1, 6))
               end if
            end do
            s = sig(1:4, e)
            sig(5, e) = -(s(1) + s(2) + s(3))/3.0_wp
            sig(6, e) = sqrt(0.5_wp*((s(1) - s(2))**2 + (s(2) - s(3))**2 + (s(3) - s(1))**2) &
                             + 3.0_wp*s(4)**2)
         end do
      end do
   end subroutine q4g_stress

end module exic_element_q4_general
