# Gaussian light fitting (pure C: synthetic maps -> fit), float images and their comparison,
# OpenEXR I/O (needs OpenEXR).
ics_add_test(NAME test_lightfit SOURCES test_lightfit.c LABELS fast)
ics_add_test(NAME test_image SOURCES test_image.c LABELS fast LIBS m)
if(ICS_HAVE_OPENEXR)
  set(ICS_EXR_TEST_LIBS OpenEXR::OpenEXRCore)
endif()
ics_add_test(NAME test_exr SOURCES test_exr.c LABELS fast LIBS ${ICS_EXR_TEST_LIBS} NEEDS OPENEXR)
ics_add_test(NAME test_exr_write_faults SOURCES test_exr_write_faults.c LABELS fast LIBS ${ICS_EXR_TEST_LIBS} NEEDS OPENEXR)
