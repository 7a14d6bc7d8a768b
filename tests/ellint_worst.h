/* ellint_worst.h — inputs that gave the largest errors in exhaustive runs of test_ellint,
 * re-tested on every run. Parameter convention: m = k^2, m1 = 1 - m. These are inputs only: the
 * expected results always come from the MPFR reference. Comments: error found (ulp), function.
 * First block of each list: found with the libm-log / Dekker-product version (commit 282952f,
 * --exhaustive seeds 4242 and 99), with that version's error and today's in brackets.
 * Second block: found with the inline-log / 26-bit-head version (--exhaustive seeds 4242, 99;
 * --focus log --n 4000000 7; --focus neg --n 6000000 11 and 23). */
static const double ellint_worst_m1[] = {
    0x1.4c0a15965244p-7,   /* 0.5562 K, log series [0.4438, now pieces] */
    0x1.6679c5821ce4p-7,   /* 0.5510 K [0.4490] */
    0x1.f8a4f35490058p-6,  /* 0.5264 E [0.4736] */
    0x1.980f4f886eeaep-6,  /* 0.5248 E [0.4752] */
    0x1.1ff398f5982bfp-1,  /* 0.5309 K, pieces [0.5309] */
    0x1.1bfd5937f798ep-1,  /* 0.5272 K [0.5272] */
    0x1.e13175c850da6p-1,  /* 0.5145 E [0.5145] */
    0x1.54a4bfaa7ea0ep+0,  /* 0.5218 K, m < 0 pieces of 1/m1 [0.4782] */
    0x1.cb3e43c306e6bp+0,  /* 0.5169 K [0.5169] */
    0x1.78795b6a71b31p+5,  /* 0.5431 K, m < 0 log series [0.4569, now pieces of 1/m1] */
    0x1.802e64c11a618p+5,  /* 0.5157 E [0.4843] */
    0x1.8e306fb926aaap+830, /* 0.5002 K, scaled square roots [0.4998] */
    /* inline log, X0 = 1/128 */
    0x1.ac55543664adap-8,  /* 0.5063 K, log series */
    0x1.fa9bbc78813b9p-8,  /* 0.5063 E, log series */
    0x1.d6f1642f5cd33p-8,  /* 0.5063 E */
    0x1.558411005e19ep+0,  /* 0.5304 E, m < 0 pieces of 1/m1 */
    0x1.73842a995cbd2p+0,  /* 0.5231 K */
    0x1.00000000007d6p+0,  /* 0.5214 K */
    0x1.0045cab0d8c92p+7,  /* 0.5187 E, m < 0 log series */
    0x1.248151d61e747p+7,  /* 0.5178 E */
    0x1.653f57873f049p+7,  /* 0.5010 K */
};
static const double ellint_worst_m[] = {
    0x1.f432e1341f75ap-1,  /* 0.5504 K, log series [0.4496, now pieces] */
    0x1.fab2075db6577p-1,  /* 0.5492 K [0.4508] */
    0x1.f165413965e6fp-1,  /* 0.5276 E [0.4724] */
    0x1.3f41973c18368p-2,  /* 0.5356 K, pieces [0.5356] */
    0x1.2fea83879fbccp-1,  /* 0.5308 K [0.5308] */
    0x1.77d151383d4bcp-3,  /* 0.5139 E [0.5139] */
    -0x1.b8ab3282506cbp+2, /* 0.5327 K, m < 0 pieces of 1/m1 [0.4673] */
    -0x1.83b5cd230afacp+2, /* 0.5313 K [0.4687] */
    -0x1.fab849d6cdfa8p-1, /* 0.5185 E [0.5185] */
    -0x1.2dbd6187e79d4p+5, /* 0.5571 E, m < 0 log series [0.4429, now pieces of 1/m1] */
    -0x1.0d8417592b8eap+5, /* 0.5535 E [0.4465] */
    -0x1.62fe85aa0e8c2p+576, /* 0.5004 K, scaled square roots [0.4996] */
    /* inline log, X0 = 1/128 */
    0x1.fcbf924baed67p-1,  /* 0.5067 E, log series */
    0x1.fc1edfc41514ap-1,  /* 0.5038 K, log series */
    -0x1.1573c8ecf308cp+2, /* 0.5293 K, m < 0 pieces of 1/m1 */
    -0x1.59890bf797daap+2, /* 0.5280 K */
    -0x1.fa7034e99e54p-1,  /* 0.5236 E */
    -0x1.ec60de09e06d9p-3, /* 0.5222 E */
    -0x1.8a623761448eep+7, /* 0.5200 E, m < 0 log series */
    -0x1.31b394bc40292p+7, /* 0.5176 E */
    /* review of c3a7d0e/e1d8ce4: with the 26-bit mask on 1/m1 dropped (q26 = q) these gave
     * K 0.5921 and E 0.5927 (reviewer's mpmath driver), inside 0.60: kept as tripwire inputs */
    -0x1.5c149d993cec5p+2, /* K, m < 0 pieces of 1/m1 */
    -0x1.659e3f4e0e5f9p-23, /* E, m < 0 pieces of 1/m1, tiny |m| */
};
