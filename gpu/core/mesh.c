/* mesh.c — triangle meshes (files are read by mesh_import.c): a BVH (median split on the
 * longest centroid axis, leaves of up to 4 triangles), all crossings of a ray (Moller-Trumbore in
 * double precision; crossings closer than 1e-9 of the mesh's diagonal are merged so that a ray
 * through a shared edge counts once), and the closedness test used to decide whether a mesh
 * bounds a volume. */
#include "mesh.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


typedef struct {
  double v0[3], e1[3], e2[3];
} tri_t;

typedef struct {
  double lo[3], hi[3];
  int left, right; /* children, or -1 for a leaf */
  int first, count;
} node_t;

struct ics_mesh {
  int ntris;
  tri_t *tris;
  int *order; /* triangle indices in BVH leaf order */
  node_t *nodes;
  int nnodes;
  int closed;
  double lo[3], hi[3], eps;
};

static void tri_bounds(const tri_t *t, double lo[3], double hi[3]) {
  for (int i = 0; i < 3; i++) {
    double a = t->v0[i], b = a + t->e1[i], c = a + t->e2[i];
    lo[i] = fmin(a, fmin(b, c));
    hi[i] = fmax(a, fmax(b, c));
  }
}

static double tri_centroid(const tri_t *t, int axis) {
  return t->v0[axis] + (t->e1[axis] + t->e2[axis]) / 3;
}

/* a triangle index with its sort key (qsort has no context argument: keys travel with it) */
typedef struct {
  double key;
  int index;
} keyed_t;

static int cmp_keyed(const void *a, const void *b) {
  const keyed_t *x = a, *y = b;
  if (x->key != y->key) return (x->key > y->key) - (x->key < y->key);
  return (x->index > y->index) - (x->index < y->index);
}

static int build(ics_mesh *m, int first, int count) {
  int id = m->nnodes++;
  node_t *n = &m->nodes[id];
  for (int i = 0; i < 3; i++) n->lo[i] = INFINITY, n->hi[i] = -INFINITY;
  double clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int k = first; k < first + count; k++) {
    double lo[3], hi[3];
    const tri_t *t = &m->tris[m->order[k]];
    tri_bounds(t, lo, hi);
    for (int i = 0; i < 3; i++) {
      n->lo[i] = fmin(n->lo[i], lo[i]);
      n->hi[i] = fmax(n->hi[i], hi[i]);
      double c = tri_centroid(t, i);
      clo[i] = fmin(clo[i], c);
      chi[i] = fmax(chi[i], c);
    }
  }
  n->first = first;
  n->count = count;
  n->left = n->right = -1;
  if (count <= 4) return id;
  int axis = 0;
  for (int i = 1; i < 3; i++)
    if (chi[i] - clo[i] > chi[axis] - clo[axis]) axis = i;
  if (!(chi[axis] > clo[axis])) return id; /* all centroids equal: one leaf */
  keyed_t *kv = malloc(sizeof *kv * (size_t)count);
  if (!kv) return -1;
  for (int k = 0; k < count; k++)
    kv[k] = (keyed_t){tri_centroid(&m->tris[m->order[first + k]], axis), m->order[first + k]};
  qsort(kv, (size_t)count, sizeof *kv, cmp_keyed);
  for (int k = 0; k < count; k++) m->order[first + k] = kv[k].index;
  free(kv);
  int half = count / 2;
  int l = build(m, first, half);
  int r = l < 0 ? -1 : build(m, first + half, count - half);
  if (r < 0) return -1;
  m->nodes[id].left = l;
  m->nodes[id].right = r;
  m->nodes[id].count = 0;
  return id;
}

/* edges keyed by (min, max) vertex index: closed iff every edge appears exactly twice */
static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

/* a vertex position with its index */
typedef struct {
  double p[3];
  int index;
} vertex_t;

static int cmp_pos(const void *a, const void *b) {
  const vertex_t *x = a, *y = b;
  for (int i = 0; i < 3; i++)
    if (x->p[i] != y->p[i]) return (x->p[i] > y->p[i]) - (x->p[i] < y->p[i]);
  return (x->index > y->index) - (x->index < y->index);
}

static int same_pos(const vertex_t *x, const vertex_t *y) {
  return x->p[0] == y->p[0] && x->p[1] == y->p[1] && x->p[2] == y->p[2];
}

/* Closedness on positions, not indices: files often split a vertex by its normal or texture
 * coordinate, which would make every edge of a closed model look like a boundary. */
static int is_closed(const double *xyz, int nverts, const int *tri, int ntris) {
  size_t ne = 3 * (size_t)ntris;
  uint64_t *e = malloc(sizeof *e * ne);
  vertex_t *ord = malloc(sizeof *ord * (size_t)nverts);
  int *canon = malloc(sizeof *canon * (size_t)nverts);
  if (!e || !ord || !canon) {
    free(e), free(ord), free(canon);
    return 0;
  }
  for (int i = 0; i < nverts; i++)
    ord[i] = (vertex_t){{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}, i};
  qsort(ord, (size_t)nverts, sizeof *ord, cmp_pos);
  for (int i = 0; i < nverts; i++)
    canon[ord[i].index] =
        i > 0 && same_pos(&ord[i], &ord[i - 1]) ? canon[ord[i - 1].index] : ord[i].index;
  free(ord);
  for (int t = 0; t < ntris; t++)
    for (int k = 0; k < 3; k++) {
      uint64_t a = (uint32_t)canon[tri[3 * t + k]], b = (uint32_t)canon[tri[3 * t + (k + 1) % 3]];
      e[3 * (size_t)t + k] = a < b ? a << 32 | b : b << 32 | a;
    }
  qsort(e, ne, sizeof *e, cmp_u64);
  int closed = 1;
  for (size_t i = 0; i < ne && closed;) {
    size_t j = i;
    while (j < ne && e[j] == e[i]) j++;
    if (j - i != 2) closed = 0;
    i = j;
  }
  free(e);
  free(canon);
  return closed;
}

ics_status ics_mesh_create_triangles(ics_mesh **out, const double *xyz, int nverts,
                                     const int *tri, int ntris) {
  *out = NULL;
  if (!xyz || !tri || nverts < 3 || ntris < 1) return ICS_ERR_SIZE;
  if (ntris > ICS_MESH_MAX_TRIANGLES) return ICS_ERR_SIZE;
  for (int i = 0; i < 3 * ntris; i++)
    if (tri[i] < 0 || tri[i] >= nverts) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < 3 * nverts; i++)
    if (!isfinite(xyz[i])) return ICS_ERR_NAN;
  ics_mesh *m = calloc(1, sizeof *m);
  if (!m) return ICS_ERR_NOMEM;
  m->ntris = ntris;
  m->tris = malloc(sizeof *m->tris * (size_t)ntris);
  m->order = malloc(sizeof *m->order * (size_t)ntris);
  m->nodes = malloc(sizeof *m->nodes * (2 * (size_t)ntris));
  if (!m->tris || !m->order || !m->nodes) {
    ics_mesh_destroy(m);
    return ICS_ERR_NOMEM;
  }
  for (int t = 0; t < ntris; t++) {
    const double *a = xyz + 3 * tri[3 * t], *b = xyz + 3 * tri[3 * t + 1],
                 *c = xyz + 3 * tri[3 * t + 2];
    for (int i = 0; i < 3; i++) {
      m->tris[t].v0[i] = a[i];
      m->tris[t].e1[i] = b[i] - a[i];
      m->tris[t].e2[i] = c[i] - a[i];
    }
    m->order[t] = t;
  }
  if (build(m, 0, ntris) < 0) {
    ics_mesh_destroy(m);
    return ICS_ERR_NOMEM;
  }
  memcpy(m->lo, m->nodes[0].lo, sizeof m->lo);
  memcpy(m->hi, m->nodes[0].hi, sizeof m->hi);
  double diag = 0;
  for (int i = 0; i < 3; i++) diag += (m->hi[i] - m->lo[i]) * (m->hi[i] - m->lo[i]);
  m->eps = 1e-9 * sqrt(diag);
  m->closed = is_closed(xyz, nverts, tri, ntris);
  *out = m;
  return ICS_OK;
}

void ics_mesh_destroy(ics_mesh *m) {
  if (!m) return;
  free(m->tris);
  free(m->order);
  free(m->nodes);
  free(m);
}

int ics_mesh_closed(const ics_mesh *m) { return m->closed; }
int ics_mesh_triangle_count(const ics_mesh *m) { return m->ntris; }
size_t ics_mesh_bytes(const ics_mesh *m) {
  return sizeof *m + (size_t)m->ntris * (sizeof *m->tris + sizeof *m->order) +
         (size_t)m->nnodes * sizeof *m->nodes;
}
double ics_mesh_bytes_min(uint64_t ntris) {
  return (double)sizeof(ics_mesh) + (double)ntris * (double)(sizeof(tri_t) + sizeof(int));
}
void ics_mesh_bounds(const ics_mesh *m, double lo[3], double hi[3]) {
  memcpy(lo, m->lo, sizeof m->lo);
  memcpy(hi, m->hi, sizeof m->hi);
}

static int box_hit(const node_t *n, const double o[3], const double inv[3]) {
  double t0 = -INFINITY, t1 = INFINITY;
  for (int i = 0; i < 3; i++) {
    double a = (n->lo[i] - o[i]) * inv[i], b = (n->hi[i] - o[i]) * inv[i];
    if (isnan(a) || isnan(b)) { /* direction 0 along i, origin on a face: inside test */
      if (o[i] < n->lo[i] || o[i] > n->hi[i]) return 0;
      continue;
    }
    if (a > b) {
      double t = a;
      a = b;
      b = t;
    }
    t0 = fmax(t0, a);
    t1 = fmin(t1, b);
  }
  return t0 <= t1;
}

/* by t, then in the order pushed (a total order: the same with any qsort, and the device's) */
static int cmp_hit_t(const void *a, const void *b) {
  const ics_hit *x = a, *y = b;
  if (x->t != y->t) return (x->t > y->t) - (x->t < y->t);
  return (x->seq > y->seq) - (x->seq < y->seq);
}

/* The crossing of the line orig + t dir with triangle t (Moller-Trumbore in double precision):
 * pushed when the line passes inside it (inside_test) or, without the test, wherever it meets
 * the triangle's plane (an accelerator has decided the hit). 0, or -1 when out of memory. */
static int push_crossing(const tri_t *t, const double orig[3], const double dir[3], int inside_test,
                         ics_hits *h) {
  double p[3] = {dir[1] * t->e2[2] - dir[2] * t->e2[1], dir[2] * t->e2[0] - dir[0] * t->e2[2],
                 dir[0] * t->e2[1] - dir[1] * t->e2[0]};
  double det = t->e1[0] * p[0] + t->e1[1] * p[1] + t->e1[2] * p[2];
  if (det == 0) return 0;
  double s[3] = {orig[0] - t->v0[0], orig[1] - t->v0[1], orig[2] - t->v0[2]};
  double u = (s[0] * p[0] + s[1] * p[1] + s[2] * p[2]) / det;
  if (inside_test && (u < 0 || u > 1)) return 0;
  double q[3] = {s[1] * t->e1[2] - s[2] * t->e1[1], s[2] * t->e1[0] - s[0] * t->e1[2],
                 s[0] * t->e1[1] - s[1] * t->e1[0]};
  double v = (dir[0] * q[0] + dir[1] * q[1] + dir[2] * q[2]) / det;
  if (inside_test && (v < 0 || u + v > 1)) return 0;
  double tt = (t->e2[0] * q[0] + t->e2[1] * q[1] + t->e2[2] * q[2]) / det;
  if (!isfinite(tt)) return 0; /* overflowing coordinates: no crossing (as gpu/backends/gl/ldi.comp) */
  double nrm[3] = {t->e1[1] * t->e2[2] - t->e1[2] * t->e2[1], t->e1[2] * t->e2[0] - t->e1[0] * t->e2[2],
                   t->e1[0] * t->e2[1] - t->e1[1] * t->e2[0]};
  return ics_hits_push(h, tt, nrm);
}

/* Sorts the crossings pushed since `start`, merges coincident ones, counts those at t <= 0 into
 * *behind and drops them. */
static void finish_hits(const ics_mesh *m, const double dir[3], ics_hits *h, int start, int *behind) {
  int n = h->n - start, nbehind = 0;
  if (n <= 0) return; /* nothing pushed (h->h may still be NULL) */
  ics_hit *t = h->h + start;
  if (n > 1) qsort(t, (size_t)n, sizeof *t, cmp_hit_t);
  /* a ray through an edge shared by two triangles facing the same way (relative to the ray)
   * crosses once: merge such pairs; two at the same t facing opposite ways are a graze along a
   * silhouette, which crosses twice or not at all: keep both */
  int w = 0;
  double dlen = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  double tol = dlen > 0 ? m->eps / dlen : 0;
  for (int i = 0; i < n; i++) {
    if (w > 0 && t[i].t - t[w - 1].t <= tol &&
        (t[i].n[0] * dir[0] + t[i].n[1] * dir[1] + t[i].n[2] * dir[2] > 0) ==
            (t[w - 1].n[0] * dir[0] + t[w - 1].n[1] * dir[1] + t[w - 1].n[2] * dir[2] > 0))
      continue;
    t[w++] = t[i];
  }
  int keep = 0;
  for (int i = 0; i < w; i++) {
    if (t[i].t > 0)
      t[keep++] = t[i];
    else
      nbehind++;
  }
  h->n = start + keep;
  *behind += nbehind;
}

int ics_mesh_hits(const ics_mesh *m, const double orig[3], const double dir[3], ics_hits *h,
                  int *behind) {
  double inv[3] = {1 / dir[0], 1 / dir[1], 1 / dir[2]};
  int stack[128], sp = 0;
  int start = h->n;
  stack[sp++] = 0;
  while (sp) {
    const node_t *n = &m->nodes[stack[--sp]];
    if (!box_hit(n, orig, inv)) continue;
    if (n->left >= 0) {
      if (sp + 2 > (int)(sizeof stack / sizeof *stack)) return -1;
      stack[sp++] = n->left;
      stack[sp++] = n->right;
      continue;
    }
    for (int k = n->first; k < n->first + n->count; k++)
      if (push_crossing(&m->tris[m->order[k]], orig, dir, 1, h)) return -1;
  }
  finish_hits(m, dir, h, start, behind);
  return 0;
}

int ics_mesh_hits_of(const ics_mesh *m, const int *tris, int ntris, const double orig[3],
                     const double dir[3], ics_hits *h, int *behind) {
  int start = h->n;
  for (int i = 0; i < ntris; i++)
    if (push_crossing(&m->tris[tris[i]], orig, dir, 0, h)) return -1;
  finish_hits(m, dir, h, start, behind);
  return 0;
}

void ics_mesh_triangle(const ics_mesh *m, int k, double v[3][3]) {
  const tri_t *t = &m->tris[k];
  for (int i = 0; i < 3; i++)
    v[0][i] = t->v0[i], v[1][i] = t->v0[i] + t->e1[i], v[2][i] = t->v0[i] + t->e2[i];
}

void ics_mesh_flat_counts(const ics_mesh *m, int *nnodes, int *ntris) {
  *nnodes = m->nnodes;
  *ntris = m->ntris;
}

void ics_mesh_flatten(const ics_mesh *m, int node_base, int tri_base, double *node_box,
                      int32_t *node_links, double *tris) {
  for (int i = 0; i < m->nnodes; i++) {
    const node_t *n = &m->nodes[i];
    memcpy(node_box + 6 * i, n->lo, sizeof n->lo);
    memcpy(node_box + 6 * i + 3, n->hi, sizeof n->hi);
    int32_t *l = node_links + 4 * i;
    l[0] = n->left >= 0 ? node_base + n->left : -1;
    l[1] = n->right >= 0 ? node_base + n->right : -1;
    l[2] = tri_base + n->first;
    l[3] = n->count;
  }
  for (int k = 0; k < m->ntris; k++) {
    const tri_t *t = &m->tris[m->order[k]];
    memcpy(tris + 9 * k, t->v0, sizeof t->v0);
    memcpy(tris + 9 * k + 3, t->e1, sizeof t->e1);
    memcpy(tris + 9 * k + 6, t->e2, sizeof t->e2);
  }
}

double ics_mesh_merge_eps(const ics_mesh *m) { return m->eps; }
