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
 * The per-pixel functions are the shared kernel source (gpu/kernel: choice.h, class_sum.h,
 * shade.h and what they include), the text slab.comp compiles too (and the host: choice.h,
 * camera.h, noise.h and transfer.h in the plan and the cpu backend, the rest in
 * test_kernel_c); this file holds the entry points, Philox in OpenCL C and the view of the
 * buffers those functions read.
 * Light buffers have the CPU's layout with its apron (below): light l, channel c at planes
 * l nch + c; ics_apron_* refresh the apron after each slab. Double precision
 * where the CPU computes in double (the device must offer cl_khr_fp64); no contraction, so a
 * product and a sum round as they do in C. */
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

/* the shared kernel source (gpu/kernel; cmake/embed_text.cmake expands the includes) */
#include "kernel/lang.h"
#include "kernel/device_layout.h"

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

/* Buffers have the CPU's layout (propagate.h): rows of `stride` floats with an apron of A
 * replicated edge pixels on every side, pixel (x, y) at origin + y stride + x, channel planes
 * `plane` floats apart. Within the apron a read needs no clamp, so neighbouring work-items read
 * neighbouring floats (PoCL vectorises that); taps that reach farther clamp every index. */
typedef struct buf_layout {
  int w, h, stride, plane, origin;
} buf_layout;
#define AT(B, x, y) ((B).origin + (y) * (B).stride + (x))

/* What ics_shade needs besides the buffers (one struct: OpenCL C 1.2 passes it by value). */
typedef struct shade_args {
  buf_layout B; /* the light buffers (B.w x B.h = the LDI grid) */
  int nch, nlights, k, nvol, W, H, pad_l, pad_t, preintegrate;
  int aov_count, aov_vis, aov_z; /* AOV floats per view pixel, offsets (-1: not asked; 0 count:
                                    none) */
  uint seed_lo, seed_hi;
  double zf, zb, window_max;
} shade_args;

/* The program's view of its buffers for the shared kernel source (gpu/kernel/lang.h): not a
 * struct (PoCL keeps a private struct of pointers in memory, work-item by work-item: the shading
 * took about 1.5x as long), but the buffers themselves as the shared functions' first
 * parameters, one list per header included. */
#define ICS_SLAB_WORD(light, slab, block, i) slab_word(seed_lo, seed_hi, light, slab, block, i)
#define ICS_VIEW_PARAM uint seed_lo, uint seed_hi,
#define ICS_VIEW_ARG seed_lo, seed_hi,
#include "kernel/choice.h"
#undef ICS_VIEW_PARAM
#undef ICS_VIEW_ARG

/* a perspective step's classes: the source planes (at light l's base) and the taps */
#define ICS_VIEW_PARAM __global const float *S, buf_layout B, __global const int *ix, \
                       __global const int *iy, __global const float *wt,
#define ICS_VIEW_ARG S, B, ix, iy, wt,
#define ICS_TAP_X(m) ix[m]
#define ICS_TAP_Y(m) iy[m]
#define ICS_TAP_W(m) wt[m]
#define ICS_SRC(c, i) S[(c) * B.plane + (i)]
#define ICS_AT(x, y) AT(B, x, y)
#define ICS_BW B.w
#define ICS_BH B.h
#include "kernel/class_sum.h"
#undef ICS_VIEW_PARAM
#undef ICS_VIEW_ARG

/* the shading: ics_shade's buffers, by the names of its parameters */
#define ICS_VIEW_PARAM const shade_args *A, __global float *dst, __global const double *obj,     \
                       __global const double *tt, __global const double *cam,                   \
                       __global const double *lpath, __global const double *lmu,                \
                       __global const double *window, __global const uchar *perm,               \
                       __global const float *grids, __global const int *vol_obj,                \
                       __global const float *fz, __global const uint *fcode,                    \
                       __global const float2 *fgrad, __global const uchar *fspan,               \
                       __global const double *lcol, __global float *aov, __global uchar *aov_seen,
#define ICS_VIEW_ARG A, dst, obj, tt, cam, lpath, lmu, window, perm, grids, vol_obj, fz, fcode, \
                     fgrad, fspan, lcol, aov, aov_seen,
#define ICS_OBJ(ob, f) obj[ICS_DEV_OBJ_STRIDE * (ob) + (f)]
#define ICS_TT(i) tt[i]
#define ICS_PERM(i) perm[i]
#define ICS_GRID(i) grids[i]
#define ICS_CAM(f) cam[f]
#define ICS_VOLOBJ(i) vol_obj[i]
#define ICS_LPATH(l) lpath[l]
#define ICS_LMU(i) lmu[i]
#define ICS_WINDOW(l) window[l]
#define ICS_DST(l, c, q) dst[((l) * A->nch + (c)) * A->B.plane + (q)]
#define ICS_ARG(name) (A->name)
#define ICS_FZ(f) fz[f]
#define ICS_FCODE(f) fcode[f]
#define ICS_FGRAD(f) fgrad[f]
#define ICS_FSPAN(f) fspan[f]
#define ICS_LCOL(i) lcol[i]
#define ICS_AOV(pi, i) aov[(size_t)(pi) * A->aov_count + (i)]
#define ICS_AOV_SEEN(pi) aov_seen[pi]
#define JITTER_STREAM 0x6a69747400000000UL /* "jitt" (backend_cpu.c) */
#define ICS_JITTER(k, p) uniform_at(A->seed_lo, A->seed_hi, JITTER_STREAM | (ulong)(k), (ulong)(p))
#include "kernel/shade.h"

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
          acc += wt[j] * S[AT(B, ics_k_clampi(x + ix[j], B.w - 1), ics_k_clampi(y + iy[j], B.h - 1))];
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
  int bits = ics_k_choice_bits((uint)entries);
  uint n = (uint)ICS_CHOICE_CHUNKS(bits), b = (uint)get_global_id(0);
  uint first = 64u * n * (b / 16u) + b % 16u;
  if (first >= (uint)npx) return;
  uint c0 = b, c1 = slab, c2 = light, c3 = 0x736c6162u, k0 = seed_lo, k1 = seed_hi;
  PHILOX(c0, c1, c2, c3, k0, k1)
  uint words[4] = {c0, c1, c2, c3};
  for (uint c = 0; c < n; c++)
    for (int i = 0; i < 4; i++) {
      uint px = first + 64u * c + 16u * (uint)i;
      if (px < (uint)npx) ent[px] = ics_k_word_choice(words[i], (uint)entries, bits, c);
    }
}
__kernel void ics_entries_run(__global uint *ent, int w, int h, int entries, uint seed_lo,
                              uint seed_hi, uint light, uint slab, int phase) {
  int k = (int)get_global_id(0), y = (int)get_global_id(1);
  int xa = max(16 * k - 16 + phase, 0), xb = min(16 * k + phase, w);
  if (y >= h || xa >= xb) return;
  uint e = ics_k_pixel_choice(seed_lo, seed_hi, light, slab, (uint)y * (uint)(w + 32) + 16u * (uint)k,
                              (uint)entries, 0, 1u);
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
      int xa = ics_k_clampi(x0, B.w - 1), xb = ics_k_clampi(x0 + 1, B.w - 1);
      int ya = ics_k_clampi(y0, B.h - 1), yb = ics_k_clampi(y0 + 1, B.h - 1);
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
    float a00 = ics_k_class_sum(src, B, ix, iy, wt, c, ntaps, Q, k0, k1, nx, ny);
    float a10 = ics_k_class_sum(src, B, ix, iy, wt, c, ntaps, Q, k0 + 1, k1, nx, ny);
    float a01 = ics_k_class_sum(src, B, ix, iy, wt, c, ntaps, Q, k0, k1 + 1, nx, ny);
    float a11 = ics_k_class_sum(src, B, ix, iy, wt, c, ntaps, Q, k0 + 1, k1 + 1, nx, ny);
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

/* ---- shading (the steps: gpu/kernel/shade.h) ------------------------------------------- */

/* Per buffer pixel, slab A.k: ics_k_shade_pixel (gpu/kernel/shade.h) where the pixel has work at
 * this slab, then the clamp of signed kernels. Fragments: depth, code (object | bias << 12 | slab << 16), depth gradient
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
  int p = bj * A.B.w + bi, q = AT(A.B, bi, bj), nch = A.nch;
  uint end = offset[p + 1], cursors[2] = {cursor[p], acursor[p]};
  ulong mask = A.nvol ? inside[p] : 0;
  int has = cursors[0] < end && ics_k_frag_slab(fcode[cursors[0]]) == k;
  int occl = cursors[1] < end && ics_k_frag_slab(fcode[cursors[1]]) <= k;
  if (has || mask || occl) {
    int ii = bi - A.pad_l, jj = bj - A.pad_t;
    int inview = ii >= 0 && ii < A.W && jj >= 0 && jj < A.H, pi = jj * A.W + ii;
    float C[4] = {0, 0, 0, 1};
    if (inview) vstore4(vload4(pi, img), 0, C);
    mask = ics_k_shade_pixel(&A, dst, obj, tt, cam, lpath, lmu, window, perm, grids, vol_obj, fz,
                             fcode, fgrad, fspan, lcol, aov, aov_seen, p, q, bi, bj, end, cursors,
                             mask, inview, pi, C);
    cursor[p] = cursors[0], acursor[p] = cursors[1];
    if (A.nvol) inside[p] = mask;
    if (inview) vstore4(vload4(0, C), pi, img);
  }
  for (int l = 0; l < A.nlights; l++)
    if (signed_l[l])
      for (int c = 0; c < nch; c++) {
        float v = dst[(l * nch + c) * A.B.plane + q];
        dst[(l * nch + c) * A.B.plane + q] = v < 0 ? 0 : v > 1 ? 1 : v;
      }
}
