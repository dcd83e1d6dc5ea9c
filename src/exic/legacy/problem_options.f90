!> The legacy API: fixities, pair and handle options, friction, massless contact faces.
submodule(exic_legacy_problem) exic_legacy_problem_options
   implicit none

contains

   !> ifix(2, nnode): non-zero marks a dof the host prescribes (the corrector leaves it alone).
   module procedure problem_set_fixed
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         ierr = IERR_ARGUMENT
         return
      end if
      p%fixed = ifix
      call inverse_masses(p)
   end procedure problem_set_fixed

   !> New options iopt(4) = method, detection, passes, rigid master and penalty stiffness of
   !> pair ipair; the surfaces and passes are rebuilt at the current positions.
   module procedure problem_set_pair
      type(problem_t), pointer :: p
      integer, allocatable :: t(:, :)
      logical, allocatable :: any_surf(:), seg_surf(:)
      integer :: k, n
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         return
      end if
      t = pair_table(p)
      t(3:6, ipair) = iopt
      n = maxval(t(1:2, :))
      allocate (any_surf(n), seg_surf(n), source=.false.)
      do k = 1, size(p%spec%surfaces)
         if (p%spec%surfaces(k)%id > n) cycle
         any_surf(p%spec%surfaces(k)%id) = .true.
         seg_surf(p%spec%surfaces(k)%id) = p%spec%surfaces(k)%by /= SURF_NODES
      end do
      if (.not. pairs_ok(who, 1, t(:, ipair:ipair), [pen], any_surf, seg_surf, ipair)) then
         p%message = last_message(0)
         return
      end if
      call apply_pair_options(p, ipair, iopt, pen)
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) p%message = last_message(0)
   end procedure problem_set_pair

   !> Coulomb friction of pair ipair (doc/friction.md, eq. F12): static coefficient amus, dynamic
   !> amud <= amus, decay with slip speed (0: amus at rest, amud sliding); amus = 0 removes it.
   !> The contact object is rebuilt at the current positions, as for a change of pair options.
   module procedure problem_set_friction
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (ipair < 1 .or. ipair > p%npair) then
         call fail(h, who//': pair '//itoa(ipair)//' is outside 1..'//itoa(p%npair))
         return
      end if
      if (.not. (ieee_is_finite(amus) .and. ieee_is_finite(amud) .and. ieee_is_finite(decay))) then
         call fail(h, who//': the friction coefficients and the decay must be finite')
         return
      end if
      if (.not. (amus >= 0.0_wp .and. amud >= 0.0_wp .and. decay >= 0.0_wp .and. amud <= amus)) then
         call fail(h, who//': expected 0 <= AMUD <= AMUS and DECAY >= 0, got AMUS = '//rtoa(amus)// &
                   ', AMUD = '//rtoa(amud)//', DECAY = '//rtoa(decay))
         return
      end if
      p%spec%pairs(ipair)%mus = amus
      p%spec%pairs(ipair)%mud = amud
      p%spec%pairs(ipair)%decay = decay
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) p%message = last_message(0)
   end procedure problem_set_friction

   !> Handle options: OPT_VELOCITY_FORM = 1 (v~(n+1), default) or 2 (v(n+1/2)).
   module procedure problem_set_option
      type(problem_t), pointer :: p
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      select case (iopt)
      case (OPT_VELOCITY_FORM)
         if (ival /= VEL_FULL_STEP .and. ival /= VEL_HALF_STEP) then
            call fail(h, who//': velocity form '//itoa(ival)//' is neither 1 nor 2')
            return
         end if
         p%velocity_form = ival
         if (ival == VEL_HALF_STEP .and. .not. allocated(p%vt)) allocate (p%vt(2, p%nnode), source=0.0_wp)
      case default
         call fail(h, who//': unknown option '//itoa(iopt))
         return
      end select
      ierr = IERR_OK
   end procedure problem_set_option

   !> The massless contact faces of method-3 pairs (doc/impact.md, section 3; doc/api.md):
   !> mass(nnode) the host's lumped masses after it moved the face nodes' mass to their
   !> elements' other nodes (eq. I.3; > 0 off the face, ignored on it), iface(nf) the face
   !> nodes (surface nodes, neither rigid nor prescribed), irp(2 nf + 1), ici, val the rows of
   !> the host's initial stiffness for the face dofs in 1-based CSR (row 2 (k-1) + d for dof d of
   !> iface(k), columns the global dofs 2 (i-1) + d). The face block must be symmetric; it is
   !> factorized (SuiteSparse LDL) when the contact object is rebuilt here. Both dofs of a face
   !> node are massless.
   module procedure problem_set_face
      call set_face(who, h, nnode, spread(mass, 1, 2), nf, iface, spread(spread(1, 1, max(nf, 0)), 1, 2), &
                    irp, ici, val, ierr)
   end procedure problem_set_face

   !> problem_set_face with massless dofs per direction (doc/impact.md, eq. I.3a, I.3b):
   !> mass(2, nnode) the host's lumped masses per dof after the transfer of eq. I.3 per direction
   !> (> 0 on every dof with mass, ignored on the massless ones), ifdof(2, nf) 1 where dof d of
   !> iface(k) is massless, 0 where it keeps its mass (every face node has one massless dof at
   !> least); the rows of the dofs with mass are not read.
   module procedure problem_set_face_dofs
      call set_face(who, h, nnode, mass, nf, iface, ifdof, irp, ici, val, ierr)
   end procedure problem_set_face_dofs

   !> The massless dofs the deck's rule gives the handle's method-3 surfaces (doc/impact.md,
   !> section 3.1, eq. I.3a and I.3b, at the reference positions): ifdof(d, i) = 1 where dof d of
   !> node i is massless, 0 elsewhere. Rigid and prescribed nodes get none; built from
   !> connectivity, so do the dofs d of elements whose every node would be massless along d
   !> (bodies one element thick); a host that gave segments drops those itself.
   module procedure problem_face_rule
      type(problem_t), pointer :: p
      logical, allocatable :: dofs(:, :)
      integer :: e, d
      ifdof = 0
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      if (nnode /= p%nnode) then
         ierr = IERR_ARGUMENT
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         return
      end if
      dofs = p%contact%face_dofs(nnode, p%x0, p%rigid) .and. spread(p%contact%face_nodes(nnode) .and. &
             .not. p%rigid, 1, 2) .and. spread(all(p%fixed == 0, 1), 1, 2)
      do e = 1, p%nelem
         do d = 1, 2
            if (all(dofs(d, p%conn(:, e)))) dofs(d, p%conn(:, e)) = .false.
         end do
      end do
      ifdof = merge(1, 0, dofs)
   end procedure problem_face_rule

   !> Both set-ups of the face: mass(2, nnode) per dof, ifdof(2, nf) the massless dofs.
   subroutine set_face(who, h, nnode, mass, nf, iface, ifdof, irp, ici, val, ierr)
      character(len=*), intent(in) :: who
      integer, intent(in) :: h, nnode, nf
      real(wp), intent(in) :: mass(2, nnode)
      integer, intent(in) :: iface(max(nf, 0)), ifdof(2, max(nf, 0)), irp(2*max(nf, 0) + 1)
      integer, intent(in) :: ici(*)
      real(wp), intent(in) :: val(*)
      integer, intent(out) :: ierr
      type(problem_t), pointer :: p
      integer, allocatable :: rp(:), ci(:)
      real(wp), allocatable :: v(:), mass_old(:, :)
      character(len=:), allocatable :: msg
      integer :: k
      p => lookup(who, h, ierr)
      if (.not. associated(p)) return
      ierr = IERR_ARGUMENT
      if (nnode /= p%nnode) then
         call fail(h, who//': NNODE = '//itoa(nnode)//' differs from the '//itoa(p%nnode)//' of the handle')
         return
      end if
      call check_face(nnode, p%spos, p%rigid, p%fixed, mass, nf, iface, ifdof, irp, ici, val, rp, ci, v, msg)
      if (len(msg) > 0) then
         call fail(h, who//': '//msg)
         return
      end if
      mass_old = p%mass
      p%mass = mass
      p%face = iface
      p%ffree = ifdof == 1
      do k = 1, nf
         where (p%ffree(:, k)) p%mass(:, iface(k)) = 0.0_wp
      end do
      p%frp = rp
      p%fci = ci
      p%fval = v
      p%face_set = .true.
      if (.not. allocated(p%zero)) allocate (p%zero(2, nnode), source=0.0_wp)
      call rebuild(who, p, ierr)
      if (ierr /= IERR_OK) then
         ! a singular face block: the handle stays as it was
         p%message = last_message(0)
         p%face_set = .false.
         p%mass = mass_old
         call rebuild(who, p, k)
         ierr = IERR_SETUP
      end if
   end subroutine set_face

end submodule exic_legacy_problem_options
