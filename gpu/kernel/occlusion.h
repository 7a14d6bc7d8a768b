/* occlusion.h — a surface fragment's occlusion of a light (docs/renderer.md "Surface bias"): a
 * parcel of the light meets the surface within a window of win slabs after its first in
 * (win + 1) / |1 - rho| slabs (rho the surface's depth change under the parcel per slab),
 * clamped to [1, 8 (win + 1)]; no window, one slab. Each of those slabs passes that root of the
 * surface's pass 1 - opacity (1 - transport), so the parcel is filtered once in all. Shared
 * kernel source (lang.h): the cpu backend, slab.cl and slab.comp compile this one text. */
#ifndef ICS_KERNEL_OCCLUSION_H
#define ICS_KERNEL_OCCLUSION_H
#include "kernel/lang.h"

/* the slabs a parcel meets the surface in; rel = |1 - rho| */
ICS_FN double ics_k_meets(double win, double rel) {
  if (!(win > 0)) return 1.0;
  return rel > 0 ? ICS_FMIN(ICS_FMAX((win + 1) / rel, 1.0), 8 * (win + 1)) : 8 * (win + 1);
}

/* the factor one of those slabs applies, for opacity a and the channel's transport */
ICS_FN float ics_k_slab_pass(double a, double transport, double meets) {
  double pass = 1 - a * (1 - transport);
  return ICS_TO_FLOAT(meets > 1 ? ICS_POW(pass, 1 / meets) : pass);
}

#endif
