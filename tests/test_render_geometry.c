/* test_render_geometry.c — ray crossings of the analytic shapes and meshes (gpu/core/geometry.c,
 * mesh.c): every crossing found, none invented, checked against an independent inside test
 * sampled densely along the ray (a crossing is where the inside state flips); closed shapes cross
 * an even number of times; the torus quartic on grazing and axial rays; the cube mesh (PLY,
 * through Assimp) renders exactly as the analytic box; open meshes are refused as volumes; a
 * malformed mesh file is named, and so are the files Assimp aborts or hangs on, a FIFO, and a
 * reader past its time limit (mesh_import.c). The normal at a fragment's float depth
 * (ics_object_normal_near) is the crossing's, a thin torus's seen from afar included. (Sampling at 20000 points per ray cannot see a pair of crossings
 * closer than 1.5e-4 of the ray; the +-1e-7 test checks every reported one.) The layered depth
 * image (ldi.c), which tests a ray only against the objects whose projected bounding box it
 * meets, holds at every buffer pixel exactly the crossings of all objects (depths, objects) and
 * the volumes containing the ray's origin, on scenes built to catch a wrong cull: objects
 * straddling and behind an orthographic eye, a perspective eye inside a volume, an object
 * straddling a perspective eye's plane, shapes at the buffer's edges, a mesh. Arguments: the
 * folder tests/data. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "geometry.h"
#include "mesh.h"
#include "plan_internal.h"
#include "render_util.h"
#include "testutil.h"

static int inside(const ics_object *o, const double p[3]) {
  double d[3] = {p[0] - o->center[0], p[1] - o->center[1], p[2] - o->center[2]}, q[3];
  for (int i = 0; i < 3; i++) q[i] = o->ax[i][0] * d[0] + o->ax[i][1] * d[1] + o->ax[i][2] * d[2];
  switch (o->shape) {
  case ICS_SHAPE_BOX: return fabs(q[0]) < o->half[0] && fabs(q[1]) < o->half[1] && fabs(q[2]) < o->half[2];
  case ICS_SHAPE_SPHERE: return q[0] * q[0] + q[1] * q[1] + q[2] * q[2] < o->half[0] * o->half[0];
  case ICS_SHAPE_TORUS: {
    double R = o->half[0], r = o->half[1], a = sqrt(q[0] * q[0] + q[1] * q[1]) - R;
    return a * a + q[2] * q[2] < r * r;
  }
  default: return 0;
  }
}

/* Checks the reported crossings t[0..n-1] (within (0, tmax]) against the inside test: each one
 * flips the inside state between t - delta and t + delta, and every flip seen by dense sampling
 * lies in a sample interval that holds a reported crossing. Returns 0 when all hold. */
static int check_crossings(const ics_object *o, const double org[3], const double dir[3],
                           double tmax, int nsamp, const ics_hit *h, int n) {
  double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]), delta = 1e-7 / len;
  for (int j = 0; j < n; j++) {
    double t = h[j].t;
    if (t > tmax) continue;
    double a[3], b[3];
    for (int c = 0; c < 3; c++) a[c] = org[c] + (t - delta) * dir[c], b[c] = org[c] + (t + delta) * dir[c];
    if (inside(o, a) == inside(o, b)) return 1; /* an invented crossing */
  }
  int prev = -1;
  for (int i = 0; i <= nsamp; i++) {
    double t = tmax * i / nsamp, p[3] = {org[0] + t * dir[0], org[1] + t * dir[1], org[2] + t * dir[2]};
    int in = inside(o, p);
    if (prev >= 0 && in != prev) {
      double t0 = tmax * (i - 1) / nsamp;
      int found = 0;
      for (int j = 0; j < n; j++) found |= h[j].t >= t0 - delta && h[j].t <= t + delta;
      if (!found) return 2; /* a missed crossing */
    }
    prev = in;
  }
  return 0;
}

static void test_shapes(void) {
  const char *json =
      "{\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [8, 8]},"
      " \"render\": {\"slab_spacing\": 0.05, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
      " \"materials\": {\"m\": {}},"
      " \"objects\": [{\"shape\": \"box\", \"center\": [0.1, -0.2, 0.3], \"size\": [1, 0.6, 0.8], \"rotate_deg\": [20, 35, -10], \"material\": \"m\"},"
      "  {\"shape\": \"sphere\", \"center\": [0.2, 0.1, -0.1], \"radius\": 0.7, \"material\": \"m\"},"
      "  {\"shape\": \"torus\", \"center\": [0, 0, 0], \"normal\": [0.3, 1, 0.5], \"major_radius\": 0.8, \"minor_radius\": 0.25, \"material\": \"m\"}]}";
  ics_scene *s = scene_from_json(json);
  int rays = 0, bad = 0, worst_obj = -1;
  ics_hits h = {0};
  for (int k = 0; k < 3; k++) {
    const ics_object *o = ics_scene_object(s, k);
    for (int i = 0; i < 1500; i++) {
      /* rays from a sphere of radius 3 toward random points near the object */
      double org[3], tgt[3], dir[3];
      for (int c = 0; c < 3; c++) org[c] = 6 * test_rng_unit() - 3;
      for (int c = 0; c < 3; c++) tgt[c] = o->center[c] + 2 * test_rng_unit() - 1;
      for (int c = 0; c < 3; c++) dir[c] = tgt[c] - org[c];
      h.n = 0;
      int behind = 0;
      ics_object_hits(o, org, dir, &h, &behind);
      /* the crossings within t <= 3 (past the far side of every object) */
      int origin_in = inside(o, org);
      if (check_crossings(o, org, dir, 3, 20000, h.h, h.n) || (behind & 1) != origin_in)
        bad++, worst_obj = k;
      rays++;
    }
  }
  CHECK(bad == 0, "%d of %d rays disagree with the sampled inside test (last: object %d)", bad, rays,
        worst_obj);
  printf("box, sphere, torus: %d random rays, every crossing a flip of the inside test and every "
         "sampled flip a crossing\n", rays);
  /* the torus along its axis: no crossing through the hole; across the ring: 4 */
  const ics_object *t = ics_scene_object(s, 2);
  double org[3], dir[3];
  for (int c = 0; c < 3; c++) org[c] = t->center[c] - 3 * t->ax[2][c], dir[c] = t->ax[2][c];
  h.n = 0;
  int behind = 0;
  ics_object_hits(t, org, dir, &h, &behind);
  CHECK(h.n == 0, "torus axis: %d crossings (none through the hole)", h.n);
  for (int c = 0; c < 3; c++) org[c] = t->center[c] - 3 * t->ax[0][c], dir[c] = t->ax[0][c];
  h.n = 0;
  ics_object_hits(t, org, dir, &h, &behind);
  CHECK(h.n == 4, "torus across the ring: %d crossings", h.n);
  if (h.n == 4) {
    double want[4] = {3 - 1.05, 3 - 0.55, 3 + 0.55, 3 + 1.05}, err = 0;
    for (int j = 0; j < 4; j++) err = fmax(err, fabs(h.h[j].t - want[j]));
    CHECK(err < 1e-12, "torus crossings off by %.3g", err);
  }
  /* far eyes: a closed shape is crossed an even number of times whatever the distance */
  int odd = 0;
  for (int i = 0; i < 2000; i++) {
    double dist = 3000, o2[3], tg[3], d2[3];
    for (int c = 0; c < 3; c++) o2[c] = t->center[c] + dist * (2 * test_rng_unit() - 1);
    for (int c = 0; c < 3; c++) tg[c] = t->center[c] + 2 * test_rng_unit() - 1;
    for (int c = 0; c < 3; c++) d2[c] = tg[c] - o2[c];
    h.n = 0;
    behind = 0;
    ics_object_hits(t, o2, d2, &h, &behind);
    odd += (h.n + behind) & 1;
  }
  CHECK(odd == 0, "torus seen from distance 3000: %d of 2000 rays cross an odd number of times", odd);
  ics_hits_free(&h);
  ics_scene_destroy(s);
  /* extreme normal lengths keep their direction */
  const char *fmt =
      "{\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [8, 8]},"
      " \"render\": {\"slab_spacing\": 0.05, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
      " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"disk\", \"center\": [0, 0, 0], \"normal\": [0, 0, %s],"
      " \"radius\": 1, \"material\": \"m\"}]}";
  const char *lens[2] = {"1e-200", "1e200"};
  for (int i = 0; i < 2; i++) {
    char j[2048];
    snprintf(j, sizeof j, fmt, lens[i]);
    ics_scene *sn = scene_from_json(j);
    const ics_object *dk = ics_scene_object(sn, 0);
    CHECK(dk->ax[2][2] == 1 && fabs(dk->ax[0][0]) + fabs(dk->ax[1][1]) > 0.5,
          "disk normal of length %s: frame z (%g %g %g)", lens[i], dk->ax[2][0], dk->ax[2][1], dk->ax[2][2]);
    ics_scene_destroy(sn);
  }
}

static void test_meshes(const char *dir) {
  if (!ics_mesh_files_supported()) {
    printf("SKIPPED mesh files: the renderer was built without Assimp\n");
    return;
  }
  char json[4096], msg[4096];
  const char *fmt =
      "{\"camera\": {\"eye\": [0.3, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [48, 48]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1}, \"lights\": [{\"mean\": [0.2, 0.3], \"var\": [0.02, 0.01]}],"
      " \"materials\": {\"m\": {\"color\": [0.8, 0.6, 0.4]}, \"w\": {}, \"fog\": {\"extinction\": 2}},"
      " \"objects\": [%s, {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [4, 4], \"material\": \"w\"}]}";
  char obj[1024];
  snprintf(obj, sizeof obj, "{\"shape\": \"box\", \"center\": [0.1, 0, 0], \"size\": [0.8, 0.8, 0.8], \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  ics_scene *sb = scene_from_json(json);
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"cube.ply\", \"scale\": 0.8, \"translate\": [0.1, 0, 0], \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  ics_scene *sm;
  ics_status st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_OK, "cube.ply scene: %s", msg);
  if (st != ICS_OK) {
    ics_scene_destroy(sb);
    return;
  }
  CHECK(ics_scene_object(sm, 0)->closed, "the cube mesh is closed");
  {
    /* rays grazing the cube's silhouette edges and through its face diagonals: even counts */
    const ics_object *cube = ics_scene_object(sm, 0);
    ics_hits h = {0};
    int odd = 0;
    for (int i = 0; i < 400; i++) {
      double a = 0.4 * (i % 20) / 19 - 0.2; /* along an edge of the cube (half 0.4, centre 0.1) */
      double org[4][3] = {{0.5, a, 3}, {a + 0.1, 0.4, 3}, {0.5, 0.4, 3}, {0.1 + a, a, 3}};
      for (int k = 0; k < 4; k++) {
        double dir[3] = {0, 0, -1};
        if (k == 3) dir[0] = 0.3, dir[1] = 0.3; /* through edges between a face's two triangles */
        h.n = 0;
        int behind = 0;
        ics_object_hits(cube, org[k], dir, &h, &behind);
        odd += (h.n + behind) & 1;
      }
    }
    CHECK(odd == 0, "cube mesh: %d grazing rays cross an odd number of times", odd);
    ics_hits_free(&h);
  }
  render_result rb = render_scene(sb, NULL, 1), rm = render_scene(sm, NULL, 1);
  double d = 0;
  for (size_t i = 0; i < 4 * 48 * 48; i++) d = fmax(d, fabs(rb.img->data[i] - rm.img->data[i]));
  CHECK(d < 1e-5, "cube mesh vs box: max difference %.3g", d);
  printf("cube.ply (12 triangles) vs the analytic box: max pixel difference %.2g\n", d);
  ics_image_destroy(rb.img);
  ics_image_destroy(rm.img);
  ics_scene_destroy(sb);
  ics_scene_destroy(sm);
  /* an open mesh as a volume, a missing file, a malformed file */
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"quad.obj\", \"material\": \"fog\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_PARSE && strstr(msg, "objects[0].material: volumetric material \"fog\" on an open mesh"),
        "open mesh as volume: %s", msg);
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"quad.obj\", \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_OK && !ics_scene_object(sm, 0)->closed, "open mesh as surface: %s", msg);
  if (st == ICS_OK) ics_scene_destroy(sm);
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"missing.ply\", \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_IO && strstr(msg, "objects[0].file:") && strstr(msg, "missing.ply: cannot open"),
        "missing mesh: %s", msg);
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"broken.ply\", \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st != ICS_OK && strstr(msg, "broken.ply"), "malformed mesh: %s (%s)", msg, ics_status_str(st));
  /* files on which Assimp 5.2 aborts the process and never returns (found by fuzz_mesh_file):
   * errors naming the file, from the child process that reads it (mesh_import.c) */
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"assimp_abort.ply\", \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_PARSE && strstr(msg, "assimp_abort.ply: ") &&
            (strstr(msg, "Assimp failed on this file") || strstr(msg, "cannot read mesh")),
        "a file Assimp aborts on: %s (%s)", msg, ics_status_str(st));
  snprintf(obj, sizeof obj, "{\"shape\": \"mesh\", \"file\": \"no_end_header.ply\", \"material\": \"m\"}");
  snprintf(json, sizeof json, fmt, obj);
  st = ics_scene_create_json(&sm, json, "mesh", dir, msg, sizeof msg);
  CHECK(st == ICS_ERR_PARSE && strstr(msg, "no_end_header.ply: a PLY header without an end_header line"),
        "a PLY header without end_header: %s (%s)", msg, ics_status_str(st));
  printf("malformed meshes: %s\n", msg);
  /* the reader's time limit (a limit already past: deterministic), a FIFO (would block the
   * reader), and a first line "ply " with a trailing blank and no end_header */
  static const double one[3] = {1, 1, 1}, zero[3] = {0, 0, 0};
  char path[1024];
  ics_mesh *m = NULL;
  snprintf(path, sizeof path, "%s/cube.ply", dir);
  st = ics_mesh_create_file(&m, path, one, zero, zero, 1e-9, NULL, msg, sizeof msg);
  CHECK(st == ICS_ERR_PARSE && !m && strstr(msg, "did not finish reading the mesh within"),
        "time limit: %s (%s)", msg, ics_status_str(st));
  st = ics_mesh_create_file(&m, path, one, zero, zero, 0, NULL, msg, sizeof msg);
  CHECK(st == ICS_OK && m && ics_mesh_triangle_count(m) == 12, "cube.ply read: %s", msg);
  ics_mesh_destroy(m), m = NULL;
  const char *td = getenv("TMPDIR");
  snprintf(path, sizeof path, "%s/test_render_geometry.fifo", td && *td ? td : "/tmp");
  remove(path);
  if (mkfifo(path, 0600) == 0) {
    st = ics_mesh_create_file(&m, path, one, zero, zero, 0, NULL, msg, sizeof msg);
    CHECK(st == ICS_ERR_IO && strstr(msg, "not a regular file"), "a FIFO: %s (%s)", msg,
          ics_status_str(st));
    remove(path);
  }
  snprintf(path, sizeof path, "%s/test_render_geometry_blank.ply", td && *td ? td : "/tmp");
  FILE *f = fopen(path, "w");
  if (f) {
    fputs("ply \nformat ascii 1.0\nelement vertex 3\nproperty float x\n", f);
    fclose(f);
    st = ics_mesh_create_file(&m, path, one, zero, zero, 5, NULL, msg, sizeof msg);
    CHECK(st == ICS_ERR_PARSE && strstr(msg, "without an end_header line"),
          "'ply ' without end_header: %s (%s)", msg, ics_status_str(st));
    remove(path);
  }
}

/* every buffer pixel of the plan's LDI against all objects' crossings of its ray, unculled */
static void check_ldi(const char *name, const char *json, const char *dir) {
  char msg[4096];
  ics_scene *s;
  if (ics_scene_create_json(&s, json, name, dir, msg, sizeof msg) != ICS_OK) {
    CHECK(0, "%s: %s", name, msg);
    return;
  }
  ics_plan *p = plan_or_exit(s, NULL, 2);
  const ics_ldi *l = &p->ldi;
  ics_hits h = {0};
  long bad = 0, frags = 0;
  for (int bj = 0; bj < l->h; bj++)
    for (int bi = 0; bi < l->w; bi++) {
      size_t px = (size_t)bj * l->w + bi;
      double o[3], d[3], z[64];
      int obj[64], n = 0;
      uint64_t inside = 0;
      ics_plan_ray(p, bi, bj, o, d);
      for (int k = 0; k < ics_scene_object_count(s); k++) {
        int behind = 0;
        h.n = 0;
        ics_object_hits(ics_scene_object(s, k), o, d, &h, &behind);
        if (p->vol_bit[k] >= 0 && (behind & 1)) inside |= 1ull << p->vol_bit[k];
        for (int i = 0; i < h.n && n < 64; i++) z[n] = h.h[i].t, obj[n++] = k;
      }
      uint32_t f0 = l->offset[px], f1 = l->offset[px + 1];
      if ((int)(f1 - f0) != n || (l->inside0 ? l->inside0[px] : 0) != inside) {
        bad++;
        continue;
      }
      for (uint32_t f = f0; f < f1; f++) { /* each fragment is one crossing (sorted by depth) */
        int found = 0;
        for (int i = 0; i < n && !found; i++)
          found = (float)z[i] == l->frag[f].z && obj[i] == ics_frag_obj(&l->frag[f]);
        bad += !found;
      }
      frags += n;
    }
  ics_hits_free(&h);
  CHECK(bad == 0 && frags > 0, "%s: %ld pixels or fragments of the LDI differ from the rays' crossings "
        "(%ld crossings)", name, bad, frags);
  printf("LDI, %s: %d x %d pixels, %ld crossings, %ld differ\n", name, l->w, l->h, frags, bad);
  ics_plan_destroy(p);
  ics_scene_destroy(s);
}

static void test_ldi_cull(const char *dir) {
  const char *head = "\"render\": {\"slab_spacing\": 0.05, \"d1\": 1}, \"lights\": [{\"mean\": [0.4, 0.3], \"var\": [0.04, 0.02]}],"
                     " \"materials\": {\"m\": {}, \"fog\": {\"extinction\": 2}},";
  char j[4096];
  snprintf(j, sizeof j, "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [40, 30]}, %s"
           " \"objects\": [{\"shape\": \"box\", \"center\": [0.5, 0, 3], \"size\": [0.6, 0.6, 1], \"material\": \"fog\"},"
           "  {\"shape\": \"sphere\", \"center\": [-0.5, 0.3, 4], \"radius\": 0.3, \"material\": \"fog\"},"
           "  {\"shape\": \"torus\", \"center\": [1.05, -0.7, 0], \"normal\": [0.3, 1, 0.2], \"major_radius\": 0.3, \"minor_radius\": 0.1, \"material\": \"m\"},"
           "  {\"shape\": \"disk\", \"center\": [-1.3, 0.9, 0.5], \"normal\": [0, 0, 1], \"radius\": 0.4, \"material\": \"m\"},"
           "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 2], \"material\": \"m\"}]}", head);
  check_ldi("orthographic: a volume straddling the eye, one behind it, shapes at the edges", j, dir);
  snprintf(j, sizeof j, "{\"camera\": {\"projection\": \"perspective\", \"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"fov_deg\": 50, \"resolution\": [40, 30]}, %s"
           " \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 2.5], \"radius\": 1, \"material\": \"fog\"},"
           "  {\"shape\": \"box\", \"center\": [0.8, 0, 3], \"size\": [0.4, 0.4, 1], \"material\": \"m\"},"
           "  {\"shape\": \"torus\", \"center\": [1.2, 0.7, 0], \"normal\": [0, 1, 0], \"major_radius\": 0.3, \"minor_radius\": 0.1, \"material\": \"m\"},"
           "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 2], \"material\": \"m\"}]}", head);
  check_ldi("perspective: the eye inside a volume, a box straddling its plane", j, dir);
  if (ics_mesh_files_supported()) {
    snprintf(j, sizeof j, "{\"camera\": {\"eye\": [0.3, 0.5, 3], \"target\": [0, 0, 0], \"height\": 2, \"resolution\": [40, 30]}, %s"
             " \"objects\": [{\"shape\": \"mesh\", \"file\": \"cube.ply\", \"scale\": 0.5, \"translate\": [0.9, 0.6, 0], \"material\": \"m\"},"
             "  {\"shape\": \"rect\", \"center\": [0, 0, -1], \"normal\": [0, 0, 1], \"size\": [3, 2], \"material\": \"m\"}]}", head);
    check_ldi("a mesh at the view's corner", j, dir);
  }
}

/* the angle between two normals (radians) */
static double normal_angle(const double a[3], const double b[3]) {
  double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2], aa = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
  double bb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  return acos(fmax(-1, fmin(1, ab / sqrt(aa * bb))));
}

/* ics_object_normal_near at a crossing's float depth (a fragment's) gives that crossing's
 * normal: a thin torus seen from 1 to 3000 units (where the float depth alone leaves the point
 * 2e-4 off a tube of radius 0.02: 1e-2 rad), a sphere and a box */
static void test_normal_near(void) {
  const char *json =
      "{\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"height\": 3, \"resolution\": [8, 8]},"
      " \"render\": {\"slab_spacing\": 0.05, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
      " \"materials\": {\"m\": {}},"
      " \"objects\": [{\"shape\": \"torus\", \"center\": [0.1, 0, 0], \"normal\": [0.3, 1, 0.5], \"major_radius\": 0.8, \"minor_radius\": 0.02, \"material\": \"m\"},"
      "  {\"shape\": \"sphere\", \"center\": [0.2, 0.1, -0.1], \"radius\": 0.7, \"material\": \"m\"},"
      "  {\"shape\": \"box\", \"center\": [0.1, -0.2, 0.3], \"size\": [1, 0.6, 0.8], \"rotate_deg\": [20, 35, -10], \"material\": \"m\"}]}";
  ics_scene *s = scene_from_json(json);
  ics_hits h = {0}, scratch = {0};
  double worst[3] = {0, 0, 0};
  int crossings = 0;
  for (int k = 0; k < 3; k++) {
    const ics_object *o = ics_scene_object(s, k);
    for (int i = 0; i < 3000; i++) {
      double dist = i % 3 == 0 ? 1 : i % 3 == 1 ? 100 : 3000, org[3], tgt[3], dir[3];
      for (int c = 0; c < 3; c++) org[c] = o->center[c] + dist * (2 * test_rng_unit() - 1);
      /* toward a point of the tube's (the sphere's, the box's) surface region */
      for (int c = 0; c < 3; c++) tgt[c] = o->center[c] + (k ? 1.4 : 1.7) * test_rng_unit() - (k ? 0.7 : 0.85);
      for (int c = 0; c < 3; c++) dir[c] = tgt[c] - org[c];
      h.n = 0;
      int behind = 0;
      ics_object_hits(o, org, dir, &h, &behind);
      for (int m = 0; m < h.n; m++) {
        double n[3], z = (float)h.h[m].t;
        if (ics_object_normal_near(o, org, dir, z, &scratch, n)) exit(2);
        worst[k] = fmax(worst[k], normal_angle(n, h.h[m].n));
        crossings++;
      }
    }
  }
  CHECK(worst[0] < 1e-7, "thin torus: normal at the float depth %.3g rad from the crossing's", worst[0]);
  CHECK(worst[1] < 1e-12 && worst[2] < 1e-12, "sphere, box: normals %.3g, %.3g rad off", worst[1],
        worst[2]);
  printf("normal near a float depth: %d crossings from 1 to 3000 units, worst %.3g rad (thin "
         "torus), %.3g (sphere), %.3g (box)\n", crossings, worst[0], worst[1], worst[2]);
  ics_hits_free(&h);
  ics_hits_free(&scratch);
  ics_scene_destroy(s);
}

int main(int argc, char **argv) {
  test_shapes();
  test_normal_near();
  test_ldi_cull(argc > 1 ? argv[1] : "tests/data");
  test_meshes(argc > 1 ? argv[1] : "tests/data");
  return test_summary("test_render_geometry");
}
