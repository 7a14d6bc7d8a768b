# CLI tests for `icshadow bench minmax`: help, a tiny run (header + one CSV line whose max
# error vs brute force is at rounding level), the SVD table, the Fig. 4 CSV, and bad input
# (exit 2, a message naming the problem, nothing on stdout, no output file left behind).
set(ics_mm_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_minmax)
file(MAKE_DIRECTORY ${ics_mm_dir})
set(f "[-0-9.e+]+")
ics_cli_test(NAME cli_minmax_help RC 0 ARGS "bench|minmax|--help"
  OUT "usage: icshadow bench minmax.*--samples LIST.*--fig4-csv FILE")
# tiny run: 64 samples, 8 rows, 4 rays; byte counts are integers (%.17g); the error column must
# be below 1e-12 (rounding only)
ics_cli_test(NAME cli_minmax_tiny RC 0 ARGS "bench|minmax|--samples|64|--rows|8|--rays|4|--reps|1"
  OUT "^samples,rows,rays,terms,build_s,prefix_s,traverse_s,march_s,tree_bytes,march_bytes,speedup,speedup_with_build,lit_runs_per_ray,max_abs_err,max_rel_err,backend,traverse_median_s,traverse_max_s,march_median_s,march_max_s\n64,8,4,4,${f},${f},${f},${f},[0-9]+,[0-9]+,${f},${f},${f},${f},(0|[0-9.]+e-(1[3-9]|[2-9][0-9]|[0-9][0-9][0-9])),cpu,${f},${f},${f},${f}\n$")
ics_cli_test(NAME cli_minmax_tiny_noise RC 0 ARGS "bench|minmax|--samples|100,33|--rows|4|--rays|8|--reps|1|--scene|noise|--terms|2"
  OUT "\n100,4,8,2,[^\n]*,cpu,[^\n]*\n33,4,8,2,[^\n]*,cpu,[^\n]*\n$")
ics_cli_test(NAME cli_minmax_backend_unknown RC 2 ARGS "bench|minmax|--backend|gpu"
  ERR "--backend: expected cpu, cl or cpu,cl, got 'gpu'")
# SVD table: 10 rows; at N = 1 the relative Frobenius error is well above rounding (the
# integrand is not rank one), and by N = 10 it is below 1e-12
ics_cli_test(NAME cli_minmax_svd_table RC 0 ARGS "bench|minmax|--svd-table|--samples|128|--rows|4|--rays|4"
  OUT "^N,sigma_rel,grid_fro_rel,grid_max_rel,fullres_max_rel,inscatter_max_rel\n1,1,0\\.[0-9]+,.*\n10,[^,]+,[0-9.]+e-(1[2-9]),")
ics_cli_test(NAME cli_minmax_fig4 RC 0 ARGS "bench|minmax|--samples|64|--rows|8|--rays|8|--fig4-csv|${ics_mm_dir}/fig4.csv")
ics_cli_test(NAME cli_minmax_unknown_option RC 2 ARGS "bench|minmax|--size|64" ERR "unknown option '--size'")
ics_cli_test(NAME cli_minmax_samples_zero RC 2 ARGS "bench|minmax|--samples|0" ERR "--samples: expected an integer in 1\\.\\.16384, got '0'")
ics_cli_test(NAME cli_minmax_samples_junk RC 2 ARGS "bench|minmax|--samples|64,x" ERR "--samples: expected an integer in 1\\.\\.16384, got 'x'")
ics_cli_test(NAME cli_minmax_samples_huge RC 2 ARGS "bench|minmax|--samples|99999999999" ERR "--samples: expected an integer")
ics_cli_test(NAME cli_minmax_samples_empty RC 2 ARGS "bench|minmax|--samples|,"
  ERR "--samples: expected integers in 1\\.\\.16384")
ics_cli_test(NAME cli_minmax_rows_nan RC 2 ARGS "bench|minmax|--rows|nan" ERR "--rows: expected an integer in 1\\.\\.8192, got 'nan'")
ics_cli_test(NAME cli_minmax_terms_big RC 2 ARGS "bench|minmax|--terms|11" ERR "--terms: expected an integer in 1\\.\\.10")
ics_cli_test(NAME cli_minmax_too_big RC 2 ARGS "bench|minmax|--rows|8192|--samples|16384" ERR "exceeds 2\\^25 samples")
ics_cli_test(NAME cli_minmax_missing_value RC 2 ARGS "bench|minmax|--reps" ERR "--reps: missing value")
ics_cli_test(NAME cli_minmax_bad_scene RC 2 ARGS "bench|minmax|--scene|forest" ERR "--scene: expected 'hf' or 'noise', got 'forest'")
ics_cli_test(NAME cli_minmax_fig4_bad_dir RC 1 ARGS "bench|minmax|--samples|16|--rows|2|--rays|2|--fig4-csv|${ics_mm_dir}/no/such/dir/f.csv"
  ERR "cannot create" NOFILE "${ics_mm_dir}/no/such/dir/f.csv")
# memory and work limits, checked before any work (the first ran > 60 s at 3.1 GB before)
ics_cli_test(NAME cli_minmax_limit_memory RC 2 ARGS "bench|minmax|--rows|8192|--rays|4096|--samples|4096|--svd-table"
  ERR "--samples 4096 with --rows 8192 and --rays 4096 .*GiB of memory; the limit is 4 GiB")
ics_cli_test(NAME cli_minmax_limit_work RC 2 ARGS "bench|minmax|--rows|8192|--rays|128|--samples|4096"
  ERR "--samples 4096 with --rows 8192, --rays 128, --terms 4 and --reps 5: an estimated [0-9.e+]+ operations; the work limit is 2\\^36")
ics_cli_test(NAME cli_minmax_limit_work_svd RC 2 ARGS "bench|minmax|--rows|1024|--rays|512|--samples|4096|--svd-table"
  ERR "and --svd-table: an estimated [0-9.e+]+ operations; the work limit is 2\\^36")
ics_cli_test(NAME cli_minmax_progress RC 0 ARGS "bench|minmax|--samples|32|--rows|2|--rays|2|--reps|2|--progress"
  ERR "samples 32: repetition 2/2")
# stdout on a full device: exit 1 with "cannot write stdout: <strerror>" (minmax and occtex)
add_test(NAME cli_bench_stdout_full
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/bench_stdout_full.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_bench_stdout_full PROPERTIES LABELS fast)
# list items must not be empty (as sat's --modes); an empty file name is a usage error
ics_cli_test(NAME cli_minmax_samples_empty_item RC 2 ARGS "bench|minmax|--samples|64,,128"
  ERR "--samples: expected integers in 1\\.\\.16384, got an empty item in '64,,128'")
ics_cli_test(NAME cli_minmax_samples_trailing_comma RC 2 ARGS "bench|minmax|--samples|64,"
  ERR "--samples: expected integers in 1\\.\\.16384, got an empty item in '64,'")
# (an empty argument cannot pass through ics_cli_test's list: a script checks both commands)
add_test(NAME cli_bench_empty_path
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/bench_empty_path.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_bench_empty_path PROPERTIES LABELS fast)
# options a mode does not use: contradictions are refused, ignored options are named
ics_cli_test(NAME cli_minmax_table_and_fig4 RC 2 ARGS "bench|minmax|--svd-table|--fig4-csv|${ics_mm_dir}/both.csv"
  ERR "--svd-table and --fig4-csv: choose one" NOFILE "${ics_mm_dir}/both.csv")
ics_cli_test(NAME cli_minmax_svd_table_ignored RC 0 ARGS "bench|minmax|--svd-table|--samples|32,64|--rows|2|--rays|2|--reps|2|--terms|3"
  OUT "^N,sigma_rel" ERR "warning: --reps is ignored with --svd-table.*warning: --terms is ignored with --svd-table.*warning: --svd-table uses only the first --samples value \\(32\\)")
