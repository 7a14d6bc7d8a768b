# The Python package (python/, docs/python.md): tests/python/run.sh installs it with pip from this
# build's libraries and checks it against the CLI built here, bit for bit where both run the same C
# (label medium; not under the sanitizers, whose libraries a plain interpreter cannot load).
# Skipped, with the reason, where /usr/bin/python3 lacks cffi, numpy, pip or setuptools.
if(ICS_HAVE_RENDER AND NOT ICS_SANITIZE)
  add_test(NAME python_package COMMAND ${CMAKE_SOURCE_DIR}/tests/python/run.sh ${CMAKE_BINARY_DIR}
    $<TARGET_FILE:icshadow_cli>)
  set_tests_properties(python_package PROPERTIES LABELS medium SKIP_RETURN_CODE 77)
endif()
