# SPDX-License-Identifier: BSD-3-Clause
# Installs the export set so that a consumer can write find_package(lmk) and link lmk::landmark.
include(CMakePackageConfigHelpers)
set(LMK_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/lmk)

install(EXPORT lmkTargets NAMESPACE lmk:: DESTINATION ${LMK_CMAKE_DIR})
install(FILES "${LMK_GENERATED_INCLUDE_DIR}/lmk/geometry/version.h"
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lmk/geometry)
configure_package_config_file(cmake/lmkConfig.cmake.in
  "${PROJECT_BINARY_DIR}/lmkConfig.cmake" INSTALL_DESTINATION ${LMK_CMAKE_DIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/lmkConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/lmkConfig.cmake" "${PROJECT_BINARY_DIR}/lmkConfigVersion.cmake"
        DESTINATION ${LMK_CMAKE_DIR})
