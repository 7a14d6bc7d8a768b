/* slab_taps.c — one slab's taps prepared for every backend's inner loops (slab_taps.h): the
 * light-buffer layout with its apron, integer and fractional read offsets per tap (s = 1: one
 * stencil of integer taps with merged bilinear weights, from the engine's ics_taps2d_discretize,
 * or several tap sets read bilinearly), and the perspective classes. The cpu backend's loops
 * (backends/cpu/propagate.c) and the cl and gl backends read the same prepared taps. */
#include "slab_taps.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/conv.h"
#include "slab_choice.h"

void ics_buf_layout_init(ics_buf_layout *L, int w, int h, int apron) {
  L->w = w;
  L->h = h;
  L->apron = apron;
  L->stride = w + 2 * apron;
  L->plane = (size_t)L->stride * (size_t)(h + 2 * apron);
  L->origin = (size_t)apron * L->stride + (size_t)apron;
}

void ics_prop_release(ics_prop_taps *pt) {
  free(pt->ix);
  free(pt->iy);
  free(pt->off);
  free(pt->fx);
  free(pt->fy);
  free(pt->w);
  free(pt->ox);
  free(pt->oy);
  free(pt->disc);
  memset(pt, 0, sizeof *pt);
}

/* the range of the read offsets (ix, iy) of n taps, widened by `wide` for the bilinear neighbour */
static void read_bounds(ics_prop_taps *pt, size_t n, int wide) {
  pt->lo[0] = pt->lo[1] = n ? INT32_MAX : 0;
  pt->hi[0] = pt->hi[1] = n ? INT32_MIN : 0;
  for (size_t j = 0; j < n; j++) {
    const int32_t v[2] = {pt->ix[j], pt->iy[j]};
    for (int a = 0; a < 2; a++) {
      if (v[a] < pt->lo[a]) pt->lo[a] = v[a];
      if (v[a] + wide > pt->hi[a]) pt->hi[a] = v[a] + wide;
    }
  }
}

void ics_prop_footprint(const ics_prop_taps *pt, int axis, int a, int b, int *first, int *last) {
  int lo = pt->lo[axis], hi = pt->hi[axis], x0 = a, x1 = b - 1;
  if (pt->s != 1) { /* the magnification's whole-pixel offset floor((s - 1)(p - c)), monotone in p */
    double c = axis ? pt->cy : pt->cx;
    x0 += (int)floor((pt->s - 1) * (a - c));
    x1 += (int)floor((pt->s - 1) * (b - 1 - c));
    if (x0 > x1) {
      int t = x0;
      x0 = x1, x1 = t;
    }
  }
  *first = x0 + lo;
  *last = x1 + hi;
}

int ics_prop_prepare(ics_prop_taps *pt, const ics_tap2d *taps, int entries, int ntaps, int cap,
                     double s, double cx, double cy, const ics_buf_layout *L) {
  size_t n = (size_t)entries * (size_t)ntaps, c = (size_t)entries * (size_t)cap;
  if (pt->ix && (pt->classes_cap || !pt->fx)) ics_prop_release(pt); /* held a perspective set */
  if (!pt->ix) {
    pt->ix = malloc(sizeof *pt->ix * 4 * c);
    pt->iy = malloc(sizeof *pt->iy * 4 * c);
    pt->off = malloc(sizeof *pt->off * 4 * c);
    pt->fx = malloc(sizeof *pt->fx * c);
    pt->fy = malloc(sizeof *pt->fy * c);
    pt->w = malloc(sizeof *pt->w * 4 * c);
    pt->ox = malloc(sizeof *pt->ox * c);
    pt->oy = malloc(sizeof *pt->oy * c);
    pt->disc = malloc(sizeof *pt->disc * 4 * c);
    if (!pt->ix || !pt->iy || !pt->off || !pt->fx || !pt->fy || !pt->w || !pt->ox || !pt->oy ||
        !pt->disc)
      return -1;
  }
  pt->classes = 0;
  pt->entries = entries;
  pt->ntaps = ntaps;
  pt->s = s;
  pt->cx = cx;
  pt->cy = cy;
  pt->stencil = 0;
  int reach = 0;
  if (entries == 1 && s == 1) {
    /* one tap set: integer taps with merged bilinear weights, applied as a stencil */
    int nd;
    if (ics_taps2d_discretize(taps, ntaps, pt->disc, 4 * cap, &nd) != ICS_OK) return -1;
    pt->stencil = 1;
    pt->ntaps = nd;
    for (int j = 0; j < nd; j++) {
      pt->ix[j] = (int32_t)-pt->disc[j].x; /* the read is at p - x_j */
      pt->iy[j] = (int32_t)-pt->disc[j].y;
      pt->off[j] = pt->iy[j] * L->stride + pt->ix[j];
      pt->w[j] = (float)pt->disc[j].w;
      int r = abs(pt->ix[j]) > abs(pt->iy[j]) ? abs(pt->ix[j]) : abs(pt->iy[j]);
      if (r > reach) reach = r;
    }
    pt->reach = reach;
    read_bounds(pt, (size_t)nd, 0);
    return 0;
  }
  for (size_t j = 0; j < n; j++) {
    double ox = -taps[j].x * s, oy = -taps[j].y * s;
    if (!(fabs(ox) < 1e9 && fabs(oy) < 1e9)) return -1;
    double fx = floor(ox), fy = floor(oy);
    pt->ox[j] = ox;
    pt->oy[j] = oy;
    pt->ix[j] = (int32_t)fx;
    pt->iy[j] = (int32_t)fy;
    pt->off[j] = pt->iy[j] * L->stride + pt->ix[j];
    pt->fx[j] = (float)(ox - fx);
    pt->fy[j] = (float)(oy - fy);
    pt->w[j] = (float)taps[j].w;
    /* the bilinear read touches ix .. ix + 1, iy .. iy + 1 */
    int r = abs(pt->ix[j]) > abs(pt->ix[j] + 1) ? abs(pt->ix[j]) : abs(pt->ix[j] + 1);
    int ry = abs(pt->iy[j]) > abs(pt->iy[j] + 1) ? abs(pt->iy[j]) : abs(pt->iy[j] + 1);
    if (ry > r) r = ry;
    if (r > reach) reach = r;
  }
  pt->reach = reach;
  if (s == 1) {
    read_bounds(pt, n, 1);
  } else { /* read at floor(c + s (p - c) + o): p + floor((s - 1)(p - c)) + floor(o) + {0, 1, 2} */
    pt->lo[0] = pt->lo[1] = INT32_MAX;
    pt->hi[0] = pt->hi[1] = INT32_MIN;
    for (size_t j = 0; j < n; j++) {
      const double o[2] = {pt->ox[j], pt->oy[j]};
      for (int a = 0; a < 2; a++) {
        int f = (int)floor(o[a]);
        if (f < pt->lo[a]) pt->lo[a] = f;
        if (f + 2 > pt->hi[a]) pt->hi[a] = f + 2;
      }
    }
  }
  return 0;
}

int ics_prop_perspective_begin(ics_prop_taps *pt, int ntaps, double s, double cx, double cy) {
  const int Q = ICS_PROP_CLASSES, cap = 4 * ntaps + 9, ncls = Q * Q;
  size_t c = (size_t)ncls * (size_t)cap;
  if (!pt->ix || pt->classes_cap < c) {
    ics_prop_release(pt);
    pt->ix = malloc(sizeof *pt->ix * c);
    pt->iy = malloc(sizeof *pt->iy * c);
    pt->w = malloc(sizeof *pt->w * c);
    pt->disc = malloc(sizeof *pt->disc * c);
    pt->off = malloc(sizeof *pt->off * (size_t)ncls); /* each class's tap count */
    if (!pt->ix || !pt->iy || !pt->w || !pt->disc || !pt->off) return -1;
    pt->classes_cap = c;
  }
  pt->entries = ncls;
  pt->s = s, pt->cx = cx, pt->cy = cy;
  pt->stencil = 0;
  pt->classes = Q;
  pt->class_cap = cap;
  return 0;
}

/* the taps as engine taps (read at p - x): x = s x_j - d for the class's fraction d */
int ics_prop_perspective_classes(ics_prop_taps *pt, const ics_tap2d *taps, int ntaps, int cl0, int cl1) {
  const int Q = pt->classes;
  ics_tap2d in[ICS_PROP_PERSPECTIVE_MAX_TAPS];
  if (ntaps > ICS_PROP_PERSPECTIVE_MAX_TAPS) return -1;
  for (int cl = cl0; cl < cl1; cl++) {
    double dx = (double)(cl % Q) / Q, dy = (double)(cl / Q) / Q;
    for (int j = 0; j < ntaps; j++) in[j] = (ics_tap2d){taps[j].x * pt->s - dx, taps[j].y * pt->s - dy, taps[j].w};
    int nout;
    if (ics_taps2d_compensate(in, ntaps, ICS_COMP_NONNEG, pt->disc + (size_t)cl * pt->class_cap,
                              pt->class_cap, &nout, NULL) != ICS_OK)
      return -1;
    pt->off[cl] = nout;
  }
  return 0;
}

void ics_prop_perspective_end(ics_prop_taps *pt) {
  const int ncls = pt->classes * pt->classes;
  int maxn = 1;
  for (int cl = 0; cl < ncls; cl++)
    if (pt->off[cl] > maxn) maxn = pt->off[cl];
  for (int cl = 0; cl < ncls; cl++) {
    const ics_tap2d *o = pt->disc + (size_t)cl * pt->class_cap;
    size_t base = (size_t)cl * (size_t)maxn;
    for (int m = 0; m < maxn; m++) {
      int in_set = m < pt->off[cl];
      pt->ix[base + m] = in_set ? (int32_t)-o[m].x : 0;
      pt->iy[base + m] = in_set ? (int32_t)-o[m].y : 0;
      pt->w[base + m] = in_set ? (float)o[m].w : 0.0f;
    }
  }
  pt->ntaps = maxn;
  /* class Q is class 0 one pixel on (pixel_classes): the reads reach one more */
  read_bounds(pt, (size_t)ncls * (size_t)maxn, 1);
}

int ics_prop_prepare_perspective(ics_prop_taps *pt, const ics_tap2d *taps, int ntaps, double s,
                                 double cx, double cy, const ics_buf_layout *L) {
  (void)L;
  if (ics_prop_perspective_begin(pt, ntaps, s, cx, cy) ||
      ics_prop_perspective_classes(pt, taps, ntaps, 0, ICS_PROP_CLASSES * ICS_PROP_CLASSES))
    return -1;
  ics_prop_perspective_end(pt);
  return 0;
}

