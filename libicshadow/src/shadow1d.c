/* shadow1d.c — the correct shadow and the CLT model behind a Heaviside edge for a 1D light
 * (Patel et al. 2013, Sec. 6, Appendix A.3). Conventions in icshadow/shadow1d.h.
 *
 * Method: the correct shadow is the light's survival function at -x/d (Eq. 16), so its
 * accuracy is that of ics_light1d_sf (~1e-15 relative for Gaussian lights and mixtures, both
 * tails). The CLT model is Phi of the standardised position. */
#include "icshadow/shadow1d.h"
#include "icshadow/normal.h"

#include <math.h>

static int bad_d(double d) { return isnan(d) || d < 0 || isinf(d); }

double ics_shadow1d_correct(const ics_light1d *l, double d, double x) {
  if (!l || bad_d(d) || isnan(x)) return NAN;
  if (d == 0) return x > 0 ? 1.0 : (x < 0 ? 0.0 : 0.5);
  return ics_light1d_sf(l, -x / d);
}

double ics_shadow1d_clt(const ics_light1d *l, double d, double d1, double x) {
  if (!l || bad_d(d) || !(d1 > 0) || isinf(d1) || isnan(x)) return NAN;
  double m = -d * ics_light1d_mean(l);
  double sd = sqrt(d * d1 * ics_light1d_var(l));
  if (sd == 0) return x > m ? 1.0 : (x < m ? 0.0 : 0.5);
  return ics_normal_cdf((x - m) / sd);
}
