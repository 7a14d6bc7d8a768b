/* ssat_frame.h — the geometry of a point light over a volume that the SSAT (ssat.c) and its
 * brute-force reference ics_volume_tau_point (volume.c) share, so that both see the same
 * frame, the same light limit and the same angular box (private to libicshadow; defined in
 * ssat_frame.c). */
#ifndef ICS_SSAT_FRAME_H
#define ICS_SSAT_FRAME_H

#include "icshadow/ssat.h"

/* Spherical frame around the light: e[0] (phi = 0, theta = pi/2) points from the light to the
 * volume centre, the polar axis e[2] is the world axis least aligned with it, orthogonalised,
 * and e[1] = e[2] x e[0] (so e[0] x e[1] = e[2]). The volume then sits around the equator,
 * away from both poles and from the phi seam at +-pi, whenever the light is outside it (the
 * angular box of a patch degenerates near a pole). A light at the volume centre keeps the
 * world axes. */
void ics_ssat_make_frame(const ics_volume *vol, const double light[3], double e[3][3]);

/* Largest distance from the light to a volume corner; ICS_ERR_RANGE when the light is more
 * than ICS_SSAT_MAX_DISTANCE volume diagonals from the farthest corner (or that distance is
 * not finite). */
ics_status ics_ssat_max_radius(const ics_volume *vol, const double light[3], double *rmax);

/* The angular box of a patch of half-width U at p in the frame e: phi in [p0, p1] (may leave
 * [-pi, pi]; p1 - p0 <= 2 pi), theta in [t0, t1], and R = |p - light|. The phi half-width
 * atan(U/R) / sin(theta) is clamped to pi: a patch over a pole (theta < atan(U/R)) becomes the
 * polar cap theta in [0, t1] over the whole ring (the same for the south pole). Returns
 * ICS_ERR_RANGE when p is at the light or |p - light| overflows. */
ics_status ics_ssat_patch_box(const double light[3], const double e[3][3], const double p[3],
                              double U, double *ph0, double *ph1, double *th0, double *th1,
                              double *R);

#endif
