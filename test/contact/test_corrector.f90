!> The contact corrector's solver: its multipliers solve the linear complementarity problem of
!> the seed's eq. 4.5-4.7 (p >= 0, g = g~ + c S p >= 0, p g = 0), compared with the solution
!> found by trying every active set.
module test_corrector
   use exic_base_kinds, only: wp, i8
   use exic_base_strings, only: itoa, rtoa
   use exic_base_error, only: error_t
   use exic_contact_corrector, only: constraints_t, corrector_t
   use testing, only: suite_t, check, section
   implicit none
   private

   public :: run_corrector_tests

contains

   subroutine run_corrector_tests(s)
      type(suite_t), intent(inout) :: s
      call section(s, 'corrector: complementarity of the multipliers')
      call corrector_complementarity(s)
      call section(s, 'corrector: components of S')
      call corrector_components(s)
      call corrector_blocks(s)
   end subroutine run_corrector_tests

   !> Components factorised as blocks of their own (exic_linalg_block_ldl, doc/contact-detection.md
   !> eq. D.6) give the bits of the sparse LDL' of all of S in the components' order (eq. D.5):
   !> 60 patches of 1 to 4 candidates on their own nodes, in random directions, interleaved in
   !> the candidate list, each with a node-on-node pair (two candidates with the same column of
   !> G, one node's slave on the other and back: the later one is removed as redundant) and gaps of both signs (passes that drop
   !> candidates, with blocks whose mask is unchanged kept from the pass before).
   subroutine corrector_blocks(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: npatch = 60, maxc = 5
      type(constraints_t) :: cs, cs2
      type(corrector_t) :: corr, ref
      type(error_t), allocatable :: e, e2
      real(wp), allocatable :: a(:, :), f(:, :), a2(:, :), f2(:, :), mi(:, :)
      integer, allocatable :: nc(:), order(:)
      real(wp) :: alpha, gap, ang, nrm(2)
      integer :: i, j, c, k, nnode, m, base, t
      integer(i8) :: seed
      logical :: same

      seed = 4242_i8
      allocate (nc(npatch))
      do c = 1, npatch
         nc(c) = 1 + int(4.0_wp*rnd(seed))
      end do
      ! patch c: nodes base+1 ... base+maxc+2; candidate k of it: slave base+k against the
      ! segment (base+k+1, base+k+2); its last one also the other way round, node on node
      nnode = npatch*(maxc + 2)
      allocate (mi(2, nnode))
      do i = 1, nnode
         mi(:, i) = 0.5_wp + 1.5_wp*rnd(seed)
      end do
      m = sum(nc) + npatch
      ! the candidates of the patches interleaved: a random permutation of the list
      allocate (order(m))
      order = [(i, i=1, m)]
      do i = m, 2, -1
         j = 1 + int(real(i, wp)*rnd(seed))
         j = min(j, i)
         t = order(i)
         order(i) = order(j)
         order(j) = t
      end do
      call cs%reserve(m)
      call cs2%reserve(m)
      do j = 1, m
         t = order(j)
         ! t-th candidate of the patches in turn
         do c = 1, npatch
            if (t <= nc(c) + 1) exit
            t = t - nc(c) - 1
         end do
         base = (c - 1)*(maxc + 2)
         ang = 6.283185307179586_wp*rnd(seed)
         nrm = [cos(ang), sin(ang)]
         alpha = 0.1_wp + 0.8_wp*rnd(seed)
         gap = 1.6_wp*rnd(seed) - 1.0_wp
         if (t <= nc(c)) then
            k = base + t
            call cs%add(k, k + 1, k + 2, alpha, nrm, gap, 0.0_wp, 1)
            call cs2%add(k, k + 1, k + 2, alpha, nrm, gap, 0.0_wp, 1)
         else
            ! node on node: slave base+2 on node base+1 (alpha 0), normal +y, the first
            ! candidate of the patch from the other side (below): the same column of G
            k = base + 1
            call cs%add(k + 1, k, k + 3, 0.0_wp, [0.0_wp, 1.0_wp], gap, 0.0_wp, 1)
            call cs2%add(k + 1, k, k + 3, 0.0_wp, [0.0_wp, 1.0_wp], gap, 0.0_wp, 1)
         end if
      end do
      ! the first candidate of each patch: slave base+1 on node base+2 (alpha 0), normal -y
      do j = 1, m
         t = order(j)
         do c = 1, npatch
            if (t <= nc(c) + 1) exit
            t = t - nc(c) - 1
         end do
         if (t /= 1) cycle
         cs%w(2:3, j) = [-1.0_wp, 0.0_wp]
         cs2%w(2:3, j) = [-1.0_wp, 0.0_wp]
         cs%nrm(:, j) = [0.0_wp, -1.0_wp]
         cs2%nrm(:, j) = [0.0_wp, -1.0_wp]
      end do
      allocate (a(2, nnode), f(2, nnode), a2(2, nnode), f2(2, nnode), source=0.0_wp)
      call corr%solve(cs, nnode, mi, 1.0_wp, a, f, e)
      ref%by_blocks = .false.
      call ref%solve(cs2, nnode, mi, 1.0_wp, a2, f2, e2)
      same = all(cs%p(1:m) == cs2%p(1:m)) .and. all(cs%active(1:m) .eqv. cs2%active(1:m)) .and. &
             all(a == a2) .and. all(f == f2)
      call check(s, .not. allocated(e) .and. .not. allocated(e2) .and. corr%blocks .and. &
                 .not. ref%blocks .and. ref%sparse%given .and. corr%ncomp == npatch .and. &
                 corr%nredundant > 0 .and. corr%passes > 1, &
                 'corrector: a step of 60 patches with node-on-node pairs goes by blocks, removes '// &
                 'redundant pairs and pivots', 'components '//itoa(corr%ncomp)//', candidates '// &
                 itoa(m)//', redundant '//itoa(corr%nredundant)//', passes '//itoa(corr%passes)// &
                 ', factorisations '//itoa(corr%nsolves))
      call check(s, same .and. corr%nredundant == ref%nredundant .and. corr%passes == ref%passes, &
                 'corrector: blocks factorised on their own give the bits of the sparse LDL'' in '// &
                 'the components'' order', 'active '//itoa(count(cs%active(1:m)))//' of '//itoa(m)// &
                 ', largest |p - p_ref| '//rtoa(maxval(abs(cs%p(1:m) - cs2%p(1:m)))))
   end subroutine corrector_blocks

   !> Three contact lines with no node in common, their candidates interleaved (candidate i on
   !> line mod(i - 1, 3) + 1): S is block diagonal with three blocks (doc/contact-detection.md
   !> eq. D.3-D.5). The components are found and listed in candidate order, the sparse
   !> factorisation eliminates them one after the other, and the multipliers agree with those
   !> of the same problem ordered by AMD as a whole to round-off, with the same active set, and
   !> solve the complementarity problem.
   subroutine corrector_components(s)
      type(suite_t), intent(inout) :: s
      integer, parameter :: nline = 3, nper = 20, m = nline*nper
      type(constraints_t) :: cs, cs2
      type(corrector_t) :: corr, whole
      type(error_t), allocatable :: e, e2
      real(wp), allocatable :: a(:, :), f(:, :), a2(:, :), f2(:, :), mi(:, :)
      real(wp) :: alpha, gap, g, worst_g, diff, pmax
      integer :: i, line, k, nnode, slave, master, base
      integer(i8) :: seed
      logical :: listed

      ! line l: slaves base+1..base+nper above masters base+nper+1..base+2 nper+1
      nnode = nline*(2*nper + 1)
      seed = 777_i8
      allocate (mi(2, nnode))
      do i = 1, nnode
         mi(:, i) = 0.5_wp + 1.5_wp*rnd(seed)
      end do
      call cs%reserve(m)
      call cs2%reserve(m)
      do i = 1, m
         line = mod(i - 1, nline) + 1
         k = (i - 1)/nline + 1
         base = (line - 1)*(2*nper + 1)
         slave = base + k
         master = base + nper + k
         alpha = 0.2_wp + 0.6_wp*rnd(seed)
         gap = 2.0_wp*rnd(seed) - 1.2_wp
         call cs%add(slave, master, master + 1, alpha, [0.0_wp, 1.0_wp], gap, 0.0_wp, 1)
         call cs2%add(slave, master, master + 1, alpha, [0.0_wp, 1.0_wp], gap, 0.0_wp, 1)
      end do
      allocate (a(2, nnode), f(2, nnode), a2(2, nnode), f2(2, nnode), source=0.0_wp)
      call corr%solve(cs, nnode, mi, 1.0_wp, a, f, e)
      whole%split = .false.
      call whole%solve(cs2, nnode, mi, 1.0_wp, a2, f2, e2)
      listed = corr%ncomp == nline
      if (listed) then
         do line = 1, nline
            do k = 1, nper
               i = corr%comp%list(corr%comp%start(line) + k - 1)
               if (i /= line + (k - 1)*nline .or. corr%comp%loc(i) /= k) listed = .false.
            end do
         end do
      end if
      call check(s, .not. allocated(e) .and. listed .and. corr%blocks .and. .not. whole%sparse%given, &
                 'corrector: three contact lines are three components, each listed in candidate order', &
                 'components '//itoa(corr%ncomp))
      pmax = maxval(abs(cs2%p(1:m)))
      diff = maxval(abs(cs%p(1:m) - cs2%p(1:m)))/pmax
      call check(s, .not. allocated(e2) .and. pmax > 0.0_wp .and. diff <= 1.0e-12_wp .and. &
                 all(cs%active(1:m) .eqv. cs2%active(1:m)), &
                 'corrector: multipliers by components equal those of the AMD-ordered S to round-off', &
                 'largest difference '//rtoa(diff)//' of the largest multiplier, active '// &
                 itoa(count(cs%active(1:m)))//' of '//itoa(m))
      ! corrected gaps g = g~ + c G^T a with a = M^-1 G p (c = 1)
      worst_g = 0.0_wp
      do i = 1, m
         g = cs%gap(i)
         do k = 1, 3
            g = g + cs%w(k, i)*dot_product(cs%nrm(:, i), a(:, cs%node(k, i)))
         end do
         worst_g = max(worst_g, -g, abs(cs%p(i)*g)/pmax)
      end do
      call check(s, all(cs%p(1:m) >= 0.0_wp) .and. worst_g <= 1.0e-12_wp, &
                 'corrector: multipliers by components solve the complementarity problem', &
                 'largest violation '//rtoa(worst_g))
   end subroutine corrector_components

   !> The corrector's multipliers solve the complementarity problem p >= 0, g = g~ + c S p >= 0,
   !> p g = 0 exactly. Instances: one where releasing every tensile multiplier at once and never
   !> re-checking those released left a gap open by 2.03 (the fault the decks of 7.4 showed as
   !> two bar ends passing through each other), and 300 pseudo-random ones; the reference
   !> solution is found by trying every active set.
   subroutine corrector_complementarity(s)
      type(suite_t), intent(inout) :: s
      integer :: inst, m, nnode, i, worst_inst, nskip
      integer, allocatable :: nodes(:, :)
      real(wp), allocatable :: alpha(:), sgn(:), gap(:), minv(:)
      real(wp) :: worst, err_i
      integer(i8) :: seed
      logical :: found_all

      ! the instance the old active-set loop got wrong
      nodes = reshape([1, 2, 4, 3, 2, 1, 1, 4, 2], [3, 3])
      alpha = [0.71_wp, 0.21_wp, 0.4_wp]
      sgn = [-1.0_wp, 1.0_wp, -1.0_wp]
      gap = [-2.02_wp, -2.04_wp, -0.1_wp]
      minv = [0.8_wp, 0.7_wp, 1.2_wp, 0.5_wp]
      found_all = .true.
      call lcp_error(nodes, alpha, sgn, gap, minv, err_i, found_all)
      call check(s, found_all .and. err_i <= 1.0e-10_wp, &
                 'corrector: multipliers of the instance with a released, still violated gap', &
                 'difference from the complementarity solution '//rtoa(err_i))
      seed = 12345_i8
      worst = 0.0_wp
      worst_inst = 0
      nskip = 0
      found_all = .true.
      do inst = 1, 300
         m = 2 + int(3.0_wp*rnd(seed))
         nnode = 5 + int(3.0_wp*rnd(seed))
         deallocate (nodes, alpha, sgn, gap, minv)
         allocate (nodes(3, m), alpha(m), sgn(m), gap(m), minv(nnode))
         do i = 1, m
            call three_distinct(seed, nnode, nodes(:, i))
            alpha(i) = rnd(seed)
            sgn(i) = merge(1.0_wp, -1.0_wp, rnd(seed) < 0.5_wp)
            gap(i) = 2.0_wp*rnd(seed) - 1.2_wp
         end do
         minv = 0.5_wp + 1.5_wp*[(rnd(seed), i=1, nnode)]
         call lcp_error(nodes, alpha, sgn, gap, minv, err_i, found_all)
         if (err_i < 0.0_wp) then
            nskip = nskip + 1           ! dependent constraints: S singular
            cycle
         end if
         if (err_i > worst) then
            worst = err_i
            worst_inst = inst
         end if
      end do
      call check(s, found_all .and. worst <= 1.0e-9_wp .and. nskip <= 100, 'corrector: multipliers of 300 '// &
                 'random instances solve the complementarity problem', 'largest difference '//rtoa(worst)// &
                 ' (instance '//itoa(worst_inst)//'), singular instances skipped '//itoa(nskip))
   end subroutine corrector_complementarity

   !> Solve one instance (1-D constraints along x: node s against the point (1 - alpha) m1 +
   !> alpha m2, normal sgn x) with the corrector and by enumeration; err: largest difference of
   !> the multipliers, relative to the largest; err = -1 for an instance whose constraints are
   !> dependent (S singular: skipped). found is cleared when the corrector fails or an instance
   !> has no complementarity solution (not expected for independent constraints).
   subroutine lcp_error(nodes, alpha, sgn, gap, minv, err, found)
      integer, intent(in) :: nodes(:, :)
      real(wp), intent(in) :: alpha(:), sgn(:), gap(:), minv(:)
      real(wp), intent(out) :: err
      logical, intent(inout) :: found
      type(constraints_t) :: cs
      type(corrector_t) :: corr
      type(error_t), allocatable :: e
      real(wp), allocatable :: a(:, :), f(:, :), mi(:, :), smat(:, :), pref(:), g(:), pf(:)
      real(wp) :: c
      integer :: m, nn, i, j, k, mask, nf
      integer, allocatable :: idx(:)
      logical :: ok

      m = size(gap)
      nn = size(minv)
      c = 1.0_wp
      call cs%reserve(m)
      do i = 1, m
         call cs%add(nodes(1, i), nodes(2, i), nodes(3, i), alpha(i), [sgn(i), 0.0_wp], gap(i), 0.0_wp, 1)
      end do
      allocate (a(2, nn), f(2, nn), mi(2, nn), source=0.0_wp)
      mi(1, :) = minv
      mi(2, :) = minv
      call corr%solve(cs, nn, mi, c, a, f, e)
      err = huge(1.0_wp)
      if (allocated(e)) then
         found = .false.
         return
      end if
      ! S = G^T M^-1 G along x
      allocate (smat(m, m), pref(m), g(m))
      smat = 0.0_wp
      do i = 1, m
         do j = 1, m
            do k = 1, 3
               smat(i, j) = smat(i, j) + sgn(i)*sgn(j)*weight(i, nodes(k, j))*cs%w(k, j)*minv(nodes(k, j))
            end do
         end do
      end do
      ! dependent constraints (S singular) have no unique solution: skip
      allocate (pf(m))
      call dense_solve(smat, gap, pf, ok)
      deallocate (pf)
      if (.not. ok) then
         err = -1.0_wp
         return
      end if
      ! enumeration of the active sets
      ok = .false.
      do mask = 0, 2**m - 1
         idx = pack([(i, i=1, m)], [(btest(mask, i - 1), i=1, m)])
         nf = size(idx)
         pref = 0.0_wp
         if (nf > 0) then
            allocate (pf(nf))
            call dense_solve(smat(idx, idx), -gap(idx)/c, pf, ok)
            pref(idx) = pf
            deallocate (pf)
            if (.not. ok) cycle
         end if
         g = gap + c*matmul(smat, pref)
         if (all(pref >= -1.0e-12_wp*max(1.0_wp, maxval(abs(pref)))) .and. &
             all(g >= -1.0e-10_wp*max(1.0_wp, maxval(abs(gap))))) then
            ok = .true.
            exit
         end if
         ok = .false.
      end do
      if (.not. ok) then
         found = .false.
         return
      end if
      err = maxval(abs(cs%p(1:m) - pref))/max(1.0_wp, maxval(abs(pref)))
   contains
      !> Weight of node nd in constraint i (sum over its occurrences).
      real(wp) function weight(ic, nd)
         integer, intent(in) :: ic, nd
         integer :: q
         weight = 0.0_wp
         do q = 1, 3
            if (nodes(q, ic) == nd) weight = weight + cs%w(q, ic)
         end do
      end function weight
   end subroutine lcp_error

   !> Gaussian elimination with partial pivoting; ok false for a (nearly) singular matrix.
   subroutine dense_solve(amat, b, x, ok)
      real(wp), intent(in) :: amat(:, :), b(:)
      real(wp), intent(out) :: x(:)
      logical, intent(out) :: ok
      real(wp) :: w(size(b), size(b) + 1), scale, tmp(size(b) + 1)
      integer :: n, i, k, p
      n = size(b)
      w(:, 1:n) = amat
      w(:, n + 1) = b
      scale = maxval(abs(amat))
      ok = .false.
      do k = 1, n
         p = k - 1 + maxloc(abs(w(k:n, k)), 1)
         if (abs(w(p, k)) <= 1.0e-9_wp*scale) return
         tmp = w(k, :)
         w(k, :) = w(p, :)
         w(p, :) = tmp
         do i = k + 1, n
            w(i, k:) = w(i, k:) - w(i, k)/w(k, k)*w(k, k:)
         end do
      end do
      do k = n, 1, -1
         x(k) = (w(k, n + 1) - dot_product(w(k, k + 1:n), x(k + 1:n)))/w(k, k)
      end do
      ok = .true.
   end subroutine dense_solve

   !> A pseudo-random number in [0, 1) (64-bit linear congruential generator).
   real(wp) function rnd(seed)
      integer(i8), intent(inout) :: seed
      seed = ieor(seed, ishft(seed, 13))
      seed = ieor(seed, ishft(seed, -7))
      seed = ieor(seed, ishft(seed, 17))
      rnd = real(iand(ishft(seed, -11), 2_i8**52 - 1_i8), wp)/2.0_wp**52
   end function rnd

   !> Three distinct node numbers in 1..n.
   subroutine three_distinct(seed, n, k)
      integer(i8), intent(inout) :: seed
      integer, intent(in) :: n
      integer, intent(out) :: k(3)
      k(1) = 1 + int(n*rnd(seed))
      do
         k(2) = 1 + int(n*rnd(seed))
         if (k(2) /= k(1)) exit
      end do
      do
         k(3) = 1 + int(n*rnd(seed))
         if (k(3) /= k(1) .and. k(3) /= k(2)) exit
      end do
   end subroutine three_distinct

end module test_corrector
