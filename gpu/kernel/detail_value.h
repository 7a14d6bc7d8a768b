/* detail_value.h — an object's detail value at a point (gpu/core/detail.c, ics_detail_value):
 * improved noise, fBm or ridged multifractal at the object's frequency, drifting with time, or
 * its grid sampled trilinearly over the object's box (ics_volume_sample: cell centres at
 * i + 1/2, clamped at the faces, 0 outside); then bias + scale x value. The object record is
 * read through ICS_OBJ(ob, O_*) (device_layout.h), its noise permutation through ICS_PERM from
 * 512 ob, the grid cells through ICS_GRID(i) (indices below 2^31: the device scene's limit).
 * Shared kernel source (lang.h) for slab.cl and slab.comp; the cpu backend evaluates detail in
 * its vector loops (gpu/backends/cpu/detail_vec.h), the same arithmetic. */
#ifndef ICS_KERNEL_DETAIL_VALUE_H
#define ICS_KERNEL_DETAIL_VALUE_H
#include "kernel/device_layout.h"
#include "kernel/lang.h"
#include "kernel/noise.h"

ICS_FN double ics_k_grid_sample(ICS_VIEW_PARAM int g0, ICS_CONST_IN int n[3],
                                ICS_CONST_IN double p[3]) {
  int i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; a++) {
    if (!(p[a] >= 0.0 && p[a] <= ICS_TO_DOUBLE(n[a]))) return 0.0;
    double g = p[a] - 0.5, fl = floor(g);
    f[a] = g - fl;
    int i = ICS_TO_INT(fl), last = n[a] - 1;
    i0[a] = i < 0 ? 0 : i > last ? last : i;
    i1[a] = i + 1 < 0 ? 0 : i + 1 > last ? last : i + 1;
  }
  int sy = n[0], sz = n[0] * n[1];
#define ICS_K_CELL(i, j, k) ICS_TO_DOUBLE(ICS_GRID(g0 + (i) + (j)*sy + (k)*sz))
  double c00 =
      ICS_K_CELL(i0[0], i0[1], i0[2]) * (1 - f[0]) + ICS_K_CELL(i1[0], i0[1], i0[2]) * f[0];
  double c10 =
      ICS_K_CELL(i0[0], i1[1], i0[2]) * (1 - f[0]) + ICS_K_CELL(i1[0], i1[1], i0[2]) * f[0];
  double c01 =
      ICS_K_CELL(i0[0], i0[1], i1[2]) * (1 - f[0]) + ICS_K_CELL(i1[0], i0[1], i1[2]) * f[0];
  double c11 =
      ICS_K_CELL(i0[0], i1[1], i1[2]) * (1 - f[0]) + ICS_K_CELL(i1[0], i1[1], i1[2]) * f[0];
#undef ICS_K_CELL
  double c0 = c00 * (1 - f[1]) + c10 * f[1], c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

ICS_FN double ics_k_detail_value(ICS_VIEW_PARAM int ob, ICS_CONST_IN double pt[3]) {
  int fn = ICS_TO_INT(ICS_OBJ(ob, O_DETAIL)), octaves = ICS_TO_INT(ICS_OBJ(ob, O_OCTAVES));
  if (fn == 4) { /* the grid over the object's box */
    int n[3];
    double q[3];
    for (int i = 0; i < 3; i++) {
      double lo = ICS_OBJ(ob, O_GRID_LO + i), hi = ICS_OBJ(ob, O_GRID_HI + i);
      n[i] = ICS_TO_INT(ICS_OBJ(ob, O_GRID_N + i));
      q[i] = hi > lo ? (pt[i] - lo) / (hi - lo) * ICS_TO_DOUBLE(n[i]) : 0.0;
    }
    return ICS_OBJ(ob, O_BIAS) +
           ICS_OBJ(ob, O_SCALE) *
               ics_k_grid_sample(ICS_VIEW_ARG ICS_TO_INT(ICS_OBJ(ob, O_GRID)), n, q);
  }
  int pb = 512 * ob;
  double fr = ICS_OBJ(ob, O_FREQ), tm = ICS_OBJ(ob, O_TIME);
  double lac = ICS_OBJ(ob, O_LACUNARITY), gain = ICS_OBJ(ob, O_GAIN);
  /* time's drift direction (detail.c) */
  double x = fr * pt[0] + tm * ICS_DBL_CONST(0.3713, 0.3713lf);
  double y = fr * pt[1] + tm * ICS_DBL_CONST(0.5129, 0.5129lf);
  double z = fr * pt[2] + tm * ICS_DBL_CONST(0.7731, 0.7731lf);
  double f;
  if (fn == 1) {
    f = ics_k_perlin(ICS_VIEW_ARG pb, x, y, z);
  } else if (fn == 2) {
    f = 0.0;
    double amp = 1.0;
    for (int o = 0; o < octaves; o++) {
      f += amp * ics_k_perlin(ICS_VIEW_ARG pb, x, y, z);
      amp *= gain;
      x *= lac, y *= lac, z *= lac;
    }
  } else {
    double off = ICS_OBJ(ob, O_OFFSET),
           signal = off - ICS_FABS(ics_k_perlin(ICS_VIEW_ARG pb, x, y, z));
    signal *= signal;
    f = signal;
    double expo = 1.0;
    for (int o = 1; o < octaves; o++) {
      x *= lac, y *= lac, z *= lac;
      expo /= lac;
      double weight = signal * gain;
      weight = weight < 0 ? 0.0 : weight > 1 ? 1.0 : weight;
      signal = off - ICS_FABS(ics_k_perlin(ICS_VIEW_ARG pb, x, y, z));
      signal *= signal * weight;
      f += signal * expo;
    }
  }
  return ICS_OBJ(ob, O_BIAS) + ICS_OBJ(ob, O_SCALE) * f;
}

#endif
