# The analysis drivers' own contracts (their results are in docs/results.md): the error-against-
# time sweep's shards merge into the whole run byte for byte, and bad shard specs and merges are
# refused (tests/cli/evt_shards.sh; Debian's python3 with numpy and the icshadow package, which
# tests/python.cmake installs);
# the same sweep as a real Slurm job array on a single-node cluster started on localhost
# (tests/cli/evt_slurm.sh, scripts/slurm_local.sh; root, slurm-wlm and munge).
find_program(ICS_PYTHON3_ANALYSIS NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
if(ICS_HAVE_RENDER AND ICS_HAVE_OPENEXR AND ICS_PYTHON3_ANALYSIS)
  add_test(NAME cli_error_vs_time_shards COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/evt_shards.sh
    ${ICS_PYTHON3_ANALYSIS} ${CMAKE_SOURCE_DIR}/analysis/error_vs_time.py)
  set_tests_properties(cli_error_vs_time_shards PROPERTIES LABELS medium SKIP_RETURN_CODE 77
    FIXTURES_REQUIRED icshadow_python ENVIRONMENT "${ICS_PYTHON_ENV}")
  add_test(NAME cli_error_vs_time_slurm COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/evt_slurm.sh
    ${ICS_PYTHON3_ANALYSIS} ${CMAKE_SOURCE_DIR}/analysis/error_vs_time.py
    ${CMAKE_SOURCE_DIR}/scripts/slurm_local.sh)
  # RUN_SERIAL: the private cluster takes fixed ports (16817+, the next free pair if busy)
  set_tests_properties(cli_error_vs_time_slurm PROPERTIES LABELS medium SKIP_RETURN_CODE 77
    RUN_SERIAL ON TIMEOUT 300 FIXTURES_REQUIRED icshadow_python ENVIRONMENT "${ICS_PYTHON_ENV}")
endif()
if(NOT ICS_PYTHON3_ANALYSIS)
  message(STATUS "icshadow: cli_error_vs_time_shards not added: no /usr/bin/python3")
endif()
