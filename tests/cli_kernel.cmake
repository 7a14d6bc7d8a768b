# CLI tests for `icshadow kernel`: --help, good output, and every kind of bad input.
set(num "-?[0-9.e+-]+")
ics_cli_test(NAME cli_kernel_help RC 0 ARGS "kernel|--help" OUT "usage: icshadow kernel ellipse.*--samples")
ics_cli_test(NAME cli_kernel_ellipse_help RC 0 ARGS "kernel|ellipse|--help" OUT "--offset U")
# good output: every field, in order, %.17g numbers, N taps. The expected t, a, b were checked
# independently: mpmath quadrature of the arc-length moments of the ellipse (1 - t, t) at 30
# digits, root-solved for V_y/V_x = 0.25, gives t = 0.29078618627769530, a = 1.5770614503123458,
# b = 0.64661414624033227.
ics_cli_test(NAME cli_kernel_repeated_option RC 2 ARGS "kernel|ellipse|--varx|1|--varx|2|--vary|0.25"
  ERR "--varx given twice: give each option once")
ics_cli_test(NAME cli_kernel_good RC 0 ARGS "kernel|ellipse|--varx|1|--vary|0.25|--angle|30|--samples|3|--offset|0.1"
  OUT "^{\"kernel\":\"ellipse\",\"varx\":1,\"vary\":0.25,\"angle_deg\":30,\"a\":1\\.57706145031234[0-9]*,\"b\":0\\.6466141462403[0-9]*,\"t\":0\\.2907861862776[0-9]*,\"samples\":3,\"offset\":0\\.10000000000000001,\"taps\":\\[\\[${num},${num}\\],\\[${num},${num}\\],\\[${num},${num}\\]\\]}\n$")
# line light: a = sqrt(3 varx) = 3, taps at the segment's ends
ics_cli_test(NAME cli_kernel_line RC 0 ARGS "kernel|ellipse|--varx|3|--vary|0"
  OUT "\"a\":3,\"b\":0,\"t\":0,\"samples\":2,\"offset\":0,\"taps\":\\[\\[3,0\\],\\[-3,0\\]\\]}")
# vertical line light: offset 0 is the end of the MAJOR axis (here y), so the 2 taps are the
# segment's ends (0, +-sqrt(3 vary)); uniform on [-c, c] has variance c^2/3, so vary = 1 gives
# c = sqrt(3) = 1.7320508075688772935... (by hand)
ics_cli_test(NAME cli_kernel_vertical_line RC 0 ARGS "kernel|ellipse|--varx|0|--vary|1"
  OUT "\"a\":0,\"b\":1\\.73205080756887[0-9]*,\"t\":1,\"samples\":2,\"offset\":0,\"taps\":\\[\\[0,1\\.73205080756887[0-9]*\\],\\[0,-1\\.73205080756887[0-9]*\\]\\]}")
# horizontal line light, varx = 1/4: taps (+-sqrt(3 varx), 0) = (+-sqrt(3)/2, 0), sqrt(3)/2 =
# 0.86602540378443864676... (by hand)
ics_cli_test(NAME cli_kernel_horizontal_line RC 0 ARGS "kernel|ellipse|--varx|0.25|--vary|0|--samples|2"
  OUT "\"a\":0\\.8660254037844(38|39)[0-9]*,\"b\":0,\"t\":0,\"samples\":2,\"offset\":0,\"taps\":\\[\\[0\\.8660254037844(38|39)[0-9]*,0\\],\\[-0\\.8660254037844(38|39)[0-9]*,0\\]\\]}")
# negative zeros: -0 options are echoed as 0 and no printed number is -0 (whole line matched)
ics_cli_test(NAME cli_kernel_negative_zero RC 0 ARGS "kernel|ellipse|--varx|-0|--vary|1|--angle|-0|--offset|-0"
  OUT "^{\"kernel\":\"ellipse\",\"varx\":0,\"vary\":1,\"angle_deg\":0,\"a\":0,\"b\":1\\.73205080756887[0-9]*,\"t\":1,\"samples\":2,\"offset\":0,\"taps\":\\[\\[0,1\\.73205080756887[0-9]*\\],\\[0,-1\\.73205080756887[0-9]*\\]\\]}\n$")
ics_cli_test(NAME cli_kernel_negative_zero_vary RC 0 ARGS "kernel|ellipse|--varx|1|--vary|-0.0|--angle|-0|--samples|1|--offset|-0e5"
  OUT "^{\"kernel\":\"ellipse\",\"varx\":1,\"vary\":0,\"angle_deg\":0,\"a\":1\\.73205080756887[0-9]*,\"b\":0,\"t\":0,\"samples\":1,\"offset\":0,\"taps\":\\[\\[1\\.73205080756887[0-9]*,0\\]\\]}\n$")
ics_cli_test(NAME cli_kernel_negative_zero_point RC 0 ARGS "kernel|ellipse|--varx|-0|--vary|-0|--angle|-0"
  OUT "^{\"kernel\":\"ellipse\",\"varx\":0,\"vary\":0,\"angle_deg\":0,\"a\":0,\"b\":0,\"t\":0\\.5,\"samples\":1,\"offset\":0,\"taps\":\\[\\[0,0\\]\\]}\n$")
# point light: one tap at the origin, samples reported as 1
ics_cli_test(NAME cli_kernel_point RC 0 ARGS "kernel|ellipse|--varx|0|--vary|0|--samples|8"
  OUT "\"samples\":1,\"offset\":0,\"taps\":\\[\\[0,0\\]\\]}")
# vary > varx, ratio 1e12: the minor radius stays accurate (a = sqrt(3/2 varx) to 1e-6 rel)
ics_cli_test(NAME cli_kernel_tall RC 0 ARGS "kernel|ellipse|--varx|1e-12|--vary|1|--samples|4"
  OUT "\"a\":1\\.22474[0-9]*e-06,\"b\":1\\.7320[0-9]*,\"t\":0\\.99999929[0-9]*,\"samples\":4")
# bad input: exit 2, a message naming the problem, nothing on stdout
ics_cli_test(NAME cli_kernel_no_kernel RC 2 ARGS "kernel" ERR "missing kernel name")
ics_cli_test(NAME cli_kernel_unknown_kernel RC 2 ARGS "kernel|gauss|--varx|1|--vary|1" ERR "unknown kernel 'gauss'")
ics_cli_test(NAME cli_kernel_not_a_number RC 2 ARGS "kernel|ellipse|--varx|abc|--vary|1" ERR "--varx: not a number: 'abc'")
ics_cli_test(NAME cli_kernel_trailing_junk RC 2 ARGS "kernel|ellipse|--varx|1|--vary|2x" ERR "--vary: not a number: '2x'")
ics_cli_test(NAME cli_kernel_nan RC 2 ARGS "kernel|ellipse|--varx|nan|--vary|1" ERR "--varx: NaN")
ics_cli_test(NAME cli_kernel_negative_variance RC 2 ARGS "kernel|ellipse|--varx|1|--vary|-0.5" ERR "--vary: negative variance")
ics_cli_test(NAME cli_kernel_infinite_variance RC 2 ARGS "kernel|ellipse|--varx|inf|--vary|1" ERR "--varx: must be finite")
ics_cli_test(NAME cli_kernel_samples_zero RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--samples|0" ERR "--samples: expected an integer in 1..4096")
ics_cli_test(NAME cli_kernel_samples_too_many RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--samples|4097" ERR "--samples: expected an integer in 1..4096")
ics_cli_test(NAME cli_kernel_samples_not_int RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--samples|2.5" ERR "--samples: expected an integer")
ics_cli_test(NAME cli_kernel_angle_nan RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--angle|nan" ERR "--angle: NaN")
ics_cli_test(NAME cli_kernel_offset_inf RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--offset|inf" ERR "--offset: must be finite")
ics_cli_test(NAME cli_kernel_missing_vary RC 2 ARGS "kernel|ellipse|--varx|1" ERR "--vary is required")
ics_cli_test(NAME cli_kernel_missing_value RC 2 ARGS "kernel|ellipse|--vary|1|--varx" ERR "--varx: missing value")
ics_cli_test(NAME cli_kernel_unknown_option RC 2 ARGS "kernel|ellipse|--varx|1|--vary|1|--bogus|3" ERR "unknown option '--bogus'")
