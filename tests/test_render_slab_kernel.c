/* test_render_slab_kernel.c — the slab kernels' tables (gpu/core/slab_kernel.c): averaged over
 * their entries, a table has the class covariance and mean of its light (the trapezoid rule on
 * the ellipse, exact rotations for Poisson), for ellipse 2 and 3 and Poisson 8. */
#include <math.h>
#include <stdlib.h>

#include "icshadow.h"
#include "render_util.h"
#include "slab_kernel.h"
#include "testutil.h"

/* the slab kernel's table averaged over its entries has the class covariance */
static void test_table_moments(ics_render_kernel member, int samples) {
  char json[1024];
  snprintf(json, sizeof json,
           "{\"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0], \"height\": 1, \"resolution\": [100, 100]},"
           " \"render\": {\"slab_spacing\": 0.01, \"d1\": 1, \"kernel\": \"%s\", \"samples\": %d, \"compensate\": \"none\", \"pixel_rotations\": 384},"
           " \"lights\": [{\"mean\": [0.1, 0.2], \"var\": [0.3, 0.05], \"angle_deg\": 35}],"
           " \"materials\": {\"m\": {}}, \"objects\": [{\"shape\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0.3, \"material\": \"m\"}]}",
           ics_render_kernel_name(member), samples);
  ics_scene *s = scene_from_json(json);
  ics_slab_kernel sk;
  char msg[256];
  double q = 0.01;
  CHECK(ics_slab_kernel_init(&sk, s, 0, q, msg, sizeof msg) == ICS_OK && sk.mode == ICS_SLAB_TABLE,
        "kernel init: %s", msg);
  ics_tap2d *t = malloc(sizeof *t * (size_t)sk.entries * (size_t)sk.cap);
  double cum[2] = {0, 0};
  int n;
  ics_slab_kernel_taps(&sk, 0, q, cum, t, &n);
  double w, m[2], c[3];
  ics_taps2d_moments(t, n, &w, m, c);
  double tr = sk.cov_px[0] + sk.cov_px[2];
  double err = fmax(fabs(c[0] - sk.cov_px[0]), fmax(fabs(c[1] - sk.cov_px[1]), fabs(c[2] - sk.cov_px[2]))) / tr;
  double merr = fmax(fabs(m[0] - sk.mean_px[0]), fabs(m[1] - sk.mean_px[1]));
  CHECK(err < 1e-12 && merr < 1e-12, "%s %d: table covariance off by %.3g of the trace, mean by %.3g",
        ics_render_kernel_name(member), samples, err, merr);
  printf("%s %d table (%d entries): covariance off by %.2g of the trace, mean by %.2g px\n",
         ics_render_kernel_name(member), samples, sk.entries, err, merr);
  free(t);
  ics_slab_kernel_release(&sk);
  ics_scene_destroy(s);
}

int main(void) {
  test_table_moments(ICS_RK_ELLIPSE, 2);
  test_table_moments(ICS_RK_ELLIPSE, 3);
  test_table_moments(ICS_RK_POISSON, 8);
  return test_summary("test_render_slab_kernel");
}
