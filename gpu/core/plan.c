/* plan.c — the render plan (icshadow/plan.h, docs/renderer.md): what the scene needs, sized
 * before anything large is allocated.
 *
 * Order: settings and camera in force; reference depth and pixel size from the objects'
 * bounding boxes; each light's slab kernel (slab_kernel.c); the light-buffer padding from the
 * kernels' total shift and spread over the (bounding-box) slab range, so casters outside the view
 * still shadow it; volume bits and light-buffer channels from the materials; a memory check;
 * then the geometry pass (ldi.c) fixes the exact depth range and slab count; a work check; and
 * the passes and omissions that `icshadow plan` prints. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "clock.h"
#include "geometry.h"
#include "icshadow/json_text.h"
#include "icshadow/constants.h"
#include "icshadow/conv.h"
#include "icshadow/light.h"
#include "icshadow/renderer.h"
#include "device_scene.h"
#include "mesh.h"
#include "own_term.h"
#include "plan_internal.h"
#include "pool.h"
#include "scene_internal.h"

/* the camera ray: the shared kernel source (gpu/kernel/camera.h, the text the cl and gl programs
 * compile) over the plan's camera record */
#define ICS_VIEW_PARAM const double *cam_rec,
#define ICS_VIEW_ARG cam_rec,
#define ICS_CAM(f) cam_rec[f]
#include "kernel/camera.h"

void ics_plan_ray(const ics_plan *p, int bi, int bj, double o[3], double d[3]) {
  ics_k_plan_ray(p->cam_rec, bi, bj, p->W, p->H, p->pad[0], p->pad[2], o, d);
}

double ics_plan_pixel_size(const ics_plan *p, double z) {
  if (p->cam.projection == ICS_PROJ_ORTHOGRAPHIC) return p->cam.height / p->H;
  return 2 * z * p->tan_half_fov / p->H;
}

double ics_plan_slab_depth(const ics_plan *p, int k) { return p->z0 + (k + 0.5) * p->e; }

double ics_plan_light_blur(const ics_plan *p, int l) {
  double varx, vary, alpha;
  if (ics_light_cov_to_eig(p->scene->lights[l].cov, &varx, &vary, &alpha) != ICS_OK) return 0;
  return sqrt(p->rs.d1 * p->e * fmax(varx, 0));
}

double ics_plan_slab_pixel(const ics_plan *p, int k, double *mag) {
  if (p->cam.projection != ICS_PROJ_PERSPECTIVE) {
    *mag = 1;
    return p->q_ref;
  }
  double zk = ics_plan_slab_depth(p, k), zp = ics_plan_slab_depth(p, k > 0 ? k - 1 : 0);
  *mag = zk / zp;
  return ics_plan_pixel_size(p, zk);
}

static int has_patel_set(const ics_plan *p) { return p->rs.model >= ICS_MODEL_SURFACE && p->solid_bits; }

int ics_plan_light_sets(const ics_plan *p) {
  return 1 + has_patel_set(p) + (p->rs.model >= ICS_MODEL_BLOCKER ? 2 : 0);
}

int ics_plan_set_channels(const ics_plan *p, int set) {
  return ics_plan_set_role(p, set) == ICS_SET_MOMENT ? 1 : p->nch;
}

/* every light-buffer set's channels, summed (the planes per light) */
static int set_planes(const ics_plan *p) {
  int n = 0;
  for (int set = 0; set < ics_plan_light_sets(p); set++) n += ics_plan_set_channels(p, set);
  return n;
}

ics_set_role ics_plan_set_role(const ics_plan *p, int set) {
  if (set == 0) return ICS_SET_FIRST;
  if (has_patel_set(p) && set == 1) return ICS_SET_PATEL;
  return set - has_patel_set(p) == 1 ? ICS_SET_SHARP : ICS_SET_MOMENT;
}

const ics_slab_kernel *ics_plan_set_kernel(const ics_plan *p, int b) {
  int l = b % p->nlights;
  return ics_plan_set_role(p, b / p->nlights) == ICS_SET_SHARP ? &p->kernels_sharp[l] : &p->kernels[l];
}

double ics_plan_window_max(const ics_plan *p) {
  double q_max = p->cam.projection == ICS_PROJ_PERSPECTIVE
                     ? ics_plan_pixel_size(p, ics_plan_slab_depth(p, p->K - 1)) : p->q_ref;
  double w = 0;
  double sharp = p->rs.model >= ICS_MODEL_BLOCKER ? sqrt(ICS_BLOCKER_SHARP) : 1; /* its sharp set's */
  for (int l = 0; l < p->nlights; l++) w = fmax(w, 1 - sharp * ics_plan_light_blur(p, l) / q_max);
  return w;
}

ics_status ics_plan_slab_taps(const ics_plan *p, int l, int k, double q, double mag,
                              double cum[2], ics_tap2d *scratch, ics_prop_taps *pt, char *msg,
                              size_t msg_size) {
  return ics_plan_kernel_taps(p, &p->kernels[l], l, k, q, mag, cum, scratch, pt, msg, msg_size);
}

ics_status ics_plan_kernel_taps(const ics_plan *p, const ics_slab_kernel *sk, int l, int k,
                                double q, double mag, double cum[2], ics_tap2d *scratch,
                                ics_prop_taps *pt, char *msg, size_t msg_size) {
  return ics_plan_kernel_taps_deferred(p, sk, l, k, q, mag, cum, scratch, pt, NULL, msg, msg_size);
}

ics_status ics_plan_kernel_taps_deferred(const ics_plan *p, const ics_slab_kernel *sk, int l, int k,
                                         double q, double mag, double cum[2], ics_tap2d *scratch,
                                         ics_prop_taps *pt, int *deferred, char *msg,
                                         size_t msg_size) {
  int n, persp = p->cam.projection == ICS_PROJ_PERSPECTIVE;
  ics_status st = ics_slab_kernel_taps(sk, (uint64_t)k, q, cum, scratch, &n);
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "light %d, slab %d: kernel taps: %s", l, k, ics_status_str(st));
    return st;
  }
  if (persp && deferred) { /* the classes left to the caller */
    if (ics_prop_perspective_begin(pt, n, mag, p->cx, p->cy)) return ICS_ERR_NOMEM;
    *deferred = n;
  } else if (persp ? ics_prop_prepare_perspective(pt, scratch, n, mag, p->cx, p->cy, &p->buf)
                   : ics_prop_prepare(pt, scratch, sk->out_entries, n / sk->out_entries, sk->cap,
                                      mag, p->cx, p->cy, &p->buf)) {
    return ICS_ERR_NOMEM;
  }
  pt->seed = p->rs.seed; /* table choices */
  pt->run = p->rs.rotation_run;
  pt->phase = (int)ics_slab_choice(p->rs.seed, (uint32_t)l, (uint32_t)k, UINT32_MAX - 2, 16);
  pt->light = (uint32_t)l;
  pt->slab = (uint32_t)k;
  return ICS_OK;
}

void ics_plan_over_background(const ics_plan *p, ics_image *img) {
  for (size_t i = 0; i < (size_t)p->W * p->H; i++) {
    float *C = img->data + 4 * i;
    for (int c = 0; c < 3; c++) C[c] += (1 - C[3]) * (float)p->rs.background[c];
  }
}

static void add_pass(ics_plan *p, const char *name, size_t bytes, int light, int taps,
                     const char *detail) {
  ics_plan_pass *q = &p->passes[p->npasses++];
  snprintf(q->name, sizeof q->name, "%s", name);
  q->bytes = bytes;
  q->light = light;
  q->taps = taps;
  snprintf(q->detail, sizeof q->detail, "%s", detail ? detail : "");
}

static void add_omitted(ics_plan *p, const char *name, const char *reason) {
  ics_plan_omitted *q = &p->omitted[p->nomitted++];
  snprintf(q->name, sizeof q->name, "%s", name);
  snprintf(q->reason, sizeof q->reason, "%s", reason);
}

/* The depth range the slabs will likely cover, before the geometry pass: the crossings of a
 * coarse grid of camera rays over the view (33 x 33, the view's edges included); without any
 * crossing, the objects' bounding boxes (clamped to depths > 0). Used only to size the padding
 * and to refuse absurd work early: the geometry pass then fixes the exact range. */
static void estimate_depth(const ics_plan *p, double *zlo, double *zhi) {
  const ics_scene *s = p->scene;
  *zlo = INFINITY;
  *zhi = -INFINITY;
  ics_hits h = {0};
  int n = 33;
  for (int a = 0; a < n; a++)
    for (int b = 0; b < n; b++) {
      double o[3], d[3];
      /* buffer coordinates of the image's pixels: the padding is not known yet (0 here) */
      int bi = (int)((double)a / (n - 1) * (p->W - 1)), bj = (int)((double)b / (n - 1) * (p->H - 1));
      ics_plan_ray(p, bi, bj, o, d);
      for (int k = 0; k < s->nobjects; k++) {
        h.n = 0;
        int behind = 0;
        if (ics_object_hits(&s->objects[k], o, d, &h, &behind)) break;
        for (int i = 0; i < h.n; i++) *zlo = fmin(*zlo, h.h[i].t), *zhi = fmax(*zhi, h.h[i].t);
      }
    }
  ics_hits_free(&h);
  if (*zhi >= *zlo) return;
  for (int k = 0; k < s->nobjects; k++) {
    double lo[3], hi[3];
    ics_object_bounds(&s->objects[k], lo, hi);
    for (int m = 0; m < 8; m++) {
      double pnt[3] = {m & 1 ? hi[0] : lo[0], m & 2 ? hi[1] : lo[1], m & 4 ? hi[2] : lo[2]};
      double z = 0;
      for (int i = 0; i < 3; i++) z += (pnt[i] - p->cam.eye[i]) * p->cam.f[i];
      *zlo = fmin(*zlo, z);
      *zhi = fmax(*zhi, z);
    }
  }
  double eps = 1e-6 * fmax(fabs(*zhi), 1);
  if (*zlo < eps) *zlo = eps;
  if (*zhi < *zlo) *zhi = *zlo;
}

#define ICS_PLAN_MAX_APRON 64             /* pixels; kernels that reach farther clamp */

static int grey(const double t[3]) { return t[0] == t[1] && t[1] == t[2]; }

/* an opaque surface material (opacity 1, black transport: one that lets light through, tinted,
 * is not solid): a closed shape of it is solid under render.model solid and after */
static int solid_candidate(const ics_material *m) {
  return !m->volumetric && m->opacity == 1 && m->transport[0] == 0 && m->transport[1] == 0 &&
         m->transport[2] == 0;
}

/* The work of a render in pixel-slab-light updates, every term that grows counted: the steps
 * (slabs x pixels x lights); volume detail, an update per octave of every volume with detail at
 * every pixel and slab (the worst case: every pixel inside every such volume); with perspective
 * kernels, the per-slab compensation of Q^2 classes per light, about 8000 updates a class and
 * 100 per tap of it (measured here at one update a nanosecond: 8.3 us a class of a 2-tap ellipse,
 * 0.18 ms one of 1609 taps). kernels_done: the kernels are built (the classes term needs their
 * taps). */
static double plan_work(const ics_plan *p, double slabs, double pixels, int kernels_done) {
  const ics_scene *s = p->scene;
  double per = p->nlights ? p->nlights * ics_plan_light_sets(p) : 1;
  for (int i = 0; i < s->nobjects; i++) {
    const ics_material *m = &s->materials[s->objects[i].material];
    if (!m->volumetric || m->detail.fn == ICS_DETAIL_NONE) continue;
    int oct = m->detail.fn == ICS_DETAIL_FBM || m->detail.fn == ICS_DETAIL_RIDGED ? m->detail.octaves : 1;
    per += oct > 1 ? oct : 1;
  }
  double work = slabs * pixels * per;
  if (kernels_done && p->cam.projection == ICS_PROJ_PERSPECTIVE)
    for (int k = 0; k < p->nlights; k++)
      work += slabs * ICS_PROP_CLASSES * ICS_PROP_CLASSES * (8000 + 100 * (4.0 * p->kernels[k].cap + 9));
  return work;
}

/* the geometry pass's ray-object tests: every buffer pixel's ray against every analytic object,
 * and down the BVH of every mesh (about 2 log2 triangles + 1 nodes) */
static double geometry_work(const ics_plan *p, double rays) {
  const ics_scene *s = p->scene;
  double per = s->nobjects;
  for (int i = 0; i < s->nmeshes; i++) per += 2 * log2(1.0 + ics_mesh_triangle_count(s->meshes[i]));
  return rays * per;
}

/* the byte counts the plan's memory estimate and its passes are made of */
typedef struct plan_bytes {
  size_t plane2, buf, state, image, tap, offset, mesh, grid, ldi, region;
} plan_bytes;

/* resolution, settings, the slab count and the steps' work, before anything is allocated:
 * *zlo, *zhi the depth range, *k_est the slabs */
static ics_status plan_limits(ics_plan *p, double *zlo, double *zhi, double *k_est, char *msg,
                              size_t msg_size) {
  if (p->cam.width > ICS_SCENE_MAX_RES || p->cam.height_px > ICS_SCENE_MAX_RES) {
    if (msg) snprintf(msg, msg_size, "resolution %dx%d exceeds %d per axis", p->cam.width,
                      p->cam.height_px, ICS_SCENE_MAX_RES);
    return ICS_ERR_SIZE;
  }
  if (!(p->rs.slab_spacing > 0) || !(p->rs.d1 > 0) || !isfinite(p->rs.slab_spacing) ||
      !isfinite(p->rs.d1)) {
    if (msg) snprintf(msg, msg_size, "slab_spacing and d1 must be finite and > 0");
    return ICS_ERR_RANGE;
  }
  p->W = p->cam.width;
  p->H = p->cam.height_px;
  ics_device_camera(p, p->cam_rec);
  p->e = p->rs.slab_spacing;
  p->nlights = p->scene->nlights;
  estimate_depth(p, zlo, zhi);
  p->q_ref = ics_plan_pixel_size(p, 0.5 * (*zlo + *zhi));
  *k_est = floor((*zhi - *zlo) / p->e) + 2;
  if (*k_est > ICS_FRAG_MAX_SLABS) {
    if (msg)
      snprintf(msg, msg_size, "about %.3g slabs (depth range %.6g / slab_spacing %.6g) exceed "
               "the limit %d: increase render.slab_spacing", *k_est, *zhi - *zlo, p->e,
               ICS_FRAG_MAX_SLABS);
    return ICS_ERR_SIZE;
  }
  /* the steps' work, from the unpadded image (the padding only adds to it); the detail and
   * perspective terms once the kernels are built */
  double work = plan_work(p, *k_est, (double)p->W * p->H, 0);
  if (work > ICS_PLAN_MAX_WORK) {
    if (msg)
      snprintf(msg, msg_size, "about %.3g slabs x %d x %d pixels x (%d light buffer(s) and the "
               "volume detail's octaves) = %.3g updates exceed the work limit %.3g: increase "
               "render.slab_spacing, lower the resolution or the detail's octaves",
               *k_est, p->W, p->H, p->nlights * ics_plan_light_sets(p), work, ICS_PLAN_MAX_WORK);
    p->over_cost = 1;
    return ICS_ERR_SIZE;
  }
  return ICS_OK;
}

/* The slab kernels of plan_kernels built on a pool's threads, one task a kernel (task i < nlights:
 * light i's; the rest: light i - nlights's sharp set's): the expected compensation iterates the
 * ellipse's arc-length table, milliseconds a light. Each task keeps its own status and message.
 * A task whose kernel the renderer kept from its last plan, resolved from the same inputs, takes
 * a copy of it instead (kernel_cache.h). */
typedef struct {
  ics_plan *p;
  const ics_scene *settings, *sharp; /* the scene with the settings in force; with d1 sharpened */
  atomic_int next;
  ics_status st[2 * ICS_SCENE_MAX_LIGHTS];
  char msg[2 * ICS_SCENE_MAX_LIGHTS][512];
  ics_slab_kernel_key key[2 * ICS_SCENE_MAX_LIGHTS];
  uint8_t kept[2 * ICS_SCENE_MAX_LIGHTS]; /* taken from the renderer's */
} kernels_job;

static int kernel_tasks(const ics_plan *p) {
  return p->kernels_sharp ? 2 * p->nlights : p->nlights;
}

static ics_slab_kernel *task_kernel(ics_plan *p, int i) {
  return i < p->nlights ? &p->kernels[i] : &p->kernels_sharp[i - p->nlights];
}

/* the scene (its settings in force) task i's kernel is resolved from */
static const ics_scene *task_scene(const kernels_job *kj, int i) {
  return i < kj->p->nlights ? kj->settings : kj->sharp;
}

static void kernels_tasks(void *ctx, int t, int n) {
  kernels_job *kj = ctx;
  ics_plan *p = kj->p;
  int nl = p->nlights;
  (void)t, (void)n;
  for (int i; (i = atomic_fetch_add(&kj->next, 1)) < kernel_tasks(p);)
    if (!kj->kept[i])
      kj->st[i] = ics_slab_kernel_init(task_kernel(p, i), task_scene(kj, i), i % nl, p->q_ref,
                                       kj->msg[i], sizeof kj->msg[i]);
}

/* every light's kernel (and its sharp set's): those the cache (may be NULL) holds for the same
 * inputs copied, the others built in parallel, on at most one thread a kernel, and kept in the
 * cache; NULL when out of memory, else the job with each kernel's status and message (to free) */
static kernels_job *build_kernels(ics_plan *p, const ics_scene *settings, const ics_scene *sharp,
                                  int threads, ics_kernel_cache *cache) {
  int tasks = kernel_tasks(p), todo = 0;
  kernels_job *kj = calloc(1, sizeof *kj);
  if (!kj) return NULL;
  kj->p = p, kj->settings = settings, kj->sharp = sharp;
  atomic_init(&kj->next, 0);
  for (int i = 0; i < tasks; i++) {
    ics_slab_kernel_key_of(task_scene(kj, i), i % p->nlights, p->q_ref, &kj->key[i]);
    kj->kept[i] = (uint8_t)ics_kernel_cache_get(cache, i, &kj->key[i], task_kernel(p, i));
    todo += !kj->kept[i];
    p->kernels_kept += kj->kept[i];
  }
  if (!todo) return kj;
  ics_pool *pool = ics_pool_create(threads > 0 && threads < todo ? threads : todo);
  if (!pool) pool = ics_pool_create(1);
  if (!pool) {
    free(kj);
    return NULL;
  }
  ics_pool_run(pool, kernels_tasks, kj);
  ics_pool_destroy(pool);
  for (int i = 0; i < tasks; i++)
    if (!kj->kept[i] && kj->st[i] == ICS_OK)
      ics_kernel_cache_put(cache, i, &kj->key[i], task_kernel(p, i));
  return kj;
}

/* each light's slab kernel (from the settings in force), and the perspective classes' work */
static ics_status plan_kernels(ics_plan *p, double k_est, int threads, ics_kernel_cache *cache,
                               char *msg, size_t msg_size) {
  const ics_scene *s = p->scene;
  p->kernels = calloc((size_t)p->nlights, sizeof *p->kernels);
  p->vol_bit = malloc(sizeof *p->vol_bit * (size_t)(s->nobjects ? s->nobjects : 1));
  p->inside_bit = malloc(sizeof *p->inside_bit * (size_t)(s->nobjects ? s->nobjects : 1));
  p->detail = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *p->detail);
  if (!p->kernels || !p->vol_bit || !p->inside_bit || !p->detail) return ICS_ERR_NOMEM;
  ics_scene tmp = *s, sharp; /* the kernels read the settings in force */
  tmp.settings = p->rs;
  sharp = tmp;
  sharp.settings.d1 *= ICS_BLOCKER_SHARP;
  if (p->rs.model >= ICS_MODEL_BLOCKER) {
    p->kernels_sharp = calloc((size_t)p->nlights, sizeof *p->kernels_sharp);
    if (!p->kernels_sharp && p->nlights) return ICS_ERR_NOMEM;
  }
  kernels_job *kj = p->nlights ? build_kernels(p, &tmp, &sharp, threads, cache) : NULL;
  if (p->nlights && !kj) return ICS_ERR_NOMEM;
  ics_status st = ICS_OK;
  /* the first failure in light order: a light's kernel, its sharp set's, then its size */
  for (int k = 0; k < p->nlights && st == ICS_OK; k++) {
    for (int i = k; i < kernel_tasks(p) && st == ICS_OK; i += p->nlights)
      if ((st = kj->st[i]) != ICS_OK && msg) snprintf(msg, msg_size, "%s", kj->msg[i]);
    if (st != ICS_OK) break;
    p->light_path[k] = sqrt(1 + s->lights[k].mean[0] * s->lights[k].mean[0] +
                            s->lights[k].mean[1] * s->lights[k].mean[1]);
    const ics_slab_kernel *sk = &p->kernels[k];
    double big = fmax(fmax(fabs(sk->mean_px[0]), fabs(sk->mean_px[1])),
                      fmax(sk->cov_px[0], sk->cov_px[2]));
    if (!(big <= 1e6)) {
      if (msg)
        snprintf(msg, msg_size, "light %d: its per-slab kernel is %.3g pixels (mean or variance) "
                 "at a pixel size of %.3g: the slab spacing, d1 or the light's spread is out of "
                 "proportion to the image", k, big, p->q_ref);
      st = ICS_ERR_RANGE;
    }
  }
  free(kj);
  if (st != ICS_OK) return st;
  if (p->cam.projection == ICS_PROJ_PERSPECTIVE) { /* the classes' compensation per slab */
    double work = plan_work(p, k_est, (double)p->W * p->H, 1);
    if (work > ICS_PLAN_MAX_WORK) {
      if (msg)
        snprintf(msg, msg_size, "about %.3g slabs with %d light(s), each compensating %d classes of "
                 "its perspective kernel per slab (and %d x %d pixels) = %.3g updates exceed the "
                 "work limit %.3g: increase render.slab_spacing, or give fewer lights or samples",
                 k_est, p->nlights, ICS_PROP_CLASSES * ICS_PROP_CLASSES, p->W, p->H, work,
                 ICS_PLAN_MAX_WORK);
      return ICS_ERR_SIZE;
    }
  }
  return ICS_OK;
}

/* the padding: content moves by +mean per slab and spreads by the covariance */
static void plan_padding(ics_plan *p, double zlo, double zhi, double k_est) {
  int persp = p->cam.projection == ICS_PROJ_PERSPECTIVE;
  double padl = 0, padr = 0, padt = 0, padb = 0;
  for (int k = 0; k < p->nlights; k++) {
    const ics_slab_kernel *sk = &p->kernels[k];
    double mx = 0, my = 0, vmax = 0;
    for (int i = 0; i < (int)k_est; i++) {
      double z = zlo + (i + 0.5) * p->e, q = persp ? ics_plan_pixel_size(p, z) : p->q_ref;
      mx += sk->mean_w[0] / q;
      my += sk->mean_w[1] / q;
      double c0 = sk->cov_w[0] / (q * q), c1 = sk->cov_w[1] / (q * q), c2 = sk->cov_w[2] / (q * q);
      vmax += 0.5 * (c0 + c2) + sqrt(0.25 * (c0 - c2) * (c0 - c2) + c1 * c1);
      if (!persp) { /* constant per slab: multiply instead of summing */
        mx *= k_est, my *= k_est, vmax *= k_est;
        break;
      }
    }
    double spread = 4 * sqrt(vmax) + 2;
    if (sk->mode == ICS_SLAB_SHIFT || vmax == 0) spread = 1;
    padl = fmax(padl, fmax(0, mx) + spread);
    padr = fmax(padr, fmax(0, -mx) + spread);
    padt = fmax(padt, fmax(0, my) + spread);
    padb = fmax(padb, fmax(0, -my) + spread);
  }
  if (persp) { /* content shrinks toward the principal point as depth grows */
    double g = zhi / zlo - 1;
    padl += 0.5 * p->W * g, padr += 0.5 * p->W * g;
    padt += 0.5 * p->H * g, padb += 0.5 * p->H * g;
  }
  int cap = p->rs.max_pad >= 0 ? p->rs.max_pad : (p->W > p->H ? p->W : p->H);
  double pads[4] = {padl, padr, padt, padb};
  int clipped = 0;
  for (int i = 0; i < 4; i++) {
    double v = ceil(pads[i]);
    if (v > cap) v = cap, clipped = 1;
    p->pad[i] = (int)v;
  }
  p->Wb = p->W + p->pad[0] + p->pad[1];
  p->Hb = p->H + p->pad[2] + p->pad[3];
  p->cx = p->pad[0] + 0.5 * p->W - 0.5;
  p->cy = p->pad[2] + 0.5 * p->H - 0.5;
  if (clipped) {
    char r[160];
    snprintf(r, sizeof r, "padding capped at %d px per side (render.max_pad): casters further "
             "outside the view do not shadow it", cap);
    add_omitted(p, "padding beyond max_pad", r);
  } else if (p->pad[0] + p->pad[1] + p->pad[2] + p->pad[3] == 0) {
    add_omitted(p, "padding", "no light moves or spreads shadows across the view's edge");
  }
}

/* render.model auto: what the renderer's backend renders (blocker without one), or patel where
 * the volumes and solids (solid_candidate) exceed the inside mask's ICS_MAX_VOLUMES bits, which
 * solid and after would refuse */
static void resolve_model(ics_plan *p, const ics_renderer *r) {
  p->model_auto = p->rs.model == ICS_MODEL_AUTO;
  if (!p->model_auto) return;
  p->rs.model = r ? ics_renderer_model_auto(r) : ICS_MODEL_BLOCKER;
  if (p->rs.model < ICS_MODEL_SOLID) return;
  const ics_scene *s = p->scene;
  int n = 0;
  for (int k = 0; k < s->nobjects; k++)
    n += s->objects[k].closed && (s->materials[s->objects[k].material].volumetric ||
                                  solid_candidate(&s->materials[s->objects[k].material]));
  p->auto_capped = n > ICS_MAX_VOLUMES;
  if (p->auto_capped) p->rs.model = ICS_MODEL_PATEL;
}

/* volumes, channels, detail, and the inside mask's bits: the volumes, then (render.model solid
 * and after) the solid objects, a closed shape of a solid_candidate material */
static ics_status plan_volumes(ics_plan *p, char *msg, size_t msg_size) {
  const ics_scene *s = p->scene;
  int coloured = 0, nvol = 0;
  for (int k = 0; k < s->nobjects; k++) {
    const ics_material *m = &s->materials[s->objects[k].material];
    p->vol_bit[k] = -1;
    if (!grey(m->transport)) coloured = 1;
    if (m->volumetric && s->objects[k].closed) {
      if (nvol == ICS_MAX_VOLUMES) {
        if (msg)
          snprintf(msg, msg_size, "more than %d objects with volumetric materials", ICS_MAX_VOLUMES);
        return ICS_ERR_SIZE;
      }
      p->vol_bit[k] = nvol++;
    }
    if (m->volumetric && m->detail.fn != ICS_DETAIL_NONE) {
      double lo[3], hi[3];
      ics_object_bounds(&s->objects[k], lo, hi);
      ics_detail_prepare(&p->detail[k], &m->detail, lo, hi);
      p->any_detail = 1;
    }
  }
  p->nvol = nvol;
  p->nch = coloured ? 3 : 1;
  int nin = nvol;
  for (int k = 0; k < s->nobjects; k++) {
    const ics_material *m = &s->materials[s->objects[k].material];
    p->inside_bit[k] = p->vol_bit[k];
    if (p->rs.model < ICS_MODEL_SOLID || !solid_candidate(m) || !s->objects[k].closed) continue;
    if (nin == ICS_MAX_VOLUMES) {
      if (msg)
        snprintf(msg, msg_size, "more than %d volumetric and solid objects (render.model %s)",
                 ICS_MAX_VOLUMES, ics_render_model_name(p->rs.model));
      return ICS_ERR_SIZE;
    }
    p->solid_bits |= 1ull << nin;
    p->inside_bit[k] = nin++;
  }
  p->ninside = nin;
  return ICS_OK;
}

/* the light buffers' layout with their apron: the farthest read of any light at the reference
 * depth (beyond ICS_PLAN_MAX_APRON, the few slabs or lights that reach farther clamp their
 * reads) */
static void plan_apron(ics_plan *p) {
  int apron = 1;
  for (int k = 0; k < p->nlights; k++)
    if (p->kernels[k].reach_bound > apron) apron = p->kernels[k].reach_bound;
  if (apron > ICS_PLAN_MAX_APRON) apron = ICS_PLAN_MAX_APRON;
  ics_buf_layout_init(&p->buf, p->Wb, p->Hb, apron);
}

/* the memory before the geometry pass, against render.memory_limit_mib and the loops' index
 * range */
static ics_status plan_memory(ics_plan *p, plan_bytes *b, char *msg, size_t msg_size) {
  const ics_scene *s = p->scene;
  size_t npx = (size_t)p->Wb * p->Hb, nimg = (size_t)p->W * p->H;
  b->plane2 = 2 * (size_t)p->buf.plane * sizeof(float); /* one channel, both ping-pong buffers */
  b->buf = (size_t)p->nch * b->plane2;
  b->state = npx * (3 * sizeof(uint32_t) + (p->ninside ? sizeof(uint64_t) : 0));
  b->image = nimg * 4 * sizeof(float);
  b->tap = 0;
  for (int k = 0; k < p->nlights; k++) {
    const ics_slab_kernel *sk = &p->kernels[k];
    b->tap += (size_t)sk->entries * (size_t)sk->cap * sizeof(ics_tap2d);
    if (p->cam.projection == ICS_PROJ_PERSPECTIVE) {
      /* the perspective step's classes (propagate.h): Q^2 compensated sets of up to
       * 4 n + 9 taps (12 bytes each) and their scratch (24 bytes each) */
      size_t n = (size_t)sk->out_entries * (size_t)sk->cap, cls = (size_t)ICS_PROP_CLASSES * ICS_PROP_CLASSES;
      if (n > ICS_PROP_PERSPECTIVE_MAX_TAPS) {
        if (msg)
          snprintf(msg, msg_size, "light %d: %zu taps per slab; perspective cameras take at most "
                   "%d (each slab compensates %zu classes of them): fewer samples or an "
                   "orthographic camera", k, n, ICS_PROP_PERSPECTIVE_MAX_TAPS, cls);
        return ICS_ERR_SIZE;
      }
      b->tap += cls * (4 * n + 9) * 36;
    }
  }
  p->backend_bytes = (size_t)p->nlights * set_planes(p) * b->plane2 + b->state + b->image +
                     b->tap;
  b->offset = (npx + 1) * sizeof(uint32_t);
  b->mesh = b->grid = 0;
  for (int i = 0; i < s->nmeshes; i++) b->mesh += ics_mesh_bytes(s->meshes[i]);
  for (int i = 0; i < s->nmaterials; i++) /* the grids read: those some object uses */
    if (s->materials[i].detail.fn == ICS_DETAIL_GRID && s->materials[i].detail.grid)
      b->grid += (size_t)s->materials[i].detail.size[0] * s->materials[i].detail.size[1] *
                 s->materials[i].detail.size[2] * sizeof(float);
  p->memory_bytes = p->backend_bytes + b->offset + b->mesh + b->grid;
  if ((double)p->memory_bytes > p->rs.memory_limit_mib * 1048576.0) {
    if (msg)
      snprintf(msg, msg_size, "the plan needs at least %.*f MiB (%d x %d light buffers for %d "
               "light(s), %d channel(s)), over render.memory_limit_mib = %g",
               p->memory_bytes < 104858 ? 4 : 1, p->memory_bytes / 1048576.0, p->Wb, p->Hb,
               p->nlights, p->nch, p->rs.memory_limit_mib); /* (a small plan: 0.0130, not 0.0) */
    p->over_cost = 1;
    return ICS_ERR_SIZE;
  }
  if (p->buf.plane > ICS_CONV_MAX_LEN) { /* the loops index a plane with 32-bit integers */
    if (msg)
      snprintf(msg, msg_size, "light buffers of %d x %d pixels (with padding and apron) exceed "
               "%zu pixels: lower the resolution or render.max_pad", p->Wb, p->Hb,
               (size_t)ICS_CONV_MAX_LEN);
    return ICS_ERR_SIZE;
  }
  return ICS_OK;
}

/* the geometry pass (the layered depth image, bounded first), the work of the slabs it found and
 * the active regions; the memory with them */
static ics_status plan_geometry(ics_plan *p, int threads, plan_bytes *b, char *msg,
                                size_t msg_size) {
  const ics_scene *s = p->scene;
  size_t npx = (size_t)p->Wb * p->Hb;
  double gwork = geometry_work(p, (double)npx);
  if (gwork > ICS_PLAN_MAX_GEOMETRY) {
    if (msg)
      snprintf(msg, msg_size, "the geometry pass: %d x %d buffer rays x %d object(s) (meshes by "
               "their BVH depth) = %.3g ray-object tests exceed the limit %.3g: lower the "
               "resolution, render.max_pad or the number of objects", p->Wb, p->Hb,
               s->nobjects, gwork, ICS_PLAN_MAX_GEOMETRY);
    return ICS_ERR_SIZE;
  }
  double t0 = ics_clock_s();
  ics_status st = ics_ldi_build(p, threads, msg, msg_size);
  p->geometry_s = ics_clock_s() - t0;
  if (st == ICS_OK) st = ics_plan_own_surfaces(p);
  if (st != ICS_OK) return st;
  b->ldi = b->offset + p->ldi.nfrag * sizeof(ics_fragment) +
           (p->ldi.inside0 ? npx * sizeof(uint64_t) : 0);
  b->region = (size_t)p->K * (size_t)p->nlights * sizeof(ics_rect) +
              (size_t)(p->nlights * ics_plan_light_sets(p) + 1) * (npx / (ICS_TILE_W * ICS_TILE_H) + 1) * sizeof(int32_t);
  p->memory_bytes = p->backend_bytes + b->ldi + b->mesh + b->grid + b->region;
  double work = plan_work(p, p->K, (double)npx, 1);
  if (work > ICS_PLAN_MAX_WORK) {
    if (msg)
      snprintf(msg, msg_size, "%d slabs x %d x %d buffer pixels x (%d light buffer(s) and the "
               "volume detail's octaves, with the perspective classes) = %.3g updates exceed the "
               "work limit %.3g: increase render.slab_spacing or lower the resolution",
               p->K, p->Wb, p->Hb, p->nlights * ics_plan_light_sets(p), work, ICS_PLAN_MAX_WORK);
    p->over_cost = 1;
    return ICS_ERR_SIZE;
  }
  return ics_active_regions_build(p, msg, msg_size);
}

/* the passes the plan makes, with their bytes, and what it leaves out and why */
static void plan_passes(ics_plan *p, const plan_bytes *b) {
  const ics_scene *s = p->scene;
  char d[192];
  snprintf(d, sizeof d, "%d layer(s) max, %zu fragments, ray cast over %d x %d", p->ldi.max_layers,
           p->ldi.nfrag, p->Wb, p->Hb);
  add_pass(p, "layered_depth_image", b->ldi, -1, 0, d);
  if (b->mesh) {
    snprintf(d, sizeof d, "%d mesh(es)", s->nmeshes);
    add_pass(p, "mesh_bvh", b->mesh, -1, 0, d);
  } else {
    add_omitted(p, "mesh_bvh", "no meshes");
  }
  for (int k = 0; k < p->nlights; k++) {
    const ics_slab_kernel *sk = &p->kernels[k];
    static const char *const modes[] = {"shift", "integer", "taps", "table"};
    snprintf(d, sizeof d, "%s %d, %s: %s", ics_render_kernel_name(sk->run_member),
             sk->run_samples, modes[sk->mode], sk->why);
    size_t kb = b->buf + (size_t)sk->entries * (size_t)sk->cap * sizeof(ics_tap2d);
    add_pass(p, sk->mode == ICS_SLAB_SHIFT ? "shift" : "convolution", kb, k, sk->taps, d);
    if (sk->mode == ICS_SLAB_SHIFT) {
      char nm[48];
      snprintf(nm, sizeof nm, "convolution taps (light %d)", k);
      add_omitted(p, nm, "zero variance: integer shifts instead");
    }
  }
  if (p->auto_capped) {
    char why[sizeof p->omitted->reason];
    snprintf(why, sizeof why, "render.model auto: more than %d volumetric and solid objects (the "
             "inside mask's bits): patel", ICS_MAX_VOLUMES);
    add_omitted(p, "render.model blocker", why);
  }
  if (p->nch == 1) add_omitted(p, "colour light buffers", "every transport colour is grey: one channel per light");
  int sets = ics_plan_light_sets(p); /* the sets beyond the first (ics_set_role) */
  if (sets > 1) {
    int patel = ics_plan_set_role(p, 1) == ICS_SET_PATEL, blocker = p->rs.model >= ICS_MODEL_BLOCKER;
    snprintf(d, sizeof d, "%d more light-buffer set(s) per light: %s%s%s", sets - 1,
             patel ? "Patel's (it lights the solids' surfaces)" : "", patel && blocker ? "; " : "",
             blocker ? "the sharp set (d1 / 4) and the blocker moment (render.model blocker)" : "");
    add_pass(p, "light_buffer_sets", (size_t)p->nlights * (size_t)(set_planes(p) - p->nch) * b->plane2,
             -1, 0, d);
  }
  if (p->any_detail) {
    snprintf(d, sizeof d, "detail functions of volumetric materials, one sample per slab piece");
    add_pass(p, "detail", b->grid, -1, 0, d);
  } else {
    add_omitted(p, "detail", "no material has volumetric detail");
  }
  if (!p->ninside)
    add_omitted(p, "volume tracking", p->rs.model >= ICS_MODEL_SOLID
                                          ? "no volumetric or solid objects (surfaces only)"
                                          : "no volumetric objects (surfaces only)");
  if (p->own_any) {
    ics_own_term_describe(p, d, sizeof d);
    add_pass(p, "own_term", 0, -1, 0, d);
  } else if (p->rs.model >= ICS_MODEL_SURFACE) {
    add_omitted(p, "own term of open surfaces", "no opaque rect or disk has the other shaded "
                "points on one side of its plane with a light in front of it (own_term.c)");
  }
  snprintf(d, sizeof d, "front-to-back compositing into the RGBA image, per-pixel layer cursors");
  add_pass(p, "shading", b->state + b->image, -1, 0, d);
}

ics_status ics_plan_create(ics_plan **out, const ics_scene *s, const ics_plan_opts *opts,
                           char *msg, size_t msg_size) {
  ics_plan_opts o = {0};
  if (opts) o = *opts;
  *out = NULL;
  if (msg && msg_size) msg[0] = 0;
  if (!s) return ICS_ERR_INVALID_ARG;
  ics_plan *p = calloc(1, sizeof *p);
  if (!p) return ICS_ERR_NOMEM;
  p->scene = s;
  p->rs = o.settings ? *o.settings : s->settings;
  resolve_model(p, o.renderer);
  p->cam = s->camera;
  p->tan_half_fov = tan(p->cam.fov_deg * (ICS_PI / 360));
  if (o.width > 0) p->cam.width = o.width;
  if (o.height > 0) p->cam.height_px = o.height;
  double zlo, zhi, k_est;
  plan_bytes b = {0};
  ics_status st = plan_limits(p, &zlo, &zhi, &k_est, msg, msg_size);
  if (st == ICS_OK)
    st = plan_kernels(p, k_est, o.threads, ics_renderer_kernel_cache(o.renderer), msg, msg_size);
  if (st == ICS_OK) {
    plan_padding(p, zlo, zhi, k_est);
    st = plan_volumes(p, msg, msg_size);
  }
  if (st == ICS_OK) {
    plan_apron(p);
    st = plan_memory(p, &b, msg, msg_size);
  }
  if (st == ICS_OK) st = plan_geometry(p, o.threads, &b, msg, msg_size);
  if (st != ICS_OK) {
    if (msg && msg_size && !msg[0]) snprintf(msg, msg_size, "cannot plan the render: %s", ics_status_str(st));
    if (p->over_cost && p->model_auto && p->rs.model != ICS_MODEL_PATEL && msg && msg_size)
      snprintf(msg + strlen(msg), msg_size - strlen(msg), " (render.model auto, planned as %s: "
               "render.model patel takes less)", ics_render_model_name(p->rs.model));
    ics_plan_destroy(p);
    return st;
  }
  plan_passes(p, &b);
  *out = p;
  return ICS_OK;
}

void ics_plan_destroy(ics_plan *p) {
  if (!p) return;
  if (p->kernels)
    for (int k = 0; k < p->nlights; k++) ics_slab_kernel_release(&p->kernels[k]);
  if (p->kernels_sharp)
    for (int k = 0; k < p->nlights; k++) ics_slab_kernel_release(&p->kernels_sharp[k]);
  free(p->kernels);
  free(p->kernels_sharp);
  free(p->vol_bit);
  free(p->inside_bit);
  free(p->own_lights);
  free(p->detail);
  ics_ldi_release(&p->ldi);
  free(p->active);
  free(p->tile_last);
  free(p->tile_shade);
  free(p);
}

const ics_scene *ics_plan_scene(const ics_plan *p) { return p->scene; }
int ics_plan_slabs(const ics_plan *p) { return p->K; }
size_t ics_plan_memory_bytes(const ics_plan *p) { return p->memory_bytes; }
int ics_plan_pass_count(const ics_plan *p) { return p->npasses; }
const ics_plan_pass *ics_plan_pass_at(const ics_plan *p, int i) {
  return i >= 0 && i < p->npasses ? &p->passes[i] : NULL;
}
int ics_plan_omitted_count(const ics_plan *p) { return p->nomitted; }
const ics_plan_omitted *ics_plan_omitted_at(const ics_plan *p, int i) {
  return i >= 0 && i < p->nomitted ? &p->omitted[i] : NULL;
}
void ics_plan_sizes(const ics_plan *p, int *w, int *h, int *bw, int *bh) {
  if (w) *w = p->W;
  if (h) *h = p->H;
  if (bw) *bw = p->Wb;
  if (bh) *bh = p->Hb;
}
double ics_plan_geometry_seconds(const ics_plan *p) { return p->geometry_s; }

ics_status ics_plan_write_json(const ics_plan *p, FILE *f) {
  fprintf(f, "{\n  \"scene\": ");
  ics_json_write_string(f, ics_scene_name(p->scene));
  fprintf(f, ",\n  \"resolution\": [%d, %d],\n  \"light_buffer\": [%d, %d],\n", p->W, p->H, p->Wb,
          p->Hb);
  fprintf(f, "  \"padding\": {\"left\": %d, \"right\": %d, \"top\": %d, \"bottom\": %d},\n",
          p->pad[0], p->pad[1], p->pad[2], p->pad[3]);
  fprintf(f, "  \"slabs\": %d,\n  \"slab_spacing\": %.17g,\n  \"depth_range\": [%.17g, %.17g],\n",
          p->K, p->e, p->z0, p->z0 + p->K * p->e);
  fprintf(f, "  \"model\": \"%s\",\n  \"model_auto\": %s,\n", ics_render_model_name(p->rs.model),
          p->model_auto ? "true" : "false");
  fprintf(f, "  \"channels_per_light\": %d,\n  \"memory_bytes\": %zu,\n  \"passes\": [", p->nch,
          p->memory_bytes);
  for (int i = 0; i < p->npasses; i++) {
    const ics_plan_pass *q = &p->passes[i];
    fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
    ics_json_write_string(f, q->name);
    fprintf(f, ", \"bytes\": %zu", q->bytes);
    if (q->light >= 0) {
      const ics_slab_kernel *sk = &p->kernels[q->light];
      static const char *const modes[] = {"shift", "integer", "taps", "table"};
      fprintf(f, ", \"light\": %d, \"taps\": %d, \"kernel\": \"%s\", \"samples\": %d, "
              "\"runs\": \"%s\", \"run_samples\": %d, \"mode\": \"%s\", \"compensate\": \"%s\", "
              "\"mean_px\": [%.17g, %.17g], \"cov_px\": [%.17g, %.17g, %.17g], "
              "\"active_fraction\": %.6f",
              q->light, q->taps, ics_render_kernel_name(sk->member), sk->samples,
              ics_render_kernel_name(sk->run_member), sk->run_samples, modes[sk->mode],
              ics_render_comp_name(sk->comp), sk->mean_px[0], sk->mean_px[1], sk->cov_px[0],
              sk->cov_px[1], sk->cov_px[2], p->active_fraction[q->light]);
    }
    fprintf(f, ", \"detail\": ");
    ics_json_write_string(f, q->detail);
    fputc('}', f);
  }
  fprintf(f, "\n  ],\n  \"omitted\": [");
  for (int i = 0; i < p->nomitted; i++) {
    fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
    ics_json_write_string(f, p->omitted[i].name);
    fprintf(f, ", \"reason\": ");
    ics_json_write_string(f, p->omitted[i].reason);
    fputc('}', f);
  }
  fprintf(f, "\n  ]\n}\n");
  return ferror(f) ? ICS_ERR_IO : ICS_OK;
}
