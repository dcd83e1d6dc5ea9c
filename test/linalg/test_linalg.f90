!> Tests of the contact linear algebra: sparse LDL' (AMD + SuiteSparse LDL) and the dense
!> Cholesky path, on S = G^T M^-1 G built from contact-like constraints.
module test_linalg
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
   use exic_base_kinds, only: wp, i8
   use exic_base_error, only: error_t
   use exic_linalg_sparse_ldl, only: sparse_ldl_t
   use exic_linalg_dense_spd, only: dense_spd_t
   use exic_linalg_lapack, only: dsyev
   use testing, only: suite_t, check, section
   implicit none
   private

   public :: run_linalg_tests

   !> Node slots per constraint column of G (3 for node-on-segment, more for combinations).
   integer, parameter :: nslot = 6
   real(wp), parameter :: eps = epsilon(1.0_wp)

   !> Constraints: column c of G has the 2-vectors w(:, p, c) at nodes node(p, c) (0 = unused).
   type :: cset_t
      integer :: nc = 0, nnode = 0
      integer, allocatable :: node(:, :)
      real(wp), allocatable :: w(:, :, :), minv(:)
   end type cset_t

   !> A matrix in 1-based compressed columns, full symmetric pattern.
   type :: csc_t
      integer :: n = 0
      integer, allocatable :: ap(:), ai(:)
      real(wp), allocatable :: ax(:)
   end type csc_t

contains

   !> Run every linear-algebra test.
   subroutine run_linalg_tests(s)
      type(suite_t), intent(inout) :: s
      call seed_random()
      call test_random_spd(s)
      call test_symbolic_reuse(s)
      call test_redundancy(s)
      call test_zero_pivots(s)
      call test_drop_mask(s)
      call test_pivot_rule(s)
      call test_large_chain(s)
   end subroutine run_linalg_tests

   ! ---------------------------------------------------------------- tests

   !> 1. Random constraint sets: sparse and dense agree and have tiny residuals.
   subroutine test_random_spd(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: sizes(5) = [1, 2, 7, 60, 300]
      type(cset_t) :: cs
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp), allocatable :: sd(:, :), b(:), xs(:), xd(:)
      integer, allocatable :: bad(:)
      type(error_t), allocatable :: err
      integer :: t, n, nbs, nbd
      real(wp) :: kappa
      character(len=40) :: tag

      call section(s, 'linalg: random contact-like S = G^T M^-1 G')
      do t = 1, size(sizes)
         n = sizes(t)
         write (tag, '(a,i0)') 'n = ', n
         call random_constraints(n, cs)
         call assemble(cs, a)
         call to_dense(a, sd)
         allocate (b(n), xs(n), xd(n), bad(n))
         call random_number(b)
         b = b - 0.5_wp
         call sp%analyze(n, a%ap, a%ai, err)
         call check(s, .not. allocated(err), trim(tag)//': sparse analyze')
         call sp%factorize(a%ax, nbs, bad, err)
         call check(s, .not. allocated(err) .and. nbs == 0 .and. .not. sp%removal_pass, &
                    trim(tag)//': sparse factorize, none redundant')
         call sp%solve(b, xs)
         call de%factorize(sd, nbd, bad, err)
         call check(s, .not. allocated(err) .and. nbd == 0 .and. .not. de%pivoted, &
                    trim(tag)//': dense factorize, none redundant')
         call de%solve(b, xd)
         call check_rel(s, residual(a, xs, b), 1.0e-12_wp, trim(tag)//': sparse ||Sx-b||/||b||')
         call check_rel(s, residual(a, xd, b), 1.0e-12_wp, trim(tag)//': dense ||Sx-b||/||b||')
         kappa = condition(sd)
         call check_rel(s, norm2(xs - xd)/norm2(xd), cholesky_bound(n, kappa), &
                        trim(tag)//': sparse = dense within 2 (3n+1) cond(S) eps')
         deallocate (b, xs, xd, bad)
      end do
   end subroutine test_random_spd

   !> 2. The analysis is reused for new values and redone for a new pattern, never stale.
   subroutine test_symbolic_reuse(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 80
      type(cset_t) :: cs
      type(csc_t) :: a, q
      type(sparse_ldl_t) :: sp
      real(wp) :: b(n), x(n)
      integer :: bad(n), perm(n), nbad, k
      type(error_t), allocatable :: err

      call section(s, 'linalg: symbolic analysis reuse')
      call random_constraints(n, cs)
      call assemble(cs, a)
      call random_number(b)
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, .not. allocated(err) .and. sp%nanalyze == 1, 'first refactorize analyzes')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'first values: residual')

      ! same pattern, new values (new masses and normals on the same nodes)
      call random_number(cs%minv)
      cs%minv = 0.5_wp + cs%minv
      do k = 1, n
         call random_number(cs%w(:, 1:3, k))
      end do
      call assemble(cs, a)
      call check(s, sp%same_pattern(n, a%ap, a%ai), 'same_pattern true for new values')
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, .not. allocated(err) .and. sp%nanalyze == 1, 'new values: analysis reused')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'new values: residual')

      ! new pattern with the same n and nnz: a symmetric permutation of S
      call random_permutation(n, perm)
      call permuted(a, perm, q)
      call check(s, .not. sp%same_pattern(n, q%ap, q%ai), 'same_pattern false for Q S Q^T')
      call sp%factorize(q%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, residual(q, x, b) > 1.0e-6_wp, 'a stale analysis would give a wrong solution')
      call sp%refactorize(n, q%ap, q%ai, q%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, .not. allocated(err) .and. sp%nanalyze == 2, 'new pattern: re-analyzed')
      call check_rel(s, residual(q, x, b), 1.0e-12_wp, 'new pattern: residual')

      ! a smaller system after a larger one (work arrays kept), then the large one again
      call random_constraints(5, cs)
      call assemble(cs, q)
      call sp%refactorize(5, q%ap, q%ai, q%ax, nbad, bad, err)
      call sp%solve(b(1:5), x(1:5))
      call check_rel(s, residual(q, x(1:5), b(1:5)), 1.0e-12_wp, 'shrunk to n = 5: residual')
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, sp%nanalyze == 4, 'pattern change back and forth re-analyzes each time')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'back to n = 80: residual')

      ! an elimination order given instead of AMD's: analyzed again, solved; kept while the
      ! pattern and the order stay, analyzed again for another order and back to AMD
      call sp%set_order(n, perm)
      call check(s, .not. sp%same_pattern(n, a%ap, a%ai), 'same_pattern false once an order is given')
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, .not. allocated(err) .and. sp%nanalyze == 5, 'given order: re-analyzed')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'given order: residual')
      call sp%set_order(n, perm)
      call check(s, sp%same_pattern(n, a%ap, a%ai), 'same pattern and the same order: analysis kept')
      call sp%set_order(n, [(k, k=n, 1, -1)])
      call check(s, .not. sp%same_pattern(n, a%ap, a%ai), 'another order: analysis not kept')
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'reversed order: residual')
      call sp%set_order(0, perm)
      call check(s, .not. sp%same_pattern(n, a%ap, a%ai), 'back to AMD: analysis not kept')
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call check(s, .not. allocated(err) .and. sp%nanalyze == 7, 'back to AMD: re-analyzed')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'back to AMD: residual')
   end subroutine test_symbolic_reuse

   !> 3. Duplicated and combined constraints: one of each dependent group is flagged, and the
   !>    reduced solution satisfies every constraint; removal = deleting the row and column.
   subroutine test_redundancy(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nb = 40, n = nb + 2, idup = 7, ia = 3, ib = 12
      type(cset_t) :: base, cs
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp), allocatable :: sd(:, :)
      real(wp) :: z(n), b(n), xs(n), xd(n)
      integer :: bad(n), nbs, nbd
      type(error_t), allocatable :: err

      call section(s, 'linalg: redundant constraints')
      call random_constraints(nb, base)
      call extend(base, n, cs)
      ! constraint nb+1 duplicates idup (node-on-node two-pass contact)
      cs%node(:, nb + 1) = cs%node(:, idup)
      cs%w(:, :, nb + 1) = cs%w(:, :, idup)
      ! constraint nb+2 = 0.6 g(ia) + 1.3 g(ib)
      cs%node(1:3, n) = cs%node(1:3, ia)
      cs%node(4:6, n) = cs%node(1:3, ib)
      cs%w(:, 1:3, n) = 0.6_wp*cs%w(:, 1:3, ia)
      cs%w(:, 4:6, n) = 1.3_wp*cs%w(:, 1:3, ib)
      call assemble(cs, a)
      call to_dense(a, sd)
      call random_number(z)
      call matvec(a, z, b)          ! consistent right-hand side: b in range(S)

      call sp%analyze(n, a%ap, a%ai, err)
      call sp%factorize(a%ax, nbs, bad, err)
      call check(s, .not. allocated(err) .and. sp%removal_pass, 'sparse: factorize singular S without error')
      call check(s, nbs == 2 .and. sp%nremoved == 2, 'sparse: exactly two constraints flagged')
      call check(s, one_each(bad(1:nbs), [idup, nb + 1], [ia, ib, n]), &
                 'sparse: one per dependent group')
      call sp%solve(b, xs)
      call check(s, all(xs(bad(1:nbs)) == 0.0_wp), 'sparse: removed multipliers are zero')
      call check_rel(s, residual(a, xs, b), 1.0e-12_wp, 'sparse: all constraints hold, dropped too')
      call compare_reduced(s, a, bad(1:nbs), b, xs, 'sparse')

      call de%factorize(sd, nbd, bad, err)
      call check(s, .not. allocated(err) .and. de%pivoted, 'dense: factorize singular S via pivoting')
      call check(s, nbd == 2 .and. de%rank == n - 2, 'dense: exactly two constraints flagged')
      call check(s, one_each(bad(1:nbd), [idup, nb + 1], [ia, ib, n]), &
                 'dense: one per dependent group')
      call de%solve(b, xd)
      call check(s, all(xd(bad(1:nbd)) == 0.0_wp), 'dense: removed multipliers are zero')
      call check_rel(s, residual(a, xd, b), 1.0e-12_wp, 'dense: all constraints hold, dropped too')
      call compare_reduced(s, a, bad(1:nbd), b, xd, 'dense')
   end subroutine test_redundancy

   !> 3b. Exact zero pivots (ldl_numeric stops early) and the 1 x 1 zero matrix.
   subroutine test_zero_pivots(s)
      type(suite_t), intent(inout) :: s
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp), allocatable :: sd(:, :)
      real(wp) :: b(4), x(4), z(4)
      integer :: bad(4), nbad
      type(error_t), allocatable :: err

      call section(s, 'linalg: zero pivots')
      ! 1 x 1 zero matrix
      call from_dense(reshape([0.0_wp], [1, 1]), a)
      b(1) = 0.0_wp
      call sp%refactorize(1, a%ap, a%ai, a%ax, nbad, bad, err)
      call check(s, .not. allocated(err) .and. nbad == 1 .and. bad(1) == 1, 'sparse: 1x1 zero flagged')
      x(1) = 1.0_wp
      call sp%solve(b(1:1), x(1:1))
      call check(s, x(1) == 0.0_wp, 'sparse: 1x1 zero solves to 0')
      call de%factorize(reshape([0.0_wp], [1, 1]), nbad, bad, err)
      call check(s, .not. allocated(err) .and. nbad == 1 .and. bad(1) == 1, 'dense: 1x1 zero flagged')
      x(1) = 1.0_wp
      call de%solve(b(1:1), x(1:1))
      call check(s, x(1) == 0.0_wp, 'dense: 1x1 zero solves to 0')

      ! two exactly singular 2x2 blocks: the first exact zero pivot stops ldl_numeric before
      ! the last row whatever the ordering
      sd = reshape([1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, 1.0_wp, 1.0_wp, 0.0_wp, 0.0_wp, &
                    0.0_wp, 0.0_wp, 2.0_wp, 2.0_wp, 0.0_wp, 0.0_wp, 2.0_wp, 2.0_wp], [4, 4])
      call from_dense(sd, a)
      z = [0.3_wp, -1.1_wp, 0.7_wp, 2.0_wp]
      call matvec(a, z, b)
      call sp%refactorize(4, a%ap, a%ai, a%ax, nbad, bad, err)
      call check(s, .not. allocated(err) .and. nbad == 2, 'sparse: two exact zero pivots flagged')
      call check(s, one_each(bad(1:nbad), [1, 2], [3, 4]), 'sparse: one per singular block')
      call sp%solve(b, x)
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'sparse: reduced solution satisfies all rows')
      call de%factorize(sd, nbad, bad, err)
      call check(s, .not. allocated(err) .and. nbad == 2, 'dense: two exact zero pivots flagged')
      call check(s, one_each(bad(1:nbad), [1, 2], [3, 4]), 'dense: one per singular block')
      call de%solve(b, x)
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'dense: reduced solution satisfies all rows')
   end subroutine test_zero_pivots

   !> 3c. Constraints dropped by the caller (drop mask) = the reduced system, pattern unchanged.
   subroutine test_drop_mask(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: n = 50
      type(cset_t) :: cs
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp), allocatable :: sd(:, :)
      real(wp) :: b(n), x(n)
      logical :: drop(n)
      integer :: bad(n), nbad
      integer, allocatable :: gone(:)
      type(error_t), allocatable :: err

      call section(s, 'linalg: caller-dropped constraints')
      call random_constraints(n, cs)
      call assemble(cs, a)
      call to_dense(a, sd)
      call random_number(b)
      gone = [2, 17, 18, 33, 50]
      drop = .false.
      drop(gone) = .true.
      call sp%refactorize(n, a%ap, a%ai, a%ax, nbad, bad, err, drop=drop)
      call check(s, .not. allocated(err) .and. nbad == 0 .and. sp%nremoved == size(gone), &
                 'sparse: dropped constraints are not reported as redundant')
      call sp%solve(b, x)
      call check(s, all(x(gone) == 0.0_wp), 'sparse: dropped multipliers are zero')
      call compare_reduced(s, a, gone, b, x, 'sparse drop')
      call de%factorize(sd, nbad, bad, err, drop=drop)
      call check(s, .not. allocated(err) .and. nbad == 0 .and. de%rank == n - size(gone), &
                 'dense: dropped constraints are not reported as redundant')
      call de%solve(b, x)
      call check(s, all(x(gone) == 0.0_wp), 'dense: dropped multipliers are zero')
      call compare_reduced(s, a, gone, b, x, 'dense drop')
   end subroutine test_drop_mask

   !> 3d. The rule D(k) <= tol S(k,k) on two nearly parallel constraints, D(2)/S(2,2) = delta,
   !>     with and without a diagonal scaling (the rule must not depend on it); bad input.
   subroutine test_pivot_rule(s)
      type(suite_t), intent(inout) :: s
      real(wp), parameter :: deltas(2) = [1.0e-12_wp, 1.0e-8_wp], scales(2) = [1.0_wp, 1.0e3_wp]
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp) :: sd(2, 2), c, d(2), nan
      integer :: bad(2), nbad, i, j
      logical :: expect
      type(error_t), allocatable :: err
      character(len=60) :: tag

      call section(s, 'linalg: pivot rule and bad input')
      do i = 1, size(deltas)
         do j = 1, size(scales)
            c = sqrt(1.0_wp - deltas(i))
            d = [scales(j), 1.0_wp/scales(j)]
            sd = reshape([d(1)**2, c*d(1)*d(2), c*d(1)*d(2), d(2)**2], [2, 2])
            expect = deltas(i) <= sp%tol
            write (tag, '(a,es8.1,a,es8.1)') 'delta ', deltas(i), ', scale ', scales(j)
            call from_dense(sd, a)
            call sp%refactorize(2, a%ap, a%ai, a%ax, nbad, bad, err)
            call check(s, .not. allocated(err) .and. ((nbad == 1) .eqv. expect), &
                       'sparse: '//trim(tag)//merge(': flagged    ', ': not flagged', expect))
            call de%factorize(sd, nbad, bad, err)
            call check(s, .not. allocated(err) .and. ((nbad == 1) .eqv. expect), &
                       'dense:  '//trim(tag)//merge(': flagged    ', ': not flagged', expect))
         end do
      end do

      nan = ieee_value(1.0_wp, ieee_quiet_nan)
      sd = reshape([1.0_wp, 0.5_wp, 0.5_wp, nan], [2, 2])
      call from_dense(sd, a)
      call sp%refactorize(2, a%ap, a%ai, a%ax, nbad, bad, err)
      call check(s, allocated(err) .and. .not. sp%factorized, 'sparse: NaN entry is an error')
      call de%factorize(sd, nbad, bad, err)
      call check(s, allocated(err) .and. .not. de%factorized, 'dense: NaN entry is an error')
      sd = reshape([1.0_wp, nan, nan, 1.0_wp], [2, 2])
      call from_dense(sd, a)
      call sp%refactorize(2, a%ap, a%ai, a%ax, nbad, bad, err)
      call check(s, allocated(err) .and. .not. sp%factorized, 'sparse: NaN off the diagonal is an error')
      call de%factorize(sd, nbad, bad, err)
      call check(s, allocated(err) .and. .not. de%factorized, 'dense: NaN off the diagonal is an error')
      call sp%free()
      call sp%factorize(a%ax, nbad, bad, err)
      call check(s, allocated(err), 'sparse: factorize before analyze is an error')
      call sp%analyze(2, [1, 2, 3], [1, 3], err)
      call check(s, allocated(err), 'sparse: row index out of range is an error')
   end subroutine test_pivot_rule

   !> 4. A contact line of 1e5 node-on-segment constraints (tridiagonal-like S), with a few
   !>    two-pass duplicates.
   subroutine test_large_chain(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nbase = 100000, ndup = 10, n = nbase + ndup
      type(cset_t) :: base, cs
      type(csc_t) :: a
      type(sparse_ldl_t) :: sp
      real(wp), allocatable :: b(:), x(:), z(:)
      integer, allocatable :: bad(:)
      integer :: k, nbad, nfound
      integer(i8) :: t0, t1, t2, rate
      type(error_t), allocatable :: err
      character(len=100) :: buf

      call section(s, 'linalg: contact line, n = 1e5')
      call chain_constraints(nbase, base)
      call extend(base, n, cs)
      do k = 1, ndup
         cs%node(:, nbase + k) = cs%node(:, k*(nbase/ndup) - 1)
         cs%w(:, :, nbase + k) = cs%w(:, :, k*(nbase/ndup) - 1)
      end do
      call assemble(cs, a)
      allocate (b(n), x(n), z(n), bad(n))
      call random_number(z)
      call matvec(a, z, b)
      call system_clock(t0, rate)
      call sp%analyze(n, a%ap, a%ai, err)
      call system_clock(t1)
      call sp%factorize(a%ax, nbad, bad, err)
      call sp%solve(b, x)
      call system_clock(t2)
      write (buf, '(a,f8.4,a,f8.4,a)') '   time: analyze ', real(t1 - t0, wp)/real(rate, wp), &
         ' s, factorize + solve ', real(t2 - t1, wp)/real(rate, wp), ' s (debug build)'
      print '(a)', trim(buf)
      call check(s, .not. allocated(err) .and. nbad == ndup, 'one constraint of each duplicate pair flagged')
      nfound = 0
      do k = 1, ndup
         if (one_each(bad(1:nbad), [k*(nbase/ndup) - 1, nbase + k], [integer ::])) nfound = nfound + 1
      end do
      call check(s, nfound == ndup, 'flags are the duplicated constraints')
      call check_rel(s, residual(a, x, b), 1.0e-12_wp, 'reduced solution satisfies all 1e5 rows')
      ! plain chain (no duplicates), reusing nothing: new pattern
      call assemble(base, a)
      call matvec(a, z(1:nbase), b(1:nbase))
      call sp%refactorize(nbase, a%ap, a%ai, a%ax, nbad, bad, err)
      call sp%solve(b(1:nbase), x(1:nbase))
      call check(s, .not. allocated(err) .and. nbad == 0, 'plain chain: nothing flagged')
      call check_rel(s, residual(a, x(1:nbase), b(1:nbase)), 1.0e-12_wp, 'plain chain: residual')
   end subroutine test_large_chain

   ! ---------------------------------------------------------------- helpers: checks

   !> Check value <= tol, printing both.
   subroutine check_rel(s, value, tol, name)
      type(suite_t), intent(inout) :: s
      real(wp), intent(in) :: value, tol
      character(len=*), intent(in) :: name
      character(len=60) :: buf
      write (buf, '(a,es10.3,a,es10.3,a)') '(', value, ' <= ', tol, ')'
      call check(s, value <= tol, name//'  '//trim(buf))
   end subroutine check_rel

   !> True when list holds exactly one member of group1 and, if group2 is not empty, exactly
   !> one of group2 (and nothing else when both are given).
   logical function one_each(list, group1, group2) result(ok)
      integer, intent(in) :: list(:), group1(:), group2(:)
      integer :: c1, c2, k
      c1 = 0
      c2 = 0
      do k = 1, size(list)
         if (any(group1 == list(k))) c1 = c1 + 1
         if (any(group2 == list(k))) c2 = c2 + 1
      end do
      if (size(group2) == 0) then
         ok = (c1 == 1)
      else
         ok = (c1 == 1 .and. c2 == 1 .and. size(list) == 2)
      end if
   end function one_each

   !> The solution x of the system with constraints `gone` removed equals the solution of the
   !> explicitly reduced system (rows and columns deleted), solved by both paths.
   subroutine compare_reduced(s, a, gone, b, x, tag)
      type(suite_t), intent(inout) :: s
      type(csc_t), intent(in) :: a
      integer, intent(in) :: gone(:)
      real(wp), intent(in) :: b(:), x(:)
      character(len=*), intent(in) :: tag
      type(csc_t) :: r
      type(sparse_ldl_t) :: sp
      type(dense_spd_t) :: de
      real(wp), allocatable :: sd(:, :), br(:), xr(:), xk(:)
      integer, allocatable :: keep(:), bad(:)
      logical :: mask(a%n)
      integer :: nbad, m
      type(error_t), allocatable :: err
      real(wp) :: tol

      mask = .true.
      mask(gone) = .false.
      keep = pack([(m, m=1, a%n)], mask)
      m = size(keep)
      call to_dense(a, sd)
      sd = sd(keep, keep)
      call from_dense(sd, r)
      br = b(keep)
      xk = x(keep)
      allocate (xr(m), bad(m))
      tol = cholesky_bound(m, condition(sd))
      call sp%refactorize(m, r%ap, r%ai, r%ax, nbad, bad, err)
      call sp%solve(br, xr)
      call check(s, .not. allocated(err) .and. nbad == 0, tag//': reduced system is regular')
      call check_rel(s, norm2(xk - xr)/norm2(xr), tol, tag//': = sparse solution of reduced system')
      call de%factorize(sd, nbad, bad, err)
      call de%solve(br, xr)
      call check_rel(s, norm2(xk - xr)/norm2(xr), tol, tag//': = dense solution of reduced system')
   end subroutine compare_reduced

   !> Forward error bound of a Cholesky solve, 2 gamma(3n+1) cond(S) ~ 2 (3n+1) eps cond(S)
   !> (Higham, Accuracy and Stability of Numerical Algorithms, thm. 10.4 with eq. 7.2).
   pure real(wp) function cholesky_bound(n, kappa) result(tol)
      integer, intent(in) :: n
      real(wp), intent(in) :: kappa
      tol = 2.0_wp*real(3*n + 1, wp)*kappa*eps
   end function cholesky_bound

   !> 2-norm condition number of the symmetric matrix sd (dsyev).
   real(wp) function condition(sd) result(kappa)
      real(wp), intent(in) :: sd(:, :)
      real(wp), allocatable :: w(:), work(:), c(:, :)
      integer :: n, info
      n = size(sd, 1)
      c = sd
      allocate (w(n), work(max(1, 3*n)))
      call dsyev('N', 'L', n, c, n, w, work, size(work), info)
      kappa = huge(1.0_wp)
      if (info == 0 .and. w(1) > 0.0_wp) kappa = w(n)/w(1)
   end function condition

   ! ---------------------------------------------------------------- helpers: matrices

   !> ||S x - b|| / ||b||.
   real(wp) function residual(a, x, b) result(r)
      type(csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:), b(:)
      real(wp), allocatable :: y(:)
      allocate (y(a%n))
      call matvec(a, x, y)
      r = norm2(y - b(1:a%n))/norm2(b(1:a%n))
   end function residual

   !> y = S x.
   subroutine matvec(a, x, y)
      type(csc_t), intent(in) :: a
      real(wp), intent(in) :: x(:)
      real(wp), intent(out) :: y(:)
      integer :: j, q
      y(1:a%n) = 0.0_wp
      do j = 1, a%n
         do q = a%ap(j), a%ap(j + 1) - 1
            y(a%ai(q)) = y(a%ai(q)) + a%ax(q)*x(j)
         end do
      end do
   end subroutine matvec

   !> Dense copy of a.
   subroutine to_dense(a, sd)
      type(csc_t), intent(in) :: a
      real(wp), allocatable, intent(out) :: sd(:, :)
      integer :: j, q
      allocate (sd(a%n, a%n), source=0.0_wp)
      do j = 1, a%n
         do q = a%ap(j), a%ap(j + 1) - 1
            sd(a%ai(q), j) = sd(a%ai(q), j) + a%ax(q)
         end do
      end do
   end subroutine to_dense

   !> Compressed columns of the structurally nonzero entries of sd, plus the diagonal.
   subroutine from_dense(sd, a)
      real(wp), intent(in) :: sd(:, :)
      type(csc_t), intent(out) :: a
      integer :: i, j, q
      a%n = size(sd, 1)
      allocate (a%ap(a%n + 1), a%ai(count(sd /= 0.0_wp) + a%n), a%ax(count(sd /= 0.0_wp) + a%n))
      q = 0
      a%ap(1) = 1
      do j = 1, a%n
         do i = 1, a%n
            if (sd(i, j) == 0.0_wp .and. i /= j) cycle
            q = q + 1
            a%ai(q) = i
            a%ax(q) = sd(i, j)
         end do
         a%ap(j + 1) = q + 1
      end do
   end subroutine from_dense

   !> q = P S P^T with q(perm(i), perm(j)) = S(i, j), rows sorted.
   subroutine permuted(a, perm, q)
      type(csc_t), intent(in) :: a
      integer, intent(in) :: perm(:)
      type(csc_t), intent(out) :: q
      real(wp), allocatable :: sd(:, :), sq(:, :)
      integer :: i, j
      call to_dense(a, sd)
      allocate (sq(a%n, a%n))
      do j = 1, a%n
         do i = 1, a%n
            sq(perm(i), perm(j)) = sd(i, j)
         end do
      end do
      call from_dense(sq, q)
   end subroutine permuted

   !> S = G^T M^-1 G in compressed columns, full pattern, rows sorted in each column.
   subroutine assemble(cs, a)
      type(cset_t), intent(in) :: cs
      type(csc_t), intent(out) :: a
      integer, allocatable :: start(:), list(:), fill(:), mark(:), rows(:)
      integer :: c, p, nd, i, j, q, nr, cap
      a%n = cs%nc
      allocate (start(cs%nnode + 1), source=0)
      do c = 1, cs%nc
         do p = 1, nslot
            if (cs%node(p, c) > 0) start(cs%node(p, c) + 1) = start(cs%node(p, c) + 1) + 1
         end do
      end do
      start(1) = 1
      do nd = 1, cs%nnode
         start(nd + 1) = start(nd + 1) + start(nd)
      end do
      allocate (list(start(cs%nnode + 1) - 1), fill(cs%nnode), mark(cs%nc), rows(cs%nc))
      fill = start(1:cs%nnode)
      do c = 1, cs%nc
         do p = 1, nslot
            nd = cs%node(p, c)
            if (nd == 0) cycle
            list(fill(nd)) = c
            fill(nd) = fill(nd) + 1
         end do
      end do
      cap = 0
      do c = 1, cs%nc
         do p = 1, nslot
            if (cs%node(p, c) > 0) cap = cap + start(cs%node(p, c) + 1) - start(cs%node(p, c))
         end do
      end do
      allocate (a%ap(cs%nc + 1), a%ai(max(cap, cs%nc)), a%ax(max(cap, cs%nc)))
      mark = 0
      a%ap(1) = 1
      q = 0
      do j = 1, cs%nc
         nr = 1
         rows(1) = j
         mark(j) = j
         do p = 1, nslot
            nd = cs%node(p, j)
            if (nd == 0) cycle
            do i = start(nd), start(nd + 1) - 1
               if (mark(list(i)) == j) cycle
               mark(list(i)) = j
               nr = nr + 1
               rows(nr) = list(i)
            end do
         end do
         call sort(rows(1:nr))
         do i = 1, nr
            q = q + 1
            a%ai(q) = rows(i)
            a%ax(q) = entry(cs, rows(i), j)
         end do
         a%ap(j + 1) = q + 1
      end do
   end subroutine assemble

   !> S(i, j) = sum over shared nodes of w_i . w_j / m.
   real(wp) function entry(cs, i, j) result(v)
      type(cset_t), intent(in) :: cs
      integer, intent(in) :: i, j
      integer :: p, r
      v = 0.0_wp
      do p = 1, nslot
         if (cs%node(p, i) == 0) cycle
         do r = 1, nslot
            if (cs%node(r, j) /= cs%node(p, i)) cycle
            v = v + dot_product(cs%w(:, p, i), cs%w(:, r, j))*cs%minv(cs%node(p, i))
         end do
      end do
   end function entry

   !> Insertion sort (short lists).
   subroutine sort(v)
      integer, intent(inout) :: v(:)
      integer :: i, j, t
      do i = 2, size(v)
         t = v(i)
         j = i - 1
         do while (j >= 1)
            if (v(j) <= t) exit
            v(j + 1) = v(j)
            j = j - 1
         end do
         v(j + 1) = t
      end do
   end subroutine sort

   ! ---------------------------------------------------------------- helpers: constraint sets

   !> nc node-on-segment constraints: slave c on a random master segment of a random
   !> master line, normal within 0.3 rad of vertical; random masses, a few rigid masters.
   subroutine random_constraints(nc, cs)
      integer, intent(in) :: nc
      type(cset_t), intent(out) :: cs
      integer :: c, nm, m, perm(nc + nc/2 + 2)
      real(wp) :: r(3), alpha, nrm(2)
      nm = nc/2 + 2
      cs%nc = nc
      cs%nnode = nc + nm
      allocate (cs%node(nslot, nc), source=0)
      allocate (cs%w(2, nslot, nc), source=0.0_wp)
      allocate (cs%minv(cs%nnode))
      call random_number(cs%minv)
      cs%minv = 1.0_wp/(0.5_wp + 1.5_wp*cs%minv)
      cs%minv(nc + 1) = 0.0_wp                    ! one rigid master node
      call random_permutation(cs%nnode, perm)      ! random node numbering
      do c = 1, nc
         call random_number(r)
         m = nc + 1 + int(r(1)*(nm - 1))
         m = min(m, nc + nm - 1)
         alpha = r(2)
         nrm = [sin(0.6_wp*(r(3) - 0.5_wp)), cos(0.6_wp*(r(3) - 0.5_wp))]
         cs%node(1:3, c) = [c, m, m + 1]
         cs%w(:, 1, c) = nrm
         cs%w(:, 2, c) = -(1.0_wp - alpha)*nrm
         cs%w(:, 3, c) = -alpha*nrm
      end do
      call renumber(cs, perm)
   end subroutine random_constraints

   !> A contact line: slave c on master segment (c, c+1), so S is tridiagonal-like.
   subroutine chain_constraints(nc, cs)
      integer, intent(in) :: nc
      type(cset_t), intent(out) :: cs
      integer :: c
      real(wp) :: r(2), nrm(2)
      cs%nc = nc
      cs%nnode = 2*nc + 1
      allocate (cs%node(nslot, nc), source=0)
      allocate (cs%w(2, nslot, nc), source=0.0_wp)
      allocate (cs%minv(cs%nnode))
      call random_number(cs%minv)
      cs%minv = 1.0_wp/(0.5_wp + 1.5_wp*cs%minv)
      do c = 1, nc
         call random_number(r)
         nrm = [sin(0.2_wp*(r(2) - 0.5_wp)), cos(0.2_wp*(r(2) - 0.5_wp))]
         cs%node(1:3, c) = [c, nc + c, nc + c + 1]
         cs%w(:, 1, c) = nrm
         cs%w(:, 2, c) = -(1.0_wp - r(1))*nrm
         cs%w(:, 3, c) = -r(1)*nrm
      end do
   end subroutine chain_constraints

   !> Copy cs into a set of n >= cs%nc constraints (the extra ones empty).
   subroutine extend(cs, n, out)
      type(cset_t), intent(in) :: cs
      integer, intent(in) :: n
      type(cset_t), intent(out) :: out
      out%nc = n
      out%nnode = cs%nnode
      out%minv = cs%minv
      allocate (out%node(nslot, n), source=0)
      allocate (out%w(2, nslot, n), source=0.0_wp)
      out%node(:, 1:cs%nc) = cs%node
      out%w(:, :, 1:cs%nc) = cs%w
   end subroutine extend

   !> Node k becomes perm(k).
   subroutine renumber(cs, perm)
      type(cset_t), intent(inout) :: cs
      integer, intent(in) :: perm(:)
      real(wp), allocatable :: minv(:)
      integer :: c, p
      minv = cs%minv
      do p = 1, cs%nnode
         cs%minv(perm(p)) = minv(p)
      end do
      do c = 1, cs%nc
         do p = 1, nslot
            if (cs%node(p, c) > 0) cs%node(p, c) = perm(cs%node(p, c))
         end do
      end do
   end subroutine renumber

   !> A random permutation of 1..n (Fisher-Yates).
   subroutine random_permutation(n, perm)
      integer, intent(in) :: n
      integer, intent(out) :: perm(:)
      integer :: i, j, t
      real(wp) :: r
      perm(1:n) = [(i, i=1, n)]
      do i = n, 2, -1
         call random_number(r)
         j = 1 + int(r*i)
         j = min(j, i)
         t = perm(i)
         perm(i) = perm(j)
         perm(j) = t
      end do
   end subroutine random_permutation

   !> Fixed seed: the tests are deterministic.
   subroutine seed_random()
      integer :: k, n
      integer, allocatable :: seed(:)
      call random_seed(size=n)
      allocate (seed(n))
      seed = [(104729*k + 17, k=1, n)]
      call random_seed(put=seed)
   end subroutine seed_random

end module test_linalg
