/* cmd_isoline.c — `icshadow isoline --light SPEC --level S --distance D --model M ...`: the x
 * position of the isoline of level S at distance D behind a Heaviside edge (Patel et al. 2013,
 * Sec. 6, Appendix A.3-A.5) for the correct shadow, the CLT model (Eq. 8) or the actually
 * iterated shadow (conv engine). Conventions: icshadow/shadow1d.h and docs/theory.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "commands.h"
#include "icshadow.h"

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow isoline --light SPEC --level S --distance D --model MODEL\n"
          "                        [--d1 D1] [--slab E] [--kernel K] [--samples N] [--seed U]\n"
          "Prints (%%.17g) the x position of the isoline of shadow level S at distance D behind\n"
          "an edge occluder opaque for x > 0. The shadow value is the blocked fraction of the\n"
          "light (0 lit, 1 umbra); light at +x on the light plane throws the shadow toward -x.\n"
          "  correct:   x = -D L^-1(1 - S)                       (Eq. 9/17)\n"
          "  clt:       x = -D mu + Phi^-1(S) sqrt(D D1 var)    (Eq. 8, A.4)\n"
          "  iterative: the iterated shadow H * kappa^{*n}, n = D/E, kappa the member K with\n"
          "             mean -E mu and variance D1 E var (Eq. 7/15), on a grid of 64 pixels per\n"
          "             final standard deviation (the 2x finer grid is what is printed).\n"
          "SPEC: gauss:MU,VAR | box:LO,HI | mix:W,MU,VAR;W,MU,VAR;... (weights normalised,\n"
          "      each VAR > 0, at most %d components)\n\n"
          "options:\n"
          "  --light SPEC     the 1D light (required)\n"
          "  --level S        shadow level in (0, 1) (required)\n"
          "  --distance D     distance behind the occluder, finite and >= 0 (required)\n"
          "  --model M        correct | clt | iterative (required)\n"
          "  --d1 D1          optimal distance, > 0 (required for clt and iterative)\n"
          "  --slab E         slab spacing, > 0, D/E an integer (required for iterative)\n"
          "  --kernel K       dirac | tophat | stochastic-dirac | gauss (default dirac)\n"
          "  --samples N      the member's sample count (gauss; 0 = default)\n"
          "  --seed U         seed of stochastic members (default 0)\n"
          "Work budget (iterative): runs whose estimated work (slabs x grid nodes x applied taps,\n"
          "plus the compensation's passes over the member's taps, for both grids) exceeds %.0e\n"
          "tap-updates (under a minute here) are refused with exit 2.\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input (message on stderr).\n",
          ICS_LIGHT1D_MAX_MIX, ICS_CONV_WORK_BUDGET);
}

static const char CMD[] = "isoline";

/* The light of a SPEC into *l (the caller destroys it); -1 after an error message. */
static int parse_light(const char *spec, ics_light1d **l) {
  const char *colon = strchr(spec, ':');
  const char *end = spec + strlen(spec);
  if (!colon) {
    cli_error(CMD, "--light: expected KIND:NUMBERS (gauss:MU,VAR, box:LO,HI, mix:W,MU,VAR;...), "
                   "got '%s'", spec);
    return -1;
  }
  size_t kl = (size_t)(colon - spec);
  const char *a = colon + 1;
  ics_status st;
  if (kl == 5 && !strncmp(spec, "gauss", 5)) {
    double v[2];
    if (cli_parse_numbers(CMD, "--light", spec, a, end, 2, v)) return -1;
    if (v[1] < 0) {
      cli_error(CMD, "--light: negative variance at position %d of '%s'",
                (int)(strrchr(spec, ',') - spec) + 2, spec);
      return -1;
    }
    st = ics_light1d_create_gauss(l, v[0], v[1]);
  } else if (kl == 3 && !strncmp(spec, "box", 3)) {
    double v[2];
    if (cli_parse_numbers(CMD, "--light", spec, a, end, 2, v)) return -1;
    if (!(v[0] < v[1])) {
      cli_error(CMD, "--light: box needs LO < HI (position %d of '%s')", (int)(a - spec) + 1,
                spec);
      return -1;
    }
    st = ics_light1d_create_box(l, v[0], v[1]);
  } else if (kl == 3 && !strncmp(spec, "mix", 3)) {
    double w[ICS_LIGHT1D_MAX_MIX], mu[ICS_LIGHT1D_MAX_MIX], var[ICS_LIGHT1D_MAX_MIX];
    int n = 0;
    const char *p = a;
    for (;;) {
      const char *q = strchr(p, ';');
      if (!q) q = end;
      if (n == ICS_LIGHT1D_MAX_MIX) {
        cli_error(CMD, "--light: more than %d components at position %d of '%s'",
                  ICS_LIGHT1D_MAX_MIX, (int)(p - spec) + 1, spec);
        return -1;
      }
      double v[3];
      if (cli_parse_numbers(CMD, "--light", spec, p, q, 3, v)) return -1;
      if (v[0] < 0) {
        cli_error(CMD, "--light: negative weight at position %d of '%s'", (int)(p - spec) + 1,
                  spec);
        return -1;
      }
      if (!(v[2] > 0)) {
        const char *c2 = p;
        for (int c = 0; c < 2; c++) c2 = strchr(c2, ',') + 1;
        cli_error(CMD, "--light: component variance must be > 0 at position %d of '%s'",
                  (int)(c2 - spec) + 1, spec);
        return -1;
      }
      w[n] = v[0], mu[n] = v[1], var[n] = v[2], n++;
      if (q == end) break;
      p = q + 1;
    }
    st = ics_light1d_create_mix(l, n, w, mu, var);
    if (st == ICS_ERR_INVALID_ARG) {
      cli_error(CMD, "--light: the weights of '%s' sum to zero", spec);
      return -1;
    }
  } else {
    cli_error(CMD, "--light: unknown light kind '%.*s' at position 1 of '%s' (gauss, box, mix)",
              (int)kl, spec, spec);
    return -1;
  }
  if (st == ICS_ERR_RANGE) {
    cli_error(CMD, "--light '%s': %s overflows double precision (not finite)", spec,
              !strncmp(spec, "box", 3) ? "the width HI - LO or its variance"
                                       : "the weights' sum, the mixture's mean or its variance");
    return -1;
  }
  if (st != ICS_OK) {
    cli_error(CMD, "--light '%s': %s", spec, ics_status_str(st));
    return -1;
  }
  return 0;
}

/* 1D members by name; -1 if unknown or without a 1D form */
static int kernel1d_member(const char *name) {
  for (int m = 0; m < ICS_KERNEL_MEMBER_COUNT_; m++) {
    const char *n = ics_kernel_member_name((ics_kernel_member)m);
    if (n && !strcmp(n, name) && (ics_kernel_member_dims((ics_kernel_member)m) & 1)) return m;
  }
  return -1;
}

/* Model iterative: the iterated isoline into *x; 0, or the exit status after an error message. */
static int iterated_isoline(const ics_light1d *l, double level, double dist, double d1,
                            double slab, int member, int samples, uint64_t seed, double *x) {
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  o.member = (ics_kernel_member)member;
  o.nsamples = samples;
  o.seed = seed;
  char msg[512];
  ics_status st = ics_isoline_iterative_bounded(l, level, dist, d1, slab, &o, x, NULL, msg, sizeof msg);
  if (st == ICS_ERR_RANGE || st == ICS_ERR_SIZE) return cli_error(CMD, "%s", msg);
  if (st != ICS_OK) return cli_status_error(CMD, st, "%s", msg);
  return 0;
}

int cmd_isoline(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  const char *spec = NULL, *model = NULL, *kname = "dirac";
  double level = NAN, dist = NAN, d1 = NAN, slab = NAN; /* NaN: not given (refused as a value) */
  uint64_t seed = 0;
  int samples = 0;
  const cli_option opts[] = {
      {"--light", .kind = CLI_STRING, .dest = &spec},
      {"--level", .kind = CLI_FINITE, .dest = &level},
      {"--distance", .kind = CLI_FINITE, .dest = &dist},
      {"--model", .kind = CLI_STRING, .dest = &model},
      {"--d1", .kind = CLI_FINITE, .dest = &d1},
      {"--slab", .kind = CLI_FINITE, .dest = &slab},
      {"--kernel", .kind = CLI_STRING, .dest = &kname},
      {"--samples", .kind = CLI_INT, .dest = &samples, .lo = 0, .hi = 4096},
      {"--seed", .kind = CLI_SEED, .dest = &seed},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  if (!spec || !model || isnan(level) || isnan(dist))
    return cli_error(CMD, "%s is required",
                     !spec          ? "--light"
                     : !model       ? "--model"
                     : isnan(level) ? "--level"
                                    : "--distance");
  int m_correct = !strcmp(model, "correct"), m_clt = !strcmp(model, "clt"),
      m_iter = !strcmp(model, "iterative");
  if (!m_correct && !m_clt && !m_iter)
    return cli_error(CMD, "--model: unknown model '%s' (correct, clt, iterative)", model);
  if (!(level > 0 && level < 1))
    return cli_error(CMD, "--level: must be in (0, 1), got %.17g", level);
  if (dist < 0) return cli_error(CMD, "--distance: negative distance %.17g", dist);
  if ((m_clt || m_iter) && isnan(d1))
    return cli_error(CMD, "--d1 is required for model %s", model);
  if (!isnan(d1) && !(d1 > 0)) return cli_error(CMD, "--d1: must be > 0, got %.17g", d1);
  if (m_iter && isnan(slab)) return cli_error(CMD, "--slab is required for model iterative");
  if (!isnan(slab) && !(slab > 0)) return cli_error(CMD, "--slab: must be > 0, got %.17g", slab);
  int member = kernel1d_member(kname);
  if (member < 0)
    return cli_error(CMD, "--kernel: unknown 1D kernel '%s' (dirac, tophat, stochastic-dirac, "
                          "gauss)", kname);
  ics_light1d *l = NULL;
  if (parse_light(spec, &l)) return 2;
  double x = NAN;
  if (m_correct)
    x = ics_isoline_correct(l, level, dist);
  else if (m_clt)
    x = ics_isoline_clt(l, level, dist, d1);
  else
    rc = iterated_isoline(l, level, dist, d1, slab, member, samples, seed, &x);
  ics_light1d_destroy(l);
  if (rc) return rc;
  if (!isfinite(x))
    return cli_error(CMD, "the isoline position is not finite (%g): distance, d1 and the light's "
                          "mean/variance overflow double precision together", x);
  printf("%.17g\n", x);
  return cli_stdout_failed(CMD);
}
