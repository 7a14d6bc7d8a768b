/* backend_options.c — the renderer's backend options as command-line flags (see
 * backend_options.h). */
#include "backend_options.h"

#ifdef ICS_HAVE_RENDER
#include <string.h>

#include "icshadow/render.h"

static int parse(const char *cmd, const char *opt, const char *value, void *dest) {
  backend_option_slot *s = dest;
  char why[512];
  snprintf(s->text, sizeof s->text, "%s.%s=%s", ics_backend_name(s->backend),
           ics_backend_option_name(s->backend, s->option), value);
  if (ics_backend_option_check(s->text, why, sizeof why)) return 0;
  /* "gl.context: expected ..." said of the flag */
  const char *colon = strstr(why, ": ");
  return cli_error(cmd, "%s: %s", opt, colon ? colon + 2 : why);
}

int backend_options_table(backend_options *bo, cli_option *opts) {
  memset(bo, 0, sizeof *bo);
  for (int b = 0; b < ics_backend_count(); b++)
    for (int j = 0; j < ics_backend_option_count(b) && bo->n < BACKEND_OPTIONS_MAX; j++) {
      backend_option_slot *s = &bo->slot[bo->n];
      s->backend = b, s->option = j;
      snprintf(s->flag, sizeof s->flag, "--%s-%s", ics_backend_name(b), ics_backend_option_name(b, j));
      opts[bo->n] = (cli_option){s->flag, .kind = CLI_CALL, .parse = parse, .dest = s, .given = &s->given};
      bo->n++;
    }
  return bo->n;
}

/* text from column 22 on, wrapped before column 96 (the other options' help is laid out so) */
static void wrapped(FILE *f, const char *text) {
  enum { INDENT = 22, WIDTH = 96 - INDENT };
  while (*text) {
    size_t n = strlen(text);
    if (n > WIDTH) {
      n = WIDTH;
      while (n > 0 && text[n] != ' ') n--;
      if (!n) n = WIDTH;
    }
    fprintf(f, "%.*s\n", (int)n, text);
    text += n;
    while (*text == ' ') text++;
    if (*text) fprintf(f, "%*s", INDENT, "");
  }
}

void backend_options_help(FILE *f) {
  for (int b = 0; b < ics_backend_count(); b++)
    for (int j = 0; j < ics_backend_option_count(b); j++) {
      char flag[64], text[512];
      const char *values = ics_backend_option_values(b, j), *env = ics_backend_option_env(b, j);
      snprintf(flag, sizeof flag, "--%s-%s %s", ics_backend_name(b), ics_backend_option_name(b, j),
               values ? "V" : "D");
      snprintf(text, sizeof text, "--backend %s: %s%s%s%s", ics_backend_name(b),
               ics_backend_option_help(b, j), env ? " (default: $" : "", env ? env : "",
               env ? ")" : "");
      fprintf(f, "  %-19s ", flag);
      wrapped(f, text);
    }
}

const char *const *backend_options_list(backend_options *bo) {
  int k = 0;
  for (int i = 0; i < bo->n; i++)
    if (bo->slot[i].given) bo->list[k++] = bo->slot[i].text;
  bo->list[k] = NULL;
  return k ? bo->list : NULL;
}

int backend_options_any(const backend_options *bo) {
  for (int i = 0; i < bo->n; i++)
    if (bo->slot[i].given) return 1;
  return 0;
}

void backend_options_warn(const backend_options *bo, const char *cmd, const char *ran,
                          const char *note) {
  for (int i = 0; i < bo->n; i++) {
    const char *b = ics_backend_name(bo->slot[i].backend);
    char passed[64];
    snprintf(passed, sizeof passed, "auto passed over %s:", b);
    if (bo->slot[i].given && strcmp(b, ran) && strncmp(note, passed, strlen(passed)))
      cli_warning(cmd, "%s only applies to --backend %s (the backend is %s)", bo->slot[i].flag, b,
                  ran);
  }
}
#endif
