/* rng.c — counter-based random numbers (Philox-4x32-10).
 *
 * Method: Salmon, Moraes, Dror, Shaw, "Parallel random numbers: as easy as 1, 2, 3" (SC 2011):
 * ten rounds of (two 32x32 -> 64 bit multiplies, xor with the key, word permutation), the key
 * bumped by the Weyl constants (0x9E3779B9, 0xBB67AE85) before rounds 2..10. Multipliers
 * 0xD2511F53, 0xCD9E8D57. Checked against the Random123 known-answer vectors
 * (tests/test_rng.c). Counter layout and the uniform / normal maps: icshadow/rng.h.
 * Normals: Box-Muller, cosine branch, on u1, u2 in [0, 1): r = sqrt(-2 log(1 - u1)) with
 * 1 - u1 in [2^-53, 1], so r <= sqrt(106 ln 2) = 8.57; exact distribution up to the 53-bit
 * quantisation of u1, u2 and libm's rounding. */
#include <math.h>

#include "icshadow/rng.h"
#include "icshadow/constants.h"

#define PHILOX_M0 UINT32_C(0xD2511F53)
#define PHILOX_M1 UINT32_C(0xCD9E8D57)
#define PHILOX_W0 UINT32_C(0x9E3779B9)
#define PHILOX_W1 UINT32_C(0xBB67AE85)

void ics_rng_philox4x32_10(const uint32_t ctr[4], const uint32_t key[2], uint32_t out[4]) {
  uint32_t c0 = ctr[0], c1 = ctr[1], c2 = ctr[2], c3 = ctr[3];
  uint32_t k0 = key[0], k1 = key[1];
  for (int r = 0; r < 10; r++) {
    if (r > 0) {
      k0 += PHILOX_W0;
      k1 += PHILOX_W1;
    }
    uint64_t p0 = (uint64_t)PHILOX_M0 * c0;
    uint64_t p1 = (uint64_t)PHILOX_M1 * c2;
    uint32_t hi0 = (uint32_t)(p0 >> 32), lo0 = (uint32_t)p0;
    uint32_t hi1 = (uint32_t)(p1 >> 32), lo1 = (uint32_t)p1;
    c0 = hi1 ^ c1 ^ k0;
    c1 = lo1;
    c2 = hi0 ^ c3 ^ k1;
    c3 = lo0;
  }
  out[0] = c0;
  out[1] = c1;
  out[2] = c2;
  out[3] = c3;
}

/* the two 64-bit words of counter block `block` (indices 2 block, 2 block + 1) */
static void u64_pair(uint64_t seed, uint64_t stream, uint64_t block, uint64_t w[2]) {
  uint32_t ctr[4] = {(uint32_t)block, (uint32_t)(block >> 32), (uint32_t)stream,
                     (uint32_t)(stream >> 32)};
  uint32_t key[2] = {(uint32_t)seed, (uint32_t)(seed >> 32)};
  uint32_t out[4];
  ics_rng_philox4x32_10(ctr, key, out);
  w[0] = (uint64_t)out[0] | ((uint64_t)out[1] << 32);
  w[1] = (uint64_t)out[2] | ((uint64_t)out[3] << 32);
}

uint64_t ics_rng_u64_at(uint64_t seed, uint64_t stream, uint64_t index) {
  uint64_t w[2];
  u64_pair(seed, stream, index >> 1, w);
  return w[index & 1];
}

static double u64_to_uniform(uint64_t x) { return (double)(x >> 11) * 0x1p-53; }

double ics_rng_uniform_at(uint64_t seed, uint64_t stream, uint64_t index) {
  return u64_to_uniform(ics_rng_u64_at(seed, stream, index));
}

void ics_rng_uniform_pair_at(uint64_t seed, uint64_t stream, uint64_t block, double out[2]) {
  uint64_t w[2];
  u64_pair(seed, stream, block, w);
  out[0] = u64_to_uniform(w[0]);
  out[1] = u64_to_uniform(w[1]);
}

void ics_rng_init(ics_rng *out, uint64_t seed, uint64_t stream) {
  if (!out) return;
  out->seed = seed;
  out->stream = stream;
  out->index = 0;
}

uint64_t ics_rng_next_u64(ics_rng *r) { return ics_rng_u64_at(r->seed, r->stream, r->index++); }

double ics_rng_uniform(ics_rng *r) { return u64_to_uniform(ics_rng_next_u64(r)); }

double ics_rng_normal(ics_rng *r) {
  double u1 = ics_rng_uniform(r);
  double u2 = ics_rng_uniform(r);
  return sqrt(-2.0 * log1p(-u1)) * cos(2 * ICS_PI * u2);
}
