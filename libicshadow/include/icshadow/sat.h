/* icshadow/sat.h — summed-area tables (SATs) in 2D and 3D over float data, and the
 * light-aligned 3D SATs of Ament et al. 2014 (CSAT for directional lights, SSAT for point
 * lights) that give box-filtered optical depth and transmittance in constant time.
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
 * Allocation failure -> ICS_ERR_NOMEM. Objects are opaque; free with the matching _free
 * (NULL is fine). The library is single-threaded; a built table may be read from several
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
const char *ics_sat_precision_name(ics_sat_precision mode);
/* Parse one of the names above; ICS_ERR_PARSE when unknown. */
ics_status ics_sat_precision_parse(const char *name, ics_sat_precision *mode);
/* The error factor of the bound above for dims = 2 or 3 (NaN for an unknown mode or dims). */
double ics_sat_error_factor(ics_sat_precision mode, int dims);
/* Bytes per table cell of a mode (4 or 8; 0 for an unknown mode). */
size_t ics_sat_cell_bytes(ics_sat_precision mode);

/* ---- 2D ------------------------------------------------------------------------------ */
typedef struct ics_sat2d ics_sat2d;

/* Build the SAT of a width x height float image (row stride in elements, >= width, and the
 * input span (height - 1) * stride + width at most ICS_SAT_MAX_SPAN_BYTES / 4 floats; otherwise
 * ICS_ERR_INVALID_ARG). */
ics_status ics_sat2d_build(ics_sat2d **out, const float *data, size_t width, size_t height,
                           size_t stride, ics_sat_precision mode);
/* Recompute an existing table from new data of the same size (no allocation: the steady
 * state of a renderer whose transfer function or time step changes). */
ics_status ics_sat2d_rebuild(ics_sat2d *sat, const float *data, size_t stride);
void ics_sat2d_free(ics_sat2d *sat);
void ics_sat2d_size(const ics_sat2d *sat, size_t *width, size_t *height);
ics_sat_precision ics_sat2d_precision(const ics_sat2d *sat);
/* The offset m subtracted before summing (0 unless ICS_SAT_FLOAT_OFFSET). */
double ics_sat2d_offset(const ics_sat2d *sat);

/* Sum over [x0, x1) x [y0, y1): rejected outside the table (ICS_ERR_RANGE). */
ics_status ics_sat2d_box_sum(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                             double *sum);
/* Same, cells outside the table count as 0 (any long bounds allowed, x0 <= x1, y0 <= y1). */
ics_status ics_sat2d_box_sum_clamped(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                                     double *sum);
/* Mean over the part of the box inside the table (the box filter with border
 * renormalisation); ICS_ERR_RANGE when that part is empty. */
ics_status ics_sat2d_box_mean_clamped(const ics_sat2d *sat, long x0, long y0, long x1, long y1,
                                      double *mean);
/* Integral of the piecewise-constant image over the continuous box [x0, x1] x [y0, y1]
 * (clamped: outside is 0). NaN bounds -> ICS_ERR_NAN, inverted -> ICS_ERR_INVALID_ARG. */
ics_status ics_sat2d_integral(const ics_sat2d *sat, double x0, double y0, double x1, double y1,
                              double *sum);
/* The inclusive table entry S(x, y) (0 <= x < width, 0 <= y < height), NaN outside. */
double ics_sat2d_at(const ics_sat2d *sat, size_t x, size_t y);

/* ---- 3D ------------------------------------------------------------------------------ */
typedef struct ics_sat3d ics_sat3d;

/* Build the SAT of a width x height x depth float volume (tightly packed, x fastest). */
ics_status ics_sat3d_build(ics_sat3d **out, const float *data, size_t width, size_t height,
                           size_t depth, ics_sat_precision mode);
ics_status ics_sat3d_rebuild(ics_sat3d *sat, const float *data);
void ics_sat3d_free(ics_sat3d *sat);
void ics_sat3d_size(const ics_sat3d *sat, size_t *width, size_t *height, size_t *depth);
ics_sat_precision ics_sat3d_precision(const ics_sat3d *sat);
double ics_sat3d_offset(const ics_sat3d *sat);
ics_status ics_sat3d_box_sum(const ics_sat3d *sat, long x0, long y0, long z0, long x1, long y1,
                             long z1, double *sum);
ics_status ics_sat3d_box_sum_clamped(const ics_sat3d *sat, long x0, long y0, long z0, long x1,
                                     long y1, long z1, double *sum);
ics_status ics_sat3d_integral(const ics_sat3d *sat, const double lo[3], const double hi[3],
                              double *sum);
double ics_sat3d_at(const ics_sat3d *sat, size_t x, size_t y, size_t z);

/* ---- Volumes and light-aligned SATs (Ament et al. 2014) ------------------------------- */
/* An extinction volume sigma_t: nx x ny x nz floats (x fastest), unit voxels, world
 * coordinates in voxel units: voxel (i, j, k) covers [i, i+1) x [j, j+1) x [k, k+1) and its
 * value sits at the centre (i + 1/2, j + 1/2, k + 1/2). sigma_t(p) is the trilinear
 * interpolation (clamp-to-edge indices) inside the box [0, nx] x [0, ny] x [0, nz] and 0
 * outside. The view does not own the data. */
typedef struct ics_volume {
  const float *data;
  size_t nx, ny, nz;
} ics_volume;

/* sigma_t at a world point (0 outside the volume box). */
double ics_volume_sample(const ics_volume *vol, const double p[3]);

/* CSAT: a 3D SAT in a frame (r_u, r_v, r_w) with r_u x r_v = r_w = l, the unit vector toward
 * a directional light. The grid has cubic cells of edge h, is centred on the volume centre and
 * covers the volume's bounding box seen in that frame; each cell holds sigma_t(cell centre) *
 * h^3. The box-filtered optical depth at p for a square filter patch of half-width U facing
 * the light (Ament Eq. 12-13) is
 *   tau_bar(p) = CSAT(C) / A,  C = {p + u r_u + v r_v + w l : |u|, |v| <= U, w >= 0},
 *   A = (2U)^2,
 * evaluated with ics_sat3d_integral in constant time, independent of U. U = 0 is the
 * unfiltered limit and is evaluated as the integral over a patch of half-width h/2 (one cell
 * column) The cell edge h must not exceed the volume's extent along any frame
 * axis (the projected box size): larger cells would lie mostly outside the volume yet carry
 * sigma_t of their centre (h = 1e6 gave tau = 5e4 on a 16^3 volume of sigma 0.1) ->
 * ICS_ERR_RANGE. */
typedef struct ics_csat ics_csat;

/* Frame from l alone (r_u chosen deterministically, perpendicular to l). */
ics_status ics_csat_build(ics_csat **out, const ics_volume *vol, const double light_dir[3],
                          double h, ics_sat_precision mode);
/* Explicit orthonormal frame (checked to 1e-9; r_w = r_u x r_v is the primary light). */
ics_status ics_csat_build_frame(ics_csat **out, const ics_volume *vol, const double r_u[3],
                                const double r_v[3], double h, ics_sat_precision mode);
void ics_csat_free(ics_csat *csat);
/* Frame vectors and grid size (cells along u, v, w). Any output pointer may be NULL. */
void ics_csat_frame(const ics_csat *csat, double r_u[3], double r_v[3], double r_w[3],
                    size_t n[3]);

/* The six orthodirectional lights of one CSAT (Ament Eq. 14-15). */
typedef enum ics_csat_light {
  ICS_CSAT_PLUS_W = 0, /* l = +r_w: the primary light */
  ICS_CSAT_MINUS_W = 1,
  ICS_CSAT_PLUS_U = 2,
  ICS_CSAT_MINUS_U = 3,
  ICS_CSAT_PLUS_V = 4,
  ICS_CSAT_MINUS_V = 5
} ics_csat_light;
/* The world direction toward light `which` (unit vector). */
ics_status ics_csat_light_dir(const ics_csat *csat, ics_csat_light which, double dir[3]);

/* Box-filtered optical depth tau_bar at world point p for light `which`, half-width U >= 0
 * (world units). NaN p or U -> ICS_ERR_NAN, U < 0 -> ICS_ERR_INVALID_ARG. */
ics_status ics_csat_tau(const ics_csat *csat, ics_csat_light which, const double p[3],
                        double half_width, double *tau);
/* exp(-tau_bar): the filtered transmittance. */
ics_status ics_csat_transmittance(const ics_csat *csat, ics_csat_light which, const double p[3],
                                  double half_width, double *transmittance);

/* Reference: the same filtered optical depth by brute-force shadow-ray marching through the
 * original volume (trilinear sigma_t): an n_patch x n_patch grid of rays on the patch
 * (midpoint rule), each marched toward `dir` with step `step` (midpoint rule) until it leaves
 * the volume box. U = 0 marches the single ray through p. */
ics_status ics_tau_bruteforce_directional(const ics_volume *vol, const double r_u[3],
                                          const double r_v[3], const double dir[3],
                                          const double p[3], double half_width, int n_patch,
                                          double step, double *tau);

/* SSAT: a 3D SAT in spherical coordinates (phi, theta, r) around a point light at x_L, in a
 * frame (e_x, e_y, e_z) derived from the light and the volume alone: e_x points from x_L to the
 * volume centre, the polar axis e_z is the world axis least aligned with e_x (orthogonalised),
 * e_y = e_z x e_x; a light exactly at the volume centre keeps the world axes. Direction
 * (phi, theta) is sin(theta) (cos(phi) e_x + sin(phi) e_y) + cos(theta) e_z: the volume lies
 * around phi = 0, theta = pi/2, away from the poles and the phi seam, whenever the light is
 * outside it. phi in [-pi, pi), theta in [0, pi], r in [0, r_max] with r_max the largest
 * distance from x_L to a volume corner. Cell (i, j, k) holds sigma_t(cell centre) *
 * dphi (cos(theta_j) - cos(theta_j+1)) dr (exact cell solid angle times dr), so a box sum
 * divided by the box's solid angle is the SOLID-ANGLE AVERAGE of the optical depth of the
 * rays from x_L through the box (the ray average that Eq. 23-24 approximate by dividing a
 * volume sum by the patch area A; see docs/sat.md). Inside a theta cell the box edge is
 * placed in cos(theta) (the solid angle is linear in cos(theta), not in theta), so a lookup is
 * the exact solid-angle integral of the cell-wise constant resampled field, also at the poles.
 * Light farther than ICS_SSAT_MAX_DISTANCE volume diagonals from the farthest volume corner,
 * or at an infinite coordinate -> ICS_ERR_RANGE (ray positions would lose all precision);
 * NaN light -> ICS_ERR_NAN. */
#define ICS_SSAT_MAX_DISTANCE 4294967296.0 /* 2^32 volume diagonals */
typedef struct ics_ssat ics_ssat;
ics_status ics_ssat_build(ics_ssat **out, const ics_volume *vol, const double light_pos[3],
                          size_t n_phi, size_t n_theta, size_t n_r, ics_sat_precision mode);
void ics_ssat_free(ics_ssat *ssat);
/* Frame axes and grid size (cells along phi, theta, r). Any output pointer may be NULL. */
void ics_ssat_frame(const ics_ssat *ssat, double e_x[3], double e_y[3], double e_z[3],
                    size_t n[3]);
/* tau_bar at p for a square patch of half-width U at p facing the light: the angular box
 * phi_p +- min(atan(U/R) / sin(theta_p), pi), theta_p +- atan(U/R) clamped to [0, pi]
 * (R = |p - x_L|), r in [0, R]. When the phi half-width reaches pi (the patch covers a pole)
 * the box is the polar cap over the whole ring; otherwise phi wraps around at +-pi (two SAT
 * lookups). Constant time. Needs U > 0 (ICS_ERR_INVALID_ARG otherwise); p at the light (or
 * so far that |p - x_L| overflows) -> ICS_ERR_RANGE. */
ics_status ics_ssat_tau(const ics_ssat *ssat, const double p[3], double half_width, double *tau);
ics_status ics_ssat_transmittance(const ics_ssat *ssat, const double p[3], double half_width,
                                  double *transmittance);
/* Reference for the SSAT: n_patch x n_patch rays over the same angular box in the same frame
 * (derived from vol and light_pos as in ics_ssat_build; midpoint in phi and in cos(theta),
 * i.e. uniform in solid angle), each marched from the light to radius R with step `step`,
 * averaged. The same light limit as ics_ssat_build (ICS_ERR_RANGE). */
ics_status ics_tau_bruteforce_point(const ics_volume *vol, const double light_pos[3],
                                    const double p[3], double half_width, int n_patch,
                                    double step, double *tau);

#ifdef __cplusplus
}
#endif
#endif
