/* backend_gl.c — the "gl" backend: the slab renderer as OpenGL 4.5 compute shaders (gpu/backends/gl/slab.comp)
 * on a windowless context (gl_context.c: EGL's device or surfaceless platform, or OSMesa).
 * Method and tolerances: docs/backend_gl.md.
 *
 * The same division of work as the cl backend: the host resolves each slab's taps exactly as
 * the cpu backend does (ics_plan_slab_taps) and uploads them; per slab the device runs, per
 * light, the tap-set choices and the step (ICS_K_ENTRIES_*, ICS_K_PROP_*), then the shading of
 * every buffer pixel (ICS_K_SHADE) and the apron (ICS_K_APRON_*), with a shader-storage barrier
 * between dispatches. The scene's records are the plan's (device_scene.c), uploaded once per
 * render into shader storage buffers; so is the layered depth image, or, with ICS_GL_LDI=device
 * (--gl-ldi device), it is built on the device each render (ldi_gl.c). Device times come
 * from GL_TIMESTAMP queries read after the last slab.
 *
 * Every failure names what failed: no context (each kind tried), a shader that does not
 * compile or link (its log), a size over the driver's limits, GL_OUT_OF_MEMORY or another GL
 * error after a slab, a lost context (glGetGraphicsResetStatus). */
#define _POSIX_C_SOURCE 200809L
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "backend.h"
#include "clock.h"
#include "device_scene.h"
#include "gl_context.h"
#include "ldi_gl.h"
#include "plan_internal.h"
#include "slab_choice.h"
#include "slab_taps.h"
#include "slab_comp_source.h" /* ics_slab_comp_source: gpu/backends/gl/slab.comp (cmake/embed_text.cmake) */

/* the programs: slab.comp's entry points, the steps also with every read clamped (variants,
 * not a uniform branch: llvmpipe would run both sides) */
/* The steps come in NSTEP forms, each also with its taps in a storage buffer (+ NSTEP: more
 * taps than a uniform block holds). */
enum { P_STENCIL, P_STENCIL_CLAMPED, P_TABLE, P_TABLE_CLAMPED, P_CLASSES, NSTEP = 5,
       P_ENTRIES_PIXEL = 2 * NSTEP, P_ENTRIES_RUN, P_SELECT, P_COUNT, P_SHADE, P_SHADE_SURFACES,
       P_APRON_SIDES, P_APRON_ENDS, NPROGS };
static const char *const PROG_NAMES[NPROGS] = {
    "ICS_K_PROP_STENCIL", "ICS_K_PROP_STENCIL", "ICS_K_PROP_TABLE", "ICS_K_PROP_TABLE",
    "ICS_K_PROP_CLASSES", "ICS_K_PROP_STENCIL", "ICS_K_PROP_STENCIL", "ICS_K_PROP_TABLE",
    "ICS_K_PROP_TABLE", "ICS_K_PROP_CLASSES", "ICS_K_ENTRIES_PIXEL", "ICS_K_ENTRIES_RUN",
    "ICS_K_SHADE_SELECT", "ICS_K_SHADE_COUNT", "ICS_K_SHADE", "ICS_K_SHADE", "ICS_K_APRON_SIDES",
    "ICS_K_APRON_ENDS"};
/* the variants' further defines */
static const char *const PROG_VARIANT[NPROGS] = {
    [P_STENCIL_CLAMPED] = "ICS_CLAMPED", [P_TABLE_CLAMPED] = "ICS_CLAMPED",
    [NSTEP + P_STENCIL] = "ICS_TAPS_STORAGE", [NSTEP + P_STENCIL_CLAMPED] = "ICS_CLAMPED 1\n#define ICS_TAPS_STORAGE",
    [NSTEP + P_TABLE] = "ICS_TAPS_STORAGE", [NSTEP + P_TABLE_CLAMPED] = "ICS_CLAMPED 1\n#define ICS_TAPS_STORAGE",
    [NSTEP + P_CLASSES] = "ICS_TAPS_STORAGE", [P_SHADE_SURFACES] = "ICS_SURFACES_ONLY"};
enum { SSBO_BINDINGS = 15 }; /* slab.comp's bindings 0..14 (the shading uses 14 of them) */

/* slab.comp's tap record (std140: ivec4, vec4) */
typedef struct gl_tap {
  int32_t ix, iy, off, pad;
  float w, fx, fy, pad2;
} gl_tap;

typedef struct gl_state {
  ics_gl g;
  GLuint prog[NPROGS];
  GLint64 max_block; /* GL_MAX_SHADER_STORAGE_BLOCK_SIZE */
  GLint max_texels;  /* GL_MAX_TEXTURE_BUFFER_SIZE */
  size_t max_taps;   /* taps a uniform block holds: GL_MAX_UNIFORM_BLOCK_SIZE / 32, at most 4096 */
  GLint max_groups[3];
  int ldi_device;                     /* ICS_GL_LDI=device: the LDI built on the device */
  GLuint ldi_prog[ICS_GL_LDI_NPROGS]; /* ldi.comp's programs, then */
} gl_state;

#define GL_ (s->g.gl)

/* the programs (the context current), then the context, which gives the thread back */
static void state_free(gl_state *s) {
  for (int i = 0; i < NPROGS; i++)
    if (s->prog[i]) GL_.DeleteProgram(s->prog[i]);
  for (int i = 0; i < ICS_GL_LDI_NPROGS; i++)
    if (s->ldi_prog[i]) GL_.DeleteProgram(s->ldi_prog[i]);
  ics_gl_close(&s->g);
  free(s);
}

static void gl_destroy(void *state) {
  gl_state *s = state;
  if (!s) return;
  if (!ics_gl_make_current(&s->g)) { /* its programs go with the context */
    memset(s->prog, 0, sizeof s->prog);
    memset(s->ldi_prog, 0, sizeof s->ldi_prog);
  }
  state_free(s);
}

const char *ics_gl_context_kind(const ics_render_opts *opts) {
  const char *k = ics_backend_option_value(ics_backend_find("gl"), opts, "context", NULL);
  return k ? k : "auto";
}

/* where the layered depth image comes from: gl.ldi (ICS_GL_LDI), "plan" (the plan's, uploaded;
 * the default) or "device" (ldi_gl.c); -1 for another value (*v: it) */
static int ldi_on_device(const ics_render_opts *opts, const char **v) {
  *v = ics_backend_option_value(ics_backend_find("gl"), opts, "ldi", NULL);
  if (!*v || !strcmp(*v, "plan")) return 0;
  return !strcmp(*v, "device") ? 1 : -1;
}

static int gl_available(const ics_render_opts *opts, char *why, size_t why_size) {
  ics_gl g;
  char w[1024];
  if (ics_gl_open(&g, ics_gl_context_kind(opts), w, sizeof w) != ICS_OK) {
    if (why) snprintf(why, why_size, "%s", w);
    return 0;
  }
  ics_gl_close(&g);
  return 1;
}

/* auto picks gl only on a GPU: an EGL device that is not Mesa's software one */
static int gl_auto_pick(char *why, size_t why_size) {
  if (ics_gl_hardware_device(why, why_size)) return 1;
  return 0;
}

/* compiles and links entry point `i`; 0 with the log in msg */
static int build(gl_state *s, int i, char *msg, size_t msg_size) {
  char head[160], name[64];
  snprintf(head, sizeof head, "#define %s 1\n#define %s 1\n#define ICS_MAX_TAPS %zu\n#line 2\n",
           PROG_NAMES[i], PROG_VARIANT[i] ? PROG_VARIANT[i] : "ICS_DEFAULT_VARIANT", s->max_taps);
  snprintf(name, sizeof name, "slab.comp (%s)", PROG_NAMES[i]);
  return ics_gl_compile(&s->g, ics_slab_comp_source, head, name, &s->prog[i], msg, msg_size);
}

static ics_status gl_create(void **state, const ics_render_opts *opts, char *msg, size_t msg_size) {
  *state = NULL;
  const char *ldi;
  int ldi_device = ldi_on_device(opts, &ldi);
  if (ldi_device < 0) { /* an option is checked already: the environment's */
    if (msg) snprintf(msg, msg_size, "backend gl: ICS_GL_LDI: expected plan or device, got '%s'", ldi);
    return ICS_ERR_INVALID_ARG;
  }
  gl_state *s = calloc(1, sizeof *s);
  if (!s) return ICS_ERR_NOMEM;
  s->ldi_device = ldi_device;
  char why[1024];
  if (ics_gl_open(&s->g, ics_gl_context_kind(opts), why, sizeof why) != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "backend gl: %s", why);
    free(s);
    return ICS_ERR_UNSUPPORTED;
  }
  /* auto took gl for a GPU the EGL device platform lists: refuse the software rasterizer the
   * context kinds may fall back to, so auto renders on cpu with this as its note */
  if ((!opts || !opts->backend || !strcmp(opts->backend, "auto")) && s->g.software) {
    if (msg) snprintf(msg, msg_size, "the %s context is %s, a software rasterizer, not the GPU "
                      "that EGL lists (--backend gl renders there)", s->g.context, s->g.renderer);
    state_free(s);
    return ICS_ERR_UNSUPPORTED;
  }
  GLint blocks = 0, bindings = 0;
  GL_.GetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &blocks);
  GL_.GetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &bindings);
  GL_.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &s->max_block);
  GL_.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &s->max_texels);
  GLint ubo = 0;
  GL_.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &ubo);
  s->max_taps = (size_t)ubo / sizeof(gl_tap) < 4096 ? (size_t)ubo / sizeof(gl_tap) : 4096;
  for (GLuint i = 0; i < 3; i++) GL_.GetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i, &s->max_groups[i]);
  if (blocks < SSBO_BINDINGS - 1 || bindings < SSBO_BINDINGS) {
    if (msg) snprintf(msg, msg_size, "backend gl: %s offers %d shader storage blocks to a compute "
                      "shader and %d bindings; the shading needs %d and %d", s->g.renderer,
                      (int)blocks, (int)bindings, SSBO_BINDINGS - 1, SSBO_BINDINGS);
    state_free(s);
    return ICS_ERR_UNSUPPORTED;
  }
  for (int i = 0; i < NPROGS; i++)
    if (!build(s, i, msg, msg_size)) {
      state_free(s);
      return ICS_ERR_UNSUPPORTED;
    }
  if (s->ldi_device && !ics_gl_ldi_programs(&s->g, s->ldi_prog, msg, msg_size)) {
    state_free(s);
    return ICS_ERR_UNSUPPORTED;
  }
  ics_gl_release(&s->g); /* current only while it renders */
  *state = s;
  return ICS_OK;
}

/* uniforms of program p by name */
static void u_int(gl_state *s, int p, const char *name, int v) { ics_gl_uniform_i(&s->g, s->prog[p], name, v); }
static void u_uint(gl_state *s, int p, const char *name, unsigned v) {
  ics_gl_uniform_ui(&s->g, s->prog[p], name, v);
}
static void u_dbl(gl_state *s, int p, const char *name, double v) {
  ics_gl_uniform_d(&s->g, s->prog[p], name, v);
}

/* the device buffers of one render (slab.comp's bindings) */
enum { B_SRC, B_DST, B_OFFSET, B_FZ, B_FCODE, B_FGRAD, B_FSPAN, B_PIX, B_OBJ, B_SD, B_PERM,
       B_GRIDS, B_INTS, B_OUT, B_WORK, B_ENT, NBUF };

typedef struct gl_job {
  gl_state *s;
  const ics_plan *P;
  GLuint buf[NBUF], taps[ICS_SCENE_MAX_LIGHTS];
  size_t taps_cap[ICS_SCENE_MAX_LIGHTS];
  GLuint tex[2]; /* buffer textures over buf[B_SRC] and buf[B_DST], swapped with them */
  gl_tap *host_taps;
  size_t host_cap;
  int off_window;
  GLuint *queries; /* 3 per slab: start, after the steps, after the shading */
} gl_job;

/* uploads light l's prepared taps (n records; a uniform block holds max_taps, a storage buffer
 * more: grown as needed); 0 when out of host memory */
static int upload_taps(gl_job *j, int l, const ics_prop_taps *pt, size_t n) {
  gl_state *s = j->s;
  if (n > j->host_cap) {
    gl_tap *t = realloc(j->host_taps, n * sizeof *t);
    if (!t) return 0;
    j->host_taps = t, j->host_cap = n;
  }
  int bilinear = !pt->stencil && !pt->classes;
  for (size_t i = 0; i < n; i++)
    j->host_taps[i] = (gl_tap){pt->ix[i], pt->iy[i], pt->off && !pt->classes ? pt->off[i] : 0, 0,
                               pt->w[i], bilinear ? pt->fx[i] : 0, bilinear ? pt->fy[i] : 0, 0};
  if (n > j->taps_cap[l] || !j->taps[l]) {
    if (j->taps[l]) GL_.DeleteBuffers(1, &j->taps[l]);
    j->taps_cap[l] = n > s->max_taps ? n : s->max_taps;
    j->taps[l] = ics_gl_buffer(&s->g, j->taps_cap[l] * sizeof(gl_tap), NULL);
  }
  GL_.NamedBufferSubData(j->taps[l], 0, (GLsizeiptr)(n * sizeof(gl_tap)), j->host_taps);
  return 1;
}

static void dispatch(gl_state *s, int p, size_t gx, size_t gy, size_t gz) {
  GL_.UseProgram(s->prog[p]);
  GL_.DispatchCompute((GLuint)gx, (GLuint)gy, (GLuint)gz);
  /* storage writes read as storage, and as texels (the next slab's steps read the buffers the
   * shading and the apron wrote through buffer textures) */
  GL_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* one slab: every light's step, then the shading and the apron */
static void run_slab(gl_job *j, int k, const ics_prop_taps *pts) {
  gl_state *s = j->s;
  const ics_plan *P = j->P;
  int nch = P->nch, plane = (int)P->buf.plane;
  size_t gx = ((size_t)P->Wb + 15) / 16, gy = ((size_t)P->Hb + 7) / 8;
  GL_.QueryCounter(j->queries[3 * k], GL_TIMESTAMP);
  GL_.BindTextureUnit(0, j->tex[0]);
  GL_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, j->buf[B_DST]);
  for (int l = 0; l < P->nlights; l++) {
    const ics_prop_taps *pt = &pts[l];
    int clamped = pt->s != 1 || pt->reach > P->buf.apron; /* as propagate.c */
    int mode = pt->classes ? P_CLASSES : (pt->stencil ? P_STENCIL : P_TABLE) + clamped;
    size_t ntap = (size_t)pt->ntaps * (size_t)(pt->stencil ? 1 : pt->entries);
    if (ntap > s->max_taps) mode += NSTEP;
    if (mode < NSTEP)
      GL_.BindBufferRange(GL_UNIFORM_BUFFER, 0, j->taps[l], 0, (GLsizeiptr)(s->max_taps * sizeof(gl_tap)));
    else
      GL_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, j->taps[l]);
    GL_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, j->buf[B_ENT]);
    if (mode % NSTEP == P_TABLE || mode % NSTEP == P_TABLE_CLAMPED) {
      int pe = pt->run > 1 ? P_ENTRIES_RUN : P_ENTRIES_PIXEL;
      size_t span = 64 * ics_slab_choice_chunks((uint32_t)pt->entries); /* pixels per 16 blocks */
      u_int(s, pe, "entries", pt->entries), u_uint(s, pe, "light", pt->light);
      u_uint(s, pe, "slab", pt->slab), u_int(s, pe, "phase", pt->phase);
      u_uint(s, pe, "seed_lo", (unsigned)pt->seed), u_uint(s, pe, "seed_hi", (unsigned)(pt->seed >> 32));
      if (pe == P_ENTRIES_RUN)
        dispatch(s, pe, ((size_t)P->Wb / 16 + 2 + 15) / 16, gy, 1);
      else
        dispatch(s, pe, (((size_t)P->Wb * P->Hb + span - 1) / span * 16 + 63) / 64, 1, 1);
      u_int(s, mode, "entries", pt->entries);
    } else if (mode % NSTEP == P_CLASSES) {
      u_int(s, mode, "Q", pt->classes);
      u_dbl(s, mode, "s", pt->s), u_dbl(s, mode, "cx", pt->cx), u_dbl(s, mode, "cy", pt->cy);
    }
    u_int(s, mode, "base", l * nch * plane), u_int(s, mode, "ntaps", pt->ntaps);
    /* over the light's active region only (active_region.h: no needed pixel ever reads the
     * rest of the buffer again), in groups of 16 x 8 */
    const ics_rect *r = ics_active_region(P, l, k);
    if (r->x1 <= r->x0 || r->y1 <= r->y0) continue;
    u_int(s, mode, "ofs_x", r->x0), u_int(s, mode, "ofs_y", r->y0);
    dispatch(s, mode, ((size_t)(r->x1 - r->x0) + 15) / 16, ((size_t)(r->y1 - r->y0) + 7) / 8, 1);
  }
  GL_.QueryCounter(j->queries[3 * k + 1], GL_TIMESTAMP);
  /* the shading's bindings 1..14 (the steps took 2 and 3); 1 is the buffers the steps wrote */
  static const int shade_binding[] = {B_DST, B_OFFSET, B_FZ, B_FCODE, B_FGRAD, B_FSPAN, B_PIX,
                                      B_OBJ, B_SD, B_PERM, B_GRIDS, B_INTS, B_OUT, B_WORK};
  for (int b = 0; b < 14; b++)
    GL_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)(b + 1), j->buf[shade_binding[b]]);
  for (int p = P_SELECT; p <= P_SHADE_SURFACES; p++) {
    u_int(s, p, "k", k);
    u_dbl(s, p, "zf", P->z0 + k * P->e), u_dbl(s, p, "zb", P->z0 + k * P->e + P->e);
  }
  /* the pixels with work, listed; their count as the shading's dispatch */
  dispatch(s, P_SELECT, gx, gy, 1);
  GL_.UseProgram(s->prog[P_COUNT]);
  GL_.DispatchCompute(1, 1, 1);
  GL_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
  GL_.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, j->buf[B_WORK]);
  for (int i = 0; i < 2; i++) { /* the volume pixels, then the others */
    GL_.UseProgram(s->prog[i ? P_SHADE_SURFACES : P_SHADE]);
    GL_.DispatchComputeIndirect((GLintptr)(i * 5 * sizeof(GLuint)));
    GL_.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  int A = P->buf.apron, nplanes = P->nlights * nch;
  if (A > 0 && nplanes > 0) {
    dispatch(s, P_APRON_SIDES, ((size_t)2 * A + 63) / 64, (size_t)P->Hb, (size_t)nplanes);
    dispatch(s, P_APRON_ENDS, ((size_t)P->buf.stride + 63) / 64, 2 * (size_t)A, (size_t)nplanes);
  }
  GL_.QueryCounter(j->queries[3 * k + 2], GL_TIMESTAMP);
}

/* the driver's thread count where it runs on the CPU (llvmpipe: LP_NUM_THREADS, else every core) */
static int software_threads(void) {
  const char *t = getenv("LP_NUM_THREADS");
  if (t && *t) return atoi(t);
  long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? (int)n : 1;
}

/* the buffers and dispatches of a render against the shaders' 32-bit indices and the driver's
 * limits, before anything is allocated */
static ics_status check_sizes(const gl_state *s, const ics_plan *P, const ics_aov_buf *aov,
                              char *msg, size_t msg_size) {
  int nl = P->nlights, nch = P->nch;
  size_t npx = (size_t)P->Wb * P->Hb, nview = (size_t)P->W * P->H, plane = P->buf.plane;
  size_t lbytes = sizeof(float) * (size_t)(nl ? nl : 1) * (size_t)nch * plane;
  size_t aov_floats = aov ? (size_t)aov->count * nview : 0;
  size_t out_floats = 4 * nview + aov_floats + nview;
  size_t gx = ((size_t)P->Wb + 15) / 16, gy = ((size_t)P->Hb + 7) / 8;
  size_t nfrag = P->ldi.nfrag ? P->ldi.nfrag : 1;
  if (lbytes / sizeof(float) > INT_MAX || out_floats > INT_MAX || npx + 1 > UINT_MAX) {
    if (msg) snprintf(msg, msg_size, "backend gl: %d lights x %d channels x %dx%d buffer pixels "
                      "exceed the shaders' 32-bit indices", nl, nch, P->Wb, P->Hb);
    return ICS_ERR_SIZE;
  }
  if (lbytes / sizeof(float) > (size_t)s->max_texels) {
    if (msg) snprintf(msg, msg_size, "backend gl: the light buffers hold %zu floats, over the "
                      "driver's largest buffer texture (%d texels, %s)", lbytes / sizeof(float),
                      s->max_texels, s->g.renderer);
    return ICS_ERR_SIZE;
  }
  /* every storage buffer against the driver's largest block (the taps' are checked per slab) */
  const struct { const char *what; size_t bytes; } sizes[] = {
      {"the light buffers", lbytes},
      {"the image and AOVs", sizeof(float) * out_floats},
      {"the per-pixel state", sizeof(uint32_t) * 4 * npx},
      {"the shading lists", sizeof(uint32_t) * (10 + 2 * npx)},
      {"the fragments' depth gradients", 2 * sizeof(float) * nfrag},
      {"the layered depth image's offsets", sizeof(uint32_t) * (npx + 1)}};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
    if (sizes[i].bytes > (size_t)s->max_block) {
      if (msg) snprintf(msg, msg_size, "backend gl: %s take %zu bytes, over the driver's largest "
                        "shader storage block (%lld bytes, %s)", sizes[i].what, sizes[i].bytes,
                        (long long)s->max_block, s->g.renderer);
      return ICS_ERR_SIZE;
    }
  size_t gz = (size_t)nl * nch, rows = (size_t)P->Hb, ends = 2 * (size_t)P->buf.apron;
  if (gx > (size_t)s->max_groups[0] || gy > (size_t)s->max_groups[1] ||
      rows > (size_t)s->max_groups[1] || ends > (size_t)s->max_groups[1] ||
      gz > (size_t)s->max_groups[2]) {
    if (msg) snprintf(msg, msg_size, "backend gl: a %dx%d light buffer of %zu planes needs "
                      "%zux%zu work groups per step and %zu apron rows, over the driver's %dx%dx%d",
                      P->Wb, P->Hb, gz, gx, gy, rows, s->max_groups[0], s->max_groups[1],
                      s->max_groups[2]);
    return ICS_ERR_SIZE;
  }
  return ICS_OK;
}

/* where each part of the scene's doubles starts: the transfer rows (ntt of 5), the camera, the
 * lights' colours, mean directions and path lengths, the shading windows */
typedef struct sd_layout {
  int cam, lcol, lmu, lpath, window, size;
} sd_layout;

static sd_layout sd_offsets(size_t ntt) {
  sd_layout o;
  o.cam = (int)(5 * ntt);
  o.lcol = o.cam + ICS_DEV_CAM;
  o.lmu = o.lcol + 3 * ICS_SCENE_MAX_LIGHTS;
  o.lpath = o.lmu + 2 * ICS_SCENE_MAX_LIGHTS;
  o.window = o.lpath + ICS_SCENE_MAX_LIGHTS;
  o.size = o.window + ICS_SCENE_MAX_LIGHTS;
  return o;
}

/* the uniforms that stay fixed over the render: the buffers' layout, the seed, the shading's
 * sizes and the offsets of the scene's doubles */
static void set_fixed_uniforms(gl_state *s, const ics_plan *P, const ics_aov_buf *aov,
                               const sd_layout *o) {
  int nl = P->nlights, nch = P->nch;
  size_t npx = (size_t)P->Wb * P->Hb, nview = (size_t)P->W * P->H;
  size_t aov_floats = aov ? (size_t)aov->count * nview : 0;
  for (int p = 0; p < NPROGS; p++) {
    u_int(s, p, "bw", P->buf.w), u_int(s, p, "bh", P->buf.h), u_int(s, p, "stride", P->buf.stride);
    u_int(s, p, "plane", (int)P->buf.plane), u_int(s, p, "origin", (int)P->buf.origin);
    u_int(s, p, "nch", nch);
    u_uint(s, p, "seed_lo", (unsigned)P->rs.seed), u_uint(s, p, "seed_hi", (unsigned)(P->rs.seed >> 32));
  }
  for (int p = 0; p < NPROGS; p++) u_int(s, p, "npx", (int)npx);
  u_int(s, P_APRON_SIDES, "A", P->buf.apron), u_int(s, P_APRON_ENDS, "A", P->buf.apron);
  static const char *const shade_i[] = {"nlights", "nvol", "W", "H", "pad_l", "pad_t",
                                        "preintegrate", "aov_count", "aov_vis", "aov_z", "off_aov",
                                        "off_seen", "off_cam", "off_lcol", "off_lmu", "off_lpath",
                                        "off_window", "off_signed"};
  const int shade_v[] = {nl, P->nvol, P->W, P->H, P->pad[0], P->pad[2], P->rs.preintegrate,
                         aov ? aov->count : 0, aov ? aov->vis : -1, aov ? aov->z : -1,
                         (int)(4 * nview), (int)(4 * nview + aov_floats), o->cam, o->lcol,
                         o->lmu, o->lpath, o->window, ICS_MAX_VOLUMES};
  for (size_t i = 0; i < sizeof shade_v / sizeof *shade_v; i++)
    for (int p = P_SELECT; p <= P_SHADE_SURFACES; p++) u_int(s, p, shade_i[i], shade_v[i]);
  u_dbl(s, P_SHADE, "window_max", ics_plan_window_max(P));
  u_dbl(s, P_SHADE_SURFACES, "window_max", ics_plan_window_max(P));
}

/* the image and AOVs read back after the last slab, the context's state checked, the passes'
 * times from the queries, the device string */
static ics_status read_back(gl_job *j, ics_image *img, ics_aov_buf *aov, ics_render_stats *stats,
                            char *msg, size_t msg_size) {
  gl_state *s = j->s;
  const ics_plan *P = j->P;
  size_t nview = (size_t)P->W * P->H, aov_floats = aov ? (size_t)aov->count * nview : 0;
  GLenum e = GL_NO_ERROR;
  GL_.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); /* the shaders' writes, then the readback */
  GL_.GetNamedBufferSubData(j->buf[B_OUT], 0, (GLsizeiptr)(sizeof(float) * 4 * nview), img->data);
  if (aov_floats)
    GL_.GetNamedBufferSubData(j->buf[B_OUT], (GLintptr)(sizeof(float) * 4 * nview),
                              (GLsizeiptr)(sizeof(float) * aov_floats), aov->data);
  GLenum reset = GL_.GetGraphicsResetStatus();
  if (reset != GL_NO_ERROR || (e = GL_.GetError()) != GL_NO_ERROR) {
    if (msg) {
      if (reset != GL_NO_ERROR)
        snprintf(msg, msg_size, "backend gl: the context was lost (%s) on %s",
                 ics_gl_reset_name(reset), s->g.renderer);
      else
        snprintf(msg, msg_size, "backend gl: %s reading the image back from %s", ics_gl_error_name(e),
                 s->g.renderer);
    }
    return reset == GL_NO_ERROR && e == GL_OUT_OF_MEMORY ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
  }
  for (int k = 0; k < P->K; k++) {
    GLuint64 t[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) GL_.GetQueryObjectui64v(j->queries[3 * k + i], GL_QUERY_RESULT, &t[i]);
    stats->ms_convolution += 1e-6 * (double)(t[1] - t[0]);
    stats->ms_shading += 1e-6 * (double)(t[2] - t[1]);
  }
  ics_plan_over_background(P, img);
  stats->threads = 0; /* a device: llvmpipe's threads are in the device string */
  stats->slabs = P->K;
  if (s->g.software)
    snprintf(stats->device, sizeof stats->device, "OpenGL %.20s: %.72s, %d threads", s->g.context,
             s->g.renderer, software_threads());
  else
    snprintf(stats->device, sizeof stats->device, "OpenGL %.20s: %.90s", s->g.context, s->g.renderer);
  return ICS_OK;
}

/* the slabs: each light's taps for the slab (uploaded), its shading window, the step and the
 * shading on the device, the buffers swapped; progress after each slab once the device has done
 * it */
static ics_status run_slabs(gl_job *j, const ics_render_opts *o, const double *blur,
                            ics_prop_taps *pts, ics_tap2d **scratch, char *msg, size_t msg_size) {
  gl_state *s = j->s;
  const ics_plan *P = j->P;
  int nl = P->nlights;
  double cum[ICS_SCENE_MAX_LIGHTS][2] = {{0}}, window[ICS_SCENE_MAX_LIGHTS] = {0};
  ics_status status = ICS_OK;
  GLenum e;
  for (int k = 0; k < P->K; k++) {
    double mag, q = ics_plan_slab_pixel(P, k, &mag);
    for (int l = 0; l < nl; l++) {
      window[l] = fmax(0, 1 - blur[l] / q);
      ics_prop_taps *pt = &pts[l];
      status = ics_plan_slab_taps(P, l, k, q, mag, cum[l], scratch[l], pt, msg, msg_size);
      size_t ntap = (size_t)pt->ntaps * (size_t)(pt->stencil ? 1 : pt->entries);
      if (status == ICS_OK && ntap * sizeof(gl_tap) > (size_t)s->max_block) {
        if (msg) snprintf(msg, msg_size, "backend gl: light %d, slab %d takes %zu taps, over the "
                          "driver's largest shader storage block (%lld bytes, %s)", l, k, ntap,
                          (long long)s->max_block, s->g.renderer);
        return ICS_ERR_SIZE;
      }
      if (status == ICS_OK &&
          !upload_taps(j, l, pt, ntap))
        status = ICS_ERR_NOMEM;
      if (status == ICS_ERR_NOMEM && msg)
        snprintf(msg, msg_size, "backend gl: light %d, slab %d: the taps could not be prepared "
                 "(out of memory, a tap out of range or a compensation that failed)", l, k);
      if (status != ICS_OK) return status;
    }
    GL_.NamedBufferSubData(j->buf[B_SD], (GLintptr)(sizeof(double) * (size_t)j->off_window),
                           (GLsizeiptr)(sizeof(double) * (size_t)nl), window);
    run_slab(j, k, pts);
    GLuint tmp = j->buf[B_SRC];
    j->buf[B_SRC] = j->buf[B_DST], j->buf[B_DST] = tmp;
    tmp = j->tex[0], j->tex[0] = j->tex[1], j->tex[1] = tmp;
    if ((e = GL_.GetError()) != GL_NO_ERROR) {
      if (msg) snprintf(msg, msg_size, "backend gl: %s in slab %d on %s", ics_gl_error_name(e), k,
                        s->g.renderer);
      return e == GL_OUT_OF_MEMORY ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
    }
    if (o->progress) {
      GL_.Finish(); /* the slab done, so the progress is the device's */
      o->progress(o->progress_ctx, k + 1, P->K);
    }
  }
  return ICS_OK;
}

static ics_status gl_render(void *state, const ics_plan *P, const ics_render_opts *o,
                            ics_image *img, ics_aov_buf *aov, ics_render_stats *stats, char *msg,
                            size_t msg_size) {
  gl_state *s = state;
  double t_start = ics_clock_s();
  int nl = P->nlights, nch = P->nch;
  size_t npx = (size_t)P->Wb * P->Hb, nview = (size_t)P->W * P->H, plane = P->buf.plane;
  size_t lbytes = sizeof(float) * (size_t)(nl ? nl : 1) * (size_t)nch * plane;
  size_t aov_floats = aov ? (size_t)aov->count * nview : 0;
  size_t out_floats = 4 * nview + aov_floats + nview;
  ics_status status = check_sizes(s, P, aov, msg, msg_size);
  if (status != ICS_OK) return status;
  ics_device_scene ds;
  if (ics_device_scene_create(&ds, P, !s->ldi_device) != ICS_OK) {
    if (msg) snprintf(msg, msg_size, "backend gl: out of host memory for the upload (%zu fragments)",
                      P->ldi.nfrag);
    return ICS_ERR_NOMEM;
  }
  if (!ics_gl_make_current(&s->g)) {
    if (msg) snprintf(msg, msg_size, "backend gl: the %s context cannot be made current on this "
                      "thread", s->g.context);
    ics_device_scene_destroy(&ds);
    return ICS_ERR_UNSUPPORTED;
  }
  gl_job job;
  memset(&job, 0, sizeof job);
  gl_job *j = &job;
  j->s = s, j->P = P;
  ics_prop_taps *pts = calloc((size_t)(nl ? nl : 1), sizeof *pts);
  ics_tap2d **scratch = calloc((size_t)(nl ? nl : 1), sizeof *scratch);
  /* host images of the packed buffers: per-pixel state (cursor, occlusion cursor, inside mask),
   * the span bytes padded to words, the scene's doubles (transfer rows, camera, lights, windows)
   * and ints (volume objects, signed lights) */
  sd_layout sdo = sd_offsets(ds.ntt);
  size_t nsd = (size_t)sdo.size;
  /* the plan's per-pixel state and spans (the device LDI makes its own) */
  uint32_t *pix = s->ldi_device ? NULL : malloc(sizeof *pix * 4 * (npx ? npx : 1));
  uint8_t *span = s->ldi_device ? NULL : calloc((ds.nfrag + 3) / 4, 4);
  double *sd = calloc(nsd, sizeof *sd);
  int32_t ints[ICS_MAX_VOLUMES + ICS_SCENE_MAX_LIGHTS];
  j->queries = calloc(3 * (size_t)(P->K ? P->K : 1), sizeof *j->queries);
  if (!pts || !scratch || (!s->ldi_device && (!pix || !span)) || !sd || !j->queries) goto nomem;
  for (int l = 0; l < nl; l++) {
    const ics_slab_kernel *sk = &P->kernels[l];
    scratch[l] = malloc(sizeof **scratch * (size_t)sk->entries * (size_t)sk->cap);
    if (!scratch[l]) goto nomem;
  }
  for (size_t p = 0; pix && p < npx; p++) {
    uint64_t m = ds.inside ? ds.inside[p] : 0;
    pix[4 * p] = pix[4 * p + 1] = P->ldi.offset[p];
    pix[4 * p + 2] = (uint32_t)m, pix[4 * p + 3] = (uint32_t)(m >> 32);
  }
  if (span) memcpy(span, ds.fspan, ds.nfrag);
  j->off_window = sdo.window;
  memcpy(sd, ds.tt, sizeof *sd * 5 * ds.ntt);
  memcpy(sd + sdo.cam, ds.cam, sizeof ds.cam);
  memcpy(sd + sdo.lcol, ds.lcol, sizeof ds.lcol);
  memcpy(sd + sdo.lmu, ds.lmu, sizeof ds.lmu);
  memcpy(sd + sdo.lpath, P->light_path, sizeof P->light_path);
  memcpy(ints, ds.vol_obj, sizeof ds.vol_obj);
  memcpy(ints + ICS_MAX_VOLUMES, ds.signed_l, sizeof ds.signed_l);

  while (GL_.GetError() != GL_NO_ERROR) {} /* what an earlier render left */
  if (s->ldi_device) { /* the fragments and per-pixel state from the device (ldi_gl.c) */
    ics_gl_ldi ldi;
    status = ics_gl_ldi_build(&s->g, s->ldi_prog, P, (long long)s->max_block, s->max_groups, &ldi,
                              msg, msg_size);
    if (status != ICS_OK) goto done;
    j->buf[B_OFFSET] = ldi.offset, j->buf[B_FZ] = ldi.fz, j->buf[B_FCODE] = ldi.fcode;
    j->buf[B_FGRAD] = ldi.fgrad, j->buf[B_FSPAN] = ldi.fspan, j->buf[B_PIX] = ldi.pix;
    stats->ms_geometry_device = ldi.ms;
  } else {
    j->buf[B_OFFSET] = ics_gl_buffer(&s->g, sizeof(uint32_t) * (npx + 1), P->ldi.offset);
    j->buf[B_FZ] = ics_gl_buffer(&s->g, sizeof *ds.fz * ds.nfrag, ds.fz);
    j->buf[B_FCODE] = ics_gl_buffer(&s->g, sizeof *ds.fcode * ds.nfrag, ds.fcode);
    j->buf[B_FGRAD] = ics_gl_buffer(&s->g, 2 * sizeof *ds.fgrad * ds.nfrag, ds.fgrad);
    j->buf[B_FSPAN] = ics_gl_buffer(&s->g, (ds.nfrag + 3) / 4 * 4, span);
    j->buf[B_PIX] = ics_gl_buffer(&s->g, sizeof *pix * 4 * (npx ? npx : 1), pix);
  }
  j->buf[B_SRC] = ics_gl_buffer(&s->g, lbytes, NULL);
  j->buf[B_DST] = ics_gl_buffer(&s->g, lbytes, NULL);
  const float one = 1;
  GL_.ClearNamedBufferData(j->buf[B_SRC], GL_R32F, GL_RED, GL_FLOAT, &one);
  GL_.CreateTextures(GL_TEXTURE_BUFFER, 2, j->tex);
  GL_.TextureBuffer(j->tex[0], GL_R32F, j->buf[B_SRC]);
  GL_.TextureBuffer(j->tex[1], GL_R32F, j->buf[B_DST]);
  j->buf[B_OBJ] = ics_gl_buffer(&s->g, sizeof *ds.obj * ds.nobj * ICS_DEV_OBJ_STRIDE, ds.obj);
  j->buf[B_SD] = ics_gl_buffer(&s->g, sizeof *sd * nsd, sd);
  j->buf[B_PERM] = ics_gl_buffer(&s->g, 512 * ds.nobj, ds.perm);
  j->buf[B_GRIDS] = ics_gl_buffer(&s->g, sizeof *ds.grids * ds.ncells, ds.grids);
  j->buf[B_INTS] = ics_gl_buffer(&s->g, sizeof ints, ints);
  j->buf[B_OUT] = ics_gl_buffer(&s->g, sizeof(float) * out_floats, NULL);
  j->buf[B_WORK] = ics_gl_buffer(&s->g, sizeof(uint32_t) * (10 + 2 * npx), NULL);
  j->buf[B_ENT] = ics_gl_buffer(&s->g, sizeof(uint32_t) * (npx ? npx : 1), NULL);
  GL_.GenQueries((GLsizei)(3 * P->K), j->queries);
  GLenum e = GL_.GetError();
  if (e != GL_NO_ERROR) {
    if (msg) snprintf(msg, msg_size, "backend gl: %s while allocating the buffers (%zu bytes of "
                      "light buffers, %zu fragments) on %s", ics_gl_error_name(e), 2 * lbytes,
                      P->ldi.nfrag, s->g.renderer);
    status = e == GL_OUT_OF_MEMORY ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
    goto done;
  }
  set_fixed_uniforms(s, P, aov, &sdo);
  status = run_slabs(j, o, ds.blur, pts, scratch, msg, msg_size);
  if (status != ICS_OK) goto done;
  status = read_back(j, img, aov, stats, msg, msg_size);
  if (status == ICS_OK && nl && P->K) stats->ns_per_px_slab = 1e6 * stats->ms_convolution / ((double)npx * P->K * nl);
  stats->ms_total = 1e3 * (ics_clock_s() - t_start);
  goto done;
nomem:
  status = ICS_ERR_NOMEM;
  if (msg) snprintf(msg, msg_size, "backend gl: out of host memory for the upload (%zu fragments)",
                    P->ldi.nfrag);
done:
  if (j->tex[0]) GL_.DeleteTextures(2, j->tex);
  for (int b = 0; b < NBUF; b++)
    if (j->buf[b]) GL_.DeleteBuffers(1, &j->buf[b]);
  for (int l = 0; l < nl; l++) {
    if (j->taps[l]) GL_.DeleteBuffers(1, &j->taps[l]);
    if (pts) ics_prop_release(&pts[l]);
    if (scratch) free(scratch[l]);
  }
  if (j->queries && j->queries[0]) GL_.DeleteQueries((GLsizei)(3 * P->K), j->queries);
  free(j->queries), free(j->host_taps);
  free(pix), free(span), free(sd);
  free(pts), free(scratch);
  ics_device_scene_destroy(&ds);
  ics_gl_release(&s->g); /* the thread's previous context, if any, is current again */
  return status;
}

/* the module's table (module_gl.c); the backend's entry: backend_gl_entry.c */
const ics_backend_funcs ics_gl_funcs = {gl_available, gl_auto_pick, gl_create, gl_render,
                                        gl_destroy};
