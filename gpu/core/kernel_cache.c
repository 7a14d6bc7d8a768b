/* kernel_cache.c — a renderer's slab kernels by their inputs (see kernel_cache.h). */
#include "kernel_cache.h"

#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
  int full;
  ics_slab_kernel_key key;
  ics_slab_kernel kernel;
} cache_slot;

struct ics_kernel_cache {
  pthread_mutex_t mu;
  cache_slot slot[ICS_KERNEL_CACHE_SLOTS];
};

ics_kernel_cache *ics_kernel_cache_create(void) {
  ics_kernel_cache *c = calloc(1, sizeof *c);
  if (c && pthread_mutex_init(&c->mu, NULL) != 0) {
    free(c);
    return NULL;
  }
  return c;
}

void ics_kernel_cache_destroy(ics_kernel_cache *c) {
  if (!c) return;
  for (int i = 0; i < ICS_KERNEL_CACHE_SLOTS; i++)
    if (c->slot[i].full) ics_slab_kernel_release(&c->slot[i].kernel);
  pthread_mutex_destroy(&c->mu);
  free(c);
}

int ics_kernel_cache_get(ics_kernel_cache *c, int slot, const ics_slab_kernel_key *key,
                         ics_slab_kernel *out) {
  if (!c || slot < 0 || slot >= ICS_KERNEL_CACHE_SLOTS) return 0;
  pthread_mutex_lock(&c->mu);
  const cache_slot *s = &c->slot[slot];
  int hit = s->full && !memcmp(&s->key, key, sizeof *key) &&
            ics_slab_kernel_copy(out, &s->kernel) == ICS_OK;
  pthread_mutex_unlock(&c->mu);
  return hit;
}

void ics_kernel_cache_put(ics_kernel_cache *c, int slot, const ics_slab_kernel_key *key,
                          const ics_slab_kernel *k) {
  if (!c || slot < 0 || slot >= ICS_KERNEL_CACHE_SLOTS) return;
  pthread_mutex_lock(&c->mu);
  cache_slot *s = &c->slot[slot];
  if (s->full) ics_slab_kernel_release(&s->kernel);
  s->full = ics_slab_kernel_copy(&s->kernel, k) == ICS_OK;
  s->key = *key;
  pthread_mutex_unlock(&c->mu);
}
