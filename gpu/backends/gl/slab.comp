#version 450
/* slab.comp — the slab renderer's steps per slab as GLSL 4.50 compute shaders (docs/backend_gl.md),
 * the same arithmetic as the cpu backend (gpu/backends/cpu/propagate.c, gpu/backends/cpu/backend_cpu.c) and the cl
 * backend (gpu/backends/cl/slab.cl). One file, one program per entry point: the host compiles it once per
 * ICS_K_* name, defined on the line after #version (glslangValidator -DICS_K_... checks each), and
 * the steps once more with ICS_CLAMPED (a tap reaches past the apron: every read clamps), and
 * each of those with ICS_TAPS_STORAGE (more taps than a uniform block holds).
 *
 *   ICS_K_PROP_STENCIL / _TABLE / _CLASSES  one light buffer's slab step with the host's
 *        prepared taps: integer taps, a table of bilinear tap sets (each pixel takes the set the
 *        counter RNG picks: Philox-4x32-10 as ics_slab_choice), or perspective classes;
 *   ICS_K_ENTRIES_PIXEL / _RUN   those tap-set choices, per pixel or per run of 16;
 *   ICS_K_SHADE_SELECT, _COUNT, ICS_K_SHADE   the buffer pixels with work at this slab, listed,
 *        then per listed pixel: the occlusions due at this slab, the colours of the surfaces and
 *        volume pieces in this slab lit by the light arriving here; the clamp of signed kernels;
 *   ICS_K_APRON_SIDES / _ENDS    the apron of replicated edge pixels, refreshed after a slab.
 *
 * The per-pixel functions are the shared kernel source (gpu/kernel: choice.h, class_sum.h,
 * shade.h and what they include), the text slab.cl compiles too (and the host: choice.h,
 * camera.h, noise.h and transfer.h in the plan and the cpu backend, the rest in
 * test_kernel_c); this file holds the entry points, Philox in GLSL and the accessors over its buffers.
 * Buffers are SSBOs (the steps read them as buffer textures) with the CPU's layout (propagate.h): light l, channel c at planes l nch + c,
 * pixel (x, y) at origin + y stride + x. Doubles where the CPU computes in double
 * (ARB_gpu_shader_fp64, core since 4.0); exp and pow have no double form in GLSL, so those two
 * run in float (the largest source of the difference to the cpu backend besides the FMAs that
 * `precise` rules out in the steps). No 64-bit integers: the inside masks are uvec2. */
#extension GL_ARB_gpu_shader_fp64 : enable
#define ICS_GLSL 1
/* the shared kernel source (gpu/kernel; cmake/embed_text.cmake expands the includes) */
#include "kernel/lang.h"
#include "kernel/device_layout.h"

#define PHILOX_M0 0xD2511F53u
#define PHILOX_M1 0xCD9E8D57u
#define PHILOX_W0 0x9E3779B9u
#define PHILOX_W1 0xBB67AE85u

/* Philox-4x32-10 (libicshadow/src/rng.c) of counter c under key k */
uvec4 philox(uvec4 c, uvec2 k) {
  for (int r = 0; r < 10; r++) {
    uint hi0, lo0, hi1, lo1;
    umulExtended(PHILOX_M0, c.x, hi0, lo0);
    umulExtended(PHILOX_M1, c.z, hi1, lo1);
    c = uvec4(hi1 ^ c.y ^ k.x, lo1, hi0 ^ c.w ^ k.y, lo0);
    k += uvec2(PHILOX_W0, PHILOX_W1);
  }
  return c;
}

/* the buffer layout and the seed (every program sets what it uses) */
uniform int bw, bh, stride, plane, origin, nch;
uniform uint seed_lo, seed_hi;
#define AT(x, y) (origin + (y) * stride + (x))
#define ICS_VIEW_PARAM
#define ICS_VIEW_ARG
/* word i of the block at counter (block, slab, light, "slab") */
#define ICS_SLAB_WORD(light, slab, block, i) philox(uvec4(block, slab, light, 0x736c6162u), uvec2(seed_lo, seed_hi))[i]
#include "kernel/choice.h"

/* ---- the slab step ------------------------------------------------------------------------ */
#if defined(ICS_K_PROP_STENCIL) || defined(ICS_K_PROP_TABLE) || defined(ICS_K_PROP_CLASSES)
layout(local_size_x = 16, local_size_y = 8) in;
/* the taps (ix, iy, off; w, fx, fy) in a uniform block: llvmpipe loads a uniform index once for
 * all invocations, a storage buffer's per invocation. ICS_MAX_TAPS comes from the host (the
 * driver's GL_MAX_UNIFORM_BLOCK_SIZE / 32). */
#ifndef ICS_MAX_TAPS
#define ICS_MAX_TAPS 512
#endif
struct tap { ivec4 i; vec4 f; };
/* the buffers read, as a buffer texture over the same storage: llvmpipe fetches texels 2.3x as
 * fast as shader-storage loads (24 reads per pixel: 25 against 58 ns) */
layout(binding = 0) uniform samplerBuffer src;
layout(std430, binding = 1) writeonly buffer Dst { float dst[]; };
#ifdef ICS_TAPS_STORAGE /* more than a uniform block holds */
layout(std430, binding = 2) readonly buffer Taps { tap taps[]; };
#else
layout(std140, binding = 0) uniform Taps { tap taps[ICS_MAX_TAPS]; };
#endif
layout(std430, binding = 3) readonly buffer Ent { uint ent[]; };
uniform int base, ntaps; /* light l's planes start at base */
uniform int ofs_x, ofs_y; /* the dispatch's first pixel: the light's active region */
uniform int entries, Q;
uniform double s, cx, cy;

float S_at(int c, int i) { return texelFetch(src, base + c * plane + i).r; }

/* the perspective classes' sums: gpu/kernel/class_sum.h over the taps and the source */
#define ICS_TAP_X(m) taps[m].i.x
#define ICS_TAP_Y(m) taps[m].i.y
#define ICS_TAP_W(m) taps[m].f.x
#define ICS_SRC(c, i) S_at(c, i)
#define ICS_AT(x, y) AT(x, y)
#define ICS_BW bw
#define ICS_BH bh
#include "kernel/class_sum.h"

void main() {
  int x = int(gl_GlobalInvocationID.x) + ofs_x, y = int(gl_GlobalInvocationID.y) + ofs_y;
  if (x >= bw || y >= bh) return;
  int p = AT(x, y);
#ifdef ICS_K_PROP_STENCIL
  for (int c = 0; c < nch; c++) {
    precise float acc = 0;
#ifdef ICS_CLAMPED
    for (int j = 0; j < ntaps; j++)
      acc += taps[j].f.x * S_at(c, AT(ics_k_clampi(x + taps[j].i.x, bw - 1), ics_k_clampi(y + taps[j].i.y, bh - 1)));
#else
    for (int j = 0; j < ntaps; j++) acc += taps[j].f.x * S_at(c, p + taps[j].i.z);
#endif
    dst[base + c * plane + p] = acc;
  }
#elif defined(ICS_K_PROP_TABLE)
  int e0 = int(ent[y * bw + x]) * ntaps;
  for (int c = 0; c < nch; c++) {
    precise float acc = 0;
    for (int j = e0; j < e0 + ntaps; j++) {
      float a, b, cc, d;
#ifdef ICS_CLAMPED
      int x0 = x + taps[j].i.x, y0 = y + taps[j].i.y;
      int xa = ics_k_clampi(x0, bw - 1), xb = ics_k_clampi(x0 + 1, bw - 1);
      int ya = ics_k_clampi(y0, bh - 1), yb = ics_k_clampi(y0 + 1, bh - 1);
      a = S_at(c, AT(xa, ya)), b = S_at(c, AT(xb, ya)), cc = S_at(c, AT(xa, yb)), d = S_at(c, AT(xb, yb));
#else
      int r0 = p + taps[j].i.z;
      a = S_at(c, r0), b = S_at(c, r0 + 1), cc = S_at(c, r0 + stride), d = S_at(c, r0 + stride + 1);
#endif
      precise float top = a + taps[j].f.y * (b - a), bot = cc + taps[j].f.y * (d - cc);
      acc += taps[j].f.x * (top + taps[j].f.z * (bot - top));
    }
    dst[base + c * plane + p] = acc;
  }
#else
  /* magnification s about (cx, cy); the four classes around the read offset's fraction */
  double Dx = (s - 1) * (x - cx), Dy = (s - 1) * (y - cy);
  double fX = floor(Dx), tX = (Dx - fX) * Q, kX = floor(tX);
  double fY = floor(Dy), tY = (Dy - fY) * Q, kY = floor(tY);
  int nx = x + int(fX), ny = y + int(fY), k0 = int(kX), k1 = int(kY);
  float r0 = float(tX - kX), r1 = float(tY - kY);
  for (int c = 0; c < nch; c++) {
    float a00 = ics_k_class_sum(c, ntaps, Q, k0, k1, nx, ny);
    float a10 = ics_k_class_sum(c, ntaps, Q, k0 + 1, k1, nx, ny);
    float a01 = ics_k_class_sum(c, ntaps, Q, k0, k1 + 1, nx, ny);
    float a11 = ics_k_class_sum(c, ntaps, Q, k0 + 1, k1 + 1, nx, ny);
    precise float top = a00 + r0 * (a10 - a00), bot = a01 + r0 * (a11 - a01);
    precise float v = top + r1 * (bot - top);
    dst[base + c * plane + p] = v;
  }
#endif
}
#endif

/* ---- the tap-set choices of a table step (ics_prop_entries_row, ics_prop_run_choice) ------- */
#if defined(ICS_K_ENTRIES_PIXEL) || defined(ICS_K_ENTRIES_RUN)
layout(std430, binding = 3) writeonly buffer Ent { uint ent[]; };
uniform int entries, npx, phase;
uniform uint light, slab;
#ifdef ICS_K_ENTRIES_PIXEL
/* one invocation per Philox block b: its four words choose pixels 64 n (b / 16) + b % 16 +
 * 64 c + 16 i (word i, chunk c; ics_slab_pixel_choice) */
layout(local_size_x = 64) in;
void main() {
  int bits = ics_k_choice_bits(uint(entries));
  uint n = uint(ICS_CHOICE_CHUNKS(bits)), b = gl_GlobalInvocationID.x;
  uint first = 64u * n * (b / 16u) + b % 16u;
  if (first >= uint(npx)) return;
  uvec4 w = philox(uvec4(b, slab, light, 0x736c6162u), uvec2(seed_lo, seed_hi));
  for (uint c = 0u; c < n; c++)
    for (int i = 0; i < 4; i++) {
      uint px = first + 64u * c + 16u * uint(i);
      if (px < uint(npx)) ent[px] = ics_k_word_choice(w[i], uint(entries), bits, c);
    }
}
#else
/* one invocation per run k of row y: the pixels x with (x + 16 - phase) / 16 = k */
layout(local_size_x = 16, local_size_y = 8) in;
void main() {
  int k = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  int xa = max(16 * k - 16 + phase, 0), xb = min(16 * k + phase, bw);
  if (y >= bh || xa >= xb) return;
  uint e = ics_k_pixel_choice(light, slab, uint(y) * uint(bw + 32) + 16u * uint(k), uint(entries), 0, 1u);
  for (int x = xa; x < xb; x++) ent[y * bw + x] = e;
}
#endif
#endif

/* ---- the apron of every plane (ics_prop_apron): the sides of each row, then whole rows ----- */
#if defined(ICS_K_APRON_SIDES) || defined(ICS_K_APRON_ENDS)
layout(local_size_x = 64) in;
layout(std430, binding = 1) buffer Dst { float dst[]; };
uniform int A, nplanes;
void main() {
  int c = int(gl_GlobalInvocationID.z);
#ifdef ICS_K_APRON_SIDES
  int a = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (a >= 2 * A || y >= bh) return;
  int row = c * plane + AT(0, y);
  if (a < A) dst[row - 1 - a] = dst[row];
  else dst[row + bw + (a - A)] = dst[row + bw - 1];
#else
  int x = int(gl_GlobalInvocationID.x) - A, r = int(gl_GlobalInvocationID.y);
  if (x >= stride - A || r >= 2 * A) return;
  if (r < A) dst[c * plane + AT(x, -1 - r)] = dst[c * plane + AT(x, 0)];
  else dst[c * plane + AT(x, bh + (r - A))] = dst[c * plane + AT(x, bh - 1)];
#endif
}
#endif

/* ---- shading ------------------------------------------------------------------------------ */
/* Compacted: ICS_K_SHADE_SELECT lists the buffer pixels with work at this slab, in two lists:
 * those in or entering a volume (list 0) and those with only surfaces or occlusion windows
 * (list 1); it clamps the others' signed buffers. ICS_K_SHADE_COUNT turns each list's length
 * into an indirect dispatch, and ICS_K_SHADE shades list 0, compiled with ICS_SURFACES_ONLY
 * list 1. A GPU skips the code that no invocation of a group takes; llvmpipe runs every branch
 * and every loop body at least once under a mask, so the full shading costs about 1 us per
 * invocation there whatever it does (measured: 8.8 ns for an empty program, 76 ns without the
 * volume code, 960 ns with it). */
#if defined(ICS_K_SHADE_SELECT) || defined(ICS_K_SHADE_COUNT) || defined(ICS_K_SHADE)
/* per list i: the indirect dispatch (groups x, y, z) at hdr[5 i], its length at hdr[5 i + 3],
 * the append counter at hdr[5 i + 4]; list i's pixels at work[i npx ...] */
layout(std430, binding = 14) buffer Work { uint hdr[10]; uint work[]; };
uniform int npx;
#endif
#ifdef ICS_K_SHADE_COUNT
layout(local_size_x = 1) in;
void main() {
  for (int i = 0; i < 2; i++) {
    uint n = hdr[5 * i + 4];
    hdr[5 * i] = min((n + 63u) / 64u, 65535u), hdr[5 * i + 1] = 1u, hdr[5 * i + 2] = 1u;
    hdr[5 * i + 3] = n;
    hdr[5 * i + 4] = 0u;
  }
}
#endif
#if defined(ICS_K_SHADE_SELECT) || defined(ICS_K_SHADE)
#ifdef ICS_K_SHADE
layout(local_size_x = 64) in;
#else
layout(local_size_x = 16, local_size_y = 8) in;
#endif
layout(std430, binding = 1) buffer Dst { float dst[]; };
layout(std430, binding = 2) readonly buffer Offsets { uint offset[]; };
layout(std430, binding = 3) readonly buffer Fz { float fz[]; };
layout(std430, binding = 4) readonly buffer Fcode { uint fcode[]; };
layout(std430, binding = 5) readonly buffer Fgrad { vec2 fgrad[]; };
layout(std430, binding = 6) readonly buffer Fspan { uint fspan4[]; }; /* bytes, 4 per word */
layout(std430, binding = 7) buffer Pix { uvec4 pix[]; }; /* cursor, occlusion cursor, inside mask */
layout(std430, binding = 8) readonly buffer Obj { double obj[]; };
layout(std430, binding = 9) readonly buffer SceneD { double sd[]; }; /* transfer rows, camera,
                                                            lights, this slab's windows */
layout(std430, binding = 10) readonly buffer Perm { uint perm4[]; }; /* bytes, 512 per object */
layout(std430, binding = 11) readonly buffer Grids { float grids[]; };
layout(std430, binding = 12) readonly buffer Ints { int ints[]; }; /* vol_obj, then signed_l */
layout(std430, binding = 13) buffer Out { float outv[]; }; /* image RGBA, AOVs, AOV seen flags */

uniform int nlights, k, nvol, W, H, pad_l, pad_t, preintegrate;
uniform int aov_count, aov_vis, aov_z, off_aov, off_seen;
uniform int off_cam, off_lcol, off_lmu, off_lpath, off_window, off_signed;
uniform double zf, zb, window_max;

uint fspan(uint f) { return fspan4[f >> 2] >> (8u * (f & 3u)) & 255u; }
int perm(int i) { return int(perm4[i >> 2] >> (8 * (i & 3)) & 255u); }

/* ics_rng_uniform_at(seed, "jitt" << 32 | k, p): 53 bits of word p of that stream */
double jitter_at(uint slab_k, uint p) {
  uvec4 w = philox(uvec4(p >> 1, 0u, slab_k, 0x6a697474u), uvec2(seed_lo, seed_hi));
  uvec2 x = (p & 1u) != 0u ? w.zw : w.xy; /* lo, hi */
  return double(x.y) * ldexp(1.0lf, -32) + double(x.x >> 11) * ldexp(1.0lf, -53);
}

/* the shading steps: gpu/kernel/shade.h over the buffers above (records: device_layout.h) */
#define ICS_OBJ(ob, f) obj[ICS_DEV_OBJ_STRIDE * (ob) + (f)]
#define ICS_TT(i) sd[i]
#define ICS_PERM(i) perm(i)
#define ICS_GRID(i) grids[i]
#define ICS_CAM(f) sd[off_cam + (f)]
#define ICS_VOLOBJ(i) ints[i]
#define ICS_LPATH(l) sd[off_lpath + (l)]
#define ICS_LMU(i) sd[off_lmu + (i)]
#define ICS_WINDOW(l) sd[off_window + (l)]
#define ICS_DST(l, c, q) dst[((l) * nch + (c)) * plane + (q)]
#define ICS_ARG(name) name
#define ICS_JITTER(k, p) jitter_at(uint(k), uint(p))
#define ICS_FZ(f) fz[f]
#define ICS_FCODE(f) fcode[f]
#define ICS_FGRAD(f) fgrad[f]
#define ICS_FSPAN(f) fspan(f)
#define ICS_LCOL(i) sd[off_lcol + (i)]
#define ICS_AOV(pi, i) outv[off_aov + (pi) * aov_count + (i)]
#define ICS_AOV_SEEN(pi) outv[off_seen + (pi)]
#include "kernel/shade.h"

/* the clamp of signed kernels, after the shading */
void clamp_signed(int q) {
  for (int l = 0; l < nlights; l++)
    if (ints[off_signed + l] != 0)
      for (int c = 0; c < nch; c++) {
        float v = ICS_DST(l, c, q);
        ICS_DST(l, c, q) = v < 0 ? 0 : v > 1 ? 1 : v;
      }
}

#ifdef ICS_K_SHADE_SELECT
void main() {
  int bi = int(gl_GlobalInvocationID.x), bj = int(gl_GlobalInvocationID.y);
  if (bi >= bw || bj >= bh) return;
  uint p = uint(bj * bw + bi);
  uvec4 st = pix[p];
  uint cur = st.x, acur = st.y, end = offset[p + 1u];
  bool has = cur < end && ics_k_frag_slab(fcode[cur]) == k;
  bool occl = acur < end && ics_k_frag_slab(fcode[acur]) <= k;
  bool vol = nvol != 0 && ics_mask_any(st.zw);
  for (uint f = cur; nvol != 0 && !vol && f < end && ics_k_frag_slab(fcode[f]) == k; f++)
    vol = ICS_OBJ(ics_k_frag_obj(fcode[f]), O_VOLBIT) >= 0;
  int list = vol ? 0 : 1;
  if (vol || has || occl) work[uint(list * npx) + atomicAdd(hdr[5 * list + 4], 1u)] = p;
  else clamp_signed(AT(bi, bj));
}
#else
/* per listed buffer pixel, slab k: ics_k_shade_pixel (gpu/kernel/shade.h), then the clamp of
 * signed kernels */
#ifdef ICS_SURFACES_ONLY
#define LIST 1
#else
#define LIST 0
#endif
void shade_pixel(uint p) {
  int bi = int(p % uint(bw)), bj = int(p / uint(bw));
  int q = AT(bi, bj);
  uvec4 st = pix[p];
  uint cursors[2] = uint[2](st.x, st.y);
  uvec2 mask = nvol != 0 ? st.zw : uvec2(0u);
  int ii = bi - pad_l, jj = bj - pad_t, pi = jj * W + ii;
  bool inview = ii >= 0 && ii < W && jj >= 0 && jj < H;
  float C[4] = float[4](0, 0, 0, 1);
  if (inview)
    for (int c = 0; c < 4; c++) C[c] = outv[4 * pi + c];
  mask = ics_k_shade_pixel(int(p), q, bi, bj, offset[p + 1u], cursors, mask, inview ? 1 : 0, pi, C);
  pix[p] = uvec4(cursors[0], cursors[1], nvol != 0 ? mask : st.zw);
  if (inview)
    for (int c = 0; c < 4; c++) outv[4 * pi + c] = C[c];
  clamp_signed(q);
}

/* the list in a grid-stride loop: ICS_K_SHADE_COUNT caps the groups at 65535 (the smallest
 * GL_MAX_COMPUTE_WORK_GROUP_COUNT) */
void main() {
  for (uint w = gl_GlobalInvocationID.x; w < hdr[5 * LIST + 3]; w += gl_NumWorkGroups.x * 64u)
    shade_pixel(work[uint(LIST * npx) + w]);
}
#endif
#endif
