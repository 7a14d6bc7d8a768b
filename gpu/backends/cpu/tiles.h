/* tiles.h — what each tile of the CPU backend's light buffers holds (tile_grid.h)
 * (docs/renderer.md "Work a frame does not need"): a constant (every pixel of each channel the
 * same value, bit for bit), grey (the channels equal bit for bit, pixel by pixel) or anything.
 * A slab step leaves a constant constant: a destination tile whose every read lies in source
 * tiles holding the same constant gets that constant without a tap being read (exactly what the
 * dense step gives when the weights' float sum is 1, as for the ellipse's 1/2 and 1/2; within a
 * few float ulps per slab otherwise). A grey neighbourhood gives a grey tile: one channel is
 * stepped and copied to the others (bit for bit the dense step). */
#ifndef ICS_RENDER_TILES_H
#define ICS_RENDER_TILES_H

#include <stdint.h>

#include "slab_taps.h"
#include "tile_grid.h"

typedef enum ics_tile_kind { ICS_TILE_ANY = 0, ICS_TILE_GREY, ICS_TILE_CONST } ics_tile_kind;

/* What a tile of one light buffer (its nch channel planes) holds. */
typedef struct ics_tile {
  uint8_t kind;
  float c[3]; /* ICS_TILE_CONST: each channel's value */
} ics_tile;

/* What a destination tile holds after a step whose reads lie in source tiles [tx0, tx1] x
 * [ty0, ty1] (inclusive) of `src` (nch channels): CONST when they all hold one constant, GREY when
 * each is grey or a grey constant (nch = 3), else ANY. */
ics_tile ics_tile_classify(const ics_tile_grid *g, const ics_tile *src, int nch, int tx0, int tx1,
                           int ty0, int ty1);
/* 1 when a and b hold the same constant (bit for bit). */
int ics_tile_same_const(const ics_tile *a, const ics_tile *b, int nch);

/* Pixels [x0, x1) x [y0, y1) of every plane of buf set to the tile's constant. */
void ics_tile_fill(const ics_buf_layout *L, float *buf, int nch, int x0, int x1, int y0, int y1,
                   const ics_tile *t);
/* Planes 1 .. nch - 1 of pixels [x0, x1) x [y0, y1) copied from plane 0. */
void ics_tile_copy_grey(const ics_buf_layout *L, float *buf, int nch, int x0, int x1, int y0,
                        int y1);
/* Pixels [x0, x1) x [y0, y1) of every plane of src copied into dst (two buffers of layout L). */
void ics_tile_copy(const ics_buf_layout *L, const float *src, float *dst, int nch, int x0, int x1,
                   int y0, int y1);
/* 1 when pixels [x0, x1) x [y0, y1) of every plane of a and b are equal bit for bit. */
int ics_tile_equal(const ics_buf_layout *L, const float *a, const float *b, int nch, int x0,
                   int x1, int y0, int y1);
/* What pixels [x0, x1) x [y0, y1) of buf hold (a scan: after shading wrote into them).
 * grey_known: the caller knows the planes equal (a grey step that nothing wrote into since), so
 * plane 0 alone is read: CONST where it is constant, else GREY (what the full scan finds). */
ics_tile ics_tile_scan(const ics_buf_layout *L, const float *buf, int nch, int x0, int x1, int y0,
                       int y1, int grey_known);

#endif
