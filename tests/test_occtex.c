/* test_occtex.c — occlusion textures (libicshadow/src/occtex.c).
 *
 * References are computed here, independently of the code under test:
 * - box averages of a texture by direct summation of texel-overlap areas (ref_box);
 * - the exact occlusion of a rectangular light by one planar axis-aligned occluder parallel to
 *   it: (footprint rectangle on the occluder plane ∩ occluder) / footprint area (plate_exact).
 * Tolerances and where they come from:
 * - SAT: the sat.h bound on a box sum, 4.04 * 2^-53 * (x1 + y1) * sum|a| <= 4.04 * 2^-53 * 2n * n^2,
 *   divided by the box area, plus 1e-15 for the interpolation weights.
 * - N-Buffers and mipmap at their exact sizes: float storage; each level is one float sum of 4
 *   values in [0, 1] and one exact multiply by 1/4, so level l carries at most 3 l ulps(1) =
 *   3 l 2^-24 absolute, plus the double bilinear weights (< 1e-15): bound (3 L + 1) 2^-24.
 * - Brute force (m x m midpoint rule) against one axis-aligned rectangle on the light: counting
 *   cell centres in an interval of length a m misses by < 1 per axis: |err| <= 2/m + 1/m^2. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

static double urand(unsigned *s) { /* LCG: reproducible, in [0, 1) */
  *s = *s * 1664525u + 1013904223u;
  return (*s >> 8) * (1.0 / 16777216.0);
}

/* exact average of the piecewise-constant texture T (n x n, 0 outside) over [u0,u1]x[v0,v1] */
static double ref_box(const float *T, int n, double u0, double v0, double u1, double v1) {
  double r = 0;
  for (int j = 0; j < n; j++) {
    double ov = fmin(v1, j + 1.0) - fmax(v0, (double)j);
    if (ov <= 0) continue;
    for (int i = 0; i < n; i++) {
      double ou = fmin(u1, i + 1.0) - fmax(u0, (double)i);
      if (ou > 0) r += ou * ov * T[j * n + i];
    }
  }
  return r / ((u1 - u0) * (v1 - v0));
}

static double overlap1(double a0, double a1, double b0, double b1) {
  double o = fmin(a1, b1) - fmax(a0, b0);
  return o > 0 ? o : 0;
}

/* exact occlusion of light L at P by the plate [x0,x1]x[y0,y1] in plane z = zo < P.z */
static double plate_exact(const ics_occ_light *L, double x0, double y0, double x1, double y1,
                          double zo, const double *P) {
  double t = (P[2] - zo) / P[2];
  double cx = P[0] + t * (L->cx - P[0]), cy = P[1] + t * (L->cy - P[1]);
  double hx = 0.5 * t * L->wx, hy = 0.5 * t * L->wy;
  return overlap1(cx - hx, cx + hx, x0, x1) * overlap1(cy - hy, cy + hy, y0, y1) / (4 * hx * hy);
}

static float bound_pyr(int L) { return (float)((3 * L + 1) * 0x1p-24); }

/* ---- prefilters against direct box averages -------------------------------------------- */
static void test_prefilters(void) {
  const int n = 32, L = 5, K = 2;
  float *tex = malloc(sizeof(float) * K * n * n);
  unsigned s = 12345;
  for (int i = 0; i < K * n * n; i++) tex[i] = (float)urand(&s);
  /* slice 1: a sparse binary pattern, like a real occlusion texture */
  for (int i = 0; i < n * n; i++) tex[n * n + i] = urand(&s) < 0.3 ? 1.0f : 0.0f;
  ics_occ_grid g = {-1, -1, 2.0 / n, n};
  ics_occtex *ot = NULL;
  CHECK(ics_occtex_create(&ot, tex, &g, K, 1, 2) == ICS_OK, "create");
  if (!ot) return;
  double r;
  CHECK(ics_occtex_box(ot, ICS_OCC_SAT, 0, 1, 1, 2, 2, &r) == ICS_ERR_UNSUPPORTED, "SAT not built yet");
  for (int pf = 0; pf < ICS_OCC_PREFILTER_COUNT; pf++)
    CHECK(ics_occtex_prefilter(ot, (ics_occ_prefilter)pf) == ICS_OK, "prefilter %d", pf);

  double worst_sat = 0, worst_nb = 0, worst_mip = 0;
  for (int k = 0; k < K; k++) {
    const float *T = tex + k * n * n;
    /* SAT: random real rectangles, also hanging over the border */
    for (int it = 0; it < 400; it++) {
      double su = 0.3 + 20 * urand(&s), sv = 0.3 + 20 * urand(&s);
      double u = -5 + (n + 10) * urand(&s), v = -5 + (n + 10) * urand(&s);
      double want = ref_box(T, n, u - su / 2, v - sv / 2, u + su / 2, v + sv / 2);
      ics_status st = ics_occtex_box(ot, ICS_OCC_SAT, k, u, v, su, sv, &r);
      double tol = 4.04 * 0x1p-53 * 2 * n * (double)n * n / (su * sv) + 1e-15;
      double e = fabs(r - want);
      if (e / tol > worst_sat) worst_sat = e / tol;
      CHECK(st == ICS_OK && e <= tol, "SAT k=%d box (%g,%g) size (%g,%g): %.17g vs %.17g", k, u, v, su, sv, r, want);
    }
    /* N-Buffers: power-of-two squares at any position */
    for (int l = 0; l <= L; l++)
      for (int it = 0; it < 60; it++) {
        double sz = (double)(1 << l);
        double u = -sz / 2 + (n + sz) * urand(&s), v = -sz / 2 + (n + sz) * urand(&s);
        double want = ref_box(T, n, u - sz / 2, v - sz / 2, u + sz / 2, v + sz / 2);
        ics_status st = ics_occtex_box(ot, ICS_OCC_NBUFFERS, k, u, v, sz, sz, &r);
        double e = fabs(r - want);
        if (e / bound_pyr(L) > worst_nb) worst_nb = e / bound_pyr(L);
        CHECK(st == ICS_OK && e <= bound_pyr(L), "N-Buffers k=%d l=%d at (%g,%g): %.17g vs %.17g", k, l, u, v, r, want);
      }
    /* mipmap: power-of-two squares aligned to the level's texels */
    for (int l = 0; l <= L; l++) {
      int m = n >> l;
      for (int j = -1; j <= m; j++)
        for (int i = -1; i <= m; i++) {
          double sz = (double)(1 << l), u = (i + 0.5) * sz, v = (j + 0.5) * sz;
          double want = ref_box(T, n, u - sz / 2, v - sz / 2, u + sz / 2, v + sz / 2);
          ics_status st = ics_occtex_box(ot, ICS_OCC_MIPMAP, k, u, v, sz, sz, &r);
          double e = fabs(r - want);
          if (e / bound_pyr(L) > worst_mip) worst_mip = e / bound_pyr(L);
          CHECK(st == ICS_OK && e <= bound_pyr(L), "mipmap k=%d l=%d texel (%d,%d): %.17g vs %.17g", k, l, i, j, r, want);
        }
    }
    /* any box: every prefilter gives a weighted mean of values in [0, 1] */
    for (int it = 0; it < 300; it++) {
      double su = 40 * urand(&s) * urand(&s), sv = it % 3 ? su : 40 * urand(&s);
      double u = -5 + (n + 10) * urand(&s), v = -5 + (n + 10) * urand(&s);
      for (int pf = 0; pf < ICS_OCC_PREFILTER_COUNT; pf++) {
        ics_status st = ics_occtex_box(ot, (ics_occ_prefilter)pf, k, u, v, su, sv, &r);
        CHECK(st == ICS_OK && r >= -1e-12 && r <= 1 + 1e-6, "%s box size (%g,%g): %.17g outside [0,1]",
              ics_occtex_prefilter_name((ics_occ_prefilter)pf), su, sv, r);
      }
    }
  }
  /* the approximate prefilters are not exact in between (the test above can tell them apart) */
  {
    double want = ref_box(tex, n, 10.3 - 2.5, 7.9 - 2.5, 10.3 + 2.5, 7.9 + 2.5), rn, rm;
    ics_occtex_box(ot, ICS_OCC_NBUFFERS, 0, 10.3, 7.9, 5, 5, &rn);
    ics_occtex_box(ot, ICS_OCC_MIPMAP, 0, 10.3, 7.9, 5, 5, &rm);
    CHECK(fabs(rn - want) > 1e-4 && fabs(rm - want) > 1e-4, "5-texel box: nb %.6g mip %.6g exact %.6g", rn, rm, want);
  }
  /* point lookups: SAT gives the texel under the point */
  CHECK(ics_occtex_box(ot, ICS_OCC_SAT, 1, 7.25, 3.5, 0, 0, &r) == ICS_OK && r == tex[n * n + 3 * n + 7],
        "SAT point lookup %.17g", r);
  printf("prefilters: worst error / bound: SAT %.3g, N-Buffers %.3g, mipmap %.3g\n", worst_sat, worst_nb, worst_mip);
  ics_occtex_destroy(ot);
  free(tex);
}

/* ---- slicing ----------------------------------------------------------------------------- */
static void test_slicing(void) {
  const int n = 8, K = 4;
  ics_occ_grid g = {0, 0, 1, n};
  float tex[4 * 64];
  ics_occ_box b[3] = {
      {1, 1, 1.2, 3, 2, 1.3},       /* slice 0 only (slices (1,1.5],(1.5,2],(2,2.5],(2.5,3]) */
      {4.5, 4, 1.6, 5, 6.25, 2.6},  /* slices 1, 2, 3; half texels in x, quarter in y */
      {0, 0, 3.5, 8, 8, 4},         /* beyond z_far: ignored */
  };
  CHECK(ics_occtex_slice_boxes(b, 3, &g, K, 1, 3, 4, tex) == ICS_OK, "slice");
  CHECK(tex[1 * n + 1] == 1 && tex[1 * n + 2] == 1 && tex[1 * n + 3] == 0 && tex[2 * n + 1] == 0,
        "box 0 in slice 0: %g %g %g %g", tex[9], tex[10], tex[11], tex[17]);
  int bad = 0;
  for (int k = 1; k < K; k++) {
    const float *T = tex + k * n * n;
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        float want = (i == 4 && j >= 4 && j < 6) ? 0.5f : (i == 4 && j == 6) ? 0.125f : 0.0f;
        if (T[j * n + i] != want) bad++;
      }
  }
  CHECK(bad == 0, "box 1 coverage wrong in %d texels", bad);
  for (int i = 0; i < n * n; i++)
    if (tex[i] != 0 && !(i == 9 || i == 10)) bad++;
  CHECK(bad == 0, "slice 0 has extra coverage");
  /* a box on the first slice's top plane counts (slice 0 is closed at z_near) */
  ics_occ_box top = {0, 0, 1, 1, 1, 1};
  CHECK(ics_occtex_slice_boxes(&top, 1, &g, K, 1, 3, 1, tex) == ICS_OK && tex[0] == 1,
        "plate at z_near");
  /* a plate on a slice's bottom plane belongs to that slice only */
  ics_occ_box mid = {0, 0, 2, 1, 1, 2};
  CHECK(ics_occtex_slice_boxes(&mid, 1, &g, K, 1, 3, 1, tex) == ICS_OK && tex[n * n] == 1 && tex[2 * n * n] == 0 && tex[0] == 0,
        "plate at z = 2: %g %g %g", tex[0], tex[n * n], tex[2 * n * n]);
}

/* ---- combination --------------------------------------------------------------------- */
static void test_combination(void) {
  unsigned s = 99;
  for (int it = 0; it < 2000; it++) {
    double f[8];
    int k = 1 + it % 8;
    for (int i = 0; i < k; i++) f[i] = it % 5 == 0 ? (urand(&s) < 0.5 ? 0 : 1) : urand(&s);
    double p = ics_occtex_combine_values(ICS_OCC_PRODUCT, f, k);
    double sm = ics_occtex_combine_values(ICS_OCC_SUM, f, k);
    double mx = ics_occtex_combine_values(ICS_OCC_MAX, f, k);
    CHECK(p >= 0 && p <= 1 && mx <= p + 1e-15 && p <= sm + 1e-15, "k=%d: max %.17g product %.17g sum %.17g", k, mx, p, sm);
  }
  double f2[2] = {0.25, 0.5};
  CHECK(fabs(ics_occtex_combine_values(ICS_OCC_PRODUCT, f2, 2) - (0.25 + 0.5 - 0.125)) < 1e-15, "a + b - ab");
  double f3[3] = {0.5, 0.75, 0.25};
  CHECK(ics_occtex_combine_values(ICS_OCC_SUM, f3, 3) == 1, "clamped sum");
  CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)7, f3, 3)), "unknown combination");
  /* bad input: NaN for every combination alike (NULL, k < 0, NaN, values outside [0, 1]) */
  double fbig[2] = {1.5, -0.5}, fneg[2] = {0.25, -0.25}, fnan[3] = {0.5, NAN, 0.25};
  for (int c = 0; c < ICS_OCC_COMBINE_COUNT; c++) {
    CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)c, NULL, 2)), "%d: NULL f", c);
    CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)c, f2, -1)), "%d: k < 0", c);
    CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)c, fbig, 2)), "%d: f outside [0, 1]", c);
    CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)c, fneg, 2)), "%d: negative f", c);
    CHECK(isnan(ics_occtex_combine_values((ics_occ_combine)c, fnan, 3)), "%d: NaN f", c);
    CHECK(ics_occtex_combine_values((ics_occ_combine)c, NULL, 0) == 0, "%d: no slices", c);
  }
  double fedge[2] = {0, 1};
  CHECK(ics_occtex_combine_values(ICS_OCC_PRODUCT, fedge, 2) == 1 && ics_occtex_combine_values(ICS_OCC_MAX, fedge, 2) == 1,
        "0 and 1 are accepted");

  /* on a real scene, through ics_occtex_shadow */
  ics_occ_box boxes[60];
  CHECK(ics_occtex_boxes_make(ICS_OCC_BOXES_FOLIAGE, 60, 7, boxes) == ICS_OK, "scene");
  const int n = 64, K = 6;
  ics_occ_grid g = {-1, -1, 2.0 / n, n};
  float *tex = malloc(sizeof(float) * K * n * n);
  ics_occtex *ot = NULL;
  CHECK(ics_occtex_slice_boxes(boxes, 60, &g, K, 1, 2, 2, tex) == ICS_OK, "slice");
  CHECK(ics_occtex_create(&ot, tex, &g, K, 1, 2) == ICS_OK && ics_occtex_prefilter(ot, ICS_OCC_NBUFFERS) == ICS_OK, "build");
  ics_occ_light L = {0.1, 0, 0.8, 0.8};
  double P[3 * 200], oc[3][200];
  for (int i = 0; i < 200; i++) {
    P[3 * i] = -1 + 2 * urand(&s);
    P[3 * i + 1] = -1 + 2 * urand(&s);
    P[3 * i + 2] = 1.2 + 1.5 * urand(&s); /* also inside the slices: fading */
  }
  for (int c = 0; c < 3; c++)
    CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_NBUFFERS, (ics_occ_combine)c, P, 200, oc[c]) == ICS_OK, "shadow");
  int bad = 0, strict = 0;
  for (int i = 0; i < 200; i++) {
    if (!(oc[0][i] >= 0 && oc[0][i] <= 1 && oc[2][i] <= oc[0][i] + 1e-12 && oc[0][i] <= oc[1][i] + 1e-12)) bad++;
    if (oc[2][i] < oc[0][i] - 1e-3 && oc[0][i] < oc[1][i] - 1e-3) strict++;
  }
  CHECK(bad == 0, "%d points violate max <= product <= sum", bad);
  CHECK(strict > 20, "only %d points tell the three combinations apart", strict);
  ics_occtex_destroy(ot);
  free(tex);
}

/* ---- one planar occluder: the exact soft shadow -------------------------------------------- */
static void test_planar(void) {
  /* plate in z = 1 on texel edges; one slice (0.5, 1] whose bottom plane is the plate's plane */
  const int n = 64;
  const double texel = 2.0 / n, px0 = -0.25, py0 = -0.5, px1 = 0.5, py1 = 0.25;
  ics_occ_grid g = {-1, -1, texel, n};
  ics_occ_box plate = {px0, py0, 1, px1, py1, 1};
  float *tex = malloc(sizeof(float) * n * n);
  ics_occtex *ot = NULL;
  CHECK(ics_occtex_slice_boxes(&plate, 1, &g, 1, 0.5, 1, 1, tex) == ICS_OK, "slice");
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 0.5, 1) == ICS_OK, "create");
  for (int pf = 0; pf < ICS_OCC_PREFILTER_COUNT; pf++) ics_occtex_prefilter(ot, (ics_occ_prefilter)pf);
  const ics_occ_light L = {0.1, -0.05, 0.5, 0.5};
  unsigned s = 4242;
  /* pz = 2: footprint 8 texels; pz = 4/3: 4 texels (N-Buffers exact); pz = 3: 10.67 (SAT only) */
  const double depths[3] = {2, 4.0 / 3, 3};
  double worst_bf = 0, worst_sat = 0, worst_nb = 0;
  for (int d = 0; d < 3; d++)
    for (int it = 0; it < 60; it++) {
      double P[3] = {-1.2 + 2.4 * urand(&s), -1.2 + 2.4 * urand(&s), depths[d]};
      double want = plate_exact(&L, px0, py0, px1, py1, 1, P), r;
      CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_SAT, ICS_OCC_PRODUCT, P, 1, &r) == ICS_OK &&
                fabs(r - want) <= 1e-12,
            "SAT at (%g,%g,%g): %.17g vs exact %.17g", P[0], P[1], P[2], r, want);
      worst_sat = fmax(worst_sat, fabs(r - want));
      if (d < 2) {
        CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_NBUFFERS, ICS_OCC_PRODUCT, P, 1, &r) == ICS_OK &&
                  fabs(r - want) <= bound_pyr(6),
              "N-Buffers at (%g,%g,%g): %.17g vs exact %.17g", P[0], P[1], P[2], r, want);
        worst_nb = fmax(worst_nb, fabs(r - want));
      }
      if (it < 15) { /* the brute force agrees with the formula to its midpoint-rule bound */
        const int m = 128;
        CHECK(ics_occtex_exact(&plate, 1, &L, m, P, 1, &r) == ICS_OK && fabs(r - want) <= 2.0 / m + 1.0 / (m * m),
              "brute force at (%g,%g,%g): %.17g vs %.17g", P[0], P[1], P[2], r, want);
        worst_bf = fmax(worst_bf, fabs(r - want));
      }
    }
  /* mipmap: exact where the footprint is a level texel (size 2^l, centre (i + 1/2) 2^l) */
  double worst_mip = 0;
  for (int l = 1; l <= 3; l++) {
    double sz = (double)(1 << l) * texel, t = sz / L.wx, pz = 1 / (1 - t);
    for (int it = 0; it < 40; it++) {
      int i = (int)(urand(&s) * (n >> l)), j = (int)(urand(&s) * (n >> l));
      double fx = g.x0 + (i + 0.5) * sz, fy = g.y0 + (j + 0.5) * sz; /* footprint centre */
      double P[3] = {(fx - t * L.cx) / (1 - t), (fy - t * L.cy) / (1 - t), pz}, r;
      double want = plate_exact(&L, px0, py0, px1, py1, 1, P);
      CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, P, 1, &r) == ICS_OK &&
                fabs(r - want) <= bound_pyr(6) + 1e-12,
            "mipmap l=%d at (%g,%g,%g): %.17g vs exact %.17g", l, P[0], P[1], P[2], r, want);
      worst_mip = fmax(worst_mip, fabs(r - want));
    }
  }
  printf("planar occluder: worst |error|: SAT %.3g, N-Buffers %.3g, mipmap (aligned) %.3g, brute force m=128 %.3g\n",
         worst_sat, worst_nb, worst_mip, worst_bf);

  ics_occtex_destroy(ot);
  free(tex);
}

/* ---- monotonicity in light size -------------------------------------------------------------- */
static void test_monotone(void) {
  /* an edge: the plate x in [-1, 0.5] fills the grid left of x = 0.5, in the plane z = 1. With
   * the light centred at 0 and P at z = 2 (t = 1/2), the footprint is centred at P/2 with half
   * side h = wx/4 <= 0.75, so it stays inside the grid. Then the exact occlusion is
   * min(2h, 0.5 - c + h)/(2h) clamped to [0, 1] for footprint centre c: falling in h for c < 0.5
   * (inside), rising for c > 0.5 (outside). */
  const int n = 64;
  ics_occ_grid g = {-1, -1, 2.0 / n, n};
  ics_occ_box plate = {-1, -1, 1, 0.5, 1, 1};
  float *tex = malloc(sizeof(float) * n * n);
  ics_occtex *ot = NULL;
  ics_occtex_slice_boxes(&plate, 1, &g, 1, 0.5, 1, 1, tex);
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 0.5, 1) == ICS_OK, "create");
  for (int pf = 0; pf < ICS_OCC_PREFILTER_COUNT; pf++) ics_occtex_prefilter(ot, (ics_occ_prefilter)pf);
  const double Pin[3] = {0.4, 0.1, 2}, Pout[3] = {1.6, -0.1, 2};
  for (int pf = -1; pf < ICS_OCC_PREFILTER_COUNT; pf++) { /* -1: the exact formula itself */
    const char *name = pf < 0 ? "exact" : ics_occtex_prefilter_name((ics_occ_prefilter)pf);
    double prev_in = 2, prev_out = -1;
    int bad = 0;
    for (int i = 0; i <= 59; i++) {
      ics_occ_light Li = {0, 0, 0.02 + 0.05 * i, 0.02 + 0.05 * i};
      double rin, rout;
      if (pf < 0) {
        rin = plate_exact(&Li, -1, -1, 0.5, 1, 1, Pin);
        rout = plate_exact(&Li, -1, -1, 0.5, 1, 1, Pout);
      } else {
        ics_occtex_shadow(ot, &Li, (ics_occ_prefilter)pf, ICS_OCC_PRODUCT, Pin, 1, &rin);
        ics_occtex_shadow(ot, &Li, (ics_occ_prefilter)pf, ICS_OCC_PRODUCT, Pout, 1, &rout);
      }
      if (rin > prev_in + 1e-12 || rout < prev_out - 1e-12) {
        bad++;
        if (pf != ICS_OCC_MIPMAP)
          fprintf(stderr, "%s light %g: inside %.17g (before %.17g), outside %.17g (before %.17g)\n", name, Li.wx,
                rin, prev_in, rout, prev_out);
      }
      prev_in = rin;
      prev_out = rout;
    }
    if (pf == ICS_OCC_MIPMAP) { /* not monotone: the trilinear blend of coarse, grid-aligned
                                   levels moves with the box size (reported, see docs/occtex.md) */
      printf("monotonicity: mipmap has %d non-monotone steps of 59\n", bad);
      continue;
    }
    CHECK(bad == 0 && prev_in < 0.9 && prev_out > 0.1, "%s: %d non-monotone steps (ends %g %g)", name, bad, prev_in, prev_out);
  }
  ics_occtex_destroy(ot);
  free(tex);
}

/* ---- slice fading --------------------------------------------------------------------- */
static void test_fading(void) {
  const int n = 32, K = 4;
  ics_occ_grid g = {-1, -1, 2.0 / n, n};
  ics_occ_box boxes[40];
  ics_occtex_boxes_make(ICS_OCC_BOXES_BLOCKS, 40, 3, boxes);
  float *tex = malloc(sizeof(float) * K * n * n);
  ics_occtex *ot = NULL;
  ics_occtex_slice_boxes(boxes, 40, &g, K, 1, 2, 2, tex);
  CHECK(ics_occtex_create(&ot, tex, &g, K, 1, 2) == ICS_OK && ics_occtex_prefilter(ot, ICS_OCC_SAT) == ICS_OK, "build");
  ics_occ_light L = {0, 0, 0.5, 0.3};
  /* weights: slice k = (1 + k/4, 1 + (k+1)/4]; P at z = 1.6 is 40% into slice 2 */
  double P[3] = {0.1, 0.2, 1.6}, w[4], o[4];
  CHECK(ics_occtex_slices_at(ot, &L, ICS_OCC_SAT, P, w, o) == ICS_OK, "slices_at");
  CHECK(w[0] == 1 && w[1] == 1 && fabs(w[2] - 0.4) < 1e-12 && w[3] == 0 && o[3] == 0, "weights %g %g %g %g", w[0], w[1], w[2], w[3]);
  CHECK(fabs(ics_occtex_plane(ot, 1) - 1.5) < 1e-15 && isnan(ics_occtex_plane(ot, 4)), "planes");
  /* continuity across the slice planes and inside the slices */
  unsigned s = 5;
  double worst = 0;
  for (int it = 0; it < 100; it++) {
    double x = -0.9 + 1.8 * urand(&s), y = -0.9 + 1.8 * urand(&s);
    for (int k = 1; k <= K; k++) {
      double z = 1 + 0.25 * k, Q[6] = {x, y, z - 1e-7, x, y, z + 1e-7}, r[2];
      ics_occtex_shadow(ot, &L, ICS_OCC_SAT, ICS_OCC_PRODUCT, Q, 2, r);
      worst = fmax(worst, fabs(r[1] - r[0]));
    }
  }
  /* over 2e-7 in z the footprint moves by < 1e-6 texels: a jump would show as O(1e-2) or more */
  CHECK(worst < 1e-4, "occlusion jumps by %g across a slice plane", worst);
  ics_occtex_destroy(ot);
  free(tex);
}

/* ---- bad input --------------------------------------------------------------------------- */
static void test_bad_input(void) {
  float tex[64] = {0};
  ics_occtex *ot = NULL;
  ics_occ_grid g = {0, 0, 1, 8};
  ics_occ_grid g0 = {0, 0, 1, 0}, g3 = {0, 0, 1, 3}, gbig = {0, 0, 1, 8192}, gnan = {NAN, 0, 1, 8},
               gneg = {0, 0, -1, 8}, ginf = {0, 0, INFINITY, 8};
  CHECK(ics_occtex_create(&ot, tex, &g0, 1, 1, 2) == ICS_ERR_SIZE && !ot, "empty texture");
  CHECK(ics_occtex_create(&ot, tex, &g3, 1, 1, 2) == ICS_ERR_SIZE, "n = 3");
  CHECK(ics_occtex_create(&ot, tex, &gbig, 1, 1, 2) == ICS_ERR_SIZE, "n = 8192");
  CHECK(ics_occtex_create(&ot, tex, &gnan, 1, 1, 2) == ICS_ERR_NAN, "NaN origin");
  ics_occ_grid g4k = {0, 0, 1, 4096}; /* 17 x 4096^2 texels > ICS_OCC_MAX_TEXELS: refused unread */
  CHECK(ics_occtex_create(&ot, tex, &g4k, 17, 1, 2) == ICS_ERR_SIZE, "17 slices of 4096^2");
  CHECK(ics_occtex_create(&ot, tex, &gneg, 1, 1, 2) == ICS_ERR_INVALID_ARG, "negative texel");
  CHECK(ics_occtex_create(&ot, tex, &ginf, 1, 1, 2) == ICS_ERR_INFINITE, "infinite texel");
  CHECK(ics_occtex_create(&ot, tex, &g, 0, 1, 2) == ICS_ERR_INVALID_ARG, "zero slices");
  CHECK(ics_occtex_create(&ot, tex, &g, ICS_OCC_MAX_SLICES + 1, 1, 2) == ICS_ERR_SIZE,
        "too many slices");
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 0, 2) == ICS_ERR_INVALID_ARG, "z_near = 0");
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 2, 2) == ICS_ERR_INVALID_ARG, "z_far = z_near");
  CHECK(ics_occtex_create(&ot, tex, &g, 1, NAN, 2) == ICS_ERR_NAN, "NaN z_near");
  CHECK(ics_occtex_create(&ot, NULL, &g, 1, 1, 2) == ICS_ERR_INVALID_ARG, "NULL texture");
  CHECK(ics_occtex_create(&ot, tex, NULL, 1, 1, 2) == ICS_ERR_INVALID_ARG, "NULL grid");
  tex[5] = NAN;
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 1, 2) == ICS_ERR_NAN && !ot, "NaN texel");
  tex[5] = 0;
  CHECK(ics_occtex_create(&ot, tex, &g, 1, 1, 2) == ICS_OK, "good");
  ics_occ_light L = {0, 0, 1, 1}, Lnan = {0, NAN, 1, 1}, Lneg = {0, 0, -1, 1};
  double P[3] = {1, 1, 3}, Pnan[3] = {1, NAN, 3}, Pz[3] = {1, 1, 0}, r;
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_SAT, ICS_OCC_PRODUCT, P, 1, &r) == ICS_ERR_UNSUPPORTED, "not built");
  CHECK(ics_occtex_prefilter(ot, ICS_OCC_MIPMAP) == ICS_OK, "mipmap");
  CHECK(ics_occtex_prefilter(ot, (ics_occ_prefilter)9) == ICS_ERR_INVALID_ARG, "unknown prefilter");
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, P, 1, &r) == ICS_OK, "good shadow");
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, (ics_occ_combine)5, P, 1, &r) == ICS_ERR_INVALID_ARG, "combine");
  CHECK(ics_occtex_shadow(ot, &Lnan, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, P, 1, &r) == ICS_ERR_NAN, "NaN light");
  CHECK(ics_occtex_shadow(ot, &Lneg, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, P, 1, &r) == ICS_ERR_INVALID_ARG, "light size");
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, Pnan, 1, &r) == ICS_ERR_NAN, "NaN point");
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, Pz, 1, &r) == ICS_ERR_INVALID_ARG, "point on the light plane");
  CHECK(ics_occtex_shadow(ot, &L, ICS_OCC_MIPMAP, ICS_OCC_PRODUCT, P, 0, &r) == ICS_ERR_SIZE, "no points");
  CHECK(ics_occtex_box(ot, ICS_OCC_MIPMAP, 0, 1, 1, NAN, 1, &r) == ICS_ERR_NAN, "NaN box size");
  CHECK(ics_occtex_box(ot, ICS_OCC_MIPMAP, 1, 1, 1, 1, 1, &r) == ICS_ERR_INVALID_ARG, "slice out of range");
  CHECK(ics_occtex_box(ot, ICS_OCC_MIPMAP, 0, 1, 1, -1, 1, &r) == ICS_ERR_INVALID_ARG, "negative box");
  ics_occtex_destroy(ot);
  ics_occtex_destroy(NULL);

  ics_occ_box b = {0, 0, 1, 1, 1, 2}, bnan = {0, 0, 1, NAN, 1, 2}, binv = {1, 0, 1, 0, 1, 2};
  CHECK(ics_occtex_slice_boxes(&b, 1, &g, 1, 1, 2, 0, tex) == ICS_ERR_SIZE, "supersample 0");
  CHECK(ics_occtex_slice_boxes(&b, 1, &g, 0, 1, 2, 1, tex) == ICS_ERR_INVALID_ARG, "zero slices");
  CHECK(ics_occtex_slice_boxes(&bnan, 1, &g, 1, 1, 2, 1, tex) == ICS_ERR_NAN, "NaN box");
  CHECK(ics_occtex_slice_boxes(&binv, 1, &g, 1, 1, 2, 1, tex) == ICS_ERR_INVALID_ARG,
        "inverted box");
  CHECK(ics_occtex_slice_boxes(&b, 1, &g3, 1, 1, 2, 1, tex) == ICS_ERR_SIZE, "n = 3");
  CHECK(ics_occtex_exact(&b, 1, &L, 0, P, 1, &r) == ICS_ERR_SIZE, "m = 0");
  CHECK(ics_occtex_exact(&b, 1, &L, 4, Pnan, 1, &r) == ICS_ERR_NAN, "NaN point");
  CHECK(ics_occtex_exact(&bnan, 1, &L, 4, P, 1, &r) == ICS_ERR_NAN, "NaN box");
  CHECK(ics_occtex_boxes_make(ICS_OCC_BOXES_FOLIAGE, 0, 1, &b) == ICS_ERR_SIZE, "no boxes");
  CHECK(ics_occtex_prefilter_name((ics_occ_prefilter)3) == NULL && ics_occtex_combine_name(ICS_OCC_MAX) != NULL, "names");
}

int main(void) {
  test_prefilters();
  test_slicing();
  test_combination();
  test_planar();
  test_monotone();
  test_fading();
  test_bad_input();
  return test_summary("test_occtex");
}
