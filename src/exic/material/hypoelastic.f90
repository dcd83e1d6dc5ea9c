!> The hypoelastic law of `ELAStic ISOTropic E nu`: Hooke's law in rate form with the Jaumann
!> rate of the Cauchy stress, integrated with Hughes & Winget's incrementally objective update
!> (doc/hypoelastic.md derives every equation tagged (Hk)). Linear isotropic elasticity for small
!> strains, objective under finite rotations (LS-DYNA's elastic material type 1).
!>
!> History per point (HYPO_NVAR = 10 values, in this order): the deformation gradient of the last
!> step F11, F12, F21, F22, F33 (1-5), the Cauchy stress sxx, syy, szz, sxy (6-9) and the energy
!> per reference volume W (10), the integral of the stress power (H13): the trapezoidal rule on
!> P : dF, which is, point by point, the central-difference scheme's internal work
!> (f(n) + f(n+1))/2 . du, so that the energy balance closes as for a hyperelastic law.
!>
!> F has the block form of doc/plasticity.md (J1): F33 = 1 in plane strain, r/R in axisymmetry;
!> the caller passes the in-plane j = F11 F22 - F12 F21 > 0 it has computed and checked.
!> Every loop runs over the points without branches (vectorized).
module exic_material_hypoelastic
   use exic_base_kinds, only: wp
   implicit none
   private

   !> History values per point.
   integer, parameter, public :: HYPO_NVAR = 10

   public :: hypo_init_history, hypo_piola, hypo_cauchy, hypo_wave_speed2

contains

   !> The initial history of n points: F = 1, sigma = 0, W = 0.
   pure subroutine hypo_init_history(n, h)
      integer, intent(in) :: n
      real(wp), intent(out) :: h(n, HYPO_NVAR)
      h = 0.0_wp
      h(:, 1) = 1.0_wp
      h(:, 4) = 1.0_wp
      h(:, 5) = 1.0_wp
   end subroutine hypo_init_history

   !> The update from t(n) (the history h) to t(n+1) (the deformation gradients F, F33), and the
   !> first Piola stress p.. and energy w at t(n+1) times the point weight wt (H3)-(H13).
   pure subroutine hypo_piola(n, lambda, mu, f11, f12, f21, f22, f33, jac, wt, h, p11, p12, p21, &
                              p22, p33, w)
      integer, intent(in) :: n                                !< number of points
      real(wp), intent(in) :: lambda, mu                      !< Lame constants
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n)  !< in-plane F(n+1)
      real(wp), intent(in) :: f33(n)                          !< F33 (1, or hoop r/R)
      real(wp), intent(in) :: jac(n)                          !< j = F11 F22 - F12 F21 > 0
      real(wp), intent(in) :: wt(n)                           !< weight of each point
      real(wp), intent(inout) :: h(n, HYPO_NVAR)              !< history: t(n) in, t(n+1) out
      real(wp), intent(out) :: p11(n), p12(n), p21(n), p22(n), p33(n) !< wt x first Piola stress
      real(wp), intent(out) :: w(n)                           !< wt x energy per reference volume
      real(wp) :: m11, m12, m21, m22, m33, jm, rm, d11, d12, d21, d22, g11, g12, g21, g22, &
                  e11, e22, e33, e12, a, b, c, s, r11, r22, r33, r12, tr, s11, s22, s33, s12, dw, &
                  n11, n12, n21, n22, n33, u11, u12, u21, u22, u33
      integer :: q

      do q = 1, n
         ! (H3) midpoint configuration and the increment of F
         m11 = 0.5_wp*(h(q, 1) + f11(q))
         m12 = 0.5_wp*(h(q, 2) + f12(q))
         m21 = 0.5_wp*(h(q, 3) + f21(q))
         m22 = 0.5_wp*(h(q, 4) + f22(q))
         m33 = 0.5_wp*(h(q, 5) + f33(q))
         d11 = f11(q) - h(q, 1)
         d12 = f12(q) - h(q, 2)
         d21 = f21(q) - h(q, 3)
         d22 = f22(q) - h(q, 4)
         jm = m11*m22 - m12*m21
         rm = 1.0_wp/jm
         ! (H4) G = dF Fm^-1, Fm^-1 = [m22 -m12; -m21 m11]/jm
         g11 = (d11*m22 - d12*m21)*rm
         g12 = (d12*m11 - d11*m12)*rm
         g21 = (d21*m22 - d22*m21)*rm
         g22 = (d22*m11 - d21*m12)*rm
         ! (H5) strain increment, (H6)-(H7) rotation of the step (Cayley transform)
         e11 = g11
         e22 = g22
         e33 = (f33(q) - h(q, 5))/m33
         e12 = 0.5_wp*(g12 + g21)
         a = 0.25_wp*(g12 - g21)
         b = 1.0_wp/(1.0_wp + a*a)
         c = (1.0_wp - a*a)*b
         s = 2.0_wp*a*b
         ! (H8) the stress of t(n) turned; P(n) (H12) for the energy (H13)
         s11 = h(q, 6)
         s22 = h(q, 7)
         s33 = h(q, 8)
         s12 = h(q, 9)
         n11 = h(q, 5)*(s11*h(q, 4) - s12*h(q, 2))
         n12 = h(q, 5)*(s12*h(q, 1) - s11*h(q, 3))
         n21 = h(q, 5)*(s12*h(q, 4) - s22*h(q, 2))
         n22 = h(q, 5)*(s22*h(q, 1) - s12*h(q, 3))
         n33 = (h(q, 1)*h(q, 4) - h(q, 2)*h(q, 3))*s33
         r11 = c*c*s11 + 2.0_wp*c*s*s12 + s*s*s22
         r22 = s*s*s11 - 2.0_wp*c*s*s12 + c*c*s22
         r12 = c*s*(s22 - s11) + (c*c - s*s)*s12
         r33 = s33
         ! (H9) Hooke's law on the increment
         tr = lambda*(e11 + e22 + e33)
         s11 = r11 + tr + 2.0_wp*mu*e11
         s22 = r22 + tr + 2.0_wp*mu*e22
         s33 = r33 + tr + 2.0_wp*mu*e33
         s12 = r12 + 2.0_wp*mu*e12
         ! (H12) P = J sigma F^-T at t(n+1), (H13) the trapezoidal rule on the stress power P : dF
         u11 = f33(q)*(s11*f22(q) - s12*f12(q))
         u12 = f33(q)*(s12*f11(q) - s11*f21(q))
         u21 = f33(q)*(s12*f22(q) - s22*f12(q))
         u22 = f33(q)*(s22*f11(q) - s12*f21(q))
         u33 = jac(q)*s33
         dw = 0.5_wp*((((n11 + u11)*d11 + (n12 + u12)*d12) + ((n21 + u21)*d21 + (n22 + u22)*d22)) &
                      + (n33 + u33)*(f33(q) - h(q, 5)))
         h(q, 10) = h(q, 10) + dw
         h(q, 1) = f11(q)
         h(q, 2) = f12(q)
         h(q, 3) = f21(q)
         h(q, 4) = f22(q)
         h(q, 5) = f33(q)
         h(q, 6) = s11
         h(q, 7) = s22
         h(q, 8) = s33
         h(q, 9) = s12
         p11(q) = wt(q)*u11
         p12(q) = wt(q)*u12
         p21(q) = wt(q)*u21
         p22(q) = wt(q)*u22
         p33(q) = wt(q)*u33
         w(q) = wt(q)*h(q, 10)
      end do
   end subroutine hypo_piola

   !> The Cauchy stress of n points from their history (output after the force pass).
   pure subroutine hypo_cauchy(n, h, sxx, syy, szz, sxy)
      integer, intent(in) :: n
      real(wp), intent(in) :: h(n, HYPO_NVAR)
      real(wp), intent(out) :: sxx(n), syy(n), szz(n), sxy(n)
      sxx = h(:, 6)
      syy = h(:, 7)
      szz = h(:, 8)
      sxy = h(:, 9)
   end subroutine hypo_cauchy

   !> Square of the dilatational wave speed at volume ratio jac (H14): (lambda + 2 mu) J/rho0.
   pure subroutine hypo_wave_speed2(n, lambda, mu, rho0, jac, c2)
      integer, intent(in) :: n
      real(wp), intent(in) :: lambda, mu, rho0
      real(wp), intent(in) :: jac(n)
      real(wp), intent(out) :: c2(n)
      integer :: q
      do q = 1, n
         c2(q) = (lambda + 2.0_wp*mu)*jac(q)/rho0
      end do
   end subroutine hypo_wave_speed2

end module exic_material_hypoelastic
