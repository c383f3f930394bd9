// Copyright (c) the ICM authors.
//
// Reading STL, ASCII or binary, into a polygon soup, one point per corner (the corners at
// one point are merged afterwards, in `read_polygon_soup()`). Binary STL is told from ASCII
// by its size, since a binary header may start with "solid" too.

#ifndef ICM_IO_READ_STL_H
#define ICM_IO_READ_STL_H

#include <ICM/IO/Soup_reading.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

inline void read_binary_stl(std::string_view data, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  std::uint32_t count = 0;
  for(int i = 0; i < 4; ++i)
    count |= static_cast<std::uint32_t>(static_cast<unsigned char>(data[80 + i])) << (8 * i);
  const std::uint64_t needed = 84 + 50 * std::uint64_t(count);
  if(needed != data.size())
    refuse("binary STL: the header announces " + std::to_string(count) + " triangles, which take " +
           std::to_string(needed) + " bytes, but the file has " + std::to_string(data.size()) +
           (needed > data.size() ? " (truncated, or not an STL file)" : " (trailing bytes, or not an STL file)"));
  if(count > limits.max_polygons || std::uint64_t(count) * 3 > limits.max_points)
    refuse("binary STL: more triangles than this reader takes");
  soup.points.reserve(3 * std::size_t(count));
  soup.polygons.reserve(count);
  for(std::size_t t = 0; t < count; ++t)
  {
    const char* record = data.data() + 84 + 50 * t;
    std::vector<std::size_t> triangle;
    for(int corner = 0; corner < 3; ++corner)
    {
      float x[3];
      for(int k = 0; k < 3; ++k)
      {
        unsigned char b[4];
        std::memcpy(b, record + 12 + 12 * corner + 4 * k, 4);
        const std::uint32_t bits =
          std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
        std::memcpy(&x[k], &bits, 4);
        if(!std::isfinite(x[k]))
          refuse("binary STL: triangle " + std::to_string(t) + " has a non-finite coordinate");
      }
      triangle.push_back(soup.points.size());
      soup.points.emplace_back(x[0], x[1], x[2]);
    }
    soup.polygons.push_back(std::move(triangle));
    soup.polygon_lines.push_back(0);
  }
}

inline void read_ascii_stl(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  std::string_view line;
  enum class State
  {
    Solid,
    Facet,
    Loop,
    Vertex,
    Endloop,
    Endfacet,
    Done
  } state = State::Solid;
  std::vector<std::size_t> triangle;
  std::size_t facet_line = 0;
  auto expect = [&](std::string_view found, const char* wanted) {
    refuse_at(lines.number(), "expected '" + std::string(wanted) + "', found " + quoted(found));
  };
  while(state != State::Done && lines.next(line))
  {
    Tokens tokens(line);
    std::string_view word;
    if(!tokens.next(word))
      continue;
    switch(state)
    {
    case State::Solid:
      if(word != "solid")
        expect(word, "solid");
      state = State::Facet;
      break;
    case State::Facet:
      if(word == "endsolid")
      {
        state = State::Done;
        break;
      }
      if(word != "facet")
        expect(word, "facet");
      if(soup.polygons.size() >= limits.max_polygons)
        refuse_at(lines.number(), "more facets than this reader takes");
      facet_line = lines.number();
      state = State::Loop;
      break;
    case State::Loop:
      if(word != "outer")
        expect(word, "outer loop");
      state = State::Vertex;
      break;
    case State::Vertex:
      if(word == "endloop")
      {
        if(triangle.size() != 3)
          refuse_at(facet_line,
                    "the facet has " + std::to_string(triangle.size()) + " vertices (STL facets are triangles)");
        soup.polygons.push_back(triangle);
        soup.polygon_lines.push_back(facet_line);
        triangle.clear();
        state = State::Endfacet;
        break;
      }
      if(word != "vertex")
        expect(word, "vertex");
      if(triangle.size() == 3)
        refuse_at(facet_line, "the facet has more than 3 vertices (STL facets are triangles)");
      {
        std::array<double, 3> x{};
        std::size_t n = 0;
        for(std::string_view t; tokens.next(t); ++n)
          if(n < 3)
            x[n] = coordinate(t, lines.number(), soup.points.size());
        if(n != 3)
          refuse_at(lines.number(), "a vertex line has " + std::to_string(n) + " numbers, not 3");
        triangle.push_back(soup.points.size());
        soup.points.emplace_back(x[0], x[1], x[2]);
      }
      break;
    case State::Endfacet:
      if(word != "endfacet")
        expect(word, "endfacet");
      state = State::Facet;
      break;
    default:
      break;
    }
  }
  if(state != State::Done)
    refuse("the file ends inside the solid (no 'endsolid'; truncated?)");
}

/// Binary when the size matches the triangle count of the binary header (a binary file may
/// start with "solid" too), ASCII when it starts with "solid", else binary (and refused if
/// its count does not match).
inline void read_stl(std::string_view data, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  const std::size_t first = data.find_first_not_of(" \t\r\n");
  const bool starts_solid = first != std::string_view::npos && data.substr(first, 5) == "solid";
  if(data.size() >= 84)
  {
    std::uint32_t count = 0;
    for(int i = 0; i < 4; ++i)
      count |= static_cast<std::uint32_t>(static_cast<unsigned char>(data[80 + i])) << (8 * i);
    if(84 + 50 * std::uint64_t(count) == data.size() || !starts_solid)
      return read_binary_stl(data, soup, limits);
  }
  if(!starts_solid)
    refuse("the file is too short for a binary STL (84 bytes of header) and does not start with 'solid'");
  try
  {
    read_ascii_stl(data, soup, limits);
  }
  catch(const Soup_error& ascii)
  {
    // A binary file whose header starts with "solid": say what is wrong either way.
    const bool looks_binary = std::any_of(data.begin(), data.end(), [](char c) { return c == '\0'; });
    if(!looks_binary || data.size() < 84)
      throw;
    soup.clear();
    try
    {
      read_binary_stl(data, soup, limits);
    }
    catch(const Soup_error& binary)
    {
      refuse("neither an ASCII STL (" + ascii.message + ") nor a binary one (" + binary.message + ")");
    }
  }
}

/// The format the content itself announces, when it announces one: a PLY or OFF keyword, or

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_READ_STL_H
