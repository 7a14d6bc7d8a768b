/* scene.c — the scene object: lifecycle, accessors, names, default settings, the camera frame,
 * and the embedded default scene (docs/scene-format.md "The default scene"). The JSON reader is
 * scene_json.c; meshes are mesh.c. */
#include "scene_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

static const char *const kernel_names[ICS_RK_COUNT_] = {"ellipse", "poisson", "gauss", "tophat"};
static const char *const comp_names[ICS_RC_COUNT_] = {"default", "expected", "integer",
                                                      "nonneg",  "signed",   "none"};
static const char *const model_names[ICS_MODEL_COUNT_] = {"patel", "solid", "surface", "blocker",
                                                          "auto"};
static const char *const shape_names[ICS_SHAPE_COUNT_] = {"rect",   "disk",  "box",
                                                          "sphere", "torus", "mesh"};

const char *ics_render_kernel_name(ics_render_kernel k) {
  return (unsigned)k < ICS_RK_COUNT_ ? kernel_names[k] : NULL;
}
const char *ics_render_comp_name(ics_render_comp c) {
  return (unsigned)c < ICS_RC_COUNT_ ? comp_names[c] : NULL;
}
const char *ics_render_model_name(ics_render_model m) {
  return (unsigned)m < ICS_MODEL_COUNT_ ? model_names[m] : NULL;
}
const char *ics_shape_name(ics_shape s) {
  return (unsigned)s < ICS_SHAPE_COUNT_ ? shape_names[s] : NULL;
}

void ics_render_settings_defaults(ics_render_settings *s) {
  memset(s, 0, sizeof *s);
  s->kernel = ICS_RK_ELLIPSE;
  s->compensate = ICS_RC_DEFAULT;
  s->max_pad = -1;
  s->pixel_rotations = 2;
  s->rotation_run = 1;
  s->memory_limit_mib = 4096;
  s->model = ICS_MODEL_AUTO;
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void cross3(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

ics_status ics_camera_derive(ics_camera *c, char *msg, size_t msg_size) {
  double f[3] = {c->target[0] - c->eye[0], c->target[1] - c->eye[1], c->target[2] - c->eye[2]};
  double nf = sqrt(dot3(f, f));
  if (!(nf > 0) || !isfinite(nf)) {
    if (msg) snprintf(msg, msg_size, "camera: eye and target must differ");
    return ICS_ERR_RANGE;
  }
  for (int i = 0; i < 3; i++) f[i] /= nf;
  double nu = sqrt(dot3(c->up, c->up));
  double r[3];
  cross3(f, c->up, r);
  double nr = sqrt(dot3(r, r));
  if (!(nu > 0) || !(nr > 1e-9 * nu)) {
    if (msg) snprintf(msg, msg_size, "camera: up must not be zero or parallel to target - eye");
    return ICS_ERR_RANGE;
  }
  for (int i = 0; i < 3; i++) r[i] /= nr;
  double u[3];
  cross3(r, f, u);
  memcpy(c->r, r, sizeof r);
  memcpy(c->u, u, sizeof u);
  memcpy(c->f, f, sizeof f);
  return ICS_OK;
}

void ics_scene_free_parts(ics_scene *s) {
  if (!s) return;
  for (int i = 0; i < s->nmaterials; i++) free(s->materials[i].detail.grid);
  free(s->materials);
  free(s->objects);
  for (int i = 0; i < s->nmeshes; i++) ics_mesh_destroy(s->meshes[i]);
  free(s->meshes);
  for (int i = 0; i < s->nfiles; i++) free(s->files[i]);
  free(s->files);
  s->files = NULL;
  s->nfiles = 0;
  s->materials = NULL;
  s->objects = NULL;
  s->meshes = NULL;
  s->nmaterials = s->nobjects = s->nmeshes = 0;
}

void ics_scene_destroy(ics_scene *s) {
  if (!s) return;
  ics_scene_free_parts(s);
  free(s);
}

const ics_camera *ics_scene_camera(const ics_scene *s) { return &s->camera; }
const ics_render_settings *ics_scene_settings(const ics_scene *s) { return &s->settings; }
int ics_scene_light_count(const ics_scene *s) { return s->nlights; }
const ics_light *ics_scene_light(const ics_scene *s, int k) {
  return k >= 0 && k < s->nlights ? &s->lights[k] : NULL;
}
int ics_scene_material_count(const ics_scene *s) { return s->nmaterials; }
const ics_material *ics_scene_material(const ics_scene *s, int k) {
  return k >= 0 && k < s->nmaterials ? &s->materials[k] : NULL;
}
int ics_scene_object_count(const ics_scene *s) { return s->nobjects; }
const ics_object *ics_scene_object(const ics_scene *s, int k) {
  return k >= 0 && k < s->nobjects ? &s->objects[k] : NULL;
}
const char *ics_scene_name(const ics_scene *s) { return s->name; }

ics_status ics_scene_note_file(ics_scene *s, const char *path) {
  char **f = realloc(s->files, sizeof *f * (size_t)(s->nfiles + 1));
  if (!f) return ICS_ERR_NOMEM;
  s->files = f;
  size_t n = strlen(path) + 1;
  if (!(f[s->nfiles] = malloc(n))) return ICS_ERR_NOMEM;
  memcpy(f[s->nfiles], path, n);
  s->nfiles++;
  return ICS_OK;
}
int ics_scene_file_count(const ics_scene *s) { return s->nfiles; }
const char *ics_scene_file(const ics_scene *s, int k) {
  return k >= 0 && k < s->nfiles ? s->files[k] : NULL;
}

/* The embedded default scene as a scene file, so that it goes through the one reader and
 * `icshadow plan` / docs can show it verbatim (ics_scene_default_json). An object with
 * procedural detail (a sphere of fBm smoke) over a floor and in front of a wall, a small opaque
 * torus beside it, two coloured lights (Patel Fig. 7d in spirit). */
static const char default_json[] =
    "{\n"
    "  \"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 1.0, 3], \"target\": [0, 0.25, 0],\n"
    "             \"up\": [0, 1, 0], \"height\": 2.4, \"resolution\": [320, 240]},\n"
    "  \"render\": {\"model\": \"auto\", \"slab_spacing\": 0.045, \"d1\": 1.0, \"kernel\": \"ellipse\",\n"
    "             \"samples\": 2, \"seed\": 1, \"background\": [0.02, 0.02, 0.03]},\n"
    "  \"lights\": [\n"
    "    {\"mean\": [-0.4, 0.5], \"var\": [0.012, 0.004], \"angle_deg\": 30, \"color\": [1.0, 0.78, 0.5],\n"
    "     \"weight\": 0.85},\n"
    "    {\"mean\": [0.35, 0.2], \"var\": [0.03, 0.03], \"color\": [0.45, 0.6, 1.0], \"weight\": 0.45}\n"
    "  ],\n"
    "  \"materials\": {\n"
    "    \"floor\": {\"color\": [0.85, 0.85, 0.8]},\n"
    "    \"wall\": {\"color\": [0.75, 0.78, 0.85]},\n"
    "    \"copper\": {\"color\": [0.9, 0.45, 0.25]},\n"
    "    \"smoke\": {\"color\": [0.95, 0.9, 0.85], \"extinction\": 14, \"transport\": [0.25, 0.12, 0.05],\n"
    "              \"detail\": {\"function\": \"fbm\", \"frequency\": 2.5, \"octaves\": 4, \"gain\": 0.5,\n"
    "                         \"lacunarity\": 2, \"scale\": 1.6, \"bias\": 0.1, \"seed\": 3},\n"
    "              \"transfer\": [[0, 0.9, 0.5, 0.2, 0], [0.4, 0.95, 0.75, 0.45, 0.6], [1, 1, 0.97, 0.9, 1.4]]}\n"
    "  },\n"
    "  \"objects\": [\n"
    "    {\"shape\": \"rect\", \"center\": [0, -0.55, 0.2], \"normal\": [0, 1, 0], \"size\": [4, 3.0], \"material\": \"floor\"},\n"
    "    {\"shape\": \"rect\", \"center\": [0, 0.8, -1.3], \"normal\": [0, 0, 1], \"size\": [4, 2.8], \"material\": \"wall\"},\n"
    "    {\"shape\": \"sphere\", \"center\": [-0.25, 0.15, 0], \"radius\": 0.62, \"material\": \"smoke\"},\n"
    "    {\"shape\": \"torus\", \"center\": [0.85, -0.3, 0.45], \"normal\": [0.3, 1, 0.2],\n"
    "     \"major_radius\": 0.28, \"minor_radius\": 0.09, \"material\": \"copper\"}\n"
    "  ]\n"
    "}\n";

const char *ics_scene_default_json(void) { return default_json; }

ics_status ics_scene_create_default(ics_scene **out) {
  char msg[256];
  ics_status st = ics_scene_create_json(out, default_json, "default", NULL, msg, sizeof msg);
  if (st == ICS_OK) snprintf((*out)->name, sizeof (*out)->name, "default");
  return st;
}
