# The gl backend (gpu/backends/gl: OpenGL 4.5 compute shaders; llvmpipe here) against the cpu backend:
# the default scene, the scene files and the variants of test_render_device.c, once per context
# kind (EGL, OSMesa); its refusals; slab.comp's programs through glslangValidator; the command
# line (--backend gl, --gl-context, the auto notice, bench slab side by side). Medium: llvmpipe
# compiles the shading program on first use (seconds; Mesa's shader cache in the build tree,
# tests/CMakeLists.txt, keeps it for later runs).
file(GLOB ics_scene_files CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.json)
ics_add_test(NAME test_render_gl SOURCES test_render_device.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER GL ARGS gl ${ics_scene_files})
if(TARGET test_render_gl)
  set_tests_properties(test_render_gl PROPERTIES ENVIRONMENT ICS_GL_CONTEXT=egl)
  add_test(NAME test_render_gl_osmesa COMMAND test_render_gl gl ${ics_scene_files})
  set_tests_properties(test_render_gl_osmesa PROPERTIES LABELS "medium;render"
    ENVIRONMENT ICS_GL_CONTEXT=osmesa SKIP_RETURN_CODE 77)
endif()

# every program of slab.comp (each entry point and variant, as backend_gl.c compiles them)
# through the reference compiler
if(ICS_HAVE_GL AND ICS_HAVE_GLSLANG)
  set(ics_glsl_variants "PROP_STENCIL" "PROP_STENCIL,ICS_CLAMPED" "PROP_TABLE"
    "PROP_TABLE,ICS_CLAMPED" "PROP_CLASSES" "PROP_STENCIL,ICS_TAPS_STORAGE"
    "PROP_STENCIL,ICS_CLAMPED,ICS_TAPS_STORAGE" "PROP_TABLE,ICS_TAPS_STORAGE"
    "PROP_TABLE,ICS_CLAMPED,ICS_TAPS_STORAGE" "PROP_CLASSES,ICS_TAPS_STORAGE" "ENTRIES_PIXEL" "ENTRIES_RUN" "SHADE_SELECT"
    "SHADE_COUNT" "SHADE" "SHADE,ICS_SURFACES_ONLY" "APRON_SIDES" "APRON_ENDS")
  foreach(v ${ics_glsl_variants})
    string(REPLACE "," ";" parts ${v})
    list(GET parts 0 k)
    set(defs -DICS_K_${k})
    list(REMOVE_AT parts 0) # what remains: the variant's further defines
    foreach(extra ${parts})
      list(APPEND defs -D${extra})
    endforeach()
    string(REPLACE "," "_" tname ${v})
    add_test(NAME glsl_slab_${tname} COMMAND ${GLSLANG_VALIDATOR} -l -S comp ${defs}
      ${CMAKE_BINARY_DIR}/gpu/generated/slab.comp) # as compiled: the includes expanded
    set_tests_properties(glsl_slab_${tname} PROPERTIES LABELS "fast;render")
  endforeach()
endif()

if(ICS_HAVE_RENDER AND ICS_HAVE_GL)
  set(rdg ${CMAKE_CURRENT_BINARY_DIR}/tmp/cli_render_gl)
  file(MAKE_DIRECTORY ${rdg})
  # the context in the summary, for each kind; the default scene's render.model auto as patel
  ics_cli_test(NAME cli_render_gl_egl RC 0 LABELS medium
    ARGS "render|--backend|gl|--gl-context|egl|--resolution|64x48|-o|${rdg}/egl.exr"
    OUT "\"backend\": \"gl\", \"device\": \"OpenGL egl-[a-z]+[^\"]*: [^\"]+\".*\"model\": \"patel\", \"model_auto\": true.*\"ns_per_px_slab\": [0-9.e+-]+")
  ics_cli_test(NAME cli_render_gl_osmesa RC 0 LABELS medium
    ARGS "render|--backend|gl|--gl-context|osmesa|--resolution|64x48|-o|${rdg}/osmesa.exr"
    OUT "\"backend\": \"gl\", \"device\": \"OpenGL osmesa: [^\"]+\"")
  # the option wins over its environment variable, the availability check included
  ics_cli_test(NAME cli_render_gl_context_over_env RC 0 LABELS medium
    ARGS "render|--backend|gl|--gl-context|osmesa|--resolution|16x12|-o|${rdg}/over_env.exr"
    OUT "\"backend\": \"gl\", \"device\": \"OpenGL osmesa: ")
  set_tests_properties(cli_render_gl_context_over_env PROPERTIES ENVIRONMENT ICS_GL_CONTEXT=bogus)
  # a context kind that does not exist: refused before anything is written
  ics_cli_test(NAME cli_render_gl_bad_context RC 2 LABELS fast
    ARGS "render|--backend|gl|--gl-context|vulkan|-o|${rdg}/none.exr"
    ERR "--gl-context: expected auto, egl or osmesa, got 'vulkan'" NOFILE ${rdg}/none.exr)
  ics_cli_test(NAME cli_render_gl_context_other_backend RC 0 LABELS fast
    ARGS "render|--gl-context|egl|--backend|cpu|--resolution|16x12|-o|${rdg}/other.exr"
    ERR "warning: --gl-context only applies to --backend gl \\(the backend is cpu\\)")
  # auto on a machine without a GPU: cpu, with the one-line notice when asked (--verbose, a
  # --gl-* option); quiet otherwise (stderr is not a terminal here)
  ics_cli_test(NAME cli_render_gl_auto_notice RC 0 LABELS fast
    ARGS "render|--verbose|--resolution|16x12|-o|${rdg}/auto.exr"
    OUT "\"backend\": \"cpu\"" ERR "note: auto passed over gl: ")
  ics_cli_test(NAME cli_render_gl_auto_notice_gl_option RC 0 LABELS fast
    ARGS "render|--gl-ldi|device|--resolution|16x12|-o|${rdg}/auto2.exr"
    OUT "\"backend\": \"cpu\"" ERR "note: auto passed over gl: ")
  ics_cli_test(NAME cli_render_gl_auto_quiet RC 0 LABELS fast
    ARGS "render|--resolution|16x12|-o|${rdg}/auto3.exr" OUT "\"backend\": \"cpu\"" ERR "^$")
  # the layered depth image built on the device: its time in the summary; a bad value refused
  ics_cli_test(NAME cli_render_gl_ldi_device RC 0 LABELS medium
    ARGS "render|--backend|gl|--gl-ldi|device|--resolution|64x48|-o|${rdg}/ldi.exr"
    OUT "\"backend\": \"gl\".*\"ms_geometry_device\": [0-9.e+-]+")
  ics_cli_test(NAME cli_render_gl_ldi_bad RC 2 LABELS fast
    ARGS "render|--backend|gl|--gl-ldi|gpu|-o|${rdg}/ldi_bad.exr"
    ERR "--gl-ldi: expected plan or device, got 'gpu'" NOFILE ${rdg}/ldi_bad.exr)
  ics_cli_test(NAME cli_render_gl_ldi_other_backend RC 0 LABELS fast
    ARGS "render|--gl-ldi|device|--backend|cpu|--resolution|16x12|-o|${rdg}/ldi_cpu.exr"
    ERR "warning: --gl-ldi only applies to --backend gl \\(the backend is cpu\\)")
  # a lost context (glGetGraphicsResetStatus reporting a reset, through tests/fault/fault_shim.c):
  # named, exit 2, no image; with the plan's LDI (found after the slabs) and the device's (found
  # after the cast), on each context kind
  if(TARGET fault_shim)
    foreach(ctx egl osmesa)
      foreach(ldi plan device)
        set(when "the context was lost \\(GL_GUILTY_CONTEXT_RESET\\)")
        if(ldi STREQUAL "device")
          set(when "the context was lost \\(GL_GUILTY_CONTEXT_RESET\\) casting the rays \\(the layered depth image\\)")
        endif()
        ics_cli_test(NAME cli_render_gl_lost_${ctx}_${ldi} RC 2 LABELS medium
          ARGS "render|--backend|gl|--gl-context|${ctx}|--gl-ldi|${ldi}|--resolution|32x24|-o|${rdg}/lost_${ctx}_${ldi}.exr"
          ERR "backend gl: ${when}" NOFILE ${rdg}/lost_${ctx}_${ldi}.exr)
        set_tests_properties(cli_render_gl_lost_${ctx}_${ldi} PROPERTIES
          ENVIRONMENT "LD_PRELOAD=$<TARGET_FILE:fault_shim>;ICS_FAULT=gl-reset")
      endforeach()
    endforeach()
    # the device's LDI: the reset found after the sort (the check after the cast passes)
    ics_cli_test(NAME cli_render_gl_lost_egl_device_sort RC 2 LABELS medium
      ARGS "render|--backend|gl|--gl-context|egl|--gl-ldi|device|--resolution|32x24|-o|${rdg}/lost_sort.exr"
      ERR "backend gl: the context was lost \\(GL_GUILTY_CONTEXT_RESET\\) sorting the fragments"
      NOFILE ${rdg}/lost_sort.exr)
    set_tests_properties(cli_render_gl_lost_egl_device_sort PROPERTIES
      ENVIRONMENT "LD_PRELOAD=$<TARGET_FILE:fault_shim>;ICS_FAULT=gl-reset;ICS_FAULT_AFTER=1")
  endif()
  ics_cli_test(NAME cli_bench_slab_gl RC 0 LABELS medium
    ARGS "bench|slab|--sizes|64|--slabs|4|--threads|1|--reps|1|--kernels|ellipse2,gauss19|--backend|cpu,gl"
    OUT "cpu,ellipse2,.*\ngl,ellipse2,2,table,64,64,4,0,.*\ncpu,gauss19,.*\ngl,gauss19,19,taps,64,64,4,0,")
endif()

# the GLSL lookup-table header executed (not only compiled): ics_tab_ellipse_tap and
# ics_tab_ellipse_radii on the gl backend's context against the library (medium: Mesa's
# compiler leaks at exit, so it stays out of the ASan run)
ics_add_test(NAME test_lut_glsl SOURCES test_lut_glsl.c LABELS medium
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER GL
  ARGS ${CMAKE_SOURCE_DIR}/gpu/backends/gl/icshadow_lut.glsl ${CMAKE_CURRENT_BINARY_DIR}/lut_out/icshadow_lut_64.glsl)
if(TARGET test_lut_glsl) # the gl module's code itself (its contexts), not the module
  target_include_directories(test_lut_glsl PRIVATE ${CMAKE_SOURCE_DIR}/gpu/backends/gl)
  target_link_libraries(test_lut_glsl PRIVATE icshadow_gl_objects)
  set_tests_properties(test_lut_glsl PROPERTIES FIXTURES_REQUIRED lut_gen_glsl_64 SKIP_RETURN_CODE 77)
endif()

# the layered depth image built on the device (gpu/backends/gl/ldi.comp) against the plan's, fragment by
# fragment; and the renders of test_render_device.c with it (ICS_GL_LDI=device)
ics_add_test(NAME test_gl_ldi SOURCES test_gl_ldi.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER GL ARGS ${CMAKE_SOURCE_DIR}/tests/data ${ics_scene_files})
if(TARGET test_gl_ldi) # the gl module's code itself, not the module
  target_include_directories(test_gl_ldi PRIVATE ${CMAKE_SOURCE_DIR}/gpu/backends/gl ${ICS_RENDER_PRIVATE_INCLUDES})
  target_link_libraries(test_gl_ldi PRIVATE icshadow_gl_objects)
  set_tests_properties(test_gl_ldi PROPERTIES SKIP_RETURN_CODE 77)
endif()
if(TARGET test_render_gl)
  add_test(NAME test_render_gl_ldi_device COMMAND test_render_gl gl ${ics_scene_files})
  set_tests_properties(test_render_gl_ldi_device PROPERTIES LABELS "medium;render"
    ENVIRONMENT "ICS_GL_CONTEXT=egl;ICS_GL_LDI=device" SKIP_RETURN_CODE 77)
endif()
foreach(k LDI_CAST LDI_SCAN LDI_SORT)
  if(ICS_HAVE_GL AND ICS_HAVE_GLSLANG)
    add_test(NAME glsl_${k} COMMAND ${GLSLANG_VALIDATOR} -l -S comp -DICS_K_${k}
      ${CMAKE_BINARY_DIR}/gpu/generated/ldi.comp)
    set_tests_properties(glsl_${k} PROPERTIES LABELS "fast;render")
  endif()
endforeach()
