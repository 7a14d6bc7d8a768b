/* test_ellipse.c — ics_ellipse_varx / vx / vy / ratio / ratio_to_t against an MPFR reference
 * (Patel's closed form evaluated at REF_PREC bits with ref_ellipke_m1), plus the independent
 * quadrature that settles the elliptic-integral convention of Patel's Appendix A.7.
 *
 * Bounds asserted here are the ones stated in libicshadow/src/ellipse.c and docs/ellipse.md. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mpfr.h>

#include "icshadow.h"
#include "ref_mpfr.h"
#include "testutil.h"

/* the documented bounds (ulps) */
#define BOUND_VARX 0.75
#define BOUND_VX 0.75
#define BOUND_VY 0.75
#define BOUND_RATIO 1.0
#define BOUND_RATIO_TO_T 1.0
#define BOUND_SUBNORMAL 1.0 /* vy and ratio when the result is subnormal (ulp = 2^-1074) */
/* round trips, in ulps of t (see docs/ellipse.md, "Round trips") */
#define BOUND_RT_R 1.5 /* ratio(ratio_to_t(r)) vs r, error expressed as an error in t */
#define BOUND_RT_T 2.0 /* ratio_to_t(ratio(t)) vs t */

#define P (REF_PREC + 64)

/* ---- deterministic random numbers -------------------------------------------------------- */
static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static double urand(void) { /* uniform in [0, 1) */
  rng_state ^= rng_state << 13;
  rng_state ^= rng_state >> 7;
  rng_state ^= rng_state << 17;
  return (double)(rng_state >> 11) * 0x1p-53;
}
static double log_uniform(double lo, double hi) { return exp(log(lo) + urand() * (log(hi) - log(lo))); }

static double ulp_of(double x) {
  x = fabs(x);
  if (x < DBL_MIN) return 0x1p-1074;
  int e;
  frexp(x, &e);
  return ldexp(1.0, e - 53);
}

/* ---- independent quadrature of the arc-length density ------------------------------------
 * Ellipse x = A cos th, y = B sin th; ds = sqrt(A^2 sin^2 + B^2 cos^2) dth. The periodic
 * trapezoid rule with n nodes converges geometrically (singularities off the real axis). */
/* compensated accumulation (ksum, testutil.h), so the rule's result is not drowned in roundoff */
static void quad_var(double A, double B, int n, double *vx, double *vy) {
  ksum s = {0, 0}, sx = {0, 0}, sy = {0, 0};
  for (int i = 0; i < n; i++) {
    double th = 2 * ICS_PI * (i + 0.5) / n;
    double c = cos(th), sn = sin(th);
    double w = sqrt(A * A * sn * sn + B * B * c * c);
    kadd(&s, w);
    kadd(&sx, A * A * c * c * w);
    kadd(&sy, B * B * sn * sn * w);
  }
  *vx = (sx.s + sx.c) / (s.s + s.c);
  *vy = (sy.s + sy.c) / (s.s + s.c);
}

static void test_convention(void) {
  const double bs[] = {0.05, 0.3, 0.5, 0.7, 0.95, 1.0, 1.5, 4.0, 20.0};
  mpfr_t b, v, m1, K, E, num, den;
  mpfr_inits2(P, b, v, m1, K, E, num, den, (mpfr_ptr)0);
  double worst_param = 0, best_modulus_as_param = INFINITY;
  for (size_t i = 0; i < sizeof bs / sizeof bs[0]; i++) {
    double bb = bs[i], qx, qy;
    quad_var(1.0, bb, 4000, &qx, &qy);
    /* reading 1: sqrt(1-b^2) is the modulus k, parameter m = 1 - b^2 (m1 = b^2) */
    mpfr_set_d(b, bb, MPFR_RNDN);
    ref_varx(v, b);
    double rel = fabs(mpfr_get_d(v, MPFR_RNDN) - qx) / qx;
    if (rel > worst_param) worst_param = rel;
    CHECK(rel < 1e-15, "b=%g: quadrature %.17g vs closed form with m = 1-b^2: rel %.3g", bb, qx,
          rel);
    /* the library */
    double lib = ics_ellipse_varx(bb);
    CHECK(fabs(lib - qx) / qx < 1e-15, "b=%g: quadrature %.17g vs ics_ellipse_varx %.17g", bb, qx,
          lib);
    /* reading 2: sqrt(1-b^2) taken as the parameter m itself (only defined for b < 1) */
    if (bb < 1.0) {
      mpfr_set_d(m1, bb, MPFR_RNDN);
      mpfr_sqr(m1, m1, MPFR_RNDN);
      mpfr_ui_sub(m1, 1, m1, MPFR_RNDN);
      mpfr_sqrt(m1, m1, MPFR_RNDN);
      mpfr_ui_sub(m1, 1, m1, MPFR_RNDN); /* m1 = 1 - sqrt(1 - b^2) */
      ref_ellipke_m1(K, E, m1);
      double Kd = mpfr_get_d(K, MPFR_RNDN), Ed = mpfr_get_d(E, MPFR_RNDN);
      double alt = (2 * bb * bb - 1 - bb * bb * Kd / Ed) / (-3 + 3 * bb * bb);
      double d = fabs(alt - qx) / qx;
      if (d < best_modulus_as_param) best_modulus_as_param = d;
      CHECK(d > 1e-5, "b=%g: the other reading unexpectedly agrees (rel %.3g)", bb, d);
    }
  }
  /* V_x and V_y of the unit ellipse (1 - t, t) against the quadrature (dyadic t: 1 - t exact) */
  const double ts[] = {1.0 / 64, 0.25, 0.375, 0.5, 0.625, 0.75, 61.0 / 64};
  for (size_t i = 0; i < sizeof ts / sizeof ts[0]; i++) {
    double tt = ts[i], qx, qy;
    quad_var(1.0 - tt, tt, 4000, &qx, &qy);
    double vx = ics_ellipse_vx(tt), vy = ics_ellipse_vy(tt);
    CHECK(fabs(vx - qx) / qx < 1e-15, "t=%g: quadrature V_x %.17g vs ics_ellipse_vx %.17g", tt, qx,
          vx);
    CHECK(fabs(vy - qy) / qy < 1e-15, "t=%g: quadrature V_y %.17g vs ics_ellipse_vy %.17g", tt, qy,
          vy);
  }
  printf("convention: quadrature vs m = 1-b^2: max rel %.3g; vs m = sqrt(1-b^2): min rel %.3g\n",
         worst_param, best_modulus_as_param);
  mpfr_clears(b, v, m1, K, E, num, den, (mpfr_ptr)0);
}

/* ---- accuracy sweeps ---------------------------------------------------------------------- */
typedef struct {
  const char *name;
  double worst, at;
} worst_t;
static void note(worst_t *w, double err, double x) {
  if (err > w->worst || (isnan(err) && !isnan(w->worst))) {
    w->worst = err;
    w->at = x;
  }
}

static void check_varx(double b, worst_t *w) {
  mpfr_t bm, v;
  mpfr_inits2(P, bm, v, (mpfr_ptr)0);
  mpfr_set_d(bm, b, MPFR_RNDN);
  ref_varx(v, bm);
  double y = ics_ellipse_varx(b);
  double e = ref_ulp_error(y, v);
  note(w, e, b);
  CHECK(e <= BOUND_VARX, "ics_ellipse_varx(%a = %.17g) = %.17g, %.3f ulp", b, b, y, e);
  mpfr_clears(bm, v, (mpfr_ptr)0);
}

static worst_t wsub = {"vy, ratio (subnormal)", 0, 0};
static void check_t(double t, worst_t *wx, worst_t *wy, worst_t *wr, worst_t *wrt) {
  mpfr_t tm, v, r;
  mpfr_inits2(P, tm, v, r, (mpfr_ptr)0);
  mpfr_set_d(tm, t, MPFR_RNDN);
  ref_vx(v, tm);
  double y = ics_ellipse_vx(t), e = ref_ulp_error(y, v);
  note(wx, e, t);
  CHECK(e <= BOUND_VX, "ics_ellipse_vx(%a = %.17g) = %.17g, %.3f ulp", t, t, y, e);
  ref_vy(v, tm);
  y = ics_ellipse_vy(t), e = ref_ulp_error(y, v);
  note(fabs(y) < DBL_MIN && y != 0 ? &wsub : wy, e, t);
  /* subnormal results are rounded twice (exponent applied last): 1 ulp of 2^-1074 there */
  CHECK(e <= (fabs(y) < DBL_MIN ? BOUND_SUBNORMAL : BOUND_VY), "ics_ellipse_vy(%a = %.17g) = %.17g, %.3f ulp", t, t, y, e);
  if (t == 0.5)
    mpfr_set_ui(r, 1, MPFR_RNDN);
  else
    ref_ratio(r, tm);
  double rr = ics_ellipse_ratio(t);
  e = ref_ulp_error(rr, r);
  note(fabs(rr) < DBL_MIN && rr != 0 ? &wsub : wr, e, t);
  CHECK(e <= BOUND_RATIO, "ics_ellipse_ratio(%a = %.17g) = %.17g, %.3f ulp", t, t, rr, e);
  /* round trip t -> ratio -> t */
  if (t > 0.0 && t < 1.0 && rr > 0.0 && isfinite(rr) && rr >= DBL_MIN) {
    double t2 = ics_ellipse_ratio_to_t(rr);
    double et = fabs(t2 - t) / ulp_of(t);
    note(wrt, et, t);
    CHECK(et <= BOUND_RT_T, "ratio_to_t(ratio(%a = %.17g)) = %.17g, %.3f ulp", t, t, t2, et);
  }
  mpfr_clears(tm, v, r, (mpfr_ptr)0);
}

static void check_r(double r, worst_t *w, worst_t *wrt) {
  double t = ics_ellipse_ratio_to_t(r);
  mpfr_t tm, d;
  mpfr_inits2(P, tm, d, (mpfr_ptr)0);
  ref_ratio_to_t(tm, r, t);
  double e = ref_ulp_error(t, tm);
  note(w, e, r);
  CHECK(e <= BOUND_RATIO_TO_T, "ics_ellipse_ratio_to_t(%a = %.17g) = %.17g (ref %.17g), %.3f ulp",
        r, r, t, mpfr_get_d(tm, MPFR_RNDN), e);
  /* round trip r -> t -> ratio(t): |ln(r'/r)| / (|d ln ratio/dt| ulp(t)) in ulps of t */
  if (t > 0.0 && t < 1.0 && r >= DBL_MIN) {
    double r2 = ics_ellipse_ratio(t);
    mpfr_set_d(tm, t, MPFR_RNDN);
    ref_dlnratio(d, tm);
    double dl = mpfr_get_d(d, MPFR_RNDN);
    double er = fabs(log(r2 / r)) / (dl * ulp_of(t));
    /* log(r2/r) is itself only good to ~1e-16 absolute: allow for that in the measure */
    er = fmax(0.0, er - 2.3e-16 / (dl * ulp_of(t)));
    note(wrt, er, r);
    CHECK(er <= BOUND_RT_R, "ratio(ratio_to_t(%a = %.17g)) = %.17g: %.3f ulp of t", r, r, r2, er);
  }
  mpfr_clears(tm, d, (mpfr_ptr)0);
}

static void test_special(void) {
  CHECK(isnan(ics_ellipse_varx(NAN)), "varx(NaN)");
  CHECK(isnan(ics_ellipse_varx(-1e-300)), "varx(-1e-300)");
  CHECK(isnan(ics_ellipse_varx(-INFINITY)), "varx(-inf)");
  CHECK(ics_ellipse_varx(0.0) == 1.0 / 3.0, "varx(0) = %.17g", ics_ellipse_varx(0.0));
  CHECK(ics_ellipse_varx(1.0) == 0.5, "varx(1) = %.17g", ics_ellipse_varx(1.0));
  CHECK(ics_ellipse_varx(INFINITY) == 2.0 / 3.0, "varx(inf) = %.17g", ics_ellipse_varx(INFINITY));
  const double bad_t[] = {NAN, -0x1p-1074, -1.0, 1.0 + 0x1p-52, INFINITY, -INFINITY};
  for (size_t i = 0; i < sizeof bad_t / sizeof bad_t[0]; i++) {
    double t = bad_t[i];
    CHECK(isnan(ics_ellipse_vx(t)), "vx(%g) not NaN", t);
    CHECK(isnan(ics_ellipse_vy(t)), "vy(%g) not NaN", t);
    CHECK(isnan(ics_ellipse_ratio(t)), "ratio(%g) not NaN", t);
  }
  CHECK(ics_ellipse_vx(0.0) == 1.0 / 3.0, "vx(0)");
  CHECK(ics_ellipse_vx(1.0) == 0.0, "vx(1)");
  CHECK(ics_ellipse_vy(0.0) == 0.0, "vy(0)");
  CHECK(ics_ellipse_vy(1.0) == 1.0 / 3.0, "vy(1) = %.17g", ics_ellipse_vy(1.0));
  CHECK(ics_ellipse_vx(0.5) == 0.125 && ics_ellipse_vy(0.5) == 0.125, "vx(1/2), vy(1/2)");
  CHECK(ics_ellipse_ratio(0.0) == 0.0, "ratio(0)");
  CHECK(ics_ellipse_ratio(0.5) == 1.0, "ratio(1/2) = %.17g", ics_ellipse_ratio(0.5));
  CHECK(ics_ellipse_ratio(1.0) == INFINITY, "ratio(1)");
  CHECK(isnan(ics_ellipse_ratio_to_t(NAN)), "ratio_to_t(NaN)");
  CHECK(isnan(ics_ellipse_ratio_to_t(-0x1p-1074)), "ratio_to_t(-tiny)");
  CHECK(isnan(ics_ellipse_ratio_to_t(-INFINITY)), "ratio_to_t(-inf)");
  CHECK(ics_ellipse_ratio_to_t(0.0) == 0.0, "ratio_to_t(0)");
  CHECK(ics_ellipse_ratio_to_t(1.0) == 0.5, "ratio_to_t(1)");
  CHECK(ics_ellipse_ratio_to_t(INFINITY) == 1.0, "ratio_to_t(inf)");
  CHECK(ics_ellipse_ratio_to_t(DBL_MAX) == 1.0, "ratio_to_t(DBL_MAX)");
  /* tiny ratios: t ~ sqrt(r/2), still a positive, accurate number */
  double t = ics_ellipse_ratio_to_t(0x1p-1074);
  CHECK(t > 0.0 && fabs(t / ldexp(sqrt(0.5), -537) - 1) < 1e-15, "ratio_to_t(2^-1074) = %g", t);
  /* symmetry: ratio(1 - t) = 1 / ratio(t) and ratio_to_t(1/r) = 1 - ratio_to_t(r) */
  for (int i = 0; i < 200; i++) {
    double tt = 0.5 + 0.5 * urand(); /* 1 - tt exact (Sterbenz) */
    double a = ics_ellipse_ratio(tt), b = ics_ellipse_ratio(1.0 - tt);
    CHECK(fabs(a * b - 1.0) <= (2 * BOUND_RATIO + 0.5) * 0x1p-52, "ratio(%.17g) ratio(1-t) - 1 = %.3g", tt, a * b - 1.0);
    double r = log_uniform(1e-6, 1.0);
    double s1 = ics_ellipse_ratio_to_t(r), s2 = ics_ellipse_ratio_to_t(1.0 / r);
    CHECK(fabs(s1 + s2 - 1.0) <= BOUND_RATIO_TO_T * (0x1p-54 + 0x1p-53) + 0x1p-54, "ratio_to_t(%.17g) + ratio_to_t(1/r) - 1 = %.3g", r,
          s1 + s2 - 1.0);
  }
  /* monotonicity on a fine grid around the switch t = 1/2 and r = 1 */
  double prev = 0.0;
  for (int k = -200; k <= 200; k++) {
    double tt = 0.5 + k * 0x1p-53;
    double r = ics_ellipse_ratio(tt);
    CHECK(r >= prev, "ratio not monotone at t = 1/2 %+d ulp", k);
    prev = r;
  }
}

/* docs/architecture.md "Contracts": math functions never touch errno. All nine eval functions on the
 * extremes of (and beyond) their domains: 0, subnormals, DBL_MIN, 1e-300, 1 - 2^-53, 1, huge,
 * DBL_MAX, +-inf, NaN, negative. (ldexp's underflow in vy/ratio's scaled square set ERANGE.) */
static void test_errno(void) {
  typedef double (*fn)(double);
  static const struct {
    const char *name;
    fn f;
  } fs[] = {{"ics_ellint_k", ics_ellint_k},
            {"ics_ellint_e", ics_ellint_e},
            {"ics_ellint_k_m1", ics_ellint_k_m1},
            {"ics_ellint_e_m1", ics_ellint_e_m1},
            {"ics_ellipse_varx", ics_ellipse_varx},
            {"ics_ellipse_vx", ics_ellipse_vx},
            {"ics_ellipse_vy", ics_ellipse_vy},
            {"ics_ellipse_ratio", ics_ellipse_ratio},
            {"ics_ellipse_ratio_to_t", ics_ellipse_ratio_to_t}};
  const double xs[] = {0.0, -0.0, 0x1p-1074, 0x1p-1073, 0x1.8p-1060, 0x1p-1040, 0x1.fffffffffffffp-1023,
                       DBL_MIN, 0x1.0000000000001p-1022, 1e-310, 1e-300, 1e-200, 0x1p-961,
                       0x1p-960, 1e-160, 0x1p-480, 1e-100, 1e-8, 0.5, 1.0 - 0x1p-53, 1.0,
                       1.0 + 0x1p-52, 2.0, 1e8, 1e100, 1e300, DBL_MAX, INFINITY, -INFINITY, NAN,
                       -NAN, -0x1p-1074, -DBL_MIN, -1e-300, -0.5, -1.0, -1e8, -1e300, -DBL_MAX};
  for (size_t i = 0; i < sizeof fs / sizeof fs[0]; i++)
    for (size_t j = 0; j < sizeof xs / sizeof xs[0]; j++) {
      errno = 0;
      double y = fs[i].f(xs[j]);
      int err = errno;
      CHECK(err == 0, "%s(%a) = %.17g set errno = %d (%s)", fs[i].name, xs[j], y, err,
            strerror(err));
    }
  /* every binade of t below the scaled square's switch, where the exponent is applied last */
  for (int k = -1074; k <= -470; k++) {
    double t = ldexp(1.0, k), ts[] = {t, nextafter(t, 1.0), 1.5 * t};
    for (int j = 0; j < 3; j++) {
      errno = 0;
      double a = ics_ellipse_vy(ts[j]), b = ics_ellipse_ratio(ts[j]);
      int err = errno;
      CHECK(err == 0, "vy/ratio(%a) = %.17g / %.17g set errno = %d", ts[j], a, b, err);
    }
  }
}

int main(int argc, char **argv) {
  int n = 400; /* random points per region; the sanitizer build uses the same count */
  if (argc > 1) n = atoi(argv[1]);
  test_convention();
  test_special();
  test_errno();

  worst_t wvarx = {"varx", 0, 0};
  const double fixed_b[] = {0x1p-1074, 1e-300, 1e-200, 1.5e-154, 1e-100, 1e-20, 1e-8, 0.001, 0.1,
                            0.25, 0.5, 0.75, 0.999, 1.0, 1.001, 1.5, 2, 4, 1e3, 1e8, 1e20, 1e100,
                            1.3e154, 1e150, 1e200, 1e300, DBL_MAX};
  for (size_t i = 0; i < sizeof fixed_b / sizeof fixed_b[0]; i++) check_varx(fixed_b[i], &wvarx);
  /* both sides of the T-formula switch p = 1/4 (beta = 0.0757001907631720..., see ellipse.c) */
  for (int k = -8; k <= 8; k++) check_varx(0.075700190763172030 + k * 0x1p-56, &wvarx);
  /* var_x(b) + var_x(1/b) = 1 (1/3 + w and 2/3 - w): exact 1/b for b = 2^k */
  for (int k = -60; k <= 60; k += 3) {
    double b = ldexp(1.0, k), s = ics_ellipse_varx(b) + ics_ellipse_varx(1.0 / b);
    CHECK(fabs(s - 1.0) <= 2 * BOUND_VARX * 0x1p-53 + 0x1p-53, "varx(2^%d) + varx(2^%d) - 1 = %.3g",
          k, -k, s - 1.0);
  }
  for (int k = 1; k <= 53; k++) { /* both sides of b = 1 */
    check_varx(1.0 - ldexp(1.0, -k), &wvarx);
    check_varx(1.0 + ldexp(1.0, -k), &wvarx);
    check_varx(nextafter(1.0 - ldexp(1.0, -k), 1.0), &wvarx);
  }
  for (int i = 0; i < n; i++) {
    check_varx(log_uniform(1e-300, 1e150), &wvarx);
    check_varx(urand() * 2.0, &wvarx);
    check_varx(1.0 + (urand() - 0.5) * ldexp(1.0, -(int)(urand() * 50)), &wvarx);
  }

  worst_t wvx = {"vx", 0, 0}, wvy = {"vy", 0, 0}, wr = {"ratio", 0, 0},
          wrtt = {"ratio_to_t(ratio(t))", 0, 0};
  const double fixed_t[] = {0x1p-1074, 1e-310, 1e-300, 1e-160, 0x1p-480, 0x1.0000000000001p-480,
                            1e-100, 1e-20, 1e-8, 0.01, 0.25, 0.5, 0.75, 0.99,
                            1.0 - 1e-8, 1.0 - 0x1p-52, 1.0 - 0x1p-53, 1.0};
  for (size_t i = 0; i < sizeof fixed_t / sizeof fixed_t[0]; i++)
    check_t(fixed_t[i], &wvx, &wvy, &wr, &wrtt);
  for (int k = -60; k <= 60; k++) check_t(0.5 + k * 0x1p-54, &wvx, &wvy, &wr, &wrtt);
  /* both sides of p = 1/4 (t = 0.0703729453738084...) and of the scaled square (t = 2^-480) */
  for (int k = -8; k <= 8; k++) {
    check_t(0.070372945373808446 + k * 0x1p-57, &wvx, &wvy, &wr, &wrtt);
    check_t(1.0 - 0.070372945373808446 + k * 0x1p-53, &wvx, &wvy, &wr, &wrtt);
    check_t(0x1p-480 + k * 0x1p-532, &wvx, &wvy, &wr, &wrtt);
  }
  for (int i = 0; i < n; i++) {
    check_t(log_uniform(1e-300, 0.5), &wvx, &wvy, &wr, &wrtt);
    check_t(1.0 - log_uniform(0x1p-53, 0.5), &wvx, &wvy, &wr, &wrtt);
    check_t(urand(), &wvx, &wvy, &wr, &wrtt);
    check_t(0.5 + (urand() - 0.5) * ldexp(1.0, -(int)(urand() * 50)), &wvx, &wvy, &wr, &wrtt);
  }

  worst_t wrt = {"ratio_to_t", 0, 0}, wrtr = {"ratio(ratio_to_t(r))", 0, 0};
  const double fixed_r[] = {0x1p-1074, 1e-320, 0x1p-1022, 1e-300, 0x1p-601, 0x1p-600,
                            0x1.0000000000001p-600, 1e-150, 1e-12, 1e-6, 0.5, 1.0 - 0x1p-53, 1.0,
                            1.0 + 0x1p-52, 2.0, 1e6, 1e12, 1e32, 0x1p106, 0x1p108, 1e150,
                            0x1p600, 0x1.0000000000001p600, 1e300, DBL_MAX};
  for (size_t i = 0; i < sizeof fixed_r / sizeof fixed_r[0]; i++) check_r(fixed_r[i], &wrt, &wrtr);
  for (int k = 1; k <= 52; k++) {
    check_r(1.0 - ldexp(1.0, -k), &wrt, &wrtr);
    check_r(1.0 + ldexp(1.0, -k), &wrt, &wrtr);
  }
  for (int i = 0; i < n; i++) {
    check_r(log_uniform(1e-300, 1e300), &wrt, &wrtr);
    check_r(log_uniform(1e-4, 1e4), &wrt, &wrtr);
  }

  /* Probes: the worst inputs found so far by independent searches and by
   * `stability_sweep --samples 3000` (docs/ellipse.md, "Measured accuracy"), checked against the
   * same bounds, plus dense stratified probes of the regions where they sit. */
  const double probe_b[] = {0x1.38033dccb7d4dp-2, 0x1.44e714a865b25p-2, 0x1.3a9ea2b979441p-2,
                            0x1.33ad1e8030728p-1, 0x1.66f2ebf098537p-2};
  for (size_t i = 0; i < sizeof probe_b / sizeof probe_b[0]; i++) check_varx(probe_b[i], &wvarx);
  const double probe_t[] = {0x1.91954faebeb8ep-1, 0x1.8815cb2ff2544p-1, 0x1.69a898ad7ea73p-1,
                            0x1.2aca5dbc5682cp-511, 0x1.27fb224018f7dp-511, 0x1.90a3dc4f43f68p-1,
                            0x1.ba6c8ddf640d2p-3, 0x1.4cbf37298bac4p-512, 0x1.d43aa45d35764p-3,
                            0x1.807a9d7362cf9p-1, 0x1.90ba7af935748p-1, 0x1.1b5c6d182d3fep-512,
                            0x1.cb8b9e9e6eaa4p-3};
  for (size_t i = 0; i < sizeof probe_t / sizeof probe_t[0]; i++)
    check_t(probe_t[i], &wvx, &wvy, &wr, &wrtt);
  const double probe_r[] = {0x1.495db980ef32dp-1, 0x1.b9af19751211ep+0, 0x1.ffffffffe353bp-1,
                            0x1.7a347d84511ffp+0, 0x1.f06a2f853dfc8p+106};
  for (size_t i = 0; i < sizeof probe_r / sizeof probe_r[0]; i++) check_r(probe_r[i], &wrt, &wrtr);
  const int ndense = 3000; /* per region, stratified: one random point in each of ndense cells */
  for (int i = 0; i < ndense; i++) {
    check_varx(0.25 + 0.25 * ((i + urand()) / ndense), &wvarx);          /* b in [1/4, 1/2] */
    check_t(0.5 + 0.5 * ((i + urand()) / ndense), &wvx, &wvy, &wr, &wrtt); /* t in [1/2, 1) */
  }
  for (int i = 0; i < 400; i++) /* t in [2^-512, 2^-510): vy, ratio cross into subnormals */
    check_t(ldexp(1.0 + (i + urand()) / 200.0, -512 + i / 200), &wvx, &wvy, &wr, &wrtt);

  worst_t *all[] = {&wvarx, &wvx, &wvy, &wr, &wsub, &wrt, &wrtt, &wrtr};
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
    printf("%-22s max %.5f ulp at %a (%.17g)\n", all[i]->name, all[i]->worst, all[i]->at,
           all[i]->at);
  mpfr_free_cache();
  return test_summary("test_ellipse");
}
