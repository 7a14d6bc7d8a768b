/* test_lut_glsl.c — the GLSL lookup-table header runs, not only compiles: concatenated into a
 * #version 450 compute shader on the gl backend's context (gl_context.c: EGL or OSMesa, llvmpipe
 * here), it evaluates ics_tab_ellipse_tap at the cases of tap_cases.h and ics_tab_ellipse_radii
 * at ratios over [1e-6, 1e6]; the taps must lie within twice the header's stamped float radii
 * error + the float allowance of test_lut_opencl.c (TAP_FLOAT_ARC) + 11 float epsilons (GLSL
 * allows 2.5 ulp per division and more for sqrt, as OpenCL's 11-ulp chain) of the larger radius
 * from ics_ellipse_kernel's, and the radii within the stamped float radii error + 11 epsilons of
 * the exact ones. Exit 77 (skipped) without a context.
 * usage: test_lut_glsl HEADER.glsl ... */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_testutil.h"
#include "icshadow.h"
#include "tap_cases.h"
#include "testutil.h"

#define GLSL_ULPS (11 * FLT_EPSILON)
#define NRAD 241

static const char *epilogue =
    "\nlayout(local_size_x = 64) in;\n"
    "layout(std430, binding = 0) readonly buffer In { vec4 v[]; };\n"
    "layout(std430, binding = 1) readonly buffer NK { ivec2 nk[]; };\n"
    "layout(std430, binding = 2) writeonly buffer Out { vec2 o[]; };\n"
    "uniform int ntaps, nrad;\n"
    "void main() {\n"
    "  int i = int(gl_GlobalInvocationID.x);\n"
    "  if (i < ntaps) o[i] = ics_tab_ellipse_tap(v[i].x, v[i].y, v[i].z, nk[i].x, nk[i].y, v[i].w);\n"
    "  else if (i < ntaps + nrad) o[i] = ics_tab_ellipse_radii(v[i].x, v[i].y);\n"
    "}\n";

static void run_one(ics_gl *g, const char *path) {
  ics_gl_fns *G = &g->gl;
  char *hdr = test_read_text(path);
  CHECK(hdr != NULL, "cannot read %s", path);
  if (!hdr) return;
  double e_radii = NAN;
  const char *p = strstr(hdr, "ellipse_radii (a and b)");
  p = p ? strchr(p, ':') : NULL;
  CHECK(p && sscanf(p + 1, "%lf", &e_radii) == 1, "%s: no stamped float radii error", path);
  size_t len = strlen(hdr) + strlen(epilogue) + 32;
  char *src = malloc(len);
  snprintf(src, len, "#version 450\n%s%s", hdr, epilogue);
  GLuint prog = 0;
  char log[8192] = "";
  int ok = ics_gl_compile(g, src, "", path, &prog, log, sizeof log);
  CHECK(ok, "%s", log);
  if (!ok) {
    free(src), free(hdr);
    return;
  }
  static tap_case tc[TAP_CASES_MAX];
  int nc = tap_cases(tc), n = nc + NRAD;
  float *in = calloc((size_t)n, 4 * sizeof *in), *out = calloc((size_t)n, 2 * sizeof *out);
  int *nk = calloc((size_t)n, 2 * sizeof *nk);
  double rat[NRAD];
  for (int i = 0; i < nc; i++) {
    float *v = in + 4 * i;
    v[0] = (float)tc[i].varx, v[1] = (float)tc[i].vary, v[2] = (float)tc[i].angle;
    v[3] = (float)tc[i].u;
    nk[2 * i] = tc[i].n, nk[2 * i + 1] = tc[i].k;
  }
  for (int i = 0; i < NRAD; i++) { /* radii of (1, rat): rat = 10^(-6 .. 6) */
    rat[i] = (double)(float)pow(10.0, -6.0 + 12.0 * i / (NRAD - 1));
    in[4 * (nc + i)] = 1.0f, in[4 * (nc + i) + 1] = (float)rat[i];
  }
  GLuint b[3];
  G->CreateBuffers(3, b);
  G->NamedBufferStorage(b[0], (GLsizeiptr)(4 * sizeof *in * (size_t)n), in, 0);
  G->NamedBufferStorage(b[1], (GLsizeiptr)(2 * sizeof *nk * (size_t)n), nk, 0);
  G->NamedBufferStorage(b[2], (GLsizeiptr)(2 * sizeof *out * (size_t)n), NULL, 0);
  for (GLuint i = 0; i < 3; i++) G->BindBufferBase(GL_SHADER_STORAGE_BUFFER, i, b[i]);
  G->UseProgram(prog);
  G->ProgramUniform1i(prog, G->GetUniformLocation(prog, "ntaps"), nc);
  G->ProgramUniform1i(prog, G->GetUniformLocation(prog, "nrad"), NRAD);
  G->DispatchCompute((GLuint)((n + 63) / 64), 1, 1);
  G->MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  G->GetNamedBufferSubData(b[2], 0, (GLsizeiptr)(2 * sizeof *out * (size_t)n), out);
  GLenum e = G->GetError();
  CHECK(e == GL_NO_ERROR, "%s: GL error 0x%x", path, e);
  double worst = 0, tap_bound = 2 * e_radii + TAP_FLOAT_ARC + GLSL_ULPS;
  int wi = 0;
  for (int i = 0; i < nc; i++) {
    double err = tap_error(&tc[i], out[2 * i], out[2 * i + 1]);
    if (!(err <= worst)) worst = err, wi = i;
  }
  double wr = 0, rad_bound = e_radii + GLSL_ULPS;
  for (int i = 0; i < NRAD; i++) {
    ics_ellipse_shape shp;
    ics_ellipse_kernel(1.0, rat[i], 0, 2, 0, &shp, NULL);
    double ea = fabs(out[2 * (nc + i)] - shp.a) / shp.a, eb = fabs(out[2 * (nc + i) + 1] - shp.b) / shp.b;
    if (!(fmax(ea, eb) <= wr)) wr = fmax(ea, eb);
  }
  printf("%s on %s: ellipse_tap: %d taps, worst %.3g of the larger radius (bound %.3g) at varx %g, "
         "vary %g, angle %g, n %d, k %d, u %g; ellipse_radii: worst %.3g (bound %.3g)\n", path,
         g->renderer, nc, worst, tap_bound, tc[wi].varx, tc[wi].vary, tc[wi].angle, tc[wi].n,
         tc[wi].k, tc[wi].u, wr, rad_bound);
  CHECK(worst <= tap_bound, "%s: ellipse_tap off by %.3g of the radius", path, worst);
  CHECK(wr <= rad_bound, "%s: ellipse_radii off by %.3g", path, wr);
  G->DeleteBuffers(3, b);
  G->DeleteProgram(prog);
  free(in), free(out), free(nk), free(src), free(hdr);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_lut_glsl HEADER.glsl ...\n");
    return 2;
  }
  ics_gl g;
  gl_open_or_skip(&g);
  for (int i = 1; i < argc; i++) run_one(&g, argv[i]);
  ics_gl_close(&g);
  return test_summary("test_lut_glsl");
}
