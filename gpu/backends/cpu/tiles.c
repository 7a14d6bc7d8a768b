/* tiles.c — the light buffers' tiles and their constants (see tiles.h). Values are compared bit
 * for bit (as 32-bit words): a constant is kept only where the dense step would read nothing
 * else. */
#include "tiles.h"

#include <string.h>

static uint32_t bits(float v) {
  uint32_t u;
  memcpy(&u, &v, sizeof u);
  return u;
}

int ics_tile_same_const(const ics_tile *a, const ics_tile *b, int nch) {
  if (a->kind != ICS_TILE_CONST || b->kind != ICS_TILE_CONST) return 0;
  for (int c = 0; c < nch; c++)
    if (bits(a->c[c]) != bits(b->c[c])) return 0;
  return 1;
}

static int grey_const(const ics_tile *t) {
  return t->kind == ICS_TILE_CONST && bits(t->c[0]) == bits(t->c[1]) && bits(t->c[1]) == bits(t->c[2]);
}

ics_tile ics_tile_classify(const ics_tile_grid *g, const ics_tile *src, int nch, int tx0, int tx1,
                           int ty0, int ty1) {
  const ics_tile *first = &src[(size_t)ty0 * g->nx + tx0];
  int same = first->kind == ICS_TILE_CONST, grey = nch == 3;
  for (int ty = ty0; ty <= ty1 && (same || grey); ty++)
    for (int tx = tx0; tx <= tx1; tx++) {
      const ics_tile *t = &src[(size_t)ty * g->nx + tx];
      if (same && !ics_tile_same_const(t, first, nch)) same = 0;
      if (grey && t->kind != ICS_TILE_GREY && !grey_const(t)) grey = 0;
    }
  ics_tile out = {ICS_TILE_ANY, {0, 0, 0}};
  if (same)
    out = *first;
  else if (grey)
    out.kind = ICS_TILE_GREY;
  return out;
}

void ics_tile_fill(const ics_buf_layout *L, float *buf, int nch, int x0, int x1, int y0, int y1,
                   const ics_tile *t) {
  for (int c = 0; c < nch; c++)
    for (int y = y0; y < y1; y++) {
      float *row = buf + (size_t)c * L->plane + ics_buf_index(L, 0, y);
      for (int x = x0; x < x1; x++) row[x] = t->c[c];
    }
}

void ics_tile_copy_grey(const ics_buf_layout *L, float *buf, int nch, int x0, int x1, int y0,
                        int y1) {
  for (int c = 1; c < nch; c++)
    for (int y = y0; y < y1; y++) {
      size_t i = ics_buf_index(L, x0, y);
      memcpy(buf + (size_t)c * L->plane + i, buf + i, sizeof *buf * (size_t)(x1 - x0));
    }
}

/* the bits in which n values differ from ref (or from b's), or-ed: 0 when all equal (loops the
 * compiler vectorises) */
static uint32_t differ_const(const float *a, uint32_t ref, int n) {
  uint32_t d = 0;
  for (int i = 0; i < n; i++) d |= bits(a[i]) ^ ref;
  return d;
}
static uint32_t differ(const float *a, const float *b, int n) {
  uint32_t d = 0;
  for (int i = 0; i < n; i++) d |= bits(a[i]) ^ bits(b[i]);
  return d;
}

void ics_tile_copy(const ics_buf_layout *L, const float *src, float *dst, int nch, int x0, int x1,
                   int y0, int y1) {
  for (int c = 0; c < nch; c++)
    for (int y = y0; y < y1; y++) {
      size_t i = (size_t)c * L->plane + ics_buf_index(L, x0, y);
      memcpy(dst + i, src + i, sizeof *dst * (size_t)(x1 - x0));
    }
}

int ics_tile_equal(const ics_buf_layout *L, const float *a, const float *b, int nch, int x0,
                   int x1, int y0, int y1) {
  for (int c = 0; c < nch; c++)
    for (int y = y0; y < y1; y++) {
      size_t i = (size_t)c * L->plane + ics_buf_index(L, x0, y);
      if (differ(a + i, b + i, x1 - x0)) return 0;
    }
  return 1;
}

ics_tile ics_tile_scan(const ics_buf_layout *L, const float *buf, int nch, int x0, int x1, int y0,
                       int y1, int grey_known) {
  ics_tile t = {ICS_TILE_CONST, {0, 0, 0}};
  int cst = 1, grey = nch == 3, n = x1 - x0, planes = grey_known ? 1 : nch;
  for (int c = 0; c < nch; c++) t.c[c] = buf[(size_t)c * L->plane + ics_buf_index(L, x0, y0)];
  for (int y = y0; y < y1 && (cst || (grey && !grey_known)); y++) {
    const float *row0 = buf + ics_buf_index(L, x0, y);
    for (int c = 0; c < planes; c++) {
      const float *row = row0 + (size_t)c * L->plane;
      if (cst && differ_const(row, bits(t.c[c]), n)) cst = 0;
      if (grey && c && differ(row, row0, n)) grey = 0;
    }
  }
  t.kind = cst ? ICS_TILE_CONST : grey ? ICS_TILE_GREY : ICS_TILE_ANY;
  return t;
}
