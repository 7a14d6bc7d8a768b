/* tile_grid.h — the light buffers cut into tiles of ICS_TILE_W x ICS_TILE_H pixels, the unit in
 * which the plan says which parts of a buffer a slab needs (active_region.h) and the cpu backend
 * tracks what each part holds (backends/cpu/tiles.h). The last column and row of tiles take the
 * remainder, so every tile is at least a tile wide (or the whole row) and a vector loop never
 * needs to write beyond one. */
#ifndef ICS_RENDER_TILE_GRID_H
#define ICS_RENDER_TILE_GRID_H

#define ICS_TILE_W 64 /* columns: a multiple of every vector width (16 floats at most) */
#define ICS_TILE_H 16 /* rows */

/* A w x h buffer as nx x ny tiles. */
typedef struct ics_tile_grid {
  int w, h, nx, ny;
} ics_tile_grid;

static inline void ics_tile_grid_init(ics_tile_grid *g, int w, int h) {
  g->w = w;
  g->h = h;
  g->nx = w / ICS_TILE_W > 0 ? w / ICS_TILE_W : 1;
  g->ny = h / ICS_TILE_H > 0 ? h / ICS_TILE_H : 1;
}
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
static inline int ics_tile_col(const ics_tile_grid *g, int x) {
  int t = x < 0 ? 0 : x / ICS_TILE_W;
  return t < g->nx ? t : g->nx - 1;
}
static inline int ics_tile_row(const ics_tile_grid *g, int y) {
  int t = y < 0 ? 0 : y / ICS_TILE_H;
  return t < g->ny ? t : g->ny - 1;
}

#endif
