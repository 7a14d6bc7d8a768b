# Write faults by LD_PRELOAD (tests/fault/fault_shim.c: fsync or rename failing with EIO) for
# every writer of the CLI: exit 1, the output and the cause named, the previous file intact, no
# temporary left. Medium: the Release CLI only (an ASan binary must load its runtime first).
if(ICS_HAVE_RENDER AND ICS_HAVE_OPENEXR)
  add_library(fault_shim MODULE ${CMAKE_CURRENT_SOURCE_DIR}/fault/fault_shim.c)
  target_link_libraries(fault_shim PRIVATE ${CMAKE_DL_LIBS})
  add_test(NAME cli_write_faults COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/write_faults.sh
    $<TARGET_FILE:icshadow_cli> $<TARGET_FILE:fault_shim>)
  set_tests_properties(cli_write_faults PROPERTIES LABELS medium)
  if(ICS_HAVE_ASSIMP) # the mesh reader's child dies with its parent (a hang made by the shim)
    add_test(NAME cli_mesh_reader_orphan COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/cli/mesh_reader_orphan.sh
      $<TARGET_FILE:icshadow_cli> $<TARGET_FILE:fault_shim>)
    set_tests_properties(cli_mesh_reader_orphan PROPERTIES LABELS medium)
  endif()
else()
  add_test(NAME cli_write_faults COMMAND ${CMAKE_COMMAND} -E echo
    "SKIPPED: cli_write_faults needs the renderer and OpenEXR (run scripts/deps.sh)")
  set_tests_properties(cli_write_faults PROPERTIES LABELS medium SKIP_REGULAR_EXPRESSION "SKIPPED:")
endif()
