/* noise.h — improved noise (Perlin 2002; gpu/core/detail.c has the method): the fade curve, the 12
 * edge gradients picked by a hash's low 4 bits, and the noise at a point from a permutation of
 * 512 bytes read through ICS_PERM(i) from index pb. Shared kernel source (lang.h): the cpu
 * backend, slab.cl and slab.comp compile this one text. */
#ifndef ICS_KERNEL_NOISE_H
#define ICS_KERNEL_NOISE_H
#include "kernel/lang.h"

ICS_FN double ics_k_fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
ICS_FN double ics_k_lerp(double t, double a, double b) { return a + t * (b - a); }
ICS_FN double ics_k_grad(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) != 0 ? -u : u) + ((h & 2) != 0 ? -v : v);
}

ICS_FN double ics_k_perlin(ICS_VIEW_PARAM int pb, double x, double y, double z) {
  double xf = floor(x), yf = floor(y), zf = floor(z);
  /* the lattice cell modulo 256, in floating point (no integer conversion can overflow) */
  int X = ICS_TO_INT(xf - 256 * floor(xf / 256)) & 255,
      Y = ICS_TO_INT(yf - 256 * floor(yf / 256)) & 255,
      Z = ICS_TO_INT(zf - 256 * floor(zf / 256)) & 255;
  x -= xf, y -= yf, z -= zf;
  double u = ics_k_fade(x), v = ics_k_fade(y), w = ics_k_fade(z);
  int A0 = ICS_PERM(pb + X) + Y, AA = ICS_PERM(pb + A0) + Z, AB = ICS_PERM(pb + A0 + 1) + Z;
  int B0 = ICS_PERM(pb + X + 1) + Y, BA = ICS_PERM(pb + B0) + Z, BB = ICS_PERM(pb + B0 + 1) + Z;
  return ics_k_lerp(w,
                    ics_k_lerp(v,
                               ics_k_lerp(u, ics_k_grad(ICS_PERM(pb + AA), x, y, z),
                                          ics_k_grad(ICS_PERM(pb + BA), x - 1, y, z)),
                               ics_k_lerp(u, ics_k_grad(ICS_PERM(pb + AB), x, y - 1, z),
                                          ics_k_grad(ICS_PERM(pb + BB), x - 1, y - 1, z))),
                    ics_k_lerp(v,
                               ics_k_lerp(u, ics_k_grad(ICS_PERM(pb + AA + 1), x, y, z - 1),
                                          ics_k_grad(ICS_PERM(pb + BA + 1), x - 1, y, z - 1)),
                               ics_k_lerp(u, ics_k_grad(ICS_PERM(pb + AB + 1), x, y - 1, z - 1),
                                          ics_k_grad(ICS_PERM(pb + BB + 1), x - 1, y - 1, z - 1))));
}

#endif
