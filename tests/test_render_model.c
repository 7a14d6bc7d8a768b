/* test_render_model.c — the slab renderer's models (render.model; docs/renderer.md "Models"),
 * each step against a closed form with a control that must fail:
 * - patel, dense, renders the default scene (96 x 72) bit for bit as the release before the
 *   models and the skipping (commit 9b34856; FNV-1a 64 of the RGBA floats, recorded per vector
 *   path with that commit's icshadow: scalar, sse2, and the paths with fused multiply-adds;
 *   recorded again where the choices' packing changed the random stream, below);
 * - solid: an opaque sphere over a white floor under a narrow light; the floor points whose
 *   light directions within 4.5 standard deviations all meet the sphere (its umbra, by ray
 *   against sphere) are dark: visibility at most 0.01 (measured 0.0048 at worst, 0.0001 on
 *   average); patel, the control, lets light slip through the sphere there (its mean umbra
 *   visibility must exceed 0.05; measured 0.069, at worst 0.33); and the floor points whose
 *   light directions all miss the sphere are lit: at least 0.95 (measured 0.957 under solid and
 *   surface, 0.996 under blocker; 0.936 while a solid's interior darkened the light from the slab
 *   it is entered in on, no longer: from the next; patel 0.55);
 * - solid: boxes a fifth of a slab, exactly one slab (the back face on a slab boundary) and two
 *   slabs thick still darken their umbra (visibility at most 0.01, measured 0; 1.0 for the first
 *   two when a ray that left the solid in its entry slab, or on the next slab's front, skipped
 *   it); the control, no box, leaves those pixels lit;
 * - surface: the sphere's own surface lit by its own term, the fraction of the Gaussian light
 *   above its tangent plane, Phi((g . mu + 1) / sqrt(g' Sigma g)), which on a sphere nothing
 *   else shadows is its exact visibility: the AOV within 0.03 of Phi at every sphere pixel away
 *   from the limb (measured 0.0096 at worst, where Patel's set, which lights the sphere, is a
 *   little below 1); the controls, patel (no attached shadow) and solid (slicing rings), must be
 *   off by more than 0.1 (measured 0.99 and 1.0);
 * - surface, open surfaces (own_term.c): a plane alone lit by its own term, the fraction of the
 *   light on its viewed side (the closed form from the camera frame here): a floor under a light
 *   at 45 deg elevation from the side (exact 0.9617; Monte Carlo at 256 spp: 0.9616) at every pixel
 *   within 0.02, a plane with its light partly below its horizon (exact Phi(-0.5) = 0.3085) within
 *   0.01 (measured: exact to 1e-6); patel, the control, shades them by slicing (measured 0.61 to
 *   0.89, and 0.29): off by more;
 * - the rule that leaves an open surface out of a light's buffers: every other shaded point on one
 *   side of its plane, the light from the other side with probability at most 1 %: on the default
 *   scene the floor and the wall for both lights; a canopy over a floor: the floor, not the canopy
 *   (the floor is behind it); lights 2.054 and 2.576 sd above a floor's horizon (2 % and 0.5 %
 *   below it): the second only; a floor with a wall seen on both of its sides: none;
 * - surface, a volume piece's own term: a slab of coloured smoke (extinction 1.7, thickness 0.5,
 *   colour (0.8, 0.6, 0.4), transport (0.5, 0.2, 0)) before a white receiver under a point light
 *   of mean (0.3, -0.2), against the closed form (test_render_mc's, there Monte Carlo's)
 *   C_c = sigma col_c (1 - exp(-a_c T)) / a_c + exp(-sigma T) exp(-sigma (1 - T_c) k T),
 *   a_c = sigma + sigma (1 - T_c) k, k = sqrt(1 + |mu|^2), at every pixel and spacings 0.01,
 *   0.07 and 0.29: within a relative 1e-4 (measured 6e-7 at worst); patel, which lights each piece
 *   with the light arriving at its slab, the control: off by more than 1e-3 at every spacing
 *   (measured 0.0043 to 0.12, growing with the spacing);
 * - blocker, blocker-aware penumbrae: a straight edge 0.1, 0.3 and 0.5 above a receiver (d1 = 1),
 *   the light of mean (-1, 0) and sigma 0.3: the receiver's visibility against the closed form
 *   Phi((x / d - 1) / sigma) over its penumbra, RMS at most 0.1, 0.02, 0.02 (measured 0.0867,
 *   0.0047 and 0.0109; at 0.1, below the sharp set's d1 / 4, the sharp set alone, still too
 *   wide); surface, the control, widens the penumbra as sqrt(d d1) for d (Patel's d1 problem):
 *   more than 0.05 (measured 0.203, 0.114 and 0.065);
 * - a scene without solid objects or open surfaces lit by their own term renders alike, bit for
 *   bit, under every model: the contract's disk (its receiver, seen head on, is left out, but its
 *   own term is 1 and nothing shaded lies behind it), and under solid a closed sphere whose
 *   transport lets tinted light through (not solid). */
#define _POSIX_C_SOURCE 200809L /* setenv */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/normal.h"
#include "plan_internal.h"
#include "render_util.h"
#include "simd_path.h"
#include "testutil.h"

static uint64_t fnv1a(const void *data, size_t n) {
  const unsigned char *b = data;
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 0x100000001b3ull;
  return h;
}

static void test_patel_unchanged(void) {
  /* icshadow render --resolution 96x72 -o X.exr, ICS_SIMD=scalar | sse2 | avx2 (avx512 the
   * same), the EXR's RGBA floats hashed: at 9b34856 (before the models); again when the per-pixel
   * choices were packed several to a Philox word (slab_choice.h), which changed the default's
   * random stream and nothing else (the default scene with 1 or 384 rotations, or runs of 16,
   * whose choices it left alone, rendered bit for bit as before it: icshadow render --compare
   * of the two builds, RMSE 0, checked by hand at that commit); the default scene's slab spacing
   * was 0.015 then (0.045 since its model became auto) */
  static const struct {
    ics_simd_path path;
    uint64_t hash;
  } before[] = {{ICS_SIMD_SCALAR, 0x6a4ddf17e2027a54ull},
                {ICS_SIMD_SSE2, 0x5ad5ad794161b2b7ull},
                {ICS_SIMD_AVX2, 0x46dff94cff69d028ull},
                {ICS_SIMD_AVX512, 0x46dff94cff69d028ull}};
  ics_scene *s = default_scene_96x72();
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = ICS_MODEL_PATEL;
  rs.slab_spacing = 0.015;
  rs.dense = 1;
  rs.pixel_rotations = 4; /* the default before it became 2 */
  for (size_t i = 0; i < sizeof before / sizeof *before; i++) {
    if (!ics_simd_has(before[i].path)) {
      printf("patel, %s: skipped (not on this processor)\n", ics_simd_name(before[i].path));
      continue;
    }
    setenv("ICS_SIMD", ics_simd_name(before[i].path), 1);
    render_result r = render_scene(s, &rs, 2);
    uint64_t h = fnv1a(r.img->data, sizeof(float) * 4 * (size_t)r.img->width * r.img->height);
    CHECK(h == before[i].hash, "patel, dense, %s: image hash %016llx, before %016llx",
          ics_simd_name(before[i].path), (unsigned long long)h, (unsigned long long)before[i].hash);
    printf("patel, dense, %s: the image before the models bit for bit (%016llx)\n",
           ics_simd_name(before[i].path), (unsigned long long)h);
    ics_image_destroy(r.img);
  }
  unsetenv("ICS_SIMD");
  ics_scene_destroy(s);
}

/* the sphere scene: camera, sphere, floor, light (docs/results.md "Error by effect") */
#define EYE_Y 1.2
#define EYE_Z 3.0
#define HEIGHT 3.0
#define RES_W 160
#define RES_H 120
static const double sphere_c[3] = {0, 0.1, 0}, sphere_r = 0.5, floor_y = -0.4;
static const double light_mu[2] = {0.6, 0.55}, light_var = 0.004;

static ics_scene *sphere_scene(void) {
  char j[2048];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, %g, %g], \"target\": [0, 0, 0], \"height\": %g, \"resolution\": [%d, %d]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 1},"
           " \"lights\": [{\"mean\": [%g, %g], \"var\": [%g, %g]}],"
           " \"materials\": {\"white\": {}, \"grey\": {\"color\": [0.8, 0.8, 0.8]}},"
           " \"objects\": [{\"shape\": \"sphere\", \"center\": [%g, %g, %g], \"radius\": %g, \"material\": \"grey\"},"
           "  {\"shape\": \"rect\", \"center\": [0, %g, 0], \"normal\": [0, 1, 0], \"size\": [6, 6], \"material\": \"white\"}]}",
           EYE_Y, EYE_Z, HEIGHT, RES_W, RES_H, light_mu[0], light_mu[1], light_var, light_var,
           sphere_c[0], sphere_c[1], sphere_c[2], sphere_r, floor_y);
  return scene_from_json(j);
}

typedef struct {
  double r[3], u[3], f[3], eye[3];
} frame_t;

static double dot(const double *a, const double *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static frame_t camera_frame(const ics_scene *s) {
  const ics_camera *c = ics_scene_camera(s);
  frame_t F;
  memcpy(F.r, c->r, sizeof F.r), memcpy(F.u, c->u, sizeof F.u), memcpy(F.f, c->f, sizeof F.f);
  memcpy(F.eye, c->eye, sizeof F.eye);
  return F;
}

/* the orthographic ray of pixel (i, j): origin o, direction f */
static void pixel_origin(const frame_t *F, int i, int j, double o[3]) {
  double w = HEIGHT * RES_W / RES_H, s = (i + 0.5) / RES_W, t = (j + 0.5) / RES_H;
  for (int k = 0; k < 3; k++) o[k] = F->eye[k] + (s - 0.5) * w * F->r[k] + (0.5 - t) * HEIGHT * F->u[k];
}

/* the nearest crossing t > 0 of the ray o + t d with the sphere, or -1 */
static double hit_sphere(const double o[3], const double d[3]) {
  double q[3] = {o[0] - sphere_c[0], o[1] - sphere_c[1], o[2] - sphere_c[2]};
  double a = dot(d, d), b = dot(q, d), c = dot(q, q) - sphere_r * sphere_r, disc = b * b - a * c;
  if (disc <= 0) return -1;
  double t0 = (-b - sqrt(disc)) / a, t1 = (-b + sqrt(disc)) / a;
  return t0 > 0 ? t0 : t1 > 0 ? t1 : -1;
}

/* the direction toward light-plane point X: X_x r + X_y u - f */
static void light_dir(const frame_t *F, double x, double y, double d[3]) {
  for (int k = 0; k < 3; k++) d[k] = x * F->r[k] + y * F->u[k] - F->f[k];
}

static double aov_v(const render_result *r, int i, int j) {
  int c = ics_exr_channel_index(r->aov, "light0.V");
  return r->aov->data[((size_t)j * RES_W + i) * r->aov->count + c];
}

/* whether floor point p's light directions within 4.5 sd (a ring of 16 and the mean) all meet
 * the sphere (lit = 0) or all miss it (lit = 1) */
static int all_directions(const frame_t *F, const double p[3], int lit) {
  double d[3], sd = sqrt(light_var);
  for (int a = -1; a < 16; a++) {
    double ang = 2 * ICS_PI * a / 16, rad = a < 0 ? 0 : 4.5 * sd;
    light_dir(F, light_mu[0] + rad * cos(ang), light_mu[1] + rad * sin(ang), d);
    if ((hit_sphere(p, d) > 0) == lit) return 0;
  }
  return 1;
}

/* the floor's umbra (lit = 0: every floor pixel whose light directions within 4.5 sd all meet
 * the sphere) or its lit part (lit = 1: all miss it): the mean visibility there, its extreme
 * (the largest in the umbra, the smallest where lit) into *worst and the pixel count into *n */
static double floor_visibility(ics_render_model m, int lit, double *worst, int *n) {
  ics_scene *s = sphere_scene();
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = m;
  render_result r = render_scene_aovs(s, &rs, 2, ICS_AOV_VISIBILITY);
  frame_t F = camera_frame(s);
  double sum = 0;
  *worst = lit, *n = 0;
  for (int j = 0; j < RES_H; j++)
    for (int i = 0; i < RES_W; i++) {
      double o[3];
      pixel_origin(&F, i, j, o);
      if (hit_sphere(o, F.f) > 0) continue;
      double t = (floor_y - o[1]) / F.f[1], p[3];
      for (int k = 0; k < 3; k++) p[k] = o[k] + t * F.f[k];
      if (fabs(p[0]) > 2.9 || fabs(p[2]) > 2.9 || !all_directions(&F, p, lit)) continue;
      double v = aov_v(&r, i, j);
      sum += v, (*n)++;
      *worst = lit ? fmin(*worst, v) : fmax(*worst, v);
    }
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  ics_scene_destroy(s);
  return *n ? sum / *n : NAN;
}

static void test_solid(void) {
  for (int m = ICS_MODEL_PATEL; m <= ICS_MODEL_BLOCKER; m++) {
    double worst;
    int n;
    double mean = floor_visibility((ics_render_model)m, 0, &worst, &n), lit_worst;
    int n_lit;
    floor_visibility((ics_render_model)m, 1, &lit_worst, &n_lit);
    printf("lit floor beside an opaque sphere, %s: %d pixels, visibility min %.4f\n",
           ics_render_model_name((ics_render_model)m), n_lit, lit_worst);
    CHECK(n_lit > 1000, "the lit floor holds %d pixels", n_lit);
    if (m != ICS_MODEL_PATEL)
      CHECK(lit_worst >= 0.95, "%s: the lit floor beside the sphere is shadowed: visibility %.4f "
            "(at least 0.95)", ics_render_model_name((ics_render_model)m), lit_worst);
    printf("umbra of an opaque sphere, %s: %d floor pixels, visibility mean %.4f, max %.4f\n",
           ics_render_model_name((ics_render_model)m), n, mean, worst);
    CHECK(n > 100, "the umbra holds %d pixels", n);
    if (m == ICS_MODEL_PATEL)
      CHECK(mean > 0.05, "the control (patel) should let light through the sphere: mean %.4f", mean);
    else
      CHECK(worst <= 0.01, "%s: the umbra is lit, max visibility %.4f (at most 0.01)",
            ics_render_model_name((ics_render_model)m), worst);
  }
}

/* the sphere's own term against the closed form at its pixels away from the limb */
static double own_term_error(ics_render_model m, int *n) {
  ics_scene *s = sphere_scene();
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = m;
  render_result r = render_scene_aovs(s, &rs, 2, ICS_AOV_VISIBILITY);
  frame_t F = camera_frame(s);
  double worst = 0;
  *n = 0;
  for (int j = 0; j < RES_H; j++)
    for (int i = 0; i < RES_W; i++) {
      double o[3], p[3], nrm[3];
      pixel_origin(&F, i, j, o);
      double t = hit_sphere(o, F.f);
      if (t <= 0) continue;
      for (int k = 0; k < 3; k++) p[k] = o[k] + t * F.f[k], nrm[k] = (p[k] - sphere_c[k]) / sphere_r;
      if (-dot(nrm, F.f) < 0.3) continue; /* the limb: the depth gradient is steep there */
      double nf = dot(nrm, F.f), gr = -dot(nrm, F.r) / nf, gu = -dot(nrm, F.u) / nf;
      double mm = gr * light_mu[0] + gu * light_mu[1] + 1, v = (gr * gr + gu * gu) * light_var;
      double phi = 0.5 * erfc(-mm / sqrt(2 * v));
      worst = fmax(worst, fabs(aov_v(&r, i, j) - phi));
      (*n)++;
    }
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  ics_scene_destroy(s);
  return worst;
}

static void test_own_term(void) {
  for (int m = ICS_MODEL_PATEL; m <= ICS_MODEL_SURFACE; m++) {
    int n;
    double e = own_term_error((ics_render_model)m, &n);
    printf("an opaque sphere's own surface, %s: %d pixels, max |V - Phi| %.4f\n",
           ics_render_model_name((ics_render_model)m), n, e);
    CHECK(n > 500, "the sphere holds %d pixels", n);
    if (m == ICS_MODEL_SURFACE)
      CHECK(e <= 0.03, "surface: the sphere's visibility off its own term by %.4f (at most 0.03)", e);
    else
      CHECK(e > 0.1, "the control (%s) should miss the own term: max %.4f",
            ics_render_model_name((ics_render_model)m), e);
  }
}

/* a plane alone (normal n through c, 96 x 72 orthographic from eye toward the origin, height 3,
 * one light of mean mu and isotropic variance var): the largest |V - Phi| over its pixels, Phi
 * the closed form of the light on its viewed side */
static double plane_own_error(ics_render_model m, const double eye[3], const double c[3],
                              const double n[3], const double mu[2], double var, double *exact) {
  char j[1024];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [%g, %g, %g], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [96, 72]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 5},"
           " \"lights\": [{\"mean\": [%.17g, %.17g], \"var\": [%.17g, %.17g]}],"
           " \"materials\": {\"white\": {}},"
           " \"objects\": [{\"shape\": \"rect\", \"center\": [%g, %g, %g], \"normal\": [%g, %g, %g], \"size\": [20, 20], \"material\": \"white\"}]}",
           eye[0], eye[1], eye[2], mu[0], mu[1], var, var, c[0], c[1], c[2], n[0], n[1], n[2]);
  ics_scene *s = scene_from_json(j);
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = m;
  render_result r = render_scene_aovs(s, &rs, 2, ICS_AOV_VISIBILITY);
  frame_t F = camera_frame(s);
  double nv[3] = {n[0], n[1], n[2]};
  if (dot(nv, F.f) > 0) nv[0] = -nv[0], nv[1] = -nv[1], nv[2] = -nv[2]; /* the viewed side */
  /* lit iff (X_x r + X_y u - f) . n > 0: a half-plane of the light plane */
  double ar = dot(nv, F.r), au = dot(nv, F.u), b = -dot(nv, F.f);
  *exact = 0.5 * erfc(-(ar * mu[0] + au * mu[1] + b) / sqrt(2 * var * (ar * ar + au * au)));
  int ch = ics_exr_channel_index(r.aov, "light0.V");
  double worst = 0;
  for (int p = 0; p < 96 * 72; p++) { /* (a NaN stays: it fails the check) */
    double e = fabs(r.aov->data[(size_t)p * r.aov->count + ch] - *exact);
    if (!(e <= worst) && !isnan(worst)) worst = e;
  }
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  ics_scene_destroy(s);
  return worst;
}

static void test_open_own_term(void) {
  static const struct {
    const char *name;
    double eye[3], c[3], n[3], mu[2], var, tol;
  } cases[] = {{"a floor under a light at 45 deg from the side", {0, 1.2, 3}, {0, -1, 0}, {0, 1, 0},
                {0.8, 0.72}, 0.4, 0.02},
               /* test_render_mc's plane: Monte Carlo there gives Phi(-0.5) */
               {"a plane with its light partly below its horizon", {0, 0, 2}, {0, 0, 0}, {0, 0.8, 0.6},
                {0, -0.8}, 0.01, 0.01}};
  for (size_t i = 0; i < sizeof cases / sizeof *cases; i++)
    for (int m = ICS_MODEL_PATEL; m <= ICS_MODEL_SURFACE; m += ICS_MODEL_SURFACE - ICS_MODEL_PATEL) {
      double exact, e = plane_own_error((ics_render_model)m, cases[i].eye, cases[i].c, cases[i].n,
                                        cases[i].mu, cases[i].var, &exact);
      printf("%s, %s: exact %.4f, max |V - exact| %.2g\n", cases[i].name,
             ics_render_model_name((ics_render_model)m), exact, e);
      if (m == ICS_MODEL_SURFACE)
        CHECK(e <= cases[i].tol, "surface, %s: off by %.4f (at most %g)", cases[i].name, e, cases[i].tol);
      else
        CHECK(e > cases[i].tol, "the control (patel), %s, should be off by more than %g: %.4f",
              cases[i].name, cases[i].tol, e);
    }
}

/* the plan's own lights of each object of scene json under render.model surface */
static void own_lights(const char *json, uint64_t *bits, int n) {
  ics_scene *s = scene_from_json(json);
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = ICS_MODEL_SURFACE;
  ics_plan_opts o = {.settings = &rs, .threads = 2};
  ics_plan *p = NULL;
  char msg[512];
  CHECK(ics_plan_create(&p, s, &o, msg, sizeof msg) == ICS_OK, "plan: %s", msg);
  for (int k = 0; k < n; k++) bits[k] = p ? p->own_lights[k] : 0;
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

#define FLOOR_SCENE(LIGHTS, OBJECTS)                                                              \
  "{\"camera\": {\"eye\": [0, 1.2, 3], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [64, 48]}," \
  " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1}, \"lights\": [" LIGHTS "],"                \
  " \"materials\": {\"white\": {}}, \"objects\": [{\"shape\": \"rect\", \"center\": [0, -0.5, 0],"      \
  " \"normal\": [0, 1, 0], \"size\": [" OBJECTS "}]}"

static void test_own_rule(void) {
  uint64_t b[4];
  ics_scene *d = default_scene_96x72();
  const char *txt = ics_scene_default_json();
  ics_scene_destroy(d);
  own_lights(txt, b, 4);
  CHECK(b[0] == 3 && b[1] == 3 && b[2] == 0 && b[3] == 0,
        "default scene: own lights %llx %llx %llx %llx (floor and wall: both lights)",
        (unsigned long long)b[0], (unsigned long long)b[1], (unsigned long long)b[2], (unsigned long long)b[3]);
  own_lights(FLOOR_SCENE("{\"mean\": [0.2, 0.5], \"var\": [0.01, 0.01]}",
                         "6, 6], \"material\": \"white\"}, {\"shape\": \"rect\", \"center\": [0, 0.2, 0],"
                         " \"normal\": [0, 1, 0], \"size\": [0.6, 0.6], \"material\": \"white\""), b, 2);
  CHECK(b[0] == 1 && b[1] == 0, "canopy over a floor: own lights floor %llx, canopy %llx (1, 0)",
        (unsigned long long)b[0], (unsigned long long)b[1]);
  /* lights z sd above the floor's horizon: the floor's normal (0, 1, 0) has a = (r . n, u . n) =
   * (0, u_y), b = -f_y, so X_y = (z sd u_y - b) / u_y with sd = sqrt(var) */
  frame_t F;
  {
    ics_scene *s = scene_from_json(FLOOR_SCENE("{\"mean\": [0, 0.5], \"var\": [0.01, 0.01]}", "6, 6], \"material\": \"white\""));
    F = camera_frame(s);
    ics_scene_destroy(s);
  }
  double var = 0.02, zs[2] = {2.054, 2.576}, y[2];
  for (int i = 0; i < 2; i++) y[i] = (zs[i] * sqrt(var) * F.u[1] + F.f[1]) / F.u[1];
  char lights[256];
  snprintf(lights, sizeof lights, "{\"mean\": [0, %.17g], \"var\": [%g, %g]}, {\"mean\": [0, %.17g], \"var\": [%g, %g]}",
           y[0], var, var, y[1], var, var);
  char json[1024];
  snprintf(json, sizeof json, FLOOR_SCENE("%s", "6, 6], \"material\": \"white\"}, {\"shape\": \"sphere\", \"center\": [0, 0, 0],"
           " \"radius\": 0.3, \"material\": \"white\""), lights);
  own_lights(json, b, 2);
  CHECK(b[0] == 2, "a floor with lights 2 %% and 0.5 %% below its horizon: own lights %llx (light 1 only)",
        (unsigned long long)b[0]);
  own_lights(FLOOR_SCENE("{\"mean\": [0.2, 0.5], \"var\": [0.01, 0.01]}",
                         "1, 1], \"material\": \"white\"}, {\"shape\": \"rect\", \"center\": [0, 0, -2],"
                         " \"normal\": [0, 0, 1], \"size\": [8, 8], \"material\": \"white\""), b, 2);
  CHECK(b[0] == 0, "a floor with a wall seen on both sides of it: own lights %llx (none)", (unsigned long long)b[0]);
  printf("the own-term rule: default scene, canopy, horizon shares, wall on both sides as stated\n");
}

/* the smoke slab's worst relative error against the closed form at slab spacing e */
static double smoke_slab_error(ics_render_model m, double e) {
  const double sigma = 1.7, T = 0.5, col[3] = {0.8, 0.6, 0.4}, Tc[3] = {0.5, 0.2, 0}, mu[2] = {0.3, -0.2};
  char j[1024];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [24, 24]},"
           " \"render\": {\"slab_spacing\": %.17g, \"d1\": 1},"
           " \"lights\": [{\"mean\": [%g, %g], \"cov\": [[0, 0], [0, 0]]}],"
           " \"materials\": {\"smoke\": {\"color\": [%g, %g, %g], \"extinction\": %g, \"transport\": [%g, %g, %g]},"
           "   \"white\": {\"color\": [1, 1, 1]}},"
           " \"objects\": [{\"shape\": \"box\", \"center\": [0, 0, 0.5], \"size\": [8, 8, %g], \"material\": \"smoke\"},"
           "   {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [8, 8], \"material\": \"white\"}]}",
           e, mu[0], mu[1], col[0], col[1], col[2], sigma, Tc[0], Tc[1], Tc[2], T);
  ics_scene *s = scene_from_json(j);
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = m;
  render_result r = render_scene(s, &rs, 2);
  double k = sqrt(1 + mu[0] * mu[0] + mu[1] * mu[1]), worst = 0;
  for (int c = 0; c < 3; c++) {
    double a = sigma + sigma * (1 - Tc[c]) * k;
    double want = sigma * col[c] * -expm1(-a * T) / a + exp(-sigma * T) * exp(-sigma * (1 - Tc[c]) * k * T);
    for (int i = 0; i < 24 * 24; i++) { /* (a NaN stays: it fails the check) */
      double e = fabs(r.img->data[4 * i + c] / want - 1);
      if (!(e <= worst) && !isnan(worst)) worst = e;
    }
  }
  ics_image_destroy(r.img);
  ics_scene_destroy(s);
  return worst;
}

static void test_volume_own_term(void) {
  const double spacings[3] = {0.01, 0.07, 0.29};
  for (int k = 0; k < 3; k++)
    for (int m = ICS_MODEL_PATEL; m <= ICS_MODEL_SURFACE; m += ICS_MODEL_SURFACE - ICS_MODEL_PATEL) {
      double e = smoke_slab_error((ics_render_model)m, spacings[k]);
      printf("a coloured smoke slab, spacing %.2f, %s: worst relative error %.2g\n", spacings[k],
             ics_render_model_name((ics_render_model)m), e);
      if (m == ICS_MODEL_SURFACE)
        CHECK(e <= 1e-4, "surface: the smoke slab off its closed form by %.3g (at most 1e-4)", e);
      else
        CHECK(e > 1e-3, "the control (patel) should miss the slab's own attenuation: %.3g", e);
    }
}

/* the scene (JSON, destroyed here) rendered under model m with the visibility AOV; *ch: light
 * 0's channel in r.aov */
static render_result visibility_render(const char *json, ics_render_model m, int *ch) {
  ics_scene *s = scene_from_json(json);
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = m;
  render_result r = render_scene_aovs(s, &rs, 2, ICS_AOV_VISIBILITY);
  *ch = ics_exr_channel_index(r.aov, "light0.V");
  ics_scene_destroy(s);
  return r;
}

/* a straight edge at height d over a receiver, the light of mean (-1, 0) and variance 0.09 on
 * each axis (sigma 0.3): the receiver's visibility AOV against the closed form
 * V(x) = Phi((x / d - 1) / sigma) (a light direction X reaches x past the edge at x + X d),
 * RMS over the receiver pixels whose exact value lies in [0.02, 0.98] */
static double edge_penumbra_error(ics_render_model m, double d, int *n) {
  const double sigma = 0.3;
  char j[1024];
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [128, 96]},"
           " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1, \"seed\": 3},"
           " \"lights\": [{\"mean\": [-1, 0], \"var\": [%g, %g]}],"
           " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {}},"
           " \"objects\": [{\"shape\": \"rect\", \"center\": [-2, 0, %g], \"normal\": [0, 0, 1], \"size\": [4, 8], \"material\": \"black\"},"
           "  {\"shape\": \"rect\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"size\": [8, 8], \"material\": \"white\"}]}",
           sigma * sigma, sigma * sigma, d);
  int ch;
  render_result r = visibility_render(j, m, &ch);
  double sum = 0, px = 2.0 / 96;
  *n = 0;
  for (int jj = 0; jj < 96; jj++)
    for (int i = 0; i < 128; i++) {
      double x = (i + 0.5 - 64) * px, exact = 0.5 * erfc(-(x / d - 1) / sigma / sqrt(2));
      if (x <= 0 || exact < 0.02 || exact > 0.98) continue; /* (x <= 0: the edge itself in view) */
      double e = r.aov->data[((size_t)jj * 128 + i) * r.aov->count + ch] - exact;
      sum += e * e, (*n)++;
    }
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  return sqrt(sum / *n);
}

/* a solid box `thick` deep 0.5 above a receiver (none where thick = 0), seen head on, slab
 * spacing 0.02, the light of mean (-1, 0) and sigma 0.05: the receiver's largest visibility over
 * x in [0.05, 0.3], inside the box's shadow [-0.5, 0.5] (the box spans x in [-1, 0], shifted by
 * 0.5) and more than 4.5 penumbra widths (sqrt(d d1) sigma = 0.035) from its edge */
static double thin_solid_umbra(ics_render_model m, double thick) {
  char j[1024], box[256] = "";
  if (thick > 0)
    snprintf(box, sizeof box, "{\"shape\": \"box\", \"center\": [-0.5, 0, %g], \"size\": [1, 4, %g],"
             " \"material\": \"black\"},", 0.5 + thick / 2, thick);
  snprintf(j, sizeof j,
           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [96, 72]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 3},"
           " \"lights\": [{\"mean\": [-1, 0], \"var\": [0.0025, 0.0025]}],"
           " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {}},"
           " \"objects\": [%s"
           "  {\"shape\": \"rect\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"size\": [8, 8], \"material\": \"white\"}]}",
           box);
  int ch;
  render_result r = visibility_render(j, m, &ch);
  double worst = 0, px = 2.0 / 72;
  for (int jj = 0; jj < 72; jj++)
    for (int i = 0; i < 96; i++) {
      double x = (i + 0.5 - 48) * px;
      if (x >= 0.05 && x <= 0.3)
        worst = fmax(worst, r.aov->data[((size_t)jj * 96 + i) * r.aov->count + ch]);
    }
  ics_image_destroy(r.img);
  ics_exr_channels_destroy(r.aov);
  return worst;
}

/* a solid's interior darkens the light from the slab after the one its ray enters it in, or at
 * once where the ray leaves it in that slab: a box a fifth of a slab thick, one exactly a slab
 * thick (its back face on the next slab's front boundary) and two slabs thick all keep their
 * umbra; the control, no box, leaves the same pixels lit */
static void test_thin_solid(void) {
  const double thick[3] = {0.004, 0.02, 0.04};
  for (int m = ICS_MODEL_SOLID; m <= ICS_MODEL_BLOCKER; m++) {
    for (int k = 0; k < 3; k++) {
      double v = thin_solid_umbra((ics_render_model)m, thick[k]);
      printf("a solid %.3f thick (slabs of 0.02), %s: its umbra's visibility at most %.4f\n",
             thick[k], ics_render_model_name((ics_render_model)m), v);
      CHECK(v <= 0.01, "%s: light passes a solid %.3f thick: visibility %.4f (at most 0.01)",
            ics_render_model_name((ics_render_model)m), thick[k], v);
    }
    double lit = thin_solid_umbra((ics_render_model)m, 0);
    CHECK(lit >= 0.99, "the control (no box), %s: the pixels should be lit: %.4f", ics_render_model_name((ics_render_model)m), lit);
  }
}

static void test_blocker(void) {
  /* 0.1 lies below the sharp set's d1 / 4, whose penumbra is then too wide (d d1 / 4 > d^2) */
  const double heights[3] = {0.1, 0.3, 0.5}, bound[3] = {0.1, 0.02, 0.02};
  for (int h = 0; h < 3; h++)
    for (int m = ICS_MODEL_SURFACE; m <= ICS_MODEL_BLOCKER; m++) {
      int n;
      double e = edge_penumbra_error((ics_render_model)m, heights[h], &n);
      printf("an edge %.1f above a receiver, %s: %d penumbra pixels, RMS |V - exact| %.4f\n",
             heights[h], ics_render_model_name((ics_render_model)m), n, e);
      CHECK(n > (h ? 1000 : 500), "the penumbra holds %d pixels", n);
      if (m == ICS_MODEL_BLOCKER)
        CHECK(e <= bound[h], "blocker, edge %.1f: the penumbra off the closed form by %.4f RMS (at most %g)",
              heights[h], e, bound[h]);
      else
        CHECK(e > 0.05, "the control (surface), edge %.1f, should widen the penumbra: %.4f RMS",
              heights[h], e);
    }
}

static void no_solids(const char *name, ics_scene *s, ics_render_model last) {
  ics_render_settings rs = *ics_scene_settings(s);
  rs.model = ICS_MODEL_PATEL;
  render_result a = render_scene(s, &rs, 2);
  for (int m = ICS_MODEL_SOLID; m <= (int)last; m++) {
    rs.model = (ics_render_model)m;
    render_result b = render_scene(s, &rs, 2);
    CHECK(!memcmp(a.img->data, b.img->data, sizeof(float) * 4 * (size_t)a.img->width * a.img->height),
          "%s differs between patel and %s", name, ics_render_model_name(rs.model));
    ics_image_destroy(b.img);
  }
  printf("%s: patel to %s bit for bit\n", name, ics_render_model_name(last));
  ics_image_destroy(a.img);
  ics_scene_destroy(s);
}

static void test_no_solids(const char *disk) {
  no_solids("the disk scene (no closed object)", scene_from_file(disk), ICS_MODEL_SURFACE);
  no_solids("a closed sphere of transport [1, 0.2, 0.2] over a floor (not solid)",
            scene_from_json(
                "{\"camera\": {\"eye\": [0, 1.2, 3], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [64, 48]},"
                " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1},"
                " \"lights\": [{\"mean\": [0.6, 0.55], \"var\": [0.004, 0.004]}],"
                " \"materials\": {\"white\": {}, \"tint\": {\"transport\": [1, 0.2, 0.2]}},"
                " \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0.1, 0], \"radius\": 0.5, \"material\": \"tint\"},"
                "  {\"shape\": \"rect\", \"center\": [0, -0.4, 0], \"normal\": [0, 1, 0], \"size\": [6, 6], \"material\": \"white\"}]}"),
            ICS_MODEL_SOLID);
}

/* render.model auto: blocker while the volumes and solids fit the inside mask (64 opaque spheres;
 * 70 with 6 of them translucent or tinted, which are not solid; 60 of smoke and 4 opaque), patel
 * beyond (65 opaque spheres, or 60 of smoke and 5 opaque, which blocker refuses), with the
 * omission in the plan */
static void test_auto_solids(void) {
  const struct {
    int spheres, other, smoke;
    ics_render_model want;
  } cases[] = {{64, 0, 0, ICS_MODEL_BLOCKER}, {70, 6, 0, ICS_MODEL_BLOCKER},
               {64, 0, 60, ICS_MODEL_BLOCKER}, {65, 0, 0, ICS_MODEL_PATEL},
               {65, 0, 60, ICS_MODEL_PATEL}};
  for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
    char json[16384];
    int n = snprintf(json, sizeof json,
                     "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 4,"
                     " \"resolution\": [32, 32]}, \"render\": {\"slab_spacing\": 0.05, \"d1\": 1},"
                     " \"lights\": [{\"mean\": [0.1, 0.1], \"var\": [0.01, 0.01]}],"
                     " \"materials\": {\"m\": {}, \"t\": {\"opacity\": 0.5}, \"c\": {\"transport\": [0.5, 0.5, 0.5]},"
                     " \"v\": {\"extinction\": 1}}, \"objects\": [");
    for (int k = 0; k < cases[c].spheres; k++) { /* translucent and tinted by turns, smoke, opaque */
      const char *m = k < cases[c].other ? (k % 2 ? "c" : "t") : k < cases[c].other + cases[c].smoke ? "v" : "m";
      n += snprintf(json + n, sizeof json - (size_t)n,
                    "%s{\"shape\": \"sphere\", \"center\": [%g, %g, 0], \"radius\": 0.1,"
                    " \"material\": \"%s\"}", k ? ", " : "", -1.8 + 0.4 * (k % 10),
                    -1.8 + 0.4 * (k / 10), m);
    }
    snprintf(json + n, sizeof json - (size_t)n, "]}");
    ics_scene *s = scene_from_json(json);
    CHECK(ics_scene_settings(s)->model == ICS_MODEL_AUTO, "render.model absent: auto");
    ics_plan *p = plan_or_exit(s, NULL, 1);
    int omitted = 0;
    for (int i = 0; i < ics_plan_omitted_count(p); i++)
      omitted |= !strcmp(ics_plan_omitted_at(p, i)->name, "render.model blocker");
    printf("auto, %d spheres (%d not solid, %d smoke): %s%s\n", cases[c].spheres, cases[c].other, cases[c].smoke,
           ics_render_model_name(p->rs.model), omitted ? ", omitted render.model blocker" : "");
    CHECK(p->model_auto && p->rs.model == cases[c].want && omitted == (cases[c].want == ICS_MODEL_PATEL),
          "auto, %d spheres: %s, want %s (omission listed: %d)", cases[c].spheres,
          ics_render_model_name(p->rs.model), ics_render_model_name(cases[c].want), omitted);
    ics_plan_destroy(p);
    ics_scene_destroy(s);
  }
}

/* render.model auto planned for a renderer (ics_plan_opts.renderer): blocker for cpu, patel for
 * mc (it ignores the model: the plan that costs least), with the plan's memory then Patel's and
 * no "render.model blocker" omission (that one is for too many volumes and solids); without a
 * renderer, blocker */
static void test_auto_renderer(void) {
  ics_scene *s = default_scene_96x72();
  ics_render_settings patel = *ics_scene_settings(s);
  patel.model = ICS_MODEL_PATEL;
  ics_plan *pp = plan_or_exit(s, &patel, 1);
  const char *const backends[] = {"cpu", "mc", NULL};
  const ics_render_model want[] = {ICS_MODEL_BLOCKER, ICS_MODEL_PATEL, ICS_MODEL_BLOCKER};
  for (int b = 0; b < 3; b++) {
    char msg[512] = "";
    ics_renderer *r = NULL;
    ics_render_opts ro = {.backend = backends[b]};
    if (backends[b] && ics_renderer_create(&r, &ro, msg, sizeof msg) != ICS_OK) {
      CHECK(0, "renderer %s: %s", backends[b], msg);
      continue;
    }
    ics_plan_opts po = {.threads = 1, .width = 96, .height = 72, .renderer = r};
    ics_plan *p = NULL;
    CHECK(ics_plan_create(&p, s, &po, msg, sizeof msg) == ICS_OK, "plan: %s", msg);
    if (p) {
      printf("auto planned for %s: %s, %zu bytes (patel's %zu)\n", backends[b] ? backends[b] : "no renderer",
             ics_render_model_name(p->rs.model), ics_plan_memory_bytes(p), ics_plan_memory_bytes(pp));
      CHECK(p->model_auto && p->rs.model == want[b], "auto for %s: %s, want %s",
            backends[b] ? backends[b] : "no renderer", ics_render_model_name(p->rs.model),
            ics_render_model_name(want[b]));
      CHECK((want[b] == ICS_MODEL_PATEL) == (ics_plan_memory_bytes(p) == ics_plan_memory_bytes(pp)),
            "auto for %s: memory %zu, patel's %zu", backends[b] ? backends[b] : "no renderer",
            ics_plan_memory_bytes(p), ics_plan_memory_bytes(pp));
      for (int i = 0; i < ics_plan_omitted_count(p); i++)
        CHECK(strcmp(ics_plan_omitted_at(p, i)->name, "render.model blocker"),
              "auto for %s: omits render.model blocker (%s)", backends[b] ? backends[b] : "no renderer",
              ics_plan_omitted_at(p, i)->reason);
    }
    ics_plan_destroy(p);
    ics_renderer_destroy(r);
  }
  ics_plan_destroy(pp);
  ics_scene_destroy(s);
}

int main(int argc, char **argv) {
  test_auto_solids();
  test_auto_renderer();
  test_patel_unchanged();
  test_solid();
  test_own_term();
  test_open_own_term();
  test_own_rule();
  test_volume_own_term();
  test_thin_solid();
  test_blocker();
  if (argc > 1) test_no_solids(argv[1]);
  return test_summary("test_render_model");
}
