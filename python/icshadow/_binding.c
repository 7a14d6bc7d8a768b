/* _binding.c — the C side of the icshadow Python package (compiled by cffi into icshadow._ffi
 * against the project's libraries): a loop that maps a library function over an array, and the
 * library's FILE * writers (LUT headers, lights files, the plan, the render summary) captured as
 * strings. Each returned string is freed with icspy_free; NULL means out of memory or, for the
 * LUT header, the reason in msg. */
#define _GNU_SOURCE /* open_memstream */
#include <stdio.h>
#include <stdlib.h>

#include "icshadow/render.h"

void icspy_map(double (*f)(double), const double *x, double *y, size_t n) {
  for (size_t i = 0; i < n; i++) y[i] = f(x[i]);
}

typedef struct {
  FILE *f;
  char *buf;
  size_t len;
} icspy_text;

static FILE *text_open(icspy_text *t) {
  t->buf = NULL;
  t->len = 0;
  return t->f = open_memstream(&t->buf, &t->len);
}

/* the text written, or NULL (freed) when a write failed */
static char *text_close(icspy_text *t, int ok) {
  int err = ferror(t->f), closed = fclose(t->f) == 0; /* closed whatever happened */
  if (err || !closed || !ok) free(t->buf), t->buf = NULL;
  return t->buf;
}

char *icspy_lut_header(int n, int lang, const char *command, char *msg, size_t msg_size) {
  size_t size = n >= ICS_LUT_MIN_SIZE && n <= ICS_LUT_MAX_SIZE ? (size_t)n : 1; /* else refused */
  double *s = malloc(sizeof *s * size), *g = malloc(sizeof *g * size);
  ics_lut_error ed, ef;
  ics_status st = s && g ? ics_lut_build_measured(n, s, g, &ed, &ef) : ICS_ERR_NOMEM;
  icspy_text t;
  if (st == ICS_OK && !text_open(&t)) st = ICS_ERR_NOMEM;
  if (st == ICS_OK) {
    ics_lut_tables L = {n, s, g};
    st = ics_lut_write(t.f, (ics_lut_lang)lang, &L, command, &ed, &ef);
    if (!text_close(&t, st == ICS_OK) && st == ICS_OK) st = ICS_ERR_NOMEM;
  }
  free(s);
  free(g);
  if (st != ICS_OK) {
    snprintf(msg, msg_size, "%s", ics_status_str(st));
    return NULL;
  }
  return t.buf;
}

char *icspy_lights_json(const ics_light *l, int n) {
  icspy_text t;
  if (!text_open(&t)) return NULL;
  return text_close(&t, ics_light_write_json(t.f, l, n) == 0);
}

char *icspy_plan_json(const ics_plan *p) {
  icspy_text t;
  if (!text_open(&t)) return NULL;
  return text_close(&t, ics_plan_write_json(p, t.f) == ICS_OK);
}

char *icspy_render_summary(const ics_plan *p, const ics_scene *s, const ics_render_stats *st,
                           double ms_plan) {
  icspy_text t;
  if (!text_open(&t)) return NULL;
  fputc('{', t.f);
  ics_render_summary_write(t.f, p, ics_scene_settings(s), st, ms_plan);
  fputc('}', t.f);
  return text_close(&t, 1);
}

void icspy_free(void *p) { free(p); }
