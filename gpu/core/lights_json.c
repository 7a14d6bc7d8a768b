/* lights_json.c — lights files and light objects in JSON (icshadow/lightsfile.h): one reader
 * for `icshadow fit-light`'s output, the CLI's --lights FILE and scenes' "lights" and
 * "lights_file". */
#include "lights_json.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/lightsfile.h"

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

static int check_light(const ics_jctx *c, const char *where, const ics_light *l) {
  for (int k = 0; k < 2; k++)
    if (!isfinite(l->mean[k])) return ics_jerr(c, "%s: mean must be finite", where);
  for (int k = 0; k < 3; k++)
    if (!isfinite(l->cov[k])) return ics_jerr(c, "%s: cov must be finite", where);
  double tr = l->cov[0] + l->cov[2], det = l->cov[0] * l->cov[2] - l->cov[1] * l->cov[1];
  if (l->cov[0] < 0 || l->cov[2] < 0 || det < -1e-12 * tr * tr)
    return ics_jerr(c, "%s: cov is not positive semidefinite", where);
  for (int k = 0; k < 3; k++)
    if (!isfinite(l->color[k]) || l->color[k] < 0)
      return ics_jerr(c, "%s: color must be finite and >= 0", where);
  if (!isfinite(l->weight) || l->weight < 0)
    return ics_jerr(c, "%s: weight must be finite and >= 0", where);
  return 0;
}

int ics_light_from_json(const ics_jctx *c, const char *where, json_t *o, ics_light *l) {
  static const char *const known[] = {"mean", "tilt_deg", "cov", "var", "angle_deg", "color",
                                      "weight"};
  json_t *x;
  double v[4];
  memset(l, 0, sizeof *l);
  if (!json_is_object(o)) return ics_jerr(c, "%s: expected an object", where);
  {
    const char *key;
    json_t *val;
    json_object_foreach(o, key, val) {
      size_t q = 0;
      while (q < sizeof known / sizeof *known && strcmp(key, known[q])) q++;
      if (q == sizeof known / sizeof *known)
        return ics_jerr(c, "%s: unknown key \"%s\" (expected mean or tilt_deg, cov or var "
                        "[+ angle_deg], color, weight)", where, key);
    }
  }
  if (json_object_get(o, "mean") && json_object_get(o, "tilt_deg"))
    return ics_jerr(c, "%s: both \"mean\" and \"tilt_deg\": give one", where);
  if (json_object_get(o, "cov") && (json_object_get(o, "var") || json_object_get(o, "angle_deg")))
    return ics_jerr(c, "%s: both \"cov\" and \"%s\": give cov, or var [+ angle_deg]", where,
                    json_object_get(o, "var") ? "var" : "angle_deg");
  if (json_object_get(o, "angle_deg") && !json_object_get(o, "var"))
    return ics_jerr(c, "%s: \"angle_deg\" without \"var\"", where);
  if ((x = json_object_get(o, "mean"))) {
    if (numbers(x, 2, l->mean)) return ics_jerr(c, "%s.mean: expected [mx, my]", where);
  } else if ((x = json_object_get(o, "tilt_deg"))) {
    if (numbers(x, 2, v) || !(fabs(v[0]) < 90) || !(fabs(v[1]) < 90))
      return ics_jerr(c, "%s.tilt_deg: expected [wx, wy] in degrees, |w| < 90", where);
    l->mean[0] = ics_light_tan_deg(v[0]);
    l->mean[1] = ics_light_tan_deg(v[1]);
  } else {
    return ics_jerr(c, "%s: needs \"mean\" or \"tilt_deg\"", where);
  }
  if ((x = json_object_get(o, "cov"))) {
    double r0[2], r1[2];
    if (!json_is_array(x) || json_array_size(x) != 2 || numbers(json_array_get(x, 0), 2, r0) ||
        numbers(json_array_get(x, 1), 2, r1))
      return ics_jerr(c, "%s.cov: expected [[cxx, cxy], [cxy, cyy]]", where);
    if (r0[1] != r1[0])
      return ics_jerr(c, "%s.cov: not symmetric (%.17g vs %.17g)", where, r0[1], r1[0]);
    l->cov[0] = r0[0];
    l->cov[1] = r0[1];
    l->cov[2] = r1[1];
  } else if ((x = json_object_get(o, "var"))) {
    double a = 0;
    json_t *ang = json_object_get(o, "angle_deg");
    if (ang && !json_is_number(ang)) return ics_jerr(c, "%s.angle_deg: expected a number", where);
    if (ang) a = json_number_value(ang);
    if (numbers(x, 2, v) || ics_light_cov_from_eig(v[0], v[1], a, l->cov) != ICS_OK)
      return ics_jerr(c, "%s.var: expected [varx, vary], finite and >= 0", where);
  } else {
    return ics_jerr(c, "%s: needs \"cov\" or \"var\"", where);
  }
  l->color[0] = l->color[1] = l->color[2] = 1;
  if ((x = json_object_get(o, "color")) && numbers(x, 3, l->color))
    return ics_jerr(c, "%s.color: expected [r, g, b]", where);
  l->weight = 1;
  if ((x = json_object_get(o, "weight"))) {
    if (!json_is_number(x)) return ics_jerr(c, "%s.weight: expected a number", where);
    l->weight = json_number_value(x);
  }
  return check_light(c, where, l);
}

ics_status ics_lightsfile_read(const char *path, ics_light **out, int *n, char *msg,
                               size_t msg_size) {
  ics_jctx c = {msg, msg_size};
  *out = NULL;
  *n = 0;
  ics_status ost;
  json_t *root = ics_jload_file(&c, path, ICS_LIGHTSFILE_MAX_BYTES, 0, "lights", &ost);
  if (!root) return ost;
  ics_status st = ICS_ERR_PARSE;
  ics_light *l = NULL;
  json_t *arr = json_is_object(root) ? json_object_get(root, "lights") : NULL;
  if (!json_is_array(arr)) {
    ics_jerr(&c, "%s: expected an object with a \"lights\" array", path);
    goto done;
  }
  {
    const char *key;
    json_t *val;
    json_object_foreach(root, key, val) {
      if (strcmp(key, "lights")) {
        ics_jerr(&c, "%s: unknown key \"%s\" at the top level (expected only \"lights\")", path,
                 key);
        goto done;
      }
    }
  }
  size_t cnt = json_array_size(arr);
  if (cnt == 0 || cnt > ICS_LIGHTSFILE_MAX) {
    ics_jerr(&c, "%s: \"lights\" must hold 1..%d lights, not %zu", path, ICS_LIGHTSFILE_MAX, cnt);
    goto done;
  }
  l = calloc(cnt, sizeof *l);
  if (!l) {
    ics_jerr(&c, "out of memory");
    st = ICS_ERR_NOMEM;
    goto done;
  }
  size_t wlen = strlen(path) + 32;
  char *where = malloc(wlen);
  if (!where) {
    ics_jerr(&c, "out of memory");
    st = ICS_ERR_NOMEM;
    goto done;
  }
  for (size_t k = 0; k < cnt; k++) {
    snprintf(where, wlen, "%s: lights[%zu]", path, k);
    if (ics_light_from_json(&c, where, json_array_get(arr, k), &l[k])) {
      free(where);
      goto done;
    }
  }
  free(where);
  *out = l;
  *n = (int)cnt;
  l = NULL;
  st = ICS_OK;
done:
  free(l);
  json_decref(root);
  return st;
}
