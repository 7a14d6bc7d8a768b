/* icshadow/isoline.h — isolines of the shadows behind an edge for a 1D light (Patel et al.
 * 2013, Sec. 6, Appendix A.4–A.5): the position x of shadow level s at distance d for the
 * correct shadow, the CLT model (both in closed form; conventions and formulas in shadow1d.h)
 * and the actually iterated shadow (iter1d.h). Math functions return NaN outside their domain
 * (d < 0, d1 <= 0, s outside (0, 1), NaN). */
#ifndef ICSHADOW_ISOLINE_H
#define ICSHADOW_ISOLINE_H

#include "icshadow/iter1d.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* isoline positions at level s in (0, 1) and distance d >= 0 */
ICS_API double ics_isoline_correct(const ics_light1d *l, double s, double d);
ICS_API double ics_isoline_clt(const ics_light1d *l, double s, double d, double d1);

/* The iterated isoline at level s, and an estimate of its discretisation error: the same
 * iteration (ics_iter1d_create) on a grid twice as fine (h / 2, same member and seed) and
 * |x(h) - x(h/2)|; *x is the finer grid's. d = 0 gives x = 0 (the edge itself). */
ICS_API ics_status ics_isoline_iterative(const ics_light1d *l, double s, double d, double d1,
                                         double e, const ics_iter1d_opts *opts, double *x,
                                         double *disc_err);

/* The same, with its work bounded before it starts (`icshadow isoline --model iterative`):
 * d / e must be a whole number of slabs, at most 1e6 (ICS_ERR_RANGE), the light must spread
 * (variance > 0, ICS_ERR_RANGE, unless d = 0), and the work on both grids must stay within
 * ICS_CONV_WORK_BUDGET (ICS_ERR_SIZE); msg (may be NULL) says which, with the numbers.
 * disc_err may be NULL. */
ICS_API ics_status ics_isoline_iterative_bounded(const ics_light1d *l, double s, double d,
                                                 double d1, double e,
                                                 const ics_iter1d_opts *opts, double *x,
                                                 double *disc_err, char *msg, size_t msg_size);

#ifdef __cplusplus
}
#endif
#endif
