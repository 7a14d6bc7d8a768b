/* stability_sweep.c — stability sweep of libicshadow's exact functions over their whole domains.
 *
 * For every function of `icshadow eval` (ellipk, ellipe, ellipk_m1, ellipe_m1, varx, vx, vy,
 * ratio, ratio_to_t) and every region of its domain — the extremes (subnormal, near 1, huge,
 * negative) and both sides of every algorithm switch listed in docs/ellint.md and
 * docs/ellipse.md — it draws deterministic random inputs, measures the maximum error in ulps
 * against the 320-bit MPFR references of tests/ref_mpfr.c, and times the function on the same
 * inputs (ns per call, minimum over repetitions). Writes CSV to stdout:
 *   function,region,lo,hi,samples,max_ulp,worst_input,ns_per_call
 * Usage: stability_sweep [--samples N] [--progress]   (default N = 2000 per region).
 * The documented bounds (0.60 ulp K/E, 0.75 varx/vx/vy, 1.0 ratio/ratio_to_t) are what
 * tests/test_ellint.c and tests/test_ellipse.c assert; this program reports, it does not assert. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <mpfr.h>

#include "icshadow.h"
#include "ref_mpfr.h"

typedef enum { F_K, F_E, F_K1, F_E1, F_VARX, F_VX, F_VY, F_RATIO, F_RATIO_TO_T } func_id;

static const struct {
  const char *name;
  double (*f)(double);
} funcs[] = {
    [F_K] = {"ellipk", ics_ellipk},          [F_E] = {"ellipe", ics_ellipe},
    [F_K1] = {"ellipk_m1", ics_ellipk_m1},   [F_E1] = {"ellipe_m1", ics_ellipe_m1},
    [F_VARX] = {"varx", ics_ellipse_varx},   [F_VX] = {"vx", ics_ellipse_vx},
    [F_VY] = {"vy", ics_ellipse_vy},         [F_RATIO] = {"ratio", ics_ellipse_ratio},
    [F_RATIO_TO_T] = {"ratio_to_t", ics_ellipse_ratio_to_t},
};

/* how inputs are drawn in [lo, hi]: uniform, log-uniform, or 1 - log-uniform(lo, hi) */
typedef enum { LIN, LOG, ONE_MINUS_LOG, NEG_LOG } draw_kind;

typedef struct {
  func_id f;
  const char *region;
  double lo, hi;
  draw_kind draw;
} region;

#define BELOW(s) ((s) * (1 - 0x1p-30)), (s)
#define ABOVE(s) (s), ((s) * (1 + 0x1p-30))

static const region regions[] = {
    /* K and E through the parameter m (m = 1 - m1 for the m1 entry points) */
    {F_K, "m near 1: 1-m log-uniform [2^-53, 1/32) (log series)", 0x1p-53, 0x1p-5, ONE_MINUS_LOG},
    {F_K, "m in [0, 31/32] (pieces)", 0.0, 31.0 / 32, LIN},
    {F_K, "just below m = 31/32 (pieces side)", BELOW(31.0 / 32), LIN},
    {F_K, "just above m = 31/32 (log side)", ABOVE(31.0 / 32), LIN},
    {F_K, "m in (-31, 0) (transform, pieces)", -31.0, 0.0, LIN},
    {F_K, "m in [-2^512, -31) (transform, log)", 31.0, 0x1p512, NEG_LOG},
    {F_K, "m < -2^512 (scaled transform)", 0x1p512, DBL_MAX, NEG_LOG},
    {F_K, "m around -31 (transform switch)", 30.99, 31.01, NEG_LOG},
    {F_E, "m near 1: 1-m log-uniform [2^-53, 1/32) (log series)", 0x1p-53, 0x1p-5, ONE_MINUS_LOG},
    {F_E, "m in [0, 31/32] (pieces)", 0.0, 31.0 / 32, LIN},
    {F_E, "just below m = 31/32 (pieces side)", BELOW(31.0 / 32), LIN},
    {F_E, "just above m = 31/32 (log side)", ABOVE(31.0 / 32), LIN},
    {F_E, "m in (-31, 0) (transform, pieces)", -31.0, 0.0, LIN},
    {F_E, "m in [-2^512, -31) (transform, log)", 31.0, 0x1p512, NEG_LOG},
    {F_E, "m < -2^512 (scaled transform)", 0x1p512, DBL_MAX, NEG_LOG},
    {F_K1, "m1 subnormal", 0x1p-1074, 0x1p-1022, LOG},
    {F_K1, "m1 in [2^-1022, 2^-64) (log series, clamped polynomials)", 0x1p-1022, 0x1p-64, LOG},
    {F_K1, "m1 in [2^-64, 1/32) (log series)", 0x1p-64, 0x1p-5, LOG},
    {F_K1, "just below m1 = 2^-64", BELOW(0x1p-64), LIN},
    {F_K1, "just above m1 = 2^-64", ABOVE(0x1p-64), LIN},
    {F_K1, "just below m1 = 1/32 (log side)", BELOW(0x1p-5), LIN},
    {F_K1, "just above m1 = 1/32 (pieces side)", ABOVE(0x1p-5), LIN},
    {F_K1, "m1 in [1/32, 1] (pieces)", 0x1p-5, 1.0, LOG},
    {F_K1, "just below m1 = 1 (m > 0)", BELOW(1.0), LIN},
    {F_K1, "just above m1 = 1 (m < 0)", ABOVE(1.0), LIN},
    {F_K1, "m1 in (1, 32] (transform, pieces)", 1.0, 32.0, LOG},
    {F_K1, "m1 in (32, 2^512] (transform, log)", 32.0, 0x1p512, LOG},
    {F_K1, "just below / above m1 = 2^512", 0x1p512 * (1 - 0x1p-30), 0x1p512 * (1 + 0x1p-30), LIN},
    {F_K1, "m1 > 2^512 (scaled transform)", 0x1p512, DBL_MAX, LOG},
    {F_E1, "m1 subnormal", 0x1p-1074, 0x1p-1022, LOG},
    {F_E1, "m1 in [2^-1022, 1/32) (log series)", 0x1p-1022, 0x1p-5, LOG},
    {F_E1, "just below m1 = 1/32 (log side)", BELOW(0x1p-5), LIN},
    {F_E1, "just above m1 = 1/32 (pieces side)", ABOVE(0x1p-5), LIN},
    {F_E1, "m1 in [1/32, 1] (pieces)", 0x1p-5, 1.0, LOG},
    {F_E1, "m1 in (1, 32] (transform, pieces)", 1.0, 32.0, LOG},
    {F_E1, "just below m1 = 32", BELOW(32.0), LIN},
    {F_E1, "just above m1 = 32", ABOVE(32.0), LIN},
    {F_E1, "m1 in (32, 2^512] (transform, log)", 32.0, 0x1p512, LOG},
    {F_E1, "m1 > 2^512 (scaled transform)", 0x1p512, DBL_MAX, LOG},
    /* ellipse variance functions */
    {F_VARX, "b log-uniform [1e-300, 0.0757) (thin, T formula 2)", 1e-300, 0.0757, LOG},
    {F_VARX, "b around 0.0757 (p = 1/4 switch)", 0.0757 * (1 - 1e-3), 0.0757 * (1 + 1e-3), LIN},
    {F_VARX, "b in [0.0757, 1)", 0.0757, 1.0, LIN},
    {F_VARX, "b = 1 - 2^-k (k up to 53)", 0x1p-53, 0.5, ONE_MINUS_LOG},
    {F_VARX, "just below b = 1", BELOW(1.0), LIN},
    {F_VARX, "just above b = 1", ABOVE(1.0), LIN},
    {F_VARX, "b in (1, 2^500)", 1.0, 0x1p500, LOG},
    {F_VARX, "b >= 2^500", 0x1p500, DBL_MAX, LOG},
    {F_VX, "t log-uniform [1e-300, 2^-480) (scaled square)", 1e-300, 0x1p-480, LOG},
    {F_VX, "t in [2^-480, 0.0703) log-uniform", 0x1p-480, 0.0703, LOG},
    {F_VX, "t in [0.0703, 1/2)", 0.0703, 0.5, LIN},
    {F_VX, "just below / above t = 1/2", 0.5 * (1 - 0x1p-30), 0.5 * (1 + 0x1p-30), LIN},
    {F_VX, "t in (1/2, 1)", 0.5, 1.0, LIN},
    {F_VX, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG},
    {F_VY, "t log-uniform [1e-300, 2^-480) (scaled square)", 1e-300, 0x1p-480, LOG},
    {F_VY, "just below / above t = 2^-480", 0x1p-480 * (1 - 0x1p-30), 0x1p-480 * (1 + 0x1p-30), LIN},
    {F_VY, "t in [2^-480, 1/2) log-uniform", 0x1p-480, 0.5, LOG},
    {F_VY, "t in (1/2, 1)", 0.5, 1.0, LIN},
    {F_VY, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG},
    {F_RATIO, "t log-uniform [1e-300, 2^-480)", 1e-300, 0x1p-480, LOG},
    {F_RATIO, "t in [2^-480, 1/2) log-uniform", 0x1p-480, 0.5, LOG},
    {F_RATIO, "t around 0.0703 (p = 1/4 switch)", 0.0703 * (1 - 1e-3), 0.0703 * (1 + 1e-3), LIN},
    {F_RATIO, "just below / above t = 1/2", 0.5 * (1 - 0x1p-30), 0.5 * (1 + 0x1p-30), LIN},
    {F_RATIO, "t in (1/2, 1)", 0.5, 1.0, LIN},
    {F_RATIO, "t = 1 - log-uniform [2^-53, 1/2)", 0x1p-53, 0.5, ONE_MINUS_LOG},
    {F_RATIO_TO_T, "r log-uniform [1e-300, 2^-600) (asymptotic)", 1e-300, 0x1p-600, LOG},
    {F_RATIO_TO_T, "just below / above r = 2^-600", 0x1p-600 * (1 - 0x1p-30), 0x1p-600 * (1 + 0x1p-30), LIN},
    {F_RATIO_TO_T, "r in [2^-600, 1e-4) log-uniform", 0x1p-600, 1e-4, LOG},
    {F_RATIO_TO_T, "r in [1e-4, 1) log-uniform", 1e-4, 1.0, LOG},
    {F_RATIO_TO_T, "just below / above r = 1", 1.0 * (1 - 0x1p-30), 1.0 * (1 + 0x1p-30), LIN},
    {F_RATIO_TO_T, "r in (1, 1e4] log-uniform", 1.0, 1e4, LOG},
    {F_RATIO_TO_T, "r in (1e4, 2^600] log-uniform", 1e4, 0x1p600, LOG},
    {F_RATIO_TO_T, "r > 2^600 (asymptotic)", 0x1p600, 1e300, LOG},
};

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double urand(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) * 0x1p-53;
}

static double draw(const region *r) {
  double u = urand();
  switch (r->draw) {
  case LIN: return r->lo + u * (r->hi - r->lo);
  case LOG: return exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  case ONE_MINUS_LOG: return 1.0 - exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  case NEG_LOG: return -exp(log(r->lo) + u * (log(r->hi) - log(r->lo)));
  }
  return NAN;
}

/* the MPFR reference of function f at the double x */
static void reference(func_id f, double x, double got, mpfr_ptr out) {
  mpfr_t a;
  mpfr_init2(a, REF_PREC + 64);
  mpfr_set_d(a, x, MPFR_RNDN);
  switch (f) {
  case F_K:
  case F_E:
    mpfr_ui_sub(a, 1, a, MPFR_RNDN); /* m1 = 1 - m, exact at this precision */
    /* fall through */
  case F_K1:
  case F_E1:
    if (f == F_K || f == F_K1)
      ref_ellipke_m1(out, NULL, a);
    else
      ref_ellipke_m1(NULL, out, a);
    break;
  case F_VARX: ref_varx(out, a); break;
  case F_VX: ref_vx(out, a); break;
  case F_VY: ref_vy(out, a); break;
  case F_RATIO: ref_ratio(out, a); break;
  case F_RATIO_TO_T: ref_ratio_to_t(out, x, got); break;
  }
  mpfr_clear(a);
}

static double now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e9 + ts.tv_nsec;
}

/* ns per call over xs[0..n): minimum over repetitions of a throughput loop */
static double time_per_call(double (*f)(double), const double *xs, int n) {
  volatile double sink = 0;
  double best = INFINITY;
  for (int rep = 0; rep < 7; rep++) {
    double t0 = now_ns(), acc = 0;
    for (int i = 0; i < n; i++) acc += f(xs[i]);
    double dt = (now_ns() - t0) / n;
    sink += acc;
    if (dt < best) best = dt;
  }
  (void)sink;
  return best;
}

int main(int argc, char **argv) {
  int samples = 2000, progress = isatty(2);
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--samples") && i + 1 < argc) {
      samples = atoi(argv[++i]);
      if (samples < 1 || samples > 10000000) {
        fprintf(stderr, "stability_sweep: --samples must be in 1..10000000\n");
        return 2;
      }
    } else if (!strcmp(argv[i], "--progress")) {
      progress = 1;
    } else {
      fprintf(stderr, "usage: stability_sweep [--samples N] [--progress]\n");
      return !strcmp(argv[i], "--help") || !strcmp(argv[i], "-h") ? 0 : 2;
    }
  }
  double *xs = malloc(sizeof *xs * (size_t)samples);
  if (!xs) {
    fprintf(stderr, "stability_sweep: out of memory\n");
    return 1;
  }
  mpfr_t ref;
  mpfr_init2(ref, REF_PREC + 64);
  const int nreg = (int)(sizeof regions / sizeof regions[0]);
  printf("function,region,lo,hi,samples,max_ulp,worst_input,ns_per_call\n");
  for (int k = 0; k < nreg; k++) {
    const region *r = &regions[k];
    double (*f)(double) = funcs[r->f].f;
    double worst = 0, worst_x = NAN;
    for (int i = 0; i < samples; i++) {
      double x = draw(r);
      xs[i] = x;
      double got = f(x);
      reference(r->f, x, got, ref);
      double e = ref_ulp_error(got, ref);
      if (e > worst || isnan(worst_x)) {
        worst = e;
        worst_x = x;
      }
    }
    double ns = time_per_call(f, xs, samples);
    printf("%s,\"%s\",%a,%a,%d,%.4f,%a,%.2f\n", funcs[r->f].name, r->region, r->lo, r->hi,
           samples, worst, worst_x, ns);
    fflush(stdout);
    if (progress) fprintf(stderr, "\rstability_sweep: %d/%d regions", k + 1, nreg);
  }
  if (progress) fputc('\n', stderr);
  mpfr_clear(ref);
  free(xs);
  return 0;
}
