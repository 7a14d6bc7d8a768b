# Complete elliptic integrals K, E (libicshadow/src/ellint.c) against the MPFR AGM reference.
ics_add_test(NAME test_ellint
  SOURCES ${CMAKE_SOURCE_DIR}/tests/test_ellint.c ${CMAKE_SOURCE_DIR}/tests/ref_mpfr.c
  LABELS fast LIBS ${ICS_MPFR_LIBS} NEEDS MPFR)
ics_add_test(NAME test_ellint_exhaustive
  SOURCES ${CMAKE_SOURCE_DIR}/tests/test_ellint.c ${CMAKE_SOURCE_DIR}/tests/ref_mpfr.c
  LABELS exhaustive LIBS ${ICS_MPFR_LIBS} ARGS --exhaustive NEEDS MPFR)

# The checked-in tables must be exactly what the generator makes (needs python3 + mpmath).
find_program(ICS_PYTHON3_MPMATH NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(ICS_PYTHON3_MPMATH)
  execute_process(COMMAND ${ICS_PYTHON3_MPMATH} -c "import mpmath"
    RESULT_VARIABLE ics_mpmath_rc OUTPUT_QUIET ERROR_QUIET)
endif()
if(ICS_PYTHON3_MPMATH AND ics_mpmath_rc EQUAL 0)
  set(ics_regen ${CMAKE_CURRENT_BINARY_DIR}/ellint_regen)
  # paths go in as arguments, never into the script text (a checkout path with blanks)
  add_test(NAME test_ellint_data_regen COMMAND sh -c
    "mkdir -p \"$1\" && \"$2\" \"$3/scripts/gen_ellint_coeffs.py\" \"$1\" && cmp \"$1/ellint_data.c\" \"$3/libicshadow/src/ellint_data.c\" && cmp \"$1/ellint_data.h\" \"$3/libicshadow/src/ellint_data.h\""
    test_ellint_data_regen ${ics_regen} ${ICS_PYTHON3_MPMATH} ${CMAKE_SOURCE_DIR})
  set_tests_properties(test_ellint_data_regen PROPERTIES LABELS fast)
else()
  add_test(NAME test_ellint_data_regen COMMAND ${CMAKE_COMMAND} -E echo
    "SKIPPED: test_ellint_data_regen needs python3 with mpmath (apt-get install python3-mpmath)")
  set_tests_properties(test_ellint_data_regen PROPERTIES LABELS fast SKIP_REGULAR_EXPRESSION "SKIPPED:")
endif()

# Long runs restricted to the log-series region (m1 < X0) and to m < 0 (label exhaustive):
# 10^6 random inputs each, every one checked for K and E against MPFR.
ics_add_test(NAME test_ellint_focus_log
  SOURCES ${CMAKE_SOURCE_DIR}/tests/test_ellint.c ${CMAKE_SOURCE_DIR}/tests/ref_mpfr.c
  LABELS exhaustive LIBS ${ICS_MPFR_LIBS} ARGS --focus log --n 1000000 NEEDS MPFR)
ics_add_test(NAME test_ellint_focus_neg
  SOURCES ${CMAKE_SOURCE_DIR}/tests/test_ellint.c ${CMAKE_SOURCE_DIR}/tests/ref_mpfr.c
  LABELS exhaustive LIBS ${ICS_MPFR_LIBS} ARGS --focus neg --n 1000000 NEEDS MPFR)
