# CLI tests for `icshadow lut`: help, report, atomic output, and bad input (exit 2, a clear
# message on stderr, nothing on stdout, no output file and no temporary file left behind;
# ics_cli_test in tests/CMakeLists.txt checks all of that).
set(ics_lut_cli $<TARGET_FILE:icshadow_cli>)
set(ics_lut_cli_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_lut)
file(MAKE_DIRECTORY ${ics_lut_cli_dir})

ics_cli_test(NAME cli_lut_help RC 0 ARGS "lut|--help"
  OUT "icshadow lut --size N --lang c\\|glsl\\|opencl\\|c-data \\[-o FILE\\]")

ics_cli_test(NAME cli_lut_size_not_number RC 2 ARGS "lut|--size|abc|--lang|glsl|-o|${ics_lut_cli_dir}/size_not_number.out" ERR "--size: expected an integer in 4\\.\\.65536, got 'abc'" NOFILE ${ics_lut_cli_dir}/size_not_number.out)
ics_cli_test(NAME cli_lut_size_trailing_junk RC 2 ARGS "lut|--size|64x|--lang|glsl|-o|${ics_lut_cli_dir}/size_trailing_junk.out" ERR "--size: expected an integer" NOFILE ${ics_lut_cli_dir}/size_trailing_junk.out)
ics_cli_test(NAME cli_lut_size_fraction RC 2 ARGS "lut|--size|64.0|--lang|c|-o|${ics_lut_cli_dir}/size_fraction.out" ERR "--size: expected an integer" NOFILE ${ics_lut_cli_dir}/size_fraction.out)
# an empty --size value (the expect driver cannot pass empty arguments): exit 2 and the message
add_test(NAME cli_lut_size_empty COMMAND sh -c
  "out=$(\"$0\" lut --size '' --lang c 2>&1 >/dev/null); rc=$?; echo \"$out\"; [ $rc -eq 2 ] && echo \"$out\" | grep -q -- '--size: expected an integer'"
  $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_lut_size_empty PROPERTIES LABELS fast)
ics_cli_test(NAME cli_lut_size_too_small RC 2 ARGS "lut|--size|3|--lang|glsl|-o|${ics_lut_cli_dir}/size_too_small.out" ERR "--size: expected an integer in 4\\.\\.65536, got '3'" NOFILE ${ics_lut_cli_dir}/size_too_small.out)
ics_cli_test(NAME cli_lut_size_negative RC 2 ARGS "lut|--size|-64|--lang|glsl|-o|${ics_lut_cli_dir}/size_negative.out" ERR "--size: expected an integer" NOFILE ${ics_lut_cli_dir}/size_negative.out)
ics_cli_test(NAME cli_lut_size_huge RC 2 ARGS "lut|--size|65537|--lang|opencl|-o|${ics_lut_cli_dir}/size_huge.out" ERR "--size: expected an integer in 4\\.\\.65536, got '65537'" NOFILE ${ics_lut_cli_dir}/size_huge.out)
ics_cli_test(NAME cli_lut_size_overflow RC 2 ARGS "lut|--size|99999999999999999999999|--lang|opencl|-o|${ics_lut_cli_dir}/size_overflow.out" ERR "--size: expected an integer" NOFILE ${ics_lut_cli_dir}/size_overflow.out)
ics_cli_test(NAME cli_lut_lang_unknown RC 2 ARGS "lut|--size|64|--lang|hlsl|-o|${ics_lut_cli_dir}/lang_unknown.out" ERR "unknown language 'hlsl'" NOFILE ${ics_lut_cli_dir}/lang_unknown.out)
ics_cli_test(NAME cli_lut_lang_case RC 2 ARGS "lut|--size|64|--lang|GLSL|-o|${ics_lut_cli_dir}/lang_case.out" ERR "unknown language 'GLSL'" NOFILE ${ics_lut_cli_dir}/lang_case.out)
ics_cli_test(NAME cli_lut_lang_missing RC 2 ARGS "lut|--size|64|-o|${ics_lut_cli_dir}/lang_missing.out" ERR "missing --lang" NOFILE ${ics_lut_cli_dir}/lang_missing.out)
ics_cli_test(NAME cli_lut_size_missing RC 2 ARGS "lut|--lang|glsl|-o|${ics_lut_cli_dir}/size_missing.out" ERR "missing --size" NOFILE ${ics_lut_cli_dir}/size_missing.out)
ics_cli_test(NAME cli_lut_value_missing RC 2 ARGS "lut|--size|64|-o|${ics_lut_cli_dir}/value_missing.out|--lang" ERR "--lang: missing value" NOFILE ${ics_lut_cli_dir}/value_missing.out)
ics_cli_test(NAME cli_lut_unknown_option RC 2 ARGS "lut|--size|64|--lang|glsl|--frobnicate|-o|${ics_lut_cli_dir}/unknown_option.out" ERR "unknown option '--frobnicate'" NOFILE ${ics_lut_cli_dir}/unknown_option.out)
ics_cli_test(NAME cli_lut_report_with_output RC 2 ARGS "lut|--report|-o|${ics_lut_cli_dir}/report_with_output.out" ERR "--report takes no" NOFILE ${ics_lut_cli_dir}/report_with_output.out)
ics_cli_test(NAME cli_lut_report_bad_sizes RC 2 ARGS "lut|--report|--sizes|8,abc" ERR "--sizes: expected increasing integers")
ics_cli_test(NAME cli_lut_report_unsorted_sizes RC 2 ARGS "lut|--report|--sizes|16,8" ERR "--sizes: expected increasing")
ics_cli_test(NAME cli_lut_report_empty_size RC 2 ARGS "lut|--report|--sizes|8,,16" ERR "--sizes: expected increasing integers")
ics_cli_test(NAME cli_lut_sizes_without_report RC 2 ARGS "lut|--sizes|8|--size|8|--lang|c" ERR "--sizes goes with --report")
# a write that cannot happen: runtime failure (exit 1), nothing left behind
ics_cli_test(NAME cli_lut_unwritable RC 1 ARGS "lut|--size|16|--lang|glsl|-o|${ics_lut_cli_dir}/no/such/dir/x.glsl" ERR "cannot create" NOFILE ${ics_lut_cli_dir}/no/such/dir/x.glsl)

# A good run: exit 0, the file in place, stamped with the command, no temporary file left.
file(WRITE ${ics_lut_cli_dir}/good.sh [=[
cli=$1; out=$2
rm -f "$out" "$out".tmp*
"$cli" lut --size 16 --lang c -o "$out" || { echo "FAIL: exit $?"; exit 1; }
grep -q "^ \* Command: icshadow lut --size 16 --lang c$" "$out" || { echo "FAIL: no stamp"; exit 1; }
grep -q "generated — do not edit" "$out" || { echo "FAIL: no generated marker"; exit 1; }
for f in "$out".tmp*; do
  if [ -e "$f" ]; then echo "FAIL: $f left behind"; exit 1; fi
done
echo "OK"
]=])
add_test(NAME cli_lut_writes_file COMMAND sh ${ics_lut_cli_dir}/good.sh ${ics_lut_cli}
  ${ics_lut_cli_dir}/good.h)
set_tests_properties(cli_lut_writes_file PROPERTIES LABELS fast)

# --report: CSV with a header, one row per size and the exact functions' timing.
ics_cli_test(NAME cli_lut_report RC 0 ARGS "lut|--report|--sizes|8,16"
  OUT "^method,size,ratio_max_rel_err,vx_max_rel_err,radii_max_rel_err,ratio_float_max_rel_err,vx_float_max_rel_err,radii_float_max_rel_err,ratio_order,vx_order,ratio_ns_per_call,vx_ns_per_call,grid_points,ratio_ns_min,ratio_ns_max,vx_ns_min,vx_ns_max\nlut,8,[^\n]+\nlut,16,[^\n]+\nexact,[^\n]+\n$")

# The driver's NOFILE check under a path holding glob syntax ('[', '*', '?'): a run that does
# write the file must be caught ("output left behind"); unescaped, the pattern matched nothing
# and the check passed whatever was left.
set(ics_lut_glob_dir "${ics_lut_cli_dir}/glob[1]*?")
file(MAKE_DIRECTORY "${ics_lut_glob_dir}")
ics_cli_test(NAME cli_expect_nofile_glob RC 0 ARGS "lut|--size|8|--lang|c|-o|${ics_lut_glob_dir}/x.h"
  NOFILE "${ics_lut_glob_dir}/x.h")
set_tests_properties(cli_expect_nofile_glob PROPERTIES
  PASS_REGULAR_EXPRESSION "output left behind:.*/glob\\[1\\]\\*\\?/x\\.h")

# -o FILE whose name is as long as the file system allows (NAME_MAX, 255 here): written, with no
# temporary left behind (the temporary FILE.tmpXXXXXX was too long: "File name too long")
file(WRITE ${ics_lut_cli_dir}/long_name.sh [=[
cli=$1; dir=$2
rm -rf "$dir" && mkdir -p "$dir" || exit 1
max=$(getconf NAME_MAX "$dir") || exit 1
name=$(head -c $((max - 2)) /dev/zero | tr "\\0" n).h
"$cli" lut --size 8 --lang c -o "$dir/$name" || { echo "FAIL: exit $?"; exit 1; }
grep -q "^ \* Command: icshadow lut --size 8 --lang c$" "$dir/$name" || { echo "FAIL: no stamp"; exit 1; }
if [ "$(ls "$dir")" != "$name" ]; then echo "FAIL: left in $dir:"; ls "$dir"; exit 1; fi
echo "OK: a ${#name}-byte name"
]=])
add_test(NAME cli_lut_long_file_name COMMAND sh ${ics_lut_cli_dir}/long_name.sh ${ics_lut_cli}
  ${ics_lut_cli_dir}/long_name)
set_tests_properties(cli_lut_long_file_name PROPERTIES LABELS fast)
# one grid per size: the report's row for a size is the same in any --sizes list and is measured
# on its header stamp's grid
add_test(NAME cli_lut_report_grid COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/lut_report_grid.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_lut_report_grid PROPERTIES LABELS fast)
