# mapfuse_lean_runtime(<target>): start-up cost of the tools a batch runs once per drive.
#
# scripts/crowd.mk runs georef once per drive (and tile / stitch / info once per batch or tile);
# on this class of VM a process start costs more than georef's work on one drive: page faults
# while the loader maps and relocates libstdc++, libgomp, libgfortran, ... and the position-
# independent executable's own relocations. For executables that load no C++ shared library
# (no OpenCV, PCL, pugixml: a second, shared libstdc++ next to a static one would break),
# MAPFUSE_LEAN_RUNTIME (default ON, GCC only) links the C++, OpenMP and Fortran runtimes
# statically and the executable at a fixed address (-no-pie). Measured on `georef --help`:
# 10.4 -> 5.8 ms, 243 -> 164 page faults. Only libc, libm, METIS, libunwind and liblzma (C
# libraries) stay shared; tests/e2e/lean_runtime.sh checks that no libstdc++.so is loaded.
option(MAPFUSE_LEAN_RUNTIME "Static C++/OpenMP/Fortran runtimes and no PIE for the per-drive tools" ON)

function(mapfuse_lean_runtime target)
  if(NOT MAPFUSE_LEAN_RUNTIME OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    return()
  endif()
  set(archives "")
  foreach(name gomp gfortran quadmath)
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=lib${name}.a
                    OUTPUT_VARIABLE path OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT IS_ABSOLUTE "${path}" OR NOT EXISTS "${path}")
      message(STATUS "mapfuse: lib${name}.a not found, ${target} keeps the shared runtimes")
      return()
    endif()
    list(APPEND archives "${path}")
  endforeach()
  # libgomp.a right after libmapfuse.a, so that it resolves the OpenMP symbols before the shared
  # libgomp further down the link line (dropped then by --as-needed); the Fortran runtime goes
  # where mapfuse_solver puts it, after the static LAPACK that needs it.
  list(GET archives 0 gomp)
  list(REMOVE_AT archives 0)
  target_link_libraries(${target} PRIVATE ${gomp})
  set_property(TARGET ${target} PROPERTY MAPFUSE_STATIC_FORTRAN "${archives}")
  target_link_options(${target} PRIVATE -static-libstdc++ -static-libgcc -no-pie)
  set_property(GLOBAL APPEND PROPERTY MAPFUSE_LEAN_TOOLS ${target})  # for tests/e2e/lean_runtime.sh
endfunction()
