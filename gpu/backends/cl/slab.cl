/* slab.cl — the slab renderer's two steps per slab in OpenCL C 1.2 (docs/backend_cl.md), the
 * same arithmetic as the CPU backend (gpu/backends/cpu/propagate.c, gpu/backends/cpu/backend_cpu.c):
 *
 *   ics_prop_* one light buffer's slab step, dst(p) = sum_j w_j src(read_j(p)), with the host's
 *              prepared taps (ics_prop_prepare / _perspective): a stencil of integer taps
 *              (_stencil), a table of bilinear tap sets of which each pixel takes the one the
 *              counter RNG picks (_table; Philox-4x32-10, the layout of ics_slab_choice), or the
 *              perspective classes blended by the fraction of the magnification's read offset
 *              (_classes);
 *   ics_shade  per buffer pixel: the occlusions due at this slab (the surface windows), the
 *              colours of the surfaces in this slab lit by the light arriving here, then the
 *              clamp of signed kernels.
 *
 * Light buffers have the CPU's layout with its apron (below): light l, channel c at planes
 * l nch + c; ics_apron_* refresh the apron after each slab. Double precision
 * where the CPU computes in double (the device must offer cl_khr_fp64); no contraction, so a
 * product and a sum round as they do in C. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u
#define PHILOX_W1 0xBB67AE85u

/* Philox-4x32-10 (libicshadow/src/rng.c) of counter (c0, c1, c2, c3) under key (k0, k1), in
 * place, the ten rounds written out. Scalars and 64-bit products, no loop: PoCL vectorises
 * that across work-items (with uint4, mul_hi and a round loop a slab step took ten times as
 * long). */
#define PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                                             \
  {                                                                                      \
    ulong p0_ = (ulong)PHILOX_M0 * c0, p1_ = (ulong)PHILOX_M1 * c2;                      \
    uint n0_ = (uint)(p1_ >> 32) ^ c1 ^ k0, n2_ = (uint)(p0_ >> 32) ^ c3 ^ k1;            \
    c1 = (uint)p1_, c3 = (uint)p0_, c0 = n0_, c2 = n2_;                                  \
  }
#define PHILOX_BUMP(k0, k1) k0 += PHILOX_W0, k1 += PHILOX_W1;
#define PHILOX(c0, c1, c2, c3, k0, k1)                                                   \
  PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                                                   \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)                               \
  PHILOX_BUMP(k0, k1) PHILOX_ROUND(c0, c1, c2, c3, k0, k1)

/* word `index` of the block at counter (block, slab, light, "slab") under key seed */
static uint slab_word(uint seed_lo, uint seed_hi, uint light, uint slab, uint block, int index) {
  uint c0 = block, c1 = slab, c2 = light, c3 = 0x736c6162u, k0 = seed_lo, k1 = seed_hi;
  PHILOX(c0, c1, c2, c3, k0, k1)
  return index == 0 ? c0 : index == 1 ? c1 : index == 2 ? c2 : c3;
}

/* ics_rng_uniform_at(seed, stream, index): 53 bits of the 64-bit word `index` of the stream */
static double uniform_at(uint seed_lo, uint seed_hi, ulong stream, ulong index) {
  ulong block = index >> 1;
  uint c0 = (uint)block, c1 = (uint)(block >> 32), c2 = (uint)stream, c3 = (uint)(stream >> 32);
  uint k0 = seed_lo, k1 = seed_hi;
  PHILOX(c0, c1, c2, c3, k0, k1)
  ulong x = (index & 1) ? ((ulong)c2 | (ulong)c3 << 32) : ((ulong)c0 | (ulong)c1 << 32);
  return (double)(x >> 11) * 0x1p-53;
}

/* ics_slab_choice_bits and ics_slab_word_choice: the bits of a packed choice among k (0: the
 * word scaled), and chunk c of a word */
static int choice_bits(uint k) {
  return k >= 2u && k <= 256u && (k & (k - 1u)) == 0u ? (int)(31u - clz(k)) : 0;
}
static uint word_choice(uint word, uint k, int b, uint c) {
  return b ? (word >> (32 - b * (int)(c + 1u))) & (k - 1u) : (uint)(((ulong)word * k) >> 32);
}

/* ics_slab_choice: the word of counter `id` scaled to [0, k) */
static uint slab_choice(uint seed_lo, uint seed_hi, uint light, uint slab, uint id, uint k) {
  uint block = (id / 64u) * 16u + id % 16u;
  uint w = slab_word(seed_lo, seed_hi, light, slab, block, (int)((id / 16u) % 4u));
  return word_choice(w, k, 0, 0u);
}

static int clampi(int v, int hi) { return v < 0 ? 0 : v > hi ? hi : v; }

/* Buffers have the CPU's layout (propagate.h): rows of `stride` floats with an apron of A
 * replicated edge pixels on every side, pixel (x, y) at origin + y stride + x, channel planes
 * `plane` floats apart. Within the apron a read needs no clamp, so neighbouring work-items read
 * neighbouring floats (PoCL vectorises that); taps that reach farther clamp every index. */
typedef struct buf_layout {
  int w, h, stride, plane, origin;
} buf_layout;
#define AT(B, x, y) ((B).origin + (y) * (B).stride + (x))

/* the taps of perspective class (bx, by) at pixel (nx, ny) (propagate.c class_sum) */
static float class_sum(__global const float *S, buf_layout B, __global const int *ix,
                       __global const int *iy, __global const float *wt, int n, int Q, int bx,
                       int by, int nx, int ny) {
  if (bx == Q) bx = 0, nx++;
  if (by == Q) by = 0, ny++;
  int base = (by * Q + bx) * n;
  float acc = 0;
  for (int m = base; m < base + n; m++)
    acc += wt[m] * S[AT(B, clampi(nx + ix[m], B.w - 1), clampi(ny + iy[m], B.h - 1))];
  return acc;
}

/* The three forms of a slab step (propagate.c), one kernel each. Each reads light l's planes at
 * src + base and writes them at dst + base; `clamped` when a tap reaches beyond the apron. */
#define PROP_ARGS                                                                              \
  __global const float *src, __global float *dst, int base, buf_layout B, int nch, int ntaps,  \
      __global const int *ix, __global const int *iy, __global const int *off,                 \
      __global const float *wt, int clamped

/* a stencil: one set of integer taps (ics_prop_prepare's discretised set; off = iy stride + ix).
 * A work-item makes 16 consecutive pixels of a row, as one float16 per tap where the reads stay
 * within the apron and the row: the same products and sums per pixel, in the same order, as the
 * scalar loop, but 16 at a time (PoCL does not vectorise a tap loop across work-items). */
__kernel __attribute__((reqd_work_group_size(8, 8, 1))) void ics_prop_stencil(PROP_ARGS) {
  int x0 = 16 * (int)get_global_id(0), y = (int)get_global_id(1);
  if (x0 >= B.w || y >= B.h) return;
  int p = AT(B, x0, y);
  src += base;
  dst += base;
  for (int c = 0; c < nch; c++) {
    __global const float *S = src + c * B.plane;
    if (!clamped && x0 + 16 <= B.w) {
      float16 acc = 0;
      for (int j = 0; j < ntaps; j++) acc += wt[j] * vload16(0, S + p + off[j]);
      vstore16(acc, 0, dst + c * B.plane + p);
      continue;
    }
    for (int x = x0; x < x0 + 16 && x < B.w; x++) {
      float acc = 0;
      if (clamped)
        for (int j = 0; j < ntaps; j++)
          acc += wt[j] * S[AT(B, clampi(x + ix[j], B.w - 1), clampi(y + iy[j], B.h - 1))];
      else
        for (int j = 0; j < ntaps; j++) acc += wt[j] * S[p + (x - x0) + off[j]];
      dst[c * B.plane + p + (x - x0)] = acc;
    }
  }
}

/* The tap set of each pixel of a table step (below), the choices of ics_prop_entries_row and
 * ics_prop_run_choice. Per pixel (run 1): one work-item per Philox block b, whose four words
 * hold the choices of pixels 64 n (b / 16) + b % 16 + 64 c + 16 i (word i = 0..3, chunk
 * c = 0..n - 1; ics_slab_pixel_choice) of the row-major w x h grid.
 * Per run of 16 (run 16): one work-item per run k of row y, the pixels x with
 * (x + 16 - phase) / 16 = k. No loops but the pixels' writes, so PoCL vectorises the rounds. */
__kernel void ics_entries_pixel(__global uint *ent, int npx, int entries, uint seed_lo,
                                uint seed_hi, uint light, uint slab) {
  int bits = choice_bits((uint)entries);
  uint n = (uint)ICS_CHOICE_CHUNKS(bits), b = (uint)get_global_id(0);
  uint first = 64u * n * (b / 16u) + b % 16u;
  if (first >= (uint)npx) return;
  uint c0 = b, c1 = slab, c2 = light, c3 = 0x736c6162u, k0 = seed_lo, k1 = seed_hi;
  PHILOX(c0, c1, c2, c3, k0, k1)
  uint words[4] = {c0, c1, c2, c3};
  for (uint c = 0; c < n; c++)
    for (int i = 0; i < 4; i++) {
      uint px = first + 64u * c + 16u * (uint)i;
      if (px < (uint)npx) ent[px] = word_choice(words[i], (uint)entries, bits, c);
    }
}
__kernel void ics_entries_run(__global uint *ent, int w, int h, int entries, uint seed_lo,
                              uint seed_hi, uint light, uint slab, int phase) {
  int k = (int)get_global_id(0), y = (int)get_global_id(1);
  int xa = max(16 * k - 16 + phase, 0), xb = min(16 * k + phase, w);
  if (y >= h || xa >= xb) return;
  uint e = slab_choice(seed_lo, seed_hi, light, slab, (uint)y * (uint)(w + 32) + 16u * (uint)k,
                       (uint)entries);
  for (int x = xa; x < xb; x++) ent[y * w + x] = e;
}

/* one pixel of a table step: tap set starting at e0 (ntaps taps) */
static float table_pixel(__global const float *S, buf_layout B, int x, int y, int p, int e0,
                         int ntaps, __global const int *ix, __global const int *iy,
                         __global const int *off, __global const float *wt,
                         __global const float *fx, __global const float *fy, int clamped) {
  float acc = 0;
  for (int j = e0; j < e0 + ntaps; j++) {
    float a, b, cc, d;
    if (clamped) {
      int x0 = x + ix[j], y0 = y + iy[j];
      int xa = clampi(x0, B.w - 1), xb = clampi(x0 + 1, B.w - 1);
      int ya = clampi(y0, B.h - 1), yb = clampi(y0 + 1, B.h - 1);
      a = S[AT(B, xa, ya)], b = S[AT(B, xb, ya)], cc = S[AT(B, xa, yb)], d = S[AT(B, xb, yb)];
    } else {
      __global const float *r0 = S + p + off[j];
      a = r0[0], b = r0[1], cc = r0[B.stride], d = r0[B.stride + 1];
    }
    float top = a + fx[j] * (b - a), bot = cc + fx[j] * (d - cc);
    acc += wt[j] * (top + fy[j] * (bot - top));
  }
  return acc;
}

/* a table of `entries` bilinear tap sets, pixel (x, y) taking set ent[y w + x] (ics_entries:
 * chosen per pixel, run 1, or per run of 16 pixels of a row starting at x = phase, run 16, by
 * the counter RNG as ics_prop_entries_row and ics_prop_run_choice choose; a kernel of its own,
 * without loops, so PoCL vectorises the ten Philox rounds across pixels). A work-item makes 16
 * consecutive pixels of a row: with at most TABLE_VEC entries and reads within the apron, every
 * tap set its pixels use is applied to all 16 as float16 and each pixel keeps its own set's
 * result (the same arithmetic per pixel as the scalar loop; a per-pixel gather does not
 * vectorise); otherwise pixel by pixel. */
#define TABLE_VEC 8
__kernel __attribute__((reqd_work_group_size(8, 8, 1))) void ics_prop_table(
    PROP_ARGS, __global const uint *ent, __global const float *fx, __global const float *fy,
    int entries) {
  int x0 = 16 * (int)get_global_id(0), y = (int)get_global_id(1);
  if (x0 >= B.w || y >= B.h) return;
  int p = AT(B, x0, y);
  src += base;
  dst += base;
  __global const uint *E = ent + y * B.w + x0;
  if (!clamped && entries <= TABLE_VEC && x0 + 16 <= B.w) {
    uint16 e16 = vload16(0, E);
    for (int c = 0; c < nch; c++) {
      __global const float *S = src + c * B.plane + p;
      float16 acc = 0;
      for (uint e = 0; e < (uint)entries; e++) {
        int16 mine = e16 == (uint16)e;
        if (!any(mine)) continue;
        float16 r = 0;
        for (int j = (int)e * ntaps; j < (int)e * ntaps + ntaps; j++) {
          __global const float *r0 = S + off[j];
          float16 a = vload16(0, r0), b = vload16(0, r0 + 1);
          float16 cc = vload16(0, r0 + B.stride), d = vload16(0, r0 + B.stride + 1);
          float16 top = a + fx[j] * (b - a), bot = cc + fx[j] * (d - cc);
          r += wt[j] * (top + fy[j] * (bot - top));
        }
        acc = select(acc, r, mine);
      }
      vstore16(acc, 0, dst + c * B.plane + p);
    }
    return;
  }
  for (int c = 0; c < nch; c++) {
    __global const float *S = src + c * B.plane;
    for (int x = x0; x < x0 + 16 && x < B.w; x++)
      dst[c * B.plane + p + (x - x0)] = table_pixel(S, B, x, y, p + (x - x0),
                                                    (int)E[x - x0] * ntaps, ntaps, ix, iy, off,
                                                    wt, fx, fy, clamped);
  }
}

/* a perspective step: Q x Q classes of integer taps (ntaps each), magnification s about
 * (cx, cy), the four classes around the read offset's fraction blended linearly */
__kernel __attribute__((reqd_work_group_size(16, 8, 1))) void ics_prop_classes(
    PROP_ARGS, int Q, double s, double cx, double cy) {
  int x = (int)get_global_id(0), y = (int)get_global_id(1);
  if (x >= B.w || y >= B.h) return;
  int p = AT(B, x, y);
  src += base;
  dst += base;
  double Dx = (s - 1) * (x - cx), Dy = (s - 1) * (y - cy);
  double fX = floor(Dx), tX = (Dx - fX) * Q, kX = floor(tX);
  double fY = floor(Dy), tY = (Dy - fY) * Q, kY = floor(tY);
  int nx = x + (int)fX, ny = y + (int)fY, k0 = (int)kX, k1 = (int)kY;
  float r0 = (float)(tX - kX), r1 = (float)(tY - kY);
  for (int c = 0; c < nch; c++) {
    __global const float *S = src + c * B.plane;
    float a00 = class_sum(S, B, ix, iy, wt, ntaps, Q, k0, k1, nx, ny);
    float a10 = class_sum(S, B, ix, iy, wt, ntaps, Q, k0 + 1, k1, nx, ny);
    float a01 = class_sum(S, B, ix, iy, wt, ntaps, Q, k0, k1 + 1, nx, ny);
    float a11 = class_sum(S, B, ix, iy, wt, ntaps, Q, k0 + 1, k1 + 1, nx, ny);
    float top = a00 + r0 * (a10 - a00), bot = a01 + r0 * (a11 - a01);
    dst[c * B.plane + p] = top + r1 * (bot - top);
  }
}

/* The apron of every plane (ics_prop_apron): first the A pixels left and right of each row
 * (work-items: apron column a of 2 A, row y, plane c), then the A rows above and below, whole
 * (work-items: column 0..stride-1, apron row of 2 A, plane c). */
__kernel void ics_apron_sides(__global float *buf, buf_layout B, int A) {
  int a = (int)get_global_id(0), y = (int)get_global_id(1), c = (int)get_global_id(2);
  __global float *row = buf + c * B.plane + AT(B, 0, y);
  if (a < A) row[-1 - a] = row[0];
  else row[B.w + (a - A)] = row[B.w - 1];
}
__kernel void ics_apron_ends(__global float *buf, buf_layout B, int A) {
  int x = (int)get_global_id(0) - A, r = (int)get_global_id(1), c = (int)get_global_id(2);
  __global float *P = buf + c * B.plane;
  if (r < A) P[AT(B, x, -1 - r)] = P[AT(B, x, 0)];
  else P[AT(B, x, B.h + (r - A))] = P[AT(B, x, B.h - 1)];
}

/* ---- shading ---------------------------------------------------------------------------- */

/* Objects and the camera: the offsets O_*, CAM_* and the strides of gpu/core/device_layout.h
 * (embedded ahead of this file) */

#define JITTER_STREAM 0x6a69747400000000UL /* "jitt" (backend_cpu.c) */
#define MAXV 8 /* overlapping volumes whose extinctions are kept (private memory) */

#define FRAG_OBJ(code) ((int)((code) & 0xfffu))
#define FRAG_BIAS(code) ((int)((code) >> 12 & 0xfu))
#define FRAG_SLAB(code) ((int)((code) >> 16))

/* ics_plan_ray: the camera ray of buffer pixel (bi, bj) */
static void plan_ray(__global const double *cam, int W, int H, int pad_l, int pad_t, int bi,
                     int bj, double o[3], double d[3]) {
  double s = (bi - pad_l + 0.5) / W, t = (bj - pad_t + 0.5) / H;
  if (cam[CAM_PROJ] == 0) {
    double h = cam[CAM_H], w = cam[CAM_W];
    for (int i = 0; i < 3; i++) {
      o[i] = cam[CAM_EYE + i] + (s - 0.5) * w * cam[CAM_R + i] + (0.5 - t) * h * cam[CAM_U + i];
      d[i] = cam[CAM_F + i];
    }
  } else {
    double th = cam[CAM_TH], asp = cam[CAM_ASP];
    for (int i = 0; i < 3; i++) {
      o[i] = cam[CAM_EYE + i];
      d[i] = cam[CAM_F + i] + (2 * s - 1) * th * asp * cam[CAM_R + i] + (1 - 2 * t) * th * cam[CAM_U + i];
    }
  }
}

/* detail.c: improved noise, fBm, ridged multifractal */
static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
static double lerp_d(double t, double a, double b) { return a + t * (b - a); }
static double grad3(int hash, double x, double y, double z) {
  int h = hash & 15;
  double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
static double perlin(__global const uchar *p, double x, double y, double z) {
  double fx = floor(x), fy = floor(y), fz = floor(z);
  int X = (int)(fx - 256 * floor(fx / 256)) & 255, Y = (int)(fy - 256 * floor(fy / 256)) & 255,
      Z = (int)(fz - 256 * floor(fz / 256)) & 255;
  x -= fx, y -= fy, z -= fz;
  double u = fade(x), v = fade(y), w = fade(z);
  int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
  int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
  return lerp_d(w,
                lerp_d(v, lerp_d(u, grad3(p[AA], x, y, z), grad3(p[BA], x - 1, y, z)),
                       lerp_d(u, grad3(p[AB], x, y - 1, z), grad3(p[BB], x - 1, y - 1, z))),
                lerp_d(v, lerp_d(u, grad3(p[AA + 1], x, y, z - 1), grad3(p[BA + 1], x - 1, y, z - 1)),
                       lerp_d(u, grad3(p[AB + 1], x, y - 1, z - 1),
                              grad3(p[BB + 1], x - 1, y - 1, z - 1))));
}

/* ics_volume_sample: trilinear, cell centres at i + 1/2, clamped at the faces, 0 outside */
static double grid_sample(__global const float *d, const size_t n[3], const double p[3]) {
  long i0[3], i1[3];
  double f[3];
  for (int a = 0; a < 3; a++) {
    if (!(p[a] >= 0.0 && p[a] <= (double)n[a])) return 0.0;
    double g = p[a] - 0.5, fl = floor(g);
    f[a] = g - fl;
    long i = (long)fl, last = (long)n[a] - 1;
    i0[a] = i < 0 ? 0 : i > last ? last : i;
    i1[a] = i + 1 < 0 ? 0 : i + 1 > last ? last : i + 1;
  }
  size_t sy = n[0], sz = n[0] * n[1];
#define V_(i, j, k) ((double)d[(size_t)(i) + (size_t)(j) * sy + (size_t)(k) * sz])
  double c00 = V_(i0[0], i0[1], i0[2]) * (1 - f[0]) + V_(i1[0], i0[1], i0[2]) * f[0];
  double c10 = V_(i0[0], i1[1], i0[2]) * (1 - f[0]) + V_(i1[0], i1[1], i0[2]) * f[0];
  double c01 = V_(i0[0], i0[1], i1[2]) * (1 - f[0]) + V_(i1[0], i0[1], i1[2]) * f[0];
  double c11 = V_(i0[0], i1[1], i1[2]) * (1 - f[0]) + V_(i1[0], i1[1], i1[2]) * f[0];
#undef V_
  double c0 = c00 * (1 - f[1]) + c10 * f[1], c1 = c01 * (1 - f[1]) + c11 * f[1];
  return c0 * (1 - f[2]) + c1 * f[2];
}

static double detail_value(__global const double *ob, __global const uchar *perm,
                           __global const float *grids, const double pt[3]) {
  const double drift[3] = {0.3713, 0.5129, 0.7731};
  int fn = (int)ob[O_DETAIL], octaves = (int)ob[O_OCTAVES];
  if (fn == 4) { /* the grid over the object's box (detail.c) */
    size_t n[3];
    double q[3];
    for (int i = 0; i < 3; i++) {
      double lo = ob[O_GRID_LO + i], hi = ob[O_GRID_HI + i];
      n[i] = (size_t)ob[O_GRID_N + i];
      q[i] = hi > lo ? (pt[i] - lo) / (hi - lo) * (double)n[i] : 0;
    }
    return ob[O_BIAS] + ob[O_SCALE] * grid_sample(grids + (size_t)ob[O_GRID], n, q);
  }
  double fr = ob[O_FREQ], tm = ob[O_TIME], lac = ob[O_LACUNARITY], gain = ob[O_GAIN];
  double x = fr * pt[0] + tm * drift[0], y = fr * pt[1] + tm * drift[1], z = fr * pt[2] + tm * drift[2];
  double f;
  if (fn == 1) {
    f = perlin(perm, x, y, z);
  } else if (fn == 2) {
    f = 0;
    double amp = 1;
    for (int o = 0; o < octaves; o++) {
      f += amp * perlin(perm, x, y, z);
      amp *= gain;
      x *= lac, y *= lac, z *= lac;
    }
  } else {
    double off = ob[O_OFFSET], signal = off - fabs(perlin(perm, x, y, z));
    signal *= signal;
    f = signal;
    double expo = 1;
    for (int o = 1; o < octaves; o++) {
      x *= lac, y *= lac, z *= lac;
      expo /= lac;
      double weight = signal * gain;
      weight = weight < 0 ? 0 : weight > 1 ? 1 : weight;
      signal = off - fabs(perlin(perm, x, y, z));
      signal *= signal * weight;
      f += signal * expo;
    }
  }
  return ob[O_BIAS] + ob[O_SCALE] * f;
}

/* ics_material_transfer */
static void transfer(__global const double *ob, __global const double *tt, double v, double rgb[3],
                     double *scale) {
  int n = (int)ob[O_NTRANSFER];
  if (n == 0) {
    for (int c = 0; c < 3; c++) rgb[c] = ob[O_COLOR + c];
    *scale = v > 0 ? v : 0;
    return;
  }
  __global const double *t = tt + 5 * (size_t)ob[O_TRANSFER];
  int k = 0;
  if (v <= t[0]) {
    k = -1;
  } else if (v >= t[5 * (n - 1)]) {
    k = n - 1;
  } else {
    while (k + 1 < n && t[5 * (k + 1)] <= v) k++;
  }
  if (k < 0 || k == n - 1) {
    __global const double *row = t + 5 * (k < 0 ? 0 : n - 1);
    rgb[0] = row[1], rgb[1] = row[2], rgb[2] = row[3];
    *scale = row[4];
    return;
  }
  double a = (v - t[5 * k]) / (t[5 * (k + 1)] - t[5 * k]);
  for (int c = 0; c < 3; c++) rgb[c] = t[5 * k + 1 + c] + a * (t[5 * (k + 1) + 1 + c] - t[5 * k + 1 + c]);
  *scale = t[5 * k + 4] + a * (t[5 * (k + 1) + 4] - t[5 * k + 4]);
}

static void linear_piece(__global const double *ob, __global const double *tt, double a, double b,
                         double *S, double CS[3]) {
  double ca[3], cm[3], cb[3], sa, sm, sb, h = b - a;
  transfer(ob, tt, a, ca, &sa);
  transfer(ob, tt, 0.5 * (a + b), cm, &sm);
  transfer(ob, tt, b, cb, &sb);
  *S += h * (sa + 4 * sm + sb) / 6;
  for (int c = 0; c < 3; c++) CS[c] += h * (ca[c] * sa + 4 * cm[c] * sm + cb[c] * sb) / 6;
}

/* ics_material_preintegrate, walking the breakpoints in order instead of collecting them */
static void preintegrate(__global const double *ob, __global const double *tt, double vf, double vb,
                         double rgb[3], double *scale) {
  double lo = fmin(vf, vb), hi = fmax(vf, vb);
  if (!(hi - lo > 1e-12 * (1 + fabs(hi)))) {
    transfer(ob, tt, 0.5 * (vf + vb), rgb, scale);
    return;
  }
  int n = (int)ob[O_NTRANSFER];
  __global const double *t = tt + 5 * (size_t)ob[O_TRANSFER];
  double S = 0, CS[3] = {0, 0, 0}, prev = lo;
  if (n == 0) {
    if (lo < 0 && hi > 0) linear_piece(ob, tt, prev, 0.0, &S, CS), prev = 0;
  } else {
    for (int i = 0; i < n; i++)
      if (t[5 * i] > lo && t[5 * i] < hi) linear_piece(ob, tt, prev, t[5 * i], &S, CS), prev = t[5 * i];
  }
  linear_piece(ob, tt, prev, hi, &S, CS);
  *scale = S / (hi - lo);
  if (S > 0) {
    for (int c = 0; c < 3; c++) rgb[c] = CS[c] / S;
  } else {
    transfer(ob, tt, 0.5 * (vf + vb), rgb, scale);
    *scale = 0;
  }
}

/* What ics_shade needs besides the buffers (one struct: OpenCL C 1.2 passes it by value). */
typedef struct shade_args {
  buf_layout B; /* the light buffers (B.w x B.h = the LDI grid) */
  int nch, nlights, k, nvol, W, H, pad_l, pad_t, preintegrate;
  int aov_count, aov_vis, aov_z; /* AOV floats per view pixel, offsets (-1: not asked; 0 count:
                                    none) */
  uint seed_lo, seed_hi;
  double zf, zb, window_max;
} shade_args;

/* the extinction and colour of volume object ob_i at the piece's sample point(s) */
static double volume_sig(const shade_args *A, __global const double *obj,
                         __global const double *tt, __global const uchar *perm,
                         __global const float *grids, int ob_i, const double pt[3],
                         const double pt2[3], double c[3]) {
  __global const double *ob = obj + ICS_DEV_OBJ_STRIDE * ob_i;
  double scale = 1;
  c[0] = ob[O_COLOR], c[1] = ob[O_COLOR + 1], c[2] = ob[O_COLOR + 2];
  if (ob[O_DETAIL] != 0) {
    __global const uchar *pm = perm + 512 * ob_i;
    double v = detail_value(ob, pm, grids, pt);
    if (A->preintegrate)
      preintegrate(ob, tt, v, detail_value(ob, pm, grids, pt2), c, &scale);
    else
      transfer(ob, tt, v, c, &scale);
  }
  return ob[O_EXTINCTION] * scale;
}

#define LOWEST_BIT(m) ((int)(63 - clz((m) & (~(m) + 1))))

/* backend_cpu.c volume_piece: one volume piece of depth extent dz from za. The extinctions of
 * up to MAXV overlapping volumes are kept for the transmittance; with more, each is evaluated
 * again per light (the same values: the sample point depends on the pixel and slab only). */
static void volume_piece(const shade_args *A, __global float *dst, __global const double *obj,
                         __global const double *tt, __global const uchar *perm,
                         __global const float *grids, __global const int *vol_obj,
                         __global const double *cam,
                         __global const double *lpath, int p, int q, int bi, int bj, ulong mask,
                         double za, double dz, const double L[3], float4 *C, int inview) {
  double sig[MAXV], o[3], d[3], pt[3], pt2[3], sum = 0, cc[3] = {0, 0, 0};
  int nv = 0, have_ray = 0, keep = popcount(mask) <= MAXV;
  for (ulong m = mask; m; m &= m - 1) /* the sample point, if some volume has detail */
    if (obj[ICS_DEV_OBJ_STRIDE * vol_obj[LOWEST_BIT(m)] + O_DETAIL] != 0) {
      plan_ray(cam, A->W, A->H, A->pad_l, A->pad_t, bi, bj, o, d);
      if (A->preintegrate) {
        for (int i = 0; i < 3; i++) pt[i] = o[i] + za * d[i], pt2[i] = o[i] + (za + dz) * d[i];
      } else {
        double xi = uniform_at(A->seed_lo, A->seed_hi, JITTER_STREAM | (ulong)A->k, (ulong)p);
        double zs = za + xi * dz;
        for (int i = 0; i < 3; i++) pt[i] = o[i] + zs * d[i];
      }
      have_ray = 1;
      break;
    }
  for (ulong m = mask; m; m &= m - 1, nv++) {
    double c[3], sg = volume_sig(A, obj, tt, perm, grids, vol_obj[LOWEST_BIT(m)], pt, pt2, c);
    if (keep) sig[nv] = sg;
    sum += sg;
    for (int k = 0; k < 3; k++) cc[k] += sg * c[k];
  }
  if (!(sum > 0)) return;
  if (inview && C->w < 1) {
    double dl = 1;
    if (cam[CAM_PROJ] != 0) {
      if (!have_ray) plan_ray(cam, A->W, A->H, A->pad_l, A->pad_t, bi, bj, o, d);
      dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    double a = 1 - exp(-sum * dz * dl), wgt = (1 - C->w) * a;
    C->x += (float)(wgt * (cc[0] / sum) * L[0]);
    C->y += (float)(wgt * (cc[1] / sum) * L[1]);
    C->z += (float)(wgt * (cc[2] / sum) * L[2]);
    C->w += (float)wgt;
  }
  for (int l = 0; l < A->nlights; l++) {
    double pass[3] = {1, 1, 1};
    int i = 0;
    for (ulong m = mask; m; m &= m - 1, i++) {
      int ob_i = vol_obj[LOWEST_BIT(m)];
      double c[3], sg = keep ? sig[i] : volume_sig(A, obj, tt, perm, grids, ob_i, pt, pt2, c);
      __global const double *T = obj + ICS_DEV_OBJ_STRIDE * ob_i + O_TRANSPORT;
      for (int k = 0; k < A->nch; k++) pass[k] *= exp(-sg * dz * lpath[l] * (1 - T[k]));
    }
    for (int k = 0; k < A->nch; k++) dst[(l * A->nch + k) * A->B.plane + q] *= (float)pass[k];
  }
}

/* backend_cpu.c surface_occlusion: fragment f's occlusion, `after` slabs after its first */
static void surface_occlusion(const shade_args *A, __global float *dst, __global const double *ob,
                              float2 g, uchar span, __global const double *lmu,
                              __global const double *window, int q, int after) {
  double a = ob[O_OPACITY];
  if (!(a > 0)) return;
  double gr = g.x, gu = g.y;
  for (int l = 0; l < A->nlights; l++) {
    double win = floor(span * window[l]);
    if (after > win) continue;
    double rho = -(gr * lmu[2 * l] + gu * lmu[2 * l + 1]), rel = fabs(1 - rho), meets = 1;
    if (win > 0) meets = rel > 0 ? fmin(fmax((win + 1) / rel, 1.0), 8 * (win + 1)) : 8 * (win + 1);
    for (int c = 0; c < A->nch; c++) {
      double pass = 1 - a * (1 - ob[O_TRANSPORT + c]);
      dst[(l * A->nch + c) * A->B.plane + q] *= (float)(meets > 1 ? pow(pass, 1 / meets) : pass);
    }
  }
}

/* Per buffer pixel, slab A.k (backend_cpu.c shade_rows): the light arriving, the occlusions due
 * now, the volume pieces and surfaces of this slab front to back, then the clamp of signed
 * kernels. Fragments: depth, code (object | bias << 12 | slab << 16), depth gradient
 * (dz/dr, dz/du), span. Lights: lcol[3 l ..] = colour x weight, lmu[2 l ..] = mean, lpath[l] =
 * light path per unit depth, window[l] this slab's window, signed_l[l] = 1 for signed weights. */
__kernel __attribute__((reqd_work_group_size(16, 8, 1))) void ics_shade(__global float *dst, shade_args A, __global const uint *offset,
                        __global const float *fz, __global const uint *fcode,
                        __global const float2 *fgrad, __global const uchar *fspan,
                        __global uint *cursor, __global uint *acursor, __global ulong *inside,
                        __global const double *obj, __global const double *tt,
                        __global const uchar *perm, __global const float *grids,
                        __global const int *vol_obj, __global const double *cam,
                        __global const double *lcol,
                        __global const double *lmu, __global const double *lpath,
                        __global const double *window, __global const int *signed_l,
                        __global float *img, __global float *aov,
                        __global uchar *aov_seen) {
  int bi = (int)get_global_id(0), bj = (int)get_global_id(1), k = A.k;
  if (bi >= A.B.w || bj >= A.B.h) return;
  int p = bj * A.B.w + bi, q = AT(A.B, bi, bj), nch = A.nch, plane = A.B.plane;
  uint cur = cursor[p], end = offset[p + 1], acur = acursor[p];
  ulong mask = A.nvol ? inside[p] : 0;
  int has = cur < end && FRAG_SLAB(fcode[cur]) == k;
  int occl = acur < end && FRAG_SLAB(fcode[acur]) <= k;
  if (has || mask || occl) {
    int ii = bi - A.pad_l, jj = bj - A.pad_t;
    int inview = ii >= 0 && ii < A.W && jj >= 0 && jj < A.H;
    float4 C = inview ? vload4((size_t)jj * A.W + ii, img) : (float4)(0, 0, 0, 1);
    double L[3] = {0, 0, 0};
    for (int l = 0; l < A.nlights; l++)
      for (int c = 0; c < 3; c++)
        L[c] += lcol[3 * l + c] * dst[(l * nch + (nch == 3 ? c : 0)) * plane + q];
    /* the AOVs of the pixel's first surface, if it is in this slab: the light arriving (before
     * this slab's occlusions) and its depth (backend_cpu.c record_aov) */
    if (A.aov_count && inview && has && !aov_seen[(size_t)jj * A.W + ii])
      for (uint f = cur; f < end && FRAG_SLAB(fcode[f]) == k; f++) {
        __global const double *ob = obj + ICS_DEV_OBJ_STRIDE * FRAG_OBJ(fcode[f]);
        if (ob[O_VOLBIT] >= 0 || !(ob[O_OPACITY] > 0)) continue;
        __global float *o = aov + ((size_t)jj * A.W + ii) * A.aov_count;
        if (A.aov_vis >= 0)
          for (int l = 0; l < A.nlights; l++)
            for (int c = 0; c < nch; c++) o[A.aov_vis + l * nch + c] = dst[(l * nch + c) * plane + q];
        if (A.aov_z >= 0) o[A.aov_z] = fz[f];
        aov_seen[(size_t)jj * A.W + ii] = 1;
        break;
      }
    for (uint f = acur; f < end && FRAG_SLAB(fcode[f]) <= k; f++) {
      uint code = fcode[f];
      int o = FRAG_OBJ(code), first = FRAG_SLAB(code) + FRAG_BIAS(code);
      if (obj[ICS_DEV_OBJ_STRIDE * o + O_VOLBIT] < 0 && first <= k && k <= first + fspan[f] * A.window_max)
        surface_occlusion(&A, dst, obj + ICS_DEV_OBJ_STRIDE * o, fgrad[f], fspan[f], lmu, window, q, k - first);
    }
    while (acur < end && FRAG_SLAB(fcode[acur]) + FRAG_BIAS(fcode[acur]) +
                             fspan[acur] * A.window_max <= k)
      acur++;
    acursor[p] = acur;
    if (has || mask) {
      double za = A.zf;
      for (;;) {
        double zn = has ? fz[cur] : A.zb;
        if (zn < za) zn = za;
        if (zn > A.zb) zn = A.zb;
        if (mask && zn > za)
          volume_piece(&A, dst, obj, tt, perm, grids, vol_obj, cam, lpath, p, q, bi, bj, mask, za, zn - za,
                       L, &C, inview);
        if (!has) break;
        int o = FRAG_OBJ(fcode[cur]);
        __global const double *ob = obj + ICS_DEV_OBJ_STRIDE * o;
        if (ob[O_VOLBIT] >= 0) {
          mask ^= 1UL << (int)ob[O_VOLBIT];
        } else if (inview) {
          double a = ob[O_OPACITY];
          if (a > 0 && C.w < 1) {
            double wgt = (1 - C.w) * a;
            C.x += (float)(wgt * ob[O_COLOR] * L[0]);
            C.y += (float)(wgt * ob[O_COLOR + 1] * L[1]);
            C.z += (float)(wgt * ob[O_COLOR + 2] * L[2]);
            C.w += (float)wgt;
          }
        }
        za = zn;
        cur++;
        has = cur < end && FRAG_SLAB(fcode[cur]) == k;
      }
      cursor[p] = cur;
      if (A.nvol) inside[p] = mask;
    }
    if (inview) vstore4(C, (size_t)jj * A.W + ii, img);
  }
  for (int l = 0; l < A.nlights; l++)
    if (signed_l[l])
      for (int c = 0; c < nch; c++) {
        float v = dst[(l * nch + c) * plane + q];
        dst[(l * nch + c) * plane + q] = v < 0 ? 0 : v > 1 ? 1 : v;
      }
}
