# The outside check: the Monte-Carlo reference against Mitsuba 3 (analysis/mitsuba_check.py;
# label medium, about 10 s). Mitsuba lives in a virtual environment under the build tree, made by
# `make mitsuba` (which `make test` runs); ICS_MITSUBA_PYTHON names another interpreter. Without
# Mitsuba the test is still listed and skipped with the reason (ICS_ENFORCE_MITSUBA: an error).
set(ICS_MITSUBA_PYTHON "${CMAKE_BINARY_DIR}/mitsuba-venv/bin/python" CACHE FILEPATH
  "A Python with mitsuba (3.x, scalar_rgb), numpy and matplotlib for the outside check")
set(ics_mitsuba_why "")
if(NOT ICS_HAVE_RENDER OR NOT ICS_HAVE_OPENEXR)
  set(ics_mitsuba_why "the renderer and OpenEXR are needed")
elseif(ICS_MITSUBA_PYTHON STREQUAL "")
  set(ics_mitsuba_why "turned off (make test MITSUBA=0, or ICS_MITSUBA_PYTHON empty)")
elseif(NOT EXISTS "${ICS_MITSUBA_PYTHON}")
  set(ics_mitsuba_why "no ${ICS_MITSUBA_PYTHON} (run `make mitsuba`, then cmake again)")
else()
  execute_process(COMMAND "${ICS_MITSUBA_PYTHON}" -c
    "import mitsuba, numpy; mitsuba.set_variant('scalar_rgb')"
    RESULT_VARIABLE ics_mi_rc OUTPUT_QUIET ERROR_QUIET)
  if(NOT ics_mi_rc EQUAL 0)
    set(ics_mitsuba_why "${ICS_MITSUBA_PYTHON} cannot import mitsuba with scalar_rgb (run `make mitsuba`, then cmake again)")
  endif()
endif()
if(ics_mitsuba_why STREQUAL "")
  set(ics_mi_dir ${CMAKE_CURRENT_BINARY_DIR}/mitsuba_check)
  # enforced: a Mitsuba that stops importing is a failure, not a skip
  if(ICS_ENFORCE_MITSUBA)
    set(ics_mi_skip "")
  else()
    set(ics_mi_skip --skip-code)
  endif()
  add_test(NAME mitsuba_outside_check COMMAND ${CMAKE_COMMAND} -E env
    MPLCONFIGDIR=${ics_mi_dir}/mpl
    "${ICS_MITSUBA_PYTHON}" ${CMAKE_SOURCE_DIR}/analysis/mitsuba_check.py
      --icshadow $<TARGET_FILE:icshadow_cli> --workdir ${ics_mi_dir}
      --json ${ics_mi_dir}/summary.json ${ics_mi_skip})
  set_tests_properties(mitsuba_outside_check PROPERTIES LABELS medium SKIP_RETURN_CODE 77 TIMEOUT 600)
elseif(ICS_ENFORCE_MITSUBA)
  message(FATAL_ERROR "Mitsuba requested (ICS_ENFORCE_MITSUBA) but unusable: ${ics_mitsuba_why}")
else()
  add_test(NAME mitsuba_outside_check COMMAND ${CMAKE_COMMAND} -E echo
    "mitsuba_outside_check skipped: ${ics_mitsuba_why}")
  set_tests_properties(mitsuba_outside_check PROPERTIES LABELS medium SKIP_REGULAR_EXPRESSION "skipped")
endif()
if(ics_mitsuba_why STREQUAL "")
  message(STATUS "icshadow: Mitsuba outside check: ${ICS_MITSUBA_PYTHON}")
else()
  # turned off on purpose: a status line; missing: a warning
  if(ICS_MITSUBA_PYTHON STREQUAL "")
    set(ics_mi_level STATUS)
  else()
    set(ics_mi_level WARNING)
  endif()
  message(${ics_mi_level} "icshadow: the Mitsuba outside check (mitsuba_outside_check) will be "
    "skipped: ${ics_mitsuba_why}; `ctest -V -R mitsuba` shows the reason")
endif()
