# Counter RNG, kernel equivalence classes, iterative convolution engine
# (libicshadow/src/rng.c, kernel.c, conv.c).
ics_add_test(NAME test_rng SOURCES test_rng.c LABELS fast LIBS m)
ics_add_test(NAME test_kernel SOURCES test_kernel.c LABELS fast LIBS m)
ics_add_test(NAME test_conv SOURCES test_conv.c LABELS fast LIBS m)
