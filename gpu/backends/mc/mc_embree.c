/* mc_embree.c — mesh crossings for the Monte-Carlo reference through Embree 3 (see mc_embree.h,
 * docs/reference.md), the module icshadow-embree.so (gpu/core/module.h; the renderer reaches it
 * through mc_embree_entry.c). The query covers the whole line through the ray, as ics_mesh_hits does:
 * Embree's segment starts at its origin (t >= 0), so the query starts where the line enters the
 * mesh's bounding box (padded by 0.1 % of its size; a line that misses it meets nothing), and t
 * is measured from the real origin again in double precision afterwards. Each mesh's vertices
 * and the query are in the mesh's own frame (its box's centre at 0): single precision then
 * keeps its digits for a mesh or a ray origin far from the world's origin. */
#include "mc_embree.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

#include <embree3/rtcore.h>

#include "module.h"

struct mc_embree {
  RTCDevice dev;
  int nobj;
  RTCScene *scene;        /* per object: NULL unless a mesh */
  const ics_mesh **mesh;  /* per object: its mesh, or NULL */
  double (*ctr)[3];       /* per object: its box's centre, Embree's origin for it */
};

/* the context of one query: Embree's, then where the filter records triangles */
typedef struct {
  struct RTCIntersectContext ctx;
  mc_embree_scratch *sc;
  int oom;
} query_t;

/* RTCHitN is N hits in SOA layout (Ng_x, Ng_y, Ng_z, u, v, primID, geomID, ...; each N wide);
 * Embree's accessor RTCHitN_primID is C++ only, this is its C form (rtcore_ray.h) */
static unsigned hitn_prim_id(const struct RTCHitN *hit, unsigned n, unsigned i) {
  return ((const unsigned *)hit)[5 * n + i];
}

/* record the triangle and reject the hit, so the traversal goes on to every other one */
static void record_all(const struct RTCFilterFunctionNArguments *a) {
  query_t *q = (query_t *)a->context;
  for (unsigned i = 0; i < a->N; i++) {
    if (a->valid[i] != -1) continue;
    mc_embree_scratch *sc = q->sc;
    if (sc->n == sc->cap) {
      int cap = sc->cap ? 2 * sc->cap : 64;
      int *t = realloc(sc->tri, sizeof *t * (size_t)cap);
      if (!t) {
        q->oom = 1;
        a->valid[i] = 0;
        continue;
      }
      sc->tri = t, sc->cap = cap;
    }
    sc->tri[sc->n++] = (int)hitn_prim_id(a->hit, a->N, i);
    a->valid[i] = 0;
  }
}

static void embree_version(char *ver, size_t ver_size) {
  if (ver) snprintf(ver, ver_size, "%d.%d.%d", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
}

static ics_status embree_error(mc_embree *e, char *msg, size_t msg_size, const char *what) {
  enum RTCError err = e->dev ? rtcGetDeviceError(e->dev) : RTC_ERROR_UNKNOWN;
  if (msg)
    snprintf(msg, msg_size, "Embree: %s failed (RTCError %d%s)", what, (int)err,
             err == RTC_ERROR_OUT_OF_MEMORY ? ": out of memory" : "");
  mc_embree_destroy(e);
  return err == RTC_ERROR_OUT_OF_MEMORY ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
}

ics_status mc_embree_create(mc_embree **out, const ics_scene *s, int threads, char *msg,
                            size_t msg_size) {
  *out = NULL;
  mc_embree *e = calloc(1, sizeof *e);
  if (!e) return ICS_ERR_NOMEM;
  e->nobj = s->nobjects;
  e->scene = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *e->scene);
  e->mesh = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *e->mesh);
  e->ctr = calloc((size_t)(s->nobjects ? s->nobjects : 1), sizeof *e->ctr);
  if (!e->scene || !e->mesh || !e->ctr) {
    mc_embree_destroy(e);
    return ICS_ERR_NOMEM;
  }
  char config[32];
  snprintf(config, sizeof config, "threads=%d", threads > 0 ? threads : 0);
  e->dev = rtcNewDevice(config);
  if (!e->dev) return embree_error(e, msg, msg_size, "rtcNewDevice");
  /* every crossing needs the intersection filter, and both faces of every triangle */
  if (!rtcGetDeviceProperty(e->dev, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) ||
      rtcGetDeviceProperty(e->dev, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED)) {
    if (msg) snprintf(msg, msg_size, "Embree: this build of Embree %s (the reference needs "
                      "intersection filters and no back-face culling): use --mc-mesh bvh",
                      rtcGetDeviceProperty(e->dev, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED)
                          ? "culls back faces" : "has no intersection filters");
    mc_embree_destroy(e);
    return ICS_ERR_UNSUPPORTED;
  }
  for (int k = 0; k < s->nobjects; k++) {
    const ics_object *o = &s->objects[k];
    if (o->shape != ICS_SHAPE_MESH) continue;
    int nt = ics_mesh_triangle_count(o->mesh);
    RTCScene sc = rtcNewScene(e->dev);
    if (!sc) return embree_error(e, msg, msg_size, "rtcNewScene");
    e->scene[k] = sc;
    e->mesh[k] = o->mesh;
    double lo[3], hi[3];
    ics_mesh_bounds(o->mesh, lo, hi);
    for (int i = 0; i < 3; i++) e->ctr[k][i] = 0.5 * (lo[i] + hi[i]);
    rtcSetSceneFlags(sc, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(sc, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry g = rtcNewGeometry(e->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!g) return embree_error(e, msg, msg_size, "rtcNewGeometry");
    /* unshared vertices: triangle t is vertices 3t, 3t + 1, 3t + 2 */
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), 3 * (size_t)nt);
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), (size_t)nt);
    if (!v || !ix) {
      rtcReleaseGeometry(g);
      return embree_error(e, msg, msg_size, "a geometry buffer");
    }
    for (int t = 0; t < nt; t++) {
      double w[3][3];
      ics_mesh_triangle(o->mesh, t, w);
      for (int c = 0; c < 3; c++) {
        for (int i = 0; i < 3; i++) v[9 * (size_t)t + 3 * c + i] = (float)(w[c][i] - e->ctr[k][i]);
        ix[3 * (size_t)t + c] = 3 * (unsigned)t + (unsigned)c;
      }
    }
    rtcSetGeometryIntersectFilterFunction(g, record_all);
    rtcCommitGeometry(g);
    rtcAttachGeometry(sc, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(sc);
    if (rtcGetDeviceError(e->dev) != RTC_ERROR_NONE) return embree_error(e, msg, msg_size, "the build");
  }
  *out = e;
  return ICS_OK;
}

void mc_embree_destroy(mc_embree *e) {
  if (!e) return;
  for (int k = 0; e->scene && k < e->nobj; k++)
    if (e->scene[k]) rtcReleaseScene(e->scene[k]);
  free(e->scene);
  free(e->mesh);
  free(e->ctr);
  if (e->dev) rtcReleaseDevice(e->dev);
  free(e);
}

int mc_embree_hits(const mc_embree *e, int obj, const double orig[3], const double dir[3],
                   mc_embree_scratch *sc, ics_hits *h, int *behind) {
  const ics_mesh *mesh = e->mesh[obj];
  const double *ctr = e->ctr[obj];
  double lo[3], hi[3], t0 = -INFINITY, t1 = INFINITY, pad = 0;
  ics_mesh_bounds(mesh, lo, hi);
  for (int i = 0; i < 3; i++) pad = fmax(pad, hi[i] - lo[i]);
  pad = 1e-3 * pad + 1e-12;
  /* where the line enters and leaves the padded box (double precision) */
  for (int i = 0; i < 3; i++) {
    double a = (lo[i] - pad - orig[i]) / dir[i], b = (hi[i] + pad - orig[i]) / dir[i];
    if (isnan(a) || isnan(b)) continue; /* parallel to this slab, on its boundary */
    if (a > b) {
      double x = a;
      a = b, b = x;
    }
    t0 = fmax(t0, a), t1 = fmin(t1, b);
  }
  sc->n = 0;
  if (!(t0 <= t1)) return ics_mesh_hits_of(mesh, sc->tri, 0, orig, dir, h, behind);
  query_t q;
  rtcInitIntersectContext(&q.ctx);
  q.sc = sc;
  q.oom = 0;
  struct RTCRayHit rh;
  memset(&rh, 0, sizeof rh);
  /* from the entry point, in the object's own frame (its centre at 0), so single precision
   * keeps its digits wherever the mesh and the ray's origin are */
  rh.ray.org_x = (float)(orig[0] + t0 * dir[0] - ctr[0]);
  rh.ray.org_y = (float)(orig[1] + t0 * dir[1] - ctr[1]);
  rh.ray.org_z = (float)(orig[2] + t0 * dir[2] - ctr[2]);
  rh.ray.dir_x = (float)dir[0], rh.ray.dir_y = (float)dir[1], rh.ray.dir_z = (float)dir[2];
  rh.ray.tnear = 0;
  rh.ray.tfar = INFINITY;
  rh.ray.mask = (unsigned)-1;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(e->scene[obj], &q.ctx, &rh);
  if (q.oom) return -1;
  return ics_mesh_hits_of(mesh, sc->tri, sc->n, orig, dir, h, behind);
}

static const mc_embree_funcs funcs = {embree_version, mc_embree_create, mc_embree_destroy,
                                      mc_embree_hits};
ICS_MODULE_DEFINE("embree", &funcs)
