/* module_host.h — the renderer functions a module calls (module.h), one list: the core fills a
 * table of them (module.c) and hands it to a module when it loads; each module compiles
 * module_client.c, which defines these functions as calls through that table, so a module's code
 * calls them by their usual names and links none of the renderer. Adding a function a module
 * needs: one line here (and ICS_MODULE_ABI raised). */
#ifndef ICS_RENDER_MODULE_HOST_H
#define ICS_RENDER_MODULE_HOST_H

#include "backend.h"
#include "device_scene.h"
#include "icshadow/input_file.h"
#include "mesh.h"
#include "path_inside.h"
#include "plan_internal.h"
#include "slab_taps.h"

/* X(return type, name, (parameters), (arguments)); V for functions that return nothing */
#define ICS_MODULE_HOST_FUNCS(X, V)                                                             \
  X(const ics_backend *, ics_backend_find, (const char *name), (name))                          \
  X(const char *, ics_backend_option_value,                                                     \
    (const ics_backend *b, const ics_render_opts *opts, const char *name, const char **from),   \
    (b, opts, name, from))                                                                      \
  V(ics_device_camera, (const ics_plan *p, double cam[ICS_DEV_CAM]), (p, cam))                  \
  X(ics_status, ics_device_geometry_create, (ics_device_geometry * g, const ics_plan *p), (g, p)) \
  V(ics_device_geometry_destroy, (ics_device_geometry * g), (g))                                \
  X(ics_status, ics_device_scene_create, (ics_device_scene * d, const ics_plan *p, int fragments), \
    (d, p, fragments))                                                                          \
  V(ics_device_scene_destroy, (ics_device_scene * d), (d))                                      \
  X(double, ics_ldi_kernel_reach, (const ics_plan *p), (p))                                     \
  X(const ics_rect *, ics_active_region, (const struct ics_plan *p, int l, int k), (p, l, k))   \
  V(ics_plan_over_background, (const ics_plan *p, ics_image *img), (p, img))                    \
  X(double, ics_plan_slab_pixel, (const ics_plan *p, int k, double *mag), (p, k, mag))          \
  X(ics_status, ics_plan_slab_taps,                                                             \
    (const ics_plan *p, int l, int k, double q, double mag, double cum[2], ics_tap2d *scratch,  \
     ics_prop_taps *pt, char *msg, size_t msg_size),                                            \
    (p, l, k, q, mag, cum, scratch, pt, msg, msg_size))                                         \
  X(double, ics_plan_window_max, (const ics_plan *p), (p))                                      \
  V(ics_prop_release, (ics_prop_taps * pt), (pt))                                               \
  V(ics_mesh_bounds, (const ics_mesh *m, double lo[3], double hi[3]), (m, lo, hi))              \
  X(int, ics_mesh_hits_of,                                                                      \
    (const ics_mesh *m, const int *tris, int ntris, const double orig[3], const double dir[3],  \
     ics_hits *h, int *behind),                                                                 \
    (m, tris, ntris, orig, dir, h, behind))                                                     \
  V(ics_mesh_triangle, (const ics_mesh *m, int k, double v[3][3]), (m, k, v))                   \
  X(int, ics_mesh_triangle_count, (const ics_mesh *m), (m))                                     \
  X(ics_status, ics_path_check_inside, (const char *path, const char *root, char *why,          \
                                        size_t why_size),                                       \
    (path, root, why, why_size))                                                                \
  X(FILE *, ics_input_open,                                                                     \
    (const char *path, uint64_t max_bytes, unsigned flags, ics_status *status, char *why,       \
     size_t why_size),                                                                          \
    (path, max_bytes, flags, status, why, why_size))

#define ICS_MODULE_HOST_FIELD_(ret, name, params, args) ret(*name) params;
#define ICS_MODULE_HOST_VFIELD_(name, params, args) void(*name) params;
struct ics_module_host {
  ICS_MODULE_HOST_FUNCS(ICS_MODULE_HOST_FIELD_, ICS_MODULE_HOST_VFIELD_)
};
#undef ICS_MODULE_HOST_FIELD_
#undef ICS_MODULE_HOST_VFIELD_

/* the core's table (module.c) */
extern const struct ics_module_host ics_module_host_table;

#endif
