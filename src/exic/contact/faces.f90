!> Massless contact faces of `LAGRange,ENERgy` in the contact step (doc/impact.md, section 3):
!> which nodes and dofs of the surfaces are massless (eq. I.3a, I.3b) and the corrector's solve
!> with the face compliance, whose candidate set is completed by detecting again on the
!> corrected positions (section 3.3, step 5).
submodule(exic_contact_contact) exic_contact_faces
   use exic_contact_face_rule, only: facing_dofs
   use exic_mesh_boundary, only: normal_dofs
   implicit none

   !> Detections on the corrected positions per step at most (doc/impact.md, section 3.3):
   !> each adds the candidates the face's correction carried across a segment; the bar and
   !> disk families need one.
   integer, parameter :: MAX_REDETECT = 4

contains

   !> The corrector's solve of a step with massless faces (eq. I.6, I.7), then detection again
   !> on the corrected positions x(n+2) = x~(n+2) + c (a - a~) (doc/impact.md, section 3.3,
   !> step 5): the face correction K_FF^-1 G_F p moves every face node, the candidates' neighbours
   !> too, and can carry a node that the search of the predicted positions did not find across a
   !> segment. Every hit of that search whose slave node has no candidate of its pair yet is added
   !> with its predicted gap at x~(n+2) (eq. 3.19, the normal and alpha of the new hit) and the
   !> problem is solved again from a~, until a search adds nothing (MAX_REDETECT at most).
   !> x = x(n+1); a holds a~(n+1) after the face's free solve on entry and a(n+1) on exit.
   module procedure face_solve
      real(wp), allocatable :: a0(:, :), f0(:, :), xt(:, :)
      real(wp) :: g, gnow
      integer :: it, k, j, node, m, nnew

      a0 = a
      f0 = fcon
      xt = self%xp
      do it = 0, MAX_REDETECT
         call self%corr%solve(self%cs, nnode, minv, c, a, fcon, err, rb, self%face)
         if (allocated(err) .or. it == MAX_REDETECT) exit
         if (.not. any(self%cs%p(1:self%cs%n) > 0.0_wp)) exit
         ! the corrected positions at t(n+2), searched from x(n+1) as the predicted ones were
         ! (the broad phase of PAIR passes again; AUTOmatic passes keep the candidates of the
         ! predicted positions, found within the search depth); normals formed anew
         self%xp = xt + c*(a - a0)
         self%stamp = self%stamp + 1
         call narrow_passes(self, nnode, x, minv, 1, self%npass)
         m = self%cs%n
         nnew = 0
         do k = 1, self%npass
            associate (ps => self%passes(k))
               if (ps%method /= METHOD_LAGRANGE .or. ps%broad%ncand == 0) cycle
               do j = 1, ps%hits%n
                  node = ps%hits%slave(j)
                  if (any(self%cs%node(1, 1:m) == node .and. self%cs%pair(1:m) == ps%pair)) cycle
                  associate (m1 => ps%hits%master(1, j), m2 => ps%hits%master(2, j), &
                             al => ps%hits%alpha(j), nr => ps%hits%normal(:, j))
                     g = dot_product(xt(:, node) - (1.0_wp - al)*xt(:, m1) - al*xt(:, m2), nr)
                     gnow = dot_product(x(:, node) - (1.0_wp - al)*x(:, m1) - al*x(:, m2), nr)
                     call self%cs%add(node, m1, m2, al, nr, g, gnow, ps%pair)
                  end associate
                  nnew = nnew + 1
               end do
            end associate
         end do
         if (nnew == 0) exit
         a = a0
         fcon = f0
      end do
      self%xp = xt
   end procedure face_solve

   !> Nodes of the surfaces (slave and master) of the passes that ask for LAGRange,ENERgy: the
   !> candidates for massless faces (doc/impact.md, section 3.1; the caller removes rigid and
   !> prescribed nodes and those of elements that would keep no mass).
   module procedure contact_face_nodes
      integer :: k
      on = .false.
      if (.not. self%active) return
      do k = 1, self%nfixed
         if (.not. self%passes(k)%energy) cycle
         on(self%surfaces(self%passes(k)%slave)%nodes) = .true.
         on(self%surfaces(self%passes(k)%master)%nodes) = .true.
      end do
      ! AUTOmatic: every one of its surfaces can meet another one
      if (self%auto_pass%auto .and. self%auto_pass%energy) then
         do k = self%auto_first + 1, self%auto_first + self%auto%nsurf
            on(self%surfaces(k)%nodes) = .true.
         end do
      end if
   end procedure contact_face_nodes

   !> The massless dofs of the surfaces of the passes that ask for LAGRange,ENERgy, at the
   !> positions x (doc/impact.md, section 3.1); rigid(nnode): the nodes of rigid bodies. A surface
   !> that meets a deformable body (a partner surface with a node not in `rigid`) is massless
   !> along its normals only: dofs(d, i) when a segment at node i has a normal n with
   !> |n_d| >= |n_other| (eq. I.3a; a node where the surface turns, a body's corner, gets both).
   !> Against rigid bodies only, the segments that face a partner (eq. I.3b) are massless so.
   module procedure contact_face_dofs
      ! per surface: 0 no ENERgy pass, 1 every partner rigid, 2 a deformable partner
      integer :: meets(size(self%surfaces))
      logical :: pairs(size(self%surfaces), size(self%surfaces))   ! (k, m): m is a partner of k
      integer :: k, s, m, ndef
      dofs = .false.
      if (.not. self%active) return
      meets = 0
      pairs = .false.
      do k = 1, self%nfixed
         if (.not. self%passes(k)%energy) cycle
         s = self%passes(k)%slave
         m = self%passes(k)%master
         meets(s) = max(meets(s), merge(2, 1, deformable(m)))
         meets(m) = max(meets(m), merge(2, 1, deformable(s)))
         pairs(s, m) = .true.
         pairs(m, s) = .true.
      end do
      if (self%auto_pass%auto .and. self%auto_pass%energy) then
         ! AUTOmatic: every one of its surfaces can meet every other one
         ndef = 0
         do k = self%auto_first + 1, self%auto_first + self%auto%nsurf
            if (deformable(k)) ndef = ndef + 1
         end do
         do k = self%auto_first + 1, self%auto_first + self%auto%nsurf
            meets(k) = max(meets(k), merge(2, 1, ndef - merge(1, 0, deformable(k)) > 0))
            pairs(k, self%auto_first + 1:self%auto_first + self%auto%nsurf) = .true.
         end do
      end if
      do k = 1, size(self%surfaces)
         if (meets(k) == 2) call normal_dofs(nnode, x, self%surfaces(k)%nseg, self%surfaces(k)%seg, dofs)
         do m = 1, size(self%surfaces)
            if (meets(k) == 1 .and. pairs(k, m) .and. m /= k) call facing_dofs(nnode, x, self%surfaces(k)%nseg, &
                                            self%surfaces(k)%seg, self%surfaces(m)%nseg, self%surfaces(m)%seg, dofs)
         end do
      end do
   contains
      logical function deformable(k)
         integer, intent(in) :: k
         deformable = .not. all(rigid(self%surfaces(k)%nodes))
      end function deformable
   end procedure contact_face_dofs

end submodule exic_contact_faces
