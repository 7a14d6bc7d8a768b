/* render_compare.h — `icshadow render --compare REF.exr` and `--reference N`: the render's
 * R, G, B against a reference image (a file, or the Monte-Carlo reference rendered in the same
 * run), with the reference's own time and noise where known, so error can be set against time.
 * docs/reference.md "Comparing a render with the reference". */
#ifndef ICS_CLI_RENDER_COMPARE_H
#define ICS_CLI_RENDER_COMPARE_H

#include <stdio.h>

#ifdef ICS_HAVE_RENDER
#include "icshadow/render.h"

typedef struct render_comparison {
  ics_image_diff d;
  ics_image *ref;        /* the reference's R, G, B (owned: render_comparison_release) */
  const char *reference; /* the file, or "mc" */
  char ref_backend[16];  /* "" when unknown */
  char ref_device[128];  /* the reference's device string ("... meshes: Embree 3.13.5"), "" when unknown */
  int ref_spp;           /* 0 when unknown */
  double ms_reference;   /* NAN when unknown */
  double ref_noise;      /* RMS standard error of the reference's R, G, B; NAN when unknown */
} render_comparison;

/* Compares img with the EXR at `path` (its R, G, B; its stderr.R/G/B for the noise; its
 * "icshadow" summary for the backend, samples and time). Returns 0, or the exit status after
 * the message (a missing or unreadable file, no R, G, B, another size: 2). */
int render_compare_file(const char *cmd, const char *path, const ics_image *img,
                        render_comparison *out);

/* Renders `plan` with the Monte-Carlo reference at spp samples per pixel on `threads` threads
 * (mc_mesh: ics_render_opts.mc_mesh; progress: ics_render_opts.progress, may be NULL) and
 * compares img with it. Returns 0, or the exit status after the message. */
int render_compare_mc(const char *cmd, const ics_plan *plan, int spp, int threads,
                      const char *mc_mesh, void (*progress)(void *, int, int), void *progress_ctx,
                      const ics_image *img, render_comparison *out);

void render_comparison_release(render_comparison *c);

/* A picture of render minus reference, mean over R, G, B, times `scale`: red where the render
 * is brighter, blue where it is darker, black where they agree (clamped at 1). NULL when out of
 * memory. */
ics_image *render_difference_image(const ics_image *img, const ics_image *ref, double scale);

/* The comparison as a JSON object's members, after ", \"compare\": ". */
void render_comparison_json(FILE *f, const render_comparison *c);
#endif

#endif
