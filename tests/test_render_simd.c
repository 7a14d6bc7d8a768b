/* test_render_simd.c — every vector path of the cpu backend this processor has (ICS_SIMD: sse2,
 * avx2, avx512, neon) against the portable loops (scalar), on the default scene and its kernel
 * variants (4 and 8 rotations, 384 per-pixel rotations, runs of 16, Gauss stencil, Poisson 16)
 * at 96 x 72, and a perspective camera (the magnification classes): the whole image within 4e-6 of the scalar path's (measured on x86-64: at most
 * 2.5e-6 for sse2, whose stencils add four partial sums where the portable loops add in one
 * chain, and 7.8e-7 for avx2 and avx512, whose multiply-adds are fused; ~190 slabs), and the paths with fused multiply-add (avx2, avx512, neon) equal to each other bit for
 * bit, as they evaluate the same formula. A path the machine lacks is reported and skipped; the
 * result of each path must not depend on the thread count (1 against 2 threads). */
#define _POSIX_C_SOURCE 200809L /* setenv */
#include <stdlib.h>
#include <string.h>

#include "render_util.h"
#include "simd_path.h"
#include "testutil.h"

#define TOLERANCE 4e-6

static double diff_max(const ics_image *a, const ics_image *b) {
  double m = 0;
  for (size_t i = 0; i < 4 * (size_t)a->width * a->height; i++)
    m = fmax(m, fabs(a->data[i] - b->data[i]));
  return m;
}

static ics_image *render_path(ics_simd_path p, const ics_scene *s, const ics_render_settings *rs,
                              int threads) {
  setenv("ICS_SIMD", ics_simd_name(p), 1);
  return render_scene(s, rs, threads).img;
}

static void check_variant(const char *name, const ics_scene *s, const ics_render_settings *rs) {
  ics_image *scalar = render_path(ICS_SIMD_SCALAR, s, rs, 2), *fused = NULL;
  const char *fused_name = NULL;
  for (int p = ICS_SIMD_SCALAR + 1; p < ICS_SIMD_PATHS_; p++) {
    if (!ics_simd_has((ics_simd_path)p)) continue;
    ics_image *img = render_path((ics_simd_path)p, s, rs, 2);
    ics_image *one = render_path((ics_simd_path)p, s, rs, 1);
    double d = diff_max(img, scalar);
    CHECK(d <= TOLERANCE, "%s, %s: %.3g from the scalar path (tolerance %g)", name,
          ics_simd_name((ics_simd_path)p), d, TOLERANCE);
    CHECK(diff_max(img, one) == 0, "%s, %s: 1 and 2 threads differ", name,
          ics_simd_name((ics_simd_path)p));
    printf("%s, %s: max %.3g from scalar\n", name, ics_simd_name((ics_simd_path)p), d);
    ics_image_destroy(one);
    if (p == ICS_SIMD_SSE2) { /* no FMA: its own last bits */
      ics_image_destroy(img);
    } else if (!fused) {
      fused = img, fused_name = ics_simd_name((ics_simd_path)p);
    } else {
      CHECK(diff_max(img, fused) == 0, "%s: %s and %s differ (both fuse a * b + c)", name,
            ics_simd_name((ics_simd_path)p), fused_name);
      ics_image_destroy(img);
    }
  }
  ics_image_destroy(fused);
  ics_image_destroy(scalar);
}

int main(void) {
  for (int p = ICS_SIMD_SCALAR + 1; p < ICS_SIMD_PATHS_; p++)
    if (!ics_simd_has((ics_simd_path)p))
      printf("%s: skipped (not built for this architecture, or this processor lacks it)\n",
             ics_simd_name((ics_simd_path)p));
  ics_scene *s = default_scene_96x72();
  ics_render_settings rs = *ics_scene_settings(s);
  check_variant("default scene", s, &rs);
  ics_render_settings v = rs;
  v.pixel_rotations = 4;
  check_variant("4 rotations", s, &v);
  v = rs, v.pixel_rotations = 8;
  check_variant("8 rotations", s, &v);
  v = rs, v.pixel_rotations = 384;
  check_variant("384 per-pixel rotations", s, &v);
  v = rs, v.rotation_run = 16;
  check_variant("runs of 16", s, &v);
  v = rs, v.kernel = ICS_RK_GAUSS, v.samples = 19;
  check_variant("gauss 19 (stencil)", s, &v);
  v = rs, v.kernel = ICS_RK_POISSON, v.samples = 16;
  check_variant("poisson 16", s, &v);
  ics_scene_destroy(s);
  /* a perspective camera: the magnification classes' vector loops */
  s = scene_from_json(
      "{\"camera\": {\"projection\": \"perspective\", \"eye\": [0.3, 0.4, 5], \"target\": [0, 0, 0],"
      " \"fov_deg\": 33.4, \"resolution\": [80, 64]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1},"
      " \"lights\": [{\"mean\": [0.3, -0.1], \"cov\": [[0.02, 0.005], [0.005, 0.01]]}],"
      " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {}},"
      " \"objects\": [{\"shape\": \"disk\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"radius\": 0.5, \"material\": \"black\"},"
      "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [8, 8], \"material\": \"white\"}]}");
  rs = *ics_scene_settings(s);
  check_variant("perspective", s, &rs);
  ics_scene_destroy(s);
  unsetenv("ICS_SIMD");
  return test_summary("test_render_simd");
}
