!> The `mpi` suite's decks of inputs/ (doc/parallel.md, "Measured"): for each contact and loading
!> feature of the decks, the smallest deck of inputs/ that has it, run by the serial program and
!> by `mpirun -np P` for P = 1, 2, 3, 4; the parallel runs must write the serial .his and .ene
!> byte for byte, and their reports must name the P ranks.
!>
!> - verify/wall_energy: `LAGRange,ENERgy` on an NTOS pair against a fixed rigid wall;
!> - paper/ex72_penalty: penalty contact (`PENAlty,SCALe`, NTOS) between two deformable bars;
!> - paper/ex75_disk: TIE (the disk's blocks form one body), two SYMMetric pairs;
!> - examples/punch: a rigid punch driven by MOTIon with a PROPortional ramp, GRAVity (a load
!>   with its own time function), NTOS pairs, a fixed rigid floor;
!> - verify/taylor_5x50 to t = 10 us instead of 80 us (a copy of the deck and its includes in the
!>   run folder with `tend` changed): plastic history (PLAStic MISEs with hardening, MIXEd),
!>   AXISymmetric, NTOS against a rigid wall; the shortened serial run must show the plastic
!>   strain and the contact force (its last .his row), so the features act in the run compared.
!>
!> inputs/ has no deck with AUTOmatic, SELF, friction or a free rigid body: the generated scenes
!> of test_mpi (auto, friction, free_rigid, self) and test_mpi_family cover those.
module test_mpi_decks
   use testing, only: suite_t, check, file_text
   use exic_base_strings, only: itoa
   use deck_runner, only: run_dir, write_text
   implicit none
   private

   public :: run_mpi_decks, DECK_CHECKS, count_lines

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: MPIRUN = 'mpirun --oversubscribe --allow-run-as-root'
   !> The decks of inputs/ run as they are (path without .inp).
   character(len=*), parameter :: DECKS(4) = [character(len=24) :: 'verify/wall_energy', 'paper/ex72_penalty', &
                                              'paper/ex75_disk', 'examples/punch']
   !> Checks: per deck 2 of the serial run and 2 per P (1..4); 2 of the shortened Taylor bar's copy.
   integer, parameter :: DECK_CHECKS = 5*(2 + 2*4) + 2

contains

   !> Run the decks of inputs/ with the exic program `exic` on 1..4 ranks.
   subroutine run_mpi_decks(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      integer :: k
      do k = 1, size(DECKS)
         call deck_test(s, exic, 'inputs/'//trim(DECKS(k))//'.inp', trim(DECKS(k)))
      end do
      call taylor_test(s, exic)
   end subroutine run_mpi_decks

   !> The Taylor bar (verify/taylor_5x50.inp) to t = 10 us: the deck and its includes copied to
   !> the run folder, `tend = 80e-6` of common/taylor_rod.inc replaced by 10e-6; its last .his
   !> row (t, disp, disp, the plastic strain of element 1 at the wall, the contact force) must
   !> show a plastic strain and a contact force, then the deck runs on 1..4 ranks.
   subroutine taylor_test(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      character(len=*), parameter :: dir = run_dir//'/mpi_deck_taylor'
      character(len=*), parameter :: src = 'inputs/verify/'
      character(len=:), allocatable :: text
      real :: row(5)
      integer :: k, code
      call execute_command_line('rm -rf '//dir//' && mkdir -p '//dir//'/common && cp '//src//'taylor_5x50.inp '// &
                                dir//'/ && cp '//src//'common/taylor.inc '//src//'common/taylor_rod.inc '//src// &
                                'common/taylor_run.inc '//dir//'/common/', exitstat=code)
      text = file_text(dir//'/common/taylor_rod.inc')
      k = index(text, 'tend = 80e-6')
      call check(s, code == 0 .and. k > 0, 'verify/taylor_5x50: the deck and its includes are copied, '// &
                 'tend = 80e-6 found in common/taylor_rod.inc')
      if (code /= 0 .or. k == 0) return
      text = text(:k - 1)//'tend = 10e-6'//text(k + len('tend = 80e-6'):)
      if (text(len(text):) == nl) text = text(:len(text) - 1)
      call write_text(dir//'/common/taylor_rod.inc', text)
      call deck_test(s, exic, dir//'/taylor_5x50.inp', 'verify/taylor_5x50 (t = 10 us)')
      row = last_row(file_text(run_dir//'/mpi_deck_taylor_5x50/serial/taylor_5x50.his'))
      call check(s, row(1) > 9.9e-6 .and. row(4) > 0.1 .and. row(5) > 0.0, 'verify/taylor_5x50 (t = 10 us): '// &
                 'at the end of the shortened serial run the element at the wall is plastic and in contact '// &
                 '(t, ep, contact force '//trim(real_text(row(1)))//' '//trim(real_text(row(4)))//' '// &
                 trim(real_text(row(5)))//')')
   end subroutine taylor_test

   !> One deck: serial, then mpirun -np 1..4; .his and .ene equal to the serial bytes.
   subroutine deck_test(s, exic, deck, label)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, deck, label
      character(len=:), allocatable :: stem, dir, his, ene, out, np_dir
      integer :: code, np
      stem = deck(index(deck, '/', back=.true.) + 1:len(deck) - 4)
      dir = run_dir//'/mpi_deck_'//stem
      call execute_command_line('rm -rf '//dir//' && mkdir -p '//dir)
      call execute_command_line(exic//' -q '//deck//' -o '//dir//'/serial > '//dir//'/serial.log 2>&1', exitstat=code)
      call check(s, code == 0, label//': the serial run succeeds', file_text(dir//'/serial.log'))
      if (code /= 0) return
      his = file_text(dir//'/serial/'//stem//'.his')
      ene = file_text(dir//'/serial/'//stem//'.ene')
      call check(s, count_lines(ene) > 10 .and. count_lines(his) > 10, &
                 label//': the serial run wrote more than 10 history and energy rows')
      do np = 1, 4
         np_dir = dir//'/np'//itoa(np)
         call execute_command_line(MPIRUN//' -np '//itoa(np)//' '//exic//' -q '//deck//' -o '//np_dir//' > '// &
                                   np_dir//'.log 2>&1', exitstat=code)
         out = file_text(np_dir//'/'//stem//'.out')
         call check(s, code == 0 .and. (np == 1 .or. index(out, 'MPI: '//itoa(np)//' ranks') > 0), &
                    label//': mpirun -np '//itoa(np)//' succeeds (the report names the ranks)', &
                    file_text(np_dir//'.log'))
         call check(s, file_text(np_dir//'/'//stem//'.his') == his .and. file_text(np_dir//'/'//stem//'.ene') == ene, &
                    label//': -np '//itoa(np)//': .his and .ene equal the serial files byte for byte')
      end do
   end subroutine deck_test

   !> The numbers of the last row of a .his text (-1 when missing or unreadable).
   function last_row(text) result(row)
      character(len=*), intent(in) :: text
      real :: row(5)
      integer :: b, ios
      row = -1.0
      if (len(text) < 2) return
      b = index(text(1:len(text) - 1), nl, back=.true.)
      if (b == 0) return
      read (text(b + 1:), *, iostat=ios) row
      if (ios /= 0) row = -1.0
   end function last_row

   !> x as text.
   function real_text(x) result(text)
      real, intent(in) :: x
      character(len=16) :: text
      write (text, '(es12.4)') x
      text = adjustl(text)
   end function real_text

   !> Newlines in text.
   pure integer function count_lines(text) result(n)
      character(len=*), intent(in) :: text
      integer :: i
      n = 0
      do i = 1, len(text)
         if (text(i:i) == nl) n = n + 1
      end do
   end function count_lines

end module test_mpi_decks
