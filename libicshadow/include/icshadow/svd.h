/* icshadow/svd.h — the singular value decomposition of a small dense matrix by one-sided
 * (Hestenes) Jacobi rotations, and its rank-N truncation: the low-rank approximation of the
 * smooth in-scattering integrand of 1D min-max mipmaps (Chen et al. 2011, Sec. 3.2; minmax.h).
 * Matrices are row-major doubles. Errors: ICS_ERR_INVALID_ARG (NULL), ICS_ERR_SIZE (n = 0,
 * m < n, m > 2^20 or n > 4096), ICS_ERR_NAN / ICS_ERR_INFINITE (an entry of A), ICS_ERR_RANGE
 * (no convergence; N > n for the truncation). */
#ifndef ICSHADOW_SVD_H
#define ICSHADOW_SVD_H

#include <stddef.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A (m x n, row-major, m >= n >= 1) = U diag(s) V^T with U m x n (orthonormal columns where
 * s > 0; columns of zero singular values are zero), s descending >= 0, V n x n orthogonal.
 * Hestenes one-sided Jacobi: rotate column pairs until every pair is orthogonal to
 * |<a_p, a_q>| <= eps ||a_p|| ||a_q||, eps = 2^-52. Measured (tests/test_minmax.c):
 * ||A - U S V^T||_F <= 10 n u ||A||_F and ||U^T U - I||, ||V^T V - I|| <= 10 n u (max entry).
 * A is scaled by a power of two internally, so any finite A works (entries up to DBL_MAX, or
 * tiny ones) as long as its singular values are finite: ICS_ERR_INFINITE if one exceeds DBL_MAX
 * (e.g. several entries near 1e308 in one column). ICS_ERR_RANGE only if 64 sweeps do not
 * converge. */
ICS_API ics_status ics_svd(const double *A, size_t m, size_t n, double *U, double *s, double *V);
/* A_N = sum_{i<N} s_i U_i V_i^T into out (m x n); N <= n. */
ICS_API ics_status ics_svd_truncate(const double *U, const double *s, const double *V, size_t m,
                                    size_t n, size_t N, double *out);

#ifdef __cplusplus
}
#endif
#endif
