/* icshadow/taps.h — tap lists, the form in which kernels reach the convolution engine: taps
 * (offset in pixels, weight) that the members of kernel.h produce and conv.h applies. Their
 * measured moments, the variance the engine's linear / bilinear interpolation adds, the integer
 * taps the engine actually applies, and the variance compensation that makes those integer
 * taps keep the moments exactly.
 *
 * Interpolation: each offset is split as x_j = i_j + f_j, i_j = floor(x_j), f_j in [0, 1) (it
 * keeps precision: docs/architecture.md "Stack facts measured here"); the tap is then the two
 * integer taps (i_j, w_j (1 - f_j)) and (i_j + 1, w_j f_j): it keeps the mean and ADDS the
 * variance w_j f_j (1 - f_j) per axis (no cross term in 2D: bilinear weights are a product).
 * ics_taps1d_interp_var / ics_taps2d_interp_var give that added variance,
 * ics_taps*_discretize the integer taps.
 *
 * Variance compensation (ics_taps*_compensate): replace taps by INTEGER taps whose discrete
 * moments (total weight, mean, covariance) equal the moments of the input taps exactly, so the
 * interpolation adds nothing. Method: the taps are shrunk about their mean, x -> m + A (x - m)
 * (1D: A = s in [0, 1], found by bisection on the discrete variance, which is continuous in s;
 * 2D: A = T^(1/2) Sigma^(-1/2) with T = Sigma - D(A), by fixed-point iteration), then
 * discretized. When the target is below what non-negative integer taps can reach (1D: the
 * minimum is f_m (1 - f_m) for f_m = frac(mean), reached by two taps at floor/ceil of the mean;
 * e.g. the zero-variance hard shadow with a 0.3 px shift), mode ICS_COMP_NONNEG returns that
 * minimum and the residual (achieved - target variance, >= 0); ICS_COMP_SIGNED returns three
 * taps round(m) - 1, round(m), round(m) + 1 (2D: 3 x 3) with SIGNED weights that reproduce mean
 * and variance exactly (overshoot: sum |w| > 1; see docs/kernels.md). */
#ifndef ICSHADOW_TAPS_H
#define ICSHADOW_TAPS_H

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ics_tap1d {
  double x; /* offset in pixels */
  double w; /* weight */
} ics_tap1d;

typedef struct ics_tap2d {
  double x, y, w;
} ics_tap2d;

/* Compensation of ics_taps*_compensate and of the engine's steps (conv.h's opts.compensate). */
typedef enum ics_comp_mode {
  ICS_COMP_NONE = 0,   /* taps as given; interpolation adds sum w f (1 - f) per step */
  ICS_COMP_NONNEG = 1, /* exact when possible, else closest non-negative taps + residual */
  ICS_COMP_SIGNED = 2, /* exact always; signed weights when non-negative ones cannot be exact */
  ICS_COMP_INTEGER = 3 /* engine runs, 1D only (2D: ICS_ERR_UNSUPPORTED): the integer-shift
                          schedule. Step i (absolute index; a single ics_conv1d_step is step 0)
                          moves the taps so that their mean is the whole-pixel shift
                          round((i + 1) m) - round(i m), m = the taps' mean (round half up),
                          carrying the fractional mean over the steps, then compensates them
                          exactly (NONNEG; with an integer mean every variance >= 0 is
                          reachable). Zero interpolation variance: a zero-variance (hard) shadow
                          stays hard, at most 1/2 px from n m after n steps from step 0. Not a
                          mode of ics_taps*_compensate (ICS_ERR_RANGE there). */
} ics_comp_mode;

/* Measured moments of a tap list (compensated sums): total weight, mean, central variance
 * (2D: cov = {cxx, cxy, cyy}). Divides by the total weight; NaN when it is 0. */
ICS_API void ics_taps1d_moments(const ics_tap1d *t, int n, double *wsum, double *mean, double *var);
ICS_API void ics_taps2d_moments(const ics_tap2d *t, int n, double *wsum, double mean[2],
                                double cov[3]);

/* Variance added by linear interpolation: sum_j w_j f_j (1 - f_j) / sum_j w_j, f_j = frac(x_j).
 * NaN for n <= 0 or a NULL pointer. 2D: out[0] along x, out[1] along y. */
ICS_API double ics_taps1d_interp_var(const ics_tap1d *t, int n);
ICS_API void ics_taps2d_interp_var(const ics_tap2d *t, int n, double out[2]);

/* The integer taps the engine actually applies (duplicates merged, sorted by x then y; zero
 * weights dropped). cap >= 2 n (1D) / 4 n (2D) always suffices. ICS_ERR_SIZE if cap too small,
 * ICS_ERR_NAN / ICS_ERR_INFINITE for a bad tap, ICS_ERR_INVALID_ARG for NULL / n <= 0,
 * ICS_ERR_RANGE for |offset| > 2^30. */
ICS_API ics_status ics_taps1d_discretize(const ics_tap1d *in, int n, ics_tap1d *out, int cap,
                                         int *nout);
ICS_API ics_status ics_taps2d_discretize(const ics_tap2d *in, int n, ics_tap2d *out, int cap,
                                         int *nout);

/* Variance-compensated integer taps (see above). cap >= 2 n + 3 (1D) / 4 n + 9 (2D) suffices.
 * residual (may be NULL): achieved - target variance (1D) / {dxx, dxy, dyy} (2D); 0 when exact.
 * mode ICS_COMP_NONE just discretizes (residual = interpolation variance). */
ICS_API ics_status ics_taps1d_compensate(const ics_tap1d *in, int n, ics_comp_mode mode,
                                         ics_tap1d *out, int cap, int *nout, double *residual);
ICS_API ics_status ics_taps2d_compensate(const ics_tap2d *in, int n, ics_comp_mode mode,
                                         ics_tap2d *out, int cap, int *nout, double residual[3]);

#ifdef __cplusplus
}
#endif
#endif
