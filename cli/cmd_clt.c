/* cmd_clt.c — `icshadow clt --kernel K --var V --steps N1,N2,...`: CLT convergence of the
 * actually iterated kappa^{*n} * H (Patel et al. 2013, Eq. 5-6) against the Gaussian cdf with
 * the same moments, as CSV: steps, sup error, discretisation estimate, cost, run time. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

#define MAX_STEPS_LIST 64

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow clt --kernel K --var V --steps N1,N2,... [--mean M] [--samples N]\n"
          "                    [--seed U] [--comp nonneg|signed|none] [--no-refine] [--rate]\n"
          "Iterates an edge H (0 for x < 0, 1 for x > 0) n times with the 1D kernel member K of\n"
          "the class (mean M, variance V) in pixels on a unit grid, and prints CSV:\n"
          "  steps,sup_error,disc_error,taps_x_steps,seconds\n"
          "sup_error = max over the nodes x of |r_n(x) - Phi((x - n M) / sqrt(n V + 1/12))| (the\n"
          "nodes are exactly the cdf of K_n + U(-1/2, 1/2), hence the 1/12); disc_error = max change\n"
          "of that error profile on a grid twice as fine (the same continuous kernel);\n"
          "taps_x_steps = integer taps applied in total (cost); seconds = CPU time so far.\n\n"
          "options:\n"
          "  --kernel K   dirac | tophat | stochastic-dirac | gauss | skew (required). skew: a\n"
          "               discretised exponential (16 taps, skewness 1.286) moved/scaled to the class\n"
          "  --var V      class variance per step in pixels^2, finite and > 0 (required)\n"
          "  --steps L    comma-separated, strictly increasing step counts in 1..1000000 (required;\n"
          "               at most %d)\n"
          "  --mean M     class mean per step in pixels, finite (default 0)\n"
          "  --samples N  the member's sample count (gauss; 0 = default)\n"
          "  --seed U     seed of stochastic members (default 0)\n"
          "  --comp C     interpolation-variance compensation (default nonneg)\n"
          "  --no-refine  skip the 2x finer run (disc_error is then nan)\n"
          "  --rate       print the fitted rate exponent (slope of log error vs log n) on stderr,\n"
          "               over the resolved points only\n"
          "A point whose disc_error >= sup_error / 10 is not resolved by the grid: a warning\n"
          "names it on stderr (it is still printed) and --rate leaves it out.\n"
          "Work budget: runs whose estimated work (steps x grid nodes x applied taps, plus the\n"
          "compensation's passes over the member's taps; x5 with the 2x finer run) exceeds %.0e\n"
          "tap-updates (a few minutes) are refused with exit 2.\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          MAX_STEPS_LIST, ICS_WORK_BUDGET);
}

static int parse_steps(const char *s, int *steps, int *n) {
  *n = 0;
  const char *p = s;
  for (;;) {
    const char *q = strchr(p, ',');
    size_t len = q ? (size_t)(q - p) : strlen(p);
    char buf[32];
    int v;
    if (len == 0 || len >= sizeof buf) {
      fprintf(stderr, "icshadow clt: --steps: empty or too long entry at position %d of '%s'\n",
              (int)(p - s) + 1, s);
      return -1;
    }
    memcpy(buf, p, len);
    buf[len] = 0;
    if (cli_parse_int(buf, 1, 1000000, &v) != 0) {
      fprintf(stderr, "icshadow clt: --steps: expected an integer in 1..1000000 at position %d "
                      "of '%s'\n", (int)(p - s) + 1, s);
      return -1;
    }
    if (*n && v <= steps[*n - 1]) {
      fprintf(stderr, "icshadow clt: --steps: not strictly increasing at position %d of '%s'\n",
              (int)(p - s) + 1, s);
      return -1;
    }
    if (*n == MAX_STEPS_LIST) {
      fprintf(stderr, "icshadow clt: --steps: more than %d entries\n", MAX_STEPS_LIST);
      return -1;
    }
    steps[(*n)++] = v;
    if (!q) break;
    p = q + 1;
  }
  return 0;
}

int cmd_clt(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *kname = NULL, *comp = "nonneg";
  double var = NAN, mean = 0;
  uint64_t seed = 0;
  int samples = 0, refine = 1, rate = 0, nsteps = 0, have_steps = 0;
  int steps[MAX_STEPS_LIST];
  for (int i = 1; i < argc; i++) {
    const char *opt = argv[i];
    if (!strcmp(opt, "--no-refine")) {
      refine = 0;
      continue;
    }
    if (!strcmp(opt, "--rate")) {
      rate = 1;
      continue;
    }
    static const char *known[] = {"--kernel", "--var", "--steps", "--mean",
                                  "--samples", "--seed", "--comp"};
    int ok = 0;
    for (size_t j = 0; j < sizeof known / sizeof *known; j++) ok |= !strcmp(opt, known[j]);
    if (!ok) {
      fprintf(stderr, "icshadow clt: unknown option '%s' (see icshadow clt --help)\n", opt);
      return 2;
    }
    if (i + 1 >= argc) {
      fprintf(stderr, "icshadow clt: %s: missing value\n", opt);
      return 2;
    }
    const char *val = argv[++i];
    int bad = 0;
    if (!strcmp(opt, "--kernel"))
      kname = val;
    else if (!strcmp(opt, "--comp"))
      comp = val;
    else if (!strcmp(opt, "--var")) {
      bad = cli_option_double("clt", opt, val, 0, &var);
      if (!bad && !(var > 0)) {
        fprintf(stderr, "icshadow clt: --var: %s variance %s (must be > 0)\n",
                var < 0 ? "negative" : "zero", val);
        bad = 1;
      }
    } else if (!strcmp(opt, "--mean"))
      bad = cli_option_double("clt", opt, val, 0, &mean);
    else if (!strcmp(opt, "--seed")) {
      if (cli_parse_seed(val, &seed) != 0) {
        fprintf(stderr, "icshadow clt: --seed: expected " CLI_SEED_RANGE ", got '%s'\n", val);
        bad = 1;
      }
    } else if (!strcmp(opt, "--steps")) {
      bad = parse_steps(val, steps, &nsteps);
      have_steps = 1;
    } else if (cli_parse_int(val, 0, 4096, &samples) != 0) {
      fprintf(stderr, "icshadow clt: --samples: expected an integer in 0..4096, got '%s'\n", val);
      bad = 1;
    }
    if (bad) return 2;
  }
  if (!kname || isnan(var) || !have_steps) {
    fprintf(stderr, "icshadow clt: %s is required\n",
            !kname ? "--kernel" : isnan(var) ? "--var" : "--steps");
    return 2;
  }
  ics_comp_mode cm;
  if (!strcmp(comp, "nonneg"))
    cm = ICS_COMP_NONNEG;
  else if (!strcmp(comp, "signed"))
    cm = ICS_COMP_SIGNED;
  else if (!strcmp(comp, "none"))
    cm = ICS_COMP_NONE;
  else {
    fprintf(stderr, "icshadow clt: --comp: unknown mode '%s' (nonneg, signed, none)\n", comp);
    return 2;
  }
  ics_kernel1d k;
  ics_tap1d skew[ICS_CLT_SKEW_TAPS];
  ics_clt_fixed fixed = {skew, ICS_CLT_SKEW_TAPS};
  ics_clt_gen gen;
  void *ctx;
  ics_status st;
  if (!strcmp(kname, "skew")) {
    st = ics_clt_skew_taps(mean, var, skew);
    gen = ics_clt_fixed_gen;
    ctx = &fixed;
  } else {
    int member = -1;
    for (int m = 0; m < ICS_KERNEL_MEMBER_COUNT_; m++) {
      const char *n = ics_kernel_member_name((ics_kernel_member)m);
      if (n && !strcmp(n, kname) && (ics_kernel_member_dims((ics_kernel_member)m) & 1)) member = m;
    }
    if (member < 0) {
      fprintf(stderr, "icshadow clt: --kernel: unknown 1D kernel '%s' (dirac, tophat, "
                      "stochastic-dirac, gauss, skew)\n", kname);
      return 2;
    }
    st = ics_kernel1d_init(&k, (ics_kernel_member)member, mean, var);
    k.nsamples = samples;
    k.seed = (uint64_t)seed;
    gen = ics_clt_member_gen;
    ctx = &k;
  }
  if (st != ICS_OK) {
    fprintf(stderr, "icshadow clt: kernel %s: %s\n", kname, ics_status_str(st));
    return 2;
  }
  double nodes = 0, work = 0;
  st = ics_clt_cost(gen, ctx, mean, var, steps, nsteps, cm, refine, &nodes, &work);
  if (st == ICS_ERR_SIZE) {
    fprintf(stderr, "icshadow clt: the grid for %d steps of mean %.17g, variance %.17g would exceed "
                    "2^24 nodes%s (give smaller --steps, --mean or --var)\n", steps[nsteps - 1],
            mean, var, refine ? " with its 2x finer copy" : "");
    return 2;
  }
  if (st == ICS_OK && work > ICS_WORK_BUDGET) {
    fprintf(stderr, "icshadow clt: estimated work %.3g tap-updates (%.0f nodes, %d steps%s) exceeds "
                    "the budget of %.0e (give smaller --steps, --var or --samples%s)\n", work,
            nodes, steps[nsteps - 1], refine ? ", x5 for the 2x finer run" : "", ICS_WORK_BUDGET,
            refine ? ", or --no-refine" : "");
    return 2;
  }
  if (st == ICS_OK && cm == ICS_COMP_NONNEG) { /* can non-negative integer taps reach the class? */
    ics_tap1d t0[ICS_CLT_SKEW_TAPS + 1];
    ics_tap1d *tg = gen == ics_clt_fixed_gen ? t0 : malloc(sizeof *tg * ICS_KERNEL_MAX_TAPS);
    ics_tap1d *td = malloc(sizeof *td * (2 * (size_t)ICS_KERNEL_MAX_TAPS + 3));
    int nt = 0, nd = 0;
    double resid = 0;
    if (tg && td && gen(ctx, 0, 1.0, tg, gen == ics_clt_fixed_gen ? ICS_CLT_SKEW_TAPS + 1
                                                                 : ICS_KERNEL_MAX_TAPS, &nt) == ICS_OK &&
        ics_taps1d_compensate(tg, nt, cm, td, 2 * ICS_KERNEL_MAX_TAPS + 3, &nd, &resid) == ICS_OK &&
        resid > 1e-12 * fmax(var, 1e-300)) {
      double f = mean - floor(mean);
      fprintf(stderr, "icshadow clt: warning: the class (mean %.17g, variance %.17g) cannot be "
                      "reached by non-negative integer taps (least variance f(1 - f) = %.17g): each "
                      "step adds a compensation residual of %.6g px^2, so the error against the "
                      "class Gaussian will not go to 0 (use --comp signed or a larger --var)\n",
              mean, var, f * (1 - f), resid);
    }
    if (tg != t0) free(tg);
    free(td);
  }
  ics_clt_point pts[MAX_STEPS_LIST];
  if (st == ICS_OK) st = ics_clt_measure(gen, ctx, mean, var, steps, nsteps, cm, refine, pts);
  if (st == ICS_ERR_RANGE && gen == ics_clt_member_gen && k.member == ICS_KERNEL_TOPHAT) {
    double f = mean - floor(mean);
    fprintf(stderr, "icshadow clt: --var %.17g is below %.17g = f(1 - f), the least variance of an "
                    "exact top-hat with mean %.17g (f = frac(mean) = %.17g): give a larger --var\n",
            var, f * (1 - f), mean, f);
    return 2;
  }
  if (st != ICS_OK) {
    fprintf(stderr, "icshadow clt: %s\n", ics_status_str(st));
    return (st == ICS_ERR_NOMEM) ? 1 : 2;
  }
  printf("steps,sup_error,disc_error,taps_x_steps,seconds\n");
  for (int i = 0; i < nsteps; i++)
    printf("%d,%.17g,%.17g,%.17g,%.17g\n", pts[i].steps, pts[i].sup_err, pts[i].disc_err,
           pts[i].cost, pts[i].seconds);
  /* a point is resolved when the grid's own error is below a tenth of the reported one */
  ics_clt_point kept[MAX_STEPS_LIST];
  int nkept = 0;
  for (int i = 0; i < nsteps; i++) {
    if (refine && !(pts[i].disc_err < 0.1 * pts[i].sup_err)) {
      fprintf(stderr, "icshadow clt: warning: n = %d: disc_error %.3g >= sup_error / 10 (%.3g): "
                      "the grid does not resolve this error%s\n", pts[i].steps, pts[i].disc_err,
              0.1 * pts[i].sup_err, rate ? "; left out of the rate" : "");
      continue;
    }
    kept[nkept++] = pts[i];
  }
  if (rate) {
    if (!refine)
      fprintf(stderr, "icshadow clt: warning: --no-refine: the grid is not checked; the rate may "
                      "be a discretisation artefact\n");
    if (nkept < 2)
      fprintf(stderr, "rate exponent: nan (fewer than 2 resolved points)\n");
    else
      fprintf(stderr, "rate exponent: %.4g (%d of %d points)\n", ics_clt_rate(kept, nkept, 1),
              nkept, nsteps);
  }
  return fflush(stdout) != 0 ? 1 : 0;
}
