# embed_text.cmake — writes a C header holding a text file as a NUL-terminated char array, so
# a program's source ships inside the library (no file to find at run time):
#   cmake -DIN=file.cl -DOUT=file_source.h -DNAME=symbol [-DPRELUDE=header.h] [-DTEXT=file]
#         -P embed_text.cmake
# PRELUDE (gpu/core/device_layout.h: definitions shared with the host) goes ahead of the text,
# after its first line when that is a GLSL "#version", followed by a #line directive so the
# compilers' messages keep the file's own line numbers. TEXT also writes the embedded text as a
# file (the program as compiled, for the GLSL compile checks).
file(READ "${IN}" text)
if(PRELUDE)
  file(READ "${PRELUDE}" prelude)
  if(text MATCHES "^#version[^\n]*\n")
    string(LENGTH "${CMAKE_MATCH_0}" first)
    string(SUBSTRING "${text}" 0 ${first} head)
    string(SUBSTRING "${text}" ${first} -1 rest)
    set(text "${head}${prelude}#line 2\n${rest}") # GLSL 4.50: the next line is line 2
  else()
    set(text "${prelude}#line 1\n${text}")
  endif()
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
get_filename_component(in_name "${IN}" NAME)
set(from "${in_name}")
if(PRELUDE)
  get_filename_component(pre_name "${PRELUDE}" NAME)
  set(from "${in_name} with ${pre_name} ahead")
endif()
file(WRITE "${OUT}" "/* generated from ${from} by cmake/embed_text.cmake: do not edit */\n"
  "static const char ${NAME}[] = {\n  ${body}0x00};\n")
