/* slab_choice.h — which tap set a pixel takes at a slab: one counter-based random word per pixel,
 * slab and light (Philox-4x32-10, icshadow/rng.h), the same in every backend and on every
 * vector path (docs/renderer.md "The light buffers"). */
#ifndef ICS_RENDER_SLAB_CHOICE_H
#define ICS_RENDER_SLAB_CHOICE_H

#include <stdint.h>

#define ICS_SLAB_TABLE_M 384 /* offsets / rotations of the per-pixel random members */

/* The per-pixel table index of buffer pixel `pixel` (row-major index in the Wb x Hb buffer) at
 * slab `slab` for light `light`: Philox-4x32-10 under key (seed low, seed high), counter
 * (block, slab, light, 0x736c6162), word `index` of the block's four, scaled to [0, M):
 * floor(word * M / 2^32), with block = (pixel / 64) 16 + pixel % 16 and index = (pixel / 16) % 4
 * (so one 16-lane Philox call gives 64 consecutive pixels in order). One definition for every
 * backend. */
uint32_t ics_slab_entry(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel);
static inline uint32_t ics_slab_word_block(uint32_t pixel) { return (pixel / 64) * 16 + pixel % 16; }
static inline int ics_slab_word_index(uint32_t pixel) { return (int)((pixel / 16) % 4); }

/* The same word scaled to [0, k): the choice among k candidates (ics_slab_entry is k = M). */
uint32_t ics_slab_choice(uint64_t seed, uint32_t light, uint32_t slab, uint32_t pixel, uint32_t k);

/* The four 32-bit words of block b (the pixels 64 (b / 16) + b % 16 + 16 i, i = 0..3). */
void ics_slab_entry_block(uint64_t seed, uint32_t light, uint32_t slab, uint32_t block,
                          uint32_t out[4]);

#endif
