/* detail.c — detail functions and transfer functions (see detail.h).
 *
 * Improved noise (Perlin 2002, "Improving Noise"): fade 6t^5 - 15t^4 + 10t^3 and the 12 edge
 * gradients picked by the low 4 bits of the hash; the permutation is a Fisher-Yates shuffle of
 * 0..255 drawn from the counter RNG under the detail's seed (so a seed names a field). fBm sums
 * `octaves` octaves with amplitude gain^i at frequency lacunarity^i. Ridged multifractal
 * (Musgrave, "Texturing and Modeling", 3rd ed., RidgedMultifractal with H = 1): signal =
 * (offset - |noise|)^2, each octave weighted by the previous signal times gain (clamped to
 * [0, 1]) and by lacunarity^-i. Time moves the field along the fixed direction
 * (0.3713, 0.5129, 0.7731) at one unit of noise space per unit of time. */
#include "detail.h"

#include <math.h>
#include <string.h>

#include "icshadow/rng.h"
#include "icshadow/volume.h"

static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static double lerp(double t, double a, double b) { return a + t * (b - a); }
static double grad(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

double ics_perlin_noise(const uint8_t p[512], double x, double y, double z) {
  double fx = floor(x), fy = floor(y), fz = floor(z);
  /* the lattice cell modulo 256, in floating point (no integer conversion can overflow) */
  int X = (int)(fx - 256 * floor(fx / 256)) & 255, Y = (int)(fy - 256 * floor(fy / 256)) & 255,
      Z = (int)(fz - 256 * floor(fz / 256)) & 255;
  x -= fx, y -= fy, z -= fz;
  double u = fade(x), v = fade(y), w = fade(z);
  int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
  int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                   lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                   lerp(u, grad(p[AB + 1], x, y - 1, z - 1), grad(p[BB + 1], x - 1, y - 1, z - 1))));
}

void ics_detail_prepare(ics_detail_eval *e, const ics_detail *d, const double lo[3],
                        const double hi[3]) {
  memset(e, 0, sizeof *e);
  e->d = d;
  memcpy(e->lo, lo, sizeof e->lo);
  memcpy(e->hi, hi, sizeof e->hi);
  uint8_t perm[256];
  for (int i = 0; i < 256; i++) perm[i] = (uint8_t)i;
  ics_rng r;
  ics_rng_init(&r, d->seed, 0x6e6f697365ULL /* "noise" */);
  for (int i = 255; i > 0; i--) {
    int j = (int)(ics_rng_uniform(&r) * (i + 1));
    uint8_t t = perm[i];
    perm[i] = perm[j];
    perm[j] = t;
  }
  for (int i = 0; i < 512; i++) e->perm[i] = perm[i & 255];
}

double ics_detail_value(const ics_detail_eval *e, const double p[3]) {
  const ics_detail *d = e->d;
  double f;
  if (d->fn == ICS_DETAIL_GRID) {
    ics_volume vol = {d->grid, (size_t)d->size[0], (size_t)d->size[1], (size_t)d->size[2]};
    double q[3];
    for (int i = 0; i < 3; i++)
      q[i] = e->hi[i] > e->lo[i] ? (p[i] - e->lo[i]) / (e->hi[i] - e->lo[i]) * d->size[i] : 0;
    f = ics_volume_sample(&vol, q);
  } else {
    static const double drift[3] = {0.3713, 0.5129, 0.7731};
    double x = d->frequency * p[0] + d->time * drift[0];
    double y = d->frequency * p[1] + d->time * drift[1];
    double z = d->frequency * p[2] + d->time * drift[2];
    if (d->fn == ICS_DETAIL_PERLIN) {
      f = ics_perlin_noise(e->perm, x, y, z);
    } else if (d->fn == ICS_DETAIL_FBM) {
      f = 0;
      double amp = 1;
      for (int o = 0; o < d->octaves; o++) {
        f += amp * ics_perlin_noise(e->perm, x, y, z);
        amp *= d->gain;
        x *= d->lacunarity, y *= d->lacunarity, z *= d->lacunarity;
      }
    } else { /* ridged */
      double signal = d->offset - fabs(ics_perlin_noise(e->perm, x, y, z));
      signal *= signal;
      f = signal;
      double expo = 1;
      for (int o = 1; o < d->octaves; o++) {
        x *= d->lacunarity, y *= d->lacunarity, z *= d->lacunarity;
        expo /= d->lacunarity;
        double weight = signal * d->gain;
        weight = weight < 0 ? 0 : weight > 1 ? 1 : weight;
        signal = d->offset - fabs(ics_perlin_noise(e->perm, x, y, z));
        signal *= signal * weight;
        f += signal * expo;
      }
    }
  }
  return d->bias + d->scale * f;
}

void ics_material_transfer(const ics_material *m, double v, double rgb[3], double *scale) {
  int n = m->ntransfer;
  if (n == 0) {
    memcpy(rgb, m->color, 3 * sizeof *rgb);
    *scale = v > 0 ? v : 0;
    return;
  }
  const double(*t)[5] = m->transfer;
  int k = 0;
  if (v <= t[0][0]) {
    k = -1;
  } else if (v >= t[n - 1][0]) {
    k = n - 1;
  } else {
    while (k + 1 < n && t[k + 1][0] <= v) k++;
  }
  if (k < 0 || k == n - 1) {
    const double *row = t[k < 0 ? 0 : n - 1];
    rgb[0] = row[1], rgb[1] = row[2], rgb[2] = row[3];
    *scale = row[4];
    return;
  }
  double a = (v - t[k][0]) / (t[k + 1][0] - t[k][0]);
  for (int c = 0; c < 3; c++) rgb[c] = t[k][1 + c] + a * (t[k + 1][1 + c] - t[k][1 + c]);
  *scale = t[k][4] + a * (t[k + 1][4] - t[k][4]);
}

/* integrals over [a, b] (a < b) of s(v) and c_k(v) s(v) for a transfer function that is linear
 * on [a, b]: s and c linear, so c s is quadratic and Simpson's rule is exact */
static void linear_piece(const ics_material *m, double a, double b, double *S, double CS[3]) {
  double ca[3], cm[3], cb[3], sa, sm, sb, h = b - a;
  ics_material_transfer(m, a, ca, &sa);
  ics_material_transfer(m, 0.5 * (a + b), cm, &sm);
  ics_material_transfer(m, b, cb, &sb);
  *S += h * (sa + 4 * sm + sb) / 6;
  for (int c = 0; c < 3; c++) CS[c] += h * (ca[c] * sa + 4 * cm[c] * sm + cb[c] * sb) / 6;
}

void ics_material_preintegrate(const ics_material *m, double vf, double vb, double rgb[3],
                               double *scale) {
  double lo = fmin(vf, vb), hi = fmax(vf, vb);
  if (!(hi - lo > 1e-12 * (1 + fabs(hi)))) {
    ics_material_transfer(m, 0.5 * (vf + vb), rgb, scale);
    return;
  }
  /* breakpoints: the transfer function's nodes inside (lo, hi), and 0 when it has none
   * (s = max(v, 0) bends there) */
  double bp[ICS_SCENE_MAX_TRANSFER + 2];
  int nb = 0;
  bp[nb++] = lo;
  if (m->ntransfer == 0) {
    if (lo < 0 && hi > 0) bp[nb++] = 0;
  } else {
    for (int i = 0; i < m->ntransfer; i++)
      if (m->transfer[i][0] > lo && m->transfer[i][0] < hi) bp[nb++] = m->transfer[i][0];
  }
  bp[nb++] = hi;
  double S = 0, CS[3] = {0, 0, 0};
  for (int i = 0; i + 1 < nb; i++) linear_piece(m, bp[i], bp[i + 1], &S, CS);
  *scale = S / (hi - lo);
  if (S > 0) {
    for (int c = 0; c < 3; c++) rgb[c] = CS[c] / S;
  } else {
    ics_material_transfer(m, 0.5 * (vf + vb), rgb, scale);
    *scale = 0;
  }
}

double ics_detail_bound(const ics_detail *d) {
  switch (d->fn) {
  case ICS_DETAIL_PERLIN: return 2;
  case ICS_DETAIL_FBM: {
    double b = 0, amp = 1;
    for (int o = 0; o < d->octaves; o++) b += 2 * amp, amp *= fabs(d->gain);
    return b;
  }
  case ICS_DETAIL_RIDGED: {
    /* each octave's signal is (offset - |n|)^2 <= max(offset^2, (offset - 2)^2) for |n| <= 2,
     * times a weight in [0, 1], times lacunarity^-o (o >= 1) */
    double a = d->offset, top = fmax(a * a, (a - 2) * (a - 2)), b = top, expo = 1;
    for (int o = 1; o < d->octaves; o++) expo /= d->lacunarity, b += top * expo;
    return b;
  }
  case ICS_DETAIL_GRID: {
    double b = 0; /* samples outside the grid are 0 */
    size_t n = (size_t)d->size[0] * d->size[1] * d->size[2];
    for (size_t i = 0; i < n; i++) b = fmax(b, fabs((double)d->grid[i]));
    return b;
  }
  default: return 0;
  }
}

double ics_material_majorant(const ics_material *m) {
  if (!m->volumetric) return 0;
  if (m->detail.fn == ICS_DETAIL_NONE) return m->extinction;
  /* the detail values the function can reach */
  double f = ics_detail_bound(&m->detail), vlo = m->detail.bias - fabs(m->detail.scale) * f,
         vhi = m->detail.bias + fabs(m->detail.scale) * f, smax = 0;
  if (m->ntransfer) {
    /* piecewise linear and clamped: its maximum over [vlo, vhi] is at an end or a node within */
    double rgb[3], s;
    ics_material_transfer(m, vlo, rgb, &s), smax = fmax(smax, s);
    ics_material_transfer(m, vhi, rgb, &s), smax = fmax(smax, s);
    for (int i = 0; i < m->ntransfer; i++)
      if (m->transfer[i][0] > vlo && m->transfer[i][0] < vhi) smax = fmax(smax, m->transfer[i][4]);
  } else {
    smax = fmax(0, vhi);
  }
  return m->extinction * smax;
}
