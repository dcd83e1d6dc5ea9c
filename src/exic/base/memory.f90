!> How much memory a mesh needs, checked before the reader allocates it.
!>
!> A run of a mesh with `nnode` nodes (the highest node number: arrays are sized by it) and
!> `nelem` elements needs about BYTES_PER_NODE nnode + BYTES_PER_ELEMENT nelem bytes at its
!> peak (reader, mesh, state, element sets, contact surfaces and HDF5 buffers). The figures were
!> measured with the release build (peak virtual size less that of an empty run) on square and
!> strip meshes of 0.3-2.6 million nodes: about 300 B per node and 370 B per element without
!> contact or field output, about 850 B per node-and-element pair with AUTOmatic contact and
!> OUTPut,HDF5; the constants below are rounded up from the latter.
!>
!> The memory available is the smaller of
!> - MemAvailable + SwapFree of /proc/meminfo (what the machine can give without swapping out
!>   other programs' pages), and
!> - the address-space limit RLIMIT_AS (`ulimit -v`) less the current virtual size VmSize of
!>   /proc/self/status.
!> When neither can be read (not Linux), no limit is applied.
module exic_base_memory
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa
   use exic_base_posix, only: address_space_limit
   implicit none
   private

   public :: mesh_bytes, available_memory, mesh_memory_message

   !> Bytes per node and per element of a run (see above).
   integer(i8), parameter, public :: BYTES_PER_NODE = 400_i8, BYTES_PER_ELEMENT = 500_i8
   !> Node and element numbers from which single records (COORdinates, BOUNdary, ELEMents ...)
   !> are checked; BLOCk and Gmsh meshes are checked whatever their size. Below it a record
   !> asks for at most 0.9 GB.
   integer, parameter, public :: MEMORY_CHECK_FROM = 1000000

   !> The memory available at the last reading by mesh_memory_message (0: none yet) and the
   !> address-space limit then (-1: none).
   integer(i8), save :: last_have = 0_i8, last_limit = -1_i8

contains

   !> Estimated peak bytes of a run of a mesh with highest node number `nnode` and `nelem`
   !> elements.
   pure integer(i8) function mesh_bytes(nnode, nelem)
      integer(i8), intent(in) :: nnode, nelem
      mesh_bytes = BYTES_PER_NODE*max(nnode, 0_i8) + BYTES_PER_ELEMENT*max(nelem, 0_i8)
   end function mesh_bytes

   !> The memory this process may still use, in bytes, and where that figure comes from;
   !> `known` is false when no limit could be read.
   subroutine available_memory(bytes, source, known)
      integer(i8), intent(out) :: bytes
      character(len=:), allocatable, intent(out) :: source
      logical, intent(out) :: known
      integer(i8) :: avail, swap, limit, vmsize
      logical :: have_avail, have_swap, limited, have_vm

      bytes = huge(1_i8)
      source = ''
      known = .false.
      call proc_value('/proc/meminfo', 'MemAvailable:', avail, have_avail)
      call proc_value('/proc/meminfo', 'SwapFree:', swap, have_swap)
      if (have_avail) then
         if (.not. have_swap) swap = 0_i8
         bytes = avail + swap
         source = 'memory available on this machine (MemAvailable + SwapFree of /proc/meminfo)'
         known = .true.
      end if
      call address_space_limit(limit, limited)
      if (limited) then
         call proc_value('/proc/self/status', 'VmSize:', vmsize, have_vm)
         if (.not. have_vm) vmsize = 0_i8
         if (limit - vmsize < bytes) then
            bytes = max(limit - vmsize, 0_i8)
            source = 'address space left under the limit RLIMIT_AS (ulimit -v)'
            known = .true.
         end if
      end if
   end subroutine available_memory

   !> '' when a mesh of `nnode` (highest number) and `nelem` elements fits in `limit` bytes
   !> (default: available_memory), else a message "needs about N GB ...". `source` names the
   !> limit in the message when `limit` is given.
   function mesh_memory_message(nnode, nelem, limit, source) result(msg)
      integer, intent(in) :: nnode, nelem
      integer(i8), intent(in), optional :: limit
      character(len=*), intent(in), optional :: source
      character(len=:), allocatable :: msg
      integer(i8) :: need, have, limit_now
      character(len=:), allocatable :: from
      logical :: known, limited

      msg = ''
      need = mesh_bytes(int(nnode, i8), int(nelem, i8))
      if (present(limit)) then
         have = limit
         from = 'given limit'
         if (present(source)) from = source
      else
         ! a mesh needing less than half of what was available at the last reading, under the
         ! same address-space limit, fits without a new one: a deck of thousands of BLOCks read
         ! /proc once per block (a quarter of the processor time of reading 4096 bodies)
         call address_space_limit(limit_now, limited)
         if (.not. limited) limit_now = -1_i8
         if (need <= last_have/2 .and. limit_now == last_limit) return
         call available_memory(have, from, known)
         if (.not. known) return
         last_have = have
         last_limit = limit_now
      end if
      if (need <= have) return
      msg = 'the mesh needs about '//gigabytes(need)//' ('//itoa(nnode)//' nodes, '// &
            itoa(nelem)//' elements, at about '//itoa(int(BYTES_PER_NODE))// &
            ' bytes per node and '//itoa(int(BYTES_PER_ELEMENT))//' per element), more than the '// &
            gigabytes(have)//' of '//from//': expected a smaller mesh'
   end function mesh_memory_message

   !> Bytes as "x.y GB" (10^9 bytes).
   pure function gigabytes(b) result(s)
      integer(i8), intent(in) :: b
      character(len=:), allocatable :: s
      character(len=32) :: buf
      write (buf, '(f0.1)') real(b, wp)/1.0e9_wp
      s = trim(adjustl(buf))
      if (s(1:1) == '.') s = '0'//s
      s = s//' GB'
   end function gigabytes

   !> The value of line `key` (in kB) of a /proc file, in bytes; `found` is false when absent.
   subroutine proc_value(path, key, bytes, found)
      character(len=*), intent(in) :: path, key
      integer(i8), intent(out) :: bytes
      logical, intent(out) :: found
      character(len=256) :: line
      integer :: u, ios
      integer(i8) :: kb

      bytes = 0_i8
      found = .false.
      open (newunit=u, file=path, status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (index(line, key) /= 1) cycle
         read (line(len(key) + 1:), *, iostat=ios) kb
         if (ios == 0 .and. kb >= 0_i8) then
            bytes = 1024_i8*kb
            found = .true.
         end if
         exit
      end do
      close (u)
   end subroutine proc_value

end module exic_base_memory
