/* propagate.h — one slab step of a light buffer on the CPU (docs/renderer.md "One step"):
 * dst(p) = sum_j w_j src(c + s (p - c) - x_j), bilinear, indices clamped to the buffer. Tap
 * offsets are split into integer and fractional parts once per tap (s = 1), so no read position
 * carries an absolute float coordinate. A table of tap sets is indexed per pixel by the counter
 * RNG (ics_slab_entry). Float buffers (nch planes of w h floats), float arithmetic. */
#ifndef ICS_RENDER_PROPAGATE_H
#define ICS_RENDER_PROPAGATE_H

#include <stdint.h>

#include "icshadow/kernel.h"

/* One slab's taps, prepared for the inner loops. */
typedef struct ics_prop_taps {
  int entries, ntaps; /* entries tap sets of ntaps taps (stencil: 1 set of integer taps) */
  int stencil;        /* one tap set at s = 1, discretised to integer taps */
  double s, cx, cy;   /* magnification and principal point (s = 1: orthographic) */
  int32_t *ix, *iy;   /* integer part of each read offset -x_j */
  int32_t *off;       /* iy * w + ix: the offset of the read within the buffer */
  float *fx, *fy, *w; /* fractional part of the read offset (tables), weight */
  double *ox, *oy;    /* the read offsets -s x_j themselves (perspective) */
  ics_tap2d *disc;    /* scratch for the discretisation */
  int reach;          /* pixels closer than this to an edge clamp their reads */
  uint64_t seed;      /* table selection: ics_slab_entry(seed, light, slab, pixel) */
  uint32_t light, slab;
} ics_prop_taps;

/* Prepares taps for buffers of width w (allocating once for capacity cap per entry; call again
 * per slab). 0, or -1 when out of memory or a tap is out of range. */
int ics_prop_prepare(ics_prop_taps *pt, const ics_tap2d *taps, int entries, int ntaps, int cap,
                     double s, double cx, double cy, int w);
void ics_prop_release(ics_prop_taps *pt);

/* Rows [y0, y1) of dst from src; scratch holds w words (the row's table entries). */
void ics_prop_rows(const ics_prop_taps *pt, const float *src, float *dst, int w, int h, int nch,
                   int y0, int y1, uint32_t *scratch);

/* Pieces shared with the vectorised loops: one pixel with clamped reads from tap set e, and the
 * table entries of row y (ics_slab_entry for pixels y w .. y w + w - 1). */
void ics_prop_pixel(const ics_prop_taps *pt, int e, const float *src, float *dst, int w, int h,
                    int nch, int x, int y);
void ics_prop_entries_row(const ics_prop_taps *pt, int w, int y, uint32_t *ent);

#endif
