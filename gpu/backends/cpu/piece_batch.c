/* piece_batch.c — a row's single-volume pieces and vec_math.h's functions (see piece_batch.h):
 * the vector build of the chosen path. */
#include "piece_batch.h"

void ics_piece_batch(const ics_piece_params *pp, const ics_piece_row *r, ics_simd_path simd) {
  switch (simd) {
  case ICS_SIMD_SSE2: ics_piece_batch_sse2(pp, r); break;
  case ICS_SIMD_NEON: ics_piece_batch_neon(pp, r); break;
  case ICS_SIMD_AVX2: ics_piece_batch_avx2(pp, r); break;
  case ICS_SIMD_AVX512: ics_piece_batch_avx512(pp, r); break;
  default: break;
  }
}

void ics_vec_math(int fn, const double *x, int n, double *out, ics_simd_path simd) {
  switch (simd) {
  case ICS_SIMD_SSE2: ics_vec_math_sse2(fn, x, n, out); break;
  case ICS_SIMD_NEON: ics_vec_math_neon(fn, x, n, out); break;
  case ICS_SIMD_AVX2: ics_vec_math_avx2(fn, x, n, out); break;
  case ICS_SIMD_AVX512: ics_vec_math_avx512(fn, x, n, out); break;
  default: break;
  }
}
