/* device_scene.h — the plan flattened for a device (the cl and gl backends): the layered depth
 * image as arrays, the objects as records of ICS_DEV_OBJ_STRIDE doubles (the O_* offsets of
 * device_layout.h), their transfer rows, noise permutations and grid cells,
 * the camera and the lights. Built on the host once per render (device_scene.c). */
#ifndef ICS_RENDER_DEVICE_SCENE_H
#define ICS_RENDER_DEVICE_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "kernel/device_layout.h"
#include "plan_internal.h"


typedef struct ics_device_scene {
  size_t nfrag, nobj, ntt, ncells; /* each at least 1, so no array is empty */
  float *fz;                       /* per fragment: depth */
  uint32_t *fcode;                 /*   object | bias << 12 | slab << 16 */
  float *fgrad;                    /*   2 each: dz/dr, dz/du (exact: int16 / 64) */
  uint8_t *fspan;                  /*   span in slabs */
  double *obj;                     /* nobj records */
  double *tt;                      /* transfer rows: v, r, g, b, scale */
  uint8_t *perm;                   /* 512 per object */
  float *grids;                    /* grid detail cells, all objects */
  uint64_t *inside;                /* Wb Hb inside masks; NULL without volumes */
  double cam[ICS_DEV_CAM];
  double lcol[3 * ICS_SCENE_MAX_LIGHTS]; /* colour x weight */
  double lmu[2 * ICS_SCENE_MAX_LIGHTS];  /* mean direction */
  double blur[ICS_SCENE_MAX_LIGHTS];     /* ics_plan_light_blur */
  int32_t signed_l[ICS_SCENE_MAX_LIGHTS]; /* 1: signed weights (clamped after each slab) */
  int32_t vol_obj[ICS_MAX_VOLUMES];      /* the object of each volume bit */
} ics_device_scene;

/* The objects' geometry for a device's ray caster (gpu/backends/gl/ldi.comp): per object
 * ICS_DEV_GEO_STRIDE doubles (shape, centre, frame rows, half sizes, volume bit, the root of
 * its mesh's BVH or -1, the mesh's merge distance), and every mesh's BVH flattened
 * (ics_mesh_flatten: nodes' boxes and links, triangles in leaf order). */
typedef struct ics_device_geometry {
  size_t nobj, nnodes, ntris; /* each at least 1 */
  double *geo;
  double *node_box;   /* 6 per node */
  int32_t *node_link; /* 4 per node */
  double *tris;       /* 9 per triangle */
} ics_device_geometry;

/* ICS_OK or ICS_ERR_NOMEM (what is made so far released). fragments 0: the layered depth
 * image's arrays (fz .. fspan, inside) are left at one zeroed entry, for a device that builds
 * its own (gpu/backends/gl/ldi_gl.c). */
ics_status ics_device_scene_create(ics_device_scene *d, const ics_plan *p, int fragments);
void ics_device_scene_destroy(ics_device_scene *d); /* a zeroed one is fine */
/* The camera as ics_plan_ray uses it: eye, r, u, f, height, width, tan(fov / 2), aspect,
 * perspective (1) or orthographic (0). */
void ics_device_camera(const ics_plan *p, double cam[ICS_DEV_CAM]);
ics_status ics_device_geometry_create(ics_device_geometry *g, const ics_plan *p);
void ics_device_geometry_destroy(ics_device_geometry *g); /* a zeroed one is fine */

#endif
