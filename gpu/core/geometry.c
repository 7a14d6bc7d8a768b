/* geometry.c — all crossings of a ray with the analytic shapes (rect, disk, box, sphere, torus;
 * meshes in mesh.c), bounding boxes and object frames.
 *
 * Every object carries a frame ax (rows: unit axes) and a centre; a ray is taken into the local
 * frame by q = ax (orig - centre), e = ax dir, and crossings are parameters t of the world ray.
 * Torus (axis = local z, major radius R, minor r): with a unit local direction, the quartic
 * q(s) = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (px^2 + py^2) on the chord of the bounding sphere is split
 * at the real roots of q' (a cubic, solved in closed form and polished by Newton) into monotone
 * pieces, and each sign change is bisected to full precision: no root of multiplicity one is
 * missed, whatever the ray (a tangential double root may be). */
#include "geometry.h"
#include "kernel/crossings.h" /* shared with ldi.comp */

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow/constants.h"
#include "mesh.h"

void ics_hits_free(ics_hits *h) {
  free(h->h);
  h->h = NULL;
  h->n = h->cap = 0;
}

int ics_hits_push(ics_hits *h, double t, const double n[3]) {
  if (h->n == h->cap) {
    int cap = h->cap ? 2 * h->cap : 16;
    ics_hit *p = realloc(h->h, sizeof *p * (size_t)cap);
    if (!p) return -1;
    h->h = p;
    h->cap = cap;
  }
  h->h[h->n].t = t;
  memcpy(h->h[h->n].n, n, sizeof h->h[h->n].n);
  h->h[h->n].seq = h->n;
  h->n++;
  return 0;
}

static double dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void to_local(const ics_object *o, const double orig[3], const double dir[3], double q[3],
                     double e[3]) {
  double d[3] = {orig[0] - o->center[0], orig[1] - o->center[1], orig[2] - o->center[2]};
  for (int i = 0; i < 3; i++) {
    q[i] = dot3(o->ax[i], d);
    e[i] = dot3(o->ax[i], dir);
  }
}

static int push_hit(ics_hits *h, int *behind, double t, const double n[3]) {
  if (t > 0) return ics_hits_push(h, t, n);
  ++*behind;
  return 0;
}

/* world normal from a local one: sum_i nl_i ax[i] */
static void to_world(const ics_object *o, const double nl[3], double n[3]) {
  for (int w = 0; w < 3; w++) n[w] = nl[0] * o->ax[0][w] + nl[1] * o->ax[1][w] + nl[2] * o->ax[2][w];
}

/* torus normal: the gradient of (|p|^2 + R^2 - r^2)^2 - 4 R^2 (px^2 + py^2) at local p */
static void torus_normal(const ics_object *o, const double q[3], const double e[3], double t,
                         double n[3]) {
  double R = o->half[0], r = o->half[1];
  double p[3] = {q[0] + t * e[0], q[1] + t * e[1], q[2] + t * e[2]};
  double a = p[0] * p[0] + p[1] * p[1] + p[2] * p[2] + R * R - r * r;
  double g[3] = {4 * a * p[0] - 8 * R * R * p[0], 4 * a * p[1] - 8 * R * R * p[1], 4 * a * p[2]};
  to_world(o, g, n);
}

/* real roots of s^3 + a s^2 + b s + c (1 or 3), polished by Newton */
static int cubic_roots(double a, double b, double c, double r[3]) {
  double Q = (a * a - 3 * b) / 9, R = (2 * a * a * a - 9 * a * b + 27 * c) / 54;
  int n;
  if (R * R < Q * Q * Q) {
    double th = acos(R / sqrt(Q * Q * Q)), sq = -2 * sqrt(Q);
    r[0] = sq * cos(th / 3) - a / 3;
    r[1] = sq * cos((th + 2 * ICS_PI) / 3) - a / 3;
    r[2] = sq * cos((th - 2 * ICS_PI) / 3) - a / 3;
    n = 3;
  } else {
    double A = -copysign(cbrt(fabs(R) + sqrt(R * R - Q * Q * Q)), R);
    double B = A != 0 ? Q / A : 0;
    r[0] = A + B - a / 3;
    n = 1;
  }
  for (int i = 0; i < n; i++)
    for (int it = 0; it < 4; it++) {
      double x = r[i], f = ((x + a) * x + b) * x + c, df = (3 * x + 2 * a) * x + b;
      if (df == 0) break;
      double nx = x - f / df;
      if (!isfinite(nx)) break;
      r[i] = nx;
    }
  return n;
}

static double quartic(const double k[5], double s) {
  return (((s + k[3]) * s + k[2]) * s + k[1]) * s + k[0];
}

static int torus_hits(const ics_object *o, const double q_orig[3], const double e0[3], ics_hits *h,
                      int *behind) {
  const double *q0 = q_orig;
  double R = o->half[0], r = o->half[1];
  double len = sqrt(dot3(e0, e0));
  if (!(len > 0)) return 0;
  double d[3] = {e0[0] / len, e0[1] / len, e0[2] / len};
  /* bounding sphere chord */
  /* the bounding sphere, slightly inflated so that its chord ends strictly outside the torus
   * (a ray through the ring's outer rim would otherwise start on a root) */
  double A = dot3(q0, d), qq = dot3(q0, q0), rad = (R + r) * (1 + 1e-6);
  double disc = A * A - (qq - rad * rad);
  if (!(disc > 0)) return 0;
  double sq = sqrt(disc), sa = -A - sq, sb = -A + sq;
  /* the quartic is formed about the chord's start, not the ray origin: its coefficients then
   * stay of the torus's size wherever the eye is (about the origin they grow like its distance
   * to the fourth power, and far eyes lost crossings) */
  double q1[3] = {q0[0] + sa * d[0], q0[1] + sa * d[1], q0[2] + sa * d[2]};
  double base = sa;
  q0 = q1;
  A = dot3(q0, d), qq = dot3(q0, q0);
  sa = 0, sb -= base;
  double B = qq + R * R - r * r;
  double a2 = d[0] * d[0] + d[1] * d[1], a1 = q0[0] * d[0] + q0[1] * d[1],
         a0 = q0[0] * q0[0] + q0[1] * q0[1];
  double k[5]; /* monic quartic: s^4 + k3 s^3 + k2 s^2 + k1 s + k0 */
  k[3] = 4 * A;
  k[2] = 4 * A * A + 2 * B - 4 * R * R * a2;
  k[1] = 4 * A * B - 8 * R * R * a1;
  k[0] = B * B - 4 * R * R * a0;
  double crit[3];
  int nc = cubic_roots(3 * k[3] / 4, 2 * k[2] / 4, k[1] / 4, crit);
  double pts[5];
  int np = 0;
  pts[np++] = sa;
  /* sort the critical points inside (sa, sb) */
  for (int i = 0; i < nc; i++)
    for (int j = i + 1; j < nc; j++)
      if (crit[j] < crit[i]) {
        double tmp = crit[i];
        crit[i] = crit[j];
        crit[j] = tmp;
      }
  for (int i = 0; i < nc; i++)
    if (crit[i] > sa && crit[i] < sb) pts[np++] = crit[i];
  pts[np++] = sb;
  for (int i = 0; i + 1 < np; i++) {
    double lo = pts[i], hi = pts[i + 1];
    double flo = quartic(k, lo), fhi = quartic(k, hi);
    if (flo == 0 && i > 0) continue; /* counted as the previous piece's upper end */
    if ((flo < 0) == (fhi < 0) && fhi != 0) continue;
    if (fhi == 0) {
      double n[3], tr = (hi + base) / len;
      torus_normal(o, q_orig, e0, tr, n);
      if (push_hit(h, behind, tr, n)) return -1;
      continue;
    }
    for (int it = 0; it < 200 && hi - lo > 0; it++) {
      double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      double fm = quartic(k, mid);
      if ((fm < 0) == (flo < 0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    double n[3], tr = (0.5 * (lo + hi) + base) / len;
    torus_normal(o, q_orig, e0, tr, n);
    if (push_hit(h, behind, tr, n)) return -1;
  }
  return 0;
}

int ics_object_hits(const ics_object *o, const double orig[3], const double dir[3], ics_hits *h,
                    int *behind) {
  double q[3], e[3];
  if (o->shape == ICS_SHAPE_MESH) return ics_mesh_hits(o->mesh, orig, dir, h, behind);
  to_local(o, orig, dir, q, e);
  switch (o->shape) {
  case ICS_SHAPE_RECT:
  case ICS_SHAPE_DISK: {
    double t[2];
    int in = ics_k_plane_crossing(q, e, o->shape == ICS_SHAPE_DISK, o->half[0], o->half[1], t);
    return in && t[0] > 0 ? ics_hits_push(h, t[0], o->ax[2]) : 0;
  }
  case ICS_SHAPE_BOX: {
    double t[2];
    int axis[2];
    if (!ics_k_box_crossings(q, e, o->half, t, axis)) return 0;
    if (push_hit(h, behind, t[0], o->ax[axis[0]])) return -1;
    return push_hit(h, behind, t[1], o->ax[axis[1]]);
  }
  case ICS_SHAPE_SPHERE: {
    double t[2], n0[3], n1[3];
    if (!ics_k_sphere_crossings(q, e, o->half[0], t)) return 0;
    for (int i = 0; i < 3; i++) n0[i] = orig[i] + t[0] * dir[i] - o->center[i];
    for (int i = 0; i < 3; i++) n1[i] = orig[i] + t[1] * dir[i] - o->center[i];
    if (push_hit(h, behind, t[0], n0)) return -1;
    return push_hit(h, behind, t[1], n1);
  }
  case ICS_SHAPE_TORUS:
    return torus_hits(o, q, e, h, behind);
  default:
    return 0;
  }
}

/* depth z of a crossing of the ray q + t e with torus o, given to a float's precision (a
 * fragment's depth: the point lies up to ~6e-8 z |e| off the surface, an angle that a thin
 * torus seen from afar would see), taken onto the surface by Newton steps on
 * F = (|p|^2 + R^2 - r^2)^2 - 4 R^2 (px^2 + py^2) along the ray, while they stay within 1e-6 z
 * of it (a grazing ray, dF/dt near 0, keeps the depth it has) */
static double torus_refine(const ics_object *o, const double q[3], const double e[3], double z) {
  double R = o->half[0], r = o->half[1], t = z;
  for (int it = 0; it < 4; it++) {
    double p[3] = {q[0] + t * e[0], q[1] + t * e[1], q[2] + t * e[2]};
    double a = dot3(p, p) + R * R - r * r, f = a * a - 4 * R * R * (p[0] * p[0] + p[1] * p[1]);
    double df = (4 * a - 8 * R * R) * (p[0] * e[0] + p[1] * e[1]) + 4 * a * p[2] * e[2];
    double next = t - f / df;
    if (!isfinite(next) || !(fabs(next - z) <= 1e-6 * fabs(z))) break;
    t = next;
  }
  return t;
}

int ics_object_normal_near(const ics_object *o, const double orig[3], const double dir[3], double z,
                           ics_hits *h, double n[3]) {
  n[0] = n[1] = n[2] = 0;
  if (o->shape == ICS_SHAPE_TORUS) {
    double q[3], e[3];
    to_local(o, orig, dir, q, e);
    torus_normal(o, q, e, torus_refine(o, q, e, z), n);
    return 0;
  }
  int behind = 0;
  h->n = 0;
  if (ics_object_hits(o, orig, dir, h, &behind)) return -1;
  double best = INFINITY;
  for (int i = 0; i < h->n; i++)
    if (fabs(h->h[i].t - z) < best) best = fabs(h->h[i].t - z), memcpy(n, h->h[i].n, sizeof(double) * 3);
  return 0;
}

void ics_object_bounds(const ics_object *o, double lo[3], double hi[3]) {
  if (o->shape == ICS_SHAPE_MESH) {
    ics_mesh_bounds(o->mesh, lo, hi);
    return;
  }
  double ext[3]; /* local half extents */
  switch (o->shape) {
  case ICS_SHAPE_RECT:
    ext[0] = o->half[0], ext[1] = o->half[1], ext[2] = 0;
    break;
  case ICS_SHAPE_DISK:
    ext[0] = ext[1] = o->half[0], ext[2] = 0;
    break;
  case ICS_SHAPE_BOX:
    memcpy(ext, o->half, sizeof ext);
    break;
  case ICS_SHAPE_SPHERE:
    ext[0] = ext[1] = ext[2] = o->half[0];
    break;
  default: /* torus */
    ext[0] = ext[1] = o->half[0] + o->half[1], ext[2] = o->half[1];
    break;
  }
  for (int w = 0; w < 3; w++) {
    double r = 0;
    for (int i = 0; i < 3; i++) r += fabs(o->ax[i][w]) * ext[i];
    lo[w] = o->center[w] - r;
    hi[w] = o->center[w] + r;
  }
}

/* scaled first, so that tiny (1e-200) and huge (1e200) vectors keep their direction */
static void normalize3(double v[3]) {
  double m = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
  if (!(m > 0) || !isfinite(m)) return;
  v[0] /= m, v[1] /= m, v[2] /= m;
  double n = sqrt(dot3(v, v));
  v[0] /= n, v[1] /= n, v[2] /= n;
}

static void cross3(const double a[3], const double b[3], double o[3]) {
  o[0] = a[1] * b[2] - a[2] * b[1];
  o[1] = a[2] * b[0] - a[0] * b[2];
  o[2] = a[0] * b[1] - a[1] * b[0];
}

void ics_frame_from_normal(const double n[3], const double *up, double ax[3][3]) {
  double z[3] = {n[0], n[1], n[2]};
  normalize3(z);
  double y[3];
  double cand[3] = {0, 1, 0};
  if (up) memcpy(cand, up, sizeof cand), normalize3(cand);
  /* y = the candidate made perpendicular to z; fall back to world axes when parallel */
  for (int attempt = 0; attempt < 3; attempt++) {
    double d = dot3(cand, z);
    for (int i = 0; i < 3; i++) y[i] = cand[i] - d * z[i];
    if (sqrt(dot3(y, y)) > 1e-6 * sqrt(dot3(cand, cand))) break;
    double alt[2][3] = {{0, 0, 1}, {1, 0, 0}};
    memcpy(cand, alt[attempt < 2 ? attempt : 1], sizeof cand);
  }
  normalize3(y);
  double x[3];
  cross3(y, z, x);
  memcpy(ax[0], x, sizeof x);
  memcpy(ax[1], y, sizeof y);
  memcpy(ax[2], z, sizeof z);
}

void ics_frame_rotate(double ax[3][3], const double rot_deg[3]) {
  for (int k = 0; k < 3; k++) {
    double a = rot_deg[k] * (ICS_PI / 180), c = cos(a), s = sin(a);
    int i = (k + 1) % 3, j = (k + 2) % 3; /* rotation in the (i, j) plane about world axis k */
    for (int row = 0; row < 3; row++) {
      double vi = ax[row][i], vj = ax[row][j];
      ax[row][i] = c * vi - s * vj;
      ax[row][j] = s * vi + c * vj;
    }
  }
}
