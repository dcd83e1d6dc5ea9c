!> What a deck asks for in loads and prescribed motion (doc/loads.md), and the kernels that turn
!> it into nodal values: the FEAP proportional (load-time) functions with their derivatives, and
!> the consistent nodal forces of edge loads on the current geometry.
!>
!> `load_spec_t` is filled by the deck reader (src/exic/input/deck/loads.f90) with everything
!> resolved to nodes and edges; the stepper receives it at `init` (src/exic/explicit/loading.f90).
!> Body forces (`BODY`) and free rigid bodies (`RIGId,FREE`) are material data (material_t).
module exic_explicit_loads
   use exic_base_kinds, only: wp
   implicit none
   private

   public :: prop_fn_t, motion_t, load_spec_t
   public :: prop_eval, prop_value, edge_forces

   integer, parameter, public :: FN_UNDEFINED = 0, FN_TYPE1 = 1, FN_TABLE = 2, FN_RAMP = 3
   integer, parameter, public :: EDGE_NORMAL = 1, EDGE_TANGENTIAL = 2

   !> One proportional function (FEAP PROPortional):
   !> type 1: a1 + a2 (t - tmin) + a3 sin^k(a4 (t - tmin)) on [tmin, tmax], 0 outside;
   !> table: linear between (t, p) points, constant beyond the ends, a repeated time a jump;
   !> ramp (a blank record): p = t for t >= 0.
   type :: prop_fn_t
      integer :: kind = FN_UNDEFINED
      integer :: k = 0
      real(wp) :: tmin = 0.0_wp, tmax = 0.0_wp
      real(wp) :: a(4) = 0.0_wp
      real(wp), allocatable :: tab(:, :)         !< (2, n): t, p in non-decreasing t
      character(len=:), allocatable :: where     !< file:line of its first record
   end type prop_fn_t

   !> MOTIon,REGIon,r,vx,vy,omega,prop: a region driven at a velocity (and, rigid, an angular
   !> velocity about its centroid) times function `prop`.
   type :: motion_t
      integer :: region = 0
      real(wp) :: v(2) = 0.0_wp
      real(wp) :: omega = 0.0_wp
      integer :: prop = 0
      logical :: rigid = .false.                 !< the region is a (fixed) RIGId body
      character(len=:), allocatable :: where
   end type motion_t

   !> Loads and prescribed motion of a model, resolved to nodes and edges.
   type :: load_spec_t
      type(prop_fn_t), allocatable :: fn(:)      !< proportional functions by number
      integer, allocatable :: fpro(:, :)         !< (2, nnode) function of each dof, 0: the sum
      logical :: has_gravity = .false.
      real(wp) :: gravity(2) = 0.0_wp            !< GRAVity acceleration
      integer :: gravity_prop = 0                !< its function (0: the sum)
      integer :: nedge = 0
      integer, allocatable :: edge(:, :)         !< (2, nedge) nodes, the element on the left
      integer, allocatable :: edge_kind(:)       !< (nedge) EDGE_NORMAL | EDGE_TANGENTIAL
      real(wp), allocatable :: edge_value(:, :)  !< (2, nedge) value at each node (p, or q x sign)
      type(motion_t), allocatable :: motions(:)
   end type load_spec_t

contains

   !> Value, first and second derivative of function `f` at time t (doc/loads.md, section 1).
   pure subroutine prop_eval(f, t, p, dp, ddp)
      type(prop_fn_t), intent(in) :: f
      real(wp), intent(in) :: t
      real(wp), intent(out) :: p, dp, ddp
      real(wp) :: tau, s, co, w
      integer :: j, n
      p = 0.0_wp
      dp = 0.0_wp
      ddp = 0.0_wp
      select case (f%kind)
      case (FN_RAMP)
         if (t >= 0.0_wp) then
            p = t
            dp = 1.0_wp
         end if
      case (FN_TYPE1)
         if (t < f%tmin .or. t > f%tmax) return
         tau = t - f%tmin
         s = sin(f%a(4)*tau)
         co = cos(f%a(4)*tau)
         p = f%a(1) + f%a(2)*tau + f%a(3)*s**f%k
         dp = f%a(2)
         if (f%k >= 1) dp = dp + f%a(3)*f%a(4)*real(f%k, wp)*s**(f%k - 1)*co
         if (f%k == 1) then
            ddp = -f%a(3)*f%a(4)**2*s
         else if (f%k >= 2) then
            ddp = f%a(3)*f%a(4)**2*real(f%k, wp)*(real(f%k - 1, wp)*s**(f%k - 2)*co*co - s**f%k)
         end if
      case (FN_TABLE)
         n = size(f%tab, 2)
         if (t <= f%tab(1, 1)) then
            p = f%tab(2, 1)
            return
         end if
         if (t > f%tab(1, n)) then
            p = f%tab(2, n)
            return
         end if
         ! the interval (t_j, t_j+1] that holds t: at a jump the first value holds at its time
         do j = 1, n - 1
            if (t <= f%tab(1, j + 1)) exit
         end do
         w = f%tab(1, j + 1) - f%tab(1, j)
         if (w > 0.0_wp) then
            dp = (f%tab(2, j + 1) - f%tab(2, j))/w
            p = f%tab(2, j) + dp*(t - f%tab(1, j))
            if (t == f%tab(1, j + 1)) p = f%tab(2, j + 1)
         else
            p = f%tab(2, j)
         end if
      end select
   end subroutine prop_eval

   !> Function number `id` of `fn` at t with its derivatives; id = 0 is the sum of all functions,
   !> 1 (and derivatives 0) when there are none (FEAP's rule).
   pure subroutine prop_value(fn, id, t, p, dp, ddp)
      type(prop_fn_t), intent(in) :: fn(:)
      integer, intent(in) :: id
      real(wp), intent(in) :: t
      real(wp), intent(out) :: p, dp, ddp
      real(wp) :: q, dq, ddq
      integer :: j
      if (id > 0) then
         call prop_eval(fn(id), t, p, dp, ddp)
         return
      end if
      p = 0.0_wp
      dp = 0.0_wp
      ddp = 0.0_wp
      if (count(fn%kind /= FN_UNDEFINED) == 0) then
         p = 1.0_wp
         return
      end if
      do j = 1, size(fn)
         if (fn(j)%kind == FN_UNDEFINED) cycle
         call prop_eval(fn(j), t, q, dq, ddq)
         p = p + q
         dp = dp + dq
         ddp = ddp + ddq
      end do
   end subroutine prop_value

   !> Add the consistent nodal forces of the edge loads on the current geometry x(2, nnode) to
   !> f(2, nnode) (doc/loads.md, section 2): for edge (a, b) with t = x_b - x_a, N = (t_y, -t_x)
   !> and values (v_a, v_b),
   !>   NORMal (pressure into the body):  f_a -= (2 v_a + v_b)/6 N,  f_b -= (v_a + 2 v_b)/6 N;
   !>   TANGential (traction along t):    f_a += (2 v_a + v_b)/6 t,  f_b += (v_a + 2 v_b)/6 t.
   !> axi (GLOBal AXISymmetric): the forces per radian, int N_a v r ds with the current radii
   !> r = x (doc/axisymmetry.md, (A6)).
   pure subroutine edge_forces(nedge, nnode, edge, kind, val, x, f, axi)
      integer, intent(in) :: nedge, nnode
      integer, intent(in) :: edge(2, nedge), kind(nedge)
      real(wp), intent(in) :: val(2, nedge), x(2, nnode)
      real(wp), intent(inout) :: f(2, nnode)
      logical, intent(in), optional :: axi
      real(wp) :: t(2), d(2), ca, cb, ra, rb, va, vb
      integer :: e, a, b
      logical :: ax
      ax = .false.
      if (present(axi)) ax = axi
      do e = 1, nedge
         a = edge(1, e)
         b = edge(2, e)
         t = x(:, b) - x(:, a)
         if (ax) then
            ra = x(1, a)
            rb = x(1, b)
            va = val(1, e)
            vb = val(2, e)
            ca = (3.0_wp*va*ra + va*rb + vb*ra + vb*rb)/12.0_wp
            cb = (3.0_wp*vb*rb + vb*ra + va*rb + va*ra)/12.0_wp
         else
            ca = (2.0_wp*val(1, e) + val(2, e))/6.0_wp
            cb = (val(1, e) + 2.0_wp*val(2, e))/6.0_wp
         end if
         if (kind(e) == EDGE_NORMAL) then
            d = [-t(2), t(1)]             ! -N: into the body
         else
            d = t
         end if
         f(:, a) = f(:, a) + ca*d
         f(:, b) = f(:, b) + cb*d
      end do
   end subroutine edge_forces

end module exic_explicit_loads
