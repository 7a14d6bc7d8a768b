/* plan_internal.h — the plan behind the opaque ics_plan, as the backends read it: buffer
 * geometry, the layered depth image, slabs, per-light kernels, per-object volume bits, detail
 * evaluators. Written once by ics_plan_create, read-only afterwards (backends may render the same
 * plan from several threads). */
#ifndef ICS_RENDER_PLAN_INTERNAL_H
#define ICS_RENDER_PLAN_INTERNAL_H

#include <stdint.h>

#include "kernel/device_layout.h"

#include "active_region.h"
#include "tile_grid.h"
#include "detail.h"
#include "slab_taps.h"
#include "icshadow/image.h"
#include "icshadow/plan.h"
#include "slab_kernel.h"

#define ICS_MAX_VOLUMES 64 /* volumetric and solid objects: one bit each in a per-pixel inside mask */
#define ICS_FRAG_OBJ_BITS 12  /* object index */
#define ICS_FRAG_BIAS_BITS 4  /* surface bias in slabs */
#define ICS_FRAG_MAX_BIAS 15
#define ICS_FRAG_SLAB_SHIFT (ICS_FRAG_OBJ_BITS + ICS_FRAG_BIAS_BITS)
#define ICS_FRAG_MAX_SLABS (1 << (32 - ICS_FRAG_SLAB_SHIFT))

#define ICS_FRAG_MAX_SPAN 255

/* One crossing of a buffer pixel's camera ray: depth, (object | bias << 12 | slab << 16), and
 * for a surface its depth gradient and the span: its depth change over one pixel in slabs
 * (rounded up), from which the backend draws the window of slabs, from slab + bias on, in which it
 * occludes (docs/renderer.md "Surface bias"). */
typedef struct ics_fragment {
  float z;
  uint32_t code;
  int16_t grad[2]; /* surfaces: the depth gradient along r and u (dz/dr, dz/du), x 64 (clamped) */
  uint8_t span;
} ics_fragment;
#define ICS_FRAG_GRAD_SCALE 64.0

static inline uint32_t ics_frag_code(int obj, int bias, int slab) {
  return (uint32_t)obj | (uint32_t)bias << ICS_FRAG_OBJ_BITS | (uint32_t)slab << ICS_FRAG_SLAB_SHIFT;
}
static inline int ics_frag_obj(const ics_fragment *f) {
  return (int)(f->code & ((1u << ICS_FRAG_OBJ_BITS) - 1));
}
static inline int ics_frag_bias(const ics_fragment *f) {
  return (int)(f->code >> ICS_FRAG_OBJ_BITS & ((1u << ICS_FRAG_BIAS_BITS) - 1));
}
static inline int ics_frag_slab(const ics_fragment *f) { return (int)(f->code >> ICS_FRAG_SLAB_SHIFT); }

typedef struct ics_ldi {
  int w, h;            /* the buffer grid */
  uint32_t *offset;    /* w h + 1: pixel p's fragments are frag[offset[p] .. offset[p + 1]) */
  ics_fragment *frag;
  uint64_t *inside0;   /* per pixel: volumes containing the ray's origin (NULL: none anywhere) */
  int max_layers;
  size_t nfrag;
} ics_ldi;

struct ics_plan {
  const ics_scene *scene;
  ics_render_settings rs; /* the settings in force (scene's or overridden; render.model auto
                             resolved to blocker) */
  int model_auto;         /* render.model was auto: a backend without blocker renders patel */
  int auto_capped;        /* auto took patel for more volumes and solids than the inside mask's
                             bits (not for the backend) */
  int over_cost;          /* refused for its memory or work, which a cheaper model may fit */
  int kernels_kept;       /* slab kernels copied from the renderer's last plan (kernel_cache.h) */
  ics_camera cam;         /* the camera in force (resolution overridden) */
  double tan_half_fov;    /* perspective: tan(fov / 2), computed once (every ray takes it) */
  double cam_rec[ICS_DEV_CAM]; /* the camera record (kernel/device_layout.h) rays are cast from */
  int W, H;               /* image */
  int Wb, Hb;             /* light buffers = LDI grid */
  int pad[4];             /* left, right, top, bottom */
  double cx, cy;          /* principal point in buffer pixel-index coordinates */
  double z0, e;           /* slab k covers [z0 + k e, z0 + (k + 1) e) */
  int K;                  /* slabs */
  double q_ref;           /* pixel size at the reference depth (orthographic: the pixel size) */
  int nch;                /* channels per light buffer: 1 (grey transport) or 3 */
  ics_buf_layout buf;     /* the light buffers' storage: Wb x Hb with an apron (propagate.h) */
  int nlights;
  ics_slab_kernel *kernels; /* nlights */
  ics_slab_kernel *kernels_sharp; /* render.model blocker: nlights, at d1 x ICS_BLOCKER_SHARP */
  int nvol;               /* volumetric objects */
  int *vol_bit;           /* per object: its bit among the volumes, or -1 (what the Monte-Carlo
                             reference tracks) */
  int ninside;            /* objects the slab renderer's per-pixel inside mask tracks */
  int *inside_bit;        /* per object: its bit in that mask, or -1: the volumes' bits, then,
                             with render.model solid or surface, the solid objects' */
  uint64_t solid_bits;    /* the bits of solid objects (closed, opaque surfaces) */
  uint64_t *own_lights;   /* per object: the lights (bit l) whose buffers leave it out, an open
                             surface lit by its own term (render.model surface; own_term.h) */
  int own_any;            /* some object has own_lights */
  int any_detail;
  ics_detail_eval *detail; /* per object with a detail material (NULL otherwise) */
  double light_path[ICS_SCENE_MAX_LIGHTS]; /* sqrt(1 + |mu_k|^2): light path per unit depth */
  ics_ldi ldi;
  ics_rect *active;       /* K x nlights: the part of each light buffer a slab propagates
                             (active_region.h), slab-major */
  ics_tile_grid tiles;    /* the light buffers' tiles */
  int32_t *tile_last;     /* sets x nlights x tiles: the last slab at which buffered light
                             b = set nlights + l needs a tile */
  int32_t *tile_shade;    /* tiles: the last slab at which a tile is shaded */
  double active_fraction[ICS_SCENE_MAX_LIGHTS]; /* per light: the regions' area over K buffers */
  double geometry_s;
  int npasses, nomitted;
  ics_plan_pass passes[ICS_SCENE_MAX_LIGHTS + 8];
  ics_plan_omitted omitted[ICS_SCENE_MAX_LIGHTS + 8];
  size_t memory_bytes;
  size_t backend_bytes;   /* what a backend allocates per render (buffers, state, image) */
};

/* The camera ray of buffer pixel (bi, bj) (origin, direction with direction . forward = 1, so
 * the ray parameter is the depth). */
void ics_plan_ray(const ics_plan *p, int bi, int bj, double o[3], double d[3]);
/* Pixel size (world units) at depth z. */
double ics_plan_pixel_size(const ics_plan *p, double z);
/* The per-slab blur of light l: the largest standard deviation (world units) of the per-slab
 * covariance d1 e Sigma_l. */
double ics_plan_light_blur(const ics_plan *p, int l);
/* Depth of slab k's light plane (its middle). */
double ics_plan_slab_depth(const ics_plan *p, int k);
/* What every slab renderer does per slab, in one place: the pixel size of slab k (*mag: its
 * magnification over slab k - 1, 1 for orthographic cameras and k = 0); the surface windows'
 * reach over all slabs (the largest 1 - blur_l / q, q of the deepest slab); light l's taps of
 * slab k prepared for the step (ics_slab_kernel_taps, then ics_prop_prepare or
 * _perspective, and the table-choice fields): ICS_OK, the taps' error with msg ("light L, slab
 * K: kernel taps: ..."), or ICS_ERR_NOMEM without msg when they cannot be prepared (cum: the
 * light's integer-shift schedule state, scratch: sk->entries * sk->cap taps); and the image's
 * RGB over the background by its accumulated alpha. */
double ics_plan_slab_pixel(const ics_plan *p, int k, double *mag);
/* The light-buffer sets a slab renderer keeps per light, in this order (buffered light
 * b = set nlights + l): the first, which lights everything else; Patel's, with render.model
 * surface and after on a scene with solid objects (surfaces occlude at their fragments, no
 * solid interiors), which lights the solids' own surfaces; and with render.model blocker the
 * first set again at d1 x ICS_BLOCKER_SHARP (kernels_sharp), and the blocker moment: the
 * light the first set lost at each occlusion times its depth, (z - z0) / (K e) in [0, 1],
 * summed and propagated with the first set's taps, so moment / (1 - V) is the mean depth of a
 * receiver's blockers (docs/renderer.md "Models"). */
typedef enum { ICS_SET_FIRST, ICS_SET_PATEL, ICS_SET_SHARP, ICS_SET_MOMENT } ics_set_role;
#define ICS_BLOCKER_SHARP 0.25
int ics_plan_light_sets(const ics_plan *p);
ics_set_role ics_plan_set_role(const ics_plan *p, int set);
/* the channels of a set's buffers: the plan's nch, the moment's 1 (it is grey: only one is read) */
int ics_plan_set_channels(const ics_plan *p, int set);
/* The kernel of buffered light b's set (the sharp set's, or light l's) */
const ics_slab_kernel *ics_plan_set_kernel(const ics_plan *p, int b);
double ics_plan_window_max(const ics_plan *p);
ics_status ics_plan_slab_taps(const ics_plan *p, int l, int k, double q, double mag,
                              double cum[2], ics_tap2d *scratch, ics_prop_taps *pt, char *msg,
                              size_t msg_size);
/* The same with kernel sk (light l's, or its sharp set's) */
ics_status ics_plan_kernel_taps(const ics_plan *p, const ics_slab_kernel *sk, int l, int k,
                                double q, double mag, double cum[2], ics_tap2d *scratch,
                                ics_prop_taps *pt, char *msg, size_t msg_size);
/* The same, but with a perspective camera and deferred != NULL the classes' compensations are
 * left to the caller (*deferred: the slab's tap count in scratch; the caller runs
 * ics_prop_perspective_classes over every class, then ics_prop_perspective_end), so that they
 * can run on several threads; *deferred is left alone otherwise. */
ics_status ics_plan_kernel_taps_deferred(const ics_plan *p, const ics_slab_kernel *sk, int l, int k,
                                         double q, double mag, double cum[2], ics_tap2d *scratch,
                                         ics_prop_taps *pt, int *deferred, char *msg,
                                         size_t msg_size);
void ics_plan_over_background(const ics_plan *p, ics_image *img);

/* Builds the LDI over the plan's buffer grid (geometry pass; ldi.c). */
ics_status ics_ldi_build(ics_plan *p, int threads, char *msg, size_t msg_size);
void ics_ldi_release(ics_ldi *l);
/* How far one slab's kernel reaches laterally (world units; the surface bias's scale). */
double ics_ldi_kernel_reach(const ics_plan *p);

#endif
