/* detail_vec.h — the volume detail functions over W points at once (detail_batch.h), written
 * once over GCC/Clang vector extensions of doubles and compiled per instruction set
 * (detail_sse2.c, detail_avx2.c, detail_avx512.c, detail_neon.c define ICS_DVEC_W, the lanes of
 * a double vector, and ICS_DVEC_FN, the entry point). Each lane repeats core/detail.c's double
 * arithmetic in its order (these files are compiled without contraction into fused
 * multiply-adds), so every value is bit for bit ics_detail_value's; the permutation lookups are
 * per lane. */
#include <math.h>

#include "detail_batch.h"

#if !defined(ICS_DVEC_W) || !defined(ICS_DVEC_FN)
#error "define ICS_DVEC_W and ICS_DVEC_FN before including detail_vec.h"
#endif
#include "vec_double.h"

static inline vd vfloor(vd x) {
  for (int i = 0; i < W; i++) x[i] = floor(x[i]);
  return x;
}

static inline vd fade(vd t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static inline vd lerp(vd t, vd a, vd b) { return a + t * (b - a); }
/* the gradient of hash h (its low 4 bits) dotted with (x, y, z) */
static inline vd grad(vl h, vd x, vd y, vd z) {
  h &= 15;
  vd u = blend(h < 8, x, y), v = blend(h < 4, y, blend((h == 12) | (h == 14), x, z));
  return blend((h & 1) != 0, -u, u) + blend((h & 2) != 0, -v, v);
}
/* p[i] for each lane */
static inline vl gather(const uint8_t *p, vl i) {
  vl r;
  for (int k = 0; k < W; k++) r[k] = p[i[k]];
  return r;
}
/* the lattice cell modulo 256, in floating point as detail.c computes it */
static inline vl cell(vd f) {
  vd m = f - 256 * vfloor(f / 256);
  vl r;
  for (int k = 0; k < W; k++) r[k] = (int64_t)m[k] & 255;
  return r;
}

/* Below 2^51 in magnitude a double's floor and its lattice cell come from adding M = 1.5 2^52,
 * where the spacing of doubles is 1: x + M - M is x rounded to an integer (exactly: a sum
 * in (2^52, 2^53) is rounded once, the difference is exact), floor is that less 1 where it
 * exceeds x, and for an integer f the low bits of f + M's bit pattern are those of 2^51 + f, so
 * its low 8 are f mod 256. Both equal vfloor's and cell's results; lanes beyond take those. */
#define LATTICE_MAGIC 0x1.8p52
static inline int all_small(vd x, vd y, vd z) {
  vl in = (vfabs(x) < 0x1p51) & (vfabs(y) < 0x1p51) & (vfabs(z) < 0x1p51);
  int64_t all = -1;
  for (int k = 0; k < W; k++) all &= in[k];
  return all != 0;
}
static inline vd floor_small(vd x) {
  vd r = (x + LATTICE_MAGIC) - LATTICE_MAGIC;
  return blend(r > x, r - 1, r);
}
static inline vl cell_small(vd f) { return (vl)(f + LATTICE_MAGIC) & 255; }

static vd noise(const uint8_t p[512], vd x, vd y, vd z) {
  vd fx, fy, fz;
  vl X, Y, Z;
  if (all_small(x, y, z)) {
    fx = floor_small(x), fy = floor_small(y), fz = floor_small(z);
    X = cell_small(fx), Y = cell_small(fy), Z = cell_small(fz);
  } else {
    fx = vfloor(x), fy = vfloor(y), fz = vfloor(z);
    X = cell(fx), Y = cell(fy), Z = cell(fz);
  }
  x -= fx, y -= fy, z -= fz;
  vd u = fade(x), v = fade(y), w = fade(z);
  vl A = gather(p, X) + Y, AA = gather(p, A) + Z, AB = gather(p, A + 1) + Z;
  vl B = gather(p, X + 1) + Y, BA = gather(p, B) + Z, BB = gather(p, B + 1) + Z;
  vd x1 = x - 1, y1 = y - 1, z1 = z - 1;
  return lerp(w,
              lerp(v, lerp(u, grad(gather(p, AA), x, y, z), grad(gather(p, BA), x1, y, z)),
                   lerp(u, grad(gather(p, AB), x, y1, z), grad(gather(p, BB), x1, y1, z))),
              lerp(v, lerp(u, grad(gather(p, AA + 1), x, y, z1), grad(gather(p, BA + 1), x1, y, z1)),
                   lerp(u, grad(gather(p, AB + 1), x, y1, z1), grad(gather(p, BB + 1), x1, y1, z1))));
}

/* detail.c's ics_detail_value for W points */
static vd value(const ics_detail_eval *e, vd px, vd py, vd pz) {
  const ics_detail *d = e->d;
  static const double drift[3] = {0.3713, 0.5129, 0.7731};
  vd x = d->frequency * px + d->time * drift[0];
  vd y = d->frequency * py + d->time * drift[1];
  vd z = d->frequency * pz + d->time * drift[2];
  vd f;
  if (d->fn == ICS_DETAIL_PERLIN) {
    f = noise(e->perm, x, y, z);
  } else if (d->fn == ICS_DETAIL_FBM) {
    f = splat(0);
    double amp = 1;
    for (int o = 0; o < d->octaves; o++) {
      f += amp * noise(e->perm, x, y, z);
      amp *= d->gain;
      x *= d->lacunarity, y *= d->lacunarity, z *= d->lacunarity;
    }
  } else { /* ridged */
    vd signal = d->offset - vfabs(noise(e->perm, x, y, z));
    signal *= signal;
    f = signal;
    double expo = 1;
    for (int o = 1; o < d->octaves; o++) {
      x *= d->lacunarity, y *= d->lacunarity, z *= d->lacunarity;
      expo /= d->lacunarity;
      vd weight = signal * d->gain;
      weight = blend(weight < 0, splat(0), blend(weight > 1, splat(1), weight));
      signal = d->offset - vfabs(noise(e->perm, x, y, z));
      signal *= signal * weight;
      f += signal * expo;
    }
  }
  return d->bias + d->scale * f;
}

void ICS_DVEC_FN(const ics_detail_eval *e, const double *x, const double *y, const double *z,
                 int n, double *out) {
  int i = 0;
  for (; i + W <= n; i += W) {
    vd v = value(e, load(x + i), load(y + i), load(z + i));
    memcpy(out + i, &v, sizeof v);
  }
  if (i < n) { /* the last points in lanes of their own, the rest of the vector repeating one */
    double bx[W], by[W], bz[W], bo[W];
    for (int k = 0; k < W; k++) {
      int s = i + k < n ? i + k : n - 1;
      bx[k] = x[s], by[k] = y[s], bz[k] = z[s];
    }
    vd v = value(e, load(bx), load(by), load(bz));
    memcpy(bo, &v, sizeof v);
    for (int k = 0; i + k < n; k++) out[i + k] = bo[k];
  }
}

#undef W
