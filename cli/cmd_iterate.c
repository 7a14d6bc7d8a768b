/* cmd_iterate.c — `icshadow iterate --kernel K --var V --steps N[,N2,...] [options]`: the 1D
 * profile of a Heaviside edge after N steps of iterative convolution with kernel member K
 * (Patel et al. 2013, Eq. 5 and Fig. 3), computed by the library's engine (icshadow/conv.h),
 * as CSV: steps,x,value,gauss_cdf.
 *
 * Grid: pixel i has centre x_i = i - W/2 + 1/2 (W even), so the edge x = 0 lies half-way between
 * two pixels; r_0(x_i) = H(x_i) = 1 for x_i > 0, else 0. After n steps the nodal values are the
 * cdf of the applied integer-tap distribution S_n at x_i: r_n(x_i) = P(S_n < x_i).
 * gauss_cdf is the Gaussian cdf with the same moments as what was applied: mean = the sum of
 * the step means, variance = the sum of the taps' own variances plus the variance the linear
 * interpolation added (ics_conv_stats), plus the grid's 1/12 px^2 (the linear interpolation of
 * the nodes is the cdf of S_n + U(-1/2, 1/2)); the same convention as `icshadow clt`.
 * Bad input: a message naming the problem on stderr, exit status 2, nothing on stdout. */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

#define MAX_MEMBERS 16
#define MAX_STEPS 1000000
#define MAX_WIDTH (1 << 24)
#define OUT_BUDGET 2e9     /* bytes of CSV */
#define OUT_LINE_BYTES 70.0 /* a typical line: steps, x and two %.17g numbers */

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow iterate --kernel K[,K2,...] --var V --steps N[,N2,...] [--mean M]\n"
          "                        [--samples S] [--param P] [--seed SEED] [--width W]\n"
          "                        [--compensate none|nonneg|signed|integer]\n"
          "Iterates a Heaviside edge H(x) (0 for x < 0, 1 for x > 0) with a 1D kernel of the\n"
          "equivalence class (mean M, variance V) in pixels (Patel et al. 2013, Eq. 5, Fig. 3)\n"
          "and prints the profile after each requested step count as CSV:\n"
          "  steps,x,value,gauss_cdf\n"
          "x: pixel centres, the edge half-way between two of them; value: the iterated shadow;\n"
          "gauss_cdf: the Gaussian cdf with the moments actually applied (sum of step means;\n"
          "sum of tap variances + interpolation variance + the grid's 1/12).\n\n"
          "options:\n"
          "  --kernel K   member: dirac, tophat, stochastic-dirac, gauss; a comma list cycles\n"
          "               through the members step by step (Lyapunov mixing), e.g. dirac,tophat\n"
          "  --var V      class variance in px^2, finite and >= 0 (required)\n"
          "  --steps N    step counts to print, strictly increasing, 0..%d: a comma list of\n"
          "               counts and ranges A:B[:STRIDE], e.g. 0:100 or 1,10,100\n"
          "  --mean M     class mean in px, finite (default 0)\n"
          "  --samples S  member sample count (gauss taps), 0 = default (9)\n"
          "  --param P    member parameter, 0 = default: stochastic-dirac jitter half-width\n"
          "               (default 1 px), gauss truncation (default 3), tophat 1 = raw box\n"
          "  --seed SEED  seed of the stochastic members (default 0)\n"
          "  --width W    grid size in pixels, even, 2..%d (default: wide enough for 10\n"
          "               standard deviations plus the kernel reach on each side)\n"
          "  --compensate none (default): off-grid taps are linearly interpolated, adding\n"
          "               variance; nonneg / signed: integer taps with the exact moments;\n"
          "               integer: each step shifts by round((i+1) M) - round(i M) whole\n"
          "               pixels (the fractional mean carried) with the variance exact: a\n"
          "               zero-variance (hard) shadow stays hard, at most 1/2 px off\n"
          "Budgets: runs whose estimated work (steps x width x applied taps, plus the per-step\n"
          "cost of generating and compensating the member's taps) exceeds %.0e tap-updates\n"
          "(under a minute here), or whose output would exceed %.0e bytes (~%.0f bytes a line), are\n"
          "refused with exit 2.\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          MAX_STEPS, MAX_WIDTH, ICS_CONV_WORK_BUDGET, OUT_BUDGET, OUT_LINE_BYTES);
}

static const char CMD[] = "iterate";

static int parse_member(const char *name, ics_kernel_member *m) {
  for (int i = 0; i < ICS_KERNEL_MEMBER_COUNT_; i++) {
    const char *n = ics_kernel_member_name((ics_kernel_member)i);
    if (n && !strcmp(n, name) && (ics_kernel_member_dims((ics_kernel_member)i) & 1)) {
      *m = (ics_kernel_member)i;
      return 0;
    }
  }
  return -1;
}

/* --kernel: a comma list of 1D member names */
typedef struct member_list {
  ics_kernel_member m[MAX_MEMBERS];
  int n;
} member_list;

static int parse_members(const char *cmd, const char *opt, const char *s, void *dest) {
  member_list *list = dest;
  char buf[512];
  if (strlen(s) >= sizeof buf) return cli_error(cmd, "%s: list too long", opt);
  strcpy(buf, s);
  int n = 0;
  char *p = buf;
  for (;;) {
    char *comma = strchr(p, ',');
    if (comma) *comma = '\0';
    if (n == MAX_MEMBERS) return cli_error(cmd, "%s: at most %d members", opt, MAX_MEMBERS);
    if (parse_member(p, &list->m[n]) != 0)
      return cli_error(cmd, "%s: unknown 1D kernel '%s' (dirac, tophat, stochastic-dirac, gauss)",
                       opt, p);
    n++;
    if (!comma) break;
    p = comma + 1;
  }
  list->n = n;
  return 0;
}

/* --steps: a comma list of step counts and ranges A:B[:S] (A, A + S, ..., up to B), strictly
 * increasing; v is allocated (a repeated --steps replaces the list) */
typedef struct step_list {
  int *v, n;
} step_list;

static int parse_steps(const char *cmd, const char *opt, const char *s, void *dest) {
  step_list *list = dest;
  free(list->v);
  list->v = NULL;
  char *buf = strdup(s);
  int cap = 16, n = 0;
  int *v = malloc(sizeof *v * (size_t)cap);
  if (!buf || !v) {
    free(buf);
    free(v);
    return cli_error(cmd, "out of memory");
  }
  char *p = buf;
  int rc = 0;
  for (;;) {
    char *comma = strchr(p, ',');
    if (comma) *comma = '\0';
    int a, b, stride = 1;
    char *c1 = strchr(p, ':'), *c2 = NULL;
    if (c1) {
      *c1 = '\0';
      c2 = strchr(c1 + 1, ':');
      if (c2) *c2 = '\0';
    }
    if (cli_parse_int(p, 0, MAX_STEPS, &a) != 0 ||
        (c1 && cli_parse_int(c1 + 1, 0, MAX_STEPS, &b) != 0) ||
        (c2 && cli_parse_int(c2 + 1, 1, MAX_STEPS, &stride) != 0)) {
      rc = cli_error(cmd, "%s: expected integers in 0..%d or ranges A:B[:STRIDE], got '%s'", opt,
                     MAX_STEPS, s);
      break;
    }
    if (!c1) b = a;
    if (b < a) {
      rc = cli_error(cmd, "%s: empty range %d:%d", opt, a, b);
      break;
    }
    for (long k = a; k <= b && !rc; k += stride) {
      if (n > 0 && k <= v[n - 1]) {
        rc = cli_error(cmd, "%s: step counts must be strictly increasing (%ld after %d)", opt, k,
                       v[n - 1]);
        break;
      }
      if (n == cap) {
        cap *= 2;
        int *nv = realloc(v, sizeof *v * (size_t)cap);
        if (!nv) {
          rc = cli_error(cmd, "out of memory");
          break;
        }
        v = nv;
      }
      v[n++] = (int)k;
    }
    if (rc || !comma) break;
    p = comma + 1;
  }
  free(buf);
  if (rc) {
    free(v);
    return rc;
  }
  list->v = v;
  list->n = n;
  return 0;
}

static int parse_param(const char *cmd, const char *opt, const char *s, void *dest) {
  if (cli_option_double(cmd, opt, s, 0, dest) != 0) return 2;
  if (*(double *)dest < 0) return cli_error(cmd, "%s: must be >= 0, got '%s'", opt, s);
  return 0;
}

static int parse_width(const char *cmd, const char *opt, const char *s, void *dest) {
  int *w = dest;
  if (cli_parse_int(s, 2, MAX_WIDTH, w) != 0 || *w % 2)
    return cli_error(cmd, "%s: expected an even integer in 2..%d, got '%s'", opt, MAX_WIDTH, s);
  return 0;
}

static int parse_compensate(const char *cmd, const char *opt, const char *s, void *dest) {
  if (cli_parse_comp(s, 1, dest) != 0)
    return cli_error(cmd, "%s: expected none, nonneg or signed (or integer), got '%s'", opt, s);
  return 0;
}

/* the command; *step_opt holds the allocated step list (freed by the caller) */
static int iterate_main(int argc, char **argv, step_list *step_opt) {
  member_list kernel = {.n = 0};
  int samples = 0, width = 0;
  double var = NAN, mean = 0, param = 0; /* var NaN: not given (refused as a value) */
  uint64_t seed = 0;
  ics_comp_mode comp = ICS_COMP_NONE;
  const cli_option opts[] = {
      {"--kernel", .kind = CLI_CALL, .dest = &kernel, .parse = parse_members},
      {"--var", .kind = CLI_VARIANCE, .dest = &var},
      {"--steps", .kind = CLI_CALL, .dest = step_opt, .parse = parse_steps},
      {"--mean", .kind = CLI_FINITE, .dest = &mean},
      {"--samples", .kind = CLI_INT, .dest = &samples, .lo = 0, .hi = ICS_KERNEL_MAX_TAPS},
      {"--param", .kind = CLI_CALL, .dest = &param, .parse = parse_param},
      {"--seed", .kind = CLI_SEED, .dest = &seed},
      {"--width", .kind = CLI_CALL, .dest = &width, .parse = parse_width},
      {"--compensate", .kind = CLI_CALL, .dest = &comp, .parse = parse_compensate},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (!kernel.n || isnan(var) || !step_opt->v)
    return cli_error(CMD, "%s is required",
                     !kernel.n ? "--kernel" : isnan(var) ? "--var" : "--steps");
  const ics_kernel_member *members = kernel.m;
  const int nmembers = kernel.n, nsnap = step_opt->n, *steps = step_opt->v;

  ics_kernel1d ks[MAX_MEMBERS];
  for (int j = 0; j < nmembers; j++) {
    ics_status st = ics_kernel1d_init(&ks[j], members[j], mean, var);
    ks[j].nsamples = samples;
    ks[j].param = param;
    ks[j].seed = seed;
    if (st == ICS_OK && ics_kernel1d_max_taps(&ks[j]) <= 0) st = ICS_ERR_RANGE;
    if (st != ICS_OK)
      return cli_error(CMD, "kernel %s with mean %.17g, variance %.17g, samples %d, param %.17g: "
                       "%s", ics_kernel_member_name(members[j]), mean, var, samples, param,
                       ics_status_str(st));
  }
  ics_schedule1d sched = {ks, nmembers};
  int cap = ics_schedule1d_max_taps(&sched);
  ics_tap1d *taps = cap > 0 ? malloc(sizeof *taps * (size_t)cap) : NULL;
  if (!taps)
    return cap > 0 ? cli_failure(CMD, "out of memory") : cli_error(CMD, "invalid kernel schedule");
  /* the first step's taps validate the member parameters (e.g. an impossible exact top-hat) */
  int nt = 0;
  ics_status st = ics_schedule1d_taps(&sched, 0, taps, cap, &nt);
  int has_tophat = 0;
  for (int j = 0; j < nmembers; j++) has_tophat |= members[j] == ICS_KERNEL_TOPHAT;
  double fm = mean - floor(mean);
  if (st == ICS_ERR_RANGE && has_tophat && param == 0 && var < fm * (1 - fm)) {
    cli_error(CMD, "kernel taps: argument out of range: --var %.17g is below %.17g = f(1 - f), the "
              "least variance of an exact top-hat with mean %.17g (f = frac(mean) = %.17g): give a "
              "larger --var or --param 1 (raw box)", var, fm * (1 - fm), mean, fm);
    free(taps);
    return 2;
  }
  if (st == ICS_ERR_RANGE && param > 0) {
    cli_error(CMD, "kernel taps: --param %.17g gives no finite taps for variance %.17g (argument "
              "out of range; give a moderate --param, or the default 0)", param, var);
    free(taps);
    return 2;
  }
  if (st != ICS_OK) {
    cli_error(CMD, "kernel taps: %s (variance %.17g too small for this member and mean?)",
              ics_status_str(st), var);
    free(taps);
    return 2;
  }
  double reach = 0; /* largest |tap| of step 0, plus the stochastic jitter */
  for (int j = 0; j < nt; j++) reach = fmax(reach, fabs(taps[j].x));
  reach += (param > 0 ? param : 1.0) + 2.0;
  free(taps);

  int nmax = steps[nsnap - 1];
  if (width == 0) {
    double sd = sqrt((double)nmax * var + 1.0 / 12.0);
    double half = fabs((double)nmax * mean) + 10.0 * sd + reach + 8.0;
    if (half > MAX_WIDTH / 2 - 1) {
      if (!(reach <= 0.5 * half))
        cli_error(CMD, "the kernel's taps reach %.3g px (--param %.17g, variance %.17g): the "
                  "automatic grid would exceed %d pixels (give a smaller --param, or the default "
                  "0)", reach, param, var, MAX_WIDTH);
      else
        cli_error(CMD, "the automatic grid would exceed %d pixels (give a smaller --steps or "
                  "--var)", MAX_WIDTH);
      return 2;
    }
    width = 2 * (int)ceil(half);
  }

  /* budgets: work (tap-updates, icshadow/shadow1d.h) and output size, before anything runs */
  double nd = fmin(2.0 * cap + 3, ceil(2 * reach) + 4); /* applied integer taps per step */
  double work = (double)nmax * ((double)width * nd + (double)ICS_CONV_WORK_COMP_PASSES * cap);
  if (work > ICS_CONV_WORK_BUDGET)
    return cli_error(CMD, "estimated work %.3g tap-updates (%d steps on %d pixels) exceeds the "
                     "budget of %.0e (give smaller --steps, --width, --var or --samples)", work,
                     nmax, width, ICS_CONV_WORK_BUDGET);
  double bytes = (double)nsnap * width * OUT_LINE_BYTES;
  if (bytes > OUT_BUDGET)
    return cli_error(CMD, "the output would be about %.3g bytes (%d profiles of %d lines) and "
                     "exceed the budget of %.0e bytes (print fewer step counts or give a smaller "
                     "--width)", bytes, nsnap, width, OUT_BUDGET);

  size_t n = (size_t)width;
  double *buf = malloc(sizeof *buf * n);
  if (!buf) return cli_failure(CMD, "out of memory");
  for (size_t i = 0; i < n; i++) buf[i] = ((double)i - width / 2 + 0.5) > 0 ? 1.0 : 0.0;

  ics_conv_opts conv = {0};
  conv.boundary = ICS_BOUNDARY_CLAMP;
  conv.compensate = comp;
  double applied_var = 0, applied_mean = 0;
  int done = 0;
  printf("steps,x,value,gauss_cdf\n");
  for (int s = 0; s < nsnap; s++) {
    ics_conv_stats stats;
    st = ics_conv1d_run(buf, n, &sched, (uint64_t)done, steps[s] - done, &conv, &stats);
    if (st != ICS_OK) {
      free(buf);
      return cli_failure(CMD, "convolution failed: %s", ics_status_str(st));
    }
    if (steps[s] > done) applied_var += stats.kernel_var[0] + stats.interp_var[0];
    for (int k = done; k < steps[s]; k++) applied_mean += mean;
    done = steps[s];
    double sd = sqrt(applied_var + 1.0 / 12.0);
    for (size_t i = 0; i < n; i++) {
      double x = (double)i - width / 2 + 0.5;
      printf("%d,%.17g,%.17g,%.17g\n", steps[s], x, buf[i], ics_normal_cdf((x - applied_mean) / sd));
    }
  }
  free(buf);
  return cli_stdout_failed(CMD);
}

int cmd_iterate(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  step_list steps = {NULL, 0};
  int rc = iterate_main(argc, argv, &steps);
  free(steps.v);
  return rc;
}
