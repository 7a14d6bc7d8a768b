/* taps_check.h — the validation of a 1D tap list (private to libicshadow; defined in taps.c):
 * the engine (conv.c) needs it before its integer-shift schedule, taps.c's discretisation and
 * compensation start with it. */
#ifndef ICS_TAPS_CHECK_H
#define ICS_TAPS_CHECK_H

#include "icshadow/taps.h"

/* ICS_ERR_INVALID_ARG (NULL, n <= 0), ICS_ERR_SIZE (n > 4 ICS_KERNEL_MAX_TAPS), ICS_ERR_NAN /
 * ICS_ERR_INFINITE (a bad tap), ICS_ERR_RANGE (|offset| > 2^30), else ICS_OK. */
ics_status ics_taps1d_check(const ics_tap1d *t, int n);

#endif
