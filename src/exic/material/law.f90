!> The material law of a solid set: an id and its parameters (`law_t`), and the block entry points
!> the element kernels call, once per block of points: the stress (first Piola-Kirchhoff, times
!> the point weight) with the energy, the wave speed of the stable step, and the Cauchy stress
!> for output. Each entry point holds the one `select case` over the laws (the list of laws
!> lives here and nowhere else); the kernels of a law are plain-array routines in a file of its
!> own (neohookean.f90, j2.f90).
!>
!> Two stress entry points serve the two element paths: `law_piola` for laws without history in
!> plane strain (quad4.f90's kernels), `law_piola_general` for every law with F33 (hoop stretch
!> in axisymmetry) and a history per point (q4_general.f90). A law with history runs the general
!> path (`law_has_history`).
module exic_material_law
   use exic_base_kinds, only: wp
   use exic_material_j2_hardening, only: j2_param_t, j2_has_temperature, J2_MISES
   use exic_material_neohookean, only: nh_piola, nh_cauchy_block, nh_wave_speed2_block
   use exic_material_j2, only: j2_piola, j2_cauchy, j2_init_history
   use exic_material_hypoelastic, only: HYPO_NVAR, hypo_init_history, hypo_piola, hypo_cauchy, &
                                        hypo_wave_speed2
   implicit none
   private

   !> The laws: neo-Hookean (seed eq. 7.2), J2 plasticity on it (doc/plasticity.md), the
   !> hypoelastic law of ELAStic ISOTropic (doc/hypoelastic.md).
   integer, parameter, public :: LAW_NEOHOOKEAN = 1, LAW_J2 = 2, LAW_HYPOELASTIC = 3

   !> Values per point of the largest history (law_piola_general's h(n, NVMAX)).
   integer, parameter, public :: NVMAX = 10

   public :: law_t, law_make, neohookean_law, law_name, law_has_history, law_init_history, law_piola, &
             law_piola_general, law_wave_speed2, law_cauchy, law_cauchy_general

   !> A law and its parameters. lambda and mu are the Lame constants of its small-strain limit,
   !> which the hourglass control and the corner barrier of the one-point element use for every
   !> law; rho the reference density (the wave speed).
   type :: law_t
      integer :: id = LAW_NEOHOOKEAN
      real(wp) :: lambda = 0.0_wp, mu = 0.0_wp, rho = 0.0_wp
      !> history values per point (0: none; law_init_history)
      integer :: nvar = 0
      !> J2's parameters; for the neo-Hookean law on the general path, a yield stress never
      !> reached (j2_piola then gives nh_piola's stress and energy, with F33)
      type(j2_param_t) :: j2
   end type law_t

contains

   !> The law `id` with Lame constants lambda, mu, density rho and, for LAW_J2, the plastic
   !> parameters j2 (required for it).
   pure function law_make(id, lambda, mu, rho, j2) result(o)
      integer, intent(in) :: id
      real(wp), intent(in) :: lambda, mu, rho
      type(j2_param_t), intent(in), optional :: j2
      type(law_t) :: o
      o%id = id
      o%lambda = lambda
      o%mu = mu
      o%rho = rho
      select case (id)
      case (LAW_J2)
         o%j2 = j2
         o%nvar = 5
         if (j2_has_temperature(j2)) o%nvar = 6
      case (LAW_HYPOELASTIC)
         o%nvar = HYPO_NVAR
      case default
         o%j2%law = J2_MISES
         o%j2%y0 = huge(1.0_wp)
         o%j2%yinf = huge(1.0_wp)
      end select
   end function law_make

   !> The neo-Hookean law with Lame constants lambda, mu and density rho.
   pure function neohookean_law(lambda, mu, rho) result(o)
      real(wp), intent(in) :: lambda, mu, rho
      type(law_t) :: o
      o = law_make(LAW_NEOHOOKEAN, lambda, mu, rho)
   end function neohookean_law

   !> The name of the law for the report (J2 plasticity is reported with its own parameters).
   pure function law_name(o) result(name)
      type(law_t), intent(in) :: o
      character(len=:), allocatable :: name
      select case (o%id)
      case (LAW_HYPOELASTIC)
         name = 'hypoelastic (Jaumann rate)'
      case default
         name = 'neo-Hookean'
      end select
   end function law_name

   !> Whether the law keeps a history per point (and so runs the general path).
   pure logical function law_has_history(o)
      type(law_t), intent(in) :: o
      law_has_history = o%nvar > 0
   end function law_has_history

   !> The initial history h(n, NVMAX) of n points (columns 1..nvar set; a law without history:
   !> the virgin state its general-path kernel reads, columns 1..6).
   pure subroutine law_init_history(o, n, h)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(inout) :: h(n, NVMAX)
      select case (o%id)
      case (LAW_HYPOELASTIC)
         call hypo_init_history(n, h(:, 1:HYPO_NVAR))
      case default
         h(:, 6) = 0.0_wp
         call j2_init_history(n, o%j2, h(:, 1), h(:, 2), h(:, 3), h(:, 4), h(:, 5), h(:, 6))
      end select
   end subroutine law_init_history

   !> Plane strain, no history: first Piola stress p.. and energy w at n points, times the weight
   !> wt, for F (in-plane j = det F >= tiny(1.0), checked by the caller).
   pure subroutine law_piola(o, n, f11, f12, f21, f22, jac, wt, p11, p12, p21, p22, w)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n), jac(n), wt(n)
      real(wp), intent(out) :: p11(n), p12(n), p21(n), p22(n), w(n)
      ! a law with history has no stress of F alone; its initial stiffness (face.f90, at F = 1)
      ! is the neo-Hookean one, which has the same small-strain moduli
      select case (o%id)
      case default
         call nh_piola(n, o%lambda, o%mu, f11, f12, f21, f22, jac, wt, p11, p12, p21, p22, w)
      end select
   end subroutine law_piola

   !> The general form: F with F33, the history h(n, NVMAX) of t(n) in and t(n+1) out, dt the
   !> step; p.. (p33: the out-of-plane or hoop component), the energy w and the dissipation dw
   !> of the step times wt, ys the yield stress (0 for an elastic law).
   pure subroutine law_piola_general(o, n, dt, f11, f12, f21, f22, f33, jac, wt, h, p11, p12, &
                                     p21, p22, p33, w, dw, ys)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(in) :: dt
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n), f33(n), jac(n), wt(n)
      real(wp), intent(inout) :: h(n, NVMAX)
      real(wp), intent(out) :: p11(n), p12(n), p21(n), p22(n), p33(n), w(n), dw(n), ys(n)
      select case (o%id)
      case (LAW_HYPOELASTIC)
         call hypo_piola(n, o%lambda, o%mu, f11, f12, f21, f22, f33, jac, wt, h(:, 1:HYPO_NVAR), &
                         p11, p12, p21, p22, p33, w)
         dw = 0.0_wp
         ys = 0.0_wp
      case default
         call j2_piola(n, o%lambda, o%mu, o%j2, dt, f11, f12, f21, f22, f33, jac, wt, h(:, 1), &
                       h(:, 2), h(:, 3), h(:, 4), h(:, 5), h(:, 6), p11, p12, p21, p22, p33, w, &
                       dw, ys)
      end select
   end subroutine law_piola_general

   !> Square of the dilatational wave speed c2 at n points of volume ratio jac >= tiny(1.0)
   !> (the current length of the stable step goes with it). Neo-Hookean and J2:
   !> nh_wave_speed2_block (the plastic tangent is softer than the elastic one); hypoelastic:
   !> doc/hypoelastic.md (H14).
   pure subroutine law_wave_speed2(o, n, jac, c2)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(in) :: jac(n)
      real(wp), intent(out) :: c2(n)
      select case (o%id)
      case (LAW_HYPOELASTIC)
         call hypo_wave_speed2(n, o%lambda, o%mu, o%rho, jac, c2)
      case default
         call nh_wave_speed2_block(n, o%lambda, o%mu, o%rho, jac, c2)
      end select
   end subroutine law_wave_speed2

   !> Plane strain, no history (the neo-Hookean law): the Cauchy stress at n points for output (zero where the
   !> caller's jk <= 0).
   pure subroutine law_cauchy(o, n, f11, f12, f21, f22, jk, sxx, syy, szz, sxy)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n), jk(n)
      real(wp), intent(out) :: sxx(n), syy(n), szz(n), sxy(n)
      select case (o%id)
      case default
         call nh_cauchy_block(n, o%lambda, o%mu, f11, f12, f21, f22, jk, sxx, syy, szz, sxy)
      end select
   end subroutine law_cauchy

   !> The general form of law_cauchy: F with F33 and the history h(n, NVMAX) of the points
   !> (J > 0, checked by the caller); ys the yield stress of a plastic law.
   pure subroutine law_cauchy_general(o, n, f11, f12, f21, f22, f33, h, sxx, syy, szz, sxy, ys)
      type(law_t), intent(in) :: o
      integer, intent(in) :: n
      real(wp), intent(in) :: f11(n), f12(n), f21(n), f22(n), f33(n), h(n, NVMAX)
      real(wp), intent(out) :: sxx(n), syy(n), szz(n), sxy(n), ys(n)
      select case (o%id)
      case (LAW_HYPOELASTIC)
         call hypo_cauchy(n, h(:, 1:HYPO_NVAR), sxx, syy, szz, sxy)
         ys = 0.0_wp
      case default
         call j2_cauchy(n, o%lambda, o%mu, o%j2, f11, f12, f21, f22, f33, h(:, 1), h(:, 2), &
                        h(:, 3), h(:, 4), h(:, 5), h(:, 6), sxx, syy, szz, sxy, ys)
      end select
   end subroutine law_cauchy_general

end module exic_material_law
