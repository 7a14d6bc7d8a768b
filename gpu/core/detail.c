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

/* the shared kernel source's noise and transfer functions (gpu/kernel: the same text the cl and gl
 * programs compile) over a permutation and a material: object 0 is the material */
typedef struct detail_view {
  const uint8_t *perm;
  const ics_material *m;
} detail_view;
#define ICS_VIEW_PARAM const detail_view *view,
#define ICS_VIEW_ARG view,
#define ICS_PERM(i) view->perm[i]
#define ICS_NTRANSFER(ob) view->m[ob].ntransfer
#define ICS_TRANSFER(ob, i) view->m[ob].transfer[(i) / 5][(i) % 5]
#define ICS_COLOR(ob, c) view->m[ob].color[c]
#include "kernel/noise.h"
#include "kernel/transfer.h"

double ics_perlin_noise(const uint8_t p[512], double x, double y, double z) {
  const detail_view view = {p, NULL};
  return ics_k_perlin(&view, 0, x, y, z);
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
  const detail_view view = {NULL, m};
  *scale = ics_k_transfer(&view, 0, v, rgb);
}

void ics_material_preintegrate(const ics_material *m, double vf, double vb, double rgb[3],
                               double *scale) {
  const detail_view view = {NULL, m};
  *scale = ics_k_preintegrate(&view, 0, vf, vb, rgb);
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
