/* icshadow/minmax.h — 1D min-max mipmaps for volumetric shadows (Chen, Baran, Durand, Jarosz
 * 2011, "Real-Time Volumetric Shadows using 1D Min-Max Mipmaps"): the trees, their traversal,
 * the prefix sums they integrate and the brute-force ray march they are compared with. The
 * low-rank (SVD) approximation of the smooth integrand is in svd.h, the epipolar rectification
 * of a directional light's shadow map in epipolar.h, the synthetic height-field scene in
 * heightfield.h.
 *
 * Conventions (docs/minmax.md has the derivations):
 *  - A rectified shadow map has `rows` rows (epipolar slices, coordinate alpha) of d samples
 *    (gamma = 0 .. d-1, the light rays of the slice). S[row][gamma] is the occluder's height in
 *    the slice; here the light-space DEPTH of the first surface the light ray hits (distance
 *    from the light plane, growing away from the light).
 *  - A camera ray in a row is a line: its height at sample gamma is
 *        h(gamma) = beta0 + slope * gamma      (double, evaluated exactly so, no FMA)
 *    For Chen's own coordinates (S stores the occluder's beta angle, the ray has constant beta)
 *    use slope = 0. Sample gamma is LIT iff  S[gamma] > h(gamma)  (Chen Eq. 6: S[alpha,gamma] >
 *    beta); equality is shadow. The ray covers gamma in [0, gamma_end), gamma_end <= d
 *    (Chen's D(alpha, beta): where the ray meets the first surface).
 *  - Tree node classification (Chen Fig. 5, lines 7-10, generalised to a sloped ray): with
 *    [hmin, hmax] the ray's heights over the node's samples below gamma_end,
 *        hmax <  min(node)  -> fully lit   (add the prefix-sum difference)
 *        hmin >= max(node)  -> fully shadowed (skip)
 *        otherwise          -> descend.
 *    For slope = 0 this is exactly Chen's "beta < min: lit; beta >= max: shadowed; else
 *    recurse". h is monotone in gamma in floating point, so hmin/hmax are the endpoint values
 *    and the classification agrees with the per-sample test bit for bit.
 *  - Tree layout: per row a complete binary tree in Ahnentafel order, root at index 1, node k
 *    has children 2k, 2k+1; P = next power of two >= d leaves at indices P .. 2P-1. A row of
 *    d < P samples is padded by repeating its LAST sample, so every node's (min, max) equals the
 *    true min/max over its range clipped to [0, d) (tight), and nodes entirely past d are never
 *    visited because gamma_end <= d. Built level by level: log2 P passes.
 *  - Integration: prefix[i*ld + k] = sum_{g<k} Gamma_i(g) (k = 0..d), so a lit run [s, e)
 *    contributes prefix[e] - prefix[s]. Adjacent lit nodes are merged into one run before the
 *    prefix sums are read (Chen Sec. 3.5), so each maximal lit run costs 2 reads per term.
 *  - Accuracy: with ics_minmax_prefix (compensated), for each term i
 *        |tree_i - exact_i| <= (5 nseg + 1) u A_i,   u = 2^-53,  A_i = sum_{g<d} |Gamma_i(g)|,
 *    nseg = number of maximal lit runs (derivation in minmax.c). With integer Gamma (|sum| <
 *    2^53) both the tree and the march are exact: they agree to 0 ulps.
 * Functions return ICS_ERR_SIZE for empty or too large sizes, ICS_ERR_NAN for NaN inputs,
 * ICS_ERR_INFINITE for infinite ray parameters, ICS_ERR_INVALID_ARG for NULL pointers or
 * inconsistent arguments, ICS_ERR_RANGE for a row index out of range, ICS_ERR_NOMEM. */
#ifndef ICSHADOW_MINMAX_H
#define ICSHADOW_MINMAX_H

#include <stddef.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest accepted depth-sample count d and row count (and rows * 2P nodes <= 2^31). */
#define ICS_MINMAX_MAX_SAMPLES ((size_t)1 << 24)
#define ICS_MINMAX_MAX_ROWS ((size_t)1 << 20)

/* ---- the tree ------------------------------------------------------------------------ */
typedef struct ics_minmax ics_minmax; /* opaque: one min-max tree per row */

/* Build the trees of `rows` rows of d samples; row r starts at values + r * stride
 * (stride >= d; ICS_ERR_SIZE if (rows - 1) stride + d floats are not addressable). Values may
 * be +-inf, not NaN. */
ICS_API ics_status ics_minmax_create(ics_minmax **out, const float *values, size_t rows, size_t d,
                                     size_t stride);
ICS_API void ics_minmax_destroy(ics_minmax *t);
ICS_API size_t ics_minmax_rows(const ics_minmax *t);
ICS_API size_t ics_minmax_samples(const ics_minmax *t); /* d */
ICS_API size_t ics_minmax_leaves(const ics_minmax *t); /* P, the padded leaf count */
/* (min, max) stored at node k in [1, 2P) of a row, and the node's sample range [g0, g1)
 * clipped to [0, d) (g0 == g1 for nodes entirely in the padding). */
ICS_API ics_status ics_minmax_node(const ics_minmax *t, size_t row, size_t k, float *lo, float *hi);
ICS_API ics_status ics_minmax_node_range(const ics_minmax *t, size_t k, size_t *g0, size_t *g1);

/* A camera ray in one row: h(gamma) = beta0 + slope * gamma over gamma in [0, gamma_end). */
typedef struct ics_minmax_ray {
  double beta0;
  double slope;
  size_t gamma_end;
} ics_minmax_ray;

/* Node classes written by ics_minmax_segments (for figures): */
enum { ICS_MINMAX_UNVISITED = 0, ICS_MINMAX_LIT = 1, ICS_MINMAX_SHADOWED = 2, ICS_MINMAX_PARTIAL = 3 };

/* The traversal of Chen Fig. 5: the maximal lit runs [seg[2j], seg[2j+1]) of the ray, in
 * increasing order, and their count *nseg. At most maxseg runs are written; *nseg is the full
 * count (so a caller can retry with more room). node_class (NULL or 2P entries, zeroed by the
 * call) receives each visited node's class. */
ICS_API ics_status ics_minmax_segments(const ics_minmax *t, size_t row, const ics_minmax_ray *ray,
                                       size_t *seg, size_t maxseg, size_t *nseg,
                                       unsigned char *node_class);

/* The traversal with integration: out[i] = sum over lit samples of Gamma_i, read from prefix
 * sums prefix[i*ld + k] (k = 0..d, ld >= d+1), i < nterms. */
ICS_API ics_status ics_minmax_integrate(const ics_minmax *t, size_t row, const ics_minmax_ray *ray,
                                        const double *prefix, size_t nterms, size_t ld,
                                        double *out);

/* Compensated (Neumaier) prefix sums: prefix[i*ldp + k] = sum_{g<k} terms[i*ldt + g], k=0..d;
 * each is within u |prefix| + d^2 u^2 A of the exact sum. */
ICS_API ics_status ics_minmax_prefix(const double *terms, size_t nterms, size_t d, size_t ldt,
                                     double *prefix, size_t ldp);

/* Brute-force ray marching at the same resolution (the reference): visit every sample
 * gamma < gamma_end of `row` (d values), and where S > h(gamma) add terms[i*ldt + gamma] to
 * out[i] (plain summation in sample order). */
ICS_API ics_status ics_minmax_march(const float *row, size_t d, const ics_minmax_ray *ray,
                                    const double *terms, size_t nterms, size_t ldt, double *out);

#ifdef __cplusplus
}
#endif
#endif
