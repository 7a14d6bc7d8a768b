/* ellint_worst.h — inputs that gave the largest errors in exhaustive runs of test_ellint
 * (--exhaustive, several seeds); re-tested on every run. Parameter convention: m = k^2,
 * m1 = 1 - m. The values are inputs only; the expected results come from MPFR. */
static const double ellint_worst_m1[] = {
    0x1p-4, 0x1p-1074,
};
static const double ellint_worst_m[] = {
    0x1.ep-1, -0x1.ep+3,
};
