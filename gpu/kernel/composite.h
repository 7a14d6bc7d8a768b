/* composite.h — the shading arithmetic every backend applies to what a slab holds
 * (docs/renderer.md "Shading and compositing"): a piece of opacity alpha and colour rgb lit by L,
 * composited front to back under the pixel's RGBA C; a volume piece's opacity along the camera
 * ray; and its pass for a light, per channel. Shared kernel source (lang.h): the cpu backend,
 * slab.cl and slab.comp compile this one text. */
#ifndef ICS_KERNEL_COMPOSITE_H
#define ICS_KERNEL_COMPOSITE_H
#include "kernel/lang.h"

/* C += (1 - C.a) alpha (rgb L, 1) */
ICS_FN void ics_k_composite(double alpha, ICS_CONST_IN double rgb[3], ICS_CONST_IN double L[3],
                            ICS_INOUT float C[4]) {
  double wgt = (1 - C[3]) * alpha;
  for (int c = 0; c < 3; c++) C[c] += ICS_TO_FLOAT(wgt * rgb[c] * L[c]);
  C[3] += ICS_TO_FLOAT(wgt);
}

/* the opacity of a piece of extinction ext and depth extent dz, dl camera path per unit depth */
ICS_FN double ics_k_piece_alpha(double ext, double dz, double dl) {
  return 1 - ICS_EXP(-ext * dz * dl);
}

/* the fraction of a light passing a volume of extinction ext and transport colour component
 * transport over dz, lpath light path per unit depth */
ICS_FN double ics_k_piece_pass(double ext, double dz, double lpath, double transport) {
  return ICS_EXP(-ext * dz * lpath * (1 - transport));
}

#endif
