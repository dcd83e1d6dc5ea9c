!> Literals that several layers must agree on.
module exic_base_constants
   use exic_base_kinds, only: wp
   implicit none
   private

   !> Courant factor of `DT,CFL` when the deck gives none, and of a deck without DT: the step is
   !> DEFAULT_CFL x the stable estimate (doc/decisions.md, "Stable step").
   real(wp), parameter, public :: DEFAULT_CFL = 0.9_wp

   !> Relative tolerance of comparisons between simulated times (end of a TIME interval, due
   !> output times, landing on tmax): times within TIME_TOL x t of each other are equal, so that
   !> the rounding of t = sum of the steps never adds or drops a step or an output.
   real(wp), parameter, public :: TIME_TOL = 1.0e-12_wp

   !> The energy guard (src/exic/explicit/step.f90): the physical energy (kinetic + strain +
   !> hourglass) may exceed the energy put in (initial energy + work of the external forces and
   !> of prescribed motion) by ENERGY_WARN of the energy put in before the run warns, and by
   !> ENERGY_STOP before it stops. A deck sets both with [ext] `CHECk,ENERgy,warn,stop`.
   real(wp), parameter, public :: ENERGY_WARN = 0.01_wp
   real(wp), parameter, public :: ENERGY_STOP = 0.10_wp
   !> The energy put in is measured against at least ENERGY_FLOOR eps M c^2 (M the deformable
   !> mass, c^2 the largest (lambda + 2 mu)/rho0): the strain energy of a body at rest, summed from
   !> terms such as mu/2 (I1 - 3) - mu ln J that cancel, is round-off of order eps mu V, and energy
   !> that appears at that level where nothing was put in is not growth (doc/decisions.md).
   real(wp), parameter, public :: ENERGY_FLOOR = 1000.0_wp

   !> The geometric penetration check (src/exic/contact/inside.f90) warns when a node lies deeper
   !> than PENETRATION_WARN element edges inside another body; [ext] `CHECk,PENEtration,fraction`.
   real(wp), parameter, public :: PENETRATION_WARN = 1.0e-3_wp

end module exic_base_constants
