!> The console progress line: percentage of the end time, simulated time, step, steps per second,
!> wall time, ETA and energy drift.
!>
!> On a terminal the line is rewritten in place (carriage return) at most every `tty_interval`
!> seconds of wall time; when standard output is a file or a pipe a new line is printed at most
!> every `log_interval` seconds. The first step and the end (`finish`) are always shown. The
!> caller asks `due` every step (one clock reading) and builds the figures only when it is.
module exic_base_progress
   use, intrinsic :: iso_fortran_env, only: output_unit
   use exic_base_kinds, only: wp, i8
   use exic_base_clock, only: wall_time
   use exic_base_terminal, only: stdout_is_terminal
   implicit none
   private

   public :: progress_t, clock_text, eta_seconds, eta_known

   character(len=*), parameter :: CR = achar(13)

   !> One run's progress line.
   type :: progress_t
      real(wp) :: start = 0.0_wp                 !< wall time of `begin`
      real(wp) :: t_begin = 0.0_wp               !< simulated time at `begin` (a restart point)
      real(wp) :: last = 0.0_wp                  !< wall time of the last line
      real(wp) :: tty_interval = 0.25_wp         !< seconds between updates on a terminal
      real(wp) :: log_interval = 5.0_wp          !< seconds between lines in a log
      integer(i8) :: last_step = 0               !< step of the last line
      logical :: quiet = .true.                  !< silent until `begin` (whose wall time is the origin)
      logical :: tty = .false.                   !< standard output is a terminal
      logical :: shown = .false.                 !< a line has been printed
      integer :: width = 0                       !< length of the in-place line on the terminal
   contains
      procedure :: begin => progress_begin
      procedure :: due => progress_due
      procedure :: show => progress_show
      procedure :: clear => progress_clear
      procedure :: finish => progress_finish
   end type progress_t

contains

   !> Start timing; `quiet` prints nothing. `t_begin`: the simulated time the run starts from
   !> (a restart point; default 0), from which the ETA is measured. `tty` overrides the terminal
   !> test (for tests). A progress line that was never begun prints nothing: the wall time is
   !> measured from `begin` only.
   subroutine progress_begin(self, quiet, t_begin, tty)
      class(progress_t), intent(inout) :: self
      logical, intent(in) :: quiet
      real(wp), intent(in), optional :: t_begin
      logical, intent(in), optional :: tty
      self%start = wall_time()
      self%t_begin = 0.0_wp
      if (present(t_begin)) self%t_begin = t_begin
      self%last = self%start
      self%last_step = 0
      self%quiet = quiet
      self%shown = .false.
      self%width = 0
      if (present(tty)) then
         self%tty = tty
      else
         self%tty = stdout_is_terminal()
      end if
   end subroutine progress_begin

   !> A line is due: not quiet, and the first one or its interval has passed.
   logical function progress_due(self) result(due)
      class(progress_t), intent(in) :: self
      due = .false.
      if (self%quiet) return
      if (.not. self%shown) then
         due = .true.
      else if (self%tty) then
         due = wall_time() - self%last >= self%tty_interval
      else
         due = wall_time() - self%last >= self%log_interval
      end if
   end function progress_due

   !> Print the line: time t of end time tmax (<= 0: unknown), step dt, step number, energy drift.
   subroutine progress_show(self, t, tmax, dt, step, drift)
      class(progress_t), intent(inout) :: self
      real(wp), intent(in) :: t, tmax, dt, drift
      integer(i8), intent(in) :: step
      character(len=160) :: line
      character(len=10) :: pct
      character(len=16) :: eta
      character(len=12) :: rate_text
      real(wp) :: now, frac, elapsed

      if (self%quiet) return
      now = wall_time()
      elapsed = now - self%start
      ! steps per second of wall time since the last line (none yet at the first line)
      rate_text = '?'
      if (self%shown .and. now > self%last) then
         write (rate_text, '(es9.2)') real(step - self%last_step, wp)/(now - self%last)
         rate_text = adjustl(rate_text)
      end if
      if (tmax > 0.0_wp) then
         frac = max(0.0_wp, min(t/tmax, 1.0_wp))
         write (pct, '(f6.1,a)') 100.0_wp*frac, ' %'
         eta = '?'
         if (frac >= 1.0_wp) then
            eta = clock_text(0.0_wp)
         else if (eta_known(elapsed, t, self%t_begin, tmax)) then
            eta = clock_text(eta_seconds(elapsed, t, self%t_begin, tmax))
         end if
      else
         pct = '     ? %'
         eta = '?'
      end if
      write (line, '(a,a,es11.4,a,es9.2,a,i0,a,a,a,a,a,a,a,es9.2)') trim(pct), '  t ', t, &
         '  dt ', dt, '  step ', step, '  ', trim(rate_text), ' steps/s  wall ', trim(clock_text(elapsed)), &
         '  ETA ', trim(eta), '  drift ', drift
      if (self%tty) then
         ! rewrite in place, blanking what is left of a longer earlier line
         write (output_unit, '(a)', advance='no') CR//trim(line)//repeat(' ', max(0, self%width - len_trim(line)))
         self%width = len_trim(line)
      else
         write (output_unit, '(a)') trim(line)
      end if
      flush (output_unit)
      self%shown = .true.
      self%last = now
      self%last_step = step
   end subroutine progress_show

   !> Before other console output: end the in-place line (a newline), so that the next text
   !> starts on a line of its own and the progress line goes on below it.
   subroutine progress_clear(self)
      class(progress_t), intent(inout) :: self
      if (self%quiet .or. .not. self%tty .or. self%width == 0) return
      write (output_unit, '(a)') ''
      flush (output_unit)
      self%width = 0
   end subroutine progress_clear

   !> The last line (the state the run ended in), then a newline on a terminal.
   subroutine progress_finish(self, t, tmax, dt, step, drift)
      class(progress_t), intent(inout) :: self
      real(wp), intent(in) :: t, tmax, dt, drift
      integer(i8), intent(in) :: step
      if (self%quiet) return
      call self%show(t, tmax, dt, step, drift)
      call self%clear()
   end subroutine progress_finish

   !> Whether eta_seconds can tell: simulated time has advanced since `t_begin`, short of tmax.
   pure logical function eta_known(elapsed, t, t_begin, tmax)
      real(wp), intent(in) :: elapsed, t, t_begin, tmax
      eta_known = t > t_begin .and. tmax > t .and. elapsed >= 0.0_wp
   end function eta_known

   !> Wall seconds left to reach tmax at the pace of this process: `elapsed` seconds since
   !> `begin` took the run from t_begin (the restart point, or 0) to t.
   pure real(wp) function eta_seconds(elapsed, t, t_begin, tmax) result(eta)
      real(wp), intent(in) :: elapsed, t, t_begin, tmax
      eta = elapsed*(tmax - t)/(t - t_begin)
   end function eta_seconds

   !> Seconds as h:mm:ss.
   function clock_text(seconds) result(s)
      real(wp), intent(in) :: seconds
      character(len=16) :: s
      integer(i8) :: n
      n = nint(max(0.0_wp, min(seconds, 3.6e9_wp)), i8)
      write (s, '(i0,a,i2.2,a,i2.2)') n/3600_i8, ':', mod(n/60_i8, 60_i8), ':', mod(n, 60_i8)
   end function clock_text

end module exic_base_progress
