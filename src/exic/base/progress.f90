!> A console progress line that does not flood a log: percent of tmax, steps per second, ETA.
module exic_base_progress
   use exic_base_kinds, only: wp, i8
   use exic_base_clock, only: wall_time
   use, intrinsic :: iso_fortran_env, only: output_unit
   implicit none
   private

   public :: progress_t

   !> Prints at most one line every `interval` seconds of wall time.
   type :: progress_t
      real(wp) :: start = 0.0_wp
      real(wp) :: last = 0.0_wp
      real(wp) :: interval = 5.0_wp
      integer(i8) :: last_step = 0
      logical :: quiet = .false.
   contains
      procedure :: begin => progress_begin
      procedure :: update => progress_update
   end type progress_t

contains

   !> Start timing.
   subroutine progress_begin(self, quiet)
      class(progress_t), intent(inout) :: self
      logical, intent(in) :: quiet
      self%start = wall_time()
      self%last = self%start
      self%last_step = 0
      self%quiet = quiet
   end subroutine progress_begin

   !> Called every step; prints when `interval` has passed since the last line.
   subroutine progress_update(self, t, tmax, step)
      class(progress_t), intent(inout) :: self
      real(wp), intent(in) :: t, tmax
      integer(i8), intent(in) :: step
      real(wp) :: now, rate, frac, eta
      character(len=16) :: eta_text

      if (self%quiet) return
      if (mod(step, 64_i8) /= 0) return
      now = wall_time()
      if (now - self%last < self%interval) return
      rate = real(step - self%last_step, wp)/max(now - self%last, 1.0e-9_wp)
      frac = 0.0_wp
      if (tmax > 0.0_wp) frac = min(t/tmax, 1.0_wp)
      eta = -1.0_wp
      if (frac > 0.0_wp) eta = (now - self%start)*(1.0_wp - frac)/frac
      if (eta >= 0.0_wp) then
         write (eta_text, '(i0,a,i2.2,a,i2.2)') int(eta/3600.0_wp), ':', mod(int(eta/60.0_wp), 60), ':', mod(int(eta), 60)
      else
         eta_text = '?'
      end if
      write (output_unit, '(a,es11.4,a,f6.2,a,i0,a,es10.3,a,a)') '  t =', t, '  ', 100.0_wp*frac, &
         ' %  step ', step, '  steps/s', rate, '  ETA ', trim(eta_text)
      flush (output_unit)
      self%last = now
      self%last_step = step
   end subroutine progress_update

end module exic_base_progress
