/* test_render_scene.c — the scene-file reader (docs/scene-format.md): the contract example and
 * every field read back, fences expanded, the lights-file forms, and bad input refused with a
 * message naming the JSON path (or line and column) and the right status. */
#define _XOPEN_SOURCE 700 /* realpath, mkdir */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "icshadow/render.h"
#include "testutil.h"

static const char *contract =
    "{\n"
    "  \"camera\": {\"projection\": \"orthographic\", \"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"up\": [0, 1, 0],\n"
    "             \"height\": 3.0, \"resolution\": [128, 128]},\n"
    "  \"render\": {\"slab_spacing\": 0.01, \"d1\": 1.0, \"kernel\": \"ellipse\", \"samples\": 2, \"seed\": 7},\n"
    "  \"lights\": [{\"mean\": [0.3, -0.1], \"cov\": [[0.02, 0.005], [0.005, 0.01]], \"color\": [1, 1, 1], \"weight\": 1}],\n"
    "  \"materials\": {\"black\": {\"color\": [0, 0, 0], \"opacity\": 1}, \"white\": {\"color\": [1, 1, 1], \"opacity\": 1}},\n"
    "  \"objects\": [\n"
    "    {\"shape\": \"disk\", \"center\": [0, 0, 0], \"normal\": [0, 0, 1], \"radius\": 0.5, \"material\": \"black\"},\n"
    "    {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 3], \"material\": \"white\"}\n"
    "  ]\n"
    "}\n";

static void test_contract(void) {
  char msg[1024];
  ics_scene *s;
  ics_status st = ics_scene_create_json(&s, contract, "contract", NULL, msg, sizeof msg);
  CHECK(st == ICS_OK, "contract example refused: %s", msg);
  if (st != ICS_OK) return;
  const ics_camera *c = ics_scene_camera(s);
  CHECK(c->projection == ICS_PROJ_ORTHOGRAPHIC && c->width == 128 && c->height_px == 128 &&
            c->height == 3.0 && c->eye[2] == 2 && c->target[2] == 0 && c->up[1] == 1,
        "camera fields");
  /* frame: looking along -z, right = +x, up = +y */
  CHECK(c->f[2] == -1 && c->r[0] == 1 && c->u[1] == 1, "camera frame f=(%g %g %g) r=(%g %g %g)",
        c->f[0], c->f[1], c->f[2], c->r[0], c->r[1], c->r[2]);
  const ics_render_settings *r = ics_scene_settings(s);
  CHECK(r->slab_spacing == 0.01 && r->d1 == 1.0 && r->kernel == ICS_RK_ELLIPSE && r->samples == 2 &&
            r->seed == 7 && r->compensate == ICS_RC_DEFAULT && !r->lut_radii,
        "render fields");
  CHECK(r->background[0] == 0 && r->memory_limit_mib == 4096 && r->max_pad < 0, "render defaults");
  CHECK(ics_scene_light_count(s) == 1, "one light");
  const ics_light *l = ics_scene_light(s, 0);
  CHECK(l->mean[0] == 0.3 && l->mean[1] == -0.1 && l->cov[0] == 0.02 && l->cov[1] == 0.005 &&
            l->cov[2] == 0.01 && l->color[1] == 1 && l->weight == 1,
        "light fields");
  CHECK(ics_scene_material_count(s) == 2, "two materials");
  const ics_material *m0 = ics_scene_material(s, 0), *m1 = ics_scene_material(s, 1);
  CHECK(!strcmp(m0->name, "black") && m0->color[0] == 0 && m0->opacity == 1 && !m0->volumetric,
        "material black");
  CHECK(!strcmp(m1->name, "white") && m1->color[2] == 1 && m1->transport[0] == 0, "material white");
  CHECK(ics_scene_object_count(s) == 2, "two objects");
  const ics_object *d = ics_scene_object(s, 0), *q = ics_scene_object(s, 1);
  CHECK(d->shape == ICS_SHAPE_DISK && d->half[0] == 0.5 && d->material == 0 && !d->closed &&
            d->ax[2][2] == 1,
        "disk");
  CHECK(q->shape == ICS_SHAPE_RECT && q->half[0] == 1.5 && q->half[1] == 1.5 && q->center[2] == -1 &&
            q->material == 1,
        "rect");
  ics_scene_destroy(s);
}

static void test_all_fields(void) {
  const char *j =
      "{\"camera\": {\"projection\": \"perspective\", \"eye\": [1, 2, 5], \"target\": [0, 0, 0],"
      " \"fov_deg\": 40, \"resolution\": [64, 48]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 2, \"kernel\": \"poisson\", \"samples\": 16,"
      "  \"compensate\": \"nonneg\", \"radii\": \"lut\", \"seed\": 3, \"background\": [0.1, 0.2, 0.3],"
      "  \"max_pad\": 10, \"memory_limit_mib\": 100},"
      " \"lights\": [{\"tilt_deg\": [10, -20], \"var\": [0.04, 0.01], \"angle_deg\": 30, \"color\": [1, 0.5, 0.25], \"weight\": 2},"
      "             {\"mean\": [0, 0], \"cov\": [[0, 0], [0, 0]]}],"
      " \"materials\": {\"glass\": {\"color\": [0.5, 0.5, 0.5], \"opacity\": 0.25, \"transport\": [1, 0.2, 0.2]},"
      "   \"smoke\": {\"extinction\": 3, \"detail\": {\"function\": \"ridged\", \"frequency\": 2, \"octaves\": 5,"
      "      \"lacunarity\": 2.5, \"gain\": 1.5, \"offset\": 0.9, \"time\": 0.5, \"seed\": 11, \"scale\": 2, \"bias\": -0.5},"
      "      \"transfer\": [[0, 0, 0, 0, 0], [1, 1, 0.5, 0.25, 2]]}},"
      " \"objects\": ["
      "  {\"shape\": \"box\", \"center\": [0, 0, 0], \"size\": [1, 2, 3], \"rotate_deg\": [0, 0, 90], \"material\": \"glass\"},"
      "  {\"shape\": \"sphere\", \"center\": [1, 0, 0], \"radius\": 0.5, \"material\": \"smoke\"},"
      "  {\"shape\": \"torus\", \"center\": [0, 1, 0], \"normal\": [0, 1, 0], \"major_radius\": 1, \"minor_radius\": 0.25, \"material\": \"smoke\"},"
      "  {\"shape\": \"fence\", \"center\": [0, -1, 0], \"poles\": 3, \"pole_size\": [0.1, 1, 0.1], \"spacing\": 0.5,"
      "   \"bar_size\": [0.1, 0.05], \"material\": \"glass\"},"
      "  {\"shape\": \"rect\", \"center\": [0, -1, 0], \"normal\": [0, 1, 0], \"size\": [4, 2], \"up\": [0, 0, -1], \"material\": \"glass\"}]}";
  char msg[1024];
  ics_scene *s;
  ics_status st = ics_scene_create_json(&s, j, "all", NULL, msg, sizeof msg);
  CHECK(st == ICS_OK, "all-fields scene refused: %s", msg);
  if (st != ICS_OK) return;
  const ics_camera *c = ics_scene_camera(s);
  CHECK(c->projection == ICS_PROJ_PERSPECTIVE && c->fov_deg == 40 && c->width == 64, "perspective");
  const ics_render_settings *r = ics_scene_settings(s);
  CHECK(r->kernel == ICS_RK_POISSON && r->samples == 16 && r->compensate == ICS_RC_NONNEG &&
            r->lut_radii && r->seed == 3 && r->background[2] == 0.3 && r->max_pad == 10 &&
            r->memory_limit_mib == 100,
        "render settings");
  const ics_light *l = ics_scene_light(s, 0);
  CHECK(fabs(l->mean[0] - tan(10 * ICS_PI / 180)) < 1e-15 && l->mean[1] < 0 && l->weight == 2 &&
            l->color[2] == 0.25,
        "tilt_deg light mean (%g %g)", l->mean[0], l->mean[1]);
  double vx, vy, ang;
  ics_light_cov_to_eig(l->cov, &vx, &vy, &ang);
  CHECK(fabs(vx - 0.04) < 1e-15 && fabs(vy - 0.01) < 1e-15 && fabs(ang - 30) < 1e-9, "var + angle");
  CHECK(ics_scene_light(s, 1)->cov[0] == 0 && ics_scene_light(s, 1)->color[0] == 1, "point light");
  const ics_material *g = ics_scene_material(s, 0), *k = ics_scene_material(s, 1);
  CHECK(g->opacity == 0.25 && g->transport[1] == 0.2 && !g->volumetric, "glass");
  CHECK(k->volumetric && k->extinction == 3 && k->detail.fn == ICS_DETAIL_RIDGED &&
            k->detail.frequency == 2 && k->detail.octaves == 5 && k->detail.lacunarity == 2.5 &&
            k->detail.gain == 1.5 && k->detail.offset == 0.9 && k->detail.time == 0.5 &&
            k->detail.seed == 11 && k->detail.scale == 2 && k->detail.bias == -0.5 &&
            k->ntransfer == 2 && k->transfer[1][2] == 0.5,
        "smoke");
  /* box, sphere, torus, fence (3 poles + bar = 4 boxes), rect */
  CHECK(ics_scene_object_count(s) == 8, "objects after fence expansion: %d",
        ics_scene_object_count(s));
  const ics_object *b = ics_scene_object(s, 0);
  CHECK(b->shape == ICS_SHAPE_BOX && b->closed && b->half[2] == 1.5 &&
            fabs(b->ax[0][1] - 1) < 1e-15 && fabs(b->ax[0][0]) < 1e-15,
        "box rotated 90 deg about z: local x along world y (%g %g)", b->ax[0][0], b->ax[0][1]);
  const ics_object *t = ics_scene_object(s, 2);
  CHECK(t->shape == ICS_SHAPE_TORUS && t->half[0] == 1 && t->half[1] == 0.25 && t->ax[2][1] == 1,
        "torus");
  for (int i = 3; i < 7; i++) {
    const ics_object *f = ics_scene_object(s, i);
    CHECK(f->shape == ICS_SHAPE_BOX && f->source == 3 && f->closed, "fence part %d", i);
  }
  const ics_object *bar = ics_scene_object(s, 6);
  CHECK(fabs(bar->half[0] - (1.0 + 0.1) / 2) < 1e-15 && fabs(bar->center[1] - (-1 + 1 - 0.05)) < 1e-15,
        "fence bar spans the poles at the top (half %g, y %g)", bar->half[0], bar->center[1]);
  const ics_object *p0 = ics_scene_object(s, 3);
  CHECK(fabs(p0->center[0] + 0.5) < 1e-15 && fabs(p0->half[1] - 0.45) < 1e-15, "first pole");
  const ics_object *rc = ics_scene_object(s, 7);
  CHECK(fabs(rc->ax[1][2] + 1) < 1e-15, "rect up vector honoured");
  ics_scene_destroy(s);
}

static void test_default(void) {
  ics_scene *s;
  CHECK(ics_scene_create_default(&s) == ICS_OK, "default scene");
  if (!s) return;
  CHECK(!strcmp(ics_scene_name(s), "default") && ics_scene_light_count(s) == 2, "default scene content");
  int detail = 0;
  for (int i = 0; i < ics_scene_material_count(s); i++)
    detail |= ics_scene_material(s, i)->detail.fn != ICS_DETAIL_NONE;
  CHECK(detail, "the default scene has procedural detail");
  ics_scene_destroy(s);
}

/* replaces the first occurrence of `from` in the contract example by `to` */
static char *edit(const char *from, const char *to) {
  const char *p = strstr(contract, from);
  if (!p) {
    fprintf(stderr, "test bug: '%s' not in the example\n", from);
    exit(3);
  }
  size_t n = strlen(contract) - strlen(from) + strlen(to) + 1;
  char *s = malloc(n);
  snprintf(s, n, "%.*s%s%s", (int)(p - contract), contract, to, p + strlen(from));
  return s;
}

/* the contract with its "lights" array replaced by `lights_file_entry` (malloc'd) */
static char *with_lights_file(const char *lights_file_entry) {
  return edit("\"lights\": [{\"mean\": [0.3, -0.1], \"cov\": [[0.02, 0.005], [0.005, 0.01]], "
              "\"color\": [1, 1, 1], \"weight\": 1}],",
              lights_file_entry);
}

/* writes a lights file of one red light of weight 3; 0 on success (a failed CHECK otherwise) */
static int write_lights_file(const char *path) {
  FILE *f = fopen(path, "w");
  CHECK(f != NULL, "cannot write %s", path);
  if (!f) return -1;
  fprintf(f, "{\"lights\": [{\"mean\": [0.1, 0.2], \"cov\": [[0.01, 0], [0, 0.02]], \"color\": [1, 0, 0], \"weight\": 3}]}\n");
  return fclose(f) ? -1 : 0;
}

static void expect_error(const char *from, const char *to, ics_status want, const char *want_msg) {
  char *j = edit(from, to);
  char msg[2048] = "";
  ics_scene *s = (ics_scene *)1;
  ics_status st = ics_scene_create_json(&s, j, "bad.json", NULL, msg, sizeof msg);
  CHECK(st == want && s == NULL && strstr(msg, want_msg),
        "edit '%s' -> '%s': status %s (want %s), message '%s' (want '%s')", from, to,
        ics_status_str(st), ics_status_str(want), msg, want_msg);
  free(j);
}

static void test_errors(void) {
  /* syntax: line and column */
  expect_error("\"height\": 3.0,", "\"height\": 3.0,,", ICS_ERR_PARSE, "bad.json:3:28: ");
  expect_error("\"radius\": 0.5", "\"radius\": NaN", ICS_ERR_PARSE, "bad.json:8:77: invalid token");
  expect_error("\"radius\": 0.5", "\"radius\": 1e999", ICS_ERR_PARSE, "bad.json:8:79: real number overflow");
  /* unknown keys and wrong types, by path */
  expect_error("\"radius\": 0.5", "\"radius\": \"big\"", ICS_ERR_PARSE,
               "bad.json: objects[0].radius: expected a number");
  expect_error("\"radius\": 0.5", "\"radius\": 0.5, \"colour\": 1", ICS_ERR_PARSE,
               "objects[0]: unknown key \"colour\" for a disk");
  expect_error("\"seed\": 7", "\"seed\": 7, \"slabs\": 4", ICS_ERR_PARSE,
               "render: unknown key \"slabs\"");
  expect_error("\"height\": 3.0", "\"height\": [3]", ICS_ERR_PARSE, "camera.height: expected a number");
  expect_error("\"kernel\": \"ellipse\"", "\"kernel\": \"box\"", ICS_ERR_PARSE,
               "render.kernel: unknown value \"box\"");
  expect_error("\"material\": \"white\"", "\"material\": \"grey\"", ICS_ERR_PARSE,
               "objects[1].material: no material named \"grey\"");
  expect_error("\"shape\": \"disk\"", "\"shape\": \"cone\"", ICS_ERR_PARSE,
               "objects[0].shape: unknown value \"cone\"");
  expect_error("\"color\": [1, 1, 1], \"weight\": 1", "\"color\": [1, 1], \"weight\": 1",
               ICS_ERR_PARSE, "lights[0].color: expected [r, g, b]");
  /* values */
  expect_error("[[0.02, 0.005], [0.005, 0.01]]", "[[-0.02, 0.005], [0.005, 0.01]]", ICS_ERR_PARSE,
               "lights[0]: cov is not positive semidefinite");
  expect_error("\"mean\": [0.3, -0.1]", "\"tilt_deg\": [90, 0]", ICS_ERR_PARSE,
               "lights[0].tilt_deg: expected [wx, wy] in degrees, |w| < 90");
  expect_error("\"opacity\": 1}, \"white\"", "\"extinction\": -2}, \"white\"", ICS_ERR_RANGE,
               "materials.black.extinction: negative extinction");
  expect_error("\"opacity\": 1}, \"white\"", "\"opacity\": 1.5}, \"white\"", ICS_ERR_RANGE,
               "materials.black.opacity: 1.5 is out of range [0, 1]");
  expect_error("\"radius\": 0.5", "\"radius\": -0.5", ICS_ERR_RANGE, "objects[0].radius: must be > 0");
  expect_error("\"slab_spacing\": 0.01", "\"slab_spacing\": 0", ICS_ERR_RANGE,
               "render.slab_spacing: must be > 0");
  expect_error("\"samples\": 2", "\"samples\": 1", ICS_ERR_PARSE, "render.samples: 1 is out of range 2..64");
  /* degenerate cameras */
  expect_error("\"target\": [0, 0, 0]", "\"target\": [0, 0, 2]", ICS_ERR_RANGE,
               "camera: eye and target must differ");
  expect_error("\"up\": [0, 1, 0]", "\"up\": [0, 0, 5]", ICS_ERR_RANGE,
               "camera: up must not be zero or parallel");
  expect_error("\"resolution\": [128, 128]", "\"resolution\": [0, 128]", ICS_ERR_PARSE,
               "camera.resolution[0]: 0 is out of range 1..16384");
  expect_error("\"resolution\": [128, 128]", "\"resolution\": [128, 100000]", ICS_ERR_PARSE,
               "camera.resolution[1]: 100000 is out of range");
  expect_error("\"height\": 3.0,", "\"fov_deg\": 40,", ICS_ERR_PARSE,
               "\"fov_deg\" is for perspective cameras");
  /* volumes on open shapes */
  expect_error("\"opacity\": 1}, \"white\"", "\"extinction\": 2}, \"white\"", ICS_ERR_PARSE,
               "objects[0].material: volumetric material \"black\" on an open shape (disk)");
  /* lights_file: missing, and both forms */
  expect_error("\"lights\": [", "\"lights_file\": \"/nonexistent/lights.json\", \"lights\": [",
               ICS_ERR_PARSE, "both \"lights\" and \"lights_file\"");
}

static void test_lights_file(void) {
  const char *dir = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
  char path[4096], scene[4096];
  snprintf(path, sizeof path, "%s/test_render_scene_lights.json", dir);
  if (write_lights_file(path)) return;
  char *j = with_lights_file("\"lights_file\": \"test_render_scene_lights.json\",");
  char msg[2048];
  ics_scene *s;
  ics_status st = ics_scene_create_json(&s, j, "lf.json", dir, msg, sizeof msg);
  CHECK(st == ICS_OK, "lights_file relative to the scene folder: %s", msg);
  if (st == ICS_OK) {
    CHECK(ics_scene_light_count(s) == 1 && ics_scene_light(s, 0)->weight == 3 &&
              ics_scene_light(s, 0)->color[1] == 0,
          "lights read from the file");
    ics_scene_destroy(s);
  }
  snprintf(scene, sizeof scene, "%s/nonexistent-dir", dir);
  st = ics_scene_create_json(&s, j, "lf.json", scene, msg, sizeof msg);
  CHECK(st == ICS_ERR_IO && strstr(msg, "lights_file of lf.json"), "missing lights file: %s (%s)",
        msg, ics_status_str(st));
  free(j);
  remove(path);
  /* a scene file that is missing or a directory */
  st = ics_scene_create_file(&s, "/nonexistent/scene.json", msg, sizeof msg);
  CHECK(st == ICS_ERR_IO && strstr(msg, "/nonexistent/scene.json: cannot open"), "missing file: %s", msg);
  st = ics_scene_create_file(&s, dir, msg, sizeof msg);
  CHECK(st != ICS_OK && s == NULL && strstr(msg, dir), "a directory as scene: %s", msg);
}

/* the folder rule (docs/scene-format.md "Files a scene reads") through the library: a sibling
 * folder that shares the scene folder's prefix is outside it, an empty `dir` is the working
 * directory (it once let every absolute path through), and ics_scene_opts lifts the rule */
static void test_outside_paths(void) {
  const char *tmp = getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
  char ab[2048], abc[2048], lights[4096], msg[2048];
  snprintf(ab, sizeof ab, "%s/test_render_scene_ab", tmp);
  snprintf(abc, sizeof abc, "%s/test_render_scene_abc", tmp);
  snprintf(lights, sizeof lights, "%s/lights.json", abc);
  mkdir(ab, 0700), mkdir(abc, 0700);
  if (write_lights_file(lights)) return;
  char *rel = with_lights_file("\"lights_file\": \"../test_render_scene_abc/lights.json\",");
  char absolute[8192];
  snprintf(absolute, sizeof absolute, "\"lights_file\": \"%s\",", lights);
  char *abs_j = with_lights_file(absolute);
  ics_scene *s = NULL;
  ics_status st = ics_scene_create_json(&s, rel, "ab.json", ab, msg, sizeof msg);
  CHECK(st == ICS_ERR_INVALID_ARG && s == NULL && strstr(msg, "lies outside the scene's folder"),
        "a sibling folder with the same prefix: %s (%s)", msg, ics_status_str(st));
  ics_scene_opts allow = {.allow_outside_paths = 1};
  st = ics_scene_create_json_opts(&s, rel, "ab.json", ab, &allow, msg, sizeof msg);
  CHECK(st == ICS_OK, "allowed: %s", msg);
  ics_scene_destroy(s);
  char *cwd = realpath(".", NULL), *real_abc = realpath(abc, NULL);
  if (cwd && real_abc && strncmp(real_abc, cwd, strlen(cwd))) {
    for (int k = 0; k < 2; k++) {
      st = ics_scene_create_json(&s, abs_j, "e.json", k ? "" : NULL, msg, sizeof msg);
      CHECK(st == ICS_ERR_INVALID_ARG && strstr(msg, "lies outside"),
            "dir %s: an absolute path outside the working directory: %s (%s)", k ? "\"\"" : "NULL",
            msg, ics_status_str(st));
    }
  } else {
    printf("SKIPPED part: %s lies in the working directory\n", abc);
  }
  free(cwd), free(real_abc), free(rel), free(abs_j);
  remove(lights), rmdir(abc), rmdir(ab);
}

int main(void) {
  test_contract();
  test_outside_paths();
  test_all_fields();
  test_default();
  test_errors();
  test_lights_file();
  return test_summary("test_render_scene");
}
