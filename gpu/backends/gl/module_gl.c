/* module_gl.c — the gl backend as the module icshadow-gl.so (gpu/core/module.h): its entry. */
#include "backend.h"
#include "module.h"

extern const ics_backend_funcs ics_gl_funcs; /* backend_gl.c */

ICS_MODULE_DEFINE("gl", &ics_gl_funcs)
