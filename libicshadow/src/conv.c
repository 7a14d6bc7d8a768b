/* conv.c — iterative convolution engine, CPU reference path (conventions in icshadow/conv.h).
 *
 * A step turns the taps into integer taps (floor/fraction split, then linear/bilinear weights,
 * or the variance-compensated integer taps), then sums shifted copies of the input:
 * out[x] = sum_j v_j in[x - k_j], reads outside the buffer clamped to the edge or a constant.
 * 1D in double; 2D float images accumulated per row in double, rounded once per pixel.
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/conv.h"
#include "taps_check.h"

/* ICS_COMP_INTEGER: the taps of step `step` moved so that their mean is the whole-pixel shift
 * round((step + 1) m) - round(step m) (m = their mean; round half up), into out[0 .. n-1] */
static ics_status integer_shift1d(const ics_tap1d *in, int n, uint64_t step, ics_tap1d *out) {
  double W, m, V;
  ics_taps1d_moments(in, n, &W, &m, &V);
  if (!(W > 0)) return ICS_ERR_RANGE;
  double i = (double)step;
  double shift = floor((i + 1) * m + 0.5) - floor(i * m + 0.5);
  for (int j = 0; j < n; j++) out[j] = (ics_tap1d){in[j].x - m + shift, in[j].w};
  return ICS_OK;
}

static ics_status prepare1d(const ics_tap1d *taps, int ntaps, const ics_conv_opts *o,
                            uint64_t step, ics_tap1d **out, int *nout, double *resid) {
  size_t cap = 2 * (size_t)(ntaps > 0 ? ntaps : 1) + 3; /* in size_t: no int overflow */
  if (cap > INT_MAX) return ICS_ERR_SIZE;
  ics_tap1d *t = malloc(sizeof *t * cap);
  if (!t) return ICS_ERR_NOMEM;
  ics_comp_mode mode = o->compensate;
  ics_tap1d *sh = NULL;
  if (mode == ICS_COMP_INTEGER) {
    ics_status cst = ics_taps1d_check(taps, ntaps);
    sh = cst == ICS_OK ? malloc(sizeof *sh * (size_t)ntaps) : NULL;
    if (cst == ICS_OK && !sh) cst = ICS_ERR_NOMEM;
    if (cst == ICS_OK) cst = integer_shift1d(taps, ntaps, step, sh);
    if (cst != ICS_OK) {
      free(sh);
      free(t);
      return cst;
    }
    taps = sh;
    mode = ICS_COMP_NONNEG; /* integer mean: f(1 - f) = 0, so the variance is always exact */
  }
  ics_status st = ics_taps1d_compensate(taps, ntaps, mode, t, (int)cap, nout, resid);
  free(sh);
  if (st != ICS_OK) {
    free(t);
    return st;
  }
  *out = t;
  return ICS_OK;
}

static ics_status check_opts(const ics_conv_opts *o) {
  if (o->boundary != ICS_BOUNDARY_CLAMP && o->boundary != ICS_BOUNDARY_CONSTANT)
    return ICS_ERR_RANGE;
  if (isnan(o->constant)) return ICS_ERR_NAN;
  if (isinf(o->constant)) return ICS_ERR_INFINITE; /* inf x 0-weight taps would give NaN */
  if (o->compensate != ICS_COMP_NONE && o->compensate != ICS_COMP_NONNEG &&
      o->compensate != ICS_COMP_SIGNED && o->compensate != ICS_COMP_INTEGER)
    return ICS_ERR_RANGE;
  return ICS_OK;
}

static void apply1d(const double *in, double *out, size_t n, const ics_tap1d *t, int nt,
                    const ics_conv_opts *o) {
  for (size_t x = 0; x < n; x++) out[x] = 0;
  long long N = (long long)n;
  for (int j = 0; j < nt; j++) {
    long long k = (long long)t[j].x;
    double w = t[j].w;
    /* valid x: 0 <= x - k < N */
    long long lo = k < 0 ? 0 : k, hi = k + N < N ? k + N : N;
    if (lo > N) lo = N;
    if (hi < 0) hi = 0;
    if (hi < lo) hi = lo;
    double left = o->boundary == ICS_BOUNDARY_CLAMP ? in[0] : o->constant;
    double right = o->boundary == ICS_BOUNDARY_CLAMP ? in[n - 1] : o->constant;
    for (long long x = 0; x < lo; x++) out[x] += w * (x - k < 0 ? left : right);
    for (long long x = lo; x < hi; x++) out[x] += w * in[x - k];
    for (long long x = hi; x < N; x++) out[x] += w * (x - k < 0 ? left : right);
  }
}

ics_status ics_conv1d_step(const double *in, double *out, size_t n, const ics_tap1d *taps,
                           int ntaps, const ics_conv_opts *opts) {
  ics_conv_opts o = opts ? *opts : (ics_conv_opts){0}; /* zero: the defaults */
  if (!in || !out || !taps || ntaps <= 0 || in == out) return ICS_ERR_INVALID_ARG;
  if (n == 0 || n > ICS_CONV_MAX_LEN) return ICS_ERR_SIZE;
  ics_status st = check_opts(&o);
  if (st != ICS_OK) return st;
  ics_tap1d *t;
  int nt;
  st = prepare1d(taps, ntaps, &o, 0, &t, &nt, NULL);
  if (st != ICS_OK) return st;
  apply1d(in, out, n, t, nt, &o);
  free(t);
  return ICS_OK;
}

static void apply2d(const float *in, float *out, size_t w, size_t h, const ics_tap2d *t, int nt,
                    const ics_conv_opts *o, double *row) {
  long long W = (long long)w, H = (long long)h;
  for (long long y = 0; y < H; y++) {
    for (long long x = 0; x < W; x++) row[x] = 0;
    for (int j = 0; j < nt; j++) {
      long long kx = (long long)t[j].x, ky = (long long)t[j].y;
      double wt = t[j].w;
      long long sy = y - ky;
      const float *src = NULL;
      if (sy < 0 || sy >= H) {
        if (o->boundary == ICS_BOUNDARY_CONSTANT) {
          for (long long x = 0; x < W; x++) row[x] += wt * o->constant;
          continue;
        }
        sy = sy < 0 ? 0 : H - 1;
      }
      src = in + sy * W;
      double left = o->boundary == ICS_BOUNDARY_CLAMP ? src[0] : o->constant;
      double right = o->boundary == ICS_BOUNDARY_CLAMP ? src[W - 1] : o->constant;
      long long lo = kx < 0 ? 0 : kx, hi = kx + W < W ? kx + W : W;
      if (lo > W) lo = W;
      if (hi < 0) hi = 0;
      if (hi < lo) hi = lo;
      for (long long x = 0; x < lo; x++) row[x] += wt * (x - kx < 0 ? left : right);
      for (long long x = lo; x < hi; x++) row[x] += wt * src[x - kx];
      for (long long x = hi; x < W; x++) row[x] += wt * (x - kx < 0 ? left : right);
    }
    for (long long x = 0; x < W; x++) out[y * W + x] = (float)row[x];
  }
}

static ics_status prepare2d(const ics_tap2d *taps, int ntaps, const ics_conv_opts *o,
                            ics_tap2d **out, int *nout, double *resid) {
  size_t cap = 4 * (size_t)(ntaps > 0 ? ntaps : 1) + 9; /* in size_t: no int overflow */
  if (cap > INT_MAX) return ICS_ERR_SIZE;
  ics_tap2d *t = malloc(sizeof *t * cap);
  if (!t) return ICS_ERR_NOMEM;
  ics_status st = ics_taps2d_compensate(taps, ntaps, o->compensate, t, (int)cap, nout, resid);
  if (st != ICS_OK) {
    free(t);
    return st;
  }
  *out = t;
  return ICS_OK;
}

static int bad_size2d(size_t w, size_t h) {
  return w == 0 || h == 0 || w > ICS_CONV_MAX_LEN || h > ICS_CONV_MAX_LEN / w;
}

ics_status ics_conv2d_step(const float *in, float *out, size_t w, size_t h, const ics_tap2d *taps,
                           int ntaps, const ics_conv_opts *opts) {
  ics_conv_opts o = opts ? *opts : (ics_conv_opts){0}; /* zero: the defaults */
  if (!in || !out || !taps || ntaps <= 0 || in == out) return ICS_ERR_INVALID_ARG;
  if (bad_size2d(w, h)) return ICS_ERR_SIZE;
  ics_status st = check_opts(&o);
  if (st == ICS_OK && o.compensate == ICS_COMP_INTEGER) return ICS_ERR_UNSUPPORTED; /* 1D only */
  if (st != ICS_OK) return st;
  ics_tap2d *t;
  int nt;
  st = prepare2d(taps, ntaps, &o, &t, &nt, NULL);
  if (st != ICS_OK) return st;
  double *row = malloc(sizeof *row * w);
  if (!row) {
    free(t);
    return ICS_ERR_NOMEM;
  }
  apply2d(in, out, w, h, t, nt, &o, row);
  free(row);
  free(t);
  return ICS_OK;
}

ics_status ics_conv1d_run(double *buf, size_t n, const ics_schedule1d *s, uint64_t first_step,
                          int nsteps, const ics_conv_opts *opts, ics_conv_stats *stats) {
  ics_conv_opts o = opts ? *opts : (ics_conv_opts){0}; /* zero: the defaults */
  if (!buf || !s || nsteps < 0) return ICS_ERR_INVALID_ARG;
  if (n == 0 || n > ICS_CONV_MAX_LEN) return ICS_ERR_SIZE;
  ics_status st = check_opts(&o);
  if (st != ICS_OK) return st;
  int cap = ics_schedule1d_max_taps(s);
  if (cap <= 0) { /* name the first invalid member's problem */
    if (!s->members || s->nmembers <= 0) return ICS_ERR_INVALID_ARG;
    for (int i = 0; i < s->nmembers; i++) {
      ics_tap1d probe[1];
      int np;
      ics_status e = ics_kernel1d_taps(&s->members[i], 0, probe, 0, &np);
      if (e != ICS_OK && e != ICS_ERR_SIZE) return e;
    }
    return ICS_ERR_INVALID_ARG;
  }
  if (stats) memset(stats, 0, sizeof *stats);
  ics_tap1d *taps = malloc(sizeof *taps * (size_t)cap);
  double *tmp = malloc(sizeof *tmp * n);
  if (!taps || !tmp) {
    free(taps);
    free(tmp);
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < nsteps && st == ICS_OK; k++) {
    int nt;
    st = ics_schedule1d_taps(s, first_step + (uint64_t)k, taps, cap, &nt);
    if (st != ICS_OK) break;
    ics_tap1d *d;
    int nd;
    double resid;
    st = prepare1d(taps, nt, &o, first_step + (uint64_t)k, &d, &nd, &resid);
    if (st != ICS_OK) break;
    apply1d(buf, tmp, n, d, nd, &o);
    free(d);
    memcpy(buf, tmp, sizeof *tmp * n);
    if (stats) {
      double v;
      ics_taps1d_moments(taps, nt, NULL, NULL, &v);
      stats->steps++;
      stats->kernel_var[0] += v;
      if (o.compensate == ICS_COMP_NONE)
        stats->interp_var[0] += resid;
      else
        stats->residual[0] += resid;
    }
  }
  free(taps);
  free(tmp);
  return st;
}

ics_status ics_conv2d_run(float *buf, size_t w, size_t h, const ics_schedule2d *s,
                          uint64_t first_step, int nsteps, const ics_conv_opts *opts,
                          ics_conv_stats *stats) {
  ics_conv_opts o = opts ? *opts : (ics_conv_opts){0}; /* zero: the defaults */
  if (!buf || !s || nsteps < 0) return ICS_ERR_INVALID_ARG;
  if (bad_size2d(w, h)) return ICS_ERR_SIZE;
  ics_status st = check_opts(&o);
  if (st == ICS_OK && o.compensate == ICS_COMP_INTEGER) return ICS_ERR_UNSUPPORTED; /* 1D only */
  if (st != ICS_OK) return st;
  int cap = ics_schedule2d_max_taps(s);
  if (cap <= 0) { /* name the first invalid member's problem */
    if (!s->members || s->nmembers <= 0) return ICS_ERR_INVALID_ARG;
    for (int i = 0; i < s->nmembers; i++) {
      ics_tap2d probe[1];
      int np;
      ics_status e = ics_kernel2d_taps(&s->members[i], 0, probe, 0, &np);
      if (e != ICS_OK && e != ICS_ERR_SIZE) return e;
    }
    return ICS_ERR_INVALID_ARG;
  }
  if (stats) memset(stats, 0, sizeof *stats);
  ics_tap2d *taps = malloc(sizeof *taps * (size_t)cap);
  float *tmp = malloc(sizeof *tmp * w * h);
  double *row = malloc(sizeof *row * w);
  if (!taps || !tmp || !row) {
    free(taps);
    free(tmp);
    free(row);
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < nsteps && st == ICS_OK; k++) {
    int nt;
    st = ics_schedule2d_taps(s, first_step + (uint64_t)k, taps, cap, &nt);
    if (st != ICS_OK) break;
    ics_tap2d *d;
    int nd;
    double resid[3];
    st = prepare2d(taps, nt, &o, &d, &nd, resid);
    if (st != ICS_OK) break;
    apply2d(buf, tmp, w, h, d, nd, &o, row);
    free(d);
    memcpy(buf, tmp, sizeof *tmp * w * h);
    if (stats) {
      double c[3];
      ics_taps2d_moments(taps, nt, NULL, NULL, c);
      stats->steps++;
      stats->kernel_var[0] += c[0];
      stats->kernel_var[1] += c[2];
      if (o.compensate == ICS_COMP_NONE) {
        stats->interp_var[0] += resid[0];
        stats->interp_var[1] += resid[2];
      } else {
        stats->residual[0] += resid[0];
        stats->residual[1] += resid[2];
      }
    }
  }
  free(taps);
  free(tmp);
  free(row);
  return st;
}
