/* icshadow/volume.h — extinction volumes: the volume view, its trilinear sampling, and the
 * brute-force shadow-ray marching of box-filtered optical depth, the references of the CSAT
 * (csat.h) and the SSAT (ssat.h) and of renderers built on them (Ament et al. 2014).
 * Errors: NULL pointers or an empty volume -> ICS_ERR_INVALID_ARG, NaN inputs -> ICS_ERR_NAN,
 * as listed per function. */
#ifndef ICSHADOW_VOLUME_H
#define ICSHADOW_VOLUME_H

#include <stddef.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An extinction volume sigma_t: nx x ny x nz floats (x fastest), unit voxels, world
 * coordinates in voxel units: voxel (i, j, k) covers [i, i+1) x [j, j+1) x [k, k+1) and its
 * value sits at the centre (i + 1/2, j + 1/2, k + 1/2). sigma_t(p) is the trilinear
 * interpolation (clamp-to-edge indices) inside the box [0, nx] x [0, ny] x [0, nz] and 0
 * outside. The view does not own the data. */
typedef struct ics_volume {
  const float *data;
  size_t nx, ny, nz;
} ics_volume;

/* sigma_t at a world point (0 outside the volume box). */
ICS_API double ics_volume_sample(const ics_volume *vol, const double p[3]);

/* Directional light (the reference of ics_csat_tau): the optical depth toward `dir` averaged
 * over a square patch of half-width U = half_width at p spanned by r_u, r_v, by brute-force
 * shadow-ray marching through the original volume (trilinear sigma_t): an n_patch x n_patch
 * grid of rays on the patch (midpoint rule), each marched toward `dir` with step `step`
 * (midpoint rule) until it leaves the volume box. U = 0 marches the single ray through p.
 * U < 0, step <= 0 or n_patch < 1 -> ICS_ERR_INVALID_ARG. */
ICS_API ics_status ics_volume_tau_directional(const ics_volume *vol, const double r_u[3],
                                              const double r_v[3], const double dir[3],
                                              const double p[3], double half_width, int n_patch,
                                              double step, double *tau);

/* Point light at light_pos (the reference of ics_ssat_tau): n_patch x n_patch rays over the
 * SSAT's angular box of the patch of half-width U > 0 at p, in the SSAT's frame (derived from
 * vol and light_pos as in ics_ssat_create; midpoint in phi and in cos(theta), i.e. uniform in
 * solid angle), each marched from the light to radius R = |p - light_pos| with step `step`,
 * averaged. The same light limit as ics_ssat_create (ICS_ERR_RANGE); p at the light ->
 * ICS_ERR_RANGE; U <= 0, step <= 0 or n_patch < 1 -> ICS_ERR_INVALID_ARG. */
ICS_API ics_status ics_volume_tau_point(const ics_volume *vol, const double light_pos[3],
                                        const double p[3], double half_width, int n_patch,
                                        double step, double *tau);

#ifdef __cplusplus
}
#endif
#endif
