# bench_ellint: K, E, K+E (libicshadow/src/ellint.c) against an AGM, Carlson's R_F/R_D and,
# when its headers are found, Boost.Math ellint_1/ellint_2 (C++ shim). Built by `benchmarks`.
# the repetition statistics are the CLI's (cli/bench_stats.c; cliutil.c and tempfiles.c for its
# warning)
add_executable(bench_ellint EXCLUDE_FROM_ALL ${CMAKE_SOURCE_DIR}/bench/bench_ellint.c
  ${CMAKE_SOURCE_DIR}/cli/bench_stats.c ${CMAKE_SOURCE_DIR}/cli/cliutil.c
  ${CMAKE_SOURCE_DIR}/cli/tempfiles.c)
target_include_directories(bench_ellint PRIVATE ${CMAKE_SOURCE_DIR}/cli)
target_link_libraries(bench_ellint PRIVATE icshadow_static m)
include(CheckIncludeFileCXX)
check_include_file_cxx(boost/math/special_functions/ellint_2.hpp ICS_HAVE_BOOST_ELLINT)
if(ICS_HAVE_BOOST_ELLINT)
  target_sources(bench_ellint PRIVATE ${CMAKE_SOURCE_DIR}/bench/bench_ellint_boost.cpp)
  target_compile_definitions(bench_ellint PRIVATE ICS_BENCH_BOOST=1)
  set_target_properties(bench_ellint PROPERTIES LINKER_LANGUAGE CXX)
endif()
add_dependencies(benchmarks bench_ellint)
