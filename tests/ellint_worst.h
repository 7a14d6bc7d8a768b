/* ellint_worst.h — inputs that gave the largest errors in exhaustive runs of test_ellint
 * (--exhaustive with seeds 4242 and 99, 3e6 random MPFR comparisons each), re-tested on every
 * run. Parameter convention: m = k^2, m1 = 1 - m. These are inputs only: the expected
 * results always come from the MPFR reference. Comments: error found (ulp), function. */
static const double ellint_worst_m1[] = {
    0x1.4c0a15965244p-7,   /* 0.5562 K, log series */
    0x1.6679c5821ce4p-7,   /* 0.5510 K */
    0x1.f8a4f35490058p-6,  /* 0.5264 E */
    0x1.980f4f886eeaep-6,  /* 0.5248 E */
    0x1.1ff398f5982bfp-1,  /* 0.5309 K, pieces */
    0x1.1bfd5937f798ep-1,  /* 0.5272 K */
    0x1.e13175c850da6p-1,  /* 0.5145 E */
    0x1.54a4bfaa7ea0ep+0,  /* 0.5218 K, m < 0 pieces of 1/m1 */
    0x1.cb3e43c306e6bp+0,  /* 0.5169 K */
    0x1.78795b6a71b31p+5,  /* 0.5431 K, m < 0 log series */
    0x1.802e64c11a618p+5,  /* 0.5157 E */
    0x1.8e306fb926aaap+830, /* 0.5002 K, scaled square roots */
};
static const double ellint_worst_m[] = {
    0x1.f432e1341f75ap-1,  /* 0.5504 K, log series */
    0x1.fab2075db6577p-1,  /* 0.5492 K */
    0x1.f165413965e6fp-1,  /* 0.5276 E */
    0x1.3f41973c18368p-2,  /* 0.5356 K, pieces */
    0x1.2fea83879fbccp-1,  /* 0.5308 K */
    0x1.77d151383d4bcp-3,  /* 0.5139 E */
    -0x1.b8ab3282506cbp+2, /* 0.5327 K, m < 0 pieces of 1/m1 */
    -0x1.83b5cd230afacp+2, /* 0.5313 K */
    -0x1.fab849d6cdfa8p-1, /* 0.5185 E */
    -0x1.2dbd6187e79d4p+5, /* 0.5571 E, m < 0 log series */
    -0x1.0d8417592b8eap+5, /* 0.5535 E */
    -0x1.62fe85aa0e8c2p+576, /* 0.5004 K, scaled square roots */
};
