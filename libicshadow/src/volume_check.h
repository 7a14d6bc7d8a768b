/* volume_check.h — whether an ics_volume view is usable: non-NULL, with data and every
 * dimension >= 1 (private to libicshadow; the one check of volume.c, csat.c and ssat.c). */
#ifndef ICS_VOLUME_CHECK_H
#define ICS_VOLUME_CHECK_H

#include "icshadow/volume.h"

static inline int ics_volume_ok(const ics_volume *v) {
  return v && v->data && v->nx && v->ny && v->nz;
}

#endif
