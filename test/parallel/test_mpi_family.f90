!> The `mpi` suite's generated decks with element history (doc/parallel.md, "Element history"):
!> three deformable bodies side by side on a rigid floor, one elastic-plastic (PLAStic MISEs),
!> one hypoelastic (ELAStic ISOTropic), one neo-Hookean, each with one-point or 2x2 quadrature,
!> moving toward each other under gravity in AUTOmatic contact (with or without Coulomb
!> friction), a driven rigid punch pressing on one, a free rigid body dropped on another; the
!> bodies touching at t = 0 or apart, the regions in any order. The histories hold stresses and
!> the plastic strain of elements of every body; fields are written and a restart file at
!> mid-run.
!>
!> `mpirun -np P` for P = 1..4 must write the .his and .ene of the serial program byte for byte
!> and the same .h5 (tools/h5_same.py: every dataset's values and every attribute); a restart
!> file written on P ranks continued on Q ranks (1 meaning the serial program) must give the
!> outputs of the uninterrupted serial run. The family's larger sample is
!> tools/stress/mpi_family.py.
module test_mpi_family
   use testing, only: suite_t, check, file_text, have_python_modules, python_command
   use exic_base_strings, only: itoa
   use deck_runner, only: run_dir, write_text
   implicit none
   private

   public :: run_mpi_family, FAMILY_CHECKS

   character(len=*), parameter :: nl = new_line('a')
   character(len=*), parameter :: MPIRUN = 'mpirun --oversubscribe --allow-run-as-root'
   !> Checks of the two variants: 3 of the serial run, 3 per P (1..4), 4 per restart (3 restarts).
   integer, parameter :: FAMILY_CHECKS = 2*(3 + 4*3) + 3*4

   !> One variant: the bodies' laws ('p' plastic, 'h' hypoelastic, 'e' elastic) and quadratures,
   !> touching or apart, the regions' order (1..3 the bodies, 4 floor, 5 punch, 6 free body),
   !> the friction record ('' none).
   type :: variant_t
      character(len=1) :: law(3)
      integer :: nq(3)
      logical :: touching
      integer :: order(6)
      character(len=:), allocatable :: friction
   end type variant_t

contains

   !> The two variants and their restarts across rank counts (2 -> 1, 1 -> 3; 3 -> 2).
   subroutine run_mpi_family(s, exic)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic
      type(variant_t) :: v
      v = variant_t(['p', 'h', 'e'], [2, 1, 2], .true., [2, 4, 1, 6, 3, 5], '  FRICtion,COULomb,0.3'//nl)
      call family_test(s, exic, 'family_a', v, [2, 1, 1, 3])
      v = variant_t(['p', 'e', 'h'], [1, 1, 2], .false., [5, 3, 1, 4, 2, 6], '')
      call family_test(s, exic, 'family_b', v, [3, 2])
   end subroutine run_mpi_family

   !> The deck of variant v.
   function family_deck(v) result(deck)
      type(variant_t), intent(in) :: v
      character(len=:), allocatable :: deck
      character(len=:), allocatable :: mats, regions, init, requests
      character(len=200) :: text(6)
      integer :: nel(6), nnode(6), first_e(6), first_n(6), k, i, r, e0, n0, reg(6)
      real :: x(3), y0, gap
      character(len=*), parameter :: E(3) = ['1000', '2000', '1500'], NU(3) = ['0.3 ', '0.45', '0.49']
      y0 = merge(0.0, 0.02, v%touching)
      gap = merge(0.0, 0.03, v%touching)
      mats = ''
      do k = 1, 3
         x(k) = (k - 1)*(1.0 + gap)
         mats = mats//'MATErial,'//itoa(k)//nl//'  SOLId'//nl
         if (v%law(k) == 'h') then
            mats = mats//'    ELAStic ISOTropic '//E(k)//' '//trim(NU(k))//nl
         else
            mats = mats//'    ELAStic NEOHookean '//E(k)//' '//trim(NU(k))//nl
         end if
         mats = mats//'    DENSity 1'//nl
         if (v%law(k) == 'p') mats = mats//'    PLAStic MISEs 10'//nl//'    PLAStic HARDening 50 0'//nl
         if (v%nq(k) == 1) mats = mats//'    QUADrature 1'//nl//'    HOURglass 0.1'//nl
         mats = mats//nl
      end do
      mats = mats//'MATErial,4'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,5'//nl//'  RIGId'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,6'//nl//'  RIGId,FREE'//nl//'    DENSity 2'//nl//nl
      ! the bodies 10 x 5 (two blocks of 32 elements each), the floor, the punch on body 1, the
      ! free body above body 3
      do k = 1, 3
         text(k) = block(10, 5, k, x(k), y0, x(k) + 1.0, y0 + 0.6)
         nel(k) = 50
         nnode(k) = 66
      end do
      text(4) = block(4, 1, 4, -0.5, -0.2, x(3) + 1.5, 0.0)
      text(5) = block(2, 1, 5, x(1) + 0.3, y0 + 0.6 + gap/3, x(1) + 0.7, y0 + 0.8 + gap/3)
      text(6) = block(2, 2, 6, x(3) + 0.35, y0 + 0.65, x(3) + 0.65, y0 + 0.95)
      nel(4:6) = [4, 2, 4]
      nnode(4:6) = [10, 6, 9]
      regions = ''
      e0 = 0
      n0 = 0
      do i = 1, 6
         r = v%order(i)
         reg(r) = i
         regions = regions//'REGIon,'//itoa(i)//nl//trim(text(r))
         first_e(r) = e0
         first_n(r) = n0
         e0 = e0 + nel(r)
         n0 = n0 + nnode(r)
      end do
      init = 'INITial,VELOcity'//nl//'  REGIon,'//itoa(reg(1))//',3,0'//nl//'  REGIon,'//itoa(reg(3))//',-3,0'// &
             nl//'  REGIon,'//itoa(reg(6))//',0,-2'//nl//nl
      ! the stresses (and the plastic strain) at two elements of each body, a displacement
      requests = ''
      do k = 1, 3
         requests = requests//'  stre,'//itoa(first_e(k) + 6)//',1'//nl//'  stre,'//itoa(first_e(k) + 45)// &
                    ','//trim(merge('8', '6', v%law(k) == 'p'))//nl
      end do
      requests = requests//'  disp,'//itoa(first_n(2) + 60)//',2'//nl
      deck = 'FEAP * * mpi family'//nl//'0 0 0 2 2 4'//nl//mats//regions//init// &
             'MOTIon,REGIon,'//itoa(reg(5))//',0,-1'//nl//nl//'CONTact'//nl//'  AUTOmatic'//nl//v%friction// &
             'END CONTact'//nl//nl//'GRAVity,0,-10'//nl//nl//'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl// &
             '  TPLOt,,1'//nl//'  OUTPut,HDF5,0.0075'//nl//'  SAVE,,0.015'//nl//'  LOOP,,100000'//nl// &
             '    TIME,,0.03'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl//requests//nl//'STOP'
   contains
      !> A BLOCk of nx x ny elements of material mat on the box (x0, y0) - (x1, y1).
      function block(nx, ny, mat, x0, y0, x1, y1) result(b)
         integer, intent(in) :: nx, ny, mat
         real, intent(in) :: x0, y0, x1, y1
         character(len=200) :: b
         b = 'BLOCk'//nl//'  CARTesian,'//itoa(nx)//','//itoa(ny)//',0,0,'//itoa(mat)//nl// &
             '    1,'//f(x0)//','//f(y0)//nl//'    2,'//f(x1)//','//f(y0)//nl// &
             '    3,'//f(x1)//','//f(y1)//nl//'    4,'//f(x0)//','//f(y1)//nl//nl
      end function block
      function f(z) result(t)
         real, intent(in) :: z
         character(len=:), allocatable :: t
         character(len=24) :: buf
         write (buf, '(f0.4)') z
         t = trim(buf)
         if (t(1:1) == '.') t = '0'//t
         if (t(1:2) == '-.') t = '-0'//t(2:)
      end function f
   end function family_deck

   !> Variant v: the serial run, mpirun -np 1..4, then each restart pair (P, Q) of `restarts`.
   subroutine family_test(s, exic, name, v, restarts)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, name
      type(variant_t), intent(in) :: v
      integer, intent(in) :: restarts(:)
      character(len=:), allocatable :: dir, deck, ref, his
      integer :: code, np, k
      logical :: h5
      dir = run_dir//'/mpi_'//name
      deck = dir//'.inp'
      ref = dir//'/serial/mpi_'//name
      call execute_command_line('rm -rf '//dir)
      call write_text(deck, family_deck(v))
      h5 = have_python_modules('h5py,numpy')
      code = run(exic, 1, deck, dir//'/serial', dir//'_serial.log')
      call check(s, code == 0, name//': the serial run succeeds', file_text(dir//'_serial.log'))
      if (code /= 0) return
      his = file_text(ref//'.his')
      call check(s, count(transfer(his, 'a', len(his)) == nl) > 40, name//': the serial run wrote more than 40 rows')
      call check(s, plastic_strain(his, v) > 0.0, name//': the plastic body yields (its plastic strain in the '// &
                 '.his is positive at the end)')
      do np = 1, 4
         code = run(exic, np, deck, dir//'/np'//itoa(np), dir//'_np'//itoa(np)//'.log')
         call check(s, code == 0, name//': mpirun -np '//itoa(np)//' succeeds', file_text(dir//'_np'//itoa(np)//'.log'))
         if (code /= 0) cycle
         call same_files(s, ref, dir//'/np'//itoa(np)//'/mpi_'//name, name//': -np '//itoa(np), h5)
      end do
      do k = 1, size(restarts), 2
         call restart_test(s, exic, name, deck, ref, restarts(k), restarts(k + 1), h5)
      end do
   end subroutine family_test

   !> The run on p ranks (its folder: the serial run's for p = 1, mpirun -np p's else) wrote a
   !> restart file at mid-run (<stem>.rst.prev after the one of the end); a copy of its outputs
   !> is continued from it on q ranks: the outputs of the uninterrupted serial run.
   subroutine restart_test(s, exic, name, deck, ref, p, q, h5)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: exic, name, deck, ref
      integer, intent(in) :: p, q
      logical, intent(in) :: h5
      character(len=:), allocatable :: d, what, first
      integer :: code
      d = run_dir//'/mpi_'//name//'/rst'//itoa(p)//itoa(q)
      first = run_dir//'/mpi_'//name//'/np'//itoa(p)
      if (p == 1) first = run_dir//'/mpi_'//name//'/serial'
      what = name//': restart written on '//itoa(p)//' rank(s), continued on '//itoa(q)
      call execute_command_line('rm -rf '//d//' && cp -r '//first//' '//d//' && mv '//d//'/mpi_'//name// &
                                '.rst.prev '//d//'/middle.rst', exitstat=code)
      call check(s, code == 0, what//': the run on '//itoa(p)//' rank(s) wrote its mid-run restart file')
      if (code /= 0) return
      code = run(exic, q, deck//' --restart '//d//'/middle.rst', d, d//'_continued.log')
      call check(s, code == 0, what//': the continued run ends normally', file_text(d//'_continued.log'))
      if (code /= 0) return
      call same_files(s, ref, d//'/mpi_'//name, what, h5)
   end subroutine restart_test

   !> .his and .ene of base equal to those of ref byte for byte; the .h5 the same
   !> (tools/h5_same.py; h5diff, which compares the datasets, without Python's h5py).
   subroutine same_files(s, ref, base, what, h5)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: ref, base, what
      logical, intent(in) :: h5
      integer :: code
      call check(s, file_text(base//'.his') == file_text(ref//'.his') .and. &
                 file_text(base//'.ene') == file_text(ref//'.ene'), what//': .his and .ene equal the serial files '// &
                 'byte for byte')
      if (h5) then
         call execute_command_line(python_command()//' tools/h5_same.py '//ref//'.h5 '//base//'.h5 > '//base// &
                                   '.h5same 2>&1', exitstat=code)
      else
         call execute_command_line('h5diff '//ref//'.h5 '//base//'.h5 > '//base//'.h5same 2>&1', exitstat=code)
      end if
      call check(s, code == 0, what//': the .h5 is the serial one (every dataset and attribute)', &
                 file_text(base//'.h5same'))
   end subroutine same_files

   !> `exic args -o out` on np ranks (1: the serial program, without mpirun), its output to log.
   integer function run(exic, np, args, out, log) result(code)
      character(len=*), intent(in) :: exic, args, out, log
      integer, intent(in) :: np
      if (np == 1) then
         call execute_command_line(exic//' -q '//args//' -o '//out//' > '//log//' 2>&1', exitstat=code)
      else
         call execute_command_line(MPIRUN//' -np '//itoa(np)//' '//exic//' -q '//args//' -o '//out//' > '//log// &
                                   ' 2>&1', exitstat=code)
      end if
   end function run

   !> The plastic strain of the plastic body's second requested element in the last .his row
   !> (its column: 2 k of the stress requests, k the plastic body), -1 when unreadable.
   real function plastic_strain(his, v) result(ep)
      character(len=*), intent(in) :: his
      type(variant_t), intent(in) :: v
      real :: row(8)
      integer :: b, k, ios
      ep = -1.0
      k = findloc(v%law, 'p', dim=1)
      b = index(his(1:len(his) - 1), nl, back=.true.)
      if (k == 0 .or. b == 0) return
      read (his(b + 1:), *, iostat=ios) row
      if (ios == 0) ep = row(1 + 2*k)
   end function plastic_strain

end module test_mpi_family
