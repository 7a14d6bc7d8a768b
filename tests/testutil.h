/* testutil.h — minimal assertion helpers for libicshadow's test programs.
 * CHECK prints the failing expression as text with a formatted explanation and counts the
 * failure; test_summary() prints "N passed, N failed" and gives the exit status. */
#ifndef ICS_TESTUTIL_H
#define ICS_TESTUTIL_H

#include <math.h>
#include <stdio.h>

static int test_passes_, test_failures_;

#define CHECK(cond, ...)                                                                   \
  do {                                                                                     \
    if (cond) {                                                                            \
      test_passes_++;                                                                      \
    } else {                                                                               \
      test_failures_++;                                                                    \
      fprintf(stderr, "%s:%d: CHECK(%s) failed: ", __FILE__, __LINE__, #cond);             \
      fprintf(stderr, __VA_ARGS__);                                                        \
      fputc('\n', stderr);                                                                 \
    }                                                                                      \
  } while (0)

/* Compensated (Kahan-Babuska-Neumaier) summation, for quadrature references in tests. */
typedef struct {
  double s, c;
} ksum;
static inline void kadd(ksum *k, double x) {
  double t = k->s + x;
  k->c += fabs(k->s) >= fabs(x) ? (k->s - t) + x : (x - t) + k->s;
  k->s = t;
}
static inline double kval(const ksum *k) { return k->s + k->c; }

static inline int test_summary(const char *name) {
  printf("%s: %d passed, %d failed\n", name, test_passes_, test_failures_);
  return test_failures_ ? 1 : 0;
}

#endif
