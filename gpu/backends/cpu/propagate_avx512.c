/* propagate_avx512.c — AVX-512 loops of the CPU slab step (see propagate_simd.h), compiled with
 * function-level target attributes and chosen at run time, so the library still runs on any
 * x86-64 processor (and builds elsewhere, where these are stubs). Preconditions: s = 1 and the
 * taps' reach within the buffers' apron (no read is clamped).
 *
 * Stencils (one tap set): 16 pixels per vector, one unaligned load and one FMA per tap.
 * Few tap sets (entries <= ICS_PROP_CANDIDATES_MAX, e.g. the default 4 rotations per slab): every
 * set evaluated with unaligned loads for the 16 pixels, each pixel keeping its own set's result
 * (a masked blend): no gathers. Many tap sets (a per-pixel table of 384): per tap three gathers
 * from the tap table and four for the bilinear corners per channel. The row's entries come from
 * a 16-lane Philox-4x32-10 (64 pixels per call; the same words as ics_slab_entry_block).
 * Arithmetic: FMA, the same formula in every path, so the last bits do not depend on the path;
 * they can differ from the portable loops'. */
#include "propagate_simd.h"

#include <stdint.h>

#include "slab_kernel.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

#define TGT __attribute__((target("avx512f,avx512bw,avx512dq,avx512vl,fma")))

int ics_prop_avx512_available(void) {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512dq");
}

/* 32 x 32 -> 64 bit products of 16 lanes: low and high halves */
TGT static inline void mul32x32(__m512i a, __m512i m, __m512i *lo, __m512i *hi) {
  __m512i pe = _mm512_mul_epu32(a, m);
  __m512i po = _mm512_mul_epu32(_mm512_srli_epi64(a, 32), m);
  *lo = _mm512_mask_blend_epi32(0xAAAA, pe, _mm512_slli_epi64(po, 32));
  *hi = _mm512_mask_blend_epi32(0xAAAA, _mm512_srli_epi64(pe, 32), po);
}

/* Philox-4x32-10 on 16 counters (rng.c's rounds, lane by lane) */
TGT static void philox16(__m512i c[4], uint32_t key0, uint32_t key1) {
  const __m512i M0 = _mm512_set1_epi32((int)0xD2511F53u), M1 = _mm512_set1_epi32((int)0xCD9E8D57u);
  uint32_t k0 = key0, k1 = key1;
  for (int r = 0; r < 10; r++) {
    if (r > 0) k0 += 0x9E3779B9u, k1 += 0xBB67AE85u;
    __m512i lo0, hi0, lo1, hi1;
    mul32x32(c[0], M0, &lo0, &hi0);
    mul32x32(c[2], M1, &lo1, &hi1);
    __m512i n0 = _mm512_xor_si512(_mm512_xor_si512(hi1, c[1]), _mm512_set1_epi32((int)k0));
    __m512i n2 = _mm512_xor_si512(_mm512_xor_si512(hi0, c[3]), _mm512_set1_epi32((int)k1));
    c[0] = n0;
    c[1] = lo1;
    c[2] = n2;
    c[3] = lo0;
  }
}

/* the entries of row y: floor(word * entries / 2^32); one 16-lane Philox call covers the 64
 * pixels 64 c .. 64 c + 63 in order (blocks 16 c .. 16 c + 15, word i for pixels + 16 i) */
TGT static void entries_row(const ics_prop_taps *pt, int w, int y, uint32_t *ent) {
  uint32_t first = (uint32_t)((size_t)y * w), last = first + (uint32_t)w - 1;
  const __m512i Mt = _mm512_set1_epi32(pt->entries);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  uint32_t tmp[64];
  for (uint32_t c64 = first / 64; c64 <= last / 64; c64++) {
    __m512i c[4] = {_mm512_add_epi32(_mm512_set1_epi32((int)(16 * c64)), iota),
                    _mm512_set1_epi32((int)pt->slab), _mm512_set1_epi32((int)pt->light),
                    _mm512_set1_epi32(0x736c6162)};
    philox16(c, (uint32_t)pt->seed, (uint32_t)(pt->seed >> 32));
    uint32_t p0 = 64 * c64;
    uint32_t *dst = p0 >= first && p0 + 63 <= last ? ent + (p0 - first) : tmp;
    for (int k = 0; k < 4; k++) {
      __m512i lo, hi;
      mul32x32(c[k], Mt, &lo, &hi);
      _mm512_storeu_si512((void *)(dst + 16 * k), hi);
    }
    if (dst == tmp)
      for (uint32_t i = 0; i < 64; i++)
        if (p0 + i >= first && p0 + i <= last) ent[p0 + i - first] = tmp[i];
  }
}

/* one pixel, unclamped, the vector loops' formula (FMA) */
TGT static inline float pixel_fma(const ics_prop_taps *pt, int e, const float *S, int stride) {
  float acc = 0;
  for (int j = e * pt->ntaps; j < (e + 1) * pt->ntaps; j++) {
    const float *r0 = S + pt->off[j];
    if (pt->stencil) {
      acc = __builtin_fmaf(pt->w[j], r0[0], acc);
      continue;
    }
    float fx = pt->fx[j], fy = pt->fy[j];
    float top = __builtin_fmaf(fx, r0[1] - r0[0], r0[0]);
    float bot = __builtin_fmaf(fx, r0[stride + 1] - r0[stride], r0[stride]);
    acc = __builtin_fmaf(pt->w[j], __builtin_fmaf(fy, bot - top, top), acc);
  }
  return acc;
}

TGT static inline __m512 bilinear16(const float *p, int stride, __m512 fx, __m512 fy) {
  __m512 a = _mm512_loadu_ps(p), b = _mm512_loadu_ps(p + 1);
  __m512 c = _mm512_loadu_ps(p + stride), d = _mm512_loadu_ps(p + stride + 1);
  __m512 top = _mm512_fmadd_ps(fx, _mm512_sub_ps(b, a), a);
  __m512 bot = _mm512_fmadd_ps(fx, _mm512_sub_ps(d, c), c);
  return _mm512_fmadd_ps(fy, _mm512_sub_ps(bot, top), top);
}

TGT static void stencil_row(const ics_prop_taps *pt, const float *src, float *dst,
                            const ics_buf_layout *L, int nch, int y) {
  int w = L->w, n = pt->ntaps;
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    int x = 0;
    for (; x + 16 <= w; x += 16) {
      /* four independent sums (the FMA latency), added in a fixed order */
      __m512 a0 = _mm512_setzero_ps(), a1 = a0, a2 = a0, a3 = a0;
      int j = 0;
      for (; j + 4 <= n; j += 4) {
        a0 = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j]), _mm512_loadu_ps(S + x + pt->off[j]), a0);
        a1 = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j + 1]), _mm512_loadu_ps(S + x + pt->off[j + 1]), a1);
        a2 = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j + 2]), _mm512_loadu_ps(S + x + pt->off[j + 2]), a2);
        a3 = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j + 3]), _mm512_loadu_ps(S + x + pt->off[j + 3]), a3);
      }
      for (; j < n; j++)
        a0 = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j]), _mm512_loadu_ps(S + x + pt->off[j]), a0);
      _mm512_storeu_ps(D + x, _mm512_add_ps(_mm512_add_ps(a0, a1), _mm512_add_ps(a2, a3)));
    }
    for (; x < w; x++) D[x] = pixel_fma(pt, 0, S + x, L->stride);
  }
}

/* two 16-pixel blocks per step: independent chains hide the FMA latency; every candidate is
 * evaluated for both (with 4 rotations per slab almost every block needs all of them) */
TGT static void candidates_row(const ics_prop_taps *pt, const float *src, float *dst,
                               const ics_buf_layout *L, int nch, int y, const uint32_t *ent) {
  int w = L->w, n = pt->ntaps, K = pt->entries, stride = L->stride;
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    int x = 0;
    for (; x + 32 <= w; x += 32) {
      __m512i e0 = _mm512_loadu_si512((const void *)(ent + x));
      __m512i e1 = _mm512_loadu_si512((const void *)(ent + x + 16));
      __m512 out0 = _mm512_setzero_ps(), out1 = out0;
      for (int k = 0; k < K; k++) {
        __m512 acc0 = _mm512_setzero_ps(), acc1 = acc0;
        for (int j = k * n; j < (k + 1) * n; j++) {
          __m512 fx = _mm512_set1_ps(pt->fx[j]), fy = _mm512_set1_ps(pt->fy[j]),
                 wt = _mm512_set1_ps(pt->w[j]);
          const float *p = S + x + pt->off[j];
          acc0 = _mm512_fmadd_ps(wt, bilinear16(p, stride, fx, fy), acc0);
          acc1 = _mm512_fmadd_ps(wt, bilinear16(p + 16, stride, fx, fy), acc1);
        }
        __m512i vk = _mm512_set1_epi32(k);
        out0 = _mm512_mask_blend_ps(_mm512_cmpeq_epi32_mask(e0, vk), out0, acc0);
        out1 = _mm512_mask_blend_ps(_mm512_cmpeq_epi32_mask(e1, vk), out1, acc1);
      }
      _mm512_storeu_ps(D + x, out0);
      _mm512_storeu_ps(D + x + 16, out1);
    }
    for (; x < w; x++) D[x] = pixel_fma(pt, (int)ent[x], S + x, stride);
  }
}

/* the choices of runs 0 .. nruns-1 of row y (run m starts at x = phase - 16 + 16 m): run m is
 * the counter Y + 16 m, Y = y (w + 32) (ics_prop_run_choice), whose word is word G % 4 of block
 * (G / 4) 16 + Y % 16 with G = Y / 16 + m: one 16-lane Philox call gives 64 runs */
TGT static void run_choices(const ics_prop_taps *pt, int w, int y, int nruns, uint32_t *out) {
  uint32_t Y = (uint32_t)((size_t)y * (size_t)(w + 32)), c0 = Y % 16, G0 = Y / 16;
  const __m512i Mt = _mm512_set1_epi32(pt->entries);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  uint32_t tmp[4][16];
  for (uint32_t q0 = G0 / 4; q0 <= (G0 + (uint32_t)nruns - 1) / 4; q0 += 16) {
    __m512i c[4] = {_mm512_add_epi32(_mm512_set1_epi32((int)(16 * q0 + c0)), _mm512_slli_epi32(iota, 4)),
                    _mm512_set1_epi32((int)pt->slab), _mm512_set1_epi32((int)pt->light),
                    _mm512_set1_epi32(0x736c6162)};
    philox16(c, (uint32_t)pt->seed, (uint32_t)(pt->seed >> 32));
    for (int k = 0; k < 4; k++) {
      __m512i lo, hi;
      mul32x32(c[k], Mt, &lo, &hi);
      _mm512_storeu_si512((void *)tmp[k], hi);
    }
    for (uint32_t i = 0; i < 16; i++)
      for (uint32_t k = 0; k < 4; k++) {
        uint32_t G = 4 * (q0 + i) + k;
        if (G >= G0 && G < G0 + (uint32_t)nruns) out[G - G0] = tmp[k][i];
      }
  }
}

/* runs of 16 pixels sharing one tap set: each vector is one run (its start moved by the slab's
 * phase, the row's ends masked), so only its own set is evaluated */
TGT static void runs_row(const ics_prop_taps *pt, const float *src, float *dst,
                         const ics_buf_layout *L, int nch, int y, uint32_t *scratch) {
  int w = L->w, n = pt->ntaps, stride = L->stride;
  int nruns = (w - pt->phase + 16 + 15) / 16;
  run_choices(pt, w, y, nruns, scratch);
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    float *D = dst + (size_t)c * L->plane + ics_buf_index(L, 0, y);
    int m = 0;
    for (int x = pt->phase - 16; x < w; x += 16, m++) {
      int e = (int)scratch[m];
      int lo = x < 0 ? -x : 0, hi = x + 16 > w ? w - x : 16;
      __mmask16 mk = (__mmask16)(((1u << hi) - 1) & ~((1u << lo) - 1));
      __m512 acc = _mm512_setzero_ps();
      for (int j = e * n; j < (e + 1) * n; j++) {
        const float *p = S + x + pt->off[j];
        __m512 fx = _mm512_set1_ps(pt->fx[j]), fy = _mm512_set1_ps(pt->fy[j]);
        __m512 a = _mm512_maskz_loadu_ps(mk, p), b = _mm512_maskz_loadu_ps(mk, p + 1);
        __m512 cc = _mm512_maskz_loadu_ps(mk, p + stride), d = _mm512_maskz_loadu_ps(mk, p + stride + 1);
        __m512 top = _mm512_fmadd_ps(fx, _mm512_sub_ps(b, a), a);
        __m512 bot = _mm512_fmadd_ps(fx, _mm512_sub_ps(d, cc), cc);
        acc = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j]), _mm512_fmadd_ps(fy, _mm512_sub_ps(bot, top), top), acc);
      }
      _mm512_mask_storeu_ps(D + x, mk, acc);
    }
  }
}

TGT static void table_row(const ics_prop_taps *pt, const float *src, float *dst,
                          const ics_buf_layout *L, int nch, int y, const uint32_t *ent) {
  int w = L->w, n = pt->ntaps, stride = L->stride;
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i vn = _mm512_set1_epi32(n), one = _mm512_set1_epi32(1),
                vs = _mm512_set1_epi32(stride), vs1 = _mm512_set1_epi32(stride + 1);
  const size_t row0 = ics_buf_index(L, 0, y);
  int x = 0;
  for (; x + 16 <= w; x += 16) {
    __m512i e = _mm512_loadu_si512((const void *)(ent + x));
    __m512i px = _mm512_add_epi32(_mm512_set1_epi32((int)(row0 + (size_t)x)), iota);
    __m512 acc[3] = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_ps()};
    __m512i en = _mm512_mullo_epi32(e, vn);
    for (int j = 0; j < n; j++) {
      __m512i idx = _mm512_add_epi32(en, _mm512_set1_epi32(j));
      __m512i off = _mm512_i32gather_epi32(idx, (const void *)pt->off, 4);
      __m512 fx = _mm512_i32gather_ps(idx, (const void *)pt->fx, 4);
      __m512 fy = _mm512_i32gather_ps(idx, (const void *)pt->fy, 4);
      __m512 wt = _mm512_i32gather_ps(idx, (const void *)pt->w, 4);
      __m512i a0 = _mm512_add_epi32(px, off);
      __m512i a1 = _mm512_add_epi32(a0, one), a2 = _mm512_add_epi32(a0, vs),
              a3 = _mm512_add_epi32(a0, vs1);
      for (int c = 0; c < nch; c++) {
        const float *S = src + (size_t)c * L->plane;
        __m512 va = _mm512_i32gather_ps(a0, (const void *)S, 4);
        __m512 vb = _mm512_i32gather_ps(a1, (const void *)S, 4);
        __m512 vc = _mm512_i32gather_ps(a2, (const void *)S, 4);
        __m512 vd = _mm512_i32gather_ps(a3, (const void *)S, 4);
        __m512 top = _mm512_fmadd_ps(fx, _mm512_sub_ps(vb, va), va);
        __m512 bot = _mm512_fmadd_ps(fx, _mm512_sub_ps(vd, vc), vc);
        __m512 v = _mm512_fmadd_ps(fy, _mm512_sub_ps(bot, top), top);
        acc[c] = _mm512_fmadd_ps(wt, v, acc[c]);
      }
    }
    for (int c = 0; c < nch; c++) _mm512_storeu_ps(dst + (size_t)c * L->plane + row0 + x, acc[c]);
  }
  for (; x < w; x++)
    for (int c = 0; c < nch; c++)
      dst[(size_t)c * L->plane + row0 + x] =
          pixel_fma(pt, (int)ent[x], src + (size_t)c * L->plane + row0 + x, stride);
}

TGT void ics_prop_rows_avx512(const ics_prop_taps *pt, const float *src, float *dst,
                              const ics_buf_layout *L, int nch, int y0, int y1,
                              uint32_t *scratch) {
  for (int y = y0; y < y1; y++) {
    if (pt->entries > 1 && pt->run > 1) {
      runs_row(pt, src, dst, L, nch, y, scratch);
      continue;
    }
    if (pt->entries > 1) entries_row(pt, L->w, y, scratch);
    if (pt->stencil)
      stencil_row(pt, src, dst, L, nch, y);
    else if (pt->entries <= ICS_PROP_CANDIDATES_MAX)
      candidates_row(pt, src, dst, L, nch, y, scratch);
    else
      table_row(pt, src, dst, L, nch, y, scratch);
  }
}

#else
int ics_prop_avx512_available(void) { return 0; }
void ics_prop_rows_avx512(const ics_prop_taps *pt, const float *src, float *dst,
                          const ics_buf_layout *L, int nch, int y0, int y1, uint32_t *scratch) {
  (void)pt, (void)src, (void)dst, (void)L, (void)nch, (void)y0, (void)y1, (void)scratch;
}
#endif
