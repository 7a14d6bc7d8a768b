/* sym2.h — eigen-decomposition of a symmetric 2x2 matrix (private to libicshadow). The one
 * implementation behind ics_cov_to_eig (light.c) and the kernel classes (kernel.c:
 * ics_class2d_check, ics_class2d_to_axes, the taps' matrix square root).
 *
 * Method: m = (a + d)/2, h = (a - d)/2, r = hypot(h, b); l1 = m + r (no cancellation for a PSD
 * matrix), l2 = det / l1 = (a d - b^2) / l1 when l1 > 0 (else m - r), so the small eigenvalue
 * keeps its relative accuracy for huge ratios l1/l2 where m - r cancels to 0; the angle of l1's
 * eigenvector is atan2(b, h)/2 in degrees, in (-90, 90], and exactly 0 when r = 0 (isotropic).
 * No input checks and no clamping: callers validate and apply their own tolerance. */
#ifndef ICS_SYM2_H
#define ICS_SYM2_H

/* Eigenvalues l1 >= l2 of [[a, b], [b, d]] and (alpha_deg may be NULL) the direction of the
 * eigenvector of l1, degrees counter-clockwise from +x. */
void ics_sym2_eig(double a, double b, double d, double *l1, double *l2, double *alpha_deg);

#endif
