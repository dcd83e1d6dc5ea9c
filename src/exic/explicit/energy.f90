!> The energy record of a run: every energy the step books, their names (the columns of
!> <stem>.ene and the energies of the field file), the physical energy the energy guard measures
!> and the balance of <stem>.ene (doc/decisions.md, "Energy balance", eq. E.3).
!>
!> One place writes each sum, always in the same order (the bits of the balance depend on it):
!>
!>     physical = kinetic + strain + hourglass + plastic + damping + bulk
!>     total    = kinetic + c + strain + hourglass + plastic + damping + bulk - wext - wcon - wpm
!>
!> with c the change since t = 0 of the kinetic correction (explicit/assembly.f90,
!> kinetic_correction). The dissipations (plastic work, mass damping, bulk viscosity) are energy
!> that left the mechanical system, booked so that the total stays at its initial value.
!> The frictional dissipation is part of the contact work wcon; the guard adds it apart.
module exic_explicit_energy
   use exic_base_kinds, only: wp
   use exic_material_material, only: material_t, MAT_SOLID
   implicit none
   private

   public :: energy_t, ENERGY_NAMES, NENERGY, E_KINETIC, E_STRAIN, E_WEXT, E_WCON, E_HOURGLASS, E_WPM, &
             E_FRICTION, E_PLASTIC, E_DAMPING, E_BULK, DEFAULT_ENERGIES, &
             model_energies

   !> The energies in the order of their columns (energy_t%values): kinetic, strain (with the
   !> hourglass energy), external work, contact work, hourglass, work of the prescribed motion,
   !> frictional dissipation, plastic work, mass-damping dissipation, bulk-viscosity dissipation.
   integer, parameter :: NENERGY = 10
   integer, parameter :: E_KINETIC = 1, E_STRAIN = 2, E_WEXT = 3, E_WCON = 4, E_HOURGLASS = 5, E_WPM = 6, &
                         E_FRICTION = 7, E_PLASTIC = 8, E_DAMPING = 9, E_BULK = 10
   !> The energies every <stem>.ene has (the others only when the model has them).
   logical, parameter :: DEFAULT_ENERGIES(NENERGY) = [.true., .true., .true., .true., .true., .true., .true., &
                                                      .true., .false., .false.]
   !> Their names: the column names of <stem>.ene and the energy names of the field file.
   character(len=20), parameter :: ENERGY_NAMES(NENERGY) = [character(len=20) :: 'kinetic', 'strain', &
      'external_work', 'contact_work', 'hourglass', 'prescribed_work', 'friction_dissipation', 'plastic_work', &
      'damping_dissipation', 'bulk_viscosity']

   !> The energies of a state at t(n+1) and the work done since t = 0.
   type :: energy_t
      real(wp) :: kinetic = 0.0_wp     !< sum 1/2 m v^2 (rigid and free bodies included)
      real(wp) :: strain = 0.0_wp      !< elastic strain energy (without the hourglass part)
      real(wp) :: hourglass = 0.0_wp   !< hourglass control energy
      real(wp) :: plastic = 0.0_wp     !< plastic work dissipated (doc/axisymmetry.md, (A13))
      real(wp) :: damping = 0.0_wp     !< dissipated by mass damping (doc/damping.md)
      real(wp) :: bulk = 0.0_wp        !< dissipated by the bulk viscosity (doc/damping.md)
      real(wp) :: wext = 0.0_wp        !< work of the external forces
      real(wp) :: wcon = 0.0_wp        !< work of the contact forces (friction included)
      real(wp) :: wpm = 0.0_wp         !< work of the prescribed motion (doc/loads.md, section 3)
      real(wp) :: friction = 0.0_wp    !< frictional dissipation (part of wcon; doc/friction.md, 5)
      real(wp) :: total0 = 0.0_wp      !< the total at t = 0
   contains
      procedure :: physical => energy_physical
      procedure :: total => energy_total
      procedure :: balance => energy_balance
      procedure :: values => energy_values
   end type energy_t

contains

   !> The energies a model's <stem>.ene has: DEFAULT_ENERGIES, and the damping and bulk
   !> viscosity dissipations when a SOLId material has DAMPing MASS or VISCosity BULK.
   pure function model_energies(materials) result(with)
      type(material_t), intent(in) :: materials(:)
      logical :: with(NENERGY)
      integer :: k
      with = DEFAULT_ENERGIES
      do k = 1, size(materials)
         if (materials(k)%kind /= MAT_SOLID) cycle
         if (materials(k)%damping > 0.0_wp) with(E_DAMPING) = .true.
         if (materials(k)%bulk) with(E_BULK) = .true.
      end do
   end function model_energies

   !> The physical energy: kinetic + strain + hourglass + plastic work + the damping and bulk
   !> viscosity dissipations (what the energy guard compares with the energy put in).
   pure real(wp) function energy_physical(self) result(e)
      class(energy_t), intent(in) :: self
      e = self%kinetic + self%strain + self%hourglass + self%plastic + self%damping + self%bulk
   end function energy_physical

   !> The total of the balance with c, the change of the kinetic correction since t = 0
   !> (doc/decisions.md, eq. E.3): constant in exact arithmetic.
   pure real(wp) function energy_total(self, c) result(total)
      class(energy_t), intent(in) :: self
      real(wp), intent(in) :: c
      total = self%kinetic + c + self%strain + self%hourglass + self%plastic + self%damping + self%bulk - &
              self%wext - self%wcon - self%wpm
   end function energy_total

   !> The balance of <stem>.ene: total (energy_total) and its drift from the initial total,
   !> relative to the largest of |initial total| and the physical energy now.
   pure subroutine energy_balance(self, c, total, drift)
      class(energy_t), intent(in) :: self
      real(wp), intent(in) :: c
      real(wp), intent(out) :: total, drift
      real(wp) :: denom
      total = self%total(c)
      denom = max(abs(self%total0), self%physical(), tiny(1.0_wp))
      drift = (total - self%total0)/denom
   end subroutine energy_balance

   !> The energies in the order of ENERGY_NAMES (strain: elastic + hourglass, as in <stem>.ene).
   pure function energy_values(self) result(v)
      class(energy_t), intent(in) :: self
      real(wp) :: v(NENERGY)
      v = [self%kinetic, self%strain + self%hourglass, self%wext, self%wcon, self%hourglass, self%wpm, &
           self%friction, self%plastic, self%damping, self%bulk]
   end function energy_values

end module exic_explicit_energy
