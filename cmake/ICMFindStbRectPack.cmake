# Finds stb_rect_pack.h (Debian: libstb-dev, in /usr/include/stb/) and defines the imported
# target `ICM::stb_rect_pack`: its include directory and the compile definition
# `ICM_HAS_STB_RECT_PACK`, which gives the atlas mode its skyline packer
# (`include/ICM/layout/Atlas_packing.h`). Sets `ICM_STB_RECT_PACK_FOUND`. Header only: ICM
# compiles stb's implementation itself, nothing is linked.
#
# Included at configure time by ICM's CMakeLists.txt and again by the installed
# ICMConfig.cmake, so that the header is the one of the machine that uses the package.
if(NOT TARGET ICM::stb_rect_pack)
  find_path(ICM_STB_RECT_PACK_INCLUDE_DIR stb_rect_pack.h PATH_SUFFIXES stb)
  mark_as_advanced(ICM_STB_RECT_PACK_INCLUDE_DIR)
  if(ICM_STB_RECT_PACK_INCLUDE_DIR)
    add_library(ICM::stb_rect_pack INTERFACE IMPORTED)
    set_target_properties(ICM::stb_rect_pack PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${ICM_STB_RECT_PACK_INCLUDE_DIR}"
      INTERFACE_COMPILE_DEFINITIONS ICM_HAS_STB_RECT_PACK)
  endif()
endif()
if(TARGET ICM::stb_rect_pack)
  set(ICM_STB_RECT_PACK_FOUND TRUE)
else()
  set(ICM_STB_RECT_PACK_FOUND FALSE)
endif()
