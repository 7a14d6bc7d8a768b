/* test_render_aov.c — the renderer's AOVs (icshadow/renderer.h ics_renderer_render_aovs) against
 * what the scene fixes independently of the renderer: the view depth of each pixel's first
 * surface is the geometry's (orthographic camera at z = 2: a disk at z = 0 has Z = 2, a receiver
 * at z = -1 has Z = 3, camera rays that pass through a volume box still report the receiver
 * behind it), the light reaching a disk with nothing above it is the unshadowed 1, pixels that see
 * no surface hold 0; and the image is the AOVs' combination by Patel's model: on a white opaque
 * receiver seen directly, RGB = sum_l colour_l weight_l V_l (per channel with coloured
 * transport), to float rounding. AOVs are bit-identical for 1 and 2 threads; unknown AOV bits
 * are refused. */
#include <math.h>
#include <string.h>

#include "render_util.h"
#include "testutil.h"

/* the contract example (grey: one buffer channel) at 64 x 64 */
static const char *disk_json =
    "{\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 2], \"target\": [0, 0, 0],"
    " \"up\": [0, 1, 0], \"height\": 3.0, \"resolution\": [64, 64]},"
    " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1.0, \"kernel\": \"ellipse\", \"samples\": 2, \"seed\": 7},"
    " \"lights\": [{\"mean\": [0.3, -0.1], \"cov\": [[0.02, 0.005], [0.005, 0.01]]}],"
    " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {\"color\": [1, 1, 1]}},"
    " \"objects\": [{\"shape\": \"disk\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"radius\": 0.5, \"material\": \"black\"},"
    "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 3], \"material\": \"white\"}]}";

/* two coloured lights, a tinted translucent disk (coloured transport: three buffer channels), a
 * box of grey smoke, a receiver smaller than the view */
static const char *colour_json =
    "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 3.0, \"resolution\": [64, 64]},"
    " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1.0, \"seed\": 3},"
    " \"lights\": [{\"mean\": [0.2, 0], \"cov\": [[0.01, 0], [0, 0.01]], \"color\": [1, 0.2, 0.2], \"weight\": 0.7},"
    "  {\"mean\": [-0.1, 0.2], \"cov\": [[0.02, 0], [0, 0.005]], \"color\": [0.2, 0.2, 1], \"weight\": 0.5}],"
    " \"materials\": {\"tint\": {\"color\": [0.3, 0.3, 0.3], \"opacity\": 0.6, \"transport\": [1, 0.5, 0]},"
    "  \"smoke\": {\"extinction\": 3}, \"white\": {}},"
    " \"objects\": [{\"shape\": \"disk\", \"center\": [0.5, 0.5, 0], \"normal\": [0, 0, 1], \"radius\": 0.4, \"material\": \"tint\"},"
    "  {\"shape\": \"box\", \"center\": [-0.5, -0.5, -0.3], \"size\": [0.6, 0.6, 0.6], \"material\": \"smoke\"},"
    "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [2, 2], \"material\": \"white\"}]}";

static double px_x(int i, int W) { return ((i + 0.5) / W - 0.5) * 3; }
static double px_y(int j, int H) { return (0.5 - (j + 0.5) / H) * 3; }

static void test_disk(void) {
  ics_scene *s = scene_from_json(disk_json);
  render_result r = render_scene_aovs(s, NULL, 0, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH);
  CHECK(r.aov && r.aov->count == 2 && !strcmp(r.aov->names[0], "light0.V") &&
            !strcmp(r.aov->names[1], "Z"), "grey scene: channels light0.V, Z");
  int W = r.img->width, H = r.img->height, nrecv = 0, ndisk = 0;
  double worst_z = 0, worst_lit = 0, worst_img = 0;
  for (int j = 0; j < H; j++)
    for (int i = 0; i < W; i++) {
      double x = px_x(i, W), y = px_y(j, H), rr = sqrt(x * x + y * y);
      const float *a = r.aov->data + ((size_t)j * W + i) * 2, *c = r.img->data + ((size_t)j * W + i) * 4;
      if (rr < 0.45) { /* the disk */
        ndisk++;
        worst_z = fmax(worst_z, fabs(a[1] - 2));
        worst_lit = fmax(worst_lit, fabs(a[0] - 1));
      } else if (rr > 0.55) { /* the white receiver: the image is V itself */
        nrecv++;
        worst_z = fmax(worst_z, fabs(a[1] - 3));
        worst_img = fmax(worst_img, fabs(c[0] - a[0]));
      }
    }
  printf("grey: %d disk and %d receiver pixels: |Z - exact| <= %.3g, disk |V - 1| <= %.3g, "
         "receiver |R - V| <= %.3g\n", ndisk, nrecv, worst_z, worst_lit, worst_img);
  CHECK(worst_z < 1e-5, "first-surface depth off by %g", worst_z);
  CHECK(worst_lit < 1e-5, "an unshadowed disk's visibility off 1 by %g", worst_lit);
  CHECK(worst_img == 0, "white receiver: R differs from the visibility AOV by %g", worst_img);
  /* the shadow is in the AOV: some receiver pixels well inside the penumbra */
  int shadowed = 0;
  for (int j = 0; j < H; j++)
    for (int i = 0; i < W; i++) {
      double x = px_x(i, W), y = px_y(j, H), rr = sqrt(x * x + y * y);
      if (rr > 0.55 && r.aov->data[((size_t)j * W + i) * 2] < 0.5) shadowed++;
    }
  CHECK(shadowed > 20, "only %d receiver pixels in shadow in the AOV", shadowed);
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  ics_scene_destroy(s);
}

static void test_colour(void) {
  ics_scene *s = scene_from_json(colour_json);
  render_result r = render_scene_aovs(s, NULL, 1, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH);
  render_result r2 = render_scene_aovs(s, NULL, 2, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH);
  static const char *const want[7] = {"light0.R", "light0.G", "light0.B", "light1.R",
                                      "light1.G", "light1.B", "Z"};
  int names_ok = r.aov && r.aov->count == 7;
  for (int c = 0; names_ok && c < 7; c++) names_ok = !strcmp(r.aov->names[c], want[c]);
  CHECK(names_ok, "coloured scene: channels light0.R .. light1.B, Z");
  if (!names_ok) return;
  int W = r.img->width, H = r.img->height;
  CHECK(!memcmp(r.aov->data, r2.aov->data, sizeof(float) * W * H * 7), "AOVs: 1 and 2 threads differ");
  int nnone = 0, nrecv = 0, nvol = 0, ndisk = 0, bad_none = 0;
  double worst_z = 0, worst_rel = 0, worst_disk = 0;
  const ics_light *L0 = ics_scene_light(s, 0), *L1 = ics_scene_light(s, 1);
  for (int j = 0; j < H; j++)
    for (int i = 0; i < W; i++) {
      double x = px_x(i, W), y = px_y(j, H);
      const float *a = r.aov->data + ((size_t)j * W + i) * 7, *c = r.img->data + ((size_t)j * W + i) * 4;
      double dd = hypot(x - 0.5, y - 0.5);
      int in_box = fabs(x + 0.5) < 0.3 && fabs(y + 0.5) < 0.3;
      if (fabs(x) > 1.05 || fabs(y) > 1.05) { /* nothing there */
        nnone++;
        for (int k = 0; k < 7; k++) bad_none += a[k] != 0;
      } else if (dd < 0.36) { /* the tinted disk: nothing above it */
        ndisk++;
        worst_z = fmax(worst_z, fabs(a[6] - 2));
        for (int k = 0; k < 6; k++) worst_disk = fmax(worst_disk, fabs(a[k] - 1));
      } else if (fabs(x) < 0.95 && fabs(y) < 0.95 && dd > 0.44 &&
                 (fabs(x + 0.5) > 0.33 || fabs(y + 0.5) > 0.33)) { /* the receiver, seen directly */
        nrecv++;
        worst_z = fmax(worst_z, fabs(a[6] - 3));
        for (int ch = 0; ch < 3; ch++) {
          double v = L0->color[ch] * L0->weight * a[ch] + L1->color[ch] * L1->weight * a[3 + ch];
          worst_rel = fmax(worst_rel, fabs(c[ch] - v) / fmax(v, 1e-3));
        }
      } else if (in_box && fabs(x + 0.5) < 0.27 && fabs(y + 0.5) < 0.27) { /* through the smoke */
        nvol++;
        worst_z = fmax(worst_z, fabs(a[6] - 3));
      }
    }
  printf("colour: %d empty, %d disk, %d receiver, %d through-smoke pixels: |Z - exact| <= %.3g, "
         "disk |V - 1| <= %.3g, receiver |RGB - sum_l c_l w_l V_l| / value <= %.3g\n",
         nnone, ndisk, nrecv, nvol, worst_z, worst_disk, worst_rel);
  CHECK(nnone > 0 && ndisk > 0 && nrecv > 0 && nvol > 0, "every pixel class present");
  CHECK(bad_none == 0, "%d AOV values not 0 where no surface is", bad_none);
  CHECK(worst_z < 1e-5, "first-surface depth off by %g (volumes must be passed through)", worst_z);
  CHECK(worst_disk < 1e-5, "an unshadowed disk's visibility off 1 by %g", worst_disk);
  CHECK(worst_rel < 1e-6, "the image is not the AOVs' combination: relative %g", worst_rel);
  /* the tinted disk's coloured transport shows in the receiver's channels: somewhere light 0's
   * blue visibility is well below its red (T = (1, 0.5, 0)) */
  double split = 0;
  for (size_t p = 0; p < (size_t)W * H; p++) split = fmax(split, r.aov->data[p * 7] - r.aov->data[p * 7 + 2]);
  CHECK(split > 0.3, "coloured transport not in the visibility AOV (max R - B %g)", split);
  ics_image_destroy(r.img), ics_image_destroy(r2.img);
  ics_exr_channels_destroy(r.aov), ics_exr_channels_destroy(r2.aov);
  ics_scene_destroy(s);
}

static void test_refusals(void) {
  ics_scene *s = scene_from_json(disk_json);
  char msg[512];
  ics_plan *p;
  CHECK(ics_plan_create(&p, s, NULL, msg, sizeof msg) == ICS_OK, "plan: %s", msg);
  ics_render_opts ro = {.backend = "cpu"};
  ics_renderer *rr;
  CHECK(ics_renderer_create(&rr, &ro, msg, sizeof msg) == ICS_OK, "renderer: %s", msg);
  ics_image *img = (ics_image *)&msg;
  ics_exr_channels *aov = (ics_exr_channels *)&msg;
  CHECK(ics_renderer_render_aovs(rr, p, 8u, &img, &aov, NULL, msg, sizeof msg) == ICS_ERR_INVALID_ARG &&
            img == NULL && aov == NULL && strstr(msg, "unknown bits"), "unknown AOV bit refused: %s", msg);
  img = (ics_image *)&msg;
  CHECK(ics_renderer_render_aovs(rr, p, ICS_AOV_DEPTH, &img, NULL, NULL, msg, sizeof msg) ==
            ICS_ERR_INVALID_ARG && img == NULL, "AOVs with nowhere to put them refused");
  ics_renderer_destroy(rr);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

int main(void) {
  test_disk();
  test_colour();
  test_refusals();
  return test_summary("test_render_aov");
}
