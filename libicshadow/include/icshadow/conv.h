/* icshadow/conv.h — (placeholder: filled by the work that implements libicshadow/src/conv.c). */
#ifndef ICSHADOW_CONV_H
#define ICSHADOW_CONV_H

#include "icshadow/status.h"

#endif
