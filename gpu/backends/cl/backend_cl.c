/* backend_cl.c — the "cl" backend: the slab renderer on an OpenCL 1.2 device (PoCL here; any
 * platform with cl_khr_fp64). Method and tolerances: docs/backend_cl.md.
 *
 * The host resolves each slab's taps exactly as the CPU backend does (ics_slab_kernel_taps, then
 * ics_prop_prepare or ics_prop_prepare_perspective) and uploads them; the device runs the two
 * kernels of slab.cl per slab: the tap-set choices and the step of every light buffer
 * (ics_entries_*, ics_prop_*), then ics_shade over the buffer pixels (occlusions, surface colours,
 * volumes, the clamp of signed kernels) and the apron (ics_apron_*). The layered depth image is
 * the plan's, built on the host and uploaded once, with the objects' materials, detail functions
 * (Perlin, fBm, ridged, grids) and transfer functions.
 *
 * The device is cl_device.c's choice (ICS_CL_DEVICE or the first GPU with fp64). The program is
 * built once per renderer
 * (PoCL caches the binary in POCL_CACHE_DIR across runs). Every OpenCL call is checked; a failure
 * names the call and the error code. */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "backend.h"
#include "cl_device.h"
#include "clock.h"
#include "device_scene.h"
#include "plan_internal.h"
#include "slab_choice.h"
#include "slab_taps.h"
#include "slab_cl_source.h" /* ics_slab_cl_source: gpu/backends/cl/slab.cl (cmake/embed_text.cmake) */

/* the wanted device (cl.device, else ICS_CL_DEVICE) and how to name it in messages */
static const char *wanted_device(const ics_render_opts *opts, const char **label) {
  const char *from, *want = ics_backend_option_value(ics_backend_find("cl"), opts, "device", &from);
  *label = from ? from : "cl.device";
  return want;
}

static int cl_available(const ics_render_opts *opts, char *why, size_t why_size) {
  const char *label, *want = wanted_device(opts, &label);
  return ics_cl_available(want, label, why, why_size);
}

typedef struct cl_state {
  ics_cl_dev d;
  cl_program prog;
  cl_kernel k[8]; /* KERNEL_NAMES, in that order */
} cl_state;

static const char *const KERNEL_NAMES[8] = {"ics_prop_stencil", "ics_prop_table",
                                            "ics_prop_classes", "ics_entries_pixel",
                                            "ics_entries_run", "ics_shade", "ics_apron_sides",
                                            "ics_apron_ends"};
enum { K_PROP = 0, K_ENTRIES = 3, K_SHADE = 5, K_APRON = 6 };

static void cl_destroy(void *state) {
  cl_state *s = state;
  if (!s) return;
  for (int i = 0; i < 8; i++)
    if (s->k[i]) clReleaseKernel(s->k[i]);
  if (s->prog) clReleaseProgram(s->prog);
  ics_cl_dev_close(&s->d);
  free(s);
}

static ics_status cl_create(void **state, const ics_render_opts *opts, char *msg, size_t msg_size) {
  *state = NULL;
  cl_state *s = calloc(1, sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  char why[2048];
  const char *label, *want = wanted_device(opts, &label);
  ics_status st = ics_cl_dev_open(&s->d, want, label, why, sizeof why);
  if (st == ICS_OK)
    st = ics_cl_build(&s->d, ics_slab_cl_source, "slab.cl", 8, KERNEL_NAMES, &s->prog, s->k, why,
                      sizeof why);
  if (st != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "backend cl: %s", why);
    cl_destroy(s);
    return st;
  }
  *state = s;
  return ICS_OK;
}

/* Per light: the device copies of its prepared taps, grown as a slab needs more. */
typedef struct cl_taps {
  cl_mem ix, iy, off, fx, fy, w;
  size_t cap;
} cl_taps;

/* slab.cl's buf_layout and shade_args, field for field (OpenCL C scalars have these sizes and
 * alignments) */
typedef struct buf_layout {
  cl_int w, h, stride, plane, origin;
} buf_layout;
typedef struct shade_args {
  buf_layout B;
  cl_int nch, nlights, k, nvol, W, H, pad_l, pad_t, preintegrate;
  cl_int aov_count, aov_vis, aov_z;
  cl_uint seed_lo, seed_hi;
  cl_double zf, zb, window_max;
} shade_args;

typedef struct cl_job {
  cl_state *s;
  shade_args args;
  const ics_plan *P;
  cl_int err;
  const char *call;
  cl_mem src, dst, offset, fz, fcode, fgrad, fspan, cursor, acursor, inside, obj, tt, perm, grids,
      vol_obj, cam, lcol, lmu, lpath, window, signed_l, img, ent, aov, aov_seen;
  cl_taps taps[ICS_SCENE_MAX_LIGHTS];
} cl_job;

static cl_mem job_buffer(cl_job *j, size_t bytes, const void *init, const char *what) {
  if (j->err != CL_SUCCESS) return NULL;
  cl_int e;
  cl_mem m = clCreateBuffer(j->s->d.ctx, CL_MEM_READ_WRITE | (init ? CL_MEM_COPY_HOST_PTR : 0),
                            bytes ? bytes : 4, (void *)init, &e);
  if (e != CL_SUCCESS) j->err = e, j->call = what;
  return m;
}

static void job_write(cl_job *j, cl_mem m, size_t bytes, const void *data, const char *what) {
  if (j->err != CL_SUCCESS || !bytes) return;
  cl_int e = clEnqueueWriteBuffer(j->s->d.q, m, CL_TRUE, 0, bytes, data, 0, NULL, NULL);
  if (e != CL_SUCCESS) j->err = e, j->call = what;
}

static void release(cl_mem *m) {
  if (*m) clReleaseMemObject(*m);
  *m = NULL;
}

/* uploads light l's prepared taps (n of them) */
static void upload_taps(cl_job *j, int l, const ics_prop_taps *pt, size_t n) {
  cl_taps *t = &j->taps[l];
  int bilinear = !pt->stencil && !pt->classes;
  if (n > t->cap) {
    release(&t->ix), release(&t->iy), release(&t->off), release(&t->fx), release(&t->fy);
    release(&t->w);
    t->cap = n;
    t->off = job_buffer(j, n * sizeof(cl_int), NULL, "clCreateBuffer(taps)");
    t->ix = job_buffer(j, n * sizeof(cl_int), NULL, "clCreateBuffer(taps)");
    t->iy = job_buffer(j, n * sizeof(cl_int), NULL, "clCreateBuffer(taps)");
    t->fx = job_buffer(j, n * sizeof(cl_float), NULL, "clCreateBuffer(taps)");
    t->fy = job_buffer(j, n * sizeof(cl_float), NULL, "clCreateBuffer(taps)");
    t->w = job_buffer(j, n * sizeof(cl_float), NULL, "clCreateBuffer(taps)");
  }
  job_write(j, t->ix, n * sizeof(cl_int), pt->ix, "clEnqueueWriteBuffer(taps)");
  job_write(j, t->iy, n * sizeof(cl_int), pt->iy, "clEnqueueWriteBuffer(taps)");
  job_write(j, t->w, n * sizeof(cl_float), pt->w, "clEnqueueWriteBuffer(taps)");
  if (!pt->classes) job_write(j, t->off, n * sizeof(cl_int), pt->off, "clEnqueueWriteBuffer(taps)");
  if (bilinear) {
    job_write(j, t->fx, n * sizeof(cl_float), pt->fx, "clEnqueueWriteBuffer(taps)");
    job_write(j, t->fy, n * sizeof(cl_float), pt->fy, "clEnqueueWriteBuffer(taps)");
  }
}

static void set_arg(cl_job *j, cl_kernel k, cl_uint i, size_t size, const void *v) {
  if (j->err != CL_SUCCESS) return;
  cl_int e = clSetKernelArg(k, i, size, v);
  if (e != CL_SUCCESS) j->err = e, j->call = "clSetKernelArg";
}
#define ARG(k, i, v) set_arg(j, k, i, sizeof(v), &(v))

/* one slab: every light's step, then the shading; their device times into the stats */
/* The work-items of light l's slab step at slab k: only its active region (active_region.h: no
 * needed pixel ever reads the rest of the buffer again), `per` pixels along x to a work-item,
 * rounded out to whole work-groups of lx x ly (the kernels skip what lies beyond the buffer).
 * 0 when the region is empty. */
static int step_range(const ics_plan *P, int l, int k, size_t per, size_t lx, size_t ly,
                      size_t off[2], size_t size[2]) {
  const ics_rect *r = ics_active_region(P, l, k);
  if (r->x1 <= r->x0 || r->y1 <= r->y0) return 0;
  size_t x0 = (size_t)r->x0 / per, x1 = ((size_t)r->x1 + per - 1) / per;
  off[0] = x0, off[1] = (size_t)r->y0;
  size[0] = (x1 - x0 + lx - 1) / lx * lx;
  size[1] = ((size_t)(r->y1 - r->y0) + ly - 1) / ly * ly;
  return 1;
}

static void run_slab(cl_job *j, int k, const ics_prop_taps *pts, ics_render_stats *stats) {
  const ics_plan *P = j->P;
  cl_state *s = j->s;
  cl_int nch = P->nch;
  buf_layout B = j->args.B;
  /* work-groups of 16 x 8 (the kernels skip the pixels beyond the buffer): a bounded group, so
   * PoCL's per-group stack (private memory times the group size) stays small */
  size_t local[2] = {16, 8};
  size_t global[2] = {((size_t)P->Wb + 15) / 16 * 16, ((size_t)P->Hb + 7) / 8 * 8};
  cl_event evs[2 * ICS_SCENE_MAX_LIGHTS + 1];
  int nev = 0;
  for (int l = 0; l < P->nlights && j->err == CL_SUCCESS; l++) {
    const ics_prop_taps *pt = &pts[l];
    /* light l's planes start at base (a sub-buffer would need the device's base-address
     * alignment, so the kernels add base themselves) */
    cl_int mode = pt->classes ? 2 : pt->stencil ? 0 : 1, ntaps = pt->ntaps, entries = pt->entries;
    cl_int base = l * nch * B.plane, run = pt->run, phase = pt->phase, Q = pt->classes;
    cl_uint seed_lo = (cl_uint)pt->seed, seed_hi = (cl_uint)(pt->seed >> 32), light = pt->light,
            slab = pt->slab;
    cl_double sc = pt->s, cx = pt->cx, cy = pt->cy;
    cl_taps *t = &j->taps[l];
    cl_kernel kp = s->k[K_PROP + mode];
    cl_int clamped = pt->s != 1 || pt->reach > P->buf.apron; /* as propagate.c */
    ARG(kp, 0, j->src), ARG(kp, 1, j->dst), ARG(kp, 2, base), ARG(kp, 3, B), ARG(kp, 4, nch);
    ARG(kp, 5, ntaps), ARG(kp, 6, t->ix), ARG(kp, 7, t->iy), ARG(kp, 8, t->off);
    ARG(kp, 9, t->w), ARG(kp, 10, clamped);
    if (mode == 1) {
      cl_kernel ke = s->k[K_ENTRIES + (run > 1)];
      cl_int bw = B.w, bh = B.h, npx = B.w * B.h;
      size_t span = 64 * ics_slab_choice_chunks((uint32_t)entries); /* pixels per 16 blocks */
      size_t g_px[1] = {((size_t)npx + span - 1) / span * 16};
      size_t g_run[2] = {(size_t)B.w / 16 + 2, (size_t)B.h};
      ARG(ke, 0, j->ent);
      if (run > 1) {
        ARG(ke, 1, bw), ARG(ke, 2, bh), ARG(ke, 3, entries), ARG(ke, 4, seed_lo);
        ARG(ke, 5, seed_hi), ARG(ke, 6, light), ARG(ke, 7, slab), ARG(ke, 8, phase);
      } else {
        ARG(ke, 1, npx), ARG(ke, 2, entries), ARG(ke, 3, seed_lo), ARG(ke, 4, seed_hi);
        ARG(ke, 5, light), ARG(ke, 6, slab);
      }
      if (j->err != CL_SUCCESS) break;
      cl_int e = clEnqueueNDRangeKernel(s->d.q, ke, run > 1 ? 2 : 1, NULL, run > 1 ? g_run : g_px,
                                        NULL, 0, NULL, &evs[nev]);
      if (e != CL_SUCCESS) {
        j->err = e, j->call = "clEnqueueNDRangeKernel(ics_entries_*)";
        break;
      }
      nev++;
      ARG(kp, 11, j->ent), ARG(kp, 12, t->fx), ARG(kp, 13, t->fy), ARG(kp, 14, entries);
    } else if (mode == 2) {
      ARG(kp, 11, Q), ARG(kp, 12, sc), ARG(kp, 13, cx), ARG(kp, 14, cy);
    }
    if (j->err != CL_SUCCESS) break;
    /* the stencil and the table: 16 pixels per work-item, groups of 8 x 8; the classes: one
     * pixel, groups of 16 x 8; over the light's active region */
    size_t local_st[2] = {8, 8}, off[2], size[2];
    if (!step_range(P, l, k, mode < 2 ? 16 : 1, mode < 2 ? 8 : 16, 8, off, size)) continue;
    cl_int e = clEnqueueNDRangeKernel(s->d.q, kp, 2, off, size, mode < 2 ? local_st : local, 0,
                                      NULL, &evs[nev]);
    if (e != CL_SUCCESS) j->err = e, j->call = "clEnqueueNDRangeKernel(ics_prop)";
    else nev++;
  }
  int nprop = nev;
  if (j->err == CL_SUCCESS) {
    cl_kernel ks = s->k[K_SHADE];
    shade_args A = j->args;
    A.k = k;
    A.zf = P->z0 + k * P->e;
    A.zb = A.zf + P->e;
    cl_mem *bufs[] = {&j->dst, NULL, &j->offset, &j->fz, &j->fcode, &j->fgrad, &j->fspan,
                      &j->cursor, &j->acursor, &j->inside, &j->obj, &j->tt, &j->perm, &j->grids,
                      &j->vol_obj, &j->cam, &j->lcol, &j->lmu, &j->lpath, &j->window,
                      &j->signed_l, &j->img, &j->aov, &j->aov_seen};
    for (cl_uint i = 0; i < sizeof bufs / sizeof *bufs; i++) {
      if (bufs[i]) set_arg(j, ks, i, sizeof(cl_mem), bufs[i]);
      else set_arg(j, ks, i, sizeof A, &A);
    }
    if (j->err == CL_SUCCESS) {
      cl_int e = clEnqueueNDRangeKernel(s->d.q, ks, 2, NULL, global, local, 0, NULL, &evs[nev]);
      if (e != CL_SUCCESS) j->err = e, j->call = "clEnqueueNDRangeKernel(ics_shade)";
      else nev++;
    }
  }
  /* the apron of the light leaving this slab */
  cl_int A = P->buf.apron, nplanes = P->nlights * nch;
  if (A > 0 && nplanes > 0) {
    size_t g_sides[3] = {2 * (size_t)A, (size_t)P->Hb, (size_t)nplanes};
    size_t g_ends[3] = {(size_t)P->buf.stride, 2 * (size_t)A, (size_t)nplanes};
    for (int i = 0; i < 2 && j->err == CL_SUCCESS; i++) {
      ARG(s->k[K_APRON + i], 0, j->dst), ARG(s->k[K_APRON + i], 1, B), ARG(s->k[K_APRON + i], 2, A);
      if (j->err != CL_SUCCESS) break;
      cl_int e = clEnqueueNDRangeKernel(s->d.q, s->k[K_APRON + i], 3, NULL, i ? g_ends : g_sides, NULL, 0,
                                        NULL, NULL);
      if (e != CL_SUCCESS) j->err = e, j->call = "clEnqueueNDRangeKernel(ics_apron)";
    }
  }
  if (nev) {
    cl_int e = clWaitForEvents((cl_uint)nev, evs);
    if (e != CL_SUCCESS && j->err == CL_SUCCESS) j->err = e, j->call = "clWaitForEvents (slab)";
    for (int i = 0; i < nev; i++) {
      double ms = ics_cl_event_ms(evs[i]);
      if (i < nprop) stats->ms_convolution += ms;
      else stats->ms_shading += ms;
      clReleaseEvent(evs[i]);
    }
  }
}

static ics_status cl_render(void *state, const ics_plan *P, const ics_render_opts *o,
                            ics_image *img, ics_aov_buf *aov, ics_render_stats *stats, char *msg,
                            size_t msg_size) {
  cl_state *s = state;
  double t_start = ics_clock_s();
  int nl = P->nlights, nch = P->nch;
  size_t plane = P->buf.plane, npx = (size_t)P->Wb * P->Hb, nfrag = P->ldi.nfrag;
  size_t lbytes = sizeof(float) * (size_t)(nl ? nl : 1) * (size_t)nch * plane;
  if ((size_t)(nl ? nl : 1) * (size_t)nch * plane > INT_MAX || npx + 1 > UINT_MAX) {
    if (msg) snprintf(msg, msg_size, "backend cl: %d lights x %d channels x %dx%d buffer pixels "
                      "exceed the kernels' 32-bit indices", nl, nch, P->Wb, P->Hb);
    return ICS_ERR_SIZE;
  }
  if (lbytes > s->d.max_alloc) {
    if (msg) snprintf(msg, msg_size, "backend cl: the light buffers take %zu bytes, over the "
                      "device's largest allocation (%llu bytes, %s)", lbytes,
                      (unsigned long long)s->d.max_alloc, s->d.name);
    return ICS_ERR_SIZE;
  }
  ics_status status = ICS_OK;
  cl_job job;
  memset(&job, 0, sizeof job);
  cl_job *j = &job;
  j->s = s;
  j->P = P;
  /* host copies of what the device reads */
  ics_device_scene ds;
  double window[ICS_SCENE_MAX_LIGHTS], cum[ICS_SCENE_MAX_LIGHTS][2];
  ics_prop_taps *pts = calloc((size_t)(nl ? nl : 1), sizeof *pts);
  ics_tap2d **scratch = calloc((size_t)(nl ? nl : 1), sizeof *scratch);
  if (ics_device_scene_create(&ds, P, 1) != ICS_OK) {
    free(pts), free(scratch);
    if (msg) snprintf(msg, msg_size, "backend cl: out of host memory for the upload (%zu fragments)", nfrag);
    return ICS_ERR_NOMEM;
  }
  if (!pts || !scratch) goto nomem;
  double wmax = ics_plan_window_max(P);
  for (int l = 0; l < nl; l++) {
    cum[l][0] = cum[l][1] = 0;
    const ics_slab_kernel *sk = &P->kernels[l];
    scratch[l] = malloc(sizeof **scratch * (size_t)sk->entries * (size_t)sk->cap);
    if (!scratch[l]) goto nomem;
  }
  buf_layout B = {P->buf.w, P->buf.h, P->buf.stride, (cl_int)P->buf.plane, (cl_int)P->buf.origin};
  j->args = (shade_args){.B = B, .nch = nch,
                         .nlights = nl, .nvol = P->nvol, .W = P->W, .H = P->H,
                         .pad_l = P->pad[0], .pad_t = P->pad[2],
                         .preintegrate = P->rs.preintegrate, .seed_lo = (cl_uint)P->rs.seed,
                         .seed_hi = (cl_uint)(P->rs.seed >> 32), .window_max = wmax,
                         .aov_count = aov ? aov->count : 0, .aov_vis = aov ? aov->vis : -1,
                         .aov_z = aov ? aov->z : -1};
  j->src = job_buffer(j, lbytes, NULL, "clCreateBuffer(light buffers)");
  j->dst = job_buffer(j, lbytes, NULL, "clCreateBuffer(light buffers)");
  j->offset = job_buffer(j, sizeof(cl_uint) * (npx + 1), P->ldi.offset, "clCreateBuffer(LDI)");
  j->cursor = job_buffer(j, sizeof(cl_uint) * (npx + 1), P->ldi.offset, "clCreateBuffer(LDI)");
  j->acursor = job_buffer(j, sizeof(cl_uint) * (npx + 1), P->ldi.offset, "clCreateBuffer(LDI)");
  j->fz = job_buffer(j, sizeof *ds.fz * ds.nfrag, ds.fz, "clCreateBuffer(LDI)");
  j->fcode = job_buffer(j, sizeof *ds.fcode * ds.nfrag, ds.fcode, "clCreateBuffer(LDI)");
  j->fgrad = job_buffer(j, 2 * sizeof *ds.fgrad * ds.nfrag, ds.fgrad, "clCreateBuffer(LDI)");
  j->fspan = job_buffer(j, ds.nfrag, ds.fspan, "clCreateBuffer(LDI)");
  j->inside = job_buffer(j, ds.inside ? sizeof *ds.inside * npx : 8, ds.inside, "clCreateBuffer(volumes)");
  j->obj = job_buffer(j, sizeof *ds.obj * ds.nobj * ICS_DEV_OBJ_STRIDE, ds.obj, "clCreateBuffer(objects)");
  j->tt = job_buffer(j, sizeof *ds.tt * 5 * ds.ntt, ds.tt, "clCreateBuffer(objects)");
  j->perm = job_buffer(j, 512 * ds.nobj, ds.perm, "clCreateBuffer(objects)");
  j->vol_obj = job_buffer(j, sizeof ds.vol_obj, ds.vol_obj, "clCreateBuffer(objects)");
  j->grids = job_buffer(j, sizeof *ds.grids * ds.ncells, ds.grids, "clCreateBuffer(grid detail)");
  j->cam = job_buffer(j, sizeof ds.cam, ds.cam, "clCreateBuffer(camera)");
  j->lcol = job_buffer(j, sizeof ds.lcol, ds.lcol, "clCreateBuffer(lights)");
  j->lmu = job_buffer(j, sizeof ds.lmu, ds.lmu, "clCreateBuffer(lights)");
  j->lpath = job_buffer(j, sizeof P->light_path, (void *)P->light_path, "clCreateBuffer(lights)");
  j->window = job_buffer(j, sizeof window, NULL, "clCreateBuffer(lights)");
  j->signed_l = job_buffer(j, sizeof ds.signed_l, ds.signed_l, "clCreateBuffer(lights)");
  j->img = job_buffer(j, sizeof(float) * 4 * (size_t)P->W * P->H, NULL, "clCreateBuffer(image)");
  j->ent = job_buffer(j, sizeof(cl_uint) * npx, NULL, "clCreateBuffer(tap-set choices)");
  size_t aov_bytes = aov ? sizeof(float) * (size_t)aov->count * (size_t)P->W * P->H : 0;
  j->aov = job_buffer(j, aov_bytes, NULL, "clCreateBuffer(AOVs)");
  j->aov_seen = job_buffer(j, (size_t)P->W * P->H, NULL, "clCreateBuffer(AOVs)");
  if (j->err == CL_SUCCESS) {
    const cl_float one = 1, zero = 0;
    cl_int e = clEnqueueFillBuffer(s->d.q, j->src, &one, sizeof one, 0, lbytes, 0, NULL, NULL);
    if (e == CL_SUCCESS)
      e = clEnqueueFillBuffer(s->d.q, j->img, &zero, sizeof zero, 0,
                              sizeof(float) * 4 * (size_t)P->W * P->H, 0, NULL, NULL);
    const cl_uchar no = 0;
    if (e == CL_SUCCESS)
      e = clEnqueueFillBuffer(s->d.q, j->aov_seen, &no, 1, 0, (size_t)P->W * P->H, 0, NULL, NULL);
    if (e == CL_SUCCESS && aov_bytes)
      e = clEnqueueFillBuffer(s->d.q, j->aov, &zero, sizeof zero, 0, aov_bytes, 0, NULL, NULL);
    if (e != CL_SUCCESS) j->err = e, j->call = "clEnqueueFillBuffer";
  }
  for (int k = 0; k < P->K && j->err == CL_SUCCESS; k++) {
    double mag, q = ics_plan_slab_pixel(P, k, &mag);
    for (int l = 0; l < nl; l++) {
      window[l] = fmax(0, 1 - ds.blur[l] / q);
      ics_prop_taps *pt = &pts[l];
      status = ics_plan_slab_taps(P, l, k, q, mag, cum[l], scratch[l], pt, msg, msg_size);
      if (status == ICS_ERR_NOMEM && msg)
        snprintf(msg, msg_size, "backend cl: light %d, slab %d: the taps could not be prepared "
                 "(out of memory, a tap out of range or a compensation that failed)", l, k);
      if (status != ICS_OK) goto done;
      upload_taps(j, l, pt, (size_t)pt->ntaps * (size_t)(pt->stencil ? 1 : pt->entries));
    }
    job_write(j, j->window, sizeof(double) * (size_t)(nl ? nl : 1), window, "clEnqueueWriteBuffer(window)");
    run_slab(j, k, pts, stats);
    cl_mem tmp = j->src;
    j->src = j->dst;
    j->dst = tmp;
    if (j->err == CL_SUCCESS && o->progress) o->progress(o->progress_ctx, k + 1, P->K);
  }
  if (j->err == CL_SUCCESS) {
    cl_int e = clEnqueueReadBuffer(s->d.q, j->img, CL_TRUE, 0, sizeof(float) * 4 * (size_t)P->W * P->H,
                                   img->data, 0, NULL, NULL);
    if (e == CL_SUCCESS && aov_bytes)
      e = clEnqueueReadBuffer(s->d.q, j->aov, CL_TRUE, 0, aov_bytes, aov->data, 0, NULL, NULL);
    if (e != CL_SUCCESS) j->err = e, j->call = "clEnqueueReadBuffer(image)";
  }
  if (j->err != CL_SUCCESS) {
    if (msg) snprintf(msg, msg_size, "backend cl: %s on %s: %s", j->call, s->d.name,
                      ics_cl_err_name(j->err));
    status = ics_cl_status(j->err);
    goto done;
  }
  ics_plan_over_background(P, img);
  stats->threads = 0;
  stats->slabs = P->K;
  snprintf(stats->device, sizeof stats->device, "%s", s->d.name);
  if (nl && P->K) stats->ns_per_px_slab = 1e6 * stats->ms_convolution / ((double)npx * P->K * nl);
  stats->ms_total = 1e3 * (ics_clock_s() - t_start);
  goto done;
nomem:
  status = ICS_ERR_NOMEM;
  if (msg) snprintf(msg, msg_size, "backend cl: out of host memory for the upload (%zu fragments)", nfrag);
done:;
  cl_mem *all[] = {&j->src, &j->dst, &j->offset, &j->fz, &j->fcode, &j->fgrad, &j->fspan,
                   &j->cursor, &j->acursor, &j->inside, &j->obj, &j->tt, &j->perm, &j->grids,
                   &j->vol_obj, &j->cam, &j->lcol, &j->lmu, &j->lpath, &j->window, &j->signed_l,
                   &j->img, &j->ent, &j->aov, &j->aov_seen};
  for (size_t i = 0; i < sizeof all / sizeof *all; i++) release(all[i]);
  for (int l = 0; l < nl; l++) {
    cl_taps *t = &j->taps[l];
    release(&t->ix), release(&t->iy), release(&t->off), release(&t->fx), release(&t->fy);
    release(&t->w);
    if (pts) ics_prop_release(&pts[l]);
    if (scratch) free(scratch[l]);
  }
  ics_device_scene_destroy(&ds);
  free(pts), free(scratch);
  return status;
}

/* the module's table (module_cl.c); the backend's entry: backend_cl_entry.c */
const ics_backend_funcs ics_cl_funcs = {cl_available, NULL, cl_create, cl_render, cl_destroy};
