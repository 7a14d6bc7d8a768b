/* mesh.h — triangle meshes for the renderer: loading through Assimp (optional: PLY, OBJ, glTF,
 * ...; mesh_import.c), a bounding-volume hierarchy, every crossing of a ray, and a closedness
 * test (every edge shared by exactly two triangles), since only closed meshes bound volumes. */
#ifndef ICS_RENDER_MESH_H
#define ICS_RENDER_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "geometry.h"
#include "icshadow/status.h"

#define ICS_MESH_MAX_TRIANGLES 50000000

/* Loads every mesh of the file as one triangle soup (Assimp: triangulated, identical vertices
 * joined), applies v' = R (s * v) + translate (R: rotations about x, then y, then z in degrees).
 * Assimp runs in a child process (mesh_import.c), so a reader that crashes or does not finish
 * within `seconds` (0: 60 s + 2 s per MiB of file) is an error, not a crash or a hang.
 * Every file Assimp opens (the mesh, a glTF's buffers, an OBJ's materials) must be a regular
 * file; with files non-NULL, *files receives the others' names (malloc'd, each NUL-terminated,
 * the list ended by an empty name; free() it), for the scene's inputs.
 * ICS_ERR_UNSUPPORTED without Assimp at build time, ICS_ERR_IO (cannot open, a file that is not a
 * regular file, cannot start the reader) / ICS_ERR_PARSE (Assimp's reason, its crash or time-out)
 * in msg, ICS_ERR_SIZE for no or too many triangles, ICS_ERR_NOMEM. */
ics_status ics_mesh_create_file(ics_mesh **out, const char *path, const double scale[3],
                                const double rot_deg[3], const double translate[3],
                                double seconds, char **files, char *msg, size_t msg_size);
/* The same in two steps, so a file referenced by several objects is read once: the file as
 * Assimp gives it (vertices as floats, triangles as vertex indices, -1 for one out of range; the
 * other files read, as for `files` above; errors as above; with root non-NULL every file Assimp
 * opens must lie in that folder or below it, path_inside.h, else ICS_ERR_IO naming it), then a
 * mesh from it under a transform. */
typedef struct ics_mesh_raw {
  float *v;
  int *tri;
  uint64_t nv, nt;
  char *files;
} ics_mesh_raw;
ics_status ics_mesh_read_file(ics_mesh_raw *raw, const char *path, double seconds,
                              const char *root, char *msg, size_t msg_size);
/* The faces a PLY file's header declares ("element face N"; 0 for another format, a header
 * without one, or a file that cannot be opened): each face becomes at least one triangle, so a
 * mesh's size is bounded below before Assimp reads it (ics_mesh_bytes_min). */
uint64_t ics_mesh_file_faces(const char *path);
ics_status ics_mesh_create_raw(ics_mesh **out, const ics_mesh_raw *raw, const double scale[3],
                               const double rot_deg[3], const double translate[3],
                               const char *path, char *msg, size_t msg_size);
void ics_mesh_raw_release(ics_mesh_raw *raw);
/* From vertex positions (x, y, z per vertex) and triangles (3 vertex indices each); copied. */
ics_status ics_mesh_create_triangles(ics_mesh **out, const double *xyz, int nverts,
                                     const int *tri, int ntris);
void ics_mesh_destroy(ics_mesh *m);

int ics_mesh_closed(const ics_mesh *m);
int ics_mesh_triangle_count(const ics_mesh *m);
size_t ics_mesh_bytes(const ics_mesh *m); /* memory held (vertices, triangles, BVH) */
/* A lower bound of ics_mesh_bytes for a mesh of ntris triangles (its triangles and their order,
 * without the hierarchy's nodes). */
double ics_mesh_bytes_min(uint64_t ntris);
void ics_mesh_bounds(const ics_mesh *m, double lo[3], double hi[3]);
/* As ics_object_hits (geometry.h); coincident crossings (a ray through an edge shared by two
 * triangles) are reported once. */
int ics_mesh_hits(const ics_mesh *m, const double orig[3], const double dir[3], ics_hits *h,
                  int *behind);
/* For another accelerator (the Monte-Carlo reference's Embree path, gpu/backends/mc/mc_embree.c):
 * triangle k's vertices (k in 0..count-1, the order of ics_mesh_create_triangles), and the
 * crossings of the line orig + t dir with the listed triangles, which the accelerator found the
 * line to pass through: t and normal computed as ics_mesh_hits computes them (double precision,
 * without a second inside test), then sorted, merged and counted the same way (a triangle listed
 * twice merges with itself). */
void ics_mesh_triangle(const ics_mesh *m, int k, double v[3][3]);
int ics_mesh_hits_of(const ics_mesh *m, const int *tris, int ntris, const double orig[3],
                     const double dir[3], ics_hits *h, int *behind);
/* For a device's ray caster (gpu/backends/gl/ldi.comp): the BVH as flat arrays. ics_mesh_flat_counts
 * gives the node and triangle counts; ics_mesh_flatten writes per node lo, hi (6 doubles) and
 * left, right, first, count (4 ints: children offset by node_base, -1 for a leaf; first offset
 * by tri_base), per triangle v0, e1, e2 (9 doubles) in leaf order, so that a leaf's triangles
 * are first .. first + count - 1 and a traversal pushes crossings in ics_mesh_hits's order. */
void ics_mesh_flat_counts(const ics_mesh *m, int *nnodes, int *ntris);
void ics_mesh_flatten(const ics_mesh *m, int node_base, int tri_base, double *node_box,
                      int32_t *node_links, double *tris);
/* The distance below which two crossings merge (1e-9 of the mesh's diagonal). */
double ics_mesh_merge_eps(const ics_mesh *m);
/* 1 when the library was built with Assimp. */
int ics_mesh_files_supported(void);

#endif
