/* cmd_fit_light.c — `icshadow fit-light ENV.exr --lights K|auto[:KMAX] [--max-angle DEG]
 * [--seed S] [--max-samples N] [--max-iter N] [--sweep] [--progress] -o LIGHTS.json`: fits K Gaussian
 * lights on the virtual light plane to an environment map (ics_lightfit) and writes the lights
 * file (docs/lights_format.md) atomically. stdout: a CSV summary table, one row per fit
 * (k = K, or k = 1..K with --sweep or --lights auto): k, lights fitted, L1, L2, edge-shadow
 * error, seconds, EM iterations, samples, cut-off loss. --lights auto[:KMAX] fits k = 1..KMAX
 * (default 8) and keeps the fewest lights whose L1 is within ICS_LIGHTFIT_AUTO_L1_FLOOR or _RATIO x
 * the best of them (docs/lightfit.md "How many lights"). stderr: the energy report, and progress when stderr is
 * a terminal or --progress is given. */
#include <stdio.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"
#include "lightsfile.h"

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow fit-light ENV.exr --lights K|auto[:KMAX] [--max-angle DEG] [--seed S]\n"
          "                          [--max-samples N] [--max-iter N] [--sweep] [--plane-csv FILE]\n"
          "                          [--progress]\n"
          "                          -o LIGHTS.json\n"
          "Projects the hemisphere behind the viewer of a latitude-longitude OpenEXR map onto the\n"
          "virtual light plane (l = L dw/dA) and fits K anisotropic Gaussians (EM from a greedy start\n"
          "and, on a map with a sky, from starts that give the sky one or two Gaussians).\n"
          "Writes the lights file (JSON: mean, cov, color, weight; docs/lights_format.md) and\n"
          "prints a CSV table on stdout:\n"
          "  k,fitted,l1,l2,edge,seconds,iterations,samples,cutoff_loss\n"
          "l1, l2: relative errors of the fitted density on the plane; edge: sup error of the\n"
          "shadow behind a straight edge at the optimal distance d1 (any d1), worst of 4\n"
          "orientations; cutoff_loss: fraction of the energy behind the viewer beyond DEG.\n\n"
          "options:\n"
          "  --lights K         number of Gaussians, 1..%d (required); auto[:KMAX]: fit 1..KMAX\n"
          "                     (default 8) and keep the fewest whose L1 is within 1%% or 2 x\n"
          "                     the best of them (said on stderr; every fit in the table)\n"
          "  --max-angle DEG    cut-off angle from the view axis, in (0, 90) (default 80)\n"
          "  --seed S           seed of the EM sample selection, 0..2^64-1 (default 1)\n"
          "  --max-samples N    EM on N pixels resampled by energy (0: all; default 32768)\n"
          "  --max-iter N       EM iterations, 1..100000 (default 300)\n"
          "  --sweep            fit k = 1..K and print one row each (the file holds k = K)\n"
          "  --progress         show progress on stderr even when it is not a terminal\n"
          "  --plane-csv FILE   also write the map projected onto the plane: one row per pixel\n"
          "                     behind the viewer: i,j,x,y,r,g,b,kept (density l = L dw/dA;\n"
          "                     kept: the fit uses the pixel: centre within DEG, not a rim pixel)\n"
          "  -o LIGHTS.json     output file (required; - for stdout, then no table)\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (unreadable or invalid map too).\n",
          ICS_LIGHTFIT_MAX_K);
}

static const char CMD[] = "fit-light";

/* --lights: K, or auto (a negative K: -KMAX) */
static int parse_lights(const char *cmd, const char *opt, const char *s, void *dest) {
  int *K = dest;
  if (!strncmp(s, "auto", 4)) {
    int kmax = ICS_LIGHTFIT_AUTO_KMAX;
    if (s[4] == ':' ? cli_parse_int(s + 5, 1, ICS_LIGHTFIT_MAX_K, &kmax) : s[4] != 0)
      return cli_error(cmd, "%s: expected auto or auto:KMAX with KMAX in 1..%d, got '%s'", opt,
                       ICS_LIGHTFIT_MAX_K, s);
    *K = -kmax;
    return 0;
  }
  if (cli_parse_int(s, 1, ICS_LIGHTFIT_MAX_K, K))
    return cli_error(cmd, "%s: expected 1..%d or auto[:KMAX], got '%s'", opt, ICS_LIGHTFIT_MAX_K, s);
  return 0;
}

/* EM progress: every iteration on a terminal, every 25th (and the first) otherwise */
typedef struct em_progress {
  cli_progress p;
  int k;
} em_progress;

static void on_progress(void *ctx, int iter, int max_iter, double ll) {
  em_progress *ep = ctx;
  if (ep->p.tty || iter % 25 == 0 || iter == 1)
    cli_progress_say(&ep->p, "K=%d EM iteration %d/%d, log-likelihood %.9g", ep->k, iter,
                     max_iter, ll);
}

/* the input map, the one positional argument */
static int take_map(const char *cmd, const char *opt, const char *arg, void *dest) {
  (void)opt;
  const char **inp = dest;
  if (*inp) return cli_error(cmd, "more than one input map ('%s', '%s')", *inp, arg);
  *inp = arg;
  return 0;
}

/* --max-angle: degrees in (0, 90) */
static int parse_max_angle(const char *cmd, const char *opt, const char *s, void *dest) {
  double *deg = dest;
  if (cli_parse_double(s, deg) || !(*deg > 0 && *deg < 90))
    return cli_error(cmd, "%s: expected degrees in (0, 90), got '%s'", opt, s);
  return 0;
}

/* the map on the light plane as CSV: i,j,x,y,r,g,b,kept for every pixel behind the viewer */
static void write_plane_csv(FILE *f, const ics_image *env, double max_angle) {
  fprintf(f, "i,j,x,y,r,g,b,kept\n");
  for (int j = 0; j < env->height; j++)
    for (int i = 0; i < env->width; i++) {
      double x, y, rgb[3];
      if (ics_envmap_plane_density(env, i, j, &x, &y, rgb)) continue;
      fprintf(f, "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", i, j, x, y, rgb[0], rgb[1], rgb[2],
              ics_envmap_pixel_kept(env->width, env->height, i, j, max_angle));
    }
}

/* the fits and the outputs once the map is read; env is the caller's */
static int fit_and_write(const ics_image *env, const char *inp, const char *outp,
                         const char *planep, int K, int sweep, ics_lightfit_params *p) {
  static ics_light fits[ICS_LIGHTFIT_MAX_K][ICS_LIGHTFIT_MAX_K]; /* per k: its lights */
  ics_lightfit_report rep[ICS_LIGHTFIT_MAX_K];
  double secs[ICS_LIGHTFIT_MAX_K];
  em_progress *ep = p->progress_ctx;
  int autopick = K < 0;
  if (autopick) K = -K, sweep = 1;
  int k0 = sweep ? 1 : K;
  for (int k = k0; k <= K; k++) {
    p->k = ep->k = k;
    double t0 = cli_now_s();
    ics_status st = ics_lightfit(env, p, fits[k - 1], &rep[k - 1]);
    secs[k - 1] = cli_now_s() - t0;
    if (p->progress) cli_progress_done(&ep->p);
    /* the options are checked above and ics_exr_read refuses bad pixels, so INVALID_ARG can
     * only mean a map without light inside the cut-off */
    if (st == ICS_ERR_INVALID_ARG)
      return cli_error(CMD, "%s: no light behind the viewer within %g degrees of the view axis",
                       inp, p->max_angle_deg);
    if (st == ICS_ERR_SIZE)
      return cli_error(CMD, "%s: a %d x %d map is too small to fit (at least 4 x 2 pixels)", inp,
                       env->width, env->height);
    if (st != ICS_OK)
      return cli_status_error(CMD, st, "%s: fit failed: %s", inp, ics_status_str(st));
  }
  int kc = autopick ? ics_lightfit_auto_choice(rep, K) : K; /* the fit written */
  for (int k = k0; k <= K; k++)
    if (!rep[k - 1].converged && (!autopick || k == kc)) /* auto: only the one kept */
      cli_warning(CMD, "K=%d: EM stopped at --max-iter %d before converging (log-likelihood "
                  "change still above 1e-9): raise --max-iter (e.g. %d), or try other numbers "
                  "of lights (--lights auto)", k, p->max_iter, 4 * p->max_iter);
  if (autopick)
    fprintf(stderr, "fit-light: --lights auto: K = %d, the fewest lights whose L1 (%.3g) is within "
            "max(%g, %g x the best of K = 1..%d)\n", kc, rep[kc - 1].l1, ICS_LIGHTFIT_AUTO_L1_FLOOR,
            ICS_LIGHTFIT_AUTO_L1_RATIO, K);
  const ics_light *lights = fits[kc - 1];
  const ics_lightfit_report *r = &rep[kc - 1];
  double behind = r->energy_kept + r->energy_cutoff;
  fprintf(stderr,
          "fit-light: %s: energy %.6g; in front of the viewer (ignored) %.3g%%; behind: %.6g, of "
          "which %.3g%% beyond %g degrees (lost at the cut-off)\n",
          inp, r->energy_total, r->energy_total > 0 ? 100 * r->energy_front / r->energy_total : 0.0,
          behind, 100 * r->cutoff_loss, p->max_angle_deg);
  if (r->k_fit < kc)
    fprintf(stderr, "fit-light: the map is explained by %d light%s; %d requested\n", r->k_fit,
            r->k_fit == 1 ? "" : "s", kc);

  /* -o first: when it cannot be opened, no plane CSV is written either. The table on stdout,
   * the lights file and the plane CSV are committed together, stdout first: when one cannot be
   * completed (a full disk, a closed stdout), no file is replaced */
  cli_output out, pout, sout;
  cli_output *all[3];
  int n = 0, to_stdout = !strcmp(outp, "-");
  if (cli_output_open(&out, CMD, outp) != 0) return 1;
  if (ics_light_write_json(out.fp, lights, r->k_fit) != 0) {
    cli_output_abort(&out);
    return cli_failure(CMD, "cannot write %s", outp);
  }
  if (planep) {
    if (cli_output_open(&pout, CMD, planep) != 0) {
      cli_output_abort(&out);
      return 1;
    }
    write_plane_csv(pout.fp, env, p->max_angle_deg);
  }
  if (!to_stdout) {
    cli_output_open(&sout, CMD, "-");
    fprintf(sout.fp, "k,fitted,l1,l2,edge,seconds,iterations,samples,cutoff_loss\n");
    for (int k = k0; k <= K; k++) {
      const ics_lightfit_report *q = &rep[k - 1];
      fprintf(sout.fp, "%d,%d,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g\n", k, q->k_fit, q->l1, q->l2,
              q->edge, secs[k - 1], q->iterations, q->samples, q->cutoff_loss);
    }
    all[n++] = &sout;
  }
  all[n++] = &out;
  if (planep) all[n++] = &pout;
  return cli_outputs_commit(all, n) ? 1 : 0;
}

int cmd_fit_light(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *inp = NULL, *outp = NULL, *planep = NULL;
  int K = 0, sweep = 0, force_progress = 0, max_samples = 32768, max_iter = 300;
  double max_angle = 80;
  uint64_t seed = 1;
  const cli_option opts[] = {
      {NULL, .kind = CLI_CALL, .dest = &inp, .parse = take_map},
      {"--lights", .kind = CLI_CALL, .dest = &K, .parse = parse_lights},
      {"--max-angle", .kind = CLI_CALL, .dest = &max_angle, .parse = parse_max_angle},
      {"--seed", .kind = CLI_SEED, .dest = &seed},
      {"--max-samples", .kind = CLI_INT, .dest = &max_samples, .lo = 0, .hi = 1 << 30},
      {"--max-iter", .kind = CLI_INT, .dest = &max_iter, .lo = 1, .hi = 100000},
      {"--sweep", .kind = CLI_FLAG, .dest = &sweep},
      {"--progress", .kind = CLI_FLAG, .dest = &force_progress},
      {"--plane-csv", .kind = CLI_FILE, .dest = &planep},
      {"-o", .kind = CLI_FILE, .dest = &outp},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (!inp) return cli_error(CMD, "missing input map ENV.exr");
  if (!K) return cli_error(CMD, "--lights K is required");
  if (!outp) return cli_error(CMD, "-o LIGHTS.json is required");
  /* the table goes to stdout unless the lights file does */
  const cli_path in = {"input map", inp},
                 outs[] = {{"-o", outp}, {"--plane-csv", planep},
                           {"the summary table", strcmp(outp, "-") ? "-" : NULL}};
  if ((rc = cli_check_outputs(CMD, &in, 1, outs, 3))) return rc;
  ics_image *env = NULL;
  char msg[CLI_MSG_MAX];
  ics_status st = ics_exr_read(inp, &env, msg, sizeof msg);
  if (st != ICS_OK) return cli_status_error(CMD, st, "%s", msg);
  em_progress ep = {.k = 0};
  cli_progress_init(&ep.p, "fit-light", force_progress);
  ics_lightfit_params p;
  ics_lightfit_params_init(&p);
  p.max_angle_deg = max_angle;
  p.seed = seed;
  p.max_samples = max_samples;
  p.max_iter = max_iter;
  p.progress_ctx = &ep;
  if (ep.p.on) p.progress = on_progress;
  rc = fit_and_write(env, inp, outp, planep, K, sweep, &p);
  ics_image_destroy(env);
  return rc;
}
