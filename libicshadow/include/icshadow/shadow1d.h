/* icshadow/shadow1d.h — shadows behind a Heaviside edge for a 1D light (Patel et al. 2013,
 * Sec. 6, Appendix A.3–A.5): the correct shadow and the CLT model. Their isolines are in
 * isoline.h, the actually iterated shadow (conv engine) in iter1d.h; the sign conventions
 * below hold for all three.
 *
 * Sign conventions (the paper's, Eq. 4 and 16, made explicit):
 * - The occluder o(x) = H(x) is opaque for x > 0 and clear for x < 0.
 * - The light l is a density on the light-plane x axis with cdf L, mean mu_l, variance var_l;
 *   light at +x on the plane (mu_l > 0) throws the shadow toward -x.
 * - The shadow value s is the BLOCKED fraction of the light (0 = fully lit, 1 = umbra):
 *     correct (Eq. 16):  s_d(x) = 1 - L(-x/d)         (the cdf of -d X_l; H(x) at d = 0)
 *     CLT     (Eq. 8):   z_d(x) = Phi((x + d mu_l) / sqrt(d d1 var_l))
 *     iterated (Eq. 5):  r_n = H * kappa^{*n}, n = d/e, kappa with mean -e mu_l and variance
 *                        d1 e var_l (Eq. 7/15).
 *   All three increase in x from 0 (lit, x -> -inf) to 1 (x -> +inf).
 * - Isolines, level s in (0, 1), distance d >= 0:
 *     correct:  x = -d L^-1(1 - s) = d C_s            (straight lines through the edge)
 *     CLT:      x = -d mu_l + Phi^-1(s) sqrt(d1 var_l) sqrt(d)   (= c sigma_l sqrt(d))
 *   At d = d1 they agree for Gaussian lights. A.5 claims the s = 1/2 isolines coincide for any
 *   light; they do when the light's median equals its mean and the kernel is symmetric.
 *
 * Math functions return NaN outside their domain (d < 0, d1 <= 0, s outside (0, 1), NaN). */
#ifndef ICSHADOW_SHADOW1D_H
#define ICSHADOW_SHADOW1D_H

#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* correct shadow s_d(x) = 1 - L(-x/d) (computed as sf(-x/d), no cancellation); d = 0: H(x)
 * with H(0) = 1/2 */
ICS_API double ics_shadow1d_correct(const ics_light1d *l, double d, double x);
/* CLT model Phi((x + d mu_l) / sqrt(d d1 var_l)); a zero variance gives the shifted edge */
ICS_API double ics_shadow1d_clt(const ics_light1d *l, double d, double d1, double x);

#ifdef __cplusplus
}
#endif
#endif
