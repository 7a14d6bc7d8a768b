# embed_text.cmake — writes a C header holding a text file as a NUL-terminated char array, so
# a program's source ships inside the library (no file to find at run time):
#   cmake -DIN=file.cl -DOUT=file_source.h -DNAME=symbol -P embed_text.cmake
file(READ "${IN}" hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," body "${hex}")
string(REGEX REPLACE "((0x..,){24})" "\\1\n  " body "${body}")
get_filename_component(in_name "${IN}" NAME)
file(WRITE "${OUT}" "/* generated from ${in_name} by cmake/embed_text.cmake: do not edit */\n"
  "static const char ${NAME}[] = {\n  ${body}0x00};\n")
