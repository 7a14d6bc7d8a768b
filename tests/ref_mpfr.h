/* ref_mpfr.h — high-precision references for the tests, in MPFR (an algorithm independent
 * of the library's: the arithmetic-geometric mean at REF_PREC bits).
 * Parameter convention: m1 = 1 - m is the complementary PARAMETER (m = k^2). */
#ifndef ICS_REF_MPFR_H
#define ICS_REF_MPFR_H

#include <mpfr.h>

#define REF_PREC 320

/* K(m) and E(m) for m = 1 - m1, m1 > 0 given exactly as an mpfr number (any m1 > 0, so
 * m1 > 1 covers negative m). Either output may be NULL. Outputs must be initialised. */
void ref_ellipke_m1(mpfr_ptr K, mpfr_ptr E, mpfr_srcptr m1);

/* Error of x against the reference in units in the last place of the double nearest to ref
 * (ulp = 2^(e-53) for |ref| in [2^(e-1), 2^e), at least 2^-1074). Infinite/NaN handling:
 * equal infinities or both NaN give 0; anything else involving them gives +inf. */
double ref_ulp_error(double x, mpfr_srcptr ref);

#endif
