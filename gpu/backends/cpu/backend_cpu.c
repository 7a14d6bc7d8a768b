/* backend_cpu.c — the CPU backend: Patel Sec. 4.2 per slab and pixel (docs/renderer.md),
 * threads taking rows of tiles (tiles.h) in turn, one barrier per slab. Per slab and row of
 * tiles, every light buffer is first propagated (propagate.c) over the tiles of its active region
 * (active_region.h) that a constant does not fill (tiles.h), then the pixels are shaded: the
 * fragments of the LDI in this slab and the volume pieces between them are composited front to
 * back with the light arriving at the slab, and filtered into the outgoing light by their
 * transport colours; the tiles shading wrote into are scanned for constants again. Every
 * per-pixel quantity depends only on (seed, slab, pixel), so the image does not depend on the
 * thread count or on which thread took which row. */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "clock.h"
#include "geometry.h"
#include "detail_batch.h"
#include "kernel/composite.h" /* shared with the cl and gl programs */
#include "kernel/occlusion.h"
#include "icshadow/rng.h"
#include "own_term.h"
#include "piece_batch.h"
#include "plan_internal.h"
#include "pool.h"
#include "propagate.h"
#include "scene_internal.h"
#include "tiles.h"

#if defined(__SANITIZE_ADDRESS__)
#define ICS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ICS_ASAN 1
#endif
#endif
#ifdef ICS_ASAN
#include <sanitizer/asan_interface.h>
#define ARENA_GUARD 64 /* AddressSanitizer: a poisoned guard after each array of a frame's block */
#else
#define ARENA_GUARD 0
#define ASAN_POISON_MEMORY_REGION(a, n) ((void)(a), (void)(n))
#define ASAN_UNPOISON_MEMORY_REGION(a, n) ((void)(a), (void)(n))
#endif

#define JITTER_STREAM 0x6a69747400000000ULL /* "jitt": the sample depth inside a slab piece */
#define DETAIL_SAMPLE 16                     /* one volume piece in 16 timed (ms_detail) */

typedef struct {
  const ics_plan *p;
  ics_image *img;
  int k;                 /* current slab */
  int nb;                /* buffered lights: nlights x sets (ics_plan_light_sets: the first,
                            Patel's, the sharp and the moment set, as the model has them) */
  ics_set_role *role;    /* per buffered light: its set's role */
  int chans[4 * ICS_SCENE_MAX_LIGHTS]; /* per buffered light: its channels (the moment's 1) */
  int patel_set;         /* Patel's set, which lights the solids' surfaces (0: none) */
  int sharp_set;         /* render.model blocker: the sharp set (the moment set follows it) */
  int moment;            /* render.model blocker: the sharp and moment sets are kept */
  float **src, **dst;    /* per buffered light b (light b % nlights, set b / nlights): nch planes */
  ics_prop_taps *pt;     /* per light, then (render.model blocker) per light its sharp set's */
  uint32_t *cursor;      /* per pixel: first fragment not yet reached (colour, volumes) */
  uint32_t *acursor;     /* per pixel: first fragment whose occlusion may still be due */
  uint64_t *mask;        /* NULL without volumes */
  int vol_obj[ICS_MAX_VOLUMES]; /* per inside-mask bit: its object */
  uint32_t *scratch;     /* per thread: ICS_PROP_SCRATCH(Wb) words (rows' entries or run choices) */
  ics_simd_path simd;    /* the propagation loops' vector path */
  ics_tile **tsrc, **tdst; /* per buffered light: what each tile of src and dst holds */
  uint8_t **ssrc, **sdst;  /* per buffered light of the second set: each tile of src and dst equal
                              to the first set's bit for bit (then it is copied, not stepped) */
  uint8_t *marks;        /* per thread: (1 + nb) x grid.nx flags for the row it works on: the
                            tiles shading wrote into, then per buffered light those filled (1),
                            stepped (2; 4 stepped grey) or copied from the first set (3) */
  ics_rect shade;        /* this slab: the pixels to shade (the lights' active regions joined) */
  atomic_int next_row;   /* the next row of tiles to take this slab */
  double active[256];    /* per thread: channel-pixel updates propagated */
  int *seg_next;         /* per row and tile column: the first slab at which a pixel of that
                            row segment has work */
  int32_t *pnext;        /* per pixel: the first slab at which it has work: 0 inside a volume
                            (every slab), else the slab of its fragment acursor (INT_MAX: none) */
  ics_aov_buf *aov;      /* NULL: no AOVs */
  uint8_t *aov_seen;     /* per view pixel: its first surface recorded */
  double prop_s[256], shade_s[256], detail_s[256];
  double window[2 * ICS_SCENE_MAX_LIGHTS]; /* this slab, per light: 1 - its blur sigma in pixels,
                                              >= 0; then (blocker) its sharp set's */
  double window_max;                   /* the largest over lights and slabs (the cursor's reach) */
  double blend_span;                   /* render.model blocker: log(d1 / (d1 s)), arriving_light's
                                          blend's denominator */
  double blur_world[ICS_SCENE_MAX_LIGHTS]; /* per light: the per-slab blur's sigma, world units */
  double *dpts;          /* per thread: 8 x Wb doubles, a row's detail points (x, y, z of the
                            first and second ends) and their values (first, second) */
  int32_t *dslot;        /* per thread: Wb, each pixel's slot in them, or -1 */
  double *prow;          /* per thread: 10 x Wb, a row's lone pieces (ics_piece_row's arrays) */
  uint8_t *lone_mark;    /* per thread: Wb, 1 where a row's pixel was a lone piece (row_pieces) */
  int lone_batched;      /* the lone pieces shaded a row at a time (the vector paths) */
  ics_piece_params pp;   /* this slab's uniforms for the lone pieces (vector paths) */
  ics_hits hits[256];    /* per thread: a ray's crossings (the own term's normals) */
  int failed;            /* out of memory in a thread (the render fails) */
  int nk;                /* kernels: each light's, then (blocker) each light's sharp set's */
  int *pending;          /* perspective, per kernel: this slab's tap count whose classes are
                            still to compensate (classes_job), or -1 */
  ics_tap2d **taps;      /* per kernel: this slab's taps */
} job_t;

/* the taps buffered light b steps with */
static ics_prop_taps *taps_of(const job_t *j, int b) {
  int l = b % j->p->nlights;
  return &j->pt[j->role[b] == ICS_SET_SHARP ? j->p->nlights + l : l];
}

/* whether an occlusion filters buffered light b: a solid object's surface only in Patel's set
 * (elsewhere its interior is dark), any other in every set but the moment */
static int occludes_in(const job_t *j, int b, int solid) {
  return j->role[b] == ICS_SET_PATEL || (!solid && j->role[b] != ICS_SET_MOMENT);
}

/* render.model blocker: the first set's light at pixel q of light l, its channels' mean */
static double first_mean(const job_t *j, int l, size_t q) {
  double v = 0;
  for (int c = 0; c < j->p->nch; c++) v += j->dst[l][(size_t)c * j->p->buf.plane + q];
  return v / j->p->nch;
}

/* render.model blocker: the moment set gains the first set's loss at pixel q of light l (its
 * channels' mean, v0 before the occlusion) times the occlusion's depth z, normalised */
static void moment_add(job_t *j, int l, size_t q, double v0, double z) {
  const ics_plan *P = j->p;
  double gain = (v0 - first_mean(j, l, q)) * (z - P->z0) / (P->K * P->e);
  for (int b = l; b < j->nb; b += P->nlights)
    if (j->role[b] == ICS_SET_MOMENT)
      j->dst[b][q] += (float)gain;
}

/* the last pair of jitters drawn: pixels 2 m and 2 m + 1 of a slab share one Philox call */
typedef struct {
  uint64_t block; /* m, or UINT64_MAX for none */
  double u[2];
} jitter_pair;

/* where a piece's detail is sampled: its two ends (preintegrate: the detail varies linearly
 * between them) or one jittered point (Patel: the volume is constant within the slab; the
 * jitter ics_rng_uniform_at(seed, JITTER_STREAM | slab, p), through *pair where the caller
 * keeps one, else NULL), on the camera ray o + z d of buffer pixel (bi, bj) = p */
static void piece_points(const job_t *j, size_t p, int bi, int bj, double za, double dz,
                         jitter_pair *pair, double o[3], double d[3], double pt[3], double pt2[3]) {
  const ics_plan *P = j->p;
  ics_plan_ray(P, bi, bj, o, d);
  if (P->rs.preintegrate) {
    for (int i = 0; i < 3; i++) pt[i] = o[i] + za * d[i], pt2[i] = o[i] + (za + dz) * d[i];
    return;
  }
  uint64_t stream = JITTER_STREAM | (uint64_t)j->k;
  double xi;
  if (pair) {
    if (pair->block != p >> 1) ics_rng_uniform_pair_at(P->rs.seed, stream, p >> 1, pair->u);
    pair->block = p >> 1;
    xi = pair->u[p & 1];
  } else {
    xi = ics_rng_uniform_at(P->rs.seed, stream, p);
  }
  double zs = za + xi * dz;
  for (int i = 0; i < 3; i++) pt[i] = o[i] + zs * d[i];
}

/* render.model surface: the light shading a volume piece of depth dz, seen at a = sigma dl
 * extinction per unit depth (sigma the pieces' sum), its own attenuation of the light inside it
 * included: light l's channel c falls off as exp(-b x) over the piece, b = sum_i sigma_i (1 -
 * T_i,c) path_l (the transport's exponent per unit depth), so the piece's emission sum_i sigma_i
 * col_i L(x) seen through exp(-a x) integrates to (1 - exp(-(a + b) dz)) / (a + b) where a light
 * that did not fall off gives (1 - exp(-a dz)) / a: each light's arriving V (arrive, per light
 * and channel, read before this slab's occlusions) is scaled by the ratio (docs/renderer.md
 * "Models": a volume piece's own term). Into L the light per colour channel. */
static void piece_light(const job_t *j, const float *arrive, int nv, const double *sig,
                        const int *objs, double a, double dz, double L[3]) {
  const ics_plan *P = j->p;
  const ics_scene *s = P->scene;
  double plain = -expm1(-a * dz) / a, bc[3] = {0, 0, 0}; /* per channel, per unit light path */
  for (int c = 0; c < P->nch; c++)
    for (int i = 0; i < nv; i++) bc[c] += sig[i] * (1 - s->materials[s->objects[objs[i]].material].transport[c]);
  L[0] = L[1] = L[2] = 0;
  for (int l = 0; l < P->nlights; l++) {
    const ics_light *lt = &s->lights[l];
    for (int c = 0; c < 3; c++) {
      int ch = P->nch == 3 ? c : 0;
      double b = bc[ch] * P->light_path[l];
      L[c] += lt->color[c] * lt->weight * arrive[l * P->nch + ch] * (-expm1(-(a + b) * dz) / (a + b)) / plain;
    }
  }
}

/* a piece's sample points, found once for all its volumes (piece_points) */
typedef struct {
  int have;
  double pt[3], pt2[3];
} piece_at;

/* one volume's colour c and extinction scale in a piece: its material's own, or from its detail
 * value through its transfer function; the value batched already (pre: the piece's one or two
 * ends) or evaluated here at the piece's points (*at, found on first use; timed one piece in
 * DETAIL_SAMPLE: a clock read per piece cost more than a tenth of the detail itself) */
static double volume_scale(job_t *j, int obj, size_t p, int bi, int bj, double za, double dz,
                           const double *pre, piece_at *at, int t, double c[3]) {
  const ics_plan *P = j->p;
  const ics_material *mat = &P->scene->materials[P->scene->objects[obj].material];
  double scale = 1, v[2];
  memcpy(c, mat->color, sizeof mat->color);
  if (mat->detail.fn == ICS_DETAIL_NONE) return scale;
  if (pre) {
    v[0] = pre[0], v[1] = pre[1];
  } else {
    int timed = (p + (size_t)j->k) % DETAIL_SAMPLE == 0;
    double t0 = timed ? ics_clock_s() : 0, o[3], d[3];
    if (!at->have) piece_points(j, p, bi, bj, za, dz, NULL, o, d, at->pt, at->pt2), at->have = 1;
    v[0] = ics_detail_value(&P->detail[obj], at->pt);
    v[1] = P->rs.preintegrate ? ics_detail_value(&P->detail[obj], at->pt2) : 0;
    if (timed) j->detail_s[t] += DETAIL_SAMPLE * (ics_clock_s() - t0);
  }
  if (P->rs.preintegrate)
    ics_material_preintegrate(mat, v[0], v[1], c, &scale);
  else
    ics_material_transfer(mat, v[0], c, &scale);
  return scale;
}

/* the camera ray's path per unit depth at buffer pixel (bi, bj): 1 for an orthographic camera */
static double camera_path(const ics_plan *P, int bi, int bj) {
  if (P->cam.projection != ICS_PROJ_PERSPECTIVE) return 1;
  double o[3], d[3];
  ics_plan_ray(P, bi, bj, o, d);
  return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

/* a piece of nv volumes (extinctions sig, colours col, their sum `sum`) composited into the
 * view pixel C, lit by L; dl the camera path per unit depth */
static void piece_composite(int nv, const double *sig, const double (*col)[3], double sum,
                            double dz, double dl, const double L[3], float *C) {
  double rgb[3];
  for (int c = 0; c < 3; c++) {
    double cc = 0;
    for (int i = 0; i < nv; i++) cc += sig[i] * col[i][c];
    rgb[c] = cc / sum;
  }
  ics_k_composite(ics_k_piece_alpha(sum, dz, dl), rgb, L, C);
}

/* the light leaving a piece of nv volumes (extinctions sig) at buffer pixel q, per light: the
 * buffers it occludes in times the piece's transmittance per channel (render.model blocker: the
 * moment gains the first set's loss at the piece's middle) */
static void piece_attenuate(job_t *j, size_t q, int nv, const double *sig, const int *objs,
                            double za, double dz) {
  const ics_plan *P = j->p;
  const ics_scene *s = P->scene;
  size_t plane = P->buf.plane;
  for (int l = 0; l < P->nlights; l++) {
    double pass[3] = {1, 1, 1};
    for (int i = 0; i < nv; i++) {
      /* a volume's transport colour scales its extinction for the light, per channel, so the
       * pieces of any slab spacing multiply to the same transmittance */
      const double *T = s->materials[s->objects[objs[i]].material].transport;
      for (int c = 0; c < P->nch; c++)
        pass[c] *= ics_k_piece_pass(sig[i], dz, P->light_path[l], T[c]);
    }
    double v0 = j->moment ? first_mean(j, l, q) : 0;
    for (int b = l; b < j->nb; b += P->nlights)
      if (occludes_in(j, b, 0))
        for (int c = 0; c < P->nch; c++) j->dst[b][(size_t)c * plane + q] *= (float)pass[c];
    if (j->moment) moment_add(j, l, q, v0, za + dz / 2);
  }
}

/* buffer pixel q inside a solid object at depth z: no light in the first set (and the sharp
 * set; render.model solid and after; Patel's set keeps it), the light lost added to the moment */
static void solid_interior(job_t *j, size_t q, double z) {
  const ics_plan *P = j->p;
  for (int l = 0; l < P->nlights; l++) {
    double v0 = j->moment ? first_mean(j, l, q) : 0;
    for (int b = l; b < j->nb; b += P->nlights)
      if (j->role[b] == ICS_SET_FIRST || j->role[b] == ICS_SET_SHARP)
        for (int c = 0; c < P->nch; c++) j->dst[b][(size_t)c * P->buf.plane + q] = 0;
    if (v0 > 0) moment_add(j, l, q, v0, z);
  }
}

/* one volume piece of depth extent dz ending the events at (pixel p, depth za..za+dz); pre: its
 * one volume's detail values (first and second end) evaluated already, or NULL (mask: volumes
 * only; a solid's interior is solid_interior's) */
static void volume_piece(job_t *j, size_t p, int bi, int bj, uint64_t mask, double za, double dz,
                         const double L[3], const float *arrive, float *C, int inview, int t,
                         const double *pre) {
  const ics_plan *P = j->p;
  double sig[ICS_MAX_VOLUMES], col[ICS_MAX_VOLUMES][3];
  int objs[ICS_MAX_VOLUMES], nv = 0;
  size_t q = ics_buf_index(&P->buf, bi, bj);
  double sum = 0;
  piece_at at = {0};
  for (uint64_t m = mask; m; m &= m - 1) {
    int obj = j->vol_obj[__builtin_ctzll(m)];
    double scale = volume_scale(j, obj, p, bi, bj, za, dz, pre, &at, t, col[nv]);
    sig[nv] = P->scene->materials[P->scene->objects[obj].material].extinction * scale;
    objs[nv] = obj;
    sum += sig[nv++];
  }
  if (!(sum > 0)) return;
  if (inview && C[3] < 1) {
    double dl = camera_path(P, bi, bj), Lp[3];
    if (arrive) piece_light(j, arrive, nv, sig, objs, sum * dl, dz, Lp);
    piece_composite(nv, sig, (const double(*)[3])col, sum, dz, dl, arrive ? Lp : L, C);
  }
  piece_attenuate(j, q, nv, sig, objs, za, dz);
}

/* a surface seen at this slab: its colour, lit by the light arriving here */
/* render.model surface: the light on a solid's surface fragment by its own lit side, per light
 * the buffer's V (set `set`) times the fraction of the Gaussian light above the surface's
 * tangent plane (docs/renderer.md "A surface's own term"): a direction X on the light plane,
 * toward w = X_x r + X_y u - f, lights the surface iff w . n > 0, n its normal turned toward the
 * camera ray d, a half-plane of the light plane, so the fraction is
 * Phi((a . mu + b) / sqrt(a' Sigma a)), a = (r . n, u . n), b = -f . n (a step where
 * a' Sigma a = 0). The normal is the object's own at the fragment (ics_object_normal_near: its
 * crossing of the pixel's ray nearest the fragment's depth z), not the layered depth image's
 * quantised depth gradient.
 * arrive: the buffers' values arriving at this slab (before its occlusions), per buffered light
 * and channel; the own term applies to the lights in `lights` (Phi = 1 for the others). Into L
 * the light (sum over lights of colour x weight x V Phi), into V the AOVs' V Phi per light and
 * channel. 0, or -1 when out of memory (j->failed is set). */
static int own_light(job_t *j, int obj, double z, int bi, int bj, const float *arrive, int set,
                     uint64_t lights, double L[3], float *V, int t) {
  const ics_plan *P = j->p;
  double o[3], d[3], n[3];
  ics_plan_ray(P, bi, bj, o, d);
  if (ics_object_normal_near(&P->scene->objects[obj], o, d, z, &j->hits[t], n)) return -1;
  if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] > 0) n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
  L[0] = L[1] = L[2] = 0;
  for (int l = 0; l < P->nlights; l++) {
    const ics_light *lt = &P->scene->lights[l];
    double phi = lights >> l & 1 ? ics_light_side_fraction(&P->cam, lt, n) : 1;
    const float *B = arrive + (size_t)(set * P->nlights + l) * P->nch;
    for (int k = 0; k < 3; k++) L[k] += lt->color[k] * lt->weight * phi * B[P->nch == 3 ? k : 0];
    for (int k = 0; k < P->nch; k++) V[l * P->nch + k] = (float)(phi * B[k]);
  }
  return 0;
}

static void surface_colour(const job_t *j, int obj, const double L[3], float *C) {
  const ics_plan *P = j->p;
  const ics_material *m = &P->scene->materials[P->scene->objects[obj].material];
  double a = m->opacity;
  if (!(a > 0) || !(C[3] < 1)) return;
  ics_k_composite(a, m->color, L, C);
}

/* a surface's occlusion of the light leaving this slab, `after` slabs after its first (slab +
 * bias); q is the pixel's index in the light buffers' layout. Each pixel occludes at its own
 * depth, so two neighbours whose depths differ by span slabs occlude span slabs apart, and a
 * light parcel moving sideways can slip between them (a steep surface leaks). Unless the light's
 * per-slab blur (sigma pixels) smears the gap shut, each fragment therefore keeps occluding for
 * the window span (1 - sigma) slabs after its first. A parcel of light l moves by -e mu per slab,
 * so the surface's depth under it changes by rho = -(dz/dr mu_x + dz/du mu_y) slabs per slab while
 * its own depth grows by one: it stays (window + 1) / |1 - rho| slabs within the windows of the
 * surface (clamped to [1, 8 (window + 1)]), and each of those slabs passes that root's share of
 * 1 - a (1 - T): the parcel is filtered once in all (docs/renderer.md "Surface bias"). Without a
 * window the fragment filters at its one slab, as it always did. The buffer sets take it as
 * occludes_in says (a solid object's surface occludes only in Patel's set). A solid's surface
 * (render.model surface and after) takes no window: its interior keeps the light out of the
 * first set, and in Patel's set, which lights only solids' surfaces by their own term, the
 * windows made the error larger (docs/renderer.md "Models": measured without them). */
static void surface_occlusion(job_t *j, size_t q, const ics_fragment *fr, int after, int solid) {
  const ics_plan *P = j->p;
  const ics_material *m = &P->scene->materials[P->scene->objects[ics_frag_obj(fr)].material];
  double a = m->opacity;
  if (!(a > 0)) return;
  size_t plane = P->buf.plane;
  double gr = fr->grad[0] / ICS_FRAG_GRAD_SCALE, gu = fr->grad[1] / ICS_FRAG_GRAD_SCALE;
  uint64_t own = P->own_lights[ics_frag_obj(fr)]; /* lights that leave this surface out */
  for (int l = 0; l < P->nlights; l++) {
    if (own >> l & 1) continue;
    const double *mu = P->scene->lights[l].mean;
    double rho = -(gr * mu[0] + gu * mu[1]), rel = fabs(1 - rho);
    double v0 = j->moment ? first_mean(j, l, q) : 0;
    for (int sharp = 0; sharp <= j->moment; sharp++) { /* the sets of d1's blur, the sharp set */
      double window = solid ? 0 : floor(fr->span * j->window[sharp * P->nlights + l]);
      if (after > window) continue;
      double meets = ics_k_meets(window, rel); /* no window (a blur of a pixel or more): one slab */
      for (int c = 0; c < P->nch; c++) {
        float f = ics_k_slab_pass(a, m->transport[c], meets);
        for (int b = l; b < j->nb; b += P->nlights)
          if (occludes_in(j, b, solid) && (j->role[b] == ICS_SET_SHARP) == sharp)
            j->dst[b][(size_t)c * plane + q] *= f;
      }
    }
    if (!solid && j->moment) moment_add(j, l, q, v0, fr->z);
  }
}

/* the AOVs of view pixel (ii, jj) at its first surface (depth z): V[l nch + c], the light
 * arriving at its slab (read before this slab's occlusions) */
static void record_aov(job_t *j, int ii, int jj, const float *V, double z) {
  const ics_plan *P = j->p;
  size_t v = (size_t)jj * P->W + ii;
  ics_aov_buf *a = j->aov;
  float *o = a->data + v * (size_t)a->count;
  j->aov_seen[v] = 1;
  if (a->vis >= 0)
    for (int l = 0; l < P->nlights; l++)
      for (int c = 0; c < P->nch; c++)
        o[a->vis + l * P->nch + c] = V[l * P->nch + c];
  if (a->z >= 0) o[a->z] = (float)z;
}

/* the pixels [*x0, *x1) of row segment tx that shading steps at this slab (the tile's within the
 * shading rectangle), or 0 where the segment is passed over: no longer needed (need, the last
 * slab it is), or nothing to do in it before its next slab (seg) */
static int segment_pixels(const job_t *j, int tx, const int32_t *need, const int *seg, int *x0,
                          int *x1) {
  if (need[tx] < j->k || seg[tx] > j->k) return 0;
  *x0 = ics_tile_x0(&j->p->tiles, tx), *x1 = ics_tile_x1(&j->p->tiles, tx);
  if (*x0 < j->shade.x0) *x0 = j->shade.x0;
  if (*x1 > j->shade.x1) *x1 = j->shade.x1;
  return 1;
}

/* row_details' pixel (bi, bj): 1 with its piece's points in *x .. *z2 when it joins the batch
 * (inside one volume with noise detail, the batch's volume *obj0, no fragment in the slab), else
 * 0; its slot -1 inside a volume (shade_rows reads a slot only there) */
static int detail_point(job_t *j, int bj, int bi, double zf, double zb, int *obj0,
                        jitter_pair *pair, double *x, double *y, double *z, double *x2, double *y2,
                        double *z2, int32_t *slot) {
  const ics_plan *P = j->p;
  const ics_scene *s = P->scene;
  size_t p = (size_t)bj * P->Wb + bi;
  uint64_t mask = j->mask[p];
  if (!mask) return 0;
  slot[bi] = -1;
  if (mask & (mask - 1)) return 0;
  int obj = j->vol_obj[__builtin_ctzll(mask)];
  ics_detail_fn fn = s->materials[s->objects[obj].material].detail.fn;
  uint32_t cur = j->cursor[p];
  if (fn == ICS_DETAIL_NONE || fn == ICS_DETAIL_GRID || (*obj0 >= 0 && obj != *obj0) ||
      (cur < P->ldi.offset[p + 1] && ics_frag_slab(&P->ldi.frag[cur]) == j->k))
    return 0;
  *obj0 = obj;
  double o[3], d[3], a[3], b[3];
  piece_points(j, p, bi, bj, zf, zb - zf, pair, o, d, a, b);
  *x = a[0], *y = a[1], *z = a[2], *x2 = b[0], *y2 = b[1], *z2 = b[2];
  return 1;
}

/* The detail values of row bj's volume pieces at this slab, evaluated in one batch on the vector
 * path (detail_batch.h; bit for bit one by one): the pixels inside exactly one volume with noise
 * detail (the row's first such volume) and no fragment in the slab, so that the slab is one piece
 * [zf, zb]. Each gets its slot in j->dslot (else -1); the pieces shade_rows meets otherwise
 * (fragments, overlapping volumes, grids) evaluate their own. */
static void row_details(job_t *j, int bj, double zf, double zb, const int32_t *need,
                        const int *seg, int tx0, int tx1, int t) {
  const ics_plan *P = j->p;
  size_t w = (size_t)P->Wb;
  double *X = j->dpts + (size_t)t * 8 * w, *Y = X + w, *Z = Y + w, *X2 = Z + w, *Y2 = X2 + w,
         *Z2 = Y2 + w, *V = Z2 + w, *V2 = V + w;
  int32_t *slot = j->dslot + (size_t)t * w;
  int n = 0, obj0 = -1;
  jitter_pair pair = {UINT64_MAX, {0, 0}};
  for (int tx = tx0, x0, x1; tx <= tx1; tx++) { /* the pixels shade_rows steps alone */
    if (!segment_pixels(j, tx, need, seg, &x0, &x1)) continue;
    for (int bi = x0; bi < x1; bi++)
      if (detail_point(j, bj, bi, zf, zb, &obj0, &pair, X + n, Y + n, Z + n, X2 + n, Y2 + n, Z2 + n,
                       slot))
        slot[bi] = n++;
  }
  if (!n) return;
  double t0 = ics_clock_s();
  ics_detail_batch(&P->detail[obj0], X, Y, Z, n, V, j->simd);
  if (P->rs.preintegrate) ics_detail_batch(&P->detail[obj0], X2, Y2, Z2, n, V2, j->simd);
  j->detail_s[t] += ics_clock_s() - t0;
}

/* The light arriving at pixel q (before this slab's occlusions) into arrive[b nch + c] for every
 * buffered light b and channel c it has (the moment: c = 0 alone). render.model blocker: the
 * first set's (b < nlights) becomes the blend sharp + t (first - sharp) of the sharp set (at
 * d1 s, s = ICS_BLOCKER_SHARP) and the first set (d1) by the receiver's distance d to its
 * blockers (its depth z less their mean depth, the moment over the first set's occlusion 1 - V):
 * the sharp set's up to d1 s, the first set's from d1 on, and between them
 * t = log(d / (d1 s)) / log(1 / s), within 0.05 of the t whose mixture of the two penumbrae fits
 * the correct one best (least squares, analysis/blocker_blend.py; docs/renderer.md "Models":
 * blocker-aware penumbrae). */
static void arriving_light(const job_t *j, size_t q, double z, float *arrive) {
  const ics_plan *P = j->p;
  size_t plane = P->buf.plane;
  for (int b = 0; b < j->nb; b++)
    for (int c = 0; c < j->chans[b]; c++) arrive[b * P->nch + c] = j->dst[b][(size_t)c * plane + q];
  if (P->rs.model < ICS_MODEL_BLOCKER) return;
  int nl = P->nlights, sharp = j->sharp_set;
  double d_sharp = P->rs.d1 * ICS_BLOCKER_SHARP;
  for (int l = 0; l < nl; l++) {
    float *first = arrive + l * P->nch;
    const float *sh = arrive + (sharp * nl + l) * P->nch, *mom = arrive + ((sharp + 1) * nl + l) * P->nch;
    double occ = 0;
    for (int c = 0; c < P->nch; c++) occ += 1 - first[c];
    occ /= P->nch;
    if (!(occ > 1e-4)) continue; /* no blocker: the sets agree */
    double zb = P->z0 + mom[0] / occ * P->K * P->e, d = z - zb;
    double t = d <= d_sharp ? 0 : d >= P->rs.d1 ? 1 : log(d / d_sharp) / j->blend_span;
    for (int c = 0; c < P->nch; c++) first[c] = (float)(sh[c] + t * (first[c] - sh[c]));
  }
}

/* pixel bi's detail values batched by row_details (slot: the row's slots, or NULL for none):
 * pre (the piece's one or two ends), or NULL where it has none */
static const double *batched(const job_t *j, const int32_t *slot, const double *values, int bi,
                             double pre[2]) {
  int s0 = slot ? slot[bi] : -1;
  if (s0 < 0) return NULL;
  pre[0] = values[s0], pre[1] = j->p->rs.preintegrate ? values[j->p->Wb + s0] : 0;
  return pre;
}

/* the light arriving (arrive: per buffered light and channel), weighted by each light's colour
 * and weight, per colour channel */
static void light_colour(const job_t *j, const float *arrive, double L[3]) {
  const ics_plan *P = j->p;
  L[0] = L[1] = L[2] = 0;
  for (int l = 0; l < P->nlights; l++) {
    const ics_light *lt = &P->scene->lights[l];
    for (int c = 0; c < 3; c++)
      L[c] += lt->color[c] * lt->weight * arrive[l * P->nch + (P->nch == 3 ? c : 0)];
  }
}

/* The common piece, without volume_piece's generality: buffer pixel p inside one volume `obj`
 * that is no solid, no fragment in the slab (the piece is the whole slab [za, za + dz]), no
 * surface occlusion due; pre its batched detail values or NULL; C its view pixel or NULL. The
 * same arithmetic as volume_piece and shade_rows for it (the same helpers: the light arriving,
 * blended under render.model blocker, the piece's own term from render.model surface on), so the
 * same bits. */
static void single_volume_piece(job_t *j, size_t p, int bi, int bj, int obj, double za,
                                double dz, float *C, int t, const double *pre) {
  const ics_plan *P = j->p;
  size_t q = ics_buf_index(&P->buf, bi, bj);
  double col[1][3];
  piece_at at = {0};
  double sig = P->scene->materials[P->scene->objects[obj].material].extinction *
               volume_scale(j, obj, p, bi, bj, za, dz, pre, &at, t, col[0]);
  if (!(sig > 0)) return;
  if (C && C[3] < 1) {
    float arrive[4 * ICS_SCENE_MAX_LIGHTS * 3];
    double L[3], dl = camera_path(P, bi, bj);
    arriving_light(j, q, za + P->e / 2, arrive);
    if (P->rs.model >= ICS_MODEL_SURFACE)
      piece_light(j, arrive, 1, &sig, &obj, sig * dl, dz, L);
    else
      light_colour(j, arrive, L);
    piece_composite(1, &sig, (const double(*)[3])col, sig, dz, dl, L, C);
  }
  piece_attenuate(j, q, 1, &sig, &obj, za, dz);
}

/* whether fragment fr occludes at slab k: a surface (open, or a solid's; a volume's boundary
 * occludes nothing) within its window of slabs from its first (its slab and bias); *solid: it
 * is a solid's */
static int occlusion_due(const job_t *j, const ics_fragment *fr, int k, int *solid) {
  const ics_plan *P = j->p;
  int first = ics_frag_slab(fr) + ics_frag_bias(fr), ib = P->inside_bit[ics_frag_obj(fr)];
  *solid = ib >= 0 && (P->solid_bits >> ib & 1);
  return (ib < 0 || *solid) && first <= k && k <= first + fr->span * j->window_max;
}

/* pixel p's occlusion cursor past the fragments whose windows ended before slab k (end: its
 * fragments' end); returns it */
static uint32_t advance_acursor(job_t *j, size_t p, uint32_t end, int k) {
  const ics_fragment *fr = j->p->ldi.frag;
  uint32_t acur = j->acursor[p];
  while (acur < end &&
         ics_frag_slab(&fr[acur]) + ics_frag_bias(&fr[acur]) + fr[acur].span * j->window_max <= k)
    acur++;
  return j->acursor[p] = acur;
}

/* pixel p's volume when its piece at slab k is a lone one (single_volume_piece's: inside one
 * volume that is no solid, no fragment in the slab, no surface occlusion due: the fragments
 * from acur reaching this slab are volumes' boundaries, or their windows are over), else -1 */
static int lone_piece(const job_t *j, size_t p, int k) {
  const ics_plan *P = j->p;
  uint64_t mask = j->mask ? j->mask[p] : 0;
  uint32_t cur = j->cursor[p], end = P->ldi.offset[p + 1];
  if (!mask || (mask & (mask - 1)) || (mask & P->solid_bits) ||
      (cur < end && ics_frag_slab(&P->ldi.frag[cur]) == k))
    return -1;
  for (uint32_t f = j->acursor[p]; f < end && ics_frag_slab(&P->ldi.frag[f]) <= k; f++) {
    int solid;
    if (occlusion_due(j, &P->ldi.frag[f], k, &solid)) return -1;
  }
  return j->vol_obj[__builtin_ctzll(mask)];
}

/* the uniforms of slab k's lone pieces (piece_batch.h) */
static void piece_params(job_t *j, int k) {
  const ics_plan *P = j->p;
  ics_piece_params *pp = &j->pp;
  double zf = P->z0 + k * P->e, zb = zf + P->e;
  pp->nlights = P->nlights, pp->nch = P->nch, pp->nb = j->nb, pp->plane = P->buf.plane;
  pp->dst = j->dst;
  for (int b = 0; b < j->nb; b++) {
    pp->attenuates[b] = (uint8_t)occludes_in(j, b, 0);
    pp->is_moment[b] = j->role[b] == ICS_SET_MOMENT;
  }
  pp->own = P->rs.model >= ICS_MODEL_SURFACE, pp->blend = P->rs.model >= ICS_MODEL_BLOCKER;
  pp->moment = j->moment, pp->sharp_set = j->sharp_set;
  for (int l = 0; l < P->nlights; l++) {
    const ics_light *lt = &P->scene->lights[l];
    for (int c = 0; c < 3; c++) pp->lcw[l][c] = lt->color[c] * lt->weight;
    pp->lpath[l] = P->light_path[l];
  }
  pp->dz = zb - zf, pp->z_light = zf + P->e / 2, pp->z_moment = zf + pp->dz / 2;
  pp->z0 = P->z0, pp->K = P->K, pp->e = P->e;
  pp->d_sharp = P->rs.d1 * ICS_BLOCKER_SHARP, pp->d1 = P->rs.d1, pp->blend_span = j->blend_span;
  pp->img = j->img->data;
}

/* Row bj's lone pieces at this slab, on the vector path in one batch (piece_batch.h): each
 * piece's volume, extinction and colour here (its detail batched by row_details, or evaluated
 * now), then the light, the view and the buffers in the batch; lone[bi] says which pixels were
 * lone pieces, for shade_rows to pass over. */
static void row_pieces(job_t *j, int bj, const int32_t *need, const int *seg, int tx0, int tx1,
                       const int32_t *slot, const double *values, int t, uint8_t *lone) {
  const ics_plan *P = j->p;
  const ics_scene *s = P->scene;
  size_t w = (size_t)P->Wb;
  double *a = j->prow + (size_t)t * 10 * w, zf = P->z0 + j->k * P->e, zb = zf + P->e;
  ics_piece_row r = {0, (int64_t *)a, (int64_t *)(a + w), a + 2 * w, a + 3 * w,
                     {a + 4 * w, a + 5 * w, a + 6 * w}, {a + 7 * w, a + 8 * w, a + 9 * w}};
  for (int tx = tx0, x0, x1; tx <= tx1; tx++) {
    if (!segment_pixels(j, tx, need, seg, &x0, &x1)) continue;
    for (int bi = x0; bi < x1; bi++) {
      size_t p = (size_t)bj * P->Wb + bi;
      int obj = j->pnext[p] > j->k ? -1 : lone_piece(j, p, j->k);
      lone[bi] = obj >= 0;
      if (obj < 0) continue;
      double pre[2], col[3];
      piece_at at = {0};
      const ics_material *mat = &s->materials[s->objects[obj].material];
      double sig = mat->extinction * volume_scale(j, obj, p, bi, bj, zf, zb - zf,
                                                  batched(j, slot, values, bi, pre), &at, t, col);
      if (!(sig > 0)) continue;
      int ii = bi - P->pad[0], jj = bj - P->pad[2], n = r.n++;
      r.q[n] = (int64_t)ics_buf_index(&P->buf, bi, bj);
      r.view[n] = ii >= 0 && ii < P->W && jj >= 0 && jj < P->H ? (int64_t)jj * P->W + ii : -1;
      r.sig[n] = sig, r.dl[n] = camera_path(P, bi, bj);
      for (int c = 0; c < 3; c++) r.col[c][n] = col[c], r.keep[c][n] = 1 - mat->transport[c];
    }
  }
  if (r.n) ics_piece_batch(&j->pp, &r, j->simd);
}

/* rows [y0, y1) within this slab's shading rectangle; the tiles written into flagged in touched */
static void shade_rows(job_t *j, int y0, int y1, int t, uint8_t *touched) {
  const ics_plan *P = j->p;
  const ics_scene *s = P->scene;
  const ics_ldi *ldi = &P->ldi;
  int k = j->k;
  double zf = P->z0 + k * P->e, zb = zf + P->e;
  if (y0 < j->shade.y0) y0 = j->shade.y0;
  if (y1 > j->shade.y1) y1 = j->shade.y1;
  const int32_t *need = y0 < y1 ? P->tile_shade + (size_t)ics_tile_row(&j->p->tiles, y0) * j->p->tiles.nx : NULL;
  for (int bj = y0; bj < y1; bj++) {
    int *seg = j->seg_next + (size_t)bj * j->p->tiles.nx, busy = 0;
    int tx0 = ics_tile_col(&j->p->tiles, j->shade.x0), tx1 = ics_tile_col(&j->p->tiles, j->shade.x1 - 1);
    for (int tx = tx0; tx <= tx1; tx++) busy |= seg[tx] <= k && need[tx] >= k;
    if (!busy) continue; /* nothing in this row before its segments' next slab */
    int batch = j->mask && P->any_detail;
    const int32_t *slot = NULL;
    const double *values = NULL;
    if (batch) {
      row_details(j, bj, zf, zb, need, seg, tx0, tx1, t);
      slot = j->dslot + (size_t)t * P->Wb;
      values = j->dpts + (size_t)t * 8 * P->Wb + 6 * (size_t)P->Wb;
    }
    int lone_batched = j->mask && j->lone_batched;
    uint8_t *lone_mark = lone_batched ? j->lone_mark + (size_t)t * P->Wb : NULL;
    if (lone_batched) row_pieces(j, bj, need, seg, tx0, tx1, slot, values, t, lone_mark);
    for (int tx = tx0, x0, x1; tx <= tx1; tx++) {
    if (!segment_pixels(j, tx, need, seg, &x0, &x1)) continue;
    int next = INT_MAX;
    for (int bi = x0; bi < x1; bi++) {
      size_t p = (size_t)bj * P->Wb + bi;
      if (j->pnext[p] > k) { /* nothing here yet (no fragment or volume mask read) */
        if (j->pnext[p] < next) next = j->pnext[p];
        continue;
      }
      uint64_t mask = j->mask ? j->mask[p] : 0;
      uint32_t cur = j->cursor[p], end = ldi->offset[p + 1], acur = j->acursor[p];
      int has = cur < end && ics_frag_slab(&ldi->frag[cur]) == k;
      int ii = bi - P->pad[0], jj = bj - P->pad[2];
      int inview = ii >= 0 && ii < P->W && jj >= 0 && jj < P->H;
      float dummy[4] = {0, 0, 0, 1};
      float *C = inview ? j->img->data + ((size_t)jj * P->W + ii) * 4 : dummy;
      /* inside one volume, nothing else due: the piece (row_pieces' already on a vector path),
       * and the pixel needs the next slab */
      int lone = lone_batched ? (lone_mark[bi] ? 0 : -1) : lone_piece(j, p, k);
      if (lone >= 0) {
        double pre[2];
        touched[ics_tile_col(&j->p->tiles, bi)] = 1;
        if (!lone_batched)
          single_volume_piece(j, p, bi, bj, lone, zf, zb - zf, inview ? C : NULL, t,
                              batched(j, batch ? slot : NULL, values, bi, pre));
        advance_acursor(j, p, end, k); /* (as the other pixels' below) */
        j->pnext[p] = 0;
        next = k + 1;
        continue;
      }
      size_t q = ics_buf_index(&P->buf, bi, bj);
      /* every set's arriving light, per buffered light and channel; the first set's (render.model
       * blocker) blended with the sharp set's by this pixel's distance to its blockers: read for
       * a pixel in view with a fragment or a volume here (one with occlusions due only shades
       * nothing) */
      int lit = inview && (has || mask);
      float arrive[4 * ICS_SCENE_MAX_LIGHTS * 3];
      if (lit) arriving_light(j, q, zf + P->e / 2, arrive);
      double L[3] = {0, 0, 0}; /* the light arriving, for the colour of what is in view */
      if (lit) light_colour(j, arrive, L);
      float V[ICS_SCENE_MAX_LIGHTS * 3]; /* AOVs: the light arriving, per light and channel */
      if (j->aov && lit) memcpy(V, arrive, sizeof(float) * (size_t)P->nlights * P->nch);
      /* surface occlusions due at this slab (fragment slab + bias == k), after the light
       * arriving here was read: a surface never shadows its own slab. The tile is flagged where
       * the buffers are written (occlusions, volume pieces, solid interiors), not where only the
       * view pixel is shaded: a tile shading left alone keeps what it holds */
      uint8_t *wrote = &touched[ics_tile_col(&j->p->tiles, bi)];
      for (uint32_t f = acur; f < end && ics_frag_slab(&ldi->frag[f]) <= k; f++) {
        const ics_fragment *fr = &ldi->frag[f];
        int solid; /* open surfaces occlude in every set; a solid's surface in Patel's set only */
        if (occlusion_due(j, fr, k, &solid))
          surface_occlusion(j, q, fr, k - ics_frag_slab(fr) - ics_frag_bias(fr), solid), *wrote = 1;
      }
      acur = advance_acursor(j, p, end, k);
      if (!has && !mask) goto next_pixel;
      /* without a fragment in the slab the one piece is the whole slab: its detail batched */
      double pre[2];
      const double *pv = batched(j, batch && mask && !has ? slot : NULL, values, bi, pre);
      double za = zf;
      /* a solid's interior is dark from the slab after the one its ray enters it in: from this
       * slab's front for the solids held since an earlier slab (dark already: no piece darkens
       * them again), from the next for those entered here, or at once where the ray leaves them
       * in this slab */
      uint64_t held = mask & P->solid_bits, entered = 0;
      if (held) solid_interior(j, q, zf), *wrote = 1;
      for (;;) {
        double zn = has ? ldi->frag[cur].z : zb;
        if (zn < za) zn = za;
        if (zn > zb) zn = zb;
        if ((mask & ~(held | entered)) && zn > za) {
          volume_piece(j, p, bi, bj, mask & ~(held | entered), za, zn - za, L,
                       P->rs.model >= ICS_MODEL_SURFACE && inview ? arrive : NULL, C, inview, t,
                       pv);
          *wrote = 1;
        }
        if (!has) break;
        int obj = ics_frag_obj(&ldi->frag[cur]), ib = P->inside_bit[obj];
        if (ib >= 0) mask ^= 1ull << ib; /* a volume's or a solid's boundary */
        int solid = ib >= 0 && (P->solid_bits >> ib & 1);
        if (solid && (mask >> ib & 1) && !(held >> ib & 1)) entered |= 1ull << ib;
        else if (solid && (entered >> ib & 1)) { /* a solid thinner than this slab's rest */
          entered &= ~(1ull << ib);
          solid_interior(j, q, zn);
          *wrote = 1;
        }
        if ((ib < 0 || solid) && inview) { /* a surface */
          double Lo[3];
          uint64_t lights = P->rs.model < ICS_MODEL_SURFACE ? 0 : solid ? ~0ull : P->own_lights[obj];
          int own = lights != 0;
          /* a solid's surface: its own term, the rest from Patel's set; an open surface lit by
           * its own term: from the first set, which leaves it out */
          if (own && own_light(j, obj, ldi->frag[cur].z, bi, bj, arrive, solid ? j->patel_set : 0,
                               lights, Lo, V, t))
            j->failed = 1;
          surface_colour(j, obj, own ? Lo : L, C);
          if (j->aov && !j->aov_seen[(size_t)jj * P->W + ii] &&
              s->materials[s->objects[obj].material].opacity > 0)
            record_aov(j, ii, jj, V, ldi->frag[cur].z);
        }
        za = zn;
        cur++;
        has = cur < end && ics_frag_slab(&ldi->frag[cur]) == k;
      }
      j->cursor[p] = cur;
      if (j->mask) j->mask[p] = mask;
    next_pixel:
      j->pnext[p] = mask ? 0 : acur < end ? ics_frag_slab(&ldi->frag[acur]) : INT_MAX;
      /* the next slab this pixel needs: a volume it is inside of, a pending occlusion (at or
       * after its fragment's slab), its next fragment */
      if (mask) next = k + 1;
      if (acur < end && ics_frag_slab(&ldi->frag[acur]) < next) next = ics_frag_slab(&ldi->frag[acur]);
      if (acur < end && ics_frag_slab(&ldi->frag[acur]) <= k) next = k + 1;
    }
    seg[tx] = next;
    }
  }
}

/* tiles [tx0, tx1] of row ty of buffered light b's dst stepped from src: one span, kind
 * ICS_TILE_GREY (one channel stepped and copied) or ICS_TILE_ANY (every channel); flagged in
 * written 4 (grey: its planes equal) or 2 */
static void step_tiles(job_t *j, int b, int ty, int tx0, int tx1, int kind, int t,
                       uint8_t *written) {
  const ics_plan *P = j->p;
  int x0 = ics_tile_x0(&j->p->tiles, tx0), x1 = ics_tile_x1(&j->p->tiles, tx1);
  int y0 = ics_tile_y0(&j->p->tiles, ty), y1 = ics_tile_y1(&j->p->tiles, ty);
  int nch = j->chans[b], planes = kind == ICS_TILE_GREY ? 1 : nch;
  ics_prop_span(taps_of(j, b), j->src[b], j->dst[b], &P->buf, planes, y0, y1, x0, x1,
                j->scratch + (size_t)t * ICS_PROP_SCRATCH(P->Wb), j->simd);
  if (planes < nch) ics_tile_copy_grey(&P->buf, j->dst[b], nch, x0, x1, y0, y1);
  j->active[t] += (double)(x1 - x0) * (y1 - y0) * planes;
  memset(written + tx0, planes < nch ? 4 : 2, (size_t)(tx1 - tx0 + 1));
}

/* 1 when source tiles [tx0, tx1] x [ty0, ty1] of second-set buffer b all equal the first set's */
static int mirrors(const job_t *j, int b, int tx0, int tx1, int ty0, int ty1) {
  for (int ty = ty0; ty <= ty1; ty++)
    for (int tx = tx0; tx <= tx1; tx++)
      if (!j->ssrc[b][(size_t)ty * j->p->tiles.nx + tx]) return 0;
  return 1;
}

/* Row ty of tiles of buffered light b's buffer at this slab: within the light's active region
 * and its needed tiles (active_region.h), each tile whose reads all lie in tiles of one constant
 * gets that constant (written only where the buffer does not hold it already: flagged 1 in
 * written), the others are stepped, consecutive ones of a kind as one span; render.dense steps
 * every tile. */
static void propagate_row(job_t *j, int b, int ty, int t, uint8_t *written) {
  const ics_plan *P = j->p;
  const ics_tile_grid *g = &j->p->tiles;
  int l = b % P->nlights;
  const ics_rect *R = ics_active_region(P, l, j->k);
  if (ty < ics_tile_row(g, R->y0) || ty > ics_tile_row(g, R->y1 - 1)) return;
  int y0 = ics_tile_y0(g, ty), y1 = ics_tile_y1(g, ty), fy0, fy1;
  ics_prop_footprint(taps_of(j, b), 1, y0, y1, &fy0, &fy1);
  fy0 = ics_tile_row(g, fy0), fy1 = ics_tile_row(g, fy1);
  int run = -1, run_kind = ICS_TILE_ANY, tx1 = ics_tile_col(g, R->x1 - 1);
  const int32_t *last = P->tile_last + (size_t)b * g->nx * g->ny + (size_t)ty * g->nx;
  for (int tx = ics_tile_col(g, R->x0); tx <= tx1; tx++) {
    ics_tile *d = &j->tdst[b][(size_t)ty * g->nx + tx], want = {ICS_TILE_ANY, {0, 0, 0}};
    if (last[tx] < j->k) { /* not needed any more: left as it is */
      if (run >= 0) step_tiles(j, b, ty, run, tx - 1, run_kind, t, written);
      run = -1;
      continue;
    }
    if (!P->rs.dense) {
      int fx0, fx1;
      ics_prop_footprint(taps_of(j, b), 0, ics_tile_x0(g, tx), ics_tile_x1(g, tx), &fx0, &fx1);
      fx0 = ics_tile_col(g, fx0), fx1 = ics_tile_col(g, fx1);
      if (j->role[b] == ICS_SET_PATEL && mirrors(j, b, fx0, fx1, fy0, fy1)) {
        /* every read equals the first set's: the step's result is the first set's (this row's
         * first-set tiles are stepped already), copied */
        if (run >= 0) step_tiles(j, b, ty, run, tx - 1, run_kind, t, written);
        run = -1;
        const ics_tile *first = &j->tdst[b - P->nlights][(size_t)ty * g->nx + tx];
        if (!ics_tile_same_const(d, first, P->nch)) /* (a constant it holds already: no copy) */
          ics_tile_copy(&P->buf, j->dst[b - P->nlights], j->dst[b], P->nch, ics_tile_x0(g, tx),
                        ics_tile_x1(g, tx), y0, y1);
        *d = *first;
        written[tx] = 3;
        continue;
      }
      want = ics_tile_classify(g, j->tsrc[b], j->chans[b], fx0, fx1, fy0, fy1);
    }
    if (run >= 0 && (want.kind == ICS_TILE_CONST || want.kind != run_kind)) {
      step_tiles(j, b, ty, run, tx - 1, run_kind, t, written);
      run = -1;
    }
    if (want.kind == ICS_TILE_CONST) {
      if (!ics_tile_same_const(d, &want, j->chans[b])) {
        ics_tile_fill(&P->buf, j->dst[b], j->chans[b], ics_tile_x0(g, tx), ics_tile_x1(g, tx), y0, y1,
                      &want);
        written[tx] = 1;
      }
    } else if (run < 0) {
      run = tx, run_kind = want.kind;
    }
    *d = want;
  }
  if (run >= 0) step_tiles(j, b, ty, run, tx1, run_kind, t, written);
}

/* 1 when a tile of the row has a mark */
static int any_mark(const uint8_t *m, int n) {
  for (int i = 0; i < n; i++)
    if (m[i]) return 1;
  return 0;
}

/* after shading: signed weights can ring (values outside [0, 1] that the slabs amplify), so
 * those lights' buffers are clamped; the tiles stepped or shaded into are scanned for what they
 * hold (a stepped tile is often still constant: so the constants do not erode a tile a slab);
 * the apron is refreshed where an edge tile was written (elsewhere it holds its edge already),
 * above the first row and below the last where a tile of theirs was: by the thread settling
 * that row (nothing reads dst's apron before the next slab) */
static void settle_row(job_t *j, int ty, const uint8_t *marks) {
  const ics_plan *P = j->p;
  const ics_tile_grid *g = &j->p->tiles;
  int y0 = ics_tile_y0(g, ty), y1 = ics_tile_y1(g, ty);
  for (int b = 0; b < j->nb; b++) {
    int signed_ = ics_plan_set_kernel(P, b)->comp == ICS_RC_SIGNED;
    if (signed_)
      for (int c = 0; c < j->chans[b]; c++)
        for (int y = y0; y < y1; y++) {
          float *row = j->dst[b] + (size_t)c * P->buf.plane + ics_buf_index(&P->buf, 0, y);
          for (int x = 0; x < P->Wb; x++) row[x] = row[x] < 0 ? 0 : row[x] > 1 ? 1 : row[x];
        }
    const uint8_t *shaded = marks, *written = marks + (size_t)(1 + b) * g->nx;
    for (int tx = 0; tx < g->nx && !P->rs.dense; tx++) { /* (dense: nothing reads the states) */
      size_t i = (size_t)ty * g->nx + tx;
      int x0 = ics_tile_x0(g, tx), x1 = ics_tile_x1(g, tx);
      if (shaded[tx] || written[tx] == 2 || written[tx] == 4 || signed_)
        j->tdst[b][i] = ics_tile_scan(&P->buf, j->dst[b], j->chans[b], x0, x1, y0, y1,
                                      written[tx] == 4 && !shaded[tx] && !signed_);
      if (j->role[b] != ICS_SET_PATEL) continue;
      /* the second set: a copied tile shading left alone still equals the first set's (and
       * holds what it holds, scanned there); a tile either set wrote is compared */
      const uint8_t *written0 = marks + (size_t)(1 + b - P->nlights) * g->nx;
      if (written[tx] == 3 && !shaded[tx] && !signed_) {
        j->tdst[b][i] = j->tdst[b - P->nlights][i];
        j->sdst[b][i] = 1;
      } else if (written[tx] || shaded[tx] || written0[tx] || signed_) {
        /* two tiles of one constant are equal without a read (the scans above are exact) */
        const ics_tile *t0 = &j->tdst[b - P->nlights][i];
        j->sdst[b][i] = ics_tile_same_const(&j->tdst[b][i], t0, P->nch) ||
                        ics_tile_equal(&P->buf, j->dst[b], j->dst[b - P->nlights], P->nch, x0,
                                       x1, y0, y1);
      }
    }
    int last = g->nx - 1, sides = shaded[0] || written[0] || shaded[last] || written[last] || signed_;
    int edges = (ty == 0 ? ICS_APRON_TOP : 0) | (ty == g->ny - 1 ? ICS_APRON_BOTTOM : 0);
    if (edges && !signed_ && !any_mark(shaded, g->nx) && !any_mark(written, g->nx))
      edges = 0; /* the edge row as it was, and its apron with it */
    if (sides || edges) ics_prop_apron(&P->buf, j->dst[b], j->chans[b], y0, sides ? y1 : y0, edges);
  }
}

static void slab_job(void *ctx, int t, int n) {
  job_t *j = ctx;
  const ics_plan *P = j->p;
  size_t nx = (size_t)P->tiles.nx;
  uint8_t *marks = j->marks + (size_t)t * (1 + (size_t)j->nb) * nx;
  (void)n;
  for (int ty; (ty = atomic_fetch_add(&j->next_row, 1)) < P->tiles.ny;) {
    double t0 = ics_clock_s();
    memset(marks, 0, (1 + (size_t)j->nb) * nx);
    for (int b = 0; b < j->nb; b++) propagate_row(j, b, ty, t, marks + (1 + (size_t)b) * nx);
    double t1 = ics_clock_s();
    shade_rows(j, ics_tile_y0(&j->p->tiles, ty), ics_tile_y1(&j->p->tiles, ty), t, marks);
    settle_row(j, ty, marks);
    j->prop_s[t] += t1 - t0;
    j->shade_s[t] += ics_clock_s() - t1;
  }
}

/* the render's start, a band of every array per thread (their pages touched on every thread):
 * the view cleared; both ping-pong buffers lit (1; the moment 0) and saying so, so that a pixel
 * outside the active regions keeps a value; the sets equal; each pixel's cursors at its first
 * fragment, its volumes those its ray starts inside, and its next slab to look at */
static void start_job(void *ctx, int t, int n) {
  job_t *j = ctx;
  const ics_plan *P = j->p;
  const ics_ldi *ldi = &P->ldi;
  size_t ntiles = (size_t)P->tiles.nx * P->tiles.ny;
  size_t npx = (size_t)P->Wb * P->Hb, nimg = 4 * (size_t)P->W * P->H;
  /* the view, transparent black, written before shading reads it: a fresh page read first maps
   * the shared zero page, and the write after it faults again and flushes every thread's TLB */
  memset(j->img->data + nimg * t / n, 0, sizeof(float) * (nimg * (t + 1) / n - nimg * t / n));
  for (size_t i = npx * t / n; i < npx * (t + 1) / n; i++) {
    j->cursor[i] = j->acursor[i] = ldi->offset[i];
    if (j->mask) j->mask[i] = ldi->inside0 ? ldi->inside0[i] : 0;
    j->pnext[i] = j->mask && j->mask[i]               ? 0
                  : ldi->offset[i] < ldi->offset[i + 1] ? ics_frag_slab(&ldi->frag[ldi->offset[i]])
                                                        : INT_MAX;
  }
  for (int i = 0; i < 2 * j->nb; i++) {
    float v0 = j->role[i % j->nb] == ICS_SET_MOMENT ? 0.0f : 1.0f;
    const ics_tile lit = {ICS_TILE_CONST, {v0, v0, v0}};
    float *buf = i < j->nb ? j->src[i] : j->dst[i - j->nb];
    size_t size = (size_t)j->chans[i % j->nb] * P->buf.plane;
    ics_tile *tiles = i < j->nb ? j->tsrc[i] : j->tdst[i - j->nb];
    uint8_t *same = i < j->nb ? j->ssrc[i] : j->sdst[i - j->nb];
    for (size_t x = size * t / n; x < size * (t + 1) / n; x++) buf[x] = v0;
    for (size_t x = ntiles * t / n; x < ntiles * (t + 1) / n; x++) tiles[x] = lit, same[x] = 1;
  }
}

/* perspective: each kernel's classes compensated, the threads taking a share of every kernel's
 * (the split does not change the taps) */
static void classes_job(void *ctx, int t, int n) {
  job_t *j = ctx;
  const int ncls = ICS_PROP_CLASSES * ICS_PROP_CLASSES;
  for (int i = 0; i < j->nk; i++)
    if (j->pending[i] >= 0 &&
        ics_prop_perspective_classes(&j->pt[i], j->taps[i], j->pending[i], t * ncls / n, (t + 1) * ncls / n))
      j->failed = 1;
}

/* this slab's shading rectangle: the lights' active regions joined (a pixel outside it is never
 * needed again: the regions only shrink) */
static ics_rect shade_rect(const ics_plan *P, int k) {
  ics_rect u = {P->Wb, P->Hb, 0, 0};
  for (int l = 0; l < P->nlights; l++) ics_rect_join(&u, ics_active_region(P, l, k));
  if (!P->nlights) u = (ics_rect){0, 0, P->Wb, P->Hb};
  return u;
}

/* the renderer's state: its threads, and the memory of its last frame's arrays, kept for the
 * next (memory taken again spares the page faults of fresh pages: docs/renderer.md "Speed") */
typedef struct {
  ics_pool *pool;
  char *mem;
  size_t cap;
} cpu_state;

static ics_status cpu_create(void **state, const ics_render_opts *opts, char *msg,
                             size_t msg_size) {
  cpu_state *st = calloc(1, sizeof *st);
  if (!st) return ICS_ERR_NOMEM;
  ics_status s = ics_backend_pool_create((void **)&st->pool, opts, msg, msg_size);
  if (s != ICS_OK) free(st);
  else *state = st;
  return s;
}

static void cpu_destroy(void *state) {
  cpu_state *st = state;
  if (!st) return;
  ics_backend_pool_destroy(st->pool);
  free(st->mem);
  free(st);
}

/* the next `bytes` of the arena at *used (64-byte aligned, and under AddressSanitizer after a
 * guard), NULL while only measuring (base NULL); under AddressSanitizer everything between it
 * and the array before is poisoned, so that an overrun or underrun into a neighbour is reported
 * as one into another allocation's redzone was */
static void *take(char *base, size_t *used, size_t bytes) {
  size_t at = (*used + ARENA_GUARD + 63) & ~(size_t)63;
  if (base) ASAN_POISON_MEMORY_REGION(base + *used, at - *used);
  *used = at + bytes;
  return base ? base + at : NULL;
}

/* the frame's arrays, carved from base (NULL: only their size); returns the bytes taken */
static size_t carve(job_t *j, char *base, int nt, float **bufs, ics_tile **tiles, uint8_t **sames) {
  const ics_plan *P = j->p;
  size_t npx = (size_t)P->Wb * P->Hb, used = 0, nx = (size_t)P->tiles.nx;
  size_t ntiles = nx * (size_t)P->tiles.ny;
  for (int i = 0; i < 2 * j->nb; i++) {
    bufs[i] = take(base, &used, sizeof(float) * (size_t)j->chans[i % j->nb] * P->buf.plane);
    tiles[i] = take(base, &used, sizeof(ics_tile) * ntiles);
    sames[i] = take(base, &used, ntiles);
  }
  j->marks = take(base, &used, nx * (1 + (size_t)j->nb) * (size_t)nt);
  j->dpts = P->any_detail ? take(base, &used, sizeof *j->dpts * 8 * (size_t)P->Wb * nt) : NULL;
  j->dslot = P->any_detail ? take(base, &used, sizeof *j->dslot * (size_t)P->Wb * nt) : NULL;
  int lone = P->ninside && j->lone_batched;
  j->prow = lone ? take(base, &used, sizeof *j->prow * 10 * (size_t)P->Wb * nt) : NULL;
  j->lone_mark = lone ? take(base, &used, (size_t)P->Wb * nt) : NULL;
  j->cursor = take(base, &used, sizeof *j->cursor * npx);
  j->acursor = take(base, &used, sizeof *j->acursor * npx);
  j->pnext = take(base, &used, sizeof *j->pnext * npx);
  j->scratch = take(base, &used, sizeof *j->scratch * ICS_PROP_SCRATCH(P->Wb) * (size_t)nt);
  j->seg_next = take(base, &used, sizeof *j->seg_next * (size_t)P->Hb * nx);
  j->mask = P->ninside ? take(base, &used, sizeof *j->mask * npx) : NULL;
  j->aov_seen = j->aov ? take(base, &used, (size_t)P->W * P->H) : NULL;
  return used;
}

/* the frame's arrays (j->src, ...; seg_next and aov_seen zeroed) in the state's memory, grown
 * when the frame needs more and renewed when it needs less than half (a small frame after a
 * large one does not keep the large one's memory); 0, or -1 when out of memory */
static int frame_arrays(cpu_state *st, job_t *j, int nt) {
  size_t bytes = carve(j, NULL, nt, j->src, j->tsrc, j->ssrc);
  if (st->mem) ASAN_UNPOISON_MEMORY_REGION(st->mem, st->cap); /* the last frame's guards */
  if (bytes > st->cap || bytes < st->cap / 2) {
    free(st->mem);
    st->cap = 0;
    st->mem = malloc(bytes ? bytes : 1);
    if (!st->mem) return -1;
    st->cap = bytes;
  }
  carve(j, st->mem, nt, j->src, j->tsrc, j->ssrc);
  ASAN_POISON_MEMORY_REGION(st->mem + bytes, st->cap - bytes); /* a larger frame's rest */
  /* seg_next 0: look at every segment first */
  memset(j->seg_next, 0, sizeof *j->seg_next * (size_t)j->p->Hb * j->p->tiles.nx);
  if (j->aov_seen) memset(j->aov_seen, 0, (size_t)j->p->W * j->p->H);
  return 0;
}

static ics_status cpu_render(void *state, const ics_plan *P, const ics_render_opts *o,
                             ics_image *img, ics_aov_buf *aov, ics_render_stats *stats, char *msg,
                             size_t msg_size) {
  cpu_state *st = state;
  ics_pool *pool = st->pool;
  double t_start = ics_clock_s();
  int nl = P->nlights, nt = ics_pool_size(pool), nb = nl * ics_plan_light_sets(P);
  int nk = P->kernels_sharp ? 2 * nl : nl; /* kernels: each light's, then its sharp set's */
  size_t plane = (size_t)P->Wb * P->Hb, npx = plane;
  job_t *j = calloc(1, sizeof *j);
  float **bufs = calloc(2 * (size_t)(nb ? nb : 1), sizeof *bufs);
  ics_tile **tiles = calloc(2 * (size_t)(nb ? nb : 1), sizeof *tiles);
  uint8_t **sames = calloc(2 * (size_t)(nb ? nb : 1), sizeof *sames);
  ics_tap2d **scratch = calloc((size_t)(nk ? nk : 1), sizeof *scratch);
  double(*cum)[2] = calloc((size_t)(nk ? nk : 1), sizeof *cum);
  ics_set_role *role = calloc((size_t)(nb ? nb : 1), sizeof *role);
  ics_status status = ICS_OK;
  if (!j || !bufs || !tiles || !sames || !scratch || !cum || !role) goto nomem;
  status = ics_simd_choose(&j->simd, msg, msg_size);
  if (status != ICS_OK) goto done;
  /* the lone volume pieces a row at a time on a vector path (ICS_PIECE_BATCH=0: one by one, as
   * the portable path does, to compare: docs/renderer.md "Volume pieces in batches") */
  const char *batch = getenv("ICS_PIECE_BATCH");
  if (batch && *batch && strcmp(batch, "0") && strcmp(batch, "1")) {
    if (msg)
      snprintf(msg, msg_size, "ICS_PIECE_BATCH=%.40s: 0 (the lone volume pieces one by one) or 1 "
               "(a row at a time on a vector path, the default)", batch);
    status = ICS_ERR_INVALID_ARG;
    goto done;
  }
  j->lone_batched = j->simd != ICS_SIMD_SCALAR && !(batch && !strcmp(batch, "0"));
  j->p = P;
  j->img = img;
  j->nb = nb;
  j->nk = nk;
  j->taps = scratch;
  j->role = role;
  j->moment = P->rs.model >= ICS_MODEL_BLOCKER;
  for (int b = 0; b < nb; b++) {
    role[b] = ics_plan_set_role(P, b / nl);
    j->chans[b] = ics_plan_set_channels(P, b / nl);
    if (role[b] == ICS_SET_PATEL) j->patel_set = b / nl;
    if (role[b] == ICS_SET_SHARP) j->sharp_set = b / nl;
  }
  j->src = bufs;
  j->dst = bufs + nb;
  j->tsrc = tiles;
  j->tdst = tiles + nb;
  j->ssrc = sames;
  j->sdst = sames + nb;
  j->pt = calloc((size_t)(nk ? nk : 1), sizeof *j->pt);
  j->aov = aov;
  if (!j->pt || frame_arrays(st, j, nt)) goto nomem;
  /* the largest pixel is the deepest slab's (perspective) */
  for (int l = 0; l < nl; l++) j->blur_world[l] = ics_plan_light_blur(P, l);
  j->window_max = ics_plan_window_max(P);
  j->blend_span = log(P->rs.d1 / (P->rs.d1 * ICS_BLOCKER_SHARP));
  for (int i = 0; i < P->scene->nobjects; i++)
    if (P->inside_bit[i] >= 0) j->vol_obj[P->inside_bit[i]] = i;
  ics_pool_run(pool, start_job, j);
  for (int i = 0; i < nk; i++) {
    const ics_slab_kernel *sk = i < nl ? &P->kernels[i] : &P->kernels_sharp[i - nl];
    scratch[i] = malloc(sizeof **scratch * (size_t)sk->entries * (size_t)sk->cap);
    if (!scratch[i]) goto nomem;
  }
  for (int k = 0; k < P->K; k++) {
    j->k = k;
    double s, q = ics_plan_slab_pixel(P, k, &s);
    for (int l = 0; l < nl; l++) {
      j->window[l] = fmax(0, 1 - j->blur_world[l] / q);
      j->window[nl + l] = fmax(0, 1 - j->blur_world[l] * sqrt(ICS_BLOCKER_SHARP) / q);
    }
    int pending[2 * ICS_SCENE_MAX_LIGHTS], any_pending = 0;
    for (int i = 0; i < nk; i++) {
      const ics_slab_kernel *sk = i < nl ? &P->kernels[i] : &P->kernels_sharp[i - nl];
      pending[i] = -1;
      status = ics_plan_kernel_taps_deferred(P, sk, i % nl, k, q, s, cum[i], scratch[i], &j->pt[i],
                                             &pending[i], msg, msg_size);
      if (status == ICS_ERR_NOMEM) goto nomem;
      if (status != ICS_OK) goto done;
      any_pending |= pending[i] >= 0;
    }
    if (any_pending) { /* a perspective step's classes, on every thread */
      j->pending = pending;
      ics_pool_run(pool, classes_job, j);
      if (j->failed) goto nomem;
      for (int i = 0; i < nk; i++)
        if (pending[i] >= 0) ics_prop_perspective_end(&j->pt[i]);
    }
    j->shade = shade_rect(P, k);
    piece_params(j, k);
    atomic_store(&j->next_row, 0);
    ics_pool_run(pool, slab_job, j);
    if (j->failed) goto nomem;
    for (int b = 0; b < nb; b++) {
      float *tmp = j->src[b];
      j->src[b] = j->dst[b];
      j->dst[b] = tmp;
      ics_tile *tt = j->tsrc[b];
      j->tsrc[b] = j->tdst[b];
      j->tdst[b] = tt;
      uint8_t *ts = j->ssrc[b];
      j->ssrc[b] = j->sdst[b];
      j->sdst[b] = ts;
    }
    if (o->progress) o->progress(o->progress_ctx, k + 1, P->K);
  }
  ics_plan_over_background(P, img);
  stats->threads = nt;
  stats->slabs = P->K;
  snprintf(stats->device, sizeof stats->device, "CPU, %d thread%s, %s", nt, nt == 1 ? "" : "s",
           ics_simd_name(j->simd));
  snprintf(stats->simd, sizeof stats->simd, "%s", ics_simd_name(j->simd));
  for (int t = 0; t < nt; t++) {
    stats->ms_convolution += 1e3 * j->prop_s[t] / nt;
    stats->ms_shading += 1e3 * j->shade_s[t] / nt;
    stats->ms_detail += 1e3 * j->detail_s[t] / nt;
    stats->updates_active += j->active[t];
  }
  for (int b = 0; b < nb; b++) stats->updates_dense += (double)npx * P->K * j->chans[b];
  if (nb && P->K)
    stats->ns_per_px_slab = 1e6 * stats->ms_convolution / ((double)npx * P->K * nb);
  stats->ms_total = 1e3 * (ics_clock_s() - t_start);
  goto done;
nomem:
  status = ICS_ERR_NOMEM;
  if (msg) snprintf(msg, msg_size, "out of memory for the light buffers (%zu bytes)", P->backend_bytes);
done:
  if (j && j->pt)
    for (int i = 0; i < nk; i++) ics_prop_release(&j->pt[i]);
  if (scratch)
    for (int i = 0; i < nk; i++) free(scratch[i]);
  if (j) {
    free(j->pt);
    for (int t = 0; t < 256; t++) ics_hits_free(&j->hits[t]);
  }
  free(bufs);
  free(tiles);
  free(sames);
  free(scratch);
  free(cum);
  free(role);
  free(j);
  return status;
}

const ics_backend ics_backend_cpu = {
    "cpu", "the slab renderer on the CPU (threads; always built)",
    ICS_AOV_VISIBILITY | ICS_AOV_DEPTH, ICS_MODELS_ALL, ICS_MODEL_BLOCKER,
    {ics_backend_always_available, NULL, cpu_create, cpu_render, cpu_destroy},
    NULL};
