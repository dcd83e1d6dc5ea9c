!> The contact step (submodule of contact.f90): predicted positions (eq. 4.4), the passes of
!> the step (AUTOmatic ones from the search over all surfaces), the candidate constraints of the
!> Lagrange passes solved by the corrector (eq. 4.5-4.7) or the frictional corrector
!> (doc/friction.md), the penalty passes, and the pairs' results.
submodule(exic_contact_contact) exic_contact_contact_step
   use exic_base_error, only: make_error
   use exic_base_clock, only: wall_time
   use exic_base_grow, only: grow
   use exic_base_sort, only: search_sorted, sorted_unique
   use exic_contact_spec, only: DETECT_STATIC
   use exic_contact_broad, only: broad_search
   use exic_contact_friction, only: coulomb_mu
   use exic_contact_penalty, only: penalty_forces
   implicit none

contains

   !> The contact correction of one step (interface: contact.f90).
   module procedure contact_correct
      integer :: k, j, i, node, nheld
      integer, allocatable :: held(:)
      real(wp) :: c, gnow, pen, t0, t1, mu
      logical :: touched

      nactive = 0
      if (.not. self%active) return
      t0 = wall_time()
      if (.not. (self%keep_fcon .and. self%fcon_clean)) fcon = 0.0_wp
      self%fcon_clean = .false.
      touched = .false.
      call predicted_positions(self, nnode, x, vt, a, dt)
      ! c = dt(n+1) (dt(n) + dt(n+1)) / 2, eq. 4.7
      c = 0.5_wp*dt*(dt_prev + dt)
      if (self%face%active) then
         ! massless faces: the free solve places them at their trial positions (eq. I.5, I.7)
         if (.not. (present(fext) .and. present(fint))) then
            call make_error(err, 'LAGRange,ENERgy needs the forces of the step (contact_t%correct: fext, fint)')
            return
         end if
         if (.not. allocated(self%fres)) allocate (self%fres(2, nnode))
         self%fres = fext - fint
         call self%face%trial(nnode, x, self%fres, c, self%xp, a, err)
         if (allocated(err)) return
      end if
      do k = 1, size(self%results)
         self%results(k)%fnormal = 0.0_wp
         self%results(k)%force = 0.0_wp
         self%results(k)%nactive = 0
         self%results(k)%penetration = 0.0_wp
         self%results(k)%pmax = 0.0_wp
      end do
      if (self%friction) call friction_begin(self)
      self%cs%friction = self%friction
      call self%cs%reserve(64)
      if (self%auto_pass%method == METHOD_PENALTY) then
         ! penalty: the springs act on the positions at t(n+1) (penalty_pass)
         call auto_passes(self, nnode, x, x, self%depth, kept=.true.)
      else
         call auto_passes(self, nnode, x, self%xp, self%depth, kept=.true.)
      end if
      ! the narrow phase of every Lagrange pass at once (src/exic/contact/narrow.f90); with
      ! penalty passes, which change node normals and forces, pass by pass in order
      if (.not. self%any_penalty) call narrow_passes(self, nnode, x, minv, 1, self%npass)
      do k = 1, self%npass
         associate (ps => self%passes(k), sl => self%surfaces(self%passes(k)%slave), &
                    ms => self%surfaces(self%passes(k)%master))
            if (ps%method == METHOD_PENALTY) then
               call surface_normals(self, sl, nnode, x)
               call penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, dt_prev, fcon, nactive)
               if (ps%broad%ncand > 0) touched = .true.
               cycle
            end if
            if (self%any_penalty) call narrow_passes(self, nnode, x, minv, k, k)
            nheld = 0
            if (ps%broad%ncand == 0) then
               if (ps%corners) ps%held = [integer ::]
               cycle
            end if
            do j = 1, ps%hits%n
               node = ps%hits%slave(j)
               associate (m1 => ps%hits%master(1, j), m2 => ps%hits%master(2, j), &
                          al => ps%hits%alpha(j), nr => ps%hits%normal(:, j))
                  ! gap at t(n+1) along the frozen normal (eq. 3.19)
                  gnow = dot_product(x(:, node) - (1.0_wp - al)*x(:, m1) - al*x(:, m2), nr)
                  if (ps%corners) then
                     ! a corner behind the slave surface at the start of the step, neither
                     ! crossing it in the step nor held at the last step, entered the slave's
                     ! body between its nodes before it was a corner: not held (eq. K.2)
                     if (ps%hits%tau(j) <= 0.0_wp .and. gnow < -self%corr%gap_tol .and. &
                         search_sorted(ps%held, node) <= 0) cycle
                     nheld = nheld + 1
                     call grow(held, nheld)
                     held(nheld) = node
                  end if
                  if (ps%friction) then
                     ! the step's coefficient from the slave's last state (eq. F12)
                     mu = coulomb_mu(ps%law(1), ps%law(2), ps%law(3), self%vslip(node))
                     call self%cs%add(node, m1, m2, al, nr, ps%hits%gap(j), gnow, ps%pair, mu)
                  else
                     call self%cs%add(node, m1, m2, al, nr, ps%hits%gap(j), gnow, ps%pair)
                  end if
               end associate
            end do
            if (ps%corners) ps%held = sorted_unique(held(1:nheld))
         end associate
      end do
      t1 = wall_time()
      self%time_search = self%time_search + (t1 - t0)
      if (self%cs%n > 0) then
         if (self%friction) then
            call self%fr%solve(self%corr, self%cs, nnode, minv, c, x, self%xp, a, fcon, self%ffric, err, rb)
         else if (self%face%active) then
            call face_solve(self, nnode, x, minv, c, a, fcon, err, rb)
         else
            call self%corr%solve(self%cs, nnode, minv, c, a, fcon, err, rb)
         end if
         self%time_corrector = self%time_corrector + (wall_time() - t1)
         if (allocated(err)) return
         self%nredundant = self%nredundant + self%corr%nredundant
         do i = 1, self%cs%n
            associate (r => self%results(self%cs%pair(i)))
               pen = max(0.0_wp, -self%cs%gap_now(i))
               r%penetration = max(r%penetration, pen)
               if (self%cs%p(i) <= 0.0_wp) cycle
               r%nactive = r%nactive + 1
               r%fnormal = r%fnormal + self%cs%p(i)
               r%pmax = max(r%pmax, self%cs%p(i))
               r%work = r%work - self%cs%p(i)*self%cs%gap_now(i)
               r%force = r%force + self%cs%p(i)*self%cs%nrm(:, i)
            end associate
         end do
         nactive = nactive + count(self%cs%p(1:self%cs%n) > 0.0_wp)
      end if
      if (self%friction) call friction_results(self, dt)
      do k = 1, size(self%results)
         self%max_penetration = max(self%max_penetration, self%results(k)%penetration)
      end do
      if (self%friction) self%xold = x
      self%fcon_clean = self%cs%n == 0 .and. .not. touched
   end procedure contact_correct

   !> The passes of AUTOmatic contact for this search (interface: contact.f90).
   module procedure auto_passes
      integer :: g, need
      type(pass_t), allocatable :: tmp(:)
      logical :: use_kept

      use_kept = .false.
      if (present(kept)) use_kept = kept
      self%stamp = self%stamp + 1
      self%npass = self%nfixed
      if (.not. self%auto_pass%auto) return
      if (use_kept) then
         call self%auto%search_kept(nnode, x0, x1, margin)
      else
         call self%auto%search(nnode, x0, x1, margin)
      end if
      need = self%nfixed + self%auto%ngroup
      if (need > size(self%passes)) then
         allocate (tmp(max(need, 2*size(self%passes), 8)))
         tmp(1:size(self%passes)) = self%passes
         call move_alloc(tmp, self%passes)
      end if
      do g = 1, self%auto%ngroup
         associate (ps => self%passes(self%nfixed + g))
            ! the options of auto_pass (its work arrays stay those of the slot)
            ps%pair = self%auto_pass%pair
            ps%method = self%auto_pass%method
            ps%detection = self%auto_pass%detection
            ps%k = self%auto_pass%k
            ps%law = self%auto_pass%law
            ps%friction = self%auto_pass%friction
            ps%energy = self%auto_pass%energy
            ps%auto = .true.
            ps%slave = self%auto_first + self%auto%gslave(g)
            ps%master = self%auto_first + self%auto%gmaster(g)
            call self%auto%take(g, ps%broad)
         end associate
      end do
      self%npass = need
   end procedure auto_passes

   !> Node normals of surface sf at positions x, once per search (interface: contact.f90).
   module procedure surface_normals
      if (sf%nrm_stamp == self%stamp) return
      call node_normals(nnode, x, sf%nseg, sf%seg, sf%nnode, sf%where, sf%nrm)
      sf%nrm_stamp = self%stamp
   end procedure surface_normals

   !> Predicted positions x~(n+2) = x + dt vt + dt^2/2 a (eq. 4.4) of the contact nodes, the
   !> only ones the search and the corrector read; with massless faces of every node, since the
   !> face's free solve (eq. I.5) reads the predicted motion of the interior nodes next to it.
   subroutine predicted_positions(self, nnode, x, vt, a, dt)
      type(contact_t), intent(inout) :: self
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), a(2, nnode), dt
      integer :: k, node
      real(wp) :: h
      h = 0.5_wp*dt*dt
      if (self%face%active) then
         self%xp = x + dt*vt + h*a
         return
      end if
      do k = 1, size(self%cnodes)
         node = self%cnodes(k)
         self%xp(:, node) = x(:, node) + dt*vt(:, node) + h*a(:, node)
      end do
   end subroutine predicted_positions

   !> At the start of a step with friction: the Coulomb work of the last step, whose interval
   !> has now been stepped, joins the dissipation (doc/friction.md, eq. F17); the step's
   !> friction results and forces start from zero.
   subroutine friction_begin(self)
      type(contact_t), intent(inout) :: self
      integer :: k
      self%dissipation = self%dissipation + self%pending
      self%pending = 0.0_wp
      do k = 1, size(self%results)
         associate (r => self%results(k))
            r%dissipation = r%dissipation + r%pending
            r%pending = 0.0_wp
            r%ftangent = 0.0_wp
            r%nstick = 0
            r%nslip = 0
         end associate
      end do
      self%ffric = 0.0_wp
   end subroutine friction_begin

   !> After the frictional corrector: the pairs' friction results, the Coulomb work of the step
   !> (eq. F16, booked at the next step) and each slave's slip speed for the next step's
   !> coefficient (eq. F12); dt = dt(n+1).
   subroutine friction_results(self, dt)
      type(contact_t), intent(inout) :: self
      real(wp), intent(in) :: dt
      integer :: i, node
      real(wp) :: d, tng(2)
      self%vslip = -1.0_wp
      do i = 1, self%cs%n
         node = self%cs%node(1, i)
         if (self%cs%state(i) == 0) cycle
         associate (r => self%results(self%cs%pair(i)))
            tng = [-self%cs%nrm(2, i), self%cs%nrm(1, i)]
            r%force = r%force + self%cs%q(i)*tng
            r%ftangent = r%ftangent + abs(self%cs%q(i))
            if (self%cs%state(i) == 1) then
               r%nstick = r%nstick + 1
            else
               r%nslip = r%nslip + 1
               d = self%cs%mu(i)*self%cs%p(i)*abs(self%cs%slip(i))
               r%pending = r%pending + d
               self%pending = self%pending + d
               self%vslip(node) = abs(self%cs%slip(i))/dt
            end if
         end associate
      end do
   end subroutine friction_results

   !> Penalty baseline of one pass (src/exic/contact/penalty.f90): static detection at t(n+1),
   !> forces k x penetration (plus damping) on the hits, with the regularised friction law when
   !> the pass has friction; the pair's results. An AUTOmatic pass has its candidates from the
   !> search over all surfaces (over x -> x with margin depth, as broad_search here) and its
   !> tangential state from auto_hist, kept per pair of surfaces.
   subroutine penalty_pass(self, ps, sl, ms, nnode, x, vt, a, minv, dt_prev, fcon, nactive)
      type(contact_t), intent(inout) :: self
      type(pass_t), intent(inout) :: ps
      type(surface_t), intent(inout) :: sl
      type(surface_t), intent(in) :: ms
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode), dt_prev
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      integer, intent(inout) :: nactive
      integer :: j, n
      real(wp) :: diss
      if (.not. ps%auto) call broad_search(ps%broad, nnode, x, x, sl%nnode, sl%nodes, ms%nseg, ms%seg, self%depth)
      if (ps%broad%ncand == 0) return
      call detect_contacts(ps%hits, DETECT_STATIC, nnode, x, x, sl%nnode, sl%nodes, &
                           sl%nrm, ms%nseg, ms%seg, ms%link, ps%broad%ncand, ps%broad%cand, &
                           self%depth, FACING)
      n = ps%hits%n
      call grow(ps%pen, n)
      call grow(ps%fn, n)
      call grow(ps%f, n, 2)
      diss = 0.0_wp
      if (ps%friction) then
         call grow(ps%q, n)
         call grow(ps%state, n)
         if (ps%auto) then
            call self%auto_hist%load(ps%slave, ps%master, self%hwork)
            call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n), &
                                self%hwork, ps%law, self%xold, dt_prev, self%ffric, ps%q(1:n), ps%state(1:n), diss)
            call self%auto_hist%store(ps%slave, ps%master, self%hwork)
         else
            call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n), &
                                ps%hist, ps%law, self%xold, dt_prev, self%ffric, ps%q(1:n), ps%state(1:n), diss)
         end if
      else
         call penalty_forces(ps%hits, ps%k, nnode, x, vt, minv, a, fcon, ps%pen(1:n), ps%fn(1:n), ps%f(:, 1:n))
      end if
      associate (r => self%results(ps%pair), pen => ps%pen, fn => ps%fn, f => ps%f)
         do j = 1, n
            if (pen(j) <= 0.0_wp) cycle
            r%nactive = r%nactive + 1
            r%fnormal = r%fnormal + fn(j)
            r%pmax = max(r%pmax, fn(j))
            r%force = r%force + f(:, j)
            r%penetration = max(r%penetration, pen(j))
            nactive = nactive + 1
            if (.not. ps%friction) cycle
            r%ftangent = r%ftangent + abs(ps%q(j))
            if (ps%state(j) == 1) r%nstick = r%nstick + 1
            if (ps%state(j) == 2) r%nslip = r%nslip + 1
         end do
         ! the realised slip of [t(n), t(n+1)] is booked at once
         r%dissipation = r%dissipation + diss
         self%dissipation = self%dissipation + diss
      end associate
   end subroutine penalty_pass

end submodule exic_contact_contact_step
