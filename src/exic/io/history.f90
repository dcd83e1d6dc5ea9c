!> The text outputs of a run (spec section 6): <stem>.his, <stem>.ene and <stem>.out.
!>
!> Rows are written as the run goes; files are flushed at most every `flush_interval` seconds
!> of wall time and always when closed, so an aborted run keeps what it wrote.
module exic_io_history
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   implicit none
   private

   public :: history_files_t, ENERGY_COLUMNS

   !> Column names of <stem>.ene, in order (prescribed_work [ext], doc/loads.md section 3, and
   !> friction_dissipation [ext], doc/friction.md section 5, appended after the older columns so
   !> that they keep their positions).
   character(len=*), parameter :: ENERGY_COLUMNS = &
      't step dt kinetic strain external_work contact_work total drift momentum_x momentum_y '// &
      'active hourglass prescribed_work friction_dissipation'

   !> The three text files of one run.
   type :: history_files_t
      integer :: his = 0, ene = 0, out = 0
      logical :: opened = .false.   !< units are valid (newunit numbers are negative)
      character(len=:), allocatable :: his_path, ene_path, out_path
      real(wp) :: last_flush = 0.0_wp
      real(wp) :: flush_interval = 0.5_wp
   contains
      procedure :: open => files_open
      procedure :: his_header => files_his_header
      procedure :: his_row => files_his_row
      procedure :: ene_row => files_ene_row
      procedure :: say => files_say
      procedure :: maybe_flush => files_maybe_flush
      procedure :: close => files_close
   end type history_files_t

contains

   !> Create <base>.his, <base>.ene and <base>.out (base = directory/stem).
   subroutine files_open(self, base, err)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: base
      type(error_t), allocatable, intent(out) :: err
      self%his_path = base//'.his'
      self%ene_path = base//'.ene'
      self%out_path = base//'.out'
      call open_new(self%his_path, self%his, err)
      if (allocated(err)) return
      call open_new(self%ene_path, self%ene, err)
      if (allocated(err)) return
      call open_new(self%out_path, self%out, err)
      if (allocated(err)) return
      self%opened = .true.
      write (self%ene, '(a)') '# '//ENERGY_COLUMNS
      self%last_flush = wall_time()
   end subroutine files_open

   !> Open `path` for writing, replacing an old file.
   subroutine open_new(path, unit, err)
      character(len=*), intent(in) :: path
      integer, intent(out) :: unit
      type(error_t), allocatable, intent(out) :: err
      integer :: ios
      character(len=256) :: msg
      open (newunit=unit, file=path, status='replace', action='write', form='formatted', &
            iostat=ios, iomsg=msg)
      if (ios /= 0) call make_error(err, 'cannot create output file: '//trim(msg), path)
   end subroutine open_new

   !> Write the '#' header naming every column of <stem>.his.
   subroutine files_his_header(self, labels)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: labels(:)
      integer :: k
      write (self%his, '(a)', advance='no') '# t'
      do k = 1, size(labels)
         write (self%his, '(2a)', advance='no') '  ', trim(labels(k))
      end do
      write (self%his, '(a)') ''
   end subroutine files_his_header

   !> One row of <stem>.his: time, then the requested values at full precision.
   subroutine files_his_row(self, t, values)
      class(history_files_t), intent(inout) :: self
      real(wp), intent(in) :: t
      real(wp), intent(in) :: values(:)
      write (self%his, '(*(es24.16))') t, values
      call self%maybe_flush()
   end subroutine files_his_row

   !> One row of <stem>.ene.
   subroutine files_ene_row(self, t, step, dt, kinetic, strain, wext, wcon, total, drift, &
                            momentum, nactive, hourglass, wpm, dfric)
      class(history_files_t), intent(inout) :: self
      real(wp), intent(in) :: t, dt, kinetic, strain, wext, wcon, total, drift, momentum(2), hourglass
      real(wp), intent(in) :: wpm      !< work of the prescribed motion
      real(wp), intent(in) :: dfric    !< frictional dissipation
      integer(i8), intent(in) :: step
      integer, intent(in) :: nactive
      write (self%ene, '(es24.16,i12,9es24.16,i10,3es24.16)') t, step, dt, kinetic, strain, wext, &
         wcon, total, drift, momentum, nactive, hourglass, wpm, dfric
      call self%maybe_flush()
   end subroutine files_ene_row

   !> A line of text in <stem>.out.
   subroutine files_say(self, text)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: text
      if (.not. self%opened) return
      write (self%out, '(a)') text
   end subroutine files_say

   !> Flush every file when `flush_interval` seconds have passed since the last flush.
   subroutine files_maybe_flush(self)
      class(history_files_t), intent(inout) :: self
      real(wp) :: now
      now = wall_time()
      if (now - self%last_flush < self%flush_interval) return
      if (.not. self%opened) return
      flush (self%his)
      flush (self%ene)
      flush (self%out)
      self%last_flush = now
   end subroutine files_maybe_flush

   !> Close every file (which flushes it).
   subroutine files_close(self)
      class(history_files_t), intent(inout) :: self
      if (.not. self%opened) return
      close (self%his)
      close (self%ene)
      close (self%out)
      self%opened = .false.
   end subroutine files_close

end module exic_io_history
