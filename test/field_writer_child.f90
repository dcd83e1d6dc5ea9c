!> Child process of the "killed writer" test in test_fields.
!>
!> `field_writer_child --child STEM N MARKER` writes the synthetic mesh and N output times (flushed) to STEM.h5 and
!> STEM.xdmf, creates the file MARKER, and then waits (up to 2 minutes) without closing anything,
!> so that the test can kill it with SIGTERM. Without `--child` first (as `fpm test` starts every
!> program under test/, with the suite words given to it), it does nothing and succeeds.
program field_writer_child
   use, intrinsic :: iso_fortran_env, only: error_unit
   use exic_base_error, only: error_t
   use exic_output_fields, only: field_writer_t
   use test_fields, only: write_synthetic
   use park, only: park_until_killed
   implicit none

   type(field_writer_t) :: w
   type(error_t), allocatable :: err
   character(len=4096) :: stem, nsteps_text, marker
   integer :: nsteps, ios

   call get_command_argument(1, stem)
   if (stem /= '--child' .or. command_argument_count() /= 4) then
      print '(a)', 'field_writer_child: helper of the field output tests; nothing to do without --child'
      stop
   end if
   call get_command_argument(2, stem)
   call get_command_argument(3, nsteps_text)
   call get_command_argument(4, marker)
   read (nsteps_text, *, iostat=ios) nsteps
   if (ios /= 0) error stop 'field_writer_child: N must be an integer'

   call write_synthetic(w, trim(stem), nsteps, err)
   if (allocated(err)) then
      write (error_unit, '(a)') 'field_writer_child: '//err%message
      error stop 2
   end if
   call park_until_killed(trim(marker), 'ready')
end program field_writer_child
