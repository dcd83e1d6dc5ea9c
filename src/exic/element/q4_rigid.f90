!> Mass properties of a set of 4-node quadrilaterals for rigid bodies (doc/loads.md, section 4):
!> mass, first moment and polar second moment about a given point, by 2x2 Gauss quadrature.
!>
!> With the bilinear map x(xi, eta) the integrands rho det J, rho x det J and rho |x - xc|^2
!> det J are polynomials of degree at most 3 in each natural coordinate, which the 2x2 rule
!> integrates exactly: the moments are exact for any convex quadrilateral.
module exic_element_q4_rigid
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: q4_mass_moments

   real(wp), parameter :: xin(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]   !< xi_a
   real(wp), parameter :: etn(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]   !< eta_a
   real(wp), parameter :: gq = 0.57735026918962576451_wp                 !< 1/sqrt(3)

contains

   !> Add the mass, first moment about xc and polar second moment about xc of the `nel`
   !> elements conn(4, nel) (reference coordinates x(2, nnode), density rho) to m, s(2), j:
   !>     m += int rho dV,   s += int rho (x - xc) dV,   j += int rho |x - xc|^2 dV.
   pure subroutine q4_mass_moments(nel, nnode, conn, x, rho, xc, m, s, j)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x(2, nnode)
      real(wp), intent(in) :: rho, xc(2)
      real(wp), intent(inout) :: m, s(2), j
      real(wp) :: xe(4), ye(4), xi, eta, n(4), dxi(4), deta(4), dj, px, py, w
      integer :: e, g

      do e = 1, nel
         xe = x(1, conn(:, e)) - xc(1)
         ye = x(2, conn(:, e)) - xc(2)
         do g = 1, 4
            xi = gq*xin(g)
            eta = gq*etn(g)
            n = 0.25_wp*(1.0_wp + xin*xi)*(1.0_wp + etn*eta)
            dxi = 0.25_wp*xin*(1.0_wp + etn*eta)
            deta = 0.25_wp*etn*(1.0_wp + xin*xi)
            dj = sum(dxi*xe)*sum(deta*ye) - sum(dxi*ye)*sum(deta*xe)
            px = sum(n*xe)
            py = sum(n*ye)
            w = rho*dj
            m = m + w
            s(1) = s(1) + w*px
            s(2) = s(2) + w*py
            j = j + w*(px*px + py*py)
         end do
      end do
   end subroutine q4_mass_moments

end module exic_element_q4_rigid
