/* geometry.h — ray intersection with the scene's objects, all hits along a ray (the layered
 * depth image needs every crossing, not only the nearest), and object bounding boxes. */
#ifndef ICS_RENDER_GEOMETRY_H
#define ICS_RENDER_GEOMETRY_H

#include "icshadow/scene.h"

/* One crossing: ray parameter and the surface normal there (world frame, not normalised, sign
 * arbitrary: only its direction relative to the view matters, for the surface bias). */
typedef struct ics_hit {
  double t;
  double n[3];
  int seq; /* its position when pushed: the last key of every sort, so orders are total */
} ics_hit;

/* A growable list of crossings. */
typedef struct ics_hits {
  ics_hit *h;
  int n, cap;
} ics_hits;

void ics_hits_free(ics_hits *h);
/* Appends a crossing; -1 when out of memory. */
int ics_hits_push(ics_hits *h, double t, const double n[3]);

/* Appends to *h every crossing of the ray orig + t dir (dir need not be unit) with object o at
 * t > 0, and adds to *behind the number of crossings at t <= 0 (so a closed object whose
 * count is odd contains the ray's origin). Returns 0, or -1 when out of memory. Grazing rays
 * that touch a surface without crossing it may or may not report a pair of equal hits. */
int ics_object_hits(const ics_object *o, const double orig[3], const double dir[3], ics_hits *h,
                    int *behind);

/* The (unnormalised, outward) normal of object o where the ray orig + t dir crosses it nearest
 * t = z, into n: the crossing nearest z among ics_object_hits' (h their scratch; n is 0 where
 * the ray crosses nothing), or for a torus, whose crossings take a root search, the gradient at
 * the ray's point at z (z a crossing already, a fragment's float depth, taken onto the surface
 * by one Newton step). 0, or -1 when out of memory. */
int ics_object_normal_near(const ics_object *o, const double orig[3], const double dir[3], double z,
                           ics_hits *h, double n[3]);

/* World-space axis-aligned bounding box of an object. */
void ics_object_bounds(const ics_object *o, double lo[3], double hi[3]);

/* Orthonormal frame whose third row is the unit vector n (the first row is chosen from `up`
 * when it is given and not parallel to n, else deterministically). */
void ics_frame_from_normal(const double n[3], const double *up, double ax[3][3]);

/* Rotation by rx, then ry, then rz degrees about the world axes applied to the rows of ax. */
void ics_frame_rotate(double ax[3][3], const double rot_deg[3]);

#endif
