# embed_text.cmake — writes a C header holding a program's source as a NUL-terminated char array,
# so the program ships inside the library (no file to find at run time):
#   cmake -DIN=file.cl -DOUT=file_source.h -DNAME=symbol [-DINCLUDE_DIR=dir] [-DTEXT=file]
#         -P embed_text.cmake
# Each line `#include "path"` is replaced by the file INCLUDE_DIR/path (the shared kernel source,
# gpu/kernel/: one text for C, OpenCL C and GLSL, which has no #include), recursively, wherever
# it stands (a GLSL program includes some only inside the #if of the entry points that use
# them); the headers' include guards keep one copy per compiled program. #line directives keep
# the compilers' messages in each file's own lines: `#line N "path"` in OpenCL C, `#line N S` in
# GLSL (a .comp file), whose source-string number S is the file's place in the list this script
# writes as a comment at the program's start. TEXT also
# writes the expanded text as a file (the program as compiled, for the GLSL compile checks).
set(ics_glsl 0)
if(IN MATCHES "\\.comp$")
  set(ics_glsl 1)
endif()
set_property(GLOBAL PROPERTY ics_embed_files "${IN}")

# `#line N` for the file with list index idx and name rel
function(ics_line_directive n idx rel out)
  if(ics_glsl)
    set(${out} "#line ${n} ${idx}\n" PARENT_SCOPE)
  else()
    set(${out} "#line ${n} \"${rel}\"\n" PARENT_SCOPE)
  endif()
endfunction()

# the text of `path` (shown as `rel`, list index idx) with its includes expanded, into out
function(ics_expand path rel idx out)
  file(READ "${path}" text)
  set(result "")
  set(line 1) # this file's line number at the start of `text`
  while(text MATCHES "(^|\n)#include \"([^\"\n]+)\"[^\n]*(\n|$)")
    set(inc "${CMAKE_MATCH_2}")
    set(lead "${CMAKE_MATCH_1}")
    string(FIND "${text}" "${CMAKE_MATCH_0}" pos)
    string(LENGTH "${CMAKE_MATCH_0}" len)
    string(LENGTH "${lead}" lead_len)
    math(EXPR cut "${pos} + ${lead_len}")
    string(SUBSTRING "${text}" 0 ${cut} before)
    math(EXPR after_at "${pos} + ${len}")
    string(SUBSTRING "${text}" ${after_at} -1 text)
    string(REGEX MATCHALL "\n" nls "${before}")
    list(LENGTH nls n_before)
    math(EXPR line "${line} + ${n_before} + 1") # the line after the #include
    string(APPEND result "${before}")
    if(NOT INCLUDE_DIR OR NOT EXISTS "${INCLUDE_DIR}/${inc}")
      message(FATAL_ERROR "embed_text: ${rel} includes \"${inc}\", not found under ${INCLUDE_DIR}")
    endif()
    get_property(seen GLOBAL PROPERTY ics_embed_files)
    list(FIND seen "${INCLUDE_DIR}/${inc}" inc_idx)
    if(inc_idx LESS 0)
      set_property(GLOBAL APPEND PROPERTY ics_embed_files "${INCLUDE_DIR}/${inc}")
      list(LENGTH seen inc_idx)
    endif()
    ics_line_directive(1 ${inc_idx} "${inc}" first)
    ics_expand("${INCLUDE_DIR}/${inc}" "${inc}" ${inc_idx} body)
    if(NOT body MATCHES "\n$")
      string(APPEND body "\n")
    endif()
    ics_line_directive(${line} ${idx} "${rel}" back)
    string(APPEND result "${first}${body}${back}")
  endwhile()
  string(APPEND result "${text}")
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

get_filename_component(in_name "${IN}" NAME)
ics_expand("${IN}" "${in_name}" 0 text)
get_property(files GLOBAL PROPERTY ics_embed_files)
list(LENGTH files nfiles)
if(nfiles GREATER 1)
  # which file each number names, first (after a GLSL #version)
  set(listing "/* expanded by cmake/embed_text.cmake; #line numbers name the files:")
  set(i 0)
  foreach(f IN LISTS files)
    file(RELATIVE_PATH shown "${INCLUDE_DIR}" "${f}")
    if(i EQUAL 0)
      set(shown "${in_name}")
    endif()
    string(APPEND listing " ${i} ${shown}")
    math(EXPR i "${i} + 1")
  endforeach()
  string(APPEND listing " */\n")
  if(text MATCHES "^#version[^\n]*\n") # a GLSL #version must come first
    string(LENGTH "${CMAKE_MATCH_0}" rest_at)
    set(first_line 2)
  else()
    set(rest_at 0)
    set(first_line 1)
  endif()
  string(SUBSTRING "${text}" 0 ${rest_at} head)
  string(SUBSTRING "${text}" ${rest_at} -1 rest)
  ics_line_directive(${first_line} 0 "${in_name}" back)
  set(text "${head}${listing}${back}${rest}")
endif()
if(NOT TEXT)
  set(TEXT "${OUT}.txt")
  set(remove_text 1)
endif()
file(WRITE "${TEXT}" "${text}")
file(READ "${TEXT}" hex HEX)
if(remove_text)
  file(REMOVE "${TEXT}")
endif()
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," body "${hex}")
string(REGEX REPLACE "((0x..,){24})" "\\1\n  " body "${body}")
file(WRITE "${OUT}" "/* generated from ${in_name} by cmake/embed_text.cmake: do not edit */\n"
  "static const char ${NAME}[] = {\n  ${body}0x00};\n")
