/* mesh.h — triangle meshes for the renderer: loading through Assimp (optional: PLY, OBJ, glTF,
 * ...), a bounding-volume hierarchy, every crossing of a ray, and a closedness test (every edge
 * shared by exactly two triangles), since only closed meshes bound volumes. */
#ifndef ICS_RENDER_MESH_H
#define ICS_RENDER_MESH_H

#include <stddef.h>

#include "geometry.h"
#include "icshadow/status.h"

#define ICS_MESH_MAX_TRIANGLES 50000000

/* Loads every mesh of the file as one triangle soup (Assimp: triangulated, identical vertices
 * joined), applies v' = R (s * v) + translate (R: rotations about x, then y, then z in degrees).
 * ICS_ERR_UNSUPPORTED without Assimp at build time, ICS_ERR_IO / ICS_ERR_PARSE with Assimp's
 * reason in msg, ICS_ERR_SIZE for no or too many triangles, ICS_ERR_NOMEM. */
ics_status ics_mesh_create_file(ics_mesh **out, const char *path, const double scale[3],
                                const double rot_deg[3], const double translate[3], char *msg,
                                size_t msg_size);
/* From vertex positions (x, y, z per vertex) and triangles (3 vertex indices each); copied. */
ics_status ics_mesh_create_triangles(ics_mesh **out, const double *xyz, int nverts,
                                     const int *tri, int ntris);
void ics_mesh_destroy(ics_mesh *m);

int ics_mesh_closed(const ics_mesh *m);
int ics_mesh_triangle_count(const ics_mesh *m);
size_t ics_mesh_bytes(const ics_mesh *m); /* memory held (vertices, triangles, BVH) */
void ics_mesh_bounds(const ics_mesh *m, double lo[3], double hi[3]);
/* As ics_object_hits (geometry.h); coincident crossings (a ray through an edge shared by two
 * triangles) are reported once. */
int ics_mesh_hits(const ics_mesh *m, const double orig[3], const double dir[3], ics_hits *h,
                  int *behind);
/* For another accelerator (the Monte-Carlo reference's Embree path, reference/mc_embree.c):
 * triangle k's vertices (k in 0..count-1, the order of ics_mesh_create_triangles), and the
 * crossings of the line orig + t dir with the listed triangles, which the accelerator found the
 * line to pass through: t and normal computed as ics_mesh_hits computes them (double precision,
 * without a second inside test), then sorted, merged and counted the same way (a triangle listed
 * twice merges with itself). */
void ics_mesh_triangle(const ics_mesh *m, int k, double v[3][3]);
int ics_mesh_hits_of(const ics_mesh *m, const int *tris, int ntris, const double orig[3],
                     const double dir[3], ics_hits *h, int *behind);
/* 1 when the library was built with Assimp. */
int ics_mesh_files_supported(void);

#endif
