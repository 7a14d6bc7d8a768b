# The renderer's modules (gpu/core/module.h, docs/architecture.md "Modules"): where none loads,
# everything that does not need one works and what does need one says which and where it was
# looked for (exit 2, no output); commands that need none map none of the heavy libraries, and a
# gl and a cl render do (the control). tests/cli/modules.sh.
if(ICS_HAVE_RENDER)
  set(ics_modules_built "")
  foreach(m GL OPENCL ASSIMP EMBREE)
    if(ICS_HAVE_${m})
      string(TOLOWER ${m} name)
      string(REPLACE "opencl" "cl" name ${name})
      list(APPEND ics_modules_built ${name})
    endif()
  endforeach()
  foreach(what missing mapped)
    add_test(NAME cli_modules_${what} COMMAND ${CMAKE_SOURCE_DIR}/tests/cli/modules.sh
      $<TARGET_FILE:icshadow_cli> ${CMAKE_SOURCE_DIR}/scenes
      ${CMAKE_CURRENT_BINARY_DIR}/tmp/cli_modules_${what} ${what} ${ics_modules_built})
    set_tests_properties(cli_modules_${what} PROPERTIES LABELS "fast;cli" TIMEOUT 300) # (a hang fails)
  endforeach()
endif()
