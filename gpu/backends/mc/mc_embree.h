/* mc_embree.h — the Monte-Carlo reference's mesh crossings through Embree 3 (optional: the
 * module icshadow-embree.so, built when CMake finds libembree-dev and loaded on first use;
 * docs/reference.md "Meshes"). Embree decides which triangles
 * the line through a ray meets (its robust, watertight traversal in single precision, one scene
 * per mesh object, an intersection filter that records every triangle and rejects it so the
 * traversal goes on); the crossings' t and normals are then computed in double precision by the
 * mesh's own code (ics_mesh_hits_of), so they are the same numbers the renderer's BVH gives
 * wherever both find the same triangles. */
#ifndef ICS_MC_EMBREE_H
#define ICS_MC_EMBREE_H

#include <stddef.h>

#include "geometry.h"
#include "icshadow/status.h"
#include "scene_internal.h"

typedef struct mc_embree mc_embree;

/* Per-thread scratch: the triangles one query found. */
typedef struct mc_embree_scratch {
  int *tri;
  int n, cap;
} mc_embree_scratch;

/* 1 when the module icshadow-embree.so loads (gpu/core/module.h), with Embree's version
 * ("3.13.5") in ver; 0 with the reason in why (neither may be NULL). */
int mc_embree_available(char *ver, size_t ver_size, char *why, size_t why_size);
/* One Embree scene per mesh object of s, built on `threads` threads (0: Embree's default, all
 * cores). ICS_ERR_UNSUPPORTED without Embree, with a build of Embree that lacks intersection
 * filters or culls back faces, or when Embree fails (the reason in msg); ICS_ERR_NOMEM. */
ics_status mc_embree_create(mc_embree **out, const ics_scene *s, int threads, char *msg,
                            size_t msg_size);
void mc_embree_destroy(mc_embree *e);
/* As ics_object_hits for mesh object obj. -1 when out of memory. */
int mc_embree_hits(const mc_embree *e, int obj, const double orig[3], const double dir[3],
                   mc_embree_scratch *sc, ics_hits *h, int *behind);
void mc_embree_scratch_free(mc_embree_scratch *sc);

/* The module's table (mc_embree.c); mc_embree_entry.c defines the functions above over it. */
typedef struct mc_embree_funcs {
  void (*version)(char *ver, size_t ver_size);
  ics_status (*create)(mc_embree **out, const ics_scene *s, int threads, char *msg, size_t msg_size);
  void (*destroy)(mc_embree *e);
  int (*hits)(const mc_embree *e, int obj, const double orig[3], const double dir[3],
              mc_embree_scratch *sc, ics_hits *h, int *behind);
} mc_embree_funcs;

#endif
