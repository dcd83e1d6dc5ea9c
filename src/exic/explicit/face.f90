!> Set-up of the massless contact faces of `LAGRange,ENERgy` (doc/impact.md, section 3.1-3.2):
!> which nodes lose their mass, the mass transfer of eq. I.3 and the rows of the initial
!> stiffness K0 for the face dofs, handed to the contact's `massless_face_t`, which factorizes
!> their face block.
module exic_explicit_face
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_base_grow, only: grow
   use exic_material_material, only: MAT_SOLID
   use exic_element_quad4, only: q4_force_2x2, q4_force_1pt, q4_lumped_mass
   use exic_contact_contact, only: contact_t
   use exic_explicit_state, only: state_t, element_set_t
   implicit none
   private

   public :: face_setup, face_refresh, to_csr

   !> Central-difference step of the stiffness columns, as a share of the element's size.
   real(wp), parameter :: FD_SHARE = 1.0e-6_wp
   !> The face rows are formed again, at the current displacements, when the displacement
   !> gradient of a face element has changed by more than this since they were last formed
   !> (doc/impact.md, section 3.2).
   real(wp), parameter :: REFRESH_STRAIN = 0.02_wp

contains

   !> Face nodes of the ENERgy pairs of `contact`, massless along their normals (doc/impact.md,
   !> section 3.1): mass moved per direction (eq. I.3), st%mass, st%mass_dof and st%minv
   !> updated, K0's face rows assembled and contact%face set up. nface: face nodes (a massless
   !> dof or two); ndof: their massless dofs; nkept: surface nodes that keep their mass (elements
   !> that would keep no mass, rigid or prescribed).
   subroutine face_setup(st, sets, contact, nface, ndof, nkept, err)
      type(state_t), intent(inout) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(contact_t), intent(inout) :: contact
      integer, intent(out) :: nface, ndof, nkept
      type(error_t), allocatable, intent(out) :: err
      logical, allocatable :: cand(:), face(:), dofs(:, :)
      integer, allocatable :: fidx(:), node(:), rp(:), ci(:)
      real(wp), allocatable :: val(:), mass(:, :), u0(:, :)
      integer :: k, e, i, nn, a, d
      integer :: conn_l(4, 1)
      real(wp) :: xe(2, 4), me(4), moved, keep

      nn = st%nnode
      cand = contact%face_nodes(nn)
      cand = cand .and. st%active .and. .not. st%rigid .and. st%minv(1, :) > 0.0_wp .and. &
             st%minv(2, :) > 0.0_wp
      ! massless along the normals of a face that meets a deformable body (eq. I.3a), along
      ! both dofs against rigid bodies only
      dofs = contact%face_dofs(nn, st%x0, st%rigid) .and. spread(cand, 1, 2)
      ! an element whose nodes are all massless along d keeps them massive along d (bodies one
      ! element thick)
      do k = 1, size(sets)
         if (sets(k)%kind /= MAT_SOLID) cycle
         do e = 1, sets(k)%nel
            do d = 1, 2
               if (all(dofs(d, sets(k)%conn(:, e)))) dofs(d, sets(k)%conn(:, e)) = .false.
            end do
         end do
      end do
      face = dofs(1, :) .or. dofs(2, :)
      nkept = count(contact%face_nodes(nn)) - count(face)
      nface = count(face)
      ndof = count(dofs)
      allocate (fidx(nn), source=0)
      node = pack([(i, i=1, nn)], face)
      do i = 1, nface
         fidx(node(i)) = i
      end do
      conn_l(:, 1) = [1, 2, 3, 4]
      ! mass transfer (eq. I.3), per direction: dof d of a face node gives its element mass to
      ! dof d of the element's nodes that keep theirs
      mass = spread(st%mass, 1, 2)
      do k = 1, size(sets)
         if (sets(k)%kind /= MAT_SOLID) cycle
         associate (s => sets(k))
            do e = 1, s%nel
               if (.not. any(face(s%conn(:, e)))) cycle
               xe = st%x0(:, s%conn(:, e))
               me = 0.0_wp
               call q4_lumped_mass(1, 4, conn_l, xe, s%rho, me)
               do d = 1, 2
                  moved = sum(me, mask=dofs(d, s%conn(:, e)))
                  if (moved == 0.0_wp) cycle
                  keep = sum(me, mask=.not. dofs(d, s%conn(:, e)))
                  do a = 1, 4
                     i = s%conn(a, e)
                     if (dofs(d, i)) then
                        mass(d, i) = mass(d, i) - me(a)
                     else
                        mass(d, i) = mass(d, i) + moved*me(a)/keep
                     end if
                  end do
               end do
            end do
         end associate
      end do
      ! K0's face rows: the stiffness at the reference state
      u0 = 0.0_wp*st%x0
      call face_rows(st, sets, fidx, nface, u0, rp, ci, val)
      ! the masses per dof, where a node keeps its mass along one dof only
      if (any(dofs(1, :) .neqv. dofs(2, :))) st%mass_dof = spread(st%mass, 1, 2)
      do i = 1, nn
         do d = 1, 2
            if (dofs(d, i)) then
               mass(d, i) = 0.0_wp
               st%minv(d, i) = 0.0_wp
            else if (mass(d, i) /= st%mass(i)) then
               if (st%minv(d, i) > 0.0_wp) st%minv(d, i) = 1.0_wp/mass(d, i)
            end if
         end do
         if (allocated(st%mass_dof)) then
            st%mass_dof(:, i) = mass(:, i)
            st%mass(i) = 0.5_wp*(mass(1, i) + mass(2, i))
         else
            st%mass(i) = mass(1, i)
         end if
      end do
      call contact%face%init(nn, nface, node, rp, ci, val, err, dofs(:, node))
   end subroutine face_setup

   !> The face rows (row 2 (f-1) + d for dof d of face node f = fidx(i) > 0, columns the global
   !> dofs, CSR) of the stiffness of the elements with a face node, at the displacements u.
   subroutine face_rows(st, sets, fidx, nface, u, rp, ci, val)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: fidx(:), nface
      real(wp), intent(in) :: u(:, :)
      integer, allocatable, intent(out) :: rp(:), ci(:)
      real(wp), allocatable, intent(out) :: val(:)
      integer, allocatable :: rows(:, :)
      real(wp), allocatable :: vals(:)
      integer :: k, e, ncoo, a, b, d, dd, r, f
      real(wp) :: ke(8, 8)
      ncoo = 0
      do k = 1, size(sets)
         if (sets(k)%kind /= MAT_SOLID) cycle
         associate (s => sets(k))
            do e = 1, s%nel
               if (all(fidx(s%conn(:, e)) == 0)) cycle
               call element_stiffness(s, st%x0(:, s%conn(:, e)), u(:, s%conn(:, e)), ke)
               call grow(rows, ncoo + 64, 2)
               call grow(vals, ncoo + 64)
               do a = 1, 4
                  f = fidx(s%conn(a, e))
                  if (f == 0) cycle
                  do d = 1, 2
                     r = 2*(f - 1) + d
                     do b = 1, 4
                        do dd = 1, 2
                           ncoo = ncoo + 1
                           rows(:, ncoo) = [r, 2*(s%conn(b, e) - 1) + dd]
                           vals(ncoo) = ke(2*(a - 1) + d, 2*(b - 1) + dd)
                        end do
                     end do
                  end do
               end do
            end do
         end associate
      end do
      call to_csr(2*nface, ncoo, rows, vals, rp, ci, val)
   end subroutine face_rows

   !> Before the contact step of a run with massless faces: when the displacement gradient of a
   !> face element (at its centre) has changed by more than REFRESH_STRAIN since the face rows
   !> were formed, form them again at the current displacements st%u (the tangent stiffness)
   !> and factorize K_FF again (doc/impact.md, section 3.2). Small-strain runs never refresh.
   subroutine face_refresh(st, sets, contact, err)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      type(contact_t), intent(inout) :: contact
      type(error_t), allocatable, intent(out) :: err
      integer, allocatable :: rp(:), ci(:)
      real(wp), allocatable :: val(:)
      if (.not. contact%face%active) return
      if (.not. strained(st, sets, contact%face%fidx, contact%face%uref)) return
      call face_rows(st, sets, contact%face%fidx, contact%face%nf, st%u, rp, ci, val)
      call contact%face%update(val, st%u, err)
   end subroutine face_refresh

   !> Some face element's displacement gradient at its centre, of u - uref, has an entry above
   !> REFRESH_STRAIN.
   logical function strained(st, sets, fidx, uref) result(yes)
      type(state_t), intent(in) :: st
      type(element_set_t), intent(in) :: sets(:)
      integer, intent(in) :: fidx(:)
      real(wp), intent(in) :: uref(:, :)
      real(wp), parameter :: dxi(4) = [-0.25_wp, 0.25_wp, 0.25_wp, -0.25_wp], &
                             deta(4) = [-0.25_wp, -0.25_wp, 0.25_wp, 0.25_wp]
      real(wp) :: xe(2, 4), du(2, 4), jac(2, 2), gxi(2, 2), g(2, 2), det
      integer :: k, e
      yes = .false.
      do k = 1, size(sets)
         if (sets(k)%kind /= MAT_SOLID) cycle
         associate (s => sets(k))
            do e = 1, s%nel
               if (all(fidx(s%conn(:, e)) == 0)) cycle
               xe = st%x0(:, s%conn(:, e))
               du = st%u(:, s%conn(:, e)) - uref(:, s%conn(:, e))
               ! columns d/dxi, d/deta of x and of u at the centre; grad u = gxi jac^-1
               jac(:, 1) = matmul(xe, dxi)
               jac(:, 2) = matmul(xe, deta)
               gxi(:, 1) = matmul(du, dxi)
               gxi(:, 2) = matmul(du, deta)
               det = jac(1, 1)*jac(2, 2) - jac(1, 2)*jac(2, 1)
               g(:, 1) = (gxi(:, 1)*jac(2, 2) - gxi(:, 2)*jac(2, 1))/det
               g(:, 2) = (gxi(:, 2)*jac(1, 1) - gxi(:, 1)*jac(1, 2))/det
               if (maxval(abs(g)) > REFRESH_STRAIN) then
                  yes = .true.
                  return
               end if
            end do
         end associate
      end do
   end function strained

   !> The stiffness of one element (reference coordinates xe) at the displacements ue by central
   !> differences of its own force kernel (doc/impact.md, section 3.2), symmetrized: at ue = 0
   !> the initial stiffness K0, elsewhere the tangent.
   subroutine element_stiffness(s, xe, ue, ke)
      type(element_set_t), intent(in) :: s
      real(wp), intent(in) :: xe(2, 4), ue(2, 4)
      real(wp), intent(out) :: ke(8, 8)
      real(wp) :: u(2, 4), fp(2, 4), fm(2, 4), h, w, whg, jmin, dt2
      integer :: j, conn_l(4, 1), eb, em, ef
      conn_l(:, 1) = [1, 2, 3, 4]
      h = FD_SHARE*max(maxval(xe(1, :)) - minval(xe(1, :)), maxval(xe(2, :)) - minval(xe(2, :)))
      do j = 1, 8
         u = ue
         u(mod(j - 1, 2) + 1, (j + 1)/2) = ue(mod(j - 1, 2) + 1, (j + 1)/2) + h
         fp = 0.0_wp
         fm = 0.0_wp
         if (s%nq == 2) then
            call q4_force_2x2(1, 4, conn_l, xe, u, s%law, fp, w, jmin, eb, dt2, em, ef)
            u(mod(j - 1, 2) + 1, (j + 1)/2) = ue(mod(j - 1, 2) + 1, (j + 1)/2) - h
            call q4_force_2x2(1, 4, conn_l, xe, u, s%law, fm, w, jmin, eb, dt2, em, ef)
         else
            call q4_force_1pt(1, 4, conn_l, xe, u, s%law, s%hourglass, fp, w, whg, jmin, &
                              eb, dt2, em, ef, s%hgkind)
            u(mod(j - 1, 2) + 1, (j + 1)/2) = ue(mod(j - 1, 2) + 1, (j + 1)/2) - h
            call q4_force_1pt(1, 4, conn_l, xe, u, s%law, s%hourglass, fm, w, whg, jmin, &
                              eb, dt2, em, ef, s%hgkind)
         end if
         ke(:, j) = reshape(fp - fm, [8])/(2.0_wp*h)
      end do
      ke = 0.5_wp*(ke + transpose(ke))
   end subroutine element_stiffness

   !> Triplets (rows(1, :) row, rows(2, :) column, vals) into CSR with sorted, merged columns.
   subroutine to_csr(nrow, n, rows, vals, rp, ci, val)
      integer, intent(in) :: nrow, n, rows(:, :)
      real(wp), intent(in) :: vals(:)
      integer, allocatable, intent(out) :: rp(:), ci(:)
      real(wp), allocatable, intent(out) :: val(:)
      integer, allocatable :: cnt(:), pos(:), tc(:)
      real(wp), allocatable :: tv(:)
      integer :: k, r, j, l, q, nnz
      allocate (cnt(nrow + 1), source=0)
      do k = 1, n
         cnt(rows(1, k) + 1) = cnt(rows(1, k) + 1) + 1
      end do
      cnt(1) = 1
      do r = 1, nrow
         cnt(r + 1) = cnt(r + 1) + cnt(r)
      end do
      pos = cnt
      allocate (tc(n), tv(n))
      do k = 1, n
         r = rows(1, k)
         tc(pos(r)) = rows(2, k)
         tv(pos(r)) = vals(k)
         pos(r) = pos(r) + 1
      end do
      allocate (rp(nrow + 1), ci(n), val(n))
      nnz = 0
      rp(1) = 1
      do r = 1, nrow
         ! insertion sort of the row by column, then merge equal columns
         do j = cnt(r) + 1, cnt(r + 1) - 1
            l = j
            do while (l > cnt(r))
               if (tc(l - 1) <= tc(l)) exit
               call swap(l - 1, l)
               l = l - 1
            end do
         end do
         do q = cnt(r), cnt(r + 1) - 1
            if (nnz >= rp(r)) then
               if (ci(nnz) == tc(q)) then
                  val(nnz) = val(nnz) + tv(q)
                  cycle
               end if
            end if
            nnz = nnz + 1
            ci(nnz) = tc(q)
            val(nnz) = tv(q)
         end do
         rp(r + 1) = nnz + 1
      end do
      ci = ci(1:nnz)
      val = val(1:nnz)
   contains
      subroutine swap(i, j)
         integer, intent(in) :: i, j
         integer :: ti
         real(wp) :: tr
         ti = tc(i)
         tc(i) = tc(j)
         tc(j) = ti
         tr = tv(i)
         tv(i) = tv(j)
         tv(j) = tr
      end subroutine swap
   end subroutine to_csr

end module exic_explicit_face
