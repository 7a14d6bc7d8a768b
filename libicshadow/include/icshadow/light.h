/* icshadow/light.h — (placeholder: filled by the work that implements libicshadow/src/light.c). */
#ifndef ICSHADOW_LIGHT_H
#define ICSHADOW_LIGHT_H

#include "icshadow/status.h"

#endif
