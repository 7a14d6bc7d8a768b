/* detail.h — volumetric detail functions (Patel Sec. 4.2 step 3): improved Perlin noise (Perlin
 * 2002), fBm, ridged multifractal (Musgrave), a 3D grid; and the transfer function from a
 * detail value to colour and extinction scale. */
#ifndef ICS_RENDER_DETAIL_H
#define ICS_RENDER_DETAIL_H

#include <stdint.h>

#include "icshadow/scene.h"

/* A detail function ready to evaluate: the seeded permutation and the grid's placement. */
typedef struct ics_detail_eval {
  const ics_detail *d;
  uint8_t perm[512];
  double lo[3], hi[3]; /* grid: the object's bounding box */
} ics_detail_eval;

/* Prepares `d` for the object bounds lo, hi (used by grids only). */
void ics_detail_prepare(ics_detail_eval *e, const ics_detail *d, const double lo[3],
                        const double hi[3]);
/* The detail value v = bias + scale f(frequency p + time drift) at world point p. */
double ics_detail_value(const ics_detail_eval *e, const double p[3]);
/* Improved noise in [-1, 1] with permutation perm (exposed for tests). */
double ics_perlin_noise(const uint8_t perm[512], double x, double y, double z);

/* Colour and extinction scale of a material at detail value v: the transfer function's
 * piecewise-linear interpolation (clamped at its ends), or (color, max(v, 0)) without one. */
void ics_material_transfer(const ics_material *m, double v, double rgb[3], double *scale);

/* Preintegration (Engel, Kraus, Ertl 2001): with the detail value varying linearly from vf to vb
 * along a piece, the mean extinction scale over the piece, (1 / (vb - vf)) int s(v) dv, and the
 * extinction-weighted mean colour, int c(v) s(v) dv / int s(v) dv, from exact integrals of the
 * piecewise-linear transfer function (vf = vb: ics_material_transfer). */
void ics_material_preintegrate(const ics_material *m, double vf, double vb, double rgb[3],
                               double *scale);

/* A bound of |f| for the detail function d's noise part (v = bias + scale f): rigorous for
 * improved noise (|noise| <= 2: the gradients' dot products with offsets in [-1, 1]^3 are at most
 * 2 and the interpolation is convex), fBm, ridged multifractal and grids (read: d->grid set). */
double ics_detail_bound(const ics_detail *d);
/* A bound of material m's extinction over every detail value its detail can take (0 for a
 * surface): the Monte-Carlo reference's majorant, and the scene reader's overflow check. */
double ics_material_majorant(const ics_material *m);

#endif
