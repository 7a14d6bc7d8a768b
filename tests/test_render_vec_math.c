/* test_render_vec_math.c — the cpu backend's vector exp, expm1 and log (gpu/backends/cpu/
 * vec_math.h, which the batched volume pieces use in place of libm's) on every vector path this
 * processor has, against long double's expl, expm1l and logl (64-bit mantissas on x86-64:
 * 2^-11 of a double's ulp): random arguments over the whole range of each (subnormal results
 * and arguments included, and near 0 and 1 where expm1 and log must stay relative), every one
 * below 2 ulps of the reference (the design's bound: the reduction and the last addition round
 * once each, the polynomials are truncated 1e-17 relative; a NaN counts as beyond it;
 * docs/renderer.md "Volume pieces in batches" gives the measured maxima); the special values
 * (0 and -0 with their signs, infinities, NaN, negatives for log) exactly as C's functions give
 * them, and the ends of the ranges (710, -746, DBL_MIN, ...) within the bound; and every path
 * the same bits (no contraction anywhere). A path the processor lacks is reported and
 * skipped. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "piece_batch.h"
#include "testutil.h"

#define BOUND_ULPS 2.0
enum { FN_EXP, FN_EXPM1, FN_LOG, FN_COUNT };
static const char *const fn_name[FN_COUNT] = {"exp", "expm1", "log"};

static long double reference(int fn, double x) {
  return fn == FN_EXP ? expl(x) : fn == FN_EXPM1 ? expm1l(x) : logl(x);
}

/* |y - r| in units of the last place of r as a double (subnormal: 2^-1074) */
static double ulps(double y, long double r) {
  if (isinf(r) || isnan(r)) return isinf(y) && (y > 0) == (r > 0) ? 0 : HUGE_VAL;
  long double ar = fabsl(r);
  int e = ar >= DBL_MIN ? ilogbl(ar) : -1022;
  if (ar >= (long double)DBL_MAX) e = 1023;
  return (double)(fabsl((long double)y - r) / ldexpl(1, e - 52));
}

static double uniform(double a, double b) { return a + (b - a) * test_rng_unit(); }
/* +-2^U(e0, e1) times a mantissa in [1, 2) */
static double log_uniform(int e0, int e1) {
  double m = 1 + test_rng_unit(), x = ldexp(m, e0 + (int)(test_rng_u64() % (uint64_t)(e1 - e0 + 1)));
  return test_rng_u64() & 1 ? -x : x;
}

/* the arguments of fn: n of them into x */
static int arguments(int fn, double *x, int cap) {
  int n = 0;
#define PUSH(v) (n < cap ? (void)(x[n++] = (v)) : (void)0)
  for (int i = 0; i < 100000; i++) {
    if (fn == FN_EXP) {
      PUSH(uniform(-745.2, 709.78));
      PUSH(uniform(-1, 1));
      if (i % 5 == 0) PUSH(fabs(log_uniform(-1074, -1)) * (i % 10 ? 1 : -1));
      if (i % 5 == 0) PUSH(uniform(-745.2, -708)); /* subnormal results */
    } else if (fn == FN_EXPM1) {
      PUSH(uniform(-40, 40));
      PUSH(uniform(-1, 1));
      if (i % 5 == 0) PUSH(log_uniform(-1074, -1));
      if (i % 10 == 0) PUSH(uniform(-745, -40));
      if (i % 10 == 0) PUSH(uniform(40, 709.78));
    } else {
      PUSH(fabs(log_uniform(-1022, 1023)));
      PUSH(uniform(0.5, 2));
      if (i % 5 == 0) PUSH(1 + uniform(-1e-6, 1e-6));
      if (i % 5 == 0) PUSH(fabs(log_uniform(-1074, -1023))); /* subnormal arguments */
    }
  }
#undef PUSH
  return n;
}

static void check_specials(ics_simd_path p) {
  static const double xs[] = {0.0, -0.0, INFINITY, -INFINITY, NAN, -1.0, 1.0, 709.78, 710.0,
                              -746.0, -1e300, DBL_MIN, 0x1p-1074, DBL_MAX};
  enum { NX = sizeof xs / sizeof *xs };
  for (int fn = 0; fn < FN_COUNT; fn++) {
    double y[NX];
    ics_vec_math(fn, xs, NX, y, p);
    for (int i = 0; i < NX; i++) {
      double c = fn == FN_EXP ? exp(xs[i]) : fn == FN_EXPM1 ? expm1(xs[i]) : log(xs[i]);
      int special = !isfinite(c) || c == 0 || !isfinite(xs[i]) || xs[i] == 0 ||
                    (fn == FN_LOG && xs[i] < 0);
      int ok = special ? (isnan(c) ? isnan(y[i]) : c == y[i] && signbit(c) == signbit(y[i]))
                       : ulps(y[i], reference(fn, xs[i])) < BOUND_ULPS;
      CHECK(ok, "%s %s(%a) = %a, C's %a", ics_simd_name(p), fn_name[fn], xs[i], y[i], c);
    }
  }
}

int main(void) {
  int cap = 400000;
  double *x = malloc(sizeof *x * (size_t)cap), *y = malloc(sizeof *y * (size_t)cap),
         *first = malloc(sizeof *first * (size_t)cap);
  if (!x || !y || !first) return 1;
  for (int fn = 0; fn < FN_COUNT; fn++) {
    int n = arguments(fn, x, cap), have = 0;
    const char *first_name = NULL;
    for (int p = ICS_SIMD_SCALAR + 1; p < ICS_SIMD_PATHS_; p++) {
      if (!ics_simd_has((ics_simd_path)p)) {
        if (fn == 0) printf("%s: skipped (not on this processor)\n", ics_simd_name((ics_simd_path)p));
        continue;
      }
      ics_vec_math(fn, x, n, y, (ics_simd_path)p);
      double worst = 0, at = 0;
      int beyond = 0;
      for (int i = 0; i < n; i++) {
        double u = ulps(y[i], reference(fn, x[i]));
        if (!(u < BOUND_ULPS)) beyond++; /* (a NaN too) */
        if (!(u <= worst) && !isnan(worst)) worst = u, at = x[i];
      }
      CHECK(beyond == 0, "%s %s: %d arguments beyond %g ulps, the worst %.3f at %a",
            ics_simd_name((ics_simd_path)p), fn_name[fn], beyond, BOUND_ULPS, worst, at);
      printf("%s, %s: %d arguments, at most %.3f ulps (at %a)\n", fn_name[fn],
             ics_simd_name((ics_simd_path)p), n, worst, at);
      if (!have) {
        memcpy(first, y, sizeof *y * (size_t)n), have = 1, first_name = ics_simd_name((ics_simd_path)p);
      } else {
        CHECK(memcmp(first, y, sizeof *y * (size_t)n) == 0, "%s: %s and %s differ", fn_name[fn],
              ics_simd_name((ics_simd_path)p), first_name);
      }
      if (fn == 0) check_specials((ics_simd_path)p);
    }
  }
  free(x), free(y), free(first);
  return test_summary("test_render_vec_math");
}
