/* test_kernel_c.c — the shared kernel source (gpu/kernel) compiled as C11: the headers that only
 * the cl and gl programs use (detail_value.h, shade.h, class_sum.h) build here against the
 * device records the host packs (device_scene.c), and their values equal the host's own:
 *   - ics_k_detail_value on every detail object of scenes/volumes.json (improved noise, fBm,
 *     ridged multifractal, a grid file), as written and with the noise moving in time and a
 *     ridged offset, equals ics_detail_value (gpu/core/detail.c) bit for bit, at points inside,
 *     around and far outside each object's box, and on the lattice;
 *   - ics_k_volume_sig equals the cpu backend's extinction (ics_material_transfer or
 *     ics_material_preintegrate of the host's detail values) x the material's extinction, bit
 *     for bit, with and without pre-integration;
 *   - ics_k_class_sum over a 3 x 3 buffer equals the weighted sum written out by hand, the
 *     reads clamped at the edges;
 *   - ics_k_plan_ray (camera.h) through the packed camera, and ics_plan_ray, equal the camera
 *     ray written out in this file from the plan's camera, orthographic and perspective.
 * A wrong record offset, a wrong drift constant or a changed operation order in the shared text
 * fails here on a machine without OpenCL or OpenGL (checked: the drift's y constant changed
 * in its last digit fails the noise comparisons). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "detail.h"
#include "icshadow/constants.h"
#include "device_scene.h"
#include "render_util.h"
#include "testutil.h"

/* the view: the device records, as slab.cl reads them */
typedef struct kernel_view {
  const ics_device_scene *d;
  int preintegrate, nlights, nch, k, W, H, pad_l, pad_t; /* shade.h's arguments */
  int aov_count, aov_vis, aov_z;
  double zf, zb, window_max;
  const float *src; /* class_sum: a 3 x 3 buffer and its taps */
  const int *tx, *ty;
  const float *tw;
} kernel_view;
#define ICS_VIEW_PARAM const kernel_view *V,
#define ICS_VIEW_ARG V,
#define ICS_OBJ(ob, f) V->d->obj[ICS_DEV_OBJ_STRIDE * (ob) + (f)]
#define ICS_TT(i) V->d->tt[i]
#define ICS_PERM(i) V->d->perm[i]
#define ICS_GRID(i) V->d->grids[i]
#define ICS_CAM(f) V->d->cam[f]
#define ICS_VOLOBJ(i) V->d->vol_obj[i]
#define ICS_LPATH(l) 1.0
#define ICS_LMU(i) V->d->lmu[i]
#define ICS_WINDOW(l) 0.0
#define ICS_DST(l, c, q) dst_unused[(l)*0 + (c)*0 + (q)*0] /* not called */
#define ICS_ARG(name) V->name
#define ICS_JITTER(k, p) ((void)(k), (void)(p), 0.5)
#define ICS_FZ(f) ((void)(f), 0.0f) /* ics_k_shade_pixel is compiled here, not called */
#define ICS_FCODE(f) ((void)(f), 0u)
#define ICS_FGRAD(f) ((void)(f), grad_unused)
#define ICS_FSPAN(f) ((void)(f), 0)
#define ICS_LCOL(i) ((void)(i), 1.0)
#define ICS_AOV(pi, i) dst_unused[(pi) * 0 + (i) * 0]
#define ICS_AOV_SEEN(pi) dst_unused[(pi) * 0]
#define ICS_TAP_X(m) V->tx[m]
#define ICS_TAP_Y(m) V->ty[m]
#define ICS_TAP_W(m) V->tw[m]
#define ICS_SRC(c, i) V->src[(c)*9 + (i)]
#define ICS_AT(x, y) ((y)*3 + (x))
#define ICS_BW 3
#define ICS_BH 3
static float dst_unused[1];
static const struct {
  float x, y;
} grad_unused;
#include "kernel/class_sum.h"
#include "kernel/shade.h"

/* a point in [-spread, spread] */
static double spread_point(double spread) { return spread * (2 * test_rng_unit() - 1); }

static void test_detail(const ics_plan *P, const ics_device_scene *d, const ics_scene *s,
                        int expected) {
  kernel_view V = {.d = d};
  int nobj = ics_scene_object_count(s), tested = 0;
  for (int o = 0; o < nobj; o++) {
    const ics_object *ob = ics_scene_object(s, o);
    const ics_material *m = ics_scene_material(s, ob->material);
    if (m->detail.fn == ICS_DETAIL_NONE) continue;
    tested++;
    double worst = 0, worst_sig = 0;
    for (int i = 0; i < 20000; i++) {
      double spread = i % 3 == 0 ? 1.5 : i % 3 == 1 ? 40 : 1e4, p[3], p2[3];
      for (int a = 0; a < 3; a++) {
        p[a] = ob->center[a] + ob->half[a] * spread_point(spread);
        p2[a] = p[a] + 0.05 * (2 * test_rng_unit() - 1);
        if (i % 97 == 0) p[a] = floor(p[a]); /* lattice points */
      }
      double host = ics_detail_value(&P->detail[o], p), dev = ics_k_detail_value(&V, o, p);
      if (!(host == dev)) worst = fmax(worst, isnan(host - dev) ? INFINITY : fabs(host - dev));
      for (int pre = 0; pre < 2; pre++) {
        V.preintegrate = pre;
        double c[3], hc[3], scale;
        double sig = ics_k_volume_sig(&V, o, p, p2, c);
        if (pre)
          ics_material_preintegrate(m, host, ics_detail_value(&P->detail[o], p2), hc, &scale);
        else
          ics_material_transfer(m, host, hc, &scale);
        double hsig = m->extinction * scale;
        if (!(sig == hsig && c[0] == hc[0] && c[1] == hc[1] && c[2] == hc[2]))
          worst_sig = fmax(worst_sig, fabs(sig - hsig) + fabs(c[0] - hc[0]) + 1e-300);
      }
    }
    char name[96];
    snprintf(name, sizeof name, "object %d (detail %d): ics_k_detail_value == host", o,
             m->detail.fn);
    CHECK(worst == 0, "%s (worst |diff| %.3g)", name, worst);
    snprintf(name, sizeof name, "object %d: ics_k_volume_sig == host, both modes", o);
    CHECK(worst_sig == 0, "%s (worst %.3g)", name, worst_sig);
  }
  CHECK(tested == expected, "%d detail objects (expected %d)", tested, expected);
}

static void test_class_sum(void) {
  float src[9];
  for (int i = 0; i < 9; i++) src[i] = (float)(i + 1) * 0.125f;
  /* Q = 2: classes (0,0) .. (1,1), n = 2 taps each */
  const int tx[8] = {-1, 0, 1, 5, 0, 0, -3, 1};
  const int ty[8] = {0, 0, 0, -1, 1, 2, 0, 0};
  const float tw[8] = {0.25f, 0.75f, 0.5f, 0.5f, 0.125f, 0.875f, 1.0f, 0.0f};
  kernel_view V = {.src = src, .tx = tx, .ty = ty, .tw = tw};
  /* class (1, 0) at pixel (1, 1): taps 2, 3: (2, 1) and (6 -> 2, 0) */
  float got = ics_k_class_sum(&V, 0, 2, 2, 1, 0, 1, 1);
  float want = 0.5f * src[1 * 3 + 2] + 0.5f * src[0 * 3 + 2];
  CHECK(got == want, "class_sum (1, 0) at (1, 1): %g == %g", got, want);
  /* class (2, 0) is class (0, 0) of pixel (2, 1): taps 0, 1: (1, 1) and (2, 1) */
  got = ics_k_class_sum(&V, 0, 2, 2, 2, 0, 1, 1);
  want = 0.25f * src[1 * 3 + 1] + 0.75f * src[1 * 3 + 2];
  CHECK(got == want, "class_sum Q wraps to the next pixel: %g == %g", got, want);
}

/* the camera ray written out from the plan's camera, as plan.c computed it before camera.h */
static void reference_ray(const ics_plan *p, int bi, int bj, double o[3], double d[3]) {
  const ics_camera *c = &p->cam;
  double s = (bi - p->pad[0] + 0.5) / p->W, t = (bj - p->pad[2] + 0.5) / p->H;
  if (c->projection == ICS_PROJ_ORTHOGRAPHIC) {
    double h = c->height, w = h * p->W / p->H;
    for (int i = 0; i < 3; i++) {
      o[i] = c->eye[i] + (s - 0.5) * w * c->r[i] + (0.5 - t) * h * c->u[i];
      d[i] = c->f[i];
    }
  } else {
    double th = tan(c->fov_deg * (ICS_PI / 360)), asp = (double)p->W / p->H;
    for (int i = 0; i < 3; i++) {
      o[i] = c->eye[i];
      d[i] = c->f[i] + (2 * s - 1) * th * asp * c->r[i] + (1 - 2 * t) * th * c->u[i];
    }
  }
}

/* ics_k_plan_ray over the packed camera, and ics_plan_ray, against the formula written out */
static void test_camera(const ics_plan *P, const ics_device_scene *d, const char *name) {
  kernel_view V = {.d = d};
  int same = 1, n = 0;
  for (int bj = 0; bj < P->Hb; bj += 7)
    for (int bi = 0; bi < P->Wb; bi += 5, n++) {
      double o[3], dir[3], ho[3], hd[3], ro[3], rd[3];
      ics_k_plan_ray(&V, bi, bj, P->W, P->H, P->pad[0], P->pad[2], o, dir);
      ics_plan_ray(P, bi, bj, ho, hd);
      reference_ray(P, bi, bj, ro, rd);
      same &= !memcmp(o, ro, sizeof o) && !memcmp(dir, rd, sizeof dir) && !memcmp(ho, ro, sizeof ho) &&
              !memcmp(hd, rd, sizeof hd);
    }
  CHECK(same && n > 0, "%s (%s): the camera rays == the formula written out (%d pixels)", name,
        P->cam.projection == ICS_PROJ_ORTHOGRAPHIC ? "orthographic" : "perspective", n);
}

/* text with every `from` replaced by `to` (malloc'd; NULL when out of memory) */
static char *replace_all(const char *text, const char *from, const char *to) {
  size_t n = 0, lf = strlen(from), lt = strlen(to);
  for (const char *p = strstr(text, from); p; p = strstr(p + lf, from)) n++;
  char *out = malloc(strlen(text) + n * lt + 1), *o = out;
  if (!out) return NULL;
  const char *p = text;
  for (const char *q; (q = strstr(p, from)); p = q + lf) {
    memcpy(o, p, (size_t)(q - p)), o += q - p;
    memcpy(o, to, lt), o += lt;
  }
  strcpy(o, p);
  return out;
}

/* scene `text` (files relative to dir; ndetail objects with detail): its detail and camera rays */
static void test_scene(const char *text, const char *name, const char *dir, int ndetail) {
  char msg[4096];
  ics_scene *s;
  if (ics_scene_create_json(&s, text, name, dir, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "%s: %s\n", name, msg);
    exit(2);
  }
  ics_plan *P = plan_sized_or_exit(s, NULL, 1, 32, 24);
  ics_device_scene d;
  memset(&d, 0, sizeof d);
  CHECK(ics_device_scene_create(&d, P, 0) == ICS_OK, "%s: device scene", name);
  test_detail(P, &d, s, ndetail);
  test_camera(P, &d, name);
  ics_device_scene_destroy(&d);
  ics_plan_destroy(P);
  ics_scene_destroy(s);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_kernel_c scenes/volumes.json\n");
    return 2;
  }
  char *text = test_read_text(argv[1]), dir[4096];
  snprintf(dir, sizeof dir, "%s", argv[1]);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = 0;
  else
    snprintf(dir, sizeof dir, ".");
  /* as written, and with time moving the noise along its drift and a ridged offset */
  char *t1 = text ? replace_all(text, "\"function\": \"perlin\"",
                                "\"function\": \"perlin\", \"time\": 0.37")
                  : NULL;
  char *t2 =
      t1 ? replace_all(t1, "\"function\": \"fbm\"", "\"function\": \"fbm\", \"time\": -1.3") : NULL;
  char *timed = t2 ? replace_all(t2, "\"function\": \"ridged\"",
                                 "\"function\": \"ridged\", \"time\": 2.1, \"offset\": 0.9")
                   : NULL;
  if (!timed) {
    fprintf(stderr, "test_kernel_c: cannot read %s\n", argv[1]);
    return 2;
  }
  CHECK(strcmp(timed, text) != 0 && strstr(timed, "\"offset\": 0.9"), "the timed variant differs");
  test_scene(text, "volumes.json", dir, 4);
  test_scene(timed, "volumes.json, timed", dir, 4);
  char persp[4200];
  snprintf(persp, sizeof persp, "%s/perspective.json", dir);
  char *ptext = test_read_text(persp);
  if (!ptext) {
    fprintf(stderr, "test_kernel_c: cannot read %s\n", persp);
    return 2;
  }
  test_scene(ptext, "perspective.json", dir, 0);
  free(ptext);
  test_class_sum();
  free(text), free(t1), free(t2), free(timed);
  return test_summary("test_kernel_c");
}
