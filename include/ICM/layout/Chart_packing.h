// Several charts in one UV map: a shelf packing of their bounding boxes.
//
// Each chart comes laid out on its own, at its 3D scale, anywhere in the plane. Packing moves
// each one by a translation (and, when allowed and useful, a quarter turn) so that their
// bounding boxes are disjoint, a gap apart, within a roughly square region starting at (0, 0).
// Charts are never scaled: their relative sizes stay those of the surface, so a texel covers
// the same 3D area in every chart.
//
// The shelf algorithm: sort the boxes by decreasing height, fill rows left to right up to a
// row width, open a new row above the tallest box of the last one. Its waste is the space
// above the shorter boxes of a row and at the rows' ends; on boxes of similar heights (the
// usual atlas) it is small, and the algorithm is O(n log n). A texture atlas is square, so
// among a few row widths around sqrt(total area) the one with the smallest enclosing square
// is kept.

#ifndef ICM_LAYOUT_CHART_PACKING_H
#define ICM_LAYOUT_CHART_PACKING_H

#include <ICM/layout/Layout.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace ICM {

/// An axis-aligned box `{xmin, ymin, xmax, ymax}`; `xmin > xmax` is the empty box.
using Chart_box = std::array<double, 4>;

struct Shelf_packing_options
{
  /// Space between neighbouring charts, as a fraction of the largest chart side (a margin
  /// against texture bleeding that scales with the atlas). Zero-size charts only: the gap is
  /// `gap_ratio` itself.
  double gap_ratio = 0.02;
  /// Row width as a multiple of sqrt(total area of the boxes with their gaps). Zero: try
  /// 1.0, 1.1, ..., 2.0 and keep the packing with the smallest enclosing square.
  double width_factor = 0.0;
  /// Whether a chart taller than wide may be turned by a quarter turn so that every chart
  /// lies flat. Used only when the result is better: a smaller enclosing square, or the
  /// same square and a smaller area.
  bool allow_rotation = false;
};

/// Where one chart goes: p -> R p + offset, R the quarter turn (u, v) -> (-v, u) when
/// `rotated`, the identity otherwise. Both are isometries, so the chart's scale is kept.
struct Chart_placement
{
  Uv offset{0.0, 0.0};
  bool rotated = false;

  Uv operator()(const Uv& p) const
  {
    return rotated ? Uv{-p[1] + offset[0], p[0] + offset[1]} : Uv{p[0] + offset[0], p[1] + offset[1]};
  }
};

/// The placements of all charts, in input order, and the extent they occupy.
struct Chart_packing
{
  std::vector<Chart_placement> placements;
  double width = 0; ///< the packed boxes lie in [0, width] x [0, height]
  double height = 0;
  double gap = 0; ///< the minimal distance between two packed boxes
};

inline bool is_empty_box(const Chart_box& box)
{
  return !(box[0] <= box[2] && box[1] <= box[3]);
}

/// The bounding box of one chart's UVs; the empty box for an empty chart.
inline Chart_box chart_bounding_box(const std::vector<Uv>& uv)
{
  const double inf = std::numeric_limits<double>::infinity();
  Chart_box box{inf, inf, -inf, -inf};
  for(const Uv& p : uv)
  {
    box[0] = std::min(box[0], p[0]);
    box[1] = std::min(box[1], p[1]);
    box[2] = std::max(box[2], p[0]);
    box[3] = std::max(box[3], p[1]);
  }
  return box;
}

/// The image of `box` under `placement` (still axis-aligned: a quarter turn maps boxes to
/// boxes).
inline Chart_box placed_box(const Chart_box& box, const Chart_placement& placement)
{
  if(is_empty_box(box))
    return box;
  const Uv low = placement({box[0], box[1]}), high = placement({box[2], box[3]});
  return {std::min(low[0], high[0]), std::min(low[1], high[1]), std::max(low[0], high[0]), std::max(low[1], high[1])};
}

namespace internal {

/// One chart's box as the shelves see it: its size after the optional quarter turn.
struct Shelf_item
{
  int chart;
  double width;
  double height;
  bool rotated;
};

inline void check_boxes(const std::vector<Chart_box>& boxes)
{
  for(std::size_t i = 0; i < boxes.size(); ++i)
    for(double x : boxes[i])
      if(std::isnan(x) || (!is_empty_box(boxes[i]) && !std::isfinite(x)))
        throw std::invalid_argument("shelf packing: chart " + std::to_string(i) + " has a non-finite bounding box");
}

inline double largest_side(const std::vector<Chart_box>& boxes)
{
  double side = 0;
  for(const Chart_box& b : boxes)
    if(!is_empty_box(b))
      side = std::max({side, b[2] - b[0], b[3] - b[1]});
  return side;
}

/// The non-empty boxes, turned flat (width >= height) when `lay_flat`, tallest first. Ties
/// keep the input order, so equal charts are placed in the order they were given.
inline std::vector<Shelf_item> sorted_items(const std::vector<Chart_box>& boxes, bool lay_flat)
{
  std::vector<Shelf_item> items;
  for(std::size_t i = 0; i < boxes.size(); ++i)
  {
    const Chart_box& b = boxes[i];
    if(is_empty_box(b))
      continue;
    const double w = b[2] - b[0], h = b[3] - b[1];
    const bool turn = lay_flat && h > w;
    items.push_back({static_cast<int>(i), turn ? h : w, turn ? w : h, turn});
  }
  std::stable_sort(items.begin(), items.end(),
                   [](const Shelf_item& a, const Shelf_item& b) { return a.height > b.height; });
  return items;
}

/// The placement that puts the lower left corner of the chart's (turned) box at (x, y).
inline Chart_placement placement_at(const Chart_box& box, bool rotated, double x, double y)
{
  Chart_placement placement;
  placement.rotated = rotated;
  // A quarter turn maps [xmin, xmax] x [ymin, ymax] to [-ymax, -ymin] x [xmin, xmax].
  placement.offset = rotated ? Uv{x + box[3], y - box[0]} : Uv{x - box[0], y - box[1]};
  return placement;
}

/// Fills rows no wider than `row_width` (a box wider than that gets a row of its own).
inline Chart_packing fill_shelves(const std::vector<Chart_box>& boxes, const std::vector<Shelf_item>& items,
                                  double row_width, double gap)
{
  Chart_packing packing;
  packing.placements.resize(boxes.size());
  packing.gap = gap;
  double x = 0, y = 0, shelf_height = 0;
  bool shelf_empty = true;
  for(const Shelf_item& item : items)
  {
    if(!shelf_empty && x + item.width > row_width)
    {
      y += shelf_height + gap;
      x = 0;
      shelf_empty = true;
    }
    if(shelf_empty)
      shelf_height = item.height; // the tallest of its row, as items are sorted
    packing.placements[item.chart] = placement_at(boxes[item.chart], item.rotated, x, y);
    packing.width = std::max(packing.width, x + item.width);
    packing.height = std::max(packing.height, y + item.height);
    x += item.width + gap;
    shelf_empty = false;
  }
  return packing;
}

inline double padded_area(const std::vector<Shelf_item>& items, double gap)
{
  double area = 0;
  for(const Shelf_item& item : items)
    area += (item.width + gap) * (item.height + gap);
  return area;
}

/// Smaller enclosing square first (the scale the atlas can be drawn at), then smaller area.
inline bool better_packing(const Chart_packing& a, const Chart_packing& b)
{
  const double side_a = std::max(a.width, a.height), side_b = std::max(b.width, b.height);
  if(side_a != side_b)
    return side_a < side_b;
  return a.width * a.height < b.width * b.height;
}

inline Chart_packing best_shelf_packing(const std::vector<Chart_box>& boxes, const std::vector<Shelf_item>& items,
                                        double gap, double width_factor)
{
  const double side = std::sqrt(padded_area(items, gap));
  if(width_factor > 0)
    return fill_shelves(boxes, items, width_factor * side, gap);
  Chart_packing best;
  for(int step = 0; step <= 10; ++step)
  {
    Chart_packing candidate = fill_shelves(boxes, items, (1.0 + 0.1 * step) * side, gap);
    if(step == 0 || better_packing(candidate, best))
      best = std::move(candidate);
  }
  return best;
}

} // namespace internal

/// Places charts given by their bounding boxes side by side, a gap apart, without overlap.
/// Placement `i` is for box `i`; an empty box gets the identity. The packed boxes lie in
/// `[0, width] x [0, height]`, pairwise at least `gap` apart.
/// \pre every non-empty box is finite (else std::invalid_argument).
inline Chart_packing shelf_pack_charts(const std::vector<Chart_box>& boxes, const Shelf_packing_options& options = {})
{
  internal::check_boxes(boxes);
  const double largest = internal::largest_side(boxes);
  const double gap = options.gap_ratio * (largest > 0 ? largest : 1.0);
  Chart_packing best =
    internal::best_shelf_packing(boxes, internal::sorted_items(boxes, false), gap, options.width_factor);
  if(options.allow_rotation)
  {
    Chart_packing flat =
      internal::best_shelf_packing(boxes, internal::sorted_items(boxes, true), gap, options.width_factor);
    if(internal::better_packing(flat, best))
      best = std::move(flat);
  }
  return best;
}

/// Translations only: `offsets[i]` is added to every UV of chart `i`, whose bounding box is
/// `boxes[i]` = `{xmin, ymin, xmax, ymax}`. Gap as in `Shelf_packing_options::gap_ratio`.
inline std::vector<Uv> shelf_pack(const std::vector<Chart_box>& boxes, double gap_ratio = 0.02)
{
  Shelf_packing_options options;
  options.gap_ratio = gap_ratio;
  const Chart_packing packing = shelf_pack_charts(boxes, options);
  std::vector<Uv> offsets;
  offsets.reserve(packing.placements.size());
  for(const Chart_placement& placement : packing.placements)
    offsets.push_back(placement.offset);
  return offsets;
}

/// Moves every chart to its packed place, in place; returns the placements applied.
inline Chart_packing pack_charts(std::vector<std::vector<Uv>>& charts, const Shelf_packing_options& options = {})
{
  std::vector<Chart_box> boxes;
  boxes.reserve(charts.size());
  for(const auto& chart : charts)
    boxes.push_back(chart_bounding_box(chart));
  Chart_packing packing = shelf_pack_charts(boxes, options);
  for(std::size_t i = 0; i < charts.size(); ++i)
    for(Uv& p : charts[i])
      p = packing.placements[i](p);
  return packing;
}

} // namespace ICM

#endif // ICM_LAYOUT_CHART_PACKING_H
