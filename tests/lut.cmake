# Lookup tables for ratioToab / abToVarx (libicshadow/src/lut.c, lut_data.c) and the headers
# generated from them (gpu/backends/gl/icshadow_lut.glsl, gpu/backends/cl/icshadow_lut.cl). See docs/lut.md.

# Error bounds, stamps, special values, 1/n^2 convergence (against ellipse.c).
ics_add_test(NAME test_lut SOURCES test_lut.c LABELS fast)

set(ics_lut_dir ${CMAKE_CURRENT_BINARY_DIR}/lut_out)
file(MAKE_DIRECTORY ${ics_lut_dir})

# The checked-in tables and headers are exactly what `icshadow lut` makes now.
add_test(NAME lut_regen
  COMMAND sh ${CMAKE_SOURCE_DIR}/scripts/gen_luts.sh --check $<TARGET_FILE:icshadow_cli>)
set_tests_properties(lut_regen PROPERTIES LABELS fast)

# Headers written by the CLI at another size (the Makefile's demo size, 64), for the compile tests.
foreach(lang glsl opencl)
  if(lang STREQUAL "glsl")
    set(ext glsl)
  else()
    set(ext cl)
  endif()
  add_test(NAME lut_gen_${lang}_64
    COMMAND $<TARGET_FILE:icshadow_cli> lut --size 64 --lang ${lang} -o ${ics_lut_dir}/icshadow_lut_64.${ext})
  set_tests_properties(lut_gen_${lang}_64 PROPERTIES LABELS fast FIXTURES_SETUP lut_gen_${lang}_64)
endforeach()

# The self-contained C header (--lang c): compiled into a test that compares it with the library.
add_custom_command(OUTPUT ${ics_lut_dir}/icshadow_lut_c64.h
  COMMAND icshadow_cli lut --size 64 --lang c -o ${ics_lut_dir}/icshadow_lut_c64.h
  DEPENDS icshadow_cli VERBATIM)
ics_add_test(NAME test_lut_cheader SOURCES test_lut_cheader.c ${ics_lut_dir}/icshadow_lut_c64.h
  LABELS fast)
if(TARGET test_lut_cheader)
  target_include_directories(test_lut_cheader PRIVATE ${ics_lut_dir})
endif()

# GLSL: the header concatenated into a #version 450 compute shader and a #version 330 fragment
# shader that call every function; glslangValidator must accept them.
file(WRITE ${ics_lut_dir}/prologue_450.glsl "#version 450\n")
file(WRITE ${ics_lut_dir}/prologue_330.glsl "#version 330\n")
file(WRITE ${ics_lut_dir}/epilogue.comp [=[
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { float v[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  vec2 ab = ics_tab_ratio_to_ab(v[i]);
  vec2 r = ics_tab_ellipse_radii(1.0, v[i]);
  vec2 tap = ics_tab_ellipse_tap(1.0, v[i], 30.0, 3, int(i % 3u), v[i] * 0.5);
  v[i] = ab.x + ab.y + ics_tab_ratio_to_t(v[i]) + ics_tab_vx(v[i]) + ics_tab_vx_ab(ab) + r.x + r.y
         + tap.x + tap.y;
}
]=])
file(WRITE ${ics_lut_dir}/epilogue.frag [=[
uniform float rat;
out vec4 color;
void main() {
  vec2 ab = ics_tab_ratio_to_ab(rat);
  color = vec4(ab, ics_tab_vx(ab.y) + ics_tab_ratio_to_t(rat) + ics_tab_vx_ab(ab),
               ics_tab_ellipse_radii(1.0, rat).x + ics_tab_ellipse_tap(1.0, rat, 30.0, 2, 1, 0.25).y);
}
]=])
file(WRITE ${ics_lut_dir}/glsl_check.sh [=[
# glsl_check.sh VALIDATOR PROLOGUE HEADER EPILOGUE OUT: concatenate and validate.
cat "$2" "$3" "$4" > "$5" || exit 1
"$1" "$5"
]=])
function(ics_lut_glsl_test name version header stage)
  if(ICS_HAVE_GLSLANG)
    add_test(NAME ${name} COMMAND sh ${ics_lut_dir}/glsl_check.sh ${GLSLANG_VALIDATOR}
      ${ics_lut_dir}/prologue_${version}.glsl ${header} ${ics_lut_dir}/epilogue.${stage}
      ${ics_lut_dir}/${name}.${stage})
  else()
    add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E echo
      "SKIPPED: ${name} needs GLSLANG (glslangValidator: run scripts/deps.sh)")
    set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "SKIPPED:")
  endif()
  set_tests_properties(${name} PROPERTIES LABELS fast)
endfunction()
ics_lut_glsl_test(lut_glsl_450 450 ${CMAKE_SOURCE_DIR}/gpu/backends/gl/icshadow_lut.glsl comp)
ics_lut_glsl_test(lut_glsl_330 330 ${CMAKE_SOURCE_DIR}/gpu/backends/gl/icshadow_lut.glsl frag)
ics_lut_glsl_test(lut_glsl_450_size64 450 ${ics_lut_dir}/icshadow_lut_64.glsl comp)
set_tests_properties(lut_glsl_450_size64 PROPERTIES FIXTURES_REQUIRED lut_gen_glsl_64)

# OpenCL: clBuildProgram on the device (PoCL), run a kernel, compare with the C float mirror
# (bit for bit with correctly rounded divide/sqrt) and with the exact functions.
ics_add_test(NAME test_lut_opencl SOURCES test_lut_opencl.c LABELS fast
  LIBS OpenCL::OpenCL m NEEDS OPENCL
  ARGS ${CMAKE_SOURCE_DIR}/gpu/backends/cl/icshadow_lut.cl ${ics_lut_dir}/icshadow_lut_64.cl)
# PoCL's kernel cache is in the build tree, not in ~/.cache/pocl (nothing written to HOME), and
# is filled first by the same program with LeakSanitizer off: a cold compile leaks inside PoCL /
# LLVM, so under ICS_SANITIZE the test passed only when an earlier run (make test's Release leg)
# had left the kernels in ~/.cache/pocl, and failed with a fresh or unwritable HOME. The test
# itself then runs with full leak detection (leaks of ours still fail it). PoCL finds no device
# when its cache directory's path passes about 900 bytes: under a longer build path the cache
# goes to /tmp/icshadow-pocl-<hash of the build directory>.
set(ics_pocl_cache ${ics_lut_dir}/pocl_cache)
string(LENGTH "${ics_pocl_cache}" ics_pocl_len)
if(ics_pocl_len GREATER 400)
  string(MD5 ics_pocl_hash "${CMAKE_BINARY_DIR}")
  string(SUBSTRING "${ics_pocl_hash}" 0 12 ics_pocl_hash)
  set(ics_pocl_cache /tmp/icshadow-pocl-${ics_pocl_hash})
endif()
set_tests_properties(test_lut_opencl PROPERTIES FIXTURES_REQUIRED "lut_gen_opencl_64;lut_opencl_cache"
  ENVIRONMENT POCL_CACHE_DIR=${ics_pocl_cache})
if(TARGET test_lut_opencl)
  add_test(NAME test_lut_opencl_compile COMMAND test_lut_opencl
    ${CMAKE_SOURCE_DIR}/gpu/backends/cl/icshadow_lut.cl ${ics_lut_dir}/icshadow_lut_64.cl)
  set_tests_properties(test_lut_opencl_compile PROPERTIES LABELS fast SKIP_RETURN_CODE 77
    FIXTURES_REQUIRED lut_gen_opencl_64 FIXTURES_SETUP lut_opencl_cache
    ENVIRONMENT "POCL_CACHE_DIR=${ics_pocl_cache};ASAN_OPTIONS=detect_leaks=0")
endif()
