/* lightsfile.c — lights files (JSON) and SPEC strings; see lightsfile.h. */
#define _POSIX_C_SOURCE 200809L
#include "lightsfile.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"

#ifdef ICS_HAVE_RENDER
#include "icshadow/lightsfile.h"
#endif

static void seterr(char *err, size_t n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, n, fmt, ap);
  va_end(ap);
}

/* checks shared by files and specs */
static int check_light(const ics_light *l, char *err, size_t n, const char *where) {
  for (int c = 0; c < 2; c++)
    if (!isfinite(l->mean[c])) return seterr(err, n, "%s: mean must be finite", where), -1;
  for (int c = 0; c < 3; c++)
    if (!isfinite(l->cov[c])) return seterr(err, n, "%s: cov must be finite", where), -1;
  double tr = l->cov[0] + l->cov[2], det = l->cov[0] * l->cov[2] - l->cov[1] * l->cov[1];
  if (l->cov[0] < 0 || l->cov[2] < 0 || det < -1e-12 * tr * tr)
    return seterr(err, n, "%s: cov is not positive semidefinite", where), -1;
  for (int c = 0; c < 3; c++)
    if (!isfinite(l->color[c]) || l->color[c] < 0)
      return seterr(err, n, "%s: color must be finite and >= 0", where), -1;
  if (!isfinite(l->weight) || l->weight < 0)
    return seterr(err, n, "%s: weight must be finite and >= 0", where), -1;
  return 0;
}

int lights_parse_spec(const char *spec, ics_light **out, int *n, char *err, size_t errlen) {
  *out = NULL;
  *n = 0;
  int cap = 1;
  for (const char *p = spec; *p; p++) cap += *p == ':';
  ics_light *l = calloc((size_t)cap, sizeof *l);
  char *copy = strdup(spec);
  if (!l || !copy) {
    free(l);
    free(copy);
    return seterr(err, errlen, "out of memory"), -1;
  }
  if (!*spec) {
    seterr(err, errlen, "empty lights SPEC");
    goto fail;
  }
  /* split by hand (strtok would merge empty fields): every light and field must be non-empty */
  int k = 0;
  for (char *tok = copy, *next; tok; tok = next, k++) {
    next = strchr(tok, ':');
    if (next) *next++ = 0;
    if (!*tok) {
      seterr(err, errlen, "light %d: empty (two ':' in a row, or a ':' at an end)", k + 1);
      goto fail;
    }
    double v[9];
    int m = 0;
    for (char *f = tok, *fn; f; f = fn, m++) {
      fn = strchr(f, ',');
      if (fn) *fn++ = 0;
      if (m == 9) {
        seterr(err, errlen, "light %d: more than 9 fields (mx,my,varx,vary[,angle_deg[,weight"
               "[,r,g,b]]])", k + 1);
        goto fail;
      }
      if (!*f) {
        seterr(err, errlen, "light %d: field %d is empty", k + 1, m + 1);
        goto fail;
      }
      if (cli_parse_double(f, &v[m]) != 0) {
        seterr(err, errlen, "light %d: not a number: '%s'", k + 1, f);
        goto fail;
      }
    }
    if (m < 4 || m == 7 || m == 8) {
      seterr(err, errlen, "light %d: expected mx,my,varx,vary[,angle_deg[,weight[,r,g,b]]], "
             "got %d fields", k + 1, m);
      goto fail;
    }
    l[k].mean[0] = v[0];
    l[k].mean[1] = v[1];
    if (ics_light_cov_from_eig(v[2], v[3], m > 4 ? v[4] : 0, l[k].cov) != ICS_OK) {
      seterr(err, errlen, "light %d: variances must be finite and >= 0, angle finite", k + 1);
      goto fail;
    }
    l[k].weight = m > 5 ? v[5] : 1;
    for (int c = 0; c < 3; c++) l[k].color[c] = m > 6 ? v[6 + c] : 1;
    char where[32];
    snprintf(where, sizeof where, "light %d", k + 1);
    if (check_light(&l[k], err, errlen, where)) goto fail;
  }
  free(copy);
  *out = l;
  *n = k;
  return 0;
fail:
  free(copy);
  free(l);
  return -1;
}

int lights_read_file(const char *path, ics_light **out, int *n, char *err, size_t errlen) {
#ifdef ICS_HAVE_RENDER
  return ics_lightsfile_read(path, out, n, err, errlen) == ICS_OK ? 0 : -1;
#else
  *out = NULL;
  *n = 0;
  seterr(err, errlen, "%s: reading lights files needs jansson, which was not found when icshadow "
         "was built (install libjansson-dev and rebuild); SPEC strings still work", path);
  return -2;
#endif
}

int lights_load(const char *arg, ics_light **out, int *n, char *err, size_t errlen) {
  struct stat sb;
  if (stat(arg, &sb) == 0) {
    if (S_ISDIR(sb.st_mode)) {
      *out = NULL;
      *n = 0;
      seterr(err, errlen, "%s: is a directory, not a lights file", arg);
      return -1;
    }
    return lights_read_file(arg, out, n, err, errlen);
  }
  if (lights_parse_spec(arg, out, n, err, errlen) == 0) return 0;
  char spec_err[CLI_MSG_MAX / 2];
  snprintf(spec_err, sizeof spec_err, "%s", err);
  seterr(err, errlen, "'%s' is neither an existing lights file nor a valid SPEC (%s)", arg,
         spec_err);
  return -1;
}
