# SPDX-License-Identifier: BSD-3-Clause
# lmk_add_library(NAME [INTERNAL] SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# One library per top-level folder, exported as lmk::NAME. INTERNAL: a static library for lmk's own
# tool and tests, neither installed nor exported (lmk::serve). Headers live beside the sources and
# are included as "lmk/NAME/header.h", in the tree and installed alike, so that a consumer's own
# geometry/ or eval/ folders never collide with lmk's. In the source tree, include/lmk/ holds one
# committed link per module folder (include/lmk/geometry -> ../../geometry), so that the includes
# resolve with -Iinclude alone: in editors and code tools without a build, as in the build.
# Headers in detail/ and internal/ are lmk's own (docs/developing.md) and are not installed.
set(LMK_INCLUDE_DIR "${PROJECT_SOURCE_DIR}/include")
set(LMK_GENERATED_INCLUDE_DIR "${PROJECT_BINARY_DIR}/generated")

option(LMK_WERROR "Treat compiler warnings as errors (CI builds with it on)" OFF)

# The warnings every lmk target is compiled with: set here once, for libraries, tools, tests,
# benchmarks, the ROS node and the Python module alike.
# In a unity build GCC sees each source as included by its batch, so it takes a source's pimpl
# (`struct X::Impl` with members of types from the source's anonymous namespace) for a header's
# class and warns of a one-definition risk that only headers carry: a false alarm there.
function(lmk_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra $<$<BOOL:${LMK_WERROR}>:-Werror>
    $<$<AND:$<CXX_COMPILER_ID:GNU>,$<BOOL:$<TARGET_PROPERTY:UNITY_BUILD>>>:-Wno-subobject-linkage>)
endfunction()

# cpp-httplib includes <resolv.h>, whose `_res` macro (glibc's resolver state) rewrites Eigen's
# parameters of that name. In a unity batch a source that includes httplib may come before one that
# includes Eigen's headers first, so the targets that use httplib undo the macro between sources.
function(lmk_unity_after_httplib target)
  set_property(TARGET ${target} PROPERTY UNITY_BUILD_CODE_BEFORE_INCLUDE "#undef _res")
endfunction()

function(lmk_add_library name)
  cmake_parse_arguments(ARG "INTERNAL" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target lmk_${name})
  if(ARG_INTERNAL)
    add_library(${target} STATIC ${ARG_SOURCES})
  else()
    add_library(${target} ${ARG_SOURCES})
  endif()
  add_library(lmk::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME lmk_${name}
    EXPORT_NAME ${name}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${LMK_INCLUDE_DIR}>
    $<BUILD_INTERFACE:${LMK_GENERATED_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_17)
  lmk_warnings(${target})
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  if(ARG_INTERNAL)
    return()
  endif()
  install(TARGETS ${target} EXPORT lmkTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # The module's headers and those of its subfolders (search/metrics/), but for detail/ and
  # internal/, which are lmk's own.
  file(GLOB_RECURSE headers RELATIVE "${CMAKE_CURRENT_SOURCE_DIR}" "${CMAKE_CURRENT_SOURCE_DIR}/*.h")
  foreach(header IN LISTS headers)
    if(header MATCHES "(^|/)(detail|internal)/")
      continue()
    endif()
    get_filename_component(folder "${header}" DIRECTORY)
    install(FILES "${header}" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lmk/${name}/${folder})
  endforeach()
endfunction()
