/* propagate.c — the CPU slab step (see propagate.h), portable C; propagate_avx512.c has the
 * vectorised interior loops and is used when the processor has AVX-512.
 *
 * Two forms. A single tap set (deterministic members, compensated or integer modes) at s = 1 is
 * discretised once per slab into integer taps with merged bilinear weights (the engine's
 * ics_taps2d_discretize, icshadow/conv.h) and applied as a stencil, row by row. A table of tap
 * sets (the per-pixel random members) keeps each tap's integer and fractional read offset and
 * reads bilinearly per pixel. Pixels closer to an edge than the taps' reach clamp each index to
 * the buffer (the engine's ICS_BOUNDARY_CLAMP); interior ones do not. Perspective steps (s != 1)
 * compute each read position in double and split it per read. */
#include "propagate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/conv.h"
#include "propagate_simd.h"
#include "slab_kernel.h"

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

int ics_prop_prepare(ics_prop_taps *pt, const ics_tap2d *taps, int entries, int ntaps, int cap,
                     double s, double cx, double cy, int w) {
  size_t n = (size_t)entries * (size_t)ntaps, c = (size_t)entries * (size_t)cap;
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
      pt->off[j] = pt->iy[j] * w + pt->ix[j];
      pt->w[j] = (float)pt->disc[j].w;
      int r = abs(pt->ix[j]) + 1;
      if (abs(pt->iy[j]) + 1 > r) r = abs(pt->iy[j]) + 1;
      if (r > reach) reach = r;
    }
    pt->reach = reach;
    return 0;
  }
  for (size_t j = 0; j < n; j++) {
    double ox = -taps[j].x * s, oy = -taps[j].y * s;
    double fx = floor(ox), fy = floor(oy);
    pt->ox[j] = ox;
    pt->oy[j] = oy;
    pt->ix[j] = (int32_t)fx;
    pt->iy[j] = (int32_t)fy;
    pt->off[j] = pt->iy[j] * w + pt->ix[j];
    pt->fx[j] = (float)(ox - fx);
    pt->fy[j] = (float)(oy - fy);
    pt->w[j] = (float)taps[j].w;
    int r = abs(pt->ix[j]) + 2;
    if (abs(pt->iy[j]) + 2 > r) r = abs(pt->iy[j]) + 2;
    if (r > reach) reach = r;
  }
  pt->reach = reach;
  return 0;
}

static inline int clampi(int v, int hi) { return v < 0 ? 0 : v > hi ? hi : v; }

/* one output pixel, clamped reads (any form) */
void ics_prop_pixel(const ics_prop_taps *pt, int e, const float *src, float *dst, int w, int h,
                    int nch, int x, int y) {
  size_t plane = (size_t)w * h;
  const int n = pt->ntaps, base = e * n;
  double bx = x, by = y;
  if (pt->s != 1) bx = pt->cx + pt->s * (x - pt->cx), by = pt->cy + pt->s * (y - pt->cy);
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * plane;
    float acc = 0;
    for (int j = base; j < base + n; j++) {
      if (pt->stencil) {
        acc += pt->w[j] * S[(size_t)clampi(y + pt->iy[j], h - 1) * w + clampi(x + pt->ix[j], w - 1)];
        continue;
      }
      int x0, y0;
      float fx, fy;
      if (pt->s != 1) {
        double X = bx + pt->ox[j], Y = by + pt->oy[j], fX = floor(X), fY = floor(Y);
        x0 = (int)fX, y0 = (int)fY;
        fx = (float)(X - fX), fy = (float)(Y - fY);
      } else {
        x0 = x + pt->ix[j], y0 = y + pt->iy[j];
        fx = pt->fx[j], fy = pt->fy[j];
      }
      int xa = clampi(x0, w - 1), xb = clampi(x0 + 1, w - 1);
      int ya = clampi(y0, h - 1), yb = clampi(y0 + 1, h - 1);
      float a = S[(size_t)ya * w + xa], b = S[(size_t)ya * w + xb];
      float cc = S[(size_t)yb * w + xa], d = S[(size_t)yb * w + xb];
      float top = a + fx * (b - a), bot = cc + fx * (d - cc);
      acc += pt->w[j] * (top + fy * (bot - top));
    }
    dst[(size_t)c * plane + (size_t)y * w + x] = acc;
  }
}

void ics_prop_entries_row(const ics_prop_taps *pt, int w, int y, uint32_t *ent) {
  uint32_t first = (uint32_t)((size_t)y * w), last = first + (uint32_t)w - 1;
  uint32_t words[4];
  for (uint32_t b = first / 4; b <= last / 4; b++) {
    ics_slab_entry_block(pt->seed, pt->light, pt->slab, b, words);
    for (int k = 0; k < 4; k++) {
      uint32_t px = 4 * b + (uint32_t)k;
      if (px >= first && px <= last)
        ent[px - first] = (uint32_t)(((uint64_t)words[k] * ICS_SLAB_TABLE_M) >> 32);
    }
  }
}

/* portable interior loops */
static void rows_portable(const ics_prop_taps *pt, const float *src, float *dst, int w, int h,
                          int nch, int y0, int y1, uint32_t *ent) {
  size_t plane = (size_t)w * h;
  int r = pt->reach;
  for (int y = y0; y < y1; y++) {
    int inside = y >= r && y < h - r && w > 2 * r;
    if (pt->entries > 1) ics_prop_entries_row(pt, w, y, ent);
    for (int x = 0; x < w; x++) {
      int e = pt->entries > 1 ? (int)ent[x] : 0;
      if (!inside || x < r || x >= w - r || pt->s != 1) {
        ics_prop_pixel(pt, e, src, dst, w, h, nch, x, y);
        continue;
      }
      const int n = pt->ntaps, base = e * n;
      size_t p = (size_t)y * w + x;
      for (int c = 0; c < nch; c++) {
        const float *S = src + (size_t)c * plane + p;
        float acc = 0;
        if (pt->stencil) {
          for (int j = 0; j < n; j++) acc += pt->w[j] * S[pt->off[j]];
        } else {
          for (int j = base; j < base + n; j++) {
            const float *r0 = S + pt->off[j];
            float fx = pt->fx[j], fy = pt->fy[j];
            float top = r0[0] + fx * (r0[1] - r0[0]);
            float bot = r0[w] + fx * (r0[w + 1] - r0[w]);
            acc += pt->w[j] * (top + fy * (bot - top));
          }
        }
        dst[(size_t)c * plane + p] = acc;
      }
    }
  }
}

void ics_prop_rows(const ics_prop_taps *pt, const float *src, float *dst, int w, int h, int nch,
                   int y0, int y1, uint32_t *scratch) {
  if (pt->s == 1 && ics_prop_avx512_available()) {
    ics_prop_rows_avx512(pt, src, dst, w, h, nch, y0, y1, scratch);
    return;
  }
  rows_portable(pt, src, dst, w, h, nch, y0, y1, scratch);
}
