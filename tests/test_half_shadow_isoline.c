/* test_half_shadow_isoline.c — the half-shadow isoline claim of Patel et al. 2013, Appendix
 * A.5 ("the iterative 1/2-isoline equals the correct one for any light"), tested where its
 * proof's assumptions hold and where they fail, with the shadow ACTUALLY ITERATED by the conv
 * engine (ics_iter1d_create), plus the isoline formulas of A.3/A.4 and Eq. 8.
 *
 * Where the expectations come from (none is read off the code under test):
 * - correct 1/2-isoline: x = -d median(l) (Eq. 17 with s = 1/2); medians of the lights are
 *   closed forms (Gaussian: the mean; box: the centre; triangle (0, 1, 3): 3 - sqrt(3)) or, for
 *   mixtures, a bisection on the mixture cdf written out here with erfc.
 * - symmetric kernel: kappa^{*n} is symmetric about n mu_k = -d mu_l, so its median is its mean
 *   and the iterated 1/2-isoline is x = -d mu_l: the deviation from the correct one is exactly
 *   d (median - mean) of the light (0 for symmetric lights).
 * - skewed kernel (skewness g, std sigma_k) with a symmetric light: Edgeworth's expansion
 *   F(z) = Phi(z) - g/(6 sqrt n) (z^2 - 1) phi(z) + O(1/n) puts the median of kappa^{*n} at
 *   n mu_k - g sigma_k / 6 + O(n^-1/2): a CONSTANT offset -g sigma_k / 6 at every distance.
 * - at d = d1 and for a Gaussian light every iterated isoline equals the correct one up to the
 *   CLT error (Eq. 8); the position tolerance is the tophat's Edgeworth term
 *   |gamma2| / 24 max|He3 phi| / n divided by the density at the isoline.
 * Tolerances are relative to the penumbra width sigma_n = sqrt(d d1 var_l). Each assertion
 * function is also run on a deliberately broken mapping (kernel mean sign flipped, variance
 * e var_l instead of d1 e var_l) and must then report failure. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "icshadow.h"
#include "testutil.h"

static const double E_SLAB = 1.0 / 64; /* slab spacing: n = 16 .. 256 steps for d = 0.25 .. 4 */
static const double DS[] = {0.25, 0.5, 1, 2, 4};
#define ND 5
#define TOL_SYM 2e-3 /* |x_it - x_expected| <= TOL_SYM * sigma_n (grid and interpolation) */

/* independent mixture median: bisection on sum w_i Phi((x - mu_i) / s_i) - 1/2 */
static double mix_median(int n, const double *w, const double *mu, const double *var) {
  double sw = 0, lo = -1e3, hi = 1e3;
  for (int i = 0; i < n; i++) sw += w[i];
  for (int it = 0; it < 200; it++) {
    double x = 0.5 * (lo + hi), c = 0;
    for (int i = 0; i < n; i++) c += w[i] / sw * 0.5 * erfc(-(x - mu[i]) / sqrt(2 * var[i]));
    if (c < 0.5)
      lo = x;
    else
      hi = x;
  }
  return 0.5 * (lo + hi);
}

/* ASSERTION FUNCTION: does the iterated 1/2-isoline sit at -d mean_l + offset(d), with
 * offset(d) = slope * d + offset0, within tol * sigma_n at every distance? Returns 1 if so.
 * worst (may be NULL) gets the largest |deviation| / sigma_n. */
static int half_isoline_at(const ics_light1d *l, const ics_iter1d_opts *o, double d1,
                           double slope, double offset0, double tol, double dmin, double *worst,
                           int verbose) {
  int ok = 1;
  double w = 0;
  for (int i = 0; i < ND; i++) {
    double d = DS[i];
    if (d < dmin) continue;
    double x, disc;
    ics_status st = ics_isoline_iterative(l, 0.5, d, d1, E_SLAB, o, &x, &disc);
    if (st != ICS_OK) return 0;
    double sd = sqrt(d * d1 * ics_light1d_var(l));
    double expect = -d * ics_light1d_mean(l) + slope * d + offset0;
    double dev = fabs(x - expect) / sd;
    if (verbose)
      printf("    d = %-5g x_it = %-+12.7f expected %-+12.7f |dev|/sigma_n = %.2e (disc. est. "
             "%.1e sigma_n)\n", d, x, expect, dev, disc / sd);
    if (dev > w) w = dev;
    if (!(dev <= tol) || !(disc / sd <= tol)) ok = 0;
  }
  if (worst) *worst = w;
  return ok;
}

static void test_formulas(void) {
  /* box light [lo, hi]: L^-1(1 - s) = hi - s (hi - lo), so x = -d (hi - s (hi - lo)) */
  ics_light1d *b = NULL, *g = NULL;
  CHECK(ics_light1d_create_box(&b, -0.5, 1.5) == ICS_OK, "box");
  for (int k = 1; k <= 9; k++) {
    double s = k / 10.0, d = 1.7;
    double x = ics_isoline_correct(b, s, d), ref = -d * (1.5 - s * 2.0);
    CHECK(fabs(x - ref) <= 4 * DBL_EPSILON * fabs(d * 1.5), "box isoline s=%g: %.17g vs %.17g", s,
          x, ref);
    /* the correct shadow has value s there: 1 - L(-x/d) = s */
    CHECK(fabs(ics_shadow1d_correct(b, d, x) - s) < 1e-15, "s_d(x) = %.17g, want %g",
          ics_shadow1d_correct(b, d, x), s);
  }
  /* Gaussian light: correct x = -d (mu - sigma Phi^-1(s)), CLT x = -d mu + Phi^-1(s)
   * sqrt(d d1) sigma: equal at d = d1, and their difference is Phi^-1(s) sigma (sqrt(d d1) - d) */
  ics_light1d_destroy(b);
  double mu = 0.3, var = 0.8, d1 = 2.0;
  CHECK(ics_light1d_create_gauss(&g, mu, var) == ICS_OK, "gauss");
  double z90 = 1.2815515655446004; /* published Phi^-1(0.9) */
  for (int i = 0; i < ND; i++) {
    double d = DS[i];
    double xc = ics_isoline_correct(g, 0.9, d), xl = ics_isoline_clt(g, 0.9, d, d1);
    double rc = -d * (mu - sqrt(var) * z90), rl = -d * mu + z90 * sqrt(d * d1 * var);
    CHECK(fabs(xc - rc) < 1e-14 * (1 + fabs(rc)) && fabs(xl - rl) < 1e-14 * (1 + fabs(rl)),
          "d=%g: correct %.17g vs %.17g, clt %.17g vs %.17g", d, xc, rc, xl, rl);
  }
  CHECK(fabs(ics_isoline_clt(g, 0.1, d1, d1) - ics_isoline_correct(g, 0.1, d1)) < 1e-14,
        "CLT and correct isolines meet at d1");
  CHECK(isnan(ics_isoline_correct(g, 0, 1)) && isnan(ics_isoline_correct(g, 1, 1)) &&
            isnan(ics_isoline_clt(g, 0.5, -1, 1)) && isnan(ics_isoline_clt(g, 0.5, 1, 0)),
        "domain: s in (0, 1), d >= 0, d1 > 0");
  CHECK(ics_shadow1d_correct(g, 0, 0.1) == 1 && ics_shadow1d_correct(g, 0, -0.1) == 0,
        "d = 0: the edge itself (opaque for x > 0)");
  /* sign convention: light at +x throws the shadow toward -x */
  CHECK(ics_isoline_correct(g, 0.5, 1) < 0 && ics_shadow1d_correct(g, 1, 10) > 0.999,
        "shadow toward -x for mu_l > 0; umbra at x -> +inf");
  ics_light1d_destroy(g);
}

/* A.5 holds: symmetric lights, symmetric kernels (also the stochastic Dirac: each iteration's
 * taps are symmetric about the class mean, so every partial sum is symmetric) */
static void test_holds(void) {
  ics_light1d *lights[3] = {NULL, NULL, NULL};
  double w[2] = {0.5, 0.5}, mu[2] = {-1.2, 1.6}, v[2] = {0.15, 0.15}; /* two peaks, symmetric */
  CHECK(ics_light1d_create_gauss(&lights[0], 0.3, 1.0) == ICS_OK &&
            ics_light1d_create_box(&lights[1], -0.5, 1.5) == ICS_OK &&
            ics_light1d_create_mix(&lights[2], 2, w, mu, v) == ICS_OK,
        "lights");
  const char *lname[3] = {"gauss(0.3, 1)", "box(-0.5, 1.5)", "two-peak symmetric mix"};
  ics_kernel_member mem[4] = {ICS_KERNEL_DIRAC, ICS_KERNEL_TOPHAT, ICS_KERNEL_STOCH_DIRAC,
                              ICS_KERNEL_GAUSS};
  for (int li = 0; li < 3; li++)
    for (int k = 0; k < 4; k++) {
      ics_iter1d_opts o;
      ics_iter1d_opts_init(&o);
      o.member = mem[k];
      double worst;
      printf("  A.5 holds? light %s, kernel %s:\n", lname[li], ics_kernel_member_name(mem[k]));
      int ok = half_isoline_at(lights[li], &o, 1.0, 0, 0, TOL_SYM, 0, &worst, 1);
      CHECK(ok, "light %s kernel %s: worst |x_it - x_correct| = %.3g sigma_n > %g", lname[li],
            ics_kernel_member_name(mem[k]), worst, TOL_SYM);
      /* the correct 1/2-isoline of a symmetric light is -d mean: consistent with the above */
      CHECK(fabs(ics_isoline_correct(lights[li], 0.5, 2) + 2 * ics_light1d_mean(lights[li])) <
                1e-12,
            "symmetric light median = mean");
      /* broken on purpose: kernel mean +e mu_l instead of -e mu_l. The same assertion must
       * now fail (mu_l != 0 for all three lights) */
      o.mean_sign = -1;
      CHECK(!half_isoline_at(lights[li], &o, 1.0, 0, 0, TOL_SYM, 0, NULL, 0),
            "flipped kernel mean NOT detected for light %s kernel %s", lname[li],
            ics_kernel_member_name(mem[k]));
    }
  for (int li = 0; li < 3; li++) ics_light1d_destroy(lights[li]);
}

/* A.5 fails: lights whose median differs from their mean. Expected deviation d (median - mean)
 * (symmetric kernels), linear in d, i.e. sqrt(d / d1) (median - mean) / sigma_l in units of the
 * penumbra width. */
static void test_fails_asymmetric_light(void) {
  ics_light1d *lights[3] = {NULL, NULL, NULL};
  double w[2] = {0.8, 0.2}, mu[2] = {0, 2}, v[2] = {0.25, 0.25};
  double med_m = mix_median(2, w, mu, v);
  double tx[3] = {0, 1, 3}, tp[3] = {0, 1, 0};
  double med_t = 3 - sqrt(3.0); /* triangle (0, 1, 3): 1 - (3 - x)^2 / 6 = 1/2 */
  double w3[3] = {0.5, 0.3, 0.2}, mu3[3] = {-1, 0.5, 2.5}, v3[3] = {0.1, 0.2, 0.1};
  double med_3 = mix_median(3, w3, mu3, v3);
  CHECK(ics_light1d_create_mix(&lights[0], 2, w, mu, v) == ICS_OK &&
            ics_light1d_create_tab(&lights[1], 3, tx, tp) == ICS_OK &&
            ics_light1d_create_mix(&lights[2], 3, w3, mu3, v3) == ICS_OK,
        "lights");
  double med[3] = {med_m, med_t, med_3};
  double mean_ref[3] = {0.4, 4.0 / 3.0, 0.5 * -1 + 0.3 * 0.5 + 0.2 * 2.5};
  const char *lname[3] = {"mix 0.8 N(0,.25) + 0.2 N(2,.25)", "triangle (0,1,3)",
                          "three-peak mix"};
  ics_kernel_member mem[3] = {ICS_KERNEL_DIRAC, ICS_KERNEL_TOPHAT, ICS_KERNEL_STOCH_DIRAC};
  for (int li = 0; li < 3; li++) {
    CHECK(fabs(ics_light1d_mean(lights[li]) - mean_ref[li]) < 1e-14, "mean of %s", lname[li]);
    double gap = med[li] - mean_ref[li];
    printf("  light %s: skewness %.4f, median - mean = %.6f (%.4f sigma_l)\n", lname[li],
           ics_light1d_skewness(lights[li]), gap, gap / sqrt(ics_light1d_var(lights[li])));
    for (int k = 0; k < 3; k++) {
      ics_iter1d_opts o;
      ics_iter1d_opts_init(&o);
      o.member = mem[k];
      /* the iterated 1/2-isoline stays at -d mean: expected offset 0 from -d mean ... */
      printf("   kernel %s:\n", ics_kernel_member_name(mem[k]));
      double worst;
      int ok = half_isoline_at(lights[li], &o, 1.0, 0, 0, TOL_SYM, 0, &worst, 1);
      CHECK(ok, "iterated 1/2-isoline of %s (%s) is not at -d mean: %.3g sigma_n", lname[li],
            ics_kernel_member_name(mem[k]), worst);
      /* ... so A.5's claim (offset d (mean - median) from -d mean: the correct isoline) fails,
       * and the same assertion function reports it. Its size at d = 4, d1 = 1: */
      CHECK(!half_isoline_at(lights[li], &o, 1.0, -gap, 0, TOL_SYM, 0, NULL, 0),
            "A.5 claim unexpectedly holds for %s", lname[li]);
      double xc = ics_isoline_correct(lights[li], 0.5, 4.0);
      CHECK(fabs(xc + 4 * med[li]) < 1e-9, "correct 1/2-isoline %.17g vs -d median %.17g", xc,
            -4 * med[li]);
      /* the conclusion at d = 4 (d1 = 1): correct vs iterative, the failure's size against
       * A.5's prediction d (median - mean) */
      double xi, disc, sd4 = sqrt(4.0 * ics_light1d_var(lights[li]));
      CHECK(ics_isoline_iterative(lights[li], 0.5, 4.0, 1.0, E_SLAB, &o, &xi, &disc) == ICS_OK,
            "iterated isoline of %s at d = 4", lname[li]);
      double fail = xi - xc, pred = 4 * gap;
      printf("    A.5 fails at d = 4: correct %+.7f, iterative %+.7f, failure %+.6f (%.4f sigma_n),"
             " predicted d (median - mean) = %+.6f: %s\n", xc, xi, fail, fail / sd4, pred,
             fabs(fail - pred) <= TOL_SYM * sd4 ? "as predicted" : "NOT as predicted");
      CHECK(fabs(fail - pred) <= TOL_SYM * sd4, "%s (%s): failure %.6f vs predicted %.6f",
            lname[li], ics_kernel_member_name(mem[k]), fail, pred);
    }
  }
  for (int li = 0; li < 3; li++) ics_light1d_destroy(lights[li]);
}

/* skewness of a tap list (independent of the library's moment helpers) */
static double tap_skewness(const ics_tap1d *t, int n, double *sd) {
  double w = 0, m = 0, m2 = 0, m3 = 0;
  for (int i = 0; i < n; i++) w += t[i].w, m += t[i].w * t[i].x;
  m /= w;
  for (int i = 0; i < n; i++) {
    double d = t[i].x - m;
    m2 += t[i].w * d * d, m3 += t[i].w * d * d * d;
  }
  m2 /= w, m3 /= w;
  *sd = sqrt(m2);
  return m3 / (m2 * sqrt(m2));
}

/* A.5 with a non-symmetric kernel of the right class (mean -e mu_l, variance d1 e var_l) and a
 * symmetric light: the median of kappa^{*n} is off by -g sigma_k / 6 (Edgeworth) */
static void test_fails_skewed_kernel(void) {
  ics_tap1d t[ICS_CLT1D_SKEW_TAPS];
  CHECK(ics_clt1d_skew_taps(0, 1, t) == ICS_OK, "skew taps");
  double sdt, g = tap_skewness(t, ICS_CLT1D_SKEW_TAPS, &sdt);
  CHECK(fabs(sdt - 1) < 1e-12, "skew taps have the class variance: sd %.17g", sdt);
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_gauss(&l, 0.3, 1.0) == ICS_OK, "gauss");
  double d1 = 1.0, sk = sqrt(d1 * E_SLAB * 1.0);
  double off = -g * sk / 6;
  printf("  skewed kernel (skewness %.4f), Gaussian light: predicted offset -g sigma_k/6 = %.5f "
         "(sigma_k = %.4f)\n", g, off, sk);
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  o.skew = 1;
  double worst;
  /* d >= 1 (n >= 64): the O(n^-1/2) remainder of the median expansion is below 3% of the
   * offset there; tolerance 0.06 |offset| */
  double tol = 0.06 * fabs(off) / sqrt(1.0 * d1 * 1.0);
  int ok = half_isoline_at(l, &o, d1, 0, off, tol, 1.0, &worst, 1);
  CHECK(ok, "skewed kernel offset off by %.3g sigma_n (tol %.3g)", worst, tol);
  /* A.5's claim (zero offset) fails for this kernel */
  CHECK(!half_isoline_at(l, &o, d1, 0, 0, TOL_SYM, 1.0, NULL, 0),
        "skewed kernel: A.5 claim unexpectedly holds");
  ics_light1d_destroy(l);
}

/* ics_iter1d_eval, the linear interpolation of the iterated shadow's nodes, against the nodes
 * themselves: their values at the nodes, the chord between two neighbours at 1/4, 1/2 and 3/4 of
 * the cell, the end values outside the grid (0 and 1 to rounding: the grid reaches 14 final
 * standard deviations past the shadow), NaN for NaN or no shadow; and the interpolated shadow
 * is s at the isoline of level s (ics_iter1d_isoline). The tolerance 1e-12 covers the rounding
 * of x0 + i h back to the cell (~ n eps); a wrong node or weight is off by a node difference,
 * ~1e-3 here. */
static void test_iter1d_eval(void) {
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_gauss(&l, 0.3, 1.0) == ICS_OK, "gauss");
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  o.member = ICS_KERNEL_TOPHAT;
  ics_iter1d *it = NULL;
  CHECK(ics_iter1d_create(&it, l, 1.0, 1.0, E_SLAB, &o) == ICS_OK && it && it->n > 8, "iterate");
  if (!it) {
    ics_light1d_destroy(l);
    return;
  }
  const double tol = 1e-12;
  int bad_node = 0, bad_chord = 0;
  for (size_t i = 0; i + 1 < it->n; i += 5) {
    double x = it->x0 + (double)i * it->h;
    if (!(fabs(ics_iter1d_eval(it, x) - it->r[i]) <= tol)) bad_node++;
    for (int q = 1; q <= 3; q++) {
      double f = q / 4.0, want = it->r[i] + f * (it->r[i + 1] - it->r[i]);
      if (!(fabs(ics_iter1d_eval(it, x + f * it->h) - want) <= tol)) bad_chord++;
    }
  }
  CHECK(bad_node == 0, "eval at the nodes: %d off", bad_node);
  CHECK(bad_chord == 0, "eval inside a cell: %d off the chord", bad_chord);
  double left = it->x0 - 3 * it->h, right = it->x0 + (double)(it->n + 2) * it->h;
  CHECK(ics_iter1d_eval(it, left) == it->r[0] && ics_iter1d_eval(it, -INFINITY) == it->r[0] &&
            fabs(it->r[0]) <= tol,
        "left of the grid: %g", ics_iter1d_eval(it, left));
  CHECK(ics_iter1d_eval(it, right) == it->r[it->n - 1] &&
            ics_iter1d_eval(it, INFINITY) == it->r[it->n - 1] && fabs(it->r[it->n - 1] - 1) <= tol,
        "right of the grid: %g", ics_iter1d_eval(it, right));
  CHECK(isnan(ics_iter1d_eval(it, NAN)) && isnan(ics_iter1d_eval(NULL, 0)), "NaN x, no shadow");
  for (int k = 1; k <= 9; k++) {
    double s = k / 10.0, x = ics_iter1d_isoline(it, s);
    CHECK(fabs(ics_iter1d_eval(it, x) - s) <= tol, "eval at the %g-isoline %.17g: %.17g", s, x,
          ics_iter1d_eval(it, x));
  }
  ics_iter1d_destroy(it);
  ics_light1d_destroy(l);
}

/* Eq. 8 at d = d1 for a Gaussian light: all isolines 0.1 .. 0.9 of the iterated shadow equal the
 * correct ones. ASSERTION FUNCTION returning 1 when they do. */
static int isolines_meet_at_d1(const ics_light1d *l, const ics_iter1d_opts *o, double d1,
                               double *worst) {
  /* tophat: excess kurtosis -6/5 per step -> gamma2 = -1.2 / n; cdf error <= 1.2/24/n *
   * max|He3 phi|; position error = that / density(x) <= that / (phi(1.2816) / sigma_n) */
  double mhe3 = 0;
  for (double z = 0; z < 5; z += 1e-4)
    mhe3 = fmax(mhe3, fabs((z * z * z - 3 * z) * exp(-z * z / 2) / sqrt(2 * ICS_PI)));
  int n = (int)nearbyint(d1 / E_SLAB);
  double cdf_tol = 1.5 * 1.2 / 24 / n * mhe3;
  double pos_tol = cdf_tol / (exp(-0.5 * 1.2816 * 1.2816) / sqrt(2 * ICS_PI)) + TOL_SYM;
  ics_iter1d *it = NULL;
  if (ics_iter1d_create(&it, l, d1, d1, E_SLAB, o) != ICS_OK) return 0;
  double sd = sqrt(d1 * d1 * ics_light1d_var(l)), w = 0;
  for (int k = 1; k <= 9; k++) {
    double s = k / 10.0;
    double dev = fabs(ics_iter1d_isoline(it, s) - ics_isoline_correct(l, s, d1)) / sd;
    if (!(dev <= w)) w = dev;
  }
  ics_iter1d_destroy(it);
  if (worst) *worst = w;
  return w <= pos_tol;
}

static void test_meet_at_d1(void) {
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_gauss(&l, -0.4, 0.6) == ICS_OK, "gauss");
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  o.member = ICS_KERNEL_TOPHAT;
  double worst;
  double d1s[2] = {1.0, 2.0};
  for (int i = 0; i < 2; i++) {
    CHECK(isolines_meet_at_d1(l, &o, d1s[i], &worst),
          "d1 = %g: iterated isolines off the correct ones by %.3g sigma_n", d1s[i], worst);
    printf("  Gaussian light, tophat, d = d1 = %g: isolines 0.1..0.9 agree to %.2e sigma_n\n",
           d1s[i], worst);
  }
  /* broken on purpose: kernel variance e var_l instead of d1 e var_l (d1 = 2): detected */
  o.var_factor = 1.0;
  CHECK(!isolines_meet_at_d1(l, &o, 2.0, &worst), "variance e var_l NOT detected (%.3g)", worst);
  printf("  broken variance (e var_l, d1 = 2): off by %.3f sigma_n -> detected\n", worst);
  o.var_factor = 0;
  o.mean_sign = -1;
  CHECK(!isolines_meet_at_d1(l, &o, 2.0, &worst), "flipped mean NOT detected (%.3g)", worst);
  printf("  broken mean sign: off by %.3f sigma_n -> detected\n", worst);
  ics_light1d_destroy(l);
}

int main(void) {
  test_formulas();
  test_holds();
  test_fails_asymmetric_light();
  test_fails_skewed_kernel();
  test_meet_at_d1();
  test_iter1d_eval();
  return test_summary("test_half_shadow_isoline");
}
