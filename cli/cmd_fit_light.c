/* cmd_fit_light.c — `icshadow fit-light ENV.exr --lights K [--max-angle DEG] [--seed S]
 * [--max-samples N] [--max-iter N] [--sweep] [--progress] -o LIGHTS.json`: fits K Gaussian
 * lights on the virtual light plane to an environment map (ics_lightfit) and writes the lights
 * file (docs/lights_format.md) atomically. stdout: a CSV summary table, one row per fit
 * (k = K, or k = 1..K with --sweep): k, lights fitted, L1, L2, edge-shadow error, seconds,
 * EM iterations, samples, cut-off loss. stderr: the energy report, and progress when stderr is
 * a terminal or --progress is given. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "commands.h"
#include "icshadow.h"
#include "lightsfile.h"

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow fit-light ENV.exr --lights K [--max-angle DEG] [--seed S]\n"
          "                          [--max-samples N] [--max-iter N] [--sweep] [--plane-csv FILE]\n"
          "                          [--progress]\n"
          "                          -o LIGHTS.json\n"
          "Projects the hemisphere behind the viewer of a latitude-longitude OpenEXR map onto the\n"
          "virtual light plane (l = L dw/dA) and fits K anisotropic Gaussians (greedy start, EM).\n"
          "Writes the lights file (JSON: mean, cov, color, weight; docs/lights_format.md) and\n"
          "prints a CSV table on stdout:\n"
          "  k,fitted,l1,l2,edge,seconds,iterations,samples,cutoff_loss\n"
          "l1, l2: relative errors of the fitted density on the plane; edge: sup error of the\n"
          "shadow behind a straight edge at the optimal distance d1 (any d1), worst of 4\n"
          "orientations; cutoff_loss: fraction of the energy behind the viewer beyond DEG.\n\n"
          "options:\n"
          "  --lights K         number of Gaussians, 1..%d (required)\n"
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

typedef struct prog {
  int tty, k;
} prog;

static void on_progress(void *ctx, int iter, int max_iter, double ll) {
  prog *p = ctx;
  if (p->tty)
    fprintf(stderr, "\rfit-light: K=%d EM iteration %d/%d, log-likelihood %.9g   ", p->k, iter,
            max_iter, ll);
  else if (iter % 25 == 0 || iter == 1)
    fprintf(stderr, "fit-light: K=%d EM iteration %d/%d, log-likelihood %.9g\n", p->k, iter,
            max_iter, ll);
}

int cmd_fit_light(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *inp = NULL, *outp = NULL, *planep = NULL;
  int K = 0, sweep = 0, force_progress = 0, max_samples = 32768, max_iter = 300;
  double max_angle = 80;
  unsigned long long seed = 1;
  for (int a = 1; a < argc; a++) {
    const char *o = argv[a];
    int needs = !strcmp(o, "--lights") || !strcmp(o, "--max-angle") || !strcmp(o, "--seed") ||
                !strcmp(o, "--max-samples") || !strcmp(o, "--max-iter") || !strcmp(o, "-o") ||
                !strcmp(o, "--plane-csv");
    if (needs && a + 1 >= argc) {
      fprintf(stderr, "icshadow fit-light: %s: missing value\n", o);
      return 2;
    }
    if (!strcmp(o, "--lights")) {
      if (cli_parse_int(argv[++a], 1, ICS_LIGHTFIT_MAX_K, &K)) {
        fprintf(stderr, "icshadow fit-light: --lights: expected an integer in 1..%d, got '%s'\n",
                ICS_LIGHTFIT_MAX_K, argv[a]);
        return 2;
      }
    } else if (!strcmp(o, "--max-angle")) {
      if (cli_parse_double(argv[++a], &max_angle) || !(max_angle > 0 && max_angle < 90)) {
        fprintf(stderr, "icshadow fit-light: --max-angle: expected degrees in (0, 90), got '%s'\n",
                argv[a]);
        return 2;
      }
    } else if (!strcmp(o, "--seed")) {
      const char *v = argv[++a];
      char *end;
      errno = 0;
      seed = strtoull(v, &end, 10);
      if (!*v || *end || v[0] == '-' || v[0] == '+' || v[0] == ' ' || errno == ERANGE) {
        fprintf(stderr, "icshadow fit-light: --seed: expected an integer in 0..%llu, got '%s'\n",
                (unsigned long long)-1, v);
        return 2;
      }
    } else if (!strcmp(o, "--max-samples")) {
      if (cli_parse_int(argv[++a], 0, 1 << 30, &max_samples)) {
        fprintf(stderr, "icshadow fit-light: --max-samples: expected an integer >= 0\n");
        return 2;
      }
    } else if (!strcmp(o, "--max-iter")) {
      if (cli_parse_int(argv[++a], 1, 100000, &max_iter)) {
        fprintf(stderr, "icshadow fit-light: --max-iter: expected an integer in 1..100000\n");
        return 2;
      }
    } else if (!strcmp(o, "--sweep")) {
      sweep = 1;
    } else if (!strcmp(o, "--progress")) {
      force_progress = 1;
    } else if (!strcmp(o, "-o")) {
      outp = argv[++a];
    } else if (!strcmp(o, "--plane-csv")) {
      planep = argv[++a];
    } else if (o[0] == '-' && o[1]) {
      fprintf(stderr, "icshadow fit-light: unknown option '%s' (see --help)\n", o);
      return 2;
    } else if (!inp) {
      inp = o;
    } else {
      fprintf(stderr, "icshadow fit-light: more than one input map ('%s', '%s')\n", inp, o);
      return 2;
    }
  }
  if (!inp) {
    fprintf(stderr, "icshadow fit-light: missing input map ENV.exr\n");
    return 2;
  }
  if (!K) {
    fprintf(stderr, "icshadow fit-light: --lights K is required\n");
    return 2;
  }
  if (!outp) {
    fprintf(stderr, "icshadow fit-light: -o LIGHTS.json is required\n");
    return 2;
  }
  ics_image env;
  char msg[CLI_MSG_MAX];
  ics_status st = ics_exr_read(inp, &env, msg, sizeof msg);
  if (st != ICS_OK) {
    fprintf(stderr, "icshadow fit-light: %s\n", msg);
    return st == ICS_ERR_NOMEM ? 1 : 2;
  }
  prog pg = {isatty(2), 0};
  ics_lightfit_params p;
  ics_lightfit_defaults(&p);
  p.max_angle_deg = max_angle;
  p.seed = seed;
  p.max_samples = max_samples;
  p.max_iter = max_iter;
  if (pg.tty || force_progress) {
    p.progress = on_progress;
    p.progress_ctx = &pg;
  }
  ics_light lights[ICS_LIGHTFIT_MAX_K];
  ics_lightfit_report rep[ICS_LIGHTFIT_MAX_K];
  double secs[ICS_LIGHTFIT_MAX_K];
  int k0 = sweep ? 1 : K;
  for (int k = k0; k <= K; k++) {
    p.k = pg.k = k;
    double t0 = cli_now_s();
    st = ics_lightfit(&env, &p, lights, &rep[k - 1]);
    secs[k - 1] = cli_now_s() - t0;
    if (p.progress && pg.tty) fputc('\n', stderr);
    if (st != ICS_OK) {
      /* the options are checked above and ics_exr_read refuses bad pixels, so INVALID_ARG
       * can only mean a map without light inside the cut-off */
      if (st == ICS_ERR_INVALID_ARG)
        fprintf(stderr, "icshadow fit-light: %s: no light behind the viewer within %g degrees of "
                "the view axis\n", inp, max_angle);
      else if (st == ICS_ERR_SIZE)
        fprintf(stderr, "icshadow fit-light: %s: a %d x %d map is too small to fit (at least "
                "4 x 2 pixels)\n", inp, env.width, env.height);
      else
        fprintf(stderr, "icshadow fit-light: %s: fit failed: %s\n", inp, ics_status_str(st));
      ics_image_free(&env);
      return st == ICS_ERR_NOMEM ? 1 : 2;
    }
    if (!rep[k - 1].converged)
      fprintf(stderr, "fit-light: warning: K=%d: EM stopped at --max-iter %d before converging "
              "(log-likelihood change still above 1e-9)\n", k, max_iter);
  }
  ics_image_free(&env);
  const ics_lightfit_report *r = &rep[K - 1];
  double behind = r->energy_kept + r->energy_cutoff;
  fprintf(stderr,
          "fit-light: %s: energy %.6g; in front of the viewer (ignored) %.3g%%; behind: %.6g, of "
          "which %.3g%% beyond %g degrees (lost at the cut-off)\n",
          inp, r->energy_total, r->energy_total > 0 ? 100 * r->energy_front / r->energy_total : 0.0,
          behind, 100 * r->cutoff_loss, max_angle);
  if (r->k_fit < K)
    fprintf(stderr, "fit-light: the map is explained by %d light%s; %d requested\n", r->k_fit,
            r->k_fit == 1 ? "" : "s", K);

  /* -o first: when it cannot be opened, no plane CSV is written either */
  cli_output out, pout;
  if (cli_output_open(&out, "fit-light", outp) != 0) return 1;
  if (lights_write(out.fp, lights, r->k_fit) != 0) {
    cli_output_abort(&out);
    fprintf(stderr, "icshadow fit-light: cannot write %s\n", outp);
    return 1;
  }
  if (planep) {
    /* written from the map directly (not from the library's internals): the same frame
     * formulas as DESIGN.md, density = radiance * (1 + r^2)^(-3/2) */
    ics_image env2;
    if (ics_exr_read(inp, &env2, msg, sizeof msg) != ICS_OK) {
      fprintf(stderr, "icshadow fit-light: %s\n", msg);
      cli_output_abort(&out);
      return 1;
    }
    if (cli_output_open(&pout, "fit-light", planep) != 0) {
      ics_image_free(&env2);
      cli_output_abort(&out);
      return 1;
    }
    fprintf(pout.fp, "i,j,x,y,r,g,b,kept\n");
    for (int j = 0; j < env2.height; j++)
      for (int i = 0; i < env2.width; i++) {
        double x, y;
        if (ics_envmap_pixel(env2.width, env2.height, i, j, &x, &y, NULL)) continue;
        double r2 = x * x + y * y, jac = pow(1 + r2, -1.5);
        const float *px = env2.data + ((size_t)j * env2.width + i) * env2.channels;
        fprintf(pout.fp, "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%d\n", i, j, x, y, px[0] * jac,
                px[1] * jac, px[2] * jac,
                ics_envmap_pixel_kept(env2.width, env2.height, i, j, max_angle));
      }
    ics_image_free(&env2);
    if (cli_output_commit(&pout) != 0) {
      cli_output_abort(&out);
      return 1;
    }
  }
  if (cli_output_commit(&out) != 0) return 1;
  if (!strcmp(outp, "-")) return 0;
  printf("k,fitted,l1,l2,edge,seconds,iterations,samples,cutoff_loss\n");
  for (int k = k0; k <= K; k++) {
    const ics_lightfit_report *q = &rep[k - 1];
    printf("%d,%d,%.17g,%.17g,%.17g,%.17g,%d,%d,%.17g\n", k, q->k_fit, q->l1, q->l2, q->edge,
           secs[k - 1], q->iterations, q->samples, q->cutoff_loss);
  }
  return cli_stdout_failed("fit-light");
}
