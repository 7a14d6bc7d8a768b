/* icshadow/lut.h — lookup tables for ratioToab and abToVarx and their header generator.
 * (Filled by the lookup-table work: see docs/lut.md.) */
#ifndef ICSHADOW_LUT_H
#define ICSHADOW_LUT_H

#include "icshadow/status.h"

#endif
