/* active_region.c — the light buffers' active regions (see active_region.h): a backward pass
 * over the slabs from the view, each step the footprint of the next slab's taps. */
#include "active_region.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "plan_internal.h"
#include "scene_internal.h"

const ics_rect *ics_active_region(const struct ics_plan *p, int l, int k) {
  return &p->active[(size_t)k * (size_t)p->nlights + (size_t)l];
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* the pixels that slab k + 1, whose reads lie within p + [off.x0, off.x1] x [off.y0, off.y1],
 * reads to make `next`, joined with `next` itself (so the regions only shrink) and the view,
 * within the buffer (orthographic: s = 1) */
static ics_rect widen(const ics_plan *p, const ics_rect *off, const ics_rect *next,
                      const ics_rect *view) {
  int x0 = next->x0 + off->x0, x1 = next->x1 - 1 + off->x1;
  int y0 = next->y0 + off->y0, y1 = next->y1 - 1 + off->y1;
  ics_rect r = {clampi(x0, 0, p->Wb - 1), clampi(y0, 0, p->Hb - 1), clampi(x1, 0, p->Wb - 1) + 1,
                clampi(y1, 0, p->Hb - 1) + 1};
  ics_rect_join(&r, next);
  ics_rect_join(&r, view);
  return r;
}

/* light l's read offsets of every slab (forwards, as the backend prepares them: the integer
 * schedule carries its state; *all: their range over the slabs), then the regions backwards */
static ics_status light_regions(ics_plan *p, int l, ics_rect *fp, ics_rect *all, char *msg,
                                size_t msg_size) {
  const ics_slab_kernel *sk = &p->kernels[l];
  ics_tap2d *scratch = malloc(sizeof *scratch * (size_t)sk->entries * (size_t)sk->cap);
  ics_prop_taps pt = {0};
  double cum[2] = {0, 0};
  ics_status st = scratch ? ICS_OK : ICS_ERR_NOMEM;
  for (int k = 1; k < p->K && st == ICS_OK; k++) {
    if (k == 1) { /* slab 0 reads the initial buffer: its taps matter only to the schedule */
      double mag, q = ics_plan_slab_pixel(p, 0, &mag);
      st = ics_plan_slab_taps(p, l, 0, q, mag, cum, scratch, &pt, msg, msg_size);
      if (st != ICS_OK) break;
    }
    double mag, q = ics_plan_slab_pixel(p, k, &mag);
    st = ics_plan_slab_taps(p, l, k, q, mag, cum, scratch, &pt, msg, msg_size);
    fp[k] = (ics_rect){pt.lo[0], pt.lo[1], pt.hi[0], pt.hi[1]};
    if (k == 1) *all = fp[k];
    ics_rect_join(all, &fp[k]);
  }
  ics_prop_release(&pt);
  free(scratch);
  if (st != ICS_OK) return st;
  ics_rect view = {p->pad[0], p->pad[2], p->pad[0] + p->W, p->pad[2] + p->H};
  ics_rect *act = p->active;
  act[(size_t)(p->K - 1) * p->nlights + l] = view;
  for (int k = p->K - 2; k >= 0; k--)
    act[(size_t)k * p->nlights + l] = widen(p, &fp[k + 1], &act[(size_t)(k + 1) * p->nlights + l], &view);
  return ICS_OK;
}

/* per tile: the last slab at which a view pixel in it is still open, its colour still able to
 * change: the slab of its first fragment of an opaque surface (opacity 1 makes the pixel's alpha
 * exactly 1, checked over every float alpha below 1, and nothing after it changes the pixel),
 * else the last slab; -1 for tiles without view pixels. For the second buffer set (solids, 1),
 * which lights only the solid objects' surfaces: that slab where that first opaque surface is a
 * solid's, -1 elsewhere. */
static void open_until(const ics_plan *p, int solids, int32_t *open) {
  const ics_tile_grid *g = &p->tiles;
  for (int i = 0; i < g->nx * g->ny; i++) open[i] = -1;
  for (int bj = p->pad[2]; bj < p->pad[2] + p->H; bj++)
    for (int bi = p->pad[0]; bi < p->pad[0] + p->W; bi++) {
      size_t px = (size_t)bj * p->Wb + bi;
      int32_t until = solids ? -1 : p->K - 1;
      for (uint32_t f = p->ldi.offset[px]; f < p->ldi.offset[px + 1]; f++) {
        int obj = ics_frag_obj(&p->ldi.frag[f]), ib = p->inside_bit[obj];
        const ics_material *m = &p->scene->materials[p->scene->objects[obj].material];
        if (!m->volumetric && m->opacity == 1) {
          if (!solids || (ib >= 0 && (p->solid_bits >> ib & 1))) until = ics_frag_slab(&p->ldi.frag[f]);
          break;
        }
      }
      int32_t *o = &open[ics_tile_row(g, bj) * g->nx + ics_tile_col(g, bi)];
      if (until > *o) *o = until;
    }
}

/* The slabs a chain of reads takes from pixels [u0, u1] to reach pixels [t0, t1] along one axis,
 * each slab reading within p + [lo, hi] or staying (the regions only shrink); INT32_MAX when it
 * never does. */
static int32_t steps(int t0, int t1, int u0, int u1, int lo, int hi) {
  if (lo > 0) lo = 0;
  if (hi < 0) hi = 0;
  if (u0 > t1) return lo < 0 ? (u0 - t1 + (-lo) - 1) / -lo : INT32_MAX;
  if (u1 < t0) return hi > 0 ? (t0 - u1 + hi - 1) / hi : INT32_MAX;
  return 0;
}

/* light l's tile needs: the last slab at which tile T can still reach an open view pixel,
 * max over tiles U of open(U) - steps(T, U) (the larger of the two axes' steps), -1 when none */
static ics_status tile_needs(ics_plan *p, const ics_rect *off, const int32_t *open, int32_t *last) {
  const ics_tile_grid *g = &p->tiles;
  int nx = g->nx, ny = g->ny;
  int32_t *sx = malloc(sizeof *sx * (size_t)nx * nx), *sy = malloc(sizeof *sy * (size_t)ny * ny);
  if (!sx || !sy) {
    free(sx), free(sy);
    return ICS_ERR_NOMEM;
  }
  for (int t = 0; t < nx; t++)
    for (int u = 0; u < nx; u++)
      sx[t * nx + u] = steps(ics_tile_x0(g, t), ics_tile_x1(g, t) - 1, ics_tile_x0(g, u),
                             ics_tile_x1(g, u) - 1, off->x0, off->x1);
  for (int t = 0; t < ny; t++)
    for (int u = 0; u < ny; u++)
      sy[t * ny + u] = steps(ics_tile_y0(g, t), ics_tile_y1(g, t) - 1, ics_tile_y0(g, u),
                             ics_tile_y1(g, u) - 1, off->y0, off->y1);
  for (int ty = 0; ty < ny; ty++)
    for (int tx = 0; tx < nx; tx++) {
      int32_t best = -1;
      for (int uy = 0; uy < ny; uy++)
        for (int ux = 0; ux < nx; ux++) {
          int32_t o = open[uy * nx + ux], m = sx[tx * nx + ux];
          if (sy[ty * ny + uy] > m) m = sy[ty * ny + uy];
          if (o >= 0 && m != INT32_MAX && o - m > best) best = o - m;
        }
      last[ty * nx + tx] = best;
    }
  free(sx), free(sy);
  return ICS_OK;
}

/* the regions' pixels over every slab, within the needed tiles */
static double active_area(const ics_plan *p, int l) {
  const ics_tile_grid *g = &p->tiles;
  const int32_t *last = p->tile_last + (size_t)l * g->nx * g->ny;
  double area = 0;
  for (int ty = 0; ty < g->ny; ty++)
    for (int tx = 0; tx < g->nx; tx++)
      for (int k = 0; k <= last[ty * g->nx + tx] && k < p->K; k++) {
        const ics_rect *r = ics_active_region(p, l, k);
        int w = (r->x1 < ics_tile_x1(g, tx) ? r->x1 : ics_tile_x1(g, tx)) -
                (r->x0 > ics_tile_x0(g, tx) ? r->x0 : ics_tile_x0(g, tx));
        int h = (r->y1 < ics_tile_y1(g, ty) ? r->y1 : ics_tile_y1(g, ty)) -
                (r->y0 > ics_tile_y0(g, ty) ? r->y0 : ics_tile_y0(g, ty));
        if (w > 0 && h > 0) area += (double)w * h;
      }
  return area;
}

ics_status ics_active_regions_build(struct ics_plan *p, char *msg, size_t msg_size) {
  size_t n = (size_t)p->K * (size_t)p->nlights;
  ics_tile_grid_init(&p->tiles, p->Wb, p->Hb);
  size_t nt = (size_t)p->tiles.nx * p->tiles.ny;
  int sets = ics_plan_light_sets(p);
  free(p->active), free(p->tile_last), free(p->tile_shade);
  p->active = malloc(sizeof *p->active * (n ? n : 1));
  p->tile_last = malloc(sizeof *p->tile_last * nt * (size_t)(p->nlights ? p->nlights : 1) * sets);
  p->tile_shade = malloc(sizeof *p->tile_shade * nt);
  int32_t *open = malloc(sizeof *open * nt);
  ics_rect *fp = malloc(sizeof *fp * (size_t)(p->K ? p->K : 1));
  ics_status st = p->active && p->tile_last && p->tile_shade && open && fp ? ICS_OK : ICS_ERR_NOMEM;
  const ics_rect whole = {0, 0, p->Wb, p->Hb};
  int full = p->rs.dense || p->cam.projection == ICS_PROJ_PERSPECTIVE;
  /* the tile needs cost tiles^2 per light and distinct set (the first set's needs are the sharp
   * and moment sets' too): beyond ICS_REGION_MAX_PAIRS every tile is needed */
  int distinct = sets > 1 && ics_plan_set_role(p, 1) == ICS_SET_PATEL ? 2 : 1;
  int by_tiles = !full && (double)nt * nt * p->nlights * distinct <= ICS_REGION_MAX_PAIRS;
  /* the rectangles and each light's offsets over all slabs, then per set the tile needs */
  ics_rect all[ICS_SCENE_MAX_LIGHTS];
  for (int l = 0; l < p->nlights && st == ICS_OK; l++) {
    all[l] = (ics_rect){0, 0, 0, 0};
    if (full)
      for (int k = 0; k < p->K; k++) p->active[(size_t)k * p->nlights + l] = whole;
    else
      st = light_regions(p, l, fp, &all[l], msg, msg_size);
  }
  for (size_t i = 0; st == ICS_OK && i < nt; i++) p->tile_shade[i] = p->K - 1;
  for (int set = 0; set < sets && st == ICS_OK; set++) {
    ics_set_role role = ics_plan_set_role(p, set);
    if (role == ICS_SET_SHARP || role == ICS_SET_MOMENT) { /* the first set's needs */
      memcpy(p->tile_last + (size_t)set * p->nlights * nt, p->tile_last,
             sizeof *p->tile_last * nt * (size_t)p->nlights);
      continue;
    }
    if (by_tiles) open_until(p, role == ICS_SET_PATEL, open);
    for (int l = 0; l < p->nlights && st == ICS_OK; l++) {
      int32_t *last = p->tile_last + (size_t)(set * p->nlights + l) * nt;
      if (by_tiles) st = tile_needs(p, &all[l], open, last);
      for (size_t i = 0; st == ICS_OK && i < nt; i++) {
        if (!by_tiles) last[i] = p->K - 1;
        if (by_tiles && !set && !l) p->tile_shade[i] = open[i]; /* view pixels open */
        if (last[i] > p->tile_shade[i]) p->tile_shade[i] = last[i];
      }
    }
  }
  for (int l = 0; l < p->nlights && st == ICS_OK; l++)
    p->active_fraction[l] = p->K ? active_area(p, l) / (ics_rect_area(&whole) * p->K) : 1;
  free(open), free(fp);
  return st;
}
