/* icshadow/scene.h — the scene model of the slab renderer (libicshadow_render): camera, render
 * settings, Gaussian lights on the camera's virtual light plane, materials, objects. A scene is
 * read from a JSON file (docs/scene-format.md) or built in: ics_scene_create_default is the
 * embedded default scene (an object with procedural detail over a floor and a wall, two coloured
 * lights). The model is read-only once created; its parts are plain structs so that tests and
 * tools can inspect every field.
 *
 * Frames (docs/renderer.md): view space x = camera right, y = camera up, the camera looks along
 * -z; depth z = (p - eye) . forward > 0. Light means are (tan wx, tan wy) along right and up. */
#ifndef ICSHADOW_SCENE_H
#define ICSHADOW_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/api.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_SCENE_MAX_RES 16384      /* per image axis */
#define ICS_SCENE_MAX_LIGHTS 64
#define ICS_SCENE_MAX_OBJECTS 4096   /* after fences are expanded into boxes */
#define ICS_SCENE_MAX_MATERIALS 256
#define ICS_SCENE_MAX_TRANSFER 256   /* transfer-function nodes */
/* a material's colour (or transfer colour) x the lights' weight x colour summed: the largest
 * value an image can take, kept far below float's 3.4e38 */
#define ICS_SCENE_MAX_RADIANCE 1e30
/* the extinction a volume can reach per world unit (its extinction x the largest extinction
 * scale its detail and transfer function give): 64 overlapping volumes at it, times a colour
 * and a path length, stay finite doubles */
#define ICS_SCENE_MAX_EXTINCTION 1e100
/* bytes of a scene file: the largest scene within the limits above (256 materials of 256
 * transfer nodes, 4096 objects) is a few MiB; parsing holds about 80 bytes per byte of JSON */
#define ICS_SCENE_FILE_MAX (16u << 20)

typedef enum ics_projection { ICS_PROJ_ORTHOGRAPHIC = 0, ICS_PROJ_PERSPECTIVE = 1 } ics_projection;

typedef struct ics_camera {
  ics_projection projection;
  double eye[3], target[3], up[3];
  double height;  /* orthographic: world extent of the vertical image side */
  double fov_deg; /* perspective: vertical field of view */
  int width, height_px;
  /* derived: orthonormal right, up, forward (unit vectors) */
  double r[3], u[3], f[3];
} ics_camera;

typedef enum ics_render_kernel {
  ICS_RK_ELLIPSE = 0, /* Patel's elliptical kernel, random offset per slab and pixel */
  ICS_RK_POISSON,     /* whitened Poisson-disk pattern, random rotation per slab and pixel */
  ICS_RK_GAUSS,       /* N x N Gaussian grid, deterministic */
  ICS_RK_TOPHAT,      /* N x N uniform grid in the whitened frame, deterministic */
  ICS_RK_COUNT_
} ics_render_kernel;

typedef enum ics_render_comp {
  ICS_RC_DEFAULT = 0, /* expected for ellipse / poisson, nonneg for gauss / tophat */
  ICS_RC_EXPECTED,    /* subtract the expected interpolation covariance from the class */
  ICS_RC_INTEGER,     /* integer-shift schedule + exact integer taps (deterministic) */
  ICS_RC_NONNEG,      /* the core's compensation of per-slab taps (non-negative weights) */
  ICS_RC_SIGNED,      /* the core's compensation, signed weights when needed */
  ICS_RC_NONE,        /* taps as they are */
  ICS_RC_COUNT_
} ics_render_comp;

/* The slab renderer's model of light transport (docs/renderer.md "Models"): each model adds one
 * step to the previous; "patel" is Patel et al.'s slicing exactly as before this option. */
typedef enum ics_render_model {
  ICS_MODEL_PATEL = 0, /* surfaces occlude at their fragments (slicing) */
  ICS_MODEL_SOLID,     /* + closed opaque objects are solid: no light inside them */
  ICS_MODEL_SURFACE,   /* + a surface's own term in closed form (the light on its lit side) */
  ICS_MODEL_BLOCKER,   /* + blocker-aware penumbrae: a sharper light-buffer set blended in by
                          each receiver's distance to its blockers */
  ICS_MODEL_AUTO,      /* the closest model the backend renders (ics_plan_opts.renderer's; none:
                          blocker): blocker on cpu, patel on cl, gl and mc, patel beyond 64
                          volumes and solids (the default; docs/renderer.md "Which model") */
  ICS_MODEL_COUNT_
} ics_render_model;

typedef struct ics_render_settings {
  double slab_spacing; /* e > 0 */
  double d1;           /* optimal distance > 0 */
  ics_render_kernel kernel;
  int samples;         /* 0 = the member's default */
  ics_render_comp compensate;
  int lut_radii;       /* 1: ellipse radii from the built-in LUT; 0: exact */
  int preintegrate;    /* 1: detail sampled at both ends of each volume piece, the transfer
                          function integrated between them (Engel 2001; Patel Fig. 19) */
  int pixel_rotations; /* ellipse / poisson: rotations a pixel chooses from per slab (1, 2, 4, 8
                          or 384; default 2) */
  int rotation_run;    /* 1: every pixel chooses; 16: runs of 16 pixels of a row share a choice
                          (their start moved by a random phase each slab) */
  ics_render_model model; /* a scene's default ICS_MODEL_AUTO (ics_plan_create resolves it); a
                             zeroed struct says ICS_MODEL_PATEL */
  int dense;           /* 1: every light-buffer pixel propagated at every slab (the reference the
                          skipping is tested against); 0 (default): only the active regions, with
                          constant tiles skipped (docs/renderer.md "Work a frame does not need") */
  uint64_t seed;
  double background[3];
  int max_pad;         /* < 0: default (larger image side) */
  double memory_limit_mib;
} ics_render_settings;

typedef enum ics_detail_fn {
  ICS_DETAIL_NONE = 0,
  ICS_DETAIL_PERLIN,
  ICS_DETAIL_FBM,
  ICS_DETAIL_RIDGED,
  ICS_DETAIL_GRID
} ics_detail_fn;

typedef struct ics_detail {
  ics_detail_fn fn;
  double frequency, lacunarity, gain, offset, time, scale, bias;
  int octaves;
  uint64_t seed;
  /* grid: nx * ny * nz floats, x fastest, mapped onto the object's bounding box */
  int size[3];
  float *grid; /* owned by the scene; NULL where no object uses the material (never read) */
} ics_detail;

typedef struct ics_material {
  char name[64];
  double color[3];
  int volumetric;    /* 1: extinction (per world unit); 0: surface opacity */
  double opacity;    /* surfaces */
  double extinction; /* volumes */
  double transport[3];
  ics_detail detail;
  int ntransfer;     /* 0: colour = color, extinction scale = max(v, 0) */
  double transfer[ICS_SCENE_MAX_TRANSFER][5]; /* v, r, g, b, extinction scale; v increasing */
} ics_material;

typedef enum ics_shape {
  ICS_SHAPE_RECT = 0,
  ICS_SHAPE_DISK,
  ICS_SHAPE_BOX,
  ICS_SHAPE_SPHERE,
  ICS_SHAPE_TORUS,
  ICS_SHAPE_MESH,
  ICS_SHAPE_COUNT_
} ics_shape;

typedef struct ics_mesh ics_mesh; /* triangles + BVH (owned by the scene) */

/* One object. Fences are expanded into boxes when read (object `source` keeps the JSON index).
 * Boxes, rects and disks carry an orthonormal frame ax[0..2] (rect/disk: ax[2] = normal). */
typedef struct ics_object {
  ics_shape shape;
  int material;   /* index into the materials */
  int closed;     /* bounds a volume (parity) */
  int source;     /* index of the object in the scene file's "objects" array */
  double center[3];
  double ax[3][3]; /* local frame: rows are the unit axes */
  double half[3];  /* rect: half sizes (x, y); box: half sizes; disk/sphere: radius in [0];
                      torus: major radius in [0], minor in [1] */
  const ics_mesh *mesh;
} ics_object;

typedef struct ics_scene ics_scene;

/* How a scene is read; a zero-initialised struct (or NULL) is the default. */
typedef struct ics_scene_opts {
  /* Every file a scene reads (lights_file, grid and mesh files, and the files a mesh file
   * names: a glTF's buffers, an OBJ's materials) must lie in the scene's folder or below it,
   * symbolic links resolved; 1 allows files anywhere (docs/scene-format.md "Files"). */
  int allow_outside_paths;
  /* NULL, or a JSON object whose members replace or add to the scene's "render" object before it
   * is read ({"model": "solid", "samples": 4}): checked as the scene's own keys are, a bad one
   * named "PATH: render.KEY: reason"; a text that is not a JSON object is refused as
   * "render overrides: reason" (ICS_ERR_PARSE). */
  const char *render_json;
} ics_scene_opts;

/* Reads a scene file. On failure *out is NULL and msg (when non-NULL) holds one line naming the
 * problem: "PATH:LINE:COLUMN: reason" for JSON syntax, "PATH: objects[1].radius: reason" for
 * content. ICS_ERR_IO (cannot read), ICS_ERR_PARSE (syntax, unknown key, wrong type),
 * ICS_ERR_RANGE / ICS_ERR_NEGATIVE_VARIANCE / ICS_ERR_NAN (values), ICS_ERR_UNSUPPORTED (mesh
 * files without Assimp), ICS_ERR_INVALID_ARG (a file outside the scene's folder), ICS_ERR_NOMEM. */
ICS_API ics_status ics_scene_create_file(ics_scene **out, const char *path, char *msg,
                                         size_t msg_size);
/* The same with options (NULL: the defaults). */
ICS_API ics_status ics_scene_create_file_opts(ics_scene **out, const char *path,
                                              const ics_scene_opts *opts, char *msg,
                                              size_t msg_size);
/* The same from a JSON text; `name` stands for the file in messages, `dir` (may be NULL: the
 * working directory) resolves relative paths (lights_file, mesh and grid files) and is the
 * folder they must lie in (ics_scene_opts; _opts: with options). Mesh files are
 * read by Assimp in a child process (fork): the caller must not ignore SIGCHLD or reap children
 * it did not start, and should read scenes before starting threads that may hold the C or C++
 * runtime's locks. */
ICS_API ics_status ics_scene_create_json(ics_scene **out, const char *json, const char *name,
                                         const char *dir, char *msg, size_t msg_size);
ICS_API ics_status ics_scene_create_json_opts(ics_scene **out, const char *json,
                                              const char *name, const char *dir,
                                              const ics_scene_opts *opts, char *msg,
                                              size_t msg_size);
/* The embedded default scene (docs/scene-format.md "The default scene"), and its text. */
ICS_API ics_status ics_scene_create_default(ics_scene **out);
ICS_API const char *ics_scene_default_json(void);
ICS_API void ics_scene_destroy(ics_scene *s); /* NULL is allowed */

ICS_API const ics_camera *ics_scene_camera(const ics_scene *s);
ICS_API const ics_render_settings *ics_scene_settings(const ics_scene *s);
ICS_API int ics_scene_light_count(const ics_scene *s);
ICS_API const ics_light *ics_scene_light(const ics_scene *s, int k);
ICS_API int ics_scene_material_count(const ics_scene *s);
ICS_API const ics_material *ics_scene_material(const ics_scene *s, int k);
ICS_API int ics_scene_object_count(const ics_scene *s);
ICS_API const ics_object *ics_scene_object(const ics_scene *s, int k);
/* The file name given at creation ("default" for the embedded scene). */
ICS_API const char *ics_scene_name(const ics_scene *s);
/* The files the scene was read from, k = 0 .. count - 1: the scene file itself (when created
 * from one), then its lights_file, grid and mesh files in the order read, as the paths that were
 * opened (relative ones joined to the scene's folder). A caller writing outputs checks them
 * against these, so that no output replaces an input. */
ICS_API int ics_scene_file_count(const ics_scene *s);
ICS_API const char *ics_scene_file(const ics_scene *s, int k);

/* Names used in scene files and plans: "ellipse", "poisson", "gauss", "tophat";
 * "expected", "integer", "nonneg", "signed", "none"; "rect", "disk", ... NULL out of range. */
ICS_API const char *ics_render_kernel_name(ics_render_kernel k);
ICS_API const char *ics_render_comp_name(ics_render_comp c);
ICS_API const char *ics_render_model_name(ics_render_model m); /* "patel", "solid", "surface" */
ICS_API const char *ics_shape_name(ics_shape s);

#ifdef __cplusplus
}
#endif
#endif
