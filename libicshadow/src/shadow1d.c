/* shadow1d.c — shadows behind a Heaviside edge for a 1D light (Patel et al. 2013, Sec. 6,
 * Appendix A.3–A.5). Conventions in icshadow/shadow1d.h.
 *
 * Method: the correct shadow is the light's survival function at -x/d (Eq. 16), so its
 * accuracy is that of ics_light1d_sf (~1e-15 relative for Gaussian lights and mixtures, both
 * tails); isolines use the upper quantile (isf) so that levels near 0 and 1 keep their
 * precision. The CLT model is Phi of the standardised position. */
#include "icshadow/shadow1d.h"
#include "icshadow/normal.h"

#include <math.h>

static int bad_d(double d) { return isnan(d) || d < 0 || isinf(d); }
static int bad_s(double s) { return !(s > 0 && s < 1); }

double ics_shadow1d_correct(const ics_light1d *l, double d, double x) {
  if (!l || bad_d(d) || isnan(x)) return NAN;
  if (d == 0) return x > 0 ? 1.0 : (x < 0 ? 0.0 : 0.5);
  return ics_light1d_sf(l, -x / d);
}

double ics_shadow1d_clt(const ics_light1d *l, double d, double d1, double x) {
  if (!l || bad_d(d) || !(d1 > 0) || isinf(d1) || isnan(x)) return NAN;
  double m = -d * ics_light1d_mean(l);
  double sd = sqrt(d * d1 * ics_light1d_var(l));
  if (sd == 0) return x > m ? 1.0 : (x < m ? 0.0 : 0.5);
  return ics_normal_cdf((x - m) / sd);
}

double ics_isoline_correct(const ics_light1d *l, double s, double d) {
  if (!l || bad_d(d) || bad_s(s)) return NAN;
  if (d == 0) return 0.0;
  return -d * ics_light1d_isf(l, s);
}

double ics_isoline_clt(const ics_light1d *l, double s, double d, double d1) {
  if (!l || bad_d(d) || bad_s(s) || !(d1 > 0) || isinf(d1)) return NAN;
  return -d * ics_light1d_mean(l) + ics_normal_quantile(s) * sqrt(d1 * ics_light1d_var(l) * d);
}

/* ---- iterated shadow ---- */

#include <stdlib.h>
#include <string.h>

ics_iter1d_opts ics_iter1d_opts_default(void) {
  ics_iter1d_opts o;
  memset(&o, 0, sizeof o);
  o.member = ICS_KERNEL_DIRAC;
  o.ppsd = 64;
  o.compensate = ICS_COMP_NONNEG;
  return o;
}

void ics_iter1d_free(ics_iter1d *it) {
  if (!it) return;
  free(it->r);
  it->r = NULL;
  it->n = 0;
}

/* the grid and class of ics_shadow1d_iterate, without allocating anything */
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
  ics_status mst = ics_kernel_map_1d(mu, var, e, d1, &kmean, &kvar);
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

ics_status ics_shadow1d_iterate_cost(const ics_light1d *l, double d, double d1, double e,
                                     const ics_iter1d_opts *opts, double *h, double *nodes,
                                     double *work) {
  if (!l) return ICS_ERR_INVALID_ARG;
  ics_iter1d_opts o = opts ? *opts : ics_iter1d_opts_default();
  iter_plan p;
  ics_status st = plan_iter(l, d, d1, e, &o, &p);
  if (st != ICS_OK) return st;
  if (h) *h = p.h;
  if (nodes) *nodes = (double)p.n;
  double nt, span; /* generated taps per step and their spread (pixels) */
  if (o.skew) {
    nt = ICS_CLT_SKEW_TAPS;
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
  if (work) *work = (double)p.steps * ((double)p.n * nd + ICS_WORK_COMP_PASSES * nt);
  return ICS_OK;
}

ics_status ics_shadow1d_iterate(const ics_light1d *l, double d, double d1, double e,
                                const ics_iter1d_opts *opts, ics_iter1d *out) {
  if (!l || !out) return ICS_ERR_INVALID_ARG;
  memset(out, 0, sizeof *out);
  ics_iter1d_opts o = opts ? *opts : ics_iter1d_opts_default();
  iter_plan p;
  ics_status pst = plan_iter(l, d, d1, e, &o, &p);
  if (pst != ICS_OK) return pst;
  int steps = p.steps;
  double kmean = p.kmean, kvar = p.kvar, h = p.h;
  size_t il = p.il, n = p.n;
  out->r = malloc(n * sizeof *out->r);
  if (!out->r) return ICS_ERR_NOMEM;
  out->n = n;
  out->h = h;
  out->x0 = (0.5 - (double)il) * h; /* node il is at +h/2: the edge is between nodes */
  for (size_t i = 0; i < n; i++) out->r[i] = i >= il ? 1.0 : 0.0;
  out->steps = steps;
  out->kmean_px = kmean / h;
  out->kvar_px = kvar / (h * h);
  if (steps == 0) return ICS_OK;
  if (!o.no_edge_comp) out->kvar_px -= 1.0 / (12.0 * steps);
  if (out->kvar_px < 0) out->kvar_px = 0;
  ics_kernel1d k;
  ics_status st;
  if (o.skew) {
    ics_tap1d taps[ICS_CLT_SKEW_TAPS];
    double *tmp = malloc(n * sizeof *tmp);
    if (!tmp) {
      ics_iter1d_free(out);
      return ICS_ERR_NOMEM;
    }
    st = ics_clt_skew_taps(out->kmean_px, out->kvar_px, taps);
    out->max_taps = ICS_CLT_SKEW_TAPS;
    ics_conv_opts co = ics_conv_opts_default();
    co.boundary = ICS_BOUNDARY_CLAMP;
    co.compensate = o.compensate;
    for (int i = 0; st == ICS_OK && i < steps; i++) {
      st = ics_conv1d_step(out->r, tmp, n, taps, ICS_CLT_SKEW_TAPS, &co);
      memcpy(out->r, tmp, n * sizeof *tmp);
    }
    out->stats.steps = steps;
    free(tmp);
    if (st != ICS_OK) ics_iter1d_free(out);
    return st;
  }
  st = ics_kernel1d_init(&k, o.member, out->kmean_px, out->kvar_px);
  if (st == ICS_OK) {
    k.nsamples = o.nsamples;
    k.param = o.param;
    k.seed = o.seed;
    ics_schedule1d sch = {&k, 1};
    out->max_taps = ics_schedule1d_max_taps(&sch);
    ics_conv_opts co = ics_conv_opts_default();
    co.boundary = ICS_BOUNDARY_CLAMP;
    co.compensate = o.compensate;
    st = ics_conv1d_run(out->r, n, &sch, 0, steps, &co, &out->stats);
  }
  if (st != ICS_OK) ics_iter1d_free(out);
  return st;
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
  if (!it || !it->r || bad_s(s)) return NAN;
  for (size_t i = 1; i < it->n; i++) {
    if (it->r[i] >= s && it->r[i - 1] < s) {
      double f = (s - it->r[i - 1]) / (it->r[i] - it->r[i - 1]);
      return it->x0 + ((double)(i - 1) + f) * it->h;
    }
  }
  return NAN;
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
  ics_iter1d_opts o = opts ? *opts : ics_iter1d_opts_default();
  ics_iter1d a, b;
  ics_status st = ics_shadow1d_iterate(l, d, d1, e, &o, &a);
  if (st != ICS_OK) return st;
  o.h = a.h / 2;
  st = ics_shadow1d_iterate(l, d, d1, e, &o, &b);
  if (st != ICS_OK) {
    ics_iter1d_free(&a);
    return st;
  }
  double xa = ics_iter1d_isoline(&a, s), xb = ics_iter1d_isoline(&b, s);
  ics_iter1d_free(&a);
  ics_iter1d_free(&b);
  if (x) *x = xb;
  if (disc_err) *disc_err = fabs(xa - xb);
  return (isnan(xa) || isnan(xb)) ? ICS_ERR_RANGE : ICS_OK;
}

/* ---- CLT convergence ---- */

#include <time.h>

ics_status ics_clt_member_gen(void *ctx, uint64_t step, double scale, ics_tap1d *taps, int cap,
                              int *ntaps) {
  ics_kernel1d k = *(const ics_kernel1d *)ctx;
  k.cls.mean *= scale;
  k.cls.var *= scale * scale;
  if (k.member == ICS_KERNEL_STOCH_DIRAC) k.param = (k.param > 0 ? k.param : 1.0) * scale;
  return ics_kernel1d_taps(&k, step, taps, cap, ntaps);
}

ics_status ics_clt_skew_taps(double mean, double var, ics_tap1d taps[ICS_CLT_SKEW_TAPS]) {
  if (isnan(mean) || isnan(var)) return ICS_ERR_NAN;
  if (isinf(mean) || isinf(var)) return ICS_ERR_INFINITE;
  if (var < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  double w[ICS_CLT_SKEW_TAPS], sw = 0, m = 0, v = 0;
  for (int j = 0; j < ICS_CLT_SKEW_TAPS; j++) sw += w[j] = exp(-j / 4.0);
  for (int j = 0; j < ICS_CLT_SKEW_TAPS; j++) m += (w[j] /= sw) * j;
  for (int j = 0; j < ICS_CLT_SKEW_TAPS; j++) v += w[j] * (j - m) * (j - m);
  double sc = sqrt(var / v);
  for (int j = 0; j < ICS_CLT_SKEW_TAPS; j++) {
    taps[j].x = mean + sc * (j - m);
    taps[j].w = w[j];
  }
  return ICS_OK;
}

ics_status ics_clt_fixed_gen(void *ctx, uint64_t step, double scale, ics_tap1d *taps, int cap,
                             int *ntaps) {
  (void)step;
  const ics_clt_fixed *f = ctx;
  if (cap < f->ntaps) return ICS_ERR_SIZE;
  for (int j = 0; j < f->ntaps; j++) {
    taps[j].x = f->taps[j].x * scale;
    taps[j].w = f->taps[j].w;
  }
  *ntaps = f->ntaps;
  return ICS_OK;
}

/* the grid of clt_run: nodes il left of the edge, n in all; 0 when it exceeds 2^24 nodes */
static int clt_grid(double mean, double var, int nmax, double scale, size_t *il, size_t *n) {
  double sd = sqrt(nmax * var * scale * scale);
  double lo = fmin(0.0, nmax * mean * scale) - 14 * sd - 64 * scale;
  double hi = fmax(0.0, nmax * mean * scale) + 14 * sd + 64 * scale;
  if (!(ceil(-lo) + ceil(hi) <= (double)((size_t)1 << 24))) return 0;
  *il = (size_t)ceil(-lo);
  *n = *il + (size_t)ceil(hi);
  return 1;
}

/* one run on a grid refined by `scale`; err[k][i] (if errs) gets the error profile at the
 * base grid's nodes i */
static ics_status clt_run(ics_clt_gen gen, void *ctx, double mean, double var, const int *steps,
                          int nsteps, ics_comp_mode comp, double scale, size_t nb, double xb0,
                          double **errs, ics_clt_point *out) {
  int nmax = steps[nsteps - 1];
  size_t il, n;
  if (!clt_grid(mean, var, nmax, scale, &il, &n)) return ICS_ERR_SIZE;
  double *buf = malloc(n * sizeof *buf), *tmp = malloc(n * sizeof *tmp);
  int cap = ICS_KERNEL_MAX_TAPS;
  ics_tap1d *taps = malloc((size_t)cap * sizeof *taps);
  ics_tap1d *dt = malloc((size_t)(2 * cap + 3) * sizeof *dt);
  ics_status st = ICS_OK;
  if (!buf || !tmp || !taps || !dt) st = ICS_ERR_NOMEM;
  double x0 = 0.5 - (double)il; /* node i at x0 + i (fine pixels) */
  ics_conv_opts co = ics_conv_opts_default();
  co.boundary = ICS_BOUNDARY_CLAMP;
  co.compensate = ICS_COMP_NONE; /* we hand the engine already compensated integer taps */
  double cost = 0, rmean = 0, rvar = 0;
  clock_t t0 = clock();
  int k = 0;
  if (st == ICS_OK)
    for (size_t i = 0; i < n; i++) buf[i] = i >= il ? 1.0 : 0.0;
  for (int s = 1; st == ICS_OK && s <= nmax; s++) {
    int nt = 0, nd = 0;
    st = gen(ctx, (uint64_t)(s - 1), scale, taps, cap, &nt);
    if (st != ICS_OK) break;
    st = ics_taps1d_compensate(taps, nt, comp, dt, 2 * cap + 3, &nd, NULL);
    if (st != ICS_OK) break;
    st = ics_conv1d_step(buf, tmp, n, dt, nd, &co);
    if (st != ICS_OK) break;
    double *sw = buf;
    buf = tmp;
    tmp = sw;
    cost += nd;
    {
      double ws, tm, tv;
      ics_taps1d_moments(dt, nd, &ws, &tm, &tv);
      rmean += tm;
      rvar += tv;
    }
    if (s == steps[k]) {
      double secs = (double)(clock() - t0) / CLOCKS_PER_SEC;
      double m = s * mean * scale, sdv = sqrt(s * var * scale * scale + 1.0 / 12.0);
      double worst = 0, worst_r = 0, sdr = sqrt(rvar + 1.0 / 12.0);
      for (size_t i = 0; i < n; i++) {
        double x = x0 + (double)i;
        double e = buf[i] - ics_normal_cdf((x - m) / sdv);
        double er = buf[i] - ics_normal_cdf((x - rmean) / sdr);
        if (fabs(e) > worst) worst = fabs(e);
        if (fabs(er) > worst_r) worst_r = fabs(er);
      }
      if (out) {
        out[k].steps = s;
        out[k].sup_err = worst;
        out[k].sup_err_realized = worst_r;
        out[k].cost = cost;
        out[k].seconds = secs;
      }
      if (errs) /* profile at the base nodes x = xb0 + i (base px) = scale * that (fine px) */
        for (size_t i = 0; i < nb; i++) {
          double xf = (xb0 + (double)i) * scale;
          double t = xf - x0;
          double r;
          if (t <= 0)
            r = buf[0];
          else if (t >= (double)(n - 1))
            r = buf[n - 1];
          else {
            size_t j = (size_t)t;
            double f = t - (double)j;
            r = buf[j] + f * (buf[j + 1] - buf[j]);
          }
          errs[k][i] = r - ics_normal_cdf((xf - m) / sdv);
        }
      k++;
    }
  }
  free(buf);
  free(tmp);
  free(taps);
  free(dt);
  return st;
}

static ics_status clt_check(ics_clt_gen gen, double mean, double var, const int *steps,
                            int nsteps, int refine) {
  if (!gen || !steps || nsteps <= 0) return ICS_ERR_INVALID_ARG;
  if (isnan(mean) || isnan(var)) return ICS_ERR_NAN;
  if (isinf(mean) || isinf(var)) return ICS_ERR_INFINITE;
  if (var < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  for (int k = 0; k < nsteps; k++)
    if (steps[k] < 1 || steps[k] > 1000000 || (k && steps[k] <= steps[k - 1])) return ICS_ERR_RANGE;
  /* every grid (base, 2x finer, the comparison nodes) must fit before anything is allocated */
  size_t il, n;
  int nmax = steps[nsteps - 1];
  if (!clt_grid(mean, var, nmax, 1.0, &il, &n)) return ICS_ERR_SIZE;
  if (refine && !clt_grid(mean, var, nmax, 2.0, &il, &n)) return ICS_ERR_SIZE;
  return ICS_OK;
}

ics_status ics_clt_cost(ics_clt_gen gen, void *ctx, double mean, double var, const int *steps,
                        int nsteps, ics_comp_mode comp, int refine, double *nodes, double *work) {
  ics_status st = clt_check(gen, mean, var, steps, nsteps, refine);
  if (st != ICS_OK) return st;
  int nmax = steps[nsteps - 1], cap = ICS_KERNEL_MAX_TAPS;
  ics_tap1d *taps = malloc((size_t)cap * sizeof *taps);
  ics_tap1d *dt = malloc((size_t)(2 * (size_t)cap + 3) * sizeof *dt);
  double w = 0, nn = 0;
  if (!taps || !dt) st = ICS_ERR_NOMEM;
  for (int r = 0; st == ICS_OK && r <= (refine ? 1 : 0); r++) {
    double scale = r ? 2.0 : 1.0;
    size_t il = 0, n = 0;
    int nt = 0, nd = 0;
    clt_grid(mean, var, nmax, scale, &il, &n);
    st = gen(ctx, 0, scale, taps, cap, &nt);
    if (st == ICS_OK) st = ics_taps1d_compensate(taps, nt, comp, dt, 2 * cap + 3, &nd, NULL);
    w += (double)nmax * ((double)n * nd + ICS_WORK_COMP_PASSES * (double)nt);
    if (!r) nn = (double)n;
  }
  free(taps);
  free(dt);
  if (st != ICS_OK) return st;
  if (nodes) *nodes = nn;
  if (work) *work = w;
  return ICS_OK;
}

ics_status ics_clt_measure(ics_clt_gen gen, void *ctx, double mean, double var, const int *steps,
                           int nsteps, ics_comp_mode comp, int refine, ics_clt_point *out) {
  if (!out) return ICS_ERR_INVALID_ARG;
  ics_status cst = clt_check(gen, mean, var, steps, nsteps, refine);
  if (cst != ICS_OK) return cst;
  if (!refine) {
    for (int k = 0; k < nsteps; k++) out[k].disc_err = NAN;
    return clt_run(gen, ctx, mean, var, steps, nsteps, comp, 1.0, 0, 0, NULL, out);
  }
  /* base grid nodes used for the comparison: +-14 sd around the path */
  int nmax = steps[nsteps - 1];
  double sd = sqrt(nmax * var);
  double lo = fmin(0.0, nmax * mean) - 14 * sd - 8, hi = fmax(0.0, nmax * mean) + 14 * sd + 8;
  double xb0 = floor(lo) + 0.5;
  size_t nb = (size_t)(hi - lo) + 2;
  double **e1 = calloc((size_t)nsteps, sizeof *e1), **e2 = calloc((size_t)nsteps, sizeof *e2);
  ics_status st = (e1 && e2) ? ICS_OK : ICS_ERR_NOMEM;
  for (int k = 0; st == ICS_OK && k < nsteps; k++) {
    e1[k] = malloc(nb * sizeof **e1);
    e2[k] = malloc(nb * sizeof **e2);
    if (!e1[k] || !e2[k]) st = ICS_ERR_NOMEM;
  }
  if (st == ICS_OK) st = clt_run(gen, ctx, mean, var, steps, nsteps, comp, 1.0, nb, xb0, e1, out);
  if (st == ICS_OK) st = clt_run(gen, ctx, mean, var, steps, nsteps, comp, 2.0, nb, xb0, e2, NULL);
  for (int k = 0; st == ICS_OK && k < nsteps; k++) {
    double w = 0;
    for (size_t i = 0; i < nb; i++) w = fmax(w, fabs(e1[k][i] - e2[k][i]));
    out[k].disc_err = w;
  }
  for (int k = 0; k < nsteps; k++) {
    if (e1) free(e1[k]);
    if (e2) free(e2[k]);
  }
  free(e1);
  free(e2);
  return st;
}

double ics_clt_rate(const ics_clt_point *p, int np, int nmin) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (int k = 0; k < np; k++) {
    if (p[k].steps < nmin || !(p[k].sup_err > 0)) continue;
    double x = log((double)p[k].steps), y = log(p[k].sup_err);
    sx += x, sy += y, sxx += x * x, sxy += x * y, m++;
  }
  if (m < 2) return NAN;
  return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}
