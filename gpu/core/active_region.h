/* active_region.h — the part of each light buffer that slab k must propagate (docs/renderer.md
 * "Work a frame does not need"): the pixels whose value can still reach a visible pixel. The
 * view's pixels are needed at every slab (they are shaded), and a pixel is needed at slab k when
 * a needed pixel of slab k + 1 reads it; so, backwards from the last slab, the region of slab k
 * is the view joined with the footprint (ics_prop_footprint) of slab k + 1's region under slab
 * k + 1's taps: exact, the taps' own read offsets, not an estimate. Outside it a backend may
 * leave the buffer as it is: no needed pixel ever reads it. */
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

/* Fills p->active (K x nlights rectangles, slab-major) and p->active_fraction (per light: the
 * regions' area over K buffers). Orthographic cameras: the regions above, from every slab's taps
 * (ics_plan_slab_taps); perspective cameras and render.dense: the whole buffer at every slab (a
 * perspective slab's taps cost 256 compensations, too many to prepare twice). ICS_OK, or the
 * taps' error with msg, or ICS_ERR_NOMEM. */
ics_status ics_active_regions_build(struct ics_plan *p, char *msg, size_t msg_size);

/* The region of light l at slab k. */
const ics_rect *ics_active_region(const struct ics_plan *p, int l, int k);

#endif
