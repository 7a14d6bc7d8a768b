/* propagate_simd.h — the AVX-512 loops of the CPU slab step (propagate_avx512.c), chosen at run
 * time: the library is built for any x86-64 (or other) processor. */
#ifndef ICS_RENDER_PROPAGATE_SIMD_H
#define ICS_RENDER_PROPAGATE_SIMD_H

#include "propagate.h"

/* Tap sets up to this many are evaluated for every pixel and blended (no gathers). */
#define ICS_PROP_CANDIDATES_MAX 8

/* 1 when this processor has AVX-512 F/BW/DQ and the library was built with the loops. */
int ics_prop_avx512_available(void);
/* As ics_prop_rows for s = 1 and taps within the apron. */
void ics_prop_rows_avx512(const ics_prop_taps *pt, const float *src, float *dst,
                          const ics_buf_layout *L, int nch, int y0, int y1, uint32_t *scratch);

#endif
