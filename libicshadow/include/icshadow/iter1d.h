/* icshadow/iter1d.h — the actually iterated shadow behind an edge for a 1D light (Patel et al.
 * 2013, Eq. 5): r_n = H * kappa^{*n} on a grid, by the conv engine (conv.h), with kappa a
 * kernel member of the Eq. 7/15 class; its interpolation, its isolines and its work model.
 * Conventions as in shadow1d.h.
 *
 * Grid: nodes x_i = x0 + i h, placed so that the edge x = 0 falls half-way between two nodes;
 * r_0(x_i) = H(x_i). The linear interpolation of the nodal values of H * K (K an integer-tap
 * distribution in pixels) is exactly the cdf of h (K + U), U ~ U(-1/2, 1/2): the grid carries an
 * extra h^2/12 of variance. With edge compensation (default) every step's class variance is
 * lowered by h^2/(12 n) so that the represented shadow has exactly the target moments (mean
 * -d mu_l, variance d d1 var_l); the remaining discretisation error is of higher order and is
 * reported by comparing against a grid twice as fine (ics_isoline_iterative, isoline.h). */
#ifndef ICSHADOW_ITER1D_H
#define ICSHADOW_ITER1D_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/conv.h"
#include "icshadow/kernel.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Options of the iteration. Not zero-initialised to its defaults: compensate's default is
 * ICS_COMP_NONNEG, and its zero, ICS_COMP_NONE, is a mode of its own (the conv engine's
 * default); ics_iter1d_opts_init fills the defaults. */
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
                               ics_clt1d_skew_taps (a non-symmetric kernel) */
} ics_iter1d_opts;

/* The defaults: DIRAC, ppsd 64, ICS_COMP_NONNEG, everything else 0. */
ICS_API void ics_iter1d_opts_init(ics_iter1d_opts *out);

/* The iterated shadow: a heap object with public fields, made by ics_iter1d_create and freed
 * by ics_iter1d_destroy. */
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
 * ICS_ERR_RANGE), kappa the member with the Eq. 7/15 class (scaled to pixels); opts NULL: the
 * defaults. d = 0 gives the sampled edge. *out is NULL on failure. Errors: ICS_ERR_INVALID_ARG
 * (NULL out or light), the light's and arguments' errors (NaN, inf, d < 0, d1 <= 0, e <= 0),
 * kernel/engine errors passed through, ICS_ERR_SIZE when the grid would exceed 2^24 nodes,
 * ICS_ERR_NOMEM. */
ICS_API ics_status ics_iter1d_create(ics_iter1d **out, const ics_light1d *l, double d, double d1,
                                     double e, const ics_iter1d_opts *opts);
/* Frees the nodes and the object (NULL is fine). */
ICS_API void ics_iter1d_destroy(ics_iter1d *it);

/* Work model of the iterations (ICS_CONV_WORK_BUDGET, conv.h): the grid spacing h, node count
 * and estimated work of ics_iter1d_create with the same arguments, without allocating the
 * grid; the same errors. tap-updates = steps x (grid nodes x applied integer taps +
 * ICS_CONV_WORK_COMP_PASSES x generated taps). Any output pointer may be NULL. */
ICS_API ics_status ics_iter1d_cost(const ics_light1d *l, double d, double d1, double e,
                                   const ics_iter1d_opts *opts, double *h, double *nodes,
                                   double *work);

/* linear interpolation of the nodes (0 / 1 left / right of the grid); NaN for NaN x */
ICS_API double ics_iter1d_eval(const ics_iter1d *it, double x);
/* the x where the interpolated shadow first reaches s in (0, 1); NaN if never */
ICS_API double ics_iter1d_isoline(const ics_iter1d *it, double s);

#ifdef __cplusplus
}
#endif
#endif
