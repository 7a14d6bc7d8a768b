/* active_region.h — the part of each light buffer that slab k must propagate (docs/renderer.md
 * "Work a frame does not need"): the pixels whose value can still reach a visible pixel whose
 * colour can still change. Two bounds, both exact (from the taps' own read offsets, not an
 * estimate), a pixel being needed when it is within both:
 * - a rectangle per light and slab: the view's pixels are needed at every slab, and a pixel is
 *   needed at slab k when a needed pixel of slab k + 1 reads it; so, backwards from the last
 *   slab, the region of slab k is the view joined with the region of slab k + 1 and its
 *   footprint (ics_prop_footprint) under slab k + 1's taps;
 * - the last slab at which each tile (tile_grid.h) is needed per light: a view pixel is open
 *   (its colour can still change) up to its first opaque surface, and a tile is needed as long
 *   as a chain of reads, each within the light's read offsets, can still carry its light to an
 *   open pixel in time.
 * Outside them a backend may leave the buffer as it is: no needed pixel ever reads it. */
#ifndef ICS_RENDER_ACTIVE_REGION_H
#define ICS_RENDER_ACTIVE_REGION_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/status.h"

struct ics_plan;

/* A pixel rectangle of the light buffer: columns [x0, x1), rows [y0, y1). */
typedef struct ics_rect {
  int32_t x0, y0, x1, y1;
} ics_rect;

static inline double ics_rect_area(const ics_rect *r) {
  return (double)(r->x1 - r->x0) * (double)(r->y1 - r->y0);
}
/* *r grown to hold o too (their bounding rectangle) */
static inline void ics_rect_join(ics_rect *r, const ics_rect *o) {
  if (o->x0 < r->x0) r->x0 = o->x0;
  if (o->y0 < r->y0) r->y0 = o->y0;
  if (o->x1 > r->x1) r->x1 = o->x1;
  if (o->y1 > r->y1) r->y1 = o->y1;
}

/* Fills p->tiles, p->active (K x nlights rectangles, slab-major), p->tile_last (light sets x
 * nlights x tiles, ics_plan_light_sets: the last slab at which light l's buffer of that set
 * needs tile T; -1: never; the second set's from the view pixels whose first opaque surface is a
 * solid object's, the only ones it lights), p->tile_shade (per tile: the last slab
 * at which some light or an open view pixel needs it: shading) and p->active_fraction (per
 * light: the needed pixels over K buffers). Orthographic cameras: the bounds above, from every
 * slab's taps (ics_plan_slab_taps); perspective cameras and render.dense: the whole buffer at
 * every slab (a perspective slab's taps cost 256 compensations, too many to prepare twice).
 * Buffers of more than ICS_REGION_MAX_PAIRS tile pairs (over the lights) need every tile at every
 * slab. ICS_OK, or the taps' error with msg, or ICS_ERR_NOMEM. */
#define ICS_REGION_MAX_PAIRS 2e8
ics_status ics_active_regions_build(struct ics_plan *p, char *msg, size_t msg_size);

/* The region of light l at slab k. */
const ics_rect *ics_active_region(const struct ics_plan *p, int l, int k);

#endif
