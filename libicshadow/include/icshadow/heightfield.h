/* icshadow/heightfield.h — a synthetic height-field scene on the light's ground plane (boxes and
 * spherical caps standing on y = 0): its ray hits and the orthographic shadow map of a
 * directional light in an epipolar frame (epipolar.h), the test and benchmark scene of the 1D
 * min-max mipmaps (minmax.h). Errors as minmax.h. */
#ifndef ICSHADOW_HEIGHTFIELD_H
#define ICSHADOW_HEIGHTFIELD_H

#include <stddef.h>

#include "icshadow/epipolar.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The plane y = 0 (infinite) with axis-aligned boxes standing on it and spherical caps
 * (spheres centred at y = cy <= 0, the part above the plane). y is up. */
#define ICS_HEIGHTFIELD_MAX_SHAPES 16
typedef struct ics_heightfield {
  size_t nboxes, ncaps;
  double box[ICS_HEIGHTFIELD_MAX_SHAPES][4]; /* x0, x1, z0, z1; height in box_h */
  double box_h[ICS_HEIGHTFIELD_MAX_SHAPES];
  double cap[ICS_HEIGHTFIELD_MAX_SHAPES][4]; /* cx, cy, cz, radius */
} ics_heightfield;

/* Fills *out with the default scene: 6 boxes and 4 caps over [-6, 6]^2, heights <= 2.5 (a NULL
 * out does nothing). */
ICS_API void ics_heightfield_init_default(ics_heightfield *out);
/* Nearest hit t > tmin of the ray o + t dir with the scene (+inf if none; NaN for a NULL
 * pointer). */
ICS_API double ics_heightfield_hit(const ics_heightfield *s, const double o[3], const double dir[3],
                                   double tmin);
/* Render the orthographic shadow map of the frame's light: w x w texels covering the square of
 * half-size half centred at the epipole (u0 = eu - half, texel = 2 half / w); each texel holds
 * the light depth of the first hit of its light ray (+inf if none). */
ICS_API ics_status ics_heightfield_shadow_map(const ics_heightfield *s, const ics_epipolar_frame *f,
                                              size_t w, double half, float *smap);

#ifdef __cplusplus
}
#endif
#endif
