/* lightfit.c — environment map -> Gaussian lights on the virtual light plane
 * (see icshadow/lightfit.h for the frames, the light convention and the error measures).
 *
 * Method.
 *  1. Pixels: every map pixel whose centre is within max_angle of +z and whose worst corner
 *     has dz >= half its centre's (so no kept pixel reaches 90 degrees) becomes a weighted sample: plane point (x, y) = (tan phi,
 *     cot theta / cos phi), luminance mass m = Y dw with the exact pixel solid angle
 *     dw = (cos theta0 - cos theta1) dphi, plane density d = m / A with A = dw (1 + r^2)^(3/2),
 *     and footprint covariance S = J diag(dphi^2, dtheta^2)/12 J^T (J = d(x, y)/d(phi, theta)).
 *  Model: a pixel's value is the radiance averaged over the pixel (a filtered map, or
 *     make-env with supersampling), so the mass placed at pixel centres has the moments of the
 *     light convolved with the pixel box: centre covariance C = Sigma + S (Sheppard). The light
 *     is Sigma = C - F, F the mass-weighted footprint, floored so that Sigma >= F (F-whitened
 *     eigenvalues clamped to >= 1): a light narrower than a pixel cannot be resolved and is
 *     represented by its pixel's own box covariance (a one-pixel sun gets ~S). Adding S to
 *     the centre moments instead would give Sigma + 2S.
 *  2. Greedy start: K times, the maximum of the residual density d - sum of started Gaussians
 *     (evaluated with each pixel's footprint added, i.e. pixel-averaged); the 4-connected
 *     pixels above half that maximum hold half the mass of a Gaussian and have centre
 *     covariance (1 - ln 2) C (in 2D, r^2 ~ Exp(mean 2) truncated at r^2 < 2 ln 2 has mean
 *     2 - 2 ln 2), so the start is mean = their centroid, C = their covariance / (1 - ln 2),
 *     Sigma = floor(C - F), weight = 2 x their residual mass. Stops early when the residual
 *     has no positive mass.
 *  2b. Starts for a sky (a floor under the lights). A sky of constant radiance c has plane
 *     density c (1 + r^2)^(-3/2) over the whole kept disc: broad, peaked at r = 0, heavy-tailed.
 *     Greedy on such a map takes the lights' peaks and then rings around them, and EM from
 *     there can leave the sky merged into a light (docs/lightfit.md "How many lights"). So when
 *     the map has a floor, two more starts: the floor's radiance Yq = the 10 % quantile of the
 *     kept pixels' luminance weighted by solid angle (the sky's radiance wherever the lights
 *     leave a tenth of the kept solid angle dark: the ring 60-80 degrees alone is 40 % of it),
 *     floor density fl = min(Y, Yq) (1 + r^2)^(-3/2) <= d; start s (s = 1, 2; s < K) gives the
 *     floor s components (s = 1: its moments, the one-Gaussian maximum-likelihood fit; s = 2:
 *     greedy on fl) and the other K - s to greedy on d - fl, where the lights stand alone. A
 *     sky needs two Gaussians to be fitted well (a uniform sky alone: L1 45 % with one,
 *     8 % with two), hence s = 2. Tried when the floor holds at least 0.1 % of the kept energy
 *     (a map of lights alone has none: their tails underflow long before the rim, and its fit
 *     is bit for bit the one of start 0 alone). EM runs from every start on the same samples;
 *     the fit with the lowest L1 (the error the fits are judged by) is kept, start 0 on ties,
 *     so no fit is worse in L1 than start 0's. Log-likelihood does not rank them the same way:
 *     on a measured map (3 lights, 2 of them overlapping) the higher-likelihood fit had L1
 *     5.1 % against start 0's 3.3 %.
 *  3. EM on the weighted samples (log-sum-exp E-step with each component's centre covariance
 *     Sigma + F; the M-step takes the centre moments C and the footprint F, Sigma = floor(C - F)
 *     as above, so no component becomes singular); components whose mass falls below 1e-12 of
 *     the total are dropped. Stops at |dLL| <= tol per unit mass or max_iter.
 *  4. Colours: RGB mass shared by the final responsibilities, divided by the luminance mass.
 * Special cases: a one-pixel sun gives one light of the pixel's footprint covariance
 * (~(pixel size)^2 / 12); a uniform sky gives a broad light and a large cutoff_loss (the
 * density (1 + r^2)^(-3/2) has infinite variance on the plane: the cut-off is what makes it
 * fittable at all). */
#include "icshadow/lightfit.h"
#include "icshadow/constants.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/rng.h"
#include "envmap_pixel.h"
#include "gauss2.h"
#include "sym2.h"

#define ONE_MINUS_LN2 0.30685281944005469 /* 1 - ln 2 */
/* the floor (step 2b): its radiance is this quantile of the kept pixels' luminance by solid
 * angle; the floor starts are tried when its mass is at least this share of the kept energy,
 * with 1 .. this many components for the floor */
#define FLOOR_QUANTILE 0.1
#define FLOOR_MIN_SHARE 1e-3
#define FLOOR_MAX_COMPONENTS 2

typedef struct px {
  double x, y, m, d, a; /* plane point, luminance mass, density, plane area */
  double rgb[3];        /* RGB mass */
  double s[3];          /* footprint covariance */
  int i, j;
} px;

typedef struct pixset {
  px *p;
  int n;
  int *grid; /* W*H -> index into p, or -1 */
  int w, h;
  double e_total, e_front, e_cut, e_kept;
} pixset;

static double lum(const float *c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void pixset_free(pixset *ps) {
  free(ps->p);
  free(ps->grid);
  memset(ps, 0, sizeof *ps);
}

static ics_status pixset_build(const ics_image *env, double max_angle_deg, pixset *ps) {
  memset(ps, 0, sizeof *ps);
  if (!env || !env->data || (env->channels != 3 && env->channels != 4)) return ICS_ERR_INVALID_ARG;
  if (env->width < 4 || env->height < 2) return ICS_ERR_SIZE;
  if (!(max_angle_deg > 0 && max_angle_deg < 90)) return ICS_ERR_INVALID_ARG;
  if (!ics_image_find_bad(env, NULL, NULL, NULL)) return ICS_ERR_INVALID_ARG;
  int w = env->width, h = env->height;
  ps->w = w;
  ps->h = h;
  ps->grid = malloc((size_t)w * h * sizeof *ps->grid);
  ps->p = malloc((size_t)w * h / 2 * sizeof *ps->p + sizeof *ps->p * (size_t)h);
  if (!ps->grid || !ps->p) {
    pixset_free(ps);
    return ICS_ERR_NOMEM;
  }
  double cosmax = cos(max_angle_deg * ICS_PI / 180);
  for (int j = 0; j < h; j++) {
    double dw = (cos(ICS_PI * j / h) - cos(ICS_PI * (j + 1.0) / h)) * (2 * ICS_PI / w);
    double th = ICS_PI * (j + 0.5) / h, st = sin(th), ct = cos(th);
    for (int i = 0; i < w; i++) {
      const float *c = env->data + ((size_t)j * w + i) * env->channels;
      double m = lum(c) * dw;
      ps->grid[(size_t)j * w + i] = -1;
      ps->e_total += m;
      double ph = 2 * ICS_PI * (i + 0.5) / w - ICS_PI, dz = st * cos(ph);
      if (!(dz > 0)) {
        ps->e_front += m;
        continue;
      }
      /* kept when the centre is within the cut-off (an unbiased boundary) and dz at the
       * pixel's worst corner is >= half of dz at its centre: the plane stretch (1 + r^2)^(3/2)
       * then varies by at most 8x over the pixel, so its plane area and footprint, taken at
       * the centre, stay meaningful. Rim pixels reaching (nearly) 90 degrees, whose area and
       * footprint are unbounded, are thereby cut whatever max_angle is. */
      if (!ics_envmap_kept_at(w, h, i, j, dz, cosmax)) {
        ps->e_cut += m;
        continue;
      }
      ps->e_kept += m;
      px *q = &ps->p[ps->n];
      q->x = tan(ph);
      q->y = ct / dz;
      double r2 = q->x * q->x + q->y * q->y;
      q->a = dw * pow(1 + r2, 1.5);
      q->m = m;
      q->d = m / q->a;
      for (int k = 0; k < 3; k++) q->rgb[k] = c[k] * dw;
      ics_envmap_footprint(w, h, i, j, q->s);
      q->i = i;
      q->j = j;
      ps->grid[(size_t)j * w + i] = ps->n++;
    }
  }
  return ICS_OK;
}

/* density of light l at pixel q, averaged over the pixel (footprint added to the covariance) */
static double light_at(const ics_light *l, const px *q) {
  double c[3] = {l->cov[0] + q->s[0], l->cov[1] + q->s[1], l->cov[2] + q->s[2]};
  gauss g;
  if (gauss_make(&g, l->mean[0], l->mean[1], c)) return 0;
  return l->weight * exp(gauss_log(&g, q->x, q->y));
}

/* Sigma = C - F with the floor Sigma >= F: with F = L L^T (Cholesky), the eigenvalues of
 * L^-1 (C - F) L^-T are clamped to >= 1. sig = C - F unchanged when no clamp is needed. */
static void cov_deconv(const double c[3], const double f[3], double sig[3]) {
  double d[3] = {c[0] - f[0], c[1] - f[1], c[2] - f[2]};
  double l00 = sqrt(f[0]), l10 = f[1] / l00, l11 = sqrt(f[2] - l10 * l10);
  if (!(l00 > 0) || !(l11 > 0)) { /* cannot happen: footprints are positive definite */
    memcpy(sig, f, 3 * sizeof *sig);
    return;
  }
  /* M = L^-1 D, A = M L^-T */
  double m00 = d[0] / l00, m01 = d[1] / l00;
  double m10 = (d[1] - l10 * m00) / l11, m11 = (d[2] - l10 * m01) / l11;
  double A0 = m00 / l00, A1 = (m01 - l10 * A0) / l11;
  double A2 = (m11 - l10 * (m10 / l00)) / l11;
  double e1, e2, ang, B[3];
  ics_sym2_eig(A0, A1, A2, &e1, &e2, &ang);
  /* no clamp needed, or NaN / overflowed moments (no floor to apply): C - F */
  if (e2 >= 1 || ics_light_cov_from_eig(e1 < 1 ? 1 : e1, 1, ang, B) != ICS_OK) {
    memcpy(sig, d, 3 * sizeof *sig);
    return;
  }
  /* sig = L B L^T, L = [[l00, 0], [l10, l11]] */
  sig[0] = l00 * l00 * B[0];
  sig[1] = l00 * (l10 * B[0] + l11 * B[1]);
  sig[2] = l10 * l10 * B[0] + 2 * l10 * l11 * B[1] + l11 * l11 * B[2];
}

/* ---- errors ---- */

static double mix_cdf(const ics_light *l, int n, double wsum, double nx, double ny, double t) {
  double f = 0;
  for (int k = 0; k < n; k++) {
    if (!(l[k].weight > 0)) continue;
    double mu = nx * l[k].mean[0] + ny * l[k].mean[1];
    double v = nx * nx * l[k].cov[0] + 2 * nx * ny * l[k].cov[1] + ny * ny * l[k].cov[2];
    double c = v > 0 ? 0.5 * erfc(-(t - mu) / sqrt(2 * v)) : (t >= mu ? 1.0 : 0.0);
    f += l[k].weight * c;
  }
  return f / wsum;
}

/* relative L1 and L2 of the lights' density (pixel-averaged) against the kept pixels' */
static void density_errors(const pixset *ps, const ics_light *l, int n, double *l1, double *l2) {
  double s1 = 0, n1 = 0, s2 = 0, n2 = 0;
  for (int q = 0; q < ps->n; q++) {
    const px *p = &ps->p[q];
    double f = 0;
    for (int k = 0; k < n; k++)
      if (l[k].weight > 0) f += light_at(&l[k], p);
    double e = p->d - f;
    s1 += fabs(e) * p->a;
    n1 += p->d * p->a;
    s2 += e * e * p->a;
    n2 += p->d * p->d * p->a;
  }
  *l1 = n1 > 0 ? s1 / n1 : NAN;
  *l2 = n2 > 0 ? sqrt(s2 / n2) : NAN;
}

static ics_status errors(const pixset *ps, const ics_light *l, int n, ics_lightfit_report *r) {
  double wsum = 0;
  for (int k = 0; k < n; k++) wsum += l[k].weight > 0 ? l[k].weight : 0;
  density_errors(ps, l, n, &r->l1, &r->l2);
  r->edge = NAN;
  if (!(wsum > 0) || !(ps->e_kept > 0)) return ICS_OK;
  /* the map's cdf across the edge: each pixel's mass spread uniformly over its footprint's
   * width across the edge, h = sqrt(12 n^T S n) (exact for columns at orientation 0), binned
   * exactly into G bins (difference array for fully covered bins) and compared at bin edges */
  enum { G = 4096 };
  double *bins = malloc(2 * (G + 1) * sizeof *bins);
  double *t = malloc(2 * (size_t)ps->n * sizeof *t);
  if (!bins || !t) {
    free(bins);
    free(t);
    return ICS_ERR_NOMEM;
  }
  double *diff = bins + G + 1, *hw = t + ps->n;
  double worst = 0;
  for (int o = 0; o < 4; o++) {
    double ang = o * ICS_PI / 4, nx = cos(ang), ny = sin(ang), lo = INFINITY, hi = -INFINITY;
    for (int q = 0; q < ps->n; q++) {
      const px *p = &ps->p[q];
      t[q] = nx * p->x + ny * p->y;
      hw[q] = 0.5 * sqrt(12 * (nx * nx * p->s[0] + 2 * nx * ny * p->s[1] + ny * ny * p->s[2]));
      lo = fmin(lo, t[q] - hw[q]);
      hi = fmax(hi, t[q] + hw[q]);
    }
    double bw = (hi - lo) / G;
    memset(bins, 0, 2 * (G + 1) * sizeof *bins);
    for (int q = 0; q < ps->n; q++) {
      double m = ps->p[q].m, a = t[q] - hw[q], b = t[q] + hw[q];
      if (!(m > 0)) continue;
      int ia = (int)floor((a - lo) / bw), ib = (int)floor((b - lo) / bw);
      ia = ia < 0 ? 0 : ia >= G ? G - 1 : ia;
      ib = ib < 0 ? 0 : ib >= G ? G - 1 : ib;
      if (ia == ib || !(b > a)) {
        bins[ia] += m;
        continue;
      }
      double dens = m / (b - a);
      bins[ia] += dens * (lo + (ia + 1) * bw - a);
      bins[ib] += dens * (b - (lo + ib * bw));
      diff[ia + 1] += dens * bw;
      diff[ib] -= dens * bw;
    }
    double run = 0, cum = 0;
    for (int g = 0; g < G; g++) {
      run += diff[g];
      cum += bins[g] + run;
      double f = mix_cdf(l, n, wsum, nx, ny, lo + (g + 1) * bw);
      double d = fabs(f - cum / ps->e_kept);
      if (d > worst) worst = d;
    }
  }
  free(bins);
  free(t);
  r->edge = worst;
  return ICS_OK;
}

static void report_energies(const pixset *ps, ics_lightfit_report *r) {
  r->pixels = ps->n;
  r->energy_total = ps->e_total;
  r->energy_front = ps->e_front;
  r->energy_cutoff = ps->e_cut;
  r->energy_kept = ps->e_kept;
  r->cutoff_loss = ps->e_cut + ps->e_kept > 0 ? ps->e_cut / (ps->e_cut + ps->e_kept) : 0;
}

ics_status ics_lightfit_errors(const ics_image *env, double max_angle_deg,
                               const ics_light *lights, int n, ics_lightfit_report *report) {
  if (!report || (n > 0 && !lights) || n < 0) return ICS_ERR_INVALID_ARG;
  memset(report, 0, sizeof *report);
  pixset ps;
  ics_status st = pixset_build(env, max_angle_deg, &ps);
  if (st != ICS_OK) return st;
  report_energies(&ps, report);
  report->k_fit = n;
  st = errors(&ps, lights, n, report);
  pixset_free(&ps);
  return st;
}

/* ---- the fit ---- */

void ics_lightfit_params_init(ics_lightfit_params *out) {
  if (!out) return;
  memset(out, 0, sizeof *out);
  out->k = 3;
  out->max_angle_deg = 80;
  out->seed = 1;
  out->max_samples = 0;
  out->max_iter = 300;
  out->tol = 1e-9;
}

/* greedy start: adds up to k Gaussians to l (returns how many); res is the residual density
 * to start from (the map's, or the map's less its floor), and is left less the Gaussians
 * started; f[k] = the mass-weighted footprint of start k's region */
static int greedy(const pixset *ps, int k, ics_light *l, double (*f)[3], int *stack, double *res,
                  char *mark) {
  int n = 0;
  while (n < k) {
    int best = -1;
    for (int q = 0; q < ps->n; q++)
      if (res[q] > 0 && (best < 0 || res[q] > res[best])) best = q;
    if (best < 0) break;
    double half = 0.5 * res[best];
    memset(mark, 0, (size_t)ps->n);
    int top = 0;
    stack[top++] = best;
    mark[best] = 1;
    double m0 = 0, mx = 0, my = 0, sxx = 0, sxy = 0, syy = 0, f0 = 0, f1 = 0, f2 = 0;
    const px *c = &ps->p[best];
    while (top) {
      int q = stack[--top];
      const px *p = &ps->p[q];
      double m = res[q] * p->a, dx = p->x - c->x, dy = p->y - c->y;
      m0 += m;
      mx += m * dx;
      my += m * dy;
      sxx += m * dx * dx;
      sxy += m * dx * dy;
      syy += m * dy * dy;
      f0 += m * p->s[0];
      f1 += m * p->s[1];
      f2 += m * p->s[2];
      static const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int e = 0; e < 4; e++) {
        int i2 = p->i + di[e], j2 = p->j + dj[e];
        if (i2 < 0 || i2 >= ps->w || j2 < 0 || j2 >= ps->h) continue;
        int q2 = ps->grid[(size_t)j2 * ps->w + i2];
        if (q2 < 0 || mark[q2] || !(res[q2] > half)) continue;
        mark[q2] = 1;
        stack[top++] = q2;
      }
    }
    if (!(m0 > 1e-12 * ps->e_kept)) break;
    mx /= m0;
    my /= m0;
    ics_light *g = &l[n];
    g->mean[0] = c->x + mx;
    g->mean[1] = c->y + my;
    /* centre covariance of the whole light, C = region's / (1 - ln 2); Sigma = C - F */
    double cc[3] = {(sxx / m0 - mx * mx) / ONE_MINUS_LN2, (sxy / m0 - mx * my) / ONE_MINUS_LN2,
                    (syy / m0 - my * my) / ONE_MINUS_LN2};
    f[n][0] = f0 / m0;
    f[n][1] = f1 / m0;
    f[n][2] = f2 / m0;
    cov_deconv(cc, f[n], g->cov);
    g->weight = 2 * m0;
    g->color[0] = g->color[1] = g->color[2] = 1;
    n++;
    for (int q = 0; q < ps->n; q++) res[q] -= light_at(g, &ps->p[q]);
  }
  return n;
}

/* ---- the floor (a sky): see the file comment, step 2b ---- */

typedef struct ywt {
  double y, w; /* luminance, solid angle */
} ywt;

static int ywt_cmp(const void *a, const void *b) {
  double u = ((const ywt *)a)->y, v = ((const ywt *)b)->y;
  return (u > v) - (u < v);
}

/* fl[q] = the floor's plane density at kept pixel q: min(Y, Yq) / (1 + r^2)^(3/2), Yq the
 * FLOOR_QUANTILE of the kept pixels' luminance Y weighted by solid angle. Returns the floor's
 * mass (sum fl A), or -1 when out of memory. */
static double floor_density(const pixset *ps, double *fl) {
  ywt *v = malloc((size_t)ps->n * sizeof *v);
  if (!v) return -1;
  double wsum = 0, wdark = 0;
  for (int q = 0; q < ps->n; q++) {
    const px *p = &ps->p[q];
    fl[q] = pow(1 + p->x * p->x + p->y * p->y, 1.5); /* dA / dw, until the floor replaces it */
    v[q].y = p->d * fl[q];
    v[q].w = p->a / fl[q];
    wsum += v[q].w;
    wdark += v[q].y > 0 ? 0 : v[q].w;
  }
  double cum = 0, yq = 0;
  if (wdark < FLOOR_QUANTILE * wsum) { /* else the quantile is 0 (lights alone): no sort */
    qsort(v, (size_t)ps->n, sizeof *v, ywt_cmp);
    for (int q = 0; q < ps->n; q++) {
      cum += v[q].w;
      yq = v[q].y;
      if (cum >= FLOOR_QUANTILE * wsum) break;
    }
  }
  free(v);
  double mass = 0;
  for (int q = 0; q < ps->n; q++) {
    const px *p = &ps->p[q];
    double fq = yq / fl[q];
    fl[q] = p->d < fq ? p->d : fq;
    mass += fl[q] * p->a;
  }
  return mass;
}

/* one Gaussian with the floor's moments (its maximum-likelihood fit): g, footprint f */
static void floor_moments(const pixset *ps, const double *fl, ics_light *g, double f[3]) {
  double m0 = 0, mx = 0, my = 0, sxx = 0, sxy = 0, syy = 0, f0 = 0, f1 = 0, f2 = 0;
  for (int q = 0; q < ps->n; q++) {
    const px *p = &ps->p[q];
    double m = fl[q] * p->a;
    m0 += m;
    mx += m * p->x;
    my += m * p->y;
    f0 += m * p->s[0];
    f1 += m * p->s[1];
    f2 += m * p->s[2];
  }
  mx /= m0;
  my /= m0;
  for (int q = 0; q < ps->n; q++) {
    const px *p = &ps->p[q];
    double m = fl[q] * p->a, dx = p->x - mx, dy = p->y - my;
    sxx += m * dx * dx;
    sxy += m * dx * dy;
    syy += m * dy * dy;
  }
  double cc[3] = {sxx / m0, sxy / m0, syy / m0};
  f[0] = f0 / m0;
  f[1] = f1 / m0;
  f[2] = f2 / m0;
  cov_deconv(cc, f, g->cov);
  g->mean[0] = mx;
  g->mean[1] = my;
  g->weight = m0;
  g->color[0] = g->color[1] = g->color[2] = 1;
}

/* ---- EM ---- */

typedef struct em_samples {
  const int *sel;      /* pixel index of each sample */
  const double *smass; /* its mass */
  int n;
  double M; /* their total mass */
} em_samples;

/* EM from the start l[0..*n), footprints fk, to convergence or prm->max_iter: *n is updated
 * (empty components dropped), *ll the final log-likelihood per unit mass, *iters the
 * iterations run, *converged. resp: room for K doubles. */
static ics_status em(const pixset *ps, const em_samples *sm, const ics_lightfit_params *prm,
                     ics_light *lights, double (*fk)[3], int *n_io, double *resp, double *ll_out,
                     int *iters, int *converged) {
  int n = *n_io;
  double pi_[ICS_LIGHTFIT_MAX_K];
  gauss g[ICS_LIGHTFIT_MAX_K];
  double wsum = 0;
  for (int k = 0; k < n; k++) wsum += lights[k].weight;
  for (int k = 0; k < n; k++) pi_[k] = lights[k].weight / wsum;
  double ll_prev = -INFINITY, ll = -INFINITY;
  int it = 0;
  *converged = 0;
  for (it = 1; it <= prm->max_iter && n > 0; it++) {
    for (int k = 0; k < n; k++) {
      /* the samples are pixel centres: their covariance under component k is Sigma + F */
      double cc[3] = {lights[k].cov[0] + fk[k][0], lights[k].cov[1] + fk[k][1],
                      lights[k].cov[2] + fk[k][2]};
      if (gauss_make(&g[k], lights[k].mean[0], lights[k].mean[1], cc))
        return ICS_ERR_RANGE; /* cannot happen: footprints keep covariances positive definite */
    }
    double acc[ICS_LIGHTFIT_MAX_K][9];
    memset(acc, 0, sizeof acc);
    ll = 0;
    for (int s = 0; s < sm->n; s++) {
      const px *p = &ps->p[sm->sel[s]];
      double lmax = -INFINITY;
      for (int k = 0; k < n; k++) {
        resp[k] = log(pi_[k]) + gauss_log(&g[k], p->x, p->y);
        if (resp[k] > lmax) lmax = resp[k];
      }
      double sum = 0;
      for (int k = 0; k < n; k++) sum += (resp[k] = exp(resp[k] - lmax));
      ll += sm->smass[s] * (lmax + log(sum));
      for (int k = 0; k < n; k++) {
        double m = sm->smass[s] * resp[k] / sum;
        double dx = p->x - lights[k].mean[0], dy = p->y - lights[k].mean[1];
        double *a = acc[k];
        a[0] += m;
        a[1] += m * dx;
        a[2] += m * dy;
        a[3] += m * dx * dx;
        a[4] += m * dx * dy;
        a[5] += m * dy * dy;
        a[6] += m * p->s[0];
        a[7] += m * p->s[1];
        a[8] += m * p->s[2];
      }
    }
    ll /= sm->M;
    /* M-step; drop empty components */
    int n2 = 0;
    for (int k = 0; k < n; k++) {
      double *a = acc[k];
      if (!(a[0] > 1e-12 * sm->M)) continue;
      double mx = a[1] / a[0], my = a[2] / a[0];
      ics_light *L = &lights[n2];
      L->mean[0] = lights[k].mean[0] + mx;
      L->mean[1] = lights[k].mean[1] + my;
      /* centre moments C = Sigma + F (pixels are area averages): Sigma = C - F, floored */
      double cc[3] = {a[3] / a[0] - mx * mx, a[4] / a[0] - mx * my, a[5] / a[0] - my * my};
      for (int c = 0; c < 3; c++) fk[n2][c] = a[6 + c] / a[0];
      cov_deconv(cc, fk[n2], L->cov);
      L->weight = a[0] / sm->M * ps->e_kept;
      pi_[n2] = a[0] / sm->M;
      n2++;
    }
    n = n2;
    if (prm->progress) prm->progress(prm->progress_ctx, it, prm->max_iter, ll);
    if (fabs(ll - ll_prev) <= prm->tol) {
      *converged = 1;
      break;
    }
    ll_prev = ll;
  }
  *iters = it > prm->max_iter ? prm->max_iter : it;
  *ll_out = ll;
  *n_io = n;
  return ICS_OK;
}

/* a start and what EM made of it */
typedef struct fit_state {
  ics_light l[ICS_LIGHTFIT_MAX_K];
  double fk[ICS_LIGHTFIT_MAX_K][3]; /* each component's mass-weighted pixel footprint */
  int n, iterations, converged;
  double ll, l1;
} fit_state;

ics_status ics_lightfit(const ics_image *env, const ics_lightfit_params *prm,
                        ics_light *lights, ics_lightfit_report *report) {
  if (!prm || !lights || !report) return ICS_ERR_INVALID_ARG;
  memset(report, 0, sizeof *report);
  const int K = prm->k;
  if (K < 1 || K > ICS_LIGHTFIT_MAX_K || prm->max_samples < 0 || prm->max_iter < 0 ||
      !(prm->tol >= 0))
    return ICS_ERR_INVALID_ARG;
  memset(lights, 0, (size_t)K * sizeof *lights);
  pixset ps;
  ics_status st = pixset_build(env, prm->max_angle_deg, &ps);
  if (st != ICS_OK) return st;
  report_energies(&ps, report);
  if (!(ps.e_kept > 0)) {
    pixset_free(&ps);
    return ICS_ERR_INVALID_ARG; /* no light behind the viewer inside the cut-off */
  }

  int *stack = malloc((size_t)ps.n * sizeof *stack);
  double *res = malloc((size_t)ps.n * sizeof *res);
  double *fl = malloc((size_t)ps.n * sizeof *fl);
  char *mark = malloc((size_t)ps.n);
  int *sel = malloc((size_t)ps.n * sizeof *sel);
  double *smass = malloc((size_t)ps.n * sizeof *smass);
  double *resp = malloc((size_t)K * sizeof *resp);
  fit_state *fs = malloc(2 * sizeof *fs); /* fs[0]: the fit kept so far, fs[1]: the next start */
  if (!stack || !res || !fl || !mark || !sel || !smass || !resp || !fs) {
    st = ICS_ERR_NOMEM;
    goto out;
  }

  /* samples: all kept pixels with mass, or a seeded systematic resampling of them */
  int ns = 0;
  int nz = 0;
  for (int q = 0; q < ps.n; q++) nz += ps.p[q].m > 0;
  if (prm->max_samples > 0 && nz > prm->max_samples) {
    int N = prm->max_samples;
    double step = ps.e_kept / N;
    double u = ics_rng_uniform_at(prm->seed, 0x6c6967687466ULL /* "lightf" */, 0) * step;
    double cum = 0;
    int drawn = 0;
    for (int q = 0; q < ps.n && drawn < N; q++) {
      cum += ps.p[q].m;
      int c = 0;
      while (drawn < N && u + drawn * step < cum) drawn++, c++;
      if (c) {
        sel[ns] = q;
        smass[ns++] = c * step;
      }
    }
  } else {
    for (int q = 0; q < ps.n; q++)
      if (ps.p[q].m > 0) {
        sel[ns] = q;
        smass[ns++] = ps.p[q].m;
      }
  }
  report->samples = ns;
  em_samples sm = {sel, smass, ns, 0};
  for (int s = 0; s < ns; s++) sm.M += smass[s];

  /* start 0: greedy on the map (step 2). When the map has a floor of at least FLOOR_MIN_SHARE
   * of the kept energy, also starts s = 1 .. FLOOR_MAX_COMPONENTS (s < K): s components for
   * the floor (s = 1: its moments; s = 2: greedy on the floor's density), greedy on the map
   * less the floor for the other K - s. EM from each; the lowest L1 is kept, the earlier start
   * on ties (so a fit is never worse in L1 than start 0's alone) */
  double l2; /* unused */
  fit_state *best = &fs[0], *cur = &fs[1];
  memset(fs, 0, 2 * sizeof *fs);
  for (int q = 0; q < ps.n; q++) res[q] = ps.p[q].d;
  best->n = greedy(&ps, K, best->l, best->fk, stack, res, mark);
  st = em(&ps, &sm, prm, best->l, best->fk, &best->n, resp, &best->ll, &best->iterations,
          &best->converged);
  if (st != ICS_OK) goto out;
  density_errors(&ps, best->l, best->n, &best->l1, &l2);
  double fmass = K > 1 ? floor_density(&ps, fl) : 0;
  if (fmass < 0) {
    st = ICS_ERR_NOMEM;
    goto out;
  }
  for (int s = 1; s <= FLOOR_MAX_COMPONENTS && s < K && fmass >= FLOOR_MIN_SHARE * ps.e_kept;
       s++) {
    memset(cur, 0, sizeof *cur);
    if (s == 1) {
      floor_moments(&ps, fl, &cur->l[0], cur->fk[0]);
      cur->n = 1;
    } else {
      memcpy(res, fl, (size_t)ps.n * sizeof *res);
      cur->n = greedy(&ps, s, cur->l, cur->fk, stack, res, mark);
    }
    for (int q = 0; q < ps.n; q++) res[q] = ps.p[q].d - fl[q];
    cur->n += greedy(&ps, K - cur->n, cur->l + cur->n, cur->fk + cur->n, stack, res, mark);
    st = em(&ps, &sm, prm, cur->l, cur->fk, &cur->n, resp, &cur->ll, &cur->iterations,
            &cur->converged);
    if (st != ICS_OK) goto out;
    density_errors(&ps, cur->l, cur->n, &cur->l1, &l2);
    if (cur->l1 < best->l1) {
      fit_state *t = best;
      best = cur;
      cur = t;
    }
  }
  int n = best->n;
  memcpy(lights, best->l, (size_t)n * sizeof *lights);
  double(*fk)[3] = best->fk;
  report->iterations = best->iterations;
  report->converged = best->converged;
  report->loglik = best->ll;

  /* colours: RGB mass shared by the responsibilities over all kept pixels */
  {
    double rgb[ICS_LIGHTFIT_MAX_K][3], ym[ICS_LIGHTFIT_MAX_K], pi_[ICS_LIGHTFIT_MAX_K];
    gauss g[ICS_LIGHTFIT_MAX_K];
    memset(rgb, 0, sizeof rgb);
    memset(ym, 0, sizeof ym);
    for (int k = 0; k < n; k++) {
      pi_[k] = lights[k].weight / ps.e_kept;
      double cc[3] = {lights[k].cov[0] + fk[k][0], lights[k].cov[1] + fk[k][1],
                      lights[k].cov[2] + fk[k][2]};
      if (gauss_make(&g[k], lights[k].mean[0], lights[k].mean[1], cc)) {
        st = ICS_ERR_RANGE;
        goto out;
      }
    }
    for (int q = 0; q < ps.n; q++) {
      const px *p = &ps.p[q];
      if (!(p->m > 0) && !(p->rgb[0] + p->rgb[1] + p->rgb[2] > 0)) continue;
      double lmax = -INFINITY, sum = 0;
      for (int k = 0; k < n; k++) {
        resp[k] = log(pi_[k]) + gauss_log(&g[k], p->x, p->y);
        if (resp[k] > lmax) lmax = resp[k];
      }
      for (int k = 0; k < n; k++) sum += (resp[k] = exp(resp[k] - lmax));
      for (int k = 0; k < n; k++) {
        double r = resp[k] / sum;
        ym[k] += r * p->m;
        for (int c = 0; c < 3; c++) rgb[k][c] += r * p->rgb[c];
      }
    }
    for (int k = 0; k < n; k++)
      for (int c = 0; c < 3; c++) lights[k].color[c] = ym[k] > 0 ? rgb[k][c] / ym[k] : 1;
  }
  for (int k = n; k < K; k++) memset(&lights[k], 0, sizeof lights[k]);
  report->k_fit = n;
  st = errors(&ps, lights, n, report);
out:
  free(stack);
  free(res);
  free(fl);
  free(mark);
  free(sel);
  free(smass);
  free(resp);
  free(fs);
  pixset_free(&ps);
  return st;
}

int ics_lightfit_auto_choice(const ics_lightfit_report *rep, int kmax) {
  if (!rep || kmax < 1) return 0;
  double best = rep[0].l1;
  for (int k = 1; k < kmax; k++) best = rep[k].l1 < best ? rep[k].l1 : best;
  double limit = best * ICS_LIGHTFIT_AUTO_L1_RATIO > ICS_LIGHTFIT_AUTO_L1_FLOOR
                     ? best * ICS_LIGHTFIT_AUTO_L1_RATIO
                     : ICS_LIGHTFIT_AUTO_L1_FLOOR;
  for (int k = 0; k < kmax; k++)
    if (rep[k].l1 <= limit) return k + 1;
  return kmax;
}
