/* clamp.h — v clamped to [lo, hi] for doubles and longs (private to libicshadow); a NaN double
 * stays NaN. Shared by the SAT lookups (sat.c) and the SSAT's angular boxes (ssat.c,
 * ssat_frame.c). */
#ifndef ICS_CLAMP_H
#define ICS_CLAMP_H

static inline double ics_clampd(double v, double lo, double hi) {
  return v < lo ? lo : v > hi ? hi : v;
}

static inline long ics_clampl(long v, long lo, long hi) { return v < lo ? lo : v > hi ? hi : v; }

#endif
