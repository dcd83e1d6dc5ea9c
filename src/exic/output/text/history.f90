!> The text outputs of a run (spec section 6): <stem>.his, <stem>.ene and <stem>.out.
!>
!> Rows are written as the run goes; files are flushed at most every `flush_interval` seconds
!> of wall time, before every field output time (so that after a kill they are never behind the
!> .h5, doc/fields.md "Kill safety") and always when closed, so an aborted run keeps what it
!> wrote. Every write, flush and close is checked: the first failure (a full disk, EFBIG, EIO)
!> is kept in `io_error`, naming the file, and the run stops on it.
!>
!> Numbers are written `1x,es24.16e3` (NUMBER_FORMAT): 17 significant digits and always an
!> exponent letter with three exponent digits (`1.2188988004400879E-302`), so every reader
!> (Fortran list-directed, Python, numpy, awk) parses every value, and at least one blank
!> separates the columns.
!>
!> Non-finite values are never written: a row holding a NaN or an infinity is not written;
!> instead `nonfinite` is set, `nonfinite_message` names the file, the column and the time, that
!> message goes once to <stem>.out, and the optional `err` of the row writer returns it, so that
!> the caller can stop the run.
module exic_output_text_history
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t, make_error
   use exic_base_clock, only: wall_time
   use exic_base_strings, only: itoa, rtoa
   use exic_output_text_number, only: put_real, put_int, REAL_WIDTH
   use exic_base_posix, only: truncate_file, file_size
   use exic_explicit_energy, only: energy_t, ENERGY_NAMES, NENERGY, E_KINETIC, E_WCON, E_HOURGLASS, E_PLASTIC, &
                                   DEFAULT_ENERGIES
   implicit none
   private

   public :: history_files_t, energy_columns

   !> Edit descriptor of one real in <stem>.his and <stem>.ene (with its leading blank).
   character(len=*), parameter, public :: NUMBER_FORMAT = '1x,es24.16e3'

   !> The three text files of one run.
   type :: history_files_t
      integer :: his = 0, ene = 0, out = 0
      logical :: opened = .false.   !< units are valid (newunit numbers are negative)
      character(len=:), allocatable :: his_path, ene_path, out_path
      real(wp) :: last_flush = 0.0_wp
      real(wp) :: flush_interval = 0.5_wp
      character(len=64), allocatable :: labels(:)  !< the .his columns after t
      logical :: nonfinite = .false.             !< a row with a non-finite value was refused
      character(len=:), allocatable :: nonfinite_message  !< the first such value: file, column, t
      character(len=:), allocatable :: row       !< the text of a row, assembled before its write
      character(len=:), allocatable :: io_error  !< the first failed write, flush or close
      !> the energies of explicit/energy.f90 that <stem>.ene has (energy_columns)
      logical :: with(NENERGY) = DEFAULT_ENERGIES
   contains
      procedure :: open => files_open
      procedure :: resume => files_resume
      procedure :: flush_all => files_flush_all
      procedure :: sizes => files_sizes
      procedure :: his_header => files_his_header
      procedure :: his_row => files_his_row
      procedure :: ene_row => files_ene_row
      procedure :: say => files_say
      procedure :: maybe_flush => files_maybe_flush
      procedure :: close => files_close
   end type history_files_t

contains

   !> Column names of <stem>.ene, in order, for the energies `with` (explicit/energy.f90):
   !> t, step, dt, kinetic, strain, external_work, contact_work, total, drift, momentum_x,
   !> momentum_y, active, hourglass, prescribed_work [ext], doc/loads.md section 3,
   !> friction_dissipation [ext], doc/friction.md section 5, plastic_work [ext],
   !> doc/axisymmetry.md section 8, kinetic_correction [ext], doc/decisions.md "Energy balance"
   !> (appended after the older columns so that they keep their positions); then, only when the
   !> model has them, damping_dissipation and bulk_viscosity (doc/damping.md).
   function energy_columns(with) result(text)
      logical, intent(in) :: with(NENERGY)
      character(len=:), allocatable :: text
      integer :: k
      text = 't step dt'
      do k = E_KINETIC, E_WCON
         text = text//' '//trim(ENERGY_NAMES(k))
      end do
      text = text//' total drift momentum_x momentum_y active'
      do k = E_HOURGLASS, E_PLASTIC
         text = text//' '//trim(ENERGY_NAMES(k))
      end do
      text = text//' kinetic_correction'
      do k = E_PLASTIC + 1, NENERGY
         if (with(k)) text = text//' '//trim(ENERGY_NAMES(k))
      end do
   end function energy_columns

   !> Create <base>.his, <base>.ene and <base>.out (base = directory/stem); `with`: the energies
   !> of <stem>.ene past the fixed ones (energy_columns; default DEFAULT_ENERGIES).
   subroutine files_open(self, base, err, with)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: base
      type(error_t), allocatable, intent(out) :: err
      logical, intent(in), optional :: with(NENERGY)
      integer :: ios
      character(len=256) :: msg
      if (present(with)) self%with = with .or. DEFAULT_ENERGIES
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
      write (self%ene, '(a)', iostat=ios, iomsg=msg) '# '//energy_columns(self%with)
      call check_io(self, ios, msg, self%ene_path)
      self%last_flush = wall_time()
   end subroutine files_open

   !> Continue the files of a run from its restart point: <base>.his and <base>.ene cut to the
   !> lengths they had then (`his_bytes`, `ene_bytes`) and appended to, <base>.out appended to.
   subroutine files_resume(self, base, his_bytes, ene_bytes, err)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: base
      integer(i8), intent(in) :: his_bytes, ene_bytes
      type(error_t), allocatable, intent(out) :: err
      self%his_path = base//'.his'
      self%ene_path = base//'.ene'
      self%out_path = base//'.out'
      call reopen(self%his_path, his_bytes, self%his, err)
      if (.not. allocated(err)) call reopen(self%ene_path, ene_bytes, self%ene, err)
      if (.not. allocated(err)) call reopen(self%out_path, -1_i8, self%out, err)
      if (allocated(err)) return
      self%opened = .true.
      self%last_flush = wall_time()
   end subroutine files_resume

   !> Open `path` to append to it, after cutting it to `bytes` (>= 0; -1: as it is). The file
   !> must hold at least `bytes`.
   subroutine reopen(path, bytes, unit, err)
      character(len=*), intent(in) :: path
      integer(i8), intent(in) :: bytes
      integer, intent(out) :: unit
      type(error_t), allocatable, intent(out) :: err
      integer :: ios
      character(len=256) :: msg
      if (bytes >= 0) then
         if (file_size(path) < bytes) then
            call make_error(err, 'the file is shorter than at the restart point ('//itoa(bytes)// &
                            ' bytes): it is not the output of the run that wrote the restart file', path)
            return
         end if
         call truncate_file(path, bytes, err)
         if (allocated(err)) return
      end if
      open (newunit=unit, file=path, status='unknown', position='append', action='write', &
            form='formatted', iostat=ios, iomsg=msg)
      if (ios /= 0) call make_error(err, 'cannot open output file to continue it: '//trim(msg), path)
   end subroutine reopen

   !> Keep the first I/O failure (status `ios`, message `msg`) on the file `path`.
   subroutine check_io(self, ios, msg, path)
      class(history_files_t), intent(inout) :: self
      integer, intent(in) :: ios
      character(len=*), intent(in) :: msg, path
      if (ios == 0 .or. allocated(self%io_error)) return
      self%io_error = "cannot write '"//path//"': "//trim(msg)
   end subroutine check_io

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
   !> (`write_it` false: only take the labels, the file has its header: a restarted run).
   subroutine files_his_header(self, labels, write_it)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: labels(:)
      logical, intent(in), optional :: write_it
      character(len=:), allocatable :: line
      integer :: k, ios
      character(len=256) :: msg
      self%labels = labels
      if (present(write_it)) then
         if (.not. write_it) return
      end if
      line = '# t'
      do k = 1, size(labels)
         line = line//'  '//trim(labels(k))
      end do
      write (self%his, '(a)', iostat=ios, iomsg=msg) line
      call check_io(self, ios, msg, self%his_path)
   end subroutine files_his_header

   !> One row of <stem>.his: time, then the requested values at full precision. A row with a
   !> non-finite value is not written (see the module header); `err` then says which.
   subroutine files_his_row(self, t, values, err)
      class(history_files_t), intent(inout) :: self
      real(wp), intent(in) :: t
      real(wp), intent(in) :: values(:)
      type(error_t), allocatable, intent(out), optional :: err
      integer :: k, n, ios
      character(len=256) :: msg
      if (.not. ieee_is_finite(t)) then
         call refuse(self, 'his', 't', t, t, err)
         return
      end if
      do k = 1, size(values)
         if (.not. ieee_is_finite(values(k))) then
            call refuse(self, 'his', his_label(self, k), values(k), t, err)
            return
         end if
      end do
      ! the text of write (self%his, '(*('//NUMBER_FORMAT//'))') t, values
      call reserve(self, REAL_WIDTH*(1 + size(values)))
      n = 0
      call put_real(self%row, n, t)
      do k = 1, size(values)
         call put_real(self%row, n, values(k))
      end do
      write (self%his, '(a)', iostat=ios, iomsg=msg) self%row(1:n)
      call check_io(self, ios, msg, self%his_path)
      call self%maybe_flush()
   end subroutine files_his_row

   !> One row of <stem>.ene: the energies `en` with the balance's total and drift and kc, the
   !> change of the kinetic correction (part of total). A row with a non-finite value is not
   !> written (see the module header); `err` then says which.
   subroutine files_ene_row(self, t, step, dt, en, total, drift, momentum, nactive, kc, err)
      class(history_files_t), intent(inout) :: self
      real(wp), intent(in) :: t, dt, total, drift, momentum(2), kc
      type(energy_t), intent(in) :: en
      integer(i8), intent(in) :: step
      integer, intent(in) :: nactive
      type(error_t), allocatable, intent(out), optional :: err
      real(wp) :: e(NENERGY), v(9 + NENERGY)
      character(len=20) :: names(9 + NENERGY)
      integer :: k, n, m, ios
      character(len=256) :: msg
      ! the real columns in the order of the row (step and active apart)
      e = en%values()
      v(1:2) = [t, dt]
      names(1:2) = [character(len=20) :: 't', 'dt']
      v(3:6) = e(E_KINETIC:E_WCON)
      names(3:6) = ENERGY_NAMES(E_KINETIC:E_WCON)
      v(7:10) = [total, drift, momentum]
      names(7:10) = [character(len=20) :: 'total', 'drift', 'momentum_x', 'momentum_y']
      v(11:14) = e(E_HOURGLASS:E_PLASTIC)
      names(11:14) = ENERGY_NAMES(E_HOURGLASS:E_PLASTIC)
      v(15) = kc
      names(15) = 'kinetic_correction'
      m = 15
      do k = E_PLASTIC + 1, NENERGY
         if (.not. self%with(k)) cycle
         m = m + 1
         v(m) = e(k)
         names(m) = ENERGY_NAMES(k)
      end do
      do k = 1, m
         if (.not. ieee_is_finite(v(k))) then
            call refuse(self, 'ene', trim(names(k)), v(k), t, err)
            return
         end if
      end do
      ! the text of write (self%ene, '('//NUMBER_FORMAT//',i12,9('//NUMBER_FORMAT//'),i10,5('// &
      ! NUMBER_FORMAT//'),...)') v(1), step, v(2:10), nactive, v(11:m)
      call reserve(self, m*REAL_WIDTH + 22)
      n = 0
      call put_real(self%row, n, v(1))
      call put_int(self%row, n, step, 12)
      do k = 2, 10
         call put_real(self%row, n, v(k))
      end do
      call put_int(self%row, n, int(nactive, i8), 10)
      do k = 11, m
         call put_real(self%row, n, v(k))
      end do
      write (self%ene, '(a)', iostat=ios, iomsg=msg) self%row(1:n)
      call check_io(self, ios, msg, self%ene_path)
      call self%maybe_flush()
   end subroutine files_ene_row

   !> The row buffer holds at least n characters.
   subroutine reserve(self, n)
      class(history_files_t), intent(inout) :: self
      integer, intent(in) :: n
      if (allocated(self%row)) then
         if (len(self%row) >= n) return
      end if
      if (allocated(self%row)) deallocate (self%row)
      allocate (character(len=max(n, 2*REAL_WIDTH*16)) :: self%row)
   end subroutine reserve

   !> Name of .his column k (after t).
   function his_label(self, k) result(name)
      class(history_files_t), intent(in) :: self
      integer, intent(in) :: k
      character(len=:), allocatable :: name
      name = 'column '//itoa(k + 1)
      if (allocated(self%labels)) then
         if (k <= size(self%labels)) name = trim(self%labels(k))
      end if
   end function his_label

   !> A row of <stem>.<ext> was refused for the non-finite value `v` of `column` at time `t`.
   subroutine refuse(self, ext, column, v, t, err)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: ext, column
      real(wp), intent(in) :: v, t
      type(error_t), allocatable, intent(out), optional :: err
      character(len=:), allocatable :: what, msg
      if (v /= v) then
         what = 'NaN'
      else
         what = 'an infinite value'
      end if
      msg = what//' in column '//column//' of <stem>.'//ext//' at t = '//rtoa(t)// &
            ': the row is not written'
      if (.not. self%nonfinite) then
         self%nonfinite = .true.
         self%nonfinite_message = msg
         call self%say('error: '//msg)
      end if
      if (present(err)) call make_error(err, msg)
   end subroutine refuse

   !> A line of text in <stem>.out.
   subroutine files_say(self, text)
      class(history_files_t), intent(inout) :: self
      character(len=*), intent(in) :: text
      integer :: ios
      character(len=256) :: msg
      if (.not. self%opened) return
      write (self%out, '(a)', iostat=ios, iomsg=msg) text
      call check_io(self, ios, msg, self%out_path)
   end subroutine files_say

   !> Flush every file when `flush_interval` seconds have passed since the last flush.
   subroutine files_maybe_flush(self)
      class(history_files_t), intent(inout) :: self
      real(wp) :: now
      now = wall_time()
      if (now - self%last_flush < self%flush_interval) return
      call self%flush_all()
   end subroutine files_maybe_flush

   !> Flush every file now (checked).
   subroutine files_flush_all(self)
      class(history_files_t), intent(inout) :: self
      integer :: ios
      character(len=256) :: msg
      if (.not. self%opened) return
      flush (self%his, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%his_path)
      flush (self%ene, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%ene_path)
      flush (self%out, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%out_path)
      self%last_flush = wall_time()
   end subroutine files_flush_all

   !> Flush, then the lengths of <stem>.his and <stem>.ene in bytes (for a restart file).
   subroutine files_sizes(self, his_bytes, ene_bytes)
      class(history_files_t), intent(inout) :: self
      integer(i8), intent(out) :: his_bytes, ene_bytes
      call self%flush_all()
      his_bytes = file_size(self%his_path)
      ene_bytes = file_size(self%ene_path)
   end subroutine files_sizes

   !> Close every file (which flushes it; checked).
   subroutine files_close(self)
      class(history_files_t), intent(inout) :: self
      integer :: ios
      character(len=256) :: msg
      if (.not. self%opened) return
      close (self%his, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%his_path)
      close (self%ene, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%ene_path)
      close (self%out, iostat=ios, iomsg=msg)
      call check_io(self, ios, msg, self%out_path)
      self%opened = .false.
   end subroutine files_close

end module exic_output_text_history
