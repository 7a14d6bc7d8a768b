/* icshadow/sat.h — summed-area tables (SATs) in 2D and 3D over float data and their precision
 * modes; the light-aligned 3D SATs of Ament et al. 2014 built on them are in csat.h
 * (directional lights) and ssat.h (point lights).
 *
 * CONVENTIONS (all SATs)
 * - Data are row-major floats: element (x, y) of a 2D table is data[y * stride + x], element
 *   (x, y, z) of a 3D table is data[(z * height + y) * width + x] (x fastest).
 * - The table is INCLUSIVE: S(x, y) = sum of a(i, j) over i <= x, j <= y; it has exactly the
 *   size of the data (no padding row/column).
 * - Boxes given to the box-sum functions are HALF-OPEN index ranges [x0, x1) x [y0, y1)
 *   (x [z0, z1)): x0 is the first cell inside, x1 one past the last. An empty box (x0 == x1)
 *   sums to 0. Four (2D) / eight (3D) table reads, constant time.
 * - Out-of-range boxes: ics_sat*_box_sum REJECTS them (ICS_ERR_RANGE when any bound lies
 *   outside [0, n]); ics_sat*_box_sum_clamped CLAMPS them to the table, i.e. treats every cell
 *   outside as 0 (the usual choice for filters near a border). An inverted box (x1 < x0) is
 *   ICS_ERR_INVALID_ARG in both. ics_sat*_integral takes CONTINUOUS coordinates (cell i covers
 *   [i, i+1)), clamps like _clamped, and is exact for the piecewise-constant field (the
 *   integral is multilinear inside a cell, so it is the multilinear interpolation of the SAT).
 * - Every result is returned as a double.
 *
 * PRECISION MODES (Hensley et al. 2005 discuss why float SATs fail): a SAT entry grows like
 * the number of cells times the mean value, so a float table of 4096^2 values near 1000 holds
 * numbers near 1.7e10 whose ulp is 2048 — a small box sum is then pure cancellation noise.
 *   ICS_SAT_FLOAT        float accumulation, float storage (4 bytes/cell).
 *   ICS_SAT_FLOAT_OFFSET float, but an offset m (the float-rounded mean of an evenly spaced
 *                        sample of <= 65536 cells) is subtracted before summing and
 *                        m * (box cells) is added back in double (Hensley's offset/bias):
 *                        the table holds a random walk instead of a ramp (4 bytes/cell).
 *   ICS_SAT_COMPENSATED  float arithmetic only, each entry a double-float pair hi + lo
 *                        (error-free TwoSum, ~48-bit significand) (8 bytes/cell).
 *   ICS_SAT_DOUBLE       double accumulation and storage (8 bytes/cell).
 * ERROR BOUND (the same number is in sat.c's header, docs/sat.md and tests/test_sat.c):
 *   |box_sum computed - exact| <= ics_sat_error_factor(mode, dims) * (x1 + y1 [+ z1] + 2^dims) * P
 * where dims is 2 or 3 and P is the sum of |a - m| over the prefix box [0, x1) x [0, y1)
 * [x [0, z1)] (m = the offset for ICS_SAT_FLOAT_OFFSET, 0 otherwise). The factor is
 * 2^dims * 1.01 * u with u = 2^-24 (float, float offset), 2^-44 (compensated: 16 u_float^2)
 * and 2^-53 (double): each of the 2^dims corner entries is a sum of depth <= x1 + y1 [+ z1]
 * (recursive-summation bound gamma_n), the 2^dims term covers the corner combination in double.
 * For clamped boxes the clamped coordinates count. ics_sat*_integral adds the rounding of the
 * interpolation weights (a few ulps of the double result).
 * LIMITS: every dimension >= 1, the cell count <= 2^31 (2D and 3D) and the table size <=
 * ICS_SAT_MAX_BYTES; otherwise ICS_ERR_SIZE. NaN or infinite data -> ICS_ERR_NAN /
 * ICS_ERR_INFINITE, float sums that overflow -> ICS_ERR_RANGE (detected after the pass; on
 * such an error from _rebuild the table is invalid and its box sums return
 * ICS_ERR_INVALID_ARG until a successful rebuild). NULL pointers -> ICS_ERR_INVALID_ARG.
 * Allocation failure -> ICS_ERR_NOMEM. Tables are opaque objects: ics_sat2d_create /
 * ics_sat3d_create make one (*out NULL on failure), ics_sat2d_destroy / ics_sat3d_destroy free
 * it (NULL is fine). The library is single-threaded; a built table may be read from several
 * threads at once. */
#ifndef ICSHADOW_SAT_H
#define ICSHADOW_SAT_H

#include <stddef.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_SAT_MAX_BYTES ((size_t)8 << 30) /* 8 GiB: larger tables are refused */
/* 64 GiB: a 2D input whose span (height - 1) * stride + width floats is larger (or overflows)
 * is refused (ICS_ERR_INVALID_ARG), like stride < width */
#define ICS_SAT_MAX_SPAN_BYTES ((size_t)64 << 30)

typedef enum ics_sat_precision {
  ICS_SAT_FLOAT = 0,
  ICS_SAT_FLOAT_OFFSET = 1,
  ICS_SAT_COMPENSATED = 2,
  ICS_SAT_DOUBLE = 3
} ics_sat_precision;
#define ICS_SAT_PRECISION_COUNT 4

/* "float", "float-offset", "compensated", "double"; NULL for an unknown mode. */
ICS_API const char *ics_sat_precision_name(ics_sat_precision mode);
/* Parse one of the names above; ICS_ERR_PARSE when unknown. */
ICS_API ics_status ics_sat_precision_parse(const char *name, ics_sat_precision *mode);
/* The error factor of the bound above for dims = 2 or 3 (NaN for an unknown mode or dims). */
ICS_API double ics_sat_error_factor(ics_sat_precision mode, int dims);
/* Bytes per table cell of a mode (4 or 8; 0 for an unknown mode). */
ICS_API size_t ics_sat_cell_bytes(ics_sat_precision mode);

/* ---- 2D ------------------------------------------------------------------------------ */
typedef struct ics_sat2d ics_sat2d;

/* Build the SAT of a width x height float image (row stride in elements, >= width, and the
 * input span (height - 1) * stride + width at most ICS_SAT_MAX_SPAN_BYTES / 4 floats; otherwise
 * ICS_ERR_INVALID_ARG). */
ICS_API ics_status ics_sat2d_create(ics_sat2d **out, const float *data, size_t width, size_t height,
                                    size_t stride, ics_sat_precision mode);
/* Recompute an existing table from new data of the same size (no allocation: the steady
 * state of a renderer whose transfer function or time step changes). */
ICS_API ics_status ics_sat2d_rebuild(ics_sat2d *sat, const float *data, size_t stride);
ICS_API void ics_sat2d_destroy(ics_sat2d *sat);
ICS_API void ics_sat2d_size(const ics_sat2d *sat, size_t *width, size_t *height);
ICS_API ics_sat_precision ics_sat2d_precision(const ics_sat2d *sat);
/* The offset m subtracted before summing (0 unless ICS_SAT_FLOAT_OFFSET). */
ICS_API double ics_sat2d_offset(const ics_sat2d *sat);

/* Sum over [x0, x1) x [y0, y1): rejected outside the table (ICS_ERR_RANGE). */
ICS_API ics_status ics_sat2d_box_sum(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                                     double *sum);
/* Same, cells outside the table count as 0 (any long bounds allowed, x0 <= x1, y0 <= y1). */
ICS_API ics_status ics_sat2d_box_sum_clamped(const ics_sat2d *sat, long x0, long y0, long x1,
                                             long y1, double *sum);
/* Mean over the part of the box inside the table (the box filter with border
 * renormalisation); ICS_ERR_RANGE when that part is empty. */
ICS_API ics_status ics_sat2d_box_mean_clamped(const ics_sat2d *sat, long x0, long y0, long x1,
                                              long y1, double *mean);
/* Integral of the piecewise-constant image over the continuous box [x0, x1] x [y0, y1]
 * (clamped: outside is 0). NaN bounds -> ICS_ERR_NAN, inverted -> ICS_ERR_INVALID_ARG. */
ICS_API ics_status ics_sat2d_integral(const ics_sat2d *sat, double x0, double y0, double x1,
                                      double y1, double *sum);
/* The inclusive table entry S(x, y) (0 <= x < width, 0 <= y < height), NaN outside. */
ICS_API double ics_sat2d_at(const ics_sat2d *sat, size_t x, size_t y);

/* ---- 3D ------------------------------------------------------------------------------ */
typedef struct ics_sat3d ics_sat3d;

/* Build the SAT of a width x height x depth float volume (tightly packed, x fastest). */
ICS_API ics_status ics_sat3d_create(ics_sat3d **out, const float *data, size_t width, size_t height,
                                    size_t depth, ics_sat_precision mode);
ICS_API ics_status ics_sat3d_rebuild(ics_sat3d *sat, const float *data);
ICS_API void ics_sat3d_destroy(ics_sat3d *sat);
ICS_API void ics_sat3d_size(const ics_sat3d *sat, size_t *width, size_t *height, size_t *depth);
ICS_API ics_sat_precision ics_sat3d_precision(const ics_sat3d *sat);
ICS_API double ics_sat3d_offset(const ics_sat3d *sat);
ICS_API ics_status ics_sat3d_box_sum(const ics_sat3d *sat, long x0, long y0, long z0, long x1,
                                     long y1, long z1, double *sum);
ICS_API ics_status ics_sat3d_box_sum_clamped(const ics_sat3d *sat, long x0, long y0, long z0,
                                             long x1, long y1, long z1, double *sum);
ICS_API ics_status ics_sat3d_integral(const ics_sat3d *sat, const double lo[3], const double hi[3],
                                      double *sum);
ICS_API double ics_sat3d_at(const ics_sat3d *sat, size_t x, size_t y, size_t z);

#ifdef __cplusplus
}
#endif
#endif
