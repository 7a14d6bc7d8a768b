/* icshadow/kernel.h — (placeholder: filled by the work that implements libicshadow/src/kernel.c). */
#ifndef ICSHADOW_KERNEL_H
#define ICSHADOW_KERNEL_H

#include "icshadow/status.h"

#endif
