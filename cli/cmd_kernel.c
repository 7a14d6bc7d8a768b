/* cmd_kernel.c — `icshadow kernel ellipse --varx X --vary Y [--angle DEG] [--samples N]
 * [--offset U]`: the N-sample elliptical kernel of a light (Patel et al. 2013, Sec. 3.4) as JSON
 * on stdout, numbers as %.17g. Bad input gives a message naming the problem on stderr and exit
 * status 2; nothing is written to stdout then. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

/* JSON never shows a negative zero: every printed number goes through nz (x + 0.0 is +0 for
 * x = -0 and x itself otherwise). The taps already have no -0 (ellipse.c); -0 options
 * (--varx -0, --angle -0, --offset -0) are echoed as 0. */
static double nz(double x) { return x + 0.0; }

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow kernel ellipse --varx X --vary Y [--angle DEG] [--samples N] "
          "[--offset U]\n"
          "Prints the N-sample elliptical kernel (Patel et al. 2013, Sec. 3.4) of a light with\n"
          "covariance R(angle) diag(X, Y) R(angle)^T as JSON:\n"
          "  {\"kernel\":\"ellipse\",\"varx\":X,\"vary\":Y,\"angle_deg\":DEG,\"a\":..,\"b\":..,"
          "\"t\":..,\n"
          "   \"samples\":N,\"offset\":U,\"taps\":[[x,y],...]}\n"
          "The taps are N points equidistant in arc length on the ellipse with radii a, b (rotated\n"
          "by DEG counter-clockwise), the first at arc fraction U of the perimeter, counted\n"
          "counter-clockwise from the end of the major axis: (a, 0) if X >= Y, else (0, b). So at\n"
          "U = 0 a line light's 2 taps are its ends: (+-sqrt(3X), 0) for Y = 0, (0, +-sqrt(3Y)) for\n"
          "X = 0. Averaged over a uniform U in [0, 1) they have exactly the target covariance.\n"
          "t is the unit-ellipse parameter (b/a = t/(1 - t)). A point light (X = Y = 0) has one\n"
          "tap at the origin, and \"samples\" is then 1.\n\n"
          "options:\n"
          "  --varx X     variance along the light's own x axis, finite and >= 0 (required)\n"
          "  --vary Y     variance along its y axis, finite and >= 0 (required)\n"
          "  --angle DEG  rotation of the x axis, degrees counter-clockwise (default 0)\n"
          "  --samples N  number of taps, 1..%d (default 2)\n"
          "  --offset U   arc-length fraction of the first tap, finite; reduced mod 1 (default 0)\n"
          "Exit status: 0 ok, 2 bad input (message on stderr).\n",
          ICS_ELLIPSE_MAX_SAMPLES);
}

static const char CMD[] = "kernel";

int cmd_kernel(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  if (argc < 2) {
    cli_error(CMD, "missing kernel name (only 'ellipse' is available)");
    help(stderr);
    return 2;
  }
  if (strcmp(argv[1], "ellipse") != 0)
    return cli_error(CMD, "unknown kernel '%s' (only 'ellipse' is available)", argv[1]);
  double varx = NAN, vary = NAN, angle = 0, offset = 0; /* NaN: not given (refused as a value) */
  int samples = 2;
  const cli_option opts[] = {
      {"--varx", .kind = CLI_VARIANCE, .dest = &varx},
      {"--vary", .kind = CLI_VARIANCE, .dest = &vary},
      {"--angle", .kind = CLI_FINITE, .dest = &angle},
      {"--samples", .kind = CLI_INT, .dest = &samples, .lo = 1, .hi = ICS_ELLIPSE_MAX_SAMPLES},
      {"--offset", .kind = CLI_FINITE, .dest = &offset},
  };
  int rc = cli_parse_options(CMD, argc, argv, 2, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (isnan(varx) || isnan(vary))
    return cli_error(CMD, "%s is required", isnan(varx) ? "--varx" : "--vary");

  double *xy = malloc(2 * (size_t)samples * sizeof *xy);
  if (!xy) return cli_failure(CMD, "out of memory");
  ics_ellipse_shape shape;
  ics_status st = ics_ellipse_kernel(varx, vary, angle, samples, offset, &shape, xy);
  if (st != ICS_OK) { /* not reachable after the checks above; reported all the same */
    free(xy);
    return cli_error(CMD, "%s", ics_status_str(st));
  }
  printf("{\"kernel\":\"ellipse\",\"varx\":%.17g,\"vary\":%.17g,\"angle_deg\":%.17g,"
         "\"a\":%.17g,\"b\":%.17g,\"t\":%.17g,\"samples\":%d,\"offset\":%.17g,\"taps\":[",
         nz(varx), nz(vary), nz(angle), nz(shape.a), nz(shape.b), nz(shape.t), shape.nsamples,
         nz(offset));
  for (int j = 0; j < shape.nsamples; j++)
    printf("%s[%.17g,%.17g]", j ? "," : "", nz(xy[2 * j]), nz(xy[2 * j + 1]));
  printf("]}\n");
  free(xy);
  return cli_stdout_failed(CMD);
}
