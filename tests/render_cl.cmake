# The cl backend (gpu/cl, OpenCL on PoCL here) against the cpu backend: the default scene, the
# scene files and variants reaching every kernel path; its refusals. Medium: PoCL builds the
# program on first use (about a second, then cached in the build tree's PoCL cache).
file(GLOB ics_scene_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.json)
ics_add_test(NAME test_render_cl SOURCES test_render_cl.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER OPENCL ARGS ${ics_scene_files})
if(TARGET test_render_cl)
  target_include_directories(test_render_cl PRIVATE ${CMAKE_SOURCE_DIR}/gpu/src)
endif()
set_tests_properties(test_render_cl PROPERTIES ENVIRONMENT POCL_CACHE_DIR=${ics_pocl_cache})
