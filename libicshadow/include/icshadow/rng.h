/* icshadow/rng.h — counter-based random numbers: reproducible stochastic kernels.
 *
 * Generator: Philox-4x32-10 (Salmon, Moraes, Dror, Shaw, "Parallel random numbers: as easy as
 * 1, 2, 3", SC 2011), a keyed bijection of a 128-bit counter; verified against the Random123
 * known-answer vectors (tests/test_rng.c). Every number is a pure function of
 * (seed, stream, index): no hidden state, so a stochastic kernel's taps for iteration i depend
 * on (seed, i) only, never on how many numbers other iterations or other kernels drew.
 *
 * Layout: key = (seed low 32 bits, seed high 32 bits); counter words
 * (block low, block high, stream low, stream high) with block = index / 2; the 128-bit output
 * gives two 64-bit words (out0 | out1 << 32 for index even, out2 | out3 << 32 for index odd).
 * Uniform doubles take the top 53 bits: u = (x >> 11) * 2^-53, in [0, 1 - 2^-53].
 * Standard normals: Box-Muller on two consecutive uniforms (cosine branch only),
 * sqrt(-2 ln(1 - u1)) cos(2 pi u2); finite for every input (1 - u1 >= 2^-53, |z| <= 8.58). */
#ifndef ICSHADOW_RNG_H
#define ICSHADOW_RNG_H

#include <stdint.h>

#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The raw Philox-4x32-10 bijection (Random123 word order). */
ICS_API void ics_rng_philox4x32_10(const uint32_t ctr[4], const uint32_t key[2], uint32_t out[4]);

/* Stateless draws: the index-th 64-bit word / uniform of stream `stream` under `seed`. */
ICS_API uint64_t ics_rng_u64_at(uint64_t seed, uint64_t stream, uint64_t index);
ICS_API double ics_rng_uniform_at(uint64_t seed, uint64_t stream, uint64_t index);
/* The uniforms at indices 2 block and 2 block + 1 (block < 2^63) into out[0], out[1]: the values
 * of ics_rng_uniform_at there, from one Philox call. */
ICS_API void ics_rng_uniform_pair_at(uint64_t seed, uint64_t stream, uint64_t block, double out[2]);

/* A cursor over one stream: next draws words index, index + 1, ... (the state is only the
 * cursor; two cursors on the same (seed, stream, index) give the same numbers). */
typedef struct ics_rng {
  uint64_t seed;
  uint64_t stream;
  uint64_t index;
} ics_rng;

/* Fills *out with the cursor at index 0 of stream `stream` under `seed`. */
ICS_API void ics_rng_init(ics_rng *out, uint64_t seed, uint64_t stream);
ICS_API uint64_t ics_rng_next_u64(ics_rng *r);
ICS_API double ics_rng_uniform(ics_rng *r); /* [0, 1), 53 bits, consumes 1 word */
ICS_API double ics_rng_normal(ics_rng *r); /* standard normal, consumes 2 words */

#ifdef __cplusplus
}
#endif
#endif
