/* fuzz_scene_json.c — libFuzzer harness for the scene reader (gpu/core/scene_json.c) and what a
 * scene it accepts goes through: the plan at 16 x 16 pixels (padding capped at 4) and, for an
 * orthographic camera and at most 256 slabs, a render on the cpu backend with one thread (a
 * perspective step compensates 256 classes of taps per slab whatever the image size: 13 s per
 * render under ASan, too slow to fuzz). Invariants: an accepted scene has a
 * right-handed orthonormal camera frame, at least one light, lights with finite means,
 * positive-semidefinite covariances, finite non-negative colours and weights, every object's
 * material index in range; a plan that is made has at least one slab and a positive memory
 * estimate; a render gives finite pixels with alpha in [0, 1] (up to float rounding). A refused
 * scene (or plan, or render) must come with a message. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_require.h"
#include "icshadow/render.h"

static double dot(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size > 16384) return 0;
  char *json = malloc(size + 1);
  if (!json) return 0;
  memcpy(json, data, size);
  json[size] = 0;
  char msg[4096] = "";
  ics_scene *s = NULL;
  ics_status st = ics_scene_create_json(&s, json, "fuzz", NULL, msg, sizeof msg);
  free(json);
  if (st != ICS_OK) {
    REQUIRE(s == NULL && msg[0]);
    return 0;
  }
  const ics_camera *c = ics_scene_camera(s);
  REQUIRE(fabs(dot(c->r, c->r) - 1) < 1e-9 && fabs(dot(c->u, c->u) - 1) < 1e-9 &&
          fabs(dot(c->f, c->f) - 1) < 1e-9);
  REQUIRE(fabs(dot(c->r, c->u)) < 1e-9 && fabs(dot(c->r, c->f)) < 1e-9 && fabs(dot(c->u, c->f)) < 1e-9);
  int nl = ics_scene_light_count(s);
  REQUIRE(nl >= 1);
  for (int k = 0; k < nl; k++) require_light(ics_scene_light(s, k));
  int nm = ics_scene_material_count(s);
  for (int i = 0; i < ics_scene_object_count(s); i++) {
    int m = ics_scene_object(s, i)->material;
    REQUIRE(m >= 0 && m < nm);
  }
  /* small and quick: 16 x 16 pixels, padding capped at 4 (a second per input would leave the
   * fuzzer a few hundred executions per minute) */
  ics_render_settings rs = *ics_scene_settings(s);
  rs.max_pad = 4;
  ics_plan_opts po = {.settings = &rs, .width = 16, .height = 16, .threads = 1};
  ics_plan *p = NULL;
  st = ics_plan_create(&p, s, &po, msg, sizeof msg);
  if (st != ICS_OK) {
    REQUIRE(p == NULL && msg[0]);
  } else {
    REQUIRE(ics_plan_slabs(p) >= 1 && ics_plan_memory_bytes(p) > 0);
    if (ics_plan_slabs(p) <= 256 && c->projection == ICS_PROJ_ORTHOGRAPHIC) {
      ics_render_opts ro = {.backend = "cpu", .threads = 1};
      ics_renderer *r = NULL;
      ics_image *img = NULL;
      st = ics_renderer_create(&r, &ro, msg, sizeof msg);
      if (st == ICS_OK) st = ics_renderer_render(r, p, &img, NULL, msg, sizeof msg);
      if (st == ICS_OK) {
        for (size_t i = 0; i < (size_t)img->width * img->height; i++) {
          const float *px = img->data + 4 * i;
          for (int ch = 0; ch < 4; ch++) REQUIRE(isfinite(px[ch]));
          REQUIRE(px[3] >= -1e-5f && px[3] <= 1 + 1e-5f);
        }
      } else {
        REQUIRE(img == NULL && msg[0]);
      }
      ics_image_destroy(img);
      ics_renderer_destroy(r);
    }
    ics_plan_destroy(p);
  }
  ics_scene_destroy(s);
  return 0;
}
