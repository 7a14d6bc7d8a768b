/* lights_json.h — one Gaussian light from a JSON object (the lights-file forms), shared by the
 * lights-file reader and the scene reader. */
#ifndef ICS_RENDER_LIGHTS_JSON_H
#define ICS_RENDER_LIGHTS_JSON_H

#include "icshadow/light.h"
#include "json_util.h"

/* `where` names the light in messages ("scene.json: lights[0]"). 0 or -1 (message written). */
int ics_light_from_json(const ics_jctx *c, const char *where, json_t *o, ics_light *out);

#endif
