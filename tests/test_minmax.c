/* test_minmax.c — 1D min-max mipmaps (libicshadow/src/minmax.c).
 * References are computed here independently of the code under test: per-node extremes by
 * scanning the node's range; lit samples by the per-sample test S > beta0 + slope*g; sums in
 * double-double (error ~ d u^2 A, far below the bounds checked). Properties: tree nodes are
 * tight bounds; traversal == brute force (exactly with integer integrands, within the stated
 * (5 nseg + 1) u A otherwise), including grazing rays, d = 1 and non-powers of two; SVD
 * reconstruction, orthogonality, Eckart-Young tail, exact at full rank; rectification puts a
 * camera ray's samples in one row. Bad input gives the documented status codes. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

static long irand(long lo, long hi) {
  return lo + (long)(test_rng_u64() % (uint64_t)(hi - lo + 1));
}

static const double U_ = 0x1p-53;

/* double-double accumulation */
typedef struct { double hi, lo; } dd;
static void dd_add(dd *a, double x) {
  double s = a->hi + x, bp = s - a->hi, e = (a->hi - (s - bp)) + (x - bp);
  a->hi = s;
  a->lo += e;
}
static double dd_val(dd a) { return a.hi + a.lo; }

static size_t pow2_at_least(size_t d) {
  size_t p = 1;
  while (p < d) p *= 2;
  return p;
}

/* ---- tree: ranges and tight bounds ---- */
static void test_tree(size_t d, int quantized) {
  size_t rows = 3, stride = d + 3;
  float *v = malloc(rows * stride * sizeof(float));
  for (size_t i = 0; i < rows * stride; i++)
    v[i] = quantized ? (float)irand(-3, 3) : (float)(test_rng_unit() * 200 - 100);
  ics_minmax *t = NULL;
  ics_status st = ics_minmax_create(&t, v, rows, d, stride);
  CHECK(st == ICS_OK, "create d=%zu: %s", d, ics_status_str(st));
  if (st != ICS_OK) {
    free(v);
    return;
  }
  size_t P = pow2_at_least(d);
  CHECK(ics_minmax_leaves(t) == P, "d=%zu: leaves %zu, expected %zu", d, ics_minmax_leaves(t), P);
  int bad_range = 0, bad_bound = 0, bad_tight = 0;
  for (size_t k = 1; k < 2 * P; k++) {
    size_t depth = 0;
    while (((size_t)1 << (depth + 1)) <= k) depth++;
    size_t width = P >> depth, a = (k - ((size_t)1 << depth)) * width, b = a + width;
    if (a > d) a = d;
    if (b > d) b = d;
    size_t g0, g1;
    ics_minmax_node_range(t, k, &g0, &g1);
    if (g0 != a || g1 != b) bad_range++;
    if (a == b) continue;
    for (size_t r = 0; r < rows; r++) {
      float lo, hi;
      ics_minmax_node(t, r, k, &lo, &hi);
      float mn = INFINITY, mx = -INFINITY;
      for (size_t g = a; g < b; g++) {
        float x = v[r * stride + g];
        if (x < lo || x > hi) bad_bound++;
        if (x < mn) mn = x;
        if (x > mx) mx = x;
      }
      if (lo != mn || hi != mx) bad_tight++;
    }
  }
  CHECK(bad_range == 0, "d=%zu: %d node ranges differ from the Ahnentafel layout", d, bad_range);
  CHECK(bad_bound == 0, "d=%zu: %d samples outside their node's [min, max]", d, bad_bound);
  CHECK(bad_tight == 0, "d=%zu: %d nodes whose min/max are not the true extremes", d, bad_tight);
  ics_minmax_destroy(t);
  free(v);
}

/* ---- traversal vs brute force ---- */
typedef struct {
  size_t d, rows, stride, P;
  float *v;
  double *terms_int, *terms_real; /* 4 x d each */
  double *pre_int, *pre_real;     /* 4 x (d+1) */
  ics_minmax *t;
} rowset;

static int is_lit(const float *row, double b0, double sl, size_t g) {
  return (double)row[g] > b0 + sl * (double)g;
}

static int check_ray(rowset *s, size_t r, ics_minmax_ray ray, const char *what, int *fails) {
  const float *row = s->v + r * s->stride;
  size_t d = s->d;
  /* reference runs */
  size_t nref = 0;
  size_t *ref = malloc(2 * (d + 1) * sizeof(size_t));
  for (size_t g = 0; g < ray.gamma_end; g++) {
    if (!is_lit(row, ray.beta0, ray.slope, g)) continue;
    if (nref && ref[2 * nref - 1] == g)
      ref[2 * nref - 1] = g + 1;
    else {
      ref[2 * nref] = g;
      ref[2 * nref + 1] = g + 1;
      nref++;
    }
  }
  size_t *seg = malloc(2 * (d + 1) * sizeof(size_t)), nseg = 0;
  ics_status st = ics_minmax_segments(s->t, r, &ray, seg, d + 1, &nseg, NULL);
  int ok = st == ICS_OK && nseg == nref && !memcmp(seg, ref, 2 * nref * sizeof(size_t));
  if (!ok && (*fails)++ < 5)
    CHECK(ok, "%s: d=%zu row %zu beta0=%a slope=%a end=%zu: %zu runs, reference %zu (%s)", what,
          d, r, ray.beta0, ray.slope, ray.gamma_end, nseg, nref, ics_status_str(st));
  /* integer integrand: tree and march exact */
  double out[4], mar[4];
  ics_minmax_integrate(s->t, r, &ray, s->pre_int, 4, d + 1, out);
  ics_minmax_march(row, d, &ray, s->terms_int, 4, d, mar);
  for (int i = 0; i < 4; i++) {
    double exact = 0;
    for (size_t j = 0; j < nref; j++)
      for (size_t g = ref[2 * j]; g < ref[2 * j + 1]; g++) exact += s->terms_int[i * d + g];
    if ((out[i] != exact || mar[i] != exact) && (*fails)++ < 5)
      CHECK(0, "%s: integer integrand term %d: tree %.17g march %.17g exact %.17g", what, i,
            out[i], mar[i], exact);
  }
  /* real integrand: the documented bound */
  ics_minmax_integrate(s->t, r, &ray, s->pre_real, 4, d + 1, out);
  ics_minmax_march(row, d, &ray, s->terms_real, 4, d, mar);
  for (int i = 0; i < 4; i++) {
    dd acc = {0, 0};
    double A = 0;
    for (size_t g = 0; g < d; g++) A += fabs(s->terms_real[i * d + g]);
    for (size_t j = 0; j < nref; j++)
      for (size_t g = ref[2 * j]; g < ref[2 * j + 1]; g++) dd_add(&acc, s->terms_real[i * d + g]);
    double ex = dd_val(acc);
    double tol_tree = (5.0 * (double)nref + 1.0) * U_ * A * (1 + 1e-6);
    double tol_march = (ray.gamma_end ? (double)(ray.gamma_end - 1) : 0.0) * U_ * A * (1 + 1e-6);
    if (fabs(out[i] - ex) > tol_tree && (*fails)++ < 5)
      CHECK(0, "%s: tree term %d: |%.17g - %.17g| = %g > (5 nseg + 1) u A = %g", what, i, out[i],
            ex, fabs(out[i] - ex), tol_tree);
    if (fabs(mar[i] - ex) > tol_march && (*fails)++ < 5)
      CHECK(0, "%s: march term %d: |%.17g - %.17g| > %g", what, i, mar[i], ex, tol_march);
  }
  free(ref);
  free(seg);
  return ok;
}

static void rowset_init(rowset *s, size_t d, int quantized) {
  s->d = d;
  s->rows = 2;
  s->stride = d + 1;
  s->P = pow2_at_least(d);
  s->v = malloc(s->rows * s->stride * sizeof(float));
  /* quantized: integers / 16 in [-4, 4] (many ties); else a random walk (long lit runs) */
  for (size_t r = 0; r < s->rows; r++) {
    double w = 0;
    for (size_t g = 0; g < s->stride; g++) {
      w += test_rng_unit() - 0.5;
      s->v[r * s->stride + g] = quantized ? (float)irand(-64, 64) / 16.0f : (float)w;
    }
  }
  s->terms_int = malloc(4 * d * sizeof(double));
  s->terms_real = malloc(4 * d * sizeof(double));
  s->pre_int = malloc(4 * (d + 1) * sizeof(double));
  s->pre_real = malloc(4 * (d + 1) * sizeof(double));
  for (size_t i = 0; i < 4 * d; i++) {
    s->terms_int[i] = (double)irand(-1000, 1000);
    /* mixed signs and magnitudes, like singular vectors */
    s->terms_real[i] = (test_rng_unit() - 0.3) * exp(4 * test_rng_unit());
  }
  CHECK(ics_minmax_prefix(s->terms_int, 4, d, d, s->pre_int, d + 1) == ICS_OK, "prefix");
  CHECK(ics_minmax_prefix(s->terms_real, 4, d, d, s->pre_real, d + 1) == ICS_OK, "prefix");
  CHECK(ics_minmax_create(&s->t, s->v, s->rows, d, s->stride) == ICS_OK, "create d=%zu", d);
}

static void rowset_free(rowset *s) {
  ics_minmax_destroy(s->t);
  free(s->v);
  free(s->terms_int);
  free(s->terms_real);
  free(s->pre_int);
  free(s->pre_real);
}

static void test_traversal(size_t d, int quantized, int nrays) {
  rowset s;
  rowset_init(&s, d, quantized);
  int fails = 0, checked = 0, grazing = 0;
  for (int k = 0; k < nrays; k++) {
    size_t r = (size_t)irand(0, (long)s.rows - 1);
    const float *row = s.v + r * s.stride;
    ics_minmax_ray ray;
    ray.gamma_end = (size_t)irand(0, (long)d);
    if (k % 4 == 0) ray.gamma_end = d;
    int kind = k % 5;
    if (kind == 0) { /* flat ray at a random height */
      ray.slope = 0;
      ray.beta0 = quantized ? irand(-70, 70) / 16.0 : (test_rng_unit() - 0.5) * 8;
    } else if (kind == 1 || kind == 2) { /* flat ray exactly at a node's min or max */
      size_t node = (size_t)irand(1, (long)(2 * s.P - 1));
      size_t g0, g1;
      ics_minmax_node_range(s.t, node, &g0, &g1);
      if (g0 == g1) node = 1;
      float lo, hi;
      ics_minmax_node(s.t, r, node, &lo, &hi);
      ray.slope = 0;
      ray.beta0 = kind == 1 ? lo : hi;
      grazing++;
    } else if (kind == 3) { /* sloped ray through a sample exactly (dyadic, exact arithmetic) */
      size_t gs = (size_t)irand(0, (long)d - 1);
      ray.slope = (double)irand(-512, 512) / 1024.0 / (double)s.P;
      ray.beta0 = (double)row[gs] - ray.slope * (double)gs;
      CHECK(ray.beta0 + ray.slope * (double)gs == (double)row[gs], "grazing ray not exact");
      grazing++;
    } else { /* random sloped ray */
      ray.slope = (test_rng_unit() - 0.5) * 8.0 / (double)d;
      ray.beta0 = (test_rng_unit() - 0.5) * 8;
    }
    check_ray(&s, r, ray, kind == 1 || kind == 2 || kind == 3 ? "grazing" : "random", &fails);
    checked++;
  }
  CHECK(fails == 0, "d=%zu: %d of %d rays disagree with brute force", d, fails, checked);
  CHECK(grazing > 0 || nrays < 2, "no grazing rays");
  rowset_free(&s);
}

/* the traversal must not visit more nodes than needed on a long lit run */
static void test_node_classes(void) {
  float v[8] = {5, 5, 5, 5, 1, 1, 5, 5};
  ics_minmax *t;
  CHECK(ics_minmax_create(&t, v, 1, 8, 8) == ICS_OK, "create");
  unsigned char cls[16];
  size_t seg[8], nseg;
  ics_minmax_ray ray = {3.0, 0.0, 8};
  ics_minmax_segments(t, 0, &ray, seg, 4, &nseg, cls);
  /* root partial; [0,4) lit (node 2); node 3 partial; [4,6) shadowed (node 6); [6,8) lit (7) */
  CHECK(nseg == 2 && seg[0] == 0 && seg[1] == 4 && seg[2] == 6 && seg[3] == 8,
        "runs %zu: [%zu,%zu) [%zu,%zu)", nseg, seg[0], seg[1], seg[2], seg[3]);
  CHECK(cls[1] == ICS_MINMAX_PARTIAL && cls[2] == ICS_MINMAX_LIT && cls[3] == ICS_MINMAX_PARTIAL &&
            cls[6] == ICS_MINMAX_SHADOWED && cls[7] == ICS_MINMAX_LIT && cls[4] == 0 && cls[8] == 0,
        "node classes %d %d %d %d %d", cls[1], cls[2], cls[3], cls[6], cls[7]);
  /* a ray ending at 5 stops before node 7 */
  ray.gamma_end = 5;
  ics_minmax_segments(t, 0, &ray, seg, 4, &nseg, cls);
  CHECK(nseg == 1 && seg[1] == 4 && cls[7] == 0, "ray end 5: %zu runs, node 7 class %d", nseg, cls[7]);
  /* beta exactly at the min of node 3 (1.0): shadowed there, lit elsewhere (equality = shadow) */
  ray.beta0 = 1.0;
  ray.gamma_end = 8;
  ics_minmax_segments(t, 0, &ray, seg, 4, &nseg, cls);
  CHECK(nseg == 2 && seg[1] == 4 && seg[2] == 6, "beta = min: runs %zu", nseg);
  ics_minmax_destroy(t);
}

/* ---- SVD ---- */
static void random_orthogonal(size_t n, double *Q) { /* product of Householder reflections */
  for (size_t i = 0; i < n * n; i++) Q[i] = 0;
  for (size_t i = 0; i < n; i++) Q[i * n + i] = 1;
  double *v = malloc(n * sizeof(double));
  for (size_t k = 0; k < n; k++) {
    double nn = 0;
    for (size_t i = 0; i < n; i++) {
      v[i] = test_rng_unit() - 0.5;
      nn += v[i] * v[i];
    }
    /* Q = Q (I - 2 v v^T / nn) */
    for (size_t r = 0; r < n; r++) {
      double dot = 0;
      for (size_t i = 0; i < n; i++) dot += Q[r * n + i] * v[i];
      for (size_t i = 0; i < n; i++) Q[r * n + i] -= 2 * dot / nn * v[i];
    }
  }
  free(v);
}

static void test_svd_case(size_t m, size_t n, int known) {
  double *A = malloc(m * n * sizeof(double)), *U = malloc(m * n * sizeof(double));
  double *s = malloc(n * sizeof(double)), *V = malloc(n * n * sizeof(double));
  double *R = malloc(m * n * sizeof(double)), *sk = malloc(n * sizeof(double));
  if (known) { /* A = Q1[:, :n] diag(sk) Q2^T with known singular values 2^-k spread */
    double *Q1 = malloc(m * m * sizeof(double)), *Q2 = malloc(n * n * sizeof(double));
    random_orthogonal(m, Q1);
    random_orthogonal(n, Q2);
    for (size_t k = 0; k < n; k++) sk[k] = ldexp(1.0, -(int)(k % 20)) * (1 + 0.01 * (double)k);
    for (size_t k = 0; k < n; k++) /* sort descending */
      for (size_t j = k + 1; j < n; j++)
        if (sk[j] > sk[k]) {
          double tmp = sk[j];
          sk[j] = sk[k];
          sk[k] = tmp;
        }
    for (size_t i = 0; i < m; i++)
      for (size_t j = 0; j < n; j++) {
        double acc = 0;
        for (size_t k = 0; k < n; k++) acc += Q1[i * m + k] * sk[k] * Q2[j * n + k];
        A[i * n + j] = acc;
      }
    free(Q1);
    free(Q2);
  } else {
    for (size_t i = 0; i < m * n; i++) A[i] = test_rng_unit() - 0.5;
  }
  ics_status st = ics_svd(A, m, n, U, s, V);
  CHECK(st == ICS_OK, "svd %zux%zu: %s", m, n, ics_status_str(st));
  double fa = 0;
  for (size_t i = 0; i < m * n; i++) fa += A[i] * A[i];
  fa = sqrt(fa);
  double bound = 10.0 * (double)n * U_;
  /* full reconstruction */
  ics_svd_truncate(U, s, V, m, n, n, R);
  double fe = 0;
  for (size_t i = 0; i < m * n; i++) fe += (A[i] - R[i]) * (A[i] - R[i]);
  fe = sqrt(fe);
  CHECK(fe <= bound * fa, "svd %zux%zu: ||A - USV'||_F / ||A||_F = %g > %g", m, n, fe / fa, bound);
  /* orthogonality */
  double eu = 0, ev = 0;
  for (size_t p = 0; p < n; p++)
    for (size_t q = 0; q < n; q++) {
      double du = 0, dv = 0;
      for (size_t i = 0; i < m; i++) du += U[i * n + p] * U[i * n + q];
      for (size_t i = 0; i < n; i++) dv += V[i * n + p] * V[i * n + q];
      eu = fmax(eu, fabs(du - (p == q)));
      ev = fmax(ev, fabs(dv - (p == q)));
    }
  CHECK(eu <= bound && ev <= bound, "svd %zux%zu: |U'U - I| = %g, |V'V - I| = %g > %g", m, n, eu,
        ev, bound);
  /* descending, and Eckart-Young: ||A - A_N||_F = sqrt(sum_{k>=N} s_k^2), non-increasing */
  int desc = 1;
  for (size_t k = 1; k < n; k++)
    if (s[k] > s[k - 1]) desc = 0;
  CHECK(desc, "svd %zux%zu: singular values not descending", m, n);
  double prev = INFINITY;
  for (size_t N = 0; N <= n; N++) {
    ics_svd_truncate(U, s, V, m, n, N, R);
    double e = 0, tail = 0;
    for (size_t i = 0; i < m * n; i++) e += (A[i] - R[i]) * (A[i] - R[i]);
    for (size_t k = N; k < n; k++) tail += s[k] * s[k];
    e = sqrt(e);
    tail = sqrt(tail);
    CHECK(fabs(e - tail) <= 2 * bound * fa, "svd %zux%zu N=%zu: error %g vs tail %g", m, n, N, e, tail);
    CHECK(e <= prev + bound * fa, "svd %zux%zu: error grows at N=%zu", m, n, N);
    prev = e;
  }
  if (known)
    for (size_t k = 0; k < n; k++)
      CHECK(fabs(s[k] - sk[k]) <= bound * sk[0], "svd %zux%zu: s[%zu] = %.17g, expected %.17g", m, n,
            k, s[k], sk[k]);
  free(A);
  free(U);
  free(s);
  free(V);
  free(R);
  free(sk);
}

static void test_svd(void) {
  test_svd_case(1, 1, 0);
  test_svd_case(5, 1, 0);
  test_svd_case(12, 8, 0);
  test_svd_case(30, 30, 1);
  test_svd_case(64, 64, 0);
  test_svd_case(80, 40, 1);
  /* exactly rank 2: A_2 reconstructs it */
  size_t m = 20, n = 10;
  double A[200], U[200], s[10], V[100], R[200];
  for (size_t i = 0; i < m; i++)
    for (size_t j = 0; j < n; j++)
      A[i * n + j] = sin(0.3 * (double)i) * cos(0.7 * (double)j) + 0.5 * (double)i * exp(-0.1 * (double)j);
  CHECK(ics_svd(A, m, n, U, s, V) == ICS_OK, "svd rank 2");
  ics_svd_truncate(U, s, V, m, n, 2, R);
  double fa = 0, fe = 0;
  for (size_t i = 0; i < m * n; i++) {
    fa += A[i] * A[i];
    fe += (A[i] - R[i]) * (A[i] - R[i]);
  }
  CHECK(sqrt(fe) <= 10.0 * (double)n * U_ * sqrt(fa), "rank-2: A_2 error %g", sqrt(fe / fa));
  CHECK(s[2] <= 10.0 * (double)n * U_ * s[0], "rank-2: s[2]/s[0] = %g", s[2] / s[0]);
}

/* ---- rectification ---- */
static void test_rectification(void) {
  ics_epipolar_frame f;
  double eye[3] = {0.3, 3.0, 9.0}, L[3] = {0.8, 0.45, -0.5};
  size_t rows = 360, d = 512;
  CHECK(ics_epipolar_frame_init(&f, eye, L, rows, d, 0.05) == ICS_OK, "frame");
  /* basis orthonormal */
  double dUV = f.U[0] * f.V[0] + f.U[1] * f.V[1] + f.U[2] * f.V[2];
  double dUL = f.U[0] * f.L[0] + f.U[1] * f.L[1] + f.U[2] * f.L[2];
  CHECK(fabs(dUV) < 1e-15 && fabs(dUL) < 1e-15, "basis not orthogonal");
  int bad_row = 0, bad_depth = 0, rays = 0;
  /* pinhole camera looking along -z, 40 x 30 pixels, 60 degree field of view */
  for (int j = 0; j < 30; j++)
    for (int i = 0; i < 40; i++) {
      double x = ((i + 0.5) / 40 - 0.5) * 2 * tan(0.5236) * 4.0 / 3.0;
      double y = ((j + 0.5) / 30 - 0.5) * 2 * tan(0.5236) - 0.3;
      double dir[3] = {x, y, -1.0};
      double alpha;
      size_t row;
      ics_minmax_ray ray;
      if (ics_epipolar_ray(&f, dir, &alpha, &row, &ray) != ICS_OK) continue;
      rays++;
      for (int k = 1; k <= 50; k++) {
        double sdist = 0.37 * k;
        double p[3] = {eye[0] + sdist * dir[0], eye[1] + sdist * dir[1], eye[2] + sdist * dir[2]};
        double a, g, dep;
        ics_epipolar_locate(&f, p, &a, &g, &dep);
        double da = fabs(a - alpha);
        if (da > ICS_PI) da = fabs(da - 2 * ICS_PI);
        size_t prow = (size_t)floor(a / (2 * ICS_PI) * (double)rows);
        if (prow >= rows) prow = rows - 1;
        if (da > 1e-13 || prow != row) bad_row++;
        double hl = ray.beta0 + ray.slope * g;
        if (fabs(hl - dep) > 1e-13 * (fabs(dep) + fabs(ray.slope * g) + fabs(ray.beta0)))
          bad_depth++;
      }
    }
  CHECK(rays == 1200, "only %d of 1200 camera rays usable", rays);
  CHECK(bad_row == 0, "%d ray samples map to another slice/row than their ray", bad_row);
  CHECK(bad_depth == 0, "%d ray samples off the ray's line h(gamma)", bad_depth);

  /* rectify a map whose texel holds its own index: each sample must read the texel that
   * contains its light-plane point, computed here from the frame's basis */
  size_t w = 64;
  double half = 20.0, texel = 2 * half / (double)w, u0 = f.eu - half, v0 = f.ev - half;
  float *smap = malloc(w * w * sizeof(float)), *rect = malloc(rows * d * sizeof(float));
  for (size_t i = 0; i < w * w; i++) smap[i] = (float)i;
  CHECK(ics_epipolar_rectify(&f, smap, w, w, u0, v0, texel, rect) == ICS_OK, "rectify");
  int bad_tex = 0, outside = 0;
  for (size_t r = 0; r < rows; r += 7)
    for (size_t g = 0; g < d; g += 3) {
      double dir[3];
      ics_epipolar_ray_dir(&f, r, ICS_PI / 2, dir); /* perpendicular to L: radial */
      double p[3] = {eye[0] + g * 0.05 * dir[0], eye[1] + g * 0.05 * dir[1], eye[2] + g * 0.05 * dir[2]};
      double pu = p[0] * f.U[0] + p[1] * f.U[1] + p[2] * f.U[2];
      double pv = p[0] * f.V[0] + p[1] * f.V[1] + p[2] * f.V[2];
      double xi = (pu - u0) / texel, yj = (pv - v0) / texel;
      float got = rect[r * d + g];
      if (xi < 0 || yj < 0 || xi >= w || yj >= w) {
        outside++;
        if (!isinf(got)) bad_tex++;
        continue;
      }
      /* near a texel border, either neighbour is acceptable */
      double fx = xi - floor(xi), fy = yj - floor(yj);
      int border = fx < 1e-9 || fx > 1 - 1e-9 || fy < 1e-9 || fy > 1 - 1e-9;
      if (!border && got != (float)((size_t)yj * w + (size_t)xi)) bad_tex++;
    }
  CHECK(bad_tex == 0, "%d rectified samples read the wrong texel", bad_tex);
  CHECK(outside > 0, "no sample outside the map: the +inf branch was not tested");

  /* the scene end to end: the rectified shadow map agrees with shooting a shadow ray from the
   * camera ray's samples for all but aliasing near edges */
  ics_heightfield sc;
  ics_heightfield_init_default(&sc);
  size_t W = 512;
  double H = 0.05 * (double)d;
  float *sm = malloc(W * W * sizeof(float));
  CHECK(ics_heightfield_shadow_map(&sc, &f, W, H, sm) == ICS_OK, "shadow map");
  CHECK(ics_epipolar_rectify(&f, sm, W, W, f.eu - H, f.ev - H, 2 * H / (double)W, rect) == ICS_OK,
        "rectify scene");
  /* every disagreement must be aliasing: the true shadow changes within 1.5 texels (in the
   * light plane) or 1.5 texels of depth of the sample */
  long agree = 0, total = 0, lit = 0, unexplained = 0;
  double tx = 2 * H / (double)W;
  for (size_t r = 0; r < rows; r += 5)
    for (double beta = 0.3; beta < 3.0; beta += 0.1) {
      double dir[3], alpha;
      size_t row;
      ics_minmax_ray ray;
      ics_epipolar_ray_dir(&f, r, beta, dir);
      ics_epipolar_ray(&f, dir, &alpha, &row, &ray);
      CHECK(row == r, "ray of row %zu maps to row %zu", r, row);
      double hit = ics_heightfield_hit(&sc, eye, dir, 0.0);
      for (size_t g = 1; g < d; g += 2) {
        double sd = (double)g * 0.05 / sin(beta);
        double p[3] = {eye[0] + sd * dir[0], eye[1] + sd * dir[1], eye[2] + sd * dir[2]};
        if (sd >= hit) break; /* past the first surface */
        if (fabs(p[0]) > 6 || fabs(p[2]) > 6 || p[1] > 2.5) continue; /* only inside the scene */
        int lit_rect = (double)rect[r * d + g] > ray.beta0 + ray.slope * (double)g;
        int lit_true = isinf(ics_heightfield_hit(&sc, p, f.L, 1e-9));
        total++;
        lit += lit_true;
        if (lit_rect == lit_true) {
          agree++;
          continue;
        }
        int explained = 0;
        for (int k = -3; k <= 3 && !explained; k++)
          for (int ax = 0; ax < 3 && !explained; ax++) {
            const double *e = ax == 0 ? f.U : ax == 1 ? f.V : f.L;
            double q[3] = {p[0] + 0.5 * k * tx * e[0], p[1] + 0.5 * k * tx * e[1], p[2] + 0.5 * k * tx * e[2]};
            if (isinf(ics_heightfield_hit(&sc, q, f.L, 1e-9)) != lit_true) explained = 1;
          }
        unexplained += !explained;
      }
    }
  CHECK(total > 1000 && lit >= 100 && total - lit >= 100,
        "scene samples: %ld, lit %ld: both lit and shadowed must be exercised", total, lit);
  CHECK(unexplained == 0, "%ld rectified shadow tests disagree with shadow rays away from edges",
        unexplained);
  printf("scene: rectified shadow test agrees with shadow rays on %ld of %ld samples (%ld lit, "
         "%ld shadowed); all disagreements within 1.5 texels of a shadow edge\n",
         agree, total, lit, total - lit);
  free(sm);
  free(smap);
  free(rect);
}

/* ---- bad input ---- */
static void test_bad_input(void) {
  float v[4] = {1, 2, 3, 4};
  ics_minmax *t = (ics_minmax *)&v; /* must be reset to NULL on failure */
  CHECK(ics_minmax_create(&t, v, 0, 4, 4) == ICS_ERR_SIZE && t == NULL, "rows = 0");
  CHECK(ics_minmax_create(&t, v, 1, 0, 4) == ICS_ERR_SIZE, "d = 0");
  CHECK(ics_minmax_create(&t, v, 1, ICS_MINMAX_MAX_SAMPLES + 1, ICS_MINMAX_MAX_SAMPLES + 1) == ICS_ERR_SIZE,
        "d too large");
  CHECK(ics_minmax_create(&t, v, ICS_MINMAX_MAX_ROWS, ICS_MINMAX_MAX_SAMPLES, ICS_MINMAX_MAX_SAMPLES) ==
            ICS_ERR_SIZE,
        "rows * d too large");
  CHECK(ics_minmax_create(&t, v, (size_t)-1, 4, 4) == ICS_ERR_SIZE, "rows = SIZE_MAX");
  CHECK(ics_minmax_create(&t, v, 1, 4, 3) == ICS_ERR_INVALID_ARG, "stride < d");
  CHECK(ics_minmax_create(&t, NULL, 1, 4, 4) == ICS_ERR_INVALID_ARG, "NULL values");
  v[2] = NAN;
  CHECK(ics_minmax_create(&t, v, 1, 4, 4) == ICS_ERR_NAN, "NaN height");
  v[2] = INFINITY;
  CHECK(ics_minmax_create(&t, v, 1, 4, 4) == ICS_OK, "+inf height is allowed");
  ics_minmax_ray ray = {NAN, 0, 4};
  double pre[5] = {0, 1, 2, 3, 4}, out[1];
  size_t nseg;
  CHECK(ics_minmax_integrate(t, 0, &ray, pre, 1, 5, out) == ICS_ERR_NAN, "NaN beta0");
  ray.beta0 = 0;
  ray.slope = INFINITY;
  CHECK(ics_minmax_integrate(t, 0, &ray, pre, 1, 5, out) == ICS_ERR_INFINITE, "inf slope");
  ray.slope = 0;
  ray.gamma_end = 5;
  CHECK(ics_minmax_integrate(t, 0, &ray, pre, 1, 5, out) == ICS_ERR_RANGE, "gamma_end > d");
  ray.gamma_end = 4;
  CHECK(ics_minmax_integrate(t, 1, &ray, pre, 1, 5, out) == ICS_ERR_RANGE, "row out of range");
  CHECK(ics_minmax_integrate(t, 0, &ray, pre, 1, 4, out) == ICS_ERR_INVALID_ARG, "ld < d + 1");
  CHECK(ics_minmax_segments(t, 0, &ray, NULL, 3, &nseg, NULL) == ICS_ERR_INVALID_ARG, "NULL seg");
  CHECK(ics_minmax_integrate(t, 0, &ray, pre, 1, 5, out) == ICS_OK && out[0] == 4.0,
        "lit: all samples > 0 -> sum of 1 over 4 samples = %g", out[0]);
  ics_minmax_destroy(t);
  double terms[3] = {1, NAN, 2}, p[4];
  CHECK(ics_minmax_prefix(terms, 1, 3, 3, p, 4) == ICS_ERR_NAN, "NaN integrand");
  CHECK(ics_minmax_prefix(terms, 1, 0, 3, p, 4) == ICS_ERR_SIZE, "empty integrand");
  CHECK(ics_minmax_march(v, 0, &ray, terms, 1, 3, out) == ICS_ERR_SIZE, "empty march");
  double A[6] = {1, 2, 3, NAN, 5, 6}, U[6], s[3], V[9];
  CHECK(ics_svd(A, 2, 3, U, s, V) == ICS_ERR_SIZE, "svd m < n");
  CHECK(ics_svd(A, 0, 0, U, s, V) == ICS_ERR_SIZE, "svd empty");
  CHECK(ics_svd(A, 3, 2, U, s, V) == ICS_ERR_NAN, "svd NaN");
  A[3] = INFINITY;
  CHECK(ics_svd(A, 3, 2, U, s, V) == ICS_ERR_INFINITE, "svd inf");
  /* a stride whose last row is not addressable: refused, not wrapped around */
  CHECK(ics_minmax_create(&t, v, 2, 4, SIZE_MAX / 2) == ICS_ERR_SIZE && t == NULL, "stride overflow");
  CHECK(ics_minmax_create(&t, v, 3, 4, SIZE_MAX / 8) == ICS_ERR_SIZE, "rows x stride overflow");
  /* NULL pointers */
  ics_heightfield_init_default(NULL);
  {
    ics_heightfield sc0;
    ics_heightfield_init_default(&sc0);
    const double o0[3] = {0, 1, 0}, d0[3] = {0, -1, 0};
    CHECK(isnan(ics_heightfield_hit(NULL, o0, d0, 0)) &&
              isnan(ics_heightfield_hit(&sc0, NULL, d0, 0)) &&
              isnan(ics_heightfield_hit(&sc0, o0, NULL, 0)),
          "scene hit with NULL");
    CHECK(ics_heightfield_shadow_map(NULL, NULL, 2, 1.0, NULL) == ICS_ERR_INVALID_ARG,
          "shadow map NULL");
  }
  CHECK(ics_svd(NULL, 3, 2, U, s, V) == ICS_ERR_INVALID_ARG && ics_svd(A, 3, 2, NULL, s, V) == ICS_ERR_INVALID_ARG &&
            ics_svd(A, 3, 2, U, NULL, V) == ICS_ERR_INVALID_ARG && ics_svd(A, 3, 2, U, s, NULL) == ICS_ERR_INVALID_ARG,
        "svd NULL");
  CHECK(ics_svd_truncate(NULL, s, V, 3, 2, 1, A) == ICS_ERR_INVALID_ARG, "truncate NULL");
  CHECK(ics_minmax_prefix(NULL, 1, 3, 3, p, 4) == ICS_ERR_INVALID_ARG &&
            ics_minmax_prefix(terms, 1, 3, 3, NULL, 4) == ICS_ERR_INVALID_ARG,
        "prefix NULL");
  CHECK(ics_minmax_march(NULL, 4, &ray, terms, 1, 4, out) == ICS_ERR_INVALID_ARG, "march NULL row");
  CHECK(ics_minmax_node(NULL, 0, 1, NULL, NULL) == ICS_ERR_INVALID_ARG &&
            ics_minmax_node_range(NULL, 1, NULL, NULL) == ICS_ERR_INVALID_ARG,
        "node NULL");
  CHECK(ics_minmax_rows(NULL) == 0 && ics_minmax_samples(NULL) == 0 && ics_minmax_leaves(NULL) == 0,
        "accessors NULL");
  ics_minmax_destroy(NULL);
  CHECK(ics_epipolar_frame_init(NULL, NULL, NULL, 4, 4, 1.0) == ICS_ERR_INVALID_ARG, "frame NULL");
  ics_epipolar_frame f;
  double eye[3] = {0, 1, 0}, L[3] = {0, 0, 0}, Lnan[3] = {0, NAN, 1};
  CHECK(ics_epipolar_frame_init(&f, eye, L, 4, 4, 1.0) == ICS_ERR_INVALID_ARG,
        "zero light direction");
  CHECK(ics_epipolar_frame_init(&f, eye, Lnan, 4, 4, 1.0) == ICS_ERR_NAN, "NaN light direction");
  L[1] = 1;
  CHECK(ics_epipolar_frame_init(&f, eye, L, 0, 4, 1.0) == ICS_ERR_SIZE, "no rows");
  CHECK(ics_epipolar_frame_init(&f, eye, L, 4, 4, -1.0) == ICS_ERR_RANGE, "negative dgamma");
  CHECK(ics_epipolar_frame_init(&f, eye, L, 4, 4, 1.0) == ICS_OK, "frame");
  double alpha;
  size_t row;
  CHECK(ics_epipolar_ray(&f, L, &alpha, &row, &ray) == ICS_ERR_RANGE, "ray parallel to the light");
  double dnan[3] = {1, NAN, 0}, dir[3];
  CHECK(ics_epipolar_ray(&f, dnan, &alpha, &row, &ray) == ICS_ERR_NAN, "NaN ray direction");
  CHECK(ics_epipolar_ray_dir(&f, 4, 1.0, dir) == ICS_ERR_RANGE, "ray_dir row out of range");
  CHECK(ics_epipolar_ray_dir(&f, 0, 0.0, dir) == ICS_ERR_RANGE, "ray_dir beta = 0 (parallel)");
  CHECK(ics_epipolar_ray_dir(&f, 0, NAN, dir) == ICS_ERR_NAN, "ray_dir NaN beta");
  float sm[4] = {1, 2, 3, 4}, rect[16];
  CHECK(ics_epipolar_rectify(&f, sm, 0, 2, 0, 0, 1, rect) == ICS_ERR_SIZE, "rectify empty map");
  CHECK(ics_epipolar_rectify(&f, sm, 2, 2, 0, NAN, 1, rect) == ICS_ERR_NAN, "rectify NaN origin");
  CHECK(ics_epipolar_rectify(&f, sm, 2, 2, 0, 0, 0, rect) == ICS_ERR_RANGE, "rectify zero texel");
  ics_heightfield sc;
  ics_heightfield_init_default(&sc);
  CHECK(ics_heightfield_shadow_map(&sc, &f, 0, 1.0, sm) == ICS_ERR_SIZE, "shadow map 0 texels");
  CHECK(ics_heightfield_shadow_map(&sc, &f, 2, NAN, sm) == ICS_ERR_NAN, "shadow map NaN size");
  CHECK(ics_heightfield_shadow_map(&sc, &f, 2, -1.0, sm) == ICS_ERR_RANGE,
        "shadow map negative size");
}

/* SVD of A 2^k for huge and tiny k: the input is scaled by a power of two internally, so the
 * result equals the SVD of A with s multiplied by 2^k, bit for bit (used to fail with
 * ICS_ERR_RANGE for entries near 1e308: the squared column norms overflowed); a singular value
 * above DBL_MAX is ICS_ERR_INFINITE. */
static void test_svd_scaling(void) {
  enum { M = 5, N = 3 };
  double B[M * N], A[M * N], UB[M * N], sB[N], VB[N * N], U[M * N], s[N], V[N * N];
  unsigned x = 12345;
  for (int i = 0; i < M * N; i++) {
    x = x * 1664525u + 1013904223u;
    B[i] = ((double)(x >> 8) / 16777216.0 - 0.5) * 0.5; /* in [-0.25, 0.25) */
  }
  CHECK(ics_svd(B, M, N, UB, sB, VB) == ICS_OK, "svd B");
  const int ks[] = {1023, 1000, 700, -700, -1000};
  for (int j = 0; j < (int)(sizeof ks / sizeof ks[0]); j++) {
    for (int i = 0; i < M * N; i++) A[i] = ldexp(B[i], ks[j]);
    ics_status st = ics_svd(A, M, N, U, s, V);
    int same = st == ICS_OK;
    for (int i = 0; same && i < N; i++) same = s[i] == ldexp(sB[i], ks[j]);
    for (int i = 0; same && i < M * N; i++) same = U[i] == UB[i];
    for (int i = 0; same && i < N * N; i++) same = V[i] == VB[i];
    CHECK(same, "svd of A 2^%d: status %s, s0 %.17g vs %.17g", ks[j], ics_status_str(st), s[0],
          ldexp(sB[0], ks[j]));
  }
  double H[2] = {1.5e308, 1.5e308}, Uh[2], sh[1], Vh[1];
  CHECK(ics_svd(H, 2, 1, Uh, sh, Vh) == ICS_ERR_INFINITE, "singular value above DBL_MAX");
  double Z[2] = {0, 0};
  CHECK(ics_svd(Z, 2, 1, Uh, sh, Vh) == ICS_OK && sh[0] == 0, "zero matrix");
}

int main(void) {
  size_t ds[] = {1, 2, 3, 5, 7, 8, 13, 64, 100, 257, 1000, 1024};
  for (size_t i = 0; i < sizeof ds / sizeof ds[0]; i++) {
    test_tree(ds[i], 0);
    test_tree(ds[i], 1);
  }
  size_t dt[] = {1, 2, 3, 5, 8, 17, 31, 64, 100, 513, 1024, 3000, 4096};
  for (size_t i = 0; i < sizeof dt / sizeof dt[0]; i++) {
    int nrays = dt[i] > 1000 ? 600 : 2000;
    test_traversal(dt[i], 0, nrays);
    test_traversal(dt[i], 1, nrays);
  }
  test_node_classes();
  test_svd();
  test_svd_scaling();
  test_rectification();
  test_bad_input();
  return test_summary("test_minmax");
}
