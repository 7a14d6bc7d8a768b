/* propagate_simd.h — the vector loops of the CPU slab step, one entry point per instruction set
 * (propagate_vec.h compiled by propagate_sse2.c, propagate_avx2.c, propagate_avx512.c,
 * propagate_neon.c), chosen at run time by simd_path.c: the library is built for any processor
 * of its architecture. */
#ifndef ICS_RENDER_PROPAGATE_SIMD_H
#define ICS_RENDER_PROPAGATE_SIMD_H

#include "propagate.h"

/* Tap sets up to this many are evaluated for every pixel and blended (no gathers). */
#define ICS_PROP_CANDIDATES_MAX 8

/* 1 when the compiler built that file's loops (its instruction set is this architecture's). */
extern const int ics_prop_built_sse2, ics_prop_built_avx2, ics_prop_built_avx512,
    ics_prop_built_neon;

/* As ics_prop_span for s = 1 and taps within the apron, or for a perspective step (pt->classes:
 * lanes reading beyond the apron clamp); call only where ics_simd_has says the processor has
 * the instructions. */
#define ICS_PROP_ROWS_DECLARE_(isa)                                                                \
  void ics_prop_rows_##isa(const ics_prop_taps *pt, const float *src, float *dst,                  \
                           const ics_buf_layout *L, int nch, int y0, int y1, int x0, int x1,       \
                           uint32_t *scratch);
ICS_PROP_ROWS_DECLARE_(sse2)
ICS_PROP_ROWS_DECLARE_(avx2)
ICS_PROP_ROWS_DECLARE_(avx512)
ICS_PROP_ROWS_DECLARE_(neon)
#undef ICS_PROP_ROWS_DECLARE_

/* What a file builds where the compiler does not target its instruction set: the path recorded
 * as not built, and an entry point that nothing calls. */
#define ICS_PROP_NOT_BUILT(isa)                                                                    \
  const int ics_prop_built_##isa = 0;                                                              \
  void ics_prop_rows_##isa(const ics_prop_taps *pt, const float *src, float *dst,                  \
                           const ics_buf_layout *L, int nch, int y0, int y1, int x0, int x1,       \
                           uint32_t *scratch) {                                                    \
    (void)pt, (void)src, (void)dst, (void)L, (void)nch, (void)y0, (void)y1, (void)x0, (void)x1;    \
    (void)scratch;                                                                                 \
  }

#endif
