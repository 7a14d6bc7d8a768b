/* icshadow/kernel.h — kernel equivalence classes (Patel et al. 2013, Sec. 3.3-3.4, Table I).
 *
 * A class is a mean and a (co)variance; by the CLT (Lyapunov condition) every member of a class,
 * and every per-iteration mix of members of one class, converges to the same Gaussian after n
 * iterations: mean n mu, variance n sigma^2. A member is given as TAPS (position, weight) in
 * pixels; the engine (icshadow/conv.h) applies out(x) = sum_j w_j in(x - x_j), so a kernel of
 * mean mu shifts the buffer content by +mu.
 *
 * Members (sigma^2 = class variance; "exact" = the taps' moments equal the class to rounding):
 *   DIRAC        1D  taps mu - sigma, mu + sigma, weights 1/2. Exact. 2 taps (1 if sigma = 0).
 *   TOPHAT       1D  the continuous box of width W centred on mu, on the pixel grid: integer
 *                    taps j with weights w_j = integral box(t) hat(t - j) dt (the box applied
 *                    to the linearly interpolated line; no further interpolation). Discrete
 *                    variance W^2/12 + E_box[f(1 - f)], f = frac(t). param = 0 (default): W is
 *                    solved so this equals sigma^2 exactly (needs sigma^2 >= f_mu (1 - f_mu),
 *                    f_mu = frac(mu), else ICS_ERR_RANGE); param = 1: the raw box
 *                    W = sqrt(12) sigma, variance sigma^2 + E_box[f(1 - f)] (NOT in the class;
 *                    for comparison). At most ceil(W) + 3 taps. A box narrower than 1e-6 px
 *                    is applied as its W -> 0 limit (linear weights at floor/ceil of mu;
 *                    variance off by < 1e-13 px^2), e.g. for sigma^2 = 1e-300.
 *   STOCH_DIRAC  1D  per iteration i, u ~ U(-h, h) from (seed, i): taps mu - (rho + u),
 *                    mu + (rho + u), weights 1/2, rho = sqrt(sigma^2 - h^2/3) with
 *                    h = min(param, sqrt(3) sigma) (param = jitter half-width, default 1 px:
 *                    Table I's width 2 sigma +- 2). Mean exactly mu every iteration; variance
 *                    (rho + u)^2, expectation exactly sigma^2. 2 taps (1 if sigma = 0).
 *   GAUSS        1D  nsamples (default 9) taps at mu + s z_k, z_k = -T + 2 T k / (N - 1),
 *                    T = param (default 3), weights exp(-z^2/2) normalised, s chosen so the
 *                    variance is exactly sigma^2. N = 1 only for sigma = 0.
 *                2D  an N x N grid (N = nsamples, default 5, at most 256) of those 1D taps in
 *                    the whitened frame, mapped by Sigma^(1/2): exact mean and covariance.
 *   ELLIPSE      2D  ics_ellipse_kernel(varx, vary, alpha, N, offset) with offset ~ U[0, 1)
 *                    from (seed, i), plus mu; weights 1/N (N = nsamples, default 2). Covariance
 *                    exact in expectation over the offset; the mean is exactly mu for even N
 *                    (antipodal pairs), in expectation for odd N. N taps.
 *   POISSON      2D  N (default 8, 3..64) points by dart throwing in the unit disk (seeded by
 *                    `seed`, fixed for the kernel), centred and WHITENED (second-moment matrix
 *                    made I), mapped by Sigma^(1/2), rotated per iteration by theta ~ U[0, 2 pi)
 *                    from (seed, i) in the whitened frame. Because the whitened pattern is
 *                    isotropic, mean and covariance are exact for EVERY rotation (so also in
 *                    expectation). N taps.
 * Stochastic members draw iteration i's numbers from stream i of ics_rng (key = seed): the taps
 * of iteration i depend on (seed, i) only. */
#ifndef ICSHADOW_KERNEL_H
#define ICSHADOW_KERNEL_H

#include <stdint.h>

#include "icshadow/class.h"
#include "icshadow/status.h"
#include "icshadow/taps.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_KERNEL_MAX_TAPS 65536 /* any member's tap count is at most this */

typedef enum ics_kernel_member {
  ICS_KERNEL_DIRAC = 0,
  ICS_KERNEL_TOPHAT,
  ICS_KERNEL_STOCH_DIRAC,
  ICS_KERNEL_GAUSS,
  ICS_KERNEL_ELLIPSE,
  ICS_KERNEL_POISSON,
  ICS_KERNEL_MEMBER_COUNT_
} ics_kernel_member;

/* "dirac", "tophat", "stochastic-dirac", "gauss", "ellipse", "poisson"; NULL when out of range. */
ICS_API const char *ics_kernel_member_name(ics_kernel_member m);
/* 1 for members with per-iteration random taps (STOCH_DIRAC, ELLIPSE, POISSON), else 0. */
ICS_API int ics_kernel_member_stochastic(ics_kernel_member m);
/* Bit 1: has a 1D form, bit 2: has a 2D form (GAUSS: 3). 0 when out of range. */
ICS_API int ics_kernel_member_dims(ics_kernel_member m);

/* A member of a 1D class. nsamples and param as described above; 0 selects the default. */
typedef struct ics_kernel1d {
  ics_kernel_member member;
  ics_class1d cls;
  int nsamples;
  double param;
  uint64_t seed;
} ics_kernel1d;

typedef struct ics_kernel2d {
  ics_kernel_member member;
  ics_class2d cls;
  int nsamples;
  double param;
  uint64_t seed;
} ics_kernel2d;

/* Fill *k with the member, the class and default parameters (seed 0). Validates. */
ICS_API ics_status ics_kernel1d_init(ics_kernel1d *k, ics_kernel_member m, double mean, double var);
ICS_API ics_status ics_kernel2d_init(ics_kernel2d *k, ics_kernel_member m, const ics_class2d *cls);

/* Cost: the largest number of taps any iteration produces (> 0), or 0 when *k is invalid. */
ICS_API int ics_kernel1d_max_taps(const ics_kernel1d *k);
ICS_API int ics_kernel2d_max_taps(const ics_kernel2d *k);

/* Taps of iteration `iter` (ignored by deterministic members) into taps[0 .. cap-1]; *ntaps gets
 * the count. Weights sum to 1. Errors: ICS_ERR_INVALID_ARG (NULL, member without this
 * dimension), class errors as ics_class*_check, ICS_ERR_RANGE (parameter out of range: nsamples
 * < 0 or > limit, param < 0 or not finite, TOPHAT exact box impossible, GAUSS N = 1 with var > 0),
 * ICS_ERR_SIZE (cap < taps needed). */
ICS_API ics_status ics_kernel1d_taps(const ics_kernel1d *k, uint64_t iter, ics_tap1d *taps, int cap,
                                     int *ntaps);
ICS_API ics_status ics_kernel2d_taps(const ics_kernel2d *k, uint64_t iter, ics_tap2d *taps, int cap,
                                     int *ntaps);

/* Expected moments of the taps over the member's randomness, in closed form (not measured): the
 * class itself for every member except TOPHAT with param = 1 (raw box: sigma^2 + E_box[f(1-f)]). */
ICS_API ics_status ics_kernel1d_expected(const ics_kernel1d *k, double *mean, double *var);
ICS_API ics_status ics_kernel2d_expected(const ics_kernel2d *k, double mean[2], double cov[3]);

#ifdef __cplusplus
}
#endif
#endif
