!> The solution program of a deck (BATCh ... END) and its TPLOt requests.
module exic_model_program
   use exic_base_kinds, only: wp
   implicit none
   private

   ! TPLOt request kinds
   integer, parameter, public :: REQ_DISP = 1, REQ_VELO = 2, REQ_ACCE = 3, REQ_STRE = 4, &
                                 REQ_REAC = 5, REQ_CONT = 6, REQ_MOME = 7
   !> [ext] reaction sums over a region's or an edge set's nodes, a rigid body's motion
   integer, parameter, public :: REQ_REAC_REGION = 8, REQ_REAC_SET = 9, REQ_RIGI = 10

   public :: command_t, request_t

   !> Deepest LOOP nesting of a BATCh program.
   integer, parameter, public :: MAX_LOOP_DEPTH = 8

   !> One solution command `name,option,v1,v2,v3` (spec section 5).
   type :: command_t
      character(len=4) :: name = ''          !< first 4 characters, lower case
      character(len=4) :: option = ''        !< second field, lower case
      real(wp) :: v(3) = 0.0_wp
      integer :: jump = 0                    !< LOOP: index of its NEXT; NEXT: index of its LOOP
      real(wp), allocatable :: data(:, :)    !< INITial,VELOcity|RATE: (2, nnode) values read after END
      logical, allocatable :: given(:)       !< INITial: (nnode) node had a record (or was generated)
      character(len=:), allocatable :: where !< file:line
   end type command_t

   !> One TPLOt request. Nearest-node/element requests keep their point until the mesh is known.
   type :: request_t
      integer :: kind = 0                    !< REQ_*
      integer :: id = 0                      !< node, element, pair, region or edge set number
      integer :: comp = 0                    !< dof or component
      logical :: by_point = .false.          !< pick the nearest node/element centroid to xy
      real(wp) :: xy(2) = 0.0_wp
      character(len=:), allocatable :: where
   end type request_t

end module exic_model_program
