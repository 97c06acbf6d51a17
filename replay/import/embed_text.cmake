# Turns one text file into a C++ source defining its bytes, so the binary carries the file and
# needs nothing from the source tree at run time. Bytes, not a raw string literal: any text works.
file(READ ${IN} bytes HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "'\\\\x\\1'," chars "${bytes}")
file(WRITE ${OUT} "#include <string_view>\nnamespace aor {\nstatic const char ${NAME}_bytes[] = {${chars}};\nextern const std::string_view ${NAME}(${NAME}_bytes, sizeof ${NAME}_bytes);\n}\n")
