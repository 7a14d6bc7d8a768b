/* icshadow.h — the one public header of libicshadow (C11; libm only).
 *
 * libicshadow computes the numerics behind convolution soft shadows (Patel et al. 2013):
 * complete elliptic integrals, the ellipse variance functions and elliptical kernels,
 * and lookup tables for shaders. Every symbol is prefixed ics_ / ICS_.
 *
 * Conventions: math functions take plain doubles, return NaN outside their domain and never
 * touch errno; functions that build objects return an ics_status (ics_status_str() names it).
 * Elliptic integrals take the PARAMETER m = k^2 (as mpmath, scipy, Mathematica), and the
 * complementary parameter m1 = 1 - m through the *_m1 entry points. */
#ifndef ICSHADOW_H
#define ICSHADOW_H

#define ICS_VERSION_MAJOR 0
#define ICS_VERSION_MINOR 1
#define ICS_VERSION_PATCH 0

#include "icshadow/constants.h"
#include "icshadow/status.h"
#include "icshadow/ellint.h"
#include "icshadow/ellipse.h"
#include "icshadow/lut.h"
#include "icshadow/rng.h"
#include "icshadow/kernel.h"
#include "icshadow/normal.h"
#include "icshadow/light.h"
#include "icshadow/conv.h"
#include "icshadow/shadow1d.h"
#include "icshadow/clt2d.h"
#include "icshadow/sat.h"
#include "icshadow/volume.h"
#include "icshadow/csat.h"
#include "icshadow/ssat.h"
#include "icshadow/minmax.h"
#include "icshadow/occtex.h"
#include "icshadow/image.h"
#include "icshadow/exr.h"
#include "icshadow/lightfit.h"
#include "icshadow/deprecated.h"

#endif
