/* fuzz_require.h — REQUIRE(c): the harnesses' invariant check; a broken invariant names itself on
 * stderr and aborts, which libFuzzer reports as a finding with its reproducer. require_light:
 * what every light a reader accepts must be (finite mean, positive-semidefinite covariance,
 * finite non-negative weight and colour). */
#ifndef ICS_FUZZ_REQUIRE_H
#define ICS_FUZZ_REQUIRE_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "icshadow/light.h"

#define REQUIRE(c)                                                                                \
  do {                                                                                            \
    if (!(c)) {                                                                                   \
      fprintf(stderr, "%s: invariant failed: %s\n", __FILE__, #c);                                \
      abort();                                                                                    \
    }                                                                                             \
  } while (0)

static inline void require_light(const ics_light *q) {
  REQUIRE(isfinite(q->mean[0]) && isfinite(q->mean[1]));
  REQUIRE(q->cov[0] >= 0 && q->cov[2] >= 0 && isfinite(q->cov[1]));
  REQUIRE(q->cov[1] * q->cov[1] <= q->cov[0] * q->cov[2] * (1 + 1e-9) + 1e-300);
  REQUIRE(isfinite(q->weight) && q->weight >= 0);
  for (int c = 0; c < 3; c++) REQUIRE(isfinite(q->color[c]) && q->color[c] >= 0);
}

#endif
