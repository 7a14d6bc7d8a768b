/* icshadow/occtex.h — (placeholder: filled by the work that implements libicshadow/src/occtex.c). */
#ifndef ICSHADOW_OCCTEX_H
#define ICSHADOW_OCCTEX_H

#include "icshadow/status.h"

#endif
