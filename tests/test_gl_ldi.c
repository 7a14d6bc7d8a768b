/* test_gl_ldi.c — the layered depth image built on the gl backend's device (gpu/backends/gl/ldi.comp,
 * ldi_gl.c) against the plan's, built on the host (gpu/core/ldi.c), fragment by fragment: per
 * pixel the number of fragments, the per-pixel state (layer cursors at the pixel's offset, the
 * inside mask), and per fragment the depth (as a float), the code (object, surface bias, slab),
 * the span and the depth gradient. Scenes: the embedded default, the scene files given on the
 * command line (scenes/), and cases for each shape and path of the ray caster: every analytic
 * shape under an orthographic and a perspective camera, a torus seen edge-on and through its
 * hole and at scales from 1e-16 to 1e16 (its cubic's float start), an eye inside volumes (box, sphere, torus, a closed mesh: the inside masks), the PLY cube
 * (rays through shared edges: merged crossings) and a generated 7 200-triangle sphere mesh (a
 * deep BVH). Each case prints its counts and the worst difference; the assertion is exact
 * equality (docs/backend_gl.md "The layered depth image on the device" says why it holds). With
 * the eye inside the sphere mesh every pixel also pushes a crossing behind the eye, more than
 * the first pool holds: that case checks that the pool is grown and the rays cast again.
 * Exit 77 (skipped) without an OpenGL 4.5 context.
 * usage: test_gl_ldi DATA_DIR [SCENE.json ...] */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_testutil.h"
#include "icshadow.h"
#include "ldi_gl.h"
#include "plan_internal.h"
#include "render_util.h"
#include "testutil.h"

static ics_gl g;
static GLuint prog[ICS_GL_LDI_NPROGS];
static GLint64 max_block;
static int max_groups[3];
static size_t total_frag, total_px;

static void *readback(GLuint b, size_t bytes) {
  void *p = malloc(bytes ? bytes : 1);
  if (!p) {
    fprintf(stderr, "out of memory\n");
    exit(2);
  }
  if (bytes) g.gl.GetNamedBufferSubData(b, 0, (GLsizeiptr)bytes, p);
  return p;
}

static int compare(const char *what, const ics_scene *s) {
  ics_plan *P = plan_or_exit(s, NULL, 0);
  const ics_ldi *L = &P->ldi;
  ics_gl_ldi d;
  char msg[4096] = "";
  ics_status st = ics_gl_ldi_build(&g, prog, P, (long long)max_block, max_groups, &d, msg, sizeof msg);
  CHECK(st == ICS_OK, "%s: %s", what, msg);
  if (st != ICS_OK) {
    ics_plan_destroy(P);
    return 0;
  }
  size_t npx = (size_t)P->Wb * P->Hb, nf = d.nfrag;
  uint32_t *off = readback(d.offset, 4 * (npx + 1)), *code = readback(d.fcode, 4 * nf);
  uint32_t *pix = readback(d.pix, 16 * npx), *span = readback(d.fspan, (nf + 3) / 4 * 4);
  float *z = readback(d.fz, 4 * nf), *grad = readback(d.fgrad, 8 * nf);
  size_t inside_px = 0, bad_px = 0, bad_state = 0, bad_z = 0, bad_code = 0, bad_span = 0, bad_grad = 0;
  double worst_z = 0;
  int first_bad = -1;
  for (size_t p = 0; p < npx; p++) {
    uint32_t n0 = L->offset[p + 1] - L->offset[p], n1 = off[p + 1] - off[p];
    uint64_t in0 = L->inside0 ? L->inside0[p] : 0, in1 = pix[4 * p + 2] | (uint64_t)pix[4 * p + 3] << 32;
    if (pix[4 * p] != off[p] || pix[4 * p + 1] != off[p] || in0 != in1) bad_state++;
    inside_px += in1 != 0;
    if (n0 != n1) {
      if (first_bad < 0) first_bad = (int)p;
      bad_px++;
      continue;
    }
    for (uint32_t i = 0; i < n0; i++) {
      const ics_fragment *f = &L->frag[L->offset[p] + i];
      size_t k = off[p] + i;
      double dz = fabs((double)f->z - z[k]);
      if (dz != 0) bad_z++, worst_z = fmax(worst_z, dz / fabs((double)f->z));
      if (f->code != code[k]) bad_code++;
      if (f->span != (span[k / 4] >> (8 * (k % 4)) & 0xff)) bad_span++;
      if ((float)(f->grad[0] / 64.0) != grad[2 * k] || (float)(f->grad[1] / 64.0) != grad[2 * k + 1])
        bad_grad++;
      if (first_bad < 0 && (dz != 0 || f->code != code[k])) first_bad = (int)p;
    }
  }
  printf("%-62s %4dx%-4d %7zu fragments (%zu), %d layers (%d), %d cast(s), %.0f ms, %zu px inside: "
         "pixels off %zu, state %zu, z %zu (worst %.2g rel), code %zu, span %zu, grad %zu\n", what, P->Wb, P->Hb,
         nf, L->nfrag, d.max_layers, L->max_layers, d.casts, d.ms, inside_px, bad_px, bad_state, bad_z,
         worst_z, bad_code, bad_span, bad_grad);
  if (first_bad >= 0) {
    int p = first_bad;
    printf("  first difference at pixel (%d, %d): plan %u fragments, device %u\n", p % P->Wb,
           p / P->Wb, L->offset[p + 1] - L->offset[p], off[p + 1] - off[p]);
    for (uint32_t i = L->offset[p]; i < L->offset[p + 1] && i < L->offset[p] + 8; i++)
      printf("    plan   z %.9g code %08x\n", L->frag[i].z, L->frag[i].code);
    for (uint32_t i = off[p]; i < off[p + 1] && i < off[p] + 8; i++)
      printf("    device z %.9g code %08x\n", z[i], code[i]);
  }
  CHECK(nf == L->nfrag, "%s: %zu fragments on the device, %zu in the plan", what, nf, L->nfrag);
  CHECK(d.max_layers == L->max_layers, "%s: %d layers on the device, %d in the plan", what,
        d.max_layers, L->max_layers);
  CHECK(bad_px == 0 && bad_state == 0, "%s: %zu pixels with other counts, %zu other states", what,
        bad_px, bad_state);
  CHECK(bad_z == 0 && bad_code == 0 && bad_span == 0 && bad_grad == 0,
        "%s: fragments differ (z %zu, code %zu, span %zu, grad %zu)", what, bad_z, bad_code,
        bad_span, bad_grad);
  total_frag += nf, total_px += npx;
  free(off), free(code), free(pix), free(span), free(z), free(grad);
  int casts = d.casts;
  ics_gl_ldi_release(&g, &d);
  ics_plan_destroy(P);
  return casts;
}

/* the unit UV sphere as an OBJ file: two poles, nv - 1 rings of nu vertices, 2 nu (nv - 1)
 * triangles (closed: every edge shared by two) */
static void write_sphere_obj(const char *path, int nu, int nv) {
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "cannot write %s\n", path);
    exit(2);
  }
  const double pi = 3.14159265358979323846;
  fprintf(f, "v 0 1 0\n");
  for (int j = 1; j < nv; j++)
    for (int i = 0; i < nu; i++) {
      double th = pi * j / nv, ph = 2 * pi * i / nu;
      fprintf(f, "v %.17g %.17g %.17g\n", sin(th) * cos(ph), cos(th), sin(th) * sin(ph));
    }
  int south = 2 + (nv - 1) * nu;
  fprintf(f, "v 0 -1 0\n");
  for (int i = 0; i < nu; i++) /* ring j's vertex i is 2 + (j - 1) nu + i */
    fprintf(f, "f 1 %d %d\n", 2 + (i + 1) % nu, 2 + i);
  for (int j = 1; j + 1 < nv; j++)
    for (int i = 0; i < nu; i++) {
      int a = 2 + (j - 1) * nu + i, b = 2 + (j - 1) * nu + (i + 1) % nu, c = a + nu, e = b + nu;
      fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, c, b, e, c);
    }
  for (int i = 0; i < nu; i++)
    fprintf(f, "f %d %d %d\n", south, 2 + (nv - 2) * nu + i, 2 + (nv - 2) * nu + (i + 1) % nu);
  if (fclose(f)) {
    fprintf(stderr, "cannot write %s\n", path);
    exit(2);
  }
}

static int case_json(const char *what, const char *json, const char *dir) {
  char msg[4096];
  ics_scene *s;
  if (ics_scene_create_json(&s, json, what, dir, msg, sizeof msg) != ICS_OK) {
    fprintf(stderr, "scene %s: %s\n", what, msg);
    exit(2);
  }
  int casts = compare(what, s);
  ics_scene_destroy(s);
  return casts;
}

#define CAM_ORTHO "\"camera\": {\"eye\": [0.3, 0.8, 3], \"target\": [0, 0, 0], \"height\": 2.6, \"resolution\": [80, 60]}"
#define CAM_PERSP "\"camera\": {\"projection\": \"perspective\", \"eye\": [0.4, 0.7, 2.6], \"target\": [0, 0, 0], \"fov_deg\": 45, \"resolution\": [80, 60]}"
#define LIGHT "\"render\": {\"slab_spacing\": 0.02, \"d1\": 1}, \"lights\": [{\"mean\": [0.4, 0.2], \"var\": [0.05, 0.02], \"angle_deg\": 25}]"
#define MATS "\"materials\": {\"m\": {\"color\": [0.8, 0.6, 0.4]}, \"fog\": {\"extinction\": 2}}"
#define FLOOR "{\"shape\": \"rect\", \"center\": [0, -0.6, 0], \"normal\": [0, 1, 0.1], \"size\": [4, 3], \"material\": \"m\"}"

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_gl_ldi DATA_DIR [SCENE.json ...]\n");
    return 2;
  }
  gl_open_or_skip(&g);
  g.gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  for (GLuint i = 0; i < 3; i++) g.gl.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i, &max_groups[i]);
  char msg[4096];
  if (!ics_gl_ldi_programs(&g, prog, msg, sizeof msg)) {
    fprintf(stderr, "%s\n", msg);
    return 1;
  }
  ics_scene *s = scene_from_json(ics_scene_default_json());
  compare("the embedded default scene", s);
  ics_scene_destroy(s);
  for (int i = 2; i < argc; i++) {
    s = scene_from_file(argv[i]);
    compare(argv[i], s);
    ics_scene_destroy(s);
  }
  static const char *const shapes[][2] = {
      {"rect, disk, box, sphere", "{\"shape\": \"disk\", \"center\": [-0.6, 0.2, 0.1], \"normal\": [0.2, 1, 0.4], \"radius\": 0.4, \"material\": \"m\"},"
       " {\"shape\": \"box\", \"center\": [0.5, -0.1, 0.2], \"size\": [0.5, 0.7, 0.4], \"rotate_deg\": [10, 35, 5], \"material\": \"m\"},"
       " {\"shape\": \"sphere\", \"center\": [0, 0.3, -0.3], \"radius\": 0.45, \"material\": \"fog\"}"},
      {"torus (tilted)", "{\"shape\": \"torus\", \"center\": [0, 0, 0], \"normal\": [0.3, 1, 0.2], \"major_radius\": 0.6, \"minor_radius\": 0.2, \"material\": \"m\"}"},
      {"torus (edge-on, a volume)", "{\"shape\": \"torus\", \"center\": [0, 0.1, 0], \"normal\": [0, 0.05, 1], \"major_radius\": 0.7, \"minor_radius\": 0.25, \"material\": \"fog\"}"},
      {"fence and a volume box", "{\"shape\": \"fence\", \"center\": [0, -0.6, -0.4], \"poles\": 5, \"pole_size\": [0.08, 0.6, 0.08], \"spacing\": 0.4, \"bar_size\": [0.06, 0.06], \"rotate_deg\": [0, 20, 0], \"material\": \"m\"},"
       " {\"shape\": \"box\", \"center\": [0, 0, 0.3], \"size\": [0.6, 0.6, 0.6], \"material\": \"fog\"}"}};
  char json[8192];
  for (size_t i = 0; i < sizeof shapes / sizeof *shapes; i++)
    for (int persp = 0; persp < 2; persp++) {
      char what[128];
      snprintf(what, sizeof what, "%s, %s", shapes[i][0], persp ? "perspective" : "orthographic");
      snprintf(json, sizeof json, "{%s, %s, %s, \"objects\": [" FLOOR ", %s]}",
               persp ? CAM_PERSP : CAM_ORTHO, LIGHT, MATS, shapes[i][1]);
      case_json(what, json, NULL);
    }
  /* a torus at scales where its cubic's float start would overflow or underflow unscaled (d1 scaled
   * too: a slab's blur goes as sqrt(d1 x spacing x variance)) */
  static const double scales[] = {1e-16, 1e-14, 3e13, 1e14, 1e16};
  for (size_t i = 0; i < sizeof scales / sizeof *scales; i++) {
    double k = scales[i];
    char what[96];
    snprintf(what, sizeof what, "torus at scale %g, perspective", k);
    snprintf(json, sizeof json,
             "{\"camera\": {\"projection\": \"perspective\", \"eye\": [%.17g, %.17g, %.17g], "
             "\"target\": [0, 0, 0], \"fov_deg\": 45, \"resolution\": [80, 60]}, "
             "\"render\": {\"slab_spacing\": %.17g, \"d1\": %.17g}, \"lights\": [{\"mean\": [0.4, 0.2], "
             "\"var\": [0.05, 0.02]}], \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": "
             "\"torus\", \"center\": [0, 0, 0], \"normal\": [0.3, 1, 0.2], \"major_radius\": %.17g, "
             "\"minor_radius\": %.17g, \"material\": \"m\"}]}",
             0.4 * k, 0.7 * k, 2.6 * k, 0.02 * k, k, 0.6 * k, 0.2 * k);
    case_json(what, json, NULL);
  }
  /* the eye inside volumes: a box, a sphere and a torus's tube contain it */
  snprintf(json, sizeof json,
           "{\"camera\": {\"projection\": \"perspective\", \"eye\": [0.7, 0, 0.05], \"target\": [0, 0, -2], "
           "\"fov_deg\": 60, \"resolution\": [64, 48]}, %s, %s, \"objects\": [" FLOOR ","
           " {\"shape\": \"box\", \"center\": [0, 0, 0], \"size\": [3, 2, 2], \"material\": \"fog\"},"
           " {\"shape\": \"sphere\", \"center\": [0.5, 0, 0], \"radius\": 0.6, \"material\": \"fog\"},"
           " {\"shape\": \"torus\", \"center\": [0, 0, 0], \"normal\": [0, 1, 0], \"major_radius\": 0.7, "
           "\"minor_radius\": 0.2, \"material\": \"fog\"},"
           " {\"shape\": \"sphere\", \"center\": [-0.3, 0.1, -1.2], \"radius\": 0.3, \"material\": \"m\"}]}",
           LIGHT, MATS);
  case_json("the eye inside a box, a sphere and a torus (inside masks)", json, NULL);
  /* meshes: the PLY cube (12 triangles; shared edges), a generated sphere (7200 triangles) */
  const char *dir = argv[1];
  snprintf(json, sizeof json, "{%s, %s, %s, \"objects\": [" FLOOR ","
           " {\"shape\": \"mesh\", \"file\": \"cube.ply\", \"scale\": 0.8, \"rotate_deg\": [20, 30, 0], \"material\": \"m\"}]}",
           CAM_ORTHO, LIGHT, MATS);
  case_json("mesh: cube.ply, rotated", json, dir);
  /* axis-aligned: rays through the cube's edges and diagonals exactly */
  snprintf(json, sizeof json, "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, "
           "\"resolution\": [64, 64]}, %s, %s, \"objects\": ["
           " {\"shape\": \"mesh\", \"file\": \"cube.ply\", \"material\": \"fog\"}]}", LIGHT, MATS);
  case_json("mesh: cube.ply, axis-aligned, a volume", json, dir);
  const char *td = getenv("TMPDIR");
  char tmp[1024], obj[1200];
  snprintf(tmp, sizeof tmp, "%s", td && *td ? td : "/tmp");
  snprintf(obj, sizeof obj, "%s/test_gl_ldi_sphere.obj", tmp);
  write_sphere_obj(obj, 80, 46); /* 7200 triangles */
  snprintf(json, sizeof json, "{%s, %s, %s, \"objects\": [" FLOOR ","
           " {\"shape\": \"mesh\", \"file\": \"test_gl_ldi_sphere.obj\", \"scale\": 0.6, \"translate\": [0.1, 0, 0], \"material\": \"fog\"},"
           " {\"shape\": \"mesh\", \"file\": \"test_gl_ldi_sphere.obj\", \"scale\": [0.2, 0.5, 0.2], \"translate\": [-0.7, 0, 0.3], \"material\": \"m\"}]}",
           CAM_PERSP, LIGHT, MATS);
  case_json("mesh: a 7200-triangle sphere (volume) and a squashed copy", json, tmp);
  /* the eye inside the closed sphere mesh */
  snprintf(json, sizeof json, "{\"camera\": {\"projection\": \"perspective\", \"eye\": [0.1, 0, 0], "
           "\"target\": [0, 0, -2], \"fov_deg\": 70, \"resolution\": [48, 36]}, %s, %s, \"objects\": ["
           " {\"shape\": \"mesh\", \"file\": \"test_gl_ldi_sphere.obj\", \"material\": \"fog\"}]}", LIGHT, MATS);
  /* every pixel has a crossing behind the eye, so the pushes outnumber the plan's fragments by
   * more than the first pool's margin: the pool is grown and the rays cast again */
  int casts = case_json("mesh: the eye inside the sphere mesh (inside mask, a grown pool)", json, tmp);
  CHECK(casts == 2, "the eye inside the sphere mesh: %d cast(s), expected 2 (a grown pool)", casts);
  remove(obj);
  printf("%zu fragments over %zu pixels compared\n", total_frag, total_px);
  for (int i = 0; i < ICS_GL_LDI_NPROGS; i++) g.gl.DeleteProgram(prog[i]);
  ics_gl_close(&g);
  return test_summary("test_gl_ldi");
}
