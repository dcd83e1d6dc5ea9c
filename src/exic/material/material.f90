!> Material sets: the compressible neo-Hookean solid of the seed's eq. 7.2 (elastic, or with
!> finite-strain J2 plasticity on it: doc/plasticity.md), or a rigid body (fixed or driven with
!> infinite mass, or free with the mass and inertia of its elements).
module exic_material_material
   use exic_base_kinds, only: wp
   use exic_material_j2_hardening, only: j2_param_t
   implicit none
   private

   integer, parameter, public :: MAT_UNDEFINED = 0, MAT_SOLID = 1, MAT_RIGID = 2
   !> Hourglass control of one-point elements (doc/hourglass.md): `HOURglass h`, the
   !> Flanagan-Belytschko stiffness form with coefficient h; `HOURglass,PHYSical[,s]`, the
   !> assumed-strain (ASQBI) stabilization in the element's turning frame, scaled by s.
   integer, parameter, public :: HOURGLASS_STIFFNESS = 1, HOURGLASS_PHYSICAL = 2

   public :: material_t, lame_from_young

   !> One MATErial set.
   type :: material_t
      integer :: kind = MAT_UNDEFINED
      real(wp) :: young = 0.0_wp, poisson = 0.0_wp   !< E, nu as given
      real(wp) :: lambda = 0.0_wp, mu = 0.0_wp       !< Lame constants from E, nu
      real(wp) :: rho = 0.0_wp                       !< reference density
      integer :: quadrature = 2                      !< 2: 2x2 Gauss; 1: one point + hourglass control
      real(wp) :: hourglass = 0.1_wp                 !< hourglass coefficient (or scale) for quadrature 1
      integer :: hourglass_kind = HOURGLASS_STIFFNESS !< HOURGLASS_STIFFNESS or HOURGLASS_PHYSICAL
      real(wp) :: body(2) = 0.0_wp                   !< BODY bx by: force per unit reference volume
      logical :: free = .false.                      !< RIGId,FREE: a free rigid body (3 dofs)
      logical :: plastic = .false.                   !< PLAStic: J2 plasticity (material/j2.f90)
      type(j2_param_t) :: j2                         !< its parameters (PLAStic, SPECific heat)
      logical :: mixed = .false.                     !< MIXEd: mean dilatation (2x2 element)
      character(len=:), allocatable :: where         !< file:line of the MATErial record
      !> DAMPing MASS c [t_end]: mass-proportional damping c (1/time) until t_end (doc/damping.md)
      real(wp) :: damping = 0.0_wp, damping_end = huge(1.0_wp)
      !> VISCosity BULK [q1 q2]: the bulk viscosity's coefficients (doc/damping.md, section 3)
      logical :: bulk = .false.
      real(wp) :: bulk_q1 = 1.5_wp, bulk_q2 = 0.06_wp
   end type material_t

contains

   !> Lame constants from Young's modulus and Poisson's ratio.
   pure subroutine lame_from_young(e, nu, lambda, mu)
      real(wp), intent(in) :: e, nu
      real(wp), intent(out) :: lambda, mu
      lambda = e*nu/((1.0_wp + nu)*(1.0_wp - 2.0_wp*nu))
      mu = e/(2.0_wp*(1.0_wp + nu))
   end subroutine lame_from_young

end module exic_material_material
