/* mc_embree_entry.c — the Monte-Carlo reference's Embree mesh crossings (mc_embree.h) through
 * the module icshadow-embree.so (mc_embree.c), loaded when a scene with meshes asks for them
 * (gpu/core/module.h): without it the reference takes the meshes' own BVH, or says why. */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mc_embree.h"
#include "module.h"

/* set when the module loads (available, or create); read by every render's threads */
static _Atomic(const mc_embree_funcs *) funcs;

int mc_embree_available(char *ver, size_t ver_size, char *why, size_t why_size) {
  const mc_embree_funcs *f = ics_module_api("embree", why, why_size);
  if (ver_size) ver[0] = 0;
  if (!f) return 0;
  atomic_store(&funcs, f);
  f->version(ver, ver_size);
  return 1;
}

ics_status mc_embree_create(mc_embree **out, const ics_scene *s, int threads, char *msg,
                            size_t msg_size) {
  char ver[32], why[1024];
  *out = NULL;
  if (!atomic_load(&funcs) && !mc_embree_available(ver, sizeof ver, why, sizeof why)) {
    if (msg) snprintf(msg, msg_size, "%s", why);
    return ICS_ERR_UNSUPPORTED;
  }
  return atomic_load(&funcs)->create(out, s, threads, msg, msg_size);
}

/* (an e exists only after a create that loaded the module) */
void mc_embree_destroy(mc_embree *e) {
  if (e) atomic_load(&funcs)->destroy(e);
}

int mc_embree_hits(const mc_embree *e, int obj, const double orig[3], const double dir[3],
                   mc_embree_scratch *sc, ics_hits *h, int *behind) {
  return atomic_load_explicit(&funcs, memory_order_acquire)->hits(e, obj, orig, dir, sc, h, behind);
}

void mc_embree_scratch_free(mc_embree_scratch *sc) {
  free(sc->tri);
  memset(sc, 0, sizeof *sc);
}
