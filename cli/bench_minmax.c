/* bench_minmax.c — `icshadow bench minmax`: Chen et al. 2011 1D min-max mipmaps against
 * brute-force ray marching at the same resolution, on the synthetic height-field scene of
 * libicshadow (boxes and spherical caps on a plane, directional light, eye outside the scene).
 *
 * Per depth-sample count d: render a d x d orthographic shadow map, rectify it into `rows`
 * epipolar rows of d samples, take the N-term SVD of the in-scattering integrand (Chen Eq. 3-5)
 * sampled on a 64 x 64 (beta, gamma) grid, then integrate `rays` camera rays per row both ways:
 * tree traversal with prefix sums, and the per-sample march over the same N terms. Both compute
 * the same sum, so "equal error" holds by construction; the max difference is printed. Times
 * are the minimum over --reps repetitions, tree and march interleaved in each repetition.
 * --svd-table prints the low-rank error against N instead; --fig4-csv writes the data of
 * Chen's Fig. 4 (one row, its tree, one ray's traversal). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench_stats.h"
#include "commands.h"
#include "icshadow.h"
#include "icshadow/cl.h"

#define GRID 64
#define MAX_TERMS 10 /* beyond, s_N / s_1 < 1e-13 and the Nystrom factors are noise */
/* Limits checked while parsing (see est_bytes / est_work and --help): the estimated peak memory
 * of one configuration, and its estimated work in "operations" (about 0.3-0.6 ns each on the
 * 2-core VM of docs/minmax.md, so 2^36 operations take roughly 20-40 s). */
#define MM_MAX_GIB 4
#define MM_MAX_BYTES ((double)MM_MAX_GIB * 1073741824.0)
#define MM_MAX_WORK 68719476736.0 /* 2^36 */

static const char CMD[] = "bench minmax";
static cli_progress g_prog; /* set up once the options are parsed */
static int g_progress;    /* --progress given */
static int g_cpu = 1;     /* --backend: the CPU rows, */
static void *g_cl; /* and the OpenCL context of the cl rows (ics_cl *, NULL: none) */
static int g_busy;        /* a size's traversal or march times spread over 30 % */

static void help(FILE *f) {
  fprintf(f,
          "usage: icshadow bench minmax [--samples LIST] [--rows N] [--rays N] [--terms N] "
          "[--reps N]\n"
          "                             [--scene hf|noise] [--svd-table] [--fig4-csv FILE] [--progress]\n"
          "\n"
          "1D min-max mipmaps (Chen et al. 2011) vs brute-force ray marching at the same\n"
          "resolution, on the built-in height-field scene. One CSV line per depth-sample count\n"
          "(numbers printed with %%.17g):\n"
          "  samples,rows,rays,terms,build_s,prefix_s,traverse_s,march_s,tree_bytes,march_bytes,\n"
          "  speedup,speedup_with_build,lit_runs_per_ray,max_abs_err,max_rel_err,backend,\n"
          "  traverse_median_s,traverse_max_s,march_median_s,march_max_s\n"
          "(times: seconds, min over --reps, then the traversal's and the march's median and max;\n"
          "speedup = march_s / traverse_s; speedup_with_build adds build_s + prefix_s to the tree\n"
          "side; max_rel_err = max |tree - march| / max |march|).\n"
          "Bytes read + written per repetition, counted from the data structures (float 4, double 8,\n"
          "tree node 8 bytes): tree_bytes = build (rows x (4 d + 16 P + 8 (2P - 2)), P = next power\n"
          "of two >= d) + prefix sums (8 N d read + 8 N (d + 1) written) + traversal (8 per visited\n"
          "node, 16 N per lit run, 8 N per ray); march_bytes = 4 per sample below each ray's end +\n"
          "8 N per lit sample + 8 N per ray (N = --terms).\n"
          "\n"
          "  --samples LIST  comma-separated depth-sample counts d, each 1..16384 (default\n"
          "                  1024,2048,4096); the shadow map is min(d, 4096)^2; rows x d <= 2^25\n"
          "  --rows N        epipolar rows (slices), 1..8192 (default 256)\n"
          "  --rays N        camera rays per row, 1..4096 (default 128)\n"
          "  --terms N       SVD terms N of the integrand, 1..10 (default 4, as the paper)\n"
          "  --reps N        repetitions, 1..100 (default 5)\n"
          "  --scene S       hf: the height-field scene (default); noise: stress rows (random walks\n"
          "                  with jumps, ~sqrt(d) lit runs per ray; same integrand)\n"
          "  --svd-table     print instead: N,sigma_rel,grid_fro_rel,grid_max_rel,\n"
          "                  fullres_max_rel,inscatter_max_rel for N = 1..10 at the first d\n"
          "  --fig4-csv FILE write Chen Fig. 4 data at the first --samples value and exit\n"
          "                  (paper_figs/chen_fig4.py passes --samples 64)\n"
          "  --backend L     cpu (default), cl or cpu,cl: the trees built and traversed on the\n"
          "                  CPU or on the OpenCL device (icshadow/cl.h; build_s and traverse_s\n"
          "                  are its device times, all rays in one batch; march_s and prefix_s\n"
          "                  the CPU's), one row each, side by side\n"
          CLI_CL_DEVICE_HELP
          "  --progress      progress on stderr (default: only when stderr is a terminal)\n"
          "\n"
          "Limits, checked per depth-sample count before anything runs (exit 2 naming the options):\n"
          "  memory: rows x samples x 4 (rectified map) + max(W^2 x 4 (shadow map, W = min(d,\n"
          "    4096)), rows x 2P x 8 (trees, P = next power of two >= d)) + rows x rays x\n"
          "    (8 terms + 48) (ray factors, rays, results) bytes <= %d GiB;\n"
          "  work: 64 W^2 + 64 x 64 x (rows x rays + samples) (set-up: shadow map, low-rank\n"
          "    factors) + reps x rows x rays x samples x (terms + 2) (traversal and march; with\n"
          "    --svd-table rows x rays x samples x 119 instead) <= 2^36 operations (roughly\n"
          "    20-40 s on a 2-core VM).\n"
          "Exit status: 0 ok, 1 runtime failure, 2 bad input.\n",
          MM_MAX_GIB);
}

/* The estimates behind the limits (mode 0: benchmark, 1: --svd-table, 2: --fig4-csv). */
static double est_bytes(double d, double rows, double rays, double terms) {
  double P = 1;
  while (P < d) P *= 2;
  double W = d < 4096 ? d : 4096;
  double big = W * W * 4 > rows * 2 * P * 8 ? W * W * 4 : rows * 2 * P * 8;
  return rows * d * 4 + big + rows * rays * (8 * terms + 48) + 2 * terms * (d + 1) * 8;
}
static double est_work(double d, double rows, double rays, double terms, double reps, int mode) {
  double W = d < 4096 ? d : 4096, nr = rows * rays;
  double w = 64 * W * W + 64.0 * GRID * (nr + d) + rows * d;
  if (mode == 0) w += reps * nr * d * (terms + 2);
  else if (mode == 1) w += nr * d * 119; /* 10 marches (1 + ... + 10 terms) + exact integrand */
  else w += nr * 64;
  return w;
}

/* ---- the scene set-up shared by all modes ---- */
typedef struct setup {
  size_t d, rows, rays, nterms;
  ics_epipolar_frame f;
  ics_heightfield sc;
  float *rect;           /* rows x d */
  double beta_lo, beta_hi;
  double grid[GRID * GRID], U[GRID * GRID], s[GRID], V[GRID * GRID];
  double *terms;          /* nterms x d : Gamma_i(gamma) * dgamma */
  double *prefix;         /* nterms x (d+1) */
  double *B;              /* rows*rays x nterms */
  ics_minmax_ray *ray;    /* rows*rays */
  double *beta;           /* rows*rays */
} setup;

static const double sigma_t = 0.08, sigma_s = 0.05, hg_g = 0.6;

/* In-scattering integrand per unit gamma sample (Chen Eq. 3 for a directional light, no
 * extinction toward the light): ray at angle beta from L; the sample at radial distance
 * rho = gamma dgamma lies at distance s = rho / sin(beta) from the eye; ds/dgamma = dgamma/sin.
 * Henyey-Greenstein phase with scattering angle beta. */
static double integrand(double beta, double gamma, double dgamma) {
  double sb = sin(beta);
  double ph = (1 - hg_g * hg_g) / (4 * ICS_PI * pow(1 + hg_g * hg_g - 2 * hg_g * cos(beta), 1.5));
  return sigma_s * ph * exp(-sigma_t * gamma * dgamma / sb) * dgamma / sb;
}

static double grid_beta(const setup *S, size_t j) {
  return S->beta_lo + (S->beta_hi - S->beta_lo) * (double)j / (GRID - 1);
}
static double grid_gamma(const setup *S, size_t k) { return (double)(S->d - 1) * (double)k / (GRID - 1); }

/* The factors at full resolution by Nystrom extension of the grid SVD A = U S V^T:
 *   Gamma_i(gamma) = sum_j U_ji I(beta_j, gamma) / s_i   (= V_i on the grid)
 *   B_i(beta)      = sum_k I(beta, gamma_k) V_ki         (= s_i U_i on the grid)
 * so sum_{i<N} B_i Gamma_i reproduces the rank-N truncation A_N on the grid and extends it
 * smoothly between grid points without interpolation error. Gamma_i includes the sample
 * width (the integrand is per sample). */
static int nystrom_gamma(const setup *S, size_t nterms, double *terms) {
  size_t d = S->d;
  double *col = malloc(GRID * sizeof(double));
  if (!col) return 1;
  for (size_t g = 0; g < d; g++) {
    for (size_t j = 0; j < GRID; j++) col[j] = integrand(grid_beta(S, j), (double)g, S->f.dgamma);
    for (size_t i = 0; i < nterms; i++) {
      double acc = 0;
      for (size_t j = 0; j < GRID; j++) acc += S->U[j * GRID + i] * col[j];
      terms[i * d + g] = acc / S->s[i];
    }
  }
  free(col);
  return 0;
}

static void nystrom_beta(const setup *S, double beta, size_t nterms, double *B) {
  double row[GRID];
  for (size_t k = 0; k < GRID; k++) row[k] = integrand(beta, grid_gamma(S, k), S->f.dgamma);
  for (size_t i = 0; i < nterms; i++) {
    double acc = 0;
    for (size_t k = 0; k < GRID; k++) acc += row[k] * S->V[k * GRID + i];
    B[i] = acc;
  }
}

static void setup_free(setup *S) {
  free(S->rect);
  free(S->terms);
  free(S->prefix);
  free(S->B);
  free(S->ray);
  free(S->beta);
}

/* returns 0, or 1 on a runtime failure (message printed) */
static int setup_init(setup *S, size_t d, size_t rows, size_t rays, size_t nterms, int noise) {
  memset(S, 0, sizeof *S);
  cli_progress_say(&g_prog, "samples %zu: scene, shadow map, rectification and low-rank factors...", d);
  S->d = d;
  S->rows = rows;
  S->rays = rays;
  S->nterms = nterms;
  ics_heightfield_init_default(&S->sc);
  const double eye[3] = {0.3, 3.0, 9.0}, L[3] = {0.8, 0.45, -0.5};
  ics_status st = ics_epipolar_frame_init(&S->f, eye, L, rows, d, 1.0);
  /* radius: the farthest light-plane projection of the scene's bounding box from the epipole */
  double R = 0;
  for (int c = 0; c < 8 && st == ICS_OK; c++) {
    double p[3] = {c & 1 ? 6.0 : -6.0, c & 2 ? 2.5 : 0.0, c & 4 ? 6.0 : -6.0}, a, g, dep;
    ics_epipolar_locate(&S->f, p, &a, &g, &dep);
    if (g > R) R = g;
  }
  R *= 1.05;
  if (st == ICS_OK) st = ics_epipolar_frame_init(&S->f, eye, L, rows, d, R / (double)d);
  S->rect = malloc(rows * d * sizeof(float));
  size_t W = d < 4096 ? d : 4096; /* shadow map W x W */
  float *smap = malloc(W * W * sizeof(float));
  S->terms = malloc(nterms * d * sizeof(double));
  S->prefix = malloc(nterms * (d + 1) * sizeof(double));
  S->B = malloc(rows * rays * nterms * sizeof(double));
  S->ray = malloc(rows * rays * sizeof(ics_minmax_ray));
  S->beta = malloc(rows * rays * sizeof(double));
  if (!S->rect || !smap || !S->terms || !S->prefix || !S->B || !S->ray || !S->beta) {
    cli_failure(CMD, "out of memory at d = %zu", d);
    free(smap);
    return 1;
  }
  if (st == ICS_OK) st = ics_heightfield_shadow_map(&S->sc, &S->f, W, R, smap);
  if (st == ICS_OK)
    st = ics_epipolar_rectify(&S->f, smap, W, W, S->f.eu - R, S->f.ev - R, 2 * R / (double)W,
                              S->rect);
  free(smap);
  /* low-rank integrand on a GRID x GRID (beta, gamma) grid */
  S->beta_lo = 0.12 * ICS_PI;
  S->beta_hi = 0.88 * ICS_PI;
  for (size_t j = 0; j < GRID; j++)
    for (size_t k = 0; k < GRID; k++)
      S->grid[j * GRID + k] = integrand(grid_beta(S, j), grid_gamma(S, k), S->f.dgamma);
  if (st == ICS_OK) st = ics_svd(S->grid, GRID, GRID, S->U, S->s, S->V);
  if (st != ICS_OK) return cli_failure(CMD, "scene set-up failed: %s", ics_status_str(st));
  if (nystrom_gamma(S, nterms, S->terms)) return cli_failure(CMD, "out of memory at d = %zu", d);
  st = ics_minmax_prefix(S->terms, nterms, d, d, S->prefix, d + 1);
  /* camera rays: `rays` angles per row, each ending at its first surface */
  for (size_t r = 0; r < rows && st == ICS_OK; r++)
    for (size_t k = 0; k < rays; k++) {
      size_t q = r * rays + k;
      double beta = S->beta_lo + (S->beta_hi - S->beta_lo) * ((double)k + 0.5) / (double)rays;
      double dir[3], alpha;
      size_t row;
      ics_epipolar_ray_dir(&S->f, r, beta, dir);
      st = ics_epipolar_ray(&S->f, dir, &alpha, &row, &S->ray[q]);
      double hit = ics_heightfield_hit(&S->sc, S->f.eye, dir, 0.0);
      double gend = isinf(hit) ? (double)d : ceil(hit * sin(beta) / S->f.dgamma);
      S->ray[q].gamma_end = gend >= (double)d ? d : (size_t)gend;
      S->beta[q] = beta;
      nystrom_beta(S, beta, nterms, S->B + q * nterms);
    }
  if (st != ICS_OK) return cli_failure(CMD, "scene set-up failed: %s", ics_status_str(st));
  if (noise) { /* stress rows: random walks (steps uniform in +-1/2, then +-8 jumps 1 in 16),
                * rays: lines through the walk's range over the whole row */
    uint64_t x = 0x2545F4914F6CDD1Dull;
    for (size_t r = 0; r < rows; r++) {
      double w = 0;
      for (size_t g = 0; g < d; g++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        double u = (double)(x >> 11) * 0x1p-53;
        w += (x & 15) == 0 ? (u - 0.5) * 16 : u - 0.5;
        S->rect[r * d + g] = (float)w;
      }
      float lo = S->rect[r * d], hi = lo;
      for (size_t g = 0; g < d; g++) {
        lo = S->rect[r * d + g] < lo ? S->rect[r * d + g] : lo;
        hi = S->rect[r * d + g] > hi ? S->rect[r * d + g] : hi;
      }
      for (size_t k = 0; k < rays; k++) {
        size_t q = r * rays + k;
        double a = lo + (hi - lo) * ((double)k + 0.5) / (double)rays;
        double b = lo + (hi - lo) * ((double)((k * 7 + 3) % rays) + 0.5) / (double)rays;
        S->ray[q].beta0 = a;
        S->ray[q].slope = (b - a) / (double)d;
        S->ray[q].gamma_end = d;
      }
    }
  }
  return 0;
}

static int bench_one(const setup *S, int reps) {
  size_t d = S->d, nr = S->rows * S->rays, N = S->nterms;
  double *Lt = malloc(nr * sizeof(double)), *Lm = malloc(nr * sizeof(double));
  double *pre = malloc(N * (d + 1) * sizeof(double));
  if (!Lt || !Lm || !pre) {
    free(Lt);
    free(Lm);
    free(pre);
    return cli_failure(CMD, "out of memory");
  }
  double tb = INFINITY, tp = INFINITY, tt = INFINITY, tm = INFINITY, tts[100], tms[100];
  int nrep = 0;
  ics_status st = ICS_OK;
  double runs = 0, visited = 0, lit = 0, marched = 0; /* totals over the rays, for the bytes */
  size_t P = 1;
  while (P < d) P <<= 1;
  const size_t maxseg = d / 2 + 1; /* maximal lit runs are separated by >= 1 shadowed sample */
  unsigned char *cls = malloc(2 * P);
  size_t *seg = malloc(2 * maxseg * sizeof *seg);
  if (!cls || !seg) st = ICS_ERR_NOMEM;
  for (int rep = 0; rep < reps && st == ICS_OK; rep++) {
    cli_progress_say(&g_prog, "samples %zu: repetition %d/%d", d, rep + 1, reps);
    ics_minmax *t = NULL;
    double t0 = cli_now_s();
    st = ics_minmax_create(&t, S->rect, S->rows, d, d);
    double t1 = cli_now_s();
    if (st == ICS_OK) st = ics_minmax_prefix(S->terms, N, d, d, pre, d + 1);
    double t2 = cli_now_s();
    double out[MAX_TERMS];
    for (size_t q = 0; q < nr && st == ICS_OK; q++) {
      st = ics_minmax_integrate(t, q / S->rays, &S->ray[q], pre, N, d + 1, out);
      double L = 0;
      for (size_t i = 0; i < N; i++) L += S->B[q * N + i] * out[i];
      Lt[q] = L;
    }
    double t3 = cli_now_s();
    for (size_t q = 0; q < nr && st == ICS_OK; q++) {
      st = ics_minmax_march(S->rect + (q / S->rays) * d, d, &S->ray[q], S->terms, N, d, out);
      double L = 0;
      for (size_t i = 0; i < N; i++) L += S->B[q * N + i] * out[i];
      Lm[q] = L;
    }
    double t4 = cli_now_s();
    if (rep == 0 && st == ICS_OK)
      for (size_t q = 0; q < nr; q++) {
        size_t ns = 0;
        ics_minmax_segments(t, q / S->rays, &S->ray[q], seg, maxseg, &ns, cls);
        runs += (double)ns;
        for (size_t k = 1; k < 2 * P; k++) visited += cls[k] != 0;
        for (size_t j = 0; j < ns && j < maxseg; j++) lit += (double)(seg[2 * j + 1] - seg[2 * j]);
        marched += (double)S->ray[q].gamma_end;
      }
    ics_minmax_destroy(t);
    tb = fmin(tb, t1 - t0);
    tp = fmin(tp, t2 - t1);
    tt = fmin(tt, t3 - t2);
    tm = fmin(tm, t4 - t3);
    if (nrep < 100) tts[nrep] = t3 - t2, tms[nrep] = t4 - t3, nrep++;
  }
  /* the columns' times are minima, with the traversal's and the march's medians and maxima at
   * the end of the row; their spread says whether the machine was busy */
  cli_spread sp_t = {tt, tt, tt}, sp_m = {tm, tm, tm};
  if (nrep > 0) sp_t = cli_spread_of(tts, nrep), sp_m = cli_spread_of(tms, nrep);
  if (nrep > 1 && (cli_spread_busy(sp_t) || cli_spread_busy(sp_m))) g_busy = 1;
  free(cls);
  free(seg);
  if (st != ICS_OK) {
    cli_failure(CMD, "%s", ics_status_str(st));
    free(Lt);
    free(Lm);
    free(pre);
    return 1;
  }
  /* Bytes read + written, from the data structures (floats 4, doubles 8, a node 8):
   * tree side = build (read rows x d samples, write rows x 2P nodes, read the 2P - 2 children)
   * + prefix sums (read N d terms, write N (d + 1) sums) + traversal (read every visited node,
   * 2 prefix sums per lit run and term, write N results per ray); march = read every sample
   * below gamma_end and N terms per lit sample, write N results per ray. */
  double Nd = (double)N, rows = (double)S->rows;
  double tree_bytes = rows * ((double)d * 4 + 2.0 * (double)P * 8 + (2.0 * (double)P - 2) * 8) +
                      Nd * (double)d * 8 + Nd * ((double)d + 1) * 8 + visited * 8 + runs * 2 * Nd * 8 +
                      (double)nr * Nd * 8;
  double march_bytes = marched * 4 + lit * Nd * 8 + (double)nr * Nd * 8;
  double maxL = 0, maxe = 0;
  for (size_t q = 0; q < nr; q++) {
    maxL = fmax(maxL, fabs(Lm[q]));
    maxe = fmax(maxe, fabs(Lt[q] - Lm[q]));
  }
  if (g_cpu)
    printf("%zu,%zu,%zu,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,cpu,"
           "%.17g,%.17g,%.17g,%.17g\n",
           d, S->rows, S->rays, N, tb, tp, tt, tm, tree_bytes, march_bytes, tm / tt,
           tm / (tb + tp + tt), runs / (double)nr, maxe, maxL > 0 ? maxe / maxL : 0.0,
           sp_t.median, sp_t.max, sp_m.median, sp_m.max);
  if (g_cl) {
    /* the same trees and rays on the device: build and one batch of all rays, min over reps */
    size_t *rr = malloc(sizeof *rr * nr);
    double *oc = malloc(sizeof *oc * nr * N), cb = INFINITY, ct = INFINITY, cts[100];
    int ncts = 0;
    char msg[1024] = "";
    if (!rr || !oc) st = ICS_ERR_NOMEM;
    for (size_t q = 0; q < nr && rr; q++) rr[q] = q / S->rays;
    if (st == ICS_OK) st = ics_minmax_prefix(S->terms, N, d, d, pre, d + 1);
    for (int rep = 0; rep < reps && st == ICS_OK; rep++) {
      ics_cl_minmax *tc = NULL;
      double mb = 0, mt = 0;
      st = ics_cl_minmax_create(g_cl, S->rect, S->rows, d, d, &tc, &mb, msg, sizeof msg);
      if (st == ICS_OK)
        st = ics_cl_minmax_integrate(tc, rr, S->ray, nr, pre, N, d + 1, oc, NULL, &mt, msg, sizeof msg);
      ics_cl_minmax_destroy(tc);
      cb = fmin(cb, 1e-3 * mb), ct = fmin(ct, 1e-3 * mt);
      if (st == ICS_OK && ncts < 100) cts[ncts++] = 1e-3 * mt;
    }
    double maxc = 0;
    for (size_t q = 0; q < nr && st == ICS_OK; q++) {
      double L = 0;
      for (size_t i = 0; i < N; i++) L += S->B[q * N + i] * oc[q * N + i];
      maxc = fmax(maxc, fabs(L - Lm[q]));
    }
    free(rr), free(oc);
    if (st != ICS_OK) {
      free(Lt), free(Lm), free(pre);
      return cli_status_error(CMD, st, "--backend cl, samples %zu: %s", d, msg[0] ? msg : ics_status_str(st));
    }
    cli_spread sp_c = ncts ? cli_spread_of(cts, ncts) : (cli_spread){ct, ct, ct};
    if (ncts > 1 && cli_spread_busy(sp_c)) g_busy = 1;
    printf("%zu,%zu,%zu,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,cl,"
           "%.17g,%.17g,%.17g,%.17g\n",
           d, S->rows, S->rays, N, cb, tp, ct, tm, tree_bytes, march_bytes, tm / ct,
           tm / (cb + tp + ct), runs / (double)nr, maxc, maxL > 0 ? maxc / maxL : 0.0,
           sp_c.median, sp_c.max, sp_m.median, sp_m.max);
  }
  free(Lt);
  free(Lm);
  free(pre);
  return cli_stdout_failed(CMD);
}

/* Low-rank error against N: on the grid, at full resolution, and on the in-scattering. */
static int svd_table(setup *S) {
  size_t d = S->d, nr = S->rows * S->rays;
  double fa = 0, ma = 0;
  for (size_t i = 0; i < GRID * GRID; i++) {
    fa += S->grid[i] * S->grid[i];
    ma = fmax(ma, fabs(S->grid[i]));
  }
  fa = sqrt(fa);
  double *AN = malloc(GRID * GRID * sizeof(double));
  double *terms = S->terms, *Lx = malloc(nr * sizeof(double));
  if (!AN || !Lx) {
    free(AN);
    free(Lx);
    return cli_failure(CMD, "out of memory");
  }
  /* reference in-scattering: the exact integrand at every lit sample */
  double maxL = 0;
  for (size_t q = 0; q < nr; q++) {
    const float *row = S->rect + (q / S->rays) * d;
    const ics_minmax_ray *ry = &S->ray[q];
    double acc = 0;
    for (size_t g = 0; g < ry->gamma_end; g++)
      if ((double)row[g] > ry->beta0 + ry->slope * (double)g) acc += integrand(S->beta[q], (double)g, S->f.dgamma);
    Lx[q] = acc;
    maxL = fmax(maxL, fabs(acc));
  }
  printf("N,sigma_rel,grid_fro_rel,grid_max_rel,fullres_max_rel,inscatter_max_rel\n");
  for (size_t N = 1; N <= MAX_TERMS; N++) {
    cli_progress_say(&g_prog, "samples %zu: N = %zu/%d", d, N, MAX_TERMS);
    ics_svd_truncate(S->U, S->s, S->V, GRID, GRID, N, AN);
    double fe = 0, me = 0;
    for (size_t i = 0; i < GRID * GRID; i++) {
      fe += (S->grid[i] - AN[i]) * (S->grid[i] - AN[i]);
      me = fmax(me, fabs(S->grid[i] - AN[i]));
    }
    /* full resolution: every ray's beta x every sample, with the interpolated factors */
    double fr = 0, frmax = 0, le = 0;
    for (size_t q = 0; q < nr; q += S->rays > 8 ? S->rays / 8 : 1) {
      const double *Bq = S->B + q * S->nterms;
      for (size_t g = 0; g < d; g += 7) {
        double ex = integrand(S->beta[q], (double)g, S->f.dgamma), ap = 0;
        for (size_t i = 0; i < N; i++) ap += Bq[i] * terms[i * d + g];
        fr = fmax(fr, fabs(ex - ap));
        frmax = fmax(frmax, fabs(ex));
      }
    }
    for (size_t q = 0; q < nr; q++) {
      const float *row = S->rect + (q / S->rays) * d;
      double out[MAX_TERMS], L = 0;
      ics_minmax_march(row, d, &S->ray[q], terms, N, d, out);
      for (size_t i = 0; i < N; i++) L += S->B[q * S->nterms + i] * out[i];
      le = fmax(le, fabs(L - Lx[q]));
    }
    printf("%zu,%.17g,%.17g,%.17g,%.17g,%.17g\n", N, S->s[N - 1] / S->s[0], sqrt(fe) / fa, me / ma,
           fr / frmax, maxL > 0 ? le / maxL : 0.0);
  }
  free(AN);
  free(Lx);
  return cli_stdout_failed(CMD);
}

/* Chen Fig. 4: the row with the most lit runs for the middle ray; all its samples, its tree
 * nodes with their class for that ray, the ray, and the lit runs. */
static int fig4(setup *S, const char *path) {
  size_t d = S->d, P = 1;
  while (P < d) P <<= 1;
  ics_minmax *t = NULL;
  ics_status st = ics_minmax_create(&t, S->rect, S->rows, d, d);
  if (st != ICS_OK) return cli_failure(CMD, "%s", ics_status_str(st));
  size_t best = 0, bestn = 0;
  for (size_t q = 0; q < S->rows * S->rays; q++) {
    size_t ns = 0;
    ics_minmax_segments(t, q / S->rays, &S->ray[q], NULL, 0, &ns, NULL);
    if (ns > bestn) {
      bestn = ns;
      best = q;
    }
  }
  size_t row = best / S->rays;
  const ics_minmax_ray *ry = &S->ray[best];
  unsigned char *cls = calloc(2 * P, 1);
  size_t *seg = malloc(2 * (d + 1) * sizeof(size_t)), nseg = 0;
  cli_output out;
  if (!cls || !seg || cli_output_open(&out, CMD, path) != 0) {
    free(cls);
    free(seg);
    ics_minmax_destroy(t);
    if (!cls || !seg) cli_failure(CMD, "out of memory");
    return 1;
  }
  ics_minmax_segments(t, row, ry, seg, d + 1, &nseg, cls);
  FILE *fp = out.fp;
  fprintf(fp, "kind,index,level,g0,g1,lo,hi,class\n");
  for (size_t g = 0; g < d; g++)
    fprintf(fp, "sample,%zu,,%zu,%zu,%.17g,%.17g,%d\n", g, g, g + 1, S->rect[row * d + g],
            S->rect[row * d + g], g < ry->gamma_end && (double)S->rect[row * d + g] > ry->beta0 + ry->slope * (double)g);
  for (size_t k = 1; k < 2 * P; k++) {
    size_t g0, g1, level = 0;
    float lo, hi;
    while (((size_t)2 << level) <= k) level++;
    ics_minmax_node_range(t, k, &g0, &g1);
    ics_minmax_node(t, row, k, &lo, &hi);
    if (g0 < g1) fprintf(fp, "node,%zu,%zu,%zu,%zu,%.17g,%.17g,%d\n", k, level, g0, g1, lo, hi, cls[k]);
  }
  fprintf(fp, "ray,%zu,,0,%zu,%.17g,%.17g,\n", row, ry->gamma_end, ry->beta0, ry->slope);
  for (size_t j = 0; j < nseg; j++) fprintf(fp, "run,%zu,,%zu,%zu,,,\n", j, seg[2 * j], seg[2 * j + 1]);
  free(cls);
  free(seg);
  ics_minmax_destroy(t);
  return cli_output_commit(&out) != 0;
}

/* --samples: comma-separated depth-sample counts, at most 16 */
typedef struct sample_list {
  int v[16], n;
} sample_list;

static int parse_samples(const char *cmd, const char *opt, const char *val, void *dest) {
  sample_list *list = dest;
  char buf[256];
  if (strlen(val) >= sizeof buf) return cli_error(cmd, "%s: list too long", opt);
  strcpy(buf, val);
  list->n = 0;
  /* split at every comma: an empty item ("", "1,,2", "1,") is an error, as in sat's --modes */
  for (char *tok = buf;;) {
    char *comma = strchr(tok, ',');
    if (comma) *comma = '\0';
    if (!*tok)
      return cli_error(cmd, "%s: expected integers in 1..16384, got an empty item in '%s'", opt,
                       val);
    if (list->n == 16) return cli_error(cmd, "%s: at most 16 values", opt);
    if (cli_parse_int(tok, 1, 16384, &list->v[list->n]) != 0)
      return cli_error(cmd, "%s: expected an integer in 1..16384, got '%s'", opt, tok);
    list->n++;
    if (!comma) break;
    tok = comma + 1;
  }
  return 0;
}

/* --scene: hf (0) or noise (1) */
static int parse_scene(const char *cmd, const char *opt, const char *val, void *dest) {
  if (strcmp(val, "hf") && strcmp(val, "noise"))
    return cli_error(cmd, "%s: expected 'hf' or 'noise', got '%s'", opt, val);
  *(int *)dest = !strcmp(val, "noise");
  return 0;
}

int bench_minmax(int argc, char **argv) {
  if (cli_wants_help(argc, argv)) {
    help(stdout);
    return 0;
  }
  sample_list samples = {{1024, 2048, 4096}, 3};
  int rows = 256, rays = 128, terms = 4, reps = 5, table = 0, noise = 0;
  const char *figpath = NULL, *backend = "cpu";
  int given_samples = 0, given_terms = 0, given_reps = 0;
  const cli_option opts[] = {
      {"--samples", .kind = CLI_CALL, .dest = &samples, .parse = parse_samples,
       .given = &given_samples},
      {"--rows", .kind = CLI_INT, .dest = &rows, .lo = 1, .hi = 8192},
      {"--rays", .kind = CLI_INT, .dest = &rays, .lo = 1, .hi = 4096},
      {"--terms", .kind = CLI_INT, .dest = &terms, .lo = 1, .hi = MAX_TERMS, .given = &given_terms},
      {"--reps", .kind = CLI_INT, .dest = &reps, .lo = 1, .hi = 100, .given = &given_reps},
      {"--scene", .kind = CLI_CALL, .dest = &noise, .parse = parse_scene},
      {"--svd-table", .kind = CLI_FLAG, .dest = &table},
      {"--fig4-csv", .kind = CLI_FILE, .dest = &figpath},
      {"--progress", .kind = CLI_FLAG, .dest = &g_progress},
      {"--backend", .kind = CLI_STRING, .dest = &backend},
      {"--cl-device", .kind = CLI_CALL, .parse = cli_parse_cl_device},
  };
  int rc = cli_parse_options(CMD, argc, argv, 1, opts, CLI_NOPTS(opts));
  if (rc) return rc;
  int want_cl = 0;
  if (!strcmp(backend, "cpu")) g_cpu = 1;
  else if (!strcmp(backend, "cl")) g_cpu = 0, want_cl = 1;
  else if (!strcmp(backend, "cpu,cl") || !strcmp(backend, "cl,cpu")) g_cpu = 1, want_cl = 1;
  else return cli_error(CMD, "--backend: expected cpu, cl or cpu,cl, got '%s'", backend);
  if (rc) return rc;
  const int *dlist = samples.v, nd = samples.n;
  for (int k = 0; k < nd; k++)
    if ((size_t)rows * (size_t)dlist[k] > ((size_t)1 << 25))
      return cli_error(CMD, "--rows %d x --samples %d exceeds 2^25 samples", rows, dlist[k]);
  /* options a mode does not use: an error when they contradict, a warning when ignored */
  if (figpath && table) return cli_error(CMD, "--svd-table and --fig4-csv: choose one");
  if (figpath || table) {
    const char *mode_opt = figpath ? "--fig4-csv" : "--svd-table";
    if (given_reps) cli_warning(CMD, "--reps is ignored with %s", mode_opt);
    if (given_terms && table)
      cli_warning(CMD, "--terms is ignored with --svd-table (it prints N = 1..%d)", MAX_TERMS);
    if (given_samples && nd > 1)
      cli_warning(CMD, "%s uses only the first --samples value (%d)", mode_opt, dlist[0]);
  }
  /* memory and work limits, per configuration that will run */
  int mode = figpath ? 2 : table ? 1 : 0, ncheck = mode ? 1 : nd;
  for (int k = 0; k < ncheck; k++) {
    double dd = dlist[k], nt = mode == 1 ? MAX_TERMS : terms;
    double by = est_bytes(dd, rows, rays, nt), wk = est_work(dd, rows, rays, nt, reps, mode);
    if (by > MM_MAX_BYTES)
      return cli_error(CMD, "--samples %d with --rows %d and --rays %d%s needs an estimated %.1f "
                       "GiB of memory; the limit is %d GiB (see --help)", dlist[k], rows, rays,
                       mode == 1 ? " (--svd-table: 10 terms)" : "", by / 1073741824.0, MM_MAX_GIB);
    if (wk > MM_MAX_WORK) {
      char extra[64];
      if (mode == 0)
        snprintf(extra, sizeof extra, ", --terms %d and --reps %d", terms, reps);
      else
        snprintf(extra, sizeof extra, "%s", mode == 1 ? " and --svd-table" : " and --fig4-csv");
      return cli_error(CMD, "--samples %d with --rows %d, --rays %d%s: an estimated %.3g "
                       "operations; the work limit is 2^36 = %.3g (about 20-40 s here; see --help)",
                       dlist[k], rows, rays, extra, wk, MM_MAX_WORK);
    }
  }
  cli_progress_init(&g_prog, "icshadow bench minmax", g_progress);
  setup S;
  if (figpath || table) {
    rc = setup_init(&S, (size_t)dlist[0], (size_t)rows, (size_t)rays,
                    figpath ? (size_t)terms : MAX_TERMS, noise);
    if (rc == 0) rc = figpath ? fig4(&S, figpath) : svd_table(&S);
    setup_free(&S);
    cli_progress_done(&g_prog);
    return rc;
  }
  if (want_cl) {
    char msg[2048];
    ics_cl *cl = NULL;
    if (ics_cl_create(&cl, msg, sizeof msg) != ICS_OK) {
      cli_progress_done(&g_prog);
      return cli_error(CMD, "--backend cl: %s", msg);
    }
    g_cl = cl;
  }
  printf("samples,rows,rays,terms,build_s,prefix_s,traverse_s,march_s,tree_bytes,march_bytes,speedup,"
         "speedup_with_build,lit_runs_per_ray,max_abs_err,max_rel_err,backend,traverse_median_s,"
         "traverse_max_s,march_median_s,march_max_s\n");
  for (int k = 0; k < nd; k++) {
    rc = setup_init(&S, (size_t)dlist[k], (size_t)rows, (size_t)rays, (size_t)terms, noise);
    if (rc == 0) rc = bench_one(&S, reps);
    setup_free(&S);
    if (rc) break;
  }
  ics_cl_destroy(g_cl);
  g_cl = NULL;
  cli_progress_done(&g_prog);
  if (g_busy) cli_warn_busy(CMD, "traverse_s, march_s; the columns are minima");
  return rc;
}
