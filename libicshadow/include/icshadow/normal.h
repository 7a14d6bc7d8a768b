/* icshadow/normal.h — the normal distribution: the standard normal cdf, its survival function
 * and quantile, and the bivariate standard normal cdf (the limits against which the CLT
 * measurements of shadow1d.h and clt2d.h compare, and the Gaussian 1D lights of light.h).
 * Methods and accuracy in libicshadow/src/normal.c. */
#ifndef ICSHADOW_NORMAL_H
#define ICSHADOW_NORMAL_H

#include "icshadow/api.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Phi(z) = P(Z < z), Z standard normal (relative error ~1e-15 in both tails); NaN for NaN.
 * These three never touch errno. */
ICS_API double ics_normal_cdf(double z);
/* 1 - Phi(z) = Phi(-z), computed without cancellation; NaN for NaN. */
ICS_API double ics_normal_sf(double z);
/* Phi^-1(p) (relative error ~1e-15 over (0, 1), subnormal p included; -inf / inf at 0 / 1, NaN
 * outside [0, 1]). */
ICS_API double ics_normal_quantile(double p);

/* Bivariate standard normal cdf P(X < a, Y < b), corr(X, Y) = r in [-1, 1] (Plackett's
 * identity integrated by Gauss-Legendre in asin r). NaN outside. */
ICS_API double ics_normal_bvn_cdf(double a, double b, double r);

#ifdef __cplusplus
}
#endif
#endif
