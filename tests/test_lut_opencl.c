/* test_lut_opencl.c — the OpenCL lookup-table header compiles (clBuildProgram) and computes what
 * was measured: a kernel evaluates ics_tab_ratio_to_ab, ics_tab_vx and ics_tab_ellipse_radii at
 * test points, and the results are compared
 *   (1) bit for bit with the C float mirror (ics_lut_float_*, which the stamped float error was
 *       measured with), when the device offers correctly rounded sqrt and division
 *       (-cl-fp32-correctly-rounded-divide-sqrt); otherwise within the spec's ulps (below);
 *   (2) with the exact functions: relative error <= the header's stamped table error (double
 *       evaluation) + ICS_LUT_FLOAT_EXTRA (+ the device allowance), and for the checked-in size
 *       <= the documented bounds (icshadow/lut.h) + the same;
 *   (3) ics_tab_ellipse_tap against ics_ellipse_kernel (tap_cases.h): within twice the stamped
 *       float radii error (the radii and the axis ratio) + TAP_FLOAT_ARC of the larger radius.
 * usage: test_lut_opencl HEADER.cl [more headers]. Exit 77 (skipped) when there is no OpenCL
 * platform or device. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "icshadow.h"
#include "tap_cases.h"
#include "testutil.h"


#define NPTS 4096


/* "ratio_to_ab (a = 1 - t and b = t): 2.41e-06" etc. in the stamp */
static int stamped(const char *src, const char *key, double *v) {
  const char *p = strstr(src, key);
  if (!p) return -1;
  p = strchr(p, ':');
  return p && sscanf(p + 1, "%lf", v) == 1 ? 0 : -1;
}

static int stamped_size(const char *src) {
  const char *p = strstr(src, "#define ICS_TAB_N ");
  int n = 0;
  return p && sscanf(p + 18, "%d", &n) == 1 ? n : -1;
}

static const char *kernel_src =
    "\n__kernel void eval_lut(__global const float *rat, __global const float *t,\n"
    "                       __global float *out) {\n"
    "  size_t i = get_global_id(0);\n"
    "  float2 ab = ics_tab_ratio_to_ab(rat[i]);\n"
    "  float2 r = (rat[i] <= 1.0e37f) ? ics_tab_ellipse_radii(1.0f, rat[i]) : (float2)(0.0f, 0.0f);\n"
    "  out[6 * i + 0] = ab.x;\n"
    "  out[6 * i + 1] = ab.y;\n"
    "  out[6 * i + 2] = ics_tab_vx(t[i]);\n"
    "  out[6 * i + 3] = r.x;\n"
    "  out[6 * i + 4] = r.y;\n"
    "  out[6 * i + 5] = ics_tab_ratio_to_t(rat[i]) - ab.y + ics_tab_vx_ab((float2)(1.0f - t[i], t[i]))\n"
    "                   - ics_tab_vx(t[i]);\n"
    "}\n"
    "__kernel void eval_taps(__global const float4 *in, __global const int2 *nk,\n"
    "                        __global float2 *out) {\n"
    "  size_t i = get_global_id(0);\n"
    "  out[i] = ics_tab_ellipse_tap(in[i].x, in[i].y, in[i].z, nk[i].x, nk[i].y, in[i].w);\n"
    "}\n";

static double rel(double x, double ref) {
  if (isnan(x) || isnan(ref)) return INFINITY;
  if (ref == 0 || isinf(ref) || isinf(x)) return x == ref ? 0 : INFINITY;
  return fabs(x - ref) / fabs(ref);
}

/* relative difference in units of float epsilon */
static double ulps(float x, float ref) {
  if (x == ref) return 0;
  if (isnan(x) || isnan(ref) || ref == 0) return INFINITY;
  return fabs((double)x - ref) / (fabs((double)ref) * FLT_EPSILON);
}

static int run_one(cl_context ctx, cl_device_id dev, cl_command_queue q, int exact_rounding,
                   const char *path) {
  char *hdr = test_read_text(path);
  CHECK(hdr != NULL, "cannot read %s", path);
  if (!hdr) return -1;
  int n = stamped_size(hdr);
  /* the float errors stamped (grid maxima) and the table errors (double evaluation) */
  double e_ratio, e_vx, e_radii, t_ratio, t_vx, t_radii;
  int ok = stamped(hdr, "ratio_to_ab (a = 1 - t and b = t)", &e_ratio) == 0 &&
           stamped(hdr, "vx (abToVarx)", &e_vx) == 0 &&
           stamped(hdr, "ellipse_radii (a and b)", &e_radii) == 0;
  const char *te = strstr(hdr, "Table error alone (double evaluation):");
  ok = ok && te && sscanf(te, "Table error alone (double evaluation): ratio %lf, vx %lf, radii %lf",
                          &t_ratio, &t_vx, &t_radii) == 3;
  CHECK(ok && n >= ICS_LUT_MIN_SIZE, "%s: no stamp (size %d)", path, n);
  if (!ok || n < ICS_LUT_MIN_SIZE) {
    free(hdr);
    return -1;
  }

  size_t len = strlen(hdr) + strlen(kernel_src) + 1;
  char *src = malloc(len);
  snprintf(src, len, "%s%s", hdr, kernel_src);
  cl_int err;
  const char *csrc = src;
  cl_program prog = clCreateProgramWithSource(ctx, 1, &csrc, NULL, &err);
  const char *opts = exact_rounding ? "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt"
                                    : "-cl-std=CL1.2";
  err = clBuildProgram(prog, 1, &dev, opts, NULL, NULL);
  if (err != CL_SUCCESS) {
    char log[16384] = "";
    clGetProgramBuildInfo(prog, dev, CL_PROGRAM_BUILD_LOG, sizeof log - 1, log, NULL);
    fprintf(stderr, "%s: clBuildProgram failed (%d):\n%s\n", path, err, log);
  }
  CHECK(err == CL_SUCCESS, "%s compiles with clBuildProgram (%s)", path, opts);
  printf("%s: clBuildProgram OK (size %d, options %s)\n", path, n, opts);
  if (err != CL_SUCCESS) {
    free(src);
    free(hdr);
    return -1;
  }

  /* Test points: rat log-uniform over [1e-30, 1e30] plus 0, 1, FLT_MIN, FLT_MAX, +inf;
   * t uniform over [0, 1] plus 0, 1 and points near both ends. */
  static float rat[NPTS], t[NPTS], out[6 * NPTS];
  unsigned long long st = 12345;
  for (int i = 0; i < NPTS; i++) {
    st = st * 6364136223846793005ull + 1442695040888963407ull;
    double u = (double)(st >> 11) / 9007199254740992.0;
    rat[i] = (float)pow(10.0, -30.0 + 60.0 * u);
    t[i] = (float)((i + 0.5) / NPTS);
  }
  rat[0] = 0.0f, rat[1] = 1.0f, rat[2] = FLT_MIN, rat[3] = FLT_MAX, rat[4] = INFINITY;
  t[0] = 0.0f, t[1] = 1.0f, t[2] = 1e-7f, t[3] = 1.0f - 1e-7f, t[4] = 0.5f;

  cl_mem brat = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof rat, rat, &err);
  cl_mem bt = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof t, t, &err);
  cl_mem bout = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, sizeof out, NULL, &err);
  cl_kernel k = clCreateKernel(prog, "eval_lut", &err);
  CHECK(err == CL_SUCCESS, "clCreateKernel: %d", err);
  clSetKernelArg(k, 0, sizeof brat, &brat);
  clSetKernelArg(k, 1, sizeof bt, &bt);
  clSetKernelArg(k, 2, sizeof bout, &bout);
  size_t gsz = NPTS;
  err = clEnqueueNDRangeKernel(q, k, 1, NULL, &gsz, NULL, 0, NULL, NULL);
  if (err == CL_SUCCESS) err = clEnqueueReadBuffer(q, bout, CL_TRUE, 0, sizeof out, out, 0, NULL, NULL);
  CHECK(err == CL_SUCCESS, "kernel run: %d", err);

  /* The same tables in C (the header was generated from these: the lut_regen test diffs it). */
  double *s = malloc(n * sizeof *s), *g = malloc(n * sizeof *g);
  float *sf = malloc(n * sizeof *sf), *gf = malloc(n * sizeof *gf);
  CHECK(ics_lut_build(n, s, g) == ICS_OK, "ics_lut_build(%d)", n);
  for (int i = 0; i < n; i++) sf[i] = (float)s[i], gf[i] = (float)g[i];

  /* Bounds (icshadow/lut.h): float evaluation error <= table error + ICS_LUT_FLOAT_EXTRA, the
   * table error being the stamped double-evaluation maximum (x 1.01: the stamp's 3 significant
   * digits and its grid of 16 points per interval can each understate the maximum by < 0.5 %).
   * Device allowance when sqrt/division are not correctly rounded: OpenCL 1.2 allows 3 ulp for
   * sqrt and 2.5 ulp for division; the evaluation chain has at most 2 sqrt and 2 divisions ahead
   * of each result, each propagating with a factor <= 1: 11 ulp, i.e. 11 FLT_EPSILON relative. */
  double allow_ulps = exact_rounding ? 0.0 : 11.0;
  double allow = allow_ulps * FLT_EPSILON + ICS_LUT_FLOAT_EXTRA;
  double max_mirror = 0, max_r = 0, max_v = 0, max_k = 0;
  for (int i = 0; i < NPTS && err == CL_SUCCESS; i++) {
    float ma, mb, mka = 0, mkb = 0, mv = ics_lut_float_vx(n, gf, t[i]);
    ics_lut_float_ratio_to_ab(n, sf, rat[i], &ma, &mb);
    int radii = rat[i] <= 1e37f;
    if (radii) ics_lut_float_ellipse_radii(n, sf, gf, 1.0f, rat[i], &mka, &mkb);
    const float *o = out + 6 * i;
    double d = fmax(fmax(ulps(o[0], ma), ulps(o[1], mb)), ulps(o[2], mv));
    if (radii) d = fmax(d, fmax(ulps(o[3], mka), ulps(o[4], mkb)));
    if (d > max_mirror) max_mirror = d;
    CHECK(d <= allow_ulps, "point %d (rat %.9g, t %.9g): kernel differs from the C float mirror "
          "by %.3g ulp: (%.9g %.9g %.9g %.9g %.9g) vs (%.9g %.9g %.9g %.9g %.9g)",
          i, rat[i], t[i], d, o[0], o[1], o[2], o[3], o[4], ma, mb, mv, mka, mkb);
    CHECK(o[5] == 0.0f, "point %d: ratio_to_t / vx_ab disagree with ratio_to_ab / vx: %g", i, o[5]);
    /* against the exact functions */
    double r = rat[i], a_ex, b_ex;
    if (r <= 1) {
      b_ex = ics_ellipse_ratio_to_t(r);
      a_ex = 1 - b_ex;
    } else {
      a_ex = isinf(r) ? 0 : ics_ellipse_ratio_to_t(1 / r);
      b_ex = 1 - a_ex;
    }
    double er = fmax(rel(o[0], a_ex), rel(o[1], b_ex));
    double ev = rel(o[2], ics_ellipse_vx(t[i]));
    if (er > max_r) max_r = er;
    if (ev > max_v) max_v = ev;
    CHECK(er <= t_ratio * 1.01 + allow, "rat %.9g: ratio error %.3g > bound %.3g", r, er,
          t_ratio * 1.01 + allow);
    CHECK(ev <= t_vx * 1.01 + allow, "t %.9g: vx error %.3g > bound %.3g", t[i], ev,
          t_vx * 1.01 + allow);
    if (radii) {
      double sc = r <= 1 ? 1 / ics_ellipse_vx(b_ex) : r / ics_ellipse_vx(a_ex);
      double ek = fmax(rel(o[3], a_ex * sqrt(sc)), rel(o[4], b_ex * sqrt(sc)));
      if (ek > max_k) max_k = ek;
      CHECK(ek <= t_radii * 1.01 + allow, "rat %.9g: radii error %.3g > bound %.3g", r, ek,
            t_radii * 1.01 + allow);
    }
  }
  /* (3) the taps */
  static tap_case tc[TAP_CASES_MAX];
  static cl_float4 tin[TAP_CASES_MAX];
  static cl_int2 tnk[TAP_CASES_MAX];
  static cl_float2 tout[TAP_CASES_MAX];
  int nc = tap_cases(tc);
  for (int i = 0; i < nc; i++) {
    tin[i] = (cl_float4){{(float)tc[i].varx, (float)tc[i].vary, (float)tc[i].angle, (float)tc[i].u}};
    tnk[i] = (cl_int2){{tc[i].n, tc[i].k}};
  }
  cl_mem bin = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof tin, tin, &err);
  cl_mem bnk = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof tnk, tnk, &err);
  cl_mem btap = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, sizeof tout, NULL, &err);
  cl_kernel kt = clCreateKernel(prog, "eval_taps", &err);
  CHECK(err == CL_SUCCESS, "clCreateKernel(eval_taps): %d", err);
  clSetKernelArg(kt, 0, sizeof bin, &bin);
  clSetKernelArg(kt, 1, sizeof bnk, &bnk);
  clSetKernelArg(kt, 2, sizeof btap, &btap);
  size_t gtap = (size_t)nc;
  err = clEnqueueNDRangeKernel(q, kt, 1, NULL, &gtap, NULL, 0, NULL, NULL);
  if (err == CL_SUCCESS)
    err = clEnqueueReadBuffer(q, btap, CL_TRUE, 0, sizeof(cl_float2) * (size_t)nc, tout, 0, NULL, NULL);
  CHECK(err == CL_SUCCESS, "eval_taps run: %d", err);
  double worst = 0, tap_bound = 2 * e_radii + TAP_FLOAT_ARC;
  int wi = 0;
  for (int i = 0; i < nc && err == CL_SUCCESS; i++) {
    double e = tap_error(&tc[i], tout[i].s[0], tout[i].s[1]);
    if (!(e <= worst)) worst = e, wi = i;
  }
  printf("%s: ellipse_tap: %d taps, worst %.3g of the larger radius (bound %.3g) at varx %g, "
         "vary %g, angle %g, n %d, k %d, u %g\n", path, nc, worst, tap_bound, tc[wi].varx,
         tc[wi].vary, tc[wi].angle, tc[wi].n, tc[wi].k, tc[wi].u);
  CHECK(worst <= tap_bound, "%s: ellipse_tap off by %.3g of the radius", path, worst);
  clReleaseKernel(kt);
  clReleaseMemObject(bin);
  clReleaseMemObject(bnk);
  clReleaseMemObject(btap);
  printf("%s: max |kernel - C float mirror| %.3g ulp; max rel error vs exact: ratio %.3g "
         "(stamped %.3g), vx %.3g (stamped %.3g), radii %.3g (stamped %.3g)\n",
         path, max_mirror, max_r, e_ratio, max_v, e_vx, max_k, e_radii);
  if (n == ICS_LUT_BUILTIN_SIZE) {
    CHECK(max_r <= ICS_LUT_BUILTIN_RATIO_BOUND + allow, "ratio %.3g > documented bound", max_r);
    CHECK(max_v <= ICS_LUT_BUILTIN_VX_BOUND + allow, "vx %.3g > documented bound", max_v);
    CHECK(max_k <= ICS_LUT_BUILTIN_RADII_BOUND + allow, "radii %.3g > documented bound", max_k);
  }
  clReleaseKernel(k);
  clReleaseMemObject(brat);
  clReleaseMemObject(bt);
  clReleaseMemObject(bout);
  clReleaseProgram(prog);
  free(s), free(g), free(sf), free(gf), free(src), free(hdr);
  return 0;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: test_lut_opencl HEADER.cl ...\n");
    return 2;
  }
  cl_platform_id plats[8];
  cl_uint np = 0;
  if (clGetPlatformIDs(8, plats, &np) != CL_SUCCESS || np == 0) {
    printf("SKIPPED: no OpenCL platform (install pocl-opencl-icd)\n");
    return 77;
  }
  cl_device_id dev = NULL;
  for (cl_uint p = 0; p < np && !dev; p++)
    if (clGetDeviceIDs(plats[p], CL_DEVICE_TYPE_ALL, 1, &dev, NULL) != CL_SUCCESS) dev = NULL;
  if (!dev) {
    printf("SKIPPED: no OpenCL device\n");
    return 77;
  }
  char name[256] = "";
  clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof name, name, NULL);
  cl_device_fp_config fp = 0;
  clGetDeviceInfo(dev, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp, NULL);
  int exact_rounding = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  printf("OpenCL device: %s (correctly rounded divide/sqrt: %s)\n", name,
         exact_rounding ? "yes: bitwise comparison" : "no: 11 ulp allowance");
  cl_int err;
  cl_context ctx = clCreateContext(NULL, 1, &dev, NULL, NULL, &err);
  CHECK(err == CL_SUCCESS, "clCreateContext: %d", err);
  cl_command_queue q = clCreateCommandQueue(ctx, dev, 0, &err);
  CHECK(err == CL_SUCCESS, "clCreateCommandQueue: %d", err);
  for (int i = 1; i < argc && err == CL_SUCCESS; i++) run_one(ctx, dev, q, exact_rounding, argv[i]);
  clReleaseCommandQueue(q);
  clReleaseContext(ctx);
  return test_summary("test_lut_opencl");
}
