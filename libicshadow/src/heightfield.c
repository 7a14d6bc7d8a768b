/* heightfield.c — the synthetic height-field scene (see icshadow/heightfield.h): the default
 * scene, ray hits (slab test for the boxes, the quadratic for the caps) and the shadow map of a
 * light ray grid. */
#include "icshadow/heightfield.h"

#include <math.h>
#include <string.h>

#include "raybox.h"
#include "vec3.h"

void ics_heightfield_init_default(ics_heightfield *out) {
  if (!out) return;
  static const double boxes[][5] = {
      {-4.5, -3.0, -4.0, -2.5, 2.0}, {-1.0, 0.2, -5.0, -4.2, 2.5}, {2.0, 3.5, -3.0, -1.0, 1.2},
      {-3.0, -2.6, 0.5, 4.0, 1.8},   {0.5, 1.0, 1.0, 1.5, 2.2},    {3.0, 5.5, 2.5, 3.0, 0.8},
  };
  static const double caps[][4] = {
      {-1.5, -0.5, -1.0, 1.6}, {1.5, -1.2, 3.5, 2.0}, {4.0, 0.0, -4.5, 0.9}, {-4.5, -0.3, 4.5, 1.1},
  };
  memset(out, 0, sizeof *out);
  out->nboxes = sizeof boxes / sizeof boxes[0];
  out->ncaps = sizeof caps / sizeof caps[0];
  for (size_t i = 0; i < out->nboxes; i++) {
    for (int j = 0; j < 4; j++) out->box[i][j] = boxes[i][j];
    out->box_h[i] = boxes[i][4];
  }
  for (size_t i = 0; i < out->ncaps; i++)
    for (int j = 0; j < 4; j++) out->cap[i][j] = caps[i][j];
}

double ics_heightfield_hit(const ics_heightfield *s, const double o[3], const double dir[3],
                           double tmin) {
  if (!s || !o || !dir) return NAN;
  double best = INFINITY;
  if (dir[1] != 0) { /* the plane y = 0 */
    double t = -o[1] / dir[1];
    if (t > tmin) best = t;
  }
  for (size_t b = 0; b < s->nboxes; b++) { /* slabs */
    double lo[3] = {s->box[b][0], 0.0, s->box[b][2]};
    double hi[3] = {s->box[b][1], s->box_h[b], s->box[b][3]};
    double t0 = -INFINITY, t1 = INFINITY;
    if (!ics_ray_box_clip(o, dir, lo, hi, &t0, &t1)) continue;
    double t = t0 > tmin ? t0 : (t1 > tmin ? t1 : INFINITY);
    if (t < best) best = t;
  }
  for (size_t c = 0; c < s->ncaps; c++) { /* sphere, the part with y >= 0 */
    double oc[3] = {o[0] - s->cap[c][0], o[1] - s->cap[c][1], o[2] - s->cap[c][2]};
    double rr = s->cap[c][3];
    double A = ics_dot3(dir, dir), B = ics_dot3(oc, dir), C = ics_dot3(oc, oc) - rr * rr;
    double disc = B * B - A * C;
    if (disc < 0) continue;
    double sq = sqrt(disc);
    double ts[2] = {(-B - sq) / A, (-B + sq) / A};
    for (int j = 0; j < 2; j++) {
      double t = ts[j];
      if (!(t > tmin) || t >= best) continue;
      if (o[1] + t * dir[1] < 0) continue;
      best = t;
      break;
    }
  }
  return best;
}

ics_status ics_heightfield_shadow_map(const ics_heightfield *s, const ics_epipolar_frame *f,
                                      size_t w, double half, float *smap) {
  if (!s || !f || !smap) return ICS_ERR_INVALID_ARG;
  if (w == 0 || w > ICS_MINMAX_MAX_SAMPLES) return ICS_ERR_SIZE;
  if (isnan(half)) return ICS_ERR_NAN;
  if (!(half > 0) || isinf(half)) return ICS_ERR_RANGE;
  double texel = 2 * half / (double)w, u0 = f->eu - half, v0 = f->ev - half;
  /* light rays start on the plane depth = start_depth (above every shape) and go along -L */
  double top = 0;
  for (size_t b = 0; b < s->nboxes; b++)
    if (s->box_h[b] > top) top = s->box_h[b];
  for (size_t c = 0; c < s->ncaps; c++)
    if (s->cap[c][1] + s->cap[c][3] > top) top = s->cap[c][1] + s->cap[c][3];
  double dir[3] = {-f->L[0], -f->L[1], -f->L[2]};
  for (size_t j = 0; j < w; j++)
    for (size_t i = 0; i < w; i++) {
      double u = u0 + ((double)i + 0.5) * texel, v = v0 + ((double)j + 0.5) * texel;
      double o[3];
      for (int k = 0; k < 3; k++) o[k] = u * f->U[k] + v * f->V[k];
      /* move the origin along L until it is above the scene's top (y > top) */
      double lift = 0;
      if (f->L[1] > 0) lift = (top + 1.0 - o[1]) / f->L[1];
      for (int k = 0; k < 3; k++) o[k] += lift * f->L[k];
      double t = ics_heightfield_hit(s, o, dir, 0.0);
      smap[j * w + i] = isinf(t) ? INFINITY : (float)(-ics_dot3(o, f->L) + t);
    }
  return ICS_OK;
}
