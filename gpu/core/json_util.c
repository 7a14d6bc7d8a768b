/* json_util.c — strict JSON value readers shared by the scene and lights readers. */
#include "json_util.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/input_file.h"

int ics_jerr(const ics_jctx *c, const char *fmt, ...) {
  if (c->msg && c->msg_size) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->msg, c->msg_size, fmt, ap);
    va_end(ap);
  }
  return -1;
}

int ics_jkeys(const ics_jctx *c, const char *where, json_t *o, const char *const *known,
              size_t nknown) {
  return ics_jkeys_of(c, where, o, known, nknown, NULL);
}

int ics_jkeys_of(const ics_jctx *c, const char *where, json_t *o, const char *const *known,
                 size_t nknown, const char *what) {
  const char *key;
  json_t *val;
  json_object_foreach(o, key, val) {
    size_t q = 0;
    while (q < nknown && strcmp(key, known[q])) q++;
    if (q < nknown) continue;
    char list[512];
    size_t len = 0;
    list[0] = 0;
    for (size_t i = 0; i < nknown && len + 1 < sizeof list; i++)
      len += (size_t)snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", known[i]);
    if (what) return ics_jerr(c, "%s: unknown key \"%s\" for a %s (expected %s)", where, key, what, list);
    return ics_jerr(c, "%s: unknown key \"%s\" (expected %s)", where, key, list);
  }
  return 0;
}

int ics_jnum(const ics_jctx *c, const char *where, json_t *v, double *out) {
  if (!json_is_number(v)) return ics_jerr(c, "%s: expected a number", where);
  double x = json_number_value(v);
  if (!isfinite(x)) return ics_jerr(c, "%s: must be finite", where);
  *out = x;
  return 0;
}

int ics_jvec(const ics_jctx *c, const char *where, json_t *v, size_t n, double *out,
             const char *what) {
  if (!json_is_array(v) || json_array_size(v) != n)
    return ics_jerr(c, "%s: expected [%s]", where, what);
  for (size_t i = 0; i < n; i++) {
    json_t *x = json_array_get(v, i);
    if (!json_is_number(x)) return ics_jerr(c, "%s: expected [%s]", where, what);
    out[i] = json_number_value(x);
    if (!isfinite(out[i])) return ics_jerr(c, "%s: must be finite", where);
  }
  return 0;
}

int ics_jint(const ics_jctx *c, const char *where, json_t *v, long long lo, long long hi,
             long long *out) {
  if (!json_is_integer(v))
    return ics_jerr(c, "%s: expected an integer in %lld..%lld", where, lo, hi);
  long long x = (long long)json_integer_value(v);
  if (x < lo || x > hi) return ics_jerr(c, "%s: %lld is out of range %lld..%lld", where, x, lo, hi);
  *out = x;
  return 0;
}

int ics_jenum(const ics_jctx *c, const char *where, json_t *v, const char *const *names, int n,
              int *out) {
  char list[256];
  size_t len = 0;
  list[0] = 0;
  for (int i = 0; i < n && len + 1 < sizeof list; i++)
    len += (size_t)snprintf(list + len, sizeof list - len, "%s\"%s\"", i ? ", " : "", names[i]);
  if (!json_is_string(v)) return ics_jerr(c, "%s: expected one of %s", where, list);
  const char *s = json_string_value(v);
  for (int i = 0; i < n; i++)
    if (!strcmp(s, names[i])) {
      *out = i;
      return 0;
    }
  return ics_jerr(c, "%s: unknown value \"%s\" (expected one of %s)", where, s, list);
}

/* a file or stream read whole, at most max_bytes (0: any): NULL past that (*st ICS_ERR_SIZE) or
 * out of memory */
static char *read_bounded(FILE *f, uint64_t max_bytes, size_t *len, ics_status *st) {
  size_t cap = 65536, n = 0;
  char *buf = malloc(cap);
  while (buf) {
    n += fread(buf + n, 1, cap - n, f);
    if (n < cap) break;
    if (max_bytes && n > max_bytes) {
      free(buf);
      *st = ICS_ERR_SIZE;
      return NULL;
    }
    char *grown = realloc(buf, cap *= 2);
    if (!grown) free(buf);
    buf = grown;
  }
  if (buf && max_bytes && n > max_bytes) {
    free(buf);
    *st = ICS_ERR_SIZE;
    return NULL;
  }
  if (!buf) *st = ICS_ERR_NOMEM;
  *len = n;
  return buf;
}

json_t *ics_jload_file(const ics_jctx *c, const char *path, uint64_t max_bytes, unsigned flags,
                       const char *kind, ics_status *st) {
  char why[256];
  FILE *f = ics_input_open(path, max_bytes, flags, st, why, sizeof why);
  if (!f) {
    ics_jerr(c, "%s: %s %s file: %s", path,
             *st == ICS_ERR_SIZE ? "refusing a too large" : "cannot open", kind, why);
    return NULL;
  }
  /* read whole (a regular file's size is already within the bound; a stream is bounded as it
   * is read), a UTF-8 byte-order mark skipped (RFC 8259 lets a parser ignore it; jansson
   * refused it with the raw glyph) */
  size_t len;
  char *text = read_bounded(f, max_bytes, &len, st);
  fclose(f);
  if (!text) {
    if (*st == ICS_ERR_SIZE)
      ics_jerr(c, "%s: refusing a too large %s file: more than the %.4g MiB this reader takes",
               path, kind, (double)max_bytes / 1048576.0);
    else
      ics_jerr(c, "%s: out of memory", path);
    return NULL;
  }
  size_t skip = len >= 3 && !memcmp(text, "\xEF\xBB\xBF", 3) ? 3 : 0;
  json_error_t je;
  json_t *root = json_loadb(text + skip, len - skip, JSON_REJECT_DUPLICATES, &je);
  free(text);
  if (!root) {
    ics_jerr(c, "%s:%d:%d: %s", path, je.line, je.column, je.text);
    *st = ICS_ERR_PARSE;
  }
  return root;
}
