/* icshadow/ssat.h — the spherical 3D summed-area table of Ament et al. 2014 (SSAT) for point
 * lights: box-filtered optical depth and transmittance of an extinction volume (volume.h) in
 * constant time, in any precision mode of sat.h. Its brute-force reference is ics_volume_tau_point
 * (volume.h). Objects are opaque: ics_ssat_create makes one (*out NULL on failure),
 * ics_ssat_destroy frees it (NULL is fine). */
#ifndef ICSHADOW_SSAT_H
#define ICSHADOW_SSAT_H

#include <stddef.h>

#include "icshadow/sat.h"
#include "icshadow/status.h"
#include "icshadow/volume.h"

#ifdef __cplusplus
extern "C" {
#endif

/* SSAT: a 3D SAT in spherical coordinates (phi, theta, r) around a point light at x_L, in a
 * frame (e_x, e_y, e_z) derived from the light and the volume alone: e_x points from x_L to the
 * volume centre, the polar axis e_z is the world axis least aligned with e_x (orthogonalised),
 * e_y = e_z x e_x; a light exactly at the volume centre keeps the world axes. Direction
 * (phi, theta) is sin(theta) (cos(phi) e_x + sin(phi) e_y) + cos(theta) e_z: the volume lies
 * around phi = 0, theta = pi/2, away from the poles and the phi seam, whenever the light is
 * outside it. phi in [-pi, pi), theta in [0, pi], r in [0, r_max] with r_max the largest
 * distance from x_L to a volume corner. Cell (i, j, k) holds sigma_t(cell centre) *
 * dphi (cos(theta_j) - cos(theta_j+1)) dr (exact cell solid angle times dr), so a box sum
 * divided by the box's solid angle is the SOLID-ANGLE AVERAGE of the optical depth of the
 * rays from x_L through the box (the ray average that Eq. 23-24 approximate by dividing a
 * volume sum by the patch area A; see docs/sat.md). Inside a theta cell the box edge is
 * placed in cos(theta) (the solid angle is linear in cos(theta), not in theta), so a lookup is
 * the exact solid-angle integral of the cell-wise constant resampled field, also at the poles.
 * Light farther than ICS_SSAT_MAX_DISTANCE volume diagonals from the farthest volume corner,
 * or at an infinite coordinate -> ICS_ERR_RANGE (ray positions would lose all precision);
 * NaN light -> ICS_ERR_NAN. */
#define ICS_SSAT_MAX_DISTANCE 4294967296.0 /* 2^32 volume diagonals */
typedef struct ics_ssat ics_ssat;
ICS_API ics_status ics_ssat_create(ics_ssat **out, const ics_volume *vol, const double light_pos[3],
                                   size_t n_phi, size_t n_theta, size_t n_r,
                                   ics_sat_precision mode);
ICS_API void ics_ssat_destroy(ics_ssat *ssat);
/* Frame axes and grid size (cells along phi, theta, r). Any output pointer may be NULL. */
ICS_API void ics_ssat_frame(const ics_ssat *ssat, double e_x[3], double e_y[3], double e_z[3],
                            size_t n[3]);
/* tau_bar at p for a square patch of half-width U at p facing the light: the angular box
 * phi_p +- min(atan(U/R) / sin(theta_p), pi), theta_p +- atan(U/R) clamped to [0, pi]
 * (R = |p - x_L|), r in [0, R]. When the phi half-width reaches pi (the patch covers a pole)
 * the box is the polar cap over the whole ring; otherwise phi wraps around at +-pi (two SAT
 * lookups). Constant time. Needs U > 0 (ICS_ERR_INVALID_ARG otherwise); p at the light (or
 * so far that |p - x_L| overflows) -> ICS_ERR_RANGE. */
ICS_API ics_status ics_ssat_tau(const ics_ssat *ssat, const double p[3], double half_width,
                                double *tau);
ICS_API ics_status ics_ssat_transmittance(const ics_ssat *ssat, const double p[3],
                                          double half_width, double *transmittance);

#ifdef __cplusplus
}
#endif
#endif
