!> The penalty baseline of contact: forces from the penetration at t(n+1), and with friction the
!> regularised Coulomb law (doc/friction.md, section 6, eq. F18).
!>
!> Normal force: f_n = k (-g) on the slave along the master normal n at t(n+1), opposite on the
!> master nodes with the weights (1 - alpha, alpha), plus a viscous part -c v_n with
!> c = 2 PENALTY_DAMPING sqrt(k m) (m the pair's effective mass, v_n the relative normal velocity
!> of the predictor), never tensile. The damping is the usual companion of explicit penalty
!> contact: without it, the on/off switching of stiff springs within a step feeds energy into the
!> struck nodes.
!>
!> Friction: an elastic tangential spring of the normal stiffness k_T = k that slips at mu f_n
!> (return mapping, Wriggers 2006): q_trial = q_old - k_T ds with ds the realised relative
!> tangential increment of the step along t = e3 x n; |q_trial| <= mu f_n sticks (q = q_trial),
!> otherwise q = mu f_n sign(q_trial) and the plastic slip (|q_trial| - mu f_n)/k_T dissipates
!> mu f_n times itself. q_old is the slave node's force of the previous step (kept in
!> penalty_history_t; 0 when it was not in contact), mu from coulomb_mu (eq. F12).
module exic_contact_penalty
   use exic_base_kinds, only: wp
   use exic_base_grow, only: grow
   use exic_contact_detect, only: contact_set_t
   use exic_contact_friction, only: coulomb_mu
   implicit none
   private

   public :: penalty_forces, penalty_history_t, smallest_mass, spring_dt, auto_spring_dt

   !> Viscous damping of penalty contact as a fraction of critical (LS-DYNA's customary 10 %).
   real(wp), parameter :: PENALTY_DAMPING = 0.1_wp

   !> The tangential state of a penalty pass's slave nodes between steps.
   type :: penalty_history_t
      real(wp), allocatable :: q(:)          !< (nnode) tangential force on each slave node (0: none)
      real(wp), allocatable :: vslip(:)      !< (nnode) slip speed of the last step (< 0: stuck or no contact)
      integer, allocatable :: nodes(:)       !< slave nodes with a state, n of them
      integer :: n = 0
   contains
      procedure :: init => history_init
   end type penalty_history_t

contains

   !> Room for nnode nodes, no state.
   subroutine history_init(self, nnode)
      class(penalty_history_t), intent(inout) :: self
      integer, intent(in) :: nnode
      if (allocated(self%q)) deallocate (self%q, self%vslip)
      allocate (self%q(nnode), source=0.0_wp)
      allocate (self%vslip(nnode), source=-1.0_wp)
      self%n = 0
   end subroutine history_init

   !> Forces of the hits of one penalty pass with stiffness k, added to `fcon` and (times minv) to
   !> `a`. Per hit j: pen(j) the penetration at t(n+1) (<= 0: no force, nothing else set),
   !> fn(j) the normal force, f(:, j) the force on the slave. With `hist` (friction with the law
   !> law = (mus, mud, decay)): the tangential force q(j) and state(j) (1 stick, 2 slip) as well,
   !> the friction forces added to `ffric`, the dissipation of the step added to `diss`;
   !> xold = x(n), dt_prev = dt(n) give the realised increments and the slip speed.
   subroutine penalty_forces(hits, k, nnode, x, vt, minv, a, fcon, pen, fn, f, hist, law, xold, dt_prev, &
                             ffric, q, state, diss)
      type(contact_set_t), intent(in) :: hits
      real(wp), intent(in) :: k
      integer, intent(in) :: nnode
      real(wp), intent(in) :: x(2, nnode), vt(2, nnode), minv(2, nnode)
      real(wp), intent(inout) :: a(2, nnode), fcon(2, nnode)
      real(wp), intent(out) :: pen(:), fn(:), f(:, :)
      type(penalty_history_t), intent(inout), optional :: hist
      real(wp), intent(in), optional :: law(3), xold(2, nnode), dt_prev
      real(wp), intent(inout), optional :: ffric(2, nnode)
      real(wp), intent(out), optional :: q(:)
      integer, intent(out), optional :: state(:)
      real(wp), intent(inout), optional :: diss
      integer :: j, node, m1, m2, nold
      real(wp) :: al, nr(2), vn, w, t(2), ds, qtr, beta, slip, mu
      real(wp), allocatable :: qprev(:), vprev(:)
      logical :: friction

      friction = present(hist)
      if (friction) then
         ! the previous step's state of this step's slave nodes; every other node forgets its own
         allocate (qprev(hits%n), vprev(hits%n))
         do j = 1, hits%n
            qprev(j) = hist%q(hits%slave(j))
            vprev(j) = hist%vslip(hits%slave(j))
         end do
         nold = hist%n
         hist%q(hist%nodes(1:nold)) = 0.0_wp
         hist%vslip(hist%nodes(1:nold)) = -1.0_wp
         hist%n = 0
         call grow(hist%nodes, max(hits%n, 1))
      end if
      do j = 1, hits%n
         pen(j) = -hits%gap(j)
         if (pen(j) <= 0.0_wp) cycle
         node = hits%slave(j)
         m1 = hits%master(1, j)
         m2 = hits%master(2, j)
         al = hits%alpha(j)
         nr = hits%normal(:, j)
         vn = dot_product(vt(:, node) - (1.0_wp - al)*vt(:, m1) - al*vt(:, m2), nr)
         w = minv(1, node) + (1.0_wp - al)**2*minv(1, m1) + al**2*minv(1, m2)
         fn(j) = k*pen(j)
         if (w > 0.0_wp) fn(j) = fn(j) - 2.0_wp*PENALTY_DAMPING*sqrt(k/w)*vn
         fn(j) = max(fn(j), 0.0_wp)
         f(:, j) = fn(j)*nr
         if (friction) then
            t = [-nr(2), nr(1)]
            ds = dot_product(t, (x(:, node) - xold(:, node)) - (1.0_wp - al)*(x(:, m1) - xold(:, m1)) - &
                             al*(x(:, m2) - xold(:, m2)))
            mu = coulomb_mu(law(1), law(2), law(3), vprev(j))
            qtr = qprev(j) - k*ds
            beta = mu*fn(j)
            hist%n = hist%n + 1
            hist%nodes(hist%n) = node
            if (abs(qtr) <= beta) then
               q(j) = qtr
               state(j) = 1
               hist%vslip(node) = -1.0_wp
            else
               q(j) = sign(beta, qtr)
               state(j) = 2
               slip = (abs(qtr) - beta)/k
               diss = diss + beta*slip
               hist%vslip(node) = 0.0_wp
               if (dt_prev > 0.0_wp) hist%vslip(node) = slip/dt_prev
            end if
            hist%q(node) = q(j)
            f(:, j) = f(:, j) + q(j)*t
            ffric(:, node) = ffric(:, node) + q(j)*t
            ffric(:, m1) = ffric(:, m1) - (1.0_wp - al)*q(j)*t
            ffric(:, m2) = ffric(:, m2) - al*q(j)*t
         end if
         fcon(:, node) = fcon(:, node) + f(:, j)
         fcon(:, m1) = fcon(:, m1) - (1.0_wp - al)*f(:, j)
         fcon(:, m2) = fcon(:, m2) - al*f(:, j)
         a(:, node) = a(:, node) + minv(:, node)*f(:, j)
         a(:, m1) = a(:, m1) - minv(:, m1)*(1.0_wp - al)*f(:, j)
         a(:, m2) = a(:, m2) - minv(:, m2)*al*f(:, j)
      end do
   end subroutine penalty_forces

   !> The smallest mass 1 / minv(1, node) of nodes(1:n) that have one (huge when none has).
   pure real(wp) function smallest_mass(nnode, minv, n, nodes) result(m)
      integer, intent(in) :: nnode, n, nodes(n)
      real(wp), intent(in) :: minv(2, nnode)
      integer :: j
      m = huge(1.0_wp)
      do j = 1, n
         if (minv(1, nodes(j)) > 0.0_wp) m = min(m, 1.0_wp/minv(1, nodes(j)))
      end do
   end function smallest_mass

   !> dt = min(dt, 1 / sqrt(k (1/m_s + 1/mmin))) over the slave nodes(1:n) of a spring of
   !> stiffness k to a master node of mass mmin (huge: none, the master side adds nothing).
   pure subroutine spring_dt(k, nnode, minv, n, nodes, mmin, dt)
      real(wp), intent(in) :: k
      integer, intent(in) :: nnode, n, nodes(n)
      real(wp), intent(in) :: minv(2, nnode), mmin
      real(wp), intent(inout) :: dt
      integer :: j
      real(wp) :: w2
      do j = 1, n
         w2 = k*(minv(1, nodes(j)) + merge(1.0_wp/mmin, 0.0_wp, mmin < huge(1.0_wp)))
         if (w2 > 0.0_wp) dt = min(dt, 1.0_wp/sqrt(w2))
      end do
   end subroutine spring_dt

   !> spring_dt of AUTOmatic contact: the nodes of each of nsurf surfaces (surface r: nodes(first(r)
   !> : first(r + 1) - 1)) are the slaves of every other surface. Their stiffest spring is the one
   !> to the lightest node of those: the smallest of the surfaces' smallest masses, or the second
   !> smallest for the surface that has it. min and the spring's formula are monotone in rounding,
   !> so dt is the one of a pass per ordered pair of surfaces, bit for bit, in O(nodes).
   pure subroutine auto_spring_dt(k, nnode, minv, nsurf, first, nodes, dt)
      real(wp), intent(in) :: k
      integer, intent(in) :: nnode, nsurf, first(nsurf + 1), nodes(*)
      real(wp), intent(in) :: minv(2, nnode)
      real(wp), intent(inout) :: dt
      integer :: r, r1
      real(wp) :: m, m1, m2
      if (nsurf < 2) return
      m1 = huge(1.0_wp)
      m2 = huge(1.0_wp)
      r1 = 0
      do r = 1, nsurf
         m = smallest_mass(nnode, minv, first(r + 1) - first(r), nodes(first(r):first(r + 1) - 1))
         if (m < m1) then
            m2 = m1
            m1 = m
            r1 = r
         else if (m < m2) then
            m2 = m
         end if
      end do
      do r = 1, nsurf
         call spring_dt(k, nnode, minv, first(r + 1) - first(r), nodes(first(r):first(r + 1) - 1), &
                        merge(m2, m1, r == r1), dt)
      end do
   end subroutine auto_spring_dt

end module exic_contact_penalty
