/* backend_module.c — the table entries of backends built as modules (backend.h,
 * ICS_MODULE_BACKEND): each call takes the module's functions, loading it on first use
 * (module.h); a module that does not load makes its backend unavailable, with the reason. */
#include <stdio.h>

#include "backend.h"
#include "module.h"

static const ics_backend_funcs *funcs(const char *module, char *why, size_t why_size) {
  return ics_module_api(module, why, why_size);
}

int ics_module_backend_available(const char *module, const ics_render_opts *opts, char *why,
                                 size_t why_size) {
  const ics_backend_funcs *f = funcs(module, why, why_size);
  return f && f->available(opts, why, why_size);
}

int ics_module_backend_auto_pick(const char *module, char *why, size_t why_size) {
  const ics_backend_funcs *f = funcs(module, why, why_size);
  if (!f) return 0;
  return f->auto_pick ? f->auto_pick(why, why_size) : f->available(NULL, why, why_size);
}

ics_status ics_module_backend_create(const char *module, void **state, const ics_render_opts *opts,
                                     char *msg, size_t msg_size) {
  const ics_backend_funcs *f = funcs(module, msg, msg_size);
  return f ? f->create(state, opts, msg, msg_size) : ICS_ERR_UNSUPPORTED;
}

/* render and destroy follow a create that loaded the module */
ics_status ics_module_backend_render(const char *module, void *state, const ics_plan *plan,
                                     const ics_render_opts *opts, ics_image *img, ics_aov_buf *aov,
                                     ics_render_stats *stats, char *msg, size_t msg_size) {
  const ics_backend_funcs *f = funcs(module, msg, msg_size);
  return f ? f->render(state, plan, opts, img, aov, stats, msg, msg_size) : ICS_ERR_UNSUPPORTED;
}

void ics_module_backend_destroy(const char *module, void *state) {
  const ics_backend_funcs *f = funcs(module, NULL, 0);
  if (f) f->destroy(state);
}
