// Copyright (c) the ICM authors.
//
// Reading Wavefront OBJ into a polygon soup: `v` and `f` (or `fo`) statements, OBJ's
// negative (relative) and forward indices; every other statement carries nothing a
// parameterization uses and is skipped.

#ifndef ICM_IO_READ_OBJ_H
#define ICM_IO_READ_OBJ_H

#include <ICM/IO/Soup_reading.h>

#include <array>
#include <cctype>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

/// The vertex of one OBJ face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`; negative indices
/// count back from the last vertex read so far. Positive indices are checked once the
/// whole file is read (a face may name a vertex defined after it).
inline std::size_t obj_corner(std::string_view token, std::size_t vertices_so_far, std::size_t line, std::size_t face)
{
  const std::string_view v = token.substr(0, token.find('/'));
  long long index = 0;
  if(!parse_integer(v, index))
    refuse_at(line, "face " + std::to_string(face) + ": " + quoted(token) + " is not a vertex reference");
  if(index == 0)
    refuse_at(line, "face " + std::to_string(face) + ": vertex index 0 (OBJ indices start at 1)");
  if(index < 0)
  {
    const unsigned long long back = static_cast<unsigned long long>(-(index + 1)) + 1;
    if(back > vertices_so_far)
      refuse_at(line, "face " + std::to_string(face) + ": relative vertex index " + std::to_string(index) +
                        " reaches before the first vertex (" + std::to_string(vertices_so_far) + " vertices so far)");
    return vertices_so_far - static_cast<std::size_t>(back);
  }
  return static_cast<std::size_t>(index - 1);
}

inline void read_obj(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  std::string_view line;
  while(next_content_line(lines, line))
  {
    Tokens tokens(line);
    std::string_view keyword;
    tokens.next(keyword); // a content line has a first token
    if(keyword == "v")
    {
      const std::size_t v = soup.points.size();
      if(v >= limits.max_points)
        refuse_at(lines.number(), "more than " + std::to_string(limits.max_points) + " vertices");
      std::array<double, 3> x{};
      std::size_t n = 0;
      for(std::string_view t; tokens.next(t); ++n)
      {
        if(n < 3)
          x[n] = coordinate(t, lines.number(), v);
        else
        {
          // A weight w, or an (r, g, b) colour as many tools write them.
          double ignored = 0;
          if(!parse_double(t, ignored))
            refuse_at(lines.number(), "vertex " + std::to_string(v) + ": " + quoted(t) + " is not a number");
        }
      }
      if(n < 3 || n > 7)
        refuse_at(lines.number(), "vertex " + std::to_string(v) + " has " + std::to_string(n) +
                                    " numbers (a 'v' line has x y z, optionally w or r g b)");
      soup.points.emplace_back(x[0], x[1], x[2]);
    }
    else if(keyword == "f" || keyword == "fo")
    {
      const std::size_t f = soup.polygons.size();
      if(f >= limits.max_polygons)
        refuse_at(lines.number(), "more than " + std::to_string(limits.max_polygons) + " faces");
      std::vector<std::size_t> polygon;
      for(std::string_view t; tokens.next(t);)
        polygon.push_back(obj_corner(t, soup.points.size(), lines.number(), f));
      if(polygon.size() < 3)
        refuse_at(lines.number(), "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) +
                                    " corner(s); a face needs at least 3");
      soup.polygons.push_back(std::move(polygon));
      soup.polygon_lines.push_back(lines.number());
    }
    else if(!std::isalpha(static_cast<unsigned char>(keyword.front())))
      refuse_at(lines.number(), quoted(keyword) + " does not start an OBJ statement");
    // Any other statement (vt, vn, g, o, s, usemtl, mtllib, l, ...) carries nothing we use.
  }
  // Positive indices may name a vertex defined after the face: checked now, 1-based as written.
  for(std::size_t f = 0; f < soup.polygons.size(); ++f)
    for(std::size_t i : soup.polygons[f])
      if(i >= soup.points.size())
        refuse_at(soup.polygon_lines[f], "face " + std::to_string(f) + ": vertex index " + std::to_string(i + 1) +
                                           " is out of range (the file has " + std::to_string(soup.points.size()) +
                                           " vertices)");
}

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_READ_OBJ_H
