/* sat_limits.h — the size limits of a summed-area table (icshadow/sat.h LIMITS), checked by
 * sat.c before it allocates a table and by ssat.c before it resamples a volume onto its grid
 * (private to libicshadow; defined in sat.c). */
#ifndef ICS_SAT_LIMITS_H
#define ICS_SAT_LIMITS_H

#include <stddef.h>

#include "icshadow/sat.h"

/* ICS_ERR_INVALID_ARG for an unknown mode; ICS_ERR_SIZE when a dimension is 0 or above 2^31,
 * the cell count above 2^31 or the table above ICS_SAT_MAX_BYTES; ICS_OK otherwise. */
ics_status ics_sat_check_size(size_t w, size_t h, size_t d, ics_sat_precision mode);

#endif
