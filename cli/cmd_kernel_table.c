/* cmd_kernel_table.c — `icshadow kernel-table [--var V] [--mean M] [--iterations N] ...`:
 * Patel et al. 2013, Table I measured: for each 1D member of the kernel equivalence class
 * (mean M, variance V), the taps' measured mean and variance (averaged over iterations for the
 * stochastic members, with their range), the tap extent (width), the tap count, the integer taps
 * the engine applies after linear-interpolation splitting, the variance that splitting adds per
 * step, and the measured engine time per pixel and step. CSV on stdout, %.17g numbers.
 * Bad input: a message naming the problem on stderr, exit status 2, nothing on stdout. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "commands.h"
#include "icshadow.h"

#define MAX_ITER 10000000
#define TIMING_LEN 65536

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow kernel-table [--var V] [--mean M] [--iterations N] [--seed SEED]\n"
          "                             [--no-timing]\n"
          "Table I of Patel et al. 2013, measured on the library's 1D kernel members of the\n"
          "equivalence class (mean M, variance V), as CSV with one row per member:\n"
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
          "options:\n"
          "  --var V         class variance in px^2, finite and > 0 (default 30.25: sigma = 5.5,\n"
          "                  the Dirac width 11 of the paper's Fig. 3)\n"
          "  --mean M        class mean in px, finite (default 0)\n"
          "  --iterations N  iterations sampled for stochastic members, 1..%d (default 10000)\n"
          "  --seed SEED     seed of the stochastic members (default 0)\n"
          "  --no-timing     skip the timing runs (ns_per_px_step = nan)\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          TIMING_LEN, MAX_ITER);
}

#define ERR(...)                                 \
  do {                                           \
    fprintf(stderr, "icshadow kernel-table: ");  \
    fprintf(stderr, __VA_ARGS__);                \
    fputc('\n', stderr);                         \
  } while (0)

static int get_double(const char *opt, const char *s, double *out) {
  double v;
  if (cli_parse_double(s, &v) != 0) {
    ERR("%s: not a number: '%s'", opt, s);
    return -1;
  }
  if (isnan(v)) {
    ERR("%s: NaN is not allowed", opt);
    return -1;
  }
  if (isinf(v)) {
    ERR("%s: must be finite, got '%s'", opt, s);
    return -1;
  }
  *out = v;
  return 0;
}

static double now_sec(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct row {
  const char *label;
  ics_kernel_member member;
  double param;
} row;

/* seconds per pixel and step of the engine, median-free but repeated until >= 50 ms */
static int time_member(const ics_kernel1d *k, double *ns) {
  double *buf = malloc(sizeof *buf * TIMING_LEN);
  if (!buf) return -1;
  for (size_t i = 0; i < TIMING_LEN; i++) buf[i] = i >= TIMING_LEN / 2 ? 1.0 : 0.0;
  ics_schedule1d s = {k, 1};
  ics_conv_opts opts = ics_conv_opts_default();
  int steps = 8;
  double best = INFINITY;
  double t_total = 0;
  for (int rep = 0; rep < 50 && (rep < 3 || t_total < 0.05); rep++) {
    double t0 = now_sec();
    ics_status st = ics_conv1d_run(buf, TIMING_LEN, &s, (uint64_t)rep * steps, steps, &opts, NULL);
    double t = now_sec() - t0;
    if (st != ICS_OK) {
      free(buf);
      return -1;
    }
    t_total += t;
    if (t < best) best = t;
  }
  free(buf);
  *ns = 1e9 * best / ((double)TIMING_LEN * steps);
  return 0;
}

int cmd_kernel_table(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  double var = 30.25, mean = 0;
  int iterations = 10000, timing = 1;
  unsigned long long seed = 0;
  for (int i = 1; i < argc; i++) {
    const char *opt = argv[i];
    if (!strcmp(opt, "--no-timing")) {
      timing = 0;
      continue;
    }
    int known = !strcmp(opt, "--var") || !strcmp(opt, "--mean") || !strcmp(opt, "--iterations") ||
                !strcmp(opt, "--seed");
    if (!known) {
      ERR("unknown option '%s' (see icshadow kernel-table --help)", opt);
      return 2;
    }
    if (i + 1 >= argc) {
      ERR("%s: missing value", opt);
      return 2;
    }
    const char *val = argv[++i];
    if (!strcmp(opt, "--var")) {
      if (get_double(opt, val, &var) != 0) return 2;
      if (var <= 0) {
        ERR("--var: the class variance must be > 0, got '%s'", val);
        return 2;
      }
    } else if (!strcmp(opt, "--mean")) {
      if (get_double(opt, val, &mean) != 0) return 2;
    } else if (!strcmp(opt, "--iterations")) {
      if (cli_parse_int(val, 1, MAX_ITER, &iterations) != 0) {
        ERR("--iterations: expected an integer in 1..%d, got '%s'", MAX_ITER, val);
        return 2;
      }
    } else {
      char *end;
      if (val[0] == '-' || val[0] == '\0' || (seed = strtoull(val, &end, 10), *end != '\0')) {
        ERR("--seed: expected a non-negative integer, got '%s'", val);
        return 2;
      }
    }
  }

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
    ks[r].seed = (uint64_t)seed;
    int mt = st == ICS_OK ? ics_kernel1d_max_taps(&ks[r]) : 0;
    if (st != ICS_OK || mt <= 0) {
      ERR("%s with mean %.17g, variance %.17g: %s", rows[r].label, mean, var,
          ics_status_str(st != ICS_OK ? st : ICS_ERR_RANGE));
      return 2;
    }
    if (mt > cap) cap = mt;
  }
  ics_tap1d *taps = malloc(sizeof *taps * (size_t)cap);
  ics_tap1d *itaps = malloc(sizeof *itaps * (2 * (size_t)cap + 3));
  char *text = NULL; /* the whole table, printed only when every row succeeded */
  size_t text_len = 0;
  FILE *mem = open_memstream(&text, &text_len);
  if (!taps || !itaps || !mem) {
    ERR("out of memory");
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
        ERR("%s with mean %.17g, variance %.17g: %s", rows[r].label, mean, var,
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
      sinterp += ics_interp_var1d(taps, nt);
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
      ERR("%s: timing run failed", rows[r].label);
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
  return fflush(stdout) != 0 ? 1 : 0;
}
