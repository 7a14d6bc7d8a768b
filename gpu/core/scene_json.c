/* scene_json.c — the scene-file reader (docs/scene-format.md): strict, every error names its
 * JSON path ("scene.json: objects[1].radius: expected a number"), malformed JSON its line and
 * column. Fences are expanded into boxes here; meshes are loaded (mesh.c); relative paths
 * (lights_file, mesh and grid files) are relative to the scene file's folder, and every file read
 * must lie in it unless the reader is told otherwise (ics_scene_opts). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "detail.h"
#include "geometry.h"
#include "icshadow/input_file.h"
#include "icshadow/lightsfile.h"
#include "json_util.h"
#include "lights_json.h"
#include "mesh.h"
#include "path_inside.h"
#include "scene_internal.h"

typedef struct {
  ics_jctx j;
  const char *name; /* the file, for messages */
  const char *dir;  /* folder of relative paths (NULL: working directory) */
  char *root;       /* that folder resolved, where every file read must lie (NULL: anywhere) */
  ics_status st;    /* status of the first error */
  char *where;      /* "NAME: path" buffer */
  size_t where_size;
  ics_scene *s;
  int obj_cap;
  char *grid_path[ICS_SCENE_MAX_MATERIALS]; /* per material: its grid file, read once an object
                                               uses it (NULL: none, or read) */
  double loaded;    /* bytes of grids and meshes read so far (render.memory_limit_mib) */
  int nread;        /* mesh files read so far, each once however often objects name it */
  struct read_mesh {
    char *path;
    ics_mesh_raw raw;
  } *read;
} rctx;

/* the mesh file at path as read for an object before, or NULL */
static const ics_mesh_raw *mesh_read_before(const rctx *c, const char *path) {
  for (int i = 0; i < c->nread; i++)
    if (!strcmp(c->read[i].path, path)) return &c->read[i].raw;
  return NULL;
}
/* the mesh file at path (not read before) as Assimp gives it; it and the other files Assimp read
 * for it become the scene's inputs; NULL with the message */
static const ics_mesh_raw *mesh_file(rctx *c, const char *path, char *msg, size_t msg_size,
                                     ics_status *st) {
  struct read_mesh *r = realloc(c->read, sizeof *r * (size_t)(c->nread + 1));
  if (!r) {
    *st = ICS_ERR_NOMEM;
    snprintf(msg, msg_size, "out of memory");
    return NULL;
  }
  c->read = r;
  r += c->nread;
  if ((*st = ics_mesh_read_file(&r->raw, path, 0, c->root, msg, msg_size)) != ICS_OK) return NULL;
  if (!(r->path = malloc(strlen(path) + 1))) {
    ics_mesh_raw_release(&r->raw);
    *st = ICS_ERR_NOMEM;
    snprintf(msg, msg_size, "out of memory");
    return NULL;
  }
  strcpy(r->path, path);
  c->nread++;
  int noted = ics_scene_note_file(c->s, path) == ICS_OK;
  for (const char *f = r->raw.files; noted && f && *f; f += strlen(f) + 1)
    noted = ics_scene_note_file(c->s, f) == ICS_OK;
  if (!noted) {
    *st = ICS_ERR_NOMEM;
    snprintf(msg, msg_size, "out of memory");
    return NULL;
  }
  return &r->raw;
}

/* 0 when `bytes` more fit with what the scene's files hold in memory under
 * render.memory_limit_mib, else -1 with the message (what: how the bytes are known, "" when
 * they are exact) */
static int fits(rctx *c, const char *where, const char *what, double bytes) {
  double limit = c->s->settings.memory_limit_mib * 1048576.0;
  if (c->loaded + bytes <= limit) return 0;
  c->st = ICS_ERR_SIZE;
  ics_jerr(&c->j, "%s: %s%.4g MiB, with the grids and meshes before it %.4g MiB, over "
           "render.memory_limit_mib = %g", where, what, bytes / 1048576.0,
           (c->loaded + bytes) / 1048576.0, c->s->settings.memory_limit_mib);
  return -1;
}

/* fits, and then counted: before a grid is read (its size is declared) and after each mesh copy
 * is built (its size is known then) */
static int account(rctx *c, const char *where, double bytes) {
  if (fits(c, where, "", bytes)) return -1;
  c->loaded += bytes;
  return 0;
}

/* "NAME: " + printf(path) in the context's buffer (valid until the next call) */
static const char *where_at(rctx *c, const char *fmt, ...) {
  int n = snprintf(c->where, c->where_size, "%s: ", c->name);
  va_list ap;
  va_start(ap, fmt);
  if (n >= 0 && (size_t)n < c->where_size) vsnprintf(c->where + n, c->where_size - (size_t)n, fmt, ap);
  va_end(ap);
  return c->where;
}

static int fail(rctx *c, ics_status st, const char *fmt, ...) {
  if (c->j.msg && c->j.msg_size) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(c->j.msg, c->j.msg_size, fmt, ap);
    va_end(ap);
  }
  c->st = st;
  return -1;
}

/* the ics_j* readers report parse errors; keep the status ICS_ERR_PARSE for those */
#define J(call) ((call) ? (c->st = ICS_ERR_PARSE, -1) : 0)

static int positive(rctx *c, const char *where, json_t *v, double *out) {
  if (J(ics_jnum(&c->j, where, v, out))) return -1;
  if (!(*out > 0)) return fail(c, ICS_ERR_RANGE, "%s: must be > 0, got %.17g", where, *out);
  return 0;
}

static int nonneg_vec(rctx *c, const char *where, json_t *v, size_t n, double *out,
                      const char *what, double hi) {
  if (J(ics_jvec(&c->j, where, v, n, out, what))) return -1;
  for (size_t i = 0; i < n; i++)
    if (out[i] < 0 || out[i] > hi)
      return fail(c, ICS_ERR_RANGE, "%s: component %zu is %.17g (must be in [0, %g])", where, i,
                  out[i], hi);
  return 0;
}

static int nonzero_vec3(rctx *c, const char *where, json_t *v, double out[3]) {
  if (J(ics_jvec(&c->j, where, v, 3, out, "x, y, z"))) return -1;
  if (out[0] == 0 && out[1] == 0 && out[2] == 0)
    return fail(c, ICS_ERR_RANGE, "%s: must not be the zero vector", where);
  return 0;
}

static char *join_path(const char *dir, const char *path) {
  if (!dir || !dir[0] || path[0] == '/') return strdup(path);
  size_t n = strlen(dir) + strlen(path) + 2;
  char *p = malloc(n);
  if (p) snprintf(p, n, "%s/%s", dir, path);
  return p;
}

/* 0 when the file at path may be read (path_inside.h), else -1 with the reason after `where` */
static int may_read(rctx *c, const char *where, const char *path) {
  char why[4096 + 512];
  ics_status st = ics_path_check_inside(path, c->root, why, sizeof why);
  if (st == ICS_OK) return 0;
  return fail(c, st, "%s: %s", where, st == ICS_ERR_NOMEM ? "out of memory" : why);
}

/* ---- camera ------------------------------------------------------------------------------ */
static int read_camera(rctx *c, json_t *o) {
  static const char *const known[] = {"projection", "eye", "target", "up", "height", "fov_deg",
                                      "resolution"};
  ics_camera *cam = &c->s->camera;
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where_at(c, "camera"));
  if (J(ics_jkeys(&c->j, where_at(c, "camera"), o, known, 7))) return -1;
  static const char *const proj[] = {"orthographic", "perspective"};
  int p = 0;
  json_t *x;
  if ((x = json_object_get(o, "projection")) && J(ics_jenum(&c->j, where_at(c, "camera.projection"), x, proj, 2, &p)))
    return -1;
  cam->projection = p ? ICS_PROJ_PERSPECTIVE : ICS_PROJ_ORTHOGRAPHIC;
  const char *req[] = {"eye", "target", "resolution"};
  for (int i = 0; i < 3; i++)
    if (!json_object_get(o, req[i]))
      return fail(c, ICS_ERR_PARSE, "%s: missing \"%s\"", where_at(c, "camera"), req[i]);
  if (J(ics_jvec(&c->j, where_at(c, "camera.eye"), json_object_get(o, "eye"), 3, cam->eye, "x, y, z")) ||
      J(ics_jvec(&c->j, where_at(c, "camera.target"), json_object_get(o, "target"), 3, cam->target,
                 "x, y, z")))
    return -1;
  cam->up[0] = 0, cam->up[1] = 1, cam->up[2] = 0;
  if ((x = json_object_get(o, "up")) && J(ics_jvec(&c->j, where_at(c, "camera.up"), x, 3, cam->up, "x, y, z")))
    return -1;
  json_t *res = json_object_get(o, "resolution");
  long long wh[2];
  if (!json_is_array(res) || json_array_size(res) != 2)
    return fail(c, ICS_ERR_PARSE, "%s: expected [W, H]", where_at(c, "camera.resolution"));
  for (int i = 0; i < 2; i++)
    if (J(ics_jint(&c->j, where_at(c, "camera.resolution[%d]", i), json_array_get(res, (size_t)i), 1,
                   ICS_SCENE_MAX_RES, &wh[i])))
      return -1;
  cam->width = (int)wh[0];
  cam->height_px = (int)wh[1];
  json_t *h = json_object_get(o, "height"), *fov = json_object_get(o, "fov_deg");
  if (cam->projection == ICS_PROJ_ORTHOGRAPHIC) {
    if (fov)
      return fail(c, ICS_ERR_PARSE, "%s: \"fov_deg\" is for perspective cameras (orthographic "
                  "ones take \"height\")", where_at(c, "camera"));
    if (!h) return fail(c, ICS_ERR_PARSE, "%s: an orthographic camera needs \"height\"", where_at(c, "camera"));
    if (positive(c, where_at(c, "camera.height"), h, &cam->height)) return -1;
    double dist = 0;
    for (int i = 0; i < 3; i++) dist += (cam->target[i] - cam->eye[i]) * (cam->target[i] - cam->eye[i]);
    if (!(cam->height >= 1e-9 * sqrt(dist) && cam->height >= 1e-150 && cam->height <= 1e12))
      return fail(c, ICS_ERR_RANGE, "%s: %.3g is out of proportion to the scene (at least 1e-9 of "
                  "the eye-target distance, at most 1e12)", where_at(c, "camera.height"), cam->height);
  } else {
    if (h)
      return fail(c, ICS_ERR_PARSE, "%s: \"height\" is for orthographic cameras (perspective "
                  "ones take \"fov_deg\")", where_at(c, "camera"));
    if (!fov) return fail(c, ICS_ERR_PARSE, "%s: a perspective camera needs \"fov_deg\"", where_at(c, "camera"));
    if (J(ics_jnum(&c->j, where_at(c, "camera.fov_deg"), fov, &cam->fov_deg))) return -1;
    /* from 1e-6 degrees: a view 1.7e-8 of the distance high, as the orthographic height's
     * 1e-9 (1e-300 gave "variance is negative" from the plan) */
    if (!(cam->fov_deg >= 1e-6 && cam->fov_deg < 170))
      return fail(c, ICS_ERR_RANGE, "%s: %.17g is out of range [1e-6, 170)", where_at(c, "camera.fov_deg"),
                  cam->fov_deg);
  }
  char msg[256];
  if (ics_camera_derive(cam, msg, sizeof msg) != ICS_OK)
    return fail(c, ICS_ERR_RANGE, "%s: %s", c->name, msg);
  return 0;
}

/* ---- render settings --------------------------------------------------------------------- */
static int read_render(rctx *c, json_t *o) {
  static const char *const known[] = {"slab_spacing", "d1", "kernel", "samples", "compensate",
                                      "radii", "seed", "background", "max_pad",
                                      "memory_limit_mib", "pixel_rotations", "preintegrate",
                                      "rotation_run", "dense", "model"};
  ics_render_settings *r = &c->s->settings;
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where_at(c, "render"));
  if (J(ics_jkeys(&c->j, where_at(c, "render"), o, known, 15))) return -1;
  json_t *x;
  if (!json_object_get(o, "slab_spacing"))
    return fail(c, ICS_ERR_PARSE, "%s: missing \"slab_spacing\"", where_at(c, "render"));
  if (!json_object_get(o, "d1")) return fail(c, ICS_ERR_PARSE, "%s: missing \"d1\"", where_at(c, "render"));
  if (positive(c, where_at(c, "render.slab_spacing"), json_object_get(o, "slab_spacing"), &r->slab_spacing) ||
      positive(c, where_at(c, "render.d1"), json_object_get(o, "d1"), &r->d1))
    return -1;
  /* far beyond any scene, and short of where the kernels' arithmetic overflows (1e308 gave
   * "argument out of range" with no key) */
  if (r->slab_spacing > 1e100 || r->d1 > 1e100)
    return fail(c, ICS_ERR_RANGE, "%s: %g is over 1e100 (world units)",
                where_at(c, r->slab_spacing > 1e100 ? "render.slab_spacing" : "render.d1"),
                r->slab_spacing > 1e100 ? r->slab_spacing : r->d1);
  static const char *const kn[] = {"ellipse", "poisson", "gauss", "tophat"};
  int k = 0;
  if ((x = json_object_get(o, "kernel")) && J(ics_jenum(&c->j, where_at(c, "render.kernel"), x, kn, 4, &k)))
    return -1;
  r->kernel = (ics_render_kernel)k;
  static const int lo[] = {2, 3, 2, 2}, dflt[] = {2, 8, 19, 5};
  r->samples = dflt[k];
  if ((x = json_object_get(o, "samples"))) {
    long long n;
    if (J(ics_jint(&c->j, where_at(c, "render.samples"), x, lo[k], 64, &n))) return -1;
    r->samples = (int)n;
  }
  static const char *const cn[] = {"expected", "integer", "nonneg", "signed", "none"};
  int cm;
  if ((x = json_object_get(o, "compensate"))) {
    if (J(ics_jenum(&c->j, where_at(c, "render.compensate"), x, cn, 5, &cm))) return -1;
    r->compensate = (ics_render_comp)(cm + 1);
  }
  static const char *const rn[] = {"exact", "lut"};
  int rad = 0;
  if ((x = json_object_get(o, "radii")) && J(ics_jenum(&c->j, where_at(c, "render.radii"), x, rn, 2, &rad)))
    return -1;
  r->lut_radii = rad;
  if ((x = json_object_get(o, "seed"))) {
    long long sd;
    if (J(ics_jint(&c->j, where_at(c, "render.seed"), x, 0, INT64_MAX, &sd))) return -1;
    r->seed = (uint64_t)sd;
  }
  if ((x = json_object_get(o, "background")) &&
      nonneg_vec(c, where_at(c, "render.background"), x, 3, r->background, "r, g, b", 1e30))
    return -1;
  if ((x = json_object_get(o, "max_pad"))) {
    long long mp;
    if (J(ics_jint(&c->j, where_at(c, "render.max_pad"), x, 0, ICS_SCENE_MAX_RES, &mp))) return -1;
    r->max_pad = (int)mp;
  }
  if ((x = json_object_get(o, "pixel_rotations"))) {
    long long pr;
    if (J(ics_jint(&c->j, where_at(c, "render.pixel_rotations"), x, 1, 384, &pr))) return -1;
    if (pr != 1 && pr != 2 && pr != 4 && pr != 8 && pr != 384)
      return fail(c, ICS_ERR_RANGE, "%s: %lld (expected 1, 2, 4, 8 or 384)",
                  where_at(c, "render.pixel_rotations"), pr);
    r->pixel_rotations = (int)pr;
  }
  if ((x = json_object_get(o, "rotation_run"))) {
    long long rr;
    if (J(ics_jint(&c->j, where_at(c, "render.rotation_run"), x, 1, 16, &rr))) return -1;
    if (rr != 1 && rr != 16)
      return fail(c, ICS_ERR_RANGE, "%s: %lld (expected 1 or 16)", where_at(c, "render.rotation_run"), rr);
    r->rotation_run = (int)rr;
  }
  if ((x = json_object_get(o, "preintegrate"))) {
    if (!json_is_boolean(x)) return fail(c, ICS_ERR_PARSE, "%s: expected true or false", where_at(c, "render.preintegrate"));
    r->preintegrate = json_is_true(x);
  }
  const char *mn[ICS_MODEL_COUNT_];
  for (int i = 0; i < ICS_MODEL_COUNT_; i++) mn[i] = ics_render_model_name((ics_render_model)i);
  int model = (int)r->model;
  if ((x = json_object_get(o, "model")) &&
      J(ics_jenum(&c->j, where_at(c, "render.model"), x, mn, ICS_MODEL_COUNT_, &model)))
    return -1;
  r->model = (ics_render_model)model;
  if ((x = json_object_get(o, "dense"))) {
    if (!json_is_boolean(x)) return fail(c, ICS_ERR_PARSE, "%s: expected true or false", where_at(c, "render.dense"));
    r->dense = json_is_true(x);
  }
  if ((x = json_object_get(o, "memory_limit_mib")) &&
      positive(c, where_at(c, "render.memory_limit_mib"), x, &r->memory_limit_mib))
    return -1;
  return 0;
}

/* ---- lights -------------------------------------------------------------------------------- */
/* power (weight x colour) and tilt the renderer can carry in float buffers and images */
#define ICS_SCENE_MAX_POWER 1e30
static int light_out_of_range(rctx *c, const char *where, const ics_light *l) {
  for (int i = 0; i < 3; i++)
    if (!(l->weight * l->color[i] <= ICS_SCENE_MAX_POWER))
      return fail(c, ICS_ERR_RANGE, "%s: weight x color = %.3g is over %g", where,
                  l->weight * l->color[i], ICS_SCENE_MAX_POWER);
  if (!(fabs(l->mean[0]) <= 1e6 && fabs(l->mean[1]) <= 1e6))
    return fail(c, ICS_ERR_RANGE, "%s: mean (%.3g, %.3g) is beyond 1e6 (a tilt of 89.99994 degrees)",
                where, l->mean[0], l->mean[1]);
  if (!(l->cov[0] <= 1e12 && l->cov[2] <= 1e12))
    return fail(c, ICS_ERR_RANGE, "%s: variance over 1e12", where);
  return 0;
}
static int read_lights(rctx *c, json_t *arr, json_t *file) {
  ics_scene *s = c->s;
  if (arr && file)
    return fail(c, ICS_ERR_PARSE, "%s: both \"lights\" and \"lights_file\": give one", c->name);
  if (!arr && !file)
    return fail(c, ICS_ERR_PARSE, "%s: needs \"lights\" or \"lights_file\"", c->name);
  if (file) {
    if (!json_is_string(file))
      return fail(c, ICS_ERR_PARSE, "%s: expected a file name", where_at(c, "lights_file"));
    char *path = join_path(c->dir, json_string_value(file));
    if (!path) return fail(c, ICS_ERR_NOMEM, "out of memory");
    if (may_read(c, where_at(c, "lights_file"), path)) {
      free(path);
      return -1;
    }
    ics_light *l;
    int n;
    ics_status st = ics_lightsfile_read(path, &l, &n, c->j.msg, c->j.msg_size);
    if (st == ICS_OK && ics_scene_note_file(s, path) != ICS_OK) {
      free(l);
      free(path);
      return fail(c, ICS_ERR_NOMEM, "out of memory");
    }
    free(path);
    if (st != ICS_OK) {
      /* the lights reader's message names the lights file; say which scene asked for it */
      if (c->j.msg && c->j.msg_size) {
        size_t len = strlen(c->j.msg);
        snprintf(c->j.msg + len, c->j.msg_size - len, " (lights_file of %s)", c->name);
      }
      c->st = st;
      return -1;
    }
    if (n > ICS_SCENE_MAX_LIGHTS) {
      free(l);
      return fail(c, ICS_ERR_SIZE, "%s: %d lights, at most %d in a scene", where_at(c, "lights_file"),
                  n, ICS_SCENE_MAX_LIGHTS);
    }
    for (int k = 0; k < n; k++)
      if (light_out_of_range(c, where_at(c, "lights_file: lights[%d]", k), &l[k])) {
        free(l);
        return -1;
      }
    memcpy(s->lights, l, sizeof *l * (size_t)n);
    s->nlights = n;
    free(l);
    return 0;
  }
  if (!json_is_array(arr)) return fail(c, ICS_ERR_PARSE, "%s: expected an array", where_at(c, "lights"));
  size_t n = json_array_size(arr);
  if (n == 0 || n > ICS_SCENE_MAX_LIGHTS)
    return fail(c, ICS_ERR_SIZE, "%s: must hold 1..%d lights, not %zu", where_at(c, "lights"),
                ICS_SCENE_MAX_LIGHTS, n);
  for (size_t k = 0; k < n; k++) {
    if (ics_light_from_json(&c->j, where_at(c, "lights[%zu]", k), json_array_get(arr, k), &s->lights[k])) {
      c->st = ICS_ERR_PARSE;
      return -1;
    }
    if (light_out_of_range(c, where_at(c, "lights[%zu]", k), &s->lights[k])) return -1;
  }
  s->nlights = (int)n;
  return 0;
}

/* ---- materials ----------------------------------------------------------------------------- */
/* a grid's "file" and "size" (the cells are read later, by load_grid, if an object uses it) */
static int read_grid(rctx *c, const char *where, json_t *o, ics_detail *d, int mi) {
  json_t *f = json_object_get(o, "file"), *sz = json_object_get(o, "size");
  if (!f || !sz) return fail(c, ICS_ERR_PARSE, "%s: a grid needs \"file\" and \"size\"", where);
  if (!json_is_string(f)) return fail(c, ICS_ERR_PARSE, "%s.file: expected a file name", where);
  if (!json_is_array(sz) || json_array_size(sz) != 3)
    return fail(c, ICS_ERR_PARSE, "%s.size: expected [nx, ny, nz]", where);
  size_t cells = 1;
  for (int i = 0; i < 3; i++) {
    json_t *v = json_array_get(sz, (size_t)i);
    if (!json_is_integer(v) || json_integer_value(v) < 1 || json_integer_value(v) > 4096)
      return fail(c, ICS_ERR_RANGE, "%s.size[%d]: expected an integer in 1..4096", where, i);
    d->size[i] = (int)json_integer_value(v);
    cells *= (size_t)d->size[i];
  }
  if (cells > ((size_t)1 << 28))
    return fail(c, ICS_ERR_SIZE, "%s.size: %zu cells (at most 2^28)", where, cells);
  if (!(c->grid_path[mi] = join_path(c->dir, json_string_value(f))))
    return fail(c, ICS_ERR_NOMEM, "out of memory");
  return 0;
}

/* the cells of material mi's grid (read_grid), within the memory limit */
static int load_grid(rctx *c, int mi) {
  ics_material *m = &c->s->materials[mi];
  ics_detail *d = &m->detail;
  char *path = c->grid_path[mi];
  c->grid_path[mi] = NULL;
  size_t cells = (size_t)d->size[0] * (size_t)d->size[1] * (size_t)d->size[2];
  int refused = may_read(c, where_at(c, "materials.%s.detail.file", m->name), path);
  const char *where = where_at(c, "materials.%s.detail", m->name);
  if (refused || account(c, where, (double)cells * sizeof *d->grid)) {
    free(path);
    return -1;
  }
  char why[256];
  ics_status ost;
  FILE *fp = ics_input_open(path, 0, 0, &ost, why, sizeof why);
  if (!fp || ics_scene_note_file(c->s, path) != ICS_OK) {
    if (fp) fclose(fp);
    if (fp) fail(c, ICS_ERR_NOMEM, "out of memory");
    else fail(c, ost, "%s.file: cannot open '%s': %s", where, path, why);
    free(path);
    return -1;
  }
  d->grid = malloc(sizeof *d->grid * cells);
  if (!d->grid) {
    fclose(fp);
    free(path);
    return fail(c, ICS_ERR_NOMEM, "%s: out of memory for %zu cells", where, cells);
  }
  size_t got = fread(d->grid, sizeof *d->grid, cells, fp);
  int extra = fgetc(fp) != EOF;
  fclose(fp);
  if (got != cells || extra) {
    fail(c, ICS_ERR_PARSE, "%s.file: '%s' %s (expected exactly %zu float32 values, %zu bytes)",
         where, path, got != cells ? "is too short" : "is too long", cells, cells * 4);
    free(path);
    return -1;
  }
  free(path);
  for (size_t i = 0; i < cells; i++)
    if (!isfinite(d->grid[i]) || d->grid[i] < 0)
      return fail(c, ICS_ERR_RANGE, "%s.file: value %zu is %g (must be finite and >= 0)", where,
                  i, (double)d->grid[i]);
  return 0;
}

/* The largest value an image can take stays finite: every material's colour (its transfer
 * rows' too) times the lights' weight x colour summed over lights is at most ICS_SCENE_MAX_RADIANCE
 * (the per-light bound already holds each light: 64 of them at that bound stay far below FLT_MAX,
 * but a colour of 1e30 on top overflowed float in the render and failed only at the write). */
static int check_radiance(rctx *c) {
  double lights = 0;
  for (int l = 0; l < c->s->nlights; l++) {
    const ics_light *L = &c->s->lights[l];
    lights += L->weight * fmax(L->color[0], fmax(L->color[1], L->color[2]));
  }
  for (int i = 0; i < c->s->nmaterials; i++) {
    const ics_material *m = &c->s->materials[i];
    double col = fmax(m->color[0], fmax(m->color[1], m->color[2]));
    for (int k = 0; k < m->ntransfer; k++)
      col = fmax(col, fmax(m->transfer[k][1], fmax(m->transfer[k][2], m->transfer[k][3])));
    if (col * lights > ICS_SCENE_MAX_RADIANCE)
      return fail(c, ICS_ERR_RANGE, "%s: a colour of %g under lights of %g in all (weight x colour, "
                  "summed) gives %g, over %g: the image would overflow; lower the colours or the "
                  "weights", where_at(c, "materials.%s", m->name), col, lights, col * lights,
                  ICS_SCENE_MAX_RADIANCE);
  }
  return 0;
}

/* A volume's extinction stays within ICS_SCENE_MAX_EXTINCTION wherever its detail takes it
 * (ics_material_majorant; after the grids are read): an extinction of 14 under a transfer
 * extinction scale of 1e308 rendered fully, then failed at the write with a NaN pixel. */
static int check_extinction(rctx *c) {
  for (int k = 0; k < c->s->nobjects; k++) {
    const ics_material *m = &c->s->materials[c->s->objects[k].material];
    double top = ics_material_majorant(m);
    if (!(top <= ICS_SCENE_MAX_EXTINCTION))
      return fail(c, ICS_ERR_RANGE, "%s: its extinction reaches %g per world unit (extinction %g "
                  "times the largest scale its detail and transfer give), over %g: the render "
                  "would overflow; lower the extinction, the detail's scale and bias, or the "
                  "transfer's extinction scales", where_at(c, "materials.%s", m->name), top,
                  m->extinction, ICS_SCENE_MAX_EXTINCTION);
  }
  return 0;
}

/* the grids of the materials some object uses; the others are never read */
static int load_used_grids(rctx *c) {
  for (int mi = 0; mi < c->s->nmaterials; mi++) {
    if (!c->grid_path[mi]) continue;
    int used = 0;
    for (int k = 0; k < c->s->nobjects && !used; k++) used = c->s->objects[k].material == mi;
    if (used && load_grid(c, mi)) return -1;
  }
  return 0;
}

static int read_detail(rctx *c, const char *mwhere, json_t *o, ics_detail *d, int mi) {
  static const char *const known[] = {"function", "frequency", "octaves", "lacunarity", "gain",
                                      "offset", "time", "seed", "scale", "bias", "file", "size"};
  char where[4096 + 320];
  snprintf(where, sizeof where, "%s.detail", mwhere);
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where);
  if (J(ics_jkeys(&c->j, where, o, known, 12))) return -1;
  static const char *const fn[] = {"perlin", "fbm", "ridged", "grid"};
  int f;
  json_t *x = json_object_get(o, "function");
  if (!x) return fail(c, ICS_ERR_PARSE, "%s: missing \"function\"", where);
  char w2[sizeof where + 32];
  snprintf(w2, sizeof w2, "%s.function", where);
  if (J(ics_jenum(&c->j, w2, x, fn, 4, &f))) return -1;
  d->fn = (ics_detail_fn)(f + 1);
  d->frequency = 1, d->octaves = 4, d->lacunarity = 2, d->gain = d->fn == ICS_DETAIL_RIDGED ? 2 : 0.5;
  d->offset = 1, d->time = 0, d->seed = 0, d->scale = 1, d->bias = 0;
  if (d->fn == ICS_DETAIL_GRID) {
    static const char *const noise_only[] = {"frequency", "octaves", "lacunarity", "gain",
                                             "offset", "time", "seed"};
    for (int i = 0; i < 7; i++)
      if (json_object_get(o, noise_only[i]))
        return fail(c, ICS_ERR_PARSE, "%s: \"%s\" is for noise functions, not grids", where,
                    noise_only[i]);
  } else if (json_object_get(o, "file") || json_object_get(o, "size")) {
    return fail(c, ICS_ERR_PARSE, "%s: \"file\" and \"size\" are for \"function\": \"grid\"", where);
  }
  struct {
    const char *key;
    double *v;
    double lo, hi;
  } nums[] = {{"frequency", &d->frequency, 1e-12, 1e12}, {"lacunarity", &d->lacunarity, 1e-6, 1e6},
              {"gain", &d->gain, 0, 1e6},                {"offset", &d->offset, -1e12, 1e12},
              {"time", &d->time, -1e12, 1e12},           {"scale", &d->scale, -1e12, 1e12},
              {"bias", &d->bias, -1e12, 1e12}};
  for (size_t i = 0; i < sizeof nums / sizeof *nums; i++) {
    if (!(x = json_object_get(o, nums[i].key))) continue;
    snprintf(w2, sizeof w2, "%s.%s", where, nums[i].key);
    if (J(ics_jnum(&c->j, w2, x, nums[i].v))) return -1;
    if (*nums[i].v < nums[i].lo || *nums[i].v > nums[i].hi)
      return fail(c, ICS_ERR_RANGE, "%s: %.17g is out of range [%g, %g]", w2, *nums[i].v,
                  nums[i].lo, nums[i].hi);
  }
  long long iv;
  if ((x = json_object_get(o, "octaves"))) {
    snprintf(w2, sizeof w2, "%s.octaves", where);
    if (J(ics_jint(&c->j, w2, x, 1, 16, &iv))) return -1;
    d->octaves = (int)iv;
  }
  if ((x = json_object_get(o, "seed"))) {
    snprintf(w2, sizeof w2, "%s.seed", where);
    if (J(ics_jint(&c->j, w2, x, 0, INT64_MAX, &iv))) return -1;
    d->seed = (uint64_t)iv;
  }
  if (d->fn == ICS_DETAIL_GRID) return read_grid(c, where, o, d, mi);
  return 0;
}

static int read_material(rctx *c, const char *name, json_t *o, ics_material *m) {
  static const char *const known[] = {"color", "opacity", "extinction", "transport", "detail",
                                      "transfer"};
  char where[4096 + 256];
  snprintf(where, sizeof where, "%s: materials.%s", c->name, name);
  char w2[sizeof where + 32];
  if (strlen(name) >= sizeof m->name)
    return fail(c, ICS_ERR_RANGE, "%s: material name longer than %zu bytes", where,
                sizeof m->name - 1);
  snprintf(m->name, sizeof m->name, "%s", name);
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where);
  if (J(ics_jkeys(&c->j, where, o, known, 6))) return -1;
  json_t *x;
  m->color[0] = m->color[1] = m->color[2] = 1;
  snprintf(w2, sizeof w2, "%s.color", where);
  if ((x = json_object_get(o, "color")) && nonneg_vec(c, w2, x, 3, m->color, "r, g, b", 1e30))
    return -1;
  snprintf(w2, sizeof w2, "%s.transport", where);
  if ((x = json_object_get(o, "transport")) && nonneg_vec(c, w2, x, 3, m->transport, "r, g, b", 1))
    return -1;
  json_t *op = json_object_get(o, "opacity"), *ex = json_object_get(o, "extinction");
  if (op && ex)
    return fail(c, ICS_ERR_PARSE, "%s: both \"opacity\" (a surface) and \"extinction\" (a "
                "volume): give one", where);
  m->opacity = 1;
  if (op) {
    snprintf(w2, sizeof w2, "%s.opacity", where);
    if (J(ics_jnum(&c->j, w2, op, &m->opacity))) return -1;
    if (m->opacity < 0 || m->opacity > 1)
      return fail(c, ICS_ERR_RANGE, "%s: %.17g is out of range [0, 1]", w2, m->opacity);
  }
  if (ex) {
    m->volumetric = 1;
    m->opacity = 0;
    snprintf(w2, sizeof w2, "%s.extinction", where);
    if (J(ics_jnum(&c->j, w2, ex, &m->extinction))) return -1;
    if (m->extinction < 0)
      return fail(c, ICS_ERR_RANGE, "%s: negative extinction %.17g (must be >= 0 per world unit)",
                  w2, m->extinction);
  }
  json_t *det = json_object_get(o, "detail"), *tf = json_object_get(o, "transfer");
  if (det && !ex)
    return fail(c, ICS_ERR_PARSE, "%s: \"detail\" needs a volumetric material (\"extinction\")",
                where);
  if (tf && !det)
    return fail(c, ICS_ERR_PARSE, "%s: \"transfer\" maps detail values: it needs \"detail\"", where);
  if (det && read_detail(c, where, det, &m->detail, (int)(m - c->s->materials))) return -1;
  if (tf) {
    snprintf(w2, sizeof w2, "%s.transfer", where);
    if (!json_is_array(tf) || json_array_size(tf) < 2 || json_array_size(tf) > ICS_SCENE_MAX_TRANSFER)
      return fail(c, ICS_ERR_PARSE, "%s: expected 2..%d rows [v, r, g, b, extinction_scale]", w2,
                  ICS_SCENE_MAX_TRANSFER);
    m->ntransfer = (int)json_array_size(tf);
    for (int i = 0; i < m->ntransfer; i++) {
      char w3[sizeof w2 + 32];
      snprintf(w3, sizeof w3, "%s[%d]", w2, i);
      if (J(ics_jvec(&c->j, w3, json_array_get(tf, (size_t)i), 5, m->transfer[i],
                     "v, r, g, b, extinction_scale")))
        return -1;
      for (int k = 1; k < 5; k++)
        if (m->transfer[i][k] < 0)
          return fail(c, ICS_ERR_RANGE, "%s: colour and extinction scale must be >= 0", w3);
      if (i > 0 && !(m->transfer[i][0] > m->transfer[i - 1][0]))
        return fail(c, ICS_ERR_RANGE, "%s: values v must increase (%.17g after %.17g)", w3,
                    m->transfer[i][0], m->transfer[i - 1][0]);
    }
  }
  return 0;
}

static int read_materials(rctx *c, json_t *o) {
  if (!o) return fail(c, ICS_ERR_PARSE, "%s: missing \"materials\"", c->name);
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where_at(c, "materials"));
  size_t n = json_object_size(o);
  if (n == 0 || n > ICS_SCENE_MAX_MATERIALS)
    return fail(c, ICS_ERR_SIZE, "%s: must hold 1..%d materials, not %zu", where_at(c, "materials"),
                ICS_SCENE_MAX_MATERIALS, n);
  c->s->materials = calloc(n, sizeof *c->s->materials);
  if (!c->s->materials) return fail(c, ICS_ERR_NOMEM, "out of memory");
  const char *key;
  json_t *val;
  json_object_foreach(o, key, val) {
    /* counted before it is read, so what a failed read allocated (a grid) is freed with the
     * scene */
    if (read_material(c, key, val, &c->s->materials[c->s->nmaterials++])) return -1;
  }
  return 0;
}

/* ---- objects ------------------------------------------------------------------------------- */
static ics_object *new_object(rctx *c) {
  ics_scene *s = c->s;
  if (s->nobjects == ICS_SCENE_MAX_OBJECTS) {
    fail(c, ICS_ERR_SIZE, "%s: more than %d objects (after fences are expanded)", c->name,
         ICS_SCENE_MAX_OBJECTS);
    return NULL;
  }
  if (s->nobjects == c->obj_cap) {
    int cap = c->obj_cap ? 2 * c->obj_cap : 16;
    ics_object *p = realloc(s->objects, sizeof *p * (size_t)cap);
    if (!p) {
      fail(c, ICS_ERR_NOMEM, "out of memory");
      return NULL;
    }
    s->objects = p;
    c->obj_cap = cap;
  }
  ics_object *o = &s->objects[s->nobjects++];
  memset(o, 0, sizeof *o);
  return o;
}

/* an object's keys: "shape", "material" and the shape's own n (n <= 14) */
static int has_only(rctx *c, const char *where, json_t *o, const char *shape,
                    const char *const *keys, size_t n) {
  const char *known[16] = {"shape", "material"};
  for (size_t i = 0; i < n; i++) known[2 + i] = keys[i];
  return J(ics_jkeys_of(&c->j, where, o, known, 2 + n, shape));
}

static json_t *need(rctx *c, const char *where, json_t *o, const char *key) {
  json_t *v = json_object_get(o, key);
  if (!v) fail(c, ICS_ERR_PARSE, "%s: missing \"%s\"", where, key);
  return v;
}

/* the "shape" values, in the order of the kinds read_object dispatches on */
static const char *const shape_names[] = {"rect", "disk", "box", "sphere", "torus", "mesh", "fence"};

/* a rect or disk (kind 0, 1): an open surface, never a volume's bound */
static int read_open_shape(rctx *c, int idx, json_t *o, const char *where, int kind, int mi) {
  char w2[4096 + 64 + 32];
#define KEY(k) (snprintf(w2, sizeof w2, "%s.%s", where, k), w2)
  const ics_material *m = &c->s->materials[mi];
  double center[3], n3[3];
  json_t *x;
  static const char *const rk[] = {"center", "normal", "size", "up"};
  static const char *const dk[] = {"center", "normal", "radius"};
  if (has_only(c, where, o, shape_names[kind], kind == 0 ? rk : dk, kind == 0 ? 4 : 3)) return -1;
  if (m->volumetric)
    return fail(c, ICS_ERR_PARSE, "%s: volumetric material \"%s\" on an open shape (%s): only "
                "closed shapes bound volumes", KEY("material"), m->name, shape_names[kind]);
  if (!(x = need(c, where, o, "center")) || J(ics_jvec(&c->j, KEY("center"), x, 3, center, "x, y, z")))
    return -1;
  if (!(x = need(c, where, o, "normal")) || nonzero_vec3(c, KEY("normal"), x, n3)) return -1;
  ics_object *ob = new_object(c);
  if (!ob) return -1;
  ob->shape = kind == 0 ? ICS_SHAPE_RECT : ICS_SHAPE_DISK;
  memcpy(ob->center, center, sizeof center);
  ob->material = mi;
  ob->source = idx;
  if (kind == 0) {
    double sz[2], up[3], *upp = NULL;
    if (!(x = need(c, where, o, "size")) || J(ics_jvec(&c->j, KEY("size"), x, 2, sz, "sx, sy")))
      return -1;
    if (!(sz[0] > 0 && sz[1] > 0)) return fail(c, ICS_ERR_RANGE, "%s: sides must be > 0", KEY("size"));
    if ((x = json_object_get(o, "up"))) {
      if (nonzero_vec3(c, KEY("up"), x, up)) return -1;
      upp = up;
    }
    ics_frame_from_normal(n3, upp, ob->ax);
    ob->half[0] = sz[0] / 2, ob->half[1] = sz[1] / 2;
  } else {
    if (!(x = need(c, where, o, "radius")) || positive(c, KEY("radius"), x, &ob->half[0])) return -1;
    ics_frame_from_normal(n3, NULL, ob->ax);
  }
  return 0;
#undef KEY
}

/* a box, sphere or torus (kind 2, 3, 4): a closed shape */
static int read_closed_shape(rctx *c, int idx, json_t *o, const char *where, int kind, int mi) {
  char w2[4096 + 64 + 32];
#define KEY(k) (snprintf(w2, sizeof w2, "%s.%s", where, k), w2)
  double center[3], v3[3], n3[3], rot[3] = {0, 0, 0};
  json_t *x;
  static const char *const bk[] = {"center", "size", "rotate_deg"};
  static const char *const sk[] = {"center", "radius"};
  static const char *const tk[] = {"center", "normal", "major_radius", "minor_radius"};
  const char *const *keys = kind == 2 ? bk : kind == 3 ? sk : tk;
  if (has_only(c, where, o, shape_names[kind], keys, kind == 2 ? 3 : kind == 3 ? 2 : 4)) return -1;
  if (!(x = need(c, where, o, "center")) || J(ics_jvec(&c->j, KEY("center"), x, 3, center, "x, y, z")))
    return -1;
  ics_object *ob = new_object(c);
  if (!ob) return -1;
  ob->shape = kind == 2 ? ICS_SHAPE_BOX : kind == 3 ? ICS_SHAPE_SPHERE : ICS_SHAPE_TORUS;
  ob->closed = 1;
  ob->material = mi;
  ob->source = idx;
  memcpy(ob->center, center, sizeof center);
  double id[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  memcpy(ob->ax, id, sizeof id);
  if (kind == 2) {
    if (!(x = need(c, where, o, "size")) || J(ics_jvec(&c->j, KEY("size"), x, 3, v3, "sx, sy, sz")))
      return -1;
    if (!(v3[0] > 0 && v3[1] > 0 && v3[2] > 0))
      return fail(c, ICS_ERR_RANGE, "%s: sides must be > 0", KEY("size"));
    for (int i = 0; i < 3; i++) ob->half[i] = v3[i] / 2;
    if ((x = json_object_get(o, "rotate_deg"))) {
      if (J(ics_jvec(&c->j, KEY("rotate_deg"), x, 3, rot, "rx, ry, rz"))) return -1;
      ics_frame_rotate(ob->ax, rot);
    }
  } else if (kind == 3) {
    if (!(x = need(c, where, o, "radius")) || positive(c, KEY("radius"), x, &ob->half[0])) return -1;
  } else {
    if (!(x = need(c, where, o, "normal")) || nonzero_vec3(c, KEY("normal"), x, n3)) return -1;
    if (!(x = need(c, where, o, "major_radius")) || positive(c, KEY("major_radius"), x, &ob->half[0]) ||
        !(x = need(c, where, o, "minor_radius")) || positive(c, KEY("minor_radius"), x, &ob->half[1]))
      return -1;
    if (!(ob->half[1] < ob->half[0]))
      return fail(c, ICS_ERR_RANGE, "%s: must be smaller than major_radius", KEY("minor_radius"));
    ics_frame_from_normal(n3, NULL, ob->ax);
  }
  return 0;
#undef KEY
}

/* a fence: its poles and its bar, expanded into boxes */
static int read_fence(rctx *c, int idx, json_t *o, const char *where, int mi) {
  char w2[4096 + 64 + 32];
#define KEY(k) (snprintf(w2, sizeof w2, "%s.%s", where, k), w2)
  double center[3], rot[3] = {0, 0, 0};
  json_t *x;
  static const char *const fk[] = {"center", "poles", "pole_size", "spacing", "bar_size",
                                   "rotate_deg"};
  if (has_only(c, where, o, "fence", fk, 6)) return -1;
  double ps[3], bs[2], spacing;
  long long np;
  if (!(x = need(c, where, o, "center")) || J(ics_jvec(&c->j, KEY("center"), x, 3, center, "x, y, z")) ||
      !(x = need(c, where, o, "poles")) || J(ics_jint(&c->j, KEY("poles"), x, 1, 1000, &np)) ||
      !(x = need(c, where, o, "pole_size")) ||
      J(ics_jvec(&c->j, KEY("pole_size"), x, 3, ps, "width, height, depth")) ||
      !(x = need(c, where, o, "spacing")) || positive(c, KEY("spacing"), x, &spacing) ||
      !(x = need(c, where, o, "bar_size")) ||
      J(ics_jvec(&c->j, KEY("bar_size"), x, 2, bs, "height, depth")))
    return -1;
  if (!(ps[0] > 0 && ps[1] > 0 && ps[2] > 0))
    return fail(c, ICS_ERR_RANGE, "%s: sizes must be > 0", KEY("pole_size"));
  if (!(bs[0] > 0 && bs[1] > 0 && bs[0] < ps[1]))
    return fail(c, ICS_ERR_RANGE, "%s: sizes must be > 0 and the bar lower than the poles",
                KEY("bar_size"));
  if (!(spacing > ps[0]))
    return fail(c, ICS_ERR_RANGE, "%s: must exceed the pole width (poles may not overlap)",
                KEY("spacing"));
  if ((x = json_object_get(o, "rotate_deg")) &&
      J(ics_jvec(&c->j, KEY("rotate_deg"), x, 3, rot, "rx, ry, rz")))
    return -1;
  double ax[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  ics_frame_rotate(ax, rot);
  double span = (double)(np - 1) * spacing;
  for (long long i = 0; i <= np; i++) {
    /* i < np: a pole from the ground to the bar's underside; i == np: the bar */
    double local[3], half[3];
    if (i < np) {
      local[0] = -span / 2 + (double)i * spacing, local[1] = (ps[1] - bs[0]) / 2, local[2] = 0;
      half[0] = ps[0] / 2, half[1] = (ps[1] - bs[0]) / 2, half[2] = ps[2] / 2;
    } else {
      local[0] = 0, local[1] = ps[1] - bs[0] / 2, local[2] = 0;
      half[0] = (span + ps[0]) / 2, half[1] = bs[0] / 2, half[2] = bs[1] / 2;
    }
    ics_object *ob = new_object(c);
    if (!ob) return -1;
    ob->shape = ICS_SHAPE_BOX;
    ob->closed = 1;
    ob->material = mi;
    ob->source = idx;
    memcpy(ob->ax, ax, sizeof ax);
    memcpy(ob->half, half, sizeof half);
    for (int w = 0; w < 3; w++)
      ob->center[w] = center[w] + local[0] * ax[0][w] + local[1] * ax[1][w] + local[2] * ax[2][w];
  }
  return 0;
#undef KEY
}

/* a mesh from a file (Assimp or the PLY reader), in the scene's folder or below */
static int read_mesh_object(rctx *c, int idx, json_t *o, const char *where, int mi) {
  char w2[4096 + 64 + 32];
#define KEY(k) (snprintf(w2, sizeof w2, "%s.%s", where, k), w2)
  const ics_material *m = &c->s->materials[mi];
  double rot[3] = {0, 0, 0};
  json_t *x;
  static const char *const mk[] = {"file", "translate", "scale", "rotate_deg"};
  if (has_only(c, where, o, "mesh", mk, 4)) return -1;
  double tr[3] = {0, 0, 0}, sc[3] = {1, 1, 1};
  if (!(x = need(c, where, o, "file"))) return -1;
  if (!json_is_string(x)) return fail(c, ICS_ERR_PARSE, "%s: expected a file name", KEY("file"));
  json_t *t;
  if ((t = json_object_get(o, "translate")) && J(ics_jvec(&c->j, KEY("translate"), t, 3, tr, "x, y, z")))
    return -1;
  if ((t = json_object_get(o, "scale"))) {
    if (json_is_number(t)) {
      sc[0] = sc[1] = sc[2] = json_number_value(t);
    } else if (J(ics_jvec(&c->j, KEY("scale"), t, 3, sc, "sx, sy, sz"))) {
      return -1;
    }
    if (!(sc[0] != 0 && sc[1] != 0 && sc[2] != 0) || !isfinite(sc[0] * sc[1] * sc[2]))
      return fail(c, ICS_ERR_RANGE, "%s: must be finite and non-zero", KEY("scale"));
  }
  if ((t = json_object_get(o, "rotate_deg")) && J(ics_jvec(&c->j, KEY("rotate_deg"), t, 3, rot, "rx, ry, rz")))
    return -1;
  char *path = join_path(c->dir, json_string_value(x));
  if (!path) return fail(c, ICS_ERR_NOMEM, "out of memory");
  if (may_read(c, KEY("file"), path)) {
    free(path);
    return -1;
  }
  /* the memory limit before the work: a PLY header's face count before the file is read, the
   * triangles read before this object's copy is built */
  const ics_mesh_raw *raw = mesh_read_before(c, path);
  uint64_t faces = raw || !ics_mesh_files_supported() ? 0 : ics_mesh_file_faces(path);
  char what[128];
  snprintf(what, sizeof what, "its PLY header declares %llu faces: at least ",
           (unsigned long long)faces);
  if ((faces && fits(c, KEY("file"), what, ics_mesh_bytes_min(faces))) ||
      (raw && fits(c, KEY("file"), "at least ", ics_mesh_bytes_min(raw->nt)))) {
    free(path);
    return -1;
  }
  ics_mesh *mesh;
  char mmsg[4096 + 512];
  ics_status st;
  if (raw || (raw = mesh_file(c, path, mmsg, sizeof mmsg, &st)))
    st = ics_mesh_create_raw(&mesh, raw, sc, rot, tr, path, mmsg, sizeof mmsg);
  free(path);
  if (st != ICS_OK) return fail(c, st, "%s: %s", KEY("file"), mmsg);
  if (account(c, KEY("file"), (double)ics_mesh_bytes(mesh))) {
    ics_mesh_destroy(mesh);
    return -1;
  }
  ics_mesh **mp = realloc(c->s->meshes, sizeof *mp * (size_t)(c->s->nmeshes + 1));
  if (!mp) {
    ics_mesh_destroy(mesh);
    return fail(c, ICS_ERR_NOMEM, "out of memory");
  }
  c->s->meshes = mp;
  mp[c->s->nmeshes++] = mesh;
  if (m->volumetric && !ics_mesh_closed(mesh))
    return fail(c, ICS_ERR_PARSE, "%s: volumetric material \"%s\" on an open mesh (some edge is "
                "not shared by exactly two triangles): only closed meshes bound volumes",
                KEY("material"), m->name);
  ics_object *ob = new_object(c);
  if (!ob) return -1;
  ob->shape = ICS_SHAPE_MESH;
  ob->closed = ics_mesh_closed(mesh);
  ob->material = mi;
  ob->source = idx;
  ob->mesh = mesh;
  double id[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  memcpy(ob->ax, id, sizeof id);
  return 0;
#undef KEY
}

static int read_object(rctx *c, int idx, json_t *o) {
  char where[4096 + 64];
  snprintf(where, sizeof where, "%s: objects[%d]", c->name, idx);
  char w2[sizeof where + 32];
#define KEY(k) (snprintf(w2, sizeof w2, "%s.%s", where, k), w2)
  if (!json_is_object(o)) return fail(c, ICS_ERR_PARSE, "%s: expected an object", where);
  json_t *sh = json_object_get(o, "shape"), *mat = json_object_get(o, "material");
  if (!sh) return fail(c, ICS_ERR_PARSE, "%s: missing \"shape\"", where);
  if (!mat) return fail(c, ICS_ERR_PARSE, "%s: missing \"material\"", where);
  int kind;
  if (J(ics_jenum(&c->j, KEY("shape"), sh, shape_names, 7, &kind))) return -1;
  if (!json_is_string(mat)) return fail(c, ICS_ERR_PARSE, "%s: expected a material name", KEY("material"));
  int mi = -1;
  for (int i = 0; i < c->s->nmaterials; i++)
    if (!strcmp(c->s->materials[i].name, json_string_value(mat))) mi = i;
  if (mi < 0)
    return fail(c, ICS_ERR_PARSE, "%s: no material named \"%s\" in \"materials\"", KEY("material"),
                json_string_value(mat));
  if (kind == 0 || kind == 1) return read_open_shape(c, idx, o, where, kind, mi);
  if (kind == 2 || kind == 3 || kind == 4) return read_closed_shape(c, idx, o, where, kind, mi);
  if (kind == 6) return read_fence(c, idx, o, where, mi);
  return read_mesh_object(c, idx, o, where, mi);
#undef KEY
}

static int read_objects(rctx *c, json_t *arr) {
  if (!arr) return fail(c, ICS_ERR_PARSE, "%s: missing \"objects\"", c->name);
  if (!json_is_array(arr)) return fail(c, ICS_ERR_PARSE, "%s: expected an array", where_at(c, "objects"));
  size_t n = json_array_size(arr);
  if (n == 0) return fail(c, ICS_ERR_SIZE, "%s: no objects", where_at(c, "objects"));
  if (n > ICS_SCENE_MAX_OBJECTS)
    return fail(c, ICS_ERR_SIZE, "%s: %zu objects (at most %d)", where_at(c, "objects"), n,
                ICS_SCENE_MAX_OBJECTS);
  for (size_t i = 0; i < n; i++)
    if (read_object(c, (int)i, json_array_get(arr, i))) return -1;
  return 0;
}

static ics_status read_root(rctx *c, json_t *root) {
  static const char *const known[] = {"camera", "render", "lights", "lights_file", "materials",
                                      "objects"};
  if (!json_is_object(root)) return fail(c, ICS_ERR_PARSE, "%s: expected a JSON object", c->name), c->st;
  if (J(ics_jkeys(&c->j, c->name, root, known, 6))) return c->st;
  json_t *cam = json_object_get(root, "camera"), *ren = json_object_get(root, "render");
  if (!cam) return fail(c, ICS_ERR_PARSE, "%s: missing \"camera\"", c->name), c->st;
  if (!ren) return fail(c, ICS_ERR_PARSE, "%s: missing \"render\"", c->name), c->st;
  if (read_camera(c, cam) || read_render(c, ren) ||
      read_lights(c, json_object_get(root, "lights"), json_object_get(root, "lights_file")) ||
      read_materials(c, json_object_get(root, "materials")) || check_radiance(c) ||
      read_objects(c, json_object_get(root, "objects")) || load_used_grids(c) ||
      check_extinction(c))
    return c->st;
  return ICS_OK;
}

/* c->root: the scene's folder resolved, unless the options allow files anywhere; a folder that
 * does not resolve (missing) stays as given: no real path lies in it, and a relative one inside
 * it fails to open with its own reason */
static ics_status resolve_root(rctx *c, const ics_scene_opts *opts) {
  if (opts && opts->allow_outside_paths) return ICS_OK;
  const char *dir = c->dir && c->dir[0] ? c->dir : ".";
  errno = 0;
  if ((c->root = realpath(dir, NULL)) || (errno != ENOMEM && (c->root = strdup(dir))))
    return ICS_OK;
  if (c->j.msg) snprintf(c->j.msg, c->j.msg_size, "out of memory");
  return ICS_ERR_NOMEM;
}

/* opts->render_json's members over root's "render" object (when both are objects: a missing or
 * malformed "render" is reported by read_root as it would be without overrides) */
static ics_status override_render(json_t *root, const ics_scene_opts *opts, char *msg,
                                  size_t msg_size) {
  if (!opts || !opts->render_json) return ICS_OK;
  json_error_t je;
  json_t *o = json_loads(opts->render_json, JSON_REJECT_DUPLICATES, &je);
  ics_status st = ICS_OK;
  if (!o || !json_is_object(o)) {
    if (msg) snprintf(msg, msg_size, "render overrides: %s", o ? "expected a JSON object" : je.text);
    st = ICS_ERR_PARSE;
  } else {
    json_t *ren = json_is_object(root) ? json_object_get(root, "render") : NULL;
    if (json_is_object(ren) && json_object_update(ren, o) != 0) {
      if (msg) snprintf(msg, msg_size, "out of memory");
      st = ICS_ERR_NOMEM;
    }
  }
  json_decref(o);
  return st;
}

/* file: the scene file (the first of the scene's files), or NULL */
static ics_status create(ics_scene **out, json_t *root, const char *name, const char *dir,
                         const char *file, const ics_scene_opts *opts, char *msg,
                         size_t msg_size) {
  ics_status ost = override_render(root, opts, msg, msg_size);
  if (ost != ICS_OK) {
    json_decref(root);
    return ost;
  }
  rctx c = {.j = {msg, msg_size}, .name = name, .dir = dir, .st = ICS_ERR_PARSE,
            .where_size = strlen(name) + 256};
  c.where = malloc(c.where_size);
  c.s = calloc(1, sizeof *c.s);
  if (!c.where || !c.s) {
    free(c.where);
    free(c.s);
    json_decref(root);
    if (msg) snprintf(msg, msg_size, "out of memory");
    return ICS_ERR_NOMEM;
  }
  snprintf(c.s->name, sizeof c.s->name, "%s", name);
  ics_render_settings_defaults(&c.s->settings);
  ics_status st = file ? ics_scene_note_file(c.s, file) : ICS_OK;
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "out of memory");
  } else if ((st = resolve_root(&c, opts)) == ICS_OK) {
    st = read_root(&c, root);
  }
  free(c.root);
  for (int i = 0; i < ICS_SCENE_MAX_MATERIALS; i++) free(c.grid_path[i]);
  for (int i = 0; i < c.nread; i++) free(c.read[i].path), ics_mesh_raw_release(&c.read[i].raw);
  free(c.read);
  json_decref(root);
  free(c.where);
  if (st != ICS_OK) {
    ics_scene_destroy(c.s);
    return st;
  }
  *out = c.s;
  return ICS_OK;
}

ics_status ics_scene_create_json(ics_scene **out, const char *json, const char *name,
                                 const char *dir, char *msg, size_t msg_size) {
  return ics_scene_create_json_opts(out, json, name, dir, NULL, msg, msg_size);
}

ics_status ics_scene_create_json_opts(ics_scene **out, const char *json, const char *name,
                                      const char *dir, const ics_scene_opts *opts, char *msg,
                                      size_t msg_size) {
  *out = NULL;
  if (msg && msg_size) msg[0] = 0;
  json_error_t je;
  json_t *root = json_loads(json, JSON_REJECT_DUPLICATES, &je);
  if (!root) {
    if (msg) snprintf(msg, msg_size, "%s:%d:%d: %s", name, je.line, je.column, je.text);
    return ICS_ERR_PARSE;
  }
  return create(out, root, name, dir, NULL, opts, msg, msg_size);
}

ics_status ics_scene_create_file(ics_scene **out, const char *path, char *msg, size_t msg_size) {
  return ics_scene_create_file_opts(out, path, NULL, msg, msg_size);
}

ics_status ics_scene_create_file_opts(ics_scene **out, const char *path,
                                      const ics_scene_opts *opts, char *msg, size_t msg_size) {
  *out = NULL;
  if (msg && msg_size) msg[0] = 0;
  ics_jctx jc = {msg, msg_size};
  ics_status ost;
  json_t *root = ics_jload_file(&jc, path, ICS_SCENE_FILE_MAX, ICS_INPUT_STREAM, "scene", &ost);
  if (!root) return ost;
  /* the scene's folder resolves relative paths */
  char *dir = strdup(path);
  if (!dir) {
    json_decref(root);
    return ICS_ERR_NOMEM;
  }
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = 0;
  else
    strcpy(dir, ".");
  if (slash == dir) strcpy(dir, "/");
  ics_status st = create(out, root, path, dir, path, opts, msg, msg_size);
  free(dir);
  return st;
}
