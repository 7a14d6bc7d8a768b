/* minmax.cl — 1D min-max mipmaps on the device (libicshadow_cl/src/minmax_cl.c, docs/minmax.md "On
 * OpenCL"): the trees of libicshadow/src/minmax.c in its layout (per row 2P (min, max) pairs,
 * Ahnentafel order, the row padded with its last sample), built level by level, and Chen's
 * traversal with integration, one work-item per ray, in the CPU's order: the same nodes visited,
 * the same lit runs merged, the same prefix-sum differences added. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

/* leaves: work-item (g, row), g < P */
__kernel void mm_leaves(__global const float *values, ulong stride, uint d, uint P,
                        __global float *node) {
  uint g = (uint)get_global_id(0), r = (uint)get_global_id(1);
  if (g >= P) return;
  __global float *nd = node + (size_t)r * 4 * P;
  float x = values[(size_t)r * stride + (g < d ? g : d - 1)];
  nd[2 * (P + g)] = x;
  nd[2 * (P + g) + 1] = x;
  if (g == 0) nd[0] = nd[1] = 0.0f; /* the unused slot 0 */
}

/* one level: nodes first .. 2 first - 1 of every row from their children */
__kernel void mm_level(__global float *node, uint P, uint first) {
  uint i = (uint)get_global_id(0), r = (uint)get_global_id(1);
  if (i >= first) return;
  __global float *nd = node + (size_t)r * 4 * P;
  uint k = first + i;
  float l0 = nd[4 * k], h0 = nd[4 * k + 1], l1 = nd[4 * k + 2], h1 = nd[4 * k + 3];
  nd[2 * k] = l1 < l0 ? l1 : l0;
  nd[2 * k + 1] = h1 > h0 ? h1 : h0;
}

/* a lit run [s, e): out += prefix[e] - prefix[s] per term */
static void emit(__global const double *prefix, uint nterms, uint ld, __global double *out,
                 uint s, uint e) {
  for (uint i = 0; i < nterms; i++) out[i] += prefix[(size_t)i * ld + e] - prefix[(size_t)i * ld + s];
}

/* ray q in row ray_row[q]: h(g) = beta0 + slope g over g < gamma_end; out[q nterms + i], and the
 * count of lit runs in nseg[q] (minmax.c traverse) */
__kernel void mm_integrate(__global const float *node, uint P, __global const uint *ray_row,
                           __global const double *beta0, __global const double *slope,
                           __global const uint *gamma_end, uint nrays,
                           __global const double *prefix, uint nterms, uint ld,
                           __global double *out, __global uint *nseg) {
  uint q = (uint)get_global_id(0);
  if (q >= nrays) return;
  __global double *o = out + (size_t)q * nterms;
  for (uint i = 0; i < nterms; i++) o[i] = 0.0;
  uint ge = gamma_end[q], runs = 0;
  if (ge > 0) {
    __global const float *nd = node + (size_t)ray_row[q] * 4 * P;
    double b0 = beta0[q], sl = slope[q];
    uint nodei = 1, width = P, g0 = 0, run_s = 0, run_e = 0;
    do {
      uint g1 = g0 + width, ce = g1 < ge ? g1 : ge;
      double ha = b0 + sl * (double)g0, hb = b0 + sl * (double)(ce - 1);
      double hmin = ha < hb ? ha : hb, hmax = ha < hb ? hb : ha;
      double lo = nd[2 * nodei], hi = nd[2 * nodei + 1];
      if (hmax < lo) { /* fully lit */
        if (run_e == g0 && run_e > run_s) {
          run_e = ce;
        } else {
          if (run_e > run_s) emit(prefix, nterms, ld, o, run_s, run_e), runs++;
          run_s = g0;
          run_e = ce;
        }
      } else if (!(hmin >= hi)) { /* partial: the left child */
        nodei *= 2;
        width >>= 1;
        continue;
      }
      nodei += 1;
      g0 = g1;
      while (!(nodei & 1)) {
        nodei >>= 1;
        width <<= 1;
      }
    } while (nodei != 1 && g0 < ge);
    if (run_e > run_s) emit(prefix, nterms, ld, o, run_s, run_e), runs++;
  }
  nseg[q] = runs;
}
