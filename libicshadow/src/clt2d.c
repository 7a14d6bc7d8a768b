/* clt2d.c — CLT convergence of the 2D kernel members (API and conventions in icshadow/clt2d.h).
 *
 * What is measured. An occluder image O (half-plane or quadrant, through the origin) is iterated
 * n times with the taps of a 2D generator by the engine of conv.c (ics_conv2d_step: bilinear
 * taps, float image, clamp boundary), the taps being first made integer by ics_taps2d_compensate
 * in the requested mode (NONNEG: exact class moments when reachable). The result r_n is compared
 * with the Gaussian limit with the same moments, sup over a window of nodes.
 *
 * Why the limit has a pixel term (the 2D form of clt1d.c's 1/12). Node p (pixel centre, grid
 * units) starts as the exact AREA COVERAGE of its pixel square by the opaque region A:
 *   r_0(p) = P(p + U in A),  U uniform on (-1/2, 1/2)^2.
 * With integer taps K (distribution of one step) the engine computes r_{k+1}(p) =
 * sum_q P(K = q) r_k(p - q), so r_n(p) = P(p - K_n + U in A), K_n the sum of the n steps' taps.
 * U is symmetric, so for the half-plane A = {u . x > 0} (unit normal u):
 *   r_n(p) = P(u . (K_n + U) < u . p)          — the cdf of the projected (kernel sum + pixel)
 * and for the quadrant A = {x > 0, y > 0}:
 *   r_n(p) = P(K_n + U < p componentwise)      — the bivariate cdf of (kernel sum + pixel).
 * These are exact on the infinite grid for every n (no interpolation enters: all taps are
 * integer). Var(u . U) = (ux^2 + uy^2)/12 = 1/12 for every edge angle and Cov(U) = I/12, so the
 * CLT limit with the same moments is
 *   edge:   Phi((u . p - n u . mu) / sqrt(n u^T Sigma u + 1/12)),
 *   corner: Phi2 of N(n mu, n Sigma + I/12) at p (ics_normal_bvn_cdf, standardised, rho = C_xy /
 *           sqrt(C_xx C_yy)),
 * mu, Sigma the per-step class. The coverage of a pixel by the half-plane is the trapezoid cdf
 * of ux U1 + uy U2 at u . p (ics_clt2d_edge_coverage: with a = max(|ux|, |uy|), b = the other,
 * F(t) = 1/2 + t/a for |t| <= (a - b)/2, 1 - ((a + b)/2 - t)^2 / (2 a b) above, symmetric);
 * the quadrant's corner lies on a pixel corner of the base grid (coverage 0/1) and on a pixel
 * centre of the fine grid (coverage products of 0, 1/2, 1). Had the occluder been POINT-sampled,
 * the nodes would read the cdf of the projected sum u . K_n at u . p: a lattice variable of span
 * h = 1/sqrt(a^2 + b^2) for a rational direction u ~ (a, b), dense for irrational ones. At 0
 * degrees the half-integer nodes sit midway between the atoms (the continuity correction: the
 * same values as the coverage image, pixel term 1/12); at 45 degrees u . p = (px + py)/sqrt 2
 * lies ON the lattice, so the nodes read the cdf at its atoms: a half-atom bias
 * (h/2) phi(0)/sd_n = O(n^-1/2) that no variance term absorbs (docs/theory.md: measured 0.0124,
 * 0.0060 at n = 16, 64 against 0.0120, 0.0060 derived). The coverage image gives the pixel
 * term 1/12 at every angle.
 * The "realised" limit uses, instead of n mu and n Sigma, the sums of the applied integer taps'
 * own means and covariances (ics_taps2d_moments): they differ from the class for stochastic
 * members (exact in expectation only) and when the compensation cannot be exact (the rank-one
 * 2-sample ellipse: ics_taps2d_compensate falls back to a trace-matching shrink).
 *
 * Grid and window. The realised path is computed first (check2: every step's taps generated
 * and compensated once; m_n, C_n summed). Base grid: nodes at x = xlo + i + 1/2,
 * y = ylo + j + 1/2 (pixels of the base grid = the world unit), covering per axis
 * [min(0, N mu, min_n m_n) - R, max(0, N mu, max_n m_n) + R], N the largest step count,
 * R = 10.5 max(sd_N, sdr_N) + 4, sd_n = sqrt(n lambda_max(Sigma) + 1/12), sdr_n =
 * sqrt(lambda_max(C_n) + 1/12). The sup runs over the union of the class window
 * |x - n mu|_inf <= 4.5 sd_n and the realised window |x - m_n|_inf <= 4.5 sdr_n (the Edgeworth
 * terms beyond 4.5 sd are < 1e-2 of their peak): when m_n drifts away from n mu (a fixed odd-N
 * ellipse, the compensation's fallback) the realised limit's error peak stays inside (a window
 * following n mu only reported 4.7e-11 at n = 4096 for an error of 4.8e-4). The 6 sd + 4 left
 * between window and border keep the clamp boundary's wrong values (where the edge's band
 * leaves the image) out of the window (Gaussian tail exp(-18) ~ 1.5e-8).
 * Discretisation check: the same iteration, in lockstep with the base grid (run2: the profiles
 * are compared node by node at each requested step, never stored), on a grid twice as fine
 * (scale 2: taps' positions
 * doubled — the same continuous kernel; stochastic draws depend on the step index only) whose
 * nodes x = xlo + k/2 include every base node (k = 2i + 1); its limit has the pixel term
 * 1/(12 * 4). disc_err = max over the window of |(r_n - G_n)_base - (r_n - G_n)_fine|: the change
 * of the error profile, which bounds the change of the reported sup error. A point is a
 * measurement only when disc_err < sup_err / 10 (the CLI and the tests apply that rule).
 *
 * Floating point: the image is float (engine contract), each step rounds every pixel once
 * (2^-24 relative), i.e. below ~n 6e-8 absolute after n steps (< 8e-6 at n = 128; the exactness
 * check at n = 1..3 in the tests sees 3.2e-8); the resolved errors in docs/theory.md are all
 * above 2e-4. */
#include "icshadow/clt2d.h"
#include "icshadow/constants.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "icshadow/ellipse.h"
#include "icshadow/normal.h"

double ics_clt2d_edge_coverage(double ux, double uy, double t) {
  if (isnan(ux) || isnan(uy) || isnan(t)) return NAN;
  double a = fabs(ux), b = fabs(uy);
  if (b > a) {
    double s = a;
    a = b;
    b = s;
  }
  double x = fabs(t), up; /* up: F(x) for x >= 0; the t < 0 side is 1 - F(|t|), formed directly */
  double lo;
  if (x >= 0.5 * (a + b)) {
    up = 1, lo = 0;
  } else if (x <= 0.5 * (a - b)) {
    up = 0.5 + x / a, lo = 0.5 - x / a;
  } else {
    double d = 0.5 * (a + b) - x;
    lo = d * d / (2 * a * b);
    up = 1 - lo;
  }
  return t >= 0 ? up : lo;
}

/* ---- generators ---- */

ics_status ics_clt2d_member_gen(void *ctx, uint64_t step, double scale, ics_tap2d *taps, int cap,
                                int *ntaps) {
  if (!ctx) return ICS_ERR_INVALID_ARG;
  ics_kernel2d k = *(const ics_kernel2d *)ctx;
  k.cls.mean[0] *= scale;
  k.cls.mean[1] *= scale;
  k.cls.cxx *= scale * scale;
  k.cls.cxy *= scale * scale;
  k.cls.cyy *= scale * scale;
  return ics_kernel2d_taps(&k, step, taps, cap, ntaps);
}

ics_status ics_clt2d_ellipse_gen(void *ctx, uint64_t step, double scale, ics_tap2d *taps, int cap,
                                 int *ntaps) {
  const ics_clt2d_ellipse *e = ctx;
  if (!e || !taps || !ntaps) return ICS_ERR_INVALID_ARG;
  if (isnan(e->offset) || isnan(e->rot)) return ICS_ERR_NAN;
  if (isinf(e->offset) || isinf(e->rot)) return ICS_ERR_INFINITE;
  if (e->nsamples < 1 || e->nsamples > ICS_ELLIPSE_MAX_SAMPLES) return ICS_ERR_RANGE;
  if (cap < e->nsamples) return ICS_ERR_SIZE;
  double o = fmod(e->offset + fmod(e->rot * (double)step, 1.0), 1.0); /* offset + i rot mod 1 */
  if (o < 0) o += 1;
  double xy[2 * ICS_ELLIPSE_MAX_SAMPLES];
  ics_ellipse_shape sh;
  ics_status st = ics_ellipse_kernel(e->varx * scale * scale, e->vary * scale * scale,
                                     e->angle_deg, e->nsamples, o, &sh, xy);
  if (st != ICS_OK) return st;
  for (int j = 0; j < sh.nsamples; j++) {
    taps[j].x = e->mean[0] * scale + xy[2 * j];
    taps[j].y = e->mean[1] * scale + xy[2 * j + 1];
    taps[j].w = 1.0 / sh.nsamples;
  }
  *ntaps = sh.nsamples;
  return ICS_OK;
}

/* ---- measurement ---- */

void ics_clt2d_setup_init(ics_clt2d_setup *out) {
  if (!out) return;
  memset(out, 0, sizeof *out);
  out->occluder = ICS_CLT2D_EDGE;
  out->comp = ICS_COMP_NONNEG;
  out->refine = 1;
}

typedef struct plan2 {
  double ux, uy;       /* edge normal */
  double lmax;         /* largest eigenvalue of Sigma */
  long xlo, ylo;       /* base node i is at x = xlo + i + 1/2 */
  size_t w, h;         /* base grid */
  double *rm, *rc;     /* realised (applied taps') summed mean [2 k] and covariance [3 k] at
                          the requested step count k (base grid, pixel term excluded) */
} plan2;

static double sd_at(const plan2 *p, int n) { return sqrt(n * p->lmax + 1.0 / 12.0); }

/* largest eigenvalue (class.h's ics_class2d_to_axes); NaN for a covariance it rejects */
static double lmax_of(double cxx, double cxy, double cyy) {
  ics_class2d c = {{0, 0}, cxx, cxy, cyy};
  double vx, vy, ang;
  return ics_class2d_to_axes(&c, &vx, &vy, &ang) == ICS_OK ? vx : NAN;
}

/* sd of the realised limit at requested step k (largest axis, pixel term included) */
static double sdr_at(const plan2 *p, int k) {
  const double *c = p->rc + 3 * k;
  return sqrt(lmax_of(c[0], c[1], c[2]) + 1.0 / 12.0);
}

static void plan2_free(plan2 *p) {
  free(p->rm);
  free(p->rc);
  p->rm = p->rc = NULL;
}

/* grid extent: the paths' box [lo, hi] (both axes) +- R */
static ics_status extent2(plan2 *p, const double lo[2], const double hi[2], double R) {
  double lox = lo[0] - R, hix = hi[0] + R, loy = lo[1] - R, hiy = hi[1] + R;
  double wx = ceil(hix) - floor(lox), wy = ceil(hiy) - floor(loy);
  if (!(wx * wy <= ICS_CLT2D_MAX_PIXELS)) return ICS_ERR_SIZE;
  p->xlo = (long)floor(lox);
  p->ylo = (long)floor(loy);
  p->w = (size_t)wx;
  p->h = (size_t)wy;
  return ICS_OK;
}

/* Arguments checked and the plan made. path = 0: the class path only (no realised moments, no
 * windows: the grid is a lower bound of the real one, for the cost's early refusal); path = 1:
 * the realised path too (one pass over every step's taps). */
static ics_status check2(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s, const int *steps,
                         int nsteps, plan2 *p, int path) {
  p->rm = p->rc = NULL;
  if (!gen || !s || !steps || nsteps <= 0) return ICS_ERR_INVALID_ARG;
  if (s->occluder != ICS_CLT2D_EDGE && s->occluder != ICS_CLT2D_CORNER) return ICS_ERR_INVALID_ARG;
  double v[6] = {s->mean[0], s->mean[1], s->cov[0], s->cov[1], s->cov[2], s->edge_angle_deg};
  for (int i = 0; i < 6; i++)
    if (isnan(v[i])) return ICS_ERR_NAN;
  for (int i = 0; i < 6; i++)
    if (isinf(v[i])) return ICS_ERR_INFINITE;
  double cxx = s->cov[0], cxy = s->cov[1], cyy = s->cov[2], tr = cxx + cyy;
  if (!(cxx >= 0 && cyy >= 0 && tr > 0 && cxx * cyy - cxy * cxy >= -1e-12 * tr * tr))
    return ICS_ERR_NEGATIVE_VARIANCE;
  if (s->comp == ICS_COMP_INTEGER) return ICS_ERR_UNSUPPORTED;
  if (s->comp != ICS_COMP_NONE && s->comp != ICS_COMP_NONNEG && s->comp != ICS_COMP_SIGNED)
    return ICS_ERR_RANGE;
  for (int k = 0; k < nsteps; k++)
    if (steps[k] < 1 || steps[k] > ICS_CLT2D_MAX_STEPS || (k && steps[k] <= steps[k - 1]))
      return ICS_ERR_RANGE;
  double a = s->edge_angle_deg * (ICS_PI / 180);
  p->ux = cos(a);
  p->uy = sin(a);
  /* exact axes at multiples of 90 degrees */
  double r90 = fmod(s->edge_angle_deg, 90.0);
  if (r90 == 0) {
    p->ux = nearbyint(p->ux);
    p->uy = nearbyint(p->uy);
  }
  p->lmax = lmax_of(cxx, cxy, cyy);
  if (isnan(p->lmax)) return ICS_ERR_NEGATIVE_VARIANCE;
  int nmax = steps[nsteps - 1];
  double clo[2] = {fmin(0.0, nmax * s->mean[0]), fmin(0.0, nmax * s->mean[1])};
  double chi[2] = {fmax(0.0, nmax * s->mean[0]), fmax(0.0, nmax * s->mean[1])};
  ics_status st = extent2(p, clo, chi, 10.5 * sd_at(p, nmax) + 4);
  if (st != ICS_OK || !path) return st;
  /* The realised path: the applied integer taps of every step (generated and compensated as
   * run2 does; the generators are deterministic in the step index), their summed mean and
   * covariance. Its mean can drift away from n mu (compensation fallback, stochastic members):
   * the grid covers both paths and the window is the union of both windows. */
  int cap = ICS_KERNEL_MAX_TAPS, dcap = 4 * ICS_KERNEL_MAX_TAPS + 9;
  ics_tap2d *taps = malloc((size_t)cap * sizeof *taps);
  ics_tap2d *dt = malloc((size_t)dcap * sizeof *dt);
  p->rm = malloc((size_t)nsteps * 2 * sizeof *p->rm);
  p->rc = malloc((size_t)nsteps * 3 * sizeof *p->rc);
  st = (taps && dt && p->rm && p->rc) ? ICS_OK : ICS_ERR_NOMEM;
  double rm[2] = {0, 0}, rc[3] = {0, 0, 0}, plo[2] = {0, 0}, phi[2] = {0, 0};
  for (int n = 1, k = 0; st == ICS_OK && n <= nmax; n++) {
    int nt = 0, nd = 0;
    st = gen(ctx, (uint64_t)(n - 1), 1.0, taps, cap, &nt);
    if (st == ICS_OK) st = ics_taps2d_compensate(taps, nt, s->comp, dt, dcap, &nd, NULL);
    if (st != ICS_OK) break;
    double ws, tm[2], tc[3];
    ics_taps2d_moments(dt, nd, &ws, tm, tc);
    rm[0] += tm[0], rm[1] += tm[1];
    rc[0] += tc[0], rc[1] += tc[1], rc[2] += tc[2];
    for (int d = 0; d < 2; d++) plo[d] = fmin(plo[d], rm[d]), phi[d] = fmax(phi[d], rm[d]);
    if (n == steps[k]) {
      memcpy(p->rm + 2 * k, rm, sizeof rm);
      memcpy(p->rc + 3 * k, rc, sizeof rc);
      k++;
    }
  }
  free(taps);
  free(dt);
  if (st == ICS_OK && !(isfinite(rm[0]) && isfinite(rm[1]) && isfinite(rc[0]) && isfinite(rc[1]) &&
                        isfinite(rc[2])))
    st = ICS_ERR_INFINITE;
  for (int k = 0; st == ICS_OK && k < nsteps; k++) /* the applied taps' summed covariance */
    if (isnan(sdr_at(p, k))) st = ICS_ERR_NEGATIVE_VARIANCE;
  if (st != ICS_OK) {
    plan2_free(p);
    return st;
  }
  for (int d = 0; d < 2; d++) plo[d] = fmin(plo[d], clo[d]), phi[d] = fmax(phi[d], chi[d]);
  st = extent2(p, plo, phi, 10.5 * fmax(sd_at(p, nmax), sdr_at(p, nsteps - 1)) + 4);
  if (st != ICS_OK) plan2_free(p);
  return st;
}

/* The window of requested step k: the union of the class window |x - n mu|_inf <= 4.5 sd_n and
 * the realised window |x - m_k|_inf <= 4.5 sdr_k (m_k the realised mean), as base node index
 * ranges [i0, i1] x [j0, j1] of the two squares (a: class, b: realised). */
typedef struct rect2 {
  long i0, i1, j0, j1;
} rect2;
typedef struct win2 {
  rect2 a, b;
  long i0, i1, j0, j1; /* bounding box */
} win2;

static rect2 rect_at(const plan2 *p, double cx, double cy, double R) {
  rect2 w;
  w.i0 = (long)ceil(cx - R - (double)p->xlo - 0.5);
  w.i1 = (long)floor(cx + R - (double)p->xlo - 0.5);
  w.j0 = (long)ceil(cy - R - (double)p->ylo - 0.5);
  w.j1 = (long)floor(cy + R - (double)p->ylo - 0.5);
  if (w.i0 < 0) w.i0 = 0;
  if (w.j0 < 0) w.j0 = 0;
  if (w.i1 > (long)p->w - 1) w.i1 = (long)p->w - 1;
  if (w.j1 > (long)p->h - 1) w.j1 = (long)p->h - 1;
  return w;
}

static win2 window_at(const plan2 *p, const ics_clt2d_setup *s, const int *steps, int k) {
  int n = steps[k];
  win2 w;
  w.a = rect_at(p, n * s->mean[0], n * s->mean[1], 4.5 * sd_at(p, n));
  w.b = rect_at(p, p->rm[2 * k], p->rm[2 * k + 1], 4.5 * sdr_at(p, k));
  w.i0 = w.a.i0 < w.b.i0 ? w.a.i0 : w.b.i0;
  w.i1 = w.a.i1 > w.b.i1 ? w.a.i1 : w.b.i1;
  w.j0 = w.a.j0 < w.b.j0 ? w.a.j0 : w.b.j0;
  w.j1 = w.a.j1 > w.b.j1 ? w.a.j1 : w.b.j1;
  return w;
}

static int in_rect(const rect2 *r, long i, long j) {
  return i >= r->i0 && i <= r->i1 && j >= r->j0 && j <= r->j1;
}

static int in_win(const win2 *w, long i, long j) { return in_rect(&w->a, i, j) || in_rect(&w->b, i, j); }

static double rect_size(const rect2 *r) {
  if (r->i1 < r->i0 || r->j1 < r->j0) return 0;
  return (double)(r->i1 - r->i0 + 1) * (double)(r->j1 - r->j0 + 1);
}

/* nodes in the union */
static size_t win_size(const win2 *w) {
  rect2 c = {w->a.i0 > w->b.i0 ? w->a.i0 : w->b.i0, w->a.i1 < w->b.i1 ? w->a.i1 : w->b.i1,
             w->a.j0 > w->b.j0 ? w->a.j0 : w->b.j0, w->a.j1 < w->b.j1 ? w->a.j1 : w->b.j1};
  return (size_t)(rect_size(&w->a) + rect_size(&w->b) - rect_size(&c));
}

/* limit at world point (x, y) for mean m and covariance c (pixel term included) */
static double limit_at(const plan2 *p, ics_clt2d_occluder occ, double x, double y,
                       const double m[2], const double c[3]) {
  if (occ == ICS_CLT2D_EDGE) {
    double v = p->ux * p->ux * c[0] + 2 * p->ux * p->uy * c[1] + p->uy * p->uy * c[2];
    return ics_normal_cdf((p->ux * (x - m[0]) + p->uy * (y - m[1])) / sqrt(v));
  }
  double sx = sqrt(c[0]), sy = sqrt(c[2]);
  double r = c[1] / (sx * sy);
  if (r > 1) r = 1;
  if (r < -1) r = -1;
  return ics_normal_bvn_cdf((x - m[0]) / sx, (y - m[1]) / sy, r);
}

/* One grid: the image (2 float buffers) refined by `scale` (1 or 2), its node (i, j) at world
 * x = xw0 + i / scale. */
typedef struct grid2 {
  size_t W, H;
  double xw0, yw0, sc;
  float *buf, *tmp;
} grid2;

static ics_status grid_init(grid2 *g, const ics_clt2d_setup *s, const plan2 *p, int scale) {
  g->W = scale == 1 ? p->w : 2 * p->w + 1;
  g->H = scale == 1 ? p->h : 2 * p->h + 1;
  g->xw0 = scale == 1 ? (double)p->xlo + 0.5 : (double)p->xlo;
  g->yw0 = scale == 1 ? (double)p->ylo + 0.5 : (double)p->ylo;
  g->sc = (double)scale;
  g->buf = malloc(g->W * g->H * sizeof *g->buf);
  g->tmp = malloc(g->W * g->H * sizeof *g->tmp);
  if (!g->buf || !g->tmp) return ICS_ERR_NOMEM;
  for (size_t j = 0; j < g->H; j++)
    for (size_t i = 0; i < g->W; i++) {
      double gx = (g->xw0 + (double)i / g->sc) * g->sc, gy = (g->yw0 + (double)j / g->sc) * g->sc;
      double v; /* grid units */
      if (s->occluder == ICS_CLT2D_EDGE)
        v = ics_clt2d_edge_coverage(p->ux, p->uy, p->ux * gx + p->uy * gy);
      else
        v = fmin(fmax(gx + 0.5, 0.0), 1.0) * fmin(fmax(gy + 0.5, 0.0), 1.0);
      g->buf[j * g->W + i] = (float)v;
    }
  return ICS_OK;
}

static void grid_free(grid2 *g) {
  free(g->buf);
  free(g->tmp);
}

/* one step of the grid with step n's taps (generated for its scale, compensated) */
static ics_status grid_step(grid2 *g, ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                            int n, ics_tap2d *taps, int cap, ics_tap2d *dt, int dcap, int *nd) {
  ics_conv_opts co = {0};
  co.boundary = ICS_BOUNDARY_CLAMP;
  co.compensate = ICS_COMP_NONE; /* the taps handed over are already integer */
  int nt = 0;
  ics_status st = gen(ctx, (uint64_t)(n - 1), g->sc, taps, cap, &nt);
  if (st == ICS_OK) st = ics_taps2d_compensate(taps, nt, s->comp, dt, dcap, nd, NULL);
  if (st == ICS_OK) st = ics_conv2d_step(g->buf, g->tmp, g->W, g->H, dt, *nd, &co);
  if (st != ICS_OK) return st;
  float *sw = g->buf;
  g->buf = g->tmp;
  g->tmp = sw;
  return ICS_OK;
}

/* value of the grid at base node (i, j) */
static double grid_at(const grid2 *g, long i, long j) {
  size_t gi = g->sc == 1 ? (size_t)i : 2 * (size_t)i + 1;
  size_t gj = g->sc == 1 ? (size_t)j : 2 * (size_t)j + 1;
  return g->buf[gj * g->W + gi];
}

/* The base grid and (s->refine) the 2x finer grid iterated in lockstep, so the error profiles
 * are compared node by node at each requested step and never stored: memory is the two grids'
 * buffers only. At requested step k: class and realised errors on the base grid, the class
 * error on the fine grid at the base nodes (only its change is needed: disc_err). */
static ics_status run2(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s, const plan2 *p,
                       const int *steps, int nsteps, ics_clt_point *out, ics_clt_progress progress,
                       void *progress_ctx) {
  grid2 gb = {0}, gf = {0};
  int cap = ICS_KERNEL_MAX_TAPS, dcap = 4 * ICS_KERNEL_MAX_TAPS + 9;
  ics_tap2d *taps = malloc((size_t)cap * sizeof *taps);
  ics_tap2d *dt = malloc((size_t)dcap * sizeof *dt);
  ics_status st = (taps && dt) ? ICS_OK : ICS_ERR_NOMEM;
  if (st == ICS_OK) st = grid_init(&gb, s, p, 1);
  if (st == ICS_OK && s->refine) st = grid_init(&gf, s, p, 2);
  double cost = 0, secs = 0;
  int nmax = steps[nsteps - 1], k = 0;
  for (int n = 1; st == ICS_OK && n <= nmax; n++) {
    int nd = 0, ndf = 0;
    clock_t t0 = clock();
    st = grid_step(&gb, gen, ctx, s, n, taps, cap, dt, dcap, &nd);
    secs += (double)(clock() - t0) / CLOCKS_PER_SEC;
    if (st == ICS_OK && s->refine) st = grid_step(&gf, gen, ctx, s, n, taps, cap, dt, dcap, &ndf);
    if (st != ICS_OK) break;
    cost += nd;
    if (progress) progress(progress_ctx, n, nmax);
    if (n != steps[k]) continue;
    const double *rm = p->rm + 2 * k, *rc = p->rc + 3 * k;
    double pix = 1.0 / 12.0, pixf = 1.0 / 48.0;
    double cm[2] = {n * s->mean[0], n * s->mean[1]};
    double cc[3] = {n * s->cov[0] + pix, n * s->cov[1], n * s->cov[2] + pix};
    double ccf[3] = {n * s->cov[0] + pixf, n * s->cov[1], n * s->cov[2] + pixf};
    double qc[3] = {rc[0] + pix, rc[1], rc[2] + pix};
    win2 w = window_at(p, s, steps, k);
    double worst = 0, worst_r = 0, disc = 0;
    for (long j = w.j0; j <= w.j1; j++)
      for (long i = w.i0; i <= w.i1; i++) {
        if (!in_win(&w, i, j)) continue;
        double x = (double)p->xlo + (double)i + 0.5, y = (double)p->ylo + (double)j + 0.5;
        double e = grid_at(&gb, i, j) - limit_at(p, s->occluder, x, y, cm, cc);
        double er = grid_at(&gb, i, j) - limit_at(p, s->occluder, x, y, rm, qc);
        worst = fmax(worst, fabs(e));
        worst_r = fmax(worst_r, fabs(er));
        if (s->refine)
          disc = fmax(disc, fabs(e - (grid_at(&gf, i, j) - limit_at(p, s->occluder, x, y, cm, ccf))));
      }
    out[k].steps = n;
    out[k].sup_err = worst;
    out[k].sup_err_realized = worst_r;
    out[k].disc_err = s->refine ? disc : NAN;
    out[k].cost = cost;
    out[k].seconds = secs;
    k++;
  }
  grid_free(&gb);
  grid_free(&gf);
  free(taps);
  free(dt);
  return st;
}

/* Cost of one limit evaluation in engine tap-updates, measured side by side in one Release
 * process (960 x 960 float image, 32 integer taps, clamp; 3 runs, min-max): the engine 0.21 ns
 * a tap-update (0.21-0.41 under load), ics_normal_cdf 12.7-13.1 ns = 60, ics_normal_bvn_cdf 0.83-0.89 us
 * = ~4000 for |rho| < 0.9 (arguments over [-3, 3]^2; 0.024 us at rho = 0) and 2.1-2.2 us =
 * ~10000 at |rho| = 0.95 (the integral from asin rho to pi/2). */
#define COST_PHI 60.0
#define COST_BVN 4000.0
#define COST_BVN_HIGH 10000.0

ics_status ics_clt2d_cost(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                          const int *steps, int nsteps, double *pixels, double *work) {
  /* First the class path's grid only (a lower bound of the real grid): a run refused on it is
   * refused before the realised path's pass over every step's taps (itself up to
   * ICS_CONV_WORK_COMP_PASSES x generated taps a step). */
  plan2 p;
  ics_status st = check2(gen, ctx, s, steps, nsteps, &p, 0);
  if (st != ICS_OK) return st;
  int cap = ICS_KERNEL_MAX_TAPS, dcap = 4 * ICS_KERNEL_MAX_TAPS + 9;
  ics_tap2d *taps = malloc((size_t)cap * sizeof *taps);
  ics_tap2d *dt = malloc((size_t)dcap * sizeof *dt);
  double wk = 0, nmax = (double)steps[nsteps - 1];
  int nt0 = 0, nd0 = 0, ntf = 0, ndf = 0;
  if (!taps || !dt) st = ICS_ERR_NOMEM;
  if (st == ICS_OK) st = gen(ctx, 0, 1.0, taps, cap, &nt0);
  if (st == ICS_OK) st = ics_taps2d_compensate(taps, nt0, s->comp, dt, dcap, &nd0, NULL);
  if (st == ICS_OK && s->refine) st = gen(ctx, 0, 2.0, taps, cap, &ntf);
  if (st == ICS_OK && s->refine) st = ics_taps2d_compensate(taps, ntf, s->comp, dt, dcap, &ndf, NULL);
  free(taps);
  free(dt);
  if (st != ICS_OK) return st;
  /* the realised path's pass, then the engine per grid */
  double lower = nmax * ICS_CONV_WORK_COMP_PASSES * (double)nt0;
  lower += nmax * ((double)p.w * p.h * nd0 + ICS_CONV_WORK_COMP_PASSES * (double)nt0);
  if (s->refine)
    lower += nmax * ((2.0 * p.w + 1) * (2.0 * p.h + 1) * ndf +
                     ICS_CONV_WORK_COMP_PASSES * (double)ntf);
  if (lower > ICS_CONV_WORK_BUDGET) {
    if (pixels) *pixels = (double)p.w * p.h;
    if (work) *work = lower;
    return ICS_OK;
  }
  st = check2(gen, ctx, s, steps, nsteps, &p, 1);
  if (st != ICS_OK) return st;
  wk = nmax * ICS_CONV_WORK_COMP_PASSES * (double)nt0; /* the realised path's pass */
  for (int r = 0; r <= (s->refine ? 1 : 0); r++) {
    double px = r ? (2.0 * p.w + 1) * (2.0 * p.h + 1) : (double)p.w * p.h;
    int nt = r ? ntf : nt0, nd = r ? ndf : nd0;
    wk += nmax * (px * nd + ICS_CONV_WORK_COMP_PASSES * (double)nt);
    /* the limits at every window node */
    double cn = (double)steps[nsteps - 1], pix = 1.0 / 12;
    double rho = cn * s->cov[1] / sqrt((cn * s->cov[0] + pix) * (cn * s->cov[2] + pix));
    double per = s->occluder == ICS_CLT2D_EDGE ? COST_PHI
                 : fabs(rho) < 0.9                ? COST_BVN
                                                  : COST_BVN_HIGH;
    for (int k = 0; k < nsteps; k++) { /* base: class and realised; fine: class */
      win2 w = window_at(&p, s, steps, k);
      wk += (double)win_size(&w) * (r ? 1 : 2) * per;
    }
  }
  plan2_free(&p);
  if (pixels) *pixels = (double)p.w * p.h;
  if (work) *work = wk;
  return ICS_OK;
}

ics_status ics_clt2d_measure(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                             const int *steps, int nsteps, ics_clt_point *out) {
  return ics_clt2d_measure_progress(gen, ctx, s, steps, nsteps, out, NULL, NULL);
}

ics_status ics_clt2d_measure_progress(ics_clt2d_gen gen, void *ctx, const ics_clt2d_setup *s,
                                      const int *steps, int nsteps, ics_clt_point *out,
                                      ics_clt_progress progress, void *progress_ctx) {
  if (!out) return ICS_ERR_INVALID_ARG;
  plan2 p;
  ics_status st = check2(gen, ctx, s, steps, nsteps, &p, 1);
  if (st != ICS_OK) return st;
  st = run2(gen, ctx, s, &p, steps, nsteps, out, progress, progress_ctx);
  plan2_free(&p);
  return st;
}
