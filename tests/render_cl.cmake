# The cl backend (gpu/backends/cl, OpenCL on PoCL here) against the cpu backend: the default scene, the
# scene files and variants reaching every kernel path; its refusals. Medium: PoCL builds the
# program on first use (about a second, then cached in the build tree's PoCL cache, which
# tests/CMakeLists.txt gives every test).
file(GLOB ics_scene_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.json)
ics_add_test(NAME test_render_cl SOURCES test_render_device.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER OPENCL ARGS cl ${ics_scene_files})
if(TARGET test_render_cl)
  target_include_directories(test_render_cl PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()

# on the command line: the default scene through --backend cl, its device in the summary; a
# device that does not exist refused before anything is written; bench slab side by side
if(ICS_HAVE_RENDER AND ICS_HAVE_OPENCL)
  set(rdc ${CMAKE_CURRENT_BINARY_DIR}/tmp/cli_render_cl)
  file(MAKE_DIRECTORY ${rdc})
  ics_cli_test(NAME cli_render_cl RC 0 LABELS medium
    ARGS "render|--backend|cl|--resolution|64x48|-o|${rdc}/default.exr"
    OUT "\"backend\": \"cl\", \"device\": \"OpenCL, [^\"]+\".*\"model\": \"patel\", \"model_auto\": true.*\"ns_per_px_slab\": [0-9.e+-]+")
  # a model with solid objects is the cpu backend's so far: refused on cl, before any output
  ics_cli_test(NAME cli_render_cl_model RC 2 LABELS medium
    ARGS "render|--backend|cl|--model|surface|--resolution|32x24|-o|${rdc}/model.exr"
    ERR "backend cl renders render.model patel only, not surface" NOFILE ${rdc}/model.exr)
  ics_cli_test(NAME cli_render_cl_no_device RC 2 LABELS medium
    ARGS "render|--backend|cl|-o|${rdc}/none.exr"
    ERR "icshadow render: --backend: ICS_CL_DEVICE=no-such-device matches no device \\(0: " NOFILE ${rdc}/none.exr)
  ics_cli_test(NAME cli_bench_slab_cl RC 0 LABELS medium
    ARGS "bench|slab|--sizes|64|--slabs|4|--threads|1|--reps|1|--kernels|ellipse2,gauss19|--backend|cpu,cl"
    OUT "cpu,ellipse2,.*\ncl,ellipse2,2,table,64,64,4,0,.*\ncpu,gauss19,.*\ncl,gauss19,19,taps,64,64,4,0,")
  ics_cli_test(NAME cli_render_cl_device_flag RC 2 LABELS medium
    ARGS "render|--backend|cl|--cl-device|no-such-device|-o|${rdc}/flag.exr"
    ERR "--backend: cl.device=no-such-device matches no device" NOFILE ${rdc}/flag.exr)
  # the option wins over its environment variable, the availability check included
  ics_cli_test(NAME cli_render_cl_device_over_env RC 0 LABELS medium
    ARGS "render|--backend|cl|--cl-device|0|--resolution|16x12|-o|${rdc}/over_env.exr"
    OUT "\"backend\": \"cl\"")
  set_tests_properties(cli_render_cl_device_over_env PROPERTIES ENVIRONMENT ICS_CL_DEVICE=no-such-device)
  ics_cli_test(NAME cli_render_cl_device_other_backend RC 0 LABELS medium
    ARGS "render|--cl-device|0|--resolution|16x12|-o|${rdc}/other.exr"
    ERR "warning: --cl-device only applies to --backend cl \\(the backend is cpu\\)")
  set_tests_properties(cli_render_cl_no_device PROPERTIES ENVIRONMENT ICS_CL_DEVICE=no-such-device)
endif()
