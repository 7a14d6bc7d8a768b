/* icshadow/renderer.h — renderers and the backend table. A backend is an entry in a runtime
 * table: "cpu" (the slab renderer) and "mc" (the Monte-Carlo reference it is measured against,
 * docs/reference.md) always build; others ("gl", "cl") are entries when built. "auto" never
 * picks "mc". A renderer owns a backend's context (threads, a GL context,
 * an OpenCL queue) and renders plans into RGBA float images (row 0 at the top; RGB composited
 * over the scene's background, A = accumulated opacity). */
#ifndef ICSHADOW_RENDERER_H
#define ICSHADOW_RENDERER_H

#include <stddef.h>

#include "icshadow/api.h"
#include "icshadow/exr.h"
#include "icshadow/image.h"
#include "icshadow/plan.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Options; a zero-initialised struct is the default (backend "auto", all cores, no progress). */
typedef struct ics_render_opts {
  const char *backend; /* NULL or "auto": the best available (says which in the stats) */
  int threads;         /* 0: all cores */
  /* called after each slab from the rendering thread (slab = 1..nslabs); may be NULL */
  /* slab renderers: after each slab (slab = 1..nslabs); "mc": after each pass of one sample per
   * pixel (slab = samples so far, nslabs = spp, or 0 when the stop is a time or a noise) */
  void (*progress)(void *ctx, int slab, int nslabs);
  void *progress_ctx;
  /* "mc" only: stop after `spp` samples per pixel, after `time_s` seconds, or once the noise
   * (ics_render_stats.noise) is at most `noise`, whichever comes first (a time or noise stop
   * after 2 samples at the earliest; a noise stop alone may run to 2^24: bound it with a time);
   * all 0: 64 samples */
  int spp;
  double time_s, noise;
  /* "mc" only: mesh crossings through "embree" (Embree 3, when the renderer was built with it)
   * or "bvh" (the renderer's own BVH, as the slab renderer's layered depth image); NULL or
   * "auto": Embree when built in. The stats' device string says which ran. */
  const char *mc_mesh;
  /* Backend options: NULL, or a NULL-terminated list of "BACKEND.NAME=VALUE" strings
   * ("cl.device=1", "gl.context=osmesa", "gl.ldi=device"; ics_backend_option_name lists each
   * backend's). ics_renderer_create checks every one, whichever backend runs (ICS_ERR_INVALID_ARG
   * naming it); the backend uses its own in place of the option's environment variable
   * (ics_backend_option_env), which stays the default. */
  const char *const *options;
} ics_render_opts;

/* Time per pass and what ran. */
typedef struct ics_render_stats {
  char backend[16];
  char device[128];  /* e.g. "CPU, 2 threads, avx2" */
  int threads;
  int slabs;
  double ms_total;   /* the render call, geometry pass excluded (ics_plan_geometry_seconds) */
  double ms_convolution, ms_shading, ms_detail;
  double ns_per_px_slab; /* ms_convolution per (buffer pixel x slab x light) */
  int spp;               /* "mc": samples per pixel taken */
  double noise;          /* "mc": RMS over pixels and R, G, B of the standard error of the mean
                            (NAN after 1 sample) */
  double ms_geometry_device; /* the layered depth image built on the device (gl with --gl-ldi
                                device; within ms_total), 0 where the plan's is used */
  char simd[16]; /* "cpu": the propagation loops' vector path (scalar, sse2, neon, avx2, avx512;
                    ICS_SIMD); "" for the other backends */
  /* "cpu": the light buffers' channel-pixel updates of a dense render (buffer pixels x slabs x
   * lights x channels) and those propagated (the rest skipped: outside the active regions,
   * constant tiles, grey tiles' copies; docs/renderer.md); 0 for the other backends */
  double updates_dense, updates_active;
  char model[16]; /* the render.model the backend rendered: the plan's (auto resolved), or
                     "patel" where a plan of auto made as blocker met a backend that renders
                     patel only */
} ics_render_stats;

/* ics_renderer: declared in icshadow/plan.h, which plans for one (ics_plan_opts.renderer) */

ICS_API ics_status ics_renderer_create(ics_renderer **out, const ics_render_opts *opts,
                                       char *msg, size_t msg_size);
ICS_API void ics_renderer_destroy(ics_renderer *r); /* NULL is allowed */
ICS_API const char *ics_renderer_backend(const ics_renderer *r);
/* With backend "auto": why it passed over an entry it prefers to the one it took (e.g. "auto
 * passed over gl: ..."), one line; "" when it took its first choice or the backend was named. */
ICS_API const char *ics_renderer_note(const ics_renderer *r);
/* What render.model auto renders on r's backend: ICS_MODEL_BLOCKER on cpu, ICS_MODEL_PATEL on cl
 * and gl (they render patel only) and on mc (it ignores the model: the plan that costs least).
 * ics_plan_opts.renderer = r plans auto so; a plan of auto made without it is blocker's, which
 * a backend without blocker renders by making Patel's plan of the same scene itself. */
ICS_API ics_render_model ics_renderer_model_auto(const ics_renderer *r);

/* Renders the plan into a new RGBA image (*out; ics_image_destroy it). stats may be NULL. A
 * renderer renders one frame at a time (call it from one thread at a time); the cpu backend's
 * keeps its last frame's memory (light buffers, per-pixel arrays) for the next frame until
 * ics_renderer_destroy, which spares a frame the page faults of fresh memory. Every renderer
 * keeps its last plans' slab kernels, which a plan made for it (ics_plan_opts.renderer) copies
 * where its lights, pixel size and kernel settings are unchanged. */
ICS_API ics_status ics_renderer_render(ics_renderer *r, const ics_plan *plan, ics_image **out,
                                       ics_render_stats *stats, char *msg, size_t msg_size);

/* Arbitrary output variables beside the image, at the FIRST SURFACE of each pixel (the first
 * opaque-or-translucent surface along the camera ray, volumes passed through; docs/renderer.md):
 * ICS_AOV_VISIBILITY: per light, the fraction of its light reaching that surface, channels
 *   "lightL.V" (one light-buffer channel) or "lightL.R", "lightL.G", "lightL.B" (coloured
 *   transport), L = 0, 1, ... in scene order;
 * ICS_AOV_DEPTH: "Z", the surface's view depth (distance from the eye along the view axis);
 * ICS_AOV_STDERR ("mc" only): the standard error of the mean of R, G, B, A ("stderr.R", ...)
 *   and, with ICS_AOV_VISIBILITY, of each visibility channel ("stderr.light0.V", ...).
 * Pixels without a surface hold 0 in every visibility and depth channel. */
#define ICS_AOV_VISIBILITY 1u
#define ICS_AOV_DEPTH 2u
#define ICS_AOV_STDERR 4u

/* As ics_renderer_render, and with aovs != 0 the AOVs asked for as a new *aov_out
 * (ics_exr_channels_destroy frees it; ics_exr_write_channels writes it). The AOVs take
 * W H (lights x channels + 1) floats (twice that and 4 more with ICS_AOV_STDERR) beyond the
 * plan's memory_bytes. ICS_ERR_INVALID_ARG for unknown bits or aovs != 0 with aov_out NULL,
 * ICS_ERR_UNSUPPORTED for an AOV the backend does not make (msg says which), ICS_ERR_SIZE for
 * more AOV channels than an EXR holds beside R, G, B, A (ICS_EXR_MAX_CHANNELS - 4); all before
 * rendering. */
ICS_API ics_status ics_renderer_render_aovs(ics_renderer *r, const ics_plan *plan, unsigned aovs,
                                            ics_image **out, ics_exr_channels **aov_out,
                                            ics_render_stats *stats, char *msg, size_t msg_size);

/* The render summary as JSON object members, without braces, each after the first preceded by
 * ", " (docs/renderer.md "The render summary"): "backend", "device", "threads", "resolution";
 * for the slab renderers "light_buffer", "slabs", "kernel", "samples", "model" (the model
 * rendered) and "model_auto" (true when the plan's render.model was auto); "seed",
 * "ms_plan" (as given), "ms_geometry", "ms_render"; for the slab renderers "ms_convolution",
 * "ms_shading", "ms_detail", "ns_per_px_slab", "memory_bytes"; "updates_dense" and
 * "updates_active" where reported, "ms_geometry_device" where the device built the layered
 * depth image; for "mc" "spp" and "noise" (null after 1 sample). rs: the settings the plan was
 * made with (its ics_plan_opts.settings, or the scene's). The CLI's `render` prints these after
 * "scene". */
ICS_API void ics_render_summary_write(FILE *f, const ics_plan *plan, const ics_render_settings *rs,
                                      const ics_render_stats *stats, double ms_plan);

/* The backend table. */
ICS_API int ics_backend_count(void);
ICS_API const char *ics_backend_name(int i);        /* NULL out of range */
ICS_API const char *ics_backend_description(int i); /* NULL out of range */
/* 1 when backend `name` can run here; else 0 with the reason in why. */
ICS_API int ics_backend_available(const char *name, char *why, size_t why_size);
/* The same for a render with these options (opts->options: a device or context asked for is
 * the one tried; NULL: as ics_backend_available). */
ICS_API int ics_backend_available_opts(const char *name, const ics_render_opts *opts, char *why,
                                       size_t why_size);

/* The renderer's modules (docs/architecture.md "Modules"): the parts that need heavy libraries
 * (the gl and cl backends, the reference's Embree meshes, Assimp's mesh files), shared objects
 * loaded on first use. i = 0 .. count - 1: the module's name ("gl") and what it is for; NULL out
 * of range. ics_render_module_loads: 1 when module `name` loads here (loading it), else 0 with
 * the reason in why (not found, with the folders searched; a library it needs missing). */
ICS_API int ics_render_module_count(void);
ICS_API const char *ics_render_module_name(int i);
ICS_API const char *ics_render_module_purpose(int i);
ICS_API int ics_render_module_loads(const char *name, char *why, size_t why_size);

/* The options backend i takes (ics_render_opts.options), j = 0 .. count - 1: the name ("device"),
 * one line of help, the values it accepts ("auto|egl|osmesa"; NULL: any text that is not empty)
 * and the environment variable that gives its default ("ICS_CL_DEVICE"). NULL out of range. */
ICS_API int ics_backend_option_count(int i);
ICS_API const char *ics_backend_option_name(int i, int j);
ICS_API const char *ics_backend_option_help(int i, int j);
ICS_API const char *ics_backend_option_values(int i, int j);
ICS_API const char *ics_backend_option_env(int i, int j);
/* 1 when "BACKEND.NAME=VALUE" names an option of a backend built here with a value it accepts;
 * else 0 with the reason in why ("backend gl has no option 'lod' (it takes context, ldi)",
 * "gl.context: expected auto, egl or osmesa, got 'vulkan'"). */
ICS_API int ics_backend_option_check(const char *option, char *why, size_t why_size);

#ifdef __cplusplus
}
#endif
#endif
