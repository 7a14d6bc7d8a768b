/* backend_cl_entry.c — the cl backend's entry in the table (compiled into the renderer): what the
 * core knows of it without loading its module (name, description, AOVs, models, options); its
 * functions are the module icshadow-cl.so (backend_cl.c with libicshadow_cl's device code and
 * OpenCL), loaded on first use (gpu/core/module.h). */
#include "backend.h"

static const ics_backend_option cl_options[] = {
    {"device", "ICS_CL_DEVICE", NULL, "OpenCL device: an index or part of \"platform: device\""},
    {NULL, NULL, NULL, NULL}};

ICS_MODULE_BACKEND(cl, "the slab renderer on an OpenCL device (PoCL or any OpenCL 1.2 platform with fp64; not picked by auto)",
                   ICS_AOV_VISIBILITY | ICS_AOV_DEPTH, 1u << ICS_MODEL_PATEL, ICS_MODEL_PATEL, cl_options, 0)
