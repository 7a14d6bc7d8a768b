/* choice.h — a pixel's tap-set choice from its counter-RNG word (gpu/core/slab_choice.h has the
 * layout): the bits of a packed choice among k, chunk c of a word, and the choice at a counter.
 * The including file defines ICS_SLAB_WORD(light, slab, block, i): word i of Philox-4x32-10 at
 * counter (block, slab, light, "slab") under the render's seed. Shared kernel source (lang.h):
 * the cpu backend, slab.cl and slab.comp compile this one text. */
#ifndef ICS_KERNEL_CHOICE_H
#define ICS_KERNEL_CHOICE_H
#include "kernel/lang.h"

/* log2 k where k is a power of two in [2, 256] (that many bits per choice), else 0 (one choice
 * per word, the word scaled to [0, k)) */
ICS_FN int ics_k_choice_bits(ICS_UINT k) {
  return k >= 2u && k <= 256u && (k & (k - 1u)) == 0u ? ICS_LOG2_POW2(k) : 0;
}

/* chunk c of a word: its choice among k (b = ics_k_choice_bits(k)) */
ICS_FN ICS_UINT ics_k_word_choice(ICS_UINT word, ICS_UINT k, int b, ICS_UINT c) {
  if (b != 0) return (word >> (32 - b * ICS_TO_INT(c + 1u))) & (k - 1u);
  return ICS_MULHI(word, k);
}

/* the choice among k of `pixel` where a word packs n choices of b bits (n = 1, b = 0: the word
 * scaled): chunk (pixel % 64 n) / 64 of word (pixel % 64) / 16 of block
 * (pixel / 64 n) 16 + pixel % 16 */
ICS_FN ICS_UINT ics_k_pixel_choice(ICS_VIEW_PARAM ICS_UINT light, ICS_UINT slab, ICS_UINT pixel,
                                   ICS_UINT k, int b, ICS_UINT n) {
  ICS_UINT r = pixel % (64u * n);
  ICS_UINT word =
      ICS_SLAB_WORD(light, slab, pixel / (64u * n) * 16u + r % 16u, ICS_TO_INT(r % 64u / 16u));
  return ics_k_word_choice(word, k, b, r / 64u);
}

#endif
