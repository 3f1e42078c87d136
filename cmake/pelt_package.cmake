# Debian packages with CPack: `cpack -G DEB` in a build tree configured with
# -DCMAKE_INSTALL_PREFIX=/usr makes one package per install component
# (cmake/pelt_install.cmake):
#   libpeltN     libpelt.so.N
#   pelt         the pelt command, pelt(1), bash completion
#   libpelt-dev  headers, libpelt.a and the layer libraries, pelt.pc, the CMake package
# The Depends of the binaries come from dpkg-shlibdeps (Debian's dpkg-dev
# and file) plus the GL libraries libepoxy loads at run time; libpelt-dev adds the -dev packages its static libraries, pelt.pc
# and the CMake package need.
set(PELT_MAINTAINER "pelt developers <pelt@localhost>" CACHE STRING
    "Maintainer field of the Debian packages")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME pelt)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "${PELT_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time dynamic shell fur over triangle meshes")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime cli dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)

set(PELT_RUNTIME_PACKAGE libpelt${PROJECT_VERSION_MAJOR})
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME ${PELT_RUNTIME_PACKAGE})
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SECTION libs)
# libepoxy dlopens libEGL.so.1 and libGL.so.1, so dpkg-shlibdeps cannot see
# them; glvnd's libEGL then needs a vendor driver: Mesa's, without a GPU.
set(PELT_GL_DEPENDS "libegl1, libgl1")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "${PELT_GL_DEPENDS}")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION
  "real-time dynamic shell fur over triangle meshes (library)\n"
  "pelt renders fur over triangle meshes with the shell method in any OpenGL 3.3\n"
  "core context and makes it move: it bends under gravity and wind, curls, and\n"
  "clumps where water drops land. This package holds the shared library.")

set(CPACK_DEBIAN_CLI_PACKAGE_NAME pelt)
set(CPACK_DEBIAN_CLI_PACKAGE_SECTION graphics)
# pelt view dlopens libglfw.so.3 (apps/view_window.c): not seen by
# dpkg-shlibdeps either.
set(CPACK_DEBIAN_CLI_PACKAGE_DEPENDS "${PELT_GL_DEPENDS}, libglfw3")
set(CPACK_DEBIAN_CLI_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri")
set(CPACK_DEBIAN_CLI_PACKAGE_SUGGESTS "ffmpeg")
set(CPACK_COMPONENT_CLI_DESCRIPTION
  "real-time dynamic shell fur over triangle meshes (command)\n"
  "The pelt command renders scene files of furry meshes headless through EGL to\n"
  "PNG, PNG sequences or (with ffmpeg) videos, benchmarks them, and checks\n"
  "meshes and their atlases. With the manual page pelt(1) and bash completion.")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME libpelt-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
  "libepoxy-dev, libegl-dev, libassimp-dev, libcjson-dev, libstb-dev, libmeshoptimizer-dev")
set(CPACK_COMPONENT_DEV_DEPENDS runtime)
set(CPACK_COMPONENT_DEV_DESCRIPTION
  "real-time dynamic shell fur over triangle meshes (development files)\n"
  "Headers, the static libraries (libpelt.a and one per layer), the pkg-config\n"
  "file pelt.pc and the CMake package: find_package(pelt) gives pelt::pelt and\n"
  "pelt::pelt_static.")

include(CPack)
