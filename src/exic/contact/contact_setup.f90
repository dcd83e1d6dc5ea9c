!> Contact set-up (submodule of contact.f90): the surfaces of the SURFace records and of every
!> region for AUTOmatic, the passes of the PAIR records, the penalty stiffness, the friction
!> state, and the refusal of bodies that overlap at the start.
submodule(exic_contact_contact) exic_contact_contact_setup
   use exic_base_error, only: make_error
   use exic_base_sort, only: sorted_unique
   use exic_contact_spec, only: SURF_REGION, SURF_MATERIAL, SURF_FACETS, SURF_NODES, PAIR_NTOS, &
                                PAIR_SYMMETRIC, PAIR_SELF, DETECT_STATIC, pair_spec_t, spec_penalty_finite
   use exic_mesh_boundary, only: free_edges, free_edges_of, surface_nodes, &
                                 segment_links, locate_nodes, node_segments
   use exic_contact_broad, only: broad_search
   use exic_contact_overlap, only: node_element_lists, inside_near
   implicit none

contains

   !> Surfaces and passes from the CONTact block, the refusal of overlapping bodies (interface: contact.f90).
   module procedure contact_init
      integer :: k, np, nsurf, nlen
      integer, allocatable :: head(:), list(:)
      real(wp) :: len_sum

      self%active = spec%active
      if (.not. self%active) return
      call build_surfaces(self, spec, nelem, conn, region, mat, err)
      if (allocated(err)) return
      call build_passes(self, spec, err)
      if (allocated(err)) return
      nsurf = size(self%surfaces)
      len_sum = 0.0_wp
      nlen = 0
      do k = 1, nsurf
         associate (sf => self%surfaces(k))
            len_sum = len_sum + sum(norm2(xref(:, sf%seg(2, :)) - xref(:, sf%seg(1, :)), dim=1))
            nlen = nlen + sf%nseg
         end associate
      end do
      if (nlen > 0) self%lref = len_sum/nlen
      self%depth = DEPTH_SHARE*self%lref
      self%depth_corner = CORNER_DEPTH_SHARE*self%lref
      self%corr%gap_tol = 1.0e-13_wp*self%lref
      allocate (self%xp(2, nnode), source=0.0_wp)
      call contact_nodes(self, nnode)
      np = size(self%passes)
      do k = 1, np
         if (self%passes(k)%method == METHOD_PENALTY) self%any_penalty = .true.
      end do
      if (self%auto_pass%auto .and. self%auto_pass%method == METHOD_PENALTY) self%any_penalty = .true.
      call penalty_stiffness(self, modulus)
      call spec_penalty_finite(spec, modulus, err)
      if (allocated(err)) return
      call friction_arrays(self, nnode, x)
      if (self%energy .and. self%friction) then
         ! the massless faces enter the normal problem only (doc/impact.md, section 3.3)
         call make_error(err, 'LAGRange,ENERgy (massless contact faces) together with Coulomb friction '// &
                         'in one model is not supported: expected friction only on LAGRange pairs of a '// &
                         'model without ENERgy')
         return
      end if
      call node_element_lists(nnode, nelem, conn, head, list)
      call check_overlap(self, nnode, x, nelem, conn, head, list, err)
   end procedure contact_init

   !> The friction state of the passes and of the model (at init): allocated only when some
   !> pass has friction (x: the positions now).
   subroutine friction_arrays(self, nnode, x)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode)
      integer :: k
      self%friction = .false.
      do k = 1, size(self%passes)
         associate (ps => self%passes(k))
            ps%friction = ps%law(1) > 0.0_wp
            if (ps%friction) self%friction = .true.
            if (ps%friction .and. ps%method == METHOD_PENALTY .and. .not. allocated(ps%hist%q)) &
               call ps%hist%init(nnode)
         end associate
      end do
      ! the options of the AUTOmatic passes (auto_passes copies them)
      self%auto_pass%friction = self%auto_pass%auto .and. self%auto_pass%law(1) > 0.0_wp
      if (self%auto_pass%friction) self%friction = .true.
      if (self%auto_pass%friction .and. self%auto_pass%method == METHOD_PENALTY .and. &
          .not. allocated(self%hwork%q)) call self%hwork%init(nnode)
      if (.not. self%friction) return
      if (.not. allocated(self%vslip)) allocate (self%vslip(nnode), source=-1.0_wp)
      if (.not. allocated(self%ffric)) allocate (self%ffric(2, nnode), source=0.0_wp)
      if (.not. allocated(self%xold)) allocate (self%xold(2, nnode), source=x)
   end subroutine friction_arrays

   !> Surfaces of the SURFace records, plus one per region for AUTOmatic.
   subroutine build_surfaces(self, spec, nelem, conn, region, mat, err)
      type(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      integer, intent(in) :: nelem
      integer, intent(in) :: conn(4, nelem), region(nelem), mat(nelem)
      type(error_t), allocatable, intent(out) :: err
      integer :: ns, nauto, k
      integer, allocatable :: regions(:), rfirst(:), relems(:)
      logical, allocatable :: sel(:)

      ns = 0
      if (allocated(spec%surfaces)) ns = size(spec%surfaces)
      nauto = 0
      if (spec%automatic) then
         call bodies_elements(nelem, region, regions, rfirst, relems)
         nauto = size(regions)
      end if
      allocate (self%surfaces(ns + nauto))
      allocate (sel(nelem))
      do k = 1, ns
         associate (sp => spec%surfaces(k), sf => self%surfaces(k))
            sf%id = sp%id
            select case (sp%by)
            case (SURF_REGION)
               sel = region == sp%ref
               call free_edges(nelem, conn, sel, sf%seg, err)
            case (SURF_MATERIAL)
               sel = mat == sp%ref
               call free_edges(nelem, conn, sel, sf%seg, err)
            case (SURF_FACETS)
               sf%seg = sp%facets
            case (SURF_NODES)
               ! slave nodes without segments: no normals, so no facing test (see detect_pairs)
               allocate (sf%seg(2, 0))
               if (size(sp%nodes) > 0) sf%nodes = sorted_unique(sp%nodes)
            end select
            if (allocated(err)) then
               err%message = 'SURFace '//itoa(sp%id)//': '//err%message
               return
            end if
            if (size(sf%seg, 2) == 0 .and. sp%by /= SURF_NODES) then
               call make_error(err, 'SURFace '//itoa(sp%id)//' has no segments')
               return
            end if
         end associate
      end do
      do k = 1, nauto
         associate (sf => self%surfaces(ns + k))
            sf%id = -regions(k) - 1          ! automatic surface of region regions(k)
            call free_edges_of(nelem, conn, relems(rfirst(k):rfirst(k + 1) - 1), sf%seg, err)
            if (allocated(err)) return
         end associate
      end do
      do k = 1, size(self%surfaces)
         associate (sf => self%surfaces(k))
            sf%nseg = size(sf%seg, 2)
            allocate (sf%link(2, sf%nseg), sf%where(2, sf%nseg))
            call segment_links(sf%nseg, sf%seg, sf%link)
            if (.not. allocated(sf%nodes)) call surface_nodes(sf%nseg, sf%seg, sf%nodes)
            sf%nnode = size(sf%nodes)
            call locate_nodes(sf%nseg, sf%seg, sf%nnode, sf%nodes, sf%where)
            allocate (sf%nrm(2, sf%nnode), sf%sn(4, sf%nseg), sf%sn_stamp(sf%nseg))
            sf%sn_stamp = -1
            call node_segments(sf%nseg, sf%where, sf%nnode, sf%nhead, sf%nsegs)
         end associate
      end do
   end subroutine build_surfaces

   !> Passes of the PAIR records (two for SYMMetric); AUTOmatic's are made per step (auto_passes).
   subroutine build_passes(self, spec, err)
      type(contact_t), intent(inout) :: self
      type(contact_spec_t), intent(in) :: spec
      type(error_t), allocatable, intent(out) :: err
      integer :: npair, np, k, i, j, nauto, ns, maxid, npass
      type(pass_t), allocatable :: p(:)

      npair = 0
      if (allocated(spec%pairs)) npair = size(spec%pairs)
      ns = 0
      if (allocated(spec%surfaces)) ns = size(spec%surfaces)
      nauto = size(self%surfaces) - ns
      allocate (p(2*npair + 1))   ! two passes a pair at most, and AUTOmatic's
      maxid = 0
      np = 0
      allocate (self%results(npair + merge(1, 0, nauto > 0)))
      do k = 1, npair
         associate (ps => spec%pairs(k))
            self%results(k)%id = ps%id
            maxid = max(maxid, ps%id)
            i = surface_index(self, ps%slave)
            j = surface_index(self, ps%master)
            if (i == 0 .or. j == 0) then
               call make_error(err, 'PAIR '//itoa(ps%id)//' names a surface that is not defined')
               return
            end if
            if (self%surfaces(j)%nseg == 0 .or. (ps%kind /= PAIR_NTOS .and. self%surfaces(i)%nseg == 0)) then
               call make_error(err, 'PAIR '//itoa(ps%id)//': a node set can only be the slave side of a one-pass pair')
               return
            end if
            select case (ps%kind)
            case (PAIR_NTOS)
               call add_pass(p, np, k, i, j, ps)
               if (self%surfaces(i)%nseg > 0 .and. i /= j .and. ps%method == METHOD_LAGRANGE) then
                  ! the corner pass: a convex corner of the master can enter the slave surface
                  ! between its nodes, where the first pass does not look (doc/contact-detection.md,
                  ! "Corner pass of a one-pass pair")
                  call add_pass(p, np, k, j, i, ps)
                  p(np)%corners = .true.
               end if
            case (PAIR_SYMMETRIC)
               call add_pass(p, np, k, i, j, ps)
               call add_pass(p, np, k, j, i, ps)
            case (PAIR_SELF)
               call add_pass(p, np, k, i, i, ps)
            end select
         end associate
      end do
      if (nauto > 0) then
         ! AUTOmatic: one search over all its surfaces per step makes the passes of the pairs
         ! of surfaces found near (auto_passes), in the order of i, then j
         self%results(npair + 1)%id = maxid + 1
         call add_pass(p, np, npair + 1, 0, 0, spec%auto_options)
         self%auto_pass = p(np)
         self%auto_pass%auto = .true.
         self%auto_pass%energy = self%auto_pass%energy .and. self%auto_pass%method == METHOD_LAGRANGE
         if (self%auto_pass%energy) self%energy = .true.
         np = np - 1
         self%auto_first = ns
         do i = ns + 1, ns + nauto
            call self%auto%add_surface(self%surfaces(i)%nodes, self%surfaces(i)%seg)
         end do
      end if
      ! a corner pass whose surfaces another pass already pairs in its direction (a SYMMetric pair,
      ! or NTOS pairs written both ways) adds nothing: dropped
      npass = 0
      do k = 1, np
         if (p(k)%corners) then
            if (any([(.not. p(i)%corners .and. p(i)%slave == p(k)%slave .and. p(i)%master == p(k)%master, &
                      i=1, np)])) cycle
         end if
         npass = npass + 1
         if (npass < k) p(npass) = p(k)
      end do
      self%nfixed = npass
      self%npass = npass
      allocate (self%passes(npass))
      do k = 1, npass
         self%passes(k)%pair = p(k)%pair
         self%passes(k)%slave = p(k)%slave
         self%passes(k)%master = p(k)%master
         self%passes(k)%method = p(k)%method
         self%passes(k)%energy = p(k)%energy .and. p(k)%method == METHOD_LAGRANGE
         if (self%passes(k)%energy) self%energy = .true.
         self%passes(k)%detection = p(k)%detection
         self%passes(k)%k = p(k)%k
         self%passes(k)%law = p(k)%law
         self%passes(k)%corners = p(k)%corners
         if (p(k)%corners) allocate (self%passes(k)%held(0))
      end do
   end subroutine build_passes

   !> Append a pass with the options of `ps`.
   subroutine add_pass(p, np, pair, slave, master, ps)
      type(pass_t), intent(inout) :: p(:)
      integer, intent(inout) :: np
      integer, intent(in) :: pair, slave, master
      type(pair_spec_t), intent(in) :: ps
      np = np + 1
      p(np)%pair = pair
      p(np)%slave = slave
      p(np)%master = master
      p(np)%method = ps%method
      p(np)%energy = ps%energy
      p(np)%detection = ps%detection
      p(np)%k = ps%penalty
      if (ps%penalty_scaled) p(np)%k = -ps%penalty   ! scale factor, resolved in penalty_stiffness
      p(np)%law = [ps%mus, ps%mud, ps%decay]
   end subroutine add_pass

   !> PENAlty,SCALe,f: k = f x modulus, the largest constrained modulus lambda + 2 mu of the solids.
   subroutine penalty_stiffness(self, modulus)
      type(contact_t), intent(inout) :: self
      real(wp), intent(in) :: modulus
      integer :: k
      do k = 1, size(self%passes)
         if (self%passes(k)%k < 0.0_wp) self%passes(k)%k = -self%passes(k)%k*modulus
      end do
      if (self%auto_pass%k < 0.0_wp) self%auto_pass%k = -self%auto_pass%k*modulus
   end subroutine penalty_stiffness

   !> Index of the surface with deck id `id` (0 if none).
   integer function surface_index(self, id) result(k)
      type(contact_t), intent(in) :: self
      integer, intent(in) :: id
      do k = 1, size(self%surfaces)
         if (self%surfaces(k)%id == id) return
      end do
      k = 0
   end function surface_index

   !> Bodies that overlap at the start are an error naming the worst node, segment and depth: a
   !> node behind a segment that lies inside an element next to it (src/exic/contact/overlap.f90).
   subroutine check_overlap(self, nnode, x, nelem, conn, head, list, err)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode, nelem, conn(4, nelem), head(:), list(:)
      real(wp), intent(in) :: x(2, nnode)
      type(error_t), allocatable, intent(out) :: err
      integer :: k, j, worst_node, worst_m(2)
      real(wp) :: worst
      worst = 0.0_wp
      worst_node = 0
      call auto_passes(self, nnode, x, x, 0.5_wp*self%lref)
      do k = 1, self%npass
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            call surface_normals(self, sl, nnode, x)
            if (.not. ps%auto) call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, &
                                                 0.5_wp*self%lref)
            if (ps%corners) call keep_convex_corners(ps%broad, nnode, x, sl%nnode, sl%nodes, sl%seg, sl%nhead, &
                                                     sl%nsegs)
            call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                                 sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                                 0.5_wp*self%lref, FACING)
            do j = 1, ps%hits%n
               if (-ps%hits%gap(j) > worst) then
                  if (.not. inside_near(ps%hits%slave(j), ps%hits%master(:, j), nnode, x, nelem, conn, &
                                        head, list)) cycle
                  worst = -ps%hits%gap(j)
                  worst_node = ps%hits%slave(j)
                  worst_m = ps%hits%master(:, j)
               end if
            end do
         end associate
      end do
      if (worst > 1.0e-8_wp*self%lref) call make_error(err, 'bodies overlap at the start: node '//itoa(worst_node)// &
                                                       ' is inside segment '//itoa(worst_m(1))//'-'// &
                                                       itoa(worst_m(2))//' by '//rtoa(worst)// &
                                                       ' (move the bodies apart or fix the mesh)')
   end subroutine check_overlap

   !> Every node of every contact surface, once (cnodes).
   subroutine contact_nodes(self, nnode)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      logical, allocatable :: on(:)
      integer :: k
      allocate (on(nnode), source=.false.)
      do k = 1, size(self%surfaces)
         on(self%surfaces(k)%nodes) = .true.
      end do
      self%cnodes = pack([(k, k=1, nnode)], on)
   end subroutine contact_nodes

end submodule exic_contact_contact_setup
