// Copyright (c) the ICM authors.
//
// PNG pictures of a parameterization: the UV layout coloured by log area ratio (the SVG's
// picture, at a fixed size whatever the mesh), and the surface seen from a fixed camera with a
// checkerboard through its UVs, which is how people judge a parameterization at a glance:
// squares stay square where the map is conformal, keep their size where it preserves area,
// and break along the seams.
//
// Needs stb_image_write (Debian's libstb-dev, whose libstb carries the implementation: ICM is
// header only and has no translation unit to compile it in); ICM's CMake package links it into
// ICM::ICM when found and defines ICM_HAS_STB_IMAGE_WRITE. The triangles are drawn by the small
// rasterizer below, supersampled and box-filtered down, so that a million faces still give a
// picture of the requested size and a file of a few hundred kilobytes.

#ifndef ICM_IO_WRITE_UV_PNG_H
#define ICM_IO_WRITE_UV_PNG_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/IO/write_uv_svg.h>
#include <ICM/internal/Atomic_file.h>

#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function" // stb_easy_font's functions are static
#endif
#include <stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <unordered_set>
#include <vector>

namespace ICM {
namespace IO {

/// Appearance of the layout picture written by `write_uv_png()`.
struct Png_options
{
  /// Side, in pixels, of the square the layout is fitted into (the colour bar adds a band below).
  int size = 1024;
  /// Empty space, in pixels, between the layout and the border of its square.
  int margin = 16;
  /// Faces are coloured by their log area ratio as in the SVG (blue shrunk, white unchanged,
  /// red enlarged), saturated at +/- this value.
  double log_ratio_range = 2.;
  /// Whether to draw the colour bar and its labels.
  bool legend = true;
};

/// Camera and texture of the surface picture written by `write_uv_preview_png()`.
struct Preview_options
{
  /// Width and height of the picture, in pixels.
  int size = 1024;
  /// Squares of the checkerboard along the side of a square of the layout's total area: about
  /// `checks`² squares cover the surface wherever the map preserves area.
  double checks = 24.;
  /// The camera looks at the mesh's centre from this direction of the mesh's own axes, turned
  /// from +z by `yaw` degrees about +y and raised by `pitch` degrees, +y up on the picture
  /// (the convention of most scanned and modelled meshes); orthographic, lit from the camera.
  double yaw = 30.;
  double pitch = 20.;
};

} // namespace IO

namespace internal {

using Rgb = std::array<std::uint8_t, 3>;

/// A picture being drawn: RGB pixels, and a depth per pixel for the surface picture.
struct Raster
{
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  std::vector<float> depth;

  Raster(int w, int h, const Rgb& background) : width(w), height(h), rgb(3 * std::size_t(w) * h)
  {
    for(std::size_t i = 0; i < rgb.size(); i += 3)
      std::copy(background.begin(), background.end(), rgb.begin() + i);
  }
  void put(int x, int y, const Rgb& c)
  {
    std::copy(c.begin(), c.end(), rgb.begin() + 3 * (std::size_t(y) * width + x));
  }
};

/// Calls `shade(x, y, b)` for every pixel whose centre lies in the triangle `p` (either
/// orientation), with `b` the barycentric coordinates of that centre. Pixels on an edge shared
/// by two triangles are drawn by both, so that no crack shows between them.
template <class Shade>
void fill_triangle(const Raster& raster, const std::array<std::array<double, 2>, 3>& p, Shade&& shade)
{
  const double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
  if(!(std::abs(area) > 0.) || !std::isfinite(area))
    return;
  const double xmin = (std::min)({p[0][0], p[1][0], p[2][0]}), xmax = (std::max)({p[0][0], p[1][0], p[2][0]});
  const double ymin = (std::min)({p[0][1], p[1][1], p[2][1]}), ymax = (std::max)({p[0][1], p[1][1], p[2][1]});
  const int x0 = (std::max)(0, static_cast<int>(std::ceil(xmin - 0.5)));
  const int x1 = (std::min)(raster.width - 1, static_cast<int>(std::floor(xmax - 0.5)));
  const int y0 = (std::max)(0, static_cast<int>(std::ceil(ymin - 0.5)));
  const int y1 = (std::min)(raster.height - 1, static_cast<int>(std::floor(ymax - 0.5)));
  for(int y = y0; y <= y1; ++y)
  {
    const double cy = y + 0.5;
    for(int x = x0; x <= x1; ++x)
    {
      const double cx = x + 0.5;
      std::array<double, 3> b;
      for(int k = 0; k < 3; ++k)
      {
        const auto& s = p[(k + 1) % 3];
        const auto& t = p[(k + 2) % 3];
        b[k] = ((t[0] - s[0]) * (cy - s[1]) - (t[1] - s[1]) * (cx - s[0])) / area;
      }
      if(b[0] >= 0. && b[1] >= 0. && b[2] >= 0.)
        shade(x, y, b);
    }
  }
}

/// A segment `width` pixels wide, as two triangles.
inline void draw_segment(Raster& raster, const std::array<double, 2>& a, const std::array<double, 2>& b, double width,
                         const Rgb& colour)
{
  const double dx = b[0] - a[0], dy = b[1] - a[1], length = std::hypot(dx, dy);
  if(!(length > 0.))
    return;
  const double nx = -dy / length * width / 2, ny = dx / length * width / 2;
  const std::array<double, 2> q[4] = {
    {a[0] + nx, a[1] + ny}, {b[0] + nx, b[1] + ny}, {b[0] - nx, b[1] - ny}, {a[0] - nx, a[1] - ny}};
  const auto put = [&](int x, int y, const std::array<double, 3>&) { raster.put(x, y, colour); };
  fill_triangle(raster, {q[0], q[1], q[2]}, put);
  fill_triangle(raster, {q[0], q[2], q[3]}, put);
}

inline void fill_box(Raster& raster, double x0, double y0, double x1, double y1, const Rgb& colour)
{
  const auto put = [&](int x, int y, const std::array<double, 3>&) { raster.put(x, y, colour); };
  fill_triangle(raster, {{{x0, y0}, {x1, y0}, {x1, y1}}}, put);
  fill_triangle(raster, {{{x0, y0}, {x1, y1}, {x0, y1}}}, put);
}

/// Writes `text` with its top left corner at (x, y), in stb_easy_font's characters (about 7
/// units high) magnified `scale` times.
inline void draw_text(Raster& raster, double x, double y, const std::string& text, double scale, const Rgb& colour)
{
  std::vector<char> characters(text.begin(), text.end());
  characters.push_back('\0');
  std::vector<float> quads(64 * (text.size() + 1) * 4); // 4 vertices of 4 floats per quad
  unsigned char rgba[4] = {colour[0], colour[1], colour[2], 255};
  const int count = stb_easy_font_print(0.f, 0.f, characters.data(), rgba, quads.data(),
                                        static_cast<int>(quads.size() * sizeof(float)));
  for(int q = 0; q < count; ++q)
  {
    const float* corner = &quads[16 * std::size_t(q)]; // the first and third vertices span it
    fill_box(raster, x + scale * corner[0], y + scale * corner[1], x + scale * corner[8], y + scale * corner[9],
             colour);
  }
}

/// Width of `text` as `draw_text` writes it.
inline double text_width(const std::string& text, double scale)
{
  std::vector<char> characters(text.begin(), text.end());
  characters.push_back('\0');
  return scale * stb_easy_font_width(characters.data());
}

/// `raster` shrunk `factor` times by averaging each factor x factor block: the supersampled
/// picture's anti-aliasing.
inline Raster downsampled(const Raster& raster, int factor)
{
  Raster small(raster.width / factor, raster.height / factor, Rgb{0, 0, 0});
  for(int y = 0; y < small.height; ++y)
    for(int x = 0; x < small.width; ++x)
    {
      std::array<int, 3> sum = {0, 0, 0};
      for(int j = 0; j < factor; ++j)
        for(int i = 0; i < factor; ++i)
          for(int k = 0; k < 3; ++k)
            sum[k] += raster.rgb[3 * (std::size_t(y * factor + j) * raster.width + x * factor + i) + k];
      const int n = factor * factor;
      small.put(x, y,
                Rgb{static_cast<std::uint8_t>((sum[0] + n / 2) / n), static_cast<std::uint8_t>((sum[1] + n / 2) / n),
                    static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
    }
  return small;
}

/// Encodes `raster` as PNG onto `os`.
inline bool write_png(std::ostream& os, const Raster& raster)
{
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
  };
  return stbi_write_png_to_func(append, &os, raster.width, raster.height, 3, raster.rgb.data(), 3 * raster.width) !=
           0 &&
         static_cast<bool>(os);
}

/// Pictures are drawn this many times larger in each direction, then averaged down.
constexpr int picture_supersampling = 3;
/// The largest side a picture may have (a 16k x 16k RGB picture is 768 MB supersampled 1x).
constexpr int picture_max_size = 8192;

inline bool check_picture_size(int size, int margin, std::string& reason)
{
  if(size < 16 || size > picture_max_size)
  {
    reason = "the picture size must be between 16 and " + std::to_string(picture_max_size) + " pixels, not " +
             std::to_string(size);
    return false;
  }
  if(margin < 0 || 2 * margin >= size)
  {
    reason = "the picture margin must be at least 0 and less than half its size";
    return false;
  }
  return true;
}

inline bool check_png_options(const IO::Png_options& opt, std::string& reason)
{
  if(!check_picture_size(opt.size, opt.margin, reason))
    return false;
  if(!(opt.log_ratio_range > 0.) || !std::isfinite(opt.log_ratio_range))
  {
    reason = "the log ratio range must be positive";
    return false;
  }
  return true;
}

inline bool check_preview_options(const IO::Preview_options& opt, std::string& reason)
{
  if(!check_picture_size(opt.size, 0, reason))
    return false;
  if(!(opt.checks > 0.) || !(opt.checks <= 10000.))
  {
    reason = "the checkerboard must have between 0 and 10000 squares a side";
    return false;
  }
  if(!std::isfinite(opt.yaw) || !std::isfinite(opt.pitch) || std::abs(opt.pitch) > 90.)
  {
    reason = "the camera's yaw must be finite and its pitch within [-90, 90] degrees";
    return false;
  }
  return true;
}

/// The UV edges on one side only (a chart's border, a seam's side), as pairs of UV indices.
inline std::vector<std::array<int, 2>> uv_border_edges(const IO::Uv_mesh& m)
{
  const auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  std::unordered_set<std::uint64_t> directed;
  directed.reserve(3 * m.number_of_faces());
  for(const auto& f : m.face_uvs)
    for(int k = 0; k < 3; ++k)
      directed.insert(key(f[k], f[(k + 1) % 3]));
  std::vector<std::array<int, 2>> border;
  for(const auto& f : m.face_uvs)
    for(int k = 0; k < 3; ++k)
      if(directed.count(key(f[(k + 1) % 3], f[k])) == 0)
        border.push_back({f[k], f[(k + 1) % 3]});
  return border;
}

/// The colour bar under the layout, its labels and caption, and the key of flipped faces.
inline void draw_png_legend(Raster& raster, double top, double unit, double range, std::size_t flipped)
{
  const Rgb ink = {34, 34, 34};
  const double bar_w = 0.6 * raster.width, bar_x = 0.5 * (raster.width - bar_w), bar_h = 14 * unit;
  for(int x = static_cast<int>(bar_x); x < static_cast<int>(bar_x + bar_w); ++x)
  {
    const std::array<int, 3> c = diverging_colour(2. * (x + 0.5 - bar_x) / bar_w - 1.);
    fill_box(raster, x, top, x + 1, top + bar_h, Rgb{std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2])});
  }
  const std::string caption = "log(UV area / 3D area), UV scaled to the total 3D area";
  const double text = (std::min)(2 * unit, 0.95 * raster.width / text_width(caption, 1.));
  const double label_y = top + bar_h + 6 * unit;
  const std::string r = message_number(range, 3);
  const std::pair<double, std::string> labels[3] = {
    {bar_x, "-" + r}, {bar_x + 0.5 * bar_w, "0"}, {bar_x + bar_w, "+" + r}};
  for(const auto& [x, label] : labels)
    draw_text(raster, x - 0.5 * text_width(label, text), label_y, label, text, ink);
  draw_text(raster, 0.5 * (raster.width - text_width(caption, text)), label_y + 18 * unit, caption, text, ink);
  if(flipped > 0)
  {
    const double x = bar_x + bar_w + 12 * unit;
    fill_box(raster, x, top, x + bar_h, top + bar_h, Rgb{0, 255, 0});
    fill_box(raster, x + unit, top + unit, x + bar_h - unit, top + bar_h - unit, Rgb{0, 0, 0});
    const std::string key = std::to_string(flipped) + " flipped";
    draw_text(raster, x + bar_h + 6 * unit, top + 2 * unit, key, text, ink);
  }
}

/// The layout picture, supersampled (see `IO::write_uv_png()`).
inline Raster draw_png_layout(const IO::Uv_mesh& m, const IO::Png_options& opt)
{
  const int s = picture_supersampling;
  const double unit = s; // one pixel of the final picture
  const int legend_h = opt.legend ? 64 : 0;
  Raster raster(s * opt.size, s * (opt.size + legend_h), Rgb{255, 255, 255});
  const IO::Uv_mesh unit_mesh = at_unit_size(m);
  const Layout_fit fit = fit_layout(m, unit_mesh, 0., 0., s * opt.size, s * opt.margin);
  const std::vector<double> ratios = IO::log_area_ratios(m);
  const auto corners = [&](const std::array<int, 3>& f) {
    return std::array<std::array<double, 2>, 3>{fit(m.uvs[f[0]]), fit(m.uvs[f[1]]), fit(m.uvs[f[2]])};
  };

  std::vector<std::size_t> flipped;
  for(std::size_t f = 0; f < m.number_of_faces(); ++f)
  {
    if(fit.flipped(unit_mesh, f))
    {
      flipped.push_back(f);
      continue;
    }
    const std::array<int, 3> c = diverging_colour(ratios[f] / opt.log_ratio_range);
    const Rgb colour = {std::uint8_t(c[0]), std::uint8_t(c[1]), std::uint8_t(c[2])};
    fill_triangle(raster, corners(m.face_uvs[f]),
                  [&](int x, int y, const std::array<double, 3>&) { raster.put(x, y, colour); });
  }
  // Face edges only where they are far enough apart to show the mesh rather than darken it.
  if(fit.mean_edge >= 8 * unit)
    for(const auto& f : m.face_uvs)
      for(int k = 0; k < 3; ++k)
        draw_segment(raster, fit(m.uvs[f[k]]), fit(m.uvs[f[(k + 1) % 3]]), 0.5 * unit, Rgb{120, 120, 120});
  for(const auto& e : uv_border_edges(m))
    draw_segment(raster, fit(m.uvs[e[0]]), fit(m.uvs[e[1]]), 1.2 * unit, Rgb{34, 34, 34});
  // Flipped faces on top, black in a green outline wide enough for the smallest to show.
  for(std::size_t f : flipped)
  {
    const auto p = corners(m.face_uvs[f]);
    for(int k = 0; k < 3; ++k)
      draw_segment(raster, p[k], p[(k + 1) % 3], 3 * unit, Rgb{0, 255, 0});
    fill_triangle(raster, p, [&](int x, int y, const std::array<double, 3>&) { raster.put(x, y, Rgb{0, 0, 0}); });
  }
  if(opt.legend)
    draw_png_legend(raster, s * (opt.size + 4.), unit, opt.log_ratio_range, flipped.size());
  return raster;
}

/// Per position, the area-weighted normal of its faces (not normalized).
inline std::vector<std::array<double, 3>> position_normals(const IO::Uv_mesh& m)
{
  std::vector<std::array<double, 3>> normals(m.positions.size(), {0., 0., 0.});
  for(const auto& f : m.face_positions)
  {
    const auto &a = m.positions[f[0]], &b = m.positions[f[1]], &c = m.positions[f[2]];
    const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for(int v : f)
      for(int k = 0; k < 3; ++k)
        normals[v][k] += n[k];
  }
  return normals;
}

/// The surface picture, supersampled (see `IO::write_uv_preview_png()`).
inline Raster draw_png_preview(const IO::Uv_mesh& m, const IO::Preview_options& opt)
{
  const int s = picture_supersampling;
  Raster raster(s * opt.size, s * opt.size, Rgb{255, 255, 255});
  raster.depth.assign(std::size_t(raster.width) * raster.height, std::numeric_limits<float>::infinity());
  const IO::Uv_mesh unit = at_unit_size(m); // the camera and the checks at any scale

  // The camera's frame in the mesh's axes: `back` points from the mesh to the camera.
  const double yaw = opt.yaw * M_PI / 180, pitch = opt.pitch * M_PI / 180;
  const std::array<double, 3> back = {std::sin(yaw) * std::cos(pitch), std::sin(pitch),
                                      std::cos(yaw) * std::cos(pitch)};
  const std::array<double, 3> right = {std::cos(yaw), 0., -std::sin(yaw)};
  const std::array<double, 3> up = {-std::sin(yaw) * std::sin(pitch), std::cos(pitch),
                                    -std::cos(yaw) * std::sin(pitch)};
  const auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };

  // Fit the projected bounding box into the picture.
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for(const auto& p : unit.positions)
  {
    xmin = (std::min)(xmin, dot(p, right)), xmax = (std::max)(xmax, dot(p, right));
    ymin = (std::min)(ymin, dot(p, up)), ymax = (std::max)(ymax, dot(p, up));
  }
  const double avail = 0.92 * raster.width, extent = (std::max)(xmax - xmin, ymax - ymin);
  const double scale = extent > 0. ? avail / extent : 1.;
  const double ox = 0.5 * (raster.width - (xmax - xmin) * scale), oy = 0.5 * (raster.height - (ymax - ymin) * scale);

  double uv_area = 0.;
  for(std::size_t f = 0; f < unit.number_of_faces(); ++f)
    uv_area += std::abs(IO::uv_signed_area(unit, f));
  const double period = uv_area > 0. ? std::sqrt(uv_area) / opt.checks : 1.;
  const std::vector<std::array<double, 3>> normals = position_normals(unit);
  const Rgb light = {242, 242, 242}, dark = {214, 96, 77};

  for(std::size_t f = 0; f < unit.number_of_faces(); ++f)
  {
    const auto& fp = unit.face_positions[f];
    const auto& ft = unit.face_uvs[f];
    std::array<std::array<double, 2>, 3> screen;
    std::array<double, 3> depth;
    for(int k = 0; k < 3; ++k)
    {
      const auto& p = unit.positions[fp[k]];
      screen[k] = {ox + (dot(p, right) - xmin) * scale, oy + (ymax - dot(p, up)) * scale};
      depth[k] = -dot(p, back);
    }
    fill_triangle(raster, screen, [&](int x, int y, const std::array<double, 3>& b) {
      const float z = static_cast<float>(b[0] * depth[0] + b[1] * depth[1] + b[2] * depth[2]);
      float& nearest = raster.depth[std::size_t(y) * raster.width + x];
      if(!(z < nearest))
        return;
      nearest = z;
      std::array<double, 3> n = {0., 0., 0.};
      double u = 0., v = 0.;
      for(int k = 0; k < 3; ++k)
      {
        for(int i = 0; i < 3; ++i)
          n[i] += b[k] * normals[fp[k]][i];
        u += b[k] * unit.uvs[ft[k]][0];
        v += b[k] * unit.uvs[ft[k]][1];
      }
      const double length = std::sqrt(dot(n, n));
      const double lit = length > 0. ? std::abs(dot(n, back)) / length : 1.; // two-sided, from the camera
      const double shade = 0.3 + 0.7 * lit;
      const bool odd =
        ((static_cast<long long>(std::floor(u / period)) + static_cast<long long>(std::floor(v / period))) & 1) != 0;
      const Rgb& c = odd ? dark : light;
      raster.put(x, y,
                 Rgb{static_cast<std::uint8_t>(std::lround(shade * c[0])),
                     static_cast<std::uint8_t>(std::lround(shade * c[1])),
                     static_cast<std::uint8_t>(std::lround(shade * c[2]))});
    });
  }
  return raster;
}

/// The layout picture (`IO::write_uv_png()`) encoded onto `os`.
inline bool put_layout_png(std::ostream& os, const IO::Uv_mesh& m, const IO::Png_options& opt)
{
  return write_png(os, downsampled(draw_png_layout(m, opt), picture_supersampling));
}

/// The surface picture (`IO::write_uv_preview_png()`) encoded onto `os`.
inline bool put_preview_png(std::ostream& os, const IO::Uv_mesh& m, const IO::Preview_options& opt)
{
  return write_png(os, downsampled(draw_png_preview(m, opt), picture_supersampling));
}

/// Writes the picture `put` encodes of `m` to `path`, atomically, after `check` accepted the
/// options and `m` was found valid; otherwise `error` names the reason and nothing is written.
template <class Options, class Check, class Put>
bool write_png_file(const std::string& path, const IO::Uv_mesh& m, std::string& error, const Options& opt, Check check,
                    Put put)
{
  std::string reason;
  if(!check(opt, reason) || !IO::is_valid_uv_mesh(m, reason))
  {
    error = "cannot write '" + path + "': " + reason;
    return false;
  }
  return write_file_atomically(
    path, [&](std::ostream& os) { return put(os, m, opt); }, error);
}

} // namespace internal

namespace IO {

/// Writes a PNG picture of the UV layout of `m`, `opt.size` pixels square plus a colour bar
/// below: faces filled by their log area ratio (`log_area_ratios()`; blue shrunk, white
/// unchanged, red enlarged, saturated at +/- `opt.log_ratio_range`), chart borders and seam
/// sides in dark grey, face edges where they are at least 8 pixels long, and flipped faces in
/// black with a green outline, on top. A layout that is clockwise overall is mirrored first, as
/// in `write_uv_svg()`. Anti-aliased by 3 x 3 supersampling.
///
/// The file is replaced atomically: on failure (invalid mesh or options, I/O error) `path` is
/// left untouched, `error` gets a one-line reason and the function returns false.
inline bool write_uv_png(const std::string& path, const Uv_mesh& m, std::string& error,
                         const Png_options& opt = Png_options())
{
  return internal::write_png_file(path, m, error, opt, internal::check_png_options, internal::put_layout_png);
}

/// Writes a PNG picture of the surface of `m` textured with a checkerboard through its UVs,
/// seen from the camera of `opt` (orthographic, lit from the camera, both sides of a face lit
/// alike). The checks have the same size in UV everywhere, so the picture shows at a glance how
/// the map distorts angles (squares turn into diamonds) and area (squares change size), and where
/// the seams run. Written atomically, with the same failure contract as `write_uv_png()`.
inline bool write_uv_preview_png(const std::string& path, const Uv_mesh& m, std::string& error,
                                 const Preview_options& opt = Preview_options())
{
  return internal::write_png_file(path, m, error, opt, internal::check_preview_options, internal::put_preview_png);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_PNG_H
