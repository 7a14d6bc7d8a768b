/* sat.c — summed-area tables in 2D and 3D (icshadow/sat.h): allocation and the size, stride
 * and finiteness checks around the builders of sat_build.c, box sums and the continuous
 * (multilinear) integrals (precision after Hensley et al. 2005; the modes in sat_precision.c).
 *
 * ERROR BOUND (same number in icshadow/sat.h, docs/sat.md, tests/test_sat.c): each table entry
 * (x, y, z) is a recursive sum of depth <= x + y + z, so its error is <= gamma_n * (sum of
 * |terms|) (Higham, Accuracy and Stability, eq. 4.4); a box combines 2^dims entries in double:
 *   |box error| <= 2^dims * 1.01 * u * (x1 + y1 [+ z1] + 2^dims) * P,   P = sum |a - m| over
 *   the prefix box [0, x1) x [0, y1) [x [0, z1)],
 * u = 2^-24 for ICS_SAT_FLOAT and ICS_SAT_FLOAT_OFFSET (m = float(mean), the subtraction
 * a - m rounds once per cell: <= u P in total), u = 2^-44 = 16 u_f^2 for ICS_SAT_COMPENSATED
 * (double-float addition with float TwoSum errs by <= ~3.1 u_f^2 (|a| + |b|)), u = 2^-53 for
 * ICS_SAT_DOUBLE. The 1.01 covers gamma_n = n u / (1 - n u) for n u <= 0.0099.
 *
 * SPECIAL CASES: NaN / Inf data are refused (ICS_ERR_NAN / ICS_ERR_INFINITE), float sums that
 * overflow give ICS_ERR_RANGE: non-finite values propagate to the table's last row, which is
 * checked after the pass (no extra pass over the input);
 * empty or huge sizes ICS_ERR_SIZE; out-of-range boxes ICS_ERR_RANGE (or clamped: outside
 * cells are 0), inverted boxes ICS_ERR_INVALID_ARG. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/sat.h"
#include "clamp.h"
#include "sat_build.h"
#include "sat_limits.h"

struct ics_sat3d {
  size_t w, h, d;
  ics_sat_precision mode;
  double offset;
  float *f;      /* float table (FLOAT, FLOAT_OFFSET) or hi part (COMPENSATED) */
  float *lo;     /* COMPENSATED: lo part */
  double *dbl;   /* DOUBLE */
  void *scratch; /* row accumulators, x prefix block, previous-slice accumulator */
  int valid;     /* 0 after a failed rebuild */
};

struct ics_sat2d {
  struct ics_sat3d s;
};

ics_status ics_sat_check_size(size_t w, size_t h, size_t d, ics_sat_precision mode) {
  if ((unsigned)mode >= ICS_SAT_PRECISION_COUNT) return ICS_ERR_INVALID_ARG;
  if (w == 0 || h == 0 || d == 0) return ICS_ERR_SIZE;
  if (w > ((size_t)1 << 31) || h > ((size_t)1 << 31) || d > ((size_t)1 << 31))
    return ICS_ERR_SIZE;
  double cells = (double)w * (double)h * (double)d;
  if (cells > 2147483648.0) return ICS_ERR_SIZE;
  if (cells * (double)ics_sat_cell_bytes(mode) > (double)ICS_SAT_MAX_BYTES) return ICS_ERR_SIZE;
  return ICS_OK;
}

/* The offset of ICS_SAT_FLOAT_OFFSET: the float-rounded mean of an evenly spaced sample of
 * at most 65536 cells (any m keeps the error bound valid, since P is measured around m). */
static float sample_mean(const float *data, size_t w, size_t h, size_t d, size_t stride,
                         size_t sstride) {
  size_t n = w * h * d, step = n / 65536 + 1, cnt = 0;
  double acc = 0.0;
  for (size_t i = 0; i < n; i += step, cnt++) {
    size_t x = i % w, y = (i / w) % h, z = i / (w * h);
    acc += data[z * sstride + y * stride + x];
  }
  float m = (float)(acc / (double)cnt);
  return isfinite(m) ? m : 0.0f;
}

/* After a build: any NaN / Inf input or float overflow propagates into the last row of the
 * last slice (sums never turn a non-finite value finite), so checking w entries suffices.
 * On failure the input is scanned to name the cause. */
static ics_status classify_bad(const float *data, size_t w, size_t h, size_t d, size_t stride,
                               size_t sstride) {
  int inf = 0;
  for (size_t z = 0; z < d; z++)
    for (size_t y = 0; y < h; y++) {
      const float *row = data + z * sstride + y * stride;
      for (size_t x = 0; x < w; x++) {
        if (isnan(row[x])) return ICS_ERR_NAN;
        if (isinf(row[x])) inf = 1;
      }
    }
  return inf ? ICS_ERR_INFINITE : ICS_ERR_RANGE; /* finite data whose float sums overflow */
}

static ics_status sat3d_fill(struct ics_sat3d *s, const float *data, size_t stride,
                             size_t sstride) {
  size_t w = s->w, h = s->h, d = s->d;
  size_t last = ((d - 1) * h + (h - 1)) * w;
  int ok = 1;
  s->valid = 0;
  if (s->mode == ICS_SAT_DOUBLE) {
    ics_sat_build_double(s->dbl, data, w, h, d, stride, sstride, s->scratch);
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->dbl[last + x]) != 0;
  } else if (s->mode == ICS_SAT_COMPENSATED) {
    ics_sat_build_compensated(s->f, s->lo, data, w, h, d, stride, sstride, s->scratch);
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->f[last + x]) && isfinite(s->lo[last + x]);
  } else {
    float m = s->mode == ICS_SAT_FLOAT_OFFSET ? sample_mean(data, w, h, d, stride, sstride) : 0.0f;
    s->offset = m;
    ics_sat_build_float(s->f, data, w, h, d, stride, sstride, m, s->scratch);
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->f[last + x]) != 0;
  }
  if (!ok) return classify_bad(data, w, h, d, stride, sstride);
  s->valid = 1;
  return ICS_OK;
}

/* A row stride is usable when stride >= w and the input span (h - 1) * stride + w floats
 * neither overflows nor exceeds ICS_SAT_MAX_SPAN_BYTES (a larger span is a caller's error, not
 * an image: reading it would run off the buffer). 3D input is tightly packed (span = the cell
 * count, checked by ics_sat_check_size). */
static int stride_ok(size_t w, size_t h, size_t stride) {
  if (stride < w) return 0;
  if (h <= 1) return 1;
  size_t lim = ICS_SAT_MAX_SPAN_BYTES / sizeof(float);
  if (stride > (lim - w) / (h - 1)) return 0;
  return 1;
}

static ics_status sat3d_init(struct ics_sat3d *s, const float *data, size_t w, size_t h,
                             size_t d, size_t stride, size_t sstride, ics_sat_precision mode) {
  memset(s, 0, sizeof *s);
  ics_status st = ics_sat_check_size(w, h, d, mode);
  if (st != ICS_OK) return st;
  if (!data || !stride_ok(w, h, stride)) return ICS_ERR_INVALID_ARG;
  size_t n = w * h * d;
  s->w = w, s->h = h, s->d = d, s->mode = mode;
  if (mode == ICS_SAT_DOUBLE) {
    s->dbl = malloc(n * sizeof(double));
  } else if (mode == ICS_SAT_COMPENSATED) {
    s->f = malloc(n * sizeof(float));
    s->lo = malloc(n * sizeof(float));
  } else {
    s->f = malloc(n * sizeof(float));
  }
  s->scratch = malloc(ics_sat_scratch_bytes(mode, w, h, d));
  if (!s->scratch || (mode == ICS_SAT_DOUBLE ? !s->dbl : !s->f) ||
      (mode == ICS_SAT_COMPENSATED && !s->lo))
    return ICS_ERR_NOMEM; /* caller releases */
  return sat3d_fill(s, data, stride, sstride);
}

static void sat3d_release(struct ics_sat3d *s) {
  free(s->scratch);
  free(s->f);
  free(s->lo);
  free(s->dbl);
}

/* Inclusive entry at (x, y, z) (indices may be -1: 0). Offset not included. */
static inline double entry(const struct ics_sat3d *s, long x, long y, long z) {
  if (x < 0 || y < 0 || z < 0) return 0.0;
  size_t i = ((size_t)z * s->h + (size_t)y) * s->w + (size_t)x;
  switch (s->mode) {
  case ICS_SAT_DOUBLE: return s->dbl[i];
  case ICS_SAT_COMPENSATED: return (double)s->f[i] + (double)s->lo[i];
  default: return s->f[i];
  }
}

/* Box [x0, x1) x [y0, y1) x [z0, z1) with 0 <= lo <= hi <= n (checked by the callers). */
static double box_raw(const struct ics_sat3d *s, long x0, long y0, long z0, long x1, long y1,
                      long z1) {
  if (x0 == x1 || y0 == y1 || z0 == z1) return 0.0;
  double v = entry(s, x1 - 1, y1 - 1, z1 - 1) - entry(s, x0 - 1, y1 - 1, z1 - 1) -
             entry(s, x1 - 1, y0 - 1, z1 - 1) + entry(s, x0 - 1, y0 - 1, z1 - 1);
  if (s->d > 1)
    v -= entry(s, x1 - 1, y1 - 1, z0 - 1) - entry(s, x0 - 1, y1 - 1, z0 - 1) -
         entry(s, x1 - 1, y0 - 1, z0 - 1) + entry(s, x0 - 1, y0 - 1, z0 - 1);
  if (s->offset != 0.0) v += s->offset * ((double)(x1 - x0) * (double)(y1 - y0) * (double)(z1 - z0));
  return v;
}

static ics_status box3(const struct ics_sat3d *s, long x0, long y0, long z0, long x1, long y1,
                       long z1, int clamp, double *sum) {
  if (!s || !sum || !s->valid) return ICS_ERR_INVALID_ARG;
  if (x1 < x0 || y1 < y0 || z1 < z0) return ICS_ERR_INVALID_ARG;
  long w = (long)s->w, h = (long)s->h, d = (long)s->d;
  if (clamp) {
    x0 = ics_clampl(x0, 0, w), x1 = ics_clampl(x1, 0, w);
    y0 = ics_clampl(y0, 0, h), y1 = ics_clampl(y1, 0, h);
    z0 = ics_clampl(z0, 0, d), z1 = ics_clampl(z1, 0, d);
  } else if (x0 < 0 || y0 < 0 || z0 < 0 || x1 > w || y1 > h || z1 > d) {
    return ICS_ERR_RANGE;
  }
  *sum = box_raw(s, x0, y0, z0, x1, y1, z1);
  return ICS_OK;
}

/* F(X, Y, Z) = integral over [0, X] x [0, Y] x [0, Z] (already clamped to the table): the
 * multilinear interpolation of G(i, j, k) = S(i-1, j-1, k-1) on the integer lattice. */
static double prefix_integral(const struct ics_sat3d *s, double X, double Y, double Z) {
  double c[3] = {X, Y, Z};
  long i0[3];
  double f[3];
  long n[3] = {(long)s->w, (long)s->h, (long)s->d};
  for (int a = 0; a < 3; a++) {
    double fl = floor(c[a]);
    i0[a] = (long)fl;
    f[a] = c[a] - fl;
    if (i0[a] >= n[a]) i0[a] = n[a], f[a] = 0.0;
  }
  double v = 0.0;
  for (int k = 0; k < 2; k++) {
    double wz = k ? f[2] : 1.0 - f[2];
    if (wz == 0.0) continue;
    for (int j = 0; j < 2; j++) {
      double wy = j ? f[1] : 1.0 - f[1];
      if (wy == 0.0) continue;
      for (int i = 0; i < 2; i++) {
        double wx = i ? f[0] : 1.0 - f[0];
        if (wx == 0.0) continue;
        v += wx * wy * wz * entry(s, i0[0] + i - 1, i0[1] + j - 1, i0[2] + k - 1);
      }
    }
  }
  if (s->offset != 0.0) v += s->offset * X * Y * Z;
  return v;
}

static ics_status integral3(const struct ics_sat3d *s, const double lo[3], const double hi[3],
                            double *sum) {
  if (!s || !lo || !hi || !sum || !s->valid) return ICS_ERR_INVALID_ARG;
  double n[3] = {(double)s->w, (double)s->h, (double)s->d};
  double a[3], b[3];
  for (int k = 0; k < 3; k++) {
    if (isnan(lo[k]) || isnan(hi[k])) return ICS_ERR_NAN;
    if (hi[k] < lo[k]) return ICS_ERR_INVALID_ARG;
    a[k] = ics_clampd(lo[k], 0.0, n[k]);
    b[k] = ics_clampd(hi[k], 0.0, n[k]);
    if (a[k] == b[k]) {
      *sum = 0.0;
      return ICS_OK;
    }
  }
  double v = 0.0;
  for (int m = 0; m < 8; m++) {
    double X = m & 1 ? b[0] : a[0], Y = m & 2 ? b[1] : a[1], Z = m & 4 ? b[2] : a[2];
    int sign = ((m & 1) ? 0 : 1) + ((m & 2) ? 0 : 1) + ((m & 4) ? 0 : 1);
    if (X == 0.0 || Y == 0.0 || Z == 0.0) continue;
    double p = prefix_integral(s, X, Y, Z);
    v += (sign & 1) ? -p : p;
  }
  *sum = v;
  return ICS_OK;
}

/* ---- 2D API --------------------------------------------------------------------------- */
ics_status ics_sat2d_create(ics_sat2d **out, const float *data, size_t width, size_t height,
                            size_t stride, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  ics_sat2d *s = malloc(sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  ics_status st = sat3d_init(&s->s, data, width, height, 1, stride, 0, mode);
  if (st != ICS_OK) {
    sat3d_release(&s->s);
    free(s);
    return st;
  }
  *out = s;
  return ICS_OK;
}

ics_status ics_sat2d_rebuild(ics_sat2d *sat, const float *data, size_t stride) {
  if (!sat || !data || !stride_ok(sat->s.w, sat->s.h, stride)) return ICS_ERR_INVALID_ARG;
  return sat3d_fill(&sat->s, data, stride, 0);
}

void ics_sat2d_destroy(ics_sat2d *sat) {
  if (!sat) return;
  sat3d_release(&sat->s);
  free(sat);
}

void ics_sat2d_size(const ics_sat2d *sat, size_t *width, size_t *height) {
  if (width) *width = sat ? sat->s.w : 0;
  if (height) *height = sat ? sat->s.h : 0;
}

ics_sat_precision ics_sat2d_precision(const ics_sat2d *sat) { return sat->s.mode; }
double ics_sat2d_offset(const ics_sat2d *sat) { return sat ? sat->s.offset : NAN; }

ics_status ics_sat2d_box_sum(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                             double *sum) {
  return box3(sat ? &sat->s : NULL, x0, y0, 0, x1, y1, 1, 0, sum);
}

ics_status ics_sat2d_box_sum_clamped(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                                     double *sum) {
  return box3(sat ? &sat->s : NULL, x0, y0, 0, x1, y1, 1, 1, sum);
}

ics_status ics_sat2d_box_mean_clamped(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                                      double *mean) {
  if (!sat || !mean || !sat->s.valid) return ICS_ERR_INVALID_ARG;
  if (x1 < x0 || y1 < y0) return ICS_ERR_INVALID_ARG;
  long cx0 = ics_clampl(x0, 0, (long)sat->s.w), cx1 = ics_clampl(x1, 0, (long)sat->s.w);
  long cy0 = ics_clampl(y0, 0, (long)sat->s.h), cy1 = ics_clampl(y1, 0, (long)sat->s.h);
  if (cx0 == cx1 || cy0 == cy1) return ICS_ERR_RANGE;
  *mean = box_raw(&sat->s, cx0, cy0, 0, cx1, cy1, 1) / ((double)(cx1 - cx0) * (double)(cy1 - cy0));
  return ICS_OK;
}

ics_status ics_sat2d_integral(const ics_sat2d *sat, double x0, double y0, double x1, double y1,
                              double *sum) {
  double lo[3] = {x0, y0, 0.0}, hi[3] = {x1, y1, 1.0};
  return integral3(sat ? &sat->s : NULL, lo, hi, sum);
}

double ics_sat2d_at(const ics_sat2d *sat, size_t x, size_t y) {
  if (!sat || !sat->s.valid || x >= sat->s.w || y >= sat->s.h) return NAN;
  return entry(&sat->s, (long)x, (long)y, 0) + sat->s.offset * (double)(x + 1) * (double)(y + 1);
}

/* ---- 3D API --------------------------------------------------------------------------- */
ics_status ics_sat3d_create(ics_sat3d **out, const float *data, size_t width, size_t height,
                            size_t depth, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  ics_sat3d *s = malloc(sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  ics_status st = sat3d_init(s, data, width, height, depth, width, width * height, mode);
  if (st != ICS_OK) {
    sat3d_release(s);
    free(s);
    return st;
  }
  *out = s;
  return ICS_OK;
}

ics_status ics_sat3d_rebuild(ics_sat3d *sat, const float *data) {
  if (!sat || !data) return ICS_ERR_INVALID_ARG;
  return sat3d_fill(sat, data, sat->w, sat->w * sat->h);
}

void ics_sat3d_destroy(ics_sat3d *sat) {
  if (!sat) return;
  sat3d_release(sat);
  free(sat);
}

void ics_sat3d_size(const ics_sat3d *sat, size_t *width, size_t *height, size_t *depth) {
  if (width) *width = sat ? sat->w : 0;
  if (height) *height = sat ? sat->h : 0;
  if (depth) *depth = sat ? sat->d : 0;
}

ics_sat_precision ics_sat3d_precision(const ics_sat3d *sat) { return sat->mode; }
double ics_sat3d_offset(const ics_sat3d *sat) { return sat ? sat->offset : NAN; }

ics_status ics_sat3d_box_sum(const ics_sat3d *sat, long x0, long y0, long z0, long x1, long y1,
                             long z1, double *sum) {
  return box3(sat, x0, y0, z0, x1, y1, z1, 0, sum);
}

ics_status ics_sat3d_box_sum_clamped(const ics_sat3d *sat, long x0, long y0, long z0, long x1,
                                     long y1, long z1, double *sum) {
  return box3(sat, x0, y0, z0, x1, y1, z1, 1, sum);
}

ics_status ics_sat3d_integral(const ics_sat3d *sat, const double lo[3], const double hi[3],
                              double *sum) {
  return integral3(sat, lo, hi, sum);
}

double ics_sat3d_at(const ics_sat3d *sat, size_t x, size_t y, size_t z) {
  if (!sat || !sat->valid || x >= sat->w || y >= sat->h || z >= sat->d) return NAN;
  return entry(sat, (long)x, (long)y, (long)z) +
         sat->offset * (double)(x + 1) * (double)(y + 1) * (double)(z + 1);
}
