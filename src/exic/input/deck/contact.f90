!> The CONTact ... END CONTact block of a deck (input language, section 4), parsed into a
!> contact_spec_t. Surfaces are only described here; their edges are built later.
!>
!> Records (blank records are skipped, except that a blank ends a FACEts list):
!> `SURFace,id` then one of `REGIon,r` | `MATErial,m` | `FACEts` + records `f, ng, n1, n2`
!> (gaps generated as for ELEMents: copies of the previous facet with non-zero nodes + ng) |
!> **[ext]** `PHYSical,c` (the edges of edge set c, a Gmsh physical curve, resolved after END);
!> `PAIR,id,NTOS|SYMMetric,s,m` | `PAIR,id,SELF,s`; `AUTOmatic`; method records after a PAIR
!> or AUTOmatic: `LAGRange`, `LAGRange,ENERgy` (massless contact faces, doc/impact.md),
!> `PENAlty,k`, `PENAlty,SCALe,f` (f defaults to 0.1), `DETEction,SWEPt|STATic`,
!> `FRICtion,COULomb,mu` | `FRICtion,COULomb,mus,mud[,decay]` (doc/friction.md). `END CONTact`
!> (or `END`) closes the block.
!>
!> A field that a PAIR or method record does not use is an error (`PAIR,1,NTOS,1,2,FRIC,0.3`
!> would otherwise run without friction); `LAGRange,ENERgy` together with Coulomb friction
!> (mus > 0) on the same pair is refused (the massless faces are not coupled to the tangential
!> problem).
module exic_input_deck_contact
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_grow, only: grow
   use exic_input_deck_grow, only: grow
   use exic_contact_spec, only: contact_spec_t, surface_spec_t, pair_spec_t, SURF_REGION, &
                                SURF_MATERIAL, SURF_FACETS, PAIR_NTOS, PAIR_SYMMETRIC, PAIR_SELF, &
                                METHOD_LAGRANGE, METHOD_PENALTY, DETECT_SWEPT, DETECT_STATIC
   use exic_input_deck_records, only: keyword_is
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: reader_t, next_record, field, word, has_field, real_field, int_field, &
                             fail, where, end_set, unknown_keyword, itoa, nfields, &
                             check_data_record, no_more_fields
   implicit none
   private

   public :: cmd_contact

   character(len=12), parameter :: words(11) = [character(len=12) :: 'SURFace', 'REGIon', &
                                                'MATErial', 'FACEts', 'PAIR', 'AUTOmatic', &
                                                'LAGRange', 'PENAlty', 'DETEction', 'PHYSical', &
                                                'FRICtion']

contains

   !> Read the block opened by the CONTact record `icmd` into `spec`.
   subroutine cmd_contact(rd, icmd, spec, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: icmd
      type(contact_spec_t), intent(inout) :: spec
      type(error_t), allocatable, intent(out) :: err
      integer :: i, nsurf, npair, target, cur
      character(len=:), allocatable :: w
      type(surface_spec_t), allocatable :: surf(:)
      type(pair_spec_t), allocatable :: pair(:)

      if (spec%active) then
         call fail(rd, icmd, 'a second CONTact block: expected one CONTact block per deck', err)
         return
      end if
      allocate (surf(4), pair(4))
      nsurf = 0
      npair = 0
      target = 0         ! 0: none, > 0: pair index, -1: AUTOmatic
      cur = 0            ! surface awaiting its description
      do
         call next_record(rd, i)
         if (i == 0) then
            call fail(rd, i, 'CONTact block opened at '//where(rd, icmd)//' is not closed: '// &
                      'expected END CONTact', err)
            return
         end if
         if (rd%src%rec(i)%blank) cycle
         w = word(rd, i, 1)
         if (keyword_is(w, 'end')) exit
         if (keyword_is(w, 'surf')) then
            call new_surface(i, err)
         else if (keyword_is(w, 'regi') .or. keyword_is(w, 'mate') .or. keyword_is(w, 'face') .or. &
                  keyword_is(w, 'phys')) then
            call describe(i, w, err)
         else if (keyword_is(w, 'pair')) then
            call new_pair(i, err)
         else if (keyword_is(w, 'auto')) then
            spec%automatic = .true.
            spec%auto_options%automatic = .true.
            spec%auto_options%where = where(rd, i)
            target = -1
            if (nfields(rd, i) >= 2) call method(i, 2, err)
         else if (keyword_is(w, 'lagr') .or. keyword_is(w, 'pena') .or. keyword_is(w, 'dete') .or. &
                  keyword_is(w, 'fric')) then
            call method(i, 1, err)
         else
            call unknown_keyword(rd, i, 'CONTact record', field(rd, i, 1), words, err)
         end if
         if (allocated(err)) return
      end do
      call close_block(i, err)
      if (allocated(err)) return
      spec%active = .true.
      spec%surfaces = surf(1:nsurf)
      spec%pairs = pair(1:npair)
   contains
      subroutine new_surface(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         integer :: id, k
         call int_field(rd, i, 2, 'SURFace,id', id, err)
         if (allocated(err)) return
         if (id < 1) then
            call fail(rd, i, 'SURFace,id: expected id >= 1', err)
            return
         end if
         do k = 1, nsurf
            if (surf(k)%id == id) then
               call fail(rd, i, 'SURFace '//itoa(id)//' is already defined at '//surf(k)%where// &
                         ': expected each surface id once', err)
               return
            end if
         end do
         call grow(surf, nsurf + 1)
         nsurf = nsurf + 1
         surf(nsurf)%id = id
         surf(nsurf)%where = where(rd, i)
         cur = nsurf
         target = 0
      end subroutine new_surface

      subroutine describe(i, w, err)
         integer, intent(in) :: i
         character(len=*), intent(in) :: w
         type(error_t), allocatable, intent(out) :: err
         if (cur == 0) then
            call fail(rd, i, field(rd, i, 1)//' outside a surface: expected SURFace,id before it', err)
            return
         end if
         if (surf(cur)%by /= 0) then
            call fail(rd, i, 'SURFace '//itoa(surf(cur)%id)//' is already described: expected '// &
                      'one of REGIon, MATErial, FACEts or PHYSical', err)
            return
         end if
         if (keyword_is(w, 'face')) then
            surf(cur)%by = SURF_FACETS
            call read_facets(rd, surf(cur), err)
         else if (keyword_is(w, 'phys')) then
            surf(cur)%by = SURF_FACETS
            surf(cur)%physical_where = where(rd, i)
            call int_field(rd, i, 2, 'SURFace PHYSical,c', surf(cur)%physical, err)
            if (allocated(err)) return
            if (surf(cur)%physical < 1) call fail(rd, i, 'SURFace PHYSical,c: expected a '// &
                                                  'physical curve tag c >= 1', err)
         else
            if (keyword_is(w, 'regi')) then
               surf(cur)%by = SURF_REGION
               call int_field(rd, i, 2, 'SURFace REGIon,r', surf(cur)%ref, err)
            else
               surf(cur)%by = SURF_MATERIAL
               call int_field(rd, i, 2, 'SURFace MATErial,m', surf(cur)%ref, err)
            end if
            if (allocated(err)) return
            if (surf(cur)%ref < 0 .or. (surf(cur)%by == SURF_MATERIAL .and. surf(cur)%ref < 1)) &
               call fail(rd, i, field(rd, i, 1)//': expected a '// &
                         'region >= 0 or a material >= 1', err)
         end if
      end subroutine describe

      subroutine new_pair(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         character(len=12), parameter :: kinds(3) = [character(len=12) :: 'NTOS', 'SYMMetric', 'SELF']
         character(len=*), parameter :: what = 'PAIR,id,NTOS|SYMMetric,slave,master or PAIR,id,SELF,s'
         type(pair_spec_t) :: p
         integer :: k
         call int_field(rd, i, 2, what, p%id, err)
         if (allocated(err)) return
         if (p%id < 1) then
            call fail(rd, i, what//': expected id >= 1', err)
            return
         end if
         do k = 1, npair
            if (pair(k)%id == p%id) then
               call fail(rd, i, 'PAIR '//itoa(p%id)//' is already defined at '//pair(k)%where// &
                         ': expected each pair id once', err)
               return
            end if
         end do
         if (keyword_is(word(rd, i, 3), 'ntos')) then
            p%kind = PAIR_NTOS
         else if (keyword_is(word(rd, i, 3), 'symm')) then
            p%kind = PAIR_SYMMETRIC
         else if (keyword_is(word(rd, i, 3), 'self')) then
            p%kind = PAIR_SELF
         else
            call unknown_keyword(rd, i, 'PAIR kind', field(rd, i, 3), kinds, err)
            return
         end if
         call int_field(rd, i, 4, what, p%slave, err)
         if (allocated(err)) return
         if (p%kind == PAIR_SELF) then
            p%master = p%slave
            call no_more_fields(rd, i, 4, 'PAIR,id,SELF,s (method records such as FRICtion,COULomb,mu '// &
                                'follow on their own lines)', err)
         else
            call int_field(rd, i, 5, what, p%master, err)
            if (allocated(err)) return
            call no_more_fields(rd, i, 5, 'PAIR,id,'//trim(kinds(p%kind))//',slave,master (method records '// &
                                'such as FRICtion,COULomb,mu follow on their own lines)', err)
         end if
         if (allocated(err)) return
         if (p%slave < 1 .or. p%master < 1) then
            call fail(rd, i, what//': expected surface ids >= 1', err)
            return
         end if
         if (p%kind /= PAIR_SELF .and. p%slave == p%master) then
            call fail(rd, i, 'PAIR '//itoa(p%id)//' names surface '//itoa(p%slave)//' as both '// &
                      'slave and master: expected PAIR,'//itoa(p%id)//',SELF,'//itoa(p%slave)// &
                      ' for self contact', err)
            return
         end if
         p%where = where(rd, i)
         call grow(pair, npair + 1)
         npair = npair + 1
         pair(npair) = p
         target = npair
         cur = 0
      end subroutine new_pair

      !> A method record whose keyword is field k0 of record i.
      subroutine method(i, k0, err)
         integer, intent(in) :: i, k0
         type(error_t), allocatable, intent(out) :: err
         character(len=12), parameter :: methods(4) = [character(len=12) :: 'LAGRange', &
                                                       'PENAlty', 'DETEction', 'FRICtion']
         character(len=12), parameter :: detections(2) = [character(len=12) :: 'SWEPt', 'STATic']
         type(pair_spec_t) :: p
         character(len=:), allocatable :: w
         if (target == 0) then
            call fail(rd, i, field(rd, i, k0)//' here: expected PAIR or AUTOmatic before a '// &
                      'method record', err)
            return
         end if
         if (target > 0) then
            p = pair(target)
         else
            p = spec%auto_options
         end if
         w = word(rd, i, k0)
         if (keyword_is(w, 'lagr')) then
            p%method = METHOD_LAGRANGE
            p%energy = keyword_is(word(rd, i, k0 + 1), 'ener')
            if (p%energy) then
               call no_more_fields(rd, i, k0 + 1, 'LAGRange,ENERgy', err)
            else
               call no_more_fields(rd, i, k0, 'LAGRange or LAGRange,ENERgy (friction is a record of '// &
                                   'its own, FRICtion,COULomb,mu)', err)
            end if
            if (allocated(err)) return
            if (p%energy .and. p%mus > 0.0_wp) then
               call fail(rd, i, 'LAGRange,ENERgy with Coulomb friction (FRICtion,COULomb,'//rtoa(p%mus, SHORT_REAL)// &
                         ') on the same pair: not supported (the massless faces are not coupled to '// &
                         'the tangential problem); expected LAGRange with friction, or ENERgy without', err)
               return
            end if
         else if (keyword_is(w, 'fric')) then
            call friction(i, k0, p, err)
            if (allocated(err)) return
            if (p%energy .and. p%method == METHOD_LAGRANGE .and. p%mus > 0.0_wp) then
               call fail(rd, i, 'FRICtion,COULomb,'//rtoa(p%mus, SHORT_REAL)//' with LAGRange,ENERgy on the same pair: '// &
                         'not supported (the massless faces are not coupled to the tangential '// &
                         'problem); expected LAGRange with friction, or ENERgy without', err)
               return
            end if
         else if (keyword_is(w, 'pena')) then
            p%method = METHOD_PENALTY
            if (keyword_is(word(rd, i, k0 + 1), 'scal')) then
               p%penalty_scaled = .true.
               p%penalty = 0.1_wp
               if (has_field(rd, i, k0 + 2)) call real_field(rd, i, k0 + 2, 'PENAlty,SCALe,f', &
                                                             p%penalty, err)
               if (.not. allocated(err)) call no_more_fields(rd, i, k0 + 2, 'PENAlty,SCALe,f', err)
            else
               p%penalty_scaled = .false.
               call real_field(rd, i, k0 + 1, 'PENAlty,k', p%penalty, err)
               if (.not. allocated(err)) call no_more_fields(rd, i, k0 + 1, 'PENAlty,k', err)
            end if
            if (allocated(err)) return
            if (.not. (p%penalty > 0.0_wp)) then
               call fail(rd, i, 'PENAlty '//rtoa(p%penalty, SHORT_REAL)//': expected PENAlty,k or '// &
                         'PENAlty,SCALe,f with a value > 0', err)
               return
            end if
         else if (keyword_is(w, 'dete')) then
            if (keyword_is(word(rd, i, k0 + 1), 'swep')) then
               p%detection = DETECT_SWEPT
            else if (keyword_is(word(rd, i, k0 + 1), 'stat')) then
               p%detection = DETECT_STATIC
            else
               call unknown_keyword(rd, i, 'DETEction option', field(rd, i, k0 + 1), detections, err)
               return
            end if
            call no_more_fields(rd, i, k0 + 1, 'DETEction,SWEPt|STATic', err)
            if (allocated(err)) return
         else
            call unknown_keyword(rd, i, 'method record', field(rd, i, k0), methods, err)
            return
         end if
         if (target > 0) then
            pair(target) = p
         else
            spec%auto_options = p
         end if
      end subroutine method

      !> FRICtion,COULomb,mu or FRICtion,COULomb,mus,mud[,decay] whose keyword is field k0 of
      !> record i, into p (doc/friction.md, eq. F12).
      subroutine friction(i, k0, p, err)
         integer, intent(in) :: i, k0
         type(pair_spec_t), intent(inout) :: p
         type(error_t), allocatable, intent(out) :: err
         character(len=*), parameter :: what = 'FRICtion,COULomb,mu or FRICtion,COULomb,mus,mud[,decay]'
         character(len=12), parameter :: laws(1) = [character(len=12) :: 'COULomb']
         if (.not. has_field(rd, i, k0 + 1)) then
            call fail(rd, i, 'FRICtion without a law: expected '//what, err)
            return
         end if
         if (.not. keyword_is(word(rd, i, k0 + 1), 'coul')) then
            call unknown_keyword(rd, i, 'friction law', field(rd, i, k0 + 1), laws, err)
            return
         end if
         if (.not. has_field(rd, i, k0 + 2)) then
            call fail(rd, i, 'FRICtion,COULomb without a coefficient: expected '//what, err)
            return
         end if
         call real_field(rd, i, k0 + 2, what, p%mus, err)
         if (allocated(err)) return
         p%mud = p%mus
         p%decay = 0.0_wp
         if (has_field(rd, i, k0 + 3)) call real_field(rd, i, k0 + 3, what, p%mud, err)
         if (allocated(err)) return
         if (has_field(rd, i, k0 + 4)) then
            call real_field(rd, i, k0 + 4, what, p%decay, err)
            if (allocated(err)) return
            if (.not. p%decay > 0.0_wp) then
               call fail(rd, i, 'FRICtion,COULomb decay '//rtoa(p%decay, SHORT_REAL)//': expected decay > 0 (or '// &
                         'no decay field: mus at rest, mud when sliding)', err)
               return
            end if
         end if
         if (.not. (p%mus >= 0.0_wp .and. p%mud >= 0.0_wp)) then
            call fail(rd, i, 'FRICtion,COULomb '//rtoa(p%mus, SHORT_REAL)//', '//rtoa(p%mud, SHORT_REAL)//': expected '// &
                      'coefficients >= 0', err)
         else if (p%mud > p%mus) then
            call fail(rd, i, 'FRICtion,COULomb,mus,mud with mud = '//rtoa(p%mud, SHORT_REAL)//' above mus = '// &
                      rtoa(p%mus, SHORT_REAL)//': expected mud <= mus (the dynamic coefficient at most the static one)', err)
         else
            call no_more_fields(rd, i, k0 + 4, what, err)
         end if
      end subroutine friction

      subroutine close_block(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         integer :: k
         if (has_field(rd, i, 2) .and. .not. keyword_is(word(rd, i, 2), 'cont')) then
            call fail(rd, i, 'END '//field(rd, i, 2)//' inside the CONTact block: expected '// &
                      'END CONTact', err)
            return
         end if
         do k = 1, nsurf
            if (surf(k)%by == 0) then
               call make_error(err, surf(k)%where//': SURFace '//itoa(surf(k)%id)//' has no '// &
                               'description: expected REGIon,r, MATErial,m, FACEts or '// &
                               'PHYSical,c after it')
               return
            end if
         end do
         do k = 1, npair
            call same_body(pair(k), err)
            if (allocated(err)) return
            if (.not. any(surf(1:nsurf)%id == pair(k)%slave)) then
               call make_error(err, pair(k)%where//': PAIR '//itoa(pair(k)%id)//' names surface '// &
                               itoa(pair(k)%slave)//': expected a defined SURFace')
               return
            end if
            if (.not. any(surf(1:nsurf)%id == pair(k)%master)) then
               call make_error(err, pair(k)%where//': PAIR '//itoa(pair(k)%id)//' names surface '// &
                               itoa(pair(k)%master)//': expected a defined SURFace')
               return
            end if
         end do
         if (npair == 0 .and. .not. spec%automatic) then
            call fail(rd, icmd, 'CONTact block without PAIR or AUTOmatic: expected at least one', err)
            return
         end if
         call energy_with_friction(err)
      end subroutine close_block

      !> LAGRange,ENERgy on one pair and Coulomb friction on another: refused at the pair (or
      !> AUTOmatic) with friction, since the massless faces enter the normal problem only.
      subroutine energy_with_friction(err)
         type(error_t), allocatable, intent(out) :: err
         integer :: k
         logical :: energy
         character(len=*), parameter :: why = ' in a model with LAGRange,ENERgy (massless contact '// &
                                              'faces, which the frictional corrector does not couple): '// &
                                              'not supported; expected no friction, or LAGRange without ENERgy'
         energy = .false.
         do k = 1, npair
            if (pair(k)%energy .and. pair(k)%method == METHOD_LAGRANGE) energy = .true.
         end do
         if (spec%automatic) then
            if (spec%auto_options%energy .and. spec%auto_options%method == METHOD_LAGRANGE) energy = .true.
         end if
         if (.not. energy) return
         do k = 1, npair
            if (pair(k)%mus > 0.0_wp) then
               call make_error(err, pair(k)%where//': PAIR '//itoa(pair(k)%id)//' has Coulomb friction'//why)
               return
            end if
         end do
         if (spec%automatic) then
            if (spec%auto_options%mus > 0.0_wp) &
               call make_error(err, spec%auto_options%where//': AUTOmatic has Coulomb friction'//why)
         end if
      end subroutine energy_with_friction

      !> A NTOS or SYMMetric pair whose two surfaces describe the same region or material is
      !> self contact in disguise: an error pointing to SELF.
      subroutine same_body(p, err)
         type(pair_spec_t), intent(in) :: p
         type(error_t), allocatable, intent(out) :: err
         integer :: a, b
         if (p%kind == PAIR_SELF) return
         a = surface_index(p%slave)
         b = surface_index(p%master)
         if (a == 0 .or. b == 0) return
         if (surf(a)%by == SURF_FACETS .or. surf(a)%by /= surf(b)%by) return
         if (surf(a)%ref /= surf(b)%ref) return
         call make_error(err, p%where//': PAIR '//itoa(p%id)//': surfaces '//itoa(p%slave)// &
                         ' and '//itoa(p%master)//' describe the same body: expected two '// &
                         'bodies, or PAIR,'//itoa(p%id)//',SELF,'//itoa(p%slave)//' for self contact')
      end subroutine same_body

      !> Index in surf(1:nsurf) of the surface with this id (0: none).
      pure integer function surface_index(id)
         integer, intent(in) :: id
         integer :: k
         surface_index = 0
         do k = 1, nsurf
            if (surf(k)%id == id) surface_index = k
         end do
      end function surface_index
   end subroutine cmd_contact

   !> FACEts records `f, ng, n1, n2` up to a blank record, with ELEMents-style generation.
   subroutine read_facets(rd, s, err)
      type(reader_t), intent(inout) :: rd
      type(surface_spec_t), intent(inout) :: s
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: what = 'FACEts record f, ng, n1, n2'
      integer, allocatable :: fac(:, :)
      integer :: i, f, ng, nd(2), m, mg, mnd(2), e, k, nf
      allocate (fac(2, 16))
      fac = 0
      m = 0
      mg = 0
      mnd = 0
      do
         call next_record(rd, i)
         if (i == 0) exit
         if (rd%src%rec(i)%blank) then
            call end_set(rd, i)
            exit
         end if
         call check_data_record(rd, i, 'FACEts', err)
         if (allocated(err)) return
         call int_field(rd, i, 1, what, f, err)
         if (.not. allocated(err)) call int_field(rd, i, 2, what, ng, err)
         do k = 1, 2
            if (.not. allocated(err)) call int_field(rd, i, 2 + k, what, nd(k), err)
         end do
         if (allocated(err)) return
         if (f <= m) then
            call fail(rd, i, what//': facet '//itoa(f)//': expected a facet number above '// &
                      itoa(m)//' (facets in increasing order)', err)
            return
         end if
         if (any(nd < 1) .or. nd(1) == nd(2)) then
            call fail(rd, i, what//': expected two different node numbers >= 1', err)
            return
         end if
         call grow(fac, f, 2)
         if (m > 0) then
            do e = m + 1, f - 1
               where (mnd /= 0) mnd = mnd + max(mg, 1)
               fac(:, e) = mnd
            end do
         end if
         fac(:, f) = nd
         m = f
         mg = ng
         mnd = nd
      end do
      nf = m
      if (nf == 0) then
         call fail(rd, i, 'FACEts: expected at least one record f, ng, n1, n2', err)
         return
      end if
      do e = 1, nf
         if (fac(1, e) == 0) then
            call fail(rd, i, 'FACEts: facet '//itoa(e)//' is missing: expected facets numbered '// &
                      'from 1 without gaps', err)
            return
         end if
      end do
      s%facets = fac(:, 1:nf)
   end subroutine read_facets

end module exic_input_deck_contact
