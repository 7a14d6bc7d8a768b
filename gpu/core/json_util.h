/* json_util.h — strict reading of JSON values for the scene and lights readers (jansson): every
 * failure writes "WHERE: reason" into the caller's message buffer, where WHERE is the value's
 * path ("scene.json: objects[1].radius"). Returns 0 on success, -1 on failure. */
#ifndef ICS_RENDER_JSON_UTIL_H
#define ICS_RENDER_JSON_UTIL_H

#include <jansson.h>
#include <stddef.h>
#include <stdint.h>

#include "icshadow/status.h"

typedef struct ics_jctx {
  char *msg;       /* the message buffer (may be NULL) */
  size_t msg_size;
} ics_jctx;

/* A JSON file read whole: a regular file of at most max_bytes (ics_input_open; with
 * ICS_INPUT_STREAM in flags also a pipe, read up to max_bytes), duplicate keys refused. NULL
 * with *st and the message "PATH: cannot open KIND file: reason" (or "refusing a too large KIND
 * file"), or "PATH:LINE:COLUMN: reason" for the syntax. */
json_t *ics_jload_file(const ics_jctx *c, const char *path, uint64_t max_bytes, unsigned flags,
                       const char *kind, ics_status *st);

/* printf into the message buffer; returns -1 so that `return ics_jerr(...)` reads well */
int ics_jerr(const ics_jctx *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Every key of object `o` must be in known[0..nknown-1]; else "WHERE: unknown key "K" (expected
 * LIST)". */
int ics_jkeys(const ics_jctx *c, const char *where, json_t *o, const char *const *known,
              size_t nknown);
/* The same, the message naming what the object is: "... unknown key "K" for a WHAT (expected
 * LIST)" (WHAT NULL: as ics_jkeys). */
int ics_jkeys_of(const ics_jctx *c, const char *where, json_t *o, const char *const *known,
                 size_t nknown, const char *what);
/* A finite number. */
int ics_jnum(const ics_jctx *c, const char *where, json_t *v, double *out);
/* An array of exactly n finite numbers ("expected [what]" names the shape in the message). */
int ics_jvec(const ics_jctx *c, const char *where, json_t *v, size_t n, double *out,
             const char *what);
/* An integer in [lo, hi]. */
int ics_jint(const ics_jctx *c, const char *where, json_t *v, long long lo, long long hi,
             long long *out);
/* A string that is one of names[0..n-1]; *out = its index. */
int ics_jenum(const ics_jctx *c, const char *where, json_t *v, const char *const *names,
              int n, int *out);

#endif
