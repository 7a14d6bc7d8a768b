/* icshadow/deprecated.h — the old names of renamed public functions and types, kept as
 * deprecated aliases for one minor version: added in 0.2.0, removed in 0.3.0 (CHANGELOG.md
 * lists every rename). Each function alias is a static inline forwarder to its new name, so
 * it returns exactly what the new name returns; GCC and Clang warn at each use
 * (-Wdeprecated-declarations) with the name to use instead. icshadow.h includes this header
 * last. */
#ifndef ICSHADOW_DEPRECATED_H
#define ICSHADOW_DEPRECATED_H

#include <stddef.h>
#include <stdint.h>

#include "icshadow/class.h"
#include "icshadow/clt1d.h"
#include "icshadow/clt2d.h"
#include "icshadow/conv.h"
#include "icshadow/csat.h"
#include "icshadow/ellint.h"
#include "icshadow/epipolar.h"
#include "icshadow/heightfield.h"
#include "icshadow/iter1d.h"
#include "icshadow/light.h"
#include "icshadow/lightfit.h"
#include "icshadow/lut.h"
#include "icshadow/normal.h"
#include "icshadow/occtex.h"
#include "icshadow/rng.h"
#include "icshadow/sat.h"
#include "icshadow/ssat.h"
#include "icshadow/status.h"
#include "icshadow/taps.h"
#include "icshadow/volume.h"

#if defined(__GNUC__) || defined(__clang__)
#define ICS_DEPRECATED(msg) __attribute__((deprecated(msg)))
#else
#define ICS_DEPRECATED(msg)
#endif

/* ---- 0.2.0: the normal distribution moved to normal.h (from light.h and clt2d.h) ---- */
ICS_DEPRECATED("since 0.2.0: use ics_normal_cdf")
static inline double ics_light_phi(double z) { return ics_normal_cdf(z); }

ICS_DEPRECATED("since 0.2.0: use ics_normal_sf")
static inline double ics_light_phic(double z) { return ics_normal_sf(z); }

ICS_DEPRECATED("since 0.2.0: use ics_normal_quantile")
static inline double ics_light_phiinv(double p) { return ics_normal_quantile(p); }

ICS_DEPRECATED("since 0.2.0: use ics_normal_bvn_cdf")
static inline double ics_bvn_cdf(double a, double b, double r) {
  return ics_normal_bvn_cdf(a, b, r);
}

/* ---- 0.2.0: the brute-force ray marchers moved to volume.h (from sat.h) ---- */
ICS_DEPRECATED("since 0.2.0: use ics_volume_tau_directional")
static inline ics_status ics_tau_bruteforce_directional(const ics_volume *vol,
                                                        const double r_u[3], const double r_v[3],
                                                        const double dir[3], const double p[3],
                                                        double half_width, int n_patch,
                                                        double step, double *tau) {
  return ics_volume_tau_directional(vol, r_u, r_v, dir, p, half_width, n_patch, step, tau);
}

ICS_DEPRECATED("since 0.2.0: use ics_volume_tau_point")
static inline ics_status ics_tau_bruteforce_point(const ics_volume *vol,
                                                  const double light_pos[3], const double p[3],
                                                  double half_width, int n_patch, double step,
                                                  double *tau) {
  return ics_volume_tau_point(vol, light_pos, p, half_width, n_patch, step, tau);
}

/* ---- 0.2.0: objects are made by ics_X_create and freed by ics_X_destroy ---- */
ICS_DEPRECATED("since 0.2.0: use ics_sat2d_create")
static inline ics_status ics_sat2d_build(ics_sat2d **out, const float *data, size_t width,
                                         size_t height, size_t stride, ics_sat_precision mode) {
  return ics_sat2d_create(out, data, width, height, stride, mode);
}

ICS_DEPRECATED("since 0.2.0: use ics_sat2d_destroy")
static inline void ics_sat2d_free(ics_sat2d *sat) { ics_sat2d_destroy(sat); }

ICS_DEPRECATED("since 0.2.0: use ics_sat3d_create")
static inline ics_status ics_sat3d_build(ics_sat3d **out, const float *data, size_t width,
                                         size_t height, size_t depth, ics_sat_precision mode) {
  return ics_sat3d_create(out, data, width, height, depth, mode);
}

ICS_DEPRECATED("since 0.2.0: use ics_sat3d_destroy")
static inline void ics_sat3d_free(ics_sat3d *sat) { ics_sat3d_destroy(sat); }

ICS_DEPRECATED("since 0.2.0: use ics_csat_create")
static inline ics_status ics_csat_build(ics_csat **out, const ics_volume *vol,
                                        const double light_dir[3], double h,
                                        ics_sat_precision mode) {
  return ics_csat_create(out, vol, light_dir, h, mode);
}

ICS_DEPRECATED("since 0.2.0: use ics_csat_create_frame")
static inline ics_status ics_csat_build_frame(ics_csat **out, const ics_volume *vol,
                                              const double r_u[3], const double r_v[3], double h,
                                              ics_sat_precision mode) {
  return ics_csat_create_frame(out, vol, r_u, r_v, h, mode);
}

ICS_DEPRECATED("since 0.2.0: use ics_csat_destroy")
static inline void ics_csat_free(ics_csat *csat) { ics_csat_destroy(csat); }

ICS_DEPRECATED("since 0.2.0: use ics_ssat_create")
static inline ics_status ics_ssat_build(ics_ssat **out, const ics_volume *vol,
                                        const double light_pos[3], size_t n_phi, size_t n_theta,
                                        size_t n_r, ics_sat_precision mode) {
  return ics_ssat_create(out, vol, light_pos, n_phi, n_theta, n_r, mode);
}

ICS_DEPRECATED("since 0.2.0: use ics_ssat_destroy")
static inline void ics_ssat_free(ics_ssat *ssat) { ics_ssat_destroy(ssat); }

/* (ics_occtex_create keeps its name but takes the out-pointer first: no alias can keep the old
 * argument order, and an old call does not compile) */
ICS_DEPRECATED("since 0.2.0: use ics_occtex_destroy")
static inline void ics_occtex_free(ics_occtex *ot) { ics_occtex_destroy(ot); }

ICS_DEPRECATED("since 0.2.0: use ics_lut_grid_create (out-pointer first)")
static inline ics_status ics_lut_grid_new(int n, int per_interval, ics_lut_grid **grid) {
  return ics_lut_grid_create(grid, n, per_interval);
}

ICS_DEPRECATED("since 0.2.0: use ics_lut_grid_destroy")
static inline void ics_lut_grid_free(ics_lut_grid *grid) { ics_lut_grid_destroy(grid); }

/* ---- 0.2.0: shadow1d.h split: the 1D CLT measurement to clt1d.h (ics_clt_* -> ics_clt1d_*),
 * the iterated shadow to iter1d.h, the work model to conv.h (ICS_WORK_* -> ICS_CONV_WORK_*) ---- */
typedef ics_clt1d_gen ics_clt_gen;     /* deprecated since 0.2.0: use ics_clt1d_gen */
typedef ics_clt1d_fixed ics_clt_fixed; /* deprecated since 0.2.0: use ics_clt1d_fixed */
#define ICS_CLT_SKEW_TAPS ICS_CLT1D_SKEW_TAPS           /* deprecated since 0.2.0 */
#define ICS_WORK_COMP_PASSES ICS_CONV_WORK_COMP_PASSES  /* deprecated since 0.2.0 */
#define ICS_WORK_BUDGET ICS_CONV_WORK_BUDGET            /* deprecated since 0.2.0 */

ICS_DEPRECATED("since 0.2.0: use ics_clt1d_member_gen")
static inline ics_status ics_clt_member_gen(void *ctx, uint64_t step, double scale,
                                            ics_tap1d *taps, int cap, int *ntaps) {
  return ics_clt1d_member_gen(ctx, step, scale, taps, cap, ntaps);
}

ICS_DEPRECATED("since 0.2.0: use ics_clt1d_skew_taps")
static inline ics_status ics_clt_skew_taps(double mean, double var,
                                           ics_tap1d taps[ICS_CLT1D_SKEW_TAPS]) {
  return ics_clt1d_skew_taps(mean, var, taps);
}

ICS_DEPRECATED("since 0.2.0: use ics_clt1d_fixed_gen")
static inline ics_status ics_clt_fixed_gen(void *ctx, uint64_t step, double scale,
                                           ics_tap1d *taps, int cap, int *ntaps) {
  return ics_clt1d_fixed_gen(ctx, step, scale, taps, cap, ntaps);
}

ICS_DEPRECATED("since 0.2.0: use ics_clt1d_measure")
static inline ics_status ics_clt_measure(ics_clt1d_gen gen, void *ctx, double mean, double var,
                                         const int *steps, int nsteps, ics_comp_mode comp,
                                         int refine, ics_clt_point *out) {
  return ics_clt1d_measure(gen, ctx, mean, var, steps, nsteps, comp, refine, out);
}

ICS_DEPRECATED("since 0.2.0: use ics_clt1d_cost")
static inline ics_status ics_clt_cost(ics_clt1d_gen gen, void *ctx, double mean, double var,
                                      const int *steps, int nsteps, ics_comp_mode comp,
                                      int refine, double *nodes, double *work) {
  return ics_clt1d_cost(gen, ctx, mean, var, steps, nsteps, comp, refine, nodes, work);
}

ICS_DEPRECATED("since 0.2.0: use ics_iter1d_opts_init")
static inline ics_iter1d_opts ics_iter1d_opts_default(void) {
  ics_iter1d_opts o;
  ics_iter1d_opts_init(&o);
  return o;
}

ICS_DEPRECATED("since 0.2.0: use ics_iter1d_cost")
static inline ics_status ics_shadow1d_iterate_cost(const ics_light1d *l, double d, double d1,
                                                   double e, const ics_iter1d_opts *opts,
                                                   double *h, double *nodes, double *work) {
  return ics_iter1d_cost(l, d, d1, e, opts, h, nodes, work);
}

/* ---- 0.2.0: minmax.h split: epipolar rectification to epipolar.h (ics_epi_* ->
 * ics_epipolar_*), the height-field scene to heightfield.h (ics_hf_* -> ics_heightfield_*) ---- */
typedef ics_epipolar_frame ics_epi_frame; /* deprecated since 0.2.0: use ics_epipolar_frame */
typedef ics_heightfield ics_hf_scene;     /* deprecated since 0.2.0: use ics_heightfield */
#define ICS_HF_MAX_SHAPES ICS_HEIGHTFIELD_MAX_SHAPES /* deprecated since 0.2.0 */

ICS_DEPRECATED("since 0.2.0: use ics_epipolar_frame_init")
static inline ics_status ics_epi_frame_init(ics_epipolar_frame *f, const double eye[3],
                                            const double to_light[3], size_t rows, size_t d,
                                            double dgamma) {
  return ics_epipolar_frame_init(f, eye, to_light, rows, d, dgamma);
}

ICS_DEPRECATED("since 0.2.0: use ics_epipolar_locate")
static inline ics_status ics_epi_locate(const ics_epipolar_frame *f, const double p[3],
                                        double *alpha, double *gamma, double *depth) {
  return ics_epipolar_locate(f, p, alpha, gamma, depth);
}

ICS_DEPRECATED("since 0.2.0: use ics_epipolar_ray")
static inline ics_status ics_epi_ray(const ics_epipolar_frame *f, const double dir[3],
                                     double *alpha, size_t *row, ics_minmax_ray *ray) {
  return ics_epipolar_ray(f, dir, alpha, row, ray);
}

ICS_DEPRECATED("since 0.2.0: use ics_epipolar_ray_dir")
static inline ics_status ics_epi_ray_dir(const ics_epipolar_frame *f, size_t row, double beta,
                                         double dir[3]) {
  return ics_epipolar_ray_dir(f, row, beta, dir);
}

ICS_DEPRECATED("since 0.2.0: use ics_epipolar_rectify")
static inline ics_status ics_epi_rectify(const ics_epipolar_frame *f, const float *smap, size_t w,
                                         size_t h, double u0, double v0, double texel,
                                         float *out) {
  return ics_epipolar_rectify(f, smap, w, h, u0, v0, texel, out);
}

ICS_DEPRECATED("since 0.2.0: use ics_heightfield_init_default")
static inline void ics_hf_scene_default(ics_heightfield *s) { ics_heightfield_init_default(s); }

ICS_DEPRECATED("since 0.2.0: use ics_heightfield_hit")
static inline double ics_hf_scene_hit(const ics_heightfield *s, const double o[3],
                                      const double dir[3], double tmin) {
  return ics_heightfield_hit(s, o, dir, tmin);
}

ICS_DEPRECATED("since 0.2.0: use ics_heightfield_shadow_map")
static inline ics_status ics_hf_shadow_map(const ics_heightfield *s, const ics_epipolar_frame *f,
                                           size_t w, double half, float *smap) {
  return ics_heightfield_shadow_map(s, f, w, half, smap);
}

/* ---- 0.2.0: occtex.h's functions carry its name (ics_occ_* -> ics_occtex_*), and its
 * synthetic scenes are box sets ("scene" is left to the renderer) ---- */
typedef ics_occ_boxes_kind ics_occ_scene_kind; /* deprecated since 0.2.0: use ics_occ_boxes_kind */
#define ICS_OCC_SCENE_FOLIAGE ICS_OCC_BOXES_FOLIAGE /* deprecated since 0.2.0 */
#define ICS_OCC_SCENE_PLATES ICS_OCC_BOXES_PLATES   /* deprecated since 0.2.0 */
#define ICS_OCC_SCENE_BLOCKS ICS_OCC_BOXES_BLOCKS   /* deprecated since 0.2.0 */

ICS_DEPRECATED("since 0.2.0: use ics_occtex_prefilter_name")
static inline const char *ics_occ_prefilter_name(ics_occ_prefilter pf) {
  return ics_occtex_prefilter_name(pf);
}

ICS_DEPRECATED("since 0.2.0: use ics_occtex_combine_name")
static inline const char *ics_occ_combine_name(ics_occ_combine c) {
  return ics_occtex_combine_name(c);
}

ICS_DEPRECATED("since 0.2.0: use ics_occtex_boxes_make")
static inline ics_status ics_occ_scene_make(ics_occ_boxes_kind kind, int nboxes, uint64_t seed,
                                            ics_occ_box *out) {
  return ics_occtex_boxes_make(kind, nboxes, seed, out);
}

ICS_DEPRECATED("since 0.2.0: use ics_occtex_slice_boxes")
static inline ics_status ics_occ_slice(const ics_occ_box *boxes, size_t nboxes,
                                       const ics_occ_grid *grid, int slices, double z_near,
                                       double z_far, int ss, float *tex) {
  return ics_occtex_slice_boxes(boxes, nboxes, grid, slices, z_near, z_far, ss, tex);
}

ICS_DEPRECATED("since 0.2.0: use ics_occtex_combine_values")
static inline double ics_occ_combine_values(ics_occ_combine c, const double *f, int k) {
  return ics_occtex_combine_values(c, f, k);
}

ICS_DEPRECATED("since 0.2.0: use ics_occtex_exact")
static inline ics_status ics_occ_exact(const ics_occ_box *boxes, size_t nboxes,
                                       const ics_occ_light *light, int m, const double *P,
                                       size_t n, double *occ) {
  return ics_occtex_exact(boxes, nboxes, light, m, P, n, occ);
}

/* ---- 0.2.0: value structs: options zero-initialised to their defaults where zero can mean
 * the default, else filled by ics_X_init(&x); constructors ics_X_init(ics_X *out, ...) ---- */
ICS_DEPRECATED("since 0.2.0: a zero-initialised ics_conv_opts ({0}) is the defaults")
static inline ics_conv_opts ics_conv_opts_default(void) {
  ics_conv_opts o = {0};
  return o;
}

ICS_DEPRECATED("since 0.2.0: use ics_clt2d_setup_init")
static inline ics_clt2d_setup ics_clt2d_setup_default(void) {
  ics_clt2d_setup s;
  ics_clt2d_setup_init(&s);
  return s;
}

ICS_DEPRECATED("since 0.2.0: use ics_lightfit_params_init")
static inline void ics_lightfit_defaults(ics_lightfit_params *p) { ics_lightfit_params_init(p); }

ICS_DEPRECATED("since 0.2.0: use ics_rng_init")
static inline ics_rng ics_rng_make(uint64_t seed, uint64_t stream) {
  ics_rng r;
  ics_rng_init(&r, seed, stream);
  return r;
}

/* ---- 0.2.0: kernel.h split: the classes to class.h, the tap lists to taps.h (with the
 * interpolation variance of conv.h: ics_interp_var* -> ics_taps*_interp_var), the schedules to
 * schedule.h ---- */
ICS_DEPRECATED("since 0.2.0: use ics_class2d_init_axes (out-pointer first)")
static inline ics_status ics_class2d_from_axes(double mx, double my, double varx, double vary,
                                               double angle_deg, ics_class2d *out) {
  return ics_class2d_init_axes(out, mx, my, varx, vary, angle_deg);
}

ICS_DEPRECATED("since 0.2.0: use ics_taps1d_interp_var")
static inline double ics_interp_var1d(const ics_tap1d *t, int n) {
  return ics_taps1d_interp_var(t, n);
}

ICS_DEPRECATED("since 0.2.0: use ics_taps2d_interp_var")
static inline void ics_interp_var2d(const ics_tap2d *t, int n, double out[2]) {
  ics_taps2d_interp_var(t, n, out);
}

/* ---- 0.2.0: the functions of light.h, rng.h and ellint.h carry their header's name ---- */
ICS_DEPRECATED("since 0.2.0: use ics_light_tan_deg")
static inline double ics_tan_deg(double w_deg) { return ics_light_tan_deg(w_deg); }

ICS_DEPRECATED("since 0.2.0: use ics_light_tilt_condition")
static inline double ics_tilt_condition(double w_deg) { return ics_light_tilt_condition(w_deg); }

ICS_DEPRECATED("since 0.2.0: use ics_light_cov_from_eig")
static inline ics_status ics_cov_from_eig(double varx, double vary, double alpha_deg,
                                          double cov[3]) {
  return ics_light_cov_from_eig(varx, vary, alpha_deg, cov);
}

ICS_DEPRECATED("since 0.2.0: use ics_light_cov_to_eig")
static inline ics_status ics_cov_to_eig(const double cov[3], double *varx, double *vary,
                                        double *alpha_deg) {
  return ics_light_cov_to_eig(cov, varx, vary, alpha_deg);
}

ICS_DEPRECATED("since 0.2.0: use ics_light_init_tilt")
static inline ics_status ics_light_from_tilt(ics_light *out, double wx_deg, double wy_deg,
                                             double varx, double vary, double alpha_deg,
                                             const double color[3], double weight) {
  return ics_light_init_tilt(out, wx_deg, wy_deg, varx, vary, alpha_deg, color, weight);
}

ICS_DEPRECATED("since 0.2.0: use ics_light_kernel_map_1d")
static inline ics_status ics_kernel_map_1d(double mu_l, double var_l, double e, double d1,
                                           double *mu_k, double *var_k) {
  return ics_light_kernel_map_1d(mu_l, var_l, e, d1, mu_k, var_k);
}

ICS_DEPRECATED("since 0.2.0: use ics_light_kernel_map_2d")
static inline ics_status ics_kernel_map_2d(const ics_light *l, double e, double d1,
                                           double mean_k[2], double cov_k[3]) {
  return ics_light_kernel_map_2d(l, e, d1, mean_k, cov_k);
}

ICS_DEPRECATED("since 0.2.0: use ics_rng_philox4x32_10")
static inline void ics_philox4x32_10(const uint32_t ctr[4], const uint32_t key[2],
                                     uint32_t out[4]) {
  ics_rng_philox4x32_10(ctr, key, out);
}

ICS_DEPRECATED("since 0.2.0: use ics_ellint_k")
static inline double ics_ellipk(double m) { return ics_ellint_k(m); }

ICS_DEPRECATED("since 0.2.0: use ics_ellint_e")
static inline double ics_ellipe(double m) { return ics_ellint_e(m); }

ICS_DEPRECATED("since 0.2.0: use ics_ellint_k_m1")
static inline double ics_ellipk_m1(double m1) { return ics_ellint_k_m1(m1); }

ICS_DEPRECATED("since 0.2.0: use ics_ellint_e_m1")
static inline double ics_ellipe_m1(double m1) { return ics_ellint_e_m1(m1); }

ICS_DEPRECATED("since 0.2.0: use ics_ellint_ke_m1")
static inline void ics_ellipke_m1(double m1, double *K, double *E) { ics_ellint_ke_m1(m1, K, E); }

#endif
