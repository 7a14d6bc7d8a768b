/* fuzz_require.h — REQUIRE(c): the harnesses' invariant check; a broken invariant names itself on
 * stderr and aborts, which libFuzzer reports as a finding with its reproducer. */
#ifndef ICS_FUZZ_REQUIRE_H
#define ICS_FUZZ_REQUIRE_H

#include <stdio.h>
#include <stdlib.h>

#define REQUIRE(c)                                                                                \
  do {                                                                                            \
    if (!(c)) {                                                                                   \
      fprintf(stderr, "%s: invariant failed: %s\n", __FILE__, #c);                                \
      abort();                                                                                    \
    }                                                                                             \
  } while (0)

#endif
