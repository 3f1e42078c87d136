# Turns every listed NAME.glsl (FILES, separated by |) into
# `const char pelt__shader_NAME[]`.
string(REPLACE "|" ";" FILES "${FILES}")
set(out "/* Generated from the gl/shaders .glsl files by cmake/embed_shaders.cmake. */\n")
foreach(f ${FILES})
  get_filename_component(name ${f} NAME_WE)
  file(READ ${f} text HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${text}")
  string(APPEND out "const char pelt__shader_${name}[] = {${bytes}0x00};\n")
endforeach()
file(WRITE ${OUT}.tmp "${out}")
file(RENAME ${OUT}.tmp ${OUT})
