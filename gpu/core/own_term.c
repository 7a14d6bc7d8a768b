/* own_term.c — the open surfaces lit by their own term (render.model surface; docs/renderer.md
 * "Models"). An opaque planar surface S (a rect or a disk of an opaque material: opacity 1, black
 * transport) can block, for a point q on one side of its plane, only light arriving from the other
 * side: a ray from q toward the light meets the plane only when it crosses it. So when every point
 * the frame shades other than S's own (the fragments up to each view pixel's first opaque surface,
 * and a ray's origin inside a volume) lies on one side h of S's plane (within half a slab), and
 * light l comes from the other side with probability at most ICS_OWN_TERM_BEHIND, leaving S out of
 * light l's buffers changes no other point's light from l by more than that share, and takes S's
 * slicing of itself out of the buffers. S's own points are then lit by the fraction of l on their
 * side of the plane times those buffers. With no other point shaded, S is left out for every
 * light. */
#include "own_term.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/normal.h"
#include "plan_internal.h"
#include "scene_internal.h"

double ics_light_side_fraction(const ics_camera *c, const ics_light *lt, const double n[3]) {
  double ar = 0, au = 0, b = 0;
  for (int i = 0; i < 3; i++) ar += n[i] * c->r[i], au += n[i] * c->u[i], b -= n[i] * c->f[i];
  double m = ar * lt->mean[0] + au * lt->mean[1] + b;
  double v = ar * ar * lt->cov[0] + 2 * ar * au * lt->cov[1] + au * au * lt->cov[2];
  return v > 0 ? ics_normal_cdf(m / sqrt(v)) : m > 0 ? 1 : m < 0 ? 0 : 0.5;
}

static int opaque_plane(const ics_scene *s, const ics_object *o) {
  const ics_material *m = &s->materials[o->material];
  return (o->shape == ICS_SHAPE_RECT || o->shape == ICS_SHAPE_DISK) && !m->volumetric &&
         m->opacity == 1 && m->transport[0] == 0 && m->transport[1] == 0 && m->transport[2] == 0;
}

/* the signed distances from candidate c's plane of the point o + z d, folded into lo[c], hi[c] */
static void fold_point(const ics_scene *s, const int *cand, int nc, int obj, const double o[3],
                       const double d[3], double z, double *lo, double *hi) {
  for (int c = 0; c < nc; c++) {
    if (cand[c] == obj) continue; /* S's own points lie on its plane */
    const ics_object *S = &s->objects[cand[c]];
    double dist = 0;
    for (int i = 0; i < 3; i++) dist += (o[i] + z * d[i] - S->center[i]) * S->ax[2][i];
    lo[c] = fmin(lo[c], dist), hi[c] = fmax(hi[c], dist);
  }
}

/* every view pixel's shaded points: its fragments up to its first opaque surface, and its ray's
 * origin (the first slab's front) when that lies inside a volume */
static void shaded_extent(const ics_plan *p, const int *cand, int nc, double *lo, double *hi) {
  const ics_scene *s = p->scene;
  const ics_ldi *L = &p->ldi;
  for (int bj = p->pad[2]; bj < p->pad[2] + p->H; bj++)
    for (int bi = p->pad[0]; bi < p->pad[0] + p->W; bi++) {
      size_t px = (size_t)bj * p->Wb + bi;
      double o[3], d[3];
      ics_plan_ray(p, bi, bj, o, d);
      if (L->inside0 && L->inside0[px]) fold_point(s, cand, nc, -1, o, d, p->z0, lo, hi);
      for (uint32_t f = L->offset[px]; f < L->offset[px + 1]; f++) {
        int obj = ics_frag_obj(&L->frag[f]);
        const ics_material *m = &s->materials[s->objects[obj].material];
        if (m->volumetric || m->opacity > 0) fold_point(s, cand, nc, obj, o, d, L->frag[f].z, lo, hi);
        if (!m->volumetric && m->opacity >= 1) break;
      }
    }
}

/* the lights for which candidate S, whose other shaded points span [lo, hi] from its plane, is
 * left out */
static uint64_t own_lights_of(const ics_plan *p, const ics_object *S, double lo, double hi) {
  double tol = p->e / 2, n[3];
  uint64_t bits = 0;
  if (lo > hi) return p->nlights < 64 ? (1ull << p->nlights) - 1 : ~0ull; /* nothing else shaded */
  for (int side = -1; side <= 1; side += 2) {
    if (side > 0 ? lo < -tol : hi > tol) continue; /* points on both sides */
    for (int i = 0; i < 3; i++) n[i] = -side * S->ax[2][i]; /* toward the other side */
    for (int l = 0; l < p->nlights; l++)
      if (ics_light_side_fraction(&p->cam, &p->scene->lights[l], n) <= ICS_OWN_TERM_BEHIND)
        bits |= 1ull << l;
  }
  return bits;
}

ics_status ics_plan_own_surfaces(ics_plan *p) {
  const ics_scene *s = p->scene;
  p->own_lights = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *p->own_lights);
  if (!p->own_lights) return ICS_ERR_NOMEM;
  if (p->rs.model < ICS_MODEL_SURFACE) return ICS_OK;
  int nc = 0, *cand = malloc(sizeof *cand * (size_t)(s->nobjects ? s->nobjects : 1));
  double *lo = malloc(sizeof *lo * (size_t)(s->nobjects ? s->nobjects : 1));
  double *hi = malloc(sizeof *hi * (size_t)(s->nobjects ? s->nobjects : 1));
  ics_status st = cand && lo && hi ? ICS_OK : ICS_ERR_NOMEM;
  for (int k = 0; st == ICS_OK && k < s->nobjects; k++)
    if (opaque_plane(s, &s->objects[k])) lo[nc] = INFINITY, hi[nc] = -INFINITY, cand[nc++] = k;
  if (st == ICS_OK && nc) {
    shaded_extent(p, cand, nc, lo, hi);
    for (int c = 0; c < nc; c++) {
      p->own_lights[cand[c]] = own_lights_of(p, &s->objects[cand[c]], lo[c], hi[c]);
      p->own_any |= p->own_lights[cand[c]] != 0;
    }
  }
  free(cand);
  free(lo);
  free(hi);
  return st;
}

void ics_own_term_describe(const ics_plan *p, char *d, size_t n) {
  d[0] = 0;
  for (int k = 0; k < p->scene->nobjects; k++) {
    uint64_t bits = p->own_lights[k];
    if (!bits) continue;
    size_t at = strlen(d);
    snprintf(d + at, n - at, "%sobject %d (lights", at ? "; " : "", p->scene->objects[k].source);
    for (int l = 0; l < p->nlights; l++)
      if (bits >> l & 1) at = strlen(d), snprintf(d + at, n - at, " %d", l);
    at = strlen(d);
    snprintf(d + at, n - at, ")");
  }
}

const char *ics_plan_model_needs(const ics_plan *p) {
  if (p->rs.model >= ICS_MODEL_BLOCKER) return "blocker-aware penumbrae";
  if (p->rs.model >= ICS_MODEL_SOLID && p->solid_bits) return "closed opaque objects";
  if (p->rs.model >= ICS_MODEL_SURFACE && p->own_any) return "open surfaces lit by their own term";
  if (p->rs.model >= ICS_MODEL_SURFACE && p->nvol) return "volumes (a piece's own term)";
  return NULL;
}
