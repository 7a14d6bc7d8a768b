/* sat.c — summed-area tables in 2D and 3D, light-aligned CSAT and spherical SSAT
 * (Ament, Sadlo, Dachsbacher, Weiskopf 2014; precision after Hensley et al. 2005).
 *
 * METHOD. One streaming pass over the data, slice by slice (z), row block by row block (y):
 *   1. the x prefix sums of 8 rows at once (8 independent add chains run in parallel instead
 *      of one serial chain per row: the serial chain, not memory, bounds a naive x pass);
 *   2. t[x] += row prefix (t is the running y sum of the current slice, one row);
 *   3. zacc[y][x] += t[x] (the previous slice's 2D SAT plus this one: the 3D SAT), written out.
 * Every input and output element is touched once; zacc (one slice) stays in cache for
 * 512^2 slices. A 2D table is the 3D table with depth 1 (no zacc).
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
 * cells are 0), inverted boxes ICS_ERR_INVALID_ARG.
 *
 * CSAT / SSAT: the volume is resampled at cell centres of a light-aligned (CSAT) or spherical
 * (SSAT) grid — piecewise-constant per cell — and summed with the 3D SAT above (double-float
 * or any other precision mode). A filtered optical depth is one continuous box integral:
 * 8 multilinear SAT lookups, independent of the filter size. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/sat.h"
#include "icshadow/constants.h"

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

/* ---- modes ---------------------------------------------------------------------------- */
static const char *const mode_names[ICS_SAT_PRECISION_COUNT] = {"float", "float-offset",
                                                                "compensated", "double"};

const char *ics_sat_precision_name(ics_sat_precision mode) {
  return (unsigned)mode < ICS_SAT_PRECISION_COUNT ? mode_names[mode] : NULL;
}

ics_status ics_sat_precision_parse(const char *name, ics_sat_precision *mode) {
  if (!name || !mode) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < ICS_SAT_PRECISION_COUNT; i++)
    if (!strcmp(name, mode_names[i])) {
      *mode = (ics_sat_precision)i;
      return ICS_OK;
    }
  return ICS_ERR_PARSE;
}

double ics_sat_error_factor(ics_sat_precision mode, int dims) {
  if (dims != 2 && dims != 3) return NAN;
  double c = (dims == 2 ? 4.0 : 8.0) * 1.01;
  switch (mode) {
  case ICS_SAT_FLOAT:
  case ICS_SAT_FLOAT_OFFSET: return c * 0x1p-24;
  case ICS_SAT_COMPENSATED: return c * 0x1p-44;
  case ICS_SAT_DOUBLE: return c * 0x1p-53;
  }
  return NAN;
}

size_t ics_sat_cell_bytes(ics_sat_precision mode) {
  switch (mode) {
  case ICS_SAT_FLOAT:
  case ICS_SAT_FLOAT_OFFSET: return 4;
  case ICS_SAT_COMPENSATED:
  case ICS_SAT_DOUBLE: return 8;
  }
  return 0;
}

/* ---- builders ------------------------------------------------------------------------- */
#define ROWS 8 /* rows whose x prefix sums run interleaved */

/* The fused pass for float and double accumulation (T = accumulator and storage type).
 * in: element (x, y, z) at in[z * sstride + y * stride + x]. */
#define DEFINE_BUILD(NAME, T)                                                                \
  static void NAME(T *out, const float *in, size_t w, size_t h, size_t d, size_t stride,     \
                   size_t sstride, T m, T *t, T *zacc, T *px) {                              \
    for (size_t z = 0; z < d; z++) {                                                         \
      for (size_t x = 0; x < w; x++) t[x] = 0;                                               \
      for (size_t y = 0; y < h; y += ROWS) {                                                 \
        size_t nr = h - y < ROWS ? h - y : ROWS;                                             \
        const float *src = in + z * sstride + y * stride;                                    \
        if (nr == ROWS) {                                                                    \
          T r0 = 0, r1 = 0, r2 = 0, r3 = 0, r4 = 0, r5 = 0, r6 = 0, r7 = 0;                  \
          for (size_t x = 0; x < w; x++) {                                                   \
            r0 += (T)src[x] - m;                                                             \
            r1 += (T)src[x + stride] - m;                                                    \
            r2 += (T)src[x + 2 * stride] - m;                                                \
            r3 += (T)src[x + 3 * stride] - m;                                                \
            r4 += (T)src[x + 4 * stride] - m;                                                \
            r5 += (T)src[x + 5 * stride] - m;                                                \
            r6 += (T)src[x + 6 * stride] - m;                                                \
            r7 += (T)src[x + 7 * stride] - m;                                                \
            px[x] = r0, px[x + w] = r1, px[x + 2 * w] = r2, px[x + 3 * w] = r3;               \
            px[x + 4 * w] = r4, px[x + 5 * w] = r5, px[x + 6 * w] = r6, px[x + 7 * w] = r7;   \
          }                                                                                  \
        } else {                                                                             \
          for (size_t r = 0; r < nr; r++) {                                                  \
            T acc = 0;                                                                       \
            for (size_t x = 0; x < w; x++) {                                                 \
              acc += (T)src[x + r * stride] - m;                                             \
              px[r * w + x] = acc;                                                           \
            }                                                                                \
          }                                                                                  \
        }                                                                                    \
        for (size_t r = 0; r < nr; r++) {                                                    \
          T *o = out + (z * h + y + r) * w;                                                  \
          const T *p = px + r * w;                                                             \
          if (d == 1) {                                                                      \
            for (size_t x = 0; x < w; x++) o[x] = t[x] += p[x];                       \
          } else if (z == 0) {                                                               \
            T *za = zacc + (y + r) * w;                                                      \
            for (size_t x = 0; x < w; x++) o[x] = za[x] = t[x] += p[x];               \
          } else {                                                                           \
            T *za = zacc + (y + r) * w;                                                      \
            for (size_t x = 0; x < w; x++) o[x] = za[x] += t[x] += p[x];              \
          }                                                                                  \
        }                                                                                    \
      }                                                                                      \
    }                                                                                        \
  }
#if !defined(__SSE2__) /* portable fallback: 8 rows' x prefixes interleaved */
DEFINE_BUILD(build_f32, float)
DEFINE_BUILD(build_f64, double)
#endif

#if defined(__SSE2__)
#include <emmintrin.h>
/* SSE2 path: the x prefix of 4 (float) / 2 (double) cells is an in-register scan (shift and
 * add), the carry between blocks is the only serial dependency, and two rows run interleaved
 * so their carry chains overlap; the y and z accumulations are fused into the same loop, so
 * the data are read once and the table written once. */
#define HAVE_SSE_BUILD_ 1
/* software prefetch distance (floats of input) — 4 KiB ahead: measured 0.41 -> 0.7 of the floor
 * on 512^3 (the hardware prefetcher alone falls behind this mixed load/compute stream) */
#ifndef PF_
#define PF_ 1024
#endif
static inline __m128 scan4(__m128 v) {
  v = _mm_add_ps(v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(v), 4)));
  return _mm_add_ps(v, _mm_castsi128_ps(_mm_slli_si128(_mm_castps_si128(v), 8)));
}
static inline __m128d scan2(__m128d v) {
  return _mm_add_pd(v, _mm_castsi128_pd(_mm_slli_si128(_mm_castpd_si128(v), 8)));
}

/* One row (or two rows r, r+1 when src1 != NULL) of the fused pass, float. */
static void row_f32(float *o0, float *o1, const float *src0, const float *src1, float m, float *t,
                    float *za0, float *za1, size_t w, int zmode, int nt) {
  __m128 c0 = _mm_setzero_ps(), c1 = _mm_setzero_ps(), mm = _mm_set1_ps(m);
  size_t x = 0;
  for (; x + 4 <= w; x += 4) {
    if ((x & 15) == 0) {
      _mm_prefetch((const char *)(src0 + x + PF_), _MM_HINT_T0);
      if (src1) _mm_prefetch((const char *)(src1 + x + PF_), _MM_HINT_T0);
    }
    __m128 v0 = _mm_add_ps(scan4(_mm_sub_ps(_mm_loadu_ps(src0 + x), mm)), c0);
    c0 = _mm_shuffle_ps(v0, v0, 0xFF);
    __m128 tv = _mm_add_ps(_mm_loadu_ps(t + x), v0);
    __m128 out0 = tv;
    if (zmode == 1) _mm_storeu_ps(za0 + x, tv);
    if (zmode == 2) _mm_storeu_ps(za0 + x, out0 = _mm_add_ps(_mm_loadu_ps(za0 + x), tv));
    if (nt)
      _mm_stream_ps(o0 + x, out0);
    else
      _mm_storeu_ps(o0 + x, out0);
    if (src1) {
      __m128 v1 = _mm_add_ps(scan4(_mm_sub_ps(_mm_loadu_ps(src1 + x), mm)), c1);
      c1 = _mm_shuffle_ps(v1, v1, 0xFF);
      tv = _mm_add_ps(tv, v1);
      __m128 out1 = tv;
      if (zmode == 1) _mm_storeu_ps(za1 + x, tv);
      if (zmode == 2) _mm_storeu_ps(za1 + x, out1 = _mm_add_ps(_mm_loadu_ps(za1 + x), tv));
      if (nt)
        _mm_stream_ps(o1 + x, out1);
      else
        _mm_storeu_ps(o1 + x, out1);
    }
    _mm_storeu_ps(t + x, tv);
  }
  float r0 = _mm_cvtss_f32(c0), r1 = _mm_cvtss_f32(c1);
  for (; x < w; x++) {
    r0 += src0[x] - m;
    float tv = t[x] + r0, out0 = tv;
    if (zmode == 1) za0[x] = tv;
    if (zmode == 2) za0[x] = out0 = za0[x] + tv;
    o0[x] = out0;
    if (src1) {
      r1 += src1[x] - m;
      tv = tv + r1;
      float out1 = tv;
      if (zmode == 1) za1[x] = tv;
      if (zmode == 2) za1[x] = out1 = za1[x] + tv;
      o1[x] = out1;
    }
    t[x] = tv;
  }
}

static void row_f64(double *o0, double *o1, const float *src0, const float *src1, double *t,
                    double *za0, double *za1, size_t w, int zmode, int nt) {
  __m128d c0 = _mm_setzero_pd(), c1 = _mm_setzero_pd();
  size_t x = 0;
  for (; x + 2 <= w; x += 2) {
    if ((x & 15) == 0) {
      _mm_prefetch((const char *)(src0 + x + PF_), _MM_HINT_T0);
      if (src1) _mm_prefetch((const char *)(src1 + x + PF_), _MM_HINT_T0);
    }
    __m128d v0 = _mm_add_pd(scan2(_mm_cvtps_pd(_mm_castsi128_ps(
                                _mm_loadl_epi64((const __m128i *)(const void *)(src0 + x))))),
                            c0);
    c0 = _mm_unpackhi_pd(v0, v0);
    __m128d tv = _mm_add_pd(_mm_loadu_pd(t + x), v0);
    __m128d out0 = tv;
    if (zmode == 1) _mm_storeu_pd(za0 + x, tv);
    if (zmode == 2) _mm_storeu_pd(za0 + x, out0 = _mm_add_pd(_mm_loadu_pd(za0 + x), tv));
    if (nt)
      _mm_stream_pd(o0 + x, out0);
    else
      _mm_storeu_pd(o0 + x, out0);
    if (src1) {
      __m128d v1 = _mm_add_pd(scan2(_mm_cvtps_pd(_mm_castsi128_ps(
                                  _mm_loadl_epi64((const __m128i *)(const void *)(src1 + x))))),
                              c1);
      c1 = _mm_unpackhi_pd(v1, v1);
      tv = _mm_add_pd(tv, v1);
      __m128d out1 = tv;
      if (zmode == 1) _mm_storeu_pd(za1 + x, tv);
      if (zmode == 2) _mm_storeu_pd(za1 + x, out1 = _mm_add_pd(_mm_loadu_pd(za1 + x), tv));
      if (nt)
        _mm_stream_pd(o1 + x, out1);
      else
        _mm_storeu_pd(o1 + x, out1);
    }
    _mm_storeu_pd(t + x, tv);
  }
  double r0 = _mm_cvtsd_f64(c0), r1 = _mm_cvtsd_f64(c1);
  for (; x < w; x++) {
    r0 += (double)src0[x];
    double tv = t[x] + r0, out0 = tv;
    if (zmode == 1) za0[x] = tv;
    if (zmode == 2) za0[x] = out0 = za0[x] + tv;
    o0[x] = out0;
    if (src1) {
      r1 += (double)src1[x];
      tv = tv + r1;
      double out1 = tv;
      if (zmode == 1) za1[x] = tv;
      if (zmode == 2) za1[x] = out1 = za1[x] + tv;
      o1[x] = out1;
    }
    t[x] = tv;
  }
}

/* Tables above NT_BYTES are written with non-temporal stores (no read-for-ownership, no
 * eviction of the data being read); the previous slice is then kept in zacc (in cache). */
#define NT_BYTES ((size_t)4 << 20)
#define DEFINE_SSE_BUILD(NAME, T, ROWFN, ...)                                                 \
  static void NAME(T *out, const float *in, size_t w, size_t h, size_t d, size_t stride,     \
                   size_t sstride, T m, T *t, T *zacc, T *px) {                              \
    (void)px;                                                                                \
    (void)m;                                                                                 \
    int nt = w * h * d * sizeof(T) > NT_BYTES;                                               \
    for (size_t z = 0; z < d; z++) {                                                         \
      int zmode = d == 1 ? 0 : z == 0 ? 1 : 2;                                               \
      for (size_t x = 0; x < w; x++) t[x] = 0;                                               \
      for (size_t y = 0; y < h; y += 2) {                                                    \
        int two = y + 1 < h;                                                                 \
        const float *s0 = in + z * sstride + y * stride;                                     \
        T *o0 = out + (z * h + y) * w;                                                       \
        T *za0 = zmode ? zacc + y * w : NULL;                                                \
        int ntr = nt && ((uintptr_t)o0 & 15) == 0 && ((uintptr_t)(o0 + w) & 15) == 0;        \
        ROWFN(o0, two ? o0 + w : NULL, s0, two ? s0 + stride : NULL, __VA_ARGS__, t, za0,    \
              za0 && two ? za0 + w : NULL, w, zmode, ntr);                                   \
      }                                                                                      \
    }                                                                                        \
    if (nt) _mm_sfence();                                                                    \
  }
DEFINE_SSE_BUILD(build_f32_sse, float, row_f32, m)
#define row_f64_(o0, o1, s0, s1, dummy, t, za0, za1, w, zm, nt) \
  row_f64(o0, o1, s0, s1, t, za0, za1, w, zm, nt)
DEFINE_SSE_BUILD(build_f64_sse, double, row_f64_, 0)
#endif

/* Double-float (hi + lo, |lo| <= ulp(hi)/2) addition in float arithmetic. */
typedef struct {
  float hi, lo;
} ff;
static inline ff ff_add(ff a, ff b) {
  float s = a.hi + b.hi;
  float bb = s - a.hi;
  float e = (a.hi - (s - bb)) + (b.hi - bb); /* TwoSum: s + e = a.hi + b.hi exactly */
  e += a.lo + b.lo;
  ff r;
  r.hi = s + e; /* Fast2Sum renormalisation */
  r.lo = e - (r.hi - s);
  return r;
}
static inline ff ff_addf(ff a, float b) {
  ff bb = {b, 0.0f};
  return ff_add(a, bb);
}

/* Compensated pass: the x prefixes of 8 rows run as 8 interleaved double-float chains (one
 * chain is ~7 dependent float adds per cell), then the y and z accumulations are double-float
 * adds across x (independent per x: vectorised by the compiler; the same IEEE operations). */
#define FF_ADD_(H, L, AH, AL, BH, BL)                                                          \
  do {                                                                                       \
    float s_ = (AH) + (BH), bb_ = s_ - (AH);                                                 \
    float e_ = ((AH) - (s_ - bb_)) + ((BH) - bb_);                                           \
    e_ += (AL) + (BL);                                                                       \
    float h_ = s_ + e_;                                                                      \
    (L) = e_ - (h_ - s_);                                                                    \
    (H) = h_;                                                                                \
  } while (0)

static void build_ff(float *hi, float *lo, const float *in, size_t w, size_t h, size_t d,
                     size_t stride, size_t sstride, float *tmp) {
  size_t slice = d > 1 ? w * h : 0, pw = w + 40; /* padded rows: no 4K aliasing with src */
  float *th = tmp, *tl = th + w, *zh = tl + w, *zl = zh + slice, *ph = zl + slice,
        *pl = ph + ROWS * pw + 24;
  for (size_t z = 0; z < d; z++) {
    for (size_t x = 0; x < w; x++) th[x] = tl[x] = 0.0f;
    for (size_t y = 0; y < h; y += ROWS) {
      size_t nr = h - y < ROWS ? h - y : ROWS;
      const float *src = in + z * sstride + y * stride;
      if (nr == ROWS) {
        ff acc[ROWS];
        for (int r = 0; r < ROWS; r++) acc[r].hi = acc[r].lo = 0.0f;
        for (size_t x = 0; x < w; x++)
          for (int r = 0; r < ROWS; r++) {
            acc[r] = ff_addf(acc[r], src[x + (size_t)r * stride]);
            ph[(size_t)r * pw + x] = acc[r].hi;
            pl[(size_t)r * pw + x] = acc[r].lo;
          }
      } else {
        for (size_t r = 0; r < nr; r++) {
          ff acc = {0.0f, 0.0f};
          for (size_t x = 0; x < w; x++) {
            acc = ff_addf(acc, src[x + r * stride]);
            ph[r * pw + x] = acc.hi;
            pl[r * pw + x] = acc.lo;
          }
        }
      }
      for (size_t r = 0; r < nr; r++) {
        size_t o = (z * h + y + r) * w;
        const float *rh = ph + r * pw, *rl = pl + r * pw;
        float *zrh = d > 1 ? zh + (y + r) * w : NULL, *zrl = d > 1 ? zl + (y + r) * w : NULL;
        for (size_t x = 0; x < w; x++) FF_ADD_(th[x], tl[x], th[x], tl[x], rh[x], rl[x]);
        if (d == 1) {
          memcpy(hi + o, th, w * sizeof(float));
          memcpy(lo + o, tl, w * sizeof(float));
        } else if (z == 0) {
          memcpy(zrh, th, w * sizeof(float));
          memcpy(zrl, tl, w * sizeof(float));
          memcpy(hi + o, th, w * sizeof(float));
          memcpy(lo + o, tl, w * sizeof(float));
        } else {
          for (size_t x = 0; x < w; x++) FF_ADD_(zrh[x], zrl[x], zrh[x], zrl[x], th[x], tl[x]);
          memcpy(hi + o, zrh, w * sizeof(float));
          memcpy(lo + o, zrl, w * sizeof(float));
        }
      }
    }
  }
}

static ics_status check_size(size_t w, size_t h, size_t d, ics_sat_precision mode) {
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
  size_t w = s->w, h = s->h, d = s->d, slice = d > 1 ? w * h : 0;
  size_t last = ((d - 1) * h + (h - 1)) * w;
  int ok = 1;
  s->valid = 0;
  if (s->mode == ICS_SAT_DOUBLE) {
    double *tmp = s->scratch;
#ifdef HAVE_SSE_BUILD_
    build_f64_sse(s->dbl, data, w, h, d, stride, sstride, 0.0, tmp, tmp + w, tmp + w + slice);
#else
    build_f64(s->dbl, data, w, h, d, stride, sstride, 0.0, tmp, tmp + w, tmp + w + slice);
#endif
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->dbl[last + x]) != 0;
  } else if (s->mode == ICS_SAT_COMPENSATED) {
    build_ff(s->f, s->lo, data, w, h, d, stride, sstride, s->scratch);
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->f[last + x]) && isfinite(s->lo[last + x]);
  } else {
    float m = s->mode == ICS_SAT_FLOAT_OFFSET ? sample_mean(data, w, h, d, stride, sstride) : 0.0f;
    s->offset = m;
    float *tmp = s->scratch;
#ifdef HAVE_SSE_BUILD_
    build_f32_sse(s->f, data, w, h, d, stride, sstride, m, tmp, tmp + w, tmp + w + slice);
#else
    build_f32(s->f, data, w, h, d, stride, sstride, m, tmp, tmp + w, tmp + w + slice);
#endif
    for (size_t x = 0; x < w; x++) ok &= isfinite(s->f[last + x]) != 0;
  }
  if (!ok) return classify_bad(data, w, h, d, stride, sstride);
  s->valid = 1;
  return ICS_OK;
}

/* A row stride is usable when stride >= w and the input span (h - 1) * stride + w floats
 * neither overflows nor exceeds ICS_SAT_MAX_SPAN_BYTES (a larger span is a caller's error, not
 * an image: reading it would run off the buffer). 3D input is tightly packed (span = the cell
 * count, checked by check_size). */
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
  ics_status st = check_size(w, h, d, mode);
  if (st != ICS_OK) return st;
  if (!data || !stride_ok(w, h, stride)) return ICS_ERR_INVALID_ARG;
  size_t n = w * h * d, slice = d > 1 ? w * h : 0;
  s->w = w, s->h = h, s->d = d, s->mode = mode;
  if (mode == ICS_SAT_DOUBLE) {
    s->dbl = malloc(n * sizeof(double));
    s->scratch = malloc((w + slice + w * ROWS) * sizeof(double));
  } else if (mode == ICS_SAT_COMPENSATED) {
    s->f = malloc(n * sizeof(float));
    s->lo = malloc(n * sizeof(float));
    s->scratch = malloc((2 * w + 2 * slice + 2 * ROWS * (w + 40) + 24) * sizeof(float));
  } else {
    s->f = malloc(n * sizeof(float));
    s->scratch = malloc((w + slice + w * ROWS) * sizeof(float));
  }
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

static long clampl(long v, long lo, long hi) { return v < lo ? lo : v > hi ? hi : v; }

static ics_status box3(const struct ics_sat3d *s, long x0, long y0, long z0, long x1, long y1,
                       long z1, int clamp, double *sum) {
  if (!s || !sum || !s->valid) return ICS_ERR_INVALID_ARG;
  if (x1 < x0 || y1 < y0 || z1 < z0) return ICS_ERR_INVALID_ARG;
  long w = (long)s->w, h = (long)s->h, d = (long)s->d;
  if (clamp) {
    x0 = clampl(x0, 0, w), x1 = clampl(x1, 0, w);
    y0 = clampl(y0, 0, h), y1 = clampl(y1, 0, h);
    z0 = clampl(z0, 0, d), z1 = clampl(z1, 0, d);
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

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

static ics_status integral3(const struct ics_sat3d *s, const double lo[3], const double hi[3],
                            double *sum) {
  if (!s || !lo || !hi || !sum || !s->valid) return ICS_ERR_INVALID_ARG;
  double n[3] = {(double)s->w, (double)s->h, (double)s->d};
  double a[3], b[3];
  for (int k = 0; k < 3; k++) {
    if (isnan(lo[k]) || isnan(hi[k])) return ICS_ERR_NAN;
    if (hi[k] < lo[k]) return ICS_ERR_INVALID_ARG;
    a[k] = clampd(lo[k], 0.0, n[k]);
    b[k] = clampd(hi[k], 0.0, n[k]);
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
ics_status ics_sat2d_build(ics_sat2d **out, const float *data, size_t width, size_t height,
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

void ics_sat2d_free(ics_sat2d *sat) {
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
  long cx0 = clampl(x0, 0, (long)sat->s.w), cx1 = clampl(x1, 0, (long)sat->s.w);
  long cy0 = clampl(y0, 0, (long)sat->s.h), cy1 = clampl(y1, 0, (long)sat->s.h);
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
ics_status ics_sat3d_build(ics_sat3d **out, const float *data, size_t width, size_t height,
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

void ics_sat3d_free(ics_sat3d *sat) {
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

/* ---- volumes -------------------------------------------------------------------------- */
static int volume_ok(const ics_volume *v) {
  return v && v->data && v->nx && v->ny && v->nz;
}

double ics_volume_sample(const ics_volume *vol, const double p[3]) {
  size_t n[3] = {vol->nx, vol->ny, vol->nz};
  long i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; a++) {
    if (!(p[a] >= 0.0 && p[a] <= (double)n[a])) return 0.0;
    double g = p[a] - 0.5, fl = floor(g);
    f[a] = g - fl;
    long i = (long)fl, last = (long)n[a] - 1;
    i0[a] = i < 0 ? 0 : i > last ? last : i;
    i1[a] = i + 1 < 0 ? 0 : i + 1 > last ? last : i + 1;
  }
  const float *d = vol->data;
  size_t sx = 1, sy = vol->nx, sz = vol->nx * vol->ny;
#define V_(i, j, k) ((double)d[(size_t)(i) * sx + (size_t)(j) * sy + (size_t)(k) * sz])
  double c00 = V_(i0[0], i0[1], i0[2]) * (1 - f[0]) + V_(i1[0], i0[1], i0[2]) * f[0];
  double c10 = V_(i0[0], i1[1], i0[2]) * (1 - f[0]) + V_(i1[0], i1[1], i0[2]) * f[0];
  double c01 = V_(i0[0], i0[1], i1[2]) * (1 - f[0]) + V_(i1[0], i0[1], i1[2]) * f[0];
  double c11 = V_(i0[0], i1[1], i1[2]) * (1 - f[0]) + V_(i1[0], i1[1], i1[2]) * f[0];
#undef V_
  double c0 = c00 * (1 - f[1]) + c10 * f[1], c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void cross3(const double a[3], const double b[3], double c[3]) {
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static int finite3(const double a[3]) {
  return isfinite(a[0]) && isfinite(a[1]) && isfinite(a[2]);
}

/* Interval of t >= 0 where o + t dir lies in the volume box; returns 0 when empty. */
static int ray_box(const ics_volume *vol, const double o[3], const double dir[3], double *t0,
                   double *t1) {
  double n[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  double a = 0.0, b = INFINITY;
  for (int k = 0; k < 3; k++) {
    if (dir[k] == 0.0) {
      if (o[k] < 0.0 || o[k] > n[k]) return 0;
      continue;
    }
    double ta = (0.0 - o[k]) / dir[k], tb = (n[k] - o[k]) / dir[k];
    if (ta > tb) {
      double t = ta;
      ta = tb, tb = t;
    }
    if (ta > a) a = ta;
    if (tb < b) b = tb;
  }
  if (!(a < b)) return 0;
  *t0 = a, *t1 = b;
  return 1;
}

/* Optical depth along o + t dir, t in [tmin, tmax] (clipped to the box), midpoint rule. */
static double march(const ics_volume *vol, const double o[3], const double dir[3], double tmin,
                    double tmax, double step) {
  double a, b;
  if (!ray_box(vol, o, dir, &a, &b)) return 0.0;
  if (a < tmin) a = tmin;
  if (b > tmax) b = tmax;
  if (!(a < b)) return 0.0;
  double len = b - a;
  long k = (long)ceil(len / step);
  if (k < 1) k = 1;
  double dt = len / (double)k, tau = 0.0;
  for (long i = 0; i < k; i++) {
    double t = a + ((double)i + 0.5) * dt;
    double p[3] = {o[0] + t * dir[0], o[1] + t * dir[1], o[2] + t * dir[2]};
    tau += ics_volume_sample(vol, p);
  }
  return tau * dt;
}

/* ---- CSAT ----------------------------------------------------------------------------- */
struct ics_csat {
  ics_sat3d *sat;
  double r[3][3]; /* r_u, r_v, r_w */
  double centre[3];
  size_t n[3];
  double h;
};

ics_status ics_csat_build_frame(ics_csat **out, const ics_volume *vol, const double r_u[3],
                                const double r_v[3], double h, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!volume_ok(vol) || !r_u || !r_v) return ICS_ERR_INVALID_ARG;
  if (isnan(h) || !finite3(r_u) || !finite3(r_v)) return ICS_ERR_NAN;
  if (!(h > 0.0) || !isfinite(h)) return ICS_ERR_INVALID_ARG;
  if (fabs(dot3(r_u, r_u) - 1) > 1e-9 || fabs(dot3(r_v, r_v) - 1) > 1e-9 ||
      fabs(dot3(r_u, r_v)) > 1e-9)
    return ICS_ERR_INVALID_ARG;
  ics_csat *c = calloc(1, sizeof *c);
  if (!c) return ICS_ERR_NOMEM;
  memcpy(c->r[0], r_u, sizeof c->r[0]);
  memcpy(c->r[1], r_v, sizeof c->r[1]);
  cross3(r_u, r_v, c->r[2]);
  c->h = h;
  double dims[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  for (int k = 0; k < 3; k++) c->centre[k] = dims[k] / 2;
  double cells = 1.0;
  for (int a = 0; a < 3; a++) { /* h beyond the volume's extent: cells mostly outside it */
    double e = fabs(c->r[a][0]) * dims[0] + fabs(c->r[a][1]) * dims[1] + fabs(c->r[a][2]) * dims[2];
    if (h > e * (1 + 1e-12)) {
      free(c);
      return ICS_ERR_RANGE;
    }
  }
  for (int a = 0; a < 3; a++) {
    double e = fabs(c->r[a][0]) * dims[0] + fabs(c->r[a][1]) * dims[1] + fabs(c->r[a][2]) * dims[2];
    double na = ceil(e / h - 1e-9);
    if (na < 1) na = 1;
    if (na > 2147483648.0) {
      free(c);
      return ICS_ERR_SIZE;
    }
    c->n[a] = (size_t)na;
    cells *= na;
  }
  if (cells > 2147483648.0 || cells * 4.0 > (double)ICS_SAT_MAX_BYTES) {
    free(c);
    return ICS_ERR_SIZE;
  }
  float *grid = malloc((size_t)cells * sizeof(float));
  if (!grid) {
    free(c);
    return ICS_ERR_NOMEM;
  }
  double h3 = h * h * h;
  for (size_t k = 0; k < c->n[2]; k++)
    for (size_t j = 0; j < c->n[1]; j++)
      for (size_t i = 0; i < c->n[0]; i++) {
        double q[3] = {((double)i + 0.5) * h - (double)c->n[0] * h / 2,
                       ((double)j + 0.5) * h - (double)c->n[1] * h / 2,
                       ((double)k + 0.5) * h - (double)c->n[2] * h / 2};
        double p[3];
        for (int a = 0; a < 3; a++)
          p[a] = c->centre[a] + q[0] * c->r[0][a] + q[1] * c->r[1][a] + q[2] * c->r[2][a];
        grid[(k * c->n[1] + j) * c->n[0] + i] = (float)(ics_volume_sample(vol, p) * h3);
      }
  ics_status st = ics_sat3d_build(&c->sat, grid, c->n[0], c->n[1], c->n[2], mode);
  free(grid);
  if (st != ICS_OK) {
    free(c);
    return st;
  }
  *out = c;
  return ICS_OK;
}

ics_status ics_csat_build(ics_csat **out, const ics_volume *vol, const double l[3], double h,
                          ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!l) return ICS_ERR_INVALID_ARG;
  if (!finite3(l)) return ICS_ERR_NAN;
  double len = sqrt(dot3(l, l));
  if (!(len > 0.0)) return ICS_ERR_INVALID_ARG;
  double w[3] = {l[0] / len, l[1] / len, l[2] / len};
  /* r_u: the world axis least aligned with l, made orthogonal (deterministic). */
  int k = 0;
  for (int a = 1; a < 3; a++)
    if (fabs(w[a]) < fabs(w[k])) k = a;
  double e[3] = {0, 0, 0}, u[3], v[3];
  e[k] = 1.0;
  double d = dot3(e, w);
  for (int a = 0; a < 3; a++) u[a] = e[a] - d * w[a];
  double ul = sqrt(dot3(u, u));
  for (int a = 0; a < 3; a++) u[a] /= ul;
  cross3(w, u, v); /* u x v = u x (w x u) = w */
  return ics_csat_build_frame(out, vol, u, v, h, mode);
}

void ics_csat_free(ics_csat *csat) {
  if (!csat) return;
  ics_sat3d_free(csat->sat);
  free(csat);
}

void ics_csat_frame(const ics_csat *csat, double r_u[3], double r_v[3], double r_w[3],
                    size_t n[3]) {
  if (r_u) memcpy(r_u, csat->r[0], sizeof csat->r[0]);
  if (r_v) memcpy(r_v, csat->r[1], sizeof csat->r[1]);
  if (r_w) memcpy(r_w, csat->r[2], sizeof csat->r[2]);
  if (n) memcpy(n, csat->n, sizeof csat->n);
}

ics_status ics_csat_light_dir(const ics_csat *csat, ics_csat_light which, double dir[3]) {
  if (!csat || !dir || (unsigned)which > ICS_CSAT_MINUS_V) return ICS_ERR_INVALID_ARG;
  static const int axis[6] = {2, 2, 0, 0, 1, 1};
  double s = (which & 1) ? -1.0 : 1.0;
  for (int a = 0; a < 3; a++) dir[a] = s * csat->r[axis[which]][a];
  return ICS_OK;
}

ics_status ics_csat_tau(const ics_csat *csat, ics_csat_light which, const double p[3],
                        double half_width, double *tau) {
  if (!csat || !p || !tau || (unsigned)which > ICS_CSAT_MINUS_V) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(p[0]) || isnan(p[1]) || isnan(p[2])) return ICS_ERR_NAN;
  if (!(half_width >= 0.0) || !isfinite(half_width) || !finite3(p)) return ICS_ERR_INVALID_ARG;
  double h = csat->h;
  double U = half_width > 0.0 ? half_width : h / 2;
  double g[3], lo[3], hi[3];
  for (int a = 0; a < 3; a++) {
    double q[3] = {p[0] - csat->centre[0], p[1] - csat->centre[1], p[2] - csat->centre[2]};
    g[a] = (dot3(q, csat->r[a]) + (double)csat->n[a] * h / 2) / h;
    lo[a] = g[a] - U / h;
    hi[a] = g[a] + U / h;
  }
  static const int axis[6] = {2, 2, 0, 0, 1, 1};
  int ax = axis[which];
  if (which & 1) {
    lo[ax] = -1.0;
    hi[ax] = g[ax];
  } else {
    lo[ax] = g[ax];
    hi[ax] = (double)csat->n[ax] + 1.0;
  }
  if (hi[ax] < lo[ax]) { /* p beyond the grid on the light's side: nothing in between */
    *tau = 0.0;
    return ICS_OK;
  }
  double s;
  ics_status st = ics_sat3d_integral(csat->sat, lo, hi, &s);
  if (st != ICS_OK) return st;
  *tau = s / (4.0 * U * U);
  return ICS_OK;
}

ics_status ics_csat_transmittance(const ics_csat *csat, ics_csat_light which, const double p[3],
                                  double half_width, double *transmittance) {
  if (!transmittance) return ICS_ERR_INVALID_ARG;
  double tau;
  ics_status st = ics_csat_tau(csat, which, p, half_width, &tau);
  if (st == ICS_OK) *transmittance = exp(-tau);
  return st;
}

ics_status ics_tau_bruteforce_directional(const ics_volume *vol, const double r_u[3],
                                          const double r_v[3], const double dir[3],
                                          const double p[3], double half_width, int n_patch,
                                          double step, double *tau) {
  if (!volume_ok(vol) || !r_u || !r_v || !dir || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(step) || !finite3(p) || !finite3(dir)) return ICS_ERR_NAN;
  if (!(half_width >= 0.0) || !(step > 0.0) || n_patch < 1) return ICS_ERR_INVALID_ARG;
  int n = half_width > 0.0 ? n_patch : 1;
  double acc = 0.0;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) {
      double u = half_width > 0.0 ? -half_width + ((double)i + 0.5) * 2 * half_width / n : 0.0;
      double v = half_width > 0.0 ? -half_width + ((double)j + 0.5) * 2 * half_width / n : 0.0;
      double o[3];
      for (int a = 0; a < 3; a++) o[a] = p[a] + u * r_u[a] + v * r_v[a];
      acc += march(vol, o, dir, 0.0, INFINITY, step);
    }
  *tau = acc / ((double)n * n);
  return ICS_OK;
}

/* ---- SSAT ----------------------------------------------------------------------------- */
/* Spherical frame around the light: e[0] (phi = 0, theta = pi/2) points from the light to the
 * volume centre, the polar axis e[2] is the world axis least aligned with it, orthogonalised,
 * and e[1] = e[2] x e[0] (so e[0] x e[1] = e[2]). The volume then sits around the equator,
 * away from both poles and from the phi seam at +-pi, whenever the light is outside it (the
 * angular box of a patch degenerates near a pole). A light at the volume centre keeps the
 * world axes. The brute-force reference derives the same frame from the same inputs. */
static void ssat_frame(const ics_volume *vol, const double light[3], double e[3][3]) {
  double a[3] = {(double)vol->nx / 2 - light[0], (double)vol->ny / 2 - light[1],
                 (double)vol->nz / 2 - light[2]};
  double len = sqrt(dot3(a, a));
  memset(e, 0, 9 * sizeof(double));
  if (!(len > 0.0) || !isfinite(len)) {
    e[0][0] = e[1][1] = e[2][2] = 1.0;
    return;
  }
  for (int k = 0; k < 3; k++) e[0][k] = a[k] / len;
  int m = 0;
  for (int k = 1; k < 3; k++)
    if (fabs(e[0][k]) < fabs(e[0][m])) m = k;
  double d = e[0][m];
  for (int k = 0; k < 3; k++) e[2][k] = (k == m ? 1.0 : 0.0) - d * e[0][k];
  double l2 = sqrt(dot3(e[2], e[2]));
  for (int k = 0; k < 3; k++) e[2][k] /= l2;
  cross3(e[2], e[0], e[1]);
}

/* Largest distance from the light to a volume corner; the light may be at most
 * ICS_SSAT_MAX_DISTANCE volume diagonals from the farthest corner. */
static ics_status ssat_rmax(const ics_volume *vol, const double light[3], double *rmax) {
  double dims[3] = {(double)vol->nx, (double)vol->ny, (double)vol->nz};
  double rm = 0.0;
  for (int c = 0; c < 8; c++) {
    double q[3];
    for (int a = 0; a < 3; a++) q[a] = ((c >> a) & 1 ? dims[a] : 0.0) - light[a];
    double r = hypot(hypot(q[0], q[1]), q[2]);
    if (!(r <= rm)) rm = r;
  }
  double diag = sqrt(dot3(dims, dims));
  if (!isfinite(rm) || rm > ICS_SSAT_MAX_DISTANCE * diag) return ICS_ERR_RANGE;
  *rmax = rm;
  return ICS_OK;
}

struct ics_ssat {
  ics_sat3d *sat;
  double light[3];
  double e[3][3]; /* ssat_frame */
  size_t n[3];    /* phi, theta, r */
  double r_max;
};

ics_status ics_ssat_build(ics_ssat **out, const ics_volume *vol, const double light_pos[3],
                          size_t n_phi, size_t n_theta, size_t n_r, ics_sat_precision mode) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!volume_ok(vol) || !light_pos) return ICS_ERR_INVALID_ARG;
  if (isnan(light_pos[0]) || isnan(light_pos[1]) || isnan(light_pos[2])) return ICS_ERR_NAN;
  if (!finite3(light_pos)) return ICS_ERR_RANGE;
  ics_status st = check_size(n_phi, n_theta, n_r, mode);
  if (st != ICS_OK) return st;
  if ((double)n_phi * (double)n_theta * (double)n_r * 4.0 > (double)ICS_SAT_MAX_BYTES)
    return ICS_ERR_SIZE;
  double rm;
  st = ssat_rmax(vol, light_pos, &rm);
  if (st != ICS_OK) return st;
  ics_ssat *s = calloc(1, sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  memcpy(s->light, light_pos, sizeof s->light);
  ssat_frame(vol, light_pos, s->e);
  s->n[0] = n_phi, s->n[1] = n_theta, s->n[2] = n_r;
  s->r_max = rm;
  float *grid = malloc(n_phi * n_theta * n_r * sizeof(float));
  if (!grid) {
    free(s);
    return ICS_ERR_NOMEM;
  }
  double dphi = 2 * ICS_PI / (double)n_phi, dth = ICS_PI / (double)n_theta, dr = rm / (double)n_r;
  for (size_t k = 0; k < n_r; k++) {
    double r = ((double)k + 0.5) * dr;
    for (size_t j = 0; j < n_theta; j++) {
      double th = ((double)j + 0.5) * dth;
      double omega = dphi * (cos((double)j * dth) - cos((double)(j + 1) * dth));
      double st_ = sin(th), ct = cos(th);
      for (size_t i = 0; i < n_phi; i++) {
        double ph = -ICS_PI + ((double)i + 0.5) * dphi;
        double c1 = r * st_ * cos(ph), c2 = r * st_ * sin(ph), c3 = r * ct, p[3];
        for (int a = 0; a < 3; a++)
          p[a] = light_pos[a] + c1 * s->e[0][a] + c2 * s->e[1][a] + c3 * s->e[2][a];
        grid[(k * n_theta + j) * n_phi + i] = (float)(ics_volume_sample(vol, p) * omega * dr);
      }
    }
  }
  st = ics_sat3d_build(&s->sat, grid, n_phi, n_theta, n_r, mode);
  free(grid);
  if (st != ICS_OK) {
    free(s);
    return st;
  }
  *out = s;
  return ICS_OK;
}

void ics_ssat_free(ics_ssat *ssat) {
  if (!ssat) return;
  ics_sat3d_free(ssat->sat);
  free(ssat);
}

void ics_ssat_frame(const ics_ssat *ssat, double e_x[3], double e_y[3], double e_z[3],
                    size_t n[3]) {
  if (!ssat) return;
  if (e_x) memcpy(e_x, ssat->e[0], sizeof ssat->e[0]);
  if (e_y) memcpy(e_y, ssat->e[1], sizeof ssat->e[1]);
  if (e_z) memcpy(e_z, ssat->e[2], sizeof ssat->e[2]);
  if (n) memcpy(n, ssat->n, sizeof ssat->n);
}

/* The angular box of a patch of half-width U at p in the frame e: phi in [p0, p1] (may leave
 * [-pi, pi]; p1 - p0 <= 2 pi), theta in [t0, t1], and R. The phi half-width
 * atan(U/R) / sin(theta) is clamped to pi: a patch over a pole (theta < atan(U/R)) becomes the
 * polar cap theta in [0, t1] over the whole ring (the same for the south pole). Returns
 * ICS_ERR_RANGE when p is at the light or |p - light| overflows. */
static ics_status ssat_box(const double light[3], const double e[3][3], const double p[3],
                           double U, double *ph0, double *ph1, double *th0, double *th1,
                           double *R) {
  double q[3] = {p[0] - light[0], p[1] - light[1], p[2] - light[2]};
  double r = hypot(hypot(q[0], q[1]), q[2]);
  if (!(r > 0.0) || !isfinite(r)) return ICS_ERR_RANGE;
  double x = dot3(q, e[0]), y = dot3(q, e[1]), z = dot3(q, e[2]);
  double th = atan2(hypot(x, y), z), ph = atan2(y, x);
  double al = atan(U / r);
  double sn = sin(th);
  double be = sn > 0.0 ? al / sn : INFINITY; /* phi half-width */
  *th0 = clampd(th - al, 0.0, ICS_PI);
  *th1 = clampd(th + al, 0.0, ICS_PI);
  if (!(be < ICS_PI)) { /* clamped to pi: the whole ring (then th0 = 0 or th1 = pi) */
    *ph0 = -ICS_PI, *ph1 = ICS_PI;
  } else {
    *ph0 = ph - be, *ph1 = ph + be;
  }
  *R = r;
  return ICS_OK;
}

/* SAT coordinate of polar angle theta: cell j covers [j dth, (j+1) dth] and holds the solid
 * angle dphi (cos(j dth) - cos((j+1) dth)) of the cell-wise constant field, so the part of it
 * above theta is the fraction (cos(j dth) - cos(theta)) / (cos(j dth) - cos((j+1) dth)) — the
 * SAT's continuous integral, linear inside a cell, is then exact in solid angle. */
static double theta_coord(double th, size_t n, double dth) {
  if (!(th > 0.0)) return 0.0;
  double j = floor(th / dth);
  if (j >= (double)n) return (double)n;
  double c0 = cos(j * dth), c1 = cos((j + 1) * dth);
  double f = (c0 - cos(th)) / (c0 - c1);
  return j + clampd(f, 0.0, 1.0);
}

ics_status ics_ssat_tau(const ics_ssat *s, const double p[3], double half_width, double *tau) {
  if (!s || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(p[0]) || isnan(p[1]) || isnan(p[2])) return ICS_ERR_NAN;
  if (!(half_width > 0.0) || !isfinite(half_width) || !finite3(p)) return ICS_ERR_INVALID_ARG;
  double ph0, ph1, th0, th1, R;
  ics_status st = ssat_box(s->light, s->e, p, half_width, &ph0, &ph1, &th0, &th1, &R);
  if (st != ICS_OK) return st;
  double dphi = 2 * ICS_PI / (double)s->n[0], dth = ICS_PI / (double)s->n[1];
  double dr = s->r_max / (double)s->n[2];
  double lo[3] = {0, theta_coord(th0, s->n[1], dth), 0.0};
  double hi[3] = {0, theta_coord(th1, s->n[1], dth), R / dr};
  double sum = 0.0;
  /* phi intervals inside [-pi, pi]: the whole ring, or one interval that wraps at most once */
  double seg[2][2];
  int ns = 0;
  if (ph1 - ph0 >= 2 * ICS_PI) {
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ICS_PI;
  } else if (ph0 < -ICS_PI) {
    seg[ns][0] = ph0 + 2 * ICS_PI, seg[ns++][1] = ICS_PI;
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ph1;
  } else if (ph1 > ICS_PI) {
    seg[ns][0] = ph0, seg[ns++][1] = ICS_PI;
    seg[ns][0] = -ICS_PI, seg[ns++][1] = ph1 - 2 * ICS_PI;
  } else {
    seg[ns][0] = ph0, seg[ns++][1] = ph1;
  }
  for (int k = 0; k < ns; k++) {
    lo[0] = (seg[k][0] + ICS_PI) / dphi;
    hi[0] = (seg[k][1] + ICS_PI) / dphi;
    double v;
    st = ics_sat3d_integral(s->sat, lo, hi, &v);
    if (st != ICS_OK) return st;
    sum += v;
  }
  double omega = (ph1 - ph0) * (cos(th0) - cos(th1));
  *tau = omega > 0.0 ? sum / omega : 0.0;
  return ICS_OK;
}

ics_status ics_ssat_transmittance(const ics_ssat *ssat, const double p[3], double half_width,
                                  double *transmittance) {
  if (!transmittance) return ICS_ERR_INVALID_ARG;
  double tau;
  ics_status st = ics_ssat_tau(ssat, p, half_width, &tau);
  if (st == ICS_OK) *transmittance = exp(-tau);
  return st;
}

ics_status ics_tau_bruteforce_point(const ics_volume *vol, const double light_pos[3],
                                    const double p[3], double half_width, int n_patch,
                                    double step, double *tau) {
  if (!volume_ok(vol) || !light_pos || !p || !tau) return ICS_ERR_INVALID_ARG;
  if (isnan(half_width) || isnan(step) || !finite3(p) || isnan(light_pos[0]) ||
      isnan(light_pos[1]) || isnan(light_pos[2]))
    return ICS_ERR_NAN;
  if (!(half_width > 0.0) || !(step > 0.0) || n_patch < 1) return ICS_ERR_INVALID_ARG;
  double ph0, ph1, th0, th1, R, e[3][3], rm;
  ics_status st0 = ssat_rmax(vol, light_pos, &rm); /* the same light limit as ics_ssat_build */
  if (st0 != ICS_OK) return st0;
  ssat_frame(vol, light_pos, e);
  ics_status st = ssat_box(light_pos, e, p, half_width, &ph0, &ph1, &th0, &th1, &R);
  if (st != ICS_OK) return st;
  double c0 = cos(th0), c1 = cos(th1), acc = 0.0;
  for (int j = 0; j < n_patch; j++) {
    double ct = c0 + ((double)j + 0.5) * (c1 - c0) / n_patch;
    double stt = sqrt(fmax(0.0, 1.0 - ct * ct));
    for (int i = 0; i < n_patch; i++) {
      double ph = ph0 + ((double)i + 0.5) * (ph1 - ph0) / n_patch;
      double dir[3];
      for (int a = 0; a < 3; a++)
        dir[a] = stt * cos(ph) * e[0][a] + stt * sin(ph) * e[1][a] + ct * e[2][a];
      acc += march(vol, light_pos, dir, 0.0, R, step);
    }
  }
  *tau = acc / ((double)n_patch * n_patch);
  return ICS_OK;
}
