!> The exic test driver: runs every test module and prints 'N passed, M failed' last.
program exic_tests
   use testing, only: suite_t
   use test_linalg, only: run_linalg_tests
   use test_contact_geom, only: run_contact_geom_tests
   use test_element, only: run_element_tests
   use test_fields, only: run_fields_tests
   use test_physics, only: run_physics_tests
   use test_contact, only: run_contact_tests
   use test_run_output, only: run_run_output_tests
   use test_deck, only: run_deck_tests
   use test_inputs, only: run_inputs_tests
   use test_legacy, only: run_legacy_tests
   use test_gmsh, only: run_gmsh_tests
   implicit none
   type(suite_t) :: s

   ! each area adds one call here
   call run_linalg_tests(s)
   call run_contact_geom_tests(s)
   call run_element_tests(s)
   call run_fields_tests(s)
   call run_physics_tests(s)
   call run_contact_tests(s)
   call run_run_output_tests(s)
   call run_deck_tests(s)
   call run_inputs_tests(s)
   call run_gmsh_tests(s)
   call run_legacy_tests(s)
   print '(i0,a,i0,a)', s%passed, ' passed, ', s%failed, ' failed'
   if (s%failed > 0) error stop 1
end program exic_tests
