/* test_render_bias.c — the surface bias against acne (docs/renderer.md "Surface bias") at every
 * resolution: an open plane tilted 20 degrees from the view (as the default scene's wall),
 * lit from the viewer's side by a broad light (per-slab kernel 6.5 px^2 at 320 x 240, 26 px^2 at
 * 640 x 480, its taps 3.6 and 7.2 px out) has no occluder, so its exact visibility is 1 and any
 * stripes are acne: the surface shadowing its own neighbours within one slab's kernel. Measured
 * by the mean |second difference| of the row means over the plane's interior (row means: the
 * per-pixel noise of the random tap rotations averages out; stripes, rows of one slab, do not).
 * With a bias of 3 pixels' depth only (before it covered the kernel's reach) this measured 0,
 * 0.0125 and 0.095 at 160 x 120, 320 x 240 and 640 x 480 (the plane's mean 1.000, 0.997, 0.925);
 * now 0 at all three (mean 1.000). Limit 0.002. (A plane tilted 60 degrees, about one slab per
 * pixel row, still shows a moire of rows against slabs with either bias: docs/renderer.md.) */
#include <math.h>

#include "render_util.h"
#include "testutil.h"

static const char *fmt =
    "{\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"up\": [0, 1, 0],"
    " \"height\": 2.0, \"resolution\": [%d, %d]},"
    " \"render\": {\"slab_spacing\": 0.015, \"d1\": 1},"
    " \"lights\": [{\"mean\": [0.35, 0.2], \"cov\": [[0.03, 0], [0, 0.03]]}],"
    " \"materials\": {\"white\": {}},"
    " \"objects\": [{\"shape\": \"rect\", \"center\": [0, 0, 0], \"normal\": [0, 0.342020143326, 0.939692620786],"
    " \"size\": [6, 6], \"material\": \"white\"}]}";

/* the mean |second difference| of the row means over the plane's interior (row means: the
 * per-pixel noise of the random tap rotations averages out; stripes, whole rows of one slab, do
 * not), and the mean value there in *mean */
static double roughness(int W, int H, double *mean) {
  char json[2048];
  snprintf(json, sizeof json, fmt, W, H);
  ics_scene *s = scene_from_json(json);
  render_result r = render_scene_aovs(s, NULL, 0, 0);
  int i0 = W / 8, i1 = W - W / 8, j0 = H / 8, j1 = H - H / 8;
  double *m = calloc((size_t)H, sizeof *m), sum = 0, all = 0;
  for (int j = j0; j < j1; j++) {
    for (int i = i0; i < i1; i++) m[j] += r.img->data[((size_t)j * W + i) * 4];
    m[j] /= i1 - i0;
    all += m[j];
  }
  for (int j = j0 + 1; j < j1 - 1; j++) sum += fabs(m[j - 1] - 2 * m[j] + m[j + 1]);
  *mean = all / (j1 - j0);
  free(m);
  ics_image_destroy(r.img);
  ics_scene_destroy(s);
  return sum / (j1 - j0 - 2);
}

int main(void) {
  const int res[3][2] = {{160, 120}, {320, 240}, {640, 480}};
  for (int k = 0; k < 3; k++) {
    double mean, rgh = roughness(res[k][0], res[k][1], &mean);
    printf("%d x %d: mean %.4f, mean |second difference| of the row means %.5f (limit 0.002)\n",
           res[k][0], res[k][1], mean, rgh);
    CHECK(rgh <= 0.002, "%d x %d: acne, mean |second difference| of the row means %.5f", res[k][0],
          res[k][1], rgh);
  }
  return test_summary("test_render_bias");
}
