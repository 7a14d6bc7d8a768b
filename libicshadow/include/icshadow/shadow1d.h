/* icshadow/shadow1d.h — shadows behind a Heaviside edge for a 1D light (Patel et al. 2013,
 * Sec. 6, Appendix A.3–A.5): the correct shadow, the CLT model and their isolines. The
 * actually iterated shadow (conv engine) is in ics_shadow1d_iterate.
 *
 * Sign conventions (the paper's, Eq. 4 and 16, made explicit):
 * - The occluder o(x) = H(x) is opaque for x > 0 and clear for x < 0.
 * - The light l is a density on the light-plane x axis with cdf L, mean mu_l, variance var_l;
 *   light at +x on the plane (mu_l > 0) throws the shadow toward -x.
 * - The shadow value s is the BLOCKED fraction of the light (0 = fully lit, 1 = umbra):
 *     correct (Eq. 16):  s_d(x) = 1 - L(-x/d)         (the cdf of -d X_l; H(x) at d = 0)
 *     CLT     (Eq. 8):   z_d(x) = Phi((x + d mu_l) / sqrt(d d1 var_l))
 *     iterated (Eq. 5):  r_n = H * kappa^{*n}, n = d/e, kappa with mean -e mu_l and variance
 *                        d1 e var_l (Eq. 7/15).
 *   All three increase in x from 0 (lit, x -> -inf) to 1 (x -> +inf).
 * - Isolines, level s in (0, 1), distance d >= 0:
 *     correct:  x = -d L^-1(1 - s) = d C_s            (straight lines through the edge)
 *     CLT:      x = -d mu_l + Phi^-1(s) sqrt(d1 var_l) sqrt(d)   (= c sigma_l sqrt(d))
 *   At d = d1 they agree for Gaussian lights. A.5 claims the s = 1/2 isolines coincide for any
 *   light; they do when the light's median equals its mean and the kernel is symmetric.
 *
 * Math functions return NaN outside their domain (d < 0, d1 <= 0, s outside (0, 1), NaN). */
#ifndef ICSHADOW_SHADOW1D_H
#define ICSHADOW_SHADOW1D_H

#include <stddef.h>

#include "icshadow/conv.h"
#include "icshadow/kernel.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* correct shadow s_d(x) = 1 - L(-x/d) (computed as sf(-x/d), no cancellation); d = 0: H(x)
 * with H(0) = 1/2 */
ICS_API double ics_shadow1d_correct(const ics_light1d *l, double d, double x);
/* CLT model Phi((x + d mu_l) / sqrt(d d1 var_l)); a zero variance gives the shifted edge */
ICS_API double ics_shadow1d_clt(const ics_light1d *l, double d, double d1, double x);

/* isoline positions at level s in (0, 1) and distance d >= 0 */
ICS_API double ics_isoline_correct(const ics_light1d *l, double s, double d);
ICS_API double ics_isoline_clt(const ics_light1d *l, double s, double d, double d1);

/* ---- the actually iterated shadow (conv engine, icshadow/conv.h) ----
 *
 * Grid: nodes x_i = x0 + i h, placed so that the edge x = 0 falls half-way between two nodes;
 * r_0(x_i) = H(x_i). The linear interpolation of the nodal values of H * K (K an integer-tap
 * distribution in pixels) is exactly the cdf of h (K + U), U ~ U(-1/2, 1/2): the grid carries an
 * extra h^2/12 of variance. With edge_comp = 1 (default) every step's class variance is lowered
 * by h^2/(12 n) so that the represented shadow has exactly the target moments (mean -d mu_l,
 * variance d d1 var_l); the remaining discretisation error is of higher order and is reported by
 * comparing against a grid twice as fine (ics_shadow1d_iterate_refine). */
typedef struct ics_iter1d_opts {
  ics_kernel_member member; /* a member with a 1D form (default ICS_KERNEL_DIRAC) */
  int nsamples;             /* member parameter (0: the member's default) */
  double param;             /* member parameter (0: the member's default) */
  uint64_t seed;            /* stochastic members */
  double h;                 /* grid spacing in world units; 0: sqrt(d d1 var_l) / ppsd */
  double ppsd;              /* pixels per final standard deviation when h = 0 (default 64) */
  ics_comp_mode compensate; /* interpolation-variance compensation (default ICS_COMP_NONNEG) */
  int no_edge_comp;         /* 1: do not remove the grid's h^2/12 (for measurements) */
  double mean_sign;         /* 0 or 1: Eq. 7 as is; -1 flips the kernel mean (broken on purpose) */
  double var_factor;        /* 0: d1 (Eq. 7); else the kernel variance is var_factor e var_l */
  int skew;                 /* 1: instead of the member, the skewed class member of
                               ics_clt_skew_taps (a non-symmetric kernel) */
} ics_iter1d_opts;

ICS_API ics_iter1d_opts ics_iter1d_opts_default(void);

typedef struct ics_iter1d {
  double x0, h;    /* node i is at x0 + i h */
  size_t n;        /* nodes */
  double *r;       /* shadow values (owned) */
  int steps;       /* d / e */
  int max_taps;    /* largest tap count of one step (kernel member, before discretisation) */
  double kmean_px, kvar_px; /* the per-step class (pixels) */
  ics_conv_stats stats;
} ics_iter1d;

/* r_n = H * kappa^{*n} with n = d / e (must be an integer to 1e-9 relative: else
 * ICS_ERR_RANGE), kappa the member with the Eq. 7/15 class (scaled to pixels). d = 0 gives the
 * sampled edge. Errors: light/arguments as above, kernel/engine errors passed through,
 * ICS_ERR_SIZE when the grid would exceed ICS_CONV_MAX_LEN, ICS_ERR_NOMEM. */
ICS_API ics_status ics_shadow1d_iterate(const ics_light1d *l, double d, double d1, double e,
                                        const ics_iter1d_opts *opts, ics_iter1d *out);
ICS_API void ics_iter1d_free(ics_iter1d *it);
/* Work model of the iterations (used by the CLI to refuse runs that would take hours):
 * tap-updates = steps x (grid nodes x applied integer taps + ICS_WORK_COMP_PASSES x generated
 * taps). A tap-update (one multiply-add on the grid) takes ~0.4 ns here (clt, tophat); the
 * second term is the per-step generation, bisection-based compensation and sorting of the
 * member's taps, measured at ~0.8 us per generated tap per step (gauss, 4096 samples: 3.2 ms a
 * step), i.e. ~1600 tap-updates: counted as 2048. ICS_WORK_BUDGET (1e11) is under a minute here
 * (0.37 ns a tap-update measured in 1D, 0.21 ns in the 2D engine). */
#define ICS_WORK_COMP_PASSES 2048
#define ICS_WORK_BUDGET 1e11
/* The grid spacing h, node count and estimated work of ics_shadow1d_iterate with the same
 * arguments, without allocating the grid; the same errors (ICS_ERR_SIZE for a grid over 2^24
 * nodes). */
ICS_API ics_status ics_shadow1d_iterate_cost(const ics_light1d *l, double d, double d1, double e,
                                             const ics_iter1d_opts *opts, double *h, double *nodes,
                                             double *work);
/* linear interpolation of the nodes (0 / 1 left / right of the grid); NaN for NaN x */
ICS_API double ics_iter1d_eval(const ics_iter1d *it, double x);
/* the x where the interpolated shadow first reaches s in (0, 1); NaN if never */
ICS_API double ics_iter1d_isoline(const ics_iter1d *it, double s);

/* The iterated isoline at level s, and an estimate of its discretisation error: the same
 * iteration on a grid twice as fine (h / 2, same member and seed) and |x(h) - x(h/2)|. */
ICS_API ics_status ics_isoline_iterative(const ics_light1d *l, double s, double d, double d1,
                                         double e, const ics_iter1d_opts *opts, double *x,
                                         double *disc_err);

/* ---- CLT convergence of kappa^{*n} * H (pixel units, grid spacing 1) ----
 *
 * A step generator gives the taps of step `step` for a grid refined by `scale` (1: the grid
 * itself, 2: twice as fine, positions doubled). Built-in generators: a kernel member
 * (ics_clt_member_gen, the class scaled by scale / scale^2; STOCH_DIRAC's jitter width scaled
 * too) and a fixed skewed tap list (ics_clt_skew_taps). */
typedef ics_status (*ics_clt_gen)(void *ctx, uint64_t step, double scale, ics_tap1d *taps,
                                  int cap, int *ntaps);
ICS_API ics_status ics_clt_member_gen(void *ctx /* const ics_kernel1d* */, uint64_t step,
                                      double scale, ics_tap1d *taps, int cap, int *ntaps);

/* ICS_CLT_SKEW_TAPS taps of a discretised exponential (weights exp(-j/4), j = 0..15) moved and
 * scaled to the class (mean, var): a skewed (skewness 1.286), non-symmetric class member. */
#define ICS_CLT_SKEW_TAPS 16
ICS_API ics_status ics_clt_skew_taps(double mean, double var, ics_tap1d taps[ICS_CLT_SKEW_TAPS]);
typedef struct ics_clt_fixed {
  const ics_tap1d *taps;
  int ntaps;
} ics_clt_fixed;
ICS_API ics_status ics_clt_fixed_gen(void *ctx /* const ics_clt_fixed* */, uint64_t step,
                                     double scale, ics_tap1d *taps, int cap, int *ntaps);

typedef struct ics_clt_point {
  int steps;
  double sup_err;   /* max over nodes |r_n - Phi((x - n mean) / sqrt(n var + 1/12))| */
  double sup_err_realized; /* the same against the moments of the taps actually applied
                              (differs for stochastic members: their variance is random) */
  double disc_err;  /* max over nodes of the change of that error profile on a grid 2x finer */
  double cost;      /* applied (integer, after compensation) taps summed over the steps */
  double seconds;   /* run time of the iteration up to `steps` on the base grid */
} ics_clt_point;

/* Iterates H on the pixel grid with the generator's taps (compensation `comp`, clamp
 * boundary) and, at each steps[k] (strictly increasing, 1..1e6), measures the sup error
 * against the Gaussian cdf with the class moments n mean, n var (plus the grid's 1/12 px^2:
 * the nodes are exactly the cdf of K_n + U(-1/2, 1/2)). mean, var: the class per step
 * (pixels). If refine is 0, disc_err is NaN and no finer run is made. */
ICS_API ics_status ics_clt_measure(ics_clt_gen gen, void *ctx, double mean, double var,
                                   const int *steps, int nsteps, ics_comp_mode comp, int refine,
                                   ics_clt_point *out);

/* Node count of the base grid and estimated work (tap-updates, see ICS_WORK_BUDGET; the 2x
 * finer run counts too when refine is set: ~5x) of ics_clt_measure with the same arguments,
 * without running it. Errors as ics_clt_measure (ICS_ERR_SIZE: a grid over 2^24 nodes). */
ICS_API ics_status ics_clt_cost(ics_clt_gen gen, void *ctx, double mean, double var,
                                const int *steps, int nsteps, ics_comp_mode comp, int refine,
                                double *nodes, double *work);

/* Least-squares slope of log(err) against log(n) (the convergence rate exponent) over the
 * points with steps >= nmin; NaN with fewer than 2 points. */
ICS_API double ics_clt_rate(const ics_clt_point *p, int npoints, int nmin);

#ifdef __cplusplus
}
#endif
#endif
