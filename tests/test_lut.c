/* test_lut.c — lookup tables for ratioToab and abToVarx (lut.c, lut_data.c).
 *
 * Against the exact functions of ellipse.c (the reference here; ellipse.c has its own MPFR
 * tests). The errors are computed by this file's own loops, not by ics_lut_measure, except
 * where the stamp is checked (the stamp IS what ics_lut_measure printed):
 *   - the facts the tabulation relies on: limits s(0) = 1/sqrt 2, g(0) = 1/3, g(1/2) = 1/2;
 *     the identity g(t) + g(1 - t) = 1; the symmetry ratioToab(1/r) = 1 - ratioToab(r);
 *   - the library's tables (lut_data.c) equal a fresh ics_lut_build (so they were generated
 *     from the current exact functions), and the stamped errors equal a fresh measurement;
 *   - documented bounds (icshadow/lut.h) on an independent, denser sample: random rat
 *     log-uniform over [1e-300, 1e300], random t, and the ends: rat = 0, +inf, DBL_MIN,
 *     DBL_MAX; t = 0, 1, 1e-300, 1 - 2^-53; both for double evaluation and for the float
 *     mirror of the GPU code (bound + ICS_LUT_FLOAT_EXTRA);
 *   - special values and domain errors, exactly;
 *   - the error falls as 1/n^2 (observed order between n = 64 and 256 in [1.7, 2.3]);
 *   - ics_lut_ellipse_radii against a = (1 - t) sqrt(sc), b = t sqrt(sc), sc = varx / V_x(t)
 *     (exact t and V_x), the kernel radii of Patel Sec. 3.4, and against ics_ellipse_kernel;
 *   - API errors (ranges, NULL, a command that would break the stamp). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

static double rel(double x, double ref) {
  if (isnan(x) || isnan(ref)) return INFINITY;
  if (ref == 0 || isinf(ref) || isinf(x)) return x == ref ? 0 : INFINITY;
  return fabs(x - ref) / fabs(ref);
}

static unsigned long long rng = 0x243F6A8885A308D3ull;
static double uniform(void) {
  rng = rng * 6364136223846793005ull + 1442695040888963407ull;
  return (double)(rng >> 11) / 9007199254740992.0;
}

/* Exact unit radii a = 1 - t, b = t, each from the side where it is small. */
static void exact_ab(double rat, double *a, double *b) {
  if (rat <= 1) {
    *b = ics_ellipse_ratio_to_t(rat);
    *a = 1 - *b;
  } else {
    *a = isinf(rat) ? 0 : ics_ellipse_ratio_to_t(1 / rat);
    *b = 1 - *a;
  }
}

static double exact_g(double t) { return ics_ellipse_vx(t) / ((1 - t) * (1 - t)); }

static void test_facts(void) {
  /* t ~ sqrt(rat / 2) as rat -> 0: s(0) = 1/sqrt 2 is the limit of t / w. The next term is
   * O(sqrt(rat)) relative (t = q/sqrt2 (1 + O(q)), q = sqrt rat): 1e-9 at rat = 1e-20. */
  for (double r = 1e-12; r >= 1e-300; r *= 1e-8) {
    double t = ics_ellipse_ratio_to_t(r);
    CHECK(rel(t / sqrt(r / 2), 1.0) <= 2 * sqrt(r) + 1e-15, "ratio_to_t(%g) = %.17g, sqrt(r/2) = %.17g", r,
          t, sqrt(r / 2));
  }
  /* V_x(0) = 1/3 (a segment), V_x(1/2) = 1/8 (circle of radius 1/2). */
  CHECK(rel(ics_ellipse_vx(0), 1.0 / 3) <= 4 * DBL_EPSILON, "vx(0) = %.17g", ics_ellipse_vx(0));
  CHECK(rel(ics_ellipse_vx(0.5), 0.125) <= 4 * DBL_EPSILON, "vx(1/2) = %.17g", ics_ellipse_vx(0.5));
  /* g(t) + g(1 - t) = 1: var_x(B) + var_x(1/B) = E[cos^2] + E[sin^2] under the arc-length
   * measure of one ellipse. The table covers t <= 1/2 and relies on it for t > 1/2.
   * Tolerance: each g carries the exact functions' error (a few ulps) divided by (1 - t)^2 with
   * 1 - t exact; 64 ulps of 1. */
  double worst = 0;
  for (int i = 1; i <= 1000; i++) { /* g(1) is a limit (0/0 in V_x(t) / (1 - t)^2) */
    double t = i / 2000.0;
    double d = fabs(exact_g(t) + exact_g(1 - t) - 1);
    if (d > worst) worst = d;
    CHECK(d <= 64 * DBL_EPSILON, "g(%g) + g(%g) - 1 = %.3g", t, 1 - t, d);
  }
  printf("identity g(t) + g(1 - t) = 1: max deviation %.3g\n", worst);
  /* ratioToab(1/r) = 1 - ratioToab(r) */
  for (double r = 1e-6; r <= 1e6; r *= 7.3) {
    double d = fabs(ics_ellipse_ratio_to_t(1 / r) - (1 - ics_ellipse_ratio_to_t(r)));
    CHECK(d <= 8 * DBL_EPSILON, "ratio_to_t(1/%g) - (1 - ratio_to_t(%g)) = %.3g", r, r, d);
  }
}

static void test_builtin_is_fresh(void) {
  const ics_lut_tables *B = ics_lut_builtin();
  CHECK(B->n == ICS_LUT_BUILTIN_SIZE, "builtin size %d, documented %d", B->n, ICS_LUT_BUILTIN_SIZE);
  double *s = malloc(B->n * sizeof *s), *g = malloc(B->n * sizeof *g);
  CHECK(ics_lut_build(B->n, s, g) == ICS_OK, "ics_lut_build(%d)", B->n);
  int diff = 0;
  for (int i = 0; i < B->n; i++) diff += s[i] != B->s[i] || g[i] != B->g[i];
  CHECK(diff == 0, "%d entries of lut_data.c differ from ics_lut_build: run scripts/gen_luts.sh", diff);
  free(s);
  free(g);

  /* the stamp is a fresh measurement on the stamp grid */
  double er, ev, ek;
  long pts;
  ics_lut_builtin_stamp(&er, &ev, &ek, &pts);
  ics_lut_grid *G = NULL;
  CHECK(ics_lut_grid_create(&G, B->n, ICS_LUT_STAMP_PER_INTERVAL) == ICS_OK, "grid");
  ics_lut_error e;
  CHECK(ics_lut_measure(G, B, 0, &e) == ICS_OK, "measure");
  CHECK(e.ratio == er && e.vx == ev && e.radii == ek && e.points == pts,
        "stamp (%.17g %.17g %.17g %ld) != measured (%.17g %.17g %.17g %ld)", er, ev, ek, pts,
        e.ratio, e.vx, e.radii, e.points);
  printf("builtin n = %d, stamped max rel error: ratio %.3g, vx %.3g, radii %.3g (%ld points)\n",
         B->n, er, ev, ek, pts);
  /* the documented bounds are the stamped values rounded up */
  CHECK(er <= ICS_LUT_BUILTIN_RATIO_BOUND, "stamped ratio %.3g > bound", er);
  CHECK(ev <= ICS_LUT_BUILTIN_VX_BOUND, "stamped vx %.3g > bound", ev);
  CHECK(ek <= ICS_LUT_BUILTIN_RADII_BOUND, "stamped radii %.3g > bound", ek);
  ics_lut_grid_destroy(G);
}

/* Documented bounds on an independent sample, double and float evaluation. */
static void test_bounds(void) {
  const ics_lut_tables *B = ics_lut_builtin();
  int n = B->n;
  float *sf = malloc(n * sizeof *sf), *gf = malloc(n * sizeof *gf);
  for (int i = 0; i < n; i++) sf[i] = (float)B->s[i], gf[i] = (float)B->g[i];
  enum { NR = 60000, NV = 40000 };
  double mr = 0, mrf = 0, mv = 0, mvf = 0, mk = 0, mkf = 0;
  double fx = ICS_LUT_FLOAT_EXTRA;
  for (int j = 0; j < NR + 8; j++) {
    double r;
    if (j < NR / 2)
      r = pow(10.0, -300 + 600 * uniform()); /* the whole double range */
    else if (j < NR)
      r = pow(10.0, -8 + 16 * uniform()); /* the table's body, w in (1e-4, 1 - 1e-4) */
    else {
      const double sp[8] = {0, INFINITY, DBL_MIN, DBL_MAX, 1, 1e-300, FLT_MIN, FLT_MAX};
      r = sp[j - NR];
    }
    double a_ex, b_ex, a, b;
    exact_ab(r, &a_ex, &b_ex);
    ics_lut_ratio_to_ab(r, &a, &b);
    double e = fmax(rel(a, a_ex), rel(b, b_ex));
    if (e > mr) mr = e;
    CHECK(e <= ICS_LUT_BUILTIN_RATIO_BOUND, "rat %.17g: (a, b) = (%.17g, %.17g), exact (%.17g, %.17g), rel %.3g",
          r, a, b, a_ex, b_ex, e);
    CHECK(ics_lut_ratio_to_t(r) == b, "ratio_to_t(%g) != ratio_to_ab b", r);
    if (r <= DBL_MAX / 4) { /* kernel radii for (varx, vary) = (1, r), documented domain */
      double sc = r <= 1 ? 1 / ics_ellipse_vx(b_ex) : r / ics_ellipse_vx(a_ex), ka, kb;
      ics_lut_ellipse_radii(1, r, &ka, &kb);
      double ek = fmax(rel(ka, a_ex * sqrt(sc)), rel(kb, b_ex * sqrt(sc)));
      if (ek > mk) mk = ek;
      CHECK(ek <= ICS_LUT_BUILTIN_RADII_BOUND, "radii(1, %.17g) = (%.17g, %.17g) rel %.3g", r, ka, kb, ek);
    }
    float rf = (float)r; /* float mirror on float inputs in the normal range (and 0, inf) */
    if (rf == 0 || isinf(rf) || rf >= FLT_MIN) {
      double fa_ex, fb_ex;
      float fa, fb;
      exact_ab(rf, &fa_ex, &fb_ex);
      ics_lut_float_ratio_to_ab(n, sf, rf, &fa, &fb);
      double ef = fmax(rel(fa, fa_ex), rel(fb, fb_ex));
      if (ef > mrf) mrf = ef;
      CHECK(ef <= ICS_LUT_BUILTIN_RATIO_BOUND + fx, "float rat %.9g: rel %.3g", rf, ef);
      if (rf <= FLT_MAX / 4) {
        float ka, kb;
        double sc = rf <= 1 ? 1 / ics_ellipse_vx(fb_ex) : rf / ics_ellipse_vx(fa_ex);
        ics_lut_float_ellipse_radii(n, sf, gf, 1.0f, rf, &ka, &kb);
        double ek = fmax(rel(ka, fa_ex * sqrt(sc)), rel(kb, fb_ex * sqrt(sc)));
        if (ek > mkf) mkf = ek;
        CHECK(ek <= ICS_LUT_BUILTIN_RADII_BOUND + fx, "float radii(1, %.9g): rel %.3g", rf, ek);
      }
    }
  }
  for (int j = 0; j < NV + 8; j++) {
    double t;
    if (j < NV / 2)
      t = uniform();
    else if (j < NV) { /* both ends, log-uniform distance 1e-16..1e-1 */
      double d = pow(10.0, -16 + 15 * uniform());
      t = (j & 1) ? d : 1 - d;
    } else {
      const double sp[8] = {0, 1, 1e-300, 1 - DBL_EPSILON / 2, 0.5, DBL_MIN, 0.25, 0.75};
      t = sp[j - NV];
    }
    double v_ex = ics_ellipse_vx(t), v = ics_lut_vx(t);
    double e = rel(v, v_ex);
    if (e > mv) mv = e;
    CHECK(e <= ICS_LUT_BUILTIN_VX_BOUND, "vx(%.17g) = %.17g, exact %.17g, rel %.3g", t, v, v_ex, e);
    CHECK(ics_lut_vx_ab(1 - t, t) == v, "vx_ab(1 - t, t) != vx(t) at %.17g", t);
    float tf = (float)t;
    double ef = rel(ics_lut_float_vx(n, gf, tf), ics_ellipse_vx(tf));
    if (ef > mvf) mvf = ef;
    CHECK(ef <= ICS_LUT_BUILTIN_VX_BOUND + fx, "float vx(%.9g): rel %.3g", tf, ef);
  }
  printf("independent sample, max rel error: double ratio %.3g vx %.3g radii %.3g; "
         "float ratio %.3g vx %.3g radii %.3g\n", mr, mv, mk, mrf, mvf, mkf);
  free(sf);
  free(gf);
}

static void test_special(void) {
  double a, b;
  ics_lut_ratio_to_ab(0, &a, &b);
  CHECK(a == 1 && b == 0, "rat 0 -> (%g, %g)", a, b);
  ics_lut_ratio_to_ab(INFINITY, &a, &b);
  CHECK(a == 0 && b == 1, "rat inf -> (%g, %g)", a, b);
  ics_lut_ratio_to_ab(1, &a, &b);
  CHECK(a == 0.5 && b == 0.5, "rat 1 -> (%.17g, %.17g)", a, b);
  ics_lut_ratio_to_ab(NAN, &a, &b);
  CHECK(isnan(a) && isnan(b), "rat nan -> (%g, %g)", a, b);
  ics_lut_ratio_to_ab(-1e-300, &a, &b);
  CHECK(isnan(a) && isnan(b), "rat < 0 -> (%g, %g)", a, b);
  CHECK(isnan(ics_lut_ratio_to_t(-INFINITY)), "ratio_to_t(-inf)");
  CHECK(ics_lut_vx(1) == 0, "vx(1) = %g", ics_lut_vx(1));
  CHECK(rel(ics_lut_vx(0), 1.0 / 3) <= DBL_EPSILON, "vx(0) = %.17g", ics_lut_vx(0));
  /* u(1/2) * scale rounds to n - 1 within an ulp or two: the last node, g = 1/2, to 2 ulps */
  CHECK(rel(ics_lut_vx(0.5), 0.125) <= 2 * DBL_EPSILON, "vx(1/2) = %.17g", ics_lut_vx(0.5));
  CHECK(isnan(ics_lut_vx(-1e-300)) && isnan(ics_lut_vx(1 + DBL_EPSILON)) && isnan(ics_lut_vx(NAN)),
        "vx outside [0, 1]");
  CHECK(isnan(ics_lut_vx_ab(0.5, NAN)), "vx_ab nan");
  ics_lut_ellipse_radii(0, 0, &a, &b);
  CHECK(a == 0 && b == 0, "radii(0, 0) = (%g, %g)", a, b);
  /* a degenerate kernel: a segment of half-length r has variance r^2 / 3 */
  ics_lut_ellipse_radii(1, 0, &a, &b);
  CHECK(rel(a, sqrt(3.0)) <= DBL_EPSILON && b == 0, "radii(1, 0) = (%.17g, %g)", a, b);
  ics_lut_ellipse_radii(0, 2, &a, &b);
  CHECK(a == 0 && rel(b, sqrt(6.0)) <= DBL_EPSILON, "radii(0, 2) = (%g, %.17g)", a, b);
  ics_lut_ellipse_radii(-1, 1, &a, &b);
  CHECK(isnan(a) && isnan(b), "radii(-1, 1)");
  ics_lut_ellipse_radii(1, INFINITY, &a, &b);
  CHECK(isnan(a) && isnan(b), "radii(1, inf)");
  ics_lut_ellipse_radii(NAN, 1, &a, &b);
  CHECK(isnan(a) && isnan(b), "radii(nan, 1)");
}

/* Linear interpolation: error ~ 1/n^2 (up to the log terms at the ends). */
static void test_order(void) {
  ics_lut_grid *G = NULL;
  CHECK(ics_lut_grid_create(&G, 256, ICS_LUT_STAMP_PER_INTERVAL) == ICS_OK, "grid");
  double s64[64], g64[64], s256[256], g256[256];
  CHECK(ics_lut_build(64, s64, g64) == ICS_OK && ics_lut_build(256, s256, g256) == ICS_OK, "build");
  ics_lut_tables L64 = {64, s64, g64}, L256 = {256, s256, g256};
  ics_lut_error e64, e256;
  ics_lut_measure(G, &L64, 0, &e64);
  ics_lut_measure(G, &L256, 0, &e256);
  double h = log(255.0 / 63.0);
  double pr = log(e64.ratio / e256.ratio) / h, pv = log(e64.vx / e256.vx) / h;
  printf("observed order (n = 64 -> 256): ratio %.3f, vx %.3f\n", pr, pv);
  CHECK(pr >= 1.7 && pr <= 2.3, "ratio table order %.3f", pr);
  CHECK(pv >= 1.7 && pv <= 2.3, "vx table order %.3f", pv);
  ics_lut_grid_destroy(G);
}

/* ics_lut_ellipse_radii against the exact elliptical kernel's radii (ics_ellipse_kernel). */
static void test_kernel(void) {
  double worst = 0;
  for (int i = 0; i < 2000; i++) {
    double vx = pow(10.0, -6 + 12 * uniform()), vy = pow(10.0, -6 + 12 * uniform());
    ics_ellipse_shape sh;
    ics_status st = ics_ellipse_kernel(vx, vy, 360 * uniform(), 2, 0.0, &sh, NULL);
    CHECK(st == ICS_OK, "ics_ellipse_kernel(%g, %g): %s", vx, vy, ics_status_str(st));
    if (st != ICS_OK) continue;
    double a, b;
    ics_lut_ellipse_radii(vx, vy, &a, &b);
    double e = fmax(rel(a, sh.a), rel(b, sh.b));
    if (e > worst) worst = e;
    CHECK(e <= ICS_LUT_BUILTIN_RADII_BOUND, "radii(%g, %g) = (%.17g, %.17g), kernel (%.17g, %.17g)",
          vx, vy, a, b, sh.a, sh.b);
  }
  printf("radii vs ics_ellipse_kernel: max rel error %.3g\n", worst);
}

static void test_api(void) {
  double s[8], g[8];
  CHECK(ics_lut_build(ICS_LUT_MIN_SIZE - 1, s, g) == ICS_ERR_RANGE, "size too small");
  CHECK(ics_lut_build(ICS_LUT_MAX_SIZE + 1, s, g) == ICS_ERR_RANGE, "size too large");
  CHECK(ics_lut_build(8, NULL, g) == ICS_ERR_INVALID_ARG, "NULL table");
  ics_lut_grid *G = (ics_lut_grid *)1;
  CHECK(ics_lut_grid_create(&G, 3, 16) == ICS_ERR_RANGE && G == NULL, "grid size too small");
  CHECK(ics_lut_build(8, s, g) == ICS_OK, "build 8");
  ics_lut_tables L = {8, s, g};
  ics_lut_error e = {0};
  FILE *f = tmpfile();
  CHECK(f != NULL, "tmpfile");
  if (f) {
    CHECK(ics_lut_write(f, ICS_LUT_LANG_GLSL, &L, "bad */ command", &e, &e) == ICS_ERR_INVALID_ARG,
          "comment end in the command");
    CHECK(ics_lut_write(f, ICS_LUT_LANG_C, &L, "bad \" command", &e, &e) == ICS_ERR_INVALID_ARG,
          "quote in the command");
    CHECK(ics_lut_write(f, (ics_lut_lang)99, &L, "x", &e, &e) == ICS_ERR_INVALID_ARG, "language");
    CHECK(ics_lut_write(f, ICS_LUT_LANG_OPENCL, &L, "icshadow lut --size 8 --lang opencl", &e, &e) ==
              ICS_OK, "write ok");
    fclose(f);
  }
}

int main(void) {
  test_facts();
  test_builtin_is_fresh();
  test_bounds();
  test_special();
  test_order();
  test_kernel();
  test_api();
  return test_summary("test_lut");
}
