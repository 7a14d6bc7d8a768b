/* sym2.h — eigen-decomposition and square root of a symmetric 2x2 matrix [[a, b], [b, d]]
 * (private to libicshadow; defined in sym2.c). The one implementation behind
 * ics_light_cov_to_eig (light.c), the kernel classes (class.c: ics_class2d_check,
 * ics_class2d_to_axes), the members' taps (kernel.c: the matrix square root and the whitening
 * of the Poisson pattern), the 2D compensation (taps.c), the light fit's covariance floor
 * (lightfit.c) and the synthetic maps' light check (envmap.c).
 *
 * Method: m = (a + d)/2, h = (a - d)/2, r = hypot(h, b); l1 = m + r (no cancellation for a PSD
 * matrix), l2 = det / l1 = (a d - b^2) / l1 when l1 > 0 (else m - r), so the small eigenvalue
 * keeps its relative accuracy for huge ratios l1/l2 where m - r cancels to 0; the angle of l1's
 * eigenvector is atan2(b, h)/2 in degrees, in (-90, 90], and exactly 0 when r = 0 (isotropic).
 * The square root is (M + s I) / t, s = sqrt(l1) sqrt(l2), t = sqrt(l1) + sqrt(l2) (Cayley-
 * Hamilton: its square is M), from these eigenvalues.
 * No input checks: callers validate and apply their own tolerance. */
#ifndef ICS_SYM2_H
#define ICS_SYM2_H

/* Eigenvalues l1 >= l2 of [[a, b], [b, d]] and (alpha_deg may be NULL) the direction of the
 * eigenvector of l1, degrees counter-clockwise from +x. No clamping. */
void ics_sym2_eig(double a, double b, double d, double *l1, double *l2, double *alpha_deg);

/* The symmetric positive-semidefinite square root {r_a, r_b, r_d} of [[a, b], [b, d]], with
 * eigenvalues below 0 (the rounding of a PSD matrix) taken as 0; all zero for the zero matrix.
 * Returns 1 when the matrix is PSD (l2 >= 0 as computed by ics_sym2_eig), 0 when an eigenvalue
 * was negative (the root is then that of the matrix with it raised to 0: a caller that needs
 * PSD input stops there). */
int ics_sym2_sqrt(double a, double b, double d, double out[3]);

#endif
