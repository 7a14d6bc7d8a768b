/* lightsfile.c — lights files (JSON) and SPEC strings; see lightsfile.h. */
#define _POSIX_C_SOURCE 200809L
#include "lightsfile.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "commands.h"

#ifdef ICS_HAVE_JANSSON
#include <jansson.h>
#endif

static void seterr(char *err, size_t n, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, n, fmt, ap);
  va_end(ap);
}

int lights_write(FILE *f, const ics_light *l, int n) {
  fprintf(f, "{\"lights\": [");
  for (int k = 0; k < n; k++)
    fprintf(f,
            "%s\n  {\"mean\": [%.17g, %.17g], \"cov\": [[%.17g, %.17g], [%.17g, %.17g]], "
            "\"color\": [%.17g, %.17g, %.17g], \"weight\": %.17g}",
            k ? "," : "", l[k].mean[0], l[k].mean[1], l[k].cov[0], l[k].cov[1], l[k].cov[1],
            l[k].cov[2], l[k].color[0], l[k].color[1], l[k].color[2], l[k].weight);
  fprintf(f, "\n]}\n");
  return ferror(f) ? -1 : 0;
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

#ifdef ICS_HAVE_JANSSON
/* a JSON array of exactly `len` numbers */
static int numbers(json_t *a, size_t len, double *v) {
  if (!json_is_array(a) || json_array_size(a) != len) return -1;
  for (size_t i = 0; i < len; i++) {
    json_t *x = json_array_get(a, i);
    if (!json_is_number(x)) return -1;
    v[i] = json_number_value(x);
  }
  return 0;
}
#endif

int lights_read_file(const char *path, ics_light **out, int *n, char *err, size_t errlen) {
  *out = NULL;
  *n = 0;
#ifndef ICS_HAVE_JANSSON
  seterr(err, errlen, "%s: reading lights files needs jansson, which was not found when icshadow "
         "was built (install libjansson-dev and rebuild); SPEC strings still work", path);
  return -2;
#else
  json_error_t je;
  json_t *root = json_load_file(path, JSON_REJECT_DUPLICATES, &je);
  if (!root) {
    seterr(err, errlen, "%s:%d:%d: %s", path, je.line, je.column, je.text);
    return -1;
  }
  ics_light *l = NULL;
  json_t *arr = json_is_object(root) ? json_object_get(root, "lights") : NULL;
  if (!json_is_array(arr)) {
    seterr(err, errlen, "%s: expected an object with a \"lights\" array", path);
    goto fail;
  }
  {
    const char *key;
    json_t *val;
    json_object_foreach(root, key, val) {
      if (strcmp(key, "lights")) {
        seterr(err, errlen, "%s: unknown key \"%s\" at the top level (expected only \"lights\")",
               path, key);
        goto fail;
      }
    }
  }
  size_t cnt = json_array_size(arr);
  if (cnt == 0 || cnt > 4096) {
    seterr(err, errlen, "%s: \"lights\" must hold 1..4096 lights, not %zu", path, cnt);
    goto fail;
  }
  l = calloc(cnt, sizeof *l);
  if (!l) {
    seterr(err, errlen, "out of memory");
    goto fail;
  }
  for (size_t k = 0; k < cnt; k++) {
    json_t *o = json_array_get(arr, k), *x;
    char where[CLI_MSG_MAX / 2]; /* the path and "lights[k]", never truncated short of PATH_MAX */
    snprintf(where, sizeof where, "%s: lights[%zu]", path, k);
    double v[4];
    if (!json_is_object(o)) {
      seterr(err, errlen, "%s: expected an object", where);
      goto fail;
    }
    {
      static const char *const known[] = {"mean", "tilt_deg", "cov", "var", "angle_deg", "color",
                                          "weight"};
      const char *key;
      json_t *val;
      json_object_foreach(o, key, val) {
        size_t q = 0;
        while (q < sizeof known / sizeof *known && strcmp(key, known[q])) q++;
        if (q == sizeof known / sizeof *known) {
          seterr(err, errlen, "%s: unknown key \"%s\" (expected mean or tilt_deg, cov or var "
                 "[+ angle_deg], color, weight)", where, key);
          goto fail;
        }
      }
    }
    if (json_object_get(o, "mean") && json_object_get(o, "tilt_deg")) {
      seterr(err, errlen, "%s: both \"mean\" and \"tilt_deg\": give one", where);
      goto fail;
    }
    if (json_object_get(o, "cov") &&
        (json_object_get(o, "var") || json_object_get(o, "angle_deg"))) {
      seterr(err, errlen, "%s: both \"cov\" and \"%s\": give cov, or var [+ angle_deg]", where,
             json_object_get(o, "var") ? "var" : "angle_deg");
      goto fail;
    }
    if (json_object_get(o, "angle_deg") && !json_object_get(o, "var")) {
      seterr(err, errlen, "%s: \"angle_deg\" without \"var\"", where);
      goto fail;
    }
    if ((x = json_object_get(o, "mean"))) {
      if (numbers(x, 2, l[k].mean)) {
        seterr(err, errlen, "%s.mean: expected [mx, my]", where);
        goto fail;
      }
    } else if ((x = json_object_get(o, "tilt_deg"))) {
      if (numbers(x, 2, v) || !(fabs(v[0]) < 90) || !(fabs(v[1]) < 90)) {
        seterr(err, errlen, "%s.tilt_deg: expected [wx, wy] in degrees, |w| < 90", where);
        goto fail;
      }
      l[k].mean[0] = ics_light_tan_deg(v[0]);
      l[k].mean[1] = ics_light_tan_deg(v[1]);
    } else {
      seterr(err, errlen, "%s: needs \"mean\" or \"tilt_deg\"", where);
      goto fail;
    }
    if ((x = json_object_get(o, "cov"))) {
      double r0[2], r1[2];
      if (!json_is_array(x) || json_array_size(x) != 2 || numbers(json_array_get(x, 0), 2, r0) ||
          numbers(json_array_get(x, 1), 2, r1)) {
        seterr(err, errlen, "%s.cov: expected [[cxx, cxy], [cxy, cyy]]", where);
        goto fail;
      }
      if (r0[1] != r1[0]) {
        seterr(err, errlen, "%s.cov: not symmetric (%.17g vs %.17g)", where, r0[1], r1[0]);
        goto fail;
      }
      l[k].cov[0] = r0[0];
      l[k].cov[1] = r0[1];
      l[k].cov[2] = r1[1];
    } else if ((x = json_object_get(o, "var"))) {
      double a = 0;
      json_t *ang = json_object_get(o, "angle_deg");
      if (ang && !json_is_number(ang)) {
        seterr(err, errlen, "%s.angle_deg: expected a number", where);
        goto fail;
      }
      if (ang) a = json_number_value(ang);
      if (numbers(x, 2, v) || ics_light_cov_from_eig(v[0], v[1], a, l[k].cov) != ICS_OK) {
        seterr(err, errlen, "%s.var: expected [varx, vary], finite and >= 0", where);
        goto fail;
      }
    } else {
      seterr(err, errlen, "%s: needs \"cov\" or \"var\"", where);
      goto fail;
    }
    l[k].color[0] = l[k].color[1] = l[k].color[2] = 1;
    if ((x = json_object_get(o, "color")) && numbers(x, 3, l[k].color)) {
      seterr(err, errlen, "%s.color: expected [r, g, b]", where);
      goto fail;
    }
    l[k].weight = 1;
    if ((x = json_object_get(o, "weight"))) {
      if (!json_is_number(x)) {
        seterr(err, errlen, "%s.weight: expected a number", where);
        goto fail;
      }
      l[k].weight = json_number_value(x);
    }
    if (check_light(&l[k], err, errlen, where)) goto fail;
  }
  json_decref(root);
  *out = l;
  *n = (int)cnt;
  return 0;
fail:
  free(l);
  json_decref(root);
  return -1;
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
