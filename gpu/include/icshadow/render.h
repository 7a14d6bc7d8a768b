/* icshadow/render.h — the public header of libicshadow_render, the slab renderer beside the
 * core library (Patel et al. 2013, Sec. 4, on full scenes; docs/renderer.md): scenes
 * (icshadow/scene.h), render plans (icshadow/plan.h), renderers and the backend table
 * (icshadow/renderer.h), lights files (icshadow/lightsfile.h), image output (icshadow/output.h).
 * Link with -licshadow_render -licshadow. (The core's primitives on an OpenCL device,
 * icshadow/cl.h, are libicshadow_cl's: -licshadow_cl -licshadow.) */
#ifndef ICSHADOW_RENDER_H
#define ICSHADOW_RENDER_H

#include "icshadow.h"
#include "icshadow/lightsfile.h"
#include "icshadow/output.h"
#include "icshadow/plan.h"
#include "icshadow/renderer.h"
#include "icshadow/scene.h"

#endif
