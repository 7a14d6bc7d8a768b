/* cmd_kernel_table.c — `icshadow kernel-table [--var V] [--mean M] [--iterations N] ...`:
 * Patel et al. 2013, Table I measured: for each 1D member of the kernel equivalence class
 * (mean M, variance V), the taps' measured mean and variance (averaged over iterations for the
 * stochastic members, with their range), the tap extent (width), the tap count, the integer taps
 * the engine applies after linear-interpolation splitting, the variance that splitting adds per
 * step, and the measured engine time per pixel and step. CSV on stdout, %.17g numbers.
 * --dims 2: the same per axis for the 2D members of Fig. 11 (elliptical, Poisson disk,
 * Gaussian grid) of a covariance class.
 * Bad input: a message naming the problem on stderr, exit status 2, nothing on stdout. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

#define MAX_ITER 10000000
#define TIMING_LEN 65536

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow kernel-table [--var V] [--mean M] [--iterations N] [--seed SEED]\n"
          "                             [--no-timing] [--dims 2 [--vary V2] [--angle DEG]]\n"
          "Table I of Patel et al. 2013, measured on the library's kernel members of one\n"
          "equivalence class, as CSV with one row per member.\n\n"
          "--dims 1 (default): the 1D members of the class (mean M, variance V):\n"
          "  member,class_mean,class_var,iterations,mean,var,var_min,var_max,width_min,\n"
          "  width_max,taps,applied_taps,interp_var,ns_per_px_step\n"
          "members: dirac, tophat (box width solved so the interpolated variance is exact),\n"
          "tophat-raw (box of width sqrt(12 V), not in the class), stochastic-dirac, gauss.\n"
          "mean, var: the taps' measured moments (mean over N iterations for stochastic members,\n"
          "1 iteration otherwise); var_min/var_max their range; width: largest minus smallest tap\n"
          "position (min/max over iterations); taps: the member's tap count (samples);\n"
          "applied_taps: integer taps after splitting each off-grid tap for linear interpolation\n"
          "(largest over iterations); interp_var: the variance that splitting adds per step\n"
          "(mean over iterations); ns_per_px_step: measured time of one engine step per pixel on\n"
          "a %d-pixel line (nan with --no-timing).\n\n"
          "--dims 2: the 2D members of Fig. 11 (ellipse-2, ellipse-3, poisson-8, poisson-16,\n"
          "gauss-5x5, gauss-19x19) for the class mean (M, 0), covariance R(DEG) diag(V, V2)\n"
          "R(DEG)^T:\n"
          "  member,class_mean_x,class_mean_y,class_cxx,class_cxy,class_cyy,iterations,mean_x,\n"
          "  mean_y,cxx,cxy,cyy,cxx_min,cxx_max,width_x_max,width_y_max,taps,applied_taps,\n"
          "  interp_var_x,interp_var_y,ns_per_px_step\n"
          "(the same measurements per axis; bilinear splitting; timing on a %dx%d image).\n\n"
          "options:\n"
          "  --var V         class variance in px^2 (2D: along the rotated x axis), finite and\n"
          "                  > 0 (default 30.25: sigma = 5.5, the Dirac width 11 of Fig. 3)\n"
          "  --mean M        class mean in px, finite (default 0)\n"
          "  --iterations N  iterations sampled for stochastic members, 1..%d (default 10000)\n"
          "  --seed SEED     seed of the stochastic members (default 0)\n"
          "  --no-timing     skip the timing runs (ns_per_px_step = nan)\n"
          "  --dims D        1 (default) or 2\n"
          "  --vary V2       2D: variance along the rotated y axis, > 0 (default V)\n"
          "  --angle DEG     2D: rotation of the x axis, degrees counter-clockwise (default 0)\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          TIMING_LEN, 256, 256, MAX_ITER);
}

static const char CMD[] = "kernel-table";

typedef struct row {
  const char *label;
  ics_kernel_member member;
  double param;
} row;

/* The fastest of repeated runs of `steps` engine steps (3 .. 50 runs, until 50 ms in all; run r
 * starts at step r * steps): 0 and *best in seconds, or -1 when a run fails. */
static int best_seconds(ics_status (*run)(void *ctx, uint64_t first, int steps), void *ctx,
                        int steps, double *best) {
  double t_total = 0;
  *best = INFINITY;
  for (int rep = 0; rep < 50 && (rep < 3 || t_total < 0.05); rep++) {
    double t0 = cli_now_s();
    ics_status st = run(ctx, (uint64_t)rep * steps, steps);
    double t = cli_now_s() - t0;
    if (st != ICS_OK) return -1;
    t_total += t;
    if (t < *best) *best = t;
  }
  return 0;
}

typedef struct run1d_ctx {
  double *buf;
  ics_schedule1d s;
  ics_conv_opts opts;
} run1d_ctx;

static ics_status run1d(void *ctx, uint64_t first, int steps) {
  run1d_ctx *c = ctx;
  return ics_conv1d_run(c->buf, TIMING_LEN, &c->s, first, steps, &c->opts, NULL);
}

/* seconds per pixel and step of the engine, median-free but repeated until >= 50 ms */
static int time_member(const ics_kernel1d *k, double *ns) {
  double *buf = malloc(sizeof *buf * TIMING_LEN);
  if (!buf) return -1;
  for (size_t i = 0; i < TIMING_LEN; i++) buf[i] = i >= TIMING_LEN / 2 ? 1.0 : 0.0;
  run1d_ctx c = {buf, {k, 1}, {0}};
  int steps = 8;
  double best;
  int rc = best_seconds(run1d, &c, steps, &best);
  free(buf);
  if (rc) return -1;
  *ns = 1e9 * best / ((double)TIMING_LEN * steps);
  return 0;
}

/* the 1D table (Table I) */
static int table1d(double var, double mean, int iterations, uint64_t seed, int timing) {
  static const row rows[] = {
      {"dirac", ICS_KERNEL_DIRAC, 0},
      {"tophat", ICS_KERNEL_TOPHAT, 0},
      {"tophat-raw", ICS_KERNEL_TOPHAT, 1},
      {"stochastic-dirac", ICS_KERNEL_STOCH_DIRAC, 0},
      {"gauss", ICS_KERNEL_GAUSS, 0},
  };
  enum { NROWS = sizeof rows / sizeof rows[0] };
  ics_kernel1d ks[NROWS];
  int cap = 0;
  for (int r = 0; r < NROWS; r++) {
    ics_status st = ics_kernel1d_init(&ks[r], rows[r].member, mean, var);
    ks[r].param = rows[r].param;
    ks[r].seed = seed;
    int mt = st == ICS_OK ? ics_kernel1d_max_taps(&ks[r]) : 0;
    double fm = mean - floor(mean);
    if (rows[r].member == ICS_KERNEL_TOPHAT && rows[r].param == 0 && var < fm * (1 - fm))
      return cli_error(CMD, "--var %.17g is below %.17g = f(1 - f), the least variance of an exact "
                       "top-hat with mean %.17g (f = frac(mean) = %.17g): give a larger --var", var,
                       fm * (1 - fm), mean, fm);
    if (st != ICS_OK || mt <= 0)
      return cli_error(CMD, "%s with mean %.17g, variance %.17g: %s", rows[r].label, mean, var,
                       ics_status_str(st != ICS_OK ? st : ICS_ERR_RANGE));
    if (mt > cap) cap = mt;
  }
  ics_tap1d *taps = malloc(sizeof *taps * (size_t)cap);
  ics_tap1d *itaps = malloc(sizeof *itaps * (2 * (size_t)cap + 3));
  char *text = NULL; /* the whole table, printed only when every row succeeded */
  size_t text_len = 0;
  FILE *mem = open_memstream(&text, &text_len);
  if (!taps || !itaps || !mem) {
    cli_failure(CMD, "out of memory");
    free(taps);
    free(itaps);
    if (mem) fclose(mem);
    free(text);
    return 1;
  }
  fprintf(mem, "member,class_mean,class_var,iterations,mean,var,var_min,var_max,width_min,"
               "width_max,taps,applied_taps,interp_var,ns_per_px_step\n");
  int status = 0;
  for (int r = 0; r < NROWS && !status; r++) {
    const ics_kernel1d *k = &ks[r];
    int iters = ics_kernel_member_stochastic(k->member) ? iterations : 1;
    double smean = 0, svar = 0, sinterp = 0, vmin = INFINITY, vmax = -INFINITY;
    double wmin = INFINITY, wmax = -INFINITY;
    int ntap_max = 0, napplied_max = 0;
    for (int it = 0; it < iters; it++) {
      int nt = 0, ni = 0;
      ics_status st = ics_kernel1d_taps(k, (uint64_t)it, taps, cap, &nt);
      if (st == ICS_OK) st = ics_taps1d_discretize(taps, nt, itaps, 2 * cap + 3, &ni);
      if (st != ICS_OK) {
        cli_error(CMD, "%s with mean %.17g, variance %.17g: %s", rows[r].label, mean, var,
                  ics_status_str(st));
        status = st == ICS_ERR_NOMEM ? 1 : 2;
        break;
      }
      double w, m, v, lo = INFINITY, hi = -INFINITY;
      ics_taps1d_moments(taps, nt, &w, &m, &v);
      for (int j = 0; j < nt; j++) {
        lo = fmin(lo, taps[j].x);
        hi = fmax(hi, taps[j].x);
      }
      smean += m;
      svar += v;
      sinterp += ics_taps1d_interp_var(taps, nt);
      vmin = fmin(vmin, v);
      vmax = fmax(vmax, v);
      wmin = fmin(wmin, hi - lo);
      wmax = fmax(wmax, hi - lo);
      if (nt > ntap_max) ntap_max = nt;
      if (ni > napplied_max) napplied_max = ni;
    }
    if (status) break;
    double ns = NAN;
    if (timing && time_member(k, &ns) != 0) {
      cli_failure(CMD, "%s: timing run failed", rows[r].label);
      status = 1;
      break;
    }
    fprintf(mem, "%s,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g,%.4g\n",
            rows[r].label, mean, var, iters, smean / iters, svar / iters, vmin, vmax, wmin, wmax,
            ntap_max, napplied_max, sinterp / iters, ns);
  }
  fclose(mem);
  free(taps);
  free(itaps);
  if (!status) fputs(text, stdout);
  free(text);
  if (status) return status;
  return cli_stdout_failed(CMD);
}

/* the 2D members (Patel Sec. 3.4, the kernels of Fig. 11), class (mean (M, 0), covariance
 * R(angle) diag(varx, vary) R(angle)^T) */
typedef struct row2d {
  const char *label;
  ics_kernel_member member;
  int nsamples;
} row2d;

#define TIMING_SIDE 256

typedef struct run2d_ctx {
  float *buf;
  ics_schedule2d s;
  ics_conv_opts opts;
} run2d_ctx;

static ics_status run2d(void *ctx, uint64_t first, int steps) {
  run2d_ctx *c = ctx;
  return ics_conv2d_run(c->buf, TIMING_SIDE, TIMING_SIDE, &c->s, first, steps, &c->opts, NULL);
}

static int time_member2d(const ics_kernel2d *k, double *ns) {
  size_t n = (size_t)TIMING_SIDE * TIMING_SIDE;
  float *buf = malloc(sizeof *buf * n);
  if (!buf) return -1;
  for (size_t i = 0; i < n; i++) buf[i] = (i % TIMING_SIDE) >= TIMING_SIDE / 2 ? 1.0f : 0.0f;
  run2d_ctx c = {buf, {k, 1}, {0}};
  int steps = 4;
  double best;
  int rc = best_seconds(run2d, &c, steps, &best);
  free(buf);
  if (rc) return -1;
  *ns = 1e9 * best / ((double)n * steps);
  return 0;
}

static int table2d(double varx, double vary, double angle, double mean, int iterations,
                   uint64_t seed, int timing) {
  static const row2d rows[] = {
      {"ellipse-2", ICS_KERNEL_ELLIPSE, 2},  {"ellipse-3", ICS_KERNEL_ELLIPSE, 3},
      {"poisson-8", ICS_KERNEL_POISSON, 8},  {"poisson-16", ICS_KERNEL_POISSON, 16},
      {"gauss-5x5", ICS_KERNEL_GAUSS, 5},    {"gauss-19x19", ICS_KERNEL_GAUSS, 19},
  };
  enum { NROWS = sizeof rows / sizeof rows[0] };
  ics_class2d cls;
  ics_status st = ics_class2d_init_axes(&cls, mean, 0, varx, vary, angle);
  if (st != ICS_OK)
    return cli_error(CMD, "class (varx %.17g, vary %.17g, angle %.17g): %s", varx, vary, angle,
                     ics_status_str(st));
  ics_kernel2d ks[NROWS];
  int cap = 0;
  for (int r = 0; r < NROWS; r++) {
    st = ics_kernel2d_init(&ks[r], rows[r].member, &cls);
    ks[r].nsamples = rows[r].nsamples;
    ks[r].seed = seed;
    int mt = st == ICS_OK ? ics_kernel2d_max_taps(&ks[r]) : 0;
    if (st != ICS_OK || mt <= 0)
      return cli_error(CMD, "%s: %s", rows[r].label,
                       ics_status_str(st != ICS_OK ? st : ICS_ERR_RANGE));
    if (mt > cap) cap = mt;
  }
  ics_tap2d *taps = malloc(sizeof *taps * (size_t)cap);
  ics_tap2d *itaps = malloc(sizeof *itaps * (4 * (size_t)cap + 9));
  char *text = NULL;
  size_t text_len = 0;
  FILE *mem = open_memstream(&text, &text_len);
  if (!taps || !itaps || !mem) {
    cli_failure(CMD, "out of memory");
    free(taps);
    free(itaps);
    if (mem) fclose(mem);
    free(text);
    return 1;
  }
  fprintf(mem, "member,class_mean_x,class_mean_y,class_cxx,class_cxy,class_cyy,iterations,mean_x,"
               "mean_y,cxx,cxy,cyy,cxx_min,cxx_max,width_x_max,width_y_max,taps,applied_taps,"
               "interp_var_x,interp_var_y,ns_per_px_step\n");
  int status = 0;
  for (int r = 0; r < NROWS && !status; r++) {
    const ics_kernel2d *k = &ks[r];
    int iters = ics_kernel_member_stochastic(k->member) ? iterations : 1;
    double sm[2] = {0, 0}, sc[3] = {0, 0, 0}, si[2] = {0, 0};
    double cmin = INFINITY, cmax = -INFINITY, wx = 0, wy = 0;
    int ntap_max = 0, napplied_max = 0;
    for (int it = 0; it < iters; it++) {
      int nt = 0, ni = 0;
      st = ics_kernel2d_taps(k, (uint64_t)it, taps, cap, &nt);
      if (st == ICS_OK) st = ics_taps2d_discretize(taps, nt, itaps, 4 * cap + 9, &ni);
      if (st != ICS_OK) {
        cli_error(CMD, "%s: %s", rows[r].label, ics_status_str(st));
        status = st == ICS_ERR_NOMEM ? 1 : 2;
        break;
      }
      double w, m[2], c[3], iv[2];
      double lox = INFINITY, hix = -INFINITY, loy = INFINITY, hiy = -INFINITY;
      ics_taps2d_moments(taps, nt, &w, m, c);
      ics_taps2d_interp_var(taps, nt, iv);
      for (int j = 0; j < nt; j++) {
        lox = fmin(lox, taps[j].x), hix = fmax(hix, taps[j].x);
        loy = fmin(loy, taps[j].y), hiy = fmax(hiy, taps[j].y);
      }
      for (int q = 0; q < 2; q++) sm[q] += m[q], si[q] += iv[q];
      for (int q = 0; q < 3; q++) sc[q] += c[q];
      cmin = fmin(cmin, c[0]);
      cmax = fmax(cmax, c[0]);
      wx = fmax(wx, hix - lox);
      wy = fmax(wy, hiy - loy);
      if (nt > ntap_max) ntap_max = nt;
      if (ni > napplied_max) napplied_max = ni;
    }
    if (status) break;
    double ns = NAN;
    if (timing && time_member2d(k, &ns) != 0) {
      cli_failure(CMD, "%s: timing run failed", rows[r].label);
      status = 1;
      break;
    }
    fprintf(mem,
            "%s,%.17g,%.17g,%.17g,%.17g,%.17g,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,"
            "%.17g,%d,%d,%.17g,%.17g,%.4g\n",
            rows[r].label, cls.mean[0], cls.mean[1], cls.cxx, cls.cxy, cls.cyy, iters,
            sm[0] / iters, sm[1] / iters, sc[0] / iters, sc[1] / iters, sc[2] / iters, cmin, cmax,
            wx, wy, ntap_max, napplied_max, si[0] / iters, si[1] / iters, ns);
  }
  fclose(mem);
  free(taps);
  free(itaps);
  if (!status) fputs(text, stdout);
  free(text);
  if (status) return status;
  return cli_stdout_failed(CMD);
}

/* --var, --vary: a class variance, finite and > 0 */
static int parse_class_var(const char *cmd, const char *opt, const char *s, void *dest) {
  if (cli_option_double(cmd, opt, s, 0, dest) != 0) return 2;
  if (*(double *)dest <= 0)
    return cli_error(cmd, "%s: the class variance must be > 0, got '%s'", opt, s);
  return 0;
}

/* --dims: "1" or "2" exactly */
static int parse_dims(const char *cmd, const char *opt, const char *s, void *dest) {
  if (strcmp(s, "1") && strcmp(s, "2"))
    return cli_error(cmd, "%s: expected 1 or 2, got '%s'", opt, s);
  *(int *)dest = s[0] - '0';
  return 0;
}

int cmd_kernel_table(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  double var = 30.25, mean = 0, vary = NAN, angle = 0; /* vary NaN: not given (then V) */
  int iterations = 10000, no_timing = 0, dims = 1;
  uint64_t seed = 0;
  const cli_option opts[] = {
      {"--var", .kind = CLI_CALL, .dest = &var, .parse = parse_class_var},
      {"--mean", .kind = CLI_FINITE, .dest = &mean},
      {"--iterations", .kind = CLI_INT, .dest = &iterations, .lo = 1, .hi = MAX_ITER},
      {"--seed", .kind = CLI_SEED, .dest = &seed},
      {"--dims", .kind = CLI_CALL, .dest = &dims, .parse = parse_dims},
      {"--vary", .kind = CLI_CALL, .dest = &vary, .parse = parse_class_var},
      {"--angle", .kind = CLI_FINITE, .dest = &angle},
      {"--no-timing", .kind = CLI_FLAG, .dest = &no_timing},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  int timing = !no_timing;
  if (dims == 1 && (!isnan(vary) || angle != 0))
    return cli_error(CMD, "--vary and --angle need --dims 2");
  if (dims == 2) return table2d(var, isnan(vary) ? var : vary, angle, mean, iterations, seed, timing);
  return table1d(var, mean, iterations, seed, timing);
}
