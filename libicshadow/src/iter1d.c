/* iter1d.c — the actually iterated shadow behind a Heaviside edge (see icshadow/iter1d.h):
 * the grid and the Eq. 7/15 class of a run, its work model, the run on the conv engine, and the
 * interpolation of its nodes. */
#include "icshadow/iter1d.h"
#include "icshadow/clt1d.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void ics_iter1d_opts_init(ics_iter1d_opts *out) {
  if (!out) return;
  memset(out, 0, sizeof *out);
  out->member = ICS_KERNEL_DIRAC;
  out->ppsd = 64;
  out->compensate = ICS_COMP_NONNEG;
}

/* the defaults when opts is NULL */
static ics_iter1d_opts opts_or_defaults(const ics_iter1d_opts *opts) {
  ics_iter1d_opts o;
  if (opts)
    o = *opts;
  else
    ics_iter1d_opts_init(&o);
  return o;
}

/* the grid and class of ics_iter1d_create, without allocating anything */
typedef struct iter_plan {
  int steps;
  double kmean, kvar, h; /* world units */
  size_t il, n;
} iter_plan;

static ics_status plan_iter(const ics_light1d *l, double d, double d1, double e,
                            const ics_iter1d_opts *o, iter_plan *p) {
  if (isnan(d) || isnan(d1) || isnan(e) || isnan(o->h) || isnan(o->var_factor)) return ICS_ERR_NAN;
  if (isinf(d) || isinf(d1) || isinf(e)) return ICS_ERR_INFINITE;
  if (d < 0 || !(d1 > 0) || !(e > 0) || o->h < 0 || o->var_factor < 0) return ICS_ERR_RANGE;
  double nf = d / e;
  double nr = nearbyint(nf);
  if (nr > 1e8 || fabs(nf - nr) > 1e-9 * fmax(nf, 1.0)) return ICS_ERR_RANGE;
  int steps = (int)nr;
  double mu = ics_light1d_mean(l), var = ics_light1d_var(l);
  double kmean, kvar; /* world units: the Eq. 7/15 mapping of light.c */
  ics_status mst = ics_light_kernel_map_1d(mu, var, e, d1, &kmean, &kvar);
  if (mst != ICS_OK) return mst;
  /* deliberate breaks (tests), applied on top of the mapping */
  if (o->mean_sign < 0) kmean = -kmean;
  if (o->var_factor > 0) kvar = kvar / d1 * o->var_factor;
  double sd_n = sqrt(steps * kvar);                            /* final std */
  double h = o->h;
  if (h == 0) {
    double ppsd = o->ppsd > 0 ? o->ppsd : 64;
    h = sd_n / ppsd;
    if (!(h > 0)) return ICS_ERR_RANGE; /* point light: give h */
  }
  double shift = steps * kmean;
  double lo = fmin(0.0, shift) - 14 * sd_n - 4 * sqrt(kvar) - 4 * h;
  double hi = fmax(0.0, shift) + 14 * sd_n + 4 * sqrt(kvar) + 4 * h;
  double nl = ceil(-lo / h), nrt = ceil(hi / h);
  if (!(nl + nrt <= (double)(1 << 24))) return ICS_ERR_SIZE;
  p->steps = steps;
  p->kmean = kmean;
  p->kvar = kvar;
  p->h = h;
  p->il = (size_t)nl;
  p->n = p->il + (size_t)nrt;
  return ICS_OK;
}

/* generated taps per step of a member and the spread of its step-0 taps (pixels; stochastic
 * members: plus twice the largest jitter, sqrt(3) sd) */
static ics_status member_span(const ics_kernel1d *k, double *nt, double *span) {
  int cap = ics_kernel1d_max_taps(k);
  if (cap <= 0) {
    ics_tap1d probe[1];
    int np;
    ics_status e = ics_kernel1d_taps(k, 0, probe, 0, &np);
    return e != ICS_OK && e != ICS_ERR_SIZE ? e : ICS_ERR_RANGE;
  }
  ics_tap1d *t = malloc((size_t)cap * sizeof *t);
  if (!t) return ICS_ERR_NOMEM;
  int n = 0;
  ics_status st = ics_kernel1d_taps(k, 0, t, cap, &n);
  double lo = INFINITY, hi = -INFINITY;
  for (int j = 0; st == ICS_OK && j < n; j++) lo = fmin(lo, t[j].x), hi = fmax(hi, t[j].x);
  free(t);
  if (st != ICS_OK) return st;
  *nt = cap;
  *span = hi - lo;
  if (ics_kernel_member_stochastic(k->member)) *span += 4 * sqrt(3 * k->cls.var);
  return ICS_OK;
}

ics_status ics_iter1d_cost(const ics_light1d *l, double d, double d1, double e,
                           const ics_iter1d_opts *opts, double *h, double *nodes, double *work) {
  if (!l) return ICS_ERR_INVALID_ARG;
  ics_iter1d_opts o = opts_or_defaults(opts);
  iter_plan p;
  ics_status st = plan_iter(l, d, d1, e, &o, &p);
  if (st != ICS_OK) return st;
  if (h) *h = p.h;
  if (nodes) *nodes = (double)p.n;
  double nt, span; /* generated taps per step and their spread (pixels) */
  if (o.skew) {
    nt = ICS_CLT1D_SKEW_TAPS;
    span = 5 * sqrt(p.kvar) / p.h; /* the skewed member spans 15 / 3.5 sd */
  } else {
    ics_kernel1d k;
    st = ics_kernel1d_init(&k, o.member, p.kmean / p.h, p.kvar / (p.h * p.h));
    if (st != ICS_OK) return st;
    k.nsamples = o.nsamples;
    k.param = o.param;
    st = member_span(&k, &nt, &span);
    if (st != ICS_OK) return st;
  }
  double nd = fmin(2 * nt + 3, ceil(span) + 4); /* applied integer taps */
  if (work) *work = (double)p.steps * ((double)p.n * nd + ICS_CONV_WORK_COMP_PASSES * nt);
  return ICS_OK;
}

/* r_n on the grid of plan p into the nodes of it (allocated, r_0 = H), steps of the run */
static ics_status iterate(ics_iter1d *it, const iter_plan *p, const ics_iter1d_opts *o) {
  const size_t n = p->n, il = p->il;
  const double h = p->h;
  const int steps = p->steps;
  it->n = n;
  it->h = h;
  it->x0 = (0.5 - (double)il) * h; /* node il is at +h/2: the edge is between nodes */
  for (size_t i = 0; i < n; i++) it->r[i] = i >= il ? 1.0 : 0.0;
  it->steps = steps;
  it->kmean_px = p->kmean / h;
  it->kvar_px = p->kvar / (h * h);
  if (steps == 0) return ICS_OK;
  if (!o->no_edge_comp) it->kvar_px -= 1.0 / (12.0 * steps);
  if (it->kvar_px < 0) it->kvar_px = 0;
  ics_conv_opts co = {0};
  co.boundary = ICS_BOUNDARY_CLAMP;
  co.compensate = o->compensate;
  ics_status st;
  if (o->skew) {
    ics_tap1d taps[ICS_CLT1D_SKEW_TAPS];
    double *tmp = malloc(n * sizeof *tmp);
    if (!tmp) return ICS_ERR_NOMEM;
    st = ics_clt1d_skew_taps(it->kmean_px, it->kvar_px, taps);
    it->max_taps = ICS_CLT1D_SKEW_TAPS;
    for (int i = 0; st == ICS_OK && i < steps; i++) {
      st = ics_conv1d_step(it->r, tmp, n, taps, ICS_CLT1D_SKEW_TAPS, &co);
      memcpy(it->r, tmp, n * sizeof *tmp);
    }
    it->stats.steps = steps;
    free(tmp);
    return st;
  }
  ics_kernel1d k;
  st = ics_kernel1d_init(&k, o->member, it->kmean_px, it->kvar_px);
  if (st != ICS_OK) return st;
  k.nsamples = o->nsamples;
  k.param = o->param;
  k.seed = o->seed;
  ics_schedule1d sch = {&k, 1};
  it->max_taps = ics_schedule1d_max_taps(&sch);
  return ics_conv1d_run(it->r, n, &sch, 0, steps, &co, &it->stats);
}

ics_status ics_iter1d_create(ics_iter1d **out, const ics_light1d *l, double d, double d1, double e,
                             const ics_iter1d_opts *opts) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!l) return ICS_ERR_INVALID_ARG;
  ics_iter1d_opts o = opts_or_defaults(opts);
  iter_plan p;
  ics_status st = plan_iter(l, d, d1, e, &o, &p);
  if (st != ICS_OK) return st;
  ics_iter1d *it = calloc(1, sizeof *it);
  if (!it) return ICS_ERR_NOMEM;
  it->r = malloc(p.n * sizeof *it->r);
  st = it->r ? iterate(it, &p, &o) : ICS_ERR_NOMEM;
  if (st != ICS_OK) {
    ics_iter1d_destroy(it);
    return st;
  }
  *out = it;
  return ICS_OK;
}

void ics_iter1d_destroy(ics_iter1d *it) {
  if (!it) return;
  free(it->r);
  free(it);
}

double ics_iter1d_eval(const ics_iter1d *it, double x) {
  if (!it || !it->r || isnan(x)) return NAN;
  double t = (x - it->x0) / it->h;
  if (t <= 0) return it->r[0];
  if (t >= (double)(it->n - 1)) return it->r[it->n - 1];
  size_t i = (size_t)t;
  double f = t - (double)i;
  return it->r[i] + f * (it->r[i + 1] - it->r[i]);
}

double ics_iter1d_isoline(const ics_iter1d *it, double s) {
  if (!it || !it->r || !(s > 0 && s < 1)) return NAN;
  for (size_t i = 1; i < it->n; i++) {
    if (it->r[i] >= s && it->r[i - 1] < s) {
      double f = (s - it->r[i - 1]) / (it->r[i] - it->r[i - 1]);
      return it->x0 + ((double)(i - 1) + f) * it->h;
    }
  }
  return NAN;
}
