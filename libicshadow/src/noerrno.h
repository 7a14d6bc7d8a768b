/* noerrno.h — libm calls that leave errno as it was (private to libicshadow), for the math
 * functions of the library, which never touch errno: glibc's erfc and exp set errno = ERANGE
 * when the result underflows or overflows (erfc(x) for x >~ 26.5, i.e. Phi(z) for z < -37.5;
 * exp in a Gaussian pdf's tails and in Phi^-1's Halley step for subnormal p). These save and
 * restore it; the results are libm's, unchanged. Used by normal.c and light.c. */
#ifndef ICS_NOERRNO_H
#define ICS_NOERRNO_H

#include <errno.h>
#include <math.h>

static inline double ics_erfc_noerrno(double x) {
  int saved = errno;
  double r = erfc(x);
  errno = saved;
  return r;
}

static inline double ics_exp_noerrno(double x) {
  int saved = errno;
  double r = exp(x);
  errno = saved;
  return r;
}

#endif
