# The deprecated aliases of renamed public functions (icshadow/deprecated.h): each returns
# exactly what its new name returns. The test calls the old names on purpose.
ics_add_test(NAME test_deprecated SOURCES test_deprecated.c LABELS fast LIBS m)
if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
  target_compile_options(test_deprecated PRIVATE -Wno-deprecated-declarations)
endif()
