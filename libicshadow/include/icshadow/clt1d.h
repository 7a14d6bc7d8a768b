/* icshadow/clt1d.h — CLT convergence of the 1D kernel members (Patel et al. 2013, Eq. 5-6,
 * Sec. 3.3-3.4): kappa^{*n} * H iterated by the conv engine (conv.h) on the pixel grid
 * (spacing 1), measured against the Gaussian cdf with the class moments, with the step
 * generators it iterates and its work model. The 2D counterpart is clt2d.h; the measured point
 * and the rate fit are in clt.h.
 *
 * A step generator gives the taps of step `step` for a grid refined by `scale` (1: the grid
 * itself, 2: twice as fine, positions doubled). Built-in generators: a kernel member
 * (ics_clt1d_member_gen, the class scaled by scale / scale^2; STOCH_DIRAC's jitter width scaled
 * too) and a fixed tap list (ics_clt1d_fixed_gen), e.g. the skewed member of
 * ics_clt1d_skew_taps. */
#ifndef ICSHADOW_CLT1D_H
#define ICSHADOW_CLT1D_H

#include <stdint.h>

#include "icshadow/clt.h"
#include "icshadow/conv.h"
#include "icshadow/kernel.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef ics_status (*ics_clt1d_gen)(void *ctx, uint64_t step, double scale, ics_tap1d *taps,
                                    int cap, int *ntaps);
ICS_API ics_status ics_clt1d_member_gen(void *ctx /* const ics_kernel1d* */, uint64_t step,
                                        double scale, ics_tap1d *taps, int cap, int *ntaps);

/* ICS_CLT1D_SKEW_TAPS taps of a discretised exponential (weights exp(-j/4), j = 0..15) moved and
 * scaled to the class (mean, var): a skewed (skewness 1.286), non-symmetric class member. */
#define ICS_CLT1D_SKEW_TAPS 16
ICS_API ics_status ics_clt1d_skew_taps(double mean, double var,
                                       ics_tap1d taps[ICS_CLT1D_SKEW_TAPS]);
typedef struct ics_clt1d_fixed {
  const ics_tap1d *taps;
  int ntaps;
} ics_clt1d_fixed;
ICS_API ics_status ics_clt1d_fixed_gen(void *ctx /* const ics_clt1d_fixed* */, uint64_t step,
                                       double scale, ics_tap1d *taps, int cap, int *ntaps);

/* Iterates H on the pixel grid with the generator's taps (compensation `comp`, clamp
 * boundary) and, at each steps[k] (strictly increasing, 1..1e6), measures the sup error
 * against the Gaussian cdf with the class moments n mean, n var (plus the grid's 1/12 px^2:
 * the nodes are exactly the cdf of K_n + U(-1/2, 1/2)). mean, var: the class per step
 * (pixels). If refine is 0, disc_err is NaN and no finer run is made. */
ICS_API ics_status ics_clt1d_measure(ics_clt1d_gen gen, void *ctx, double mean, double var,
                                     const int *steps, int nsteps, ics_comp_mode comp, int refine,
                                     ics_clt_point *out);
/* The same, calling progress(progress_ctx, done, total) after each step (the finer grid runs
 * after the base grid: total is twice the last step count when refine is set). */
ICS_API ics_status ics_clt1d_measure_progress(ics_clt1d_gen gen, void *ctx, double mean,
                                              double var, const int *steps, int nsteps,
                                              ics_comp_mode comp, int refine, ics_clt_point *out,
                                              ics_clt_progress progress, void *progress_ctx);

/* Node count of the base grid and estimated work (tap-updates, see ICS_CONV_WORK_BUDGET of
 * conv.h; the 2x finer run counts too when refine is set: ~5x) of ics_clt1d_measure with the
 * same arguments, without running it. Errors as ics_clt1d_measure (ICS_ERR_SIZE: a grid over
 * 2^24 nodes). */
ICS_API ics_status ics_clt1d_cost(ics_clt1d_gen gen, void *ctx, double mean, double var,
                                  const int *steps, int nsteps, ics_comp_mode comp, int refine,
                                  double *nodes, double *work);

#ifdef __cplusplus
}
#endif
#endif
