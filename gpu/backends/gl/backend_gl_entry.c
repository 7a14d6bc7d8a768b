/* backend_gl_entry.c — the gl backend's entry in the table (compiled into the renderer): what the
 * core knows of it without loading its module (name, description, AOVs, models, options); its
 * functions are the module icshadow-gl.so (backend_gl.c and the rest of this folder, with EGL,
 * OSMesa and what they load), loaded on first use (gpu/core/module.h). */
#include "backend.h"

static const ics_backend_option gl_options[] = {
    {"context", "ICS_GL_CONTEXT", "auto|egl|osmesa",
     "the context: auto (egl, then osmesa), egl (a GPU's driver, else Mesa's surfaceless "
     "llvmpipe) or osmesa"},
    {"ldi", "ICS_GL_LDI", "plan|device",
     "the layered depth image: plan (the plan's, uploaded) or device (built on the device)"},
    {NULL, NULL, NULL, NULL}};

ICS_MODULE_BACKEND(gl, "the slab renderer as OpenGL 4.5 compute shaders (EGL or OSMesa; auto picks it on a GPU)",
                   ICS_AOV_VISIBILITY | ICS_AOV_DEPTH, 1u << ICS_MODEL_PATEL, ICS_MODEL_PATEL, gl_options, 1)
