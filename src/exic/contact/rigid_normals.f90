!> Contact normals of rigid slave nodes (doc/contact-detection.md, "A rigid node meeting a
!> deformable face"): the force between a frictionless rigid face and a body acts along the
!> face's normal, so a node of a smooth stretch of a rigid surface that meets a deformable
!> segment takes its own surface's outward normal, reversed, as the constraint normal. The
!> deformable segment's normal is tilted by the indentation of its nodes, and where a node of
!> each body meets the other's head-on that tilt gave a frictionless wall a tangential push.
module exic_contact_rigid_normals
   use exic_base_kinds, only: wp
   use exic_contact_detect, only: contact_set_t
   implicit none
   private

   public :: smooth_rigid, own_normals

   !> A rigid surface node is smooth where its two segments turn by less than this (degrees);
   !> at a sharper corner (a punch's) the deformable segment's normal stays.
   real(wp), parameter :: SMOOTH_TURN = 30.0_wp

contains

   !> own(p) for the ns nodes of a surface of nseg segments (seg, positions `where` of their
   !> nodes in `nodes`): node p is of a rigid body and its two segments turn by less than
   !> SMOOTH_TURN in the configuration x (a rigid body keeps its angles). True when some node is.
   function smooth_rigid(nseg, seg, where, ns, nodes, nnode, x, rigid, own) result(any_own)
      integer, intent(in) :: nseg, ns, nnode
      integer, intent(in) :: seg(2, nseg), where(2, nseg), nodes(ns)
      real(wp), intent(in) :: x(2, nnode)
      logical, intent(in) :: rigid(nnode)
      logical, allocatable, intent(out) :: own(:)
      logical :: any_own
      real(wp) :: t1(2, ns), t2(2, ns), t(2), cmin
      integer :: cnt(ns), k, e, p
      any_own = .false.
      if (.not. any(rigid(nodes))) return
      t1 = 0.0_wp
      t2 = 0.0_wp
      cnt = 0
      do k = 1, nseg
         t = x(:, seg(2, k)) - x(:, seg(1, k))
         t = t/max(norm2(t), tiny(1.0_wp))
         do e = 1, 2
            p = where(e, k)
            cnt(p) = cnt(p) + 1
            if (cnt(p) == 1) then
               t1(:, p) = t
            else
               t2(:, p) = t
            end if
         end do
      end do
      cmin = cos(SMOOTH_TURN*acos(-1.0_wp)/180.0_wp)
      allocate (own(ns))
      do p = 1, ns
         own(p) = rigid(nodes(p)) .and. cnt(p) == 2 .and. dot_product(t1(:, p), t2(:, p)) >= cmin
      end do
      any_own = any(own)
   end function smooth_rigid

   !> For each contact of `hits` whose slave is a smooth rigid node (own, over the ns sorted
   !> `nodes` of the slave surface, with their outward normals nrm) and whose master segment is
   !> not rigid: the normal -nrm of the slave and the predicted gap along it at x1 (eq. 3.19).
   subroutine own_normals(hits, ns, nodes, own, nrm, rigid, nnode, x1)
      type(contact_set_t), intent(inout) :: hits
      integer, intent(in) :: ns, nnode
      integer, intent(in) :: nodes(ns)
      logical, intent(in) :: own(ns), rigid(nnode)
      real(wp), intent(in) :: nrm(2, ns), x1(2, nnode)
      integer :: j, p, node, m1, m2
      real(wp) :: n(2), al
      do j = 1, hits%n
         node = hits%slave(j)
         m1 = hits%master(1, j)
         m2 = hits%master(2, j)
         if (rigid(m1) .and. rigid(m2)) cycle
         p = position(nodes, node)
         if (p == 0) cycle
         if (.not. own(p)) cycle
         n = -nrm(:, p)
         if (all(n == 0.0_wp)) cycle
         al = hits%alpha(j)
         hits%normal(:, j) = n
         hits%gap(j) = dot_product(x1(:, node) - ((1.0_wp - al)*x1(:, m1) + al*x1(:, m2)), n)
      end do
   end subroutine own_normals

   !> Index of v in the sorted list a, 0 if absent.
   pure integer function position(a, v) result(k)
      integer, intent(in) :: a(:), v
      integer :: lo, hi
      lo = 1
      hi = size(a)
      do while (lo <= hi)
         k = (lo + hi)/2
         if (a(k) == v) return
         if (a(k) < v) then
            lo = k + 1
         else
            hi = k - 1
         end if
      end do
      k = 0
   end function position

end module exic_contact_rigid_normals
