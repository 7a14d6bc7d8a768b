/* icshadow/conv.h — the iterative convolution engine, CPU reference path (Patel et al. 2013,
 * Eq. 5: r_{n+1} = r_n * kappa).
 *
 * One step: out(x) = sum_j w_j in(x - x_j) on integer pixels x, for taps (x_j, w_j) from
 * icshadow/kernel.h. A kernel of mean mu therefore shifts the buffer content by +mu pixels.
 * Off-grid taps are read with linear (1D) / bilinear (2D) interpolation. Each offset is split
 * as x_j = i_j + f_j, i_j = floor(x_j), f_j in [0, 1) (it keeps precision: docs/architecture.md
 * "Stack facts measured here"); the tap is then the two integer taps (i_j, w_j (1 - f_j)) and
 * (i_j + 1, w_j f_j): it keeps the mean and ADDS the variance w_j f_j (1 - f_j) per axis (no
 * cross term in 2D: bilinear weights are a product). ics_interp_var1d/2d give that added variance; ics_taps*_discretize the integer taps.
 *
 * Boundary: reads outside the buffer take the nearest edge pixel (ICS_BOUNDARY_CLAMP, default:
 * outside the light buffer is lit like its edge) or a constant (ICS_BOUNDARY_CONSTANT).
 * 1D lines are double; 2D images float (row-major, width w, height h, y = row index), summed in
 * double per pixel and rounded once. opts.constant must be finite (ICS_ERR_NAN /
 * ICS_ERR_INFINITE). NaN pixels are not checked: a NaN (or inf) pixel propagates to every output
 * pixel whose taps read it, spreading by the kernel's reach each step (it is the caller's job
 * to keep buffers finite).
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
#ifndef ICSHADOW_CONV_H
#define ICSHADOW_CONV_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/status.h"
#include "icshadow/kernel.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_CONV_MAX_LEN ((size_t)1 << 28) /* largest line length / image pixel count */

/* Work model of engine runs (ics_iter1d_cost, ics_clt1d_cost, ics_clt2d_cost; the CLI refuses
 * runs that would take hours): tap-updates = steps x (grid nodes x applied integer taps +
 * ICS_CONV_WORK_COMP_PASSES x generated taps). A tap-update (one multiply-add on the grid) takes
 * ~0.4 ns here (clt, tophat); the second term is the per-step generation, bisection-based
 * compensation and sorting of the member's taps, measured at ~0.8 us per generated tap per step
 * (gauss, 4096 samples: 3.2 ms a step), i.e. ~1600 tap-updates: counted as 2048.
 * ICS_CONV_WORK_BUDGET (1e11) is under a minute here (0.37 ns a tap-update measured in 1D, 0.21
 * ns in the 2D engine). */
#define ICS_CONV_WORK_COMP_PASSES 2048
#define ICS_CONV_WORK_BUDGET 1e11

typedef enum ics_boundary {
  ICS_BOUNDARY_CLAMP = 0,   /* nearest edge pixel */
  ICS_BOUNDARY_CONSTANT = 1 /* opts.constant */
} ics_boundary;

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

/* Options of a step or run; zero-initialised ({0}) they are the defaults: clamp-to-edge,
 * constant 0, no compensation. A NULL opts means the same. */
typedef struct ics_conv_opts {
  ics_boundary boundary;
  double constant;      /* value outside the buffer for ICS_BOUNDARY_CONSTANT */
  ics_comp_mode compensate;
} ics_conv_opts;

/* Accumulated over the steps of a run (all in pixels^2, per axis for 2D: [0] x, [1] y). */
typedef struct ics_conv_stats {
  int steps;
  double kernel_var[2];  /* sum of the taps' own variances (before interpolation) */
  double interp_var[2];  /* sum of the variance the interpolation added (0 when compensated,
                            except the residual) */
  double residual[2];    /* sum of compensation residuals (achieved - target), NONNEG mode */
} ics_conv_stats;

/* Variance added by linear interpolation: sum_j w_j f_j (1 - f_j) / sum_j w_j, f_j = frac(x_j).
 * NaN for n <= 0 or a NULL pointer. 2D: out[0] along x, out[1] along y. */
ICS_API double ics_interp_var1d(const ics_tap1d *t, int n);
ICS_API void ics_interp_var2d(const ics_tap2d *t, int n, double out[2]);

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

/* One step, in -> out (distinct buffers, length n / w x h). opts NULL = defaults (compensation
 * applies here too). Errors: ICS_ERR_INVALID_ARG (NULL, in == out, ntaps <= 0),
 * ICS_ERR_SIZE (n or w h zero or > ICS_CONV_MAX_LEN), tap errors as discretize, ICS_ERR_NOMEM. */
ICS_API ics_status ics_conv1d_step(const double *in, double *out, size_t n, const ics_tap1d *taps,
                                   int ntaps, const ics_conv_opts *opts);
ICS_API ics_status ics_conv2d_step(const float *in, float *out, size_t w, size_t h,
                                   const ics_tap2d *taps, int ntaps, const ics_conv_opts *opts);

/* nsteps steps in place on buf, step i = first_step + k using the schedule's taps for that step.
 * stats may be NULL (else it is reset, then filled). nsteps = 0 is a no-op. */
ICS_API ics_status ics_conv1d_run(double *buf, size_t n, const ics_schedule1d *s,
                                  uint64_t first_step, int nsteps, const ics_conv_opts *opts,
                                  ics_conv_stats *stats);
ICS_API ics_status ics_conv2d_run(float *buf, size_t w, size_t h, const ics_schedule2d *s,
                                  uint64_t first_step, int nsteps, const ics_conv_opts *opts,
                                  ics_conv_stats *stats);

#ifdef __cplusplus
}
#endif
#endif
