/* backend.h — the backend table's entries: a backend is a name, a description, an availability
 * test and create / render / destroy over its own state (sokol's backends, c-ray's opaque
 * renderer are the models). "cpu" and "mc" always build. */
#ifndef ICS_RENDER_BACKEND_H
#define ICS_RENDER_BACKEND_H

#include "icshadow/renderer.h"
#include "kernel_cache.h"
#include "list.h"

/* The AOV channels a backend fills beside the image (docs/renderer.md "AOVs"): W x H pixels of
 * `count` floats, zero-initialised; -1 marks a channel set not asked for. */
typedef struct ics_aov_buf {
  int count;
  int vis;     /* light l, buffer channel c at vis + l nch + c (nch: the plan's 1 or 3) */
  int z;       /* the view depth of the first surface */
  int err;     /* standard errors: R, G, B, A at err + 0..3, then visibility channel v at
                  err + 4 + v - vis */
  float *data; /* pixel (i, j) at (j W + i) count */
} ics_aov_buf;

#define ICS_MODELS_ALL ((1u << ICS_MODEL_COUNT_) - 1)

/* An option a backend takes (ics_render_opts.options, "BACKEND.NAME=VALUE"): its name, the
 * environment variable that gives its default, the values it accepts ("a|b|c"; NULL: any text
 * that is not empty) and one line of help. */
typedef struct ics_backend_option {
  const char *name, *env, *values, *help;
} ics_backend_option;

/* What a backend does: an availability test, whether auto takes it, and create / render /
 * destroy over its own state. */
typedef struct ics_backend_funcs {
  /* opts: the options of a render (NULL: the defaults, its options' environment variables) */
  int (*available)(const ics_render_opts *opts, char *why, size_t why_size);
  /* NULL: "auto" takes it when available; else whether auto takes it (0 with why: the notice) */
  int (*auto_pick)(char *why, size_t why_size);
  ics_status (*create)(void **state, const ics_render_opts *opts, char *msg, size_t msg_size);
  /* aov: NULL when no AOV was asked for */
  ics_status (*render)(void *state, const ics_plan *plan, const ics_render_opts *opts,
                       ics_image *img, ics_aov_buf *aov, ics_render_stats *stats, char *msg,
                       size_t msg_size);
  void (*destroy)(void *state);
} ics_backend_funcs;

typedef struct ics_backend {
  const char *name;
  const char *description;
  unsigned aovs; /* the ICS_AOV_* bits it makes */
  unsigned models; /* 1 << ics_render_model: the render.model values it renders (ICS_MODELS_ALL) */
  ics_render_model auto_model; /* what render.model auto renders on it (ics_renderer_model_auto) */
  ics_backend_funcs f;
  const ics_backend_option *options; /* NULL, or entries up to one whose name is NULL */
} ics_backend;


/* A backend built as a module (module.h: the gl and cl backends, whose libraries are heavy): its
 * entry in the table, with what the core must know without loading it (name, description, AOVs,
 * models, options), comes from ICS_MODULE_BACKEND in its folder's *_entry.c; its functions are
 * the module's table (ics_backend_funcs), loaded on the first call (a module that does not
 * load makes the backend unavailable, with the reason). AUTO_PICK: 1 when the module decides
 * whether auto takes it (its auto_pick), 0 when auto takes it whenever available. AUTO_MODEL:
 * what render.model auto renders on it, one of MODELS. */
int ics_module_backend_available(const char *module, const ics_render_opts *opts, char *why,
                                 size_t why_size);
int ics_module_backend_auto_pick(const char *module, char *why, size_t why_size);
ics_status ics_module_backend_create(const char *module, void **state, const ics_render_opts *opts,
                                     char *msg, size_t msg_size);
ics_status ics_module_backend_render(const char *module, void *state, const ics_plan *plan,
                                     const ics_render_opts *opts, ics_image *img, ics_aov_buf *aov,
                                     ics_render_stats *stats, char *msg, size_t msg_size);
void ics_module_backend_destroy(const char *module, void *state);
#define ICS_MODULE_BACKEND(NAME, DESCRIPTION, AOVS, MODELS, AUTO_MODEL, OPTIONS, AUTO_PICK)       \
  static int NAME##_available_(const ics_render_opts *o, char *why, size_t n) {                \
    return ics_module_backend_available(#NAME, o, why, n);                                       \
  }                                                                                              \
  static int NAME##_auto_pick_(char *why, size_t n) {                                            \
    return ics_module_backend_auto_pick(#NAME, why, n);                                          \
  }                                                                                              \
  static ics_status NAME##_create_(void **st, const ics_render_opts *o, char *msg, size_t n) {  \
    return ics_module_backend_create(#NAME, st, o, msg, n);                                      \
  }                                                                                              \
  static ics_status NAME##_render_(void *st, const ics_plan *p, const ics_render_opts *o,       \
                                   ics_image *img, ics_aov_buf *aov, ics_render_stats *stats,    \
                                   char *msg, size_t n) {                                        \
    return ics_module_backend_render(#NAME, st, p, o, img, aov, stats, msg, n);                  \
  }                                                                                              \
  static void NAME##_destroy_(void *st) { ics_module_backend_destroy(#NAME, st); }              \
  const ics_backend ics_backend_##NAME = {                                                      \
      #NAME, DESCRIPTION, AOVS, MODELS, AUTO_MODEL,                                              \
      {NAME##_available_, AUTO_PICK ? NAME##_auto_pick_ : NULL, NAME##_create_, NAME##_render_, \
       NAME##_destroy_},                                                                         \
      OPTIONS};

/* The table's entry named `name`, or NULL. */
const ics_backend *ics_backend_find(const char *name);

/* The value of option `name` (one of b's) for a render: from opts->options (checked by
 * ics_renderer_create), else from its environment variable when set and not empty, else NULL.
 * *from (may be NULL) says where it came from: "BACKEND.NAME" or the variable's name. */
const char *ics_backend_option_value(const ics_backend *b, const ics_render_opts *opts,
                                     const char *name, const char **from);

/* For the backends that run on a pool of CPU threads ("cpu", "mc"): the state is the pool
 * itself (opts->threads workers; NULL and ICS_ERR_NOMEM with msg when they cannot start), and
 * such a backend is always available. */
ics_status ics_backend_pool_create(void **state, const ics_render_opts *opts, char *msg,
                                   size_t msg_size);
void ics_backend_pool_destroy(void *state);
int ics_backend_always_available(const ics_render_opts *opts, char *why, size_t why_size);

/* every backend of gpu/backends/list.h: ics_backend_cpu, ics_backend_mc, ... */
#define ICS_BACKEND_DECLARE_(name) extern const ics_backend ics_backend_##name;
ICS_BACKEND_LIST(ICS_BACKEND_DECLARE_)
#undef ICS_BACKEND_DECLARE_

/* The renderer's kept slab kernels (ics_plan_opts.renderer's: plan.c takes the unchanged ones
 * from it), or NULL */
ics_kernel_cache *ics_renderer_kernel_cache(const ics_renderer *r);

#endif
