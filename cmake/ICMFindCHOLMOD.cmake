# Finds SuiteSparse's CHOLMOD and defines the imported target `ICM::CHOLMOD`: the CHOLMOD
# headers and libraries, and the compile definition `ICM_HAS_CHOLMOD` that turns on ICM's
# CHOLMOD solvers (`include/ICM/curvature/Dynamic_laplacian.h`). Sets `ICM_CHOLMOD_FOUND`.
#
# ICM's own CMakeLists.txt includes it at configure time, and the installed ICMConfig.cmake
# includes it again on the user's machine, so the libraries are those found there, not the
# paths of the machine ICM was configured on. SuiteSparse 5 (Debian 12) ships no CMake
# package, hence the plain search.
if(NOT TARGET ICM::CHOLMOD)
  find_path(ICM_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(ICM_CHOLMOD_LIBRARY cholmod)
  find_library(ICM_SUITESPARSECONFIG_LIBRARY suitesparseconfig)
  mark_as_advanced(ICM_CHOLMOD_INCLUDE_DIR ICM_CHOLMOD_LIBRARY ICM_SUITESPARSECONFIG_LIBRARY)
  if(ICM_CHOLMOD_INCLUDE_DIR AND ICM_CHOLMOD_LIBRARY)
    set(_icm_cholmod_libraries "${ICM_CHOLMOD_LIBRARY}")
    if(ICM_SUITESPARSECONFIG_LIBRARY)
      list(APPEND _icm_cholmod_libraries "${ICM_SUITESPARSECONFIG_LIBRARY}")
    endif()
    add_library(ICM::CHOLMOD INTERFACE IMPORTED)
    set_target_properties(ICM::CHOLMOD PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${ICM_CHOLMOD_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_icm_cholmod_libraries}"
      INTERFACE_COMPILE_DEFINITIONS ICM_HAS_CHOLMOD)
    unset(_icm_cholmod_libraries)
  endif()
endif()
if(TARGET ICM::CHOLMOD)
  set(ICM_CHOLMOD_FOUND TRUE)
else()
  set(ICM_CHOLMOD_FOUND FALSE)
endif()
