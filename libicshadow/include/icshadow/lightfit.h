/* icshadow/lightfit.h — environment maps to a few Gaussian lights on the virtual light plane
 * (Patel et al. 2013, Sec. 3.2 last paragraphs: "project [the environment map] onto the
 * virtual light plane to define l(x), and perform Gaussian fitting on l(x)").
 *
 * Frames, the plane density l(x, y) = L(w) dw/dA of a map and the kept-pixel rule of the
 * cut-off are envmap.h's (docs/architecture.md "Frames and file formats"). Radiance is reduced
 * to luminance Y = 0.2126 R + 0.7152 G + 0.0722 B for the fit; colours are fitted afterwards.
 * Cut-off: only the kept pixels (ics_envmap_pixel_kept with max_angle_deg) are fitted; the
 * energy of the others is left out and reported (ics_lightfit_report.cutoff_loss), and dz <= 0
 * at the centre (in front of the viewer) separately.
 *
 * Light convention (docs/lights_format.md): weight = luminance power of the light, the
 * integral of its Y over the plane (= over the hemisphere, in map units x steradian); color =
 * its RGB power / weight (so Y(color) = 1). Light k contributes
 * weight_k color_k g(x; mean_k, cov_k) to l(x); sum_k weight_k = the fitted energy.
 *
 * Fit: each map pixel is a weighted sample (plane point of its centre, mass Y dw, and the
 * covariance S of its footprint on the plane, J diag(dphi^2, dtheta^2)/12 J^T). Model: a
 * pixel's value is the radiance averaged over the pixel, so the centre moments of a light are
 * Sigma + S (Sheppard) and the fit returns Sigma = centre covariance - footprint, floored at
 * the footprint (a light narrower than a pixel is represented by its pixel's box covariance; a
 * one-pixel sun gets ~S, never a singular covariance). A point-sampled map comes out narrower
 * by S. Greedy initialisation (after Annen et al. 2008): K times, take the maximum of the
 * residual density l - current mixture, flood-fill the 4-connected pixels above half that
 * maximum, and start a Gaussian with their moments scaled to a full Gaussian
 * (x 1/(1 - ln 2) ... see lightfit.c) and twice their residual mass. A map with a sky (a
 * floor of radiance under the lights holding at least 0.1 % of the kept energy) also gets two
 * starts that give the floor one or two components and greedy on the map less the floor the
 * rest; EM runs from each and the fit with the lowest L1 is kept (lightfit.c step 2b).
 * Refinement: EM on the weighted samples (E-step with each component's centre covariance
 * Sigma + F). When a map has more kept pixels than max_samples, EM runs on max_samples
 * pixels drawn by systematic resampling of the mass with a start drawn from `seed`
 * (icshadow/rng.h); otherwise the fit is deterministic and the seed is unused.
 *
 * Errors (ics_lightfit_report): relative L1 and L2 of fitted against map density over the kept
 * disc; and the edge-shadow error at the optimal distance d1: at d1 the iterative shadow of a
 * Gaussian light is its correct shadow (Eq. 7/8), so the shadow error behind a straight edge
 * is only the fit's, sup_t |L_map(t) - L_fit(t)| for the cdf L of the light's marginal across
 * the edge (both normalised to 1) — independent of d1 (the shadow is L(x/d1)). Reported as the
 * maximum over edge orientations 0, 45, 90, 135 degrees.
 *
 * Type: the lights are light.h's ics_light (mean, cov = cxx, cxy, cyy, color, weight), the one
 * Gaussian light type of the library. */
#ifndef ICSHADOW_LIGHTFIT_H
#define ICSHADOW_LIGHTFIT_H

#include <stdint.h>

#include "icshadow/image.h"
#include "icshadow/light.h"
#include "icshadow/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ICS_LIGHTFIT_MAX_K 32

/* How many lights (`fit-light --lights auto`, docs/lightfit.md "How many lights"): of the fits
 * K = 1 .. KMAX (default ICS_LIGHTFIT_AUTO_KMAX), the fewest lights whose L1 is at most
 * max(ICS_LIGHTFIT_AUTO_L1_FLOOR, ICS_LIGHTFIT_AUTO_L1_RATIO x the best L1): measured on maps of
 * known lights with and without a sky. */
#define ICS_LIGHTFIT_AUTO_KMAX 8
#define ICS_LIGHTFIT_AUTO_L1_FLOOR 0.01
#define ICS_LIGHTFIT_AUTO_L1_RATIO 2.0

typedef struct ics_lightfit_params {
  int k;                /* number of Gaussians, 1..ICS_LIGHTFIT_MAX_K (default 3) */
  double max_angle_deg; /* cut-off angle from +z, (0, 90) (default 80) */
  uint64_t seed;        /* resampling seed (default 1) */
  int max_samples;      /* EM samples; 0 = every kept pixel (default 0) */
  int max_iter;         /* EM iterations (default 300) */
  double tol;           /* stop when the log-likelihood per unit mass changes less (1e-9) */
  /* optional: called after each EM iteration (iter from 1, again for each start) */
  void (*progress)(void *ctx, int iter, int max_iter, double loglik);
  void *progress_ctx;
} ics_lightfit_params;

typedef struct ics_lightfit_report {
  int k_fit;            /* lights produced (< k when the map is explained with fewer) */
  int iterations;       /* EM iterations run from the start kept */
  int samples;          /* weighted samples EM used */
  int pixels;           /* kept pixels (behind the viewer, inside the cut-off) */
  double energy_total;  /* luminance power of the whole map */
  double energy_front;  /* dz <= 0: not representable on the plane */
  double energy_cutoff; /* behind the viewer but beyond max_angle_deg: lost */
  double energy_kept;   /* fitted */
  double cutoff_loss;   /* energy_cutoff / (energy_cutoff + energy_kept) */
  double loglik;        /* per unit mass */
  double l1, l2, edge;  /* errors, see above */
  int converged;        /* 1: EM stopped at |dLL| <= tol; 0: it ran out of max_iter */
} ics_lightfit_report;

/* Fills *out with the defaults given above. A zeroed struct is not the defaults: seed 0,
 * max_iter 0 and tol 0 are settings of their own. */
ICS_API void ics_lightfit_params_init(ics_lightfit_params *out);

/* Fits p->k Gaussians to env (3 or 4 channels; alpha ignored). lights must hold p->k entries;
 * entries past report->k_fit are zeroed. ICS_ERR_INVALID_ARG for bad parameters, a NaN / inf /
 * negative pixel, or a map without light inside the cut-off; ICS_ERR_SIZE for maps smaller than
 * 4 x 2; ICS_ERR_NOMEM. */
ICS_API ics_status ics_lightfit(const ics_image *env, const ics_lightfit_params *p,
                                ics_light *lights, ics_lightfit_report *report);

/* The K the auto rule (above) keeps among kmax fits, reports[k - 1] the fit of k lights; 0 when
 * kmax < 1 or reports is NULL. */
ICS_API int ics_lightfit_auto_choice(const ics_lightfit_report *reports, int kmax);

/* The error fields (l1, l2, edge) and energies of any set of n lights against env, with the
 * cut-off max_angle_deg (k_fit = n, iterations = samples = 0). */
ICS_API ics_status ics_lightfit_errors(const ics_image *env, double max_angle_deg,
                                       const ics_light *lights, int n, ics_lightfit_report *report);

#ifdef __cplusplus
}
#endif
#endif
