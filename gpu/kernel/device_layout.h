/* device_layout.h — the records the host packs for a device (gpu/core/device_scene.c) and the cl
 * and gl programs read (gpu/backends/cl/slab.cl, gpu/backends/gl/slab.comp and ldi.comp, and
 * the shared kernel source beside this file): each offset named once, here. Written in the
 * common subset of C, OpenCL C 1.2 and GLSL 4.50 (#define and comments only); the programs
 * include it (cmake/embed_text.cmake expands the include). test_render_cl and test_render_gl
 * fail when host and device disagree (checked: two fields swapped in the host's packing),
 * test_kernel_c when the shared source reads a record wrongly, kernel_source_once when a
 * program defines an offset of its own. */
#ifndef ICS_DEVICE_LAYOUT_H
#define ICS_DEVICE_LAYOUT_H

/* The camera, ICS_DEV_CAM doubles: eye, r, u, f (3 each), the view's height and width, tan(fov /
 * 2), aspect W / H, projection (1: perspective, 0: orthographic). */
#define ICS_DEV_CAM 17
#define CAM_EYE 0
#define CAM_R 3
#define CAM_U 6
#define CAM_F 9
#define CAM_H 12
#define CAM_W 13
#define CAM_TH 14
#define CAM_ASP 15
#define CAM_PROJ 16

/* An object, ICS_DEV_OBJ_STRIDE doubles: its material, detail and volume bit. */
#define ICS_DEV_OBJ_STRIDE 32
#define O_OPACITY 0
#define O_COLOR 1     /* 3 */
#define O_TRANSPORT 4 /* 3 */
#define O_EXTINCTION 7
#define O_VOLBIT 8 /* its bit in the inside mask, -1 for a surface */
#define O_DETAIL 9 /* 0 none, 1 perlin, 2 fbm, 3 ridged, 4 grid */
#define O_FREQ 10
#define O_LACUNARITY 11
#define O_GAIN 12
#define O_OFFSET 13
#define O_TIME 14
#define O_SCALE 15
#define O_BIAS 16
#define O_OCTAVES 17
#define O_NTRANSFER 18
#define O_TRANSFER 19 /* first row in the transfer table (rows of v, r, g, b, scale) */
#define O_GRID 20     /* grid detail: first cell in the grid table */
#define O_GRID_N 21   /* its cells along x, y, z (3) */
#define O_GRID_LO 24  /* the grid's box: lo (3), hi (3) */
#define O_GRID_HI 27

/* An object's geometry for the gl ray caster, ICS_DEV_GEO_STRIDE doubles. */
#define ICS_DEV_GEO_STRIDE 20
#define G_SHAPE 0      /* ics_shape */
#define G_CENTER 1     /* 3 */
#define G_AXES 4       /* 9: the object's frame, axis i at G_AXES + 3 i */
#define G_HALF 13      /* 3: half sizes (radius, minor radius, ... by shape) */
#define G_VOLBIT 16    /* its bit in the inside mask, -1 for a surface */
#define G_BVH_ROOT 17  /* a mesh: the root of its BVH among all meshes' nodes; else -1 */
#define G_MERGE_EPS 18 /* a mesh: the distance under which crossings merge */

/* The per-pixel tap-set choices (slab_choice.h, ics_slab_pixel_choice): b bits each, b = log2
 * of the candidates where that is a power of two in [2, 256], else 0 (one word scaled per
 * choice); ICS_CHOICE_CHUNKS(b) choices to a 32-bit word. */
#define ICS_CHOICE_CHUNKS(b) ((b) == 0 ? 1 : (b) == 1 ? 32 : (b) == 2 ? 16 : (b) <= 4 ? 8 : 4)

#endif
