/* test_deprecated.c — the deprecated aliases of icshadow/deprecated.h: each old name returns
 * exactly (bit for bit, NaN for NaN, the same status) what its new name returns, on inputs
 * that cover the ordinary range, the tails, the edges of the domain and invalid arguments.
 * Built with -Wno-deprecated-declarations: calling the old names is the point. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

/* the same double: identical bits, or both NaN */
static int same(double a, double b) {
  if (isnan(a) && isnan(b)) return 1;
  uint64_t ua, ub;
  memcpy(&ua, &a, sizeof ua);
  memcpy(&ub, &b, sizeof ub);
  return ua == ub;
}

static void test_normal(void) {
  const double zs[] = {0.0, -0.0, 0.5, -1.25, 3.0, -8.0, 37.0, -38.5, 1e-300, -1e300,
                       INFINITY, -INFINITY, NAN};
  for (size_t i = 0; i < sizeof zs / sizeof zs[0]; i++) {
    double z = zs[i];
    CHECK(same(ics_light_phi(z), ics_normal_cdf(z)), "ics_light_phi(%a)", z);
    CHECK(same(ics_light_phic(z), ics_normal_sf(z)), "ics_light_phic(%a)", z);
  }
  const double ps[] = {0.0, 0x1p-1074, 1e-300, 1e-10, 0.025, 0.5, 0.975, 1.0 - 0x1p-53, 1.0,
                       -0.1, 1.5, NAN};
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++)
    CHECK(same(ics_light_phiinv(ps[i]), ics_normal_quantile(ps[i])), "ics_light_phiinv(%a)",
          ps[i]);
  const double abr[][3] = {{0, 0, 0},      {0.3, -0.7, 0.5},  {1.5, 2, -0.95}, {-2, 1, 0.99},
                           {1, 1, 1},      {-1, 0.5, -1},     {INFINITY, 0.2, 0.3},
                           {0.2, -INFINITY, 0.3}, {0, 0, 1.5}, {NAN, 0, 0}};
  for (size_t i = 0; i < sizeof abr / sizeof abr[0]; i++) {
    double a = abr[i][0], b = abr[i][1], r = abr[i][2];
    CHECK(same(ics_bvn_cdf(a, b, r), ics_normal_bvn_cdf(a, b, r)), "ics_bvn_cdf(%g, %g, %g)", a,
          b, r);
  }
}

static void test_volume(void) {
  enum { N = 8 };
  static float data[N * N * N];
  for (int k = 0; k < N; k++)
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++)
        data[(k * N + j) * N + i] = 0.05f + 0.01f * (float)((i * 7 + j * 3 + k * 5) % 11);
  ics_volume vol = {data, N, N, N};
  const double ru[3] = {1, 0, 0}, rv[3] = {0, 1, 0}, dir[3] = {0, 0, 1};
  const double pts[][3] = {{4, 4, 2}, {1.5, 6.25, 0.5}, {-1, 4, 4}, {4, 4, 20}};
  const double Us[] = {0.0, 0.5, 2.0, -1.0};
  for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
    for (size_t u = 0; u < sizeof Us / sizeof Us[0]; u++) {
      double t_old = -1, t_new = -1;
      ics_status s_old = ics_tau_bruteforce_directional(&vol, ru, rv, dir, pts[i], Us[u], 3,
                                                        0.25, &t_old);
      ics_status s_new = ics_volume_tau_directional(&vol, ru, rv, dir, pts[i], Us[u], 3, 0.25,
                                                    &t_new);
      CHECK(s_old == s_new && same(t_old, t_new), "directional p %zu U %g: %d %.17g vs %d %.17g",
            i, Us[u], s_old, t_old, s_new, t_new);
    }
  const double lights[][3] = {{-6, 4, 4}, {4, 4, 4}, {4, 4, 30}};
  for (size_t l = 0; l < sizeof lights / sizeof lights[0]; l++)
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
      for (size_t u = 0; u < sizeof Us / sizeof Us[0]; u++) {
        double t_old = -1, t_new = -1;
        ics_status s_old = ics_tau_bruteforce_point(&vol, lights[l], pts[i], Us[u], 3, 0.25,
                                                    &t_old);
        ics_status s_new = ics_volume_tau_point(&vol, lights[l], pts[i], Us[u], 3, 0.25, &t_new);
        CHECK(s_old == s_new && same(t_old, t_new),
              "point light %zu p %zu U %g: %d %.17g vs %d %.17g", l, i, Us[u], s_old, t_old,
              s_new, t_new);
      }
  double t = 0;
  CHECK(ics_tau_bruteforce_directional(NULL, ru, rv, dir, pts[0], 1, 3, 0.25, &t) ==
            ics_volume_tau_directional(NULL, ru, rv, dir, pts[0], 1, 3, 0.25, &t),
        "directional, no volume");
  CHECK(ics_tau_bruteforce_point(&vol, lights[0], lights[0], 1, 3, 0.25, &t) ==
            ics_volume_tau_point(&vol, lights[0], lights[0], 1, 3, 0.25, &t),
        "point, p at the light");
}

/* ---- objects: ics_X_build / ics_X_free -> ics_X_create / ics_X_destroy ---- */

/* 1000 + a pattern in [-1, 1): every precision mode differs from the others here */
static void fill_pattern(float *a, size_t n) {
  for (size_t i = 0; i < n; i++) a[i] = 1000.0f + (float)((i * 37) % 101) / 50.0f - 1.0f;
}

static void test_sat(void) {
  enum { W = 13, H = 7, D = 5 };
  static float a[W * H * D];
  fill_pattern(a, W * H * D);
  for (int m = 0; m < ICS_SAT_PRECISION_COUNT; m++) {
    ics_sat_precision mode = (ics_sat_precision)m;
    ics_sat2d *o2 = NULL, *n2 = NULL;
    ics_status so = ics_sat2d_build(&o2, a, W, H, W, mode);
    ics_status sn = ics_sat2d_create(&n2, a, W, H, W, mode);
    CHECK(so == ICS_OK && sn == ICS_OK, "sat2d mode %d: %d %d", m, so, sn);
    for (size_t y = 0; y < H && so == ICS_OK && sn == ICS_OK; y++)
      for (size_t x = 0; x < W; x++)
        CHECK(same(ics_sat2d_at(o2, x, y), ics_sat2d_at(n2, x, y)), "sat2d mode %d (%zu, %zu)", m,
              x, y);
    ics_sat2d_free(o2);
    ics_sat2d_destroy(n2);
    ics_sat3d *o3 = NULL, *n3 = NULL;
    so = ics_sat3d_build(&o3, a, W, H, D, mode);
    sn = ics_sat3d_create(&n3, a, W, H, D, mode);
    CHECK(so == ICS_OK && sn == ICS_OK, "sat3d mode %d: %d %d", m, so, sn);
    for (size_t z = 0; z < D && so == ICS_OK && sn == ICS_OK; z++)
      for (size_t y = 0; y < H; y++)
        for (size_t x = 0; x < W; x++)
          CHECK(same(ics_sat3d_at(o3, x, y, z), ics_sat3d_at(n3, x, y, z)),
                "sat3d mode %d (%zu, %zu, %zu)", m, x, y, z);
    ics_sat3d_free(o3);
    ics_sat3d_destroy(n3);
  }
  /* a refused size: the same status, *out NULL both ways; the old free takes NULL */
  ics_sat2d *o2 = (ics_sat2d *)a, *n2 = (ics_sat2d *)a;
  CHECK(ics_sat2d_build(&o2, a, 0, H, W, ICS_SAT_FLOAT) ==
                ics_sat2d_create(&n2, a, 0, H, W, ICS_SAT_FLOAT) &&
            !o2 && !n2,
        "sat2d width 0");
  ics_sat3d *o3 = (ics_sat3d *)a, *n3 = (ics_sat3d *)a;
  CHECK(ics_sat3d_build(&o3, a, W, H, 0, ICS_SAT_DOUBLE) ==
                ics_sat3d_create(&n3, a, W, H, 0, ICS_SAT_DOUBLE) &&
            !o3 && !n3,
        "sat3d depth 0");
  ics_sat2d_free(NULL);
  ics_sat3d_free(NULL);
}

static void test_csat_ssat(void) {
  enum { N = 8 };
  static float data[N * N * N];
  fill_pattern(data, N * N * N);
  for (size_t i = 0; i < N * N * N; i++) data[i] = (data[i] - 999.0f) / 10.0f; /* [0, 0.2) */
  ics_volume vol = {data, N, N, N};
  const double dir[3] = {0.3, -0.4, 0.866}, ru[3] = {1, 0, 0}, rv[3] = {0, 0.6, 0.8};
  const double pts[][3] = {{4, 4, 2}, {1.5, 6.25, 0.5}, {7.9, 0.1, 4}, {-1, 4, 4}};
  const double Us[] = {0.0, 0.5, 2.0};
  ics_csat *oc = NULL, *nc = NULL, *of = NULL, *nf = NULL;
  CHECK(ics_csat_build(&oc, &vol, dir, 1.0, ICS_SAT_COMPENSATED) == ICS_OK &&
            ics_csat_create(&nc, &vol, dir, 1.0, ICS_SAT_COMPENSATED) == ICS_OK,
        "csat create");
  CHECK(ics_csat_build_frame(&of, &vol, ru, rv, 0.5, ICS_SAT_DOUBLE) == ICS_OK &&
            ics_csat_create_frame(&nf, &vol, ru, rv, 0.5, ICS_SAT_DOUBLE) == ICS_OK,
        "csat create frame");
  for (int l = 0; l < 6 && oc && nc && of && nf; l++)
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
      for (size_t u = 0; u < sizeof Us / sizeof Us[0]; u++) {
        double to = -1, tn = -2, fo = -1, fn = -2;
        ics_status so = ics_csat_tau(oc, (ics_csat_light)l, pts[i], Us[u], &to);
        ics_status sn = ics_csat_tau(nc, (ics_csat_light)l, pts[i], Us[u], &tn);
        CHECK(so == sn && same(to, tn), "csat light %d p %zu U %g: %.17g vs %.17g", l, i, Us[u],
              to, tn);
        so = ics_csat_tau(of, (ics_csat_light)l, pts[i], Us[u], &fo);
        sn = ics_csat_tau(nf, (ics_csat_light)l, pts[i], Us[u], &fn);
        CHECK(so == sn && same(fo, fn), "csat frame light %d p %zu U %g: %.17g vs %.17g", l, i,
              Us[u], fo, fn);
      }
  ics_csat_free(oc);
  ics_csat_destroy(nc);
  ics_csat_free(of);
  ics_csat_destroy(nf);
  const double light[3] = {-6, 4, 4};
  ics_ssat *os = NULL, *ns = NULL;
  CHECK(ics_ssat_build(&os, &vol, light, 32, 16, 24, ICS_SAT_FLOAT_OFFSET) == ICS_OK &&
            ics_ssat_create(&ns, &vol, light, 32, 16, 24, ICS_SAT_FLOAT_OFFSET) == ICS_OK,
        "ssat create");
  for (size_t i = 0; i < sizeof pts / sizeof pts[0] && os && ns; i++)
    for (size_t u = 1; u < sizeof Us / sizeof Us[0]; u++) {
      double to = -1, tn = -2;
      ics_status so = ics_ssat_tau(os, pts[i], Us[u], &to);
      ics_status sn = ics_ssat_tau(ns, pts[i], Us[u], &tn);
      CHECK(so == sn && same(to, tn), "ssat p %zu U %g: %.17g vs %.17g", i, Us[u], to, tn);
    }
  ics_ssat_free(os);
  ics_ssat_destroy(ns);
  /* refused arguments: the same status, *out NULL */
  const double zero[3] = {0, 0, 0};
  ics_csat *bc = (ics_csat *)data, *bn = (ics_csat *)data;
  CHECK(ics_csat_build(&bc, &vol, zero, 1.0, ICS_SAT_DOUBLE) ==
                ics_csat_create(&bn, &vol, zero, 1.0, ICS_SAT_DOUBLE) &&
            !bc && !bn,
        "csat zero direction");
  CHECK(ics_csat_build_frame(&bc, &vol, ru, ru, 1.0, ICS_SAT_DOUBLE) ==
                ics_csat_create_frame(&bn, &vol, ru, ru, 1.0, ICS_SAT_DOUBLE) &&
            !bc && !bn,
        "csat frame not orthonormal");
  ics_ssat *bs = (ics_ssat *)data, *bt = (ics_ssat *)data;
  CHECK(ics_ssat_build(&bs, &vol, light, 0, 16, 24, ICS_SAT_DOUBLE) ==
                ics_ssat_create(&bt, &vol, light, 0, 16, 24, ICS_SAT_DOUBLE) &&
            !bs && !bt,
        "ssat n_phi 0");
  ics_csat_free(NULL);
  ics_ssat_free(NULL);
}

static void test_occtex(void) {
  enum { N = 16 };
  static float tex[2 * N * N];
  for (int i = 0; i < 2 * N * N; i++) tex[i] = (float)((i * 7) % 5) / 4.0f;
  const ics_occ_grid g = {-1, -1, 2.0 / N, N};
  ics_occtex *ot = NULL;
  CHECK(ics_occtex_create(&ot, tex, &g, 2, 1, 2) == ICS_OK, "occtex create");
  ics_occtex_free(ot); /* ASan: freed exactly once, nothing leaked */
  ics_occtex_free(NULL);
}

/* ics_occ_* -> ics_occtex_*, scenes -> box sets */
static void test_occtex_names(void) {
  CHECK((int)ICS_OCC_SCENE_FOLIAGE == (int)ICS_OCC_BOXES_FOLIAGE &&
            (int)ICS_OCC_SCENE_PLATES == (int)ICS_OCC_BOXES_PLATES &&
            (int)ICS_OCC_SCENE_BLOCKS == (int)ICS_OCC_BOXES_BLOCKS &&
            sizeof(ics_occ_scene_kind) == sizeof(ics_occ_boxes_kind),
        "ICS_OCC_SCENE_*");
  for (int i = -1; i <= ICS_OCC_PREFILTER_COUNT; i++)
    CHECK(ics_occ_prefilter_name((ics_occ_prefilter)i) ==
              ics_occtex_prefilter_name((ics_occ_prefilter)i),
          "ics_occ_prefilter_name(%d)", i);
  for (int i = -1; i <= ICS_OCC_COMBINE_COUNT; i++)
    CHECK(ics_occ_combine_name((ics_occ_combine)i) == ics_occtex_combine_name((ics_occ_combine)i),
          "ics_occ_combine_name(%d)", i);
  enum { NB = 40, N = 32, K = 3 };
  static ics_occ_box bo[NB], bn[NB];
  static float to[K * N * N], tn[K * N * N];
  const ics_occ_grid g = {-1, -1, 2.0 / N, N};
  const ics_occ_light L = {0.1, -0.05, 0.6, 0.4};
  const double P[] = {0, 0, 2.5, 0.3, -0.4, 2.2, -0.9, 0.8, 1.5};
  for (int kind = 0; kind < 3; kind++) {
    memset(bo, 0, sizeof bo);
    memset(bn, 0, sizeof bn);
    CHECK(ics_occ_scene_make((ics_occ_boxes_kind)kind, NB, 7, bo) == ICS_OK &&
              ics_occtex_boxes_make((ics_occ_boxes_kind)kind, NB, 7, bn) == ICS_OK &&
              !memcmp(bo, bn, sizeof bo),
          "ics_occ_scene_make kind %d", kind);
    CHECK(ics_occ_slice(bn, NB, &g, K, 1, 2, 2, to) == ICS_OK &&
              ics_occtex_slice_boxes(bn, NB, &g, K, 1, 2, 2, tn) == ICS_OK &&
              !memcmp(to, tn, sizeof to),
          "ics_occ_slice kind %d", kind);
    double oo[3] = {-1, -1, -1}, on[3] = {-1, -1, -1};
    CHECK(ics_occ_exact(bn, NB, &L, 9, P, 3, oo) == ICS_OK &&
              ics_occtex_exact(bn, NB, &L, 9, P, 3, on) == ICS_OK && same(oo[0], on[0]) &&
              same(oo[1], on[1]) && same(oo[2], on[2]),
          "ics_occ_exact kind %d", kind);
  }
  CHECK(ics_occ_scene_make(ICS_OCC_BOXES_PLATES, 0, 7, bo) ==
                ics_occtex_boxes_make(ICS_OCC_BOXES_PLATES, 0, 7, bn) &&
            ics_occ_slice(bn, NB, &g, 0, 1, 2, 2, to) ==
                ics_occtex_slice_boxes(bn, NB, &g, 0, 1, 2, 2, tn) &&
            ics_occ_exact(bn, NB, &L, 0, P, 3, NULL) == ics_occtex_exact(bn, NB, &L, 0, P, 3, NULL),
        "ics_occ_*, bad arguments");
  const double fs[][3] = {{0.2, 0.5, 0.9}, {0, 1, 0.5}, {0.3, NAN, 0.1}, {1.5, 0, 0}};
  for (int c = -1; c <= ICS_OCC_COMBINE_COUNT; c++)
    for (size_t i = 0; i < sizeof fs / sizeof fs[0]; i++)
      for (int k = -1; k <= 3; k++)
        CHECK(same(ics_occ_combine_values((ics_occ_combine)c, fs[i], k),
                   ics_occtex_combine_values((ics_occ_combine)c, fs[i], k)),
              "ics_occ_combine_values(%d, %zu, %d)", c, i, k);
}

static void test_lut_grid(void) {
  const int sizes[][2] = {{4, 2}, {16, 16}, {256, ICS_LUT_STAMP_PER_INTERVAL}};
  for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++) {
    ics_lut_grid *o = NULL, *n = NULL;
    ics_status so = ics_lut_grid_new(sizes[i][0], sizes[i][1], &o);
    ics_status sn = ics_lut_grid_create(&n, sizes[i][0], sizes[i][1]);
    CHECK(so == ICS_OK && sn == ICS_OK, "lut grid %d/%d: %d %d", sizes[i][0], sizes[i][1], so, sn);
    ics_lut_error eo, en;
    CHECK(ics_lut_measure(o, ics_lut_builtin(), 0, &eo) == ICS_OK &&
              ics_lut_measure(n, ics_lut_builtin(), 0, &en) == ICS_OK,
          "lut measure");
    CHECK(ics_lut_grid_points(o) == ics_lut_grid_points(n) && eo.points == en.points &&
              same(eo.ratio, en.ratio) && same(eo.ratio_at, en.ratio_at) && same(eo.vx, en.vx) &&
              same(eo.vx_at, en.vx_at) && same(eo.radii, en.radii) &&
              same(eo.radii_at, en.radii_at),
          "lut grid %d/%d: the same points and errors", sizes[i][0], sizes[i][1]);
    ics_lut_grid_free(o);
    ics_lut_grid_destroy(n);
  }
  ics_lut_grid *o = (ics_lut_grid *)sizes, *n = (ics_lut_grid *)sizes;
  CHECK(ics_lut_grid_new(3, 16, &o) == ics_lut_grid_create(&n, 3, 16) && !o && !n,
        "lut grid size 3");
  CHECK(ics_lut_grid_new(16, 16, NULL) == ics_lut_grid_create(NULL, 16, 16), "lut grid NULL");
  ics_lut_grid_free(NULL);
}

/* ---- shadow1d.h split: ics_clt_* -> ics_clt1d_*, the iterated shadow's cost and options ---- */

static int same_taps(const ics_tap1d *a, int na, const ics_tap1d *b, int nb) {
  if (na != nb) return 0;
  for (int j = 0; j < na; j++)
    if (!same(a[j].x, b[j].x) || !same(a[j].w, b[j].w)) return 0;
  return 1;
}

/* every field but the measured run time */
static int same_points(const ics_clt_point *a, const ics_clt_point *b, int n) {
  for (int k = 0; k < n; k++)
    if (a[k].steps != b[k].steps || !same(a[k].sup_err, b[k].sup_err) ||
        !same(a[k].sup_err_realized, b[k].sup_err_realized) ||
        !same(a[k].disc_err, b[k].disc_err) || !same(a[k].cost, b[k].cost))
      return 0;
  return 1;
}

static void test_clt1d(void) {
  CHECK(ICS_CLT_SKEW_TAPS == ICS_CLT1D_SKEW_TAPS, "ICS_CLT_SKEW_TAPS");
  CHECK(ICS_WORK_COMP_PASSES == ICS_CONV_WORK_COMP_PASSES &&
            ICS_WORK_BUDGET == ICS_CONV_WORK_BUDGET,
        "ICS_WORK_*");
  const double mv[][2] = {{0, 1}, {0.3, 2.5}, {-1.25, 1e-3}, {0, 0},
                          {0, -1}, {NAN, 1},    {0, INFINITY}};
  for (size_t i = 0; i < sizeof mv / sizeof mv[0]; i++) {
    ics_tap1d a[ICS_CLT1D_SKEW_TAPS], b[ICS_CLT1D_SKEW_TAPS];
    memset(a, 0, sizeof a);
    memset(b, 0, sizeof b);
    ics_status sa = ics_clt_skew_taps(mv[i][0], mv[i][1], a);
    ics_status sb = ics_clt1d_skew_taps(mv[i][0], mv[i][1], b);
    CHECK(sa == sb && same_taps(a, ICS_CLT1D_SKEW_TAPS, b, ICS_CLT1D_SKEW_TAPS),
          "ics_clt_skew_taps(%g, %g)", mv[i][0], mv[i][1]);
  }
  ics_kernel1d k;
  CHECK(ics_kernel1d_init(&k, ICS_KERNEL_STOCH_DIRAC, 0.2, 3.0) == ICS_OK, "kernel");
  k.seed = 11;
  for (uint64_t step = 0; step < 4; step++)
    for (int r = 1; r <= 2; r++) {
      ics_tap1d a[8], b[8];
      int na = -1, nb = -2;
      ics_status sa = ics_clt_member_gen(&k, step, r, a, 8, &na);
      ics_status sb = ics_clt1d_member_gen(&k, step, r, b, 8, &nb);
      CHECK(sa == sb && sa == ICS_OK && same_taps(a, na, b, nb), "ics_clt_member_gen step %d",
            (int)step);
      CHECK(ics_clt_member_gen(&k, step, r, a, 1, &na) ==
                ics_clt1d_member_gen(&k, step, r, b, 1, &nb),
            "ics_clt_member_gen, no room");
    }
  ics_tap1d skew[ICS_CLT1D_SKEW_TAPS];
  ics_clt1d_skew_taps(0.1, 2.0, skew);
  ics_clt_fixed fixed = {skew, ICS_CLT1D_SKEW_TAPS};
  for (int r = 1; r <= 2; r++) {
    ics_tap1d a[ICS_CLT1D_SKEW_TAPS], b[ICS_CLT1D_SKEW_TAPS];
    int na = -1, nb = -2;
    CHECK(ics_clt_fixed_gen(&fixed, 3, r, a, ICS_CLT1D_SKEW_TAPS, &na) == ICS_OK &&
              ics_clt1d_fixed_gen(&fixed, 3, r, b, ICS_CLT1D_SKEW_TAPS, &nb) == ICS_OK &&
              same_taps(a, na, b, nb),
          "ics_clt_fixed_gen scale %d", r);
    CHECK(ics_clt_fixed_gen(&fixed, 3, r, a, 4, &na) ==
              ics_clt1d_fixed_gen(&fixed, 3, r, b, 4, &nb),
          "ics_clt_fixed_gen, no room");
  }
  const int steps[] = {1, 4, 9};
  const ics_clt_gen gens[] = {ics_clt1d_member_gen, ics_clt1d_fixed_gen};
  void *ctxs[] = {&k, &fixed};
  for (int g = 0; g < 2; g++)
    for (int refine = 0; refine <= 1; refine++) {
      ics_clt_point a[3], b[3];
      ics_status sa = ics_clt_measure(gens[g], ctxs[g], 0.2, 3.0, steps, 3, ICS_COMP_NONNEG,
                                      refine, a);
      ics_status sb = ics_clt1d_measure(gens[g], ctxs[g], 0.2, 3.0, steps, 3, ICS_COMP_NONNEG,
                                        refine, b);
      CHECK(sa == sb && sa == ICS_OK && same_points(a, b, 3), "ics_clt_measure gen %d refine %d",
            g, refine);
      double na = -1, wa = -1, nb = -1, wb = -1;
      sa = ics_clt_cost(gens[g], ctxs[g], 0.2, 3.0, steps, 3, ICS_COMP_SIGNED, refine, &na, &wa);
      sb = ics_clt1d_cost(gens[g], ctxs[g], 0.2, 3.0, steps, 3, ICS_COMP_SIGNED, refine, &nb, &wb);
      CHECK(sa == sb && same(na, nb) && same(wa, wb), "ics_clt_cost gen %d refine %d", g, refine);
    }
  const int bad_steps[] = {4, 2};
  ics_clt_point p[2];
  CHECK(ics_clt_measure(ics_clt1d_member_gen, &k, 0.2, 3.0, bad_steps, 2, ICS_COMP_NONE, 0, p) ==
            ics_clt1d_measure(ics_clt1d_member_gen, &k, 0.2, 3.0, bad_steps, 2, ICS_COMP_NONE, 0,
                              p),
        "ics_clt_measure, steps not increasing");
  double nodes, work;
  CHECK(ics_clt_cost(NULL, &k, 0, 1, steps, 3, ICS_COMP_NONE, 0, &nodes, &work) ==
            ics_clt1d_cost(NULL, &k, 0, 1, steps, 3, ICS_COMP_NONE, 0, &nodes, &work),
        "ics_clt_cost, no generator");
}

static void test_iter1d(void) {
  ics_iter1d_opts a = ics_iter1d_opts_default(), b;
  ics_iter1d_opts_init(&b);
  CHECK(a.member == b.member && a.nsamples == b.nsamples && same(a.param, b.param) &&
            a.seed == b.seed && same(a.h, b.h) && same(a.ppsd, b.ppsd) &&
            a.compensate == b.compensate && a.no_edge_comp == b.no_edge_comp &&
            same(a.mean_sign, b.mean_sign) && same(a.var_factor, b.var_factor) && a.skew == b.skew,
        "ics_iter1d_opts_default");
  ics_light1d *l = NULL;
  CHECK(ics_light1d_create_gauss(&l, 0.3, 0.8) == ICS_OK, "light");
  const double dd1e[][3] = {{2, 1, 0.25}, {0, 1, 0.5}, {1, 2, 0.3}, {-1, 1, 0.5}, {1, 0, 0.5}};
  for (int skew = 0; skew <= 1; skew++)
    for (size_t i = 0; i < sizeof dd1e / sizeof dd1e[0]; i++) {
      ics_iter1d_opts o = b;
      o.skew = skew;
      double ha = -1, na = -1, wa = -1, hb = -1, nb = -1, wb = -1; /* kept on errors */
      ics_status sa = ics_shadow1d_iterate_cost(l, dd1e[i][0], dd1e[i][1], dd1e[i][2], &o, &ha,
                                                &na, &wa);
      ics_status sb = ics_iter1d_cost(l, dd1e[i][0], dd1e[i][1], dd1e[i][2], &o, &hb, &nb, &wb);
      CHECK(sa == sb && same(ha, hb) && same(na, nb) && same(wa, wb),
            "ics_shadow1d_iterate_cost skew %d case %zu", skew, i);
    }
  CHECK(ics_shadow1d_iterate_cost(NULL, 1, 1, 0.5, NULL, NULL, NULL, NULL) ==
            ics_iter1d_cost(NULL, 1, 1, 0.5, NULL, NULL, NULL, NULL),
        "ics_shadow1d_iterate_cost, no light");
  ics_light1d_destroy(l);
}

/* ---- minmax.h split: ics_epi_* -> ics_epipolar_*, ics_hf_* -> ics_heightfield_* ---- */

static int same_frames(const ics_epipolar_frame *a, const ics_epipolar_frame *b) {
  for (int i = 0; i < 3; i++)
    if (!same(a->eye[i], b->eye[i]) || !same(a->L[i], b->L[i]) || !same(a->U[i], b->U[i]) ||
        !same(a->V[i], b->V[i]))
      return 0;
  return same(a->eu, b->eu) && same(a->ev, b->ev) && same(a->depth_eye, b->depth_eye) &&
         same(a->dgamma, b->dgamma) && a->rows == b->rows && a->d == b->d;
}

static void test_epipolar_heightfield(void) {
  CHECK(ICS_HF_MAX_SHAPES == ICS_HEIGHTFIELD_MAX_SHAPES, "ICS_HF_MAX_SHAPES");
  ics_hf_scene so;
  ics_heightfield sn;
  memset(&so, 0xa5, sizeof so);
  memset(&sn, 0x5a, sizeof sn);
  ics_hf_scene_default(&so);
  ics_heightfield_init_default(&sn);
  CHECK(!memcmp(&so, &sn, sizeof so), "ics_hf_scene_default");
  ics_hf_scene_default(NULL);
  const double eye[3] = {0.5, 1.5, 9.0}, L[3] = {0.3, 0.9, 0.2}, zero[3] = {0, 0, 0};
  ics_epi_frame fo;
  ics_epipolar_frame fn;
  memset(&fo, 0, sizeof fo);
  memset(&fn, 0, sizeof fn);
  CHECK(ics_epi_frame_init(&fo, eye, L, 16, 32, 0.25) == ICS_OK &&
            ics_epipolar_frame_init(&fn, eye, L, 16, 32, 0.25) == ICS_OK && same_frames(&fo, &fn),
        "ics_epi_frame_init");
  ics_epipolar_frame bad;
  CHECK(ics_epi_frame_init(&bad, eye, zero, 16, 32, 0.25) ==
                ics_epipolar_frame_init(&bad, eye, zero, 16, 32, 0.25) &&
            ics_epi_frame_init(&bad, eye, L, 0, 32, 0.25) ==
                ics_epipolar_frame_init(&bad, eye, L, 0, 32, 0.25),
        "ics_epi_frame_init, bad arguments");
  const double pts[][3] = {{1, 0, 2}, {-3, 0.5, 4}, {0.5, 1.5, 9.0}, {NAN, 0, 0}};
  for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++) {
    double ao = -1, go = -1, dpo = -1, an = -1, gn = -1, dpn = -1;
    ics_status so1 = ics_epi_locate(&fn, pts[i], &ao, &go, &dpo);
    ics_status sn1 = ics_epipolar_locate(&fn, pts[i], &an, &gn, &dpn);
    CHECK(so1 == sn1 && same(ao, an) && same(go, gn) && same(dpo, dpn), "ics_epi_locate %zu", i);
  }
  const double dirs[][3] = {{0.1, -0.2, -1}, {1, 0.3, 0.2}, {0.3, 0.9, 0.2}, {0, INFINITY, 0}};
  for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++) {
    double ao = -1, an = -1;
    size_t ro = 99, rn = 99;
    ics_minmax_ray yo = {-1, -1, 0}, yn = {-1, -1, 0};
    ics_status so1 = ics_epi_ray(&fn, dirs[i], &ao, &ro, &yo);
    ics_status sn1 = ics_epipolar_ray(&fn, dirs[i], &an, &rn, &yn);
    CHECK(so1 == sn1 && same(ao, an) && ro == rn && same(yo.beta0, yn.beta0) &&
              same(yo.slope, yn.slope),
          "ics_epi_ray %zu", i);
  }
  const double betas[] = {0.3, 1.2, 0.0, 4.0};
  for (size_t row = 0; row < 17; row += 4)
    for (size_t i = 0; i < sizeof betas / sizeof betas[0]; i++) {
      double dno[3] = {-1, -1, -1}, dnn[3] = {-1, -1, -1};
      ics_status so1 = ics_epi_ray_dir(&fn, row, betas[i], dno);
      ics_status sn1 = ics_epipolar_ray_dir(&fn, row, betas[i], dnn);
      CHECK(so1 == sn1 && same(dno[0], dnn[0]) && same(dno[1], dnn[1]) && same(dno[2], dnn[2]),
            "ics_epi_ray_dir row %zu beta %g", row, betas[i]);
    }
  enum { W = 24 };
  static float smo[W * W], smn[W * W], ro[16 * 32], rn[16 * 32];
  CHECK(ics_hf_shadow_map(&sn, &fn, W, 6.0, smo) == ICS_OK &&
            ics_heightfield_shadow_map(&sn, &fn, W, 6.0, smn) == ICS_OK &&
            !memcmp(smo, smn, sizeof smo),
        "ics_hf_shadow_map");
  CHECK(ics_hf_shadow_map(&sn, &fn, W, -1.0, smo) ==
            ics_heightfield_shadow_map(&sn, &fn, W, -1.0, smn),
        "ics_hf_shadow_map, negative size");
  CHECK(ics_epi_rectify(&fn, smn, W, W, fn.eu - 6.0, fn.ev - 6.0, 0.5, ro) == ICS_OK &&
            ics_epipolar_rectify(&fn, smn, W, W, fn.eu - 6.0, fn.ev - 6.0, 0.5, rn) == ICS_OK &&
            !memcmp(ro, rn, sizeof ro),
        "ics_epi_rectify");
  CHECK(ics_epi_rectify(&fn, smn, W, W, 0, 0, 0.0, ro) ==
            ics_epipolar_rectify(&fn, smn, W, W, 0, 0, 0.0, rn),
        "ics_epi_rectify, zero texel");
  for (int k = 0; k < 3; k++) {
    const double o[3] = {-5 + 4 * k, 8, 1 - k}, d[3] = {0.2 * k, -1, 0.1};
    CHECK(same(ics_hf_scene_hit(&sn, o, d, 0), ics_heightfield_hit(&sn, o, d, 0)) &&
              same(ics_hf_scene_hit(&sn, o, d, 3.0), ics_heightfield_hit(&sn, o, d, 3.0)),
          "ics_hf_scene_hit %d", k);
  }
  const double o[3] = {0, 1, 0};
  CHECK(same(ics_hf_scene_hit(NULL, o, o, 0), ics_heightfield_hit(NULL, o, o, 0)),
        "ics_hf_scene_hit, no scene");
}

/* ---- value structs: defaults and constructors ---- */

static void test_value_structs(void) {
  ics_conv_opts co = ics_conv_opts_default(), zero = {0};
  CHECK(co.boundary == zero.boundary && same(co.constant, zero.constant) &&
            co.compensate == zero.compensate && co.boundary == ICS_BOUNDARY_CLAMP &&
            co.compensate == ICS_COMP_NONE,
        "ics_conv_opts_default is the zero struct");
  ics_clt2d_setup so = ics_clt2d_setup_default(), sn;
  ics_clt2d_setup_init(&sn);
  CHECK(so.occluder == sn.occluder && same(so.edge_angle_deg, sn.edge_angle_deg) &&
            same(so.mean[0], sn.mean[0]) && same(so.mean[1], sn.mean[1]) &&
            same(so.cov[0], sn.cov[0]) && same(so.cov[1], sn.cov[1]) &&
            same(so.cov[2], sn.cov[2]) && so.comp == sn.comp && so.refine == sn.refine,
        "ics_clt2d_setup_default");
  ics_lightfit_params po, pn;
  memset(&po, 0xa5, sizeof po);
  memset(&pn, 0x5a, sizeof pn);
  ics_lightfit_defaults(&po);
  ics_lightfit_params_init(&pn);
  CHECK(po.k == pn.k && same(po.max_angle_deg, pn.max_angle_deg) && po.seed == pn.seed &&
            po.max_samples == pn.max_samples && po.max_iter == pn.max_iter &&
            same(po.tol, pn.tol) && po.progress == pn.progress &&
            po.progress_ctx == pn.progress_ctx,
        "ics_lightfit_defaults");
  const uint64_t seeds[][2] = {{0, 0}, {12345, 7}, {UINT64_MAX, 1}};
  for (size_t i = 0; i < sizeof seeds / sizeof seeds[0]; i++) {
    ics_rng a = ics_rng_make(seeds[i][0], seeds[i][1]), b;
    ics_rng_init(&b, seeds[i][0], seeds[i][1]);
    int eq = a.seed == b.seed && a.stream == b.stream && a.index == b.index;
    for (int k = 0; k < 8 && eq; k++) eq = ics_rng_next_u64(&a) == ics_rng_next_u64(&b);
    CHECK(eq, "ics_rng_make(%llu, %llu)", (unsigned long long)seeds[i][0],
          (unsigned long long)seeds[i][1]);
  }
}

/* ---- kernel.h split ---- */

static void test_class_taps(void) {
  const double args[][5] = {{0, 0, 3, 1.5, 30},       {1, -2, 6, 2, 90},  {0.3, 0.5, 0, 0, 0},
                            {0, 0, 1e300, 1e-300, -45}, {0, 0, -1, 1, 0},  {NAN, 0, 1, 1, 0},
                            {0, 0, 1, INFINITY, 0}};
  for (size_t i = 0; i < sizeof args / sizeof args[0]; i++) {
    ics_class2d a, b;
    memset(&a, 0, sizeof a);
    memset(&b, 0, sizeof b);
    const double *v = args[i];
    ics_status sa = ics_class2d_from_axes(v[0], v[1], v[2], v[3], v[4], &a);
    ics_status sb = ics_class2d_init_axes(&b, v[0], v[1], v[2], v[3], v[4]);
    CHECK(sa == sb && same(a.mean[0], b.mean[0]) && same(a.mean[1], b.mean[1]) &&
              same(a.cxx, b.cxx) && same(a.cxy, b.cxy) && same(a.cyy, b.cyy),
          "ics_class2d_from_axes case %zu", i);
  }
  CHECK(ics_class2d_from_axes(0, 0, 1, 1, 0, NULL) == ics_class2d_init_axes(NULL, 0, 0, 1, 1, 0),
        "ics_class2d_from_axes, NULL out");
  const ics_tap1d t1[] = {{0.25, 0.5}, {-1.75, 0.25}, {3.0, 0.125}, {1e9 + 0.5, 0.125}};
  const ics_tap2d t2[] = {{0.25, -0.5, 0.5}, {-1.75, 2.125, 0.25}, {3.0, 0.0, 0.25}};
  for (int n = 0; n <= 4; n++)
    CHECK(same(ics_interp_var1d(t1, n), ics_taps1d_interp_var(t1, n)), "ics_interp_var1d n %d",
          n);
  CHECK(same(ics_interp_var1d(NULL, 2), ics_taps1d_interp_var(NULL, 2)), "ics_interp_var1d NULL");
  for (int n = 0; n <= 3; n++) {
    double a[2] = {-1, -1}, b[2] = {-1, -1};
    ics_interp_var2d(t2, n, a);
    ics_taps2d_interp_var(t2, n, b);
    CHECK(same(a[0], b[0]) && same(a[1], b[1]), "ics_interp_var2d n %d", n);
  }
}

/* ---- light.h, rng.h, ellint.h: prefixed by their header ---- */

static void test_light_rng_ellint(void) {
  const double ws[] = {0, 30, -45, 45.0000001, 89.999999, -89.9999999999, 90, 120, NAN, INFINITY};
  for (size_t i = 0; i < sizeof ws / sizeof ws[0]; i++)
    CHECK(same(ics_tan_deg(ws[i]), ics_light_tan_deg(ws[i])) &&
              same(ics_tilt_condition(ws[i]), ics_light_tilt_condition(ws[i])),
          "ics_tan_deg / ics_tilt_condition(%a)", ws[i]);
  const double eig[][3] = {{3, 1, 30}, {3, 1, 90}, {1e-300, 0, -90}, {2, 2, 45},
                           {-1, 1, 0}, {NAN, 1, 0}, {1, INFINITY, 0}};
  for (size_t i = 0; i < sizeof eig / sizeof eig[0]; i++) {
    double a[3] = {-1, -1, -1}, b[3] = {-1, -1, -1};
    ics_status sa = ics_cov_from_eig(eig[i][0], eig[i][1], eig[i][2], a);
    ics_status sb = ics_light_cov_from_eig(eig[i][0], eig[i][1], eig[i][2], b);
    CHECK(sa == sb && same(a[0], b[0]) && same(a[1], b[1]) && same(a[2], b[2]),
          "ics_cov_from_eig case %zu", i);
    double va = -1, wa = -1, aa = -1, vb = -1, wb = -1, ab = -1;
    sa = ics_cov_to_eig(b, &va, &wa, &aa);
    sb = ics_light_cov_to_eig(b, &vb, &wb, &ab);
    CHECK(sa == sb && same(va, vb) && same(wa, wb) && same(aa, ab), "ics_cov_to_eig case %zu", i);
  }
  const double bad_cov[3] = {1, 5, 1};
  double x = 0;
  CHECK(ics_cov_to_eig(bad_cov, &x, &x, &x) == ics_light_cov_to_eig(bad_cov, &x, &x, &x),
        "ics_cov_to_eig, not PSD");
  const double tilts[][2] = {{10, -6}, {0, 0}, {89.5, 1}, {90, 0}, {NAN, 0}};
  const double rgb[3] = {1, 0.5, 0.25};
  for (size_t i = 0; i < sizeof tilts / sizeof tilts[0]; i++)
    for (int colored = 0; colored <= 1; colored++) {
      ics_light a, b;
      memset(&a, 0, sizeof a);
      memset(&b, 0, sizeof b);
      const double *c = colored ? rgb : NULL;
      ics_status sa = ics_light_from_tilt(&a, tilts[i][0], tilts[i][1], 0.02, 0.008, 30, c, 2);
      ics_status sb = ics_light_init_tilt(&b, tilts[i][0], tilts[i][1], 0.02, 0.008, 30, c, 2);
      CHECK(sa == sb && !memcmp(&a, &b, sizeof a), "ics_light_from_tilt case %zu", i);
      double ma[2] = {-1, -1}, ca[3] = {-1, -1, -1}, mb[2] = {-1, -1}, cb[3] = {-1, -1, -1};
      sa = ics_kernel_map_2d(&b, 0.25, 2, ma, ca);
      sb = ics_light_kernel_map_2d(&b, 0.25, 2, mb, cb);
      CHECK(sa == sb && same(ma[0], mb[0]) && same(ma[1], mb[1]) && same(ca[0], cb[0]) &&
                same(ca[1], cb[1]) && same(ca[2], cb[2]),
            "ics_kernel_map_2d case %zu", i);
    }
  const double m1d[][4] = {{0.3, 2, 0.1, 4}, {0.3, -2, 0.1, 4}, {0, 1, 0, 1}, {NAN, 1, 1, 1}};
  for (size_t i = 0; i < sizeof m1d / sizeof m1d[0]; i++) {
    double ma = -1, va = -1, mb = -1, vb = -1;
    ics_status sa = ics_kernel_map_1d(m1d[i][0], m1d[i][1], m1d[i][2], m1d[i][3], &ma, &va);
    ics_status sb = ics_light_kernel_map_1d(m1d[i][0], m1d[i][1], m1d[i][2], m1d[i][3], &mb, &vb);
    CHECK(sa == sb && same(ma, mb) && same(va, vb), "ics_kernel_map_1d case %zu", i);
  }
  const uint32_t ctr[4] = {0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344};
  const uint32_t key[2] = {0xa4093822, 0x299f31d0};
  uint32_t oa[4], ob[4];
  ics_philox4x32_10(ctr, key, oa);
  ics_rng_philox4x32_10(ctr, key, ob);
  CHECK(!memcmp(oa, ob, sizeof oa), "ics_philox4x32_10");
  const double ms[] = {0.0, 0.5, 1.0, -1e300, 0x1p-1074, 1.0 - 0x1p-53, 1.5, -INFINITY, NAN};
  for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++) {
    double m = ms[i];
    CHECK(same(ics_ellipk(m), ics_ellint_k(m)) && same(ics_ellipe(m), ics_ellint_e(m)) &&
              same(ics_ellipk_m1(m), ics_ellint_k_m1(m)) &&
              same(ics_ellipe_m1(m), ics_ellint_e_m1(m)),
          "ics_ellipk/e(_m1)(%a)", m);
    double ka = -1, ea = -1, kb = -1, eb = -1;
    ics_ellipke_m1(m, &ka, &ea);
    ics_ellint_ke_m1(m, &kb, &eb);
    CHECK(same(ka, kb) && same(ea, eb), "ics_ellipke_m1(%a)", m);
  }
  ics_ellipke_m1(0.5, NULL, NULL);
}

int main(void) {
  test_normal();
  test_volume();
  test_sat();
  test_csat_ssat();
  test_occtex();
  test_occtex_names();
  test_lut_grid();
  test_clt1d();
  test_iter1d();
  test_epipolar_heightfield();
  test_value_structs();
  test_class_taps();
  test_light_rng_ellint();
  return test_summary("test_deprecated");
}
