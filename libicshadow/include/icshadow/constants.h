/* icshadow/constants.h — the mathematical constants of libicshadow, one definition each, for
 * the library, the CLI, the tests and the benchmarks alike. */
#ifndef ICSHADOW_CONSTANTS_H
#define ICSHADOW_CONSTANTS_H

/* pi to 21 digits: the literal rounds to the double nearest pi, and 2 * ICS_PI, ICS_PI / 2 and
 * ICS_PI / 4 are exact (the doubles nearest 2 pi, pi/2, pi/4). */
#define ICS_PI 3.14159265358979323846

#endif
