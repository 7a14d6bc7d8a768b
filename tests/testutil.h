/* testutil.h — minimal assertion helpers for libicshadow's test programs.
 * CHECK prints the failing expression as text with a formatted explanation and counts the
 * failure; test_summary() prints "N passed, N failed" and gives the exit status. */
#ifndef ICS_TESTUTIL_H
#define ICS_TESTUTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

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

/* Reproducible random numbers: splitmix64 (Steele, Lea, Flood 2014) on one state per test
 * program, seeded with the golden-ratio increment (a test may xor a seed from argv into it). */
static uint64_t test_rng_state = 0x9E3779B97F4A7C15ull;
static inline uint64_t test_rng_u64(void) {
  uint64_t z = (test_rng_state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
/* Uniform in [0, 1), 53 random bits. */
static inline double test_rng_unit(void) { return (double)(test_rng_u64() >> 11) * 0x1p-53; }

static inline int test_summary(const char *name) {
  printf("%s: %d passed, %d failed\n", name, test_passes_, test_failures_);
  return test_failures_ ? 1 : 0;
}

/* the whole file as a NUL-terminated string (malloc'd), or NULL */
static inline char *test_read_text(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  long n = ftell(f);
  fseek(f, 0, SEEK_SET);
  char *s = n >= 0 ? malloc((size_t)n + 1) : NULL;
  if (s && fread(s, 1, (size_t)n, f) != (size_t)n) {
    free(s);
    s = NULL;
  }
  if (s) s[n] = 0;
  fclose(f);
  return s;
}

#endif
