!> The compressible neo-Hookean solid of the seed's eq. 7.2, in plane strain.
!>
!> Cauchy stress (eq. 7.2):
!>
!>     sigma = lambda ln(J)/J 1 + mu/J (b - 1),        b = F F^T,  J = det F
!>
!> Strain energy per unit reference volume:
!>
!>     W = lambda/2 (ln J)^2 + mu/2 (I1 - 3) - mu ln J,   I1 = tr C = tr b
!>
!> This W is the one whose derivative gives eq. 7.2 (P = dW/dF, sigma = P F^T / J). The seed's
!> eq. 7.1 as printed, mu (I1 - 3 - 1/2 ln J), is a misprint: its derivative leaves a residual
!> stress at F = 1. The correct term is mu (I1 - 3)/2 - mu ln J = mu/2 (I1 - 3 - 2 ln J).
!>
!> Plane strain: F = [F11 F12 0; F21 F22 0; 0 0 1], so J = F11 F22 - F12 F21 and I1 carries
!> C33 = 1. First Piola-Kirchhoff stress (in-plane components):
!>
!>     P = J sigma F^-T = lambda ln(J) F^-T + mu (F - F^-T)
!>
!> The kernels assume J > 0; callers check J first. nh_piola is the law for the internal forces
!> (one kernel for every quadrature), nh_cauchy its Cauchy form for stress output (and
!> nh_cauchy_block the same operations on a block of points), nh_wave_speed2_block the wave
!> speed of the stable step. ln J is exic's own logarithm (src/exic/base/logarithm.f90), the
!> same bits in vector and scalar code; the block kernels take it with ln_normal_block, for J a
!> positive normal number (>= tiny(1.0) = 2.2e-308), nh_cauchy_block with ln_block.
module exic_material_neohookean
   use exic_base_kinds, only: wp
   use exic_base_logarithm, only: ln, ln_block, ln_normal_block
   implicit none
   private

   public :: nh_piola, nh_cauchy, nh_cauchy_block, nh_wave_speed2, nh_wave_speed2_block

   !> Points per pass of the block kernels (their ln J work array stays in the L1 cache).
   integer, parameter :: CHUNK = 128

contains

   !> Cauchy stress (eq. 7.2), J and the strain energy per reference volume for plane-strain F:
   !> the law in the Cauchy form the seed prints, for stress output (forces use nh_piola).
   elemental subroutine nh_cauchy(lambda, mu, f11, f12, f21, f22, sxx, syy, szz, sxy, jac, w)
      real(wp), intent(in) :: lambda, mu          !< Lame constants
      real(wp), intent(in) :: f11, f12, f21, f22  !< in-plane deformation gradient
      real(wp), intent(out) :: sxx, syy, szz, sxy !< Cauchy stress
      real(wp), intent(out) :: jac                !< J = det F
      real(wp), intent(out) :: w                  !< strain energy per reference volume
      real(wp) :: lnj, rj, b11, b22, b12, p

      jac = f11*f22 - f12*f21
      lnj = ln(jac)
      rj = 1.0_wp/jac
      b11 = f11*f11 + f12*f12
      b22 = f21*f21 + f22*f22
      b12 = f11*f21 + f12*f22
      p = lambda*lnj*rj
      sxx = p + mu*rj*(b11 - 1.0_wp)
      syy = p + mu*rj*(b22 - 1.0_wp)
      szz = p
      sxy = mu*rj*b12
      w = 0.5_wp*lambda*lnj*lnj + 0.5_wp*mu*(b11 + b22 - 2.0_wp) - mu*lnj
   end subroutine nh_cauchy

   !> The Cauchy stress of nh_cauchy at n points, vectorized: the same operations in the same
   !> order (ln_block gives the bits of ln), so the same bits as nh_cauchy point by point. Where
   !> the caller's volume ratio jk(q) is not positive the stress is zero and F is not used.
   pure subroutine nh_cauchy_block(n, lambda, mu, f11, f12, f21, f22, jk, sxx, syy, szz, sxy)
      integer, intent(in) :: n                             !< number of points
      real(wp), intent(in) :: lambda, mu                   !< Lame constants
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n) !< in-plane deformation gradient
      real(wp), intent(in) :: jk(n)                        !< the caller's J of each point
      real(wp), intent(out) :: sxx(n), syy(n), szz(n), sxy(n) !< Cauchy stress
      real(wp) :: jac(CHUNK), lnj(CHUNK), rj, b11, b22, b12, p
      integer :: q0, m, i, q

      ! every value is formed for every point and selected in a loop of its own: gcc keeps a
      ! floating-point operation under a condition (merge of a formed value) out of vector code
      do q0 = 1, n, CHUNK
         m = min(CHUNK, n - q0 + 1)
         do i = 1, m
            q = q0 + i - 1
            jac(i) = f11(q)*f22(q) - f12(q)*f21(q)
         end do
         do i = 1, m
            jac(i) = merge(jac(i), 1.0_wp, jk(q0 + i - 1) > 0.0_wp)
         end do
         call ln_block(m, jac, lnj)
         do i = 1, m
            q = q0 + i - 1
            rj = 1.0_wp/jac(i)
            b11 = f11(q)*f11(q) + f12(q)*f12(q)
            b22 = f21(q)*f21(q) + f22(q)*f22(q)
            b12 = f11(q)*f21(q) + f12(q)*f22(q)
            p = lambda*lnj(i)*rj
            sxx(q) = p + mu*rj*(b11 - 1.0_wp)
            syy(q) = p + mu*rj*(b22 - 1.0_wp)
            szz(q) = p
            sxy(q) = mu*rj*b12
         end do
         do q = q0, q0 + m - 1
            sxx(q) = merge(sxx(q), 0.0_wp, jk(q) > 0.0_wp)
            syy(q) = merge(syy(q), 0.0_wp, jk(q) > 0.0_wp)
            szz(q) = merge(szz(q), 0.0_wp, jk(q) > 0.0_wp)
            sxy(q) = merge(sxy(q), 0.0_wp, jk(q) > 0.0_wp)
         end do
      end do
   end subroutine nh_cauchy_block

   !> First Piola-Kirchhoff stress and strain energy at n points whose J = det F the caller has
   !> computed and checked to be a positive normal number (ln_normal_block), each times the
   !> point's weight wt (the quadrature weight x reference volume it stands for; 1 for values
   !> per unit reference volume): the one kernel
   !> of the law for forces, used by both quadratures of the element and by the tests.
   !>
   !>     P = lambda ln(J) F^-T + mu (F - F^-T) = mu F + (lambda ln J - mu)/J cof F
   !>     W = ln J (lambda/2 ln J - mu) + mu/2 (F11^2 + F12^2 + F21^2 + F22^2 - 2)
   !>
   !> with cof F = [F22 -F21; -F12 F11] in plane strain (F33 = 1, so I1 - 3 = |F|^2 - 2).
   pure subroutine nh_piola(n, lambda, mu, f11, f12, f21, f22, jac, wt, p11, p12, p21, p22, w)
      integer, intent(in) :: n                             !< number of points
      real(wp), intent(in) :: lambda, mu                   !< Lame constants
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n) !< in-plane deformation gradient
      real(wp), intent(in) :: jac(n)                       !< J = det F >= tiny(1.0)
      real(wp), intent(in) :: wt(n)                        !< weight of each point
      real(wp), intent(out) :: p11(n), p12(n), p21(n), p22(n) !< wt x first Piola-Kirchhoff stress
      real(wp), intent(out) :: w(n)                        !< wt x strain energy per reference volume
      real(wp) :: lnj(CHUNK), c
      integer :: q0, m, i, q

      do q0 = 1, n, CHUNK
         m = min(CHUNK, n - q0 + 1)
         call ln_normal_block(m, jac(q0:q0 + m - 1), lnj)
         do i = 1, m
            q = q0 + i - 1
            c = (lambda*lnj(i) - mu)/jac(q)
            p11(q) = wt(q)*(mu*f11(q) + c*f22(q))
            p12(q) = wt(q)*(mu*f12(q) - c*f21(q))
            p21(q) = wt(q)*(mu*f21(q) - c*f12(q))
            p22(q) = wt(q)*(mu*f22(q) + c*f11(q))
            w(q) = wt(q)*(lnj(i)*(0.5_wp*lambda*lnj(i) - mu) &
                          + 0.5_wp*mu*(f11(q)*f11(q) + f12(q)*f12(q) + f21(q)*f21(q) + f22(q)*f22(q) - 2.0_wp))
         end do
      end do
   end subroutine nh_piola

   !> Square of the tangent dilatational wave speed at volume ratio J:
   !> c^2 = (lambda + 2 mu - 2 lambda ln J)/rho0 (spatial moduli lambda/J and (mu - lambda ln J)/J,
   !> current density rho0/J). Where that falls below mu/rho0 (large dilatation, where the
   !> tangent loses ellipticity) mu/rho0 is returned so that the value stays positive.
   elemental function nh_wave_speed2(lambda, mu, rho0, jac) result(c2)
      real(wp), intent(in) :: lambda, mu !< Lame constants
      real(wp), intent(in) :: rho0       !< reference density
      real(wp), intent(in) :: jac        !< volume ratio J > 0
      real(wp) :: c2
      c2 = max(lambda + 2.0_wp*mu - 2.0_wp*lambda*ln(jac), mu)/rho0
   end function nh_wave_speed2

   !> nh_wave_speed2 at n points: c2(q) = c^2 at volume ratio jac(q) >= tiny(1.0), a positive
   !> normal number (ln_normal_block; the same bits as nh_wave_speed2).
   pure subroutine nh_wave_speed2_block(n, lambda, mu, rho0, jac, c2)
      integer, intent(in) :: n           !< number of points
      real(wp), intent(in) :: lambda, mu !< Lame constants
      real(wp), intent(in) :: rho0       !< reference density
      real(wp), intent(in) :: jac(n)     !< volume ratios J >= tiny(1.0)
      real(wp), intent(out) :: c2(n)
      real(wp) :: lnj(CHUNK)
      integer :: q0, m, i
      do q0 = 1, n, CHUNK
         m = min(CHUNK, n - q0 + 1)
         call ln_normal_block(m, jac(q0:q0 + m - 1), lnj)
         do i = 1, m
            c2(q0 + i - 1) = max(lambda + 2.0_wp*mu - 2.0_wp*lambda*lnj(i), mu)/rho0
         end do
      end do
   end subroutine nh_wave_speed2_block

end module exic_material_neohookean
