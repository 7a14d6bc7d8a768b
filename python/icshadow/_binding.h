/* _binding.h — what the icshadow Python package calls (cffi cdef, parsed by pycparser: no
 * includes; a macro only as "#define NAME ...", its value taken from the header). The library's own declarations, copied from its headers; structs end in
 * "...;" so that the compiler, not this file, fixes their layout (cffi API mode). Below: the
 * package's own helpers (_binding.c). */
typedef enum { ICS_OK, ICS_ERR_NOMEM, ... } ics_status;
const char *ics_status_str(ics_status status);

/* numerics (icshadow/ellint.h, ellipse.h) */
double ics_ellint_k(double m);
double ics_ellint_e(double m);
double ics_ellint_k_m1(double m1);
double ics_ellint_e_m1(double m1);
double ics_ellipse_varx(double b);
double ics_ellipse_vx(double t);
double ics_ellipse_vy(double t);
double ics_ellipse_ratio(double t);
double ics_ellipse_ratio_to_t(double rat);
typedef struct {
  double a, b, angle_deg, t;
  int nsamples;
  ...;
} ics_ellipse_shape;
ics_status ics_ellipse_kernel(double varx, double vary, double angle_deg, int nsamples,
                              double offset, ics_ellipse_shape *shape, double *xy);

/* 1D lights and the isolines of the shadow behind an edge (icshadow/light.h, isoline.h) */
#define ICS_LIGHT1D_MAX_MIX ...
typedef struct ics_light1d ics_light1d;
ics_status ics_light1d_create_gauss(ics_light1d **out, double mean, double var);
ics_status ics_light1d_create_box(ics_light1d **out, double lo, double hi);
ics_status ics_light1d_create_mix(ics_light1d **out, int n, const double *w, const double *mu,
                                  const double *var);
void ics_light1d_destroy(ics_light1d *l);
double ics_isoline_correct(const ics_light1d *l, double s, double d);
double ics_isoline_clt(const ics_light1d *l, double s, double d, double d1);
typedef struct {
  ...;
} ics_iter1d_opts;
void ics_iter1d_opts_init(ics_iter1d_opts *out);
ics_status ics_isoline_iterative_bounded(const ics_light1d *l, double s, double d, double d1,
                                         double e, const ics_iter1d_opts *opts, double *x,
                                         double *disc_err, char *msg, size_t msg_size);

/* images and EXR files (icshadow/image.h, exr.h) */
typedef struct {
  int width, height, channels;
  float *data;
  ...;
} ics_image;
ics_status ics_image_create(ics_image **out, int width, int height, int channels);
void ics_image_destroy(ics_image *img);
typedef struct {
  double rmse, max_abs;
  int max_x, max_y, max_channel;
  double psnr;
  ...;
} ics_image_diff;
ics_status ics_image_diff_rgb(const ics_image *a, const ics_image *b, ics_image_diff *out);
ics_status ics_exr_read(const char *path, ics_image **out, char *msg, size_t msg_size);
typedef struct {
  int width, height, count;
  const char *const *names;
  const float *data;
  const char *info;
  ...;
} ics_exr_channels;
ics_status ics_exr_read_channels(const char *path, ics_exr_channels **out, char *msg,
                                 size_t msg_size);
void ics_exr_channels_destroy(ics_exr_channels *ch);
typedef enum { ICS_EXR_FLOAT, ... } ics_exr_type;
ics_status ics_exr_write_channels(const char *path, const ics_exr_channels *ch, ics_exr_type type,
                                  int latlong, char *msg, size_t msg_size);
ics_status ics_output_png(const ics_image *img, const char *path, char *msg, size_t msg_size);
double ics_output_srgb(double linear);

/* lights (icshadow/light.h, lightsfile.h) and light fitting (icshadow/lightfit.h) */
typedef struct {
  double mean[2], cov[3], color[3], weight;
  ...;
} ics_light;
ics_status ics_lightsfile_read(const char *path, ics_light **out, int *n, char *msg,
                               size_t msg_size);
#define ICS_LIGHTFIT_MAX_K ...
#define ICS_LIGHTFIT_AUTO_KMAX ...
typedef struct {
  int k;
  double max_angle_deg;
  uint64_t seed;
  int max_samples, max_iter;
  double tol;
  ...;
} ics_lightfit_params;
typedef struct {
  int k_fit, iterations, samples, pixels;
  double energy_total, energy_front, energy_cutoff, energy_kept, cutoff_loss, loglik, l1, l2,
      edge;
  int converged;
  ...;
} ics_lightfit_report;
void ics_lightfit_params_init(ics_lightfit_params *out);
ics_status ics_lightfit(const ics_image *env, const ics_lightfit_params *p, ics_light *lights,
                        ics_lightfit_report *report);
int ics_lightfit_auto_choice(const ics_lightfit_report *reports, int kmax);

/* LUTs (icshadow/lut.h) */
#define ICS_LUT_MIN_SIZE ...
#define ICS_LUT_MAX_SIZE ...
ics_status ics_lut_build(int n, double *s, double *g);

/* scenes, plans and renders (icshadow/scene.h, plan.h, renderer.h) */
typedef struct ics_scene ics_scene;
typedef struct ics_plan ics_plan;
typedef struct ics_renderer ics_renderer;
typedef struct {
  int allow_outside_paths;
  const char *render_json;
  ...;
} ics_scene_opts;
ics_status ics_scene_create_file_opts(ics_scene **out, const char *path,
                                      const ics_scene_opts *opts, char *msg, size_t msg_size);
ics_status ics_scene_create_json_opts(ics_scene **out, const char *json, const char *name,
                                      const char *dir, const ics_scene_opts *opts, char *msg,
                                      size_t msg_size);
const char *ics_scene_default_json(void);
void ics_scene_destroy(ics_scene *s);
typedef struct {
  int width, height, threads;
  const ics_renderer *renderer;
  ...;
} ics_plan_opts;
ics_status ics_plan_create(ics_plan **out, const ics_scene *scene, const ics_plan_opts *opts,
                           char *msg, size_t msg_size);
void ics_plan_destroy(ics_plan *p);
typedef struct {
  const char *backend;
  int threads, spp;
  double time_s, noise;
  const char *const *options;
  ...;
} ics_render_opts;
typedef struct {
  char backend[16];
  ...;
} ics_render_stats;
ics_status ics_renderer_create(ics_renderer **out, const ics_render_opts *opts, char *msg,
                               size_t msg_size);
void ics_renderer_destroy(ics_renderer *r);
const char *ics_renderer_backend(const ics_renderer *r);
ics_status ics_renderer_render_aovs(ics_renderer *r, const ics_plan *plan, unsigned aovs,
                                    ics_image **out, ics_exr_channels **aov_out,
                                    ics_render_stats *stats, char *msg, size_t msg_size);
int ics_backend_count(void);
const char *ics_backend_name(int i);
const char *ics_backend_description(int i);
int ics_backend_available(const char *name, char *why, size_t why_size);
int ics_backend_option_count(int i);
const char *ics_backend_option_name(int i, int j);
const char *ics_backend_option_help(int i, int j);
const char *ics_backend_option_values(int i, int j);
const char *ics_backend_option_env(int i, int j);

/* the package's helpers (_binding.c) */
void icspy_map(double (*f)(double), const double *x, double *y, size_t n);
char *icspy_lut_header(int n, int lang, const char *command, char *msg, size_t msg_size);
char *icspy_lights_json(const ics_light *l, int n);
char *icspy_plan_json(const ics_plan *p);
char *icspy_render_summary(const ics_plan *p, const ics_scene *s, const ics_render_stats *st,
                           double ms_plan);
void icspy_free(void *p);
