/* module_client.c — compiled into every module (module.h), not into the renderer: the renderer
 * functions of module_host.h, defined as calls through the table the core hands over when it
 * loads the module, and the module's init that takes that table. Hidden (the modules are built
 * with -fvisibility=hidden), so a module's calls never bind to another copy. */
#include "module.h"
#include "module_host.h"

static const ics_module_host *host;

void ics_module_client_init(const ics_module_host *h) { host = h; }

#define ICS_MODULE_CLIENT_FN_(ret, name, params, args) \
  ret name params { return host->name args; }
#define ICS_MODULE_CLIENT_VFN_(name, params, args) \
  void name params { host->name args; }
ICS_MODULE_HOST_FUNCS(ICS_MODULE_CLIENT_FN_, ICS_MODULE_CLIENT_VFN_)
