/* svd.c — one-sided Jacobi SVD and its truncation (see icshadow/svd.h).
 *
 * Method: Hestenes one-sided Jacobi on the columns of A (m >= n): for each pair (p, q) compute
 * alpha = |a_p|^2, beta = |a_q|^2, gamma = <a_p, a_q>; if |gamma| > eps sqrt(alpha beta), rotate
 * by the angle that zeroes gamma (Rutishauser's stable tan formula), apply the same rotation to
 * V. Sweep until no rotation happens (quadratic convergence, typically 6-10 sweeps for 64 x 64).
 * s_j = |a_j|, U_j = a_j / s_j, sorted descending. */
#include "icshadow/svd.h"

#include <float.h>
#include <math.h>

ics_status ics_svd(const double *A, size_t m, size_t n, double *U, double *s, double *V) {
  if (!A || !U || !s || !V) return ICS_ERR_INVALID_ARG;
  if (n == 0 || m < n || m > ((size_t)1 << 20) || n > 4096) return ICS_ERR_SIZE;
  for (size_t i = 0; i < m * n; i++) {
    if (isnan(A[i])) return ICS_ERR_NAN;
    if (isinf(A[i])) return ICS_ERR_INFINITE;
  }
  /* work on W = A 2^-e (columns rotated in place), stored in U: scaling by a power of two
   * (exact, apart from entries that become subnormal, far below u max|A|) puts the largest
   * entry in [1/2, 1), so the squared column norms neither overflow nor underflow */
  double amax = 0;
  for (size_t i = 0; i < m * n; i++) amax = fmax(amax, fabs(A[i]));
  int e = 0;
  if (amax > 0) frexp(amax, &e);
  for (size_t i = 0; i < m * n; i++) U[i] = ldexp(A[i], -e);
  for (size_t i = 0; i < n * n; i++) V[i] = 0.0;
  for (size_t i = 0; i < n; i++) V[i * n + i] = 1.0;
  const double eps = DBL_EPSILON;
  int converged = 0;
  for (int sweep = 0; sweep < 64 && !converged; sweep++) {
    converged = 1;
    for (size_t p = 0; p + 1 < n; p++)
      for (size_t q = p + 1; q < n; q++) {
        double al = 0, be = 0, ga = 0;
        for (size_t i = 0; i < m; i++) {
          double x = U[i * n + p], y = U[i * n + q];
          al += x * x;
          be += y * y;
          ga += x * y;
        }
        if (ga == 0.0 || fabs(ga) <= eps * sqrt(al) * sqrt(be)) continue;
        converged = 0;
        double zeta = (be - al) / (2.0 * ga);
        double tn = (zeta >= 0 ? 1.0 : -1.0) / (fabs(zeta) + sqrt(1.0 + zeta * zeta));
        double c = 1.0 / sqrt(1.0 + tn * tn), sn = c * tn;
        for (size_t i = 0; i < m; i++) {
          double x = U[i * n + p], y = U[i * n + q];
          U[i * n + p] = c * x - sn * y;
          U[i * n + q] = sn * x + c * y;
        }
        for (size_t i = 0; i < n; i++) {
          double x = V[i * n + p], y = V[i * n + q];
          V[i * n + p] = c * x - sn * y;
          V[i * n + q] = sn * x + c * y;
        }
      }
  }
  if (!converged) return ICS_ERR_RANGE;
  for (size_t j = 0; j < n; j++) {
    double nn = 0;
    for (size_t i = 0; i < m; i++) nn = hypot(nn, U[i * n + j]);
    s[j] = ldexp(nn, e);
    for (size_t i = 0; i < m; i++) U[i * n + j] = nn > 0 ? U[i * n + j] / nn : 0.0;
  }
  for (size_t j = 0; j < n; j++)
    if (isinf(s[j])) return ICS_ERR_INFINITE; /* a singular value above DBL_MAX */
  /* selection sort by descending s, swapping columns of U and V */
  for (size_t j = 0; j < n; j++) {
    size_t b = j;
    for (size_t k = j + 1; k < n; k++)
      if (s[k] > s[b]) b = k;
    if (b == j) continue;
    double tmp = s[j];
    s[j] = s[b];
    s[b] = tmp;
    for (size_t i = 0; i < m; i++) {
      tmp = U[i * n + j];
      U[i * n + j] = U[i * n + b];
      U[i * n + b] = tmp;
    }
    for (size_t i = 0; i < n; i++) {
      tmp = V[i * n + j];
      V[i * n + j] = V[i * n + b];
      V[i * n + b] = tmp;
    }
  }
  return ICS_OK;
}

ics_status ics_svd_truncate(const double *U, const double *s, const double *V, size_t m, size_t n,
                            size_t N, double *out) {
  if (!U || !s || !V || !out) return ICS_ERR_INVALID_ARG;
  if (n == 0 || m < n) return ICS_ERR_SIZE;
  if (N > n) return ICS_ERR_RANGE;
  for (size_t i = 0; i < m; i++)
    for (size_t j = 0; j < n; j++) {
      double acc = 0;
      for (size_t k = 0; k < N; k++) acc += s[k] * U[i * n + k] * V[j * n + k];
      out[i * n + j] = acc;
    }
  return ICS_OK;
}
