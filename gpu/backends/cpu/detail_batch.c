/* detail_batch.c — the detail functions over many points (see detail_batch.h): the vector build
 * of the chosen path, or point by point. */
#include "detail_batch.h"

void ics_detail_batch(const ics_detail_eval *e, const double *x, const double *y, const double *z,
                      int n, double *out, ics_simd_path simd) {
  if (e->d->fn != ICS_DETAIL_GRID) {
    switch (simd) {
    case ICS_SIMD_SSE2: ics_detail_batch_sse2(e, x, y, z, n, out); return;
    case ICS_SIMD_NEON: ics_detail_batch_neon(e, x, y, z, n, out); return;
    case ICS_SIMD_AVX2: ics_detail_batch_avx2(e, x, y, z, n, out); return;
    case ICS_SIMD_AVX512: ics_detail_batch_avx512(e, x, y, z, n, out); return;
    default: break;
    }
  }
  for (int i = 0; i < n; i++) out[i] = ics_detail_value(e, (const double[3]){x[i], y[i], z[i]});
}
