// Copyright (c) the ICM authors.
//
// Reading Stanford PLY, ASCII or binary in either byte order, into a polygon soup: the
// header's elements together must fit in the bytes that follow it, every list count and
// index must be a non-negative integer, every list must end inside the file.

#ifndef ICM_IO_READ_PLY_H
#define ICM_IO_READ_PLY_H

#include <ICM/IO/Soup_reading.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ICM {
namespace internal {
namespace reading {

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
  static const Entry entries[] = {{"char", "int8", {1, true, false}},    {"uchar", "uint8", {1, false, false}},
                                  {"short", "int16", {2, true, false}},  {"ushort", "uint16", {2, false, false}},
                                  {"int", "int32", {4, true, false}},    {"uint", "uint32", {4, false, false}},
                                  {"float", "float32", {4, true, true}}, {"double", "float64", {8, true, true}}};
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
  Ply_type type; ///< of the value, or of the items of a list
  bool is_list = false;
  Ply_type count_type; ///< of a list's count
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
  const char* part = ""; ///< " (list count)", " item " or ""
  std::size_t item = 0;  ///< with part " item "

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

/// What the header of a PLY file declares.
struct Ply_header
{
  std::optional<Ply_encoding> encoding;
  std::vector<Ply_element> elements;
};

/// One `element` or `property` line of the header, into `header`.
inline void read_ply_declaration(std::string_view word, const std::vector<std::string_view>& args,
                                 std::string_view line, std::size_t line_number, Ply_header& header,
                                 const Soup_reading_limits& limits)
{
  if(word == "element")
  {
    if(args.size() != 2)
      refuse_at(line_number, "expected 'element NAME COUNT'");
    Ply_element e;
    e.name = std::string(args[0]);
    e.count = header_count(args[1], line_number, ("'" + e.name + "' elements").c_str(),
                           std::max(limits.max_points, limits.max_polygons));
    e.header_line = line_number;
    header.elements.push_back(std::move(e));
    return;
  }
  if(header.elements.empty())
    refuse_at(line_number, "a property before any element");
  Ply_property p;
  const bool list = !args.empty() && args[0] == "list";
  if(list ? args.size() != 4 : args.size() != 2)
    refuse_at(line_number, "expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
  p.is_list = list;
  const std::string_view type_name = list ? args[2] : args[0];
  if(!ply_type(type_name, p.type) || (list && !ply_type(args[1], p.count_type)))
    refuse_at(line_number, "unknown PLY type in " + quoted(line));
  if(list && p.count_type.is_float)
    refuse_at(line_number, "a list count of floating-point type");
  p.name = std::string(args.back());
  header.elements.back().properties.push_back(std::move(p));
}

inline Ply_encoding ply_encoding(const std::vector<std::string_view>& args, std::size_t line_number)
{
  if(args.size() != 2 || args[1] != "1.0")
    refuse_at(line_number, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  if(args[0] == "ascii")
    return Ply_encoding::Ascii;
  if(args[0] == "binary_little_endian")
    return Ply_encoding::Little_endian;
  if(args[0] == "binary_big_endian")
    return Ply_encoding::Big_endian;
  refuse_at(line_number, "unknown PLY format " + quoted(args[0]));
}

/// Reads the header up to `end_header`, leaving `lines` at the first line of the body.
inline Ply_header read_ply_header(Text_lines& lines, const Soup_reading_limits& limits)
{
  std::string_view line;
  lines.next(line);
  {
    Tokens first(line);
    std::string_view word;
    if(!first.next(word) || word != "ply" || first.next(word))
      refuse("line 1: the file does not start with 'ply'");
  }
  Ply_header header;
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
      header.encoding = ply_encoding(args, lines.number());
    else if(word == "element" || word == "property")
      read_ply_declaration(word, args, line, lines.number(), header, limits);
    else if(word == "end_header")
      ended = true;
    else
      refuse_at(lines.number(), "unknown PLY header line " + quoted(line));
  }
  if(!ended)
    refuse("the PLY header has no 'end_header' line");
  if(!header.encoding)
    refuse("the PLY header has no 'format' line");
  return header;
}

/// Where the soup is in a PLY body: the vertex element and its x, y, z; the face element and
/// its list of indices.
struct Ply_soup_layout
{
  const Ply_element* vertex = nullptr;
  const Ply_element* face = nullptr;
  std::array<int, 3> xyz{-1, -1, -1};
  int indices = -1;
};

inline Ply_soup_layout ply_soup_layout(const std::vector<Ply_element>& elements, const Soup_reading_limits& limits)
{
  Ply_soup_layout layout;
  for(const Ply_element& e : elements)
  {
    if(e.name == "vertex")
      layout.vertex = &e;
    if(e.name == "face")
      layout.face = &e;
  }
  const Ply_element* vertex = layout.vertex;
  const Ply_element* face = layout.face;
  if(vertex == nullptr)
    refuse("the PLY header declares no 'vertex' element");
  for(std::size_t i = 0; i < vertex->properties.size(); ++i)
    for(int k = 0; k < 3; ++k)
      if(vertex->properties[i].name == std::string(1, "xyz"[k]))
      {
        if(vertex->properties[i].is_list)
          refuse_at(vertex->header_line, "the vertex property " + vertex->properties[i].name + " is a list");
        layout.xyz[k] = static_cast<int>(i);
      }
  if(*std::min_element(layout.xyz.begin(), layout.xyz.end()) < 0)
    refuse_at(vertex->header_line, "the vertex element has no x, y and z properties");
  if(face != nullptr)
    for(std::size_t i = 0; i < face->properties.size(); ++i)
      if(face->properties[i].is_list &&
         (face->properties[i].name == "vertex_indices" || face->properties[i].name == "vertex_index"))
        layout.indices = static_cast<int>(i);
  if(face != nullptr && face->count > 0 && layout.indices < 0)
    refuse_at(face->header_line, "the face element has no list property 'vertex_indices'");
  if(vertex->count > limits.max_points || (face != nullptr && face->count > limits.max_polygons))
    refuse("the PLY header announces more vertices or faces than this reader takes");
  return layout;
}

/// Refuses elements that cannot all fit in what follows the header.
inline void check_ply_body_fits(const std::vector<Ply_element>& elements, Ply_encoding encoding, const Ply_body& body)
{
  std::size_t available = body.remaining_bytes();
  for(const Ply_element& e : elements)
  {
    const std::size_t each = e.min_bytes(encoding);
    check_fits(e.count, each, available, e.header_line, "'" + e.name + "' elements");
    available -= e.count * each;
  }
}

/// Reads one list property of element `i` of `e`; when it is the face's list of indices,
/// they go into `polygon`, each checked against the vertex count.
inline void read_ply_list(const Ply_element& e, std::size_t i, std::size_t pi, Ply_encoding encoding,
                          const Ply_soup_layout& layout, Ply_body& body, std::vector<std::size_t>& polygon)
{
  const Ply_property& p = e.properties[pi];
  const Ply_value_name what{e.name, i, p.name};
  const Ply_value_name count_name{e.name, i, p.name, " (list count)"};
  const std::size_t count = ply_index(body.value(p.count_type, count_name), body, count_name);
  const bool is_face_list = &e == layout.face && static_cast<int>(pi) == layout.indices;
  const std::size_t vertices = layout.vertex->count;
  // Each item takes at least its size (binary) or two bytes (ASCII).
  const std::size_t item_bytes = encoding == Ply_encoding::Ascii ? 2 : p.type.size;
  if(count > body.remaining_bytes() / item_bytes)
    refuse(body.where() + what.str() + ": a list of " + std::to_string(count) + " items runs past the end of the file");
  if(is_face_list)
  {
    if(count < 3)
      refuse(body.where() + "face " + std::to_string(i) + " has " + std::to_string(count) +
             " corner(s); a face needs at least 3");
    if(count > vertices)
      refuse(body.where() + "face " + std::to_string(i) + " announces " + std::to_string(count) +
             " corners but the file has only " + std::to_string(vertices) + " vertices");
    polygon.reserve(count);
  }
  for(std::size_t c = 0; c < count; ++c)
  {
    const Ply_value_name item_name{e.name, i, p.name, " item ", c};
    const double item = body.value(p.type, item_name);
    if(!is_face_list)
      continue;
    const std::size_t index = ply_index(item, body, item_name);
    if(index >= vertices)
      refuse(body.where() + "face " + std::to_string(i) + ": vertex index " + std::to_string(index) +
             " is out of range (the file has " + std::to_string(vertices) + " vertices)");
    polygon.push_back(index);
  }
}

/// Reads element `i` of `e`: a point when `e` is the vertex element, a polygon when it is the
/// face element, values read and dropped otherwise.
inline void read_ply_element(const Ply_element& e, std::size_t i, Ply_encoding encoding, const Ply_soup_layout& layout,
                             Ply_body& body, Polygon_soup& soup)
{
  std::array<double, 3> x{};
  std::vector<std::size_t> polygon;
  std::size_t polygon_line = 0;
  for(std::size_t pi = 0; pi < e.properties.size(); ++pi)
  {
    const Ply_property& p = e.properties[pi];
    if(p.is_list)
    {
      read_ply_list(e, i, pi, encoding, layout, body, polygon);
      if(&e == layout.face && static_cast<int>(pi) == layout.indices)
        polygon_line = body.line();
      continue;
    }
    const double value = body.value(p.type, Ply_value_name{e.name, i, p.name});
    if(&e == layout.vertex)
      for(int k = 0; k < 3; ++k)
        if(layout.xyz[k] == static_cast<int>(pi))
        {
          if(!std::isfinite(value))
            refuse(body.where() + "vertex " + std::to_string(i) + " has a non-finite coordinate");
          x[k] = value;
        }
  }
  if(&e == layout.vertex)
    soup.points.emplace_back(x[0], x[1], x[2]);
  else if(&e == layout.face)
  {
    soup.polygons.push_back(std::move(polygon));
    soup.polygon_lines.push_back(polygon_line);
  }
}

inline void read_ply(std::string_view text, Polygon_soup& soup, const Soup_reading_limits& limits)
{
  Text_lines lines(text);
  const Ply_header header = read_ply_header(lines, limits);
  const Ply_soup_layout layout = ply_soup_layout(header.elements, limits);
  const Ply_encoding encoding = *header.encoding;
  Ply_body body(text.substr(lines.position()), encoding, lines.number() + 1);
  check_ply_body_fits(header.elements, encoding, body);
  reserve_at_most(soup.points, layout.vertex->count, body.remaining_bytes(), 6);
  reserve_at_most(soup.polygons, layout.face ? layout.face->count : 0, body.remaining_bytes(), 8);
  for(const Ply_element& e : header.elements)
    for(std::size_t i = 0; i < e.count; ++i)
      read_ply_element(e, i, encoding, layout, body, soup);
}

} // namespace reading
} // namespace internal
} // namespace ICM

#endif // ICM_IO_READ_PLY_H
