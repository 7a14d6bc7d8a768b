/* schedule.c — per-iteration member choice (see icshadow/schedule.h): step i takes the taps of
 * members[i % nmembers] with iteration index i. */
#include "icshadow/schedule.h"

ics_status ics_schedule1d_taps(const ics_schedule1d *s, uint64_t step, ics_tap1d *taps, int cap,
                               int *ntaps) {
  if (!s || !s->members || s->nmembers <= 0) return ICS_ERR_INVALID_ARG;
  return ics_kernel1d_taps(&s->members[step % (uint64_t)s->nmembers], step, taps, cap, ntaps);
}

ics_status ics_schedule2d_taps(const ics_schedule2d *s, uint64_t step, ics_tap2d *taps, int cap,
                               int *ntaps) {
  if (!s || !s->members || s->nmembers <= 0) return ICS_ERR_INVALID_ARG;
  return ics_kernel2d_taps(&s->members[step % (uint64_t)s->nmembers], step, taps, cap, ntaps);
}

int ics_schedule1d_max_taps(const ics_schedule1d *s) {
  if (!s || !s->members || s->nmembers <= 0) return 0;
  int m = 0;
  for (int i = 0; i < s->nmembers; i++) {
    int t = ics_kernel1d_max_taps(&s->members[i]);
    if (t == 0) return 0;
    if (t > m) m = t;
  }
  return m;
}

int ics_schedule2d_max_taps(const ics_schedule2d *s) {
  if (!s || !s->members || s->nmembers <= 0) return 0;
  int m = 0;
  for (int i = 0; i < s->nmembers; i++) {
    int t = ics_kernel2d_max_taps(&s->members[i]);
    if (t == 0) return 0;
    if (t > m) m = t;
  }
  return m;
}
