#version 450
/* ldi.comp — the layered depth image built on the device (docs/backend_gl.md "The layered depth
 * image on the device"): the same fragments as the plan's geometry pass (gpu/core/ldi.c,
 * geometry.c, mesh.c), ray cast in double precision into per-pixel linked lists, then sorted
 * front to back into the offsets-and-arrays layout the shading reads. One program per entry
 * point, defined on the line after #version (glslangValidator -DICS_K_... checks each):
 *
 *   ICS_K_LDI_CAST  per buffer pixel: every crossing of its camera ray with every object
 *        (rect, disk, box, sphere, torus; meshes through their BVH, with mesh.c's merge of
 *        coincident crossings), each appended to the pixel's list from one pool (an atomic
 *        counter; past the pool's capacity the counter still counts, so the host grows the pool
 *        and casts again); the pixel's count and its inside mask (volumes containing the eye);
 *   ICS_K_LDI_SCAN  the counts' exclusive prefix sum: the fragments' offsets (one work group);
 *   ICS_K_LDI_SORT  per pixel: its list sorted by (depth, object, order of crossing), as the
 *        host's stable sort, then each fragment's depth, code (object, surface bias, slab),
 *        depth gradient and span as ldi.c computes them, and the pixel's shading state.
 *
 * Every double is `precise` (no contraction into FMAs: the host's geometry code has none) and
 * each expression keeps the host's order of operations, so the fragments agree bit for bit;
 * the torus's closed-form cubic needs acos, cos and cbrt, which GLSL has in float only: its
 * roots start in float and are polished by Newton's method in double, and only split the chord
 * into monotone pieces, within which bisection finds the crossing as the host does. */
#extension GL_ARB_gpu_shader_fp64 : enable
#define ICS_GLSL 1
#include "kernel/lang.h"
#include "kernel/device_layout.h"

#define SHAPE_RECT 0
#define SHAPE_DISK 1
#define SHAPE_BOX 2
#define SHAPE_SPHERE 3
#define SHAPE_TORUS 4
#define SHAPE_MESH 5
/* the records' offsets G_*, CAM_* and ICS_DEV_GEO_STRIDE: gpu/kernel/device_layout.h */
#define NIL 0xffffffffu
#define DEAD 0xffffffffu /* a merged or behind mesh crossing's object */

/* the pool of crossings: t and the normal, then (object, next) */
layout(std430, binding = 4) buffer PoolTN { dvec4 pool_tn[]; };
layout(std430, binding = 5) buffer PoolLink { uvec2 pool_link[]; };
layout(std430, binding = 6) buffer Head { uint head[]; };
layout(std430, binding = 7) buffer Count { uint cnt[]; };
layout(std430, binding = 8) buffer Inside { uvec2 inside[]; };
/* next node, the largest count, the most crossings one pixel pushed (the host's bound on the
 * 32-bit counter: pushes x pixels < 2^32) */
layout(std430, binding = 9) buffer Counter { uint next_node; uint max_layers; uint max_pushes; };

uniform int npx, gw, gh, W, H, pad_l, pad_t;
uniform uint cap;

#if defined(ICS_K_LDI_CAST) || defined(ICS_K_LDI_SORT)
/* the camera as device_scene.c packs it: eye, r, u, f, height, width, tan(fov / 2), aspect,
 * perspective */
layout(std430, binding = 0) readonly buffer Geo { double geo[]; };
layout(std430, binding = 1) readonly buffer Cam { double cam[]; };

/* the camera ray of a buffer pixel: gpu/kernel/camera.h over the camera record */
#define ICS_VIEW_PARAM
#define ICS_VIEW_ARG
#define ICS_CAM(f) cam[f]
#include "kernel/camera.h"
#include "kernel/crossings.h"
void plan_ray(int bi, int bj, out dvec3 o, out dvec3 d) {
  double oa[3], da[3];
  ics_k_plan_ray(bi, bj, W, H, pad_l, pad_t, oa, da);
  o = dvec3(oa[0], oa[1], oa[2]);
  d = dvec3(da[0], da[1], da[2]);
}
#endif

#ifdef ICS_K_LDI_CAST
layout(local_size_x = 16, local_size_y = 8) in;
layout(std430, binding = 2) readonly buffer NodeBox { double node_box[]; };
layout(std430, binding = 3) readonly buffer NodeLink { ivec4 node_link[]; };
layout(std430, binding = 10) readonly buffer Tris { double tris[]; };
uniform int nobj;

uint list_head, live, pushes;

double g(int k, int i) { return geo[k * ICS_DEV_GEO_STRIDE + i]; }

double dot3(dvec3 a, dvec3 b) {
  precise double r = a.x * b.x + a.y * b.y + a.z * b.z;
  return r;
}
dvec3 axis(int k, int i) { return dvec3(g(k, G_AXES + 3 * i), g(k, G_AXES + 1 + 3 * i), g(k, G_AXES + 2 + 3 * i)); }

void push(double t, dvec3 n, uint obj) {
  uint idx = atomicAdd(next_node, 1u);
  live++, pushes++;
  if (idx >= cap) return; /* counted: the host grows the pool and casts again */
  pool_tn[idx] = dvec4(t, n);
  pool_link[idx] = uvec2(obj, list_head);
  list_head = idx;
}

/* geometry.c push_hit */
void push_hit(double t, dvec3 n, uint obj, inout int behind) {
  if (t > 0.0LF)
    push(t, n, obj);
  else
    behind++;
}

/* ---- torus (geometry.c torus_hits) ---- */
/* cbrt(x) for x >= 0 in double: the exponent split off (x = m 2^(3q + r)), a float start for
 * the cube root of m 2^r in [0.5, 4), which float holds whatever the torus's size, and Newton */
double dcbrt(double x) {
  if (!(x > 0.0LF) || isinf(x)) return x;
  int e;
  double m = frexp(x, e);
  int q = e >= 0 ? e / 3 : -((2 - e) / 3), rem = e - 3 * q;
  precise double mm = ldexp(m, rem);
  precise double y = double(pow(float(mm), 1.0 / 3.0));
  for (int it = 0; it < 3; it++) y = y - (y * y * y - mm) / (3.0LF * y * y);
  return ldexp(y, q);
}

int cubic_roots(double a, double b, double c, out double r[3]) {
  precise double Q = (a * a - 3.0LF * b) / 9.0LF;
  precise double R = (2.0LF * a * a * a - 9.0LF * a * b + 27.0LF * c) / 54.0LF;
  precise double QQQ = Q * Q * Q, RR = R * R;
  int n;
  if (RR < QQQ) {
    precise double sq = -2.0LF * sqrt(Q), a3 = a / 3.0LF;
    float th = acos(float(R / sqrt(QQQ))); /* in [-1, 1]: float holds it */
    precise double r0 = sq * double(cos(th / 3.0)) - a3;
    precise double r1 = sq * double(cos((th + 2.0 * 3.14159265358979) / 3.0)) - a3;
    precise double r2 = sq * double(cos((th - 2.0 * 3.14159265358979) / 3.0)) - a3;
    r[0] = r0, r[1] = r1, r[2] = r2;
    n = 3;
  } else {
    precise double A = dcbrt(abs(R) + sqrt(RR - QQQ));
    if ((unpackDouble2x32(R).y & 0x80000000u) == 0u) A = -A; /* -copysign(cbrt(...), R) */
    precise double B = A != 0.0LF ? Q / A : 0.0LF;
    r[0] = A + B - a / 3.0LF;
    r[1] = r[2] = 0.0LF;
    n = 1;
  }
  /* the host's 4 Newton steps, and 2 more for the float start */
  for (int i = 0; i < n; i++)
    for (int it = 0; it < 6; it++) {
      precise double x = r[i], f = ((x + a) * x + b) * x + c, df = (3.0LF * x + 2.0LF * a) * x + b;
      if (df == 0.0LF) break;
      precise double nx = x - f / df;
      if (isnan(nx) || isinf(nx)) break;
      r[i] = nx;
    }
  return n;
}

double quartic(double k[5], double s) {
  precise double r = (((s + k[3]) * s + k[2]) * s + k[1]) * s + k[0];
  return r;
}

dvec3 to_world(int k, dvec3 nl) {
  dvec3 n;
  for (int w = 0; w < 3; w++) {
    precise double v = nl.x * g(k, G_AXES + w) + nl.y * g(k, G_AXES + 3 + w) + nl.z * g(k, G_AXES + 6 + w);
    n[w] = v;
  }
  return n;
}

dvec3 torus_normal(int k, dvec3 q, dvec3 e, double t) {
  precise double R = g(k, G_HALF), r = g(k, G_HALF + 1);
  precise dvec3 p = dvec3(q.x + t * e.x, q.y + t * e.y, q.z + t * e.z);
  precise double a = p.x * p.x + p.y * p.y + p.z * p.z + R * R - r * r;
  precise dvec3 gr = dvec3(4.0LF * a * p.x - 8.0LF * R * R * p.x, 4.0LF * a * p.y - 8.0LF * R * R * p.y,
                           4.0LF * a * p.z);
  return to_world(k, gr);
}

void torus_hits(int k, dvec3 q_orig, dvec3 e0, inout int behind) {
  precise double R = g(k, G_HALF), r = g(k, G_HALF + 1);
  precise double len = sqrt(dot3(e0, e0));
  if (!(len > 0.0LF)) return;
  precise dvec3 d = dvec3(e0.x / len, e0.y / len, e0.z / len);
  precise double A = dot3(q_orig, d), qq = dot3(q_orig, q_orig), rad = (R + r) * (1.0LF + 1e-6LF);
  precise double disc = A * A - (qq - rad * rad);
  if (!(disc > 0.0LF)) return;
  precise double sq = sqrt(disc), sa = -A - sq, sb = -A + sq;
  precise dvec3 q0 = dvec3(q_orig.x + sa * d.x, q_orig.y + sa * d.y, q_orig.z + sa * d.z);
  precise double base = sa;
  A = dot3(q0, d), qq = dot3(q0, q0);
  sa = 0.0LF, sb -= base;
  precise double B = qq + R * R - r * r;
  precise double a2 = d.x * d.x + d.y * d.y, a1 = q0.x * d.x + q0.y * d.y, a0 = q0.x * q0.x + q0.y * q0.y;
  double kq[5];
  precise double k3 = 4.0LF * A, k2 = 4.0LF * A * A + 2.0LF * B - 4.0LF * R * R * a2;
  precise double k1 = 4.0LF * A * B - 8.0LF * R * R * a1, k0 = B * B - 4.0LF * R * R * a0;
  kq[3] = k3, kq[2] = k2, kq[1] = k1, kq[0] = k0, kq[4] = 1.0LF;
  double crit[3];
  precise double c2 = 3.0LF * k3 / 4.0LF, c1 = 2.0LF * k2 / 4.0LF, c0 = k1 / 4.0LF;
  int nc = cubic_roots(c2, c1, c0, crit);
  double pts[5];
  int np = 0;
  pts[np++] = sa;
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
    precise double lo = pts[i], hi = pts[i + 1];
    precise double flo = quartic(kq, lo), fhi = quartic(kq, hi);
    if (flo == 0.0LF && i > 0) continue;
    if ((flo < 0.0LF) == (fhi < 0.0LF) && fhi != 0.0LF) continue;
    if (fhi == 0.0LF) {
      precise double tr = (hi + base) / len;
      push_hit(tr, torus_normal(k, q_orig, e0, tr), uint(k), behind);
      continue;
    }
    for (int it = 0; it < 200 && hi - lo > 0.0LF; it++) {
      precise double mid = 0.5LF * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      precise double fm = quartic(kq, mid);
      if ((fm < 0.0LF) == (flo < 0.0LF)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    precise double tr = (0.5LF * (lo + hi) + base) / len;
    push_hit(tr, torus_normal(k, q_orig, e0, tr), uint(k), behind);
  }
}

/* ---- meshes (mesh.c) ---- */
bool box_hit(int n, dvec3 o, dvec3 d) {
  precise double t0 = 0.0LF, t1 = 0.0LF; /* the host's -inf, inf: no axis yet */
  bool any0 = false, any1 = false;
  for (int i = 0; i < 3; i++) {
    double lo = node_box[6 * n + i], hi = node_box[6 * n + 3 + i];
    if (d[i] == 0.0LF) { /* the host's 0 x inf: an inside test on that axis */
      if (o[i] < lo || o[i] > hi) return false;
      continue;
    }
    precise double inv = 1.0LF / d[i];
    precise double a = (lo - o[i]) * inv, b = (hi - o[i]) * inv;
    if (a > b) {
      double t = a;
      a = b;
      b = t;
    }
    t0 = any0 ? max(t0, a) : a, any0 = true;
    t1 = any1 ? min(t1, b) : b, any1 = true;
  }
  return !any0 || t0 <= t1;
}

/* push_crossing with the inside test */
void mesh_crossing(int tri, dvec3 o, dvec3 d, uint obj) {
  dvec3 v0 = dvec3(tris[9 * tri], tris[9 * tri + 1], tris[9 * tri + 2]);
  dvec3 e1 = dvec3(tris[9 * tri + 3], tris[9 * tri + 4], tris[9 * tri + 5]);
  dvec3 e2 = dvec3(tris[9 * tri + 6], tris[9 * tri + 7], tris[9 * tri + 8]);
  precise dvec3 p = dvec3(d.y * e2.z - d.z * e2.y, d.z * e2.x - d.x * e2.z, d.x * e2.y - d.y * e2.x);
  precise double det = e1.x * p.x + e1.y * p.y + e1.z * p.z;
  if (det == 0.0LF) return;
  precise dvec3 s = dvec3(o.x - v0.x, o.y - v0.y, o.z - v0.z);
  precise double u = (s.x * p.x + s.y * p.y + s.z * p.z) / det;
  if (u < 0.0LF || u > 1.0LF) return;
  precise dvec3 q = dvec3(s.y * e1.z - s.z * e1.y, s.z * e1.x - s.x * e1.z, s.x * e1.y - s.y * e1.x);
  precise double v = (d.x * q.x + d.y * q.y + d.z * q.z) / det;
  if (v < 0.0LF || u + v > 1.0LF) return;
  precise double tt = (e2.x * q.x + e2.y * q.y + e2.z * q.z) / det;
  if (isnan(tt) || isinf(tt)) return; /* overflowing coordinates: no crossing (as mesh.c) */
  precise dvec3 nrm = dvec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                            e1.x * e2.y - e1.y * e2.x);
  push(tt, nrm, obj);
}

/* (t, index) of node c; the crossings of one mesh in the host's stable order by t */
bool key_less(double ta, uint ia, double tb, uint ib) { return ta < tb || (ta == tb && ia < ib); }

/* finish_hits on the crossings pushed since `stop`: in order of (t, push order), those within
 * tol of the last one kept and facing the same way are merged away; then those at t <= 0 are
 * counted into behind and dropped. Done in place over the list (at most n passes over the n
 * crossings), so no mesh has a limit on its crossings per ray. */
void mesh_finish(uint stop, dvec3 d, double eps, inout int behind) {
  precise double dlen = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  precise double tol = dlen > 0.0LF ? eps / dlen : 0.0LF;
  double prev_t = 0.0LF, kept_t = 0.0LF;
  uint prev_i = NIL;
  bool have_prev = false, have_kept = false, kept_face = false;
  for (;;) {
    uint best = NIL;
    double best_t = 0.0LF;
    for (uint c = list_head; c != stop; c = pool_link[c].y) {
      double t = pool_tn[c].x;
      if (have_prev && !key_less(prev_t, prev_i, t, c)) continue;
      if (best == NIL || key_less(t, c, best_t, best)) best = c, best_t = t;
    }
    if (best == NIL) break;
    have_prev = true, prev_t = best_t, prev_i = best;
    dvec3 n = pool_tn[best].yzw;
    precise double nd = n.x * d.x + n.y * d.y + n.z * d.z;
    bool face = nd > 0.0LF;
    precise double gap = best_t - kept_t;
    if (have_kept && gap <= tol && face == kept_face) {
      pool_link[best].x = DEAD;
      live--;
      continue;
    }
    have_kept = true, kept_t = best_t, kept_face = face;
    if (!(best_t > 0.0LF)) {
      pool_link[best].x = DEAD;
      live--;
      behind++;
    }
  }
}

void mesh_hits(int k, dvec3 o, dvec3 d, inout int behind) {
  uint stop = list_head;
  int stack[64], sp = 1;
  stack[0] = int(g(k, G_BVH_ROOT));
  while (sp > 0 && sp <= 62) { /* the host's BVH of median splits is at most 26 deep */
    sp--;
    int node = stack[sp];
    if (box_hit(node, o, d)) {
      ivec4 l = node_link[node];
      if (l.x >= 0) {
        stack[sp] = l.x;
        stack[sp + 1] = l.y;
        sp += 2;
      } else {
        for (int t = l.z; t < l.z + l.w; t++) mesh_crossing(t, o, d, uint(k));
      }
    }
  }
  mesh_finish(stop, d, g(k, G_MERGE_EPS), behind);
}

void main() {
  int bi = int(gl_GlobalInvocationID.x), bj = int(gl_GlobalInvocationID.y);
  if (bi >= gw || bj >= gh) return;
  int px = bj * gw + bi;
  dvec3 o, d;
  plan_ray(bi, bj, o, d);
  list_head = NIL, live = 0u, pushes = 0u;
  uvec2 ins = uvec2(0u);
  for (int k = 0; k < nobj; k++) {
    int shape = int(g(k, G_SHAPE)), behind = 0;
    if (shape == SHAPE_MESH) {
      mesh_hits(k, o, d, behind);
    } else {
      precise dvec3 c = dvec3(g(k, G_CENTER), g(k, G_CENTER + 1), g(k, G_CENTER + 2));
      precise dvec3 dd = dvec3(o.x - c.x, o.y - c.y, o.z - c.z);
      dvec3 q, e;
      for (int i = 0; i < 3; i++) q[i] = dot3(axis(k, i), dd), e[i] = dot3(axis(k, i), d);
      double qa[3] = double[3](q.x, q.y, q.z), ea[3] = double[3](e.x, e.y, e.z), t[2];
      int axis_of[2];
      if (shape == SHAPE_RECT || shape == SHAPE_DISK) {
        if (ics_k_plane_crossing(qa, ea, shape == SHAPE_DISK ? 1 : 0, g(k, G_HALF), g(k, G_HALF + 1), t) != 0 &&
            t[0] > 0.0LF)
          push(t[0], axis(k, 2), uint(k));
      } else if (shape == SHAPE_BOX) {
        double hb[3] = double[3](g(k, G_HALF), g(k, G_HALF + 1), g(k, G_HALF + 2));
        if (ics_k_box_crossings(qa, ea, hb, t, axis_of) != 0) {
          push_hit(t[0], axis(k, axis_of[0]), uint(k), behind);
          push_hit(t[1], axis(k, axis_of[1]), uint(k), behind);
        }
      } else if (shape == SHAPE_SPHERE) {
        if (ics_k_sphere_crossings(qa, ea, g(k, G_HALF), t) != 0) {
          precise dvec3 n0 = dvec3(o.x + t[0] * d.x - c.x, o.y + t[0] * d.y - c.y, o.z + t[0] * d.z - c.z);
          precise dvec3 n1 = dvec3(o.x + t[1] * d.x - c.x, o.y + t[1] * d.y - c.y, o.z + t[1] * d.z - c.z);
          push_hit(t[0], n0, uint(k), behind);
          push_hit(t[1], n1, uint(k), behind);
        }
      } else if (shape == SHAPE_TORUS) {
        torus_hits(k, q, e, behind);
      }
    }
    int bit = int(g(k, G_VOLBIT));
    if (bit >= 0 && (behind & 1) != 0) {
      if (bit < 32) ins.x |= 1u << bit;
      else ins.y |= 1u << (bit - 32);
    }
  }
  head[px] = list_head;
  cnt[px] = live;
  inside[px] = ins;
  atomicMax(max_layers, live);
  atomicMax(max_pushes, pushes);
}
#endif

#ifdef ICS_K_LDI_SCAN
layout(local_size_x = 256) in;
layout(std430, binding = 11) buffer Offset { uint offset[]; };
shared uint part[256];
void main() {
  uint i = gl_LocalInvocationIndex, n = uint(npx), chunk = (n + 255u) / 256u;
  uint lo = min(i * chunk, n), hi = min(lo + chunk, n), s = 0u;
  for (uint p = lo; p < hi; p++) s += cnt[p];
  part[i] = s;
  barrier();
  if (i == 0u) {
    uint acc = 0u;
    for (uint j = 0u; j < 256u; j++) {
      uint v = part[j];
      part[j] = acc;
      acc += v;
    }
    offset[n] = acc;
  }
  barrier();
  uint acc = part[i];
  for (uint p = lo; p < hi; p++) {
    offset[p] = acc;
    acc += cnt[p];
  }
}
#endif

#ifdef ICS_K_LDI_SORT
layout(local_size_x = 64) in;
layout(std430, binding = 11) readonly buffer Offset { uint offset[]; };
layout(std430, binding = 12) buffer Order { uint order[]; };
layout(std430, binding = 13) writeonly buffer FZ { float fz[]; };
layout(std430, binding = 14) writeonly buffer FCode { uint fcode[]; };
layout(std430, binding = 15) writeonly buffer FGrad { vec2 fgrad[]; };
layout(std430, binding = 3) buffer FSpan { uint fspan[]; }; /* bytes, 4 per word (zeroed) */
layout(std430, binding = 2) writeonly buffer Pix { uvec4 pix[]; };
uniform double z0, e, reach;
uniform int K;

#define FRAG_OBJ_BITS 12
#define FRAG_SLAB_SHIFT 16
#define FRAG_MAX_BIAS 15.0LF
#define FRAG_MAX_SPAN 255.0LF
#define FRAG_GRAD_SCALE 64.0LF

bool frag_less(uint a, uint b) {
  double ta = pool_tn[a].x, tb = pool_tn[b].x;
  if (ta != tb) return ta < tb;
  uint oa = pool_link[a].x, ob = pool_link[b].x;
  if (oa != ob) return oa < ob;
  return a < b;
}

void main() {
  /* pixels in rows of groups (a dispatch has at most 65535 groups per dimension) */
  uint px = gl_GlobalInvocationID.y * gl_NumWorkGroups.x * 64u + gl_GlobalInvocationID.x;
  if (px >= uint(npx)) return;
  int bi = int(px % uint(gw)), bj = int(px / uint(gw));
  uint off = offset[px], n = offset[px + 1u] - off;
  /* the live crossings, then an insertion sort (stable: ties keep the order of crossing) */
  uint m = 0u;
  for (uint c = head[px]; c != NIL && m < n; c = pool_link[c].y)
    if (pool_link[c].x != DEAD) order[off + m++] = c;
  for (uint i = 1u; i < n; i++) {
    uint x = order[off + i], j = i;
    while (j > 0u && frag_less(x, order[off + j - 1u])) {
      order[off + j] = order[off + j - 1u];
      j--;
    }
    order[off + j] = x;
  }
  dvec3 ro, rd;
  plan_ray(bi, bj, ro, rd);
  for (uint i = 0u; i < n; i++) {
    uint c = order[off + i], obj = pool_link[c].x;
    precise double t = pool_tn[c].x;
    dvec3 nv = pool_tn[c].yzw;
    /* surface_gradient: the tan of the tilt from the ray over the slab spacing */
    precise double nn = nv.x * nv.x + nv.y * nv.y + nv.z * nv.z;
    precise double dd = rd.x * rd.x + rd.y * rd.y + rd.z * rd.z;
    precise double nd = nv.x * rd.x + nv.y * rd.y + nv.z * rd.z;
    precise double c2 = nd * nd / (nn * dd);
    bool level = !(c2 < 1.0LF), edge_on = !level && !(c2 > 0.0LF);
    precise double gr = level || edge_on ? 0.0LF : sqrt((1.0LF - c2) / c2) / e;
    precise double q = cam[CAM_PROJ] == 0.0LF ? cam[CAM_H] / double(H) : 2.0LF * t * cam[CAM_TH] / double(H);
    precise double u = (t - z0) / e + 1e-6LF, k = floor(u);
    precise double reach3 = max(3.0LF * q, reach);
    precise double delay = edge_on ? FRAG_MAX_BIAS : min(gr * reach3, FRAG_MAX_BIAS);
    precise double ko = floor(u + delay);
    precise double span = edge_on ? FRAG_MAX_SPAN : ceil(min(gr * q, FRAG_MAX_SPAN));
    if (k < 0.0LF) k = 0.0LF;
    if (k > double(K - 1)) k = double(K - 1);
    int bias = int(min(max(ko - k, 0.0LF), FRAG_MAX_BIAS));
    uint f = off + i;
    fz[f] = float(t);
    fcode[f] = obj | uint(bias) << FRAG_OBJ_BITS | uint(k) << FRAG_SLAB_SHIFT;
    /* surfaces only; a volume's span is 0 */
    uint sp = int(geo[int(obj) * ICS_DEV_GEO_STRIDE + G_VOLBIT]) >= 0 ? 0u : uint(max(span, 0.0LF));
    if (sp != 0u) atomicOr(fspan[f / 4u], sp << (8u * (f % 4u)));
    /* surface_depth_gradient: -n.r / n.f and -n.u / n.f, x 64, rounded, clamped */
    precise double nr = nv.x * cam[CAM_R] + nv.y * cam[CAM_R + 1] + nv.z * cam[CAM_R + 2];
    precise double nu = nv.x * cam[CAM_U] + nv.y * cam[CAM_U + 1] + nv.z * cam[CAM_U + 2];
    precise double nf = nv.x * cam[CAM_F] + nv.y * cam[CAM_F + 1] + nv.z * cam[CAM_F + 2];
    precise double g0 = abs(nf) > 0.0LF ? -nr / nf : 0.0LF, g1 = abs(nf) > 0.0LF ? -nu / nf : 0.0LF;
    precise double s0 = roundEven(max(-32767.0LF, min(32767.0LF, g0 * FRAG_GRAD_SCALE)));
    precise double s1 = roundEven(max(-32767.0LF, min(32767.0LF, g1 * FRAG_GRAD_SCALE)));
    fgrad[f] = vec2(float(s0 / FRAG_GRAD_SCALE), float(s1 / FRAG_GRAD_SCALE));
  }
  uvec2 ins = inside[px];
  pix[px] = uvec4(off, off, ins.x, ins.y);
}
#endif
