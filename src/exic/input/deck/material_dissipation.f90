!> The dissipation records of a SOLId material set (doc/damping.md, doc/input-language.md):
!>
!> ```
!>   DAMPing MASS c [t_end]          mass-proportional damping, force -c m v, c >= 0 in 1/time,
!>                                   until t_end (default: the whole run)
!>   VISCosity BULK [q1 q2]          bulk viscosity q = rho l (q1 l trD^2 - q2 c trD), trD < 0;
!>                                   defaults q1 = 1.5, q2 = 0.06
!> ```
module exic_input_deck_material_dissipation
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use exic_material_material, only: material_t, MAT_SOLID
   use exic_input_deck_records, only: keyword_is
   use exic_input_deck_reader, only: reader_t, field, word, real_field, fail, has_field, itoa
   use exic_base_strings, only: rtoa, SHORT_REAL
   implicit none
   private

   public :: damping_record, viscosity_record, check_dissipation

contains

   !> `DAMPing MASS c [t_end]` (record i) into mat%damping, mat%damping_end.
   subroutine damping_record(rd, i, mat, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      type(material_t), intent(inout) :: mat
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: WHAT = 'DAMPing MASS c [t_end]'
      if (.not. keyword_is(word(rd, i, 2), 'mass')) then
         call fail(rd, i, 'DAMPing "'//field(rd, i, 2)//'": expected '//WHAT//' (mass-proportional '// &
                   'damping, c in 1/time)', err)
         return
      end if
      if (.not. has_field(rd, i, 3)) then
         call fail(rd, i, WHAT//': the coefficient c is missing', err)
         return
      end if
      call real_field(rd, i, 3, WHAT, mat%damping, err)
      if (allocated(err)) return
      if (.not. (mat%damping >= 0.0_wp .and. ieee_is_finite(mat%damping))) then
         call fail(rd, i, WHAT//': c = '//rtoa(mat%damping, SHORT_REAL)//': expected a finite c >= 0', err)
         return
      end if
      mat%damping_end = huge(1.0_wp)
      if (has_field(rd, i, 4)) then
         call real_field(rd, i, 4, WHAT, mat%damping_end, err)
         if (allocated(err)) return
         if (.not. (mat%damping_end >= 0.0_wp .and. ieee_is_finite(mat%damping_end))) then
            call fail(rd, i, WHAT//': t_end = '//rtoa(mat%damping_end, SHORT_REAL)//': expected a finite t_end >= 0', err)
            return
         end if
      end if
      if (has_field(rd, i, 5)) call fail(rd, i, WHAT//': unexpected field 5 "'//field(rd, i, 5)//'"', err)
   end subroutine damping_record

   !> `VISCosity BULK [q1 q2]` (record i) into mat%bulk, mat%bulk_q1, mat%bulk_q2.
   subroutine viscosity_record(rd, i, mat, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: i
      type(material_t), intent(inout) :: mat
      type(error_t), allocatable, intent(out) :: err
      character(len=*), parameter :: WHAT = 'VISCosity BULK [q1 q2]'
      if (.not. keyword_is(word(rd, i, 2), 'bulk')) then
         call fail(rd, i, 'VISCosity "'//field(rd, i, 2)//'": expected '//WHAT//' (the bulk '// &
                   'viscosity of the DYNA codes)', err)
         return
      end if
      mat%bulk = .true.
      mat%bulk_q1 = 1.5_wp
      mat%bulk_q2 = 0.06_wp
      if (has_field(rd, i, 3) .neqv. has_field(rd, i, 4)) then
         call fail(rd, i, WHAT//': give both q1 and q2, or neither (q1 = 1.5, q2 = 0.06)', err)
         return
      end if
      if (has_field(rd, i, 3)) then
         call real_field(rd, i, 3, WHAT, mat%bulk_q1, err)
         if (.not. allocated(err)) call real_field(rd, i, 4, WHAT, mat%bulk_q2, err)
         if (allocated(err)) return
         if (.not. (mat%bulk_q1 >= 0.0_wp .and. ieee_is_finite(mat%bulk_q1) .and. mat%bulk_q2 >= 0.0_wp .and. &
                    ieee_is_finite(mat%bulk_q2))) then
            call fail(rd, i, WHAT//': q1 = '//rtoa(mat%bulk_q1, SHORT_REAL)//', q2 = '//rtoa(mat%bulk_q2, SHORT_REAL)// &
                      ': expected finite q1 >= 0 and q2 >= 0', err)
            return
         end if
      end if
      if (has_field(rd, i, 5)) call fail(rd, i, WHAT//': unexpected field 5 "'//field(rd, i, 5)//'"', err)
   end subroutine viscosity_record

   !> A dissipation record on a material that is not a SOLId is an error (record irec).
   subroutine check_dissipation(rd, irec, ma, mat, err)
      type(reader_t), intent(in) :: rd
      integer, intent(in) :: irec, ma
      type(material_t), intent(in) :: mat
      type(error_t), allocatable, intent(out) :: err
      if (mat%kind /= MAT_SOLID .and. (mat%damping > 0.0_wp .or. mat%bulk)) &
         call fail(rd, irec, 'MATErial '//itoa(ma)//': DAMPing and VISCosity apply to a deformable '// &
                   'SOLId material (a RIGId body has no elements to damp)', err)
   end subroutine check_dissipation

end module exic_input_deck_material_dissipation
