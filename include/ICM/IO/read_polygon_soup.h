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

#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace ICM {
namespace IO {

/// The mesh file formats `read_polygon_soup()` reads.
enum class Mesh_file_format
{
  Off, ///< Geomview OFF with the prefixes ST, C, N and 4 (nOFF and binary OFF are refused)
  Obj, ///< Wavefront OBJ: `v` and `f` (or `fo`) statements, other statements ignored
  Ply, ///< Stanford PLY, ASCII or binary (either byte order)
  Stl  ///< STL, ASCII or binary; identical corners are merged into one vertex
};

/// Polygons over points, as read from a file, in the file's order.
struct Polygon_soup
{
  using Point_3 = CGAL::Simple_cartesian<double>::Point_3;
  std::vector<Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  /// Where each polygon was read: its line in a text file, 0 in a binary one (messages then
  /// name the polygon by its number).
  std::vector<std::size_t> polygon_lines;

  void clear()
  {
    points.clear();
    polygons.clear();
    polygon_lines.clear();
  }
  /// "face 12 (line 20)" or "face 12": how messages name polygon `p`.
  std::string describe_polygon(std::size_t p) const
  {
    std::string s = "face " + std::to_string(p);
    if(p < polygon_lines.size() && polygon_lines[p] > 0)
      s += " (line " + std::to_string(polygon_lines[p]) + ")";
    return s;
  }
};

/// Limits beyond what the file's own size implies. Mesh_index and CGAL::Surface_mesh number
/// vertices, faces and halfedges with 32-bit integers.
struct Soup_reading_limits
{
  std::size_t max_points = std::size_t(1) << 28;
  std::size_t max_polygons = std::size_t(1) << 28;
};

/// The format named by the file's extension (case-insensitive), or nothing.
inline std::optional<Mesh_file_format> format_from_extension(const std::string& path)
{
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if(ext == ".off")
    return Mesh_file_format::Off;
  if(ext == ".obj")
    return Mesh_file_format::Obj;
  if(ext == ".ply")
    return Mesh_file_format::Ply;
  if(ext == ".stl")
    return Mesh_file_format::Stl;
  return std::nullopt;
}

inline const char* format_name(Mesh_file_format format)
{
  switch(format)
  {
  case Mesh_file_format::Off: return "OFF";
  case Mesh_file_format::Obj: return "OBJ";
  case Mesh_file_format::Ply: return "PLY";
  case Mesh_file_format::Stl: return "STL";
  }
  return "?";
}

} // namespace IO

namespace internal {
namespace reading {

using IO::format_name;
using IO::Mesh_file_format;
using IO::Polygon_soup;
using IO::Soup_reading_limits;

/// Thrown inside the readers to unwind to `read_polygon_soup()`, which turns it into the
/// returned message; it never leaves this header.
struct Soup_error
{
  std::string message;
};

[[noreturn]] inline void refuse(const std::string& message) { throw Soup_error{message}; }

[[noreturn]] inline void refuse_at(std::size_t line, const std::string& message)
{
  refuse("line " + std::to_string(line) + ": " + message);
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// A token as it may be quoted in a message: at most 40 characters, control bytes as '?'.
inline std::string quoted(std::string_view token)
{
  std::string s;
  for(char c : token.substr(0, 40))
    s += (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) ? '?' : c;
  return "'" + s + (token.size() > 40 ? "...'" : "'");
}

/// The lines of a text, each without its end of line, with their numbers.
class Text_lines
{
public:
  explicit Text_lines(std::string_view text, std::size_t first_line_number = 1)
    : text_(text), next_number_(first_line_number)
  {}

  bool next(std::string_view& line)
  {
    if(position_ >= text_.size())
      return false;
    const std::size_t end = text_.find('\n', position_);
    const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
    line = text_.substr(position_, stop - position_);
    position_ = end == std::string_view::npos ? text_.size() : end + 1;
    number_ = next_number_++;
    return true;
  }
  /// The number of the line last returned by `next()`.
  std::size_t number() const { return number_; }
  std::size_t remaining_bytes() const { return text_.size() - position_; }
  std::size_t position() const { return position_; }

private:
  std::string_view text_;
  std::size_t position_ = 0, number_ = 0, next_number_;
};

/// The whitespace-separated tokens of one line.
class Tokens
{
public:
  explicit Tokens(std::string_view line) : line_(line) {}
  bool next(std::string_view& token)
  {
    while(position_ < line_.size() && is_space(line_[position_]))
      ++position_;
    if(position_ >= line_.size())
      return false;
    const std::size_t start = position_;
    while(position_ < line_.size() && !is_space(line_[position_]))
      ++position_;
    token = line_.substr(start, position_ - start);
    return true;
  }
  /// Characters not read yet.
  std::size_t remaining() const { return line_.size() - position_; }
  std::size_t count() const
  {
    Tokens copy(line_);
    std::string_view t;
    std::size_t n = 0;
    while(copy.next(t))
      ++n;
    return n;
  }

private:
  std::string_view line_;
  std::size_t position_ = 0;
};

/// The line without a `#` comment.
inline std::string_view without_comment(std::string_view line)
{
  const std::size_t hash = line.find('#');
  return hash == std::string_view::npos ? line : line.substr(0, hash);
}

inline bool is_blank(std::string_view line)
{
  return std::all_of(line.begin(), line.end(), [](char c) { return is_space(c); });
}

/// Parses the whole token as a double; accepts a leading '+'. Non-finite values parse (the
/// caller decides), trailing characters do not.
inline bool parse_double(std::string_view token, double& value)
{
  if(!token.empty() && token.front() == '+')
    token.remove_prefix(1);
  if(token.empty())
    return false;
  const std::from_chars_result r = std::from_chars(token.data(), token.data() + token.size(), value);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

/// Parses the whole token as a signed integer.
inline bool parse_integer(std::string_view token, long long& value)
{
  if(!token.empty() && token.front() == '+')
    token.remove_prefix(1);
  if(token.empty())
    return false;
  const std::from_chars_result r = std::from_chars(token.data(), token.data() + token.size(), value);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

/// A coordinate: a finite double, or a refusal naming the line, the vertex and the token.
inline double coordinate(std::string_view token, std::size_t line, std::size_t vertex)
{
  double x = 0;
  if(!parse_double(token, x))
    refuse_at(line, "vertex " + std::to_string(vertex) + ": " + quoted(token) +
                      " is not a number (or is out of the range of a double)");
  if(!std::isfinite(x))
    refuse_at(line, "vertex " + std::to_string(vertex) + " has a non-finite coordinate " + quoted(token));
  return x;
}

/// A count in a header: a non-negative integer not above `limit`.
inline std::size_t header_count(std::string_view token, std::size_t line, const char* what,
                                std::size_t limit)
{
  long long n = 0;
  if(!parse_integer(token, n) || n < 0)
    refuse_at(line, std::string("the ") + what + " count " + quoted(token) +
                      " is not a non-negative integer");
  if(static_cast<unsigned long long>(n) > limit)
    refuse_at(line, std::string("the header announces ") + std::to_string(n) + " " + what +
                      ", more than this reader takes (" + std::to_string(limit) + ")");
  return static_cast<std::size_t>(n);
}

/// Refuses a header whose elements cannot fit in what follows it, before anything is
/// allocated for them: `count` elements of at least `bytes_each` bytes in `available`.
inline void check_fits(std::size_t count, std::size_t bytes_each, std::size_t available,
                       std::size_t line, const std::string& what)
{
  // One byte of slack: the last element needs no separator after it.
  if(bytes_each > 0 && count > (available + 1) / bytes_each)
    refuse_at(line, "the header announces " + std::to_string(count) + " " + what +
                      " but only " + std::to_string(available) + " bytes follow (at least " +
                      std::to_string(bytes_each) + " per element): the count is wrong or the file "
                      "is truncated");
}

/// Reserves room for `count` elements announced by a header, but never more than the bytes
/// left could hold at `realistic_bytes` each: a header within the file's size can still
/// announce far more small elements than a real file of that size has, and reserving for
/// all of them would cost many times the file's size.
template <class Vector>
void reserve_at_most(Vector& v, std::size_t count, std::size_t available, std::size_t realistic_bytes)
{
  v.reserve(std::min(count, available / realistic_bytes + 1));
}

/// Checks one polygon as read: at least 3 corners, each a vertex of the file, none twice.
inline void check_polygon(const std::vector<std::size_t>& polygon, std::size_t number_of_points,
                          const Polygon_soup& soup, std::size_t p)
{
  if(polygon.size() < 3)
    refuse(soup.describe_polygon(p) + " has " + std::to_string(polygon.size()) +
           " corner(s); a face needs at least 3");
  for(std::size_t i : polygon)
    if(i >= number_of_points)
      refuse(soup.describe_polygon(p) + ": vertex index " + std::to_string(i) +
             " is out of range (the file has " + std::to_string(number_of_points) + " vertices)");
  // Small polygons by a quadratic scan; large ones sorted, so that a face of a million
  // corners costs n log n and not n^2.
  if(polygon.size() <= 16)
  {
    for(std::size_t a = 0; a < polygon.size(); ++a)
      for(std::size_t b = a + 1; b < polygon.size(); ++b)
        if(polygon[a] == polygon[b])
          refuse(soup.describe_polygon(p) + " uses vertex " + std::to_string(polygon[a]) +
                 " twice (a degenerate face)");
  }
  else
  {
    std::vector<std::size_t> sorted = polygon;
    std::sort(sorted.begin(), sorted.end());
    const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
    if(twice != sorted.end())
      refuse(soup.describe_polygon(p) + " uses vertex " + std::to_string(*twice) +
             " twice (a degenerate face)");
  }
}

// --- OFF ---------------------------------------------------------------------------------

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

/// The next line that is neither blank nor a comment, without its comment.
inline bool next_content_line(Text_lines& lines, std::string_view& line)
{
  while(lines.next(line))
  {
    line = without_comment(line);
    if(!is_blank(line))
      return true;
  }
  return false;
}

inline void read_off(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  std::string_view line;
  if(!next_content_line(lines, line))
    refuse("the file has no OFF header");
  Tokens tokens(line);
  std::string_view word;
  tokens.next(word);
  Off_layout layout;
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
  const std::size_t count_line = lines.number();
  if(counts.size() < 2 || counts.size() > 3)
    refuse_at(count_line, "expected the counts of vertices, faces and edges, found " +
                            std::to_string(counts.size()) + " value(s)");
  const std::size_t nv = header_count(counts[0], count_line, "vertices", limits.max_points);
  const std::size_t nf = header_count(counts[1], count_line, "faces", limits.max_polygons);
  if(counts.size() == 3)
    header_count(counts[2], count_line, "edges", std::numeric_limits<std::size_t>::max());
  // Each vertex line has at least its numbers and a separator each, each face line a count
  // and a separator (what else it needs is checked as it is read).
  const std::size_t vertex_bytes = 2 * layout.min_numbers();
  check_fits(nv, vertex_bytes, lines.remaining_bytes(), count_line, "vertices");
  check_fits(nf, 2, lines.remaining_bytes() - std::min(lines.remaining_bytes(), nv * vertex_bytes),
             count_line, "faces");

  reserve_at_most(soup.points, nv, lines.remaining_bytes(), vertex_bytes);
  for(std::size_t v = 0; v < nv; ++v)
  {
    if(!next_content_line(lines, line))
      refuse("the file ends after " + std::to_string(v) + " of the " + std::to_string(nv) +
             " vertices its header announces (truncated?)");
    Tokens numbers(line);
    const std::size_t n = numbers.count();
    if(n < layout.min_numbers() || n > layout.max_numbers())
      refuse_at(lines.number(), "vertex " + std::to_string(v) + " has " + std::to_string(n) +
                                  " numbers; this OFF variant has " + std::to_string(layout.min_numbers()) +
                                  (layout.max_numbers() > layout.min_numbers()
                                     ? " to " + std::to_string(layout.max_numbers())
                                     : std::string()) +
                                  " per vertex line");
    std::array<double, 4> x{0, 0, 0, 1};
    std::string_view t;
    for(std::size_t i = 0; numbers.next(t); ++i)
    {
      if(i < (layout.homogeneous ? 4u : 3u))
        x[i] = coordinate(t, lines.number(), v);
      else
      {
        double ignored = 0;
        if(!parse_double(t, ignored))
          refuse_at(lines.number(), "vertex " + std::to_string(v) + ": " + quoted(t) + " is not a number");
      }
    }
    if(layout.homogeneous)
    {
      // 4OFF: homogeneous coordinates, the point is (x/w, y/w, z/w).
      if(!(x[3] != 0))
        refuse_at(lines.number(), "vertex " + std::to_string(v) + " has the homogeneous coordinate w = 0");
      for(int i = 0; i < 3; ++i)
      {
        x[i] /= x[3];
        if(!std::isfinite(x[i]))
          refuse_at(lines.number(), "vertex " + std::to_string(v) + " divided by its w is not finite");
      }
    }
    soup.points.emplace_back(x[0], x[1], x[2]);
  }

  reserve_at_most(soup.polygons, nf, lines.remaining_bytes(), 8);
  reserve_at_most(soup.polygon_lines, nf, lines.remaining_bytes(), 8);
  for(std::size_t f = 0; f < nf; ++f)
  {
    if(!next_content_line(lines, line))
      refuse("the file ends after " + std::to_string(f) + " of the " + std::to_string(nf) +
             " faces its header announces (truncated?)");
    Tokens items(line);
    std::string_view t;
    items.next(t);
    long long size = 0;
    if(!parse_integer(t, size) || size < 0)
      refuse_at(lines.number(), "face " + std::to_string(f) + ": its corner count " + quoted(t) +
                                  " is not a non-negative integer");
    if(size < 3)
      refuse_at(lines.number(), "face " + std::to_string(f) + " has " + std::to_string(size) +
                                  " corner(s); a face needs at least 3");
    if(static_cast<unsigned long long>(size) > nv)
      refuse_at(lines.number(), "face " + std::to_string(f) + " announces " + std::to_string(size) +
                                  " corners but the file has only " + std::to_string(nv) + " vertices");
    std::vector<std::size_t> polygon;
    // Bounded by the line's own length: no allocation from the announced count alone.
    polygon.reserve(std::min<std::size_t>(static_cast<std::size_t>(size), line.size() / 2 + 1));
    for(long long c = 0; c < size; ++c)
    {
      if(!items.next(t))
        refuse_at(lines.number(), "face " + std::to_string(f) + " announces " + std::to_string(size) +
                                    " corners but lists " + std::to_string(c));
      long long index = 0;
      if(!parse_integer(t, index))
        refuse_at(lines.number(), "face " + std::to_string(f) + ": " + quoted(t) + " is not a vertex index");
      if(index < 0 || static_cast<unsigned long long>(index) >= nv)
        refuse_at(lines.number(), "face " + std::to_string(f) + ": vertex index " + std::to_string(index) +
                                    " is out of range (the file has " + std::to_string(nv) + " vertices)");
      polygon.push_back(static_cast<std::size_t>(index));
    }
    // What may follow the indices is a face colour: an index or 3-4 components.
    std::size_t extra = 0;
    for(; items.next(t); ++extra)
    {
      double ignored = 0;
      if(!parse_double(t, ignored))
        refuse_at(lines.number(), "face " + std::to_string(f) + ": " + quoted(t) +
                                    " after its corners is not a colour component");
    }
    if(extra > 4)
      refuse_at(lines.number(), "face " + std::to_string(f) + " has " + std::to_string(extra) +
                                  " values after its " + std::to_string(size) +
                                  " corners (at most a colour of 4 components may follow)");
    soup.polygons.push_back(std::move(polygon));
    soup.polygon_lines.push_back(lines.number());
  }
  // Faces beyond the announced count would be lost unseen: the header or the file is wrong.
  if(next_content_line(lines, line))
    refuse_at(lines.number(), "the file goes on after the " + std::to_string(nf) +
                                " faces its header announces (is the face count wrong?)");
}

// --- OBJ ---------------------------------------------------------------------------------

/// The vertex of one OBJ face corner `v`, `v/vt`, `v//vn` or `v/vt/vn`; negative indices
/// count back from the last vertex read so far. Positive indices are checked once the
/// whole file is read (a face may name a vertex defined after it).
inline std::size_t obj_corner(std::string_view token, std::size_t vertices_so_far, std::size_t line,
                              std::size_t face)
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
                        " reaches before the first vertex (" + std::to_string(vertices_so_far) +
                        " vertices so far)");
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

// --- PLY ---------------------------------------------------------------------------------

enum class Ply_encoding
{
  Ascii,
  Little_endian,
  Big_endian
};

/// A PLY scalar type: its size in bytes and how to read it.
struct Ply_type
{
  std::size_t size = 0;
  bool is_signed = false, is_float = false;
};

inline bool ply_type(std::string_view name, Ply_type& type)
{
  struct Entry
  {
    const char* a;
    const char* b;
    Ply_type type;
  };
  static const Entry entries[] = {{"char", "int8", {1, true, false}},     {"uchar", "uint8", {1, false, false}},
                                  {"short", "int16", {2, true, false}},   {"ushort", "uint16", {2, false, false}},
                                  {"int", "int32", {4, true, false}},     {"uint", "uint32", {4, false, false}},
                                  {"float", "float32", {4, true, true}},  {"double", "float64", {8, true, true}}};
  for(const Entry& e : entries)
    if(name == e.a || name == e.b)
    {
      type = e.type;
      return true;
    }
  return false;
}

struct Ply_property
{
  std::string name;
  Ply_type type;        ///< of the value, or of the items of a list
  bool is_list = false;
  Ply_type count_type;  ///< of a list's count
};

struct Ply_element
{
  std::string name;
  std::size_t count = 0, header_line = 0;
  std::vector<Ply_property> properties;

  /// The fewest bytes one element can take: every scalar, every list's count (binary), or
  /// two bytes per value (ASCII: a digit and a separator).
  std::size_t min_bytes(Ply_encoding encoding) const
  {
    std::size_t bytes = 0;
    for(const Ply_property& p : properties)
      bytes += encoding == Ply_encoding::Ascii ? 2 : (p.is_list ? p.count_type.size : p.type.size);
    return bytes;
  }
};

/// Names a value of a PLY body in a message ("face 12, property vertex_indices item 3"),
/// built only when a message needs it: a body has millions of values.
struct Ply_value_name
{
  const std::string& element;
  std::size_t index;
  const std::string& property;
  const char* part = "";        ///< " (list count)", " item " or ""
  std::size_t item = 0;         ///< with part " item "

  std::string str() const
  {
    std::string s = element + " " + std::to_string(index) + ", property " + property + part;
    if(std::strcmp(part, " item ") == 0)
      s += std::to_string(item);
    return s;
  }
};

/// Reads the values of a PLY body, binary or ASCII, with the position for messages.
class Ply_body
{
public:
  Ply_body(std::string_view body, Ply_encoding encoding, std::size_t first_line)
    : body_(body), encoding_(encoding), lines_(body, first_line)
  {}

  std::size_t remaining_bytes() const
  {
    return encoding_ == Ply_encoding::Ascii ? lines_.remaining_bytes() + tokens_.remaining() : body_.size() - offset_;
  }

  /// The line of the value last read (ASCII), 0 in a binary body.
  std::size_t line() const { return encoding_ == Ply_encoding::Ascii ? lines_.number() : 0; }

  /// The next value as a double; `what` names it in a message.
  double value(const Ply_type& type, const Ply_value_name& what)
  {
    return encoding_ == Ply_encoding::Ascii ? ascii_value(what) : binary_value(type, what);
  }

  std::string where() const
  {
    return encoding_ == Ply_encoding::Ascii ? "line " + std::to_string(lines_.number()) + ": "
                                            : "byte " + std::to_string(offset_) + " of the body: ";
  }

private:
  double ascii_value(const Ply_value_name& what)
  {
    std::string_view t;
    while(!tokens_.next(t))
    {
      std::string_view line;
      if(!lines_.next(line))
        refuse("the file ends before " + what.str() + " (truncated?)");
      tokens_ = Tokens(line);
    }
    double x = 0;
    if(!parse_double(t, x))
      refuse(where() + what.str() + ": " + quoted(t) + " is not a number");
    return x;
  }

  double binary_value(const Ply_type& type, const Ply_value_name& what)
  {
    if(body_.size() - offset_ < type.size)
      refuse("the file ends inside " + what.str() + " (truncated?)");
    unsigned char b[8];
    std::memcpy(b, body_.data() + offset_, type.size);
    offset_ += type.size;
    if((encoding_ == Ply_encoding::Big_endian) == host_is_little_endian())
      std::reverse(b, b + type.size);
    if(type.is_float)
    {
      if(type.size == 4)
      {
        float f;
        std::memcpy(&f, b, 4);
        return f;
      }
      double d;
      std::memcpy(&d, b, 8);
      return d;
    }
    std::uint64_t u = 0;
    for(std::size_t i = 0; i < type.size; ++i)
      u |= static_cast<std::uint64_t>(b[i]) << (8 * i); // b is little endian now
    if(type.is_signed && type.size < 8 && (u >> (8 * type.size - 1)) != 0)
      return static_cast<double>(static_cast<std::int64_t>(u) - (std::int64_t(1) << (8 * type.size)));
    return static_cast<double>(u);
  }

  static bool host_is_little_endian()
  {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
  }

  std::string_view body_;
  Ply_encoding encoding_;
  std::size_t offset_ = 0;
  Text_lines lines_;
  Tokens tokens_{std::string_view()};
};

/// A list's count or an index: an integral, non-negative value.
inline std::size_t ply_index(double x, Ply_body& body, const Ply_value_name& what)
{
  if(!(x >= 0) || x != std::floor(x) || x > 4294967295.0)
    refuse(body.where() + what.str() + " is " + (std::isfinite(x) ? std::to_string(x) : std::string("not finite")) +
           ", not a non-negative integer");
  return static_cast<std::size_t>(x);
}

inline void read_ply(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  std::string_view line;
  lines.next(line);
  {
    Tokens first(line);
    std::string_view word;
    if(!first.next(word) || word != "ply" || first.next(word))
      refuse("line 1: the file does not start with 'ply'");
  }
  std::optional<Ply_encoding> encoding;
  std::vector<Ply_element> elements;
  bool ended = false;
  while(!ended && lines.next(line))
  {
    Tokens tokens(line);
    std::string_view word;
    if(!tokens.next(word) || word == "comment" || word == "obj_info")
      continue;
    std::vector<std::string_view> args;
    for(std::string_view t; tokens.next(t);)
      args.push_back(t);
    if(word == "format")
    {
      if(args.size() != 2 || args[1] != "1.0")
        refuse_at(lines.number(), "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if(args[0] == "ascii")
        encoding = Ply_encoding::Ascii;
      else if(args[0] == "binary_little_endian")
        encoding = Ply_encoding::Little_endian;
      else if(args[0] == "binary_big_endian")
        encoding = Ply_encoding::Big_endian;
      else
        refuse_at(lines.number(), "unknown PLY format " + quoted(args[0]));
    }
    else if(word == "element")
    {
      if(args.size() != 2)
        refuse_at(lines.number(), "expected 'element NAME COUNT'");
      Ply_element e;
      e.name = std::string(args[0]);
      e.count = header_count(args[1], lines.number(), ("'" + e.name + "' elements").c_str(),
                             std::max(limits.max_points, limits.max_polygons));
      e.header_line = lines.number();
      elements.push_back(std::move(e));
    }
    else if(word == "property")
    {
      if(elements.empty())
        refuse_at(lines.number(), "a property before any element");
      Ply_property p;
      const bool list = !args.empty() && args[0] == "list";
      if(list ? args.size() != 4 : args.size() != 2)
        refuse_at(lines.number(), "expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
      p.is_list = list;
      const std::string_view type_name = list ? args[2] : args[0];
      if(!ply_type(type_name, p.type) || (list && !ply_type(args[1], p.count_type)))
        refuse_at(lines.number(), "unknown PLY type in " + quoted(line));
      if(list && p.count_type.is_float)
        refuse_at(lines.number(), "a list count of floating-point type");
      p.name = std::string(args.back());
      elements.back().properties.push_back(std::move(p));
    }
    else if(word == "end_header")
      ended = true;
    else
      refuse_at(lines.number(), "unknown PLY header line " + quoted(line));
  }
  if(!ended)
    refuse("the PLY header has no 'end_header' line");
  if(!encoding)
    refuse("the PLY header has no 'format' line");

  // The vertex element and its x, y, z; the face element and its list of indices.
  const Ply_element* vertex = nullptr;
  const Ply_element* face = nullptr;
  for(const Ply_element& e : elements)
  {
    if(e.name == "vertex")
      vertex = &e;
    if(e.name == "face")
      face = &e;
  }
  if(vertex == nullptr)
    refuse("the PLY header declares no 'vertex' element");
  std::array<int, 3> xyz{-1, -1, -1};
  for(std::size_t i = 0; i < vertex->properties.size(); ++i)
    for(int k = 0; k < 3; ++k)
      if(vertex->properties[i].name == std::string(1, "xyz"[k]))
      {
        if(vertex->properties[i].is_list)
          refuse_at(vertex->header_line, "the vertex property " + vertex->properties[i].name + " is a list");
        xyz[k] = static_cast<int>(i);
      }
  if(*std::min_element(xyz.begin(), xyz.end()) < 0)
    refuse_at(vertex->header_line, "the vertex element has no x, y and z properties");
  int indices = -1;
  if(face != nullptr)
    for(std::size_t i = 0; i < face->properties.size(); ++i)
      if(face->properties[i].is_list &&
         (face->properties[i].name == "vertex_indices" || face->properties[i].name == "vertex_index"))
        indices = static_cast<int>(i);
  if(face != nullptr && face->count > 0 && indices < 0)
    refuse_at(face->header_line, "the face element has no list property 'vertex_indices'");
  if(vertex->count > limits.max_points || (face != nullptr && face->count > limits.max_polygons))
    refuse("the PLY header announces more vertices or faces than this reader takes");

  const std::size_t body_start = lines.position();
  Ply_body body(text.substr(body_start), *encoding, lines.number() + 1);
  // All elements together must fit in what follows the header.
  {
    std::size_t available = body.remaining_bytes();
    for(const Ply_element& e : elements)
    {
      const std::size_t each = e.min_bytes(*encoding);
      check_fits(e.count, each, available, e.header_line, "'" + e.name + "' elements");
      available -= e.count * each;
    }
  }

  reserve_at_most(soup.points, vertex->count, body.remaining_bytes(), 6);
  reserve_at_most(soup.polygons, face ? face->count : 0, body.remaining_bytes(), 8);
  for(const Ply_element& e : elements)
    for(std::size_t i = 0; i < e.count; ++i)
    {
      std::array<double, 3> x{};
      std::vector<std::size_t> polygon;
      std::size_t polygon_line = 0;
      for(std::size_t pi = 0; pi < e.properties.size(); ++pi)
      {
        const Ply_property& p = e.properties[pi];
        const Ply_value_name what{e.name, i, p.name};
        if(!p.is_list)
        {
          const double value = body.value(p.type, what);
          if(&e == vertex)
            for(int k = 0; k < 3; ++k)
              if(xyz[k] == static_cast<int>(pi))
              {
                if(!std::isfinite(value))
                  refuse(body.where() + "vertex " + std::to_string(i) + " has a non-finite coordinate");
                x[k] = value;
              }
          continue;
        }
        const Ply_value_name count_name{e.name, i, p.name, " (list count)"};
        const std::size_t count = ply_index(body.value(p.count_type, count_name), body, count_name);
        const bool is_face_list = &e == face && static_cast<int>(pi) == indices;
        // Each item takes at least its size (binary) or two bytes (ASCII).
        const std::size_t item_bytes = *encoding == Ply_encoding::Ascii ? 2 : p.type.size;
        if(count > body.remaining_bytes() / item_bytes)
          refuse(body.where() + what.str() + ": a list of " + std::to_string(count) +
                 " items runs past the end of the file");
        if(is_face_list)
        {
          if(count < 3)
            refuse(body.where() + "face " + std::to_string(i) + " has " + std::to_string(count) +
                   " corner(s); a face needs at least 3");
          if(count > vertex->count)
            refuse(body.where() + "face " + std::to_string(i) + " announces " + std::to_string(count) +
                   " corners but the file has only " + std::to_string(vertex->count) + " vertices");
          polygon.reserve(count);
        }
        for(std::size_t c = 0; c < count; ++c)
        {
          const Ply_value_name item_name{e.name, i, p.name, " item ", c};
          const double item = body.value(p.type, item_name);
          if(!is_face_list)
            continue;
          const std::size_t index = ply_index(item, body, item_name);
          if(index >= vertex->count)
            refuse(body.where() + "face " + std::to_string(i) + ": vertex index " + std::to_string(index) +
                   " is out of range (the file has " + std::to_string(vertex->count) + " vertices)");
          polygon.push_back(index);
        }
        if(is_face_list)
          polygon_line = body.line();
      }
      if(&e == vertex)
        soup.points.emplace_back(x[0], x[1], x[2]);
      else if(&e == face)
      {
        soup.polygons.push_back(std::move(polygon));
        soup.polygon_lines.push_back(polygon_line);
      }
    }
}

// --- STL ---------------------------------------------------------------------------------

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
        const std::uint32_t bits = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                                   std::uint32_t(b[3]) << 24;
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
  enum class State { Solid, Facet, Loop, Vertex, Endloop, Endfacet, Done } state = State::Solid;
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
          refuse_at(facet_line, "the facet has " + std::to_string(triangle.size()) +
                                  " vertices (STL facets are triangles)");
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
inline bool read_polygon_soup(std::string_view data, Mesh_file_format format, Polygon_soup& soup,
                              std::string& error, const Soup_reading_limits& limits = Soup_reading_limits())
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
    case Mesh_file_format::Off: internal::read_off(data, soup, limits); break;
    case Mesh_file_format::Obj: internal::read_obj(data, soup, limits); break;
    case Mesh_file_format::Ply: internal::read_ply(data, soup, limits); break;
    case Mesh_file_format::Stl: internal::read_stl(data, soup, limits); break;
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
