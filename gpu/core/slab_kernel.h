/* slab_kernel.h — the convolution kernel of one light for each slab (docs/renderer.md "The
 * light buffers"): the kernel class of Eq. 7/15 in buffer pixels, the member's taps, and the
 * interpolation-variance compensation, resolved once per light (the plan) and evaluated per
 * slab by the backends. The gather convention is the engine's (icshadow/conv.h): a slab step is
 * I1(p) = sum_j w_j I0(c + s (p - c) - x_j) with taps (x_j, w_j) in pixels (mean included),
 * s the perspective magnification (1 for orthographic cameras) and c the principal point. */
#ifndef ICS_RENDER_SLAB_KERNEL_H
#define ICS_RENDER_SLAB_KERNEL_H

#include <stdint.h>

#include "icshadow/kernel.h"
#include "icshadow/scene.h"
#include "slab_choice.h"


typedef enum ics_slab_mode {
  ICS_SLAB_SHIFT = 0, /* zero variance: one integer tap per slab (integer-shift schedule) */
  ICS_SLAB_INTEGER,   /* integer-shift schedule + exact integer taps (no interpolation) */
  ICS_SLAB_TAPS,      /* one tap set per slab, bilinear */
  ICS_SLAB_TABLE      /* a table of tap sets, one chosen per pixel by the counter RNG */
} ics_slab_mode;

/* The resolved kernel of one light. */
typedef struct ics_slab_kernel {
  int light;
  ics_render_kernel member;   /* what the scene asked for */
  int samples;
  ics_render_kernel run_member; /* what runs (a low-variance light falls back to a 3 x 3 Gaussian) */
  int run_samples;
  ics_render_comp comp;  /* what was asked (resolved default) */
  ics_slab_mode mode;    /* what runs */
  char why[160];         /* why this mode (plan JSON) */
  int lut_radii;
  uint64_t seed;
  double mean_w[2];      /* per-slab mean in world units along the buffer axes (x right, y down) */
  double cov_w[3];       /* per-slab covariance, world units^2, buffer axes */
  double mean_px[2], cov_px[3]; /* the same in pixels at the reference depth (orthographic: all) */
  double class_px[3];    /* the class handed to the taps after compensation (expected mode) */
  double residual[3];    /* compensation residual, pixels^2 (achieved - target), per slab */
  int taps;              /* taps per pixel (after discretisation for integer modes) */
  int cap;               /* capacity per entry that ics_slab_kernel_taps needs */
  int entries;           /* tap sets held in base (the stochastic members: ICS_SLAB_TABLE_M) */
  int out_entries;       /* tap sets ics_slab_kernel_taps returns per slab, of which each pixel
                            takes one (ICS_SLAB_TABLE: K = render.pixel_rotations distinct
                            entries from a random first, ics_slab_candidate_step apart; the other
                            modes: 1) */
  int reach_bound;       /* pixels a read can reach at the reference depth (buffer apron) */
  int integer;           /* offsets are integers (no bilinear read) */
  ics_tap2d *base;       /* TABLE / TAPS / INTEGER: entries * taps taps WITHOUT the mean (integer
                            modes: centred exact integer taps) */
  int base_taps;
  double q_ref;          /* the pixel size the kernel was resolved for */
  ics_tap2d *fixed;      /* deterministic nonneg / signed: the compensated taps at q_ref */
  int nfixed;
} ics_slab_kernel;

/* Resolves light `k` of the scene for pixel size q (world units per pixel at the reference
 * depth; for orthographic cameras the only one). ICS_OK, or an error with msg. */
ics_status ics_slab_kernel_init(ics_slab_kernel *sk, const ics_scene *s, int k, double q,
                                char *msg, size_t msg_size);
void ics_slab_kernel_release(ics_slab_kernel *sk);

/* Everything ics_slab_kernel_init reads, so that equal keys resolve to the same kernel
 * (kernel_cache.h): the light's index, mean and covariance, the pixel size, the projection and
 * the settings the kernel takes. Compared bit for bit (padding zeroed). */
typedef struct ics_slab_kernel_key {
  double mean[2], cov[3], q, slab_spacing, d1;
  uint64_t seed;
  int light, projection, kernel, samples, lut_radii, compensate, pixel_rotations;
} ics_slab_kernel_key;
void ics_slab_kernel_key_of(const ics_scene *s, int k, double q, ics_slab_kernel_key *key);
/* dst as a copy of src (its own taps); ICS_ERR_NOMEM leaves dst released */
ics_status ics_slab_kernel_copy(ics_slab_kernel *dst, const ics_slab_kernel *src);

/* Taps of slab `slab` for pixel size q (perspective: the slab's depth) into out (capacity
 * sk->entries * sk->cap; *nout gets the count); the mean is included. cum_mean[2] carries the integer-shift
 * schedule's cumulative mean between slabs (start at {0, 0}, update in place). */
ics_status ics_slab_kernel_taps(const ics_slab_kernel *sk, uint64_t slab, double q,
                                double cum_mean[2], ics_tap2d *out, int *nout);

/* max over a 33 x 33 grid of frequencies in [-pi, pi]^2 of |sum_j w_j exp(i w . x_j)|: 1 for
 * non-negative weights summing to 1, more when signed weights amplify a frequency. */
double ics_taps_amplification(const ics_tap2d *t, int n);

/* Entries between a slab's candidates: M / (K N) for the ellipse (its N taps are M / N apart, so
 * K candidates M / (K N) apart are K distinct tap sets), M / K for Poisson, 1 when K = M. */
int ics_slab_candidate_step(const ics_slab_kernel *sk);

#endif
