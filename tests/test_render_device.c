/* test_render_device.c — a device backend (cl: gpu/backends/cl, gl: gpu/backends/gl) renders what the cpu backend
 * renders: the embedded default scene, every scene file given on the command line (scenes/, at
 * most 128 pixels on a side), and variants that reach each path of slab.cl and slab.comp
 * (stencil, table with per-pixel and run-of-16 choices, 1 and 384
 * rotations, the perspective classes, integer and signed kernels, coloured transport, translucent
 * surfaces, volumes with and without detail, Perlin / fBm / ridged / grid detail,
 * preintegration, more overlapping volumes than the shading keeps, several lights). Per image:
 * the largest absolute difference and the RMS difference over R, G, B, A against the cpu
 * backend's image (and of the AOVs), within the tolerances of docs/backend_cl.md and
 * docs/backend_gl.md (the same float arithmetic in the same order; exp and pow in double on cl
 * and the CPU may differ in the last bits, GLSL has them in float only). Then the refusals with
 * their messages and no image: cl, a device that does not exist (ICS_CL_DEVICE); gl, a context
 * kind that does not exist (ICS_GL_CONTEXT) and light buffers over the driver's limits. Exit 77
 * (skipped) when the backend cannot run here. The gl backend renders on the context that
 * ICS_GL_CONTEXT names (the CMake tests run it once per context kind), with the layered depth
 * image that ICS_GL_LDI names (with "device", each render checks that it was built there).
 * usage: test_render_device cl|gl [SCENE.json ...] */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render_util.h"
#include "testutil.h"

#define TOL_MAX 1e-5 /* largest |device - cpu| over the pixels and channels */
#define TOL_RMS 1e-6

static const char *backend; /* argv[1] */
static char device[128];    /* the device of the last render (its stats) */

/* name, the mode light 0's kernel runs in (the plan's pass detail), scene */
static const char *const variants[][3] = {
    {"ellipse (4 rotations per pixel), 2 lights, coloured transport, translucent", "table",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 5, \"pixel_rotations\": 4},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25},"
     "  {\"mean\": [-0.3, 0.1], \"var\": [0.01, 0.01], \"color\": [0.4, 0.6, 1], \"weight\": 0.5}],"
     " \"materials\": {\"floor\": {\"color\": [0.8, 0.8, 0.75]}, \"glass\": {\"color\": [0.3, 0.6, 0.9],"
     "  \"opacity\": 0.4, \"transport\": [0.2, 0.5, 0.8]}, \"red\": {\"color\": [0.9, 0.2, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"sphere\", \"center\": [-0.3, 0.1, 0], \"radius\": 0.4, \"material\": \"glass\"},"
     "  {\"shape\": \"box\", \"center\": [0.5, -0.2, 0.3], \"size\": [0.4, 0.6, 0.4], \"material\": \"red\"}]}"},
    {"poisson 8, 384 rotations, rotation runs of 16", "table",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"kernel\": \"poisson\", \"pixel_rotations\": 384,"
     "  \"rotation_run\": 16, \"seed\": 11},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"torus\", \"center\": [0, 0, 0], \"normal\": [0.3, 1, 0.2], \"major_radius\": 0.5, \"minor_radius\": 0.15, \"material\": \"dark\"}]}"},
    {"ellipse 3, 1 rotation per slab (one tap set: the stencil kernel)", "table",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"samples\": 3, \"pixel_rotations\": 1},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"gauss 19, nonneg (stencil)", "taps",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"kernel\": \"gauss\"},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"tophat, signed compensation (values clamped to [0, 1])", "taps",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"kernel\": \"tophat\", \"compensate\": \"signed\"},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.004, 0.002]}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"gauss, a light wide enough that taps reach past the apron (clamped stencil reads)", "taps",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [49, 35]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"kernel\": \"gauss\", \"samples\": 5},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [200, 160]}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"ellipse, a light wide enough that taps reach past the apron (clamped table reads)", "table",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [97, 71]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [150, 100], \"angle_deg\": 20}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"ellipse, integer compensation", "integer",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"compensate\": \"integer\"},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
     " \"materials\": {\"floor\": {}, \"dark\": {\"color\": [0.1, 0.1, 0.1]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"disk\", \"center\": [0, 0.1, 0], \"normal\": [0, 1, 0.3], \"radius\": 0.5, \"material\": \"dark\"}]}"},
    {"perspective camera (classes), volume with ridged detail", "table",
     "{\"camera\": {\"projection\": \"perspective\", \"eye\": [0, 0.6, 3], \"target\": [0, 0, 0], \"fov_deg\": 40,"
     "  \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.03, \"d1\": 1, \"seed\": 3},"
     " \"lights\": [{\"mean\": [0.3, 0.3], \"var\": [0.015, 0.01]}],"
     " \"materials\": {\"floor\": {}, \"fog\": {\"color\": [0.9, 0.9, 0.95], \"extinction\": 6,"
     "  \"transport\": [0.1, 0.1, 0.1], \"detail\": {\"function\": \"ridged\", \"octaves\": 3, \"frequency\": 3}}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"sphere\", \"center\": [0, 0.1, 0], \"radius\": 0.5, \"material\": \"fog\"}]}"},
    {"two overlapping volumes: plain and Perlin with a transfer function, preintegrated", "table",
     "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
     " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"preintegrate\": true},"
     " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
     " \"materials\": {\"floor\": {}, \"haze\": {\"color\": [0.7, 0.8, 1], \"extinction\": 2},"
     "  \"smoke\": {\"color\": [1, 0.9, 0.8], \"extinction\": 9, \"transport\": [0.3, 0.2, 0.1],"
     "  \"detail\": {\"function\": \"perlin\", \"frequency\": 4, \"scale\": 1.5, \"bias\": 0.3},"
     "  \"transfer\": [[0, 0.9, 0.5, 0.2, 0], [0.5, 0.95, 0.8, 0.5, 0.7], [1, 1, 1, 0.9, 1.5]]}},"
     " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
     "  {\"shape\": \"box\", \"center\": [-0.2, 0, 0], \"size\": [1, 0.8, 0.8], \"material\": \"haze\"},"
     "  {\"shape\": \"sphere\", \"center\": [0.2, 0.1, 0], \"radius\": 0.45, \"material\": \"smoke\"}]}"},
};

/* Scene files are compared at most SCENE_FILE_SIDE pixels on their longer side, the aspect kept
 * (scenes/ holds the gallery's scenes, up to 320 x 240): the same paths as at their own size,
 * and the gl runs on llvmpipe stay medium (at their own sizes the gallery's scenes took 87 s
 * more on each of the three gl runs). */
#define SCENE_FILE_SIDE 128

/* cpu against the backend on scene s at width x height (0, 0: the scene's resolution); mode: the
 * path light 0 must run in (NULL: any). The backend renders the scene's render.model (auto, which
 * it renders as patel, or patel), the cpu patel. */
static void compare(const char *what, const char *mode, const ics_scene *s, int width,
                    int height) {
  if (mode) { /* the path this variant is for */
    char got[64] = "";
    ics_plan *p = plan_sized_or_exit(s, NULL, 0, width, height);
    for (int i = 0; i < ics_plan_pass_count(p); i++) {
      const ics_plan_pass *q = ics_plan_pass_at(p, i);
      if (q->light == 0) sscanf(q->detail, "%*s %*s %63[a-z]", got);
    }
    ics_plan_destroy(p);
    CHECK(!strcmp(got, mode), "%s: light 0 runs in mode '%s', the variant is for '%s'", what, got, mode);
  }
  const unsigned aovs = ICS_AOV_VISIBILITY | ICS_AOV_DEPTH;
  ics_render_settings patel = *ics_scene_settings(s);
  patel.model = ICS_MODEL_PATEL;
  render_result a = render_scene_sized_on("cpu", s, &patel, 0, aovs, width, height),
                b = render_scene_sized_on(backend, s, NULL, 0, aovs, width, height);
  double maxd = 0, sum = 0;
  int at = 0;
  size_t n = (size_t)a.img->width * a.img->height * 4;
  CHECK(a.img->width == b.img->width && a.img->height == b.img->height, "%s: sizes", what);
  for (size_t i = 0; i < n; i++) {
    double d = fabs((double)a.img->data[i] - b.img->data[i]);
    if (!(d <= maxd)) maxd = d, at = (int)(i / 4);
    sum += d * d;
  }
  double rms = sqrt(sum / (double)n), amax = 0; /* the AOVs: visibility per light, depth */
  size_t na = (size_t)a.aov->count * a.aov->width * a.aov->height;
  CHECK(a.aov->count == b.aov->count, "%s: AOV channels %d vs %d", what, a.aov->count, b.aov->count);
  for (size_t i = 0; i < na && a.aov->count == b.aov->count; i++) {
    double d = fabs((double)a.aov->data[i] - b.aov->data[i]);
    if (!(d <= amax)) amax = d;
  }
  printf("%-72s %dx%d, %3d slabs: max %.3g at (%d, %d), RMS %.3g; AOVs max %.3g (%.0f ms)\n", what,
         a.img->width, a.img->height, b.stats.slabs, maxd, at % a.img->width, at / a.img->width,
         rms, amax, b.stats.ms_total);
  CHECK(maxd <= TOL_MAX, "%s: max difference %.3g > %.3g", what, maxd, TOL_MAX);
  CHECK(rms <= TOL_RMS, "%s: RMS difference %.3g > %.3g", what, rms, TOL_RMS);
  CHECK(amax <= TOL_MAX, "%s: AOVs differ by %.3g > %.3g", what, amax, TOL_MAX);
  CHECK(!strcmp(b.stats.backend, backend), "%s: backend %s", what, b.stats.backend);
  CHECK(!strcmp(b.stats.model, "patel"), "%s: the backend rendered model %s", what, b.stats.model);
  const char *ldi = getenv("ICS_GL_LDI"); /* the device's layered depth image: it was built */
  if (!strcmp(backend, "gl") && ldi && !strcmp(ldi, "device"))
    CHECK(b.stats.ms_geometry_device > 0, "%s: ICS_GL_LDI=device, but no LDI built on the device",
          what);
  snprintf(device, sizeof device, "%s", b.stats.device);
  ics_image_destroy(a.img);
  ics_image_destroy(b.img);
  ics_exr_channels_destroy(a.aov);
  ics_exr_channels_destroy(b.aov);
}

/* render.model auto planned for a renderer of the backend (ics_plan_opts.renderer): Patel's plan
 * (its memory), rendered as patel, no second plan needed */
static void auto_planned(const ics_scene *s) {
  char msg[1024] = "";
  ics_render_opts ro = {.backend = backend};
  ics_renderer *r = NULL;
  CHECK(ics_renderer_create(&r, &ro, msg, sizeof msg) == ICS_OK, "renderer: %s", msg);
  if (!r) return;
  CHECK(ics_renderer_model_auto(r) == ICS_MODEL_PATEL, "auto on %s: %s", backend,
        ics_render_model_name(ics_renderer_model_auto(r)));
  ics_render_settings patel = *ics_scene_settings(s);
  patel.model = ICS_MODEL_PATEL;
  ics_plan_opts po = {.width = 64, .height = 48, .renderer = r}, pp = {.width = 64, .height = 48, .settings = &patel};
  ics_plan *a = NULL, *b = NULL;
  ics_image *img = NULL;
  ics_render_stats st;
  memset(&st, 0, sizeof st);
  CHECK(ics_plan_create(&a, s, &po, msg, sizeof msg) == ICS_OK, "plan for %s: %s", backend, msg);
  CHECK(ics_plan_create(&b, s, &pp, msg, sizeof msg) == ICS_OK, "Patel's plan: %s", msg);
  if (a && b) {
    CHECK(ics_plan_memory_bytes(a) == ics_plan_memory_bytes(b), "auto planned for %s: %zu bytes, Patel's %zu",
          backend, ics_plan_memory_bytes(a), ics_plan_memory_bytes(b));
    CHECK(ics_renderer_render(r, a, &img, &st, msg, sizeof msg) == ICS_OK, "render: %s", msg);
    CHECK(!strcmp(st.model, "patel"), "auto planned for %s rendered %s", backend, st.model);
    printf("auto planned for %s: %zu bytes (Patel's), rendered %s\n", backend, ics_plan_memory_bytes(a), st.model);
  }
  ics_image_destroy(img);
  ics_plan_destroy(a);
  ics_plan_destroy(b);
  ics_renderer_destroy(r);
}

/* a render the backend refuses: status, message, no image */
static void refused(const char *what, const char *json, ics_status want, const char *needle) {
  ics_scene *s = scene_from_json(json);
  char msg[2048] = "";
  ics_plan *p = plan_or_exit(s, NULL, 0);
  ics_render_opts ro = {.backend = backend};
  ics_renderer *r = NULL;
  ics_image *img = NULL;
  ics_status st = ics_renderer_create(&r, &ro, msg, sizeof msg);
  if (st == ICS_OK) st = ics_renderer_render(r, p, &img, NULL, msg, sizeof msg);
  printf("refused, %s: %s (%s)\n", what, msg, ics_status_str(st));
  CHECK(st == want, "%s: status %s, want %s", what, ics_status_str(st), ics_status_str(want));
  CHECK(strstr(msg, needle) != NULL, "%s: message '%s' lacks '%s'", what, msg, needle);
  CHECK(img == NULL, "%s: an image came back", what);
  ics_renderer_destroy(r);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

/* a render of plan p on renderer r; ICS_OK or the status with msg */
typedef struct lifecycle_job {
  ics_renderer *r;
  const ics_plan *p;
  ics_status st;
  char msg[1024];
} lifecycle_job;
static void *render_job(void *arg) {
  lifecycle_job *j = arg;
  ics_image *img = NULL;
  j->st = ics_renderer_render(j->r, j->p, &img, NULL, j->msg, sizeof j->msg);
  ics_image_destroy(img);
  return NULL;
}

/* Renderers as an application holds them: two at once, the first destroyed before the second
 * renders; the availability check while one exists; a render on another thread than the one
 * that created the renderer (each must leave the others' contexts intact). */
static void lifecycle(const char *json) {
  ics_scene *s = scene_from_json(json);
  char msg[1024] = "";
  ics_plan *p = plan_or_exit(s, NULL, 0);
  ics_render_opts ro = {.backend = backend};
  ics_renderer *a = NULL, *b = NULL;
  CHECK(ics_renderer_create(&a, &ro, msg, sizeof msg) == ICS_OK, "renderer a: %s", msg);
  CHECK(ics_renderer_create(&b, &ro, msg, sizeof msg) == ICS_OK, "renderer b: %s", msg);
  lifecycle_job j = {.r = a, .p = p};
  render_job(&j);
  CHECK(j.st == ICS_OK, "renderer a with b alive: %s", j.msg);
  ics_renderer_destroy(a);
  char why[512];
  CHECK(ics_backend_available(backend, why, sizeof why), "available while b exists: %s", why);
  j = (lifecycle_job){.r = b, .p = p};
  render_job(&j);
  CHECK(j.st == ICS_OK, "renderer b after a was destroyed and the backend probed: %s", j.msg);
  pthread_t th;
  j = (lifecycle_job){.r = b, .p = p};
  CHECK(pthread_create(&th, NULL, render_job, &j) == 0, "pthread_create");
  pthread_join(th, NULL);
  CHECK(j.st == ICS_OK, "renderer b on another thread: %s", j.msg);
  j = (lifecycle_job){.r = b, .p = p};
  render_job(&j);
  CHECK(j.st == ICS_OK, "renderer b back on its first thread: %s", j.msg);
  printf("lifecycle: two renderers, a probe, a render on another thread: %s\n",
         test_failures_ ? "FAILED" : "ok");
  ics_renderer_destroy(b);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

int main(int argc, char **argv) {
  char why[1024];
  if (argc < 2 || (strcmp(argv[1], "cl") && strcmp(argv[1], "gl"))) {
    fprintf(stderr, "usage: test_render_device cl|gl [SCENE.json ...]\n");
    return 2;
  }
  backend = argv[1];
  if (!ics_backend_available(backend, why, sizeof why)) {
    printf("SKIPPED: the %s backend cannot run here: %s\n", backend, why);
    return 77;
  }
  lifecycle(variants[3][2]);
  ics_scene *s = scene_from_json(ics_scene_default_json());
  auto_planned(s);
  compare("the embedded default scene", "table", s, 0, 0);
  ics_scene_destroy(s);
  for (int i = 2; i < argc; i++) {
    s = scene_from_file(argv[i]);
    const ics_camera *c = ics_scene_camera(s);
    int side = c->width > c->height_px ? c->width : c->height_px, w = 0, h = 0;
    if (side > SCENE_FILE_SIDE) { /* sides below 16384: no overflow; at least 1 x 1 */
      w = c->width * SCENE_FILE_SIDE / side;
      h = c->height_px * SCENE_FILE_SIDE / side;
      w = w > 0 ? w : 1;
      h = h > 0 ? h : 1;
    }
    compare(argv[i], NULL, s, w, h);
    ics_scene_destroy(s);
  }
  for (size_t v = 0; v < sizeof variants / sizeof *variants; v++) {
    s = scene_from_json(variants[v][2]);
    compare(variants[v][0], variants[v][1], s, 0, 0);
    ics_scene_destroy(s);
  }
  /* grid detail: a 5 x 4 x 3 grid of random values over a box, preintegrated */
  const char *td = getenv("TMPDIR");
  char grid[1024], json[4096];
  snprintf(grid, sizeof grid, "%s/test_render_%s_grid.raw", td && *td ? td : "/tmp", backend);
  FILE *f = fopen(grid, "wb");
  float cells[60];
  for (int i = 0; i < 60; i++) cells[i] = (float)((test_rng_u64() >> 11) * 0x1p-53 * 1.5);
  if (!f || fwrite(cells, sizeof cells, 1, f) != 1 || fclose(f)) {
    fprintf(stderr, "cannot write %s\n", grid);
    return 2;
  }
  snprintf(json, sizeof json,
           "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [96, 72]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"preintegrate\": true},"
           " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06], \"angle_deg\": 25}],"
           " \"materials\": {\"floor\": {}, \"g\": {\"extinction\": 5, \"transport\": [0.2, 0.3, 0.4],"
           " \"detail\": {\"function\": \"grid\", \"file\": \"%s\", \"size\": [5, 4, 3], \"scale\": 1.2}}},"
           " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"},"
           "  {\"shape\": \"box\", \"center\": [0, 0.1, 0], \"size\": [1.2, 0.8, 0.9], \"material\": \"g\"}]}",
           grid);
  s = scene_from_json(json);
  compare("volume with grid detail (5 x 4 x 3), preintegrated", "table", s, 0, 0);
  ics_scene_destroy(s);
  remove(grid);
  /* ten volumes overlapping at the centre (more than the 8 whose extinctions ics_shade keeps),
   * with fBm detail in every other one */
  int n = snprintf(json, sizeof json,
                   "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [64, 48]},"
                   " \"render\": {\"slab_spacing\": 0.03, \"d1\": 1},"
                   " \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.2, 0.06]}, {\"mean\": [-0.3, 0.1], \"var\": [0.1, 0.1]}],"
                   " \"materials\": {\"floor\": {}, \"a\": {\"extinction\": 1.5, \"transport\": [0.3, 0.2, 0.1]},"
                   " \"b\": {\"extinction\": 2, \"color\": [0.8, 0.6, 0.4], \"detail\": {\"function\": \"fbm\", \"frequency\": 3}}},"
                   " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.6, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"}");
  for (int v = 0; v < 10 && n > 0 && (size_t)n < sizeof json; v++)
    n += snprintf(json + n, sizeof json - (size_t)n,
                  ", {\"shape\": \"sphere\", \"center\": [%g, %g, 0], \"radius\": %g, \"material\": \"%c\"}",
                  0.04 * v - 0.2, 0.02 * v, 0.5 + 0.02 * v, v % 2 ? 'b' : 'a');
  if (n > 0 && (size_t)n + 3 < sizeof json) snprintf(json + n, sizeof json - (size_t)n, "]}");
  s = scene_from_json(json);
  compare("ten overlapping volumes (five with fBm detail), two lights", "table", s, 0, 0);
  ics_scene_destroy(s);
  if (!strcmp(backend, "cl")) {
    setenv("ICS_CL_DEVICE", "no such device anywhere", 1);
    refused("ICS_CL_DEVICE naming no device", variants[0][2], ICS_ERR_UNSUPPORTED,
            "ICS_CL_DEVICE=no such device anywhere matches no device");
    setenv("ICS_CL_DEVICE", "99", 1);
    refused("ICS_CL_DEVICE out of range", variants[0][2], ICS_ERR_UNSUPPORTED, "ICS_CL_DEVICE=99");
    unsetenv("ICS_CL_DEVICE");
  } else {
    /* light buffers of 4000 x 3000 x 3 channels: 150 MB, over llvmpipe's 128 MiB shader storage
     * blocks (a GPU driver may take them: then the render must agree instead) */
    const char *big =
        "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [4000, 3000]},"
        " \"render\": {\"slab_spacing\": 0.5, \"d1\": 1, \"max_pad\": 0},"
        " \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01], \"color\": [1, 0.5, 0.2]}],"
        " \"materials\": {\"floor\": {\"transport\": [0.5, 0.2, 0.1], \"opacity\": 0.5}},"
        " \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0], \"normal\": [0, 1, 0], \"size\": [4, 4], \"material\": \"floor\"}]}";
    const char *ctx = getenv("ICS_GL_CONTEXT");
    printf("gl device: %s\n", device);
    if (strstr(device, "llvmpipe")) /* llvmpipe's limits */
      refused("light buffers over the driver's largest shader storage block", big, ICS_ERR_SIZE,
              "over the driver's largest");
    char *saved = ctx ? strdup(ctx) : NULL;
    setenv("ICS_GL_CONTEXT", "vulkan", 1);
    refused("ICS_GL_CONTEXT naming no kind", variants[0][2], ICS_ERR_UNSUPPORTED,
            "no OpenGL context kind 'vulkan'");
    if (saved) setenv("ICS_GL_CONTEXT", saved, 1);
    else unsetenv("ICS_GL_CONTEXT");
    free(saved);
  }
  return test_summary(!strcmp(backend, "cl") ? "test_render_device cl" : "test_render_device gl");
}
