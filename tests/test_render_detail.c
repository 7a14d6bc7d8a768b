/* test_render_detail.c — volumetric detail and transfer functions (gpu/core/detail.c):
 * improved noise is 0 on the integer lattice, bounded by 1, continuous, and a seed names a field;
 * fBm with one octave is the noise itself, and its octaves add; a 3D grid file is sampled
 * trilinearly over the object's box (values checked at corners and midpoints by hand) and a file
 * of the wrong length is refused; the transfer function interpolates its nodes and clamps at the
 * ends; preintegration equals a fine midpoint quadrature of the transfer function over the ramp;
 * the cpu backend's batches of detail values (detail_batch.h) equal ics_detail_value bit for bit
 * on every vector path this processor has, for noise, fBm and ridged multifractal (its weight
 * clamped at both ends), at points near and far from the origin, on lattice points, and for
 * counts that are not whole vectors. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "detail.h"
#include "detail_batch.h"
#include "render_util.h"
#include "testutil.h"

static ics_scene *volume_scene(const char *detail, const char *transfer, const char *dir) {
  char j[4096], msg[4096];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [8, 8]},"
           " \"render\": {\"slab_spacing\": 0.1, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
           " \"materials\": {\"v\": {\"extinction\": 2, \"detail\": %s%s%s}},"
           " \"objects\": [{\"shape\": \"box\", \"center\": [1, 2, 3], \"size\": [2, 4, 6], \"material\": \"v\"}]}",
           detail, transfer ? ", \"transfer\": " : "", transfer ? transfer : "");
  ics_scene *s;
  if (ics_scene_create_json(&s, j, "detail", dir, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "scene: %s\n", msg);
    return NULL;
  }
  return s;
}

static void prepare(ics_detail_eval *e, const ics_scene *s) {
  double lo[3], hi[3];
  const ics_object *o = ics_scene_object(s, 0);
  for (int i = 0; i < 3; i++) lo[i] = o->center[i] - o->half[i], hi[i] = o->center[i] + o->half[i];
  ics_detail_prepare(e, &ics_scene_material(s, 0)->detail, lo, hi);
}

static void test_noise(void) {
  ics_scene *s = volume_scene("{\"function\": \"perlin\", \"seed\": 5}", NULL, NULL);
  ics_scene *s2 = volume_scene("{\"function\": \"perlin\", \"seed\": 6}", NULL, NULL);
  if (!s || !s2) return;
  ics_detail_eval e, e2;
  prepare(&e, s);
  prepare(&e2, s2);
  double lattice = 0, vmax = 0, jump = 0, diff = 0;
  for (int i = 0; i < 200000; i++) {
    double p[3] = {20 * test_rng_unit() - 10, 20 * test_rng_unit() - 10, 20 * test_rng_unit() - 10};
    double v = ics_perlin_noise(e.perm, p[0], p[1], p[2]);
    vmax = fmax(vmax, fabs(v));
    double q[3] = {p[0] + 1e-7, p[1] - 1e-7, p[2] + 1e-7};
    jump = fmax(jump, fabs(ics_perlin_noise(e.perm, q[0], q[1], q[2]) - v));
    diff = fmax(diff, fabs(ics_detail_value(&e, p) - ics_detail_value(&e2, p)));
    double lp[3] = {floor(p[0]), floor(p[1]), floor(p[2])};
    lattice = fmax(lattice, fabs(ics_perlin_noise(e.perm, lp[0], lp[1], lp[2])));
  }
  CHECK(lattice == 0, "noise on the integer lattice: %g", lattice);
  CHECK(vmax <= 1.0 && vmax > 0.6, "noise range: max |n| = %g", vmax);
  CHECK(jump < 1e-5, "noise continuity: a 1e-7 step moves it by %g", jump);
  CHECK(diff > 0.5, "another seed gives the same field (max difference %g)", diff);
  printf("improved noise: 0 on the lattice, max |n| = %.3f over 2e5 points, seeds differ\n", vmax);
  ics_scene_destroy(s);
  ics_scene_destroy(s2);
  /* fBm: one octave is the noise; two octaves add the second at lacunarity and gain */
  ics_scene *f1 = volume_scene("{\"function\": \"fbm\", \"octaves\": 1, \"frequency\": 2, \"seed\": 5}", NULL, NULL);
  ics_scene *f2 = volume_scene("{\"function\": \"fbm\", \"octaves\": 2, \"frequency\": 2, \"gain\": 0.3, \"lacunarity\": 3, \"seed\": 5}", NULL, NULL);
  if (!f1 || !f2) return;
  ics_detail_eval a, b;
  prepare(&a, f1);
  prepare(&b, f2);
  double worst = 0;
  for (int i = 0; i < 1000; i++) {
    double p[3] = {test_rng_unit(), test_rng_unit(), test_rng_unit()};
    double n1 = ics_perlin_noise(a.perm, 2 * p[0], 2 * p[1], 2 * p[2]);
    double n2 = ics_perlin_noise(a.perm, 6 * p[0], 6 * p[1], 6 * p[2]);
    worst = fmax(worst, fabs(ics_detail_value(&a, p) - n1));
    worst = fmax(worst, fabs(ics_detail_value(&b, p) - (n1 + 0.3 * n2)));
  }
  CHECK(worst < 1e-12, "fBm octaves: off by %g", worst);
  ics_scene_destroy(f1);
  ics_scene_destroy(f2);
}

static void test_grid(const char *dir) {
  char path[4096];
  snprintf(path, sizeof path, "%s/test_render_detail_grid.raw", dir);
  FILE *f = fopen(path, "wb");
  CHECK(f != NULL, "cannot write %s", path);
  if (!f) return;
  /* 2 x 2 x 2, x fastest: value = x + 2 y + 4 z (0..7) */
  float v[8];
  for (int i = 0; i < 8; i++) v[i] = (float)i;
  fwrite(v, sizeof v, 1, f);
  fclose(f);
  ics_scene *s = volume_scene("{\"function\": \"grid\", \"file\": \"test_render_detail_grid.raw\", \"size\": [2, 2, 2]}",
                              NULL, dir);
  CHECK(s != NULL, "grid scene");
  if (s) {
    ics_detail_eval e;
    prepare(&e, s);
    /* the box [0, 2] x [0, 4] x [0, 6] holds 2 cells per axis: cell centres at 1/4 and 3/4 of
     * each side; the sample is trilinear between centres, clamped at the faces (ics_volume) */
    double c000[3] = {0.5, 1, 1.5}, c111[3] = {1.5, 3, 4.5}, mid[3] = {1, 2, 3}, x1[3] = {1.5, 1, 1.5};
    CHECK(fabs(ics_detail_value(&e, c000) - 0) < 1e-6, "grid at cell (0,0,0): %g", ics_detail_value(&e, c000));
    CHECK(fabs(ics_detail_value(&e, c111) - 7) < 1e-6, "grid at cell (1,1,1): %g", ics_detail_value(&e, c111));
    CHECK(fabs(ics_detail_value(&e, mid) - 3.5) < 1e-6, "grid at the centre: %g", ics_detail_value(&e, mid));
    CHECK(fabs(ics_detail_value(&e, x1) - 1) < 1e-6, "grid at cell (1,0,0): %g", ics_detail_value(&e, x1));
    ics_scene_destroy(s);
  }
  /* wrong length, missing file */
  char j[4096], msg[4096];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [8, 8]},"
           " \"render\": {\"slab_spacing\": 0.1, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
           " \"materials\": {\"v\": {\"extinction\": 2, \"detail\": {\"function\": \"grid\", \"file\": \"%s\", \"size\": [3, 2, 2]}}},"
           " \"objects\": [{\"shape\": \"box\", \"center\": [0, 0, 0], \"size\": [1, 1, 1], \"material\": \"v\"}]}",
           "test_render_detail_grid.raw");
  ics_scene *bad;
  ics_status st = ics_scene_create_json(&bad, j, "g", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_PARSE && strstr(msg, "materials.v.detail.file:") && strstr(msg, "too short"),
        "short grid file: %s", msg);
  remove(path);
  st = ics_scene_create_json(&bad, j, "g", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_IO && strstr(msg, "cannot open"), "missing grid file: %s", msg);
}

static void test_transfer(void) {
  ics_scene *s = volume_scene("{\"function\": \"perlin\"}",
                              "[[0, 1, 0, 0, 0], [0.5, 0, 1, 0, 2], [1, 0, 0, 1, 1]]", NULL);
  if (!s) return;
  const ics_material *m = ics_scene_material(s, 0);
  double rgb[3], sc;
  ics_material_transfer(m, 0.25, rgb, &sc);
  CHECK(fabs(rgb[0] - 0.5) < 1e-15 && fabs(rgb[1] - 0.5) < 1e-15 && fabs(sc - 1) < 1e-15,
        "transfer at 0.25: (%g %g %g) %g", rgb[0], rgb[1], rgb[2], sc);
  ics_material_transfer(m, -3, rgb, &sc);
  CHECK(rgb[0] == 1 && sc == 0, "transfer clamps below");
  ics_material_transfer(m, 7, rgb, &sc);
  CHECK(rgb[2] == 1 && sc == 1, "transfer clamps above");
  /* preintegration against a midpoint rule with 1e5 steps, across nodes and the clamped ends */
  const double ramps[4][2] = {{0.1, 0.9}, {0.8, -0.4}, {0.3, 0.31}, {-1, 2}};
  double worst = 0;
  for (int r = 0; r < 4; r++) {
    double vf = ramps[r][0], vb = ramps[r][1], S = 0, CS[3] = {0, 0, 0};
    const int n = 100000;
    for (int i = 0; i < n; i++) {
      double v = vf + (vb - vf) * (i + 0.5) / n, c[3], x;
      ics_material_transfer(m, v, c, &x);
      S += x / n;
      for (int k = 0; k < 3; k++) CS[k] += c[k] * x / n;
    }
    double prgb[3], ps;
    ics_material_preintegrate(m, vf, vb, prgb, &ps);
    worst = fmax(worst, fabs(ps - S));
    for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(prgb[k] - CS[k] / S));
  }
  CHECK(worst < 1e-8, "preintegration vs midpoint quadrature: %g", worst);
  printf("transfer function: nodes interpolated, ends clamped; preintegration = quadrature to %.1g\n",
         worst);
  ics_scene_destroy(s);
}

static void test_batch(void) {
  static const char *const details[] = {
      "{\"function\": \"perlin\", \"seed\": 5, \"frequency\": 1.7}",
      "{\"function\": \"fbm\", \"octaves\": 6, \"gain\": 0.6, \"lacunarity\": 2.1, \"time\": 0.7, \"scale\": 1.3, \"bias\": 0.2}",
      "{\"function\": \"ridged\", \"octaves\": 5, \"gain\": 3, \"offset\": 1.1, \"frequency\": 2.3}",
      "{\"function\": \"ridged\", \"octaves\": 4, \"gain\": 0.2, \"offset\": 0.4}"};
  enum { N = 1003 };
  static double x[N], y[N], z[N], want[N], got[N];
  for (int i = 0; i < N; i++) {
    /* beyond 2^51 (the vector paths' fast floor stops there) every 13th point */
    double far = i % 13 == 0 ? 3e15 : i % 7 == 0 ? 1e6 : i % 5 == 0 ? 300 : 4;
    x[i] = far * (2 * test_rng_unit() - 1), y[i] = far * (2 * test_rng_unit() - 1);
    z[i] = far * (2 * test_rng_unit() - 1);
    if (i % 11 == 0) x[i] = floor(x[i]), y[i] = floor(y[i]), z[i] = -3; /* on the lattice */
  }
  int paths = 0;
  for (size_t d = 0; d < sizeof details / sizeof *details; d++) {
    ics_scene *s = volume_scene(details[d], NULL, NULL);
    ics_detail_eval e;
    prepare(&e, s);
    for (int i = 0; i < N; i++) want[i] = ics_detail_value(&e, (const double[3]){x[i], y[i], z[i]});
    for (int p = 0; p < ICS_SIMD_PATHS_; p++) {
      if (!ics_simd_has((ics_simd_path)p)) continue;
      for (int n = N - 8; n <= N; n++) {
        memset(got, 0, sizeof got);
        ics_detail_batch(&e, x, y, z, n, got, (ics_simd_path)p);
        int bad = 0;
        for (int i = 0; i < n; i++) bad += memcmp(&got[i], &want[i], sizeof got[i]) != 0;
        CHECK(bad == 0, "detail %zu, %s, %d points: %d values differ from ics_detail_value", d,
              ics_simd_name((ics_simd_path)p), n, bad);
      }
      paths += d == 0;
    }
    ics_scene_destroy(s);
  }
  printf("detail batches: noise, fBm, ridged on %d path(s), %d points, bit for bit\n", paths, N);
}

int main(void) {
  const char *dir = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
  test_noise();
  test_grid(dir);
  test_transfer();
  test_batch();
  return test_summary("test_render_detail");
}
