/* sat_build.h — the fused one-pass builders of the 2D and 3D summed-area tables, one per
 * accumulation type (private to libicshadow; defined in sat_build.c, used by sat.c).
 *
 * Input element (x, y, z) of the w x h x d data is in[z * sstride + y * stride + x]; the
 * inclusive table is written tightly packed, x fastest (d = 1: a 2D table). Each builder needs
 * a scratch buffer of ics_sat_scratch_bytes(mode, w, h, d) bytes (its own row accumulators,
 * x prefix block and previous-slice accumulator), allocated once per table so that a rebuild
 * does not allocate. Non-finite input or overflow propagates to the last row of the last
 * slice (sums never turn a non-finite value finite): the caller checks that row. */
#ifndef ICS_SAT_BUILD_H
#define ICS_SAT_BUILD_H

#include <stddef.h>

#include "icshadow/sat.h"

/* Scratch bytes of the builder of `mode` for a w x h x d table. */
size_t ics_sat_scratch_bytes(ics_sat_precision mode, size_t w, size_t h, size_t d);

/* float accumulation and storage of a - m (ICS_SAT_FLOAT: m = 0; ICS_SAT_FLOAT_OFFSET). */
void ics_sat_build_float(float *out, const float *in, size_t w, size_t h, size_t d,
                         size_t stride, size_t sstride, float m, void *scratch);
/* double accumulation and storage (ICS_SAT_DOUBLE). */
void ics_sat_build_double(double *out, const float *in, size_t w, size_t h, size_t d,
                          size_t stride, size_t sstride, void *scratch);
/* double-float pairs hi + lo in float arithmetic only (ICS_SAT_COMPENSATED). */
void ics_sat_build_compensated(float *hi, float *lo, const float *in, size_t w, size_t h,
                               size_t d, size_t stride, size_t sstride, void *scratch);

#endif
