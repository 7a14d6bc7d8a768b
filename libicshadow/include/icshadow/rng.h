/* icshadow/rng.h — (placeholder: filled by the work that implements libicshadow/src/rng.c). */
#ifndef ICSHADOW_RNG_H
#define ICSHADOW_RNG_H

#include "icshadow/status.h"

#endif
