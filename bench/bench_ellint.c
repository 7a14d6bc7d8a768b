/* bench_ellint.c — speed of K(m), E(m) and K+E (icshadow/ellint.h) side by side with peers,
 * in one run, with ratios.  Parameter convention: m = k^2, m1 = 1 - m.
 *
 * Peers (written here, from the textbook algorithms):
 *   agm      arithmetic-geometric mean in double: K = pi / (2 AGM(1, sqrt(m1))),
 *            E = K (1 - sum 2^(n-1) c_n^2)  (A&S 17.6); K+E from one AGM.
 *   carlson  Carlson's duplication: K = R_F(0, m1, 1), E = R_F - (m/3) R_D(0, m1, 1)
 *            (DLMF 19.25.1; R_F, R_D as in Carlson 1995 / Numerical Recipes, tolerances set
 *            for double); K+E shares R_F.
 *   boost    Boost.Math ellint_1(k), ellint_2(k) (takes the MODULUS k = sqrt(m); default
 *            policy), through bench_ellint_boost.cpp when the headers are found; not for m < 0.
 * Data sets (4096 inputs each, precomputed): m uniform in [0,1); m near 1 (m1 log-uniform in
 * [1e-300, 1e-2], ours through the *_m1 entry points; no Boost: its k = sqrt(m) rounds to 1);
 * m near 1 with k < 1 (m1 log-uniform in [1e-15, 1e-2], Boost included); subnormal m1
 * (binary exponent uniform in [-1074, -1023], random significand; through *_m1, no Boost);
 * m < 0 (m = -10^u, u uniform in [-3, 6]; no Boost: it takes a real modulus), and its two
 * halves: m uniform in (-127, 0] (transformed argument in the pieces) and m = -10^u,
 * u uniform in [2.11, 6] (m < -128: transformed argument in the log series); two edge sets:
 * m1 in the binade [2^-1021, 2^-1020) (random significand, through *_m1: just above the old
 * 2^-1021 outer-factor clamp, where subnormal products used to cost 18-26 ns), m1 in
 * [2^-1019, 2^-1018) (just above the new clamp: the smallest products kept are normal) and subnormal
 * negative m (-2^-1022 < m < 0, exponent uniform, through *_m: 69 ns for K+E before they went
 * to the m >= 0 route).
 * Throughput loop over the array, once to warm up, then REPEAT times; the median, minimum and maximum time
 * per call are reported (cli/bench_stats.c, as every benchmark of the CLI), ratios of the
 * medians, and a warning on stderr when some repetitions spread over 30 % (a busy machine).
 * A checksum of the results is printed so that nothing is optimised away.
 * Output: CSV  dataset,function,impl,ns_per_call,ns_min,ns_max,ratio_to_ours,checksum */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "bench_stats.h"
#include "icshadow/ellint.h"
#include "icshadow/constants.h"

#define N 4096
#define REPEAT 40

#ifdef ICS_BENCH_BOOST
double ics_bench_boost_ellint_1(double k);
double ics_bench_boost_ellint_2(double k);
#endif

#define NOINLINE __attribute__((noinline))

/* ---- peer 1: AGM in double -------------------------------------------------------------- */
static inline void agm_ke(double m1, double *K, double *E) {
  double a = 1.0, b = sqrt(m1), sum = 0.5 * (1.0 - m1), pw = 1.0;
  for (int i = 0; i < 40; i++) {
    double c = 0.5 * (a - b);
    sum += pw * c * c;
    pw *= 2.0;
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
    if (fabs(c) <= 1e-16 * a) break;
  }
  double k = ICS_PI / 2 / a;
  *K = k;
  if (E) *E = k * (1.0 - sum);
}
static NOINLINE double agm_k(double m1) {
  double k;
  agm_ke(m1, &k, NULL);
  return k;
}
static NOINLINE double agm_e(double m1) {
  double k, e;
  agm_ke(m1, &k, &e);
  return e;
}
static NOINLINE void agm_both(double m1, double *k, double *e) { agm_ke(m1, k, e); }

/* ---- peer 2: Carlson R_F, R_D by duplication ----------------------------------------------- */
static inline double carlson_rf(double x, double y, double z) {
  for (;;) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * (sy + sz) + sy * sz;
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    double ave = (x + y + z) * (1.0 / 3.0), inv = 1.0 / ave;
    double dx = (ave - x) * inv, dy = (ave - y) * inv, dz = (ave - z) * inv;
    if (fmax(fmax(fabs(dx), fabs(dy)), fabs(dz)) < 0.0008) {
      double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
      return (1.0 + (e2 * (1.0 / 24.0) - 0.1 - (3.0 / 44.0) * e3) * e2 + e3 * (1.0 / 14.0)) /
             sqrt(ave);
    }
  }
}

static inline double carlson_rd(double x, double y, double z) {
  double sum = 0.0, fac = 1.0;
  for (;;) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * (sy + sz) + sy * sz;
    sum += fac / (sz * (z + lam));
    fac *= 0.25;
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    double ave = 0.2 * (x + y + 3.0 * z), inv = 1.0 / ave;
    double dx = (ave - x) * inv, dy = (ave - y) * inv, dz = (ave - z) * inv;
    if (fmax(fmax(fabs(dx), fabs(dy)), fabs(dz)) < 0.0005) {
      double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6.0 * eb, ee = ed + ec + ec;
      return 3.0 * sum +
             fac *
                 (1.0 + ed * (-3.0 / 14.0 + (9.0 / 88.0) * ed - (9.0 / 52.0) * dz * ee) +
                  dz * (ee / 6.0 + dz * (-(9.0 / 22.0) * ec + dz * (3.0 / 26.0) * ea))) /
                 (ave * sqrt(ave));
    }
  }
}
static NOINLINE double carlson_k(double m1) { return carlson_rf(0.0, m1, 1.0); }
static NOINLINE double carlson_e(double m1) {
  return carlson_rf(0.0, m1, 1.0) - (1.0 - m1) / 3.0 * carlson_rd(0.0, m1, 1.0);
}
static NOINLINE void carlson_both(double m1, double *k, double *e) {
  double rf = carlson_rf(0.0, m1, 1.0);
  *k = rf;
  *e = rf - (1.0 - m1) / 3.0 * carlson_rd(0.0, m1, 1.0);
}

/* ---- timing ------------------------------------------------------------------------------ */
static double now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static double checksum;
static double rep_ns[REPEAT];  /* the last measurement's repetitions */
static cli_spread last;        /* their median, min and max per call */
static int busy;               /* some measurement spread over 30 % */

/* OUT = the median ns per call over the repetitions in rep_ns; `last` keeps the spread */
static double per_call(void) {
  last = cli_spread_of(rep_ns, REPEAT);
  last.min /= N, last.median /= N, last.max /= N;
  if (cli_spread_busy(last)) busy = 1;
  return last.median;
}

#define TIME1(FN, ARR, OUT)                                              \
  do {                                                                   \
    double cs = 0;                                                       \
    for (int rep = -1; rep < REPEAT; rep++) { /* -1: the warm-up */      \
      double t0 = now_ns(), s = 0;                                       \
      for (int i = 0; i < N; i++) s += FN((ARR)[i]);                     \
      if (rep >= 0) rep_ns[rep] = now_ns() - t0;                         \
      cs = s;                                                            \
    }                                                                    \
    checksum = cs;                                                       \
    OUT = per_call();                                                    \
  } while (0)

#define TIME2(FN, ARR, OUT)                                              \
  do {                                                                   \
    double cs = 0;                                                       \
    for (int rep = -1; rep < REPEAT; rep++) { /* -1: the warm-up */      \
      double t0 = now_ns(), s = 0;                                       \
      for (int i = 0; i < N; i++) {                                      \
        double ko_, eo_;                                                 \
        FN((ARR)[i], &ko_, &eo_);                                        \
        s += ko_ + eo_;                                                  \
      }                                                                  \
      if (rep >= 0) rep_ns[rep] = now_ns() - t0;                         \
      cs = s;                                                            \
    }                                                                    \
    checksum = cs;                                                       \
    OUT = per_call();                                                    \
  } while (0)

#ifdef ICS_BENCH_BOOST
static void boost_both(double k, double *K, double *E) {
  *K = ics_bench_boost_ellint_1(k);
  *E = ics_bench_boost_ellint_2(k);
}
#endif

static uint64_t rng = 0x2545f4914f6cdd1dULL;
static double unit(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return (double)(rng >> 11) * 0x1p-53;
}

static double m_[N], m1_[N], k_[N];

static void row(const char *ds, const char *fn, const char *impl, double ns, double ours) {
  printf("%s,%s,%s,%.2f,%.2f,%.2f,%.2f,%.17g\n", ds, fn, impl, ns, last.min, last.max, ns / ours,
         checksum);
}

/* near1: ours through the *_m1 entry points; boost_ok: k = sqrt(m) is meaningful (m in [0,1)
 * and m1 > 1.1e-16: below that k rounds to 1 and Boost returns inf at once, not comparable) */
static void run(const char *ds, int near1, int boost_ok) {
  double ours, t;
  /* K */
  if (near1) TIME1(ics_ellint_k_m1, m1_, ours); else TIME1(ics_ellint_k, m_, ours);
  row(ds, "K", "icshadow", ours, ours);
  TIME1(agm_k, m1_, t);
  row(ds, "K", "agm", t, ours);
  TIME1(carlson_k, m1_, t);
  row(ds, "K", "carlson", t, ours);
#ifdef ICS_BENCH_BOOST
  if (boost_ok) {
    TIME1(ics_bench_boost_ellint_1, k_, t);
    row(ds, "K", "boost", t, ours);
  }
#endif
  /* E */
  if (near1) TIME1(ics_ellint_e_m1, m1_, ours); else TIME1(ics_ellint_e, m_, ours);
  row(ds, "E", "icshadow", ours, ours);
  TIME1(agm_e, m1_, t);
  row(ds, "E", "agm", t, ours);
  TIME1(carlson_e, m1_, t);
  row(ds, "E", "carlson", t, ours);
#ifdef ICS_BENCH_BOOST
  if (boost_ok) {
    TIME1(ics_bench_boost_ellint_2, k_, t);
    row(ds, "E", "boost", t, ours);
  }
#endif
  /* K+E */
  TIME2(ics_ellint_ke_m1, m1_, ours);
  row(ds, "K+E", "icshadow", ours, ours);
  TIME2(agm_both, m1_, t);
  row(ds, "K+E", "agm", t, ours);
  TIME2(carlson_both, m1_, t);
  row(ds, "K+E", "carlson", t, ours);
#ifdef ICS_BENCH_BOOST
  if (boost_ok) {
    TIME2(boost_both, k_, t);
    row(ds, "K+E", "boost", t, ours);
  }
#else
  (void)boost_ok;
#endif
}

int main(void) {
  printf("dataset,function,impl,ns_per_call,ns_min,ns_max,ratio_to_ours,checksum\n");
  for (int i = 0; i < N; i++) {
    m_[i] = unit();
    m1_[i] = 1.0 - m_[i];
    k_[i] = sqrt(m_[i]);
  }
  run("m_uniform_0_1", 0, 1);
  for (int i = 0; i < N; i++) {
    m1_[i] = pow(10.0, -300.0 + 298.0 * unit());
    m_[i] = 1.0 - m1_[i];
    k_[i] = 1.0;
  }
  run("m_near_1", 1, 0);
  for (int i = 0; i < N; i++) { /* where the modulus k = sqrt(1 - m1) is still below 1 */
    m1_[i] = pow(10.0, -15.0 + 13.0 * unit());
    m_[i] = 1.0 - m1_[i];
    k_[i] = sqrt(m_[i]);
  }
  run("m_near_1_k_lt_1", 1, 1);
  for (int i = 0; i < N; i++) { /* subnormal m1 (E = 1, K = ln(16/m1)/2 to double precision) */
    m1_[i] = ldexp(1.0 + unit(), -1074 + (int)(52.0 * unit()));
    if (m1_[i] == 0) m1_[i] = 0x1p-1074;
    m_[i] = 1.0 - m1_[i];
    k_[i] = 1.0;
  }
  run("m1_subnormal", 1, 0);
  for (int i = 0; i < N; i++) {
    m_[i] = -pow(10.0, -3.0 + 9.0 * unit());
    m1_[i] = 1.0 - m_[i];
    k_[i] = 0;
  }
  run("m_negative", 0, 0);
  for (int i = 0; i < N; i++) {
    m_[i] = -127.0 * unit();
    m1_[i] = 1.0 - m_[i];
    k_[i] = 0;
  }
  run("m_negative_pieces", 0, 0);
  for (int i = 0; i < N; i++) {
    m_[i] = -pow(10.0, 2.11 + 3.89 * unit());
    m1_[i] = 1.0 - m_[i];
    k_[i] = 0;
  }
  run("m_negative_log", 0, 0);
  for (int i = 0; i < N; i++) { /* m1 in [2^-1021, 2^-1020) */
    m1_[i] = ldexp(1.0 + unit(), -1021);
    if (m1_[i] >= 0x1p-1020) m1_[i] = 0x1p-1021;
    m_[i] = 1.0 - m1_[i];
    k_[i] = 1.0;
  }
  run("m1_binade_2^-1021", 1, 0);
  for (int i = 0; i < N; i++) { /* m1 in [2^-1019, 2^-1018) */
    m1_[i] = ldexp(1.0 + unit(), -1019);
    if (m1_[i] >= 0x1p-1018) m1_[i] = 0x1p-1019;
    m_[i] = 1.0 - m1_[i];
    k_[i] = 1.0;
  }
  run("m1_binade_2^-1019", 1, 0);
  for (int i = 0; i < N; i++) { /* subnormal negative m */
    m_[i] = -ldexp(1.0 + unit(), -1074 + (int)(52.0 * unit()));
    if (m_[i] == 0) m_[i] = -0x1p-1074;
    m1_[i] = 1.0 - m_[i]; /* = 1 */
    k_[i] = 0;
  }
  run("m_negative_subnormal", 0, 0);
#ifndef ICS_BENCH_BOOST
  fprintf(stderr, "bench_ellint: Boost.Math headers not found at configure time; boost rows omitted\n");
#endif
  if (busy) cli_warn_busy("bench ellint", "ns_min vs ns_max");
  return 0;
}
