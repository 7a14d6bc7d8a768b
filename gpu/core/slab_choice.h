/* slab_choice.h — which tap set a pixel takes at a slab: counter-based random words per pixel,
 * slab and light (Philox-4x32-10, icshadow/rng.h; a word per choice, or several choices packed
 * in one where the candidates are few), the same in every backend and on every vector path
 * (docs/renderer.md "The light buffers"). */
#ifndef ICS_RENDER_SLAB_CHOICE_H
#define ICS_RENDER_SLAB_CHOICE_H

#include <stdint.h>

#include "kernel/device_layout.h"
#define ICS_VIEW_PARAM uint64_t seed,
#define ICS_VIEW_ARG seed,
#define ICS_SLAB_WORD(light, slab, block, i) ics_slab_entry_word(seed, light, slab, block, i)
uint32_t ics_slab_entry_word(uint64_t seed, uint32_t light, uint32_t slab, uint32_t block, int i);
#include "kernel/choice.h" /* the arithmetic, shared with the cl and gl programs */
#undef ICS_VIEW_PARAM
#undef ICS_VIEW_ARG
#undef ICS_SLAB_WORD

#define ICS_SLAB_TABLE_M 384 /* offsets / rotations of the per-pixel random members */

/* The per-pixel table index of buffer pixel `pixel` (row-major index in the Wb x Hb buffer) at
 * slab `slab` for light `light`: Philox-4x32-10 under key (seed low, seed high), counter
 * (block, slab, light, 0x736c6162), word `index` of the block's four, scaled to [0, M):
 * floor(word * M / 2^32), with block = (pixel / 64) 16 + pixel % 16 and index = (pixel / 16) % 4
 * (so one 16-lane Philox call gives 64 consecutive pixels in order). One definition for every
 * backend. */
uint32_t ics_slab_entry(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel);

/* The same word scaled to [0, k): the choice among k candidates (ics_slab_entry is k = M). The
 * choices of runs (ics_prop_run_choice) and of a slab's phase take one word each. */
uint32_t ics_slab_choice(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel, uint32_t k);

/* The four 32-bit words of block b (the pixels 64 (b / 16) + b % 16 + 16 i, i = 0..3). */
void ics_slab_entry_block(uint64_t seed, uint32_t light, uint32_t slab, uint32_t block,
                          uint32_t out[4]);

/* Per-pixel choices among k candidates, packed: where k is a power of two in [2, 256] each word
 * gives n = ics_slab_choice_chunks(k) choices of b = log2 k bits (chunk c: bits 31 - b c down to
 * 32 - b (c + 1)), so a block of four words chooses for 4 n pixels: block 16 g + i holds the
 * pixels 64 n g + 64 c + 16 w + i (word w = 0..3, chunk c = 0..n - 1, i = 0..15), and one
 * 16-lane Philox call chooses for 64 n consecutive pixels. Any other k (the table's M = 384):
 * n = 1, the word scaled as ics_slab_choice (so chunk 0 of a packed word is that choice too).
 * Every backend chooses so; Philox's words are independent uniform bits, so every choice is
 * exactly uniform. */
static inline int ics_slab_choice_bits(uint32_t k) { return ics_k_choice_bits(k); }
static inline uint32_t ics_slab_choice_chunks(uint32_t k) {
  return (uint32_t)ICS_CHOICE_CHUNKS(ics_slab_choice_bits(k));
}
/* chunk c of a pixel's word: its choice among k (b = ics_slab_choice_bits(k)) */
static inline uint32_t ics_slab_word_choice(uint32_t word, uint32_t k, int b, uint32_t c) {
  return ics_k_word_choice(word, k, b, c);
}
uint32_t ics_slab_pixel_choice(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel,
                               uint32_t k);

#endif
