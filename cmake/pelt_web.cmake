# The browser build (scripts/web.sh, docs/web.md): `pelt view` on a WebGL2
# canvas. The same core/, scene/ and gl/ components as the desktop build,
# the viewer's sources of apps/, and the page of web/. Nothing else:
# no headless context, no tests (tests/web/ drives the page in Chromium).
add_executable(pelt_web
  apps/web_main.c apps/commands.c apps/cmd_view.c apps/view_window.c apps/view_input.c apps/view_script.c
  apps/view_hud.c apps/options.c apps/png_out.c)
set_target_properties(pelt_web PROPERTIES OUTPUT_NAME pelt SUFFIX .html)
target_include_directories(pelt_web PRIVATE ${CMAKE_SOURCE_DIR})
target_compile_definitions(pelt_web PRIVATE PELT_HAVE_GLFW)
target_link_libraries(pelt_web PRIVATE pelt_scene pelt_gl PkgConfig::STB m)
set(PELT_WEB_PAGE ${CMAKE_SOURCE_DIR}/web/shell.html ${CMAKE_SOURCE_DIR}/web/page.js)
target_link_options(pelt_web PRIVATE
  -sUSE_GLFW=3 -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2
  -sALLOW_MEMORY_GROWTH=1 -sINITIAL_MEMORY=134217728
  -sINVOKE_RUN=0 -sEXIT_RUNTIME=0 -sFORCE_FILESYSTEM=1
  # Debian's emcc 3.1.6 calls htmlmin wrongly at -O2 and above: the page stays as written.
  -sMINIFY_HTML=0
  "-sEXPORTED_RUNTIME_METHODS=['FS','callMain']"
  # assimp reports a malformed mesh by throwing: catch it, as on the desktop.
  -fexceptions -sDISABLE_EXCEPTION_CATCHING=0
  --shell-file ${CMAKE_SOURCE_DIR}/web/shell.html
  --pre-js ${CMAKE_SOURCE_DIR}/web/page.js
  # The bundled scenes, their meshes and maps, at /scenes in the page's files.
  --preload-file ${CMAKE_SOURCE_DIR}/scenes@/scenes)
set_property(TARGET pelt_web APPEND PROPERTY LINK_DEPENDS ${PELT_WEB_PAGE})
