/* propagate_avx512.c — AVX-512 interior loops of the CPU slab step (see propagate_simd.h),
 * compiled with function-level target attributes and chosen at run time, so the library still
 * runs on any x86-64 processor (and builds elsewhere, where these are stubs).
 *
 * Stencils (one tap set): 16 pixels per vector, one unaligned load and one FMA per tap.
 * Tables (per-pixel random tap sets): the row's entries from a 16-lane Philox-4x32-10 (64 pixels
 * per call; the same words as ics_slab_entry), then per tap three gathers from the tap table
 * (offset, fractions, weight) and four gathers for the bilinear corners per channel. Edge pixels
 * use the clamped scalar pixel (propagate.c). Arithmetic: FMA, so the interior's last bits can
 * differ from the portable loops'; the result still depends on nothing but the pixel. */
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

/* the table entries of row y: entry = floor(word * M / 2^32) */
TGT static void entries_row(const ics_prop_taps *pt, int w, int y, uint32_t *ent) {
  uint32_t first = (uint32_t)((size_t)y * w), last = first + (uint32_t)w - 1;
  uint32_t b0 = first / 4, b1 = last / 4;
  const __m512i Mt = _mm512_set1_epi32(ICS_SLAB_TABLE_M);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  uint32_t tmp[4][16];
  for (uint32_t b = b0; b <= b1; b += 16) {
    __m512i c[4] = {_mm512_add_epi32(_mm512_set1_epi32((int)b), iota),
                    _mm512_set1_epi32((int)pt->slab), _mm512_set1_epi32((int)pt->light),
                    _mm512_set1_epi32(0x736c6162)};
    philox16(c, (uint32_t)pt->seed, (uint32_t)(pt->seed >> 32));
    for (int k = 0; k < 4; k++) {
      __m512i lo, hi;
      mul32x32(c[k], Mt, &lo, &hi);
      _mm512_storeu_si512((void *)tmp[k], hi);
    }
    for (int i = 0; i < 16 && b + (uint32_t)i <= b1; i++)
      for (int k = 0; k < 4; k++) {
        uint32_t px = 4 * (b + (uint32_t)i) + (uint32_t)k;
        if (px >= first && px <= last) ent[px - first] = tmp[k][i];
      }
  }
}

TGT static void table_row(const ics_prop_taps *pt, const float *src, float *dst, int w, int h,
                          int nch, int y, const uint32_t *ent) {
  size_t plane = (size_t)w * h;
  int r = pt->reach, n = pt->ntaps;
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512i vn = _mm512_set1_epi32(n), one = _mm512_set1_epi32(1), vw = _mm512_set1_epi32(w),
                vw1 = _mm512_set1_epi32(w + 1);
  int x = r;
  for (; x + 16 <= w - r; x += 16) {
    __m512i e = _mm512_loadu_si512((const void *)(ent + x));
    __m512i px = _mm512_add_epi32(_mm512_set1_epi32((int)((size_t)y * w + x)), iota);
    __m512 acc[3] = {_mm512_setzero_ps(), _mm512_setzero_ps(), _mm512_setzero_ps()};
    __m512i en = _mm512_mullo_epi32(e, vn);
    for (int j = 0; j < n; j++) {
      __m512i idx = _mm512_add_epi32(en, _mm512_set1_epi32(j));
      __m512i off = _mm512_i32gather_epi32(idx, (const void *)pt->off, 4);
      __m512 fx = _mm512_i32gather_ps(idx, (const void *)pt->fx, 4);
      __m512 fy = _mm512_i32gather_ps(idx, (const void *)pt->fy, 4);
      __m512 wt = _mm512_i32gather_ps(idx, (const void *)pt->w, 4);
      __m512i a0 = _mm512_add_epi32(px, off);
      __m512i a1 = _mm512_add_epi32(a0, one), a2 = _mm512_add_epi32(a0, vw),
              a3 = _mm512_add_epi32(a0, vw1);
      for (int c = 0; c < nch; c++) {
        const float *S = src + (size_t)c * plane;
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
    for (int c = 0; c < nch; c++)
      _mm512_storeu_ps(dst + (size_t)c * plane + (size_t)y * w + x, acc[c]);
  }
  for (int xx = 0; xx < w; xx++)
    if (xx < r || xx >= x) ics_prop_pixel(pt, (int)ent[xx], src, dst, w, h, nch, xx, y);
}

TGT static void stencil_row(const ics_prop_taps *pt, const float *src, float *dst, int w, int h,
                            int nch, int y) {
  size_t plane = (size_t)w * h;
  int r = pt->reach, n = pt->ntaps;
  int x = r;
  for (int c = 0; c < nch; c++) {
    const float *S = src + (size_t)c * plane + (size_t)y * w;
    float *D = dst + (size_t)c * plane + (size_t)y * w;
    for (x = r; x + 16 <= w - r; x += 16) {
      __m512 acc = _mm512_setzero_ps();
      for (int j = 0; j < n; j++)
        acc = _mm512_fmadd_ps(_mm512_set1_ps(pt->w[j]), _mm512_loadu_ps(S + x + pt->off[j]), acc);
      _mm512_storeu_ps(D + x, acc);
    }
  }
  for (int xx = 0; xx < w; xx++)
    if (xx < r || xx >= x) ics_prop_pixel(pt, 0, src, dst, w, h, nch, xx, y);
}

TGT void ics_prop_rows_avx512(const ics_prop_taps *pt, const float *src, float *dst, int w, int h,
                              int nch, int y0, int y1, uint32_t *scratch) {
  int r = pt->reach;
  for (int y = y0; y < y1; y++) {
    int inside = y >= r && y < h - r && w > 2 * r + 16;
    if (pt->entries > 1) entries_row(pt, w, y, scratch);
    if (!inside) {
      for (int x = 0; x < w; x++)
        ics_prop_pixel(pt, pt->entries > 1 ? (int)scratch[x] : 0, src, dst, w, h, nch, x, y);
    } else if (pt->stencil) {
      stencil_row(pt, src, dst, w, h, nch, y);
    } else {
      table_row(pt, src, dst, w, h, nch, y, scratch);
    }
  }
}

#else
int ics_prop_avx512_available(void) { return 0; }
void ics_prop_rows_avx512(const ics_prop_taps *pt, const float *src, float *dst, int w, int h,
                          int nch, int y0, int y1, uint32_t *scratch) {
  (void)pt, (void)src, (void)dst, (void)w, (void)h, (void)nch, (void)y0, (void)y1, (void)scratch;
}
#endif
