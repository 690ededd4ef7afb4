# Writes a C++ header holding a text file as one raw string literal, at build time:
#   cmake -DINPUT=file.js -DOUTPUT=file.hpp -DNAME=kSymbol -P embed_text.cmake
# The text stays a readable file of its own in the sources (compare/replay/replay.js); the
# header is generated in the build tree and never installed.
file(READ "${INPUT}" text)
set(delimiter "motus_embed")
string(FIND "${text}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT}: contains )${delimiter}\", which would end the raw string literal")
endif()
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${INPUT} by cmake/embed_text.cmake; edit that file, not this one.\n"
  "#pragma once\n"
  "inline constexpr char ${NAME}[] = R\"${delimiter}(${text})${delimiter}\";\n")
file(COPY_FILE "${OUTPUT}.tmp" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.tmp")
