/* icshadow/shadow1d.h — (placeholder: filled by the work that implements libicshadow/src/shadow1d.c). */
#ifndef ICSHADOW_SHADOW1D_H
#define ICSHADOW_SHADOW1D_H

#include "icshadow/status.h"

#endif
