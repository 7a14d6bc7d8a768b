/* icshadow/plan.h — the render plan: what a render of a scene does and allocates, and what it
 * leaves out because the scene does not need it (docs/renderer.md "Work that a scene does not
 * need is not done"). Building a plan runs the geometry pass (the layered depth image over the
 * light-buffer area), so the slab count, depth complexity and memory figure are exact.
 * `icshadow plan SCENE` prints ics_plan_write_json's output. */
#ifndef ICSHADOW_PLAN_H
#define ICSHADOW_PLAN_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "icshadow/api.h"
#include "icshadow/scene.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ics_renderer ics_renderer; /* icshadow/renderer.h */

/* Overrides of the scene's values; a zero-initialised struct changes nothing. */
typedef struct ics_plan_opts {
  const ics_render_settings *settings; /* NULL: the scene's "render" block */
  int width, height;                   /* 0: the scene's resolution */
  int threads;                         /* geometry pass threads; 0: all cores */
  const ics_renderer *renderer; /* the renderer it will render on: render.model auto is planned as
                                   what its backend renders (ics_renderer_model_auto); NULL:
                                   blocker, the cpu backend's. The plan takes copies of the
                                   slab kernels the renderer kept from its last plan where their
                                   lights, pixel size and kernel settings are unchanged, and
                                   leaves its own with it (under the renderer's lock: plans
                                   may be made for it on several threads). Used by
                                   ics_plan_create only: the plan keeps no reference to it */
} ics_plan_opts;

typedef struct ics_plan ics_plan;

/* One pass of the plan: its name, the bytes it allocates, and for convolutions the light and the
 * taps per pixel (0 otherwise, light -1). */
typedef struct ics_plan_pass {
  char name[48];
  size_t bytes;
  int light;
  int taps;
  char detail[192]; /* kernel, mode and why (convolutions), or what the pass holds */
} ics_plan_pass;

typedef struct ics_plan_omitted {
  char name[48];
  char reason[160];
} ics_plan_omitted;

/* Builds the plan (and its layered depth image). Refused before allocating, with the estimate
 * in msg: ICS_ERR_SIZE when the plan's memory exceeds render.memory_limit_mib, its work exceeds
 * ICS_PLAN_MAX_WORK pixel-slab-light updates (the steps, an update per octave of volume detail
 * per pixel and slab, the perspective kernels' per-slab class compensation), or its geometry
 * pass ICS_PLAN_MAX_GEOMETRY ray-object tests. Other errors: ICS_ERR_NOMEM, ICS_ERR_RANGE (a
 * kernel that cannot be built), ICS_ERR_INVALID_ARG. */
#define ICS_PLAN_MAX_WORK 2e11
#define ICS_PLAN_MAX_GEOMETRY 1e10
ICS_API ics_status ics_plan_create(ics_plan **out, const ics_scene *scene,
                                   const ics_plan_opts *opts, char *msg, size_t msg_size);
ICS_API void ics_plan_destroy(ics_plan *p); /* NULL is allowed */

ICS_API const ics_scene *ics_plan_scene(const ics_plan *p);
ICS_API int ics_plan_slabs(const ics_plan *p);
ICS_API size_t ics_plan_memory_bytes(const ics_plan *p);
ICS_API int ics_plan_pass_count(const ics_plan *p);
ICS_API const ics_plan_pass *ics_plan_pass_at(const ics_plan *p, int i);
ICS_API int ics_plan_omitted_count(const ics_plan *p);
ICS_API const ics_plan_omitted *ics_plan_omitted_at(const ics_plan *p, int i);
/* Image and light-buffer sizes: W x H and the padded Wb x Hb. */
ICS_API void ics_plan_sizes(const ics_plan *p, int *width, int *height, int *buf_width,
                            int *buf_height);
/* Seconds the geometry pass (the layered depth image) took. */
ICS_API double ics_plan_geometry_seconds(const ics_plan *p);

/* The plan as JSON (docs/renderer.md): "passes" (name, bytes, light, taps, ...), "omitted"
 * (name, reason), "slabs", "memory_bytes", sizes and depth range. ICS_ERR_IO on write errors. */
ICS_API ics_status ics_plan_write_json(const ics_plan *p, FILE *f);

#ifdef __cplusplus
}
#endif
#endif
