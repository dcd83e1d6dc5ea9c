!> The force pass on P ranks (doc/parallel.md): every rank holds the whole nodal state and runs
!> the nodal part of the step itself; the element pass is divided. Each rank computes the
!> blocks of NBLOCK elements (the serial pass's blocks, same ranges, same colours) that hold an
!> element it owns or an element at a node it owns, so that at every node it owns it adds the
!> same element forces in the same order as the serial scatter (per node: sets in order, the
!> colours of a set in order, within a colour the one range that touches the node, its
!> elements in order): the serial bits. The owners' nodal forces are then copied to every rank
!> (one MPI_Allgatherv of values), so that every rank holds the serial internal force at every
!> node.
!>
!> The element sums keep the serial order too: the strain, hourglass and plastic energies of a
!> block are formed by the block's owner (the owner of its first element) as the serial kernel
!> forms them (one lane_sum per block), copied to every rank, and folded there in the serial
!> order: blocks of a range in order from +0, ranges of a set in order from +0, sets in order.
!> The stable step is the smallest squared estimate with the first element in the serial order
!> among equal ones (per set, then sqrt, then sets in order, as set_forces and internal_forces
!> do); the first inverted and the first folded element likewise: exact reductions.
module exic_explicit_decomposition
   use exic_base_kinds, only: wp
   use, intrinsic :: iso_fortran_env, only: int64
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_base_threads, only: threaded
   use exic_material_material, only: MAT_SOLID
   use exic_element_quad4, only: q4_force_2x2, q4_force_1pt, NBLOCK
   use exic_element_q4_general, only: q4g_force
   use exic_element_q4_bulk_viscosity, only: q4_bulk_viscosity
   use exic_base_clock, only: wall_time
   use exic_explicit_central, only: CHUNK
   use exic_parallel_mpi, only: par_rank, par_size, par_allgatherv, par_allgather_int
   use exic_parallel_partition, only: partition_mesh, node_owners
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_assembly, only: force_result_t, forces_open, set_damping, forces_close
   implicit none
   private

   public :: decomposition_t, element_weights, decomposition_init, decomposition_forces, decomposition_summary

   !> Relative cost of an element in the force pass (METIS vertex weights): one point 3, 2x2 5
   !> (48.3 and 28.7 M element-steps/s, doc/performance.md), the general path (axisymmetric,
   !> plastic, mixed) 10, rigid elements (no force pass) 1.
   integer, parameter, public :: COST_1PT = 3, COST_2X2 = 5, COST_GENERAL = 10, COST_RIGID = 1

   !> Smallest set whose blocks run on several threads (as assembly's PAR_MIN_ELEMENTS).
   integer, parameter :: PAR_MIN_ELEMENTS = 2048

   !> The blocks one rank computes in one set, by range.
   type :: set_blocks_t
      integer, allocatable :: rfirst(:)   !< (nrange + 1) first entry of range r in e0, gid, slot
      integer, allocatable :: e0(:)       !< first element (local to the set) of the block
      integer, allocatable :: gid(:)      !< global block number
      integer, allocatable :: slot(:)     !< position in the rank's owned blocks, 0: not owned
      !> divided nodes: (nrange) position of range r in the rank's owned ranges, 0: not owned
      integer, allocatable :: rslot(:)
   end type set_blocks_t

   !> One rank's part of the decomposition.
   type :: decomposition_t
      logical :: active = .false.         !< several ranks
      integer :: rank = 0, nrank = 1
      integer :: nset = 0
      integer :: nblock = 0               !< blocks of every set (global)
      integer :: cut = 0                  !< METIS: edges of the dual graph between parts
      integer, allocatable :: elem_owner(:)   !< (nelem) owner of each element
      integer, allocatable :: node_owner(:)   !< (nnode) owner of each node
      integer, allocatable :: block_owner(:)  !< (nblock)
      integer, allocatable :: set_block(:)    !< (nset + 1) first global block of each set
      integer, allocatable :: set_elem(:)     !< (nset + 1) ordinal offset of each set (0-based)
      type(set_blocks_t), allocatable :: sb(:)
      integer :: ncomputed = 0            !< blocks this rank computes
      integer :: nowned = 0               !< blocks this rank owns
      integer, allocatable :: mine(:)         !< nodes this rank owns, ascending
      integer, allocatable :: node_order(:)   !< (nnode) nodes by owner, ascending in each
      integer, allocatable :: node_counts(:)  !< (nrank) 2 x nodes owned
      integer, allocatable :: block_order(:)  !< (nblock) blocks by owner, ascending in each
      integer, allocatable :: rec_counts(:)   !< (nrank) values each rank sends of its blocks
      real(wp), allocatable :: fsend(:), frecv(:), bsend(:), brecv(:)
      real(wp), allocatable :: bval(:, :)     !< (3, nunit) w, whg, wd of every block (range)
      ! the nodal state divided (doc/parallel.md, "Divided nodes"): steps without contact, loads
      ! or masses per dof, decks without VISCosity BULK and DAMPing MASS
      logical :: nodes = .false.
      logical :: whole = .true.               !< every rank holds the whole nodal state now
      integer :: nunit = 0                    !< units of the energy sums: blocks, or ranges (nodes)
      integer, allocatable :: set_range(:)    !< (nset + 1) first global range of each set
      integer, allocatable :: cbound(:)       !< (nrank + 1) rank r owns chunks cbound(r+1) .. cbound(r+2)-1
      integer :: c1 = 1, c2 = 0               !< this rank's chunks
      integer :: n1 = 1, n2 = 0               !< this rank's nodes
      integer, allocatable :: ghost(:)        !< nodes of its computed blocks that others own
      integer, allocatable :: nb(:)           !< neighbours (ranks it sends to or receives from)
      integer, allocatable :: sfirst(:), snodes(:)   !< nodes sent to nb(k): snodes(sfirst(k):sfirst(k+1)-1)
      integer, allocatable :: rfirst(:), rnodes(:)   !< nodes received from nb(k)
      real(wp), allocatable :: sbuf(:), rbuf(:)
      integer, allocatable :: pcounts(:), pdispls(:), ncounts(:), ndispls(:)
      real(wp), allocatable :: pall(:, :)     !< (5, nchunk) the chunks' sums (cd_update_plain_chunks)
      integer :: redundant = 0                !< blocks computed by more than one rank (sum over ranks - all)
      ! wall time of the divided steps on this rank (seconds) and their count
      real(wp) :: t_elements = 0.0_wp, t_exchange = 0.0_wp, t_nodal = 0.0_wp
      integer :: nsteps = 0
   end type decomposition_t

   !> Values per rank after its blocks' energies: per set the smallest squared step, its
   !> ordinal and the smallest bulk-viscosity step ratio (1 without); jmin, the first inverted
   !> and the first folded ordinal.
   integer, parameter :: PER_SET = 3, TAIL = 3

contains

   !> METIS weights of the elements of `sets` (element_weights(e) for global element e).
   subroutine element_weights(nelem, sets, weight)
      integer, intent(in) :: nelem
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(out) :: weight(nelem)
      integer :: k, c
      weight = COST_RIGID
      do k = 1, size(sets)
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            c = merge(COST_2X2, COST_1PT, s%nq == 2)
            if (s%general) c = COST_GENERAL
            weight(s%elems) = c
         end associate
      end do
   end subroutine element_weights

   !> The decomposition of the sets' elements over every rank (same result on every rank);
   !> inactive (nothing done) on one rank.
   !> divide: the steps will all be plain (no contact, loads or masses per dof) and the deck has
   !> no VISCosity BULK or DAMPing MASS: the nodal state is divided in chunk ranges (node
   !> owners) and the energy sums come per range of elements (doc/parallel.md, "Divided nodes");
   !> else METIS parts of the blocks and the replicated nodal state.
   subroutine decomposition_init(self, st, sets, conn, divide, err)
      type(decomposition_t), intent(out) :: self
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: conn(:, :)
      logical, intent(in) :: divide
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: weight(:), every(:), first(:)
      logical, allocatable :: mark(:)
      integer :: k, r, e0, nb, j, a, g, ne, n, p, nown, ncomp, i
      logical :: take

      self%rank = par_rank()
      self%nrank = par_size()
      self%active = self%nrank > 1
      self%nset = size(sets)
      if (.not. self%active) return
      ne = st%nelem
      allocate (weight(ne), self%elem_owner(ne), self%node_owner(st%nnode))
      call element_weights(ne, sets, weight)

      ! global blocks: per solid set, blocks of NBLOCK from the start of each range
      self%nodes = divide
      allocate (self%set_block(self%nset + 1), self%set_elem(self%nset + 1), self%sb(self%nset), &
                self%set_range(self%nset + 1))
      self%set_block(1) = 1
      self%set_elem(1) = 0
      self%set_range(1) = 1
      do k = 1, self%nset
         associate (s => sets(k))
            nb = 0
            if (s%kind == MAT_SOLID) then
               do r = 1, s%nrange
                  if (mod(s%rfirst(r) - 1, NBLOCK) /= 0) then
                     call make_error(err, 'element set '//itoa(k)//': range '//itoa(r)//' does not start '// &
                                     'on a block of '//itoa(NBLOCK)//' elements')
                     return
                  end if
               end do
               nb = (s%nel + NBLOCK - 1)/NBLOCK
            end if
            self%set_block(k + 1) = self%set_block(k) + nb
            self%set_elem(k + 1) = self%set_elem(k) + s%nel
            self%set_range(k + 1) = self%set_range(k) + merge(s%nrange, 0, s%kind == MAT_SOLID)
         end associate
      end do
      if (self%nodes) then
         call chunk_owners(self, st%nnode, sets, weight)
      else
         call partition_blocks(self, st%nnode, sets, weight, err)
         if (allocated(err)) return
         call node_owners(ne, st%nnode, conn, self%elem_owner, self%node_owner)
      end if
      allocate (mark(st%nnode))
      mark = self%node_owner == self%rank
      ncomp = 0
      nown = 0
      do k = 1, self%nset
         associate (s => sets(k), b => self%sb(k))
            allocate (b%rfirst(max(s%nrange, 0) + 1))
            b%rfirst(1) = 1
            allocate (b%e0(0), b%gid(0), b%slot(0), b%rslot(max(s%nrange, 0)))
            b%rslot = 0
            if (s%kind /= MAT_SOLID) then
               b%rfirst = 1
               cycle
            end if
            do r = 1, s%nrange
               if (self%nodes) then
                  ! whole ranges: the rank's ranges with an element at a node it owns; it owns
                  ! those whose first element's first node it owns
                  take = .false.
                  do j = s%rfirst(r), s%rfirst(r + 1) - 1
                     if (any(mark(s%conn(:, j)))) take = .true.
                  end do
                  if (take) then
                     do e0 = s%rfirst(r), s%rfirst(r + 1) - 1, NBLOCK
                        b%e0 = [b%e0, e0]
                        b%gid = [b%gid, self%set_block(k) + (e0 - 1)/NBLOCK]
                        b%slot = [b%slot, merge(1, 0, mark(s%conn(1, s%rfirst(r))))]
                        ncomp = ncomp + 1
                     end do
                     if (mark(s%conn(1, s%rfirst(r)))) then
                        nown = nown + 1
                        b%rslot(r) = nown
                     end if
                  end if
                  b%rfirst(r + 1) = size(b%e0) + 1
                  cycle
               end if
               do e0 = s%rfirst(r), s%rfirst(r + 1) - 1, NBLOCK
                  nb = min(NBLOCK, s%rfirst(r + 1) - e0)
                  g = self%set_block(k) + (e0 - 1)/NBLOCK
                  take = .false.
                  do j = e0, e0 + nb - 1
                     if (self%elem_owner(s%elems(j)) == self%rank) take = .true.
                     do a = 1, 4
                        if (mark(s%conn(a, j))) take = .true.
                     end do
                  end do
                  if (.not. take) cycle
                  b%e0 = [b%e0, e0]
                  b%gid = [b%gid, g]
                  if (self%block_owner(g) == self%rank) then
                     nown = nown + 1
                     b%slot = [b%slot, nown]
                  else
                     b%slot = [b%slot, 0]
                  end if
                  ncomp = ncomp + 1
               end do
               b%rfirst(r + 1) = size(b%e0) + 1
            end do
         end associate
      end do
      self%ncomputed = ncomp
      self%nowned = nown

      ! nodes by owner (each rank's ascending), and blocks by owner
      self%mine = pack([(n, n=1, st%nnode)], mark)
      allocate (self%node_counts(self%nrank), self%rec_counts(self%nrank), every(self%nrank))
      call par_allgather_int(size(self%mine), every)
      self%node_counts = 2*every
      allocate (self%node_order(st%nnode), first(self%nrank + 1))
      call by_owner(st%nnode, self%node_owner, self%nrank, self%node_order)
      call par_allgather_int(nown, every)
      self%rec_counts = 3*every + PER_SET*self%nset + TAIL
      if (self%nodes) then
         self%nunit = self%set_range(self%nset + 1) - 1
      else
         self%nunit = self%nblock
      end if
      allocate (self%block_order(self%nunit))
      call by_owner(self%nunit, self%block_owner, self%nrank, self%block_order)
      do i = 1, self%nrank
         if (count(self%block_owner == i - 1) /= every(i)) then
            call make_error(err, 'decomposition: rank '//itoa(i - 1)//' computes '//itoa(every(i))// &
                            ' of the blocks it owns, not '//itoa(count(self%block_owner == i - 1)))
            return
         end if
      end do
      p = sum(self%rec_counts)
      if (.not. self%nodes) allocate (self%fsend(2*size(self%mine)), self%frecv(2*st%nnode))
      allocate (self%bsend(self%rec_counts(self%rank + 1)), self%brecv(p), self%bval(3, self%nunit))
      call par_allgather_int(ncomp, every)
      self%redundant = sum(every) - self%nblock
   end subroutine decomposition_init

   !> The blocks of every solid set as the parts' units (doc/parallel.md, "Partition"): METIS's
   !> parts of the mesh whose elements are the blocks (each with its distinct nodes, weighted by
   !> its elements' cost), in min(nrank, nblock) parts; every element takes its block's owner
   !> (the elements of rigid sets, which have no block, huge: they own no node).
   subroutine partition_blocks(self, nnode, sets, weight, err)
      type(decomposition_t), intent(inout) :: self
      integer, intent(in) :: nnode
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: weight(:)
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: eptr(:), eind(:), bw(:), seen(:)
      integer :: k, g, e0, j, a, n, nb
      self%nblock = self%set_block(self%nset + 1) - 1
      allocate (self%block_owner(self%nblock), eptr(self%nblock + 1), eind(4*NBLOCK*self%nblock), &
                bw(self%nblock), seen(nnode))
      seen = 0
      eptr(1) = 0
      n = 0
      do k = 1, self%nset
         associate (s => sets(k))
            do g = self%set_block(k), self%set_block(k + 1) - 1
               e0 = 1 + (g - self%set_block(k))*NBLOCK
               nb = min(NBLOCK, s%nel - e0 + 1)
               bw(g) = sum(weight(s%elems(e0:e0 + nb - 1)))
               do j = e0, e0 + nb - 1
                  do a = 1, 4
                     if (seen(s%conn(a, j)) == g) cycle
                     seen(s%conn(a, j)) = g
                     n = n + 1
                     eind(n) = s%conn(a, j)
                  end do
               end do
               eptr(g + 1) = n
            end do
         end associate
      end do
      call partition_mesh(self%nblock, nnode, eptr, eind(1:n), bw, min(self%nrank, self%nblock), &
                          self%block_owner, self%cut, err)
      if (allocated(err)) return
      self%elem_owner = huge(1)
      do k = 1, self%nset
         associate (s => sets(k))
            do g = self%set_block(k), self%set_block(k + 1) - 1
               e0 = 1 + (g - self%set_block(k))*NBLOCK
               nb = min(NBLOCK, s%nel - e0 + 1)
               self%elem_owner(s%elems(e0:e0 + nb - 1)) = self%block_owner(g)
            end do
         end associate
      end do
   end subroutine partition_blocks

   !> Divided nodes (doc/parallel.md): rank r owns the chunks cbound(r+1) .. cbound(r+2) - 1 of
   !> CHUNK consecutive nodes, the boundaries cutting the running sum of the elements' weights
   !> (each element counted at the chunk of its first node) into nrank nearly equal parts; a
   !> node's owner is its chunk's; a range of elements (the unit of the energy sums) is owned by
   !> the owner of its first element's first node, and so are its elements. The same on every
   !> rank (integers only).
   subroutine chunk_owners(self, nnode, sets, weight)
      type(decomposition_t), intent(inout) :: self
      integer, intent(in) :: nnode
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: weight(:)
      integer(int64), allocatable :: cw(:)
      integer(int64) :: total, run
      integer :: nchunk, k, j, c, r, q, g
      self%nblock = self%set_block(self%nset + 1) - 1
      nchunk = (nnode + CHUNK - 1)/CHUNK
      allocate (cw(nchunk), self%cbound(self%nrank + 1))
      cw = 0
      do k = 1, self%nset
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            do j = 1, s%nel
               c = (s%conn(1, j) - 1)/CHUNK + 1
               cw(c) = cw(c) + weight(s%elems(j))
            end do
         end associate
      end do
      ! a chunk of no element still costs its nodes' update
      cw = cw + 1
      total = sum(cw)
      self%cbound(1) = 1
      run = 0
      q = 1
      do c = 1, nchunk
         run = run + cw(c)
         ! rank q - 1 ends at the chunk where the running sum reaches q/nrank of the total
         do while (q < self%nrank .and. run*self%nrank >= total*q)
            q = q + 1
            self%cbound(q) = c + 1
         end do
      end do
      do r = q + 1, self%nrank + 1
         self%cbound(r) = nchunk + 1
      end do
      self%c1 = self%cbound(self%rank + 1)
      self%c2 = self%cbound(self%rank + 2) - 1
      self%n1 = (self%c1 - 1)*CHUNK + 1
      self%n2 = min(self%c2*CHUNK, nnode)
      do r = 1, self%nrank
         self%node_owner((self%cbound(r) - 1)*CHUNK + 1:min((self%cbound(r + 1) - 1)*CHUNK, nnode)) = r - 1
      end do
      allocate (self%block_owner(self%set_range(self%nset + 1) - 1))
      self%elem_owner = huge(1)
      do k = 1, self%nset
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            do r = 1, s%nrange
               g = self%set_range(k) + r - 1
               self%block_owner(g) = self%node_owner(s%conn(1, s%rfirst(r)))
               self%elem_owner(s%elems(s%rfirst(r):s%rfirst(r + 1) - 1)) = self%block_owner(g)
            end do
         end associate
      end do
   end subroutine chunk_owners

   !> One line for the report: ranks, the cut, elements and nodes per rank, this rank's blocks.
   function decomposition_summary(self) result(text)
      type(decomposition_t), intent(in) :: self
      character(len=:), allocatable :: text
      integer :: r
      if (self%nodes) then
         text = 'MPI: '//itoa(self%nrank)//' ranks; nodal state divided in chunks of '//itoa(CHUNK)// &
                ' nodes, chunks per rank'
         do r = 1, self%nrank
            text = text//' '//itoa(self%cbound(r + 1) - self%cbound(r))
         end do
         text = text//'; blocks computed again by another rank '//itoa(self%redundant)//' (of '// &
                itoa(self%nblock)//'); rank '//itoa(self%rank)//' has '//itoa(size(self%ghost))// &
                ' ghost nodes, '//itoa(size(self%nb))//' neighbours, sends '//itoa(8*size(self%sbuf))// &
                ' and receives '//itoa(8*size(self%rbuf))//' bytes of v and a a step; elements per rank'
      else
         text = 'MPI: '//itoa(self%nrank)//' ranks; METIS parts of the element blocks cut '//itoa(self%cut)// &
                ' block edges; elements '// &
                'per rank'
      end if
      do r = 0, self%nrank - 1
         text = text//' '//itoa(count(self%elem_owner == r))
      end do
      text = text//'; nodes per rank'
      do r = 0, self%nrank - 1
         text = text//' '//itoa(count(self%node_owner == r))
      end do
      text = text//'; rank '//itoa(self%rank)//' computes '//itoa(self%ncomputed)//' blocks of '// &
             itoa(self%nblock)//' and owns '//itoa(self%nowned)
   end function decomposition_summary

   !> order = 1 .. n by owner(i) (0 .. nrank - 1), ascending within each owner.
   pure subroutine by_owner(n, owner, nrank, order)
      integer, intent(in) :: n, nrank
      integer, intent(in) :: owner(n)
      integer, intent(out) :: order(n)
      integer :: pos(0:nrank), i
      pos = 0
      do i = 1, n
         pos(owner(i)) = pos(owner(i)) + 1
      end do
      pos(1:nrank) = pos(0:nrank - 1)
      pos(0) = 0
      do i = 1, nrank
         pos(i) = pos(i) + pos(i - 1)
      end do
      do i = 1, n
         pos(owner(i)) = pos(owner(i)) + 1
         order(pos(owner(i))) = i
      end do
   end subroutine by_owner

   !> internal_forces (explicit/assembly.f90) on P ranks: the same outputs to the bit (res, the
   !> forces, st%energy, st%jmin). With VISCosity BULK, the bulk-viscosity forces of the blocks
   !> are exchanged as the internal forces are (st%gbulk: the owners' values) and each set's
   !> step ratio is the smallest over the ranks (exact); the mass damping (DAMPing MASS) and the
   !> works of both are nodal and run on every rank on the replicated state (forces_open,
   !> set_damping, forces_close: the serial code).
   subroutine decomposition_forces(self, st, sets, res)
      type(decomposition_t), intent(inout) :: self
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(inout) :: sets(:)
      type(force_result_t), intent(out) :: res
      real(wp), allocatable :: bw(:, :), bj(:), bd(:), bq(:)
      integer, allocatable :: be(:), bm(:), bf(:)
      real(wp) :: d2(self%nset), q2(self%nset), jmin, w, whg, wd, pw, phg, pd, dset, wdamp, wbulk
      integer :: o2(self%nset), obad, ofold, k, i, r, q, base, p, g, orank, b1, b2
      integer :: ord
      real(wp) :: t0

      t0 = wall_time()
      if (self%nodes) then
         ! divided nodes (no bulk viscosity, no mass damping): the forces start from +0 at the
         ! nodes this rank's blocks touch, its own and its ghosts
         wdamp = 0.0_wp
         wbulk = 0.0_wp
         st%fint(:, self%n1:self%n2) = 0.0_wp
         st%fint(:, self%ghost) = 0.0_wp
      else
         call forces_open(st, wdamp, wbulk)
      end if
      ! this rank's blocks, set by set, colour by colour (the serial order at every node)
      d2 = huge(1.0_wp)
      o2 = huge(1)
      q2 = 1.0_wp
      obad = huge(1)
      ofold = huge(1)
      jmin = huge(1.0_wp)
      do k = 1, self%nset
         associate (s => sets(k), b => self%sb(k))
            if (s%kind /= MAT_SOLID .or. size(b%e0) == 0) cycle
            allocate (bw(3, size(b%e0)), bj(size(b%e0)), bd(size(b%e0)), bq(size(b%e0)), be(size(b%e0)), &
                      bm(size(b%e0)), bf(size(b%e0)))
            bq = 1.0_wp
            call set_blocks(sets(k), self%sb(k), st, bw, bj, bd, bq, be, bm, bf)
            ! the owned blocks' values, in ascending global block order (the order of b%gid)
            do q = 1, size(b%e0)
               if (b%slot(q) == 0) cycle
               if (.not. self%nodes) self%bsend(3*b%slot(q) - 2:3*b%slot(q)) = bw(:, q)
               jmin = min(jmin, bj(q))
               q2(k) = min(q2(k), bq(q))
               base = self%set_elem(k) + b%e0(q) - 1
               if (be(q) /= 0) obad = min(obad, base + be(q))
               if (bf(q) /= 0) ofold = min(ofold, base + bf(q))
               if (bm(q) /= 0) then
                  ord = base + bm(q)
                  if (bd(q) < d2(k) .or. (bd(q) == d2(k) .and. ord < o2(k))) then
                     d2(k) = bd(q)
                     o2(k) = ord
                  end if
               end if
            end do
            if (self%nodes) then
               ! an owned range's sums: its blocks in order from +0 (the fold below, done here)
               do r = 1, s%nrange
                  if (b%rslot(r) == 0) cycle
                  pw = 0.0_wp
                  phg = 0.0_wp
                  pd = 0.0_wp
                  do q = b%rfirst(r), b%rfirst(r + 1) - 1
                     pw = pw + bw(1, q)
                     phg = phg + bw(2, q)
                     pd = pd + bw(3, q)
                  end do
                  self%bsend(3*b%rslot(r) - 2:3*b%rslot(r)) = [pw, phg, pd]
               end do
            end if
            deallocate (bw, bj, bd, bq, be, bm, bf)
         end associate
      end do
      p = 3*self%nowned
      do k = 1, self%nset
         self%bsend(p + PER_SET*k - 2) = d2(k)
         self%bsend(p + PER_SET*k - 1) = real(o2(k), wp)
         self%bsend(p + PER_SET*k) = q2(k)
      end do
      p = p + PER_SET*self%nset
      self%bsend(p + 1) = jmin
      self%bsend(p + 2) = real(obad, wp)
      self%bsend(p + 3) = real(ofold, wp)

      ! the owners' nodal forces (and bulk-viscosity forces) to every rank; with divided nodes
      ! they stay where they are (each rank updates its own nodes)
      self%t_elements = self%t_elements + (wall_time() - t0)
      t0 = wall_time()
      if (.not. self%nodes) then
         call exchange_owned(self, st%nnode, st%fint)
         if (allocated(st%gbulk)) call exchange_owned(self, st%nnode, st%gbulk)
      end if
      call par_allgatherv(size(self%bsend), self%bsend, self%rec_counts, self%brecv)
      self%t_exchange = self%t_exchange + (wall_time() - t0)

      ! every block's energies in place; the ranks' step, ratio, jmin and first elements combined
      d2 = huge(1.0_wp)
      o2 = huge(1)
      q2 = 1.0_wp
      obad = huge(1)
      ofold = huge(1)
      jmin = huge(1.0_wp)
      p = 0
      q = 0
      do orank = 1, self%nrank
         do i = 1, (self%rec_counts(orank) - PER_SET*self%nset - TAIL)/3
            q = q + 1
            self%bval(:, self%block_order(q)) = self%brecv(p + 3*i - 2:p + 3*i)
         end do
         p = p + self%rec_counts(orank) - PER_SET*self%nset - TAIL
         do k = 1, self%nset
            pd = self%brecv(p + PER_SET*k - 2)
            ord = nint(self%brecv(p + PER_SET*k - 1))
            if (pd < d2(k) .or. (pd == d2(k) .and. ord < o2(k))) then
               d2(k) = pd
               o2(k) = ord
            end if
            q2(k) = min(q2(k), self%brecv(p + PER_SET*k))
         end do
         p = p + PER_SET*self%nset
         jmin = min(jmin, self%brecv(p + 1))
         obad = min(obad, nint(self%brecv(p + 2)))
         ofold = min(ofold, nint(self%brecv(p + 3)))
         p = p + TAIL
      end do

      ! fold in the serial order (internal_forces, set_forces, add_result, the kernels)
      do k = 1, self%nset
         associate (s => sets(k))
            if (s%kind /= MAT_SOLID) cycle
            w = 0.0_wp
            whg = 0.0_wp
            wd = 0.0_wp
            do r = 1, s%nrange
               if (self%nodes) then
                  g = self%set_range(k) + r - 1
                  pw = self%bval(1, g)
                  phg = self%bval(2, g)
                  pd = self%bval(3, g)
               else
                  b1 = self%set_block(k) + (s%rfirst(r) - 1)/NBLOCK
                  b2 = self%set_block(k) + (s%rfirst(r + 1) - 2)/NBLOCK
                  pw = 0.0_wp
                  phg = 0.0_wp
                  pd = 0.0_wp
                  do g = b1, b2
                     pw = pw + self%bval(1, g)
                     phg = phg + self%bval(2, g)
                     pd = pd + self%bval(3, g)
                  end do
               end if
               w = w + pw
               wd = wd + pd
               whg = whg + phg
            end do
            dset = sqrt(d2(k))
            if (s%bulk) dset = dset*q2(k)
            call set_damping(s, st, dset)
            st%energy%plastic = st%energy%plastic + wd
            res%strain = res%strain + w
            res%dissipation = res%dissipation + wd
            res%hourglass = res%hourglass + whg
            if (dset < res%dt) then
               res%dt = dset
               res%emin = element_of(o2(k))
            end if
         end associate
      end do
      res%jmin = jmin
      res%ebad = element_of(obad)
      res%efold = element_of(ofold)
      st%energy%strain = res%strain
      st%energy%hourglass = res%hourglass
      st%jmin = res%jmin
      call forces_close(st, wdamp, wbulk)
   contains
      !> The global element of an ordinal (0 for none).
      integer function element_of(o) result(e)
         integer, intent(in) :: o
         integer :: kk
         e = 0
         if (o == huge(1)) return
         do kk = 1, self%nset
            if (o <= self%set_elem(kk + 1)) then
               e = sets(kk)%elems(o - self%set_elem(kk))
               return
            end if
         end do
      end function element_of
   end subroutine decomposition_forces

   !> The owners' values of the nodal field f(2, nnode) copied to every rank (one MPI_Allgatherv
   !> of values, never summed): f is then, at every node, its owner's value.
   subroutine exchange_owned(self, nnode, f)
      type(decomposition_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(inout) :: f(2, nnode)
      integer :: i
      do i = 1, size(self%mine)
         self%fsend(2*i - 1:2*i) = f(:, self%mine(i))
      end do
      call par_allgatherv(size(self%fsend), self%fsend, self%node_counts, self%frecv)
      do i = 1, nnode
         f(:, self%node_order(i)) = self%frecv(2*i - 1:2*i)
      end do
   end subroutine exchange_owned

   !> The blocks this rank computes in set s: the ranges of each colour on the threads, one
   !> colour after the other (set_forces of explicit/assembly.f90).
   subroutine set_blocks(s, b, st, bw, bj, bd, bq, be, bm, bf)
      type(element_set_t), intent(inout) :: s
      type(set_blocks_t), intent(in) :: b
      type(state_t), intent(inout) :: st
      real(wp), intent(inout) :: bw(:, :), bj(:), bd(:), bq(:)
      integer, intent(inout) :: be(:), bm(:), bf(:)
      integer :: c, i
      if (threaded(s%nel, PAR_MIN_ELEMENTS)) then
         !$omp parallel default(none) private(c, i) shared(s, b, st, bw, bj, bd, bq, be, bm, bf)
         do c = 1, s%ncolour
            !$omp do schedule(dynamic)
            do i = s%cfirst(c), s%cfirst(c + 1) - 1
               call range_blocks(s, b, s%cranges(i), st, bw, bj, bd, bq, be, bm, bf)
            end do
            !$omp end do
         end do
         !$omp end parallel
      else
         do c = 1, s%ncolour
            do i = s%cfirst(c), s%cfirst(c + 1) - 1
               call range_blocks(s, b, s%cranges(i), st, bw, bj, bd, bq, be, bm, bf)
            end do
         end do
      end if
   end subroutine set_blocks

   !> The blocks this rank computes in range r of set s, each by one kernel call (one block:
   !> the serial kernel's block, with its lane sums and scatter in the same order; set_forces's
   !> range_forces); with VISCosity BULK the block's viscous forces into st%gbulk and its step
   !> ratio bq.
   subroutine range_blocks(s, b, r, st, bw, bj, bd, bq, be, bm, bf)
      type(element_set_t), intent(inout) :: s
      type(set_blocks_t), intent(in) :: b
      integer, intent(in) :: r
      type(state_t), intent(inout) :: st
      real(wp), intent(inout) :: bw(:, :), bj(:), bd(:), bq(:)
      integer, intent(inout) :: be(:), bm(:), bf(:)
      integer :: q, e0, n
      do q = b%rfirst(r), b%rfirst(r + 1) - 1
         e0 = b%e0(q)
         n = min(NBLOCK, s%rfirst(r + 1) - e0)
         if (s%general) then
            if (s%solid%nvar > 0) then
               call q4g_force(s%solid, n, st%nnode, s%conn(:, e0:e0 + n - 1), st%x0, st%u, st%dt_prev, &
                              s%hist(:, :, e0:e0 + n - 1), st%fint, bw(1, q), bw(2, q), bw(3, q), bj(q), be(q), &
                              bd(q), bm(q), bf(q), st%v)
            else
               call q4g_force(s%solid, n, st%nnode, s%conn(:, e0:e0 + n - 1), st%x0, st%u, st%dt_prev, s%hist, &
                              st%fint, bw(1, q), bw(2, q), bw(3, q), bj(q), be(q), bd(q), bm(q), bf(q), st%v)
            end if
         else if (s%nq == 2) then
            call q4_force_2x2(n, st%nnode, s%conn(:, e0:e0 + n - 1), st%x0, st%u, s%law, &
                              st%fint, bw(1, q), bj(q), be(q), bd(q), bm(q), bf(q))
            bw(2:3, q) = 0.0_wp
         else
            call q4_force_1pt(n, st%nnode, s%conn(:, e0:e0 + n - 1), st%x0, st%u, s%law, &
                              s%hourglass, st%fint, bw(1, q), bw(2, q), bj(q), be(q), bd(q), bm(q), bf(q), &
                              s%hgkind, st%v)
            bw(3, q) = 0.0_wp
         end if
         if (s%bulk) call q4_bulk_viscosity(n, st%nnode, s%conn(:, e0:e0 + n - 1), st%x0, st%u, st%v, st%a, &
                                            st%dt_prev, s%rho, s%wave, s%q1, s%q2, s%bulk_axi, st%gbulk, bq(q))
      end do
   end subroutine range_blocks

end module exic_explicit_decomposition
