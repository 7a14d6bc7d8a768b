# CLI tests for `icshadow eval` and the top-level dispatcher: help, domain handling, and bad
# input (line numbers on stderr, nan kept in place on stdout, exit status 2).
ics_cli_test(NAME cli_help RC 0 ARGS "--help" OUT "eval.*kernel.*lut")
ics_cli_test(NAME cli_no_command RC 2 ARGS "" ERR "usage: icshadow COMMAND")
ics_cli_test(NAME cli_unknown_command RC 2 ARGS "frobnicate" ERR "unknown command 'frobnicate'")
ics_cli_test(NAME cli_eval_help RC 0 ARGS "eval|--help" OUT "ratio_to_t")
ics_cli_test(NAME cli_eval_unknown_function RC 2 ARGS "eval|no_such_function"
  ERR "unknown function 'no_such_function'")
ics_cli_test(NAME cli_eval_no_function RC 2 ARGS "eval" ERR "usage: icshadow eval FUNC")
add_test(NAME cli_eval_bad_line
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/eval_bad_line.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_eval_bad_line PROPERTIES LABELS fast)
