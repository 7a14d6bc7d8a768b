/* clock.h — the renderer's one clock: monotonic seconds, for the per-pass times of plans and
 * backends (ics_render_stats) and the Monte-Carlo reference's time stop. */
#ifndef ICS_RENDER_CLOCK_H
#define ICS_RENDER_CLOCK_H

#include <time.h>

static inline double ics_clock_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
