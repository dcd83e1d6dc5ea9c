!> The narrow phase of the Lagrange passes of a step, on the threads when there is enough of it
!> (doc/decisions.md, "Threads": the contact step).
!>
!> Every pass fills its own hits from its own candidates; what passes share is the state of
!> their surfaces: the node normals sl%nrm of a slave surface (with sl%nrm_stamp), and the
!> segment-normal cache sn, sn_stamp of a surface, which detect_pairs fills when the surface is
!> the pass's master (its candidate segments) and when it is the slave (the segments at a slave
!> with a hit). The work is therefore done in three sweeps, each over independent items:
!>
!>  1. per pass: its candidates (the kept broad-phase list of a PAIR pass, the flat immovable
!>     slaves dropped from an AUTOmatic one); each pass writes its own broad phase only;
!>  2. per master surface: the normals of every candidate segment of its swept passes (slave
!>     and master surfaces differ), formed into its cache with the operations detect_pairs
!>     uses (candidate_normals); each surface's cache is written by one task;
!>  3. per slave surface: its passes in pass order, each detect_contacts as before. A task
!>     writes only the node normals and the segment cache of its own slave surface, and of
!>     those only entries that sweep 2 did not form (a candidate segment of another task is
!>     formed already: detect_pairs only reads it).
!>
!> Every value is formed by the same operations on the same positions as in one sweep over the
!> passes, and each pass's hits come from its own candidates in their order, so the hits are the
!> same bits for any number of threads and any schedule. The constraints are then added in pass
!> order by the caller, as before.
submodule(exic_contact_contact) exic_contact_narrow
   use exic_base_threads, only: threaded
   use exic_contact_detect, only: candidate_normals
   implicit none

   !> Candidates (over the passes) from which the narrow phase is worth a parallel region: about
   !> 0.1 microsecond each against a few microseconds for the region (doc/performance.md 6.3).
   integer, parameter :: NARROW_MIN = 1000

contains

   !> The narrow phase of the Lagrange passes k1 ... k2 (penalty passes are left alone): their
   !> candidates and hits (ps%broad, ps%hits) at x(n+1) -> self%xp over the step.
   module procedure narrow_passes
      integer, allocatable :: sfirst(:), slist(:), mfirst(:), mlist(:)
      integer :: k, g, work, ns, nm

      work = 0
      do k = k1, k2
         if (self%passes(k)%method == METHOD_LAGRANGE) work = work + self%passes(k)%broad%ncand
      end do
      ns = 0
      if (threaded(work, NARROW_MIN)) then
         ! the passes of each slave surface, and the swept ones of each master surface
         call by_surface(self, k1, k2, .true., ns, sfirst, slist)
         call by_surface(self, k1, k2, .false., nm, mfirst, mlist)
      end if
      if (ns > 1) then
         self%nthreaded = self%nthreaded + 1
         !$omp parallel default(shared) private(k, g)
         !$omp do schedule(dynamic)
         do k = k1, k2
            call candidates(self, k, nnode, x, minv)
         end do
         !$omp end do
         !$omp do schedule(dynamic)
         do g = 1, nm
            call master_normals(self, mlist(mfirst(g):mfirst(g + 1) - 1), nnode, x)
         end do
         !$omp end do
         !$omp do schedule(dynamic)
         do g = 1, ns
            call slave_passes(self, slist(sfirst(g):sfirst(g + 1) - 1), nnode, x)
         end do
         !$omp end do
         !$omp end parallel
      else
         ! one thread: pass after pass, each detection forming the normals it needs as it goes
         ! (the same values: sweeps 2 and 3 only split that work between tasks)
         do k = k1, k2
            call candidates(self, k, nnode, x, minv)
            if (self%passes(k)%method == METHOD_LAGRANGE) call slave_passes(self, [k], nnode, x)
         end do
      end if
   end procedure narrow_passes

   !> The Lagrange passes among k1 ... k2 grouped by their slave surface (`slave`), or the swept
   !> ones whose slave is not their master grouped by master surface: n groups, group g the
   !> passes list(first(g):first(g + 1) - 1) in pass order, groups in order of their surfaces
   !> (mesh/boundary's bodies_elements, which groups any numbers the same way).
   subroutine by_surface(self, k1, k2, slave, n, first, list)
      type(contact_t), intent(in) :: self
      integer, intent(in) :: k1, k2
      logical, intent(in) :: slave
      integer, intent(out) :: n
      integer, allocatable, intent(out) :: first(:), list(:)
      integer :: surf(k2 - k1 + 1), pass(k2 - k1 + 1)
      integer, allocatable :: ids(:), members(:)
      integer :: k, m

      m = 0
      do k = k1, k2
         associate (ps => self%passes(k))
            if (ps%method /= METHOD_LAGRANGE) cycle
            if (.not. slave .and. (ps%detection /= DETECT_SWEPT .or. ps%slave == ps%master)) cycle
            m = m + 1
            surf(m) = merge(ps%slave, ps%master, slave)
            pass(m) = k
         end associate
      end do
      call bodies_elements(m, surf(1:m), ids, first, members)
      list = pass(members)
      n = size(ids)
   end subroutine by_surface

   !> Sweep 1: the candidates of Lagrange pass k (its own broad phase).
   subroutine candidates(self, k, nnode, x, minv)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: k, nnode
      real(wp), intent(in) :: x(2, nnode), minv(2, nnode)
      associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                 ms => self%surfaces(self%passes(k)%master))
         if (ps%method /= METHOD_LAGRANGE) return
         if (.not. ps%auto) call broad_search_kept(ps%broad, nnode, x, self%xp, sl%nnode, sl%nodes, &
                                                   ms%nseg, ms%seg, self%depth)
         if (ps%auto) call drop_flat_fixed(ps%broad, nnode, x, minv, sl%nnode, sl%nodes, sl%seg, sl%nhead, &
                                           sl%nsegs)
         if (ps%corners) call keep_convex_corners(ps%broad, nnode, x, sl%nnode, sl%nodes, sl%seg, sl%nhead, &
                                                  sl%nsegs)
      end associate
   end subroutine candidates

   !> Sweep 2: the segment normals of the candidates of the passes `ks` (one master surface).
   subroutine master_normals(self, ks, nnode, x)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: ks(:), nnode
      real(wp), intent(in) :: x(2, nnode)
      integer :: i
      do i = 1, size(ks)
         associate (ps => self%passes(ks(i)), ms => self%surfaces(self%passes(ks(i))%master))
            call candidate_normals(nnode, x, self%xp, ms%nseg, ms%seg, ps%broad%ncand, ps%broad%cand, &
                                   self%stamp, ms%sn, ms%sn_stamp)
         end associate
      end do
   end subroutine master_normals

   !> Sweep 3: the hits of the passes `ks` (one slave surface), in pass order.
   subroutine slave_passes(self, ks, nnode, x)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: ks(:), nnode
      real(wp), intent(in) :: x(2, nnode)
      integer :: i
      real(wp) :: depth
      do i = 1, size(ks)
         associate (ps => self%passes(ks(i)), sl => self%surfaces(self%passes(ks(i))%slave), &
                    ms => self%surfaces(self%passes(ks(i))%master))
            if (ps%broad%ncand == 0) cycle
            depth = merge(self%depth_corner, self%depth, ps%corners)
            if (ps%slave == ps%master .and. sl%nrm_stamp /= self%stamp) then
               ! every node normal of the surface, once per search (surface_normals)
               call node_normals(nnode, x, sl%nseg, sl%seg, sl%nnode, sl%where, sl%nrm)
               sl%nrm_stamp = self%stamp
            end if
            if (sl%nrm_stamp == self%stamp .and. ps%slave == ps%master) then
               ! self contact: the node normal alone (the side test pairs a node with its own
               ! body's faces across a corner; doc/contact-detection.md, "Facing test")
               call detect_contacts(ps%hits, ps%detection, nnode, x, self%xp, sl%nnode, sl%nodes, &
                                    sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                    depth, FACING)
            else if (sl%nrm_stamp == self%stamp) then
               ! this search formed every normal of the surface
               call detect_contacts(ps%hits, ps%detection, nnode, x, self%xp, sl%nnode, sl%nodes, &
                                    sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                    depth, FACING, fseg=sl%seg, fhead=sl%nhead, fsegs=sl%nsegs)
            else
               ! the normals of the slaves that have a hit and of the segments, formed by the
               ! narrow phase once in this search (another surface than the master: above)
               call detect_contacts(ps%hits, ps%detection, nnode, x, self%xp, sl%nnode, sl%nodes, &
                                    sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                    depth, FACING, sl%nseg, sl%seg, sl%nhead, sl%nsegs, &
                                    self%stamp, ms%sn, ms%sn_stamp, sl%sn, sl%sn_stamp)
            end if
         end associate
      end do
   end subroutine slave_passes

end submodule exic_contact_narrow
