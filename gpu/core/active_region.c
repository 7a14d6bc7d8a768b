/* active_region.c — the light buffers' active regions (see active_region.h): a backward pass
 * over the slabs from the view, each step the footprint of the next slab's taps. */
#include "active_region.h"

#include <stdlib.h>

#include "plan_internal.h"

const ics_rect *ics_active_region(const struct ics_plan *p, int l, int k) {
  return &p->active[(size_t)k * (size_t)p->nlights + (size_t)l];
}

static int clampi(int v, int lo, int hi) { return v < lo ? lo : v > hi ? hi : v; }

/* the pixels that slab k + 1, whose reads lie within p + [off.x0, off.x1] x [off.y0, off.y1],
 * reads to make `next`, joined with the view, within the buffer (orthographic: s = 1) */
static ics_rect widen(const ics_plan *p, const ics_rect *off, const ics_rect *next,
                      const ics_rect *view) {
  int x0 = next->x0 + off->x0, x1 = next->x1 - 1 + off->x1;
  int y0 = next->y0 + off->y0, y1 = next->y1 - 1 + off->y1;
  ics_rect r = {clampi(x0, 0, p->Wb - 1), clampi(y0, 0, p->Hb - 1), clampi(x1, 0, p->Wb - 1) + 1,
                clampi(y1, 0, p->Hb - 1) + 1};
  if (view->x0 < r.x0) r.x0 = view->x0;
  if (view->y0 < r.y0) r.y0 = view->y0;
  if (view->x1 > r.x1) r.x1 = view->x1;
  if (view->y1 > r.y1) r.y1 = view->y1;
  return r;
}

/* light l's read offsets of every slab (forwards, as the backend prepares them: the integer
 * schedule carries its state), then the regions backwards */
static ics_status light_regions(ics_plan *p, int l, ics_rect *fp, char *msg, size_t msg_size) {
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

ics_status ics_active_regions_build(struct ics_plan *p, char *msg, size_t msg_size) {
  size_t n = (size_t)p->K * (size_t)p->nlights;
  free(p->active);
  p->active = malloc(sizeof *p->active * (n ? n : 1));
  if (!p->active) return ICS_ERR_NOMEM;
  ics_rect whole = {0, 0, p->Wb, p->Hb};
  int full = p->rs.dense || p->cam.projection == ICS_PROJ_PERSPECTIVE;
  ics_rect *fp = full ? NULL : malloc(sizeof *fp * (size_t)(p->K ? p->K : 1));
  if (!full && !fp) return ICS_ERR_NOMEM;
  for (int l = 0; l < p->nlights; l++) {
    if (full) {
      for (int k = 0; k < p->K; k++) p->active[(size_t)k * p->nlights + l] = whole;
    } else {
      ics_status st = light_regions(p, l, fp, msg, msg_size);
      if (st != ICS_OK) {
        free(fp);
        return st;
      }
    }
    double area = 0;
    for (int k = 0; k < p->K; k++) area += ics_rect_area(ics_active_region(p, l, k));
    p->active_fraction[l] = p->K ? area / (ics_rect_area(&whole) * p->K) : 1;
  }
  free(fp);
  return ICS_OK;
}
