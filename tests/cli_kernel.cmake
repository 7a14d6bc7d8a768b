# CLI tests for `icshadow kernel`: --help, good output, and every kind of bad input.
#
# This file is also a CTest driver script: run with `cmake -P` (CMAKE_SCRIPT_MODE_FILE set) it
# executes the CLI once and checks the exit status (RC), a regular expression on stdout (OUT)
# and on stderr (ERR). Arguments are passed '|'-separated in ARGS (';' would be split by add_test).
if(CMAKE_SCRIPT_MODE_FILE)
  string(REPLACE "|" ";" args "${ARGS}")
  execute_process(COMMAND ${CLI} ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "icshadow ${args}\n  exit ${rc}\n  stdout: ${out}\n  stderr: ${err}")
  if(NOT "${rc}" STREQUAL "${RC}")
    message(FATAL_ERROR "exit status ${rc}, expected ${RC}")
  endif()
  if(DEFINED OUT AND NOT out MATCHES "${OUT}")
    message(FATAL_ERROR "stdout does not match '${OUT}'")
  endif()
  if(DEFINED ERR AND NOT err MATCHES "${ERR}")
    message(FATAL_ERROR "stderr does not match '${ERR}'")
  endif()
  if(NOT "${RC}" STREQUAL "0" AND NOT "${out}" STREQUAL "")
    message(FATAL_ERROR "a failed run wrote to stdout")
  endif()
  return()
endif()

set(ICS_KERNEL_CLI_SCRIPT ${CMAKE_CURRENT_LIST_FILE})
# ics_cli_kernel_test(name rc args [OUT regex] [ERR regex])
function(ics_cli_kernel_test name rc args)
  cmake_parse_arguments(K "" "OUT;ERR" "" ${ARGN})
  set(defs -DCLI=$<TARGET_FILE:icshadow_cli> "-DARGS=${args}" -DRC=${rc})
  if(DEFINED K_OUT)
    list(APPEND defs "-DOUT=${K_OUT}")
  endif()
  if(DEFINED K_ERR)
    list(APPEND defs "-DERR=${K_ERR}")
  endif()
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} ${defs} -P ${ICS_KERNEL_CLI_SCRIPT})
  set_tests_properties(${name} PROPERTIES LABELS fast)
endfunction()

set(num "-?[0-9.e+-]+")
ics_cli_kernel_test(cli_kernel_help 0 "kernel|--help" OUT "usage: icshadow kernel ellipse.*--samples")
ics_cli_kernel_test(cli_kernel_ellipse_help 0 "kernel|ellipse|--help" OUT "--offset U")
# good output: every field, in order, %.17g numbers, N taps
ics_cli_kernel_test(cli_kernel_good 0
  "kernel|ellipse|--varx|1|--vary|0.25|--angle|30|--samples|3|--offset|0.1"
  OUT "^{\"kernel\":\"ellipse\",\"varx\":1,\"vary\":0.25,\"angle_deg\":30,\"a\":1\\.57706145031234[0-9]*,\"b\":0\\.6466141462403[0-9]*,\"t\":0\\.2907861862776[0-9]*,\"samples\":3,\"offset\":0\\.10000000000000001,\"taps\":\\[\\[${num},${num}\\],\\[${num},${num}\\],\\[${num},${num}\\]\\]}\n$")
# line light: a = sqrt(3 varx) = 3, taps at the segment's ends
ics_cli_kernel_test(cli_kernel_line 0 "kernel|ellipse|--varx|3|--vary|0"
  OUT "\"a\":3,\"b\":0,\"t\":0,\"samples\":2,\"offset\":0,\"taps\":\\[\\[3,0\\],\\[-3,0\\]\\]}")
# point light: one tap at the origin, samples reported as 1
ics_cli_kernel_test(cli_kernel_point 0 "kernel|ellipse|--varx|0|--vary|0|--samples|8"
  OUT "\"samples\":1,\"offset\":0,\"taps\":\\[\\[0,0\\]\\]}")
# vary > varx, ratio 1e12: the minor radius stays accurate (a = sqrt(3/2 varx) to 1e-6 rel)
ics_cli_kernel_test(cli_kernel_tall 0 "kernel|ellipse|--varx|1e-12|--vary|1|--samples|4"
  OUT "\"a\":1\\.22474[0-9]*e-06,\"b\":1\\.7320[0-9]*,\"t\":0\\.99999929[0-9]*,\"samples\":4")
# bad input: exit 2, a message naming the problem, nothing on stdout
ics_cli_kernel_test(cli_kernel_no_kernel 2 "kernel" ERR "missing kernel name")
ics_cli_kernel_test(cli_kernel_unknown_kernel 2 "kernel|gauss|--varx|1|--vary|1" ERR "unknown kernel 'gauss'")
ics_cli_kernel_test(cli_kernel_not_a_number 2 "kernel|ellipse|--varx|abc|--vary|1" ERR "--varx: not a number: 'abc'")
ics_cli_kernel_test(cli_kernel_trailing_junk 2 "kernel|ellipse|--varx|1|--vary|2x" ERR "--vary: not a number: '2x'")
ics_cli_kernel_test(cli_kernel_nan 2 "kernel|ellipse|--varx|nan|--vary|1" ERR "--varx: NaN")
ics_cli_kernel_test(cli_kernel_negative_variance 2 "kernel|ellipse|--varx|1|--vary|-0.5" ERR "--vary: negative variance")
ics_cli_kernel_test(cli_kernel_infinite_variance 2 "kernel|ellipse|--varx|inf|--vary|1" ERR "--varx: must be finite")
ics_cli_kernel_test(cli_kernel_samples_zero 2 "kernel|ellipse|--varx|1|--vary|1|--samples|0" ERR "--samples: expected an integer in 1..4096")
ics_cli_kernel_test(cli_kernel_samples_too_many 2 "kernel|ellipse|--varx|1|--vary|1|--samples|4097" ERR "--samples: expected an integer in 1..4096")
ics_cli_kernel_test(cli_kernel_samples_not_int 2 "kernel|ellipse|--varx|1|--vary|1|--samples|2.5" ERR "--samples: expected an integer")
ics_cli_kernel_test(cli_kernel_angle_nan 2 "kernel|ellipse|--varx|1|--vary|1|--angle|nan" ERR "--angle: NaN")
ics_cli_kernel_test(cli_kernel_offset_inf 2 "kernel|ellipse|--varx|1|--vary|1|--offset|inf" ERR "--offset: must be finite")
ics_cli_kernel_test(cli_kernel_missing_vary 2 "kernel|ellipse|--varx|1" ERR "--vary is required")
ics_cli_kernel_test(cli_kernel_missing_value 2 "kernel|ellipse|--vary|1|--varx" ERR "--varx: missing value")
ics_cli_kernel_test(cli_kernel_unknown_option 2 "kernel|ellipse|--varx|1|--vary|1|--bogus|3" ERR "unknown option '--bogus'")
