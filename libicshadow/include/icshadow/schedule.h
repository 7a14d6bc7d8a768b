/* icshadow/schedule.h — per-iteration choice of kernel members (Lyapunov mixing, Patel et al.
 * 2013, Sec. 3.3): the taps of step i come from members[i % nmembers] (kernel.h) with iteration
 * index i; the engine's runs (conv.h) take a schedule. */
#ifndef ICSHADOW_SCHEDULE_H
#define ICSHADOW_SCHEDULE_H

#include <stdint.h>

#include "icshadow/kernel.h"
#include "icshadow/status.h"
#include "icshadow/taps.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Per-iteration member choice (Lyapunov mixing): step i uses members[i % nmembers] with
 * iteration index i. All members should share one class (not enforced: a schedule of different
 * classes is legal and its moments still add). */
typedef struct ics_schedule1d {
  const ics_kernel1d *members;
  int nmembers;
} ics_schedule1d;

typedef struct ics_schedule2d {
  const ics_kernel2d *members;
  int nmembers;
} ics_schedule2d;

ICS_API ics_status ics_schedule1d_taps(const ics_schedule1d *s, uint64_t step, ics_tap1d *taps,
                                       int cap, int *ntaps);
ICS_API ics_status ics_schedule2d_taps(const ics_schedule2d *s, uint64_t step, ics_tap2d *taps,
                                       int cap, int *ntaps);
ICS_API int ics_schedule1d_max_taps(const ics_schedule1d *s); /* 0 when invalid */
ICS_API int ics_schedule2d_max_taps(const ics_schedule2d *s);

#ifdef __cplusplus
}
#endif
#endif
