# What `cmake --install` puts where, in three CPack components
# (cmake/pelt_package.cmake makes one Debian package of each):
#   runtime  libpelt.so.N                                  -> libpeltN
#   cli      the pelt command, pelt(1), bash completion    -> pelt
#   dev      headers, static libraries, pelt.pc, the CMake
#            package (find_package(pelt)), the .so link     -> libpelt-dev
# Included from CMakeLists.txt after the targets are defined.
include(CMakePackageConfigHelpers)

# The version the package files carry is the one pelt.h reports.
file(STRINGS ${CMAKE_SOURCE_DIR}/include/pelt/pelt.h PELT_H_VERSION
     REGEX "#define PELT_VERSION_STRING")
if(NOT PELT_H_VERSION MATCHES "\"${PROJECT_VERSION}\"")
  message(FATAL_ERROR "include/pelt/pelt.h says ${PELT_H_VERSION}; project() says ${PROJECT_VERSION}")
endif()

# libpelt.a: every component in one static library, for pelt::pelt_static.
pelt_bundle(pelt_static STATIC)
set_target_properties(pelt_static PROPERTIES OUTPUT_NAME pelt)
set_target_properties(pelt_shared PROPERTIES EXPORT_NAME pelt)

# The .pc file finds the prefix from its own place, so `cmake --install
# --prefix DIR` gives a working file wherever DIR is.
file(RELATIVE_PATH PELT_PC_UP "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig" "${CMAKE_INSTALL_PREFIX}")
string(REGEX REPLACE "/$" "" PELT_PC_UP "${PELT_PC_UP}")
set(PELT_PC_PREFIX "\${pcfiledir}/${PELT_PC_UP}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/pelt.pc.in ${CMAKE_BINARY_DIR}/pelt.pc @ONLY)

# The manual page and the bash completion, printed by the pelt just built
# from the tables behind its --help (apps/commands.c), so none can drift.
set(PELT_MAN ${CMAKE_BINARY_DIR}/pelt.1)
set(PELT_COMPLETION ${CMAKE_BINARY_DIR}/pelt.bash-completion)
set(PELT_PRINT ${CMAKE_SOURCE_DIR}/cmake/pelt_print.cmake)
add_custom_command(OUTPUT ${PELT_MAN} ${PELT_MAN}.gz
  COMMAND ${CMAKE_COMMAND} -DPELT=$<TARGET_FILE:pelt> -DARGS=manpage -DOUT=${PELT_MAN} -DGZIP=ON
          -P ${PELT_PRINT}
  DEPENDS pelt ${PELT_PRINT} COMMENT "Printing the manual page pelt.1" VERBATIM)
add_custom_command(OUTPUT ${PELT_COMPLETION}
  COMMAND ${CMAKE_COMMAND} -DPELT=$<TARGET_FILE:pelt> -DARGS=completion|bash
          -DOUT=${PELT_COMPLETION} -P ${PELT_PRINT}
  DEPENDS pelt ${PELT_PRINT} COMMENT "Printing the bash completion" VERBATIM)
add_custom_target(pelt_manual ALL DEPENDS ${PELT_MAN} ${PELT_COMPLETION})

install(TARGETS pelt RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
install(FILES ${PELT_MAN}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT cli)
install(FILES ${PELT_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
  RENAME pelt COMPONENT cli)

install(TARGETS pelt_shared EXPORT peltTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT runtime NAMELINK_COMPONENT dev)
install(TARGETS pelt_static ${PELT_COMPONENTS} EXPORT peltTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/pelt DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  COMPONENT dev)
install(FILES ${CMAKE_BINARY_DIR}/pelt.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
  COMPONENT dev)

# The CMake package: find_package(pelt CONFIG) gives pelt::pelt (libpelt.so),
# pelt::pelt_static (libpelt.a) and the layers pelt::pelt_core, _gl, _scene,
# _headless. 0.x: only the same minor version is compatible.
set(PELT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pelt)
install(EXPORT peltTargets NAMESPACE pelt:: DESTINATION ${PELT_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/peltConfig.cmake.in
  ${CMAKE_BINARY_DIR}/peltConfig.cmake INSTALL_DESTINATION ${PELT_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/peltConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/peltConfig.cmake ${CMAKE_BINARY_DIR}/peltConfigVersion.cmake
  DESTINATION ${PELT_CMAKE_DIR} COMPONENT dev)
