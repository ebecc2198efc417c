# `cmake --install build --prefix P`: the public libraries and headers, the `neopipe` program and its
# media plug-in, a CMake package (find_package(neopipe CONFIG)) and a pkg-config file (neopipe.pc).
include(CMakePackageConfigHelpers)

get_property(neopipe_public_targets GLOBAL PROPERTY NEOPIPE_PUBLIC_TARGETS)
get_property(neopipe_public_headers GLOBAL PROPERTY NEOPIPE_PUBLIC_HEADERS)

install(TARGETS ${neopipe_public_targets} EXPORT neopipeTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(header IN LISTS neopipe_public_headers)
  get_filename_component(dir ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/neopipe/${dir})
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/generated/neopipe_version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/neopipe)

# The program, and its plug-in where the program looks for it: ${NEOPIPE_MEDIA_PLUGIN_DIR} relative to
# the program's directory (pipeline/media/media.cpp), so the installed tree can move as a whole.
install(TARGETS neopipe RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS neopipe_media LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/neopipe)

install(EXPORT neopipeTargets NAMESPACE neopipe:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/neopipe)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/neopipeConfig.cmake.in
  ${PROJECT_BINARY_DIR}/neopipeConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/neopipe)
# 0.x: every minor version may break the interface (semantic versioning), so only the same minor matches.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/neopipeConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/neopipeConfig.cmake ${PROJECT_BINARY_DIR}/neopipeConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/neopipe)

# pkg-config: the static libraries in link order (users before what they use), and the packages
# they link, whose own .pc files bring their flags.
file(RELATIVE_PATH NEOPIPE_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" NEOPIPE_PC_TO_PREFIX "${NEOPIPE_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/neopipe.pc.in ${PROJECT_BINARY_DIR}/neopipe.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/neopipe.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
