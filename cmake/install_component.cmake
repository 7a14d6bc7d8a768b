# ics_install_component(TARGET EXPORT_SET INCLUDE_DIR PC_NAME): a shared library installed as a
# component of the CMake package beside the core: its public headers (INCLUDE_DIR's contents),
# the library (run path $ORIGIN: it finds libicshadow beside itself, also for a consumer linked
# --as-needed that calls only it), its export set (icshadow::..., included by
# icshadowConfig.cmake when present) and pkg-config PC_NAME (cmake/PC_NAME.pc.in).
function(ics_install_component target export_set include_dir pc_name)
  install(DIRECTORY ${include_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN")
  install(TARGETS ${target} EXPORT ${export_set}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT ${export_set} NAMESPACE icshadow::
    DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/icshadow)
  configure_file(${CMAKE_SOURCE_DIR}/cmake/${pc_name}.pc.in ${CMAKE_BINARY_DIR}/${pc_name}.pc @ONLY)
  install(FILES ${CMAKE_BINARY_DIR}/${pc_name}.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endfunction()
