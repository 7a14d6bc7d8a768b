/* occtex.c — occlusion textures (Eisemann & Décoret 2006): slicing, three prefilters (mipmap,
 * N-Buffers, summed-area table), box lookups of size s(P) (their Eq. 4), product / sum / max
 * combination (their Eq. 5) with slice fading, and a brute-force reference.
 *
 * Method and conventions: see icshadow/occtex.h and docs/occtex.md. Summary:
 * - Slicing: K slices (z_k, z_{k+1}] (slice 0 closed at z_near), each projected along z onto its
 *   bottom plane z_{k+1}; texel coverage from ss x ss sub-cell centre samples of the union of the
 *   box parts in the slice (exact when box edges fall on sub-cell edges).
 * - Texture = piecewise-constant field on [0, n]^2 (texel units), 0 outside.
 * - SAT (ics_sat2d from sat.h, double precision): exact box integral of any real rectangle
 *   (bilinear interpolation of the table, clamped to the grid); error bound of sat.h:
 *   4.04 * 2^-53 * 2n * n^2 on the integral. Boxes of area below 1 texel^2 (including zero-size
 *   point lookups) are summed directly over the (at most a few) texels they touch, which is
 *   exact too and avoids dividing cancellation noise by a tiny area.
 * - N-Buffers: level l (0 .. L = log2 n) stores N_l(i, j) = mean over [i, i + 2^l) x [j, j + 2^l)
 *   for i, j in [-(2^l - 1), n - 1] (the padded range, so boxes hanging over the lower/left
 *   border stay exact; outside it the value is 0). Built by N_{l+1}(i) = mean of N_l at i and
 *   i + 2^l (per axis). Lookup of a square box of side s at centre c: bilinear interpolation of
 *   N_l at the corner c - 2^l/2 (exact: the response of a box of integer width is bilinear
 *   between integer corners), for l = floor(log2 s) and l + 1, blended linearly in s:
 *   f = (s - 2^l)/2^l. s <= 1 uses level 0 at s = 1 (= bilinear texture filtering).
 * - Mipmap: level l has (n >> l)^2 texels, each the mean of its 4 children. Lookup: bilinear in
 *   levels floor(log2 s) and +1 at the box centre (texel centres at (i + 1/2) 2^l), blended
 *   linearly in log2 s (trilinear filtering). s <= 1 is bilinear on level 0.
 * - Both pyramids: a box wider than the texture (s > n) uses the top level's value scaled by
 *   (n/s)^2 (exact when all occlusion inside the box lies in its central n x n part); a
 *   rectangular box picks the level from its minor side s_e = max(minor, major/16) and averages
 *   N = ceil(major/s_e) taps spread along the major side.
 * - Combination of faded contributions f_k = w_k O_k: product 1 - prod(1 - f_k); sum
 *   min(1, sum f_k); max. max <= product <= clamped sum holds for f_k in [0, 1].
 * - Brute force: m x m rays from P to the light cell centres, slab test against every box whose
 *   xy-extent meets the bounding box of the light and P and whose z0 < pz. The ray segment is
 *   taken as s in [1e-12, 1] (s = 0 at P), so a point lying on a box's face toward the light is
 *   not occluded by that box; boxes are closed otherwise (zero-thickness plates occlude).
 * Special cases: NaN/Inf and bad sizes are rejected with a status before any work. */
#include "icshadow/occtex.h"
#include "icshadow/constants.h"
#include "icshadow/sat.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_finite.h"
#include "raybox.h"

struct ics_occtex {
  int n, K, L; /* side, slices, top level (n = 2^L) */
  double x0, y0, texel, z_near, z_far;
  float *tex;  /* K n^2 */
  float *mip;  /* K * mip_total */
  size_t mip_off[14], mip_total;
  float *nb; /* K * nb_total */
  size_t nb_off[14], nb_total;
  ics_sat2d **sat; /* K tables, or NULL */
};

static const char *const prefilter_names[] = {"mipmap", "nbuffers", "sat"};
static const char *const combine_names[] = {"product", "sum", "max"};

const char *ics_occtex_prefilter_name(ics_occ_prefilter pf) {
  return (unsigned)pf < ICS_OCC_PREFILTER_COUNT ? prefilter_names[pf] : NULL;
}
const char *ics_occtex_combine_name(ics_occ_combine c) {
  return (unsigned)c < ICS_OCC_COMBINE_COUNT ? combine_names[c] : NULL;
}

/* ---- argument checks ------------------------------------------------------------------ */
static int log2_exact(int n) { /* log2 n for a power of two n >= 1, else -1 */
  if (n < 1 || (n & (n - 1))) return -1;
  int l = 0;
  while ((1 << l) < n) l++;
  return l;
}

static ics_status check_grid(const ics_occ_grid *g) {
  if (!g) return ICS_ERR_INVALID_ARG;
  ics_status st;
  if ((st = ics_check_finite(g->x0)) || (st = ics_check_finite(g->y0)) || (st = ics_check_finite(g->texel))) return st;
  if (!(g->texel > 0)) return ICS_ERR_INVALID_ARG;
  if (g->n > ICS_OCC_MAX_SIZE || log2_exact(g->n) < 0) return ICS_ERR_SIZE;
  return ICS_OK;
}

static ics_status check_slices(int slices, double z_near, double z_far) {
  ics_status st;
  if ((st = ics_check_finite(z_near)) || (st = ics_check_finite(z_far))) return st;
  if (slices < 1) return ICS_ERR_INVALID_ARG;
  if (slices > ICS_OCC_MAX_SLICES) return ICS_ERR_SIZE;
  if (!(z_near > 0) || !(z_far > z_near)) return ICS_ERR_INVALID_ARG;
  return ICS_OK;
}

static ics_status check_light(const ics_occ_light *l) {
  if (!l) return ICS_ERR_INVALID_ARG;
  ics_status st;
  if ((st = ics_check_finite(l->cx)) || (st = ics_check_finite(l->cy)) || (st = ics_check_finite(l->wx)) ||
      (st = ics_check_finite(l->wy)))
    return st;
  if (l->wx < 0 || l->wy < 0) return ICS_ERR_INVALID_ARG;
  return ICS_OK;
}

static ics_status check_boxes(const ics_occ_box *b, size_t nb) {
  if (nb && !b) return ICS_ERR_INVALID_ARG;
  for (size_t i = 0; i < nb; i++) {
    const double v[6] = {b[i].x0, b[i].y0, b[i].z0, b[i].x1, b[i].y1, b[i].z1};
    for (int j = 0; j < 6; j++) {
      ics_status st = ics_check_finite(v[j]);
      if (st) return st;
    }
    if (b[i].x1 < b[i].x0 || b[i].y1 < b[i].y0 || b[i].z1 < b[i].z0) return ICS_ERR_INVALID_ARG;
  }
  return ICS_OK;
}

static ics_status check_points(const double *P, size_t n, const double *out) {
  if (n == 0) return ICS_ERR_SIZE;
  if (!P || !out) return ICS_ERR_INVALID_ARG;
  for (size_t i = 0; i < 3 * n; i++) {
    ics_status st = ics_check_finite(P[i]);
    if (st) return st;
  }
  for (size_t i = 0; i < n; i++)
    if (!(P[3 * i + 2] > 0)) return ICS_ERR_INVALID_ARG;
  return ICS_OK;
}

/* ---- scenes ----------------------------------------------------------------------------- */
static uint64_t splitmix64(uint64_t *s) {
  uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
static double uni(uint64_t *s, double a, double b) { /* uniform in [a, b) */
  return a + (b - a) * (double)(splitmix64(s) >> 11) * 0x1p-53;
}

ics_status ics_occtex_boxes_make(ics_occ_boxes_kind kind, int nboxes, uint64_t seed,
                                 ics_occ_box *out) {
  if (nboxes < 1) return ICS_ERR_SIZE;
  if (!out) return ICS_ERR_INVALID_ARG;
  if (kind != ICS_OCC_BOXES_FOLIAGE && kind != ICS_OCC_BOXES_PLATES && kind != ICS_OCC_BOXES_BLOCKS)
    return ICS_ERR_INVALID_ARG;
  uint64_t s = seed;
  for (int i = 0; i < nboxes; i++) {
    double sx, sy, sz, cx, cy, cz;
    if (kind == ICS_OCC_BOXES_FOLIAGE) {
      sx = sy = sz = uni(&s, 0.06, 0.16);
      /* a canopy: denser toward its centre (x, y) and its middle depth */
      double r = 0.85 * sqrt(uni(&s, 0, 1)), a = uni(&s, 0, 2 * ICS_PI);
      cx = r * cos(a);
      cy = r * sin(a);
      cz = 1.5 + 0.42 * (uni(&s, 0, 1) + uni(&s, 0, 1) - 1);
    } else if (kind == ICS_OCC_BOXES_PLATES) {
      sx = uni(&s, 0.2, 0.8);
      sy = uni(&s, 0.2, 0.8);
      sz = 0.01;
      cx = uni(&s, -1 + sx / 2, 1 - sx / 2);
      cy = uni(&s, -1 + sy / 2, 1 - sy / 2);
      cz = uni(&s, 1.01, 1.99);
    } else {
      sx = uni(&s, 0.1, 0.5);
      sy = uni(&s, 0.1, 0.5);
      sz = uni(&s, 0.1, 0.5);
      cx = uni(&s, -1 + sx / 2, 1 - sx / 2);
      cy = uni(&s, -1 + sy / 2, 1 - sy / 2);
      cz = uni(&s, 1 + sz / 2, 2 - sz / 2);
    }
    out[i] = (ics_occ_box){cx - sx / 2, cy - sy / 2, cz - sz / 2, cx + sx / 2, cy + sy / 2, cz + sz / 2};
  }
  return ICS_OK;
}

/* ---- slicing ---------------------------------------------------------------------------- */
static double slice_edge(double z_near, double z_far, int K, int k) {
  return k == K ? z_far : z_near + (z_far - z_near) * k / K;
}

/* first sub-cell index whose centre x0 + (a + 1/2) h is >= x; clamped to [0, N] */
static long first_centre_at_or_after(double x, double x0, double h, long N) {
  double a = ceil((x - x0) / h - 0.5);
  if (a < 0) return 0;
  if (a > (double)N) return N;
  return (long)a;
}

ics_status ics_occtex_slice_boxes(const ics_occ_box *boxes, size_t nboxes, const ics_occ_grid *grid,
                                  int slices, double z_near, double z_far, int ss, float *tex) {
  ics_status st;
  if ((st = check_grid(grid)) || (st = check_slices(slices, z_near, z_far))) return st;
  if ((st = check_boxes(boxes, nboxes))) return st;
  if (!tex) return ICS_ERR_INVALID_ARG;
  if (ss < 1 || ss > ICS_OCC_MAX_SUPERSAMPLE || (long)grid->n * ss > 8192) return ICS_ERR_SIZE;
  const int n = grid->n;
  const long N = (long)n * ss;
  const double h = grid->texel / ss;
  unsigned char *bits = malloc((size_t)N * (size_t)N);
  if (!bits) return ICS_ERR_NOMEM;
  const float inv = 1.0f / (float)(ss * ss);
  for (int k = 0; k < slices; k++) {
    const double zlo = slice_edge(z_near, z_far, slices, k), zhi = slice_edge(z_near, z_far, slices, k + 1);
    memset(bits, 0, (size_t)N * (size_t)N);
    for (size_t b = 0; b < nboxes; b++) {
      const ics_occ_box *B = &boxes[b];
      int in = (k == 0 ? B->z1 >= zlo : B->z1 > zlo) && B->z0 <= zhi;
      if (!in) continue;
      long a0 = first_centre_at_or_after(B->x0, grid->x0, h, N);
      long a1 = first_centre_at_or_after(B->x1, grid->x0, h, N); /* centres < x1: a < a1 */
      long c0 = first_centre_at_or_after(B->y0, grid->y0, h, N);
      long c1 = first_centre_at_or_after(B->y1, grid->y0, h, N);
      for (long c = c0; c < c1; c++) memset(bits + c * N + a0, 1, (size_t)(a1 > a0 ? a1 - a0 : 0));
    }
    float *T = tex + (size_t)k * n * n;
    for (int j = 0; j < n; j++)
      for (int i = 0; i < n; i++) {
        int cnt = 0;
        for (int q = 0; q < ss; q++) {
          const unsigned char *row = bits + ((long)j * ss + q) * N + (long)i * ss;
          for (int p = 0; p < ss; p++) cnt += row[p];
        }
        T[(size_t)j * n + i] = (float)cnt * inv;
      }
  }
  free(bits);
  return ICS_OK;
}

/* ---- object ----------------------------------------------------------------------------- */
static void free_sat(ics_occtex *ot) {
  if (!ot->sat) return;
  for (int k = 0; k < ot->K; k++) ics_sat2d_destroy(ot->sat[k]);
  free(ot->sat);
  ot->sat = NULL;
}

void ics_occtex_destroy(ics_occtex *ot) {
  if (!ot) return;
  free(ot->tex);
  free(ot->mip);
  free(ot->nb);
  free_sat(ot);
  free(ot);
}

ics_status ics_occtex_create(ics_occtex **out, const float *tex, const ics_occ_grid *grid,
                             int slices, double z_near, double z_far) {
  if (!out) return ICS_ERR_INVALID_ARG;
  *out = NULL;
  ics_status st;
  if ((st = check_grid(grid)) || (st = check_slices(slices, z_near, z_far))) return st;
  if (!tex) return ICS_ERR_INVALID_ARG;
  const size_t nn = (size_t)grid->n * grid->n, total = nn * slices;
  if (total > ICS_OCC_MAX_TEXELS) return ICS_ERR_SIZE;
  for (size_t i = 0; i < total; i++) {
    if (isnan(tex[i])) return ICS_ERR_NAN;
    if (isinf(tex[i])) return ICS_ERR_INFINITE;
  }
  ics_occtex *ot = calloc(1, sizeof *ot);
  if (!ot) return ICS_ERR_NOMEM;
  ot->tex = malloc(total * sizeof *ot->tex);
  if (!ot->tex) {
    free(ot);
    return ICS_ERR_NOMEM;
  }
  for (size_t i = 0; i < total; i++) ot->tex[i] = tex[i] < 0 ? 0.0f : tex[i] > 1 ? 1.0f : tex[i];
  ot->n = grid->n;
  ot->L = log2_exact(grid->n);
  ot->K = slices;
  ot->x0 = grid->x0;
  ot->y0 = grid->y0;
  ot->texel = grid->texel;
  ot->z_near = z_near;
  ot->z_far = z_far;
  *out = ot;
  return ICS_OK;
}

int ics_occtex_slices(const ics_occtex *ot) { return ot ? ot->K : 0; }

double ics_occtex_plane(const ics_occtex *ot, int k) {
  if (!ot || k < 0 || k >= ot->K) return NAN;
  return slice_edge(ot->z_near, ot->z_far, ot->K, k + 1);
}

/* mipmap level sizes: n >> l; N-Buffer level widths: n + 2^l - 1 */
static ics_status build_mipmap(ics_occtex *ot) {
  const int n = ot->n, L = ot->L;
  size_t off = 0;
  for (int l = 0; l <= L; l++) {
    ot->mip_off[l] = off;
    off += (size_t)(n >> l) * (n >> l);
  }
  ot->mip_total = off;
  free(ot->mip);
  ot->mip = NULL;
  if (off * ot->K > ICS_OCC_MAX_PREFILTER_BYTES / sizeof *ot->mip) return ICS_ERR_SIZE;
  ot->mip = malloc(off * ot->K * sizeof *ot->mip);
  if (!ot->mip) return ICS_ERR_NOMEM;
  for (int k = 0; k < ot->K; k++) {
    float *M = ot->mip + (size_t)k * off;
    memcpy(M, ot->tex + (size_t)k * n * n, (size_t)n * n * sizeof *M);
    for (int l = 1; l <= L; l++) {
      const int m = n >> l, mp = m * 2;
      const float *src = M + ot->mip_off[l - 1];
      float *dst = M + ot->mip_off[l];
      for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++)
          dst[j * m + i] = 0.25f * (src[(2 * j) * mp + 2 * i] + src[(2 * j) * mp + 2 * i + 1] +
                                    src[(2 * j + 1) * mp + 2 * i] + src[(2 * j + 1) * mp + 2 * i + 1]);
    }
  }
  return ICS_OK;
}

/* N_l(i, j) for i, j in [-(2^l - 1), n - 1]; 0 outside */
static inline float nb_get(const ics_occtex *ot, const float *lev, int l, long i, long j) {
  const long p = (1L << l) - 1, w = ot->n + p;
  i += p;
  j += p;
  if (i < 0 || j < 0 || i >= w || j >= w) return 0.0f;
  return lev[j * w + i];
}

static ics_status build_nbuffers(ics_occtex *ot) {
  const int n = ot->n, L = ot->L;
  size_t off = 0;
  for (int l = 0; l <= L; l++) {
    ot->nb_off[l] = off;
    size_t w = (size_t)n + ((size_t)1 << l) - 1;
    off += w * w;
  }
  ot->nb_total = off;
  free(ot->nb);
  ot->nb = NULL;
  if (off * ot->K > ICS_OCC_MAX_PREFILTER_BYTES / sizeof *ot->nb) return ICS_ERR_SIZE;
  ot->nb = malloc(off * ot->K * sizeof *ot->nb);
  if (!ot->nb) return ICS_ERR_NOMEM;
  /* zero-padded copy of level l over [-(2d - 1), n - 1 + d] (d = 2^l): plain loops, no checks */
  const size_t tw = (size_t)n + 3 * ((size_t)1 << (L > 0 ? L - 1 : 0));
  float *tmp = malloc(tw * tw * sizeof *tmp);
  if (!tmp) {
    free(ot->nb);
    ot->nb = NULL;
    return ICS_ERR_NOMEM;
  }
  for (int k = 0; k < ot->K; k++) {
    float *B = ot->nb + (size_t)k * off;
    memcpy(B, ot->tex + (size_t)k * n * n, (size_t)n * n * sizeof *B);
    for (int l = 0; l < L; l++) {
      const long d = 1L << l, ws = n + d - 1, p = 2 * d - 1, w = n + p, W = n + 3 * d - 1;
      const float *src = B + ot->nb_off[l];
      float *dst = B + ot->nb_off[l + 1];
      memset(tmp, 0, (size_t)W * W * sizeof *tmp);
      for (long j = 0; j < ws; j++) memcpy(tmp + (j + d) * W + d, src + j * ws, (size_t)ws * sizeof *tmp);
      for (long j = 0; j < w; j++) { /* dst row j is index j - p; tmp row r is index r - p */
        const float *r0 = tmp + j * W, *r1 = tmp + (j + d) * W;
        float *o = dst + j * w;
        for (long i = 0; i < w; i++) o[i] = 0.25f * ((r0[i] + r0[i + d]) + (r1[i] + r1[i + d]));
      }
    }
  }
  free(tmp);
  return ICS_OK;
}

static ics_status build_sat(ics_occtex *ot) {
  free_sat(ot);
  ot->sat = calloc((size_t)ot->K, sizeof *ot->sat);
  if (!ot->sat) return ICS_ERR_NOMEM;
  const size_t n = (size_t)ot->n;
  for (int k = 0; k < ot->K; k++) {
    ics_status st =
        ics_sat2d_create(&ot->sat[k], ot->tex + (size_t)k * n * n, n, n, n, ICS_SAT_DOUBLE);
    if (st) {
      free_sat(ot);
      return st;
    }
  }
  return ICS_OK;
}

ics_status ics_occtex_prefilter(ics_occtex *ot, ics_occ_prefilter pf) {
  if (!ot) return ICS_ERR_INVALID_ARG;
  switch (pf) {
  case ICS_OCC_MIPMAP: return build_mipmap(ot);
  case ICS_OCC_NBUFFERS: return build_nbuffers(ot);
  case ICS_OCC_SAT: return build_sat(ot);
  default: return ICS_ERR_INVALID_ARG;
  }
}

static int is_built(const ics_occtex *ot, ics_occ_prefilter pf) {
  return pf == ICS_OCC_MIPMAP ? ot->mip != NULL : pf == ICS_OCC_NBUFFERS ? ot->nb != NULL : ot->sat != NULL;
}

/* ---- lookups (texel units) -------------------------------------------------------------- */
/* bilinear interpolation of N_l at the real corner (x, y) */
static double nb_bilinear(const ics_occtex *ot, const float *lev, int l, double x, double y) {
  double fx0 = floor(x), fy0 = floor(y);
  long i = (long)fx0, j = (long)fy0;
  double fx = x - fx0, fy = y - fy0;
  double a = nb_get(ot, lev, l, i, j), b = nb_get(ot, lev, l, i + 1, j);
  double c = nb_get(ot, lev, l, i, j + 1), d = nb_get(ot, lev, l, i + 1, j + 1);
  return (1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * c + fx * d);
}

static double nb_square(const ics_occtex *ot, int k, double u, double v, double s) {
  const float *B = ot->nb + (size_t)k * ot->nb_total;
  if (s <= 1) return nb_bilinear(ot, B, 0, u - 0.5, v - 0.5);
  const int L = ot->L;
  if (s >= (double)(1L << L)) {
    double h = 0.5 * (double)(1L << L);
    double r = nb_bilinear(ot, B + ot->nb_off[L], L, u - h, v - h);
    double q = (double)(1L << L) / s;
    return r * q * q;
  }
  int l = (int)floor(log2(s));
  if (l < 0) l = 0;
  if (l >= L) l = L - 1;
  double f = (s - (double)(1L << l)) / (double)(1L << l);
  if (f < 0) f = 0;
  if (f > 1) f = 1;
  double h0 = 0.5 * (double)(1L << l), h1 = 2 * h0;
  double r0 = nb_bilinear(ot, B + ot->nb_off[l], l, u - h0, v - h0);
  if (f == 0) return r0;
  double r1 = nb_bilinear(ot, B + ot->nb_off[l + 1], l + 1, u - h1, v - h1);
  return r0 + f * (r1 - r0);
}

/* bilinear sample of mip level l at (u, v) in level-0 texel units; zero border */
static double mip_bilinear(const ics_occtex *ot, const float *M, int l, double u, double v) {
  const long m = ot->n >> l;
  const float *lev = M + ot->mip_off[l];
  double x = u / (double)(1L << l) - 0.5, y = v / (double)(1L << l) - 0.5;
  double fx0 = floor(x), fy0 = floor(y);
  long i = (long)fx0, j = (long)fy0;
  double fx = x - fx0, fy = y - fy0, r = 0;
  for (int q = 0; q < 2; q++)
    for (int p = 0; p < 2; p++) {
      long ii = i + p, jj = j + q;
      if (ii < 0 || jj < 0 || ii >= m || jj >= m) continue;
      r += (p ? fx : 1 - fx) * (q ? fy : 1 - fy) * lev[jj * m + ii];
    }
  return r;
}

static double mip_square(const ics_occtex *ot, int k, double u, double v, double s) {
  const float *M = ot->mip + (size_t)k * ot->mip_total;
  const int L = ot->L;
  if (s <= 1) return mip_bilinear(ot, M, 0, u, v);
  double lam = log2(s);
  if (lam >= L) {
    double q = (double)(1L << L) / s;
    return mip_bilinear(ot, M, L, u, v) * q * q;
  }
  int l = (int)floor(lam);
  if (l < 0) l = 0;
  if (l >= L) l = L - 1;
  double f = lam - l;
  double r0 = mip_bilinear(ot, M, l, u, v);
  if (f <= 0) return r0;
  return r0 + f * (mip_bilinear(ot, M, l + 1, u, v) - r0);
}

/* rectangle via square taps along the major side */
static double aniso(const ics_occtex *ot, int k, double u, double v, double su, double sv,
                    double (*sq)(const ics_occtex *, int, double, double, double)) {
  if (su == sv) return sq(ot, k, u, v, su);
  int major_x = su > sv;
  double smaj = major_x ? su : sv, smin = major_x ? sv : su;
  double se = smin > smaj / 16 ? smin : smaj / 16;
  int N = (int)ceil(smaj / se - 1e-9);
  if (N < 1) N = 1;
  double d = smaj / N, r = 0;
  for (int t = 0; t < N; t++) {
    double o = -0.5 * smaj + (t + 0.5) * d;
    r += major_x ? sq(ot, k, u + o, v, se) : sq(ot, k, u, v + o, se);
  }
  return r / N;
}

/* exact box average by direct summation (small boxes and point lookups) */
static void axis_weights(double a0, double a1, long *i0, long *i1) {
  *i0 = (long)floor(a0);
  *i1 = (long)floor(a1);
}
static double direct_box(const ics_occtex *ot, int k, double u0, double v0, double u1, double v1) {
  const float *T = ot->tex + (size_t)k * ot->n * ot->n;
  const long n = ot->n;
  long i0, i1, j0, j1;
  axis_weights(u0, u1, &i0, &i1);
  axis_weights(v0, v1, &j0, &j1);
  const double wu = u1 - u0, wv = v1 - v0;
  double r = 0;
  for (long j = j0 > 0 ? j0 : 0; j <= j1 && j < n; j++) {
    double ov = wv > 0 ? (fmin(v1, (double)j + 1) - fmax(v0, (double)j)) / wv : (j == j0);
    if (ov <= 0) continue;
    for (long i = i0 > 0 ? i0 : 0; i <= i1 && i < n; i++) {
      double ou = wu > 0 ? (fmin(u1, (double)i + 1) - fmax(u0, (double)i)) / wu : (i == i0);
      if (ou <= 0) continue;
      r += ou * ov * T[j * n + i];
    }
  }
  return r;
}

static double sat_box(const ics_occtex *ot, int k, double u, double v, double su, double sv) {
  double u0 = u - 0.5 * su, u1 = u + 0.5 * su, v0 = v - 0.5 * sv, v1 = v + 0.5 * sv;
  if (su * sv < 1) return direct_box(ot, k, u0, v0, u1, v1);
  double sum = 0;
  if (ics_sat2d_integral(ot->sat[k], u0, v0, u1, v1, &sum) != ICS_OK) return NAN;
  return sum / (su * sv);
}

static double box_lookup(const ics_occtex *ot, ics_occ_prefilter pf, int k, double u, double v,
                         double su, double sv) {
  switch (pf) {
  case ICS_OCC_SAT: return sat_box(ot, k, u, v, su, sv);
  case ICS_OCC_NBUFFERS: return aniso(ot, k, u, v, su, sv, nb_square);
  default: return aniso(ot, k, u, v, su, sv, mip_square);
  }
}

ics_status ics_occtex_box(const ics_occtex *ot, ics_occ_prefilter pf, int k, double u, double v,
                          double su, double sv, double *out) {
  if (!ot || !out || (unsigned)pf >= ICS_OCC_PREFILTER_COUNT || k < 0 || k >= ot->K)
    return ICS_ERR_INVALID_ARG;
  ics_status st;
  if ((st = ics_check_finite(u)) || (st = ics_check_finite(v)) || (st = ics_check_finite(su)) || (st = ics_check_finite(sv)))
    return st;
  if (su < 0 || sv < 0) return ICS_ERR_INVALID_ARG;
  if (!is_built(ot, pf)) return ICS_ERR_UNSUPPORTED;
  double r = box_lookup(ot, pf, k, u, v, su, sv);
  if (isnan(r)) return ICS_ERR_RANGE;
  *out = r;
  return ICS_OK;
}

/* ---- shadows ---------------------------------------------------------------------------- */
double ics_occtex_combine_values(ics_occ_combine c, const double *f, int k) {
  if ((unsigned)c >= ICS_OCC_COMBINE_COUNT || k < 0 || (k > 0 && !f)) return NAN;
  for (int i = 0; i < k; i++)
    if (!(f[i] >= 0 && f[i] <= 1)) return NAN; /* NaN or outside [0, 1] */
  double r;
  switch (c) {
  case ICS_OCC_PRODUCT:
    r = 1;
    for (int i = 0; i < k; i++) r *= 1 - f[i];
    return 1 - r;
  case ICS_OCC_SUM:
    r = 0;
    for (int i = 0; i < k; i++) r += f[i];
    return r > 1 ? 1 : r;
  case ICS_OCC_MAX:
    r = 0;
    for (int i = 0; i < k; i++) r = f[i] > r ? f[i] : r;
    return r;
  default: return NAN;
  }
}

static void slices_at(const ics_occtex *ot, const ics_occ_light *L, ics_occ_prefilter pf,
                      const double *P, double *w, double *o) {
  const double pz = P[2], inv = 1 / ot->texel;
  for (int k = 0; k < ot->K; k++) {
    const double zk = slice_edge(ot->z_near, ot->z_far, ot->K, k);
    const double zo = slice_edge(ot->z_near, ot->z_far, ot->K, k + 1);
    double wk = (pz - zk) / (zo - zk);
    wk = wk < 0 ? 0 : wk > 1 ? 1 : wk;
    w[k] = wk;
    if (wk == 0) {
      o[k] = 0;
      continue;
    }
    double t = (pz - zo) / pz;
    if (t < 0) t = 0;
    double x = P[0] + t * (L->cx - P[0]), y = P[1] + t * (L->cy - P[1]);
    o[k] = box_lookup(ot, pf, k, (x - ot->x0) * inv, (y - ot->y0) * inv, t * L->wx * inv, t * L->wy * inv);
  }
}

ics_status ics_occtex_slices_at(const ics_occtex *ot, const ics_occ_light *light,
                                ics_occ_prefilter pf, const double P[3], double *w, double *o) {
  if (!ot || !w || !o || (unsigned)pf >= ICS_OCC_PREFILTER_COUNT) return ICS_ERR_INVALID_ARG;
  ics_status st;
  if ((st = check_light(light)) || (st = check_points(P, 1, w))) return st;
  if (!is_built(ot, pf)) return ICS_ERR_UNSUPPORTED;
  slices_at(ot, light, pf, P, w, o);
  return ICS_OK;
}

ics_status ics_occtex_shadow(const ics_occtex *ot, const ics_occ_light *light, ics_occ_prefilter pf,
                             ics_occ_combine c, const double *P, size_t n, double *occ) {
  if (!ot || (unsigned)pf >= ICS_OCC_PREFILTER_COUNT || (unsigned)c >= ICS_OCC_COMBINE_COUNT)
    return ICS_ERR_INVALID_ARG;
  ics_status st;
  if ((st = check_light(light)) || (st = check_points(P, n, occ))) return st;
  if (!is_built(ot, pf)) return ICS_ERR_UNSUPPORTED;
  double w[ICS_OCC_MAX_SLICES], o[ICS_OCC_MAX_SLICES];
  for (size_t i = 0; i < n; i++) {
    slices_at(ot, light, pf, P + 3 * i, w, o);
    for (int k = 0; k < ot->K; k++) { /* a box average of values in [0, 1]: clamp rounding */
      double f = w[k] * o[k];
      w[k] = f < 0 ? 0 : f > 1 ? 1 : f;
    }
    occ[i] = ics_occtex_combine_values(c, w, ot->K);
  }
  return ICS_OK;
}

/* ---- brute force ------------------------------------------------------------------------ */
/* does the segment P + s (Q - P), s in [1e-12, 1], meet the closed box? */
static int seg_hits(const double *P, const double *d, const ics_occ_box *B) {
  double lo = 1e-12, hi = 1;
  const double bmin[3] = {B->x0, B->y0, B->z0}, bmax[3] = {B->x1, B->y1, B->z1};
  return ics_ray_box_clip(P, d, bmin, bmax, &lo, &hi);
}

ics_status ics_occtex_exact(const ics_occ_box *boxes, size_t nboxes, const ics_occ_light *light,
                            int m, const double *P, size_t n, double *occ) {
  ics_status st;
  if ((st = check_light(light)) || (st = check_boxes(boxes, nboxes)) || (st = check_points(P, n, occ)))
    return st;
  if (m < 1 || m > ICS_OCC_MAX_LIGHT_SAMPLES) return ICS_ERR_SIZE;
  const ics_occ_box **cand = malloc((nboxes ? nboxes : 1) * sizeof *cand);
  if (!cand) return ICS_ERR_NOMEM;
  const double lx0 = light->cx - 0.5 * light->wx, ly0 = light->cy - 0.5 * light->wy;
  const double lx1 = light->cx + 0.5 * light->wx, ly1 = light->cy + 0.5 * light->wy;
  for (size_t i = 0; i < n; i++) {
    const double *p = P + 3 * i;
    const double bx0 = fmin(lx0, p[0]), bx1 = fmax(lx1, p[0]), by0 = fmin(ly0, p[1]), by1 = fmax(ly1, p[1]);
    size_t nc = 0;
    for (size_t b = 0; b < nboxes; b++) {
      const ics_occ_box *B = &boxes[b];
      if (B->z0 < p[2] && B->z1 >= 0 && B->x1 >= bx0 && B->x0 <= bx1 && B->y1 >= by0 && B->y0 <= by1)
        cand[nc++] = B;
    }
    long hit = 0;
    if (nc) {
      for (int b = 0; b < m; b++) {
        const double qy = ly0 + (b + 0.5) * light->wy / m;
        for (int a = 0; a < m; a++) {
          const double qx = lx0 + (a + 0.5) * light->wx / m;
          const double d[3] = {qx - p[0], qy - p[1], -p[2]};
          for (size_t c = 0; c < nc; c++)
            if (seg_hits(p, d, cand[c])) {
              hit++;
              break;
            }
        }
      }
    }
    occ[i] = (double)hit / ((double)m * m);
  }
  free(cand);
  return ICS_OK;
}
