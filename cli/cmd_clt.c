/* cmd_clt.c — `icshadow clt --kernel K --var V --steps N1,N2,...`: CLT convergence of the
 * actually iterated kappa^{*n} * H (Patel et al. 2013, Eq. 5-6) against the Gaussian cdf with
 * the same moments, as CSV: steps, sup error, discretisation estimate, cost, run time.
 * With --cov VX,VY,ANGLE the kernel is a 2D member (ellipse, poisson, gauss) and the occluder a
 * half-plane (--edge-angle) or a quadrant (--corner): ics_clt2d_measure (icshadow/clt2d.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

#define MAX_STEPS_LIST 64

static const char CMD[] = "clt";

/* progress on stderr (a terminal, or --progress): the steps iterated, at most 5 times a second */
typedef struct {
  cli_progress p;
  double last;
} clt_progress;

static void on_progress(void *ctx, long done, long total) {
  clt_progress *c = ctx;
  double now = cli_now_s();
  if (done < total && now - c->last < 0.2) return;
  c->last = now;
  cli_progress_say(&c->p, "%ld/%ld steps (%.0f%%)%s", done, total, 100.0 * done / total,
                   done < total ? "" : ", measuring");
}

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow clt --kernel K --var V --steps N1,N2,... [--mean M] [--samples N]\n"
          "                    [--seed U] [--comp nonneg|signed|none] [--no-refine] [--rate]\n"
          "                    [--progress]\n"
          "       icshadow clt --kernel K2 --cov VX,VY,ANGLE --steps N1,N2,... [--mean MX,MY]\n"
          "                    [--edge-angle DEG | --corner] [--samples N] [--seed U]\n"
          "                    [--offsets random|fixed|golden] [--offset U]\n"
          "                    [--comp nonneg|signed|none] [--no-refine] [--rate] [--progress]\n"
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
          "  --progress   the steps iterated on stderr even when it is not a terminal (on a\n"
          "               terminal it is always shown; with the 2x finer run 1D counts both runs)\n"
          "\n2D (--cov): the kernel K2 is a 2D member of the class with mean (MX, MY) (default 0,0)\n"
          "and covariance R(ANGLE) diag(VX, VY) R(ANGLE)^T in pixels (VX, VY >= 0, not both 0;\n"
          "ANGLE in degrees ccw from +x); the occluder image (exact pixel area coverage) is\n"
          "  --edge-angle DEG  the half-plane u.x > 0, u = (cos DEG, sin DEG) (default 0), limit\n"
          "                    Phi((u.x - n u.mu) / sqrt(n u'Sigma u + 1/12)), or\n"
          "  --corner          the quadrant x > 0, y > 0, limit the bivariate normal cdf of\n"
          "                    N(n mu, n Sigma + I/12),\n"
          "and the CSV is\n"
          "  steps,sup_error,sup_error_realized,disc_error,taps_x_steps,seconds\n"
          "sup_error: max over the nodes x with |x - n mu|_inf <= 4.5 sd_n or |x - m_n|_inf <=\n"
          "4.5 sdr_n of |r_n - limit|; sup_error_realized: the same with the limit N(m_n, C_n +\n"
          "I/12), m_n, C_n the summed moments of the integer taps actually applied (stochastic\n"
          "members, fixed odd-N or rank-one ellipses), sdr_n^2 = lambda_max(C_n) + 1/12; the image\n"
          "covers both paths; seconds: CPU time of the iteration only.\n"
          "  --kernel K2  ellipse | poisson | gauss (2D forms of kernel.h)\n"
          "  --samples N  ellipse 1..4096 (default 2), poisson 3..64 (default 8), gauss N x N\n"
          "               (default 5)\n"
          "  --offsets O  ellipse only: random (default: offset ~ U[0,1) per step from the seed,\n"
          "               the kernel member), fixed (the same taps every step, at --offset U),\n"
          "               golden (--offset U + step x 0.618...: rotated by the golden ratio)\n"
          "  --offset U   start offset in [0, 1) for fixed / golden (default 0)\n"
          "  --seed U     poisson and random-offset ellipse only (gauss and fixed / golden\n"
          "               offsets are deterministic: --seed is refused there)\n"
          "  steps up to %d; the base image must hold at most %.0f pixels (it spans both paths\n"
          "  +- 10.5 sd at the last step).\n\n"
          "A point whose disc_error >= sup_error / 10 is not resolved by the grid: a warning\n"
          "names it on stderr (it is still printed) and --rate leaves it out.\n"
          "Work budget: runs whose estimated work (steps x grid nodes x applied taps, plus the\n"
          "compensation's passes over the member's taps; x5 with the 2x finer run; 2D: plus the\n"
          "limits at the window's nodes) exceeds %.0e tap-updates (under a minute here) are refused\n"
          "with exit 2.\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          MAX_STEPS_LIST, ICS_CLT2D_MAX_STEPS, ICS_CLT2D_MAX_PIXELS, ICS_CONV_WORK_BUDGET);
}

/* --rate on stderr: the fitted exponent over the kept (grid-resolved) points, with a warning
 * first when the grid was not checked (refine 0). */
static void print_rate(int refine, const char *what, const ics_clt_point *kept, int nkept,
                       int nsteps) {
  if (!refine)
    cli_warning(CMD, "--no-refine: the grid is not checked; the rate may be a discretisation "
                "artefact");
  if (nkept < 2)
    fprintf(stderr, "rate exponent%s: nan (fewer than 2 resolved points)\n", what);
  else
    fprintf(stderr, "rate exponent%s: %.4g (%d of %d points)\n", what,
            ics_clt_rate(kept, nkept, 1), nkept, nsteps);
}

static int parse_steps(const char *s, int *steps, int *n, int maxv) {
  *n = 0;
  const char *p = s;
  for (;;) {
    const char *q = strchr(p, ',');
    size_t len = q ? (size_t)(q - p) : strlen(p);
    char buf[32];
    int v;
    if (len == 0 || len >= sizeof buf) {
      cli_error(CMD, "--steps: empty or too long entry at position %d of '%s'", (int)(p - s) + 1,
                s);
      return -1;
    }
    memcpy(buf, p, len);
    buf[len] = 0;
    if (cli_parse_int(buf, 1, maxv, &v) != 0) {
      cli_error(CMD, "--steps: expected an integer in 1..%d at position %d of '%s'", maxv,
                (int)(p - s) + 1, s);
      return -1;
    }
    if (*n && v <= steps[*n - 1]) {
      cli_error(CMD, "--steps: not strictly increasing at position %d of '%s'", (int)(p - s) + 1,
                s);
      return -1;
    }
    if (*n == MAX_STEPS_LIST) {
      cli_error(CMD, "--steps: more than %d entries", MAX_STEPS_LIST);
      return -1;
    }
    steps[(*n)++] = v;
    if (!q) break;
    p = q + 1;
  }
  return 0;
}

/* the 2D path (--cov): ics_clt2d_measure */
static int clt2d(const char *kname, const char *cov_s, const char *mean_s, const char *steps_s,
                 const char *samples_s, const char *edge_s, int corner, const char *offsets_s,
                 const char *offset_s, uint64_t seed, int seed_given, const char *comp,
                 int refine, int rate, clt_progress *prog) {
  double cv[3], mv[2] = {0, 0}, edge = 0, offset = 0;
  int steps[MAX_STEPS_LIST], nsteps = 0, samples = 0;
  if (cli_parse_numbers(CMD, "--cov", cov_s, cov_s, NULL, 3, cv) != 0) return 2;
  if (cv[0] < 0 || cv[1] < 0 || !(cv[0] + cv[1] > 0))
    return cli_error(CMD, "--cov: variances VX, VY must be >= 0 and not both 0, got '%s'", cov_s);
  if (mean_s && cli_parse_numbers(CMD, "--mean", mean_s, mean_s, NULL, 2, mv) != 0) return 2;
  if (edge_s && cli_option_double(CMD, "--edge-angle", edge_s, 0, &edge) != 0) return 2;
  if (edge_s && corner) return cli_error(CMD, "give either --edge-angle or --corner, not both");
  if (!kname || !steps_s) return cli_error(CMD, "%s is required", !kname ? "--kernel" : "--steps");
  if (parse_steps(steps_s, steps, &nsteps, ICS_CLT2D_MAX_STEPS) != 0) return 2;
  ics_kernel_member member;
  if (!strcmp(kname, "ellipse"))
    member = ICS_KERNEL_ELLIPSE;
  else if (!strcmp(kname, "poisson"))
    member = ICS_KERNEL_POISSON;
  else if (!strcmp(kname, "gauss"))
    member = ICS_KERNEL_GAUSS;
  else
    return cli_error(CMD, "--kernel: unknown 2D kernel '%s' (ellipse, poisson, gauss)", kname);
  if (samples_s) {
    int lo = member == ICS_KERNEL_POISSON ? 3 : member == ICS_KERNEL_GAUSS ? 2 : 1;
    int hi = member == ICS_KERNEL_POISSON ? 64 : member == ICS_KERNEL_GAUSS ? 256 : 4096;
    if (cli_parse_int(samples_s, lo, hi, &samples) != 0)
      return cli_error(CMD, "--samples: expected an integer in %d..%d for %s, got '%s'", lo, hi,
                       kname, samples_s);
  }
  int offsets = 0; /* 0 random, 1 fixed, 2 golden */
  if (offsets_s) {
    if (member != ICS_KERNEL_ELLIPSE)
      return cli_error(CMD, "--offsets applies to the ellipse kernel only");
    if (!strcmp(offsets_s, "random"))
      offsets = 0;
    else if (!strcmp(offsets_s, "fixed"))
      offsets = 1;
    else if (!strcmp(offsets_s, "golden"))
      offsets = 2;
    else
      return cli_error(CMD, "--offsets: unknown schedule '%s' (random, fixed, golden)", offsets_s);
  }
  if (offset_s) {
    if (offsets == 0) return cli_error(CMD, "--offset needs --offsets fixed or golden");
    if (cli_option_double(CMD, "--offset", offset_s, 0, &offset) != 0) return 2;
    if (offset < 0 || offset >= 1)
      return cli_error(CMD, "--offset: must be in [0, 1), got '%s'", offset_s);
  }
  if (seed_given && (member == ICS_KERNEL_GAUSS || offsets))
    return cli_error(CMD, "--seed: the %s is deterministic (the seed applies to poisson and to "
                     "ellipse with --offsets random)",
                     member == ICS_KERNEL_GAUSS ? "gauss kernel"
                     : offsets == 1             ? "ellipse with --offsets fixed"
                                                : "ellipse with --offsets golden");
  ics_comp_mode cm;
  if (cli_parse_comp(comp, 0, &cm) != 0)
    return cli_error(CMD, "--comp: unknown mode '%s' (nonneg, signed, none)", comp);
  ics_class2d cls;
  ics_status st = ics_class2d_init_axes(&cls, mv[0], mv[1], cv[0], cv[1], cv[2]);
  if (st != ICS_OK) return cli_error(CMD, "--cov '%s': %s", cov_s, ics_status_str(st));
  ics_kernel2d k;
  ics_clt2d_ellipse el = {{mv[0], mv[1]}, cv[0], cv[1], cv[2], samples ? samples : 2, offset,
                          offsets == 2 ? ICS_CLT2D_GOLDEN : 0};
  ics_clt2d_gen gen;
  void *ctx;
  st = ics_kernel2d_init(&k, member, &cls);
  k.nsamples = samples;
  k.seed = seed;
  if (member == ICS_KERNEL_ELLIPSE && offsets) {
    gen = ics_clt2d_ellipse_gen;
    ctx = &el;
  } else {
    gen = ics_clt2d_member_gen;
    ctx = &k;
  }
  ics_clt2d_setup su;
  ics_clt2d_setup_init(&su);
  su.occluder = corner ? ICS_CLT2D_CORNER : ICS_CLT2D_EDGE;
  su.edge_angle_deg = edge;
  su.mean[0] = cls.mean[0], su.mean[1] = cls.mean[1];
  su.cov[0] = cls.cxx, su.cov[1] = cls.cxy, su.cov[2] = cls.cyy;
  su.comp = cm;
  su.refine = refine;
  double pixels = 0, work = 0;
  if (st == ICS_OK) st = ics_clt2d_cost(gen, ctx, &su, steps, nsteps, &pixels, &work);
  if (st == ICS_ERR_SIZE)
    return cli_error(CMD, "the image for %d steps of this class would exceed %.0f pixels (give "
                     "smaller --steps, --cov or --mean)", steps[nsteps - 1], ICS_CLT2D_MAX_PIXELS);
  if (st != ICS_OK) return cli_error(CMD, "kernel %s: %s", kname, ics_status_str(st));
  if (work > ICS_CONV_WORK_BUDGET)
    return cli_error(CMD, "estimated work %.3g tap-updates (%.0f pixels, %d steps%s) exceeds the "
                     "budget of %.0e (give smaller --steps, --cov or --samples%s)", work, pixels,
                     steps[nsteps - 1], refine ? ", x5 for the 2x finer run" : "",
                     ICS_CONV_WORK_BUDGET, refine ? ", or --no-refine" : "");
  if (cm == ICS_COMP_NONNEG) { /* can non-negative integer taps reach the step's covariance? */
    static ics_tap2d tg[ICS_KERNEL_MAX_TAPS], td[4 * ICS_KERNEL_MAX_TAPS + 9];
    int nt = 0, nd = 0;
    double res[3] = {0, 0, 0};
    if (gen(ctx, 0, 1.0, tg, ICS_KERNEL_MAX_TAPS, &nt) == ICS_OK &&
        ics_taps2d_compensate(tg, nt, cm, td, 4 * ICS_KERNEL_MAX_TAPS + 9, &nd, res) == ICS_OK &&
        fabs(res[0]) + fabs(res[1]) + fabs(res[2]) > 1e-9 * (cls.cxx + cls.cyy))
      cli_warning(CMD, "the integer taps of step 0 miss the taps' own covariance by (%.3g, %.3g, "
                  "%.3g) px^2 (rank-deficient or too narrow taps): compare sup_error_realized",
                  res[0], res[1], res[2]);
  }
  ics_clt_point pts[MAX_STEPS_LIST];
  st = ics_clt2d_measure_progress(gen, ctx, &su, steps, nsteps, pts, on_progress, prog);
  cli_progress_done(&prog->p);
  if (st != ICS_OK) return cli_status_error(CMD, st, "%s", ics_status_str(st));
  printf("steps,sup_error,sup_error_realized,disc_error,taps_x_steps,seconds\n");
  for (int i = 0; i < nsteps; i++)
    printf("%d,%.17g,%.17g,%.17g,%.17g,%.17g\n", pts[i].steps, pts[i].sup_err,
           pts[i].sup_err_realized, pts[i].disc_err, pts[i].cost, pts[i].seconds);
  ics_clt_point kept[MAX_STEPS_LIST], kept_r[MAX_STEPS_LIST];
  int nkept = 0, nkept_r = 0;
  for (int i = 0; i < nsteps; i++) {
    if (refine && !(pts[i].disc_err < 0.1 * pts[i].sup_err))
      cli_warning(CMD, "n = %d: disc_error %.3g >= sup_error / 10 (%.3g): the grid does not "
                  "resolve this error%s", pts[i].steps, pts[i].disc_err, 0.1 * pts[i].sup_err,
                  rate ? "; left out of the rate" : "");
    else
      kept[nkept++] = pts[i];
    if (!refine || pts[i].disc_err < 0.1 * pts[i].sup_err_realized) {
      kept_r[nkept_r] = pts[i];
      kept_r[nkept_r++].sup_err = pts[i].sup_err_realized;
    }
  }
  if (rate) {
    print_rate(refine, "", kept, nkept, nsteps);
    print_rate(1, " (realised moments)", kept_r, nkept_r, nsteps);
  }
  return cli_stdout_failed(CMD);
}

int cmd_clt(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *kname = NULL, *comp = "nonneg";
  double var = NAN, mean = 0;
  uint64_t seed = 0;
  int seed_given = 0;
  int samples = 0, no_refine = 0, rate = 0, nsteps = 0, corner = 0, progress = 0;
  int steps[MAX_STEPS_LIST];
  /* kept as text: their meaning depends on 1D (--var) or 2D (--cov), decided below */
  const char *steps_s = NULL, *mean_s = NULL, *cov_s = NULL, *edge_s = NULL, *offsets_s = NULL,
             *offset_s = NULL, *var_s = NULL, *samples_s = NULL;
  const cli_option opts[] = {
      {"--kernel", .kind = CLI_STRING, .dest = &kname},
      {"--var", .kind = CLI_STRING, .dest = &var_s},
      {"--steps", .kind = CLI_STRING, .dest = &steps_s},
      {"--mean", .kind = CLI_STRING, .dest = &mean_s},
      {"--samples", .kind = CLI_STRING, .dest = &samples_s},
      {"--seed", .kind = CLI_SEED, .dest = &seed, .given = &seed_given},
      {"--comp", .kind = CLI_STRING, .dest = &comp},
      {"--cov", .kind = CLI_STRING, .dest = &cov_s},
      {"--edge-angle", .kind = CLI_STRING, .dest = &edge_s},
      {"--offsets", .kind = CLI_STRING, .dest = &offsets_s},
      {"--offset", .kind = CLI_STRING, .dest = &offset_s},
      {"--no-refine", .kind = CLI_FLAG, .dest = &no_refine},
      {"--rate", .kind = CLI_FLAG, .dest = &rate},
      {"--corner", .kind = CLI_FLAG, .dest = &corner},
      {"--progress", .kind = CLI_FLAG, .dest = &progress},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  clt_progress prog = {{0}, 0};
  cli_progress_init(&prog.p, "icshadow clt", progress);
  int refine = !no_refine;
  if (cov_s) { /* 2D: --var and the 1D-only kernels do not apply */
    if (var_s)
      return cli_error(CMD, "give either --var (1D kernel) or --cov (2D kernel), not both");
    return clt2d(kname, cov_s, mean_s, steps_s, samples_s, edge_s, corner, offsets_s, offset_s,
                 seed, seed_given, comp, refine, rate, &prog);
  }
  {
    const char *only2d = edge_s ? "--edge-angle" : corner ? "--corner" : offsets_s ? "--offsets"
                         : offset_s ? "--offset" : NULL;
    if (only2d)
      return cli_error(CMD, "%s applies to 2D kernels only (give --cov VX,VY,ANGLE)", only2d);
  }
  if (var_s) {
    if (cli_option_double(CMD, "--var", var_s, 0, &var) != 0) return 2;
    if (!(var > 0))
      return cli_error(CMD, "--var: %s variance %s (must be > 0)", var < 0 ? "negative" : "zero",
                       var_s);
  }
  if (mean_s && cli_option_double(CMD, "--mean", mean_s, 0, &mean) != 0) return 2;
  if (steps_s && parse_steps(steps_s, steps, &nsteps, 1000000) != 0) return 2;
  if (samples_s && cli_parse_int(samples_s, 0, 4096, &samples) != 0)
    return cli_error(CMD, "--samples: expected an integer in 0..4096, got '%s'", samples_s);
  if (!kname || isnan(var) || !steps_s)
    return cli_error(CMD, "%s is required", !kname ? "--kernel" : isnan(var) ? "--var" : "--steps");
  ics_comp_mode cm;
  if (cli_parse_comp(comp, 0, &cm) != 0)
    return cli_error(CMD, "--comp: unknown mode '%s' (nonneg, signed, none)", comp);
  ics_kernel1d k;
  ics_tap1d skew[ICS_CLT1D_SKEW_TAPS];
  ics_clt1d_fixed fixed = {skew, ICS_CLT1D_SKEW_TAPS};
  ics_clt1d_gen gen;
  void *ctx;
  ics_status st;
  if (!strcmp(kname, "skew")) {
    st = ics_clt1d_skew_taps(mean, var, skew);
    gen = ics_clt1d_fixed_gen;
    ctx = &fixed;
  } else {
    int member = -1;
    for (int m = 0; m < ICS_KERNEL_MEMBER_COUNT_; m++) {
      const char *n = ics_kernel_member_name((ics_kernel_member)m);
      if (n && !strcmp(n, kname) && (ics_kernel_member_dims((ics_kernel_member)m) & 1)) member = m;
    }
    if (member < 0)
      return cli_error(CMD, "--kernel: unknown 1D kernel '%s' (dirac, tophat, stochastic-dirac, "
                       "gauss, skew)", kname);
    st = ics_kernel1d_init(&k, (ics_kernel_member)member, mean, var);
    k.nsamples = samples;
    k.seed = (uint64_t)seed;
    gen = ics_clt1d_member_gen;
    ctx = &k;
  }
  if (st != ICS_OK) return cli_error(CMD, "kernel %s: %s", kname, ics_status_str(st));
  double nodes = 0, work = 0;
  st = ics_clt1d_cost(gen, ctx, mean, var, steps, nsteps, cm, refine, &nodes, &work);
  if (st == ICS_ERR_SIZE)
    return cli_error(CMD, "the grid for %d steps of mean %.17g, variance %.17g would exceed 2^24 "
                     "nodes%s (give smaller --steps, --mean or --var)", steps[nsteps - 1], mean,
                     var, refine ? " with its 2x finer copy" : "");
  if (st == ICS_OK && work > ICS_CONV_WORK_BUDGET)
    return cli_error(CMD, "estimated work %.3g tap-updates (%.0f nodes, %d steps%s) exceeds the "
                     "budget of %.0e (give smaller --steps, --var or --samples%s)", work, nodes,
                     steps[nsteps - 1], refine ? ", x5 for the 2x finer run" : "",
                     ICS_CONV_WORK_BUDGET, refine ? ", or --no-refine" : "");
  if (st == ICS_OK && cm == ICS_COMP_NONNEG) { /* can non-negative integer taps reach the class? */
    ics_tap1d t0[ICS_CLT1D_SKEW_TAPS + 1];
    ics_tap1d *tg = gen == ics_clt1d_fixed_gen ? t0 : malloc(sizeof *tg * ICS_KERNEL_MAX_TAPS);
    ics_tap1d *td = malloc(sizeof *td * (2 * (size_t)ICS_KERNEL_MAX_TAPS + 3));
    int nt = 0, nd = 0;
    double resid = 0;
    if (tg && td && gen(ctx, 0, 1.0, tg, gen == ics_clt1d_fixed_gen ? ICS_CLT1D_SKEW_TAPS + 1
                                                                 : ICS_KERNEL_MAX_TAPS, &nt) == ICS_OK &&
        ics_taps1d_compensate(tg, nt, cm, td, 2 * ICS_KERNEL_MAX_TAPS + 3, &nd, &resid) == ICS_OK &&
        resid > 1e-12 * fmax(var, 1e-300)) {
      double f = mean - floor(mean);
      cli_warning(CMD, "the class (mean %.17g, variance %.17g) cannot be reached by non-negative "
                  "integer taps (least variance f(1 - f) = %.17g): each step adds a compensation "
                  "residual of %.6g px^2, so the error against the class Gaussian will not go to 0 "
                  "(use --comp signed or a larger --var)", mean, var, f * (1 - f), resid);
    }
    if (tg != t0) free(tg);
    free(td);
  }
  ics_clt_point pts[MAX_STEPS_LIST];
  if (st == ICS_OK)
    st = ics_clt1d_measure_progress(gen, ctx, mean, var, steps, nsteps, cm, refine, pts,
                                    on_progress, &prog);
  cli_progress_done(&prog.p);
  if (st == ICS_ERR_RANGE && gen == ics_clt1d_member_gen && k.member == ICS_KERNEL_TOPHAT) {
    double f = mean - floor(mean);
    return cli_error(CMD, "--var %.17g is below %.17g = f(1 - f), the least variance of an exact "
                     "top-hat with mean %.17g (f = frac(mean) = %.17g): give a larger --var", var,
                     f * (1 - f), mean, f);
  }
  if (st != ICS_OK) {
    cli_error(CMD, "%s", ics_status_str(st));
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
      cli_warning(CMD, "n = %d: disc_error %.3g >= sup_error / 10 (%.3g): the grid does not "
                  "resolve this error%s", pts[i].steps, pts[i].disc_err, 0.1 * pts[i].sup_err,
                  rate ? "; left out of the rate" : "");
      continue;
    }
    kept[nkept++] = pts[i];
  }
  if (rate) print_rate(refine, "", kept, nkept, nsteps);
  return cli_stdout_failed(CMD);
}
