// Copyright (c) the ICM authors.
//
// SVG pictures of UV layouts, coloured by area distortion, for the command-line tool, the demo
// and the benchmark comparisons (several methods side by side on one mesh).

#ifndef ICM_IO_WRITE_UV_SVG_H
#define ICM_IO_WRITE_UV_SVG_H

#include <ICM/IO/Uv_mesh.h>
#include <ICM/internal/Atomic_file.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace ICM {
namespace IO {

/// Appearance of the pictures written by `write_uv_svg()` and `write_uv_svg_panels()`.
struct Svg_options
{
  /// Side, in px, of the square each layout is fitted into (aspect ratio preserved).
  double size = 800.;
  /// Empty space, in px, between a layout and the border of its square.
  double margin = 20.;
  /// Faces are coloured by their log area ratio (see `log_area_ratios()`), from blue (shrunk)
  /// through white (0) to red (enlarged); the colour saturates at +/- this value.
  double log_ratio_range = 2.;
  /// Optional title written above the picture.
  std::string title;
  /// Whether to draw the colour bar.
  bool legend = true;
  /// Face edges are stroked up to this many faces per layout; beyond, they would only darken
  /// the picture and bloat the file, so faces are drawn filled only.
  std::size_t max_faces_with_edges = 20000;
};

} // namespace IO

namespace internal {

/// Escapes text for SVG element content and attribute values.
inline std::string svg_escape(const std::string& s)
{
  std::string out;
  out.reserve(s.size());
  for(char c : s)
  {
    switch(c)
    {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&#39;";
      break;
    default:
      out += c;
    }
  }
  return out;
}

/// Writes `x` rounded to 2 decimals, without trailing zeros and without "-0": exact,
/// independent of the stream's locale and flags, and short.
inline void put_coordinate(std::ostream& os, double x)
{
  long long r = std::llround(x * 100.);
  if(r < 0)
  {
    os << '-';
    r = -r;
  }
  os << r / 100;
  const int frac = static_cast<int>(r % 100);
  if(frac != 0)
  {
    os << '.' << static_cast<char>('0' + frac / 10);
    if(frac % 10 != 0)
      os << static_cast<char>('0' + frac % 10);
  }
}

/// Diverging blue - white - red colour map (the stops of ColorBrewer's RdBu) on t in [-1, 1].
inline std::array<int, 3> diverging_colour(double t)
{
  static const double stops[5][3] = {{33, 102, 172}, {146, 197, 222}, {255, 255, 255}, {244, 165, 130}, {178, 24, 43}};
  if(!(t >= -1.)) // also catches NaN
    t = (t > 0.) ? 1. : -1.;
  t = (std::min)(1., t);
  const double s = (t + 1.) * 2.; // in [0, 4]
  const int i = (std::min)(3, static_cast<int>(s));
  const double a = s - i;
  std::array<int, 3> rgb;
  for(int k = 0; k < 3; ++k)
    rgb[k] = static_cast<int>(std::lround((1. - a) * stops[i][k] + a * stops[i + 1][k]));
  return rgb;
}

inline void put_colour(std::ostream& os, const std::array<int, 3>& rgb)
{
  static const char hex[] = "0123456789abcdef";
  os << '#';
  for(int c : rgb)
    os << hex[(c >> 4) & 15] << hex[c & 15];
}

/// Where a layout goes in a square of a picture. A layout that came out mirrored (clockwise
/// overall) is not a defect of its faces: it is mirrored back, so that only faces oriented
/// against the majority count as flipped. The layout is fitted with its aspect ratio kept and
/// centred; one of (nearly) zero extent is drawn as a point rather than blown up to infinity.
struct Layout_fit
{
  double mirror = 1., umin = 0., vmax = 0., scale = 1., ox = 0., oy = 0.;
  /// The mean edge length on the picture, which sets how thick lines are drawn.
  double mean_edge = 0.;

  /// Picture coordinates of a UV, y down (as SVG and PNG have it) so that UV up is drawn up.
  std::array<double, 2> operator()(const std::array<double, 2>& t) const
  {
    return {ox + (mirror * t[0] - umin) * scale, oy + (vmax - t[1]) * scale};
  }
  /// Whether face `f` of `unit` (the layout at unit size) is flipped against the majority.
  bool flipped(const IO::Uv_mesh& unit, std::size_t f) const { return mirror * IO::uv_signed_area(unit, f) < 0.; }
};

/// Fits the layout of `m` (and `unit`, the same at unit size) into the square
/// [x0, x0 + size] x [y0, y0 + size], `margin` inside its border.
inline Layout_fit fit_layout(const IO::Uv_mesh& m, const IO::Uv_mesh& unit, double x0, double y0, double size,
                             double margin)
{
  const std::size_t nf = m.number_of_faces();
  Layout_fit fit;
  double total_signed = 0.;
  for(std::size_t f = 0; f < nf; ++f)
    total_signed += IO::uv_signed_area(unit, f);
  fit.mirror = total_signed < 0. ? -1. : 1.;

  double umin = std::numeric_limits<double>::infinity(), umax = -umin;
  double vmin = umin, vmax = -umin;
  double edge_sum = 0.;
  for(std::size_t f = 0; f < nf; ++f)
  {
    for(int k = 0; k < 3; ++k)
    {
      const auto& t = m.uvs[m.face_uvs[f][k]];
      const auto& s = m.uvs[m.face_uvs[f][(k + 1) % 3]];
      const double u = fit.mirror * t[0];
      umin = (std::min)(umin, u);
      umax = (std::max)(umax, u);
      vmin = (std::min)(vmin, t[1]);
      vmax = (std::max)(vmax, t[1]);
      edge_sum += std::hypot(s[0] - t[0], s[1] - t[1]);
    }
  }
  if(nf == 0)
    return fit;
  const double avail = (std::max)(0., size - 2. * margin);
  const double extent = (std::max)(umax - umin, vmax - vmin);
  const double scale = extent > 0. ? avail / extent : 1.;
  fit.scale = std::isfinite(scale) ? scale : 1.;
  fit.umin = umin;
  fit.vmax = vmax;
  fit.ox = x0 + margin + 0.5 * (avail - (umax - umin) * fit.scale);
  fit.oy = y0 + margin + 0.5 * (avail - (vmax - vmin) * fit.scale);
  fit.mean_edge = fit.scale * edge_sum / (3. * nf);
  return fit;
}

/// Draws one layout fitted into the square [x0, x0 + size] x [y0, y0 + size].
/// Returns the number of flipped faces.
inline std::size_t draw_layout(std::ostream& os, const IO::Uv_mesh& m, double x0, double y0, const IO::Svg_options& opt)
{
  const std::size_t nf = m.number_of_faces();
  const std::vector<double> ratios = IO::log_area_ratios(m);
  const IO::Uv_mesh unit = at_unit_size(m); // no overflow or underflow of the areas
  const Layout_fit fit = fit_layout(m, unit, x0, y0, opt.size, opt.margin);

  auto put_face = [&](std::size_t f) {
    os << "<polygon points=\"";
    for(int k = 0; k < 3; ++k)
    {
      const std::array<double, 2> p = fit(m.uvs[m.face_uvs[f][k]]);
      if(k > 0)
        os << ' ';
      put_coordinate(os, p[0]);
      os << ',';
      put_coordinate(os, p[1]);
    }
    os << '"';
  };

  // Hairlines scaled to the mean edge length on screen, so that small meshes get visible
  // edges and dense ones are not drowned in ink.
  const double stroke = (std::min)(0.8, (std::max)(0.1, 0.04 * fit.mean_edge));
  const bool edges = nf <= opt.max_faces_with_edges;

  os << "<g stroke=\"";
  if(edges)
  {
    os << "#333333\" stroke-width=\"";
    put_coordinate(os, stroke);
    os << "\" stroke-linejoin=\"round\">\n";
  }
  else
  {
    os << "none\">\n";
  }
  std::vector<std::size_t> flipped;
  for(std::size_t f = 0; f < nf; ++f)
  {
    if(fit.flipped(unit, f))
    {
      flipped.push_back(f);
      continue;
    }
    put_face(f);
    os << " fill=\"";
    put_colour(os, diverging_colour(ratios[f] / opt.log_ratio_range));
    os << "\"/>\n";
  }
  os << "</g>\n";

  // Flipped faces last, on top, in black with a bright outline so that even tiny ones show.
  if(!flipped.empty())
  {
    os << "<g fill=\"#000000\" stroke=\"#00ff00\" stroke-width=\"1\" "
          "stroke-linejoin=\"round\">\n";
    for(std::size_t f : flipped)
    {
      put_face(f);
      os << "/>\n";
    }
    os << "</g>\n";
  }
  return flipped.size();
}

inline bool check_svg_options(const IO::Svg_options& opt, std::string& reason)
{
  if(!(opt.size > 0.) || !std::isfinite(opt.size) || !(opt.margin >= 0.) || !(2. * opt.margin < opt.size))
  {
    reason = "invalid picture size or margin";
    return false;
  }
  if(!(opt.log_ratio_range > 0.) || !std::isfinite(opt.log_ratio_range))
  {
    reason = "the log ratio range must be positive";
    return false;
  }
  return true;
}

/// Where the parts of a picture of panels go: a title band, a band of panel names, the
/// squares of the layouts, the colour bar.
struct Svg_frame
{
  double title_h = 0., panel_title_h = 0., legend_h = 0., width = 0., height = 0.;

  Svg_frame(const std::vector<std::pair<std::string, const IO::Uv_mesh*>>& panels, const IO::Svg_options& opt)
  {
    title_h = opt.title.empty() ? 0. : 40.;
    bool any_panel_title = false;
    for(const auto& p : panels)
      any_panel_title = any_panel_title || !p.first.empty();
    panel_title_h = any_panel_title ? 30. : 0.;
    legend_h = opt.legend ? 64. : 0.;
    width = opt.size * static_cast<double>((std::max)(std::size_t(1), panels.size()));
    height = title_h + panel_title_h + opt.size + legend_h;
  }
};

/// The `<svg>` element, a white background and the title.
inline void put_svg_start(std::ostream& os, const Svg_frame& frame, const IO::Svg_options& opt)
{
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 ";
  put_coordinate(os, frame.width);
  os << ' ';
  put_coordinate(os, frame.height);
  os << "\" width=\"";
  put_coordinate(os, frame.width);
  os << "\" height=\"";
  put_coordinate(os, frame.height);
  os << "\" font-family=\"sans-serif\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";

  if(!opt.title.empty())
  {
    os << "<text x=\"";
    put_coordinate(os, 0.5 * frame.width);
    os << "\" y=\"28\" font-size=\"22\" text-anchor=\"middle\">" << svg_escape(opt.title) << "</text>\n";
  }
}

/// Every layout in its square, with its name above it and its count of flipped faces.
/// Returns the flipped faces of all layouts.
inline std::size_t put_svg_panels(std::ostream& os,
                                  const std::vector<std::pair<std::string, const IO::Uv_mesh*>>& panels,
                                  const Svg_frame& frame, const IO::Svg_options& opt)
{
  std::size_t total_flipped = 0;
  for(std::size_t i = 0; i < panels.size(); ++i)
  {
    const double x0 = opt.size * static_cast<double>(i);
    const double y0 = frame.title_h + frame.panel_title_h;
    if(!panels[i].first.empty())
    {
      os << "<text x=\"";
      put_coordinate(os, x0 + 0.5 * opt.size);
      os << "\" y=\"";
      put_coordinate(os, frame.title_h + 22.);
      os << "\" font-size=\"18\" text-anchor=\"middle\">" << svg_escape(panels[i].first) << "</text>\n";
    }
    const std::size_t flipped = draw_layout(os, *panels[i].second, x0, y0, opt);
    total_flipped += flipped;
    if(flipped > 0)
    {
      os << "<text x=\"";
      put_coordinate(os, x0 + opt.size - 6.);
      os << "\" y=\"";
      put_coordinate(os, y0 + 16.);
      os << "\" font-size=\"13\" text-anchor=\"end\">" << flipped << " flipped face" << (flipped > 1 ? "s" : "")
         << "</text>\n";
    }
  }
  return total_flipped;
}

/// The colour bar below the panels, with its labels, and the key of flipped faces if any.
inline void put_svg_legend(std::ostream& os, const Svg_frame& frame, const IO::Svg_options& opt,
                           std::size_t total_flipped)
{
  const double width = frame.width;
  const double bar_w = (std::min)(400., 0.8 * width);
  const double bar_x = 0.5 * (width - bar_w);
  const double bar_y = frame.title_h + frame.panel_title_h + opt.size + 8.;
  const double r = opt.log_ratio_range;
  os << "<defs><linearGradient id=\"icm_log_area_ratio\" x1=\"0\" x2=\"1\" y1=\"0\" y2=\"0\">";
  for(int s = 0; s <= 8; ++s)
  {
    os << "<stop offset=\"" << s * 12.5 << "%\" stop-color=\"";
    put_colour(os, diverging_colour(-1. + s / 4.));
    os << "\"/>";
  }
  os << "</linearGradient></defs>\n";
  os << "<rect x=\"";
  put_coordinate(os, bar_x);
  os << "\" y=\"";
  put_coordinate(os, bar_y);
  os << "\" width=\"";
  put_coordinate(os, bar_w);
  os << "\" height=\"14\" fill=\"url(#icm_log_area_ratio)\" stroke=\"#222222\" "
        "stroke-width=\"0.5\"/>\n";
  const double label_y = bar_y + 30.;
  const std::pair<double, std::string> labels[3] = {{bar_x, "-" + internal::message_number(r, 3)},
                                                    {bar_x + 0.5 * bar_w, "0"},
                                                    {bar_x + bar_w, "+" + internal::message_number(r, 3)}};
  for(const auto& l : labels)
  {
    os << "<text x=\"";
    put_coordinate(os, l.first);
    os << "\" y=\"";
    put_coordinate(os, label_y);
    os << "\" font-size=\"13\" text-anchor=\"middle\">" << l.second << "</text>\n";
  }
  os << "<text x=\"";
  put_coordinate(os, 0.5 * width);
  os << "\" y=\"";
  put_coordinate(os, label_y + 18.);
  os << "\" font-size=\"13\" text-anchor=\"middle\">"
        "log(UV area / 3D area), UV scaled to the total 3D area</text>\n";
  if(total_flipped > 0)
  {
    os << "<rect x=\"";
    put_coordinate(os, bar_x + bar_w + 16.);
    os << "\" y=\"";
    put_coordinate(os, bar_y);
    os << "\" width=\"14\" height=\"14\" fill=\"#000000\" stroke=\"#00ff00\" "
          "stroke-width=\"1\"/>\n<text x=\"";
    put_coordinate(os, bar_x + bar_w + 36.);
    os << "\" y=\"";
    put_coordinate(os, bar_y + 12.);
    os << "\" font-size=\"13\">flipped</text>\n";
  }
}

inline bool write_svg_panels(std::ostream& os, const std::vector<std::pair<std::string, const IO::Uv_mesh*>>& panels,
                             const IO::Svg_options& opt)
{
  const Svg_frame frame(panels, opt);
  put_svg_start(os, frame, opt);
  const std::size_t total_flipped = put_svg_panels(os, panels, frame, opt);
  if(opt.legend)
    put_svg_legend(os, frame, opt, total_flipped);
  os << "</svg>\n";
  return static_cast<bool>(os);
}

inline bool write_svg_file(const std::string& path,
                           const std::vector<std::pair<std::string, const IO::Uv_mesh*>>& panels, std::string& error,
                           const IO::Svg_options& opt)
{
  std::string reason;
  if(!check_svg_options(opt, reason))
  {
    error = "cannot write '" + path + "': " + reason;
    return false;
  }
  for(const auto& p : panels)
  {
    if(!IO::is_valid_uv_mesh(*p.second, reason))
    {
      error =
        "cannot write '" + path + "': " + (p.first.empty() ? std::string() : "layout '" + p.first + "': ") + reason;
      return false;
    }
  }
  return write_file_atomically(
    path, [&](std::ostream& os) { return write_svg_panels(os, panels, opt); }, error);
}

} // namespace internal

namespace IO {

/// Writes an SVG picture of the UV layout of `m`: one `<polygon>` per face, filled by its log
/// area ratio (see `log_area_ratios()`; blue = shrunk, white = unchanged, red = enlarged,
/// saturated at +/- `opt.log_ratio_range`), with thin dark edges, UV up drawn up, fitted into
/// a square of `opt.size` px, plus an optional title above and a colour bar below.
///
/// If the layout is clockwise overall it is mirrored first; faces still oriented the other
/// way are flipped faces and are drawn in black with a bright green outline, on top.
///
/// The file is replaced atomically: on failure (invalid mesh or options, I/O error) `path` is
/// left untouched, `error` gets a one-line reason and the function returns false.
inline bool write_uv_svg(const std::string& path, const Uv_mesh& m, std::string& error,
                         const Svg_options& opt = Svg_options())
{
  return internal::write_svg_file(path, {{std::string(), &m}}, error, opt);
}

/// Writes the SVG picture of `m` (see the overload on a path) to `os`. Returns false with
/// `error` naming the reason when the options or the mesh are invalid, or the stream failed;
/// for an output written together with others, all or nothing (`write_uv_files()`).
inline bool write_uv_svg(std::ostream& os, const Uv_mesh& m, std::string& error, const Svg_options& opt = Svg_options())
{
  if(!internal::check_svg_options(opt, error) || !is_valid_uv_mesh(m, error))
    return false;
  if(!internal::write_svg_panels(os, {{std::string(), &m}}, opt))
  {
    error = "output error";
    return false;
  }
  error.clear();
  return true;
}

/// Like `write_uv_svg()`, for several layouts side by side (e.g. ICM, LSCM and ARAP on the
/// same mesh), each in its own square with its name above it, and one shared colour bar.
/// Each layout is fitted to its square independently; the colours do not depend on the scale
/// of a layout, so they compare across panels.
inline bool write_uv_svg_panels(const std::string& path, const std::vector<std::pair<std::string, Uv_mesh>>& panels,
                                std::string& error, const Svg_options& opt = Svg_options())
{
  std::vector<std::pair<std::string, const Uv_mesh*>> refs;
  refs.reserve(panels.size());
  for(const auto& p : panels)
    refs.emplace_back(p.first, &p.second);
  return internal::write_svg_file(path, refs, error, opt);
}

} // namespace IO
} // namespace ICM

#endif // ICM_IO_WRITE_UV_SVG_H
