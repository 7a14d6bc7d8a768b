/* icshadow/clt.h — what the CLT convergence measurements in 1D (clt1d.h) and 2D (clt2d.h)
 * share: the measured point of one step count and the fit of the convergence rate. */
#ifndef ICSHADOW_CLT_H
#define ICSHADOW_CLT_H

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One step count of a measurement (the fields' exact definitions are in ics_clt1d_measure and
 * ics_clt2d_measure). */
typedef struct ics_clt_point {
  int steps;
  double sup_err;   /* max over nodes |r_n - Phi((x - n mean) / sqrt(n var + 1/12))| */
  double sup_err_realized; /* the same against the moments of the taps actually applied
                              (differs for stochastic members: their variance is random) */
  double disc_err;  /* max over nodes of the change of that error profile on a grid 2x finer */
  double cost;      /* applied (integer, after compensation) taps summed over the steps */
  double seconds;   /* run time of the iteration up to `steps` on the base grid */
} ics_clt_point;

/* A measurement's progress: called after each step of the iteration with the steps done and
 * the total (both grids' steps when a finer grid runs after the base grid). */
typedef void (*ics_clt_progress)(void *ctx, long done, long total);

/* Least-squares slope of log(err) against log(n) (the convergence rate exponent) over the
 * points with steps >= nmin and sup_err > 0; NaN with fewer than 2 points. */
ICS_API double ics_clt_rate(const ics_clt_point *p, int npoints, int nmin);

#ifdef __cplusplus
}
#endif
#endif
