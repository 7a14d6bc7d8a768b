/* test_render_propagate.c — the CPU slab step (gpu/src/propagate*.c) against the core engine
 * (ics_conv2d_step, double sums per pixel, clamp-to-edge): one tap set with fractional offsets
 * (discretised into a stencil), and per-pixel tables, where each pixel's tap set is chosen by
 * ics_slab_entry and the reference applies that set to that pixel alone. Both the AVX-512 and the
 * portable loops are compared (the AVX-512 ones only where the processor has them). Agreement to
 * 4 float ulps of the values (the engine sums in double and rounds once). Also: the vectorised
 * Philox gives exactly ics_slab_entry's words, and the slab kernels' tables have the target
 * covariance averaged over their entries (the trapezoid rule on the ellipse, exact rotations for
 * Poisson). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "propagate.h"
#include "propagate_simd.h"
#include "render_util.h"
#include "slab_kernel.h"
#include "testutil.h"

enum { W = 77, H = 45 };

static void fill(float *a) {
  for (int i = 0; i < W * H; i++) a[i] = (float)test_rng_unit();
}

/* reference for pixel (x, y): the engine's single-step on the tap set, read at that pixel */
static double ref_pixel(const float *src, const ics_tap2d *t, int n, int x, int y, float *tmp) {
  ics_conv2d_step(src, tmp, W, H, t, n, NULL);
  return tmp[(size_t)y * W + x];
}

static void test_stencil(int use_simd) {
  float *src = malloc(sizeof(float) * W * H), *dst = malloc(sizeof(float) * W * H),
        *ref = malloc(sizeof(float) * W * H);
  fill(src);
  ics_tap2d taps[4] = {{0.3, -1.2, 0.4}, {-2.6, 0.7, 0.25}, {1, 2, 0.25}, {4.5, -3.25, 0.1}};
  ics_prop_taps pt = {0};
  CHECK(ics_prop_prepare(&pt, taps, 1, 4, 4, 1, 0, 0, W) == 0 && pt.stencil, "prepare stencil");
  uint32_t scratch[W];
  if (use_simd)
    ics_prop_rows_avx512(&pt, src, dst, W, H, 1, 0, H, scratch);
  else
    ics_prop_rows(&pt, src, dst, W, H, 1, 0, H, scratch);
  ics_conv2d_step(src, ref, W, H, taps, 4, NULL);
  double worst = 0;
  for (int i = 0; i < W * H; i++) worst = fmax(worst, fabs(dst[i] - ref[i]) / 0x1p-24);
  CHECK(worst <= 4, "%s stencil vs engine: %.2f ulps of 1", use_simd ? "AVX-512" : "portable", worst);
  printf("stencil (%s) vs ics_conv2d_step: max %.2f float ulps of 1\n",
         use_simd ? "AVX-512" : "portable", worst);
  ics_prop_release(&pt);
  free(src), free(dst), free(ref);
}

static void test_table(int use_simd) {
  float *src = malloc(sizeof(float) * 3 * W * H), *dst = malloc(sizeof(float) * 3 * W * H),
        *tmp = malloc(sizeof(float) * W * H);
  for (int c = 0; c < 3; c++) fill(src + (size_t)c * W * H);
  /* a table of M entries of 2 taps (an ellipse-like antipodal pair around a mean) */
  const int M = ICS_SLAB_TABLE_M;
  ics_tap2d *t = malloc(sizeof *t * 2 * M);
  for (int e = 0; e < M; e++) {
    double a = 2 * ICS_PI * e / M;
    t[2 * e] = (ics_tap2d){-0.37 + 1.7 * cos(a), 0.21 + 0.9 * sin(a), 0.5};
    t[2 * e + 1] = (ics_tap2d){-0.37 - 1.7 * cos(a), 0.21 - 0.9 * sin(a), 0.5};
  }
  ics_prop_taps pt = {0};
  CHECK(ics_prop_prepare(&pt, t, M, 2, 2, 1, 0, 0, W) == 0 && !pt.stencil, "prepare table");
  pt.seed = 12345, pt.light = 1, pt.slab = 7;
  uint32_t scratch[W];
  if (use_simd)
    ics_prop_rows_avx512(&pt, src, dst, W, H, 3, 0, H, scratch);
  else
    ics_prop_rows(&pt, src, dst, W, H, 3, 0, H, scratch);
  double worst = 0;
  for (int y = 0; y < H; y += 4)
    for (int x = 0; x < W; x++) {
      int e = (int)ics_slab_entry(12345, 1, 7, (uint32_t)(y * W + x));
      for (int c = 0; c < 3; c++) {
        double r = ref_pixel(src + (size_t)c * W * H, t + 2 * e, 2, x, y, tmp);
        worst = fmax(worst, fabs(dst[(size_t)c * W * H + y * W + x] - r) / 0x1p-24);
      }
    }
  CHECK(worst <= 4, "%s table vs engine per pixel: %.2f ulps of 1", use_simd ? "AVX-512" : "portable",
        worst);
  printf("table (%s, 3 channels) vs ics_conv2d_step per pixel: max %.2f float ulps of 1\n",
         use_simd ? "AVX-512" : "portable", worst);
  ics_prop_release(&pt);
  free(src), free(dst), free(tmp), free(t);
}

static void test_entries(void) {
  /* the entries of rows through both loops equal ics_slab_entry */
  ics_prop_taps pt = {0};
  pt.seed = 0xfeedface12345678ull, pt.light = 3, pt.slab = 99, pt.entries = ICS_SLAB_TABLE_M;
  uint32_t ent[W];
  int bad = 0;
  for (int y = 0; y < 9; y++) {
    ics_prop_entries_row(&pt, W, y, ent);
    for (int x = 0; x < W; x++)
      bad += ent[x] != ics_slab_entry(pt.seed, 3, 99, (uint32_t)(y * W + x)) || ent[x] >= ICS_SLAB_TABLE_M;
  }
  CHECK(bad == 0, "portable row entries differ from ics_slab_entry in %d pixels", bad);
  /* the entries are uniform over the table: chi-square over 384 bins, 384 000 draws */
  static long cnt[ICS_SLAB_TABLE_M];
  const int N = 384000;
  for (int i = 0; i < N; i++) cnt[ics_slab_entry(7, 0, 0, (uint32_t)i)]++;
  double chi = 0, expct = (double)N / ICS_SLAB_TABLE_M;
  for (int i = 0; i < ICS_SLAB_TABLE_M; i++) chi += (cnt[i] - expct) * (cnt[i] - expct) / expct;
  /* 383 degrees of freedom: mean 383, sd 27.7; 5 sd */
  CHECK(fabs(chi - 383) < 5 * 27.7, "entries not uniform: chi^2 = %.1f (383 +- 27.7)", chi);
}

/* the slab kernel's table averaged over its entries has the class covariance */
static void test_table_moments(ics_render_kernel member, int samples) {
  char json[1024];
  snprintf(json, sizeof json,
           "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [100, 100]},"
           " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1, \"kernel\": \"%s\", \"samples\": %d, \"compensate\": \"none\"},"
           " \"lights\": [{\"mean\": [0.1, 0.2], \"var\": [0.3, 0.05], \"angle_deg\": 35}],"
           " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.3, \"material\": \"m\"}]}",
           ics_render_kernel_name(member), samples);
  ics_scene *s = scene_from_json(json);
  ics_slab_kernel sk;
  char msg[256];
  double q = 0.01;
  CHECK(ics_slab_kernel_init(&sk, s, 0, q, msg, sizeof msg) == ICS_OK && sk.mode == ICS_SLAB_TABLE,
        "kernel init: %s", msg);
  ics_tap2d *t = malloc(sizeof *t * (size_t)sk.entries * (size_t)sk.cap);
  double cum[2] = {0, 0};
  int n;
  ics_slab_kernel_taps(&sk, 0, q, cum, t, &n);
  double w, m[2], c[3];
  ics_taps2d_moments(t, n, &w, m, c);
  double tr = sk.cov_px[0] + sk.cov_px[2];
  double err = fmax(fabs(c[0] - sk.cov_px[0]), fmax(fabs(c[1] - sk.cov_px[1]), fabs(c[2] - sk.cov_px[2]))) / tr;
  double merr = fmax(fabs(m[0] - sk.mean_px[0]), fabs(m[1] - sk.mean_px[1]));
  CHECK(err < 1e-12 && merr < 1e-12, "%s %d: table covariance off by %.3g of the trace, mean by %.3g",
        ics_render_kernel_name(member), samples, err, merr);
  printf("%s %d table (%d entries): covariance off by %.2g of the trace, mean by %.2g px\n",
         ics_render_kernel_name(member), samples, sk.entries, err, merr);
  free(t);
  ics_slab_kernel_release(&sk);
  ics_scene_destroy(s);
}

int main(void) {
  test_stencil(0);
  test_table(0);
  if (ics_prop_avx512_available()) {
    test_stencil(1);
    test_table(1);
  } else {
    printf("AVX-512 loops: skipped (this processor has no AVX-512)\n");
  }
  test_entries();
  test_table_moments(ICS_RK_ELLIPSE, 2);
  test_table_moments(ICS_RK_ELLIPSE, 3);
  test_table_moments(ICS_RK_POISSON, 8);
  return test_summary("test_render_propagate");
}
