!> The program's view of MPI (doc/parallel.md): rank, size, stop of every rank, and the few
!> exchanges the distributed step uses. Every exchange moves values (copies, never sums of
!> reals), so that what a rank receives is bit for bit what another computed.
!>
!> A program that never calls `par_init` (the test programs, a host of the legacy library)
!> is one rank: `par_rank` is 0, `par_size` 1, and no MPI routine other than MPI_Initialized
!> is called. `exic` calls `par_init` first thing, which starts MPI only when a launcher
!> started the process (mpirun, srun, mpiexec: LAUNCHER_VARIABLES below); started alone, it is
!> one rank without MPI (an MPI singleton would start OpenMPI's run-time daemon, about a second
!> and a shared-memory segment, for nothing).
module exic_parallel_mpi
   use exic_base_kinds, only: wp
   use mpi_f08, only: MPI_Init_thread, MPI_Initialized, MPI_Finalized, MPI_Finalize, MPI_Abort, &
                      MPI_Comm_rank, MPI_Comm_size, MPI_Allgather, MPI_Allgatherv, MPI_Allreduce, &
                      MPI_Bcast, MPI_Barrier, MPI_COMM_WORLD, MPI_THREAD_FUNNELED, &
                      MPI_DOUBLE_PRECISION, MPI_INTEGER, MPI_LOGICAL, MPI_LOR, MPI_MAX, MPI_BOR, &
                      MPI_Alltoall, MPI_Alltoallv, MPI_Isend, MPI_Irecv, MPI_Waitall, MPI_Request, &
                      MPI_STATUSES_IGNORE, MPI_IN_PLACE
   implicit none
   private

   public :: par_init, par_finalize, par_abort, par_rank, par_size, par_running
   public :: par_allgatherv, par_allgather_int, par_any, par_max_int, par_or_bits, par_barrier, par_bcast_int
   public :: par_allgatherv_in_place, par_alltoallv_int, par_neighbour_exchange

   !> Environment variables of which one is set in a process that an MPI launcher started:
   !> OpenMPI's mpirun, PMIx (srun --mpi=pmix, OpenMPI 4), PMI-1/2 (srun --mpi=pmi2, MPICH's
   !> Hydra mpiexec).
   character(len=*), parameter :: LAUNCHER_VARIABLES(4) = [character(len=20) :: 'OMPI_COMM_WORLD_SIZE', &
                                                           'PMIX_RANK', 'PMI_RANK', 'PMI_SIZE']

   !> MPI_Allgatherv of reals, or of integers.
   interface par_allgatherv
      module procedure allgatherv_real, allgatherv_int
   end interface par_allgatherv

contains

   !> Start MPI when an MPI launcher started this process (threads: only the thread that called
   !> this one makes MPI calls, FUNNELED); else nothing (one rank).
   subroutine par_init()
      integer :: provided, k, l
      logical :: on
      call MPI_Initialized(on)
      if (on) return
      do k = 1, size(LAUNCHER_VARIABLES)
         call get_environment_variable(trim(LAUNCHER_VARIABLES(k)), length=l)
         if (l > 0) then
            call MPI_Init_thread(MPI_THREAD_FUNNELED, provided)
            return
         end if
      end do
   end subroutine par_init

   !> End MPI, when it was started and is not ended yet.
   subroutine par_finalize()
      logical :: on, off
      call MPI_Initialized(on)
      if (.not. on) return
      call MPI_Finalized(off)
      if (.not. off) call MPI_Finalize()
   end subroutine par_finalize

   !> MPI is started and not yet ended in this process.
   logical function par_running() result(on)
      logical :: off
      call MPI_Initialized(on)
      if (.not. on) return
      call MPI_Finalized(off)
      on = .not. off
   end function par_running

   !> This process's rank (0 without MPI).
   integer function par_rank() result(r)
      r = 0
      if (par_running()) call MPI_Comm_rank(MPI_COMM_WORLD, r)
   end function par_rank

   !> The number of ranks (1 without MPI).
   integer function par_size() result(p)
      p = 1
      if (par_running()) call MPI_Comm_size(MPI_COMM_WORLD, p)
   end function par_size

   !> Stop every rank with exit code `code` (MPI_Abort; a plain stop without MPI).
   subroutine par_abort(code)
      integer, intent(in) :: code
      if (par_running()) call MPI_Abort(MPI_COMM_WORLD, code)
      error stop code
   end subroutine par_abort

   !> Wait for every rank.
   subroutine par_barrier()
      if (par_size() > 1) call MPI_Barrier(MPI_COMM_WORLD)
   end subroutine par_barrier

   !> recv = the send(1:counts(r+1)) of every rank r, rank after rank (counts of every rank
   !> known to every rank). One rank: a copy.
   subroutine allgatherv_real(n, send, counts, recv)
      integer, intent(in) :: n
      real(wp), intent(in) :: send(n)
      integer, intent(in) :: counts(:)
      real(wp), intent(out) :: recv(:)
      integer :: displs(size(counts)), r
      if (size(counts) == 1) then
         recv(1:n) = send
         return
      end if
      displs(1) = 0
      do r = 2, size(counts)
         displs(r) = displs(r - 1) + counts(r - 1)
      end do
      call MPI_Allgatherv(send, n, MPI_DOUBLE_PRECISION, recv, counts, displs, MPI_DOUBLE_PRECISION, &
                          MPI_COMM_WORLD)
   end subroutine allgatherv_real

   !> The integer twin of allgatherv_real.
   subroutine allgatherv_int(n, send, counts, recv)
      integer, intent(in) :: n
      integer, intent(in) :: send(n)
      integer, intent(in) :: counts(:)
      integer, intent(out) :: recv(:)
      integer :: displs(size(counts)), r
      if (size(counts) == 1) then
         recv(1:n) = send
         return
      end if
      displs(1) = 0
      do r = 2, size(counts)
         displs(r) = displs(r - 1) + counts(r - 1)
      end do
      call MPI_Allgatherv(send, n, MPI_INTEGER, recv, counts, displs, MPI_INTEGER, MPI_COMM_WORLD)
   end subroutine allgatherv_int

   !> every(r+1) = the `mine` of rank r.
   subroutine par_allgather_int(mine, every)
      integer, intent(in) :: mine
      integer, intent(out) :: every(:)
      if (size(every) == 1) then
         every(1) = mine
         return
      end if
      call MPI_Allgather(mine, 1, MPI_INTEGER, every, 1, MPI_INTEGER, MPI_COMM_WORLD)
   end subroutine par_allgather_int

   !> True on every rank when `flag` is true on one of them (a logical reduction: exact).
   logical function par_any(flag) result(any_rank)
      logical, intent(in) :: flag
      any_rank = flag
      if (par_size() > 1) call MPI_Allreduce(flag, any_rank, 1, MPI_LOGICAL, MPI_LOR, MPI_COMM_WORLD)
   end function par_any

   !> The largest `k` of every rank (an integer reduction: exact).
   integer function par_max_int(k) result(kmax)
      integer, intent(in) :: k
      kmax = k
      if (par_size() > 1) call MPI_Allreduce(k, kmax, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD)
   end function par_max_int

   !> The bitwise or of `bits` over every rank (the signals that came to any rank).
   integer function par_or_bits(bits) result(all_bits)
      integer, intent(in) :: bits
      all_bits = bits
      if (par_size() > 1) call MPI_Allreduce(bits, all_bits, 1, MPI_INTEGER, MPI_BOR, MPI_COMM_WORLD)
   end function par_or_bits

   !> buf(displs(r+1)+1 : displs(r+1)+counts(r+1)) of rank r copied to every rank, in place
   !> (MPI_Allgatherv with MPI_IN_PLACE: each rank's part is already where it belongs). One
   !> rank: nothing.
   subroutine par_allgatherv_in_place(n, buf, counts, displs)
      integer, intent(in) :: n
      real(wp), intent(inout) :: buf(n)
      integer, intent(in) :: counts(:), displs(:)
      if (size(counts) == 1) return
      call MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DOUBLE_PRECISION, buf, counts, displs, MPI_DOUBLE_PRECISION, &
                          MPI_COMM_WORLD)
   end subroutine par_allgatherv_in_place

   !> Integers to every rank: send(sdispl(r+1)+1 : ... + scounts(r+1)) goes to rank r; recv
   !> gets from rank r rcounts(r+1) values (exchanged first with MPI_Alltoall), rank after rank.
   subroutine par_alltoallv_int(send, scounts, recv, rcounts)
      integer, intent(in) :: send(:), scounts(:)
      integer, allocatable, intent(out) :: recv(:)
      integer, intent(out) :: rcounts(:)
      integer :: sd(size(scounts)), rd(size(scounts)), r
      if (size(scounts) == 1) then
         rcounts = scounts
         recv = send(1:scounts(1))
         return
      end if
      call MPI_Alltoall(scounts, 1, MPI_INTEGER, rcounts, 1, MPI_INTEGER, MPI_COMM_WORLD)
      sd(1) = 0
      rd(1) = 0
      do r = 2, size(scounts)
         sd(r) = sd(r - 1) + scounts(r - 1)
         rd(r) = rd(r - 1) + rcounts(r - 1)
      end do
      allocate (recv(sum(rcounts)))
      call MPI_Alltoallv(send, scounts, sd, MPI_INTEGER, recv, rcounts, rd, MPI_INTEGER, MPI_COMM_WORLD)
   end subroutine par_alltoallv_int

   !> Point-to-point exchange of values with the neighbours nb(:) (ranks): sbuf(sfirst(k) :
   !> sfirst(k+1) - 1) goes to nb(k), rbuf(rfirst(k) : rfirst(k+1) - 1) comes from nb(k)
   !> (MPI_Irecv, MPI_Isend, MPI_Waitall; values copied, never summed).
   subroutine par_neighbour_exchange(nb, sfirst, sbuf, rfirst, rbuf)
      integer, intent(in) :: nb(:), sfirst(:), rfirst(:)
      real(wp), intent(in), asynchronous, contiguous, target :: sbuf(:)
      real(wp), intent(inout), asynchronous, contiguous, target :: rbuf(:)
      type(MPI_Request) :: req(2*size(nb))
      integer :: k, n
      n = 0
      do k = 1, size(nb)
         if (rfirst(k + 1) > rfirst(k)) then
            n = n + 1
            call MPI_Irecv(rbuf(rfirst(k):rfirst(k + 1) - 1), rfirst(k + 1) - rfirst(k), MPI_DOUBLE_PRECISION, nb(k), 31, &
                           MPI_COMM_WORLD, req(n))
         end if
      end do
      do k = 1, size(nb)
         if (sfirst(k + 1) > sfirst(k)) then
            n = n + 1
            call MPI_Isend(sbuf(sfirst(k):sfirst(k + 1) - 1), sfirst(k + 1) - sfirst(k), MPI_DOUBLE_PRECISION, nb(k), 31, &
                           MPI_COMM_WORLD, req(n))
         end if
      end do
      if (n > 0) call MPI_Waitall(n, req(1:n), MPI_STATUSES_IGNORE)
   end subroutine par_neighbour_exchange

   !> a(1:n) of rank 0 on every rank.
   subroutine par_bcast_int(n, a)
      integer, intent(in) :: n
      integer, intent(inout) :: a(n)
      if (par_size() > 1) call MPI_Bcast(a, n, MPI_INTEGER, 0, MPI_COMM_WORLD)
   end subroutine par_bcast_int

end module exic_parallel_mpi
