# Finds tinygltf and defines the imported target `ICM::TinyGLTF`: its header and library, and
# the compile definition `ICM_HAS_TINYGLTF` that turns on ICM's glTF output
# (`include/ICM/IO/write_uv_gltf.h`). Sets `ICM_TINYGLTF_FOUND`.
#
# tinygltf is a header whose implementation one translation unit compiles; Debian
# (libtinygltf-dev) ships that implementation as a shared library with a CMake package
# (TinyGLTF::TinyGLTF), which is used when present. Elsewhere the header and a library named
# tinygltf are searched for. A header alone is not enough: ICM is header only and has no
# translation unit of its own to compile the implementation in.
#
# ICM's own CMakeLists.txt includes it at configure time, and the installed ICMConfig.cmake
# includes it again on the user's machine.
if(NOT TARGET ICM::TinyGLTF)
  find_package(TinyGLTF CONFIG QUIET)
  if(TARGET TinyGLTF::TinyGLTF)
    find_path(ICM_TINYGLTF_INCLUDE_DIR tiny_gltf.h)
    set(_icm_tinygltf_library TinyGLTF::TinyGLTF)
  else()
    find_path(ICM_TINYGLTF_INCLUDE_DIR tiny_gltf.h)
    find_library(ICM_TINYGLTF_LIBRARY tinygltf)
    mark_as_advanced(ICM_TINYGLTF_LIBRARY)
    set(_icm_tinygltf_library "${ICM_TINYGLTF_LIBRARY}")
  endif()
  mark_as_advanced(ICM_TINYGLTF_INCLUDE_DIR)
  if(ICM_TINYGLTF_INCLUDE_DIR AND _icm_tinygltf_library)
    add_library(ICM::TinyGLTF INTERFACE IMPORTED)
    set_target_properties(ICM::TinyGLTF PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${ICM_TINYGLTF_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${_icm_tinygltf_library}"
      INTERFACE_COMPILE_DEFINITIONS ICM_HAS_TINYGLTF)
  endif()
  unset(_icm_tinygltf_library)
endif()
if(TARGET ICM::TinyGLTF)
  set(ICM_TINYGLTF_FOUND TRUE)
else()
  set(ICM_TINYGLTF_FOUND FALSE)
endif()
