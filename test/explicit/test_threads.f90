!> Results do not depend on the number of threads: a deck with two element sets (2x2 and one
!> point), more elements and nodes than the thresholds of the threaded loops, a contact pair
!> and field output runs with one thread and with two (and three); its histories and energies
!> must agree byte for byte, its HDF5 datasets value for value (h5dump). The same deck without
!> the contact pair (the step's two sweeps over the nodes) too. Without OpenMP the check is
!> skipped.
module test_threads
   use deck_runner, only: run_dir, run_deck
   use testing, only: suite_t, check, section, skip, have_command
   use exic_explicit_assembly, only: PAR_MIN_ELEMENTS
   use exic_explicit_central, only: PAR_MIN_NODES
   !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
   implicit none
   private

   public :: run_threads_tests

   character(len=*), parameter :: nl = new_line('a')
   !> Elements per block in x and y (two blocks).
   integer, parameter :: nx = 60, ny = 40

contains

   !> Run every test of the suite.
   subroutine run_threads_tests(s)
      type(suite_t), intent(inout) :: s
      logical :: openmp

      call section(s, 'threads: one, two and three threads give the same results')
      openmp = .false.
      !$ openmp = .true.
      if (.not. openmp) then
         call skip(s, 'results for 1, 2 and 3 threads', 'OpenMP (built without -fopenmp)')
         return
      end if
      call check(s, nx*ny >= PAR_MIN_ELEMENTS .and. 2*(nx + 1)*(ny + 1) >= PAR_MIN_NODES, &
                 'the deck is large enough for the threaded element and nodal loops')
      ! with contact, and without (the step's two sweeps over the nodes, central.f90)
      call same_for_threads(s, 'threads', threads_deck(.true.))
      call same_for_threads(s, 'plain', threads_deck(.false.))
      ! the contact step: narrow phase and blocks of S on the threads
      call same_for_threads(s, 'bodies', bodies_deck(12, 4, 40), h5=.false.)
      call check(s, contact_threaded(run_dir//'/bodies_2.out'), 'bodies: with 2 threads the narrow '// &
                 'phase and the blocks of S ran on the threads (<stem>.out)')
      call check(s, .not. contact_threaded(run_dir//'/bodies_1.out'), 'bodies: with 1 thread the '// &
                 'contact step took its serial branches')
   end subroutine run_threads_tests

   !> <stem>.out reports both parts of the contact step on the threads a positive number of times.
   logical function contact_threaded(path)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: text
      character(len=*), parameter :: key = 'contact on the threads: narrow phase in '
      integer :: i, j, n1, n2, ios
      contact_threaded = .false.
      if (.not. read_all(path, text)) return
      i = index(text, key)
      if (i == 0) return
      i = i + len(key)
      read (text(i:), *, iostat=ios) n1
      if (ios /= 0) return
      j = index(text(i:), 'blocks of S in ')
      if (j == 0) return
      read (text(i + j - 1 + len('blocks of S in '):), *, iostat=ios) n2
      contact_threaded = ios == 0 .and. n1 > 0 .and. n2 > 0
   end function contact_threaded

   !> nside x nside free square bodies of ne x ne elements 0.25 wide, 0.05 apart, with AUTOmatic
   !> contact, for `steps` steps: the columns move at +5 and -5 in x alternately, so columns
   !> 1-2, 3-4, ... collide (bench/decks.py body_grid); histories of the first and the last body
   !> and the contact force every step.
   function bodies_deck(nside, ne, steps) result(deck)
      integer, intent(in) :: nside, ne, steps
      character(len=:), allocatable :: deck, init
      character(len=120) :: line
      integer :: ix, iy, r
      real :: h, x0, y0
      h = 0.25*ne
      deck = 'FEAP * * bodies on the threads'//nl//'0 0 0 2 2 4'//nl//'MATErial,1'//nl//'  SOLId'//nl// &
             '    ELAStic NEOHookean 14285.7 0.434'//nl//'    DENSity 0.1'//nl//'    QUADrature 2'//nl//nl
      init = 'INITial,VELOcity'//nl
      r = 0
      do iy = 0, nside - 1
         do ix = 0, nside - 1
            r = r + 1
            x0 = ix*(h + 0.05)
            y0 = iy*(h + 0.05)
            write (line, '(a,i0,a,i0,a,i0,a)') 'REGIon,', r, nl//'BLOCk'//nl//'  CARTesian,', ne, ',', ne, ',0,0,1'
            deck = deck//trim(line)//nl
            write (line, '(4(4x,i0,",",f0.4,",",f0.4,a))') 1, x0, y0, nl, 2, x0 + h, y0, nl, 3, x0 + h, y0 + h, nl, &
               4, x0, y0 + h, nl
            deck = deck//trim(line)//nl
            write (line, '(a,i0,a)') '  REGIon,', r, merge(',5,0 ', ',-5,0', mod(ix, 2) == 0)
            init = init//trim(line)//nl
         end do
      end do
      write (line, '(a,i0,a,i0,a)') '  LOOP,,', steps, nl//'    TIME'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl// &
         'END'//nl//'  disp,,1,0,0'//nl//'  velo,', (ne + 1)**2*nside**2, ',1'
      deck = deck//init//nl//'CONTact'//nl//'  AUTOmatic'//nl//'END CONTact'//nl//nl//'END'//nl//'BATCh'//nl// &
             '  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl//trim(line)//nl//'  cont,1,1'//nl//nl//'STOP'
   end function bodies_deck

   !> Run `deck` as <stem>_1, <stem>_2, <stem>_3 with 1, 2, 3 threads; the histories and energies
   !> of 2 and 3 threads must equal those of one byte for byte, every HDF5 dataset value for value.
   subroutine same_for_threads(s, stem, deck, h5)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: stem, deck
      logical, intent(in), optional :: h5          !< the deck writes fields (default: it does)
      integer :: nmax, th, stage
      character(len=:), allocatable :: msg
      character(len=1) :: c
      nmax = 1
      !$ nmax = omp_get_max_threads()
      do th = 1, 3
         !$ call omp_set_num_threads(th)
         write (c, '(i1)') th
         call run_deck(stem//'_'//c, deck, stage, msg)
         call check(s, stage == 0, stem//': the deck runs with '//c//' thread(s)', msg)
      end do
      !$ call omp_set_num_threads(nmax)
      do th = 2, 3
         write (c, '(i1)') th
         call check(s, same_bytes(run_dir//'/'//stem//'_1.his', run_dir//'/'//stem//'_'//c//'.his'), &
                    stem//': histories (.his) with '//c//' threads equal those with one, byte for byte')
         call check(s, same_bytes(run_dir//'/'//stem//'_1.ene', run_dir//'/'//stem//'_'//c//'.ene'), &
                    stem//': energies (.ene) with '//c//' threads equal those with one, byte for byte')
         if (present(h5)) then
            if (.not. h5) cycle
         end if
         if (have_command('h5dump')) then
            call check(s, same_dump(run_dir//'/'//stem//'_1.h5', run_dir//'/'//stem//'_'//c//'.h5'), &
                       stem//': every HDF5 dataset with '//c//' threads equals that with one')
         else
            call skip(s, stem//': HDF5 datasets with '//c//' threads', 'h5dump')
         end if
      end do
   end subroutine same_for_threads

   !> Two blocks 6 x 4 (nx x ny elements each), 2x2 below and one point above, 0.05 apart: the
   !> lower one deforming everywhere (initial velocity linear along each row, varying from row
   !> to row), the upper one falling onto it (NTOS contact, when `contact`; else through it,
   !> two bodies that never meet); fields every 0.05.
   function threads_deck(contact) result(deck)
      logical, intent(in) :: contact
      character(len=:), allocatable :: deck
      character(len=80) :: line
      integer :: j, m
      deck = 'FEAP * * threads: two blocks, both quadratures, contact, fields'//nl//'0 0 0 2 2 4'//nl
      do m = 1, 2
         write (line, '(a,i0)') 'MATErial,', m
         deck = deck//trim(line)//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl// &
                '    DENSity 1'//nl
         write (line, '(a,i0)') '    QUADrature ', 3 - m
         deck = deck//trim(line)//nl//nl
      end do
      write (line, '(a,i0,a,i0,a)') '  CARTesian,', nx, ',', ny, ',0,0,1'
      deck = deck//'REGIon,1'//nl//'BLOCk'//nl//trim(line)//nl//'    1,0,0'//nl//'    2,6,0'//nl// &
             '    3,6,4'//nl//'    4,0,4'//nl//nl
      write (line, '(a,i0,a,i0,a)') '  CARTesian,', nx, ',', ny, ',0,0,2'
      deck = deck//'REGIon,2'//nl//'BLOCk'//nl//trim(line)//nl//'    1,0,4.05'//nl//'    2,6,4.05'//nl// &
             '    3,6,8.05'//nl//'    4,0,8.05'//nl//nl
      deck = deck//'INITial,VELOcity'//nl
      do j = 0, ny
         write (line, '(2x,i0,a,f9.6)') 1 + j*(nx + 1), ',1,0.3,', 0.3*sin(6.2831853*(j + 0.5)/16.0)
         deck = deck//trim(line)//nl
         write (line, '(2x,i0,a,f9.6)') (j + 1)*(nx + 1), ',0,-0.3,', 0.3*sin(6.2831853*(j + 0.5)/16.0)
         deck = deck//trim(line)//nl
      end do
      deck = deck//'  REGIon,2,0,-0.5'//nl//nl
      if (contact) deck = deck//'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,1'//nl//'  SURFace,2'//nl// &
                          '    REGIon,2'//nl//'  PAIR,1,NTOS,2,1'//nl//'END CONTact'//nl//nl
      deck = deck//'END'//nl//'BATCh'//nl//'  TRANsient,EXPLicit'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,5'//nl// &
             '  OUTPut,HDF5,0.05'//nl//'  LOOP,,200'//nl//'    TIME'//nl//'    FORM,EXPLicit'//nl// &
             '  NEXT'//nl//'END'//nl//'  disp,,1,0,0'//nl//'  velo,,2,6,4'//nl
      if (contact) deck = deck//'  cont,1,1'//nl
      deck = deck//nl//'STOP'
   end function threads_deck

   !> The two files exist and have the same bytes.
   logical function same_bytes(a, b)
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: ta, tb
      same_bytes = read_all(a, ta) .and. read_all(b, tb)
      if (same_bytes) same_bytes = ta == tb .and. len(ta) > 0
   end function same_bytes

   !> h5dump prints the same datasets and attributes for both files (its first line names the
   !> file; HDF5 keeps modification times in the object headers, so the bytes differ).
   logical function same_dump(a, b)
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: ta, tb
      call execute_command_line('h5dump '//a//' | tail -n +2 > '//a//'.dump 2>&1; h5dump '//b// &
                                ' | tail -n +2 > '//b//'.dump 2>&1')
      same_dump = read_all(a//'.dump', ta) .and. read_all(b//'.dump', tb)
      if (same_dump) same_dump = ta == tb .and. len(ta) > 1000
   end function same_dump

   !> The whole file as one string; false if it cannot be read.
   logical function read_all(path, text)
      character(len=*), intent(in) :: path
      character(len=:), allocatable, intent(out) :: text
      integer :: u, ios, n
      read_all = .false.
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', iostat=ios)
      if (ios /= 0) then
         text = ''
         return
      end if
      inquire (unit=u, size=n)
      allocate (character(len=n) :: text)
      if (n > 0) read (u, iostat=ios) text
      close (u)
      read_all = ios == 0
   end function read_all

end module test_threads
