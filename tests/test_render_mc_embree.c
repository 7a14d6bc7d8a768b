/* test_render_mc_embree.c — the Monte-Carlo reference's mesh crossings through Embree 3
 * (gpu/backends/mc/mc_embree.c) against the renderer's own BVH (gpu/core/mesh.c), on a closed bumpy
 * sphere of 9024 triangles written as OBJ and read through Assimp:
 * - 20000 random lines (origins around the mesh, some inside, isotropic directions): the same
 *   crossings, t and normal equal bit for bit (both compute them with the same double-precision
 *   formula; Embree only chooses the triangles), and the same count behind the origin;
 * - 6000 lines aimed exactly at a vertex or an edge's midpoint (a set of measure zero for sampled
 *   rays, forced here), where a crossing can be lost or doubled: a closed mesh must be crossed an
 *   even number of times, and a line with an odd count turns a volume inside out behind it. The
 *   BVH's double-precision inside test (u, v >= 0 per triangle) is not watertight: measured here,
 *   14.5 % of these lines cross it an odd number of times; Embree's watertight traversal,
 *   0.35 % (21). Asserted: Embree's odd lines at most half the BVH's and at most 1 %;
 * - the mesh translated by 1e5, and ray origins 1e5 away from it: no line crosses differently
 *   or an odd number of times (Embree works in the mesh's own frame, from the line's entry into
 *   its box);
 * - a render of two meshes (one opaque, one of smoke) over a plane, 24 spp: Embree's image equals
 *   the BVH's pixel for pixel (the same crossings, the same samples);
 * - the option: "bvh" and "embree" say which ran in the device string, a bad value is refused. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "icshadow/constants.h"
#include "icshadow/rng.h"
#include "mc_embree.h"
#include "mesh.h"
#include "render_util.h"
#include "testutil.h"

#define NU 96
#define NV 48

static double radius(double th, double ph) { return 0.5 * (1 + 0.15 * sin(3 * ph) * sin(th) * sin(th)); }

/* a closed bumpy UV sphere: two poles, NV - 1 rings of NU vertices */
static int write_blob(const char *path) {
  FILE *f = fopen(path, "w");
  if (!f) return -1;
  fprintf(f, "v 0 0 0.5\n");
  for (int j = 1; j < NV; j++)
    for (int i = 0; i < NU; i++) {
      double th = ICS_PI * j / NV, ph = 2 * ICS_PI * i / NU, r = radius(th, ph);
      fprintf(f, "v %.17g %.17g %.17g\n", r * sin(th) * cos(ph), r * sin(th) * sin(ph), 0.5 * cos(th));
    }
  fprintf(f, "v 0 0 -0.5\n");
  int south = 1 + (NV - 1) * NU;
#define IDX(j, i) (1 + ((j) - 1) * NU + ((i) % NU))
  for (int i = 0; i < NU; i++) fprintf(f, "f 1 %d %d\n", IDX(1, i) + 1, IDX(1, i + 1) + 1);
  for (int j = 1; j < NV - 1; j++)
    for (int i = 0; i < NU; i++) {
      int a = IDX(j, i) + 1, b = IDX(j, i + 1) + 1, c = IDX(j + 1, i) + 1, d = IDX(j + 1, i + 1) + 1;
      fprintf(f, "f %d %d %d\nf %d %d %d\n", a, c, d, a, d, b);
    }
  for (int i = 0; i < NU; i++) fprintf(f, "f %d %d %d\n", south + 1, IDX(NV - 1, i + 1) + 1, IDX(NV - 1, i) + 1);
#undef IDX
  return fclose(f);
}

static const char *scene_fmt =
    "{\"camera\": {\"eye\": [0.2, 0.3, 3], \"target\": [0, 0, 0], \"height\": 2.4, \"resolution\": [48, 48]},"
    " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1, \"seed\": 5},"
    " \"lights\": [{\"mean\": [0.3, 0.2], \"var\": [0.01, 0.005]}],"
    " \"materials\": {\"m\": {\"color\": [0.9, 0.6, 0.3]}, \"w\": {}, \"fog\": {\"extinction\": 3, \"color\": [0.5, 0.7, 1]}},"
    " \"objects\": [{\"shape\": \"mesh\", \"file\": \"%s\", \"material\": \"m\", \"translate\": [-0.35, 0, 0.3], \"scale\": 0.7},"
    "  {\"shape\": \"mesh\", \"file\": \"%s\", \"material\": \"fog\", \"translate\": [0.45, 0.2, 0.4], \"scale\": 0.6},"
    "  {\"shape\": \"rect\", \"center\": [0, 0, -0.6], \"normal\": [0, 0, 1], \"size\": [4, 4], \"material\": \"w\"}]}";

/* 0 when both crossing lists and the counts behind are equal */
static int differ(const ics_hits *a, int ba, const ics_hits *b, int bb) {
  if (a->n != b->n || ba != bb) return 1;
  for (int i = 0; i < a->n; i++)
    if (a->h[i].t != b->h[i].t || memcmp(a->h[i].n, b->h[i].n, sizeof a->h[i].n)) return 1;
  return 0;
}

static void random_dir(ics_rng *r, double d[3]) {
  double z = 2 * ics_rng_uniform(r) - 1, ph = 2 * ICS_PI * ics_rng_uniform(r), s = sqrt(1 - z * z);
  d[0] = s * cos(ph), d[1] = s * sin(ph), d[2] = z;
}

static void test_lines(const ics_scene *s, const mc_embree *e) {
  const ics_mesh *mesh = ics_scene_object(s, 0)->mesh;
  ics_hits ha = {0}, hb = {0};
  mc_embree_scratch sc = {0};
  ics_rng r;
  ics_rng_init(&r, 11, 0);
  int bad = 0, inside = 0;
  for (int k = 0; k < 20000; k++) {
    double o[3], d[3];
    for (int i = 0; i < 3; i++) o[i] = (i == 2 ? 0.3 : i == 0 ? -0.35 : 0) + 1.2 * (ics_rng_uniform(&r) - 0.5);
    random_dir(&r, d);
    int ba = 0, bb = 0;
    ha.n = hb.n = 0;
    CHECK(ics_mesh_hits(mesh, o, d, &ha, &ba) == 0 && mc_embree_hits(e, 0, o, d, &sc, &hb, &bb) == 0, "out of memory");
    bad += differ(&ha, ba, &hb, bb);
    inside += ba & 1;
  }
  printf("random lines: %d of 20000 differ (%d origins inside the mesh)\n", bad, inside);
  CHECK(bad == 0, "%d random lines cross differently through Embree", bad);
  CHECK(inside > 1000, "only %d origins inside: the sample misses the mesh", inside);

  /* lines through a vertex or an edge's midpoint of a random triangle */
  int nt = ics_mesh_triangle_count(mesh), differ_n = 0, odd_bvh = 0, odd_embree = 0, lost = 0;
  for (int k = 0; k < 6000; k++) {
    double v[3][3], p[3], d[3], o[3];
    ics_mesh_triangle(mesh, (int)(ics_rng_uniform(&r) * nt), v);
    int c = k % 3;
    for (int i = 0; i < 3; i++) p[i] = k % 2 ? v[c][i] : 0.5 * (v[c][i] + v[(c + 1) % 3][i]);
    random_dir(&r, d);
    for (int i = 0; i < 3; i++) o[i] = p[i] - 2 * d[i];
    int ba = 0, bb = 0;
    ha.n = hb.n = 0;
    CHECK(ics_mesh_hits(mesh, o, d, &ha, &ba) == 0 && mc_embree_hits(e, 0, o, d, &sc, &hb, &bb) == 0, "out of memory");
    differ_n += differ(&ha, ba, &hb, bb);
    int pa = (ha.n + ba) & 1, pb = (hb.n + bb) & 1;
    odd_bvh += pa, odd_embree += pb;
    lost += pb && !pa;
  }
  printf("lines through vertices and edges: %d of 6000 cross differently; odd crossing counts: "
         "BVH %d, Embree %d (%d of them where the BVH's is even)\n", differ_n, odd_bvh, odd_embree, lost);
  CHECK(2 * odd_embree <= odd_bvh, "Embree: %d odd lines, the BVH %d", odd_embree, odd_bvh);
  CHECK(odd_embree <= 60, "Embree: %d of 6000 vertex/edge lines cross an odd number of times (limit 1 %%)",
        odd_embree);
  ics_hits_free(&ha);
  ics_hits_free(&hb);
  mc_embree_scratch_free(&sc);
}

/* the mesh far from the world's origin (translated by 1e5), and ray origins 1e5 away from it:
 * no line may cross differently or an odd number of times (single precision in world
 * coordinates lost every crossing here) */
static void test_far(const char *dir, const char *file) {
  char json[4096], msg[4096];
  static const char *fmt =
      "{\"camera\": {\"eye\": [1e5, -2e5, 30010], \"target\": [1e5, -2e5, 3e4], \"height\": 2, \"resolution\": [8, 8]},"
      " \"render\": {\"slab_spacing\": 0.02, \"d1\": 1}, \"lights\": [{\"mean\": [0, 0], \"var\": [0.01, 0.01]}],"
      " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"mesh\", \"file\": \"%s\", \"material\": \"m\","
      " \"translate\": [1e5, -2e5, 3e4]}]}";
  snprintf(json, sizeof json, fmt, file);
  ics_scene *s;
  mc_embree *e;
  if (ics_scene_create_json(&s, json, "far", dir, msg, sizeof msg) != ICS_OK ||
      mc_embree_create(&e, s, 0, msg, sizeof msg) != ICS_OK) {
    CHECK(0, "far scene: %s", msg);
    return;
  }
  const ics_mesh *mesh = ics_scene_object(s, 0)->mesh;
  double lo[3], hi[3], c[3];
  ics_mesh_bounds(mesh, lo, hi);
  for (int i = 0; i < 3; i++) c[i] = 0.5 * (lo[i] + hi[i]);
  ics_hits ha = {0}, hb = {0};
  mc_embree_scratch sc = {0};
  ics_rng r;
  ics_rng_init(&r, 12, 0);
  int bad[2] = {0, 0}, odd[2] = {0, 0}, met[2] = {0, 0};
  for (int k = 0; k < 20000; k++) {
    int far_origin = k % 2;
    double o[3], d[3];
    if (far_origin) { /* from 1e5 away toward a point of the mesh's box */
      double u[3], len = 0;
      random_dir(&r, u);
      for (int i = 0; i < 3; i++) o[i] = c[i] + 1e5 * u[i];
      for (int i = 0; i < 3; i++) d[i] = lo[i] + (hi[i] - lo[i]) * ics_rng_uniform(&r) - o[i], len += d[i] * d[i];
      for (int i = 0; i < 3; i++) d[i] /= sqrt(len);
    } else {
      for (int i = 0; i < 3; i++) o[i] = c[i] + 1.2 * (ics_rng_uniform(&r) - 0.5);
      random_dir(&r, d);
    }
    int ba = 0, bb = 0;
    ha.n = hb.n = 0;
    CHECK(ics_mesh_hits(mesh, o, d, &ha, &ba) == 0 && mc_embree_hits(e, 0, o, d, &sc, &hb, &bb) == 0, "out of memory");
    bad[far_origin] += differ(&ha, ba, &hb, bb);
    odd[far_origin] += (hb.n + bb) & 1;
    met[far_origin] += ha.n + ba > 0;
  }
  printf("mesh translated by 1e5: %d of 10000 lines differ, %d odd (%d meet it); origins 1e5 away: "
         "%d of 10000 differ, %d odd (%d meet it)\n", bad[0], odd[0], met[0], bad[1], odd[1], met[1]);
  CHECK(bad[0] == 0 && odd[0] == 0 && met[0] > 1000, "far mesh: %d differ, %d odd, %d meet it", bad[0], odd[0], met[0]);
  CHECK(bad[1] == 0 && odd[1] == 0 && met[1] > 1000, "far origins: %d differ, %d odd, %d meet it", bad[1], odd[1],
        met[1]);
  ics_hits_free(&ha);
  ics_hits_free(&hb);
  mc_embree_scratch_free(&sc);
  mc_embree_destroy(e);
  ics_scene_destroy(s);
}

static ics_image *render_mc(const ics_scene *s, const char *mc_mesh, char *device, size_t dsize) {
  char msg[4096];
  ics_plan *p = plan_or_exit(s, NULL, 0);
  ics_render_opts ro;
  memset(&ro, 0, sizeof ro);
  ro.backend = "mc", ro.spp = 24, ro.mc_mesh = mc_mesh;
  ics_renderer *rr;
  ics_image *img = NULL;
  ics_render_stats st;
  ics_status status = ics_renderer_create(&rr, &ro, msg, sizeof msg);
  if (status == ICS_OK) {
    status = ics_renderer_render(rr, p, &img, &st, msg, sizeof msg);
    ics_renderer_destroy(rr);
  }
  ics_plan_destroy(p);
  if (status != ICS_OK) {
    snprintf(device, dsize, "error %d: %s", (int)status, msg);
    return NULL;
  }
  snprintf(device, dsize, "%s", st.device);
  return img;
}

int main(void) {
  const char *td = getenv("TMPDIR");
  char dir[512], path[600], json[4096], msg[4096];
  snprintf(dir, sizeof dir, "%s/ics_embree_XXXXXX", td && *td ? td : "/tmp");
  if (!mkdtemp(dir)) return 2;
  snprintf(path, sizeof path, "%s/blob.obj", dir);
  ics_scene *s = NULL;
  snprintf(json, sizeof json, scene_fmt, "blob.obj", "blob.obj");
  int ok = write_blob(path) == 0 && ics_scene_create_json(&s, json, "blob", dir, msg, sizeof msg) == ICS_OK;
  if (ok) test_far(dir, "blob.obj");
  remove(path);
  rmdir(dir);
  if (!ok) {
    fprintf(stderr, "scene: %s\n", msg);
    return 2;
  }
  CHECK(ics_scene_object(s, 0)->closed, "the bumpy sphere is closed");
  CHECK(ics_mesh_triangle_count(ics_scene_object(s, 0)->mesh) == 2 * NU * (NV - 1), "triangle count %d",
        ics_mesh_triangle_count(ics_scene_object(s, 0)->mesh));
  mc_embree *e;
  CHECK(mc_embree_create(&e, s, 0, msg, sizeof msg) == ICS_OK, "mc_embree_create: %s", msg);
  test_lines(s, e);
  mc_embree_destroy(e);

  char dev_bvh[4200], dev_embree[4200], dev_bad[4200];
  ics_image *a = render_mc(s, "bvh", dev_bvh, sizeof dev_bvh), *b = render_mc(s, "embree", dev_embree, sizeof dev_embree);
  CHECK(a && b, "renders: %s / %s", dev_bvh, dev_embree);
  CHECK(strstr(dev_bvh, "meshes: own BVH") != NULL, "device: %s", dev_bvh);
  CHECK(strstr(dev_embree, "meshes: Embree 3.") != NULL, "device: %s", dev_embree);
  if (a && b) {
    int ndiff = 0;
    double maxd = 0;
    const float *pa = a->data, *pb = b->data;
    for (size_t i = 0; i < (size_t)a->width * a->height * a->channels; i++) {
      double d = fabs((double)pa[i] - pb[i]);
      maxd = fmax(maxd, d), ndiff += d > 0;
    }
    printf("render, 48 x 48 at 24 spp: %d values differ, max difference %.3g (%s vs %s)\n", ndiff, maxd,
           dev_embree, dev_bvh);
    CHECK(ndiff == 0, "Embree's image differs from the BVH's in %d values (max %.3g)", ndiff, maxd);
  }
  ics_image_destroy(a);
  ics_image_destroy(b);
  CHECK(render_mc(s, "kd-tree", dev_bad, sizeof dev_bad) == NULL && strstr(dev_bad, "expected auto, embree or bvh"),
        "a bad mc_mesh: %s", dev_bad);
  ics_scene_destroy(s);
  return test_summary("test_render_mc_embree");
}
