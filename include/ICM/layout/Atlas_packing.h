// Atlas mode: every chart into the unit square [0, 1]^2 of a SIZE x SIZE texture, at one texel
// density, with at least `padding` texels between charts and from the square's border.
//
// Padding is counted in texels, so it does not scale with the charts: the charts' boxes are
// inflated by padding / SIZE in UV units after scaling, and the scale is the largest one at
// which the inflated boxes still pack into the square. That scale is found by bisection, each
// trial one packing in texel units (the packers work on integers: a chart's box is rounded up
// to whole texels, so every chart lies inside its texel rectangle). Packing heuristics are not
// monotone in the scale (a larger scale can pack where a smaller one failed), so the bisection
// keeps the largest scale that packed, which is what it returns.
//
// Two packers of the boxes: today's shelves (Chart_packing.h), rows as wide as the square,
// and the skyline packer of stb_rect_pack.h (Debian's libstb-dev), used when ICM was
// configured with it (ICM_HAS_STB_RECT_PACK). On the shared meshes they tie: one or two charts
// far larger than the rest span the square and set the scale, and both fit the rest beside
// them. Where many charts of like sizes share the square the skyline covers more of it, so it
// is the default when present (doc/benchmarks.md, Atlas packing).

#ifndef ICM_LAYOUT_ATLAS_PACKING_H
#define ICM_LAYOUT_ATLAS_PACKING_H

#include <ICM/Options.h>
#include <ICM/Status.h>
#include <ICM/layout/Chart_packing.h>

#ifdef ICM_HAS_STB_RECT_PACK
#ifndef STB_INCLUDE_STB_RECT_PACK_H
// Header-only ICM compiles stb's implementation into each translation unit that packs an
// atlas, as static functions, so that no user source has to define it. A program that
// includes stb_rect_pack.h itself before ICM uses its own implementation instead.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#define STBRP_STATIC
#define STB_RECT_PACK_IMPLEMENTATION
#include <stb_rect_pack.h>
#undef STB_RECT_PACK_IMPLEMENTATION
#pragma GCC diagnostic pop
#else
#include <stb_rect_pack.h>
#endif
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace ICM {

/// Where the charts go in the atlas: chart `i`'s point p goes to `placements[i](scale * p)`,
/// in [0, 1]^2.
struct Atlas_packing
{
  std::vector<Chart_placement> placements;
  double scale = 0; ///< UV units of the atlas per unit of the boxes (one for every chart)
  int rotated_charts = 0;
};

namespace internal {

/// One chart's box as a packer sees it, in texels: the chart's extent rounded up plus the
/// padding, on its right and top (the square's left and bottom padding are kept out of the
/// bin), so that two rectangles that touch leave `padding` texels between their charts.
struct Texel_rect
{
  int chart;
  int width, height; ///< padded
  bool rotated;
  int x = 0, y = 0; ///< lower left corner in the bin, once packed
};

/// How the charts are turned in one trial.
enum class Chart_turn
{
  None,
  Flat,   ///< every chart wider than tall
  Upright ///< every chart taller than wide
};

/// A chart's extent in whole texels at `texels_per_unit`, at least one: a zero-size chart
/// still takes a texel, so that its padding is kept. The extent is rounded up less a hair
/// (1e-9 texel) so that the largest chart at the largest scale, exactly the bin's width,
/// does not round to one texel more.
inline int texel_extent(double extent, double texels_per_unit)
{
  const double texels = extent * texels_per_unit;
  return std::max(1, static_cast<int>(std::ceil(texels - 1e-9)));
}

inline std::vector<Texel_rect> texel_rects(const std::vector<Chart_box>& boxes, double texels_per_unit, int padding,
                                           Chart_turn turn)
{
  std::vector<Texel_rect> rects;
  for(std::size_t i = 0; i < boxes.size(); ++i)
  {
    const Chart_box& b = boxes[i];
    if(is_empty_box(b))
      continue;
    const double w = b[2] - b[0], h = b[3] - b[1];
    const bool rotated = (turn == Chart_turn::Flat && h > w) || (turn == Chart_turn::Upright && w > h);
    const int tw = texel_extent(rotated ? h : w, texels_per_unit), th = texel_extent(rotated ? w : h, texels_per_unit);
    rects.push_back({static_cast<int>(i), tw + padding, th + padding, rotated});
  }
  return rects;
}

/// Today's shelves (`fill_shelves`: tallest first, left to right, a new row above the tallest
/// rectangle of the last one), rows as wide as the `bin` x `bin` square. Whether every
/// rectangle fits. Texel counts are exact in doubles.
inline bool shelf_pack_rects(std::vector<Texel_rect>& rects, int bin)
{
  std::vector<Chart_box> padded;
  for(const Texel_rect& r : rects)
    padded.push_back({0.0, 0.0, static_cast<double>(r.width), static_cast<double>(r.height)});
  const Chart_packing packing = fill_shelves(padded, sorted_items(padded, false), bin, 0.0);
  if(packing.width > bin || packing.height > bin)
    return false;
  for(std::size_t i = 0; i < rects.size(); ++i)
  {
    rects[i].x = static_cast<int>(std::lround(packing.placements[i].offset[0]));
    rects[i].y = static_cast<int>(std::lround(packing.placements[i].offset[1]));
  }
  return true;
}

#ifdef ICM_HAS_STB_RECT_PACK
/// stb_rect_pack's skyline packer in a `bin` x `bin` square, with one node per texel column
/// (stb's condition for widths not to be rounded up): bottom-left first, then best-fit (the
/// lowest waste under each rectangle), which fits some sets the first does not.
inline bool skyline_pack_rects(std::vector<Texel_rect>& rects, int bin)
{
  if(rects.empty())
    return true;
  std::vector<stbrp_node> nodes(static_cast<std::size_t>(bin));
  std::vector<stbrp_rect> packed(rects.size());
  for(int heuristic : {STBRP_HEURISTIC_Skyline_BL_sortHeight, STBRP_HEURISTIC_Skyline_BF_sortHeight})
  {
    stbrp_context context;
    stbrp_init_target(&context, bin, bin, nodes.data(), bin);
    stbrp_setup_heuristic(&context, heuristic);
    for(std::size_t i = 0; i < rects.size(); ++i)
    {
      packed[i] = stbrp_rect();
      packed[i].id = static_cast<int>(i);
      packed[i].w = rects[i].width;
      packed[i].h = rects[i].height;
    }
    if(!stbrp_pack_rects(&context, packed.data(), static_cast<int>(packed.size())))
      continue;
    for(const stbrp_rect& p : packed)
    {
      rects[p.id].x = p.x;
      rects[p.id].y = p.y;
    }
    return true;
  }
  return false;
}
#endif

inline bool pack_rects(std::vector<Texel_rect>& rects, int bin, Atlas_packer packer)
{
#ifdef ICM_HAS_STB_RECT_PACK
  if(packer == Atlas_packer::Skyline)
    return skyline_pack_rects(rects, bin);
#endif
  return shelf_pack_rects(rects, bin);
}

/// One trial: the charts at `texels_per_unit`, packed with the first way of turning them that
/// fits (all flat, as they are, all upright; without rotation only as they are). Unset when
/// none fits.
inline std::optional<std::vector<Texel_rect>> pack_at(const std::vector<Chart_box>& boxes, double texels_per_unit,
                                                      const Atlas_options& options)
{
  const int bin = options.size - options.padding;
  for(Chart_turn turn : {Chart_turn::Flat, Chart_turn::None, Chart_turn::Upright})
  {
    if(!options.allow_rotation && turn != Chart_turn::None)
      continue;
    std::vector<Texel_rect> rects = texel_rects(boxes, texels_per_unit, options.padding, turn);
    if(pack_rects(rects, bin, options.packer))
      return rects;
  }
  return std::nullopt;
}

} // namespace internal

/// Packs charts given by their bounding boxes into the unit square of an `options.size`
/// texture, all at one scale, the largest that the packer fits to 1e-6 (relative), at least
/// `options.padding` texels apart and from the border. Placement `i` is for box `i`; an empty
/// box gets the identity.
/// \returns `ERROR_WRONG_PARAMETER` for options out of range, or when the charts do not fit
///          even at one texel each (too many charts for the padding); a non-finite box is an
///          `std::invalid_argument` as for the shelves.
inline Status pack_atlas(const std::vector<Chart_box>& boxes, const Atlas_options& options, Atlas_packing& packing)
{
  if(const Status checked = check_options(options); !checked.ok())
    return checked;
  internal::check_boxes(boxes);
  packing = Atlas_packing();
  packing.placements.assign(boxes.size(), Chart_placement());
  const int inner = options.size - 2 * options.padding; // texels inside the border
  const double largest = internal::largest_side(boxes);
  // Texels per unit of the boxes: the largest chart alone spans the inner square at `high`.
  double low = 0, high = largest > 0 ? inner / largest : 1.0;
  std::optional<std::vector<internal::Texel_rect>> best = internal::pack_at(boxes, high, options);
  if(best)
    low = high;
  else
  {
    best = internal::pack_at(boxes, 0.0, options);
    if(!best)
      return Status::wrong_parameter("option atlas.padding = " + std::to_string(options.padding) + ": " +
                                     std::to_string(boxes.size()) + " charts of one texel each, " +
                                     std::to_string(options.padding) + " texels apart, do not fit in a " +
                                     std::to_string(options.size) + " x " + std::to_string(options.size) + " atlas");
    while(high - low > 1e-6 * high)
    {
      const double middle = 0.5 * (low + high);
      std::optional<std::vector<internal::Texel_rect>> trial = internal::pack_at(boxes, middle, options);
      if(trial)
      {
        low = middle;
        best = std::move(trial);
      }
      else
        high = middle;
    }
  }
  const double texels_per_unit = low;
  packing.scale = texels_per_unit / options.size;
  for(const internal::Texel_rect& r : *best)
  {
    const Chart_box& b = boxes[r.chart];
    const Chart_box scaled{b[0] * packing.scale, b[1] * packing.scale, b[2] * packing.scale, b[3] * packing.scale};
    packing.placements[r.chart] =
      internal::placement_at(scaled, r.rotated, static_cast<double>(r.x + options.padding) / options.size,
                             static_cast<double>(r.y + options.padding) / options.size);
    packing.rotated_charts += r.rotated;
  }
  return Status::success();
}

/// The share of the unit square that triangles cover: the sum of their areas (UVs in the
/// atlas's units).
inline double atlas_utilization(const std::vector<std::vector<Uv>>& uvs,
                                const std::vector<std::vector<std::array<int, 3>>>& triangles)
{
  double area = 0;
  for(std::size_t c = 0; c < uvs.size(); ++c)
    for(const std::array<int, 3>& t : triangles[c])
      area += 0.5 * std::abs(internal::twice_signed_area(uvs[c][t[0]], uvs[c][t[1]], uvs[c][t[2]]));
  return area;
}

} // namespace ICM

#endif // ICM_LAYOUT_ATLAS_PACKING_H
