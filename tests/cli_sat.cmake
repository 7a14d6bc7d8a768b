# CLI tests for `icshadow bench sat2d|sat3d` (cli/bench_sat.c): help, a tiny quick run (CSV
# header and one line per mode, every mode within its documented error bound), the chirp CSV
# for paper_figs/ament_fig4.py, and bad input (exit 2, a clear message, nothing on stdout).
set(ics_sat_cli_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_sat)
file(MAKE_DIRECTORY ${ics_sat_cli_dir})
set(f "[0-9.e+-]+")
set(lt1 "(0|0\\.[0-9]+|[0-9](\\.[0-9]+)?e-[0-9]+)") # a number below 1
set(hdr "kind,mode,width,height,depth,reps,time_s,first_build_s,bytes,memcpy_s,floor_ratio,gbytes_per_s,max_rel_err,max_bound_frac,boxes,time_median_s,time_max_s\n")

ics_cli_test(NAME cli_sat2d_help RC 0 ARGS "bench|sat2d|--help" OUT "usage: icshadow bench sat2d.*--chirp-csv")
ics_cli_test(NAME cli_sat3d_help RC 0 ARGS "bench|sat3d|--help" OUT "usage: icshadow bench sat3d.*--depth")
# tiny runs: 2D 64 x 48 cells, all four modes; 3D 20 x 16 x 12 cells, two modes. Bytes touched
# = 4 per input cell + 4 or 8 per table cell; max_bound_frac (error / documented bound) < 1 for
# float and float-offset, 0 (exact) for compensated and double.
ics_cli_test(NAME cli_sat2d_tiny RC 0 ARGS "bench|sat2d|--width|64|--height|48|--reps|2|--boxes|50"
  OUT "^${hdr}sat2d,float,64,48,1,2,${f},${f},24576,${f},${f},${f},${f},${lt1},50,${f},${f}\nsat2d,float-offset,64,48,1,2,${f},${f},24576,${f},${f},${f},${f},${lt1},50,${f},${f}\nsat2d,compensated,64,48,1,2,${f},${f},36864,${f},${f},${f},0,0,50,${f},${f}\nsat2d,double,64,48,1,2,${f},${f},36864,${f},${f},${f},0,0,50,${f},${f}\n$")
ics_cli_test(NAME cli_sat3d_tiny RC 0 ARGS "bench|sat3d|--width|20|--height|16|--depth|12|--modes|double,float|--reps|1|--boxes|20"
  OUT "^${hdr}sat3d,double,20,16,12,1,${f},${f},46080,${f},${f},${f},0,0,20,${f},${f}\nsat3d,float,20,16,12,1,${f},${f},30720,${f},${f},${f},${f},${lt1},20,${f},${f}\n$")
# the chirp CSV: header, 708 rows, tau = 16 sigma, T = exp(-tau), and the SAT box filter equal
# to an independent moving sum (tests/cli/sat_csv_checks.sh)
add_test(NAME cli_sat2d_chirp
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/sat_csv_checks.sh $<TARGET_FILE:icshadow_cli> chirp ${ics_sat_cli_dir})
# (both checkers parse the CSV with awk, which reads and prints numbers in the caller's
# LC_NUMERIC: under de_DE.UTF-8 mawk read "0.125" as 0 and every row failed. The CLI itself
# does not depend on the locale: tests/cli/locale_numbers.sh.)
set_tests_properties(cli_sat2d_chirp PROPERTIES LABELS fast ENVIRONMENT LC_ALL=C)
ics_cli_test(NAME cli_sat2d_chirp_stdout RC 0 ARGS "bench|sat2d|--chirp-csv|-"
  OUT "^x,sigma,tau,T_none,tau_box,T_box,tau_gauss,T_gauss\n0\\.125,")
# bad input
ics_cli_test(NAME cli_sat2d_size_text RC 2 ARGS "bench|sat2d|--size|abc" ERR "--size: expected an integer in 1\\.\\.1073741824, got 'abc'")
ics_cli_test(NAME cli_sat2d_size_zero RC 2 ARGS "bench|sat2d|--size|0" ERR "--size: expected an integer")
ics_cli_test(NAME cli_sat2d_size_negative RC 2 ARGS "bench|sat2d|--width|-5|--height|4" ERR "--width: expected an integer")
ics_cli_test(NAME cli_sat2d_size_junk RC 2 ARGS "bench|sat2d|--size|64x" ERR "--size: expected an integer")
ics_cli_test(NAME cli_sat2d_size_huge RC 2 ARGS "bench|sat2d|--size|100000" ERR "would allocate .* GiB.*limit is 8 GiB")
ics_cli_test(NAME cli_sat3d_size_huge RC 2 ARGS "bench|sat3d|--size|2048" ERR "would allocate .* GiB.*limit is 8 GiB")
ics_cli_test(NAME cli_sat3d_size_overflow RC 2 ARGS "bench|sat3d|--size|99999999999999999999" ERR "--size: expected an integer")
ics_cli_test(NAME cli_sat2d_mode_unknown RC 2 ARGS "bench|sat2d|--modes|float,half" ERR "unknown precision mode 'half'")
ics_cli_test(NAME cli_sat2d_mode_twice RC 2 ARGS "bench|sat2d|--modes|float,float" ERR "mode given twice 'float'")
ics_cli_test(NAME cli_sat2d_mode_empty RC 2 ARGS "bench|sat2d|--modes|float,,double" ERR "bad --modes list")
ics_cli_test(NAME cli_sat2d_reps_bad RC 2 ARGS "bench|sat2d|--reps|0" ERR "--reps: expected an integer in 1\\.\\.100")
ics_cli_test(NAME cli_sat2d_missing_value RC 2 ARGS "bench|sat2d|--size" ERR "--size: missing value")
ics_cli_test(NAME cli_sat2d_unknown_option RC 2 ARGS "bench|sat2d|--frobnicate" ERR "unknown option '--frobnicate'")
ics_cli_test(NAME cli_sat2d_depth RC 2 ARGS "bench|sat2d|--depth|4" ERR "--depth is for sat3d")
ics_cli_test(NAME cli_sat3d_chirp RC 2 ARGS "bench|sat3d|--chirp-csv|x.csv" ERR "--chirp-csv is for sat2d")
ics_cli_test(NAME cli_sat2d_size_and_width RC 2 ARGS "bench|sat2d|--size|8|--width|8" ERR "either --size or --width")
ics_cli_test(NAME cli_sat2d_chirp_unwritable RC 1 ARGS "bench|sat2d|--chirp-csv|${ics_sat_cli_dir}/no/such/dir/c.csv"
  ERR "cannot create" NOFILE ${ics_sat_cli_dir}/no/such/dir/c.csv)
ics_cli_test(NAME cli_sat2d_lights RC 2 ARGS "bench|sat2d|--lights" ERR "--lights is for sat3d")
# CSAT / SSAT against brute-force marching (a few seconds): 16 csat and 12 ssat rows; mean
# error <= 5 % and max error <= 50 % of the mean optical depth, the mean error falling when the
# table is refined (tests/cli/sat_csv_checks.sh; the times are the benchmark's, docs/sat.md).
add_test(NAME cli_sat3d_lights
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/sat_csv_checks.sh $<TARGET_FILE:icshadow_cli> lights)
set_tests_properties(cli_sat3d_lights PROPERTIES LABELS medium ENVIRONMENT LC_ALL=C)
# stdout on a full device: the write error is reported on stderr and the exit status is 1
add_test(NAME cli_sat_stdout_full
  COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/sat_stdout_full.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_sat_stdout_full PROPERTIES LABELS fast)
ics_cli_test(NAME cli_sat2d_backend_unknown RC 2 ARGS "bench|sat2d|--backend|gpu"
  ERR "--backend: expected cpu, cl or cpu,cl, got 'gpu'")
