/* test_ellint.c — K(m), E(m) (icshadow/ellint.h) against the 320-bit MPFR AGM (ref_mpfr.c).
 *
 * Parameter convention: m = k^2, m1 = 1 - m.
 * Usage: test_ellint [--exhaustive] [--focus log|neg] [--n N] [SEED]
 *   default: ~10^5 MPFR comparisons (label fast, also run under ASan+UBSan);
 *   --exhaustive: 3 * 10^6 random inputs (label exhaustive);
 *   --focus log: the random inputs only in the log-series region (m1 < X0, both entry points,
 *     subnormals included); --focus neg: only m < 0 (pieces of 1/m1, log series, scaled);
 *   --n N: N random inputs (each checked for K and E).
 * Random inputs are weighted toward m -> 1 (log-uniform m1 down to the smallest subnormal)
 * and toward large negative m (log-uniform down to -DBL_MAX); both sides (+-8 ulps) of every
 * algorithm switch in ellint.c are tested, and the worst inputs in ellint_worst.h.
 * The thresholds are the bounds documented in ellint.c and docs/ellint.md. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/ellint.h"
#include "ellint_data.h" /* switch points: ICS_ELLINT_X0_LOG2, ICS_ELLINT_S */
#include "ref_mpfr.h"
#include "testutil.h"

#define BOUND_K 0.60 /* ulp: the documented bound (ellint.c header, docs/ellint.md) */
#define BOUND_E 0.60
/* Regression tripwires below the contract, per region (K and E alike): where the measured
 * maxima are <= 0.531 ulp (log series, all m < 0 routes), an error above TRIP means the code
 * got worse although it may still be inside the 0.60 contract (e.g. the 26-bit mask on 1/m1
 * dropped: 0.59 ulp on the m < 0 pieces).  The pieces (measured 0.536) keep the contract. */
#define TRIP 0.55

/* ---- RNG: splitmix64 from testutil.h (test_rng_u64, test_rng_unit, test_rng_state) ---- */
/* log-uniform: binary exponent uniform in [emin, emax], random mantissa; subnormals included */
static double rng_logu(int emin, int emax) {
  int e = emin + (int)(test_rng_u64() % (uint64_t)(emax - emin + 1));
  double f = 1.0 + (double)(test_rng_u64() >> 12) * 0x1p-52;
  double v = ldexp(f, e); /* correctly rounded into the subnormal range */
  return v > 0 ? v : 0x1p-1074;
}

/* ---- statistics per (entry, function, region) ------------------------------------------- */
enum { F_K, F_E, NF };
static const char *fname[NF] = {"K", "E"};
enum { R_SUB, R_LOG, R_PIECE, R_NEGPIECE, R_NEGLOG, R_HUGE, NR };
static const char *rname[NR] = {
    "m1 in (0, 2^-1022)   log series, subnormal",
    "m1 in [2^-1022, X0)  log series",
    "m1 in [X0, 1]        pieces",
    "m1 in (1, 1/X0]      m<0: pieces of 1/m1",
    "m1 in (1/X0, 2^512]  m<0: log series",
    "m1 > 2^512           m<0: scaled sqrt",
};
enum { E_M1, E_M, NE_ };
static const char *ename[NE_] = {"m1 entry", "m entry"};
static double worst_err[NE_][NF][NR];
static double worst_in[NE_][NF][NR];
static long count[NE_][NR];

static int region_of(double m1) {
  if (m1 < 0x1p-1022) return R_SUB;
  if (m1 < ICS_ELLINT_X0) return R_LOG;
  if (m1 <= 1.0) return R_PIECE;
  if (m1 <= 1.0 / ICS_ELLINT_X0) return R_NEGPIECE;
  if (m1 <= 0x1p512) return R_NEGLOG;
  return R_HUGE;
}

/* per-region threshold: the tripwire where the region has the margin, else the contract */
static const double region_trip[NR] = {TRIP, TRIP, 0.60, TRIP, TRIP, TRIP};

static mpfr_t rK, rE, rm1;

static void record(int entry, int f, int reg, double err, double input, double got) {
  if (err > worst_err[entry][f][reg] || (err != err)) {
    worst_err[entry][f][reg] = err;
    worst_in[entry][f][reg] = input;
  }
  double bound = f == F_K ? BOUND_K : BOUND_E;
  CHECK(err <= bound, "%s(%s %a = %.17g) = %.17g: %.4f ulp > %.2f", fname[f], ename[entry],
        input, input, got, err, bound);
  double trip = region_trip[reg] < bound ? region_trip[reg] : bound;
  CHECK(err <= trip || err > bound,
        "%s(%s %a = %.17g) = %.17g: %.4f ulp > %.2f, the regression tripwire of region '%s' "
        "(measured maxima there <= 0.531; contract %.2f)",
        fname[f], ename[entry], input, input, got, err, trip, rname[reg], bound);
}

/* test the m1 entry points at m1 (> 0, finite) */
static void test_m1(double m1) {
  mpfr_set_d(rm1, m1, MPFR_RNDN);
  ref_ellipke_m1(rK, rE, rm1);
  int reg = region_of(m1);
  double k = ics_ellint_k_m1(m1), e = ics_ellint_e_m1(m1), k2 = -1, e2 = -1;
  ics_ellint_ke_m1(m1, &k2, &e2);
  count[E_M1][reg]++;
  record(E_M1, F_K, reg, ref_ulp_error(k, rK), m1, k);
  record(E_M1, F_E, reg, ref_ulp_error(e, rE), m1, e);
  CHECK(memcmp(&k, &k2, sizeof k) == 0 && memcmp(&e, &e2, sizeof e) == 0,
        "ics_ellint_ke_m1(%a) = (%a, %a) differs from ics_ellint_k_m1/ics_ellint_e_m1 (%a, %a)", m1,
        k2, e2, k, e);
}

/* test the m entry points at m (< 1, finite); the reference gets 1 - m exactly */
static void test_m(double m) {
  mpfr_set_d(rm1, m, MPFR_RNDN);
  mpfr_ui_sub(rm1, 1, rm1, MPFR_RNDN); /* exact: rm1 has 2200 bits */
  ref_ellipke_m1(rK, rE, rm1);
  double m1r = mpfr_get_d(rm1, MPFR_RNDN);
  int reg = region_of(m1r);
  double k = ics_ellint_k(m), e = ics_ellint_e(m);
  count[E_M][reg]++;
  record(E_M, F_K, reg, ref_ulp_error(k, rK), m, k);
  record(E_M, F_E, reg, ref_ulp_error(e, rE), m, e);
  /* where 1 - m is exact, the m and m1 entry points must agree bit for bit */
  if (mpfr_cmp_d(rm1, m1r) == 0) {
    double k1 = ics_ellint_k_m1(m1r), e1 = ics_ellint_e_m1(m1r);
    CHECK(memcmp(&k, &k1, sizeof k) == 0 && memcmp(&e, &e1, sizeof e) == 0,
          "ics_ellint_k/e(%a) = (%a, %a) but ics_ellint_k/e_m1(%a) = (%a, %a)", m, k, e, m1r, k1,
          e1);
  }
}

/* x and up to n ulps either side, through both entry points where it makes sense */
static void around_m1(double x, int n) {
  double v = x;
  for (int i = 0; i < n; i++) v = nextafter(v, 0.0);
  for (int i = 0; i <= 2 * n; i++, v = nextafter(v, INFINITY)) {
    if (v > 0 && v < INFINITY) {
      test_m1(v);
      if (1.0 - v < 1.0) test_m(1.0 - v); /* m = 1 - v, exact or rounded */
    }
  }
}

static void around_m(double m, int n) {
  double v = m;
  for (int i = 0; i < n; i++) v = nextafter(v, -INFINITY);
  for (int i = 0; i <= 2 * n; i++, v = nextafter(v, INFINITY))
    if (v < 1 && v > -INFINITY) test_m(v);
}

static void test_switches(void) {
  /* pieces: boundaries a (1 + j/2^S) of the binades [X0, 2 X0) ... [1/2, 1]; x = X0 is the
   * log-series / pieces switch, x = 1 the m = 0 point (pos / neg routes) */
  const int ns = 1 << ICS_ELLINT_S;
  for (int b = -ICS_ELLINT_X0_LOG2; b >= 1; b--) {
    double a = ldexp(1.0, -b);
    for (int j = 0; j <= ns; j++) {
      double x = a * (1.0 + (double)j / ns);
      around_m1(x, 8);
      around_m1(1.0 / x, 8); /* same boundaries reached through 1/m1 on the m < 0 route */
    }
  }
  around_m1(1.0 / ICS_ELLINT_X0, 8); /* m < 0: pieces of 1/m1 / log series of ln(16 m1) */
  around_m(1.0 - 1.0 / ICS_ELLINT_X0, 8);
  around_m1(0x1p512, 8);       /* m < 0: scaled square root */
  around_m(-0x1p512, 8);
  around_m1(0x1p-1022, 8);     /* subnormal rescaling in the logarithm */
  around_m1(0x1p-64, 8);       /* polynomial argument clamp */
  around_m1(0x1p-1019, 8);     /* outer factor x clamp */
  around_m1(0x1p-1021, 8);     /* the old outer clamp (now inside the clamped range) */
  around_m(-0x1p-60, 8);       /* tiny m < 0: m >= 0 route above, transformation below */
  around_m1(1.0, 16);          /* m = 0 */
  around_m(0.0, 8);            /* m = 0 from both sides (tiny negative m) */
  around_m(0.5, 8);            /* 1 - m exact / rounded */
  around_m(-0x1p-1074, 0);
  around_m(-DBL_MIN, 4);
  around_m(1.0 - 0x1p-53, 0);  /* largest m < 1 */
  around_m1(0x1p-1074, 8);     /* smallest subnormals */
  around_m1(DBL_MAX, 8);       /* m -> -DBL_MAX */
  around_m(-DBL_MAX, 4);
  around_m(-1e300, 4);
}

/* The inline logarithm's table: both ends of each of its ICS_ELLINT_LOG_N intervals of z in
 * [sqrt(1/2), sqrt(2)) (bit patterns LOG_OFF + i 2^(52 - LOG_B)), scaled into the log region
 * (m1 < X0, normal and subnormal) and into the m < 0 log route (m1 > 1/X0). */
static void test_log_table_ends(void) {
  const int exps_small[] = {-8, -9, -40, -300, -1000, -1022};
  const int exps_big[] = {8, 9, 60, 511, 512, 513, 1000};
  for (int i = 0; i <= ICS_ELLINT_LOG_N; i++) {
    uint64_t b = ICS_ELLINT_LOG_OFF + ((uint64_t)i << (52 - ICS_ELLINT_LOG_B));
    double z;
    memcpy(&z, &b, sizeof z); /* i = LOG_N: sqrt(2), the next binade's sqrt(1/2) times 2 */
    for (size_t j = 0; j < sizeof exps_small / sizeof exps_small[0]; j++) {
      double x = ldexp(z, exps_small[j]);
      if (x < ICS_ELLINT_X0) around_m1(x, 2);
    }
    for (size_t j = 0; j < sizeof exps_big / sizeof exps_big[0]; j++) around_m1(ldexp(z, exps_big[j]), 2);
    /* subnormal m1 whose rescaled significand lands on the interval ends */
    around_m1(ldexp(z, -1060), 1);
  }
}

/* The logarithm's table itself against MPFR's log: an error of lhi + llo is worth at most
 * ~0.06 ulp of K (2^-54 in L), too little to show in the ulp checks reliably, so each entry is
 * checked directly: |lhi + llo - ln c| <= 2^-80 (the generator makes them within 2^-87), lhi a
 * multiple of 2^-32, |c invc - 1| <= 2^-52. */
static void test_log_table(void) {
  mpfr_t a, b;
  mpfr_inits2(REF_PREC, a, b, (mpfr_ptr)0);
  for (int i = 0; i < ICS_ELLINT_LOG_N; i++) {
    const struct ics_ellint_lnc *t = &ics_ellint_lnc[i];
    mpfr_set_d(a, t->c, MPFR_RNDN);
    mpfr_log(a, a, MPFR_RNDN);
    mpfr_sub_d(a, a, t->lhi, MPFR_RNDN);
    mpfr_sub_d(a, a, t->llo, MPFR_RNDN);
    double d = fabs(mpfr_get_d(a, MPFR_RNDN));
    CHECK(d <= 0x1p-80, "log table entry %d (c = %a): |lhi + llo - ln c| = %a > 2^-80", i, t->c, d);
    CHECK(ldexp(t->lhi, 32) == nearbyint(ldexp(t->lhi, 32)), "log table entry %d: lhi = %a is not "
          "a multiple of 2^-32", i, t->lhi);
    mpfr_set_d(b, t->c, MPFR_RNDN);
    mpfr_mul_d(b, b, t->invc, MPFR_RNDN); /* exact at REF_PREC */
    mpfr_sub_ui(b, b, 1, MPFR_RNDN);
    d = fabs(mpfr_get_d(b, MPFR_RNDN));
    CHECK(d <= 0x1p-52, "log table entry %d: |c invc - 1| = %a > 2^-52", i, d);
  }
  mpfr_clears(a, b, (mpfr_ptr)0);
}

/* m < 0 where the square root or the reciprocal is exact or nearly so (the 26-bit heads are
 * then the whole value or the tails vanish): m1 = 2^k, j^2, 1/(2^k) inverses, j^2 +- 1 ulp. */
static void test_neg_exact_cases(void) {
  for (int k = 1; k <= 1023; k++) around_m1(ldexp(1.0, k), 1);
  for (int j = 2; j <= 3000; j += (j < 100 ? 1 : 37)) {
    double v = (double)j * (double)j;
    around_m1(v, 1);
    around_m(1.0 - v, 1);
  }
}

/* Both sides of the two speed switches, densely: m1 log-uniform in [2^-1023, 2^-1016] (outer
 * factor x dropped below 2^-1019, kept above) and m = -2^u, u in [-1074, -40] (m >= 0 route
 * above -2^-60, transformation below), and m in (-2^-50, 2^-50) uniformly. */
static void test_speed_switches(void) {
  for (int i = 0; i < 3000; i++) {
    test_m1(rng_logu(-1023, -1017));
    test_m(-rng_logu(-1074, -40));
    test_m(0x1p-50 * (2.0 * test_rng_unit() - 1.0));
  }
}

#include "ellint_worst.h"

static int focus; /* 0: all regions, 1: log series, 2: m < 0 */

static void test_random(long n) {
  for (long i = 0; i < n; i++) {
    if (focus == 1) { /* m1 < X0: a quarter each subnormal, normal, near X0, through m */
      switch (i % 4) {
        case 0: test_m1(rng_logu(-1074, -1023)); break;
        case 1: test_m1(rng_logu(-1022, ICS_ELLINT_X0_LOG2 - 1)); break;
        case 2: test_m1(rng_logu(-64, ICS_ELLINT_X0_LOG2 - 1)); break;
        default: test_m(1.0 - rng_logu(-53, ICS_ELLINT_X0_LOG2 - 1)); break;
      }
      continue;
    }
    if (focus == 2) { /* m < 0: a sixth each for (m1 | m entry) x (pieces | log | scaled) */
      const int lg = -ICS_ELLINT_X0_LOG2; /* m1 = 2^lg = 1/X0 */
      switch (i % 6) {
        case 0: test_m1(i % 12 ? 1.0 + rng_logu(-52, lg - 1) : 1.0 + (1.0 / ICS_ELLINT_X0 - 1.0) * test_rng_unit()); break;
        case 1: test_m1(rng_logu(lg, 511)); break;
        case 2: test_m1(rng_logu(512, 1023)); break;
        case 3: test_m(i % 12 ? -rng_logu(-52, lg - 1) : -(1.0 / ICS_ELLINT_X0 - 1.0) * test_rng_unit()); break;
        case 4: test_m(-rng_logu(lg, 511)); break;
        default: test_m(-rng_logu(512, 1023)); break;
      }
      continue;
    }
    switch (i % 8) {
      case 0: test_m1(rng_logu(-1074, -1)); break;           /* m -> 1, down to subnormals */
      case 1: test_m1(rng_logu(-60, -1)); break;
      case 2: test_m1(test_rng_unit() + 0x1p-60); break;          /* m1 uniform in (0, 1] */
      case 3: test_m1(1.0 + rng_logu(-1074, 1023)); break;   /* m < 0, log-uniform */
      case 4: test_m(test_rng_unit()); break;                     /* m uniform in [0, 1) */
      case 5: test_m(1.0 - rng_logu(-53, -1)); break;        /* m -> 1 through m */
      case 6: test_m(-rng_logu(-1074, 1023)); break;         /* m < 0 down to -DBL_MAX */
      default: test_m(-40.0 * test_rng_unit()); break;            /* m in (-40, 0] */
    }
  }
}

static void test_special(void) {
  mpfr_t pi2;
  mpfr_init2(pi2, REF_PREC);
  mpfr_const_pi(pi2, MPFR_RNDN);
  mpfr_div_2ui(pi2, pi2, 1, MPFR_RNDN);
  double pi2d = mpfr_get_d(pi2, MPFR_RNDN); /* pi/2 correctly rounded */
  mpfr_clear(pi2);
  CHECK(ics_ellint_k(0.0) == pi2d, "K(0) = %a, want %a", ics_ellint_k(0.0), pi2d);
  CHECK(ics_ellint_e(0.0) == pi2d, "E(0) = %a, want %a", ics_ellint_e(0.0), pi2d);
  CHECK(ics_ellint_k(-0.0) == pi2d, "K(-0) = %a", ics_ellint_k(-0.0));
  CHECK(ics_ellint_e(-0.0) == pi2d, "E(-0) = %a", ics_ellint_e(-0.0));
  CHECK(ics_ellint_k_m1(1.0) == pi2d, "K_m1(1) = %a", ics_ellint_k_m1(1.0));
  CHECK(ics_ellint_e_m1(1.0) == pi2d, "E_m1(1) = %a", ics_ellint_e_m1(1.0));

  CHECK(isinf(ics_ellint_k(1.0)) && ics_ellint_k(1.0) > 0, "K(1) = %g", ics_ellint_k(1.0));
  CHECK(ics_ellint_e(1.0) == 1.0, "E(1) = %g", ics_ellint_e(1.0));
  CHECK(isinf(ics_ellint_k_m1(0.0)) && ics_ellint_k_m1(0.0) > 0, "K_m1(0) = %g",
        ics_ellint_k_m1(0.0));
  CHECK(ics_ellint_e_m1(0.0) == 1.0, "E_m1(0) = %g", ics_ellint_e_m1(0.0));
  CHECK(isinf(ics_ellint_k_m1(-0.0)) && ics_ellint_e_m1(-0.0) == 1.0, "m1 = -0");

  const double bad_m[] = {nextafter(1.0, 2.0), 1.5, 2.0, 1e300, INFINITY, NAN, -NAN};
  for (size_t i = 0; i < sizeof bad_m / sizeof bad_m[0]; i++) {
    double m = bad_m[i];
    CHECK(isnan(ics_ellint_k(m)), "K(%g) = %g, want NaN", m, ics_ellint_k(m));
    CHECK(isnan(ics_ellint_e(m)), "E(%g) = %g, want NaN", m, ics_ellint_e(m));
    double m1 = (m != m) ? m : 1.0 - m; /* < 0 */
    if (m1 == 0) m1 = -0x1p-1074;
    CHECK(isnan(ics_ellint_k_m1(m1)), "K_m1(%g) = %g, want NaN", m1, ics_ellint_k_m1(m1));
    CHECK(isnan(ics_ellint_e_m1(m1)), "E_m1(%g) = %g, want NaN", m1, ics_ellint_e_m1(m1));
    double k = 0, e = 0;
    ics_ellint_ke_m1(m1, &k, &e);
    CHECK(isnan(k) && isnan(e), "ics_ellint_ke_m1(%g) = (%g, %g), want NaN", m1, k, e);
  }
  CHECK(isnan(ics_ellint_k_m1(-0x1p-1074)) && isnan(ics_ellint_e_m1(-INFINITY)), "m1 < 0");

  CHECK(ics_ellint_k(-INFINITY) == 0.0, "K(-inf) = %g", ics_ellint_k(-INFINITY));
  CHECK(isinf(ics_ellint_e(-INFINITY)) && ics_ellint_e(-INFINITY) > 0, "E(-inf) = %g",
        ics_ellint_e(-INFINITY));
  CHECK(ics_ellint_k_m1(INFINITY) == 0.0, "K_m1(inf) = %g", ics_ellint_k_m1(INFINITY));
  CHECK(isinf(ics_ellint_e_m1(INFINITY)), "E_m1(inf) = %g", ics_ellint_e_m1(INFINITY));

  /* NULL outputs */
  double k = 0, e = 0;
  ics_ellint_ke_m1(0.25, &k, NULL);
  CHECK(k == ics_ellint_k_m1(0.25), "ke_m1(K only)");
  ics_ellint_ke_m1(0.25, NULL, &e);
  CHECK(e == ics_ellint_e_m1(0.25), "ke_m1(E only)");
  ics_ellint_ke_m1(0.25, NULL, NULL);
  ics_ellint_ke_m1(INFINITY, &k, &e);
  CHECK(k == 0.0 && isinf(e), "ke_m1(inf) = (%g, %g)", k, e);
  ics_ellint_ke_m1(0.0, &k, &e);
  CHECK(isinf(k) && e == 1.0, "ke_m1(0) = (%g, %g)", k, e);

  /* monotonicity near the ends: K increases and E decreases with m */
  double prevk = 0, preve = INFINITY;
  for (double x = 0x1p-1074; x < 2; x *= 1.7) { /* m1 decreasing order reversed: x grows */
    double kk = ics_ellint_k_m1(x), ee = ics_ellint_e_m1(x);
    if (x > 0x1p-1074) {
      CHECK(kk <= prevk, "K_m1 not decreasing at m1 = %a", x);
      CHECK(ee >= preve, "E_m1 not increasing at m1 = %a", x);
    }
    prevk = kk;
    preve = ee;
  }
}

/* Legendre's relation E K' + E' K - K K' = pi/2 (K' = K(m1)); a property check of the
 * m1 entry points at x and 1 - x (x dyadic so both are exact). With |errors| <= 0.6 ulp
 * in each value, the residual is below 3 * 2^-52 * (|E K'| + |E' K| + |K K'|). */
static void test_legendre(long n) {
  double worst = 0, worst_x = 0;
  for (long i = 0; i < n; i++) {
    double x = (i % 2) ? rng_logu(-60, -2) : ldexp((double)(test_rng_u64() >> 11), -53);
    if (x <= 0) continue;
    double y = 1.0 - x; /* exact for dyadic x with <= 53 bits below 1 */
    if (1.0 - y != x) continue;
    double K, E, Kp, Ep;
    ics_ellint_ke_m1(x, &K, &E);   /* m = y */
    ics_ellint_ke_m1(y, &Kp, &Ep); /* m = x */
    long double r = (long double)E * Kp + (long double)Ep * K - (long double)K * Kp;
    double scale = fabs(E * Kp) + fabs(Ep * K) + fabs(K * Kp);
    double res = fabs((double)(r - 1.5707963267948966192313216916397514L));
    double rel = res / (0x1p-52 * scale);
    if (rel > worst) {
      worst = rel;
      worst_x = x;
    }
    CHECK(rel <= 3.0, "Legendre relation at m1 = %a: residual %.3g = %.3g * 2^-52 * scale", x,
          res, rel);
  }
  printf("Legendre relation: worst residual %.3f * 2^-52 * (|EK'|+|E'K|+|KK'|) at m1 = %a\n",
         worst, worst_x);
}

static void test_errno(void) {
  errno = 0;
  volatile double s = 0;
  const double v[] = {-INFINITY, -1e308, -1, -0.0, 0, 0.5, 1, 1.5, INFINITY, NAN, 0x1p-1074};
  for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
    double k, e;
    s += ics_ellint_k(v[i]) + ics_ellint_e(v[i]) + ics_ellint_k_m1(v[i]) + ics_ellint_e_m1(v[i]);
    ics_ellint_ke_m1(v[i], &k, &e);
    s += k + e;
  }
  (void)s;
  CHECK(errno == 0, "errno = %d after special inputs", errno);
}

int main(int argc, char **argv) {
  long n = 60000; /* MPFR comparisons in the random part (fast label) */
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--exhaustive") == 0) n = 3000000;
    else if (strcmp(argv[i], "--focus") == 0 && i + 1 < argc) {
      i++;
      focus = strcmp(argv[i], "log") == 0 ? 1 : strcmp(argv[i], "neg") == 0 ? 2 : -1;
      if (focus < 0) {
        fprintf(stderr, "test_ellint: --focus takes log or neg, not '%s'\n", argv[i]);
        return 2;
      }
    } else if (strcmp(argv[i], "--n") == 0 && i + 1 < argc) {
      char *end;
      n = strtol(argv[++i], &end, 10);
      if (*end || n < 0) {
        fprintf(stderr, "test_ellint: --n takes a count, not '%s'\n", argv[i]);
        return 2;
      }
    } else test_rng_state ^= (uint64_t)strtoull(argv[i], NULL, 0);
  }
  mpfr_inits2(REF_PREC, rK, rE, (mpfr_ptr)0);
  mpfr_init2(rm1, 2200);

  test_special();
  test_errno();
  test_switches();
  test_log_table();
  test_log_table_ends();
  test_neg_exact_cases();
  test_speed_switches();
  for (size_t i = 0; i < sizeof ellint_worst_m1 / sizeof ellint_worst_m1[0]; i++)
    test_m1(ellint_worst_m1[i]);
  for (size_t i = 0; i < sizeof ellint_worst_m / sizeof ellint_worst_m[0]; i++)
    test_m(ellint_worst_m[i]);
  test_random(n);
  test_legendre(n / 10);

  printf("max error in ulps against MPFR (bounds: K %.2f, E %.2f; tripwire %.2f outside the "
         "m1 in [X0, 1] pieces; X0 = %a), worst inputs:\n",
         BOUND_K, BOUND_E, TRIP, ICS_ELLINT_X0);
  for (int en = 0; en < NE_; en++)
    for (int r = 0; r < NR; r++) {
      if (!count[en][r]) continue;
      printf("  %-8s %-42s n=%-8ld K %.4f at %-24a E %.4f at %a\n", ename[en], rname[r],
             count[en][r], worst_err[en][F_K][r], worst_in[en][F_K][r], worst_err[en][F_E][r],
             worst_in[en][F_E][r]);
    }
  mpfr_clears(rK, rE, rm1, (mpfr_ptr)0);
  mpfr_free_cache();
  return test_summary("test_ellint");
}
