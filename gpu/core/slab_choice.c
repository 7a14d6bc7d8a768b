/* slab_choice.c — the per-pixel tap-set choice (slab_choice.h): Philox-4x32-10 words by block of
 * 64 pixels, or of 64 n where a word packs n choices. */
#include "slab_choice.h"

#include "icshadow/rng.h"

void ics_slab_entry_block(uint64_t seed, uint32_t light, uint32_t slab, uint32_t block,
                          uint32_t out[4]) {
  const uint32_t key[2] = {(uint32_t)seed, (uint32_t)(seed >> 32)};
  const uint32_t ctr[4] = {block, slab, light, 0x736c6162u /* "slab" */};
  ics_rng_philox4x32_10(ctr, key, out);
}

uint32_t ics_slab_entry(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel) {
  return ics_slab_choice(seed, light, slab, pixel, ICS_SLAB_TABLE_M);
}

/* word i of block `block` */
uint32_t ics_slab_entry_word(uint64_t seed, uint32_t light, uint32_t slab, uint32_t block, int i) {
  uint32_t w[4];
  ics_slab_entry_block(seed, light, slab, block, w);
  return w[i];
}

uint32_t ics_slab_choice(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel, uint32_t k) {
  return ics_k_pixel_choice(seed, light, slab, pixel, k, 0, 1);
}

uint32_t ics_slab_pixel_choice(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel,
                               uint32_t k) {
  return ics_k_pixel_choice(seed, light, slab, pixel, k, ics_slab_choice_bits(k), ics_slab_choice_chunks(k));
}
