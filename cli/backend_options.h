/* backend_options.h — the renderer's backend options on the command line (`render`, `bench
 * slab`): a flag --BACKEND-NAME VALUE for each option of each backend in the library's table
 * (ics_backend_option_*: --cl-device, --gl-context, --gl-ldi), checked by the library and passed
 * as ics_render_opts.options; one warning for an option of a backend that did not run. A
 * backend's new option touches no file in cli/. */
#ifndef ICS_CLI_BACKEND_OPTIONS_H
#define ICS_CLI_BACKEND_OPTIONS_H

#include <stdio.h>

#include "commands.h"

#ifdef ICS_HAVE_RENDER
#define BACKEND_OPTIONS_MAX 16

typedef struct backend_option_slot {
  int backend, option; /* indices in the library's table */
  char flag[48];       /* "--cl-device" */
  char text[512];      /* "cl.device=VALUE" once given */
  int given;
} backend_option_slot;

typedef struct backend_options {
  int n;
  backend_option_slot slot[BACKEND_OPTIONS_MAX];
  const char *list[BACKEND_OPTIONS_MAX + 1]; /* the given ones, NULL-terminated */
} backend_options;

/* Fills bo and writes one cli_option per backend option to opts (room for
 * BACKEND_OPTIONS_MAX); returns how many. */
int backend_options_table(backend_options *bo, cli_option *opts);
/* The help lines of every backend option ("  --gl-context V  ..."). */
void backend_options_help(FILE *f);
/* After parsing: the given options as ics_render_opts.options (NULL when none). */
const char *const *backend_options_list(backend_options *bo);
/* 1 when an option was given */
int backend_options_any(const backend_options *bo);
/* After the renderer is made: a warning for each given option of a backend other than `ran`,
 * unless auto passed over that backend (`note`: ics_renderer_note, printed by the caller). */
void backend_options_warn(const backend_options *bo, const char *cmd, const char *ran,
                          const char *note);
#endif

#endif
