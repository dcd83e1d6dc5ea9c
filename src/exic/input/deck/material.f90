!> MATErial data sets of a deck (input language, section 3, MATErial).
!>
!> ```
!> MATErial,ma
!>   SOLId | RIGId | RIGId,FREE       element type record (FREE [ext]: a free rigid body)
!>   ELAStic NEOHookean E nu         (ELAStic ISOTropic E nu: read as NEOHookean, with a warning)
!>   DENSity rho
!>   QUADrature 1|2                  [ext]
!>   HOURglass h                     [ext] Flanagan-Belytschko stiffness coefficient (default 0.1)
!>   HOURglass,PHYSical[,s]          [ext] assumed-strain stabilization, scale 0 < s <= 1 (doc/hourglass.md)
!>   BODY bx by                      body force per unit reference volume (FEAP)
!>   MASS LUMPed                     (explicit runs always use lumped mass)
!>   PLANe STRAin | FINIte           accepted (the geometry is GLOBal's: plane strain or AXISymmetric)
!>   PLAStic MISEs Y0 Yinf beta      J2 plasticity, FEAP's saturation hardening (doc/plasticity.md)
!>   PLAStic HARDening Hiso Hkin     linear isotropic hardening (Hkin = 0: kinematic refused)
!>   PLAStic POWEr A B n             [ext] Y = A + B ep^n
!>   PLAStic JOHNson-cook A B n C m Tmelt Troom epsdot0   [ext] Johnson-Cook
!>   SPECific heat c                 adiabatic heating (Taylor-Quinney 0.9)
!>   MIXEd                           mean dilatation for the 2x2 element (FEAP's mixed element)
!>   DAMPing MASS c [t_end]          [ext] mass damping (deck_material_dissipation.f90)
!>   VISCosity BULK [q1 q2]          [ext] bulk viscosity (deck_material_dissipation.f90)
!> ```
!> A set is checked when its blank record is read: element type given; for SOLId E > 0,
!> -1 < nu < 0.5 and rho > 0; for RIGId rho >= 0; for RIGId,FREE rho > 0 (a free body needs a
!> mass); a PLAStic set: the checks of j2_check_parameters, and it must be a SOLId.
module exic_input_deck_material
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use exic_material_material, only: material_t, lame_from_young, MAT_SOLID, MAT_RIGID, &
                                     MAT_UNDEFINED, HOURGLASS_STIFFNESS, HOURGLASS_PHYSICAL
   use exic_material_j2_hardening, only: j2_check_parameters, J2_MISES, J2_POWER, J2_JOHNSON_COOK
   use exic_input_deck_records, only: keyword_is
   use exic_input_deck_material_dissipation, only: damping_record, viscosity_record, check_dissipation
   use exic_base_strings, only: rtoa, SHORT_REAL
   use exic_input_deck_reader, only: reader_t, next_record, field, word, real_field, int_field, fail, &
                             warn, where, end_set, unknown_keyword, itoa, &
                             check_data_record, has_field
   implicit none
   private

   public :: cmd_material

   character(len=16), parameter :: props(15) = [character(len=16) :: 'SOLId', 'RIGId', &
                                                'ELAStic', 'DENSity', 'QUADrature', 'HOURglass', &
                                                'MASS', 'PLANe', 'FINIte', 'BODY', 'PLAStic', &
                                                'SPECific', 'MIXEd', 'DAMPing', 'VISCosity']

contains

   !> `HOURglass h` (Flanagan-Belytschko stiffness form, coefficient h >= 0) or
   !> `HOURglass,PHYSical[,s]` (assumed-strain stabilization with scale 0 < s <= 1, default 1;
   !> above 1 it could exceed the 2x2 element's hourglass stiffness that the stable step covers,
   !> doc/hourglass.md section 2).
   subroutine hourglass_record(rd, i, mat, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: i
      type(material_t), intent(inout) :: mat
      type(error_t), allocatable, intent(out) :: err
      if (keyword_is(word(rd, i, 2), 'phys')) then
         mat%hourglass_kind = HOURGLASS_PHYSICAL
         mat%hourglass = 1.0_wp
         if (.not. has_field(rd, i, 3)) return
         call real_field(rd, i, 3, 'HOURglass,PHYSical,s', mat%hourglass, err)
         if (allocated(err)) return
         if (.not. (mat%hourglass > 0.0_wp .and. mat%hourglass <= 1.0_wp)) &
            call fail(rd, i, 'HOURglass,PHYSical,'//rtoa(mat%hourglass, SHORT_REAL)//': expected a scale s with '// &
                      '0 < s <= 1 (1: the assumed-strain stiffness of the material)', err)
      else
         mat%hourglass_kind = HOURGLASS_STIFFNESS
         call real_field(rd, i, 2, 'HOURglass h (a coefficient) or HOURglass,PHYSical[,s]', &
                         mat%hourglass, err)
         if (allocated(err)) return
         if (.not. mat%hourglass >= 0.0_wp) call fail(rd, i, 'HOURglass '//rtoa(mat%hourglass, SHORT_REAL)// &
                                                      ': expected a coefficient >= 0', err)
      end if
   end subroutine hourglass_record

   !> Read `MATErial,ma` (record `icmd`) and its data set into `mat`; `ma` is the set number.
   subroutine cmd_material(rd, icmd, ma, mat, err)
      type(reader_t), intent(inout) :: rd
      integer, intent(in) :: icmd
      integer, intent(out) :: ma
      type(material_t), intent(out) :: mat
      type(error_t), allocatable, intent(out) :: err
      integer :: i, ielas, idens, irig, iplas, idiss
      logical :: has_e, has_rho

      call int_field(rd, icmd, 2, 'MATErial,ma', ma, err)
      if (allocated(err)) return
      if (ma < 1) then
         call fail(rd, icmd, 'MATErial,ma: expected a material set number ma >= 1', err)
         return
      end if
      mat%where = where(rd, icmd)
      has_e = .false.
      has_rho = .false.
      ielas = icmd
      idens = icmd
      irig = icmd
      iplas = 0
      idiss = 0
      do
         call next_record(rd, i)
         if (i == 0) exit
         if (rd%src%rec(i)%blank) then
            call end_set(rd, i)
            exit
         end if
         call property(i, err)
         if (allocated(err)) return
      end do
      call check(err)
      if (.not. allocated(err) .and. idiss > 0) call check_dissipation(rd, idiss, ma, mat, err)
   contains
      subroutine property(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         character(len=:), allocatable :: w
         integer :: q
         w = word(rd, i, 1)
         if (keyword_is(w, 'soli') .or. keyword_is(w, 'rigi')) then
            if (mat%kind /= MAT_UNDEFINED) then
               call fail(rd, i, 'MATErial '//itoa(ma)//': a second element type record: '// &
                         'expected one SOLId or RIGId', err)
            else if (keyword_is(w, 'soli')) then
               mat%kind = MAT_SOLID
            else
               mat%kind = MAT_RIGID
               irig = i
               if (keyword_is(word(rd, i, 2), 'free')) then
                  mat%free = .true.
               else if (len(word(rd, i, 2)) > 0) then
                  call fail(rd, i, 'RIGId,'//field(rd, i, 2)//': expected RIGId (fixed or driven) '// &
                            'or RIGId,FREE (a free rigid body)', err)
               end if
            end if
         else if (keyword_is(w, 'elas')) then
            if (keyword_is(word(rd, i, 2), 'isot')) then
               call warn(rd, i, 'ELAStic ISOTropic is read as ELAStic NEOHookean (exic''s only '// &
                         'solid law)')
            else if (.not. keyword_is(word(rd, i, 2), 'neoh')) then
               call fail(rd, i, 'ELAStic law "'//field(rd, i, 2)//'" is not supported: expected '// &
                         'ELAStic NEOHookean E nu', err)
               return
            end if
            call real_field(rd, i, 3, 'ELAStic NEOHookean E nu', mat%young, err)
            if (.not. allocated(err)) call real_field(rd, i, 4, 'ELAStic NEOHookean E nu', &
                                                      mat%poisson, err)
            has_e = .true.
            ielas = i
         else if (keyword_is(w, 'dens')) then
            call real_field(rd, i, 2, 'DENSity rho', mat%rho, err)
            has_rho = .true.
            idens = i
         else if (keyword_is(w, 'quad')) then
            call int_field(rd, i, 2, 'QUADrature 1|2', q, err)
            if (allocated(err)) return
            if (q /= 1 .and. q /= 2) then
               call fail(rd, i, 'QUADrature '//itoa(q)//': expected 1 (one point + hourglass '// &
                         'control) or 2 (2x2 Gauss)', err)
               return
            end if
            mat%quadrature = q
         else if (keyword_is(w, 'hour')) then
            call hourglass_record(rd, i, mat, err)
         else if (keyword_is(w, 'mass')) then
            if (keyword_is(word(rd, i, 2), 'cons')) then
               call warn(rd, i, 'MASS CONSistent ignored: explicit runs use a lumped mass')
            else if (.not. keyword_is(word(rd, i, 2), 'lump')) then
               call fail(rd, i, 'MASS "'//field(rd, i, 2)//'": expected MASS LUMPed', err)
            end if
         else if (keyword_is(w, 'plan')) then
            if (.not. keyword_is(word(rd, i, 2), 'stra')) call fail(rd, i, 'PLANe "'// &
               field(rd, i, 2)//'" is not supported: expected PLANe STRAin', err)
         else if (keyword_is(w, 'fini')) then
            continue
         else if (keyword_is(w, 'plas')) then
            call plastic_record(i, err)
         else if (keyword_is(w, 'spec')) then
            call real_field(rd, i, 3, 'SPECific heat c', mat%j2%cheat, err)
            if (iplas == 0) iplas = i
         else if (keyword_is(w, 'mixe')) then
            mat%mixed = .true.
         else if (keyword_is(w, 'damp')) then
            call damping_record(rd, i, mat, err)
            idiss = i
         else if (keyword_is(w, 'visc')) then
            call viscosity_record(rd, i, mat, err)
            idiss = i
         else if (keyword_is(w, 'body')) then
            call real_field(rd, i, 2, 'BODY bx by', mat%body(1), err)
            if (.not. allocated(err)) call real_field(rd, i, 3, 'BODY bx by', mat%body(2), err)
         else
            call check_data_record(rd, i, 'MATErial', err)
            if (.not. allocated(err)) call unknown_keyword(rd, i, 'MATErial record', &
                                                          field(rd, i, 1), props, err)
         end if
      end subroutine property

      !> PLAStic MISEs|HARDening|POWEr|JOHNson-cook with their numbers.
      subroutine plastic_record(i, err)
         integer, intent(in) :: i
         type(error_t), allocatable, intent(out) :: err
         character(len=:), allocatable :: w2
         w2 = word(rd, i, 2)
         mat%plastic = .true.
         if (iplas == 0 .or. .not. keyword_is(word(rd, iplas, 1), 'plas')) iplas = i
         if (keyword_is(w2, 'mise')) then
            mat%j2%law = J2_MISES
            call reals(i, 'PLAStic MISEs Y0 Yinf beta', [3, 4, 5], err, mat%j2%y0, mat%j2%yinf, &
                       mat%j2%beta, nreq=1)
            if (.not. has_field(rd, i, 4)) mat%j2%yinf = mat%j2%y0
         else if (keyword_is(w2, 'hard')) then
            call reals(i, 'PLAStic HARDening Hiso Hkin', [3, 4], err, mat%j2%hiso, mat%j2%hkin, nreq=1)
         else if (keyword_is(w2, 'powe')) then
            mat%j2%law = J2_POWER
            call reals(i, 'PLAStic POWEr A B n', [3, 4, 5], err, mat%j2%a, mat%j2%b, mat%j2%en)
         else if (keyword_is(w2, 'john')) then
            mat%j2%law = J2_JOHNSON_COOK
            call reals(i, 'PLAStic JOHNson-cook A B n C m Tmelt Troom epsdot0', [3, 4, 5], err, &
                       mat%j2%a, mat%j2%b, mat%j2%en)
            if (.not. allocated(err)) call reals(i, 'PLAStic JOHNson-cook A B n C m Tmelt Troom '// &
                                                 'epsdot0', [6, 7, 8], err, mat%j2%crate, mat%j2%m, &
                                                 mat%j2%tmelt)
            if (.not. allocated(err)) call reals(i, 'PLAStic JOHNson-cook A B n C m Tmelt Troom '// &
                                                 'epsdot0', [9, 10], err, mat%j2%troom, mat%j2%epsdot0)
         else
            call fail(rd, i, 'PLAStic "'//field(rd, i, 2)//'": expected PLAStic MISEs Y0 Yinf '// &
                      'beta, PLAStic HARDening Hiso Hkin, PLAStic POWEr A B n or PLAStic '// &
                      'JOHNson-cook A B n C m Tmelt Troom epsdot0', err)
         end if
      end subroutine plastic_record

      !> Real fields idx(1..) of record i into a, b(, c); fields past the first nreq may be
      !> left out (the value keeps its default: Yinf = Y0 and beta = 0, Hkin = 0).
      subroutine reals(i, what, idx, err, a, b, c, nreq)
         integer, intent(in) :: i, idx(:)
         character(len=*), intent(in) :: what
         type(error_t), allocatable, intent(out) :: err
         real(wp), intent(inout) :: a, b
         real(wp), intent(inout), optional :: c
         integer, intent(in), optional :: nreq
         integer :: nr
         nr = size(idx)
         if (present(nreq)) nr = nreq
         call real_field(rd, i, idx(1), what, a, err)
         if (allocated(err)) return
         if (nr >= 2 .or. has_field(rd, i, idx(2))) call real_field(rd, i, idx(2), what, b, err)
         if (allocated(err) .or. .not. present(c)) return
         if (nr >= 3 .or. has_field(rd, i, idx(3))) call real_field(rd, i, idx(3), what, c, err)
      end subroutine reals

      subroutine check(err)
         type(error_t), allocatable, intent(out) :: err
         select case (mat%kind)
         case (MAT_UNDEFINED)
            call fail(rd, icmd, 'MATErial '//itoa(ma)//' has no element type record: expected '// &
                      'SOLId or RIGId', err)
         case (MAT_SOLID)
            if (.not. has_e) then
               call fail(rd, icmd, 'MATErial '//itoa(ma)//' (SOLId): expected ELAStic NEOHookean '// &
                         'E nu', err)
            else if (.not. (mat%young > 0.0_wp)) then
               call fail(rd, ielas, 'MATErial '//itoa(ma)//': E = '//rtoa(mat%young, SHORT_REAL)// &
                         ': expected E > 0', err)
            else if (.not. (mat%poisson > -1.0_wp .and. mat%poisson < 0.5_wp)) then
               call fail(rd, ielas, 'MATErial '//itoa(ma)//': nu = '//rtoa(mat%poisson, SHORT_REAL)// &
                         ': expected -1 < nu < 0.5', err)
            else if (.not. (mat%rho > 0.0_wp)) then
               call fail(rd, idens, 'MATErial '//itoa(ma)//': rho = '//rtoa(mat%rho, SHORT_REAL)// &
                         ': expected DENSity rho > 0', err)
            else
               call lame_from_young(mat%young, mat%poisson, mat%lambda, mat%mu)
               if (mat%plastic) then
                  call check_plastic(err)
               else if (iplas > 0) then
                  call fail(rd, iplas, 'MATErial '//itoa(ma)//': SPECific heat without a PLAStic '// &
                            'law: expected PLAStic MISEs, POWEr or JOHNson-cook (the heat comes '// &
                            'from the plastic work)', err)
               end if
               if (mat%mixed .and. mat%quadrature == 1 .and. .not. allocated(err)) &
                  call warn(rd, icmd, 'MATErial '//itoa(ma)//': MIXEd ignored with QUADrature 1 '// &
                            '(the one-point element has a single volume change already)')
            end if
         case (MAT_RIGID)
            if (mat%plastic) then
               call fail(rd, iplas, 'MATErial '//itoa(ma)//': PLAStic on a RIGId body: '// &
                         'plasticity needs a deformable SOLId material', err)
               return
            end if
            if (mat%rho < 0.0_wp) call fail(rd, idens, 'MATErial '//itoa(ma)//': rho = '// &
                                            rtoa(mat%rho, SHORT_REAL)//': expected DENSity rho >= 0', err)
            if (has_e) call warn(rd, ielas, 'ELAStic ignored for a RIGId material')
            if (mat%free .and. .not. allocated(err) .and. .not. (mat%rho > 0.0_wp)) &
               call fail(rd, irig, 'MATErial '//itoa(ma)//': a free rigid body (RIGId,FREE) needs '// &
                         'its mass: expected DENSity rho > 0', err)
            if (.not. mat%free .and. any(mat%body /= 0.0_wp)) call warn(rd, icmd, 'BODY ignored '// &
               'for a fixed or driven RIGId material (it moves only as prescribed)')
         end select
         if (.not. has_rho .and. mat%kind == MAT_RIGID) mat%rho = 0.0_wp
      end subroutine check

      !> The plastic parameters (j2_check_parameters), reported at the PLAStic record.
      subroutine check_plastic(err)
         type(error_t), allocatable, intent(out) :: err
         character(len=:), allocatable :: msg
         mat%j2%rho = mat%rho
         call j2_check_parameters(mat%j2, msg)
         if (len(msg) > 0) call fail(rd, iplas, 'MATErial '//itoa(ma)//': '//msg, err)
      end subroutine check_plastic
   end subroutine cmd_material

end module exic_input_deck_material
