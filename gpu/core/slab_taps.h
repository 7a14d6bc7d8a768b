/* slab_taps.h — one slab's taps prepared for the inner loops of every backend, and the layout
 * of the light buffers they step (docs/renderer.md "One step"): dst(p) = sum_j w_j src(c + s (p
 * - c) - x_j), bilinear, with the engine's clamp-to-edge boundary (icshadow/conv.h). Tap offsets
 * are split into integer and fractional parts once per tap (s = 1), so no read position carries
 * an absolute float coordinate.
 *
 * Buffers carry an apron: a w x h buffer is stored in rows of stride w + 2A with A replicated
 * edge pixels on every side, so reads within the apron need no clamping; taps that reach farther
 * take the clamped path. Light buffers are nch planes of that layout, float.
 *
 * Tap sets: one per slab (a stencil of integer taps with merged bilinear weights), or several
 * ("entries") of which each pixel uses the one chosen by the counter RNG
 * (ics_slab_pixel_choice: 2, 4 or 8 entries packed several to a word, else the word scaled). */
#ifndef ICS_RENDER_SLAB_TAPS_H
#define ICS_RENDER_SLAB_TAPS_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/kernel.h"

/* The storage of a w x h buffer with an apron of A pixels. */
typedef struct ics_buf_layout {
  int w, h, apron, stride;
  size_t plane;  /* floats per channel plane: stride * (h + 2 A) */
  size_t origin; /* index of pixel (0, 0): A stride + A */
} ics_buf_layout;

void ics_buf_layout_init(ics_buf_layout *L, int w, int h, int apron);
static inline size_t ics_buf_index(const ics_buf_layout *L, int x, int y) {
  return L->origin + (size_t)y * L->stride + (size_t)x;
}
/* One slab's taps, prepared for the inner loops. */
typedef struct ics_prop_taps {
  int entries, ntaps; /* entries tap sets of ntaps taps (stencil: 1 set of integer taps) */
  int stencil;        /* one tap set at s = 1, discretised to integer taps */
  double s, cx, cy;   /* magnification and principal point (s = 1: orthographic) */
  int32_t *ix, *iy;   /* integer part of each read offset -x_j */
  int32_t *off;       /* iy * stride + ix: the read's offset within the layout */
  float *fx, *fy, *w; /* fractional part of the read offset (tables), weight */
  double *ox, *oy;    /* the read offsets -s x_j themselves (perspective) */
  ics_tap2d *disc;    /* scratch for the discretisation */
  int reach;          /* max |integer offset| (+1 for the bilinear neighbour) */
  int lo[2], hi[2];   /* the read offsets' range per axis (x, y), bilinear neighbours included:
                         s = 1: pixel p reads within p + [lo, hi]; perspective: within
                         p + floor((s - 1)(p - c)) + [lo, hi] (ics_prop_footprint) */
  int classes;        /* perspective: Q x Q classes of the magnification's fraction (0: none) */
  size_t classes_cap; /* capacity of the perspective arrays */
  int class_cap;      /* perspective: taps room per class (4 ntaps + 9) */
  uint64_t seed;      /* entry selection: ics_slab_entry_block(seed, light, slab, ...) */
  int run;            /* 1: a choice per pixel; 16: runs of 16 pixels share one (ics_prop_run_choice) */
  int phase;          /* runs start at x = phase (mod 16) this slab */
  uint32_t light, slab;
} ics_prop_taps;

/* The source pixels that destination pixels [a, b) (b > a) read along axis 0 (x) or 1 (y):
 * [*first, *last], not clamped to the buffer (reads beyond it take its edge). */
void ics_prop_footprint(const ics_prop_taps *pt, int axis, int a, int b, int *first, int *last);

/* Prepares taps for the layout L (allocating once for capacity cap per entry; call again per
 * slab). 0, or -1 when out of memory or a tap is out of range. */
int ics_prop_prepare(ics_prop_taps *pt, const ics_tap2d *taps, int entries, int ntaps, int cap,
                     double s, double cx, double cy, const ics_buf_layout *L);
void ics_prop_release(ics_prop_taps *pt);

/* A perspective step (s != 1) with the magnification's fractional read offset folded into the
 * taps: the read of pixel p is p + D_p - s x_j with D_p = (s - 1)(p - c); for each of Q^2 classes
 * d = (i, j) / Q of the fraction (Q = ICS_PROP_CLASSES) the offsets -s x_j + d are compensated to
 * non-negative integer taps with their moments (the core's ICS_COMP_NONNEG: exact where the
 * variance exceeds the fraction's f (1 - f), else the closest, a little wider), and pixel p takes the
 * results of the four classes around frac(D_p) at p + floor(D_p), blended linearly: reads at
 * integer offsets, so the interpolation adds only r (1 - r) / Q^2 <= 1 / (4 Q^2) px^2 per axis and
 * slab (r: where the fraction lies between its classes) instead of up to 1/4, and no drift (a
 * fixed quantisation to the nearest class would move the shadow by up to 1/(2Q) px every slab,
 * in the same direction). 0, or -1 (out of memory or a compensation that failed). */
#define ICS_PROP_CLASSES 16
#define ICS_PROP_PERSPECTIVE_MAX_TAPS 400 /* taps per slab a perspective step compensates */
int ics_prop_prepare_perspective(ics_prop_taps *pt, const ics_tap2d *taps, int ntaps, double s,
                                 double cx, double cy, const ics_buf_layout *L);
/* The same in three parts, so that the Q^2 classes' compensations can run on several threads:
 * begin (allocation; 0 or -1 out of memory), the classes [cl0, cl1) (independent of each other:
 * any split gives the same taps; 0, or -1 when a compensation failed; ntaps at most
 * ICS_PROP_PERSPECTIVE_MAX_TAPS), end (the classes' taps laid out for the loops, the reads'
 * bounds) once every class is done. */
int ics_prop_perspective_begin(ics_prop_taps *pt, int ntaps, double s, double cx, double cy);
int ics_prop_perspective_classes(ics_prop_taps *pt, const ics_tap2d *taps, int ntaps, int cl0, int cl1);
void ics_prop_perspective_end(ics_prop_taps *pt);

#endif
