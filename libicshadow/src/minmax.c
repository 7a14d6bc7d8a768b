/* minmax.c — 1D min-max mipmaps (Chen, Baran, Durand, Jarosz 2011), their traversal (Fig. 5),
 * brute-force ray marching, a one-sided Jacobi SVD for the low-rank integrand (Sec. 3.2), and
 * epipolar rectification of a directional light's shadow map over a height-field scene.
 *
 * Method. Per row, a complete binary tree of (min, max) in Ahnentafel order (root 1, children
 * 2k and 2k+1), P = 2^ceil(log2 d) leaves at P .. 2P-1; rows with d < P are padded by repeating
 * the last sample, which leaves every node's (min, max) equal to the exact extremes over its
 * range clipped to [0, d). Built bottom-up, one level per pass (log2 P passes).
 * Traversal: Chen's Fig. 5 without recursion, start at the root; a node is fully lit if the
 * ray's largest height over the node's samples below gamma_end is < the node's min, fully
 * shadowed if the smallest is >= its max, otherwise we go to its left child. After a lit or
 * shadowed node: node + 1, then up while the node is a left child (even), and stop at the root
 * or once the node starts at or past gamma_end. Lit nodes that touch are merged into one run;
 * a run [s, e) adds prefix[e] - prefix[s] per term.
 *
 * Exactness of the classification: h(g) = beta0 + slope * g is a composition of rounded,
 * monotone operations, so fl(h) is monotone in g and its extremes over [g0, g1) are fl(h(g0))
 * and fl(h(g1 - 1)); both are compared with the float node values converted exactly to double,
 * the same comparisons the per-sample march makes. Hence the lit samples are identical.
 * (The build uses -std=c11, where GCC does not contract a*b+c into an FMA; an FMA would also be
 * monotone.)
 *
 * Error bound of the integral (term i, u = 2^-53, A = sum_{g<d} |Gamma(g)|): the compensated
 * prefix sums satisfy |P~[k] - P[k]| <= u |P[k]| + 2 d^2 u^2 A <= 1.01 u A for d <= 2^24
 * (Neumaier). A run's difference fl(P~[e] - P~[s]) is then within 2.02 u A + u (2.02 A) of the
 * exact run sum (|P~[e] - P~[s]| <= 2.02 A), i.e. 4.04 u A; adding nseg runs one after another
 * adds at most nseg u (sum of partial magnitudes) <= nseg u (1 + 4.04 nseg u) A. Total
 * <= (5 nseg + 1) u A (the +1 absorbs second-order terms). The plain march's error is
 * <= (gamma_end - 1) u A (recursive summation).
 *
 * SVD: Hestenes one-sided Jacobi on the columns of A (m >= n): for each pair (p, q) compute
 * alpha = |a_p|^2, beta = |a_q|^2, gamma = <a_p, a_q>; if |gamma| > eps sqrt(alpha beta), rotate
 * by the angle that zeroes gamma (Rutishauser's stable tan formula), apply the same rotation to
 * V. Sweep until no rotation happens (quadratic convergence, typically 6-10 sweeps for 64 x 64).
 * s_j = |a_j|, U_j = a_j / s_j, sorted descending. */
#include "icshadow/minmax.h"
#include "icshadow/constants.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "raybox.h"
#include "vec3.h"

struct ics_minmax {
  size_t rows, d, P;
  float *node; /* rows * 2P pairs (lo, hi); pair 0 of each row unused */
};

static size_t next_pow2(size_t d) {
  size_t p = 1;
  while (p < d) p <<= 1;
  return p;
}

ics_status ics_minmax_create(ics_minmax **out, const float *values, size_t rows, size_t d,
                             size_t stride) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  if (!values) return ICS_ERR_INVALID_ARG;
  if (rows == 0 || d == 0 || rows > ICS_MINMAX_MAX_ROWS || d > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  if (stride < d) return ICS_ERR_INVALID_ARG;
  /* the last row ends at (rows - 1) stride + d floats: must be addressable */
  if ((rows - 1) > (SIZE_MAX / sizeof(float) - d) / stride) return ICS_ERR_SIZE;
  size_t P = next_pow2(d);
  if (rows * 2 * P > ((size_t)1 << 31)) return ICS_ERR_SIZE;
  for (size_t r = 0; r < rows; r++)
    for (size_t g = 0; g < d; g++)
      if (isnan(values[r * stride + g])) return ICS_ERR_NAN;
  ics_minmax *t = malloc(sizeof *t);
  if (!t) return ICS_ERR_NOMEM;
  t->node = malloc(rows * 2 * P * 2 * sizeof(float));
  if (!t->node) {
    free(t);
    return ICS_ERR_NOMEM;
  }
  t->rows = rows;
  t->d = d;
  t->P = P;
  for (size_t r = 0; r < rows; r++) {
    float *nd = t->node + r * 4 * P;
    const float *v = values + r * stride;
    nd[0] = nd[1] = 0.0f; /* unused slot 0 */
    for (size_t g = 0; g < P; g++) {
      float x = v[g < d ? g : d - 1];
      nd[2 * (P + g)] = x;
      nd[2 * (P + g) + 1] = x;
    }
    /* one pass per level, from the leaves' parents up to the root */
    for (size_t first = P >> 1; first >= 1; first >>= 1) {
      for (size_t k = first; k < 2 * first; k++) {
        float l0 = nd[4 * k], h0 = nd[4 * k + 1], l1 = nd[4 * k + 2], h1 = nd[4 * k + 3];
        nd[2 * k] = l1 < l0 ? l1 : l0;
        nd[2 * k + 1] = h1 > h0 ? h1 : h0;
      }
    }
  }
  *out = t;
  return ICS_OK;
}

void ics_minmax_destroy(ics_minmax *t) {
  if (!t) return;
  free(t->node);
  free(t);
}

size_t ics_minmax_rows(const ics_minmax *t) { return t ? t->rows : 0; }
size_t ics_minmax_samples(const ics_minmax *t) { return t ? t->d : 0; }
size_t ics_minmax_leaves(const ics_minmax *t) { return t ? t->P : 0; }

ics_status ics_minmax_node(const ics_minmax *t, size_t row, size_t k, float *lo, float *hi) {
  if (!t || !lo || !hi) return ICS_ERR_INVALID_ARG;
  if (row >= t->rows || k == 0 || k >= 2 * t->P) return ICS_ERR_RANGE;
  const float *nd = t->node + row * 4 * t->P;
  *lo = nd[2 * k];
  *hi = nd[2 * k + 1];
  return ICS_OK;
}

/* Level width and start of node k (1 <= k < 2P). */
static void node_span(size_t P, size_t k, size_t *g0, size_t *w) {
  size_t level_first = 1;
  while (level_first * 2 <= k) level_first <<= 1;
  size_t width = P / level_first;
  *g0 = (k - level_first) * width;
  *w = width;
}

ics_status ics_minmax_node_range(const ics_minmax *t, size_t k, size_t *g0, size_t *g1) {
  if (!t || !g0 || !g1) return ICS_ERR_INVALID_ARG;
  if (k == 0 || k >= 2 * t->P) return ICS_ERR_RANGE;
  size_t a, w;
  node_span(t->P, k, &a, &w);
  size_t b = a + w;
  if (a > t->d) a = t->d;
  if (b > t->d) b = t->d;
  *g0 = a;
  *g1 = b;
  return ICS_OK;
}

static ics_status check_ray(const ics_minmax_ray *ray, size_t d) {
  if (!ray) return ICS_ERR_INVALID_ARG;
  if (isnan(ray->beta0) || isnan(ray->slope)) return ICS_ERR_NAN;
  if (isinf(ray->beta0) || isinf(ray->slope)) return ICS_ERR_INFINITE;
  if (ray->gamma_end > d) return ICS_ERR_RANGE;
  return ICS_OK;
}

static inline double ray_h(double b0, double slope, size_t g) { return b0 + slope * (double)g; }

/* The traversal, shared by segments and integrate. Runs are reported through the callback
 * state: seg (capacity maxseg) and/or prefix sums. */
typedef struct trav_out {
  size_t *seg;
  size_t maxseg, nseg;
  const double *prefix;
  size_t nterms, ld;
  double *out;
  unsigned char *cls;
} trav_out;

static inline void emit(trav_out *o, size_t s, size_t e) {
  if (o->seg && o->nseg < o->maxseg) {
    o->seg[2 * o->nseg] = s;
    o->seg[2 * o->nseg + 1] = e;
  }
  o->nseg++;
  if (o->prefix)
    for (size_t i = 0; i < o->nterms; i++) {
      const double *p = o->prefix + i * o->ld;
      o->out[i] += p[e] - p[s];
    }
}

static void traverse(const ics_minmax *t, size_t row, const ics_minmax_ray *ray, trav_out *o) {
  const size_t ge = ray->gamma_end;
  if (ge == 0) return;
  const float *nd = t->node + row * 4 * t->P;
  const double b0 = ray->beta0, sl = ray->slope;
  size_t node = 1, width = t->P, g0 = 0;
  size_t run_s = 0, run_e = 0; /* open lit run [run_s, run_e); empty when equal */
  do {
    size_t g1 = g0 + width;
    size_t ce = g1 < ge ? g1 : ge;
    double ha = ray_h(b0, sl, g0), hb = ray_h(b0, sl, ce - 1);
    double hmin = ha < hb ? ha : hb, hmax = ha < hb ? hb : ha;
    double lo = nd[2 * node], hi = nd[2 * node + 1];
    if (hmax < lo) { /* fully lit */
      if (o->cls) o->cls[node] = ICS_MINMAX_LIT;
      if (run_e == g0 && run_e > run_s) {
        run_e = ce;
      } else {
        if (run_e > run_s) emit(o, run_s, run_e);
        run_s = g0;
        run_e = ce;
      }
    } else if (hmin >= hi) { /* fully shadowed */
      if (o->cls) o->cls[node] = ICS_MINMAX_SHADOWED;
    } else { /* descend to the left child (leaves never get here: lo == hi) */
      if (o->cls) o->cls[node] = ICS_MINMAX_PARTIAL;
      node *= 2;
      width >>= 1;
      continue;
    }
    node += 1;
    g0 = g1;
    while (!(node & 1)) {
      node >>= 1;
      width <<= 1;
    }
  } while (node != 1 && g0 < ge);
  if (run_e > run_s) emit(o, run_s, run_e);
}

ics_status ics_minmax_segments(const ics_minmax *t, size_t row, const ics_minmax_ray *ray,
                               size_t *seg, size_t maxseg, size_t *nseg,
                               unsigned char *node_class) {
  if (!t || !nseg || (maxseg && !seg)) return ICS_ERR_INVALID_ARG;
  if (row >= t->rows) return ICS_ERR_RANGE;
  ics_status st = check_ray(ray, t->d);
  if (st != ICS_OK) return st;
  if (node_class) memset(node_class, 0, 2 * t->P);
  trav_out o = {seg, maxseg, 0, NULL, 0, 0, NULL, node_class};
  traverse(t, row, ray, &o);
  *nseg = o.nseg;
  return ICS_OK;
}

ics_status ics_minmax_integrate(const ics_minmax *t, size_t row, const ics_minmax_ray *ray,
                                const double *prefix, size_t nterms, size_t ld, double *out) {
  if (!t || !prefix || !out || nterms == 0 || ld < t->d + 1) return ICS_ERR_INVALID_ARG;
  if (row >= t->rows) return ICS_ERR_RANGE;
  ics_status st = check_ray(ray, t->d);
  if (st != ICS_OK) return st;
  for (size_t i = 0; i < nterms; i++) out[i] = 0.0;
  trav_out o = {NULL, 0, 0, prefix, nterms, ld, out, NULL};
  traverse(t, row, ray, &o);
  return ICS_OK;
}

ics_status ics_minmax_prefix(const double *terms, size_t nterms, size_t d, size_t ldt,
                             double *prefix, size_t ldp) {
  if (!terms || !prefix || nterms == 0) return ICS_ERR_INVALID_ARG;
  if (d == 0 || d > ICS_MINMAX_MAX_SAMPLES) return ICS_ERR_SIZE;
  if (ldt < d || ldp < d + 1) return ICS_ERR_INVALID_ARG;
  for (size_t i = 0; i < nterms; i++)
    for (size_t g = 0; g < d; g++)
      if (isnan(terms[i * ldt + g])) return ICS_ERR_NAN;
  for (size_t i = 0; i < nterms; i++) {
    const double *x = terms + i * ldt;
    double *p = prefix + i * ldp;
    double s = 0.0, c = 0.0;
    p[0] = 0.0;
    for (size_t g = 0; g < d; g++) {
      double y = x[g], tt = s + y;
      if (fabs(s) >= fabs(y))
        c += (s - tt) + y;
      else
        c += (y - tt) + s;
      s = tt;
      p[g + 1] = s + c;
    }
  }
  return ICS_OK;
}

ics_status ics_minmax_march(const float *row, size_t d, const ics_minmax_ray *ray,
                            const double *terms, size_t nterms, size_t ldt, double *out) {
  if (!row || !terms || !out || nterms == 0) return ICS_ERR_INVALID_ARG;
  if (d == 0 || d > ICS_MINMAX_MAX_SAMPLES) return ICS_ERR_SIZE;
  if (ldt < d) return ICS_ERR_INVALID_ARG;
  ics_status st = check_ray(ray, d);
  if (st != ICS_OK) return st;
  const double b0 = ray->beta0, sl = ray->slope;
  if (nterms == 4) { /* the paper's N = 4, unrolled */
    double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
    for (size_t g = 0; g < ray->gamma_end; g++) {
      if ((double)row[g] > ray_h(b0, sl, g)) {
        a0 += terms[g];
        a1 += terms[ldt + g];
        a2 += terms[2 * ldt + g];
        a3 += terms[3 * ldt + g];
      }
    }
    out[0] = a0;
    out[1] = a1;
    out[2] = a2;
    out[3] = a3;
    return ICS_OK;
  }
  for (size_t i = 0; i < nterms; i++) out[i] = 0.0;
  for (size_t g = 0; g < ray->gamma_end; g++)
    if ((double)row[g] > ray_h(b0, sl, g))
      for (size_t i = 0; i < nterms; i++) out[i] += terms[i * ldt + g];
  return ICS_OK;
}

/* ---- one-sided Jacobi SVD ------------------------------------------------------------- */
ics_status ics_svd(const double *A, size_t m, size_t n, double *U, double *s, double *V) {
  if (!A || !U || !s || !V) return ICS_ERR_INVALID_ARG;
  if (n == 0 || m < n || m > ((size_t)1 << 20) || n > 4096) return ICS_ERR_SIZE;
  for (size_t i = 0; i < m * n; i++) {
    if (isnan(A[i])) return ICS_ERR_NAN;
    if (isinf(A[i])) return ICS_ERR_INFINITE;
  }
  /* work on W = A 2^-e (columns rotated in place), stored in U: scaling by a power of two
   * (exact, apart from entries that become subnormal, far below u max|A|) puts the largest
   * entry in [1/2, 1), so the squared column norms neither overflow nor underflow */
  double amax = 0;
  for (size_t i = 0; i < m * n; i++) amax = fmax(amax, fabs(A[i]));
  int e = 0;
  if (amax > 0) frexp(amax, &e);
  for (size_t i = 0; i < m * n; i++) U[i] = ldexp(A[i], -e);
  for (size_t i = 0; i < n * n; i++) V[i] = 0.0;
  for (size_t i = 0; i < n; i++) V[i * n + i] = 1.0;
  const double eps = DBL_EPSILON;
  int converged = 0;
  for (int sweep = 0; sweep < 64 && !converged; sweep++) {
    converged = 1;
    for (size_t p = 0; p + 1 < n; p++)
      for (size_t q = p + 1; q < n; q++) {
        double al = 0, be = 0, ga = 0;
        for (size_t i = 0; i < m; i++) {
          double x = U[i * n + p], y = U[i * n + q];
          al += x * x;
          be += y * y;
          ga += x * y;
        }
        if (ga == 0.0 || fabs(ga) <= eps * sqrt(al) * sqrt(be)) continue;
        converged = 0;
        double zeta = (be - al) / (2.0 * ga);
        double tn = (zeta >= 0 ? 1.0 : -1.0) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
        double c = 1.0 / sqrt(1.0 + tn * tn), sn = c * tn;
        for (size_t i = 0; i < m; i++) {
          double x = U[i * n + p], y = U[i * n + q];
          U[i * n + p] = c * x - sn * y;
          U[i * n + q] = sn * x + c * y;
        }
        for (size_t i = 0; i < n; i++) {
          double x = V[i * n + p], y = V[i * n + q];
          V[i * n + p] = c * x - sn * y;
          V[i * n + q] = sn * x + c * y;
        }
      }
  }
  if (!converged) return ICS_ERR_RANGE;
  for (size_t j = 0; j < n; j++) {
    double nn = 0;
    for (size_t i = 0; i < m; i++) nn = hypot(nn, U[i * n + j]);
    s[j] = ldexp(nn, e);
    for (size_t i = 0; i < m; i++) U[i * n + j] = nn > 0 ? U[i * n + j] / nn : 0.0;
  }
  for (size_t j = 0; j < n; j++)
    if (isinf(s[j])) return ICS_ERR_INFINITE; /* a singular value above DBL_MAX */
  /* selection sort by descending s, swapping columns of U and V */
  for (size_t j = 0; j < n; j++) {
    size_t b = j;
    for (size_t k = j + 1; k < n; k++)
      if (s[k] > s[b]) b = k;
    if (b == j) continue;
    double tmp = s[j];
    s[j] = s[b];
    s[b] = tmp;
    for (size_t i = 0; i < m; i++) {
      tmp = U[i * n + j];
      U[i * n + j] = U[i * n + b];
      U[i * n + b] = tmp;
    }
    for (size_t i = 0; i < n; i++) {
      tmp = V[i * n + j];
      V[i * n + j] = V[i * n + b];
      V[i * n + b] = tmp;
    }
  }
  return ICS_OK;
}

ics_status ics_svd_truncate(const double *U, const double *s, const double *V, size_t m,
                            size_t n, size_t N, double *out) {
  if (!U || !s || !V || !out) return ICS_ERR_INVALID_ARG;
  if (n == 0 || m < n) return ICS_ERR_SIZE;
  if (N > n) return ICS_ERR_RANGE;
  for (size_t i = 0; i < m; i++)
    for (size_t j = 0; j < n; j++) {
      double acc = 0;
      for (size_t k = 0; k < N; k++) acc += s[k] * U[i * n + k] * V[j * n + k];
      out[i * n + j] = acc;
    }
  return ICS_OK;
}

/* ---- epipolar rectification --------------------------------------------------------- */
ics_status ics_epi_frame_init(ics_epi_frame *f, const double eye[3], const double to_light[3],
                              size_t rows, size_t d, double dgamma) {
  if (!f || !eye || !to_light) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++) {
    if (isnan(eye[i]) || isnan(to_light[i])) return ICS_ERR_NAN;
    if (isinf(eye[i]) || isinf(to_light[i])) return ICS_ERR_INFINITE;
  }
  if (isnan(dgamma)) return ICS_ERR_NAN;
  if (!(dgamma > 0) || isinf(dgamma)) return ICS_ERR_RANGE;
  if (rows == 0 || d == 0 || rows > ICS_MINMAX_MAX_ROWS || d > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  double nl = sqrt(ics_dot3(to_light, to_light));
  if (!(nl > 0)) return ICS_ERR_INVALID_ARG;
  memset(f, 0, sizeof *f);
  for (int i = 0; i < 3; i++) {
    f->eye[i] = eye[i];
    f->L[i] = to_light[i] / nl;
  }
  /* U: the world axis least aligned with L, made perpendicular; V = L x U */
  double a[3] = {0, 0, 0};
  int k = 0;
  for (int i = 1; i < 3; i++)
    if (fabs(f->L[i]) < fabs(f->L[k])) k = i;
  a[k] = 1.0;
  double pr = ics_dot3(a, f->L);
  for (int i = 0; i < 3; i++) f->U[i] = a[i] - pr * f->L[i];
  double nu = sqrt(ics_dot3(f->U, f->U));
  for (int i = 0; i < 3; i++) f->U[i] /= nu;
  f->V[0] = f->L[1] * f->U[2] - f->L[2] * f->U[1];
  f->V[1] = f->L[2] * f->U[0] - f->L[0] * f->U[2];
  f->V[2] = f->L[0] * f->U[1] - f->L[1] * f->U[0];
  f->eu = ics_dot3(eye, f->U);
  f->ev = ics_dot3(eye, f->V);
  f->depth_eye = -ics_dot3(eye, f->L);
  f->dgamma = dgamma;
  f->rows = rows;
  f->d = d;
  return ICS_OK;
}

ics_status ics_epi_locate(const ics_epi_frame *f, const double p[3], double *alpha,
                          double *gamma, double *depth) {
  if (!f || !p || !alpha || !gamma || !depth) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++)
    if (isnan(p[i])) return ICS_ERR_NAN;
  /* relative to the eye first: the slice of E + s v is then exact up to rounding of s v */
  double r[3] = {p[0] - f->eye[0], p[1] - f->eye[1], p[2] - f->eye[2]};
  double du = ics_dot3(r, f->U), dv = ics_dot3(r, f->V);
  double a = atan2(dv, du);
  if (a < 0) a += 2 * ICS_PI;
  *alpha = a;
  *gamma = hypot(du, dv) / f->dgamma;
  *depth = f->depth_eye - ics_dot3(r, f->L);
  return ICS_OK;
}

ics_status ics_epi_ray(const ics_epi_frame *f, const double dir[3], double *alpha, size_t *row,
                       ics_minmax_ray *ray) {
  if (!f || !dir || !alpha || !row || !ray) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3; i++) {
    if (isnan(dir[i])) return ICS_ERR_NAN;
    if (isinf(dir[i])) return ICS_ERR_INFINITE;
  }
  double du = ics_dot3(dir, f->U), dv = ics_dot3(dir, f->V), dl = ics_dot3(dir, f->L);
  double perp = hypot(du, dv);
  double n = sqrt(du * du + dv * dv + dl * dl);
  if (!(perp > 1e-12 * n)) return ICS_ERR_RANGE;
  double a = atan2(dv, du);
  if (a < 0) a += 2 * ICS_PI;
  *alpha = a;
  double x = a / (2 * ICS_PI) * (double)f->rows; /* row r is centred at x = r + 1/2 */
  size_t r = (size_t)floor(x);
  if (r >= f->rows) r = f->rows - 1;
  *row = r;
  ray->beta0 = f->depth_eye;
  ray->slope = -f->dgamma * dl / perp;
  return ICS_OK;
}

ics_status ics_epi_ray_dir(const ics_epi_frame *f, size_t row, double beta, double dir[3]) {
  if (!f || !dir) return ICS_ERR_INVALID_ARG;
  if (isnan(beta)) return ICS_ERR_NAN;
  if (row >= f->rows) return ICS_ERR_RANGE;
  if (!(beta > 0 && beta < ICS_PI)) return ICS_ERR_RANGE;
  double a = 2 * ICS_PI * ((double)row + 0.5) / (double)f->rows;
  double ca = cos(a), sa = sin(a), sb = sin(beta), cb = cos(beta);
  for (int i = 0; i < 3; i++) dir[i] = sb * (ca * f->U[i] + sa * f->V[i]) + cb * f->L[i];
  return ICS_OK;
}

ics_status ics_epi_rectify(const ics_epi_frame *f, const float *smap, size_t w, size_t h,
                           double u0, double v0, double texel, float *out) {
  if (!f || !smap || !out) return ICS_ERR_INVALID_ARG;
  if (w == 0 || h == 0 || w > ICS_MINMAX_MAX_SAMPLES || h > ICS_MINMAX_MAX_SAMPLES)
    return ICS_ERR_SIZE;
  if (isnan(u0) || isnan(v0) || isnan(texel)) return ICS_ERR_NAN;
  if (!(texel > 0) || isinf(texel) || isinf(u0) || isinf(v0)) return ICS_ERR_RANGE;
  for (size_t r = 0; r < f->rows; r++) {
    double a = 2 * ICS_PI * ((double)r + 0.5) / (double)f->rows;
    double ca = cos(a), sa = sin(a);
    for (size_t g = 0; g < f->d; g++) {
      double rad = (double)g * f->dgamma;
      double x = (f->eu + rad * ca - u0) / texel, y = (f->ev + rad * sa - v0) / texel;
      float val = INFINITY;
      if (x >= 0 && y >= 0 && x < (double)w && y < (double)h)
        val = smap[(size_t)y * w + (size_t)x];
      out[r * f->d + g] = val;
    }
  }
  return ICS_OK;
}

/* ---- synthetic height-field scene ---------------------------------------------------- */
void ics_hf_scene_default(ics_hf_scene *s) {
  if (!s) return;
  static const double boxes[][5] = {
      {-4.5, -3.0, -4.0, -2.5, 2.0}, {-1.0, 0.2, -5.0, -4.2, 2.5}, {2.0, 3.5, -3.0, -1.0, 1.2},
      {-3.0, -2.6, 0.5, 4.0, 1.8},   {0.5, 1.0, 1.0, 1.5, 2.2},    {3.0, 5.5, 2.5, 3.0, 0.8},
  };
  static const double caps[][4] = {
      {-1.5, -0.5, -1.0, 1.6}, {1.5, -1.2, 3.5, 2.0}, {4.0, 0.0, -4.5, 0.9}, {-4.5, -0.3, 4.5, 1.1},
  };
  memset(s, 0, sizeof *s);
  s->nboxes = sizeof boxes / sizeof boxes[0];
  s->ncaps = sizeof caps / sizeof caps[0];
  for (size_t i = 0; i < s->nboxes; i++) {
    for (int j = 0; j < 4; j++) s->box[i][j] = boxes[i][j];
    s->box_h[i] = boxes[i][4];
  }
  for (size_t i = 0; i < s->ncaps; i++)
    for (int j = 0; j < 4; j++) s->cap[i][j] = caps[i][j];
}

double ics_hf_scene_hit(const ics_hf_scene *s, const double o[3], const double dir[3],
                        double tmin) {
  if (!s || !o || !dir) return NAN;
  double best = INFINITY;
  if (dir[1] != 0) { /* the plane y = 0 */
    double t = -o[1] / dir[1];
    if (t > tmin) best = t;
  }
  for (size_t b = 0; b < s->nboxes; b++) { /* slabs */
    double lo[3] = {s->box[b][0], 0.0, s->box[b][2]}, hi[3] = {s->box[b][1], s->box_h[b], s->box[b][3]};
    double t0 = -INFINITY, t1 = INFINITY;
    if (!ics_ray_box_clip(o, dir, lo, hi, &t0, &t1)) continue;
    double t = t0 > tmin ? t0 : (t1 > tmin ? t1 : INFINITY);
    if (t < best) best = t;
  }
  for (size_t c = 0; c < s->ncaps; c++) { /* sphere, the part with y >= 0 */
    double oc[3] = {o[0] - s->cap[c][0], o[1] - s->cap[c][1], o[2] - s->cap[c][2]};
    double rr = s->cap[c][3];
    double A = ics_dot3(dir, dir), B = ics_dot3(oc, dir), C = ics_dot3(oc, oc) - rr * rr;
    double disc = B * B - A * C;
    if (disc < 0) continue;
    double sq = sqrt(disc);
    double ts[2] = {(-B - sq) / A, (-B + sq) / A};
    for (int j = 0; j < 2; j++) {
      double t = ts[j];
      if (!(t > tmin) || t >= best) continue;
      if (o[1] + t * dir[1] < 0) continue;
      best = t;
      break;
    }
  }
  return best;
}

ics_status ics_hf_shadow_map(const ics_hf_scene *s, const ics_epi_frame *f, size_t w,
                             double half, float *smap) {
  if (!s || !f || !smap) return ICS_ERR_INVALID_ARG;
  if (w == 0 || w > ICS_MINMAX_MAX_SAMPLES) return ICS_ERR_SIZE;
  if (isnan(half)) return ICS_ERR_NAN;
  if (!(half > 0) || isinf(half)) return ICS_ERR_RANGE;
  double texel = 2 * half / (double)w, u0 = f->eu - half, v0 = f->ev - half;
  /* light rays start on the plane depth = start_depth (above every shape) and go along -L */
  double top = 0;
  for (size_t b = 0; b < s->nboxes; b++)
    if (s->box_h[b] > top) top = s->box_h[b];
  for (size_t c = 0; c < s->ncaps; c++)
    if (s->cap[c][1] + s->cap[c][3] > top) top = s->cap[c][1] + s->cap[c][3];
  double dir[3] = {-f->L[0], -f->L[1], -f->L[2]};
  for (size_t j = 0; j < w; j++)
    for (size_t i = 0; i < w; i++) {
      double u = u0 + ((double)i + 0.5) * texel, v = v0 + ((double)j + 0.5) * texel;
      double o[3];
      for (int k = 0; k < 3; k++) o[k] = u * f->U[k] + v * f->V[k];
      /* move the origin along L until it is above the scene's top (y > top) */
      double lift = 0;
      if (f->L[1] > 0) lift = (top + 1.0 - o[1]) / f->L[1];
      for (int k = 0; k < 3; k++) o[k] += lift * f->L[k];
      double t = ics_hf_scene_hit(s, o, dir, 0.0);
      smap[j * w + i] = isinf(t) ? INFINITY : (float)(-ics_dot3(o, f->L) + t);
    }
  return ICS_OK;
}
