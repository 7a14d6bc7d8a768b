/* backend.c — the backend table and the renderer object (icshadow/renderer.h). "auto" takes the
 * first entry in table order that it may pick (auto_pick, else available) and that starts;
 * "cpu" is always available, so it never reaches what follows: "cl" (slower than cpu on PoCL)
 * and "mc", the Monte-Carlo reference. "gl" comes first but auto picks it only on a GPU (an EGL
 * device that is not Mesa's software one); an entry passed over or failing to start leaves a
 * one-line note (ics_renderer_note). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "clock.h"
#include "kernel_cache.h"
#include "own_term.h"
#include "plan_internal.h"
#include "pool.h"

#define ICS_BACKEND_ENTRY_(name) &ics_backend_##name,
static const ics_backend *const table[] = {ICS_BACKEND_LIST(ICS_BACKEND_ENTRY_)};
#undef ICS_BACKEND_ENTRY_
#define NBACKENDS ((int)(sizeof table / sizeof *table))

int ics_backend_count(void) { return NBACKENDS; }
const char *ics_backend_name(int i) { return i >= 0 && i < NBACKENDS ? table[i]->name : NULL; }
const char *ics_backend_description(int i) {
  return i >= 0 && i < NBACKENDS ? table[i]->description : NULL;
}

const ics_backend *ics_backend_find(const char *name) {
  for (int i = 0; i < NBACKENDS; i++)
    if (!strcmp(table[i]->name, name)) return table[i];
  return NULL;
}

int ics_backend_available(const char *name, char *why, size_t why_size) {
  return ics_backend_available_opts(name, NULL, why, why_size);
}

int ics_backend_available_opts(const char *name, const ics_render_opts *opts, char *why,
                               size_t why_size) {
  const ics_backend *b = name ? ics_backend_find(name) : NULL;
  if (!b) {
    if (why) {
      int n = snprintf(why, why_size, "no backend named '%s' (built:", name ? name : "(null)");
      for (int i = 0; i < NBACKENDS && n >= 0 && (size_t)n < why_size; i++)
        n += snprintf(why + n, why_size - (size_t)n, " %s", table[i]->name);
      if (n >= 0 && (size_t)n < why_size) snprintf(why + n, why_size - (size_t)n, ")");
    }
    return 0;
  }
  return b->f.available(opts, why, why_size);
}

/* ---- backend options ---------------------------------------------------------------------- */

static int option_count(const ics_backend *b) {
  int n = 0;
  while (b->options && b->options[n].name) n++;
  return n;
}

static const ics_backend_option *option_at(int i, int j) {
  return i >= 0 && i < NBACKENDS && j >= 0 && j < option_count(table[i]) ? &table[i]->options[j]
                                                                          : NULL;
}

int ics_backend_option_count(int i) { return i >= 0 && i < NBACKENDS ? option_count(table[i]) : 0; }
const char *ics_backend_option_name(int i, int j) { return option_at(i, j) ? option_at(i, j)->name : NULL; }
const char *ics_backend_option_help(int i, int j) { return option_at(i, j) ? option_at(i, j)->help : NULL; }
const char *ics_backend_option_values(int i, int j) {
  return option_at(i, j) ? option_at(i, j)->values : NULL;
}
const char *ics_backend_option_env(int i, int j) { return option_at(i, j) ? option_at(i, j)->env : NULL; }

/* value is one of the '|'-separated words of values (NULL: any text that is not empty) */
static int value_accepted(const char *values, const char *value) {
  if (!values) return value[0] != 0;
  for (const char *w = values; *w;) {
    size_t n = strcspn(w, "|");
    if (strlen(value) == n && !strncmp(w, value, n)) return 1;
    w += n + (w[n] == '|');
  }
  return 0;
}

/* "BACKEND.NAME=VALUE": its backend and option, *value after the '='; NULL with why */
static const ics_backend_option *parse_option(const char *text, const ics_backend **b,
                                              const char **value, char *why, size_t why_size) {
  const char *dot = strchr(text, '.'), *eq = strchr(text, '=');
  if (!dot || !eq || dot > eq) {
    if (why) snprintf(why, why_size, "backend option '%s': expected BACKEND.NAME=VALUE", text);
    return NULL;
  }
  *b = NULL;
  for (int i = 0; i < NBACKENDS && !*b; i++)
    if (strlen(table[i]->name) == (size_t)(dot - text) && !strncmp(table[i]->name, text, (size_t)(dot - text)))
      *b = table[i];
  if (!*b) {
    if (why) snprintf(why, why_size, "backend option '%s': no backend named '%.*s'", text,
                      (int)(dot - text), text);
    return NULL;
  }
  const ics_backend_option *o = NULL;
  for (int j = 0; j < option_count(*b) && !o; j++)
    if (strlen((*b)->options[j].name) == (size_t)(eq - dot - 1) &&
        !strncmp((*b)->options[j].name, dot + 1, (size_t)(eq - dot - 1)))
      o = &(*b)->options[j];
  if (!o) {
    if (why) {
      int n = snprintf(why, why_size, "backend %s has no option '%.*s' (it takes", (*b)->name,
                       (int)(eq - dot - 1), dot + 1);
      for (int j = 0; j < option_count(*b) && n >= 0 && (size_t)n < why_size; j++)
        n += snprintf(why + n, why_size - (size_t)n, "%s %s", j ? "," : "", (*b)->options[j].name);
      if (n >= 0 && (size_t)n < why_size)
        snprintf(why + n, why_size - (size_t)n, "%s)", option_count(*b) ? "" : " none");
    }
    return NULL;
  }
  *value = eq + 1;
  return o;
}

int ics_backend_option_check(const char *option, char *why, size_t why_size) {
  const ics_backend *b;
  const char *value;
  const ics_backend_option *o = option ? parse_option(option, &b, &value, why, why_size) : NULL;
  if (!o) {
    if (!option && why) snprintf(why, why_size, "backend option: NULL");
    return 0;
  }
  if (value_accepted(o->values, value)) return 1;
  if (why) {
    if (!o->values) {
      snprintf(why, why_size, "%s.%s: expected a value, got ''", b->name, o->name);
    } else { /* "a|b|c" as "a, b or c" */
      char list[128] = "";
      const char *w = o->values;
      while (*w) {
        size_t n = strcspn(w, "|");
        const char *sep = !list[0] ? "" : w[n] ? ", " : " or ";
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%.*s", sep, (int)n, w);
        w += n + (w[n] == '|');
      }
      snprintf(why, why_size, "%s.%s: expected %s, got '%s'", b->name, o->name, list, value);
    }
  }
  return 0;
}

const char *ics_backend_option_value(const ics_backend *b, const ics_render_opts *opts,
                                     const char *name, const char **from) {
  size_t nb = strlen(b->name), nn = strlen(name);
  for (const char *const *o = opts ? opts->options : NULL; o && *o; o++)
    if (!strncmp(*o, b->name, nb) && (*o)[nb] == '.' && !strncmp(*o + nb + 1, name, nn) &&
        (*o)[nb + 1 + nn] == '=') {
      if (from) *from = NULL; /* said as "BACKEND.NAME" by the caller's message */
      return *o + nb + nn + 2;
    }
  for (int j = 0; j < option_count(b); j++)
    if (!strcmp(b->options[j].name, name) && b->options[j].env) {
      const char *v = getenv(b->options[j].env);
      if (v && *v) {
        if (from) *from = b->options[j].env;
        return v;
      }
    }
  return NULL;
}

struct ics_renderer {
  const ics_backend *b;
  void *state;
  ics_render_opts opts;
  char note[512]; /* why auto passed over an entry before the one it took ("" if none) */
  ics_kernel_cache *kernels; /* the last plan's slab kernels (NULL: none kept) */
};

ics_status ics_renderer_create(ics_renderer **out, const ics_render_opts *opts, char *msg,
                               size_t msg_size) {
  *out = NULL;
  if (msg && msg_size) msg[0] = 0;
  ics_render_opts o = {0};
  if (opts) o = *opts;
  for (const char *const *op = o.options; op && *op; op++)
    if (!ics_backend_option_check(*op, msg, msg_size)) return ICS_ERR_INVALID_ARG;
  ics_renderer *r = calloc(1, sizeof *r);
  if (!r) return ICS_ERR_NOMEM;
  r->opts = o;
  if (!o.backend || !strcmp(o.backend, "auto")) {
    for (int i = 0; i < NBACKENDS && !r->b; i++) {
      char why[512] = "";
      const ics_backend *c = table[i];
      int ok = c->f.auto_pick ? c->f.auto_pick(why, sizeof why) : c->f.available(&o, why, sizeof why);
      if (ok) {
        ics_status st = c->f.create(&r->state, &o, why, sizeof why);
        if (st == ICS_OK) r->b = c;
        else if (c == &ics_backend_cpu) { /* the last resort failed: say so */
          if (msg) snprintf(msg, msg_size, "%s", why);
          free(r);
          return st;
        }
      }
      if (!r->b && c->f.auto_pick && !r->note[0]) { /* one line, without a "backend NAME: " */
        char prefix[32];
        snprintf(prefix, sizeof prefix, "backend %s: ", c->name);
        const char *w = strncmp(why, prefix, strlen(prefix)) ? why : why + strlen(prefix);
        snprintf(r->note, sizeof r->note, "auto passed over %s: %.*s%s", c->name,
                 (int)strcspn(w, "\n") < 400 ? (int)strcspn(w, "\n") : 400, w,
                 w[strcspn(w, "\n")] ? " (...)" : "");
      }
    }
  } else {
    char why[1024];
    if (!ics_backend_available_opts(o.backend, &o, why, sizeof why)) {
      if (msg) {
        if (ics_backend_find(o.backend)) snprintf(msg, msg_size, "backend %s: %s", o.backend, why);
        else snprintf(msg, msg_size, "backend %s", why);
      }
      free(r);
      return ICS_ERR_UNSUPPORTED;
    }
    r->b = ics_backend_find(o.backend);
    ics_status st = r->b->f.create(&r->state, &o, msg, msg_size);
    if (st != ICS_OK) {
      free(r);
      return st;
    }
  }
  r->kernels = ics_kernel_cache_create(); /* (without one, every plan resolves its kernels) */
  *out = r;
  return ICS_OK;
}

void ics_renderer_destroy(ics_renderer *r) {
  if (!r) return;
  r->b->f.destroy(r->state);
  ics_kernel_cache_destroy(r->kernels);
  free(r);
}

ics_kernel_cache *ics_renderer_kernel_cache(const ics_renderer *r) { return r ? r->kernels : NULL; }

const char *ics_renderer_backend(const ics_renderer *r) { return r->b->name; }
const char *ics_renderer_note(const ics_renderer *r) { return r->note; }
ics_render_model ics_renderer_model_auto(const ics_renderer *r) { return r->b->auto_model; }

/* The AOV channels asked for: their names (one block: pointers, then the strings, as
 * ics_exr_channels_destroy frees it) and zeroed data. */
static ics_status aov_create(const ics_plan *P, unsigned aovs, ics_exr_channels **out,
                             ics_aov_buf *buf) {
  int nl = P->nlights, nch = P->nch;
  int nvis = (aovs & ICS_AOV_VISIBILITY) ? nl * nch : 0, depth = (aovs & ICS_AOV_DEPTH) ? 1 : 0;
  int nerr = (aovs & ICS_AOV_STDERR) ? 4 + nvis : 0, count = nvis + depth + nerr;
  buf->count = count;
  buf->vis = nvis ? 0 : -1;
  buf->z = depth ? nvis : -1;
  buf->err = nerr ? nvis + depth : -1;
  enum { NAME = 32 }; /* "stderr.light%d.%c": at most 22 bytes */
  char **names = malloc((size_t)(count ? count : 1) * (sizeof(char *) + NAME));
  float *data = calloc((size_t)P->W * P->H * (size_t)(count ? count : 1), sizeof *data);
  ics_exr_channels *ch = malloc(sizeof *ch);
  if (!names || !data || !ch) {
    free(names), free(data), free(ch);
    return ICS_ERR_NOMEM;
  }
  char *str = (char *)(names + (count ? count : 1));
  for (int c = 0; c < count; c++) names[c] = str + (size_t)c * NAME;
  static const char rgb[3] = {'R', 'G', 'B'}, rgba[4] = {'R', 'G', 'B', 'A'};
  for (int l = 0; l < nl && nvis; l++)
    for (int c = 0; c < nch; c++) {
      snprintf(names[buf->vis + l * nch + c], NAME, "light%d.%c", l, nch == 1 ? 'V' : rgb[c]);
      if (nerr)
        snprintf(names[buf->err + 4 + l * nch + c], NAME, "stderr.light%d.%c", l,
                 nch == 1 ? 'V' : rgb[c]);
    }
  if (depth) snprintf(names[buf->z], NAME, "Z");
  for (int c = 0; c < 4 && nerr; c++) snprintf(names[buf->err + c], NAME, "stderr.%c", rgba[c]);
  buf->data = data;
  ch->width = P->W, ch->height = P->H, ch->count = count;
  ch->info = NULL;
  ch->names = (const char *const *)names;
  ch->data = data;
  *out = ch;
  return ICS_OK;
}

static ics_status render_plan(ics_renderer *r, const ics_plan *plan, unsigned aovs,
                              ics_image **out, ics_exr_channels **aov_out,
                              ics_render_stats *stats, char *msg, size_t msg_size) {
  *out = NULL;
  if (aov_out) *aov_out = NULL;
  if (msg && msg_size) msg[0] = 0;
  if ((aovs & ~(ICS_AOV_VISIBILITY | ICS_AOV_DEPTH | ICS_AOV_STDERR)) || (aovs && !aov_out)) {
    if (msg) snprintf(msg, msg_size, "AOVs 0x%x: unknown bits or nowhere to put them", aovs);
    return ICS_ERR_INVALID_ARG;
  }
  if (aovs & ~r->b->aovs) {
    static const char *const aov_names[3] = {"visibility", "depth", "stderr"};
    unsigned missing = aovs & ~r->b->aovs;
    char list[64] = "";
    for (int i = 0; i < 3; i++)
      if (missing & (1u << i))
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", list[0] ? ", " : "",
                 aov_names[i]);
    if (msg)
      snprintf(msg, msg_size, "backend %s does not make the AOV %s%s", r->b->name, list,
               (missing & ICS_AOV_STDERR) ? " (only mc estimates a standard error)" : "");
    return ICS_ERR_UNSUPPORTED;
  }
  /* a scene with nothing the model changes renders alike under every model */
  const char *needs = ics_plan_model_needs(plan);
  if (!(r->b->models >> plan->rs.model & 1) && needs) {
    if (msg)
      snprintf(msg, msg_size, "backend %s renders render.model patel only, not %s, which this "
               "scene's %s need (the cpu backend renders every model)", r->b->name,
               ics_render_model_name(plan->rs.model), needs);
    return ICS_ERR_UNSUPPORTED;
  }
  ics_render_stats local;
  if (!stats) stats = &local;
  memset(stats, 0, sizeof *stats);
  snprintf(stats->backend, sizeof stats->backend, "%s", r->b->name);
  snprintf(stats->model, sizeof stats->model, "%s", ics_render_model_name(plan->rs.model));
  ics_image *img;
  ics_status st = ics_image_create(&img, plan->W, plan->H, 4);
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "cannot allocate the %dx%d image: %s", plan->W, plan->H,
                      ics_status_str(st));
    return st;
  }
  int nvis = (aovs & ICS_AOV_VISIBILITY) ? plan->nlights * plan->nch : 0;
  int naov = nvis + ((aovs & ICS_AOV_DEPTH) ? 1 : 0) + ((aovs & ICS_AOV_STDERR) ? 4 + nvis : 0);
  if (naov > ICS_EXR_MAX_CHANNELS - 4) {
    if (msg)
      snprintf(msg, msg_size, "%d AOV channels (%d lights x %d channels): an EXR holds at most %d "
               "beside R, G, B, A", naov, plan->nlights, plan->nch, ICS_EXR_MAX_CHANNELS - 4);
    ics_image_destroy(img);
    return ICS_ERR_SIZE;
  }
  ics_exr_channels *ch = NULL;
  ics_aov_buf buf;
  if (aovs && aov_create(plan, aovs, &ch, &buf) != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "cannot allocate the AOVs (%dx%d)", plan->W, plan->H);
    ics_image_destroy(img);
    return ICS_ERR_NOMEM;
  }
  st = r->b->f.render(r->state, plan, &r->opts, img, ch ? &buf : NULL, stats, msg, msg_size);
  if (st != ICS_OK) {
    if (msg && msg_size && !msg[0]) snprintf(msg, msg_size, "render failed: %s", ics_status_str(st));
    ics_image_destroy(img);
    ics_exr_channels_destroy(ch);
    return st;
  }
  *out = img;
  if (aov_out) *aov_out = ch;
  return ICS_OK;
}

/* a plan of render.model auto made without this renderer (ics_plan_opts.renderer) is blocker's;
 * a backend that renders patel only renders Patel's plan of the same scene, settings and size,
 * made here (its geometry pass counted in the render's time) */
ics_status ics_renderer_render_aovs(ics_renderer *r, const ics_plan *plan, unsigned aovs,
                                    ics_image **out, ics_exr_channels **aov_out,
                                    ics_render_stats *stats, char *msg, size_t msg_size) {
  if (!plan->model_auto || (r->b->models >> plan->rs.model & 1))
    return render_plan(r, plan, aovs, out, aov_out, stats, msg, msg_size);
  *out = NULL;
  if (aov_out) *aov_out = NULL;
  double t0 = ics_clock_s();
  ics_render_settings rs = plan->rs;
  rs.model = ICS_MODEL_PATEL;
  ics_plan_opts po = {.settings = &rs, .width = plan->W, .height = plan->H,
                      .threads = r->opts.threads};
  ics_plan *patel;
  ics_status st = ics_plan_create(&patel, plan->scene, &po, msg, msg_size);
  if (st != ICS_OK) return st;
  double ms_plan = 1e3 * (ics_clock_s() - t0);
  st = render_plan(r, patel, aovs, out, aov_out, stats, msg, msg_size);
  if (st == ICS_OK && stats) stats->ms_total += ms_plan;
  ics_plan_destroy(patel);
  return st;
}

ics_status ics_renderer_render(ics_renderer *r, const ics_plan *plan, ics_image **out,
                               ics_render_stats *stats, char *msg, size_t msg_size) {
  return ics_renderer_render_aovs(r, plan, 0, out, NULL, stats, msg, msg_size);
}

ics_status ics_backend_pool_create(void **state, const ics_render_opts *opts, char *msg,
                                   size_t msg_size) {
  ics_pool *pool = ics_pool_create(opts->threads);
  if (!pool) {
    if (msg) snprintf(msg, msg_size, "cannot start %d worker threads", opts->threads);
    return ICS_ERR_NOMEM;
  }
  *state = pool;
  return ICS_OK;
}

void ics_backend_pool_destroy(void *state) { ics_pool_destroy(state); }

int ics_backend_always_available(const ics_render_opts *opts, char *why, size_t why_size) {
  (void)opts;
  (void)why, (void)why_size;
  return 1;
}
