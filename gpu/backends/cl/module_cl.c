/* module_cl.c — the cl backend as the module icshadow-cl.so (gpu/core/module.h): its entry. */
#include "backend.h"
#include "module.h"

extern const ics_backend_funcs ics_cl_funcs; /* backend_cl.c */

ICS_MODULE_DEFINE("cl", &ics_cl_funcs)
