/* sat.cl — summed-area tables in OpenCL C 1.2 (libicshadow_cl/src/sat_cl.c, docs/sat.md "On OpenCL"): the
 * same sums in the same order as the core's SSE2 builder (libicshadow/src/sat_build.c), as three
 * passes over the table, so a table built here equals the CPU's bit for bit:
 *   rows    one work-item per row (all slices): the x prefix in blocks of 4 (float) or 2
 *           (double) as an in-block scan (v + v shifted by one, then by two) plus the carry, the
 *           tail cell by cell; the double-float mode cell by cell (TwoSum);
 *   columns one work-item per (x, slice): t += row prefix down the rows;
 *   slices  one work-item per (x, y): S(z) = S(z - 1) + t(z) (3D tables).
 * Float modes subtract the offset m (0 for ICS_SAT_FLOAT) before summing. No contraction: every
 * product and sum rounds as in C. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

__kernel void sat_rows_f32(__global const float *in, __global float *out, int w, int rows, float m) {
  int r = (int)get_global_id(0);
  if (r >= rows) return;
  in += (size_t)r * w;
  out += (size_t)r * w;
  float c = 0;
  int x = 0;
  for (; x + 4 <= w; x += 4) {
    float a0 = in[x] - m, a1 = in[x + 1] - m, a2 = in[x + 2] - m, a3 = in[x + 3] - m;
    float s0 = a0 + 0.0f, s1 = a1 + a0, s2 = a2 + a1, s3 = a3 + a2; /* v + (v << 1) */
    float u0 = s0 + 0.0f, u1 = s1 + 0.0f, u2 = s2 + s0, u3 = s3 + s1; /* + (v << 2) */
    out[x] = u0 + c, out[x + 1] = u1 + c, out[x + 2] = u2 + c, out[x + 3] = c = u3 + c;
  }
  for (; x < w; x++) out[x] = c += in[x] - m;
}

__kernel void sat_rows_f64(__global const float *in, __global double *out, int w, int rows) {
  int r = (int)get_global_id(0);
  if (r >= rows) return;
  in += (size_t)r * w;
  out += (size_t)r * w;
  double c = 0;
  int x = 0;
  for (; x + 2 <= w; x += 2) {
    double a0 = in[x], a1 = in[x + 1];
    double s0 = a0 + 0.0, s1 = a1 + a0;
    out[x] = s0 + c, out[x + 1] = c = s1 + c;
  }
  for (; x < w; x++) out[x] = c += (double)in[x];
}

/* double-float addition (sat_build.c ff_add): TwoSum, then Fast2Sum */
static float2 ff_add(float2 a, float2 b) {
  float s = a.x + b.x;
  float bb = s - a.x;
  float e = (a.x - (s - bb)) + (b.x - bb);
  e += a.y + b.y;
  float hi = s + e;
  return (float2)(hi, e - (hi - s));
}

__kernel void sat_rows_ff(__global const float *in, __global float *hi, __global float *lo, int w,
                          int rows) {
  int r = (int)get_global_id(0);
  if (r >= rows) return;
  size_t o = (size_t)r * w;
  float2 acc = (float2)(0.0f, 0.0f);
  for (int x = 0; x < w; x++) {
    acc = ff_add(acc, (float2)(in[o + x], 0.0f));
    hi[o + x] = acc.x, lo[o + x] = acc.y;
  }
}

/* columns: one work-item per (x, slice z) of a w x h x d table */
__kernel void sat_cols_f32(__global float *t, int w, int h, int d) {
  int x = (int)get_global_id(0), z = (int)get_global_id(1);
  if (x >= w || z >= d) return;
  __global float *p = t + (size_t)z * h * w + x;
  float acc = 0;
  for (int y = 0; y < h; y++) p[(size_t)y * w] = acc = acc + p[(size_t)y * w];
}
__kernel void sat_cols_f64(__global double *t, int w, int h, int d) {
  int x = (int)get_global_id(0), z = (int)get_global_id(1);
  if (x >= w || z >= d) return;
  __global double *p = t + (size_t)z * h * w + x;
  double acc = 0;
  for (int y = 0; y < h; y++) p[(size_t)y * w] = acc = acc + p[(size_t)y * w];
}
__kernel void sat_cols_ff(__global float *hi, __global float *lo, int w, int h, int d) {
  int x = (int)get_global_id(0), z = (int)get_global_id(1);
  if (x >= w || z >= d) return;
  size_t o = (size_t)z * h * w + x;
  float2 acc = (float2)(0.0f, 0.0f);
  for (int y = 0; y < h; y++) {
    size_t i = o + (size_t)y * w;
    acc = ff_add(acc, (float2)(hi[i], lo[i]));
    hi[i] = acc.x, lo[i] = acc.y;
  }
}

/* slices: one work-item per (x, y) cell of a slice, z = 1 .. d - 1 */
__kernel void sat_slices_f32(__global float *t, int n, int d) {
  int i = (int)get_global_id(0);
  if (i >= n) return;
  for (int z = 1; z < d; z++) t[(size_t)z * n + i] = t[(size_t)(z - 1) * n + i] + t[(size_t)z * n + i];
}
__kernel void sat_slices_f64(__global double *t, int n, int d) {
  int i = (int)get_global_id(0);
  if (i >= n) return;
  for (int z = 1; z < d; z++) t[(size_t)z * n + i] = t[(size_t)(z - 1) * n + i] + t[(size_t)z * n + i];
}
__kernel void sat_slices_ff(__global float *hi, __global float *lo, int n, int d) {
  int i = (int)get_global_id(0);
  if (i >= n) return;
  for (int z = 1; z < d; z++) {
    size_t a = (size_t)(z - 1) * n + i, b = (size_t)z * n + i;
    float2 r = ff_add((float2)(hi[a], lo[a]), (float2)(hi[b], lo[b]));
    hi[b] = r.x, lo[b] = r.y;
  }
}
