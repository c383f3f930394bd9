// Copyright (c) the ICM authors.
//
// What the readers of untrusted mesh files share (read_off.h, read_obj.h, read_ply.h,
// read_stl.h): the polygon soup they fill, the reader's limits, numbers parsed whole and
// checked, a cursor over lines and tokens, and the checks every format makes of a count or
// a face. A refusal unwinds as a `Soup_error` to `read_polygon_soup()`, which returns it as
// the message.

#ifndef ICM_IO_SOUP_READING_H
#define ICM_IO_SOUP_READING_H

#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <filesystem>
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
  case Mesh_file_format::Off:
    return "OFF";
  case Mesh_file_format::Obj:
    return "OBJ";
  case Mesh_file_format::Ply:
    return "PLY";
  case Mesh_file_format::Stl:
    return "STL";
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
/// returned message; it never leaves that function.
struct Soup_error
{
  std::string message;
};

[[noreturn]] inline void refuse(const std::string& message)
{
  throw Soup_error{message};
}

[[noreturn]] inline void refuse_at(std::size_t line, const std::string& message)
{
  refuse("line " + std::to_string(line) + ": " + message);
}

inline bool is_space(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

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

/// Parses the whole token as a number; accepts a leading '+', no trailing characters.
template <class Number>
bool parse_whole(std::string_view token, Number& value)
{
  if(!token.empty() && token.front() == '+')
    token.remove_prefix(1);
  if(token.empty())
    return false;
  const std::from_chars_result r = std::from_chars(token.data(), token.data() + token.size(), value);
  return r.ec == std::errc() && r.ptr == token.data() + token.size();
}

/// Parses the whole token as a double. Non-finite values parse (the caller decides).
inline bool parse_double(std::string_view token, double& value)
{
  return parse_whole(token, value);
}

/// Parses the whole token as a signed integer.
inline bool parse_integer(std::string_view token, long long& value)
{
  return parse_whole(token, value);
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
inline std::size_t header_count(std::string_view token, std::size_t line, const char* what, std::size_t limit)
{
  long long n = 0;
  if(!parse_integer(token, n) || n < 0)
    refuse_at(line, std::string("the ") + what + " count " + quoted(token) + " is not a non-negative integer");
  if(static_cast<unsigned long long>(n) > limit)
    refuse_at(line, std::string("the header announces ") + std::to_string(n) + " " + what +
                      ", more than this reader takes (" + std::to_string(limit) + ")");
  return static_cast<std::size_t>(n);
}

/// Refuses a header whose elements cannot fit in what follows it, before anything is
/// allocated for them: `count` elements of at least `bytes_each` bytes in `available`.
inline void check_fits(std::size_t count, std::size_t bytes_each, std::size_t available, std::size_t line,
                       const std::string& what)
{
  // One byte of slack: the last element needs no separator after it.
  if(bytes_each > 0 && count > (available + 1) / bytes_each)
    refuse_at(line, "the header announces " + std::to_string(count) + " " + what + " but only " +
                      std::to_string(available) + " bytes follow (at least " + std::to_string(bytes_each) +
                      " per element): the count is wrong or the file "
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
    refuse(soup.describe_polygon(p) + " has " + std::to_string(polygon.size()) + " corner(s); a face needs at least 3");
  for(std::size_t i : polygon)
    if(i >= number_of_points)
      refuse(soup.describe_polygon(p) + ": vertex index " + std::to_string(i) + " is out of range (the file has " +
             std::to_string(number_of_points) + " vertices)");
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
      refuse(soup.describe_polygon(p) + " uses vertex " + std::to_string(*twice) + " twice (a degenerate face)");
  }
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

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_SOUP_READING_H
