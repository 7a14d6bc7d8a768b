# The shared library exports exactly the functions (and data) the public headers declare with
# ICS_API: a private symbol exported, or a declared one missing, fails (tests/export/).
add_test(NAME export_symbols
  COMMAND ${CMAKE_SOURCE_DIR}/tests/export/check_exports.sh ${CMAKE_NM}
    $<TARGET_FILE:icshadow_shared> ${CMAKE_SOURCE_DIR}/libicshadow/include)
set_tests_properties(export_symbols PROPERTIES LABELS fast)
add_test(NAME export_symbols_cl
  COMMAND ${CMAKE_SOURCE_DIR}/tests/export/check_exports.sh ${CMAKE_NM}
    $<TARGET_FILE:icshadow_cl_shared> ${CMAKE_SOURCE_DIR}/libicshadow_cl/include)
set_tests_properties(export_symbols_cl PROPERTIES LABELS fast)
if(ICS_HAVE_RENDER)
  add_test(NAME export_symbols_render
    COMMAND ${CMAKE_SOURCE_DIR}/tests/export/check_exports.sh ${CMAKE_NM}
      $<TARGET_FILE:icshadow_render_shared> ${CMAKE_SOURCE_DIR}/gpu/include)
  set_tests_properties(export_symbols_render PROPERTIES LABELS fast)
endif()
