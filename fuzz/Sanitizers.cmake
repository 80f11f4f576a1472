# Compiler flags of the sanitizer build (MAPFUSE_SANITIZE=ON, included by the root CMakeLists
# before any target): everything built, library, tools, tests and fuzz targets, runs under
# AddressSanitizer and UndefinedBehaviorSanitizer, and undefined behaviour stops the process
# (-fno-sanitize-recover) so that a test or a fuzz run fails on it. With MAPFUSE_FUZZ=ON (clang
# only) the code also carries libFuzzer's coverage instrumentation; without libFuzzer linked the
# sanitizer runtime's no-op hooks take it, so the unit tests of the same build run as usual.
if(MAPFUSE_FUZZ AND NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "MAPFUSE_FUZZ needs clang (libFuzzer): configure with "
                      "-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang")
endif()
set(_mapfuse_sanitize -fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
if(MAPFUSE_FUZZ)
  list(APPEND _mapfuse_sanitize -fsanitize=fuzzer-no-link)
endif()
add_compile_options(${_mapfuse_sanitize})
add_link_options(-fsanitize=address,undefined)
