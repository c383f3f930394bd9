// Copyright (c) the ICM authors.
//
// Reading untrusted mesh files (OFF and its variants, OBJ, PLY ASCII and binary, STL ASCII
// and binary) into a polygon soup, safely: nothing the file says is trusted before it is
// checked. Counts in a header are compared with the bytes that follow before anything is
// allocated for them, every index is range checked (OBJ's negative, relative indices
// included), every coordinate must be a finite double, a face cannot have more corners than
// the file has vertices nor name one vertex twice. Every refusal names the line (text
// formats) or the element (binary ones) and what is wrong with it.
//
// Why not CGAL's readers: CGAL 5.5's OFF, OBJ and PLY readers trust the file (a header count
// of 2e9 allocates 48 GB, an index out of range writes out of bounds in
// Generic_facegraph_builder, STOFF/COFF scanning overflows) and answer every malformed file
// with one boolean. The soup built here goes on to CGAL's Polygon_mesh_processing
// (read_triangle_mesh.h), which repairs what users expect to see repaired.

#ifndef ICM_IO_READ_POLYGON_SOUP_H
#define ICM_IO_READ_POLYGON_SOUP_H

#include <ICM/IO/Soup_reading.h>
#include <ICM/IO/read_obj.h>
#include <ICM/IO/read_off.h>
#include <ICM/IO/read_ply.h>
#include <ICM/IO/read_stl.h>

#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace ICM {
namespace internal {
namespace reading {

/// The format the content itself announces, when it announces one: a PLY or OFF keyword, or
/// an STL "solid" line. Used to name a file with the wrong extension.
inline std::optional<Mesh_file_format> format_from_content(std::string_view data)
{
  Text_lines lines(data);
  std::string_view line;
  if(!next_content_line(lines, line))
    return std::nullopt;
  Tokens tokens(line);
  std::string_view word;
  tokens.next(word); // a content line has a first token
  if(word == "ply")
    return Mesh_file_format::Ply;
  if(word == "solid")
    return Mesh_file_format::Stl;
  if(word.size() >= 3 && word.substr(word.size() - 3) == "OFF" && word.size() <= 9)
    return Mesh_file_format::Off;
  return std::nullopt;
}

} // namespace reading
} // namespace internal

namespace IO {

/// Reads a polygon soup from `data`, the content of a file in `format`. Returns false, with
/// `error` naming the line or element and what is wrong, on anything the file does not say
/// correctly; `soup` is then cleared. Never allocates more than a small multiple of the
/// size of `data`, whatever the file announces.
///
/// Checked: header counts against the bytes that follow; vertex indices in range (OBJ's
/// negative ones relative to the vertices read so far); coordinates finite; every face with
/// 3 or more corners, no more than the file has vertices, none named twice. STL corners at
/// the same point are merged into one vertex (`merge_duplicate_points_in_polygon_soup`), in
/// the order they first appear.
inline bool read_polygon_soup(std::string_view data, Mesh_file_format format, Polygon_soup& soup, std::string& error,
                              const Soup_reading_limits& limits = Soup_reading_limits())
{
  soup.clear();
  namespace internal = ICM::internal::reading;
  try
  {
    // A UTF-8 byte-order mark, which some editors put at the start of a text file, is not
    // content. (A binary STL's 80-byte header is free text, so it is left alone.)
    constexpr std::string_view byte_order_mark = "\xEF\xBB\xBF";
    if(format != Mesh_file_format::Stl && data.substr(0, byte_order_mark.size()) == byte_order_mark)
      data.remove_prefix(byte_order_mark.size());
    if(data.empty())
      internal::refuse("the file is empty");
    // A content that announces another format is named, rather than misread as this one.
    const std::optional<Mesh_file_format> announced = internal::format_from_content(data);
    if(announced && *announced != format && *announced != Mesh_file_format::Stl)
      internal::refuse(std::string("the content looks like ") + format_name(*announced) + ", not " +
                       format_name(format) + " as the file name says");
    switch(format)
    {
    case Mesh_file_format::Off:
      internal::read_off(data, soup, limits);
      break;
    case Mesh_file_format::Obj:
      internal::read_obj(data, soup, limits);
      break;
    case Mesh_file_format::Ply:
      internal::read_ply(data, soup, limits);
      break;
    case Mesh_file_format::Stl:
      internal::read_stl(data, soup, limits);
      break;
    }
    for(std::size_t p = 0; p < soup.polygons.size(); ++p)
      internal::check_polygon(soup.polygons[p], soup.points.size(), soup, p);
    if(format == Mesh_file_format::Stl)
    {
      CGAL::Polygon_mesh_processing::merge_duplicate_points_in_polygon_soup(soup.points, soup.polygons);
      for(std::size_t p = 0; p < soup.polygons.size(); ++p)
        internal::check_polygon(soup.polygons[p], soup.points.size(), soup, p);
    }
  }
  catch(const internal::Soup_error& e)
  {
    soup.clear();
    error = e.message;
    return false;
  }
  error.clear();
  return true;
}

/// Reads the mesh file `path` as a polygon soup, in the format its extension names (.off,
/// .obj, .ply, .stl, any case). Messages start with the file's name. See the overload on
/// the file's content for what is checked.
inline bool read_polygon_soup(const std::string& path, Polygon_soup& soup, std::string& error,
                              const Soup_reading_limits& limits = Soup_reading_limits())
{
  soup.clear();
  const std::string name = "'" + path + "'";
  const std::optional<Mesh_file_format> format = format_from_extension(path);
  if(!format)
  {
    error = name + ": unknown extension '" + std::filesystem::path(path).extension().string() +
            "' (reads .off, .obj, .ply and .stl)";
    return false;
  }
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if(ec || !std::filesystem::exists(status))
  {
    error = name + ": no such file";
    return false;
  }
  if(!std::filesystem::is_regular_file(status))
  {
    error = name + ": not a regular file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if(!in || ec)
  {
    error = name + ": cannot open the file";
    return false;
  }
  std::string data;
  try
  {
    data.resize(static_cast<std::size_t>(size));
  }
  catch(const std::exception&)
  {
    error = name + ": the file (" + std::to_string(size) + " bytes) does not fit in memory";
    return false;
  }
  if(!in.read(data.data(), static_cast<std::streamsize>(data.size())))
  {
    error = name + ": cannot read the file";
    return false;
  }
  if(!read_polygon_soup(std::string_view(data), *format, soup, error, limits))
  {
    error = name + ": " + error;
    return false;
  }
  return true;
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_READ_POLYGON_SOUP_H