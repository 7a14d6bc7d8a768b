/* test_lut_cheader.c — the self-contained C header written by `icshadow lut --size 64 --lang c`
 * (generated at build time into the build folder) compiles, and its ics_tab_* functions return
 * exactly what the library's evaluators return on the same tables (same operations in double),
 * including special values and NaN outside the domain; and its ics_tab_ellipse_tap places the
 * kernel's taps where ics_ellipse_kernel does (tap_cases.h), to within what the tables' radii
 * error moves them: at most 2 ICS_TAB_RADII_MAX_REL_ERR of the larger radius (the radii and the
 * axis ratio that places the arc each carry that error once). */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "icshadow.h"
#include "icshadow_lut_c64.h"
#include "tap_cases.h"
#include "testutil.h"

static int same(double x, double y) { return x == y || (isnan(x) && isnan(y)); }

int main(void) {
  CHECK(ICS_TAB_N == 64, "ICS_TAB_N = %d", ICS_TAB_N);
  double s[64], g[64];
  CHECK(ics_lut_build(64, s, g) == ICS_OK, "ics_lut_build(64)");
  int diff = 0;
  for (int i = 0; i < 64; i++) diff += s[i] != ics_tab_s[i] || g[i] != ics_tab_g[i];
  CHECK(diff == 0, "%d table entries differ from ics_lut_build(64)", diff);
  ics_lut_tables L = {64, s, g};
  const double rats[] = {0, 1e-300, 1e-12, 0.01, 0.5, 1, 2, 1e6, 1e300, INFINITY, -1, NAN};
  for (unsigned k = 0; k < sizeof rats / sizeof rats[0]; k++) {
    double a, b, ea, eb;
    ics_tab_ratio_to_ab(rats[k], &a, &b);
    ics_lut_tables_ratio_to_ab(&L, rats[k], &ea, &eb);
    CHECK(same(a, ea) && same(b, eb), "ratio_to_ab(%g): (%.17g, %.17g) vs (%.17g, %.17g)", rats[k],
          a, b, ea, eb);
    CHECK(same(ics_tab_ratio_to_t(rats[k]), eb), "ratio_to_t(%g)", rats[k]);
    ics_tab_ellipse_radii(1.0, rats[k], &a, &b);
    ics_lut_tables_ellipse_radii(&L, 1.0, rats[k], &ea, &eb);
    CHECK(same(a, ea) && same(b, eb), "ellipse_radii(1, %g): (%.17g, %.17g) vs (%.17g, %.17g)",
          rats[k], a, b, ea, eb);
  }
  for (int k = -2; k <= 1002; k++) {
    double t = k / 1000.0;
    CHECK(same(ics_tab_vx(t), ics_lut_tables_vx(&L, t)), "vx(%g): %.17g vs %.17g", t,
          ics_tab_vx(t), ics_lut_tables_vx(&L, t));
    CHECK(same(ics_tab_vx_ab(1 - t, t), ics_lut_tables_vx_ab(&L, 1 - t, t)), "vx_ab at %g", t);
  }
  static tap_case tc[TAP_CASES_MAX];
  int nc = tap_cases(tc), wi = 0;
  double worst = 0;
  for (int i = 0; i < nc; i++) {
    double x, y;
    ics_tab_ellipse_tap(tc[i].varx, tc[i].vary, tc[i].angle, tc[i].n, tc[i].k, tc[i].u, &x, &y);
    double e = tap_error(&tc[i], x, y);
    if (!(e <= worst)) worst = e, wi = i;
  }
  printf("ellipse_tap: %d taps, worst %.3g of the larger radius (bound 2 x %.3g) at varx %g, "
         "vary %g, angle %g, n %d, k %d, u %g\n", nc, worst, ICS_TAB_RADII_MAX_REL_ERR,
         tc[wi].varx, tc[wi].vary, tc[wi].angle, tc[wi].n, tc[wi].k, tc[wi].u);
  CHECK(nc > 2000, "only %d tap cases", nc);
  CHECK(worst <= 2 * ICS_TAB_RADII_MAX_REL_ERR, "ellipse_tap off by %.3g of the radius", worst);
  double x, y;
  ics_tab_ellipse_tap(-1, 1, 0, 2, 0, 0, &x, &y);
  CHECK(isnan(x) && isnan(y), "negative variance: (%g, %g), not NaN", x, y);
  ics_tab_ellipse_tap(1, 1, 0, 0, 0, 0, &x, &y);
  CHECK(isnan(x) && isnan(y), "n = 0: (%g, %g), not NaN", x, y);
  ics_tab_ellipse_tap(0, 0, 30, 2, 1, 0.4, &x, &y);
  CHECK(x == 0 && y == 0, "point light: (%g, %g)", x, y);
  return test_summary("test_lut_cheader");
}
