/* detail_batch.h — the volume detail functions (core/detail.h: improved noise, fBm, ridged
 * multifractal) at many points at once, in the vector paths of simd_path.h (detail_vec.h, one
 * build per instruction set): bit for bit ics_detail_value, whose double operations they repeat
 * lane by lane in the same order with no contraction into fused multiply-adds. */
#ifndef ICS_RENDER_DETAIL_BATCH_H
#define ICS_RENDER_DETAIL_BATCH_H

#include "detail.h"
#include "simd_path.h"

/* out[i] = ics_detail_value(e, (x[i], y[i], z[i])) for i < n; grids (and the scalar path) point
 * by point. */
void ics_detail_batch(const ics_detail_eval *e, const double *x, const double *y, const double *z,
                      int n, double *out, ics_simd_path simd);

/* The vector builds (detail_sse2.c, detail_avx2.c, detail_avx512.c, detail_neon.c): noise
 * functions only (not grids); call only where ics_simd_has says the processor has the path. */
#define ICS_DETAIL_BATCH_DECLARE_(isa)                                                             \
  void ics_detail_batch_##isa(const ics_detail_eval *e, const double *x, const double *y,         \
                              const double *z, int n, double *out);
ICS_DETAIL_BATCH_DECLARE_(sse2)
ICS_DETAIL_BATCH_DECLARE_(avx2)
ICS_DETAIL_BATCH_DECLARE_(avx512)
ICS_DETAIL_BATCH_DECLARE_(neon)
#undef ICS_DETAIL_BATCH_DECLARE_

/* What a file builds where the compiler does not target its instruction set. */
#define ICS_DETAIL_NOT_BUILT(isa)                                                                  \
  void ics_detail_batch_##isa(const ics_detail_eval *e, const double *x, const double *y,         \
                              const double *z, int n, double *out) {                              \
    (void)e, (void)x, (void)y, (void)z, (void)n, (void)out;                                        \
  }

#endif
