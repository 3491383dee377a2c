# SPDX-License-Identifier: BSD-3-Clause
# Sanitizer and fuzzing builds (issue #17, docs/reliability.md). Each applies to every target of
# the build, lmk's libraries included, so that a finding is reported where it happens:
#   LMK_SANITIZE  AddressSanitizer + UndefinedBehaviorSanitizer; any finding aborts the test.
#   LMK_TSAN      ThreadSanitizer, for the threaded search and evaluation tests.
#   LMK_FUZZ      libFuzzer coverage on all code and libFuzzer binaries for tests/fuzz (clang);
#                 implies LMK_SANITIZE, as libFuzzer finds memory errors only through ASan.
option(LMK_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(LMK_TSAN "Build with ThreadSanitizer" OFF)
option(LMK_FUZZ "Build the libFuzzer targets (clang only); implies LMK_SANITIZE" OFF)

if(LMK_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "LMK_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14")
  endif()
  set(LMK_SANITIZE ON)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(LMK_SANITIZE AND LMK_TSAN)
  message(FATAL_ERROR "LMK_TSAN cannot be combined with LMK_SANITIZE or LMK_FUZZ")
endif()

if(LMK_SANITIZE)
  # -fno-sanitize-recover: an undefined-behaviour report fails the run instead of scrolling by.
  set(lmk_sanitizer_flags -fsanitize=address,undefined -fno-sanitize-recover=undefined
                          -fno-omit-frame-pointer)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    list(APPEND lmk_sanitizer_flags
         -fsanitize-ignorelist=${PROJECT_SOURCE_DIR}/cmake/sanitizer-ignorelist.txt)
  endif()
elseif(LMK_TSAN)
  set(lmk_sanitizer_flags -fsanitize=thread -fno-omit-frame-pointer)
endif()
if(lmk_sanitizer_flags)
  # A sanitizer's report needs file and line in its stack traces, which clang's line tables give
  # in a fraction of full debug information's compile and link time (issue #62: the sanitizer
  # build was a third of CI). After the build type's -g, so it wins.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    add_compile_options(${lmk_sanitizer_flags} -gline-tables-only)
  else()
    add_compile_options(${lmk_sanitizer_flags} -g)
  endif()
  add_link_options(${lmk_sanitizer_flags})
endif()
