/* minmax.c — 1D min-max mipmaps (Chen, Baran, Durand, Jarosz 2011), their traversal (Fig. 5),
 * the prefix sums they integrate and brute-force ray marching (see icshadow/minmax.h).
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
 */
#include "icshadow/minmax.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
