/* test_render_piece_batch.c — the lone volume pieces shaded a row at a time on the widest vector
 * path this processor has (gpu/backends/cpu/piece_vec.h) against the same path shading them one
 * by one (ICS_PIECE_BATCH=0: backend_cpu.c's single_volume_piece, with libm's exp, expm1 and
 * log): the default scene (coloured transport, two lights) and a scene of grey transport with
 * four lights and an opaque sphere, orthographic and perspective, with and without
 * preintegration, under patel, solid, surface and blocker, at sizes whose rows end in partial
 * vectors. The batch repeats the per-pixel arithmetic in its order and differs only in the
 * vector exp, expm1 and log (within 2 ulps of libm's, test_render_vec_math), which change a
 * float only where a last-bit difference crosses its rounding: each image and AOV within 1e-6
 * of the other, at most 0.1 % of its floats different (an operation out of order changes most
 * of a volume's pixels; measured: none different). Skipped on a processor with no vector path. */
#define _POSIX_C_SOURCE 200809L /* setenv */
#include <stdlib.h>
#include <string.h>

#include "render_util.h"
#include "simd_path.h"
#include "testutil.h"

#define MAX_DIFF 1e-6
#define MAX_SHARE 1e-3

static const char *const grey_json =
    "{\"camera\": {\"projection\": \"%s\", \"eye\": [0, 0.8, 3], \"target\": [0, -0.1, 0],"
    " %s, \"resolution\": [101, 67]},"
    " \"render\": {\"slab_spacing\": 0.03, \"d1\": 1, \"seed\": 4},"
    " \"lights\": [{\"mean\": [-0.5, 0.3], \"var\": [0.01, 0.005]},"
    "  {\"mean\": [0.3, 0.2], \"var\": [0.03, 0.02], \"color\": [0.6, 0.7, 1], \"weight\": 0.4},"
    "  {\"mean\": [0.1, -0.4], \"var\": [0.004, 0.004], \"weight\": 0.3},"
    "  {\"mean\": [-0.2, -0.1], \"var\": [0.05, 0.01], \"angle_deg\": 40, \"weight\": 0.2}],"
    " \"materials\": {\"floor\": {\"color\": [0.85, 0.85, 0.8]}, \"red\": {\"color\": [0.8, 0.2, 0.1]},"
    "  \"smoke\": {\"color\": [0.9, 0.9, 0.95], \"extinction\": 10, \"transport\": [0.3, 0.3, 0.3],"
    "   \"detail\": {\"function\": \"fbm\", \"frequency\": 3, \"octaves\": 3, \"scale\": 1.5, \"bias\": 0.2, \"seed\": 2}},"
    "  \"haze\": {\"color\": [0.7, 0.8, 0.9], \"extinction\": 3, \"transport\": [0.5, 0.5, 0.5]}},"
    " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 3], \"material\": \"floor\"},"
    "  {\"shape\": \"sphere\", \"center\": [-0.3, -0.1, 0], \"radius\": 0.4, \"material\": \"smoke\"},"
    "  {\"shape\": \"box\", \"center\": [0.45, -0.2, 0.1], \"size\": [0.5, 0.5, 0.5], \"material\": \"haze\"},"
    "  {\"shape\": \"sphere\", \"center\": [0.5, 0.35, -0.3], \"radius\": 0.18, \"material\": \"red\"}]}";

static render_result render_batch(const ics_scene *s, const ics_render_settings *rs, int batch) {
  setenv("ICS_PIECE_BATCH", batch ? "1" : "0", 1);
  return render_scene_sized_on("cpu", s, rs, 2, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH, 0, 0);
}

/* the largest difference of n floats, and how many differ */
static double compare(const float *a, const float *b, size_t n, size_t *differ) {
  double m = 0;
  for (size_t i = 0; i < n; i++)
    if (memcmp(&a[i], &b[i], sizeof *a)) (*differ)++, m = fmax(m, fabs((double)a[i] - b[i]));
  return m;
}

static void check_case(const char *name, const ics_scene *s, const ics_render_settings *base,
                       ics_render_model model, int preintegrate) {
  ics_render_settings rs = *base;
  rs.model = model, rs.preintegrate = preintegrate;
  render_result one = render_batch(s, &rs, 0), row = render_batch(s, &rs, 1);
  size_t n = 4 * (size_t)one.img->width * one.img->height, differ = 0, total = n;
  double m = compare(one.img->data, row.img->data, n, &differ);
  size_t k = (size_t)one.aov->count * one.img->width * one.img->height;
  m = fmax(m, compare(one.aov->data, row.aov->data, k, &differ));
  total += k;
  const char *mn = ics_render_model_name(model);
  CHECK(m <= MAX_DIFF && differ <= MAX_SHARE * total,
        "%s, %s%s: the batch %.3g from one by one, %zu of %zu floats different", name, mn,
        preintegrate ? ", preintegrated" : "", m, differ, total);
  printf("%s, %s%s: %zu of %zu floats different, max %.3g\n", name, mn,
         preintegrate ? ", preintegrated" : "", differ, total, m);
  ics_image_destroy(one.img), ics_image_destroy(row.img);
  ics_exr_channels_destroy(one.aov), ics_exr_channels_destroy(row.aov);
}

static void check_scene(const char *name, const ics_scene *s) {
  static const ics_render_model models[] = {ICS_MODEL_PATEL, ICS_MODEL_SOLID, ICS_MODEL_SURFACE,
                                            ICS_MODEL_BLOCKER};
  for (int i = 0; i < 4; i++) check_case(name, s, ics_scene_settings(s), models[i], 0);
  check_case(name, s, ics_scene_settings(s), ICS_MODEL_BLOCKER, 1);
}

int main(void) {
  ics_simd_path widest = ICS_SIMD_SCALAR;
  for (int p = ICS_SIMD_SCALAR + 1; p < ICS_SIMD_PATHS_; p++)
    if (ics_simd_has((ics_simd_path)p)) widest = (ics_simd_path)p;
  if (widest == ICS_SIMD_SCALAR) {
    printf("SKIPPED: no vector path on this processor (the portable path shades one by one)\n");
    return 77;
  }
  setenv("ICS_SIMD", ics_simd_name(widest), 1);
  printf("path %s\n", ics_simd_name(widest));
  ics_scene *s = default_scene_96x72();
  check_scene("default scene 96x72", s);
  ics_scene_destroy(s);
  char json[4096];
  snprintf(json, sizeof json, grey_json, "orthographic", "\"height\": 1.9");
  s = scene_from_json(json);
  check_scene("grey transport, four lights, 101x67", s);
  ics_scene_destroy(s);
  snprintf(json, sizeof json, grey_json, "perspective", "\"fov_deg\": 36");
  s = scene_from_json(json);
  check_scene("the same, perspective", s);
  ics_scene_destroy(s);
  unsetenv("ICS_PIECE_BATCH");
  unsetenv("ICS_SIMD");
  return test_summary("test_render_piece_batch");
}
