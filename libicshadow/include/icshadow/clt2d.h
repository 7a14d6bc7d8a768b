/* icshadow/clt2d.h — CLT convergence of the 2D kernel members (Patel et al. 2013, Eq. 5-6,
 * Sec. 3.3-3.4): the actually iterated kappa^{*n} * O for a 2D occluder image O (the 2D engine of
 * icshadow/conv.h, bilinear taps, interpolation-variance compensation), measured against the
 * Gaussian limit with the same moments. The 2D counterpart of ics_clt1d_measure (clt1d.h);
 * method, formulas and checks in the header comment of libicshadow/src/clt2d.c and in
 * docs/theory.md ("CLT convergence of 2D members").
 *
 * Units: pixels of the base grid; a grid refined by `scale` (2: twice as fine) has its taps'
 * positions multiplied by scale. Shadow value 0 = lit, 1 = umbra (as in shadow1d.h).
 * Occluders (opaque part, the edge/corner through the origin):
 *   ICS_CLT2D_EDGE    the half-plane u . x > 0, u = (cos a, sin a), a = edge_angle_deg
 *                     (a = 0: opaque for x > 0, the 1D case of shadow1d.h on every row);
 *                     limit Phi((u . x - n u . mu) / sqrt(n u^T Sigma u + 1/12));
 *   ICS_CLT2D_CORNER  the quadrant x > 0 and y > 0; limit the bivariate normal cdf
 *                     P(X < x, Y < y), (X, Y) ~ N(n mu, n Sigma + I/12).
 * The 1/12 (1/(12 scale^2) on a refined grid) is the pixel: the initial image is the exact
 * area coverage of the occluder, so the nodes hold exactly the cdf of K_n + U, U uniform on the
 * pixel square (clt2d.c). */
#ifndef ICSHADOW_CLT2D_H
#define ICSHADOW_CLT2D_H

#include <stdint.h>

#include "icshadow/clt.h"
#include "icshadow/conv.h"
#include "icshadow/kernel.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Taps of step `step` for a grid refined by `scale` (positions x scale, covariance x scale^2).
 * The same continuous kernel on both grids: stochastic members draw from (seed, step) only. */
typedef ics_status (*ics_clt2d_gen)(void *ctx, uint64_t step, double scale, ics_tap2d *taps,
                                    int cap, int *ntaps);

/* A kernel member of kernel.h (ELLIPSE: random offset per step from (seed, step); POISSON: random
 * rotation per step; GAUSS: fixed N x N grid), its class scaled. ctx: const ics_kernel2d*. */
ICS_API ics_status ics_clt2d_member_gen(void *ctx, uint64_t step, double scale, ics_tap2d *taps,
                                        int cap, int *ntaps);

/* The N-sample elliptical kernel (ics_ellipse_kernel) with a DETERMINISTIC offset schedule:
 * step i uses offset + i * rot (mod 1). rot = 0: the same taps every step (fixed offset);
 * rot = (sqrt(5) - 1) / 2 = ICS_CLT2D_GOLDEN: offsets rotated by the golden ratio each step. */
#define ICS_CLT2D_GOLDEN 0.61803398874989484820
typedef struct ics_clt2d_ellipse {
  double mean[2];
  double varx, vary, angle_deg; /* the class covariance as axes (class.h, ics_class2d_to_axes) */
  int nsamples;                 /* 1..ICS_ELLIPSE_MAX_SAMPLES */
  double offset, rot;
} ics_clt2d_ellipse;
ICS_API ics_status ics_clt2d_ellipse_gen(void *ctx /* const ics_clt2d_ellipse* */, uint64_t step,
                                         double scale, ics_tap2d *taps, int cap, int *ntaps);

typedef enum ics_clt2d_occluder {
  ICS_CLT2D_EDGE = 0,
  ICS_CLT2D_CORNER = 1
} ics_clt2d_occluder;

typedef struct ics_clt2d_setup {
  ics_clt2d_occluder occluder;
  double edge_angle_deg; /* EDGE: direction of the opaque side's normal, degrees ccw from +x */
  double mean[2];        /* the class per step (pixels): the Gaussian the error is measured to */
  double cov[3];         /* cxx, cxy, cyy (pixels^2): positive SEMIdefinite (rank one, e.g. a
                            line light, is accepted; det >= -1e-12 trace^2), trace > 0 */
  ics_comp_mode comp;    /* NONE, NONNEG or SIGNED (INTEGER: ICS_ERR_UNSUPPORTED, as the engine) */
  int refine;            /* 1: also run a grid twice as fine and report disc_err; 0: NaN */
} ics_clt2d_setup;

/* Fills *out with the defaults: edge at 0 degrees, mean 0, cov 0 (must be set), NONNEG, refine
 * 1. A zeroed setup is not the defaults: comp's zero is ICS_COMP_NONE and refine's 0 skips the
 * finer grid, both settings of their own. */
ICS_API void ics_clt2d_setup_init(ics_clt2d_setup *out);

#define ICS_CLT2D_MAX_STEPS 100000
/* Base grid cap. Memory of ics_clt2d_measure: 2 float buffers per grid, the base and (refine)
 * the 2x finer grid iterated in lockstep, the error profiles compared node by node and never
 * stored: 8 bytes a base pixel + ~32 for the fine grid, i.e. <= 160 MiB at the cap, plus
 * 40 bytes per requested step count. */
#define ICS_CLT2D_MAX_PIXELS ((double)(1 << 22))

/* First generates and compensates every step's taps once (the realised path m_n, C_n; the
 * generator must be deterministic in the step index), sizes the grid to hold both paths, then
 * iterates the occluder image with the generator's taps (compensation s->comp, clamp boundary,
 * float image as the engine) and at each steps[k] (strictly increasing, 1..ICS_CLT2D_MAX_STEPS)
 * fills out[k] (the point type of clt.h):
 *   sup_err          max over the nodes x of the window of |r_n(x) - G_n(x)|, G_n the class
 *                    limit above; the window is the union of |x - n mu|_inf <= 4.5 sd_n
 *                    (sd_n^2 = n lambda_max(Sigma) + 1/12) and |x - m_n|_inf <= 4.5 sdr_n, m_n,
 *                    sdr_n^2 = lambda_max(C_n) + 1/12 from the realised moments below (they
 *                    can drift apart: a fixed odd-N ellipse, the compensation's fallback);
 *   sup_err_realized the same against the limit N(m_n, C_n + I/12), m_n and C_n the summed
 *                    means and covariances of the integer taps actually applied (differ from
 *                    n mu, n Sigma for stochastic members and when compensation leaves a
 *                    residual, e.g. the rank-one 2-sample ellipse);
 *   disc_err         max over the same nodes of the change of the class error profile
 *                    r_n - G_n on the 2x finer grid (whose nodes include the base nodes);
 *   cost             integer taps applied, summed over the steps (base grid);
 *   seconds          CPU time of the base grid's iteration up to n (measurement excluded).
 * Errors: ICS_ERR_INVALID_ARG (NULL, nsteps <= 0, unknown occluder), ICS_ERR_NAN /
 * ICS_ERR_INFINITE (mean, cov, angle), ICS_ERR_NEGATIVE_VARIANCE (cov not positive
 * semidefinite or trace 0),
 * ICS_ERR_RANGE (steps), ICS_ERR_UNSUPPORTED (comp INTEGER), ICS_ERR_SIZE (base grid over
 * ICS_CLT2D_MAX_PIXELS), generator/engine errors passed through, ICS_ERR_NOMEM. */
ICS_API ics_status ics_clt2d_measure(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                                     const int *steps, int nsteps, ics_clt_point *out);
/* The same, calling progress(progress_ctx, n, steps[nsteps - 1]) after each step n (the finer
 * grid steps together with the base grid). */
ICS_API ics_status ics_clt2d_measure_progress(ics_clt2d_gen gen, void *ctx,
                                              const ics_clt2d_setup *s, const int *steps,
                                              int nsteps, ics_clt_point *out,
                                              ics_clt_progress progress, void *progress_ctx);

/* Base-grid pixel count and estimated work (tap-updates as ICS_CONV_WORK_BUDGET of conv.h: steps x
 * pixels x applied taps + ICS_CONV_WORK_COMP_PASSES x generated taps, per grid, plus the limits at
 * the window's nodes: 60 per node for the edge's Phi, 4000 for the corner's ics_normal_bvn_cdf
 * (10000 when |rho| >= 0.9), x 2 on the base grid (class and realised), x 1 on the finer grid
 * (class), which counts when s->refine; plus the realised path's pass, ICS_CONV_WORK_COMP_PASSES x
 * generated taps a step) of ics_clt2d_measure, without running it. When the estimate on the class
 * path's grid alone (a lower bound) already exceeds ICS_CONV_WORK_BUDGET, that lower bound is
 * returned without the realised pass, so a refusal costs no step's taps. Same argument errors.
 * Measured here (clt2d.c): 0.21 ns per engine tap-update (Release; 0.21-0.41 under load), so the 1D
 * budget ICS_CONV_WORK_BUDGET of 1e11 is 21-41 s. */
ICS_API ics_status ics_clt2d_cost(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                                  const int *steps, int nsteps, double *pixels, double *work);

/* Area of the unit pixel square centred at the node on the opaque side of an edge whose unit
 * normal is (ux, uy), at signed distance t = u . x of the node from the edge: the cdf of
 * ux U1 + uy U2 at t, U uniform on (-1/2, 1/2) (a trapezoid). NaN for NaN. */
ICS_API double ics_clt2d_edge_coverage(double ux, double uy, double t);

#ifdef __cplusplus
}
#endif
#endif
