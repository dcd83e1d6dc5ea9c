!> The exic test driver: runs the suites the command line selects and prints
!> 'N passed, M failed' last (test_support/src/testing.f90).
!>
!>     fpm test                      every suite
!>     fpm test -- contact legacy    the suites whose name contains 'contact' or 'legacy'
!>     fpm test -- --list            the suite names
program exic_tests
   use testing, only: runner_t
   use test_linalg, only: run_linalg_tests
   use test_corrector, only: run_corrector_tests
   use test_contact_geom, only: run_contact_geom_tests
   use test_contact_concave, only: run_contact_concave_tests
   use test_nearest_face, only: run_nearest_face_tests
   use test_element, only: run_element_tests
   use test_hourglass, only: run_hourglass_tests
   use test_fields, only: run_fields_tests
   use test_fields_nodes, only: run_fields_nodes_tests
   use test_xdmf, only: run_xdmf_tests
   use test_viewers, only: run_viewers_tests
   use test_physics, only: run_physics_tests
   use test_contact, only: run_contact_tests
   use test_contact_auto, only: run_contact_auto_tests
   use test_run_output, only: run_run_output_tests
   use test_console, only: run_console_tests
   use test_parallel, only: run_parallel_tests
   use test_mpi, only: run_mpi_tests
   use test_deck, only: run_deck_tests
   use test_inputs, only: run_inputs_tests
   use test_legacy, only: run_legacy_tests
   use test_layers, only: run_layers_tests
   use test_gmsh, only: run_gmsh_tests
   use test_loads, only: run_loads_tests
   use test_punch, only: run_punch_tests
   use test_rigid, only: run_rigid_tests
   use test_plasticity, only: run_plasticity_tests
   use test_axisymmetric, only: run_axisymmetric_tests
   use test_hypoelastic, only: run_hypoelastic_tests
   use test_plastic_decks, only: run_plastic_decks_tests
   use test_plastic_step, only: run_plastic_step_tests
   use test_hostile, only: run_hostile_tests
   use test_math, only: run_math_tests
   use test_threads, only: run_threads_tests
   use test_friction, only: run_friction_tests
   use test_dissipation, only: run_dissipation_tests
   use test_restart, only: run_restart_tests
   use test_inside, only: run_inside_tests
   use test_stress_decks, only: run_stress_decks_tests
   use test_erosion, only: run_erosion_tests
   implicit none
   type(runner_t) :: r

   call r%init()
   ! each suite adds one line here
   call r%run('layers', run_layers_tests)
   call r%run('linalg', run_linalg_tests)
   call r%run('math', run_math_tests)
   call r%run('corrector', run_corrector_tests)
   call r%run('contact_geom', run_contact_geom_tests)
   call r%run('contact_concave', run_contact_concave_tests)
   call r%run('nearest_face', run_nearest_face_tests)
   call r%run('inside', run_inside_tests)
   call r%run('element', run_element_tests)
   call r%run('hourglass', run_hourglass_tests)
   call r%run('plasticity', run_plasticity_tests)
   call r%run('axisymmetric', run_axisymmetric_tests)
   call r%run('hypoelastic', run_hypoelastic_tests)
   call r%run('plastic_decks', run_plastic_decks_tests)
   call r%run('plastic_step', run_plastic_step_tests)
   call r%run('fields', run_fields_tests)
   call r%run('fields_nodes', run_fields_nodes_tests)
   call r%run('xdmf', run_xdmf_tests)
   call r%run('viewers', run_viewers_tests)
   call r%run('physics', run_physics_tests)
   call r%run('threads', run_threads_tests)
   call r%run('contact', run_contact_tests)
   call r%run('contact_auto', run_contact_auto_tests)
   call r%run('run_output', run_run_output_tests)
   call r%run('restart', run_restart_tests)
   call r%run('console', run_console_tests)
   call r%run('deck', run_deck_tests)
   call r%run('inputs', run_inputs_tests)
   call r%run('gmsh', run_gmsh_tests)
   call r%run('erosion', run_erosion_tests)
   call r%run('loads', run_loads_tests)
   call r%run('punch', run_punch_tests)
   call r%run('rigid', run_rigid_tests)
   call r%run('friction', run_friction_tests)
   call r%run('dissipation', run_dissipation_tests)
   call r%run('hostile', run_hostile_tests)
   call r%run('stress_decks', run_stress_decks_tests)
   call r%run('legacy', run_legacy_tests)
   call r%run('parallel', run_parallel_tests)
   call r%run('mpi', run_mpi_tests)
   call r%finish()
end program exic_tests
