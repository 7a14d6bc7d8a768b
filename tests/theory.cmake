# Theory of iterative convolution shadows (libicshadow/src/light.c, shadow1d.c): lights and the
# Eq. 7/15 mapping; the half-shadow isoline (A.5) and CLT convergence suites (names asked for by
# users: clt_convergence, half_shadow_isoline).
ics_add_test(NAME test_light SOURCES test_light.c LABELS fast LIBS m)
# medium by cost: 7 s under ASan, under 1 s Release (docs/testing.md)
ics_add_test(NAME half_shadow_isoline SOURCES test_half_shadow_isoline.c LABELS medium LIBS m)
# medium by cost: 8 s Release, 76 s under ASan (fast tests take seconds)
ics_add_test(NAME clt_convergence SOURCES test_clt_convergence.c LABELS medium LIBS m)
# Release ~5 s, ASan ~15-20 s (expensive 2D cases skipped there): a hang fails within 5 min
set_tests_properties(clt_convergence PROPERTIES TIMEOUT 300)
