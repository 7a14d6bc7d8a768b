# CLI tests for `icshadow iterate` and `icshadow kernel-table`: --help, good output checked
# against values worked out by hand, and every kind of bad input (exit 2, message, no stdout).
set(num "-?[0-9.e+-]+")
ics_cli_test(NAME cli_iterate_help RC 0 ARGS "iterate|--help" OUT "usage: icshadow iterate --kernel K.*--compensate")
# Dirac, variance 1: taps at -1 and +1 (weight 1/2, on the grid: no interpolation). One step of
# H (edge half-way between x = -0.5 and 0.5) gives 1/2 H(x + 1) + 1/2 H(x - 1): 0 for x < -1,
# 1/2 for -1 < x < 1, 1 for x > 1. gauss_cdf = Phi(x / sqrt(1 + 1/12)): Phi(-0.5 / 1.0408) =
# 0.3154770 (by hand from the normal table / erfc).
ics_cli_test(NAME cli_iterate_dirac_one_step RC 0 ARGS "iterate|--kernel|dirac|--var|1|--steps|1|--width|8"
  OUT "^steps,x,value,gauss_cdf\n1,-3\\.5,0,${num}\n1,-2\\.5,0,${num}\n1,-1\\.5,0,${num}\n1,-0\\.5,0\\.5,0\\.315477[0-9]*\n1,0\\.5,0\\.5,0\\.684522[0-9]*\n1,1\\.5,1,${num}\n1,2\\.5,1,${num}\n1,3\\.5,1,${num}\n$")
# The sign convention: a kernel of mean +2 (variance 0) moves the edge by +2 px per step; step
# counts 0 and 1 are both printed.
ics_cli_test(NAME cli_iterate_mean_shift RC 0 ARGS "iterate|--kernel|dirac|--var|0|--mean|2|--steps|0,1|--width|8"
  OUT "\n0,-0\\.5,0,${num}\n0,0\\.5,1,${num}\n.*\n1,1\\.5,0,${num}\n1,2\\.5,1,${num}\n1,3\\.5,1,${num}\n$")
# Dirac at +-0.5 px: each tap is split into two integer taps (linear interpolation); after one
# step the line is 1/4, 1/2, 3/4 around the edge: 1/2 [H(x+1/2) interpolated] + ...
ics_cli_test(NAME cli_iterate_dirac_interpolated RC 0 ARGS "iterate|--kernel|dirac|--var|0.25|--steps|1|--width|6"
  OUT "\n1,-1\\.5,0,${num}\n1,-0\\.5,0\\.25,${num}\n1,0\\.5,0\\.75,${num}\n1,1\\.5,1,${num}\n")
# ... and with --compensate signed the same class is applied with integer taps of variance 1/4
# exactly: weights 1/8, 3/4, 1/8 at -1, 0, 1, giving 1/8 and 7/8 beside the edge.
ics_cli_test(NAME cli_iterate_compensated RC 0 ARGS "iterate|--kernel|dirac|--var|0.25|--steps|1|--width|6|--compensate|signed"
  OUT "\n1,-1\\.5,0,${num}\n1,-0\\.5,0\\.125,${num}\n1,0\\.5,0\\.875,${num}\n1,1\\.5,1,${num}\n")
# step ranges A:B[:STRIDE]: 1:3 prints the profile after 1, 2 and 3 steps; Dirac +-1 after two
# steps (CMake regexes have no {n}: the 8 lines are spelled out): 1/4 H(x + 2) + 1/2 H(x) + 1/4 H(x - 2) = 1/4 at x = -1.5, 3/4 at x = 1.5.
ics_cli_test(NAME cli_iterate_step_range RC 0 ARGS "iterate|--kernel|dirac|--var|1|--steps|1:3|--width|8"
  OUT "^steps,x,value,gauss_cdf\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n1,[^\n]*\n2,-3\\.5,0,[^\n]*\n2,-2\\.5,0,[^\n]*\n2,-1\\.5,0\\.25,[^\n]*\n2,-0\\.5,0\\.25,[^\n]*\n2,0\\.5,0\\.75,[^\n]*\n2,1\\.5,0\\.75,[^\n]*\n2,2\\.5,1,[^\n]*\n2,3\\.5,1,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n3,[^\n]*\n$")
ics_cli_test(NAME cli_iterate_empty_range RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|5:3" ERR "--steps: empty range 5:3")
# bad input: exit 2, a message naming the problem, nothing on stdout
ics_cli_test(NAME cli_iterate_no_kernel RC 2 ARGS "iterate|--var|1|--steps|1" ERR "--kernel is required")
ics_cli_test(NAME cli_iterate_no_steps RC 2 ARGS "iterate|--kernel|dirac|--var|1" ERR "--steps is required")
ics_cli_test(NAME cli_iterate_unknown_kernel RC 2 ARGS "iterate|--kernel|ellipse|--var|1|--steps|1" ERR "unknown 1D kernel 'ellipse'")
ics_cli_test(NAME cli_iterate_bad_list RC 2 ARGS "iterate|--kernel|dirac,|--var|1|--steps|1" ERR "unknown 1D kernel ''")
ics_cli_test(NAME cli_iterate_negative_variance RC 2 ARGS "iterate|--kernel|dirac|--var|-1|--steps|1" ERR "--var: negative variance")
ics_cli_test(NAME cli_iterate_nan RC 2 ARGS "iterate|--kernel|dirac|--var|nan|--steps|1" ERR "--var: NaN")
ics_cli_test(NAME cli_iterate_mean_inf RC 2 ARGS "iterate|--kernel|dirac|--var|1|--mean|inf|--steps|1" ERR "--mean: must be finite")
ics_cli_test(NAME cli_iterate_steps_decreasing RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|10,5" ERR "strictly increasing")
ics_cli_test(NAME cli_iterate_steps_junk RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|1x" ERR "--steps: expected integers")
ics_cli_test(NAME cli_iterate_steps_negative RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|-3" ERR "--steps: expected integers")
ics_cli_test(NAME cli_iterate_odd_width RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|1|--width|7" ERR "--width: expected an even integer")
ics_cli_test(NAME cli_iterate_bad_compensate RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|1|--compensate|yes" ERR "--compensate: expected none, nonneg or signed")
ics_cli_test(NAME cli_iterate_bad_seed RC 2 ARGS "iterate|--kernel|stochastic-dirac|--var|1|--steps|1|--seed|-1" ERR "--seed: expected a non-negative integer")
# an exact top-hat of variance 0.1 cannot have mean 0.5 (its least variance is 1/4)
ics_cli_test(NAME cli_iterate_tophat_impossible RC 2 ARGS "iterate|--kernel|tophat|--var|0.1|--mean|0.5|--steps|1" ERR "out of range")
ics_cli_test(NAME cli_iterate_missing_value RC 2 ARGS "iterate|--kernel|dirac|--steps|1|--var" ERR "--var: missing value")
ics_cli_test(NAME cli_iterate_unknown_option RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|1|--bogus|1" ERR "unknown option '--bogus'")

ics_cli_test(NAME cli_kernel_table_help RC 0 ARGS "kernel-table|--help" OUT "usage: icshadow kernel-table.*ns_per_px_step")
# Dirac, sigma = 5.5: taps at +-5.5 (width 11, 2 taps), each split into two integer taps (4 applied)
# with fraction 1/2, adding 1/2 * 1/2 = 0.25 px^2 per step. Raw top-hat of width sqrt(12 V)
# applied to the interpolated line: V + E[f(1 - f)] = 30.25 + 1/6 = 30.41(6). Stochastic Dirac:
# every width inside 2 rho +- 2, rho = sqrt(30.25 - 1/3) = 5.4696: [8.94, 12.94].
ics_cli_test(NAME cli_kernel_table_good RC 0 ARGS "kernel-table|--no-timing|--iterations|100"
  OUT "^member,class_mean,class_var,iterations,mean,var,var_min,var_max,width_min,width_max,taps,applied_taps,interp_var,ns_per_px_step\ndirac,0,30\\.25,1,0,30\\.25,30\\.25,30\\.25,11,11,2,4,0\\.25,nan\ntophat,0,30\\.25,1,${num},30\\.2(5|49999999)[0-9]*,${num},${num},${num},${num},[0-9]+,[0-9]+,0,nan\ntophat-raw,0,30\\.25,1,${num},30\\.416[0-9]*,.*\nstochastic-dirac,0,30\\.25,100,${num},${num},${num},${num},(8\\.9[4-9]|9|10|11|12)[0-9.]*,(9|10|11|12)[0-9.]*,2,4,.*\ngauss,0,30\\.25,1,${num},30\\.2(5|49999999)[0-9]*,.*,9,[0-9]+,${num},nan\n$")
ics_cli_test(NAME cli_kernel_table_zero_var RC 2 ARGS "kernel-table|--var|0" ERR "--var: the class variance must be > 0")
ics_cli_test(NAME cli_kernel_table_bad_iterations RC 2 ARGS "kernel-table|--iterations|0" ERR "--iterations: expected an integer")
ics_cli_test(NAME cli_kernel_table_unknown_option RC 2 ARGS "kernel-table|--bogus" ERR "unknown option '--bogus'")
# 2D members (Fig. 11 kernels), isotropic class 30.25 px^2: three points at 120 degrees on a circle
# of radius^2 = 2 * 30.25 have cxx = cyy = 30.25, cxy = 0 for every rotation; the whitened Poisson
# patterns are exact for every rotation too; the 5x5 Gaussian grid has 25 taps, the 19x19 361.
set(v3025 "30\\.2(5|4999)[0-9]*")
ics_cli_test(NAME cli_kernel_table_2d RC 0 ARGS "kernel-table|--dims|2|--no-timing|--iterations|100"
  OUT "^member,class_mean_x,class_mean_y,class_cxx,class_cxy,class_cyy,iterations,mean_x,mean_y,cxx,cxy,cyy,cxx_min,cxx_max,width_x_max,width_y_max,taps,applied_taps,interp_var_x,interp_var_y,ns_per_px_step\nellipse-2,0,0,30\\.25,0,30\\.25,100,[^\n]*,2,[0-9]+,${num},${num},nan\nellipse-3,0,0,30\\.25,0,30\\.25,100,${num},${num},${v3025},${num},${v3025},${v3025},${v3025},${num},${num},3,[^\n]*\npoisson-8,0,0,30\\.25,0,30\\.25,100,${num},${num},${v3025},${num},${v3025},${v3025},${v3025},${num},${num},8,[^\n]*\npoisson-16,[^\n]*,16,[0-9]+,${num},${num},nan\ngauss-5x5,0,0,30\\.25,0,30\\.25,1,[^\n]*,25,[0-9]+,${num},${num},nan\ngauss-19x19,[^\n]*,361,[0-9]+,${num},${num},nan\n$")
ics_cli_test(NAME cli_kernel_table_2d_rotated RC 0 ARGS "kernel-table|--dims|2|--var|0.8|--vary|0.2|--angle|30|--no-timing|--iterations|10"
  OUT "\npoisson-8,0,0,0\\.65[0-9]*,0\\.2598076211353[0-9]*,0\\.34999[0-9]*,10,")
ics_cli_test(NAME cli_kernel_table_bad_dims RC 2 ARGS "kernel-table|--dims|3" ERR "--dims: expected 1 or 2")
ics_cli_test(NAME cli_kernel_table_vary_1d RC 2 ARGS "kernel-table|--vary|2" ERR "--vary and --angle need --dims 2")
ics_cli_test(NAME cli_kernel_table_vary_zero RC 2 ARGS "kernel-table|--dims|2|--vary|0" ERR "--vary: the class variance must be > 0")
# budgets: work (1e11 tap-updates) and output (2e9 bytes), checked before anything runs
ics_cli_test(NAME cli_iterate_work_budget RC 2 ARGS "iterate|--kernel|gauss|--samples|65536|--var|36|--steps|1000000|--width|16777216"
  OUT "^$" ERR "estimated work [0-9.e+]+ tap-updates \\(1000000 steps on 16777216 pixels\\) exceeds the budget of 1e\\+11")
ics_cli_test(NAME cli_iterate_work_budget_range RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|0:1000000:1"
  OUT "^$" ERR "exceeds the budget of 1e\\+11")
# 100001 profiles of 1000 lines: ~7e9 bytes
ics_cli_test(NAME cli_iterate_output_budget RC 2 ARGS "iterate|--kernel|dirac|--var|1|--steps|0:100000:1|--width|1000"
  OUT "^$" ERR "output would be about [0-9.e+]+ bytes \\(100001 profiles of 1000 lines\\) and exceed the budget of 2e\\+09 bytes")
# messages that name the problem: the top-hat's least variance, a --param without finite taps,
# a --param whose taps alone exceed the automatic grid
ics_cli_test(NAME cli_iterate_tophat_min_var RC 2 ARGS "iterate|--kernel|tophat|--var|0.1|--mean|0.5|--steps|4"
  OUT "^$" ERR "is below 0.25 = f\\(1 - f\\), the least variance of an exact top-hat with mean 0.5")
ics_cli_test(NAME cli_iterate_param_tiny RC 2 ARGS "iterate|--kernel|gauss|--param|1e-300|--var|1|--steps|1"
  OUT "^$" ERR "--param 1e-300 gives no finite taps")
ics_cli_test(NAME cli_iterate_param_huge RC 2 ARGS "iterate|--kernel|stochastic-dirac|--param|1e300|--var|1|--steps|1"
  OUT "^$" ERR "the kernel's taps reach [0-9.e+]+ px \\(--param 1[.0-9]*e\\+300")
ics_cli_test(NAME cli_kernel_table_tophat_min_var RC 2 ARGS "kernel-table|--var|0.1|--mean|0.5"
  OUT "^$" ERR "is below 0.25 = f\\(1 - f\\), the least variance of an exact top-hat")
ics_cli_test(NAME cli_kernel_table_tiny_var RC 0 ARGS "kernel-table|--var|1e-300"
  OUT "\ntophat,0,1e-300,")
# --compensate integer: zero variance, mean 0.3 px: 10 steps shift by round(3.0) = 3 whole pixels
# and the edge stays hard (0 at x = 2.5, 1 at x = 3.5; nothing in between)
ics_cli_test(NAME cli_iterate_integer_shift RC 0 ARGS "iterate|--kernel|dirac|--var|0|--mean|0.3|--steps|10|--width|8|--compensate|integer"
  OUT "^steps,x,value,gauss_cdf\n10,-3\\.5,0,${num}\n10,-2\\.5,0,${num}\n10,-1\\.5,0,${num}\n10,-0\\.5,0,${num}\n10,0\\.5,0,${num}\n10,1\\.5,0,${num}\n10,2\\.5,0,${num}\n10,3\\.5,1,${num}\n$")
# seeds: one strict parser (decimal digits, 0..2^64 - 1, overflow checked) in all four commands
ics_cli_test(NAME cli_iterate_seed_overflow RC 2 ARGS "iterate|--kernel|stochastic-dirac|--var|1|--steps|1|--seed|18446744073709551616"
  OUT "^$" ERR "--seed: expected a non-negative integer in 0..18446744073709551615")
ics_cli_test(NAME cli_iterate_seed_exponent RC 2 ARGS "iterate|--kernel|stochastic-dirac|--var|1|--steps|1|--seed|1e23"
  OUT "^$" ERR "--seed: expected a non-negative integer in 0..18446744073709551615")
ics_cli_test(NAME cli_iterate_seed_max RC 0 ARGS "iterate|--kernel|stochastic-dirac|--var|1|--steps|1|--width|4|--seed|18446744073709551615"
  OUT "^steps,x,value,gauss_cdf\n")
ics_cli_test(NAME cli_kernel_table_seed_overflow RC 2 ARGS "kernel-table|--seed|18446744073709551616"
  OUT "^$" ERR "--seed: expected a non-negative integer in 0..18446744073709551615")
