# Finds stb_image_write.h and stb_easy_font.h with the library that carries stb's
# implementations (Debian: libstb-dev, headers in /usr/include/stb/, libstb.so), and defines
# the imported target `ICM::stb_image_write`: the include directory, the library and the
# compile definition `ICM_HAS_STB_IMAGE_WRITE`, which turns on the PNG pictures
# (`include/ICM/IO/write_uv_png.h`). Sets `ICM_STB_IMAGE_WRITE_FOUND`. The library is needed:
# ICM is header only and has no translation unit of its own to compile stb's implementation
# in, and Debian's tinygltf links the same library.
#
# Included at configure time by ICM's CMakeLists.txt and again by the installed
# ICMConfig.cmake, so that the library is the one of the machine that uses the package.
if(NOT TARGET ICM::stb_image_write)
  find_path(ICM_STB_IMAGE_WRITE_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
  find_path(ICM_STB_EASY_FONT_INCLUDE_DIR stb_easy_font.h PATH_SUFFIXES stb)
  find_library(ICM_STB_LIBRARY stb)
  mark_as_advanced(ICM_STB_IMAGE_WRITE_INCLUDE_DIR ICM_STB_EASY_FONT_INCLUDE_DIR ICM_STB_LIBRARY)
  if(ICM_STB_IMAGE_WRITE_INCLUDE_DIR AND ICM_STB_EASY_FONT_INCLUDE_DIR AND ICM_STB_LIBRARY)
    add_library(ICM::stb_image_write INTERFACE IMPORTED)
    set_target_properties(ICM::stb_image_write PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${ICM_STB_IMAGE_WRITE_INCLUDE_DIR};${ICM_STB_EASY_FONT_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${ICM_STB_LIBRARY}"
      INTERFACE_COMPILE_DEFINITIONS ICM_HAS_STB_IMAGE_WRITE)
  endif()
endif()
if(TARGET ICM::stb_image_write)
  set(ICM_STB_IMAGE_WRITE_FOUND TRUE)
else()
  set(ICM_STB_IMAGE_WRITE_FOUND FALSE)
endif()
