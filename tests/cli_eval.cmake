# CLI tests for `icshadow eval`, the top-level dispatcher and the shared -o handling: help,
# domain handling, output targets (links, FIFOs, directories), and bad input (line numbers on
# stderr, nan kept in place on stdout, exit status 2; unreadable stdin, exit status 1).
ics_cli_test(NAME cli_help RC 0 ARGS "--help" OUT "eval.*kernel.*lut")
ics_cli_test(NAME cli_no_command RC 2 ARGS "" ERR "usage: icshadow COMMAND")
ics_cli_test(NAME cli_unknown_command RC 2 ARGS "frobnicate" ERR "unknown command 'frobnicate'")
ics_cli_test(NAME cli_eval_help RC 0 ARGS "eval|--help" OUT "ratio_to_t")
ics_cli_test(NAME cli_eval_unknown_function RC 2 ARGS "eval|no_such_function"
  ERR "unknown function 'no_such_function'")
ics_cli_test(NAME cli_eval_no_function RC 2 ARGS "eval" ERR "icshadow eval: give a FUNC")
ics_cli_test(NAME cli_eval_file_argument RC 2 ARGS "eval|ellipk|/nonexistent"
  ERR "icshadow eval: expected one FUNC, got 2 arguments \\(the numbers come on stdin")
add_test(NAME cli_eval_bad_line
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/eval_bad_line.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_eval_bad_line PROPERTIES LABELS fast)
add_test(NAME cli_output_targets
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/output_targets.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_output_targets PROPERTIES LABELS fast)
# numbers printed and parsed do not change with the caller's locale (LC_NUMERIC with a decimal
# comma, when such a locale is installed; skipped otherwise)
add_test(NAME cli_locale_numbers
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/locale_numbers.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_locale_numbers PROPERTIES LABELS fast SKIP_RETURN_CODE 77)
# every command reports a stdout it cannot write (full device, closed) with exit status 1
add_test(NAME cli_stdout_full
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/stdout_full.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_stdout_full PROPERTIES LABELS fast)
