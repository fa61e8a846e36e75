# cmake -DINPUT=file -DOUTPUT=file.inc -P embed_file.cmake
# Writes the bytes of INPUT as a comma-separated list of hexadecimal literals, to be included
# in an array initializer (a string literal would exceed what -Wpedantic allows).
file(READ ${INPUT} hex HEX)
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
string(REGEX REPLACE "((0x..,){32})" "\\1\n" bytes "${bytes}")
file(WRITE ${OUTPUT} "${bytes}\n")
