/* test_deprecated.c — the deprecated aliases of icshadow/deprecated.h: each old name returns
 * exactly (bit for bit, NaN for NaN, the same status) what its new name returns, on inputs
 * that cover the ordinary range, the tails, the edges of the domain and invalid arguments.
 * Built with -Wno-deprecated-declarations: calling the old names is the point. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "icshadow.h"
#include "testutil.h"

/* the same double: identical bits, or both NaN */
static int same(double a, double b) {
  if (isnan(a) && isnan(b)) return 1;
  uint64_t ua, ub;
  memcpy(&ua, &a, sizeof ua);
  memcpy(&ub, &b, sizeof ub);
  return ua == ub;
}

static void test_normal(void) {
  const double zs[] = {0.0, -0.0, 0.5, -1.25, 3.0, -8.0, 37.0, -38.5, 1e-300, -1e300,
                       INFINITY, -INFINITY, NAN};
  for (size_t i = 0; i < sizeof zs / sizeof zs[0]; i++) {
    double z = zs[i];
    CHECK(same(ics_light_phi(z), ics_normal_cdf(z)), "ics_light_phi(%a)", z);
    CHECK(same(ics_light_phic(z), ics_normal_sf(z)), "ics_light_phic(%a)", z);
  }
  const double ps[] = {0.0, 0x1p-1074, 1e-300, 1e-10, 0.025, 0.5, 0.975, 1.0 - 0x1p-53, 1.0,
                       -0.1, 1.5, NAN};
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++)
    CHECK(same(ics_light_phiinv(ps[i]), ics_normal_quantile(ps[i])), "ics_light_phiinv(%a)",
          ps[i]);
  const double abr[][3] = {{0, 0, 0},      {0.3, -0.7, 0.5},  {1.5, 2, -0.95}, {-2, 1, 0.99},
                           {1, 1, 1},      {-1, 0.5, -1},     {INFINITY, 0.2, 0.3},
                           {0.2, -INFINITY, 0.3}, {0, 0, 1.5}, {NAN, 0, 0}};
  for (size_t i = 0; i < sizeof abr / sizeof abr[0]; i++) {
    double a = abr[i][0], b = abr[i][1], r = abr[i][2];
    CHECK(same(ics_bvn_cdf(a, b, r), ics_normal_bvn_cdf(a, b, r)), "ics_bvn_cdf(%g, %g, %g)", a,
          b, r);
  }
}

static void test_volume(void) {
  enum { N = 8 };
  static float data[N * N * N];
  for (int k = 0; k < N; k++)
    for (int j = 0; j < N; j++)
      for (int i = 0; i < N; i++)
        data[(k * N + j) * N + i] = 0.05f + 0.01f * (float)((i * 7 + j * 3 + k * 5) % 11);
  ics_volume vol = {data, N, N, N};
  const double ru[3] = {1, 0, 0}, rv[3] = {0, 1, 0}, dir[3] = {0, 0, 1};
  const double pts[][3] = {{4, 4, 2}, {1.5, 6.25, 0.5}, {-1, 4, 4}, {4, 4, 20}};
  const double Us[] = {0.0, 0.5, 2.0, -1.0};
  for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
    for (size_t u = 0; u < sizeof Us / sizeof Us[0]; u++) {
      double t_old = -1, t_new = -1;
      ics_status s_old = ics_tau_bruteforce_directional(&vol, ru, rv, dir, pts[i], Us[u], 3,
                                                        0.25, &t_old);
      ics_status s_new = ics_volume_tau_directional(&vol, ru, rv, dir, pts[i], Us[u], 3, 0.25,
                                                    &t_new);
      CHECK(s_old == s_new && same(t_old, t_new), "directional p %zu U %g: %d %.17g vs %d %.17g",
            i, Us[u], s_old, t_old, s_new, t_new);
    }
  const double lights[][3] = {{-6, 4, 4}, {4, 4, 4}, {4, 4, 30}};
  for (size_t l = 0; l < sizeof lights / sizeof lights[0]; l++)
    for (size_t i = 0; i < sizeof pts / sizeof pts[0]; i++)
      for (size_t u = 0; u < sizeof Us / sizeof Us[0]; u++) {
        double t_old = -1, t_new = -1;
        ics_status s_old = ics_tau_bruteforce_point(&vol, lights[l], pts[i], Us[u], 3, 0.25,
                                                    &t_old);
        ics_status s_new = ics_volume_tau_point(&vol, lights[l], pts[i], Us[u], 3, 0.25, &t_new);
        CHECK(s_old == s_new && same(t_old, t_new),
              "point light %zu p %zu U %g: %d %.17g vs %d %.17g", l, i, Us[u], s_old, t_old,
              s_new, t_new);
      }
  double t = 0;
  CHECK(ics_tau_bruteforce_directional(NULL, ru, rv, dir, pts[0], 1, 3, 0.25, &t) ==
            ics_volume_tau_directional(NULL, ru, rv, dir, pts[0], 1, 3, 0.25, &t),
        "directional, no volume");
  CHECK(ics_tau_bruteforce_point(&vol, lights[0], lights[0], 1, 3, 0.25, &t) ==
            ics_volume_tau_point(&vol, lights[0], lights[0], 1, 3, 0.25, &t),
        "point, p at the light");
}

int main(void) {
  test_normal();
  test_volume();
  return test_summary("test_deprecated");
}
