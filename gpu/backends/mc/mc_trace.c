/* mc_trace.c — the Monte-Carlo reference's estimators (see mc_trace.h, docs/reference.md). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "mc_trace.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "detail.h"
#include "geometry.h"
#include "icshadow/light.h"
#include "scene_internal.h"

ics_status mc_scene_init(mc_scene *m, const ics_plan *P, int embree, char *msg, size_t msg_size) {
  memset(m, 0, sizeof *m);
  const ics_scene *s = P->scene;
  m->P = P;
  m->s = s;
  m->majorant = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *m->majorant);
  if (!m->majorant) return ICS_ERR_NOMEM;
  double extent = 0;
  for (int i = 0; i < s->nobjects; i++) {
    if (P->vol_bit[i] >= 0) {
      m->vol_obj[P->vol_bit[i]] = i;
      m->majorant[i] = ics_material_majorant(&s->materials[s->objects[i].material]);
    }
    double lo[3], hi[3];
    ics_object_bounds(&s->objects[i], lo, hi);
    for (int k = 0; k < 3; k++) extent = fmax(extent, fmax(fabs(lo[k]), fabs(hi[k])));
  }
  for (int k = 0; k < 3; k++) extent = fmax(extent, fabs(P->cam.eye[k]));
  m->eps = 1e-9 * (1 + extent);
  for (int l = 0; l < P->nlights; l++) ics_light_cov_sqrt(s->lights[l].cov, m->root[l]);
  if (embree > 0 && s->nmeshes > 0) {
    ics_status st = mc_embree_create(&m->embree, s, embree, msg, msg_size);
    if (st != ICS_OK) {
      mc_scene_release(m);
      return st;
    }
  }
  return ICS_OK;
}

void mc_scene_release(mc_scene *m) {
  free(m->majorant);
  m->majorant = NULL;
  mc_embree_destroy(m->embree);
  m->embree = NULL;
}

void mc_thread_release(mc_thread *th) {
  ics_hits_free(&th->hits);
  mc_embree_scratch_free(&th->esc);
  free(th->x);
  free(th->cam);
  memset(th, 0, sizeof *th);
}

static int cmp_cross(const void *a, const void *b) {
  const mc_cross *x = a, *y = b;
  if (x->t != y->t) return x->t < y->t ? -1 : 1;
  if (x->obj != y->obj) return x->obj - y->obj;
  return x->seq - y->seq;
}

int mc_crossings(mc_thread *th, const mc_scene *m, const double orig[3], const double dir[3],
                 double tmin, uint64_t *inside) {
  const ics_scene *s = m->s;
  th->nx = 0;
  *inside = 0;
  for (int k = 0; k < s->nobjects; k++) {
    th->hits.n = 0;
    int behind = 0;
    if (m->embree && s->objects[k].shape == ICS_SHAPE_MESH
            ? mc_embree_hits(m->embree, k, orig, dir, &th->esc, &th->hits, &behind)
            : ics_object_hits(&s->objects[k], orig, dir, &th->hits, &behind))
      return -1;
    int bit = m->P->vol_bit[k];
    if (bit >= 0 && (behind & 1)) *inside |= 1ull << bit;
    for (int i = 0; i < th->hits.n; i++) {
      if (th->hits.h[i].t <= tmin) {
        /* a volume's crossing in (0, tmin] still counts for the parity at the origin */
        if (bit >= 0) *inside ^= 1ull << bit;
        continue;
      }
      if (th->nx == th->cap) {
        int cap = th->cap ? 2 * th->cap : 64;
        mc_cross *x = realloc(th->x, sizeof *x * (size_t)cap);
        if (!x) return -1;
        th->x = x, th->cap = cap;
      }
      th->x[th->nx].t = th->hits.h[i].t;
      th->x[th->nx].seq = th->nx;
      memcpy(th->x[th->nx].n, th->hits.h[i].n, sizeof th->x[th->nx].n);
      th->x[th->nx++].obj = k;
    }
  }
  if (th->nx > 1) qsort(th->x, (size_t)th->nx, sizeof *th->x, cmp_cross);
  return 0;
}

/* the extinction of each volume of `inside` at p (detail evaluated), their sum, and the
 * extinction-weighted colour */
static double volume_at(const mc_scene *m, uint64_t inside, const double p[3], double *sig,
                        double col[3]) {
  const ics_scene *s = m->s;
  double sum = 0;
  if (col) col[0] = col[1] = col[2] = 0;
  int n = 0;
  for (uint64_t b = inside; b; b &= b - 1, n++) {
    int obj = m->vol_obj[__builtin_ctzll(b)];
    const ics_material *mat = &s->materials[s->objects[obj].material];
    double scale = 1, c[3] = {mat->color[0], mat->color[1], mat->color[2]};
    if (mat->detail.fn != ICS_DETAIL_NONE)
      ics_material_transfer(mat, ics_detail_value(&m->P->detail[obj], p), c, &scale);
    sig[n] = mat->extinction * scale;
    sum += sig[n];
    if (col)
      for (int k = 0; k < 3; k++) col[k] += sig[n] * c[k];
  }
  if (col && sum > 0)
    for (int k = 0; k < 3; k++) col[k] /= sum;
  return sum;
}

/* Only volumes with detail are tracked step by step (the others are integrated in closed form,
 * and a camera walk through them ends at its first step); over a chord a walk takes about
 * majorant x length steps at most, and no chord inside a volume is longer than its bounding
 * box's diagonal. A bound, not an expectation: dense volumes end walks sooner (a camera walk at
 * its first real collision, a light ray once its transmittance has underflowed to 0). */
double mc_steps_per_ray(const mc_scene *m) {
  const ics_scene *s = m->s;
  double sum = 0;
  for (int i = 0; i < s->nobjects; i++) {
    if (!(m->majorant[i] > 0) || s->materials[s->objects[i].material].detail.fn == ICS_DETAIL_NONE)
      continue;
    double lo[3], hi[3];
    ics_object_bounds(&s->objects[i], lo, hi);
    sum += m->majorant[i] * sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                 (hi[2] - lo[2]) * (hi[2] - lo[2]));
  }
  return sum;
}

static double majorant_of(const mc_scene *m, uint64_t inside, int *any_detail) {
  double sum = 0;
  *any_detail = 0;
  for (uint64_t b = inside; b; b &= b - 1) {
    int obj = m->vol_obj[__builtin_ctzll(b)];
    sum += m->majorant[obj];
    *any_detail |= m->s->materials[m->s->objects[obj].material].detail.fn != ICS_DETAIL_NONE;
  }
  return sum;
}

static double exp_step(ics_rng *r, double rate) { return -log(1 - ics_rng_uniform(r)) / rate; }

/* 1 (and th->late) once th->deadline has passed; the clock is read every 1024 steps */
static int past_deadline(mc_thread *th) {
  if (!(th->deadline > 0) || (++th->steps & 1023u)) return 0;
  return th->late = ics_clock_s() > th->deadline;
}


static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

int mc_light_transmittance(mc_thread *th, const mc_scene *m, int l, const double p[3],
                           const mc_surface *own, ics_rng *r, double T[3]) {
  const ics_plan *P = m->P;
  const ics_scene *s = m->s;
  const ics_light *L = &s->lights[l];
  const double *R = m->root[l];
  double z1 = ics_rng_normal(r), z2 = ics_rng_normal(r);
  double X = L->mean[0] + R[0] * z1 + R[1] * z2, Y = L->mean[1] + R[1] * z1 + R[2] * z2, w[3];
  for (int k = 0; k < 3; k++) w[k] = X * P->cam.r[k] + Y * P->cam.u[k] - P->cam.f[k];
  double wl = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  T[0] = T[1] = T[2] = 1;
  if (own && dot3(w, own->n) * dot3(own->d, own->n) > 0) /* through the surface itself */
    for (int c = 0; c < 3; c++) T[c] *= 1 - own->mat->opacity * (1 - own->mat->transport[c]);
  /* the ray's own volume state just off p (robust where p lies on a volume's boundary: a point
   * strictly inside has the camera's), up to the eye plane: depth falls by 1 per unit t */
  uint64_t mask;
  if (mc_crossings(th, m, p, w, m->eps, &mask)) return -1;
  double tmax = 0;
  for (int k = 0; k < 3; k++) tmax += (p[k] - P->cam.eye[k]) * P->cam.f[k];
  double ta = 0;
  for (int i = 0; i <= th->nx && ta < tmax; i++) {
    double tb = i < th->nx && th->x[i].t < tmax ? th->x[i].t : tmax;
    int at_crossing = i < th->nx && th->x[i].t < tmax;
    if (mask && tb > ta) {
      int detail;
      double maj = majorant_of(m, mask, &detail), sig[ICS_MAX_VOLUMES];
      if (!detail) {
        double sc[3] = {0, 0, 0};
        int n = 0;
        volume_at(m, mask, p, sig, NULL);
        for (uint64_t b = mask; b; b &= b - 1, n++) {
          const double *tr = s->materials[s->objects[m->vol_obj[__builtin_ctzll(b)]].material].transport;
          for (int c = 0; c < 3; c++) sc[c] += sig[n] * (1 - tr[c]);
        }
        for (int c = 0; c < 3; c++) T[c] *= exp(-sc[c] * (tb - ta) * wl);
      } else if (maj > 0) { /* ratio tracking */
        for (double t = ta + exp_step(r, maj * wl); t < tb; t += exp_step(r, maj * wl)) {
          if (past_deadline(th)) return -1;
          double q[3], sc[3] = {0, 0, 0};
          for (int k = 0; k < 3; k++) q[k] = p[k] + t * w[k];
          volume_at(m, mask, q, sig, NULL);
          int n = 0;
          for (uint64_t b = mask; b; b &= b - 1, n++) {
            const double *tr = s->materials[s->objects[m->vol_obj[__builtin_ctzll(b)]].material].transport;
            for (int c = 0; c < 3; c++) sc[c] += sig[n] * (1 - tr[c]);
          }
          for (int c = 0; c < 3; c++) T[c] *= 1 - sc[c] / maj;
          if (T[0] == 0 && T[1] == 0 && T[2] == 0) break; /* stays 0 */
        }
      }
    }
    if (!at_crossing) break;
    int obj = th->x[i].obj, bit = P->vol_bit[obj];
    if (bit >= 0) {
      mask ^= 1ull << bit;
    } else {
      const ics_material *mat = &s->materials[s->objects[obj].material];
      for (int c = 0; c < 3; c++) T[c] *= 1 - mat->opacity * (1 - mat->transport[c]);
    }
    if (T[0] == 0 && T[1] == 0 && T[2] == 0) break;
    ta = tb;
  }
  return 0;
}

/* L(p) per channel and, when vis is non-NULL, the transmittance toward each light; own: the
 * surface p lies on, or NULL */
static int light_at(mc_thread *th, const mc_scene *m, const double p[3], const mc_surface *own,
                    ics_rng *r, double Lc[3], double (*vis)[3]) {
  Lc[0] = Lc[1] = Lc[2] = 0;
  for (int l = 0; l < m->P->nlights; l++) {
    const ics_light *L = &m->s->lights[l];
    double T[3];
    if (mc_light_transmittance(th, m, l, p, own, r, T)) return -1;
    for (int c = 0; c < 3; c++) Lc[c] += L->color[c] * L->weight * T[c];
    if (vis) memcpy(vis[l], T, sizeof T);
  }
  return 0;
}

int mc_pixel_sample(mc_thread *th, const mc_scene *m, int i, int j, int want_vis, ics_rng *r,
                    mc_sample *out) {
  const ics_plan *P = m->P;
  const ics_scene *s = m->s;
  memset(out, 0, sizeof *out);
  if (th->deadline > 0 && (th->late = ics_clock_s() > th->deadline)) return -1;
  double o[3], d[3];
  ics_plan_ray(P, i + P->pad[0], j + P->pad[2], o, d);
  double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]); /* path per unit depth */
  uint64_t mask;
  if (mc_crossings(th, m, o, d, 0, &mask)) return -1;
  /* the light estimates below reuse th's crossing list: the camera's moves to th->cam */
  int nx = th->nx;
  if (nx > th->camcap) {
    mc_cross *c = realloc(th->cam, sizeof *c * (size_t)nx);
    if (!c) return -1;
    th->cam = c, th->camcap = nx;
  }
  mc_cross *cam = th->cam;
  if (nx) memcpy(cam, th->x, sizeof *cam * (size_t)nx);
  /* the first surface (opacity > 0), from the geometry alone */
  int first = -1;
  for (int k = 0; k < nx && first < 0; k++)
    if (P->vol_bit[cam[k].obj] < 0 && s->materials[s->objects[cam[k].obj].material].opacity > 0)
      first = k;
  if (first >= 0) out->surface = 1, out->z = cam[first].t;
  double beta = 1, ta = 0, Lc[3];
  int ended = 0;
  for (int k = 0; k <= nx && (!ended || (want_vis && k <= first)); k++) {
    double tb = k < nx ? cam[k].t : INFINITY;
    if (!ended && mask && tb < INFINITY) { /* delta tracking through the volumes */
      int detail;
      double maj = majorant_of(m, mask, &detail), sig[ICS_MAX_VOLUMES], col[3];
      for (double t = maj > 0 ? ta + exp_step(r, maj * dl) : INFINITY; t < tb;
           t += exp_step(r, maj * dl)) {
        if (past_deadline(th)) return -1;
        double q[3];
        for (int c = 0; c < 3; c++) q[c] = o[c] + t * d[c];
        double sg = volume_at(m, mask, q, sig, col);
        if (detail && ics_rng_uniform(r) * maj >= sg) continue; /* a null collision */
        if (light_at(th, m, q, NULL, r, Lc, NULL)) return -1;
        for (int c = 0; c < 3; c++) out->rgba[c] += beta * col[c] * Lc[c];
        beta = 0;
        ended = 1;
        break;
      }
    }
    if (k == nx) break;
    int obj = cam[k].obj, bit = P->vol_bit[obj];
    if (bit >= 0) {
      mask ^= 1ull << bit;
    } else {
      const ics_material *mat = &s->materials[s->objects[obj].material];
      int vis_here = want_vis && k == first;
      if (mat->opacity > 0 && (vis_here || !ended)) {
        double q[3];
        for (int c = 0; c < 3; c++) q[c] = o[c] + tb * d[c];
        mc_surface own = {cam[k].n, d, mat};
        if (light_at(th, m, q, &own, r, Lc, vis_here ? out->vis : NULL)) return -1;
        if (!ended) {
          for (int c = 0; c < 3; c++) out->rgba[c] += beta * mat->opacity * mat->color[c] * Lc[c];
          beta *= 1 - mat->opacity;
          if (beta == 0) ended = 1;
        }
      }
    }
    ta = tb;
  }
  for (int c = 0; c < 3; c++) out->rgba[c] += beta * P->rs.background[c];
  out->rgba[3] = 1 - beta;
  return 0;
}
