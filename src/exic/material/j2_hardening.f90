!> Parameters of the finite-strain J2 material and its hardening laws (doc/plasticity.md,
!> sections 4 and 7): FEAP's saturation law with linear isotropic hardening (`PLAStic MISEs
!> Y0 Yinf beta`, `PLAStic HARDening Hiso Hkin`), the power law (`PLAStic POWEr A B n`) and
!> Johnson-Cook (`PLAStic JOHNson-cook A B n C m Tmelt Troom epsdot0`), with adiabatic heating
!> from the specific heat (`SPECific heat c`).
!>
!>     MISEs     Y = Y0 + (Yinf - Y0)(1 - exp(-beta ep)) + Hiso ep                   (J14)
!>     POWEr     Y = A + B ep^n                                                       (J15)
!>     JOHNson   Y = (A + B ep^n)(1 + C ln max(epdot/epsdot0, 1))(1 - T*^m)           (J16)
!>               T* = (T - Troom)/(Tmelt - Troom) clipped to [0, 1]   (Johnson & Cook 1983, eq. 1)
!>
!> The yield stress of a step is evaluated with the plastic strain at its end, the rate
!> dep/dt of the step and the temperature at its start (doc/plasticity.md, section 4.1).
module exic_material_j2_hardening
   use exic_base_kinds, only: wp
   use exic_base_strings, only: rtoa
   implicit none
   private

   public :: j2_param_t, j2_flow_stress, j2_static_yield, j2_has_temperature, j2_check_parameters
   public :: j2_is_linear, j2_strain_part, j2_rate_factor, j2_thermal_factor

   !> Hardening laws.
   integer, parameter, public :: J2_NONE = 0, J2_MISES = 1, J2_POWER = 2, J2_JOHNSON_COOK = 3

   !> Parameters of one plastic material set. The elastic constants (lambda, mu) stay in
   !> `material_t` and are passed to the kernels separately, as to the neo-Hookean kernel.
   type :: j2_param_t
      integer :: law = J2_NONE
      real(wp) :: y0 = 0.0_wp, yinf = 0.0_wp, beta = 0.0_wp   !< MISEs Y0 Yinf beta
      real(wp) :: hiso = 0.0_wp, hkin = 0.0_wp                !< HARDening Hiso Hkin
      real(wp) :: a = 0.0_wp, b = 0.0_wp, en = 1.0_wp          !< POWEr / JOHNson: A + B ep^n
      real(wp) :: crate = 0.0_wp, m = 1.0_wp                  !< JOHNson: C, m
      real(wp) :: tmelt = 1.0_wp, troom = 0.0_wp              !< JOHNson: Tmelt, Troom
      real(wp) :: epsdot0 = 1.0_wp                            !< JOHNson: reference rate
      real(wp) :: rho = 0.0_wp                                !< reference density
      real(wp) :: cheat = 0.0_wp                              !< specific heat c (0: no heating)
      real(wp) :: chi = 0.9_wp                                !< Taylor-Quinney fraction (J17)
   end type j2_param_t

contains

   !> True when the law is linear in ep and rate-independent, Y = Y0 + Hiso ep (MISEs with
   !> beta = 0 or Yinf = Y0): the return is then the closed form (J22).
   pure logical function j2_is_linear(prm)
      type(j2_param_t), intent(in) :: prm
      j2_is_linear = prm%law == J2_MISES .and. (prm%beta == 0.0_wp .or. prm%yinf == prm%y0)
   end function j2_is_linear

   !> True when the history carries a temperature: Johnson-Cook (which reads it) or heating on
   !> (c > 0, which writes it).
   pure logical function j2_has_temperature(prm)
      type(j2_param_t), intent(in) :: prm
      j2_has_temperature = prm%law == J2_JOHNSON_COOK .or. prm%cheat > 0.0_wp
   end function j2_has_temperature

   !> Thermal softening factor 1 - T*^m of Johnson-Cook (1 for the other laws), with T* clipped
   !> to [0, 1] (J16).
   elemental real(wp) function j2_thermal_factor(prm, temp) result(th)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: temp   !< temperature
      real(wp) :: ts
      th = 1.0_wp
      if (prm%law /= J2_JOHNSON_COOK) return
      ts = min(max((temp - prm%troom)/(prm%tmelt - prm%troom), 0.0_wp), 1.0_wp)
      if (ts > 0.0_wp) th = 1.0_wp - ts**prm%m
   end function j2_thermal_factor

   !> Rate-independent part Ys(ep) of the law and its slope dYs/dep (J14)-(J16). At ep = 0 the
   !> power laws return the slope 0 (infinite for n < 1; the return never uses it there).
   pure subroutine j2_strain_part(prm, ep, ys, dys)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep           !< equivalent plastic strain
      real(wp), intent(out) :: ys, dys     !< Ys(ep) and dYs/dep
      real(wp) :: e
      select case (prm%law)
      case (J2_MISES)
         if (prm%beta == 0.0_wp .or. ep == 0.0_wp) then
            ys = prm%y0 + prm%hiso*ep
            dys = prm%beta*(prm%yinf - prm%y0) + prm%hiso
         else
            e = exp(-prm%beta*ep)
            ys = prm%y0 + (prm%yinf - prm%y0)*(1.0_wp - e) + prm%hiso*ep
            dys = prm%beta*(prm%yinf - prm%y0)*e + prm%hiso
         end if
      case (J2_POWER, J2_JOHNSON_COOK)
         if (ep > 0.0_wp) then
            e = ep**prm%en
            ys = prm%a + prm%b*e
            dys = prm%en*prm%b*e/ep
         else
            ys = prm%a
            dys = 0.0_wp
         end if
      case default
         ys = huge(1.0_wp)
         dys = 0.0_wp
      end select
   end subroutine j2_strain_part

   !> Johnson-Cook rate factor r = 1 + C ln max(dep/(dt epsdot0), 1) of a step and dr/d(dep);
   !> r = 1 for the other laws and for dt <= 0 (a quasi-static evaluation) (J16).
   pure subroutine j2_rate_factor(prm, dep, dt, r, dr)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: dep, dt   !< increment of ep and step
      real(wp), intent(out) :: r, dr
      r = 1.0_wp
      dr = 0.0_wp
      if (prm%law /= J2_JOHNSON_COOK .or. .not. (dt > 0.0_wp .and. prm%crate > 0.0_wp)) return
      if (dep > dt*prm%epsdot0) then
         r = 1.0_wp + prm%crate*log(dep/(dt*prm%epsdot0))
         dr = prm%crate/dep
      end if
   end subroutine j2_rate_factor

   !> Static yield stress Y(ep, rate factor 1, T): the trial check of a step (J19) and the
   !> yield stress of the output fields.
   elemental real(wp) function j2_static_yield(prm, ep, temp) result(y)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep    !< equivalent plastic strain
      real(wp), intent(in) :: temp  !< temperature (used by Johnson-Cook only)
      real(wp) :: dys
      call j2_strain_part(prm, ep, y, dys)
      if (prm%law == J2_JOHNSON_COOK) y = y*j2_thermal_factor(prm, temp)
   end function j2_static_yield

   !> Flow stress of a step and its slope with respect to the increment:
   !> y = Y(ep0 + dep, dep/dt, temp), dydep = dY/d(dep) at fixed ep0 (J14)-(J16).
   !> The rate factor is 1 for dep <= dt epsdot0 and for dt <= 0 (quasi-static evaluation).
   pure subroutine j2_flow_stress(prm, ep0, dep, dt, temp, y, dydep)
      type(j2_param_t), intent(in) :: prm
      real(wp), intent(in) :: ep0    !< plastic strain at the start of the step
      real(wp), intent(in) :: dep    !< increment dep >= 0
      real(wp), intent(in) :: dt     !< step (Johnson-Cook rate)
      real(wp), intent(in) :: temp   !< temperature at the start of the step
      real(wp), intent(out) :: y, dydep
      real(wp) :: ys, dys, r, dr, th
      call j2_strain_part(prm, ep0 + dep, ys, dys)
      call j2_rate_factor(prm, dep, dt, r, dr)
      th = j2_thermal_factor(prm, temp)
      y = ys*r*th
      dydep = (dys*r + ys*dr)*th
   end subroutine j2_flow_stress

   !> Check the parameters for the deck reader (doc/plasticity.md, section 7): msg is '' when
   !> they are usable, else the first problem as a sentence (the reader adds file:line). Every
   !> condition is written as "not (valid)" so that NaN is refused too.
   pure subroutine j2_check_parameters(prm, msg)
      type(j2_param_t), intent(in) :: prm
      character(len=:), allocatable, intent(out) :: msg
      msg = ''
      select case (prm%law)
      case (J2_MISES)
         call check_mises(prm, msg)
      case (J2_POWER)
         call check_power(prm, 'PLAStic POWEr', msg)
      case (J2_JOHNSON_COOK)
         call check_power(prm, 'PLAStic JOHNson-cook', msg)
         if (len(msg) == 0) call check_jc(prm, msg)
      case default
         msg = 'a PLAStic law is needed: MISEs Y0 Yinf beta, POWEr A B n or JOHNson-cook '// &
               'A B n C m Tmelt Troom epsdot0'
      end select
      if (len(msg) > 0) return
      if (.not. (prm%hkin == 0.0_wp)) then
         msg = 'kinematic hardening (PLAStic HARDening Hiso Hkin with Hkin = '//num(prm%hkin)// &
               ') is not implemented: give Hkin = 0'
      else if (prm%law /= J2_MISES .and. .not. (prm%hiso == 0.0_wp)) then
         msg = 'PLAStic HARDening belongs to PLAStic MISEs: the POWEr and JOHNson-cook laws '// &
               'carry their own hardening (got Hiso = '//num(prm%hiso)//')'
      else if (.not. (prm%cheat >= 0.0_wp)) then
         msg = 'SPECific heat must be >= 0 (got '//num(prm%cheat)//')'
      else if (prm%cheat > 0.0_wp .and. .not. (prm%rho > 0.0_wp)) then
         msg = 'adiabatic heating (SPECific heat) needs a positive DENSity (got '// &
               num(prm%rho)//')'
      else if (.not. (prm%chi >= 0.0_wp .and. prm%chi <= 1.0_wp)) then
         msg = 'the Taylor-Quinney fraction must lie in [0, 1] (got '//num(prm%chi)//')'
      end if
   end subroutine j2_check_parameters

   !> Checks of PLAStic MISEs and HARDening.
   pure subroutine check_mises(prm, msg)
      type(j2_param_t), intent(in) :: prm
      character(len=:), allocatable, intent(inout) :: msg
      if (.not. (prm%y0 > 0.0_wp .and. prm%y0 < huge(1.0_wp))) then
         msg = 'PLAStic MISEs: the initial yield stress Y0 must be positive and finite (got '// &
               num(prm%y0)//')'
      else if (.not. (prm%beta >= 0.0_wp .and. prm%beta < huge(1.0_wp))) then
         msg = 'PLAStic MISEs: the saturation rate beta must be >= 0 (got '//num(prm%beta)//')'
      else if (prm%beta > 0.0_wp .and. .not. (prm%yinf >= prm%y0 .and. prm%yinf < huge(1.0_wp))) then
         msg = 'PLAStic MISEs: the saturation stress Yinf = '//num(prm%yinf)// &
               ' is below the initial yield stress Y0 = '//num(prm%y0)//' with beta = '// &
               num(prm%beta)//' > 0, so the yield stress would soften from Y0 to Yinf: give '// &
               'Yinf >= Y0 (the two may be swapped), or beta = 0 for linear hardening'
      else if (.not. (prm%hiso >= 0.0_wp .and. prm%hiso < huge(1.0_wp))) then
         msg = 'PLAStic HARDening: the isotropic modulus Hiso must be >= 0 (got '// &
               num(prm%hiso)//'); softening is not supported'
      end if
   end subroutine check_mises

   !> Checks of the strain part A + B ep^n (POWEr and JOHNson-cook).
   pure subroutine check_power(prm, rec, msg)
      type(j2_param_t), intent(in) :: prm
      character(len=*), intent(in) :: rec
      character(len=:), allocatable, intent(inout) :: msg
      if (.not. (prm%a > 0.0_wp .and. prm%a < huge(1.0_wp))) then
         msg = rec//': the initial yield stress A must be positive and finite (got '//num(prm%a)//')'
      else if (.not. (prm%b >= 0.0_wp .and. prm%b < huge(1.0_wp))) then
         msg = rec//': the hardening coefficient B must be >= 0 (got '//num(prm%b)//')'
      else if (.not. (prm%en > 0.0_wp .and. prm%en < huge(1.0_wp))) then
         msg = rec//': the hardening exponent n must be positive (got '//num(prm%en)// &
               '); with n <= 0, ep^n is infinite at ep = 0'
      end if
   end subroutine check_power

   !> Checks of the rate and thermal parts of JOHNson-cook.
   pure subroutine check_jc(prm, msg)
      type(j2_param_t), intent(in) :: prm
      character(len=:), allocatable, intent(inout) :: msg
      character(len=*), parameter :: rec = 'PLAStic JOHNson-cook: '
      if (.not. (prm%crate >= 0.0_wp .and. prm%crate < huge(1.0_wp))) then
         msg = rec//'the rate coefficient C must be >= 0 (got '//num(prm%crate)//')'
      else if (.not. (prm%m > 0.0_wp .and. prm%m < huge(1.0_wp))) then
         msg = rec//'the thermal exponent m must be positive (got '//num(prm%m)//')'
      else if (.not. (prm%tmelt > prm%troom .and. abs(prm%troom) < huge(1.0_wp) &
                      .and. prm%tmelt < huge(1.0_wp))) then
         msg = rec//'the melting temperature Tmelt = '//num(prm%tmelt)// &
               ' must be above the room temperature Troom = '//num(prm%troom)
      else if (.not. (prm%epsdot0 > 0.0_wp .and. prm%epsdot0 < huge(1.0_wp))) then
         msg = rec//'the reference strain rate epsdot0 must be positive (got '// &
               num(prm%epsdot0)//')'
      end if
   end subroutine check_jc

   !> A number for a message.
   pure function num(x) result(s)
      real(wp), intent(in) :: x
      character(len=:), allocatable :: s
      s = rtoa(x)
   end function num

end module exic_material_j2_hardening
