/* clt1d.c — CLT convergence of the 1D kernel members (see icshadow/clt1d.h): the step
 * generators, the run on a grid refined by `scale` with its sup errors and error profile, the
 * 2x finer comparison and the work model. */
#include "icshadow/clt1d.h"
#include "icshadow/normal.h"

#include <math.h>
#include <stdlib.h>
#include <time.h>

ics_status ics_clt1d_member_gen(void *ctx, uint64_t step, double scale, ics_tap1d *taps, int cap,
                                int *ntaps) {
  ics_kernel1d k = *(const ics_kernel1d *)ctx;
  k.cls.mean *= scale;
  k.cls.var *= scale * scale;
  if (k.member == ICS_KERNEL_STOCH_DIRAC) k.param = (k.param > 0 ? k.param : 1.0) * scale;
  return ics_kernel1d_taps(&k, step, taps, cap, ntaps);
}

ics_status ics_clt1d_skew_taps(double mean, double var, ics_tap1d taps[ICS_CLT1D_SKEW_TAPS]) {
  if (isnan(mean) || isnan(var)) return ICS_ERR_NAN;
  if (isinf(mean) || isinf(var)) return ICS_ERR_INFINITE;
  if (var < 0) return ICS_ERR_NEGATIVE_VARIANCE;
  double w[ICS_CLT1D_SKEW_TAPS], sw = 0, m = 0, v = 0;
  for (int j = 0; j < ICS_CLT1D_SKEW_TAPS; j++) sw += w[j] = exp(-j / 4.0);
  for (int j = 0; j < ICS_CLT1D_SKEW_TAPS; j++) m += (w[j] /= sw) * j;
  for (int j = 0; j < ICS_CLT1D_SKEW_TAPS; j++) v += w[j] * (j - m) * (j - m);
  double sc = sqrt(var / v);
  for (int j = 0; j < ICS_CLT1D_SKEW_TAPS; j++) {
    taps[j].x = mean + sc * (j - m);
    taps[j].w = w[j];
  }
  return ICS_OK;
}

ics_status ics_clt1d_fixed_gen(void *ctx, uint64_t step, double scale, ics_tap1d *taps, int cap,
                               int *ntaps) {
  (void)step;
  const ics_clt1d_fixed *f = ctx;
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
typedef struct {
  ics_clt_progress fn;
  void *ctx;
  long base, total; /* steps done before this run, steps in all runs */
} clt_progress_t;

static ics_status clt_run(ics_clt1d_gen gen, void *ctx, double mean, double var, const int *steps,
                          int nsteps, ics_comp_mode comp, double scale, size_t nb, double xb0,
                          double **errs, ics_clt_point *out, const clt_progress_t *pr) {
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
  ics_conv_opts co = {0};
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
    if (pr->fn) pr->fn(pr->ctx, pr->base + s, pr->total);
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

static ics_status clt_check(ics_clt1d_gen gen, double mean, double var, const int *steps,
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

ics_status ics_clt1d_cost(ics_clt1d_gen gen, void *ctx, double mean, double var, const int *steps,
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
    w += (double)nmax * ((double)n * nd + ICS_CONV_WORK_COMP_PASSES * (double)nt);
    if (!r) nn = (double)n;
  }
  free(taps);
  free(dt);
  if (st != ICS_OK) return st;
  if (nodes) *nodes = nn;
  if (work) *work = w;
  return ICS_OK;
}

ics_status ics_clt1d_measure(ics_clt1d_gen gen, void *ctx, double mean, double var,
                             const int *steps, int nsteps, ics_comp_mode comp, int refine,
                             ics_clt_point *out) {
  return ics_clt1d_measure_progress(gen, ctx, mean, var, steps, nsteps, comp, refine, out, NULL,
                                    NULL);
}

ics_status ics_clt1d_measure_progress(ics_clt1d_gen gen, void *ctx, double mean, double var,
                                      const int *steps, int nsteps, ics_comp_mode comp,
                                      int refine, ics_clt_point *out, ics_clt_progress progress,
                                      void *progress_ctx) {
  if (!out) return ICS_ERR_INVALID_ARG;
  ics_status cst = clt_check(gen, mean, var, steps, nsteps, refine);
  if (cst != ICS_OK) return cst;
  long last = steps[nsteps - 1];
  clt_progress_t pr = {progress, progress_ctx, 0, refine ? 2 * last : last};
  if (!refine) {
    for (int k = 0; k < nsteps; k++) out[k].disc_err = NAN;
    return clt_run(gen, ctx, mean, var, steps, nsteps, comp, 1.0, 0, 0, NULL, out, &pr);
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
  if (st == ICS_OK) st = clt_run(gen, ctx, mean, var, steps, nsteps, comp, 1.0, nb, xb0, e1, out, &pr);
  pr.base = last;
  if (st == ICS_OK) st = clt_run(gen, ctx, mean, var, steps, nsteps, comp, 2.0, nb, xb0, e2, NULL, &pr);
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
