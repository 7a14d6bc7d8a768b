/* icshadow/minmax.h — (placeholder: filled by the work that implements libicshadow/src/minmax.c). */
#ifndef ICSHADOW_MINMAX_H
#define ICSHADOW_MINMAX_H

#include "icshadow/status.h"

#endif
