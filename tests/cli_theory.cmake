# CLI tests for `icshadow isoline` and `icshadow clt`. Expected numbers are derived
# independently: closed-form isolines (box: x = -d (hi - s (hi - lo)); Gaussian: -d mu +
# Phi^-1(s) sqrt(d d1 var) with the published Phi^-1(0.975) = 1.959963984540054), the mixture
# median by a bisection in Python's math.erfc (0.8 N(0, .25) + 0.2 N(2, .25): median
# 0.15928145625928486), and the tophat's Edgeworth error 1.705e-3 at n = 16 (docs/theory.md).
ics_cli_test(NAME cli_isoline_help RC 0 ARGS "isoline|--help" OUT "usage: icshadow isoline --light SPEC")
ics_cli_test(NAME cli_clt_help RC 0 ARGS "clt|--help" OUT "usage: icshadow clt --kernel K")
ics_cli_test(NAME cli_isoline_box RC 0 ARGS "isoline|--light|box:-1,3|--level|0.25|--distance|2|--model|correct"
  OUT "^-4\n$")
ics_cli_test(NAME cli_isoline_gauss_half RC 0 ARGS "isoline|--light|gauss:0.3,2|--level|0.5|--distance|2|--model|correct"
  OUT "^-0\\.(6|59999999999999[0-9]*|60000000000000[0-9]*)\n$")
ics_cli_test(NAME cli_isoline_clt RC 0 ARGS "isoline|--light|gauss:0,1|--level|0.975|--distance|2|--d1|2|--model|clt"
  OUT "^3\\.91992796908010[0-9]*\n$")
# iterated: the 1/2-isoline of a Gaussian light sits at -d mu (A.5 holds here) to 1e-4
ics_cli_test(NAME cli_isoline_iterative RC 0 ARGS "isoline|--light|gauss:0.5,1|--level|0.5|--distance|1|--d1|1|--slab|0.015625|--model|iterative|--kernel|tophat"
  OUT "^-0\\.(5000|4999)[0-9]*\n$")
ics_cli_test(NAME cli_isoline_distance_zero RC 0 ARGS "isoline|--light|gauss:0.5,1|--level|0.3|--distance|0|--d1|1|--slab|0.1|--model|iterative"
  OUT "^0\n$")
# bad input
ics_cli_test(NAME cli_isoline_spec_short RC 2 ARGS "isoline|--light|gauss:1|--level|0.5|--distance|1|--model|correct"
  ERR "--light: expected 2 comma-separated numbers at position 7 of 'gauss:1'")
ics_cli_test(NAME cli_isoline_spec_kind RC 2 ARGS "isoline|--light|cauchy:0,1|--level|0.5|--distance|1|--model|correct"
  ERR "unknown light kind 'cauchy'")
ics_cli_test(NAME cli_isoline_spec_negvar RC 2 ARGS "isoline|--light|gauss:0,-1|--level|0.5|--distance|1|--model|correct"
  ERR "negative variance at position 9")
ics_cli_test(NAME cli_isoline_spec_box RC 2 ARGS "isoline|--light|box:2,1|--level|0.5|--distance|1|--model|correct"
  ERR "box needs LO < HI")
ics_cli_test(NAME cli_isoline_spec_extra RC 2 ARGS "isoline|--light|box:0,1,2|--level|0.5|--distance|1|--model|correct"
  ERR "too many numbers at position 8")
ics_cli_test(NAME cli_isoline_spec_nanval RC 2 ARGS "isoline|--light|gauss:nan,1|--level|0.5|--distance|1|--model|correct"
  ERR "NaN at position 7")
ics_cli_test(NAME cli_isoline_level RC 2 ARGS "isoline|--light|gauss:0,1|--level|1|--distance|1|--model|correct"
  ERR "--level: must be in \\(0, 1\\)")
ics_cli_test(NAME cli_isoline_level_nan RC 2 ARGS "isoline|--light|gauss:0,1|--level|nan|--distance|1|--model|correct"
  ERR "--level: NaN")
ics_cli_test(NAME cli_isoline_distance RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|-1|--model|correct"
  ERR "negative distance")
ics_cli_test(NAME cli_isoline_model RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|1|--model|exact"
  ERR "unknown model 'exact'")
ics_cli_test(NAME cli_isoline_kernel RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|1|--d1|1|--slab|0.1|--model|iterative|--kernel|ellipse"
  ERR "unknown 1D kernel 'ellipse'")
ics_cli_test(NAME cli_isoline_need_d1 RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|1|--model|clt"
  ERR "--d1 is required")
ics_cli_test(NAME cli_isoline_slabs RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|1|--d1|1|--slab|0.3|--model|iterative"
  ERR "integer number of slabs")
ics_cli_test(NAME cli_isoline_unknown_opt RC 2 ARGS "isoline|--lite|gauss:0,1" ERR "unknown option '--lite'")
# clt: CSV header, then the tophat at n = 16 within 3 % of Edgeworth's 1.705e-3
ics_cli_test(NAME cli_clt_tophat RC 0 ARGS "clt|--kernel|tophat|--var|36|--steps|16,64"
  OUT "^steps,sup_error,disc_error,taps_x_steps,seconds\n16,0\\.001(6[6-9]|7[0-5])[0-9]*,[0-9.e-]+,[0-9]+,[0-9.e-]+\n64,")
ics_cli_test(NAME cli_clt_skew RC 0 ARGS "clt|--kernel|skew|--var|36|--steps|4,8|--no-refine" OUT "^steps,sup_error,disc_error,taps_x_steps,seconds\n4,[0-9.e-]+,nan,")
ics_cli_test(NAME cli_clt_var_negative RC 2 ARGS "clt|--kernel|tophat|--var|-1|--steps|4" ERR "--var: negative variance")
ics_cli_test(NAME cli_clt_var_nan RC 2 ARGS "clt|--kernel|tophat|--var|nan|--steps|4" ERR "--var: NaN")
ics_cli_test(NAME cli_clt_kernel RC 2 ARGS "clt|--kernel|poisson|--var|1|--steps|4" ERR "unknown 1D kernel 'poisson'")
ics_cli_test(NAME cli_clt_steps_order RC 2 ARGS "clt|--kernel|dirac|--var|1|--steps|8,4" ERR "not strictly increasing at position 3")
ics_cli_test(NAME cli_clt_steps_bad RC 2 ARGS "clt|--kernel|dirac|--var|1|--steps|4,x" ERR "expected an integer in 1..1000000 at position 3")
ics_cli_test(NAME cli_clt_missing RC 2 ARGS "clt|--kernel|dirac|--steps|4" ERR "--var is required")
# mixture SPECs hold ';' (not passable through ics_cli_test): tests/cli/theory_mix.sh
add_test(NAME cli_isoline_mix COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/theory_mix.sh $<TARGET_FILE:icshadow_cli>)
set_tests_properties(cli_isoline_mix PROPERTIES LABELS fast)
# The 9-tap Gaussian with sigma = 6 is a comb 4.5 px apart that the grid's interpolation smooths:
# its error at n = 16, 32 is below a tenth of the 2x-grid change (docs/figures.md), so clt warns
# about each point on stderr, still prints it, and --rate has no resolved point left.
ics_cli_test(NAME cli_clt_unresolved_warning RC 0 ARGS "clt|--kernel|gauss|--var|36|--steps|16,32|--rate"
  OUT "^steps,sup_error,disc_error,taps_x_steps,seconds\n16,[^\n]*\n32,[^\n]*\n$"
  ERR "warning: n = 16: disc_error [0-9.e-]+ >= sup_error / 10 .*left out of the rate.*warning: n = 32: .*rate exponent: nan \\(fewer than 2 resolved points\\)")
# a resolved run gives the rate over all its points and no warning
ics_cli_test(NAME cli_clt_rate_resolved RC 0 ARGS "clt|--kernel|tophat|--var|36|--steps|16,32,64|--rate"
  ERR "^rate exponent: -(0\\.99|1\\.0)[0-9]* \\(3 of 3 points\\)\n$")
# work budget (1e11 tap-updates, ICS_CONV_WORK_BUDGET): refused before running, exit 2, nothing
# on stdout.
# tophat sigma 6, 1e6 steps: ~1.7e5 nodes x ~23 taps x 1e6 steps = ~4e12 (hours)
ics_cli_test(NAME cli_clt_work_budget RC 2 ARGS "clt|--kernel|tophat|--var|36|--steps|1000000|--no-refine"
  OUT "^$" ERR "estimated work [0-9.e+]+ tap-updates .*exceeds the budget of 1e\\+11")
# 4096 generated taps per step for 1e5 steps (x5 with the finer run)
ics_cli_test(NAME cli_clt_work_budget_samples RC 2 ARGS "clt|--kernel|gauss|--samples|4096|--var|36|--steps|100000"
  OUT "^$" ERR "exceeds the budget of 1e\\+11 .*--no-refine")
# 1e5 slabs with 4096 taps each, twice
ics_cli_test(NAME cli_isoline_work_budget RC 2 ARGS "isoline|--light|gauss:0.3,1|--level|0.3|--distance|1e5|--slab|1|--d1|1|--model|iterative|--kernel|gauss|--samples|4096"
  OUT "^$" ERR "estimated work [0-9.e+]+ tap-updates \\(100000 slabs on [0-9]+ nodes.*exceeds the budget of 1e\\+11")
# a grid over 2^24 nodes is a usage error named as such (was "out of memory", exit 1)
ics_cli_test(NAME cli_clt_grid_size RC 2 ARGS "clt|--kernel|dirac|--var|36|--mean|1e9|--steps|1000"
  OUT "^$" ERR "the grid for 1000 steps of mean 1000000000, variance 36 would exceed 2\\^24 nodes")
# overflow: a box width 2e308, an isoline position -d mu = -1e400 or sqrt(d d1 var) = 1e159
# overflowing in the clt model, NaN from inf - inf: exit 2 with a message, nothing printed
ics_cli_test(NAME cli_isoline_box_overflow RC 2 ARGS "isoline|--light|box:-1e308,1e308|--level|0.3|--distance|1|--model|correct"
  OUT "^$" ERR "the width HI - LO or its variance overflows")
ics_cli_test(NAME cli_isoline_result_overflow RC 2 ARGS "isoline|--light|gauss:1e200,1|--level|0.3|--distance|1e200|--model|correct"
  OUT "^$" ERR "the isoline position is not finite")
ics_cli_test(NAME cli_isoline_clt_overflow RC 2 ARGS "isoline|--light|gauss:0,1e308|--level|0.3|--distance|1|--d1|1e10|--model|clt"
  OUT "^$" ERR "the isoline position is not finite")
ics_cli_test(NAME cli_isoline_clt_nan RC 2 ARGS "isoline|--light|gauss:1,1|--level|0.5|--distance|1e308|--d1|1e308|--model|clt"
  OUT "^$" ERR "the isoline position is not finite")
# exact top-hat below its least variance f(1 - f) (f = frac(0.5): 0.25) is named as such
ics_cli_test(NAME cli_clt_tophat_min_var RC 2 ARGS "clt|--kernel|tophat|--var|0.1|--mean|0.5|--steps|4"
  OUT "^$" ERR "--var 0.10000000000000001 is below 0.25 = f\\(1 - f\\), the least variance of an exact top-hat")
# a tiny variance is legal: the top-hat becomes its W -> 0 limit (one tap at mean 0)
ics_cli_test(NAME cli_clt_tiny_var RC 0 ARGS "clt|--kernel|tophat|--var|1e-300|--steps|4|--no-refine"
  OUT "^steps,sup_error,disc_error,taps_x_steps,seconds\n4,")
# a class below f(1 - f) (Dirac, variance 0.1, mean 0.5: least 0.25) cannot be reached with
# non-negative integer taps: clt warns with the residual 0.25 - 0.1 = 0.15 px^2 per step
ics_cli_test(NAME cli_clt_unreachable RC 0 ARGS "clt|--kernel|dirac|--var|0.1|--mean|0.5|--steps|4,16|--no-refine"
  OUT "^steps,sup_error" ERR "cannot be reached by non-negative integer taps \\(least variance f\\(1 - f\\) = 0.25\\): each step adds a compensation residual of 0.15 px\\^2")
ics_cli_test(NAME cli_clt_seed_exponent RC 2 ARGS "clt|--kernel|stochastic-dirac|--var|1|--steps|4|--seed|1e3"
  OUT "^$" ERR "--seed: expected a non-negative integer in 0..18446744073709551615")
ics_cli_test(NAME cli_isoline_seed_exponent RC 2 ARGS "isoline|--light|gauss:0,1|--level|0.5|--distance|1|--model|correct|--seed|1e3"
  OUT "^$" ERR "--seed: expected a non-negative integer in 0..18446744073709551615")
