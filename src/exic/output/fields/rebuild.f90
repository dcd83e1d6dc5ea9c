!> The live field file and its safe changes (submodule of fields.f90, doc/fields.md "Kill
!> safety"): opened write-through with every dataset an output time writes held, closed, and
!> changed only as a copy renamed over it (growth, restart, the final cut); the count of
!> complete output times of a file.
submodule(exic_output_fields) exic_output_fields_rebuild
   use exic_base_posix, only: copy_file
   use exic_output_fields_text, only: BUFFER
   implicit none

contains

   !> Release the held datasets and close the live file (interface: fields.f90).
   module procedure close_live
      type(error_t), allocatable :: err2
      call self%held%release(err)
      call self%h5%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
   end procedure close_live

   !> Open the live file write-through and hold its datasets (interface: fields.f90).
   module procedure open_live
      character(len=:), allocatable :: g
      integer :: i, b, j
      call self%h5%open(self%path_h5, .true., err, write_through=.true.)
      if (allocated(err)) return
      call self%held%hold(self%h5, COUNT_NAME, self%id_count, err)
      do i = 1, self%nvec
         if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/'//trim(NODE_VECTORS(i)), self%id_vec(i), err)
      end do
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/contact_active', self%id_active, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/stress', self%id_stress, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/fields/nodal_stress', self%id_nodal, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/time', self%id_time, err)
      if (.not. allocated(err)) call self%held%hold(self%h5, '/step', self%id_step, err)
      if (allocated(self%id_energy)) deallocate (self%id_energy)
      allocate (self%id_energy(max(self%nenergy, 0)))
      do i = 1, self%nenergy
         if (.not. allocated(err)) call self%held%hold(self%h5, '/energies/'//trim(self%energy_names(i)), &
                                                     self%id_energy(i), err)
      end do
      if (allocated(self%id_last)) deallocate (self%id_last)
      allocate (self%id_last(self%nvec + 2 + 2*self%ncomp, 0:1))
      do b = 0, 1
         g = '/last/'//BUFFER(b)//'/'
            do i = 1, self%nvec
               if (.not. allocated(err)) call self%held%hold(self%h5, g//trim(NODE_VECTORS(i)), self%id_last(i, b), err)
            end do
            j = self%nvec + 1
            if (.not. allocated(err)) call self%held%hold(self%h5, g//'contact_active', self%id_last(j, b), err)
            do i = 1, self%ncomp
               if (.not. allocated(err)) call self%held%hold(self%h5, g//'cell_'//trim(self%comp_names(i)), &
                                                           self%id_last(j + i, b), err)
               if (.not. allocated(err)) call self%held%hold(self%h5, g//'node_'//trim(self%comp_names(i)), &
                                                           self%id_last(j + self%ncomp + i, b), err)
            end do
            if (.not. allocated(err)) call self%held%hold(self%h5, g//'output', self%id_last(j + 2*self%ncomp + 1, b), err)
      end do
   end procedure open_live

   !> Change the metadata as a copy renamed over the file (interface: fields.f90).
   module procedure rebuild
      type(hdf5_file_t) :: tmp
      type(error_t), allocatable :: err2
      character(len=:), allocatable :: path
      integer :: i

      path = self%path_h5//'.tmp'
      call close_live(self, err)
      if (allocated(err)) return
      call copy_file(self%path_h5, path, err)
      if (.not. allocated(err)) call tmp%open(path, .true., err)
      if (allocated(err)) then
         call remove_file(path)
         return
      end if
      if (present(new_energies)) then
         if (new_energies) call create_energy_series(self, tmp, self%energy_names, err)
      end if
      associate (names => series_names(self))
         do i = 1, size(names)
            if (allocated(err)) exit
            call tmp%resize_series(trim(names(i)), nkeep, err)
            if (.not. allocated(err) .and. .not. final) call tmp%resize_series(trim(names(i)), capacity, err)
         end do
      end associate
      if (.not. allocated(err)) then
         if (tmp%exists(COUNT_NAME(2:))) then
            call tmp%rewrite(COUNT_NAME, [nkeep], err)
         else
            call tmp%write(COUNT_NAME, [nkeep], err)
         end if
      end if
      if (.not. allocated(err) .and. final .and. allocated(self%failed)) &
         call tmp%write_attr('/', 'failed', self%failed, err)
      call tmp%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      if (.not. allocated(err)) call rename_file(path, self%path_h5, err)
      if (allocated(err)) then
         call remove_file(path)
      else if (.not. final) then
         self%capacity = capacity
      end if
      ! the live file again (the old one when the copy failed), unless the run is over
      if (.not. final) then
         call open_live(self, err2)
         if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
      end if
   end procedure rebuild

   !> Every series of the file: nodal vectors, contact flag, element values and their nodal
   !> averages, energies, /time and /step.
   function series_names(self) result(names)
      type(field_writer_t), intent(in) :: self
      character(len=64), allocatable :: names(:)
      integer :: i
      allocate (names(0))
      do i = 1, self%nvec
         names = [character(len=64) :: names, '/fields/'//trim(NODE_VECTORS(i))]
      end do
      names = [character(len=64) :: names, '/fields/contact_active', '/fields/stress', '/fields/nodal_stress']
      do i = 1, max(self%nenergy, 0)
         names = [character(len=64) :: names, '/energies/'//trim(self%energy_names(i))]
      end do
      names = [character(len=64) :: names, '/time', '/step']
   end function series_names

   !> The number of complete output times of a field file (interface: fields.f90).
   module procedure complete_times
      type(hdf5_file_t) :: f
      type(error_t), allocatable :: err2
      integer :: c(1)
      n = 0
      call f%open(path, .false., err)
      if (allocated(err)) return
      if (f%exists(COUNT_NAME(2:))) then
         call f%read(COUNT_NAME, c, err)
         n = c(1)
      else
         call f%series_length('/time', n, err)
      end if
      call f%close(err2)
      if (.not. allocated(err) .and. allocated(err2)) call move_alloc(err2, err)
   end procedure complete_times

end submodule exic_output_fields_rebuild
