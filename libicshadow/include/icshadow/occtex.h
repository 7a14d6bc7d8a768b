/* icshadow/occtex.h — occlusion textures (Eisemann & Décoret 2006, "Plausible image-based soft
 * shadows using occlusion textures"): a scene is cut into K slices parallel to a rectangular
 * light, each slice becomes an occlusion texture (fraction of each texel that is opaque), each
 * texture is prefiltered (mipmap, N-Buffers or summed-area table), and the shadow at a point P is
 * one box lookup per slice, of size s(P) = d(P, slice plane) / d(P, light plane) x size(light)
 * (their Eq. 4), combined over slices by 1 - prod(1 - O_k) (their Eq. 5), by a clamped sum or by
 * the maximum.
 *
 * Geometry conventions (the light's frame; see docs/occtex.md):
 *   - The light is the rectangle [cx - wx/2, cx + wx/2] x [cy - wy/2, cy + wy/2] in the plane
 *     z = 0. z is the distance from the light plane and grows away from the light; occluders
 *     and receivers have z > 0.
 *   - Occluders are opaque axis-aligned boxes (ics_occ_box); the texture grid is n x n square
 *     texels of side `texel`, texel (i, j) covering [x0 + i texel, x0 + (i+1) texel) x (same in y).
 *     Outside the grid the occlusion is 0.
 *   - Slice k (k = 0 .. K-1) is the z-range (z_k, z_{k+1}] with z_k = z_near + k (z_far - z_near)/K;
 *     everything in it is projected orthographically (along z) onto its bottom plane z_{k+1}, the
 *     plane farthest from the light (as in the paper, Sec. 3.4).
 *   - For a point P = (px, py, pz) the rays to the light cross the plane z = zo (0 < zo < pz) in
 *     the rectangle of centre (px, py) + t ((cx, cy) - (px, py)) and size t (wx, wy),
 *     t = (pz - zo) / pz: Eq. 4 (which gives the size only; the centre moves toward the light's
 *     centre unless the light is centred above P).
 *   - Shadow values are OCCLUSION: the fraction of the light hidden from P, in [0, 1]
 *     (visibility = 1 - occlusion). O_k(P) is the box average of slice k's texture.
 *   - Slice fading (the paper's self-shadowing fix, Sec. 3.4): slice k enters with the weight
 *     w_k(P) = clamp((pz - z_k) / (z_{k+1} - z_k), 0, 1): 0 for slices at or beyond P, 1 for slices
 *     entirely between the light and P, linear in the depth of P inside the slice containing it;
 *     t is clamped at 0 there (a point lookup at P when P lies above the slice's bottom plane).
 *     The faded contribution is w_k O_k.
 *
 * Prefilters (box lookups in texel units, centre (u, v), size (su, sv)):
 *   ICS_OCC_SAT       exact box average of the piecewise-constant texture (any real rectangle:
 *                     bilinear interpolation of the summed-area table is exact), to rounding.
 *   ICS_OCC_NBUFFERS  level l holds, at every texel, the average over the 2^l x 2^l box anchored
 *                     there (Décoret 2005); exact for power-of-two square boxes at any position
 *                     (bilinear interpolation of box responses with integer width is exact);
 *                     between levels linear in the box size. Extra memory ~ (log2 n + 5) n^2.
 *   ICS_OCC_MIPMAP    dyadic pyramid, trilinear (bilinear in a level, linear in log2 of the box
 *                     size between levels); exact for power-of-two square boxes aligned to the
 *                     level's texels.
 *   Rectangular boxes (for NBUFFERS and MIPMAP): the minor side picks the level and up to 16
 *   taps are spread along the major side (as anisotropic GPU filtering does).
 *
 * Everything that can fail returns an ics_status: ICS_ERR_INVALID_ARG (NULL pointer, unknown
 * enum, zero slices, z_near <= 0, z_far <= z_near, negative light size, box with x1 < x0 ...),
 * ICS_ERR_NAN (NaN in any coordinate), ICS_ERR_INFINITE, ICS_ERR_SIZE (n not a power of two in
 * 1..ICS_OCC_MAX_SIZE, slices > ICS_OCC_MAX_SLICES, slices x n^2 > ICS_OCC_MAX_TEXELS, a
 * prefilter over ICS_OCC_MAX_PREFILTER_BYTES, no receivers where some are required),
 * ICS_ERR_NOMEM, ICS_ERR_UNSUPPORTED (a prefilter that was not built). */
#ifndef ICSHADOW_OCCTEX_H
#define ICSHADOW_OCCTEX_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_OCC_MAX_SIZE 4096  /* texture side, texels */
#define ICS_OCC_MAX_SLICES 64
#define ICS_OCC_MAX_SUPERSAMPLE 16
#define ICS_OCC_MAX_LIGHT_SAMPLES 4096 /* per side, brute force */
#define ICS_OCC_MAX_TEXELS ((size_t)1 << 28) /* slices x n^2 (1 GiB of floats) */
#define ICS_OCC_MAX_PREFILTER_BYTES ((size_t)4 << 30) /* one prefilter, all slices */

typedef struct ics_occ_box { /* an opaque axis-aligned box [x0, x1] x [y0, y1] x [z0, z1] */
  double x0, y0, z0, x1, y1, z1;
} ics_occ_box;

typedef struct ics_occ_light { /* rectangle in z = 0: centre (cx, cy), sides wx, wy >= 0 */
  double cx, cy, wx, wy;
} ics_occ_light;

typedef struct ics_occ_grid { /* n x n texels of side `texel`, lower corner (x0, y0) */
  double x0, y0, texel;
  int n;
} ics_occ_grid;

typedef enum ics_occ_prefilter { ICS_OCC_MIPMAP, ICS_OCC_NBUFFERS, ICS_OCC_SAT, ICS_OCC_PREFILTER_COUNT } ics_occ_prefilter;
typedef enum ics_occ_combine { ICS_OCC_PRODUCT, ICS_OCC_SUM, ICS_OCC_MAX, ICS_OCC_COMBINE_COUNT } ics_occ_combine;

/* "mipmap", "nbuffers", "sat"; "product", "sum", "max" (NULL for an unknown value). */
ICS_API const char *ics_occtex_prefilter_name(ics_occ_prefilter pf);
ICS_API const char *ics_occtex_combine_name(ics_occ_combine c);

/* Synthetic sets of nboxes occluder boxes into out, deterministic in `seed`, inside x, y in
 * [-1, 1], z in [1, 2]:
 *   ICS_OCC_BOXES_FOLIAGE  nboxes small cubes (side 0.06 .. 0.16) scattered in a canopy;
 *   ICS_OCC_BOXES_PLATES   nboxes thin square plates (thickness 0.01) at random depths and sizes;
 *   ICS_OCC_BOXES_BLOCKS   nboxes larger blocks (sides 0.1 .. 0.5), overlapping in depth. */
typedef enum ics_occ_boxes_kind {
  ICS_OCC_BOXES_FOLIAGE,
  ICS_OCC_BOXES_PLATES,
  ICS_OCC_BOXES_BLOCKS
} ics_occ_boxes_kind;
ICS_API ics_status ics_occtex_boxes_make(ics_occ_boxes_kind kind, int nboxes, uint64_t seed,
                                         ics_occ_box *out);

/* Slice boxes into K occlusion textures tex[k n^2 + j n + i] (slice k, row j, column i): the
 * fraction of texel (i, j) covered by the orthographic projection of the union of the box parts
 * inside slice k, estimated with ss x ss sub-texel samples at the sub-cell centres (exact when
 * box edges fall on sub-cell edges). Boxes may overlap and extend outside the grid. */
ICS_API ics_status ics_occtex_slice_boxes(const ics_occ_box *boxes, size_t nboxes,
                                          const ics_occ_grid *grid, int slices, double z_near,
                                          double z_far, int ss, float *tex);

/* The occlusion-texture object: K textures + their prefilters (opaque). */
typedef struct ics_occtex ics_occtex;

/* Creates the object from K textures, copied (layout as in ics_occtex_slice_boxes; values must be
 * finite, clamped to [0, 1] on input), for slices between z_near and z_far; *out is NULL on
 * failure. No prefilter is built yet. ics_occtex_destroy frees it (NULL is fine). */
ICS_API ics_status ics_occtex_create(ics_occtex **out, const float *tex, const ics_occ_grid *grid,
                                     int slices, double z_near, double z_far);
ICS_API void ics_occtex_destroy(ics_occtex *ot);

/* Build one prefilter for every slice (again: rebuilds). */
ICS_API ics_status ics_occtex_prefilter(ics_occtex *ot, ics_occ_prefilter pf);

/* Box average of slice k's texture through prefilter pf: centre (u, v) and size (su, sv) >= 0 in
 * texel units (u = (x - x0)/texel). A zero-size box is a point lookup (the texel containing
 * (u, v) for SAT; level-0 bilinear filtering for the other two). */
ICS_API ics_status ics_occtex_box(const ics_occtex *ot, ics_occ_prefilter pf, int k, double u,
                                  double v, double su, double sv, double *out);

/* Occlusion at n points P[3 i .. 3 i + 2] = (x, y, z), z > 0, for the rectangular light, through
 * prefilter pf and combination c, with slice fading (see top). occ[i] in [0, 1]. */
ICS_API ics_status ics_occtex_shadow(const ics_occtex *ot, const ics_occ_light *light,
                                     ics_occ_prefilter pf, ics_occ_combine c, const double *P,
                                     size_t n, double *occ);

/* Per-slice contributions at one point (before combination): w[k] (fade weight) and o[k] (box
 * average), arrays of K. */
ICS_API ics_status ics_occtex_slices_at(const ics_occtex *ot, const ics_occ_light *light,
                                        ics_occ_prefilter pf, const double P[3], double *w,
                                        double *o);

/* Combine K faded contributions f[k] = w_k O_k in [0, 1]: product 1 - prod(1 - f_k), sum
 * min(1, sum f_k), or max f_k (k = 0: 0). NaN, for every combination alike, if c is unknown,
 * k < 0, f is NULL with k > 0, or any f_k is NaN or outside [0, 1] (not clamped: such a value
 * is a caller's error). ics_occtex_shadow clamps w_k O_k to [0, 1] (rounding) before calling. */
ICS_API double ics_occtex_combine_values(ics_occ_combine c, const double *f, int k);

ICS_API int ics_occtex_slices(const ics_occtex *ot);
/* Bottom plane z_{k+1} of slice k (NaN if k is out of range). */
ICS_API double ics_occtex_plane(const ics_occtex *ot, int k);

/* Brute-force reference: occlusion of the light seen from P (n points), by m x m rays to the
 * centres of an m x m grid of light cells, each tested against every box (slab test, boxes
 * closed). Midpoint-rule error: at most 2/m per straight shadow edge crossing the light. */
ICS_API ics_status ics_occtex_exact(const ics_occ_box *boxes, size_t nboxes,
                                    const ics_occ_light *light, int m, const double *P, size_t n,
                                    double *occ);

#ifdef __cplusplus
}
#endif
#endif
