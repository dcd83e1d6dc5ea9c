program exic_main
   implicit none
   print '(a)', 'exic'
end program exic_main
