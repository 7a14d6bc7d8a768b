# Ellipse variance functions and the elliptical kernel (libicshadow/src/ellipse.c).
ics_add_test(NAME test_ellipse SOURCES test_ellipse.c ref_mpfr.c LABELS fast
  LIBS ${ICS_MPFR_LIBS} m NEEDS MPFR)
ics_add_test(NAME test_ellipse_kernel SOURCES test_ellipse_kernel.c LABELS fast LIBS m)
