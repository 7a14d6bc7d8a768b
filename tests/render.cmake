# The slab renderer (libicshadow_render, gpu/): scene files, plans, the CPU backend against
# Eq. 4 and Beer-Lambert, reproducibility, memory. Built when the renderer is (needs jansson).
set(ICS_RENDER_TEST_LIBS icshadow_render_static)
function(ics_add_render_test name label)
  ics_add_test(NAME ${name} SOURCES ${name}.c LABELS ${label} render
    LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ${ARGN})
  if(TARGET ${name})
    target_include_directories(${name} PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
  endif()
endfunction()
ics_add_render_test(test_render_scene fast)
ics_add_test(NAME test_render_disk SOURCES test_render_disk.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/scenes/disk.json)
ics_add_render_test(test_render_volume fast)
# medium by cost (docs/testing.md): 15 s under ASan on the scalar path, 1.6 s Release
ics_add_test(NAME test_render_repro SOURCES test_render_repro.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/scenes/disk.json)
if(TARGET test_render_repro)
  target_include_directories(test_render_repro PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()
# its frames on one renderer alone, fast: the ASan run checks the kept memory's guards
if(TARGET test_render_repro)
  add_test(NAME test_render_frames COMMAND test_render_repro ${CMAKE_SOURCE_DIR}/scenes/disk.json --frames)
  set_tests_properties(test_render_frames PROPERTIES LABELS "fast;render" SKIP_RETURN_CODE 77)
endif()
ics_add_render_test(test_render_plan medium)
ics_add_render_test(test_render_propagate fast)
ics_add_render_test(test_render_simd medium) # 42 renders: 5 s Release
ics_add_render_test(test_render_vec_math fast)
ics_add_render_test(test_render_piece_batch medium)
if(TARGET test_render_piece_batch)
  set_tests_properties(test_render_piece_batch PROPERTIES SKIP_RETURN_CODE 77)
endif()
ics_add_test(NAME test_render_model SOURCES test_render_model.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/scenes/disk.json)
if(TARGET test_render_model)
  target_include_directories(test_render_model PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()
ics_add_test(NAME test_render_skip SOURCES test_render_skip.c LABELS medium render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/scenes/disk.json)
if(TARGET test_render_skip)
  target_include_directories(test_render_skip PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()
ics_add_render_test(test_render_slab_kernel fast)
# the NEON loops: test_render_propagate built by Debian's AArch64 cross compiler and run under
# qemu-user (scripts/deps.sh installs both); skipped with the reason where either is missing
find_program(ICS_AARCH64_CC aarch64-linux-gnu-gcc)
find_program(ICS_QEMU_AARCH64 qemu-aarch64)
if(ICS_AARCH64_CC AND ICS_QEMU_AARCH64)
  add_test(NAME test_render_propagate_neon COMMAND ${CMAKE_SOURCE_DIR}/tests/cross/neon.sh
    ${CMAKE_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/cross_neon ${ICS_AARCH64_CC} ${ICS_QEMU_AARCH64})
else()
  add_test(NAME test_render_propagate_neon COMMAND ${CMAKE_COMMAND} -E echo
    "SKIPPED: test_render_propagate_neon needs aarch64-linux-gnu-gcc and qemu-aarch64 (scripts/deps.sh: gcc-aarch64-linux-gnu qemu-user)")
  set_tests_properties(test_render_propagate_neon PROPERTIES SKIP_REGULAR_EXPRESSION "SKIPPED:")
endif()
set_tests_properties(test_render_propagate_neon PROPERTIES LABELS "medium;render")
ics_add_test(NAME test_render_geometry SOURCES test_render_geometry.c LABELS fast render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/tests/data)
if(TARGET test_render_geometry)
  target_include_directories(test_render_geometry PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()
ics_add_render_test(test_render_perspective medium)
ics_add_render_test(test_render_detail fast)
ics_add_render_test(test_render_aov fast)
ics_add_render_test(test_render_bias medium) # 8.4 s under ASan (scalar path), 1 s Release
ics_add_render_test(test_render_mc medium)
ics_add_render_test(test_render_mc_embree fast ASSIMP EMBREE)
# Under the sanitizers, LeakSanitizer's exit-time tracer crashes (SIGSEGV, "LeakSanitizer has
# encountered a fatal error") in about half the runs of this test on a loaded machine, before
# and after any change of ours: a known fault of the sanitizer runtime when it suspends many
# threads (Embree's TBB workers; google/sanitizers#1353). Leak checking is off for this test
# alone; AddressSanitizer still checks every access.
if(TEST test_render_mc_embree)
  set_tests_properties(test_render_mc_embree PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
endif()
# the shared kernel source (gpu/kernel) compiled as C against the host's detail, transfer and rays
ics_add_test(NAME test_kernel_c SOURCES test_kernel_c.c LABELS fast render
  LIBS ${ICS_RENDER_TEST_LIBS} NEEDS RENDER ARGS ${CMAKE_SOURCE_DIR}/scenes/volumes.json)
if(TARGET test_kernel_c)
  target_include_directories(test_kernel_c PRIVATE ${ICS_RENDER_PRIVATE_INCLUDES})
endif()
# the kernel source is written once (gpu/kernel): no device function defined in two kernel files,
# no record offset or stride defined outside gpu/kernel/device_layout.h
file(GLOB ics_kernel_shared ${CMAKE_SOURCE_DIR}/gpu/kernel/*.h)
add_test(NAME kernel_source_once COMMAND ${CMAKE_SOURCE_DIR}/tests/source/kernel_once.sh
  ${CMAKE_SOURCE_DIR}/gpu/backends/cl/slab.cl ${CMAKE_SOURCE_DIR}/gpu/backends/gl/slab.comp
  ${CMAKE_SOURCE_DIR}/gpu/backends/gl/ldi.comp ${ics_kernel_shared})
set_tests_properties(kernel_source_once PROPERTIES LABELS fast)
