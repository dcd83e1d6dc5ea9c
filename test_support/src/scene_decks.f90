!> Decks of scenes that suites of several folders run: the sliding blocks on a floor with
!> friction (suites contact_auto and restart).
module scene_decks
   use exic_base_strings, only: itoa
   implicit none
   private

   public :: sliding_blocks_deck, blocks_contact

   character(len=*), parameter :: nl = new_line('a')

contains

   !> An elastic block launched at 3 along a rigid floor with gravity and Coulomb friction 0.3
   !> slides into a second block at rest and pushes it on (regions 1 and 2; the floor region
   !> 3), DT,CFL so the springs set the step. `contact`: the CONTact block.
   function sliding_blocks_deck(contact, extra) result(deck)
      character(len=*), intent(in) :: contact
      character(len=*), intent(in), optional :: extra   !< BATCh records before the LOOP
      character(len=:), allocatable :: deck
      deck = 'FEAP * * two blocks sliding on a floor, penalty contact with friction'//nl//'0 0 0 2 2 4'//nl// &
             'MATErial,1'//nl//'  SOLId'//nl//'    ELAStic NEOHookean 1000 0.3'//nl//'    DENSity 1'//nl//nl// &
             'MATErial,2'//nl//'  RIGId'//nl//nl// &
             'REGIon,1'//nl//'BLOCk'//nl//'  CARTesian,2,2,0,0,1'//nl//'    1,0,0'//nl//'    2,1,0'//nl// &
             '    3,1,1'//nl//'    4,0,1'//nl//nl// &
             'REGIon,2'//nl//'BLOCk'//nl//'  CARTesian,2,2,0,0,1'//nl//'    1,1.4,0'//nl//'    2,2.4,0'//nl// &
             '    3,2.4,1'//nl//'    4,1.4,1'//nl//nl// &
             'REGIon,3'//nl//'BLOCk'//nl//'  CARTesian,8,1,0,0,2'//nl//'    1,-1,-0.2'//nl//'    2,7,-0.2'//nl// &
             '    3,7,0'//nl//'    4,-1,0'//nl//nl// &
             'INITial,VELOcity'//nl//'  REGIon,1,3,0'//nl//nl//'GRAVity,0,-10'//nl//nl// &
             contact//nl//'END'//nl//'BATCh'//nl//'  DT,CFL,0.9'//nl//'  TPLOt,,1'//nl
      if (present(extra)) deck = deck//extra
      deck = deck//'  LOOP,,100000'//nl//'    TIME,,0.4'//nl//'    FORM,EXPLicit'//nl//'  NEXT'//nl//'END'//nl// &
             '  disp,1,1'//nl//'  disp,1,2'//nl//'  velo,5,1'//nl//'  disp,10,1'//nl//'  velo,14,1'//nl// &
             '  disp,14,2'//nl//nl//'STOP'
   end function sliding_blocks_deck


   !> The CONTact block of the sliding blocks with AUTOmatic, or with the six NTOS PAIRs of
   !> the ordered pairs of regions in AUTOmatic's order (slave 1, 2, 3, each against the others).
   function blocks_contact(automatic) result(text)
      logical, intent(in) :: automatic
      character(len=:), allocatable :: text
      character(len=*), parameter :: law = '    PENAlty,1e5'//nl//'    FRICtion,COULomb,0.3'//nl
      integer :: i, j, p
      if (automatic) then
         text = 'CONTact'//nl//'  AUTOmatic'//nl//law//'END CONTact'//nl
         return
      end if
      text = 'CONTact'//nl
      do i = 1, 3
         text = text//'  SURFace,'//itoa(i)//nl//'    REGIon,'//itoa(i)//nl
      end do
      p = 0
      do i = 1, 3
         do j = 1, 3
            if (i == j) cycle
            p = p + 1
            text = text//'  PAIR,'//itoa(p)//',NTOS,'//itoa(i)//','//itoa(j)//nl//law
         end do
      end do
      text = text//'END CONTact'//nl
   end function blocks_contact

end module scene_decks
