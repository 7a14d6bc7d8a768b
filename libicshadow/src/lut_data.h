/* lut_data.h — the lookup tables libicshadow itself uses (private; see icshadow/lut.h).
 * lut_data.c is generated — do not edit it: `icshadow lut --size N --lang c-data`, run by
 * scripts/gen_luts.sh, writes it from the exact functions of ellipse.c (never from these tables,
 * so the generator always builds). This header is size-independent: regenerating at another
 * size needs no edit here. */
#ifndef ICS_LUT_DATA_H
#define ICS_LUT_DATA_H

#include "icshadow/lut.h"

/* One table of n entries, linear interpolation between uniform nodes of its tabulation
 * variable (see lut.c and icshadow/lut.h for the variables). */
typedef struct ics_lut_data_table {
  int n;              /* entries */
  double max_rel_err; /* stamped: measured max relative error (double evaluation) */
  long grid_points;   /* stamped: points of the measurement grid (both tables) */
  const double *y;
} ics_lut_data_table;

/* ratioToab: s(w) = t / w at w_i = i / (2 (n - 1)), w = sqrt(rat) / (1 + sqrt(rat)). */
extern const ics_lut_data_table ics_lut_data_ratio;
/* abToVarx: g(t) = V_x(t) / (1 - t)^2 in [1/3, 1/2] for t in [0, 1/2], nodes uniform in
 * u = sqrt(t (t + 1/5)); g(t) = 1 - g(1 - t) covers t > 1/2. */
extern const ics_lut_data_table ics_lut_data_vx;
/* Both tables as the evaluators take them (same n: one command writes both). */
extern const ics_lut_tables ics_lut_data_tables;
/* stamped: max relative error of ics_lut_ellipse_radii on the ratio grid. */
extern const double ics_lut_data_radii_max_rel_err;
/* stamped: the command that generated lut_data.c. */
extern const char ics_lut_data_command[];

#endif
