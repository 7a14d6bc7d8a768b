/* tiles.h — the CPU backend's light buffers cut into tiles, and what each tile holds
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

#define ICS_TILE_W 64 /* columns: a multiple of every vector width (16 floats at most) */
#define ICS_TILE_H 16 /* rows */

typedef enum ics_tile_kind { ICS_TILE_ANY = 0, ICS_TILE_GREY, ICS_TILE_CONST } ics_tile_kind;

/* What a tile of one light buffer (its nch channel planes) holds. */
typedef struct ics_tile {
  uint8_t kind;
  float c[3]; /* ICS_TILE_CONST: each channel's value */
} ics_tile;

/* A w x h buffer cut into nx x ny tiles of ICS_TILE_W x ICS_TILE_H pixels, the last column and
 * row of tiles taking the remainder (so every tile is at least a tile wide, or the whole row). */
typedef struct ics_tile_grid {
  int w, h, nx, ny;
} ics_tile_grid;

void ics_tile_grid_init(ics_tile_grid *g, int w, int h);
/* Tile column tx covers pixels [ics_tile_x0, ics_tile_x1); rows likewise. */
static inline int ics_tile_x0(const ics_tile_grid *g, int tx) { (void)g; return tx * ICS_TILE_W; }
static inline int ics_tile_x1(const ics_tile_grid *g, int tx) {
  return tx == g->nx - 1 ? g->w : (tx + 1) * ICS_TILE_W;
}
static inline int ics_tile_y0(const ics_tile_grid *g, int ty) { (void)g; return ty * ICS_TILE_H; }
static inline int ics_tile_y1(const ics_tile_grid *g, int ty) {
  return ty == g->ny - 1 ? g->h : (ty + 1) * ICS_TILE_H;
}
/* The tile column (row) holding pixel column x (row y), clamped to the buffer: a read beyond its
 * edge takes the edge pixel. */
int ics_tile_col(const ics_tile_grid *g, int x);
int ics_tile_row(const ics_tile_grid *g, int y);

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
/* What pixels [x0, x1) x [y0, y1) of buf hold (a scan: after shading wrote into them). */
ics_tile ics_tile_scan(const ics_buf_layout *L, const float *buf, int nch, int x0, int x1, int y0,
                       int y1);

#endif
