!> Quantities of the 4-node quadrilateral's reference mesh, computed once at set-up: the check
!> that every element has det J0 > 0 and the row-sum lumped mass (plane and axisymmetric). The
!> force kernels (quad4.f90, which makes both available with its own procedures) recompute
!> the reference gradients in every pass instead of storing them.
!>
!> Local node a has natural coordinates (xi_a, eta_a) = (-1,-1), (1,-1), (1,1), (-1,1); the 2x2
!> Gauss points are at +-1/sqrt(3) in the same order.
module exic_element_q4_reference
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: q4_check_reference, q4_lumped_mass

   real(wp), parameter :: xin(4) = [-1.0_wp, 1.0_wp, 1.0_wp, -1.0_wp]   !< xi_a
   real(wp), parameter :: etn(4) = [-1.0_wp, -1.0_wp, 1.0_wp, 1.0_wp]   !< eta_a
   !> 1/sqrt(3), the coordinate of the 2x2 Gauss points
   real(wp), parameter, public :: gq = 0.57735026918962576451_wp

contains

   !> First element with det J0 <= 0 at a corner of the reference mesh (det J0 is a linear
   !> function of xi and eta on each edge, so its corner values bound it everywhere, Gauss
   !> points included) or a non-positive area; 0 if none.
   pure subroutine q4_check_reference(nel, nnode, conn, x0, ebad)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode)
      integer, intent(out) :: ebad
      real(wp) :: xe(4), ye(4), dnx(4), dny(4), dj, a0
      integer :: e, a

      ebad = 0
      do e = 1, nel
         xe = x0(1, conn(:, e))
         ye = x0(2, conn(:, e))
         a0 = 0.5_wp*((xe(3) - xe(1))*(ye(4) - ye(2)) - (ye(3) - ye(1))*(xe(4) - xe(2)))
         if (.not. a0 > 0.0_wp) then
            ebad = e
            return
         end if
         do a = 1, 4
            call grad_at(xe, ye, xin(a), etn(a), dnx, dny, dj)
            if (dj <= 0.0_wp) then
               ebad = e
               return
            end if
         end do
      end do
   end subroutine q4_check_reference

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

   !> Row-sum lumped mass m_a = rho integral N_a dA0 (2x2 Gauss, exact for the bilinear
   !> element), accumulated into mass(nnode). The element masses sum to rho A0 exactly.
   !> axi (GLOBal AXISymmetric): m_a = rho integral N_a R dA0, the ring mass per radian
   !> (doc/axisymmetry.md, (A5); 2x2 Gauss is exact for it too).
   pure subroutine q4_lumped_mass(nel, nnode, conn, x0, rho, mass, axi)
      integer, intent(in) :: nel, nnode
      integer, intent(in) :: conn(4, nel)
      real(wp), intent(in) :: x0(2, nnode)
      real(wp), intent(in) :: rho
      real(wp), intent(inout) :: mass(nnode)
      logical, intent(in), optional :: axi
      real(wp) :: xe(4), ye(4), dnx(4), dny(4), dj, xi, eta, me(4), rg
      integer :: e, g
      logical :: ax

      ax = .false.
      if (present(axi)) ax = axi
      do e = 1, nel
         xe = x0(1, conn(:, e))
         ye = x0(2, conn(:, e))
         me = 0.0_wp
         do g = 1, 4
            xi = gq*xin(g)
            eta = gq*etn(g)
            call grad_at(xe, ye, xi, eta, dnx, dny, dj)
            if (ax) then
               rg = 0.25_wp*sum((1.0_wp + xin*xi)*(1.0_wp + etn*eta)*xe)
               me = me + (rho*dj*0.25_wp*rg)*(1.0_wp + xin*xi)*(1.0_wp + etn*eta)
            else
               me = me + (rho*dj*0.25_wp)*(1.0_wp + xin*xi)*(1.0_wp + etn*eta)
            end if
         end do
         mass(conn(:, e)) = mass(conn(:, e)) + me
      end do
   end subroutine q4_lumped_mass

end module exic_element_q4_reference
