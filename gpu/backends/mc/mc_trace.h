/* mc_trace.h — the estimators of the Monte-Carlo reference (backend "mc", docs/reference.md):
 * the scene's semantics (docs/scene-format.md) evaluated without slabs. One sample of a pixel
 * walks its camera ray through every crossing in order: a surface of opacity a and colour c adds
 * beta a c (x) L(p) and leaves beta (1 - a); a volume is crossed by delta tracking against a
 * majorant of its extinction, and a real collision adds beta c(p) (x) L(p) and ends the walk (the
 * transmittance as a probability); what escapes adds beta background. L(p) = sum_k colour_k
 * weight_k T_k(p), where T_k(p) is one sample of the transmittance toward light k: a direction
 * X ~ N(mu_k, Sigma_k) on the virtual light plane, the ray p + t (X_x r + X_y u - f), surfaces
 * passing 1 - a (1 - T_c), volumes exp(-sigma (1 - T_c) length) (exact for constant extinction,
 * ratio tracking through detail). A shadow ray from a surface point that leaves on the far side
 * of that surface (the side the camera ray goes on to) crosses the surface itself and is filtered
 * by it: a surface is lit only from its viewed side (the limit of Patel's slicing). Light enters
 * the scene at the eye plane (depth 0): what lies behind the camera casts no shadow, as in the
 * slab renderer. Every estimator is unbiased for the model's exact value. */
#ifndef ICS_MC_TRACE_H
#define ICS_MC_TRACE_H

#include <stdint.h>

#include "geometry.h"
#include "icshadow/rng.h"
#include "mc_embree.h"
#include "plan_internal.h"

/* What the estimators read, fixed per render. */
typedef struct mc_scene {
  const ics_plan *P;
  const ics_scene *s;
  double *majorant;  /* per object: a bound of its extinction (volumes), 0 for surfaces */
  int vol_obj[ICS_MAX_VOLUMES]; /* the object of each volume bit */
  double root[ICS_SCENE_MAX_LIGHTS][3]; /* per light: Sigma = R R, R symmetric (ra, rb, rd) */
  double eps;        /* crossings at ray parameters <= eps from a ray's origin are its own */
  mc_embree *embree; /* mesh crossings through Embree, or NULL: the renderer's own BVH */
} mc_scene;

/* One crossing of a ray: parameter and object. */
typedef struct mc_cross {
  double t;
  int obj, seq; /* seq: the order found, the sort's last key (a total order) */
  double n[3]; /* the surface normal there (not normalised, sign arbitrary) */
} mc_cross;

/* Per-thread scratch. */
typedef struct mc_thread {
  ics_hits hits;
  mc_cross *x;     /* the last ray's crossings */
  int nx, cap;
  mc_cross *cam;   /* the camera ray's, while light rays use x */
  int camcap;
  mc_embree_scratch esc;
  double deadline; /* ics_clock_s() past which a sample gives up (0: none) */
  unsigned steps;  /* tracking steps taken (the clock is read every 1024) */
  int late;        /* the last failure was the deadline, not memory */
} mc_thread;

/* One sample of one pixel. */
typedef struct mc_sample {
  double rgba[4];
  int surface;                          /* the ray meets a surface (opacity > 0) */
  double z;                             /* its view depth */
  double vis[ICS_SCENE_MAX_LIGHTS][3];  /* the transmittance toward each light there */
} mc_sample;

/* Majorants and light factors for plan P; with embree > 0, Embree's scenes for the meshes (when
 * the scene has any), built on `embree` threads. ICS_ERR_NOMEM, or mc_embree_create's error
 * with msg. */
ics_status mc_scene_init(mc_scene *m, const ics_plan *P, int embree, char *msg, size_t msg_size);
void mc_scene_release(mc_scene *m);
void mc_thread_release(mc_thread *th);

/* A bound of the tracking steps of one ray through the volumes with detail: the sum of majorant
 * x the diagonal of each one's bounding box (no chord inside it is longer); the work estimate of
 * a sample (infinite or huge for extinctions no render can finish). */
double mc_steps_per_ray(const mc_scene *m);

/* The crossings of orig + t dir with t > tmin, sorted by t, in th->x (th->nx); *inside gets the
 * volumes (bits of P->vol_bit) containing orig + tmin dir by parity. -1 when out of memory. */
int mc_crossings(mc_thread *th, const mc_scene *m, const double orig[3], const double dir[3],
                 double tmin, uint64_t *inside);

/* The surface a shading point lies on, seen along the camera direction d. */
typedef struct mc_surface {
  const double *n, *d;
  const ics_material *mat;
} mc_surface;

/* One sample of the transmittance toward light l from p, per channel (the volumes around p from
 * the ray's own crossings); own: the surface p lies on (NULL for a point in a volume). -1 when out
 * of memory, or past th->deadline (th->late set). */
int mc_light_transmittance(mc_thread *th, const mc_scene *m, int l, const double p[3],
                           const mc_surface *own, ics_rng *r, double T[3]);

/* One sample of view pixel (i, j): the first surface (opacity > 0) and its depth always;
 * want_vis: also its transmittances (even where the walk ended in a volume in front of it).
 * -1 when out of memory, or past th->deadline (th->late set: checked at the start and every 1024
 * tracking steps, so a deadline stops a sample within microseconds, however dense the volume). */
int mc_pixel_sample(mc_thread *th, const mc_scene *m, int i, int j, int want_vis, ics_rng *r,
                    mc_sample *out);

#endif
