/* isoline.c — isolines behind a Heaviside edge for a 1D light (Patel et al. 2013, Sec. 6,
 * Appendix A.4–A.5): correct and CLT in closed form, iterated from two grids (see
 * icshadow/isoline.h). The correct isolines use the light's upper quantile (isf) so that
 * levels near 0 and 1 keep their precision. */
#include "icshadow/isoline.h"
#include "icshadow/conv.h"
#include "icshadow/normal.h"

#include <math.h>
#include <stdio.h>

static int bad_d(double d) { return isnan(d) || d < 0 || isinf(d); }
static int bad_s(double s) { return !(s > 0 && s < 1); }

double ics_isoline_correct(const ics_light1d *l, double s, double d) {
  if (!l || bad_d(d) || bad_s(s)) return NAN;
  if (d == 0) return 0.0;
  return -d * ics_light1d_isf(l, s);
}

double ics_isoline_clt(const ics_light1d *l, double s, double d, double d1) {
  if (!l || bad_d(d) || bad_s(s) || !(d1 > 0) || isinf(d1)) return NAN;
  return -d * ics_light1d_mean(l) + ics_normal_quantile(s) * sqrt(d1 * ics_light1d_var(l) * d);
}

ics_status ics_isoline_iterative(const ics_light1d *l, double s, double d, double d1, double e,
                                 const ics_iter1d_opts *opts, double *x, double *disc_err) {
  if (bad_s(s)) return isnan(s) ? ICS_ERR_NAN : ICS_ERR_RANGE;
  if (isnan(d)) return ICS_ERR_NAN;
  if (d == 0) { /* the edge itself: every isoline passes through x = 0 */
    if (x) *x = 0;
    if (disc_err) *disc_err = 0;
    return ICS_OK;
  }
  ics_iter1d_opts o;
  if (opts)
    o = *opts;
  else
    ics_iter1d_opts_init(&o);
  ics_iter1d *a = NULL, *b = NULL;
  ics_status st = ics_iter1d_create(&a, l, d, d1, e, &o);
  if (st != ICS_OK) return st;
  o.h = a->h / 2;
  st = ics_iter1d_create(&b, l, d, d1, e, &o);
  if (st != ICS_OK) {
    ics_iter1d_destroy(a);
    return st;
  }
  double xa = ics_iter1d_isoline(a, s), xb = ics_iter1d_isoline(b, s);
  ics_iter1d_destroy(a);
  ics_iter1d_destroy(b);
  if (x) *x = xb;
  if (disc_err) *disc_err = fabs(xa - xb);
  return (isnan(xa) || isnan(xb)) ? ICS_ERR_RANGE : ICS_OK;
}

ics_status ics_isoline_iterative_bounded(const ics_light1d *l, double s, double d, double d1,
                                         double e, const ics_iter1d_opts *opts, double *x,
                                         double *disc_err, char *msg, size_t msg_size) {
  double nf = d / e, disc;
  if (fabs(nf - nearbyint(nf)) > 1e-9 * fmax(nf, 1.0) || nf > 1e6) {
    if (msg) snprintf(msg, msg_size, "distance / slab = %.17g must be an integer number of slabs "
                      "(at most 1e6)", nf);
    return ICS_ERR_RANGE;
  }
  if (ics_light1d_var(l) == 0 && d > 0) {
    if (msg) snprintf(msg, msg_size, "the iterated isoline needs a light with variance > 0");
    return ICS_ERR_RANGE;
  }
  double h = 0, nodes = 0, w1 = 0, w2 = 0;
  ics_status st = d > 0 ? ics_iter1d_cost(l, d, d1, e, opts, &h, &nodes, &w1) : ICS_OK;
  if (st == ICS_OK && d > 0) { /* and the run on the grid twice as fine */
    ics_iter1d_opts o2 = *opts;
    o2.h = h / 2;
    st = ics_iter1d_cost(l, d, d1, e, &o2, NULL, NULL, &w2);
  }
  if (st == ICS_OK && w1 + w2 > ICS_CONV_WORK_BUDGET) {
    if (msg) snprintf(msg, msg_size, "estimated work %.3g tap-updates (%.0f slabs on %.0f nodes, "
                      "and again on a grid twice as fine) exceeds the budget of %.0e (give fewer "
                      "slabs: a larger slab or a smaller distance, or fewer samples)",
                      w1 + w2, nearbyint(nf), nodes, ICS_CONV_WORK_BUDGET);
    return ICS_ERR_SIZE;
  }
  if (st == ICS_OK) st = ics_isoline_iterative(l, s, d, d1, e, opts, x, &disc);
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "iterated shadow failed: %s", ics_status_str(st));
    return st;
  }
  if (disc_err) *disc_err = disc;
  return ICS_OK;
}
