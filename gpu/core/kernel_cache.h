/* kernel_cache.h — a renderer's slab kernels of its last frame, by the inputs they were resolved
 * from (ics_slab_kernel_key), so that the next frame's plan takes a copy of each kernel whose
 * light, pixel size and settings did not change instead of resolving it again (the expected
 * compensation iterates the ellipse's arc-length table: milliseconds a light; docs/renderer.md
 * "Speed"). One slot per plan task (a light's kernel, then its sharp set's); safe to use from
 * several threads. */
#ifndef ICS_RENDER_KERNEL_CACHE_H
#define ICS_RENDER_KERNEL_CACHE_H

#include "slab_kernel.h"

#define ICS_KERNEL_CACHE_SLOTS (2 * ICS_SCENE_MAX_LIGHTS)

typedef struct ics_kernel_cache ics_kernel_cache;

ics_kernel_cache *ics_kernel_cache_create(void); /* NULL when out of memory */
void ics_kernel_cache_destroy(ics_kernel_cache *c); /* NULL is allowed */
/* 1 with a copy of slot's kernel in *out when it was resolved from *key; else 0 (a slot out of
 * range, another key, or no memory for the copy) */
int ics_kernel_cache_get(ics_kernel_cache *c, int slot, const ics_slab_kernel_key *key,
                         ics_slab_kernel *out);
/* slot's kernel replaced by a copy of k, resolved from *key (left empty when out of memory) */
void ics_kernel_cache_put(ics_kernel_cache *c, int slot, const ics_slab_kernel_key *key,
                          const ics_slab_kernel *k);

#endif
