/* icshadow.h — the one public header of libicshadow (C11; libm only, OpenEXR optional).
 *
 * libicshadow computes and measures the numerics behind convolution soft shadows (Patel et al.
 * 2013) and the primitives of their peers. Including this header includes every module below;
 * each module's own header states its conventions and measured accuracy, and the layers are
 * described in docs/architecture.md. Every symbol is prefixed ics_ / ICS_.
 *
 * Conventions (docs/architecture.md "Conventions of the API"): the functions of icshadow/X.h
 * are named ics_X_* (ics_X1d_*, ics_X2d_*, ics_X3d_*); objects that own memory are made by
 * ics_X_create(&out, ...) (*out NULL on failure) and freed by ics_X_destroy (NULL is fine);
 * value structs are filled by ics_X_init(&out, ...), and options structs zero-initialised are
 * their defaults where zero can mean the default; every public declaration carries ICS_API
 * (icshadow/api.h). Math functions take plain doubles, return NaN outside their domain and
 * never touch errno; functions that build objects return an ics_status (ics_status_str()
 * names it). Elliptic integrals take the PARAMETER m = k^2 (as mpmath, scipy, Mathematica),
 * and the complementary parameter m1 = 1 - m through the *_m1 entry points. */
#ifndef ICSHADOW_H
#define ICSHADOW_H

#define ICS_VERSION_MAJOR 0
#define ICS_VERSION_MINOR 2
#define ICS_VERSION_PATCH 0

/* ---- numerics ---- */
#include "icshadow/status.h"    /* ics_status codes and ics_status_str */
#include "icshadow/constants.h" /* ICS_PI */
#include "icshadow/ellint.h"    /* complete elliptic integrals K(m), E(m), <= 0.60 ulp */
#include "icshadow/ellipse.h"   /* ellipse variances (abToVarx, ratioToab), elliptical kernel */
#include "icshadow/lut.h"       /* lookup tables for ratioToab / abToVarx, C/GLSL/OpenCL headers */
#include "icshadow/normal.h"    /* the normal distribution: cdf, sf, quantile, bivariate cdf */

/* ---- theory: kernels, lights, engine, shadows, CLT ---- */
#include "icshadow/rng.h"      /* counter-based Philox RNG: reproducible stochastic kernels */
#include "icshadow/class.h"    /* kernel equivalence classes: mean and (co)variance */
#include "icshadow/taps.h"     /* tap lists: moments, discretisation, variance compensation */
#include "icshadow/kernel.h"   /* the members of a class and their taps */
#include "icshadow/schedule.h" /* per-iteration member choice (Lyapunov mixing) */
#include "icshadow/light.h"    /* virtual light plane, Gaussian lights, Eq. 7/15, 1D lights */
#include "icshadow/conv.h"     /* iterative convolution engine (1D/2D): steps, runs, budget */
#include "icshadow/shadow1d.h" /* correct and CLT shadows behind an edge, sign conventions */
#include "icshadow/iter1d.h"   /* the iterated shadow behind an edge (conv engine) */
#include "icshadow/isoline.h"  /* isolines of the correct, CLT and iterated shadows */
#include "icshadow/clt.h"      /* CLT measurements: the measured point, the rate fit */
#include "icshadow/clt1d.h"    /* CLT convergence of the 1D kernel members */
#include "icshadow/clt2d.h"    /* CLT convergence of the 2D kernel members */

/* ---- images and lights ---- */
#include "icshadow/image.h"    /* float RGB(A) images, row 0 at the top */
#include "icshadow/input_file.h" /* inputs: regular files only, with a size bound */
#include "icshadow/exr.h"      /* OpenEXR I/O (optional: ICS_ERR_UNSUPPORTED without it) */
#include "icshadow/envmap.h"   /* latitude-longitude maps on the light plane, synthetic maps */
#include "icshadow/lightfit.h" /* environment map -> Gaussian lights on the light plane */
#include "icshadow/json_text.h" /* JSON strings as the library and its tools write them */

/* ---- peer primitives ---- */
#include "icshadow/sat.h"         /* summed-area tables 2D/3D in four precision modes (Ament 2014) */
#include "icshadow/volume.h"      /* volumes of extinction: sampling, ray-marched optical depth */
#include "icshadow/csat.h"        /* light-aligned CSAT: box-filtered optical depth, six lights */
#include "icshadow/ssat.h"        /* spherical SAT (SSAT) around a point light */
#include "icshadow/minmax.h"      /* 1D min-max mipmaps (Chen 2011) */
#include "icshadow/svd.h"         /* one-sided Jacobi SVD: the low-rank integrand */
#include "icshadow/epipolar.h"    /* epipolar rectification of a directional light */
#include "icshadow/heightfield.h" /* a synthetic height-field scene and its shadow map */
#include "icshadow/occtex.h"      /* occlusion textures (Eisemann & Decoret 2006) */

/* ---- deprecated aliases (kept for one minor version; see CHANGELOG.md) ---- */
#include "icshadow/deprecated.h"

#endif
