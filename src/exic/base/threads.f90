!> Whether a loop runs in an OpenMP parallel region (doc/decisions.md, "Threads").
!>
!> libgomp enters every `!$omp parallel` construct through GOMP_parallel, also when its `if`
!> clause is false or only one thread is allowed: it builds a team of one and, when the region
!> ends, wakes the team's barrier with a futex system call. That is about a microsecond per
!> region, several regions a step: a third of the step of a 360-element mesh. The loops of a
!> step therefore take their serial branch, which never enters libgomp, unless the work is large
!> enough to share and more than one thread is allowed. Both branches make the same operations
!> in the same order, so the choice never changes a result.
module exic_base_threads
   !$ use omp_lib, only: omp_get_max_threads
   implicit none
   private

   public :: threaded

contains

   !> True when a loop over `n` items (nodes, elements) of which at least `n_min` are worth a
   !> parallel region should run on the threads: n >= n_min and more than one thread allowed.
   !> Always false in a build without OpenMP.
   logical function threaded(n, n_min)
      integer, intent(in) :: n, n_min
      threaded = .false.
      !$ threaded = n >= n_min .and. omp_get_max_threads() > 1
   end function threaded

end module exic_base_threads
