# SPDX-License-Identifier: BSD-3-Clause
# lmk_add_library(NAME SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One library per top-level folder, exported as lmk::NAME. Headers live beside the sources and are
# included as "lmk/NAME/header.h", in the tree and installed alike, so that a consumer's own
# geometry/ or eval/ folders never collide with lmk's. Only lmk/ is on a consumer's include path:
# in the build tree it holds one link per module (lmk_expose_headers); headers in detail/ stay
# private to the build and are not installed.
set(LMK_INCLUDE_DIR "${PROJECT_BINARY_DIR}/include")
set(LMK_GENERATED_INCLUDE_DIR "${PROJECT_BINARY_DIR}/generated")

# Makes the current folder's headers includable as "lmk/NAME/...": a link from the build tree's
# include/lmk/NAME to the folder, so that the sources stay beside their headers.
function(lmk_expose_headers name)
  file(MAKE_DIRECTORY "${LMK_INCLUDE_DIR}/lmk")
  file(CREATE_LINK "${CMAKE_CURRENT_SOURCE_DIR}" "${LMK_INCLUDE_DIR}/lmk/${name}" SYMBOLIC)
endfunction()

function(lmk_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target lmk_${name})
  add_library(${target} ${ARG_SOURCES})
  add_library(lmk::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME lmk_${name}
    EXPORT_NAME ${name}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  lmk_expose_headers(${name})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${LMK_INCLUDE_DIR}>
    $<BUILD_INTERFACE:${LMK_GENERATED_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  install(TARGETS ${target} EXPORT lmkTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  file(GLOB headers "${CMAKE_CURRENT_SOURCE_DIR}/*.h")
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lmk/${name})
endfunction()
