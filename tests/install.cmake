# Install into a temporary prefix and build a consumer both ways (pkg-config, find_package).
add_test(NAME install_consumer
  COMMAND ${CMAKE_SOURCE_DIR}/tests/install/run.sh ${CMAKE_BINARY_DIR} ${CMAKE_SOURCE_DIR} ${CMAKE_C_COMPILER})
set_tests_properties(install_consumer PROPERTIES LABELS medium)
