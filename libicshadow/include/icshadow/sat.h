/* icshadow/sat.h — (placeholder: filled by the work that implements libicshadow/src/sat.c). */
#ifndef ICSHADOW_SAT_H
#define ICSHADOW_SAT_H

#include "icshadow/status.h"

#endif
