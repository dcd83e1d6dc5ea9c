!> What a run on several MPI ranks needs around the step (doc/parallel.md): the features not
!> yet supported there, refused at the start with their name; the scratch folder of a rank
!> other than 0, which runs the whole program like rank 0 (the nodal state is the same on
!> every rank) but whose files are not the run's: rank 0 writes the run's files, the others
!> write theirs into a private folder under $TMPDIR (else /tmp) that is removed at the end.
module exic_session_ranks
   use, intrinsic :: iso_c_binding, only: c_char, c_int, c_ptr, c_null_char, c_associated
   use exic_base_kinds, only: wp
   use exic_base_error, only: error_t, make_error
   use exic_base_strings, only: itoa
   use exic_material_material, only: MAT_SOLID
   use exic_model_model, only: model_t
   use exic_base_posix, only: remove_file
   implicit none
   private

   public :: parallel_refusal, scratch_base, scratch_remove

   interface
      !> char *mkdtemp(char *template)
      function c_mkdtemp(template) bind(C, name='mkdtemp') result(p)
         import :: c_char, c_ptr
         character(kind=c_char), intent(inout) :: template(*)
         type(c_ptr) :: p
      end function c_mkdtemp
      !> int rmdir(const char *path)
      function c_rmdir(path) bind(C, name='rmdir') result(status)
         import :: c_char, c_int
         character(kind=c_char), intent(in) :: path(*)
         integer(c_int) :: status
      end function c_rmdir
   end interface

   !> The files a run writes under its base (dir/stem), which scratch_remove removes.
   character(len=*), parameter :: SUFFIXES(7) = [character(len=13) :: '.his', '.ene', '.out', '.h5', &
                                                 '.xdmf', '_series.xdmf', '.rst']

contains

   !> '' when `model` runs on `nranks` ranks as it does on one; else the message naming the
   !> first feature that is not yet supported on several ranks.
   function parallel_refusal(model, nranks) result(msg)
      type(model_t), intent(in) :: model
      integer, intent(in) :: nranks
      character(len=:), allocatable :: msg
      integer :: k
      msg = ''
      if (nranks <= 1) return
      do k = 1, size(model%materials)
         associate (m => model%materials(k))
            if (m%kind == MAT_SOLID .and. (m%erode_inverted .or. m%erode_strain > 0.0_wp .or. &
                                           m%erode_dt > 0.0_wp)) then
               msg = 'MATErial '//itoa(k)//': EROSion (elements removed during the run) is not yet '// &
                     'supported on several MPI ranks; run this deck on one rank'
               return
            end if
         end associate
      end do
   end function parallel_refusal

   !> A new private folder for rank `rank`'s files and the base (folder/stem) to write them under.
   subroutine scratch_base(rank, stem, dir, base, err)
      integer, intent(in) :: rank
      character(len=*), intent(in) :: stem
      character(len=:), allocatable, intent(out) :: dir, base
      type(error_t), allocatable, intent(out) :: err
      character(len=:), allocatable :: tmp
      character(kind=c_char, len=:), allocatable :: template
      integer :: l
      call get_environment_variable('TMPDIR', length=l)
      if (l > 0) then
         allocate (character(len=l) :: tmp)
         call get_environment_variable('TMPDIR', tmp)
      else
         tmp = '/tmp'
      end if
      template = tmp//'/exic-rank'//itoa(rank)//'-XXXXXX'//c_null_char
      if (.not. c_associated(c_mkdtemp(template))) then
         call make_error(err, 'rank '//itoa(rank)//': cannot create a scratch folder under '//tmp)
         return
      end if
      dir = template(:len(template) - 1)
      base = dir//'/'//stem
   end subroutine scratch_base

   !> Remove the files of a run under dir/stem and the folder dir (what scratch_base made).
   subroutine scratch_remove(dir, stem)
      character(len=*), intent(in) :: dir, stem
      integer :: k
      integer(c_int) :: status
      do k = 1, size(SUFFIXES)
         call remove_file(dir//'/'//stem//trim(SUFFIXES(k)))
      end do
      status = c_rmdir(dir//c_null_char)
   end subroutine scratch_remove

end module exic_session_ranks
