/* ldi_gl.c — the layered depth image built on the device (ldi_gl.h; the programs are
 * gpu/backends/gl/ldi.comp). The host uploads the objects' geometry (device_scene.c) and the camera, then:
 *   1. the cast appends every crossing to its pixel's linked list in a pool sized from the
 *      plan's fragment count; the pool's counter counts on past its end, so when the pool was
 *      too small the host grows it to the count and casts once more;
 *   2. the scan turns the per-pixel counts into offsets;
 *   3. the sort orders each pixel's list front to back and writes the fragments and the
 *      per-pixel shading state.
 * The pool, lists and counts are released; the shading's buffers are handed to the caller. */
#define _POSIX_C_SOURCE 200809L
#include "ldi_gl.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "clock.h"
#include "device_scene.h"
#include "ldi_comp_source.h"
#include "scene_internal.h" /* ics_ldi_comp_source: gpu/backends/gl/ldi.comp (cmake/embed_text.cmake) */

static const char *const LDI_NAMES[ICS_GL_LDI_NPROGS] = {"ICS_K_LDI_CAST", "ICS_K_LDI_SCAN",
                                                         "ICS_K_LDI_SORT"};

int ics_gl_ldi_programs(ics_gl *g, GLuint prog[ICS_GL_LDI_NPROGS], char *msg, size_t msg_size) {
  for (int i = 0; i < ICS_GL_LDI_NPROGS; i++) {
    char head[64], name[64];
    snprintf(head, sizeof head, "#define %s 1\n#line 2\n", LDI_NAMES[i]);
    snprintf(name, sizeof name, "ldi.comp (%s)", LDI_NAMES[i]);
    if (!ics_gl_compile(g, ics_ldi_comp_source, head, name, &prog[i], msg, msg_size)) {
      for (int j = 0; j < i; j++) g->gl.DeleteProgram(prog[j]), prog[j] = 0;
      return 0;
    }
  }
  return 1;
}

void ics_gl_ldi_release(ics_gl *g, ics_gl_ldi *l) {
  GLuint b[] = {l->offset, l->fz, l->fcode, l->fgrad, l->fspan, l->pix};
  for (size_t i = 0; i < sizeof b / sizeof *b; i++)
    if (b[i]) g->gl.DeleteBuffers(1, &b[i]);
  memset(l, 0, sizeof *l);
}

/* the working buffers of one build */
enum { W_GEO, W_CAM, W_NBOX, W_NLINK, W_TRIS, W_TN, W_LINK, W_HEAD, W_CNT, W_INSIDE, W_CTR,
       W_ORDER, NWORK };

static void run(ics_gl *g, GLuint prog, GLuint gx, GLuint gy) {
  g->gl.UseProgram(prog);
  g->gl.DispatchCompute(gx, gy, 1);
  g->gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* a GL error or a lost context since the last check, named into msg */
static ics_status gl_failed(ics_gl *g, const char *when, char *msg, size_t msg_size) {
  GLenum reset = g->gl.GetGraphicsResetStatus(), e = g->gl.GetError();
  if (reset == GL_NO_ERROR && e == GL_NO_ERROR) return ICS_OK;
  if (reset != GL_NO_ERROR)
    snprintf(msg, msg_size, "backend gl: the context was lost (%s) %s (the layered depth image) "
             "on %s", ics_gl_reset_name(reset), when, g->renderer);
  else
    snprintf(msg, msg_size, "backend gl: %s %s (the layered depth image) on %s",
             ics_gl_error_name(e), when, g->renderer);
  return reset == GL_NO_ERROR && e == GL_OUT_OF_MEMORY ? ICS_ERR_NOMEM : ICS_ERR_UNSUPPORTED;
}

ics_status ics_gl_ldi_build(ics_gl *g, const GLuint prog[ICS_GL_LDI_NPROGS], const ics_plan *P,
                            long long max_block, const int max_groups[3], ics_gl_ldi *out,
                            char *msg, size_t msg_size) {
  memset(out, 0, sizeof *out);
  double t_start = ics_clock_s();
  size_t npx = (size_t)P->Wb * P->Hb;
  ics_device_geometry geo;
  if (ics_device_geometry_create(&geo, P) != ICS_OK) {
    snprintf(msg, msg_size, "backend gl: out of host memory for the objects' geometry");
    return ICS_ERR_NOMEM;
  }
  double cam[ICS_DEV_CAM];
  ics_device_camera(P, cam);
  /* the pool: the plan's fragments and a margin for the crossings a mesh merges or that lie
   * behind the eye; grown once if the cast finds more */
  size_t cap = P->ldi.nfrag + npx / 4 + 64;
  GLuint w[NWORK] = {0};
  ics_status st = ICS_OK;
  const struct { const char *what; size_t bytes; } sizes[] = {
      {"object records", sizeof(double) * ICS_DEV_GEO_STRIDE * geo.nobj},
      {"mesh BVH nodes", sizeof(double) * 6 * geo.nnodes},
      {"mesh triangles", sizeof(double) * 9 * geo.ntris},
      {"per-pixel shading state", sizeof(uint32_t) * 4 * npx},
      {"pool of crossings", sizeof(double) * 4 * cap}};
  for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
    if ((long long)sizes[i].bytes > max_block) {
      snprintf(msg, msg_size, "backend gl: the layered depth image's %s: %zu bytes, over the "
               "driver's largest shader storage block (%lld bytes, %s)", sizes[i].what,
               sizes[i].bytes, max_block, g->renderer);
      ics_device_geometry_destroy(&geo);
      return ICS_ERR_SIZE;
    }
  while (g->gl.GetError() != GL_NO_ERROR) {}
  w[W_GEO] = ics_gl_buffer(g, sizeof(double) * ICS_DEV_GEO_STRIDE * geo.nobj, geo.geo);
  w[W_CAM] = ics_gl_buffer(g, sizeof cam, cam);
  w[W_NBOX] = ics_gl_buffer(g, sizeof(double) * 6 * geo.nnodes, geo.node_box);
  w[W_NLINK] = ics_gl_buffer(g, sizeof(int32_t) * 4 * geo.nnodes, geo.node_link);
  w[W_TRIS] = ics_gl_buffer(g, sizeof(double) * 9 * geo.ntris, geo.tris);
  w[W_HEAD] = ics_gl_buffer(g, sizeof(uint32_t) * npx, NULL);
  w[W_CNT] = ics_gl_buffer(g, sizeof(uint32_t) * npx, NULL);
  w[W_INSIDE] = ics_gl_buffer(g, sizeof(uint32_t) * 2 * npx, NULL);
  w[W_CTR] = ics_gl_buffer(g, sizeof(uint32_t) * 3, NULL);
  ics_device_geometry_destroy(&geo);

  GLuint cast = prog[ICS_GL_LDI_CAST], scan = prog[ICS_GL_LDI_SCAN], sort = prog[ICS_GL_LDI_SORT];
  for (int i = 0; i < ICS_GL_LDI_NPROGS; i++) {
    ics_gl_uniform_i(g, prog[i], "npx", (int)npx);
    ics_gl_uniform_i(g, prog[i], "gw", P->Wb), ics_gl_uniform_i(g, prog[i], "gh", P->Hb);
    ics_gl_uniform_i(g, prog[i], "W", P->W), ics_gl_uniform_i(g, prog[i], "H", P->H);
    ics_gl_uniform_i(g, prog[i], "pad_l", P->pad[0]), ics_gl_uniform_i(g, prog[i], "pad_t", P->pad[2]);
  }
  ics_gl_uniform_i(g, cast, "nobj", P->scene->nobjects);
  ics_gl_uniform_d(g, sort, "z0", P->z0), ics_gl_uniform_d(g, sort, "e", P->e);
  ics_gl_uniform_d(g, sort, "reach", ics_ldi_kernel_reach(P));
  ics_gl_uniform_i(g, sort, "K", P->K);
  static const struct { int binding, buf; } cast_b[] = {
      {0, W_GEO}, {1, W_CAM}, {2, W_NBOX}, {3, W_NLINK}, {4, W_TN}, {5, W_LINK},
      {6, W_HEAD}, {7, W_CNT}, {8, W_INSIDE}, {9, W_CTR}, {10, W_TRIS}};
  uint32_t ctr[3] = {0, 0, 0}; /* pushes, the largest count, the most pushes of one pixel */
  for (out->casts = 1;; out->casts++) {
    w[W_TN] = ics_gl_buffer(g, sizeof(double) * 4 * cap, NULL);
    w[W_LINK] = ics_gl_buffer(g, sizeof(uint32_t) * 2 * cap, NULL);
    for (size_t i = 0; i < sizeof cast_b / sizeof *cast_b; i++)
      g->gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)cast_b[i].binding, w[cast_b[i].buf]);
    ics_gl_uniform_ui(g, cast, "cap", (unsigned)cap);
    const GLuint zero = 0;
    g->gl.ClearNamedBufferData(w[W_CTR], GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    run(g, cast, (GLuint)((P->Wb + 15) / 16), (GLuint)((P->Hb + 7) / 8));
    g->gl.GetNamedBufferSubData(w[W_CTR], 0, sizeof ctr, ctr);
    if ((st = gl_failed(g, "casting the rays", msg, msg_size)) != ICS_OK) goto done;
    if ((uint64_t)ctr[2] * npx >= UINT32_MAX) { /* the 32-bit counter may have wrapped */
      snprintf(msg, msg_size, "backend gl: up to %u crossings per pixel over %zu pixels: more "
               "than the device's 32-bit crossing counter holds (use --gl-ldi plan)", ctr[2], npx);
      st = ICS_ERR_SIZE;
      goto done;
    }
    if (ctr[0] <= cap || out->casts == 2) break;
    cap = ctr[0];
    if ((long long)(sizeof(double) * 4 * cap) > max_block) {
      snprintf(msg, msg_size, "backend gl: %zu crossings need a pool of %zu bytes, over the "
               "driver's largest shader storage block (%lld bytes, %s)", cap,
               sizeof(double) * 4 * cap, max_block, g->renderer);
      st = ICS_ERR_SIZE;
      goto done;
    }
    g->gl.DeleteBuffers(1, &w[W_TN]), g->gl.DeleteBuffers(1, &w[W_LINK]);
    w[W_TN] = w[W_LINK] = 0;
  }
  if (ctr[0] > cap) { /* the second cast found more than the first: cannot happen */
    snprintf(msg, msg_size, "backend gl: the second cast found %u crossings, over the %zu the "
             "first counted (%s)", ctr[0], cap, g->renderer);
    st = ICS_ERR_UNSUPPORTED;
    goto done;
  }
  size_t nodes = ctr[0] ? ctr[0] : 1;
  if ((long long)(2 * sizeof(float) * nodes) > max_block) {
    snprintf(msg, msg_size, "backend gl: %zu fragments' depth gradients take %zu bytes, over the "
             "driver's largest shader storage block (%lld bytes, %s)", nodes,
             2 * sizeof(float) * nodes, max_block, g->renderer);
    st = ICS_ERR_SIZE;
    goto done;
  }
  out->offset = ics_gl_buffer(g, sizeof(uint32_t) * (npx + 1), NULL);
  w[W_ORDER] = ics_gl_buffer(g, sizeof(uint32_t) * nodes, NULL);
  out->fz = ics_gl_buffer(g, sizeof(float) * nodes, NULL);
  out->fcode = ics_gl_buffer(g, sizeof(uint32_t) * nodes, NULL);
  out->fgrad = ics_gl_buffer(g, 2 * sizeof(float) * nodes, NULL);
  out->fspan = ics_gl_buffer(g, (nodes + 3) / 4 * 4, NULL);
  out->pix = ics_gl_buffer(g, sizeof(uint32_t) * 4 * npx, NULL);
  g->gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, w[W_CNT]);
  g->gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, out->offset);
  run(g, scan, 1, 1);
  const struct { int binding; GLuint buf; } sort_b[] = {
      {0, w[W_GEO]}, {1, w[W_CAM]}, {2, out->pix}, {3, out->fspan}, {4, w[W_TN]},
      {5, w[W_LINK]}, {6, w[W_HEAD]}, {8, w[W_INSIDE]}, {11, out->offset}, {12, w[W_ORDER]},
      {13, out->fz}, {14, out->fcode}, {15, out->fgrad}};
  for (size_t i = 0; i < sizeof sort_b / sizeof *sort_b; i++)
    g->gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)sort_b[i].binding, sort_b[i].buf);
  size_t groups = (npx + 63) / 64, gx = groups < (size_t)max_groups[0] ? groups : (size_t)max_groups[0];
  if (!gx) gx = 1;
  run(g, sort, (GLuint)gx, (GLuint)((groups + gx - 1) / gx));
  uint32_t total = 0;
  g->gl.GetNamedBufferSubData(out->offset, (GLintptr)(sizeof(uint32_t) * npx), sizeof total, &total);
  if ((st = gl_failed(g, "sorting the fragments", msg, msg_size)) != ICS_OK) goto done;
  out->nfrag = total;
  out->max_layers = (int)ctr[1];
  out->ms = 1e3 * (ics_clock_s() - t_start);
done:
  for (int i = 0; i < NWORK; i++)
    if (w[i]) g->gl.DeleteBuffers(1, &w[i]);
  if (st != ICS_OK) ics_gl_ldi_release(g, out);
  return st;
}
