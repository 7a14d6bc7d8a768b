/* ldi.c — the layered depth image (Patel Sec. 4.1) over the light-buffer grid, built by ray
 * casting: for every buffer pixel all crossings of its camera ray with every object, sorted
 * front to back, in a CSR layout sized exactly by a counting pass (so no layer beyond the
 * scene's depth complexity is allocated). The counting pass also finds the depth range, which
 * fixes the slabs; the fill pass stores each fragment's slab index with its object. Rows are
 * split over threads; every pixel's list depends on that pixel alone. A ray is tested only
 * against the objects whose bounding box it can meet: the box's projection onto the buffer,
 * widened by 2 pixels (a ray outside it crosses neither the box nor the object, before or
 * behind its origin; test_render_geometry checks the LDI against every object's crossings). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geometry.h"
#include "icshadow/constants.h"
#include "plan_internal.h"
#include "pool.h"
#include "scene_internal.h"

void ics_ldi_release(ics_ldi *l) {
  free(l->offset);
  free(l->frag);
  free(l->inside0);
  memset(l, 0, sizeof *l);
}

typedef struct {
  double t;
  int obj, seq; /* seq: the order found (objects in order, each object's in its order) */
  double n[3];
} hit_t;

/* by depth, object, then the order found: a total order (the same with any qsort, and the
 * device's, gpu/backends/gl/ldi.comp) */
static int cmp_hit(const void *a, const void *b) {
  const hit_t *x = a, *y = b;
  if (x->t != y->t) return (x->t > y->t) - (x->t < y->t);
  if (x->obj != y->obj) return (x->obj > y->obj) - (x->obj < y->obj);
  return (x->seq > y->seq) - (x->seq < y->seq);
}

typedef struct {
  ics_plan *p;
  int fill;        /* 0: count, 1: fill */
  int failed;      /* out of memory in some thread */
  double zmin[256], zmax[256];
  int layers[256];
  int any_inside[256];
  double reach;    /* kernel_reach, for the surface bias */
  int (*cull)[4];  /* per object: the buffer pixels [x0, x1] x [y0, y1] whose rays can meet it */
} job_t;

/* the buffer pixels whose rays can meet object o: its bounding box's corners projected with the
 * inverse of ics_plan_ray, widened by 2 pixels; every pixel when a corner is not in front of a
 * perspective eye */
static void cull_rect(const ics_plan *p, const ics_object *o, int r[4]) {
  const ics_camera *c = &p->cam;
  double lo[3], hi[3], x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  ics_object_bounds(o, lo, hi);
  r[0] = r[1] = INT32_MIN, r[2] = r[3] = INT32_MAX;
  double th = p->tan_half_fov, asp = (double)p->W / p->H;
  for (int m = 0; m < 8; m++) {
    double v[3] = {(m & 1 ? hi[0] : lo[0]) - c->eye[0], (m & 2 ? hi[1] : lo[1]) - c->eye[1],
                   (m & 4 ? hi[2] : lo[2]) - c->eye[2]};
    double a = 0, b = 0, z = 0, s, t;
    for (int i = 0; i < 3; i++) a += v[i] * c->r[i], b += v[i] * c->u[i], z += v[i] * c->f[i];
    if (c->projection == ICS_PROJ_ORTHOGRAPHIC) {
      s = a / (c->height * p->W / p->H) + 0.5, t = 0.5 - b / c->height;
    } else {
      if (!(z > 1e-9 * (fabs(a) + fabs(b) + fabs(z)))) return;
      s = 0.5 * (a / (z * th * asp) + 1), t = 0.5 * (1 - b / (z * th));
    }
    double bx = s * p->W + p->pad[0] - 0.5, by = t * p->H + p->pad[2] - 0.5;
    if (!isfinite(bx) || !isfinite(by)) return;
    x0 = fmin(x0, bx), x1 = fmax(x1, bx), y0 = fmin(y0, by), y1 = fmax(y1, by);
  }
  r[0] = (int)fmin(fmax(floor(x0) - 2, -1), p->Wb), r[1] = (int)fmin(fmax(floor(y0) - 2, -1), p->Hb);
  r[2] = (int)fmax(fmin(ceil(x1) + 2, p->Wb), -1), r[3] = (int)fmax(fmin(ceil(y1) + 2, p->Hb), -1);
}

/* all crossings of pixel (bi, bj) into *hv (grown as needed), sorted when `sorted` (the counting
 * pass needs only their number and depth range); returns the count or -1 */
static int pixel_hits(const ics_plan *p, int bi, int bj, ics_hits *h, hit_t **hv, int *hcap,
                      uint64_t *inside, int sorted, int (*cull)[4]) {
  const ics_scene *s = p->scene;
  double o[3], d[3];
  ics_plan_ray(p, bi, bj, o, d);
  int n = 0;
  *inside = 0;
  for (int k = 0; k < s->nobjects; k++) {
    if (bi < cull[k][0] || bj < cull[k][1] || bi > cull[k][2] || bj > cull[k][3]) continue;
    h->n = 0;
    int behind = 0;
    if (ics_object_hits(&s->objects[k], o, d, h, &behind)) return -1;
    if (p->inside_bit[k] >= 0 && (behind & 1)) *inside |= 1ull << p->inside_bit[k];
    if (n + h->n > *hcap) {
      int cap = 2 * (n + h->n) + 16;
      hit_t *nv = realloc(*hv, sizeof *nv * (size_t)cap);
      if (!nv) return -1;
      *hv = nv;
      *hcap = cap;
    }
    for (int i = 0; i < h->n; i++) {
      hit_t *x = &(*hv)[n];
      x->seq = n++;
      x->t = h->h[i].t;
      x->obj = k;
      memcpy(x->n, h->h[i].n, sizeof x->n);
    }
  }
  if (n > 1 && sorted) qsort(*hv, (size_t)n, sizeof **hv, cmp_hit);
  return n;
}

/* The depth gradient of a surface with normal n along the camera's r and u, dz/dr = -n.r / n.f
 * and dz/du = -n.u / n.f (dimensionless), stored x ICS_FRAG_GRAD_SCALE and clamped. */
static void surface_depth_gradient(const ics_plan *p, const double n[3], int16_t grad[2]) {
  const ics_camera *c = &p->cam;
  double nr = 0, nu = 0, nf = 0;
  for (int i = 0; i < 3; i++) {
    nr += n[i] * c->r[i];
    nu += n[i] * c->u[i];
    nf += n[i] * c->f[i];
  }
  double g[2] = {fabs(nf) > 0 ? -nr / nf : 0, fabs(nf) > 0 ? -nu / nf : 0};
  for (int k = 0; k < 2; k++)
    grad[k] = (int16_t)lrint(fmax(-32767, fmin(32767, g[k] * ICS_FRAG_GRAD_SCALE)));
}

/* How far one slab's kernel reaches laterally (world units), the largest over the lights: the
 * 2-sample ellipse's taps sit at sqrt(2 lambda_max) of the per-slab covariance d1 e Sigma, and
 * the mean moves the buffer by e |mu|. */
double ics_ldi_kernel_reach(const ics_plan *p) {
  double reach = 0;
  for (int l = 0; l < p->nlights; l++) {
    const double *mu = p->scene->lights[l].mean;
    double r = sqrt(2) * ics_plan_light_blur(p, l) + p->e * hypot(mu[0], mu[1]);
    if (r > reach) reach = r;
  }
  return reach;
}

/* A surface's depth change per unit of lateral distance, in slabs: the tan of its tilt from the
 * pixel's ray d (the view direction for orthographic cameras) over the slab spacing; 0 for a
 * surface facing the ray. */
static double surface_gradient(const ics_plan *p, const double n[3], const double d[3]) {
  double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2], dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  double nd = n[0] * d[0] + n[1] * d[1] + n[2] * d[2], c2 = nd * nd / (nn * dd);
  if (!(c2 < 1)) return 0;
  return c2 > 0 ? sqrt((1 - c2) / c2) / p->e : INFINITY;
}

static void ldi_rows(void *ctx, int t, int nt) {
  job_t *j = ctx;
  ics_plan *p = j->p;
  ics_ldi *l = &p->ldi;
  ics_hits h = {0};
  hit_t *hv = NULL;
  int hcap = 0;
  double zmin = INFINITY, zmax = -INFINITY;
  int layers = 0, any_inside = 0;
  /* rows t, t + nt, ...: the objects' rows spread over the threads (bands left one thread the
   * sky's rows) */
  for (int bj = t; bj < l->h && !j->failed; bj += nt)
    for (int bi = 0; bi < l->w; bi++) {
      size_t px = (size_t)bj * l->w + bi;
      /* filling: a ray the count found no crossing on has nothing to fill (nor a volume it
       * starts inside, with no volume containing the eye) */
      if (j->fill && l->offset[px] == l->offset[px + 1] && !l->inside0) continue;
      uint64_t inside;
      int n = pixel_hits(p, bi, bj, &h, &hv, &hcap, &inside, j->fill, j->cull);
      if (n < 0) {
        j->failed = 1;
        break;
      }
      if (!j->fill) {
        l->offset[px + 1] = (uint32_t)n; /* counts; prefix-summed afterwards */
        if (n > layers) layers = n;
        for (int i = 0; i < n; i++) zmin = fmin(zmin, hv[i].t), zmax = fmax(zmax, hv[i].t);
        if (inside) any_inside = 1;
        continue;
      }
      ics_fragment *f = l->frag + l->offset[px];
      double ro[3], rd[3];
      ics_plan_ray(p, bi, bj, ro, rd);
      for (int i = 0; i < n; i++) {
        /* the fragment's slab, and the slab its occlusion enters (docs/renderer.md "Surface
         * bias"): continuous in the surface's tilt and 0 for a surface parallel to the slabs */
        double u = (hv[i].t - p->z0) / p->e + 1e-6, k = floor(u);
        double g = surface_gradient(p, hv[i].n, rd), q = ics_plan_pixel_size(p, hv[i].t);
        /* the delay: the depth change over the larger of 3 pixels and the kernel's reach (its
         * neighbours within what one slab's kernel reads are shaded first); the span: the depth
         * change over one pixel, from which the backend takes, per light, the window a light
         * parcel cannot slip through between two neighbours (backend_cpu.c surface_occlusion) */
        double delay = fmin(g * fmax(3 * q, j->reach), ICS_FRAG_MAX_BIAS);
        double ko = floor(u + delay), span = ceil(fmin(g * q, ICS_FRAG_MAX_SPAN));
        if (k < 0) k = 0;
        if (k > p->K - 1) k = p->K - 1;
        int bias = (int)fmin(fmax(ko - k, 0), ICS_FRAG_MAX_BIAS);
        f[i].z = (float)hv[i].t;
        f[i].code = ics_frag_code(hv[i].obj, bias, (int)k);
        f[i].span = p->vol_bit[hv[i].obj] >= 0 ? 0 : (uint8_t)fmax(span, 0); /* surfaces */
        surface_depth_gradient(p, hv[i].n, f[i].grad);
      }
      if (l->inside0) l->inside0[px] = inside;
    }
  ics_hits_free(&h);
  free(hv);
  j->zmin[t] = zmin;
  j->zmax[t] = zmax;
  j->layers[t] = layers;
  j->any_inside[t] = any_inside;
}

ics_status ics_ldi_build(ics_plan *p, int threads, char *msg, size_t msg_size) {
  ics_ldi *l = &p->ldi;
  l->w = p->Wb;
  l->h = p->Hb;
  size_t npx = (size_t)l->w * l->h;
  l->offset = calloc(npx + 1, sizeof *l->offset);
  if (!l->offset) {
    if (msg) snprintf(msg, msg_size, "out of memory for the layered depth image (%zu pixels)", npx);
    return ICS_ERR_NOMEM;
  }
  ics_pool *pool = ics_pool_create(threads);
  if (!pool) pool = ics_pool_create(1);
  if (!pool) return ICS_ERR_NOMEM;
  job_t *j = calloc(1, sizeof *j);
  if (!j) {
    ics_pool_destroy(pool);
    return ICS_ERR_NOMEM;
  }
  j->p = p;
  j->cull = malloc(sizeof *j->cull * (size_t)(p->scene->nobjects ? p->scene->nobjects : 1));
  if (!j->cull) {
    free(j);
    ics_pool_destroy(pool);
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < p->scene->nobjects; k++) cull_rect(p, &p->scene->objects[k], j->cull[k]);
  ics_pool_run(pool, ldi_rows, j);
  int nt = ics_pool_size(pool);
  double zmin = INFINITY, zmax = -INFINITY;
  int any_inside = 0;
  for (int t = 0; t < nt; t++) {
    zmin = fmin(zmin, j->zmin[t]);
    zmax = fmax(zmax, j->zmax[t]);
    if (j->layers[t] > l->max_layers) l->max_layers = j->layers[t];
    any_inside |= j->any_inside[t];
  }
  ics_status st = ICS_OK;
  if (j->failed) {
    if (msg) snprintf(msg, msg_size, "out of memory in the geometry pass");
    st = ICS_ERR_NOMEM;
    goto done;
  }
  /* prefix sums; the total must fit the 32-bit offsets */
  unsigned long long total = 0;
  for (size_t i = 1; i <= npx; i++) {
    total += l->offset[i];
    if (total > 0xffffffffull) {
      if (msg) snprintf(msg, msg_size, "more than 2^32 fragments in the layered depth image");
      st = ICS_ERR_SIZE;
      goto done;
    }
    l->offset[i] = (uint32_t)total;
  }
  l->nfrag = (size_t)total;
  /* slabs: from the nearest crossing (or the eye when a volume contains it) to the farthest */
  if (l->nfrag == 0) {
    p->z0 = 0;
    p->K = 1;
  } else {
    p->z0 = any_inside ? 0 : zmin;
    double k = floor((zmax - p->z0) / p->e + 1e-6) + 1;
    if (k > ICS_FRAG_MAX_SLABS) {
      if (msg)
        snprintf(msg, msg_size, "%.3g slabs (depth range %.6g / slab_spacing %.6g) exceed the "
                 "limit %d: increase render.slab_spacing", k, zmax - p->z0, p->e, ICS_FRAG_MAX_SLABS);
      st = ICS_ERR_SIZE;
      goto done;
    }
    p->K = (int)k;
  }
  size_t fbytes = l->nfrag * sizeof *l->frag + (any_inside ? npx * sizeof *l->inside0 : 0);
  double limit = p->rs.memory_limit_mib * 1048576.0;
  if ((double)(fbytes + p->memory_bytes) > limit) {
    if (msg)
      snprintf(msg, msg_size, "the plan needs %.1f MiB (layered depth image %zu fragments, %.1f "
               "MiB), over render.memory_limit_mib = %g", (fbytes + p->memory_bytes) / 1048576.0,
               l->nfrag, fbytes / 1048576.0, p->rs.memory_limit_mib);
    st = ICS_ERR_SIZE;
    goto done;
  }
  l->frag = malloc(l->nfrag ? l->nfrag * sizeof *l->frag : 1);
  l->inside0 = any_inside ? calloc(npx, sizeof *l->inside0) : NULL;
  if (!l->frag || (any_inside && !l->inside0)) {
    if (msg) snprintf(msg, msg_size, "out of memory for %zu fragments", l->nfrag);
    st = ICS_ERR_NOMEM;
    goto done;
  }
  j->fill = 1;
  j->reach = ics_ldi_kernel_reach(p);
  ics_pool_run(pool, ldi_rows, j);
  if (j->failed) {
    if (msg) snprintf(msg, msg_size, "out of memory in the geometry pass");
    st = ICS_ERR_NOMEM;
  }
done:
  free(j->cull);
  free(j);
  ics_pool_destroy(pool);
  return st;
}
