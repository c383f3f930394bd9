// Copyright (c) the ICM authors.
//
// Reading OFF and its variants ([ST][C][N][4]OFF, the keyword optional) into a polygon soup:
// the counts of the header are checked against the bytes that follow before anything is
// allocated, every vertex line against the numbers its variant has, every face against the
// vertices the header announced.

#ifndef ICM_IO_READ_OFF_H
#define ICM_IO_READ_OFF_H

#include <ICM/IO/Soup_reading.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

/// What the prefixes of an OFF keyword add to each vertex line.
struct Off_layout
{
  bool texture = false, colour = false, normal = false, homogeneous = false;
  std::size_t min_numbers() const
  {
    return (homogeneous ? 4 : 3) + (normal ? 3 : 0) + (texture ? 2 : 0) + (colour ? 1 : 0);
  }
  std::size_t max_numbers() const
  {
    return (homogeneous ? 4 : 3) + (normal ? 3 : 0) + (texture ? 2 : 0) + (colour ? 4 : 0);
  }
};

/// Reads `[ST][C][N][4][n]OFF`; refuses nOFF (any dimension) and an unknown keyword.
inline bool parse_off_keyword(std::string_view word, Off_layout& layout, std::size_t line)
{
  if(word.size() < 3 || word.substr(word.size() - 3) != "OFF")
    return false;
  std::string_view prefix = word.substr(0, word.size() - 3);
  auto take = [&](std::string_view p) {
    if(prefix.substr(0, p.size()) != p)
      return false;
    prefix.remove_prefix(p.size());
    return true;
  };
  layout.texture = take("ST");
  layout.colour = take("C");
  layout.normal = take("N");
  layout.homogeneous = take("4");
  if(take("n"))
    refuse_at(line, "nOFF (vertices of a dimension given in the file) is not supported");
  if(!prefix.empty())
    refuse_at(line, "unknown OFF keyword " + quoted(word) + " (known: [ST][C][N][4]OFF)");
  return true;
}

/// What the header of an OFF file says: its variant and its counts.
struct Off_header
{
  Off_layout layout;
  std::size_t vertices = 0, faces = 0;
};

/// The counts of the header, as tokens: on the keyword's line, or on the next content line.
inline std::vector<std::string_view> off_count_tokens(Text_lines& lines, std::string_view& line, Off_layout& layout)
{
  if(!next_content_line(lines, line))
    refuse("the file has no OFF header");
  Tokens tokens(line);
  std::string_view word;
  tokens.next(word);
  std::vector<std::string_view> counts;
  const bool has_keyword = parse_off_keyword(word, layout, lines.number());
  if(!has_keyword)
  {
    // Geomview allows the keyword to be left out; then the first line holds the counts.
    long long unused = 0;
    if(!parse_integer(word, unused))
      refuse_at(lines.number(), "the file does not start with an OFF keyword (found " + quoted(word) + ")");
    counts.push_back(word);
  }
  for(std::string_view t; tokens.next(t);)
    counts.push_back(t);
  if(!counts.empty() && counts[0] == "BINARY")
    refuse_at(lines.number(), "binary OFF is not supported");
  if(counts.empty())
  {
    if(!next_content_line(lines, line))
      refuse("the file ends after its OFF keyword (no vertex and face counts)");
    Tokens count_tokens(line);
    for(std::string_view t; count_tokens.next(t);)
      counts.push_back(t);
  }
  return counts;
}

/// Reads the keyword and the counts, and refuses counts that what follows cannot hold.
inline Off_header read_off_header(Text_lines& lines, const Soup_reading_limits& limits)
{
  std::string_view line;
  Off_header header;
  const std::vector<std::string_view> counts = off_count_tokens(lines, line, header.layout);
  const std::size_t count_line = lines.number();
  if(counts.size() < 2 || counts.size() > 3)
    refuse_at(count_line,
              "expected the counts of vertices, faces and edges, found " + std::to_string(counts.size()) + " value(s)");
  header.vertices = header_count(counts[0], count_line, "vertices", limits.max_points);
  header.faces = header_count(counts[1], count_line, "faces", limits.max_polygons);
  if(counts.size() == 3)
    header_count(counts[2], count_line, "edges", std::numeric_limits<std::size_t>::max());
  // Each vertex line has at least its numbers and a separator each, each face line a count
  // and a separator (what else it needs is checked as it is read).
  const std::size_t vertex_bytes = 2 * header.layout.min_numbers();
  check_fits(header.vertices, vertex_bytes, lines.remaining_bytes(), count_line, "vertices");
  check_fits(header.faces, 2,
             lines.remaining_bytes() - std::min(lines.remaining_bytes(), header.vertices * vertex_bytes), count_line,
             "faces");
  return header;
}

/// One vertex line: its point, the numbers after it (normal, texture, colour) checked and dropped.
inline void read_off_vertex(std::string_view line, std::size_t line_number, std::size_t v, const Off_layout& layout,
                            Polygon_soup& soup)
{
  Tokens numbers(line);
  const std::size_t n = numbers.count();
  if(n < layout.min_numbers() || n > layout.max_numbers())
    refuse_at(
      line_number,
      "vertex " + std::to_string(v) + " has " + std::to_string(n) + " numbers; this OFF variant has " +
        std::to_string(layout.min_numbers()) +
        (layout.max_numbers() > layout.min_numbers() ? " to " + std::to_string(layout.max_numbers()) : std::string()) +
        " per vertex line");
  std::array<double, 4> x{0, 0, 0, 1};
  std::string_view t;
  for(std::size_t i = 0; numbers.next(t); ++i)
  {
    if(i < (layout.homogeneous ? 4u : 3u))
      x[i] = coordinate(t, line_number, v);
    else
    {
      double ignored = 0;
      if(!parse_double(t, ignored))
        refuse_at(line_number, "vertex " + std::to_string(v) + ": " + quoted(t) + " is not a number");
    }
  }
  if(layout.homogeneous)
  {
    // 4OFF: homogeneous coordinates, the point is (x/w, y/w, z/w).
    if(!(x[3] != 0))
      refuse_at(line_number, "vertex " + std::to_string(v) + " has the homogeneous coordinate w = 0");
    for(int i = 0; i < 3; ++i)
    {
      x[i] /= x[3];
      if(!std::isfinite(x[i]))
        refuse_at(line_number, "vertex " + std::to_string(v) + " divided by its w is not finite");
    }
  }
  soup.points.emplace_back(x[0], x[1], x[2]);
}

inline void read_off_vertices(Text_lines& lines, const Off_header& header, Polygon_soup& soup)
{
  std::string_view line;
  reserve_at_most(soup.points, header.vertices, lines.remaining_bytes(), 2 * header.layout.min_numbers());
  for(std::size_t v = 0; v < header.vertices; ++v)
  {
    if(!next_content_line(lines, line))
      refuse("the file ends after " + std::to_string(v) + " of the " + std::to_string(header.vertices) +
             " vertices its header announces (truncated?)");
    read_off_vertex(line, lines.number(), v, header.layout, soup);
  }
}

/// One face line: its corners, each a vertex the header announced, then at most a colour.
inline std::vector<std::size_t> read_off_face(std::string_view line, std::size_t line_number, std::size_t f,
                                              std::size_t nv)
{
  Tokens items(line);
  std::string_view t;
  items.next(t);
  long long size = 0;
  if(!parse_integer(t, size) || size < 0)
    refuse_at(line_number,
              "face " + std::to_string(f) + ": its corner count " + quoted(t) + " is not a non-negative integer");
  if(size < 3)
    refuse_at(line_number,
              "face " + std::to_string(f) + " has " + std::to_string(size) + " corner(s); a face needs at least 3");
  if(static_cast<unsigned long long>(size) > nv)
    refuse_at(line_number, "face " + std::to_string(f) + " announces " + std::to_string(size) +
                             " corners but the file has only " + std::to_string(nv) + " vertices");
  std::vector<std::size_t> polygon;
  // Bounded by the line's own length: no allocation from the announced count alone.
  polygon.reserve(std::min<std::size_t>(static_cast<std::size_t>(size), line.size() / 2 + 1));
  for(long long c = 0; c < size; ++c)
  {
    if(!items.next(t))
      refuse_at(line_number, "face " + std::to_string(f) + " announces " + std::to_string(size) +
                               " corners but lists " + std::to_string(c));
    long long index = 0;
    if(!parse_integer(t, index))
      refuse_at(line_number, "face " + std::to_string(f) + ": " + quoted(t) + " is not a vertex index");
    if(index < 0 || static_cast<unsigned long long>(index) >= nv)
      refuse_at(line_number, "face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                               " is out of range (the file has " + std::to_string(nv) + " vertices)");
    polygon.push_back(static_cast<std::size_t>(index));
  }
  // What may follow the indices is a face colour: an index or 3-4 components.
  std::size_t extra = 0;
  for(; items.next(t); ++extra)
  {
    double ignored = 0;
    if(!parse_double(t, ignored))
      refuse_at(line_number,
                "face " + std::to_string(f) + ": " + quoted(t) + " after its corners is not a colour component");
  }
  if(extra > 4)
    refuse_at(line_number, "face " + std::to_string(f) + " has " + std::to_string(extra) + " values after its " +
                             std::to_string(size) + " corners (at most a colour of 4 components may follow)");
  return polygon;
}

inline void read_off_faces(Text_lines& lines, const Off_header& header, Polygon_soup& soup)
{
  std::string_view line;
  reserve_at_most(soup.polygons, header.faces, lines.remaining_bytes(), 8);
  reserve_at_most(soup.polygon_lines, header.faces, lines.remaining_bytes(), 8);
  for(std::size_t f = 0; f < header.faces; ++f)
  {
    if(!next_content_line(lines, line))
      refuse("the file ends after " + std::to_string(f) + " of the " + std::to_string(header.faces) +
             " faces its header announces (truncated?)");
    soup.polygons.push_back(read_off_face(line, lines.number(), f, header.vertices));
    soup.polygon_lines.push_back(lines.number());
  }
  // Faces beyond the announced count would be lost unseen: the header or the file is wrong.
  if(next_content_line(lines, line))
    refuse_at(lines.number(), "the file goes on after the " + std::to_string(header.faces) +
                                " faces its header announces (is the face count wrong?)");
}

inline void read_off(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  const Off_header header = read_off_header(lines, limits);
  read_off_vertices(lines, header, soup);
  read_off_faces(lines, header, soup);
}

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_READ_OFF_H
