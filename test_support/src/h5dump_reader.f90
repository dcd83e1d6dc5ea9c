!> Read a dataset of an HDF5 file through the h5dump command (hdf5-tools): its dataspace text
!> and every number of its data, for tests that check a file as a reader other than exic sees it.
module h5dump_reader
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: h5dump

contains

   !> Run h5dump with `args` (after `env`, e.g. a variable assignment) and collect the first
   !> DATASPACE text (between braces) and every number of the DATA block, in storage order.
   subroutine h5dump(env, args, ok, space, vals)
      character(len=*), intent(in) :: env, args
      logical, intent(out) :: ok
      character(len=:), allocatable, intent(out) :: space
      real(wp), allocatable, intent(out) :: vals(:)
      character(len=*), parameter :: out = 'build/test_fields/h5dump.txt'
      character(len=:), allocatable :: line
      integer :: code, u, ios, i, j
      logical :: in_data

      space = ''
      allocate (vals(0))
      call execute_command_line('mkdir -p build/test_fields')
      call execute_command_line(env//'h5dump -A 0 -y -w 0 -m %.17g '//args//' > '//out//' 2>&1', &
                                exitstat=code)
      ok = code == 0
      open (newunit=u, file=out, action='read', status='old', iostat=ios)
      if (ios /= 0) then
         ok = .false.
         return
      end if
      in_data = .false.
      do
         call read_line(u, line, ios)
         if (ios /= 0) exit
         if (in_data) then
            if (adjustl(line) == '}') exit
            call append_numbers(line, vals)
         else if (index(line, 'DATASPACE') > 0 .and. len(space) == 0) then
            i = index(line, '{')
            j = index(line, '}', back=.true.)
            if (i > 0 .and. j > i) space = trim(adjustl(line(i + 1:j - 1)))
         else if (index(line, 'DATA {') > 0) then
            in_data = .true.
         end if
      end do
      close (u)
   end subroutine h5dump


   !> Append the comma/blank separated numbers of `line` to `vals`.
   subroutine append_numbers(line, vals)
      character(len=*), intent(in) :: line
      real(wp), allocatable, intent(inout) :: vals(:)
      character(len=len(line)) :: work
      integer :: i, j, ios
      real(wp) :: x

      work = line
      do i = 1, len(work)
         if (work(i:i) == ',') work(i:i) = ' '
      end do
      i = 1
      do
         do while (i <= len(work))
            if (work(i:i) /= ' ') exit
            i = i + 1
         end do
         if (i > len(work)) exit
         j = index(work(i:), ' ')
         if (j == 0) then
            j = len(work)
         else
            j = i + j - 2
         end if
         read (work(i:j), *, iostat=ios) x
         if (ios == 0) vals = [vals, x]
         i = j + 1
      end do
   end subroutine append_numbers


   !> Read one whole line of any length.
   subroutine read_line(u, line, ios)
      integer, intent(in) :: u
      character(len=:), allocatable, intent(out) :: line
      integer, intent(out) :: ios
      character(len=256) :: buf
      integer :: n
      line = ''
      do
         read (u, '(a)', advance='no', iostat=ios, size=n) buf
         line = line//buf(1:n)
         if (ios /= 0) exit
      end do
      if (is_iostat_eor(ios)) ios = 0
   end subroutine read_line

end module h5dump_reader
