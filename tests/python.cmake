# The Python package (python/, docs/python.md). python_install (a fixture) installs it with pip
# from this build's libraries into tmp/python-pkg (tests/python/run.sh --install); python_package
# checks it against the CLI built here, bit for bit where both run the same C
# (tests/python/test_icshadow.py); the analysis drivers that use it (tests/analysis.cmake) require
# the fixture and find it through ICS_PYTHON_ENV (tests/CMakeLists.txt). Not under the sanitizers, whose libraries a
# plain interpreter cannot load. Skipped, with the reason, where /usr/bin/python3 lacks cffi,
# numpy, pip or setuptools.
if(ICS_HAVE_RENDER AND NOT ICS_SANITIZE)
  add_test(NAME python_install COMMAND ${CMAKE_SOURCE_DIR}/tests/python/run.sh --install
    ${CMAKE_BINARY_DIR} $<TARGET_FILE:icshadow_cli>)
  set_tests_properties(python_install PROPERTIES LABELS medium SKIP_RETURN_CODE 77
    FIXTURES_SETUP icshadow_python)
  add_test(NAME python_package COMMAND ${CMAKE_SOURCE_DIR}/tests/python/run.sh --test
    ${CMAKE_BINARY_DIR} $<TARGET_FILE:icshadow_cli>)
  set_tests_properties(python_package PROPERTIES LABELS medium SKIP_RETURN_CODE 77
    FIXTURES_REQUIRED icshadow_python)
endif()
