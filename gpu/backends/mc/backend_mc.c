/* backend_mc.c — the Monte-Carlo reference as a backend ("mc", docs/reference.md): progressive
 * passes of one sample per pixel (mc_trace.c) over the worker pool (rows t, t + n, ...), the
 * per-pixel mean and standard error of the mean (Welford), until a sample count, a time or a
 * noise level is reached. Sample s of pixel p draws from the counter RNG's stream
 * (tag, p, s) under the scene's seed, so the image depends on the seed and the sample count
 * only, never on the thread count. A pass is written into its own buffer and merged once every
 * pixel has its sample, so a pass cut short by --time (checked inside the paths) leaves the
 * accumulators as they were. Before any work, the tracking steps are held to a budget
 * (check_work). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "clock.h"
#include "mc_trace.h"
#include "pool.h"
#include "scene_internal.h"

#define MC_STREAM_TAG 0x6dULL          /* "m", in the stream's top byte */
#define MC_MAX_SPP (1 << 24)           /* samples per pixel: the stream's low 24 bits */
#define MC_DEFAULT_SPP 64
/* expected volume tracking steps of a render (each a detail evaluation, 20-200 ns here: minutes
 * to an hour on 2 cores) */
#define MC_STEP_BUDGET 2e10

typedef struct {
  const mc_scene *m;
  mc_thread *th;   /* per thread */
  int *failed;     /* per thread */
  int n;           /* samples per pixel before this pass */
  int nv;          /* visibility values per pixel (lights x buffer channels), 0: none asked */
  double *mean, *m2;   /* per pixel: R, G, B, A, then nv visibility values */
  double *cur;         /* per pixel: this pass's sample, the same values */
  float *z;            /* per pixel: first-surface depth (0: none) */
  uint8_t *surface;    /* per pixel: a first surface was found */
} pass_t;

static void pass_job(void *ctx, int t, int nt) {
  pass_t *ps = ctx;
  const ics_plan *P = ps->m->P;
  int per = 4 + ps->nv, nch = P->nch;
  mc_sample smp;
  for (int j = t; j < P->H && !ps->failed[t]; j += nt)
    for (int i = 0; i < P->W; i++) {
      size_t p = (size_t)j * P->W + i;
      ics_rng r;
      ics_rng_init(&r, P->rs.seed, MC_STREAM_TAG << 56 | (uint64_t)p << 24 | (uint64_t)ps->n);
      if (mc_pixel_sample(&ps->th[t], ps->m, i, j, ps->nv > 0, &r, &smp)) {
        ps->failed[t] = ps->th[t].late ? 2 : 1;
        return;
      }
      double *x = ps->cur + p * per;
      memcpy(x, smp.rgba, sizeof smp.rgba);
      for (int l = 0; l < ps->nv / (nch ? nch : 1); l++)
        for (int c = 0; c < nch; c++) x[4 + l * nch + c] = smp.surface ? smp.vis[l][c] : 0;
      if (smp.surface) ps->surface[p] = 1, ps->z[p] = (float)smp.z;
    }
}

/* a complete pass into the per-pixel mean and sum of squares (Welford) */
static void pass_merge(pass_t *ps, size_t npx) {
  int per = 4 + ps->nv;
  double k = ps->n + 1;
  for (size_t i = 0; i < npx * (size_t)per; i++) {
    double d = ps->cur[i] - ps->mean[i];
    ps->mean[i] += d / k;
    ps->m2[i] += d * (ps->cur[i] - ps->mean[i]);
  }
}

/* The tracking steps a render may take, before it starts. Steps finer than a position's double
 * precision (majorant x size of a volume above 2^50) cannot advance a walk: refused always. Past
 * that, without --time (a hard stop) the bound of the steps (mc_steps_per_ray x rays x pixels x
 * samples) is held to MC_STEP_BUDGET. Rays per sample: the camera's and, per light, one from the
 * end of the walk and one from each surface that lets light on (opacity below 1). ICS_ERR_RANGE
 * with the estimate and what to change. */
static ics_status check_work(const mc_scene *m, size_t npx, int spp, const ics_render_opts *o,
                             char *msg, size_t msg_size) {
  const ics_scene *s = m->s;
  int translucent = 0;
  for (int i = 0; i < s->nobjects; i++) {
    double op = s->materials[s->objects[i].material].opacity;
    translucent += m->majorant[i] == 0 && op > 0 && op < 1;
  }
  double per_ray = mc_steps_per_ray(m), rays = 1 + (double)m->P->nlights * (2 + translucent);
  if (!(per_ray <= 0x1p50)) {
    if (msg)
      snprintf(msg, msg_size, "mc: %.3g tracking steps per ray through the volumes with detail "
               "(their extinction bound x size): steps that small cannot advance a position in "
               "double precision; lower the extinction or the detail's scale", per_ray);
    return ICS_ERR_RANGE;
  }
  double work = per_ray * rays * (double)npx * spp;
  if (o->time_s > 0 || work <= MC_STEP_BUDGET) return ICS_OK;
  if (msg)
    snprintf(msg, msg_size, "mc: up to %.3g volume tracking steps (%.3g per ray: extinction bound "
             "x size of the volumes with detail; %.3g rays a sample, %zu pixels, %d sample%s) is "
             "above the budget of %.0e (about an hour here): give --time S (a hard stop), or "
             "lower the extinction, the resolution or --spp", work, per_ray, rays, npx, spp,
             spp == 1 ? "" : "s", MC_STEP_BUDGET);
  return ICS_ERR_RANGE;
}

/* RMS over pixels and R, G, B of the standard error of the mean after n samples */
static double noise_of(const pass_t *ps, size_t npx, int n) {
  if (n < 2) return INFINITY;
  int per = 4 + ps->nv;
  double sum = 0;
  for (size_t p = 0; p < npx; p++)
    for (int c = 0; c < 3; c++) sum += ps->m2[p * per + c] / ((double)(n - 1) * n);
  return sqrt(sum / (3.0 * (double)npx));
}

static ics_status mc_render(void *state, const ics_plan *P, const ics_render_opts *o,
                            ics_image *img, ics_aov_buf *aov, ics_render_stats *stats, char *msg,
                            size_t msg_size) {
  ics_pool *pool = state;
  double t_start = ics_clock_s();
  int nt = ics_pool_size(pool);
  size_t npx = (size_t)P->W * P->H;
  if (o->spp < 0 || o->spp > MC_MAX_SPP || !(o->time_s >= 0) || !(o->noise >= 0) ||
      isinf(o->time_s) || isinf(o->noise)) {
    if (msg) snprintf(msg, msg_size, "mc: samples per pixel must be in 0..%d, time and noise "
                      "finite and >= 0 (got %d, %g, %g)", MC_MAX_SPP, o->spp, o->time_s, o->noise);
    return ICS_ERR_INVALID_ARG;
  }
  if (aov && aov->err >= 0 && o->spp == 1) {
    if (msg) snprintf(msg, msg_size, "mc: a standard error needs at least 2 samples per pixel");
    return ICS_ERR_INVALID_ARG;
  }
  int spp = o->spp, stop_by_count = spp > 0;
  if (spp == 0 && !(o->time_s > 0) && !(o->noise > 0)) spp = MC_DEFAULT_SPP, stop_by_count = 1;
  if (!stop_by_count) spp = MC_MAX_SPP;
  char ver[32] = "", why[1024] = "";
  int embree = 0; /* Embree's module is loaded only for a scene with meshes */
  if (o->mc_mesh && strcmp(o->mc_mesh, "auto") && strcmp(o->mc_mesh, "embree") &&
      strcmp(o->mc_mesh, "bvh")) {
    if (msg) snprintf(msg, msg_size, "mc: mesh crossings '%s': expected auto, embree or bvh", o->mc_mesh);
    return ICS_ERR_INVALID_ARG;
  }
  int want = !o->mc_mesh || strcmp(o->mc_mesh, "bvh");
  if (want && P->scene->nmeshes) embree = mc_embree_available(ver, sizeof ver, why, sizeof why);
  if (o->mc_mesh && !strcmp(o->mc_mesh, "embree") && P->scene->nmeshes && !embree) {
    if (msg) snprintf(msg, msg_size, "mc: meshes through Embree: %s", why);
    return ICS_ERR_UNSUPPORTED;
  }
  pass_t ps = {0};
  mc_scene m;
  ics_status status = mc_scene_init(&m, P, embree ? nt : 0, msg, msg_size);
  if (status != ICS_OK) return status;
  ps.m = &m;
  ps.nv = aov && aov->vis >= 0 ? P->nlights * P->nch : 0;
  int per = 4 + ps.nv;
  ps.th = calloc((size_t)nt, sizeof *ps.th);
  ps.failed = calloc((size_t)nt, sizeof *ps.failed);
  ps.mean = calloc(npx * (size_t)per, sizeof *ps.mean);
  ps.m2 = calloc(npx * (size_t)per, sizeof *ps.m2);
  ps.cur = malloc(npx * (size_t)per * sizeof *ps.cur);
  ps.z = calloc(npx, sizeof *ps.z);
  ps.surface = calloc(npx, 1);
  if (!ps.th || !ps.failed || !ps.mean || !ps.m2 || !ps.cur || !ps.z || !ps.surface) goto nomem;
  /* a noise stop alone: one pass is what can be bounded (docs: bound --noise with --time) */
  if ((status = check_work(&m, npx, stop_by_count ? spp : 1, o, msg, msg_size)) != ICS_OK)
    goto done;
  for (int t = 0; t < nt; t++) ps.th[t].deadline = o->time_s > 0 ? t_start + o->time_s : 0;
  int n = 0, late = 0;
  double noise = INFINITY;
  while (n < spp && !late) {
    ps.n = n;
    ics_pool_run(pool, pass_job, &ps);
    for (int t = 0; t < nt; t++) {
      if (ps.failed[t] == 1) goto nomem;
      late |= ps.failed[t] == 2;
    }
    if (late) break; /* the pass is incomplete: not merged */
    pass_merge(&ps, npx);
    n++;
    if (o->progress) o->progress(o->progress_ctx, n, stop_by_count ? spp : 0);
    if (o->noise > 0 || n == spp) noise = noise_of(&ps, npx, n);
    if (n < 2) continue; /* a standard error needs 2 samples; past the deadline the next pass
                            stops at its first pixel */
    if (o->noise > 0 && noise <= o->noise) break;
    if (o->time_s > 0 && ics_clock_s() - t_start >= o->time_s) break;
  }
  if (n == 0) {
    status = ICS_ERR_RANGE;
    if (msg)
      snprintf(msg, msg_size, "mc: no sample of every pixel finished within --time %g s (up to "
               "%.3g volume tracking steps per ray): give more time, or lower the extinction or "
               "the resolution", o->time_s, mc_steps_per_ray(&m));
    goto done;
  }
  if (!(o->noise > 0) && n != spp) noise = noise_of(&ps, npx, n);
  for (size_t p = 0; p < npx; p++)
    for (int c = 0; c < 4; c++) img->data[p * 4 + c] = (float)ps.mean[p * per + c];
  if (aov) {
    for (size_t p = 0; p < npx; p++) {
      float *a = aov->data + p * (size_t)aov->count;
      const double *mu = ps.mean + p * per, *m2 = ps.m2 + p * per;
      for (int v = 0; aov->vis >= 0 && v < ps.nv; v++) a[aov->vis + v] = (float)mu[4 + v];
      if (aov->z >= 0) a[aov->z] = ps.surface[p] ? ps.z[p] : 0;
      for (int c = 0; aov->err >= 0 && c < per; c++)
        a[aov->err + c] = n > 1 ? (float)sqrt(m2[c] / ((double)(n - 1) * n)) : 0;
    }
  }
  stats->threads = nt;
  stats->slabs = 0;
  stats->spp = n;
  stats->noise = n > 1 ? noise : NAN;
  snprintf(stats->device, sizeof stats->device, "CPU, %d thread%s (Monte Carlo%s%s)", nt, nt == 1 ? "" : "s",
           !P->scene->nmeshes ? "" : m.embree ? "; meshes: Embree " : "; meshes: own BVH",
           P->scene->nmeshes && m.embree ? ver : "");
  stats->ms_total = 1e3 * (ics_clock_s() - t_start);
  stats->ms_shading = stats->ms_total;
  goto done;
nomem:
  status = ICS_ERR_NOMEM;
  if (msg) snprintf(msg, msg_size, "out of memory for the Monte-Carlo accumulators (%zu pixels)", npx);
done:
  for (int t = 0; ps.th && t < nt; t++) mc_thread_release(&ps.th[t]);
  free(ps.th);
  free(ps.failed);
  free(ps.mean);
  free(ps.m2);
  free(ps.cur);
  free(ps.z);
  free(ps.surface);
  mc_scene_release(&m);
  return status;
}

const ics_backend ics_backend_mc = {
    "mc", "the Monte-Carlo reference: exact shadows by light sampling, delta and ratio tracking "
          "(CPU threads; always built; never chosen by auto)",
    /* the reference is the truth every model approximates: it renders them all alike, and auto
     * takes the plan that costs least */
    ICS_AOV_VISIBILITY | ICS_AOV_DEPTH | ICS_AOV_STDERR, ICS_MODELS_ALL, ICS_MODEL_PATEL,
    {ics_backend_always_available, NULL, ics_backend_pool_create, mc_render,
     ics_backend_pool_destroy},
    NULL};
