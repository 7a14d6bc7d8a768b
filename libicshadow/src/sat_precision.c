/* sat_precision.c — the precision modes of the summed-area tables (icshadow/sat.h): names,
 * parsing, the error factor of the documented bound (derived in sat.c's header) and the bytes
 * per table cell. */
#include <math.h>
#include <string.h>

#include "icshadow/sat.h"

static const char *const mode_names[ICS_SAT_PRECISION_COUNT] = {"float", "float-offset",
                                                                "compensated", "double"};

const char *ics_sat_precision_name(ics_sat_precision mode) {
  return (unsigned)mode < ICS_SAT_PRECISION_COUNT ? mode_names[mode] : NULL;
}

ics_status ics_sat_precision_parse(const char *name, ics_sat_precision *mode) {
  if (!name || !mode) return ICS_ERR_INVALID_ARG;
  for (int i = 0; i < ICS_SAT_PRECISION_COUNT; i++)
    if (!strcmp(name, mode_names[i])) {
      *mode = (ics_sat_precision)i;
      return ICS_OK;
    }
  return ICS_ERR_PARSE;
}

double ics_sat_error_factor(ics_sat_precision mode, int dims) {
  if (dims != 2 && dims != 3) return NAN;
  double c = (dims == 2 ? 4.0 : 8.0) * 1.01;
  switch (mode) {
  case ICS_SAT_FLOAT:
  case ICS_SAT_FLOAT_OFFSET: return c * 0x1p-24;
  case ICS_SAT_COMPENSATED: return c * 0x1p-44;
  case ICS_SAT_DOUBLE: return c * 0x1p-53;
  }
  return NAN;
}

size_t ics_sat_cell_bytes(ics_sat_precision mode) {
  switch (mode) {
  case ICS_SAT_FLOAT:
  case ICS_SAT_FLOAT_OFFSET: return 4;
  case ICS_SAT_COMPENSATED:
  case ICS_SAT_DOUBLE: return 8;
  }
  return 0;
}
