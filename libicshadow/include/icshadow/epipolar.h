/* icshadow/epipolar.h — epipolar rectification of a directional light's shadow map (Chen,
 * Baran, Durand, Jarosz 2011): the frame of the light and the eye, the slice and depth line of a
 * camera ray (the ics_minmax_ray of minmax.h), and the resampling of an orthographic shadow map
 * into rectified rows for the min-max trees. Errors as minmax.h. */
#ifndef ICSHADOW_EPIPOLAR_H
#define ICSHADOW_EPIPOLAR_H

#include <stddef.h>

#include "icshadow/minmax.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Light plane basis U, V (orthonormal, perpendicular to the unit direction L toward the light);
 * light-space coordinates of a world point p: u = p.U, v = p.V, depth = -(p.L). The epipole is
 * the eye's (u, v). Slice alpha is the half-plane through the eye spanned by L and the
 * direction w(alpha) = cos(alpha) U + sin(alpha) V; row r holds alpha_r = 2 pi (r + 1/2) / rows.
 * Sample gamma of a row is the light ray at radial distance gamma * dgamma from the eye's light
 * ray. A camera ray from the eye with direction v (not parallel to L) lies in slice
 * alpha = atan2(v.V, v.U), and its light depth at sample gamma is
 *     depth_eye - gamma * dgamma * (v.L) / |v - (v.L) L|,
 * a line in gamma: every camera ray lies in one row, as Chen's rectification requires. */
typedef struct ics_epipolar_frame {
  double eye[3];
  double L[3], U[3], V[3];
  double eu, ev, depth_eye; /* the eye in light space (epipole and its depth) */
  double dgamma;            /* world distance between samples along a row */
  size_t rows, d;
} ics_epipolar_frame;

/* Fills *out with the frame of the eye and the direction to_light toward the light (normalised
 * here; ICS_ERR_INVALID_ARG when it is zero) for rows x d samples dgamma > 0 apart (rows <=
 * ICS_MINMAX_MAX_ROWS, d <= ICS_MINMAX_MAX_SAMPLES, else ICS_ERR_SIZE). */
ICS_API ics_status ics_epipolar_frame_init(ics_epipolar_frame *out, const double eye[3],
                                           const double to_light[3], size_t rows, size_t d,
                                           double dgamma);
/* World point -> continuous (alpha in [0, 2 pi), gamma = radial distance / dgamma, depth). */
ICS_API ics_status ics_epipolar_locate(const ics_epipolar_frame *f, const double p[3],
                                       double *alpha, double *gamma, double *depth);
/* Camera ray direction -> its slice angle alpha, the nearest row, and its line h(gamma)
 * (gamma_end is left to the caller). ICS_ERR_RANGE if dir is (nearly) parallel to L. */
ICS_API ics_status ics_epipolar_ray(const ics_epipolar_frame *f, const double dir[3], double *alpha,
                                    size_t *row, ics_minmax_ray *ray);
/* The unit direction of the ray at angle beta from L in row r's slice. */
ICS_API ics_status ics_epipolar_ray_dir(const ics_epipolar_frame *f, size_t row, double beta,
                                        double dir[3]);

/* Resample an orthographic shadow map (w x h depths, texel (i, j) centred at light-plane point
 * (u0 + (i + 1/2) texel, v0 + (j + 1/2) texel), row-major by j) into rows x d rectified depths:
 * nearest texel; samples outside the map get +inf (no occluder). */
ICS_API ics_status ics_epipolar_rectify(const ics_epipolar_frame *f, const float *smap, size_t w,
                                        size_t h, double u0, double v0, double texel, float *out);

#ifdef __cplusplus
}
#endif
#endif
