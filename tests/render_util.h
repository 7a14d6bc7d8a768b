/* render_util.h — helpers for the renderer's tests: a scene from JSON text (or a file) through
 * plan and render (the CPU backend, or one named) to an RGBA image (and AOVs when asked), with
 * optional setting overrides. Exits 2 on a setup or render failure, so no check runs on a
 * missing image. */
#ifndef ICS_RENDER_UTIL_H
#define ICS_RENDER_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/render.h"

typedef struct render_result {
  ics_image *img;
  ics_exr_channels *aov; /* render_scene_aovs with aovs != 0 */
  ics_render_stats stats;
  size_t memory_bytes;
  int slabs;
} render_result;

/* The plan of scene s for renderer r (rs, threads, width and height as ics_plan_opts take them:
 * NULL and 0 keep the scene's; r may be NULL); exits 2 with the message when it cannot be made. */
static inline ics_plan *plan_for_or_exit(const ics_scene *s, const ics_render_settings *rs,
                                         int threads, int width, int height,
                                         const ics_renderer *r) {
  char msg[4096];
  ics_plan_opts po;
  memset(&po, 0, sizeof po);
  po.settings = rs;
  po.threads = threads;
  po.width = width;
  po.height = height;
  po.renderer = r;
  ics_plan *p;
  if (ics_plan_create(&p, s, &po, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "render_util: plan: %s\n", msg);
    exit(2);
  }
  return p;
}

static inline ics_plan *plan_sized_or_exit(const ics_scene *s, const ics_render_settings *rs,
                                           int threads, int width, int height) {
  return plan_for_or_exit(s, rs, threads, width, height, NULL);
}

static inline ics_plan *plan_or_exit(const ics_scene *s, const ics_render_settings *rs,
                                     int threads) {
  return plan_sized_or_exit(s, rs, threads, 0, 0);
}

/* Renders scene s on `backend` with `threads` threads (0: all) and the settings rs (NULL: the
 * scene's), with the AOVs `aovs` (ICS_AOV_* bits; 0: none), at width x height (0, 0: the
 * scene's resolution). */
static inline render_result render_scene_sized_on(const char *backend, const ics_scene *s,
                                                  const ics_render_settings *rs, int threads,
                                                  unsigned aovs, int width, int height) {
  render_result r;
  memset(&r, 0, sizeof r);
  char msg[4096];
  ics_plan *p = plan_sized_or_exit(s, rs, threads, width, height);
  ics_render_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.backend = backend;
  ro.threads = threads;
  ics_renderer *rr;
  if (ics_renderer_create(&rr, &ro, msg, sizeof msg) != ICS_OK ||
      ics_renderer_render_aovs(rr, p, aovs, &r.img, aovs ? &r.aov : NULL, &r.stats, msg,
                               sizeof msg) != ICS_OK) {
    fprintf(stderr, "render_util: render (%s): %s\n", backend, msg);
    exit(2);
  }
  r.memory_bytes = ics_plan_memory_bytes(p);
  r.slabs = ics_plan_slabs(p);
  ics_renderer_destroy(rr);
  ics_plan_destroy(p);
  return r;
}

static inline render_result render_scene_on(const char *backend, const ics_scene *s,
                                            const ics_render_settings *rs, int threads,
                                            unsigned aovs) {
  return render_scene_sized_on(backend, s, rs, threads, aovs, 0, 0);
}

static inline render_result render_scene_aovs(const ics_scene *s, const ics_render_settings *rs,
                                              int threads, unsigned aovs) {
  return render_scene_on("cpu", s, rs, threads, aovs);
}

static inline render_result render_scene(const ics_scene *s, const ics_render_settings *rs,
                                         int threads) {
  return render_scene_aovs(s, rs, threads, 0);
}

static inline ics_scene *scene_from_json(const char *json) {
  char msg[4096];
  ics_scene *s;
  if (ics_scene_create_json(&s, json, "test", NULL, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "render_util: scene: %s\n", msg);
    exit(2);
  }
  return s;
}

/* The embedded default scene at 96 x 72 (its text with the resolution replaced; exits 2 when
 * that text has changed shape). */
static inline ics_scene *default_scene_96x72(void) {
  const char *txt = ics_scene_default_json();
  char *small = malloc(strlen(txt) + 1);
  strcpy(small, txt);
  char *res = strstr(small, "[320, 240]");
  if (!res) {
    fprintf(stderr, "render_util: the default scene's resolution [320, 240] not found\n");
    exit(2);
  }
  memcpy(res, "[ 96,  72]", 10);
  ics_scene *s = scene_from_json(small);
  free(small);
  return s;
}

static inline ics_scene *scene_from_file(const char *path) {
  char msg[4096];
  ics_scene *s;
  if (ics_scene_create_file(&s, path, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "render_util: scene: %s\n", msg);
    exit(2);
  }
  return s;
}

#endif
