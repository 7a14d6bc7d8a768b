/* test_render_repro.c — reproducibility of the CPU backend: the same scene renders to the same
 * bits with 1, 2 and 3 threads (every per-pixel quantity is a function of (seed, slab, pixel)),
 * twice in a row, and a different seed changes the stochastic kernel's image (so the seed is
 * really used). The default scene at 96 x 72 (a volume with fBm detail, a torus, per-pixel
 * random ellipse taps for one light) and the contract example with per-pixel random taps. One
 * renderer rendering frames of several scenes, sizes and models in turn (its memory kept from
 * frame to frame, grown and renewed; its slab kernels kept where a frame's lights, pixel size
 * and kernel settings are the last frame's, and only there) gives each the bits, AOVs
 * included, of a new renderer;
 * `test_render_repro DISK.json --frames` runs that part alone (CTest test_render_frames, fast:
 * the AddressSanitizer run sees the kept memory's guards). */
#include <string.h>

#include "plan_internal.h"
#include "render_util.h"
#include "testutil.h"

static int same(const ics_image *a, const ics_image *b) {
  return a->width == b->width && a->height == b->height &&
         !memcmp(a->data, b->data, sizeof(float) * 4 * (size_t)a->width * a->height);
}

static double diff_max(const ics_image *a, const ics_image *b) {
  double m = 0;
  for (size_t i = 0; i < 4 * (size_t)a->width * a->height; i++)
    m = fmax(m, fabs(a->data[i] - b->data[i]));
  return m;
}

static void check_scene(const char *name, ics_scene *s, const ics_render_settings *rs) {
  render_result r1 = render_scene(s, rs, 1), r2 = render_scene(s, rs, 2),
                r3 = render_scene(s, rs, 3), again = render_scene(s, rs, 2);
  CHECK(same(r1.img, r2.img), "%s: 1 vs 2 threads differ (max %.3g)", name, diff_max(r1.img, r2.img));
  CHECK(same(r1.img, r3.img), "%s: 1 vs 3 threads differ (max %.3g)", name, diff_max(r1.img, r3.img));
  CHECK(same(r2.img, again.img), "%s: two renders differ", name);
  ics_render_settings other = rs ? *rs : *ics_scene_settings(s);
  other.seed ^= 0x5eed;
  render_result r4 = render_scene(s, &other, 2);
  double d = diff_max(r2.img, r4.img);
  CHECK(d > 1e-4, "%s: another seed gives the same image (max difference %.3g)", name, d);
  printf("%s: 1, 2, 3 threads bit-identical; another seed differs by up to %.3g\n", name, d);
  ics_image_destroy(r1.img);
  ics_image_destroy(r2.img);
  ics_image_destroy(r3.img);
  ics_image_destroy(again.img);
  ics_image_destroy(r4.img);
}

static int same_aovs(const ics_exr_channels *a, const ics_exr_channels *b) {
  return a->width == b->width && a->height == b->height && a->count == b->count &&
         !memcmp(a->data, b->data, sizeof(float) * (size_t)a->count * a->width * a->height);
}

/* frames of (scene, settings, size) in turn on one renderer, each against a new renderer's */
typedef struct {
  const char *name;
  const ics_scene *s;
  const ics_render_settings *rs;
  int w, h;
  int kept; /* the slab kernels its plan takes from the renderer's last (kernel_cache.h) */
} frame_case;

/* the default scene at 96 x 72 with its first light's mean moved (its text edited; exits 2 when
 * that text has changed shape) */
static ics_scene *default_light_moved(void) {
  const char *txt = ics_scene_default_json();
  char *t = malloc(strlen(txt) + 1), *res = NULL, *mean = NULL;
  if (t) strcpy(t, txt), res = strstr(t, "[320, 240]"), mean = strstr(t, "\"mean\": [-0.4, 0.5]");
  if (!res || !mean) {
    fprintf(stderr, "test_render_repro: the default scene's resolution or first light not found\n");
    exit(2);
  }
  memcpy(res, "[ 96,  72]", 10);
  memcpy(mean, "\"mean\": [-0.3, 0.5]", 19);
  ics_scene *s = scene_from_json(t);
  free(t);
  return s;
}

static void check_one_renderer(const frame_case *c, int n) {
  char msg[4096];
  ics_render_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.backend = "cpu";
  ro.threads = 2;
  ics_renderer *r;
  if (ics_renderer_create(&r, &ro, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "renderer: %s\n", msg);
    exit(2);
  }
  const unsigned aovs = ICS_AOV_VISIBILITY | ICS_AOV_DEPTH;
  for (int i = 0; i < n; i++) {
    ics_plan *p = plan_for_or_exit(c[i].s, c[i].rs, 2, c[i].w, c[i].h, r);
    CHECK(p->kernels_kept == c[i].kept, "frame %d (%s %dx%d): %d slab kernels kept from the last "
          "frame, expected %d", i + 1, c[i].name, c[i].w, c[i].h, p->kernels_kept, c[i].kept);
    ics_image *img;
    ics_exr_channels *aov;
    if (ics_renderer_render_aovs(r, p, aovs, &img, &aov, NULL, msg, sizeof msg) != ICS_OK) {
      fprintf(stderr, "render: %s\n", msg);
      exit(2);
    }
    render_result fresh = render_scene_sized_on("cpu", c[i].s, c[i].rs, 2, aovs, c[i].w, c[i].h);
    CHECK(same(img, fresh.img) && same_aovs(aov, fresh.aov),
          "frame %d (%s %dx%d) on one renderer differs from a new renderer's (max %.3g)", i + 1,
          c[i].name, c[i].w, c[i].h, diff_max(img, fresh.img));
    ics_image_destroy(img);
    ics_image_destroy(fresh.img);
    ics_exr_channels_destroy(aov);
    ics_exr_channels_destroy(fresh.aov);
    ics_plan_destroy(p);
  }
  ics_renderer_destroy(r);
  printf("one renderer, %d frames in turn: each the bits of a new renderer's\n", n);
}

int main(int argc, char **argv) {
  ics_scene *s = default_scene_96x72();
  int frames_only = argc > 2 && !strcmp(argv[2], "--frames"); /* (the ASan run's: CTest
                                                                  test_render_frames) */
  if (!frames_only) check_scene("default scene 96x72", s, NULL);
  if (argc > 1) {
    ics_scene *d = scene_from_file(argv[1]);
    ics_render_settings rs = *ics_scene_settings(d);
    rs.compensate = ICS_RC_NONE; /* per-pixel random ellipse taps (the default falls back) */
    if (!frames_only) check_scene("contract example, per-pixel ellipse taps", d, &rs);
    ics_render_settings patel = *ics_scene_settings(s);
    patel.model = ICS_MODEL_PATEL;
    ics_render_settings dense = *ics_scene_settings(s), far = *ics_scene_settings(s),
                        seed = *ics_scene_settings(s), four = *ics_scene_settings(s),
                        nonneg = *ics_scene_settings(s), integer = *ics_scene_settings(s),
                        lut = *ics_scene_settings(s), rot4 = *ics_scene_settings(s),
                        wide = *ics_scene_settings(s), poisson = *ics_scene_settings(s);
    dense.dense = 1;
    /* each changes every kernel (the settings ics_slab_kernel_key_of reads, one at a time) */
    far.d1 *= 1.5, seed.seed += 1, four.samples = 4, nonneg.compensate = ICS_RC_NONNEG;
    integer.compensate = ICS_RC_INTEGER, lut.lut_radii = 1, rot4.pixel_rotations = 4;
    wide.slab_spacing *= 1.2, poisson.kernel = ICS_RK_POISSON;
    ics_scene *moved = default_light_moved();
    /* grown (160 x 120: 20 MB); its memory taken again, stale, by frames needing over half of
     * it (128 x 96, 140 x 105 dense, 256 x 192 under patel: one set of buffers instead of
     * four); renewed for a frame under half (the contract example), taken again by 32 x 24,
     * grown again (96 x 72). The kernels: a light's and its sharp set's under blocker (patel:
     * the light's alone, the sharp sets' left as they were, so the blocker frame after it
     * finds all four); kept where only the frame repeats, the model or render.dense changes,
     * none where the size (the pixel), d1, the seed, the samples, a light, the compensation,
     * the LUT radii, the rotations per pixel, the slab spacing or the kernel do; copies of
     * every kind of kernel (table, taps with fixed compensated taps, integer) kept and used */
    frame_case frames[] = {
        {"default", s, NULL, 96, 72, 0},           {"default", s, NULL, 160, 120, 0},
        {"default", s, NULL, 128, 96, 0},          {"default dense", s, &dense, 140, 105, 0},
        {"default patel", s, &patel, 256, 192, 0}, {"contract", d, &rs, 0, 0, 0},
        {"default", s, NULL, 32, 24, 0},           {"default", s, NULL, 96, 72, 0},
        {"default", s, NULL, 96, 72, 4},           {"default dense", s, &dense, 96, 72, 4},
        {"default patel", s, &patel, 96, 72, 2},   {"default", s, NULL, 96, 72, 4},
        {"default d1 x 1.5", s, &far, 96, 72, 0},  {"default", s, NULL, 96, 72, 0},
        {"default seed + 1", s, &seed, 96, 72, 0}, {"default", s, NULL, 96, 72, 0},
        {"default 4 samples", s, &four, 96, 72, 0}, {"default", s, NULL, 96, 72, 0},
        {"default, light 0 moved", moved, NULL, 96, 72, 2}, {"default", s, NULL, 96, 72, 2},
        {"default nonneg", s, &nonneg, 96, 72, 0}, {"default nonneg", s, &nonneg, 96, 72, 4},
        {"default", s, NULL, 96, 72, 0},           {"default integer", s, &integer, 96, 72, 0},
        {"default integer", s, &integer, 96, 72, 4}, {"default", s, NULL, 96, 72, 0},
        {"default LUT radii", s, &lut, 96, 72, 0}, {"default", s, NULL, 96, 72, 0},
        {"default 4 rotations", s, &rot4, 96, 72, 0}, {"default", s, NULL, 96, 72, 0},
        {"default e x 1.2", s, &wide, 96, 72, 0},  {"default", s, NULL, 96, 72, 0},
        {"default poisson", s, &poisson, 96, 72, 0}, {"default poisson", s, &poisson, 96, 72, 4},
        {"default", s, NULL, 96, 72, 0},
    };
    int n = (int)(sizeof frames / sizeof *frames);
    for (int i = 0; i < n && frames_only; i++) /* half the sides under ASan: three reuses */
      frames[i].w /= 2, frames[i].h /= 2;
    check_one_renderer(frames, n);
    ics_scene_destroy(moved);
    ics_scene_destroy(d);
  }
  ics_scene_destroy(s);
  return test_summary("test_render_repro");
}
