/* gl_testutil.h — the tests that drive a GL context themselves (test_lut_glsl.c, test_gl_ldi.c):
 * open the context ICS_GL_CONTEXT names (as the gl backend does) or skip with the reason. */
#ifndef ICS_GL_TESTUTIL_H
#define ICS_GL_TESTUTIL_H

#include <stdio.h>
#include <stdlib.h>

#include "gl_context.h"

/* opens g and prints what it is; exits 77 (skipped) with the reason when no context opens */
static inline void gl_open_or_skip(ics_gl *g) {
  char why[1024];
  if (ics_gl_open(g, ics_gl_context_kind(NULL), why, sizeof why) != ICS_OK) {
    printf("SKIPPED: %s\n", why);
    exit(77);
  }
  printf("OpenGL context: %s, %s, %s\n", g->context, g->renderer, g->version);
}

#endif
