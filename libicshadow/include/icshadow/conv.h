/* icshadow/conv.h — the iterative convolution engine, CPU reference path (Patel et al. 2013,
 * Eq. 5: r_{n+1} = r_n * kappa).
 *
 * One step: out(x) = sum_j w_j in(x - x_j) on integer pixels x, for taps (x_j, w_j) (taps.h)
 * from the members of kernel.h, one member per step as a schedule (schedule.h) chooses. A
 * kernel of mean mu therefore shifts the buffer content by +mu pixels. Off-grid taps are read
 * with linear (1D) / bilinear (2D) interpolation, i.e. applied as the integer taps of
 * ics_taps*_discretize, which add the variance of ics_taps*_interp_var; with opts.compensate
 * they are applied as the variance-compensated integer taps of ics_taps*_compensate (taps.h).
 *
 * Boundary: reads outside the buffer take the nearest edge pixel (ICS_BOUNDARY_CLAMP, default:
 * outside the light buffer is lit like its edge) or a constant (ICS_BOUNDARY_CONSTANT).
 * 1D lines are double; 2D images float (row-major, width w, height h, y = row index), summed in
 * double per pixel and rounded once. opts.constant must be finite (ICS_ERR_NAN /
 * ICS_ERR_INFINITE). NaN pixels are not checked: a NaN (or inf) pixel propagates to every output
 * pixel whose taps read it, spreading by the kernel's reach each step (it is the caller's job
 * to keep buffers finite). */
#ifndef ICSHADOW_CONV_H
#define ICSHADOW_CONV_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/kernel.h"
#include "icshadow/schedule.h"
#include "icshadow/status.h"
#include "icshadow/taps.h"

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
