/* propagate_vec.h — the vector loops of the CPU slab step, written once over GCC/Clang vector
 * extensions and compiled once per instruction set (propagate_sse2.c, propagate_avx2.c,
 * propagate_avx512.c, propagate_neon.c: each defines ICS_VEC_W, the lanes of a float vector,
 * and ICS_VEC_FN, the name of its entry point, and is compiled with its target's flags; the
 * processor's paths are chosen at run time, simd_path.h). Preconditions: s = 1 and the taps'
 * reach within the buffers' apron (no read is clamped), or a perspective step (pt->classes),
 * whose lanes reading beyond the apron take the clamped portable pixel.
 *
 * Stencils (one tap set): W pixels per vector, one unaligned load and one multiply-add per tap,
 * four independent sums added in a fixed order. Few tap sets (entries <= ICS_PROP_CANDIDATES_MAX,
 * e.g. the default 2 rotations per slab): every set evaluated for a vector of pixels in blocks of
 * ICS_PROP_ROW_BLOCK rows with unaligned loads, a buffer row's horizontal interpolation shared
 * by the two output rows that read it, each pixel keeping its own set's result (a masked blend).
 * Runs of 16 pixels sharing a set: each run as vectors of its own set, the partial runs at the
 * row's ends evaluated over the row's first or last 16 pixels. Many tap sets (a per-pixel
 * table): per lane loads of the taps and corners. Tap-set choices come from a W-lane
 * Philox-4x32-10 (the same words as ics_slab_entry_block), packed as ics_slab_pixel_choice.
 * Perspective steps: the magnification classes (classes_row, below).
 *
 * Arithmetic: a * b + c written once (madd, and madd1 for one pixel: pixel_fma and class_pixel
 * at the spans' ends), with the target's fused multiply-add where it has one (AVX2 + FMA,
 * AVX-512, NEON) and a multiply and an add on SSE2. So the last bits depend on the path (and can
 * differ from the portable loops'), never on the thread count, the span or the build type. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "propagate_simd.h"
#include "slab_choice.h"

#if defined(__x86_64__)
#include <immintrin.h>
#elif defined(__ARM_NEON)
#include <arm_neon.h>
#endif

#if !defined(ICS_VEC_W) || !defined(ICS_VEC_FN)
#error "define ICS_VEC_W and ICS_VEC_FN before including propagate_vec.h"
#endif

#define W ICS_VEC_W
typedef float vf __attribute__((vector_size(4 * W)));
typedef int32_t vi __attribute__((vector_size(4 * W)));
typedef uint32_t vu __attribute__((vector_size(4 * W)));
typedef uint64_t vh __attribute__((vector_size(4 * W))); /* the same bytes as W / 2 lanes */

static inline vf loadf(const float *p) {
  vf v;
  memcpy(&v, p, sizeof v);
  return v;
}
static inline vu loadu(const uint32_t *p) {
  vu v;
  memcpy(&v, p, sizeof v);
  return v;
}
static inline void storef(float *p, vf v) { memcpy(p, &v, sizeof v); }
static inline void storeu(uint32_t *p, vu v) { memcpy(p, &v, sizeof v); }
static inline vf splatf(float x) { return (vf){0} + x; }
static inline vu splatu(uint32_t x) { return (vu){0} + x; }
static inline vu iota(void) {
  vu v;
  for (int i = 0; i < W; i++) v[i] = (uint32_t)i;
  return v;
}
/* a * b + c, fused where the target has FMA: spelled with the target's fused multiply-add (GCC
 * contracts a * b + c only from -O2 on, and not every scalar accumulation chain even there), so
 * the vector lanes and the one-pixel formula (madd1) round alike in every build */
static inline vf madd(vf a, vf b, vf c) {
#if defined(__x86_64__) && defined(__FMA__) && W == 16
  return (vf)_mm512_fmadd_ps((__m512)a, (__m512)b, (__m512)c);
#elif defined(__x86_64__) && defined(__FMA__) && W == 8
  return (vf)_mm256_fmadd_ps((__m256)a, (__m256)b, (__m256)c);
#elif defined(__x86_64__) && defined(__FMA__) && W == 4
  return (vf)_mm_fmadd_ps((__m128)a, (__m128)b, (__m128)c);
#elif defined(__ARM_FEATURE_FMA) && W == 4
  return (vf)vfmaq_f32((float32x4_t)c, (float32x4_t)a, (float32x4_t)b);
#else
  return a * b + c;
#endif
}
static inline float madd1(float a, float b, float c) {
#if defined(__FMA__) || defined(__ARM_FEATURE_FMA)
  return __builtin_fmaf(a, b, c);
#else
  return a * b + c;
#endif
}
/* lanes of `a` where mask (all ones or zero per lane) is set, else `b` */
static inline vf blend(vi mask, vf a, vf b) { return (vf)(((vi)a & mask) | ((vi)b & ~mask)); }

/* 32 x 32 -> 64 bit products of W lanes: the high and low halves. The one place the source
 * names an instruction set: vector extensions have no widening multiply, and written as a
 * 64-bit product the compilers emit a full 64 x 64 multiply (three multiplies and the shifts
 * and adds, or vpmullq) where one pmuludq per pair of lanes does. */
#if defined(__x86_64__)
/* the products of the even 32-bit lanes (the low halves of each 64-bit pair) with m */
static inline vh mul_even(vh a, uint32_t m) {
#if W == 16
  return (vh)_mm512_mul_epu32((__m512i)a, _mm512_set1_epi64((long long)m));
#elif W == 8
  return (vh)_mm256_mul_epu32((__m256i)a, _mm256_set1_epi64x((long long)m));
#else
  return (vh)_mm_mul_epu32((__m128i)a, _mm_set1_epi64x((long long)m));
#endif
}
static inline void mul32(vu a, uint32_t m, vu *lo, vu *hi) {
  const vh low = (vh){0} + 0xffffffffu;
  vh ev = mul_even((vh)a, m), od = mul_even((vh)a >> 32, m);
  *lo = (vu)((ev & low) | (od << 32));
  *hi = (vu)((ev >> 32) | (od & ~low));
}
#elif defined(__ARM_NEON) && W == 4
static inline void mul32(vu a, uint32_t m, vu *lo, vu *hi) {
  uint32x4_t va = (uint32x4_t)a;
  uint32x2_t vm = vdup_n_u32(m);
  uint64x2_t p0 = vmull_u32(vget_low_u32(va), vm), p1 = vmull_u32(vget_high_u32(va), vm);
  uint32x4x2_t z = vuzpq_u32(vreinterpretq_u32_u64(p0), vreinterpretq_u32_u64(p1));
  *lo = (vu)z.val[0];
  *hi = (vu)z.val[1];
}
#else
typedef uint64_t vu64 __attribute__((vector_size(8 * W)));
static inline void mul32(vu a, uint32_t m, vu *lo, vu *hi) {
  vu64 p = __builtin_convertvector(a, vu64) * (uint64_t)m;
  *lo = __builtin_convertvector(p, vu);
  *hi = __builtin_convertvector(p >> 32, vu);
}
#endif

/* Philox-4x32-10 on W counters (rng.c's rounds, lane by lane) */
static void philox(vu c[4], uint64_t seed) {
  uint32_t k0 = (uint32_t)seed, k1 = (uint32_t)(seed >> 32);
  for (int r = 0; r < 10; r++) {
    if (r > 0) k0 += 0x9E3779B9u, k1 += 0xBB67AE85u;
    vu lo0, hi0, lo1, hi1;
    mul32(c[0], 0xD2511F53u, &lo0, &hi0);
    mul32(c[2], 0xCD9E8D57u, &lo1, &hi1);
    vu n0 = hi1 ^ c[1] ^ k0, n2 = hi0 ^ c[3] ^ k1;
    c[0] = n0, c[1] = lo1, c[2] = n2, c[3] = lo0;
  }
}

/* the four words of the W blocks `blocks` (ics_slab_entry_block): words[k] lane i is word k of
 * block i */
static void block_words(const ics_prop_taps *pt, vu blocks, vu words[4]) {
  words[0] = blocks, words[1] = splatu(pt->slab), words[2] = splatu(pt->light);
  words[3] = splatu(0x736c6162u);
  philox(words, pt->seed);
}

/* the words scaled to a choice in 0 .. entries - 1 (ics_slab_choice) */
static inline vu scaled(vu word, uint32_t k) {
  vu lo, hi;
  mul32(word, k, &lo, &hi);
  return hi;
}

/* the choices of pixels [x0, x1) of row y (ent[x], nothing else written), packed as
 * ics_slab_pixel_choice: block 16 g + i holds the pixels span g + 64 c + 16 k + i (chunk c of
 * word k), span = 64 n; only the chunks the row's pixels take are unpacked */
static void entries_row(const ics_prop_taps *pt, int w, int y, int x0, int x1, uint32_t *ent) {
  uint32_t k = (uint32_t)pt->entries, span = 64 * ics_slab_choice_chunks(k);
  int b = ics_slab_choice_bits(k);
  uint32_t row = (uint32_t)((size_t)y * w), first = row + (uint32_t)x0, last = row + (uint32_t)x1 - 1;
  for (uint32_t g = first / span; g <= last / span; g++) {
    uint32_t p0 = span * g, lo = p0 > first ? p0 : first;
    uint32_t hi = p0 + span - 1 < last ? p0 + span - 1 : last;
    vu words[16 / W][4];
    for (int h = 0; h < 16; h += W) block_words(pt, splatu(16 * g + (uint32_t)h) + iota(), words[h / W]);
    for (uint32_t c = (lo - p0) / 64; c <= (hi - p0) / 64; c++) {
      uint32_t q0 = p0 + 64 * c, tmp[64];
      uint32_t *dst = q0 >= first && q0 + 63 <= last ? ent + (q0 - row) : tmp;
      for (int h = 0; h < 16; h += W)
        for (int q = 0; q < 4; q++) {
          vu v = words[h / W][q];
          storeu(dst + 16 * q + h, b ? (v >> (32 - b * (int)(c + 1))) & (k - 1) : scaled(v, k));
        }
      if (dst == tmp) {
        uint32_t a = q0 > lo ? q0 : lo, z = q0 + 63 < hi ? q0 + 63 : hi;
        memcpy(ent + (a - row), tmp + (a - q0), sizeof(uint32_t) * (z - a + 1));
      }
    }
  }
}

/* the choices of runs m0 .. m0 + nruns - 1 of row y (run m starts at x = phase - 16 + 16 m) into
 * out[0 ..]: run m is the counter Y + 16 m, Y = y (w + 32) (ics_prop_run_choice), whose word is
 * word G % 4 of block (G / 4) 16 + Y % 16 with G = Y / 16 + m: W consecutive blocks give 4 W runs */
static void run_choices(const ics_prop_taps *pt, int w, int y, int m0, int nruns, uint32_t *out) {
  uint32_t Y = (uint32_t)((size_t)y * (size_t)(w + 32)), c0 = Y % 16, G0 = Y / 16 + (uint32_t)m0;
  for (uint32_t q0 = G0 / 4; q0 <= (G0 + (uint32_t)nruns - 1) / 4; q0 += W) {
    vu words[4];
    block_words(pt, splatu(16 * q0 + c0) + 16 * iota(), words);
    for (int k = 0; k < 4; k++) words[k] = scaled(words[k], (uint32_t)pt->entries);
    for (uint32_t i = 0; i < W; i++)
      for (uint32_t k = 0; k < 4; k++) {
        uint32_t G = 4 * (q0 + i) + k;
        if (G >= G0 && G < G0 + (uint32_t)nruns) out[G - G0] = words[k][i];
      }
  }
}

/* one pixel, unclamped, the vector loops' formula (a stencil's four partial sums included), for
 * spans narrower than a vector */
static inline float pixel_fma(const ics_prop_taps *pt, int e, const float *S, int stride) {
  if (pt->stencil) {
    float a[4] = {0, 0, 0, 0};
    int n = pt->ntaps, j = 0;
    for (; j + 4 <= n; j += 4)
      for (int k = 0; k < 4; k++) a[k] = madd1(pt->w[j + k], S[pt->off[j + k]], a[k]);
    for (; j < n; j++) a[0] = madd1(pt->w[j], S[pt->off[j]], a[0]);
    return (a[0] + a[1]) + (a[2] + a[3]);
  }
  float acc = 0;
  for (int j = e * pt->ntaps; j < (e + 1) * pt->ntaps; j++) {
    const float *r0 = S + pt->off[j];
    float fx = pt->fx[j], fy = pt->fy[j];
    float top = madd1(fx, r0[1] - r0[0], r0[0]);
    float bot = madd1(fx, r0[stride + 1] - r0[stride], r0[stride]);
    acc = madd1(pt->w[j], madd1(fy, bot - top, top), acc);
  }
  return acc;
}

static inline vf bilinear(const float *p, int stride, vf fx, vf fy) {
  vf a = loadf(p), b = loadf(p + 1), c = loadf(p + stride), d = loadf(p + stride + 1);
  vf top = madd(fx, b - a, a), bot = madd(fx, d - c, c);
  return madd(fy, bot - top, top);
}

/* W pixels of a stencil from x on: four independent sums (the multiply-add latency), added in a
 * fixed order */
static inline vf stencil_vector(const ics_prop_taps *pt, const float *S, int x) {
  vf a0 = splatf(0), a1 = a0, a2 = a0, a3 = a0;
  int n = pt->ntaps, j = 0;
  for (; j + 4 <= n; j += 4) {
    a0 = madd(splatf(pt->w[j]), loadf(S + x + pt->off[j]), a0);
    a1 = madd(splatf(pt->w[j + 1]), loadf(S + x + pt->off[j + 1]), a1);
    a2 = madd(splatf(pt->w[j + 2]), loadf(S + x + pt->off[j + 2]), a2);
    a3 = madd(splatf(pt->w[j + 3]), loadf(S + x + pt->off[j + 3]), a3);
  }
  for (; j < n; j++) a0 = madd(splatf(pt->w[j]), loadf(S + x + pt->off[j]), a0);
  return (a0 + a1) + (a2 + a3);
}

/* The spans' ends: a span [x0, x1) that is not a whole number of vectors ends with one more
 * vector over its last W pixels (overlapping the previous one, with the same values there), so
 * every pixel of a span at least W wide comes out of a vector and nothing outside the span is
 * written; spans narrower than W are evaluated pixel by pixel (pixel_fma). Every lane is
 * pixel_fma's formula, so where a pixel is computed does not change it: the paths with fused
 * multiply-adds agree bit for bit whatever W and wherever a span starts. */
static void stencil_row(const ics_prop_taps *pt, const float *src, float *dst,
                        const ics_buf_layout *L, int nch, int y, int x0, int x1) {
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    if (x1 - x0 < W) {
      for (int x = x0; x < x1; x++) D[x] = pixel_fma(pt, 0, S + x, L->stride);
      continue;
    }
    for (int x = x0;; x += W) {
      if (x + W > x1) x = x1 - W;
      storef(D + x, stencil_vector(pt, S, x));
      if (x + W == x1) break;
    }
  }
}

/* the horizontal interpolation of a tap's two reads p[0], p[1] (bilinear's first step) */
static inline vf hlerp(const float *p, vf fx) {
  vf a = loadf(p), b = loadf(p + 1);
  return madd(fx, b - a, a);
}

/* rows 0 .. R - 1 (R <= ICS_PROP_ROW_BLOCK) of the W pixels from x on (row r's entries at
 * ent + r es): every candidate evaluated, each pixel keeping its own set's. A tap's two rows of
 * reads are shared by neighbouring output rows (row r's lower row is row r + 1's upper): each
 * buffer row's horizontal interpolation is made once for both, the same value, so every lane is
 * bilinear's formula bit for bit and 8 rows take 9 interpolations per tap instead of 16. */
static inline __attribute__((always_inline)) void
candidates_block(const ics_prop_taps *pt, const float *S, int stride, const uint32_t *ent, int es,
                 int x, int R, float *D) {
  int n = pt->ntaps, K = pt->entries;
  vf out[ICS_PROP_ROW_BLOCK];
  vi e[ICS_PROP_ROW_BLOCK];
  for (int r = 0; r < R; r++) out[r] = splatf(0), e[r] = (vi)loadu(ent + (size_t)r * es + x);
  for (int k = 0; k < K; k++) {
    vf acc[ICS_PROP_ROW_BLOCK];
    for (int r = 0; r < R; r++) acc[r] = splatf(0);
    for (int j = k * n; j < (k + 1) * n; j++) {
      vf fx = splatf(pt->fx[j]), fy = splatf(pt->fy[j]), wt = splatf(pt->w[j]);
      const float *p = S + x + pt->off[j];
      vf top = hlerp(p, fx);
      for (int r = 0; r < R; r++) {
        vf bot = hlerp(p + (size_t)(r + 1) * stride, fx);
        acc[r] = madd(wt, madd(fy, bot - top, top), acc[r]);
        top = bot;
      }
    }
    for (int r = 0; r < R; r++) out[r] = blend(e[r] == k, acc[r], out[r]);
  }
  for (int r = 0; r < R; r++) storef(D + (size_t)r * stride + x, out[r]);
}

/* pixels [x0, x1) (at least W) of rows y .. y + R - 1 of a few tap sets: the rows' entries, then
 * vectors of candidates_block, the span's end as in stencil_row. Inlined, so that where R is a
 * constant the blocks' loops unroll (called, the blocks' arrays were zeroed and kept in memory
 * every vector: no faster than one row at a time). */
static inline __attribute__((always_inline)) void
candidates_rows(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                int nch, int y, int R, int x0, int x1, uint32_t *scratch) {
  int es = L->w + 2, stride = L->stride;
  for (int r = 0; r < R; r++) entries_row(pt, L->w, y + r, x0, x1, scratch + (size_t)r * es);
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    for (int x = x0;; x += W) {
      if (x + W > x1) x = x1 - W;
      candidates_block(pt, S, stride, scratch, es, x, R, D);
      if (x + W == x1) break;
    }
  }
}

/* a span narrower than a vector of a few tap sets (wider ones: candidates_rows), pixel by pixel */
static void candidates_narrow(const ics_prop_taps *pt, const float *src, float *dst,
                              const ics_buf_layout *L, int nch, int y, int x0, int x1,
                              const uint32_t *ent) {
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    for (int x = x0; x < x1; x++) D[x] = pixel_fma(pt, (int)ent[x], S + x, L->stride);
  }
}

/* one run's set e over the 16 pixels from x on (16 / W vectors) into out */
static inline void run_vectors(const ics_prop_taps *pt, int e, const float *S, int x, int stride,
                               float *out) {
  for (int h = 0; h < 16; h += W) {
    vf acc = splatf(0);
    for (int j = e * pt->ntaps; j < (e + 1) * pt->ntaps; j++)
      acc = madd(splatf(pt->w[j]),
                 bilinear(S + x + h + pt->off[j], stride, splatf(pt->fx[j]), splatf(pt->fy[j])),
                 acc);
    storef(out + h, acc);
  }
}

/* runs of 16 pixels sharing one tap set (their starts moved by the slab's phase), each as 16 / W
 * vectors evaluating only its own set. A run that the span [x0, x1) or the row cuts is evaluated
 * over 16 pixels within the row (from its start, or from the row's last 16) and only its pixels in
 * the span kept; rows narrower than 16 pixel by pixel. Every lane is pixel_fma's formula, so
 * where a pixel is computed does not change it. */
static void runs_row(const ics_prop_taps *pt, const float *src, float *dst,
                     const ics_buf_layout *L, int nch, int y, int x0, int x1, uint32_t *scratch) {
  int w = L->w, stride = L->stride, first = pt->phase - 16;
  int m0 = (x0 - first) / 16, m1 = (x1 - 1 - first) / 16;
  run_choices(pt, w, y, m0, m1 - m0 + 1, scratch);
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    for (int m = m0; m <= m1; m++) {
      int e = (int)scratch[m - m0], xs = first + 16 * m;
      int a = xs > x0 ? xs : x0, b = xs + 16 < x1 ? xs + 16 : x1;
      if (w < 16) {
        for (int i = a; i < b; i++) D[i] = pixel_fma(pt, e, S + i, stride);
      } else if (a == xs && b == xs + 16) {
        run_vectors(pt, e, S, xs, stride, D + xs);
      } else {
        float part[16];
        int base = xs < 0 ? 0 : xs + 16 > w ? w - 16 : xs;
        run_vectors(pt, e, S, base, stride, part);
        memcpy(D + a, part + (a - base), sizeof(float) * (size_t)(b - a));
      }
    }
  }
}

/* a tap set per pixel from a large table: the taps and corners gathered lane by lane; the span's
 * end as in stencil_row */
static void table_row(const ics_prop_taps *pt, const float *src, float *dst,
                      const ics_buf_layout *L, int nch, int y, int x0, int x1, const uint32_t *ent) {
  int n = pt->ntaps, stride = L->stride;
  const size_t row0 = ics_buf_index(L, 0, y);
  for (int x = x0; x1 - x0 >= W; x += W) {
    if (x + W > x1) x = x1 - W;
    vf acc[3] = {splatf(0), splatf(0), splatf(0)};
    for (int j = 0; j < n; j++) {
      vf fx, fy, wt;
      int32_t off[W];
      for (int i = 0; i < W; i++) {
        int t = (int)ent[x + i] * n + j;
        fx[i] = pt->fx[t], fy[i] = pt->fy[t], wt[i] = pt->w[t];
        off[i] = pt->off[t];
      }
      for (int c = 0; c < nch; c++) {
        const float *S = src + (size_t)c * L->plane + row0 + x;
        vf va, vb, vc, vd;
        for (int i = 0; i < W; i++) {
          const float *r = S + i + off[i];
          va[i] = r[0], vb[i] = r[1], vc[i] = r[stride], vd[i] = r[stride + 1];
        }
        vf top = madd(fx, vb - va, va), bot = madd(fx, vd - vc, vc);
        acc[c] = madd(wt, madd(fy, bot - top, top), acc[c]);
      }
    }
    for (int c = 0; c < nch; c++) storef(dst + (size_t)c * L->plane + row0 + x, acc[c]);
    if (x + W == x1) break;
  }
  for (int x = x0; x < x1 && x1 - x0 < W; x++)
    for (int c = 0; c < nch; c++)
      dst[(size_t)c * L->plane + row0 + x] =
          pixel_fma(pt, (int)ent[x], src + (size_t)c * L->plane + row0 + x, stride);
}

/* Perspective steps (pt->classes; ics_prop_prepare_perspective): pixel x of row y takes the four
 * classes around the fraction of D = (s - 1)(x - c) at x + floor(D_x), y + floor(D_y), blended
 * by where the fraction lies between them (propagate.c's pixel_classes, whose arithmetic decides
 * every pixel's classes and blend weights here too). Numbered along an axis, class
 * l = floor(D) Q + floor(frac(D) Q) is class l mod Q shifted by floor(l / Q) pixels, and a pixel
 * blends l and l + 1; along a row l changes by (s - 1) Q per pixel, so a vector's lanes span a
 * few consecutive l. Each is a stencil of integer taps over the whole vector, and each lane keeps
 * its own two (a masked blend). Lanes whose reads leave the apron take the clamped portable
 * pixel, vectors spanning more than CLASS_SPAN classes and spans narrower than a vector
 * class_pixel (each lane's formula). */
#define CLASS_SPAN 3

/* floor(a / Q) */
static inline int floor_div(int a, int Q) { return a >= 0 ? a / Q : -((-a + Q - 1) / Q); }

/* a pixel's class number along one axis (above) and its blend r */
static inline int class_axis(double s, double c, int x, int Q, float *r) {
  double D = (s - 1) * (x - c), f = floor(D), t = (D - f) * Q, kk = floor(t);
  *r = (float)(t - kk);
  return (int)f * Q + (int)kk;
}

/* class number l along x and m along y: its first tap, and its reads' offset from the pixel */
static inline void class_at(const ics_prop_taps *pt, int stride, int l, int m, int *base, int *shift) {
  const int Q = pt->classes;
  int sx = floor_div(l, Q), sy = floor_div(m, Q);
  *base = ((m - sy * Q) * Q + (l - sx * Q)) * pt->ntaps;
  *shift = sy * stride + sx;
}

/* class (l, m) over W pixels from S */
static inline vf class_vector(const ics_prop_taps *pt, const float *S, int stride, int l, int m) {
  int base, shift;
  class_at(pt, stride, l, m, &base, &shift);
  vf acc = splatf(0);
  for (int t = base; t < base + pt->ntaps; t++)
    acc = madd(splatf(pt->w[t]), loadf(S + shift + pt->iy[t] * stride + pt->ix[t]), acc);
  return acc;
}

/* one pixel (class l along x, m along y), reads within the apron: each lane's formula of
 * classes_vector */
static inline float class_pixel(const ics_prop_taps *pt, const float *S, int stride, int l,
                                float rx, int m, float ry) {
  float a[4];
  for (int q = 0; q < 4; q++) {
    int base, shift;
    class_at(pt, stride, l + (q & 1), m + (q >> 1), &base, &shift);
    float acc = 0;
    for (int t = base; t < base + pt->ntaps; t++)
      acc = madd1(pt->w[t], S[shift + pt->iy[t] * stride + pt->ix[t]], acc);
    a[q] = acc;
  }
  float top = madd1(rx, a[1] - a[0], a[0]), bot = madd1(rx, a[3] - a[2], a[2]);
  return madd1(ry, bot - top, top);
}

/* W pixels whose classes along x are lmin + lane's d (0 <= d <= span <= CLASS_SPAN) */
static inline vf classes_vector(const ics_prop_taps *pt, const float *S, int stride, int lmin,
                                int span, vi d, vf rx, int m, float ry) {
  vf row0[CLASS_SPAN + 2] = {0}, row1[CLASS_SPAN + 2] = {0};
  for (int i = 0; i <= span + 1; i++) {
    row0[i] = class_vector(pt, S, stride, lmin + i, m);
    row1[i] = class_vector(pt, S, stride, lmin + i, m + 1);
  }
  vf a00 = row0[0], a10 = row0[1], a01 = row1[0], a11 = row1[1];
  for (int i = 1; i <= span; i++) {
    vi sel = d == i;
    a00 = blend(sel, row0[i], a00), a10 = blend(sel, row0[i + 1], a10);
    a01 = blend(sel, row1[i], a01), a11 = blend(sel, row1[i + 1], a11);
  }
  vf top = madd(rx, a10 - a00, a00), bot = madd(rx, a11 - a01, a01);
  return madd(splatf(ry), bot - top, top);
}

/* pixel x (class l, blend r) of row y (class m, blend ry): within the apron, the lanes' formula;
 * else clamped reads */
static inline void class_one(const ics_prop_taps *pt, const float *src, float *dst,
                             const ics_buf_layout *L, int nch, int x, int y, int l, float r, int m,
                             float ry, int row_in) {
  int nx = floor_div(l, pt->classes), A = L->apron;
  if (!row_in || x + nx + pt->lo[0] < -A || x + nx + pt->hi[0] > L->w - 1 + A) {
    ics_prop_pixel_classes(pt, src, dst, L, nch, x, y);
    return;
  }
  for (int c = 0; c < nch; c++)
    dst[(size_t)c * L->plane + ics_buf_index(L, x, y)] =
        class_pixel(pt, src + (size_t)c * L->plane + ics_buf_index(L, x, y), L->stride, l, r, m, ry);
}

/* pixels [x0, x1) of row y of a perspective step; the span's end as in stencil_row */
static void classes_row(const ics_prop_taps *pt, const float *src, float *dst,
                        const ics_buf_layout *L, int nch, int y, int x0, int x1) {
  const int Q = pt->classes, A = L->apron, stride = L->stride;
  float ry, r[W];
  int m = class_axis(pt->s, pt->cy, y, Q, &ry), ny = floor_div(m, Q), l[W];
  int row_in = y + ny + pt->lo[1] >= -A && y + ny + pt->hi[1] <= L->h - 1 + A;
  if (x1 - x0 < W) {
    for (int x = x0; x < x1; x++) {
      int lx = class_axis(pt->s, pt->cx, x, Q, &r[0]);
      class_one(pt, src, dst, L, nch, x, y, lx, r[0], m, ry, row_in);
    }
    return;
  }
  for (int x = x0;; x += W) {
    if (x + W > x1) x = x1 - W;
    int lmin = INT32_MAX, lmax = INT32_MIN;
    for (int i = 0; i < W; i++) {
      l[i] = class_axis(pt->s, pt->cx, x + i, Q, &r[i]);
      lmin = l[i] < lmin ? l[i] : lmin, lmax = l[i] > lmax ? l[i] : lmax;
    }
    /* every lane evaluates every class lmin .. lmax + 1: lane i reads within
     * x + i + floor(l' / Q) + [lo, hi] (hi counts class Q's extra pixel), so within
     * x + floor(lmin / Q) + lo .. x + W - 1 + floor(lmax / Q) + hi */
    int in = row_in && x + floor_div(lmin, Q) + pt->lo[0] >= -A &&
             x + W - 1 + floor_div(lmax, Q) + pt->hi[0] <= L->w - 1 + A;
    if (in && lmax - lmin <= CLASS_SPAN) {
      vi d;
      for (int i = 0; i < W; i++) d[i] = l[i] - lmin;
      for (int c = 0; c < nch; c++) {
        size_t o = (size_t)c * L->plane + ics_buf_index(L, x, y);
        storef(dst + o, classes_vector(pt, src + o, stride, lmin, lmax - lmin, d, loadf(r), m, ry));
      }
    } else {
      for (int i = 0; i < W; i++) class_one(pt, src, dst, L, nch, x + i, y, l[i], r[i], m, ry, row_in);
    }
    if (x + W == x1) break;
  }
}

void ICS_VEC_FN(const ics_prop_taps *pt, const float *src, float *dst, const ics_buf_layout *L,
                int nch, int y0, int y1, int x0, int x1, uint32_t *scratch) {
  if (!pt->classes && pt->entries > 1 && pt->run <= 1 && !pt->stencil &&
      pt->entries <= ICS_PROP_CANDIDATES_MAX && x1 - x0 >= W) { /* blocks of rows */
    int y = y0;
    for (; y + ICS_PROP_ROW_BLOCK <= y1; y += ICS_PROP_ROW_BLOCK)
      candidates_rows(pt, src, dst, L, nch, y, ICS_PROP_ROW_BLOCK, x0, x1, scratch);
    if (y < y1) candidates_rows(pt, src, dst, L, nch, y, y1 - y, x0, x1, scratch);
    return;
  }
  for (int y = y0; y < y1; y++) {
    if (pt->classes) {
      classes_row(pt, src, dst, L, nch, y, x0, x1);
      continue;
    }
    if (pt->entries > 1 && pt->run > 1) {
      runs_row(pt, src, dst, L, nch, y, x0, x1, scratch);
      continue;
    }
    if (pt->entries > 1) entries_row(pt, L->w, y, x0, x1, scratch);
    if (pt->stencil)
      stencil_row(pt, src, dst, L, nch, y, x0, x1);
    else if (pt->entries <= ICS_PROP_CANDIDATES_MAX)
      candidates_narrow(pt, src, dst, L, nch, y, x0, x1, scratch);
    else
      table_row(pt, src, dst, L, nch, y, x0, x1, scratch);
  }
}

#undef W
