# CLI tests for `icshadow lut`: help, report, atomic output, and bad input (exit 2, a clear
# message on stderr, no output file and no temporary file left behind).
set(ics_lut_cli $<TARGET_FILE:icshadow_cli>)
set(ics_lut_cli_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_lut)
file(MAKE_DIRECTORY ${ics_lut_cli_dir})

add_test(NAME cli_lut_help COMMAND ${ics_lut_cli} lut --help)
set_tests_properties(cli_lut_help PROPERTIES LABELS fast
  PASS_REGULAR_EXPRESSION "icshadow lut --size N --lang c\\|glsl\\|opencl\\|c-data \\[-o FILE\\]")

# expect.sh STATUS REGEX OUT CLI ARGS...: run `CLI lut ARGS...`; require exit STATUS, stderr
# matching REGEX, and (when STATUS != 0) neither OUT nor OUT.tmp* existing afterwards.
file(WRITE ${ics_lut_cli_dir}/expect.sh [=[
want=$1; re=$2; out=$3; cli=$4; shift 4
rm -f "$out" "$out".tmp*
"$cli" lut "$@" 2> "$out.err" > "$out.stdout"; st=$?
cat "$out.err"
if [ "$st" -ne "$want" ]; then echo "FAIL: exit status $st, expected $want"; exit 1; fi
if ! grep -Eq -- "$re" "$out.err"; then echo "FAIL: stderr does not match /$re/"; exit 1; fi
if [ "$want" -ne 0 ]; then
  for f in "$out" "$out".tmp*; do
    if [ -e "$f" ]; then echo "FAIL: $f left behind"; exit 1; fi
  done
fi
echo "OK: exit $st"
]=])
function(ics_lut_cli_expect name status regex)
  set(out ${ics_lut_cli_dir}/${name}.out)
  string(REPLACE "@OUT@" "${out}" args "${ARGN}")
  add_test(NAME cli_lut_${name}
    COMMAND sh ${ics_lut_cli_dir}/expect.sh ${status} ${regex} ${out} ${ics_lut_cli} ${args})
  set_tests_properties(cli_lut_${name} PROPERTIES LABELS fast)
endfunction()

ics_lut_cli_expect(size_not_number 2 "--size must be an integer in 4\\.\\.65536, got 'abc'"
  --size abc --lang glsl -o @OUT@)
ics_lut_cli_expect(size_trailing_junk 2 "--size must be an integer" --size 64x --lang glsl -o @OUT@)
ics_lut_cli_expect(size_fraction 2 "--size must be an integer" --size 64.0 --lang c -o @OUT@)
ics_lut_cli_expect(size_empty 2 "--size must be an integer" --size "" --lang c -o @OUT@)
ics_lut_cli_expect(size_too_small 2 "--size must be an integer in 4\\.\\.65536, got '3'"
  --size 3 --lang glsl -o @OUT@)
ics_lut_cli_expect(size_negative 2 "--size must be an integer" --size -64 --lang glsl -o @OUT@)
ics_lut_cli_expect(size_huge 2 "--size must be an integer in 4\\.\\.65536, got '65537'"
  --size 65537 --lang opencl -o @OUT@)
ics_lut_cli_expect(size_overflow 2 "--size must be an integer"
  --size 99999999999999999999999 --lang opencl -o @OUT@)
ics_lut_cli_expect(lang_unknown 2 "unknown language 'hlsl'" --size 64 --lang hlsl -o @OUT@)
ics_lut_cli_expect(lang_case 2 "unknown language 'GLSL'" --size 64 --lang GLSL -o @OUT@)
ics_lut_cli_expect(lang_missing 2 "missing --lang" --size 64 -o @OUT@)
ics_lut_cli_expect(size_missing 2 "missing --size" --lang glsl -o @OUT@)
ics_lut_cli_expect(value_missing 2 "missing value after '--lang'" --size 64 -o @OUT@ --lang)
ics_lut_cli_expect(unknown_option 2 "unknown argument '--frobnicate'"
  --size 64 --lang glsl --frobnicate -o @OUT@)
ics_lut_cli_expect(report_with_output 2 "--report takes no" --report -o @OUT@)
ics_lut_cli_expect(report_bad_sizes 2 "--sizes must be increasing integers" --report --sizes 8,abc)
ics_lut_cli_expect(report_unsorted_sizes 2 "--sizes must be increasing" --report --sizes 16,8)
ics_lut_cli_expect(sizes_without_report 2 "--sizes goes with --report" --sizes 8 --size 8 --lang c)
# a write that cannot happen: runtime failure (exit 1), nothing left behind
ics_lut_cli_expect(unwritable 1 "cannot create"
  --size 16 --lang glsl -o ${ics_lut_cli_dir}/no/such/dir/x.glsl)

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
add_test(NAME cli_lut_report COMMAND ${ics_lut_cli} lut --report --sizes 8,16)
set_tests_properties(cli_lut_report PROPERTIES LABELS fast PASS_REGULAR_EXPRESSION
  "^method,size,ratio_max_rel_err,vx_max_rel_err,radii_max_rel_err,ratio_float_max_rel_err,vx_float_max_rel_err,radii_float_max_rel_err,ratio_order,vx_order,ratio_ns_per_call,vx_ns_per_call,grid_points\nlut,8,[^\n]+\nlut,16,[^\n]+\nexact,[^\n]+\n$")
