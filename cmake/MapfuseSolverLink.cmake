# mapfuse_solver: how the library links Ceres and GeographicLib.
#
# Debian's Ceres is a static library whose dependencies (SuiteSparse, CXSparse, LAPACK/ATLAS,
# glog, gflags) are shared: a tool that solves one small problem per process (georef runs once
# per drive in scripts/crowd.mk) then spends most of its time loading 27 shared libraries
# (page faults on this class of VM: 15.7 ms per georef run, 11.7 ms with these linked in; the
# 50-drive Karlsruhe chain through crowd.mk 1.60 -> 1.33 s). With MAPFUSE_STATIC_SOLVER (default
# ON) the static archives that libceres-dev's own dependencies install are linked instead, as
# one rescanned group; METIS (no static archive in Debian), libunwind and gfortran stay shared. When an archive is missing the imported Ceres::ceres target is used as before.
option(MAPFUSE_STATIC_SOLVER "Link Ceres' solver dependencies and GeographicLib statically" ON)

add_library(mapfuse_solver INTERFACE)

set(_mapfuse_static_ok OFF)
if(MAPFUSE_STATIC_SOLVER)
  get_target_property(_ceres_archive Ceres::ceres IMPORTED_LOCATION_RELEASE)
  set(_archives "${_ceres_archive}")
  set(_multiarch "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}")
  foreach(_name glog gflags spqr cholmod amd camd ccolamd colamd suitesparseconfig cxsparse
                atlas/liblapack f77blas atlas/libblas atlas GeographicLib)
    if(_name MATCHES "^atlas/")
      set(_path "${_multiarch}/${_name}.a")  # ATLAS' reference LAPACK / BLAS front ends
    else()
      set(_path "${_multiarch}/lib${_name}.a")
    endif()
    if(NOT EXISTS "${_path}")
      message(STATUS "mapfuse: ${_path} not found, linking Ceres' dependencies as shared")
      set(_archives "")
      break()
    endif()
    list(APPEND _archives "${_path}")
  endforeach()
  # runtime libraries only (no -dev symlink): found by their versioned names
  find_library(_metis NAMES libmetis.so.5 metis)
  find_library(_unwind NAMES libunwind.so.8 unwind)
  find_library(_gfortran NAMES libgfortran.so.5 gfortran)
  if(_archives AND EXISTS "${_ceres_archive}" AND _metis AND _unwind AND _gfortran)
    set(_mapfuse_static_ok ON)
  elseif(_archives)
    message(STATUS "mapfuse: METIS, libunwind or libgfortran not found (${_metis} ${_unwind} "
                   "${_gfortran}), linking Ceres' dependencies as shared")
  endif()
endif()

if(_mapfuse_static_ok)
  message(STATUS "mapfuse: Ceres' dependencies and GeographicLib linked statically")
  string(REPLACE ";" "," _group "${_archives}")
  target_include_directories(mapfuse_solver INTERFACE
    $<TARGET_PROPERTY:Ceres::ceres,INTERFACE_INCLUDE_DIRECTORIES> ${GeographicLib_INCLUDE_DIRS})
  # gfortran: the consuming executable's MAPFUSE_STATIC_FORTRAN archives when it sets them
  # (cmake/MapfuseLeanRuntime.cmake), after the LAPACK / BLAS archives that need them.
  set(_fortran "$<IF:$<BOOL:$<TARGET_PROPERTY:MAPFUSE_STATIC_FORTRAN>>,$<TARGET_PROPERTY:MAPFUSE_STATIC_FORTRAN>,${_gfortran}>")
  target_link_libraries(mapfuse_solver INTERFACE
    "$<LINK_GROUP:RESCAN,${_group}>" ${_metis} ${_unwind} "${_fortran}"
    Threads::Threads Eigen3::Eigen)
else()
  target_include_directories(mapfuse_solver INTERFACE ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(mapfuse_solver INTERFACE Ceres::ceres ${GeographicLib_LIBRARIES})
endif()
