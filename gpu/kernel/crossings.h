/* crossings.h — a ray's crossings with the analytic shapes, in the shape's own frame: q is the ray's
 * origin and e its direction relative to the object's centre along its axes (the ray is
 * q + t e; geometry.c's ics_object_hits). Each returns how many crossings it wrote to t (and,
 * for a box, the axis of each face), in increasing t, behind the origin too (t <= 0: the
 * caller counts those for the inside test); every operation in the host's order and `precise`,
 * so the device's layered depth image (ldi.comp) matches the host's bit for bit. The torus and
 * meshes are the callers' own (GLSL has acos, cos and cbrt in float only). Shared kernel source
 * (lang.h): geometry.c and ldi.comp compile this one text. */
#ifndef ICS_KERNEL_CROSSINGS_H
#define ICS_KERNEL_CROSSINGS_H
#include "kernel/lang.h"

/* a rect (half sizes hx, hy) or a disk (disk != 0, radius hx) in the plane z = 0 */
ICS_FN int ics_k_plane_crossing(ICS_CONST_IN double q[3], ICS_CONST_IN double e[3], int disk,
                                double hx, double hy, ICS_OUT double t[2]) {
  if (e[2] == 0.0) return 0;
  ICS_PRECISE double tt = -q[2] / e[2];
  ICS_PRECISE double x = q[0] + tt * e[0], y = q[1] + tt * e[1];
  ICS_PRECISE double rr = x * x + y * y, r2 = hx * hx;
  int inside = disk == 0 ? (ICS_FABS(x) <= hx && ICS_FABS(y) <= hy ? 1 : 0) : (rr <= r2 ? 1 : 0);
  t[0] = tt;
  return inside;
}

/* a box of half sizes h: where the line enters and leaves the slabs of all three axes (an axis
 * the line is parallel to: outside its slab, no crossing); the face's axis of each in axis */
ICS_FN int ics_k_box_crossings(ICS_CONST_IN double q[3], ICS_CONST_IN double e[3],
                               ICS_CONST_IN double h[3], ICS_OUT double t[2], ICS_OUT int axis[2]) {
  ICS_PRECISE double t0 = -ICS_DBL_INF, t1 = ICS_DBL_INF;
  int i0 = 0, i1 = 0;
  for (int i = 0; i < 3; i++) {
    if (e[i] == 0.0) {
      if (ICS_FABS(q[i]) > h[i]) return 0;
      continue;
    }
    ICS_PRECISE double a = (-h[i] - q[i]) / e[i], b = (h[i] - q[i]) / e[i];
    if (a > b) {
      double tmp = a;
      a = b;
      b = tmp;
    }
    if (a > t0) t0 = a, i0 = i;
    if (b < t1) t1 = b, i1 = i;
  }
  if (!(t0 < t1)) return 0;
  t[0] = t0, t[1] = t1, axis[0] = i0, axis[1] = i1;
  return 2;
}

/* a sphere of radius r: the stable pair t = (-b -+ s) / a, the far one from c / (a t_near) */
ICS_FN int ics_k_sphere_crossings(ICS_CONST_IN double q[3], ICS_CONST_IN double e[3], double r,
                                  ICS_OUT double t[2]) {
  ICS_PRECISE double a = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  ICS_PRECISE double b = q[0] * e[0] + q[1] * e[1] + q[2] * e[2];
  ICS_PRECISE double c = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - r * r;
  ICS_PRECISE double disc = b * b - a * c;
  if (!(disc > 0.0) || !(a > 0.0)) return 0;
  ICS_PRECISE double s = sqrt(disc);
  ICS_PRECISE double qv = -(b + ICS_COPYSIGN(s, b));
  ICS_PRECISE double t0 = qv / a, t1 = c / qv;
  if (t0 > t1) {
    double tmp = t0;
    t0 = t1;
    t1 = tmp;
  }
  t[0] = t0, t[1] = t1;
  return 2;
}

#endif
