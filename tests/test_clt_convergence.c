/* test_clt_convergence.c — CLT convergence of the ACTUALLY ITERATED kappa^{*n} * H (conv
 * engine) to the Gaussian cdf with the same moments (Patel et al. 2013, Eq. 6, Sec. 3.3), per
 * kernel member, and of the iterated shadow to the Eq. 8 model.
 *
 * Expected rates and constants are derived, not read off the code:
 * - Edgeworth: for a class member whose integer taps (as applied) have cumulants c2, c3, c4,
 *   the nodes hold the cdf of K_n + U(-1/2, 1/2) (cumulants n c2 + 1/12, n c3, n c4 - 1/120), and
 *   F - Phi = -phi(z) [g1/6 He2 + g2/24 He3 + g1^2/72 He5] + ..., g1 = k3/k2^1.5, g2 = k4/k2^2.
 *   Skewed kernels: sup error ~ |g| phi(0) / (6 sqrt n) (rate n^-1/2, Berry-Esseen order);
 *   symmetric ones: ~ |excess kurtosis| max|He3 phi| / (24 n) (rate n^-1).
 * - Lattice kernels (Dirac with integer sigma: taps 2 sigma apart): the cdf is a staircase with
 *   steps J = 2 sigma phi(0) / sigma_n every 2 sigma pixels, each smeared over 1 pixel by the
 *   grid, so sup error -> J/2 (1 - 1/(2 sigma)) = phi(0) (2 sigma - 1) / (2 sigma sqrt n): rate
 *   n^-1/2 that no amount of iteration removes; convergence only in a smoothed sense.
 * - The grid must resolve what is measured: disc_err (change on a 2x finer grid) is asserted to
 *   be below 1/10 of the reported error; a Dirac with sigma = 2.5 px looks like n^-1 on the
 *   coarse grid only because interpolation smooths the lattice: the test asserts that
 *   disc_err then EXCEEDS the error (the measurement is flagged, not reported as a rate).
 * - Each assertion function is also run on a deliberately broken case and must fail. */
#include <math.h>
#include <stdio.h>

#include "icshadow.h"
#include "testutil.h"

static const int STEPS[] = {16, 64, 256, 1024};
#define NS 4

static double phi(double z) { return exp(-0.5 * z * z) / sqrt(2 * ICS_PI); }

/* sup_z |Edgeworth correction| for the applied taps after n steps */
static double edgeworth_sup(const ics_tap1d *t, int nt, int n) {
  double w = 0, m = 0, c2 = 0, c3 = 0, c4 = 0;
  for (int i = 0; i < nt; i++) w += t[i].w, m += t[i].w * t[i].x;
  m /= w;
  for (int i = 0; i < nt; i++) {
    double d = t[i].x - m;
    c2 += t[i].w * d * d, c3 += t[i].w * d * d * d, c4 += t[i].w * d * d * d * d;
  }
  c2 /= w, c3 /= w, c4 /= w;
  double k2 = n * c2 + 1.0 / 12, k3 = n * c3, k4 = n * (c4 - 3 * c2 * c2) - 1.0 / 120;
  double g1 = k3 / pow(k2, 1.5), g2 = k4 / (k2 * k2), best = 0;
  for (double z = -8; z <= 8; z += 1e-3) {
    double he2 = z * z - 1, he3 = z * z * z - 3 * z, he5 = z * z * z * z * z - 10 * z * z * z + 15 * z;
    best = fmax(best, fabs(phi(z) * (g1 / 6 * he2 + g2 / 24 * he3 + g1 * g1 / 72 * he5)));
  }
  return best;
}

/* applied (compensated integer) taps of step 0 */
static int applied_taps(ics_clt1d_gen gen, void *ctx, ics_tap1d *out, int cap) {
  ics_tap1d t[256];
  int nt = 0, nd = 0;
  if (gen(ctx, 0, 1.0, t, 256, &nt) != ICS_OK) return 0;
  if (ics_taps1d_compensate(t, nt, ICS_COMP_NONNEG, out, cap, &nd, NULL) != ICS_OK) return 0;
  return nd;
}

static void print_points(const char *name, double var, const ics_clt_point *p) {
  printf("  %s, var %g px^2: rate (n >= 64) %.4f\n", name, var, ics_clt_rate(p, NS, 64));
  for (int i = 0; i < NS; i++)
    printf("    n = %-5d sup %.4e (vs realised moments %.4e)  disc %.2e  taps x n %-7g %.4f s\n",
           p[i].steps, p[i].sup_err, p[i].sup_err_realized, p[i].disc_err, p[i].cost,
           p[i].seconds);
}

/* ASSERTION FUNCTION: measured errors follow the Edgeworth prediction within rel (n >= 64),
 * the fitted rate is within rtol of `rate`, and the grid resolves the error. 1 = pass. */
static int follows_edgeworth(ics_clt1d_gen gen, void *ctx, double mean, double var, double rate,
                             double rtol, double rel, const char *name, int verbose) {
  ics_clt_point p[NS];
  if (ics_clt1d_measure(gen, ctx, mean, var, STEPS, NS, ICS_COMP_NONNEG, 1, p) != ICS_OK) return 0;
  if (verbose) print_points(name, var, p);
  ics_tap1d t[1024];
  int nt = applied_taps(gen, ctx, t, 1024);
  if (!nt) return 0;
  int ok = fabs(ics_clt_rate(p, NS, 64) - rate) <= rtol;
  for (int i = 1; i < NS; i++) {
    double pred = edgeworth_sup(t, nt, p[i].steps);
    if (verbose) printf("    n = %-5d Edgeworth %.4e, measured / predicted %.4f\n", p[i].steps, pred,
                        p[i].sup_err / pred);
    if (!(fabs(p[i].sup_err / pred - 1) <= rel)) ok = 0;
    if (!(p[i].disc_err <= 0.1 * p[i].sup_err)) ok = 0;
  }
  return ok;
}

static void test_members(void) {
  double V = 36; /* sigma = 6 px per step */
  ics_kernel1d top;
  CHECK(ics_kernel1d_init(&top, ICS_KERNEL_TOPHAT, 0, V) == ICS_OK, "tophat");
  CHECK(follows_edgeworth(ics_clt1d_member_gen, &top, 0, V, -1.0, 0.05, 0.04, "tophat", 1),
        "tophat: not the Edgeworth n^-1 behaviour");
  ics_tap1d sk[ICS_CLT1D_SKEW_TAPS];
  CHECK(ics_clt1d_skew_taps(0, V, sk) == ICS_OK, "skew");
  ics_clt1d_fixed fx = {sk, ICS_CLT1D_SKEW_TAPS};
  CHECK(follows_edgeworth(ics_clt1d_fixed_gen, &fx, 0, V, -0.5, 0.05, 0.04, "skew", 1),
        "skewed member: not the Edgeworth n^-1/2 behaviour");
  /* a nonzero class mean (shift 0.3 px per step) changes nothing but the position */
  ics_kernel1d topm;
  CHECK(ics_kernel1d_init(&topm, ICS_KERNEL_TOPHAT, 0.3, V) == ICS_OK, "tophat mean");
  CHECK(follows_edgeworth(ics_clt1d_member_gen, &topm, 0.3, V, -1.0, 0.05, 0.04,
                          "tophat mean 0.3", 1),
        "tophat with mean 0.3 px");
  /* broken on purpose: the skewed kernel claimed to converge like a symmetric one (rate -1)
   * and the tophat measured against a Gaussian of the wrong variance (class says V, kernel
   * has 1.1 V): both must fail the same assertion */
  CHECK(!follows_edgeworth(ics_clt1d_fixed_gen, &fx, 0, V, -1.0, 0.05, 0.04, "skew (as -1)", 0),
        "wrong rate for the skewed kernel NOT detected");
  ics_kernel1d topw;
  ics_kernel1d_init(&topw, ICS_KERNEL_TOPHAT, 0, 1.1 * V);
  CHECK(!follows_edgeworth(ics_clt1d_member_gen, &topw, 0, V, -1.0, 0.05, 0.04, "tophat 1.1V", 0),
        "variance mismatch NOT detected");
}

static void test_lattice(void) {
  /* Dirac sigma = 6 px (integer): lattice span 12 px */
  double V = 36, s = 6;
  ics_kernel1d k;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_DIRAC, 0, V) == ICS_OK, "dirac");
  ics_clt_point p[NS];
  CHECK(ics_clt1d_measure(ics_clt1d_member_gen, &k, 0, V, STEPS, NS, ICS_COMP_NONNEG, 1, p) ==
            ICS_OK,
        "measure");
  print_points("dirac (lattice, span 12 px)", V, p);
  double c = phi(0) * (2 * s - 1) / (2 * s);
  double rate = ics_clt_rate(p, NS, 64);
  CHECK(fabs(rate + 0.5) < 0.02, "dirac rate %.4f, expected -1/2", rate);
  for (int i = 1; i < NS; i++) {
    double pred = c / sqrt((double)p[i].steps);
    CHECK(fabs(p[i].sup_err / pred - 1) < 0.01, "dirac n=%d: %.5g vs staircase %.5g", p[i].steps,
          p[i].sup_err, pred);
    CHECK(p[i].disc_err < 0.01 * p[i].sup_err, "dirac grid resolution %.3g", p[i].disc_err);
  }
  /* Dirac sigma = 2.5 px: the taps fall between pixels, interpolation smooths the lattice and
   * the coarse grid shows a fast decay; the 2x grid (sigma = 5 px, a lattice again) disagrees by
   * more than the error itself: the measurement is discretisation-dominated and is flagged. */
  ics_kernel1d k2;
  CHECK(ics_kernel1d_init(&k2, ICS_KERNEL_DIRAC, 0, 6.25) == ICS_OK, "dirac 2.5");
  CHECK(ics_clt1d_measure(ics_clt1d_member_gen, &k2, 0, 6.25, STEPS, NS, ICS_COMP_NONNEG, 1, p) ==
            ICS_OK, "measure");
  print_points("dirac sigma 2.5 px (interpolated taps)", 6.25, p);
  int unres = 1;
  for (int i = 1; i < NS; i++) {
    CHECK(p[i].disc_err > 10 * p[i].sup_err, "n=%d: disc %.3g not >> sup %.3g", p[i].steps,
          p[i].disc_err, p[i].sup_err);
    unres = unres && p[i].disc_err > 10 * p[i].sup_err;
  }
  printf("    -> %s\n", unres ? "unresolved (no rate claimed): the 2x grid changes it by more than 10x "
                                 "the error at every n but the first"
                               : "NOT unresolved as asserted");
  /* the GAUSS member (9 taps, a comb 0.75 s apart) is lattice-like too: on a 6 px grid its tiny
   * error is grid smoothing (disc >> sup at n = 256) */
  ics_kernel1d g;
  CHECK(ics_kernel1d_init(&g, ICS_KERNEL_GAUSS, 0, V) == ICS_OK, "gauss");
  CHECK(ics_clt1d_measure(ics_clt1d_member_gen, &g, 0, V, STEPS, NS, ICS_COMP_NONNEG, 1, p) ==
            ICS_OK,
        "measure");
  print_points("gauss (9-tap comb)", V, p);
  CHECK(p[2].disc_err > 10 * p[2].sup_err, "gauss n=256: disc %.3g vs sup %.3g", p[2].disc_err,
        p[2].sup_err);
  printf("    -> %s\n", p[2].disc_err > 10 * p[2].sup_err
                           ? "unresolved (no rate claimed): grid smoothing at n = 256 (disc > 10 sup)"
                           : "NOT unresolved as asserted");
}

static void test_stochastic(void) {
  /* stochastic Dirac: each step symmetric with a random variance (rho + u)^2, E = sigma^2.
   * Against its REALISED moments the shape converges like a symmetric kernel (rate -1); against
   * the class the random total variance (relative sd ~ n^-1/2) dominates. */
  double V = 36;
  ics_kernel1d k;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_STOCH_DIRAC, 0, V) == ICS_OK, "stoch");
  ics_clt_point p[NS];
  CHECK(ics_clt1d_measure(ics_clt1d_member_gen, &k, 0, V, STEPS, NS, ICS_COMP_NONNEG, 1, p) ==
            ICS_OK,
        "measure");
  print_points("stochastic-dirac (seed 0)", V, p);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 1; i < NS; i++) {
    double x = log((double)p[i].steps), y = log(p[i].sup_err_realized);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  double rate = (3 * sxy - sx * sy) / (3 * sxx - sx * sx);
  printf("    rate against the realised moments (n >= 64): %.4f\n", rate);
  CHECK(rate < -0.8 && rate > -1.3, "stochastic dirac realised-moment rate %.4f", rate);
  for (int i = 1; i < NS; i++) {
    CHECK(p[i].sup_err >= p[i].sup_err_realized, "class error below realised error");
    /* the 1-px jitter is itself interpolated: the grid resolves the realised-moment error
     * from n = 256 on (at n = 64 disc is 0.7 of it: that point is not a measurement) */
    if (p[i].steps >= 256)
      CHECK(p[i].disc_err < 0.1 * p[i].sup_err_realized, "grid resolution %.3g vs %.3g",
            p[i].disc_err, p[i].sup_err_realized);
  }
}

/* ASSERTION FUNCTION: the iterated shadow at distance d (Gaussian light) is within tol of the
 * Eq. 8 model Phi((x + d mu_l) / sqrt(d d1 var_l)) everywhere on the grid. 1 = pass. */
static int iterated_matches_eq8(const ics_light1d *l, double d, double d1, double e,
                                const ics_iter1d_opts *o, double tol, double *worst) {
  ics_iter1d *it = NULL;
  if (ics_iter1d_create(&it, l, d, d1, e, o) != ICS_OK) return 0;
  double w = 0;
  for (size_t i = 0; i < it->n; i++) {
    double x = it->x0 + (double)i * it->h;
    w = fmax(w, fabs(it->r[i] - ics_shadow1d_clt(l, d, d1, x)));
  }
  ics_iter1d_destroy(it);
  *worst = w;
  return w <= tol;
}

static void test_eq8(void) {
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_gauss(&l, 0.25, 0.5) == ICS_OK, "gauss");
  double d1 = 2.0, e = 1.0 / 64, d = 3.0; /* n = 192 */
  int n = 192;
  /* tophat: |excess kurtosis| 1.2 -> cdf error 1.2/24/n max|He3 phi| (x1.5 margin) */
  double mhe3 = 0;
  for (double z = 0; z < 5; z += 1e-4) mhe3 = fmax(mhe3, fabs((z * z * z - 3 * z) * phi(z)));
  double tol = 1.5 * 1.2 / 24 / n * mhe3;
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  o.member = ICS_KERNEL_TOPHAT;
  double w;
  CHECK(iterated_matches_eq8(l, d, d1, e, &o, tol, &w), "Eq. 8: sup %.3g > tol %.3g", w, tol);
  printf("  Eq. 8 (Gaussian light, tophat, d = 3, d1 = 2, n = 192): sup %.3e <= %.3e\n", w, tol);
  o.var_factor = 1.0; /* broken: variance e var_l instead of d1 e var_l */
  CHECK(!iterated_matches_eq8(l, d, d1, e, &o, tol, &w), "broken variance NOT detected");
  printf("  broken variance e var_l: sup %.3e -> detected\n", w);
  o.var_factor = 0;
  o.mean_sign = -1; /* broken: kernel mean +e mu_l */
  CHECK(!iterated_matches_eq8(l, d, d1, e, &o, tol, &w), "broken mean sign NOT detected");
  printf("  broken mean sign: sup %.3e -> detected\n", w);
  ics_light1d_destroy(l);
}

/* ASSERTION FUNCTION (2D, end to end): a 2D Gaussian light mapped by ics_light_kernel_map_2d
 * (Eq. 15) to a kernel class, the 2D Gaussian member of that class propagated by the 2D engine
 * from an impulse for n = d / e steps (compensated taps: the applied integer taps have exactly
 * the class moments, so the image's moments are exactly n times them up to float rounding). The
 * image's mean and covariance (world units) must be -d mu_l and d d1 Sigma_l: max abs deviation
 * of the 5 numbers, relative to sqrt(trace(d d1 Sigma_l)) for the mean and trace for the
 * covariance, <= tol. kbreak: 0 none; 1 kernel covariance e Sigma_l (d1 dropped); 2 kernel mean
 * +e mu_l (sign). 1 = pass. */
static int conv2d_matches_mapping(const ics_light *L, double d, double d1, double e, double h,
                                  int kbreak, double tol, double *worst) {
  double mk[2], ck[3];
  *worst = INFINITY;
  if (ics_light_kernel_map_2d(L, e, d1, mk, ck) != ICS_OK) return 0;
  if (kbreak == 1)
    for (int i = 0; i < 3; i++) ck[i] /= d1;
  if (kbreak == 2) mk[0] = -mk[0], mk[1] = -mk[1];
  ics_class2d cls = {{mk[0] / h, mk[1] / h}, ck[0] / (h * h), ck[1] / (h * h), ck[2] / (h * h)};
  ics_kernel2d k;
  if (ics_kernel2d_init(&k, ICS_KERNEL_GAUSS, &cls) != ICS_OK) return 0;
  int n = (int)lround(d / e);
  enum { W = 256, H = 256 };
  static float img[W * H];
  for (size_t i = 0; i < (size_t)W * H; i++) img[i] = 0;
  const size_t cx = 128, cy = 128;
  img[cy * W + cx] = 1.0f;
  ics_schedule2d sch = {&k, 1};
  ics_conv_opts co = {0};
  co.boundary = ICS_BOUNDARY_CONSTANT;
  co.compensate = ICS_COMP_NONNEG;
  if (ics_conv2d_run(img, W, H, &sch, 0, n, &co, NULL) != ICS_OK) return 0;
  double s0 = 0, sx = 0, sy = 0;
  for (size_t y = 0; y < H; y++)
    for (size_t x = 0; x < W; x++) {
      double v = img[y * W + x], px = ((double)x - cx) * h, py = ((double)y - cy) * h;
      s0 += v, sx += v * px, sy += v * py;
    }
  double m[2] = {sx / s0, sy / s0}, c[3] = {0, 0, 0};
  for (size_t y = 0; y < H; y++)
    for (size_t x = 0; x < W; x++) {
      double v = img[y * W + x], px = ((double)x - cx) * h - m[0], py = ((double)y - cy) * h - m[1];
      c[0] += v * px * px, c[1] += v * px * py, c[2] += v * py * py;
    }
  for (int i = 0; i < 3; i++) c[i] /= s0;
  double tm[2] = {-d * L->mean[0], -d * L->mean[1]};
  double tc[3] = {d * d1 * L->cov[0], d * d1 * L->cov[1], d * d1 * L->cov[2]};
  double tr = tc[0] + tc[2], w = 0;
  for (int i = 0; i < 2; i++) w = fmax(w, fabs(m[i] - tm[i]) / sqrt(tr));
  for (int i = 0; i < 3; i++) w = fmax(w, fabs(c[i] - tc[i]) / tr);
  *worst = w;
  return w <= tol;
}

static void test_2d_mapping(void) {
  /* light: tilt (10, -6) degrees, eigen-variances 0.02, 0.008 rotated 30 degrees */
  ics_light L;
  CHECK(ics_light_init_tilt(&L, 10, -6, 0.02, 0.008, 30, NULL, 1) == ICS_OK, "light");
  double d1 = 2.0, e = 0.25, d = 2.0, h = 0.05; /* d = d1: 8 steps of ~(4, 1.6) px^2 */
  /* tolerance: float storage rounds each pixel to 2^-24 relative once per step, so the moments
   * drift by at most ~8 x 6e-8 = 4.8e-7 relative; tol 1e-6 */
  double tol = 1e-6, w;
  CHECK(conv2d_matches_mapping(&L, d, d1, e, h, 0, tol, &w),
        "2D: moments off the Eq. 15 prediction by %.3g > %.3g", w, tol);
  printf("  2D Gaussian light -> ics_light_kernel_map_2d -> conv2d (gauss 5x5, 8 steps, d = d1 = "
         "2): mean -d mu_l, covariance d1^2 Sigma_l to %.2e (tol %.0e)\n", w, tol);
  CHECK(!conv2d_matches_mapping(&L, d, d1, e, h, 1, tol, &w), "2D broken variance NOT detected");
  printf("  2D broken covariance e Sigma_l: %.3e -> detected\n", w);
  CHECK(!conv2d_matches_mapping(&L, d, d1, e, h, 2, tol, &w), "2D broken mean sign NOT detected");
  printf("  2D broken mean sign: %.3e -> detected\n", w);
}


/* ======================= 2D members (icshadow/clt2d.h) =======================
 * Expected behaviour derived, not read off the code:
 * - Node values are exactly the cdf of u . (K_n + U) (edge, unit normal u; U uniform on the
 *   pixel) because the occluder image is the exact area coverage (clt2d.c). So the projected
 *   sum has cumulants k2 = sum_steps c2 + 1/12, k3 = sum c3, k4 = sum (c4 - 3 c2^2) -
 *   (ux^4 + uy^4)/120 (c_j: central moments of u . x over one step's APPLIED integer taps) and
 *   the 1D Edgeworth formula above is applied to the sum of non-identical steps: the cumulants
 *   add exactly; the expansion is asymptotic.
 * - Independent references for the bivariate normal cdf: Phi2(0, 0; r) = 1/4 + asin(r)/(2 pi)
 *   (closed form), Phi(a) Phi(b) at r = 0, and an adaptive Simpson quadrature of
 *   phi(x) Phi((b - r x) / sqrt(1 - r^2)) written here.
 * - The edge coverage (trapezoid cdf) against a 2000 x 2000 midpoint sampling of the pixel. */

static double phic(double z) { return 0.5 * erfc(-z / sqrt(2.0)); }

static double simpson_bvn_f(double x, double b, double r) {
  return phi(x) * phic((b - r * x) / sqrt(1 - r * r));
}
static double simpson_adapt(double lo, double hi, double flo, double fm, double fhi, double whole,
                            double b, double r, int depth) {
  double m = 0.5 * (lo + hi), l = 0.5 * (lo + m), rr = 0.5 * (m + hi);
  double fl = simpson_bvn_f(l, b, r), fr = simpson_bvn_f(rr, b, r);
  double left = (m - lo) / 6 * (flo + 4 * fl + fm), right = (hi - m) / 6 * (fm + 4 * fr + fhi);
  if (depth > 50 || fabs(left + right - whole) <= 15 * 1e-16) return left + right + (left + right - whole) / 15;
  return simpson_adapt(lo, m, flo, fl, fm, left, b, r, depth + 1) +
         simpson_adapt(m, hi, fm, fr, fhi, right, b, r, depth + 1);
}
/* P(X < a, Y < b) by quadrature over x in [-40, a] (|r| < 1) */
static double bvn_ref(double a, double b, double r) {
  double lo = -40, hi = a < 40 ? a : 40;
  if (hi <= lo) return 0;
  /* split at 0 and +-8 so the adaptive rule sees the bulk */
  double cuts[5] = {lo, -8, 0, 8, hi}, s = 0;
  for (int i = 0; i < 4; i++) {
    double x0 = cuts[i], x1 = cuts[i + 1] < hi ? cuts[i + 1] : hi;
    if (x1 <= x0) break;
    double f0 = simpson_bvn_f(x0, b, r), f1 = simpson_bvn_f(x1, b, r);
    double fmm = simpson_bvn_f(0.5 * (x0 + x1), b, r);
    s += simpson_adapt(x0, x1, f0, fmm, f1, (x1 - x0) / 6 * (f0 + 4 * fmm + f1), b, r, 0);
  }
  return s;
}

static void test_bvn(void) {
  double worst_c = 0, worst_p = 0, worst_q = 0;
  double rs[] = {-0.999, -0.95, -0.9, -0.5, -0.1, 0, 0.2, 0.6, 0.92, 0.93, 0.97, 0.999};
  for (size_t i = 0; i < sizeof rs / sizeof *rs; i++)
    worst_c = fmax(worst_c, fabs(ics_normal_bvn_cdf(0, 0, rs[i]) - (0.25 + asin(rs[i]) / (2 * ICS_PI))));
  for (double a = -6; a <= 6; a += 0.75)
    for (double b = -6; b <= 6; b += 0.75) {
      worst_p = fmax(worst_p, fabs(ics_normal_bvn_cdf(a, b, 0) - phic(a) * phic(b)));
      for (size_t i = 0; i < sizeof rs / sizeof *rs; i++)
        worst_q = fmax(worst_q, fabs(ics_normal_bvn_cdf(a, b, rs[i]) - bvn_ref(a, b, rs[i])));
    }
  printf("  bvn: |Phi2(0,0;r) - 1/4 - asin r/2pi| <= %.2e, |r = 0 - Phi Phi| <= %.2e, "
         "vs Simpson quadrature <= %.2e (17 x 17 x 12 points)\n", worst_c, worst_p, worst_q);
  CHECK(worst_c <= 1e-15, "bvn closed form %.3g", worst_c);
  CHECK(worst_p <= 1e-15, "bvn r = 0 %.3g", worst_p);
  CHECK(worst_q <= 1e-12, "bvn vs quadrature %.3g", worst_q);
  CHECK(isnan(ics_normal_bvn_cdf(0, 0, 1.5)) && isnan(ics_normal_bvn_cdf(NAN, 0, 0)), "bvn domain");
  /* edge coverage vs the exact area of the pixel square clipped by the half-plane
   * (Sutherland-Hodgman clip of the 4 corners, shoelace area) */
  double wc = 0;
  double angs[] = {0, 17, 30, 45, 60, 90, 123, 200, 315};
  for (size_t k = 0; k < sizeof angs / sizeof *angs; k++) {
    double ux = cos(angs[k] * ICS_PI / 180), uy = sin(angs[k] * ICS_PI / 180);
    for (double t = -0.9; t <= 0.9; t += 0.05) {
      double sq[4][2] = {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, poly[8][2];
      int np = 0;
      for (int i = 0; i < 4; i++) { /* keep t + u . x > 0 */
        const double *a = sq[i], *b = sq[(i + 1) % 4];
        double fa = t + ux * a[0] + uy * a[1], fb = t + ux * b[0] + uy * b[1];
        if (fa > 0) poly[np][0] = a[0], poly[np][1] = a[1], np++;
        if ((fa > 0) != (fb > 0)) {
          double l = fa / (fa - fb);
          poly[np][0] = a[0] + l * (b[0] - a[0]), poly[np][1] = a[1] + l * (b[1] - a[1]), np++;
        }
      }
      double area = 0;
      for (int i = 0; i < np; i++)
        area += poly[i][0] * poly[(i + 1) % np][1] - poly[(i + 1) % np][0] * poly[i][1];
      wc = fmax(wc, fabs(ics_clt2d_edge_coverage(ux, uy, t) - 0.5 * area));
    }
  }
  printf("  edge coverage vs clipped-polygon area: max diff %.2e (9 angles x 37 offsets)\n", wc);
  CHECK(wc <= 1e-15, "edge coverage %.3g", wc);
}

/* applied (compensated NONNEG) integer taps of one step */
static int applied2(ics_clt2d_gen gen, void *ctx, uint64_t step, ics_tap2d *out, int cap) {
  static ics_tap2d t[4096];
  int nt = 0, nd = 0;
  if (gen(ctx, step, 1.0, t, 4096, &nt) != ICS_OK) return 0;
  if (ics_taps2d_compensate(t, nt, ICS_COMP_NONNEG, out, cap, &nd, NULL) != ICS_OK) return 0;
  return nd;
}

/* sup_z of the Edgeworth correction of u . (K_n + U), the steps' applied taps regenerated */
static double edgeworth2d_sup(ics_clt2d_gen gen, void *ctx, double ux, double uy, int n) {
  static ics_tap2d t[4 * 4096 + 9];
  double k2 = 1.0 / 12, k3 = 0, k4 = -(pow(ux, 4) + pow(uy, 4)) / 120;
  for (int s = 0; s < n; s++) {
    int nt = applied2(gen, ctx, (uint64_t)s, t, 4 * 4096 + 9);
    if (!nt) return NAN;
    double w = 0, m = 0, c2 = 0, c3 = 0, c4 = 0;
    for (int i = 0; i < nt; i++) w += t[i].w, m += t[i].w * (ux * t[i].x + uy * t[i].y);
    m /= w;
    for (int i = 0; i < nt; i++) {
      double d = ux * t[i].x + uy * t[i].y - m;
      c2 += t[i].w * d * d, c3 += t[i].w * d * d * d, c4 += t[i].w * d * d * d * d;
    }
    c2 /= w, c3 /= w, c4 /= w;
    k2 += c2, k3 += c3, k4 += c4 - 3 * c2 * c2;
  }
  double g1 = k3 / pow(k2, 1.5), g2 = k4 / (k2 * k2), best = 0;
  for (double z = -8; z <= 8; z += 1e-3) {
    double he2 = z * z - 1, he3 = z * z * z - 3 * z, he5 = z * z * z * z * z - 10 * z * z * z + 15 * z;
    best = fmax(best, fabs(phi(z) * (g1 / 6 * he2 + g2 / 24 * he3 + g1 * g1 / 72 * he5)));
  }
  return best;
}

/* Under AddressSanitizer (ICS_SANITIZE builds, ~3-4x slower here) the most expensive 2D cases
 * (random-offset 8-sample ellipse, corner convergence and its control, the 1.1 Sigma edge
 * control) are skipped; every code path they use (member generator, corner image and limit,
 * refinement) is still run by the other cases (exactness at the corner, Poisson edge). The
 * whole test then takes 14.5 s alone under ASan and 17.1 s in `ctest -L fast -j2` (was 21 s
 * alone, 40-79 s reported under load); Release 5.3 s. The Release build runs everything. */
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANITIZED 1
#endif
#endif
#ifndef SANITIZED
#define SANITIZED 0
#endif

static const int STEPS2[] = {8, 16, 32, 64};
#define NS2 4

static void print2(const char *name, const ics_clt_point *p, int np) {
  printf("  %s:\n", name);
  for (int i = 0; i < np; i++)
    printf("    n = %-4d sup %.4e (vs realised moments %.4e)  disc %.2e  taps x n %-6g %.3f s\n",
           p[i].steps, p[i].sup_err, p[i].sup_err_realized, p[i].disc_err, p[i].cost,
           p[i].seconds);
}

/* realised-moment rate over points with steps >= nmin */
static double rate_realised(const ics_clt_point *p, int np, int nmin) {
  ics_clt_point q[16];
  for (int i = 0; i < np; i++) q[i] = p[i], q[i].sup_err = p[i].sup_err_realized;
  return ics_clt_rate(q, np, nmin);
}

/* ASSERTION FUNCTION (2D edge): for n >= nmin the measured sup error (against the class limit
 * if `vs_class`, else against the realised moments) is within rel of the Edgeworth prediction
 * from the applied taps, its fitted rate within rtol of `rate`, and the 2x grid changes the
 * error profile by less than a tenth of it. 1 = pass, 0 = fail, -1 = the measurement itself
 * failed (a test failure for the positive cases and the broken-on-purpose controls alike). */
static int edge2d_judge(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                        const ics_clt_point *p, int ns, int vs_class, int nmin, double rate,
                        double rtol, double rel, int verbose) {
  double ux = cos(s->edge_angle_deg * ICS_PI / 180), uy = sin(s->edge_angle_deg * ICS_PI / 180);
  double r = vs_class ? ics_clt_rate(p, ns, nmin) : rate_realised(p, ns, nmin);
  int ok = fabs(r - rate) <= rtol;
  if (verbose) printf("    fitted rate (%s, n >= %d) %.4f, expected %.2f +- %.2f\n",
                      vs_class ? "class" : "realised", nmin, r, rate, rtol);
  for (int i = 0; i < ns; i++) {
    if (p[i].steps < nmin) continue;
    double pred = edgeworth2d_sup(gen, ctx, ux, uy, p[i].steps);
    double m = vs_class ? p[i].sup_err : p[i].sup_err_realized;
    if (verbose) printf("    n = %-4d Edgeworth %.4e, measured / predicted %.4f\n", p[i].steps, pred,
                        m / pred);
    if (!(fabs(m / pred - 1) <= rel)) ok = 0;
    if (!(p[i].disc_err <= 0.1 * m)) ok = 0;
  }
  return ok;
}

/* measures at STEPS2 (the points also go to pts if not NULL, for a control on the same
 * measurement) and judges them */
static int edge2d_follows_edgeworth(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                                    int vs_class, int nmin, double rate, double rtol, double rel,
                                    const char *name, int verbose, ics_clt_point *pts) {
  ics_clt_point p[NS2];
  if (ics_clt2d_measure(gen, ctx, s, STEPS2, NS2, p) != ICS_OK) return -1;
  if (verbose) print2(name, p, NS2);
  if (pts)
    for (int i = 0; i < NS2; i++) pts[i] = p[i];
  return edge2d_judge(gen, ctx, s, p, NS2, vs_class, nmin, rate, rtol, rel, verbose);
}

static ics_clt2d_setup setup2(ics_clt2d_occluder occ, double angle, const ics_class2d *c) {
  ics_clt2d_setup s;
  ics_clt2d_setup_init(&s);
  s.occluder = occ;
  s.edge_angle_deg = angle;
  s.mean[0] = c->mean[0], s.mean[1] = c->mean[1];
  s.cov[0] = c->cxx, s.cov[1] = c->cxy, s.cov[2] = c->cyy;
  return s;
}


/* ASSERTION (2D exactness, small n): the nodes hold exactly the cdf of u . (K_n + U) (edge) /
 * of K_n + U (corner) and the limits carry the pixel's 1/12: for n = 1, 2, 3 the test convolves
 * the applied integer taps itself (double, no engine), forms the node values from the pixel
 * coverage, sums the applied taps' means and covariances itself (m, C) and takes the sup of
 * |node - limit| for the class limit N(n mu, n Sigma + I/12) (*cls) and the realised one
 * N(m, C + I/12) (*real) over the documented window: the union of |x - n mu|_inf <= 4.5 sd_n
 * and |x - m|_inf <= 4.5 sdr_n (nodes at half-integers, sd_n^2 = n lambda_max + 1/12, sdr_n^2 =
 * lambda_max(C) + 1/12); ics_clt2d_measure must report the same numbers to float storage
 * (tol 2e-7; measured <= 3.2e-8). */
static double lmax2(double cxx, double cxy, double cyy) {
  return 0.5 * (cxx + cyy) + sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
}
static double limit2(const ics_clt2d_setup *s, double ux, double uy, double px, double py,
                     const double m[2], double vx, double vxy, double vy) {
  px -= m[0], py -= m[1];
  if (s->occluder == ICS_CLT2D_EDGE)
    return phic((ux * px + uy * py) / sqrt(ux * ux * vx + 2 * ux * uy * vxy + uy * uy * vy));
  return bvn_ref(px / sqrt(vx), py / sqrt(vy), vxy / sqrt(vx * vy));
}
static void exact_sup(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s, int n, double *cls,
                      double *real) {
  enum { R = 40, D = 2 * R + 1 };
  static double P[D * D], Q[D * D];
  static ics_tap2d t[4 * 4096 + 9];
  double m[2] = {0, 0}, C[3] = {0, 0, 0};
  *cls = *real = NAN;
  for (int i = 0; i < D * D; i++) P[i] = 0;
  P[R * D + R] = 1;
  for (int k = 0; k < n; k++) {
    int nt = applied2(gen, ctx, (uint64_t)k, t, 4 * 4096 + 9);
    double w = 0, mx = 0, my = 0, cxx = 0, cxy = 0, cyy = 0;
    for (int j = 0; j < nt; j++) w += t[j].w, mx += t[j].w * t[j].x, my += t[j].w * t[j].y;
    mx /= w, my /= w;
    for (int j = 0; j < nt; j++) {
      double dx = t[j].x - mx, dy = t[j].y - my;
      cxx += t[j].w * dx * dx, cxy += t[j].w * dx * dy, cyy += t[j].w * dy * dy;
    }
    m[0] += mx, m[1] += my, C[0] += cxx / w, C[1] += cxy / w, C[2] += cyy / w;
    for (int i = 0; i < D * D; i++) Q[i] = 0;
    for (int y = 0; y < D; y++)
      for (int x = 0; x < D; x++) {
        if (P[y * D + x] == 0) continue;
        for (int j = 0; j < nt; j++) {
          int xx = x + (int)t[j].x, yy = y + (int)t[j].y;
          if (xx < 0 || yy < 0 || xx >= D || yy >= D) return;
          Q[yy * D + xx] += P[y * D + x] * t[j].w;
        }
      }
    for (int i = 0; i < D * D; i++) P[i] = Q[i];
  }
  double cxx = s->cov[0], cxy = s->cov[1], cyy = s->cov[2], pix = 1.0 / 12;
  double W = 4.5 * sqrt(n * lmax2(cxx, cxy, cyy) + pix);
  double Wr = 4.5 * sqrt(lmax2(C[0], C[1], C[2]) + pix);
  double ux = cos(s->edge_angle_deg * ICS_PI / 180), uy = sin(s->edge_angle_deg * ICS_PI / 180);
  double cm[2] = {n * s->mean[0], n * s->mean[1]}, wc = 0, wr = 0;
  double lo = fmin(-W, fmin(m[0], m[1]) - Wr), hi = fmax(W, fmax(m[0], m[1]) + Wr);
  for (double py = floor(lo) - 0.5; py <= hi + 1; py += 1)
    for (double px = floor(lo) - 0.5; px <= hi + 1; px += 1) {
      int in_c = fabs(px - cm[0]) <= W && fabs(py - cm[1]) <= W;
      int in_r = fabs(px - m[0]) <= Wr && fabs(py - m[1]) <= Wr;
      if (!in_c && !in_r) continue;
      double r = 0;
      for (int y = 0; y < D; y++)
        for (int x = 0; x < D; x++) {
          double w = P[y * D + x];
          if (w == 0) continue;
          double qx = px - (x - R), qy = py - (y - R);
          if (s->occluder == ICS_CLT2D_EDGE)
            r += w * ics_clt2d_edge_coverage(ux, uy, ux * qx + uy * qy);
          else
            r += w * (qx > 0 && qy > 0);
        }
      wc = fmax(wc, fabs(r - limit2(s, ux, uy, px, py, cm, n * cxx + pix, n * cxy, n * cyy + pix)));
      wr = fmax(wr, fabs(r - limit2(s, ux, uy, px, py, m, C[0] + pix, C[1], C[2] + pix)));
    }
  *cls = wc, *real = wr;
}

static void test_2d_exact(void) {
  ics_class2d c;
  CHECK(ics_class2d_init_axes(&c, 0, 0, 3, 1.5, 30) == ICS_OK, "class");
  ics_kernel2d pk;
  CHECK(ics_kernel2d_init(&pk, ICS_KERNEL_POISSON, &c) == ICS_OK, "poisson");
  /* the golden-ratio 2-sample ellipse at start offset 0.25 (rank-one steps: the compensation's
   * fallback makes the realised moments differ from the class) */
  ics_clt2d_ellipse eg = {{0, 0}, 3, 1.5, 30, 2, 0.25, ICS_CLT2D_GOLDEN};
  static const int ST[] = {1, 2, 3};
  for (int cs = 0; cs < 3; cs++) {
    int occ = cs == 1, golden = cs == 2;
    ics_clt2d_setup s = setup2(occ ? ICS_CLT2D_CORNER : ICS_CLT2D_EDGE, 30, &c);
    s.refine = 0;
    ics_clt2d_gen gen = golden ? ics_clt2d_ellipse_gen : ics_clt2d_member_gen;
    void *ctx = golden ? (void *)&eg : (void *)&pk;
    const char *name = golden ? "edge 30 deg, golden 2-sample ellipse (offset 0.25)"
                              : occ ? "corner, poisson" : "edge 30 deg, poisson";
    ics_clt_point p[3];
    CHECK(ics_clt2d_measure(gen, ctx, &s, ST, 3, p) == ICS_OK, "measure");
    for (int i = 0; i < 3; i++) {
      double ref, ref_r;
      exact_sup(gen, ctx, &s, ST[i], &ref, &ref_r);
      printf("  exact %s (3, 1.5, 30 deg), n = %d: measured sup %.6e / realised %.6e, direct "
             "convolution %.6e / %.6e\n", name, ST[i], p[i].sup_err, p[i].sup_err_realized, ref,
             ref_r);
      CHECK(fabs(p[i].sup_err - ref) <= 2e-7, "%s n = %d: %.9g vs %.9g", name, ST[i],
            p[i].sup_err, ref);
      CHECK(fabs(p[i].sup_err_realized - ref_r) <= 2e-7, "%s n = %d: realised %.9g vs %.9g",
            name, ST[i], p[i].sup_err_realized, ref_r);
    }
  }
  /* the golden schedule itself: step i's taps are ics_ellipse_kernel at offset frac(U + i phi)
   * (phi = (sqrt 5 - 1)/2, formed here in long double), moved to the mean */
  ics_clt2d_ellipse e3 = {{0.5, -1.25}, 3, 1.5, 30, 5, 0.25, ICS_CLT2D_GOLDEN};
  double worst = 0;
  for (int i = 0; i < 40; i++) {
    ics_tap2d t[16];
    int nt = 0;
    long double u = 0.25L + (long double)i * ((sqrtl(5.0L) - 1) / 2);
    double off = (double)(u - floorl(u)), xy[2 * 16];
    ics_ellipse_shape sh;
    CHECK(ics_clt2d_ellipse_gen(&e3, (uint64_t)i, 1.0, t, 16, &nt) == ICS_OK &&
              ics_ellipse_kernel(3, 1.5, 30, 5, off, &sh, xy) == ICS_OK && nt == sh.nsamples,
          "golden step %d", i);
    for (int j = 0; j < nt && j < sh.nsamples; j++)
      worst = fmax(worst, fmax(fabs(t[j].x - 0.5 - xy[2 * j]), fabs(t[j].y + 1.25 - xy[2 * j + 1])));
  }
  printf("  golden schedule: steps 0..39 vs ics_ellipse_kernel at frac(0.25 + i phi): max tap "
         "difference %.2e\n", worst);
  CHECK(worst <= 1e-9, "golden schedule taps off by %.3g", worst);
}

/* ASSERTION (2D, realised mean away from the class path): a generator whose integer taps
 * (x = 0, 1, 2 with weights 1/4, 1/2, 1/4, y = 0) have mean (1, 0) per step while the setup's
 * class has mean 0 (class covariance = the taps' own, (1/2, 0, 0)). The nodes hold exactly
 * P(Binomial(2n, 1/2) <= m) at x = m + 1/2 (K_n + U < m + 1/2 iff K_n <= m), so the test forms
 * both errors itself: realised limit Phi((x - n) / sqrt(n/2 + 1/12)), class limit
 * Phi(x / sqrt(n/2 + 1/12)), sup over the union of the two windows |x|, |x - n| <= 4.5 sd_n. At
 * n = 64, 256 the realised mean lies 11 and 23 sd from n mu: a window that follows only n mu
 * misses the realised error's peak (it reported 1.3e-12 and 5.6e-74 there). */
static ics_status drift_gen(void *ctx, uint64_t step, double scale, ics_tap2d *taps, int cap,
                            int *ntaps) {
  (void)ctx, (void)step;
  if (cap < 3) return ICS_ERR_SIZE;
  for (int i = 0; i < 3; i++) taps[i].x = i * scale, taps[i].y = 0, taps[i].w = i == 1 ? 0.5 : 0.25;
  *ntaps = 3;
  return ICS_OK;
}

static void drift_ref(int n, double *err_class, double *err_real) {
  double sd = sqrt(0.5 * n + 1.0 / 12), W = 4.5 * sd, ec = 0, er = 0;
  for (double x = -floor(W + 0.5) + 0.5; x <= n + W; x += 1) {
    if (fabs(x) > W && fabs(x - n) > W) continue;
    double m = x - 0.5, cdf = 0; /* P(Bin(2n, 1/2) <= m) */
    for (int k = 0; k <= 2 * n && k <= m; k++)
      cdf += exp(lgamma(2 * n + 1.0) - lgamma(k + 1.0) - lgamma(2 * n - k + 1.0) - 2 * n * log(2.0));
    ec = fmax(ec, fabs(cdf - phic(x / sd)));
    er = fmax(er, fabs(cdf - phic((x - n) / sd)));
  }
  *err_class = ec, *err_real = er;
}

static void test_2d_drift(void) {
  ics_clt2d_setup s;
  ics_clt2d_setup_init(&s);
  s.cov[0] = 0.5;
  static const int ST[] = {16, 64, 256};
  ics_clt_point p[3];
  CHECK(ics_clt2d_measure(drift_gen, NULL, &s, ST, 3, p) == ICS_OK, "drift measure");
  print2("integer taps of mean (1, 0) per step, class mean 0, edge 0 deg", p, 3);
  for (int i = 0; i < 3; i++) {
    double ec, er;
    drift_ref(ST[i], &ec, &er);
    printf("    n = %-4d reference: class %.6e, realised %.6e (binomial cdf)\n", ST[i], ec, er);
    CHECK(fabs(p[i].sup_err - ec) <= 1e-6 && fabs(p[i].sup_err_realized - er) <= 1e-6,
          "drift n = %d: class %.9g vs %.9g, realised %.9g vs %.9g", ST[i], p[i].sup_err, ec,
          p[i].sup_err_realized, er);
  }
}

static void test_2d_members(void) {
  /* class: sigma^2 = (9, 4.5) px^2 rotated 30 degrees, mean 0 */
  ics_class2d c;
  CHECK(ics_class2d_init_axes(&c, 0, 0, 9, 4.5, 30) == ICS_OK, "class");
  ics_kernel2d pk;
  CHECK(ics_kernel2d_init(&pk, ICS_KERNEL_POISSON, &c) == ICS_OK, "poisson");
  ics_clt2d_setup s = setup2(ICS_CLT2D_EDGE, 30, &c);
  CHECK(edge2d_follows_edgeworth(ics_clt2d_member_gen, &pk, &s, 1, 16, -1.0, 0.1, 0.1,
                                 "poisson N = 8, edge 30 deg", 1, NULL) == 1,
        "poisson: not the Edgeworth n^-1 behaviour against the class");
  /* broken on purpose, on exactly the parameters just passed (steps 8..64, n >= 16): a Poisson
   * kernel of covariance 1.1 Sigma measured against Sigma (the error stops decreasing). A
   * check of the test, not of a code path: skipped under the sanitizer (~4 s there). */
  ics_class2d cw = c;
  cw.cxx *= 1.1, cw.cxy *= 1.1, cw.cyy *= 1.1;
  ics_kernel2d pw;
  CHECK(ics_kernel2d_init(&pw, ICS_KERNEL_POISSON, &cw) == ICS_OK, "poisson 1.1");
  if (SANITIZED)
    printf("  broken 1.1 Sigma edge control: skipped under the sanitizer (Release runs it)\n");
  else
    CHECK(edge2d_follows_edgeworth(ics_clt2d_member_gen, &pw, &s, 1, 16, -1.0, 0.1, 0.1, "", 0,
                                   NULL) == 0,
          "2D covariance mismatch NOT detected");
  /* fixed offset 0, N = 3: one tap on the major axis (30 deg), so every step is skewed except
   * in projection on the minor axis (120 deg: the taps are symmetric about the major axis;
   * there the rate is n^-1, docs/theory.md, but the grid resolves it only from n = 64 on) */
  ics_clt2d_ellipse fx3 = {{0, 0}, 9, 4.5, 30, 3, 0, 0};
  s.edge_angle_deg = 60;
  /* skewed: rate -1/2 asymptotically; at n = 16..64 the n^-1 kurtosis term still adds (the
   * Edgeworth prediction's own slope there is -0.6), hence the band 0.2 */
  ics_clt_point p3[NS2];
  CHECK(edge2d_follows_edgeworth(ics_clt2d_ellipse_gen, &fx3, &s, 0, 16, -0.5, 0.2, 0.1,
                                 "ellipse N = 3, fixed offset 0, edge 60 deg", 1, p3) == 1,
        "fixed-offset 3-sample ellipse: not the skewed n^-1/2 behaviour at 60 deg");
  /* broken on purpose, the same measurement: the skewed direction claimed to converge like n^-1 */
  CHECK(edge2d_judge(ics_clt2d_ellipse_gen, &fx3, &s, p3, NS2, 0, 16, -1.0, 0.2, 0.1, 0) == 0,
        "2D wrong rate for the skewed ellipse NOT detected");
  /* random offset per step (the kernel.h member), N = 8: symmetric steps -> n^-1 against the
   * realised moments */
  ics_kernel2d e8;
  CHECK(ics_kernel2d_init(&e8, ICS_KERNEL_ELLIPSE, &c) == ICS_OK, "ellipse");
  e8.nsamples = 8;
  s.edge_angle_deg = 30;
  if (SANITIZED)
    printf("  ellipse N = 8, random offset: skipped under the sanitizer (Release runs it)\n");
  else
    CHECK(edge2d_follows_edgeworth(ics_clt2d_member_gen, &e8, &s, 0, 16, -1.0, 0.1, 0.1,
                                   "ellipse N = 8, random offset per step, edge 30 deg", 1,
                                   NULL) == 1,
          "random-offset 8-sample ellipse: not n^-1 against its realised moments");
  /* the 2-sample ellipse, fixed offset 0: rank-one steps along the major axis (30 deg), so the
   * class Gaussian is the wrong limit: across the major axis (edge at 120 deg) the error
   * against it stops decreasing (~0.33: the image is barely blurred along 120 deg) */
  ics_clt2d_ellipse fx2 = {{0, 0}, 9, 4.5, 30, 2, 0, 0};
  ics_clt_point p[NS2];
  static const int ST3[] = {8, 16, 32};
  s.edge_angle_deg = 120;
  CHECK(ics_clt2d_measure(ics_clt2d_ellipse_gen, &fx2, &s, ST3, 3, p) == ICS_OK, "measure");
  print2("ellipse N = 2, fixed offset 0, edge 120 deg", p, 3);
  CHECK(p[2].sup_err > 0.9 * p[1].sup_err && p[2].sup_err > 0.1,
        "fixed 2-sample ellipse converges to the class?");
  /* the Gaussian 5 x 5 member is a comb (taps 1.5 sd apart): at n = 8, 16 its error is below
   * the 2x-grid change, i.e. grid smoothing, not a measurement (as the 1D 9-tap comb) */
  ics_kernel2d gk;
  CHECK(ics_kernel2d_init(&gk, ICS_KERNEL_GAUSS, &c) == ICS_OK, "gauss");
  s.edge_angle_deg = 30;
  CHECK(ics_clt2d_measure(ics_clt2d_member_gen, &gk, &s, STEPS2, 2, p) == ICS_OK, "measure");
  print2("gauss 5 x 5, edge 30 deg", p, 2);
  int unres2 = 1;
  for (int i = 0; i < 2; i++) {
    CHECK(p[i].disc_err > p[i].sup_err, "gauss comb n = %d: disc %.3g vs sup %.3g", p[i].steps,
          p[i].disc_err, p[i].sup_err);
    unres2 = unres2 && p[i].disc_err > p[i].sup_err;
  }
  printf("    -> %s\n", unres2 ? "unresolved (no rate claimed): grid smoothing at n = 8, 16 (disc > sup)"
                                : "NOT unresolved as asserted");
}

/* ASSERTION FUNCTION (2D corner, limit = bivariate normal cdf of N(n mu, n Sigma + I/12)): the
 * class error's rate over the 3 step counts st is within rtol of -1 and every point is resolved
 * (disc < err / 10). The Poisson member's per-step third cumulants are random (random rotation),
 * so the n^-1 coefficient fluctuates: the band is 0.25. 1 = pass, 0 = fail, -1 = measure
 * failed. */
static int corner2d_converges(const ics_kernel2d *k, const ics_class2d *c, const int *st,
                              double rtol, const char *name, int verbose) {
  ics_clt2d_setup s = setup2(ICS_CLT2D_CORNER, 0, c);
  ics_clt_point p[3];
  if (ics_clt2d_measure(ics_clt2d_member_gen, (void *)k, &s, st, 3, p) != ICS_OK) return -1;
  if (verbose) print2(name, p, 3);
  double r = ics_clt_rate(p, 3, st[0]);
  int ok = fabs(r + 1) <= rtol;
  for (int i = 0; i < 3; i++)
    if (!(p[i].disc_err < 0.1 * p[i].sup_err)) ok = 0;
  if (verbose) printf("    rate (n >= %d) %.4f, expected -1 +- %.2f\n", st[0], r, rtol);
  return ok;
}

static void test_2d_corner(void) {
  if (SANITIZED) {
    printf("  corner convergence: skipped under the sanitizer (Release runs it)\n");
    return;
  }
  /* sigma^2 = (25, 12.5) px^2 at 30 deg: the corner's axis-aligned sides need ~5 px per step
   * for the 2x grid to change the error by < 10 % (at (9, 4.5) it changes it by ~20 %) */
  ics_class2d c, cw;
  CHECK(ics_class2d_init_axes(&c, 0, 0, 25, 12.5, 30) == ICS_OK, "class");
  CHECK(ics_class2d_init_axes(&cw, 0, 0, 27.5, 13.75, 30) == ICS_OK, "class");
  ics_kernel2d pk, pw;
  CHECK(ics_kernel2d_init(&pk, ICS_KERNEL_POISSON, &c) == ICS_OK, "poisson");
  static const int ST[] = {8, 16, 32};
  CHECK(corner2d_converges(&pk, &c, ST, 0.25, "poisson N = 8, corner, (25, 12.5, 30 deg)", 1) == 1,
        "corner: poisson not n^-1 to the bivariate normal");
  /* broken on purpose, on the same steps: covariance 1.1 Sigma measured against Sigma */
  CHECK(ics_kernel2d_init(&pw, ICS_KERNEL_POISSON, &cw) == ICS_OK, "poisson 1.1");
  CHECK(corner2d_converges(&pw, &c, ST, 0.25, "", 0) == 0,
        "corner: covariance mismatch NOT detected");
}

int main(void) {
  test_members();
  test_lattice();
  test_stochastic();
  test_eq8();
  test_2d_mapping();
  test_bvn();
  test_2d_exact();
  test_2d_drift();
  test_2d_members();
  test_2d_corner();
  return test_summary("test_clt_convergence");
}
