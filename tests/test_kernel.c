/* test_kernel.c — kernel equivalence classes: every member's moments equal its class.
 *
 * Deterministic members: total weight 1, mean and variance equal to the target within a
 * rounding bound (64 eps relative to the scale |mu| + sigma + 1 for the mean, 1e-13 relative
 * for the variance: tens of terms summed with compensated sums).
 * Stochastic members: the per-iteration realised moments are checked against their exact
 * expectation formula (kernel.h) by the sample average over M iterations from a fixed seed,
 * within 5 standard deviations (the sd from the closed form where one is stated, else from the
 * sample itself). Expected values are derived in this file (formulas, quadrature), not read from
 * the library. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

#define EPS 2.220446049250313e-16
#define CAP 70000

static ics_tap1d t1[CAP];
static ics_tap2d t2[CAP];

static int near_rel(double a, double b, double rel, double scale) {
  return fabs(a - b) <= rel * scale;
}

/* ---------------------------------------------------------------- 1D deterministic */
static void check_member1d(ics_kernel_member m, double mu, double var, int nsamples) {
  ics_kernel1d k;
  ics_status st = ics_kernel1d_init(&k, m, mu, var);
  k.nsamples = nsamples;
  CHECK(st == ICS_OK, "init %s", ics_status_str(st));
  int n = 0;
  st = ics_kernel1d_taps(&k, 0, t1, CAP, &n);
  CHECK(st == ICS_OK, "%s mu %g var %g: %s", ics_kernel_member_name(m), mu, var, ics_status_str(st));
  if (st != ICS_OK) return;
  CHECK(n >= 1 && n <= ics_kernel1d_max_taps(&k), "%s: %d taps, max %d", ics_kernel_member_name(m),
        n, ics_kernel1d_max_taps(&k));
  double W, M, V;
  ics_taps1d_moments(t1, n, &W, &M, &V);
  double scale = fabs(mu) + sqrt(var) + 1;
  CHECK(fabs(W - 1) <= 64 * EPS, "%s mu %g var %g: weight sum %.17g", ics_kernel_member_name(m), mu,
        var, W);
  CHECK(near_rel(M, mu, 64 * EPS, scale), "%s mu %g var %g: mean %.17g",
        ics_kernel_member_name(m), mu, var, M);
  /* variance: 1e-13 relative, plus the positions' rounding (|mu| + 1) eps times 2 sigma */
  CHECK(fabs(V - var) <= 1e-13 * var + 8 * EPS * (fabs(mu) + 1) * sqrt(var),
        "%s mu %g var %g: variance %.17g (diff %.3g)", ics_kernel_member_name(m), mu, var, V, V - var);
  for (int j = 0; j < n; j++)
    if (!(t1[j].w >= 0)) {
      CHECK(0, "%s: negative weight %g", ics_kernel_member_name(m), t1[j].w);
      break;
    }
}

static void test_deterministic1d(void) {
  const double mus[] = {0, 0.3, 0.5, -2.7, 1000.25};
  const double vars[] = {0, 0.05, 0.25, 1, 7.3, 30};
  for (size_t i = 0; i < sizeof mus / sizeof *mus; i++)
    for (size_t j = 0; j < sizeof vars / sizeof *vars; j++) {
      double mu = mus[i], var = vars[j];
      check_member1d(ICS_KERNEL_DIRAC, mu, var, 0);
      check_member1d(ICS_KERNEL_GAUSS, mu, var, 0);
      check_member1d(ICS_KERNEL_GAUSS, mu, var, 4);
      check_member1d(ICS_KERNEL_GAUSS, mu, var, 19);
      double f = mu - floor(mu);
      if (var >= f * (1 - f)) {
        check_member1d(ICS_KERNEL_TOPHAT, mu, var, 0);
      } else {
        ics_kernel1d k;
        ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, mu, var);
        int n;
        ics_status st = ics_kernel1d_taps(&k, 0, t1, CAP, &n);
        CHECK(st == ICS_ERR_RANGE, "tophat below f(1-f): mu %g var %g gives %s", mu, var,
              ics_status_str(st));
      }
    }
  /* Dirac: the taps are exactly mu -+ sigma */
  ics_kernel1d k;
  int n;
  ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0.25, 2.25);
  ics_kernel1d_taps(&k, 0, t1, CAP, &n);
  CHECK(n == 2 && t1[0].x == -1.25 && t1[1].x == 1.75 && t1[0].w == 0.5 && t1[1].w == 0.5,
        "dirac taps");
  /* Gauss: equally spaced, weights exp(-z^2/2) in units of the spacing */
  ics_kernel1d_init(&k, ICS_KERNEL_GAUSS, 0, 4);
  k.nsamples = 7;
  k.param = 2.5;
  ics_kernel1d_taps(&k, 0, t1, CAP, &n);
  double h = t1[1].x - t1[0].x, s = h * 6 / (2 * 2.5); /* z spacing 2T/(N-1) maps to h */
  int shape_ok = n == 7;
  for (int j = 0; j < n && shape_ok; j++) {
    double z = -2.5 + 5.0 * j / 6;
    if (fabs(t1[j].x - z * s) > 1e-13 * 4) shape_ok = 0;
    if (fabs(t1[j].w / t1[3].w - exp(-0.5 * z * z)) > 1e-14) shape_ok = 0;
  }
  CHECK(shape_ok, "gauss shape: equally spaced, Gaussian weights");
}

/* E over the box [m - W/2, m + W/2] of f(1 - f), by the midpoint rule (independent of kernel.c) */
static double box_interp_quad(double m, double W) {
  const int N = 200000;
  double s = 0;
  for (int i = 0; i < N; i++) {
    double t = m - W / 2 + W * (i + 0.5) / N, f = t - floor(t);
    s += f * (1 - f);
  }
  return s / N;
}

static void test_tophat(void) {
  /* raw box (param 1): discrete variance = W^2/12 + E_box[f(1-f)]; weights = box * hat */
  const double cases[][2] = {{0, 1}, {0.3, 2.5}, {0.5, 30}, {-1.75, 0.4}, {0.1, 0.02}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
    double mu = cases[i][0], var = cases[i][1], W = sqrt(12 * var);
    ics_kernel1d k;
    ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, mu, var);
    k.param = 1;
    int n;
    ics_status st = ics_kernel1d_taps(&k, 0, t1, CAP, &n);
    CHECK(st == ICS_OK, "raw tophat: %s", ics_status_str(st));
    double Wt, M, V;
    ics_taps1d_moments(t1, n, &Wt, &M, &V);
    double expect = var + box_interp_quad(mu - floor(mu), W);
    CHECK(fabs(V - expect) < 1e-8, "raw tophat mu %g var %g: variance %.12g, quadrature %.12g", mu,
          var, V, expect);
    CHECK(fabs(M - mu) < 1e-13 * (1 + fabs(mu)), "raw tophat mean %.17g", M);
    double ev;
    ics_kernel1d_expected(&k, NULL, &ev);
    CHECK(fabs(ev - expect) < 1e-8, "raw tophat expected() %.12g vs quadrature %.12g", ev, expect);
    /* one weight against quadrature of box(t) hat(t - j) */
    int j = n / 2;
    double x = t1[j].x, q = 0;
    const int Q = 200000;
    for (int s = 0; s < Q; s++) {
      double t = mu - W / 2 + W * (s + 0.5) / Q, hv = 1 - fabs(t - x);
      q += hv > 0 ? hv : 0;
    }
    q /= Q;
    CHECK(fabs(t1[j].w - q) < 1e-8, "tophat weight at %g: %.12g, quadrature %.12g", x, t1[j].w, q);
    for (int a = 0; a < n; a++)
      if (t1[a].x != floor(t1[a].x)) {
        CHECK(0, "tophat tap not on the grid: %g", t1[a].x);
        break;
      }
  }
  /* Table I: the exact grid box for sigma^2 = 30 spans about sqrt(12) sigma = 19 pixels */
  ics_kernel1d k;
  ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, 0, 30);
  int n;
  ics_kernel1d_taps(&k, 0, t1, CAP, &n);
  CHECK(n >= 19 && n <= 21, "tophat sigma^2 = 30: %d taps", n);
}

/* ---------------------------------------------------------------- stochastic Dirac */
/* tiny variances: the top-hat's box narrower than 1e-6 px is applied as its W -> 0 limit (the
 * weights' cancellation would otherwise give no taps at all); the Gaussian member with a
 * truncation so small that its scale overflows is rejected instead of returning inf taps */
static void test_tiny(void) {
  ics_kernel1d k;
  ics_tap1d t[16];
  int n = 0;
  double w, m, v;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, 0, 1e-300) == ICS_OK, "tophat 1e-300 init");
  CHECK(ics_kernel1d_taps(&k, 0, t, 16, &n) == ICS_OK && n >= 1, "tophat 1e-300 taps (n = %d)", n);
  ics_taps1d_moments(t, n, &w, &m, &v);
  CHECK(w == 1 && m == 0 && fabs(v - 1e-300) <= 1e-13, "tophat 1e-300: w %g m %g v %g", w, m, v);
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, 0.25, 0.1875 + 1e-14) == ICS_OK, "tophat f(1-f)");
  CHECK(ics_kernel1d_taps(&k, 0, t, 16, &n) == ICS_OK, "tophat at f(1-f) + 1e-14");
  ics_taps1d_moments(t, n, &w, &m, &v);
  CHECK(fabs(m - 0.25) <= 1e-15 && fabs(v - 0.1875) <= 1e-13, "tophat near f(1-f): m %g v %.17g", m, v);
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_GAUSS, 0, 1) == ICS_OK, "gauss init");
  k.param = 1e-300;
  CHECK(ics_kernel1d_taps(&k, 0, t, 16, &n) == ICS_ERR_RANGE, "gauss T = 1e-300: no inf taps");
}

static void test_stoch_dirac(void) {
  const double cases[][3] = {{0, 30, 1}, {0.3, 1, 1}, {-0.5, 0.1, 1}, {2, 4, 0.5}};
  for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
    double mu = cases[c][0], var = cases[c][1], h = cases[c][2];
    ics_kernel1d k;
    ics_kernel1d_init(&k, ICS_KERNEL_STOCH_DIRAC, mu, var);
    k.param = h;
    k.seed = 42 + c;
    double he = h < sqrt(3 * var) ? h : sqrt(3 * var);
    double rho = sqrt(var - he * he / 3 > 0 ? var - he * he / 3 : 0);
    const int M = 100000;
    double sv = 0, maxdm = 0;
    int inrange = 1;
    for (int i = 0; i < M; i++) {
      int n;
      ics_kernel1d_taps(&k, (uint64_t)i, t1, CAP, &n);
      double W, m, v;
      ics_taps1d_moments(t1, n, &W, &m, &v);
      if (fabs(m - mu) > maxdm) maxdm = fabs(m - mu);
      double r = sqrt(v);
      if (r < rho - he - 1e-12 || r > rho + he + 1e-12) inrange = 0;
      sv += v;
    }
    sv /= M;
    /* Var[(rho + u)^2] = E(rho+u)^4 - sigma^4 = rho^4 + 2 rho^2 h^2 + h^4/5 - sigma^4 */
    double e4 = rho * rho * rho * rho + 2 * rho * rho * he * he + he * he * he * he / 5;
    double sd = sqrt((e4 - var * var) / M);
    CHECK(maxdm <= 64 * EPS * (fabs(mu) + sqrt(var) + 1), "stoch dirac mean off by %g", maxdm);
    CHECK(inrange, "stoch dirac half-distance outside rho +- h");
    CHECK(fabs(sv - var) < 5 * sd, "stoch dirac E var: %.8g vs %g (5 sd = %.3g)", sv, var, 5 * sd);
  }
  /* reproducible, order-independent, seed-dependent */
  ics_kernel1d k;
  ics_kernel1d_init(&k, ICS_KERNEL_STOCH_DIRAC, 0, 9);
  k.seed = 7;
  int n;
  ics_kernel1d_taps(&k, 5, t1, CAP, &n);
  double a5 = t1[1].x;
  ics_kernel1d_taps(&k, 3, t1, CAP, &n);
  double a3 = t1[1].x;
  ics_kernel1d_taps(&k, 5, t1, CAP, &n);
  CHECK(t1[1].x == a5 && a3 != a5, "stoch dirac reproducible per iteration");
  k.seed = 8;
  ics_kernel1d_taps(&k, 5, t1, CAP, &n);
  CHECK(t1[1].x != a5, "stoch dirac depends on the seed");
}

/* ---------------------------------------------------------------- 2D */
static void check_cov(const char *what, const ics_tap2d *t, int n, const ics_class2d *c,
                      double rel) {
  double W, m[2], cov[3];
  ics_taps2d_moments(t, n, &W, m, cov);
  double scale = c->cxx + c->cyy + 1e-300;
  double ms = fabs(c->mean[0]) + fabs(c->mean[1]) + sqrt(scale) + 1;
  CHECK(fabs(W - 1) <= 64 * EPS * n, "%s: weight %.17g", what, W);
  CHECK(fabs(m[0] - c->mean[0]) <= 64 * EPS * ms && fabs(m[1] - c->mean[1]) <= 64 * EPS * ms,
        "%s: mean (%.17g, %.17g)", what, m[0], m[1]);
  CHECK(fabs(cov[0] - c->cxx) <= rel * scale && fabs(cov[1] - c->cxy) <= rel * scale &&
            fabs(cov[2] - c->cyy) <= rel * scale,
        "%s: cov (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", what, cov[0], cov[1], cov[2], c->cxx,
        c->cxy, c->cyy);
}

static void test_2d(void) {
  const double cl[][5] = {{0, 0, 1, 1, 0},   {0.3, -0.7, 3, 1, 30}, {5.5, 2.25, 0.8, 0.05, -70},
                          {0, 0, 2, 0, 45}, {0.25, 0.5, 0, 0, 0}, {0, 0, 40, 10, 110}};
  for (size_t i = 0; i < sizeof cl / sizeof *cl; i++) {
    ics_class2d c;
    ics_status st = ics_class2d_init_axes(&c, cl[i][0], cl[i][1], cl[i][2], cl[i][3], cl[i][4]);
    CHECK(st == ICS_OK, "from_axes %s", ics_status_str(st));
    /* round trip */
    double vx, vy, ang;
    ics_class2d_to_axes(&c, &vx, &vy, &ang);
    double big = cl[i][2] > cl[i][3] ? cl[i][2] : cl[i][3], sm = cl[i][2] + cl[i][3] - big;
    CHECK(fabs(vx - big) <= 1e-14 * big + 1e-300 && fabs(vy - sm) <= 1e-14 * big,
          "to_axes eigenvalues %g %g", vx, vy);
    if (big > sm) {
      double want = cl[i][2] >= cl[i][3] ? cl[i][4] : cl[i][4] + 90;
      double d = fmod(fabs(ang - want), 180.0);
      CHECK(d < 1e-9 || 180 - d < 1e-9, "to_axes angle %g vs %g", ang, want);
    }
    /* GAUSS 2D: exact */
    ics_kernel2d k;
    ics_kernel2d_init(&k, ICS_KERNEL_GAUSS, &c);
    int n;
    st = ics_kernel2d_taps(&k, 0, t2, CAP, &n);
    CHECK(st == ICS_OK && n == ((c.cxx > 0 || c.cyy > 0) ? 25 : 1), "gauss2d taps %d", n);
    check_cov("gauss2d", t2, n, &c, 1e-13);
    /* POISSON: exact for every rotation */
    ics_kernel2d_init(&k, ICS_KERNEL_POISSON, &c);
    for (int ns = 3; ns <= 16; ns += 13) {
      k.nsamples = ns;
      k.seed = 3;
      double first = 0;
      for (uint64_t it = 0; it < 5; it++) {
        st = ics_kernel2d_taps(&k, it, t2, CAP, &n);
        CHECK(st == ICS_OK && n == ns, "poisson taps %d", n);
        check_cov("poisson", t2, n, &c, 1e-13);
        if (it == 0) first = t2[0].x;
        if (it == 1 && (c.cxx > 0)) CHECK(t2[0].x != first, "poisson rotates per iteration");
      }
    }
    /* ELLIPSE: mean exact for N = 2; covariance in expectation */
    ics_kernel2d_init(&k, ICS_KERNEL_ELLIPSE, &c);
    for (int ns = 2; ns <= 3; ns++) {
      k.nsamples = ns;
      k.seed = 11;
      const int M = 20000;
      double s[5] = {0}, s2[5] = {0};
      for (int it = 0; it < M; it++) {
        ics_kernel2d_taps(&k, (uint64_t)it, t2, CAP, &n);
        double W, m[2], cov[3];
        ics_taps2d_moments(t2, n, &W, m, cov);
        double v[5] = {m[0], m[1], cov[0] + (m[0] - c.mean[0]) * (m[0] - c.mean[0]),
                       cov[1] + (m[0] - c.mean[0]) * (m[1] - c.mean[1]),
                       cov[2] + (m[1] - c.mean[1]) * (m[1] - c.mean[1])};
        for (int a = 0; a < 5; a++) s[a] += v[a], s2[a] += v[a] * v[a];
        if (ns == 2 && it < 100)
          CHECK(fabs(m[0] - c.mean[0]) < 1e-12 * (1 + fabs(c.mean[0]) + sqrt(c.cxx + c.cyy)),
                "ellipse N=2 mean exact");
      }
      /* second moments about the class mean: their expectation is the class covariance */
      double want[5] = {c.mean[0], c.mean[1], c.cxx, c.cxy, c.cyy};
      for (int a = 0; a < 5; a++) {
        double mean = s[a] / M, sd = sqrt(fmax(s2[a] / M - mean * mean, 0) / M);
        CHECK(fabs(mean - want[a]) <= 5 * sd + 1e-12 * (1 + fabs(want[a]) + c.cxx + c.cyy),
              "ellipse N=%d class %zu moment %d: %.10g vs %.10g (5 sd %.3g)", ns, i, a, mean,
              want[a], 5 * sd);
      }
    }
  }
}

/* ics_kernel2d_expected against the taps the members actually produce: the moments measured
 * (independently of the library's moment helpers) on GAUSS and POISSON, exact members, at every
 * iteration, and their average over M iterations of ELLIPSE (odd N: exact only in expectation,
 * mean included), within 5 standard deviations */
static void test_expected2d(void) {
  ics_class2d c;
  CHECK(ics_class2d_init_axes(&c, 0.3, -0.7, 3, 1, 30) == ICS_OK, "class");
  const ics_kernel_member mem[] = {ICS_KERNEL_GAUSS, ICS_KERNEL_POISSON, ICS_KERNEL_ELLIPSE};
  for (size_t q = 0; q < sizeof mem / sizeof mem[0]; q++) {
    ics_kernel2d k;
    CHECK(ics_kernel2d_init(&k, mem[q], &c) == ICS_OK, "init %s", ics_kernel_member_name(mem[q]));
    k.seed = 5;
    if (mem[q] == ICS_KERNEL_ELLIPSE) k.nsamples = 3;
    double em[2] = {NAN, NAN}, ec[3] = {NAN, NAN, NAN};
    CHECK(ics_kernel2d_expected(&k, em, ec) == ICS_OK, "expected %s",
          ics_kernel_member_name(mem[q]));
    const int M = ics_kernel_member_stochastic(mem[q]) ? 20000 : 3;
    /* per iteration: mean and second moments about the expected mean (their expectation is the
     * expected covariance whether or not the mean is exact) */
    double s[5] = {0}, s2[5] = {0};
    for (int it = 0; it < M; it++) {
      int n = 0;
      CHECK(ics_kernel2d_taps(&k, (uint64_t)it, t2, CAP, &n) == ICS_OK, "taps");
      double w = 0, mx = 0, my = 0, v[5] = {0};
      for (int j = 0; j < n; j++) w += t2[j].w, mx += t2[j].w * t2[j].x, my += t2[j].w * t2[j].y;
      mx /= w, my /= w;
      v[0] = mx, v[1] = my;
      for (int j = 0; j < n; j++) {
        double dx = t2[j].x - em[0], dy = t2[j].y - em[1];
        v[2] += t2[j].w * dx * dx, v[3] += t2[j].w * dx * dy, v[4] += t2[j].w * dy * dy;
      }
      for (int a = 2; a < 5; a++) v[a] /= w;
      for (int a = 0; a < 5; a++) s[a] += v[a], s2[a] += v[a] * v[a];
    }
    const double want[5] = {em[0], em[1], ec[0], ec[1], ec[2]};
    for (int a = 0; a < 5; a++) {
      double mean = s[a] / M, sd = sqrt(fmax(s2[a] / M - mean * mean, 0) / M);
      CHECK(fabs(mean - want[a]) <= 5 * sd + 1e-12 * (1 + c.cxx + c.cyy),
            "%s: measured moment %d %.10g, expected() %.10g (5 sd %.3g)",
            ics_kernel_member_name(mem[q]), a, mean, want[a], 5 * sd);
    }
  }
  ics_kernel2d k;
  CHECK(ics_kernel2d_init(&k, ICS_KERNEL_GAUSS, &c) == ICS_OK, "init");
  CHECK(ics_kernel2d_expected(&k, NULL, NULL) == ICS_OK, "expected: NULL outputs allowed");
  CHECK(ics_kernel2d_expected(NULL, NULL, NULL) == ICS_ERR_INVALID_ARG, "expected: NULL kernel");
  k.member = ICS_KERNEL_TOPHAT; /* no 2D form */
  CHECK(ics_kernel2d_expected(&k, NULL, NULL) == ICS_ERR_INVALID_ARG, "expected: 1D-only member");
  k.member = ICS_KERNEL_GAUSS;
  k.cls.cxx = NAN;
  CHECK(ics_kernel2d_expected(&k, NULL, NULL) == ICS_ERR_NAN, "expected: NaN class");
}

/* ---------------------------------------------------------------- schedules, errors */
static void test_schedule(void) {
  ics_kernel1d m[3];
  ics_kernel1d_init(&m[0], ICS_KERNEL_DIRAC, 0.25, 2);
  ics_kernel1d_init(&m[1], ICS_KERNEL_STOCH_DIRAC, 0.25, 2);
  ics_kernel1d_init(&m[2], ICS_KERNEL_TOPHAT, 0.25, 2);
  m[1].seed = 99;
  ics_schedule1d s = {m, 3};
  CHECK(ics_schedule1d_max_taps(&s) == ics_kernel1d_max_taps(&m[2]), "schedule max taps");
  for (uint64_t i = 0; i < 9; i++) {
    int n1, n2;
    static ics_tap1d a[64];
    ics_schedule1d_taps(&s, i, t1, CAP, &n1);
    ics_kernel1d_taps(&m[i % 3], i, a, 64, &n2);
    CHECK(n1 == n2 && memcmp(t1, a, sizeof *a * (size_t)n1) == 0, "schedule step %d", (int)i);
  }
}

static void test_errors(void) {
  ics_kernel1d k;
  int n;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, NAN, 1) == ICS_ERR_NAN, "NaN mean");
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, NAN) == ICS_ERR_NAN, "NaN var");
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, -1) == ICS_ERR_NEGATIVE_VARIANCE, "neg var");
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, INFINITY) == ICS_ERR_INFINITE, "inf var");
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_ELLIPSE, 0, 1) == ICS_ERR_INVALID_ARG, "2D-only in 1D");
  CHECK(ics_kernel1d_init(NULL, ICS_KERNEL_DIRAC, 0, 1) == ICS_ERR_INVALID_ARG, "NULL");
  ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, 1);
  CHECK(ics_kernel1d_taps(&k, 0, t1, 1, &n) == ICS_ERR_SIZE, "cap too small");
  CHECK(ics_kernel1d_taps(&k, 0, NULL, 8, &n) == ICS_ERR_INVALID_ARG, "NULL taps");
  CHECK(ics_kernel1d_taps(NULL, 0, t1, 8, &n) == ICS_ERR_INVALID_ARG, "NULL kernel");
  ics_kernel1d_init(&k, ICS_KERNEL_GAUSS, 0, 1);
  k.nsamples = 1;
  CHECK(ics_kernel1d_taps(&k, 0, t1, CAP, &n) == ICS_ERR_RANGE, "gauss N=1, var>0");
  k.nsamples = ICS_KERNEL_MAX_TAPS + 1;
  CHECK(ics_kernel1d_taps(&k, 0, t1, CAP, &n) == ICS_ERR_RANGE, "huge nsamples");
  k.nsamples = -3;
  CHECK(ics_kernel1d_max_taps(&k) == 0, "max_taps of invalid kernel");
  ics_kernel1d_init(&k, ICS_KERNEL_TOPHAT, 0, 1e12);
  CHECK(ics_kernel1d_taps(&k, 0, t1, CAP, &n) == ICS_ERR_RANGE, "huge tophat");
  ics_kernel1d_init(&k, ICS_KERNEL_STOCH_DIRAC, 0, 1);
  k.param = NAN;
  CHECK(ics_kernel1d_taps(&k, 0, t1, CAP, &n) == ICS_ERR_NAN, "NaN jitter");
  k.param = -1;
  CHECK(ics_kernel1d_taps(&k, 0, t1, CAP, &n) == ICS_ERR_RANGE, "negative jitter");

  ics_class2d c = {{0, 0}, 1, 2, 1}; /* eigenvalues 3, -1 */
  CHECK(ics_class2d_check(&c) == ICS_ERR_NEGATIVE_VARIANCE, "non-PSD class");
  c.cxy = NAN;
  CHECK(ics_class2d_check(&c) == ICS_ERR_NAN, "NaN cov");
  CHECK(ics_class2d_init_axes(&c, 0, 0, -1, 1, 0) == ICS_ERR_NEGATIVE_VARIANCE, "neg axes");
  CHECK(ics_class2d_init_axes(&c, 0, 0, 1, 1, INFINITY) == ICS_ERR_INFINITE, "inf angle");
  ics_class2d_init_axes(&c, 0, 0, 1, 1, 0);
  ics_kernel2d k2;
  CHECK(ics_kernel2d_init(&k2, ICS_KERNEL_DIRAC, &c) == ICS_ERR_INVALID_ARG, "1D-only in 2D");
  ics_kernel2d_init(&k2, ICS_KERNEL_POISSON, &c);
  k2.nsamples = 2;
  CHECK(ics_kernel2d_taps(&k2, 0, t2, CAP, &n) == ICS_ERR_RANGE, "poisson N=2");
  ics_kernel2d_init(&k2, ICS_KERNEL_ELLIPSE, &c);
  k2.nsamples = 100000;
  CHECK(ics_kernel2d_taps(&k2, 0, t2, CAP, &n) == ICS_ERR_RANGE, "ellipse huge N");
  ics_schedule1d s = {NULL, 2};
  CHECK(ics_schedule1d_taps(&s, 0, t1, CAP, &n) == ICS_ERR_INVALID_ARG, "NULL schedule");
  CHECK(ics_kernel_member_name(ICS_KERNEL_MEMBER_COUNT_) == NULL, "name out of range");
  double W, M, V;
  ics_taps1d_moments(NULL, 3, &W, &M, &V);
  CHECK(isnan(W) && isnan(M) && isnan(V), "moments of nothing are NaN");
}

/* Table I equivalent (printed for docs/kernels.md): mean, variance, width (tap span), taps. */
static void print_table1(void) {
  printf("Table I (measured), class mean 0, variance 30 (Patel Fig. 3: width 19):\n");
  printf("%-18s %10s %12s %14s %6s\n", "member", "mean", "variance", "width", "taps");
  const ics_kernel_member mem[] = {ICS_KERNEL_TOPHAT, ICS_KERNEL_DIRAC, ICS_KERNEL_STOCH_DIRAC,
                                   ICS_KERNEL_GAUSS};
  for (int q = 0; q < 4; q++) {
    ics_kernel1d k;
    ics_kernel1d_init(&k, mem[q], 0, 30);
    const int M = ics_kernel_member_stochastic(mem[q]) ? 100000 : 1;
    double sm = 0, sv = 0, wmin = 1e300, wmax = 0;
    int n = 0;
    for (int i = 0; i < M; i++) {
      ics_kernel1d_taps(&k, (uint64_t)i, t1, CAP, &n);
      double W, m, v;
      ics_taps1d_moments(t1, n, &W, &m, &v);
      sm += m, sv += v;
      double w = t1[n - 1].x - t1[0].x;
      if (w < wmin) wmin = w;
      if (w > wmax) wmax = w;
    }
    char width[32];
    if (wmin == wmax)
      snprintf(width, sizeof width, "%.4f", wmin);
    else
      snprintf(width, sizeof width, "%.3f..%.3f", wmin, wmax);
    printf("%-18s %10.3g %12.9f %14s %6d%s\n", ics_kernel_member_name(mem[q]), sm / M, sv / M,
           width, n, M > 1 ? "  (average of 1e5 iterations)" : "");
  }
  ics_class2d c;
  ics_class2d_init_axes(&c, 0, 0, 3, 1, 30);
  printf("2D, class (3, 1, 30 deg): cxx %.9f cxy %.9f cyy %.9f\n", c.cxx, c.cxy, c.cyy);
  const ics_kernel_member m2[] = {ICS_KERNEL_GAUSS, ICS_KERNEL_ELLIPSE, ICS_KERNEL_ELLIPSE,
                                  ICS_KERNEL_POISSON, ICS_KERNEL_POISSON};
  const int ns[] = {0, 2, 3, 8, 16};
  for (int q = 0; q < 5; q++) {
    ics_kernel2d k;
    ics_kernel2d_init(&k, m2[q], &c);
    k.nsamples = ns[q];
    const int M = ics_kernel_member_stochastic(m2[q]) ? 100000 : 1;
    double acc[3] = {0, 0, 0};
    int n = 0;
    for (int i = 0; i < M; i++) {
      ics_kernel2d_taps(&k, (uint64_t)i, t2, CAP, &n);
      double W, m[2], cv[3];
      ics_taps2d_moments(t2, n, &W, m, cv);
      acc[0] += cv[0] + m[0] * m[0], acc[1] += cv[1] + m[0] * m[1], acc[2] += cv[2] + m[1] * m[1];
    }
    printf("%-10s N=%-3d taps %3d: E second moment %.9f %.9f %.9f%s\n",
           ics_kernel_member_name(m2[q]), ns[q] ? ns[q] : 25, n, acc[0] / M, acc[1] / M,
           acc[2] / M, M > 1 ? "  (average of 1e5 iterations)" : "");
  }
}

int main(void) {
  test_tiny();
  print_table1();
  test_deterministic1d();
  test_tophat();
  test_stoch_dirac();
  test_2d();
  test_expected2d();
  test_schedule();
  test_errors();
  return test_summary("test_kernel");
}
