!> The nodal part of a plain step (no contact, loads or masses per dof) on P ranks with the
!> nodal state divided (doc/parallel.md, "Divided nodes"). Rank r owns the nodes of a range of
!> whole chunks of CHUNK nodes (decomposition_t%cbound) and updates them with the serial chunk
!> kernels (cd_update_plain_chunks); the chunks' sums (5 values each) are copied to every rank
!> and folded there in chunk order (cd_plain_fold), which is the serial fold of cd_update_plain:
!> the serial bits of the work of the external forces, the kinetic energy, the momentum and Q.
!> After the update each rank sends v and a of its nodes that are ghosts of another rank (the
!> nodes of that rank's element blocks) to that rank, point to point (values copied); step 1
!> of the next step then forms u at its own and ghost nodes with the serial arithmetic, so
!> every rank holds the owner's bits wherever its element blocks read. What reads the whole
!> state (outputs, restart files, commands between steps) calls decomposition_gather_nodes
!> first.
module exic_explicit_decomposition_nodes
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa, rtoa
   use exic_base_clock, only: wall_time
   use exic_parallel_mpi, only: par_allgatherv_in_place, par_alltoallv_int, par_neighbour_exchange
   use exic_explicit_state, only: state_t, element_set_t
   use exic_explicit_central, only: CHUNK, cd_displacement_plain, cd_displacement_plain_at, &
                                    cd_update_plain_chunks, cd_plain_fold
   use exic_explicit_decomposition, only: decomposition_t
   use exic_element_quad4, only: NBLOCK
   implicit none
   private

   public :: nodes_init, nodes_displacement, nodes_update, decomposition_gather_nodes, decomposition_timing

contains

   !> The ghost nodes of this rank (the nodes of the element blocks it computes that another
   !> rank owns), the nodes it sends to each neighbour (its own nodes that are ghosts there:
   !> the lists are exchanged once, MPI_Alltoallv), and the counts of the exchanges.
   subroutine nodes_init(dd, st, sets, err)
      type(decomposition_t), intent(inout) :: dd
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(error_t), allocatable, intent(out) :: err
      logical, allocatable :: seen(:)
      integer, allocatable :: want(:), wcount(:), got(:), gcount(:)
      integer :: k, q, e0, n, j, a, i, r, ng, nchunk
      allocate (seen(st%nnode))
      seen = .false.
      do k = 1, size(sets)
         associate (s => sets(k), b => dd%sb(k))
            ! a block ends at NBLOCK elements or at the end of its range (range_blocks)
            do r = 1, size(b%rfirst) - 1
               do q = b%rfirst(r), b%rfirst(r + 1) - 1
                  e0 = b%e0(q)
                  do j = e0, min(e0 + NBLOCK - 1, s%rfirst(r + 1) - 1)
                     do a = 1, 4
                        seen(s%conn(a, j)) = .true.
                     end do
                  end do
               end do
            end do
         end associate
      end do
      seen(dd%n1:dd%n2) = .false.
      dd%ghost = pack([(i, i=1, st%nnode)], seen)
      ng = size(dd%ghost)
      ! ghosts by owner (ascending nodes within each: node order is owner order)
      allocate (wcount(dd%nrank))
      wcount = 0
      do i = 1, ng
         r = dd%node_owner(dd%ghost(i))
         if (r == dd%rank) then
            call make_error(err, 'decomposition: ghost node '//itoa(dd%ghost(i))//' is owned by this rank')
            return
         end if
         wcount(r + 1) = wcount(r + 1) + 1
      end do
      want = dd%ghost
      allocate (gcount(dd%nrank))
      call par_alltoallv_int(want, wcount, got, gcount)
      ! neighbours: ranks this one receives from or sends to, ascending
      n = count(wcount > 0 .or. gcount > 0)
      allocate (dd%nb(n), dd%sfirst(n + 1), dd%rfirst(n + 1))
      n = 0
      dd%sfirst(1) = 1
      dd%rfirst(1) = 1
      do r = 1, dd%nrank
         if (.not. (wcount(r) > 0 .or. gcount(r) > 0)) cycle
         n = n + 1
         dd%nb(n) = r - 1
         dd%sfirst(n + 1) = dd%sfirst(n) + 4*gcount(r)
         dd%rfirst(n + 1) = dd%rfirst(n) + 4*wcount(r)
      end do
      dd%snodes = got
      dd%rnodes = want
      do i = 1, size(got)
         if (got(i) < dd%n1 .or. got(i) > dd%n2) then
            call make_error(err, 'decomposition: rank '//itoa(dd%rank)//' was asked for node '//itoa(got(i))// &
                            ', which it does not own')
            return
         end if
      end do
      allocate (dd%sbuf(4*size(got)), dd%rbuf(4*ng))
      ! the chunks' sums (5 a chunk) and the nodal arrays (2 a node) of every rank
      nchunk = (st%nnode + CHUNK - 1)/CHUNK
      allocate (dd%pall(5, nchunk), dd%pcounts(dd%nrank), dd%pdispls(dd%nrank), dd%ncounts(dd%nrank), &
                dd%ndispls(dd%nrank))
      do r = 1, dd%nrank
         dd%pcounts(r) = 5*(dd%cbound(r + 1) - dd%cbound(r))
         dd%pdispls(r) = 5*(dd%cbound(r) - 1)
         dd%ndispls(r) = 2*min((dd%cbound(r) - 1)*CHUNK, st%nnode)
         dd%ncounts(r) = 2*min((dd%cbound(r + 1) - 1)*CHUNK, st%nnode) - dd%ndispls(r)
      end do
      dd%whole = .true.
   end subroutine nodes_init

   !> Step 1 at this rank's nodes and ghosts: u = u + (dt v + dt^2/2 a), cd_displacement_plain's
   !> operations on the values the element pass reads.
   subroutine nodes_displacement(dd, st)
      type(decomposition_t), intent(inout) :: dd
      type(state_t), intent(inout) :: st
      real(wp) :: t0
      t0 = wall_time()
      dd%whole = .false.
      if (dd%n2 >= dd%n1) call cd_displacement_plain(dd%n2 - dd%n1 + 1, st%dt, st%v(1, dd%n1), st%a(1, dd%n1), &
                                                     st%u(1, dd%n1))
      call cd_displacement_plain_at(st%nnode, st%dt, st%v, st%a, dd%ghost, st%u)
      dd%t_nodal = dd%t_nodal + (wall_time() - t0)
   end subroutine nodes_displacement

   !> Steps 4, 6 and 7 (cd_update_plain) at this rank's chunks; every chunk's sums to every rank
   !> (MPI_Allgatherv of values) folded in chunk order: st%energy%wext, kinetic, momentum and
   !> qnodes (Q of eq. E.3 at the new state), the serial bits on every rank; then v and a of
   !> this rank's nodes to the ranks that hold them as ghosts.
   subroutine nodes_update(dd, st, qnodes)
      type(decomposition_t), intent(inout) :: dd
      type(state_t), intent(inout) :: st
      real(wp), intent(out) :: qnodes
      real(wp) :: t0, t1
      integer :: i, j
      t0 = wall_time()
      if (dd%c2 >= dd%c1) call cd_update_plain_chunks(st%nnode, dd%c1, dd%c2, st%dt_prev, st%minv, st%fext, &
                                                      st%fext_zero, st%fint, st%mass, st%a, st%v, &
                                                      dd%pall(1, dd%c1))
      t1 = wall_time()
      call par_allgatherv_in_place(size(dd%pall), dd%pall, dd%pcounts, dd%pdispls)
      dd%t_exchange = dd%t_exchange + (wall_time() - t1)
      call cd_plain_fold(size(dd%pall, 2), dd%pall, st%energy%wext, st%energy%kinetic, st%momentum, qnodes)
      st%power_nodes = qnodes
      st%power_known = .true.
      ! v and a of the owned nodes that are ghosts elsewhere
      do i = 1, size(dd%snodes)
         j = dd%snodes(i)
         dd%sbuf(4*i - 3:4*i) = [st%v(1, j), st%v(2, j), st%a(1, j), st%a(2, j)]
      end do
      t1 = wall_time()
      dd%t_nodal = dd%t_nodal + (t1 - t0)
      call par_neighbour_exchange(dd%nb, dd%sfirst, dd%sbuf, dd%rfirst, dd%rbuf)
      t0 = wall_time()
      dd%t_exchange = dd%t_exchange + (t0 - t1)
      do i = 1, size(dd%rnodes)
         j = dd%rnodes(i)
         st%v(:, j) = dd%rbuf(4*i - 3:4*i - 2)
         st%a(:, j) = dd%rbuf(4*i - 1:4*i)
      end do
      dd%nsteps = dd%nsteps + 1
      dd%t_nodal = dd%t_nodal + (wall_time() - t0)
   end subroutine nodes_update

   !> The whole nodal state on every rank (u, v, a and the internal force of every node from
   !> its owner: MPI_Allgatherv of values, in place), when it is divided; before anything that
   !> reads nodes other than a rank's own (outputs, restart files, commands between steps, the
   !> end of the run). Nothing when the state is whole already or not divided.
   subroutine decomposition_gather_nodes(dd, st)
      type(decomposition_t), intent(inout) :: dd
      type(state_t), intent(inout) :: st
      if (.not. dd%nodes .or. dd%whole) return
      call par_allgatherv_in_place(size(st%u), st%u, dd%ncounts, dd%ndispls)
      call par_allgatherv_in_place(size(st%v), st%v, dd%ncounts, dd%ndispls)
      call par_allgatherv_in_place(size(st%a), st%a, dd%ncounts, dd%ndispls)
      call par_allgatherv_in_place(size(st%fint), st%fint, dd%ncounts, dd%ndispls)
      dd%whole = .true.
   end subroutine decomposition_gather_nodes

   !> One line for the report of a run whose nodal state was divided: this rank's wall time in
   !> the element pass, the exchanges and the nodal update of its divided steps, and what it
   !> receives and sends a step (bytes, messages); empty otherwise.
   function decomposition_timing(dd) result(text)
      type(decomposition_t), intent(in) :: dd
      character(len=:), allocatable :: text
      integer :: recv_bytes, send_bytes, nmsg
      text = ''
      if (.not. dd%nodes .or. dd%nsteps == 0) return
      ! the ghosts' v and a (point to point), the chunks' sums and the ranges' sums (MPI_Allgatherv)
      recv_bytes = 8*size(dd%rbuf) + 8*(size(dd%pall) - dd%pcounts(dd%rank + 1)) + &
                   8*(sum(dd%rec_counts) - dd%rec_counts(dd%rank + 1))
      send_bytes = 8*size(dd%sbuf) + 8*dd%pcounts(dd%rank + 1) + 8*dd%rec_counts(dd%rank + 1)
      nmsg = count(dd%sfirst(2:) > dd%sfirst(:size(dd%sfirst) - 1)) + &
             count(dd%rfirst(2:) > dd%rfirst(:size(dd%rfirst) - 1))
      text = 'MPI rank '//itoa(dd%rank)//', '//itoa(dd%nsteps)//' divided steps: elements '//rtoa(dd%t_elements)// &
             ' s, exchanges '//rtoa(dd%t_exchange)//' s, nodal update '//rtoa(dd%t_nodal)//' s; a step receives '// &
             itoa(recv_bytes)//' bytes and sends '//itoa(send_bytes)//' ('//itoa(nmsg)// &
             ' point-to-point messages and 2 MPI_Allgatherv)'
   end function decomposition_timing

end module exic_explicit_decomposition_nodes
