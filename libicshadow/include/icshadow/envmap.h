/* icshadow/envmap.h — latitude-longitude environment maps on the virtual light plane: the
 * plane point and solid angle of a pixel, the kept-pixel rule of the light fit's cut-off
 * (lightfit.h), the map projected onto the plane as a light density, and synthetic maps drawn
 * from Gaussian lights (light.h's ics_light).
 *
 * Frames (docs/architecture.md "Frames and file formats"): latitude-longitude map W x H,
 * pixel (i, j) centre u = (i + 1/2)/W, v = (j + 1/2)/H, theta = pi v from +y, phi = 2 pi u - pi,
 * direction (sin theta sin phi, cos theta, sin theta cos phi). Directions with dz > 0 (behind
 * the viewer) map to the plane point (x, y) = (dx/dz, dy/dz) = (tan wx, tan wy), and the light
 * function is the density l(x, y) = L(w) dw/dA, dw/dA = (1 + x^2 + y^2)^(-3/2), so
 * integral of l over the plane = integral of L over the hemisphere.
 *
 * Cut-off: a pixel whose centre is behind the viewer is kept when its centre is within
 * max_angle_deg of +z (plane radius <= tan max_angle) and dz at its worst corner is at least
 * half of dz at its centre (ics_envmap_pixel_kept). The second condition cuts rim pixels that
 * reach (nearly) 90 degrees, where the plane area and footprint are unbounded, whatever the
 * cut-off. */
#ifndef ICSHADOW_ENVMAP_H
#define ICSHADOW_ENVMAP_H

#include "icshadow/image.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Plane point and solid angle of pixel (i, j) of a W x H map: returns 0 (and *x, *y, *domega)
 * when the pixel centre is behind the viewer (dz > 0), -1 otherwise. */
ICS_API int ics_envmap_pixel(int width, int height, int i, int j, double *x, double *y,
                             double *domega);

/* 1 when the fit keeps pixel (i, j) of a W x H map with the cut-off max_angle_deg (in (0, 90)):
 * its centre is within the cut-off and dz at its worst corner >= half of dz at its centre;
 * 0 otherwise (also for bad arguments). */
ICS_API int ics_envmap_pixel_kept(int width, int height, int i, int j, double max_angle_deg);

/* The map projected onto the light plane at pixel (i, j) of env (3 or 4 channels; alpha
 * ignored): the plane point (x, y) of the pixel centre (as ics_envmap_pixel) and, per colour
 * channel, the light density l = L dw/dA = L (1 + x^2 + y^2)^(-3/2) of the pixel's radiance L
 * in rgb. Returns 0 when the centre is behind the viewer (dz > 0), -1 otherwise or for bad
 * arguments (then nothing is written). x or y may be NULL. */
ICS_API int ics_envmap_plane_density(const ics_image *env, int i, int j, double *x, double *y,
                                     double rgb[3]);

/* Synthetic environment map: env (an image made by ics_image_create, 3 or 4 channels) is
 * overwritten with sky_rgb (NULL: black) plus n Gaussian lights drawn with radiance weight color
 * g(x) (1 + |x|^2)^(3/2), averaged over supersample^2 points per pixel (1..16). Lights with a
 * covariance eigenvalue below (pixel size on the plane / 4)^2 are widened to it along that axis;
 * lights narrower than that in both axes are drawn as a delta into the one pixel holding their mean
 * (energy weight color). Alpha is set to 1. ICS_ERR_INVALID_ARG for bad lights (negative weight /
 * colour / non-PSD covariance, NaN). */
ICS_API ics_status ics_envmap_render(ics_image *env, const double sky_rgb[3],
                                     const ics_light *lights, int n, int supersample);

/* The same, calling progress(ctx, rows_done, rows) after each row of pixels (progress may be
 * NULL). */
ICS_API ics_status ics_envmap_render_progress(ics_image *env, const double sky_rgb[3],
                                              const ics_light *lights, int n, int supersample,
                                              void (*progress)(void *ctx, int rows_done, int rows),
                                              void *ctx);

#ifdef __cplusplus
}
#endif
#endif
