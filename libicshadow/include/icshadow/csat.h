/* icshadow/csat.h — the light-aligned 3D summed-area table of Ament et al. 2014 (CSAT) for
 * directional lights: box-filtered optical depth and transmittance of an extinction volume
 * (volume.h) in constant time, in any precision mode of sat.h. Its brute-force reference is
 * ics_volume_tau_directional (volume.h). Objects are opaque: ics_csat_create (or
 * ics_csat_create_frame) makes one (*out NULL on failure), ics_csat_destroy frees it (NULL is
 * fine). */
#ifndef ICSHADOW_CSAT_H
#define ICSHADOW_CSAT_H

#include <stddef.h>

#include "icshadow/sat.h"
#include "icshadow/status.h"
#include "icshadow/volume.h"

#ifdef __cplusplus
extern "C" {
#endif

/* CSAT: a 3D SAT in a frame (r_u, r_v, r_w) with r_u x r_v = r_w = l, the unit vector toward
 * a directional light. The grid has cubic cells of edge h, is centred on the volume centre and
 * covers the volume's bounding box seen in that frame; each cell holds sigma_t(cell centre) *
 * h^3. The box-filtered optical depth at p for a square filter patch of half-width U facing
 * the light (Ament Eq. 12-13) is
 *   tau_bar(p) = CSAT(C) / A,  C = {p + u r_u + v r_v + w l : |u|, |v| <= U, w >= 0},
 *   A = (2U)^2,
 * evaluated with ics_sat3d_integral in constant time, independent of U. U = 0 is the
 * unfiltered limit and is evaluated as the integral over a patch of half-width h/2 (one cell
 * column) The cell edge h must not exceed the volume's extent along any frame
 * axis (the projected box size): larger cells would lie mostly outside the volume yet carry
 * sigma_t of their centre (h = 1e6 gave tau = 5e4 on a 16^3 volume of sigma 0.1) ->
 * ICS_ERR_RANGE. */
typedef struct ics_csat ics_csat;

/* Frame from l alone (r_u chosen deterministically, perpendicular to l). */
ICS_API ics_status ics_csat_create(ics_csat **out, const ics_volume *vol, const double light_dir[3],
                                   double h, ics_sat_precision mode);
/* Explicit orthonormal frame (checked to 1e-9; r_w = r_u x r_v is the primary light). */
ICS_API ics_status ics_csat_create_frame(ics_csat **out, const ics_volume *vol, const double r_u[3],
                                         const double r_v[3], double h, ics_sat_precision mode);
ICS_API void ics_csat_destroy(ics_csat *csat);
/* Frame vectors and grid size (cells along u, v, w). Any output pointer may be NULL. */
ICS_API void ics_csat_frame(const ics_csat *csat, double r_u[3], double r_v[3], double r_w[3],
                            size_t n[3]);

/* The six orthodirectional lights of one CSAT (Ament Eq. 14-15). */
typedef enum ics_csat_light {
  ICS_CSAT_PLUS_W = 0, /* l = +r_w: the primary light */
  ICS_CSAT_MINUS_W = 1,
  ICS_CSAT_PLUS_U = 2,
  ICS_CSAT_MINUS_U = 3,
  ICS_CSAT_PLUS_V = 4,
  ICS_CSAT_MINUS_V = 5
} ics_csat_light;
/* The world direction toward light `which` (unit vector). */
ICS_API ics_status ics_csat_light_dir(const ics_csat *csat, ics_csat_light which, double dir[3]);

/* Box-filtered optical depth tau_bar at world point p for light `which`, half-width U >= 0
 * (world units). NaN p or U -> ICS_ERR_NAN, U < 0 -> ICS_ERR_INVALID_ARG. */
ICS_API ics_status ics_csat_tau(const ics_csat *csat, ics_csat_light which, const double p[3],
                                double half_width, double *tau);
/* exp(-tau_bar): the filtered transmittance. */
ICS_API ics_status ics_csat_transmittance(const ics_csat *csat, ics_csat_light which,
                                          const double p[3], double half_width,
                                          double *transmittance);

#ifdef __cplusplus
}
#endif
#endif
