/* check_finite.h — the status of one number given to a function that builds or checks an
 * object: ICS_ERR_NAN, ICS_ERR_INFINITE or ICS_OK (private to libicshadow; the one copy for
 * light.c and occtex.c). */
#ifndef ICS_CHECK_FINITE_H
#define ICS_CHECK_FINITE_H

#include <math.h>

#include "icshadow/status.h"

static inline ics_status ics_check_finite(double v) {
  if (isnan(v)) return ICS_ERR_NAN;
  if (isinf(v)) return ICS_ERR_INFINITE;
  return ICS_OK;
}

#endif
