/* own_term.h — a surface's own light term (render.model surface; docs/renderer.md "Models"): the
 * fraction of a Gaussian light on one side of a plane, and the open surfaces the plan lets light
 * by their own term instead of their own slicing. */
#ifndef ICS_RENDER_OWN_TERM_H
#define ICS_RENDER_OWN_TERM_H

#include <stddef.h>

#include "icshadow/scene.h"

struct ics_plan;

/* A share of a light at most this large may come from behind an open surface whose occlusion the
 * plan leaves out (own_term.c): the most that leaving it out changes another point's light. */
#define ICS_OWN_TERM_BEHIND 0.01

/* The fraction of light lt (directions w = X_x r + X_y u - f on the light plane of camera c, X
 * Gaussian) with w . n > 0: Phi((a . mean + b) / sqrt(a' cov a)), a = (r . n, u . n), b = -f . n;
 * 0, 1/2 or 1 where a' cov a = 0. n need not be a unit vector. */
double ics_light_side_fraction(const ics_camera *c, const ics_light *lt, const double n[3]);

/* render.model surface: per object, the lights (bit l) for which it is an open surface lit by its
 * own term and left out of the light's buffers (own_term.c); p->own_lights, from the layered depth
 * image. Other models: none. */
ics_status ics_plan_own_surfaces(struct ics_plan *p);

/* What in the plan's scene its model renders differently from Patel's (closed opaque objects,
 * open surfaces lit by their own term, volumes under surface), or NULL: nothing, the model
 * renders it as patel does. */
const char *ics_plan_model_needs(const struct ics_plan *p);

/* "object I (lights L, ...); ..." for the objects with own lights (their scene-file indices) */
void ics_own_term_describe(const struct ics_plan *p, char *d, size_t n);

#endif
