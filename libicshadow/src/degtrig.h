/* degtrig.h — sine and cosine of an angle in degrees (private to libicshadow). The one
 * implementation behind ics_light_cov_from_eig (light.c, hence ics_class2d_init_axes and the
 * CLI's lights files) and the ellipse kernel's rotation (ellipse.c, where it is defined).
 *
 * Method: r = fmod(deg, 360) (exact), q = nearest multiple of 90 to r, rem = r - 90 q (exact,
 * |rem| <= 45); sin and cos of rem * pi/180 are swapped and negated by the quadrant. Exact at
 * multiples of 90 degrees, and ~1 ulp relative near them, where sin(deg * pi/180) would keep
 * only an absolute error of ~1 ulp of pi (sin of 179.999 degrees: 1.2e-11 relative error, here
 * 1e-17). */
#ifndef ICS_DEGTRIG_H
#define ICS_DEGTRIG_H

void ics_sincos_deg(double deg, double *s, double *c);

#endif
