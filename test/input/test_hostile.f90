!> Hostile inputs and environments (issue 10): each case once made the reader hang, crash, take
!> quadratic time or stay silent. Every refused input must be an error naming file:line (or the
!> file, for the deck itself) and what was expected.
!>
!> - INCLude of /dev/zero, of a directory, and a deck that is a directory or a device;
!> - records far over 256 characters (rejected at once; trailing blanks are not counted);
!> - control characters (binary files);
!> - BOUNdary, FORCe and DISPlacement on nodes that do not exist;
!> - NTOS and SYMMetric pairs of one surface (or of two surfaces of one body);
!> - a mesh too large for the memory left under RLIMIT_AS (`ulimit -v`), in-process;
!> - the output directory made with mkdir(2) from text that a shell would run;
!> - numbers with three-digit exponents in .his/.ene read back by Fortran, and rows with a NaN or
!>   an infinity refused by the writers;
!> - fields a record has but no command uses;
!> - a LOOP of FORMs with no TIME (a fuzzed deck that lost its TIME record ran 10^7 steps without
!>   a row of output and looked hung): a warning at the LOOP.
module test_hostile
   use, intrinsic :: iso_c_binding, only: c_int, c_long
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, ieee_is_finite
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_model_model, only: model_t
   use exic_input_deck, only: read_deck
   use exic_output_text_history, only: history_files_t
   use exic_explicit_energy, only: energy_t
   use exic_output_text_number, only: put_real, put_int, REAL_WIDTH
   use exic_base_memory, only: mesh_memory_message
   use exic_base_posix, only: make_directories, file_kind, FILE_DIRECTORY, FILE_MISSING
   use testing, only: suite_t, check, section, file_text
   implicit none
   private

   public :: run_hostile_tests

   character(len=*), parameter :: tmp = 'build/test_hostile/'
   character(len=*), parameter :: nl = new_line('a')
   !> A complete small deck: a 2 x 1 block of 6 nodes; `mesh_extra` goes before the mesh END.
   character(len=*), parameter :: head = 'FEAP * * hostile'//nl//'0 0 0 2 2 4'//nl// &
      'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl// &
      nl//'BLOCk'//nl//'  CARTesian,2,1,0,0,1'//nl//'    1,0,0'//nl//'    2,2,0'//nl// &
      '    3,2,1'//nl//'    4,0,1'//nl//nl
   !> Lines of `head` (the next record is on line head_lines + 1).
   integer, parameter :: head_lines = 14
   character(len=*), parameter :: tail = 'END'//nl//'BATCh'//nl//'END'//nl//'STOP'

   !> struct rlimit of Linux (rlim_t is unsigned long; RLIM_INFINITY reads as -1).
   type, bind(C) :: rlimit_t
      integer(c_long) :: cur, max
   end type rlimit_t
   !> RLIMIT_AS on Linux (x86, ARM, RISC-V).
   integer(c_int), parameter :: RLIMIT_AS = 9_c_int

   interface
      !> int getrlimit(int resource, struct rlimit *rlim);
      function c_getrlimit(resource, rlim) bind(C, name='getrlimit') result(status)
         import :: c_int, rlimit_t
         integer(c_int), value :: resource
         type(rlimit_t), intent(out) :: rlim
         integer(c_int) :: status
      end function c_getrlimit
      !> int setrlimit(int resource, const struct rlimit *rlim);
      function c_setrlimit(resource, rlim) bind(C, name='setrlimit') result(status)
         import :: c_int, rlimit_t
         integer(c_int), value :: resource
         type(rlimit_t), intent(in) :: rlim
         integer(c_int) :: status
      end function c_setrlimit
   end interface

contains

   !> Every hostile-input test.
   subroutine run_hostile_tests(s)
      type(suite_t), intent(inout) :: s
      type(error_t), allocatable :: err
      call make_directories(tmp, err)
      call section(s, 'hostile: files that are not regular files')
      call not_regular(s)
      call section(s, 'hostile: long records and binary text')
      call long_records(s)
      call section(s, 'hostile: nodal records on nodes that do not exist')
      call missing_nodes(s)
      call section(s, 'hostile: contact pairs of one surface')
      call self_pairs(s)
      call section(s, 'hostile: a mesh larger than the memory left')
      call memory(s)
      call section(s, 'hostile: output directories without a shell')
      call directories(s)
      call section(s, 'hostile: three-digit exponents and non-finite values in .his/.ene')
      call number_format(s)
      call nonfinite_rows(s)
      call section(s, 'hostile: fields that no command uses')
      call unused_fields(s)
      call section(s, 'hostile: a LOOP of FORMs without TIME')
      call loop_without_time(s)
   end subroutine run_hostile_tests

   pure logical function has(str, sub)
      character(len=*), intent(in) :: str, sub
      has = index(str, sub) > 0
   end function has

   !> Write `text` to tmp/name.
   subroutine write_text(name, text)
      character(len=*), intent(in) :: name, text
      integer :: u
      open (newunit=u, file=tmp//name, status='replace', action='write')
      write (u, '(a)') text
      close (u)
   end subroutine write_text

   !> Read tmp/name (written from `text` first) and check that it fails with a message that
   !> contains `where` and `what`.
   subroutine expect_error(s, label, name, text, where, what)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: label, name, text, where, what
      type(model_t) :: m
      type(error_t), allocatable :: err
      call write_text(name, text)
      call read_deck(tmp//name, m, err)
      if (.not. allocated(err)) then
         call check(s, .false., label, 'the deck was accepted')
         return
      end if
      call check(s, has(err%message, where) .and. has(err%message, what), label, err%message)
   end subroutine expect_error

   !> Read tmp/name (written from `text` first) and check that it is accepted; `warnings`
   !> returns the reader's warnings.
   subroutine expect_ok(s, label, name, text, warnings)
      type(suite_t), intent(inout) :: s
      character(len=*), intent(in) :: label, name, text
      character(len=:), allocatable, intent(out), optional :: warnings
      type(model_t) :: m
      type(error_t), allocatable :: err
      call write_text(name, text)
      call read_deck(tmp//name, m, err)
      if (allocated(err)) then
         call check(s, .false., label, err%message)
      else
         call check(s, .true., label)
      end if
      if (present(warnings)) then
         warnings = ''
         if (allocated(m%warnings)) warnings = m%warnings
      end if
   end subroutine expect_ok

   !> INCLude,/dev/zero used to read forever; INCLude of a directory was read as an empty file.
   subroutine not_regular(s)
      type(suite_t), intent(inout) :: s
      type(model_t) :: m
      type(error_t), allocatable :: err
      integer :: u
      call expect_error(s, 'INCLude,/dev/zero is refused with file:line', 'zero.inp', &
                        head//'INCLude,/dev/zero'//nl//tail, tmp//'zero.inp:15:', &
                        'not a regular file')
      call expect_error(s, 'INCLude of a directory is refused with file:line', 'dir.inp', &
                        head//'INCLude,.'//nl//tail, tmp//'dir.inp:15:', 'is a directory')
      call expect_error(s, 'INCLude of a missing file is refused with file:line', 'missing.inp', &
                        head//'INCLude,nothere.inc'//nl//tail, tmp//'missing.inp:15:', &
                        'expected an existing file')
      call read_deck('/dev/zero', m, err)
      call check(s, allocated(err), 'a deck that is a device is refused')
      if (allocated(err)) call check(s, has(err%message, 'not a regular file'), &
                                     'and the message says so', err%message)
      open (newunit=u, file=tmp//'empty.inp', status='replace', action='write')
      close (u)
      call read_deck(tmp//'empty.inp', m, err)
      call check(s, allocated(err), 'an empty file (0 bytes) is refused')
      if (allocated(err)) call check(s, has(err%message, tmp//'empty.inp:1: the deck is empty: '// &
                                     'expected a title record'), 'naming file:1', err%message)
      call read_deck(tmp, m, err)
      call check(s, allocated(err), 'a deck that is a directory is refused')
      if (allocated(err)) call check(s, has(err%message, 'is a directory'), &
                                     'and the message says so', err%message)
   end subroutine not_regular

   !> A 2e6-character record is rejected naming its line (the reader stops at character 257);
   !> blanks after 256 characters are not counted; control characters are refused.
   subroutine long_records(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: long, comment
      long = 'PARA '//repeat('x', 1999995)
      call expect_error(s, 'a 2e6-character record is an error naming its line', 'long.inp', &
                        head//long//nl//tail, tmp//'long.inp:15:', 'longer than 256 characters')
      comment = '!'//repeat('c', 255)
      call expect_ok(s, 'a 256-character record followed by 1e5 blanks is read', 'blanks.inp', &
                     head//comment//repeat(' ', 100000)//nl//tail)
      call expect_error(s, 'a 257-character record is an error', 'l257.inp', &
                        head//comment//'c'//nl//tail, tmp//'l257.inp:15:', 'longer than 256')
      call expect_error(s, 'a NUL character is an error naming line and column', 'nul.inp', &
                        head//'PARA'//achar(0)//nl//tail, tmp//'nul.inp:15:', &
                        'control character (code 0) in column 5')
      call expect_error(s, 'a form feed is an error', 'ff.inp', &
                        head//achar(12)//nl//tail, tmp//'ff.inp:15:', 'control character (code 12)')
      call expect_ok(s, 'tabs and CR are blanks', 'tabs.inp', &
                     head//'PARAmeters'//achar(9)//achar(13)//nl//'  a = 1'//achar(13)//nl//nl//tail)
   end subroutine long_records

   !> BOUNdary, FORCe and DISPlacement on a node no command defines were accepted silently.
   subroutine missing_nodes(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: w
      call expect_error(s, 'BOUNdary on node 999 (6 nodes) is an error naming its record', &
                        'boun.inp', head//'BOUNdary'//nl//'  1,0,1,1'//nl//'  999,0,1,1'//nl// &
                        nl//tail, tmp//'boun.inp:17:', 'node 999 has no coordinates')
      call expect_error(s, 'FORCe on node 7 is an error naming its record', 'forc.inp', &
                        head//'FORCe'//nl//'  7,0,1,0'//nl//nl//tail, tmp//'forc.inp:16:', &
                        'node 7 has no coordinates')
      call expect_error(s, 'DISPlacement on node 8 is an error naming its record', 'disp.inp', &
                        head//'DISPlacement'//nl//'  8,0,0.1,0'//nl//nl//tail, tmp//'disp.inp:16:', &
                        'node 8 has no coordinates')
      call expect_error(s, 'a generated BOUNdary run past the last node is an error', 'gen.inp', &
                        head//'BOUNdary'//nl//'  1,1,1,1'//nl//'  9,0,1,1'//nl//nl//tail, &
                        tmp//'gen.inp:17:', 'node 7 has no coordinates')
      call expect_error(s, 'BOUNdary before the BLOCk that defines no such node', 'before.inp', &
                        'FEAP * * hostile'//nl//'0 0 0 2 2 4'//nl//'BOUNdary'//nl//'  12,0,1,1'// &
                        nl//nl//head(index(head, 'MATE'):)//tail, tmp//'before.inp:4:', &
                        'node 12 has no coordinates')
      call expect_ok(s, 'BOUNdary before the BLOCk (node1 = 1) that defines its node is fine', &
                     'ok.inp', 'FEAP * * hostile'//nl//'0 0 0 2 2 4'//nl//'BOUNdary'//nl// &
                     '  6,0,1,1'//nl//nl//head(index(head, 'MATE'):index(head, ',0,0,1') - 1)// &
                     ',1,1,1'//head(index(head, ',0,0,1') + 6:)//tail)
      call expect_ok(s, 'FORCe on a node used by no element is read', 'unused.inp', &
                     head//'COORdinates'//nl//'  10,0,5,5'//nl//nl//'FORCe'//nl//'  10,0,1,0'// &
                     nl//nl//tail, w)
      call check(s, has(w, tmp//'unused.inp:19: warning: node 10 is used by no element'), &
                 'with a warning naming the record', w)
   end subroutine missing_nodes

   !> PAIR,1,NTOS,1,1 was accepted: self contact is only through SELF.
   subroutine self_pairs(s)
      type(suite_t), intent(inout) :: s
      character(len=*), parameter :: two = 'REGIon,2'//nl//'BLOCk'//nl// &
         '  CARTesian,1,1,0,0,1'//nl//'    1,3,0'//nl//'    2,4,0'//nl//'    3,4,1'//nl// &
         '    4,3,1'//nl//nl
      character(len=*), parameter :: surfs = 'CONTact'//nl//'  SURFace,1'//nl//'    REGIon,0'// &
         nl//'  SURFace,2'//nl//'    REGIon,2'//nl
      call expect_error(s, 'PAIR,1,NTOS,1,1 is an error pointing to SELF', 'ntos.inp', &
                        head//two//surfs//'  PAIR,1,NTOS,1,1'//nl//'END CONTact'//nl//tail, &
                        tmp//'ntos.inp:28:', 'expected PAIR,1,SELF,1')
      call expect_error(s, 'PAIR,2,SYMMetric,2,2 is an error', 'symm.inp', &
                        head//two//surfs//'  PAIR,2,SYMMetric,2,2'//nl//'END CONTact'//nl//tail, &
                        tmp//'symm.inp:28:', 'as both slave and master')
      call expect_error(s, 'two surfaces of one region paired NTOS are an error', 'same.inp', &
                        head//two//surfs//'  SURFace,3'//nl//'    REGIon,2'//nl// &
                        '  PAIR,1,NTOS,3,2'//nl//'END CONTact'//nl//tail, tmp//'same.inp:30:', &
                        'describe the same body')
      call expect_ok(s, 'PAIR,1,SELF,1 and PAIR,2,NTOS,1,2 are read', 'selfok.inp', &
                     head//two//surfs//'  PAIR,1,SELF,1'//nl//'  PAIR,2,NTOS,1,2'//nl// &
                     'END CONTact'//nl//tail)
   end subroutine self_pairs

   !> The estimate against a given limit, and CARTesian,3000,3000 read under an address-space
   !> limit set in this process (it used to end in SIGSEGV).
   subroutine memory(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: msg, deck
      type(rlimit_t) :: old, lim
      integer(i8) :: vmsize
      logical :: found
      msg = mesh_memory_message(9006001, 9000000, 4000000000_i8, 'test limit')
      call check(s, has(msg, 'needs about 8.1 GB') .and. has(msg, '4.0 GB of test limit'), &
                 'a 3000 x 3000 mesh needs about 8.1 GB', msg)
      msg = mesh_memory_message(9006001, 9000000, 9000000000_i8, 'test limit')
      call check(s, len(msg) == 0, 'and fits in 9 GB', msg)
      call vm_size(vmsize, found)
      if (c_getrlimit(RLIMIT_AS, old) /= 0_c_int .or. .not. found) then
         call check(s, .false., 'getrlimit(RLIMIT_AS) and VmSize are readable')
         return
      end if
      lim = old
      lim%cur = int(vmsize + 1000000000_i8, c_long)
      if (old%max >= 0_c_long) lim%cur = min(lim%cur, old%max)
      if (c_setrlimit(RLIMIT_AS, lim) /= 0_c_int) then
         call check(s, .false., 'setrlimit(RLIMIT_AS) lowers the soft limit')
         return
      end if
      deck = head(1:index(head, 'CARTesian') - 1)//'CARTesian,3000,3000,0,0,1'// &
             head(index(head, ',0,0,1') + 6:)//tail
      call expect_error(s, 'CARTesian,3000,3000 under a limit of VmSize + 1 GB: "needs 8.1 GB"', &
                        'big.inp', deck, tmp//'big.inp:9:', 'needs about 8.1 GB')
      call expect_error(s, 'and the message names the limit', 'big.inp', deck, 'BLOCk', &
                        'RLIMIT_AS (ulimit -v)')
      call expect_error(s, 'COORdinates of node 1e8 check the memory first', 'coor.inp', &
                        head//'COORdinates'//nl//'  100000000,0,5,5'//nl//nl//tail, &
                        tmp//'coor.inp:16:', 'needs about 40.0 GB')
      call check(s, c_setrlimit(RLIMIT_AS, old) == 0_c_int, 'the old limit is restored')
   end subroutine memory

   !> VmSize of this process in bytes.
   subroutine vm_size(bytes, found)
      integer(i8), intent(out) :: bytes
      logical, intent(out) :: found
      character(len=256) :: line
      integer :: u, ios
      bytes = 0_i8
      found = .false.
      open (newunit=u, file='/proc/self/status', status='old', action='read', iostat=ios)
      if (ios /= 0) return
      do
         read (u, '(a)', iostat=ios) line
         if (ios /= 0) exit
         if (index(line, 'VmSize:') == 1) then
            read (line(8:), *, iostat=ios) bytes
            found = ios == 0
            bytes = 1024_i8*bytes
            exit
         end if
      end do
      close (u)
   end subroutine vm_size

   !> make_directories makes the literal path, parents too; no shell reads it.
   subroutine directories(s)
      type(suite_t), intent(inout) :: s
      type(error_t), allocatable :: err
      character(len=*), parameter :: odd = tmp//'out"; touch "'//tmp//'pwned'
      call make_directories(odd, err)
      call check(s, .not. allocated(err), 'a name with quotes and ; is made')
      call check(s, file_kind(odd) == FILE_DIRECTORY, 'as the directory of that literal name')
      call check(s, file_kind(tmp//'pwned') == FILE_MISSING, 'and no command ran')
      call make_directories(tmp//'p/q//r/', err)
      call check(s, .not. allocated(err) .and. file_kind(tmp//'p/q/r') == FILE_DIRECTORY, &
                 'parents are made (p/q//r/)')
      call make_directories(tmp//'p/q//r/', err)
      call check(s, .not. allocated(err), 'an existing directory is fine')
      call write_text('plain', 'x')
      call make_directories(tmp//'plain/sub', err)
      call check(s, allocated(err), 'a path through a regular file is an error')
      if (allocated(err)) call check(s, has(err%message, 'a file of that name exists'), &
                                     'that says so', err%message)
   end subroutine directories

   !> 1e-302 and -1e-302 written to .his and .ene read back exactly by Fortran list-directed
   !> input (they used to be written 1.2188988004400879-302, without E).
   subroutine number_format(s)
      type(suite_t), intent(inout) :: s
      type(history_files_t) :: f
      type(error_t), allocatable :: err
      real(wp), parameter :: tiny_value = 1.2188988004400879e-302_wp
      real(wp) :: row(3), ene(14)
      type(energy_t) :: en
      character(len=32) :: labels(2)
      character(len=400) :: line
      integer :: u, ios
      call f%open(tmp//'fmt', err)
      call check(s, .not. allocated(err), 'history files open')
      if (allocated(err)) return
      labels = ['a', 'b']
      call f%his_header(labels)
      call f%his_row(1.0e-300_wp, [tiny_value, -tiny_value], err)
      call check(s, .not. allocated(err), 'a row of tiny values is written')
      en = energy_t(kinetic=tiny_value, strain=3.0e300_wp, wext=0.0_wp, wcon=-tiny_value)
      call f%ene_row(2.0_wp, 7_i8, 1.0e-301_wp, en, 1.0_wp, 0.0_wp, [1.0e-310_wp, -2.0e-320_wp], 3, 0.0_wp, err)
      call check(s, .not. allocated(err), 'an energy row of tiny values is written')
      call f%close()
      open (newunit=u, file=tmp//'fmt.his', status='old', action='read')
      read (u, '(a)') line
      read (u, '(a)') line
      close (u)
      call check(s, has(line, '1.2188988004400879E-302') .and. has(line, ' -1.2188988004400879E-302'), &
                 '.his writes 1.2188988004400879E-302 with its E and a blank before the sign', &
                 trim(line))
      read (line, *, iostat=ios) row
      call check(s, ios == 0, '.his row reads back (list-directed)')
      call check(s, row(1) == 1.0e-300_wp .and. row(2) == tiny_value .and. row(3) == -tiny_value, &
                 '.his values round-trip exactly', trim(line))
      open (newunit=u, file=tmp//'fmt.ene', status='old', action='read')
      read (u, '(a)') line
      read (u, *, iostat=ios) ene
      close (u)
      call check(s, ios == 0, '.ene row reads back (list-directed)')
      call check(s, ene(3) == 1.0e-301_wp .and. ene(4) == tiny_value .and. ene(7) == -tiny_value &
                 .and. ene(10) == 1.0e-310_wp .and. ene(11) == -2.0e-320_wp .and. ene(5) == 3.0e300_wp, &
                 '.ene values (subnormals too) round-trip exactly')
      call check(s, has(rtoa(tiny_value), 'E-302'), 'rtoa writes the E of a 3-digit exponent', &
                 rtoa(tiny_value))
      call row_text(s)
   end subroutine number_format

   !> The rows' own number formatting (exic_output_text_number) gives the characters of Fortran's
   !> `1x,es24.16e3` and `i12` editing: zeros, subnormals, the extremes, powers of ten and
   !> their neighbours, 300000 random bit patterns of every exponent, and 200000 numbers whose
   !> decimal expansion is a tie or nearly one at the 17th significant digit.
   subroutine row_text(s)
      type(suite_t), intent(inout) :: s
      character(len=REAL_WIDTH) :: want
      character(len=64) :: got
      character(len=200) :: first
      integer :: k, n, nbad, e
      integer(i8) :: state, bits, iv(6)
      real(wp) :: x, special(10)
      nbad = 0
      first = ''
      special = [0.0_wp, -0.0_wp, tiny(1.0_wp), -huge(1.0_wp), huge(1.0_wp), 4.9406564584124654e-324_wp, &
                 1.0_wp, 9.9999999999999995e-1_wp, 0.5_wp, -1.0e300_wp]
      do k = 1, size(special)
         call compare(special(k))
      end do
      do e = -320, 308
         x = 10.0_wp**e
         if (x == 0.0_wp .or. .not. ieee_is_finite(x)) cycle
         call compare(x)
         call compare(nearest(x, 1.0_wp))
         call compare(-nearest(x, -1.0_wp))
      end do
      state = 88172645463325252_i8
      do k = 1, 300000
         ! xorshift64: every exponent and mantissa pattern
         state = ieor(state, shiftl(state, 13))
         state = ieor(state, shiftr(state, 7))
         state = ieor(state, shiftl(state, 17))
         bits = state
         x = transfer(bits, 1.0_wp)
         if (.not. ieee_is_finite(x)) cycle
         call compare(x)
      end do
      call check(s, nbad == 0, 'row text of reals equals es24.16e3 editing (random bit patterns, powers of ten)', &
                 trim(first))
      ! m/2**j with m an odd integer of 50 to 53 bits and j = 1..6: decimal expansions of 17 to
      ! 22 digits, many of them exact ties at the 17th (1000000000000000.25 -> ...0002E+015,
      ! to even); ties are where a conversion that does not round exactly would differ
      nbad = 0
      first = ''
      call compare(1000000000000000.25_wp)
      call compare(1000000000000000.75_wp)
      do k = 1, 100000
         state = ieor(state, shiftl(state, 13))
         state = ieor(state, shiftr(state, 7))
         state = ieor(state, shiftl(state, 17))
         bits = ior(shiftr(ibclr(state, 63), 10 + int(mod(ibclr(state, 63), 4_i8))), 1_i8)
         x = scale(real(bits, wp), -1 - int(mod(shiftr(ibclr(state, 63), 20), 6_i8)))
         call compare(x)
         call compare(-x)
      end do
      call check(s, nbad == 0, 'row text of reals equals es24.16e3 editing at exact ties of the 17th digit', &
                 trim(first))
      iv = [0_i8, 7_i8, -3_i8, 123456789012_i8, 999999999999_i8, 1000000000000_i8]
      nbad = 0
      do k = 1, size(iv)
         write (want(1:12), '(i12)') iv(k)
         n = 0
         call put_int(got, n, iv(k), 12)
         if (n /= 12 .or. got(1:12) /= want(1:12)) nbad = nbad + 1
      end do
      call check(s, nbad == 0, 'row text of integers equals i12 editing (and asterisks beyond 12 digits)')
   contains
      subroutine compare(y)
         real(wp), intent(in) :: y
         write (want, '(1x,es24.16e3)') y
         n = 0
         got = ''
         call put_real(got, n, y)
         if (n == REAL_WIDTH .and. got(1:n) == want) return
         nbad = nbad + 1
         if (first == '') first = 'first difference: "'//want//'" against "'//got(1:REAL_WIDTH)//'"'
      end subroutine compare
   end subroutine row_text

   !> A row with a NaN or an infinity is not written; the writer says which column and when.
   subroutine nonfinite_rows(s)
      type(suite_t), intent(inout) :: s
      type(history_files_t) :: f
      type(error_t), allocatable :: err
      real(wp) :: nan, inf
      character(len=32) :: labels(2)
      character(len=:), allocatable :: his, ene, out
      nan = ieee_value(nan, ieee_quiet_nan)
      inf = ieee_value(inf, ieee_positive_inf)
      call f%open(tmp//'nan', err)
      if (allocated(err)) then
         call check(s, .false., 'history files open', err%message)
         return
      end if
      labels = ['disp(n1,1)', 'velo(n1,1)']
      call f%his_header(labels)
      call f%his_row(0.0_wp, [1.0_wp, 2.0_wp])
      call f%his_row(0.5_wp, [1.0_wp, nan], err)
      call check(s, allocated(err), 'a .his row with a NaN returns an error')
      if (allocated(err)) call check(s, has(err%message, 'NaN in column velo(n1,1) of <stem>.his'), &
                                     'naming the column', err%message)
      call check(s, f%nonfinite, 'and sets the nonfinite flag')
      call f%ene_row(0.5_wp, 1_i8, 0.1_wp, energy_t(kinetic=inf), 0.0_wp, 0.0_wp, [0.0_wp, 0.0_wp], 0, 0.0_wp, err)
      call check(s, allocated(err), 'a .ene row with an infinity returns an error')
      if (allocated(err)) call check(s, has(err%message, 'infinite value in column kinetic'), &
                                     'naming the column', err%message)
      call f%his_row(0.75_wp, [nan, nan])
      call check(s, f%nonfinite_message == 'NaN in column velo(n1,1) of <stem>.his at t = '// &
                 '5.0000000E-01: the row is not written', 'the first refusal is kept', &
                 f%nonfinite_message)
      call f%close()
      his = file_text(tmp//'nan.his')
      ene = file_text(tmp//'nan.ene')
      out = file_text(tmp//'nan.out')
      call check(s, .not. (has(his, 'NaN') .or. has(his, 'Infinity') .or. has(ene, 'NaN') .or. &
                           has(ene, 'Infinity')), 'no NaN or Infinity in .his or .ene')
      call check(s, has(his, '1.0000000000000000E+000'), 'the finite row is there')
      call check(s, has(out, 'error: NaN in column velo(n1,1)'), '.out says so once')
   end subroutine nonfinite_rows

   !> Fields that no command reads were ignored silently.
   subroutine unused_fields(s)
      type(suite_t), intent(inout) :: s
      call expect_ok(s, 'the base deck reads', 'base.inp', head//tail)
   end subroutine unused_fields

   !> LOOP,,n with FORM and no TIME runs all n steps and writes nothing while it runs: a warning
   !> naming the LOOP's file:line; none when TIME is in the loop or in a loop inside it.
   subroutine loop_without_time(s)
      type(suite_t), intent(inout) :: s
      character(len=:), allocatable :: w
      character(len=*), parameter :: batch = 'END'//nl//'BATCh'//nl
      call expect_ok(s, 'a LOOP of FORMs without TIME is read', 'notime.inp', &
                     head//batch//'LOOP,,10000000'//nl//'  FORM,EXPLicit'//nl//'NEXT'//nl// &
                     'END'//nl//'STOP', w)
      call check(s, has(w, tmp//'notime.inp:17: warning: LOOP,,10000000 steps FORM with no TIME'), &
                 'warning at the LOOP (line 17)', w)
      call expect_ok(s, 'a LOOP with TIME and FORM is read', 'time.inp', &
                     head//batch//'LOOP,,10'//nl//'  TIME,,1'//nl//'  FORM,EXPLicit'//nl//'NEXT'//nl// &
                     'END'//nl//'STOP', w)
      call check(s, .not. has(w, 'no TIME'), 'no warning when TIME is in the loop', w)
      call expect_ok(s, 'an outer LOOP around a LOOP with TIME is read', 'nested.inp', &
                     head//batch//'LOOP,,2'//nl//'LOOP,,10'//nl//'  TIME,,1'//nl//'  FORM,EXPLicit'//nl// &
                     'NEXT'//nl//'NEXT'//nl//'END'//nl//'STOP', w)
      call check(s, .not. has(w, 'no TIME'), 'no warning when TIME is in an inner loop', w)
   end subroutine loop_without_time

end module test_hostile
