# ics_library_pair(NAME OBJECTS INCLUDE_DIR): the static and shared libraries NAME_static and
# NAME_shared (libNAME.a, libNAME.so.VERSION) from the object library OBJECTS, their public
# headers in INCLUDE_DIR (the build tree) or the install prefix's include folder. The callers add
# each one's links (the core, the renderer and libicshadow_cl are made alike).
function(ics_library_pair name objects include_dir)
  foreach(kind static shared)
    string(TOUPPER ${kind} KIND)
    add_library(${name}_${kind} ${KIND} $<TARGET_OBJECTS:${objects}>)
    set_target_properties(${name}_${kind} PROPERTIES OUTPUT_NAME ${name}
      VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
    target_include_directories(${name}_${kind} PUBLIC
      $<BUILD_INTERFACE:${include_dir}>
      $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  endforeach()
endfunction()
