/* propagate.c — the CPU slab step (see propagate.h), portable C; propagate_vec.h has the vector
 * loops, one build per instruction set, taken where the processor has it (simd_path.h).
 *
 * A single tap set at s = 1 (core/slab_taps.c discretised it into integer taps with merged
 * bilinear weights) is applied as a stencil. Several tap sets keep each tap's integer and
 * fractional read offset and read bilinearly. Reads within the apron need
 * no clamping; a step whose taps reach beyond it, and every perspective step (s != 1), clamps
 * each index to the buffer: the engine's ICS_BOUNDARY_CLAMP either way. */
#include "propagate.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "propagate_simd.h"
#include "slab_choice.h"

void ics_prop_apron(const ics_buf_layout *L, float *buf, int nch, int y0, int y1, int edges) {
  int A = L->apron;
  if (!A) return;
  for (int c = 0; c < nch; c++) {
    float *P = buf + (size_t)c * L->plane;
    for (int y = y0; y < y1; y++) {
      float *row = P + ics_buf_index(L, 0, y);
      for (int i = 1; i <= A; i++) row[-i] = row[0], row[L->w - 1 + i] = row[L->w - 1];
    }
    const float *first = P + ics_buf_index(L, 0, 0) - A, *last = P + ics_buf_index(L, 0, L->h - 1) - A;
    for (int i = 1; i <= A; i++) {
      if (edges & ICS_APRON_TOP)
        memcpy(P + ics_buf_index(L, 0, -i) - A, first, sizeof *P * (size_t)L->stride);
      if (edges & ICS_APRON_BOTTOM)
        memcpy(P + ics_buf_index(L, 0, L->h - 1 + i) - A, last, sizeof *P * (size_t)L->stride);
    }
  }
}

static inline int clampi(int v, int hi) { return v < 0 ? 0 : v > hi ? hi : v; }

/* the taps of class (bx, by) of a perspective step applied at pixel (nx, ny), clamped reads */
static inline float class_sum(const ics_prop_taps *pt, const float *S, const ics_buf_layout *L,
                              int bx, int by, int nx, int ny) {
  const int Q = pt->classes, n = pt->ntaps;
  if (bx == Q) bx = 0, nx++; /* class Q is class 0 one pixel on */
  if (by == Q) by = 0, ny++;
  size_t base = (size_t)(by * Q + bx) * (size_t)n;
  float acc = 0;
  for (size_t m = base; m < base + (size_t)n; m++)
    acc += pt->w[m] * S[ics_buf_index(L, clampi(nx + pt->ix[m], L->w - 1), clampi(ny + pt->iy[m], L->h - 1))];
  return acc;
}

/* a perspective step's pixel (see ics_prop_prepare_perspective): the classes on either side of
 * the fraction, blended linearly by where it lies between them */
void ics_prop_pixel_classes(const ics_prop_taps *pt, const float *src, float *dst,
                            const ics_buf_layout *L, int nch, int x, int y) {
  const int Q = pt->classes;
  double D[2] = {(pt->s - 1) * (x - pt->cx), (pt->s - 1) * (y - pt->cy)};
  int n[2], k[2];
  float r[2];
  for (int a = 0; a < 2; a++) {
    double f = floor(D[a]), t = (D[a] - f) * Q, kk = floor(t);
    n[a] = (int)f;
    k[a] = (int)kk;
    r[a] = (float)(t - kk);
  }
  int nx = x + n[0], ny = y + n[1];
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane;
    float a00 = class_sum(pt, S, L, k[0], k[1], nx, ny), a10 = class_sum(pt, S, L, k[0] + 1, k[1], nx, ny);
    float a01 = class_sum(pt, S, L, k[0], k[1] + 1, nx, ny),
          a11 = class_sum(pt, S, L, k[0] + 1, k[1] + 1, nx, ny);
    float top = a00 + r[0] * (a10 - a00), bot = a01 + r[0] * (a11 - a01);
    dst[(size_t)c * L->plane + ics_buf_index(L, x, y)] = top + r[1] * (bot - top);
  }
}

void ics_prop_pixel(const ics_prop_taps *pt, int e, const float *src, float *dst,
                    const ics_buf_layout *L, int nch, int x, int y) {
  const int w = L->w, h = L->h, n = pt->ntaps, base = e * n;
  double bx = x, by = y;
  if (pt->s != 1) bx = pt->cx + pt->s * (x - pt->cx), by = pt->cy + pt->s * (y - pt->cy);
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane;
    float acc = 0;
    for (int j = base; j < base + n; j++) {
      if (pt->stencil) {
        acc += pt->w[j] * S[ics_buf_index(L, clampi(x + pt->ix[j], w - 1), clampi(y + pt->iy[j], h - 1))];
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
      float a = S[ics_buf_index(L, xa, ya)], b = S[ics_buf_index(L, xb, ya)];
      float cc = S[ics_buf_index(L, xa, yb)], d = S[ics_buf_index(L, xb, yb)];
      float top = a + fx * (b - a), bot = cc + fx * (d - cc);
      acc += pt->w[j] * (top + fy * (bot - top));
    }
    dst[(size_t)c * L->plane + ics_buf_index(L, x, y)] = acc;
  }
}

uint32_t ics_prop_run_choice(const ics_prop_taps *pt, int w, int x, int y) {
  uint32_t id = (uint32_t)((size_t)y * (size_t)(w + 32) + 16 * (size_t)((x + 16 - pt->phase) / 16));
  return ics_slab_choice(pt->seed, pt->light, pt->slab, id, (uint32_t)pt->entries);
}

void ics_prop_entries_row(const ics_prop_taps *pt, int w, int y, int x0, int x1, uint32_t *ent) {
  if (pt->run > 1) {
    for (int x = x0; x < x1; x++) ent[x] = ics_prop_run_choice(pt, w, x, y);
    return;
  }
  uint32_t first = (uint32_t)((size_t)y * w), k = (uint32_t)pt->entries;
  uint32_t span = 64 * ics_slab_choice_chunks(k), words[4], block = UINT32_MAX;
  int b = ics_slab_choice_bits(k);
  for (int x = x0; x < x1; x++) { /* (ics_slab_pixel_choice, a block's words fetched once) */
    uint32_t px = first + (uint32_t)x, r = px % span, bl = px / span * 16 + r % 16;
    if (bl != block) ics_slab_entry_block(pt->seed, pt->light, pt->slab, bl, words), block = bl;
    ent[x] = ics_slab_word_choice(words[r % 64 / 16], k, b, r / 64);
  }
}

/* portable loops: unclamped reads within the apron */
static void span_portable(const ics_prop_taps *pt, const float *src, float *dst,
                          const ics_buf_layout *L, int nch, int y0, int y1, int x0, int x1,
                          uint32_t *ent) {
  int w = L->w, clamped = pt->s != 1 || pt->reach > L->apron;
  for (int y = y0; y < y1; y++) {
    if (pt->entries > 1) ics_prop_entries_row(pt, w, y, x0, x1, ent);
    for (int x = x0; x < x1; x++) {
      int e = pt->entries > 1 ? (int)ent[x] : 0;
      if (clamped) {
        ics_prop_pixel(pt, e, src, dst, L, nch, x, y);
        continue;
      }
      const int n = pt->ntaps, base = e * n;
      size_t p = ics_buf_index(L, x, y);
      for (int c = 0; c < nch; c++) {
        const float *S = src + (size_t)c * L->plane + p;
        float acc = 0;
        if (pt->stencil) {
          for (int j = 0; j < n; j++) acc += pt->w[j] * S[pt->off[j]];
        } else {
          for (int j = base; j < base + n; j++) {
            const float *r0 = S + pt->off[j];
            float fx = pt->fx[j], fy = pt->fy[j];
            float top = r0[0] + fx * (r0[1] - r0[0]);
            float bot = r0[L->stride] + fx * (r0[L->stride + 1] - r0[L->stride]);
            acc += pt->w[j] * (top + fy * (bot - top));
          }
        }
        dst[(size_t)c * L->plane + p] = acc;
      }
    }
  }
}

void ics_prop_span(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                   int nch, int y0, int y1, int x0, int x1, uint32_t *scratch, ics_simd_path simd) {
  if (x1 <= x0 || y1 <= y0) return;
  if (pt->classes || (pt->s == 1 && pt->reach <= L->apron)) {
    switch (simd) {
    case ICS_SIMD_SSE2: ics_prop_rows_sse2(pt, src, dst, L, nch, y0, y1, x0, x1, scratch); return;
    case ICS_SIMD_NEON: ics_prop_rows_neon(pt, src, dst, L, nch, y0, y1, x0, x1, scratch); return;
    case ICS_SIMD_AVX2: ics_prop_rows_avx2(pt, src, dst, L, nch, y0, y1, x0, x1, scratch); return;
    case ICS_SIMD_AVX512: ics_prop_rows_avx512(pt, src, dst, L, nch, y0, y1, x0, x1, scratch); return;
    default: break;
    }
  }
  if (pt->classes) {
    for (int y = y0; y < y1; y++)
      for (int x = x0; x < x1; x++) ics_prop_pixel_classes(pt, src, dst, L, nch, x, y);
    return;
  }
  span_portable(pt, src, dst, L, nch, y0, y1, x0, x1, scratch);
}

void ics_prop_rows(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                   int nch, int y0, int y1, uint32_t *scratch, ics_simd_path simd) {
  ics_prop_span(pt, src, dst, L, nch, y0, y1, 0, L->w, scratch, simd);
}
