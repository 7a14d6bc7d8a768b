/* envmap_pixel.h — the pixel geometry of latitude-longitude maps that envmap.c and the light fit
 * (lightfit.c) share (private to libicshadow; defined in envmap.c). */
#ifndef ICS_ENVMAP_PIXEL_H
#define ICS_ENVMAP_PIXEL_H

/* Covariance {sxx, sxy, syy} of the footprint of pixel (i, j) of a w x h map on the light plane:
 * J diag(dphi^2, dtheta^2) / 12 J^T, J = d(x, y) / d(phi, theta) at the pixel centre. */
void ics_envmap_footprint(int w, int h, int i, int j, double s[3]);

/* The kept-pixel rule (ics_envmap_pixel_kept) for a pixel whose centre has dz = dzc, with
 * cosmax = cos(max_angle): the centre within the cut-off and dz at the worst corner >= dzc / 2. */
int ics_envmap_kept_at(int w, int h, int i, int j, double dzc, double cosmax);

#endif
