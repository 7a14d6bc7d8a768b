# CLI tests for `icshadow bench occtex`: --help, a small run (CSV header and rows, errors in
# range), the Fig. 3 CSV, and bad input (exit 2, a message naming the problem, no stdout).
set(num "[0-9.e+-]+")
set(frac "(0(\\.[0-9]+)?|1|[0-9](\\.[0-9]+)?e-[0-9]+)") # a number in [0, 1] as %.17g prints it
set(int "[0-9]+") # a byte count (an integer below 2^53 prints as one with %.17g)
set(occ_small "bench|occtex|--sizes|32|--slices|2|--scene|plates|--receivers|6|--light-samples|4|--reps|1")
ics_cli_test(NAME cli_occtex_help RC 0 ARGS "bench|occtex|--help" OUT "usage: icshadow bench occtex.*--fig3-csv")
# a small run: the header, then exactly the 9 rows (3 prefilters x 3 combinations) in order;
# mean and max errors are fractions in [0, 1] (checked on the first row: CMake regexes allow
# few groups)
set(occ_rows "plates,mipmap,product,32,2,${num},${num},${num},${int},${int},${num},${frac},${frac},-?${num},${num},${num},${num},${num}\n")
foreach(pf mipmap nbuffers sat)
  foreach(c product sum max)
    if(NOT pf STREQUAL "mipmap" OR NOT c STREQUAL "product")
      string(APPEND occ_rows "plates,${pf},${c},32,2,${num},${num},${num},${int},${int},${num},${num},${num},-?${num},${num},${num},${num},${num}\n")
    endif()
  endforeach()
endforeach()
ics_cli_test(NAME cli_occtex_small RC 0 ARGS "${occ_small}"
  OUT "^scene,prefilter,combination,size,slices,build_ms,query_ms,time_ms,build_bytes,query_bytes,brute_ms,mean_abs_err,max_abs_err,mean_signed_err,speedup,brute_median_ms,time_median_ms,speedup_median\n${occ_rows}$")
ics_cli_test(NAME cli_occtex_fig3 RC 0
  ARGS "bench|occtex|--sizes|32|--slices|2|--receivers|4|--light-samples|4|--fig3-csv|${CMAKE_CURRENT_BINARY_DIR}/occtex_fig3.csv")
ics_cli_test(NAME cli_occtex_fig3_bad_dir RC 1
  ARGS "bench|occtex|--sizes|32|--slices|2|--receivers|4|--fig3-csv|${CMAKE_CURRENT_BINARY_DIR}/no/such/dir/f.csv"
  ERR "cannot create" NOFILE "${CMAKE_CURRENT_BINARY_DIR}/no/such/dir/f.csv")
ics_cli_test(NAME cli_occtex_size_not_pow2 RC 2 ARGS "bench|occtex|--sizes|100" ERR "--sizes: expected power-of-two integers in 1..4096, got '100'")
ics_cli_test(NAME cli_occtex_size_huge RC 2 ARGS "bench|occtex|--sizes|8192" ERR "--sizes: expected power-of-two integers in 1..4096, got '8192'")
ics_cli_test(NAME cli_occtex_size_empty RC 2 ARGS "bench|occtex|--sizes|,," ERR "--sizes: empty list")
ics_cli_test(NAME cli_occtex_slices_zero RC 2 ARGS "bench|occtex|--slices|0" ERR "--slices: expected integers in 1..64, got '0'")
ics_cli_test(NAME cli_occtex_light_nan RC 2 ARGS "bench|occtex|--light|nan" ERR "--light: expected a size in \\(0, 100\\], got 'nan'")
ics_cli_test(NAME cli_occtex_light_text RC 2 ARGS "bench|occtex|--light|big" ERR "--light: not a number: 'big'")
ics_cli_test(NAME cli_occtex_scene_unknown RC 2 ARGS "bench|occtex|--scene|trees" ERR "--scene: expected a list of distinct names")
ics_cli_test(NAME cli_occtex_receivers_zero RC 2 ARGS "bench|occtex|--receivers|0" ERR "--receivers: expected an integer in 1..1024, got '0'")
ics_cli_test(NAME cli_occtex_missing_value RC 2 ARGS "bench|occtex|--reps" ERR "--reps: missing value")
ics_cli_test(NAME cli_occtex_unknown_option RC 2 ARGS "bench|occtex|--bogus|1" ERR "unknown option '--bogus'")
ics_cli_test(NAME cli_occtex_supersample_too_big RC 2 ARGS "bench|occtex|--sizes|4096|--supersample|4" ERR "--sizes x --supersample must stay <= 8192")
# memory and work limits, checked before any allocation or work
ics_cli_test(NAME cli_occtex_limit_brute RC 2 ARGS "bench|occtex|--receivers|1024|--light-samples|1024|--sizes|1|--slices|1"
  ERR "brute force: --receivers 1024 with --light-samples 1024, 12 boxes \\(plates\\) and --reps 3: an estimated [0-9.e+]+ operations; the work limit is 2\\^36")
ics_cli_test(NAME cli_occtex_limit_texels RC 2 ARGS "bench|occtex|--sizes|4096|--slices|64"
  ERR "--sizes 4096 with --slices 64: 64 x 4096\\^2 texels exceeds the limit 2\\^28")
ics_cli_test(NAME cli_occtex_limit_memory RC 2 ARGS "bench|occtex|--sizes|4096|--slices|4"
  ERR "--sizes 4096 with --slices 4: an estimated [0-9.]+ GiB of memory .*the limit is 4 GiB")
ics_cli_test(NAME cli_occtex_limit_work RC 2 ARGS "bench|occtex|--sizes|512|--slices|64|--supersample|16|--reps|10"
  ERR "--sizes 512 with --slices 64, --supersample 16, --receivers 48 and --reps 10: an estimated [0-9.e+]+ operations; the work limit is 2\\^36")
ics_cli_test(NAME cli_occtex_limit_fig3_brute RC 2 ARGS "bench|occtex|--receivers|1024|--light-samples|512|--scene|foliage|--fig3-csv|${CMAKE_CURRENT_BINARY_DIR}/occtex_limit.csv"
  ERR "brute force: --receivers 1024 with --light-samples 512, 150 boxes \\(foliage\\) and --reps 1" NOFILE "${CMAKE_CURRENT_BINARY_DIR}/occtex_limit.csv")
ics_cli_test(NAME cli_occtex_progress RC 0 ARGS "${occ_small}|--progress" ERR "plates: repetition 1/1: size 32, 2 slices, sat")
# list items must not be empty (the empty --fig3-csv name: tests/cli/bench_empty_path.sh)
ics_cli_test(NAME cli_occtex_sizes_empty_item RC 2 ARGS "bench|occtex|--sizes|8,,16" ERR "--sizes: empty list item in '8,,16'")
ics_cli_test(NAME cli_occtex_slices_trailing_comma RC 2 ARGS "bench|occtex|--slices|2," ERR "--slices: empty list item in '2,'")
# ignored options are named
ics_cli_test(NAME cli_occtex_fig3_prefilter_ignored RC 0 ARGS "${occ_small}|--fig3-prefilter|mipmap"
  OUT "^scene," ERR "warning: --fig3-prefilter is ignored without --fig3-csv")
ics_cli_test(NAME cli_occtex_fig3_ignored RC 0
  ARGS "bench|occtex|--sizes|32,64|--slices|2|--receivers|4|--light-samples|4|--reps|2|--fig3-csv|${CMAKE_CURRENT_BINARY_DIR}/occtex_fig3_ign.csv"
  ERR "warning: --reps is ignored with --fig3-csv.*warning: --fig3-csv uses only the first --scene, --sizes and --slices values \\(plates, 32, 2\\)")
