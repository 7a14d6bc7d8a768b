/* test_render_mc.c — the Monte-Carlo reference (backend "mc") where the answer is known, each
 * check stated in units of the standard error:
 * - the contract example's disk against Eq. 4 (tests/disk_eq4.h): a white receiver's value is
 *   the visibility V, and one sample of it is Bernoulli(V), so its exact standard error is
 *   sqrt(V (1 - V) / n); the z-scores over the penumbra must have mean square in [0.85, 1.15] and
 *   none beyond 5.5, the reported standard errors must match the exact ones within 5 %, and a
 *   control (the reference with 20 % more variance: mean square 1.8 at 256 spp) must fall
 *   outside that window;
 * - a laterally infinite slab of smoke (constant extinction, and the same extinction through a
 *   transfer function whose majorant is twice it, so delta and ratio tracking take null
 *   collisions) over a white receiver, a point light: the closed form
 *   C_c = sigma col_c (1 - exp(-a_c l)) / a_c + exp(-sigma l) exp(-sigma (1 - T_c) k l),
 *   a_c = sigma + sigma (1 - T_c) k, k = sqrt(1 + |mu|^2); the mean over all pixels within 4
 *   standard errors of the mean, per channel;
 * - a two-light scene against the sum of its one-light renders (independent seeds): the
 *   per-pixel z-scores' mean square in [0.8, 1.25], none beyond 6;
 * - a surface is lit only from its viewed side: a plane seen obliquely (normal (0, 0.8, 0.6),
 *   camera along -z) under a light whose directions straddle it, X_y ~ N(-0.8, 0.01): the light
 *   reaches the viewed side for 0.8 X_y + 0.6 > 0, so V = Phi(-0.5) = 0.30854 (mean over the
 *   plane's pixels within 4 standard errors);
 * - the same slab resting on the receiver, listed before and after it (coincident crossings);
 * - the depth AOV behind smoke every walk ends in; an occluder behind the eye casts no shadow;
 * - 1 and 2 threads bit-identical; the detail bounds hold on 200000 random points; a noise stop
 *   ends at or below its noise; the stderr AOV is refused by the slab renderer. */
#include <math.h>
#include <string.h>

#include "detail.h"
#include "disk_eq4.h"
#include "mc_trace.h"
#include "render_util.h"
#include "testutil.h"

static const char *disk_json =
    "{\"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 2], \"target\": [0, 0, 0],"
    " \"up\": [0, 1, 0], \"height\": 3.0, \"resolution\": [128, 128]},"
    " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1.0, \"kernel\": \"ellipse\", \"samples\": 2, \"seed\": 7},"
    " \"lights\": [{\"mean\": [0.3, -0.1], \"cov\": [[0.02, 0.005], [0.005, 0.01]]}],"
    " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {\"color\": [1, 1, 1]}},"
    " \"objects\": [{\"shape\": \"disk\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"radius\": 0.5, \"material\": \"black\"},"
    "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 3], \"material\": \"white\"}]}";

static render_result mc_render(const char *json, int spp, int threads, unsigned aovs) {
  ics_scene *s = scene_from_json(json);
  char msg[4096];
  ics_plan *p = plan_or_exit(s, NULL, threads);
  ics_render_opts ro = {.backend = "mc", .threads = threads, .spp = spp};
  ics_renderer *rr;
  render_result r = {0};
  if (ics_renderer_create(&rr, &ro, msg, sizeof msg) != ICS_OK ||
      ics_renderer_render_aovs(rr, p, aovs, &r.img, &r.aov, &r.stats, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "mc render: %s\n", msg);
    exit(2);
  }
  ics_renderer_destroy(rr);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
  return r;
}

static void release(render_result *r) {
  ics_image_destroy(r->img);
  ics_exr_channels_destroy(r->aov);
}

static void test_disk(void) {
  enum { N = 256 };
  render_result r = mc_render(disk_json, N, 0, ICS_AOV_STDERR);
  int W = r.img->width, H = r.img->height, ie = ics_exr_channel_index(r.aov, "stderr.R");
  CHECK(r.stats.spp == N && ie >= 0, "spp %d, stderr.R channel %d", r.stats.spp, ie);
  const double mu[2] = {0.3, -0.1}, S[3] = {0.02, 0.005, 0.01}, S2[3] = {0.024, 0.006, 0.012};
  double z2 = 0, z2_control = 0, zmax = 0, ratio = 0;
  int n = 0, wi = -1, wj = -1;
  for (int j = 0; j < H; j++)
    for (int i = 0; i < W; i++) {
      double x = ((i + 0.5) / W - 0.5) * 3, y = (0.5 - (j + 0.5) / H) * 3;
      if (x * x + y * y < 0.3) continue; /* the disk and its edge */
      double V = 1 - p_disk(x + mu[0], y + mu[1], S, 0.5);
      if (V < 0.02 || V > 0.98) continue;
      double Vc = 1 - p_disk(x + mu[0], y + mu[1], S2, 0.5);
      double v = r.img->data[((size_t)j * W + i) * 4], se = sqrt(V * (1 - V) / N);
      double z = (v - V) / se, zc = (v - Vc) / se;
      z2 += z * z, z2_control += zc * zc, n++;
      ratio += r.aov->data[((size_t)j * W + i) * r.aov->count + ie] / se;
      if (fabs(z) > zmax) zmax = fabs(z), wi = i, wj = j;
    }
  z2 /= n, z2_control /= n, ratio /= n;
  printf("disk (%d spp, %d penumbra pixels): mean z^2 %.3f (control, 20%% more variance: %.3f), "
         "max |z| %.2f at (%d, %d), reported / exact standard error %.4f\n",
         N, n, z2, z2_control, zmax, wi, wj, ratio);
  CHECK(n > 1000, "only %d penumbra pixels", n);
  CHECK(z2 >= 0.85 && z2 <= 1.15, "disk: mean z^2 %.3f outside [0.85, 1.15]", z2);
  CHECK(zmax <= 5.5, "disk: |z| %.2f at (%d, %d)", zmax, wi, wj);
  CHECK(fabs(ratio - 1) <= 0.05, "disk: reported standard errors %.4f x the exact ones", ratio);
  CHECK(z2_control > 1.15, "disk control: mean z^2 %.3f inside the window: the check cannot see a "
        "20 %% variance error", z2_control);
  release(&r);
}

/* layout: 0 the slab floating, 1 the same through a transfer function, 2 and 3 the slab resting on
 * the receiver (its bottom face at the receiver's depth), listed before and after it: the shading
 * point lies on the volume's boundary, so its shadow ray's volume state must come from its own
 * crossings, whatever order the two coincident crossings sort in */
static void test_slab(int layout) {
  const int through_transfer = layout == 1;
  const double sigma = 1.5, l = 0.8, col[3] = {0.8, 0.6, 0.4}, T[3] = {0.5, 0.2, 0};
  const double mu[2] = {0.3, -0.2}, k = sqrt(1 + mu[0] * mu[0] + mu[1] * mu[1]);
  char json[4096];
  const char *receiver_first = "{\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [20, 20], \"material\": \"white\"}, ",
             *receiver_last = ", {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [20, 20], \"material\": \"white\"}";
  static const char *const what[4] = {"", " (transfer, null collisions)", " (on the receiver, listed first)",
                                      " (on the receiver, listed after it)"};
  /* through_transfer: detail value 0.3 everywhere (scale 0), mapped to half the extinction
   * scale of the transfer function's top node, so the majorant is twice the extinction */
  snprintf(json, sizeof json,
           "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [48, 48]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 11},"
           " \"lights\": [{\"mean\": [%g, %g], \"cov\": [[0, 0], [0, 0]]}],"
           " \"materials\": {\"smoke\": {\"color\": [%g, %g, %g], \"extinction\": %g, \"transport\": [%g, %g, %g]%s},"
           "  \"white\": {}},"
           " \"objects\": [%s{\"shape\": \"box\", \"center\": [0, 0, %g], \"size\": [20, 20, %g], \"material\": \"smoke\"}%s]}",
           mu[0], mu[1], col[0], col[1], col[2], through_transfer ? 2 * sigma : sigma, T[0], T[1], T[2],
           through_transfer
               ? ", \"detail\": {\"function\": \"perlin\", \"scale\": 0, \"bias\": 0.3},"
                 " \"transfer\": [[0, 0.8, 0.6, 0.4, 0], [0.3, 0.8, 0.6, 0.4, 0.5], [1, 0.8, 0.6, 0.4, 1]]"
               : "",
           layout == 3 ? receiver_first : "", layout >= 2 ? -1 + l / 2 : 0, l, layout == 3 ? "" : receiver_last);
  render_result r = mc_render(json, 64, 0, ICS_AOV_STDERR);
  int W = r.img->width, H = r.img->height, ie = ics_exr_channel_index(r.aov, "stderr.R");
  double worst = 0;
  for (int c = 0; c < 3; c++) {
    double a = sigma + sigma * (1 - T[c]) * k;
    double exact = sigma * col[c] * (1 - exp(-a * l)) / a + exp(-sigma * l) * exp(-sigma * (1 - T[c]) * k * l);
    double sum = 0, var = 0;
    for (int p = 0; p < W * H; p++) {
      sum += r.img->data[p * 4 + c];
      double se = r.aov->data[(size_t)p * r.aov->count + ie + c];
      var += se * se;
    }
    double mean = sum / (W * H), se = sqrt(var) / (W * H), z = (mean - exact) / se;
    printf("slab%s, channel %d: %.6f, exact %.6f (standard error %.2g, z %.2f)\n", what[layout], c,
           mean, exact, se, z);
    worst = fmax(worst, fabs(z));
  }
  CHECK(worst <= 4, "Beer-Lambert slab%s: |z| %.2f", what[layout], worst);
  release(&r);
}

static void test_own_side(void) {
  const char *json =
      "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [32, 32]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 13},"
      " \"lights\": [{\"mean\": [0, -0.8], \"cov\": [[0.01, 0], [0, 0.01]]}],"
      " \"materials\": {\"white\": {}},"
      " \"objects\": [{\"shape\": \"rect\", \"center\": [0, 0, 0], \"normal\": [0, 0.8, 0.6], \"size\": [10, 10], \"material\": \"white\"}]}";
  render_result r = mc_render(json, 64, 0, ICS_AOV_STDERR);
  int npx = r.img->width * r.img->height, ie = ics_exr_channel_index(r.aov, "stderr.R");
  double sum = 0, var = 0, exact = 0.5 * erfc(0.5 / sqrt(2));
  for (int p = 0; p < npx; p++) {
    sum += r.img->data[p * 4];
    double se = r.aov->data[(size_t)p * r.aov->count + ie];
    var += se * se;
  }
  double mean = sum / npx, se = sqrt(var) / npx, z = (mean - exact) / se;
  printf("plane lit from its viewed side only: V %.5f, exact %.5f (standard error %.2g, z %.2f)\n",
         mean, exact, se, z);
  CHECK(fabs(z) <= 4, "own side: |z| %.2f", fabs(z));
  release(&r);
}

/* the depth AOV is the first surface's, from the geometry alone: behind a smoke slab so dense that
 * every camera walk ends in it, the receiver at view depth 3 is still found at each pixel */
static void test_depth_behind_smoke(void) {
  const char *json =
      "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [16, 16]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 17},"
      " \"lights\": [{\"mean\": [0.1, 0], \"cov\": [[0.01, 0], [0, 0.01]]}],"
      " \"materials\": {\"smoke\": {\"extinction\": 200}, \"white\": {}},"
      " \"objects\": [{\"shape\": \"box\", \"center\": [0, 0, 0], \"size\": [20, 20, 0.8], \"material\": \"smoke\"},"
      "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [20, 20], \"material\": \"white\"}]}";
  render_result r = mc_render(json, 4, 0, ICS_AOV_DEPTH | ICS_AOV_VISIBILITY);
  int npx = r.img->width * r.img->height, iz = ics_exr_channel_index(r.aov, "Z"),
      iv = ics_exr_channel_index(r.aov, "light0.V");
  double worst = 0, vmax = 0;
  for (int p = 0; p < npx; p++) {
    worst = fmax(worst, fabs(r.aov->data[(size_t)p * r.aov->count + iz] - 3));
    vmax = fmax(vmax, r.aov->data[(size_t)p * r.aov->count + iv]);
  }
  printf("depth behind dense smoke: max |Z - 3| %.2g, max visibility %.2g (exp(-160) expected)\n", worst, vmax);
  CHECK(iz >= 0 && worst <= 1e-5, "depth behind smoke: |Z - 3| up to %g", worst);
  CHECK(iv >= 0 && vmax <= 1e-6, "visibility under dense smoke: %g", vmax);
  release(&r);
}

/* light enters at the eye plane: an opaque plane behind the camera, across every shadow ray,
 * casts no shadow (V = 1 exactly on the white receiver) */
static void test_behind_eye(void) {
  const char *json =
      "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [16, 16]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 19},"
      " \"lights\": [{\"mean\": [0.1, 0], \"cov\": [[0.01, 0], [0, 0.01]]}],"
      " \"materials\": {\"black\": {\"color\": [0, 0, 0]}, \"white\": {}},"
      " \"objects\": [{\"shape\": \"rect\", \"center\": [0, 0, 3], \"normal\": [0, 0, 1], \"size\": [100, 100], \"material\": \"black\"},"
      "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [20, 20], \"material\": \"white\"}]}";
  render_result r = mc_render(json, 4, 0, 0);
  int npx = r.img->width * r.img->height;
  double worst = 0;
  for (int p = 0; p < npx; p++) worst = fmax(worst, fabs(r.img->data[p * 4] - 1));
  printf("an occluder behind the eye: max |V - 1| %.2g\n", worst);
  CHECK(worst <= 1e-6, "an occluder behind the eye darkens the receiver: |V - 1| up to %g", worst);
  release(&r);
}

static const char *two_lights(int which) {
  static char json[4096];
  const char *a = "{\"mean\": [0.2, 0], \"cov\": [[0.01, 0], [0, 0.01]], \"color\": [1, 0.2, 0.2], \"weight\": 0.7}";
  const char *b = "{\"mean\": [-0.1, 0.2], \"cov\": [[0.02, 0], [0, 0.005]], \"color\": [0.2, 0.2, 1], \"weight\": 0.5}";
  snprintf(json, sizeof json,
           "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 3.0, \"resolution\": [48, 48]},"
           " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1.0, \"seed\": %d},"
           " \"lights\": [%s%s%s],"
           " \"materials\": {\"tint\": {\"color\": [0.3, 0.3, 0.3], \"opacity\": 0.6, \"transport\": [1, 0.5, 0]},"
           "  \"smoke\": {\"extinction\": 3, \"detail\": {\"function\": \"fbm\", \"frequency\": 3, \"octaves\": 3}},"
           "  \"white\": {}},"
           " \"objects\": [{\"shape\": \"disk\", \"center\": [0.5, 0.5, 0], \"normal\": [0, 0, 1], \"radius\": 0.4, \"material\": \"tint\"},"
           "  {\"shape\": \"sphere\", \"center\": [-0.5, -0.4, -0.3], \"radius\": 0.4, \"material\": \"smoke\"},"
           "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [2.5, 2.5], \"material\": \"white\"}]}",
           which + 1, which != 2 ? a : "", which == 0 ? ", " : "", which != 1 ? b : "");
  return json;
}

static void test_two_lights(void) {
  enum { N = 128 };
  render_result ab = mc_render(two_lights(0), N, 0, ICS_AOV_STDERR);
  render_result a = mc_render(two_lights(1), N, 0, ICS_AOV_STDERR);
  render_result b = mc_render(two_lights(2), N, 0, ICS_AOV_STDERR);
  int npx = ab.img->width * ab.img->height, ie = ics_exr_channel_index(ab.aov, "stderr.R");
  double z2 = 0, zmax = 0;
  int n = 0, exact_bad = 0;
  for (int p = 0; p < npx; p++)
    for (int c = 0; c < 3; c++) {
      double d = ab.img->data[p * 4 + c] - a.img->data[p * 4 + c] - b.img->data[p * 4 + c];
      double s1 = ab.aov->data[(size_t)p * ab.aov->count + ie + c],
             s2 = a.aov->data[(size_t)p * a.aov->count + ie + c],
             s3 = b.aov->data[(size_t)p * b.aov->count + ie + c], se = sqrt(s1 * s1 + s2 * s2 + s3 * s3);
      if (se == 0) {
        exact_bad += fabs(d) > 1e-6;
        continue;
      }
      double z = d / se;
      z2 += z * z, n++;
      zmax = fmax(zmax, fabs(z));
    }
  z2 /= n;
  printf("two lights vs the sum of one-light renders (%d spp, %d noisy values): mean z^2 %.3f, "
         "max |z| %.2f; %d noise-free values off by > 1e-6\n", N, n, z2, zmax, exact_bad);
  CHECK(n > 1000 && z2 >= 0.8 && z2 <= 1.25, "two lights: mean z^2 %.3f over %d values", z2, n);
  CHECK(zmax <= 6, "two lights: |z| %.2f", zmax);
  CHECK(exact_bad == 0, "two lights: %d noise-free values differ", exact_bad);
  release(&ab), release(&a), release(&b);
}

static void test_threads_and_stops(void) {
  render_result r1 = mc_render(two_lights(0), 8, 1, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH | ICS_AOV_STDERR);
  render_result r2 = mc_render(two_lights(0), 8, 2, ICS_AOV_VISIBILITY | ICS_AOV_DEPTH | ICS_AOV_STDERR);
  size_t npx = (size_t)r1.img->width * r1.img->height;
  CHECK(!memcmp(r1.img->data, r2.img->data, sizeof(float) * npx * 4) &&
            r1.aov->count == r2.aov->count &&
            !memcmp(r1.aov->data, r2.aov->data, sizeof(float) * npx * r1.aov->count),
        "1 and 2 threads differ");
  release(&r1), release(&r2);
  /* a noise stop */
  ics_scene *s = scene_from_json(disk_json);
  char msg[512];
  ics_plan *p;
  CHECK(ics_plan_create(&p, s, NULL, msg, sizeof msg) == ICS_OK, "plan: %s", msg);
  ics_render_opts ro = {.backend = "mc", .noise = 0.02};
  ics_renderer *rr;
  ics_image *img = NULL;
  ics_render_stats st;
  CHECK(ics_renderer_create(&rr, &ro, msg, sizeof msg) == ICS_OK &&
            ics_renderer_render(rr, p, &img, &st, msg, sizeof msg) == ICS_OK,
        "noise stop: %s", msg);
  printf("noise stop at 0.02: %d spp, noise %.4f\n", st.spp, st.noise);
  CHECK(st.noise <= 0.02 && st.spp >= 2, "noise stop: %d spp, noise %g", st.spp, st.noise);
  ics_image_destroy(img);
  ics_renderer_destroy(rr);
  /* refusals */
  ro.noise = 0, ro.spp = (1 << 24) + 1;
  CHECK(ics_renderer_create(&rr, &ro, msg, sizeof msg) == ICS_OK, "renderer");
  img = (ics_image *)&msg;
  CHECK(ics_renderer_render(rr, p, &img, NULL, msg, sizeof msg) == ICS_ERR_INVALID_ARG && img == NULL &&
            strstr(msg, "samples per pixel"), "spp out of range refused: %s", msg);
  ics_renderer_destroy(rr);
  ics_render_opts rc = {.backend = "cpu"};
  ics_exr_channels *aov = NULL;
  CHECK(ics_renderer_create(&rr, &rc, msg, sizeof msg) == ICS_OK, "cpu renderer");
  CHECK(ics_renderer_render_aovs(rr, p, ICS_AOV_STDERR, &img, &aov, NULL, msg, sizeof msg) ==
            ICS_ERR_UNSUPPORTED && strstr(msg, "only mc estimates a standard error"),
        "stderr AOV on cpu refused: %s", msg);
  ics_renderer_destroy(rr);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

/* the detail bounds (the majorants rest on them) against random points */
static void test_bounds(void) {
  ics_detail ds[3];
  memset(ds, 0, sizeof ds);
  ds[0].fn = ICS_DETAIL_PERLIN;
  ds[1].fn = ICS_DETAIL_FBM, ds[1].octaves = 5, ds[1].gain = 0.5, ds[1].lacunarity = 2;
  ds[2].fn = ICS_DETAIL_RIDGED, ds[2].octaves = 4, ds[2].gain = 2, ds[2].lacunarity = 2, ds[2].offset = 1;
  for (int k = 0; k < 3; k++) {
    ds[k].frequency = 1.7, ds[k].scale = 1, ds[k].seed = 5 + k;
    ics_detail_eval e;
    double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, worst = 0;
    ics_detail_prepare(&e, &ds[k], lo, hi);
    ics_rng r;
    ics_rng_init(&r, 99, (uint64_t)k);
    for (int i = 0; i < 200000; i++) {
      double p[3] = {20 * ics_rng_uniform(&r) - 10, 20 * ics_rng_uniform(&r) - 10, 20 * ics_rng_uniform(&r) - 10};
      worst = fmax(worst, fabs(ics_detail_value(&e, p)));
    }
    double b = ics_detail_bound(&ds[k]);
    printf("detail %d: max |f| %.4f on 200000 points, bound %.4f\n", k, worst, b);
    CHECK(worst <= b, "detail %d: |f| %.4f above the bound %.4f", k, worst, b);
  }
}

int main(void) {
  gl_init(GL_N);
  test_bounds();
  test_disk();
  for (int layout = 0; layout < 4; layout++) test_slab(layout);
  test_two_lights();
  test_own_side();
  test_depth_behind_smoke();
  test_behind_eye();
  test_threads_and_stops();
  return test_summary("test_render_mc");
}
