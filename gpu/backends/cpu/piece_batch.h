/* piece_batch.h — the commonest volume pieces of a row of light-buffer pixels at one slab, in
 * one call of a vector path (piece_vec.h, one build per instruction set): pixels inside exactly
 * one volume that is no solid, with no fragment in the slab and no surface occlusion due, so
 * that the piece is the whole slab. For each: the light arriving (render.model blocker: blended
 * with the sharp set's by the distance to the blockers), its colour composited into the view
 * pixel (render.model surface on: the piece's own term), and every buffer the piece occludes
 * attenuated (the moment gains the first set's loss). backend_cpu.c's single_volume_piece is the
 * same arithmetic pixel by pixel (the portable path's); here exp, expm1 and log are
 * vec_math.h's, within a few ulps of libm's (docs/renderer.md "Volume pieces in batches"). */
#ifndef ICS_RENDER_PIECE_BATCH_H
#define ICS_RENDER_PIECE_BATCH_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/scene.h"
#include "simd_path.h"

#define ICS_PIECE_MAX_BUFFERS (4 * ICS_SCENE_MAX_LIGHTS)

/* A slab's uniforms for the pieces (backend_cpu.c fills them). */
typedef struct ics_piece_params {
  int nlights, nch, nb;  /* lights, channels, buffered lights (b = set nlights + l) */
  size_t plane;          /* floats between a buffer's channels */
  float *const *dst;     /* per buffered light: the buffers after this slab's step */
  uint8_t attenuates[ICS_PIECE_MAX_BUFFERS]; /* per buffered light: a volume occludes it */
  uint8_t is_moment[ICS_PIECE_MAX_BUFFERS];  /* per buffered light: the blocker moment */
  int own;               /* render.model surface on: the piece's own term */
  int blend;             /* render.model blocker: the first set blended with the sharp set */
  int moment;            /* the moment set is kept */
  int sharp_set;         /* the sharp set's index (the moment set follows it) */
  double lcw[ICS_SCENE_MAX_LIGHTS][3]; /* per light: colour x weight */
  double lpath[ICS_SCENE_MAX_LIGHTS];  /* per light: its path per unit depth */
  double dz, z_light, z_moment;        /* the piece's depth; where the light is read (the slab's
                                          middle) and where the moment gains its loss */
  double z0, K, e;                     /* the slabs' front, count and spacing */
  double d_sharp, d1, blend_span;      /* the blend's ends and log(d1 / d_sharp) */
  float *img;                          /* the view image, RGBA */
} ics_piece_params;

/* A row's pieces, n of them, as arrays (piece i at index i of each). */
typedef struct ics_piece_row {
  int n;
  int64_t *q;    /* the pixel's index in the light buffers */
  int64_t *view; /* its view pixel's index in img (in pixels), or -1: not in view */
  double *sig;   /* the volume's extinction at the piece (> 0) */
  double *dl;    /* the camera path per unit depth */
  double *col[3];  /* the volume's colour there */
  double *keep[3]; /* 1 - the volume's transport colour, per channel */
} ics_piece_row;

/* The pieces of r on vector path simd (not scalar: ics_simd_has must say the processor has it). */
void ics_piece_batch(const ics_piece_params *pp, const ics_piece_row *r, ics_simd_path simd);

/* vec_math.h's functions on path simd (test_render_vec_math): fn 0 exp, 1 expm1, 2 log */
void ics_vec_math(int fn, const double *x, int n, double *out, ics_simd_path simd);

#define ICS_PIECE_BATCH_DECLARE_(isa)                                                              \
  void ics_piece_batch_##isa(const ics_piece_params *pp, const ics_piece_row *r);                \
  void ics_vec_math_##isa(int fn, const double *x, int n, double *out);
ICS_PIECE_BATCH_DECLARE_(sse2)
ICS_PIECE_BATCH_DECLARE_(avx2)
ICS_PIECE_BATCH_DECLARE_(avx512)
ICS_PIECE_BATCH_DECLARE_(neon)
#undef ICS_PIECE_BATCH_DECLARE_

/* What a file builds where the compiler does not target its instruction set. */
#define ICS_PIECE_NOT_BUILT(isa)                                                                   \
  void ics_piece_batch_##isa(const ics_piece_params *pp, const ics_piece_row *r) {               \
    (void)pp, (void)r;                                                                             \
  }                                                                                                \
  void ics_vec_math_##isa(int fn, const double *x, int n, double *out) {                          \
    (void)fn, (void)x, (void)n, (void)out;                                                         \
  }

#endif
